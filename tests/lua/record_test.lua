-- w:record: every series equals what the world's and bodies' own accessors give at the same
-- steps; every, bodies, stop and CSV; what stops a recording; the agreed errors.
local T = dofile("testing.lua")

local function scene()
  local w = world{}
  w:add_plane{}
  local box = w:add(body.box{mass = 2, size = vec3(0.5, 0.15, 1), position = vec3(0, 2, 0),
                             angular_velocity = vec3(1, 0.3, 2), velocity = vec3(1, 0, 0)})
  local ball = w:add(body.sphere{mass = 1, radius = 0.2, position = vec3(2, 0.5, 0)})
  return w, box, ball
end

-- What the accessors say now, for the comparison.
local function observe(w, b)
  local q = b.orientation
  return {
    t = w.time, kinetic_energy = w:kinetic_energy(), potential_energy = w:potential_energy(),
    energy = w:energy(), linear_momentum = w:linear_momentum(),
    angular_momentum = w:angular_momentum(),
    position = b.position, orientation = q, velocity = b.velocity,
    angular_velocity = b.angular_velocity,
    velocity_body = q:conj():rotate(b.velocity),
    angular_velocity_body = q:conj():rotate(b.angular_velocity),
    body_kinetic_energy = b:kinetic_energy(), body_angular_momentum = b:angular_momentum(),
    angular_momentum_body = q:conj():rotate(b:angular_momentum()),
  }
end

