-- mat3 from Lua, checked against the defining identities (A·A⁻¹ = E, A·V = V·D, ...).
local T = dofile("testing.lua")
local rnd = T.random(7)

local function random_matrix()
  return mat3(rnd(-3, 3), rnd(-3, 3), rnd(-3, 3), rnd(-3, 3), rnd(-3, 3), rnd(-3, 3),
              rnd(-3, 3), rnd(-3, 3), rnd(-3, 3))
end

T.case("construction, entries, rows and columns", function()
  local m = mat3(1, 2, 3, 4, 5, 6, 7, 8, 9)
  T.equal(m:get(1, 2), 2, "row-major get(1, 2)")
  T.equal(m:get(3, 1), 7, "get(3, 1)")
  T.equal(m:row(2), vec3(4, 5, 6), "row 2")
  T.equal(m:col(3), vec3(3, 6, 9), "col 3")
  T.equal(mat3{{1, 2, 3}, {4, 5, 6}, {7, 8, 9}}, m, "table form")
  T.equal(tostring(m), "((1, 2, 3), (4, 5, 6), (7, 8, 9))", "tostring")
  T.equal(mat3.identity(), mat3.diag(1, 1, 1), "identity")
  T.equal(mat3.diag(vec3(1, 2, 3)), mat3.diag(1, 2, 3), "diag from vec3")
  T.equal(mat3.zero() + mat3.identity(), mat3.identity(), "zero")
end)

T.case("operators", function()
  local a, b = random_matrix(), random_matrix()
  local v = vec3(1, -2, 0.5)
  T.near((a * b) * v, a * (b * v), 1e-12, "associativity with a vector")
  T.near((a + b) - b, a, 1e-14, "+ and -")
  T.equal(2 * a, a * 2, "s * M == M * s")
  T.near(a / 2 * 2, a, 1e-15, "/")
  T.equal(-a + a, mat3.zero(), "unary -")
  T.near((a * b):transpose(), b:transpose() * a:transpose(), 1e-12, "(AB)ᵀ = BᵀAᵀ")
  T.near(mat3.skew(v) * vec3(0, 1, 0), v:cross(vec3(0, 1, 0)), 1e-15, "skew")
  T.near(mat3(2, 0, 0, 0, 3, 0, 0, 0, 4):det(), 24, 0, "det of a diagonal")
  T.equal(mat3(1, 2, 3, 4, 5, 6, 7, 8, 9):trace(), 15, "trace")
end)

T.case("inverse and determinant on random matrices", function()
  for _ = 1, 200 do
    local a = random_matrix()
    if math.abs(a:det()) > 1e-3 then
      T.near(a * a:inverse(), mat3.identity(), 1e-9, "A A⁻¹ = E")
      T.near((a * a):det(), a:det() ^ 2, 1e-9 * math.max(1, a:det() ^ 2), "det(AA) = det(A)²")
    end
  end
  -- a tiny but regular tensor is not called singular
  local tiny = mat3.diag(1e-9, 2e-9, 3e-9)
  T.near(tiny * tiny:inverse(), mat3.identity(), 1e-12, "small scale")
end)

T.case("eigen on random symmetric matrices", function()
  for _ = 1, 500 do
    local r = random_matrix()
    local a = (r + r:transpose()) / 2
    local values, axes = a:eigen()
    T.near(a * axes, axes * mat3.diag(values), 1e-12, "A·V = V·D")
    T.near(axes:transpose() * axes, mat3.identity(), 1e-12, "orthonormal axes")
    T.near(axes:det(), 1, 1e-12, "right-handed")
    assert(values.x <= values.y and values.y <= values.z, "ascending values")
  end
  local values, axes = mat3.diag(3, 1, 2):eigen()
  T.equal(values, vec3(1, 2, 3), "diagonal values ascending")
  T.near(axes:col(1), vec3(0, 1, 0), 0, "axis of the smallest value")
end)

-- Issue 12 item 11: symmetrising as ½(M + Mᵀ) overflowed for entries near the largest double
-- and gave (nan, nan, nan). A diagonal matrix is its own decomposition.
T.case("eigen of matrices with entries near the largest double", function()
  local values, axes = mat3.diag(1e308, 1, 1):eigen()
  -- The solver works on M / 1e308: the small values carry that scale's rounding (an ulp).
  T.near(values.x, 1, 2e-16, "1"); T.near(values.y, 1, 2e-16, "1")
  T.equal(values.z, 1e308, "1e308")
  T.near(axes:col(3), vec3(1, 0, 0), 0, "the axis of 1e308")
  T.near(axes:det(), 1, 1e-15, "right-handed")
  local big = 1.5e308  -- M = big·(outer of (1, 1, 0)/√2) + ... has the eigenvalue 2·big: inf
  T.fails(function() return mat3(big, big, 0, big, big, 0, 0, 0, 1):eigen() end,
    "calling 'mat3:eigen' on bad self (the eigenvalues are not finite (the largest overflows " ..
    "the largest double, 1.8e308))", "eigenvalue 3e308")
  -- Still exact where it fits: [[a, a], [a, a]] has eigenvalues 0 and 2a.
  local a = 0.8e308
  local v2 = mat3(a, a, 0, a, a, 0, 0, 0, 1):eigen()
  T.near(v2, vec3(0, 1, 2 * a), 1e-15 * 2 * a, "eigenvalues 0, 1, 1.6e308")
end)

