 -- Option tables whose fields run code while a binding reads them: bodies added (the body
-- vector grows) and removed (an argument goes away), garbage collected, fields that come from
-- __index alone.
local w = world{}
local a = w:add(body.sphere{mass = 1, radius = 0.5, position = vec3(0, 0, 0)})
local b = w:add(body.sphere{mass = 1, radius = 0.5, position = vec3(0.9, 0, 0)})
local c = w:add(body.box{mass = 1, size = vec3(1, 1, 1), position = vec3(3, 0, 0)})
local function grow() for i = 1, 20 do w:add(body.sphere{mass = 1, radius = 0.1, position = vec3(i, 5, 0)}) end end
local function remove(x) pcall(w.remove, w, x) end
local fields = {point = vec3(0.45, 0, 0), normal = vec3(1, 0, 0), restitution = 0.5, friction = 0.3}
pcall(collide.resolve, a, b, setmetatable({}, {__index = function(_, k) grow() return fields[k] end}))
pcall(collide.resolve, a, b, setmetatable({}, {__index = function(_, k) remove(a) return fields[k] end}))
pcall(w.add_spring, w, setmetatable({k = 10}, {__index = function(_, k)
  remove(c) collectgarbage() return ({a = b, b = c, a_point = vec3(), b_point = vec3()})[k] end}))
pcall(w.add_drag, w, setmetatable({linear = 1}, {__index = function(_, k) remove(b) return ({body = b})[k] end}))
pcall(w.add_plane, w, setmetatable({}, {__index = function(_, k) grow() return ({normal = vec3(0, 1, 0), offset = -1})[k] end}))
pcall(world, setmetatable({}, {__index = function(_, k) grow() collectgarbage() end}))
pcall(body.sphere, setmetatable({}, {__index = function(_, k) remove(a) return ({mass = 1, radius = 1})[k] end}))
w:step(0.01)
pcall(w.step, w, 0.01, setmetatable({}, {__index = function() grow() end}))
