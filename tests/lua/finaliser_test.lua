-- Finalisers called by hand (issue 12 item 2): debug.getmetatable(w).__gc(w) from a force
-- callback used to free the world the running step was using (SIGSEGV in evaluate_forces).
-- A world's or body's __gc is refused while its world steps, and after it has run the object
-- is no object any more: every use is a clean error, a second __gc does nothing. Run under
-- ASan by the sanitizer build, which would report any use after free.
local T = dofile("testing.lua")

local world_gc = debug.getmetatable(world{}).__gc
local body_gc = debug.getmetatable(body{static = true}).__gc

local function falling_world()
  local w = world{}
  local b = w:add(body.sphere{mass = 1, radius = 0.5, position = vec3(0, 2, 0)})
  return w, b
end

T.case("a world's __gc from its own force callback is refused, and the step goes on", function()
  local w, b = falling_world()
  local message
  w:add_force(function(v)
    local ok, e = pcall(world_gc, v)
    if not ok then message = e end
  end)
  w:step(0.01, 10)
  T.equal(message, "bad argument #1 to 'world.__gc' (the world is stepping: it cannot be " ..
    "finalised until world:step returns)", "refused")
  T.near(w.time, 0.1, 1e-15, "all ten steps ran")
  T.near(b.velocity, vec3(0, -0.981, 0), 1e-12, "the body fell as it should")
end)

T.case("the issue's script: __gc by hand in the callback, then step", function()
  local w = falling_world()
  w:add_force(function(v) debug.getmetatable(v).__gc(v) end)
  T.fails(function() w:step(0.01) end, "the world is stepping: it cannot be finalised",
    "the callback's error stops the step")
  T.equal(w.time, 0, "the step was undone")
  T.fails(function() w:step(0.01) end, "the world is stepping", "and again, cleanly")
  T.equal(#w:bodies(), 1, "the world is intact")
end)

T.case("a body's __gc from a force callback of its world is refused", function()
  local w, b = falling_world()
  local message
  w:add_force(function() local ok, e = pcall(body_gc, b); message = e end)
  w:step(0.01)
  T.equal(message, "bad argument #1 to 'body.__gc' (the body's world is stepping: it cannot " ..
    "be finalised until world:step returns)", "refused")
  T.equal(tostring(b):sub(1, 12), "body(sphere,", "the body is still a body")
end)

T.case("after __gc by hand the object is no object: clean errors, a second __gc is harmless", function()
  local w, b = falling_world()
  world_gc(w)
  world_gc(w)  -- nothing: no double free
  T.fails(function() w:step(0.01) end,
    "calling 'world:step' on bad self (the world was finalised (its __gc has run; it is used " ..
    "from a finaliser))", "step")
  T.fails(function() return w.time end, "the world was finalised", "a field")
  T.fails(function() w.gravity = vec3() end, "the world was finalised", "an assignment")
  T.fails(function() return tostring(w) end, "the world was finalised", "tostring")
  -- Its bodies keep the world's storage and stay usable; they may join another world.
  T.near(b.position, vec3(0, 2, 0), 0, "the body is readable")
  local v = world{}
  v:add(b)
  v:step(0.1)
  T.near(b.velocity, vec3(0, -0.981, 0), 1e-12, "and moves in its new world")
  body_gc(b)
  body_gc(b)
  T.fails(function() return b.position end,
    "bad argument #1 to 'body.__index' (must be a body, got a finalised one", "a finalised body")
  T.fails(function() v:remove(b) end, "got a finalised one", "w:remove of a finalised body")
  T.fails(function() v:add(b) end, "got a finalised one", "w:add of a finalised body")
  v:step(0.1)  -- the world still steps its (now unreachable) body: its store owns it
  T.equal(#v:bodies(), 1, "the world's list is unchanged")
end)

T.case("a finaliser that finalises a world mid-call cannot free what the call uses", function()
  -- A table collected during the option table's reading finalises the world by hand; the
  -- method must see it and refuse, not write into freed memory.
  local w, b = falling_world()
  local opts = setmetatable({}, {__index = function(_, key)
    if key == "k" then world_gc(w) return 10 end
  end})
  opts.a = b
  opts.anchor = vec3()
  T.fails(function() w:add_spring(opts) end,
    "calling 'world:add_spring' on bad self (the world was finalised", "add_spring")
  local v, c = falling_world()
  local plane = setmetatable({}, {__index = function(_, key)
    if key == "offset" then world_gc(v) end
  end})
  T.fails(function() v:add_plane(plane) end, "the world was finalised", "add_plane")
  T.near(c.position, vec3(0, 2, 0), 0, "its body is intact")
end)

T.finish()
