#!/usr/bin/env bash
# The REPL in a terminal, driven through tmux: banner, prompts, values, Ctrl-C interrupting a
# loop and one huge w:step (the world left as before the step) and clearing a line, multi-line
# chunks, Tab completion, tracebacks, Ctrl-D, and the history in $HOME/.rigidlab_history.
# Exit 77 (CTest: skipped) when tmux is not installed.
# Usage: repl_terminal_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"
source "$(dirname "$0")/terminal.sh"
history=$home/.rigidlab_history

start HOME="$home"
wait_for "banner" '^rigidlab [0-9.]+ \(Lua 5\.4\.[0-9]+\) — help\(\) lists topics, Ctrl-D exits$'
wait_for "first prompt" '^> $'

enter '1+1'
wait_for "an expression prints its value" '^2$'
enter 'r = {} for i = 1, 40 do r[i] = i * 1000 end r.name = "r"'
enter 'r'
wait_for "a table shows its fields, packed to the terminal's width (100)" \
  '^  1000, 2000, 3000, 4000, 5000, 6000, 7000, 8000, 9000, 10000, 11000, 12000, 13000, 14000, 15000,$'
wait_for "then its named fields, one a line" '^  name = "r"$'

enter 'print("looping") for i=1,1e12 do end'
wait_for "a long loop starts" '^looping$'
key C-c
wait_for "Ctrl-C interrupts a running loop" 'interrupted!$'
wait_for "with a traceback" '^stack traceback:$'
enter '2*3'
wait_for "the REPL goes on after Ctrl-C" '^6$'

# Ctrl-C inside one huge w:step (hours: 10000 substeps, 1000 solver sweeps over 100 boxes)
# stops it where the engine polls, and the world is exactly as before the step.
enter 'w = world{iterations = 1000} w:add_plane{normal = vec3(0, 1, 0), offset = 0}'
enter 'for i = 0, 99 do w:add(body.box{mass = 1, size = vec3(1, 1, 1), position = vec3(i % 10 * 1.01, 0.5 + i // 10, 0)}) end'
enter 'b = w:bodies()[55] b.angular_velocity = vec3(0, 1, 0) w:step(0.01) t0, p0, q0 = w.time, b.position, b.orientation'
enter 'w.substeps = 10000 print("stepping") w:step(0.01)'
wait_for "a huge step starts" '^stepping$'
sleep 0.3
key C-c
wait_for "Ctrl-C interrupts the step" '^(\^C)?stdin:1: interrupted!$'
enter 'print(w.time == t0 and b.position == p0 and b.orientation == q0 and "unchanged")'
wait_for "time and bodies are as before the step" '^unchanged$'
enter 'w.substeps = 1 w:step(0.01) print(w.time == t0 + 0.01 and b.orientation ~= q0 and "stepped")'
wait_for "and the world steps normally afterwards" '^stepped$'
key C-l  # a clear screen for the tests below, which count prompts on it

type_text 'error("this line was never run")'
wait_for "a line typed" '^> error\("this line was never run"\)$'
wait_reading "the REPL waits for the next key"
key C-c
enter '7*6'
wait_for "Ctrl-C at the prompt clears the line" '^42$'
case_name="the cleared line did not run"
screen | grep -q 'never run$' && fail "it ran" || pass

enter 'function sq(x)'
wait_for "a continuation prompt" '^>> $'
enter 'return x * x'
enter 'end'
enter 'sq(12)'
wait_for "a function typed over three lines" '^144$'

type_text 'inertia.solid_bo'
key Tab
wait_for "Tab completes a field" '^> inertia\.solid_box$'
key Enter
wait_for "a function value prints" '^(builtin: |function: )'

enter 'v = vec3(1, 2, 3)'
type_text 'v:cro'
key Tab
type_text '(vec3(0, 0, 1))'
key Enter
wait_for "Tab completes a method of a vec3" '^\(2, -1, 0\)$'

enter 'vec3(1,2,3):cross(5)'
wait_for "a binding error names function and argument" \
  "^stdin:1: bad argument #1 to 'vec3:cross' \(vec3 expected, got number\)$"
wait_for "a runtime error has a traceback" "in method 'cross'"

enter 'function unfinished()'
wait_for "continuation" '^>> $'
before=$(prompt_count)
key C-d
wait_for "Ctrl-D inside a chunk reports it" "^stdin:1: 'end' expected near <eof>$"
wait_prompt "and the REPL goes on" $((before + 1))
enter '1+2'
wait_for "still evaluating" '^3$'

