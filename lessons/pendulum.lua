-- A pendulum as a motion constraint (000 "Motion constraint", "Degree of freedom"): a bob on a
-- hinge. Its small-angle period 2π√(L/g), the large-amplitude period 4√(L/g)·K(sin(θ₀/2))
-- with the complete elliptic integral K computed here twice (arithmetic-geometric mean and
-- power series), and both measured in a world at 60 Hz with each solver, with and without
-- substeps.

local L = 1            -- m, from the hinge to the bob's centre
local g = 9.81         -- m/s², rigidlab's default gravity
local mass = 1         -- kg
local radius = 0.05    -- m, the bob: a small solid sphere
local frame = 1 / 60   -- s
local amplitudes = {10, 30, 60, 80}                               -- degrees
local listed = {2.009893, 2.040990, 2.152875, 2.281886}           -- s, LESSONS.md's periods
local rounding = {abs = 5e-7, reason = "the values are given to 6 decimals"}

-- K(k) = ∫₀^{π/2} dφ / √(1 − k² sin²φ) by Gauss's arithmetic-geometric mean:
-- K = π / (2·AGM(1, √(1 − k²))); the mean converges quadratically (5 rounds reach 1e-16).
local function K_agm(k)
  local a, b = 1, math.sqrt(1 - k * k)
  while math.abs(a - b) > 1e-15 * a do a, b = (a + b) / 2, math.sqrt(a * b) end
  return math.pi / (2 * a)
end

-- The same integral by its power series K = (π/2)·Σ [(2n)!/(2²ⁿ(n!)²)]² k²ⁿ, a separate route
-- to the same number (slow for k near 1, quick enough for k = sin 40° = 0.64).
local function K_series(k)
  local sum, c, n = 1, 1, 0
  repeat
    n = n + 1
    c = c * (2 * n - 1) / (2 * n)          -- (2n)!/(2²ⁿ(n!)²), term by term
    local term = c * c * k ^ (2 * n)
    sum = sum + term
  until term < 1e-17
  return math.pi / 2 * sum
end

local function period(length, theta0_deg)
  return 4 * math.sqrt(length / g) * K_agm(math.sin(math.rad(theta0_deg) / 2))
end

-- The bob is a sphere, not a point: about the hinge its inertia is mL² + (2/5)mr², so it swings
-- like a point mass on the equivalent length I_hinge/(mL) (a physical pendulum).
local I_hinge = mass * L ^ 2 + 2 / 5 * mass * radius ^ 2
local L_eq = I_hinge / (mass * L)

-- A world with the bob released from rest at θ₀ (from the downward vertical, toward +x) on a
-- hinge about z at the origin.
local function hinged_bob(theta0_deg, solver, substeps)
  local w = world{solver = solver, substeps = substeps}
  local th = math.rad(theta0_deg)
  local bob = w:add(body.sphere{mass = mass, radius = radius,
                                position = vec3(L * math.sin(th), -L * math.cos(th), 0)})
  local hinge = w:add_joint{type = "hinge", a = bob, anchor = vec3(0, 0, 0), axis = vec3(0, 0, 1)}
  return w, bob, hinge
end

local function angle_of(bob) return math.atan(bob.position.x, -bob.position.y) end

