"""One mechanism out of the optimal face: the dual of a solved limit problem at a vertex.

An interior-point solver returns the centre of the optimal face of the dual: when
several collapse mechanisms are optimal (a wall that can slide on any of its bed
joints at lambda = f), its duals are a blend of all of them, which cannot be drawn.
Given the solved problem (primal z*, slacks s*), a dual y is optimal exactly when it
is dual feasible and complementary to z*: it vanishes on rows that are slack at z*.
:func:`vertex_dual` solves, over that set, one more problem,

    min  sum of the multipliers of the joint rows     (the plastic multipliers)
    s.t. A^T y + c = 0,  b^T y <= b^T y_ip,  y = 0 on slack rows, y in K*,

restricted further to the blocks that move in the blend (the centre of the face moves
every block that moves in any optimal mechanism). For a linear program (2D, or 3D
with pyramids) HiGHS' dual simplex returns a vertex: one mechanism. With friction cones
the minimiser of the same objective is found by Clarabel: an extreme point of the face
where it is unique.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from ..solvers import OPTIMAL, ConicProblem, SolverResult, solve

#: a row is active when its slack is below this (scaled units) ...
ACTIVE_TOL = 1e-7
#: ... or its dual above this fraction of the largest (near-degenerate rows, where an
#: interior-point solution leaves both small, must stay in)
DUAL_TOL = 1e-9
#: slack of the LP's bound b^T y <= b^T y_ip (relative): the interior-point duals are
#: optimal to about the solver's tolerance
BOUND_TOL = 1e-7
#: a dual whose objective (the multiplier of its mechanism) exceeds the optimum by more
#: than this (relative) is refused; within it, the gap goes into the result's notes
OPTIMAL_GAP = 1e-4
#: a block moves in the blend when its velocity exceeds this fraction of the largest
MOVING_TOL = 1e-6


def vertex_dual(prob: ConicProblem, res: SolverResult, eq_rows: slice, dofs: int,
                time_limit: float = 60.0) -> tuple[np.ndarray, str] | None:
    """Duals at a vertex (LP) or extreme point (cones) of the optimal face, and which
    ("vertex" or "extreme"); None when the restricted problem cannot be solved or its
    solution's objective exceeds the interior-point dual's by more than OPTIMAL_GAP
    (relative), or when the simplex needs more than ``time_limit`` seconds. The
    objective b^T y of the duals is the multiplier at which their mechanism's work
    balances: compare it with lambda*.

    ``eq_rows`` are the equilibrium rows (``dofs`` per free block, in block order).
    """
    z, y = res.z, res.y
    if z is None or y is None:
        return None
    A = prob.A.tocsr()
    b = prob.b
    s = b - A @ z
    ne, nl = prob.n_eq, prob.n_nonneg
    n_rows = len(b)
    # blocks that move in the blend
    v = y[eq_rows].reshape(-1, dofs)
    mag = np.abs(v).max(axis=1)
    top = float(mag.max(initial=0.0))
    if not top > 0:
        return None
    moving = np.repeat(mag > MOVING_TOL * top, dofs)
    keep = np.zeros(n_rows, dtype=bool)
    keep[eq_rows.start:eq_rows.stop] = moving
    # active nonnegative rows
    lin = slice(ne, ne + nl)
    ymax = float(np.abs(y).max(initial=1.0))
    keep[lin] = (s[lin] <= ACTIVE_TOL) | (y[lin] >= DUAL_TOL * ymax)
    # active cones: slack on the cone's boundary
    cone_rows: list[np.ndarray] = []
    at = ne + nl
    for k in prob.soc:
        r = np.arange(at, at + k)
        sk = s[r]
        if sk[0] - np.linalg.norm(sk[1:]) <= ACTIVE_TOL * max(1.0, abs(sk[0])) or \
                y[r[0]] >= DUAL_TOL * ymax:
            keep[r] = True
            cone_rows.append(r)
        at += k
    # joint rows count where they reach a moving block's variables (a row between two
    # blocks at rest has no equation of a moving block to enter)
    moving_cols = np.zeros(A.shape[1], dtype=bool)
    moving_cols[np.unique(A[np.flatnonzero(keep[:ne]), :].indices)] = True
    idx = np.flatnonzero(keep)
    rest = sp.csr_matrix(A[idx][:, ~moving_cols])
    idx = idx[(idx < ne) | (np.diff(rest.indptr) == 0)]
    cols = np.unique(A[idx, :].indices)
    At = A[idx][:, cols].T.tocsc()  # one equation per variable column
    rhs = -np.asarray(prob.c, float)[cols]
    bound = float(b @ y)
    n_eq_k = int(np.sum(idx < ne))
    n_lin_k = int(np.sum((idx >= ne) & (idx < ne + nl)))
    w = np.concatenate([np.zeros(n_eq_k), np.ones(len(idx) - n_eq_k)])
    if not prob.soc:
        from scipy.optimize import linprog

        bounds = [(None, None)] * n_eq_k + [(0, None)] * (len(idx) - n_eq_k)
        lp = dict(A_ub=b[idx][None, :], b_ub=[bound + BOUND_TOL * max(1.0, abs(bound))],
                  A_eq=At, b_eq=rhs, bounds=bounds, options={"time_limit": time_limit})
        # where the active set taken at the interior point's tolerances leaves the
        # restricted problem without a solution (large walls), HiGHS' interior-point
        # method says so in a fraction of the simplex's time (1,009-block wall: 0.08 s
        # against 0.7 s, when the simplex does not end in a solve error)
        if linprog(w, method="highs-ipm", **lp).status == 2:
            return None
        out = linprog(w, method="highs-ds", **lp)
        if out.status != 0:
            return None
        yv = np.zeros(n_rows)
        yv[idx] = out.x
        return yv, "vertex"
    # cones: Clarabel on the restricted dual (variables y_idx)
    k_idx = {int(r): j for j, r in enumerate(idx)}
    cones = [[k_idx[int(r)] for r in cr] for cr in cone_rows if int(cr[0]) in k_idx
             and all(int(r) in k_idx for r in cr)]
    n = len(idx)
    w = np.zeros(n)
    w[n_eq_k:n_eq_k + n_lin_k] = 1.0
    for c in cones:
        w[c[0]] = 1.0
    eye = sp.identity(n, format="csr")
    lin_sel = np.arange(n_eq_k, n_eq_k + n_lin_k)
    # no bound on b^T y here: it leaves the cones' feasible set without an interior,
    # out of the interior-point solver's reach; optimality is checked afterwards
    blocks = [At, -eye[lin_sel]]
    rhs_all = [rhs, np.zeros(n_lin_k)]
    for c in cones:
        blocks.append(-eye[c])
        rhs_all.append(np.zeros(len(c)))
    dual = ConicProblem(c=w, A=sp.vstack(blocks, format="csc"), b=np.concatenate(rhs_all),
                        n_eq=At.shape[0], n_nonneg=n_lin_k,
                        soc=tuple(len(c) for c in cones))
    r = solve(dual, "clarabel")
    if r.status != OPTIMAL:
        return None
    yv = np.zeros(n_rows)
    yv[idx] = r.z
    if float(b @ yv) > bound + OPTIMAL_GAP * max(1.0, abs(bound)):
        return None  # not near the optimal face
    return yv, "extreme"
