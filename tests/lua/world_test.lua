-- world from Lua: motion against closed forms (projectile, spring statics, drag decay), force
-- callbacks at every RK4 stage, ownership of bodies (same objects back, survival across the
-- collector, remove gives the body its own storage), the step's guarantees (NaN refused and
-- undone, callback errors propagate and undo, re-entrance refused) and the exact error texts.
local T = dofile("testing.lua")

T.case("defaults and fields", function()
  local w = world()
  T.equal(w.gravity, vec3(0, -9.81, 0), "gravity"); T.equal(w.time, 0, "time")
  T.equal(w.integrator, "semi_implicit", "integrator"); T.equal(w.gyroscopic, "conserving", "gyroscopic")
  T.equal(w.substeps, 1, "substeps")
  w.gravity = vec3(0, 0, -1); w.integrator = "euler"; w.gyroscopic = "off"; w.substeps = 4
  T.equal(w.gravity, vec3(0, 0, -1), "gravity written"); T.equal(w.integrator, "euler", "integrator written")
  T.equal(w.gyroscopic, "off", "gyroscopic written"); T.equal(w.substeps, 4, "substeps written")
  w.gyroscopic = "conserving"; w.integrator = "rk4"
  T.equal(tostring(w), "world(0 bodies, t=0, rk4)", "tostring")
  w.substeps = 3.0
  T.equal(w.substeps, 3, "3.0 is an integer, as for luaL_checkinteger")
  T.equal(world{substeps = 2.0}.substeps, 2, "also in the constructor")
  local v = world{gravity = vec3(1, 0, 0), integrator = "euler", gyroscopic = "explicit", substeps = 2}
  T.equal(v.integrator, "euler", "constructor integrator"); T.equal(v.substeps, 2, "constructor substeps")
end)

-- x(t) = x0 + v0 t + ½ g t²: RK4 is exact for a quadratic.
T.case("projectile: rk4 is exact, semi-implicit overshoots by ½ g t dt", function()
  for _, method in ipairs{"rk4", "semi_implicit", "euler"} do
    local w = world{integrator = method}
    local b = w:add(body.sphere{mass = 1, radius = 0.1, position = vec3(0, 10, 0), velocity = vec3(3, 4, 0)})
    w:step(0.05, 40)
    local t = 2
    local exact = vec3(3 * t, 10 + 4 * t - 0.5 * 9.81 * t * t, 0)
    local offset = ({rk4 = 0, semi_implicit = -0.5 * 9.81 * t * 0.05, euler = 0.5 * 9.81 * t * 0.05})[method]
    T.near(b.position, exact + vec3(0, offset, 0), 1e-11, method)
    T.near(w.time, 2, 1e-14, "time")
  end
end)

T.case("spring: static deflection m g / k, and rest length", function()
  local w = world()
  local b = w:add(body.sphere{mass = 2, radius = 0.1})
  w:add_spring{a = b, anchor = vec3(0, 5, 0), k = 50, damping = 8}
  local c = w:add(body.sphere{mass = 2, radius = 0.1, position = vec3(3, 0, 0)})
  w:add_spring{a = c, anchor = vec3(3, 5, 0), k = 50, damping = 8, rest_length = 1.5}
  w:step(0.01, 2000)
  T.near(b.position, vec3(0, 5 - 2 * 9.81 / 50, 0), 1e-9, "rest length 0")
  T.near(c.position, vec3(3, 5 - 1.5 - 2 * 9.81 / 50, 0), 1e-9, "rest length 1.5")
end)

T.case("spring between two bodies at offset points conserves energy under rk4", function()
  local w = world{integrator = "rk4"}
  -- Bodies without collision shapes: a box and a ball on these springs would hit each other.
  local a = w:add(body{mass = 1, inertia = inertia.solid_box(1, 1, 0.5, 0.2)})
  local b = w:add(body{mass = 2, inertia = inertia.solid_sphere(2, 0.5),
                       position = vec3(1.5, -0.5, 0.3)})
  w:add_spring{a = a, a_point = vec3(0.5, 0.25, 0.1), b = b, b_point = vec3(0, 0.5, 0), k = 40,
    rest_length = 0.5}
  w:add_spring{a = a, a_point = vec3(-0.5, 0, 0), anchor = vec3(-1, 1, 0), k = 30}
  local e0 = w:energy()
  for _ = 1, 50 do
    w:step(1e-3, 100)
    T.near(w:energy(), e0, 1e-7 * math.abs(e0), "energy")
  end
  T.equal(w:energy(), w:kinetic_energy() + w:potential_energy(), "energy = kinetic + potential")
end)

