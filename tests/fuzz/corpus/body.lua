 local b = body{mass = 2, inertia = mat3.diag(1, 2, 2.5), position = vec3(1, 2, 3), angular_velocity = vec3(0, 1, 5), restitution = 0.2, friction = 0.7}
b:apply_force(vec3(1, 0, 0), vec3(0, 1, 0)) b:apply_torque(vec3(0, 0, 1)) b:apply_impulse(vec3(0, 1, 0), vec3(1, 0, 0)) b:apply_angular_impulse(vec3(1, 0, 0))
local x = b:point_velocity(vec3(1, 1, 1)) + b:to_world(vec3(1, 0, 0)) + b:to_local(vec3()) + b:linear_momentum() + b:angular_momentum()
local I = b:world_inertia() * b:inv_world_inertia()
local k = b:kinetic_energy() + b.mass + b.inv_mass
b.position = vec3() b.velocity = vec3(1, 1, 1) b.orientation = quat(1, 1, 0, 0) b.restitution = 1 b.friction = 0
local s = body{static = true} local w = world{gyroscopic = "explicit"} w:add(b) w:add(s) w:step(0.001, 1000)
collectgarbage() local ws = w:bodies() w = nil collectgarbage() local p = ws[1].position
