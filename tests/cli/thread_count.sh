#!/usr/bin/env bash
# A map does not depend on the thread count: camel-cow (above the faces at which the per-face loops run on the
# threads) mapped with --threads 1 and --threads 2 gives byte-identical files, and report.json differs only in its
# seconds. Sums over faces used to be OpenMP reductions, whose partial sums round differently per thread count: the
# barrier method's iterates then differed by about 1e-11 and the maps in their last digits (on pairs whose
# subproblems stall, by more).
set -u
liftmap="$1"
meshes="$2"
examples="$3"
source "$(dirname "$0")/lib.sh"
for t in 1 2; do
  expect "map --threads $t" 0 "" -- map "$meshes/camel.off" "$meshes/cow.off" \
    -l "$examples/camel-cow/landmarks.txt" -o "$tmp/t$t" --threads "$t" --quiet
done
for f in "$tmp"/t1/*; do
  name=$(basename "$f")
  [ "$name" = report.json ] && continue
  require "$name the same at 1 and 2 threads" cmp -s "$f" "$tmp/t2/$name"
done
require "the same files at 1 and 2 threads" diff <(ls "$tmp/t1") <(ls "$tmp/t2")
checks=$((checks + 1))
if ! /usr/bin/python3 - "$tmp/t1/report.json" "$tmp/t2/report.json" <<'PY'; then
import json
import sys


def without_seconds(d):
    if isinstance(d, dict):
        return {k: without_seconds(v) for k, v in d.items() if "seconds" not in k}
    if isinstance(d, list):
        return [without_seconds(x) for x in d]
    return d


one, two = (without_seconds(json.load(open(p))) for p in sys.argv[1:3])
if one != two:
    sys.exit("report.json differs between 1 and 2 threads beyond its seconds")
PY
  echo "FAIL report.json at 1 and 2 threads"
  failures=$((failures + 1))
fi
finish
