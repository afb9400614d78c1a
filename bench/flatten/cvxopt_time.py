#!/usr/bin/python3
"""Times CVXOPT on an exported subproblem (tests/flatten/cvxopt_reference.py's formulation) and prints the
ratio to our time. Usage: cvxopt_time.py INSTANCE.json OUR_SECONDS [sparse|dense]

sparse (the default): CVXOPT's interior-point method with the sparse KKT solver of
tests/flatten/cvxopt_sparse_kkt.py (UMFPACK, CVXOPT's own sparse LU). dense: `solvers.socp` with its default KKT
solver ('qr', on dense copies of the constraint matrix), whose time grows like faces^2.7 on these problems.
CVXOPT runs at tolerance 1e-8 (abstol, reltol, feastol), the accuracy our solver is asked for (relative gap
1e-8), and retries at 1e-7 only if its scaling update fails ("domain error"): the differential test's tighter
retries make its time erratic. The time includes building the problem in Python (under 2% of it)."""

import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tests", "flatten"))
from cvxopt_reference import Instance  # noqa: E402

inst = Instance(sys.argv[1])
ours = float(sys.argv[2])
kkt = sys.argv[3] if len(sys.argv) > 3 else "sparse"
t0 = time.perf_counter()
obj, X = inst.solve(tolerances=(1e-8, 1e-7), kkt=kkt)
sec = time.perf_counter() - t0
print("cvxopt (%s KKT) %.3f s (objective %.10g), ours %.3f s (objective %.10g): ratio %.1fx, objective rel. diff %.1e"
      % (kkt, sec, obj, ours, inst.obj_ours, sec / ours, abs(obj - inst.obj_ours) / obj))
print("cvxopt_seconds %.6f objective %.12g" % (sec, obj))
