-- ode.step against closed forms: the Taylor polynomials of e^h, exact quadratures, a rotation,
-- the harmonic oscillator as a table state; plus the errors a learner meets.
local T = dofile("testing.lua")

local grow = function(_, y) return y end

T.case("one step of y' = y is the Taylor polynomial of e^h", function()
  -- An order-p Runge-Kutta step on a linear autonomous equation multiplies y by the degree-p
  -- Taylor polynomial of e^h (Butcher 2016, 23).
  for _, h in ipairs{0.5, 0.1, 1e-3} do
    local taylor2 = 1 + h + h ^ 2 / 2
    local taylor4 = taylor2 + h ^ 3 / 6 + h ^ 4 / 24
    T.near(ode.step("rk4", grow, 0, 1, h), taylor4, 1e-15, "rk4 h = " .. h)
    T.near(ode.step("euler", grow, 0, 1, h), 1 + h, 1e-15, "euler h = " .. h)
    T.near(ode.step("midpoint", grow, 0, 1, h), taylor2, 1e-15, "midpoint h = " .. h)
    T.near(ode.step("heun", grow, 0, 1, h), taylor2, 1e-15, "heun h = " .. h)
    T.near(ode.step("rk4", grow, 0, 3, h), 3 * taylor4, 1e-14, "linear in y0")
  end
end)

T.case("time enters the stages: exact quadratures", function()
  local t, h = 0.7, 0.3
  -- y' = 2t: midpoint and trapezoid are exact; y' = 4t³: Simpson's rule (RK4) is exact.
  local linear = function(s) return 2 * s end
  T.near(ode.step("midpoint", linear, t, 5, h), 5 + (t + h) ^ 2 - t ^ 2, 1e-15, "midpoint")
  T.near(ode.step("heun", linear, t, 5, h), 5 + (t + h) ^ 2 - t ^ 2, 1e-15, "heun")
  T.near(ode.step("rk4", function(s) return 4 * s ^ 3 end, t, 0, h), (t + h) ^ 4 - t ^ 4, 1e-15,
    "rk4")
end)

T.case("vec3 state: rotation about z", function()
  -- y' = ω × y with ω = 1.5 ẑ: in the xy plane u = x + iy obeys u' = iωu, so each RK4 step
  -- multiplies u by T4(iωh) = (1 − θ²/2 + θ⁴/24) + i(θ − θ³/6), θ = ωh; z is constant.
  local omega, h = vec3(0, 0, 1.5), 0.01
  local theta = 1.5 * h
  local re, im = 1 - theta ^ 2 / 2 + theta ^ 4 / 24, theta - theta ^ 3 / 6
  local y, u_re, u_im = vec3(1, 0, 0.5), 1, 0
  for n = 0, 99 do
    y = ode.step("rk4", function(_, p) return omega:cross(p) end, n * h, y, h)
    u_re, u_im = u_re * re - u_im * im, u_re * im + u_im * re
  end
  T.near(y, vec3(u_re, u_im, 0.5), 1e-13, "RK4 amplification factor")
  T.near(y, vec3(math.cos(1.5), math.sin(1.5), 0.5), 1e-9, "close to the exact rotation")
  local c = vec3(1, -2, 3)
  for _, method in ipairs{"euler", "midpoint", "heun", "rk4"} do
    T.near(ode.step(method, function() return c end, 0, vec3(1, 1, 1), 0.5),
      vec3(1.5, 0, 2.5), 1e-15, method .. " constant slope")
  end
end)

