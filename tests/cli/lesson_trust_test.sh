#!/usr/bin/env bash
# What a careless or hostile lesson, or a strange name, does to `rigidlab lesson` and `check`
# (issue 12 items 1, 4 and 7): a ctx kept past its lesson is an error, never a double free; a
# name too long, an answer too long and symlink loops are clean errors (exit 1 or 2), never an
# uncaught std::filesystem::filesystem_error; the limits of an untrusted lesson cover its
# loading and its whole run. The sanitizer build runs this under ASan.
# Usage: lesson_trust_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"
fixtures=$(cd "$(dirname "$0")/../lessons" && pwd)

expect_no_exception() {  # neither an uncaught exception nor a crash
  case_name="$case_name: no uncaught exception"
  if grep -qE "terminate called|filesystem_error|Aborted|double free" "$scratch/err"; then
    fail "stderr shows a crash" stderr
  else
    pass
  fi
}

# ---- item 1: the ctx after its lesson --------------------------------------------------------
for command in lesson check; do
  run "a ctx kept in a table whose __gc uses it after the lesson ($command)" -- \
    "$rigidlab" "$command" "$fixtures/ctx_after_end.lua"
  expect_status 1
  expect_no_exception
  case_name="nothing is checked after the end ($command)"
  grep -q "after the end" "$scratch/out" && fail "a check ran after the lesson ended" || pass
done
run "the lesson's own check is counted" -- "$rigidlab" lesson "$fixtures/ctx_after_end.lua"
expect_stdout_contains "1 of 2 checks passed"

# A trusted lesson has debug: it can call the ctx's __gc twice and dress a vec3 in its metatable.
mkdir "$scratch/trusted"
cat >"$scratch/trusted/gc.lua" <<'LESSON'
return lesson{id = "gc", title = "Finalises its ctx", source = "tests", steps = {
  {title = "Dress", text = "A vec3 in the ctx's metatable.", run = function(ctx)
    local mt = debug.getmetatable(ctx)
    local v = debug.setmetatable(vec3(1, 2, 3), mt)
    mt.__gc(v)
    local ok, message = pcall(v.expect, v, "x", 1, 1)
    ctx:expect("a vec3 is no ctx", message:match("lesson context expected, got vec3") ~= nil, true)
  end},
  {title = "Finalise", text = "Calls __gc twice.", run = function(ctx)
    local gc = debug.getmetatable(ctx).__gc
    gc(ctx)
    gc(ctx)
    print(select(2, pcall(ctx.expect, ctx, "x", 1, 2)))
  end},
  {title = "After", text = "The ctx stays finalised.", run = function(ctx)
    ctx:expect("x", 1, 1)
  end}}}
LESSON
run "a trusted lesson that finalises its ctx twice" -- \
  env RIGIDLAB_LESSONS="$scratch/trusted" "$rigidlab" lesson gc
expect_status 1
expect_no_exception
expect_stdout_contains "bad argument #1 to 'ctx:expect' (the lesson context was garbage-collected (it is used from a finaliser))"
expect_stdout_contains "  error: $scratch/trusted/gc.lua:16: calling 'ctx:expect' on bad self (the lesson context was garbage-collected"
expect_stdout_contains "1 of 1 checks passed"
run "the same in check" -- env RIGIDLAB_LESSONS="$scratch/trusted" "$rigidlab" check gc
expect_status 1
expect_no_exception
expect_stdout_contains "error: step 3: $scratch/trusted/gc.lua:16: calling 'ctx:expect' on bad self"

# ---- item 4: names and folders the filesystem refuses ----------------------------------------
long=$(printf 'a%.0s' {1..300})
for command in check lesson; do
  run "$command with a 300-character id" -- "$rigidlab" "$command" "$long"
  expect_status 2
  expect_no_exception
  expect_stderr_line 1 "rigidlab: no lesson '$(printf 'a%.0s' {1..59})…' (rigidlab lessons lists them)"
  run "$command with a 300-character file name" -- "$rigidlab" "$command" "$scratch/$long.lua"
  expect_status 2
  expect_no_exception
  expect_stderr_contains "File name too long"
done

