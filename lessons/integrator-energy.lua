-- Energy of a mass on a spring under the three integrators of motion.simulate: explicit Euler
-- pumps energy in, semi-implicit Euler keeps it in a fixed band, RK4 leaks a tiny amount.
-- Each behaviour is checked against its closed form for the linear oscillator.

local mass = 2          -- kg
local stiffness = 8     -- N/m
local x0 = 0.5          -- m, released at rest
local dt = 0.05         -- s
local steps = 200       -- 10 s
local omega = math.sqrt(stiffness / mass)   -- rad/s, natural angular frequency
local theta = omega * dt                    -- ωΔt, the step measured in radians of the swing

local function spring_accel(_, x, _) return -(stiffness / mass) * x end

-- Total energy E = ½mv² + ½kx² (J).
local function energy(x, v) return 0.5 * mass * v * v + 0.5 * stiffness * x * x end

local function energies(method)
  local trajectory = motion.simulate{method = method, accel = spring_accel, x0 = x0, v0 = 0,
                                     dt = dt, steps = steps}
  local list = {}
  for i = 1, #trajectory.t do list[i] = energy(trajectory.x[i], trajectory.v[i]) end
  return list, trajectory
end

local initial_energy = 0.5 * stiffness * x0 * x0   -- J, all potential at release

local function extremes(list)
  local low, high = math.huge, -math.huge
  for _, value in ipairs(list) do low, high = math.min(low, value), math.max(high, value) end
  return low, high
end

