-- A spinning top on a ball joint (001 "Torque-free precession" and its reference on gyroscopic
-- precession; 002 "Newton-Euler Equations"): launched with the right sideways rate it precesses
-- with its axis level at Ω = mgl/(I₃ω₃); let go without it, the axis dips and bobs (nutation)
-- between two heights and at a period that the heavy top's conservation laws give in closed
-- form (a cubic's roots and the elliptic integral K, computed here), while it precesses on
-- average at about the same Ω.

local mass = 1            -- kg
local R, h = 0.1, 0.02    -- m, the disc: radius and thickness (its axis is the top's axis)
local arm = 0.1           -- m, from the pivot to the disc's centre, along the axis
local spin = 100          -- rad/s about the axis
local g = 9.81
local dt = 0.001          -- s
local seconds = 2

local I1 = mass * (3 * R ^ 2 + h ^ 2) / 12        -- about a diameter (000's cylinder)
local I3 = mass * R ^ 2 / 2                        -- about the axis
local I1p = I1 + mass * arm ^ 2                    -- about a line through the pivot ⟂ axis
local mgl = mass * g * arm
local L3 = I3 * spin                               -- angular momentum along the axis
local Omega = mgl / L3                             -- precession rate, level axis

-- Complete elliptic integral of the first kind by the arithmetic-geometric mean.
local function K(k)
  local a, b = 1, math.sqrt(1 - k * k)
  while math.abs(a - b) > 1e-15 * a do a, b = (a + b) / 2, math.sqrt(a * b) end
  return math.pi / (2 * a)
end

-- The heavy symmetric top let go at rest with its axis level (u = cos of the axis' angle from
-- the upward vertical, u₀ = 0) and spin ω₃. Energy and the two conserved momenta (about the
-- vertical and about the axis) leave u̇² = (u₀ − u)·[a(1 − u²) − b(u₀ − u)] with
-- a = 2mgl/I₁', b = (L₃/I₁')², so u swings between u₀ and the root u₁ < u₀ of the bracket; its
-- other root u₂ > 1 is out of reach. The nutation period is 2∫ du/√(u̇²) over [u₁, u₀].
local a_coef, b_coef = 2 * mgl / I1p, (L3 / I1p) ^ 2
local u0 = 0
local disc = math.sqrt(b_coef ^ 2 + 4 * a_coef * (a_coef - b_coef * u0))
local u1 = (b_coef - disc) / (2 * a_coef)
local u2 = (b_coef + disc) / (2 * a_coef)

-- With u = u₁ + (u₀ − u₁)sin²s the integrals have smooth integrands on s ∈ [0, π/2]:
-- dt = 2 ds / √(a(u₂ − u)), and the precession rate is φ̇ = (L₃/I₁')(u₀ − u)/(1 − u²).
local function over_a_swing(f)
  local n, sum = 400, 0                      -- Simpson's rule, n even
  for i = 0, n do
    local s = (math.pi / 2) * i / n
    local u = u1 + (u0 - u1) * math.sin(s) ^ 2
    local weight = (i == 0 or i == n) and 1 or (i % 2 == 1 and 4 or 2)
    sum = sum + weight * f(u) * 2 / math.sqrt(a_coef * (u2 - u))
  end
  return 2 * sum * (math.pi / 2) / (3 * n)   -- ×2: down and up again
end
local T_nut_K = 4 * K(math.sqrt((u0 - u1) / (u2 - u1))) / math.sqrt(a_coef * (u2 - u1))
local T_nut_quad = over_a_swing(function() return 1 end)
local phi_per_swing = over_a_swing(function(u) return math.sqrt(b_coef) * (u0 - u) / (1 - u * u) end)

local level = quat.axis_angle(vec3(0, 1, 0), math.pi / 2)   -- turns the disc's z axis to +x

local function top_on_ball_joint(angular_velocity, velocity)
  local w = world{integrator = "rk4", substeps = 4}
  local top = w:add(body{mass = mass, inertia = inertia.solid_cylinder(mass, R, h),
                         position = vec3(arm, 0, 0), orientation = level,
                         angular_velocity = angular_velocity, velocity = velocity})
  local joint = w:add_joint{type = "ball", a = top, anchor = vec3(0, 0, 0)}
  return w, top, joint
end

local function axis_of(top) return top.orientation:rotate(vec3(0, 0, 1)) end

-- Runs the top; returns the time, elevation (degrees) and unwrapped azimuth φ (about +y,
-- from +x toward −z) of its axis at every step, and the largest joint error.
local function spin_it(w, top, joint)
  local t, elev, phi, worst = {0}, {0}, {0}, 0
  for i = 1, math.floor(seconds / dt + 0.5) do
    w:step(dt)
    local e = axis_of(top)
    local p = math.atan(-e.z, e.x)
    while p < phi[i] - math.pi do p = p + 2 * math.pi end
    t[i + 1], elev[i + 1], phi[i + 1] = w.time, math.deg(math.asin(e.y)), p
    worst = math.max(worst, (joint:error()))
  end
  return t, elev, phi, worst
end

-- The local minima of a list (by a parabola through three samples): times and values.
local function minima(t, y)
  local times, values = {}, {}
  for i = 2, #y - 1 do
    if y[i] < y[i - 1] and y[i] <= y[i + 1] then
      local d = y[i - 1] - 2 * y[i] + y[i + 1]
      local shift = (y[i - 1] - y[i + 1]) / (2 * d)
      times[#times + 1] = t[i] + shift * (t[i + 1] - t[i])
      values[#values + 1] = y[i] - (y[i - 1] - y[i + 1]) ^ 2 / (8 * d)
    end
  end
  return times, values
end

return lesson{
  id = "gyroscope",
  title = "A top on a ball joint: precession and nutation",
  source = "001_8a70f78e0cc79e25.txt, \"Torque-free precession\" (its reference [4]); " ..
           "002_5497adede943f513.txt, \"Newton-Euler Equations\"",
  steps = {
    {
      title = "The top and its numbers",
      text = [[
A disc of 1 kg, radius 0.1 m and thickness 0.02 m sits on an axle whose end rests in a ball
joint (000's spherical pair: the end stays put, all three rotations are free). The disc's
centre is 0.1 m from the pivot along the axle, which starts level, along +x (the disc's
own z axis turned 90° about y). It spins at 100 rad/s about the axle.

The moments: about the axle I₃ = mR²/2, about a diameter I₁ = m(3R² + h²)/12 (000 "Inertia
of primitive shapes"), and about a line through the pivot square to the axle, by the
parallel-axis theorem, I₁' = I₁ + ml². Gravity pulls at the centre with the torque mgl
about the pivot; the spin carries the angular momentum L₃ = I₃ω₃ along the axle.]],
      formula = "I₃ = mR²/2,  I₁' = m(3R² + h²)/12 + ml²,  L₃ = I₃ω₃,  torque mgl",
      run = function(ctx)
        local I = inertia.solid_cylinder(mass, R, h)
        ctx:show("disc: inertia about its centre (kg·m², axle = z)", I)
        ctx:expect("I₁ = m(3R² + h²)/12", I:get(1, 1), I1)
        ctx:expect("I₃ = mR²/2", I:get(3, 3), I3)
        ctx:show("I₁' about the pivot (kg·m²)", I1p)
        ctx:show("mgl (N·m)", mgl)
        ctx:show("L₃ = I₃ω₃ (kg·m²/s)", L3)
      end,
    },
    {
      title = "Steady precession: the axle stays level",
      text = [[
002 "Newton-Euler Equations" writes the rotation as τ = ω × Iω + Iω̇: torque changes the
angular momentum, dL/dt = τ. Gravity's torque mgl is horizontal and square to the axle, so
it does not speed the spin up; it turns L sideways. If the axle turns about the vertical at
the rate Ω, the spin's momentum L₃ turns with it and changes at the rate Ω·L₃ in exactly the
torque's direction. So with the axle level, Ω·I₃ω₃ = mgl: Ω = mgl/(I₃ω₃) is exact there,
not an approximation. Launched with that sideways rate (ω = (ω₃, Ω, 0), and the centre's
velocity ω × r to match the joint), the top circles with its axle level. The run is 2 s
in steps of 1 ms, each in 4 RK4 substeps (the disc turns 0.025 rad per substep); an axle that
turns 1.96 rad/s ends 3.92 rad around.]],
      formula = "Ω·I₃ω₃ = mgl  ⇒  Ω = mgl / (I₃ω₃)",
      run = function(ctx)
        ctx:show("Ω = mgl/(I₃ω₃) (rad/s)", Omega)
        local omega = vec3(spin, Omega, 0)
        local velocity = omega:cross(vec3(arm, 0, 0))
        ctx:show("initial ω (rad/s)", omega)
        ctx:show("initial velocity of the centre (m/s)", velocity)
        local w, top, joint = top_on_ball_joint(omega, velocity)
        local t, elev, phi, worst = spin_it(w, top, joint)
        local lowest, highest = 0, 0
        for _, e in ipairs(elev) do lowest, highest = math.min(lowest, e), math.max(highest, e) end
        local rate = phi[#phi] / t[#t]
        ctx:show("axle elevation: lowest, highest (°)", {lowest, highest})
        ctx:show("azimuth after 2 s (rad)", phi[#phi])
        ctx:show("measured precession rate (rad/s)", rate)
        ctx:show("largest joint position error (m)", worst)
        ctx:expect("precession rate = mgl/(I₃ω₃)", rate, Omega,
                   {rel = 1e-4, reason = "RK4 at 0.25 ms, with the joint"})
        ctx:expect_range("the axle stays level (°)", math.max(-lowest, highest), nil, 0.01)
      end,
    },
    {
      title = "Let go without precession: nutation",
      text = [[
Let go with the spin alone, the top first falls: nothing turns its momentum sideways yet.
The falling itself is a rotation about a horizontal line, and the gyroscopic coupling turns
it into the sideways swing; the axle dips, swings back up to level, and bobs so, while
precessing on average at nearly the rate above.

How low it dips follows from three conservation laws: the energy, the momentum about the
vertical (gravity's torque is horizontal) and the momentum L₃ along the axle (the torque is
square to it). With u the height of the axle's unit vector, they give
u̇² = (u₀ − u)·[a(1 − u²) − b(u₀ − u)], a = 2mgl/I₁', b = (L₃/I₁')², u₀ = 0. The axle turns
around where the bracket vanishes: at u₁ = (b − √(b² + 4a²))/(2a). The time for a
dip and back is 2∫du/√(u̇²) from u₁ to u₀, an elliptic integral: T = 4K(k)/√(a(u₂ − u₁)) with
k² = (u₀ − u₁)/(u₂ − u₁) and u₂ the bracket's other root; we also compute it by Simpson's
rule after the change u = u₁ + (u₀ − u₁)sin²s that removes the square-root ends. For a fast
top these are close to the textbook approximations: a dip of 2mglI₁'/L₃² and a period of
2πI₁'/L₃.

The world (RK4, 4 substeps of 0.25 ms) follows the closed form to a few parts in 10⁴, but
not forever: a frictionless top would nutate for ever, while the world's dips shrink by
about 1 % over the 2 s (compare the first and the last): the joint's rows take out a little
of the bobbing each substep. Smaller substeps shrink that loss.]],
      formula = "u̇² = (u₀ − u)(a(1 − u²) − b(u₀ − u)),   T_nut = 4K(k)/√(a(u₂ − u₁))",
      run = function(ctx)
        ctx:show("a = 2mgl/I₁' (1/s²)", a_coef)
        ctx:show("b = (L₃/I₁')² (1/s²)", b_coef)
        ctx:show("roots u₁, u₂", {u1, u2})
        ctx:show("lowest axle elevation, asin u₁ (°)", math.deg(math.asin(u1)))
        ctx:show("  fast-top approximation 2mglI₁'/L₃² (°)", math.deg(2 * mgl * I1p / L3 ^ 2))
        ctx:show("nutation period by K (s)", T_nut_K)
        ctx:show("  by Simpson's rule (s)", T_nut_quad)
        ctx:show("  fast-top approximation 2πI₁'/L₃ (s)", 2 * math.pi * I1p / L3)
        ctx:expect("the two periods agree", T_nut_quad, T_nut_K,
                   {rel = 1e-10, reason = "Simpson with 400 panels on a smooth integrand"})
        local mean_rate = phi_per_swing / T_nut_K
        ctx:show("mean precession rate, exact (rad/s)", mean_rate)

        local w, top, joint = top_on_ball_joint(vec3(spin, 0, 0), vec3(0, 0, 0))
        local t, elev, phi, worst = spin_it(w, top, joint)
        local times, lows = minima(t, elev)
        local deepest = math.huge
        for _, v in ipairs(lows) do deepest = math.min(deepest, v) end
        local measured_T = (times[#times] - times[1]) / (#times - 1)
        local highest = -math.huge
        for i = 2, #elev do highest = math.max(highest, elev[i]) end
        local first, last = math.floor(times[1] / dt + 0.5), math.floor(times[#times] / dt + 0.5)
        local measured_rate = (phi[last + 1] - phi[first + 1]) / (t[last + 1] - t[first + 1])
        ctx:plot{{x = t, y = elev, label = "axle elevation"}, title = "Nutation: the axle dips and bobs",
                 xlabel = "t (s)", ylabel = "°", height = 10}
        ctx:table({"", "world", "closed form"},
                  {{"lowest elevation (°)", deepest, math.deg(math.asin(u1))},
                   {"first dip, last dip (°)", string.format("%.4f, %.4f", lows[1], lows[#lows]),
                    math.deg(math.asin(u1))},
                   {"highest elevation (°)", highest, 0},
                   {"nutation period (s)", measured_T, T_nut_K},
                   {"mean precession (rad/s)", measured_rate, mean_rate}})
        ctx:show("dips timed", #times)
        ctx:show("largest joint position error (m)", worst)
        local why = "the world damps the nutation: its dips shrink by about 1 % in 2 s"
        ctx:expect("lowest elevation", deepest, math.deg(math.asin(u1)), {rel = 2e-3, reason = why})
        ctx:expect("nutation period", measured_T, T_nut_K, {rel = 1e-3, reason = why})
        ctx:expect("mean precession rate", measured_rate, mean_rate, {rel = 1e-3, reason = why})
      end,
    },
  },
}
