#!/usr/bin/env bash
# `rigidlab lesson` in a real terminal of 80x40, driven through tmux, as a student meets it
# (issue 17 "the tour"): each step waits on a prompt; keys act at once, without Enter (Enter
# or → next, b or ← back, r runs the step again, c shows its code, m the menu, q quits, any
# other key the key help); the end of a lesson shows its summary and the next lesson's title,
# and Enter starts that one; a typo at the menu is answered with the closest ids and stays on
# screen; --from starts at a step; Ctrl-C stops a long step without ending the lesson; the
# time limit of an untrusted lesson does not count the wait at the prompt.
# Exit 77 (CTest: skipped) when tmux is not installed.
# Usage: lesson_terminal_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"
terminal_columns=80
terminal_rows=40
source "$(dirname "$0")/terminal.sh"

fixtures=$(cd "$(dirname "$0")/../lessons" && pwd)
fixture=$fixtures/three_steps.lua
step_prompt='^\[Enter\] next step   b back   c code   r again   q quit > '
# the screen and what scrolled off it
history() { tmux -S "$socket" capture-pane -p -J -S - 2>/dev/null || true; }
count_on_screen() { history | grep -cE -- "$1" || true; }
wait_count() {  # wait_count NAME REGEX N: until REGEX matches N lines of the screen
  case_name=$1
  local deadline=$((SECONDS + wait_limit))
  until (($(count_on_screen "$2") == $3)) || ((SECONDS > deadline)); do sleep 0.05; done
  (($(count_on_screen "$2") == $3)) && pass || fail "/$2/ on $(count_on_screen "$2") lines, want $3"
}
linger=1  # the screen after the lesson has ended is part of what is tested

# ---- stepping through one lesson -------------------------------------------------------------
start -- lesson "$fixture"
wait_for "the first step is shown" '^-- Step 1/3: First -+$'
wait_for "its check is shown" '^  ✓ one: got 1, want 1$'
wait_for "then a prompt" "$step_prompt"
sleep 0.3
case_name="the lesson waits: no second step before a key"
screen | grep -qE '^-- Step 2/3' && fail "step 2 was shown without a key" || pass
key Enter
wait_for "Enter shows the next step" '^-- Step 2/3: Second -+$'
key b
wait_count "b goes back at once, without Enter" '^-- Step 1/3: First' 2
key r
wait_count "r runs the step again" '^-- Step 1/3: First' 3
key x
wait_for "an unknown key shows the keys" '^  keys: Enter \(or →\) next step, b \(or ←\) back, r run this step again, c show its$'
case_name="and does nothing else"
(($(count_on_screen '^-- Step') == 4)) && pass || fail "a step ran"
key Right
wait_count "the right arrow is the next step" '^-- Step 2/3: Second' 2
key Left
wait_count "the left arrow goes back" '^-- Step 1/3: First' 4
key Enter
key Enter
wait_for "the last step" '^-- Step 3/3: Third -+$'
wait_for "a summary: steps run again count once" '^3 of 3 checks passed ✓$'
wait_for "a file outside the lesson folders has no next lesson" '^\[Enter\] quit   m menu > $'
key Enter
wait_exit "Enter there ends the lesson, exit 0" 0

start -- lesson "$fixture"
wait_for "second run: a prompt" "$step_prompt"
key q
wait_exit "q quits at once, exit 0" 0

start -- lesson --from 2 "$fixture"
wait_for "--from 2 starts at step 2" '^-- Step 2/3: Second -+$'
case_name="and step 1 is not shown"
screen | grep -qE '^-- Step 1/3' && fail "step 1 was shown" || pass
key Enter
wait_for "the summary says which steps ran" '^2 of 2 checks passed in 2 of 3 steps$'
key q
wait_exit "q at the end quits, exit 0" 0

# ---- c: the step's code, ready for the REPL --------------------------------------------------
mkdir "$scratch/code"
cat >"$scratch/code/code.lua" <<'LESSON'
local mass, size = 2, vec3(1, 0.5, 0.25)
local function box() return body.box{mass = mass, size = size} end
return lesson{id = "code", title = "Code", source = "tests", steps = {
  {title = "Box", text = "A box.", run = function(ctx)
    local b = box()
    ctx:expect("mass", b.mass, 2)
  end}}}
LESSON
start -- lesson "$scratch/code/code.lua"
wait_for "a lesson with values and a function at its top" '^\[Enter\] quit   m menu > $'
key c
wait_for "c shows the step's code" '^  -- the code of step 1 \(code.lua, lines 4 to 7\); to try it, paste these'
wait_for "with the values it uses" '^  size = vec3\(1, 0.5, 0.25\)$'
wait_for "the functions it calls, with what they use" '^  function box\(\) return body.box\{mass = mass, size = size\} end$'
wait_for "its own code" '^  run = function\(ctx\)$'
wait_for "and a call with a ctx" '^  run\(lesson_context\(\)\)$'
screen | sed -n '/^  mass = 2$/,/^  run(lesson_context())$/p' | sed 's/^  //' >"$scratch/pasted.lua"
run "the shown code runs as it is" -- "$rigidlab" "$scratch/pasted.lua"
expect_status 0
expect_stdout_contains "  ✓ mass: got 2, want 2"
key q
wait_exit "q quits" 0

# ---- the tour: the end of a lesson leads to the next one ------------------------------------
mkdir "$scratch/course"
for id in first second; do
  cat >"$scratch/course/$id.lua" <<LESSON
return lesson{id = "$id", title = "The $id lesson", source = "course notes", steps = {
  {title = "Only", text = "One step.", run = function(ctx) ctx:expect("$id", 1, 1) end}}}
