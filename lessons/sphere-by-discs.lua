-- The solid sphere's moment of inertia built from thin discs (000 "Inertia of primitive
-- shapes"): I = ½ρπ∫(R² − z²)² dz over −R..R = ρπ(1 − 2/3 + 1/5)R⁵ = (2/5)mR².

local density = 7850   -- kg/m³, steel
local radius = 0.1     -- m
local exact_mass = density * 4 / 3 * math.pi * radius ^ 3            -- m = ρ(4/3)πR³
local exact_inertia = density * math.pi * (1 - 2 / 3 + 1 / 5) * radius ^ 5  -- the document's result

-- Cuts the sphere into n discs of equal thickness h = 2R/n and adds up their mass and their
-- moment about z, each disc taken at the middle of its slice (the midpoint rule):
-- disc radius² r² = R² − z², dm = ρπr²h, dI = ½r²dm.
local function sum_of_discs(n)
  local h = 2 * radius / n
  local mass, moment = 0, 0
  for k = 1, n do
    local z = -radius + (k - 0.5) * h
    local r2 = radius ^ 2 - z ^ 2
    local dm = density * math.pi * r2 * h
    mass = mass + dm
    moment = moment + 0.5 * r2 * dm
  end
  return mass, moment
end

return lesson{
  id = "sphere-by-discs",
  title = "A solid sphere's inertia, summed from thin discs",
  source = "000_3bd95e59483beea1.txt, \"Inertia of primitive shapes\"",
  steps = {
    {
      title = "The sphere as a stack of coins",
      text = [[
A ball is hard to integrate over directly, but easy to slice. Cut a steel ball (radius 0.1 m,
density 7850 kg/m³) across the z axis into thin discs, like a stack of coins of different
sizes. A disc at height z has radius r with r² = R² − z² (the sphere's surface is
x² + y² + z² = R²), thickness dz, and so mass dm = ρ·πr²·dz.

We already know a thin disc's moment about its own axis: ½r²·dm, half of what it would be if
all its mass sat on the rim, because most of a disc's mass is closer in. Every disc shares the
z axis, so the ball's moment about z is just the sum of the discs' moments. Here is one disc,
the one through the equator, 1 mm thick.]],
      formula = "r² = R² − z²,   dm = ρ·π·r²·dz,   dI = ½·r²·dm = ½·ρ·π·r⁴·dz",
      run = function(ctx)
        local dz = 0.001
        local r2 = radius ^ 2
        local dm = density * math.pi * r2 * dz
        ctx:show("disc at z = 0: radius r (m)", math.sqrt(r2))
        ctx:show("its mass dm = ρπr²dz (kg)", dm)
        ctx:show("its moment dI = ½r²dm (kg·m²)", 0.5 * r2 * dm)
        local disc = inertia.solid_cylinder(dm, radius, dz)
        ctx:show("inertia.solid_cylinder(dm, R, dz) (kg·m²)", disc)
        ctx:expect("a thin disc about its axis: ½r²dm", disc:get(3, 3), 0.5 * r2 * dm)
      end,
    },
    {
      title = "Adding up the discs",
      text = [[
Now add the discs. With n slices of thickness h = 2R/n we take each disc at the middle of its
slice; as n grows the stack of flat discs hugs the round surface better and the sums approach
the integrals: the mass ρπ∫(R² − z²) dz and the moment I = ½ρπ∫(R² − z²)² dz, from −R to R.

Watch the two error columns. Each time the number of slices doubles, the error of the mass
falls by a factor of 4: the midpoint rule's error shrinks like h², the square of the slice
thickness. The error of the moment falls by 16, like h⁴. That is a bonus, not luck: the
midpoint rule's h² error is proportional to the difference of the integrand's slopes at the
two ends, and the disc moments (R² − z²)² flatten out to zero slope at the poles, where the
discs shrink to points. So the h² part cancels and only an h⁴ part is left. With 1024 slices
the mass is within 5e-7 of exact (relative) and the moment within 1e-12; the checks allow
1e-6 and 1e-10, relative.]],
      formula = "I = ½ρπ ∫₋ᴿᴿ (R² − z²)² dz ≈ Σₖ ½ρπ(R² − zₖ²)²·h,\n" ..
                "  zₖ = −R + (k − ½)h,   h = 2R/n",
      run = function(ctx)
        local rows, errors = {}, {}
        for i, n in ipairs({1, 2, 4, 8, 16, 32, 64, 128}) do
          local mass, moment = sum_of_discs(n)
          errors[i] = {mass = math.abs(mass - exact_mass) / exact_mass,
                       moment = math.abs(moment - exact_inertia) / exact_inertia}
          local ratio = function(key)
            return i > 1 and string.format("%.4f", errors[i - 1][key] / errors[i][key]) or ""
          end
          rows[i] = {n, mass, errors[i].mass, ratio("mass"), moment, errors[i].moment,
                     ratio("moment")}
        end
        ctx:table({"n", "Σ dm (kg)", "error", "ratio", "Σ dI (kg·m²)", "error", "ratio"}, rows)
        local last = errors[#errors]
        ctx:expect("mass error ratio per halving of h: 4 (h²)",
                   errors[#errors - 1].mass / last.mass, 4, {rel = 1e-6})
        ctx:expect("moment error ratio per halving of h: 16 (h⁴)",
                   errors[#errors - 1].moment / last.moment, 16, {rel = 1e-6})
        local mass, moment = sum_of_discs(1024)
        ctx:show("sum of 1024 discs: mass (kg)", mass)
        ctx:show("sum of 1024 discs: I (kg·m²)", moment)
        ctx:expect("Σ dm → ρ(4/3)πR³ (relative error 1/(2n²))", mass / exact_mass, 1,
                   {rel = 1e-6})
        ctx:expect("Σ dI → ρπ(1 − 2/3 + 1/5)R⁵", moment / exact_inertia, 1, {rel = 1e-10})
      end,
    },
    {
      title = "The exact integral, and (2/5)·m·R²",
      text = [[
The integral itself is a polynomial and can be done exactly: the antiderivative of
(R² − z²)² = R⁴ − 2R²z² + z⁴ is R⁴z − 2R²z³/3 + z⁵/5. Between −R and R this gives
2R⁵(1 − 2/3 + 1/5) = (16/15)R⁵, so I = ρπ(8/15)R⁵. The ball's mass is ρ(4/3)πR³; dividing,
I/(mR²) = (8/15)/(4/3) = 2/5. The familiar I = (2/5)mR² is just this bookkeeping: a solid ball
resists spinning like 40% of its mass placed on a ring of radius R, because most of its mass
is well inside.

The engine's inertia.solid_sphere gives the same number, and the same for every axis, as a
ball must.]],
      formula = "I = ½ρπ[R⁴z − 2R²z³/3 + z⁵/5]₋ᴿᴿ = ρπ(1 − 2/3 + 1/5)R⁵,   m = ρ(4/3)πR³\n" ..
                "  ⇒ I = (2/5)·m·R²",
      run = function(ctx)
        ctx:show("1 − 2/3 + 1/5", 1 - 2 / 3 + 1 / 5)
        ctx:expect("1 − 2/3 + 1/5 = 8/15", 1 - 2 / 3 + 1 / 5, 8 / 15)
        ctx:show("m = ρ(4/3)πR³ (kg)", exact_mass)
        ctx:show("I = ρπ(8/15)R⁵ (kg·m²)", exact_inertia)
        ctx:show("I / (m·R²)", exact_inertia / (exact_mass * radius ^ 2))
        ctx:expect("I / (m·R²) = 2/5", exact_inertia / (exact_mass * radius ^ 2), 0.4)
        local sphere = inertia.solid_sphere(exact_mass, radius)
        ctx:show("inertia.solid_sphere(m, R) (kg·m²)", sphere)
        ctx:expect("engine = (2/5)mR² on every axis", sphere,
                   mat3.diag(1, 1, 1) * (2 / 5 * exact_mass * radius ^ 2))
        ctx:expect("engine I_zz = the disc integral ρπ(8/15)R⁵", sphere:get(3, 3), exact_inertia)
      end,
    },
  },
}
