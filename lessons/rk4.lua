-- One step of the classical Runge-Kutta method of 003 "Fourth-Order Runge-Kutta", stage by
-- stage, and its measured order of convergence next to Euler's.

-- The test problem: y' = −2·t·y, y(0) = 1, whose exact solution is y(t) = exp(−t²).
local function slope(t, y) return 0 - 2 * t * y end  -- 0 − …: no "-0" at t = 0
local function exact(t) return math.exp(-t * t) end

-- Integrates from 0 to 1 s with n steps of `method` and returns |y_n − y(1)|.
local function error_at_one(method, n)
  local y, dt = 1, 1 / n
  for i = 0, n - 1 do y = ode.step(method, slope, i * dt, y, dt) end
  return math.abs(y - exact(1))
end

-- Measured order p from the errors at step counts n and 2n: error ∝ Δtᵖ ⇒ p = log₂(e_n / e_2n).
local function measured_order(method, n)
  return math.log(error_at_one(method, n) / error_at_one(method, 2 * n), 2)
end

return lesson{
  id = "rk4",
  title = "Fourth-order Runge-Kutta, one stage at a time",
  source = "003_636de12a6b81385f.txt, \"Fourth-Order Runge-Kutta\"",
  steps = {
    {
      title = "Four looks at the slope",
      text = [[
Euler's method takes the slope at the start of a step and follows it blindly for the whole
step. Runge-Kutta 4 is more careful: it probes the slope four times. k₁ is the slope at the
start; k₂ is the slope at the midpoint, reached by following k₁ for half a step; k₃ is
the slope at the midpoint again, this time reached with the better guess k₂; k₄ is the
slope at the end, reached by following k₃ for a full step. The step then uses a weighted
average, counting the two midpoint slopes twice. The weights 1, 2, 2, 1 over 6 are
Simpson's rule (1, 4, 1 over 6) with the middle weight shared by the two midpoint
probes; when the slope depends on t alone, RK4 is exactly Simpson's rule.

We try it on y' = −2·t·y starting from y(0) = 1 (exact answer y = exp(−t²)), with one big
step of Δt = 0.5 s. rigidlab's ode.step calls our slope function; we record each call to
see the four stages, and compare them with the slides' formulas worked out by hand.]],
      formula = "k₁ = f(tₙ, yₙ)\n" ..
                "k₂ = f(tₙ + Δt/2, yₙ + Δt·k₁/2)\n" ..
                "k₃ = f(tₙ + Δt/2, yₙ + Δt·k₂/2)\n" ..
                "k₄ = f(tₙ + Δt, yₙ + Δt·k₃)\n" ..
                "yₙ₊₁ = yₙ + Δt/6·(k₁ + 2k₂ + 2k₃ + k₄)",
      run = function(ctx)
        local t0, y0, dt = 0, 1, 0.5
        local calls = {}
        local function recording_slope(t, y)
          local k = slope(t, y)
          calls[#calls + 1] = {t = t, y = y, k = k}
          return k
        end
        local y1 = ode.step("rk4", recording_slope, t0, y0, dt)

        -- The same stages by hand, straight from the slide's formulas.
        local k1 = slope(t0, y0)
        local k2 = slope(t0 + dt / 2, y0 + dt * k1 / 2)
        local k3 = slope(t0 + dt / 2, y0 + dt * k2 / 2)
        local k4 = slope(t0 + dt, y0 + dt * k3)
        local by_hand = {k1, k2, k3, k4}

        ctx:show("number of slope evaluations", #calls)
        ctx:expect("ode.step evaluates the slope 4 times", #calls, 4)
        local rows = {}
        for i, call in ipairs(calls) do
          rows[i] = {"k" .. i, call.t, call.y, call.k, by_hand[i]}
        end
        ctx:table({"stage", "t", "y probed", "slope (ode.step)", "slope (by hand)"}, rows)
        ctx:expect("stage times t, t+Δt/2, t+Δt/2, t+Δt",
                   {calls[1].t, calls[2].t, calls[3].t, calls[4].t}, {0, 0.25, 0.25, 0.5})
        ctx:expect("stage states 1, 1, 1 − 0.125, 1 − 0.21875",
                   {calls[1].y, calls[2].y, calls[3].y, calls[4].y}, {1, 1, 0.875, 0.78125})
        ctx:expect("k₁..k₄", {calls[1].k, calls[2].k, calls[3].k, calls[4].k},
                   {0, -0.5, -0.4375, -0.78125})

        local blended = y0 + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        ctx:show("weighted slope (k₁ + 2k₂ + 2k₃ + k₄)/6", (k1 + 2 * k2 + 2 * k3 + k4) / 6)
        ctx:show("y(0.5) from ode.step", y1)
        ctx:expect("y(0.5) = y₀ + Δt/6·(k₁ + 2k₂ + 2k₃ + k₄)", y1, blended)
        ctx:show("exact exp(−0.25)", exact(0.5))
        ctx:show("error of one RK4 step", y1 - exact(0.5))
        ctx:show("error of one Euler step (y₀ + Δt·k₁ = 1)", y0 + dt * k1 - exact(0.5))
      end,
    },
    {
      title = "Measuring the order",
      text = [[
"Fourth order" is a promise about how the error shrinks: halve the step and the error at a
fixed end time drops by 2⁴ = 16. Euler, a first-order method, only halves it. We can
measure this instead of taking it on trust: integrate to t = 1 s with n steps and with 2n
steps, and take log₂ of the ratio of the two errors. The result approaches the order as
the steps get small (for big steps the higher-order terms of the error still show).
ode.step also offers two second-order methods, midpoint and Heun, which land in between.

We accept a measured order within 0.05 of the theory, taken where the steps are small
enough for the leading error term to dominate: n = 20 → 40 for RK4 (smaller steps would
bring its error down toward the level where rounding makes the ratio noisy), n = 80 → 160
for the others.]],
      formula = "error ≈ C·Δtᵖ   ⇒   p ≈ log₂(error(Δt) / error(Δt/2))",
      run = function(ctx)
        local methods = {"euler", "midpoint", "heun", "rk4"}
        local rows = {}
        for _, n in ipairs({10, 20, 40, 80, 160}) do
          local row = {n, 1 / n}
          for _, method in ipairs(methods) do
            row[#row + 1] = error_at_one(method, n)
          end
          rows[#rows + 1] = row
        end
        ctx:table({"n", "Δt (s)", "Euler error", "midpoint error", "Heun error", "RK4 error"},
                  rows)
        local order_rows = {}
        for _, n in ipairs({10, 20, 40, 80}) do
          local row = {string.format("%d → %d", n, 2 * n)}
          for _, method in ipairs(methods) do row[#row + 1] = measured_order(method, n) end
          order_rows[#order_rows + 1] = row
        end
        ctx:table({"n", "Euler order", "midpoint order", "Heun order", "RK4 order"}, order_rows)
        ctx:expect("RK4 order (n = 20 → 40)", measured_order("rk4", 20), 4, {abs = 0.05})
        ctx:expect("Euler order (n = 80 → 160)", measured_order("euler", 80), 1, {abs = 0.05})
        ctx:expect("midpoint order (n = 80 → 160)", measured_order("midpoint", 80), 2,
                   {abs = 0.05})
        ctx:expect("Heun order (n = 80 → 160)", measured_order("heun", 80), 2, {abs = 0.05})
        ctx:show("Euler error (n = 160) / RK4 error (n = 10)",
                 error_at_one("euler", 160) / error_at_one("rk4", 10))
        ctx:say("Ten RK4 steps (40 slope evaluations) beat 160 Euler steps (160 evaluations).")
      end,
    },
  },
}
