 local t = motion.simulate{method = "rk4", accel = function(t, x, v) return -x - 0.1 * v end, x0 = 1, v0 = 0, dt = 0.01, steps = 100}
local t2 = motion.simulate{method = "semi_implicit", accel = function(t, x, v) return vec3(0, -9.81, 0) end, x0 = vec3(), v0 = vec3(1, 5, 0), dt = 0.1, steps = 10}
local y = ode.step("rk4", function(t, y) return {y[2], -y[1]} end, 0, {1, 0}, 0.1)
local z = ode.step("euler", function(t, y) return -y end, 0, vec3(1, 2, 3), 0.1)
local J, va, vb = collide.impulse_1d(1, 2, math.huge, 0, 0.5)
local a = body.sphere{mass = 1, radius = 1, velocity = vec3(1, 0, 0)}
local b = body.box{mass = 2, size = vec3(1, 1, 1), position = vec3(2, 0, 0)}
local j = collide.resolve(a, b, {point = vec3(1, 0, 0), normal = vec3(1, 0, 0), restitution = 0.5, friction = 0.3})
local K = collide.inverse_mass_matrix(a, vec3(0, 1, 0), vec3(0, 1, 0))
local me = collide.effective_mass(a, b, vec3(1, 0, 0), vec3(1, 0, 0))
plot.lines{{x = t.t, y = t.x, label = "rk4"}, {y = {1, 2, 3}}, title = "x", xlabel = "t", ylabel = "x", width = 40, height = 10}
help() help(vec3) help("inertia.solid_box") help(a) help(world)
local l = lesson{id = "a-1", title = "A", source = "s", steps = {{title = "t", text = "x", run = function(ctx) end}}}
