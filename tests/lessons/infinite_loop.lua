-- A lesson that never ends: the checker must stop it within seconds and say which limit.
return lesson{
  id = "fixture-infinite-loop", title = "Loops forever", source = "tests",
  steps = {{title = "Loop", text = "Forever.", run = function(ctx) while true do end end}},
}
