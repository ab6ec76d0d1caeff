-- Kinematic pairs and their degrees of freedom (000 "Degree of freedom", "Kinematic pair"): one
-- box on each joint type, struck by random impulses; the motions that survive the solver are
-- collected and their independent directions counted (the rank of the surviving velocities).
-- The count is the slide's DOF for every pair; the slide's planar pair is "3 translational
-- DOF", which is a slip: it is 2 translations in the plane and 1 rotation about its normal.

local mass = 1
local size = vec3(0.4, 0.2, 0.3)          -- m
local axis = vec3(1, 2, 2) / 3            -- a unit axis along no coordinate direction
local pitch = 0.05                        -- m per turn, for the screw
local trials = 12                         -- random blows per joint
local dt = 1e-5                           -- s, one short step after each blow
local strength = 0.01                     -- N·s, the largest component of a blow

-- The pairs: 000's list in its order, then the fixed joint, and the slide's count of each.
local pairs_list = {
  {type = "hinge", slide = "1 rotational", dof = 1, v = 0, w = 1},
  {type = "slider", slide = "1 translational", dof = 1, v = 1, w = 0},
  {type = "screw", slide = "1 coordinated", dof = 1, v = 1, w = 1},
  {type = "cylindrical", slide = "1 transl. + 1 rot.", dof = 2, v = 1, w = 1},
  {type = "ball", slide = "3 rotational", dof = 3, v = 0, w = 3},
  {type = "planar", slide = "\"3 translational\"", dof = 3, v = 2, w = 1},
  {type = "fixed", slide = "(not listed)", dof = 0, v = 0, w = 0},
  {type = "distance", slide = "(not listed)", dof = 5, v = 2, w = 3},
}

