"""A sparse KKT solver for CVXOPT's cone LP solver: `solvers.conelp(..., kktsolver=sparse_kkt_solver(G, dims, A))`.

CVXOPT's built-in KKT solvers for problems with second-order cones ('qr', the default of `solvers.socp`, 'chol',
'ldl') work on dense copies of G: their time grows like n^2.7 on our subproblems, and a 2k-face instance would need
dense n x n matrices of ~10 GB. This module solves the same systems with UMFPACK, CVXOPT's own sparse LU
(`cvxopt.umfpack`), through the `kktsolver` argument that CVXOPT documents for exploiting problem structure. CVXOPT's
interior-point method (scalings, steps, stopping rules) is unchanged; only the linear algebra of its iterations is.

CVXOPT asks for the solution of
    [ 0  A^T  G^T   ] [ux]   [bx]
    [ A  0    0     ] [uy] = [by]
    [ G  0   -W^T W ] [uz]   [bz]
with z returned as W uz, for its Nesterov-Todd scaling W (symmetric). With wz = W uz the system is equivalent to
    [ 0        A^T  G^T W^-1 ] [ux]   [bx      ]
    [ A        0    0        ] [uy] = [by      ]
    [ W^-1 G   0    -I       ] [wz]   [W^-1 bz ]
(CVXOPT's 'ldl' solves this form densely). Its condition number is that of W^-1 G; the normal equations
(W^-1 G)^T (W^-1 G), as in CVXOPT's 'chol2', square it and were tried first: on the p = inf instances their Cholesky
factorisation failed near the optimum and the dual residual stalled at 3e-7.

W^-1 is diag(di) on the linear rows and (1 / beta) (2 u u^T - J), u = J v, on a second-order cone. On a large cone
(the p = 2 objective cones, one entry per face) the rank-one part (2 / beta) u u^T would make W^-1 G dense, so
W^-1 G = M + sum_k a_k g_k^T with M sparse, a_k = u_k on cone k's rows and g_k^T = (2 / beta_k) u_k^T G_k. The
matrix is then K0 + sum_k (a_k g_k^T + g_k a_k^T) (a_k in the wz rows, g_k in the ux rows), K0 the sparse system
with M: UMFPACK factorises K0 and the Sherman-Morrison-Woodbury formula adds the rank-2 terms. (Extra unknowns
g_k^T ux and a_k^T wz in the LU instead put dense rows into it: 2.7 s per factorisation against 0.19 s for K0 on a
25k x 25k system.)
"""

import numpy as np
from cvxopt import matrix, spmatrix, umfpack

# Cones of more rows than this get the low-rank treatment.
LARGE_CONE = 16


def _triplets(S, row0=0, col0=0, transpose=False):
    I = np.array(S.I, dtype=np.int64).ravel()
    J = np.array(S.J, dtype=np.int64).ravel()
    if transpose:
        I, J = J, I
    return I + row0, J + col0, np.array(S.V).ravel()