key C-d
wait_exit "Ctrl-D at the prompt exits 0" 0
case_name="the session is gone"
tmux -S "$socket" has-session 2>/dev/null && fail "still running" || pass

# libedit's history file: a header line, then one entry a line with spaces and newlines
# written as octal escapes (strvis).
case_name="the history file"
if [[ ! -f $history ]]; then
  fail "no $history"
else
  for entry in '_HiStOrY_V2_' '1+1' 'print("looping")\040for\040i=1,1e12\040do\040end' '2*3' '7*6' \
      'function\040sq(x)\012return\040x\040*\040x\012end' 'sq(12)' 'function\040unfinished()' '1+2'; do
    grep -qxF -- "$entry" "$history" && pass || fail "no line '$entry' in the history"
  done
  grep -qF 'never\040run' "$history" && fail "the cleared line is in the history" || pass
fi

# A new session loads the history: Up recalls the last entry; repeating it adds no duplicate.
start HOME="$home"
wait_for "second session" '^> $'
# Up at once, as the prompt appears: libedit shows the prompt before it switches the terminal
# to raw mode, and a key typed in between was echoed by the terminal ("> 1+2A" once in CI);
# the REPL turns echo off before the prompt.
key Up
wait_for "Up recalls the last line of the previous session" '^> 1\+2$'
key Enter
wait_for "and it runs" '^3$'
enter 'os.exit(5)'
wait_exit "os.exit(5) in the REPL" 5
case_name="a repeated line is stored once; os.exit's line is saved"
[[ $(tail -n 2 "$history") == $'1+2\nos.exit(5)' ]] && pass || fail "history ends with: $(tail -n 3 "$history")"

# Without HOME, or with a HOME where nothing can be written, the REPL still works.
start -u HOME
wait_for "no HOME" '^> $'
enter '10/4'
wait_for "no HOME: evaluates" '^2\.5$'
key C-d
wait_exit "no HOME: exits 0" 0

stderr_file=$scratch/stderr
start HOME=/nonexistent/rigidlab-test
wait_for "unwritable history" '^> $'
enter '2^3'
wait_for "unwritable history: evaluates" '^8\.0$'
key C-d
wait_exit "unwritable history: exits 0" 0
case_name="unwritable history: one warning on stderr"
[[ $(cat "$scratch/stderr") == "rigidlab: the history is not saved (cannot write /nonexistent/rigidlab-test/.rigidlab_history: No such file or directory)" ]] \
  && pass || fail "stderr: $(cat "$scratch/stderr")"

# The same moment made long, where strace can trace: every write of rigidlab returns 0.5 s
# late (strace's fault injection), so Up comes while the prompt is shown and the terminal is
# still in cooked mode. A recalled line shorter than the echoed "^[[A" showed the echo's tail.
if slow=$(slow_writes 500000); then
  printf '_HiStOrY_V2_\n7\n' >"$history"
  fast=$rigidlab
  rigidlab=$slow
  stderr_file=""
  start HOME="$home"
  wait_for "slow writes: the prompt" '^> $'
  key Up
  wait_for "Up typed before raw mode recalls the line" '^> 7'
  sleep 1
  case_name="and the line shows nothing else"
  screen | grep -qE '^> 7$' && pass || fail "the line is '$(screen | grep -E '^> 7')'"
  rigidlab=$fast  # the session ends with the test: its slow writes would outlast wait_exit
else
  echo "no strace that can trace here, or a sanitizer build: the slow-write case is skipped"
fi

# Multibyte input in a UTF-8 terminal: the line editor's key reader decodes the bytes itself
# (cli/line_reader.cpp), so é (2 bytes) and → (3) arrive whole, and editing moves and deletes
# characters, not bytes.
LC_ALL=C.UTF-8 start HOME="$home" LC_ALL=C.UTF-8
wait_for "UTF-8: the prompt" '^> $'
enter 's = "é→"'
enter 'print(#s, s == "\u{e9}\u{2192}")'
wait_for "é and → reach Lua as their 5 bytes" '^5[[:space:]]+true$'
type_text 'x = "aé'
key BSpace
enter 'b"'
enter 'print(x)'
wait_for "Backspace deletes é whole" '^ab$'
type_text 'y = "é"'
key Left Left
enter 'z'
enter 'print(y)'
wait_for "Left moves over é whole" '^zé$'
key C-d
wait_exit "UTF-8: Ctrl-D exits 0" 0

finish
