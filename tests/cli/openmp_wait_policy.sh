#!/usr/bin/env bash
# The liftmap executable runs with OpenMP's passive wait policy unless the user chose a policy or a spin count
# (app/passive_openmp_waits.h): report.json records the policy the map ran with.
set -u
liftmap="$1"
meshes="$2"
examples="$3"
source "$(dirname "$0")/lib.sh"
policy_of() {  # FOLDER: the report's run.openmp_wait_policy
  /usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["run"]["openmp_wait_policy"])' \
    "$1/report.json"
}
map() {  # FOLDER: a map of the example without optimisation
  expect "map into $1" 0 ".*" -- map "$meshes/larger_sphere.off" "$meshes/ellipsoid.off" \
    -l "$examples/sphere-ellipsoid/landmarks.txt" -o "$tmp/$1" --max-iterations 0 --quiet
}
unset OMP_WAIT_POLICY GOMP_SPINCOUNT
map unset
require "unset: passive" test "$(policy_of "$tmp/unset")" = passive
export OMP_WAIT_POLICY=active
map active
require "the user's choice kept" test "$(policy_of "$tmp/active")" = active
unset OMP_WAIT_POLICY
export GOMP_SPINCOUNT=1000
map spin
require "a spin count set: libgomp's default policy" test "$(policy_of "$tmp/spin")" = default
finish
