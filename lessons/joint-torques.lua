-- A two-link arm actuated the three ways of document 000: joint torques (a motor at each
-- joint), gravity compensation by inverse dynamics, and a virtual force at the hand turned
-- into joint torques τ = Jᵀ F that hold a weight. Checked against the arm's closed forms.

local g = 9.81
local L1, m1 = 0.30, 2.0    -- upper arm: length (m), mass (kg), a uniform rod
local L2, m2 = 0.25, 1.5    -- forearm
local weight = 0.5          -- kg, hung at the hand in the last step
local q = {0.4, 0.6}        -- rad: shoulder from the horizontal, elbow from the upper arm

local function rod(m, l) return mat3.diag(0, m * l * l / 12, m * l * l / 12) end  -- along x

-- The arm in the vertical x-y plane: shoulder at the origin, hinges about z, each link along
-- its own x axis; with `load`, a point mass on a fixed joint at the hand.
local function arm(load)
  local art = articulation{gravity = vec3(0, -g, 0), integrator = "rk4"}
  local upper = art:add_link{mass = m1, com = vec3(L1 / 2, 0, 0), inertia = rod(m1, L1)}
  local fore = art:add_link{parent = upper, origin = vec3(L1, 0, 0), mass = m2,
                            com = vec3(L2 / 2, 0, 0), inertia = rod(m2, L2)}
  if load then
    art:add_link{parent = fore, joint = "fixed", origin = vec3(L2, 0, 0), mass = load}
  end
  art:set_state(q, {0, 0})
  return art
end

local hand = vec3(L2, 0, 0)   -- in the forearm's frame

-- 2 x 2 solve for the check of q̈ = M⁻¹(τ − g).
local function solve2(M, b)
  local det = M[1][1] * M[2][2] - M[1][2] * M[2][1]
  return {(M[2][2] * b[1] - M[1][2] * b[2]) / det, (M[1][1] * b[2] - M[2][1] * b[1]) / det}
end

local c1, c12 = math.cos(q[1]), math.cos(q[1] + q[2])
local s1, s12 = math.sin(q[1]), math.sin(q[1] + q[2])

