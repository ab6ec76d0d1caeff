 -- Articulations under hostile use: option tables that add links (q, q̇ and the torques grow)
-- while add_link, set_state, set_torques and step read them; controls that return wrong
-- torques, raise, or try to change or step the articulation calling them; a free base with a
-- non-unit quaternion; recorders and queries on links of another articulation.
local A = articulation{gravity = vec3(0, -9.81, 0), integrator = "rk4"}
local l1 = A:add_link{joint = "revolute", axis = vec3(0, 0, 1), mass = 1, com = vec3(0, -1, 0)}
local function grow() pcall(function() A:add_link{parent = A.links[#A.links], mass = 1} end) end
local sneaky = setmetatable({}, {__index = function(_, k)
  grow()
  return ({joint = "prismatic", axis = vec3(0, 1, 0), mass = 1, parent = l1})[k]
end})
pcall(A.add_link, A, sneaky)
pcall(A.set_state, A, setmetatable({}, {__index = function() grow() return 0 end, __len = function() return #A.q end}), A.qd)
pcall(A.set_torques, A, setmetatable({}, {__len = function() grow() return #A.qd end}))
pcall(A.add_control, A, function(a, t) grow() return a.qd end)
pcall(A.add_control, A, function(a, t) return {1e308, 0/0, math.huge} end)
pcall(A.add_control, A, function(a, t) a:set_state(a.q, a.qd) end)
pcall(A.add_control, A, function(a, t) return a:step(0.01) end)
pcall(A.add_control, A, function(a, t) error("control") end)
pcall(A.step, A, 0.01, 3)
pcall(A.clear_controls, A)
pcall(A.step, A, 1e308)
pcall(A.step, A, 0.01, math.maxinteger)
local F = articulation{base = "free"}
pcall(F.add_link, F, {parent = l1, mass = 1})
pcall(F.add_link, F, {joint = "fixed", mass = 1, inertia = mat3.diag(1, 2, 3)})
pcall(F.set_state, F, {0, 0, 0, 2, 0, 0, 0}, {0, 0, 0, 1e308, 0, 0})
pcall(F.step, F, 0.01)
for _, l in ipairs(A.links) do
  pcall(l.position, l); pcall(function() return l:to_world(vec3(0/0, 0, 0)) end); pcall(l.point_velocity, l, {})
  pcall(A.jacobian, A, l, vec3()); pcall(F.jacobian, F, l, vec3())
  pcall(A.virtual_force, A, l, vec3(), vec3(1e308, 1e308, 1e308))
end
pcall(A.forward_dynamics, A, {}); pcall(A.inverse_dynamics, A, A.qd)
pcall(A.mass_matrix, A); pcall(A.bias_forces, A)
local rec = A:record{every = 1}
pcall(A.step, A, 0.01, 5)
pcall(function() return #rec end)
pcall(A.energy, A)
