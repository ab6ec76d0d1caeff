-- The inertia module from Lua: every function callable with the documented conventions, values
-- against the closed forms and geometric facts written out here, and every refusal with an
-- error naming the function and the argument.
local T = dofile("testing.lua")

local function diag(a, b, c) return mat3.diag(a, b, c) end

-- The error text of a call that must fail (without the "file:line:" position).
local function error_of(fn, ...)
  local ok, message = pcall(fn, ...)
  assert(not ok, "expected an error")
  return (tostring(message):gsub("^[^:]*:%d+: ", ""))
end

T.case("shapes follow the documented formulas and axes", function()
  local m = 2
  T.near(inertia.solid_sphere(m, 0.5), diag(0.2, 0.2, 0.2), 1e-15, "solid sphere 2/5 m r²")
  T.near(inertia.hollow_sphere(m, 0.5), diag(1 / 3, 1 / 3, 1 / 3), 1e-15, "shell 2/3 m r²")
  -- w along x, h along y, d along z: Ixx = m(h² + d²)/12
  local box = diag(m * (4 + 9) / 12, m * (1 + 9) / 12, m * (1 + 4) / 12)
  T.near(inertia.solid_box(m, 1, 2, 3), box, 1e-15, "box w, h, d")
  T.equal(inertia.solid_box(m, vec3(1, 2, 3)), inertia.solid_box(m, 1, 2, 3), "box from vec3")
  local t = m * (0.75 + 4) / 12
  T.near(inertia.solid_cylinder(m, 0.5, 2), diag(t, t, m * 0.25 / 2), 1e-15, "cylinder, axis z")
  T.near(inertia.hollow_cylinder(m, 0.5, 2), diag(m * (1.5 + 4) / 12, m * (1.5 + 4) / 12, m * 0.25),
    1e-15, "thin-walled tube, axis z")
  T.near(inertia.solid_ellipsoid(5, 1, 2, 3), diag(13, 10, 5), 1e-14, "ellipsoid semi-axes x, y, z")
  T.near(inertia.solid_cone(80, 1, 2), diag(3 * (4 + 4), 3 * (4 + 4), 24), 1e-13,
    "cone about its COM: (3/80) m (4r² + h²), (3/10) m r²")
  T.near(inertia.point(2, vec3(1, 2, 3)), mat3(26, -4, -6, -4, 20, -12, -6, -12, 10), 1e-15,
    "point: m((r·r)E − r⊗r)")
end)

T.case("a capsule is a cylinder plus two hemispheres", function()
  local r, h, rho = 0.5, 2, 3
  T.near(inertia.capsule(1, r, 0), inertia.solid_sphere(1, r), 1e-15, "h = 0 is a sphere")
  -- Independently: a hemisphere of radius r has its COM 3r/8 from the flat face and, about
  -- its own COM, transverse moment (2/5 − 9/64) m r² and axial (2/5) m r².
  local m_cyl, m_hemi = rho * math.pi * r * r * h, rho * 2 / 3 * math.pi * r ^ 3
  local hemi = diag((2 / 5 - 9 / 64) * m_hemi * r * r, (2 / 5 - 9 / 64) * m_hemi * r * r,
                    2 / 5 * m_hemi * r * r)
  local offset = h / 2 + 3 * r / 8
  local mass, com, I = inertia.composite{
    {mass = m_cyl, com = vec3(), inertia = inertia.solid_cylinder(m_cyl, r, h)},
    {mass = m_hemi, com = vec3(0, 0, offset), inertia = hemi},
    {mass = m_hemi, com = vec3(0, 0, -offset), inertia = hemi},
  }
  T.near(com, vec3(), 1e-15, "symmetric")
  T.near(inertia.capsule(mass, r, h), I, 1e-13, "capsule")
end)

