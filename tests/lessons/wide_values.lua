-- Values too wide for one line, for tests/cli/lesson_display_test.sh: a lesson fits what it
-- shows into the terminal's width.
local M = mat3(1/3, 2/3, -1/7, 2/3, 5/3, 1e-17, -1/7, 1e-17, 4/9)
return lesson{
  id = "fixture-wide", title = "Wide values", source = "tests",
  steps = {
    {title = "Matrices and lists", text = "Long values.", run = function(ctx)
       ctx:show("a matrix", M)
       ctx:show("a long list", {1/3, 2/3, 1/7, 2/7, 3/7, 4/7, 5/7, 6/7, 1/9, 2/9, 4/9, 5/9})
       ctx:show("minus zero", vec3(-0.0, 1, -0.0))
       ctx:expect("the matrix against itself, a check too long for one line", M, M)
       ctx:expect("a short check", 2, 2)
       ctx:say("A sentence long enough that it has to be wrapped onto a second line when the " ..
               "terminal is eighty columns wide, and every line keeps the indentation.")
     end},
  },
}
