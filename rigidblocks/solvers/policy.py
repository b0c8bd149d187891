"""Solver policy: what each back end can do, the settings a verdict needs, and retries.

The analyses ask for a solve of a problem and get either a canonical result
(optimal, infeasible, unbounded) or a :class:`~rigidblocks.errors.SolverFailure`; how the
back end is driven to that answer is decided here, in one place:

* **capabilities**: LP-only back ends hand quadratic problems (the force-state QP) to
  :data:`FALLBACK`;
* **tight settings**: the relaxations decide verdicts by comparing a residual with 1e-9
  of the largest force, so their solves run at :data:`TIGHT_SETTINGS` (tolerance 1e-10)
  where a back end's defaults are looser, and those whose answer is read as a number
  (lambda*) with the finer KKT regularisation of :data:`VALUE_SETTINGS` (or, tried
  once where a search needs it, :data:`FINER_SETTINGS`: :data:`FINER_FIRST`);
* **rungs and ladders**: a solve climbs the rungs of the ladder of its intent
  (:class:`Ladder`: :data:`VERDICT` for the relaxations, :data:`VALUE` and
  :data:`FINER_VALUE` for lambda*, :data:`CONFIRMATION` for a verdict near its
  threshold, :data:`STATE` for the least-energy QP, :data:`ESTIMATE` at the back end's
  defaults), in order, until one answers. Each rung (:class:`Rung`) is declared once,
  above the ladders, with its settings and the condition of it: :data:`TIGHT` (or
  :data:`TIGHT_VALUE`), the retries :data:`WITHOUT_VALUE` and :data:`REFINED` (within
  :data:`REFINE_WITHIN` iterations), :data:`NEAR_TIGHT` (or :data:`NEAR_TIGHT_VALUE`;
  where the runner's later tight rungs start), :data:`DEFAULTS`, :data:`FINER_FIRST`,
  :data:`CONFIRMING`. Clarabel is given the next rung's settings with a rung that
  stops where it stalls: where its iteration stalls, or ends, with an iterate that
  meets their tolerances, that is the next rung's answer
  (:mod:`~rigidblocks.solvers.clarabel_backend`), and that solve is not needed;
* **verification**: every answer is checked against the problem itself before it is
  passed on (:func:`~rigidblocks.solvers.base.residuals`: an optimal answer's primal and
  dual residuals and duality gap, an infeasibility certificate's residual and margin)
  to :data:`VERIFY_TOL`. An answer that fails the check, or an infeasible or unbounded
  status without a certificate to check, is solved again by :data:`FALLBACK` up the
  tight rungs of its ladder (``Ladder.again``); if that answer fails too, the result
  is returned with ``verified=False`` and its residuals, and the methods report the
  verdict as undecided with them (never as a verdict). A linear program on which
  :data:`FALLBACK` itself fails and which :data:`RESCUE` (HiGHS's simplex) proves
  infeasible or unbounded, its certificate checked, has that answer, noted as a
  rejected one; anything else is reported as the failure.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from functools import partial
from typing import Any

from ..errors import InputError, SolverFailure
from .base import (
    INFEASIBLE,
    OPTIMAL,
    UNBOUNDED,
    ConicProblem,
    SolverResult,
    certificate_problem,
    normalised,
    residuals,
)
from .registry import SOLVERS, solve

#: tolerances of the verdict-deciding solves (the relaxations, the max-load LP)
RELAX_SETTINGS = {"tol_gap_abs": 1e-10, "tol_gap_rel": 1e-10, "tol_feas": 1e-10}
#: SCS (a first-order method, defaults 1e-4) at tolerances that bring its answers within
#: the check of :data:`VERIFY_TOL` on the catalogue (docs/methods.md gives the figures):
#: at 1e-8 every answer passes (at the defaults 12 of 34 runs did); 1e-9 took 111 s for
#: f* of the 106-block wall at load factor 1 (0.14 s at 1e-8), the same f*
SCS_TIGHT = {"eps_abs": 1e-8, "eps_rel": 1e-8, "max_iters": 100_000}
#: the same for each back end whose defaults are looser than the verdict threshold
TIGHT_SETTINGS = {
    "clarabel": RELAX_SETTINGS,
    "cvxpy-highs": {"primal_feasibility_tolerance": 1e-10,
                    "dual_feasibility_tolerance": 1e-10},
    "cvxpy-clarabel": RELAX_SETTINGS,
    "scs": SCS_TIGHT,
    "cvxpy-scs": SCS_TIGHT,
}
#: the next tolerances short of a back end's defaults, where TIGHT_SETTINGS are out of
#: its reach at the scene's size (the relaxation of a 20,093-block wall at f = 1: no
#: answer after 152 Clarabel iterations at 1e-10, an answer after 88 at 1e-9); once
#: tried, a :class:`Runner`'s later tight solves start there
NEAR_TIGHT_SETTINGS = {"clarabel": {"tol_gap_abs": 1e-9, "tol_gap_rel": 1e-9,
                                    "tol_feas": 1e-9}}
#: KKT regularisation of the tight solves whose answer is read as a number (lambda*,
#: the :data:`VALUE` ladder): Clarabel's static regularisation (default 1e-8)
#: bounds the dual residual its answers reach, and the dual residual, times forces of
#: thousands of block loads, the accuracy of the objective. The max-load LP of a
#: 1,009-block wall at f = 1.18372: lambda* 0.9999956 with the default (dual residual
#: 1.9e-8), 1.0000005 with 1e-10 (7.8e-10), HiGHS' simplex 1.0000009; on the 5,006-block
#: wall at f = 1.25, 0.9997980 (9.1e-8) and 1.0002615 (9.8e-10), where the relaxation
#: certifies an admissible state at lambda = 1 below f = 1.24977. The relaxations' LPs
#: do not take it (Clarabel ends them with InsufficientProgress or AlmostSolved at 1e-9
#: to 1e-12).
VALUE_SETTINGS = {"clarabel": {"static_regularization_constant": 1e-10}}
#: finer still, for the max-load LPs of a search whose values VALUE_SETTINGS resolve too
#: coarsely (:meth:`Runner.attempt`; the one solve that fails is followed by the usual
#: one). Out of reach on small problems, of use on large ones: the max-load LP of a
#: 1,009-block wall at f = 1 ends AlmostSolved after 41 iterations (Solved after 47 at
#: 1e-10); of a 5,006-block wall at f = 1.25, 75 iterations with dual residual work
#: 5.5e-6 (78 and 9.4e-6 at 1e-10); of a 20,093-block wall at f = 1.28, 110 iterations
#: with 5.2e-5 (about 95 and 2.9e-4 at 1e-10)
FINER_SETTINGS = {"clarabel": {"static_regularization_constant": 1e-11}}
#: retry settings when a solve ends short of optimal: KKT systems regularised and refined
#: further. Where the interior-point iteration is near-degenerate a rounding decides
#: between "Solved" and "AlmostSolved" (the max-load SOCP of the extruded stocky arch with
#: glued pieces, tests/test_extrude_all.py, shifted by 1e-12 or by (3, 2)); a static
#: regularisation of 1e-7 (default 1e-8) with refined linear solves settles it.
REFINE_SETTINGS = {"clarabel": {"static_regularization_constant": 1e-7,
                                "iterative_refinement_reltol": 1e-14,
                                "iterative_refinement_abstol": 1e-14}}
#: a solve that ended short of optimal after this many iterations is not retried with
#: REFINE_SETTINGS: the retries that settle a rounding follow failures within a few
#: dozen iterations (the glued stocky arch: AlmostSolved after 12, Solved after 14 with
#: them), while at scale a failure after 109-152 iterations at 1e-10 was followed by a
#: refined retry that also failed, after 200 (the extruded 5,006-block wall, 204 s; the
#: 20,093-block wall, 229 s), before the 1e-9 solve that answered
REFINE_WITHIN = 100
#: settings of a confirming solve (a verdict near its threshold): Clarabel two orders
#: tighter than RELAX_SETTINGS, with refined KKT solves
CONFIRM_SETTINGS = {"tol_gap_abs": 1e-12, "tol_gap_rel": 1e-12, "tol_feas": 1e-12,
                    "tol_ktratio": 1e-9, "max_iter": 400,
                    "iterative_refinement_reltol": 1e-14,
                    "iterative_refinement_abstol": 1e-14}
#: the confirming settings by back end (:meth:`Runner.confirm`)
CONFIRM_BY = {"clarabel": CONFIRM_SETTINGS, "cvxpy-clarabel": CONFIRM_SETTINGS,
              "osqp": {"eps_abs": 1e-12, "eps_rel": 1e-12},
              "cvxpy-osqp": {"eps_abs": 1e-12, "eps_rel": 1e-12, "polishing": True},
              "scs": {**SCS_TIGHT, "eps_abs": 1e-10, "eps_rel": 1e-10},
              "cvxpy-scs": {**SCS_TIGHT, "eps_abs": 1e-10, "eps_rel": 1e-10}}
#: back ends that solve linear programs only
LP_ONLY = ("highs",)
#: the back end that takes the problems an LP-only back end cannot
FALLBACK = "clarabel"
#: the back end that takes a linear program on which FALLBACK failed
RESCUE = "highs"


class Rejection(str):
    """An entry of :attr:`Runner.rejected`: the rejected answer's text, and the back end
    that answered the problem again (``again_by``; None: the usual one, FALLBACK or
    the next settings of the ladder). A plain string appended there reads as None."""

    again_by: str | None

    def __new__(cls, text: str, again_by: str | None = None) -> Rejection:
        obj = super().__new__(cls, text)
        obj.again_by = again_by
        return obj
#: user tolerances looser than this are noted in results (verdicts compare with 1e-9)
LOOSE_TOL = 1e-9
_DONE = (OPTIMAL, INFEASIBLE, UNBOUNDED)
#: largest residual (relative, see :func:`~rigidblocks.solvers.base.residuals`) of a
#: verified answer: above what Clarabel leaves at its defaults (1.5e-7 on the corbel
#: dome's relaxation at f = 1, where the tight tolerances are out of its reach), two
#: orders below what SCS leaves at its defaults (1e-4)
VERIFY_TOL = 1e-6
#: smallest relative margin of a verified infeasibility certificate (-b'y) or unbounded
#: ray (-c'd), :func:`~rigidblocks.solvers.base.residuals`: ten times the tolerance at
#: which a state counts as admissible (ADMISSIBLE_TOL, 1e-9), below which "no state" and
#: "a state" are one answer to round-off. With 1e-9, HiGHS's maximum-load
#: LP of the inclined corbel arch at f = 0.7651297, 4.8e-9 above its f*, was infeasible
#: by a margin of 1.4e-9 (its certificate exact to 1e-15) while `check` stood there:
#: `load` said UNSTABLE; now Clarabel answers, lambda* = 0
CERT_MARGIN = 1e-8


@dataclass(frozen=True)
class _At:
    """Where a climb starts: the back end, the settings under every rung (``base``: the
    user's), whether the runner learnt that its tight tolerances are out of reach
    (``far``, where it has NEAR_TIGHT_SETTINGS) and its VALUE_SETTINGS unless those are
    (``value``)."""

    solver: str
    base: dict
    far: bool
    value: dict


@dataclass(frozen=True)
class Rung:
    """One solve of a ladder: its settings for a climb (``settings(at, before)``, with
    ``before`` those of the last rung solved that is not a retry), None where the rung
    does not apply to the climb (the back end has no such settings, or the rung's
    condition excludes it). A climb solves its rungs in order until one answers.

    ``stall``: Clarabel is given the settings of the next rung that is not a retry and
    stops where it stalls with an iterate that meets them; a failure whose last iterate
    meets them is the next rung's answer, without its solve. ``retry``: a retry of the
    last rung solved that is not one, only after a failure of it within
    :data:`REFINE_WITHIN` iterations; never given the next rung's settings (a failure of
    the rung retried whose last iterate meets them is kept over the retry's failure).
    ``alone``: a checked solve before the ladder's
    others (:meth:`Runner.attempt`), whose answer stands only where it is a checked
    optimum or infeasibility; not climbed again where an answer is solved again by
    :data:`FALLBACK`. ``tight``: at the tight tolerances. ``reached`` and ``answered``:
    the set of the :class:`Runner` to which the back end is added where the rung is
    reached (the rungs before it did not answer at their own tolerances) or answers."""

    name: str
    settings: Callable[[_At, dict | None], dict | None]
    stall: bool = False
    retry: bool = False
    alone: bool = False
    tight: bool = False
    reached: str = ""
    answered: str = ""


def _tight(at: _At, before: dict | None, value: bool = False) -> dict | None:
    """TIGHT_SETTINGS (NEAR_TIGHT_SETTINGS once out of reach), with ``value`` the
    back end's VALUE_SETTINGS, the user's settings on top; None without them."""
    if at.solver not in TIGHT_SETTINGS:
        return None
    start = NEAR_TIGHT_SETTINGS[at.solver] if at.far else TIGHT_SETTINGS[at.solver]
    return {**start, **(at.value if value else {}), **at.base}


def _near(at: _At, before: dict | None, value: bool = False) -> dict | None:
    """NEAR_TIGHT_SETTINGS after a rung at TIGHT_SETTINGS, as :func:`_tight`."""
    near = NEAR_TIGHT_SETTINGS.get(at.solver)
    if near is None or at.far or at.solver not in TIGHT_SETTINGS:
        return None
    return {**near, **(at.value if value else {}), **at.base}


def _defaults(at: _At, before: dict | None) -> dict:
    return at.base


def _refinable(at: _At, before: dict | None) -> bool:
    """Whether a retry applies: after a rung, with REFINE_SETTINGS for the back end,
    none of which the user set."""
    refine = REFINE_SETTINGS.get(at.solver, {})
    return before is not None and bool(refine) and not refine.keys() & at.base.keys()


def _plain(at: _At, settings: dict) -> dict:
    """``settings`` without the VALUE_SETTINGS the user did not set."""
    return {k: v for k, v in settings.items() if k not in at.value or k in at.base}


def _without_value(at: _At, before: dict | None) -> dict | None:
    return _plain(at, before) if at.value and _refinable(at, before) else None


def _refined(at: _At, before: dict | None) -> dict | None:
    if not _refinable(at, before):
        return None
    return {**_plain(at, before), **REFINE_SETTINGS[at.solver]}


def _over_tight(by: dict, at: _At, before: dict | None = None) -> dict | None:
    """The tight settings with the back end's entry of ``by`` on top, the user's last;
    None where it has no such entry."""
    extra = by.get(at.solver)
    if not extra or at.solver not in TIGHT_SETTINGS:
        return None
    return {**TIGHT_SETTINGS[at.solver], **extra, **at.base}


def _confirming(at: _At, before: dict | None) -> dict | None:
    extra = CONFIRM_BY.get(at.solver)
    return None if extra is None else {**at.base, **extra}


#: TIGHT_SETTINGS (NEAR_TIGHT_SETTINGS once those were out of the back end's reach),
#: stopped where it stalls with an iterate that meets the next rung's tolerances
TIGHT = Rung("tight", _tight, stall=True, tight=True)
#: the same with VALUE_SETTINGS (unless those were out of reach), not stopped where it
#: stalls (on the 20,093- and 50,065-block walls lambda* so stopped at 1e-9 was 1.3e-3
#: and 4.8e-3 below the 1e-10 answer)
TIGHT_VALUE = Rung("tight, for a value", partial(_tight, value=True), tight=True)
#: a retry of the rung before without its VALUE_SETTINGS, after a failure of it within
#: REFINE_WITHIN iterations, where REFINED applies (the max-load LP of a 1,009-block
#: wall at f = 1 - 1e-10: AlmostSolved after 44 iterations with them, Solved after 43
#: without, after 196 refined); where it answers, later solves go without them
WITHOUT_VALUE = Rung("without VALUE_SETTINGS", _without_value, retry=True,
                     answered="value_out_of_reach")
#: a retry of the rung before (without VALUE_SETTINGS) at REFINE_SETTINGS, after a
#: failure of it within REFINE_WITHIN iterations, unless the user set one of them; not
#: given the next rung's settings: its regularised iterates
#: are not the ones that rung goes through (the extruded 1,009-block wall near f*: one
#: that met 1e-9 after 73 iterations breached the joint laws by 1.8e-5, the 1e-9 solve's
#: answer by 3.8e-6, under the threshold of 3.9e-6)
REFINED = Rung("refined", _refined, retry=True)
#: NEAR_TIGHT_SETTINGS after TIGHT_SETTINGS, stopped where it stalls with an iterate
#: that meets the back end's defaults; once reached, the runner's later tight rungs
#: start there
NEAR_TIGHT = Rung("near-tight", _near, stall=True, reached="out_of_reach")
#: the same with VALUE_SETTINGS, not stopped where it stalls
NEAR_TIGHT_VALUE = Rung("near-tight, for a value", partial(_near, value=True),
                        reached="out_of_reach")
#: the back end's defaults (under the user's settings, as every rung): where the
#: tighter rungs before were out of reach, they decide
DEFAULTS = Rung("defaults", _defaults)
#: FINER_SETTINGS on top of TIGHT_SETTINGS, checked, alone (:meth:`Runner.attempt`)
FINER_FIRST = Rung("finer first", partial(_over_tight, FINER_SETTINGS), alone=True,
                   tight=True)
#: the back end's entry of CONFIRM_BY (Clarabel at it alone, whatever the user's
#: settings: :meth:`Runner.confirm`)
CONFIRMING = Rung("confirming", _confirming)


@dataclass(frozen=True)
class Ladder:
    """The rungs a solve climbs for one intent (:meth:`Runner.run`), in order, each
    where it applies (:class:`Rung`), until one answers; a failure of every rung that
    applies raises :class:`SolverFailure` with the last one's status. ``again``: the
    rungs :data:`FALLBACK` climbs where an answer fails its check, or the back end fails
    (module docstring); None: ``rungs``. Every answer is checked, whatever the
    ladder."""

    intent: str
    rungs: tuple[Rung, ...]
    again: tuple[Rung, ...] | None = None

    @property
    def tight(self) -> bool:
        """Whether the ladder has a rung at the tight tolerances."""
        return any(r.tight for r in self.rungs)

    @property
    def stall(self) -> bool:
        """Whether a rung is stopped where it stalls with an iterate that meets the next
        rung's tolerances."""
        return any(r.stall for r in self.rungs)

    @property
    def refine(self) -> bool:
        """Whether the ladder has retries."""
        return any(r.retry for r in self.rungs)

    def without_retries(self) -> Ladder:
        """The same ladder without its retries."""
        def bare(rungs: tuple[Rung, ...] | None) -> tuple[Rung, ...] | None:
            return None if rungs is None else tuple(r for r in rungs if not r.retry)
        return replace(self, rungs=bare(self.rungs), again=bare(self.again))


#: a verdict against a threshold (the relaxations)
VERDICT = Ladder("verdict", (TIGHT, REFINED, NEAR_TIGHT, DEFAULTS))
#: a number read from the answer (lambda* from the max-load LP)
VALUE = Ladder("value", (TIGHT_VALUE, WITHOUT_VALUE, REFINED, NEAR_TIGHT_VALUE, DEFAULTS))
#: the same, at FINER_SETTINGS first: the max-load LPs of a search whose values
#: VALUE_SETTINGS resolve too coarsely
FINER_VALUE = Ladder("value", (FINER_FIRST, *VALUE.rungs))
#: a verdict left near its threshold, solved again tighter, then the verdict's rungs;
#: checked, and where the back end's answer fails the check (or it has no entry in
#: CONFIRM_BY) the verdict's ladder (:meth:`Runner.confirm`)
CONFIRMATION = Ladder("confirmation", (CONFIRMING, *VERDICT.rungs))
#: the least-energy force state: the back end's defaults, solved once (where the
#: interior-point iteration stalls near a limit, a refined retry stalls too: the
#: 5,006-block wall at f*, AlmostSolved after 200 iterations twice)
STATE = Ladder("state", (DEFAULTS,), again=(TIGHT, NEAR_TIGHT, DEFAULTS))
#: an estimate at the back end's defaults, with the refined retry: the first max-load LP
#: of a search (far from f* as a rule), a bound on the forces of a state
ESTIMATE = Ladder("estimate", (DEFAULTS, REFINED), again=VERDICT.rungs)


def ladder_of(tight: bool = False, stall: bool = True, refine: bool = True,
              confirm: bool = False) -> Ladder:
    """The ladder of a solve asked for by flags: :data:`CONFIRMATION` (``confirm``),
    :data:`VERDICT` (``tight``), :data:`VALUE` (``tight`` without ``stall``),
    :data:`ESTIMATE`, or :data:`STATE` (without ``refine``); a tight one without
    ``refine`` is that ladder without its retries."""
    if confirm:
        return CONFIRMATION
    if not tight:
        return ESTIMATE if refine else STATE
    ladder = VERDICT if stall else VALUE
    return ladder if refine else ladder.without_retries()


def _steps(rungs: tuple[Rung, ...], at: _At) -> list[tuple[Rung, dict, dict | None]]:
    """The rungs that apply to a climb from ``at`` (the checked ones alone aside), with
    their settings and, for those that stop where they stall, the next rung's."""
    steps, before = [], None
    for rung in rungs:
        settings = None if rung.alone else rung.settings(at, before)
        if settings is not None:
            steps.append((rung, settings))
            before = before if rung.retry else settings
    return [(rung, settings,
             next((s for r, s in steps[k + 1:] if not r.retry), None) if rung.stall else None)
            for k, (rung, settings) in enumerate(steps)]


def check_solver(name: str) -> str:
    """The back end's canonical name, or an :class:`InputError` naming the choices."""
    n = name.lower()
    if n in SOLVERS or n.startswith("cvxpy-"):
        return n
    raise InputError(f"unknown solver {name!r} (choose from {', '.join(SOLVERS)} "
                     "or cvxpy-NAME)")


@dataclass
class Runner:
    """Drives one back end through the policy above and counts the work done.

    ``n_solves``, ``solve_time`` (the back ends' own seconds) and ``iterations`` add up
    every solve, retries included.
    """

    solver: str = "clarabel"
    settings: dict = field(default_factory=dict)
    source: str = ""
    n_solves: int = 0
    solve_time: float = 0.0
    iterations: int = 0
    wall_time: float = 0.0
    #: an object with ``stage``, ``solves`` and ``iterations`` kept up to date (a
    #: progress line reads it), or None
    progress: Any = None

    #: check every answer (the setting ``verify``: False measures a back end alone)
    verify: bool = True
    #: answers of the back end that were rejected and solved again by FALLBACK
    rejected: list = field(default_factory=list)
    #: the back ends that answered a solve (optimal, infeasible or unbounded), in the
    #: order of their first answer: others than ``solver`` where an answer of it was
    #: rejected and solved again, where a problem is beyond its capabilities (a QP for
    #: an LP-only back end), or for a confirming solve
    answered_by: list = field(default_factory=list)
    #: back ends whose TIGHT_SETTINGS were out of reach: their tight solves start at
    #: NEAR_TIGHT_SETTINGS
    out_of_reach: set = field(default_factory=set)
    #: back ends whose VALUE_SETTINGS failed where the same solve without them did not:
    #: their later solves go without them (small problems: the max-load LP of the
    #: 19-block example wall fails with them at every f tried, AlmostSolved)
    value_out_of_reach: set = field(default_factory=set)

    def __post_init__(self) -> None:
        self.solver = check_solver(self.solver)
        self.settings = dict(self.settings or {})
        self.verify = bool(self.settings.pop("verify", self.verify))

    def loose_settings(self) -> list[str]:
        """User tolerance settings looser than the verdict threshold."""
        return sorted(k for k, v in self.settings.items()
                      if k.startswith("tol") and isinstance(v, int | float) and v > LOOSE_TOL)

    def _solve(self, problem: ConicProblem, solver: str, settings: dict,
               after: dict | None = None) -> SolverResult:
        t0 = time.perf_counter()
        res = solve(problem, solver, after=after, **settings)
        if solver not in self.answered_by and (res.status in _DONE or res.next_met):
            self.answered_by.append(solver)
        self.wall_time += time.perf_counter() - t0
        self.n_solves += 1
        self.solve_time += res.solve_time
        self.iterations += res.iterations
        if self.progress is not None:
            self.progress.solves = self.n_solves
            self.progress.iterations = self.iterations
        return res

    def record(self, solver: str, seconds: float, iterations: int) -> None:
        """Count a solve made outside :meth:`run` by ``solver`` (the non-associative
        limit iteration's warm-started simplex LPs,
        :mod:`rigidblocks.solvers.highs_warm`) with the others: the solves, their time
        and iterations, and the back ends that answered."""
        if solver not in self.answered_by:
            self.answered_by.append(solver)
        self.wall_time += seconds
        self.solve_time += seconds
        self.n_solves += 1
        self.iterations += iterations
        if self.progress is not None:
            self.progress.solves = self.n_solves
            self.progress.iterations = self.iterations

    @contextmanager
    def afresh(self) -> Iterator[None]:
        """The solves inside run as a fresh runner's would, without what the solves
        before learnt (``out_of_reach``, ``value_out_of_reach``), and what they learn is
        forgotten after them: for trials that must each run as a fresh analysis would
        (the non-associative friction's trials: the corbel dome's limit runs at f = 0.6
        do not settle in 200 steps without VALUE_SETTINGS, which the solves at f = 0.3
        before them found out of reach)."""
        saved = self.out_of_reach, self.value_out_of_reach
        self.out_of_reach, self.value_out_of_reach = set(), set()
        try:
            yield
        finally:
            self.out_of_reach, self.value_out_of_reach = saved

    def run(self, problem: ConicProblem, what: str, ladder: Ladder = ESTIMATE,
            verify: bool = True) -> SolverResult:
        """Solve ``problem`` (named ``what`` in errors) up the rungs of ``ladder``:
        optimal, infeasible or unbounded; anything else raises :class:`SolverFailure`
        with the back end's status. With ``verify`` the answer is checked (module
        docstring): a failed check is solved again by :data:`FALLBACK` up the ladder's
        ``again`` rungs, and what still fails comes back ``verified=False``."""
        if CONFIRMING in ladder.rungs:
            return self.confirm(problem, what)
        at = self._at(self.solver, self.settings)
        for rung in (r for r in ladder.rungs if r.alone):
            res = self._alone(problem, what, rung.settings(at, None))
            if res is not None and res.status in (OPTIMAL, INFEASIBLE) and res.verified:
                return res
        if self.progress is not None:
            self.progress.stage = f"{what} problem"
        check = verify and self.verify
        res = None
        try:
            res = self._climb(problem, what, ladder.rungs, self.solver, self.settings)
        except SolverFailure as exc:
            if not check:
                raise
            if self.solver == FALLBACK:
                return self._simplex_rescue(problem, what, ladder, exc)
            # another back end that fails: the default one answers, and it is noted
            rejected = f"{exc.solver} ended with status {exc.status}"
        else:
            if not check:
                return res
            res = verified(problem, self._certified(problem, what, res))
            if res.verified or (res.solver == FALLBACK and ladder.tight and not self.settings):
                return res
            rejected = f"{res.solver} {res.status}: {describe(res.residuals)}"
        try:
            again = verified(problem, self._climb(problem, what, ladder.again or ladder.rungs,
                                                  FALLBACK, {}))
        except SolverFailure:
            if res is None:
                raise
            return res
        self.rejected.append(Rejection(f"the {what} problem ({rejected})"))
        return replace(again, residuals={**again.residuals, "rejected": rejected})

    def _simplex_rescue(self, problem: ConicProblem, what: str, ladder: Ladder,
                        exc: SolverFailure) -> SolverResult:
        """A linear program on which the default back end failed, proven infeasible or
        unbounded by HiGHS's simplex (scipy's) with a certificate that passes its check,
        its failure in :attr:`rejected`; anything else raises that failure. Clarabel
        ends at MaxIterations on the inclined corbel arch's maximum-load LP at f =
        0.7651, just below its f*, where no state is admissible at any multiplier:
        `load` printed "solver failure" where HiGHS proves it UNSTABLE. An optimum of
        HiGHS is not taken: its accuracy is its tolerances' on the problem's scale (the
        4 x 4 wall at f = 1e6, where Clarabel ends AlmostSolved: 1.99999 against the
        closed form 2, its residuals within the check)."""
        if not problem.is_lp:
            raise exc
        try:
            again = self._climb(problem, what, ladder.again or ladder.rungs, RESCUE, {})
            again = verified(problem, self._certified(problem, what, again, RESCUE))
        except SolverFailure:
            raise exc from None
        if not again.verified or again.status == OPTIMAL:
            raise exc
        rejected = f"{exc.solver} ended with status {exc.status}; {RESCUE} answered it"
        self.rejected.append(Rejection(f"the {what} problem ({rejected})", RESCUE))
        return replace(again, residuals={**again.residuals, "rejected": rejected})

    def _certified(self, problem: ConicProblem, what: str, res: SolverResult,
                   solver: str | None = None) -> SolverResult:
        """An infeasible or unbounded answer of this runner's back end (or of
        ``solver``, at its defaults) given without its certificate, with the one the same
        back end finds for it (:func:`~rigidblocks.solvers.base.certificate_problem`: a
        negative optimum), else as it is."""
        solver, settings = (self.solver, self.settings) if solver is None else (solver, {})
        missing = (res.status == INFEASIBLE and res.y is None
                   or res.status == UNBOUNDED and res.z is None)
        # Clarabel's statuses come with its own certificate tests (:func:`verified`)
        cp = certificate_problem(problem, res.status) \
            if missing and solver != FALLBACK else None
        if cp is None:
            return res
        try:
            ans = self._climb(cp, f"{what} certificate", VERDICT.rungs, solver, settings)
        except SolverFailure:
            return res
        if ans.status != OPTIMAL or not ans.objective < 0:
            return res
        return replace(res, y=ans.z) if res.status == INFEASIBLE else replace(res, z=ans.z)

    def attempt(self, problem: ConicProblem, what: str,
                settings: dict) -> SolverResult | None:
        """One checked solve at the tight tolerances with this back end's entry of
        ``settings`` (a dict by back end, as :data:`FINER_SETTINGS`) on top, without
        retries or a stall stop; the answer, whatever its status (the caller solves
        again through :meth:`run` where it is not a checked optimum), or None where the
        back end has no such entry."""
        at = self._at(self.solver, self.settings)
        return self._alone(problem, what, _over_tight(settings, at))

    def _alone(self, problem: ConicProblem, what: str,
               settings: dict | None) -> SolverResult | None:
        """One solve of this runner's back end at ``settings`` (None: none), checked
        where it ends with an answer."""
        if settings is None:
            return None
        if self.progress is not None:
            self.progress.stage = f"{what} problem"
        res = self._solve(problem, self.solver, settings)
        return verified(problem, res) if res.status in _DONE else res

    def confirm(self, problem: ConicProblem, what: str) -> SolverResult:
        """A tighter, checked solve of a problem whose answer left a verdict near its
        threshold, up the rungs of :data:`CONFIRMATION` by this runner's back end
        (Clarabel at its confirming settings alone, whatever the user's); the verdict's
        :meth:`run` where the back end has no entry in :data:`CONFIRM_BY` (HiGHS'
        simplex answers with a vertex), or where its answer fails its check."""
        if CONFIRM_BY.get(self.solver) is None:
            return self.run(problem, what, VERDICT)
        own = {} if self.solver == FALLBACK else self.settings
        res = verified(problem, self._climb(problem, what, CONFIRMATION.rungs, self.solver,
                                            own))
        if res.verified or self.solver == FALLBACK:
            return res
        return self.run(problem, what, VERDICT)

    def _at(self, solver: str, base: dict) -> _At:
        """A climb by ``solver`` on top of ``base``, with what this runner learnt."""
        far = solver in self.out_of_reach and solver in NEAR_TIGHT_SETTINGS
        value = {} if solver in self.value_out_of_reach else VALUE_SETTINGS.get(solver, {})
        return _At(solver, base, far, value)

    def _learn(self, what: str, solver: str) -> None:
        """``solver`` added to the runner's set named ``what`` (if any: ``out_of_reach``,
        ``value_out_of_reach``)."""
        if what:
            getattr(self, what).add(solver)

    def _climb(self, problem: ConicProblem, what: str, rungs: tuple[Rung, ...],
               solver: str, base: dict) -> SolverResult:
        """The ``rungs`` with ``solver`` on top of the settings ``base`` (LP-only back
        ends hand a QP to :data:`FALLBACK` at its defaults), as :class:`Rung` says."""
        if problem.P is not None and solver in LP_ONLY:
            solver, base = FALLBACK, {}
        res = last = None
        for rung, settings, after in _steps(rungs, self._at(solver, base)):
            if rung.retry:
                if res.status not in _DONE and last.iterations < REFINE_WITHIN:
                    again = self._solve(problem, solver, settings)
                    res = again if again.status in _DONE or not res.next_met else res
                    self._learn(rung.answered if res.status in _DONE else "", solver)
                continue
            if res is not None and (res := _settled(res)).status in _DONE:
                # an answer that meets only this rung's tolerances reaches it
                self._learn(rung.reached if res.next_met else "", solver)
                break
            self._learn(rung.reached, solver)
            res = last = self._solve(problem, solver, settings, after)
        res = _settled(res)
        if res.status not in _DONE:
            raise SolverFailure(f"{res.solver} could not solve the {what} problem of "
                                f"{self.source or 'the scene'}: status {res.raw_status}",
                                res.solver, res.raw_status)
        return res


def _settled(res: SolverResult) -> SolverResult:
    """A failure whose last iterate meets the tolerances of the next solve
    (``next_met``) taken as that solve's answer, without the solve; anything else as
    is."""
    if res.status in _DONE or not res.next_met:
        return res
    return replace(res, status=OPTIMAL)


def verified(problem: ConicProblem, res: SolverResult) -> SolverResult:
    """``res`` with its residuals and whether they pass :data:`VERIFY_TOL`: an optimal
    answer by its primal and dual residuals and gap, an infeasible or unbounded one by
    its certificate (the duals, or a ray in ``z``); one without what it takes to check
    it fails unless Clarabel gave it (its statuses come with their own certificate tests). An
    optimal answer that fails with its duals as given passes with them normalised
    (:func:`~rigidblocks.solvers.base.normalised`) where they then pass: that answer
    is returned, with the dual residual before normalisation as ``normalised``."""
    def passes(r: dict) -> bool:
        return max(r["primal"], r["dual"], r["gap"]) <= VERIFY_TOL

    r = residuals(problem, res)
    if res.status == OPTIMAL and r:
        ok = passes(r)
        scaled = None if ok else normalised(problem, res)
        if scaled is not None:
            rs = residuals(problem, scaled)
            if passes(rs):
                return replace(scaled, residuals={**rs, "normalised": r["dual"]},
                               verified=True)
    elif res.status in (INFEASIBLE, UNBOUNDED) and r:
        ok = r["certificate"] <= VERIFY_TOL and r["margin"] > CERT_MARGIN
    else:
        ok = res.solver == FALLBACK
    return replace(res, residuals=r, verified=ok)


def describe(r: dict) -> str:
    """The residuals of :func:`verified` in words."""
    names = {"primal": "primal residual", "dual": "dual residual", "gap": "duality gap",
             "certificate": "certificate residual", "margin": "certificate margin"}
    parts = [f"{names[k]} {v:.1e}" for k, v in r.items() if k in names]
    if "rejected" in r:
        parts.append(f"answer rejected before: {r['rejected']}")
    return ", ".join(parts) or "nothing to check"


__all__ = ["CERT_MARGIN", "CONFIRMATION", "CONFIRM_SETTINGS", "ESTIMATE", "FALLBACK",
           "FINER_SETTINGS", "FINER_VALUE", "LP_ONLY", "REFINE_SETTINGS", "REFINE_WITHIN",
           "RELAX_SETTINGS", "STATE", "TIGHT_SETTINGS", "VALUE", "VALUE_SETTINGS", "VERDICT",
           "VERIFY_TOL", "Ladder", "Rejection", "Rung", "Runner", "check_solver", "describe",
           "ladder_of", "verified"]
