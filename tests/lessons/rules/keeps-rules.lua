-- Keeps both rules (tests/lessons/lesson_rules_test.lua): the size is in the text, each step
-- makes its own box.
local function box() return body.box{mass = 2, size = vec3(0.5, 0.15, 1)} end
return lesson{id = "keeps-rules", title = "A box shown in full", source = "tests", steps = {
  {title = "Spin", text = "A box of 2 kg, 0.5 × 0.15 × 1 m.", run = function(ctx)
    ctx:show("mass (kg)", box().mass)
  end},
  {title = "Again", text = "The same box.", run = function(ctx)
    ctx:show("mass (kg)", box().mass)
  end}}}
