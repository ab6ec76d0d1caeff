-- Breaks the standing-alone rule (tests/lessons/lesson_rules_test.lua): step 2 shows a value
-- that step 1 left in an upvalue, so alone (--from 2, b, r) it shows another.
local count = 0
return lesson{id = "dependent-steps", title = "Steps that lean on each other", source = "tests",
  steps = {
    {title = "First", text = "Counts.", run = function(ctx)
      count = count + 1
      ctx:show("count", count)
    end},
    {title = "Second", text = "Counts on.", run = function(ctx)
      count = count + 1
      ctx:show("count", count)
    end}}}
