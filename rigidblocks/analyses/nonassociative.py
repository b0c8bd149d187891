"""Non-associative sliding: Coulomb friction without dilatancy, the seed's joint law.

The seed's joint has separate links: normal links that carry no tension and shear
links that slip at f times the normal force, so a slip does not open the joint. The
admissible force states are the same as with associative friction (|T| <= f N, N >= 0),
but the limit theorems no longer hold: the associative collapse multiplier is only an
upper bound on the non-associative one (Radenkovic's first theorem; Drucker, "Coulomb
friction, plasticity, and limit loads", J. Appl. Mech. 21, 1954), and the multiplier of
frictionless joints is a lower bound (Drucker 1954; Radenkovic's second theorem: the
law |T| <= 0, whose normality is sliding without dilatancy, lies inside Coulomb's).

Non-associative answers are not unique: a pinch (a self-stress in the normal links that
no load causes) raises the shear the joints can carry. The state computed here is the
one reached from the elastic state X0, the least-complementary-energy state under
equilibrium alone (the seed's Eq. 3, before any joint law is imposed): a state X with

    A X + F = 0,   N >= -t,   |T_j| <= f_j (N_j1 + N_j2) + c_j,
    C (X - X0) = A^T y + p,

whose plastic distortion p is an opening (-N direction) only where a normal link is at
its tensile limit and a slip along the joint (no normal component: no dilatancy) only
where a shear link is at its threshold, in the direction of its shear. Two independent
algorithms compute it:

* ``convex`` (2D and 3D): a sequence of convex problems in the spirit of Gilbert,
  Casapulla & Ahmed (Computers & Structures 84, 2006, 873-887): each marked joint's
  Coulomb law is replaced by the cohesion-only law |T| <= f N_prev (N_prev the previous
  iterate's normal forces, per contact point in 3D), and the least-energy state under
  it is the next iterate; from N_0 = the normal forces of X0 (tension clipped), iterated
  to a fixed point, with damping when the change stops falling (cycle detection).
  The KKT conditions of the last problem are the conditions above: the normal cone of
  a cohesion-only law has no normal component. Where the capped problem is infeasible
  the iterate is the least-energy state of its relaxation (the smallest uniform breach
  R of the laws); a fixed point with R > 0 is a state the iteration settles on that the
  joints cannot carry: inadmissible.
* ``distortion`` (2D): the seed's impressed-distortion iteration
  (:mod:`rigidblocks.solvers.distortion`) whose projection onto the joint laws caps the
  shear links at f times the normal force without changing the normal links
  (:class:`~rigidblocks.solvers.distortion._NonAssocLaws`); its fixed point satisfies
  the same conditions, with p the accumulated distortions.

Verdicts: ``admissible`` at a fixed point within the laws; ``inadmissible`` when even
the associative (static) problem has no admissible state (proven), at a fixed point
that breaches the laws (convex), or when the distortion iteration drifts along a
mechanism without dilatancy on which the loads do more work than the joints dissipate
at their current normal forces; ``undecided`` (with the reason) when the iteration does
not settle within its budget. ``check`` gives these verdicts at one load factor.

The limit analyses on the convex path do not bisect on them: ``load`` iterates the limit
problem itself (:mod:`rigidblocks.analyses.na_limit`: max lambda under |T| <= f N_prev,
then the least confined state carrying it near N_prev, to a fixed point checked a
posteriori), from X0 under the dead load and from the associative collapse state, and
reports both; ``friction`` iterates the least f under the same caps at the load factor
(or, where a uniform joint dilates, searches f on the load's fixed point). On the
distortion path (the seed's procedure) ``load`` bisects on the verdicts between 0 and
the associative multiplier, ``friction`` upwards from the static f*.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..equilibrium import force_state
from ..errors import InputError, SolverFailure
from ..methods import ADMISSIBLE, FAILURE, INADMISSIBLE, UNDECIDED, Method, Verdict
from ..methods.base import ranked_breaches
from ..methods.convex import (
    ADMISSIBLE_TOL,
    OFF_FACE_NOTE,
    OTHER_MECHANISMS,
    STATE_SLACK,
    VERDICT_RTOL,
    ConvexMethod,
)
from ..methods.distortion import DistortionMethod
from ..methods.engine import (
    Search,
    Trial,
    beside_the_undecided,
    midpoint,
    narrow_enough,
    run,
    undecided_band,
)
from ..methods.relaxation import FRICTION_ATOL
from ..problems.formulation import build_energy_qp, build_max_load, build_relaxation, flexibility
from ..results import (
    BELOW_DEAD_LOAD,
    BOUND_STANDS,
    DIRECT_STANDS,
    STATIC_UNSTABLE,
    CheckResult,
    ForceState,
    FrictionResult,
    LoadResult,
    fmt_bracket,
    fmt_safe,
    relative_width,
    within,
)
from ..scene.model import (
    NON_ASSOCIATIVE,
    Scene,
    flow_value,
    friction_label,
    friction_value,
    geometry_key,
    loading_keys,
)
from ..scene.validate import check_live_load
from ..solvers import OPTIMAL
from .na_limit import (
    CARRY_TOL,
    MIN_DAMPING,
    CappedLimit,
    LimitRun,
    _damped,
    carried_text,
    certificate,
    reached_normals,
)
from .na_mechanism import FIXED_TOL, limit_runs, walks
from .notes import with_friction_governs
from .search import BRACKET_ATOL, UNBOUNDED_AT, bisect, no_number_note

#: relative change of the normal forces (of the largest force) that ends the iteration
FIXED_POINT_TOL = 1e-6
#: iteration budget of one fixed-point run (convex path)
FIXED_POINT_MAX_ITER = 300
#: relative accuracy of the non-associative multiplier and friction
NA_RTOL = 1e-5
#: the opening of the note that gives the answer from every start (:func:`starts_text`;
#: a terminal prints the same as its ``starts`` line)
SPREAD_NOTE = "non-associative collapse states: "
#: the first trial of the multiplier lies this far (relative) below the associative one
TOP_RTOL = 1e-6
#: normal forces below this fraction of the largest force are not resolved: the state
#: problems are quadratic programs solved by an interior-point method at its default
#: tolerances (duality gap 1e-8), which leaves a force at its bound of zero off it by
#: about the square root of the gap (2e-5 of the largest force on the joints of the
#: peer's "H" sample, whose normal forces are zero); an admissible verdict whose shear
#: capacity f N rests on such forces is round-off, not a verdict
N_RESOLUTION = 1e-4
#: the non-associative friction search goes no higher, and a non-associative answer at a
#: larger friction says what it rests on (ABOVE_CEILING): above 1e-3 / N_RESOLUTION the
#: caps f N of normal forces at the solver's resolution exceed 1e-3 of the largest
#: force, and they move the limit iteration's path (a 4 x 4 running-bond wall under 0.7
#: of its weight, with the ceiling at 1 / N_RESOLUTION: f* = 2939.57, from the caps of
#: its head joints' elastic normal forces, 1e-5 of the largest, round-off of 0; its
#: answer is 0.636 at every f from 1 to 1e5 but about 3,000)
NA_FRICTION_CEILING = 1e-3 / N_RESOLUTION
#: the note of an answer at a friction above NA_FRICTION_CEILING
ABOVE_CEILING = ("at f = {f:g} the caps f N of normal forces that are numerically zero "
                 f"(up to {N_RESOLUTION:g} of the largest force) reach {{share:.2g}} of "
                 "it: without dilatancy an answer above f = "
                 f"{NA_FRICTION_CEILING:g} rests on them, not on the joints' laws; "
                 "infinite friction (no sliding) is another law")
#: the note of a non-associative analysis at infinite friction: not the limit of large f
#: (the 4 x 4 running-bond wall: lambda* = 2 at infinite friction, 0.636 at f = 10, where
#: its head joints, without compression, carry no shear)
INFINITE_NOTE = ("with infinite friction no joint slides (Heyman's law) and the flow rule "
                 "does not enter; that law lets a joint without compression carry shear, "
                 "which no finite friction does without dilatancy: a large finite f may "
                 f"give less (compare --friction {NA_FRICTION_CEILING:g})")
#: the reason of an undecided verdict for that reason (its beginning)
UNRESOLVED_N = "the shear is carried on normal forces"
#: undecided trials in a row after which the friction search stops bracketing upwards
UNDECIDED_RUN = 3
#: the reason of a distortion run that found an admissible iterate but did not settle
_UNSETTLED = "admissible; the iteration budget"

#: the starts of the limit iteration, as the notes name them
FROM_X0 = "the elastic state X0"
FROM_ASSOC = "the associative collapse state"
#: the a-posteriori check of a fixed point: equilibrium and Coulomb with its own normal
#: forces to this fraction of its largest force
CERT_TOL = 1e-7

#: the note every non-associative result carries
STATE_NOTE = ("non-associative sliding (no dilatancy): the answer is the one reached from "
              "the elastic state X0 (least complementary energy under equilibrium alone, "
              "the starting state of the distortion method), with no pinch the loads do "
              "not cause; other states, and so other answers, may exist")


#: why the limit iteration has no start at a friction
DEAD_LOAD_BREACH = ("the state reached from the elastic state X0 under the dead load "
                    "alone breaches the joint laws")


#: the note of the limit analyses on the convex path
LIMIT_NOTE = ("non-associative sliding (no dilatancy): the answer is a collapse state "
              "reached from the elastic state X0 by iterating the limit problem with the "
              "shear capacities f N of the previous state's normal forces (Gilbert, "
              "Casapulla & Ahmed 2006), checked a posteriori; non-associative collapse "
              "states are not unique, and other starts may give other answers")


#: the note of the limit analyses in 2D (:mod:`rigidblocks.analyses.na_mechanism`)
WALK_NOTE = ("non-associative sliding (no dilatancy): the answer is a collapse state "
             "reached from the elastic state X0 by iterating the limit problem with the "
             "shear capacities f N of the previous state's normal forces (Gilbert, "
             "Casapulla & Ahmed 2006) until its mechanism has states that carry their own "
             "caps (the one nearest the iterate ends it), checked a posteriori; "
             "non-associative collapse states are not unique: the other states of that "
             "mechanism, and those from other starts, carry other multipliers")


#: how a non-associative result shows the associative step's notes on its own lambda*
#: (its bracket, its accuracy, its mechanism), which is the upper bound, not the answer
ASSOC_NOTE = ("on the associative multiplier lambda_a (the upper bound), not on the "
              "non-associative answer: ", "lambda_a")


def _bound_notes(na: NonAssociative, cv: ConvexMethod, seen: int, symbol: str,
                 wording: tuple[str, str]) -> None:
    """The notes the bound's own analysis added to ``cv`` (from index ``seen`` on) as a
    non-associative result shows them: those on the bound's number (naming ``symbol``,
    which the result's answer is also called) say so, ``wording`` = (prefix, the
    bound's symbol in their text), in ``cv``'s notes and in ``na``'s (the same list on
    the convex path; merged once on the distortion path). The rest (tolerances, the
    dead load) are the run's and stay as they are."""
    prefix, name = wording
    # the bound's mechanism is not the one shown: whether it is one of several, or off
    # its optimal face, is moot (the corbel dome's answer read "the mechanism drawn ...
    # is not a collapse mechanism at lambda_a" beside its own mechanism)
    for k in reversed(range(seen, len(cv.notes))):
        if cv.notes[k] == OTHER_MECHANISMS or cv.notes[k].startswith(OFF_FACE_NOTE):
            del cv.notes[k]
    for k in range(seen, len(cv.notes)):
        if symbol in cv.notes[k]:
            cv.notes[k] = prefix + cv.notes[k].replace(symbol, name)
            if cv.notes is not na.notes and cv.notes[k] not in na.notes:
                na.notes.append(cv.notes[k])


def flow_mask(scene: Scene, contacts: Any, flow: str | None = None) -> np.ndarray:
    """(m,) True where a joint slides without dilatancy.

    ``flow`` (None: the scene's ``flow``) is the rule of every joint without its own
    ``flow`` override; the overrides keep theirs.
    """
    default = flow_value(flow) if flow is not None else scene.effective_flow
    m = contacts.n_joints
    mask = np.full(m, default == NON_ASSOCIATIVE)
    own = {frozenset(j.blocks): j.flow for j in scene.joints if j.flow is not None}
    if own:
        ids = contacts.block_ids
        for k, (a, b) in enumerate(contacts.pairs):
            rule = own.get(frozenset((ids[a], ids[b])))
            if rule is not None:
                mask[k] = rule == NON_ASSOCIATIVE
    return mask


def is_nonassociative(scene: Scene, flow: str | None = None) -> bool:
    """Does any joint of ``scene`` slide without dilatancy (``flow`` as in
    :func:`flow_mask`)?"""
    default = flow_value(flow) if flow is not None else scene.effective_flow
    return default == NON_ASSOCIATIVE or any(j.flow == NON_ASSOCIATIVE for j in scene.joints)


@dataclass
class FixedPoint:
    """One non-associative run at (f, lambda).

    ``x``: the link forces (force units) of the last iterate; ``converged``: the
    iteration settled; ``history``: the relative change of the normal forces per
    iteration (convex path) or the joint-law violation per iteration (distortion).
    """

    status: str
    x: np.ndarray
    iterations: int
    converged: bool
    violation: float
    reason: str = ""
    history: list[float] = field(default_factory=list)
    time: float = 0.0


