 local w = world{integrator = "rk4", substeps = 2}
local b = w:add(body.sphere{mass = 1, radius = 0.5, position = vec3(0, 2, 0), velocity = vec3(1, 0, 0)})
local c = w:add(body.box{mass = 2, size = vec3(1, 1, 1), position = vec3(0, 4, 0), orientation = quat.axis_angle(vec3(1, 1, 0), 0.3)})
w:add_plane{normal = vec3(0, 1, 0), offset = 0, restitution = 0.5, friction = 0.4}
w:add_spring{a = b, b = c, k = 10, damping = 0.1, rest_length = 1}
w:add_drag{body = c, linear = 0.1, angular = 0.1}
w:add_force(function(world, t) b:apply_force(vec3(0, 1, 0), b.position + vec3(0.1, 0, 0)) end)
w:step(0.01, 200)
local e = w:energy() + w:kinetic_energy() + w:potential_energy()
local p, l = w:linear_momentum(), w:angular_momentum(vec3(1, 0, 0))
for _, contact in ipairs(w:contacts()) do local n = contact.normal + contact.point end
for _, plane in ipairs(w:planes()) do local x = plane.offset end
w:remove(c) w.gravity = vec3(0, -1, 0) w.iterations = 20 w.restitution_threshold = 0.5
