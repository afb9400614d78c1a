#!/usr/bin/env bash
# liftmap check on libcgal-demo meshes: genus-0 meshes are mappable (exit 0, "genus: 0"); a genus-3 mesh, an
# open mesh and a mesh of many components are rejected (exit 4) with the reason.
set -u
liftmap="$1"
meshes="$2"
failures=0
expect() {  # file exit stdout-pattern stderr-pattern
  out=$(timeout 120 "$liftmap" check "$meshes/$1" 2>/tmp/liftmap_check_err.$$)
  code=$?
  err=$(cat /tmp/liftmap_check_err.$$)
  rm -f /tmp/liftmap_check_err.$$
  if [ "$code" != "$2" ] || ! grep -qE -- "$3" <<<"$out" || ! grep -qE -- "$4" <<<"$err"; then
    echo "FAIL $1: exit $code (expected $2)"
    echo "$out"
    echo "$err"
    failures=$((failures + 1))
  fi
}
for m in camel cow man bull dino armadillo; do
  expect "$m.off" 0 "genus: +0" "^$"
done
expect elephant.off 4 "genus: +3" "genus 3: only genus 0 is supported"
expect head.off 4 "boundary loops: +3" "3 boundary loop\(s\): only closed surfaces can be mapped"
expect bones.off 4 "connected components: +26" "26 connected components"
echo "real meshes: $failures failed"
[ "$failures" = 0 ]