class NonAssociative(Method):
    """Non-associative verdicts on top of an opened method (``inner``)."""

    def __init__(self, inner: Method, marked: np.ndarray):
        super().__init__(inner.scene, inner.system, inner.timings)
        self.inner = inner
        self.name = inner.name
        self.solver = inner.solver
        self.notes = inner.notes
        self.marked = np.asarray(marked, dtype=bool)
        self.runs = 0
        self.fp_iterations = 0
        #: the result's :attr:`~rigidblocks.results.Result.cause`
        self.cause = ""
        #: what the lower bound of a `load` is (:func:`_lower_bound`)
        self.lower_by = "frictionless"
        self.converged_runs = 0
        #: the limit analyses answered by iterating the limit problem: True, or "walk"
        #: where they walked to a mechanism (2D)
        self.limit_path: bool | str = False
        #: the last state reached from X0 under the dead load and its friction
        #: (:func:`~rigidblocks.analyses.na_limit.reached_normals`): its breaches are
        #: named from it, not from the same fixed point run again
        self.dead_load: tuple[float, FixedPoint] | None = None
        #: the convex method of the bounds (:func:`_open`), and the back ends of a
        #: bound that is the answer itself (:meth:`answer_is_bound`)
        self.bounds_by: Method | None = None
        self.number_by: tuple[str, ...] = ()

    def answer_is_bound(self) -> None:
        """The answer is a bound's own number (the associative multiplier, the static
        f*) where the state reached from X0 stands there: the back ends that computed
        it answered too (the distortion path named itself alone beside Clarabel's
        lambda* = 2.4000000002 of the reference model)."""
        if self.bounds_by is not None:
            self.number_by = tuple(self.bounds_by.answered_by)

    @property
    def n_solves(self) -> int:
        return self.inner.n_solves

    @property
    def solve_time(self) -> float:
        return self.inner.solve_time

    @property
    def answered_by(self) -> tuple[str, ...]:
        own = tuple(self.inner.answered_by)
        return own + tuple(b for b in self.number_by if b not in own)

    @property
    def rejected(self) -> tuple[str, ...]:
        return self.inner.rejected

    @property
    def iterations(self) -> int:
        return self.fp_iterations

    def fixed_point(self, f: float, load_factor: float) -> FixedPoint:
        raise NotImplementedError

    def admissible(self, f: float, load_factor: float, for_state: bool = False) -> Verdict:
        r = self.fixed_point(f, load_factor)
        self.runs += 1
        self.fp_iterations += r.iterations
        self.converged_runs += bool(r.converged)
        notes = (r.reason,) if r.reason else ()
        return Verdict(r.status, 0.0 if r.status == ADMISSIBLE else r.violation, notes, r)

    def breaches(self, f: float, verdict: Verdict) -> tuple[tuple[int, float], ...]:
        """Where the state reached from X0 that a NOT ADMISSIBLE verdict rests on breaches
        the joint laws (the same laws as the associative ones: statics does not see the
        flow rule)."""
        d = verdict.data
        if verdict.status != INADMISSIBLE or not isinstance(d, FixedPoint):
            return ()
        return ranked_breaches(self.system, d.x, self.f_joint(f))

    def state(self, f: float, load_factor: float, verdict: Verdict,
              limit: bool = False) -> ForceState | None:
        if verdict.status != ADMISSIBLE or verdict.data is None:
            return None
        if isinstance(verdict.data, ForceState):  # (:func:`_bound_state`)
            return verdict.data
        return force_state(self.system, verdict.data.x,
                           "non-associative state reached from the elastic state")


class ConvexNonAssociative(NonAssociative):
    """The sequence of convex problems (Gilbert, Casapulla & Ahmed 2006), 2D and 3D."""

    def __init__(self, inner: ConvexMethod, marked: np.ndarray,
                 tol: float = FIXED_POINT_TOL, max_iter: int = FIXED_POINT_MAX_ITER):
        super().__init__(inner, marked)
        self.cv = inner
        self.tol = tol
        self.max_iter = max_iter
        #: the initial damping factor of the fixed-point update
        self.damping = 1.0
        self._lu: Any = None
        self._lu_done = False

    def elastic(self, load_factor: float) -> np.ndarray | None:
        """X0 = K A^T (A K A^T)^-1 (-F) in scaled units (None: A K A^T is singular, the
        linked structure is a mechanism)."""
        import scipy.sparse as sp

        sysm, sc = self.system, self.cv.scaling
        As = sp.diags(sc.row) @ sysm.A.tocsr()
        K = 1.0 / flexibility(sysm)
        if not self._lu_done:
            self._lu_done = True
            if As.shape[0]:
                from scipy.sparse.linalg import splu  # here: 60 ms of start-up
                try:
                    lu = splu((As @ sp.diags(K) @ As.T).tocsc())
                    d = np.abs(lu.U.diagonal())
                    if d.size and d.min() > 1e-12 * d.max() and np.all(np.isfinite(d)):
                        self._lu = lu
                except RuntimeError:
                    self._lu = None
        if self._lu is None:
            return None
        b = -sc.row * (sysm.dead + load_factor * sysm.live) / sc.force
        return K * (As.T @ self._lu.solve(b))

    def solve_capped(self, f_eff: np.ndarray, lf: float, cap: np.ndarray
                     ) -> tuple[np.ndarray | None, float]:
        """The least-energy state under the capped laws, or of their relaxation:
        (x scaled, breach R); x None when the equilibrium equations have no solution."""
        cv = self.cv

        def energy(relax: float) -> np.ndarray | None:
            prob = build_energy_qp(self.system, cv.scaling, f_eff, lf, relax, cv.pyramid,
                                   cap)
            try:
                res = cv.solve(prob, "non-associative state")
            except SolverFailure:  # (almost) infeasible: decided by the relaxation
                return None
            return res.z[prob.cols["x"]] if res.status == OPTIMAL else None

        x = energy(STATE_SLACK)
        if x is not None:
            return x, 0.0
        rprob, _ = build_relaxation(self.system, cv.scaling, f_eff, lf, cv.pyramid, cap=cap)
        rres = cv.solve(rprob, "relaxation", tight=True)
        if rres.status != OPTIMAL:
            return None, math.inf
        R = max(float(rres.z[rprob.cols["r"]][0]), 0.0)
        x = energy(R + STATE_SLACK)
        return (rres.z[rprob.cols["x"]] if x is None else x), R

    def _unresolved_breach(self, f_eff: np.ndarray, lf: float, f_pt: np.ndarray,
                           N: np.ndarray, scale: float) -> float | None:
        """The breach of the capped laws when the caps f N of the contact points whose
        normal force N is below N_RESOLUTION x ``scale`` (not resolved) are zero; None
        where there are none or the breach is within that resolution."""
        low = (f_pt > 0) & (N > 0) & (N <= N_RESOLUTION * scale)
        if not low.any():
            return None
        cap = np.where(low, 0.0, f_pt * N)
        rprob, _ = build_relaxation(self.system, self.cv.scaling, f_eff, lf, self.cv.pyramid,
                                    cap=cap)
        rres = self.cv.solve(rprob, "relaxation", tight=True)
        if rres.status != OPTIMAL:
            return None
        R0 = max(float(rres.z[rprob.cols["r"]][0]), 0.0)
        # a breach within the resolution is what removing caps of at most f x the
        # resolution does to any state near its threshold: only a larger one says the
        # state rests on those forces
        return R0 if R0 > N_RESOLUTION * scale else None

    def fixed_point(self, f: float, load_factor: float) -> FixedPoint:
        t0 = time.perf_counter()
        cv, sysm = self.cv, self.system
        c = sysm.contacts
        F = cv.scaling.force
        pj = c.point_joint
        fj = cv.f_joint(f)
        fin = np.isfinite(fj)
        mk = self.marked & fin
        f_eff = np.where(mk, 0.0, fj)
        f_pt = np.where(mk, fj, 0.0)[pj]
        t_pt = c.tensile_strength[pj] * c.point_areas / F
        nsl = sysm.layout.normal
        # the start: X0 with the no-tension law imposed (its least-energy state with the
        # normal links alone, whose plastic distortions are openings only), or X0's
        # normal forces with tension cleared when that has no solution
        x0, _ = self.solve_capped(np.full(c.n_joints, math.inf), load_factor,
                                   np.zeros(c.n_points))
        if x0 is None:
            x0 = self.elastic(load_factor)
            if x0 is None:
                return FixedPoint(INADMISSIBLE, np.full(sysm.layout.size, np.nan), 0, True,
                                  math.inf, "the equilibrium equations have no solution",
                                  time=time.perf_counter() - t0)
        N = np.maximum(x0[nsl], -t_pt)
        beta, best, since = self.damping, math.inf, 0
        past: list[np.ndarray] = []
        hist: list[float] = []
        x, R = x0, math.inf
        for k in range(1, self.max_iter + 1):
            x, R = self.solve_capped(f_eff, load_factor, f_pt * N)
            if x is None:
                return FixedPoint(INADMISSIBLE, np.full(sysm.layout.size, np.nan), k, True,
                                  math.inf, "the equilibrium equations have no solution",
                                  hist, time.perf_counter() - t0)
            scale = max(1.0, float(np.abs(x).max(initial=0.0)))
            Nn = np.maximum(x[nsl], -t_pt)  # a relaxed state's tension is not a cap
            change = float(np.abs(Nn - N).max(initial=0.0)) / scale
            hist.append(change)
            if change <= self.tol:
                if R <= ADMISSIBLE_TOL * scale:
                    R0 = self._unresolved_breach(f_eff, load_factor, f_pt, N, scale)
                    if R0 is not None:
                        return FixedPoint(UNDECIDED, x * F, k, True, R0 * F,
                                          f"{UNRESOLVED_N} below the solver's resolution "
                                          f"({N_RESOLUTION:g} of the largest force): with "
                                          f"them zero the joints breach their laws by "
                                          f"{R0 * F:.3g}; the state stands on round-off",
                                          hist, time.perf_counter() - t0)
                    return FixedPoint(ADMISSIBLE, x * F, k, True, 0.0,
                                      f"fixed point after {k} convex solves (change "
                                      f"{change:.2g})", hist, time.perf_counter() - t0)
                return FixedPoint(INADMISSIBLE, x * F, k, True, R * F,
                                  f"the iteration from the elastic state settles after {k} "
                                  f"solves on normal forces with which the joints cannot "
                                  f"carry the shear (breach {R * F:.3g})", hist,
                                  time.perf_counter() - t0)
            # damping: halved after STALL iterations without a new smallest change
            # (:func:`~rigidblocks.analyses.na_limit._damped`; it was after STALL rises
            # in a row, which an oscillation of period 14 never made: the inclined corbel
            # arch at f = 0.8 and lambda = 0.0106, undecided after 300 solves, stands
            # after 57), or when the iterate returns to one of the last few (a cycle)
            damped, best, since = _damped(beta, best, since, change)
            if damped == beta and beta > MIN_DAMPING and any(
                    float(np.abs(Nn - p).max()) <= 1e-3 * change * scale for p in past[:-1]):
                damped, since = 0.5 * beta, 0
            if damped != beta:
                beta = damped
                past.clear()
            past.append(Nn)
            if len(past) > 6:
                past.pop(0)
            N = N + beta * (Nn - N)
        return FixedPoint(UNDECIDED, x * F, self.max_iter, False, R * F,
                          f"no fixed point within {self.max_iter} convex solves (last "
                          f"relative change {hist[-1]:.3g}, damping {beta:g})", hist,
                          time.perf_counter() - t0)


class DistortionNonAssociative(NonAssociative):
    """The seed's distortion iteration with separate normal and shear links (2D)."""

    def __init__(self, inner: DistortionMethod, marked: np.ndarray):
        super().__init__(inner, marked)
        self.dm = inner

    def fixed_point(self, f: float, load_factor: float) -> FixedPoint:
        ds = self.dm.solver_
        laws = ds.laws(self.f_joint(f), nonassociative=self.marked)
        r = self.dm.run(laws, load_factor, optimal=True, keep_history=True)
        F = ds.scaling.force
        status, reason, settled = r.status, r.reason, r.status == ADMISSIBLE
        if status == ADMISSIBLE and reason.startswith(_UNSETTLED):
            status, settled = UNDECIDED, False
            reason = ("an admissible iterate, but the iteration did not settle on its "
                      "fixed point: " + reason)
        if status == ADMISSIBLE:
            reason = f"fixed point after {r.iterations} iterations"
        return FixedPoint(status, r.x * F, r.iterations, settled or status == INADMISSIBLE,
                          r.violation * F, reason, r.history, r.time)


def nonassociative_method(m: Method, marked: np.ndarray) -> NonAssociative:
    """The non-associative verdicts of an opened method."""
    if isinstance(m, ConvexMethod):
        return ConvexNonAssociative(m, marked)
    if isinstance(m, DistortionMethod):
        return DistortionNonAssociative(m, marked)
    raise InputError(f"method {m.name!r} has no non-associative analysis")


