-- The machinery of tests/lua/bad_input_test.lua: the objects every case may touch, a bit-exact
-- snapshot of everything observable about them, and the check of one case.
--
-- The agreed forms of the first line of an error (after Lua's "case:LINE: " position):
--   bad argument #N to 'FUNC' (REASON)    an argument of a function, method or operator
--                                         ('inertia.solid_box', 'body:apply_force', 'vec3.__add')
--   calling 'FUNC' on bad self (REASON)   the object a method was called on (v:normalized())
--   bad field 'NAME' of TYPE (REASON)     b.position = 5, b.mass = 1, return v.w: an assignment
--                                         to (or a read of) a field that refuses it
-- A case's expected text must start with one of these forms; the error's first line must start
-- with the expected text (so it names the function and the argument, and the reason's start).
local H = {}

-- Captured before any case runs, so a case cannot reach them through the environment.
local format, concat, pcall, type, rawequal, pairs, ipairs, tostring, load, setmetatable =
  string.format, table.concat, pcall, type, rawequal, pairs, ipairs, tostring, load, setmetatable
local vec3_unpack, mat3_unpack, quat_unpack = vec3.unpack, mat3.unpack, quat.unpack
local getmt, setmt = debug.getmetatable, debug.setmetatable
local body_index = getmt(body{static = true}).__index  -- reads a body whatever its metatable
local world_index = getmt(world{}).__index

H.forms = {
  "^bad argument #%d+ to '[%w_.:]+' %(.",
  "^calling '[%w_.:]+' on bad self %(.",
  "^bad field '[%w_]+' of [%w_]+ %(.",
}

function H.is_agreed_form(text)
  for _, pattern in ipairs(H.forms) do
    if text:find(pattern) then return true end
  end
  return false
end

-- The objects of one case. Deterministic: two calls give identical objects (the twin check).
-- w holds b (sphere), bx (box), s (static box floor), a plane, a spring, drag and a force
-- callback, with non-default settings, and has taken one step (so it has contacts); f is a
-- body in no world.
function H.fresh()
  local e = setmetatable({}, {__index = _G})
  e.v = vec3(1, 2, 3)
  e.m = mat3(2, 0, 0, 0, 3, 0, 0, 0, 4)
  e.q = quat.axis_angle(vec3(0, 0, 1), 0.5)
  e.b = body.sphere{mass = 2, radius = 0.5, position = vec3(0, 0.499, 0), velocity = vec3(1, 0, 0),
                    angular_velocity = vec3(0, 0, 0.5), restitution = 0.4, friction = 0.3}
  e.bx = body.box{mass = 3, size = vec3(1, 2, 3), position = vec3(3, 2, 0),
                  orientation = quat.axis_angle(vec3(1, 1, 0), 0.3)}
  e.s = body.box{static = true, size = vec3(8, 0.2, 8), position = vec3(0, -0.1, 0)}
  e.f = body{mass = 1, inertia = mat3.diag(1, 2, 2.5), velocity = vec3(0, 1, 0)}
  e.w = world{gravity = vec3(0, -9.8, 0.1), substeps = 2, iterations = 12,
              restitution_threshold = 0.3}
  e.w:add(e.b)
  e.w:add(e.bx)
  e.w:add(e.s)
  e.w:add_plane{normal = vec3(0, 1, 0), offset = -1, restitution = 0.2, friction = 0.5}
  e.w:add_spring{a = e.bx, anchor = vec3(3, 4, 0), k = 20, damping = 0.5, rest_length = 1}
  e.w:add_drag{body = e.b, linear = 0.1}
  local bx = e.bx
  e.w:add_force(function() bx:apply_force(vec3(0.1, 0, 0)) end)
  e.w:step(0.01)
  -- For cases that break a shared metatable: sets mt[key] = value (raw) for the call of fn,
  -- then restores it, and re-raises fn's error.
  e.with_field = function(mt, key, value, fn)
    local old = rawget(mt, key)
    rawset(mt, key, value)
    local ok, message = pcall(fn)
    rawset(mt, key, old)
    if not ok then error(message, 0) end
  end
  return e
end

-- ---- snapshots ------------------------------------------------------------------------------

local function number(x) return format("%a", x) end

-- Any value, bit-exact, without using its metatable (a case may have replaced it).
local function encode(x, names)
  local kind = type(x)
  if kind == "number" then return number(x) end
  if kind ~= "userdata" then return kind .. ":" .. tostring(x) end
  for name, value in pairs(names or {}) do
    if rawequal(x, value) then return "<" .. name .. ">" end
  end
  for _, unpack in ipairs({vec3_unpack, quat_unpack, mat3_unpack}) do
    local packed = {pcall(unpack, x)}
    if packed[1] then
      for i = 2, #packed do packed[i] = number(packed[i]) end
      packed[1] = "("
      return concat(packed, " ") .. ")"
    end
  end
  return "userdata?"
end

local body_fields = {"position", "orientation", "velocity", "angular_velocity", "mass", "inv_mass",
                     "inertia", "inv_inertia", "static", "shape", "radius", "size", "restitution",
                     "friction"}
local world_fields = {"time", "gravity", "integrator", "gyroscopic", "substeps", "iterations",
                      "restitution_threshold"}
local world_totals = {"kinetic_energy", "potential_energy", "energy", "linear_momentum",
                      "angular_momentum"}

local function body_state(b, out)
  for _, f in ipairs(body_fields) do out[#out + 1] = f .. "=" .. encode(body_index(b, f)) end
end

local function list_state(list, names, out, label)
  out[#out + 1] = label .. "#" .. #list
  for i, item in ipairs(list) do
    if type(item) == "table" then
      local keys = {}
      for k in pairs(item) do keys[#keys + 1] = k end
      table.sort(keys)
      for _, k in ipairs(keys) do out[#out + 1] = format("%s%d.%s=%s", label, i, k, encode(item[k], names)) end
    else
      out[#out + 1] = format("%s%d=%s", label, i, encode(item, names))
    end
  end
end

local function world_state(w, names, out)
  for _, f in ipairs(world_fields) do out[#out + 1] = f .. "=" .. encode(world_index(w, f)) end
  for _, f in ipairs(world_totals) do out[#out + 1] = f .. "=" .. encode(world_index(w, f)(w)) end
  list_state(world_index(w, "bodies")(w), names, out, "body")
  list_state(world_index(w, "planes")(w), names, out, "plane")
  list_state(world_index(w, "contacts")(w), names, out, "contact")
end

-- Everything observable about the objects of `e`, as text (numbers bit-exact).
function H.snapshot(e)
  local names = {b = e.b, bx = e.bx, s = e.s, f = e.f}
  local out = {"v=" .. encode(e.v), "m=" .. encode(e.m), "q=" .. encode(e.q)}
  for _, name in ipairs({"b", "bx", "s", "f"}) do
    out[#out + 1] = name .. ":"
    body_state(e[name], out)
  end
  out[#out + 1] = "w:"
  world_state(e.w, names, out)
  return concat(out, " ")
end

-- The first few fields in which two snapshots differ, as lines "  name: before -> after".
function H.difference(a, b)
  local function fields(text)
    local list, owner = {}, ""
    for token in text:gmatch("%S+") do
      if token:sub(-1) == ":" then owner = token else list[#list + 1] = owner .. token end
    end
    return list
  end
  local x, y, out = fields(a), fields(b), {}
  for i = 1, math.max(#x, #y) do
    if x[i] ~= y[i] and #out < 4 then out[#out + 1] = "\n    " .. tostring(x[i]) .. " -> " .. tostring(y[i]) end
  end
  return concat(out)
end

-- State not visible in fields (accumulated forces, springs, drag, force callbacks, contact
-- caches) shows in how the world moves: the snapshot after three more steps.
function H.stepped_snapshot(e)
  local ok, message = pcall(function() for _ = 1, 3 do world_index(e.w, "step")(e.w, 0.01) end end)
  return (ok and "" or "step failed: " .. tostring(message) .. " ") .. H.snapshot(e)
end

-- The identity and contents of the shared tables and metatables, to prove a case left them
-- as it found them (a case may break a metatable only through e.with_field).
function H.shared_tables()
  local e = H.fresh()
  local out = {}
  local function add(label, t)
    if type(t) ~= "table" then out[#out + 1] = label .. "=" .. tostring(t) return end
    local keys = {}
    for k, value in pairs(t) do keys[#keys + 1] = tostring(k) .. "=" .. tostring(value) end
    table.sort(keys)
    out[#out + 1] = label .. "{" .. concat(keys, ",") .. "}"
  end
  for _, name in ipairs({"vec3", "mat3", "quat", "body", "world", "inertia", "collide", "motion",
                         "ode", "plot", "csv", "help", "lesson", "print", "string"}) do
    add(name, _G[name])
    if type(_G[name]) == "table" then add(name .. " mt", getmt(_G[name])) end
  end
  for _, name in ipairs({"v", "m", "q", "b", "w"}) do add(name .. " values' mt", getmt(e[name])) end
  return concat(out, "\n")
end

-- Runs one case. Returns nil when it passed, or a description of what went wrong. For a known
-- failure only the form is excused: the error, the survival and the unchanged state are not.
function H.run(code, want, known)
  if not H.is_agreed_form(want) then
    return "the expected text is not in an agreed form: " .. want
  end
  local e, twin = H.fresh(), H.fresh()
  local own_metatables = {}
  for name, value in pairs(e) do own_metatables[name] = getmt(value) end
  local before = H.snapshot(e)
  if before ~= H.snapshot(twin) then return "the fresh objects are not deterministic" end
  local chunk, load_error = load(code, "=case", "t", e)
  if not chunk then return "does not compile: " .. load_error end
  local ok, message = pcall(chunk)
  if ok then return "no error raised; expected: " .. want end
  local first_line = tostring(message):match("^[^\n]*"):gsub("^case:%d+: ", "")
  local problems = {}
  if first_line:sub(1, #want) ~= want then
    if not known then
      problems[#problems + 1] = "error was\n    " .. first_line .. "\n  expected it to start with\n    " .. want
    end
  elseif known then
    H.fixed[#H.fixed + 1] = code
  end
  if known then H.known_messages[code] = first_line end
  local after = H.snapshot(e)
  if after ~= before then
    problems[#problems + 1] = "the objects changed:" .. H.difference(before, after)
  elseif H.stepped_snapshot(e) ~= H.stepped_snapshot(twin) then
    problems[#problems + 1] = "hidden state changed: the world moves differently after the case"
  end
  -- A case that gave an object another metatable through the debug library: its own is put
  -- back, so that its finaliser runs. (A world or body left with a metatable that has not its
  -- __gc is never destroyed; the debug library is beyond what rigidlab can guard.)
  for name, mt in pairs(own_metatables) do
    if not rawequal(getmt(e[name]), mt) then setmt(e[name], mt) end
  end
  if #problems > 0 then return concat(problems, "\n  ") end
  return nil
end

H.fixed = {}           -- known failures that now pass
H.known_messages = {}  -- what the known failures say today

return H
