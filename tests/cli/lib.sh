# Helpers of the CLI tests: run liftmap, check its exit code and the key words of its messages.
# Sourced by the test scripts, which set $liftmap and call `finish` at the end.
failures=0
checks=0
tmp=$(mktemp -d "${TMPDIR:-/tmp}/liftmap_cli.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# expect NAME CODE PATTERN -- ARGS...: runs `liftmap ARGS` and requires exit CODE, stderr+stdout matching the
# extended regular expression PATTERN, no crash or sanitizer report. Leaves stdout in $out, stderr in $err.
expect() {
  local name="$1" code="$2" pattern="$3"
  shift 4
  out=$(timeout 300 "$liftmap" "$@" 2>"$tmp/stderr")
  local got=$?
  err=$(cat "$tmp/stderr")
  checks=$((checks + 1))
  if [ "$got" != "$code" ]; then
    echo "FAIL $name: exit $got, expected $code"
    echo "  liftmap $*"
    echo "  stderr: $err"
    failures=$((failures + 1))
  elif ! grep -qE -- "$pattern" <<<"$err"$'\n'"$out"; then
    echo "FAIL $name: output does not match '$pattern'"
    echo "  stderr: $err"
    failures=$((failures + 1))
  elif grep -qE 'AddressSanitizer|runtime error|LeakSanitizer' <<<"$err"; then
    echo "FAIL $name: sanitizer report: $err"
    failures=$((failures + 1))
  fi
}

# require NAME CONDITION...: a check on files, e.g. require "no output" test ! -e "$dir".
require() {
  local name="$1"
  shift
  checks=$((checks + 1))
  if ! "$@"; then
    echo "FAIL $name: $*"
    failures=$((failures + 1))
  fi
}

finish() {
  echo "$(basename "$0"): $checks checks, $failures failed"
  [ "$failures" = 0 ]
}
