-- motion.simulate against closed forms: the car of 003_* "Explicit Euler", the projectile of
-- the same document, polynomial motions, and the convergence order on the harmonic
-- oscillator; plus the errors a learner meets.
local T = dofile("testing.lua")

local function car(method)
  return motion.simulate{method = method, accel = function() return 10 end, x0 = 0, v0 = 0,
                         dt = 1, steps = 10}
end

T.case("the car of document 003: 450 / 550 / 500 m after 10 s", function()
  -- 003 "Explicit Euler": a = 10 m/s², dt = 1 s; analytic ½at² = 500 m. The document's table
  -- (v first) gives 550 m; x from the old v gives Σ 10n for n < 10 = 450 m; RK4 is exact.
  T.near(car("euler").x[11], 450, 1e-12, "euler")
  T.near(car("semi_implicit").x[11], 550, 1e-12, "semi_implicit")
  T.near(car("rk4").x[11], 500, 1e-12, "rk4")
  local r = car("semi_implicit")
  local table_rows = {0, 10, 30, 60, 100, 150, 210, 280, 360, 450, 550}
  T.equal(#r.t, 11, "steps + 1 times"); T.equal(#r.x, 11, "positions"); T.equal(#r.v, 11, "velocities")
  for i = 1, 11 do
    T.near(r.x[i], table_rows[i], 1e-12, "document row " .. i)
    T.near(r.v[i], 10 * (i - 1), 1e-12, "v row " .. i)
    T.near(r.t[i], i - 1, 0, "t row " .. i)
  end
end)

T.case("default method is semi_implicit; v0 defaults to zero", function()
  local r = motion.simulate{accel = function() return 10 end, x0 = 0, dt = 1, steps = 10}
  T.near(r.x[11], 550, 1e-12, "default")
  local s = motion.simulate{accel = function() return vec3(0, 10, 0) end, x0 = vec3(), dt = 1,
                            steps = 10}
  T.near(s.v[1], vec3(), 0, "v0 defaults to the zero vec3")
  T.near(s.x[11], vec3(0, 550, 0), 1e-12, "vec3 car")
end)

T.case("projectile: rk4 reproduces y = ½gt² + v0 t + y0 at every step", function()
  -- 003 "Explicit Euler", analytic part, g = −9.8 m/s².
  local g, x0, v0 = vec3(0, -9.8, 0), vec3(1, 20, -2), vec3(3, 15, 0.5)
  local r = motion.simulate{method = "rk4", accel = function() return g end, x0 = x0, v0 = v0,
                            dt = 0.05, steps = 60}
  for i, t in ipairs(r.t) do
    T.near(r.x[i], g * (0.5 * t * t) + v0 * t + x0, 1e-12, "x at t = " .. t)
    T.near(r.v[i], g * t + v0, 1e-12, "v at t = " .. t)
  end
end)

T.case("accel sees t, x and v; t0 shifts the clock", function()
  -- x'' = t from rest at t0 = 1: x = (t³ − 1)/6 − (t − 1)/2, exact for RK4 (Simpson's rule).
  local r = motion.simulate{method = "rk4", accel = function(t) return t end, x0 = 0, v0 = 0,
                            t0 = 1, dt = 0.25, steps = 8}
  T.near(r.t[9], 3, 1e-15, "final time")
  T.near(r.x[9], (27 - 1) / 6 - 1, 1e-13, "x(3)")
  T.near(r.v[9], (9 - 1) / 2, 1e-13, "v(3)")
  -- x'' = −x' (linear drag): v = v0 e^{−t}, x = v0 (1 − e^{−t}).
  local d = motion.simulate{method = "rk4", accel = function(_, _, v) return -v end, x0 = 0,
                            v0 = 2, dt = 0.01, steps = 100}
  T.near(d.v[101], 2 * math.exp(-1), 1e-10, "drag v")
  T.near(d.x[101], 2 * (1 - math.exp(-1)), 1e-10, "drag x")
end)

-- Error of (x, v) at T = 2 s for x'' = −9x, x(0) = 1: x = cos 3t, v = −3 sin 3t.
local function oscillator_error(method, dt)
  local steps = math.floor(2 / dt + 0.5)
  local r = motion.simulate{method = method, accel = function(_, x) return -9 * x end, x0 = 1,
                            v0 = 0, dt = dt, steps = steps}
  local ex, ev = r.x[steps + 1] - math.cos(6), r.v[steps + 1] + 3 * math.sin(6)
  return math.sqrt(ex * ex + ev * ev)
end

T.case("convergence orders on the harmonic oscillator: 1, 1, 4", function()
  for _, c in ipairs{{"euler", 1e-3, 1}, {"semi_implicit", 1e-3, 1}, {"rk4", 2e-2, 4}} do
    local method, dt, order = c[1], c[2], c[3]
    local measured = math.log(oscillator_error(method, dt) / oscillator_error(method, dt / 2), 2)
    T.near(measured, order, 0.1, method .. " order")
  end
end)

T.case("the states handed to accel and returned are values", function()
  local seen = {}
  local r = motion.simulate{method = "rk4", x0 = vec3(1, 0, 0), v0 = vec3(0, 1, 0), dt = 0.1,
                            steps = 3,
                            accel = function(_, x, v) seen[#seen + 1] = x; return vec3() end}
  T.near(r.x[4], vec3(1, 0.3, 0), 1e-12, "free motion")
  T.fails(function() seen[1].x = 99 end, "bad field 'x' of vec3 (read-only", "accel's x")
  T.fails(function() r.x[1].x = 5 end, "bad field 'x' of vec3 (read-only", "an entry")
  T.near(r.x[2], vec3(1, 0.1, 0), 1e-15, "entries unchanged")
  local zero = motion.simulate{accel = function() return 1 end, x0 = 3, dt = 1, steps = 0}
  T.equal(#zero.x, 1, "steps = 0 gives the initial state only")
  T.equal(zero.x[1], 3, "x0")
end)

T.case("errors name the function, the field and the rule", function()
  local ok_accel = function() return 1 end
  local function fails(options, text, what)
    T.fails(function() return motion.simulate(options) end, text, what)
  end
  fails({method = "rk5", accel = ok_accel, x0 = 0, dt = 1, steps = 1},
    "bad argument #1 to 'motion.simulate' (field 'method' must be one of 'euler', " ..
    "'semi_implicit', 'rk4', got 'rk5')", "unknown method")
  fails({method = 4, accel = ok_accel, x0 = 0, dt = 1, steps = 1},
    "bad argument #1 to 'motion.simulate' (field 'method' must be one of 'euler', " ..
    "'semi_implicit', 'rk4', got number)", "method type")
  fails({accel = ok_accel, x0 = 0, dt = 1e308, steps = 3},
    "bad argument #1 to 'motion.simulate' (the last time t0 + steps·dt overflows (t0 = 0, " ..
    "dt = 1e+308, steps = 3): use a smaller dt or fewer steps)", "time overflow")
  fails({x0 = 0, dt = 1, steps = 1},
    "bad argument #1 to 'motion.simulate' (field 'accel' is required)", "no accel")
  fails({accel = 3, x0 = 0, dt = 1, steps = 1},
    "bad argument #1 to 'motion.simulate' (field 'accel' must be a function, got number)",
    "accel type")
  fails({accel = ok_accel, dt = 1, steps = 1},
    "bad argument #1 to 'motion.simulate' (field 'x0' is required)", "no x0")
  fails({accel = ok_accel, x0 = "0", dt = 1, steps = 1},
    "bad argument #1 to 'motion.simulate' (field 'x0' must be a number or a vec3, got string)",
    "x0 type")
  fails({accel = ok_accel, x0 = 0 / 0, dt = 1, steps = 1},
    "bad argument #1 to 'motion.simulate' (field 'x0' must be finite, got nan)", "x0 NaN")
  fails({accel = ok_accel, x0 = 0, v0 = vec3(), dt = 1, steps = 1},
    "bad argument #1 to 'motion.simulate' (field 'v0' must be a number like x0, got vec3)",
    "mixed kinds")
  fails({accel = ok_accel, x0 = vec3(), v0 = 1, dt = 1, steps = 1},
    "bad argument #1 to 'motion.simulate' (field 'v0' must be a vec3 like x0, got number)",
    "mixed kinds (vec3)")
  fails({accel = ok_accel, x0 = 0, dt = 0, steps = 1},
    "bad argument #1 to 'motion.simulate' (field 'dt' must be > 0, got 0)", "dt = 0")
  fails({accel = ok_accel, x0 = 0, dt = math.huge, steps = 1},
    "bad argument #1 to 'motion.simulate' (field 'dt' must be finite, got inf)", "dt = inf")
  fails({accel = ok_accel, x0 = 0, dt = 1},
    "bad argument #1 to 'motion.simulate' (field 'steps' is required)", "no steps")
  fails({accel = ok_accel, x0 = 0, dt = 1, steps = 2.5},
    "bad argument #1 to 'motion.simulate' (field 'steps' must be an integer from 0 to 1000000, "
    .. "got 2.5)", "fractional steps")
  fails({accel = ok_accel, x0 = 0, dt = 1, steps = -1},
    "bad argument #1 to 'motion.simulate' (field 'steps' must be an integer from 0 to 1000000, "
    .. "got -1)", "negative steps")
  fails({accel = ok_accel, x0 = 0, dt = 1, steps = 1e7},
    "bad argument #1 to 'motion.simulate' (field 'steps' must be an integer from 0 to 1000000, "
    .. "got 10000000)", "too many steps")
  T.equal(#motion.simulate{accel = ok_accel, x0 = 0, dt = 1, steps = 2.0}.x, 3, "steps = 2.0")
  fails({accel = ok_accel, x0 = 0, dt = 1, steps = 1, t0 = "now"},
    "bad argument #1 to 'motion.simulate' (field 't0' must be a number, got string)", "t0")
  fails({accel = ok_accel, x0 = 0, dt = 1, steps = 1, x = 0},
    "bad argument #1 to 'motion.simulate' (unknown field 'x' (fields are: method, accel, x0, " ..
    "v0, dt, steps, t0))", "unknown field")
  T.fails(function() return motion.simulate(1) end,
    "bad argument #1 to 'motion.simulate' (table expected, got number)", "not a table")
  T.fails(function() return motion.simulate({}, 2) end,
    "bad argument #2 to 'motion.simulate' (no more than 1 argument expected, got 2)", "extra")
end)

T.case("a wrong acceleration names the step and the time", function()
  local function fails(options, text, what)
    options.dt, options.steps = options.dt or 0.1, options.steps or 5
    T.fails(function() return motion.simulate(options) end, text, what)
  end
  fails({method = "rk4", x0 = 0, accel = function(t) if t > 0.15 then return nil end return 1 end},
    "bad argument #1 to 'motion.simulate' (accel returned nil at step 2 (t = 0.15), " ..
    "expected number)", "nil in an RK4 stage")
  fails({x0 = vec3(), accel = function() return 1 end},
    "bad argument #1 to 'motion.simulate' (accel returned number at step 1 (t = 0), " ..
    "expected vec3)", "number for a vec3 state")
  fails({x0 = 0, accel = function(t) if t > 0.25 then return 0 / 0 end return 0 end},
    "bad argument #1 to 'motion.simulate' (accel returned nan at step 4 (t = 0.3), " ..
    "expected a finite number)", "NaN")
  fails({x0 = 0, accel = function() return mat3.identity() end},
    "bad argument #1 to 'motion.simulate' (accel returned mat3 at step 1 (t = 0), " ..
    "expected number)", "mat3")
  fails({x0 = 1, v0 = 1, dt = 1, steps = 20, accel = function(_, x) return 1e300 * x end},
    "bad argument #1 to 'motion.simulate' (accel returned inf at step 2 (t = 1), " ..
    "expected a finite number)", "overflowing acceleration")
  fails({x0 = 1e308, v0 = 1e308, dt = 1, steps = 3, accel = function() return 0 end},
    "'motion.simulate': the state is not finite after step 1 (t = 1): the motion diverged " ..
    "(try a smaller dt)", "overflowing state")
  local ok, message = pcall(motion.simulate, {x0 = 0, dt = 1, steps = 3,
                                              accel = function() error("my own error") end})
  T.equal(ok, false, "an error inside accel stops the simulation")
  assert(message:find("my own error", 1, true), "and keeps its message: " .. message)
end)

T.case("help and require", function()
  T.equal(require("rigidlab").motion, motion, "require gives the same table")
  local text = {}
  local real_print = print
  print = function(s) text[#text + 1] = s end
  help("motion.simulate")
  print = real_print
  assert(table.concat(text):find("semi_implicit", 1, true), "help lists the methods")
end)

T.finish()
