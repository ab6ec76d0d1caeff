-- help() finds the documentation by value and by name, and refuses unknown topics clearly.
local T = dofile("testing.lua")

local function captured(...)
  local lines = {}
  local real_print = print
  print = function(s) lines[#lines + 1] = s end
  local ok, err = pcall(help, ...)
  print = real_print
  if not ok then error(err, 2) end
  return table.concat(lines, "\n")
end

T.case("by value and by name give the same text", function()
  T.equal(captured(vec3.cross), captured("vec3:cross"), "vec3.cross")
  T.equal(captured(mat3), captured("mat3"), "mat3 topic")
  T.equal(captured(quat(1, 0, 0, 0)), captured("quat"), "a value shows its type's help")
end)

T.case("texts carry signatures", function()
  assert(captured("vec3:cross"):find("a:cross(b) -> vec3", 1, true), "signature")
  assert(captured(mat3):find("M:eigen() -> values, axes", 1, true), "methods listed")
  local overview = captured()
  for _, topic in ipairs({"vec3", "mat3", "quat", "help"}) do
    assert(overview:find(" " .. topic, 1, true), "topic " .. topic .. " listed")
  end
end)

T.case("every documented name of a type has a signature", function()
  for _, name in ipairs({"vec3", "mat3", "quat"}) do
    for key, value in pairs(_G[name]) do
      if type(value) == "function" then
        assert(#captured(value) > 0, name .. "." .. key .. " has help")
      end
    end
  end
end)

T.case("unknown topics", function()
  T.fails(function() help("nope") end,
    "bad argument #1 to 'help' (no topic 'nope' (help() lists the topics))", "unknown name")
  T.fails(function() help(42) end,
    "bad argument #1 to 'help' (no help for a number value (help() lists the topics))", "a number")
  T.fails(function() help(io.stdout) end, "bad argument #1 to 'help' (no help for a FILE* value",
    "a userdata of another library")
end)

T.finish()
