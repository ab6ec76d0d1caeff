#!/usr/bin/env bash
# The REPL's history file behind symbolic links (issue 12, item 14), driven through tmux: a
# link is written through, never replaced by a regular file; a link whose target does not
# exist yet creates it; a target that is not a regular file (a FIFO here, /dev/null for users
# who keep no history) is neither read nor replaced; a loop of links is one clean message.
# Exit 77 (CTest: skipped) when tmux is not installed.
# Usage: repl_history_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"
source "$(dirname "$0")/terminal.sh"
history=$home/.rigidlab_history

# session NAME LINE: a session that evaluates LINE (an expression printing 42) and exits.
session() {
  start HOME="$home"
  wait_for "$1: prompt" '^> $'
  enter "$2"
  wait_for "$1: evaluates" '^42$'
  key C-d
  wait_exit "$1: exits 0" 0
}

mkdir "$scratch/elsewhere"
printf '_HiStOrY_V2_\nold_entry\n' >"$scratch/elsewhere/history"
chmod 600 "$scratch/elsewhere/history"
ln -s "$scratch/elsewhere/history" "$history"
session "a link to a regular file" '6*7'
case_name="the link is still a link, to the same file"
[[ -L $history && $(readlink "$history") == "$scratch/elsewhere/history" ]] && pass || fail "$(ls -l "$history")"
case_name="the file it leads to has the new entry after the old one"
[[ $(tail -n 2 "$scratch/elsewhere/history") == $'old_entry\n6*7' ]] && pass || fail "$(cat "$scratch/elsewhere/history")"
case_name="the file keeps its mode"
[[ $(stat -c %a "$scratch/elsewhere/history") == 600 ]] && pass || fail "mode $(stat -c %a "$scratch/elsewhere/history")"

rm "$history"
ln -s "elsewhere/new_history" "$history"  # relative, to a file not there yet
ln -s "$scratch/elsewhere" "$home/elsewhere"
session "a link to a file not there yet" '40+2'
case_name="the link is kept and its target created"
[[ -L $history && -f $scratch/elsewhere/new_history ]] && pass || fail "$(ls -l "$history" "$scratch/elsewhere")"
grep -qxF '40+2' "$scratch/elsewhere/new_history" && pass || fail "no entry in the new file"

rm "$history"
mkfifo "$scratch/elsewhere/fifo"
ln -s "$scratch/elsewhere/fifo" "$history"
session "a link to a FIFO" '84//2'
case_name="the FIFO is left a FIFO"
[[ -p $scratch/elsewhere/fifo ]] && pass || fail "$(ls -l "$scratch/elsewhere")"

rm "$history"
ln -s "$home/loop_b" "$history"
ln -s "$history" "$home/loop_b"
stderr_file=$scratch/stderr
session "a loop of links" '21*2'
case_name="a loop of links: one message, the links untouched"
[[ $(cat "$scratch/stderr") == "rigidlab: the history is not saved (cannot write "*": Too many levels of symbolic links)" ]] \
  && pass || fail "stderr: $(cat "$scratch/stderr")"
[[ -L $history && -L $home/loop_b ]] && pass || fail "$(ls -l "$home")"

finish
