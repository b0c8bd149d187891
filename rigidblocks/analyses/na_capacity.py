"""The capacity bound: a lower bound on every non-associative collapse multiplier from
each joint's least normal force over the admissible states (Radenkovic's second theorem,
:func:`_capacity_bound`), and the linear programs over the admissible states it rests
on, which the safe multiplier's mixed-integer program
(:mod:`rigidblocks.analyses.na_bounds`) shares: its data (:class:`_Model`), the least or
largest of a linear function over the admissible states between two multipliers
(:func:`_admissible_lps`).

The non-associative analyses (:mod:`rigidblocks.analyses.nonassociative`) compute it by
themselves on small 2D scenes (:func:`capacity_bound`): a theorem that decides where
the iterations from the elastic state X0 do not.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp
from scipy.optimize import linprog

from ..errors import SolverFailure
from ..solvers import INFEASIBLE, OPTIMAL
from ..solvers.highs_warm import warm_lp

if TYPE_CHECKING:
    from ..methods.convex import ConvexMethod

#: the largest scene (joints) the mixed-integer program is tried on by default, and
#: on which the analyses compute the capacity bound by themselves
MAX_JOINTS = 50


@dataclass(frozen=True, eq=False)
class _Model:
    """The data of the safe multiplier's mixed-integer program, and of the capacity
    bound's LPs (scaled; the equations are in :mod:`rigidblocks.analyses.na_bounds`)."""

    A: sp.csr_matrix  # (ne, n) equilibrium
    live: np.ndarray  # (ne,) scaled live column
    b: np.ndarray  # (ne,) minus the scaled dead load
    G: sp.csr_matrix  # (L, n) joint laws G x <= h
    h: np.ndarray
    Q: sp.csr_matrix  # (L, n) flow rows
    normal: slice  # the normal-force columns of x
    n_points: int  # the first n_points law rows are the no-tension rows
    #: a friction row's slack over its friction-and-cohesion term (h_r + f N) at most:
    #: 2 for |T| <= f N + c in 2D, 1 + 1 / cos(pi / k) for a facet of an inscribed
    #: k-facet pyramid (its slack h + f cos N - T . d_i, with |T| <= f N + c)
    slack_factor: float = 2.0


def _model(cv: ConvexMethod, marked: np.ndarray, f: float) -> _Model:
    from ..problems.formulation import build_max_load

    sysm, sc = cv.system, cv.scaling
    prob, jr = build_max_load(sysm, sc, cv.f_joint(f), cv.pyramid)
    ne, n = sysm.n_rows, sysm.layout.size
    A = prob.A.tocsr()
    G = jr.G_lin.tocsr()[:, :n]
    _, rows, cols, joint, vals = jr.f_entries
    na = marked[joint]
    # the flow rows: the -f N terms of the non-associative joints taken out
    Q = (G - sp.csr_matrix((vals[na], (rows[na], cols[na])), shape=G.shape)).tocsr()
    Q.eliminate_zeros()
    return _Model(A=A[:ne, :n], live=A[:ne, n].toarray().ravel(), b=prob.b[:ne],
                  G=G, h=jr.h_lin, Q=Q, normal=sysm.layout.normal,
                  n_points=jr.n_normal_rows,
                  slack_factor=2.0 if cv.pyramid is None else
                  1.0 + 1.0 / math.cos(math.pi / cv.pyramid))


def _admissible_lps(m: _Model, lo: float, hi: float,
                    costs: Iterator[np.ndarray]) -> Iterator[tuple[str, float]]:
    """min c'(x, lambda) over the admissible states at ``lo`` <= lambda <= ``hi`` for
    each cost c of ``costs``: (status, optimum) each, in one HiGHS model whose basis the
    next cost starts from (:meth:`~rigidblocks.solvers.highs_warm.WarmLp.minimise`): a
    3D wall of 42 joints has 1,512 law rows, whose slacks took 150 s as LPs solved from
    scratch."""
    L, n = m.G.shape
    A = sp.vstack([sp.hstack([m.A, sp.csr_matrix(m.live[:, None])]),
                   sp.hstack([m.G, sp.csr_matrix((L, 1))]),
                   sp.csr_matrix(([1.0], ([0], [n])), shape=(1, n + 1))], format="csc")
    lower = np.concatenate([m.b, np.full(L, -np.inf), [lo]])
    upper = np.concatenate([m.b, m.h, [hi if math.isfinite(hi) else np.inf]])
    lp = warm_lp(np.zeros(n + 1), A, lower, upper)
    for c in costs:
        st = lp.minimise(c)
        yield st, (float(np.asarray(c) @ lp.x) if st == OPTIMAL else math.nan)


