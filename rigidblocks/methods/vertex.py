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
complementarity leaves each active cone's dual one direction where its slack is on the
cone's boundary (the contact point at its friction limit) and the cone itself where the
slack is at the apex (the point carries nothing), which an inscribed pyramid of
APEX_EDGES edges approximates: the problem becomes an LP, and the simplex again
returns a vertex (:func:`_cone_lp`; the 28-block 3D wall and the box stack). Where that
LP has no solution, Clarabel minimises over the cones themselves: an extreme point of
the face where the minimiser is unique (:func:`_cone_extreme`; the 62-block corbel
dome).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..solvers import OPTIMAL, ConicProblem, SolverResult, solve

if TYPE_CHECKING:  # scipy.sparse is imported where a vertex is sought, not with the module
    import scipy.sparse as sp

#: a row is active when its slack is below this (scaled units) ...
ACTIVE_TOL = 1e-7
#: ... or its dual above this fraction of the largest (near-degenerate rows, where an
#: interior-point solution leaves both small, must stay in)
DUAL_TOL = 1e-9
#: slack of the LP's bound b^T y <= b^T y_ip (relative): the interior-point duals are
#: optimal to about the solver's tolerance
BOUND_TOL = 1e-7


def face_allowance(bound: float) -> float:
    """How far (absolute) above the optimum ``bound`` = b^T y_ip the objective of a dual
    returned as on the optimal face may lie: the restricted problems' bound slack
    (BOUND_TOL, relative, on at least 1). A mechanism that balances further above it is
    not on the face (the 3D wall at f = 0.05 draws its bed-joint slide at 0.0500001,
    within this allowance of lambda* = 0.05)."""
    return BOUND_TOL * max(1.0, abs(bound))


#: a dual whose objective (the multiplier of its mechanism) exceeds the optimum by more
#: than this (relative) is refused; within it, the gap goes into the result's notes
OPTIMAL_GAP = 1e-4
#: a block moves in the blend when its velocity exceeds this fraction of the largest
MOVING_TOL = 1e-6
#: a cone's slack whose size is below this fraction of the largest slack is at the
#: cone's apex (the contact point carries nothing)
APEX_TOL = 1e-7
#: edges of a cone at its apex in the linear restricted dual (an inscribed pyramid)
APEX_EDGES = 16
#: weight of the multipliers' sum after b^T y in the second objective (relative)
LEX_WEIGHT = 1e-3
#: the search is bounded by work, not by time, so that its answer does not depend on
#: the machine's load: HiGHS' iterations (simplex, and interior point where it checks
#: feasibility) per linear program. Measured (CPU): the 62-block corbel dome's cone LP
#: ends without a solution after 1,804 dual simplex iterations (0.15 s; the cone
#: problems answer), the 127-block 3D wall's after 20 (0.02 s), the 1,009-block 3D
#: wall's (32 courses x 31) after 62 (0.15 s, 2.4 ms an iteration), the 2D arch's in
#: presolve; the 1,009-block 2D wall's interior-point check after 2
LP_ITERATIONS = 5_000
#: ... and Clarabel's iterations per cone problem: the corbel dome's two take 9 and 19
CONE_ITERATIONS = 100


def vertex_dual(prob: ConicProblem, res: SolverResult, eq_rows: slice, dofs: int,
                ) -> tuple[np.ndarray, str] | None:
    """Duals at a vertex (LP) or extreme point (cones) of the optimal face, and which
    ("vertex" or "extreme"); None when the restricted problem cannot be solved or its
    solution's objective exceeds the interior-point dual's by more than OPTIMAL_GAP
    (relative), or when a solve reaches its budget (LP_ITERATIONS, CONE_ITERATIONS:
    work, never time, so the answer is the same on a loaded machine). The
    objective b^T y of the duals is the multiplier at which their mechanism's work
    balances: compare it with lambda*.

    ``eq_rows`` are the equilibrium rows (``dofs`` per free block, in block order).
    """
    import scipy.sparse as sp

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
    if not prob.soc:
        yv = _linear_vertex(prob, idx, n_eq_k, At, rhs, bound)
        return None if yv is None else (yv, "vertex")
    lp = _cone_lp(prob, idx, n_eq_k, n_lin_k, cone_rows, At, rhs, s, bound)
    if lp is not None:
        return lp, "vertex"
    return _cone_extreme(prob, idx, n_eq_k, n_lin_k, cone_rows, At, rhs, bound, y)


def _linear_vertex(prob: ConicProblem, idx: np.ndarray, n_eq_k: int, At: sp.csc_matrix,
                   rhs: np.ndarray, bound: float) -> np.ndarray | None:
    """The restricted dual of a linear program by HiGHS' dual simplex: a vertex."""
    from scipy.optimize import linprog

    w = np.concatenate([np.zeros(n_eq_k), np.ones(len(idx) - n_eq_k)])
    bounds = [(None, None)] * n_eq_k + [(0, None)] * (len(idx) - n_eq_k)
    lp = dict(A_ub=prob.b[idx][None, :], b_ub=[bound + face_allowance(bound)],
              A_eq=At, b_eq=rhs, bounds=bounds, options={"maxiter": LP_ITERATIONS})
    # where the active set taken at the interior point's tolerances leaves the
    # restricted problem without a solution (large walls), HiGHS' interior-point
    # method says so in a fraction of the simplex's time (1,009-block wall: 0.08 s
    # against 0.7 s, when the simplex does not end in a solve error)
    if linprog(w, method="highs-ipm", **lp).status == 2:
        return None
    out = linprog(w, method="highs-ds", **lp)
    if out.status != 0:
        return None
    yv = np.zeros(len(prob.b))
    yv[idx] = out.x
    return yv


