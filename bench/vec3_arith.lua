-- vec3 arithmetic from Lua against the same arithmetic on plain Lua tables, side by side in one
-- interpreter. The workload is a particle update and the products a physics script uses:
--   v = v + g*dt; p = p + v*dt; d = p:dot(v); c = p:cross(v)
-- Baselines: (1) tables with Lua functions, (2) tables with a Lua metatable (same syntax as
-- vec3). Prints the time of each and vec3's ratio to the faster baseline (goal: <= 0.75).
local N = tonumber(arg and arg[1]) or 1000000

local function timed(fn)
  local best = math.huge
  for _ = 1, 5 do
    collectgarbage("collect")
    local t0 = os.clock()
    fn()
    best = math.min(best, os.clock() - t0)
  end
  return best
end

local function run_vec3()
  local p, v, g, dt = vec3(0, 0, 0), vec3(1, 2, 3), vec3(0, -9.81, 0), 0.001
  local d = 0
  for _ = 1, N do
    v = v + g * dt
    p = p + v * dt
    d = d + p:dot(v)
    local c = p:cross(v)
  end
  return d
end

local function add(a, b) return {x = a.x + b.x, y = a.y + b.y, z = a.z + b.z} end
local function scale(a, s) return {x = a.x * s, y = a.y * s, z = a.z * s} end
local function dot(a, b) return a.x * b.x + a.y * b.y + a.z * b.z end
local function cross(a, b)
  return {x = a.y * b.z - a.z * b.y, y = a.z * b.x - a.x * b.z, z = a.x * b.y - a.y * b.x}
end

local function run_functions()
  local p, v, g, dt = {x = 0, y = 0, z = 0}, {x = 1, y = 2, z = 3}, {x = 0, y = -9.81, z = 0}, 0.001
  local d = 0
  for _ = 1, N do
    v = add(v, scale(g, dt))
    p = add(p, scale(v, dt))
    d = d + dot(p, v)
    local c = cross(p, v)
  end
  return d
end

local V = {}
V.__index = V
local function new(x, y, z) return setmetatable({x = x, y = y, z = z}, V) end
V.__add = function(a, b) return new(a.x + b.x, a.y + b.y, a.z + b.z) end
V.__mul = function(a, s) return new(a.x * s, a.y * s, a.z * s) end
V.dot = dot
V.cross = function(a, b) return new(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x) end

local function run_metatable()
  local p, v, g, dt = new(0, 0, 0), new(1, 2, 3), new(0, -9.81, 0), 0.001
  local d = 0
  for _ = 1, N do
    v = v + g * dt
    p = p + v * dt
    d = d + p:dot(v)
    local c = p:cross(v)
  end
  return d
end

-- The three must compute the same thing, or the comparison means nothing.
local a, b, c = run_vec3(), run_functions(), run_metatable()
assert(math.abs(a - b) <= 1e-9 * math.abs(b) and math.abs(a - c) <= 1e-9 * math.abs(c),
  "the variants disagree")

local t_vec3, t_functions, t_metatable = timed(run_vec3), timed(run_functions), timed(run_metatable)
local baseline = math.min(t_functions, t_metatable)
print(string.format("vec3 arithmetic, %d iterations (best of 5)", N))
print(string.format("  plain tables, Lua functions : %.3f s", t_functions))
print(string.format("  plain tables, Lua metatable : %.3f s", t_metatable))
print(string.format("  rigidlab vec3               : %.3f s", t_vec3))
print(string.format("  ratio vec3 / faster baseline: %.2f  (goal <= 0.75)", t_vec3 / baseline))
