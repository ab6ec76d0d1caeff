-- vec3 from Lua: construction, fields, operators, methods, and the errors a learner meets.
local T = dofile("testing.lua")

T.case("construction and fields", function()
  local v = vec3(1, 2, 3)
  T.equal(v.x, 1, "x"); T.equal(v.y, 2, "y"); T.equal(v.z, 3, "z")
  T.equal(vec3(), vec3(0, 0, 0), "missing components are 0")
  T.equal(vec3(5), vec3(5, 0, 0), "vec3(5)")
  T.fails(function() v.y = -7 end,
    "bad field 'y' of vec3 (read-only: vec3 values are immutable, like numbers; build a new " ..
    "one, e.g. v = vec3(v.x, -7, v.z), or for a body b.position = vec3(b.position.x, -7, " ..
    "b.position.z))", "fields are read-only (API.md Conventions)")
  T.equal(v, vec3(1, 2, 3), "the failed write changed nothing")
  T.equal(require("rigidlab").vec3, vec3, "require gives the same vec3")
end)

T.case("tostring is short and stable", function()
  T.equal(tostring(vec3(1, 2, 3)), "(1, 2, 3)", "integers")
  T.equal(tostring(vec3(0.5, -0.25, 1e20)), "(0.5, -0.25, 1e+20)", "fractions")
  T.equal("v = " .. vec3(1, 0, 0), "v = (1, 0, 0)", "concat")
end)

T.case("operators", function()
  local a, b = vec3(1, 2, 3), vec3(4, 5, 6)
  T.equal(a + b, vec3(5, 7, 9), "+")
  T.equal(a - b, vec3(-3, -3, -3), "-")
  T.equal(-a, vec3(-1, -2, -3), "unary -")
  T.equal(a * 2, vec3(2, 4, 6), "v * s")
  T.equal(2 * a, vec3(2, 4, 6), "s * v")
  T.equal(b / 2, vec3(2, 2.5, 3), "/")
  T.equal(a == vec3(1, 2, 3), true, "== equal")
  T.equal(a == b, false, "== different")
  T.equal(a == 5, false, "== other type")
  local c = a + b
  T.equal(rawequal(c, a) or rawequal(c, b), false, "operators return new values")
end)

T.case("products against their defining identities", function()
  local rnd = T.random(1)
  for _ = 1, 200 do
    local a = vec3(rnd(-5, 5), rnd(-5, 5), rnd(-5, 5))
    local b = vec3(rnd(-5, 5), rnd(-5, 5), rnd(-5, 5))
    local c = a:cross(b)
    T.near(c:dot(a), 0, 1e-12, "a×b ⟂ a")
    T.near(c:dot(b), 0, 1e-12, "a×b ⟂ b")
    -- Lagrange's identity |a×b|² = |a|²|b|² − (a·b)²
    T.near(c:norm()^2, a:norm()^2 * b:norm()^2 - a:dot(b)^2, 1e-9, "Lagrange")
    T.near(a:skew() * b, c, 1e-12, "hat operator")
    T.near(a:outer(b) * b, a * b:dot(b), 1e-10, "outer product (a bᵀ) b = a (b·b)")
    T.near(a:normalized():norm(), 1, 1e-15, "normalized")
  end
  T.equal(vec3(1, 0, 0):cross(vec3(0, 1, 0)), vec3(0, 0, 1), "right-handed")
  T.equal(vec3(3, 4, 0):norm(), 5, "3-4-5")
  T.equal(vec3.dot(vec3(1, 2, 3), vec3(1, 1, 1)), 6, "vec3.dot as a function")
  T.equal(select("#", vec3(1, 2, 3):unpack()), 3, "unpack count")
end)

T.case("norm and normalized at huge and tiny scales", function()
  -- |(a, a, 0)| = √2 a with direction (1, 1, 0)/√2, also where a² overflows or underflows
  -- (a subnormal length like √2·1e-320 has too few digits to compare, its direction has not).
  local r = math.sqrt(0.5)
  for _, a in ipairs{1e300, 1e-170, 1e-300, 1e-320} do
    if a > 1e-308 then T.near(vec3(a, a, 0):norm() / a, math.sqrt(2), 1e-15, "norm " .. a) end
    T.near(vec3(a, a, 0):normalized(), vec3(r, r, 0), 1e-15, "normalized " .. a)
  end
end)

