#!/usr/bin/env bash
# Runs liftmap on every file of tests/data/bad/ and checks the exit code and the message of EXPECTED.tsv.
# Fails if a file has no expectation, if liftmap crashes (exit >= 128, sanitizer report), or hangs (timeout).
set -u
liftmap="$1"
data="$2"
bad="$data/bad"
good="$data/good/octahedron.off"
failures=0
checked=0
listed=$(grep -v '^#' "$bad/EXPECTED.tsv" | cut -f1 | sort)
for f in "$bad"/*; do
  name=$(basename "$f")
  [ "$name" = EXPECTED.tsv ] && continue
  if ! grep -qx "$name" <<<"$listed"; then
    echo "FAIL $name: no expectation in EXPECTED.tsv"
    failures=$((failures + 1))
  fi
done
while IFS=$'\t' read -r name mode code message; do
  [ -z "$name" ] && continue
  case "$name" in \#*) continue ;; esac
  if [ "$mode" = landmarks ]; then
    args=(check "$good" "$good" -l "$bad/$name")
  else
    args=(check "$bad/$name")
  fi
  err=$(timeout 60 "$liftmap" "${args[@]}" 2>&1 >/dev/null)
  got=$?
  checked=$((checked + 1))
  if [ "$got" != "$code" ]; then
    echo "FAIL $name: exit $got, expected $code; stderr: $err"
    failures=$((failures + 1))
  elif ! grep -qF -- "$message" <<<"$err"; then
    echo "FAIL $name: message '$err' does not contain '$message'"
    failures=$((failures + 1))
  elif grep -q -E 'AddressSanitizer|runtime error|LeakSanitizer' <<<"$err"; then
    echo "FAIL $name: sanitizer report: $err"
    failures=$((failures + 1))
  fi
done <"$bad/EXPECTED.tsv"
echo "bad inputs: $checked checked, $failures failed"
[ "$failures" = 0 ]
