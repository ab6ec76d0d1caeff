-- An elbow driven by a muscle (document 000 "Muscle forces"): a contractile element scaled by
-- the activation, a nonlinear parallel spring and a damper, pulling along its line of action;
-- the torque at the hinge is a virtual force τ = Jᵀ F. Activation steps up three times and
-- the forearm settles each time at the angle where muscle and gravity balance, found
-- independently by bisection on the static balance.

local g = 9.81
local m, length = 1.5, 0.30          -- forearm: kg, m (a uniform rod)
local c = length / 2                 -- its COM from the elbow (m)
local h, r = 0.25, 0.04              -- muscle origin above the elbow, insertion along the forearm
local F_max = 500                    -- N, the contractile element's largest force
local l_opt, width = 0.30, 0.15      -- m, length of largest force; width of the force–length curve
local k_pe, l_slack = 5e4, 0.28      -- N/m², m: the parallel spring, taut beyond l_slack
local b = 300                        -- N·s/m, the damper
local origin = vec3(0, h, 0)         -- on the upper arm (the base), world
local insertion = vec3(r, 0, 0)      -- on the forearm, link frame
local activations = {0.2, 0.4, 0.8}  -- each held for `hold` seconds
local hold, dt = 3.0, 0.002

-- The muscle's length and its rate of change for elbow angle q (from the forearm horizontal)
-- and rate qd: ℓ² = r² + h² − 2 h r sin q.
local function muscle_length(q) return math.sqrt(r * r + h * h - 2 * h * r * math.sin(q)) end
local function moment_arm(q) return h * r * math.cos(q) / muscle_length(q) end  -- −dℓ/dq

-- Tension (N, pulling only): contractile element a·F_max·f_L(ℓ) with a Gaussian force–length
-- curve, parallel spring k_pe (ℓ − ℓ_slack)² when stretched, damper b ℓ̇.
local function force_length(l) return math.exp(-((l / l_opt - 1) / width) ^ 2) end
local function tension(a, l, l_rate)
  local spring = l > l_slack and k_pe * (l - l_slack) ^ 2 or 0
  return math.max(0, a * F_max * force_length(l) + spring + b * l_rate)
end

local function forearm()
  local art = articulation{gravity = vec3(0, -g, 0), integrator = "rk4"}
  art:add_link{name = "forearm", mass = m, com = vec3(c, 0, 0),
               inertia = mat3.diag(0, m * length ^ 2 / 12, m * length ^ 2 / 12)}
  return art
end

-- The muscle's force on the forearm (world), from the stage state: along the line from the
-- insertion to the origin, with ℓ̇ = −u·v_insertion for the unit vector u towards the origin.
local function muscle_force(art, a)
  local link = art.links[1]
  local toward = origin - link:to_world(insertion)
  local l = toward:norm()
  local u = toward / l
  local l_rate = -u:dot(link:point_velocity(insertion))
  return u * tension(a, l, l_rate)
end

-- The angle where the muscle's torque at rest balances gravity, by bisection on
-- F(ℓ(q)) h r / ℓ(q) − m g c = 0 (both torques carry cos q).
local function balance_angle(a)
  local function excess(q) return tension(a, muscle_length(q), 0) * moment_arm(q) / math.cos(q)
                                  - m * g * c end
  local low, high = -1.2, 1.2
  assert(excess(low) > 0 and excess(high) < 0, "the balance is not bracketed")
  for _ = 1, 60 do
    local mid = 0.5 * (low + high)
    if excess(mid) > 0 then low = mid else high = mid end
  end
  return 0.5 * (low + high)
end

