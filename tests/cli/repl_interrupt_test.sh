#!/usr/bin/env bash
# Ctrl-C and Tab in the REPL whatever the code does (issue 12, item 10), driven through tmux:
# Ctrl-C stops a loop inside a coroutine (hooks are per thread) and inside a script's own hook
# setup; a second Ctrl-C does not kill the REPL; Tab completion runs none of the user's code,
# so an __index that loops on _G cannot hang it. Exit 77 (CTest: skipped) without tmux.
# Usage: repl_interrupt_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"
source "$(dirname "$0")/terminal.sh"

start HOME="$home"
wait_for "first prompt" '^> $'

enter 'co = coroutine.wrap(function() print("spinning") while true do end end) co()'
wait_for "a loop inside a coroutine runs" '^spinning$'
key C-c
wait_for "Ctrl-C interrupts it" '^(\^C)?stdin:1: interrupted!$'
enter '2*3'
wait_for "the REPL goes on" '^6$'

enter 'co = coroutine.create(function() print("nested") while true do end end) coroutine.resume(co)'
wait_for "a loop inside coroutine.resume runs" '^nested$'
key C-c
enter 'print(coroutine.status(co))'
wait_for "Ctrl-C ends the coroutine; resume returns its error" '^dead$'

enter 'co = coroutine.wrap(function() debug.sethook() print("unhooked") while true do end end) co()'
wait_for "a coroutine that clears its hook runs" '^unhooked$'
key C-c
wait_for "Ctrl-C still interrupts it" '^(\^C)?stdin:1: interrupted!$'

# Ctrl-C twice in a row: the second one must not kill the REPL.
enter 'co = coroutine.wrap(function() print("twice") for i = 1, 1e12 do end end) co()'
wait_for "another loop" '^twice$'
key C-c
key C-c
enter '7*6'
wait_for "two Ctrl-Cs: the REPL is still there" '^42$'

# Tab runs no user code: an __index on _G that loops forever, reached by the completion of a
# method of a value whose type name (__name) is no global.
# (A statement, not an expression: the REPL would print the whole of _G, and under load the
# keys typed below arrived while it was still printing: '25' was not on the screen in 15 s.)
enter 'local _ = setmetatable(_G, {__index = function() while true do end end})'
enter 'x = setmetatable({}, {__name = "no_such_type"})'
type_text 'x:'
key Tab
# Ctrl-C is a signal, not a key in the input queue: sent before the REPL has read what was typed,
# it would reach the REPL first and the typed text would stay on the next line ('x:5*5').
wait_for "the REPL read 'x:' and the Tab" '> x:$'
wait_reading "the REPL handled the Tab and waits for a key"
key C-c
enter '5*5'
wait_for "Tab on a value whose type loops in _G's __index returns" '^25$'
type_text 'no_such_glo'
key Tab
wait_for "the REPL read 'no_such_glo' and the Tab" '> no_such_glo$'
wait_reading "the REPL handled the Tab and waits for a key"
key C-c
enter '4*4'
wait_for "Tab on a missing global returns" '^16$'

key C-d
wait_exit "Ctrl-D at the prompt exits 0" 0

# With a time limit the REPL has a second thread, the watchdog's. The kernel gives a Ctrl-C to
# any thread that does not block it, and one taken there would not wake the main thread from
# its wait for a key: every thread but the main one must block SIGINT (cli/watchdog.cpp).
start HOME="$home" -- --timeout 1000
wait_for "with --timeout: the prompt" '^> $'
enter 'print("timed")'
wait_for "with --timeout: a chunk runs" '^timed$'
case_name="with --timeout: only the main thread takes Ctrl-C"
shell=$(tmux -S "$socket" display -p '#{pane_pid}' 2>/dev/null || true)
pid=$(pgrep -P "${shell:-0}" 2>/dev/null | head -1 || true)
if [[ -n $pid && -r /proc/$pid/task ]]; then
  others=0 taking=0
  for task in /proc/"$pid"/task/*; do
    [[ ${task##*/} == "$pid" ]] && continue
    others=$((others + 1))
    blocked=$(awk '/^SigBlk:/ {print $2}' "$task/status")
    ((16#$blocked & 2)) || taking=$((taking + 1))  # bit 1: SIGINT (2)
  done
  ((others > 0 && taking == 0)) && pass || fail "$others other threads, $taking of them take SIGINT"
else
  echo "no /proc/PID/task to read: the thread check is skipped"
fi
key C-d
wait_exit "with --timeout: Ctrl-D exits 0" 0

# A Ctrl-C that comes while the REPL is still handling a key (here: echoing it, with every
# write(2) made 0.3 s slow by strace) clears the line at once. It used to be noticed only when
# the next line was entered, and that line was dropped: '1+3*3' silently, no '9'.
if slow=$(slow_writes 300000); then
  fast=$rigidlab
  rigidlab=$slow
  start HOME="$home"
  wait_for "slow writes: the prompt" '^> $'
  type_text '1+'
  wait_for "slow writes: the REPL echoes '1+'" '^> 1\+$'
  key C-c
  enter '3*3'
  wait_limit=30 wait_for "a Ctrl-C while a key is handled clears the line at once" '^9$'
  rigidlab=$fast
fi

finish
