# Helpers for the tests that drive rigidlab in a real terminal through tmux (sourced after
# testlib.sh, not a test itself). Exits 77 (CTest: skipped) when tmux is not installed.
if ! command -v tmux >/dev/null; then
  echo "tmux is not installed: skipping the terminal tests"
  exit 77
fi
unset TMUX
socket=$scratch/tmux.socket
sessions=0
# Every tmux server of the test (one per start) ends with it; see testlib.sh for the BASHPID.
trap '[[ $BASHPID != "$$" ]] || {
  for server in "$scratch"/tmux*; do tmux -S "$server" kill-server 2>/dev/null || true; done
  rm -rf "$scratch"; }' EXIT
home=$scratch/home
mkdir "$home"

# start [ENV_ASSIGNMENT...] [-- ARGUMENT...]: rigidlab with those arguments in a new 100x40
# terminal (or $terminal_columns x $terminal_rows); its exit status goes to $scratch/status when it ends. With $stderr_file set,
# stderr goes there, not to the screen. With $linger set, the terminal stays open after
# rigidlab has ended, so its last screen can still be read.
stderr_file=""
linger=""
start() {
  rm -f "$scratch/status"
  # A new server each time: the one whose last session just ended may still be exiting, and a
  # new session started on its socket then fails ("server exited unexpectedly").
  sessions=$((sessions + 1))
  socket=$scratch/tmux.$sessions.socket
  local environment=() arguments=""
  while (($# > 0)) && [[ $1 != -- ]]; do environment+=("$1"); shift; done
  (($# > 0)) && shift
  for argument in "$@"; do arguments+=" '$argument'"; done
  local redirect=""
  [[ -n $stderr_file ]] && redirect="2>'$stderr_file'"
  tmux -S "$socket" new-session -d -x "${terminal_columns:-100}" -y "${terminal_rows:-40}" \
    "cd '$scratch' && env ${environment[*]} '$rigidlab'$arguments $redirect; echo \$? >'$scratch/status'${linger:+; sleep 60}"
}
screen() { tmux -S "$socket" capture-pane -p -J 2>/dev/null || true; }
type_text() { tmux -S "$socket" send-keys -l "$1"; }
key() { tmux -S "$socket" send-keys "$@"; }
enter() { type_text "$1"; key Enter; }

# How long the waits below wait for what should come at once: long, since a passing test never
# waits it out and a sanitizer build under a loaded machine can take seconds for a step.
wait_limit=15

# wait_for NAME REGEX: until a line of the screen matches REGEX (extended), $wait_limit s at most.
wait_for() {
  case_name=$1
  local deadline=$((SECONDS + wait_limit))
  until screen | grep -qE -- "$2"; do
    if ((SECONDS > deadline)); then
      fail "no line matching /$2/ on the screen:"
      screen | sed '/^$/d; s/^/    | /'
      return 0
    fi
    sleep 0.05
  done
  pass
}

# wait_exit NAME STATUS: until rigidlab has ended, with that status.
wait_exit() {
  case_name=$1
  local deadline=$((SECONDS + wait_limit))
  until [[ -s $scratch/status ]]; do
    if ((SECONDS > deadline)); then
      fail "rigidlab did not exit"
      return 0
    fi
    sleep 0.05
  done
  [[ $(cat "$scratch/status") == "$2" ]] && pass || fail "exit status $(cat "$scratch/status"), want $2"
}

# wait_reading NAME: until rigidlab (the program in the terminal) sleeps waiting for a key, in
# read(2) on its standard input (the lesson pages) or in ppoll(2) (the REPL's line editor: see
# cli/line_reader.cpp), seen twice 0.05 s apart: it has taken in every key sent so far. A
# Ctrl-C sent before then could overtake keys still queued (a signal is not a key): the line
# they were typed into would be cleared before they arrive, and they would land on the next.
# Where /proc/PID/syscall cannot be read (no ptrace access), it waits 1 s instead: what a
# loaded machine may take to read a queued key.
wait_reading() {
  case_name=$1
  local shell pid
  shell=$(tmux -S "$socket" display -p '#{pane_pid}' 2>/dev/null || true)
  pid=$(pgrep -P "${shell:-0}" 2>/dev/null | head -1 || true)
  if [[ -z $pid ]] || ! cat "/proc/$pid/syscall" >/dev/null 2>&1; then
    sleep 1
    pass
    return 0
  fi
  local deadline=$((SECONDS + wait_limit)) seen=0 state call
  while ((seen < 2)); do
    state=$(awk '{print $3}' "/proc/$pid/stat" 2>/dev/null || true)
    call=$(cut -d' ' -f1,2 "/proc/$pid/syscall" 2>/dev/null || true)
    if [[ $state == S && ($call == "0 0x0" || $call == "271 "*) ]]; then
      seen=$((seen + 1))
    else
      seen=0
    fi
    if ((SECONDS > deadline)); then
      fail "rigidlab is not waiting for a key (state '$state', system call '$call')"
      return 0
    fi
    sleep 0.05
  done
  pass
}

prompt_count() { screen | grep -cE '^> ' || true; }
# wait_prompt NAME: until a new `> ` prompt has appeared after the last command.
wait_prompt() {
  case_name=$1
  local want=$2 deadline=$((SECONDS + wait_limit))
  until (($(prompt_count) >= want)); do
    if ((SECONDS > deadline)); then
      fail "no new prompt"
      screen | sed '/^$/d; s/^/    | /'
      return 0
    fi
    sleep 0.05
  done
  pass
}

# slow_writes DELAY: prints the path of a wrapper that runs $rigidlab under strace with each of
# its writes returning DELAY µs late (strace's fault injection): the moment between a prompt
# and the program's switch to raw input, in which a key was echoed by the terminal, made long
# enough to type into. Returns 1 where strace is missing or may not trace, and for a
# sanitizer build: AddressSanitizer makes writes of its own (every one delayed too) and
# LeakSanitizer cannot run under ptrace.
slow_writes() {
  command -v strace >/dev/null && strace -o /dev/null true 2>/dev/null || return 1
  ! ldd "$rigidlab" 2>/dev/null | grep -q libasan || return 1
  cat >"$scratch/slow_writes" <<SCRIPT
#!/bin/sh
exec strace -o /dev/null -e trace=write -e inject=write:delay_exit=$1 '$rigidlab' "\$@"
SCRIPT
  chmod +x "$scratch/slow_writes"
  echo "$scratch/slow_writes"
}
