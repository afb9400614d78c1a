#!/usr/bin/env bash
# `liftmap batch` (issue 30). A manifest of 6 pairs (2 that map, one with a bad landmark file, one with a
# non-manifold mesh, one with a genus-1 mesh, one with a missing mesh) is killed after its first pair and resumed:
# every good pair's folder holds exactly the files of `liftmap map` (report.json equal but for its wall times), the
# bad pairs are in summary.csv with their exit codes (4, 4, 4, 3) and messages, and the batch exits with 6. Each map
# costs seconds (its pictures; about 15 s under AddressSanitizer), hence only two good pairs, and a 5th argument
# `without-reference` skips the comparison with `liftmap map` (the sanitizer build: 2 of its 6 maps). Two shards run at the same time into one folder make the files of
# the unsharded run. Manifest and option errors stop the batch before any pair is mapped.
set -u
liftmap="$1"
meshes="$2"
examples="$3"
data="$4"
reference="${5:-with-reference}"
source "$(dirname "$0")/lib.sh"
a="$meshes/larger_sphere.off"
b="$meshes/ellipsoid.off"

# The manifest: relative paths are read from its folder; the last pair gets the default name.
in="$tmp/in"
mkdir -p "$in/lm"
sed 's/#.*//' "$examples/sphere-ellipsoid/landmarks.txt" | awk 'NF { print $1, $2 }' >"$in/lm/se.txt"
printf '0 0\n1 1\n' >"$in/lm/nm.txt"
manifest="$in/manifest.csv"
cat >"$manifest" <<EOF
# issue 30's test manifest
name,mesh_a,mesh_b,landmarks,tree,max_iterations
sphere-ellipsoid,$a,$b,lm/se.txt,,
path-tree,$a,$b,lm/se.txt,path,3
bad-landmarks,$a,$b,$data/bad/lm_duplicate_a.txt,,
non-manifold,$data/bad/nonmanifold_edge.off,$b,lm/nm.txt,,
,missing.off,$b,lm/se.txt,,
torus,$data/bad/torus.off,$b,lm/nm.txt,,
EOF
good=(sphere-ellipsoid path-tree)

# The reference: `liftmap map` on the same paths with the same options, one thread as each batch map has.
ref="$tmp/ref"
if [ "$reference" = with-reference ]; then
  expect "map sphere-ellipsoid" 0 ".*" -- map "$a" "$b" -l "$in/lm/se.txt" -o "$ref/sphere-ellipsoid" --threads 1 -q
  expect "map path-tree" 0 ".*" -- map "$a" "$b" -l "$in/lm/se.txt" -o "$ref/path-tree" --tree path \
    --max-iterations 3 --threads 1 -q
fi

# Killed (SIGKILL) once a pair is complete, then resumed with two pairs at a time.
bout="$tmp/out"
"$liftmap" batch "$manifest" -o "$bout" --threads 1 -q >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 6000); do  # up to 5 minutes (AddressSanitizer on a busy machine)
  [ "$(ls "$bout"/*/report.json 2>/dev/null | wc -l)" -ge 1 ] && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.05
