-- The PD controller of 000 ("PD controller"): a wheel on a hinge driven by the hinge's motor,
-- τ = kp(θd − θ) + kv(θ̇d − θ̇), toward a target angle. Too little kv oscillates, kv at critical
-- damping settles without overshoot, much more kv crawls: each case against the closed-form
-- response of the second-order system I·θ̈ = τ, and the torque limit max_torque as a ramp.

local mass, R, thickness = 4, 0.5, 0.1   -- kg, m, m: a solid wheel, its axle along z
local I = mass * R ^ 2 / 2               -- kg·m² about the axle
local kp = 50                            -- N·m/rad
local target = 1                         -- rad
local frame = 1 / 60                     -- s
local seconds = 3
local omega_n = math.sqrt(kp / I)        -- rad/s, the undamped natural rate
local kv_critical = 2 * math.sqrt(kp * I)
local cases = {                          -- the three of 000's list, by the damping ratio ζ
  {name = "too little kv", kv = 0.1 * kv_critical},
  {name = "critical kv", kv = kv_critical},
  {name = "much more kv", kv = 6 * kv_critical},
}

-- θ(t) of I·θ̈ = kp(θd − θ) − kv·θ̇ from rest at 0: with ζ = kv/(2√(kp·I)) and ω = √(kp/I),
-- the roots of I·r² + kv·r + kp = 0 decide the shape.
local function closed_form(kv, t)
  local zeta = kv / (2 * math.sqrt(kp * I))
  if zeta < 1 then
    local wd = omega_n * math.sqrt(1 - zeta ^ 2)          -- = √(kp/I − (kv/2I)²)
    return target * (1 - math.exp(-zeta * omega_n * t) *
                     (math.cos(wd * t) + zeta * omega_n / wd * math.sin(wd * t)))
  elseif zeta == 1 then
    return target * (1 - math.exp(-omega_n * t) * (1 + omega_n * t))
  end
  local s = omega_n * math.sqrt(zeta ^ 2 - 1)
  local r1, r2 = -zeta * omega_n + s, -zeta * omega_n - s
  return target * (1 + (r2 * math.exp(r1 * t) - r1 * math.exp(r2 * t)) / (r1 - r2))
end

local function driven_wheel(kv, substeps, max_torque)
  local w = world{gravity = vec3(0, 0, 0), substeps = substeps}
  local wheel = w:add(body{mass = mass, inertia = inertia.solid_cylinder(mass, R, thickness)})
  local hinge = w:add_joint{type = "hinge", a = wheel, anchor = vec3(0, 0, 0), axis = vec3(0, 0, 1),
                            motor = {target = target, target_rate = 0, kp = kp, kv = kv,
                                     max_torque = max_torque}}
  return w, wheel, hinge
end

-- Runs `seconds`; returns the trace of θ and the largest distance from the closed form.
local function run(kv, substeps)
  local w, _, hinge = driven_wheel(kv, substeps)
  local t, theta, exact, worst = {0}, {0}, {0}, 0
  for i = 1, math.floor(seconds / frame + 0.5) do
    w:step(frame)
    t[i + 1], theta[i + 1], exact[i + 1] = w.time, hinge.angle, closed_form(kv, w.time)
    worst = math.max(worst, math.abs(theta[i + 1] - exact[i + 1]))
  end
  return t, theta, exact, worst
end

local function largest(list)
  local m = -math.huge
  for _, x in ipairs(list) do m = math.max(m, x) end
  return m
end

-- The first time a trace reaches 90 % of the target (linear interpolation between samples).
local function rise_time(t, theta)
  for i = 2, #theta do
    if theta[i] >= 0.9 * target then
      return t[i - 1] + (0.9 * target - theta[i - 1]) / (theta[i] - theta[i - 1]) * (t[i] - t[i - 1])
    end
  end
  return math.huge
end

-- The same for the closed form: the first 1 ms interval in which it reaches 90 %, then
-- bisection inside it (the oscillating case crosses 90 % many times).
local function closed_rise_time(kv)
  local lo = 0
  while closed_form(kv, lo + 1e-3) < 0.9 * target do lo = lo + 1e-3 end
  local hi = lo + 1e-3
  for _ = 1, 60 do
    local mid = (lo + hi) / 2
    if closed_form(kv, mid) >= 0.9 * target then hi = mid else lo = mid end
  end
  return hi
