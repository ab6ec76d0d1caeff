-- Sleeping islands from Lua (engine/islands.hpp): world.sleeping and its tolerances, b.sleeping
-- and b:wake(),
-- what wakes an island, bad input, determinism.
local T = dofile("testing.lua")

local dt = 1 / 60

-- A column of three unit boxes on a floor (placed touching, at rest).
local function column(options)
  local w = world(options or {})
  w:add_plane{normal = vec3(0, 1, 0), offset = 0}
  local boxes = {}
  for i = 1, 3 do
    boxes[i] = w:add(body.box{mass = 1, size = vec3(1, 1, 1), position = vec3(0, i - 0.5, 0)})
  end
  return w, boxes
end

local function step_until_asleep(w, limit)
  local start = w.time
  while w.time - start < limit do
    w:step(dt)
    if w.sleeping_count == #w:bodies() then return w.time - start end
  end
  return nil
end

T.case("off by default: nothing sleeps", function()
  local w, boxes = column()
  T.equal(w.sleeping, false, "world.sleeping")
  w:step(dt, 120)
  T.equal(w.sleeping_count, 0, "sleeping bodies")
  T.equal(boxes[3].sleeping, false, "b.sleeping")
end)

T.case("a column at rest falls asleep after sleep_time, then does not move", function()
  local w, boxes = column{sleeping = true}
  T.equal(w.sleep_linear, 0.05, "default sleep_linear")
  T.near(w.sleep_angular, math.rad(2), 1e-15, "default sleep_angular")
  T.equal(w.sleep_time, 0.5, "default sleep_time")
  local took = step_until_asleep(w, 2)
  assert(took, "the column did not fall asleep within 2 s")
  assert(took >= 0.5 and took <= 0.5 + 2 * dt, "fell asleep after " .. took .. " s")
  for i = 1, 3 do T.equal(boxes[i].sleeping, true, "box " .. i) end
  local y = boxes[3].position.y
  w:step(dt, 300)
  T.equal(boxes[3].position.y, y, "top box after 5 s asleep")
  T.equal(boxes[3].velocity, vec3(0, 0, 0), "top box velocity")
end)

T.case("a longer sleep_time takes longer", function()
  local w = column{sleeping = true, sleep_time = 1.5}
  local took = step_until_asleep(w, 3)
  assert(took and took >= 1.5 and took <= 1.5 + 2 * dt, "fell asleep after " .. tostring(took))
end)

T.case("what wakes the island", function()
  local changes = {
    ["b:wake()"] = function(b) b:wake() end,
    ["b.position"] = function(b) b.position = b.position + vec3(0, 0.01, 0) end,
    ["b.orientation"] = function(b) b.orientation = quat.axis_angle(vec3(0, 1, 0), 0.1) end,
    ["b.velocity"] = function(b) b.velocity = vec3(0, 0, 0) end,
    ["b.angular_velocity"] = function(b) b.angular_velocity = vec3(0, 1, 0) end,
    ["b.friction"] = function(b) b.friction = 0.2 end,
    ["b:apply_force"] = function(b) b:apply_force(vec3(1, 0, 0)) end,
    ["b:apply_torque"] = function(b) b:apply_torque(vec3(1, 0, 0)) end,
    ["b:apply_impulse"] = function(b) b:apply_impulse(vec3(1, 0, 0)) end,
    ["b:apply_angular_impulse"] = function(b) b:apply_angular_impulse(vec3(0, 1, 0)) end,
    ["w.sleeping = false"] = function(_, w) w.sleeping = false end,
    ["w.gravity"] = function(_, w) w.gravity = vec3(0, -1.62, 0) end,
  }
  for name, change in pairs(changes) do
    local w, boxes = column{sleeping = true}
    assert(step_until_asleep(w, 2), name .. ": never asleep")
    change(boxes[1], w)
    -- the whole column is one island through its touching contacts
    T.equal(w.sleeping_count, 0, name .. ": sleeping bodies after")
    T.equal(boxes[3].sleeping, false, name .. ": the top box")
  end
end)