return lesson{
  id = "muscle",
  title = "A muscle drives the elbow",
  source = "000_3bd95e59483beea1.txt, \"Muscle forces\", \"Virtual forces\"",
  steps = {
    {
      title = "Where the muscle pulls",
      text = [[
A forearm (a 0.30 m rod of 1.5 kg) hangs on an elbow hinge; the upper arm above it is the
fixed base. A muscle runs from a point 0.25 m up the upper arm to a point 4 cm along the
forearm, like a biceps. A muscle only pulls, along its own line. At the joint that pull is a
torque: its tension times the moment arm, the distance from the hinge to the line, which is
also how fast the muscle shortens per radian of flexion, −dℓ/dq. With q the forearm's angle
above the horizontal, ℓ² = r² + h² − 2hr sin q, so the moment arm is hr cos q / ℓ.

Document 000 "Virtual forces" gives the same torque without any geometry: τ = Jᵀ F for the
force F at the insertion point (art:virtual_force).]],
      formula = "ℓ(q) = √(r² + h² − 2 h r sin q)     moment arm = −dℓ/dq = h r cos q / ℓ",
      run = function(ctx)
        local art = forearm()
        local q = 0.3
        art:set_state({q}, {0})
        local toward = origin - art.links[1]:to_world(insertion)
        ctx:expect("muscle length (m)", toward:norm(), muscle_length(q), 1e-14)
        local step = 1e-6
        local slope = (muscle_length(q + step) - muscle_length(q - step)) / (2 * step)
        ctx:expect("moment arm = −dℓ/dq (m)", moment_arm(q), -slope, 1e-9)
        local F = 50
        local tau = art:virtual_force(1, insertion, toward * (F / toward:norm()))
        ctx:expect("τ = Jᵀ F for 50 N (N·m)", tau[1], F * moment_arm(q), 1e-13)
      end,
    },
    {
      title = "Three elements",
      text = [[
The slide says a muscle model is usually "two nonlinear springs and one damper". That is
Hill's muscle: a contractile element, which produces the active force, in series with an
elastic tendon (the first spring), and a parallel elastic element, the passive tissue (the
second spring); the damping stands for the contractile element's force falling with its
shortening speed. We keep the tendon rigid and use:
 contractile element  a · F_max · exp(−((ℓ/ℓ_opt − 1)/w)²), activation a from 0 to 1
 parallel spring      k (ℓ − ℓ_slack)², only when stretched beyond ℓ_slack
 damper               b ℓ̇
The active force depends on the length: a muscle pulls hardest near its optimal length and
weaker when it is shorter. That makes the arm settle: flexing shortens the muscle, so the
same activation pulls less, until its torque equals gravity's.]],
      run = function(ctx)
        local rows = {}
        for _, q in ipairs({-0.6, -0.3, 0, 0.3, 0.6}) do
          local l = muscle_length(q)
          rows[#rows + 1] = {q, l, force_length(l), tension(0, l, 0), moment_arm(q)}
        end
        ctx:table({"q (rad)", "ℓ (m)", "f_L(ℓ)", "passive (N)", "moment arm (m)"}, rows)
        ctx:expect("f_L(ℓ_opt)", force_length(l_opt), 1)
      end,
    },
    {
      title = "Activation steps and the angle the arm settles at",
      text = [[
A control function computes the muscle's tension at every evaluation of the dynamics (each
RK4 stage) from the forearm's current angle and speed, and returns its torque τ = Jᵀ F.
Starting from the forearm horizontal and at rest, the activation is 0.2, then 0.4, then
0.8, three seconds each. Each time the arm swings, is damped, and settles where the static
balance F(ℓ(q)) · hr cos q / ℓ = m g c cos q holds. Those angles we find separately, by
bisection on the muscle law and the gravity torque alone, without simulating anything.]],
      formula = "F(ℓ) h r / ℓ(q) = m g c",
      run = function(ctx)
        local art = forearm()
        local level = activations[1]
        art:add_control(function(a) return a:virtual_force(1, insertion, muscle_force(a, level)) end)
        local times, angles, rows = {0}, {0}, {}
        for _, a in ipairs(activations) do
          level = a
          for _ = 1, math.floor(hold / dt + 0.5) do
            art:step(dt)
            times[#times + 1], angles[#angles + 1] = art.time, art.q[1]
          end
          local want = balance_angle(a)
          rows[#rows + 1] = {a, art.q[1], want, math.deg(want)}
          ctx:expect(string.format("settled angle at a = %.1f (rad)", a), art.q[1], want,
                     {abs = 1e-5})
        end
        ctx:table({"activation", "simulated q (rad)", "balance (rad)", "balance (°)"}, rows)
        plot.lines{{x = times, y = angles, label = "elbow angle q"},
                   title = "Forearm angle as the activation steps 0.2, 0.4, 0.8",
                   xlabel = "t (s)", ylabel = "q (rad)"}
      end,
    },
  },
}
