#!/usr/bin/python3
"""Times CVXOPT on an exported subproblem (tests/flatten/cvxopt_reference.py's formulation) and prints the
ratio to our time. Usage: cvxopt_time.py INSTANCE.json OUR_SECONDS"""

import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "tests", "flatten"))
from cvxopt_reference import Instance  # noqa: E402

inst = Instance(sys.argv[1])
ours = float(sys.argv[2])
t0 = time.perf_counter()
obj, X = inst.solve()
sec = time.perf_counter() - t0
print("cvxopt %.3f s (objective %.10g), ours %.3f s (objective %.10g): ratio %.1fx, objective rel. diff %.1e"
      % (sec, obj, ours, inst.obj_ours, sec / ours, abs(obj - inst.obj_ours) / obj))
