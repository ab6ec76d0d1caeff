-- The thrown ball of 003 "Analytical Solution": the high-school formula against each of the
-- integrators, with the exact discrete solutions that explain their errors.

local g = -9.8                       -- m/s², the slides' value (y up)
local start = vec3(0, 2, 0)          -- m, thrown from 2 m above the ground
local launch = vec3(5, 15, 0)        -- m/s
local dt = 0.1                       -- s
local steps = 30                     -- 3 s

local gravity = vec3(0, g, 0)
local function falling(_, _, _) return gravity end

local function throw(method)
  return motion.simulate{method = method, accel = falling, x0 = start, v0 = launch, dt = dt,
                         steps = steps}
end

-- y(t) = ½gt² + v₀t + y₀ (003 "Analytical Solution"); x moves at constant speed.
local function exact(t)
  return vec3(start.x + launch.x * t, 0.5 * g * t * t + launch.y * t + start.y, 0)
end

-- Exact discrete solutions for a constant g after n steps (t = nΔt): the Euler variants add
-- g·Δt²·Σk, with k = 0..n−1 (explicit) or k = 1..n (semi-implicit), instead of ½g t².
local function explicit_closed_form(n)
  local t = n * dt
  return vec3(start.x + launch.x * t, start.y + launch.y * t + g * dt * dt * n * (n - 1) / 2, 0)
end
local function semi_implicit_closed_form(n)
  local t = n * dt
  return vec3(start.x + launch.x * t, start.y + launch.y * t + g * dt * dt * n * (n + 1) / 2, 0)
end

