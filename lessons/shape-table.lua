-- The table of primitive inertia tensors (000 "Inertia of primitive shapes", 003 "List of 3D
-- inertia tensors"): each shape's closed form, the engine's inertia.*, and a Monte Carlo
-- estimate from points sampled uniformly in (or on) the shape with a fixed seed.

local samples = 20000   -- points per shape: sampling error ~ 1/√N, a little under 1%
local seed = 42         -- fixed, so the lesson prints the same numbers every time

-- Uniform random number in [lo, hi).
local function uniform(lo, hi) return lo + (hi - lo) * math.random() end

-- Samplers: each returns one point (x, y, z) in m, uniform over the shape's volume or surface.
-- Solid shapes use rejection: draw in the bounding box, keep the points inside.
local function inside(test, a, b, c)
  return function()
    while true do
      local x, y, z = uniform(-a, a), uniform(-b, b), uniform(-c, c)
      if test(x, y, z) then return x, y, z end
    end
  end
end

local function ellipsoid_sampler(a, b, c)
  return inside(function(x, y, z) return (x / a) ^ 2 + (y / b) ^ 2 + (z / c) ^ 2 <= 1 end, a, b, c)
end

-- On a sphere, z uniform in [−r, r] with a uniform angle gives uniform area (Archimedes: the
-- sphere's area between two heights equals that of the enclosing cylinder's band).
local function sphere_surface_sampler(r)
  return function()
    local z, phi = uniform(-r, r), uniform(-math.pi, math.pi)
    local ring = math.sqrt(r * r - z * z)
    return ring * math.cos(phi), ring * math.sin(phi), z
  end
end

local function box_sampler(w, h, d)
  return function()
    return uniform(-w / 2, w / 2), uniform(-h / 2, h / 2), uniform(-d / 2, d / 2)
  end
end

local function cylinder_sampler(r, h)
  local disc = inside(function(x, y) return x * x + y * y <= r * r end, r, r, 0)
  return function()
    local x, y = disc()
    return x, y, uniform(-h / 2, h / 2)
  end
end

-- The tube's wall (no end caps): a uniform angle and a uniform height.
local function tube_sampler(r, h)
  return function()
    local phi = uniform(-math.pi, math.pi)
    return r * math.cos(phi), r * math.sin(phi), uniform(-h / 2, h / 2)
  end
end

-- Monte Carlo tensor: m times the average of (r·r)E − r⊗r over the samples, and the standard
-- error of the average for each of the six entries (kg·m²). Returns the tensor and the
-- largest standard error.
local function sampled_tensor(mass, sampler)
  math.randomseed(seed)
  local sum, square = {0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0}
  for _ = 1, samples do
    local x, y, z = sampler()
    local q = {y * y + z * z, x * x + z * z, x * x + y * y, -x * y, -x * z, -y * z}
    for k = 1, 6 do
      sum[k], square[k] = sum[k] + q[k], square[k] + q[k] * q[k]
    end
  end
  local mean, largest_error = {}, 0
  for k = 1, 6 do
    mean[k] = mass * sum[k] / samples
    local variance = square[k] / samples - (sum[k] / samples) ^ 2
    largest_error = math.max(largest_error, mass * math.sqrt(variance / samples))
  end
  return mat3(mean[1], mean[4], mean[5], mean[4], mean[2], mean[6], mean[5], mean[6], mean[3]),
         largest_error
end

-- Shows one shape: the engine's tensor against the closed form, and against the samples
-- within four standard errors.
local function check_shape(ctx, name, engine, closed_form, mass, sampler)
  ctx:say(name .. ":")
  ctx:show("engine (kg·m²)", engine)
  ctx:expect(name .. ": engine = closed form", engine, closed_form)
  local sampled, standard_error = sampled_tensor(mass, sampler)
  ctx:show("sampled from " .. samples .. " points (kg·m²)", sampled)
  ctx:show("largest standard error of a sampled entry (kg·m²)", standard_error)
    local largest_deviation = 0
  for i = 1, 3 do
    for j = 1, 3 do
      largest_deviation = math.max(largest_deviation,
                                   math.abs(sampled:get(i, j) - closed_form:get(i, j)))
    end
  end
  ctx:expect(name .. ": largest |sampled − closed form| (≤ 4σ)",
             largest_deviation, 0, {abs = 4 * standard_error})
end

return lesson{
  id = "shape-table",
  title = "The table of primitive shapes, confirmed by sampling",
  source = "000_3bd95e59483beea1.txt, \"Inertia of primitive shapes\"; " ..
           "003_636de12a6b81385f.txt, \"List of 3D inertia tensors\"",
  steps = {
    {
      title = "Checking a formula by throwing darts",
      text = [[
The closed forms in the tables come from integrals like the ones in the box and cylinder
lessons. There is a completely different way to get the same numbers, one that needs no
calculus at all: scatter many random points evenly through the shape, treat each as an equal
share of the mass, and average the particle formula (r·r)E − r⊗r over them. This is Monte
Carlo integration. Its error does not depend on how clever the formula is, only on how many
points we throw: it shrinks like 1/√N. With N = 20000 points the entries are good to a little
under 1%; the lesson computes each entry's standard error from the points themselves and
accepts the sample when it lies within four standard errors of the closed form. The random
generator starts from a fixed seed (42), so every run prints the same numbers.

First the two spheres, radius r = 0.5 m and mass m = 2 kg. For the solid ball we draw points in
the surrounding cube and keep those inside. For the hollow shell all the mass is on the
surface, and a neat fact of Archimedes gives uniform points there: pick the height z uniformly
and the angle uniformly. The shell's 2/3 is bigger than the ball's 2/5 because all of its mass
is as far out as it can be.]],
      formula = "solid sphere  I = (2/5)·m·r²·E        hollow sphere  I = (2/3)·m·r²·E\n" ..
                "Monte Carlo   I ≈ (m/N)·Σ ((rₖ·rₖ)E − rₖ⊗rₖ),   error ~ 1/√N",
      run = function(ctx)
        local m, r = 2, 0.5
        check_shape(ctx, "solid sphere", inertia.solid_sphere(m, r),
                    mat3.diag(1, 1, 1) * (2 / 5 * m * r ^ 2), m,
                    ellipsoid_sampler(r, r, r))
        ctx:expect("solid sphere: (2/5)·2·0.5² = 0.2", inertia.solid_sphere(m, r):get(1, 1), 0.2)
        check_shape(ctx, "hollow sphere", inertia.hollow_sphere(m, r),
                    mat3.diag(1, 1, 1) * (2 / 3 * m * r ^ 2), m, sphere_surface_sampler(r))
        ctx:expect("hollow sphere: (2/3)·2·0.5² = 1/3", inertia.hollow_sphere(m, r):get(1, 1),
                   1 / 3)
      end,
    },
    {
      title = "Ellipsoid and box",
      text = [[
The solid ellipsoid with semi-axes a, b, c is a stretched ball, and its formula is the
ball's with the stretch put in: the moment about x involves the two semi-axes across x,
I_xx = (1/5)·m·(b² + c²). (With a = b = c = r it falls back to (2/5)·m·r².) The box is the
same pattern with edges instead of semi-axes and 1/12 instead of 1/5. Both have 3 kg and the
numbers 0.6, 0.4 and 0.2 m: the box's edges and the ellipsoid's semi-axes, so the ellipsoid
is twice as long in each direction as the box. Notice the ellipsoid's moments are larger than the
box's: it reaches further out.]],
      formula = "ellipsoid  I = (m/5)·diag(b² + c², a² + c², a² + b²)\n" ..
                "box        I = (m/12)·diag(h² + d², w² + d², w² + h²)",
      run = function(ctx)
        local m, a, b, c = 3, 0.6, 0.4, 0.2
        check_shape(ctx, "solid ellipsoid", inertia.solid_ellipsoid(m, a, b, c),
                    mat3.diag(m * (b ^ 2 + c ^ 2) / 5, m * (a ^ 2 + c ^ 2) / 5,
                              m * (a ^ 2 + b ^ 2) / 5), m, ellipsoid_sampler(a, b, c))
        ctx:expect("ellipsoid: diag(0.12, 0.24, 0.312)", inertia.solid_ellipsoid(m, a, b, c),
                   mat3.diag(0.12, 0.24, 0.312))
        local w, h, d = 0.6, 0.4, 0.2
        check_shape(ctx, "solid box", inertia.solid_box(m, w, h, d),
                    mat3.diag(m * (h ^ 2 + d ^ 2) / 12, m * (w ^ 2 + d ^ 2) / 12,
                              m * (w ^ 2 + h ^ 2) / 12), m, box_sampler(w, h, d))
        ctx:expect("box: diag(0.05, 0.1, 0.13)", inertia.solid_box(m, w, h, d),
                   mat3.diag(0.05, 0.1, 0.13))
      end,
    },
    {
      title = "Solid and hollow cylinders",
      text = [[
A solid cylinder of radius r = 0.3 m, length h = 1 m and mass 2 kg, axis along z, and a thin
tube of the same size and mass (only the wall, no end caps). About the axis the tube has all
its mass at distance r, so I_zz = m·r², twice the solid cylinder's m·r²/2. About a cross axis
both get the same h²/12 from their length, but the tube's wall again sits further out: 6r² in
place of 3r². For the solid cylinder we sample a disc by rejection and a height uniformly; for
the tube an angle and a height.]],
      formula = "solid cylinder  I = diag(m(3r² + h²)/12, m(3r² + h²)/12, m·r²/2)\n" ..
                "hollow cylinder I = diag(m(6r² + h²)/12, m(6r² + h²)/12, m·r²)",
      run = function(ctx)
        local m, r, h = 2, 0.3, 1
        check_shape(ctx, "solid cylinder", inertia.solid_cylinder(m, r, h),
                    mat3.diag(m * (3 * r ^ 2 + h ^ 2) / 12, m * (3 * r ^ 2 + h ^ 2) / 12,
                              m * r ^ 2 / 2), m, cylinder_sampler(r, h))
        check_shape(ctx, "hollow cylinder", inertia.hollow_cylinder(m, r, h),
                    mat3.diag(m * (6 * r ^ 2 + h ^ 2) / 12, m * (6 * r ^ 2 + h ^ 2) / 12,
                              m * r ^ 2), m, tube_sampler(r, h))
        ctx:expect("tube I_zz = 2·0.3² = 0.18, twice the solid cylinder's 0.09",
                   {inertia.hollow_cylinder(m, r, h):get(3, 3),
                    inertia.solid_cylinder(m, r, h):get(3, 3)},
                   {0.18, 0.09})
      end,
    },
    {
      title = "Any other axis: n·I·n",
      text = [[
The tables list each shape along its principal axes, but a body can spin about any line
through its centre. 003 gives the rule: for a unit vector n along that line, the scalar moment
is n·I·n. For the box (0.6 × 0.4 × 0.2 m, 3 kg), the long diagonal from corner to corner has
n = (w, h, d)/√(w² + h² + d²), so n·I·n = (w²·I_xx + h²·I_yy + d²·I_zz)/(w² + h² + d²) =
(0.36·0.05 + 0.16·0.1 + 0.04·0.13)/0.56 ≈ 0.0700 kg·m². Sampling checks it too: the moment
about n is the mean of m·(|r|² − (r·n)²), the squared distance of each point from that line.]],
      formula = "I_n = n·I·n = Σᵢⱼ nᵢ·Iᵢⱼ·nⱼ   (n a unit vector)",
      run = function(ctx)
        local m, w, h, d = 3, 0.6, 0.4, 0.2
        local diagonal = vec3(w, h, d)
        local I_n = inertia.about_axis(inertia.solid_box(m, w, h, d), diagonal)
        ctx:show("axis (not normalised; about_axis normalises)", diagonal)
        ctx:show("n·I·n (kg·m²)", I_n)
        ctx:expect("(0.36·0.05 + 0.16·0.1 + 0.04·0.13)/0.56", I_n,
                   (0.36 * 0.05 + 0.16 * 0.1 + 0.04 * 0.13) / 0.56)
        local n = diagonal:normalized()
        local sampler, sum, square = box_sampler(w, h, d), 0, 0
        math.randomseed(seed)
        for _ = 1, samples do
          local x, y, z = sampler()
          local along = x * n.x + y * n.y + z * n.z
          local distance2 = x * x + y * y + z * z - along * along
          sum, square = sum + distance2, square + distance2 * distance2
        end
        local mean = sum / samples
        local standard_error = m * math.sqrt((square / samples - mean * mean) / samples)
        ctx:show("sampled m·mean(distance² from the diagonal) (kg·m²)", m * mean)
        ctx:show("its standard error (kg·m²)", standard_error)
        ctx:expect("sampled = n·I·n within 4 standard errors", m * mean, I_n,
                   {abs = 4 * standard_error})
      end,
    },
  },
}
