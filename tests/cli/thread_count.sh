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
same_pair "--threads 2 against --threads 1" "$tmp/t2" "$tmp/t1"
finish
