#!/usr/bin/env bash
# Option values are checked when the command line is parsed: exit 2, one line starting with "liftmap:",
# before any input is read or any output folder is made (issue 26: --threads 100000 crashed in libgomp,
# --threads -3 and --tolerance nan ran).
set -u
liftmap="$1"
meshes="$2"
examples="$3"
source "$(dirname "$0")/lib.sh"
a="$meshes/larger_sphere.off"
b="$meshes/ellipsoid.off"
lm="$examples/sphere-ellipsoid/landmarks.txt"
never="$tmp/never"
max=$((4 * $(nproc --all)))

bad_value() {  # NAME OPTION-PATTERN SUBCOMMAND-ARGS...
  local name="$1" option="$2"
  shift 2
  expect "$name" 2 "^liftmap: .*$option" -- "$@" -o "$never"
  if [ "$(wc -l <<<"$err")" != 1 ]; then
    echo "FAIL $name: more than one line on stderr: $err"
    failures=$((failures + 1))
  fi
  require "$name: nothing written" test ! -e "$never"
}

for sub in map cut; do
  bad_value "$sub threads 100000" --threads "$sub" "$a" "$b" -l "$lm" --threads 100000
  bad_value "$sub threads 40000" --threads "$sub" "$a" "$b" -l "$lm" --threads 40000
  bad_value "$sub threads -3" --threads "$sub" "$a" "$b" -l "$lm" --threads -3
  bad_value "$sub threads 0" --threads "$sub" "$a" "$b" -l "$lm" --threads 0
  bad_value "$sub threads max+1" --threads "$sub" "$a" "$b" -l "$lm" --threads $((max + 1))
  bad_value "$sub threads not a number" --threads "$sub" "$a" "$b" -l "$lm" --threads two
done
for t in nan inf -inf 0 -1e-3 abc; do
  bad_value "tolerance $t" --tolerance map "$a" "$b" -l "$lm" --tolerance "$t"
done
for n in -1 -3 10001 1.5; do
  bad_value "max-iterations $n" --max-iterations map "$a" "$b" -l "$lm" --max-iterations "$n"
done
for n in -1 10001 2.5 x; do
  bad_value "start-relaxation $n" --start-relaxation map "$a" "$b" -l "$lm" --start-relaxation "$n"
done
for n in 0 -2 11 nan; do
  bad_value "samples $n" --samples map "$a" "$b" -l "$lm" --samples "$n"
done
bad_value "unknown option" "--bogus" map "$a" "$b" -l "$lm" --bogus
bad_value "missing landmarks" "landmarks" map "$a" "$b"
bad_value "bad --p" "--p" map "$a" "$b" -l "$lm" --p 3
expect "no subcommand" 2 "^liftmap: " --
expect "check without a mesh" 2 "^liftmap: " -- check
expect "transfer without a mode" 2 "^liftmap: " -- transfer
expect "check -l with one mesh" 2 "^liftmap: check --landmarks needs two meshes" -- check "$a" -l "$lm"

# The bounds are not too tight: the largest accepted values run.
expect "threads $max and max-iterations 0 accepted" 0 ".*" -- map "$a" "$b" -l "$lm" --threads "$max" \
  --max-iterations 0 --tolerance 1e300 --samples 1 -o "$tmp/ok" --quiet
require "accepted run wrote its report" test -f "$tmp/ok/report.json"
finish