T.case("metatable is protected", function()
  T.equal(getmetatable(vec3()), "vec3", "getmetatable")
  T.fails(function() setmetatable(vec3(), {}) end, "table expected, got vec3", "setmetatable")
  T.equal(getmetatable(vec3), "vec3", "the vec3 table too")
end)

T.case("errors name the function and the argument", function()
  T.fails(function() return vec3(1, 2, 3):cross(5) end,
    "bad argument #1 to 'vec3:cross' (vec3 expected, got number)", "cross(5)")
  T.fails(function() return vec3(1, 2, 3):dot() end,
    "bad argument #1 to 'vec3:dot' (vec3 expected, got no value)", "dot()")
  T.fails(function() return vec3("1") end,
    "bad argument #1 to 'vec3' (number expected, got string)", "string component")
  T.fails(function() return vec3(0/0) end,
    "bad argument #1 to 'vec3' (x must be finite, got nan)", "NaN component")
  T.fails(function() return vec3(1, math.huge) end,
    "bad argument #2 to 'vec3' (y must be finite, got inf)", "Inf component")
  T.fails(function() return vec3(1, 2, 3, 4) end,
    "bad argument #4 to 'vec3' (no more than 3 arguments expected, got 4)", "extra argument")
  T.fails(function() return vec3(1, 2, 3) + 5 end,
    "bad argument #2 to 'vec3.__add' (vec3 expected, got number)", "v + 5")
  T.fails(function() return 5 - vec3(1, 2, 3) end,
    "bad argument #1 to 'vec3.__sub' (vec3 expected, got number)", "5 - v")
  T.fails(function() return vec3(1, 2, 3) * vec3(1, 2, 3) end,
    "vec3 * vec3 is not defined: use a:dot(b), a:cross(b) or a:outer(b)", "v * v")
  T.fails(function() return vec3(1, 2, 3) * "2" end,
    "bad argument #2 to 'vec3.__mul' (number (vec3 * number) expected, got string)", "v * '2'")
  T.fails(function() return vec3(1, 2, 3) / 0 end,
    "bad argument #2 to 'vec3.__div' (division of a vec3 by zero)", "v / 0")
  T.fails(function() return vec3():normalized() end,
    "calling 'vec3:normalized' on bad self (cannot normalize the zero vector)", "normalize 0")
  T.fails(function() return vec3(1e300, 0, 0) * 1e300 end,
    "bad argument #2 to 'vec3.__mul' (the result is not finite (a component overflows the "
    .. "largest double, 1.8e308))", "overflow")
  T.fails(function() return vec3(1, 2, 3) * (0/0) end,
    "bad argument #2 to 'vec3.__mul' (factor must be finite, got nan)", "v * nan")
  T.fails(function() return vec3().w end,
    "bad field 'w' of vec3 (no such field; the fields are x, y, z, the methods are in help(\"vec3\"))",
    "unknown field")
  T.fails(function() local v = vec3(); v.w = 1 end,
    "bad field 'w' of vec3 (no such field; the fields are x, y, z)", "set unknown")
  T.fails(function() local v = vec3(); v.x = 0/0 end,
    "bad field 'x' of vec3 (read-only: vec3 values are immutable, like numbers; build a new " ..
    "one, e.g. v = vec3(nan, v.y, v.z)", "set NaN")
  T.fails(function() local v = vec3(); v.z = "a" end,
    "bad field 'z' of vec3 (read-only: vec3 values are immutable, like numbers; build a new " ..
    "one, e.g. v = vec3(v.x, v.y, new)", "set string")
  T.fails(function() return vec3.cross(5, vec3()) end,
    "bad argument #1 to 'vec3:cross' (vec3 expected, got number)", "wrong self as function")
  T.fails(function() return vec3(1, 2, 3):cross(mat3.identity()) end,
    "bad argument #1 to 'vec3:cross' (vec3 expected, got mat3)", "mat3 where vec3 expected")
end)

T.case("a failed write leaves the value unchanged", function()
  local v = vec3(1, 2, 3)
  pcall(function() v.x = 0/0 end)
  T.equal(v, vec3(1, 2, 3), "unchanged")
end)

T.finish()
