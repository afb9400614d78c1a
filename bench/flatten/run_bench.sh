#!/bin/sh
# Runs the flattening benchmark side by side: ours (bench_flatten) and CVXOPT on the same first subproblem.
# Usage: bench/flatten/run_bench.sh BUILD_DIR   (build first: ninja -C BUILD_DIR bench_flatten)
set -e
build=${1:-build}
out=$build/bench/flatten
mkdir -p "$out"
"$build/tests/flatten/bench_flatten" "$out" | tee "$out/bench.txt"
ours=$(sed -n 's/^ours_seconds //p' "$out/bench.txt")
/usr/bin/python3 "$(dirname "$0")/cvxopt_time.py" "$out/first_subproblem_2k.json" "$ours"
