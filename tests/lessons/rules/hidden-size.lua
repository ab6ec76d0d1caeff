-- Breaks the setup rule (tests/lessons/lesson_rules_test.lua): the box's mass is shown, its
-- size never is.
return lesson{id = "hidden-size", title = "A box of unknown size", source = "tests", steps = {
  {title = "Spin", text = "A box of 2 kg spins.", run = function(ctx)
    local b = body.box{mass = 2, size = vec3(0.5, 0.15, 1)}
    ctx:show("mass (kg)", b.mass)
  end}}}
