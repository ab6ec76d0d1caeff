-- A head-on elastic collision on a line (001 "System Of Particles", Appendix C): a 1 kg
-- particle at 2 m/s hits a resting 1 kg particle (J = 2, it stops, the other leaves at 2 m/s),
-- then the resting 4 kg body of four particles (J = 3.2, it bounces back at -1.2, the body
-- leaves at 0.8 m/s). Momentum and kinetic energy are the same before and after.

local speed_a = 2        -- m/s, the striking particle
local speed_b = 0        -- m/s, the target at rest
local elastic = 1        -- restitution e = 1: no kinetic energy lost
local corners = {vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, 0), vec3(0.5, 0.5, 0), vec3(-0.5, 0.5, 0)}

local function momentum(ma, va, mb, vb) return ma * va + mb * vb end
local function kinetic_energy(ma, va, mb, vb) return 0.5 * ma * va ^ 2 + 0.5 * mb * vb ^ 2 end

-- Appendix C's result from the two conservation laws alone, without any impulse:
-- va' = (ma − mb)/(ma + mb)·va + 2mb/(ma + mb)·vb, and vb' = va + va' − vb.
local function conservation_velocities(ma, va, mb, vb)
  local va_after = (ma - mb) / (ma + mb) * va + 2 * mb / (ma + mb) * vb
  return va_after, va + va_after - vb
end

-- Prints J, va', vb', the momentum and energy before and after, and checks them.
local function collide_and_check(ctx, mb, want)
  local ma = 1
  local J, va_after, vb_after = collide.impulse_1d(ma, speed_a, mb, speed_b, elastic)
  ctx:show("J (N·s)", J)
  ctx:show("va' = va − J/ma (m/s)", va_after)
  ctx:show("vb' = vb + J/mb (m/s)", vb_after)
  ctx:expect("J", J, want.J)
  ctx:expect("va'", va_after, want.va)
  ctx:expect("vb'", vb_after, want.vb)
  local p_before, p_after = momentum(ma, speed_a, mb, speed_b), momentum(ma, va_after, mb, vb_after)
  local t_before = kinetic_energy(ma, speed_a, mb, speed_b)
  local t_after = kinetic_energy(ma, va_after, mb, vb_after)
  ctx:table({"", "momentum (kg·m/s)", "kinetic energy (J)"},
            {{"before", p_before, t_before}, {"after", p_after, t_after}})
  ctx:expect("momentum conserved", p_after, p_before)
  ctx:expect("kinetic energy conserved", t_after, t_before)
end

