-- Contacts through Lua: w:add_plane, w:planes, w:contacts, body materials and the world's
-- contact settings, with their exact error texts; and the physics a user sees: a ball
-- rebounds to e² of its height (001 Appendix C), rolls at 5/7 of its speed, rests, e = 0 does
-- not bounce, friction 0 never spins it, a box landing flat does not spin, a stack stands.
local T = dofile("testing.lua")

local function floor_world(fields, plane)
  local w = world(fields or {})
  w:add_plane(plane or {})
  return w
end

T.case("add_plane: defaults, normalisation, index, planes()", function()
  local w = world{}
  T.equal(w:add_plane{}, 1, "first index")
  T.equal(w:add_plane{normal = vec3(0, 0, -4), offset = 8, restitution = 0.25, friction = 0},
    2, "second index")
  local planes = w:planes()
  T.equal(#planes, 2, "two planes")
  T.equal(planes[1].normal, vec3(0, 1, 0), "default normal")
  T.equal(planes[1].offset, 0, "default offset")
  T.equal(planes[1].restitution, 0, "default restitution")
  T.equal(planes[1].friction, 0.6, "default friction")
  -- −4 z >= 8 is the half-space −z >= 2.
  T.equal(planes[2].normal, vec3(0, 0, -1), "unit normal")
  T.equal(planes[2].offset, 2, "offset / |normal|")
  T.equal(planes[2].restitution, 0.25, "restitution")
  T.equal(planes[2].friction, 0, "friction")
end)

T.case("add_plane: errors", function()
  local w = world{}
  T.fails(function() w:add_plane{normal = vec3()} end,
    "bad argument #1 to 'world:add_plane' (field 'normal' must be a non-zero vector, got (0, 0, 0))")
  T.fails(function() w:add_plane{normal = 1} end,
    "bad argument #1 to 'world:add_plane' (field 'normal' must be a vec3, got number)")
  T.fails(function() w:add_plane{offset = math.huge} end,
    "bad argument #1 to 'world:add_plane' (field 'offset' must be finite, got inf)")
  T.fails(function() w:add_plane{restitution = 2} end,
    "bad argument #1 to 'world:add_plane' (field 'restitution' must be in [0, 1], got 2)")
  T.fails(function() w:add_plane{friction = -1} end,
    "bad argument #1 to 'world:add_plane' (field 'friction' must be finite and >= 0, got -1)")
  T.fails(function() w:add_plane{normale = vec3(0, 1, 0)} end,
    "bad argument #1 to 'world:add_plane' (unknown field 'normale' (fields are: normal, offset, " ..
    "restitution, friction))")
  T.fails(function() w:add_plane(3) end,
    "bad argument #1 to 'world:add_plane' (table expected, got number)")
  -- Counted like the errors above: the table is #1, so an extra argument is #2 of 1.
  T.fails(function() w:add_plane({}, 3) end,
    "bad argument #2 to 'world:add_plane' (no more than 1 argument (the table) expected, got 2)")
  T.equal(#w:planes(), 0, "nothing was added")
end)

T.case("body materials: defaults, fields, errors", function()
  local b = body.sphere{mass = 1, radius = 1}
  T.equal(b.restitution, 0, "default restitution")
  T.equal(b.friction, 0.6, "default friction")
  b.restitution, b.friction = 0.75, 0.2
  T.equal(b.restitution, 0.75, "set restitution")
  T.equal(b.friction, 0.2, "set friction")
  local c = body.box{mass = 1, size = vec3(1, 1, 1), restitution = 1, friction = 0}
  T.equal(c.restitution, 1, "constructor restitution")
  T.equal(c.friction, 0, "constructor friction")
  T.fails(function() b.restitution = 1.5 end,
    "bad field 'restitution' of body (must be in [0, 1], got 1.5)")
  T.fails(function() b.friction = -0.1 end,
    "bad field 'friction' of body (must be finite and >= 0, got -0.1)")
  T.fails(function() b.friction = "high" end,
    "bad field 'friction' of body (number expected, got string)")
  T.equal(b.friction, 0.2, "unchanged after the errors")
  T.fails(function() return body.sphere{mass = 1, radius = 1, restitution = -1} end,
    "bad argument #1 to 'body.sphere' (field 'restitution' must be in [0, 1], got -1)")
  T.fails(function() return body{mass = 1, inertia = mat3.identity(), friction = 0 / 0} end,
    "bad argument #1 to 'body' (field 'friction' must be finite and >= 0, got nan)")
  T.fails(function() return world{}:add_plane{friction = 0 / 0} end,
    "bad argument #1 to 'world:add_plane' (field 'friction' must be finite and >= 0, got nan)",
    "planes and bodies share the material rules")
end)

T.case("world contact settings: defaults, constructor, fields, errors", function()
  local w = world{}
  local defaults = {iterations = 10, position_iterations = 3, restitution_threshold = 1,
                    slop = 0.005, baumgarte = 0.2, max_correction = 0.2,
                    speculative_distance = 0.02}
  for name, value in pairs(defaults) do T.equal(w[name], value, "default " .. name) end
  local changed = {iterations = 30, position_iterations = 0, restitution_threshold = 0.25,
                   slop = 0.001, baumgarte = 1, max_correction = 0.05, speculative_distance = 0}
  for name, value in pairs(changed) do
    w[name] = value
    T.equal(w[name], value, "set " .. name)
  end
  local v = world(changed)
  for name, value in pairs(changed) do T.equal(v[name], value, "constructor " .. name) end
  local function fails(text, fn) T.fails(fn, text, text) end
  fails("bad field 'iterations' of world (must be an integer from 1 to 1000, got 0)",
    function() w.iterations = 0 end)
  fails("bad field 'iterations' of world (must be an integer from 1 to 1000, got 2.5)",
    function() w.iterations = 2.5 end)
  fails("bad field 'position_iterations' of world (must be an integer from 0 to 1000, got -1)",
    function() w.position_iterations = -1 end)
  fails("bad field 'restitution_threshold' of world (must be a finite number >= 0 (m/s), " ..
    "got -1)", function() w.restitution_threshold = -1 end)
  fails("bad field 'slop' of world (must be a finite number >= 0 (m), got inf)",
    function() w.slop = math.huge end)
  fails("bad field 'baumgarte' of world (must be a number from 0 to 1, got 1.5)",
    function() w.baumgarte = 1.5 end)
  fails("bad field 'max_correction' of world (must be a finite number >= 0 (m), got nan)",
    function() w.max_correction = 0 / 0 end)
  fails("bad field 'speculative_distance' of world (number expected, got boolean)",
    function() w.speculative_distance = true end)
  fails("bad argument #1 to 'world' (field 'iterations' must be an integer from 1 to 1000, " ..
    "got 'many')", function() return world{iterations = "many"} end)
  fails("bad argument #1 to 'world' (field 'slop' must be a finite number >= 0 (m), got -0.1)",
    function() return world{slop = -0.1} end)
  for name, value in pairs(changed) do T.equal(w[name], value, "unchanged after errors: " .. name) end
end)

T.case("slop: a sunk box rises until it overlaps the floor by the slop", function()
  -- sequential_impulses' position correction removes β (overlap − slop) per sweep (Box2D
  -- v2.4), a geometric approach to overlap = slop; the slop is at most 1 % of the body's
  -- smallest size, so a 0.1 m cube rests 1 mm deep where a 1 m cube rests 5 mm deep.
  for _, case in ipairs{{size = 1, slop = 0.005, want = 0.005}, {size = 1, slop = 0.002, want = 0.002},
                        {size = 0.1, slop = 0.005, want = 0.001}} do
    local w = floor_world({slop = case.slop, solver = "sequential_impulses"})
    local box = w:add(body.box{mass = 1, size = vec3(case.size, case.size, case.size),
                               position = vec3(0, case.size / 2 - 0.03, 0)})
    w:step(1 / 60, 600)
    T.near(case.size / 2 - box.position.y, case.want, 1e-6, "rests the slop deep")
  end
  -- soft_step pushes the overlap out to 4 % of the slop (help(world), slop): a damped spring
  -- on it, moving positions only, whose rest is that overlap; a box placed touching stays.
  for _, case in ipairs{{size = 1, want = 0.04 * 0.005}, {size = 0.1, want = 0.04 * 0.001}} do
    local w = floor_world()
    local half = case.size / 2
    local box = w:add(body.box{mass = 1, size = vec3(case.size, case.size, case.size),
                               position = vec3(0, half - 0.03 * case.size, 0)})
    w:step(1 / 60, 600)
    T.near(half - box.position.y, case.want, 1e-9, "soft_step: rests 4 % of the slop deep")
    T.near(box.velocity, vec3(), 1e-12, "soft_step: and the push-out left no velocity")
  end
  local w = floor_world()
  local box = w:add(body.box{mass = 1, size = vec3(1, 1, 1), position = vec3(0, 0.5, 0)})
  w:step(1 / 60, 600)
  T.near(box.position.y, 0.5, 1e-12, "soft_step: a box set on the floor stays there")
end)

T.case("contacts(): a ball on the floor and two balls touching", function()
  local dt = 1 / 60
  local w = floor_world()
  local ball = w:add(body.sphere{mass = 2, radius = 0.5, position = vec3(0, 0.5, 0)})
  T.equal(#w:contacts(), 0, "none before the first step")
  w:step(dt)
  local cs = w:contacts()
  T.equal(#cs, 1, "one contact")
  local c = cs[1]
  -- One convention for every contact: the normal from a to b, the impulses b's. Against a
  -- plane, a is the plane (a = nil, plane = its index) and b the ball.
  T.equal(c.a, nil, "a is the plane: nil")
  T.equal(c.b, ball, "b is the ball")
  T.equal(c.plane, 1, "the plane's index")
  T.near(c.normal, vec3(0, 1, 0), 0, "the plane's normal, from the plane to the ball")
  T.near(c.point, vec3(0, 0, 0), 1e-12, "at the bottom of the ball")
  T.near(c.depth, 0, 1e-12, "touching")
  -- Holding the ball for one step: the floor gives exactly what gravity took, m g Δt.
  T.near(c.normal_impulse, 2 * 9.81 * dt, 1e-12, "normal impulse m g dt")
  T.near(c.friction_impulse, vec3(), 1e-15, "no friction needed")
  T.equal(c.restitution, 0, "mixed restitution")
  T.near(c.friction, 0.6, 1e-15, "mixed friction")
  T.near(ball.position, vec3(0, 0.5, 0), 1e-12, "the ball stays")

  local v = world{gravity = vec3()}
  local a = v:add(body.sphere{mass = 1, radius = 0.5, velocity = vec3(2, 0, 0), restitution = 1})
  local b = v:add(body.sphere{mass = 1, radius = 0.5, position = vec3(1.01, 0, 0)})
  -- The 1 cm gap closes during the first step of 0.01 s: a lands on b at its end, and they
  -- bounce in the same step with the 2 m/s they met with, so the state the step leaves is
  -- after the impact. Equal masses, e = 1: they exchange velocities (001 "System Of
  -- Particles"), J = m v = 2.
  v:step(0.01)
  cs = v:contacts()
  T.equal(#cs, 1, "one contact between the balls")
  T.equal(cs[1].a, a, "a"); T.equal(cs[1].b, b, "b"); T.equal(cs[1].plane, nil, "no plane")
  T.near(cs[1].normal, vec3(1, 0, 0), 1e-15, "from a to b")
  T.near(cs[1].depth, -0.01, 1e-12, "the gap the step closed")
  T.near(cs[1].normal_impulse, 2, 1e-12, "impulse")
  T.near(a.velocity, vec3(0, 0, 0), 1e-12, "a stops")
  T.near(b.velocity, vec3(2, 0, 0), 1e-12, "b leaves at 2 m/s")
  v:step(0.01)
  v:remove(a)
  T.equal(v:contacts()[1], nil, "the removed ball's contact is gone")
end)

-- Drops a ball (radius 0.1) with its bottom at height h and returns the apex after the bounce.
local function rebound_apex(h, e, dt, integrator)
  local w = floor_world({integrator = integrator}, {restitution = e})
  local ball = w:add(body.sphere{mass = 1, radius = 0.1, position = vec3(0, h + 0.1, 0)})
  local rising, apex = false, 0
  for _ = 1, 100000 do
    w:step(dt)
    local vy = ball.velocity.y
    if vy > 0 then rising = true end
    if rising then
      apex = math.max(apex, ball.position.y - 0.1)
      if vy < 0 then return apex end
    end
  end
end

T.case("a dropped ball rebounds to e² of its height", function()
  for _, integrator in ipairs{"semi_implicit", "euler", "rk4"} do
    local apex = rebound_apex(1, 0.8, 1e-3, integrator)
    T.near(apex / 0.64, 1, 0.03, integrator .. ": apex / (e² h)")
  end
end)

T.case("restitution 0 does not bounce; friction 0 never spins", function()
  local w = floor_world()
  local ball = w:add(body.sphere{mass = 1, radius = 0.2, position = vec3(0, 1.2, 0)})
  local highest, landed = 0, false
  for _ = 1, 180 do
    w:step(1 / 60)
    if ball.position.y < 0.2 + 1e-6 then landed = true end
    if landed then highest = math.max(highest, ball.position.y) end
  end
  T.equal(landed, true, "landed")
  T.near(highest, 0.2, 1e-6, "never rose again")

  local v = floor_world({}, {friction = 0, restitution = 0.5})
  local slider = v:add(body.sphere{mass = 1, radius = 0.2, position = vec3(0, 1, 0),
                                   velocity = vec3(3, -2, 1), restitution = 0.5})
  for _ = 1, 300 do
    v:step(1 / 60)
    T.equal(slider.angular_velocity, vec3(), "no spin")
  end
  T.near(slider.velocity.x, 3, 1e-12, "nor slowed")
end)

T.case("a ball pushed along the floor ends rolling at 5/7 of its speed", function()
  local w = floor_world({}, {friction = 0.3})
  local r = 0.25
  local ball = w:add(body.sphere{mass = 1, radius = r, position = vec3(0, r, 0),
                                 velocity = vec3(3, 0, 0)})
  w:step(1 / 60, 120)
  T.near(ball.velocity.x / (5 / 7 * 3), 1, 0.02, "v / (5/7 v0)")
  T.near(-ball.angular_velocity.z * r, ball.velocity.x, 1e-9, "rolling: v = ω r")
end)

T.case("resting bodies stay: a ball and a stack of three boxes for 10 s at 60 Hz", function()
  local w = floor_world()
  local ball = w:add(body.sphere{mass = 1, radius = 0.3, position = vec3(5, 0.3, 0)})
  local boxes = {}
  for k = 1, 3 do
    boxes[k] = w:add(body.box{mass = 1, size = vec3(1, 1, 1), position = vec3(0, k - 0.5, 0)})
  end
  local top0, drift, moved = boxes[3].position, 0, 0
  for _ = 1, 600 do
    w:step(1 / 60)
    drift = math.max(drift, (ball.position - vec3(5, 0.3, 0)):norm())
    moved = math.max(moved, (boxes[3].position - top0):norm())
  end
  T.near(drift, 0, 1e-3, "ball drift (m)")
  T.near(moved, 0, 1e-2, "top box moved (m)")
end)

T.case("a box landing flat does not spin; on an edge it does", function()
  local function largest_spin(tilt)
    local w = floor_world()
    local box = w:add(body.box{mass = 1, size = vec3(1, 0.5, 0.7), position = vec3(0, 1, 0),
                               orientation = quat.axis_angle(vec3(0, 0, 1), tilt)})
    local largest = 0
    for _ = 1, 120 do
      w:step(1 / 60)
      largest = math.max(largest, box.angular_velocity:norm())
    end
    return largest
  end
  T.near(largest_spin(0), 0, 1e-3, "flat: |ω| (rad/s)")
  local edge = largest_spin(0.3)
  if not (edge > 1) then error("on an edge: |ω| = " .. edge .. ", want > 1 rad/s") end
end)

T.finish()
