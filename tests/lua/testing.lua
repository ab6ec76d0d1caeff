-- Assertion helpers for the Lua test scripts (tests/lua/*_test.lua).
-- Usage:  local T = dofile("testing.lua")   (the tests run with tests/lua as working directory)
--   T.case("name", function() ... end)   runs a case; failures are collected, not fatal
--   T.near(got, want, tol, what)         numbers, vec3, mat3 or quat, |got - want| <= tol
--   T.equal(got, want, what)             exact ==
--   T.fails(fn, pattern_or_text, what)   fn must raise an error whose message contains the text
--   T.finish()                           raises if any case failed, prints the counts
local T = {}
local passed, failed, failures = 0, 0, {}

local function components(x)
  local kind = type(x) == "userdata" and tostring(getmetatable(x)) or type(x)
  if kind == "number" then return {x} end
  if kind == "vec3" then return {x.x, x.y, x.z} end
  if kind == "quat" then return {x.w, x.x, x.y, x.z} end
  if kind == "mat3" then return {x:unpack()} end
  error("cannot compare a " .. kind, 3)
end

function T.near(got, want, tol, what)
  local g, w = components(got), components(want)
  assert(#g == #w, (what or "value") .. ": different kinds")
  for i = 1, #g do
    if not (math.abs(g[i] - w[i]) <= tol) then
      error(string.format("%s: got %s, want %s (tolerance %g, component %d off by %g)",
        what or "value", tostring(got), tostring(want), tol, i, math.abs(g[i] - w[i])), 2)
    end
  end
end

function T.equal(got, want, what)
  if got ~= want then
    error(string.format("%s: got %s, want %s", what or "value", tostring(got), tostring(want)), 2)
  end
end

-- `expected` is plain text (not a pattern) that the error message must contain.
function T.fails(fn, expected, what)
  local ok, message = pcall(fn)
  if ok then error((what or "call") .. ": expected an error containing '" .. expected .. "'", 2) end
  message = tostring(message)
  if not message:find(expected, 1, true) then
    error(string.format("%s: error was\n  %s\nexpected it to contain\n  %s", what or "call",
      message, expected), 2)
  end
end

function T.case(name, fn)
  local ok, message = xpcall(fn, debug.traceback)
  if ok then
    passed = passed + 1
  else
    failed = failed + 1
    failures[#failures + 1] = name .. ": " .. tostring(message)
  end
end

function T.finish()
  for _, f in ipairs(failures) do io.stderr:write("FAILED ", f, "\n") end
  print(string.format("%d passed, %d failed", passed, failed))
  if failed > 0 then error(failed .. " case(s) failed", 0) end
end

-- A deterministic pseudo-random generator, so failures reproduce.
function T.random(seed)
  local state = seed or 12345
  return function(lo, hi)
    state = (state * 1103515245 + 12345) % 2147483648
    return lo + (hi - lo) * state / 2147483648
  end
end

return T
