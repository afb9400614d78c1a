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

# same_pair NAME DIR REF: the same files, byte for byte but report.json, which is equal without its wall times.
same_pair() {
  require "$1: the files of liftmap map" diff <(ls -A "$2") <(ls -A "$3")
  for f in $(ls -A "$3"); do
    [ "$f" = report.json ] && continue
    require "$1: $f identical" cmp -s "$2/$f" "$3/$f"
  done
  require "$1: report.json equal but for wall times" python3 -c '
import json, sys
def strip(x):
    if isinstance(x, dict):
        return {k: strip(v) for k, v in x.items() if k not in ("seconds", "run")}
    return [strip(v) for v in x] if isinstance(x, list) else x
assert strip(json.load(open(sys.argv[1]))) == strip(json.load(open(sys.argv[2])))' "$2/report.json" "$3/report.json"
}

finish() {
  echo "$(basename "$0"): $checks checks, $failures failed"
  [ "$failures" = 0 ]
}
