-- A lesson whose one step draws a film strip (ctx:motion): the fixture of
-- motion_strip_test.sh and of view_test.sh (the key v).
return lesson{
  id = "spin", title = "A box spins", source = "the test",
  steps = {{
    title = "Watch it",
    text = "A box of 1 kg, 0.5 x 0.15 x 1 m, at rest at the origin, spins at (4, 0.05, 0.05) rad/s.",
    run = function(ctx)
      local w = world{gravity = vec3(0, 0, 0)}
      w:add(body.box{mass = 1, size = vec3(0.5, 0.15, 1), angular_velocity = vec3(4, 0.05, 0.05)})
      ctx:motion(w, {seconds = 1.5, frames = 4, show = {"omega", "L"}})
      ctx:expect("the world is at the last frame's time", w.time, 1.5, 1e-12)
    end,
  }},
}
