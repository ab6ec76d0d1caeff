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
start=$(date +%s)
expect "infinite loop is stopped" 1 "stopped: the instruction limit" -- \
  "$rigidlab" check "$here/infinite_loop.lua"
expect "unbounded allocation is stopped" 1 "stopped: the memory limit" -- \
  "$rigidlab" check "$here/memory_hog.lua"
elapsed=$(($(date +%s) - start))
if ((elapsed > 30)); then
  echo "FAIL runaway lessons took ${elapsed} s to stop"; failures=$((failures + 1))
fi
expect "the rest still run after a runaway lesson" 1 "1 passed, 2 failed" -- \
  "$rigidlab" check "$here/infinite_loop.lua" "$here/good.lua" "$here/wrong.lua"
expect "lessons outside lessons/ run in the sandbox" 0 "1 passed, 0 failed" -- \
  "$rigidlab" check "$here/untrusted.lua"
expect "unknown lesson is a usage error" 2 "no lesson 'no-such-lesson'" -- \
  "$rigidlab" check no-such-lesson
expect "lesson runs straight through without a terminal" 0 "Step 2/2: A table" -- \
  "$rigidlab" lesson "$here/good.lua"

((failures == 0)) && echo "all checker tests passed" || exit 1
