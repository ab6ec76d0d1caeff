 -- 2000 overlapping spheres: the contacts of one step pass the memory limit (engine memory
-- counts against it, as under rigidlab --max-memory), and the step is undone.
local w = world{}
for i = 1, 2000 do w:add(body.sphere{mass = 1, radius = 1, position = vec3(i * 1e-3, 0, 0)}) end
w:step(1/60)
