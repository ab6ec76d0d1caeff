-- Orientation as a unit quaternion (003 "Orientation", "Solving Angular Equations in 3D";
-- 001 "Implementation of The Dynamics"): q = [u sin(θ/2), cos(θ/2)], the rate dq/dt = ½ωq,
-- an Euler step on it with and without renormalisation, against the exact axis-angle update.

local omega = vec3(0, 1.2, 1.6)                    -- rad/s, |ω| = 2, axis (0, 0.6, 0.8)
local start = quat.axis_angle(vec3(1, 0, 0), 0.5)  -- the body starts tilted 0.5 rad about x
local duration = 1                                 -- s

local function pure(v) return quat(0, v.x, v.y, v.z) end

-- 003's update: q ← q + ½·[ω, 0]·q·Δt, optionally renormalised.
local function euler_orientation(dt, steps, renormalise)
  local q = start
  for _ = 1, steps do
    q = q + pure(omega) * q * (0.5 * dt)
    if renormalise then q = q:normalized() end
  end
  return q
end

-- The exact update for a constant ω: turn by |ω|·t about ω's axis (world frame, so on the left).
local function exact_orientation(t) return quat.axis_angle(omega, omega:norm() * t) * start end

-- How far q trails the exact orientation: the angle of exact·q⁻¹ (q unit).
local function lag_angle(q, t)
  local axis, angle = (exact_orientation(t) * q:conj()):axis_angle()
  return angle, axis
end

