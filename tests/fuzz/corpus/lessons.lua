 -- Lessons as `rigidlab check` runs them (the harness runs the lessons a program returns):
-- steps and their tables with metatables, a tolerance with one, a ctx kept past its lesson by a
-- finaliser, every ctx method with good and bad values.
local W = world{}
W:add(body.sphere{mass = 1, radius = 0.5})
local steps = setmetatable({
  {title = "show", text = "values", run = function(ctx)
    ctx:show("n", 1.5) ctx:show("v", vec3(1, 2, 3)) ctx:show("m", mat3.identity())
    ctx:show("q", quat()) ctx:show("t", {1, 2, x = {y = 3}})
    ctx:say("a line") ctx:table({"a", "b"}, {{1, 2}, {3, 4}})
    ctx:plot{{x = {0, 1, 2}, y = {0, 1, 4}, label = "sq"}, title = "t"}
  end},
  setmetatable({title = "checks", text = "pass and fail"}, {__index = function(_, k)
    W:add(body.sphere{mass = 1, radius = 0.5})
    if k == "run" then return function(ctx) end end
  end}),
  {title = "expect", text = "every kind", run = function(ctx)
    ctx:expect("num", 1, 1) ctx:expect("tol", 1.001, 1, 1e-2) ctx:expect("abs", 1, 1.1, {abs = 0.2})
    ctx:expect("inf", math.huge, math.huge) ctx:expect("str", "a", "b") ctx:expect("nil", nil, nil)
    ctx:expect("tab", {1, a = {2}}, {1, a = {3}}) ctx:expect("vec", vec3(1, 2, 3), vec3(1, 2, 3))
    ctx:expect_range("r", 2, 1, 3) ctx:expect_range("low", 2, nil, 1)
    K = ctx
    setmetatable({}, {__gc = function() pcall(K.expect, K, "late", 1, 1) pcall(K.say, K, "late") end})
    pcall(ctx.expect, ctx, "bad", 1, 1, "x")
    pcall(ctx.expect, ctx, setmetatable({}, {__tostring = function() error("ts") end}), 1, 1)
  end},
}, {__len = function() return 2^31 - 1 end, __index = function() W:remove(W:bodies()[1]) end})
return {
  lesson{id = "fuzz-a", title = "A", source = "s", steps = steps},
  lesson{id = "fuzz-b", title = "B", source = "s", steps = {{title = "x", text = "y",
    run = function(ctx) collectgarbage() pcall(K.expect, K, "from b", 1, 1) end}},
    tolerance = setmetatable({rel = 1e-3, reason = "r"}, {__index = function() collectgarbage() end})},
}
