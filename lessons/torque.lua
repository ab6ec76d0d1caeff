-- Torque on a particle held at a distance from a pivot (001, opening section): τ = rF,
-- I = mr², α = τ/I, and the angular impulse H = ∫τ dt with ω' = ω + I⁻¹H.

local mass = 1                   -- kg
local radius = 2                 -- m, distance from the pivot
local push = math.pi             -- N, the document's force
local push_time = 1              -- s

-- A push with the same total impulse as a constant π N for 1 s, but smooth in time:
-- F(t) = (π²/2)·sin(πt) for 0 ≤ t ≤ 1 s, whose integral over the second is π N·s.
local function smooth_push(t) return math.pi ^ 2 / 2 * math.sin(math.pi * t) end

-- Moment of inertia of the particle about the pivot's z axis, from its inertia tensor.
local function moment_about_pivot(r)
  return inertia.about_axis(inertia.point(mass, vec3(r, 0, 0)), vec3(0, 0, 1))
end

-- Integrates dH/dt = τ(t) = r·F(t) over the push with ode.step (RK4), n steps.
local function angular_impulse(force, r, n)
  local h, dt = 0, push_time / n
  for i = 0, n - 1 do
    h = ode.step("rk4", function(t) return r * force(t) end, i * dt, h, dt)
  end
  return h
end

return lesson{
  id = "torque",
  title = "Torque, moment of inertia and angular impulse of one particle",
  source = "001_8a70f78e0cc79e25.txt, \"Demystifying Rotational Dynamics in Rigid Bodies\" " ..
           "(the opening section, before \"System Of Particles\")",
  steps = {
    {
      title = "Torque and the particle's resistance to turning",
      text = [[
A particle of 1 kg sits on a massless rod, 2 m from a fixed pivot, and we push it sideways
with a force of π newtons. A push this far out has a lot of leverage: the turning effect,
the torque, is the force times the arm, τ = r·F = 2π N·m, and in 3D it is the cross
product r × F, pointing along the axis the push turns about.

How strongly the particle resists being turned grows with the square of its distance,
I = m·r² = 4 kg·m²: further out, the same angular acceleration α means a larger linear
acceleration r·α and so a larger force m·r·α (one factor r), and a force acting on an arm
r takes r times as much torque (the other). rigidlab's inertia.point gives the
particle's whole tensor about the pivot, and inertia.about_axis reads its moment about z.
Their ratio is the angular acceleration, α = τ/I = 2π/4 = π/2 rad/s², the document's value.

A units slip in the document: it writes the force as "F = π rad/s²". A force is measured
in newtons; π/2 rad/s² is the resulting angular acceleration.]],
      formula = "τ = r × F  (τ = r·F when r ⟂ F),   I = m·r²,   α = I⁻¹·τ = rF/(mr²)",
      run = function(ctx)
        local r = vec3(radius, 0, 0)
        local force = vec3(0, push, 0)
        local torque = r:cross(force)
        ctx:show("r (m)", r)
        ctx:show("F (N)", force)
        ctx:show("τ = r × F (N·m)", torque)
        ctx:expect("τ = r·F = 2π about z", torque, vec3(0, 0, 2 * math.pi))
        local tensor = inertia.point(mass, r)
        ctx:show("inertia tensor about the pivot m((r·r)E − r⊗r) (kg·m²)", tensor)
        local I = moment_about_pivot(radius)
        ctx:show("I about z (kg·m²)", I)
        ctx:expect("I = m·r² = 1 · 2²", I, 4)
        ctx:show("α = τ/I (rad/s²)", torque.z / I)
        ctx:expect("α = π/2, the document's value", torque.z / I, math.pi / 2)
        ctx:say("(The tensor's xx entry is 0: a point on the x axis does not resist spinning")
        ctx:say("about x at all, which is why a lone particle's tensor cannot be inverted.)")
      end,
    },
    {
      title = "Angular impulse: what a push leaves behind",
      text = [[
A real push does not jump to full strength and stop dead; its force varies over time. What
counts for the final spin is the total, the angular impulse H = ∫τ dt, just as a linear
impulse ∫F dt sets the change of momentum. The spin then changes by ω' = ω + I⁻¹·H.

We compare two pushes that deliver the same total: π N held for 1 s, and a smooth bump
F(t) = (π²/2)·sin(πt) that rises and falls over the same second. rigidlab's ode.step
integrates dH/dt = r·F(t) with RK4 in 20 steps. For the constant push RK4 is exact; for
the bump it is Simpson's rule, whose error falls with the fourth power of the step and is
about 1e-6 here, so that check allows 1e-5. Both end at H = 2π N·m·s, and the particle,
starting at rest, turns at ω' = 2π/4 = π/2 rad/s.]],
      formula = "H = ∫ τ(t) dt,   ω' = ω + I⁻¹·H",
      run = function(ctx)
        local I = moment_about_pivot(radius)
        local constant = angular_impulse(function() return push end, radius, 20)
        local smooth = angular_impulse(smooth_push, radius, 20)
        ctx:show("H, constant π N for 1 s (N·m·s)", constant)
        ctx:show("H, smooth bump (N·m·s)", smooth)
        ctx:expect("H = r·π·1 s = 2π (constant push)", constant, 2 * math.pi)
        ctx:expect("H = 2π (smooth bump, Simpson error ~1e-6)", smooth, 2 * math.pi,
                   {abs = 1e-5})
        local omega0 = 0
        ctx:show("ω' = ω + H/I (rad/s)", omega0 + constant / I)
        ctx:expect("ω' = π/2", omega0 + constant / I, math.pi / 2)
      end,
    },
    {
      title = "Half the angle, the same arc",
      text = [[
Now compare with the same push on a particle only 1 m from the pivot. There the torque is
half as big but the moment of inertia four times smaller, so it ends up spinning twice as
fast: ω' = π rad/s instead of π/2. Yet both particles move along their circles at the
same speed, ω'·r = π m/s, because the push gave each the same linear momentum,
F·t = π kg·m/s, whatever the radius.

So in the second after the push the outer particle turns only half the angle, π/2 rad
against π, but covers the same arc, r·θ = π m. We let motion.simulate coast the angle for
that second (no torque, so the rate stays fixed) and read off angle and arc.]],
      formula = "ω' = rFt/(mr²) = Ft/(mr),   tangential speed ω'·r = Ft/m,   arc L = r·θ",
      run = function(ctx)
        local rows = {}
        for _, r in ipairs({1, 2}) do
          local spin = angular_impulse(function() return push end, r, 20) /
                       moment_about_pivot(r)
          local coast = motion.simulate{method = "rk4", accel = function() return 0 end, x0 = 0,
                                        v0 = spin, dt = 0.1, steps = 10}
          local angle = coast.x[#coast.x]
          rows[#rows + 1] = {r, moment_about_pivot(r), spin, spin * r, angle, r * angle}
          ctx:expect(string.format("r = %g: ω' = π/r", r), spin, math.pi / r)
          ctx:expect(string.format("r = %g: arc after 1 s = π", r), r * angle, math.pi)
        end
        ctx:table({"r (m)", "I (kg·m²)", "ω' (rad/s)", "ω'·r (m/s)", "θ after 1 s (rad)",
                   "arc r·θ (m)"}, rows)
      end,
    },
  },
}
