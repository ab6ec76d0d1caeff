-- Moment of inertia of mass points (000 "Moment of inertia", 002 "Rotational Inertia of a
-- Particle"): I = m·r², I = Σ mᵢ·rᵢ², and the particle's full tensor −m·r̂·r̂ = m((r·r)E − r⊗r).

local z_axis = vec3(0, 0, 1)

-- Distance of a point from the z axis (m): the r of I = m·r² for spinning about z.
local function distance_from_z_axis(p) return math.sqrt(p.x ^ 2 + p.y ^ 2) end

-- A few particles around the z axis (kg, m). Their distances from the axis are 1, 0.5 and 2 m.
local particles = {
  {mass = 1, pos = vec3(1, 0, 0.3)},
  {mass = 2, pos = vec3(0.3, -0.4, -1)},
  {mass = 3, pos = vec3(-1.2, 1.6, 0.5)},
}

return lesson{
  id = "point-inertia",
  title = "Moment of inertia of mass points, and the particle's tensor",
  source = "000_3bd95e59483beea1.txt, \"Moment of inertia\"; " ..
           "002_5497adede943f513.txt, \"Rotational Inertia of a Particle\"",
  steps = {
    {
      title = "One mass point: I = m·r²",
      text = [[
The moment of inertia says how hard it is to change how fast something spins about a given
axis. For a single small mass it depends on two things only: how much mass there is, and how
far it sits from the axis. Doubling the mass doubles I; doubling the distance quadruples it:
the same angular acceleration then means twice the linear acceleration, so twice the force,
and a force on a lever twice as long takes twice the torque.

The r here is the distance from the AXIS, not from the origin. A 2 kg particle at
(0.9, 1.2, 0.7) m sits 1.5 m from the z axis (√(0.9² + 1.2²)); its height along z does not
matter for turning about z. So I_z = 2 · 1.5² = 4.5 kg·m². rigidlab's inertia.point builds
the particle's tensor, and inertia.about_axis reads off the moment about any axis n as n·I·n.]],
      formula = "I = m·r²   (r = distance from the rotation axis)",
      run = function(ctx)
        local m, p = 2, vec3(0.9, 1.2, 0.7)
        local r = distance_from_z_axis(p)
        ctx:show("particle position (m)", p)
        ctx:show("distance from the z axis r (m)", r)
        ctx:expect("r = √(0.9² + 1.2²)", r, 1.5)
        local tensor = inertia.point(m, p)
        ctx:show("particle tensor about the origin (kg·m²)", tensor)
        local I_z = inertia.about_axis(tensor, z_axis)
        ctx:show("I about z = n·I·n (kg·m²)", I_z)
        ctx:expect("I_z = m·r² = 2 · 1.5²", I_z, 4.5)
        local moved = inertia.about_axis(inertia.point(m, vec3(0.9, 1.2, -5)), z_axis)
        ctx:show("same particle moved to z = −5 m: I_z (kg·m²)", moved)
        ctx:expect("sliding along the axis leaves I_z unchanged", moved, 4.5)
        local doubled = inertia.about_axis(inertia.point(m, vec3(1.8, 2.4, 0.7)), z_axis)
        ctx:show("twice as far from the axis: I_z (kg·m²)", doubled)
        ctx:expect("twice the distance, four times the inertia", doubled, 4 * 4.5)
      end,
    },
    {
      title = "Several mass points: I = Σ mᵢ·rᵢ²",
      text = [[
A body made of several particles resists turning with the sum of what each particle
contributes: nothing couples them except that they turn together. Here masses of 1, 2 and 3 kg
sit at 1, 0.5 and 2 m from the z axis, so I_z = 1·1² + 2·0.5² + 3·2² = 1 + 0.5 + 12 = 13.5
kg·m². Notice how the outermost particle dominates: the square of the distance makes far-away
mass count much more than mass near the axis. For a continuous body the sum becomes an
integral over its mass, I = ∫ r² dm (the later lessons do exactly that).]],
      formula = "I = Σᵢ mᵢ·rᵢ²        (continuous body: I = ∫ r² dm)",
      run = function(ctx)
        local rows, total = {}, mat3.zero()
        for i, p in ipairs(particles) do
          local r = distance_from_z_axis(p.pos)
          local tensor = inertia.point(p.mass, p.pos)
          total = total + tensor
          rows[i] = {i, p.mass, r, p.mass * r ^ 2, inertia.about_axis(tensor, z_axis)}
        end
        ctx:table({"particle", "m (kg)", "r (m)", "m·r² by hand", "engine n·I·n"}, rows)
        local I_z = inertia.about_axis(total, z_axis)
        ctx:show("sum of the particle tensors (kg·m²)", total)
        ctx:show("I_z of the set (kg·m²)", I_z)
        ctx:expect("I_z = 1·1² + 2·0.5² + 3·2²", I_z, 13.5)
      end,
    },
    {
      title = "The particle's tensor from the hat operator",
      text = [[
About one axis a number is enough, but a body can spin about any axis, so we want one object
that answers for all of them: the inertia tensor, a 3×3 matrix with L = I·ω. For a particle
the slides of 002 get it from the angular momentum L = m·r × (ω × r). Writing the cross product
with the hat (skew) matrix, r × a = r̂·a, gives L = −m·r̂·r̂·ω, so I = −m·r̂·r̂. Multiplying the
two hat matrices out gives the same thing as m((r·r)E − r⊗r): the diagonal holds m times the
squared distance from each coordinate axis, the off-diagonal entries are −m·rₓ·r_y and so on.

For m = 2 kg at r = (1, 2, 3) m, r·r = 14 and the tensor is 2·((13, −2, −3), (−2, 10, −6),
(−3, −6, 5)). Each diagonal entry is the I = m·r² of the previous steps about x, y or z.

A slip in the same slide deck (002, "Cross Product & Hat Operator"): the third component of
a × b is printed as aₓb_y − a_y·b_z; it must be aₓb_y − a_y·bₓ. With a = (1, 2, 3) and
b = (4, 5, 6) the printed form gives 1·5 − 2·6 = −7 instead of the right 1·5 − 2·4 = −3.]],
      formula = "I = −m·r̂·r̂ = m((r·r)E − r⊗r) =\n" ..
                "  [ m(r_y²+r_z²)   −m rₓr_y        −m rₓr_z      ]\n" ..
                "  [ −m rₓr_y       m(rₓ²+r_z²)     −m r_y r_z    ]\n" ..
                "  [ −m rₓr_z       −m r_y r_z      m(rₓ²+r_y²)   ]",
      run = function(ctx)
        local a, b = vec3(1, 2, 3), vec3(4, 5, 6)
        local slide_z = a.x * b.y - a.y * b.z
        ctx:show("a × b, z component as printed, aₓb_y − a_y·b_z", slide_z)
        ctx:show("a × b (vec3:cross)", a:cross(b))
        ctx:expect("right z component aₓb_y − a_y·bₓ = −3", a:cross(b).z, -3)
        ctx:expect("hat operator: â·b = a × b", a:skew() * b, vec3(-3, 6, -3))

        local m, r = 2, vec3(1, 2, 3)
        local hat = r:skew()
        ctx:show("r̂ (hat matrix of r)", hat)
        local from_hat = -m * (hat * hat)
        ctx:show("−m·r̂·r̂ (kg·m²)", from_hat)
        local by_hand = mat3(26, -4, -6,
                             -4, 20, -12,
                             -6, -12, 10)
        ctx:expect("−m·r̂·r̂ = 2·((13,−2,−3), (−2,10,−6), (−3,−6,5))", from_hat, by_hand)
        local engine = inertia.point(m, r)
        ctx:show("inertia.point(2, (1, 2, 3)) (kg·m²)", engine)
        ctx:expect("engine tensor = m((r·r)E − r⊗r) written out", engine, by_hand)
      end,
    },
    {
      title = "The tensor at work: L = I·ω",
      text = [[
The point of the tensor is that one matrix product gives the particle's angular momentum for
any spin: L = I·ω must equal the definition L = r × p = m·r × (ω × r) for every ω. We try it
with ω = (0.5, −1, 2) rad/s. Notice the answer is not a multiple of ω: a particle spun about an
axis that does not pass through it carries angular momentum tilted away from that axis. That
mismatch between L and ω is what makes 3D rotation interesting, and the next lessons follow it.]],
      formula = "L = I·ω = m·r × (ω × r)",
      run = function(ctx)
        local m, r, omega = 2, vec3(1, 2, 3), vec3(0.5, -1, 2)
        local L_tensor = inertia.point(m, r) * omega
        local L_definition = m * r:cross(omega:cross(r))
        ctx:show("ω (rad/s)", omega)
        ctx:show("ω × r = velocity of the particle (m/s)", omega:cross(r))
        ctx:show("L = m·r × (ω × r) (kg·m²/s)", L_definition)
        ctx:show("L = I·ω (kg·m²/s)", L_tensor)
        -- by hand: I·ω = 2·(13·0.5 + 2 − 6, −1 − 10 − 12, −1.5 + 6 + 10) = (5, −46, 29)
        ctx:expect("I·ω = (5, −46, 29) worked out by hand", L_tensor, vec3(5, -46, 29))
        ctx:expect("I·ω = m·r × (ω × r)", L_tensor, L_definition)
        local cosine = L_tensor:dot(omega) / (L_tensor:norm() * omega:norm())
        ctx:show("angle between L and ω (degrees)", math.deg(math.acos(cosine)))
      end,
    },
  },
}
