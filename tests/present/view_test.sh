#!/usr/bin/env bash
# rigidlab view in a real terminal (tmux): the view runs in real time, pauses, steps forward
# one step per key (the same state gives the same frame), orbits, follows a resize, and q
# ends it with the terminal restored (main screen, cursor visible); so do an error in a force
# callback and Ctrl-C. (Stepping back waits for the engine's World::save_state: ← says so.)
# Usage: view_test.sh PATH_TO_RIGIDLAB
source "$(dirname "$0")/../cli/testlib.sh" "$1"
source "$(dirname "$0")/../cli/terminal.sh"

cat >"$scratch/flip.lua" <<'LUA'
local w = world{gravity = vec3(0, 0, 0)}
w:add(body.box{mass = 1, size = vec3(0.5, 0.15, 1), angular_velocity = vec3(4, 0.05, 0.05)})
return w
LUA

# The screen once it has stopped changing (a frame is drawn at most 30 times a second).
settled() {
  local previous current
  current=$(screen)
  for _ in $(seq 40); do
    sleep 0.05
    previous=$current
    current=$(screen)
    [[ $current == "$previous" ]] && break
  done
  printf '%s\n' "$current"
}
status_line() { settled | grep -E '^t [0-9.]+ s  E ' | head -1; }
time_shown() { status_line | sed -E 's/^t ([0-9.]+) s.*/\1/'; }
restored() { [[ $(tmux -S "$socket" display -p '#{alternate_on} #{cursor_flag}') == "0 1" ]]; }

run "view needs a script" -- "$rigidlab" view
[[ $status == 2 && $err == *"'view' needs a script that returns a world"* ]] && pass || fail "status $status: $err"
printf 'return 42\n' >"$scratch/number.lua"
run "the script must return a world" -- "$rigidlab" view "$scratch/number.lua"
[[ $status == 1 && $err == *"number.lua must return a world, got number"* ]] && pass || fail "status $status: $err"

linger=1
start LANG=C.UTF-8 -- view flip.lua
wait_for "the view starts" '^t [0-9.]+ s  E .* running'
now() { date +%s.%N; }
shown_now() { screen | grep -E '^t [0-9.]+ s  E ' | head -1 | sed -E 's/^t ([0-9.]+) s.*/\1/'; }
w0=$(now); t0=$(shown_now)
sleep 1
w1=$(now); t1=$(shown_now)
case_name="it runs in real time"
awk -v a="$t0" -v b="$t1" -v u="$w0" -v v="$w1" 'BEGIN { exit !((b - a) / (v - u) > 0.5 && (b - a) / (v - u) < 1.5) }' &&
  pass || fail "t went from $t0 to $t1 in $(awk -v u="$w0" -v v="$w1" 'BEGIN { print v - u }') s"
key Space
wait_for "space pauses" '  paused'
paused_at=$(time_shown)
sleep 0.5
case_name="paused, time stands still"
[[ $(time_shown) == "$paused_at" ]] && pass || fail "t moved from $paused_at to $(time_shown)"
key Right
sleep 0.3
case_name="-> advances one step of 1/60 s"
awk -v a="$paused_at" -v b="$(time_shown)" 'BEGIN { d = b - a; exit !(d > 0.0155 && d < 0.0175) }' &&
  pass || fail "t went from $paused_at to $(time_shown)"
before=$(settled)
key Left
wait_for "<- says why it cannot step back yet" 'stepping back needs'
case_name="the same state gives the same picture"
[[ $(settled | grep -v '^t ') == "$(printf '%s\n' "$before" | grep -v '^t ')" ]] && pass ||
  fail "the picture changed without a step"
key S-Left
sleep 0.3
case_name="shift+left orbits the camera"
[[ $(settled | grep -v '^t ') != "$(printf '%s\n' "$before" | grep -v '^t ')" ]] && pass ||
  fail "the picture did not turn"
tmux -S "$socket" resize-window -x 70 -y 24
sleep 0.4
case_name="a resize redraws at the new size: the status line is fitted to 70 columns"
last=$(settled | grep -E '^t [0-9.]+ s  E ' | sed 's/ *$//')  # -J keeps trailing blanks
columns=$(printf '%s' "$last" | LC_ALL=C.UTF-8 wc -m)
((columns <= 69 && columns >= 60)) && pass || fail "the status line has $columns columns: $last"
key q
sleep 0.4
case_name="q ends the view: status 0, main screen, cursor visible"
[[ $(cat "$scratch/status" 2>/dev/null) == 0 ]] || fail "exit status $(cat "$scratch/status" 2>/dev/null)"
restored && pass || fail "terminal: $(tmux -S "$socket" display -p 'alternate_on=#{alternate_on} cursor_flag=#{cursor_flag}')"
tmux -S "$socket" kill-server 2>/dev/null || true
socket=$scratch/tmux-2.socket  # a new server: one being killed may still hold the old socket

cat >"$scratch/broken.lua" <<'LUA'
local w = world{}
w:add(body.sphere{mass = 1, radius = 0.2})
w:add_force(function(w, t) if t > 0.2 then error("the callback broke") end end)
return w
LUA
start -- view broken.lua
sleep 1.5
case_name="an error in a force callback ends the view with the terminal restored"
[[ $(cat "$scratch/status" 2>/dev/null) == 1 ]] || fail "exit status $(cat "$scratch/status" 2>/dev/null)"
screen | grep -q "the callback broke" && pass || fail "no message: $(screen | head -3)"
restored && pass || fail "terminal not restored"
tmux -S "$socket" kill-server 2>/dev/null || true
socket=$scratch/tmux-3.socket

start -- view flip.lua
wait_for "the view starts again" '^t [0-9.]+ s  E '
key C-c
sleep 0.6
case_name="Ctrl-C ends the view with the terminal restored"
screen | grep -q "interrupted" && pass || fail "no 'interrupted': $(screen | head -3)"
restored && pass || fail "terminal not restored"

tmux -S "$socket" kill-server 2>/dev/null || true
finish
