-- Joints from Lua (API.md "Joints"): the fields and methods of the contract against closed
-- forms (a hinged pendulum's energy, a free hinge's angle past 2π), bad input with its exact
-- messages, and removal (w:remove_joint, a removed body takes its joints along).
local T = dofile("testing.lua")

local function pendulum(kind, solver)
  local w = world{solver = solver, substeps = 4}
  local bob = w:add(body.sphere{mass = 1, radius = 0.05, position = vec3(1, 0, 0)})
  local j
  if kind == "distance" then
    j = w:add_joint{type = "distance", a = bob, b_point = vec3(0, 0, 0)}
  else
    j = w:add_joint{type = "hinge", a = bob, anchor = vec3(0, 0, 0), axis = vec3(0, 0, 1)}
  end
  return w, bob, j
end

T.case("fields of a hinge and of a distance rod", function()
  for _, solver in ipairs{"soft_step", "sequential_impulses"} do
    local w, bob, j = pendulum("hinge", solver)
    T.equal(j.type, "hinge", "type"); T.equal(j.a, bob, "a is the same body object")
    T.equal(j.b, nil, "b: the world"); T.equal(j.angle, 0, "angle 0 at creation")
    T.equal(j.axis, vec3(0, 0, 1), "axis")
    T.equal(j.anchor, vec3(0, 0, 0), "anchor")
    -- Energy (a conservation law): the semi-implicit step's energy swings by O(h) about the
    -- true value (0.6 % of m g L at 240 Hz) and must not drift over 10 s (5 periods).
    local e0, worst = w:energy(), 0
    for _ = 1, 600 do
      w:step(1 / 60)
      worst = math.max(worst, math.abs(w:energy() - e0))
    end
    assert(worst < 0.01 * 9.81, solver .. ": energy kept to 1 % of m g L, off by " .. worst)
    w:step(1 / 60, 30)
    -- The angle is the arm's: atan2 of the bob's position, measured from +x.
    T.near(math.sin(j.angle - math.atan(bob.position.y, bob.position.x)), 0, 1e-3,
      "angle is the arm's")
    T.near(j.rate, bob.angular_velocity.z, 1e-9, "rate of a hinge about z")
    local position, angle = j:error()
    assert(position < 1e-3 and angle < 1e-6, "error " .. position .. " " .. angle)
    -- The rod pulls the bob toward the pivot: b is the world, so the impulse is on... a got
    -- −impulse: toward the pivot (−x side of the bob at the bottom).
    T.equal(#w:joints(), 1, "one joint"); T.equal(w:joints()[1], j, "the same object")
    local report = w:solver_report()
    T.equal(#report, w.iterations, "one entry per iteration")
  end
  local w, bob, rod = pendulum("distance", "soft_step")
  T.near(rod.length, 1, 1e-12, "length at creation")
  w:step(1 / 60, 30)
  T.near(rod.length, 1, 1e-3, "the rod holds")
end)

T.case("a free hinge counts its turns", function()
  local w = world{gravity = vec3(0, 0, 0)}
  local wheel = w:add(body.box{mass = 1, size = vec3(1, 0.2, 0.2), angular_velocity = vec3(0, 0, 10)})
  local j = w:add_joint{type = "hinge", a = wheel, axis = vec3(0, 0, 1)}
  w:step(0.01, 100)
  T.near(j.angle, 10, 1e-9, "10 rad after 1 s at 10 rad/s")
  T.near(j.rate, 10, 1e-9, "rate")
end)

T.case("limits, springs and motors", function()
  local w = world{gravity = vec3(0, 0, 0), substeps = 4}
  local wheel = w:add(body.box{mass = 1, size = vec3(1, 1, 1), angular_velocity = vec3(0, 0, 3)})
  local j = w:add_joint{type = "hinge", a = wheel, axis = vec3(0, 0, 1), upper = 0.5}
  w:step(1 / 60, 60)
  assert(j.angle <= 0.5 + 1e-3, "upper limit holds: " .. j.angle)
  j:set_limits(nil, nil)
  T.equal(j.upper, math.huge, "no limit")
  j:set_motor{target = 1, kp = 10, kv = 2, max_torque = 0.5}
  w:step(1 / 60)
  assert(math.abs(j.motor_torque) <= 0.5 + 1e-12, "clamped to max_torque")
  j:set_motor(nil)
  w:step(1 / 60)
  T.equal(j.motor_torque, 0, "no motor")
end)

T.case("bad input", function()
  local w = world()
  local b = w:add(body.sphere{mass = 1, radius = 0.1})
  T.fails(function() w:add_joint{type = "hing", a = b} end,
    "bad argument #1 to 'world:add_joint' (field 'type' must be one of 'ball', 'hinge', " ..
    "'slider', 'cylindrical', 'planar', 'screw', 'fixed', 'distance', got 'hing')", "unknown type")
  T.fails(function() w:add_joint{type = "hinge", a = b, axis = vec3(0, 0, 0)} end,
    "field 'axis' must be a non-zero vector, got (0, 0, 0)", "zero axis")
  T.fails(function() w:add_joint{type = "hinge", a = b} end, "field 'axis' is required", "no axis")
  T.fails(function() w:add_joint{type = "ball"} end, "field 'a' (a body) is required", "no a")
  T.fails(function() w:add_joint{type = "ball", a = b, b = b} end, "must be different bodies", "a = b")
  T.fails(function() w:add_joint{type = "ball", a = b, pitch = 1} end,
    "field 'pitch' is not for a ball joint", "a field of another type")
  T.fails(function() w:add_joint{type = "hinge", a = b, axis = vec3(0, 0, 1), lower = 1, upper = 0} end,
    "the limits must satisfy lower <= upper", "crossed limits")
  local other = world()
  local c = other:add(body.sphere{mass = 1, radius = 0.1})
  T.fails(function() w:add_joint{type = "ball", a = b, b = c} end,
    "field 'b' must be a body in this world (w:add it first), got a body in another world",
    "a body of another world")
  local lone = body.sphere{mass = 1, radius = 0.1}
  T.fails(function() w:add_joint{type = "ball", a = lone} end, "got a body in no world", "a lone body")
  T.equal(#w:joints(), 0, "nothing was added by the failed calls")
end)

T.case("removing joints and bodies", function()
  local w = world()
  local a = w:add(body.sphere{mass = 1, radius = 0.1})
  local b = w:add(body.sphere{mass = 1, radius = 0.1, position = vec3(1, 0, 0)})
  local j1 = w:add_joint{type = "ball", a = a}
  local j2 = w:add_joint{type = "fixed", a = a, b = b}
  w:remove_joint(j1)
  T.equal(#w:joints(), 1, "one left"); T.equal(w:joints()[1], j2, "the other one")
  T.fails(function() return j1.angle end, "the joint was removed from its world", "a removed joint")
  T.fails(function() w:remove_joint(j1) end, "the joint was already removed", "removed twice")
  w:remove(b)
  T.equal(#w:joints(), 0, "removing a body removes its joints")
  T.fails(function() return j2:error() end, "the joint was removed", "its joint is gone")
  T.equal(j2.type, "fixed", "the type is still known")
  T.fails(function() w:add_joint{type = "ball", a = b} end, "got a body in no world", "a removed body")
end)

-- Two unit cubes side by side, b hinged to a (static) at the top of their shared face: b's
-- lower edge swings into a. Without `collide` (the default) b is a free physical pendulum,
-- I about the edge = m/6 + m d² = 2/3 kg m² with d² = 0.5 m², released 45° from below the
-- edge: at the bottom ½ I ω² = m g d (1 − cos 45°). With collide = true the cubes touch and
-- b stays where it is.
local function hinged_cubes(collide, solver)
  local w = world{solver = solver, substeps = 4}
  local a = w:add(body.box{mass = math.huge, size = vec3(1, 1, 1)})
  local b = w:add(body.box{mass = 1, size = vec3(1, 1, 1), position = vec3(1, 0, 0)})
  local j = w:add_joint{type = "hinge", a = b, b = a, anchor = vec3(0.5, 0.5, 0),
                        axis = vec3(0, 0, 1), collide = collide}
  local fastest, farthest = 0, 0
  for _ = 1, 60 do
    w:step(1 / 60)
    fastest = math.max(fastest, math.abs(j.rate))
    farthest = math.max(farthest, math.abs(j.angle))
  end
  return j, fastest, farthest
end

T.case("jointed bodies do not collide unless the joint says collide = true", function()
  local g, d = 9.81, math.sqrt(0.5)
  local omega = math.sqrt(2 * g * d * (1 - math.cos(math.pi / 4)) / (2 / 3))
  for _, solver in ipairs({"soft_step", "sequential_impulses"}) do
    local j, fastest, farthest = hinged_cubes(nil, solver)
    T.equal(j.collide, false, "the default")
    T.near(fastest, omega, 0.01 * omega, solver .. ": swings through as a physical pendulum")
    assert(farthest > 1, solver .. ": it swung " .. farthest .. " rad")
    local held, _, moved = hinged_cubes(true, solver)
    T.equal(held.collide, true, "asked for")
    assert(moved < 0.02, solver .. ": the contact holds it, turned " .. moved .. " rad")
  end
  local w = world{}
  local a = w:add(body.sphere{mass = 1, radius = 0.1})
  T.fails(function() w:add_joint{type = "ball", a = a, collide = 1} end,
    "bad argument #1 to 'world:add_joint' (field 'collide' must be a boolean, got number)",
    "not a boolean")
end)

T.finish()
