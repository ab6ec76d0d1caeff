-- collide.* from Lua against the documents' numbers (001 "System Of Particles") and physics
-- computed here from the bodies' own methods: conservation of linear and angular momentum,
-- kinetic energy, Newton's restitution law, rolling at 5/7 of the speed, the Coulomb limit,
-- the direct formula of the effective mass, and the velocity change an impulse causes.
local T = dofile("testing.lua")

T.case("impulse_1d: the document's numbers", function()
  -- 001 "System Of Particles": equal masses exchange velocities; 1 against 4 bounces back.
  local j, va, vb = collide.impulse_1d(1, 2, 1, 0, 1)
  T.near(j, 2, 1e-15, "J"); T.near(va, 0, 1e-15, "va'"); T.near(vb, 2, 1e-15, "vb'")
  j, va, vb = collide.impulse_1d(1, 2, 4, 0, 1)
  T.near(j, 3.2, 1e-15, "J"); T.near(va, -1.2, 1e-15, "va'"); T.near(vb, 0.8, 1e-15, "vb'")
end)

T.case("impulse_1d: immovable bodies, momentum, restitution", function()
  -- 003 "Collision Response": against an immovable body p = (1 + ε) m v, and v' = −ε v.
  local j, va, vb = collide.impulse_1d(3, 4, math.huge, 0, 0.5)
  T.near(j, 1.5 * 3 * 4, 1e-14, "J"); T.near(va, -2, 1e-15, "va'"); T.equal(vb, 0, "wall")
  j, va, vb = collide.impulse_1d(math.huge, 1, 2, -3, 1)  -- a moving wall hits b
  T.near(vb, 1 + 4, 1e-15, "elastic bounce off a moving wall: vb' = 2 v_wall − vb")
  T.equal(va, 1, "the wall keeps its speed")
  local rnd = T.random(3)
  for _ = 1, 100 do
    local ma, mb, ua, ub, e = rnd(0.1, 10), rnd(0.1, 10), rnd(-5, 5), rnd(-5, 5), rnd(0, 1)
    local _, wa, wb = collide.impulse_1d(ma, ua, mb, ub, e)
    T.near(ma * wa + mb * wb, ma * ua + mb * ub, 1e-12, "momentum")
    T.near(wb - wa, -e * (ub - ua), 1e-12, "restitution law")
  end
end)

T.case("impulse_1d: errors", function()
  T.fails(function() return collide.impulse_1d(0, 1, 1, 0, 1) end,
    "bad argument #1 to 'collide.impulse_1d' (mass must be > 0 (math.huge for immovable), got 0)",
    "zero mass")
  T.fails(function() return collide.impulse_1d(1, 1, 0 / 0, 0, 1) end,
    "bad argument #3 to 'collide.impulse_1d' (mass must be > 0 (math.huge for immovable), " ..
    "got nan)", "NaN mass")
  T.fails(function() return collide.impulse_1d(1, math.huge, 1, 0, 1) end,
    "bad argument #2 to 'collide.impulse_1d' (va must be finite, got inf)", "infinite velocity")
  T.fails(function() return collide.impulse_1d(1, 1, 1, 0, 1.5) end,
    "bad argument #5 to 'collide.impulse_1d' (restitution must be in [0, 1], got 1.5)", "e > 1")
  T.fails(function() return collide.impulse_1d(1, 1, 1, 0) end,
    "bad argument #5 to 'collide.impulse_1d' (number expected, got no value)", "no e")
  T.fails(function() return collide.impulse_1d(math.huge, 1, math.huge, 0, 1) end,
    "bad argument #3 to 'collide.impulse_1d' (both masses are math.huge: two immovable " ..
    "bodies cannot collide)", "two walls")
end)

-- A random box with its body axes turned, at a random pose, moving and spinning.
local function random_body(rnd)
  local m = rnd(0.5, 5)
  local axis = vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)) + vec3(0.1, 0, 0)
  local turn = quat.axis_angle(vec3(rnd(-1, 1), rnd(-1, 1), 1), rnd(0, 3))
  return body{mass = m,
              inertia = inertia.rotate(inertia.solid_box(m, rnd(0.2, 2), rnd(0.2, 2), rnd(0.2, 2)), turn),
              position = vec3(rnd(-3, 3), rnd(-3, 3), rnd(-3, 3)),
              orientation = quat.axis_angle(axis, rnd(0, 3)),
              velocity = vec3(rnd(-4, 4), rnd(-4, 4), rnd(-4, 4)),
              angular_velocity = vec3(rnd(-3, 3), rnd(-3, 3), rnd(-3, 3))}
