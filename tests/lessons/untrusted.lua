-- A lesson from outside lessons/: it runs in the sandbox, so io and os.execute are gone.
return lesson{
  id = "fixture-untrusted", title = "Runs sandboxed", source = "tests",
  steps = {{title = "No io", text = "The sandbox removed io.", run = function(ctx)
    ctx:expect("io is gone", io == nil and 1 or 0, 1)
    ctx:expect("os.execute is gone", os.execute == nil and 1 or 0, 1)
  end}},
}