# -- the analyses -----------------------------------------------------------------------
def _open(scene: Scene, method: str, flow: str | None, **kw: Any
          ) -> tuple[NonAssociative, ConvexMethod]:
    """The non-associative method and a convex method for the static bounds."""
    from ..methods import open_method

    m = open_method(scene, method, **kw)
    na = nonassociative_method(m, flow_mask(scene, m.contacts, flow))
    cv = m if isinstance(m, ConvexMethod) else ConvexMethod(scene, m.system, m.timings)
    na.bounds_by = cv
    return na, cv


def _fields(na: NonAssociative, analysis: str, status: str, friction: Any,
            load_factor: float | None, history: tuple = (), converged: bool | None = None
            ) -> dict[str, Any]:
    path = getattr(na, "limit_path", False)
    first = WALK_NOTE if path == "walk" else LIMIT_NOTE if path else STATE_NOTE
    # (not where a bound decides, nor where no state stands at all: no other state
    # can give another answer)
    notes = [first] * (na.cause not in (BOUND_STANDS, STATIC_UNSTABLE)) + \
        [n for n in na.notes if n not in (STATE_NOTE, LIMIT_NOTE, WALK_NOTE)]
    return dict(analysis=analysis, status=status, friction=friction_label(friction),
                load_factor=load_factor, contacts=na.contacts, solver=na.solver,
                n_solves=na.n_solves, solve_time=na.solve_time, iterations=na.iterations,
                geometry=geometry_key(na.scene), loading=loading_keys(na.scene),
                units=(na.scene.length_unit, na.scene.force_unit), notes=tuple(notes),
                timings=dict(na.timings.wall), cpu_timings=dict(na.timings.cpu),
                flow=NON_ASSOCIATIVE, converged=converged, history=history,
                answered_by=na.answered_by, rejected=na.rejected, cause=na.cause,
                sliding_joints=(None if na.marked.all() else int(na.marked.sum())))


def _trial(kind: str, value: float, v: Verdict) -> dict[str, Any]:
    d = v.data
    return {kind: value, "status": v.status,
            "iterations": int(d.iterations) if d is not None else 0,
            "converged": bool(d.converged) if d is not None else False}


def check_nonassociative(scene: Scene, friction: Any = None, load_factor: float = 1.0,
                         method: str = "clarabel", *, flow: str | None = None,
                         state: bool = True, **kw: Any) -> CheckResult:
    """Is the state reached from the elastic state admissible under non-associative
    sliding? See the module docstring; the arguments are those of
    :func:`rigidblocks.analyses.check`. On the convex path an admissible state stands
    only where the limit fixed point from X0 (`load`'s answer) carries the load factor
    too (:func:`_loaded_from_x0`)."""
    f = friction_value(scene.effective_friction if friction is None else friction)
    lf = float(load_factor)
    na, cv = _open(scene, method, flow, **kw)
    res = _check(na, cv, f, lf, state)
    # (not in a study's bisection on verdicts, which asks for no state)
    return with_friction_governs(res, cv, f, lf) if res.status == INADMISSIBLE and state \
        else res


def _check(na: NonAssociative, cv: ConvexMethod, f: float, lf: float, state: bool
           ) -> CheckResult:
    """:func:`check_nonassociative` with its methods open."""
    _above_ceiling(na, f)
    static = cv.admissible(f, lf)
    if static.status == INADMISSIBLE:  # (undecided: the states from X0 may decide)
        na.notes.append("no admissible state exists at all (the associative, static "
                        "problem has none): inadmissible under either flow rule")
        na.cause = STATIC_UNSTABLE
        return CheckResult(**_fields(na, "check", INADMISSIBLE, f, lf, (), True),
                           admissible=False, violation=static.violation,
                           breaches=cv.breaches(f, static))
    v = na.admissible(f, lf)
    d = v.data
    # one trial, as those of load and friction, with the changes of its iterations
    trial = {**_trial("load_factor", lf, v), "friction": f,
             "changes": [float(c) for c in d.history] if d else []}
    na.explain(v)
    st = na.state(f, lf, v)
    status = v.status if v.status in (ADMISSIBLE, INADMISSIBLE, UNDECIDED) else FAILURE
    admissible, violation = v.admissible, 0.0 if v.status == ADMISSIBLE else v.violation
    if status == ADMISSIBLE and isinstance(na, ConvexNonAssociative) and \
            na.scene.has_live_load:
        before = na.fp_iterations
        status = _loaded_from_x0(na, cv, f, lf)
        trial["limit_steps"] = na.fp_iterations - before
        trial["limit_status"] = status
        if status != ADMISSIBLE:  # the state shown breaches nothing
            admissible, violation = (False if status == INADMISSIBLE else None), math.nan
    elif status == UNDECIDED and isinstance(na, ConvexNonAssociative) and \
            na.scene.has_live_load:
        before = na.fp_iterations
        status = _loaded_from_x0(na, cv, f, lf, direct=False)
        trial["limit_steps"] = na.fp_iterations - before
        trial["limit_status"] = status
        if status == INADMISSIBLE:  # (the state shown did not settle: no breach of its)
            admissible, violation = False, math.nan
    if (isinstance(na, ConvexNonAssociative) or status == UNDECIDED) and \
            na.scene.has_live_load:
        # a theorem decides where the iterations from X0 do not stand, and says more
        # where they do: it stands in every state, not only in the one from X0 (the
        # reference model with self-weight at 0.5, below its bound 0.6, read "another
        # state may collapse at a lower load"); on the distortion path, the seed's
        # procedure as it is, only where it decides nothing (seed Fig. 4a bonded in
        # tension alone at 0.5, below its capacity bound 1: UNDECIDED, as `load` was
        # beside the bounds that give its answer)
        lower = _bound_carries(na, cv, f, lf)
        shown = (v if v.status == ADMISSIBLE else _bound_state(cv, f, lf, static)) \
            if lower is not None else None
        if shown is not None:
            na.notes.append(f"{lower[1]} on every collapse state "
                            + ("at lambda >= 0 " if "capacity" in lower[1] else "")
                            + f"is {fmt_safe(lower[0], 7, False)} > {lf:.10g}: no "
                            "collapse state lies at or below this load, so it stands "
                            "whatever state it is in, that reached from X0 or another"
                            + ("" if shown is v else " (the state shown: an admissible one "
                               "of least complementary energy)"))
            if status != ADMISSIBLE:  # the bound's verdict, not the state's
                st = na.state(f, lf, shown)
                na.answer_is_bound()
            status, admissible, violation, na.cause = ADMISSIBLE, True, 0.0, BOUND_STANDS
    breaches = na.breaches(f, v) if status == INADMISSIBLE and v.status == INADMISSIBLE \
        else ()
    if breaches:
        # the state's own largest breach, as the joints list it (the capped relaxation's
        # measure, 0.0031 on the 3 x 3 wall at f = 0.8 and lambda = 0.76, read beside
        # joints breached by 0.0081)
        violation = breaches[0][1]
    return CheckResult(**_fields(na, "check", status, f, lf, (trial,),
                                 bool(d.converged) if d else None),
                       state=st if state else None, admissible=admissible,
                       violation=violation, breaches=breaches)


def _x0_limit_run(na: ConvexNonAssociative, cv: ConvexMethod, f: float
                  ) -> tuple[str, LimitRun | None]:
    """The limit iteration from the state reached from X0 under the dead load at ``f``
    (`load`'s answer, and each trial of `friction`): the verdict of that state, and the
    run (None where X0 has no such state)."""
    verdict, start = reached_normals(na, f)
    if start is None:
        return verdict, None
    capped = CappedLimit(cv, na.marked, f)
    (r,) = limit_runs(capped, [(FROM_X0, start)])
    na.fp_iterations += r.iterations
    return verdict, r


#: a limit fixed point within this (relative, and of the live load below 1) of the
#: associative multiplier, an upper bound on every state (Radenkovic), is it: the checks'
#: resolution (:func:`_limit_checks`), coarser than a mechanism's states solved by an
#: interior-point method (the reference model with one joint without dilatancy:
#: 1.199999975 for 1.2)
SAME_AS_ASSOCIATIVE = 1e-6


def _at_associative(lam: float, hi: float | None) -> bool:
    """Is the multiplier ``lam`` the associative one ``hi`` (:data:`SAME_AS_ASSOCIATIVE`)?"""
    return hi is not None and math.isfinite(hi) and \
        abs(lam - hi) <= SAME_AS_ASSOCIATIVE * max(abs(hi), 1.0)


def _as_load_reads(na: NonAssociative, cv: ConvexMethod, f: float, r: LimitRun,
                   lf: float) -> LimitRun:
    """The limit run from X0 ``r`` as `load` reads its answer (:func:`_x0_answer`): where
    it falls short of ``lf`` within :data:`SAME_AS_ASSOCIATIVE` and is the associative
    multiplier to that accuracy, at the associative multiplier (noted). `load` printed
    lambda* = 1.2 for the reference model with one joint without dilatancy (its fixed
    point 1.199999975), and `check` at 1.2 said NOT ADMISSIBLE ("collapses at lambda =
    1.199999 < 1.2"), `friction` at 1.2 "f = 0.6 is NOT enough"."""
    if r.lam is None or r.carries(lf) or \
            r.lam < lf - SAME_AS_ASSOCIATIVE * max(abs(lf), 1.0):
        return r
    seen = len(cv.notes)
    try:
        up = cv.load_limit(f, 1e-9)
    finally:
        del cv.notes[seen:]  # (the associative analysis' notes: not this answer's)
    hi = max(float(up.value), 0.0) if up.status == "collapse" else None
    if not _at_associative(r.lam, hi):
        return r
    na.notes.append(f"at f = {f:.10g} the limit fixed point from X0, {r.lam:.10g}, is the "
                    f"associative multiplier {hi:.10g} to {SAME_AS_ASSOCIATIVE:g}, an upper "
                    "bound on every state: it is read as that (as `load` reads it)")
    return replace(r, lam=hi)


def _loaded_from_x0(na: ConvexNonAssociative, cv: ConvexMethod, f: float,
                    lf: float, direct: bool = True) -> str:
    """The check's verdict where the state reached from X0 at the load factor ``lf`` is
    admissible: it stands where the limit iteration from X0 (`load`'s answer) carries
    ``lf`` too. The two ask different things of the same start (the state at ``lf``
    reached directly; the collapse state reached by the limit iteration), and without
    dilatancy they may disagree: the Arpino gate at f = 0.6 stands in the first at
    lambda = 0.12 while the second collapses at 0.1187021, the smallest multiplier of
    any state (`load --safe`). The check then says that it does not stand, as `load`
    and `friction` say.

    ``direct`` False: the state at ``lf`` reached directly did not settle; the verdict
    is then INADMISSIBLE where the limit iteration collapses below ``lf``, else
    UNDECIDED (the 6 x 6 wall at f = 2 and lambda = 0.6: no fixed point at 0.6 within
    300 solves, where `load` collapses from X0 at 0.5789473 < 0.6)."""
    with cv.runner.afresh():
        _, r = _x0_limit_run(na, cv, f)
    if r is None or r.status == "unbounded":
        return ADMISSIBLE if direct else UNDECIDED
    if not direct and (not r.converged or _limit_checks(cv, f, r, (None, None))):
        return UNDECIDED
    if not r.converged or _limit_checks(cv, f, r, (None, None)):
        if _by_states(cv):  # (as `load` reads it there)
            na.notes.append(f"{by_states_note(r.reason)}, and at lambda = {lf:.10g} the "
                            "state reached from X0 stands")
            return ADMISSIBLE
        na.notes.append("no limit fixed point from X0 (`load`'s answer) was found "
                        f"({r.reason}): whether loading from X0 reaches lambda = {lf:.10g} is "
                        "undecided")
        return UNDECIDED
    r = _as_load_reads(na, cv, f, r, lf)
    if not direct:
        if r.carries(lf):
            return UNDECIDED
        na.notes.append(f"loaded from X0 it collapses at lambda = {fmt_safe(r.lam, 7, False)} "
                        f"< {lf:.10g} (the limit fixed point from X0, `load`'s answer): it "
                        f"does not stand at lambda = {lf:.10g}, although the state reached "
                        "from X0 at this load directly did not settle")
        return INADMISSIBLE
    if r.carries(lf):
        na.notes.append(f"loaded from X0 it carries lambda = {fmt_safe(r.lam, 7, False)} "
                        f"{carried_text(r.lam, lf, r.carry_tol)} (`load`'s answer, the limit "
                        "fixed point from X0)")
        return ADMISSIBLE
    na.notes.append(f"loaded from X0 it collapses at lambda = {fmt_safe(r.lam, 7, False)} "
                    f"< {lf:.10g} (the limit fixed point from X0, `load`'s answer), though the "
                    f"state reached from X0 at lambda = {lf:.10g} directly is admissible (the "
                    "state shown)")
    na.cause = DIRECT_STANDS
    return INADMISSIBLE


