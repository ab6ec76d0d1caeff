#!/usr/bin/env bash
# `rigidlab lesson` in a real terminal, driven through tmux: it waits on a visible prompt after
# each step, Enter shows the next step, b goes back, q quits, `rigidlab lesson` alone offers a
# numbered menu, and Ctrl-C stops a long step without ending the lesson. Exit 77 (CTest: skipped) when tmux is not installed.
# Usage: lesson_terminal_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"
source "$(dirname "$0")/terminal.sh"

fixture=$(cd "$(dirname "$0")/../lessons" && pwd)/three_steps.lua
step_prompt='^\[Enter\] next step +b back +q quit > $'
count_on_screen() { screen | grep -cE -- "$1" || true; }
linger=1  # the screen after the lesson has ended is part of what is tested

start -- lesson "$fixture"
wait_for "the first step is shown" '^-- Step 1/3: First -+$'
wait_for "its check is shown" '^  ✓ one: got 1, want 1$'
wait_for "then a prompt" "$step_prompt"
sleep 0.3
case_name="the lesson waits: no second step before Enter"
screen | grep -qE '^-- Step 2/3' && fail "step 2 was shown without Enter" || pass

key Enter
wait_for "Enter shows the next step" '^-- Step 2/3: Second -+$'
enter b
wait_for "b goes back to the first step" '^  ✓ one: got 1, want 1$'
case_name="the first step is shown twice"
until (($(count_on_screen '^-- Step 1/3: First') == 2)) || ((SECONDS > 10)); do sleep 0.05; done
(($(count_on_screen '^-- Step 1/3: First') == 2)) && pass || fail "step 1 shown $(count_on_screen '^-- Step 1/3') times"
key Enter
wait_for "forward again" '^  ✓ two: got 2, want 2$'
key Enter
wait_for "the last step" '^-- Step 3/3: Third -+$'
wait_for "a summary after the last step" '^[0-9]+ of [0-9]+ checks passed ✓$'
wait_exit "the lesson ends by itself after the last step, exit 0" 0

start -- lesson "$fixture"
wait_for "second run: a prompt" "$step_prompt"
enter q
wait_exit "q quits, exit 0" 0

# The time limit of an untrusted lesson counts its steps, not the wait at the prompt: 1.5 s
# of reading under a 1 s limit, and the next step still runs (issue 12 item 7).
start -- lesson --timeout 1 "$fixture"
wait_for "a lesson under a 1 s limit waits at its prompt" "$step_prompt"
sleep 1.5
key Enter
wait_for "after 1.5 s at the prompt the next step runs" '^  ✓ two: got 2, want 2$'
enter q
wait_exit "and quits with 0" 0

mkdir "$scratch/lessons"
cp "$fixture" "$scratch/lessons/"
start RIGIDLAB_LESSONS="$scratch/lessons" -- lesson
wait_for "rigidlab lesson alone shows a numbered menu" '^ +1  fixture-steps +Three short steps +tests$'
wait_for "and asks for a lesson" '^lesson number or id \(q quits\) > $'
enter 1
wait_for "a number opens that lesson" '^-- Step 1/3: First -+$'
enter q
wait_for "q returns to the menu" '^lesson number or id \(q quits\) > $'
enter no-such-lesson
wait_for "an unknown id is refused" "^no lesson 'no-such-lesson'$"
enter q
wait_exit "q at the menu exits 0" 0

# Ctrl-C during a step's run stops it (inside w:step) and reports it; the lesson goes on.
long=$(cd "$(dirname "$0")/../lessons" && pwd)/long_step.lua
start -- lesson "$long"
wait_for "a step with a huge w:step starts" '^stepping$'
sleep 0.3
key C-c
wait_for "Ctrl-C stops the step and the error says so" '^(\^C)?  error: .*long_step\.lua:14: interrupted!$'
wait_for "the lesson waits at its prompt" "$step_prompt"
key Enter
wait_for "the next step runs" '^  ✓ after: got 2, want 2$'
wait_for "the summary has no tick: a step failed" '^1 of 1 checks passed$'
wait_exit "and the exit status is 1" 1

finish
