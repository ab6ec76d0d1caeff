#!/usr/bin/env bash
# rigidlab view in a real terminal (tmux): the view runs in real time, pauses, steps forward
# one step per key (the same state gives the same frame), orbits, follows a resize, and q
# ends it with the terminal restored (main screen, cursor visible); so do an error in a force
# callback and Ctrl-C. Rewind: ← ten times from a paused state and → ten times shows, on the
# way forward, the very screens seen on the way back (the states restored and stepped again
# bit for bit), and they are ten different pictures.
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
[[ $status == 1 && $err == *"number.lua must return a world or an articulation, got number"* ]] && pass || fail "status $status: $err"

run "view refuses an unknown option" -- "$rigidlab" view --fast "$scratch/flip.lua"
[[ $status == 2 && $err == *"unrecognized option '--fast' for 'view'"* ]] && pass || fail "status $status: $err"

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
# after KEY SCREEN: presses KEY, waits until the screen is no longer SCREEN, then until it settles.
after() {
  key "$1"
  for _ in $(seq 60); do [[ $(screen) != "$2" ]] && break; sleep 0.05; done
  settled
}
picture() { printf '%s\n' "$1" | grep -v '^t '; }
shown_time() { printf '%s\n' "$1" | grep -E '^t [0-9.]+ s  E ' | sed -E 's/^t ([0-9.]+) s.*/\1/'; }
declare -a back_frames
back_frames[0]=$(settled)
for k in $(seq 10); do back_frames[k]=$(after Left "${back_frames[k - 1]}"); done
case_name="<- steps back ten steps of 1/60 s, and the status says so"
awk -v a="$(shown_time "${back_frames[0]}")" -v b="$(shown_time "${back_frames[10]}")" \
  'BEGIN { d = a - b; exit !(d > 0.160 && d < 0.174) }' &&
  [[ ${back_frames[10]} == *"rewound 10 of "* ]] && pass ||
  fail "t went from $(shown_time "${back_frames[0]}") to $(shown_time "${back_frames[10]}"): $(printf '%s\n' "${back_frames[10]}" | grep '^t ')"
case_name="the ten steps back are ten different pictures"
distinct=$(for k in $(seq 0 10); do picture "${back_frames[k]}" | md5sum; done | sort -u | wc -l)
((distinct == 11)) && pass || fail "only $distinct different pictures among 11"
forward=${back_frames[10]}
identical=0
for k in $(seq 9 -1 0); do
  forward=$(after Right "$forward")
  if [[ $forward == "${back_frames[k]}" ]]; then
    identical=$((identical + 1))
  else
    diff <(printf '%s\n' "${back_frames[k]}") <(printf '%s\n' "$forward") | head -6 | sed 's/^/    /'
  fi
done
case_name="-> ten times from there shows, screen for screen, what <- showed (exact replay)"
((identical == 10)) && pass || fail "$identical of 10 screens identical"
before=$(after Right "$forward")
case_name="one more -> goes past the history: a new state, not rewound"
[[ $before != *"rewound"* && $before != "${back_frames[0]}" ]] && pass || fail "$(printf '%s\n' "$before" | grep '^t ')"
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
socket=$scratch/tmux-4.socket

# 2000 bodies: 600 saved states would take some 500 MB; under --max-memory 24 the history
# takes what fits (the view's memory counts against the limit) and still steps back.
cat >"$scratch/many.lua" <<'LUA'
local w = world{gravity = vec3(0, 0, 0)}
for i = 1, 2000 do
  w:add(body.sphere{mass = 1, radius = 0.1, position = vec3(i % 50, i // 50, 0), velocity = vec3(0, 0.1, 0)})
end
return w
LUA
linger=1
start -- view --max-memory 24 many.lua
wait_for "a large world starts under --max-memory 24" '^t [0-9.]+ s  E '
key Space
sleep 0.5
key Right  # one step of its own: under load the view may not have stepped before the pause
sleep 0.5
key Left
wait_for "and steps back within the memory limit" 'rewound 1 of [0-9]+ steps'
key q
wait_exit "q ends it: status 0" 0
tmux -S "$socket" kill-server 2>/dev/null || true
socket=$scratch/tmux-5.socket

# An articulation: a pendulum swings in art:view; <- <- goes back to the picture of two steps
# before, and the status says so.
cat >"$scratch/pendulum.lua" <<'LUA'
local a = articulation{}
a:add_link{joint = "revolute", axis = vec3(0, 0, 1), mass = 1, com = vec3(1, 0, 0)}
return a
LUA
start -- view pendulum.lua
wait_for "rigidlab view shows an articulation" '^t [0-9.]+ s  E .* running'
sleep 0.3
key Space
sleep 0.3
picture_a=$(settled | grep -v '^t ')
key Right
key Right
sleep 0.3
case_name="the pendulum moves"
[[ $(settled | grep -v '^t ') != "$picture_a" ]] && pass || fail "the same picture after two steps"
picture_b=$(settled | grep -v '^t ')
key Left
key Left
wait_for "<- <- on an articulation rewinds two steps" 'rewound 2 of '
case_name="two steps back is the picture two steps before"
[[ $(settled | grep -v '^t ') == "$picture_a" ]] && pass || fail "not the picture before the two steps"
key Right
key Right
sleep 0.3
case_name="-> -> restores the picture after them"
[[ $(settled | grep -v '^t ') == "$picture_b" ]] && pass || fail "not the picture after the two steps"
key q
wait_exit "q ends the articulation's view" 0
tmux -S "$socket" kill-server 2>/dev/null || true
socket=$scratch/tmux-6.socket

# A lesson step that draws a strip (ctx:motion) offers its live view on the key v: the view
# starts from the strip's first state (t = 0, the strip ended at 1.5 s), q returns to the
# lesson's prompt.
mkdir -p "$scratch/lessons"
cp "$(dirname "$0")/spin_lesson.lua" "$scratch/lessons/spin.lua"
start LANG=C.UTF-8 -- lesson lessons/spin.lua
wait_for "the lesson offers the live view" 'v watch'
key v
wait_for "v starts the view at the strip's first state" '^t 0\.[0-9]+ s  E .* running'
key q
sleep 0.5
case_name="q returns to the lesson's prompt, the terminal restored"
[[ $(tmux -S "$socket" display -p '#{alternate_on}') == 0 ]] && screen | grep -q 'v watch   m menu' &&
  pass || fail "$(screen | tail -3)"
key q
wait_exit "q ends the lesson" 0
tmux -S "$socket" kill-server 2>/dev/null || true
finish
