-- A lesson from outside lessons/ (so sandboxed: no debug) that keeps its ctx in a table whose
-- __gc uses it after the lesson has ended, when the state is closed (issue 12 item 1). The
-- table is made before the ctx, so the ctx is finalised first; before the fix that freed the
-- list of failures (one is recorded here on purpose) and the check in __gc freed it again:
-- "free(): double free". Now the ctx is an error there, which a finaliser only warns about:
-- nothing is checked or printed after the lesson's summary.
local keep = setmetatable({}, {__gc = function(t)
  for i = 1, 3 do t.ctx:expect("after the end", 1, 2) end
end})
return lesson{id = "fixture-ctx-after-end", title = "Keeps its ctx", source = "tests",
  steps = {{title = "Keep", text = "Keeps ctx past the lesson; one check fails on purpose.",
            run = function(ctx)
              keep.ctx = ctx
              ctx:expect("one", 1, 1)
              ctx:expect("fails on purpose", 1, 2)
            end}}}
