# Helpers for the CLI tests (sourced, not a test itself). Each check compares exactly and,
# on failure, prints what differs; the test script ends with `finish`, which exits 1 if any
# check failed. Usage in a test:  source "$(dirname "$0")/testlib.sh" "$1"
set -euo pipefail

rigidlab=${1:?usage: $0 PATH_TO_RIGIDLAB}
[[ -x $rigidlab ]] || { echo "not an executable: $rigidlab"; exit 1; }
rigidlab=$(cd "$(dirname "$rigidlab")" && pwd)/$(basename "$rigidlab")  # tests change directory
scratch=$(mktemp -d)
# Only this shell removes it: a background job's forked copy of this shell that is killed before
# it execs (wait_or_kill's killer, a pipeline's brace group) would otherwise run the trap too and
# remove the scratch folder in the middle of the test.
trap '[[ $BASHPID != "$$" ]] || rm -rf "$scratch"' EXIT
failures=0
checks=0
case_name=""

# run NAME [--stdin TEXT] -- COMMAND...: runs COMMAND, keeping $out, $err and $status.
run() {
  case_name=$1
  shift
  local input=""
  if [[ $1 == --stdin ]]; then
    input=$2
    shift 2
  fi
  [[ $1 == -- ]] && shift
  printf '%s' "$input" >"$scratch/in"
  status=0
  "$@" <"$scratch/in" >"$scratch/out" 2>"$scratch/err" || status=$?
  out=$(cat "$scratch/out"; echo .)
  out=${out%.}  # keep trailing newlines: stdout is compared exactly
  err=$(cat "$scratch/err")
}

fail() {
  failures=$((failures + 1))
  echo "FAIL [$case_name] $1"
  if [[ -n ${2-} ]]; then
    echo "  stderr was:"
    sed 's/^/    | /' "$scratch/err"
  fi
}

pass() { checks=$((checks + 1)); }

expect_status() {
  if [[ $status -eq $1 ]]; then pass; else fail "exit status $status, want $1" stderr; fi
}

expect_stdout() {  # exact, trailing newlines included
  if [[ $out == "$1" ]]; then
    pass
  else
    fail "stdout differs (--- want, +++ got):"
    diff -u <(printf '%s' "$1") <(printf '%s' "$out") | tail -n +3 | sed 's/^/    /' || true
  fi
}

expect_stderr_line() {  # line N (1-based) of stderr, exactly
  local line
  line=$(sed -n "$1p" "$scratch/err")
  if [[ $line == "$2" ]]; then pass; else fail "stderr line $1 is '$line', want '$2'" stderr; fi
}

expect_stderr_line_count() {
  local count
  count=$(wc -l <"$scratch/err")
  if ((count == $1)); then pass; else fail "stderr has $count lines, want $1" stderr; fi
}

expect_stderr_contains() {
  if grep -qF -- "$1" "$scratch/err"; then pass; else fail "stderr lacks '$1'" stderr; fi
}

expect_stderr_empty() {
  if [[ ! -s $scratch/err ]]; then pass; else fail "stderr not empty" stderr; fi
}

expect_stdout_contains() {
  if grep -qF -- "$1" "$scratch/out"; then
    pass
  else
    fail "stdout lacks '$1'; it was:"
    sed 's/^/    | /' "$scratch/out"
  fi
}

finish() {
  if ((failures > 0)); then
    echo "$failures of $((checks + failures)) checks failed"
    exit 1
  fi
  echo "all $checks checks passed"
}