end

-- Two random bodies and an approaching contact between them.
local function random_contact(rnd)
  local a, b = random_body(rnd), random_body(rnd)
  local p = (a.position + b.position) * 0.5 + vec3(rnd(-0.5, 0.5), rnd(-0.5, 0.5), rnd(-0.5, 0.5))
  local n = vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)):normalized()
  if (b:point_velocity(p) - a:point_velocity(p)):dot(n) > 0 then n = -n end
  return a, b, p, n
end

local function angular_momentum_about(b, q)
  return (b.position - q):cross(b:linear_momentum()) + b:angular_momentum()
end

T.case("resolve conserves linear and angular momentum about any point", function()
  local rnd = T.random(11)
  for _ = 1, 100 do
    local a, b, p, n = random_contact(rnd)
    local q = vec3(rnd(-5, 5), rnd(-5, 5), rnd(-5, 5))
    local p0 = a:linear_momentum() + b:linear_momentum()
    local l0 = angular_momentum_about(a, q) + angular_momentum_about(b, q)
    local j = collide.resolve(a, b, {point = p, normal = n, restitution = rnd(0, 1),
                                     friction = rnd(0, 2)})
    assert(j > 0, "approaching bodies get a positive impulse")
    T.near(a:linear_momentum() + b:linear_momentum(), p0, 1e-11, "linear momentum")
    T.near(angular_momentum_about(a, q) + angular_momentum_about(b, q), l0, 1e-10,
      "angular momentum about q")
  end
end)

T.case("resolve: energy and Newton's restitution law without friction", function()
  local rnd = T.random(12)
  for i = 1, 100 do
    local a, b, p, n = random_contact(rnd)
    local e = i % 3 == 0 and 1 or rnd(0, 0.95)
    local vn = (b:point_velocity(p) - a:point_velocity(p)):dot(n)
    local t0 = a:kinetic_energy() + b:kinetic_energy()
    collide.resolve(a, b, {point = p, normal = n, restitution = e})
    local t1 = a:kinetic_energy() + b:kinetic_energy()
    T.near((b:point_velocity(p) - a:point_velocity(p)):dot(n), -e * vn, 1e-11, "v_n' = −e v_n")
    if e == 1 then
      T.near(t1, t0, 1e-10 * t0, "elastic: energy kept")
    else
      assert(t1 < t0, "inelastic: energy lost")
    end
  end
end)

-- The contact's inverse mass matrix K = M_a⁻¹ + M_b⁻¹ at p from collide.inverse_mass_matrix
-- (checked above against b:apply_impulse): v_rel' = v_rel + K P for P on b and −P on a.
local function contact_matrix(a, b, p)
  local ra, rb = p - a.position, p - b.position
  return collide.inverse_mass_matrix(a, ra, ra) + collide.inverse_mass_matrix(b, rb, rb)
end