T.case("points: mass, COM and tensor about the COM", function()
  local mass, com, I = inertia.points{{mass = 1, pos = vec3(0, 0, 0)},
                                      {mass = 3, pos = vec3(2, 0, 0)}}
  T.equal(mass, 4, "mass")
  T.near(com, vec3(1.5, 0, 0), 1e-15, "com")
  local mu = 1 * 3 / 4 * 2 * 2  -- reduced mass times length²
  T.near(I, diag(0, mu, mu), 1e-15, "dumbbell")
end)

T.case("parallel axis, rotation and moment about an axis", function()
  local m, L = 2, 3
  local along_x = quat.axis_angle(vec3(0, 1, 0), math.pi / 2)
  local rod = inertia.rotate(inertia.solid_cylinder(m, 1e-6, L), along_x)
  local at_end = inertia.parallel_axis(rod, m, vec3(L / 2, 0, 0))
  T.near(inertia.about_axis(at_end, vec3(0, 5, 0)), m * L * L / 3, 1e-11,
    "rod about its end, m L²/3")
  local box = inertia.solid_box(1, 1, 2, 3)
  local q = quat.axis_angle(vec3(1, 2, 3), 0.7)
  T.near(inertia.rotate(box, q), q:to_mat3() * box * q:to_mat3():transpose(), 1e-15, "R I Rᵀ")
  T.near(inertia.rotate(box, q), inertia.rotate(box, q:to_mat3()), 1e-15, "quat or mat3")
  local q2 = quat(2 * q.w, 2 * q.x, 2 * q.y, 2 * q.z)
  T.near(inertia.rotate(box, q2), inertia.rotate(box, q), 1e-15,
    "a quaternion is normalised")
  local n = vec3(1, 2, 2) / 3
  T.near(inertia.about_axis(box, vec3(1, 2, 2)), n:dot(box * n), 1e-15, "n normalised")
  -- Any scale of axis or quaternion, also where its squares overflow or underflow: box has
  -- moments (13, 10, 5)/12, so about (1, 1, 0) it is (13 + 10)/24, and a quarter turn about x
  -- swaps the y and z moments.
  for _, a in ipairs{1e300, 1e-320} do
    T.near(inertia.about_axis(box, vec3(a, a, 0)), 23 / 24, 1e-15, "huge or tiny axis " .. a)
    T.near(inertia.rotate(box, quat(a, a, 0, 0)), mat3.diag(13 / 12, 5 / 12, 10 / 12), 1e-15,
      "huge or tiny quaternion " .. a)
  end
end)

T.case("principal recovers a rotated diagonal", function()
  local R = quat.axis_angle(vec3(-1, 2, 0.5), 1.1):to_mat3()
  local values, axes = inertia.principal(R * diag(3, 1, 2) * R:transpose())
  T.near(values, vec3(1, 2, 3), 1e-14, "ascending moments")
  T.near(axes * diag(values.x, values.y, values.z) * axes:transpose(),
         R * diag(3, 1, 2) * R:transpose(), 1e-14, "I = V D Vᵀ")
  T.near(math.abs(axes:col(1):dot(R:col(2))), 1, 1e-14, "smallest moment's axis is R's 2nd column")
  T.near(axes:det(), 1, 1e-14, "right-handed")
end)

T.case("composite: two half boxes make the whole box", function()
  local half = inertia.solid_box(3, 1, 1, 0.5)
  local mass, com, I = inertia.composite{
    {mass = 3, com = vec3(4, 4.5, 6), inertia = half},
    {mass = 3, com = vec3(4, 5.5, 6), inertia = half},
  }
  T.equal(mass, 6, "mass")
  T.near(com, vec3(4, 5, 6), 1e-15, "com")
  T.near(I, inertia.solid_box(6, 1, 2, 0.5), 1e-14, "tensor")
end)

