"""The solver interface: a conic problem in, a canonical status and solution out.

Problems are posed in one standard form (Clarabel's)::

    minimise    1/2 z'Pz + c'z
    subject to  A z + s = b,   s in K = {0}^n_eq x R+^n_nonneg x SOC(k_1) x ... x SOC(k_r)

Every back end maps its own statuses onto four canonical ones: ``optimal``,
``infeasible`` (no z satisfies the constraints: for us, no admissible equilibrium; a
result, not an error), ``unbounded`` and ``failure`` (iteration limit, numerical
trouble, "almost" answers). A failure carries the solver's own status words and is
raised as :class:`~rigidblocks.errors.SolverFailure` by the analyses, never passed on
as a number.

Duals ``y`` follow the sign convention of the KKT condition ``P z + c + A' y = 0``
(y >= 0 on the nonnegative rows), whatever the back end.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..sparse import as_csc

OPTIMAL = "optimal"
INFEASIBLE = "infeasible"
UNBOUNDED = "unbounded"
FAILURE = "failure"


@dataclass(frozen=True, eq=False)
class ConicProblem:
    """A problem in standard conic form (see the module docstring).

    ``cols`` and ``rows`` name blocks of variables and of constraint rows, so that
    callers read solutions and duals by name, not by stride arithmetic.
    """

    c: np.ndarray
    #: a :class:`~rigidblocks.sparse.CscMatrix`, or any of scipy's sparse matrices
    A: Any
    b: np.ndarray
    n_eq: int
    n_nonneg: int
    soc: tuple[int, ...] = ()
    P: Any = None
    cols: dict[str, slice] = field(default_factory=dict)
    rows: dict[str, slice] = field(default_factory=dict)
    #: parametric entries of A by name: (positions in ``A.data``, coefficients), so that
    #: ``with_parameter(name, p)`` sets those entries to ``coefficients * p``
    params: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)

    @property
    def n(self) -> int:
        return len(self.c)

    def with_parameter(self, name: str, value: float) -> ConicProblem:
        """The same problem with the entries of parameter ``name`` set for ``value``
        (a copy of ``A.data``; the sparsity pattern is shared)."""
        pos, coef = self.params[name]
        A = as_csc(self.A)
        data = A.data.copy()
        data[pos] = coef * value
        return replace(self, A=A.with_data(data))

    @property
    def is_lp(self) -> bool:
        return not self.soc and (self.P is None or self.P.nnz == 0)


@dataclass(frozen=True, eq=False)
class SolverResult:
    """What a back end returns: canonical status, primal z, duals y and diagnostics."""

    status: str
    z: np.ndarray | None
    y: np.ndarray | None
    objective: float
    solver: str
    raw_status: str
    iterations: int = 0
    solve_time: float = 0.0
    #: the answer's residuals against the problem itself (:func:`residuals`), and
    #: whether they passed the check of the solver policy (None: not checked)
    residuals: dict = field(default_factory=dict)
    verified: bool | None = None
    #: the solve stopped short of its own tolerances with an answer that meets those of
    #: the next solve it was given (stalled: an optimal answer), or failed with a last
    #: iterate that does, then carried in ``z`` and ``y`` (see
    #: :mod:`~rigidblocks.solvers.clarabel_backend`)
    next_met: bool = False

    @property
    def ok(self) -> bool:
        return self.status == OPTIMAL


def _cone_breach(problem: ConicProblem, s: np.ndarray) -> float:
    """How far ``s`` (slacks of the inequality rows: nonnegative rows, then cones) is
    outside the cone: the largest negative entry, or norm of the tail above the head."""
    ne, nl = problem.n_eq, problem.n_nonneg
    out = float(np.maximum(-s[ne:ne + nl], 0.0).max(initial=0.0))
    if problem.soc:
        ks = set(problem.soc)
        pos = ne + nl
        if ks == {3}:
            q = s[pos:pos + 3 * len(problem.soc)].reshape(-1, 3)
            out = max(out, float(np.maximum(np.hypot(q[:, 1], q[:, 2]) - q[:, 0],
                                            0.0).max(initial=0.0)))
        else:
            for k in problem.soc:
                q = s[pos:pos + k]
                out = max(out, float(np.linalg.norm(q[1:]) - q[0]))
                pos += k
    return out


def normalised(problem: ConicProblem, res: SolverResult) -> SolverResult | None:
    """The optimal answer of a problem whose objective is one variable (min r, max
    lambda; no quadratic term) with its duals scaled so that the dual residual of that
    variable is exact; None where the problem or answer is not of that kind.

    The dual of such a problem carries one normalisation (the multipliers of the rows
    that hold the variable sum to its cost). An interior-point solver can miss it by
    far more than the rest of its dual residual: Clarabel at 1e-8 on the relaxation of
    the 1,000-block wall near f*, 5.4e-6 on the relaxation variable against 6.6e-8 on
    any force (extruded: 1.0e-5 against 2.6e-8). Scaling the duals by a positive factor
    keeps them in the dual cone (nonnegative orthant or second-order cones) and scales
    every other residual and the dual objective by the same factor.
    """
    if (res.status != OPTIMAL or res.z is None or res.y is None
            or (problem.P is not None and problem.P.nnz)):
        return None
    k = np.flatnonzero(problem.c)
    if len(k) != 1:
        return None
    k = int(k[0])
    A = problem.A if problem.A.format == "csc" else problem.A.tocsc()
    lo, hi = A.indptr[k], A.indptr[k + 1]
    held = float(A.data[lo:hi] @ res.y[A.indices[lo:hi]])
    scale = -float(problem.c[k]) / held if held else 0.0
    if not (math.isfinite(scale) and scale > 0):
        return None
    return replace(res, y=res.y * scale)


def certificate_problem(problem: ConicProblem, status: str) -> ConicProblem | None:
    """The problem whose solution is the certificate of an infeasible (``status``
    infeasible) or unbounded problem, for a back end that returns the status without
    one, in the same standard form (the back end solves it as any other; its matrix is
    scipy's):

    * infeasible: min b'y s.t. A'y = 0, y in the dual cone K* (= K: zero rows free,
      nonnegative rows, second-order cones), |y| <= 1;
    * unbounded (no quadratic term): min c'd s.t. A d + s = 0 with s in K, |d| <= 1.

    A negative optimum is the certificate (y, or the ray d as ``z``); None for an
    unbounded problem with a quadratic term."""
    import scipy.sparse as sp

    A = problem.A.tocsr()
    m, n = A.shape
    ne, nl = problem.n_eq, problem.n_nonneg
    eye_m, eye_n = sp.identity(m, format="csr"), sp.identity(n, format="csr")
    if status == INFEASIBLE:
        # rows: A'y = 0; y >= 0 on the nonnegative rows; box; y in the cones
        rows = [A.T.tocsr(), -eye_m[ne:ne + nl], eye_m, -eye_m, -eye_m[ne + nl:]]
        rhs = [np.zeros(n), np.zeros(nl), np.ones(m), np.ones(m), np.zeros(m - ne - nl)]
        return ConicProblem(c=problem.b.astype(float), A=sp.vstack(rows).tocsc(),
                            b=np.concatenate(rhs), n_eq=n, n_nonneg=nl + 2 * m,
                            soc=problem.soc)
    if problem.P is not None and problem.P.nnz:
        return None
    rows = [A[:ne], A[ne:ne + nl], eye_n, -eye_n, A[ne + nl:]]
    rhs = [np.zeros(ne), np.zeros(nl), np.ones(n), np.ones(n), np.zeros(m - ne - nl)]
    return ConicProblem(c=problem.c.astype(float), A=sp.vstack(rows).tocsc(),
                        b=np.concatenate(rhs), n_eq=ne, n_nonneg=nl + 2 * n,
                        soc=problem.soc)


def residuals(problem: ConicProblem, res: SolverResult) -> dict:
    """The answer's residuals against the problem itself, relative to its size.

    Optimal: ``primal`` (equality rows |A z - b| and cone breach of b - A z, over
    max(1, |b|, |A| |z|)), ``dual`` (|P z + c + A'y| and cone breach of y, over
    max(1, |c|, |P z|, |A|' |y|): the sizes of the terms that cancel) and ``gap``
    (|primal - dual objective| over max(1, |objective|)).
    Infeasible with a certificate y: ``certificate`` (|A'y| and the cone breach of y,
    over |y| |A|) and ``margin`` (-b'y over |y| max(1, |b|), > 0 for a certificate).
    Unbounded with a ray d in ``z`` (no quadratic term): ``certificate`` (|A d| on the
    zero rows and the cone breach of -A d, over |d| |A|) and ``margin`` (-c'd over
    |d| max(1, |c|)).
    Empty when the back end returned nothing to check.
    """
    A, b, c = problem.A, problem.b, problem.c
    ne = problem.n_eq
    if res.status == OPTIMAL and res.z is not None and res.y is not None:
        z, y = res.z, res.y
        Az = A @ z
        s = b - Az
        absA = abs(A)
        pscale = max(1.0, float(np.abs(b).max(initial=0.0)),
                     float((absA @ np.abs(z)).max(initial=0.0)))
        primal = max(float(np.abs(s[:ne]).max(initial=0.0)), _cone_breach(problem, s))
        Pz = problem.P @ z if problem.P is not None else np.zeros_like(z)
        dres = Pz + c + A.T @ y
        dscale = max(1.0, float(np.abs(c).max(initial=0.0)), float(np.abs(Pz).max(initial=0.0)),
                     float((absA.T @ np.abs(y)).max(initial=0.0)))
        dual = max(float(np.abs(dres).max(initial=0.0)), _cone_breach(problem, y))
        pobj = float(c @ z + 0.5 * z @ Pz)
        dobj = float(-b @ y - 0.5 * z @ Pz)
        return {"primal": primal / pscale, "dual": dual / dscale,
                "gap": abs(pobj - dobj) / max(1.0, abs(pobj), abs(dobj))}
    if res.status == UNBOUNDED and res.z is not None and (problem.P is None
                                                          or not problem.P.nnz):
        d = res.z
        nd = float(np.abs(d).max(initial=0.0))
        if not nd > 0:
            return {"certificate": float("inf"), "margin": 0.0}
        na = float(abs(A).max()) if A.nnz else 1.0
        Ad = A @ d
        ray = max(float(np.abs(Ad[:ne]).max(initial=0.0)), _cone_breach(problem, -Ad))
        return {"certificate": ray / (nd * na),
                "margin": float(-c @ d) / (nd * max(1.0, float(np.abs(c).max(initial=0.0))))}
    if res.status == INFEASIBLE and res.y is not None:
        y = res.y
        ny = float(np.abs(y).max(initial=0.0))
        if not ny > 0:
            return {"certificate": float("inf"), "margin": 0.0}
        na = float(abs(A).max()) if A.nnz else 1.0
        cert = max(float(np.abs(A.T @ y).max(initial=0.0)), _cone_breach(problem, y))
        return {"certificate": cert / (ny * na),
                "margin": float(-b @ y) / (ny * max(1.0, float(np.abs(b).max(initial=0.0))))}
    return {}
