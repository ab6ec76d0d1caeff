-- Five steps of about 400000 VM instructions each (a counted loop): each alone is well under
-- any limit used with it, together they are not. The limits of `rigidlab lesson FILE` count
-- the whole lesson, never restarting per step (issue 12 item 7).
local function busy()
  local x = 0
  for i = 1, 200000 do x = x + i end
  return x
end
local steps = {}
for i = 1, 5 do
  steps[i] = {title = "Busy " .. i, text = "A loop.", run = function(ctx)
    ctx:expect("sum " .. i, busy(), 20000100000)
  end}
end
return lesson{id = "fixture-slow-steps", title = "Five busy steps", source = "tests", steps = steps}
