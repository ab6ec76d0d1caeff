#!/usr/bin/env bash
# `rigidlab check` on the fixture lessons: a passing lesson, a wrong value, an infinite loop
# and unbounded allocation. Usage: checker_test.sh RIGIDLAB
set -uo pipefail
rigidlab=$1
here=$(cd "$(dirname "$0")" && pwd)
failures=0

expect() {  # expect NAME WANT_EXIT WANT_TEXT -- command...
  local name=$1 want_exit=$2 want_text=$3
  shift 4
  local out exit_code
  out=$("$@" 2>&1)
  exit_code=$?
  if [[ $exit_code -ne $want_exit ]] || ! grep -qF -- "$want_text" <<<"$out"; then
    echo "FAIL $name: exit $exit_code (want $want_exit), output:"
    echo "$out" | sed 's/^/    /'
    echo "  expected to contain: $want_text"
    failures=$((failures + 1))
  else
    echo "ok   $name"
  fi
}

expect "passing lesson" 0 "1 passed, 0 failed" -- "$rigidlab" check "$here/good.lua"
expect "wrong value" 1 "0 passed, 1 failed" -- "$rigidlab" check "$here/wrong.lua"
expect "wrong value shows got and want" 1 "two and two: got 4, want 5" -- \
  "$rigidlab" check "$here/wrong.lua"
expect "an error object that is not a string is described" 1 \
  "error: step 1: (error object is a table value)" -- "$rigidlab" check "$here/error_objects.lua"
expect "an error object's __tostring is used" 1 "error: a described failure" -- \
  "$rigidlab" lesson "$here/error_objects.lua"
# (a small instruction limit: the default one is tested once below; 500 million
# instructions take seconds, more on a loaded machine)
expect "infinite loop is stopped" 1 "stopped: the instruction limit" -- \
  "$rigidlab" check --max-instructions 1e7 "$here/infinite_loop.lua"
expect "unbounded allocation is stopped" 1 "stopped: the memory limit" -- \
  "$rigidlab" check "$here/memory_hog.lua"
expect "the rest still run after a runaway lesson" 1 "1 passed, 2 failed" -- \
  "$rigidlab" check --max-instructions 1e7 "$here/infinite_loop.lua" "$here/good.lua" "$here/wrong.lua"

# Each lesson runs in its own process: one stuck in a C function is killed at the deadline
# (time limit + 1 s), one huge w:step is stopped inside the engine, and the rest still run.
start=$(date +%s)
expect "a C function that never returns is stopped" 1 \
  "error: stopped: the time limit (1 s) reached in a C function" -- \
  "$rigidlab" check --timeout 1 "$here/stuck_in_c.lua" "$here/huge_step.lua" "$here/good.lua"
expect "a huge w:step is stopped inside the engine" 1 \
  "error: step 1: $here/huge_step.lua:11: stopped: the time limit (1 s) reached" -- \
  "$rigidlab" check --timeout 1 "$here/huge_step.lua"
expect "the lessons after them still run" 1 "1 passed, 2 failed" -- \
  "$rigidlab" check --timeout 1 "$here/stuck_in_c.lua" "$here/huge_step.lua" "$here/good.lua"
elapsed=$(($(date +%s) - start))
if ((elapsed > 40)); then  # a margin for a loaded machine: the point is that they stop
  echo "FAIL stuck lessons took ${elapsed} s to stop (want about 2 + 1 + 2 + 1 s)"; failures=$((failures + 1))
fi
expect "the stuck lesson is named by its id" 1 "FAIL fixture-stuck-in-c" -- \
  "$rigidlab" check --timeout 1 "$here/stuck_in_c.lua"

# A crash (a signal) or os.exit in a lesson is that lesson's failure, not the checker's end.
# Lessons in the lesson directory are trusted (no sandbox): they can do both.
trusted_dir=$(mktemp -d)
trap 'rm -rf "$trusted_dir"' EXIT
cat >"$trusted_dir/fixture-crash.lua" <<'LESSON'
return lesson{id = "fixture-crash", title = "Crashes", source = "tests",
  steps = {{title = "Check", text = "One check.", run = function(ctx) ctx:expect("one", 1, 1) end},
           {title = "Crash", text = "SIGABRT, as abort() sends.", run = function(ctx) os.execute("exec >/dev/null 2>&1; kill -ABRT $PPID; sleep 5") end}}}
LESSON
cat >"$trusted_dir/fixture-exits.lua" <<'LESSON'
return lesson{id = "fixture-exits", title = "Exits", source = "tests",
  steps = {{title = "Exit", text = "os.exit(0).", run = function(ctx) ctx:expect("one", 1, 1) os.exit(0) end}}}
LESSON
cp "$here/good.lua" "$trusted_dir/fixture-good.lua"
expect "a crashing lesson fails with its signal" 1 "error: crashed: signal 6 (Aborted)" -- \
  env RIGIDLAB_LESSONS="$trusted_dir" "$rigidlab" check fixture-crash
expect "the crash keeps the checks of the steps before it" 1 "FAIL fixture-crash                1/1 checks" -- \
  env RIGIDLAB_LESSONS="$trusted_dir" "$rigidlab" check fixture-crash
expect "os.exit(0) in a lesson is no pass" 1 "error: the lesson ended the process (exit status 0)" -- \
  env RIGIDLAB_LESSONS="$trusted_dir" "$rigidlab" check fixture-exits
expect "the other lessons still run" 1 "1 passed, 2 failed" -- \
  env RIGIDLAB_LESSONS="$trusted_dir" "$rigidlab" check fixture-crash fixture-exits fixture-good

# check takes the limit options (the defaults otherwise) and refuses other options.
expect "--max-instructions overrides the default" 1 \
  "stopped: the instruction limit (1000000 instructions) reached" -- \
  "$rigidlab" check --max-instructions 1e6 "$here/infinite_loop.lua"
expect "the default instruction limit" 1 "stopped: the instruction limit (500000000 instructions) reached" -- \
  "$rigidlab" check --timeout 0 "$here/infinite_loop.lua"
expect "--max-memory overrides the default" 1 "stopped: the memory limit (16 MB) reached" -- \
  "$rigidlab" check --max-memory=16 "$here/memory_hog.lua"
expect "--timeout overrides the default" 1 "stopped: the time limit (0.5 s) reached" -- \
  "$rigidlab" check --timeout 0.5 --max-instructions 0 "$here/infinite_loop.lua"
expect "a bad limit is a usage error" 2 "rigidlab: '--timeout' needs a number of seconds >= 0, got 'soon'" -- \
  "$rigidlab" check --timeout soon "$here/good.lua"
expect "an unknown option is a usage error" 2 "unrecognized option '--fast' for 'check'" -- \
  "$rigidlab" check --fast "$here/good.lua"

expect "lessons outside lessons/ run in the sandbox" 0 "1 passed, 0 failed" -- \
  "$rigidlab" check "$here/untrusted.lua"
expect "unknown lesson is a usage error" 2 "no lesson 'no-such-lesson'" -- \
  "$rigidlab" check no-such-lesson
expect "lesson runs straight through without a terminal" 0 "Step 2/2: A table" -- \
  "$rigidlab" lesson "$here/good.lua"
expect "a lesson from outside lessons/ is stepped through under the check limits" 1 \
  "error: $here/infinite_loop.lua:4: stopped: the instruction limit (10000000 instructions) reached" -- \
  "$rigidlab" lesson --max-instructions 1e7 "$here/infinite_loop.lua"

((failures == 0)) && echo "all checker tests passed" || exit 1
