-- body from Lua: constructors against the closed-form tensors of a sphere and a box, derived
-- quantities against hand-computed values, static bodies, and the exact text of the errors.
local T = dofile("testing.lua")

T.case("sphere and box carry their closed-form tensors and shapes", function()
  local s = body.sphere{mass = 2, radius = 0.5, position = vec3(0, 1, 0)}
  T.near(s.inertia, mat3.diag(0.2, 0.2, 0.2), 1e-15, "(2/5) m r²")
  T.equal(s.mass, 2, "mass"); T.equal(s.inv_mass, 0.5, "inv_mass")
  T.equal(s.shape, "sphere", "shape"); T.equal(s.radius, 0.5, "radius"); T.equal(s.size, nil, "size")
  T.equal(s.static, false, "static")
  T.equal(tostring(s), "body(sphere, m=2, pos=(0, 1, 0))", "tostring")
  local b = body.box{mass = 12, size = vec3(1, 2, 3)}
  T.near(b.inertia, mat3.diag(13, 10, 5), 1e-14, "m(h²+d²)/12, m(w²+d²)/12, m(w²+h²)/12")
  T.near(b.inv_inertia, mat3.diag(1 / 13, 1 / 10, 1 / 5), 1e-15, "inv_inertia")
  T.equal(b.shape, "box", "shape"); T.equal(b.size, vec3(1, 2, 3), "size"); T.equal(b.radius, nil, "radius")
  local g = body{mass = 3, inertia = mat3.diag(1, 2, 2.5)}
  T.equal(g.shape, "none", "no shape")
  T.equal(tostring(g), "body(m=3, pos=(0, 0, 0))", "tostring without shape")
end)

T.case("state fields: defaults, writes, normalisation", function()
  local b = body{mass = 1, inertia = mat3.identity()}
  T.equal(b.position, vec3(), "position"); T.equal(b.velocity, vec3(), "velocity")
  T.equal(b.orientation, quat.identity(), "orientation")
  b.position = vec3(1, 2, 3); b.velocity = vec3(0, 1, 0); b.angular_velocity = vec3(0, 0, 2)
  T.equal(b.position, vec3(1, 2, 3), "position written")
  -- Fields are values (API.md "Conventions"): changing a component of one is an error that
  -- says how to build the new value, never a silent change of a copy (issue 12 item 21).
  T.fails(function() b.position.x = 5 end,
    "bad field 'x' of vec3 (read-only: vec3 values are immutable, like numbers; build a new " ..
    "one, e.g. v = vec3(5, v.y, v.z), or for a body b.position = vec3(5, b.position.y, " ..
    "b.position.z))", "b.position.x = 5")
  T.fails(function() b.orientation.w = 1 end,
    "bad field 'w' of quat (read-only: quat values are immutable", "b.orientation.w = 1")
  T.equal(b.position, vec3(1, 2, 3), "the body is unchanged")
  b.position = vec3(5, b.position.y, b.position.z)  -- what the message says to write
  T.equal(b.position, vec3(5, 2, 3), "the suggested form works")
  b.orientation = quat(2, 0, 0, 0)
  T.equal(b.orientation, quat.identity(), "orientation normalised on write")
  local c = body{mass = 1, inertia = mat3.identity(), orientation = quat(0, 0, 0, 3)}
  T.equal(c.orientation, quat(0, 0, 0, 1), "orientation normalised in the constructor")
  -- Huge and tiny quaternions are rotations too: (a, a, 0, 0) is a quarter turn about x.
  local r = math.sqrt(0.5)
  for _, a in ipairs{1e200, 1e-320} do
    local d = body{mass = 1, inertia = mat3.identity(), orientation = quat(a, a, 0, 0)}
    T.near(d.orientation, quat(r, r, 0, 0), 1e-15, "constructor, scale " .. a)
    d.orientation = quat(0, 0, a, a)
    T.near(d.orientation, quat(0, 0, r, r), 1e-15, "setter, scale " .. a)
  end
end)

