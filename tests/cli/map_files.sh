#!/usr/bin/env bash
# Map files read by `eval` and `transfer` are validated (issue 26: `eval` printed "mean error: nan" and exited 0
# for NaN barycentrics; `transfer` wrote NaN or off-surface points for negative ones, ones that do not sum to 1,
# or 1e308): the file and line named, exit 3 for a line that is not a face index and 3 numbers, exit 4 for
# barycentric coordinates that are not a point of the face.
set -u
liftmap="$1"
meshes="$2"
examples="$3"
source "$(dirname "$0")/lib.sh"
a="$meshes/larger_sphere.off"
b="$meshes/ellipsoid.off"
expect "map" 0 ".*" -- map "$a" "$b" -l "$examples/sphere-ellipsoid/landmarks.txt" -o "$tmp/m" --quiet
good="$tmp/m/A_to_B.txt"
first=$(grep -n -v '^#' "$good" | head -1 | cut -d: -f1)  # line number of the first map line

corrupt() {  # NAME REPLACEMENT: the first map line replaced
  awk -v n="$first" -v r="$2" 'NR == n { print r; next } { print }' "$good" >"$tmp/$1.txt"
}
bad() {  # NAME REPLACEMENT CODE PATTERN
  corrupt "$1" "$2"
  local f="$tmp/$1.txt"
  expect "$1: eval" "$3" "^liftmap: $f:$first: $4" -- eval "$f" "$good" --target "$b"
  expect "$1: eval as truth" "$3" "^liftmap: $f:$first: $4" -- eval "$good" "$f" --target "$b"
  expect "$1: transfer mesh" "$3" "^liftmap: $f:$first: $4" -- transfer mesh "$f" --onto "$b" --connectivity "$a" \
    -o "$tmp/$1_out.obj"
  require "$1: transfer wrote nothing" test ! -e "$tmp/$1_out.obj"
}
bad nan "0 nan 0.5 0.5" 4 "barycentric coordinate nan is not finite"
bad inf "0 inf 0 0" 4 "barycentric coordinate inf is not finite"
bad negative "0 -0.5 1 0.5" 4 "barycentric coordinate -0.5 is negative: the point is outside face 0"
bad sum "0 0.5 0.5 0.5" 4 "barycentric coordinates sum to 1.5, not 1"
bad huge "0 1e308 0 0" 4 "barycentric coordinates sum to 1e\+308, not 1"
bad face_range "320 1 0 0" 3 "face 320 is not a face index of the target mesh \(320 faces\)"
bad face_negative "-1 1 0 0" 3 "face -1 is not a face index"
bad face_fraction "2.5 1 0 0" 3 "face 2.5 is not a face index"
bad face_nan "nan 1 0 0" 3 "face nan is not a face index"
bad columns "0 1 0" 3 "expected 'face b0 b1 b2', found 3 fields"
bad word "0 one 0 0" 3 "'one' is not a number"

# Within the tolerance (1e-6) coordinates as another tool prints them (7 digits) are accepted.
corrupt rounded "0 0.3333333 0.3333333 0.3333334"
expect "rounded coordinates accepted" 0 "mean error" -- eval "$tmp/rounded.txt" "$good" --target "$b"
expect "map against itself" 0 "mean error: 0" -- eval "$good" "$good" --target "$b"

# transfer mesh reports the triangles folded against the target and lists them (issue 25): none for
# sphere-ellipsoid; all of them for the source faces reversed.
expect "transfer mesh" 0 "^liftmap: 0 of 1620 transferred triangles are folded" -- \
  transfer mesh "$good" --onto "$b" --connectivity "$a" -o "$tmp/a_on_b.obj"
require "folded list written" grep -q "0 of 1620" "$tmp/a_on_b.obj.folded.txt"
python3 "$(dirname "$0")/make_variant.py" invert "$a" "$tmp/inverted.off"
expect "transfer mesh, reversed faces" 0 "^liftmap: 1620 of 1620 transferred triangles are folded" -- \
  transfer mesh "$good" --onto "$b" --connectivity "$tmp/inverted.off" -o "$tmp/inv_on_b.obj"
require "folded list holds every face" test "$(grep -c -v '^#' "$tmp/inv_on_b.obj.folded.txt")" = 1620

# Map files and the overlay name the meshes they were made for (vertex and face counts, a hash of the faces): a map
# applied to other meshes is refused (exit 4, both files named) where it gave exit 0 and a meaningless output.
# Another pose of the same mesh (the same faces) is accepted; so are files that name no mesh (other tools).
require "A_to_B.txt names A" grep -q "^# source mesh: 812 vertices, 1620 faces, connectivity fnv1a64:" "$good"
require "A_to_B.txt names B" grep -q "^# target mesh: 162 vertices, 320 faces, connectivity fnv1a64:" "$good"
require "B_to_A.txt names them the other way" grep -q "^# target mesh: 812 vertices" "$tmp/m/B_to_A.txt"
require "the overlay names them" grep -q "^# target mesh: 162 vertices" "$tmp/m/overlay_points.txt"
cp "$meshes/cow.off" "$tmp/cow.off"
not_b="made for a target mesh with 162 vertices, 320 faces, connectivity fnv1a64:[0-9a-f]{16}, but $tmp/cow.off has"
expect "transfer mesh onto another mesh" 4 "^liftmap: $good: $not_b" -- \
  transfer mesh "$good" --onto "$tmp/cow.off" --connectivity "$a" -o "$tmp/other.obj"