T.case("series equal the accessors at the same steps", function()
  local w, box = scene()
  local rec = w:record{}
  local seen = {observe(w, box)}
  for _ = 1, 40 do
    w:step(1 / 60)
    seen[#seen + 1] = observe(w, box)
  end
  T.equal(#rec, 41, "a sample at the start and one per step")
  T.equal(rec.count, 41, "count")
  local world_names = {"kinetic_energy", "potential_energy", "energy", "linear_momentum",
                       "angular_momentum"}
  local t = rec.t
  for i, s in ipairs(seen) do
    T.equal(t[i], s.t, "t " .. i)
    for _, name in ipairs(world_names) do
      T.near(rec:series(name)[i], s[name], 0, name .. " " .. i)
    end
    for _, name in ipairs({"position", "orientation", "velocity", "angular_velocity"}) do
      T.near(rec:series(name, box)[i], s[name], 0, name .. " " .. i)
    end
    for _, name in ipairs({"velocity_body", "angular_velocity_body", "angular_momentum_body"}) do
      T.near(rec:series(name, box)[i], s[name], 1e-13, name .. " " .. i)  -- q:conj():rotate vs the stored orientation's Rᵀ
    end
    T.near(rec:series("kinetic_energy", box)[i], s.body_kinetic_energy, 1e-13, "body KE " .. i)
    T.near(rec:series("angular_momentum", 1)[i], s.body_angular_momentum, 1e-13, "body L " .. i)
  end
end)

T.case("every and bodies", function()
  local w, box, ball = scene()
  local rec = w:record{every = 3, bodies = {ball}}
  local positions = {ball.position}
  for k = 1, 10 do
    w:step(1 / 60)
    if k % 3 == 0 then positions[#positions + 1] = ball.position end
  end
  T.equal(#rec, 4, "steps 0, 3, 6, 9")
  local got = rec:series("position")  -- one body recorded: it may be left out
  for i = 1, 4 do T.near(got[i], positions[i], 0, "position " .. i) end
  T.near(rec.t[4], 9 / 60, 1e-15, "time of the last sample")
  T.equal(rec.bodies[1], ball, "rec.bodies")
  T.equal(rec.every, 3, "rec.every")
  T.fails(function() rec:series("position", box) end, "not one this recorder records", "other body")
end)

T.case("stop, and a recorded body that leaves", function()
  local w, box, ball = scene()
  local rec = w:record{}
  w:step(1 / 60, 5)
  rec:stop()
  w:step(1 / 60, 5)
  T.equal(#rec, 6, "nothing after stop")
  T.equal(rec.recording, false, "recording")
  T.equal(rec.stop_reason, "stopped by rec:stop()", "reason")
  local rec2 = w:record{}
  w:remove(ball)
  w:step(1 / 60, 2)
  T.equal(#rec2, 1, "stopped when body 2 left")
  assert(rec2.stop_reason:find("recorded body 2 left the world", 1, true), rec2.stop_reason)
  assert(tostring(rec2):find("recorder(2 bodies, 1 samples", 1, true), tostring(rec2))
end)

T.case("csv: a header and one row per sample, numbers that read back", function()
  local w, box = scene()
  local rec = w:record{bodies = {box}}
  w:step(1 / 60, 3)
  local path = os.tmpname()
  rec:csv(path)
  local rows = {}
  for line in io.lines(path) do rows[#rows + 1] = line end
  os.remove(path)
  T.equal(#rows, 5, "header + 4 samples")
  local header = {}
  for name in rows[1]:gmatch("[^,]+") do header[#header + 1] = name end
  T.equal(header[1], "t", "first column")
  local column = {}
  for i, name in ipairs(header) do column[name] = i end
  for _, name in ipairs({"energy", "angular_momentum.z", "body1.position.y", "body1.orientation.w",
                         "body1.angular_velocity_body.x", "body1.angular_momentum_body.z"}) do
    assert(column[name], "column " .. name)
  end
  local last = {}
  for x in rows[5]:gmatch("[^,]+") do last[#last + 1] = tonumber(x) end
  T.equal(last[column["body1.position.y"]], box.position.y, "position read back exactly")
  T.equal(last[column.energy], w:energy(), "energy read back exactly")
  T.fails(function() rec:csv("/dev/full") end,
    "bad argument #1 to 'recorder:csv' (cannot write '/dev/full': No space left on device)")
end)

T.case("a recorder outlives its world, and a finalised one says so", function()
  local w = world{}
  w:add(body.sphere{mass = 1, radius = 1})
  local rec = w:record{}
  w:step(0.01, 3)
  debug.getmetatable(w).__gc(w)  -- the world goes first: the samples stay readable
  T.equal(#rec, 4, "samples")
  T.equal(rec.recording, false, "no world to record")
  T.near(rec:series("position")[4], vec3(0, -0.005886, 0), 1e-12, "position after 3 steps")
  rec:stop()
  local w2 = world{}
  local rec2 = w2:record{}
  debug.getmetatable(rec2).__gc(rec2)
  T.fails(function() return #rec2 end, "the recorder was finalised")
  w2:step(0.01, 5)  -- the world still tells it of steps: nothing breaks
  T.fails(function() w2:render{show = "trail"} end, "'trail' needs a recorder")
  for _ = 1, 3 do  -- worlds and recorders collected together, in any order
    local w3 = world{}
    w3:add(body.sphere{mass = 1, radius = 1})
    w3:record{}
    w3:step(0.01, 2)
  end
  collectgarbage()
  collectgarbage()
end)

T.case("art:record: q, qd, energies and link poses equal the accessors at the same steps", function()
  local art = articulation{}
  local upper = art:add_link{axis = vec3(0, 0, 1), mass = 1, com = vec3(1, 0, 0), name = "upper"}
  local lower = art:add_link{parent = upper, axis = vec3(0, 0, 1), origin = vec3(2, 0, 0), mass = 2,
                             com = vec3(0.5, 0, 0), name = "lower"}
  art:set_state({0.3, -0.2}, {0, 1})
  local rec = art:record{every = 2}
  local seen = {}
  local function observe()
    seen[#seen + 1] = {t = art.time, q = art.q, qd = art.qd, ke = art:kinetic_energy(),
      pe = art:potential_energy(), e = art:energy(), p = lower:position(), r = lower:orientation(),
      com = lower:to_world(vec3(0.5, 0, 0)), w = upper:angular_velocity()}
  end
  observe()
  for k = 1, 20 do
    art:step(1 / 120)
    if k % 2 == 0 then observe() end
  end
  T.equal(#rec, 11, "samples at steps 0, 2, ..., 20")
  for i, s in ipairs(seen) do
    T.equal(rec.t[i], s.t, "t " .. i)
    T.equal(rec:series("q", 1)[i], s.q[1], "q1 " .. i)
    T.equal(rec:series("qd", 2)[i], s.qd[2], "qd2 " .. i)
    T.near(rec:series("kinetic_energy")[i], s.ke, 0, "KE " .. i)
    T.near(rec:series("potential_energy")[i], s.pe, 0, "PE " .. i)
    T.near(rec:series("energy")[i], s.e, 1e-15 * math.max(1, math.abs(s.e)), "E " .. i)
    T.near(rec:series("position", lower)[i], s.p, 0, "joint position " .. i)
    T.near(rec:series("orientation", "lower")[i], s.r, 1e-15, "orientation " .. i)
    T.near(rec:series("com", 2)[i], s.com, 1e-15, "COM " .. i)
    T.near(rec:series("angular_velocity", upper)[i], s.w, 0, "omega " .. i)
  end
  T.equal(rec.bodies[2], lower, "rec.bodies lists the links")
  T.fails(function() rec:series("q") end, "a coordinate is needed for 'q' (2 coordinates")
  T.fails(function() rec:series("q", 3) end, "the index must be from 1 to 2, got 3")
  T.fails(function() rec:series("position", "elbow") end, "elbow")
  T.fails(function() rec:series("linear_momentum") end, "no articulation series 'linear_momentum'")
  local path = os.tmpname()
  rec:csv(path)
  local header = io.lines(path)()
  os.remove(path)
  T.equal(header, "t,kinetic_energy,potential_energy,energy,q1,q2,qd1,qd2,link1.position.x," ..
    "link1.position.y,link1.position.z,link1.orientation.w,link1.orientation.x,link1.orientation.y," ..
    "link1.orientation.z,link1.com.x,link1.com.y,link1.com.z,link1.angular_velocity.x," ..
    "link1.angular_velocity.y,link1.angular_velocity.z,link2.position.x,link2.position.y," ..
    "link2.position.z,link2.orientation.w,link2.orientation.x,link2.orientation.y," ..
    "link2.orientation.z,link2.com.x,link2.com.y,link2.com.z,link2.angular_velocity.x," ..
    "link2.angular_velocity.y,link2.angular_velocity.z", "columns")
  rec:stop()
  art:step(1 / 120, 4)
  T.equal(#rec, 11, "nothing after stop")
  local rec2 = art:record{}
  rec2 = nil
  collectgarbage()
  art:step(1 / 120, 2)  -- a collected recorder is detached; nothing breaks
end)

T.case("errors", function()
  local w, box = scene()
  local other = world{}
  local stranger = other:add(body.sphere{mass = 1, radius = 1})
  T.fails(function() w:record{every = 0} end,
    "bad argument #1 to 'world:record' (field 'every' must be an integer from 1 to")
  T.fails(function() w:record{bodies = {stranger}} end,
    "bad argument #1 to 'world:record' (field 'bodies[1]' must be a body in this world")
  T.fails(function() w:record{evry = 2} end, "unknown field 'evry'")
  local rec = w:record{}
  T.fails(function() rec:series("positon", box) end, "no body series 'positon'")
  T.fails(function() rec:series("position") end, "a body is needed for 'position' (2 bodies")
  T.fails(function() rec:series("energy", box) end, "no body series 'energy'")
  T.fails(function() rec:series("t\0x") end, "NUL")
  T.fails(function() rec:series("position", 3) end, "body number must be from 1 to 2")
  T.fails(function() rec.count = 5 end, "bad field 'count' of recorder")
end)

T.finish()
