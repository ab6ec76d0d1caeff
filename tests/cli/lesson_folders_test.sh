#!/usr/bin/env bash
# A teacher's lesson folders (issue 17 items 1 and 2), tried as a teacher would: RIGIDLAB_LESSONS
# adds folders after the built-in lessons (the list and the menu say where each comes from),
# `rigidlab check DIR` checks just one folder, an id defined twice is an error naming both
# files; checks a teacher can state: deep tables, strings, ranges, a tolerance with its reason.
# Usage: lesson_folders_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"
built_in=$(cd "$(dirname "$0")/../../lessons" && pwd)

course=$scratch/course
mkdir "$course"
cat >"$course/intro.lua" <<'LESSON'
return lesson{id = "intro", title = "Course intro", source = "course notes, week 1",
  tolerance = {rel = 1e-3, reason = "the notes give g = 9.81 to three digits"},
  steps = {
    {title = "Trusted", text = "A course folder is trusted.", run = function(ctx)
      ctx:expect("io is there", io ~= nil, true)
    end},
    {title = "Checks", text = "Deep tables and strings.", run = function(ctx)
      ctx:expect("same table", {a = 1, list = {1, 2}}, {a = 1, list = {1, 2}})
      ctx:expect("equal strings", "box", "box")
      ctx:expect_range("apex (m)", 5.1, 5, 5.2)
      ctx:expect("g", 9.8067, 9.81)
    end}}}
LESSON
cat >"$course/wrong.lua" <<'LESSON'
return lesson{id = "wrong", title = "A table that differs", source = "course notes",
  steps = {{title = "Differs", text = "a differs.", run = function(ctx)
    ctx:expect("t", {a = 1}, {a = 2})
    ctx:expect("s", "abc", "abd")
  end}}}
LESSON
printf 'wrong\nintro\n' >"$course/tour.txt"

# ---- the list and the menu -------------------------------------------------------------------
run "the list with a course folder" -- env RIGIDLAB_LESSONS="$course" "$rigidlab" lessons
expect_status 0
expect_stdout_contains "built-in lessons ($built_in)"
expect_stdout_contains "lessons from $course (RIGIDLAB_LESSONS)"
case_name="the course's lessons after the built-in ones, in the course's tour order"
order=$(grep -nE '^(particle-system|kinetic-energy|wrong|intro) ' "$scratch/out" | cut -d' ' -f1 | tr '\n' ' ')
[[ $order =~ particle-system.*kinetic-energy.*wrong.*intro ]] && pass || fail "order: $order"
run "the menu with a course folder" --stdin $'q\n' -- env RIGIDLAB_LESSONS="$course" "$rigidlab" lesson
expect_status 0
expect_stdout_contains "lessons from $course (RIGIDLAB_LESSONS)"
case_name="the menu numbers the course's lessons after the built-in ones"
built_in_count=$(ls "$built_in"/*.lua | wc -l)
grep -qE "^ *$((built_in_count + 1))  wrong " "$scratch/out" && pass || fail "no row $((built_in_count + 1)) for 'wrong'"
run "a lesson from a course folder shows its folder" -- \
  env RIGIDLAB_LESSONS="$course" "$rigidlab" lesson intro
expect_stdout_contains "  from:   $course"
expect_stdout_contains "  tolerance: rel 0.001 — the notes give g = 9.81 to three digits"
run "several folders, empty entries skipped" -- \
  env RIGIDLAB_LESSONS=":$course::$scratch/none:" "$rigidlab" lessons
expect_status 1
expect_stdout_contains "lessons from $course (RIGIDLAB_LESSONS)"
expect_stderr_contains "rigidlab: cannot read the lesson folder '$scratch/none': No such file or directory"

# ---- check DIR -------------------------------------------------------------------------------
run "check DIR checks just that folder" -- env RIGIDLAB_LESSONS="$course" "$rigidlab" check "$course"
expect_status 1
expect_stdout_contains "1 passed, 1 failed"
case_name="and none of the built-in lessons"
grep -q "particle-system" "$scratch/out" && fail "a built-in lesson was checked" || pass
expect_stdout_contains "ok   intro                        5/5 checks"
expect_stdout_contains "✗ t: got {a = 1}, want {a = 2} (key a: off by 1; tolerance rel 1e-09)"
expect_stdout_contains "✗ s: got \"abc\", want \"abd\" (strings differ at character 3)"
run "check DIR with a folder name of the working folder, no slash" -- \
  env RIGIDLAB_LESSONS="$course" bash -c 'cd "$1" && "$2" check course' _ "$scratch" "$rigidlab"
expect_status 1
expect_stdout_contains "1 passed, 1 failed"
mkdir "$scratch/spring"
run "a lesson id is the lesson, not a folder of that name" -- \
  bash -c 'cd "$1" && "$2" check spring' _ "$scratch" "$rigidlab"
expect_status 0
expect_stdout_contains "ok   spring "
rmdir "$scratch/spring"
run "a folder not in RIGIDLAB_LESSONS is checked in the sandbox" -- "$rigidlab" check "$course"
expect_stdout_contains "✗ io is there: got false, want true"
case_name="a reason that repeats the values is left out"
grep -q "want true (" "$scratch/out" && fail "$(grep 'io is there' "$scratch/out")" || pass

# ---- an id defined twice -----------------------------------------------------------------------
cp "$built_in/spring.lua" "$course/spring.lua"
twice="lesson 'spring' is defined twice: $built_in/spring.lua and $course/spring.lua"
run "an id defined twice: the list" -- env RIGIDLAB_LESSONS="$course" "$rigidlab" lessons
expect_status 1
expect_stderr_contains "rigidlab: $twice"
run "an id defined twice: lesson ID" -- env RIGIDLAB_LESSONS="$course" "$rigidlab" lesson spring
expect_status 2
expect_stderr_contains "rigidlab: $twice (rename one of them)"
run "an id defined twice: check ID" -- env RIGIDLAB_LESSONS="$course" "$rigidlab" check spring
expect_status 2
expect_stderr_contains "rigidlab: $twice (rename one of them)"
run "an id defined twice: the menu" --stdin $'q\n' -- env RIGIDLAB_LESSONS="$course" "$rigidlab" lesson
expect_stdout_contains "! $twice"
rm "$course/spring.lua"

cp "$built_in/spring.lua" "$course/springs.lua"
run "a lesson's file is named after its id" -- env RIGIDLAB_LESSONS="$course" "$rigidlab" lesson springs
expect_status 1
expect_stderr_contains "its id is 'spring', but a lesson's file is named after its id: spring.lua"
rm "$course/springs.lua"

# ---- lesson --from -----------------------------------------------------------------------------
run "--from past the last step" -- env RIGIDLAB_LESSONS="$course" "$rigidlab" lesson intro --from 3
expect_status 2
expect_stderr_line 1 "rigidlab: --from 3: lesson 'intro' has 2 steps"
run "--from needs a number" -- "$rigidlab" lesson spring --from two
expect_status 2
expect_stderr_contains "rigidlab: '--from' needs a step number >= 1, got 'two'"
run "--from 2 without a terminal" -- env RIGIDLAB_LESSONS="$course" "$rigidlab" lesson intro --from 2
expect_status 0
expect_stdout_contains "-- Step 2/2: Checks"
expect_stdout_contains "4 of 4 checks passed in 1 of 2 steps"

finish
