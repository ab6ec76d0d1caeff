-- A lesson with a wrong expectation: `rigidlab check` must print "0 passed, 1 failed", exit 1.
return lesson{
  id = "fixture-wrong", title = "A lesson with a wrong value", source = "tests",
  steps = {
    {title = "Wrong", text = "The document says 5.",
     run = function(ctx) ctx:expect("two and two", 2 + 2, 5) end},
  },
}
