"""Clarabel through its native API (the default back end).

The problem matrices go to ``clarabel.DefaultSolver`` as they are: no modelling layer
in between, so the only cost above the interior-point iterations is building the
sparse matrices.

A solve can be given looser ``fallbacks`` (tolerance settings the caller would solve
again at if its own are out of reach). Clarabel's iterates do not depend on its
tolerances, only where it stops does; so a solve whose iteration stalls short of its own
tolerances, with an iterate that already meets a fallback's, stops there
(:class:`_Stall`) and returns the answer the fallback solve would have gone through,
instead of iterating on to its limit and being solved again. A solve that ends short of
its tolerances by itself is a failure, but one that carries its last iterate where that
meets a fallback's tolerances.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence

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


#: iterations in which the distance to a solve's own tolerances must halve; after that
#: many without, a solve whose iterate meets a fallback's tolerances stops there. On the
#: 20,093-block wall's relaxation at f = 1 the 1e-10 solve met 1e-9 after 88 iterations,
#: got to 2.8 times its own tolerances after 104 and no closer in the 96 after that (its
#: limit of 200, 257 s), before the 1e-9 solve that answered (89 iterations, 102 s)
STALL_WINDOW = 15


def _distance(info, tol: tuple[float, float, float]) -> float:
    """How far an iterate (its ``clarabel.DefaultInfo``) is from Clarabel's test for
    "Solved" at the tolerances ``tol`` (feasibility, absolute gap, relative gap): each
    residual over its tolerance, the gap by the closer of its two forms; below 1 passes.
    An iterate on the way to an infeasibility certificate (kappa/tau > 1) never does."""
    feas, gap_abs, gap_rel = tol
    if not info.ktratio <= 1.0:
        return math.inf
    return max(info.res_primal / feas, info.res_dual / feas,
               min(info.gap_abs / gap_abs, info.gap_rel / gap_rel))


def _tolerances(settings) -> tuple[float, float, float]:
    return settings.tol_feas, settings.tol_gap_abs, settings.tol_gap_rel


class _Stall:
    """Termination callback: stop once the distance to the solve's own tolerances has
    not halved in :data:`STALL_WINDOW` iterations and the iterate meets the tolerances of
    one of the fallbacks (``met``: the first, in the order given, that it meets)."""

    def __init__(self, own: tuple[float, float, float],
                 fallbacks: list[tuple[float, float, float]]):
        self.own, self.fallbacks = own, fallbacks
        self.best, self.best_at = math.inf, 0
        self.met: int | None = None

    def meets(self, info) -> int | None:
        """The first fallback whose tolerances the iterate meets, or None."""
        return next((i for i, tol in enumerate(self.fallbacks)
                     if _distance(info, tol) < 1.0), None)

    def __call__(self, info) -> bool:
        d = _distance(info, self.own)
        if d <= 0.5 * self.best:
            self.best, self.best_at = d, info.iterations
        if info.iterations - self.best_at < STALL_WINDOW:
            return False
        self.met = self.meets(info)
        return self.met is not None


def cones(problem: ConicProblem) -> list:
    import clarabel

    out = []
    if problem.n_eq:
        out.append(clarabel.ZeroConeT(problem.n_eq))
    if problem.n_nonneg:
        out.append(clarabel.NonnegativeConeT(problem.n_nonneg))
    out.extend(clarabel.SecondOrderConeT(k) for k in problem.soc)
    return out


def solve_clarabel(problem: ConicProblem, fallbacks: Sequence[dict] = (),
                   **settings) -> SolverResult:
    """Solve with Clarabel; settings are ``clarabel.DefaultSettings`` attributes.

    ``fallbacks``: the settings (whole, not changes to these) of the solves the caller
    would try next, in that order, where the iteration may stop once it stalls (module
    docstring); the result's ``fallback`` is then the index of the one whose tolerances
    its answer meets (of a failure: its last iterate, which it then carries)."""
    import clarabel

    n = problem.n
    if problem.P is None:
        P = sp.csc_matrix((np.zeros(0), np.zeros(0, np.int32), np.zeros(n + 1, np.int32)),
                          shape=(n, n))
    else:
        P = sp.triu(problem.P, format="csc")
    A = problem.A if problem.A.format == "csc" else sp.csc_matrix(problem.A)
    own = clarabel_settings(**settings)
    t0 = time.perf_counter()
    solver = clarabel.DefaultSolver(P, np.asarray(problem.c, float), A,
                                    np.asarray(problem.b, float), cones(problem), own)
    stall = None
    if fallbacks:
        stall = _Stall(_tolerances(own), [_tolerances(clarabel_settings(**f))
                                          for f in fallbacks])
        solver.set_termination_callback(stall)
    sol = solver.solve()
    elapsed = time.perf_counter() - t0
    raw = str(sol.status).split(".")[-1]
    status = _STATUS.get(raw, FAILURE)
    fallback = None
    if stall is not None and raw == "CallbackTerminated":
        fallback = stall.met
        status = OPTIMAL
        met = clarabel_settings(**fallbacks[fallback])
        raw = f"Solved to tolerance {met.tol_feas:.0e} (stalled short of {own.tol_feas:.0e})"
    elif stall is not None and status == FAILURE:
        # ended short of its own tolerances by itself (Clarabel's AlmostSolved, an
        # iteration limit): still a failure, with its last iterate where that meets a
        # fallback's tolerances (the caller decides whether to take it)
        fallback = stall.meets(solver.get_info())
        if fallback is not None:
            met = clarabel_settings(**fallbacks[fallback])
            raw = f"{raw} (its last iterate meets tolerance {met.tol_feas:.0e})"
    z = np.asarray(sol.x) if status == OPTIMAL or fallback is not None else None
    y = np.asarray(sol.z) if status in (OPTIMAL, INFEASIBLE) or fallback is not None else None
    return SolverResult(status=status, z=z, y=y, objective=float(sol.obj_val),
                        solver="clarabel", raw_status=raw, iterations=int(sol.iterations),
                        solve_time=elapsed, fallback=fallback)
