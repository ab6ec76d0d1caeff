-- The inertia tensor of a solid box as a triple integral (001 Appendix B, 003 "The Inertia
-- Tensor"): I_xx = M/(whd)·∫∫∫(y² + z²) dx dy dz = M(h² + d²)/12, products of inertia 0.
-- Axes as in rigidlab: width w along x, height h along y, depth d along z.

local M = 3                        -- kg
local w, h, d = 0.6, 0.4, 0.2      -- m
local density = M / (w * h * d)    -- ρ = M/V, kg/m³

-- The six independent entries of ∫ρ((r·r)E − r⊗r) dV over the box, by the midpoint rule on an
-- n × n × n grid of equal cells: each cell's integrand is taken at its centre.
local function box_tensor_by_cells(n)
  local dx, dy, dz = w / n, h / n, d / n
  local cell_mass = density * dx * dy * dz
  local xx, yy, zz, xy, xz, yz = 0, 0, 0, 0, 0, 0
  for i = 1, n do
    local x = -w / 2 + (i - 0.5) * dx
    for j = 1, n do
      local y = -h / 2 + (j - 0.5) * dy
      for k = 1, n do
        local z = -d / 2 + (k - 0.5) * dz
        xx, yy, zz = xx + (y * y + z * z) * cell_mass, yy + (x * x + z * z) * cell_mass,
                     zz + (x * x + y * y) * cell_mass
        xy, xz, yz = xy - x * y * cell_mass, xz - x * z * cell_mass, yz - y * z * cell_mass
      end
    end
  end
  return mat3(xx, xy, xz, xy, yy, yz, xz, yz, zz)
end

-- The closed form of Appendix B, with its brackets: diag(h² + d², w² + d², w² + h²)·M/12.
local closed_form = mat3.diag(M * (h ^ 2 + d ^ 2) / 12, M * (w ^ 2 + d ^ 2) / 12,
                              M * (w ^ 2 + h ^ 2) / 12)

return lesson{
  id = "box-integral",
  title = "The box's inertia tensor as a triple integral",
  source = "001_8a70f78e0cc79e25.txt, \"Appendix B - Deriving Moments of Inertia for Common " ..
           "Shapes\"; 003_636de12a6b81385f.txt, \"The Inertia Tensor\"",
  steps = {
    {
      title = "From a sum over particles to an integral over the volume",
      text = [[
A real box is not a handful of particles but mass spread evenly through its volume. The sum
Σ mᵢ((rᵢ·rᵢ)E − rᵢ⊗rᵢ) becomes an integral, each tiny piece of volume dV carrying mass ρ·dV,
where the density ρ = M/V is the mass per cubic metre. For the diagonal entry about x that is
I_xx = ρ∫∫∫(y² + z²) dx dy dz over the box, centred on its centre of mass.

Our box: M = 3 kg, width w = 0.6 m along x, height h = 0.4 m along y, depth d = 0.2 m along z
(rigidlab's layout; the article instead runs y over the depth and z over the height, which
swaps the names of I_yy and I_zz but not I_xx). Its density is 3/(0.6·0.4·0.2) = 62.5 kg/m³.

Doing the x integral first just multiplies by w, leaving (M/(hd))∫∫(y² + z²) dy dz; the y
integral gives h³/12 + h·z², and the z integral then (h³d + hd³)/12. So I_xx = M(h² + d²)/12.]],
      formula = "I_xx = M/(w·h·d) ∫∫∫ (y² + z²) dx dy dz  (x∈±w/2, y∈±h/2, z∈±d/2)\n" ..
                "     = M/(h·d) · (h³d + h·d³)/12 = M(h² + d²)/12",
      run = function(ctx)
        ctx:show("volume V = w·h·d (m³)", w * h * d)
        ctx:show("density ρ = M/V (kg/m³)", density)
        ctx:expect("ρ = 3 / 0.048", density, 62.5)
        local after_x = M / (h * d)       -- the factor left once ∫dx = w has cancelled
        local after_y_and_z = (h ^ 3 * d + h * d ^ 3) / 12
        ctx:show("M/(h·d) (kg/m²)", after_x)
        ctx:show("∫∫(y² + z²) dy dz = (h³d + hd³)/12 (m⁴)", after_y_and_z)
        ctx:show("I_xx = M/(h·d)·(h³d + hd³)/12 (kg·m²)", after_x * after_y_and_z)
        ctx:expect("I_xx = 3·(0.4² + 0.2²)/12 = 0.05", after_x * after_y_and_z, 0.05)
      end,
    },
    {
      title = "The integral done numerically, cell by cell",
      text = [[
Let the computer do the integral the honest way: cut the box into n × n × n little cells,
treat each as a particle of mass ρ·(cell volume) at the cell's centre, and add up the
particle formula. This is the midpoint rule in three dimensions.

For an integrand like y² the midpoint rule comes out a little low, by exactly a fraction 1/n²
of the true value (each cell misses the curvature of y² within it). So the table's column
"error × n²" stays fixed at 1: the error is O(h²) in the cell size. Because that error is so
regular, Richardson's trick removes it: (4·S(2n) − S(n))/3 cancels the 1/n² part exactly, and
what remains agrees with M(h² + d²)/12 to rounding (checked to 1e-12 kg·m²).

The products of inertia come out as zero. The cells pair up mirror-image: for every cell at
(x, y, z) there is one at (−x, y, z) whose −x·y cancels it. That is the article's argument
for I₁₂ = 0: the inner integral of −x·y over a range symmetric about zero vanishes.]],
      formula = "I ≈ Σ_cells ρ·ΔV·((r·r)E − r⊗r)\n" ..
                "S(n) = I_exact·(1 − 1/n²) on the diagonal\n" ..
                "Richardson: (4·S(2n) − S(n))/3 = I_exact",
      run = function(ctx)
        local rows, coarse, fine = {}, nil, nil
        for _, n in ipairs({1, 2, 4, 8, 16}) do
          local I = box_tensor_by_cells(n)
          local error = (closed_form:get(1, 1) - I:get(1, 1)) / closed_form:get(1, 1)
          rows[#rows + 1] = {n, n ^ 3, I:get(1, 1), I:get(2, 2), I:get(3, 3), error, error * n * n}
          coarse, fine = fine, I
        end
        ctx:table({"n", "cells", "I_xx", "I_yy", "I_zz", "rel. error I_xx", "error × n²"}, rows)
        ctx:expect("I_xx error × n² = 1 at n = 16 (midpoint rule: S = I(1 − 1/n²))",
                   rows[#rows][7], 1, {rel = 1e-9})
                local extrapolated = (4 * fine - coarse) * (1 / 3)
        local diagonal = {extrapolated:get(1, 1), extrapolated:get(2, 2), extrapolated:get(3, 3)}
        ctx:show("Richardson (4·S(16) − S(8))/3, diagonal (kg·m²)", diagonal)
        ctx:expect("equals (h² + d², w² + d², w² + h²)·M/12", diagonal, {0.05, 0.1, 0.13},
                   {abs = 1e-12})
        ctx:show("products of inertia at n = 16: I₁₂, I₁₃, I₂₃",
                 {fine:get(1, 2), fine:get(1, 3), fine:get(2, 3)})
        ctx:expect("products of inertia vanish by symmetry",
                   {fine:get(1, 2), fine:get(1, 3), fine:get(2, 3)}, {0, 0, 0}, {abs = 1e-15})
      end,
    },
    {
      title = "The engine's box, and a dropped bracket in the article",
      text = [[
rigidlab's inertia.solid_box(M, w, h, d) holds the closed form, so it must agree with the
integral: I_xx = M(h² + d²)/12, I_yy = M(w² + d²)/12, I_zz = M(w² + h²)/12, all other entries
zero. Notice which lengths appear: the moment about an axis involves the two edges across it,
never the edge along it. Spinning about the long x edge is easy; about z, across the two long
edges, hardest.

Some typesetting slips to be aware of. The article's final matrix (001, Appendix B) prints
the first entry as "M/12 d² + h²", which read literally is (M/12)·d² + h², the bracket around
d² + h² having been lost; that even mixes units (kg·m² plus m²). For our box it would give
0.17 instead of 0.05. Its own derivation just before ends correctly with (M/12)(d² + h²).
And in 003 ("The Inertia Tensor") the inner integral over z is evaluated "from z = −z₀/2 to
z = −z₀/2", which would be zero; the upper limit is +z₀/2 (the next line uses it). Two
lines later the y antiderivative is written with y₀ where y belongs, "y₀³z₀/3 + z₀³y₀/12"
evaluated from y = −y₀/2 to y₀/2, though the result it states next, (y₀³z₀ + z₀³y₀)/12,
is right. 003 also writes M = x₀y₀z₀, which is the volume: it silently takes ρ = 1.]],
      formula = "I_box = M/12 · diag(h² + d², w² + d², w² + h²)",
      run = function(ctx)
        local engine = inertia.solid_box(M, w, h, d)
        ctx:show("inertia.solid_box(3, 0.6, 0.4, 0.2) (kg·m²)", engine)
        ctx:expect("M/12·diag(h² + d², w² + d², w² + h²) = diag(0.05, 0.1, 0.13)", engine,
                   mat3.diag(0.05, 0.1, 0.13))
        ctx:expect("engine = the same closed form in symbols", engine, closed_form)
        local as_typeset = M / 12 * d ^ 2 + h ^ 2
        ctx:show("\"M/12 d² + h²\" as typeset (wrong)", as_typeset)
        ctx:show("(M/12)(d² + h²) (right)", M / 12 * (d ^ 2 + h ^ 2))
        ctx:expect("engine I_xx is the bracketed form", engine:get(1, 1), M / 12 * (d ^ 2 + h ^ 2))
      end,
    },
  },
}
