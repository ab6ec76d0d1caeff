-- lesson{...} validates a lesson table and names what is wrong.
local T = dofile("testing.lua")

local function step() return {title = "t", text = "x", run = function() end} end

T.case("a valid lesson is returned as it is", function()
  local l = {id = "a-1", title = "A", source = "000 x", steps = {step()}}
  T.equal(lesson(l), l, "same table")
end)

T.case("errors", function()
  T.fails(function() lesson(5) end, "bad argument #1 to 'lesson' (table expected, got number)",
    "not a table")
  T.fails(function() lesson{title = "A", source = "s", steps = {step()}} end,
    "bad argument #1 to 'lesson' (field 'id' must be a non-empty string, got nil)", "no id")
  T.fails(function() lesson{id = "Bad Id", title = "A", source = "s", steps = {step()}} end,
    "field 'id' may hold only a-z, 0-9 and '-', got 'Bad Id'", "id characters")
  T.fails(function() lesson{id = "a", title = "A", source = "s", steps = {}} end,
    "field 'steps' must be a non-empty list of steps", "no steps")
  T.fails(function() lesson{id = "a", title = "A", source = "s", steps = {step(), 5}} end,
    "steps[2] must be a table, got number", "step not a table")
  T.fails(function()
    lesson{id = "a", title = "A", source = "s", steps = {{title = "t", text = "x", run = 1}}}
  end, "steps[1]: field 'run' must be a function, got number", "run not a function")
  T.fails(function()
    lesson{id = "a", title = "A", source = "s", steps = {{title = "t", txt = "x"}}}
  end, "steps[1]: unknown field 'txt'", "misspelt field")
  T.fails(function() lesson{id = "a", title = "A", source = "s", steps = {step()}, extra = 1} end,
    "unknown field 'extra'", "unknown lesson field")
end)

T.finish()