require "nothing written onto another mesh" test ! -e "$tmp/other.obj"
expect "transfer mesh from another mesh" 4 "^liftmap: $good: 812 lines, but $tmp/cow.off has 2904 vertices" -- \
  transfer mesh "$good" --onto "$b" --connectivity "$tmp/cow.off" -o "$tmp/other.obj"
grep -v -e '^# source mesh: ' -e '^# target mesh: ' "$good" >"$tmp/unnamed.txt"  # as a map of another tool
cat "$tmp/unnamed.txt" <(echo "# target mesh: 1 vertices, 0 faces, connectivity fnv1a64:0000000000000000") >"$tmp/late.txt"
expect "a mesh line after the map lines" 4 "^liftmap: $tmp/late.txt: made for a target mesh with 1 vertices" -- \
  eval "$tmp/late.txt" "$good" --target "$b"
seq 1 162 >"$tmp/on_b.txt"
expect "transfer attributes onto another mesh" 4 "^liftmap: $tmp/m/A_to_B.txt: made for a target mesh with 162 vertices" -- \
  transfer attributes "$tmp/m/A_to_B.txt" --onto "$tmp/cow.off" --data "$tmp/on_b.txt" -o "$tmp/other.txt"
expect "eval on another mesh" 4 "^liftmap: $good: $not_b" -- eval "$good" "$good" --target "$tmp/cow.off"
sed 's/^# source mesh: 812 vertices/# source mesh: 999 vertices/' "$good" >"$tmp/from_other.txt"
expect "eval of maps from two meshes" 4 "^liftmap: $good: 812 map lines from a mesh with 812 vertices, .* but $tmp/from_other.txt has 812 from a mesh with 999 vertices" -- \
  eval "$good" "$tmp/from_other.txt" --target "$b"
expect "transfer mesh --exact onto another mesh" 4 "^liftmap: $tmp/m/overlay_points.txt: $not_b" -- \
  transfer mesh --exact "$tmp/m/overlay.obj" --onto "$tmp/cow.off" --connectivity "$a" -o "$tmp/other.obj"
mkdir -p "$tmp/blank"
cp "$tmp/m/overlay.obj" "$tmp/m/overlay_faces.txt" "$tmp/blank/"
{ echo; cat "$tmp/m/overlay_points.txt"; } >"$tmp/blank/overlay_points.txt"
expect "transfer mesh --exact, the table's lines after a blank line" 4 \
  "^liftmap: $tmp/blank/overlay_points.txt: made for a source mesh with 812 vertices, .* but $b has 162" -- \
  transfer mesh --exact "$tmp/blank/overlay.obj" --onto "$b" --connectivity "$b" -o "$tmp/other.obj"
python3 "$(dirname "$0")/make_variant.py" scale "$b" "$tmp/b_scaled.off" 3
expect "transfer mesh onto another pose of B" 0 "^liftmap: 0 of 1620 transferred triangles are folded" -- \
  transfer mesh "$good" --onto "$tmp/b_scaled.off" --connectivity "$a" -o "$tmp/a_on_scaled_b.obj"
expect "a map that names no mesh" 0 "mean error: 0" -- eval "$tmp/unnamed.txt" "$good" --target "$b"

# The overlay (issue 32): written with the map, its checks in report.json, and `transfer mesh --exact` places it on B
# with no folded triangle; damaged overlay tables are refused naming the file and line.
for f in overlay.obj overlay_points.txt overlay_faces.txt; do require "map wrote $f" test -s "$tmp/m/$f"; done
require "overlay checks in report.json" python3 -c "
import json, sys
o = json.load(open('$tmp/m/report.json'))['overlay']
sys.exit(not (o['area_error_A'] < 1e-12 and o['area_error_B'] < 1e-12 and o['uncovered_faces_A'] == 0
              and o['uncovered_faces_B'] == 0 and o['vertex_error'] < 1e-12 and o['triangles'] > 1620))"
expect "transfer mesh --exact" 0 "^liftmap: 0 of [0-9]+ transferred triangles are folded" -- \
  transfer mesh --exact "$tmp/m/overlay.obj" --onto "$b" --connectivity "$a" -o "$tmp/exact_on_b.obj"
mkdir -p "$tmp/ov"
cp "$tmp/m/overlay.obj" "$tmp/ov/overlay.obj"
head -n -1 "$tmp/m/overlay_points.txt" >"$tmp/ov/overlay_points.txt"
cp "$tmp/m/overlay_faces.txt" "$tmp/ov/overlay_faces.txt"
expect "overlay table one row short" 3 "^liftmap: $tmp/ov/overlay_points.txt: expected [0-9]+ rows of 8 numbers" -- \
  transfer mesh --exact "$tmp/ov/overlay.obj" --onto "$b" --connectivity "$a" -o "$tmp/short.obj"
require "nothing written for a short table" test ! -e "$tmp/short.obj"
cp "$tmp/m/overlay_points.txt" "$tmp/ov/overlay_points.txt"
awk 'NR == 3 { print "99999 0"; next } { print }' "$tmp/m/overlay_faces.txt" >"$tmp/ov/overlay_faces.txt"
expect "overlay face out of range" 4 "^liftmap: $tmp/ov/overlay_faces.txt:3: 99999 is not a face index of A" -- \
  transfer mesh --exact "$tmp/ov/overlay.obj" --onto "$b" --connectivity "$a" -o "$tmp/range.obj"
finish