def sparse_kkt_solver(G, dims, A):
    """kktsolver argument of cvxopt.solvers.conelp for G (spmatrix), dims ('l', 'q'; no 's') and A (spmatrix)."""
    if dims.get("s"):
        raise ValueError("sparse_kkt_solver: semidefinite cones are not supported")
    n = G.size[1]
    p = A.size[0]
    rows = G.size[0]
    ml = dims["l"]
    offsets = [ml]
    for q in dims["q"]:
        offsets.append(offsets[-1] + q)
    large = [k for k, q in enumerate(dims["q"]) if q > LARGE_CONE]
    small = {}
    for k, q in enumerate(dims["q"]):
        if q <= LARGE_CONE:
            small.setdefault(q, []).append(k)
    G_large = [G[offsets[k]:offsets[k + 1], :] for k in large]
    nb = len(large)
    size = n + p + rows
    o_z = n + p
    A_trip = _triplets(A, n, 0)
    At_trip = _triplets(A, 0, n, transpose=True)
    state = {"symbolic": None, "pattern": None}

    def factor(W):
        # Block-diagonal sparse part of W^-1, as triplets: the linear rows, then the small cones by dimension.
        I, J, V = [np.arange(ml)], [np.arange(ml)], [np.array(W["di"]).ravel()]
        for q, ks in small.items():
            u = np.concatenate([np.array(W["v"][k]).ravel() for k in ks]).reshape(len(ks), q)
            u[:, 1:] *= -1  # J v
            beta = np.array([W["beta"][k] for k in ks])
            B = 2 * np.einsum("ki,kj->kij", u, u)  # 2 u u^T - J
            B[:, 0, 0] -= 1
            B[:, np.arange(1, q), np.arange(1, q)] += 1
            B /= beta[:, None, None]
            o = np.array([offsets[k] for k in ks])[:, None, None]
            rr, cc = np.meshgrid(np.arange(q), np.arange(q), indexing="ij")
            I.append((o + rr[None]).ravel())
            J.append((o + cc[None]).ravel())
            V.append(B.ravel())
        u_large = []
        for k in large:
            q = dims["q"][k]
            beta = W["beta"][k]
            u = np.array(W["v"][k]).ravel().copy()
            u[1:] *= -1  # J v
            d = np.ones(q)
            d[0] = -1  # -J
            I.append(offsets[k] + np.arange(q))
            J.append(offsets[k] + np.arange(q))
            V.append(d / beta)
            u_large.append((u, beta, k))
        I, J, V = np.concatenate(I), np.concatenate(J), np.concatenate(V)
        Winv = spmatrix(V.tolist(), I.tolist(), J.tolist(), (rows, rows))
        M = Winv * G
        KI, KJ, KV = [], [], []

        def put(trip):
            KI.append(trip[0])
            KJ.append(trip[1])
            KV.append(trip[2])

        put(At_trip)
        put(A_trip)
        put(_triplets(M, 0, o_z, transpose=True))  # M^T in the ux rows
        put(_triplets(M, o_z, 0))  # M in the wz rows
        put((o_z + np.arange(rows), o_z + np.arange(rows), -np.ones(rows)))
        K = spmatrix(np.concatenate(KV).tolist(), np.concatenate(KI).tolist(), np.concatenate(KJ).tolist(),
                     (size, size))
        # UMFPACK's symbolic analysis is reused while the pattern is the same (it is, iteration after iteration).
        pattern = (np.array(K.CCS[0]), np.array(K.CCS[1]))
        if state["symbolic"] is None or not all(np.array_equal(a, b) for a, b in zip(pattern, state["pattern"])):
            state["symbolic"] = umfpack.symbolic(K)
            state["pattern"] = pattern
        Fn = umfpack.numeric(K, state["symbolic"])

        def k0_solve(r):
            sol = matrix(r)
            umfpack.solve(K, Fn, sol)
            return np.array(sol)

        # The large cones' rank-one parts: K0 + U V^T with U = [a_1 g_1 ...], V = [g_1 a_1 ...] (a_k in the wz
        # rows, g_k in the ux rows), solved by the Sherman-Morrison-Woodbury formula around K0's factors.
        U = np.zeros((size, 2 * nb))
        for i, ((u, beta, k), Gk) in enumerate(zip(u_large, G_large)):
            U[o_z + offsets[k]:o_z + offsets[k + 1], 2 * i] = u
            U[:n, 2 * i + 1] = np.array((2 / beta) * (Gk.T * matrix(u))).ravel()  # g_k
        Vt = U[:, [j ^ 1 for j in range(2 * nb)]].T
        if nb:
            Z = k0_solve(U)
            cap = np.eye(2 * nb) + Vt @ Z

        def winv_apply(w):
            out = np.array(Winv * matrix(w)).ravel()
            for u, beta, k in u_large:
                o, e = offsets[k], offsets[k + 1]
                out[o:e] += (2 / beta) * u * float(u @ w[o:e])
            return out

        def solve(x, y, z):
            rhs = np.zeros(size)
            rhs[:n] = np.array(x).ravel()
            rhs[n:n + p] = np.array(y).ravel()
            rhs[o_z:] = winv_apply(np.array(z).ravel())
            sol = k0_solve(rhs).ravel()
            if nb:
                sol -= Z @ np.linalg.solve(cap, Vt @ sol)
            x[:] = matrix(sol[:n])
            y[:] = matrix(sol[n:n + p])
            z[:] = matrix(sol[o_z:])

        return solve

    return factor
