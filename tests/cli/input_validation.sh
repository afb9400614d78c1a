#!/usr/bin/env bash
# One validation for `check` and `map` (issue 26): an inside-out mesh and coordinates the pipeline cannot
# handle are reported by `check` and rejected by `map` with exit 4, naming the file, before any computation;
# copies inside the documented limits map and verify.
set -u
liftmap="$1"
meshes="$2"
examples="$3"
data="$4"
source "$(dirname "$0")/lib.sh"
variant="$(dirname "$0")/make_variant.py"
lm="$examples/sphere-ellipsoid/landmarks.txt"

pair() {  # KIND VALUE: writes $tmp/A.off, $tmp/B.off, variants of the sphere-ellipsoid pair
  "$variant" "$1" "$meshes/larger_sphere.off" "$tmp/A.off" ${2:+"$2"}
  "$variant" "$1" "$meshes/ellipsoid.off" "$tmp/B.off" ${2:+"$2"}
}

rejected() {  # NAME KIND VALUE PATTERN
  local name="$1" pattern="$4"
  pair "$2" "$3"
  expect "$name: check" 4 "A\.off: cannot be mapped: .*$pattern" -- check "$tmp/A.off"
  require "$name: check says not mappable" grep -q "mappable: *no" <<<"$out"
  expect "$name: map" 4 "^liftmap: [^ ]*A\.off: cannot be mapped: .*$pattern" -- map "$tmp/A.off" "$tmp/B.off" -l "$lm" \
    -o "$tmp/out"
  require "$name: map rejects before the cut" bash -c "! grep -q '\] cut ' <<<\"\$1\"" _ "$err"
  require "$name: no report" test ! -e "$tmp/out/report.json"
}
rejected "inside-out" invert "" "the faces are oriented inward \(signed volume -[0-9.]+ < 0\)"
rejected "scaled by 1e307" scale 1e307 "beyond \+-1e\+30: scale the mesh down"
rejected "scaled by 1e-35" scale 1e-35 "below 1e-30: scale the mesh up"
rejected "translated by 1e12" translate 1e12 "times the bounding box diagonal .* translate the mesh towards the origin"
rejected "translated by 1e5" translate 1e5 "at most 1e\+04"
pair invert ""
expect "inside-out: check --json" 4 '"kind": "inside-out mesh"' -- check "$tmp/A.off" --json

# --fix-orientation: the inside-out mesh is flipped with a warning and maps as the original does; the map
# files keep the vertex order of the inside-out file.
"$variant" invert "$meshes/larger_sphere.off" "$tmp/inside_out.off"
expect "fix-orientation" 0 "^liftmap: warning: .*inside_out.off is inside-out \(signed volume -[0-9.]+\): its faces are reversed" \
  -- map "$tmp/inside_out.off" "$meshes/ellipsoid.off" -l "$lm" -o "$tmp/fixed" --quiet --fix-orientation
require "fix-orientation: verification passed" grep -q '"passed": true' "$tmp/fixed/report.json"
require "fix-orientation: report says so" grep -q '"faces_reversed": true' "$tmp/fixed/report.json"
expect "original" 0 ".*" -- map "$meshes/larger_sphere.off" "$meshes/ellipsoid.off" -l "$lm" -o "$tmp/orig" --quiet
# (converted by hand: without the header lines that name the original's faces)
awk '/^#/ { next } { print $1, $2, $4, $3 }' "$tmp/orig/B_to_A.txt" >"$tmp/orig_B_to_A_in_inverted_order.txt"
expect "fix-orientation: B_to_A is the original's, in the inverted file's order" 0 "max error: +0 " -- \
  eval "$tmp/fixed/B_to_A.txt" "$tmp/orig_B_to_A_in_inverted_order.txt" --target "$tmp/inside_out.off"
expect "fix-orientation: A_to_B is the original's" 0 "max error: +0 " -- \
  eval "$tmp/fixed/A_to_B.txt" "$tmp/orig/A_to_B.txt" --target "$meshes/ellipsoid.off"
printf '0 0\n1 1\n' >"$tmp/two_pairs.txt"
expect "fix-orientation does not hide other problems" 4 "torus.off: cannot be mapped: .*genus 1" -- \
  map "$data/bad/torus.off" "$meshes/ellipsoid.off" -l "$tmp/two_pairs.txt" -o "$tmp/torus" --fix-orientation

accepted() {  # NAME KIND VALUE
  pair "$2" "$3"
  expect "$1: check A" 0 "mappable: *yes" -- check "$tmp/A.off"
  expect "$1: check B" 0 "mappable: *yes" -- check "$tmp/B.off"
  expect "$1: map" 0 ".*" -- map "$tmp/A.off" "$tmp/B.off" -l "$lm" -o "$tmp/ok" --quiet
  require "$1: verification passed" grep -q '"passed": true' "$tmp/ok/report.json"
}
accepted "translated by 1e4" translate 1e4
accepted "scaled by 1e29" scale 1e29
accepted "scaled by 1e-29" scale 1e-29

# A device is no input (a link to /dev/zero was read until memory ran out); a pipe is (process substitution).
ln -s /dev/zero "$tmp/zero.off"
expect "device as a mesh" 3 "^liftmap: .*zero.off: is a device or socket, not a mesh file" -- check "$tmp/zero.off"
expect "device as landmarks" 3 "^liftmap: /dev/zero: is a device or socket, not a landmark file" -- \
  map "$meshes/larger_sphere.off" "$meshes/ellipsoid.off" -l /dev/zero -o "$tmp/device"
require "device as landmarks: no output folder" test ! -e "$tmp/device"
expect "landmarks from a pipe" 0 ".*" -- map "$meshes/larger_sphere.off" "$meshes/ellipsoid.off" \
  -l <(cat "$lm") -o "$tmp/pipe" --quiet --max-iterations 0
require "landmarks from a pipe: verification passed" grep -q '"passed": true' "$tmp/pipe/report.json"
finish