def _cone_directions(s: np.ndarray, rows: np.ndarray, scale: float) -> np.ndarray:
    """The directions a cone's dual may take, complementary to its slack ``s[rows]``:
    one, d = (s0, -s1, -s2) / |s|, where the slack is on the boundary away from the
    apex (the point carries force at the friction limit); where it is at the apex (the
    point carries nothing) the cone's edges at APEX_EDGES angles, whose non-negative
    combinations approximate the cone from inside (a dual among them is feasible)."""
    sk = s[rows]
    size = float(np.linalg.norm(sk))
    if size > APEX_TOL * scale:
        return (np.concatenate([[sk[0]], -sk[1:]]) / size)[None, :]
    if len(rows) == 2:
        return np.array([[1.0, 1.0], [1.0, -1.0]])
    th = 2 * np.pi * np.arange(APEX_EDGES) / APEX_EDGES
    return np.column_stack([np.ones(APEX_EDGES), np.cos(th), np.sin(th)])


def _cone_lp(prob: ConicProblem, idx: np.ndarray, n_eq_k: int, n_lin_k: int,
             cone_rows: list[np.ndarray], At: sp.csc_matrix, rhs: np.ndarray,
             s: np.ndarray, bound: float) -> np.ndarray | None:
    """The restricted dual as a linear program: each active cone's dual is a
    non-negative combination of the directions :func:`_cone_directions` allows
    (complementarity y . s = 0 leaves one where the slack is on the cone's boundary),
    so the simplex returns a vertex, one mechanism, with b^T y within BOUND_TOL of
    lambda*. None where that LP has no solution (the directions are read from the
    interior-point slacks to the solver's accuracy, and the apex cones' edges only
    approximate them)."""
    import scipy.sparse as sp
    from scipy.optimize import linprog

    pos = {int(r): j for j, r in enumerate(idx)}
    scale = max(1.0, float(np.abs(s).max(initial=0.0)))
    lin = np.arange(n_eq_k + n_lin_k)
    gens, g_cols, g_obj, g_b = [], [], [], []
    for rows in cone_rows:
        if not all(int(r) in pos for r in rows):
            continue
        dirs = _cone_directions(s, rows, scale)
        cols = [pos[int(r)] for r in rows]
        gens.append((rows, dirs))
        g_cols.append(At[:, cols] @ dirs.T)
        g_obj.append(dirs[:, 0])
        g_b.append(dirs @ prob.b[rows])
    parts = [At[:, lin]] + [sp.csc_matrix(g) for g in g_cols]
    A_eq = sp.hstack(parts, format="csc")
    n_g = A_eq.shape[1] - len(lin)
    w = np.concatenate([np.zeros(n_eq_k), np.ones(n_lin_k), *g_obj])
    b_row = np.concatenate([prob.b[idx[lin]], *g_b])
    bounds = [(None, None)] * n_eq_k + [(0, None)] * (n_lin_k + n_g)
    out = linprog(w, A_ub=b_row[None, :], b_ub=[bound + face_allowance(bound)],
                  A_eq=A_eq, b_eq=rhs, bounds=bounds, method="highs-ds",
                  options={"maxiter": LP_ITERATIONS})
    if out.status != 0:
        return None
    y = np.zeros(len(prob.b))
    y[idx[lin]] = out.x[:len(lin)]
    at = len(lin)
    for rows, dirs in gens:
        y[rows] = out.x[at:at + len(dirs)] @ dirs
        at += len(dirs)
    return y


def _cone_extreme(prob: ConicProblem, idx: np.ndarray, n_eq_k: int, n_lin_k: int,
                  cone_rows: list[np.ndarray], At: sp.csc_matrix, rhs: np.ndarray,
                  bound: float, y_ip: np.ndarray) -> tuple[np.ndarray, str] | None:
    """The restricted dual with its cones, solved by Clarabel: an extreme point of the
    face where the minimiser is unique. First the sum of the multipliers alone; where
    its minimiser lies off the optimal face (its multiplier b^T y more than
    OPTIMAL_GAP above lambda*: a simpler mechanism that needs a larger load, the ring
    of a corbel dome sliding at lambda = f), b^T y first and the multipliers after
    (their sum weighted LEX_WEIGHT of the interior-point dual's)."""
    import scipy.sparse as sp

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
    A = sp.vstack(blocks, format="csc")
    lex = prob.b[idx] / max(abs(bound), 1e-300) + \
        LEX_WEIGHT * w / (float(w @ np.abs(y_ip[idx])) or 1.0)
    for objective in (w, lex):
        dual = ConicProblem(c=objective, A=A, b=np.concatenate(rhs_all),
                            n_eq=At.shape[0], n_nonneg=n_lin_k,
                            soc=tuple(len(c) for c in cones))
        r = solve(dual, "clarabel", max_iter=CONE_ITERATIONS)
        if r.status != OPTIMAL:
            continue
        yv = np.zeros(len(prob.b))
        yv[idx] = r.z
        if float(prob.b @ yv) <= bound + OPTIMAL_GAP * max(1.0, abs(bound)):
            return yv, "extreme"
    return None  # not near the optimal face
