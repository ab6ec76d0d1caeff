-- A file whose top level runs a backtracking string.find that would take hours: a C function,
-- so only the watchdog of the time limit stops it. Loading is under the limits too.
string.find(string.rep("a", 3000), string.rep(".-", 12) .. "b")
return lesson{id = "fixture-backtracking", title = "Never loads", source = "tests",
  steps = {{title = "Unreached", text = "x", run = function(ctx) ctx:expect("x", 1, 1) end}}}
