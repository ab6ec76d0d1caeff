 local a, b = vec3(1, 2, 3), vec3(-1, 0.5, 2)
local m = a:outer(b) + a:skew() * 2 - mat3.diag(1, 2, 3) / 4
local n = mat3{{2, 1, 0}, {1, 3, 0}, {0, 0, 4}}
local vals, axes = n:eigen()
local q = quat.axis_angle(a, 1) * quat(1, 0.1, 0.2, 0.3):normalized()
local r = q:rotate(b) + q:to_mat3() * b + n:inverse() * a + m:transpose():row(1) + m:col(2)
local axis, angle = q:axis_angle()
local x = a:dot(b) + a:cross(b):norm() + m:det() + m:get(1, 2) + q:norm() + q:dot(q:conj()) + q:inverse().w
local s = tostring(a) .. tostring(m) .. tostring(q) .. a .. m .. q
local w = quat.from_mat3(q:to_mat3()) == q and -a == a * -1 and mat3.skew(a) * b == a:cross(b)
a.x = 5 q.w = 2 local p = {a:unpack()} local z = {m:unpack()} local u = {q:unpack()}
