-- Three short steps, for the tests that step through a lesson in a terminal (Enter, b, q).
return lesson{
  id = "fixture-steps", title = "Three short steps", source = "tests",
  steps = {
    {title = "First", text = "One.", run = function(ctx) ctx:expect("one", 1, 1) end},
    {title = "Second", text = "Two.", run = function(ctx) ctx:expect("two", 1 + 1, 2) end},
    {title = "Third", text = "Three.", run = function(ctx) ctx:expect("three", 1 + 2, 3) end},
  },
}
