-- The accelerating car of 003 "Explicit Euler": what the slides' table really computes, and how
-- the three integrators of motion.simulate compare with the exact answer.

local acceleration = 10   -- m/s², constant
local duration = 10       -- s
local slides_dt = 1       -- s

-- The car starts at rest at r = 0 and accelerates at a constant rate.
local function car(method, dt)
  return motion.simulate{method = method, accel = function() return acceleration end,
                         x0 = 0, v0 = 0, dt = dt, steps = math.floor(duration / dt + 0.5)}
end

local function final_position(method, dt)
  local trajectory = car(method, dt)
  return trajectory.x[#trajectory.x]
end

-- Closed forms of the three discrete updates for a constant a (sums of an arithmetic series):
--   explicit Euler       r_n = a Δt² n(n−1)/2   (step k adds Δt·v_k = a Δt² k, k = 0..n−1)
--   semi-implicit Euler  r_n = a Δt² n(n+1)/2   (step k adds Δt·v_{k+1}, k = 0..n−1)
--   exact                r(t) = ½ a t²
local function explicit_closed_form(n, dt) return acceleration * dt * dt * n * (n - 1) / 2 end
local function semi_implicit_closed_form(n, dt) return acceleration * dt * dt * n * (n + 1) / 2 end
local function exact_position(t) return 0.5 * acceleration * t * t end

return lesson{
  id = "euler-car",
  title = "Euler's method on an accelerating car",
  source = "003_636de12a6b81385f.txt, \"Explicit Euler\" and \"Analytical Solution\"",
  steps = {
    {
      title = "Where is the car after 10 s?",
      text = [[
A car waits at r = 0, then accelerates at a steady 10 m/s². Because the acceleration
never changes, calculus gives the answer outright: velocity grows linearly, v = a·t, and
position is the area under that straight line, a triangle, r = ½·a·t². After 10 s the car
is going 100 m/s and has covered 500 m. Keep that 500 in mind: it is the number every
integrator below is trying to hit.]],
      formula = "v(t) = a·t,   r(t) = ½·a·t² + v₀·t   (v₀ = 0, a = 10 m/s², t = 10 s)",
      run = function(ctx)
        local v = acceleration * duration
        local r = exact_position(duration)
        ctx:show("a (m/s²)", acceleration)
        ctx:show("v(10 s) (m/s)", v)
        ctx:show("r(10 s) (m)", r)
        ctx:expect("analytic r(10 s), the slides' value", r, 500)
      end,
    },
    {
      title = "The slides' table: velocity first, then position",
      text = [[
The slides march the car forward one second at a time. Each step first adds a·Δt to the
velocity, and then moves the car by Δt times that NEW velocity. Run with Δt = 1 s, this is
exactly the table on the slide: 10, 30, 60, ... ending at r = 550 m, 50 m too far.
A note on the name: the slide calls this "explicit Euler", but an update that uses the
freshly computed velocity to move the position is the semi-implicit (also called
symplectic) Euler method. Textbook explicit Euler moves the position with the OLD
velocity, the one from the start of the step. The difference matters, as the next step
shows. rigidlab calls the slides' update method = "semi_implicit".]],
      formula = "vₙ = vₙ₋₁ + a·Δt,   rₙ = rₙ₋₁ + vₙ·Δt\n" ..
                "(the slides label this explicit Euler; it is semi-implicit Euler)",
      run = function(ctx)
        local trajectory = car("semi_implicit", slides_dt)
        local slides_r = {0, 10, 30, 60, 100, 150, 210, 280, 360, 450, 550}  -- 003's table
        local slides_v = {0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100}
        local rows = {}
        for i = 1, #trajectory.t do
          rows[i] = {trajectory.t[i], trajectory.v[i], trajectory.x[i]}
        end
        ctx:table({"t (s)", "v (m/s)", "r (m)"}, rows)
        ctx:expect("velocities, the slides' column", trajectory.v, slides_v)
        ctx:expect("positions, the slides' column", trajectory.x, slides_r)
        ctx:expect("r(10 s) with the slides' update", trajectory.x[11], 550)
        ctx:show("overshoot r − 500 (m)", trajectory.x[11] - 500)
      end,
    },
    {
      title = "True explicit Euler falls short instead",
      text = [[
Textbook explicit Euler updates both quantities from the state at the start of the step:
the car moves by Δt times the velocity it HAD, then the velocity grows. In the first second
the car therefore does not move at all (it was at rest), and it lags behind from then on,
finishing at 450 m, 50 m short. The two Euler variants miss by the same amount in
opposite directions: one uses the velocity at the end of each step, the other the velocity
at its start, while the truth is the velocity in the middle. Each column also matches the
closed form of its own update, which you get by summing an arithmetic series.]],
      formula = "explicit:      rₙ = rₙ₋₁ + vₙ₋₁·Δt, vₙ = vₙ₋₁ + a·Δt ⇒ rₙ = aΔt²·n(n−1)/2\n" ..
                "semi-implicit: vₙ = vₙ₋₁ + a·Δt, rₙ = rₙ₋₁ + vₙ·Δt   ⇒ rₙ = aΔt²·n(n+1)/2",
      run = function(ctx)
        local explicit = car("euler", slides_dt)
        local semi = car("semi_implicit", slides_dt)
        local rows, explicit_want, semi_want = {}, {}, {}
        for i = 1, #explicit.t do
          local n = i - 1
          explicit_want[i] = explicit_closed_form(n, slides_dt)
          semi_want[i] = semi_implicit_closed_form(n, slides_dt)
          rows[i] = {explicit.t[i], exact_position(explicit.t[i]), explicit.x[i], semi.x[i]}
        end
        ctx:table({"t (s)", "exact r", "explicit Euler r", "semi-implicit r"}, rows)
        local times, parabola = {}, {}  -- the exact path, sampled finely enough to look smooth
        for i = 0, 100 do times[#times + 1], parabola[#parabola + 1] = i / 10, exact_position(i / 10) end
        ctx:plot{{x = times, y = parabola, label = "exact ½at²"},
                 {x = explicit.t, y = explicit.x, label = "explicit Euler"},
                 {x = semi.t, y = semi.x, label = "semi-implicit Euler"},
                 title = "The car's position, Δt = 1 s", xlabel = "t (s)", ylabel = "r (m)",
                 height = 10}
        ctx:expect("explicit Euler column = a·Δt²·n(n−1)/2", explicit.x, explicit_want)
        ctx:expect("semi-implicit column = a·Δt²·n(n+1)/2", semi.x, semi_want)
        ctx:expect("explicit Euler r(10 s)", explicit.x[11], 450)
        ctx:show("explicit Euler error r − 500 (m)", explicit.x[11] - 500)
      end,
    },
    {
      title = "Runge-Kutta 4 hits 500 exactly",
      text = [[
The fourth-order Runge-Kutta method samples the slope at the start, twice in the middle
and at the end of each step, and blends them (see the rk4 lesson). For a constant
acceleration the true path is a parabola, and RK4's blend integrates parabolas without
any error, so even with one-second steps it lands on 500 m. Only rounding in the last
digits could separate it from the exact value.]],
      formula = "rₙ₊₁ = rₙ + Δt/6·(k₁ + 2k₂ + 2k₃ + k₄)",
      run = function(ctx)
        local rk4 = car("rk4", slides_dt)
        ctx:show("RK4 r(10 s) (m)", rk4.x[11])
        ctx:show("RK4 v(10 s) (m/s)", rk4.v[11])
        ctx:expect("RK4 r(10 s), the analytic value", rk4.x[11], 500)
        ctx:expect("RK4 v(10 s)", rk4.v[11], 100)
      end,
    },
    {
      title = "Halving Δt halves the error",
      text = [[
Both Euler methods are first-order: their error is proportional to the step size. For this
car the error after time T is exactly ±½·a·Δt·T (subtract ½·a·t² from the closed forms
above, with t = n·Δt). So 1 s steps miss by 50 m, 0.5 s steps by 25 m, 0.25 s steps by
12.5 m. One-second steps are an exaggeration; a game running at 60 frames per second
would miss this car's position by under a metre after 10 s, but a first-order error never
goes away, it only shrinks as slowly as you pay for smaller steps.]],
      formula = "error(T) = rₙ − ½·a·T² = ±½·a·Δt·T   (+ semi-implicit, − explicit)",
      run = function(ctx)
        local rows = {}
        for _, dt in ipairs({1, 0.5, 0.25}) do
          local semi_error = final_position("semi_implicit", dt) - 500
          local explicit_error = final_position("euler", dt) - 500
          rows[#rows + 1] = {dt, semi_error, explicit_error}
          local bound = 0.5 * acceleration * dt * duration
          ctx:expect(string.format("semi-implicit error at Δt = %g s = ½·a·Δt·T", dt),
                     semi_error, bound)
          ctx:expect(string.format("explicit error at Δt = %g s = −½·a·Δt·T", dt),
                     explicit_error, -bound)
        end
        ctx:table({"Δt (s)", "semi-implicit error (m)", "explicit error (m)"}, rows)
        ctx:show("error ratio Δt = 1 s : 0.5 s", rows[1][2] / rows[2][2])
        ctx:expect("halving Δt halves the error", rows[1][2] / rows[2][2], 2)
      end,
    },
  },
}