T.case("resolve with friction: Newton's law, Coulomb's cone, no energy gain, sticking", function()
  -- Turned boxes couple normal and tangential motion (n·K t ≠ 0): the normal condition must
  -- hold after friction acts, and a contact that the cone allows to stop must stop.
  local rnd = T.random(21)
  local stuck = 0
  for i = 1, 300 do
    local a, b, p, n = random_contact(rnd)
    local e = i % 2 == 0 and 0 or rnd(0, 1)
    local mu = i % 3 == 0 and 100 or rnd(0, 2)
    local v = b:point_velocity(p) - a:point_velocity(p)
    local vn = v:dot(n)
    local t0 = a:kinetic_energy() + b:kinetic_energy()
    local p0 = a:linear_momentum() + b:linear_momentum()
    -- The impulse that would leave the point at −e v_n n, with no slip: P = K⁻¹(v' − v).
    local k = contact_matrix(a, b, p)
    local stop = k:inverse() * (n * (-e * vn) - v)
    local stop_n = stop:dot(n)
    local can_stick = stop_n > 0 and (stop - n * stop_n):norm() <= mu * stop_n and
      stop:dot(v) + 0.5 * stop:dot(k * stop) <= -1e-9
    local j, jt = collide.resolve(a, b, {point = p, normal = n, restitution = e, friction = mu})
    local after = b:point_velocity(p) - a:point_velocity(p)
    T.near(after:dot(n), -e * vn, 1e-11 * (1 + math.abs(vn)), "v_n' = −e v_n")
    assert(jt:norm() <= mu * j * (1 + 1e-12), "inside Coulomb's cone")
    T.near(a:linear_momentum() + b:linear_momentum(), p0, 1e-11, "momentum")
    assert(a:kinetic_energy() + b:kinetic_energy() <= t0 * (1 + 1e-13), "no energy gained")
    if can_stick then
      stuck = stuck + 1
      T.near((after - n * after:dot(n)):norm(), 0, 1e-10 * (1 + v:norm()), "ends sticking")
    end
  end
  assert(stuck > 50, "sticking cases were tested: " .. stuck)
end)

T.case("resolve: effective_mass against the direct formula, and the energy it predicts", function()
  local rnd = T.random(13)
  for _ = 1, 50 do
    local a, b, p, n = random_contact(rnd)
    local ra, rb = p - a.position, p - b.position
    local ca, cb = ra:cross(n), rb:cross(n)
    local jwj = 1 / a.mass + 1 / b.mass + ca:dot(a:inv_world_inertia() * ca) +
                cb:dot(b:inv_world_inertia() * cb)
    local m_eff = collide.effective_mass(a, b, p, n * 2.5)  -- any normal length
    T.near(m_eff * jwj, 1, 1e-12, "1/(J W Jᵀ)")
    -- An impulse along n with e = 0 removes ½ m_eff v_n² of kinetic energy.
    local vn = (b:point_velocity(p) - a:point_velocity(p)):dot(n)
    local t0 = a:kinetic_energy() + b:kinetic_energy()
    local j = collide.resolve(a, b, {point = p, normal = n, restitution = 0})
    T.near(j, -m_eff * vn, 1e-12 * (1 + j), "J = −m_eff v_n for e = 0")
    T.near(t0 - (a:kinetic_energy() + b:kinetic_energy()), 0.5 * m_eff * vn * vn, 1e-10,
      "energy lost")
  end
end)

T.case("inverse_mass_matrix times an impulse is the velocity change at r2", function()
  -- 002 "Inverse Mass Matrix", measured with b:apply_impulse and b:point_velocity.
  local rnd = T.random(14)
  for _ = 1, 50 do
    local b = random_body(rnd)
    local r1 = vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1))
    local r2 = vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1))
    local j = vec3(rnd(-2, 2), rnd(-2, 2), rnd(-2, 2))
    local m_inv = collide.inverse_mass_matrix(b, r1, r2)
    local before = b:point_velocity(b.position + r2)
    b:apply_impulse(j, b.position + r1)
    T.near(b:point_velocity(b.position + r2) - before, m_inv * j, 1e-12, "M⁻¹ j")
  end
  local wall = body{mass = math.huge}
  T.equal(collide.inverse_mass_matrix(wall, vec3(1, 2, 3), vec3(0, 1, 0)), mat3(0, 0, 0, 0, 0, 0, 0, 0, 0),
    "immovable: zero")
end)

-- A solid sphere (2 kg, radius 0.5 m) hitting the floor at (3, −4, 0) m/s without spin.
local function sphere_on_floor(friction)
  local floor = body{static = true}
  local ball = body.sphere{mass = 2, radius = 0.5, position = vec3(0, 0.5, 0),
                           velocity = vec3(3, -4, 0)}
  local j, friction_impulse = collide.resolve(floor, ball, {point = vec3(), normal = vec3(0, 1, 0),
    restitution = 0, friction = friction})
  return ball, floor, j, friction_impulse
end

