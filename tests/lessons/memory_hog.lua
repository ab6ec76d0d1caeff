-- A lesson that allocates without bound: the checker must stop it at the memory limit.
return lesson{
  id = "fixture-memory-hog", title = "Allocates forever", source = "tests",
  steps = {{title = "Grow", text = "More and more.", run = function(ctx)
    local t = {}
    for i = 1, math.huge do t[i] = {i, i, i, i} end
  end}},
}