def _bound_carries(na: NonAssociative, cv: ConvexMethod, f: float, lf: float
                   ) -> tuple[float, str] | None:
    """The lower bound on every collapse state at friction ``f`` (:func:`_lower_bound`;
    the capacity bound holds for those at lambda >= 0) and how the notes name it, where
    it lies above ``lf`` >= 0: no collapse state lies at or below ``lf``, so the structure
    stands there whatever state it is in (a theorem: Radenkovic's second), whichever
    state an iteration from X0 reaches. None elsewhere. The reference model with
    self-weight at lambda = 0.5, below its capacity bound 0.6: the state reached from X0
    stands, and `check` said "another state may collapse at a lower load", which the
    bound excludes."""
    if lf < 0:
        return None
    seen = len(cv.notes)
    tol = CARRY_TOL * max(abs(lf), 1.0)
    try:
        up = cv.load_limit(f, 1e-9)
        # (every lower bound lies at or below the associative multiplier: none of them
        # carries lf where that does not)
        if up.status != "collapse" or up.value <= lf + tol:
            return None
        lo, by = _lower_bound(cv, na.marked, f, max(float(up.value), 0.0))
    finally:
        del cv.notes[seen:]  # the bounds' own analyses: not this answer's notes
    # above lf, beyond the LPs' accuracy: a collapse state may lie at the bound itself
    # (the frictionless bound of a wall, 0, says nothing of its dead load)
    if lo is None or lo <= lf + tol:
        return None
    return lo, LOWER_WORDS[by]


def _bound_state(cv: ConvexMethod, f: float, lf: float, static: Verdict | None = None
                 ) -> Verdict | None:
    """An admissible state at ``lf`` (the least complementary energy one; statics is
    the same under either flow rule) as a verdict whose data is that state, where a
    bound, not a state reached from X0, says that the structure stands; ``static`` the
    convex method's verdict there, where it was solved already."""
    static = static or cv.admissible(f, lf)
    if static.status != ADMISSIBLE:
        return None
    return Verdict(ADMISSIBLE, 0.0, (), cv.state(f, lf, static))


def max_load_nonassociative(scene: Scene, friction: Any = None, method: str = "clarabel",
                            *, flow: str | None = None, state: bool = True,
                            rtol: float = NA_RTOL, mechanism: str = "vertex",
                            **kw: Any) -> LoadResult:
    """The collapse multiplier under non-associative sliding, from the elastic state.

    Convex path: the fixed point of the capped limit problem from X0
    (:func:`_load_by_limit`, :mod:`rigidblocks.analyses.na_limit`), with the answer
    from the associative collapse state beside it. Distortion path: bisection between
    0 and the associative multiplier on the verdicts of the state the seed's iteration
    reaches from X0 (:func:`_load_by_bisection`).

    ``load_multiplier_bounds`` = [lo, hi]: hi the associative multiplier (Radenkovic's
    first theorem), lo the associative multiplier with frictionless marked joints
    (Drucker 1954; None where it is not defined: the frictionless dead load has no
    admissible state): bounds on every state's multiplier, not on the answer's alone
    (which may equal hi while another state collapses below it: the reference model
    with self-weight, 2.4 and 0.6). ``mechanism``: "vertex" (default)
    or "blend", which of the optimal mechanisms of the computed state is drawn, as for
    associative friction (see :func:`_collapse_mechanism`).
    """
    check_live_load(scene)
    f = friction_value(scene.effective_friction if friction is None else friction)
    na, cv = _open(scene, method, flow, **kw)
    _above_ceiling(na, f)
    seen = len(cv.notes)
    up = cv.load_limit(f, 1e-9)
    _bound_notes(na, cv, seen, "lambda*", ASSOC_NOTE)
    # the associative multiplier, within round-off below 0 taken as 0 (as the
    # associative analysis reports it)
    hi = (up.value if up.value > 0 else 0.0) if up.status == "collapse" else None
    if up.status == "unbounded":
        na.notes.append("the associative multiplier is unbounded: no upper bound")
    lo, na.lower_by = _lower_bound(cv, na.marked, f, hi)
    bounds = (lo, math.inf if up.status == "unbounded" else hi)
    if isinstance(na, ConvexNonAssociative) and up.status in ("collapse", "unbounded"):
        by_states = None
        if up.status == "collapse" and _by_states(cv):
            def by_states(why: str) -> LoadResult:
                na.limit_path = False
                na.notes.append(by_states_note(why))
                return _load_by_bisection(na, cv, f, up, hi, lo, bounds, state, rtol,
                                          mechanism)
        res = _load_by_limit(na, cv, f, up, bounds, state, mechanism, by_states)
    else:
        res = _load_by_bisection(na, cv, f, up, hi, lo, bounds, state, rtol, mechanism)
    if res.load_multiplier_bounds is not None and res.load_multiplier_bounds[0] is not None:
        res = replace(res, lower_bound_by=na.lower_by)
    return with_friction_governs(res, cv, f, 0.0) if res.status == "unstable" else res


#: a computed lower bound less this (relative)
BOUND_MARGIN = 1e-10
#: how the notes name a lower bound (:func:`_lower_bound`)
LOWER_WORDS = {"frictionless": "the frictionless bound", "capacity": "the capacity bound",
               "no sliding": "the associative multiplier (no joint without dilatancy can "
                             "slide)"}


def _lower_bound(cv: ConvexMethod, marked: np.ndarray, f: float, hi: float | None
                 ) -> tuple[float | None, str]:
    """The best lower bound on the non-associative collapse multipliers at friction f
    below the associative one ``hi``, and what it is: the frictionless bound (every
    collapse state; Drucker 1954), or where it is higher the capacity bound (every
    collapse state at lambda >= 0; :func:`~rigidblocks.analyses.na_bounds.capacity_bound`,
    computed on 2D scenes of up to 50 joints): the Arpino gate's bracket at 0.6 was
    [-, 0.122798] ("none with the joints frictionless"), now [0.118702, 0.122798]. The
    inclined corbel arch's at f = 0.8 stays [-, 0.0212988]: the live load's mechanisms
    collapse at or above 0.0212988, but states the dead load drives collapse at 0.0128
    (:func:`~rigidblocks.analyses.na_capacity._capacity_bound`)."""
    from .na_capacity import capacity_bound  # (scipy's LPs: not at every check's start)

    if hi is not None and math.isfinite(hi) and not (marked & np.isfinite(cv.f_joint(f))).any():
        # infinite friction on every joint without dilatancy: a mechanism slides at none
        # of them, its openings follow the no-tension law's normality, and every
        # collapse state is an associative one, at hi (the kinematic theorem); the
        # frictionless bound said "none" on the arch (its frictionless joints do not
        # carry the dead load)
        return hi, "no sliding"
    lo = _frictionless_bound(cv, marked, f)
    cap = capacity_bound(cv, marked, f, lo, hi)
    if cap is None:
        return lo, "frictionless"
    # on the safe side of the states it bounds by more than round-off (the inclined
    # corbel arch's live-load bound at f = 0.9: 0.04144903032439328 above its answer, the
    # safe multiplier 0.04144903032439297), less than the printed figures resolve (ROUND_OFF: the
    # reference model's 0.6 read 0.599999 with 1e-9)
    return cap - BOUND_MARGIN * abs(cap), "capacity"


def _proven(bounds: tuple[float | None, float | None]) -> bool:
    """Is the lower bound of [lo, hi] above 0 (beyond the LPs' accuracy)? Then no
    collapse state lies between 0 and it, under the dead load either, whichever state an
    iteration from X0 reaches."""
    return bounds[0] is not None and bounds[0] > CARRY_TOL * max(abs(bounds[0]), 1.0)


def _closes(bounds: tuple[float | None, float | None]) -> bool:
    """Do the bounds [lo, hi] meet (to CARRY_TOL, the LPs' accuracy): every collapse
    state within them collapses at hi?"""
    lo, hi = bounds
    return lo is not None and hi is not None and math.isfinite(hi) and \
        lo >= hi - CARRY_TOL * max(abs(hi), 1.0)


def _equals_static(fs: float, rtol: float) -> str:
    """The note of a non-associative f* that is the static one, ``fs``: found by the
    static search to this search's bracket, finer than `friction` without --flow, whose
    f* is certified to ``rtol`` (the inclined corbel arch: 0.7651297008 here, 0.76536
    to 2e-3 there, read as two answers)."""
    return (f"the non-associative friction equals the static f* ({fs:.10g}; `friction` "
            f"without --flow gives it to the accuracy asked, {rtol:g})")


def _above_ceiling(na: NonAssociative, f: float) -> None:
    """The note of an analysis at a friction above NA_FRICTION_CEILING, or infinite."""
    if not na.marked.any() or f <= NA_FRICTION_CEILING:
        return
    na.notes.append(ABOVE_CEILING.format(f=f, share=f * N_RESOLUTION) if f < math.inf
                    else INFINITE_NOTE)


def _load_by_bisection(na: NonAssociative, cv: ConvexMethod, f: float, up: Any,
                       hi: float | None, lo: float | None,
                       bounds: tuple[float | None, float | None], state: bool, rtol: float,
                       mechanism: str) -> LoadResult:
    """The multiplier by bisection on the verdicts of the state reached from X0 (the
    distortion path, the seed's procedure) between 0 and ``hi`` (tried first)."""
    trials: list[dict[str, Any]] = []

    def result(status: str, lam: float | None = None, v: Verdict | None = None,
               converged: bool | None = None,
               bracket: tuple[float, float] | None = None) -> LoadResult:
        # bracket: the answer's (the state reached from X0); the bounds hold for every
        # state (Drucker 1954, Radenkovic): an admissible trial of this one raises no
        # bound, other states may collapse earlier (docs/safe-multiplier.md)
        st = na.state(f, lam, v) if (v is not None and lam is not None) else None
        mech, gov = _collapse_mechanism(cv, na, f, lam, st, mechanism) if st else (None, ())
        return LoadResult(**_fields(na, "max_load_multiplier", status, f, lam,
                                    tuple(trials), converged), state=st if state else None,
                          load_multiplier=lam, load_multiplier_bounds=bounds,
                          mechanism=mech, governing=gov,
                          bracket=bracket if bracket and bracket[0] < bracket[1] else None)

    if up.status == "unstable":
        na.notes.append("the dead load alone has no admissible state (static problem)")
        na.cause = STATIC_UNSTABLE
        return result("unstable", converged=True)

    def decide(lam: float) -> tuple[bool | None, Verdict]:
        v = na.admissible(f, lam)
        trials.append(_trial("load_factor", lam, v))
        if v.status == FAILURE:
            na.explain(v)
        return v.admissible, v

    def by_the_bounds(what: str) -> LoadResult | None:  # (see _by_the_bounds)
        if not _closes(bounds):
            return None
        na.notes.append(f"the state reached from X0 {what}")
        return _by_the_bounds(na, cv, f, up, bounds, tuple(trials), state)

    ok0, v0 = decide(0.0)
    if ok0 is not True and v0.status != FAILURE and \
            (ans := by_the_bounds("stands at no load factor tried from 0")) is not None:
        return ans
    if ok0 is not True:
        na.explain(v0)
        # a method that fails is a failure (exit 1), not an undecided search (3)
        return result("unstable" if ok0 is False else
                      FAILURE if v0.status == FAILURE else UNDECIDED, converged=ok0 is False)
    if hi is None:  # associative unbounded: bracket by doubling
        got = _double_up(na, decide, v0)
        if isinstance(got, str):
            return result(got, converged=got == "unbounded")
        good, bad, best = got
    else:
        top, v, at = _at_the_top(na, decide, hi, up)
        if at is not None:
            wide = _too_wide_at_the_top(na, at, rtol)
            return result(UNDECIDED if wide else "collapse", None if wide else top, v, True, at)
        good, bad, best = 0.0, top, v0
    br = bisect(decide, bad, good, rtol)
    best_v = br.good_data or best
    if br.undecided_at is not None:
        wide = br.too_wide(rtol, BRACKET_ATOL)
        if wide and (ans := by_the_bounds(
                f"did not settle at lambda = {br.undecided_at:.9g}: it brackets its "
                f"multiplier in {fmt_bracket(br.lower, br.upper, 9)} only")) is not None:
            return ans
        na.notes.append(f"the iteration did not settle at lambda = {br.undecided_at:.9g}: "
                        f"the multiplier is bracketed in {fmt_bracket(br.lower, br.upper, 9)}")
        if wide:
            return _undecided_bracket(na, f, br, trials, bounds, rtol)
    if lo is not None and br.good < lo * (1.0 - 1e-6):
        na.notes.append(_below_the_bound(na, br.good, lo))
        if (ans := by_the_bounds("gives none")) is not None:
            return ans
    # (converged False where a trial did not settle: the flow line said "converged"
    # beside the inclined corbel arch's at f = 0.8, its bracket decided by its width)
    return result("collapse", br.good, best_v, br.undecided_at is None,
                  (br.lower, br.upper))


def _below_the_bound(na: NonAssociative, lam: float, lo: float) -> str:
    """The note of a multiplier ``lam`` from X0 below the lower bound ``lo``."""
    return (f"the computed multiplier {lam:.6g} is below {LOWER_WORDS[na.lower_by]} "
            f"{lo:.6g}, a lower bound on every collapse state: the state reached from the "
            "elastic state is not one")


