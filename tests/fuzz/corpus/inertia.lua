 local I = inertia.solid_box(2, 1, 2, 3)
local values, axes = inertia.principal(inertia.rotate(I, quat.axis_angle(vec3(1, 2, 3), 0.7)))
local m, com, Ic = inertia.points{{mass = 1, pos = vec3(1, 0, 0)}, {mass = 2, pos = vec3(0, 1, 0)}}
local M, C, J = inertia.composite{{mass = 1, com = vec3(), inertia = inertia.solid_sphere(1, 1)}, {mass = 2, com = vec3(1, 0, 0), inertia = inertia.solid_cylinder(2, 0.5, 1)}}
local v = {vec3(), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)}
local mass, c, Imesh, vol = inertia.mesh(v, {{1, 3, 2}, {1, 2, 4}, {1, 4, 3}, {2, 3, 4}}, 2)
local x = inertia.about_axis(I, vec3(1, 1, 1)) + inertia.parallel_axis(I, 2, vec3(1, 0, 0)):trace()
local ok, why = inertia.check(mat3.diag(1, 1, 3))
local h = inertia.hollow_sphere(1, 2) + inertia.hollow_cylinder(1, 1, 2) + inertia.solid_ellipsoid(1, 1, 2, 3) + inertia.capsule(1, 0.5, 1) + inertia.solid_cone(1, 1, 2) + inertia.point(1, vec3(1, 2, 3))
