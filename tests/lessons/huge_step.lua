-- One w:step of hours (10000 substeps, 1000 solver sweeps, 400 boxes): the engine polls the
-- time limit inside the step, so the checker stops it there with the lesson's own message.
return lesson{
  id = "fixture-huge-step", title = "Steps for hours", source = "tests",
  steps = {{title = "Step", text = "One step.", run = function(ctx)
    local w = world{substeps = 10000, iterations = 1000}
    w:add_plane{normal = vec3(0, 1, 0), offset = 0}
    for i = 0, 399 do
      w:add(body.box{mass = 1, size = vec3(1, 1, 1), position = vec3(i % 20 * 1.01, 0.5 + i // 20, 0)})
    end
    w:step(0.01)
    ctx:expect("stepped", 1, 1)
  end}},
}
