#!/usr/bin/env bash
# The options of rigidlab, as lua.c's: -e (in order), -l, -i, -v, -h, -E, -W, --, usage errors.
# Usage: options_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"

run "-e runs code" -- "$rigidlab" -e 'print(1 + 1)'
expect_status 0
expect_stdout $'2\n'
expect_stderr_empty

run "-e is repeatable and runs in order" -- "$rigidlab" -e 'x = 2' -e 'x = x * 10' -e 'print(x)'
expect_status 0
expect_stdout $'20\n'

run "-eCODE without a space" -- "$rigidlab" '-eprint("joined")'
expect_stdout $'joined\n'

run "rigidlab names are globals" -- "$rigidlab" -e 'print(vec3(1, 2, 3):cross(vec3(4, 5, 6)))'
expect_stdout $'(-3, 6, -3)\n'

run "-e error: message, traceback, exit 1" -- "$rigidlab" -e 'vec3(1,2,3):cross(5)'
expect_status 1
expect_stdout ""
expect_stderr_line 1 "rigidlab: (command line):1: bad argument #1 to 'vec3:cross' (vec3 expected, got number)"
expect_stderr_line 2 "stack traceback:"

run "a failing -e stops the ones after it" -- "$rigidlab" -e 'error("first")' -e 'print("second")'
expect_status 1
expect_stdout ""
expect_stderr_line 1 "rigidlab: (command line):1: first"

run "-e without its argument" -- "$rigidlab" -e
expect_status 2
expect_stdout ""
expect_stderr_line 1 "rigidlab: '-e' needs an argument"
expect_stderr_line 2 "Try 'rigidlab --help' for more information."

run "-e followed by an option" -- "$rigidlab" -e -i
expect_status 2
expect_stderr_line 1 "rigidlab: '-e' needs an argument"

run "unknown short option" -- "$rigidlab" -z
expect_status 2
expect_stdout ""
expect_stderr_line 1 "rigidlab: unrecognized option '-z'"
expect_stderr_line 2 "Try 'rigidlab --help' for more information."

run "unknown long option" -- "$rigidlab" --frobnicate
expect_status 2
expect_stderr_line 1 "rigidlab: unrecognized option '--frobnicate'"

run "a known letter with extra characters" -- "$rigidlab" -iv
expect_status 2
expect_stderr_line 1 "rigidlab: unrecognized option '-iv'"

# --version: the same version as require("rigidlab").version, and Lua's release.
run "the library's version" -- "$rigidlab" -e 'io.write(require("rigidlab").version)'
version=$out
run "--version" -- "$rigidlab" --version
expect_status 0
lua_release=$(sed -n 's/^rigidlab [^ ]* (\(Lua 5\.4\.[0-9]*\))$/\1/p' <<<"$out")
if [[ -z $lua_release ]]; then fail "--version prints '$out'"; else pass; fi
expect_stdout "rigidlab $version ($lua_release)"$'\n'
expect_stderr_empty
run "-v" -- "$rigidlab" -v
expect_stdout "rigidlab $version ($lua_release)"$'\n'
run "-v then -e: version, then the code" -- "$rigidlab" -v -e 'print("ran")'
expect_stdout "rigidlab $version ($lua_release)"$'\n'"ran"$'\n'

# --help lists every option and every command, and nothing runs.
for spelling in --help -h; do
  run "$spelling" -- "$rigidlab" "$spelling" -e 'print("must not run")'
  expect_status 0
  expect_stderr_empty
  [[ $out == usage:* ]] && pass || fail "help does not start with usage:"
  for item in "-e CODE" "-l MOD" "-i " "-v, --version" "-h, --help" "-E " "-W " "-- " "-  " \
              "--sandbox " "--max-instructions N" "--max-memory MB" "--timeout S" \
              "lessons" "lesson [ID|FILE]" "check [LIMITS] [ID|FILE ...]"; do
    expect_stdout_contains "  $item"
  done
  expect_stdout_contains "Exit status: 0 success; 1 a script error"
done

run "-l MOD requires into a global" -- "$rigidlab" -l rigidlab -e 'print(rigidlab.vec3 == vec3)'
expect_stdout $'true\n'
run "-l G=MOD names the global" -- "$rigidlab" -l rl=rigidlab -e 'print(rl.quat == quat)'
expect_stdout $'true\n'
run "-l of a missing module" -- "$rigidlab" -l no_such_module_here
expect_status 1
expect_stderr_line 1 "rigidlab: module 'no_such_module_here' not found:"

run "LUA_PATH is read" -- env LUA_PATH='/from/env/?.lua' "$rigidlab" -e 'print(package.path)'
expect_stdout $'/from/env/?.lua\n'
run "-E ignores LUA_PATH" -- env LUA_PATH='/from/env/?.lua' "$rigidlab" -E -e 'print(package.path)'
[[ $out != *"/from/env/"* && -n $out ]] && pass || fail "package.path is '$out'"

run "warnings are off by default" -- "$rigidlab" -e 'warn("careful")'
expect_stderr_empty
run "-W turns them on" -- "$rigidlab" -W -e 'warn("careful")'
expect_status 0
expect_stderr_line 1 "Lua warning: careful"

printf 'print("dash file", ...)\n' >"$scratch/-"
run "-- ends the options: '-' after it is a file" -- bash -c 'cd "$1" && "$2" -- - x' _ "$scratch" "$rigidlab"
expect_stdout $'dash file\tx\n'

printf 'print("script", ...)\n' >"$scratch/opt.lua"
run "-- then a script" -- "$rigidlab" -- "$scratch/opt.lua" -e
expect_stdout $'script\t-e\n'

finish