T.case("a sphere with high friction leaves rolling at 5/7 of its speed", function()
  -- Friction s stops the contact point when 3 = s (1/m + R²/I), I = (2/5) m R²:
  -- s = (2/7) m 3, v = 3 − s/m = (5/7) 3, and ω R = −v (rolling).
  local ball, floor, j = sphere_on_floor(10)
  T.near(j, 2 * 4, 1e-14, "e = 0: J = m v_n")
  T.near(ball.velocity, vec3(15 / 7, 0, 0), 1e-14, "v = 5/7 v0")
  T.near(ball.angular_velocity, vec3(0, 0, -(15 / 7) / 0.5), 1e-13, "ω = −v/R about z")
  T.near(ball:point_velocity(vec3()), vec3(), 1e-14, "the contact point is at rest")
  T.equal(floor.velocity, vec3(), "the floor does not move")
end)

T.case("with low friction the friction impulse is exactly μ J", function()
  local ball, _, j, friction_impulse = sphere_on_floor(0.1)
  T.near(friction_impulse, vec3(-0.1 * j, 0, 0), 1e-14, "μ J against the slip")
  T.near(ball.velocity, vec3(3 - 0.1 * j / 2, 0, 0), 1e-14, "v = v0 − μ J / m")
  assert(ball:point_velocity(vec3()).x > 0, "still sliding")
end)

T.case("separating bodies are left alone", function()
  local a = body.sphere{mass = 1, radius = 1, velocity = vec3(-1, 0, 0)}
  local b = body.sphere{mass = 1, radius = 1, position = vec3(2, 0, 0), velocity = vec3(1, 0, 0)}
  local j, f = collide.resolve(a, b, {point = vec3(1, 0, 0), normal = vec3(1, 0, 0),
                                      restitution = 1, friction = 1})
  T.equal(j, 0, "J = 0"); T.equal(f, vec3(), "no friction")
  T.equal(a.velocity, vec3(-1, 0, 0), "a unchanged"); T.equal(b.velocity, vec3(1, 0, 0), "b")
end)

