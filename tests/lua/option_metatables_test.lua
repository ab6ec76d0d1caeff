-- Option tables with metamethods (issue 12 item 3): a field's __index may run any Lua code,
-- such as adding bodies to a world (its body vector grows and moves) or removing one (the
-- indices of the later ones drop). collide.resolve gave the impulse to freed memory or to a
-- body that was no argument, and w:add_spring / w:add_drag attached to the wrong body. Every
-- binding now reads every argument and field before taking a pointer or an index, so the
-- result is the same as with a plain table on a world already in the final state. The
-- sanitizer build runs this file under ASan.
local T = dofile("testing.lua")

-- A table whose every field read (through __index) first runs `effect`, then gives `fields`.
local function meddling(fields, effect)
  return setmetatable({}, {__index = function(_, key)
    effect(key)
    return fields[key]
  end})
end

-- A world with bodies a, b, c (c a bystander) and `extra` more; no gravity.
local function scene(extra)
  local w = world{gravity = vec3()}
  local list = {}
  for i = 1, extra do
    list[i] = w:add(body.sphere{mass = 1, radius = 0.1, position = vec3(10 + i, 0, 0)})
  end
  local a = w:add(body.sphere{mass = 2, radius = 0.5, position = vec3(0, 0, 0),
                              velocity = vec3(1, 0.5, 0)})
  local b = w:add(body.box{mass = 3, size = vec3(1, 1, 1), position = vec3(1, 0.2, 0),
                           velocity = vec3(-1, 0, 0.25)})
  local c = w:add(body.sphere{mass = 5, radius = 0.5, position = vec3(-3, 0, 0),
                              velocity = vec3(0, 0, 1)})
  return w, a, b, c, list
end

local contact = {point = vec3(0.5, 0.1, 0), normal = vec3(1, 0.1, 0), restitution = 0.5,
                 friction = 0.3}

T.case("collide.resolve: bodies added while the options are read (the vector moves)", function()
  local _, a0, b0, c0 = scene(0)
  local J0, f0 = collide.resolve(a0, b0, contact)
  local w, a, b, c = scene(0)
  local J, f = collide.resolve(a, b, meddling(contact, function()
    for _ = 1, 64 do w:add(body.sphere{mass = 1, radius = 0.1, position = vec3(0, 50, 0)}) end
  end))
  T.equal(J, J0, "the same normal impulse")
  T.equal(f, f0, "the same friction impulse")
  T.equal(a.velocity, a0.velocity, "a got it"); T.equal(b.velocity, b0.velocity, "b got it")
  T.equal(a.angular_velocity, a0.angular_velocity, "a's spin")
  T.equal(c.velocity, c0.velocity, "the bystander c got nothing")
  T.equal(#w:bodies(), 3 + 4 * 64, "the bodies were added")
end)

T.case("collide.resolve: a removed from its world while the options are read", function()
  local w0, a0, b0, c0 = scene(2)
  w0:remove(a0)
  local J0 = collide.resolve(a0, b0, contact)
  local w, a, b, c = scene(2)
  local J = collide.resolve(a, b, meddling(contact, function()
    if w:bodies()[3] == a then w:remove(a) end
  end))
  T.equal(J, J0, "the same impulse")
  T.equal(a.velocity, a0.velocity, "a (now alone) got it")
  T.equal(b.velocity, b0.velocity, "b got it")
  T.equal(c.velocity, c0.velocity, "the bystander c, now at a's old index, got nothing")
end)

T.case("collide.resolve: a finalised while the options are read", function()
  local _, a, b, c = scene(0)
  local gc = debug.getmetatable(a).__gc
  local before = b.velocity
  T.fails(function()
    collide.resolve(a, b, meddling(contact, function() gc(a) end))
  end, "bad argument #1 to 'collide.resolve' (must be a body, got a finalised one", "refused")
  T.equal(b.velocity, before, "b unchanged")
end)

-- The spring's force is seen in the potential energy: ½ k |xa − xb|² with rest length 0.
local function spring_energy(a, b, k)
  local d = a.position - b.position
  return 0.5 * k * d:dot(d)
end

T.case("w:add_spring: a body removed while the options are read", function()
  local w, a, b, c, extra = scene(3)
  local removed = false
  w:add_spring(meddling({a = a, b = b, k = 40}, function()
    if not removed then removed = true; w:remove(extra[1]) end
  end))
  T.equal(removed, true, "the metamethod ran")
  T.near(w:potential_energy(), spring_energy(a, b, 40), 1e-13, "the spring joins a and b")
  T.equal(c.velocity, vec3(0, 0, 1), "c untouched")
  -- Which bodies it pulls: after a step, a and b moved toward each other, c did not turn.
  w:step(0.01)
  T.equal(c.velocity, vec3(0, 0, 1), "no force on c")
  T.equal(extra[2].velocity, vec3(), "no force on the body at a's old index")
end)

T.case("w:add_spring: bodies added while the options are read", function()
  local w, a, b = scene(0)
  w:add_spring(meddling({a = a, b = b, k = 10}, function()
    for _ = 1, 32 do w:add(body.sphere{mass = 1, radius = 0.1, position = vec3(0, 90, 0)}) end
  end))
  T.near(w:potential_energy(), spring_energy(a, b, 10), 1e-13, "the spring joins a and b")
end)

T.case("w:add_drag: a body removed while the options are read", function()
  local w, _, _, c, extra = scene(2)
  local removed = false
  w:add_drag(meddling({body = c, linear = 50}, function()
    if not removed then removed = true; w:remove(extra[1]) end
  end))
  extra[2].velocity = vec3(0, 1, 0)
  w:step(0.01)
  T.equal(extra[2].velocity, vec3(0, 1, 0), "the body now at c's old index minus one: no drag")
  T.near(c.velocity, vec3(0, 0, 1 - 0.01 * 50 / 5), 1e-15, "c has it: v - dt c v / m")
end)

T.case("constructors read their option tables before the object exists", function()
  local w, a = scene(0)
  local made = body(meddling({mass = 2, inertia = mat3.identity(), velocity = vec3(1, 2, 3)},
    function() w:add(body.sphere{mass = 1, radius = 1}) end))
  T.equal(made.velocity, vec3(1, 2, 3), "a body")
  local v = world(meddling({substeps = 3, gravity = vec3(0, -1, 0)},
    function() if #w:bodies() > 1 then w:remove(w:bodies()[#w:bodies()]) end end))
  T.equal(v.substeps, 3, "a world")
  T.equal(w:bodies()[1], a, "the other world is consistent")
end)

T.finish()