-- A small linear congruential generator (Knuth's MMIX constants) so every run draws the same
-- blows: uniform numbers in [−1, 1).
local function generator(seed)
  local state = seed
  return function()
    state = (state * 6364136223846793005 + 1442695040888963407) & 0xFFFFFFFFFFFF
    return state / 0x800000000000 - 1
  end
end

-- The number of independent vectors among `list` (each a list of numbers), by Gaussian
-- elimination with partial pivoting: a pivot under `tol` counts as zero.
local function rank(list, tol)
  local rows = {}
  for i, v in ipairs(list) do rows[i] = {table.unpack(v)} end
  local r, columns = 0, rows[1] and #rows[1] or 0
  for c = 1, columns do
    local best, at = tol, nil
    for i = r + 1, #rows do
      if math.abs(rows[i][c]) > best then best, at = math.abs(rows[i][c]), i end
    end
    if at then
      r = r + 1
      rows[r], rows[at] = rows[at], rows[r]
      for i = r + 1, #rows do
        local f = rows[i][c] / rows[r][c]
        for k = c, columns do rows[i][k] = rows[i][k] - f * rows[r][k] end
      end
    end
  end
  return r
end

-- The motions a pair allows at its anchor (the box's centre), as (v, ω) six-vectors.
local function allowed(p)
  local t1 = axis:cross(vec3(1, 0, 0)):normalized()
  local t2 = axis:cross(t1)
  local zero = vec3(0, 0, 0)
  local basis = {
    hinge = {{zero, axis}},
    slider = {{axis, zero}},
    screw = {{axis * (pitch / (2 * math.pi)), axis}},
    cylindrical = {{axis, zero}, {zero, axis}},
    ball = {{zero, vec3(1, 0, 0)}, {zero, vec3(0, 1, 0)}, {zero, vec3(0, 0, 1)}},
    planar = {{t1, zero}, {t2, zero}, {zero, axis}},
    fixed = {},
    distance = {{vec3(1, 0, 0), zero}, {vec3(0, 0, 1), zero}, {zero, vec3(1, 0, 0)},
                {zero, vec3(0, 1, 0)}, {zero, vec3(0, 0, 1)}},
  }
  return basis[p.type]
end

-- The part of (v, ω) outside the allowed directions (Gram–Schmidt on the basis first).
local function outside(v, w, basis)
  local ortho = {}
  for _, b in ipairs(basis) do
    local bv, bw = b[1], b[2]
    for _, o in ipairs(ortho) do
      local d = bv:dot(o[1]) + bw:dot(o[2])
      bv, bw = bv - o[1] * d, bw - o[2] * d
    end
    local n = math.sqrt(bv:dot(bv) + bw:dot(bw))
    ortho[#ortho + 1] = {bv / n, bw / n}
  end
  for _, o in ipairs(ortho) do
    local d = v:dot(o[1]) + w:dot(o[2])
    v, w = v - o[1] * d, w - o[2] * d
  end
  return math.sqrt(v:dot(v) + w:dot(w))
end

-- Strikes a box on pair p `trials` times (from rest each time) and returns the surviving
-- (v, ω) of each, the largest part of any outside the allowed directions, and the size
-- |ω|(|ω| + |v|)Δt of the joint's turn during the step (the largest over the blows).
local function survivors(p, step)
  local w = world{gravity = vec3(0, 0, 0), solver = "sequential_impulses"}
  w.iterations = 50
  local box = w:add(body.box{mass = mass, size = size})
  if p.type == "distance" then     -- a rod from the box's centre to a hook 1 m above it
    w:add_joint{type = "distance", a = box, a_point = vec3(0, 0, 0), b_point = vec3(0, 1, 0)}
  elseif p.type then
    local takes_axis = p.type ~= "ball" and p.type ~= "fixed"
    w:add_joint{type = p.type, a = box, axis = takes_axis and axis or nil,
                pitch = p.type == "screw" and pitch or nil}
  end
  local random = generator(2024)
  local found, worst, bound = {}, 0, 0
  for k = 1, trials do
    box.velocity, box.angular_velocity = vec3(0, 0, 0), vec3(0, 0, 0)
    box.position, box.orientation = vec3(0, 0, 0), quat()   -- the pose the allowed motions are of
    local blow = vec3(random(), random(), random()) * strength
    local where = box.position + vec3(random() * size.x, random() * size.y, random() * size.z) / 2
    box:apply_impulse(blow, where)
    w:step(step or dt)
    local v, om = box.velocity, box.angular_velocity
    found[k] = {v, om}
    if p.type then worst = math.max(worst, outside(v, om, allowed(p))) end
    bound = math.max(bound, om:norm() * (om:norm() + v:norm()) * (step or dt))
  end
  return found, worst, bound
end

local function counts(found)
  local both, lin, ang = {}, {}, {}
  for k, u in ipairs(found) do
    local v, w = u[1], u[2]
    both[k] = {v.x, v.y, v.z, w.x, w.y, w.z}
    lin[k], ang[k] = {v.x, v.y, v.z}, {w.x, w.y, w.z}
  end
  return rank(both, 1e-6), rank(lin, 1e-6), rank(ang, 1e-6)
end

return lesson{
  id = "kinematic-pairs",
  title = "Kinematic pairs: counting the freedoms each joint leaves",
  source = "000_3bd95e59483beea1.txt, \"Degree of freedom\", \"Kinematic pair\"",
  steps = {
    {
      title = "A free body has six",
      text = [[
000 "Degree of freedom" describes how a body can move by its translational and rotational
degrees of freedom. To count them without trusting any formula, we strike a box (1 kg,
0.4 × 0.2 × 0.3 m, at rest at the origin) 12 times, each time from rest, with a random
impulse (each component at most 0.01 N·s) at a random point of it, take one short step
(0.01 ms, no gravity) and keep the
velocity v of its centre and its angular velocity ω. The number of independent directions
among those 12 six-vectors (v, ω), the rank of their matrix, is the number of freedoms the
blows could reach. For a free body: 6, 3 of them in v and 3 in ω.]],
      formula = "DOF = rank [ (v₁, ω₁); (v₂, ω₂); … ; (v₁₂, ω₁₂) ]",
      run = function(ctx)
        local found = survivors({})
        local all, lin, ang = counts(found)
        ctx:show("first blow left v (m/s)", found[1][1])
        ctx:show("and ω (rad/s)", found[1][2])
        ctx:show("rank of (v, ω), of v, of ω", {all, lin, ang})
        ctx:expect("a free body: 6 freedoms", all, 6)
        ctx:expect("3 translational", lin, 3)
        ctx:expect("3 rotational", ang, 3)
      end,
    },
    {
      title = "Each pair, counted",
      text = [[
000 "Kinematic pair" lists the lower pairs with their freedoms: revolute (a hinge) 1
rotational, prismatic (a slider) 1 translational, screw 1 in which rotation and translation
are tied (here 0.05 m per turn), cylindrical 1 + 1, spherical (a ball joint) 3 rotational,
planar "3 translational". We join the box to the world with each, anchored at its centre,
about the axis (1, 2, 2)/3 (a direction along no coordinate axis, so nothing lines up by
luck), strike it the same 12 ways with the sequential_impulses solver at 50 sweeps, and
count again: all six components, and the translational and rotational parts apart.

The column "outside" is the largest part of any surviving (v, ω) outside the motions the
pair allows. It is rounding: the sequential_impulses solver ends each step by sweeping the
joint's rows once more at the pose where the step leaves the body, so the velocities a step
hands back are ones the joint allows there (see the lesson sequential-impulses). Its main
sweeps aim at the END of the step (the pose the body turns to), and what they leave differs
from an allowed motion by about the turn of the joint's directions during the step,
|ω|(|ω| + |v|)Δt, the last column; that last sweep takes it out. One pair keeps a leftover
of that size: the distance rod, whose direction at the end of the step is not the one at its
start when the box has moved sideways, and "outside" is measured against the start's. (The
blows are small, at most 0.01 N·s a component, and the step short, 0.01 ms, so that leftover
stays far below the motions the rank counts.)

Two joints are not on the slide: fixed (no freedom at all) and distance, a rigid rod from
the box's centre to a point 1 m above it, which forbids only moving along the rod: 5
freedoms, 2 of them translational (square to the rod) and all 3 rotations (the rod is
fixed to the box's centre, so turning the box does not move it).

The counts agree with the slide except for one word: a planar pair (a puck on a table)
slides in two directions in the plane and turns about the plane's normal, 2 translational +
1 rotational freedoms. "3 translational" on the slide is a slip; the count is 3.]],
      run = function(ctx)
        local rows = {}
        for _, p in ipairs(pairs_list) do
          local found, worst, bound = survivors(p)
          local all, lin, ang = counts(found)
          rows[#rows + 1] = {p.type, p.slide, all, lin, ang, string.format("%.2g", worst),
                             string.format("%.2g", bound)}
          ctx:expect(p.type .. ": DOF", all, p.dof)
          ctx:expect(p.type .. ": translational, rotational", {lin, ang}, {p.v, p.w})
          -- the rod's direction turns as the box moves off the hook's vertical in the step
          local limit = p.type == "distance" and bound + 1e-14 or 1e-12
          ctx:expect_range(p.type .. ": outside the allowed motions (at the start pose)", worst, nil,
                           limit)
        end
        ctx:table({"joint", "000 says", "DOF", "in v", "in ω", "outside", "|ω|(|ω|+|v|)Δt"},
                  rows)
      end,
    },
    {
      title = "Longer steps, nothing left over",
      text = [[
What the main sweeps leave outside a hinge's allowed motions grows with the step, as the
turn of the joint's directions during it, |ω|(|ω| + |v|)Δt; what the step hands back does
not: the last sweep at the end pose leaves rounding at every step length. The hinge, struck
the same 12 ways, with steps of 1 µs, 0.1 ms and 10 ms.]],
      run = function(ctx)
        local rows = {}
        for k, step in ipairs{1e-6, 1e-4, 1e-2} do
          local _, worst, bound = survivors(pairs_list[1], step)
          rows[k] = {step, worst, bound}
          ctx:expect_range(string.format("Δt = %g s: outside the allowed motions: rounding", step),
                           worst, nil, 1e-12)
        end
        ctx:table({"Δt (s)", "outside", "|ω|(|ω|+|v|)Δt"}, rows)
      end,
    },
    {
      title = "The screw: rotation and travel tied",
      text = [[
The screw pair's one freedom couples its two motions: every turn advances it by the pitch,
0.05 m, so the travel along the axis per radian is 0.05/(2π) = 0.00796 m. Its surviving
motions are all multiples of one six-vector, and the ratio of the speed along the axis to
the rate about it must be that number for every blow.]],
      formula = "v·n = (pitch / 2π)·(ω·n)",
      run = function(ctx)
        local found = survivors(pairs_list[3])
        local lowest, highest = math.huge, -math.huge
        for _, u in ipairs(found) do
          local ratio = u[1]:dot(axis) / u[2]:dot(axis)
          lowest, highest = math.min(lowest, ratio), math.max(highest, ratio)
        end
        ctx:show("pitch/2π (m/rad)", pitch / (2 * math.pi))
        ctx:show("v·n / ω·n over the 12 blows: lowest, highest (m/rad)", {lowest, highest})
        ctx:expect("lowest ratio", lowest, pitch / (2 * math.pi), 1e-9)
        ctx:expect("highest ratio", highest, pitch / (2 * math.pi), 1e-9)
      end,
    },
  },
}
