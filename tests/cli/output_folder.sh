#!/usr/bin/env bash
# Output folders never mislead (issue 26): outputs are renamed into place (a symlink is replaced, its target
# untouched), report.json is written last, the previous run's files are removed at the start (a failed run
# leaves no stale passing report.json; `cut` into a map's folder leaves no map file), the folder's
# writability is checked before any computation, and an input that an output would overwrite is refused.
set -u
liftmap="$1"
meshes="$2"
examples="$3"
data="$4"
source "$(dirname "$0")/lib.sh"
variant="$(dirname "$0")/make_variant.py"
a="$meshes/larger_sphere.off"
b="$meshes/ellipsoid.off"
lm="$examples/sphere-ellipsoid/landmarks.txt"
dir="$tmp/out"

# A symlink named report.json: replaced by the report, the file it points to untouched.
mkdir -p "$dir"
echo "not a report" >"$tmp/target.txt"
ln -s "$tmp/target.txt" "$dir/report.json"
ln -s "$tmp/target.txt" "$dir/A_to_B.txt"
expect "map over symlinks" 0 ".*" -- map "$a" "$b" -l "$lm" -o "$dir" --quiet
require "symlink target untouched" test "$(cat "$tmp/target.txt")" = "not a report"
require "report.json is a regular file" bash -c "test -f '$dir/report.json' && test ! -L '$dir/report.json'"
require "A_to_B.txt is a regular file" test ! -L "$dir/A_to_B.txt"
require "report says passed" grep -q '"passed": true' "$dir/report.json"
require "no temporary file left" bash -c "! ls -A '$dir' | grep -q tmp"
require "report.json is the newest file" bash -c "test -z \"\$(find '$dir' -newer '$dir/report.json' -type f)\""

# A failed run into the same folder leaves none of the previous run's files.
"$variant" invert "$a" "$tmp/inside_out.off"
expect "failed run" 4 "inside_out.off: cannot be mapped" -- map "$tmp/inside_out.off" "$b" -l "$lm" -o "$dir"
require "no stale report.json" test ! -e "$dir/report.json"
require "no stale map" test ! -e "$dir/A_to_B.txt"

# `cut` into a map's folder: the map's own files go too, the folder holds one run.
expect "map again" 0 ".*" -- map "$a" "$b" -l "$lm" -o "$dir" --quiet
expect "cut into the map's folder" 0 ".*" -- cut "$a" "$b" -l "$lm" -o "$dir" --quiet
for f in report.json A_to_B.txt B_to_A.ijv render.png texture.png cut_A_to_B.txt; do
  require "cut removed $f" test ! -e "$dir/$f"
done
for f in cut_A.obj cut_B.obj boundary_map.txt cut_graph_A.obj cut_graph_B.obj; do
  require "cut wrote $f" test -s "$dir/$f"
done

# --no-pictures: every file of the map but the two pictures, and a previous run's pictures removed.
expect "map again" 0 ".*" -- map "$a" "$b" -l "$lm" -o "$dir" --quiet
require "the default draws render.png" test -s "$dir/render.png"
cp -r "$dir" "$tmp/with_pictures"
expect "map without pictures" 0 ".*" -- map "$a" "$b" -l "$lm" -o "$dir" --quiet --no-pictures
for f in render.png distortion.png; do
  require "--no-pictures: no $f" test ! -e "$dir/$f"
done
for f in $(ls "$tmp/with_pictures"); do
  case "$f" in
    render.png | distortion.png) ;;
    report.json) require "--no-pictures: report says passed" grep -q '"passed": true' "$dir/report.json" ;;
    *) require "--no-pictures: $f as with the pictures" cmp -s "$tmp/with_pictures/$f" "$dir/$f" ;;
  esac
done

# An unwritable folder is found before any computation (as root, chmod does not stop writes: sysfs does).
if [ "$(id -u)" = 0 ]; then
  ro=/sys/kernel
else
  ro="$tmp/read_only"
  mkdir -p "$ro"
  chmod 555 "$ro"
fi
if touch "$ro/.liftmap_probe" 2>/dev/null; then
  rm -f "$ro/.liftmap_probe"
  echo "FAIL: no read-only folder to test with ($ro is writable)"
  failures=$((failures + 1))
fi
expect "read-only folder" 3 "^liftmap: $ro: cannot write into the output folder" -- map "$a" "$b" -l "$lm" -o "$ro"
require "read-only folder: nothing computed" bash -c "! grep -q '\] cut ' <<<\"\$1\"" _ "$err"
echo "a file" >"$tmp/file"
expect "folder is a file" 3 "^liftmap: $tmp/file(/.*)?: " -- map "$a" "$b" -l "$lm" -o "$tmp/file"
# The folder named as one of the inputs: the command line's mistake (exit 2), not an unwritable folder (exit 3).
expect "folder is an input mesh" 2 "^liftmap: the output $a would overwrite the input $a" -- map "$a" "$b" -l "$lm" -o "$a"
expect "folder is the landmark file" 2 "would overwrite the input $lm" -- map "$a" "$b" -l "$lm" -o "$lm"
mkdir -p "$tmp/blocked/render.png/inside"
expect "old output that cannot be removed" 3 "render.png: cannot remove the previous run's file" -- \
  map "$a" "$b" -l "$lm" -o "$tmp/blocked"
require "old output: nothing computed" bash -c "! grep -q '\] cut ' <<<\"\$1\"" _ "$err"

# An input that an output would overwrite is refused before anything is removed or computed.
in="$tmp/inputs"
mkdir -p "$in"
cp "$data/good/octahedron.obj" "$in/cut_A.obj"
cp "$data/good/landmarks.txt" "$in/report.json"
expect "input named like an output" 2 "^liftmap: the output $in/cut_A.obj would overwrite the input $in/cut_A.obj" -- \
  map "$in/cut_A.obj" "$data/good/octahedron.off" -l "$data/good/landmarks.txt" -o "$in"
require "input mesh intact" cmp -s "$data/good/octahedron.obj" "$in/cut_A.obj"
expect "landmarks named like an output" 2 "would overwrite the input $in/report.json" -- \
  cut "$data/good/octahedron.off" "$data/good/octahedron.off" -l "$in/report.json" -o "$in"
require "input landmarks intact" cmp -s "$data/good/landmarks.txt" "$in/report.json"
ln -s "$in/report.json" "$tmp/landmarks_link.txt"
expect "input through a symlink" 2 "would overwrite the input $tmp/landmarks_link.txt" -- \
  map "$data/good/octahedron.off" "$data/good/octahedron.off" -l "$tmp/landmarks_link.txt" -o "$in"
ln "$in/cut_A.obj" "$tmp/hard_link.obj"
expect "input through a hard link" 2 "would overwrite the input $tmp/hard_link.obj" -- \
  map "$tmp/hard_link.obj" "$data/good/octahedron.off" -l "$data/good/landmarks.txt" -o "$in"
expect "transfer onto its own input" 2 "would overwrite the input" -- \
  transfer mesh "$dir/cut_A_to_B.txt" --onto "$b" --connectivity "$a" -o "$b"
finish
