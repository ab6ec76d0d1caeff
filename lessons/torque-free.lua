-- Torque-free motion (002 "Newton-Euler Equations", "Torque-Free Motion"): with no torque,
-- ω̇ = −I⁻¹(ω × Iω). Off a principal axis ω tumbles while the angular momentum L and the
-- kinetic energy stay fixed; for a symmetric body ω circles the symmetry axis at the rate
-- Ω = (I₃ − I₁)ω₃/I₁ (Euler's equations). The world's default integrator keeps L to
-- round-off at a game's time step (gyroscopic = "conserving").

local box_mass, box_size = 3, vec3(1, 0.6, 0.3)     -- kg, m
local box_spin = vec3(1, 0.3, 2)                      -- rad/s, not along a principal axis

local function box_world(dt_integrator, spin)
  local w = world{gravity = vec3(0, 0, 0), integrator = dt_integrator or "rk4"}
  local b = w:add(body.box{mass = box_mass, size = box_size, angular_velocity = spin or box_spin})
  return w, b
end

-- 002's torque-free acceleration, with the box's closed-form tensor (000 "Inertia of
-- primitive shapes"); the box starts unrotated, so world and body axes agree at t = 0.
local function torque_free_rate(omega)
  local I = mat3.diag(box_mass * (box_size.y ^ 2 + box_size.z ^ 2) / 12,
                      box_mass * (box_size.x ^ 2 + box_size.z ^ 2) / 12,
                      box_mass * (box_size.x ^ 2 + box_size.y ^ 2) / 12)
  return -(I:inverse() * omega:cross(I * omega))
end

-- A flat cylinder (a coin-like top): I₁ = I₂ = m(3R² + h²)/12, I₃ = mR²/2 (001 Appendix B).
local top_mass, top_radius, top_height = 2, 0.3, 0.2
local top_spin = vec3(1.5, 0, 4)                      -- rad/s, body frame = world at t = 0

local function top_body_rate(t)
  local I1 = top_mass * (3 * top_radius ^ 2 + top_height ^ 2) / 12
  local I3 = top_mass * top_radius ^ 2 / 2
  local rate = (I3 - I1) / I1 * top_spin.z
  return vec3(top_spin.x * math.cos(rate * t), top_spin.x * math.sin(rate * t), top_spin.z), rate
end

-- The top's body-frame ω after each second up to 5 s, with RK4 steps of dt; returns the
-- largest distance from the closed form and the rows for a table.
local function run_top(dt)
  local w = world{gravity = vec3(0, 0, 0), integrator = "rk4"}
  local top = w:add(body{mass = top_mass,
                         inertia = inertia.solid_cylinder(top_mass, top_radius, top_height),
                         angular_velocity = top_spin})
  local worst, rows = 0, {}
  for second = 1, 5 do
    w:step(dt, math.floor(1 / dt + 0.5))
    local body_omega = top.orientation:conj():rotate(top.angular_velocity)
    local want = top_body_rate(second)
    worst = math.max(worst, (body_omega - want):norm())
    rows[#rows + 1] = {second, body_omega.x, want.x, body_omega.y, want.y, body_omega.z}
  end
  return worst, rows
end

return lesson{
  id = "torque-free",
  title = "Torque-free motion: ω tumbles, L stays",
  source = "002_5497adede943f513.txt, \"Newton-Euler Equations\", \"Torque-Free Motion\"",
  steps = {
    {
      title = "Spin without torque still changes ω",
      text = [[
Rearranged for the accelerations, the Newton-Euler equations give a = f/m and, for the rotation,
ω̇ = I⁻¹(τ − ω × Iω). With no force the centre of mass coasts. With no torque, though, ω
can still change: ω̇ = −I⁻¹(ω × Iω). The term vanishes only when Iω is parallel to ω, that
is when the body spins about a principal axis. Our box, 3 kg and 1 × 0.6 × 0.3 m, has
three different moments, and we start it spinning at ω = (1, 0.3, 2) rad/s, not along any
axis of the box.

We compute 002's rate by hand from the box's inertia and compare with what the world does
in its first moment of motion: one RK4 step of 1e-6 s, differenced. A one-sided difference
is off by about ½ω̈h, so the comparison allows 1e-5. A spin about the box's own z axis, in
contrast, does not change at all.]],
      formula = "ω̇ = I⁻¹(τ − ω × Iω);   τ = 0:  ω̇ = −I⁻¹(ω × Iω)",
      run = function(ctx)
        local w, box = box_world()
        local rate = torque_free_rate(box_spin)
        ctx:show("ω (rad/s)", box_spin)
        ctx:show("Iω (kg·m²/s)", box:world_inertia() * box_spin)
        ctx:show("ω̇ = −I⁻¹(ω × Iω) (rad/s²)", rate)
        local h = 1e-6
        w:step(h)
        local measured = (box.angular_velocity - box_spin) / h
        ctx:show("(ω(h) − ω(0))/h in the world (rad/s²)", measured)
        ctx:expect("the world follows 002's rate", measured, rate, 1e-5)
        local axis_spin = vec3(0, 0, 2)
        local w2, spinner = box_world("rk4", axis_spin)
        ctx:expect("principal axis: ω̇ = 0", torque_free_rate(axis_spin), vec3(0, 0, 0))
        w2:step(0.01, 100)
        ctx:expect("principal axis: ω after 1 s unchanged", spinner.angular_velocity, axis_spin,
                   1e-12)
      end,
    },
    {
      title = "ω wanders, L and T do not",
      text = [[
Let the box run for 5 s with RK4 steps of 0.01 s. ω swings around in direction and size,
and the angle between ω and L keeps changing. What stays put is the angular momentum
L = Iω: there is no torque, so dL/dt = 0 in world axes, and the kinetic energy
½ω·Iω, since nothing does work. The body rearranges how its spin is shared among its axes
(its inertia in world axes changes as it turns) in exactly the way that keeps both fixed.
RK4 holds them to about 1e-8 here; that residue is its truncation error.]],
      formula = "dL/dt = τ = 0,   L = Iω = const,   T = ½ω·Iω = const",
      run = function(ctx)
        local w, box = box_world()
        local L0, T0 = w:angular_momentum(), w:kinetic_energy()
        ctx:show("L₀ (kg·m²/s)", L0)
        ctx:show("T₀ (J)", T0)
        local rows = {}
        local trace = {t = {0}, x = {box_spin.x}, y = {box_spin.y}, z = {box_spin.z}}
        local worst_L, worst_T, widest, narrowest = 0, 0, 0, math.pi
        for step = 1, 100 do
          w:step(0.01, 5)
          local omega, L = box.angular_velocity, w:angular_momentum()
          trace.t[step + 1], trace.x[step + 1] = w.time, omega.x
          trace.y[step + 1], trace.z[step + 1] = omega.y, omega.z
          if step % 10 == 0 then
            local angle = math.acos(omega:dot(L) / (omega:norm() * L:norm()))
            widest, narrowest = math.max(widest, angle), math.min(narrowest, angle)
            worst_L = math.max(worst_L, (L - L0):norm() / L0:norm())
            worst_T = math.max(worst_T, math.abs(w:kinetic_energy() - T0) / T0)
            local function fixed(x) return string.format("%.4f", x) end
            rows[#rows + 1] = {w.time, fixed(omega.x), fixed(omega.y), fixed(omega.z),
                               fixed(omega:norm()), fixed(math.deg(angle)), (L - L0):norm()}
          end
        end
        ctx:table({"t (s)", "ωx", "ωy", "ωz", "|ω| (rad/s)", "∠(ω, L) (°)", "‖L − L₀‖"}, rows)
        ctx:plot{{x = trace.t, y = trace.x, label = "ωx"}, {x = trace.t, y = trace.y, label = "ωy"},
                 {x = trace.t, y = trace.z, label = "ωz"},
                 title = "ω in world axes wanders (L stays)", xlabel = "t (s)", ylabel = "rad/s",
                 height = 10}
        ctx:show("∠(ω, L) at these times, least and most (°)", {math.deg(narrowest), math.deg(widest)})
        ctx:expect("L constant (relative)", worst_L, 0, {abs = 1e-7})
        ctx:expect("T constant (relative)", worst_T, 0, {abs = 1e-7})
      end,
    },
    {
      title = "A symmetric top: ω circles the axis at Ω = (I₃ − I₁)ω₃/I₁",
      text = [[
For a body with two equal moments, like a thick coin (I₁ = I₂ ≠ I₃), the torque-free
equations can be solved by hand. Written in the body's own axes they become Euler's
equations; the component ω₃ along the symmetry axis stays constant, and the other two
turn around it at the steady rate Ω = (I₃ − I₁)ω₃/I₁. Seen from the body, ω sweeps a cone
about the symmetry axis; this is the wobble of a tossed plate or coin. Our coin (2 kg,
R = 0.3 m, h = 0.2 m) spinning at ω₃ = 4 rad/s with a 1.5 rad/s wobble has Ω ≈ 2.97 rad/s.
The world's RK4 follows the closed form to a few 1e-6 rad/s over 5 s with Δt = 0.01 s;
with Δt = 0.02 s the error is 16 times larger, as a fourth-order method should show.]],
      formula = "ω_body(t) = (ω₁cos Ωt, ω₁sin Ωt, ω₃),   Ω = (I₃ − I₁)ω₃/I₁",
      run = function(ctx)
        local _, rate = top_body_rate(0)
        ctx:show("Ω (rad/s)", rate)
        local worst, rows = run_top(0.01)
        local coarse = run_top(0.02)
        ctx:table({"t (s)", "ω₁ world run", "ω₁ cos Ωt", "ω₂ world run", "ω₁ sin Ωt", "ω₃"}, rows)
        ctx:show("largest deviation, Δt = 0.01 s (rad/s)", worst)
        ctx:show("largest deviation, Δt = 0.02 s (rad/s)", coarse)
        ctx:expect("Δt = 0.01 s: within 1e-5 rad/s of the closed form", worst, 0, {abs = 1e-5})
        ctx:expect("halving Δt divides the error by ≈ 16", coarse / worst, 16, {abs = 1})
      end,
    },
    {
      title = "At a game's time step: the default world keeps L",
      text = [[
RK4 with Δt = 0.01 s is an accurate reference, but a game steps at 60 Hz with a cheaper
method. rigidlab's default world (semi-implicit Euler, gyroscopic = "conserving") turns a
body by exact rotations about its principal axes, each of which leaves the world L as it
is, so L stays constant to round-off however large the step, and T stays within a small
bound that does not grow (see the dzhanibekov lesson for how the step is built). We run
the same box for 100 s at 60 Hz in the default world, with the gyroscopic setting of
document 001 ("implicit", one Newton step per frame) and with RK4 at the same step, and
keep the largest change of L and of T seen after any frame.]],
      formula = "default: ‖L − L₀‖/‖L₀‖ ≈ 1e-13 at Δt = 1/60 s; T error bounded, no drift",
      run = function(ctx)
        local rows, worst = {}, {}
        for _, setup in ipairs({{"default (conserving)", {}},
                                {"implicit", {gyroscopic = "implicit"}},
                                {"rk4", {integrator = "rk4"}}}) do
          local options = setup[2]
          options.gravity = vec3(0, 0, 0)
          local w = world(options)
          w:add(body.box{mass = box_mass, size = box_size, angular_velocity = box_spin})
          local L0, T0 = w:angular_momentum(), w:kinetic_energy()
          local worst_L, worst_T = 0, 0
          for _ = 1, 6000 do
            w:step(1 / 60)
            worst_L = math.max(worst_L, (w:angular_momentum() - L0):norm() / L0:norm())
            worst_T = math.max(worst_T, math.abs(w:kinetic_energy() / T0 - 1))
          end
          rows[#rows + 1] = {setup[1], string.format("%.1e", worst_L),
                             string.format("%.1e", worst_T)}
          worst[setup[1]] = {L = worst_L, T = worst_T}
        end
        ctx:table({"world", "max ‖L − L₀‖/‖L₀‖", "max |T/T₀ − 1|"}, rows)
        local default = worst["default (conserving)"]
        ctx:expect("default world: L constant to round-off over 100 s", default.L, 0,
                   {abs = 1e-9})
        ctx:expect("default world: T within 1e-4 over 100 s", default.T, 0, {abs = 1e-4})
        ctx:show("the implicit step loses (largest ‖L − L₀‖/‖L₀‖)", worst.implicit.L)
      end,
    },
    {
      title = "Watch it tumble",
      text = [[
The box of step 1 (3 kg, 1 × 0.6 × 0.3 m, at rest at the origin, ω = (1, 0.3, 2) rad/s) in
the default world at 60 Hz for 3 s, a frame every second, with its ω and L drawn at the
centre. The box tumbles and ω turns with it, but the L arrow stays where it is. Poinsot's
picture of the same fact: ω·L = 2T, and both T and L are constant, so the tip of ω moves in
a plane perpendicular to L (the invariable plane) while ω itself wanders. In a terminal,
v at the prompt shows it live: space pauses, ← steps back.]],
      formula = "L constant;   ω·L = ωᵀIω = 2T constant   (Poinsot)",
      run = function(ctx)
        local w, box = box_world("semi_implicit")
        local I = mat3.diag(box_mass * (box_size.y ^ 2 + box_size.z ^ 2) / 12,
                            box_mass * (box_size.x ^ 2 + box_size.z ^ 2) / 12,
                            box_mass * (box_size.x ^ 2 + box_size.y ^ 2) / 12)
        local twoT = box_spin:dot(I * box_spin)   -- unrotated at t = 0: body axes = world axes
        local L0 = I * box_spin
        ctx:motion(w, {seconds = 3, frames = 4, dt = 1 / 60, show = {"omega", "L"},
                       camera = {eye = vec3(2.5, 1.5, -0.5)}})
        local omega, L = box.angular_velocity, w:angular_momentum()
        local turned = math.deg(math.acos(omega:dot(box_spin) / (omega:norm() * box_spin:norm())))
        ctx:show("ω at t = 3 s (rad/s)", omega)
        ctx:show("angle between ω(0) and ω(3 s) (°)", turned)
        ctx:expect_range("ω has turned by more than 10°", turned, 10, nil)
        ctx:expect("L(3 s) = Iω(0) (relative change)", (L - L0):norm() / L0:norm(), 0, {abs = 1e-9})
        ctx:expect("ω·L = 2T = ωᵀIω at t = 0", omega:dot(L), twoT,
                   {rel = 1e-3, reason = "the default world keeps T within 1e-4 (step 4)"})
      end,
    },
  },
}
