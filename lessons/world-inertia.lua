-- The inertia tensor in world space (000 "Reference frame", 001 "Stepping Into 3 Dimensions",
-- 002 "Rigid Body Dynamics"): I_world = R·I_body·Rᵀ, its inverse R·I_body⁻¹·Rᵀ, and a torque
-- given in the body frame or in the world frame producing the same ω.

-- A body of six particles (kg, body-frame positions in m), centre of mass at the origin.
-- By hand: I_xx = Σm(y² + z²) = 2·1·0.2² + 2·0.5·0.1² = 0.09, I_yy = 2·2·0.3² + 0.01 = 0.37,
-- I_zz = 0.36 + 0.08 = 0.44, no products (the set is mirror-symmetric).
local particles = {
  {mass = 2, pos = vec3(0.3, 0, 0)}, {mass = 2, pos = vec3(-0.3, 0, 0)},
  {mass = 1, pos = vec3(0, 0.2, 0)}, {mass = 1, pos = vec3(0, -0.2, 0)},
  {mass = 0.5, pos = vec3(0, 0, 0.1)}, {mass = 0.5, pos = vec3(0, 0, -0.1)},
}
local total_mass = 7
local I_body = mat3.diag(0.09, 0.37, 0.44)
local I_body_inverse = mat3.diag(1 / 0.09, 1 / 0.37, 1 / 0.44)
local orientation = quat.axis_angle(vec3(1, 1, 0), math.rad(60))

-- Σ m((r·r)E − r⊗r) over the particles, each position first turned by R (001's derivation:
-- r' = R·r, so I' = R·I·Rᵀ). Plain components, apart from the engine's inertia module.
local function tensor_of_turned_particles(R)
  local xx, yy, zz, xy, xz, yz = 0, 0, 0, 0, 0, 0
  for _, p in ipairs(particles) do
    local r = R * p.pos
    xx, yy, zz = xx + p.mass * (r.y ^ 2 + r.z ^ 2), yy + p.mass * (r.x ^ 2 + r.z ^ 2),
                 zz + p.mass * (r.x ^ 2 + r.y ^ 2)
    xy, xz, yz = xy - p.mass * r.x * r.y, xz - p.mass * r.x * r.z, yz - p.mass * r.y * r.z
  end
  return mat3(xx, xy, xz, xy, yy, yz, xz, yz, zz)
end

local function make_body(q, omega)
  return body{mass = total_mass, inertia = I_body, orientation = q,
              angular_velocity = omega or vec3(0, 0, 0)}
end

