#!/usr/bin/env bash
# A coarse subproblem that ends above its start is solved again from the same start, finer, and a map whose second
# solve ends above its start too is converged (docs/algorithm.md, "When a subproblem ends above its start"). The
# example pairs never take that path; sphere-ellipsoid refined to about 60k faces per mesh does, in its second outer
# iteration (about 20 s; ctest -L slow). The map must converge through it with every invariant of the report kept.
set -u
liftmap="$1"
meshes="$2"
examples="$3"
subdivide="$4"
source "$(dirname "$0")/lib.sh"
"$subdivide" "$meshes/larger_sphere.off" "$tmp/A.off" 60000 >/dev/null
"$subdivide" "$meshes/ellipsoid.off" "$tmp/B.off" 60000 >/dev/null
expect "map" 0 "solved again to a finer gap" -- map "$tmp/A.off" "$tmp/B.off" \
  -l "$examples/sphere-ellipsoid/landmarks.txt" -o "$tmp/m" --threads 2
checks=$((checks + 1))
if ! /usr/bin/python3 - "$tmp/m/report.json" <<'PY'; then
import json
import sys

report = json.load(open(sys.argv[1]))
flatten, tolerance = report["flatten"], report["options"]["relative_tolerance"]
its = flatten["iterations"]
refined = [i for i, it in enumerate(its) if it.get("subproblem_refined")]
problems = []
# Either the second solve ended below its start (an outer iteration marked subproblem_refined) or above it too
# (converged there: last_subproblem_steps counts both solves).
if not refined and not flatten["last_subproblem_steps"] > 0:
    problems.append("no subproblem was solved again: the instance no longer exercises the path")
for i in refined:
    it = its[i]
    if not (it["subproblem_converged"] and it["subproblem_gap"] <= 0.5 * tolerance):
        problems.append(f"iteration {i}: the second solve is not certified at half the tolerance: {it}")
    if not it["subproblem_objective"] < its[i - 1]["energy"]:
        problems.append(f"iteration {i}: the second solve did not end below its start")
for i in range(1, len(its)):
    if its[i]["energy"] > its[i - 1]["energy"]:
        problems.append(f"iteration {i}: the energy rose")
if not flatten["converged"] or flatten["stop_reason"]:
    problems.append(f"not converged: {flatten['stop_reason']}")
if not report["verification"]["passed"]:
    problems.append(f"verification failed: {report['verification']['failures']}")
print("\n".join(problems))
sys.exit(1 if problems else 0)
PY
  echo "FAIL report.json of the refined map"
  failures=$((failures + 1))
fi
finish
