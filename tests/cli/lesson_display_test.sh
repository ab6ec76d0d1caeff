#!/usr/bin/env bash
# How a lesson lays out what it shows: every line fits the width (COLUMNS without a terminal),
# long checks put got and want on lines of their own, a matrix on its rows, -0 shows as 0; the
# heading gives one line per source document; the lesson list fits the width too, and keeps
# every source in full when written to a pipe with no width known.
# Usage: lesson_display_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"
fixture=$(cd "$(dirname "$0")/../lessons" && pwd)/wide_values.lua

expect_lines_within() {  # every line of the last run's stdout at most $1 columns
  case_name="every line within $1 columns"
  too_long=$(LC_ALL=C.UTF-8 bash -c 'while IFS= read -r line; do
      ((${#line} > $1)) && echo "${#line}: $line"; done <"$2"; true' _ "$1" "$scratch/out")
  [[ -z $too_long ]] && pass || fail "lines over $1 columns:"$'\n'"$too_long"
}

for columns in 80 60 40; do
  run "lesson at $columns columns" -- env COLUMNS=$columns "$rigidlab" lesson "$fixture"
  expect_status 0
  expect_lines_within $columns
  run "lesson list at $columns columns" -- env COLUMNS=$columns "$rigidlab" lessons
  expect_status 0
  expect_lines_within $columns
  expect_stdout_contains "center-of-mass  "
done

run "lesson at 40 columns" -- env COLUMNS=40 "$rigidlab" lesson "$fixture"
expect_stdout_contains "    (0.3333333333, 0.6666666667,"
expect_stdout_contains "     -0.1428571429)"  # a row too wide breaks, under its first number
expect_stdout_contains "  ✓ the matrix against itself, a check"
expect_stdout_contains "    too long for one line"

run "lesson list with no width (a pipe)" -- env -u COLUMNS "$rigidlab" lessons
expect_stdout_contains '"Center of mass"; 001_8a70f78e0cc79e25.txt, "System Of Particles"; 004_8f5d2bfd6f0c2787.txt, "Center of Mass"'
run "lesson list at 130 columns" -- env COLUMNS=130 "$rigidlab" lessons
expect_lines_within 130
expect_stdout_contains "000_3bd95e59483beea1.txt, \"Mass\""
expect_stdout_contains "…"

run "heading of a lesson with three documents, at 60 columns" -- \
  env COLUMNS=60 "$rigidlab" lesson center-of-mass
expect_stdout_contains "center-of-mass — The centre of mass: balance point, average"
expect_stdout_contains "                 motion, no-turning point"
expect_stdout_contains '  source: 000_3bd95e59483beea1.txt, "Center of mass"'
expect_stdout_contains '          001_8a70f78e0cc79e25.txt, "System Of Particles"'
expect_stdout_contains '          004_8f5d2bfd6f0c2787.txt, "Center of Mass"'

run "lesson at 80 columns" -- env COLUMNS=80 "$rigidlab" lesson "$fixture"
expect_stdout_contains "  ✓ the matrix against itself, a check too long for one line"
expect_stdout_contains "      got  ((0.3333333333, 0.6666666667, -0.1428571429),"
expect_stdout_contains "            (0.6666666667, 1.666666667, 1e-17),"
expect_stdout_contains "  a matrix ="
expect_stdout_contains "    (-0.1428571429, 1e-17, 0.4444444444)"
expect_stdout_contains "  minus zero = (0, 1, 0)"
expect_stdout_contains "  ✓ a short check: got 2, want 2"
expect_stdout_contains "  A sentence long enough that it has to be wrapped onto a second line when the"
expect_stdout_contains "  terminal is eighty columns wide, and every line keeps the indentation."
case_name="no line ends in a space"
grep -qE ' $' "$scratch/out" && fail "$(grep -nE ' $' "$scratch/out")" || pass

finish
