-- Errors that are not strings, for tests/lessons/checker_test.sh: a lesson shows what lua.c
-- would (the __tostring of the object, else its type), never a bare "error".
return lesson{
  id = "fixture-error-objects", title = "Error objects", source = "tests",
  steps = {
    {title = "A table", text = "error({}).", run = function() error({}) end},
    {title = "With __tostring", text = "An object that describes itself.", run = function()
       error(setmetatable({}, {__tostring = function() return "a described failure" end}))
     end},
  },
}