mkdir "$scratch/loops"
cp "$fixtures/good.lua" "$scratch/loops/fixture-good.lua"
ln -s loop.lua "$scratch/loops/loop.lua"
ln -s sub "$scratch/loops/sub"
for command in check lesson; do
  run "$command of a file that is a symlink loop" -- "$rigidlab" "$command" "$scratch/loops/loop.lua"
  expect_status 2
  expect_no_exception
  expect_stderr_contains "Too many levels of symbolic links"
done
run "check of a lesson folder with a symlink loop" -- "$rigidlab" check "$scratch/loops"
expect_status 1
expect_no_exception
expect_stdout_contains "1 passed, 1 failed"
run "the list of a lesson folder with a symlink loop" -- \
  env RIGIDLAB_LESSONS="$scratch/loops" "$rigidlab" lessons
expect_status 1
expect_no_exception
expect_stdout_contains "loop"
ln -s loopdir "$scratch/loopdir"
run "a lesson folder that is itself a symlink loop" -- \
  env RIGIDLAB_LESSONS="$scratch/loopdir" "$rigidlab" lessons
expect_status 1
expect_no_exception
expect_stderr_contains "rigidlab: cannot read the lesson folder '$scratch/loopdir': Too many levels of symbolic links"
run "a long answer at the menu" --stdin "$long"$'\n'"$(printf '9%.0s' {1..300})"$'\nq\n' -- \
  env RIGIDLAB_LESSONS="$scratch/loops" "$rigidlab" lesson
expect_status 0
expect_no_exception
expect_stdout_contains "no lesson '$(printf 'a%.0s' {1..59})…'"
expect_stdout_contains "no lesson $(printf '9%.0s' {1..59})…: the lessons are numbered 1 to"

# ---- item 7: the limits of an untrusted lesson cover loading, step lookup and every step -----
SECONDS=0
run "a backtracking string.find at the top level is stopped" -- \
  "$rigidlab" lesson --timeout 1 "$fixtures/backtracking_load.lua"
expect_status 1
expect_stderr_contains "rigidlab: stopped: the time limit (1 s) reached in a C function"
case_name="stopped at the time limit and its grace period, not later"
((SECONDS < 8)) && pass || fail "took $SECONDS s"
run "the same under check" -- "$rigidlab" check --timeout 1 "$fixtures/backtracking_load.lua"
expect_status 1
expect_stdout_contains "error: stopped: the time limit (1 s) reached in a C function"

run "a steps table with __len = 2^31-1 is no list of steps" -- \
  "$rigidlab" lesson "$fixtures/endless_steps.lua"
expect_status 1
expect_stderr_contains "the file must return lesson{...} (field 'steps' must be a non-empty list of steps)"
run "the same under check" -- "$rigidlab" check "$fixtures/endless_steps.lua"
expect_status 1
expect_stdout_contains "field 'steps' must be a non-empty list of steps"

run "the instruction limit counts every step, it does not restart" -- \
  "$rigidlab" lesson --max-instructions 1e6 "$fixtures/slow_steps.lua"
expect_status 1
expect_stdout_contains "stopped: the instruction limit (1000000 instructions) reached"
expect_stdout_contains "The lesson is stopped: its limits count all of its steps."
expect_stdout_contains "✓ sum 2"
case_name="no step runs after the limit"
grep -q "Step 4/5" "$scratch/out" && fail "step 4 ran" || pass
run "the same limit lets the lesson finish when it is enough" -- \
  "$rigidlab" lesson --max-instructions 3e6 "$fixtures/slow_steps.lua"
expect_status 0
expect_stdout_contains "5 of 5 checks passed ✓"
run "check counts the same way" -- "$rigidlab" check --max-instructions 1e6 "$fixtures/slow_steps.lua"
expect_status 1
expect_stdout_contains "error: step 3:"

cat >"$scratch/top_loop.lua" <<'LESSON'
while true do end
LESSON
run "an endless loop at the top level of an untrusted lesson is stopped" -- \
  "$rigidlab" lesson --max-instructions 1e6 "$scratch/top_loop.lua"
expect_status 1
expect_stderr_contains "top_loop.lua:1: stopped: the instruction limit (1000000 instructions) reached"

run "a lesson option that is not a limit is a usage error" -- "$rigidlab" lesson --fast good
expect_status 2
expect_stderr_contains "unrecognized option '--fast' for 'lesson'"

finish
