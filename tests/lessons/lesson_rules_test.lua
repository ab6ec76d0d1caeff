-- Two rules every lesson of lessons/ keeps (issue 17 item 5; docs/writing-lessons.md "Rules"),
-- checked by running each lesson with a recording ctx (run by lua_test_runner):
--
-- 1. Lessons show their setup: every body a step makes, and every shape whose inertia it
--    computes, has its mass, its size and its initial state (position, velocity, angular
--    velocity, orientation: what differs from rest at the origin) shown to the student by the
--    end of that step — in a title, text or formula of the lesson up to that step, or in what
--    ctx showed, said, tabulated or checked up to there. A number counts as shown when the
--    visible text holds it to 3 significant digits (0.3333 shows 1/3; signs are not compared,
--    texts write −). The constructors are wrapped to record what they were given: body{...},
--    body.box{...}, body.sphere{...} and the shape functions of inertia.
-- 2. Steps stand on their own: each step shows and checks the same values when it runs alone
--    (a fresh load of the lesson) as after the steps before it. `b`, `r` and `--from` rely on
--    it.
local T = dofile("testing.lua")
local here = arg[0]:match("^(.*)/[^/]*$") or "."
local lessons_dir = here .. "/../../lessons"

local function lesson_ids()
  local ids = {}
  local list = assert(io.popen('ls "' .. lessons_dir .. '"'))
  for name in list:lines() do
    local id = name:match("^(.+)%.lua$")
    if id then ids[#ids + 1] = id end
  end
  list:close()
  return ids
end

-- ---- what a student sees ---------------------------------------------------------------------

local function describe(value, depth)
  depth = depth or 0
  if type(value) == "number" then return string.format("%.10g", value) end
  if type(value) == "table" then
    if depth > 3 then return "{...}" end
    local parts = {}
    for k, v in pairs(value) do parts[#parts + 1] = tostring(k) .. "=" .. describe(v, depth + 1) end
    table.sort(parts)
    return "{" .. table.concat(parts, ", ") .. "}"
  end
  return tostring(value)
end

-- A ctx that keeps what it shows: text for rule 1, a log of the values for rule 2.
local function recording_ctx()
  local ctx = {text = {}, log = {}}
  local function keep(...)
    for i = 1, select("#", ...) do
      local s = describe((select(i, ...)))
      ctx.text[#ctx.text + 1] = s
      ctx.log[#ctx.log + 1] = s
    end
  end
  function ctx:show(label, value) keep(label, value) end
  function ctx:say(text) keep(text) end
  function ctx:table(columns, rows) keep(columns, rows) end
  function ctx:expect(label, got, want) keep(label, got, want) return true end
  function ctx:expect_range(label, got, low, high) keep(label, got, low, high) return true end
  function ctx:plot(spec) keep(spec.title or "", spec.x_label or "", spec.y_label or "") end
  function ctx:motion(object, options)  -- steps as ctx:motion does (lua/render_motion.cpp)
    options = options or {}
    local frames, seconds, dt = options.frames or 4, options.seconds or 2, options.dt or 1 / 60
    local per_frame = math.max(1, math.floor(seconds / math.max(frames - 1, 1) / dt + 0.5))
    for _ = 2, frames do object:step(dt, per_frame) end
  end
  return ctx
end

-- The numbers in a text: 12, 0.5, 1e-3, .25, ½ ¼ ¾ ⅓, and lengths in cm, mm or µm as metres.
local fractions = {["½"] = 0.5, ["¼"] = 0.25, ["¾"] = 0.75, ["⅓"] = 1 / 3, ["⅔"] = 2 / 3}
local function numbers_in(text, into)
  for token in text:gmatch("%d*%.?%d+[eE][-+]?%d+") do into[#into + 1] = tonumber(token) end
  for token in text:gmatch("%d*%.?%d+") do into[#into + 1] = tonumber(token) end
  for token in text:gmatch("(%d*%.?%d+) ?cm%f[%A]") do into[#into + 1] = tonumber(token) / 100 end
  for token in text:gmatch("(%d*%.?%d+) ?mm%f[%A]") do into[#into + 1] = tonumber(token) / 1000 end
  for token in text:gmatch("(%d*%.?%d+) ?µm") do into[#into + 1] = tonumber(token) * 1e-6 end
  for glyph, value in pairs(fractions) do
    if text:find(glyph, 1, true) then into[#into + 1] = value end
  end
end

local function shown(value, numbers)
  local v = math.abs(value)
  for _, n in ipairs(numbers) do
    if math.abs(n - v) <= 5e-4 * math.max(v, 1e-300) then return true end
  end
  return false
end

-- ---- what a step uses --------------------------------------------------------------------------

-- The quantities a constructor was given, each a list of numbers to show: "mass", "size", ...
local function quantities(options, into)
  if type(options) ~= "table" then return end
  local function add(what, ...)
    for i = 1, select("#", ...) do
      local x = select(i, ...)
      if type(x) == "number" and x ~= 0 and x == x and math.abs(x) ~= math.huge then
        into[#into + 1] = {what = what, value = x}
      end
    end
  end
  local function add_vec3(what, v)
    if type(v) == "userdata" and tostring(getmetatable(v)) == "vec3" then add(what, v.x, v.y, v.z) end
  end
  add("mass", options.mass)
  add("radius", options.radius)
  add("height", options.height)
  add("length", options.length)
  add_vec3("size", options.size)
  add_vec3("position", options.position)
  add_vec3("velocity", options.velocity)
  add_vec3("angular velocity", options.angular_velocity)
  local q = options.orientation
  if type(q) == "userdata" and tostring(getmetatable(q)) == "quat" and math.abs(q.w) < 1 - 1e-12 then
    local angle = 2 * math.acos(math.min(1, math.abs(q.w)))
    into[#into + 1] = {what = "orientation (angle)", value = angle, also = math.deg(angle)}
  end
end

local shape_functions = {"solid_box", "solid_sphere", "solid_cylinder", "hollow_sphere",
                         "hollow_cylinder", "solid_ellipsoid", "solid_cone", "capsule"}

-- An environment for a lesson file in which the constructors record into `uses`.
local function instrumented_env(uses)
  local function recorder(constructor, describe_args)
    return function(...)
      describe_args(uses, ...)
      return constructor(...)
    end
  end
  local body_proxy = setmetatable({
    box = recorder(body.box, function(u, o) quantities(o, u) end),
    sphere = recorder(body.sphere, function(u, o) quantities(o, u) end),
  }, {
    __index = body,
    __call = function(_, o) quantities(o, uses) return body(o) end,
  })
  local inertia_proxy = setmetatable({}, {__index = inertia})
  for _, name in ipairs(shape_functions) do
    inertia_proxy[name] = recorder(inertia[name], function(u, ...)
      for i = 1, select("#", ...) do
        local x = select(i, ...)
        if type(x) == "number" and x ~= 0 then u[#u + 1] = {what = "inertia." .. name .. " argument", value = x} end
      end
    end)
  end
  return setmetatable({body = body_proxy, inertia = inertia_proxy, print = function() end},
                      {__index = _G})
end

local function load_lesson(path, uses)
  local chunk = assert(loadfile(path, "t", instrumented_env(uses)))
  return chunk()
end

-- ---- the rules ---------------------------------------------------------------------------------

-- Checks the lesson of the file `path`; raises an error that names `id` and each rule broken.
local function check_lesson(id, path)
  local uses = {}
  local lesson = load_lesson(path, uses)
  local visible = {lesson.title}
  local sequential_logs = {}
  local problems = {}
  for k, step in ipairs(lesson.steps) do
    visible[#visible + 1] = step.title
    visible[#visible + 1] = step.text
    visible[#visible + 1] = step.formula or ""
    local ctx = recording_ctx()
    local first_use = #uses + 1
    if step.run then step.run(ctx) end
    for _, s in ipairs(ctx.text) do visible[#visible + 1] = s end
    sequential_logs[k] = table.concat(ctx.log, "\n")
    local numbers = {}
    numbers_in(table.concat(visible, "\n"), numbers)
    for i = first_use, #uses do
      local u = uses[i]
      if not (shown(u.value, numbers) or (u.also and shown(u.also, numbers))) then
        problems[#problems + 1] = string.format("step %d uses a %s of %.10g that the lesson never shows",
                                                k, u.what, u.value)
        break
      end
    end
  end
  for k in ipairs(lesson.steps) do
    local alone = load_lesson(path, {})
    local ctx = recording_ctx()
    if alone.steps[k].run then alone.steps[k].run(ctx) end
    if table.concat(ctx.log, "\n") ~= sequential_logs[k] then
      problems[#problems + 1] = string.format("step %d shows other values alone than after the steps before it", k)
    end
  end
  if #problems > 0 then error(id .. ": " .. table.concat(problems, "; "), 0) end
end

for _, id in ipairs(lesson_ids()) do
  if not os.getenv("LESSON") or os.getenv("LESSON") == id then  -- LESSON=id: only that one
    T.case("lesson " .. id, function() check_lesson(id, lessons_dir .. "/" .. id .. ".lua") end)
  end
end

-- The rules themselves catch what they are for, on lessons of tests/lessons/rules/: one that
-- never gives its box's size, one whose second step depends on the first, and one that keeps
-- both rules.
local function rule_problems(id)
  local ok, message = pcall(check_lesson, id, here .. "/rules/" .. id .. ".lua")
  return ok and "" or message
end
T.case("the setup rule catches a size never shown", function()
  T.equal(rule_problems("hidden-size"), "hidden-size: step 1 uses a size of 0.5 that the lesson never shows")
end)
T.case("the standing-alone rule catches a step that depends on the one before", function()
  T.equal(rule_problems("dependent-steps"),
          "dependent-steps: step 2 shows other values alone than after the steps before it")
end)
T.case("a lesson that keeps both rules passes", function()
  T.equal(rule_problems("keeps-rules"), "")
end)

T.finish()