T.case("derived quantities against hand-computed values", function()
  local b = body{mass = 1, inertia = mat3.diag(1, 2, 3), position = vec3(1, 2, 3),
    orientation = quat.axis_angle(vec3(0, 0, 1), math.pi / 2)}
  T.near(b:world_inertia(), mat3.diag(2, 1, 3), 1e-14, "a quarter turn about z swaps Ixx, Iyy")
  T.near(b:inv_world_inertia(), mat3.diag(0.5, 1, 1 / 3), 1e-14, "R I⁻¹ Rᵀ")
  T.near(b:to_world(vec3(1, 0, 0)), vec3(1, 3, 3), 1e-15, "to_world")
  T.near(b:to_local(vec3(1, 3, 3)), vec3(1, 0, 0), 1e-15, "to_local")
  b.velocity = vec3(1, 0, 0); b.angular_velocity = vec3(0, 0, 2)
  T.near(b:point_velocity(vec3(2, 2, 3)), vec3(1, 2, 0), 1e-15, "v + ω × r")
  local s = body.sphere{mass = 2, radius = 1, velocity = vec3(3, 0, 0), angular_velocity = vec3(0, 0, 1)}
  T.near(s:linear_momentum(), vec3(6, 0, 0), 1e-15, "m v")
  T.near(s:angular_momentum(), vec3(0, 0, 0.8), 1e-15, "I ω")
  T.near(s:kinetic_energy(), 0.5 * 2 * 9 + 0.5 * 0.8, 1e-14, "½ m v² + ½ I ω²")
end)

T.case("impulses change velocities now", function()
  local s = body.sphere{mass = 2, radius = 1}  -- I = 0.8
  s:apply_impulse(vec3(0, 4, 0), vec3(1, 0, 0))  -- r × j = (0, 0, 4)
  T.near(s.velocity, vec3(0, 2, 0), 1e-15, "Δv = j/m")
  T.near(s.angular_velocity, vec3(0, 0, 5), 1e-14, "Δω = I⁻¹ (r × j)")
  s:apply_angular_impulse(vec3(0.8, 0, 0))
  T.near(s.angular_velocity, vec3(1, 0, 5), 1e-14, "Δω = I⁻¹ h")
  s:apply_impulse(vec3(2, 0, 0))
  T.near(s.velocity, vec3(1, 2, 0), 1e-15, "at the COM by default")
end)

T.case("forces accumulate until the next step", function()
  local w = world{gravity = vec3()}
  local b = w:add(body.sphere{mass = 2, radius = 1})  -- I = 0.8
  b:apply_force(vec3(4, 0, 0))
  b:apply_force(vec3(0, 0, 0.4), vec3(0, 1, 0))  -- τ = (0,1,0) × (0,0,0.4) = (0.4, 0, 0)
  b:apply_torque(vec3(0, 0.8, 0))
  w:step(0.5)
  T.near(b.velocity, vec3(1, 0, 0.1), 1e-15, "Δv = F dt / m")
  T.near(b.angular_velocity, vec3(0.25, 0.5, 0), 1e-15, "Δω = I⁻¹ τ dt")
  w:step(0.5)
  T.near(b.velocity, vec3(1, 0, 0.1), 1e-15, "cleared after the step")
end)

T.case("static bodies", function()
  for _, s in ipairs{body{mass = math.huge}, body{static = true}, body.sphere{radius = 1, static = true},
                     body.box{size = vec3(1, 1, 1), mass = math.huge, position = vec3(0, -1, 0)}} do
    T.equal(s.static, true, "static"); T.equal(s.inv_mass, 0, "inv_mass"); T.equal(s.mass, math.huge, "mass")
    T.equal(s.inv_inertia, mat3.diag(0, 0, 0), "inv_inertia")
    s:apply_impulse(vec3(1, 2, 3), vec3(1, 0, 0)); s:apply_angular_impulse(vec3(1, 0, 0))
    s:apply_force(vec3(1, 0, 0))
    T.equal(s.velocity, vec3(), "impulses do nothing"); T.equal(s.angular_velocity, vec3(), "no spin")
    T.equal(s:kinetic_energy(), 0, "no energy"); T.equal(s:linear_momentum(), vec3(), "no momentum")
    s.velocity = vec3()  -- zero is allowed
  end
  local w = world()
  local floor = w:add(body.box{size = vec3(10, 1, 10), static = true})
  w:step(0.1, 10)
  T.equal(floor.position, vec3(), "a static body does not fall")
  T.equal(tostring(floor), "body(box, static, pos=(0, 0, 0))", "tostring")
end)