return lesson{
  id = "projectile",
  title = "A thrown ball: the analytic path against the integrators",
  source = "003_636de12a6b81385f.txt, \"Analytical Solution\" and \"Explicit Euler\"",
  steps = {
    {
      title = "The formula from school",
      text = [[
Throw a ball and, ignoring air, only gravity acts on it: a constant acceleration g straight
down. Integrating once gives the velocity, which changes linearly, v = g·t + v₀; integrating
again gives the height, a parabola, y = ½·g·t² + v₀·t + y₀. The slides of 003 use
g = −9.8 m/s² with y pointing up. Our ball leaves a 2 m ledge at 15 m/s upward and
5 m/s sideways. Sideways nothing pushes it, so x just grows steadily.

The slides point out the catch: in a game the forces change with what the player does, so
a formula like this is rarely available. Still, when it is, it is the perfect referee.]],
      formula = "ẏ(t) = g·t + v₀,   y(t) = ½·g·t² + v₀·t + y₀,   g = −9.8 m/s²",
      run = function(ctx)
        local apex_time = -launch.y / g
        local apex = exact(apex_time)
        ctx:show("time of the apex −v₀/g (s)", apex_time)
        ctx:show("apex height y₀ − v₀²/(2g) (m)", apex.y)
        ctx:show("position at t = 3 s (m)", exact(3))
        local rk4 = throw("rk4")
        ctx:show("RK4 position at t = 3 s (m)", rk4.x[steps + 1])
        ctx:expect("RK4 reproduces the parabola at t = 3 s", rk4.x[steps + 1], exact(3))
        ctx:expect("RK4 velocity at t = 3 s = g·t + v₀", rk4.v[steps + 1],
                   launch + gravity * 3)
      end,
    },
    {
      title = "Each integrator, step by step",
      text = [[
Now the three integrators fly the same throw with 0.1 s steps. RK4 follows the parabola to
the last digit: its four slope samples integrate any path up to a quartic exactly, and a
parabola is well within that. The two Euler methods bracket the truth. Explicit Euler
moves the ball with the velocity from the start of each step, which is always a little
too upward, so the ball flies high; semi-implicit Euler uses the end-of-step velocity,
always a little too downward, so it flies low. Both miss by ½·|g|·Δt·t, growing steadily
with time: 1.47 m after 3 s. The horizontal motion has no acceleration and all three get
it exactly.]],
      formula = "explicit:      yₙ = y₀ + v₀·tₙ + g·Δt²·n(n−1)/2\n" ..
                "semi-implicit: yₙ = y₀ + v₀·tₙ + g·Δt²·n(n+1)/2\n" ..
                "error = ∓½·g·Δt·tₙ",
      run = function(ctx)
        local explicit, semi, rk4 = throw("euler"), throw("semi_implicit"), throw("rk4")
        local rows = {}
        for i = 1, steps + 1, 5 do
          local t = explicit.t[i]
          rows[#rows + 1] = {t, exact(t).y, explicit.x[i].y, semi.x[i].y, rk4.x[i].y}
        end
        ctx:table({"t (s)", "exact y (m)", "explicit y", "semi-implicit y", "RK4 y"}, rows)
        local heights = {explicit = {}, semi = {}, rk4 = {}, exact = {}}
        for i = 1, steps + 1 do
          heights.explicit[i], heights.semi[i] = explicit.x[i].y, semi.x[i].y
          heights.rk4[i], heights.exact[i] = rk4.x[i].y, exact(explicit.t[i]).y
        end
        ctx:plot{{x = explicit.t, y = heights.exact, label = "exact parabola"},
                 {x = explicit.t, y = heights.explicit, label = "explicit Euler"},
                 {x = explicit.t, y = heights.semi, label = "semi-implicit Euler"},
                 {x = rk4.t, y = heights.rk4, label = "RK4 (on the parabola)"},
                 title = "Height of the ball, Δt = 0.1 s", xlabel = "t (s)", ylabel = "y (m)",
                 height = 10}
        local worst_rk4, worst_explicit, worst_semi = 0, 0, 0
        for i = 1, steps + 1 do
          local n = i - 1
          worst_rk4 = math.max(worst_rk4, (rk4.x[i] - exact(n * dt)):norm())
          worst_explicit = math.max(worst_explicit,
                                    (explicit.x[i] - explicit_closed_form(n)):norm())
          worst_semi = math.max(worst_semi, (semi.x[i] - semi_implicit_closed_form(n)):norm())
        end
        ctx:expect("RK4: largest distance from the parabola over all 31 samples (m)",
                   worst_rk4, 0, {abs = 1e-12})
        ctx:expect("explicit Euler: largest distance from its closed form (m)",
                   worst_explicit, 0, {abs = 1e-12})
        ctx:expect("semi-implicit: largest distance from its closed form (m)",
                   worst_semi, 0, {abs = 1e-12})
        local t_end = steps * dt
        ctx:show("explicit error at 3 s (m)", explicit.x[steps + 1].y - exact(t_end).y)
        ctx:show("semi-implicit error at 3 s (m)", semi.x[steps + 1].y - exact(t_end).y)
        ctx:expect("explicit error = −½·g·Δt·t", explicit.x[steps + 1].y - exact(t_end).y,
                   -0.5 * g * dt * t_end)
        ctx:expect("semi-implicit error = +½·g·Δt·t", semi.x[steps + 1].y - exact(t_end).y,
                   0.5 * g * dt * t_end)
        ctx:expect("every method moves x exactly: x(3 s) = 5·3 m",
                   {explicit.x[steps + 1].x, semi.x[steps + 1].x, rk4.x[steps + 1].x},
                   {15, 15, 15})
      end,
    },
    {
      title = "The same throw in a rigid-body world",
      text = [[
A full rigidlab world does the same arithmetic for the centre of mass of every body. We
throw a small ball (a body.sphere of 0.2 kg and radius 0.05 m, from the same start with the
same velocity) in worlds with gravity −9.8 m/s² and each of the three
integrators: after 30 steps of 0.1 s they land on the same three heights as above, 4.37 m
(explicit), 1.43 m (semi-implicit, the world's default) and the exact 2.9 m (RK4).]],
      formula = "y(3 s): exact 2.9 m, explicit 2.9 + 1.47, semi-implicit 2.9 − 1.47",
      run = function(ctx)
        local t_end = steps * dt
        local want = {euler = explicit_closed_form(steps),
                      semi_implicit = semi_implicit_closed_form(steps), rk4 = exact(t_end)}
        for _, method in ipairs({"euler", "semi_implicit", "rk4"}) do
          local w = world{gravity = gravity, integrator = method}
          local ball = w:add(body.sphere{mass = 0.2, radius = 0.05, position = start,
                                         velocity = launch})
          w:step(dt, steps)
          ctx:show(method .. ": position at 3 s (m)", ball.position)
          ctx:expect(method .. ": the closed form", ball.position, want[method], 1e-12)
          ctx:expect(method .. ": velocity g·t + v₀", ball.velocity, launch + gravity * t_end,
                     1e-12)
        end
      end,
    },
  },
}
