#!/usr/bin/env bash
# One validation for `check` and `map` (issue 26): an inside-out mesh and coordinates the pipeline cannot
# handle are reported by `check` and rejected by `map` with exit 4, naming the file, before any computation;
# copies inside the documented limits map and verify.
set -u
liftmap="$1"
meshes="$2"
examples="$3"
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
finish
