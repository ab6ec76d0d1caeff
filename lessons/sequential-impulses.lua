-- Sequential impulses (000 "Integrate constraints", "Sequential impulses"): the three steps on a
-- chain of three balls on rigid rods, done by hand in Lua and compared with a world whose
-- solver is "sequential_impulses": the tentative velocities, each Gauss-Seidel sweep's largest
-- constraint velocity error (against w:solver_report()), the limit the sweeps converge to (a
-- direct solve of the same equations), and the drift a velocity-level solve leaves, which
-- rigidlab's rows avoid by aiming at the rods' lengths at the end of the step.

local g = 9.81
local dt = 1 / 60
local masses = {1, 2, 3}                       -- kg
local radius = 0.1                             -- m, each ball
local pivot = vec3(0, 0, 0)
local start = {vec3(0.6, -0.8, 0), vec3(1.4, -1.4, 0), vec3(1.4, -2.4, 0)}   -- m
local sweeps = 12
local ahead = true     -- the rows' targets look ahead to the end of the step (see step 2)

-- The rods: {a, b}, 0 for the fixed pivot. Each keeps |x_b − x_a| at its starting length.
local rods = {{0, 1}, {1, 2}, {2, 3}}

local function position(i, x) return i == 0 and pivot or x[i] end

local function velocity(i, v) return i == 0 and vec3(0, 0, 0) or v[i] end

-- One row per rod: the unit vector n from a to b; the row's velocity is n·(v_b − v_a), and its
-- effective mass 1/(1/m_a + 1/m_b) (the pivot has 1/m = 0). With `look_ahead` the row aims not
-- at n·(v_b − v_a) = 0 but at the velocity that brings the rod back to its length at the END
-- of the step: moving the ends with the tentative velocities v* for Δt stretches the rod by
-- R = |d + Δt·Δv*| − |d| − Δt·n·Δv* beyond what its straight-line rate says, so the row's
-- target is n·Δv = −R/Δt (its "bias" is R/Δt).
local function rows_at(x, v_star, look_ahead)
  local rows = {}
  for k, rod in ipairs(rods) do
    local d = position(rod[2], x) - position(rod[1], x)
    local inv_a = rod[1] == 0 and 0 or 1 / masses[rod[1]]
    local inv_b = 1 / masses[rod[2]]
    local n = d / d:norm()
    local dv = velocity(rod[2], v_star) - velocity(rod[1], v_star)
    local R = (d + dv * dt):norm() - d:norm() - dt * n:dot(dv)
    rows[k] = {a = rod[1], b = rod[2], n = n, inv_a = inv_a, inv_b = inv_b,
               mass = 1 / (inv_a + inv_b), bias = look_ahead and R / dt or 0}
  end
  return rows
end

-- Step 2 by hand: Gauss-Seidel over the rows, forward then backward in turn (as the world
-- sweeps), each row given the impulse that zeroes its own velocity error (its distance from
-- its target). Returns the velocities and, per sweep, the largest error a row had when its
-- turn came.
local function gauss_seidel(rows, v_star, count)
  local v = {table.unpack(v_star)}
  local errors = {}
  for s = 1, count do
    local largest = 0
    for step = 1, #rows do
      local r = rows[s % 2 == 1 and step or #rows + 1 - step]
      local err = r.n:dot(velocity(r.b, v) - velocity(r.a, v)) + r.bias
      largest = math.max(largest, math.abs(err))
      local lambda = -r.mass * err
      if r.a ~= 0 then v[r.a] = v[r.a] - r.n * (lambda * r.inv_a) end
      v[r.b] = v[r.b] + r.n * (lambda * r.inv_b)
    end
    errors[s] = largest
  end
  return v, errors
end

-- The limit: all rows at once, (J W Jᵀ) λ = −(J v* + bias), solved by Gaussian elimination.
local function direct(rows, v_star)
  local n, A, rhs = #rows, {}, {}
  for i, ri in ipairs(rows) do
    A[i] = {}
    for j, rj in ipairs(rows) do
      local s = 0     -- row i's velocity change per unit impulse of row j, through shared balls
      if ri.b == rj.b then s = s + ri.n:dot(rj.n) * ri.inv_b end
      if ri.b == rj.a and rj.a ~= 0 then s = s - ri.n:dot(rj.n) * ri.inv_b end
      if ri.a == rj.b and ri.a ~= 0 then s = s - ri.n:dot(rj.n) * ri.inv_a end
      if ri.a == rj.a and ri.a ~= 0 then s = s + ri.n:dot(rj.n) * ri.inv_a end
      A[i][j] = s
    end
    rhs[i] = -ri.n:dot(velocity(ri.b, v_star) - velocity(ri.a, v_star)) - ri.bias
  end
  for c = 1, n do
    for r = c + 1, n do
      local f = A[r][c] / A[c][c]
      for k = c, n do A[r][k] = A[r][k] - f * A[c][k] end
      rhs[r] = rhs[r] - f * rhs[c]
    end
  end
  local lambda = {}
  for i = n, 1, -1 do
    local s = rhs[i]
    for k = i + 1, n do s = s - A[i][k] * lambda[k] end
    lambda[i] = s / A[i][i]
  end
  local v = {table.unpack(v_star)}
  for k, r in ipairs(rows) do
    if r.a ~= 0 then v[r.a] = v[r.a] - r.n * (lambda[k] * r.inv_a) end
    v[r.b] = v[r.b] + r.n * (lambda[k] * r.inv_b)
  end
  return v, lambda
end

-- The world's last stage with sequential_impulses (engine/solver.cpp, RATTLE's velocity
-- half): the balls moved to x' = x + Δt·v (no position pass here), the rows rebuilt there with
-- no look-ahead, and `count` sweeps more, so the velocities the step leaves are square to the
-- rods as they are at its end.
local function at_end(v, count)
  local x = {}
  for i = 1, #masses do x[i] = start[i] + v[i] * dt end
  local rows = rows_at(x, v, false)
  return (gauss_seidel(rows, v, count)), rows
