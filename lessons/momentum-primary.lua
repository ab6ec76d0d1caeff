-- Angular momentum as the state (002 "Rigid Body Dynamics", 003 "Solving Angular Equations
-- in 3D", 004 "Rigid Body Update Code"): L += τΔt, ω = I⁻¹L with I = A I₀ Aᵀ, then turn the
-- orientation by ωΔt. L comes out exact for a constant torque; the gyroscopic term is hidden
-- in the turning of I.

local mass, size = 3, vec3(1, 0.6, 0.3)            -- kg, m: a flat box
local start = quat.axis_angle(vec3(1, 1, 0), 0.6)  -- its initial orientation A₀
local spin = vec3(1, 0.3, 2)                       -- rad/s, its initial ω (world)
local torque = vec3(0.5, -0.2, 0.8)                -- N·m, constant, world frame
local duration = 2                                 -- s

-- I₀ of the box about its centre, body axes (000 "Inertia of primitive shapes").
local I0 = mat3.diag(mass * (size.y ^ 2 + size.z ^ 2) / 12, mass * (size.x ^ 2 + size.z ^ 2) / 12,
                     mass * (size.x ^ 2 + size.y ^ 2) / 12)
local I0_inverse = mat3.diag(1 / I0:get(1, 1), 1 / I0:get(2, 2), 1 / I0:get(3, 3))

local function world_inverse_inertia(q)
  local A = q:to_mat3()
  return A * I0_inverse * A:transpose()
end

-- The slides' loop with L as the state: L += τΔt, ω = A I₀⁻¹ Aᵀ L, A ← Rotate(ωΔt)·A.
-- Returns L, ω and the orientation after the steps.
local function momentum_loop(dt, steps, tau)
  local q = start
  local A = q:to_mat3()
  local L = A * I0 * A:transpose() * spin
  local omega = spin
  for _ = 1, steps do
    L = L + tau * dt
    omega = world_inverse_inertia(q) * L
    q = (quat.axis_angle(omega, omega:norm() * dt) * q):normalized()
  end
  return L, world_inverse_inertia(q) * L, q
end

local function box_in_world(integrator, gyroscopic)
  local w = world{gravity = vec3(0, 0, 0), integrator = integrator, gyroscopic = gyroscopic}
  local b = w:add(body.box{mass = mass, size = size, orientation = start, angular_velocity = spin})
  return w, b
end

return lesson{
  id = "momentum-primary",
  title = "Angular momentum as the primary quantity",
  source = "002_5497adede943f513.txt, \"Rigid Body Dynamics\"; 003_636de12a6b81385f.txt, " ..
           "\"Angular Momentum\", \"Solving Angular Equations in 3D\"; " ..
           "004_8f5d2bfd6f0c2787.txt, \"Rigid Body Update Code\"",
  steps = {
    {
      title = "The inertia tensor turns with the body",
      text = [[
A body's inertia is simple in its own axes: for our box (3 kg, 1 × 0.6 × 0.3 m, turned by
0.6 rad about (1, 1, 0) and spinning at ω = (1, 0.3, 2) rad/s), I₀ is diagonal with
m(h² + d²)/12 and so on. But torques and angular momentum live in world axes, and there the
tensor is I = A I₀ Aᵀ, with A the orientation matrix: rotate a vector into body axes (Aᵀ),
apply I₀, rotate back (A). Because A is orthonormal, A⁻¹ = Aᵀ, and the inverse comes for
free: I⁻¹ = A I₀⁻¹ Aᵀ, where I₀⁻¹ just holds the reciprocals of the diagonal. 002 notes
this so that no 3×3 inversion is ever needed in the loop.]],
      formula = "I = A·I₀·Aᵀ,   I⁻¹ = (A·I₀·Aᵀ)⁻¹ = A·I₀⁻¹·Aᵀ",
      run = function(ctx)
        local _, b = box_in_world("semi_implicit")
        local A = start:to_mat3()
        ctx:show("I₀ (kg·m², body axes)", I0)
        ctx:show("A", A)
        ctx:show("I = A I₀ Aᵀ (kg·m²)", A * I0 * A:transpose())
        ctx:expect("b:world_inertia() = A I₀ Aᵀ", b:world_inertia(), A * I0 * A:transpose(), 1e-12)
        ctx:expect("b:inv_world_inertia() = A I₀⁻¹ Aᵀ", b:inv_world_inertia(),
                   A * I0_inverse * A:transpose(), 1e-12)
        ctx:expect("I · I⁻¹ = E", b:world_inertia() * b:inv_world_inertia(), mat3.identity(), 1e-12)
      end,
    },
    {
      title = "The loop: L += τΔt, then ω = I⁻¹L",
      text = [[
The slides keep the angular momentum L, not ω, as the state, just as the linear part keeps
p = mv. Each frame: add the torque to L, compute ω = I⁻¹L with the current orientation,
turn the orientation by ωΔt (004's loop does the same with linearMomentum and
angularMomentum). The reason is that dL/dt = τ holds in world axes with nothing else in
it, so for a constant torque the update L += τΔt is exact: L(t) = L₀ + τt whatever the
step. rigidlab's world keeps ω instead. Its default rotation update (gyroscopic =
"conserving") works on L too: half the torque impulse, a turn made of exact rotations that
leave the world L as it is, the other half; so it also ends at L₀ + τt to round-off, with
either Euler integrator. The table shows the error in L after 2 s, against the loop's, for
a tumbling box under a constant world torque. RK4, which steps ω, gets close; an Euler
step of ω itself (gyroscopic = "implicit", 001's Newton step) is off by a lot, because ω
about this box's axes changes fast and it follows ω in straight pieces.
The loop is not exact in everything, though: ω = I⁻¹L depends on the orientation, which it
still steps to first order, so ω after 2 s differs a lot between Δt = 0.1 and 0.05 s.]],
      formula = "L(t+Δt) = L(t) + τΔt,   ω = A I₀⁻¹ Aᵀ L,   A ← Rotate(ωΔt)·A",
      run = function(ctx)
        local rows = {}
        for _, dt in ipairs({0.1, 0.05}) do
          local steps = math.floor(duration / dt + 0.5)
          local L, omega = momentum_loop(dt, steps, torque)
          local w0, b0 = box_in_world("semi_implicit")
          local want = b0:angular_momentum() + torque * duration
          local row = {dt, (L - want):norm()}
          for _, method in ipairs({"semi_implicit", "euler", "rk4", "implicit"}) do
            local w, b = box_in_world(method == "implicit" and "semi_implicit" or method,
                                      method == "implicit" and "implicit" or nil)
            w:add_force(function() b:apply_torque(torque) end)
            w:step(dt, steps)
            row[#row + 1] = (b:angular_momentum() - want):norm()
            if method == "semi_implicit" or method == "euler" then
              ctx:expect("Δt = " .. dt .. ": world " .. method .. " (conserving): L = L₀ + τt",
                         b:angular_momentum(), want, 1e-12)
            end
          end
          rows[#rows + 1] = row
          ctx:show("Δt = " .. dt .. ": L after 2 s, momentum loop (kg·m²/s)", L)
          ctx:show("Δt = " .. dt .. ": ω after 2 s = I⁻¹L (rad/s)", omega)
          ctx:expect("Δt = " .. dt .. ": L = L₀ + τt exactly", L, want, 1e-12)
        end
        ctx:table({"Δt (s)", "‖L − (L₀+τt)‖ loop", "world semi_implicit", "world euler",
                   "world rk4", "semi_implicit, implicit"}, rows)
      end,
    },
    {
      title = "Where did the gyroscopic term go?",
      text = [[
002 writes the torque-free motion as ω̇ = −I⁻¹(ω × Iω): without any torque, ω still
changes. The momentum loop has no such term, yet it tumbles correctly. With L fixed,
ω = I⁻¹L changes only because I⁻¹ = A I₀⁻¹ Aᵀ turns with the body, and differentiating that
gives exactly −I⁻¹(ω × Iω). We check it by turning the orientation a hair (h = 1e-4 s)
back and forth about ω and differencing I⁻¹L; the central difference is accurate to O(h²),
so we compare to 1e-6. L stays exactly constant in the loop, but the kinetic energy ½L·ω
creeps up, by an amount that shrinks roughly in proportion to Δt: the orientation update
is still a first-order step.]],
      formula = "ω̇ = d/dt(A I₀⁻¹ Aᵀ) L = −I⁻¹(ω × Iω)   (L constant, τ = 0)",
      run = function(ctx)
        local h = 1e-4
        local A = start:to_mat3()
        local L = A * I0 * A:transpose() * spin
        local ahead = quat.axis_angle(spin, spin:norm() * h) * start
        local behind = quat.axis_angle(spin, -spin:norm() * h) * start
        local rate = (world_inverse_inertia(ahead) * L - world_inverse_inertia(behind) * L) /
                     (2 * h)
        local inertia_world = A * I0 * A:transpose()
        local gyroscopic = -(world_inverse_inertia(start) * spin:cross(inertia_world * spin))
        ctx:show("ω̇ from turning I⁻¹ (rad/s²)", rate)
        ctx:show("−I⁻¹(ω × Iω) (rad/s²)", gyroscopic)
        ctx:expect("the same rate", rate, gyroscopic, 1e-6)
        local energy0 = 0.5 * L:dot(spin)
        local rows = {}
        for _, dt in ipairs({0.1, 0.05, 0.025}) do
          local L_end, omega_end = momentum_loop(dt, math.floor(duration / dt + 0.5), vec3(0, 0, 0))
          rows[#rows + 1] = {dt, (L_end - L):norm(), 0.5 * L_end:dot(omega_end) - energy0}
          ctx:expect("Δt = " .. dt .. ": L unchanged", L_end, L, 1e-12)
        end
        ctx:table({"Δt (s)", "‖L − L₀‖ (kg·m²/s)", "½L·ω − T₀ (J)"}, rows)
        ctx:show("T₀ = ½L·ω (J)", energy0)
      end,
    },
    {
      title = "Rotate on the left: a slip in 002's update",
      text = [[
002 writes the orientation update as A' = A·Rotate(ωΔt). That order would be right for an
ω given in body axes, but here ω = I⁻¹L is in world axes, and a world-axis turn must be
applied on the left: A' = Rotate(ωΔt)·A. For a body that is already tilted, the two differ
by much more than a rounding error. A ball (1 kg, radius 0.5 m) tilted by 90° about x and
spinning about the world z axis at 1 rad/s for 0.5 s shows it: rigidlab's world ends up at Rotate(ωΔt)·A, and A·Rotate(ωΔt) would be a
turn about the body's own z axis, a different axis in the world. (003 has a similar
inconsistency: its summary says to integrate the orientation with the new ω computed from
the new L, while its formula uses ω(t₁), the old one.)]],
      formula = "right: A' = Rotate(ωΔt)·A   (ω in world axes)\n" ..
                "002 prints A' = A·Rotate(ωΔt)",
      run = function(ctx)
        local omega, dt = vec3(0, 0, 1), 0.5
        local tilt = quat.axis_angle(vec3(1, 0, 0), math.pi / 2)
        local w = world{gravity = vec3(0, 0, 0)}
        local ball = w:add(body.sphere{mass = 1, radius = 0.5, orientation = tilt,
                                       angular_velocity = omega})
        w:step(dt)
        local A, turn = tilt:to_mat3(), quat.axis_angle(omega, omega:norm() * dt):to_mat3()
        ctx:show("Rotate(ωΔt)·A", turn * A)
        ctx:show("A·Rotate(ωΔt) (002's order)", A * turn)
        ctx:show("world after one step", ball.orientation:to_mat3())
        ctx:expect("the world turns on the left", ball.orientation:to_mat3(), turn * A, 1e-12)
        -- Where the body's own z axis points: the wrong order turns about that very axis,
        -- so it stays at A·ẑ = (0, −1, 0); the right one swings it to (sin ωΔt, −cos ωΔt, 0).
        local z_right = ball.orientation:rotate(vec3(0, 0, 1))
        local z_wrong = (A * turn) * vec3(0, 0, 1)
        ctx:show("body z axis, world result", z_right)
        ctx:show("body z axis, 002's order", z_wrong)
        ctx:expect("world: body z at (sin ωΔt, −cos ωΔt, 0)", z_right,
                   vec3(math.sin(dt), -math.cos(dt), 0), 1e-12)
        ctx:expect("002's order: body z stays at (0, −1, 0)", z_wrong, vec3(0, -1, 0), 1e-12)
        ctx:expect("apart by 2 sin(ωΔt/2)", (z_right - z_wrong):norm(), 2 * math.sin(dt / 2), 1e-12)
      end,
    },
  },
}
