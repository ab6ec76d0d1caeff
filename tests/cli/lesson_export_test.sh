#!/usr/bin/env bash
# `rigidlab lesson ID --export FILE.md` (issue 17 item 3): the transcript as Markdown with the
# headings, texts, formulas, values and checks as shown, and each ctx:plot as an SVG file
# beside it whose link resolves and which parses as XML; the same for a sandboxed lesson, whose
# charts go into the export folder only; a folder that cannot be made is a clean error.
# Usage: lesson_export_test.sh PATH_TO_RIGIDLAB
set -euo pipefail
source "$(dirname "$0")/testlib.sh" "$1"

# Every chart link of a Markdown file points to a file beside it that is a well-formed SVG
# document (xmllint when installed, else its first and last element).
expect_charts() {  # expect_charts FILE.md COUNT
  case_name="$1 links $2 charts that exist and parse"
  local folder links problems=""
  folder=$(dirname "$1")
  links=$(grep -oE '!\[[^]]*\]\([^)]+\.svg\)' "$1" | sed -E 's/.*\(([^)]+)\)$/\1/' || true)
  local count=0
  for link in $links; do
    count=$((count + 1))
    [[ -f $folder/$link ]] || { problems+=" $link is missing;"; continue; }
    if command -v xmllint >/dev/null; then
      xmllint --noout "$folder/$link" 2>/dev/null || problems+=" $link is not well-formed XML;"
    else
      head -c 200 "$folder/$link" | grep -q '<svg' && tail -c 20 "$folder/$link" | grep -q '</svg>' ||
        problems+=" $link is not an SVG document;"
    fi
  done
  ((count == $2)) || problems+=" $count links, want $2;"
  [[ -z $problems ]] && pass || fail "$problems"
}

exported=$scratch/exported
run "export euler-car into a folder that does not exist yet" -- \
  "$rigidlab" lesson euler-car --export "$exported/euler-car.md"
expect_status 0
expect_stdout_contains "wrote $exported/euler-car.md and 1 chart beside it (euler-car-1.svg)"
expect_stdout_contains "16 of 16 checks passed ✓"
md=$exported/euler-car.md
expect_charts "$md" 1
case_name="the transcript has the heading, steps, formulas, values and checks"
for want in "# euler-car — Euler's method on an accelerating car" \
            "*Source:* 003_636de12a6b81385f.txt, \"Explicit Euler\" and \"Analytical Solution\"" \
            "## Step 3/5: True explicit Euler falls short instead" \
            "explicit:      rₙ = rₙ₋₁ + vₙ₋₁·Δt, vₙ = vₙ₋₁ + a·Δt ⇒ rₙ = aΔt²·n(n−1)/2" \
            "  ✓ explicit Euler r(10 s): got 450, want 450" \
            "![The car's position, Δt = 1 s](euler-car-1.svg)" \
            "**16 of 16 checks passed ✓**"; do
  grep -qF -- "$want" "$md" || { fail "no line '$want'"; continue 2; }
done
pass
case_name="text blocks are closed: an even number of fences"
(($(grep -c '^```' "$md") % 2 == 0)) && pass || fail "odd number of \`\`\` lines"

for id in projectile integrator-energy torque-free dzhanibekov sphere-bounce spring; do
  run "export $id" -- "$rigidlab" lesson "$id" --export "$exported/$id.md"
  expect_status 0
  charts=1
  [[ $id == integrator-energy ]] && charts=2
  expect_charts "$exported/$id.md" "$charts"
done

# A sandboxed lesson: its charts are written by the runner into the export folder; the lesson
# itself still may not write a file.
mkdir "$scratch/elsewhere"
cat >"$scratch/elsewhere/plots.lua" <<'LESSON'
return lesson{id = "plots", title = "Two *charts*", source = "tests", steps = {
  {title = "Charts", text = "Two charts_and one _check_.", run = function(ctx)
    ctx:plot{{y = {1, 4, 9}, label = "n²"}, title = "Squares"}
    ctx:show("between", 1)
    ctx:plot{{y = {1, 8, 27}, label = "n³"}}
    ctx:expect("one", 1, 1)
  end},
  {title = "Its own file", text = "Refused.", run = function(ctx)
    ctx:plot{{y = {1, 2}}, svg = "mine.svg"}
  end}}}
LESSON
cd "$scratch/elsewhere"
run "export a sandboxed lesson" -- "$rigidlab" lesson plots.lua --export "$scratch/sandboxed/plots.md"
expect_status 1
expect_stdout_contains "and 2 charts beside it (plots-1.svg, plots-2.svg)"
expect_charts "$scratch/sandboxed/plots.md" 2
case_name="the sandboxed lesson wrote no file of its own"
[[ ! -e $scratch/elsewhere/mine.svg && ! -e $scratch/sandboxed/mine.svg ]] && pass || fail "mine.svg was written"
case_name="its own svg = is refused in the transcript"
grep -q "error: .*plots.lua:9: bad argument #1 to 'ctx:plot'" "$scratch/sandboxed/plots.md" && pass ||
  fail "$(grep -n error "$scratch/sandboxed/plots.md")"
case_name="Markdown in a title or text is escaped"
grep -qF '# plots — Two \*charts\*' "$scratch/sandboxed/plots.md" &&
  grep -qF 'Two charts_and one \_check\_.' "$scratch/sandboxed/plots.md" && pass || fail "not escaped"
case_name="an untitled chart is linked as chart N"
grep -qF '![chart 2](plots-2.svg)' "$scratch/sandboxed/plots.md" && pass || fail "no link 'chart 2'"
cd "$scratch"

run "a folder that cannot be made" -- "$rigidlab" lesson euler-car --export /proc/no/such/euler-car.md
expect_status 1
expect_stderr_contains "rigidlab: cannot make the folder '/proc/no/such'"
run "--export needs a lesson" -- "$rigidlab" lesson --export "$exported/x.md"
expect_status 2
expect_stderr_contains "'--export' needs a lesson id or file"
run "--export needs a file name" -- "$rigidlab" lesson euler-car --export
expect_status 2
expect_stderr_contains "'--export' needs a file name (FILE.md)"
run "--export with --from" -- "$rigidlab" lesson euler-car --from 5 --export "$exported/from5.md"
expect_status 0
case_name="starts at step 5"
grep -q "^## Step 5/5" "$exported/from5.md" && ! grep -q "^## Step 1/5" "$exported/from5.md" && pass ||
  fail "steps: $(grep '^## ' "$exported/from5.md")"

finish