-- Swings `periods` full periods (as the closed form counts them, plus a margin) and measures
-- the period from the times θ crosses zero going toward −x, each found by linear
-- interpolation between frames (near θ = 0 the swing is almost straight: θ̈ ∝ sin θ ≈ 0).
-- Also returns the trace of θ (degrees), the largest gap |θ₀ + angle − θ| between the hinge's
-- own angle and the bob's direction from the hinge, and the joint's largest position error.
local function measure(theta0_deg, solver, substeps, periods)
  local w, bob, hinge = hinged_bob(theta0_deg, solver, substeps)
  local steps = math.ceil((periods + 0.6) * period(L_eq, theta0_deg) / frame)
  local crossings, trace_t, trace_y, gap, drift = {}, {0}, {theta0_deg}, 0, 0
  local before = math.rad(theta0_deg)
  for i = 1, steps do
    w:step(frame)
    local now = angle_of(bob)
    gap = math.max(gap, math.abs(math.rad(theta0_deg) + hinge.angle - now))
    drift = math.max(drift, (hinge:error()))
    if before > 0 and now <= 0 then
      crossings[#crossings + 1] = w.time - frame * now / (now - before)
    end
    before = now
    trace_t[i + 1], trace_y[i + 1] = w.time, math.deg(now)
  end
  local measured = (crossings[#crossings] - crossings[1]) / (#crossings - 1)
  return measured, trace_t, trace_y, gap, drift, #crossings - 1
end

return lesson{
  id = "pendulum",
  title = "A pendulum on a hinge: the period, small and large swings",
  source = "000_3bd95e59483beea1.txt, \"Motion constraint\", \"Degree of freedom\"",
  steps = {
    {
      title = "A body that is not free: the small-angle period",
      text = [[
000 "Motion constraint" opens the part on joints with bodies that cannot move on their own:
a door on its hinges, a wheel on its axle. A hinge leaves one of the six freedoms of
000 "Degree of freedom": the rotation about its axis. A bob hung 1 m from a hinge therefore
has one coordinate, the angle θ from the downward vertical, and gravity's torque about the
hinge gives mL²θ̈ = −mgL sin θ, that is θ̈ = −(g/L) sin θ.

For small swings sin θ ≈ θ, the motion is harmonic with ω₀ = √(g/L), and the period does not
depend on the amplitude: T₀ = 2π√(L/g). With L = 1 m and g = 9.81 m/s² that is 2.006067 s.]],
      formula = "θ̈ = −(g/L)·sin θ,   small θ:  T₀ = 2π·√(L/g)",
      run = function(ctx)
        ctx:show("L (m)", L)
        ctx:show("g (m/s²)", g)
        local T0 = 2 * math.pi * math.sqrt(L / g)
        ctx:show("T₀ = 2π√(L/g) (s)", T0)
        ctx:expect("T₀ as listed", T0, 2.006067, rounding)
      end,
    },
    {
      title = "Large swings: the elliptic integral",
      text = [[
Far from the bottom, sin θ < θ: gravity pulls back less than the harmonic law says, and the
pendulum takes longer. Energy conservation gives θ̇ as a function of θ, and the time for a
quarter swing is an integral that the substitution sin(θ/2) = k·sin φ, with k = sin(θ₀/2),
turns into the complete elliptic integral of the first kind K(k). So the period is
T = 4√(L/g)·K(sin(θ₀/2)), which tends to T₀ as θ₀ → 0 since K(0) = π/2.

K has no elementary closed form, so we compute it two independent ways: Gauss's
arithmetic-geometric mean, K = π/(2·AGM(1, √(1 − k²))), and the power series
K = (π/2)·Σ [(2n)!/(2²ⁿ(n!)²)]²·k²ⁿ. They must agree to rounding, and the periods must be
the listed 2.009893, 2.040990, 2.152875 and 2.281886 s at 10°, 30°, 60° and 80°.]],
      formula = "T = 4·√(L/g)·K(k),  k = sin(θ₀/2),  K(k) = ∫₀^{π/2} dφ / √(1 − k²sin²φ)",
      run = function(ctx)
        local rows = {}
        for i, deg in ipairs(amplitudes) do
          local k = math.sin(math.rad(deg) / 2)
          rows[i] = {deg, k, K_agm(k), K_series(k), period(L, deg), period(L, deg) / period(L, 0) - 1}
        end
        ctx:table({"θ₀ (°)", "k", "K by AGM", "K by series", "T (s)", "T/T₀ − 1"}, rows)
        for i, deg in ipairs(amplitudes) do
          local k = math.sin(math.rad(deg) / 2)
          ctx:expect(string.format("K(sin %d°): AGM = series", deg / 2), K_agm(k), K_series(k),
                     {rel = 1e-14, reason = "two routes to one number, to rounding"})
          ctx:expect(string.format("T at %d° as listed", deg), period(L, deg), listed[i], rounding)
        end
      end,
    },
    {
      title = "The bob is a small ball, not a point",
      text = [[
rigidlab's bodies have a size: our bob is a solid sphere of 1 kg and radius 0.05 m. Its own
inertia (2/5)mr² = 0.001 kg·m² adds to mL² about the hinge, so it swings like a point mass on
the equivalent length L_eq = I_hinge/(mL) = 1.001 m (a physical pendulum), which makes every
period √1.001 times longer: 0.05 % more. These are the periods the world must reproduce,
for the ball released at rest from (L sin θ₀, −L cos θ₀), the hinge at the origin.]],
      formula = "I_hinge = mL² + (2/5)·m·r²,   L_eq = I_hinge / (m·L),\nT = 4·√(L_eq/g)·K(k)",
      run = function(ctx)
        ctx:show("bob: mass (kg)", mass)
        ctx:show("bob: radius (m)", radius)
        ctx:show("I_hinge (kg·m²)", I_hinge)
        ctx:show("L_eq (m)", L_eq)
        ctx:expect("L_eq = 1 + 0.4·0.05²", L_eq, 1.001)
        local rows = {}
        for i, deg in ipairs(amplitudes) do
          local th = math.rad(deg)
          rows[i] = {deg, L * math.sin(th), -L * math.cos(th), period(L, deg), period(L_eq, deg)}
        end
        ctx:table({"θ₀ (°)", "starts at x (m)", "y (m)", "point mass (s)", "the ball (s)"}, rows)
      end,
    },
    {
      title = "Measured in a world at 60 Hz",
      text = [[
Now the hinge itself: w:add_joint{type = "hinge", anchor = origin, axis = z} holds the ball
1 m from the origin, released at rest at θ₀ toward +x. We step at 60 Hz (Δt = 1/60 s) and
time two full swings from the moments θ crosses zero, with each solver (soft_step, the
default, and sequential_impulses, 000's three steps) and with 1 or 4 substeps ("sub").

What to expect: each step moves the bob along a straight chord that the joint then pulls
back onto the circle. The error this leaves is of order (ωΔt)², ω the swing's rate, so 4
substeps should be about 16 times closer. We require 0.2 % with 4 substeps (the joints
issue's bound) and 1 % with one; the table shows how much closer the world actually is.

The last column is the joint's drift, the largest distance j:error() reported between the
hinge point on the bob and the hinge point in the world. The hinge's angle (j.angle, from the
bob's orientation) and the bob's direction from the origin can differ by at most that
drift over L. sequential_impulses at one substep lets the hinge stretch by millimetres
at the larger swings; soft_step's relax sweeps and position feedback keep it far tighter.]],
      formula = "hinge: the bob's anchor point stays at the origin,\n       only rotation about z is free",
      run = function(ctx)
        local rows, worst, excess, drift4 = {}, {}, 0, 0
        for _, solver in ipairs{"soft_step", "sequential_impulses"} do
          for _, substeps in ipairs{1, 4} do
            local key = solver .. substeps
            worst[key] = 0
            for _, deg in ipairs(amplitudes) do
              local measured, _, _, gap, drift = measure(deg, solver, substeps, 2)
              local want = period(L_eq, deg)
              local err = measured / want - 1
              worst[key] = math.max(worst[key], math.abs(err))
              rows[#rows + 1] = {solver, substeps, deg, string.format("%.6f", measured),
                                 string.format("%.6f", want), string.format("%+.4f", 100 * err),
                                 string.format("%.4f", 1000 * drift)}
              excess = math.max(excess, gap - 1.01 * drift / L)
              if substeps == 4 and solver == "soft_step" then drift4 = math.max(drift4, drift) end
            end
          end
        end
        ctx:table({"solver", "sub", "θ₀ (°)", "measured (s)", "closed (s)", "err (%)",
                   "drift (mm)"}, rows)
        ctx:expect_range("the hinge's angle is the bob's direction, up to the drift (rad)", excess,
                         nil, 1e-12)
        ctx:expect_range("soft_step, 4 substeps: the hinge drifts less than 0.1 mm (m)", drift4, nil,
                         1e-4)
        for _, solver in ipairs{"soft_step", "sequential_impulses"} do
          ctx:expect_range(solver .. ", 4 substeps: largest period error", worst[solver .. 4],
                           nil, 0.002)
          ctx:expect_range(solver .. ", 1 substep: largest period error", worst[solver .. 1],
                           nil, 0.01)
        end
      end,
    },
    {
      title = "How the swing looks",
      text = [[
At 80° the swing (soft_step, 4 substeps) lags the small-angle cosine θ₀·cos(2πt/T₀) more at
every period: after three periods of the large swing the harmonic one is 0.83 s, more than a
third of a period, ahead.]],
      run = function(ctx)
        local measured, t, y = measure(80, "soft_step", 4, 3)
        local T0 = 2 * math.pi * math.sqrt(L_eq / g)
        local cosine = {}
        for i, ti in ipairs(t) do cosine[i] = 80 * math.cos(2 * math.pi * ti / T0) end
        ctx:plot{{x = t, y = y, label = "the world, θ₀ = 80°"},
                 {x = t, y = cosine, label = "small-angle cosine"},
                 title = "θ(t) at 80°", xlabel = "t (s)", ylabel = "θ (°)", height = 10}
        ctx:show("measured period at 80° (s)", measured)
        ctx:show("small-angle period of the ball (s)", T0)
        ctx:expect("three large periods exceed three small ones by", 3 * (period(L_eq, 80) - T0),
                   3 * (2.281886 - 2.006067) * math.sqrt(L_eq),
                   {abs = 3e-6, reason = "the listed periods are given to 6 decimals"})
      end,
    },
  },
}
