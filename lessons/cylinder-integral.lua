-- The inertia tensor of a solid cylinder in cylindrical coordinates (001 Appendix B):
-- I₁₁ = M/(πR²h)·∫∫∫(r²sin²θ + z²)·r dθ dr dz = M(3R² + h²)/12, I₃₃ = MR²/2. Axis along z.

local M = 2                  -- kg
local R, h = 0.3, 1.0        -- m, radius and length
local angle_cells = 12       -- midpoint cells over θ: exact for sin²θ, cos²θ, sinθcosθ

-- ∫∫∫ f(r, θ, z)·r dθ dr dz over the cylinder by the midpoint rule: n cells in r, n in z and
-- `angle_cells` in θ. `f` returns several integrands at once; the sums come back in a list.
local function cylinder_integral(n, f)
  local dr, dtheta, dz = R / n, 2 * math.pi / angle_cells, h / n
  local sums = {}
  for i = 1, n do
    local r = (i - 0.5) * dr
    for j = 1, angle_cells do
      local theta = -math.pi + (j - 0.5) * dtheta
      for k = 1, n do
        local z = -h / 2 + (k - 0.5) * dz
        for index, value in ipairs(f(r, theta, z)) do
          sums[index] = (sums[index] or 0) + value * r * dr * dtheta * dz  -- r: the Jacobian
        end
      end
    end
  end
  return sums
end

-- The tensor entries' integrands in cylindrical coordinates: x = r cos θ, y = r sin θ.
local function tensor_integrands(r, theta, z)
  local x, y = r * math.cos(theta), r * math.sin(theta)
  return {y * y + z * z, x * x + z * z, x * x + y * y, -x * y, -x * z, -y * z, 1}
end

-- The tensor (and the volume) from n cells in r and z, with ρ = M/(πR²h).
local function cylinder_tensor(n)
  local s = cylinder_integral(n, tensor_integrands)
  local rho = M / (math.pi * R ^ 2 * h)
  return rho * mat3(s[1], s[4], s[5], s[4], s[2], s[6], s[5], s[6], s[3]), s[7]
end

