#!/usr/bin/env bash
# Every message says what it is (issue 26), on the inputs that exposed it: counts that do not match the
# header, a byte-order mark, an OFF written on one line, a PLY index of -5, NaN in PLY and STL, the boundary
# of a non-manifold mesh, and `check A B -l L --json` as one JSON document with the landmark verdict.
set -u
liftmap="$1"
meshes="$2"
examples="$3"
data="$4"
source "$(dirname "$0")/lib.sh"
variant="$(dirname "$0")/make_variant.py"
sphere="$meshes/larger_sphere.off"
b="$meshes/ellipsoid.off"
lm="$examples/sphere-ellipsoid/landmarks.txt"
v() { "$variant" "$1" "$sphere" "$tmp/$2" ${3:+"$3"}; }

# Counts that do not match the content: not "the mesh is open".
v extra_face extra_face.off
expect "OFF with one face too many" 3 "extra_face.off:[0-9]+: the header announces 812 vertices and 1619 faces, but the file goes on" \
  -- check "$tmp/extra_face.off"
v stl_binary short.stl 1619
expect "binary STL count too small" 3 "short.stl: the binary STL header announces 1619 triangles .*room for 1620 triangles" \
  -- check "$tmp/short.stl"
v stl_binary long.stl 1621
expect "binary STL count too large" 3 "long.stl: the binary STL header announces 1621 triangles" -- check "$tmp/long.stl"
v stl_binary good.stl
expect "binary STL" 0 "vertices: +812" -- check "$tmp/good.stl"
require "no 'open' for count mismatches" bash -c "! grep -q open <<<\"\$1\"" _ "$err"

# A byte-order mark is skipped: same report as without it.
v bom bom.off
expect "OFF with a byte-order mark" 0 "mappable: +yes" -- check "$tmp/bom.off"
printf '\xef\xbb\xbf' >"$tmp/bom_landmarks.txt"
cat "$lm" >>"$tmp/bom_landmarks.txt"
expect "landmarks with a byte-order mark" 0 "landmarks: +6 pairs" -- check "$sphere" "$b" -l "$tmp/bom_landmarks.txt"

# An OFF written on one line.
v one_line one_line.off
expect "OFF on one line" 3 "one_line.off:1: [0-9]+ more values after the 'vertices faces edges' counts: .*written on one line" \
  -- check "$tmp/one_line.off"

# A negative PLY index is printed as written, not as 2^64 - 5.
v ply_ascii neg.ply -5
expect "ASCII PLY index -5" 3 "neg.ply: face 0 references vertex -5, but there are 812 vertices" -- check "$tmp/neg.ply"
v ply_binary neg_bin.ply -5
expect "binary PLY index -5" 3 "neg_bin.ply: face 0 references vertex -5" -- check "$tmp/neg_bin.ply"
v ply_ascii good.ply
expect "ASCII PLY" 0 "mappable: +yes" -- check "$tmp/good.ply"

# NaN in PLY and STL: a non-finite coordinate (exit 4), as in OFF.
v ply_nan nan.ply
expect "NaN in ASCII PLY" 4 "nan.ply:10: non-finite coordinate 'nan'" -- check "$tmp/nan.ply"
v stl_ascii_nan nan.stl
expect "NaN in ASCII STL" 4 "nan.stl: cannot be mapped: vertex 0 has a non-finite coordinate \(.*, nan, .*\)$" -- check "$tmp/nan.stl"

# Boundary loops are not "0" beside boundary edges.
expect "non-manifold: loops undefined" 4 "boundary loops: +undefined \(not a manifold\)" -- check "$data/bad/nonmanifold_edge.off"
require "non-manifold: boundary edges counted" grep -qE "boundary edges: +[1-9]" <<<"$out"
expect "open mesh: loops and edges" 4 "boundary loops: +1" -- check "$data/bad/single_triangle.off"
require "open mesh: 3 boundary edges" grep -qE "boundary edges: +3" <<<"$out"

# check A B -l L --json: one JSON document with the landmark verdict.
json_has() {  # NAME PYTHON-EXPRESSION-ON-doc
  checks=$((checks + 1))
  if ! python3 -c "import json, sys; doc = json.loads(sys.stdin.read()); sys.exit(0 if ($2) else 1)" <<<"$out" 2>/dev/null; then
    echo "FAIL $1: stdout is not one JSON document with $2:"
    echo "$out" | head -20
    failures=$((failures + 1))
  fi
}
expect "check --json with landmarks" 0 ".*" -- check "$sphere" "$b" -l "$lm" --json
json_has "valid landmarks" "len(doc['meshes']) == 2 and doc['landmarks']['valid'] and doc['landmarks']['pairs'] == 6 and doc['mappable']"
printf '286 117\n286 138\n' >"$tmp/dup_landmarks.txt"
expect "check --json with invalid landmarks" 4 "dup_landmarks.txt:2: vertex 286 of mesh A is already a landmark" -- \
  check "$sphere" "$b" -l "$tmp/dup_landmarks.txt" --json
json_has "invalid landmarks" "not doc['landmarks']['valid'] and 'already a landmark' in doc['landmarks']['error'] and not doc['mappable']"
expect "check --json of one mesh" 0 ".*" -- check "$sphere" --json
json_has "one mesh" "doc['meshes'][0]['genus'] == 0 and 'landmarks' not in doc"
finish