def _least_normal(m: _Model, groups: np.ndarray, starts: np.ndarray, lo: float,
                  hi: float) -> np.ndarray | None:
    """(len(groups),) the least sum of the normal forces of each group of contact points
    (group g: points starts[g] to starts[g + 1]) over the admissible states at lo <=
    lambda <= hi (one LP each); None when there is no such state."""
    n = m.G.shape[1]

    def cost(j: int) -> np.ndarray:
        c = np.zeros(n + 1)
        c[m.normal.start + starts[j]:m.normal.start + starts[j + 1]] = 1.0
        return c

    out = np.zeros(len(groups))
    for i, (st, fun) in enumerate(_admissible_lps(m, lo, hi, (cost(j) for j in groups))):
        if st == INFEASIBLE:
            return None
        if st != OPTIMAL:
            raise SolverFailure(f"HiGHS: {st} (least normal force of a joint)", "highs", st)
        out[i] = fun
    return out


def _highs(prob, cost: np.ndarray, lam: float | None = None, dead: float = 1.0):
    """HiGHS's simplex (scipy) over the rows of a linear maximum-load problem ``prob``
    (:func:`build_max_load`, 2D or with pyramids): minimise ``cost``, lambda fixed at
    ``lam`` where given, the dead load times ``dead``; scipy's result."""
    ne = prob.n_eq
    A = prob.A.tocsr()
    bounds = [(None, None)] * prob.n
    if lam is not None:
        bounds[prob.cols["lambda"].start] = (lam, lam)
    return linprog(cost, A_ub=A[ne:], b_ub=prob.b[ne:], A_eq=A[:ne], b_eq=dead * prob.b[:ne],
                   bounds=bounds, method="highs")


def _max_load_lp(prob) -> float | None:
    """lambda* of a linear maximum-load problem by HiGHS's simplex (:func:`_highs`): inf
    when unbounded, None when infeasible."""
    res = _highs(prob, prob.c)
    if res.status == 3:
        return math.inf
    if res.status == 2:
        return None
    if res.status != 0:
        raise SolverFailure(f"HiGHS: {res.message} (maximum load, capped laws)", "highs",
                            str(res.status))
    return float(res.x[prob.cols["lambda"]][0])


def _carries_more_dead(prob, lam: float) -> bool:
    """Does the (capped) structure of the maximum-load problem ``prob`` have an
    admissible state under (1 + DEAD_MARGIN) x its dead load plus ``lam`` x its live
    load (:func:`_highs`)?"""
    res = _highs(prob, np.zeros(prob.n), lam, 1.0 + DEAD_MARGIN)
    if res.status not in (0, 2):
        raise SolverFailure(f"HiGHS: {res.message} (capped laws under more dead load)",
                            "highs", str(res.status))
    return res.status == 0


#: the share by which the capped structure of a round must carry more than the dead load
#: (:func:`_capacity_bound`): above HiGHS's feasibility tolerance (1e-7 of the scaled
#: loads)
DEAD_MARGIN = 1e-6


