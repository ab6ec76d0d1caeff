-- Mass as the integral of density (000 "Mass"): m = ∭ρ dV, which is ρV for a uniform body.
-- The triple integral is done numerically with the midpoint rule and refined; the errors are
-- printed and compared with what quadrature theory predicts.

local density = 500                            -- kg/m³ (about that of dry pine)
local half = vec3(1, 0.5, 0.25)                -- m, half-sizes of a 2 × 1 × 0.5 m box
local box_volume = 8 * half.x * half.y * half.z   -- m³
local radius = 0.5                             -- m, the sphere
local sphere_volume = 4 / 3 * math.pi * radius ^ 3
local refinements = {4, 8, 16, 32}             -- cells per axis

-- Midpoint rule for ∭ρ over the box [−hx, hx] × [−hy, hy] × [−hz, hz] with n cells per axis:
-- the sum of ρ at each cell centre times the cell volume.
local function box_midpoint(rho, n)
  local hx, hy, hz = 2 * half.x / n, 2 * half.y / n, 2 * half.z / n
  local sum = 0
  for i = 1, n do
    local x = -half.x + (i - 0.5) * hx
    for j = 1, n do
      local y = -half.y + (j - 0.5) * hy
      for k = 1, n do sum = sum + rho(x, y, -half.z + (k - 0.5) * hz) end
    end
  end
  return sum * hx * hy * hz
end

-- Midpoint rule over the sphere's bounding cube, counting only cell centres inside the ball.
local function sphere_voxels(n)
  local h = 2 * radius / n
  local inside = 0
  for i = 1, n do
    local x = -radius + (i - 0.5) * h
    for j = 1, n do
      local y = -radius + (j - 0.5) * h
      for k = 1, n do
        local z = -radius + (k - 0.5) * h
        if x * x + y * y + z * z <= radius * radius then inside = inside + 1 end
      end
    end
  end
  return density * inside * h ^ 3
end

-- Midpoint rule in spherical coordinates: dV = r² sin θ dr dθ dφ on [0, R] × [0, π] × [0, 2π].
local function sphere_spherical(n)
  local hr, htheta, hphi = radius / n, math.pi / n, 2 * math.pi / n
  local sum = 0
  for i = 1, n do
    local r = (i - 0.5) * hr
    for j = 1, n do
      local jacobian = r * r * math.sin((j - 0.5) * htheta)
      for _ = 1, n do sum = sum + density * jacobian end
    end
  end
  return sum * hr * htheta * hphi
end

