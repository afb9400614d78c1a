#!/usr/bin/python3
"""Differential test of the joint-flattening subproblem (10) against CVXOPT's second-order-cone solver.

Written from the paper's formulation (SIGGRAPH 2014, Sec. 3.3, eqs. (5), (7), (10)) in CVXOPT's standard form
    minimise c^T x  s.t.  G_l x + s_l = h_l, s_l >= 0;  G_k x + s_k = h_k, s_k in SOC_k;  A x = b,
independently of the C++ barrier method: the Jacobians are rebuilt here from the rest triangles with
A = U D (X D)^+ and the rotations R_j are recomputed here as the polar rotations of the Jacobians at the start X0.
Ghost faces (the paper's, closing each boundary vertex's one-ring) carry no energy: they must not flip, and their
largest singular value is bounded by GHOST_STRETCH times its value at X0, as in liftmap.

Usage: cvxopt_reference.py INSTANCE_DIR   (instances written by export_instances)
CVXOPT's interior-point method runs with the sparse KKT solver of cvxopt_sparse_kkt.py (UMFPACK), or with its
default dense one if the environment sets CVXOPT_KKT=dense. Either way CVXOPT's own residuals and gap certify the
reference solution, so a wrong KKT solve cannot produce a wrong reference, only a failure to converge.
Each instance: meshes[0..1] and ghosts with rest positions V, faces F, slot per vertex; p ("2"/"inf"),
h ("norm"/"max"), X0 (start, slot 0 held fixed: translation gauge), and the C++ minimiser X and objective, of the
barrier method and (key "primal_dual", if present) of the primal-dual method.
Checks, for each of the two C++ solvers: optimal objectives agree to 1e-6 relative; its X is feasible and its
objective (evaluated here) is optimal to 1e-6; minimisers agree to 1e-4 (p = 2; for p = inf the minimiser is not
unique, only reported). A primal-dual result that stopped at the limit of double precision before its certified gap
(p = 2: relative gaps of 1e-7..1e-6, see primal_dual_solver.h) is held to 1e-3 on the minimiser.
"""

import glob
import json
import math
import os
import sys
import time

import numpy as np
from cvxopt import matrix, solvers, sparse, spmatrix

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cvxopt_sparse_kkt import sparse_kkt_solver  # noqa: E402


# Bound of a ghost face's largest singular value, relative to its value at the start X0.
GHOST_STRETCH = 10.0


def face_jacobian_maps(V, F):
    """Per face, the 2x3 matrix M with A = U M for U the 2x3 flattened corners (A = U D (X D)^+)."""
    D = np.eye(3) - np.ones((3, 3)) / 3.0
    maps = []
    areas = []
    for f in F:
        P = V[f]  # 3x3 rows = corners
        e1, e2 = P[1] - P[0], P[2] - P[0]
        n = np.cross(e1, e2)
        areas.append(0.5 * np.linalg.norm(n))
        # Orthonormal frame of the plane, oriented by the normal (any such frame gives the same problem).
        q, _ = np.linalg.qr(np.column_stack([e1, e2]))
        bx, by = q[:, 0], q[:, 1]
        if np.dot(np.cross(bx, by), n) < 0:
            by = -by
        X = np.array([[np.dot(p - P[0], bx) for p in P], [np.dot(p - P[0], by) for p in P]])  # 2x3
        maps.append(D @ np.linalg.pinv(X @ D))
    return maps, np.array(areas)


def parts(A):
    """(alpha, beta, gamma, delta) of a 2x2 matrix, docs/algorithm.md (the convexified distortion)."""
    return ((A[0, 0] + A[1, 1]) / 2, (A[1, 0] - A[0, 1]) / 2, (A[0, 0] - A[1, 1]) / 2, (A[0, 1] + A[1, 0]) / 2)


