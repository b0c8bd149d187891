"""The non-associative collapse states of one mechanism, and the end of the limit
iteration at them (2D).

A non-associative collapse state (:mod:`rigidblocks.analyses.na_limit`) is a fixed
point: with the marked joints' shear capped by the state's own normal forces,
|T| <= f N, the state carries the largest multiplier of the capped problem (phase 1:
max lambda) and is the least confined of the states that carry it (phase 2: min sum N
on phase 1's optimal face). In 2D both phases are linear programs whose constraint
matrices do not depend on the caps (the caps are right-hand sides), so a dual solution
of each stays dual feasible whatever the caps. Given one dual vertex of each (the
mechanism: the block velocities and the rows they hold active), a state x is a fixed
point exactly when

* it is in equilibrium, with every joint law met under the caps of its own normal
  forces: K x <= b0 with K = A - f M E (E picks the normal forces, M puts them in the
  friction rows);
* every row with a non-zero dual in either phase is active: K_i x = b0_i
  (complementary slackness: x is optimal in both phases at its own caps).

These are linear conditions: the collapse states of one mechanism form a polytope, in
general more than a point, so that the multiplier of a non-associative collapse state
is not unique even for one mechanism. Linear programs give its range (min and max
lambda over the polytope); a least-squares problem gives the state of the polytope
nearest the iterate that reached the mechanism, the answer "reached" from the start.

The limit iteration (:meth:`~rigidblocks.analyses.na_limit.CappedLimit.run`) follows its
path from the start as before; after each of its limit solves (phase 1, HiGHS's dual
simplex warm-started, :mod:`rigidblocks.solvers.highs_warm`) the rows phase 1 holds
active are read, and where they have settled (they change by at most ``SETTLED`` of
their number between steps) phase 2 is solved at the same caps and the polytope of the
mechanism of the two phases' rows is sought; where it is not empty its state nearest the
iterate ends the run, checked by solving both phases again at its own caps. The
iteration by itself approaches such a state at the rate of its contraction (hundreds of
steps on walls of hundreds of blocks, not settling in 500 on 1,000); the mechanism
settles within tens.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import SolverFailure
from ..methods.convex import ConvexMethod
from ..solvers import FAILURE, INFEASIBLE, OPTIMAL
from ..solvers.base import ConicProblem
from ..solvers.highs_warm import nonzero, warm_lp
from .na_limit import DUAL_ZERO, CappedLimit, LimitRun, hold_rows

#: an interior-point dual below this fraction of the largest is zero (the solver's
#: duals of rows that do not hold are about its gap over their slack, 1e-10 and less)
CONE_DUAL_ZERO = 1e-6
#: least-squares steps after a walk without collapse states from which a mechanism
#: whose polytope is empty is sought with phase 1's rows alone (:meth:`Mechanisms.states`):
#: the 1,041-block wall at f = 0.8 reached no polytope of both phases' rows with states in
#: 200 limit solves from either start (54 attempts, all empty), and ends at states of
#: phase 1's rows after 118 and 88; the 10 x 10 wall at f = 0.956 from X0 reaches one of
#: both phases' rows 13 least-squares steps after its walk (one state, 0.5428571), where
#: phase 1's rows alone would give at once states from 0.5286624 to 0.6068579
LOOSE_AFTER = 20
#: the mechanism's polytope is sought once its active rows change by at most this
#: fraction of their number between two steps
SETTLED = 0.02
#: least-squares steps of the limit iteration after which it goes on by vertex steps
#: (:meth:`Mechanisms.walk`): each least-squares step costs a QP (0.8 s on the
#: 1,041-block wall, 0.16 s on the 311-block one) and the path can cycle on a face (the
#: 311-block wall at f = 0.8 from the associative state); a vertex step costs two warm
#: LPs. With 20 the 1,041-block wall at f = 0.6 took 91 s (38 QPs), with 5 45 s (8),
#: the 311-block one 7.4 s and 3.6 s; the answers move within their mechanisms' ranges
PATH_STEPS = 5
#: vertex steps of one walk: those that reach a mechanism with states take 2 to 36 (the
#: walls from 6 x 4 to 32 x 32 at f = 0.6 and 0.8, from both starts); one that reaches
#: none costs two warm LPs a step (2 s at 1,041 blocks: the 32 x 32 wall at f = 0.8
#: took 442 s with 100, 344 s with 50)
WALK_STEPS = 50
#: vertex steps after which a walk whose mechanism has not once settled ends: the walks
#: that reached a mechanism with states first settled within 11 (the walls from 8 x 5 to
#: 32 x 32 at f = 0.6, 0.8 and 0.956, both starts), while those that never settle
#: wander (the 32 x 32 wall at f = 0.8 from X0: 137 to 405 of its 2,900 rows change at
#: every step of a 50-step walk, where 57 settle; each step two warm LPs, 2.5 s)
UNSETTLED_WALK = 20
#: ... and, sooner, after WANDER_STEPS vertex steps none of which changed fewer than
#: WANDER of the rows. The walks that settled had a step below 6 % of them by their
#: 14th: the walls from 8 x 5 to 32 x 32 at f = 0.6, 0.8 and 0.956, both starts, and the
#: 20 x 15 wall at f = 0.8 walking from the associative state itself (no least-squares
#: step first: 7.6 % at its 10th step, 3.1 % at its 13th, settled at its 14th); those
#: that never did had none below 6.8 % (the 10 x 10 wall at f = 0.956 from X0; the
#: 32 x 32 wall at f = 0.8: 7.0 % and 8.8 % by the 15th step from its two starts, each
#: step 1.5 to 2 s). The run goes on by least-squares steps either way, but the
#: warm-started solvers' bases differ after fewer vertex steps, and with them the
#: vertices chosen later
WANDER_STEPS = 15
WANDER = 0.06
#: the nearest state within this (relative) of the mechanism's lowest or highest
#: multiplier is that state: the iterate is itself that far from a fixed point when the
#: mechanism settles (the reference model: 1.199994 and 2.399991, the vertices 1.2 and
#: 2.4 that the iteration approaches)
SNAP = 1e-5
#: what collapse states sought with phase 1's rows alone are, and how a run's reason
#: names them
LOOSE_STATES = ("states that carry the largest multiplier under the caps of their own "
                "normal forces, not the least confined")
LOOSE = f" (with the maximum-load problem's rows alone: {LOOSE_STATES})"
#: simplex iterations of a warm phase-2 solve before it is solved from scratch
#: (:class:`~rigidblocks.solvers.highs_warm.WarmLp`; 3,000 for phase 1): its face's rows
#: change from step to step, and a warm start far from its answer runs long before the
#: IPM solve (the 1,041-block wall at f = 0.6, whole processes in turn, three pairs:
#: 0.928 of the CPU time with 3,000, the same answers; 1,000 for phase 1 too was no
#: faster, 44.2 s against 42.5 s)
PHASE2_WARM_LIMIT = 1000
#: ... and the solve after one given up goes to IPM at once: phase 2's warm solves are
#: given up in runs (36 of the 1,041-block wall's 60 at f = 0.8). Whole processes in
#: turn: 0.908-0.974 of the CPU time on the walls 10 x 10 at f = 0.8, 20 x 15 and
#: 32 x 32 at f = 0.6 and 0.8 (175.0 s against 189.7 s on the last), the same answers
#: from X0. After further give-ups in a row, twice as many solves go to IPM at once each
#: time: on the 1,041-block wall at f = 0.8 the walks' warm phase-2 solves that follow
#: an IPM one are given up every time (1,000 iterations, 0.9 s, then IPM 0.45 s); whole
#: `load` processes in turn, two pairs: 0.971 of the CPU time (110.3 s against
#: 113.6 s), the same answers
PHASE2_COLD_AFTER_GIVE_UP = True
#: the answer passes its check where, at its own caps, phase 1's multiplier and
#: phase 2's total normal force are its own to this (relative)
FIXED_TOL = 1e-7
#: the same for Coulomb's cones, solved by the interior-point method, whose duals give a
#: mechanism's rows only to CONE_DUAL_ZERO: a state of its polytope is a fixed point to
#: a few 1e-6. With FIXED_TOL the states of the 491-block wall3d in plane at f = 0.6
#: failed their checks by 8.4e-7 to 1.5e-6 (0.437426419 at their own caps, not
#: 0.437426051), and its runs ended as plain fixed points after 30 and 36 limit solves;
#: with 1e-6, at the states of a mechanism after 16 and 31, X0's answer 0.4374261 in
#: [0.4373490, 0.4374477] (the 2D wall's 0.4374252 in [0.4373650, 0.4374597]), in 0.739
#: of the CPU time (whole processes in turn, two pairs: 121-131 s against 167-176 s).
#: The 1,041-block one's state failed 1e-6 by 2.6e-6 (0.411038056 at its own caps, not
#: 0.411036983) and its run from X0 stalled (stopped after 55 least-squares steps);
#: with 1e-5, 0.4110370 at states of its mechanism, [0.4108544, 0.4110587], after 42
#: (the 2D wall's 0.4110464 in [0.4110464, 0.4110589])
CONE_FIXED_TOL = 1e-5


class Mechanisms:
    """The mechanisms of the capped problem ``capped`` (a linear program: 2D, its
    solver a :class:`~rigidblocks.solvers.highs_warm.WarmLp`, whose last answer is
    phase 1's) and the collapse states of each."""

    #: does a walk go on past a settled mechanism that gave no collapse state before?
    walk_past_failures = True
    #: the relative tolerance of :meth:`check`
    fixed_tol = FIXED_TOL
    #: does a walk that wanders end after WANDER_STEPS (:meth:`walk`)?
    wander = True

    def __init__(self, capped: CappedLimit):
        import scipy.sparse as sp

        p = capped.prob
        self.capped, self.cv = capped, capped.cv
        ne, ni = p.n_eq, p.n_nonneg
        self.ne, self.ni = ne, ni
        self.li = p.cols["lambda"].start
        self.rows = np.arange(ne, ne + ni)
        #: the mechanisms (their packed rows) whose polytopes were found empty
        self.empty: set[bytes] = set()
        self._make_phase2()
        nsl = capped.nsl
        m = nsl.stop - nsl.start
        E = sp.csr_matrix((np.ones(m), (np.arange(m), np.arange(nsl.start, nsl.stop))),
                          shape=(capped.P, p.n))
        MF = sp.vstack([sp.csr_matrix((ne, capped.P)),
                        capped.M @ sp.diags(capped.f_pt)]).tocsr()
        self.K = (p.A.tocsr() - MF @ E).tocsr()

    def _make_phase2(self) -> None:
        """Phase 2's LP (min sum N; phase 1's is the capped problem's own model)."""
        p, ne, ni = self.capped.prob, self.ne, self.ni
        c2 = np.zeros(p.n)
        c2[self.capped.nsl] = 1.0
        self.phase2 = warm_lp(c2, p.A, np.concatenate([p.b[:ne], np.full(ni, -math.inf)]),
                              p.b[:ne + ni])
        self.phase2.limit = PHASE2_WARM_LIMIT
        self.phase2.cold_after_give_up = PHASE2_COLD_AFTER_GIVE_UP

    @property
    def phase2_x(self) -> np.ndarray:
        """Phase 2's last solution."""
        return self.phase2.x

    def key(self, mech: Any) -> np.ndarray:
        """What of the mechanism ``mech`` is compared between steps (its active rows)."""
        return mech

    def tried(self, mech: Any) -> bool:
        """Is the mechanism ``mech`` (its rows, on which alone its polytope depends) one
        whose polytope was found empty before?"""
        return np.packbits(mech).tobytes() in self.empty

    def failed(self, mech: Any, empty: bool) -> None:
        """Record that the mechanism ``mech`` gave no collapse state (``empty``: its
        polytope is empty; else its nearest state failed its check)."""
        if empty:
            self.empty.add(np.packbits(mech).tobytes())

    def phase1_rows(self) -> Any:
        """The joint rows with a non-zero dual in phase 1's last answer."""
        return self.capped.solver.held()

    def active(self, bj: np.ndarray) -> np.ndarray | None:
        """The joint rows the mechanism at the caps ``bj`` (joint rows' right-hand
        sides; phase 1 just solved there) holds active: non-zero duals of phase 1 and
        of phase 2 at the same caps. None where phase 2 has no answer."""
        face = self.phase1_rows()
        lp = self.phase2
        st = self.cv.count_solve("highs", "least confined state", lambda: (
            lp.solve(self.rows, np.where(face, bj, -math.inf), bj), lp.iterations))
        if st != OPTIMAL:
            return None
        return face | nonzero(self.phase2.duals[self.ne:], DUAL_ZERO)

    def settler(self) -> Any:
        """A ``settle`` for one run of :meth:`CappedLimit.run`: at each step phase 1's
        rows; once they settle, phase 2 at the same caps and the state of the polytope
        of the two phases' rows nearest the iterate, checked, with the span of its
        multipliers, how it was reached, the limit solves it took beyond the run's own
        and whether it is least confined (None: go on). After ``PATH_STEPS`` steps
        without one, the run goes on by :meth:`walk` from where it is; where the walk
        finds no state, by least-squares steps again (the 10 x 10 wall at f = 0.956: its
        walk's mechanism does not settle within 20 vertex steps, one with collapse
        states 12 least-squares steps later). ``LOOSE_AFTER`` least-squares steps after
        a walk that found none, a settled mechanism whose polytope is empty is sought
        again with phase 1's rows alone (:meth:`states`, ``least_confined`` False)."""
        prev: list[np.ndarray] = []
        steps = [0]
        loose_from = [math.inf]

        def settle(N: np.ndarray) -> tuple[Any, Any, str, int, bool] | None:
            steps[0] += 1
            if steps[0] == PATH_STEPS:
                prev.clear()
                got = self.walk(N)
                if got[0] is None:
                    loose_from[0] = steps[0] + LOOSE_AFTER
                return (*got, True)
            # phase 2 only where phase 1's rows have settled: most least-squares steps
            # move them far (phase 2 there was 7.7 of the 40.7 CPU s of the 1,041-block
            # wall at f = 0.6; `load` without it, whole processes in turn: 0.736 of
            # the CPU time)
            face = self.phase1_rows()  # kept: a check below solves phase 1 again
            if face is None:
                return None
            last = prev[-1] if prev else None
            prev[:] = [self.key(face)]
            if not _settled(prev[0], last):
                return None
            act = self.active(self.capped.rhs(N))
            if act is None:
                return None
            got = self.states(act, N)
            if got is not None:
                return (*got, "", 0, True)
            if steps[0] > loose_from[0]:
                got = self.states(face, N, least_confined=False)
                if got is not None:
                    return (*got, LOOSE, 0, False)
            return None

        return settle

    def walk(self, N: np.ndarray, max_steps: int | None = None
             ) -> tuple[Any, Any, str, int]:
        """From the normal forces ``N`` by steps to phase 2's vertex (no least-squares
        term) until the mechanism's rows settle and its polytope has a state, as
        :meth:`settler`, the first step at ``N`` itself (the limit solve the run made
        there); no state, and why, where none is found within ``max_steps``
        (``WALK_STEPS``), or where the mechanism has not once settled within
        ``UNSETTLED_WALK``, or within ``WANDER_STEPS`` none of whose steps changed fewer
        than ``WANDER`` of its rows."""
        max_steps = max_steps or WALK_STEPS
        last = None
        settled = False
        least = math.inf  # the smallest share of the rows a step changed
        after = f"after {PATH_STEPS - 1} least-squares steps"
        progress = self.cv.progress
        run_context = progress.context
        for k in range(1, max_steps + 1):
            progress.context = f"{run_context}, vertex step {k} of at most {max_steps}"
            bj = self.capped.rhs(N)
            st, _, _ = self.capped.solver.maximise(bj)
            act = self.active(bj) if st == OPTIMAL else None
            if act is None:
                why = f"the limit problem gave no answer ({st})" if st != OPTIMAL else \
                    "the least confined state gave no answer"
                return None, None, f"{why} at vertex step {k} {after}", k - 1
            key = self.key(act)
            changed = _changed(key, last)
            least = min(least, changed)
            if changed <= SETTLED:
                settled = True
                if not self.walk_past_failures and self.tried(act):
                    return None, None, (f"the mechanism settled at vertex step {k} {after} "
                                        "gave no collapse state before"), k - 1
                got = self.states(act, N)
                if got is not None:
                    return (*got, f" ({k} of them by steps to the least confined state "
                                  f"{after})", k - 1)
            wanders = self.wander and k == WANDER_STEPS and least > WANDER
            if (k == UNSETTLED_WALK or wanders) and not settled and k < max_steps:
                how = (f", each step changing at least {least:.1%} of its rows"
                       if wanders else "")
                return None, None, (f"the mechanism did not settle within {k} vertex "
                                    f"steps{how} {after}"), k - 1
            last = key
            N = np.maximum(self.phase2_x[self.capped.nsl], 0.0)
        return None, None, (f"no mechanism with collapse states within {max_steps} vertex "
                            f"steps {after}"), max_steps - 1

    def states(self, active: np.ndarray, N: np.ndarray, least_confined: bool = True
               ) -> tuple[np.ndarray, tuple[float, float]] | None:
        """The collapse state of the mechanism (joint rows ``active``) nearest the
        normal forces ``N``, checked (:meth:`check`; ``least_confined`` False where
        ``active`` are phase 1's rows alone), and the multipliers of the mechanism's
        lowest and highest states; None where its polytope is empty, the check fails or
        the solver fails on it (not recorded: tried again). An empty polytope is not
        sought again (the 311-block wall at f = 0.8 from the associative state: 5 of
        its 14 attempts on the rows of one before)."""
        if self.tried(active):
            return None
        # where the solver fails (not the mechanism) it is sought again at the next
        # settled step: the 204-block wall3d in plane at f = 0.6 from X0, where Clarabel
        # failed on a nearest state at two steps, ends at a checked state after 19 limit
        # solves (a plain fixed point after 26 when such failures were recorded as the
        # mechanism's); the 1,041-block one stalled for 100 limit solves after one
        # lowest state ended AlmostSolved
        st, lo = self._over_polytope(active, self._lam_cost(1.0), None)
        if lo is None:
            if st == INFEASIBLE:
                self.failed(active, True)
            return None
        z = self.nearest(active, N)
        if z is None:
            return None
        if self.check(z, least_confined):
            self.failed(active, False)
            return None
        hi = self.extreme(active, -1.0)
        lam = float(z[self.li])
        ends = [(float(lo[self.li]), lo)] + ([] if hi is None else [(float(hi[self.li]), hi)])
        for v, ze in ends:
            if abs(v - lam) <= SNAP * max(1.0, abs(v)) and not self.check(ze, least_confined):
                z, lam = ze, v
        span = (min(ends[0][0], lam), max(ends[-1][0], lam))
        return z, tuple(0.0 if abs(v) <= DUAL_ZERO else v for v in span)

    def extreme(self, active: np.ndarray, sense: float) -> np.ndarray | None:
        """The state of the mechanism (joint rows ``active``) of least (``sense`` 1) or
        largest (-1) multiplier; None where the polytope is empty or the solver gives no
        answer."""
        return self._over_polytope(active, self._lam_cost(sense), None)[1]

    def _lam_cost(self, sense: float) -> np.ndarray:
        """The cost ``sense`` lambda."""
        c = np.zeros(self.capped.prob.n)
        c[self.li] = sense
        return c

    def nearest(self, active: np.ndarray, N: np.ndarray) -> np.ndarray | None:
        """The state of the mechanism whose normal forces are nearest ``N`` (least
        squares, scaled forces)."""
        import scipy.sparse as sp

        n, nsl = self.capped.prob.n, self.capped.nsl
        d = np.zeros(n)
        d[nsl] = 1.0
        c = np.zeros(n)
        c[nsl] = -N
        return self._over_polytope(active, c, sp.diags(d, format="csc"))[1]

    def _over_polytope(self, active: np.ndarray, c: np.ndarray, P: Any
                       ) -> tuple[str, np.ndarray | None]:
        """min c'z (+ z'Pz/2) over the collapse states of the mechanism (joint rows
        ``active``): one problem by the convex method's back end; its status
        (INFEASIBLE: the polytope is empty) and its solution (None unless OPTIMAL)."""
        prob = self._polytope(active, c, P)
        try:
            res = self.cv.solve(prob, "collapse states of one mechanism", tight=True,
                                stall=False)
        except SolverFailure:
            return FAILURE, None
        return res.status, (res.z if res.status == OPTIMAL else None)

    def _polytope(self, active: np.ndarray, c: np.ndarray, P: Any) -> ConicProblem:
        """The problem min c'z (+ z'Pz/2) over the states in equilibrium under their own
        caps (K z <= b0) with the rows ``active`` held."""
        p = self.capped.prob
        A, b, n_eq, n_nonneg = hold_rows(self.K, np.concatenate([p.b[:self.ne],
                                                                 self.capped.b0]),
                                         self.ne, active)
        return ConicProblem(c=c, A=A, b=b, n_eq=n_eq, n_nonneg=n_nonneg, P=P, cols=p.cols,
                            rows={})

    def check(self, z: np.ndarray, least_confined: bool = True) -> str:
        """Why the state ``z`` is not a fixed point ("" where it is): at its own caps,
        phase 1's multiplier and (``least_confined``) phase 2's total normal force must
        be its own. Without phase 2, ``z`` is a collapse state all the same: it carries
        the largest multiplier under the caps of its own normal forces, and phase 1's
        duals there are a mechanism compatible with it; it is not the state the
        iteration selects among those that carry that multiplier."""
        nsl = self.capped.nsl
        N = np.maximum(z[nsl], 0.0)
        bj = self.capped.rhs(N)
        st, lam, _ = self.capped.solver.maximise(bj)
        own = float(z[self.li])
        if st != OPTIMAL:
            return f"at its own caps the limit problem gave no answer ({st})"
        if abs(lam - own) > self.fixed_tol * max(1.0, abs(own)):
            return f"at its own caps the multiplier is {lam:.9g}, not {own:.9g}"
        if not least_confined:
            return ""
        if self.active(bj) is None:
            return "at its own caps the least confined state gave no answer"
        s2, s = float(self.phase2_x[nsl].sum()), float(N.sum())
        if abs(s2 - s) > self.fixed_tol * max(1.0, s):
            return f"at its own caps a less confined state carries it ({s2:.9g} < {s:.9g})"
        return ""


class ConeMechanisms(Mechanisms):
    """The mechanisms of a capped problem with Coulomb's cones (3D; its solver the
    convex method's back end, whose last answer is phase 1's). Complementarity with a
    cone's dual z != 0 puts the cone's slack s on the ray of (z0, -z1, -z2): the
    contact slides in the direction the dual gives, with |T| at its cap; two linear
    conditions per cone (s_v z0 + s0 z_v = 0), so that the collapse states of one
    mechanism are a convex set (the cones of the other contacts remain), its range two
    second-order cone programs. A row or cone holds where its dual is not zero (to
    ``CONE_DUAL_ZERO``: an interior-point answer's duals are never exactly zero)."""

    #: no: the walk's steps cost two cone programs each, and its mechanism, once
    #: settled, stays within SETTLED of the one that failed (the 491-block wall3d in
    #: plane at f = 0.6: 100 vertex steps per run after one failed attempt, 465 s; ended
    #: there, 204 s, the same answer)
    walk_past_failures = False
    fixed_tol = CONE_FIXED_TOL
    #: the walk's limit of WANDER_STEPS was measured on linear programs only
    wander = False

    def __init__(self, capped: CappedLimit):
        Mechanisms.__init__(self, capped)
        p = capped.prob
        self.nc = len(p.soc)
        #: the keys of the mechanisms that gave no collapse state
        self.failures: list[np.ndarray] = []
        self._z2 = np.zeros(p.n)
        self.A = p.A.tocsr()

    def _make_phase2(self) -> None:
        """Phase 2 is a second-order cone program solved at each step (no warm LP)."""

    @property
    def phase2_x(self) -> np.ndarray:
        return self._z2

    def tried(self, mech: Any) -> bool:
        """Is ``mech`` within ``SETTLED`` of a mechanism that gave no collapse state
        (the cones' directions take part in its polytope, so no key identifies one)?
        Each attempt costs four or five cone programs, and a run's mechanism, once
        settled, changes by a few rows a step: the 491-block wall3d in plane at
        f = 0.6 spent 1,631 of its 2,152 s in 470 attempts that gave none (164 of
        them failed in Clarabel), its runs ending as plain fixed points. A failure of
        the solver on the polytope is not recorded (:meth:`states`)."""
        key = self.key(mech)
        return any(_settled(key, k) for k in self.failures)

    def failed(self, mech: Any, empty: bool) -> None:
        self.failures.append(self.key(mech))

    def key(self, mech: Any) -> np.ndarray:
        lin, cones = mech
        ray = np.zeros(self.nc, dtype=bool)
        ray[[k for k, _ in cones]] = True
        return np.concatenate([lin, ray])

    def _held(self, y: np.ndarray, n_eq: int, ni: int
              ) -> tuple[np.ndarray, list[tuple[int, np.ndarray]]]:
        """The ``ni`` linear rows (after the first ``n_eq``) and the cones (with their
        duals' unit vectors) whose duals ``y`` (of an interior-point answer) are not
        zero: holding fewer would admit states that are not fixed points (the check
        finds them: on the extruded 10 x 10 wall, states down to 0.5096697 when the
        rows whose duals exceed their slacks were held)."""
        nc = self.nc
        scale = max(1.0, float(np.abs(y).max(initial=0.0)))
        yl = y[n_eq:n_eq + ni]
        lin = yl > CONE_DUAL_ZERO * scale
        zc = y[n_eq + ni:].reshape(nc, 3)
        nz = np.linalg.norm(zc, axis=1)
        ray = nz > CONE_DUAL_ZERO * scale
        return lin, [(int(k), zc[k] / nz[k]) for k in np.flatnonzero(ray)]

    def _conditions(self, A: Any, b: np.ndarray, lin: np.ndarray,
                    cones: list[tuple[int, np.ndarray]]) -> tuple[Any, np.ndarray]:
        """The rows (G, g) of G x = g that hold the linear rows ``lin`` of the joint rows
        (A, b) and put each of ``cones``' slacks on the ray of its dual."""
        import scipy.sparse as sp

        ne, ni = self.ne, self.ni
        rows = [A[ne:ne + ni][lin]]
        rhs = [b[ne:ne + ni][lin]]
        if cones:
            r0 = ne + ni + 3 * np.array([k for k, _ in cones])
            d = np.array([u for _, u in cones])
            for v in (1, 2):
                rows.append(sp.diags(d[:, 0]) @ A[r0 + v] + sp.diags(d[:, v]) @ A[r0])
                rhs.append(d[:, 0] * b[r0 + v] + d[:, v] * b[r0])
        return sp.vstack(rows, format="csr"), np.concatenate(rhs)

    def _problem(self, A: Any, b: np.ndarray, mech: Any, c: np.ndarray, P: Any
                 ) -> ConicProblem:
        """min c'x (+ x'Px/2) over the states of (A, b) (equilibrium rows first, then
        the joint rows) that hold the mechanism ``mech``."""
        import scipy.sparse as sp

        ne, ni = self.ne, self.ni
        lin, cones = mech
        G, g = self._conditions(A, b, lin, cones)
        free = np.flatnonzero(~lin)
        AA = sp.vstack([A[:ne], G, A[ne:ne + ni][free], A[ne + ni:]], format="csc")
        bb = np.concatenate([b[:ne], g, b[ne:ne + ni][free], b[ne + ni:]])
        p = self.capped.prob
        return ConicProblem(c=c, A=AA, b=bb, n_eq=ne + G.shape[0], n_nonneg=len(free),
                            soc=p.soc, P=P, cols=p.cols, rows={})

    def phase1_rows(self) -> Any:
        last = self.capped.solver.last
        return None if last is None else self._held(last.y, self.ne, self.ni)

    def active(self, bj: np.ndarray) -> Any:
        face = self.phase1_rows()
        if face is None:
            return None
        p = self.capped.prob
        b = np.concatenate([p.b[:self.ne], bj])
        lin, cones = face
        c2 = np.zeros(p.n)
        c2[self.capped.nsl] = 1.0
        prob = self._problem(self.A, b, (lin, cones), c2, None)
        try:
            res = self.cv.solve(prob, "least confined collapse state", tight=True,
                                stall=False)
        except SolverFailure:
            return None
        if res.status != OPTIMAL:
            return None
        self._z2 = res.z
        # phase 2's own rows, read on its problem (its conditions are equalities there)
        lin2, cones2 = self._held(res.y, prob.n_eq, prob.n_nonneg)
        free = np.flatnonzero(~lin)
        lin_all = lin.copy()
        lin_all[free[lin2]] = True
        return lin_all, cones + cones2

    def _polytope(self, mech: Any, c: np.ndarray, P: Any) -> ConicProblem:
        p = self.capped.prob
        return self._problem(self.K, np.concatenate([p.b[:self.ne], self.capped.b0]),
                             mech, c, P)


def _changed(act: np.ndarray, last: np.ndarray | None) -> float:
    """The share of the mechanism's rows ``act`` that differ from the last step's
    (infinite where there is none)."""
    return math.inf if last is None else int((act ^ last).sum()) / max(int(act.sum()), 1)


def _settled(act: np.ndarray, last: np.ndarray | None) -> bool:
    """Have the mechanism's rows settled: do they differ from the last step's by at most
    ``SETTLED`` of their number?"""
    return _changed(act, last) <= SETTLED


def walks(cv: ConvexMethod) -> bool:
    """Do the mechanisms' polytopes end the limit iteration on the scene of ``cv``: are
    its capped problems linear programs (2D, or 3D with Coulomb's cones linearised as
    pyramids)?"""
    return cv.contacts.dimension == 2 or cv.pyramid is not None


def limit_runs(capped: CappedLimit, starts: list[tuple[str, np.ndarray]]
               ) -> list[LimitRun]:
    """One run of the limit iteration per start (name, scaled normal forces), ended at
    the collapse states of the mechanism it reaches where it has them: LPs (2D, 3D
    pyramids) and Coulomb's cones."""
    if walks(capped.cv) and capped.backend == "highs":
        mech: Mechanisms = Mechanisms(capped)
    elif capped.prob.soc and set(capped.prob.soc) == {3}:
        mech = ConeMechanisms(capped)
    else:
        return [capped.run(n, name) for name, n in starts]
    return [capped.run(n, name, settle=mech.settler()) for name, n in starts]


__all__ = ["ConeMechanisms", "Mechanisms", "limit_runs", "walks"]
