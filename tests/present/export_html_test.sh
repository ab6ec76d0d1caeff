#!/usr/bin/env bash
# w:export_html in a real browser: the page references nothing outside itself, loads in
# headless Chromium without an error (its script marks <body data-state="frame K"> when it
# has drawn, "error: ..." when anything threw), and shows different pictures at two slider
# positions (the page starts at the frame its #frame=K fragment names).
# Usage: export_html_test.sh PATH_TO_RIGIDLAB PATH_TO_CHROMIUM
set -euo pipefail
rigidlab=${1:?usage: $0 RIGIDLAB CHROMIUM}
chromium=${2:?usage: $0 RIGIDLAB CHROMIUM}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
failures=0
fail() { echo "FAIL $1"; failures=$((failures + 1)); }

cat >"$scratch/flip.lua" <<'LUA'
local w = world{gravity = vec3(0, 0, 0)}
w:add(body.box{mass = 1, size = vec3(0.5, 0.15, 1), angular_velocity = vec3(4, 0.05, 0.05)})
w:add_plane{offset = -1.5}
local frames = w:export_html(arg[1], {seconds = 4, fps = 30,
                                      show = {"omega", "L", "trail", "frames"},
                                      title = "flip </script> & <b>"})
assert(frames == 121, "frames: " .. frames)
assert(math.abs(w.time - 4) < 1e-9, "the world ran on 4 s: " .. w.time)
LUA
"$rigidlab" "$scratch/flip.lua" "$scratch/flip.html" || fail "the export failed"
page=$scratch/flip.html

# Self-contained: no URL, no external script, style, image or font.
if grep -Eiq 'https?://|src=|href=|url\(|@import' "$page"; then
  fail "the page references something outside itself: $(grep -Eio '.{20}(https?://|src=|href=|url\(|@import).{20}' "$page" | head -1)"
fi
[[ $(grep -c '</script>' "$page") == 1 ]] || fail "a label closed the script element"

browse() {  # browse OUTPUT_FLAG URL: runs headless Chromium with a fresh profile
  local profile
  profile=$(mktemp -d -p "$scratch")
  timeout 60 "$chromium" --headless --no-sandbox --disable-gpu --disable-background-networking \
    --disable-component-update --disable-sync --no-first-run --user-data-dir="$profile" \
    --window-size=900,760 --virtual-time-budget=3000 "$1" "$2" 2>>"$scratch/browser.err"
}

for frame in 0 100; do
  browse --dump-dom "file://$page#frame=$frame" >"$scratch/dom$frame.html" || fail "chromium failed (frame $frame)"
  state=$(grep -o 'data-state="[^"]*"' "$scratch/dom$frame.html" | head -1)
  [[ $state == "data-state=\"frame $frame\"" ]] || fail "frame $frame: the page says $state"
  grep -q "t = $(awk -v f="$frame" 'BEGIN { printf "%.3f", f / 30 }') s" "$scratch/dom$frame.html" ||
    fail "frame $frame: the clock does not show its time"
  (cd "$scratch" && browse --screenshot="$scratch/shot$frame.png" "file://$page#frame=$frame" >/dev/null) ||
    fail "no screenshot (frame $frame)"
  [[ -s $scratch/shot$frame.png ]] || fail "empty screenshot (frame $frame)"
done
if cmp -s "$scratch/shot0.png" "$scratch/shot100.png"; then
  fail "the picture is the same at frames 0 and 100"
fi
if grep -q "Uncaught" "$scratch/browser.err"; then
  fail "console errors: $(grep Uncaught "$scratch/browser.err" | head -3)"
fi

if ((failures > 0)); then exit 1; fi
echo "export_html: self-contained, loads without errors, pictures differ"
