-- A lesson whose first step runs one w:step of hours (10000 substeps, 1000 solver sweeps over
-- 100 boxes): Ctrl-C while it runs stops the step, the error is shown and the lesson goes on.
return lesson{
  id = "fixture-long-step", title = "A step of hours", source = "tests",
  steps = {
    {title = "Long", text = "One huge step.", run = function(ctx)
      local w = world{iterations = 1000}
      w:add_plane{normal = vec3(0, 1, 0), offset = 0}
      for i = 0, 99 do
        w:add(body.box{mass = 1, size = vec3(1, 1, 1), position = vec3(i % 10 * 1.01, 0.5 + i // 10, 0)})
      end
      w.substeps = 10000
      print("stepping")
      w:step(0.01)
    end},
    {title = "After", text = "Still here.", run = function(ctx) ctx:expect("after", 2, 2) end},
  },
}