done
kill -KILL "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
complete=$(ls "$bout"/*/report.json 2>/dev/null | wc -l)
require "killed with 1 of the 2 good pairs complete ($complete)" test "$complete" = 1
expect "resumed run" 6 "^liftmap: batch: 6 pairs in .*summary.csv: 2 ok, 4 failed, 0 pending; shard 0/1: 6 pairs, \
5 mapped now, 1 complete before, 4 failed" -- batch "$manifest" -o "$bout" --jobs 2 --threads 2
require "progress: skipped pairs" grep -q "^liftmap: batch: $complete of 6 pairs already complete: skipped" <<<"$err"
require "progress: a line per pair" test "$(grep -cE "^liftmap: batch: \[[2-6]/6\] [^ ]+: (ok in [0-9]+ s|failed \
\(exit [34]\): .*) \| [0-4] failed, [0-9]+ s elapsed" <<<"$err")" = 5
require "progress: estimated remaining time" grep -qE "elapsed, about [0-9]+ s left$" <<<"$err"
if [ "$reference" = with-reference ]; then
  for name in "${good[@]}"; do same_pair "$name" "$bout/$name" "$ref/$name"; done
fi
require "no temporary file left" test -z "$(find "$bout" -name '*.tmp-*')"
summary="$bout/summary.csv"
require "summary: a header and 6 rows" test "$(wc -l <"$summary")" = 7
for name in "${good[@]}"; do
  require "summary: $name ok and verified" grep -qE "^$name,ok,0,[0-9.e+-]+(,[0-9.e+-]+){6},yes,$" "$summary"
done
require "summary: bad landmark file, exit 4" \
  grep -qE "^bad-landmarks,failed,4,.*,no,.*lm_duplicate_a.txt:2: vertex 0 of mesh A is already a landmark" "$summary"
require "summary: non-manifold mesh, exit 4" \
  grep -qE '^non-manifold,failed,4,.*,no,".*nonmanifold_edge.off: cannot be mapped: .*edge \(0, 1\) is shared by 3' \
  "$summary"
require "summary: genus 1, exit 4" grep -qE "^torus,failed,4,.*,no,.*torus.off: cannot be mapped: .*genus 1" "$summary"
require "summary: missing mesh, exit 3" grep -qE "^missing-ellipsoid,failed,3,.*,no,.*in/missing.off: " "$summary"
for name in bad-landmarks non-manifold torus missing-ellipsoid; do
  require "$name: no report" test ! -e "$bout/$name/report.json"
done

# A second resume maps only the failed pairs again.
expect "second resume" 6 "shard 0/1: 6 pairs, 4 mapped now, 2 complete before, 4 failed" -- \
  batch "$manifest" -o "$bout" --threads 1 -q

# Two shards at the same time into one folder (a good pair in each): the files of the unsharded run.
sharded="$tmp/sharded"
"$liftmap" batch "$manifest" -o "$sharded" --shard 0/2 --threads 1 -q >"$tmp/shard0.txt" 2>&1 &
p0=$!
"$liftmap" batch "$manifest" -o "$sharded" --shard 1/2 --threads 1 -q >"$tmp/shard1.txt" 2>&1 &
p1=$!
wait "$p0"
c0=$?
wait "$p1"
c1=$?
require "shard 0/2 exits 6 (its pairs failed)" test "$c0" = 6
require "shard 1/2 exits 6 (its pairs failed)" test "$c1" = 6
require "shards: the same folders" diff <(ls -A "$sharded") <(ls -A "$bout")
for name in "${good[@]}"; do same_pair "shards: $name" "$sharded/$name" "$bout/$name"; done
require "shards: summary.csv equal but for seconds" python3 -c '
import csv, sys
rows = [[r[:3] + r[4:] for r in csv.reader(open(p))] for p in sys.argv[1:]]
assert rows[0] == rows[1], rows' "$sharded/summary.csv" "$summary"

# Errors of the whole batch: exit 2 or 3 before any pair is mapped.
never="$tmp/never"
bad_manifest() {  # NAME CODE PATTERN CONTENT
  printf '%s\n' "$4" >"$tmp/bad.csv"
  expect "$1" "$2" "^liftmap: $3" -- batch "$tmp/bad.csv" -o "$never"
  require "$1: nothing written" test ! -e "$never"
}
bad_manifest "unknown column" 2 ".*bad.csv:1: unknown column 'colour'" "mesh_a,mesh_b,landmarks,colour"
bad_manifest "threads column" 2 ".*bad.csv:1: threads cannot be set per pair" "mesh_a,mesh_b,landmarks,threads"
bad_manifest "missing column" 3 ".*bad.csv:1: the header has no column 'landmarks'" "mesh_a,mesh_b"
bad_manifest "bad option value" 2 ".*bad.csv:2: column max_iterations: value -1 not in range 0 to 10000" \
  "$(printf 'mesh_a,mesh_b,landmarks,max_iterations\na.off,b.off,l.txt,-1')"
bad_manifest "field count" 3 ".*bad.csv:2: 2 fields, but the header has 3" "$(printf 'mesh_a,mesh_b,landmarks\na,b')"
bad_manifest "duplicate name" 2 ".*bad.csv:3: the name 'a-b' is already the name of line 2" \
  "$(printf 'mesh_a,mesh_b,landmarks\na.off,b.off,l.txt\na.off,b.off,m.txt')"
bad_manifest "name with a slash" 2 ".*bad.csv:2: 'a/x' is a name with a '/'" \
  "$(printf 'name,mesh_a,mesh_b,landmarks\na/x,a.off,b.off,l.txt')"
expect "missing manifest" 3 "^liftmap: .*missing.csv: cannot open manifest" -- batch "$tmp/missing.csv" -o "$never"
expect "bad shard" 2 "^liftmap: --shard: '2/2' is not i/n" -- batch "$manifest" -o "$never" --shard 2/2
expect "bad jobs" 2 "^liftmap: .*--jobs" -- batch "$manifest" -o "$never" --jobs 0
expect "bad option" 2 "^liftmap: --max-iterations: value 10001 not in range 0 to 10000" -- \
  batch "$manifest" -o "$never" --max-iterations 10001
require "nothing written" test ! -e "$never"

# Pictures per pair from the manifest's column, or for every pair from --no-pictures.
cat >"$in/pictures.csv" <<EOF
name,mesh_a,mesh_b,landmarks,pictures
drawn,$a,$b,lm/se.txt,
not-drawn,$a,$b,lm/se.txt,false
EOF
expect "batch with a pictures column" 0 "2 ok, 0 failed" -- batch "$in/pictures.csv" -o "$tmp/pictures" -q
require "pictures: drawn by default" test -s "$tmp/pictures/drawn/render.png"
require "pictures: false in the manifest" test ! -e "$tmp/pictures/not-drawn/render.png"
require "pictures: the rest written" test -s "$tmp/pictures/not-drawn/A_to_B.txt"
expect "batch --no-pictures" 0 "1 ok, 0 failed" -- batch "$in/pictures.csv" -o "$tmp/no_pictures" -q --no-pictures \
  --shard 0/2
require "--no-pictures: none drawn" test ! -e "$tmp/no_pictures/drawn/render.png"
require "--no-pictures: the pair mapped" grep -q '"passed": true' "$tmp/no_pictures/drawn/report.json"
finish
