 local ok = pcall(function() return vec3(1, 2, 3) + mat3.identity() end)
for _, f in ipairs{vec3, mat3, quat, body, world, help, lesson, inertia.solid_box, plot.lines, csv.write, motion.simulate, ode.step, collide.resolve} do
  pcall(f) pcall(f, 0/0) pcall(f, {}) pcall(f, -1, math.huge, "x") pcall(f, setmetatable({}, {__index = function() error("x") end}))
end
local w = world{} local b = w:add(body.sphere{mass = 1, radius = 1})
pcall(function() w:add_force(function(world) world:step(0.1) end) w:step(0.1) end)
pcall(function() w:add_force(function(world) world:remove(b) end) w:step(0.1) end)
pcall(function() w:add_force(function(world) b.position = vec3(0/0, 0, 0) end) w:step(0.1) end)
pcall(setmetatable, b, {}) pcall(csv.write, "x.csv", {x = {1}}, {"x"}) pcall(plot.lines, {{y = {1}}, svg = "x.svg"})
