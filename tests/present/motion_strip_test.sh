#!/usr/bin/env bash
# ctx:motion in a lesson: a film strip of the frames, its captions at the times the frames
# show, fitted to the lesson's 80 columns, ASCII without a byte above 127 in a C locale and
# braille in a UTF-8 one, no colour; different pictures as the box turns; the world stepped
# to the last frame's time; `rigidlab check` draws nothing and passes.
# Usage: motion_strip_test.sh PATH_TO_RIGIDLAB
source "$(dirname "$0")/../cli/testlib.sh" "$1"

mkdir "$scratch/lessons"
cp "$(dirname "$0")/spin_lesson.lua" "$scratch/lessons/spin.lua"
lesson=$scratch/lessons/spin.lua

run "a lesson with ctx:motion, C locale" -- env LANG=C LC_ALL=C "$rigidlab" lesson "$lesson"
expect_status 0
strip=$(printf '%s' "$out" | grep -E '^    [+|]' || true)
case_name="four captions at 0, 0.5, 1 and 1.5 s, two boxes to a row"
[[ $(printf '%s\n' "$strip" | grep -c '^    +- t = 0.00 s -.*+  +- t = 0.50 s -') == 1 &&
   $(printf '%s\n' "$strip" | grep -c '^    +- t = 1.00 s -.*+  +- t = 1.50 s -') == 1 ]] && pass ||
  fail "$(printf '%s\n' "$strip" | grep -- '- t =')"
case_name="the strip: ASCII only, no escape sequence, within 80 columns"
bad=$(printf '%s\n' "$strip" | LC_ALL=C grep -c $'[\x80-\xff\x1b]' || true)
wide=$(printf '%s\n' "$strip" | awk 'length > 80' | wc -l)
((bad == 0 && wide == 0)) && pass || fail "$bad lines with non-ASCII bytes, $wide lines past 80 columns"
case_name="the box turns: the first and the last frame differ"
# Pictures are 35 columns: the left one from column 6, the right one 4 columns after it.
first=$(printf '%s\n' "$strip" | sed -n '2,/^    +-----/p' | sed '$d' | cut -c6-40)
last=$(printf '%s\n' "$strip" | awk '/t = 1.00 s/ { on = 1; next } on && /^    \+---/ { exit } on' | cut -c45-79)
[[ -n $first && -n $last && $first != "$last" ]] && pass || fail "first: [$first] last: [$last]"
case_name="the legend under the strip and the check after it"
[[ $out == *"angular momentum ("* && $out == *"✓ the world is at the last frame's time"* ||
   $out == *"the world is at the last frame's time"* ]] && pass || fail "$out"

run "the same in a UTF-8 locale" -- env LANG=C.UTF-8 LC_ALL=C.UTF-8 "$rigidlab" lesson "$lesson"
case_name="braille pictures in box-drawing frames"
[[ $status == 0 && $out == *"┌─ t = 0.00 s ─"* && $out == *"│  │"* && $out == *"⠤⠤⠤⠤⠤ 1 box"* &&
   $out != *$'\x1b'* ]] && pass || fail "$out"

run "rigidlab check draws nothing" -- "$rigidlab" check "$lesson"
case_name="check passes and shows no frame"
[[ $status == 0 && $out == *"1 passed, 0 failed"* && $out != *"t = 0.00 s"* ]] && pass || fail "status $status: $out"
finish