def _double_up(na: NonAssociative, decide: Any, v0: Verdict
               ) -> tuple[float, float, Verdict] | str:
    """An unbounded associative multiplier: the state reached from X0 tried at 1, 2,
    4, ...; (the last load it stands at, the first it does not, the verdict there) or
    what ends the search (FAILURE, UNDECIDED, or "unbounded" past UNBOUNDED_AT)."""
    good, bad, best = 0.0, 1.0, v0
    while True:
        ok, v = decide(bad)
        if ok is None:
            na.explain(v)
            return FAILURE if v.status == FAILURE else UNDECIDED
        if ok is False:
            return good, bad, best
        good, best = bad, v
        bad *= 2
        if bad > UNBOUNDED_AT:
            return "unbounded"


def _undecided_bracket(na: NonAssociative, f: float, br: Any, trials: list[dict[str, Any]],
                       bounds: tuple[float | None, float | None], rtol: float) -> LoadResult:
    """The bisection stopped by a trial that did not settle, its bracket wider than
    ``rtol`` asks: no number, the bracket and why."""
    na.notes.append(_too_wide_note(br, rtol))
    return LoadResult(**_fields(na, "max_load_multiplier", UNDECIDED, f, None,
                                tuple(trials), bool(trials[-1]["converged"])),
                      load_multiplier_bounds=bounds, bracket=(br.lower, br.upper))


def _at_the_top(na: NonAssociative, decide: Any, hi: float, up: Any
                ) -> tuple[float, Any, tuple[float, float] | None]:
    """The bisection's first trials: the associative multiplier ``hi`` (an upper bound:
    where the state reached from X0 stands there, it is the answer), then just below
    it. The last trial's load factor and verdict, and the answer's bracket where it
    stood (None where not): at ``hi`` itself the associative multiplier's own, as no
    state lies above its upper end (the Arpino gate by the distortion method had no
    accuracy line)."""
    for top in (hi, hi * (1.0 - TOP_RTOL)):
        ok, v = decide(top)
        if ok is True:
            if top == hi:
                na.answer_is_bound()
            na.notes.append("the non-associative multiplier equals the associative one "
                            "(the state reached from X0 stands at it)" if top == hi else
                            f"the non-associative multiplier is within {TOP_RTOL:g} "
                            f"(relative) below the associative one, {hi:.9g}")
            up_end = up.upper if top == hi and up.upper is not None else hi
            return top, v, (top, max(up_end, hi))
    return top, v, None


def _too_wide_at_the_top(na: NonAssociative, at: tuple[float, float], rtol: float) -> bool:
    """Is the bracket ``at`` of an answer at the associative multiplier (that
    multiplier's own) wider than ``rtol`` asks (:func:`~rigidblocks.results.within`, as
    the associative answer is held to it)? Said in the notes where it is: the 4 x 4 wall
    at --rtol 1e-9 gave 0.6 from a bracket 3.8e-9 wide, "decided by ... the absolute
    floor for answers near 0", where the associative `load` said UNDECIDED."""
    if within(*at, rtol, BRACKET_ATOL):
        return False
    na.notes.append(no_number_note("lambda*, the associative multiplier,", *at,
                                   relative_width(*at), rtol))
    return True


def _too_wide_note(br: Any, rtol: float) -> str:
    """Why a bisection stopped by an undecided trial gives no number (as
    :func:`~rigidblocks.analyses.core.certified` says it of every other limit)."""
    return (f"accuracy {relative_width(br.lower, br.upper):.1e} reached, {rtol:.1e} "
            "requested (rtol): undecided, no number")


def _starts(na: ConvexNonAssociative, cv: ConvexMethod, up: Any, f: float
            ) -> tuple[str, list[tuple[str, np.ndarray]]]:
    """The verdict under the dead load of the state reached from X0 (see
    :func:`~rigidblocks.analyses.na_limit.reached_normals`), and the starts of the limit
    iteration (scaled normal forces): that state (the seed's start, the answer's, where
    it stands) and the associative collapse state."""
    out = []
    verdict, n0 = reached_normals(na, f)
    if n0 is not None:
        out.append((FROM_X0, n0))
    if up.status == "collapse" and up.at is not None and up.at.data is not None:
        res, prob = up.at.data
        xa = cv.lscaling.forces(res.z[prob.cols["x"]])
        out.append((FROM_ASSOC, np.maximum(xa[cv.system.layout.normal], 0.0)
                    / cv.scaling.force))
    return verdict, out


def _limit_checks(cv: ConvexMethod, f: float, run: LimitRun,
                  bounds: tuple[float | None, float | None], by: str = "frictionless"
                  ) -> list[str]:
    """What the fixed point ``run`` fails of its a-posteriori checks (empty: none):
    equilibrium to CERT_TOL of its largest force (or block load), Coulomb's law with
    its own normal forces to CERT_TOL plus f times the distance of those forces from
    the caps it was solved under (:attr:`~rigidblocks.analyses.na_limit.LimitRun.
    resolution`: a plain fixed point's last change; the corbel dome's cone runs end
    3e-6 of its largest force from their caps), lo <= lambda <= hi (Drucker 1954; Radenkovic's
    first theorem; ``by`` says what lo is, :data:`LOWER_WORDS`)."""
    lam, x = run.lam, run.x * cv.scaling.force
    eq, breach = certificate(cv, f, lam, x)
    fj = cv.f_joint(f)
    fmax = float(fj[np.isfinite(fj)].max(initial=0.0))
    bad = []
    if eq > CERT_TOL or breach > CERT_TOL + fmax * run.resolution:
        bad.append(f"the fixed point fails its check: equilibrium residual {eq:.2g}, "
                   f"breach of Coulomb's law with its own normal forces {breach:.2g} "
                   f"(of the largest force or block load; its normal forces settled to "
                   f"{run.resolution:.2g})")
    lo, hi = bounds
    slack = 1e-6 * max(abs(lam), 1.0)
    if hi is not None and lam > hi + slack:
        bad.append(f"lambda = {lam:.9g} is above the associative multiplier {hi:.9g}")
    if lo is not None and lam < lo - slack and (lam >= 0 or by == "frictionless"):
        # (the capacity bound holds for the collapse states at lambda >= 0)
        bad.append(f"lambda = {lam:.9g} is below {LOWER_WORDS[by]} {lo:.9g}")
    return bad


def _load_by_limit(na: ConvexNonAssociative, cv: ConvexMethod, f: float, up: Any,
                   bounds: tuple[float | None, float | None], state: bool,
                   mechanism: str, by_states: Any = None) -> LoadResult:
    """The non-associative collapse multiplier as the fixed point of the capped limit
    problem (:mod:`rigidblocks.analyses.na_limit`) from X0, with the answer from the
    associative collapse state beside it; ``by_states(why)`` the answer where the run from
    X0 stops and no bound decides (:func:`_by_states`), else undecided."""
    na.limit_path = "walk" if walks(cv) else True
    capped = CappedLimit(cv, na.marked, f)
    # afresh, as the friction's trials run (:func:`_limit_oracle`): the run from X0 at f
    # is the same computation in both, whatever the solves before learnt
    with cv.runner.afresh():
        verdict, starts = _starts(na, cv, up, f)
        runs = limit_runs(capped, starts)
    # the iterations are the limit steps of the runs, as each start's history gives them
    na.fp_iterations += sum(r.iterations for r in runs)
    trials = tuple({"start": r.start, "load_factor": r.lam, "status": r.status,
                    "iterations": r.iterations, "converged": r.converged,
                    "span": None if r.span is None else list(r.span),
                    "least_confined": r.least_confined, "reason": r.reason,
                    "carry_tol": r.carry_tol}
                   for r in runs)
    proven = _proven(bounds)
    if verdict == INADMISSIBLE:
        if all(r.start != FROM_X0 for r in runs):  # the starts line names it too
            trials = ({"start": FROM_X0, "load_factor": None, "status": "unstable",
                       "iterations": 0, "converged": True, "reason": DEAD_LOAD_BREACH},
                      ) + trials
        if proven:
            na.notes.append(f"{DEAD_LOAD_BREACH}, but no collapse state lies below "
                            f"{LOWER_WORDS[na.lower_by]}: it stands under the dead load in "
                            "another state")
            return _by_the_bounds(na, cv, f, up, bounds, trials, state)
        na.notes.append(f"{DEAD_LOAD_BREACH}{_breached_at(na, f)}: it does not stand" +
                        (f"; from the associative collapse state: lambda = "
                         f"{fmt_safe(runs[0].lam, 7, False)}"
                         if runs and runs[0].converged else ""))
        return LoadResult(**_fields(na, "max_load_multiplier", "unstable", f, None, trials,
                                    True), load_multiplier_bounds=bounds)
    if verdict == UNDECIDED:
        na.notes.append("the state reached from X0 under the dead load did not settle: the "
                        "limit iteration starts from X0's normal forces")
    main = runs[0] if runs else None
    if main is not None and main.status == "unbounded" and up.status == "unbounded" \
            and not (na.marked & np.isfinite(cv.f_joint(f))).any():
        # no joint of non-associative flow can slide: the capped problem is the
        # associative one, whose multiplier is unbounded
        na.notes.append("no joint of non-associative flow can slide (infinite friction): "
                        "the flow plays no part, and the multiplier is the associative "
                        "one, unbounded")
        return LoadResult(**_fields(na, "max_load_multiplier", "unbounded", f, None, trials,
                                    True), load_multiplier_bounds=bounds)
    settled = main is not None and main.converged
    bad = ["the elastic state X0 has no solution"] if main is None else \
        [f"from {main.start}: {main.reason}"] if not settled else \
        _limit_checks(cv, f, main, bounds, na.lower_by)
    if bad:
        if by_states is not None and not proven:
            return by_states(main.reason if main is not None and not settled
                             else "; ".join(bad))
        na.notes.extend(bad)
        if proven:
            return _by_the_bounds(na, cv, f, up, bounds, trials, state)
        na.notes.extend(_elsewhere(cv))
        return LoadResult(**_fields(na, "max_load_multiplier", UNDECIDED, f, None, trials,
                                    settled), load_multiplier_bounds=bounds)
    return _x0_answer(na, cv, f, up, main, bounds, trials, state, mechanism)


def _breached_at(na: NonAssociative, f: float, first: int = 5) -> str:
    """Where the state reached from X0 under the dead load breaches the joint laws: the
    joints, largest breach first (`load` said only that it breaches, on an 8 x 8 wall
    with an opening, where `check --load-factor 0` names c5b4-c6b4 and more)."""
    f0, r = na.dead_load  # (the verdict this follows read it: `reached_normals`)
    assert f0 == f
    ranked = na.breaches(f, Verdict(r.status, r.violation, (), r))
    if not ranked:
        return ""
    ids, pairs = na.contacts.block_ids, na.contacts.pairs
    names = [f"{ids[pairs[k, 0]]}-{ids[pairs[k, 1]]}" for k, _ in ranked[:first]]
    more = f" and {len(ranked) - first} more" if len(ranked) > first else ""
    unit = na.scene.force_unit or "force units"
    return (f" (at {', '.join(names)}{more}; by up to {ranked[0][1]:.3g} {unit})")


def _by_states(cv: ConvexMethod) -> bool:
    """Where the limit iteration from X0 stops (its capped laws carry nothing after a
    few steps) and no bound decides, are `load`, `check` and `friction` read off the
    state reached from X0 at each load factor, as the distortion method reads the
    seed's procedure? On 2D scenes of up to MAX_JOINTS joints, where those runs are
    cheap. The inclined corbel arch at f = 0.77 and 0.8: 0.00186212 and 0.0127922,
    where the least collapse state over all states (`--safe`) lies, 0.00186212 and
    0.0127927; at 0.85 and 0.87: 0.0489 and 0.0567 (the distortion method 0.0490 and
    0.0568)."""
    from .na_capacity import MAX_JOINTS

    c = cv.contacts
    return c.dimension == 2 and c.n_joints <= MAX_JOINTS


#: the note of an answer read off the states reached from X0 (:func:`_by_states`),
#: after why no limit fixed point from X0 was found
BY_STATES = ("on this small scene the answer is read off the state reached from X0 at "
             "each load factor, by bisection, as the distortion method reads the seed's "
             "procedure")


def by_states_note(why: str) -> str:
    """The note of an answer read off the states reached from X0, with ``why`` the
    no limit fixed point from X0 was found (the inclined corbel arch at f = 0.8 said
    "from the elastic state X0: the capped laws carry not even the dead load" on a line
    of its own, just above the positive answer those states give)."""
    return f"no limit fixed point from X0 was found ({why}): {BY_STATES}"


def _elsewhere(cv: ConvexMethod) -> list[str]:
    """Where `load` is undecided from X0 with no lower bound on a 2D scene too large to
    be read off the states reached from X0 (:func:`_by_states`): the seed's procedure,
    which answers there by its own iteration."""
    return ["`--method distortion` follows the seed's procedure from X0"] \
        if cv.contacts.dimension == 2 else []