return lesson{
  id = "cylinder-integral",
  title = "The cylinder's inertia tensor in cylindrical coordinates",
  source = "001_8a70f78e0cc79e25.txt, \"Appendix B - Deriving Moments of Inertia for Common " ..
           "Shapes\"",
  steps = {
    {
      title = "Coordinates that fit the shape",
      text = [[
Integrating over a cylinder with x, y and z is awkward, because the limits of y depend on x.
In cylindrical coordinates the cylinder is a plain box of numbers: distance from the axis r
from 0 to R, angle θ from −π to π, height z from −h/2 to h/2. The price is one extra factor:
a small step dr, dθ, dz sweeps a volume r·dr·dθ·dz, not dr·dθ·dz, because an angle step dθ
covers more ground further out. Forget that r and even the volume comes out wrong.

Our cylinder: M = 2 kg, R = 0.3 m, h = 1 m, axis along z. We integrate numerically with the
midpoint rule, 12 cells around the angle (for sin²θ and cos²θ over a whole turn that is already
exact) and n cells along r and z.]],
      formula = "x = r·cos θ,  y = r·sin θ,  dV = r·dθ·dr·dz\n" ..
                "V = ∫₋ₕ/₂ʰ/² ∫₀ᴿ ∫₋ππ r dθ dr dz = πR²h",
      run = function(ctx)
        local volume = cylinder_integral(4, function() return {1} end)[1]
        -- integrand 1/r cancels the Jacobian: what the volume would be without it
        local without_jacobian = cylinder_integral(4, function(r) return {1 / r} end)[1]
        ctx:show("∫∫∫ r dθ dr dz with 4 cells in r and z (m³)", volume)
        ctx:show("πR²h (m³)", math.pi * R ^ 2 * h)
        ctx:expect("volume = πR²h (the midpoint rule is exact for the linear r)", volume,
                   math.pi * 0.09)
        ctx:show("forgetting the Jacobian, ∫∫∫ dθ dr dz (m³)", without_jacobian)
        ctx:expect("... gives 2πRh instead, not a volume of this cylinder", without_jacobian,
                   2 * math.pi * 0.3)
      end,
    },
    {
      title = "The integrals, numerically",
      text = [[
The tensor's entries become, with ρ = M/(πR²h):
I₁₁ = ρ∫∫∫(r²sin²θ + z²)·r, I₃₃ = ρ∫∫∫(r²cos²θ + r²sin²θ)·r = ρ∫∫∫r³, and the products
−ρ∫∫∫xy·r and so on. The article works them out by hand; here the computer adds up cells.

As for the box, the midpoint rule's error falls like the square of the cell size, and here it
is exactly regular: I₁₁ is low by (3R²/2 + h²)/(3R² + h²)·(1/n²) of itself and I₃₃ by 1/(2n²), so
"error × n²" is constant in the table. Richardson's (4·S(2n) − S(n))/3 removes that part
completely and leaves the exact tensor (checked to 1e-12). The products of inertia vanish:
over a whole turn sin θ·cos θ averages to zero, and z is as often negative as positive.]],
      formula = "I₁₁ = M/(πR²h) ∫∫∫ (r²sin²θ + z²)·r dθ dr dz\n" ..
                "I₃₃ = M/(πR²h) ∫∫∫ r³ dθ dr dz",
      run = function(ctx)
        local exact_11, exact_33 = M * (3 * R ^ 2 + h ^ 2) / 12, M * R ^ 2 / 2
        local rows, coarse, fine = {}, nil, nil
        for _, n in ipairs({2, 4, 8, 16}) do
          local I = cylinder_tensor(n)
          local error_11 = (exact_11 - I:get(1, 1)) / exact_11
          local error_33 = (exact_33 - I:get(3, 3)) / exact_33
          rows[#rows + 1] = {n, I:get(1, 1), error_11 * n * n, I:get(3, 3), error_33 * n * n}
          coarse, fine = fine, I
        end
        ctx:table({"n", "I₁₁ (kg·m²)", "I₁₁ error × n²", "I₃₃ (kg·m²)", "I₃₃ error × n²"}, rows)
        ctx:expect("I₃₃ relative error × n² = 1/2", rows[#rows][5], 0.5, {rel = 1e-9})
        ctx:expect("I₁₁ relative error × n² = (3R²/2 + h²)/(3R² + h²)", rows[#rows][3],
                   (1.5 * R ^ 2 + h ^ 2) / (3 * R ^ 2 + h ^ 2), {rel = 1e-9})
                local extrapolated = (4 * fine - coarse) * (1 / 3)
        local diagonal = {extrapolated:get(1, 1), extrapolated:get(2, 2), extrapolated:get(3, 3)}
        ctx:show("Richardson (4·S(16) − S(8))/3, diagonal (kg·m²)", diagonal)
        ctx:expect("= (M(3R² + h²)/12, same, MR²/2) = (0.21167, 0.21167, 0.09)", diagonal,
                   {2 * 1.27 / 12, 2 * 1.27 / 12, 0.09}, {abs = 1e-12})
        local products = {fine:get(1, 2), fine:get(1, 3), fine:get(2, 3)}
        ctx:show("products I₁₂, I₁₃, I₂₃ at n = 16", products)
        ctx:expect("products of inertia vanish", products, {0, 0, 0}, {abs = 1e-14})
      end,
    },
    {
      title = "The closed form, the engine, and a stray π",
      text = [[
By hand, the θ integral of r²sin²θ over a whole turn gives πr², the r integral then πR⁴/4,
and the z² part contributes 2π·(R²/2)·(h³/12); all over πR²h that is I₁₁ = M(3R² + h²)/12.
For I₃₃ the angle plays no part: 2π·(R⁴/4)·h/(πR²h) = R²/2, so I₃₃ = MR²/2, exactly the thin
disc's formula: stacking discs along the axis does not change how far the mass is from it.
The length h appears only in the moments about the cross axes, where a longer cylinder is a
longer lever.

A slip in the article's last lines for I₁₁: the bracket is printed as (1/12)πhR²(3R²π + h²),
with a π inside the bracket that does not belong there (it has already been taken out in
front). Read literally it gives M(3πR² + h²)/12; the right result, and the article's own final
matrix, is M(3R² + h²)/12. rigidlab's inertia.solid_cylinder holds the right one.]],
      formula = "I_cylinder = diag( M(3R² + h²)/12,  M(3R² + h²)/12,  MR²/2 )",
      run = function(ctx)
        local engine = inertia.solid_cylinder(M, R, h)
        ctx:show("inertia.solid_cylinder(2, 0.3, 1) (kg·m²)", engine)
        ctx:expect("M(3R² + h²)/12 on x and y, MR²/2 on z", engine,
                   mat3.diag(M * (3 * R ^ 2 + h ^ 2) / 12, M * (3 * R ^ 2 + h ^ 2) / 12,
                             M * R ^ 2 / 2))
        local printed = M / (math.pi * R ^ 2 * h) *
                        (math.pi * h * R ^ 2 * (3 * R ^ 2 * math.pi + h ^ 2) / 12)
        ctx:show("I₁₁ with the stray π, M(3πR² + h²)/12 (wrong)", printed)
        ctx:show("I₁₁ = M(3R² + h²)/12 (right)", M * (3 * R ^ 2 + h ^ 2) / 12)
        ctx:expect("engine I₁₁ = 2·(0.27 + 1)/12", engine:get(1, 1), 2 * 1.27 / 12)
        ctx:expect("engine I₃₃ = 2·0.09/2", engine:get(3, 3), 0.09)
      end,
    },
  },
}