return lesson{
  id = "world-inertia",
  title = "The inertia tensor in world space",
  source = "000_3bd95e59483beea1.txt, \"Reference frame\"; 001_8a70f78e0cc79e25.txt, " ..
           "\"Stepping Into 3 Dimensions\"; 002_5497adede943f513.txt, \"Rigid Body Dynamics\"",
  steps = {
    {
      title = "Body frame and world frame",
      text = [[
A rigid body's inertia tensor never changes in the body's own frame, the axes that turn with
it: the particles keep their places relative to each other. But the equations of motion are
written in the world frame, and there the body's mass is arranged differently every time it
turns. So each frame, the simulation turns the constant body tensor into world axes with the
orientation matrix R: I_world = R·I_body·Rᵀ.

001 derives this directly: turning the body moves each particle offset to r' = R·r; putting r'
into the particle formula, the R's factor out on both sides. We check exactly that: a body
of six particles, 7 kg in all (2 kg at x = ±0.3 m, 1 kg at y = ±0.2 m, 0.5 kg at
z = ±0.1 m), with I_body = diag(0.09, 0.37, 0.44) kg·m², turned 60° about (1, 1, 0).
Rebuilding the tensor from the turned particles must match the body's world_inertia().]],
            formula = "I_world = R·I_body·Rᵀ\n" ..
                "(from r' = R·r:  (r'·r')E − r'⊗r' = R((r·r)E − r⊗r)Rᵀ)",
      run = function(ctx)
        local _, _, from_particles = inertia.points(particles)
        ctx:expect("the particles' body tensor = diag(0.09, 0.37, 0.44)", from_particles, I_body)
        local b = make_body(orientation)
        local R = orientation:to_mat3()
        ctx:show("R (orientation as a matrix)", R)
        ctx:show("body-frame tensor b.inertia (kg·m²)", b.inertia)
        ctx:show("world-frame tensor b:world_inertia() (kg·m²)", b:world_inertia())
        ctx:expect("b.inertia stays the body tensor", b.inertia, I_body)
        ctx:expect("world_inertia = R·I_body·Rᵀ", b:world_inertia(), R * I_body * R:transpose())
        ctx:expect("world_inertia = tensor of the turned particles", b:world_inertia(),
                   tensor_of_turned_particles(R))
      end,
    },
    {
      title = "The inverse: R·I⁻¹·Rᵀ",
      text = [[
To get the angular velocity from the angular momentum, ω = I_world⁻¹·L, the simulation needs
the inverse of the world tensor every step. Inverting a 3×3 matrix every frame is wasteful
and, for nearly flat bodies, inaccurate. It is also unnecessary: the inverse of R·I·Rᵀ is
R·I⁻¹·Rᵀ (Rᵀ undoes R), and the inverse of the diagonal body tensor is just the reciprocals
of its three moments, computed once. inv_world_inertia() returns that.]],
      formula = "I_world⁻¹ = (R·I_body·Rᵀ)⁻¹ = R·I_body⁻¹·Rᵀ\n" ..
                "I_body⁻¹ = diag(1/I_x, 1/I_y, 1/I_z)",
      run = function(ctx)
        local b = make_body(orientation)
        local R = orientation:to_mat3()
        local inverse = b:inv_world_inertia()
        ctx:show("I_body⁻¹ = diag(1/0.09, 1/0.37, 1/0.44) (1/(kg·m²))", I_body_inverse)
        ctx:show("b:inv_world_inertia() (1/(kg·m²))", inverse)
        ctx:expect("inv_world_inertia = R·I_body⁻¹·Rᵀ", inverse, R * I_body_inverse * R:transpose())
        ctx:expect("inv_world_inertia = (world_inertia)⁻¹", inverse, b:world_inertia():inverse())
        ctx:expect("I_world·I_world⁻¹ = E", b:world_inertia() * inverse, mat3.identity())
      end,
    },
    {
      title = "The same push, a different turn of the body",
      text = [[
Because the world tensor depends on the orientation, the very same angular impulse gives a
body a different spin depending on how it is turned at that moment (001 shows this with two
copies of one particle system). Give the body an angular impulse H = (0, 0, 0.1) N·m·s about
the world z axis, once unturned and once turned as before. Unturned, it spins about z with
ω = H/I_zz = 0.1/0.44 rad/s. Turned, the z axis is no longer a principal axis of the body, so
ω = R·I⁻¹·Rᵀ·H leans away from z.]],
      formula = "ω' = ω + I_world⁻¹·H = ω + R·I_body⁻¹·Rᵀ·H",
      run = function(ctx)
        local H = vec3(0, 0, 0.1)
        local straight, turned = make_body(quat.identity()), make_body(orientation)
        straight:apply_angular_impulse(H)
        turned:apply_angular_impulse(H)
        ctx:show("unturned: ω (rad/s)", straight.angular_velocity)
        ctx:show("turned:   ω (rad/s)", turned.angular_velocity)
        ctx:expect("unturned: ω = (0, 0, 0.1/0.44)", straight.angular_velocity,
                   vec3(0, 0, 0.1 / 0.44))
        local R = orientation:to_mat3()
        local in_body = R:transpose() * H
        ctx:expect("turned: ω = R·(H_body / moments)", turned.angular_velocity,
                   R * vec3(in_body.x / 0.09, in_body.y / 0.37, in_body.z / 0.44))
      end,
    },
    {
      title = "A torque in the body frame or in the world frame",
      text = [[
A torque can be given in either frame; the physics must not care. Say a small thruster fixed
on the body pushes with τ_body = (0.2, −0.1, 0.3) N·m in body axes for Δt = 0.05 s, while the
body already spins at ω = (0.5, 0, 0) rad/s. In world axes the same torque is τ_world = R·τ_body.
The world-frame update is ω' = ω + R·I⁻¹·Rᵀ·(τ_world·Δt). Substituting τ_world = R·τ_body, the
Rᵀ·R in the middle cancels and leaves ω' = ω + R·(I⁻¹·τ_body·Δt): divide the body-frame torque
by the body's own moments, then turn the result into the world. That is 001's equation, and
it means the engine can work in whichever frame is cheaper.]],
      formula = "ω' = ω + R·I⁻¹·Rᵀ·R·(τ_body·Δt) = ω + R·(I⁻¹·τ_body·Δt)",
      run = function(ctx)
        local torque_body, dt = vec3(0.2, -0.1, 0.3), 0.05
        local omega = vec3(0.5, 0, 0)
        local R = orientation:to_mat3()
        local torque_world = R * torque_body
        ctx:show("τ_body (N·m)", torque_body)
        ctx:show("τ_world = R·τ_body (N·m)", torque_world)
        local b = make_body(orientation, omega)
        b:apply_angular_impulse(torque_world * dt)
        ctx:show("ω' from the world-frame impulse, engine (rad/s)", b.angular_velocity)
        local body_route = omega + R * vec3(0.2 * dt / 0.09, -0.1 * dt / 0.37, 0.3 * dt / 0.44)
        ctx:show("ω + R·(I⁻¹·τ_body·Δt), by hand (rad/s)", body_route)
        ctx:expect("world-frame route = body-frame route", b.angular_velocity, body_route)
      end,
    },
  },
}
