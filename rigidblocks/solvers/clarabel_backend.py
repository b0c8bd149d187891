"""Clarabel through its native API (the default back end).

The problem matrices go to ``clarabel.DefaultSolver`` as their CSC arrays (its Python
interface reads ``data``, ``indices``, ``indptr``, ``shape`` and
``has_canonical_format`` of whatever it is given, scipy's or not: :class:`_Listed`): no
modelling layer in between, so the only cost above the interior-point iterations is
building the sparse matrices.

A solve can be given the settings of the solve its caller would try next where its own
tolerances are out of reach (looser ones). Clarabel's iterates do not depend on its
tolerances, only where it stops does; so a solve whose iteration stalls short of its own
tolerances, with an iterate that already meets the next solve's, stops there
(:class:`_Stall`) and returns the answer the next solve would have gone through,
instead of iterating on to its limit and being solved again. A solve that ends short of
its tolerances by itself is a failure, but one that carries its last iterate where that
meets the next solve's tolerances. Only the next solve's count: an iterate that meets
looser ones still goes on to it (on the extruded 1,009-block wall a 1e-10 solve that
met 1e-9 after 54 iterations ended after 62 with an iterate meeting only 1e-8; the 1e-9
solve after it answered).
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..errors import InputError
from ..sparse import CscMatrix, as_csc
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
#: many without, a solve whose iterate meets the next solve's tolerances stops there. On
#: the 20,093-block wall's relaxation at f = 1 the 1e-10 solve met 1e-9 after 88
#: iterations, got to 2.8 times its own tolerances after 104 and no closer in the 96
#: after that (its limit of 200, 257 s), before the 1e-9 solve that answered (89
#: iterations, 102 s)
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
    not halved in :data:`STALL_WINDOW` iterations and the iterate meets the next
    solve's tolerances (``stopped``).

    A Ctrl-C that lands in the callback stops the solve (``interrupted``) for the caller
    to raise again: raised inside it, Clarabel printed its traceback, dropped it and
    iterated on, and the interrupted analysis answered."""

    def __init__(self, own: tuple[float, float, float], after: tuple[float, float, float]):
        self.own, self.after = own, after
        self.best, self.best_at = math.inf, 0
        self.stopped = self.interrupted = False

    def meets(self, info) -> bool:
        """Whether the iterate meets the next solve's tolerances."""
        return _distance(info, self.after) < 1.0

    def __call__(self, info) -> bool:
        try:
            d = _distance(info, self.own)
            if d <= 0.5 * self.best:
                self.best, self.best_at = d, info.iterations
            self.stopped = (info.iterations - self.best_at >= STALL_WINDOW
                            and self.meets(info))
        except KeyboardInterrupt:
            self.interrupted = True
        return self.stopped or self.interrupted


class _Listed:
    """A CSC matrix as Clarabel's Python interface reads it, its arrays as lists: it
    copies them element by element through Python's sequence protocol, which takes a
    list's numbers as they are but builds a numpy scalar for each element of an array
    (the extruded 1,041-block wall's least-energy problem: 1.6e8 instructions fewer,
    1 % of its whole check)."""

    has_canonical_format = True

    def __init__(self, m: CscMatrix):
        self.shape = m.shape
        self.data, self.indices, self.indptr = (m.data.tolist(), m.indices.tolist(),
                                                m.indptr.tolist())


def cones(problem: ConicProblem) -> list:
    import clarabel

    out = []
    if problem.n_eq:
        out.append(clarabel.ZeroConeT(problem.n_eq))
    if problem.n_nonneg:
        out.append(clarabel.NonnegativeConeT(problem.n_nonneg))
    out.extend(clarabel.SecondOrderConeT(k) for k in problem.soc)
    return out


def solve_clarabel(problem: ConicProblem, after: dict | None = None,
                   **settings) -> SolverResult:
    """Solve with Clarabel; settings are ``clarabel.DefaultSettings`` attributes.

    ``after``: the settings (whole, not changes to these) of the solve the caller would
    try next, where the iteration may stop once it stalls (module docstring); the
    result's ``next_met`` then says its answer meets their tolerances (that of a
    failure: its last iterate, which it then carries)."""
    import clarabel

    n = problem.n
    P = CscMatrix.empty((n, n)) if problem.P is None else as_csc(problem.P).triu()
    A = as_csc(problem.A)
    own = clarabel_settings(**settings)
    t0 = time.perf_counter()
    solver = clarabel.DefaultSolver(_Listed(P), np.asarray(problem.c, float).tolist(),
                                    _Listed(A), np.asarray(problem.b, float).tolist(),
                                    cones(problem), own)
    stall = None
    if after is not None:
        nxt = clarabel_settings(**after)
        stall = _Stall(_tolerances(own), _tolerances(nxt))
        solver.set_termination_callback(stall)
    sol = solver.solve()
    if stall is not None and stall.interrupted:
        raise KeyboardInterrupt
    elapsed = time.perf_counter() - t0
    raw = str(sol.status).split(".")[-1]
    status = _STATUS.get(raw, FAILURE)
    met = False
    if stall is not None and raw == "CallbackTerminated" and stall.stopped:
        status, met = OPTIMAL, True
        raw = f"Solved to tolerance {nxt.tol_feas:.0e} (stalled short of {own.tol_feas:.0e})"
    elif stall is not None and status == FAILURE and stall.meets(solver.get_info()):
        # ended short of its own tolerances by itself (Clarabel's AlmostSolved, an
        # iteration limit): still a failure, with its last iterate, which meets the next
        # solve's tolerances (the caller decides whether to take it)
        met = True
        raw = f"{raw} (its last iterate meets tolerance {nxt.tol_feas:.0e})"
    z = np.asarray(sol.x) if status == OPTIMAL or met else None
    y = np.asarray(sol.z) if status in (OPTIMAL, INFEASIBLE) or met else None
    return SolverResult(status=status, z=z, y=y, objective=float(sol.obj_val),
                        solver="clarabel", raw_status=raw, iterations=int(sol.iterations),
                        solve_time=elapsed, next_met=met)
