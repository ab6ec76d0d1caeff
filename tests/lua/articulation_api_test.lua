-- API.md "Articulated bodies", walked name by name: every name the contract lists exists and
-- behaves as written there. The numbers come from one hinged link whose dynamics are known by
-- hand, not from the engine: a hinge about z at the base origin, mass m = 1 kg with its COM
-- r = 1 m out along the link's x axis, I_c = E (kg·m²), gravity (0, -9.81, 0). About the hinge
-- its inertia is I = I_zz + m r² = 2 kg·m²; at angle θ the COM is at (cos θ, sin θ, 0), gravity's
-- torque is −m g r cos θ, so at rest q̈ = −m g r cos θ / I (RBDL's single-link case: −4.905 at
-- θ = 0); the energy is ½ I θ̇² + m g r sin θ (potential zero at the hinge's height).
local T = dofile("testing.lua")

local g, m, r, I = 9.81, 1.0, 1.0, 2.0

local function hinge(options)
  local art = articulation(options or {gravity = vec3(0, -g, 0)})
  local link = art:add_link{parent = nil, joint = "revolute", axis = vec3(0, 0, 1),
                            origin = vec3(), mass = m, inertia = mat3.identity(),
                            com = vec3(r, 0, 0), name = "arm"}
  return art, link
end

-- The contract's names: art = articulation{...}, the art:... methods and fields, link:...
T.case("every name of the contract exists", function()
  T.equal(type(articulation), "table", "articulation (a callable table)")
  local art, link = hinge()
  for _, name in ipairs{"add_link", "set_state", "step", "forward_dynamics", "inverse_dynamics",
                        "mass_matrix", "bias_forces", "set_torques", "add_control", "jacobian",
                        "virtual_force", "kinetic_energy", "potential_energy", "energy",
                        "record"} do
    T.equal(type(art[name]), "function", "art:" .. name)
  end
  for _, name in ipairs{"position", "orientation", "to_world", "point_velocity"} do
    T.equal(type(link[name]), "function", "link:" .. name)
  end
  T.equal(type(art.q), "table", "art.q")
  T.equal(type(art.qd), "table", "art.qd")
  T.equal(art.time, 0, "art.time")
  -- help() knows each (it prints through the global print, caught here)
  local printed
  local saved_print = print
  print = function(text) printed = text end
  for topic, shown in pairs{articulation = "art:forward_dynamics(", ["articulation:add_link"] =
                            "art:add_link{", ["articulation:step"] = "art:step(dt",
                            ["articulation:virtual_force"] = "art:virtual_force(",
                            link = "link:position()", ["link:to_world"] = "link:to_world(p)"} do
    printed = nil
    local ok = pcall(help, topic)
    T.equal(ok and printed ~= nil and printed:find(shown, 1, true) ~= nil, true,
            "help('" .. topic .. "') shows " .. shown)
  end
  print = saved_print
end)

T.case("articulation{base, gravity, integrator, position, orientation}", function()
  local turn = quat.axis_angle(vec3(0, 0, 1), math.pi / 2)
  local art = articulation{base = "fixed", gravity = vec3(0, -1, 0), integrator = "rk4",
                           position = vec3(1, 2, 3), orientation = turn}
  T.equal(art.base, "fixed", "base")
  T.near(art.gravity, vec3(0, -1, 0), 0, "gravity")
  T.equal(art.integrator, "rk4", "integrator")
  local link = art:add_link{origin = vec3(1, 0, 0)}
  -- the joint sits at position + orientation · origin = (1, 2, 3) + (0, 1, 0)
  T.near(link:position(), vec3(1, 3, 3), 1e-15, "position and orientation place the base")
  local free = articulation{base = "free"}
  free:add_link{joint = "fixed", mass = 2, inertia = mat3.identity()}
  T.equal(free.base, "free", "free base")
  T.equal(#free.q, 7, "a free base adds position (3) and orientation (4) to q")
  T.equal(#free.qd, 6, "and its velocity (3) and angular velocity (3) to qd")
end)

T.case("add_link: parent, joint, axis, origin, mass, inertia, com, name", function()
  local art = articulation{}
  local a = art:add_link{joint = "revolute", axis = vec3(0, 0, 3), name = "a"}
  local b = art:add_link{parent = a, joint = "prismatic", axis = vec3(1, 0, 0),
                         origin = vec3(0, -1, 0)}
  local c = art:add_link{parent = b, joint = "fixed", mass = 2, com = vec3(0, 0.5, 0),
                         inertia = mat3.diag(1, 2, 3)}
  T.equal(#art.q, 2, "each revolute or prismatic joint is one coordinate; fixed adds none")
  T.equal(a.q_index, 1, "coordinates in the order added")
  T.equal(b.q_index, 2, "coordinates in the order added")
  T.equal(c.q_index, nil, "a fixed joint has none")
  T.equal(b.parent, a, "parent is a link")
  T.equal(a.parent, nil, "nil parent is the base")
  T.near(a.axis, vec3(0, 0, 1), 0, "axis normalised")
  T.equal(a.name, "a", "name")
  T.near(c.com, vec3(0, 0.5, 0), 0, "com")
  T.equal(c.mass, 2, "mass")
  -- the prismatic joint slides along x of its parent's frame, from origin (0, -1, 0)
  art:set_state({math.pi / 2, 0.5}, {0, 0})
  T.near(b:position(), vec3(1, 0, 0) + vec3(0, 0.5, 0), 1e-15,
         "origin (0, -1, 0) turned 90° about z is (1, 0, 0); slid 0.5 along x turned is +y")
end)

T.case("art.q, art.qd, set_state, art.time, step(dt [, n])", function()
  local art = hinge()
  art:set_state({0.3}, {-2})
  T.equal(art.q[1], 0.3, "q")
  T.equal(art.qd[1], -2, "qd")
  art:step(0.01)
  T.near(art.time, 0.01, 1e-15, "one step")
  art:step(0.01, 9)
  T.near(art.time, 0.1, 1e-15, "n steps")
  T.equal(art.integrator, "semi_implicit", "the world's default integrator")
end)

T.case("forward_dynamics, inverse_dynamics, mass_matrix, bias_forces", function()
  local art = hinge()
  T.near(art:forward_dynamics()[1], -m * g * r / I, 1e-14, "q̈ = −m g r / I = −4.905 at rest")
  T.near(art:forward_dynamics({1})[1], (1 - m * g * r) / I, 1e-14, "with τ = 1")
  local theta, rate = 0.4, 1.5
  art:set_state({theta}, {rate})
  T.near(art:mass_matrix()[1][1], I, 1e-14, "M = I_zz + m r² (rows)")
  -- a single hinge has no Coriolis term: the bias is gravity's generalised force, negated
  T.near(art:bias_forces()[1], m * g * r * math.cos(theta), 1e-14, "C q̇ + g = m g r cos θ")
  T.near(art:inverse_dynamics({0.7})[1], I * 0.7 + m * g * r * math.cos(theta), 1e-14,
         "τ = M q̈ + C q̇ + g")
end)

T.case("set_torques holds; add_control is called at every RK4 stage", function()
  local art = hinge()
  art:set_torques({m * g * r})
  T.near(art:forward_dynamics()[1], 0, 1e-14, "gravity compensation, held")
  art:step(0.01)
  T.near(art:forward_dynamics()[1], 0, 1e-14, "still held after a step")
  T.equal(art.q[1], 0, "held still")
  art:set_torques({0})
  art.integrator = "rk4"
  local times = {}
  art:add_control(function(a, t)
    times[#times + 1] = t
    return {m * g * r * math.cos(a.q[1])}  -- compensate gravity at the stage state
  end)
  art:set_state({0.5}, {1})
  local t0 = art.time
  art:step(0.1)
  T.equal(#times, 4, "four evaluations in an RK4 step")
  T.near(times[1], t0, 1e-15, "stage 1 at t")
  T.near(times[2], t0 + 0.05, 1e-15, "stage 2 at t + h/2")
  T.near(times[4], t0 + 0.1, 1e-15, "stage 4 at t + h")
  T.near(art.q[1], 0.6, 1e-14, "gravity compensated at every stage: uniform rotation")
  T.near(art.qd[1], 1, 1e-14, "at constant rate")
end)

T.case("jacobian and virtual_force (τ = Jᵀ F)", function()
  local art, link = hinge()
  art:set_state({math.pi / 2}, {0})
  local J = art:jacobian(link, vec3(1, 0, 0))
  T.equal(#J, 6, "6 rows")
  -- the point (1, 0, 0) of the link is at (0, 1, 0); a unit rate moves it by z × (0, 1, 0)
  local want = {-1, 0, 0, 0, 0, 1}
  for row = 1, 6 do T.near(J[row][1], want[row], 1e-15, "J row " .. row) end
  T.near(art:virtual_force(link, vec3(1, 0, 0), vec3(-3, 0, 0))[1], 3, 1e-15,
         "a force along the point's velocity gives τ = |F| r")
end)

T.case("link:position, orientation, to_world, point_velocity; energies", function()
  local art, link = hinge()
  local theta, rate = math.pi / 3, 2
  art:set_state({theta}, {rate})
  T.near(link:position(), vec3(), 0, "the hinge stays at the origin")
  T.near(link:orientation():rotate(vec3(1, 0, 0)), vec3(math.cos(theta), math.sin(theta), 0),
         1e-15, "orientation turns x by θ about z")
  local com = vec3(math.cos(theta), math.sin(theta), 0)
  T.near(link:to_world(vec3(1, 0, 0)), com, 1e-15, "to_world")
  T.near(link:point_velocity(vec3(1, 0, 0)), vec3(0, 0, rate):cross(com), 1e-15,
         "point_velocity = ω × r")
  T.near(art:kinetic_energy(), 0.5 * I * rate ^ 2, 1e-14, "½ I θ̇²")
  T.near(art:potential_energy(), m * g * r * math.sin(theta), 1e-14, "m g r sin θ")
  T.near(art:energy(), 0.5 * I * rate ^ 2 + m * g * r * math.sin(theta), 1e-14, "sum")
end)

T.finish()