T.case("constructor errors", function()
  local I = mat3.identity()
  T.fails(function() return body(5) end, "bad argument #1 to 'body' (table expected, got number)")
  T.fails(function() return body{inertia = I} end,
    "bad argument #1 to 'body' (field 'mass' is required (or static = true))")
  T.fails(function() return body{mass = -1, inertia = I} end,
    "bad argument #1 to 'body' (field 'mass' must be > 0, got -1)")
  T.fails(function() return body{mass = 0/0, inertia = I} end,
    "bad argument #1 to 'body' (field 'mass' must be finite or math.huge, got nan)")
  T.fails(function() return body{mass = "1", inertia = I} end,
    "bad argument #1 to 'body' (field 'mass' must be a number, got string)")
  T.fails(function() return body{mass = 1} end, "bad argument #1 to 'body' (field 'inertia' is required)")
  T.fails(function() return body{mass = 1, inertia = vec3(1, 1, 1)} end,
    "bad argument #1 to 'body' (field 'inertia' must be a mat3, got vec3)")
  T.fails(function() return body{mass = 1, inertia = mat3.diag(1, 1, 3)} end,
    "bad argument #1 to 'body' (field 'inertia' is not a valid inertia tensor (symmetric, positive "
    .. "definite, A + B >= C): principal moments 1, 1, 3 violate A + B >= C (1 + 1 < 3 by 1))")
  T.fails(function() return body{mass = 1, inertia = mat3(1, 0.5, 0, 0, 1, 0, 0, 0, 1)} end,
    "bad argument #1 to 'body' (field 'inertia' is not a valid inertia tensor (symmetric, positive "
    .. "definite, A + B >= C): ")
  T.fails(function() return body{mass = 1, inertia = mat3.diag(1, 1, -1)} end,
    "bad argument #1 to 'body' (field 'inertia' is not a valid inertia tensor (symmetric, positive "
    .. "definite, A + B >= C): principal moments -1, 1, 1 are not all > 0")
  T.fails(function() return body{mass = 1, inertia = I, colour = "red"} end,
    "bad argument #1 to 'body' (unknown field 'colour' (fields are: mass, inertia, static, "
    .. "position, orientation, velocity, angular_velocity, restitution, friction))")
  T.fails(function() return body{mass = 1, inertia = I, position = 3} end,
    "bad argument #1 to 'body' (field 'position' must be a vec3, got number)")
  T.fails(function() return body{mass = 1, inertia = I, orientation = vec3()} end,
    "bad argument #1 to 'body' (field 'orientation' must be a quat, got vec3)")
  T.fails(function() return body{mass = 1, inertia = I, orientation = quat(0, 0, 0, 0)} end,
    "bad argument #1 to 'body' (field 'orientation' must be a rotation, got the zero quaternion)")
  T.fails(function() return body{mass = 2, static = true} end,
    "bad argument #1 to 'body' (field 'mass' must be math.huge or absent for a static body, got 2)")
  T.fails(function() return body{mass = math.huge, static = false} end,
    "bad argument #1 to 'body' (mass = math.huge makes a static body, but field 'static' is false)")
  T.fails(function() return body{static = 1} end,
    "bad argument #1 to 'body' (field 'static' must be a boolean, got number)")
  -- API.md "Bodies": a static body takes no inertia, however it is made static (item 22).
  local no_inertia = "bad argument #1 to 'body' (field 'inertia' must be absent: a static body "
    .. "(static = true or mass = math.huge) takes no inertia (its inverse inertia is 0))"
  T.fails(function() return body{static = true, inertia = I} end, no_inertia)
  T.fails(function() return body{mass = math.huge, inertia = I} end, no_inertia)
  T.fails(function() return body{static = true, velocity = vec3(1, 0, 0)} end,
    "bad argument #1 to 'body' (field 'velocity' must be zero for a static body (it never moves), "
    .. "got (1, 0, 0))")
  -- Subnormal masses and moments have inverses that overflow; huge entries overflow the moments.
  T.fails(function() return body{mass = 1e-320, inertia = I} end,
    "bad argument #1 to 'body' (field 'mass' is too small: 1/mass overflows, got 9.9998886718268e-321)")
  T.fails(function() return body{mass = 1, inertia = mat3.diag(1e-320, 1e-320, 1e-320)} end,
    "bad argument #1 to 'body' (field 'inertia' is not a valid inertia tensor (symmetric, positive "
    .. "definite, A + B >= C): principal moments 9.999888672e-321, 9.999888672e-321, "
    .. "9.999888672e-321 are too small for a body: the inverse tensor overflows "
    .. "(1/9.999888672e-321 = inf))")
  T.fails(function() return body{mass = 1, inertia = mat3.diag(1e308, 1e308, 1e308)} end,
    "bad argument #1 to 'body' (field 'inertia' is not a valid inertia tensor (symmetric, positive "
    .. "definite, A + B >= C): the tensor is too large: its principal moments overflow (largest "
    .. "entry 1e+308))")
  T.fails(function() return body.sphere{mass = 1, radius = 1e200} end,
    "bad argument #1 to 'body.sphere' (fields 'mass' (1) and 'radius' (1e+200) are too large: "
    .. "the inertia (2/5) m r² overflows)")
  T.fails(function() return body.box{mass = 1e300, size = vec3(1, 1e5, 1)} end,
    "bad argument #1 to 'body.box' (fields 'mass' (1e+300) and 'size' (1, 100000, 1) are too "
    .. "large: the inertia m (h² + d²)/12, ... overflows)")
  T.fails(function() return body.sphere{mass = 1e-300, radius = 1e-10} end,
    "bad argument #1 to 'body.sphere' (fields 'mass' (1e-300) and 'radius' (1e-10) give an inertia "
    .. "(2/5) m r² that no body can have: principal moments 4.001931731e-321")
  local tiny = body{mass = 1e-300, inertia = mat3.diag(1e-300, 2e-300, 2e-300)}
  T.near(tiny.inv_mass * 1e-300, 1, 1e-15, "1/m of a tiny but normal mass")
  T.near(tiny.inv_inertia * 1e-300, mat3.diag(1, 0.5, 0.5), 1e-15, "its inverse tensor")
  T.fails(function() return body.sphere{mass = 1, radius = -1} end,
    "bad argument #1 to 'body.sphere' (field 'radius' must be > 0, got -1)")
  T.fails(function() return body.sphere{mass = 1} end,
    "bad argument #1 to 'body.sphere' (field 'radius' is required)")
  T.fails(function() return body.sphere{mass = 1, radius = 1, size = vec3(1, 1, 1)} end,
    "bad argument #1 to 'body.sphere' (unknown field 'size'")
  T.fails(function() return body.box{mass = 1, size = vec3(1, 0, 1)} end,
    "bad argument #1 to 'body.box' (field 'size' must have every component > 0, got (1, 0, 1))")
  T.fails(function() return body.box{mass = 1, size = 2} end,
    "bad argument #1 to 'body.box' (field 'size' must be a vec3, got number)")
  T.fails(function() return body.box{mass = -2, size = vec3(1, 1, 1)} end,
    "bad argument #1 to 'body.box' (field 'mass' must be > 0, got -2)")
end)