-- A box of size (w, h, d) centred at c, its faces counter-clockwise seen from outside.
local function box_mesh(w, h, d, c)
  local v = {}
  for k = 0, 7 do
    v[k + 1] = c + vec3((k % 2 == 1 and 0.5 or -0.5) * w, (k % 4 >= 2 and 0.5 or -0.5) * h,
                        (k >= 4 and 0.5 or -0.5) * d)
  end
  local faces = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5}, {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}}
  local triangles = {}
  for _, f in ipairs(faces) do
    triangles[#triangles + 1] = {f[1], f[2], f[3]}
    triangles[#triangles + 1] = {f[1], f[3], f[4]}
  end
  return v, triangles
end

T.case("mesh: a box mesh is the solid box", function()
  local vertices, triangles = box_mesh(1, 2, 3, vec3(5, -1, 2))
  local mass, com, I, volume = inertia.mesh(vertices, triangles, 2)
  T.near(volume, 6, 1e-13, "volume")
  T.near(mass, 12, 1e-13, "mass = density · volume")
  T.near(com, vec3(5, -1, 2), 1e-13, "com")
  T.near(I, inertia.solid_box(12, 1, 2, 3), 1e-12, "tensor about the COM")
  local m1 = inertia.mesh(vertices, triangles)
  T.near(m1, 6, 1e-13, "density defaults to 1")
  local float_indices = {}
  for i, t in ipairs(triangles) do float_indices[i] = {t[1] + 0.0, t[2] * 1.0, t[3] / 1} end
  T.equal(inertia.mesh(vertices, float_indices), m1, "2.0 is an index, as in luaL_checkinteger")
  T.fails(function() inertia.mesh(vertices, {{1, 2, 3.5}}) end,
    "bad argument #2 to 'inertia.mesh' (entry 1: vertex index 3 must be an integer, got 3.5)",
    "fractional index")
  T.fails(function() inertia.mesh(vertices, {{1, 2, "3"}}) end,
    "(entry 1: vertex index 3 must be an integer, got string)", "string index")
end)

T.case("inertia.check", function()
  T.equal(inertia.check(inertia.solid_box(1, 1, 2, 3)), true, "a box")
  local ok, message = inertia.check(diag(1, 1, 3))
  T.equal(ok, false, "1, 1, 3")
  T.equal(message, "principal moments 1, 1, 3 violate A + B >= C (1 + 1 < 3 by 1)", "message")
  ok, message = inertia.check(mat3(1, 0.5, 0, 0, 1, 0, 0, 0, 1))
  T.equal(ok, false, "asymmetric")
  assert(message:find("not symmetric", 1, true), message)
  ok, message = inertia.check(diag(0, 1, 1))
  assert(not ok and message:find("not all > 0", 1, true), "a rod is not a body")
  T.equal(inertia.check(diag(1, 2, 3)), true, "planar at equality")
end)

T.case("exact error messages", function()
  T.equal(error_of(inertia.solid_box, 1, -1, 1, 1),
    "bad argument #2 to 'inertia.solid_box' (width must be > 0, got -1)", "negative width")
  T.equal(error_of(inertia.solid_box, 1, vec3(1, 1, 0)),
    "bad argument #2 to 'inertia.solid_box' (depth (size.z) must be > 0, got 0)", "vec3 size")
  T.equal(error_of(inertia.solid_sphere, 0 / 0, 1),
    "bad argument #1 to 'inertia.solid_sphere' (mass must be finite, got nan)", "NaN")
  T.equal(error_of(inertia.hollow_sphere, 1, math.huge),
    "bad argument #2 to 'inertia.hollow_sphere' (radius must be finite, got inf)", "Inf")
  T.equal(error_of(inertia.solid_cylinder, 1, 1, "2"),
    "bad argument #3 to 'inertia.solid_cylinder' (number expected, got string)", "string")
  T.equal(error_of(inertia.capsule, 1, 1, -1),
    "bad argument #3 to 'inertia.capsule' (height must be >= 0, got -1)", "capsule height")
  T.equal(error_of(inertia.solid_cone, 1, 1, 1, 1),
    "bad argument #4 to 'inertia.solid_cone' (no more than 3 arguments expected, got 4)", "extra")
  T.equal(error_of(inertia.points, {{mass = 1, pos = vec3()}, {mass = 2, pos = vec3(1)},
                                    {mass = 0, pos = vec3()}}),
    "bad argument #1 to 'inertia.points' (entry 3: field 'mass' must be > 0, got 0)", "list entry")
  T.equal(error_of(inertia.points, {a = {mass = 1, pos = vec3()}}),
    "bad argument #1 to 'inertia.points' (list of {mass =, pos =}: unexpected key 'a' (the "
    .. "entries of a list are numbered 1, 2, ...; this one has none))", "only a named key")
  T.equal(error_of(inertia.about_axis, mat3.identity(), body{static = true}.inertia:row(1)),
    "bad argument #2 to 'inertia.about_axis' (the axis must be finite, got (inf, 0, 0))",
    "infinite axis")
  T.equal(error_of(inertia.points, {{mass = 1, position = vec3()}}),
    "bad argument #1 to 'inertia.points' (entry 1: unknown field 'position' (fields are: mass, "
    .. "pos))", "unknown field")
  T.equal(error_of(inertia.points, {{mass = 1}}),
    "bad argument #1 to 'inertia.points' (entry 1: field 'pos' is required)", "missing field")
  T.equal(error_of(inertia.parallel_axis, diag(1, 1, 3), 1, vec3()),
    "bad argument #1 to 'inertia.parallel_axis' (not a physical inertia tensor: principal "
    .. "moments 1, 1, 3 violate A + B >= C (1 + 1 < 3 by 1))", "impossible tensor")
  T.equal(error_of(inertia.rotate, diag(1, 1, 1), diag(1, 1, -1)),
    "bad argument #2 to 'inertia.rotate' (R must be a rotation: the matrix is a reflection, "
    .. "not a rotation (det = -1, want +1))", "reflection")
  T.equal(error_of(inertia.about_axis, diag(1, 1, 1), vec3()),
    "bad argument #2 to 'inertia.about_axis' (the axis must be a non-zero vector)", "zero axis")
  T.equal(error_of(inertia.mesh, {vec3(), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)},
                   {{1, 3, 2}, {1, 2, 4}, {1, 4, 3}, {2, 3, 5}}),
    "bad argument #2 to 'inertia.mesh' (entry 4: vertex index 5 is out of range (the vertices "
    .. "are 1 to 4))", "index range")
end)

T.case("every bad argument is refused naming function and argument", function()
  local I = diag(1, 1, 1)
  local cases = {
    {inertia.solid_sphere, {-1, 1}, "#1 to 'inertia.solid_sphere'"},
    {inertia.solid_sphere, {1}, "#2 to 'inertia.solid_sphere' (number expected, got no value)"},
    {inertia.solid_box, {1, 1, 2}, "#4 to 'inertia.solid_box'"},
    {inertia.solid_box, {1, vec3(1, 2, 3), 4}, "#3 to 'inertia.solid_box' (no more than 2"},
    {inertia.solid_ellipsoid, {1, 1, 1, 0},
      "#4 to 'inertia.solid_ellipsoid' (semi-axis c must be > 0"},
    {inertia.hollow_cylinder, {1, 0, 1}, "#2 to 'inertia.hollow_cylinder' (radius must be > 0"},
    {inertia.solid_cylinder, {1, 1, 0}, "#3 to 'inertia.solid_cylinder' (height must be > 0"},
    {inertia.point, {1, {1, 2, 3}}, "#2 to 'inertia.point' (vec3 expected, got table)"},
    {inertia.point, {0, vec3()}, "#1 to 'inertia.point' (mass must be > 0, got 0)"},
    {inertia.points, {}, "#1 to 'inertia.points' (list of {mass =, pos =} expected, got no value)"},
    {inertia.points, {{}}, "#1 to 'inertia.points' (list of {mass =, pos =}: the list is empty)"},
    {inertia.points, {{5}},
      "#1 to 'inertia.points' (entry 1 must be a table {mass =, pos =}, got number)"},
    {inertia.points, {{{mass = 1, pos = vec3()}, extra = 1}},
      "#1 to 'inertia.points' (list of {mass =, pos =}: unexpected key 'extra'"},
    {inertia.points, {{{mass = 1 / 0, pos = vec3()}}},
      "#1 to 'inertia.points' (entry 1: field 'mass' must be finite, got inf)"},
    {inertia.points, {{{mass = 1, pos = 3}}},
      "#1 to 'inertia.points' (entry 1: field 'pos' must be a vec3, got number)"},
    {inertia.composite, {{{mass = 1, com = vec3()}}},
      "#1 to 'inertia.composite' (entry 1: field 'inertia' is required)"},
    {inertia.composite, {{{mass = 1, com = vec3(), inertia = diag(-1, 1, 1)}}},
      "#1 to 'inertia.composite' (entry 1: field 'inertia' is not a physical inertia tensor: "
      .. "principal moments -1, 1, 1 are not all >= 0"},
    {inertia.parallel_axis, {I, -1, vec3()}, "#2 to 'inertia.parallel_axis' (mass must be > 0"},
    {inertia.parallel_axis, {I, 1, 2}, "#3 to 'inertia.parallel_axis' (vec3 expected, got number)"},
    {inertia.rotate, {I, 2 * mat3.identity()},
      "#2 to 'inertia.rotate' (R must be a rotation: the matrix is not orthonormal"},
    {inertia.rotate, {I, vec3()}, "#2 to 'inertia.rotate' (mat3 or quat expected, got vec3)"},
    {inertia.rotate, {mat3(1, 0.2, 0, 0, 1, 0, 0, 0, 1), mat3.identity()},
      "#1 to 'inertia.rotate' (not a physical inertia tensor: the tensor is not symmetric"},
    {inertia.about_axis, {I, vec3(1, 0, 0), 3}, "#3 to 'inertia.about_axis' (no more than 2"},
    {inertia.principal, {vec3()}, "#1 to 'inertia.principal' (mat3 expected, got vec3)"},
    {inertia.check, {5}, "#1 to 'inertia.check' (mat3 expected, got number)"},
    {inertia.mesh, {{vec3(), vec3(1)}, {{1, 2, 3}}},
      "#1 to 'inertia.mesh' (a closed mesh needs at least 4 vertices, got 2)"},
    {inertia.mesh, {{vec3(), 7}, {}}, "#1 to 'inertia.mesh' (entry 2 must be a vec3, got number)"},
    {inertia.mesh, {{vec3(), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)}, {{1, 2}}},
      "#2 to 'inertia.mesh' (entry 1 must be a table of 3 vertex indices {i, j, k}"},
    {inertia.mesh, {{vec3(), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)}, {{1, 3, 2}}, 0},
      "#3 to 'inertia.mesh' (density must be > 0, got 0)"},
    -- An overflowing result blames the size that made it too large: the largest one.
    {inertia.solid_box, {1, 1, 1e200, 1},
      "#3 to 'inertia.solid_box' (the result is not finite (an entry overflows the largest double"},
    {inertia.solid_ellipsoid, {1, 1, 1, 1e200}, "#4 to 'inertia.solid_ellipsoid' (the result is"},
    {inertia.parallel_axis, {I, 1, vec3(1e200, 0, 0)}, "#3 to 'inertia.parallel_axis' (the result"},
    {inertia.points, {{{mass = 1e308, pos = vec3()}, {mass = 1e308, pos = vec3()}}},
      "#1 to 'inertia.points' (the result is not finite (it overflows the largest double"},
  }
  for i, c in ipairs(cases) do
    T.fails(function() return c[1](table.unpack(c[2], 1, c[2].n or #c[2])) end,
      "bad argument " .. c[3], "case " .. i)
  end
end)

T.case("mesh refusals say what is wrong", function()
  local vertices, triangles = box_mesh(1, 1, 1, vec3())
  local open = {table.unpack(triangles, 2)}
  T.fails(function() inertia.mesh(vertices, open) end,
    "bad argument #2 to 'inertia.mesh' (the mesh is not closed: edge 1-4 belongs only to "
    .. "triangle 1", "open mesh")
  local flipped = {}
  for i, t in ipairs(triangles) do flipped[i] = {t[1], t[3], t[2]} end
  T.fails(function() inertia.mesh(vertices, flipped) end,
    "(the mesh is inside-out (signed volume -1 m³ is negative): its triangles are clockwise "
    .. "seen from outside; reverse the vertex order of every triangle)", "inside out")
  local one_flipped = {table.unpack(triangles)}
  one_flipped[3] = flipped[3]
  T.fails(function() inertia.mesh(vertices, one_flipped) end, "windings disagree", "winding")
  local repeated = {table.unpack(triangles)}
  repeated[2] = {1, 1, 4}
  T.fails(function() inertia.mesh(vertices, repeated) end,
    "(triangle 2 (1, 1, 4) is degenerate: it repeats a vertex)", "repeated vertex")
  -- Two separate tetrahedra, the smaller inside-out: not a cavity, so negative mass.
  local tet = {{1, 3, 2}, {1, 2, 4}, {1, 4, 3}, {2, 3, 4}}
  local two = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1),
               vec3(10, 0, 0), vec3(10.5, 0, 0), vec3(10, 0.5, 0), vec3(10, 0, 0.5)}
  local pieces = {table.unpack(tet)}
  for _, t in ipairs(tet) do pieces[#pieces + 1] = {t[1] + 4, t[3] + 4, t[2] + 4} end
  T.fails(function() inertia.mesh(two, pieces) end,
    "bad argument #2 to 'inertia.mesh' (piece 2 of the mesh's 2 separate closed surfaces (4 "
    .. "triangles, the first is triangle 5) is inside-out: its signed volume -0.02083333333 m³ "
    .. "is negative, and it does not lie inside another piece as a cavity would; reverse the "
    .. "vertex order of its triangles)", "inside-out piece")
  local huge, tiny = {}, {}
  for i = 1, 4 do huge[i], tiny[i] = two[i] * 1e200, two[i] * 1e-200 end
  T.fails(function() inertia.mesh(huge, tet) end,
    "(the mesh is too large to integrate: it spans 1e+200 m, and its second moments (of order "
    .. "span⁵) would overflow; express it in larger units (it must span at most 1e+60 m))", "huge")
  T.fails(function() inertia.mesh(tiny, tet) end,
    "(the mesh is too small to integrate: it spans 1e-200 m", "tiny")
end)

