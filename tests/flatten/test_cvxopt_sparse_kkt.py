#!/usr/bin/python3
"""Checks cvxopt_sparse_kkt.py against a dense solve of the same KKT system.

A random cone LP structure like ours (linear rows, 3-dimensional cones, and two cones larger than LARGE_CONE, which
take the low-rank path), a random Nesterov-Todd scaling W from CVXOPT's own misc.compute_scaling at random interior
points, and random right-hand sides. The sparse solver's (ux, uy, W uz) must satisfy the KKT equations
    A^T uy + G^T uz = bx,   A ux = by,   G ux - W^T W uz = bz
to 1e-9 relative, and match numpy's dense solve.
"""

import os
import sys

import numpy as np
from cvxopt import matrix, misc, spmatrix

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cvxopt_sparse_kkt import LARGE_CONE, sparse_kkt_solver  # noqa: E402


def random_cone_point(rng, dims):
    """A point strictly inside the product cone."""
    parts = [rng.uniform(0.1, 2.0, dims["l"])]
    for q in dims["q"]:
        tail = rng.normal(size=q - 1)
        parts.append(np.concatenate([[np.linalg.norm(tail) + rng.uniform(0.05, 1.0)], tail]))
    return np.concatenate(parts)


def dense_w(W, dims):
    """W as a dense matrix (block diagonal: diag(d), then beta (2 v v^T - J) per second-order cone)."""
    blocks = [np.diag(np.array(W["d"]).ravel())]
    for v, beta in zip(W["v"], W["beta"]):
        v = np.array(v).ravel()
        J = -np.eye(len(v))
        J[0, 0] = 1
        blocks.append(beta * (2 * np.outer(v, v) - J))
    rows = sum(b.shape[0] for b in blocks)
    out = np.zeros((rows, rows))
    o = 0
    for b in blocks:
        out[o:o + b.shape[0], o:o + b.shape[0]] = b
        o += b.shape[0]
    return out


def main():
    rng = np.random.default_rng(7)
    failures = 0
    for trial in range(4):
        n = 60
        dims = {"l": 25, "q": [3] * 30 + [LARGE_CONE + 20, LARGE_CONE + 9], "s": []}
        rows = dims["l"] + sum(dims["q"])
        # Sparse G with full column rank: an identity block plus random sparse entries.
        Gd = np.zeros((rows, n))
        Gd[np.arange(n), np.arange(n)] = 1.0
        mask = rng.random((rows, n)) < 0.05
        Gd[mask] += rng.normal(size=mask.sum())
        G = spmatrix(Gd[Gd != 0].tolist(), *[x.tolist() for x in np.nonzero(Gd)], (rows, n))
        fixed = [0, 1]
        A = spmatrix([1.0, 1.0], [0, 1], fixed, (2, n))
        s = matrix(random_cone_point(rng, dims))
        z = matrix(random_cone_point(rng, dims))
        lmbda = matrix(0.0, (rows, 1))
        W = misc.compute_scaling(s, z, lmbda, dims)
        solve = sparse_kkt_solver(G, dims, A)(W)
        bx, by, bz = rng.normal(size=n), rng.normal(size=2), rng.normal(size=rows)
        x, y, zz = matrix(bx), matrix(by), matrix(bz)
        solve(x, y, zz)
        ux, uy, wuz = np.array(x).ravel(), np.array(y).ravel(), np.array(zz).ravel()
        Wd = dense_w(W, dims)
        uz = np.linalg.solve(Wd, wuz)
        Ad = np.array(matrix(A))
        res = np.concatenate([Ad.T @ uy + Gd.T @ uz - bx, Ad @ ux - by, Gd @ ux - Wd.T @ Wd @ uz - bz])
        scale = max(np.abs(bx).max(), np.abs(bz).max(), 1.0)
        # The dense reference solve of the same system.
        K = np.zeros((n + 2 + rows, n + 2 + rows))
        K[:n, n:n + 2] = Ad.T
        K[:n, n + 2:] = Gd.T
        K[n:n + 2, :n] = Ad
        K[n + 2:, :n] = Gd
        K[n + 2:, n + 2:] = -Wd.T @ Wd
        ref = np.linalg.solve(K, np.concatenate([bx, by, bz]))
        diff = max(np.abs(ux - ref[:n]).max(), np.abs(uz - ref[n + 2:]).max()) / max(np.abs(ref).max(), 1.0)
        ok = np.abs(res).max() <= 1e-9 * scale and diff <= 1e-8
        failures += not ok
        print("trial %d: KKT residual %.1e, difference to the dense solve %.1e  %s"
              % (trial, np.abs(res).max() / scale, diff, "ok" if ok else "FAIL"))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