T.case("drag decays v as exp(-c t / m)", function()
  local w = world{gravity = vec3(), integrator = "rk4"}
  local b = w:add(body.sphere{mass = 2, radius = 0.5, velocity = vec3(3, 0, 0), angular_velocity = vec3(0, 0, 5)})
  w:add_drag{body = b, linear = 0.4, angular = 0.1}  -- I = 0.2
  w:step(1e-3, 1000)
  T.near(b.velocity.x, 3 * math.exp(-0.2), 1e-12, "linear")
  T.near(b.angular_velocity.z, 5 * math.exp(-0.5), 1e-11, "angular")
end)

T.case("totals against hand-computed values", function()
  local w = world()
  local a = w:add(body.sphere{mass = 2, radius = 0.5, position = vec3(0, 2, 0), velocity = vec3(1, 0, 0),
    angular_velocity = vec3(0, 0, 3)})  -- I = 0.2
  w:add(body.sphere{mass = 2, radius = 0.5, position = vec3(1, 0, 0), velocity = vec3(0, 0, 2)})
  w:add(body{static = true, position = vec3(0, -100, 0)})
  T.near(w:kinetic_energy(), 1 + 0.9 + 4, 1e-14, "kinetic")
  T.near(w:potential_energy(), 2 * 9.81 * 2, 1e-12, "m g h, zero at the origin, statics excluded")
  T.equal(w:linear_momentum(), vec3(2, 0, 4), "Σ m v")
  T.near(w:angular_momentum(), vec3(0, -4, -4 + 0.6), 1e-14, "about the origin")
  T.near(w:angular_momentum(vec3(1, 0, 0)), vec3(0, 0, -4 + 0.6), 1e-14, "about (1, 0, 0)")
  T.near(a:angular_momentum(), vec3(0, 0, 0.6), 1e-15, "body: about its COM")
end)

T.case("force callbacks: called at every rk4 stage with the stage state", function()
  -- A Hooke spring written as a callback gives the same motion as the built-in spring.
  local function make(with_callback)
    local w = world{integrator = "rk4"}
    local b = w:add(body.box{mass = 1, size = vec3(1, 0.4, 0.2), position = vec3(1, 0, 0),
      angular_velocity = vec3(0.3, 0.2, 1)})
    local point, anchor, k, c = vec3(0.5, 0.2, 0), vec3(0, 1, 0), 20, 0.7
    if with_callback then
      w:add_force(function(world_, t)
        local p = b:to_world(point)
        local d = anchor - p
        local u = d / d:norm()
        local tension = k * d:norm() + c * (vec3() - b:point_velocity(p)):dot(u)
        b:apply_force(u * tension, p)
      end)
    else
      w:add_spring{a = b, a_point = point, anchor = anchor, k = k, damping = c}
    end
    return w, b
  end
  local w1, b1 = make(false)
  local w2, b2 = make(true)
  w1:step(0.01, 300); w2:step(0.01, 300)
  T.near(b2.position, b1.position, 1e-12, "position")
  T.near(b2.angular_velocity, b1.angular_velocity, 1e-12, "angular velocity")
  T.near(b2.orientation, b1.orientation, 1e-12, "orientation")
end)