return lesson{
  id = "collision-1d",
  title = "A head-on elastic collision: the impulse J",
  source = "001_8a70f78e0cc79e25.txt, \"System Of Particles\", " ..
           "\"Appendix C - Deriving Collision Impulses Using Conservation Laws Only\"",
  steps = {
    {
      title = "Equal masses swap their velocities",
      text = [[
When two bodies collide, a very large force acts for a very short time. We do not need to
know its shape, only its total effect, the impulse J = ∫F dt (N·s): the change of momentum
it causes. Newton's third law says each body receives the same impulse with opposite sign,
so whatever b gains, a loses, and the total momentum cannot change.

The formula asks only for the closing speed vb − va and the two inverse masses. The
factor 2 is 1 + e with restitution e = 1: a perfectly elastic bounce. Let a 1 kg particle
at 2 m/s hit a resting 1 kg particle: J = −2·(0 − 2)/(1 + 1) = 2 N·s. The first one stops
dead and the second leaves at exactly 2 m/s, the billiard-ball swap of 001's video.]],
      formula = "J = −(1+e)(vb − va)/(1/ma + 1/mb),   va' = va − J/ma,   vb' = vb + J/mb",
      run = function(ctx)
        collide_and_check(ctx, 1, {J = 2, va = 0, vb = 2})
      end,
    },
    {
      title = "Against a body of four particles",
      text = [[
Now the target is the square of four 1 kg particles tied by rigid rods (see the
system-momentum lesson). Hit through its centre of mass along the line, it reacts exactly
like one 4 kg particle, so mb = 4 and 1/mb = 0.25. The impulse grows to
J = −2·(0 − 2)/(1 + 0.25) = 3.2 N·s; the heavy body leaves at 3.2/4 = 0.8 m/s, and the light
particle, having given away more momentum than it had, bounces back at 2 − 3.2 = −1.2 m/s.

A slip in 001: for both targets it writes vb' = vb − J/mb and then evaluates 0 + 2/1 = 2
and 0 + 3.2/4 = 0.8. The numbers are right, the sign in the formula is not: b receives +J (Newton's third law, Ja = −Jb), so
vb' = vb + J/mb. With the minus sign as printed, b would move at −0.8 m/s, into a.]],
      formula = "J = −2·(0 − 2)/(1/1 + 1/4) = 3.2\n" ..
                "va' = 2 − 3.2/1 = −1.2,   vb' = 0 + 3.2/4 = 0.8",
      run = function(ctx)
        collide_and_check(ctx, 4, {J = 3.2, va = -1.2, vb = 0.8})
        ctx:show("vb' with the document's printed sign, vb − J/mb (m/s)", speed_b - 3.2 / 4)
      end,
    },
    {
      title = "The same answer from the conservation laws alone",
      text = [[
Appendix C derives the impulse from two facts: total momentum is kept, and, for an elastic
collision, total kinetic energy is kept. Dividing the energy equation by the momentum
equation leaves va + va' = vb + vb', and solving gives va' directly, without ever naming J.
These closed forms are independent of the impulse formula, so they make a good check of
collide.impulse_1d. They agree for both targets, and for any other mass as well: try a
heavy target of 1000 kg and the particle comes back at almost its full speed.

A sign to watch in Appendix C: it defines an impulse as the change of momentum,
J = mv' − mv, but a few lines later writes Ja = ΔPa = ma·va − ma·va', which is minus
that change. The J of the impulse formula is the momentum a gives away, which is what b
receives: ma(va − va') = 1·(2 − (−1.2)) = 3.2 = mb(vb' − vb) = 4·0.8. As a change of
a's momentum it is −3.2.]],
      formula = "va' = (ma − mb)/(ma + mb)·va + 2mb/(ma + mb)·vb,   vb' = va + va' − vb",
      run = function(ctx)
        local rows = {}
        for _, mb in ipairs({1, 4, 1000}) do
          local _, va_after, vb_after = collide.impulse_1d(1, speed_a, mb, speed_b, elastic)
          local want_a, want_b = conservation_velocities(1, speed_a, mb, speed_b)
          rows[#rows + 1] = {mb, va_after, want_a, vb_after, want_b}
          ctx:expect("mb = " .. mb .. ": va' from conservation", va_after, want_a)
          ctx:expect("mb = " .. mb .. ": vb' from conservation", vb_after, want_b)
        end
        ctx:table({"mb (kg)", "va' impulse", "va' conservation", "vb' impulse",
                   "vb' conservation"}, rows)
        local J, va_after, vb_after = collide.impulse_1d(1, speed_a, 4, speed_b, elastic)
        ctx:show("J from the formula (N·s)", J)
        ctx:show("a's change of momentum ma(va' − va) (kg·m/s)", 1 * (va_after - speed_a))
        ctx:show("b's change of momentum mb(vb' − vb) (kg·m/s)", 4 * (vb_after - speed_b))
        ctx:expect("J = what b receives, mb(vb' − vb) = 4·0.8", 4 * (vb_after - speed_b), 3.2)
        ctx:expect("a's change of momentum = −J = 1·(−1.2 − 2)", 1 * (va_after - speed_a), -3.2)
      end,
    },
    {
      title = "The square as a rigid body",
      text = [[
Finally the same collision between real rigid bodies: a 1 kg ball of radius 0.05 m,
centred at x = −0.55 m and moving at 2 m/s along x, and the square built by inertia.points
from its four particles, at rest. collide.resolve applies the impulse at the
contact point, here on the line through the square's centre, with the normal along x from
the ball to the square. It finds the same J = 3.2 N·s, the same velocities −1.2 and
0.8 m/s, and the square does not start to turn, since the blow passes through its centre
of mass.]],
      formula = "J n on b, −J n on a at the contact point, with n from a to b",
      run = function(ctx)
        local list = {}
        for i, corner in ipairs(corners) do list[i] = {mass = 1, pos = corner} end
        local mass, com, inertia_com = inertia.points(list)
        local square = body{mass = mass, inertia = inertia_com, position = com}
        local ball = body.sphere{mass = 1, radius = 0.05, position = vec3(-0.55, 0, 0),
                                 velocity = vec3(speed_a, 0, 0)}
        local J = collide.resolve(ball, square, {point = vec3(-0.5, 0, 0), normal = vec3(1, 0, 0),
                                                 restitution = elastic})
        ctx:show("J (N·s)", J)
        ctx:show("ball: v' (m/s)", ball.velocity)
        ctx:show("square: v' (m/s)", square.velocity)
        ctx:show("square: ω' (rad/s)", square.angular_velocity)
        ctx:expect("J = 3.2", J, 3.2, 1e-12)
        ctx:expect("ball: v' = −1.2", ball.velocity, vec3(-1.2, 0, 0), 1e-12)
        ctx:expect("square: v' = 0.8", square.velocity, vec3(0.8, 0, 0), 1e-12)
        ctx:expect("square: no rotation", square.angular_velocity, vec3(0, 0, 0), {abs = 1e-12})
      end,
    },
  },
}