end

return lesson{
  id = "pd-controller",
  title = "A PD controller on a hinge: too little, just enough and too much damping",
  source = "000_3bd95e59483beea1.txt, \"Joint torques\", \"PD controller\"",
  steps = {
    {
      title = "The controller and the wheel",
      text = [[
000 "Joint torques" imagines a motor in the joint that produces whatever torque we ask for,
and "PD controller" asks for τ = kp(θd − θ) + kv(θ̇d − θ̇): a spring toward the target angle θd
and a damper toward the target rate θ̇d. Our joint is a hinge about z holding a solid wheel
of 4 kg, radius 0.5 m and thickness 0.1 m at its centre, so only the wheel's inertia about
the axle, I = mR²/2 = 0.5 kg·m², resists (no gravity). The target is θd = 1 rad at rest
(θ̇d = 0), with kp = 50 N·m/rad.

The wheel then obeys I·θ̈ + kv·θ̇ + kp·θ = kp·θd, a damped oscillator with the natural rate
ω = √(kp/I) = 10 rad/s and the damping ratio ζ = kv/(2√(kp·I)). Critical damping, ζ = 1, is
kv = 2√(kp·I) = 10 N·m·s/rad; 000's three warnings are ζ < 1 ("too low kv will produce
oscillations"), ζ = 1, and ζ > 1 ("too high kv will converge too slowly"). We try ζ = 0.1, 1
and 6: kv = 1, 10 and 60 N·m·s/rad.]],
      formula = "τ = kp(θd − θ) + kv(θ̇d − θ̇),   I·θ̈ = τ\nω = √(kp/I),   ζ = kv/(2√(kp·I))",
      run = function(ctx)
        local inertia_tensor = inertia.solid_cylinder(mass, R, thickness)
        ctx:show("I about the axle (kg·m²)", inertia_tensor:get(3, 3))
        ctx:expect("I = mR²/2", inertia_tensor:get(3, 3), 0.5)
        ctx:show("ω = √(kp/I) (rad/s)", omega_n)
        ctx:show("critical kv = 2√(kp·I) (N·m·s/rad)", kv_critical)
        local rows = {}
        for i, c in ipairs(cases) do rows[i] = {c.name, c.kv, c.kv / kv_critical} end
        ctx:table({"case", "kv (N·m·s/rad)", "ζ"}, rows)
      end,
    },
    {
      title = "The three responses",
      text = [[
Over one step the motor's law with its fixed target is a linear differential equation
with a known solution, and rigidlab's solver uses it: the motor row's target is the rate
the exact solution has at the end of the step, and the positions are moved to the exact
angle (a push, as for joint springs). So the world follows the closed form to rounding, at
any step: here 60 Hz with 8 substeps, checked to 1e-12 rad. The closed forms: for ζ < 1,
θ = θd(1 − e^{−ζωt}(cos ω_d t + (ζω/ω_d) sin ω_d t)) with ω_d = ω√(1 − ζ²) =
√(kp/I − (kv/2I)²); for ζ = 1, θ = θd(1 − e^{−ωt}(1 + ωt)); for ζ > 1 a sum of two
decaying exponentials with the rates of the roots of I·r² + kv·r + kp = 0.]],
      formula = "ζ < 1:  overshoot = e^{−πζ/√(1 − ζ²)},   ω_d = √(kp/I − (kv/2I)²)",
      run = function(ctx)
        local series, rows = {}, {}
        for i, c in ipairs(cases) do
          local t, theta, _, worst = run(c.kv, 8)
          series[#series + 1] = {x = t, y = theta, label = c.name}
          rows[i] = {c.name, largest(theta), rise_time(t, theta), closed_rise_time(c.kv), worst}
          ctx:expect(c.name .. ": largest distance from the closed form (rad)", worst, 0,
                     {abs = 1e-12, reason = "rounding over 180 steps"})
        end
        ctx:plot{series[1], series[2], series[3], title = "θ(t), target 1 rad", xlabel = "t (s)",
                 ylabel = "rad", height = 10}
        ctx:table({"case", "largest θ (rad)", "90 % at (s)", "closed form (s)", "largest error"},
                  rows)
        local zeta = cases[1].kv / kv_critical
        local overshoot = math.exp(-math.pi * zeta / math.sqrt(1 - zeta ^ 2))
        ctx:show("ζ = 0.1: overshoot by the closed form (rad)", overshoot * target)
        ctx:expect("ζ = 0.1 overshoots", rows[1][2] - target, overshoot * target,
                   {abs = 5e-3, reason = "frames 1/60 s apart miss the peak by up to ½·ω_d²·A·(Δt/2)² = 2.5e-3"})
        ctx:expect_range("ζ = 1 never overshoots (rad)", rows[2][2], nil, target + 1e-12)
        ctx:expect("ζ = 1 reaches 90 % at", rows[2][3], rows[2][4],
                   {abs = 5e-4, reason = "interpolated between frames"})
        ctx:expect("ζ = 6 is slow: 90 % at", rows[3][3], rows[3][4],
                   {abs = 5e-4, reason = "interpolated between frames"})
      end,
    },
    {
      title = "Any step size",
      text = [[
Because the motor's row follows the exact solution over each step, the step size does not
matter: for ζ = 0.1 (the case that moves most), the largest distance from the closed form
over 3 s with 1, 2, 4 and 8 substeps of a 60 Hz frame. A first-order treatment (the
implicit-Euler "soft" rows of game engines) would lag by a phase of order ωΔt per period,
some 0.1 rad here at one substep.]],
      run = function(ctx)
        local rows = {}
        for k, substeps in ipairs{1, 2, 4, 8} do
          local _, _, _, worst = run(cases[1].kv, substeps)
          rows[k] = {substeps, frame / substeps, worst}
          ctx:expect(string.format("%d substeps: the closed form (rad)", substeps), worst, 0,
                     {abs = 1e-12, reason = "rounding over 180 steps"})
        end
        ctx:table({"substeps", "Δt (s)", "largest error (rad)"}, rows)
      end,
    },
    {
      title = "A motor with a torque limit",
      text = [[
A real motor has a largest torque. With max_torque = 5 N·m the controller asks for
kp·θd = 50 N·m at the start and gets 5: the wheel accelerates at the constant 5/I =
10 rad/s², θ = ½·10·t², until kp(θd − θ) − kv·θ̇ falls to the limit. With kv = 10 that is
when 50(1 − 5t²) − 100t = 5, at t = 0.269 s; we watch the first 0.2 s (12 frames, 8 substeps
each), in which the motor must report 5 N·m and θ must follow the parabola. Semi-implicit
Euler, which updates the rate before the angle, leads a constant acceleration by ½·α·Δt·t:
2.1e-3 rad at 0.2 s with Δt = 1/480 s, which is the tolerance.]],
      formula = "|τ| ≤ τ_max:  θ = ½(τ_max/I)·t²  while the PD torque exceeds τ_max",
      run = function(ctx)
        local tau_max = 5
        local alpha = tau_max / I
        local qa, qb, qc = kp * alpha / 2, kv_critical * alpha, -(kp * target - tau_max)
        local t_end = (-qb + math.sqrt(qb ^ 2 - 4 * qa * qc)) / (2 * qa)
        ctx:show("α = τ_max/I (rad/s²)", alpha)
        ctx:show("the limit holds until t (s)", t_end)
        ctx:expect("until t = 0.269 s", t_end, 0.269, {abs = 5e-4, reason = "the text rounds"})
        local w, _, hinge = driven_wheel(kv_critical, 8, tau_max)
        local worst, torque = 0, 0
        for _ = 1, 12 do
          w:step(frame)
          worst = math.max(worst, math.abs(hinge.angle - 0.5 * tau_max / I * w.time ^ 2))
          torque = math.max(torque, math.abs(hinge.motor_torque))
        end
        ctx:show("t (s)", w.time)
        ctx:show("θ (rad)", hinge.angle)
        ctx:show("largest |θ − ½(τ_max/I)t²| (rad)", worst)
        ctx:show("largest motor torque (N·m)", torque)
        ctx:expect("the motor gives at most τ_max", torque, tau_max,
                   {rel = 1e-9, reason = "the clamp"})
        local lead = 0.5 * tau_max / I * (frame / 8) * w.time
        ctx:show("½·α·Δt·t at 0.2 s (rad)", lead)
        ctx:expect("θ follows the parabola", worst, 0,
                   {abs = lead * 1.05, reason = "semi-implicit Euler's lead ½·α·Δt·t, 5 % margin"})
      end,
    },
  },
}
