#!/usr/bin/env bash
# Running scripts: `rigidlab FILE.lua args`, `rigidlab - args` (stdin), the arg table as lua.c
# builds it, error messages and exit codes, text-only loading, subcommand or file.
# Usage: script_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"

cat >"$scratch/args.lua" <<'LUA'
print("varargs", ...)
print("arg", #arg, arg[0], arg[1], arg[2], arg[3])
print("before", arg[-1], arg[-2], arg[-3] == nil)
LUA
run "a script with arguments" -- "$rigidlab" "$scratch/args.lua" one "two words" 3
expect_status 0
expect_stdout "varargs	one	two words	3
arg	3	$scratch/args.lua	one	two words	3
before	$rigidlab	nil	true
"
expect_stderr_empty

run "negative indices hold the interpreter and its options" -- \
  "$rigidlab" -e 'x = 1' "$scratch/args.lua" a
expect_stdout "varargs	a
arg	1	$scratch/args.lua	a	nil	nil
before	x = 1	-e	false
"

run "without a script arg[0] is the interpreter" -- "$rigidlab" -e 'print(arg[0], arg[1], arg[2], #arg)'
expect_stdout "$rigidlab	-e	print(arg[0], arg[1], arg[2], #arg)	2"$'\n'

run "options after the script are the script's" -- "$rigidlab" "$scratch/args.lua" -e -v
expect_status 0
expect_stdout "varargs	-e	-v
arg	2	$scratch/args.lua	-e	-v	nil
before	$rigidlab	nil	true
"

run "- runs stdin as a script" --stdin $'local a, b = ...\nprint(a + b, arg[0])\n' -- "$rigidlab" - 2 3
expect_status 0
expect_stdout $'5\t-\n'

run "- with a multi-line script" --stdin $'local function f(n)\n  return n * 2\nend\nprint(f(21))\n' -- "$rigidlab" -
expect_stdout $'42\n'

cat >"$scratch/fails.lua" <<'LUA'
local function inner()
  error("something broke")
end
inner()
LUA
run "a runtime error: message with chunk and line, traceback, exit 1" -- "$rigidlab" "$scratch/fails.lua"
expect_status 1
expect_stdout ""
expect_stderr_line 1 "rigidlab: $scratch/fails.lua:2: something broke"
expect_stderr_line 2 "stack traceback:"
expect_stderr_line 3 "	[C]: in function 'error'"
expect_stderr_contains "$scratch/fails.lua:2: in local 'inner'"
expect_stderr_contains "$scratch/fails.lua:4: in main chunk"

printf 'print("printed first")\nlocal x = = 1\n' >"$scratch/syntax.lua"
run "a syntax error: nothing runs, exit 1" -- "$rigidlab" "$scratch/syntax.lua"
expect_status 1
expect_stdout ""
expect_stderr_line 1 "rigidlab: $scratch/syntax.lua:2: unexpected symbol near '='"

printf 'print("out before")\nerror("after output")\n' >"$scratch/order.lua"
run "output before an error is kept" -- "$rigidlab" "$scratch/order.lua"
expect_status 1
expect_stdout $'out before\n'
expect_stderr_line 1 "rigidlab: $scratch/order.lua:2: after output"

run "an error object that is a table" -- "$rigidlab" -e 'error({})'
expect_status 1
expect_stderr_line 1 "rigidlab: (error object is a table value)"
run "an error object with __tostring" -- \
  "$rigidlab" -e 'error(setmetatable({}, {__tostring = function() return "custom" end}))'
expect_status 1
expect_stderr_line 1 "rigidlab: custom"

run "a missing script is a usage error (exit 2)" -- "$rigidlab" "$scratch/absent.lua"
expect_status 2
expect_stdout ""
expect_stderr_line 1 "rigidlab: cannot open $scratch/absent.lua: No such file or directory"
expect_stderr_line 2 "Try 'rigidlab --help' for more information."

run "a directory as script" -- "$rigidlab" "$scratch"
expect_status 2
expect_stderr_line 1 "rigidlab: cannot read $scratch: Is a directory"

# Names the file system refuses are clean usage errors too, never an uncaught exception
# (issue 12, item 4): a name too long, a loop of symbolic links.
long_name=$(printf 'a%.0s' {1..300}).lua
run "a script name too long" -- "$rigidlab" "$long_name"
expect_status 2
expect_stderr_line 1 "rigidlab: cannot open $long_name: File name too long"
ln -s "$scratch/loop_b" "$scratch/loop_a"
ln -s "$scratch/loop_a" "$scratch/loop_b"
run "a loop of symbolic links as script" -- "$rigidlab" "$scratch/loop_a"
expect_status 2
expect_stderr_line 1 "rigidlab: cannot open $scratch/loop_a: Too many levels of symbolic links"

run "os.exit(3) exits 3" -- "$rigidlab" -e 'print("bye") os.exit(3)'
expect_status 3
expect_stdout $'bye\n'
run "os.exit(true) exits 0" -- "$rigidlab" -e 'os.exit(true)'
expect_status 0
run "os.exit(false) exits 1" -- "$rigidlab" -e 'os.exit(false)'
expect_status 1
printf 'os.exit(7, true)\n' >"$scratch/exit.lua"
run "os.exit(7, true) from a script" -- "$rigidlab" "$scratch/exit.lua"
expect_status 7

printf '#!/usr/bin/env rigidlab\nprint("shebang skipped")\n' >"$scratch/shebang.lua"
run "a #! first line is skipped" -- "$rigidlab" "$scratch/shebang.lua"
expect_stdout $'shebang skipped\n'

# Scripts are text: precompiled chunks are refused, from the command line, load, dofile,
# require and -l.
printf 'local f = assert(io.open(arg[1], "wb"))\nf:write(string.dump(function() print(1) end))\nf:close()\n' \
  >"$scratch/dump.lua"
"$rigidlab" "$scratch/dump.lua" "$scratch/binary.luac"
run "a binary chunk is refused" -- "$rigidlab" "$scratch/binary.luac"
expect_status 1
expect_stderr_line 1 "rigidlab: $scratch/binary.luac: attempt to load a binary chunk (rigidlab loads text only)"
run "- refuses binary chunks too" -- bash -c '"$1" - <"$2"' _ "$rigidlab" "$scratch/binary.luac"
expect_status 1
expect_stderr_line 1 "rigidlab: stdin: attempt to load a binary chunk (rigidlab loads text only)"
run "load refuses mode b" -- "$rigidlab" -e 'load(string.dump(function() end), nil, "b")'
expect_status 1
expect_stderr_line 1 \
  "rigidlab: (command line):1: bad argument #3 to 'load' (mode must be \"t\": rigidlab loads text only, got \"b\")"
run "load of a binary string gives nil and the reason" -- \
  "$rigidlab" -e 'print(load(string.dump(function() end)))'
expect_stdout $'nil\tattempt to load a binary chunk (rigidlab loads text only)\n'
run "dofile refuses binary chunks" -- "$rigidlab" -e "dofile('$scratch/binary.luac')"
expect_status 1
expect_stderr_line 1 "rigidlab: $scratch/binary.luac: attempt to load a binary chunk (rigidlab loads text only)"
cp "$scratch/binary.luac" "$scratch/binmod.lua"
run "-l refuses a binary module" -- env LUA_PATH="$scratch/?.lua" "$rigidlab" -l binmod
expect_status 1
expect_stderr_line 1 "rigidlab: error loading module 'binmod' from file '$scratch/binmod.lua':"
expect_stderr_line 2 "	attempt to load a binary chunk (rigidlab loads text only)"
run "require refuses it too" -- env LUA_PATH="$scratch/?.lua" "$rigidlab" -e 'require("binmod")'
expect_status 1
expect_stderr_line 1 "rigidlab: error loading module 'binmod' from file '$scratch/binmod.lua':"

run "require(\"rigidlab\") is the table of the globals" -- \
  "$rigidlab" -e 'local r = require("rigidlab") print(r.vec3 == vec3, r.help == help, type(r.version))'
expect_stdout $'true\ttrue\tstring\n'

# SIGINT (Ctrl-C) stops a running script with an "interrupted!" error, as in lua, that says
# where the script was. The file is emptied here, not by the background job's redirection: that
# one runs after the fork, so a stale out from the case before could end the wait at once and
# the SIGINT would reach the forked shell before rigidlab started.
: >"$scratch/out"
"$rigidlab" -e 'print("looping") io.stdout:flush() while true do end' \
  >"$scratch/out" 2>"$scratch/err" &
looping=$!
for _ in $(seq 600); do [[ -s $scratch/out ]] && break; sleep 0.05; done  # 30 s at most
kill -INT "$looping"
case_name="SIGINT interrupts a script"
status=0
wait "$looping" || status=$?
expect_status 1
expect_stderr_line 1 "rigidlab: (command line):1: interrupted!"
expect_stderr_line 2 "stack traceback:"

# wait_or_kill PID: waits for PID, keeping its exit status in $status; kills it after 60 s,
# so that a test of an interruption fails instead of hanging when the interruption fails.
wait_or_kill() {
  # Killed just after its fork, before it execs, the killer is still a copy of this shell; the
  # EXIT trap of testlib.sh leaves $scratch alone in such a copy.
  bash -c 'sleep 60 && kill -KILL "$1"' _ "$1" >/dev/null 2>&1 &
  local killer=$!
  status=0
  wait "$1" || status=$?
  kill "$killer" 2>/dev/null || true
}
# start_looping CODE: rigidlab -e CODE in the background ($looping), once it has printed.
start_looping() {
  : >"$scratch/out"
  "$rigidlab" -e "$1" >"$scratch/out" 2>"$scratch/err" &
  looping=$!
  for _ in $(seq 600); do [[ -s $scratch/out ]] && break; sleep 0.05; done  # 30 s at most
}
# ... a loop inside a coroutine too (hooks are per thread; issue 12, item 10).
start_looping 'coroutine.wrap(function() print("looping") io.stdout:flush() while true do end end)()'
kill -INT "$looping" || true
case_name="SIGINT interrupts a loop in a coroutine"
wait_or_kill "$looping"
expect_status 1
expect_stderr_line 1 "rigidlab: (command line):1: interrupted!"
# Two SIGINTs in a row stop the REPL's chunk, not the REPL (here reading a pipe).
: >"$scratch/out"
{
  printf 'coroutine.wrap(function() print("looping") io.stdout:flush() while true do end end)()\n'
  sleep 2
  printf 'print("still here")\n'
} | "$rigidlab" >"$scratch/out" 2>"$scratch/err" &
looping=$!  # of a pipeline in the background: its last process, rigidlab
for _ in $(seq 600); do [[ -s $scratch/out ]] && break; sleep 0.05; done  # 30 s at most
kill -INT "$looping" || true
kill -INT "$looping" || true
case_name="two SIGINTs in a row: the REPL goes on"
wait_or_kill "$looping"
out=$(cat "$scratch/out")$'\n'
expect_status 0
expect_stdout $'looping\nstill here\n'
expect_stderr_line 1 "stdin:1: interrupted!"
# A C function that never returns to Lua (backtracking for years) cannot be interrupted: once
# a SIGINT has waited a second, the next one ends the process with a message.
start_looping 'print("finding") io.stdout:flush() string.find(string.rep("a", 40) .. "b", string.rep("a*", 40) .. "c")'
kill -INT "$looping" || true
sleep 1.2
kill -INT "$looping" || true
case_name="SIGINT in a C function that does not return"
wait_or_kill "$looping"
expect_status 130
expect_stderr_contains "rigidlab: ended by Ctrl-C: a C function has not returned to Lua since the first one"

# The first argument names a command unless a file of that name exists.
run "lessons is a command" -- "$rigidlab" lessons extra
expect_status 2
expect_stderr_line 1 "rigidlab: 'lessons' takes no arguments"
run "check rejects unknown options" -- "$rigidlab" check --bogus
expect_status 2
expect_stderr_line 1 "rigidlab: unrecognized option '--bogus' for 'check'"
mkdir "$scratch/cwd" "$scratch/cwd/lessons"
printf 'print("the file named check", ...)\n' >"$scratch/cwd/check"
run "a file named like a command is run" -- bash -c 'cd "$1" && "$2" check x' _ "$scratch/cwd" "$rigidlab"
expect_status 0
expect_stdout $'the file named check\tx\n'
run "a directory named like a command does not hide it" -- \
  bash -c 'cd "$1" && "$2" lessons extra' _ "$scratch/cwd" "$rigidlab"
expect_status 2
expect_stderr_line 1 "rigidlab: 'lessons' takes no arguments"
run "a command name after an option is a script" -- \
  bash -c 'cd "$1" && "$2" -e "x = 1" lessons' _ "$scratch" "$rigidlab"
expect_status 2
expect_stderr_line 1 "rigidlab: cannot open lessons: No such file or directory"

finish