return lesson{
  id = "quaternion-orientation",
  title = "Orientation as a quaternion: dq/dt = ½ωq",
  source = "003_636de12a6b81385f.txt, \"Orientation\", \"Solving Angular Equations in 3D\"; " ..
           "001_8a70f78e0cc79e25.txt, \"Implementation of The Dynamics\"",
  steps = {
    {
      title = "Axis and half-angle in four numbers",
      text = [[
In 2D one angle says how a body is turned; in 3D we need an axis and an angle. Three Euler
angles can encode that, but they jam at certain poses (gimbal lock), so the slides use a
unit quaternion: the unit axis u scaled by the sine of half the angle, plus the cosine of
half the angle. The half angles are what make the algebra work: rotating a vector v is
q·[v, 0]·q*, in which q appears twice, each contributing half the turn.

003 lists the components as [qx, qy, qz, qw] with the scalar last; rigidlab writes
quat(w, x, y, z) with the scalar first. Same numbers, different order. Here we turn by
θ = 2 rad about (0, 0.6, 0.8) and compare q:rotate and q·[v, 0]·q* with Rodrigues' rotation
formula, a closed form that uses no quaternion at all.]],
      formula = "q = [u sin(θ/2), cos(θ/2)];   v' = v cosθ + (u×v) sinθ + u(u·v)(1 − cosθ)",
      run = function(ctx)
        local u, theta = omega:normalized(), 2
        local q = quat.axis_angle(omega, theta)
        ctx:show("q = quat.axis_angle(u, 2)", q)
        ctx:expect("w = cos(θ/2)", q.w, math.cos(theta / 2))
        ctx:expect("(x, y, z) = u sin(θ/2)", vec3(q.x, q.y, q.z), u * math.sin(theta / 2))
        ctx:expect("|q| = 1", q:norm(), 1)
        local v = vec3(1, 2, 3)
        local rodrigues = v * math.cos(theta) + u:cross(v) * math.sin(theta) +
                          u * (u:dot(v) * (1 - math.cos(theta)))
        local sandwich = q * pure(v) * q:conj()
        ctx:show("q:rotate(v)", q:rotate(v))
        ctx:show("q·[v, 0]·q*", sandwich)
        ctx:expect("q:rotate(v) = Rodrigues", q:rotate(v), rodrigues, 1e-12)
        ctx:expect("q·[v, 0]·q* = [Rodrigues, 0]", sandwich, quat(0, rodrigues.x, rodrigues.y,
                                                                   rodrigues.z), 1e-12)
      end,
    },
    {
      title = "The rate dq/dt = ½ωq, and why Euler leaves the unit sphere",
      text = [[
If the body spins at ω (world frame), its quaternion changes at dq/dt = ½·[ω, 0]·q: the
½ is the half angle again, and the product sits on the left because ω is measured in
world axes. 003 integrates it with one Euler step, q + ½ωqΔt, and stops there. The trouble
is that ½ωq is always perpendicular to q, seen as a 4-vector, so every step moves q along a
tangent of the unit sphere and off it: |q|² grows by exactly the factor 1 + (|ω|Δt/2)².
With |ω| = 2 rad/s and Δt = 0.1 s that is 1.01 per step. A quaternion that is not unit
no longer only rotates: q·[v, 0]·q* also stretches v by |q|², 10 % after one second here.
Hence 001's code renormalises after each update.]],
      formula = "dq/dt = ½·[ω, 0]·q;   q' = q + ½ωqΔt  ⇒  |q'|² = |q|²·(1 + (|ω|Δt/2)²)",
      run = function(ctx)
        local dt, rows = 0.1, {}
        local rate = 0.5 * pure(omega) * start
        ctx:show("½ωq at the start (1/s)", rate)
        ctx:expect("½ωq ⟂ q (4-vector dot product)", rate:dot(start), 0, {abs = 1e-15})
        local growth = 1 + (omega:norm() * dt / 2) ^ 2
        for _, steps in ipairs({1, 2, 5, 10}) do
          local q = euler_orientation(dt, steps, false)
          local stretched = (q * pure(vec3(1, 0, 0)) * q:conj())
          local length = vec3(stretched.x, stretched.y, stretched.z):norm()
          rows[#rows + 1] = {steps, q:norm() ^ 2, growth ^ steps, length}
          ctx:expect(steps .. " steps: |q|² = (1 + (|ω|Δt/2)²)^n", q:norm() ^ 2, growth ^ steps)
          ctx:expect(steps .. " steps: a unit vector stretched to |q|²", length, growth ^ steps)
        end
        ctx:table({"steps", "|q|²", "(1 + (|ω|Δt/2)²)^n", "|q·[x̂,0]·q*|"}, rows)
      end,
    },
    {
      title = "Renormalised Euler against the exact turn",
      text = [[
Renormalising fixes the length but not the angle. For a constant ω the Euler factor
1 + ½ωΔt, scaled back to unit length, is a turn by 2·atan(|ω|Δt/2) instead of |ω|Δt: a
little short each step, about (|ω|Δt)³/12. The exact update simply turns by |ω|Δt about ω's
axis, the quat.axis_angle of 001's code. After one second the renormalised Euler
quaternion trails the exact one by a small turn about the same axis; halve Δt and the lag
drops by four, the global error O(Δt²) of a method whose local error is O(Δt³).]],
      formula = "Euler + renormalise: turn 2·atan(|ω|Δt/2) per step;   exact: |ω|Δt\n" ..
                "lag after N steps = N·(|ω|Δt − 2·atan(|ω|Δt/2)) ≈ N(|ω|Δt)³/12",
      run = function(ctx)
        local rows, previous = {}, nil
        for _, dt in ipairs({0.2, 0.1, 0.05, 0.025}) do
          local steps = math.floor(duration / dt + 0.5)
          local q = euler_orientation(dt, steps, true)
          local lag, axis = lag_angle(q, duration)
          local want = steps * (omega:norm() * dt - 2 * math.atan(omega:norm() * dt / 2))
          rows[#rows + 1] = {dt, lag, want, previous and previous / lag or "", q:norm()}
          ctx:expect("Δt = " .. dt .. ": lag = N(|ω|Δt − 2 atan(|ω|Δt/2))", lag, want,
                     {abs = 1e-12})
          ctx:expect("Δt = " .. dt .. ": the lag is a turn about ω", axis, omega:normalized(), 1e-6)
          previous = lag
        end
        ctx:table({"Δt (s)", "lag after 1 s (rad)", "closed form (rad)", "ratio", "|q|"}, rows)
        ctx:say("The lag's axis is checked to 1e-6: for tiny turns axis_angle divides by")
        ctx:say("sin(lag/2), which magnifies rounding.")
      end,
    },
    {
      title = "What the engine does",
      text = [[
rigidlab's world uses the exact turn in its Euler-family integrators, like 001's
update_rigid_body_state: each step multiplies the orientation by the axis-angle
quaternion of ω·Δt and renormalises only to sweep away rounding. So a freely spinning ball
(constant ω, as for any sphere) lands exactly on quat.axis_angle(ω, |ω|t) times its start.
Ours is 1 kg with radius 0.5 m, starts tilted by 0.5 rad about x, as above, and spins at
ω = (0, 1.2, 1.6) rad/s, without gravity.
With integrator = "rk4" the world integrates dq/dt = ½ωq itself with four stages; for a
constant ω one RK4 step multiplies q by the Taylor polynomial 1 + x + x²/2 + x³/6 + x⁴/24
of x = ½ωΔt, which again is a slightly short turn, now short by only O(Δt⁵) per step.]],
      formula = "RK4 per step: turn 2·atan((h − h³/6)/(1 − h²/2 + h⁴/24)),  h = |ω|Δt/2",
      run = function(ctx)
        local rows = {}
        for _, dt in ipairs({0.2, 0.1, 0.05}) do
          local steps = math.floor(duration / dt + 0.5)
          local result = {}
          for _, method in ipairs({"semi_implicit", "rk4"}) do
            local w = world{gravity = vec3(0, 0, 0), integrator = method}
            local ball = w:add(body.sphere{mass = 1, radius = 0.5, orientation = start,
                                           angular_velocity = omega})
            w:step(dt, steps)
            result[method] = lag_angle(ball.orientation, duration)
          end
          local h = omega:norm() * dt / 2
          local rk4_turn = 2 * math.atan((h - h ^ 3 / 6) / (1 - h ^ 2 / 2 + h ^ 4 / 24))
          local want_rk4 = steps * (omega:norm() * dt - rk4_turn)
          rows[#rows + 1] = {dt, result.semi_implicit, result.rk4, want_rk4}
          ctx:expect("Δt = " .. dt .. ": semi_implicit turns exactly", result.semi_implicit, 0,
                     {abs = 1e-12})
          ctx:expect("Δt = " .. dt .. ": rk4 lag = closed form", result.rk4, want_rk4,
                     {abs = 1e-12})
        end
        ctx:table({"Δt (s)", "lag, semi_implicit (rad)", "lag, rk4 (rad)", "rk4 closed form"}, rows)
      end,
    },
  },
}
