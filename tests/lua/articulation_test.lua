-- articulation and link (lua/articulation*.cpp): the published values through Lua, the state
-- and controls as the API says, and bad input refused in the agreed forms with nothing changed.
local T = dofile("testing.lua")

-- RBDL's double chain (rbdl/rbdl tests/DynamicsTests.cc): two revolute z joints 1 m apart,
-- each body m = 1 with its COM 1 m out along x and I_c = E, gravity (0, -9.81, 0).
local function rbdl_chain(n)
  local art = articulation{gravity = vec3(0, -9.81, 0)}
  local parent
  for k = 1, n do
    parent = art:add_link{parent = parent, origin = k == 1 and vec3() or vec3(1, 0, 0),
                          mass = 1, com = vec3(1, 0, 0), inertia = mat3.diag(1, 1, 1)}
  end
  return art
end

-- Every observable of an articulation, to check that a failed call changed nothing.
local function snapshot(art)
  local parts = {tostring(art), table.concat(art.q, ","), table.concat(art.qd, ","),
                 table.concat(art.torques, ","), tostring(art.gravity), art.integrator}
  return table.concat(parts, "|")
end

T.case("RBDL's published forward dynamics", function()
  T.near(rbdl_chain(1):forward_dynamics()[1], -4.905, 1e-14, "single chain")
  local qdd = rbdl_chain(2):forward_dynamics({0, 0})
  T.near(qdd[1], -5.886, 1e-13, "double chain, joint 1")
  T.near(qdd[2], 3.924, 1e-13, "double chain, joint 2")
end)

