#!/usr/bin/env bash
# The REPL reading a pipe: the same evaluation as in a terminal (expressions print their
# values, statements span lines), no banner, no prompts, each error one line on stderr, and
# exit 0 at the end of input. Usage: repl_pipe_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"

run "the session of issue 2" --stdin $'1+1\nvec3(1,2,3)\nerror("boom")\nx = 5\nx * 2\n' -- "$rigidlab"
expect_status 0
expect_stdout $'2\n(1, 2, 3)\n10\n'
expect_stderr_line 1 "stdin:1: boom"
expect_stderr_line_count 1

run "a chunk over several lines" --stdin $'function f()\nreturn 3\nend\nf()\n' -- "$rigidlab"
expect_status 0
expect_stdout $'3\n'
expect_stderr_empty

run "an unfinished expression continues" --stdin $'1 +\n2\n(\n3\n)\n' -- "$rigidlab"
expect_stdout $'3\n3\n'

run "a call over lines prints its values, as on one line" --stdin $'math.max(\n1,\n5)\n' -- "$rigidlab"
expect_stdout $'5\n'

run "a long string over lines" --stdin $'s = [[a\nb]]\n#s\n' -- "$rigidlab"
expect_stdout $'3\n'

run "several values, tab separated; nil" --stdin $'1, "two", nil, true\nnil\n' -- "$rigidlab"
expect_stdout $'1\ttwo\tnil\ttrue\nnil\n'

run "statements and calls without values print nothing" \
  --stdin $'local y = 1\nprint("printed")\nfunction g() end\ng()\n\n   \n' -- "$rigidlab"
expect_stdout $'printed\n'
expect_stderr_empty

run "values print with tostring: rigidlab types" \
  --stdin $'mat3.identity()\nquat()\n' -- "$rigidlab"
expect_stdout_contains "((1, 0, 0), (0, 1, 0), (0, 0, 1))"

run "=expression, as in Lua 5.2" --stdin $'=2^10\n' -- "$rigidlab"
expect_stdout $'1024.0\n'

run "a runtime error in a binding" --stdin $'vec3(1,2,3):cross(5)\n1\n' -- "$rigidlab"
expect_status 0
expect_stdout $'1\n'
expect_stderr_line 1 "stdin:1: bad argument #1 to 'vec3:cross' (vec3 expected, got number)"
expect_stderr_line_count 1

run "a syntax error, then evaluation goes on" --stdin $'x = = 1\n"after"\n' -- "$rigidlab"
expect_status 0
expect_stdout $'after\n'
expect_stderr_line 1 "stdin:1: unexpected symbol near '='"

run "input ending inside a chunk" --stdin $'function h()\nreturn 1\n' -- "$rigidlab"
expect_status 0
expect_stdout ""
expect_stderr_line 1 "stdin:2: 'end' expected (to close 'function' at line 1) near <eof>"

run "no final newline" --stdin $'40 + 2' -- "$rigidlab"
expect_stdout $'42\n'

run "a non-string error object" --stdin $'error({})\nerror(setmetatable({}, {__tostring = function() return "mine" end}))\n' -- "$rigidlab"
expect_stderr_line 1 "(error object is a table value)"
expect_stderr_line 2 "mine"

run "results show without the global print (a script may replace it)" \
  --stdin $'print = nil\n1\n' -- "$rigidlab"
expect_status 0
expect_stdout $'1\n'
expect_stderr_empty

run "globals persist; prompts are not printed" --stdin $'_PROMPT = "custom> "\na = 6\na * 7\n' -- "$rigidlab"
expect_stdout $'42\n'

run "io.read reads the next lines of stdin" --stdin $'io.read("n") * 2\n21\n"next"\n' -- "$rigidlab"
expect_stdout $'42\nnext\n'

run "os.exit ends the session with its status" --stdin $'print("a")\nos.exit(4)\nprint("b")\n' -- "$rigidlab"
expect_status 4
expect_stdout $'a\n'