T.case("field errors", function()
  local b = body.sphere{mass = 1, radius = 1}
  T.fails(function() b.mass = 2 end,
    "bad field 'mass' of body (read-only: mass properties and shape are fixed when the body is "
    .. "made)")
  T.fails(function() b.inertia = mat3.identity() end, "bad field 'inertia' of body (read-only")
  T.fails(function() b.inv_mass = 1 end, "bad field 'inv_mass' of body (read-only")
  T.fails(function() b.radius = 2 end, "bad field 'radius' of body (read-only")
  T.fails(function() b.colour = 1 end,
    "bad field 'colour' of body (no such field; the settable fields are position, orientation, "
    .. "velocity, angular_velocity, restitution, friction)")
  T.fails(function() return b.colour end,
    "bad field 'colour' of body (no such field; the fields are position, orientation")
  T.fails(function() b.position = 1 end, "bad field 'position' of body (vec3 expected, got number)")
  T.fails(function() b.velocity = {1, 2, 3} end,
    "bad field 'velocity' of body (vec3 expected, got table)")
  T.fails(function() b.orientation = vec3(1, 0, 0) end,
    "bad field 'orientation' of body (quat expected, got vec3)")
  T.fails(function() b.orientation = quat(0, 0, 0, 0) end,
    "bad field 'orientation' of body (must be a rotation, got the zero quaternion)")
  T.fails(function() return vec3(0 / 0, 0, 0) end,
    "bad argument #1 to 'vec3' (x must be finite, got nan)")  -- no vec3 holds NaN, but one can
  local infinite = body{static = true}.inertia:row(1)     -- hold inf: a static body's tensor row
  T.equal(infinite.x, math.huge, "an infinite vec3")
  T.fails(function() b.position = infinite end,
    "bad field 'position' of body (must be finite, got (inf, 0, 0))")
  T.fails(function() b.velocity = infinite end,
    "bad field 'velocity' of body (must be finite, got (inf, 0, 0))")
  T.fails(function() b.angular_velocity = infinite end,
    "bad field 'angular_velocity' of body (must be finite, got (inf, 0, 0))")
  T.fails(function() return body{mass = 1, inertia = mat3.identity(), position = infinite} end,
    "bad argument #1 to 'body' (field 'position' must be finite, got (inf, 0, 0))")
  T.fails(function() return body.sphere{mass = 1, radius = 1, angular_velocity = infinite} end,
    "bad argument #1 to 'body.sphere' (field 'angular_velocity' must be finite, got (inf, 0, 0))")
  -- NaN reads "nan" (printf writes the 0/0 of x86 as "-nan").
  T.fails(function() b.friction = 0 / 0 end,
    "bad field 'friction' of body (must be finite and >= 0, got nan)")
  T.fails(function() b.restitution = 0 / 0 end,
    "bad field 'restitution' of body (must be in [0, 1], got nan)")
  T.fails(function() b.friction = -math.huge end,
    "bad field 'friction' of body (must be finite and >= 0, got -inf)")
  T.fails(function() b.restitution = 1.5 end,
    "bad field 'restitution' of body (must be in [0, 1], got 1.5)")
  local s = body{static = true}
  T.fails(function() s.velocity = vec3(1, 0, 0) end,
    "bad field 'velocity' of body (must be zero for a static body (it never moves), got (1, 0, 0))")
  T.fails(function() s.angular_velocity = vec3(0, 1, 0) end,
    "bad field 'angular_velocity' of body (must be zero for a static body (it never moves), got "
    .. "(0, 1, 0))")
  T.equal(b.position, vec3(), "nothing changed")
end)