T.case("a ball dropped on the sleeping column wakes it; one flying past does not", function()
  local w, boxes = column{sleeping = true}
  assert(step_until_asleep(w, 2))
  local past = w:add(body.sphere{mass = 1, radius = 0.1, position = vec3(-3, 3.6, 0),
                                 velocity = vec3(25, 0, 0)})
  for _ = 1, 20 do
    w:step(dt)
    T.equal(boxes[3].sleeping, true, "while the ball flies past at t = " .. w.time)
  end
  assert(past.position.x > 3, "the flying ball went past")
  local ball = w:add(body.sphere{mass = 2, radius = 0.25, position = vec3(0.1, 4.25, 0)})
  local woke = false
  for _ = 1, 40 do
    w:step(dt)
    woke = woke or not boxes[3].sleeping
  end
  assert(woke, "the column woke")
  assert(ball.position.y < 3.3 and ball.position.y > 3.2, "the ball rests on the column: y = "
    .. ball.position.y)
end)

T.case("determinism: the same script, the same states", function()
  local function run()
    local w, boxes = column{sleeping = true}
    w:step(dt, 60)
    local ball = w:add(body.sphere{mass = 2, radius = 0.25, position = vec3(0.1, 4.25, 0.05),
                                   restitution = 0.5})
    w:step(dt, 90)
    local parts = {}
    for _, b in ipairs(w:bodies()) do
      parts[#parts + 1] = string.format("%a %a %a %a %a %a", b.position.x, b.position.y,
        b.position.z, b.velocity.x, b.velocity.y, b.velocity.z)
      parts[#parts + 1] = tostring(b.sleeping)
    end
    return table.concat(parts, "|")
  end
  T.equal(run(), run(), "two runs")
end)

T.case("bad input", function()
  T.fails(function() world{sleeping = 1} end,
    "bad argument #1 to 'world' (field 'sleeping' must be a boolean, got number)")
  local w, boxes = column()
  T.fails(function() w.sleeping = "yes" end, "bad field 'sleeping' of world")
  T.fails(function() w.sleep_linear = 0 end,
    "bad field 'sleep_linear' of world (must be finite and > 0, got 0)")
  T.fails(function() w.sleep_angular = 0 / 0 end, "bad field 'sleep_angular' of world")
  T.fails(function() w.sleep_time = math.huge end, "bad field 'sleep_time' of world")
  T.fails(function() world{sleep_time = -1} end, "field 'sleep_time' must be finite and > 0")
  T.fails(function() boxes[1].sleeping = true end,
    "bad field 'sleeping' of body (read-only: bodies fall asleep by themselves")
  T.fails(function() boxes[1]:wake(1) end, "bad argument #1 to 'body:wake' (no more than 1 argument expected, got 2)")
  T.fails(function() body.sphere{mass = 1, radius = 1, sleeping = false} end, "unknown field 'sleeping'")
  T.equal(w.sleep_linear, 0.05, "unchanged by the failed sets")
  T.equal(w.sleep_time, 0.5, "unchanged by the failed sets")
  T.fails(function() w.sleeping_count = 3 end, "sleeping_count")
end)

T.case("a hanging hinge pendulum sleeps; a new motor wakes it and turns it", function()
  local w = world{sleeping = true}
  local bob = w:add(body.sphere{mass = 1, radius = 0.1, position = vec3(0, -1, 0)})
  local j = w:add_joint{type = "hinge", a = bob, anchor = vec3(0, 0, 0), axis = vec3(0, 0, 1)}
  assert(step_until_asleep(w, 2), "the hanging bob never slept")
  j:set_motor{target_rate = 1, kv = 50}
  T.equal(bob.sleeping, false, "after j:set_motor")
  w:step(dt, 30)
  assert(bob.position.x > 0.1, "the motor turned the bob: x = " .. bob.position.x)
  assert(step_until_asleep(w, 1) == nil, "a driven pendulum never sleeps")
  j:set_motor(nil)
  w.sleeping = false
  w.sleeping = true
  T.equal(bob.sleeping, false, "w.sleeping = false woke it")
end)

T.case("a lone body is awake and can be woken harmlessly", function()
  local b = body.sphere{mass = 1, radius = 1}
  T.equal(b.sleeping, false, "lone body")
  b:wake()
  local w = world{sleeping = true}
  w:add(b)
  T.equal(b.sleeping, false, "just added")
end)

T.finish()
