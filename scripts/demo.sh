#!/usr/bin/env bash
# The bundled example: maps larger_sphere.off onto ellipsoid.off (libcgal-demo), examples/sphere-ellipsoid.
set -euo pipefail
liftmap="$1"
root="$(cd "$(dirname "$0")/.." && pwd)"
example="$root/examples/sphere-ellipsoid"
read -r mesh_a mesh_b <"$example/meshes.txt"
out="$root/out/sphere-ellipsoid"
"$liftmap" map "$root/data/meshes/$mesh_a" "$root/data/meshes/$mesh_b" -l "$example/landmarks.txt" -o "$out"
echo
echo "demo: the map and its report are in $out"
ls "$out"
for picture in render.png distortion.png; do
  if [ -f "$out/$picture" ]; then echo "picture: $out/$picture"; fi
done