T.case("method errors", function()
  local b = body.sphere{mass = 1, radius = 1}
  T.fails(function() b:apply_force("up") end,
    "bad argument #1 to 'body:apply_force' (vec3 expected, got string)")
  T.fails(function() b:apply_force(vec3(), 5) end,
    "bad argument #2 to 'body:apply_force' (vec3 expected, got number)")
  T.fails(function() b:apply_impulse() end,
    "bad argument #1 to 'body:apply_impulse' (vec3 expected, got no value)")
  T.fails(function() b:apply_torque(vec3(), vec3()) end,
    "bad argument #2 to 'body:apply_torque' (no more than 2 arguments expected, got 3)")
  T.fails(function() return b:to_world() end,
    "bad argument #1 to 'body:to_world' (vec3 expected, got no value)")
  T.fails(function() return b.kinetic_energy(vec3()) end,
    "bad argument #1 to 'body:kinetic_energy' (body expected, got vec3)")
  T.fails(function() b:apply_force(vec3(1e308, 0, 0)); b:apply_force(vec3(1e308, 0, 0)) end,
    "bad argument #1 to 'body:apply_force' (the accumulated force or torque would overflow)")
  T.fails(function() b:apply_impulse(vec3(1e308, 0, 0)); b:apply_impulse(vec3(1e308, 0, 0)) end,
    "bad argument #1 to 'body:apply_impulse' (the impulse would make the velocity non-finite)")
end)

T.case("help knows bodies", function()
  T.equal(type(body.sphere), "function", "body.sphere")
  T.equal(body.kinetic_energy(body.sphere{mass = 2, radius = 1, velocity = vec3(1, 0, 0)}), 1,
    "methods are also functions of the body table")
end)

T.finish()