def _capacity_bound(m: _Model, cv: ConvexMethod, marked: np.ndarray, f: float, lo: float,
                    hi: float, max_rounds: int = 100, live_too: bool = False
                    ) -> tuple[float, int, float]:
    """A lower bound on every non-associative collapse multiplier in [lo, hi], the
    rounds it took, and (``live_too``) a lower bound on those whose mechanism the live
    load drives (else the first again).

    Radenkovic's second theorem with the least normal forces: a collapse state at
    lambda is admissible at lambda, so each joint's normal force sum N_j is at least
    N_j^min, its least over the admissible states at lo <= lambda <= hi, and the shear
    its slip dissipates against, f N_j + c_j a_j, at least k_j = max(0, f N_j^min +
    c_j a_j). The mechanism (openings where N is at its tensile limit, slips without
    dilatancy) is a mechanism of the structure whose non-associative joints follow the
    cohesion-only law |T_j| <= k_j (normality for it: a slip without opening), and it
    dissipates there no more than in the collapse state: by the kinematic theorem that
    structure's associative multiplier is a lower bound (with N_j^min = 0 it is the
    frictionless bound, Drucker 1954). The bound raises lo, which raises N^min: repeated
    until it stops rising (or reaches hi).

    The kinematic theorem bounds the collapse states whose mechanism the live load
    drives (F_live . u > 0). Those the dead load drives (F_live . u <= 0: the live load
    does no work on them, or resists them) are excluded only where the capped structure
    carries (1 + DEAD_MARGIN) x the dead load plus lo x the live load
    (:func:`_carries_more_dead`): such a state y and the collapse state's mechanism u
    give (1 + e) F_dead . u + lo F_live . u <= D_cap(u) <= D(u) = F_dead . u + lambda
    F_live . u, which no lambda >= lo meets while the mechanism dissipates. A round
    whose capped structure does not carries its bound for the live load's mechanisms
    only (``live_too``); the bound on every state stops before it. The inclined corbel
    arch at f = 0.8: the first round's capped structure has no state under the dead load
    alone, and a state at lambda = 0.0128 collapses by a mechanism the live load resists
    (the mixed-integer LP of :mod:`rigidblocks.analyses.na_bounds` finds it), below the
    live load's bound, its associative multiplier 0.0213."""
    from ..problems.formulation import build_max_load

    sysm, sc = cv.system, cv.scaling
    c = sysm.contacts
    fj = cv.f_joint(f)
    f_eff = np.where(marked & np.isfinite(fj), 0.0, fj)
    if c.dimension == 2:  # the law of a joint: its normal forces' sum
        mk = np.flatnonzero(marked & np.isfinite(fj))
        starts, at = c.joint_start, c.joint_start[mk]
        fk, coh = fj[mk], (c.cohesion * c.areas / sc.force)[mk]
    else:  # the law of a contact point (a pyramid per point)
        pj = c.point_joint
        mk = np.flatnonzero((marked & np.isfinite(fj))[pj])
        starts, at = np.arange(c.n_points + 1), mk
        fk, coh = fj[pj[mk]], (c.cohesion[pj] * c.point_areas / sc.force)[mk]
    rounds, every = 0, None  # (every: the bound on every state, once it stopped)
    while rounds < max_rounds and lo < hi:
        rounds += 1
        nmin = _least_normal(m, mk, starts, lo, hi)
        if nmin is None:  # no admissible state in [lo, hi]: no collapse state either
            return (hi if every is None else every), rounds, hi
        cap = np.zeros(c.n_points)
        cap[at] = np.maximum(fk * nmin, -coh)
        prob, _ = build_max_load(sysm, sc, f_eff, cv.pyramid, cap=cap)
        lam = _max_load_lp(prob)
        if lam is None or lam <= lo * (1 + 1e-12) + 1e-12:
            break
        if every is None and not _carries_more_dead(prob, lo):
            every = lo
            if not live_too:
                break
        lo = min(lam, hi)
    return (lo if every is None else every), rounds, lo


#: the rounds of the capacity bound an analysis without dilatancy computes by itself
#: (:func:`capacity_bound`): each is one LP per joint. It rises by rounds: the stocky
#: arch at f = 0.6 reaches 0.3948 in 20 (0.29 s), 0.43226 in 100 (1.6 s), against its
#: associative 0.43228; the Arpino gate 0.118702 in 10 (0.24 s)
BOUND_ROUNDS = 20


def capacity_bound(cv: ConvexMethod, marked: np.ndarray, f: float, frictionless: float | None,
                   hi: float | None, max_rounds: int = BOUND_ROUNDS) -> float | None:
    """A lower bound on every non-associative collapse multiplier at friction ``f``
    between 0 (or the frictionless bound where it is higher) and the associative one
    ``hi`` (:func:`_capacity_bound`), as :func:`safe_multiplier` searches them, where an
    analysis computes it by itself: 2D scenes of at most MAX_JOINTS joints (on the
    walls it stays at the frictionless bound, 0, while the 10 x 10 wall's 290 joints
    take 1.7 s a round). None where it is not computed or does not rise above that
    start."""
    c = cv.contacts
    if c.dimension != 2 or c.n_joints > MAX_JOINTS or hi is None or not math.isfinite(hi) \
            or not (marked & np.isfinite(cv.f_joint(f))).any():
        return None
    lo = max(frictionless or 0.0, 0.0)
    if lo >= hi:
        return None
    cap, _, _ = _capacity_bound(_model(cv, marked, f), cv, marked, f, lo, hi, max_rounds)
    return cap if cap > lo else None


__all__ = ["BOUND_ROUNDS", "DEAD_MARGIN", "MAX_JOINTS", "capacity_bound"]