def _x0_answer(na: ConvexNonAssociative, cv: ConvexMethod, f: float, up: Any,
               main: LimitRun, bounds: tuple[float | None, float | None], trials: tuple,
               state: bool, mechanism: str) -> LoadResult:
    """`load`'s answer from the limit run from X0 ``main``, converged and checked: its
    multiplier, or the bounds' where it lies below 0 and a lower bound above 0 holds
    (:func:`_by_the_bounds`), or UNSTABLE where it lies below 0 and none does."""
    proven = _proven(bounds)
    na.notes.append(SPREAD_NOTE + starts_text(trials))
    lam = float(main.lam)
    if proven and lam < -main.carry_tol:
        # a collapse state below the dead load (a reversed live load), not on the path
        # from 0, where a lower bound above 0 holds for every state at lambda >= 0
        na.notes.append(f"the limit fixed point from X0 lies at lambda = "
                        f"{fmt_safe(lam, 7, False)} < 0, under a reversed live load; no "
                        f"collapse state lies between 0 and {LOWER_WORDS[na.lower_by]}")
        return _by_the_bounds(na, cv, f, up, bounds, trials, state)
    if lam < -main.carry_tol:
        # as `check` at the dead load says (:func:`_loaded_from_x0`): not a collapse
        # multiplier, the dead load alone collapses it (where no lower bound above 0
        # says otherwise)
        na.notes.append(f"loaded from X0 it collapses at lambda = {fmt_safe(lam, 7, False)} "
                        "< 0: the limit fixed point from X0 does not carry even the dead "
                        "load")
        na.cause = BELOW_DEAD_LOAD
        return LoadResult(**_fields(na, "max_load_multiplier", "unstable", f, None, trials,
                                    True), load_multiplier_bounds=bounds)
    hi = bounds[1]
    if _at_associative(lam, hi):
        # the associative multiplier is an upper bound on every state (Radenkovic): a
        # fixed point within the checks' 1e-6 of it (an interior-point value) is it
        na.notes.append(f"the non-associative multiplier equals the associative one (the "
                        f"fixed point's {lam:.10g} is {abs(lam - hi):.1e} from it)")
        lam = float(hi)
    elif na.lower_by == "capacity" and abs(lam - bounds[0]) <= 1e-6 * max(abs(lam), 1.0):
        # (the Arpino gate at f = 0.6: 0.118702 from X0, its capacity bound too)
        na.notes.append(f"the answer from X0 meets the capacity bound {bounds[0]:.9g}: no "
                        "collapse state at lambda >= 0 carries less (it is the safe "
                        "multiplier, the least over all states)")
    st = force_state(cv.system, main.x * cv.scaling.force,
                     "non-associative collapse state reached from the elastic state")
    mech, gov = _collapse_mechanism(cv, na, f, lam, st, mechanism)
    return LoadResult(**_fields(na, "max_load_multiplier", "collapse", f, lam, trials, True),
                      state=st if state else None, load_multiplier=lam,
                      load_multiplier_bounds=bounds, mechanism=mech, governing=gov)


def _by_the_bounds(na: NonAssociative, cv: ConvexMethod, f: float, up: Any,
                   bounds: tuple[float | None, float | None], trials: tuple, state: bool
                   ) -> LoadResult:
    """The answer where the limit iteration from X0 (or the distortion path's
    bisection: fig4a without cohesion read UNDECIDED in [0, 0.999999] beside its
    bounds [1, 1]) gives none in [0, hi] but a lower
    bound lo > 0 holds (:func:`_lower_bound`): where the bounds meet (:func:`_closes`)
    every collapse state at lambda >= 0 lies at the associative multiplier hi, beyond
    which no state is admissible, and that is the answer whatever the state (shown: the
    associative collapse state's, and its mechanism); else the answer lies in [lo, hi],
    undecided. (The inclined corbel arch at f = 0.8, where from either start the capped
    laws of the next step carry nothing, was answered so while the capacity bound
    counted the live load's mechanisms alone: 0.0212988, where a state the dead load
    drives collapses at 0.0128.)"""
    lo, hi = bounds
    word = LOWER_WORDS[na.lower_by]
    if not _closes(bounds):
        na.notes.append(f"{word} and the associative multiplier bracket the answer: "
                        f"[{lo:.9g}, {hi:.9g}]")
        return LoadResult(**_fields(na, "max_load_multiplier", UNDECIDED, f, None, trials,
                                    False), load_multiplier_bounds=bounds,
                          bracket=(float(lo), float(hi)))
    hi = float(hi)
    na.answer_is_bound()
    na.notes.append(f"{word} meets the associative multiplier: every collapse state "
                    + ("" if na.lower_by == "frictionless" else "at lambda >= 0 ")
                    + f"collapses at lambda_a = {hi:.9g}, whichever state it is in, and "
                    "beyond it no state is admissible whatever the flow rule; the state "
                    "and mechanism shown are the associative collapse state's (its sliding "
                    "joints dilate)")
    res, prob = up.at.data
    st = force_state(cv.system, cv.lscaling.forces(res.z[prob.cols["x"]]),
                     "associative collapse state (the bounds meet)")
    # (converged: False, the runs did not; the bounds answer)
    return LoadResult(**_fields(na, "max_load_multiplier", "collapse", f, hi, trials, False),
                      state=st if state else None, load_multiplier=hi,
                      load_multiplier_bounds=bounds, mechanism=up.mechanism,
                      governing=tuple(up.governing))


@dataclass(frozen=True)
class StartAnswer:
    """One start's answer as the history gives it (:func:`compare_starts`)."""

    start: str
    #: its multiplier; None where its run did not converge
    lam: float | None
    status: str
    reason: str
    #: the multipliers of its mechanism's lowest and highest collapse states, where they
    #: differ (more than SAME_ANSWER); None otherwise
    span: tuple[float, float] | None
    #: its mechanism has one collapse state
    one_state: bool
    #: its mechanism is the first start's (the same range)
    same_mechanism: bool
    #: its states are the least confined that carry their multiplier (the iteration's
    #: fixed points); False: states that carry the largest multiplier under the caps of
    #: their own normal forces (:data:`~rigidblocks.analyses.na_mechanism.LOOSE_STATES`)
    least_confined: bool = True


#: two multipliers within this (relative) are one answer, and a mechanism's range that
#: narrow one state; within the runs' own accuracy where it is coarser (Coulomb's
#: cones: 1e-5, where box_stack_3d's 0.3079191 and 0.3079195 "differed")
SAME_ANSWER = 1e-6


def start_entries(history: Any) -> list[dict[str, Any]]:
    """The entries of a result's history that are runs of the limit iteration (one per
    start, with a ``start``)."""
    return [h for h in (history or ()) if isinstance(h, dict) and "start" in h]


def compare_starts(history: Any) -> tuple[list[StartAnswer], tuple[float, float] | None]:
    """The answer from every start of the limit iteration (:func:`start_entries`) and
    the spread of their multipliers where they differ (None where they agree, or fewer
    than two converged): what the report's note and a terminal's ``starts`` line say."""
    entries = start_entries(history)
    # one answer to the accuracy of the runs' multipliers (Coulomb's cones: 1e-5)
    same = max([SAME_ANSWER] + [float(h.get("carry_tol") or 0.0) for h in entries])

    def apart(lo: float, hi: float) -> bool:
        # relative, and beyond the fixed points' own check (FIXED_TOL of the live load
        # below 1): the inclined corbel arch at its static f* = 0.7651297008, where the
        # associative multiplier is 9.5e-12, read "the answers differ: [1.186472e-10,
        # 4.197021e-08] (the answer is X0's)" beside the answer lambda* = 0; the 20 x 15
        # wall's 0.4374230 and 0.4374235 (1e-6 relative) differ
        return hi - lo > max(same * max(abs(lo), abs(hi)), FIXED_TOL)

    out: list[StartAnswer] = []
    for k, h in enumerate(entries):
        lam = h.get("load_factor") if h.get("converged") else None
        span = h.get("span")
        wide = span is not None and apart(span[0], span[1])
        out.append(StartAnswer(
            h["start"], lam, h.get("status", "-"), h.get("reason", ""),
            (float(span[0]), float(span[1])) if wide else None,
            span is not None and not wide,
            k > 0 and lam is not None and out[0].lam is not None and span is not None
            and span == entries[0].get("span"), h.get("least_confined", True)))
    lams = [a.lam for a in out if a.lam is not None]
    spread = ((min(lams), max(lams)) if len(lams) > 1
              and apart(min(lams), max(lams)) else None)
    return out, spread


def collapse_state_at(res: Any) -> float | None:
    """The multiplier of the collapse state the answer ``res`` rests on, checked (the
    limit iteration's state from X0, converged: a ``load`` whose history has starts)
    under the linear laws of 2D; None otherwise (a bisection's value, an associative
    answer, Coulomb's cones)."""
    starts = start_entries(getattr(res, "history", None))
    if getattr(res, "status", None) != "collapse" or not starts \
            or not starts[0].get("converged") or res.contacts.dimension != 2:
        return None
    return float(starts[0]["load_factor"])


def starts_text(history: Any) -> str:
    """The answer from every start, the multipliers the collapse states of the mechanism
    each reached carry (where they were computed), and whether the answers differ
    (:func:`compare_starts`): the report's note (after :data:`SPREAD_NOTE`) and a
    terminal's ``starts`` line. Each multiplier is printed to 7 figures on the safe side
    (:func:`~rigidblocks.results.fmt_safe`): the 6 x 5 wall's 0.5789473684 as 0.5789473,
    at which a check stands, not 0.5789474."""
    def lam(x: float) -> str:
        return fmt_safe(x, 7, False)

    def one(a: StartAnswer) -> str:
        if a.lam is None:
            return f"{a.status} ({a.reason})" if a.reason else a.status
        text = f"lambda = {lam(a.lam)}"
        loose = "" if a.least_confined else \
            " optimal under their own caps, not least confined,"
        if a.same_mechanism:
            return text + " (the same mechanism)"
        if a.span is not None:
            return text + f" (its mechanism's states{loose} [{lam(a.span[0])}, " \
                f"{lam(a.span[1])}])"
        if a.one_state:
            return text + " (its mechanism's one state" + \
                ("" if a.least_confined else ", optimal under its own caps, not least "
                 "confined") + ")"
        return text

    answers, spread = compare_starts(history)
    text = "; ".join(f"from {a.start}: {one(a)}" for a in answers)
    if spread is not None:
        text += f"; the answers differ: [{lam(spread[0])}, {lam(spread[1])}] (the " \
            "answer is X0's)"
    elif sum(a.lam is not None for a in answers) > 1:
        text += "; the same answer"
    return text


def _collapse_mechanism(cv: ConvexMethod, na: NonAssociative, f: float, lam: float,
                        st: ForceState, kind: str = "vertex") -> tuple[Any, tuple[int, ...]]:
    """The mechanism of the computed state: max lambda under the cohesion-only laws
    |T| <= f N* of its normal forces N* (one LP); its duals are block velocities whose
    marked joints slide without dilatancy. It is the collapse mechanism when that LP's
    multiplier equals the computed one (to 1e-3 and BRACKET_ATOL): otherwise a note says
    so, and None.

    ``kind``: "vertex" picks one mechanism of that LP's optimal face (one that can be
    drawn, :func:`~rigidblocks.methods.vertex.vertex_dual`), "blend" keeps the
    interior-point duals (a mix of every optimal mechanism), as the associative
    analysis does."""
    from ..equilibrium import mechanism

    c = cv.contacts
    pj = c.point_joint
    fj = cv.f_joint(f)
    mk = na.marked & np.isfinite(fj)
    f_eff = np.where(mk, 0.0, fj)
    cap = np.where(mk, fj, 0.0)[pj] * np.maximum(st.normal, 0.0) / cv.scaling.force
    prob, _ = build_max_load(cv.system, cv.scaling, f_eff, cv.pyramid, cap=cap)
    res = cv.solve(prob, "maximum load (capped laws)", tight=True, stall=False)
    if res.status != OPTIMAL:
        return None, ()
    lam_cap = float(res.z[prob.cols["lambda"]][0])
    # to 1e-3, or to the answers' absolute floor near 0 (the inclined corbel arch at its
    # static f*, lambda* = 0: its state's caps give 5.5e-7, its collapse mechanism)
    if abs(lam_cap - lam) > 1e-3 * abs(lam) + BRACKET_ATOL:
        na.notes.append("no collapse mechanism is given: the computed state is not a "
                        "collapse state of its own caps (with its normal forces as fixed "
                        f"shear capacities f N the multiplier is {lam_cap:.6g}, not "
                        f"{fmt_safe(lam, 6, False)})")
        return None, ()
    y_eq, got = cv.mechanism_duals(prob, res, lam_cap, kind, "the capped laws' multiplier")
    na.notes.extend(n for n in cv.notes if n.startswith(("mechanism:", OFF_FACE_NOTE))
                    and n not in na.notes)
    mech = mechanism(cv.system, cv.scaling.row, y_eq, got,
                     res.z[prob.cols["x"]] * cv.scaling.force)
    sliding = tuple(k for k, md in enumerate(mech.modes) if md.startswith("slide"))
    return mech, sliding


def _frictionless_bound(cv: ConvexMethod, marked: np.ndarray, f: float) -> float | None:
    """The associative multiplier with the marked joints frictionless (cohesion kept):
    a lower bound on any non-associative collapse multiplier (Drucker 1954)."""
    fj = np.where(marked, 0.0, cv.f_joint(f))
    prob, _ = build_max_load(cv.system, cv.scaling, fj, cv.pyramid)
    res = cv.solve(prob, "maximum load (frictionless bound)", tight=True, stall=False)
    if res.status != OPTIMAL:
        return None
    lam = float(res.z[prob.cols["lambda"]][0])
    if lam < -ADMISSIBLE_TOL:
        return None
    rprob, _ = build_relaxation(cv.system, cv.scaling, fj, 0.0, cv.pyramid)
    rres = cv.solve(rprob, "relaxation", tight=True)
    if rres.status != OPTIMAL:
        return None
    x = rres.z[rprob.cols["x"]]
    if float(rres.z[rprob.cols["r"]][0]) > ADMISSIBLE_TOL * max(1.0, float(np.abs(x).max())):
        return None
    return lam if lam > ADMISSIBLE_TOL else 0.0  # round-off of a zero bound


