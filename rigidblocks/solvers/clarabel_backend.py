"""Clarabel through its native API (the default back end).

The problem matrices go to ``clarabel.DefaultSolver`` as they are: no modelling layer
in between, so the only cost above the interior-point iterations is building the
sparse matrices.
"""

from __future__ import annotations

import time

import numpy as np
import scipy.sparse as sp

from ..errors import InputError
from .base import FAILURE, INFEASIBLE, OPTIMAL, UNBOUNDED, ConicProblem, SolverResult

_STATUS = {
    "Solved": OPTIMAL,
    "PrimalInfeasible": INFEASIBLE,
    "DualInfeasible": UNBOUNDED,
}


def clarabel_settings(**overrides):
    import clarabel

    s = clarabel.DefaultSettings()
    s.verbose = False
    s.presolve_enable = True
    # the single-threaded sparse LDL: on the block assemblies' KKT systems it is several
    # times faster than the multithreaded supernodal factorisation "auto" picks
    s.direct_solve_method = "qdldl"
    for k, v in overrides.items():
        if not hasattr(s, k):
            raise InputError(f"unknown Clarabel setting {k!r}")
        setattr(s, k, v)
    return s


def cones(problem: ConicProblem) -> list:
    import clarabel

    out = []
    if problem.n_eq:
        out.append(clarabel.ZeroConeT(problem.n_eq))
    if problem.n_nonneg:
        out.append(clarabel.NonnegativeConeT(problem.n_nonneg))
    out.extend(clarabel.SecondOrderConeT(k) for k in problem.soc)
    return out


def solve_clarabel(problem: ConicProblem, **settings) -> SolverResult:
    """Solve with Clarabel; settings are ``clarabel.DefaultSettings`` attributes."""
    import clarabel

    n = problem.n
    if problem.P is None:
        P = sp.csc_matrix((np.zeros(0), np.zeros(0, np.int32), np.zeros(n + 1, np.int32)),
                          shape=(n, n))
    else:
        P = sp.triu(problem.P, format="csc")
    A = problem.A if problem.A.format == "csc" else sp.csc_matrix(problem.A)
    t0 = time.perf_counter()
    solver = clarabel.DefaultSolver(P, np.asarray(problem.c, float), A,
                                    np.asarray(problem.b, float), cones(problem),
                                    clarabel_settings(**settings))
    sol = solver.solve()
    elapsed = time.perf_counter() - t0
    raw = str(sol.status).split(".")[-1]
    status = _STATUS.get(raw, FAILURE)
    z = np.asarray(sol.x) if status == OPTIMAL else None
    y = np.asarray(sol.z) if status in (OPTIMAL, INFEASIBLE) else None
    return SolverResult(status=status, z=z, y=y, objective=float(sol.obj_val),
                        solver="clarabel", raw_status=raw, iterations=int(sol.iterations),
                        solve_time=elapsed)