-- The box as a closed triangle mesh (outward counter-clockwise faces), for inertia.mesh.
local function box_mesh()
  local vertices = {}
  for i = 0, 7 do
    vertices[i + 1] = vec3(i & 1 == 1 and half.x or -half.x, i & 2 == 2 and half.y or -half.y,
                           i & 4 == 4 and half.z or -half.z)
  end
  local quads = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5}, {3, 7, 8, 4}, {1, 5, 7, 3},
                 {2, 4, 8, 6}}
  local triangles = {}
  for _, q in ipairs(quads) do
    triangles[#triangles + 1] = {q[1], q[2], q[3]}
    triangles[#triangles + 1] = {q[1], q[3], q[4]}
  end
  return vertices, triangles
end

return lesson{
  id = "mass-density",
  title = "Mass is density integrated over the volume",
  source = "000_3bd95e59483beea1.txt, \"Mass\"",
  steps = {
    {
      title = "Uniform density: m = ρV",
      text = [[
Density ρ says how many kilograms are packed into each cubic metre at a given spot. To get
the mass of a whole object you add up ρ over every tiny piece of its volume, which is what
the integral m = ∫ρ dV means. For a rigid body made of one material ρ is the same
everywhere, it comes out of the integral, and what is left is the volume: m = ρV.

Our box is 2 m × 1 m × 0.5 m of wood at 500 kg/m³: 1 m³, so 500 kg. rigidlab's
inertia.mesh integrates exactly over a closed triangle mesh (the Mirtich–Eberly
polyhedral integrals); fed the box's 12 triangles and the density, it returns the mass and
the volume.]],
      formula = "m = ∫_V ρ dV = ∭ ρ(x, y, z) dx dy dz,   uniform ρ: m = ρ·V",
      run = function(ctx)
        ctx:show("ρ (kg/m³)", density)
        ctx:show("V = w·h·d (m³)", box_volume)
        ctx:show("ρV (kg)", density * box_volume)
        local vertices, triangles = box_mesh()
        local mass, com, _, volume = inertia.mesh(vertices, triangles, density)
        ctx:show("inertia.mesh volume (m³)", volume)
        ctx:show("inertia.mesh mass (kg)", mass)
        ctx:show("inertia.mesh centre of mass (m)", com)
        ctx:expect("volume of the box mesh = 2 · 1 · 0.5", volume, 1)
        ctx:expect("mass = ρV = 500 · 1", mass, 500)
        ctx:expect("centre of mass at the centre", com, vec3(0, 0, 0), {abs = 1e-12})
      end,
    },
    {
      title = "The triple integral, done by hand with the midpoint rule",
      text = [[
A computer integrates by cutting the box into n × n × n small cells, taking ρ at the centre
of each and multiplying by the cell volume (the midpoint rule). With uniform density each
cell contributes exactly ρ times its volume, so even 4 cells per axis give 500 kg exactly.

To watch the method actually work, make the wood denser toward the corners:
ρ = ρ₀(1 + (x² + y² + z²)/s²) with s = 1 m. The exact mass is ρ₀V(1 + (a² + b² + c²)/(3s²))
(a, b, c the half-sizes), 718.75 kg here. Each cell's centre value now slightly
underestimates a curved integrand, by exactly ρ₀/s²·(h²/12) per axis and unit volume, so the
error is −ρ₀V(hx² + hy² + hz²)/(12s²): halving the cells' size quarters it, the signature
of a second-order method.]],
      formula = "m ≈ Σ ρ(cell centre)·hx·hy·hz,   error = −ρ₀V·(hx² + hy² + hz²)/(12s²)",
      run = function(ctx)
        local function uniform() return density end
        local function graded(x, y, z) return density * (1 + x * x + y * y + z * z) end  -- s = 1 m
        local exact_graded = density * box_volume *
                             (1 + (half.x ^ 2 + half.y ^ 2 + half.z ^ 2) / 3)
        ctx:show("exact mass of the graded box (kg)", exact_graded)
        ctx:expect("ρ₀V(1 + (a² + b² + c²)/3)", exact_graded, 718.75)
        local rows, previous_error = {}, nil
        for _, n in ipairs(refinements) do
          local uniform_mass = box_midpoint(uniform, n)
          local graded_mass = box_midpoint(graded, n)
          local error = graded_mass - exact_graded
          local h2 = (2 * half.x / n) ^ 2 + (2 * half.y / n) ^ 2 + (2 * half.z / n) ^ 2
          local predicted = -density * box_volume * h2 / 12
          rows[#rows + 1] = {n, uniform_mass, graded_mass, error, predicted,
                             previous_error and previous_error / error or ""}
          ctx:expect(string.format("uniform box, n = %d: ρV", n), uniform_mass, 500)
          ctx:expect(string.format("graded box, n = %d: error = −ρ₀VΣh²/12", n), error, predicted,
                     {abs = 1e-9})
          previous_error = error
        end
        ctx:table({"n", "uniform m (kg)", "graded m (kg)", "error (kg)", "predicted error",
                   "error ratio"}, rows)
      end,
    },
    {
      title = "A sphere cut into cubes converges slowly and unevenly",
      text = [[
A ball of radius 0.5 m of the same wood has mass ρ·(4/3)πR³ ≈ 261.8 kg. The simplest
numerical attempt fills its bounding cube with cells and counts those whose centre lies
inside the ball. The trouble is the curved surface: cells there are partly in and partly
out, and each is counted as all or nothing. The error shrinks only roughly in proportion to
the cell size, and jumps about in sign as the grid happens to line up with the surface.
At 32 cells per axis it is still about half a percent, so we only ask for 1%.]],
      formula = "m ≈ ρ·h³·#{cell centres with x² + y² + z² ≤ R²}",
      run = function(ctx)
        local exact = density * sphere_volume
        ctx:show("ρ·(4/3)πR³ (kg)", exact)
        local rows, last = {}, nil
        for _, n in ipairs(refinements) do
          last = sphere_voxels(n)
          rows[#rows + 1] = {n, n ^ 3, last, last - exact, (last - exact) / exact}
        end
        ctx:table({"n", "cells", "m (kg)", "error (kg)", "relative error"}, rows)
        ctx:expect("n = 32: within 1% of ρ(4/3)πR³", last, exact, {rel = 0.01})
      end,
    },
    {
      title = "The same sphere in spherical coordinates",
      text = [[
Better: describe the ball in the coordinates that fit it, radius r, polar angle θ and
azimuth φ. The ball becomes a plain box in (r, θ, φ), with no ragged surface, and the
price is the volume factor r²·sin θ (a cell far from the centre, or near the equator,
holds more space). Now the integrand is smooth and the midpoint rule is second order again:
each halving of the cells divides the error by about 4. The quadrature can even be
summed in closed form, ρ·2π·(R³/3 − R·hr²/12)·hθ/sin(hθ/2), which the sums match to
rounding; the error at n = 32 is about 1.6e-4 of the mass.]],
      formula = "m = ∫₀^2π ∫₀^π ∫₀^R ρ r² sin θ dr dθ dφ = ρ·(4/3)πR³",
      run = function(ctx)
        local exact = density * sphere_volume
        local rows, errors = {}, {}
        for index, n in ipairs(refinements) do
          local mass = sphere_spherical(n)
          local hr, htheta = radius / n, math.pi / n
          local closed_form = density * 2 * math.pi * (radius ^ 3 / 3 - radius * hr * hr / 12) *
                              htheta / math.sin(htheta / 2)
          errors[index] = (mass - exact) / exact
          rows[#rows + 1] = {n, mass, errors[index],
                             index > 1 and errors[index - 1] / errors[index] or ""}
          ctx:expect(string.format("n = %d: the sum's closed form", n), mass, closed_form, 1e-12)
        end
        ctx:table({"n", "m (kg)", "relative error", "error ratio"}, rows)
        ctx:expect("n = 32: error ratio to n = 16 ≈ 4 (second order)",
                   errors[#errors - 1] / errors[#errors], 4, {abs = 0.01})
        ctx:expect("n = 32: within 2e-4 of ρ(4/3)πR³", sphere_spherical(32), exact, {rel = 2e-4})
      end,
    },
  },
}
