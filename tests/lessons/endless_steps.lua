-- A steps table that claims 2^31-1 steps through __len and makes each one up in __index: the
-- runners read steps raw, so it is no list of steps (issue 12 item 7: it ran forever).
local steps = setmetatable({}, {
  __len = function() return 2^31 - 1 end,
  __index = function(_, i)
    return {title = "Step " .. i, text = "x", run = function(ctx) ctx:expect("x", 1, 1) end}
  end})
return {id = "fixture-endless", title = "Endless steps", source = "tests", steps = steps}