def _same(breach: list[tuple[float, float]]) -> bool:
    """Do the breaches (f, R) of the trials agree (to 1e-3 relative): R independent
    of f?"""
    r = [b for _, b in breach]
    return math.isfinite(max(r)) and max(r) - min(r) <= 1e-3 * max(abs(max(r)), 1e-300)


def _no_friction_note(breach: list[tuple[float, float]], fs: float) -> str:
    """Why no friction makes the state reached from the elastic state stand, from the
    breaches of the trials (f, R) of the upward search."""
    (f0, r0), (f1, r1) = breach[0], breach[-1]
    text = (f"no friction up to {NA_FRICTION_CEILING:g} (above it f times the solver's "
            f"resolution of the normal forces reaches the loads) makes the state reached "
            f"from the elastic state stand: it breaches the joint laws by {r0:.4g} at f = {f0:.6g} "
            f"and by {r1:.4g} at f = {f1:.6g}")
    if _same(breach):
        text += (" (the breach does not depend on f: the joints that must carry the shear "
                 "have no normal force in that state, as the loads cause none there, so "
                 "their capacity f N is zero whatever f)")
    return text + (f". The static f* = {fs:.6g} admits a state only with a normal force "
                   "the loads do not cause (a pinch, a prestress) or with a slip that "
                   "opens the joint (dilatancy): without either the structure does not "
                   "stand, at any finite friction")


def min_friction_nonassociative(scene: Scene, load_factor: float = 1.0,
                                method: str = "clarabel", *, flow: str | None = None,
                                state: bool = True, rtol: float = NA_RTOL,
                                **kw: Any) -> FrictionResult:
    """The smallest uniform f at which the non-associative analysis finds the structure
    standing at ``load_factor`` (the seed's "friction needed"), upwards from the static
    f* (below which no state is admissible at all): on the convex path with a live
    load, the least f whose limit fixed point from X0 carries it
    (:func:`_friction_by_limit`); else by bisection on the verdicts of the state
    reached from X0 (:func:`_friction_by_verdicts`)."""
    import math as _m

    lf = float(load_factor)
    na, cv = _open(scene, method, flow, **kw)
    if na.contacts.n_joints and not na.uniform.any():
        raise InputError("every joint has its own friction override: there is no uniform "
                         "friction to minimise", scene.source)
    trials: list[dict[str, Any]] = []
    # the static f* as the associative analysis gives it (same accuracy, same solves):
    # where the answer equals it, the two print the same number
    lim = cv.friction_limit(lf, min(VERDICT_RTOL, rtol))

    def out(status: str, fstar: float | None = None, v: Verdict | None = None,
            lower: float | None = None, upper: float | None = None,
            converged: bool | None = None) -> FrictionResult:
        st = na.state(fstar, lf, v) if (v is not None and fstar is not None) else None
        gov: tuple[int, ...] = ()
        if st is not None and fstar is not None and fstar > 0:
            fj = na.f_joint(fstar)
            at = (np.abs(st.joint_shear) >= (1 - 1e-5) * fj * st.joint_normal) \
                & (st.joint_normal > 1e-9 * max(1.0, float(np.abs(st.joint_normal).max())))
            gov = tuple(int(k) for k in np.flatnonzero(at & na.uniform))
        bracket = (lower, upper) if (lower is not None and upper is not None
                                     and (status == UNDECIDED or lower < upper)) else None
        return FrictionResult(**_fields(na, "min_friction", status, fstar, lf,
                                        tuple(trials), converged), bracket=bracket,
                              state=st if state else None, governing=gov, friction_factor=fstar,
                              friction_angle_deg=(_m.degrees(_m.atan(fstar))
                                                  if fstar is not None else None),
                              lower=lower, upper=upper)

    if lim.status != "stable":
        # the static f* bounds the non-associative one from below: without it, nothing
        na.notes.append("no friction admits an equilibrium state (static problem)"
                        if lim.status == "unstable" else
                        "the static f*, below which no state stands, was not found "
                        f"({lim.status}): the search starts there")
        na.cause = STATIC_UNSTABLE if lim.status == "unstable" else ""
        return out("unstable" if lim.status == "unstable" else lim.status, converged=True)
    # without dilatancy f* does not say whether the scene's own friction suffices
    # (lambda(f) need not grow with f): that friction is tried as well
    fsc = scene.effective_friction
    own = float(fsc) if not isinstance(fsc, str) and 0 < float(fsc) < _m.inf else None
    if own is not None and own < (lim.lower if lim.lower is not None else lim.value):
        own = None  # below the static f* no state stands at all: nothing to try
    if isinstance(na, ConvexNonAssociative) and scene.has_live_load and lf >= 0:
        # as `check` judges a load factor (:func:`_loaded_from_x0`), at lambda = 0 too:
        # judged by the state reached from X0 alone, the segmental arch's f* for its
        # dead load was 0.18274331, where `check` is undecided (loaded from X0, the
        # capped laws carry nothing at a step), now 0.182948, where it stands. The
        # limit runs start from that state: at lambda = 0, where it stands at no
        # friction, its own search says why (the breach that no f changes)
        if lf == 0:
            seen = len(na.notes)
            first = _friction_by_verdicts(na, lf, lim, rtol, out, trials, own)
            if first.status != "stable":
                return first
            del na.notes[seen:]
            trials.clear()
        return _friction_by_limit(na, cv, lf, lim, rtol, out, trials, own)
    # without a live load there is no limit to iterate: the state reached from X0
    # answers
    return _friction_by_verdicts(na, lf, lim, rtol, out, trials, own)


def _also_at(own: float | None, trials: list[dict[str, Any]], probe: Any) -> None:
    """Try the scene's own friction ``own`` (by ``probe``, which records its trial)
    unless a trial was made there."""
    if own is not None and all(t.get("friction") != own for t in trials):
        probe(own)


def _friction_by_verdicts(na: NonAssociative, lf: float, lim: Any, rtol: float, out: Any,
                          trials: list[dict[str, Any]], own: float | None = None
                          ) -> FrictionResult:
    """The smallest f at which the state reached from X0 stands at ``lf``: bisection
    upwards from the static f* (``lim``) on the verdicts (the distortion path, and the
    convex path without a live load). ``out``, ``trials`` and ``own`` as in
    :func:`_friction_by_limit`."""
    fs = float(lim.value)

    def decide(fv: float) -> tuple[bool | None, Verdict]:
        v = na.admissible(fv, lf)
        trials.append(_trial("friction", fv, v))
        return v.admissible, v

    # the static f* first (a lower bound: where the state reached from the elastic
    # state stands there, it is the answer, in the static f*'s bracket), then rtol above
    first = fs
    for first in (fs, fs * (1.0 + rtol)) if fs > 0 else (0.0,):
        low = lim.lower if first == fs and lim.lower is not None else fs
        ok, v = decide(first)
        if ok is True:
            if first == fs:
                na.answer_is_bound()
            na.notes.append(_equals_static(fs, rtol) if first == fs else
                            f"the non-associative friction is within {rtol:g} (relative) "
                            f"above the static f* = {fs:.9g}")
            _also_at(own, trials, decide)
            return out("stable", first, v, low, first, True)
    bad, good, best = first, max(2.0 * fs, 1e-3), None
    breach = [(first, v.violation)] if ok is False else []
    unsettled: list[float] = []
    while True:
        ok, v = decide(good)
        if ok is True:
            best = v
            break
        if ok is False:
            bad = good
            breach.append((good, v.violation))
            unsettled = []
        elif (v.notes and v.notes[0].startswith(UNRESOLVED_N) and len(breach) > 1
              and _same(breach + [(good, v.violation)])):
            # the state stands only on unresolved normal forces, and with them zero it
            # breaches the laws by what every trial below did at every f: the same state
            bad = good
            breach.append((good, v.violation))
        elif v.status == FAILURE:
            na.explain(v)
            return out(FAILURE, lower=bad, converged=False)
        else:
            unsettled.append(good)
            why = v.notes[0] if v.notes else "the iteration did not settle"
            if why.startswith(UNRESOLVED_N) or len(unsettled) >= UNDECIDED_RUN:
                # larger f only raises the caps f N on the same normal forces: the
                # search cannot certify anything further up
                at = ", ".join(f"{u:.6g}" for u in unsettled)
                na.notes.append(f"undecided at f = {at} ({why}); f = {bad:.9g} is not "
                                "enough (inadmissible): the non-associative friction, if "
                                "any, lies above it and is not resolved")
                return out(UNDECIDED, lower=bad, converged=False)
        good *= 2.0
        if good > NA_FRICTION_CEILING:
            if bad < good / 2:
                na.notes.append(f"no friction up to {NA_FRICTION_CEILING:g} is found "
                                "standing")
                return out(UNDECIDED, lower=bad, converged=False)
            na.notes.append(_no_friction_note(breach, fs))
            return out("unstable", converged=True)
    br = bisect(decide, bad, good, rtol)
    best = br.good_data or best
    if br.undecided_at is not None:
        na.notes.append(f"the iteration did not settle at f = {br.undecided_at:.9g}: the "
                        f"friction is bracketed in {fmt_bracket(br.lower, br.upper, 9)}")
        if br.too_wide(rtol, BRACKET_ATOL):
            na.notes.append(_too_wide_note(br, rtol))
            return out(UNDECIDED, lower=br.lower, upper=br.upper, converged=False)
    _also_at(own, trials, decide)
    return out("stable", br.good, best, br.lower, br.upper, True)


def _limit_oracle(na: ConvexNonAssociative, cv: ConvexMethod, lf: float,
                  trials: list[dict[str, Any]]) -> Any:
    """The trial of :func:`_friction_by_limit` at a friction fv: the limit iteration from
    the start `load` takes at fv (the state reached from X0 under the dead load), which
    carries ``lf`` or not (None: undecided), its record appended to ``trials``."""
    def oracle(fv: float) -> Trial:
        # each trial as `load` at fv would run it: not under what the solves before it
        # learnt about the solver's reach on their own problems
        with cv.runner.afresh():
            return trial(fv)

    def trial(fv: float) -> Trial:
        verdict, r = _x0_limit_run(na, cv, fv)
        if r is None:
            decided = verdict == INADMISSIBLE  # else X0 itself has no solution
            why = (DEAD_LOAD_BREACH if decided else "the elastic state X0 has no solution")
            trials.append({"friction": fv, "load_factor": None,
                           "status": "unstable" if decided else UNDECIDED,
                           "iterations": 0, "converged": decided})
            return Trial(fv, False if decided else None,
                         data=Verdict(INADMISSIBLE if decided else UNDECIDED,
                                      notes=(why,)), why=why)
        rec = {"friction": fv, "load_factor": r.lam, "status": r.status,
               "iterations": r.iterations, "converged": r.converged,
               "carry_tol": r.carry_tol}
        trials.append(rec)
        v = _verdict(r, cv.scaling.force)
        if r.status == "unbounded":
            return Trial(fv, True, data=v)
        if not r.converged or _limit_checks(cv, fv, r, (None, None)):
            # the lower bound on every collapse state may carry lf (as `check` judges
            # it): a theorem, where the run gives nothing
            by_bound = _trial_by_the_bound(na, cv, fv, lf, rec)
            if by_bound is not None:
                return by_bound
            if _by_states(cv):  # (as `load` reads it there)
                direct = na.admissible(fv, lf)
                rec["carries"] = direct.admissible
                rec["by_states"] = True
                return Trial(fv, direct.admissible, data=direct,
                             why={True: "", False: "the state reached from X0 at this load "
                                  "breaches the joint laws"}.get(
                                      direct.admissible, "the state reached from X0 did not "
                                      "settle"))
            # (a run whose capped laws carry nothing at a step proves nothing of the
            # structure: the inclined corbel arch's at its static f* for lambda = 0.063
            # counted as "does not carry", a verdict no state supports)
            return Trial(fv, None, data=v, why=r.reason or r.status)
        # whether it carries lf, to the accuracy of its multiplier
        r = _as_load_reads(na, cv, fv, r, lf)
        rec["load_factor"] = r.lam
        rec["carries"] = r.carries(lf)
        if not rec["carries"]:  # (the theorem, as `check` judges it)
            by_bound = _trial_by_the_bound(na, cv, fv, lf, rec)
            if by_bound is not None:
                return by_bound
        return Trial(fv, rec["carries"], value=r.lam - lf, data=v)

    return oracle


