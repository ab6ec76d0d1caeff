-- Wrong self, objects of the wrong type, and broken metatables: {code, expected start of the
-- error's first line}. A case that changes a shared metatable does it through
-- with_field(mt, key, value, fn), which restores it; debug.setmetatable on one value changes
-- that value only. Locals in scope: v, m, q, b, bx, s, f, w (see harness.lua).
local vec3_mt, mat3_mt, body_mt, world_mt =
  "debug.getmetatable(v)", "debug.getmetatable(m)", "debug.getmetatable(b)", "debug.getmetatable(w)"
return {
  -- methods called with . instead of :, or on the wrong object
  {"b.apply_torque(v)", "bad argument #1 to 'body:apply_torque' (body expected, got vec3)"},
  {"b.to_world(b)", "bad argument #2 to 'body:to_world' (vec3 expected, got no value)"},
  {"w.add(b)", "bad argument #1 to 'world:add' (world expected, got body)"},
  {"w.step(w)", "bad argument #2 to 'world:step' (number expected, got no value)"},
  {"w.add_plane(b, {})", "bad argument #1 to 'world:add_plane' (world expected, got body)"},
  {"m.get(v, 1, 1)", "bad argument #1 to 'mat3:get' (mat3 expected, got vec3)"},
  {"q.rotate(q)", "bad argument #2 to 'quat:rotate' (vec3 expected, got no value)"},
  {"v.cross(b, v)", "bad argument #1 to 'vec3:cross' (vec3 expected, got body)"},
  {"vec3.dot(w, v)", "bad argument #1 to 'vec3:dot' (vec3 expected, got world)"},
  {"mat3.row(q, 1)", "bad argument #1 to 'mat3:row' (mat3 expected, got quat)"},
  {"quat.to_mat3(m)", "bad argument #1 to 'quat:to_mat3' (quat expected, got mat3)"},
  {"body.to_world(f, 5)", "bad argument #2 to 'body:to_world' (vec3 expected, got number)"},
  {"world.contacts(w, w)", "bad argument #2 to 'world:contacts' (no more than 1 argument expected, got 2)"},
  {"b.point_velocity(io.stdout, v)", "bad argument #1 to 'body:point_velocity' (body expected, got FILE*)"},
  {"vec3.norm(io.stdout)", "bad argument #1 to 'vec3:norm' (vec3 expected, got FILE*)"},
  {"mat3.det(coroutine.create(print))", "bad argument #1 to 'mat3:det' (mat3 expected, got thread)"},
  {"quat.norm(function() end)", "bad argument #1 to 'quat:norm' (quat expected, got function)"},
  -- lookalikes: tables dressed as rigidlab values are refused by their real type
  {"vec3.dot(setmetatable({}, {__name = 'vec3'}), v)", "bad argument #1 to 'vec3:dot' (vec3 expected, got table"},
  {"w:add(setmetatable({x = 1}, {__index = b}))", "bad argument #1 to 'world:add' (body expected, got table)"},
  {"return v + setmetatable({}, {__add = function() return 1 end})", "bad argument #2 to 'vec3.__add' (vec3 expected, got table)"},
  -- metatables are protected
  {"setmetatable(v, {})", "bad argument #1 to 'setmetatable' (table expected, got vec3)"},
  {"setmetatable(b, {})", "bad argument #1 to 'setmetatable' (table expected, got body)"},
  {"setmetatable(w, nil)", "bad argument #1 to 'setmetatable' (table expected, got world)"},
  -- one value's metatable replaced (debug.setmetatable): the bindings still know its type
  {"debug.setmetatable(v, " .. mat3_mt .. ") return v:get(1, 1)", "bad argument #1 to 'mat3.__index' (mat3 expected, got vec3)"},
  {"debug.setmetatable(m, " .. vec3_mt .. ") return m.x", "bad argument #1 to 'vec3.__index' (vec3 expected, got mat3)"},
  {"debug.setmetatable(b, " .. world_mt .. ") return b:step(0.1)", "calling 'world:step' on bad self (world expected, got body)"},
  {"debug.setmetatable(b, " .. world_mt .. ") return b.time", "bad argument #1 to 'world.__index' (world expected, got body)"},
  {"debug.setmetatable(b, " .. world_mt .. ") b.gravity = v", "bad argument #1 to 'world.__newindex' (world expected, got body)"},
  {"debug.setmetatable(w, " .. body_mt .. ") return w:apply_force(v)", "calling 'body:apply_force' on bad self (body expected, got world)"},
  {"debug.setmetatable(w, " .. body_mt .. ") return w.position", "bad argument #1 to 'body.__index' (body expected, got world)"},
  {"debug.setmetatable(b, " .. vec3_mt .. ") b.x = 1", "bad argument #1 to 'vec3.__newindex' (vec3 expected, got body)"},
  {"debug.setmetatable(v, nil) return vec3.normalized(vec3.cross(v, v))", "bad argument #1 to 'vec3:normalized' (cannot normalize the zero vector)"},
  {"debug.setmetatable(v, {__index = quat}) return v:norm()", "calling 'quat:norm' on bad self (quat expected, got vec3)"},
  {"debug.setmetatable(v, {__index = world}) return v:bodies()", "calling 'world:bodies' on bad self (world expected, got vec3)"},
  {"debug.setmetatable(b, {__index = mat3}) return b:inverse()", "calling 'mat3:inverse' on bad self (mat3 expected, got body)"},
  {"debug.setmetatable(w, {__index = inertia}) return w:solid_sphere(1)", "calling 'inertia.solid_sphere' on bad self (number expected, got world)"},
  {"debug.setmetatable(q, {__index = plot}) return q:lines()", "calling 'plot.lines' on bad self (table expected, got quat)"},
  {"debug.setmetatable(q, {__index = csv}) return q:write({}, {})", "calling 'csv.write' on bad self (string (a file path) expected, got quat)"},
  {"debug.setmetatable(m, {__index = _G}) return m:lesson()", "calling 'lesson' on bad self (table expected, got mat3)"},
  {"debug.setmetatable(m, {__index = _G}) return m:help(1)", "bad argument #1 to 'help' (no more than 1 argument expected, got 2)"},
  -- shared metatables changed (and restored) with rawset
  {"with_field(" .. vec3_mt .. ", '__add', quat.conj, function() return v + v end)", "bad argument #1 to 'quat:conj' (quat expected, got vec3)"},
  {"with_field(" .. vec3_mt .. ", '__index', mat3, function() return v:trace() end)", "calling 'mat3:trace' on bad self (mat3 expected, got vec3)"},
  {"with_field(" .. body_mt .. ", '__index', world, function() return b:energy() end)", "calling 'world:energy' on bad self (world expected, got body)"},
  {"with_field(" .. body_mt .. ", '__newindex', debug.getmetatable(w).__newindex, function() b.gravity = v end)", "bad argument #1 to 'world.__newindex' (world expected, got body)"},
  {"with_field(" .. world_mt .. ", '__index', body, function() return w:kinetic_energy() end)", "calling 'body:kinetic_energy' on bad self (body expected, got world)"},
  {"with_field(" .. mat3_mt .. ", '__mul', vec3.cross, function() return m * v end)", "bad argument #1 to 'vec3:cross' (vec3 expected, got mat3)"},
  {"with_field(" .. mat3_mt .. ", '__tostring', body.kinetic_energy, function() return tostring(m) end)", "bad argument #1 to 'body:kinetic_energy' (body expected, got mat3)"},
  {"with_field(" .. world_mt .. ", '__tostring', vec3.norm, function() return tostring(w) end)", "bad argument #1 to 'vec3:norm' (vec3 expected, got world)"},
  -- metamethods called directly
  {"return " .. vec3_mt .. ".__index(5, 'x')", "bad argument #1 to 'vec3.__index' (vec3 expected, got number)"},
  {"return " .. body_mt .. ".__index(v, 'mass')", "bad argument #1 to 'body.__index' (body expected, got vec3)"},
  {"return " .. world_mt .. ".__index(b, 'time')", "bad argument #1 to 'world.__index' (world expected, got body)"},
  {"return " .. mat3_mt .. ".__add(m)", "bad argument #2 to 'mat3.__add' (mat3 expected, got no value)"},
  {"return " .. body_mt .. ".__tostring(w)", "bad argument #1 to 'body.__tostring' (body expected, got world)"},
}
