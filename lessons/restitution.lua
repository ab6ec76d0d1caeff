-- Restitution (001 Appendix C, 003 "Collision Response"): the impulse
-- J = −(1+e)(vb − va)·N/(1/ma + 1/mb) for e = 0, 0.5 and 1, the kinetic energy each one
-- loses (closed form ½μ(1 − e²)v_n², μ the reduced mass), and a bounce off an immovable
-- body, p̂ = −(e+1)m1(v1·n)n.

local ma, va = 1, 2      -- kg, m/s: 001's striking particle
local mb, vb = 4, 0      -- kg, m/s: 001's body of four particles, at rest
local restitutions = {0, 0.5, 1}

-- The kinetic energy a collision turns into heat and sound: in the frame of the centre of
-- mass the pair carries ½μ·v_n² in its normal closing motion, with the reduced mass
-- μ = ma·mb/(ma + mb); restitution scales v_n by −e, so the loss is ½μ(1 − e²)v_n².
local function energy_lost(mass_a, mass_b, e, normal_speed)
  local reduced_mass = mass_a * mass_b / (mass_a + mass_b)
  return 0.5 * reduced_mass * (1 - e * e) * normal_speed ^ 2
end

local function kinetic(m, v) return 0.5 * m * v ^ 2 end

return lesson{
  id = "restitution",
  title = "Restitution: how much of the bounce survives",
  source = "001_8a70f78e0cc79e25.txt, \"Appendix C - Deriving Collision Impulses Using " ..
           "Conservation Laws Only\"; 003_636de12a6b81385f.txt, \"Collision Response\"",
  steps = {
    {
      title = "One number between sticking and bouncing",
      text = [[
Real collisions are not perfectly elastic: part of the kinetic energy goes into heat,
sound and permanent dents. Instead of modelling all that, we summarise it in one number,
the coefficient of restitution e between 0 and 1: after the collision the bodies separate
along the normal at e times the speed at which they approached. With e = 1 nothing is lost;
with e = 0 they do not separate at all and move on together.

The impulse only changes by the factor (1 + e). For 001's pair, a 1 kg particle at 2 m/s
against the resting 4 kg body, J = (1 + e)·1.6 N·s: 1.6, 2.4 and 3.2 N·s for e = 0, 0.5, 1.
With e = 0 both move at 0.4 m/s afterwards, which is the velocity of their common centre of
mass (ma·va + mb·vb)/(ma + mb), the "sticking together" case Appendix C starts from.]],
      formula = "J = −(1+e)(vb − va)·N/(1/ma + 1/mb),   (vb' − va')·N = −e·(vb − va)·N",
      run = function(ctx)
        local rows = {}
        for _, e in ipairs(restitutions) do
          local J, va_after, vb_after = collide.impulse_1d(ma, va, mb, vb, e)
          rows[#rows + 1] = {e, J, va_after, vb_after, vb_after - va_after}
          ctx:expect("e = " .. e .. ": J = (1+e)·1.6", J, (1 + e) * 1.6)
          ctx:expect("e = " .. e .. ": separation speed = e·2", vb_after - va_after, e * (va - vb))
          ctx:expect("e = " .. e .. ": momentum kept", ma * va_after + mb * vb_after,
                     ma * va + mb * vb)
        end
        ctx:table({"e", "J (N·s)", "va' (m/s)", "vb' (m/s)", "vb' − va' (m/s)"}, rows)
        local _, stuck_a, stuck_b = collide.impulse_1d(ma, va, mb, vb, 0)
        local v_com = (ma * va + mb * vb) / (ma + mb)
        ctx:show("velocity of the centre of mass (m/s)", v_com)
        ctx:expect("e = 0: a moves with the centre of mass", stuck_a, 0.4)
        ctx:expect("e = 0: b moves with the centre of mass", stuck_b, 0.4)
      end,
    },
    {
      title = "The energy that is lost",
      text = [[
Momentum is kept for every e; kinetic energy only for e = 1. How much goes? Watch the
pair from its centre of mass: that motion is untouched by the collision, and what remains
is the closing motion, which carries ½μ·v_rel² with the reduced mass μ = ma·mb/(ma + mb),
here 0.8 kg. Restitution multiplies the closing speed by −e, so the energy left is e² of
it. For our pair that is 1.6·(1 − e²) J: 1.6 J lost when they stick, 1.2 J at e = 0.5, and
nothing at e = 1.

003 writes the energy balance as ½m1v1² + ½m2v2² = ½m1v1² + ½m2v2² + T_lost: the primes on
the right-hand side, the velocities after the collision, have been dropped, which as
printed would force T_lost = 0. Its restitution relation (v'2 − v'1) = ε(v2 − v1) also
lacks a minus sign: the bodies separate, so the relative velocity reverses direction.]],
      formula = "T_lost = ½μ(1 − e²)·v_rel²,   μ = ma·mb/(ma + mb)",
      run = function(ctx)
        local rows = {}
        local before = kinetic(ma, va) + kinetic(mb, vb)
        ctx:show("kinetic energy before (J)", before)
        ctx:show("reduced mass μ (kg)", ma * mb / (ma + mb))
        for _, e in ipairs(restitutions) do
          local _, va_after, vb_after = collide.impulse_1d(ma, va, mb, vb, e)
          local after = kinetic(ma, va_after) + kinetic(mb, vb_after)
          local lost = energy_lost(ma, mb, e, va - vb)
          rows[#rows + 1] = {e, after, before - after, lost}
          ctx:expect("e = " .. e .. ": energy lost = ½μ(1 − e²)v²", before - after, lost, 1e-12)
        end
        ctx:table({"e", "T after (J)", "T lost (J)", "½μ(1 − e²)v² (J)"}, rows)
        ctx:expect("e = 0 loses 1.6 J", rows[1][3], 1.6, 1e-12)
        ctx:expect("e = 0.5 loses 1.2 J", rows[2][3], 1.2, 1e-12)
        ctx:expect("e = 1 loses nothing", rows[3][3], 0, {abs = 1e-12})
      end,
    },
    {
      title = "In three dimensions only the normal part bounces",
      text = [[
In 3D the bodies meet along a contact normal N, and only the velocity components along N
take part: dotting the relative velocity with N turns the problem back into the 1D one.
Without friction the parts of the velocities across N pass through unchanged. Here two
balls of radius 0.5 m, 1 kg and 4 kg, meet at a slant: they touch at the origin, centred at
∓0.5N with N = (0.6, 0.8, 0), moving at (2, 1, −1) and (−1, 0.5, 2) m/s, with e = 0.5 —
their velocities are not along the line of centres. collide.resolve is given the contact point between them; its impulse must equal 003's
formula with the normal components only, and the energy lost must be ½μ(1 − e²)(v_rel·N)².
The contact point lies on the line of centres, so the impulse passes through both centres
of mass and neither ball starts to spin.]],
      formula = "p̂ = (e+1)(v2·n − v1·n)/(1/m1 + 1/m2)·n,\n" ..
                "v1' = v1 + p̂/m1,   v2' = v2 − p̂/m2",
      run = function(ctx)
        local e = 0.5
        local normal = vec3(3, 4, 0):normalized()
        local v1, v2 = vec3(2, 1, -1), vec3(-1, 0.5, 2)
        local a = body.sphere{mass = ma, radius = 0.5, position = -0.5 * normal, velocity = v1}
        local b = body.sphere{mass = mb, radius = 0.5, position = 0.5 * normal, velocity = v2}
        ctx:show("centres of the balls (m)", {a.position, b.position})
        local before = a:kinetic_energy() + b:kinetic_energy()
        local J = collide.resolve(a, b, {point = vec3(0, 0, 0), normal = normal, restitution = e})
        local closing = (v2 - v1):dot(normal)
        -- (Subtracting from the zero vector keeps zero components +0 when printed.)
        local p_hat = vec3() - normal * (-(e + 1) * closing / (1 / ma + 1 / mb))
        ctx:show("N", normal)
        ctx:show("(v2 − v1)·N (m/s)", closing)
        ctx:show("J from collide.resolve (N·s)", J)
        ctx:show("p̂ from 003's formula (N·s)", p_hat)
        ctx:show("v1' (m/s)", a.velocity)
        ctx:show("v2' (m/s)", b.velocity)
        ctx:expect("J N = −p̂ (resolve's J acts on b, p̂ on body 1)", J * normal, vec3() - p_hat,
                   1e-12)
        ctx:expect("v1' = v1 + p̂/m1", a.velocity, v1 + p_hat / ma, 1e-12)
        ctx:expect("v2' = v2 − p̂/m2", b.velocity, v2 - p_hat / mb, 1e-12)
        ctx:expect("tangential part of v1 unchanged", a.velocity - a.velocity:dot(normal) * normal,
                   v1 - v1:dot(normal) * normal, 1e-12)
        ctx:expect("separating at e times the closing speed", (b.velocity - a.velocity):dot(normal),
                   -e * closing, 1e-12)
        local lost = before - a:kinetic_energy() - b:kinetic_energy()
        ctx:show("energy lost (J)", lost)
        ctx:expect("energy lost = ½μ(1 − e²)(v_rel·N)²", lost, energy_lost(ma, mb, e, closing),
                   1e-12)
        ctx:expect("no spin from a central impulse", a.angular_velocity, vec3(0, 0, 0),
                   {abs = 1e-12})
      end,
    },
    {
      title = "Bouncing off something immovable",
      text = [[
A floor or a wall is far heavier than what hits it. Rather than putting in a huge mass, the
engine stores inverse masses, and an immovable body has 1/m = 0 (Appendix C). The mass of
the wall then drops out of the formula, and 003's impulse reduces to p̂ = −(e+1)m1(v1·n)n:
the ball's normal momentum is reversed and scaled by e, its sideways velocity untouched.

A 2 kg ball of radius 0.1 m at the origin, moving at (1, −3, 0) m/s, hits a static floor
below it (a box of 10 × 1 × 10 m centred at y = −0.6 m, its top at −0.1 m) with e = 0.5; the normal n
points from the ball to the floor, (0, −1, 0), so v1·n = 3 m/s and p̂ = −1.5·2·3·n, an
impulse of 9 N·s upward. The ball leaves at (1, 1.5, 0) m/s and keeps a quarter (e²) of
the kinetic energy of its vertical motion. (A small slip in Appendix C, where it lists
inverse masses of very heavy bodies: 1/2000000000 is printed as 5^-10, meaning 5·10⁻¹⁰,
and 1/(2·10²³) as 5^-24, meaning 5·10⁻²⁴.)]],
      formula = "p̂ = −(e+1)·m1·(v1·n)·n   (1/m2 = 0)",
      run = function(ctx)
        local e, m1, v1, normal = 0.5, 2, vec3(1, -3, 0), vec3(0, -1, 0)
        local floor = body.box{static = true, size = vec3(10, 1, 10), position = vec3(0, -0.6, 0)}
        local ball = body.sphere{mass = m1, radius = 0.1, velocity = v1}
        ctx:show("floor: inverse mass (1/kg)", floor.inv_mass)
        local p_hat = vec3() - normal * ((e + 1) * m1 * v1:dot(normal))
        local J = collide.resolve(ball, floor, {point = vec3(0, -0.1, 0), normal = normal,
                                                restitution = e})
        ctx:show("p̂ = −(e+1)m1(v1·n)n (N·s)", p_hat)
        ctx:show("J from collide.resolve (N·s)", J)
        ctx:show("v1' (m/s)", ball.velocity)
        ctx:expect("J = 9 N·s", J, 9, 1e-12)
        ctx:expect("the ball receives p̂", vec3() - normal * J, p_hat, 1e-12)
        ctx:expect("v1' = (1, 1.5, 0)", ball.velocity, vec3(1, 1.5, 0), 1e-12)
        ctx:expect("the floor does not move", floor.velocity, vec3(0, 0, 0))
        local J1d, v_after = collide.impulse_1d(m1, 3, math.huge, 0, e)
        ctx:show("the same along the normal with impulse_1d(2, 3, math.huge, 0, 0.5): J", J1d)
        ctx:expect("impulse_1d with an immovable body: J = 9", J1d, 9, 1e-12)
        ctx:expect("impulse_1d: normal speed −e·3", v_after, -1.5, 1e-12)
      end,
    },
  },
}