T.case("errors name the argument and the rule", function()
  local a = body.sphere{mass = 1, radius = 1}
  local b = body.sphere{mass = 1, radius = 1, position = vec3(2, 0, 0), velocity = vec3(-1, 0, 0)}
  local wall = body{static = true}
  local wall2 = body{mass = math.huge}
  local ok = {point = vec3(1, 0, 0), normal = vec3(1, 0, 0)}
  local function contact(changes)
    local c = {point = ok.point, normal = ok.normal}
    for k, v in pairs(changes) do c[k] = v end
    return c
  end
  local function fails(text, fn) T.fails(fn, text, text) end
  fails("bad argument #3 to 'collide.resolve' (field 'normal' must not be zero)",
    function() collide.resolve(a, b, contact{normal = vec3()}) end)
  fails("bad argument #3 to 'collide.resolve' (field 'restitution' must be in [0, 1], got 1.2)",
    function() collide.resolve(a, b, contact{restitution = 1.2}) end)
  fails("bad argument #3 to 'collide.resolve' (field 'restitution' must be in [0, 1], got -0.5)",
    function() collide.resolve(a, b, contact{restitution = -0.5}) end)
  fails("bad argument #3 to 'collide.resolve' (field 'friction' must be >= 0, got -1)",
    function() collide.resolve(a, b, contact{friction = -1}) end)
  fails("bad argument #3 to 'collide.resolve' (field 'point' is required)",
    function() collide.resolve(a, b, {normal = vec3(1, 0, 0)}) end)
  fails("bad argument #3 to 'collide.resolve' (field 'normal' must be a vec3, got number)",
    function() collide.resolve(a, b, contact{normal = 1}) end)
  fails("bad argument #3 to 'collide.resolve' (unknown field 'restitutoin' (fields are: " ..
    "point, normal, restitution, friction))",
    function() collide.resolve(a, b, contact{restitutoin = 1}) end)
  fails("bad argument #2 to 'collide.resolve' (b must be a different body from a)",
    function() collide.resolve(a, a, ok) end)
  fails("bad argument #2 to 'collide.resolve' (both bodies are immovable: a contact between " ..
    "them has no impulse)", function() collide.resolve(wall, wall2, ok) end)
  fails("bad argument #1 to 'collide.resolve' (body expected, got vec3)",
    function() collide.resolve(vec3(), b, ok) end)
  fails("bad argument #3 to 'collide.resolve' (table expected, got no value)",
    function() collide.resolve(a, b) end)
  fails("bad argument #4 to 'collide.effective_mass' (normal must not be zero)",
    function() collide.effective_mass(a, b, vec3(1, 0, 0), vec3()) end)
  fails("bad argument #2 to 'collide.effective_mass' (b must be a different body from a)",
    function() collide.effective_mass(b, b, vec3(1, 0, 0), vec3(1, 0, 0)) end)
  fails("bad argument #2 to 'collide.effective_mass' (both bodies are immovable: a contact " ..
    "between them has no impulse)",
    function() collide.effective_mass(wall, wall2, vec3(), vec3(1, 0, 0)) end)
  fails("bad argument #3 to 'collide.inverse_mass_matrix' (vec3 expected, got no value)",
    function() collide.inverse_mass_matrix(a, vec3()) end)
  -- Values the engine cannot use: refused with the argument named, never a stray message.
  fails("bad argument #1 to 'collide.impulse_1d' (mass must be at least 5.562684646268e-309 " ..
    "(1/mass overflows), got 9.9998886718268e-321)",
    function() collide.impulse_1d(1e-320, 1, 1, 0, 0.5) end)
  fails("bad argument #2 to 'collide.impulse_1d' (the impulse overflows",
    function() collide.impulse_1d(1, 1e308, 1, -1e308, 1) end)
  fails("bad argument #3 to 'collide.effective_mass' (point (1e+300, 0, 0) is too far from " ..
    "the centres of mass: J W Jᵀ overflows)",
    function() collide.effective_mass(a, b, vec3(1e300, 0, 0), vec3(0, 1, 0)) end)
  fails("bad argument #3 to 'collide.resolve' (point (1, 1e+160, 0) is too far from the " ..
    "centres of mass: the impulse overflows)",
    function() collide.resolve(a, b, contact{point = vec3(1, 1e160, 0)}) end)
  fails("bad argument #3 to 'collide.inverse_mass_matrix' (r1 and r2 are too long: " ..
    "r̂2 I⁻¹ r̂1 overflows, got r1 = (1e+200, 0, 0), r2 = (0, 1e+200, 0))",
    function() collide.inverse_mass_matrix(b, vec3(1e200, 0, 0), vec3(0, 1e200, 0)) end)
  T.equal(b.velocity, vec3(-1, 0, 0), "refused calls change nothing")
  T.equal(a.velocity, vec3(), "refused calls change nothing (a)")
  T.equal(b.angular_velocity, vec3(), "nor the spin")
  -- A long normal is still a direction: (1e300, 1e300, 0) acts as (1, 1, 0).
  local a2, b2 = body.sphere{mass = 1, radius = 1}, body.sphere{mass = 1, radius = 1,
    position = vec3(2, 0, 0), velocity = vec3(-1, 0, 0)}
  local j_long = collide.resolve(a, b, contact{normal = vec3(1e300, 1e300, 0)})
  local j_unit = collide.resolve(a2, b2, contact{normal = vec3(1, 1, 0)})
  T.near(j_long, j_unit, 1e-15, "J along a long normal")
  assert(j_unit > 0, "and it is an impact")
  T.near(collide.effective_mass(a, b, vec3(1, 0, 0), vec3(1e300, 1e300, 0)),
    collide.effective_mass(a, b, vec3(1, 0, 0), vec3(1, 1, 0)), 1e-15, "m_eff along a long normal")
end)

T.case("no impulses in the middle of a world step", function()
  local w = world{}
  local a = w:add(body.sphere{mass = 1, radius = 1})
  local b = body.sphere{mass = 1, radius = 1, position = vec3(2, 0, 0), velocity = vec3(-1, 0, 0)}
  w:add_force(function()
    collide.resolve(b, a, {point = vec3(1, 0, 0), normal = vec3(-1, 0, 0)})
  end)
  T.fails(function() w:step(0.1) end,
    "bad argument #2 to 'collide.resolve' (the world is stepping: cannot apply collision impulses", "inside a callback")
  T.equal(b.velocity, vec3(-1, 0, 0), "nothing applied")
end)

T.finish()
