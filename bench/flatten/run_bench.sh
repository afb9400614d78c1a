#!/bin/sh
# Runs the flattening benchmark side by side: ours (bench_flatten) and CVXOPT on the same first subproblem.
# Usage: bench/flatten/run_bench.sh BUILD_DIR [FACES_PER_MESH]   (build first: ninja -C BUILD_DIR bench_flatten)
# bench/run.py does the same under its time budget, over several sizes.
set -e
build=${1:-build}
faces=${2:-2000}
out=$build/bench/flatten
mkdir -p "$out"
"$build/bench/flatten/bench_flatten" "$out" "$faces" | tee "$out/bench.txt"
ours=$(sed -n 's/.* ours_seconds \([^ ]*\) .*/\1/p' "$out/bench.txt")
/usr/bin/python3 "$(dirname "$0")/cvxopt_time.py" "$out/first_subproblem_$faces.json" "$ours" sparse
