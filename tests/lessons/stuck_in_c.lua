-- A lesson stuck in a C function that never returns to Lua (string.find backtracking over 40
-- stars): no hook runs, so the checker's parent process must stop it at the deadline.
return lesson{
  id = "fixture-stuck-in-c", title = "Backtracks for years", source = "tests",
  steps = {{title = "Find", text = "Never returns.", run = function(ctx)
    string.find(string.rep("a", 40) .. "b", string.rep("a*", 40) .. "c")
    ctx:expect("returned", 1, 1)
  end}},
}