T.case("table state: the harmonic oscillator as y = {x, v}", function()
  -- x'' = −4x. w = 2x + iv obeys w' = −2i w, so each RK4 step multiplies w by T4(−2ih) =
  -- (1 − θ²/2 + θ⁴/24) − i(θ − θ³/6), θ = 2h; the exact solution is x = cos 2t.
  local f = function(_, y) return {y[2], -4 * y[1]} end
  local y0 = {1, 0}
  local y, h = y0, 0.01
  local theta = 2 * h
  local re, im = 1 - theta ^ 2 / 2 + theta ^ 4 / 24, -(theta - theta ^ 3 / 6)
  local w_re, w_im = 2, 0
  for n = 0, 99 do
    y = ode.step("rk4", f, n * h, y, h)
    w_re, w_im = w_re * re - w_im * im, w_re * im + w_im * re
  end
  T.near(y[1], w_re / 2, 1e-13, "x(1), RK4 amplification factor")
  T.near(y[2], w_im, 1e-13, "v(1), RK4 amplification factor")
  T.near(y[1], math.cos(2), 1e-8, "x(1) close to cos 2")
  T.equal(#y, 2, "same length")
  T.equal(y0[1] == 1 and y0[2] == 0, true, "the input table is not modified")
  local seen
  ode.step("euler", function(_, s) seen = s; s[1] = 42; return {0, 0} end, 0, y0, 0.1)
  T.equal(seen ~= y0 and y0[1] == 1, true, "f gets a copy of y")
end)

T.case("errors name the function and the argument", function()
  local function fails(text, ...)
    local args = table.pack(...)
    T.fails(function() return ode.step(table.unpack(args, 1, args.n)) end, text, text)
  end
  fails("bad argument #1 to 'ode.step' (method must be one of 'euler', 'midpoint', 'heun', " ..
    "'rk4', got 'semi_implicit')", "semi_implicit", grow, 0, 1, 0.1)
  fails("bad argument #1 to 'ode.step' (method must be one of 'euler', 'midpoint', 'heun', " ..
    "'rk4', got nil)", nil, grow, 0, 1, 0.1)
  fails("bad argument #2 to 'ode.step' (function expected, got number)", "rk4", 5, 0, 1, 0.1)
  fails("bad argument #3 to 'ode.step' (t must be finite, got inf)", "rk4", grow, math.huge, 1, 0.1)
  fails("bad argument #4 to 'ode.step' (number, vec3 or table of numbers expected, got string)",
    "rk4", grow, 0, "1", 0.1)
  fails("bad argument #4 to 'ode.step' (y must be finite, got nan)", "rk4", grow, 0, 0 / 0, 0.1)
  fails("bad argument #4 to 'ode.step' (y must be a number, a vec3 or a non-empty list of " ..
    "numbers)", "rk4", grow, 0, {}, 0.1)
  fails("bad argument #4 to 'ode.step' (y[2] must be a number, got boolean)", "rk4", grow, 0,
    {1, true}, 0.1)
  fails("bad argument #4 to 'ode.step' (y[1] must be finite, got -inf)", "rk4", grow, 0,
    {-math.huge}, 0.1)
  -- A named key would be neither integrated nor shown to f: refused, not ignored.
  fails("bad argument #4 to 'ode.step' (y (a list of numbers): unexpected key 'x' (entries must " ..
    "be numbered 1 to 1))", "rk4", grow, 0, {1, x = 5}, 0.1)
  fails("bad argument #4 to 'ode.step' (y (a list of numbers): unexpected key 'x' (the entries " ..
    "of a list are numbered 1, 2, ...; this one has none))", "rk4", grow, 0, {x = 5}, 0.1)
  fails("bad argument #5 to 'ode.step' (dt must be > 0, got -0.1)", "rk4", grow, 0, 1, -0.1)
  fails("bad argument #5 to 'ode.step' (number expected, got no value)", "rk4", grow, 0, 1)
  fails("bad argument #6 to 'ode.step' (no more than 5 arguments expected, got 6)", "rk4", grow,
    0, 1, 0.1, 1)
end)

T.case("a wrong derivative says what came and when", function()
  local function fails(text, f, y)
    T.fails(function() return ode.step("rk4", f, 0, y, 0.1) end, text, text)
  end
  fails("bad argument #2 to 'ode.step' (f returned nil at t = 0, expected number)",
    function() end, 1)
  fails("bad argument #2 to 'ode.step' (f returned number at t = 0.05, expected vec3)",
    function(t) if t > 0 then return 1 end return vec3() end, vec3())
  fails("bad argument #2 to 'ode.step' (f returned nan at t = 0.1, expected a finite number)",
    function(t) if t > 0.07 then return 0 / 0 end return 0 end, 1)
  fails("bad argument #2 to 'ode.step' (f returned a table of 1 value at t = 0, expected a " ..
    "table of 2 numbers)", function() return {1} end, {1, 2})
  fails("bad argument #2 to 'ode.step' (f returned a table with a string at index 2 at t = 0, " ..
    "expected a table of 2 finite numbers)", function() return {1, "2"} end, {1, 2})
  fails("bad argument #2 to 'ode.step' (f returned a table with inf at index 1 at t = 0, " ..
    "expected a table of 2 finite numbers)", function() return {math.huge, 2} end, {1, 2})
  fails("bad argument #2 to 'ode.step' (f returned number at t = 0, expected a table of 2 " ..
    "numbers)", function() return 1 end, {1, 2})
  -- y + 0.1 y' = 1.7e308 + 1e307 is past the largest double (1.797e308): a true overflow
  fails("'ode.step': the new y is not finite (overflow): try a smaller dt",
    function() return 1e308 end, 1.7e308)
  local ok, message = pcall(ode.step, "euler", function() error("inside f") end, 0, 1, 0.1)
  T.equal(ok, false, "error inside f")
  assert(message:find("inside f", 1, true), "keeps its message: " .. message)
end)

T.finish()
