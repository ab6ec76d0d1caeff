-- Bad input across the whole API: every case must raise a Lua error whose first line names the
-- function and the argument in one of the agreed forms (bad_input/harness.lua), the interpreter
-- must survive, and every object the case could touch must be unchanged, bit for bit, in its
-- fields and in how its world moves afterwards. The cases are in bad_input/cases_*.lua.
local T = dofile("testing.lua")
local H = dofile("bad_input/harness.lua")

-- KNOWN_FAILURES: cases whose error is not yet in the agreed form because the binding that
-- raises it belongs to another area. They still must raise an error and leave every object
-- unchanged; only the form is excused. Remove an entry when its binding is fixed (the test
-- says which entries pass now). Key: the case's code; value: the file to fix.
local KNOWN_FAILURES = {
}

local cases = {}
for _, file in ipairs({"math", "bodies", "world", "tools", "metatables"}) do
  for _, c in ipairs(dofile("bad_input/cases_" .. file .. ".lua")) do cases[#cases + 1] = c end
end

print(string.format("%d known failures (errors not yet in the agreed form):", #(function()
  local list = {}
  for code in pairs(KNOWN_FAILURES) do list[#list + 1] = code end
  return list
end)()))
local seen, known_listed = {}, {}
for _, c in ipairs(cases) do
  if seen[c[1]] then error("case listed twice: " .. c[1]) end
  seen[c[1]] = true
end
for code, where in pairs(KNOWN_FAILURES) do
  if not seen[code] then error("KNOWN_FAILURES names a case that does not exist: " .. code) end
end

local shared_before = H.shared_tables()
for i, c in ipairs(cases) do
  local code, want = c[1], c[2]
  local known = KNOWN_FAILURES[code]
  T.case(string.format("case %d: %s", i, code), function()
    local problem = H.run(code, want, known)
    if H.shared_tables() ~= shared_before then
      problem = (problem or "") .. "\n  a shared table or metatable was left changed"
      shared_before = H.shared_tables()
    end
    if problem then error(problem, 0) end
  end)
end

for _, c in ipairs(cases) do
  local where = KNOWN_FAILURES[c[1]]
  if where and H.known_messages[c[1]] then
    print(string.format("  known failure (%s): %s\n      says: %s\n      want: %s", where, c[1],
      H.known_messages[c[1]], c[2]))
  end
end
for _, code in ipairs(H.fixed) do
  print("  now in the agreed form, remove from KNOWN_FAILURES: " .. code)
end
-- The checks themselves must be able to fail: each of these mistakes must be caught.
local raise = " error(\"bad argument #1 to 'f' (x)\", 0)"
for _, c in ipairs({
  {"return 1", "no error raised"},
  {"error('something else', 0)", "error was"},
  {"error(\"bad argument #2 to 'f' (x)\", 0)", "error was"},
  {"b.position = vec3(9, 9, 9)" .. raise, "the objects changed"},
  {"w.substeps = 3" .. raise, "the objects changed"},
  {"w:add_plane{}" .. raise, "the objects changed"},
  {"b:apply_force(vec3(1, 0, 0))" .. raise, "hidden state changed"},
  {"w:add_spring{a = b, anchor = v, k = 1}" .. raise, "the objects changed"},
  {"w:add_drag{body = bx, linear = 5}" .. raise, "hidden state changed"},
  {"w:add_force(function() end)" .. raise, nil},  -- a callback that does nothing is invisible
}) do
  T.case("the checks catch: " .. c[1], function()
    local problem = H.run(c[1], "bad argument #1 to 'f' (x)")
    if c[2] == nil then return end
    if not (problem and problem:find(c[2], 1, true)) then
      error("expected the problem '" .. c[2] .. "', got: " .. tostring(problem))
    end
  end)
end

print(string.format("%d bad-input cases", #cases))
T.finish()
