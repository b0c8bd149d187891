"""The non-associative collapse state as a fixed point of the limit problem.

Gilbert, Casapulla & Ahmed (Computers & Structures 84, 2006, 873-887) and, with cones
in 3D, Portioli et al. (2014) iterate the limit analysis itself: each marked joint's
Coulomb law |T| <= f N is replaced by the cohesion-only law |T| <= f N_prev (per contact
point, N_prev the previous iterate's normal forces), the maximum load multiplier is
solved under it, and its normal forces give the next caps. A fixed point is a
non-associative collapse state:

* equilibrium at lambda, with |T| <= f N on the state's own normal forces (the caps
  are its own forces);
* lambda is the largest multiplier any state carries with those caps, and the duals of
  that problem are a mechanism whose marked joints slide without opening (a
  cohesion-only law has no normal component in its normal cone) and whose power
  balance is the dissipation f N |slip| of the state's own forces: the non-associative
  kinematic condition, compatible with the forces.

The maximum-load problem has in general a face of optimal states, and the normal forces
of one of its vertices jump from iteration to iteration: taking the vertex HiGHS gives,
the 106-block wall cycles for hundreds of iterations within 5e-4 of one multiplier,
and the 3 x 3 wall's answer depends on which vertex the simplex path meets (0.714286,
0.715907 or 0.720409). Each step here therefore solves two problems: the maximum
multiplier lambda_k under the caps, then, among the states carrying lambda_k, the least
confined one near the previous iterate: min sum N + 1/2 |N - N_prev|^2 (scaled forces),
unique. A pinch (a self-stress of the normal forces) only raises the next caps; the
least squares term alone keeps it (the block pinched under a lintel then settles at
0.345 instead of f = 0.3, the 3 x 3 wall at 0.715918 in 2D and 3D), the total normal
force alone leaves the step's choice among equal totals to the solver (the 3 x 3 wall
and the 106-block wall do not settle in 200 steps). The step stops exactly where the
previous normal forces are themselves selected, the fixed-point condition. The
plain map oscillates about its fixed point and contracts slowly (by about 0.8 a step on
the 106-block wall, still 2e-7 from it after 500 steps on the 311-block one at f = 0.6):
the next normal forces combine the last steps (Anderson acceleration, :class:`_Anderson`),
halving the step where that stalls. In 2D the
maximum is a linear program solved by HiGHS's dual simplex, warm-started from the
previous basis (only right-hand sides change); in 3D a second-order cone program solved
by the convex method's back end; the selection is a quadratic program solved by the
latter.

Non-associative collapse states are not unique: the fixed point reached depends on the
start. :func:`limit_fixed_point` starts from given normal forces; the analyses start
from the elastic state X0 under the dead load (tension cleared) and from the associative
collapse state, and report both.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import SolverFailure
from ..methods.convex import ConvexMethod
from ..problems.formulation import build_max_load
from ..solvers import OPTIMAL
from ..solvers.base import ConicProblem
from ..solvers.highs_warm import nonzero, warm_lp

#: relative change of the normal forces (of the largest force) that ends the iteration
LIMIT_TOL = 1e-7
#: ... with Coulomb's cones (3D): the interior-point steps do not settle much below 1e-7
#: (the corbel dome: 68 steps to 1e-7, none within 200 to 1e-8, and none within 200 at
#: f = 0.59995; to 1e-6 in 44 steps, its multiplier 2e-9 from the one at 1e-7)
CONE_LIMIT_TOL = 1e-6
#: limit solves of one run, its vertex steps (:mod:`rigidblocks.analyses.na_mechanism`)
#: included: runs that end at their mechanism's states take 6 to 120 on the walls up to
#: 1,041 blocks, and one that does not settle costs a least-squares step each (1.5 s at
#: 1,041 blocks: the 32 x 32 wall's friction search at f = 0.8 spent over 20 minutes in
#: the run of its first trial, at the static f*, with a budget of 500)
LIMIT_MAX_ITER = 200
#: steps without a new smallest change after which the step is halved, down to
STALL = 12
MIN_DAMPING = 1.0 / 64
#: past steps the accelerated update combines (Anderson acceleration)
MEMORY = 5
#: weight of the proximal term of the selection step (scaled forces: the largest block
#: load is 1)
PROX_WEIGHT = 1.0
#: the selection step keeps lambda within this (relative) of the step's maximum: a
#: simplex maximum (2D) is exact to rounding, an interior-point one (3D cones) to the
#: solver's accuracy, and the selection among states within 1e-9 of it fails in
#: Clarabel (the corbel dome: 111 of its 121 selections). Where the maximum is a
#: simplex answer the selection holds its face instead (:func:`_select_problem`)
PROX_SLACK = 1e-9
CONE_PROX_SLACK = 1e-6
#: a multiplier this far (relative) below a load factor carries it: a simplex maximum
#: (2D) is exact to rounding; with Coulomb's cones (3D) a collapse state's multiplier is
#: checked to CONE_FIXED_TOL (:mod:`rigidblocks.analyses.na_mechanism`), and finer
#: comparisons read the interior-point solver's accuracy (the 3 x 3 wall3d out of plane
#: at load factor 0.5, its hinging multiplier: 0.4999997 from X0 at f = 0.6, 0.5 at
#: 2.4; with 1e-9 its friction search gave f* = 1.30313 where the associative one
#: gives 0.5)
CARRY_TOL = 1e-9
CONE_CARRY_TOL = 1e-5
#: a simplex dual below this fraction of the largest is zero: its row is not held on
#: the optimal face (:meth:`_HighsLimit.held`)
DUAL_ZERO = 1e-9


@dataclass
class LimitRun:
    """One fixed-point run of the limit problem from one start.

    ``lam`` the last multiplier; ``x`` the last state's link forces (scaled: the
    largest block load is 1);
    ``history`` (lambda, relative change of the normal forces) per step.
    """

    start: str
    status: str  # "converged", "undecided", "infeasible", "unbounded"
    lam: float | None
    x: np.ndarray | None
    iterations: int
    reason: str = ""
    history: list[tuple[float, float]] = field(default_factory=list)
    time: float = 0.0
    #: the multipliers of the lowest and highest collapse states of the mechanism
    #: reached (:mod:`rigidblocks.analyses.na_mechanism`); None where not computed
    span: tuple[float, float] | None = None
    #: are those states the least confined of the states that carry their multiplier
    #: (the iteration's fixed points), or only states that carry the largest multiplier
    #: under the caps of their own normal forces?
    least_confined: bool = True
    #: how far (relative) ``lam`` may lie below a load factor that it carries: the
    #: accuracy of the run's multipliers (:attr:`CappedLimit.carry_tol`)
    carry_tol: float = CARRY_TOL

    def carries(self, load_factor: float) -> bool:
        """Does the run's multiplier reach ``load_factor`` (to :attr:`carry_tol` of it, and
        of the live load itself where the load factor is below 1: the 1-ring barrel vault
        at its f* for the dead load alone reached lambda = -5.2e-14, which did not carry
        0)?"""
        return self.lam is not None and \
            self.lam >= load_factor - self.carry_tol * max(abs(load_factor), 1.0)

    @property
    def converged(self) -> bool:
        return self.status == "converged"

    @property
    def resolution(self) -> float:
        """How far the state's normal forces are from the caps it was solved under,
        relative to its largest force or to the largest block load where that is larger
        (as :func:`certificate` measures): the last step's change for a plain fixed point
        (its caps are the previous iterate's forces), 0 for a mechanism's state (its
        caps are its own)."""
        if self.span is not None or not self.history or self.x is None:
            return 0.0
        return self.history[-1][1]


def carried_text(lam: float, lf: float, tol: float) -> str:
    """How a multiplier ``lam`` that carries the load factor ``lf`` (to ``tol``,
    :meth:`LimitRun.carries`) compares with it: ">= lf", or where it lies below, "= lf to
    the accuracy of its multiplier" (a cone multiplier's)."""
    scale = "relative" if abs(lf) >= 1 else "of the live load"
    return f">= {lf:.10g}" if lam >= lf else \
        f"= {lf:.10g} to the accuracy of its multiplier, {tol:g} {scale}"


class _HighsLimit:
    """The capped maximum-load LP (2D) in one HiGHS model, warm-started between solves
    (only the joint rows' right-hand sides change), its solves counted as the convex
    method's (:meth:`~rigidblocks.methods.convex.ConvexMethod.count_solve`)."""

    def __init__(self, prob: ConicProblem, cv: ConvexMethod):
        self.cv = cv
        ne, ni = prob.n_eq, prob.n_nonneg
        self.ni = ni
        self.li = prob.cols["lambda"].start
        self.lp = warm_lp(prob.c, prob.A, np.concatenate([prob.b[:ne], np.full(ni, -math.inf)]),
                          prob.b[:ne + ni])
        self.rows = np.arange(ne, ne + ni)
        self.free = np.full(ni, -math.inf)

    def maximise(self, b_joints: np.ndarray) -> tuple[str, float, np.ndarray | None]:
        """max lambda with the joint rows' right-hand sides ``b_joints``."""
        lp = self.lp
        st = self.cv.count_solve("highs", "maximum load (capped laws)", lambda: (
            lp.solve(self.rows, self.free, b_joints), lp.iterations))
        if st != OPTIMAL:
            return ("failure" if st == "failure" else st), math.nan, None
        z = self.lp.x
        return OPTIMAL, float(z[self.li]), z

    def held(self) -> np.ndarray:
        """The joint rows with a non-zero dual in the last answer: a state is optimal
        exactly where it holds them active (complementary slackness with that dual
        solution), so that they give the optimal face without a bound on lambda."""
        return nonzero(self.lp.duals[self.rows], DUAL_ZERO)


class _ConicLimit:
    """The capped maximum-load problem through the convex method's back end (3D cones)."""

    def __init__(self, cv: ConvexMethod, prob: ConicProblem):
        self.cv, self.prob = cv, prob
        #: the last answer (its duals read by :mod:`rigidblocks.analyses.na_mechanism`)
        self.last: Any = None

    def maximise(self, b_joints: np.ndarray) -> tuple[str, float, np.ndarray | None]:
        p = self.prob
        b = np.concatenate([p.b[:p.n_eq], b_joints])
        prob = ConicProblem(c=p.c, A=p.A, b=b, n_eq=p.n_eq, n_nonneg=p.n_nonneg, soc=p.soc,
                            cols=p.cols, rows=p.rows)
        self.last = None
        try:
            res = self.cv.solve(prob, "maximum load (capped laws)", tight=True, stall=False)
        except SolverFailure:
            return "failure", math.nan, None
        if res.status != OPTIMAL:
            return res.status, math.nan, None
        self.last = res
        return OPTIMAL, float(res.z[p.cols["lambda"]][0]), res.z

    def held(self) -> None:
        """No face: an interior-point answer's duals are never exactly zero, and the
        selection bounds lambda instead (``CONE_PROX_SLACK``)."""
        return None


def hold_rows(A: Any, b: np.ndarray, ne: int, held: np.ndarray
              ) -> tuple[Any, np.ndarray, int, int]:
    """The rows (A, b) of a problem (its ``ne`` equalities first, then its joint rows,
    inequalities) with the joint rows ``held`` made equalities: the rows, their
    right-hand sides, and the numbers of equalities and of inequalities."""
    import scipy.sparse as sp

    A = A.tocsr()
    Aj, bj = A[ne:], b[ne:]
    return (sp.vstack([A[:ne], Aj[held], Aj[~held]], format="csc"),
            np.concatenate([b[:ne], bj[held], bj[~held]]),
            ne + int(held.sum()), int((~held).sum()))


def _select_problem(prob: ConicProblem, nsl: slice, b_joints: np.ndarray, lam: float,
                     N_prev: np.ndarray, face: np.ndarray | None = None) -> ConicProblem:
    """min sum N + w/2 |N - N_prev|^2 (w = PROX_WEIGHT, N scaled) over the states of
    ``prob`` (the capped maximum-load problem, joint rows' right-hand sides
    ``b_joints``) that carry the step's maximum: the least confined state, near the
    previous. The maximum is kept by holding the joint rows ``face`` active (the
    optimal face of a simplex answer, :meth:`_HighsLimit.held`), or else by the bound
    lambda >= ``lam``. The bound admits, besides the face, states a relative 1e-9 below
    the maximum along the directions where it barely falls: on the 1,041-block wall
    at f = 0.6 the two selections' normal forces differ by up to 2 (scaled), and
    Clarabel takes 0.27-0.45 s on the face against 0.57-1.49 s under the bound (the
    first 8 selections). `load`, whole processes in turn: 0.77-0.85 of the
    CPU time on the walls 10 x 10 at f = 0.8, 20 x 15 at f = 0.6 and 0.8 and 32 x 32
    at f = 0.8 (190 s against 245 s on the last), but 1.22 on 32 x 32 at f = 0.6,
    whose run from the associative state takes another path (17 limit solves, not
    12)."""
    import scipy.sparse as sp

    n, ne, ni = prob.n, prob.n_eq, prob.n_nonneg
    if face is None:
        A = prob.A.tocsr()
        li = prob.cols["lambda"].start
        lam_row = sp.csr_matrix(([-1.0], ([0], [li])), shape=(1, n))
        A2 = sp.vstack([A[:ne], lam_row, A[ne:]], format="csc")
        b2 = np.concatenate([prob.b[:ne], [-lam], b_joints])
        n_eq, n_nonneg = ne, ni + 1
    else:
        A2, b2, n_eq, n_nonneg = hold_rows(prob.A, np.concatenate([prob.b[:ne], b_joints]),
                                           ne, face)
    d = np.zeros(n)
    d[nsl] = 1.0
    c = np.zeros(n)
    c[nsl] = -N_prev
    return ConicProblem(c=c * PROX_WEIGHT + d, A=A2, b=b2, n_eq=n_eq, n_nonneg=n_nonneg,
                        soc=prob.soc, P=sp.diags(d * PROX_WEIGHT, format="csc"),
                        cols=prob.cols, rows={})


class CappedLimit:
    """The maximum-load problem of a scene with the marked joints' Coulomb law replaced
    by caps |T| <= f N_prev per contact point, at one friction ``f``."""

    def __init__(self, cv: ConvexMethod, marked: np.ndarray, f: float,
                 backend: str | None = None):
        c = cv.contacts
        self.cv = cv
        fj = cv.f_joint(f)
        mk = marked & np.isfinite(fj)
        self.f_eff = np.where(mk, 0.0, fj)
        self.f_pt = np.where(mk, fj, 0.0)[c.point_joint]
        self.nsl = cv.system.layout.normal
        self.P = c.n_points
        prob, _ = build_max_load(cv.system, cv.scaling, self.f_eff, cv.pyramid,
                                 cap=np.zeros(self.P))
        self.b0 = prob.b[prob.n_eq:].copy()
        # the caps enter the joint rows' right-hand sides linearly: b = b0 + M cap
        self.M = self._cap_matrix()
        # a linear program (2D, or 3D with pyramids) by HiGHS, warm-started
        self.backend = backend or ("highs" if prob.is_lp else "conic")
        self.prob = prob
        self._solver: Any = None
        #: how far (relative) below a step's maximum its selected state may carry, and
        #: the change of the normal forces that ends a run
        self.slack, self.tol = (PROX_SLACK, LIMIT_TOL) if self.backend == "highs" else \
            (CONE_PROX_SLACK, CONE_LIMIT_TOL)
        #: the accuracy of its multipliers (:attr:`LimitRun.carry_tol`)
        self.carry_tol = CARRY_TOL if self.backend == "highs" or not prob.soc else \
            CONE_CARRY_TOL

    @property
    def solver(self) -> Any:
        """The maximum-load problem's solver (built at its first use)."""
        if self._solver is None:
            self._solver = _HighsLimit(self.prob, self.cv) if self.backend == "highs" else \
                _ConicLimit(self.cv, self.prob)
        return self._solver

    def _cap_matrix(self) -> Any:
        """M with b_joints(cap) = b0 + M cap: each friction row's right-hand side holds
        the caps of the points whose normal forces it sums (``JointRows.fric_nsum``:
        the joint's points in 2D with one shear per joint, the point itself otherwise,
        times cos(pi/k) on a k-facet pyramid); the uniform scaling leaves them unscaled."""
        import scipy.sparse as sp

        from ..problems.formulation import joint_rows

        cv = self.cv
        jr = joint_rows(cv.system, cv.scaling, self.f_eff, cv.system.layout.size + 1,
                        pyramid=cv.pyramid)
        nsum = jr.fric_nsum.tocsc()[:, self.nsl].tocoo()
        head = np.asarray(jr.fric_head)
        return sp.csr_matrix((nsum.data, (head[nsum.row], nsum.col)),
                             shape=(len(self.b0), self.P))

    def nearest(self, b_joints: np.ndarray, lam: float, N_prev: np.ndarray,
                face: np.ndarray | None = None) -> np.ndarray | None:
        """The state under the caps selected by :func:`_select_problem` on the optimal
        face ``face`` (held rows), or at lambda >= ``lam`` where there is none or the
        solver fails on it."""
        for held in ([face] if face is not None else []) + [None]:
            prob = _select_problem(self.prob, self.nsl, b_joints, lam, N_prev, held)
            try:
                res = self.cv.solve(prob, "nearest capped state", tight=True, stall=False)
            except SolverFailure:
                continue
            if res.status == OPTIMAL:
                return res.z
        return None

    def rhs(self, N: np.ndarray) -> np.ndarray:
        """The joint rows' right-hand sides with caps f N (N scaled, per point)."""
        return self.b0 + self.M @ (self.f_pt * np.maximum(N, 0.0))

    def run(self, N_start: np.ndarray, start: str, tol: float | None = None,
            max_iter: int = LIMIT_MAX_ITER, settle: Any = None) -> LimitRun:
        """Iterate from the normal forces ``N_start`` (scaled) to a fixed point (their
        change below ``tol``, :attr:`tol` by default). ``settle(N)``, called after each
        step's limit solve at the caps of N, ends the run where it gives a collapse
        state: (its solution, its multiplier's span, how it was reached, the limit
        solves it took beyond the run's own, whether it is least confined), or (None,
        None, why, solves, True) where it found none and the run goes on
        (:mod:`rigidblocks.analyses.na_mechanism`)."""

        def step(N: np.ndarray) -> tuple:
            b = self.rhs(N)
            st, lam, z = self.solver.maximise(b)
            if st != OPTIMAL:
                # (in words not read as the structure's: "the capped laws carry not
                # even the dead load" stood beside ADMISSIBLE)
                why = {"infeasible": "a step's shear caps, f N of the last state's normal "
                                     "forces, carry not even the dead load",
                       "unbounded": "no multiplier makes the capped problem collapse"}
                failed = f"the solver failed ({st})"
                return (st if st in why else "undecided"), why.get(st, failed)
            return lam, b, z, lam, self.solver.held()

        progress = self.cv.progress
        try:
            run = _iterate(self, N_start, start, step, "limit solves", tol or self.tol,
                           max_iter, settle)
        finally:
            progress.context = ""
        run.carry_tol = self.carry_tol
        return run


def _iterate(capped: CappedLimit, N_start: np.ndarray, start: str, step: Any, what: str,
             tol: float, max_iter: int, settle: Any = None) -> LimitRun:
    """The fixed-point loop of :meth:`CappedLimit.run`: ``step(N)`` solves one problem at
    the caps of the normal forces N and gives (value, joint rows' right-hand sides, its
    solution, the multiplier the state must carry, the rows that hold its optimal face
    or None), or (status, reason) where it has no answer;
    then the state is selected (:func:`_select_step`) and the next normal forces
    combined from the last steps (:class:`_Anderson`), damped (:func:`_damped`, which
    starts the combination afresh) until they settle, or until ``settle(N)`` (see
    :meth:`CappedLimit.run`) gives a collapse state. ``what`` names the solves."""
    t0 = time.perf_counter()
    N = np.maximum(N_start, 0.0)
    hist: list[tuple[float, float]] = []
    beta, best, since = 1.0, math.inf, 0
    value, x = math.nan, None
    acc = _Anderson(MEMORY)
    N_ok: np.ndarray | None = None  # the last normal forces whose caps carried the load
    extra = 0  # limit solves made by ``settle`` (vertex steps)
    k = 0
    progress = capped.cv.progress
    while k + extra < max_iter:
        k += 1
        last = f", lambda {value:.7g}" if math.isfinite(value) else ""
        progress.context = f"limit run from {start}: step {k + extra} of at most " \
                           f"{max_iter}{last}"
        got = step(N)
        if len(got) == 2:
            if got[0] == "infeasible" and N_ok is not None and beta > MIN_DAMPING:
                # the caps of these normal forces carry nothing, those of the last step
                # did: halfway back (the caps that carry the dead load are a convex set)
                beta = 0.5 * beta
                acc.reset()
                N = N_ok + 0.5 * (N - N_ok)
                continue
            return LimitRun(start, got[0], None, None, k + extra, got[1], hist,
                            time.perf_counter() - t0)
        N_ok = N
        value, b, z, target, face = got
        done = settle(N) if settle is not None else None
        if done is not None:
            zs, span, how, more, least = done
            extra += more
            if zs is not None:
                return LimitRun(start, "converged",
                                float(zs[capped.prob.cols["lambda"].start]),
                                zs[:capped.cv.system.layout.size], k + extra,
                                f"the mechanism reached after {k + extra} {what}{how} has "
                                "collapse states", hist, time.perf_counter() - t0, span=span,
                                least_confined=least)
        x, own, Nn, change = _select_step(capped, b, target, N, z, face)
        hist.append((value, change))
        if change <= tol:
            run = LimitRun(start, "converged", own, x, k + extra,
                           f"fixed point after {k + extra} {what}", hist,
                           time.perf_counter() - t0)
            run.reason += f" (its normal forces {run.resolution:.1g} of its largest force " \
                          "or block load from their caps)"
            return run
        damped, best, since = _damped(beta, best, since, change)
        if damped != beta:
            acc.reset()
        beta = damped
        N = np.maximum(acc.update(N, Nn - N, beta), 0.0)
    last = f" (last relative change of the normal forces {hist[-1][1]:.3g})" if hist else ""
    return LimitRun(start, "undecided", value, x, k + extra,
                    f"no fixed point within {max_iter} {what}{last}", hist,
                    time.perf_counter() - t0)


class _Anderson:
    """Anderson acceleration of the fixed-point map N -> S(N) (Anderson, J. ACM 12, 1965;
    in the form of Walker & Ni, SIAM J. Numer. Anal. 49, 2011): the next iterate
    combines the last ``memory`` steps so that their residuals g = S(N) - N cancel in
    the least-squares sense. On the walls the plain map oscillates about its fixed point
    and contracts by about 0.8 a step (the 106-block wall at f = 0.8: 61 steps to 1e-7);
    combined, 26."""

    def __init__(self, memory: int):
        self.memory = memory
        self.reset()

    def reset(self) -> None:
        """Forget the past steps (where the damping changes)."""
        self.dx: list[np.ndarray] = []
        self.dg: list[np.ndarray] = []
        self.last: tuple[np.ndarray, np.ndarray] | None = None

    def update(self, N: np.ndarray, g: np.ndarray, beta: float) -> np.ndarray:
        """The next iterate from N with residual g = S(N) - N and mixing ``beta``."""
        if self.last is not None:
            self.dx.append(N - self.last[0])
            self.dg.append(g - self.last[1])
            del self.dx[:-self.memory], self.dg[:-self.memory]
        self.last = (N, g)
        if not self.dx:
            return N + beta * g
        G = np.array(self.dg).T
        gamma = np.linalg.lstsq(G, g, rcond=1e-10)[0]
        nxt = N + beta * g - (np.array(self.dx).T + beta * G) @ gamma
        return nxt if np.all(np.isfinite(nxt)) else N + beta * g


def _select_step(capped: CappedLimit, b: np.ndarray, target: float, N: np.ndarray,
                 z: np.ndarray, face: np.ndarray | None = None
                 ) -> tuple[np.ndarray, float, np.ndarray, float]:
    """One step's state: the least-confined state near the normal forces ``N`` that
    carries ``target`` (on the optimal face held by the rows ``face``, or to
    :attr:`CappedLimit.slack`) under the joint rows' right-hand sides ``b`` (the limit
    solve's own ``z`` where that selection fails), the
    multiplier it carries, its normal forces, and their change from ``N`` relative to
    the state's largest force (or to the largest block load where that is larger)."""
    zz = capped.nearest(b, target - capped.slack * max(1.0, abs(target)), N, face)
    zs = z if zz is None else zz
    x = zs[:capped.cv.system.layout.size]
    Nn = np.maximum(x[capped.nsl], 0.0)
    scale = max(1.0, float(np.abs(x).max(initial=0.0)))
    return (x, float(zs[capped.prob.cols["lambda"].start]), Nn,
            float(np.abs(Nn - N).max(initial=0.0)) / scale)


def reached_normals(na: Any, f: float) -> tuple[str, np.ndarray | None]:
    """The normal forces (scaled) of the state reached from X0 under the dead load at
    friction ``f`` (the fixed point of the seed's procedure at lambda = 0, from a
    :class:`~rigidblocks.analyses.nonassociative.ConvexNonAssociative`), and its
    verdict: "admissible" (the forces), "inadmissible" (the dead load alone is not
    carried from X0: None) or "undecided" (X0's normal forces,
    :func:`x0_normals`)."""
    from ..methods import ADMISSIBLE, INADMISSIBLE

    r = na.fixed_point(f, 0.0)
    na.dead_load = (f, r)
    if r.status == ADMISSIBLE:
        return "admissible", np.maximum(r.x[na.system.layout.normal], 0.0) / \
            na.cv.scaling.force
    if r.status == INADMISSIBLE:
        return "inadmissible", None
    return "undecided", x0_normals(na)


def _damped(beta: float, best: float, since: int, change: float
            ) -> tuple[float, float, int]:
    """Damping where the change stops falling (a cycle on the optimal face): the step
    ``beta`` is halved after STALL steps without a new smallest change ``best``
    (``since`` counts them), down to MIN_DAMPING."""
    if change < best:
        return beta, change, 0
    since += 1
    if since >= STALL and beta > MIN_DAMPING:
        return 0.5 * beta, best, 0
    return beta, best, since


def x0_normals(na: Any) -> np.ndarray | None:
    """The normal forces (scaled) of the elastic state X0 under the dead load, with the
    no-tension law imposed (its least-energy state with the normal links alone, the
    start of the seed's procedure), from a
    :class:`~rigidblocks.analyses.nonassociative.ConvexNonAssociative`."""
    c = na.contacts
    x0, _ = na.solve_capped(np.full(c.n_joints, math.inf), 0.0, np.zeros(c.n_points))
    if x0 is None:
        x0 = na.elastic(0.0)
    return None if x0 is None else np.maximum(x0[na.system.layout.normal], 0.0)


def certificate(cv: ConvexMethod, f: float, lam: float, x: np.ndarray
                ) -> tuple[float, float]:
    """(equilibrium residual, breach of the Coulomb laws with the state's own normal
    forces), both relative to the largest force of the state ``x`` (scene units) at
    multiplier ``lam``, or to the largest load on a block where that is larger (a block
    lifted off its base at lambda* = 1 has no forces but round-off, of which its
    residual 9e-5 read as a breach of 1): the a-posteriori check of a fixed point."""
    from ..problems.formulation import joint_violations

    sysm = cv.system
    scale = max(float(np.abs(x).max(initial=0.0)), cv.scaling.force)
    res = sysm.A @ x + sysm.dead + lam * sysm.live
    prob, jr = build_max_load(sysm, cv.scaling, cv.f_joint(f), cv.pyramid)
    z = np.concatenate([x / cv.scaling.force, [lam]])
    v = joint_violations(prob, jr, z, cv.contacts.n_joints)
    return (float(np.abs(res).max(initial=0.0)) / scale,
            float(v.max(initial=0.0)) * cv.scaling.force / scale)