def _trial_by_the_bound(na: ConvexNonAssociative, cv: ConvexMethod, fv: float, lf: float,
                        rec: dict[str, Any]) -> Any:
    """A trial of the friction search decided by the lower bound on every collapse state
    at ``fv`` (:func:`_bound_carries`), as `check` decides it: it carries ``lf`` (its
    state an admissible one, :func:`_bound_state`), its record ``rec`` saying so; None
    where the bound does not decide it."""
    lower = _bound_carries(na, cv, fv, lf)
    st = _bound_state(cv, fv, lf) if lower is not None else None
    if st is None:
        return None
    rec["carries"] = True
    rec["by_bound"] = lower[0]
    return Trial(fv, True, value=lower[0] - lf, data=st)


def _friction_by_limit(na: ConvexNonAssociative, cv: ConvexMethod, lf: float, lim: Any,
                       rtol: float, out: Any, trials: list[dict[str, Any]],
                       own: float | None = None) -> FrictionResult:
    """The smallest f whose limit fixed point from X0 (:func:`_load_by_limit`'s answer)
    carries ``load_factor``: the search engine between the static f* (no state at all
    below it) and the first of 2 f*, 4 f*, ... that carries it, stepping by the secant
    of lambda(f) - load_factor (:func:`_secant`, :func:`_across`) where it can, else
    halving. ``out`` builds the result (as :func:`min_friction_nonassociative` does)
    from the ``trials``, appended to here; the scene's own friction ``own`` is tried too
    where the search did not (whether it suffices is not read from f*)."""
    na.limit_path = "walk" if walks(cv) else True
    fs = float(lim.value)
    oracle = _limit_oracle(na, cv, lf, trials)

    # (an absolute floor too: where f* is 0 a relative bracket is never narrow; the flat
    # arch on fixed abutments, radial joints, halved [0, 6.2e-64] to its trial budget)
    s = Search(fs, fs, rtol, FRICTION_ATOL)
    t = _at_the_static(s, oracle)
    if t.side:
        _also_at(own, trials, oracle)
        if t.x > fs:
            na.notes.append(_across_f_star(s, lf, trials))
            return out("stable", t.x, t.data, fs, t.x, True)
        na.notes.append(_equals_static(fs, rtol))
        na.notes.extend(_past_the_brink(s, oracle))
        return out("stable", fs, t.data, lim.lower if lim.lower is not None else fs, fs,
                   True)
    good = max(2.0 * fs, 1e-3)
    if own is not None and own > fs:
        # the scene's own friction first: where it carries the load, f* is sought below
        # it (lambda(f) need not grow with f: above the static f* the first f that
        # carries it, doubling, can lie above one that does)
        t = oracle(own)
        s.record(t)
        if t.side:
            good = own
        elif t.side is False:
            good = max(good, 2.0 * own)
    # doubling up to the ceiling, which is tried too (the 6 x 6 wall at load factor 0.6
    # stopped at 5.26 and answered "no friction up to 10")
    good = min(good, max(NA_FRICTION_CEILING, fs))
    while not t.side:
        t = oracle(good)
        s.record(t)
        if t.side is None:
            na.notes.append(f"the limit iteration did not settle at f = {good:.6g} "
                            f"({t.why})")
            return out(UNDECIDED, lower=s.bad, converged=False)
        if t.side:
            break
        if good >= NA_FRICTION_CEILING:
            na.notes.extend([f"no friction tried up to {NA_FRICTION_CEILING:g} carries the "
                             "load at the limit fixed point reached from X0",
                             *_flat_below(trials, found=False)])
            return out("unstable", converged=True)
        good = min(2.0 * good, NA_FRICTION_CEILING)
    run(s, oracle, (undecided_band, narrow_enough),
        (beside_the_undecided, _across, _secant, midpoint))
    if not s.narrow():
        at = ", ".join(f"{t.x:.9g}" for t in s.trials if t.side is None)
        why = f"the limit iteration did not settle at f = {at}" if at else \
            f"the search ended after {len(s.trials)} trials"
        na.notes.append(f"{why}: bracket [{s.lower:.9g}, {s.upper:.9g}] wider than {rtol:g}")
        return out(UNDECIDED, lower=s.lower, upper=s.upper, converged=False)
    at = s.end(True)
    _also_at(own, trials, oracle)
    na.notes.append(_across_f_star(s, lf, trials))
    na.notes.extend(_flat_below(trials))
    na.notes.extend(_undecided_below(s))
    return out("stable", s.good, at.data, s.lower, s.upper, True)


def _at_the_static(s: Any, oracle: Any) -> Any:
    """The trial at the static f* (``s.good``), recorded in ``s``; where it decides
    nothing, the one just above it within a tenth of the accuracy asked, where a bound
    may decide (the non-associative f* is the static one where the bounds meet the
    associative multiplier above it)."""
    fs = s.good
    t = oracle(fs)
    s.record(t)
    if t.side is None:
        t = oracle(fs + 0.1 * (s.rtol * fs + s.atol))
        s.record(t)
    return t


def _past_the_brink(s: Any, oracle: Any) -> list[str]:
    """Where the non-associative f* is the static one (``s.good``), the brink at which
    a single state is admissible, a trial just above it (the accuracy asked): where
    that does not carry the load, the least friction above it that does (doubling the
    step, then bisection to the same accuracy), in a note: a margin above f* need not
    carry it. The inclined corbel arch under its dead load: f* = 0.7651297008,
    and from X0 it collapses below the dead load at 0.7652 to 0.76666, stands again
    from about 0.767."""
    fs = s.good
    step = s.rtol * fs + s.atol
    t = oracle(fs + step)
    if t.side is not False:
        return []
    above = Search(t.x, math.inf, s.rtol, s.atol, [t])
    stuck = None  # a friction whose run decided nothing, where the doubling stopped
    while above.good == math.inf:
        x = fs + 2.0 * (above.bad - fs)
        if x > NA_FRICTION_CEILING:
            break
        u = oracle(x)
        if u.side is None:
            stuck = x
            break
        above.record(u)
    first = (f"f* = {fs:.10g} is the static f*, the brink at which a single state is "
             f"admissible: just above it, at f = {t.x:.6g}, the state reached from X0 does "
             "not carry the load")
    if above.good == math.inf:
        return [f"{first}, nor at any friction tried up to {above.bad:.6g}"
                + (f" (at {stuck:.6g} the run decides nothing)" if stuck else "")
                + ": a margin above f* need not make it stand"]
    run(above, oracle, (undecided_band, narrow_enough), (beside_the_undecided, midpoint))
    if not above.narrow():
        return [f"{first}; it carries it at f = {above.good:.6g}, and between the two "
                "the runs decide nothing"]
    return [f"{first}, and carries it again at f = {above.good:.6g} (from not carrying to "
            f"carrying between {above.lower:.6g} and {above.upper:.6g}, to the accuracy "
            "asked): a margin above f* need not make it stand"]


def _undecided_below(s: Any) -> list[str]:
    """A note where runs from X0 below f*'s bracket decided nothing: lambda(f) need not
    grow with f, and a smaller f may carry the load there (the inclined corbel arch
    under lambda = 0.063: at the static f* 0.86894 and just above it the capped laws
    carry nothing, and f* is 1.02342, past a run at 0.9777 that carries 0.0555)."""
    low = [t for t in s.trials if t.side is None and t.x < s.lower]
    if not low:
        return []
    why = low[0].why
    return [f"below f* the runs from X0 at f = {', '.join(f'{t.x:.6g}' for t in low)} "
            f"decided nothing{f' ({why})' if why else ''}: a smaller friction may carry "
            "the load in the state reached from X0"]


def _across_f_star(s: Any, lf: float, trials: list[dict[str, Any]]) -> str:
    """What the limit fixed point from X0 carries at the two ends of f*'s bracket, f to
    the last digit (repr): the answer from X0 is not unique and moves with f at
    round-off (the 10 x 10 wall at load factor 0.5: 0.500014578 at f* =
    0.5346341035199138, 0.500001342 at 0.534634104), so that `load --friction` at the
    printed f gives the printed lambda."""
    at, below = s.end(True), s.end(False)
    rec = next(t for t in reversed(trials) if t.get("friction") == s.good)
    if below is None:  # the static f*, where the run decided nothing
        why = next((t.why for t in s.trials if t.x == s.bad and t.why), "")
        short = ("the static f*: no equilibrium state lies below it (the run from X0 "
                 f"decides nothing there{': ' + why if why else ''})")
    else:
        short = f"it carries {below.value + lf:.9g}" if math.isfinite(below.value) else \
            (below.why or "it does not carry it")
    # (a trial the bound decides: the run from X0 may have given no answer or one
    # below lf, and the state shown is an admissible one, not the one reached from X0)
    carried = (f"the lower bound on every collapse state at lambda >= 0 is "
               f"{rec['by_bound']:.9g} > {lf:.10g}: it stands whatever state it is in"
               if "by_bound" in rec else
               f"the state reached from X0 at lambda = {lf:.10g} stands (the limit run "
               "from X0 stops there; read off that state, as `load` does)"
               if rec.get("by_states") else
               f"the limit fixed point from X0 carries lambda = {at.value + lf:.9g} "
               f"{carried_text(at.value + lf, lf, rec['carry_tol'])}"
               if math.isfinite(at.value) else
               "loaded from X0 it does not collapse: no multiplier of the live load makes "
               "the capped problem collapse")
    return f"at f = {s.good:.10g} {carried}; at f = {s.bad:.10g} {short}"


def _flat_below(trials: list[dict[str, Any]], found: bool = True) -> list[str]:
    """A note where the trials that do not carry the load all carry one multiplier:
    lambda(f) is flat below f* (``found``; else up to the search's ceiling), which is
    where another mechanism takes over (the 6 x 5 wall at load factor 0.590526: 0.578947
    from f = 0.6 to 266.2, then 0.77 from forces at the solver's resolution: with the
    ceiling of 10, none found)."""
    short = [t for t in trials if t.get("carries") is False and t["load_factor"] is not None]
    lams = [t["load_factor"] for t in short]
    if len(short) < 3 or max(lams) - min(lams) > 1e-6 * abs(max(lams)):
        return []
    fs = [t["friction"] for t in short]
    return [f"{'below f* ' if found else ''}the limit fixed point from X0 carries lambda = "
            f"{fmt_safe(lams[0], 7, False)} at "
            f"every f tried from {min(fs):.6g} to {max(fs):.6g} ({len(short)} trials): "
            "there it does not grow with f" + (", and f* is where another mechanism takes "
                                               "over" if found else "")]


def _secant(s: Any) -> float | None:
    """The root of the secant of lambda(f) - load_factor through the bracket's ends,
    kept inside its middle 98 %; None (halve) where an end has no value, the last two
    trials landed on one side (the secant then creeps), or the last was a step across
    (:func:`_across`) that did not cross: lambda(f) is not the line the secant assumed
    (the wall3d 3 x 3 out of plane at load factor 0.5, its hinging multiplier: lambda(f)
    = 0.5 to round-off from f = 2.4 on, where each secant landed beside the good end and
    each step across on the same side, 200 trials creeping from 2.4 to 1.64)."""
    g, b = s.end(True), s.end(False)
    if g is None or b is None or not (math.isfinite(g.value) and math.isfinite(b.value)):
        return None
    last = s.trials[-2:]
    if len(last) == 2 and last[1].side is last[0].side and \
            (last[0].rule, last[1].rule) in (("_secant", "_secant"), ("_secant", "_across")):
        return None
    if g.value == b.value:
        return None
    x = g.x - g.value * (g.x - b.x) / (g.value - b.value)
    lo, hi = s.lower + 0.01 * s.width, s.upper - 0.01 * s.width
    return min(max(x, lo), hi)


def _across(s: Any) -> float | None:
    """After a secant step whose root, by the secant through it and the bracket's other
    end, lies within the requested accuracy: a point a third of that accuracy past it
    towards the other end, where the bracket closes in two trials."""
    t = s.last
    if t is None or t.rule != "_secant" or t.side is None:
        return None
    o = s.end(not t.side)
    if o is not None and math.isfinite(o.value) and math.isfinite(t.value) \
            and o.value != t.value:
        # the root by the secant through this trial and the other end: step across
        # only where it lies within the requested accuracy (else another secant step)
        root = t.x - t.value * (t.x - o.x) / (t.value - o.value)
        if abs(root - t.x) > s.rtol * abs(t.x):
            return None
    other = s.bad if t.side else s.good
    x = t.x + math.copysign(s.rtol * abs(t.x) / 3.0, other - t.x)
    return x if s.lower < x < s.upper else None


def _verdict(r: LimitRun, force: float) -> Verdict:
    """A limit run as a verdict whose data the result reads the state from (``force``
    the reference force of the run's scaled forces)."""
    fp = FixedPoint(ADMISSIBLE if r.converged else UNDECIDED,
                    np.full(0, np.nan) if r.x is None else r.x * force, r.iterations,
                    r.converged,
                    0.0, r.reason, [c for _, c in r.history], r.time)
    return Verdict(fp.status, 0.0, (r.reason,) if r.reason else (), fp)


__all__ = ["ConvexNonAssociative", "DistortionNonAssociative", "FixedPoint",
           "NonAssociative", "SPREAD_NOTE", "STATE_NOTE", "StartAnswer",
           "check_nonassociative", "collapse_state_at", "compare_starts", "flow_mask",
           "is_nonassociative", "max_load_nonassociative", "min_friction_nonassociative",
           "nonassociative_method", "start_entries", "starts_text"]