T.case("gyroscopic and rk4: the field refuses what the constructor refuses", function()
  local w = world{integrator = "rk4"}
  T.fails(function() w.gyroscopic = "explicit" end,
    "bad field 'gyroscopic' of world (must not be set on an rk4 world: it is for the Euler "
    .. "integrators (rk4 always integrates the full Euler equations))")
  T.equal(w.gyroscopic, "conserving", "unchanged")
  local v = world{gyroscopic = "explicit"}
  T.fails(function() v.integrator = "rk4" end,
    "bad field 'integrator' of world ('rk4' ignores world.gyroscopic = 'explicit' (rk4 always "
    .. "integrates the full Euler equations): set world.gyroscopic = 'conserving' first)")
  T.equal(v.integrator, "semi_implicit", "unchanged")
  v.gyroscopic = "conserving"; v.integrator = "rk4"
  T.equal(v.integrator, "rk4", "allowed once the gyroscopic setting is the default")
end)

-- The stage states themselves, not only a comparison with the built-in spring: a body moving
-- at constant v (no forces) is at x0 + c v dt at the stage times t + c dt, c = 0, ½, ½, 1.
T.case("force callbacks: rk4 stage times and states", function()
  local w = world{integrator = "rk4", gravity = vec3()}
  local b = w:add(body.sphere{mass = 1, radius = 1, position = vec3(1, 0, 0), velocity = vec3(2, 0, 0)})
  w:step(0.5)
  local seen = {}
  w:add_force(function(_, t) seen[#seen + 1] = {t, b.position.x} end)
  w:step(0.25)
  local want = {{0.5, 2}, {0.625, 2.25}, {0.625, 2.25}, {0.75, 2.5}}
  T.equal(#seen, 4, "four stages")
  for i = 1, 4 do
    T.near(seen[i][1], want[i][1], 1e-15, "stage time " .. i)
    T.near(seen[i][2], want[i][2], 1e-15, "stage position " .. i)
  end
end)

-- ẍ = −x + cos 2t from rest at 0 (a callback force): x = (cos t − cos 2t)/3. The largest error
-- over 3 s falls 16-fold when dt halves only if the callback sees the stage states and times.
T.case("force callbacks: rk4 with a callback force converges at 4th order to the closed form", function()
  local function largest_error(dt)
    local w = world{integrator = "rk4", gravity = vec3()}
    local b = w:add(body.sphere{mass = 2, radius = 0.1})
    w:add_force(function(_, t) b:apply_force(vec3(b.mass * (-b.position.x + math.cos(2 * t)), 0, 0)) end)
    local largest = 0
    for _ = 1, math.floor(3 / dt + 0.5) do
      w:step(dt)
      local t = w.time
      largest = math.max(largest, math.abs(b.position.x - (math.cos(t) - math.cos(2 * t)) / 3))
    end
    return largest
  end
  local coarse, fine = largest_error(0.1), largest_error(0.05)
  T.near(math.log(coarse / fine, 2), 4, 0.1, "order")
  T.near(coarse, 0, 1e-5, "small")
end)

-- A stage state that overflows (v = 1e306 m/s, dt = 1000 s) ends the step before a callback
-- sees it: before, the callback was shown (inf, 0, 0) and could store it and write it back.
T.case("force callbacks never see a non-finite stage state", function()
  local w = world{integrator = "rk4", gravity = vec3()}
  local b = w:add(body.sphere{mass = 1, radius = 1, velocity = vec3(1e306, 0, 0)})
  local seen = {}
  w:add_force(function() seen[#seen + 1] = b.position end)
  T.fails(function() w:step(1000) end,
    "'world:step': body 1 of 1 would get a non-finite position in the step from t = 0 s to "
    .. "t = 1000 s; nothing was changed (the world is still at t = 0 s)")
  T.equal(#seen, 1, "only the first stage was shown")
  T.equal(seen[1], vec3(), "and it was finite")
  T.equal(b.position, vec3(), "undone")
end)

T.case("force callbacks: arguments and stage times", function()
  local w = world{integrator = "rk4", substeps = 2}
  w:add(body.sphere{mass = 1, radius = 1})
  local times, worlds = {}, {}
  w:add_force(function(world_, t) times[#times + 1] = t; worlds[#worlds + 1] = world_; T.equal(world_.time, t, "w.time") end)
  w:step(0.5)
  local want = {0, 0.125, 0.125, 0.25, 0.25, 0.375, 0.375, 0.5}
  T.equal(#times, #want, "eight evaluations")
  for i = 1, #want do T.equal(times[i], want[i], "stage time " .. i); T.equal(worlds[i], w, "the world") end
  T.equal(w.time, 0.5, "time after")
end)

T.case("ownership: same objects, survival across the collector, remove, two worlds", function()
  local w = world()
  do
    local b = body.sphere{mass = 1, radius = 1, position = vec3(0, 7, 0)}
    T.equal(w:add(b), b, "add returns the body")
    w:add(body.box{mass = 1, size = vec3(1, 1, 1)})
  end
  collectgarbage(); collectgarbage()
  local list = w:bodies()
  T.equal(#list, 2, "two bodies")
  T.equal(list[1].position, vec3(0, 7, 0), "a body only the world references survives the collector")
  T.equal(w:bodies()[1], list[1], "w:bodies() returns the same objects")
  list[1] = nil
  T.equal(#w:bodies(), 2, "w:bodies() is a copy")
  local b = w:bodies()[1]
  w:remove(b)
  T.equal(#w:bodies(), 1, "removed")
  T.equal(w:bodies()[1].shape, "box", "the others keep their order")
  w:step(0.1)
  T.equal(b.position, vec3(0, 7, 0), "a removed body no longer moves with the world")
  b.position = vec3(1, 1, 1)
  T.equal(b.position, vec3(1, 1, 1), "and is writable")
  w:add(b)
  T.equal(w:bodies()[2], b, "and can come back")
  local other = world()
  T.fails(function() other:add(b) end,
    "bad argument #1 to 'world:add' (the body is already in another world (remove it there first))")
  T.fails(function() w:add(b) end, "bad argument #1 to 'world:add' (the body is already in this world)")
  T.fails(function() other:remove(b) end,
    "bad argument #1 to 'world:remove' (must be a body in this world (w:add it first), got a body "
    .. "in another world)")
  -- A body outlives its world: readable, and free to join another.
  local survivor = w:bodies()[1]
  w = nil
  collectgarbage(); collectgarbage()
  T.equal(survivor.shape, "box", "readable after its world was collected")
  other:add(survivor)
  other:step(0.1)
  T.near(survivor.velocity, vec3(0, -2 * 0.981, 0), 1e-15, "joins another world (it fell 0.1 s in each)")
end)

T.case("removing a body removes its springs", function()
  local w = world{gravity = vec3()}
  local a = w:add(body.sphere{mass = 1, radius = 1})
  local b = w:add(body.sphere{mass = 1, radius = 1, position = vec3(2, 0, 0)})
  w:add_spring{a = a, b = b, k = 10}
  w:remove(a)
  w:step(0.1)
  T.equal(b.velocity, vec3(), "the spring went with a")
end)

T.case("a non-finite state is refused, names the body and the time, and undoes that step", function()
  local w = world{gravity = vec3()}
  w:add(body.sphere{mass = 1, radius = 1})
  local b = w:add(body.sphere{mass = 1, radius = 1, velocity = vec3(1e306, 0, 0)})
  w:step(0.1)
  b:apply_force(vec3(1, 0, 0))
  local position, velocity = b.position, b.velocity
  T.fails(function() w:step(1000) end,
    "'world:step': body 2 of 2 would get a non-finite position in the step from t = 0.1 s to "
    .. "t = 1000.1 s; nothing was changed (the world is still at t = 0.1 s)")
  T.equal(b.position, position, "position restored"); T.equal(b.velocity, velocity, "velocity restored")
  T.equal(w.time, 0.1, "time restored")
  -- In a run of steps the ones before the failing step are kept (issue 12 item 19).
  T.fails(function() w:step(1, 2000) end,
    "'world:step': body 2 of 2 would get a non-finite position in the step from t = 179.1 s to "
    .. "t = 180.1 s; that step was undone: 179 of 2000 steps completed (the world is at t = 179.1 s)")
  T.near(w.time, 179.1, 1e-9, "the completed steps are kept")
  T.near(b.velocity, velocity + vec3(1, 0, 0), 1e-15, "the force applied before the call acted in the first step")
  w.gravity = vec3()
  b.velocity = vec3()
  w:step(1)
  T.equal(b.velocity, vec3(), "and was then cleared")
end)

T.case("an error in a callback propagates and undoes the step it happened in", function()
  local w = world{integrator = "rk4"}
  local b = w:add(body.sphere{mass = 1, radius = 1, velocity = vec3(1, 0, 0)})
  local calls = 0
  w:add_force(function() calls = calls + 1; if calls == 3 then error("boom at call 3") end end)
  T.fails(function() w:step(0.1) end, "boom at call 3")
  T.equal(b.position, vec3(), "position"); T.equal(b.velocity, vec3(1, 0, 0), "velocity")
  T.equal(w.time, 0, "time")
  -- rk4 calls it 4 times a step: call 7 is in the second of 3 steps, and the first is kept.
  w = world{integrator = "rk4"}
  b = w:add(body.sphere{mass = 1, radius = 1, velocity = vec3(1, 0, 0)})
  calls = 0
  w:add_force(function() calls = calls + 1; if calls == 7 then error("boom at call 7") end end)
  T.fails(function() w:step(0.1, 3) end, "boom at call 7 (1 of 3 steps completed; the world is at t = 0.1 s)")
  T.near(b.position, vec3(0.1, -0.5 * 9.81 * 0.01, 0), 1e-15, "the first step is kept")
  T.equal(w.time, 0.1, "time")
  w:step(0.1)
  T.near(b.position, vec3(0.2, -0.5 * 9.81 * 0.04, 0), 1e-15, "the world still works")
end)

T.case("callbacks may only apply forces", function()
  local w = world()
  local b = w:add(body.sphere{mass = 1, radius = 1})
  local function in_step(fn, text)
    local v = world()
    local c = v:add(body.sphere{mass = 1, radius = 1})
    v:add_force(function(world_) fn(world_, c) end)
    T.fails(function() v:step(0.1) end, text)
    T.equal(v.time, 0, "unchanged")
  end
  in_step(function(v) v:step(0.1) end,
    "calling 'world:step' on bad self (the world is already stepping: a force callback cannot "
    .. "step its own world)")
  in_step(function(v) v:add(body.sphere{mass = 1, radius = 1}) end,
    "calling 'world:add' on bad self (the world is stepping: cannot add a body until world:step "
    .. "returns; force callbacks may only apply forces)")
  in_step(function(v, c) v:remove(c) end, "calling 'world:remove' on bad self (the world is stepping: cannot remove a body")
  in_step(function(v) v:add_force(print) end, "calling 'world:add_force' on bad self (the world is stepping: cannot add a force")
  in_step(function(v, c) v:add_spring{a = c, anchor = vec3(), k = 1} end,
    "calling 'world:add_spring' on bad self (the world is stepping: cannot add a spring")
  in_step(function(v, c) v:add_drag{body = c, linear = 1} end,
    "calling 'world:add_drag' on bad self (the world is stepping: cannot add drag")
  in_step(function(v) v:add_plane{normal = vec3(0, 0, 1)} end,
    "calling 'world:add_plane' on bad self (the world is stepping: cannot add a plane")
  in_step(function(v) v.gravity = vec3() end,
    "bad field 'gravity' of world (the world is stepping: it cannot be set until world:step "
    .. "returns; force callbacks may only apply forces)")
  in_step(function(_, c) c.position = vec3(1, 0, 0) end,
    "bad field 'position' of body (the world is stepping: it cannot be set until world:step "
    .. "returns; force callbacks may only apply forces)")
  in_step(function(_, c) c.velocity = vec3(1, 0, 0) end,
    "bad field 'velocity' of body (the world is stepping")
  in_step(function(_, c) c:apply_impulse(vec3(1, 0, 0)) end,
    "calling 'body:apply_impulse' on bad self (the world is stepping: cannot apply an impulse")
  T.equal(b.position, vec3(), "untouched")
end)

-- A long w:step is stopped (Ctrl-C, a time limit) by the embedding program's stop check,
-- which the engine polls inside its loops, not by Lua hooks: tests/bindings/stop_check_test.cpp.

T.case("constructor and field errors", function()
  T.fails(function() return world(5) end, "bad argument #1 to 'world' (table expected, got number)")
  T.fails(function() return world{integrator = "rk5"} end,
    "bad argument #1 to 'world' (field 'integrator' must be one of 'euler', 'semi_implicit', 'rk4', got 'rk5')")
  T.fails(function() return world{integrator = 4} end,
    "bad argument #1 to 'world' (field 'integrator' must be one of 'euler', 'semi_implicit', 'rk4', got number)")
  T.fails(function() return world{gyroscopic = "yes"} end,
    "bad argument #1 to 'world' (field 'gyroscopic' must be one of 'conserving', 'implicit', 'explicit', 'off', got 'yes')")
  T.fails(function() return world{substeps = 0} end,
    "bad argument #1 to 'world' (field 'substeps' must be an integer from 1 to 10000, got 0)")
  T.fails(function() return world{substeps = 1.5} end,
    "bad argument #1 to 'world' (field 'substeps' must be an integer from 1 to 10000, got 1.5)")
  T.fails(function() return world{gravity = 9.81} end,
    "bad argument #1 to 'world' (field 'gravity' must be a vec3, got number)")
  T.fails(function() return world{gravty = vec3()} end,
    "bad argument #1 to 'world' (unknown field 'gravty' (fields are: gravity, integrator, gyroscopic, "
    .. "substeps, sleeping, sleep_linear, sleep_angular, sleep_time, solver, iterations, relax_iterations, position_iterations, "
    .. "restitution_threshold, slop, baumgarte, max_correction, contact_hertz, "
    .. "contact_damping_ratio, joint_hertz, joint_damping_ratio, contact_push_speed, "
    .. "speculative_distance))")
  T.fails(function() return world{integrator = "rk4", gyroscopic = "off"} end,
    "bad argument #1 to 'world' (field 'gyroscopic' must not be set on an rk4 world: it is for "
    .. "the Euler integrators (rk4 always integrates the full Euler equations))")
  local w = world()
  T.fails(function() w.time = 3 end,
    "bad field 'time' of world (read-only: it advances with w:step)")
  T.fails(function() w.gravity = 1 end, "bad field 'gravity' of world (vec3 expected, got number)")
  local infinite = body{static = true}.inertia:row(1)  -- a vec3 can hold inf
  T.fails(function() w.gravity = infinite end,
    "bad field 'gravity' of world (must be finite, got (inf, 0, 0))")
  T.fails(function() return world{gravity = infinite} end,
    "bad argument #1 to 'world' (field 'gravity' must be finite, got (inf, 0, 0))")
  T.fails(function() w.integrator = "verlet" end,
    "bad field 'integrator' of world (must be one of 'euler', 'semi_implicit', 'rk4', got "
    .. "'verlet')")
  T.fails(function() w.substeps = -1 end,
    "bad field 'substeps' of world (must be an integer from 1 to 10000, got -1)")
  T.fails(function() w.bodies = {} end,
    "bad field 'bodies' of world (no such field; the settable fields are gravity, integrator, "
    .. "gyroscopic, substeps, sleeping, sleep_linear, sleep_angular, sleep_time, solver, iterations, relax_iterations, position_iterations, "
    .. "restitution_threshold, slop, baumgarte, max_correction, contact_hertz, "
    .. "contact_damping_ratio, joint_hertz, joint_damping_ratio, contact_push_speed, "
    .. "speculative_distance)")
  T.fails(function() return w.dt end,
    "bad field 'dt' of world (no such field; the fields are time, gravity")
  T.equal(w.integrator, "semi_implicit", "unchanged")
end)

T.case("method errors", function()
  local w = world()
  local b = w:add(body.sphere{mass = 1, radius = 1})
  T.fails(function() w:step() end, "bad argument #1 to 'world:step' (number expected, got no value)")
  T.fails(function() w:step(0) end, "bad argument #1 to 'world:step' (dt must be > 0, got 0)")
  T.fails(function() w:step(-0.1) end, "bad argument #1 to 'world:step' (dt must be > 0, got -0.1)")
  T.fails(function() w:step(0/0) end, "bad argument #1 to 'world:step' (dt must be finite, got nan)")
  T.fails(function() w:step(math.huge) end, "bad argument #1 to 'world:step' (dt must be finite, got inf)")
  T.fails(function() w:step(0.1, 0) end,
    "bad argument #2 to 'world:step' (n must be an integer from 1 to 100000000, got 0)")
  T.fails(function() w:step(0.1, 2.5) end,
    "bad argument #2 to 'world:step' (n must be an integer from 1 to 100000000, got 2.5)")
  local other = world()
  other:step(0.1, 2.0)
  T.near(other.time, 0.2, 1e-15, "n = 2.0 is 2 steps, as luaL_checkinteger would take it")
  -- One integer rule everywhere (issue 12 item 20): an integral float is the integer.
  local floats = world{iterations = 2.0, position_iterations = 0.0, substeps = 2.0}
  T.equal(floats.iterations, 2, "iterations = 2.0")
  T.equal(math.type(floats.iterations), "integer", "read back as an integer")
  T.equal(floats.position_iterations, 0, "position_iterations = 0.0")
  floats.iterations = 3.0
  T.equal(floats.iterations, 3, "w.iterations = 3.0")
  T.fails(function() w:step(0.1, 1e12) end,
    "bad argument #2 to 'world:step' (n must be an integer from 1 to 100000000, got 1000000000000)")
  T.fails(function() w:step(0.1, "3") end,
    "bad argument #2 to 'world:step' (n must be an integer from 1 to 100000000, got '3')")
  T.fails(function() w:add(vec3()) end, "bad argument #1 to 'world:add' (body expected, got vec3)")
  T.fails(function() w:add_force("f") end, "bad argument #1 to 'world:add_force' (function expected, got string)")
  T.fails(function() w:add_spring{a = b, k = 1} end,
    "bad argument #1 to 'world:add_spring' (field 'b' (a body) or 'anchor' (a world point) is required)")
  T.fails(function() w:add_spring{anchor = vec3(), k = 1} end,
    "bad argument #1 to 'world:add_spring' (field 'a' is required)")
  T.fails(function() w:add_spring{a = b, anchor = vec3()} end,
    "bad argument #1 to 'world:add_spring' (field 'k' is required)")
  T.fails(function() w:add_spring{a = b, anchor = vec3(), k = -1} end,
    "bad argument #1 to 'world:add_spring' (field 'k' must be >= 0, got -1)")
  T.fails(function() w:add_spring{a = b, anchor = vec3(), k = 1, damping = 0/0} end,
    "bad argument #1 to 'world:add_spring' (field 'damping' must be finite, got nan)")
  T.fails(function() w:add_spring{a = b, b = b, k = 1} end,
    "bad argument #1 to 'world:add_spring' (fields 'a' and 'b' must be different bodies)")
  T.fails(function() w:add_spring{a = b, anchor = vec3(), b_point = vec3(), k = 1} end,
    "bad argument #1 to 'world:add_spring' (field 'b_point' needs field 'b')")
  T.fails(function() w:add_spring{a = body.sphere{mass = 1, radius = 1}, anchor = vec3(), k = 1} end,
    "bad argument #1 to 'world:add_spring' (field 'a' must be a body in this world (w:add it "
    .. "first), got a body in no world)")
  T.fails(function() w:add_spring{a = b, anchor = vec3(), k = 1, stiffness = 2} end,
    "bad argument #1 to 'world:add_spring' (unknown field 'stiffness'")
  T.fails(function() w:add_drag{body = b, linear = -1} end,
    "bad argument #1 to 'world:add_drag' (field 'linear' must be >= 0, got -1)")
  T.fails(function() w:add_drag{linear = 1} end, "bad argument #1 to 'world:add_drag' (field 'body' is required)")
  T.fails(function() w:add_drag{body = 3} end,
    "bad argument #1 to 'world:add_drag' (field 'body' must be a body, got number)")
  T.fails(function() w:angular_momentum(1) end,
    "bad argument #1 to 'world:angular_momentum' (vec3 expected, got number)")
  T.equal(w.time, 0, "nothing stepped")
end)

T.finish()