return lesson{
  id = "joint-torques",
  title = "Joint torques, external and virtual forces on a two-link arm",
  source = "000_3bd95e59483beea1.txt, \"Joint torques\", \"External forces\", " ..
           "\"Virtual forces\"",
  steps = {
    {
      title = "Holding the arm still: gravity compensation",
      text = [[
An arm of two rods (upper arm 0.30 m, 2 kg; forearm 0.25 m, 1.5 kg) hinged at the shoulder
and the elbow, raised 0.4 rad above the horizontal with the elbow bent 0.6 rad. Document 000
"Joint torques" puts a motor at each joint. Which torques hold this pose? At rest nothing
accelerates, so the motors must cancel gravity exactly: τ = g(q), the inverse dynamics with
q̇ = 0 and q̈ = 0 (recursive Newton-Euler). For two rods it is the weight of everything
beyond each joint times its horizontal lever arm:
 τ₂ = m₂ g (L₂/2) cos(q₁+q₂)
 τ₁ = (m₁ L₁/2 + m₂ L₁) g cos q₁ + τ₂
Held by these torques, the arm must not move at all: q̈ = 0, and a second of simulation
leaves it where it was.]],
      run = function(ctx)
        local art = arm()
        local tau = art:inverse_dynamics({0, 0})
        local tau2 = m2 * g * L2 / 2 * c12
        local tau1 = (m1 * L1 / 2 + m2 * L1) * g * c1 + tau2
        ctx:expect("τ = g(q) (N·m)", tau, {tau1, tau2}, 1e-12)
        ctx:expect("q̈ with τ = g(q)", art:forward_dynamics(tau), {0, 0}, {abs = 1e-12})
        local falling = art:forward_dynamics({0, 0})
        ctx:show("q̈ without motors (rad/s²)", falling)
        art:set_torques(tau)
        art:step(0.001, 1000)
        ctx:expect("q after 1 s held (rad)", art.q, q, {abs = 1e-10})
      end,
    },
    {
      title = "A motor at the elbow moves the shoulder too",
      text = [[
Add 0.5 N·m at the elbow on top of the compensation. Only the elbow is driven, yet the
shoulder accelerates as well: the forearm pushes back on the upper arm (the off-diagonal
terms of the mass matrix). The accelerations solve M(q) q̈ = τ − g(q): with gravity
cancelled, q̈ = M⁻¹ (0, 0.5). The articulated-body algorithm finds them without forming M.]],
      formula = "M(q) q̈ + C(q, q̇) q̇ + g(q) = τ",
      run = function(ctx)
        local art = arm()
        local g_q = art:bias_forces()
        local qdd = art:forward_dynamics({g_q[1], g_q[2] + 0.5})
        local M = art:mass_matrix()
        ctx:table({"M (kg·m²)", ""}, M)
        ctx:show("q̈ (rad/s²)", qdd)
        ctx:expect("q̈ = M⁻¹ (0, 0.5)", qdd, solve2(M, {0, 0.5}), 1e-12)
        ctx:expect_range("q̈₁ < 0: the shoulder turns back (the forearm's reaction)", qdd[1],
                         nil, 0)
      end,
    },
    {
      title = "An external force at the hand and the Jacobian",
      text = [[
Document 000 "External forces" pushes on a body from outside, like a puppeteer; "Virtual
forces" gets the same effect from the joint motors instead, through the Jacobian J(q) that
maps joint rates to the hand's velocity, v_hand = J q̇. By the principle of virtual work the
torques that act like a force F at the hand are τ = Jᵀ F: both do the same work for any
motion. For the planar arm the hand's velocity rows are the derivatives of its position
(L₁ cos q₁ + L₂ cos(q₁+q₂), L₁ sin q₁ + L₂ sin(q₁+q₂)):
 J = [ −L₁ sin q₁ − L₂ sin(q₁+q₂)   −L₂ sin(q₁+q₂) ]
     [  L₁ cos q₁ + L₂ cos(q₁+q₂)    L₂ cos(q₁+q₂) ]
and rows 4 to 6 of art:jacobian, the angular velocity, are (0, 0), (0, 0), (1, 1).]],
      run = function(ctx)
        local art = arm()
        local J = art:jacobian(2, hand)
        ctx:table({"∂/∂q̇₁", "∂/∂q̇₂"}, J)
        ctx:expect("hand position", art.links[2]:to_world(hand),
                   vec3(L1 * c1 + L2 * c12, L1 * s1 + L2 * s12, 0), 1e-14)
        local want = {{-L1 * s1 - L2 * s12, -L2 * s12}, {L1 * c1 + L2 * c12, L2 * c12},
                      {0, 0}, {0, 0}, {0, 0}, {1, 1}}
        ctx:expect("J", J, want, 1e-14)
        local F = vec3(2, -3, 0)
        ctx:expect("virtual force τ = Jᵀ F", art:virtual_force(2, hand, F),
                   {J[1][1] * F.x + J[2][1] * F.y, J[1][2] * F.x + J[2][2] * F.y}, 1e-14)
      end,
    },
    {
      title = "Holding a weight with virtual forces",
      text = [[
Now a 0.5 kg weight hangs at the hand. To hold it, the hand must push up with m_w g; the
motors can do that as a virtual force, adding Jᵀ (0, m_w g) to the arm's own gravity
compensation. The arm with the weight, driven by these torques, must not accelerate, and
neither may the hand (its acceleration is J q̈ at rest). As an independent check, the
inverse dynamics of the arm with the weight (which knows nothing of Jacobians) asks for
the same torques.]],
      formula = "τ = g_arm(q) + Jᵀ (0, m_w g, 0)",
      run = function(ctx)
        local bare = arm()
        local g_arm = bare:bias_forces()
        local lift = bare:virtual_force(2, hand, vec3(0, weight * g, 0))
        local tau = {g_arm[1] + lift[1], g_arm[2] + lift[2]}
        ctx:show("g_arm(q) (N·m)", g_arm)
        ctx:show("Jᵀ F (N·m)", lift)
        local loaded = arm(weight)
        ctx:expect("inverse dynamics of arm + weight", loaded:inverse_dynamics({0, 0}), tau,
                   1e-12)
        local qdd = loaded:forward_dynamics(tau)
        ctx:expect("q̈", qdd, {0, 0}, {abs = 1e-12})
        local J = loaded:jacobian(2, hand)
        local hand_acceleration = vec3(J[1][1] * qdd[1] + J[1][2] * qdd[2],
                                       J[2][1] * qdd[1] + J[2][2] * qdd[2], 0)
        ctx:expect("hand acceleration J q̈ (m/s²)", hand_acceleration, vec3(), {abs = 1e-12})
        loaded:set_torques(tau)
        loaded:step(0.001, 1000)
        ctx:expect("hand after 1 s (m)", loaded.links[2]:to_world(hand),
                   vec3(L1 * c1 + L2 * c12, L1 * s1 + L2 * s12, 0), {abs = 1e-10})
      end,
    },
  },
}
