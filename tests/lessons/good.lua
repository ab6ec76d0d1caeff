-- A lesson whose expectations hold: the checker must report it as passed.
return lesson{
  id = "fixture-good", title = "A lesson that passes", source = "tests",
  steps = {
    {title = "Arithmetic", text = "Two and two.", formula = "2 + 2 = 4",
     run = function(ctx)
       ctx:show("sum", 2 + 2)
       ctx:expect("sum", 2 + 2, 4)
       ctx:expect("cross", vec3(1, 0, 0):cross(vec3(0, 1, 0)), vec3(0, 0, 1))
     end},
    {title = "A table", text = "Squares.",
     run = function(ctx)
       ctx:table({"n", "n²"}, {{1, 1}, {2, 4}, {3, 9}})
       ctx:expect("sqrt 2", math.sqrt(2), 1.41421356, {abs = 1e-8})
     end},
  },
}
