#!/usr/bin/env bash
# rigidlab --sandbox: scripts, -e and the REPL run without io, os (but clock, time, date,
# difftime), require, dofile, loadfile, string.dump and debug (but traceback), and cannot write
# files through plot or csv; -l is refused with it. Usage: sandbox_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"

cat >"$scratch/probe.lua" <<'LUA'
print(io, package, require, dofile, loadfile, string.dump, debug.getinfo, os.execute, os.getenv)
print(type(os.clock()), type(os.time()), type(os.date("%Y")), os.difftime(2, 1))
print(debug.traceback("tb"):match("^tb"), vec3(1, 2, 3) + vec3(1, 1, 1))
LUA
run "a script in the sandbox" -- "$rigidlab" --sandbox "$scratch/probe.lua"
expect_status 0
expect_stdout $'nil\tnil\tnil\tnil\tnil\tnil\tnil\tnil\tnil\nnumber\tnumber\tstring\t1.0\ntb\t(2, 3, 4)\n'
expect_stderr_empty

run "the same script outside it" -- "$rigidlab" "$scratch/probe.lua"
expect_status 0
[[ $out == "table: "* ]] && pass || fail "io is '$out'"

run "-e in the sandbox" -- "$rigidlab" --sandbox -e 'io.open("x", "w")'
expect_status 1
expect_stderr_line 1 "rigidlab: (command line):1: attempt to index a nil value (global 'io')"

run "no files through csv.write" -- "$rigidlab" --sandbox -e "csv.write('$scratch/x.csv', {x = {1}}, {'x'})"
expect_status 1
expect_stderr_line 1 \
  "rigidlab: (command line):1: bad argument #1 to 'csv.write' (files cannot be written in the sandbox)"
[[ ! -e $scratch/x.csv ]] && pass || fail "the file was written"

run "the REPL in the sandbox" --stdin $'print(io)\nprint(os.exit)\nprint(1 + 1)\n' -- "$rigidlab" --sandbox
expect_status 0
expect_stdout $'nil\nnil\n2\n'

run "load stays text only" -- "$rigidlab" --sandbox -e 'print(load("return 1")(), (pcall(load, "x", "x", "b")))'
expect_stdout $'1\tfalse\n'

run "-l with --sandbox is a usage error" -- "$rigidlab" --sandbox -l rigidlab -e 'print(1)'
expect_status 2
expect_stdout ""
expect_stderr_line 1 "rigidlab: '-l' cannot be used with '--sandbox' (the sandbox has no require)"

run "with the limits" -- "$rigidlab" --sandbox --max-instructions 1000 -e 'while true do end'
expect_status 1
expect_stderr_line 1 "rigidlab: (command line):1: stopped: the instruction limit (1000 instructions) reached"

finish
