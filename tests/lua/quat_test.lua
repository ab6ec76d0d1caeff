-- quat from Lua, checked against geometry: rotations preserve length, compose as products,
-- agree with their matrices and with the axis-angle they were built from.
local T = dofile("testing.lua")
local rnd = T.random(11)

local function random_rotation()
  return quat.axis_angle(vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)), rnd(-3, 3))
end

T.case("construction and fields", function()
  local q = quat(1, 2, 3, 4)
  T.equal(q.w, 1, "w"); T.equal(q.z, 4, "z")
  T.fails(function() q.x = 0 end,
    "bad field 'x' of quat (read-only: quat values are immutable, like numbers; build a new " ..
    "one, e.g. q = quat(q.w, 0, q.y, q.z), or for a body b.orientation = " ..
    "quat.axis_angle(axis, angle))", "fields are read-only (API.md Conventions)")
  T.equal(q, quat(1, 2, 3, 4), "the failed write changed nothing")
  T.equal(quat(), quat.identity(), "quat() is the identity")
  T.equal(tostring(quat.identity()), "quat(1, 0, 0, 0)", "tostring")
end)

T.case("known rotations", function()
  local q = quat.axis_angle(vec3(0, 0, 2), math.pi / 2)
  T.near(q:rotate(vec3(1, 0, 0)), vec3(0, 1, 0), 1e-15, "quarter turn about z")
  local axis, angle = q:axis_angle()
  T.near(axis, vec3(0, 0, 1), 1e-15, "axis back")
  T.near(angle, math.pi / 2, 1e-15, "angle back")
  T.near(quat.axis_angle(vec3(1, 0, 0), math.pi):rotate(vec3(0, 1, 0)), vec3(0, -1, 0), 1e-15,
    "half turn")
end)

T.case("huge and tiny quaternions and axes mean their direction", function()
  -- (a, a, 0, 0) normalises to (√½, √½, 0, 0) even where a² overflows or underflows; a
  -- quarter turn about (1, 1, 0) maps z to (1, −1, 0)/√2 whatever the axis length.
  local r = math.sqrt(0.5)
  for _, a in ipairs{1e200, 1e300, 1e-170, 1e-320} do
    T.near(quat(a, a, 0, 0):normalized(), quat(r, r, 0, 0), 1e-15, "normalized " .. a)
    if a > 1e-308 then T.near(quat(a, a, 0, 0):norm() / a, math.sqrt(2), 1e-15, "norm " .. a) end
    local q = quat.axis_angle(vec3(a, a, 0), math.pi / 2)
    T.near(q:norm(), 1, 1e-15, "axis_angle unit " .. a)
    T.near(q:rotate(vec3(0, 0, 1)), vec3(r, -r, 0), 1e-15, "axis_angle turn " .. a)
  end
end)

T.case("random rotations", function()
  for _ = 1, 200 do
    local q, r = random_rotation(), random_rotation()
    local v = vec3(rnd(-2, 2), rnd(-2, 2), rnd(-2, 2))
    T.near(q:rotate(v):norm(), v:norm(), 1e-12, "length preserved")
    T.near((q * r):rotate(v), q:rotate(r:rotate(v)), 1e-12, "product composes")
    T.near(q:to_mat3() * v, q:rotate(v), 1e-12, "matrix agrees")
    T.near(q:to_mat3():det(), 1, 1e-12, "proper rotation")
    T.near(q:conj():rotate(q:rotate(v)), v, 1e-12, "conjugate undoes")
    T.near(q * q:inverse(), quat.identity(), 1e-12, "inverse")
    local back = quat.from_mat3(q:to_mat3())
    T.near(math.abs(back:dot(q)), 1, 1e-12, "from_mat3 round trip (up to sign)")
    T.near((q * 3):normalized(), q, 1e-15, "normalized")
    -- Hamilton product of pure quaternions: (0, a)(0, b) = (−a·b, a×b)
    local a, b = vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1)), vec3(rnd(-1, 1), rnd(-1, 1), rnd(-1, 1))
    local p = quat(0, a.x, a.y, a.z) * quat(0, b.x, b.y, b.z)
    T.near(p, quat(-a:dot(b), a:cross(b).x, a:cross(b).y, a:cross(b).z), 1e-14, "Hamilton")
  end
end)

T.case("errors", function()
  T.fails(function() return quat(1, 2) end,
    "bad argument #3 to 'quat' (number expected, got no value)", "count")
  T.fails(function() return quat(0, 0, 0, 0):normalized() end,
    "calling 'quat:normalized' on bad self (the zero quaternion is not a rotation)", "zero")
  T.fails(function() return quat.axis_angle(vec3(), 1) end,
    "bad argument #1 to 'quat.axis_angle' (axis must be non-zero)", "zero axis")
  -- A vec3 can hold inf (a row of a static body's tensor); the engine's exception must not
  -- escape as a bare value.
  T.fails(function() return quat.axis_angle(body{static = true}.inertia:row(1), 1) end,
    "bad argument #1 to 'quat.axis_angle' (axis must be finite, got (inf, 0, 0))", "inf axis")
  T.fails(function() return quat.axis_angle(vec3(1, 0, 0), 0/0) end,
    "bad argument #2 to 'quat.axis_angle' (angle must be finite, got nan)", "NaN angle")
  T.fails(function() return quat.from_mat3(mat3.diag(1, 1, -1)) end,
    "bad argument #1 to 'quat.from_mat3' (matrix is a reflection (det = -1), not a rotation)",
    "reflection")
  T.fails(function() return quat.from_mat3(mat3.diag(2, 1, 1)) end,
    "matrix is not orthonormal", "scaled")
  -- Issue 12 item 11: a quaternion is finite or refused, whatever the matrix holds.
  T.fails(function() return quat.from_mat3(mat3.diag(1e308, 1, 1)) end,
    "bad argument #1 to 'quat.from_mat3' (matrix is not orthonormal (largest |RᵀR - E| entry = " ..
    "inf))", "RᵀR overflows")
  T.fails(function() return quat.from_mat3(body{static = true}.inertia) end,
    "bad argument #1 to 'quat.from_mat3' (matrix must be finite, got ((inf, 0, 0), (0, inf, 0), " ..
    "(0, 0, inf)))", "an infinite matrix: its products hold NaN, which passed the check")
  local _, axes = mat3.diag(1e308, 1, 1):eigen()
  local q = quat.from_mat3(axes)
  T.equal(q.w == q.w and q:norm() > 0.99, true, "the eigen axes of a huge matrix give a rotation")
  T.fails(function() return quat() * vec3() end, "quat * vec3 is not defined: use q:rotate(v)",
    "q * v")
  T.fails(function() return quat():rotate(5) end,
    "bad argument #1 to 'quat:rotate' (vec3 expected, got number)", "rotate(5)")
end)

T.finish()