end

local function tentative()
  local v = {}
  for i = 1, #masses do v[i] = vec3(0, -g * dt, 0) end
  return v
end

local function chain_world(iterations, position_iterations)
  local w = world{solver = "sequential_impulses"}
  w.iterations = iterations
  w.position_iterations = position_iterations
  local balls = {}
  for i, m in ipairs(masses) do
    balls[i] = w:add(body.sphere{mass = m, radius = radius, position = start[i]})
  end
  for _, rod in ipairs(rods) do
    if rod[1] == 0 then
      w:add_joint{type = "distance", a = balls[rod[2]], a_point = vec3(0, 0, 0), b_point = pivot}
    else
      w:add_joint{type = "distance", a = balls[rod[2]], a_point = vec3(0, 0, 0),
                  b = balls[rod[1]], b_point = vec3(0, 0, 0)}
    end
  end
  return w, balls
end

local function largest_gap(balls, v)
  local worst = 0
  for i, b in ipairs(balls) do worst = math.max(worst, (b.velocity - v[i]):norm()) end
  return worst
end

return lesson{
  id = "sequential-impulses",
  title = "Sequential impulses: the solver's three steps, sweep by sweep",
  source = "000_3bd95e59483beea1.txt, \"Integrate constraints\", \"Sequential impulses\"",
  steps = {
    {
      title = "The chain, and step 1: tentative velocities",
      text = [[
Three balls of 1, 2 and 3 kg (radius 0.1 m) hang in a zigzag from a fixed pivot at the
origin, each on a massless rigid rod of 1 m to the one before: the first at (0.6, −0.8, 0),
the second at (1.4, −1.4, 0), the third at (1.4, −2.4, 0), all at rest. 000 "Sequential
impulses" solves such a system in three steps per time step. Step 1 integrates the applied
forces alone, as if there were no rods: over Δt = 1/60 s gravity gives every ball the
tentative velocity v* = (0, −gΔt, 0) = (0, −0.1635, 0) m/s.]],
      formula = "step 1:  v* = v + Δt·F/m",
      run = function(ctx)
        ctx:show("Δt (s)", dt)
        local v = tentative()
        for i = 1, #masses do ctx:show(string.format("v*%d (m/s)", i), v[i]) end
        ctx:expect("v* = −gΔt", v[1].y, -9.81 / 60)
      end,
    },
    {
      title = "Step 2: impulses, one rod at a time",
      text = [[
Each rod forbids its two ends to move apart or together: the row's velocity is n·(v_b − v_a),
n the unit vector along the rod. Step 2 visits the rods one after another and gives each the
impulse λ = −m_eff·(its error) along n, m_eff = 1/(1/m_a + 1/m_b), which makes that rod's
error exactly zero, but disturbs its neighbours, which share a ball. Hence 000 "Integrate
constraints": solving one constraint influences the others, so we sweep over them again and
again, until the errors are small or a sweep budget runs out. We sweep 12 times, forward and
backward in turn, as the world does.

One refinement of rigidlab's over the plain scheme: a row's error is measured from a target
that looks ahead. Moving in a straight line for Δt, the ends of a turning rod drift apart
(step 4 shows by how much); so the target is the rate that brings the rod back to its length
at the end of the step, n·Δv = −R/Δt, with R how much the tentative motion would stretch the
rod beyond its straight-line rate (SHAKE's condition, Ryckaert, Ciccotti and Berendsen 1977).
Here R/Δt is a few 1e-5 m/s, so the targets are nearly zero.

The table shows each sweep's largest error as our hand-written sweeps see it and as
w:solver_report() reports it for a world with solver = "sequential_impulses" stepped once.
They must agree to rounding: both are the same arithmetic on the same numbers.]],
      formula = "step 2:  for each rod:  λ = −(n·(v_b − v_a) + R/Δt) / (1/m_a + 1/m_b),\n" ..
                "         v_a −= λn/m_a,  v_b += λn/m_b;   repeat",
      run = function(ctx)
        local rows = rows_at(start, tentative(), ahead)
        local _, errors = gauss_seidel(rows, tentative(), sweeps)
        local w = chain_world(sweeps, 0)
        w:step(dt)
        local report = w:solver_report()
        local biases = {}
        for k, r in ipairs(rows) do biases[k] = r.bias end
        ctx:show("targets' look-ahead R/Δt per rod (m/s)", biases)
        local table_rows, xs, ys = {}, {}, {}
        for s = 1, sweeps do
          table_rows[s] = {s, errors[s], report[s], s > 1 and errors[s] / errors[s - 1] or ""}
          xs[s], ys[s] = s, math.log(errors[s], 10)
        end
        ctx:table({"sweep", "by hand (m/s)", "world (m/s)", "ratio"}, table_rows)
        ctx:plot{{x = xs, y = ys, label = "largest velocity error"},
                 title = "Sweeps shrink the error", xlabel = "sweep", ylabel = "log₁₀ m/s",
                 height = 8}
        ctx:expect("the report has one entry per sweep", #report, sweeps)
        ctx:expect("the world's sweeps are the hand-written ones", report, errors,
                   {abs = 1e-14, reason = "the same operations, to rounding"})
        local growth = 0
        for s = 2, sweeps do growth = math.max(growth, errors[s] / errors[s - 1]) end
        ctx:expect_range("no sweep makes the largest error larger", growth, nil, 1)
      end,
    },
    {
      title = "What the sweeps converge to",
      text = [[
Solved all at once, the rods' impulses satisfy one linear system: (J W Jᵀ)λ = −(J v* + b),
with J the rows' directions, W the inverse masses and b the look-ahead R/Δt of each row; the
velocities v* + W Jᵀλ then meet every target exactly. Gauss-Seidel sweeps converge to that
solution (000: "converges to a global solution"), here slowly: the heavier balls below make
each sweep keep about four fifths of the error. After 12 sweeps the world's velocities
differ from the solution by about the remaining error, and with 200 sweeps by rounding only.
(One more stage before the world hands the velocities back: the rods' rows are built again
where the step leaves the balls, without look-ahead, and swept as many times, so that the
velocities it leaves are square to the rods as they are then; we do the same by hand.)]],
      formula = "(J W Jᵀ)·λ = −(J·v* + b),   v = v* + W Jᵀ λ",
      run = function(ctx)
        local rows = rows_at(start, tentative(), ahead)
        local exact, lambda = direct(rows, tentative())
        ctx:show("impulses λ (N·s)", lambda)
        for i = 1, #masses do ctx:show(string.format("v%d exact (m/s)", i), exact[i]) end
        local hand = gauss_seidel(rows, tentative(), sweeps)
        local w, balls = chain_world(sweeps, 0)
        w:step(dt)
        local _, end_rows = at_end(exact, 0)
        local exact_end = direct(end_rows, exact)   -- the solution, then its last stage exactly
        ctx:show("12 sweeps: largest |v − exact| (m/s)", largest_gap(balls, exact_end))
        ctx:expect("12 sweeps: the world's velocities are the hand-written sweeps'",
                   largest_gap(balls, (at_end(hand, sweeps))), 0,
                   {abs = 1e-14, reason = "the same operations"})
        local w2, balls2 = chain_world(200, 0)
        w2:step(dt)
        ctx:show("200 sweeps: largest |v − exact| (m/s)", largest_gap(balls2, exact_end))
        ctx:expect("200 sweeps reach the direct solution", largest_gap(balls2, exact_end), 0,
                   {abs = 1e-13, reason = "converged to rounding"})
      end,
    },
    {
      title = "Step 3, and the drift it leaves",
      text = [[
Step 3 moves the balls with the new velocities: x' = x + Δt·v. Had the rows aimed at
n·Δv = 0 (the plain scheme), the velocities would be square to each rod as it is now; but a
straight step square to a rod lengthens it, to √(ℓ² + (Δt·v⊥)²) ≈ ℓ + (Δt·v⊥)²/(2ℓ), with v⊥
the rod ends' relative speed across it (Pythagoras). That is 000's warning: "velocity
constraints not precise, might produce position drift". We solve the plain rows by hand and
find exactly those lengths.

The world's rows aim ahead, but in this very first step the tentative motion they look
ahead along is the free fall, all balls falling together, not the swing the rods are about
to start: its rods end up stretched about as much (last column; the balls are exactly
where x + Δt·v puts them with our look-ahead velocities). Over a second of swinging the
difference shows: the plain scheme by hand (no position pass) lets the rods stretch by
centimetres, the world's rows, which then look ahead along the actual swing, by millimetres,
and the position pass (3 sweeps of Box2D's non-linear Gauss-Seidel on the positions, the
default) removes most of what is left (we ask for three quarters).]],
      formula = "step 3:  x' = x + Δt·v;   plain rows: rod length = √(ℓ² + (Δt·v⊥)²)",
      run = function(ctx)
        local v_plain = direct(rows_at(start, tentative(), false), tentative())
        local rows = rows_at(start, tentative(), ahead)
        local v_ahead = direct(rows, tentative())
        local w, balls = chain_world(200, 0)
        w:step(dt)
        local worst_position = 0
        for i, b in ipairs(balls) do
          worst_position = math.max(worst_position, (b.position - (start[i] + v_ahead[i] * dt)):norm())
        end
        ctx:show("largest |x_world − (x + Δt·v)| (m)", worst_position)
        ctx:expect("the world moved the balls by Δt·v", worst_position, 0,
                   {abs = 1e-14, reason = "one multiply-add, to rounding"})
        local plain_x, world_x, table_rows = {}, {}, {}
        for i, b in ipairs(balls) do plain_x[i], world_x[i] = start[i] + v_plain[i] * dt, b.position end
        for k, r in ipairs(rows) do
          local rel = velocity(r.b, v_plain) - velocity(r.a, v_plain)
          local s2 = (dt * (rel - r.n * r.n:dot(rel)):norm()) ^ 2
          local predicted = s2 / (math.sqrt(1 + s2) + 1)      -- √(1 + s²) − 1, without cancelling
          local plain = (position(r.b, plain_x) - position(r.a, plain_x)):norm() - 1
          local world_length = (position(r.b, world_x) - position(r.a, world_x)):norm() - 1
          table_rows[k] = {k, plain, predicted, world_length}
          ctx:expect(string.format("rod %d, plain rows: stretched by √(ℓ² + (Δt·v⊥)²) − ℓ", k), plain,
                     predicted, {rel = 1e-8, reason = "length − 1 m loses 6 digits to cancellation"})
        end
        ctx:table({"rod", "plain rows: length − 1 m", "√(ℓ² + (Δt·v⊥)²) − ℓ", "world: length − 1 m"},
                  table_rows)
        -- a second of swinging: the plain scheme by hand against the world
        local x, v = {table.unpack(start)}, {vec3(), vec3(), vec3()}
        local wl, wballs = chain_world(200, 0)
        local hand_worst, world_worst = 0, 0
        local function longest(xs)
          local m = 0
          for _, rod in ipairs(rods) do
            m = math.max(m, math.abs((position(rod[2], xs) - position(rod[1], xs)):norm() - 1))
          end
          return m
        end
        for _ = 1, 60 do
          local vs = {}
          for i = 1, #masses do vs[i] = v[i] + vec3(0, -g * dt, 0) end
          local rows_now = {}
          for k, rod in ipairs(rods) do
            local d = position(rod[2], x) - position(rod[1], x)
            local inv_a = rod[1] == 0 and 0 or 1 / masses[rod[1]]
            rows_now[k] = {a = rod[1], b = rod[2], n = d / d:norm(), inv_a = inv_a,
                           inv_b = 1 / masses[rod[2]], bias = 0}
          end
          v = direct(rows_now, vs)
          for i = 1, #masses do x[i] = x[i] + v[i] * dt end
          hand_worst = math.max(hand_worst, longest(x))
          wl:step(dt)
          local xs = {}
          for i, b in ipairs(wballs) do xs[i] = b.position end
          world_worst = math.max(world_worst, longest(xs))
        end
        local wp, pballs = chain_world(200, 3)
        local pass_worst = 0
        for _ = 1, 60 do
          wp:step(dt)
          local xs = {}
          for i, b in ipairs(pballs) do xs[i] = b.position end
          pass_worst = math.max(pass_worst, longest(xs))
        end
        ctx:table({"over 1 s", "largest |length − 1 m| (m)"},
                  {{"plain rows (by hand)", hand_worst}, {"world, rows aim ahead", world_worst},
                   {"world, and 3 position sweeps", pass_worst}})
        ctx:expect_range("aiming ahead drifts 5 times less than plain rows", world_worst, nil,
                         hand_worst / 5)
        ctx:expect_range("the position pass takes most of the rest out", pass_worst, nil,
                         world_worst / 4)
      end,
    },
  },
}
