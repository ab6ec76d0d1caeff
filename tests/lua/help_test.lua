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

T.case("an unknown plain name points to the members and fields of that name", function()
  T.fails(function() help("hinge") end,
    "bad argument #1 to 'help' (no topic 'hinge' (did you mean 'joint.hinge'? help() lists " ..
    "the topics))", "a joint type")
  T.fails(function() help("gravity") end, "did you mean 'articulation.gravity', 'world.gravity'?",
    "a field of two types")
  T.fails(function() help("solid_box") end, "did you mean 'inertia.solid_box'?", "a function")
  for _, name in ipairs({"joint.hinge", "articulation.gravity", "world.gravity",
                         "inertia.solid_box"}) do
    assert(#captured(name) > 0, name .. " has help")  -- every suggestion is a working topic
  end
end)

T.case("names with a NUL byte are refused, not truncated (issue 12 item 12)", function()
  T.fails(function() help("vec3\0junk") end,
    "bad argument #1 to 'help' (the topic name must not contain a NUL byte ('\\0' at byte 5 of " ..
    "9; C reads the name only up to it))", "help('vec3\\0junk') used to show vec3")
  T.fails(function() help("\0") end, "must not contain a NUL byte ('\\0' at byte 1 of 1;",
    "a lone NUL")
end)

T.case("types list their fields from the property table, and each field has help", function()
  local text = captured("world")
  assert(text:find("Fields (read/write unless marked):\n  time (read-only): s", 1, true), text)
  assert(text:find("  substeps: ", 1, true), "substeps listed")
  assert(text:find("  speculative_distance: m (0.02)", 1, true), "contact settings listed")
  assert(text:find("Methods:\n  w:add(b) -> b", 1, true), "methods after the fields")
  for line in text:gmatch("[^\n]+") do
    assert(utf8.len(line) <= 94, "a line of help(\"world\") is too long: " .. line)
  end
  T.equal(captured("world.gravity"), "world.gravity\n  vec3, m/s², default vec3(0, -9.81, 0)",
    "a property by name")
  T.equal(captured("body.mass"), "body.mass (read-only)\n  kg (math.huge: static)\n  " ..
    "Read-only: mass properties and shape are fixed when the body is made.", "a read-only one")
  T.fails(function() help("world.gravityy") end, "no topic 'world.gravityy'", "unknown field")
end)

T.case("a static body takes no inertia, and help says so (issue 12 item 22)", function()
  local text = captured("body")
  assert(text:find("mass = math.huge makes an immovable body, which takes no inertia", 1, true),
    text)
end)

T.finish()
