#!/usr/bin/env bash
# The bundled example: checks an example pair of libcgal-demo meshes and their landmarks.
set -euo pipefail
liftmap="$1"
root="$(cd "$(dirname "$0")/.." && pwd)"
example="$root/examples/camel-cow"
"$liftmap" check "$root/data/meshes/camel.off" "$root/data/meshes/cow.off" -l "$example/landmarks.txt"
echo "demo: camel.off and cow.off are mappable and the landmarks of $example are valid"