LESSON
done
printf 'first\nsecond\n' >"$scratch/course/tour.txt"
start RIGIDLAB_LESSONS="$scratch/course" -- lesson first
wait_for "a course lesson shows where it comes from" "^  from:   $scratch/course\$"
wait_for "finishing a lesson shows its summary" '^1 of 1 checks passed ✓$'
wait_for "and the next lesson's title" '^Next: second — The second lesson$'
wait_for "with its prompt" '^\[Enter\] next lesson   m menu   q quit > $'
key Enter
wait_for "Enter starts the next lesson" '^second — The second lesson$'
wait_for "the last lesson says so" '^That was the last lesson of the tour\.$'
key m
wait_for "m opens the menu" '^lesson number or id \(q quits\) > $'
wait_for "the course's lessons after the built-in ones" "^lessons from $scratch/course \(RIGIDLAB_LESSONS\)\$"
case_name="the built-in lessons come first"
built_in_line=$(screen | grep -n '^built-in lessons' | cut -d: -f1)
course_line=$(screen | grep -n '^lessons from' | cut -d: -f1)
[[ -n $built_in_line && -n $course_line ]] && ((built_in_line < course_line)) && pass ||
  fail "built-in at line '$built_in_line', course at '$course_line'"
type_text dzhanibekof
wait_for "the menu's answer is echoed (no echo is for a lesson's keys only)" \
  '^lesson number or id \(q quits\) > dzhanibekof$'
key Enter
wait_for "a typo at the menu gets the closest id" "^no lesson 'dzhanibekof'; did you mean 'dzhanibekov'\?$"
wait_for "and the prompt again" '^lesson number or id \(q quits\) > $'
sleep 0.3
case_name="the message stays on screen (the menu is not printed over it)"
screen | grep -qE "^no lesson 'dzhanibekof'" && pass || fail "the message scrolled away"
enter second
wait_for "an id at the menu opens that lesson" '^-- Step 1/1: Only -+$'
key q
wait_exit "q quits from a lesson opened at the menu, exit 0" 0

start RIGIDLAB_LESSONS="$scratch/course" -- lesson
wait_for "the menu fits 40 rows: numbers and ids in columns" '^ +1  particle-system +[0-9]+  '
wait_for "and the prompt is on screen" '^lesson number or id \(q quits\) > $'
enter 1
wait_for "a number opens that lesson" '^-- Step 1/[0-9]+: '
key m
wait_for "m in a lesson returns to the menu" '^lesson number or id \(q quits\) > $'
enter q
wait_exit "q at the menu exits 0" 0

# ---- the terminal after the lesson ------------------------------------------------------------
# Echo is off while a lesson runs; a trusted lesson that ends the process (os.exit) leaves the
# terminal echoing again, as the shell needs it.
mkdir "$scratch/exits"
cat >"$scratch/exits/exits.lua" <<'LESSON'
return lesson{id = "exits", title = "Exits", source = "tests", steps = {
  {title = "Exit", text = "Ends the process.", run = function(ctx) os.exit(3) end}}}
LESSON
socket=$scratch/tmux.exits.socket
tmux -S "$socket" new-session -d -x 80 -y 40 \
  "env RIGIDLAB_LESSONS='$scratch/exits' '$rigidlab' lesson exits; stty -a >'$scratch/stty.tmp'; mv '$scratch/stty.tmp' '$scratch/stty'"
case_name="os.exit in a lesson: the terminal echoes afterwards"
for _ in $(seq 100); do [[ -f $scratch/stty ]] && break; sleep 0.05; done
grep -qE '(^| )echo( |$)' "$scratch/stty" 2>/dev/null && pass || fail "stty: $(grep -oE -- '-?echo ' "$scratch/stty" 2>/dev/null)"

# ---- limits and Ctrl-C -----------------------------------------------------------------------
# The time limit of an untrusted lesson counts its steps, not the wait at the prompt: 1.5 s
# of reading under a 1 s limit, and the next step still runs (issue 12 item 7).
start -- lesson --timeout 1 "$fixture"
wait_for "a lesson under a 1 s limit waits at its prompt" "$step_prompt"
sleep 1.5
key Enter
wait_for "after 1.5 s at the prompt the next step runs" '^  ✓ two: got 2, want 2$'
key q
wait_exit "and quits with 0" 0

# Ctrl-C during a step's run stops it (inside w:step) and reports it; the lesson goes on.
start -- lesson "$fixtures/long_step.lua"
wait_for "a step with a huge w:step starts" '^stepping$'
sleep 0.3
key C-c
wait_for "Ctrl-C stops the step and the error says so" '^(\^C)?  error: .*long_step\.lua:14: interrupted!$'
wait_for "the lesson waits at its prompt" "$step_prompt"
key Enter
wait_for "the next step runs" '^  ✓ after: got 2, want 2$'
wait_for "the summary has no tick: a step failed" '^1 of 1 checks passed$'
key Enter
wait_exit "and the exit status is 1" 1

# A key typed as the step's prompt appears, stretched by strace where it can trace (each write
# 0.3 s late): the terminal does not echo it, the lesson shows it once ("> c", not "> cc").
if slow=$(slow_writes 300000); then
  fast=$rigidlab
  rigidlab=$slow
  start -- lesson "$fixture"
  wait_for "slow writes: the step's prompt" "$step_prompt"
  key c
  wait_for "c typed as the prompt appears shows the code" '^  -- the code of step 1 '
  case_name="and the key is shown once"
  history | grep -qE "${step_prompt}c\$" && pass || fail "the prompt line is '$(history | grep -E "$step_prompt" | head -1)'"
  rigidlab=$fast  # the session ends with the test: its slow writes would outlast wait_exit
else
  echo "no strace that can trace here, or a sanitizer build: the slow-write case is skipped"
fi

finish