T.case("links, names and fields", function()
  local art = rbdl_chain(2)
  local l1, l2 = art.links[1], art.links[2]
  T.equal(#art.links, 2, "#links")
  T.equal(l2.parent, l1, "parent is the same object")
  T.equal(art:link(2), l2, "art:link(n)")
  local named = art:add_link{parent = 1, name = "tip", joint = "prismatic", axis = vec3(0, 2, 0)}
  T.equal(art:link("tip"), named, "art:link(name)")
  T.equal(named.index, 3, "index")
  T.equal(named.joint, "prismatic", "joint")
  T.near(named.axis, vec3(0, 1, 0), 0, "axis normalised")
  T.equal(named.q_index, 3, "q_index")
  local fixed = art:add_link{parent = named, joint = "fixed", mass = 2}
  T.equal(fixed.q, nil, "a fixed joint has no coordinate")
  T.equal(#art.q, 3, "a fixed joint adds nothing to q")
  T.equal(tostring(named), "link(3 tip, prismatic)", "tostring")
end)

T.case("state, step and energy", function()
  local art = rbdl_chain(2)
  art:set_state({0.3, -0.2}, {0.1, 0.4})
  T.equal(art.q[1], 0.3, "q")
  T.equal(art.qd[2], 0.4, "qd")
  art.integrator = "rk4"
  local e0 = art:energy()
  art:step(1e-3, 1000)
  T.near(art.time, 1, 1e-12, "time")
  T.near(art:energy(), e0, 1e-9 * math.abs(e0), "energy kept under rk4")
  -- The kinetic energy is ½ qdᵀ M qd.
  local M, qd = art:mass_matrix(), art.qd
  local quadratic = 0
  for i = 1, 2 do for j = 1, 2 do quadratic = quadratic + qd[i] * M[i][j] * qd[j] end end
  T.near(art:kinetic_energy(), 0.5 * quadratic, 1e-12, "T = ½ qdᵀ M qd")
end)

T.case("gravity compensation holds a pose", function()
  local art = rbdl_chain(3)
  art:set_state({0.5, -1.0, 0.7}, {0, 0, 0})
  local g = art:inverse_dynamics({0, 0, 0})
  for i, x in ipairs(art:forward_dynamics(g)) do T.near(x, 0, 1e-12, "qdd " .. i) end
  art:set_torques(g)
  art:step(0.01, 100)
  T.near(art.q[2], -1.0, 1e-11, "still held after 1 s")
end)

T.case("the Jacobian and virtual forces of a link point", function()
  local art = rbdl_chain(2)
  art:set_state({0.4, 0.3}, {0.2, -0.5})
  local tip = art.links[2]
  local J = art:jacobian(tip, vec3(1, 0, 0))
  local v = tip:point_velocity(vec3(1, 0, 0))
  local qd = art.qd
  T.near(vec3(J[1][1] * qd[1] + J[1][2] * qd[2], J[2][1] * qd[1] + J[2][2] * qd[2],
              J[3][1] * qd[1] + J[3][2] * qd[2]), v, 1e-14, "J qd = point velocity")
  local tau = art:virtual_force(tip, vec3(1, 0, 0), vec3(0, 2, 0))
  T.near(tau[1], J[2][1] * 2, 1e-14, "τ = Jᵀ F, joint 1")
  T.near(tau[2], J[2][2] * 2, 1e-14, "τ = Jᵀ F, joint 2")
  -- The planar closed form: the point (1, 0) of link 2 is at L(cos θ₁ + cos θ₁₂, sin ...).
  T.near(tip:to_world(vec3(1, 0, 0)), vec3(math.cos(0.4) + math.cos(0.7),
         math.sin(0.4) + math.sin(0.7), 0), 1e-15, "to_world")
end)

T.case("controls run at every RK4 stage, on the stage state", function()
  local art = rbdl_chain(1)
  art.integrator = "rk4"
  art:set_state({0.5}, {1.0})
  local times, angles = {}, {}
  art:add_control(function(a, t)
    times[#times + 1], angles[#angles + 1] = t, a.q[1]
    T.equal(a.time, t, "art.time is the stage time")
    return {0}
  end)
  art:step(0.1)
  T.equal(#times, 4, "four evaluations")
  T.near(times[2], 0.05, 1e-15, "stage 2 at t + h/2")
  T.near(times[4], 0.1, 1e-15, "stage 4 at t + h")
  T.near(angles[2], 0.5 + 0.05 * 1.0, 1e-15, "stage 2 at q + h/2 k1")
  art:clear_controls()
  art:add_control(function() return nil end)  -- nil adds nothing
  art:step(0.1)
  T.equal(#times, 4, "cleared")
end)

T.case("queries from inside a control do not disturb the step", function()
  local function run(nested)
    local art = rbdl_chain(2)
    art.integrator = "rk4"
    art:set_state({0.4, -0.3}, {0.2, 0.1})
    art:add_control(function(a)
      if nested then
        a:forward_dynamics({1, 2})
        a:aba_trace({0, 0})
        a:mass_matrix()
        a:jacobian(2)
        a:inverse_dynamics({1, 1})
      end
      return {0.1, -0.2}
    end)
    art:step(0.01, 50)
    return art.q[1], art.q[2], art.qd[1], art.qd[2]
  end
  local a = {run(false)}
  local b = {run(true)}
  for i = 1, 4 do T.equal(b[i], a[i], "entry " .. i) end
end)

T.case("a PD controller: the document's τ = kp(θd − θ) + kv(θ̇d − θ̇)", function()
  local art = articulation{gravity = vec3()}
  art:add_link{inertia = mat3.diag(1, 1, 2)}
  art.integrator = "rk4"
  local kp, kv = 20, 3
  art:add_control(function(a) return {kp * (1 - a.q[1]) + kv * (0 - a.qd[1])} end)
  art:step(1e-3, 2000)
  local zeta = kv / 4
  local omega = math.sqrt(kp / 2 - zeta * zeta)
  local exact = 1 - math.exp(-zeta * 2) * (math.cos(omega * 2) + zeta / omega * math.sin(omega * 2))
  T.near(art.q[1], exact, 1e-11, "θ(2 s)")
end)

T.case("free base", function()
  local art = articulation{base = "free", gravity = vec3(), position = vec3(1, 2, 3)}
  art:add_link{joint = "fixed", mass = 2, inertia = mat3.diag(0.1, 0.2, 0.3)}
  art:add_link{parent = 1, origin = vec3(0.5, 0, 0), com = vec3(0.2, 0, 0)}
  T.equal(#art.q, 8, "7 base coordinates + 1")
  T.equal(#art.qd, 7, "6 base velocities + 1")
  T.near(vec3(art.q[1], art.q[2], art.q[3]), vec3(1, 2, 3), 0, "position first")
  art:set_state({1, 2, 3, 1, 0, 0, 0, 0.3}, {0.1, 0, 0, 0, 0.2, 0.5, -1})
  art.integrator = "rk4"
  local p0, l0 = art:linear_momentum(), art:angular_momentum()
  art:step(1e-3, 500)
  T.near(art:linear_momentum(), p0, 1e-12, "P kept")
  T.near(art:angular_momentum(), l0, 1e-11, "L kept")
end)

-- ---- bad input: the agreed forms, and nothing changed ---------------------------------------

T.case("bad input is refused and changes nothing", function()
  local art, other = rbdl_chain(2), rbdl_chain(1)
  art:set_state({0.1, 0.2}, {0.3, 0.4})
  local before = snapshot(art)
  local cases = {
    {function() articulation{base = "floating"} end,
     "bad argument #1 to 'articulation' (field 'base' must be one of 'fixed', 'free', got 'floating')"},
    {function() articulation{gravty = vec3()} end,
     "bad argument #1 to 'articulation' (unknown field 'gravty'"},
    {function() articulation{base = "free", orientation = quat(2, 0, 0, 0)} end,
     "bad argument #1 to 'articulation' (orientation must be a unit quaternion, got length 2)"},
    {function() art:add_link{joint = "hinge"} end,
     "bad argument #1 to 'articulation:add_link' (field 'joint' must be one of 'revolute', 'prismatic', 'fixed', got 'hinge')"},
    {function() art:add_link{axis = vec3(0, 0, 0)} end,
     "bad argument #1 to 'articulation:add_link' (field 'axis' must be non-zero for a revolute joint, got (0, 0, 0))"},
    {function() art:add_link{parent = other.links[1]} end,
     "bad argument #1 to 'articulation:add_link' (field 'parent' must be a link of this articulation, got a link of another one)"},
    {function() art:add_link{parent = 7} end,
     "bad argument #1 to 'articulation:add_link' (field 'parent' must be a link number from 1 to 2, got 7)"},
    {function() art:add_link{parent = "nobody"} end,
     "bad argument #1 to 'articulation:add_link' (field 'parent' no link is called 'nobody')"},
    {function() art:add_link{mass = -1} end,
     "bad argument #1 to 'articulation:add_link' (field 'mass' must be"},
    {function() art:add_link{inertia = mat3.diag(1, 1, 3)} end,
     "bad argument #1 to 'articulation:add_link' (field 'inertia' is not a valid tensor"},
    {function() art:add_link{inertia = 5} end,
     "bad argument #1 to 'articulation:add_link' (field 'inertia' must be a mat3, got number)"},
    {function() art:add_link{mas = 1} end,
     "bad argument #1 to 'articulation:add_link' (unknown field 'mas'"},
    {function() art:set_state({1, 2, 3}, {0, 0}) end,
     "bad argument #1 to 'articulation:set_state' (q must have 2 entries (one per moving joint), got 3)"},
    {function() art:set_state({1, 2}, {0}) end,
     "bad argument #2 to 'articulation:set_state' (qd must have 2 entries"},
    {function() art:set_state({1, 0 / 0}, {0, 0}) end,
     "bad argument #1 to 'articulation:set_state' (q[2] must be a finite number, got nan)"},
    {function() art:set_state({1, "2"}, {0, 0}) end,
     "bad argument #1 to 'articulation:set_state' (q[2] must be a finite number, got string)"},
    {function() art:set_state({1, 2, x = 3}, {0, 0}) end,
     "bad argument #1 to 'articulation:set_state' (q: unexpected key 'x'"},
    {function() art:set_torques({1}) end,
     "bad argument #1 to 'articulation:set_torques' (tau must have 2 entries"},
    {function() art:forward_dynamics({1, 2, 3}) end,
     "bad argument #1 to 'articulation:forward_dynamics' (tau must have 2 entries"},
    {function() art:inverse_dynamics(5) end,
     "bad argument #1 to 'articulation:inverse_dynamics' (list of numbers expected, got number)"},
    {function() art:jacobian(3) end,
     "bad argument #1 to 'articulation:jacobian' (link must be a link number from 1 to 2, got 3)"},
    {function() art:jacobian(other.links[1]) end,
     "bad argument #1 to 'articulation:jacobian' (link must be a link of this articulation"},
    {function() art:virtual_force(1, vec3(), 5) end,
     "bad argument #3 to 'articulation:virtual_force' (vec3 expected, got number)"},
    {function() art:step(0) end, "bad argument #1 to 'articulation:step' (dt must be > 0"},
    {function() art:step(0.1, 1.5) end,
     "bad argument #2 to 'articulation:step' (n must be an integer from 1 to"},
    {function() art:step(0.1, 1, 2) end,
     "bad argument #3 to 'articulation:step' (no more than"},
    {function() art.q = {1, 2} end, "bad field 'q' of articulation (read-only"},
    {function() art.time = 2 end, "bad field 'time' of articulation (read-only"},
    {function() art.gravity = 5 end, "bad field 'gravity' of articulation (vec3 expected, got number)"},
    {function() art.integrator = "verlet" end,
     "bad field 'integrator' of articulation (must be one of 'euler', 'semi_implicit', 'rk4', got 'verlet')"},
    {function() art.speed = 1 end, "bad field 'speed' of articulation (no such field"},
    {function() art.links[1].mass = 3 end, "bad field 'mass' of link (read-only"},
    {function() articulation.step(5, 0.1) end,
     "bad argument #1 to 'articulation:step' (articulation expected, got number)"},
  }
  for i, c in ipairs(cases) do
    local ok, message = pcall(c[1])
    T.equal(ok, false, "case " .. i .. " raises")
    message = tostring(message):gsub("^[^:]*:%d+: ", "")
    if message:sub(1, #c[2]) ~= c[2] then
      error(string.format("case %d:\n  got  %s\n  want %s", i, message, c[2]))
    end
    T.equal(snapshot(art), before, "case " .. i .. " changed nothing")
  end
  T.equal(#art.links, 2, "no link was added")
end)

T.case("a failing or misbehaving control leaves the state as it was", function()
  local art = rbdl_chain(2)
  art.integrator = "rk4"
  art:set_state({0.1, 0.2}, {0.3, 0.4})
  local before = snapshot(art)
  local calls = 0
  art:add_control(function()
    calls = calls + 1
    if calls == 3 then error("stage 3 failed") end
  end)
  T.fails(function() art:step(0.01) end, "stage 3 failed")
  T.equal(snapshot(art), before, "after a control error")
  art:clear_controls()
  art:add_control(function() return {1, 0 / 0} end)
  T.fails(function() art:step(0.01) end,
          "'articulation:step': control 1 returned a tau whose entry 2 is not a finite number (nan)")
  art:clear_controls()
  art:add_control(function(a) a:set_state({0, 0}, {0, 0}) end)
  T.fails(function() art:step(0.01) end,
          "calling 'articulation:set_state' on bad self (the articulation is stepping: cannot set the state")
  art:clear_controls()
  art:add_control(function(a) a:step(0.1) end)
  T.fails(function() art:step(0.01) end,
          "calling 'articulation:step' on bad self (the articulation is already stepping")
  art:clear_controls()
  art:add_control(function(a) a:forward_dynamics() end)
  T.fails(function() art:step(0.01) end, "a control cannot ask for the controls' torques")
  T.equal(snapshot(art), before, "after every refused control")
  art:clear_controls()
  art:set_torques({1e300, 0})
  T.fails(function() art:step(1) end, "would leave a state that is not finite")
  T.equal(art.time, 0, "time not advanced")
end)

T.case("links keep their articulation alive; a finalised one is refused", function()
  local link = rbdl_chain(2).links[2]
  collectgarbage()
  collectgarbage()
  T.equal(link.articulation:link(2), link, "still there")
  local art = link.articulation
  debug.getmetatable(art).__gc(art)
  T.fails(function() art:step(0.1) end, "the articulation was finalised")
  T.fails(function() return link.q end, "the articulation was finalised")
end)

T.finish()
