#!/usr/bin/env bash
# --max-instructions, --max-memory and --timeout for scripts, -e, stdin and the REPL: a runaway
# run is stopped within seconds with one line naming the limit and exit 1, also inside one huge
# w:step and inside a C function that never returns to Lua (a backtracking string.find); bad
# values are usage errors. Usage: limits_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"

# timed NAME MAX_SECONDS -- COMMAND...: run, then fail if it took longer than MAX_SECONDS.
timed() {
  local name=$1 max=$2
  shift 3
  local start end
  start=$(date +%s%N)
  run "$name" -- "$@"
  end=$(date +%s%N)
  elapsed_ms=$(((end - start) / 1000000))
  if ((elapsed_ms <= max * 1000)); then pass; else fail "took ${elapsed_ms} ms, want <= ${max} s"; fi
}

printf 'print("looping")\nwhile true do end\n' >"$scratch/loop.lua"
printf 'local t = {}\nfor i = 1, math.huge do t[i] = {i} end\n' >"$scratch/hog.lua"
# Backtracking over 40 stars: years inside one C call that never returns to Lua.
printf 'print("finding")\nstring.find(string.rep("a", 40) .. "b", string.rep("a*", 40) .. "c")\n' \
  >"$scratch/find.lua"
# One step of 10000 substeps with 1000 solver sweeps over 400 boxes: hours inside w:step.
cat >"$scratch/step.lua" <<'EOF'
local w = world{substeps = 10000, iterations = 1000}
w:add_plane{normal = vec3(0, 1, 0), offset = 0}
for i = 0, 399 do
  w:add(body.box{mass = 1, size = vec3(1, 1, 1), position = vec3(i % 20 * 1.01, 0.5 + i // 20, 0)})
end
print("stepping")
w:step(0.01)
EOF

timed "an endless loop, --timeout" 3 -- "$rigidlab" --timeout 1 "$scratch/loop.lua"
expect_status 1
expect_stdout $'looping\n'
expect_stderr_line 1 "rigidlab: $scratch/loop.lua:2: stopped: the time limit (1 s) reached"
expect_stderr_line_count 1

timed "an endless loop, --max-instructions" 3 -- "$rigidlab" --max-instructions 1e6 "$scratch/loop.lua"
expect_status 1
expect_stderr_line 1 \
  "rigidlab: $scratch/loop.lua:2: stopped: the instruction limit (1000000 instructions) reached"
expect_stderr_line_count 1

timed "unbounded allocation, --max-memory" 5 -- "$rigidlab" --max-memory 32 "$scratch/hog.lua"
expect_status 1
expect_stderr_line 1 "rigidlab: stopped: the memory limit (32 MB) reached"
expect_stderr_line_count 1

# The engine's memory counts against the same limit (issue 12, item 6): planes without end,
# and the contacts of 2000 overlapping spheres in one w:step (1.6 GB without the limit).
run "planes without end: the memory limit" -- \
  "$rigidlab" --max-memory 16 -e 'local w = world{} for i = 1, 5e6 do w:add_plane() end'
expect_status 1
expect_stderr_line 1 "rigidlab: stopped: the memory limit (16 MB) reached"
expect_stderr_line_count 1
# A plane holds at least a normal and an offset (32 bytes), so at most 16 MB / 32 fit; the
# failed add changes nothing and the world goes on.
cat >"$scratch/planes.lua" <<'EOF'
local w, n = world{}, 0
local ok, message = pcall(function() for i = 1, 5e6 do w:add_plane() n = n + 1 end end)
print(ok, message, n > 1000 and n <= 16 * 2^20 / 32)
collectgarbage()
print(pcall(w.step, w, 0.25))
print(w.time)
EOF
run "a failed w:add_plane is Lua's memory error" -- "$rigidlab" --max-memory 16 "$scratch/planes.lua"
expect_status 0
expect_stdout $'false\tnot enough memory\ttrue\ntrue\n0.25\n'
cat >"$scratch/spheres.lua" <<'EOF'
local w = world{gravity = vec3(0, -9.81, 0)}
for i = 1, 2000 do w:add(body.sphere{mass = 1, radius = 1, position = vec3(i * 1e-3, 0, 0)}) end
local b = w:bodies()[1000]
local p, v = b.position, b.velocity
print(pcall(w.step, w, 1 / 60))
print(w.time == 0, b.position == p, b.velocity == v)
w:step(1 / 60)
EOF
run "2000 overlapping spheres: one w:step stops at the limit, undone" -- \
  "$rigidlab" --max-memory 64 "$scratch/spheres.lua"
expect_status 1
expect_stdout $'false\tnot enough memory\ntrue\ttrue\ttrue\n'
expect_stderr_line 1 "rigidlab: stopped: the memory limit (64 MB) reached"
# Garbage worlds are collected at the pace their engine memory grows, not only Lua's: a loop
# of big short-lived worlds fits in a limit a few of them would fill.
run "garbage worlds do not fill the limit" -- "$rigidlab" --max-memory 16 \
  -e 'for i = 1, 300 do local w = world{} for j = 1, 5000 do w:add_plane() end end print("ok")'
expect_status 0
expect_stdout $'ok\n'

# ... in lessons too: `rigidlab check` and `rigidlab lesson` charge a step's engine memory.
cat >"$scratch/hog_lesson.lua" <<'EOF'
return lesson{id = "engine-hog", title = "Planes without end", source = "tests", steps = {
  {title = "Planes", text = "More and more.", run = function(ctx)
    local w = world{}
    for i = 1, 5e6 do w:add_plane() end
  end},
}}
EOF
run "a lesson's engine memory under check's memory limit" -- \
  "$rigidlab" check --max-memory 16 "$scratch/hog_lesson.lua"
expect_status 1
expect_stdout_contains "error: step 1: stopped: the memory limit (16 MB) reached"

run "a memory limit smaller than the libraries: stopped, not a panic" -- "$rigidlab" --max-memory 0.001 -e 'print(1)'
expect_status 1
expect_stdout ""
expect_stderr_line 1 "rigidlab: stopped: the memory limit (0.001 MB) reached"
expect_stderr_line_count 1

timed "a C function that never returns: the watchdog ends the process" 4 -- \
  "$rigidlab" --timeout 1 "$scratch/find.lua"
expect_status 1
expect_stdout $'finding\n'
expect_stderr_line 1 "rigidlab: stopped: the time limit (1 s) reached in a C function"
expect_stderr_line_count 1

timed "one huge w:step is stopped inside the engine" 3 -- "$rigidlab" --timeout 1 "$scratch/step.lua"
expect_status 1
expect_stdout $'stepping\n'
expect_stderr_line 1 "rigidlab: $scratch/step.lua:7: stopped: the time limit (1 s) reached"

# The world is as before the stopped step: the script can catch the error and look, as long
# as what it does afterwards fits in the grace second (the deadline stays passed).
cat >"$scratch/consistent.lua" <<'EOF'
local w = world{}
w:add_plane{normal = vec3(0, 1, 0), offset = 0}
for i = 0, 99 do w:add(body.box{mass = 1, size = vec3(1, 1, 1), position = vec3(i % 10 * 1.01, 0.5 + i // 10, 0)}) end
w:step(0.01)
local b = w:bodies()[55]
local t0, p0 = w.time, b.position
w.substeps, w.iterations = 10000, 1000  -- a step of hours; the one above is quick (ASan too)
local ok, message = pcall(w.step, w, 0.01)
print(ok, message)
print(w.time == t0, b.position == p0)
EOF
timed "a stopped step leaves the world unchanged" 3 -- "$rigidlab" --timeout 1 "$scratch/consistent.lua"
expect_stdout $'false\t'"$scratch"$'/consistent.lua:8: stopped: the time limit (1 s) reached\ntrue\ttrue\n'

# A limit in a run of steps keeps the steps completed before it and says how many (issue 12
# item 19: the whole call was rolled back, 2 s of a 20 s run left w.time = 0).
cat >"$scratch/run_of_steps.lua" <<'EOF'
local w = world{}
w:add_plane{normal = vec3(0, 1, 0), offset = 0}
for i = 0, 99 do w:add(body.box{mass = 1, size = vec3(1, 1, 1), position = vec3(i % 10 * 1.01, 0.5 + i // 10, 0)}) end
local ok, message = pcall(w.step, w, 0.01, 1000000)
local k = tonumber(message:match("%((%d+) of 1000000 steps completed; the world is at t = "))
print(ok, message:find("stopped: the time limit (1 s) reached", 1, true) ~= nil, k ~= nil and k > 0,
      k ~= nil and math.abs(w.time - k * 0.01) < 1e-9)
EOF
timed "a stopped run of steps keeps the completed ones and says how many" 3 -- \
  "$rigidlab" --timeout 1 "$scratch/run_of_steps.lua"
expect_stdout $'false\ttrue\ttrue\ttrue\n'

timed "-e is limited too" 3 -- "$rigidlab" --timeout 0.5 -e 'while true do end'
expect_status 1
expect_stderr_line 1 "rigidlab: (command line):1: stopped: the time limit (0.5 s) reached"

timed "a script on stdin" 3 -- bash -c '"$1" --max-instructions 100000 - <"$2"' _ "$rigidlab" "$scratch/loop.lua"
expect_status 1
expect_stderr_line 1 "rigidlab: stdin:2: stopped: the instruction limit (100000 instructions) reached"

timed "the limits apply to each chunk of the REPL, which goes on" 5 -- bash -c \
  'printf "x = 0\nwhile true do x = x + 1 end\nprint(x > 0)\nwhile true do end\nprint(\"after\")\n" | "$1" --timeout 0.5' \
  _ "$rigidlab"
expect_status 0
expect_stdout $'true\nafter\n'
expect_stderr_line 1 "stdin:1: stopped: the time limit (0.5 s) reached"
expect_stderr_line 2 "stdin:1: stopped: the time limit (0.5 s) reached"
expect_stderr_line_count 2

run "--option=value" -- "$rigidlab" --max-instructions=1000 -e 'for i = 1, 1e9 do end'
expect_status 1
expect_stderr_line 1 "rigidlab: (command line):1: stopped: the instruction limit (1000 instructions) reached"

run "limits that are not reached change nothing" -- \
  "$rigidlab" --max-instructions 1e9 --max-memory 64 --timeout 30 -e 'print(#string.rep("x", 1e6))'
expect_status 0
expect_stdout $'1000000\n'
expect_stderr_empty

run "0 means no limit" -- "$rigidlab" --timeout 0 --max-memory 0 --max-instructions 0 -e 'print("ok")'
expect_status 0
expect_stdout $'ok\n'

# A limit stop is not a script's own error: pcall cannot swallow it for good.
run "pcall in a loop cannot outlive the limit" -- \
  "$rigidlab" --timeout 0.5 -e 'while true do pcall(function() while true do end end) end'
expect_status 1
expect_stderr_contains "stopped: the time limit (0.5 s) reached"

# The limits survive what a script does to hooks (issue 12, item 8): debug.sethook() alone,
# a hook of the script's own, on the main thread, in a coroutine or set on another coroutine.
for code in 'debug.sethook() while true do end' \
    'debug.sethook(function() end, "l") while true do end' \
    'debug.sethook(function() end, "", 1e9) while true do end' \
    'coroutine.wrap(function() debug.sethook() while true do end end)()' \
    'local co = coroutine.create(function() while true do end end) debug.sethook(co) error(select(2, coroutine.resume(co)), 0)'; do
  run "debug.sethook does not switch the instruction limit off: $code" -- \
    timeout 20 "$rigidlab" --max-instructions 1e6 -e "$code"
  expect_status 1
  expect_stderr_contains "stopped: the instruction limit (1000000 instructions) reached"
done
timed "debug.sethook does not switch the time limit's checks off" 3 -- \
  timeout 20 "$rigidlab" --timeout 0.5 -e 'debug.sethook() while true do end'
expect_status 1
expect_stderr_line 1 "rigidlab: (command line):1: stopped: the time limit (0.5 s) reached"
# A script's hooks still behave as Lua's own: the same events, counts and gethook results as
# in the reference interpreter, when it is installed (lua5.4).
hooks='local n, lines, m = 0, 0, 0
debug.sethook(function() n = n + 1 end, "", 7) for i = 1, 1000 do end debug.sethook()
debug.sethook(function() m = m + 1 end, "", 2500) for i = 1, 10000 do end debug.sethook()
debug.sethook(function() lines = lines + 1 end, "l")
local x = 1
x = x + 1
debug.sethook()
local f, mask, count = debug.gethook()
debug.sethook(function() end, "cr", 3)
local _, mask2, count2 = debug.gethook()
debug.sethook()
print(n, m, lines, f, mask, count, mask2, count2)'
if command -v lua5.4 >/dev/null; then
  run "script hooks as in lua5.4" -- "$rigidlab" --max-instructions 1e9 -e "$hooks"
  expect_stdout "$(lua5.4 -e "$hooks")"$'\n'
fi

# A limit raised inside coroutine.wrap: the position of the loop, once (coroutine.wrap prepends
# the position of its call to an error crossing it; issue 12, item 23).
run "a limit inside coroutine.wrap names the loop's line once" -- "$rigidlab" --max-instructions 1e6 \
  -e $'local f = coroutine.wrap(function()\n  while true do end\nend)\nf()'
expect_status 1
expect_stderr_line 1 "rigidlab: (command line):2: stopped: the instruction limit (1000000 instructions) reached"
expect_stderr_line_count 1
printf 'f = coroutine.wrap(function()\n  while true do end\nend)\nf()\nprint("after")\n' >"$scratch/wrap.lua"
run "in the REPL too" -- bash -c '"$1" --max-instructions 1e6 <"$2"' _ "$rigidlab" "$scratch/wrap.lua"
expect_stdout $'after\n'
expect_stderr_line 1 "stdin:2: stopped: the instruction limit (1000000 instructions) reached"
expect_stderr_line_count 1

# Bad values are usage errors: exit 2, nothing runs.
for bad in "--timeout" "--timeout x" "--timeout -1" "--timeout nan" "--timeout inf" "--timeout=" \
    "--timeout 1s" "--max-memory -5" "--max-memory 1e99" "--max-instructions 1.5" \
    "--max-instructions 2e18" "--max-instructions=" "--timeout= 1"; do
  read -ra words <<<"$bad"
  run "bad value: $bad" -- "$rigidlab" "${words[@]}" -e 'print("ran")'
  expect_status 2
  expect_stdout ""
  expect_stderr_line 2 "Try 'rigidlab --help' for more information."
done
run "the message says what was expected" -- "$rigidlab" --timeout x -e 'print("ran")'
expect_stderr_line 1 "rigidlab: '--timeout' needs a number of seconds >= 0, got 'x'"
run "a missing value" -- "$rigidlab" --max-memory
expect_stderr_line 1 "rigidlab: '--max-memory' needs an argument (a number of megabytes >= 0)"
run "a fractional instruction count" -- "$rigidlab" --max-instructions 1.5 -e ''
expect_stderr_line 1 "rigidlab: '--max-instructions' needs a whole number of instructions >= 0, got '1.5'"

finish