T.case("mesh: a cavity (an inside-out surface inside the solid) is subtracted", function()
  -- A 2 m cube with a 1 m cubic hole: mass 8 − 1, tensor of the big box minus the small one.
  local vertices, triangles = box_mesh(2, 2, 2, vec3(1, 2, 3))
  local inner_vertices, inner_triangles = box_mesh(1, 1, 1, vec3(1, 2, 3))
  for _, v in ipairs(inner_vertices) do vertices[#vertices + 1] = v end
  for _, t in ipairs(inner_triangles) do triangles[#triangles + 1] = {t[1] + 8, t[3] + 8, t[2] + 8} end
  local mass, com, I = inertia.mesh(vertices, triangles)
  T.near(mass, 7, 1e-13, "mass")
  T.near(com, vec3(1, 2, 3), 1e-13, "com")
  T.near(I, inertia.solid_box(8, 2, 2, 2) - inertia.solid_box(1, 1, 1, 1), 1e-13, "tensor")
end)

T.case("every function is documented for help()", function()
  local real_print, text = print, nil
  for name, fn in pairs(inertia) do
    print = function(s) text = s end
    local ok, err = pcall(help, fn)
    print = real_print
    assert(ok, err)
    assert(text:find("inertia." .. name, 1, true), name .. " signature in help")
  end
end)

T.finish()
