-- A particle on a rigid rod (001, the opening section before "System Of Particles"): a ball tied
-- by a massless rigid rod (a distance joint) to an immovable one is struck square to the rod by a
-- third ball of the same mass. It goes round a circle at the striker's speed, ω = ‖v‖/‖r‖, the
-- rod pulling it inward by m·v²/r; and, as the article notes for its particle simulation, a
-- velocity-level solver loses energy at large steps: shown for Δt from 1/60 to 1/1000 s with
-- both solvers.

local mass = 1            -- kg, the green and the blue ball
local radius = 0.1        -- m, each ball
local r = 2               -- m, the rod
local speed = 3           -- m/s, the blue ball's
local yellow_at = vec3(0, 0, 0)
local green_at = vec3(r, 0, 0)
local blue_at = vec3(r, -1, 0)

local omega = speed / r                       -- rad/s, once the green ball goes round
local revolution = 2 * math.pi / omega        -- s

-- Green tied to the immovable yellow ball; blue coming up square to the rod. No gravity (the
-- article's scene is seen from above). Bounces are elastic and frictionless.
local function scene(solver, substeps)
  local w = world{gravity = vec3(0, 0, 0), solver = solver, substeps = substeps}
  local yellow = w:add(body{static = true, position = yellow_at})
  local green = w:add(body.sphere{mass = mass, radius = radius, position = green_at,
                                  restitution = 1, friction = 0})
  local blue = w:add(body.sphere{mass = mass, radius = radius, position = blue_at,
                                 velocity = vec3(0, speed, 0), restitution = 1, friction = 0})
  local rod = w:add_joint{type = "distance", a = green, a_point = vec3(0, 0, 0),
                          b = yellow, b_point = vec3(0, 0, 0)}
  return w, green, blue, rod
end

-- Steps at dt until the strike is over (the blue ball no longer moves toward the green one),
-- takes the blue ball out (on its circle the green ball would meet it again), then runs one
-- revolution. Returns the speed after the strike, the blue ball's velocity, and after the
-- revolution the kinetic energy over ½mv² (and its largest distance from 1 on the way), the
-- largest |‖x‖ − r| and the last step's rod impulse.
local function strike_and_turn(solver, dt, substeps)
  local w, green, blue, rod = scene(solver, substeps)
  repeat w:step(dt) until green.velocity:norm() > 0.5 * speed or w.time > 2
  local after = green.velocity:norm()
  local blue_after = blue.velocity
  w:remove(blue)
  local struck_at, worst, deviation = w.time, 0, 0
  local t, energy = {}, {}
  while w.time < struck_at + revolution - 1e-9 do
    w:step(dt)
    worst = math.max(worst, math.abs(green.position:norm() - r))
    t[#t + 1], energy[#energy + 1] = w.time - struck_at, green:kinetic_energy() / (0.5 * mass * speed ^ 2)
    deviation = math.max(deviation, math.abs(energy[#energy] - 1))
  end
  return {speed = after, blue = blue_after, kept = energy[#energy], deviation = deviation, drift = worst,
          impulse = rod.impulse, green = green, t = t, energy = energy}
end

-- The article's plain particle scheme, by hand: `steps` steps of dt for a particle already
-- going round at `speed` on the circle of radius r. Each step removes the velocity's part
-- along the rod, moves the particle straight, and puts it back on the circle. Returns the
-- kinetic energy kept, as a fraction.
local function plain_projection(dt, steps)
  local x, v = green_at, vec3(0, speed, 0)
  for _ = 1, steps do
    local n = x / x:norm()
    v = v - n * n:dot(v)
    x = x + v * dt
    x = x * (r / x:norm())
  end
  return v:dot(v) / speed ^ 2
end

return lesson{
  id = "rigid-rod",
  title = "A ball on a rigid rod: struck, it goes round at the striker's speed",
  source = "001_8a70f78e0cc79e25.txt, opening section (before \"System Of Particles\")",
  steps = {
    {
      title = "The scene",
      text = [[
001 opens with two particles joined by a massless rigid rod, one of them immovable (infinite
mass). We take a yellow immovable body at the origin, a green ball of 1 kg and radius 0.1 m
at (2, 0, 0) on a rod of 2 m (w:add_joint{type = "distance"}, the rod between the two
centres), and a blue ball of the same mass and size at (2, −1, 0) coming at 3 m/s along +y,
square to the rod. No gravity: the article's scene is seen from above. The bounce is
elastic (restitution 1, no friction).

At the instant of the strike the rod cannot help or hinder: it can only pull along its own
length, which is square to the blow. So this is the collision of 001 "System Of Particles"
between equal masses: the impulse J = 2·m_a·m_b·v/(m_a + m_b) = m·v = 3 N·s, the blue ball
stops and the green one leaves at 3 m/s.]],
      formula = "J = (1 + e)·v / (1/m_a + 1/m_b),   v_blue' = v − J/m,   v_green' = J/m",
      run = function(ctx)
        local J = (1 + 1) * speed / (1 / mass + 1 / mass)
        ctx:show("J (N·s)", J)
        local res = strike_and_turn("soft_step", 1 / 600, 1)
        ctx:show("green after the strike: speed (m/s)", res.speed)
        ctx:show("blue after the strike (m/s)", res.blue)
        ctx:expect("green leaves at J/m", res.speed, J / mass,
                   {rel = 1e-6, reason = "the rod's pull during the strike step, of order ωΔt²"})
        ctx:expect("blue stops", res.blue:norm(), 0,
                   {abs = 1e-9, reason = "the bounce, to rounding"})
      end,
    },
    {
      title = "Round the circle: ω = ‖v‖/‖r‖",
      text = [[
The rod keeps the green ball at 2 m from the yellow one, so the ball goes round a circle.
Nothing pushes it along the circle, so its speed stays 3 m/s: as the article says, it moves
"at the speed of the blue particle", only not in a straight line. Its angular velocity
about the yellow ball is ω = ‖v‖/‖r‖ = 1.5 rad/s, or as a vector ω⃗ = r × v/‖r‖², along +z,
and one revolution takes 2π/ω = 4.19 s. The rod now does work-free pulling: the inward
force m·v²/r = 4.5 N, so over a step Δt it gives the ball the impulse m·v²·Δt/r
(rod.impulse, toward the yellow ball). We check these in small steps, Δt = 1/1000 s, after
one revolution; the chart shows the kinetic energy over that revolution (its scale is parts
per million).]],
      formula = "ω = ‖v‖/‖r‖,  ω⃗ = r × v / ‖r‖²,  rod impulse per step = m·v²·Δt/r",
      run = function(ctx)
        local dt = 1 / 1000
        local res = strike_and_turn("soft_step", dt, 1)
        local g = res.green
        local w_vec = g.position:cross(g.velocity) / g.position:norm() ^ 2
        ctx:show("ω = ‖v‖/‖r‖ (rad/s)", omega)
        ctx:show("after one revolution: position (m)", g.position)
        ctx:show("velocity (m/s)", g.velocity)
        ctx:show("r × v/‖r‖² (rad/s)", w_vec)
        ctx:show("the ball's own spin (rad/s)", g.angular_velocity)
        ctx:show("rod impulse of the last step (N·s)", res.impulse)
        ctx:plot{{x = res.t, y = res.energy, label = "½mv² / ½m·(3 m/s)²"}, title = "Energy kept",
                 xlabel = "t after the strike (s)", ylabel = "fraction", height = 8}
        local why = "the steps' error, of order (ωΔt)² = 2.25e-6"
        ctx:expect("ω⃗ = (0, 0, ‖v‖/‖r‖)", w_vec, vec3(0, 0, omega), {rel = 1e-5, reason = why})
        ctx:expect("|rod impulse| = m·v²·Δt/r", res.impulse:norm(), mass * speed ^ 2 * dt / r,
                   {rel = 1e-5, reason = why})
        ctx:expect_range("the ball stays on the circle (m)", res.drift, nil, 1e-4)
      end,
    },
    {
      title = "Large steps lose energy, unless the rod looks ahead",
      text = [[
001 notes that its particle simulation "was losing some bits of energy after the collision",
less with smaller steps. Here is why, in the plainest velocity-level scheme: each step makes
the ball's velocity square to the rod as the rod points now, then moves the ball in a
straight line, and puts it back on the circle. The rod has turned by atan(vΔt/r) meanwhile,
so the next step takes away the part of the velocity that now runs along it: v² becomes
v²/(1 + (vΔt/r)²), that is, 1/v² grows by (Δt/r)² every step. After N steps (the first loses
nothing: the ball starts square to the rod) the energy kept is 1/(1 + (N − 1)(ωΔt)²), with
ω = v/r at the start; over one revolution, N ≈ 2π/(ωΔt), that is about 1/(1 + 2π·ωΔt): a loss
proportional to Δt, 14 % at 60 Hz. We run that scheme by hand (a few lines of Lua) and find
the formula.

rigidlab's rod does better: it asks for the velocity that puts the ball back at the rod's
length at the END of the step (SHAKE's condition, which the engine's solver uses for every
equality row), not the one square to the rod at its start. Such a scheme is symplectic: its
energy wobbles by a small amount of order (ωΔt)² but does not drain. The table has the
energy kept after one revolution by the hand-written plain scheme, by the formula, and the
largest energy error over the revolution in the world, with both solvers (SI for
sequential_impulses).]],
      formula = "plain projection: 1/v²ₖ₊₁ = 1/v²ₖ + (Δt/r)²\n" ..
                "                  ⇒  kept = 1/(1 + (N − 1)(ωΔt)²)\n" ..
                "rigidlab: |ΔE/E| = O((ωΔt)²)",
      run = function(ctx)
        local rows, worst_ratio = {}, 0
        for _, hz in ipairs{60, 120, 240, 500, 1000} do
          local dt = 1 / hz
          local steps = math.floor(revolution / dt + 0.5)
          local plain = plain_projection(dt, steps)
          local predicted = 1 / (1 + (steps - 1) * (omega * dt) ^ 2)
          local soft = strike_and_turn("soft_step", dt, 1)
          local si = strike_and_turn("sequential_impulses", dt, 1)
          rows[#rows + 1] = {hz, string.format("%.10f", plain), string.format("%.10f", predicted),
                             string.format("%.3g", soft.deviation), string.format("%.3g", si.deviation)}
          ctx:expect(string.format("%d Hz: the plain scheme keeps 1/(1 + (N − 1)(ωΔt)²)", hz),
                     plain, predicted, 1e-12)
          worst_ratio = math.max(worst_ratio, soft.deviation / (omega * dt) ^ 2,
                                 si.deviation / (omega * dt) ^ 2)
        end
        ctx:table({"steps/s", "plain: kept", "formula", "|ΔE/E| soft_step", "|ΔE/E| SI"}, rows)
        ctx:show("largest world |ΔE/E| / (ωΔt)²", worst_ratio)
        ctx:expect("60 Hz, plain scheme: about 1/(1 + 2π·ωΔt) kept", tonumber(rows[1][2]),
                   1 / (1 + 2 * math.pi * omega / 60),
                   {abs = 2e-3, reason = "N − 1 = 250 steps against 2π/(ωΔt) = 251.3"})
        ctx:expect_range("the world's energy error stays below (ωΔt)²", worst_ratio, nil, 1)
      end,
    },
  },
}