return lesson{
  id = "integrator-energy",
  title = "Energy drift of Euler, semi-implicit Euler and RK4",
  source = "003_636de12a6b81385f.txt, \"Explicit Euler\", \"Fourth-Order Runge-Kutta\", " ..
           "\"Energy\"; 000_3bd95e59483beea1.txt, \"Particle system\"",
  steps = {
    {
      title = "A spring that should swing forever",
      text = [[
A 2 kg mass on a spring of stiffness 8 N/m is pulled 0.5 m aside and let go. With no
friction its energy, E = ½mv² + ½kx², can only slosh back and forth between the moving
mass and the stretched spring; the total must stay at its starting value (003, "Energy":
an isolated system keeps its total energy). That makes the spring a perfect lie
detector for integrators: any change in E is numerical error.

The exact motion is x = x₀·cos(ωt) with ω = √(k/m) = 2 rad/s, one swing every π
seconds. We take steps of 0.05 s, so each step advances the swing by ωΔt = 0.1 rad.]],
      formula = "x'' = −(k/m)·x,   ω = √(k/m),   E = ½mv² + ½kx² = ½kx₀²",
      run = function(ctx)
        ctx:show("ω (rad/s)", omega)
        ctx:show("period 2π/ω (s)", 2 * math.pi / omega)
        ctx:show("ωΔt (rad)", theta)
        ctx:show("E₀ = ½kx₀² (J)", initial_energy)
        local euler, semi, rk4 = energies("euler"), energies("semi_implicit"), energies("rk4")
        ctx:expect("every method starts from E₀", {euler[1], semi[1], rk4[1]},
                   {initial_energy, initial_energy, initial_energy})
      end,
    },
    {
      title = "Energy over ten seconds",
      text = [[
Here are the three methods side by side, sampled once a second. Explicit Euler's energy
climbs without stopping: the simulated mass swings wider and wider, a spring that creates
energy from nothing. Semi-implicit Euler wobbles a few percent above and below the true
value but never wanders off. RK4 looks perfect at this precision; its error is real but
lives in the sixth decimal.]],
      formula = "E(t) = ½m·v(t)² + ½k·x(t)²   (exact: constant 1 J)",
      run = function(ctx)
        local euler, semi, rk4 = energies("euler"), energies("semi_implicit"), energies("rk4")
        local rows, times = {}, {}
        for i = 1, steps + 1 do times[i] = (i - 1) * dt end
        for i = 1, steps + 1, 20 do
          rows[#rows + 1] = {times[i], euler[i], semi[i], rk4[i]}
        end
        ctx:table({"t (s)", "explicit Euler E (J)", "semi-implicit E (J)", "RK4 E (J)"}, rows)
        ctx:plot{{x = times, y = euler, label = "explicit Euler"},
                 {x = times, y = semi, label = "semi-implicit Euler"},
                 {x = times, y = rk4, label = "RK4"},
                 title = "Spring energy (J)", xlabel = "t (s)", ylabel = "E (J)", height = 10}
        ctx:plot{{x = times, y = semi, label = "semi-implicit Euler"},
                 {x = times, y = rk4, label = "RK4"},
                 title = "Zoom: the two that stay near 1 J", xlabel = "t (s)",
                 ylabel = "E (J)", height = 10}
        ctx:show("explicit Euler E(10 s) (J)", euler[steps + 1])
        ctx:show("semi-implicit E(10 s) (J)", semi[steps + 1])
        ctx:show("RK4 E(10 s) (J)", rk4[steps + 1])
      end,
    },
    {
      title = "Explicit Euler multiplies the energy by 1 + (ωΔt)² every step",
      text = [[
Why does explicit Euler gain energy, and by how much? Measure position in the same units
as velocity, u = ω·x, so that E = ½m(u² + v²) is a squared length. One explicit step maps
(u, v) to (u + ωΔt·v, v − ωΔt·u): a rotation by the angle ωΔt, but with the cosine replaced
by 1 and the sine by ωΔt. That stretches the vector by √(1 + (ωΔt)²), so E grows by the
factor 1 + (ωΔt)² at every single step, no matter where the mass is. Here that is 1.01
per step, and 1.01²⁰⁰ ≈ 7.3 after 200 steps. Smaller steps slow the growth, they never
stop it.]],
      formula = "Eₙ₊₁ = (1 + (ωΔt)²)·Eₙ   ⇒   Eₙ = E₀·(1 + (ωΔt)²)ⁿ",
      run = function(ctx)
        local euler = energies("euler")
        local factor = 1 + theta * theta
        local worst = 0
        for i = 1, steps do worst = math.max(worst, math.abs(euler[i + 1] / euler[i] - factor)) end
        ctx:show("predicted factor 1 + (ωΔt)²", factor)
        ctx:show("measured factor, first step", euler[2] / euler[1])
        ctx:show("measured factor, last step", euler[steps + 1] / euler[steps])
        ctx:show("largest deviation of any step's factor", worst)
        ctx:expect("every step's factor is 1 + (ωΔt)² (to rounding)", worst, 0, {abs = 1e-12})
        ctx:expect("E(10 s) = E₀·(1 + (ωΔt)²)²⁰⁰", euler[steps + 1],
                   initial_energy * factor ^ steps, 1e-12)
      end,
    },
    {
      title = "Semi-implicit Euler stays inside a band",
      text = [[
Semi-implicit Euler (velocity first, then position with the new velocity; the update the
slides of 003 use) does not conserve E exactly, but it conserves something very close to
it: the "shadow energy" C = v² + ω²x² − Δt·ω²·x·v is unchanged by every step, exactly.
Since E = ½m(v² + ω²x²), and the extra term −Δt·ω²·x·v can at most shift C by the fraction
ωΔt/2 of v² + ω²x², the true energy is trapped between ½mC/(1 + ωΔt/2) and
½mC/(1 − ωΔt/2). For our numbers that is 0.952 J to 1.053 J: a wobble of about ±5%, for
as long as you care to run. This is why games prefer it, and halving Δt halves the band.]],
      formula = "C = v² + ω²x² − Δt·ω²·x·v = const\n" ..
                "½mC/(1 + ωΔt/2) ≤ E ≤ ½mC/(1 − ωΔt/2)",
      run = function(ctx)
        local semi, trajectory = energies("semi_implicit")
        local function shadow(i)
          local x, v = trajectory.x[i], trajectory.v[i]
          return v * v + omega * omega * x * x - dt * omega * omega * x * v
        end
        local shadow0 = omega * omega * x0 * x0   -- v₀ = 0
        local worst = 0
        for i = 1, steps + 1 do worst = math.max(worst, math.abs(shadow(i) - shadow0)) end
        local lower = 0.5 * mass * shadow0 / (1 + theta / 2)
        local upper = 0.5 * mass * shadow0 / (1 - theta / 2)
        local low, high = extremes(semi)
        ctx:show("C at the start (m²/s²)", shadow0)
        ctx:show("largest change of C over 200 steps", worst)
        ctx:expect("C is conserved (to rounding)", worst, 0, {abs = 1e-12})
        ctx:show("band: lower edge (J)", lower)
        ctx:show("band: upper edge (J)", upper)
        ctx:show("lowest E reached (J)", low)
        ctx:show("highest E reached (J)", high)
        ctx:expect("E never leaves the band (distance outside it)",
                   math.max(0, high - upper, lower - low), 0, {abs = 1e-12})
        ctx:say("E is only sampled once per step (a swing takes about 63 steps), so the")
        ctx:say("extremes come close to the edges but not exactly; hence rel 1e-4 here:")
        ctx:expect("highest E ≈ upper edge", high, upper, 1e-4)
        ctx:expect("lowest E ≈ lower edge", low, lower, 1e-4)
      end,
    },
    {
      title = "RK4 leaks energy, very slowly",
      text = [[
RK4 is not energy-conserving either: each step multiplies the energy of this oscillator by
|R(iωΔt)|², where R(z) = 1 + z + z²/2 + z³/6 + z⁴/24 is RK4's step polynomial. Working out
that modulus gives 1 − (ωΔt)⁶/72 + (ωΔt)⁸/576, just below 1. With ωΔt = 0.1 the loss is
about 1.4e-8 per step, 2.8 parts per million after 200 steps: far better than either
Euler method over this run, though over a very long run, or with big steps, the slow
drain becomes visible, while semi-implicit Euler's band never grows.]],
      formula = "Eₙ₊₁ = |R(iωΔt)|²·Eₙ,   |R(iθ)|² = 1 − θ⁶/72 + θ⁸/576",
      run = function(ctx)
        local rk4, trajectory = energies("rk4")
        local factor = 1 - theta ^ 6 / 72 + theta ^ 8 / 576
        ctx:show("predicted factor per step", factor)
        ctx:show("measured factor, first step", rk4[2] / rk4[1])
        ctx:expect("E(10 s) = E₀·(1 − θ⁶/72 + θ⁸/576)²⁰⁰", rk4[steps + 1],
                   initial_energy * factor ^ steps, 1e-12)
        ctx:show("relative drift after 10 s", rk4[steps + 1] / initial_energy - 1)
        local t_end = steps * dt
        ctx:show("RK4 x(10 s) (m)", trajectory.x[steps + 1])
        ctx:show("exact x₀·cos(ω·10 s) (m)", x0 * math.cos(omega * t_end))
        ctx:say("RK4's global error is O(Δt⁴); with ωΔt = 0.1 over 20 rad of swing it is")
        ctx:say("about 1e-5 m, so the position is checked to 1e-4 m:")
        ctx:expect("RK4 x(10 s) ≈ x₀·cos(ωt)", trajectory.x[steps + 1],
                   x0 * math.cos(omega * t_end), {abs = 1e-4})
      end,
    },
  },
}
