"""HiGHS for linear programs, through scipy.optimize.linprog (a cross-check back end)."""

from __future__ import annotations

import time

import numpy as np

from ..errors import InputError
from .base import FAILURE, INFEASIBLE, OPTIMAL, UNBOUNDED, ConicProblem, SolverResult

# scipy's linprog status codes
_STATUS = {0: OPTIMAL, 2: INFEASIBLE, 3: UNBOUNDED}


def solve_highs(problem: ConicProblem, **options) -> SolverResult:
    """Solve an LP with HiGHS (dual simplex / IPM as HiGHS chooses)."""
    from scipy.optimize import linprog

    if not problem.is_lp:
        raise InputError("the HiGHS back end solves linear programs only "
                         "(3D friction cones are second-order cones: use clarabel)")
    A = problem.A.tocsr()
    ne, ni = problem.n_eq, problem.n_nonneg
    t0 = time.perf_counter()
    opts = {"primal_feasibility_tolerance": 1e-9, "dual_feasibility_tolerance": 1e-9}
    opts.update(options)
    res = linprog(problem.c, A_ub=A[ne:ne + ni] if ni else None, b_ub=problem.b[ne:ne + ni]
                  if ni else None, A_eq=A[:ne] if ne else None,
                  b_eq=problem.b[:ne] if ne else None, bounds=(None, None), method="highs",
                  options=opts)
    elapsed = time.perf_counter() - t0
    status = _STATUS.get(res.status, FAILURE)
    z = y = None
    if status == OPTIMAL:
        z = np.asarray(res.x)
        # marginals are d(objective)/d(rhs); the KKT convention here is y = -marginals
        y = -np.concatenate([res.eqlin.marginals if ne else [],
                             res.ineqlin.marginals if ni else []])
    return SolverResult(status=status, z=z, y=y,
                        objective=float(res.fun) if res.fun is not None else np.nan,
                        solver="highs", raw_status=f"{res.status}: {res.message}",
                        iterations=int(getattr(res, "nit", 0) or 0), solve_time=elapsed)
