"""OSQP for quadratic programs with linear constraints (the force-state QP)."""

from __future__ import annotations

import time

import numpy as np

from ..errors import InputError
from ..sparse import CscMatrix, as_csc
from .base import FAILURE, INFEASIBLE, OPTIMAL, UNBOUNDED, ConicProblem, SolverResult


def solve_osqp(problem: ConicProblem, **settings) -> SolverResult:
    import osqp

    if problem.soc:
        raise InputError("OSQP handles linear constraints only (no friction cones)")
    n = problem.n
    P = as_csc(problem.P) if problem.P is not None else CscMatrix.empty((n, n))
    ne = problem.n_eq
    lower = np.concatenate([problem.b[:ne], np.full(problem.n_nonneg, -np.inf)])
    # certificates to the accuracy of the solver policy's check (the defaults, 1e-4,
    # left a ray of the catalogue's pressed-down block with a residual of 2.5e-5)
    opts = dict(verbose=False, eps_abs=1e-9, eps_rel=1e-9, polishing=True,
                max_iter=200000, eps_prim_inf=1e-9, eps_dual_inf=1e-9)
    opts.update(settings)
    t0 = time.perf_counter()
    solver = osqp.OSQP()
    solver.setup(P=P.triu().tocsc(), q=problem.c, A=as_csc(problem.A).tocsc(),
                 l=lower, u=problem.b, **opts)
    res = solver.solve(raise_error=False)  # a status, not an exception
    elapsed = time.perf_counter() - t0
    raw = str(res.info.status)
    status = (OPTIMAL if raw == "solved" else INFEASIBLE if raw == "primal infeasible"
              else UNBOUNDED if raw == "dual infeasible" else FAILURE)
    z = np.asarray(res.x) if status == OPTIMAL else None
    y = np.asarray(res.y) if status == OPTIMAL else None
    if status == INFEASIBLE and getattr(res, "prim_inf_cert", None) is not None:
        # OSQP's certificate: A'y = 0 and u'max(y, 0) + l'min(y, 0) < 0, here (l = -inf
        # on the inequality rows) y >= 0 there and b'y < 0, in this module's convention
        y = np.asarray(res.prim_inf_cert)
    if status == UNBOUNDED and getattr(res, "dual_inf_cert", None) is not None:
        z = np.asarray(res.dual_inf_cert)  # a ray: A d in -K, c'd < 0 (checked)
    return SolverResult(status, z, y, float(res.info.obj_val), "osqp", raw,
                        int(res.info.iter), elapsed)
