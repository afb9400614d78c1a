#!/usr/bin/env bash
# Runs every libFuzzer target of a -DLIFTMAP_FUZZ=ON build for a bounded time (make fuzz).
#   scripts/fuzz.sh [BUILD]   BUILD: the fuzz build folder (default build-fuzz)
#   FUZZ_SECONDS  seconds per target (default 600)
#   FUZZ_JOBS     targets run at the same time (default 1; at most 2 on a shared machine)
#   FUZZ_TARGETS  which targets (default: off obj ply stl landmarks surface_landmarks vertex_map obj_uv overlay)
# Seeds come from tests/data (tests/data/fuzz-seeds/<target> and PLY/STL versions of its octahedron); the corpus
# each run grows is kept in BUILD/fuzz-corpus/<target>, findings (crash-*, leak-*, timeout-*) go to
# BUILD/fuzz-findings/<target>/ and fail the run: keep each as a regression input in
# tests/data/fuzz-regressions/<target>/ once fixed.
# BUILD/fuzz-summary.txt lists the executions and seconds per target.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build-fuzz}"
seconds="${FUZZ_SECONDS:-600}"
jobs="${FUZZ_JOBS:-1}"
targets="${FUZZ_TARGETS:-off obj ply stl landmarks surface_landmarks vertex_map obj_uv overlay}"
data="$root/tests/data"

seed() {  # TARGET: fills BUILD/fuzz-seeds/TARGET
  local t="$1" dir="$build/fuzz-seeds/$1"
  rm -rf "$dir"
  mkdir -p "$dir"
  case "$t" in
    off | obj | ply | stl) find "$data/good" "$data/bad" -name "*.$t" -exec cp {} "$dir" \; ;;
    landmarks) cp "$data/good/landmarks.txt" "$data"/bad/lm_*.txt "$dir" ;;
    surface_landmarks)
      cp "$data/good/landmarks.txt" "$dir"
      printf '4 f0:0.6,0.2,0.2\nf1:0.25,0.25,0.5 0.2,0.3,0.5  # face and 3D point\nf7:0.0005,0.4995,0.5 2,2,2\n' \
        >"$dir/surface.txt"
      ;;
    vertex_map)
      printf '# map\n0 1 0 0\n1 0.25 0.25 0.5\n1999 0 0 1  # last face\n' >"$dir/map.txt"
      # the header lines naming the meshes, as read_as_fuzzed expects them (map_header.h)
      printf '# source mesh: 3 vertices, 1 faces, connectivity fnv1a64:00000000000000a1\n# target mesh: 1000 vertices, 2000 faces, connectivity fnv1a64:0123456789abcdef\n0 1 0 0\n' \
        >"$dir/named.txt"
      ;;
    obj_uv)
      printf 'mtllib m.mtl\nv 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl a\n' \
        >"$dir/octahedron_uv.obj"
      printf 'f 1/1 3/2 5/3\nf 3/1 2/2 5/3\nf 2/1 4/2 5/3\nf 4/1 1/2 5/3\nf 3/1 1/2 6/3\nf -4/1 -5/2 -1/3\n' \
        >>"$dir/octahedron_uv.obj"
      printf 'f 4/-3/1 2/-2/2 6/-1/3\nf 1//1 4/1 6/2\n' >"$dir/octahedron_uv_bad.obj"
      ;;
  esac
  case "$t" in
    ply)
      "$root/tests/cli/make_variant.py" ply_ascii "$data/good/octahedron.off" "$dir/octahedron_ascii.ply"
      "$root/tests/cli/make_variant.py" ply_binary "$data/good/octahedron.off" "$dir/octahedron_binary.ply"
      ;;
    stl)
      "$root/tests/cli/make_variant.py" stl_binary "$data/good/octahedron.off" "$dir/octahedron_binary.stl"
      "$root/tests/cli/make_variant.py" stl_ascii_nan "$data/good/octahedron.off" "$dir/octahedron_ascii.stl"
      ;;
  esac
  # Seeds kept as files (overlay: its three files NUL-separated, fuzz/overlay_as_fuzzed.h), and earlier findings.
  if [ -d "$data/fuzz-seeds/$t" ]; then cp "$data/fuzz-seeds/$t"/* "$dir"; fi
  if [ -d "$data/fuzz-regressions/$t" ]; then cp "$data/fuzz-regressions/$t"/* "$dir" 2>/dev/null || true; fi
}

run() {  # TARGET
  local t="$1"
  mkdir -p "$build/fuzz-corpus/$t" "$build/fuzz-findings/$t"
  seed "$t"
  nice -n 19 "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build/fuzz-findings/$t/" "$build/fuzz-corpus/$t" "$build/fuzz-seeds/$t" \
    >"$build/fuzz-$t.log" 2>&1 || true
  local runs
  runs=$(grep -oE 'stat::number_of_executed_units: [0-9]+' "$build/fuzz-$t.log" | grep -oE '[0-9]+$' || echo "?")
  local time
  time=$(grep -oE 'Done [0-9]+ runs in [0-9]+ second' "$build/fuzz-$t.log" | grep -oE 'in [0-9]+' | grep -oE '[0-9]+' ||
    echo "?")
  # slow-unit-* files are not findings: on a loaded machine at nice 19 a 0.1 s input can take 13 s of wall time.
  local found slow
  found=$(find "$build/fuzz-findings/$t" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o \
    -name 'oom-*' \) | wc -l)
  slow=$(find "$build/fuzz-findings/$t" -type f -name 'slow-unit-*' | wc -l)
  echo "$t: $runs executions in $time s, $found finding(s), $slow slow unit(s)" | tee -a "$build/fuzz-summary.txt"
}

: >"$build/fuzz-summary.txt"
running=0
for t in $targets; do
  run "$t" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n
    running=$((running - 1))
  fi
done
wait
if grep -qv ' 0 finding(s),' "$build/fuzz-summary.txt"; then
  echo "fuzz: findings above (BUILD/fuzz-findings/<target>/)"
  exit 1
fi
echo "fuzz: no findings"
