-- The inertia tensor of a set of particles (001 "Stepping Into 3 Dimensions", 003 "The Inertia
-- Tensor", 004 "Inertia Tensor in 3D"): I = Σ mᵢ((rᵢ·rᵢ)E − rᵢ⊗rᵢ) about the centre of mass,
-- L = I·ω not parallel to ω, and a particle moved toward the COM counting for less.

-- Four particles (kg, m) chosen so that their centre of mass is the origin:
-- Σ m·x = 4 − 4 = 0, Σ m·y = 4 − 4 = 0, Σ m·z = 4 − 4 = 0.
local particles = {
  {mass = 1, pos = vec3(4, 0, 0)},
  {mass = 1, pos = vec3(0, 4, 0)},
  {mass = 2, pos = vec3(0, 0, 2)},
  {mass = 4, pos = vec3(-1, -1, -1)},
}

-- The document's formula entry by entry (004, "Inertia Tensor in 3D"), with each offset taken
-- from the centre of mass `com`. Written out with plain numbers, apart from the engine.
local function tensor_by_hand(list, com)
  local xx, yy, zz, xy, xz, yz = 0, 0, 0, 0, 0, 0
  for _, p in ipairs(list) do
    local x, y, z = p.pos.x - com.x, p.pos.y - com.y, p.pos.z - com.z
    xx, yy, zz = xx + p.mass * (y * y + z * z), yy + p.mass * (x * x + z * z),
                 zz + p.mass * (x * x + y * y)
    xy, xz, yz = xy - p.mass * x * y, xz - p.mass * x * z, yz - p.mass * y * z
  end
  return mat3(xx, xy, xz, xy, yy, yz, xz, yz, zz)
end

-- Angle between two vectors (degrees).
local function angle_between(a, b)
  return math.deg(math.acos(math.max(-1, math.min(1, a:dot(b) / (a:norm() * b:norm())))))
end

return lesson{
  id = "particle-tensor",
  title = "The inertia tensor of a set of particles",
  source = "001_8a70f78e0cc79e25.txt, \"Stepping Into 3 Dimensions\"; " ..
           "003_636de12a6b81385f.txt, \"The Inertia Tensor\"; " ..
           "004_8f5d2bfd6f0c2787.txt, \"Inertia Tensor in 3D\"",
  steps = {
    {
      title = "Summing the particles' tensors about the centre of mass",
      text = [[
A rigid body made of particles turns about its centre of mass, so every offset rᵢ is
measured from there. Each particle contributes the same matrix we met for a single mass point,
mᵢ((rᵢ·rᵢ)E − rᵢ⊗rᵢ), and the body's tensor is their sum. The diagonal entries are the moments
about the x, y and z axes (mass times squared distance from that axis); the off-diagonal
entries, the products of inertia, measure how lopsided the mass is: they are zero when the
body is mirror-symmetric about the coordinate planes.

Our body: 1 kg at (4, 0, 0), 1 kg at (0, 4, 0), 2 kg at (0, 0, 2) and 4 kg at (−1, −1, −1).
The heavy particle balances the others, so the centre of mass is exactly the origin. Adding
up by hand: I_xx = 0 + 16 + 8 + 8 = 32, I_yy = 16 + 0 + 8 + 8 = 32, I_zz = 16 + 16 + 0 + 8 =
40, and only the 4 kg particle, off every axis, makes products: −4·(−1)(−1) = −4 each.

A slip in 003 ("The Inertia Tensor"): the offset from the centre of mass is printed as
r'ᵢ = rᵢ(t) x(t); the minus sign is lost. It is r'ᵢ = rᵢ(t) − x(t).]],
      formula = "I = Σᵢ mᵢ((rᵢ·rᵢ)E − rᵢ⊗rᵢ),  rᵢ = pᵢ − x_com\n" ..
                "  = Σᵢ mᵢ [ r_y²+r_z²  −rₓr_y     −rₓr_z    ]\n" ..
                "          [ −rₓr_y     rₓ²+r_z²   −r_y r_z  ]\n" ..
                "          [ −rₓr_z     −r_y r_z   rₓ²+r_y²  ]",
      run = function(ctx)
        local rows = {}
        for i, p in ipairs(particles) do
          local d = inertia.point(p.mass, p.pos)
          rows[i] = {i, p.mass, tostring(p.pos), d:get(1, 1), d:get(2, 2), d:get(3, 3), d:get(1, 2)}
        end
        ctx:table({"particle", "m (kg)", "r (m)", "I_xx", "I_yy", "I_zz", "I_xy"}, rows)
        local mass, com, I = inertia.points(particles)
        ctx:show("total mass (kg)", mass)
        ctx:show("centre of mass (m)", com)
        ctx:expect("mass = 1 + 1 + 2 + 4", mass, 8)
        ctx:expect("centre of mass at the origin", com, vec3(0, 0, 0))
        ctx:show("inertia.points: tensor about the COM (kg·m²)", I)
        ctx:expect("the tensor summed by hand above", I,
                   mat3(32, -4, -4,
                        -4, 32, -4,
                        -4, -4, 40))
        ctx:expect("the same from the document's entries in plain Lua", I,
                   tensor_by_hand(particles, vec3(0, 0, 0)))
      end,
    },
    {
      title = "L = I·ω does not point along ω",
      text = [[
For a single spinning particle on a plane, angular momentum and angular velocity point the
same way. A 3D body is different: because of the products of inertia, and because the moments
differ from axis to axis, L = I·ω generally points somewhere else. Spin our body at
ω = (1, 2, 0) rad/s. The tensor says L = (32 − 8, −4 + 64, −4 − 8) = (24, 60, −12) kg·m²/s.
We check it against the definition itself, the sum of each particle's own r × m·v with
v = ω × r, and measure the angle between L and ω: the two vectors differ by several degrees.

This is the root of the tumbling of free bodies: with no torque, L stays fixed in space, but ω
need not, because it is ω = I⁻¹·L with a tensor that turns with the body.]],
      formula = "L = Σᵢ rᵢ × (mᵢ·(ω × rᵢ)) = I·ω",
      run = function(ctx)
        local _, _, I = inertia.points(particles)
        local omega = vec3(1, 2, 0)
        local L_sum = vec3(0, 0, 0)
        for _, p in ipairs(particles) do
          L_sum = L_sum + p.mass * p.pos:cross(omega:cross(p.pos))
        end
        local L_tensor = I * omega
        ctx:show("ω (rad/s)", omega)
        ctx:show("L = Σ rᵢ × mᵢ(ω × rᵢ) (kg·m²/s)", L_sum)
        ctx:show("L = I·ω (kg·m²/s)", L_tensor)
        ctx:expect("I·ω = (24, 60, −12)", L_tensor, vec3(24, 60, -12))
        ctx:expect("I·ω equals the particle sum", L_tensor, L_sum)
        local angle = angle_between(L_tensor, omega)
        ctx:show("angle between L and ω (degrees)", angle)
        -- cos θ = L·ω/(|L||ω|) = 144/(√4320·√5) = 144/√21600
        ctx:expect("angle = acos(144/√21600)", angle, math.deg(math.acos(144 / math.sqrt(21600))))
      end,
    },
    {
      title = "A particle moved toward the centre of mass counts for less",
      text = [[
The squared distance in the formula means mass far from the centre weighs heavily in I,
and the same mass brought closer weighs much less. Move the 1 kg particle from (4, 0, 0)
halfway in, to (2, 0, 0). Its own contribution to I_yy and I_zz drops from 1·4² = 16 to
1·2² = 4. The centre of mass also shifts, away from the particle, to
((1·2 + 4·(−1))/8, 0, 0) = (−0.25, 0, 0); the tensor about the new centre is the tensor
about the origin minus M((c·c)E − c⊗c) = 8·diag(0, 0.0625, 0.0625).
So I_yy = 32 − 12 − 0.5 = 19.5 and I_zz = 40 − 12 − 0.5 = 27.5, while I_xx, the moment about
the line the particle moved along, stays 32.

The trace, the sum of the three moments, equals 2·Σ mᵢ|rᵢ|² and so measures how spread out
the mass is: it falls from 104 to 79. This is why a figure skater pulling in the arms spins
faster: the same angular momentum with a smaller I means a larger ω.]],
      formula = "I_com = I_origin − M((c·c)E − c⊗c),   trace I = 2·Σ mᵢ|rᵢ|²",
      run = function(ctx)
        local moved = {
          {mass = 1, pos = vec3(2, 0, 0)}, particles[2], particles[3], particles[4],
        }
        local _, _, before = inertia.points(particles)
        local mass, com, after = inertia.points(moved)
        ctx:show("new centre of mass (m)", com)
        ctx:expect("COM x = (1·2 + 0 + 0 + 4·(−1))/8 = −0.25", com, vec3(-0.25, 0, 0))
        ctx:show("tensor about the new COM (kg·m²)", after)
        ctx:expect("I_xx 32, I_yy 19.5, I_zz 27.5, products −4", after,
                   mat3(32, -4, -4,
                        -4, 19.5, -4,
                        -4, -4, 27.5))
        ctx:expect("the same from the document's entries in plain Lua", after,
                   tensor_by_hand(moved, vec3(-0.25, 0, 0)))
        ctx:table({"", "I_xx", "I_yy", "I_zz", "trace"}, {
          {"particle at x = 4", before:get(1, 1), before:get(2, 2), before:get(3, 3),
           before:trace()},
          {"particle at x = 2", after:get(1, 1), after:get(2, 2), after:get(3, 3), after:trace()},
        })
        ctx:expect("trace before = 32 + 32 + 40", before:trace(), 104)
        ctx:expect("trace after = 32 + 19.5 + 27.5", after:trace(), 79)
        ctx:show("total mass is unchanged (kg)", mass)
      end,
    },
  },
}