T.case("inverse: decided on the equilibrated matrix, so scale alone is not singularity", function()
  T.equal(mat3.diag(1e308, 1, 1):inverse(), mat3.diag(1e-308, 1, 1), "huge entry")
  T.equal(mat3.diag(1e-6, 2e-6, 4e-6):inverse(), mat3.diag(1e6, 5e5, 2.5e5), "small tensor")
  -- Rows and columns of very different sizes: M M⁻¹ = E to rounding, entry by entry.
  local r, c = {2^600, 1, 2^-600}, {2^-300, 2^200, 1}
  local base = mat3(4, 1, 2, 1, 3, 0, 2, 0, 5)
  local rows = {}
  for i = 1, 3 do
    rows[i] = {}
    for j = 1, 3 do rows[i][j] = r[i] * base:get(i, j) * c[j] end
  end
  local M = mat3(rows)
  local product = M:inverse() * M
  T.near(product, mat3.identity(), 1e-14, "M⁻¹ M for rows 2^600..2^-600, columns 2^-300..2^200")
  T.fails(function() return mat3(1, 2, 3, 2, 4, 6.000000000000001, 0, 0, 1):inverse() end,
    "calling 'mat3:inverse' on bad self (matrix is singular (rank 2", "singular to rounding")
end)

T.case("errors", function()
  local m = mat3.identity()
  T.fails(function() return mat3(1, 2) end,
    "bad argument #3 to 'mat3' (number expected, got no value)", "count")
  T.fails(function() return mat3(1, 2, 3, 4, 5, 6, 7, 8, 9, 10) end,
    "bad argument #10 to 'mat3' (no more than 9 arguments expected, got 10)", "too many")
  T.fails(function() return mat3("x") end,
    "bad argument #1 to 'mat3' (number or table of 3 rows expected, got string)", "neither")
  T.fails(function() return mat3(1, 2, 3, 4, 5, 6, 7, 8, 0/0) end,
    "bad argument #9 to 'mat3' (a33 must be finite, got nan)", "NaN entry")
  T.fails(function() return mat3{{1, 2, 3}, {4, 5}, {7, 8, 9}} end,
    "bad argument #1 to 'mat3' (row 2 must have 3 numbers, got 2)", "short row")
  T.fails(function() return mat3{{1, 2, 3}, {4, 5, "x"}, {7, 8, 9}} end,
    "bad argument #1 to 'mat3' (entry (2, 3) must be a number, got string)", "string entry")
  T.fails(function() return m:get(0, 1) end,
    "bad argument #1 to 'mat3:get' (row must be an integer from 1 to 3, got 0)", "row 0")
  T.fails(function() return m:get(1, 1.5) end,
    "bad argument #2 to 'mat3:get' (column must be an integer from 1 to 3, got 1.5)", "col 1.5")
  -- Integer-valued floats count as integers everywhere (issue 12 item 20).
  T.equal(m:get(2.0, 3.0), m:get(2, 3), "2.0 is the integer 2")
  T.equal(m:row(1.0), m:row(1), "row 1.0")
  T.fails(function() return mat3(1, 2, 3, 2, 4, 6, 0, 0, 1):inverse() end,
    "calling 'mat3:inverse' on bad self (matrix is singular (rank 2, det = 0))", "singular")
  T.fails(function() return mat3(1, 2, 0, 0, 1, 0, 0, 0, 1):eigen() end,
    "calling 'mat3:eigen' on bad self (matrix must be symmetric (largest |a_ij - a_ji| = 2))",
    "non-symmetric eigen")
  T.fails(function() return vec3(1, 2, 3) * m end,
    "vec3 * mat3 is not defined (vectors are columns)", "v * M")
  T.fails(function() return m * "x" end,
    "bad argument #2 to 'mat3.__mul' (vec3, mat3 or number expected, got string)", "M * 'x'")
  T.fails(function() return m / 0 end, "division of a mat3 by zero", "M / 0")
  T.fails(function() m.x = 1 end,
    "bad field 'x' of mat3 (read-only: mat3 values are immutable, like numbers", "write")
  T.fails(function() return m.foo end, "bad field 'foo' of mat3 (no such field", "unknown field")
  T.fails(function() return m * 1e308 * 2 end,
    "bad argument #2 to 'mat3.__mul' (the result is not finite", "overflow")
  T.fails(function() return mat3.diag(1e-310, 1, 1):inverse() end,
    "calling 'mat3:inverse' on bad self (the inverse is not finite", "inverse overflows")
  T.fails(function() return mat3.transpose(vec3()) end,
    "bad argument #1 to 'mat3:transpose' (mat3 expected, got vec3)", "wrong self")
end)

T.finish()
