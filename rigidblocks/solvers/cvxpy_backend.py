"""Any conic solver installed for cvxpy (HiGHS, SCS, ECOS, Clarabel, ...), for cross-checks.

The standard-form problem is handed to cvxpy as it is, so every solver sees the same
formulation as the native Clarabel path.
"""

from __future__ import annotations

import time
import warnings

import numpy as np

from ..errors import InputError
from .base import FAILURE, INFEASIBLE, OPTIMAL, UNBOUNDED, ConicProblem, SolverResult

#: the back end's own defaults by cvxpy solver, under the caller's settings: OSQP as
#: the native back end runs it (polished, 1e-9, up to 200,000 iterations; cvxpy's
#: defaults, 1e-5, left the force state of the catalogue's leaning pair with a duality
#: gap of 1.5e-6, failing its check, and 20,000 iterations a relaxation of the seed's
#: model inaccurate)
DEFAULTS = {"OSQP": {"eps_abs": 1e-9, "eps_rel": 1e-9, "polishing": True,
                     "max_iter": 200_000}}


def installed_cvxpy_solvers() -> list[str]:
    import cvxpy as cp

    return list(cp.installed_solvers())


def solve_cvxpy(problem: ConicProblem, solver: str, **options) -> SolverResult:
    import cvxpy as cp

    name = solver.upper()
    if name not in cp.installed_solvers():
        from cvxpy.settings import SOLVERS

        from ..extras import solver_install_hint

        installed = f"(installed: {', '.join(cp.installed_solvers())})"
        if name not in SOLVERS:  # a typo: no package to install
            raise InputError(f"cvxpy has no solver {solver!r} {installed}")
        raise InputError(f"solver {solver!r} is not installed for cvxpy: "
                         f"{solver_install_hint(solver)} {installed}")
    n = problem.n
    z = cp.Variable(n)
    A = problem.A.tocsr()
    b = problem.b
    ne, ni = problem.n_eq, problem.n_nonneg
    cons = []
    if ne:
        cons.append(A[:ne] @ z == b[:ne])
    if ni:
        cons.append(A[ne:ne + ni] @ z <= b[ne:ne + ni])
    start = ne + ni
    for k in problem.soc:
        # s = b - A z in SOC(k): s[0] >= ||s[1:]||
        s = b[start:start + k] - A[start:start + k] @ z
        cons.append(cp.SOC(s[0], s[1:]))
        start += k
    obj = problem.c @ z
    if problem.P is not None and problem.P.nnz:
        obj = obj + 0.5 * cp.quad_form(z, cp.psd_wrap(problem.P.tocsc()))
    prob = cp.Problem(cp.Minimize(obj), cons)
    t0 = time.perf_counter()
    try:
        with warnings.catch_warnings():
            # "Solution may be inaccurate": the status says so (a failure here)
            warnings.simplefilter("ignore", UserWarning)
            prob.solve(solver=name, **{**DEFAULTS.get(name, {}), **options})
    except cp.error.SolverError as err:
        return SolverResult(FAILURE, None, None, np.nan, f"cvxpy-{name.lower()}", str(err),
                            solve_time=time.perf_counter() - t0)
    elapsed = time.perf_counter() - t0
    raw = str(prob.status)
    status = {cp.OPTIMAL: OPTIMAL, cp.INFEASIBLE: INFEASIBLE,
              cp.UNBOUNDED: UNBOUNDED}.get(prob.status, FAILURE)
    zz = y = None
    if status == OPTIMAL:
        zz = np.asarray(z.value)
    if status in (OPTIMAL, INFEASIBLE) and all(c.dual_value is not None for c in cons):
        # infeasible: the duals are a certificate (A'y = 0, y in the dual cone, b'y < 0)
        parts = []
        k = 0
        # cvxpy's duals follow the convention of the module's KKT condition already
        # (min z s.t. z == 1 gives -1, as Clarabel's)
        if ne:
            parts.append(np.asarray(cons[k].dual_value).ravel())
            k += 1
        if ni:
            parts.append(np.asarray(cons[k].dual_value).ravel())
            k += 1
        for size in problem.soc:
            dv = cons[k].dual_value
            parts.append(np.concatenate([np.ravel(dv[0]), np.ravel(dv[1])])
                         if isinstance(dv, list) else np.zeros(size))
            k += 1
        y = np.concatenate(parts) if parts else np.zeros(0)
    stats = prob.solver_stats
    return SolverResult(status=status, z=zz, y=y,
                        objective=float(prob.value) if prob.value is not None else np.nan,
                        solver=f"cvxpy-{name.lower()}", raw_status=raw,
                        iterations=int(getattr(stats, "num_iters", 0) or 0),
                        solve_time=elapsed)