class Instance:
    def __init__(self, path):
        with open(path) as fh:
            d = json.load(fh)
        self.name = os.path.basename(path)
        self.p_inf = d["p"] == "inf"
        self.h_max = d["h"] == "max"
        self.n_slots = d["n_slots"]
        self.X0 = np.array(d["X0"])
        self.X_ours = np.array(d["X"])
        self.obj_ours = d["objective"]
        # (label, X, objective, minimiser tolerance) of every C++ solver in the instance.
        self.results = [("barrier", self.X_ours, self.obj_ours, 1e-4)]
        if "primal_dual" in d:
            pd = d["primal_dual"]
            self.results.append(("primal-dual", np.array(pd["X"]), pd["objective"], 1e-4 if pd["converged"] else 1e-3))
        # Ghost vertices carry no energy: their optimal positions are not unique, so minimisers are compared on
        # the slots of the two meshes only.
        self.mesh_slots = sorted(set(d["meshes"][0]["slot"]) | set(d["meshes"][1]["slot"]))
        # (maps, areas, slots per face corner, thetas, is_ghost, bounds: GHOST_STRETCH Sigma(X0) per face, used on
        # ghost faces only)
        self.sets = []
        for k, m in enumerate(d["meshes"] + [d["ghosts"]]):
            if len(m["F"]) == 0:
                continue
            V = np.array(m["V"], dtype=float)
            F = np.array(m["F"], dtype=int)
            slot = np.array(m["slot"], dtype=int)
            maps, areas = face_jacobian_maps(V, F)
            corners = slot[F]
            thetas, bounds = [], []
            for M, c in zip(maps, corners):
                a, b, g, dl = parts(self.X0[c].T @ M)
                thetas.append(math.atan2(b, a))
                bounds.append(GHOST_STRETCH * (math.hypot(a, b) + math.hypot(g, dl)))
            self.sets.append((maps, areas, corners, np.array(thetas), k == 2, np.array(bounds)))

    def objective(self, X):
        """(10a) at X with the auxiliaries eliminated; inf if infeasible (a flipped face, or a ghost face stretched
        beyond its bound)."""
        total = 0.0
        for maps, areas, corners, thetas, ghost, bounds in self.sets:
            vals = []
            for M, c, th, bound in zip(maps, corners, thetas, bounds):
                a, b, g, dl = parts(X[c].T @ M)
                st = a * math.cos(th) + b * math.sin(th) - math.hypot(g, dl)
                if st <= 0:
                    return math.inf
                S = math.hypot(a, b) + math.hypot(g, dl)
                if ghost:
                    if S >= bound:
                        return math.inf
                    continue
                vals.append(max(S, 1 / st) if self.h_max else math.hypot(S, 1 / st))
            if ghost:
                continue
            vals = np.array(vals)
            total += vals.max() if self.p_inf else math.sqrt(np.dot(areas, vals ** 2))
        return total

    def solve(self, tolerances=(1e-10, 1e-9, 1e-8, 1e-7), kkt="sparse"):
        """Builds and solves the SOCP, trying each tolerance in turn; returns (objective, X).
        kkt: "sparse" (cvxopt_sparse_kkt.py: UMFPACK on the KKT systems) or "dense" (CVXOPT's default for socp)."""
        nx = 2 * self.n_slots
        n = nx
        rows_l, rows_q = [], []  # linear rows: (coeffs dict, rhs); cones: list of rows

        def new_var():
            nonlocal n
            n += 1
            return n - 1

        def jac_rows(M, c):
            """alpha, beta, gamma, delta as dicts over the position variables."""
            a11, a12, a21, a22 = {}, {}, {}, {}
            for k in range(3):
                ux, uy = 2 * c[k], 2 * c[k] + 1
                a11[ux] = a11.get(ux, 0) + M[k, 0]
                a12[ux] = a12.get(ux, 0) + M[k, 1]
                a21[uy] = a21.get(uy, 0) + M[k, 0]
                a22[uy] = a22.get(uy, 0) + M[k, 1]

            def comb(x, y, sy):
                out = dict((i, v / 2) for i, v in x.items())
                for i, v in y.items():
                    out[i] = out.get(i, 0) + sy * v / 2
                return out

            return comb(a11, a22, 1), comb(a21, a12, -1), comb(a11, a22, -1), comb(a12, a21, 1)

        taus = []
        tau_cones = []
        for maps, areas, corners, thetas, ghost, bounds in self.sets:
            E = []
            for M, c, th, bound in zip(maps, corners, thetas, bounds):
                al, be, ga, de = jac_rows(M, c)
                ell = dict((i, math.cos(th) * v) for i, v in al.items())
                for i, v in be.items():
                    ell[i] = ell.get(i, 0) + math.sin(th) * v
                if ghost:
                    # ||(gamma, delta)|| <= alpha cos + beta sin
                    rows_q.append([ell, ga, de])
                    # Sigma = ||(alpha, beta)|| + ||(gamma, delta)|| <= GHOST_STRETCH Sigma(X0): liftmap keeps the
                    # ghost vertices, which no energy holds, in a bounded region (barrier_solver.h, kGhostStretch).
                    gB, gC = new_var(), new_var()
                    rows_q.append([{gB: 1}, al, be])
                    rows_q.append([{gC: 1}, ga, de])
                    rows_l.append(({gB: 1, gC: 1}, float(bound)))
                    continue
                r, s, u, sB, sC = (new_var() for _ in range(5))
                rows_l.append(({sB: 1, sC: 1, r: -1}, 0.0))  # (5a) sB + sC <= r
                rows_q.append([{sB: 1}, al, be])  # (5b) |(alpha,beta)| <= sB
                rows_q.append([{sC: 1}, ga, de])  # (5c) |(gamma,delta)| <= sC
                rows_q.append([{u: 1, s: 1}, {u: 1, s: -1}, {"const": 2.0}])  # (7a)
                e7b = dict(ell)
                e7b[u] = e7b.get(u, 0) - 1
                rows_q.append([e7b, ga, de])  # (7b)
                rows_l.append(({u: -1}, 0.0))  # (7c) u >= 0
                e = new_var()
                if self.h_max:
                    rows_l.append(({r: 1, e: -1}, 0.0))
                    rows_l.append(({s: 1, e: -1}, 0.0))
                else:
                    rows_q.append([{e: 1}, {r: 1}, {s: 1}])
                E.append(e)
            if ghost:
                continue
            tau = new_var()
            taus.append(tau)
            if self.p_inf:
                for e in E:
                    rows_l.append(({e: 1, tau: -1}, 0.0))
            else:
                tau_cones.append([{tau: 1}] + [{e: math.sqrt(w)} for e, w in zip(E, areas)])
        rows_q.extend(tau_cones)

        cvec = matrix(0.0, (n, 1))
        for t in taus:
            cvec[t] = 1.0

        def lin_matrix(rows):
            I, J, V, h = [], [], [], []
            for i, (coeffs, rhs) in enumerate(rows):
                for j, v in coeffs.items():
                    I.append(i)
                    J.append(int(j))
                    V.append(float(v))
                h.append(rhs)
            return spmatrix(V, I, J, (len(rows), n)), matrix(h)

        Gl, hl = lin_matrix(rows_l)
        Gq, hq = [], []
        for cone in rows_q:
            # s = h - G x must lie in the cone, and s_i = row_i(x): G = -coeffs, h = constants.
            I, J, V, h = [], [], [], []
            for i, row in enumerate(cone):
                h.append(row.get("const", 0.0))
                for j, v in row.items():
                    if j == "const":
                        continue
                    I.append(i)
                    J.append(int(j))
                    V.append(-float(v))
            Gq.append(spmatrix(V, I, J, (len(cone), n)))
            hq.append(matrix(h))
        # Translation gauge: slot 0 fixed at its start position.
        A = spmatrix([1.0, 1.0], [0, 1], [0, 1], (2, n))
        b = matrix([float(self.X0[0, 0]), float(self.X0[0, 1])])
        # The same problem as one cone LP (socp's own stacking: linear rows first, then the cones in order).
        G = sparse([Gl] + Gq)
        h = matrix([hl] + hq)
        dims = {"l": Gl.size[0], "q": [g.size[0] for g in Gq], "s": []}
        # CVXOPT's Nesterov-Todd scaling update can take the square root of a slightly negative number in its
        # last iterations when the tolerances are tighter than it can reach ("domain error"): retry looser.
        # Where it fails depends on the BLAS kernel's rounding: under OpenBLAS's Nehalem kernel it failed on
        # man_elephant_pinf_max at 1e-10, 1e-9 and 1e-8. 1e-7 is still an order below what the comparison needs
        # (1e-6 objectives, 1e-4 minimisers).
        for tol in tolerances:
            solvers.options.update({"show_progress": bool(os.environ.get("CVXOPT_PROGRESS")), "abstol": tol,
                                    "reltol": tol, "feastol": tol, "maxiters": 200})
            try:
                if kkt == "sparse":
                    sol = solvers.conelp(cvec, G, h, dims, A, b, kktsolver=sparse_kkt_solver(G, dims, A))
                else:
                    sol = solvers.socp(cvec, Gl=Gl, hl=hl, Gq=Gq, hq=hq, A=A, b=b)
            except (ValueError, ArithmeticError) as e:
                print("%s: cvxopt failed at tolerance %g (%s), retrying" % (self.name, tol, e), flush=True)
                continue
            if sol["status"] == "optimal":
                break
            # Tolerances this tight can stall in the last digits; accept a near-optimal certificate.
            if sol["x"] is not None and sol["relative gap"] is not None and sol["relative gap"] <= 1e-8:
                break
        else:
            raise RuntimeError("%s: cvxopt found no optimal solution at any tolerance" % self.name)
        x = np.array(sol["x"]).ravel()
        return float(sol["primal objective"]), x[:nx].reshape(-1, 2)