run "-i after -e reads stdin as the REPL" --stdin $'x + 1\n' -- "$rigidlab" -e 'x = 41' -i
expect_status 0
expect_stdout $'42\n'
expect_stderr_empty

printf 'y = 9\n' >"$scratch/setup.lua"
run "-i after a script" --stdin $'y * y\n' -- "$rigidlab" -i "$scratch/setup.lua"
expect_stdout $'81\n'

run "-e alone does not read stdin" --stdin $'print("must not run")\n' -- "$rigidlab" -e 'print("only")'
expect_stdout $'only\n'

run "an error in -e skips the REPL, exit 1" --stdin $'1\n' -- "$rigidlab" -e 'error("x")' -i
expect_status 1
expect_stdout ""

# Reading a chunk is linear in its length (issue 12, item 9): a 200,000-line `--[[` comment,
# block, table or continued string is read in one pass, not compiled again after each line
# (that took minutes; the timeout only turns a regression into a failure instead of a hang).
big_chunk() {  # OPEN LINE CLOSE: OPEN, 200,000 times LINE, CLOSE, each on a line
  printf '%s\n' "$1"
  line=$2 awk 'BEGIN { for (i = 0; i < 200000; i++) print ENVIRON["line"] }'
  printf '%s\n' "$3"
}
{ big_chunk '--[[' 'x' ']]'; printf 'print("after the comment")\n'; } >"$scratch/comment.lua"
run "a 200,000-line comment" -- bash -c 'timeout 60 "$1" --timeout 10 <"$2"' _ "$rigidlab" "$scratch/comment.lua"
expect_status 0
expect_stdout $'after the comment\n'
expect_stderr_empty
{ big_chunk 'do' 'n = (n or 0) + 1' 'end'; printf 'print(n)\n'; } >"$scratch/block.lua"
run "a 200,000-line block" -- bash -c 'timeout 60 "$1" --timeout 10 <"$2"' _ "$rigidlab" "$scratch/block.lua"
expect_stdout $'200000\n'
{ big_chunk 't = {' '1,' '}'; printf '#t\n'; } >"$scratch/table.lua"
run "a 200,000-line table" -- bash -c 'timeout 60 "$1" --timeout 10 <"$2"' _ "$rigidlab" "$scratch/table.lua"
expect_stdout $'200000\n'
{ big_chunk 's = "\' 'ab\' '"'; printf '#s\n'; } >"$scratch/string.lua"
run "a string continued over 200,000 lines" -- bash -c 'timeout 60 "$1" --timeout 10 <"$2"' _ "$rigidlab" "$scratch/string.lua"
expect_stdout $'600001\n'
# An error inside a long open chunk is still reported, found when the chunk has doubled (past
# 4 KB, the chunk is no longer compiled after every line).
{
  printf 'f = function()\n'
  line='  x = 1' awk 'BEGIN { for (i = 0; i < 1000; i++) print ENVIRON["line"] }'
  printf '  local y = = 1\nend\nprint("next")\n'
} >"$scratch/error.lua"
run "a syntax error inside a long function" -- bash -c '"$1" <"$2"' _ "$rigidlab" "$scratch/error.lua"
expect_stderr_line 1 "stdin:1002: unexpected symbol near '='"
expect_stdout $'next\n'
# The pending chunk's text counts against --max-memory: a comment that never ends is stopped.
run "a comment that never ends: the memory limit" -- bash -c \
  '{ printf "%s\n" "--[["; awk "BEGIN { for (i = 0; i < 40000; i++) printf \"%01000d\\n\", 0 }"; printf "]]\nprint(\"after\")\n"; } | "$1" --max-memory 16' \
  _ "$rigidlab"
expect_stderr_line 1 "stopped: the memory limit (16 MB) reached"

# Values print as luaprompt and IPython show them (issue 16, item 6): tables with their
# fields, nested, within limits; metamethods other than __tostring never run. COLUMNS sets
# the width outside a terminal.
pretty() {  # NAME INPUT: runs INPUT through the REPL, 80 columns, a 5 s time limit
  run "$1" --stdin "$2" -- env COLUMNS=80 "$rigidlab" --timeout 5
}
pretty "a table shows its fields: the array part, then numbers, then names" \
  $'{a = 1, b = "two", [3] = true, {1, 2}}\n{}\n'
expect_stdout $'{{1, 2}, [3] = true, a = 1, b = "two"}\n{}\n'
pretty "keys that are not names; strings quoted inside, raw at the top" \
  $'{["end"] = 1, ["a b"] = 2, [1.5] = 3, [false] = 4}\n"x\\ny", {"x\\ny", \'q"\'}\n'
expect_stdout $'{[1.5] = 3, ["a b"] = 2, ["end"] = 1, [false] = 4}\nx\ny\t{"x\\ny", "q\\""}\n'
pretty "nesting is cut at depth 4" $'{a = {b = {c = {d = {e = 1}}}}}\n'
expect_stdout $'{a = {b = {c = {d = {…}}}}}\n'
pretty "a cycle" $'t = {1}; t.me = t; t.list = {t}\nt\n'
expect_stdout $'{1, list = {<cycle>}, me = <cycle>}\n'
pretty "__index, __pairs and __len are not run" \
  $'setmetatable({x = 1}, {__index = function() while true do end end, __pairs = function() while true do end end, __len = function() while true do end end})\n'
expect_stdout $'{x = 1}\n'
expect_stderr_empty
pretty "__tostring shows the table as print would; its error is shown; __name titles" \
  $'setmetatable({}, {__tostring = function() return "custom!" end})\nsetmetatable({}, {__tostring = function() error("boom") end})\nsetmetatable({y = 2}, {__name = "Point"})\n'
expect_stdout $'custom!\n<error in __tostring: stdin:1: boom>\nPoint {y = 2}\n'
run "a __tostring that loops is stopped by the limits; the REPL goes on" \
  --stdin $'setmetatable({}, {__tostring = function() while true do end end})\n1 + 1\n' -- \
  "$rigidlab" --max-instructions 1e6
expect_stdout $'2\n'
expect_stderr_line 1 "stdin:1: stopped: the instruction limit (1000000 instructions) reached"
pretty "long lists are cut at 50 entries, packed to the width" $'t = {} for i = 1, 1e6 do t[i] = i end\nt\n'
expect_stdout $'{\n  1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22,\n  23, 24, 25, 26, 27, 28, 29, 30, 31, 32, 33, 34, 35, 36, 37, 38, 39, 40, 41,\n  42, 43, 44, 45, 46, 47, 48, 49, 50, … (999950 more)\n}\n'
pretty "long strings in a table are cut" $'{string.rep("ab", 150)}\n'
expect_stdout $'{\n  "'"$(printf 'ab%.0s' {1..100})"$'"… (300 bytes)\n}\n'
# Euler's method with a = 1 from rest: x_n = n(n-1)/2, v_n = n (steps of 1 s).
pretty "motion.simulate's trajectory" \
  $'motion.simulate{method = "euler", accel = function() return 1 end, x0 = 0, v0 = 0, dt = 1, steps = 3}\n'
expect_stdout $'{t = {0.0, 1.0, 2.0, 3.0}, v = {0.0, 1.0, 2.0, 3.0}, x = {0.0, 0.0, 1.0, 3.0}}\n'
pretty "w:planes() and w:contacts() show their fields" \
  $'w = world{} w:add_plane{normal = vec3(0, 1, 0), offset = 0, restitution = 0.5, friction = 0.25}\nw:add(body.sphere{mass = 1, radius = 0.5, position = vec3(0, 0.45, 0)}) w:step(0.01)\nw:planes()\nw:contacts()\n'
expect_stdout_contains "{{friction = 0.25, normal = (0, 1, 0), offset = 0.0, restitution = 0.5"
expect_stdout_contains "    normal = (0, 1, 0),"
expect_stdout_contains "    normal_impulse = "
expect_stderr_empty

finish