def main():
    files = sorted(glob.glob(os.path.join(sys.argv[1], "*.json")))
    if not files:
        print("no instances in", sys.argv[1])
        return 1
    failures = 0
    for path in files:
        inst = Instance(path)
        t0 = time.perf_counter()
        obj_ref, X_ref = inst.solve(kkt=os.environ.get("CVXOPT_KKT", "sparse"))
        seconds = time.perf_counter() - t0
        for label, X_ours, obj_ours, x_tol in inst.results:
            obj_at_ours = inst.objective(X_ours)
            rel = abs(obj_ours - obj_ref) / abs(obj_ref)
            rel_eval = abs(obj_at_ours - obj_ref) / abs(obj_ref)
            dx = np.abs(X_ours[inst.mesh_slots] - X_ref[inst.mesh_slots]).max()
            ok = rel <= 1e-6 and rel_eval <= 1e-6 and (inst.p_inf or dx <= x_tol)
            failures += not ok
            print("%-28s %-11s cvxopt %.12g  ours %.12g  rel %.1e  (evaluated here: rel %.1e)  max|dX| %.1e%s  "
                  "cvxopt %.1f s  %s" % (inst.name, label, obj_ref, obj_ours, rel, rel_eval, dx,
                                         " (p=inf: not unique)" if inst.p_inf else "", seconds,
                                         "ok" if ok else "FAIL"), flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
