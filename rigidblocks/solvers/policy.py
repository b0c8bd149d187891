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
  once where a search needs it, :data:`FINER_SETTINGS`: :meth:`Runner.attempt`);
* **retries**: a solve that ends short of optimal is retried once with
  :data:`REFINE_SETTINGS` (stronger regularisation, refined KKT solves; not after
  :data:`REFINE_WITHIN` iterations or more), then, if the
  tight tolerances were out of reach, at :data:`NEAR_TIGHT_SETTINGS` (where later tight
  solves of the same runner start) and at the back end's defaults. Clarabel is given
  the next of those settings with each solve: where its iteration stalls, or ends, with
  an iterate that meets their tolerances, that is the next solve's answer
  (:mod:`~rigidblocks.solvers.clarabel_backend`), and that solve is not needed;
* **ladders**: which of these settings and retries a solve climbs through is declared
  once per intent (:class:`Ladder`): :data:`VERDICT` (the relaxations), :data:`VALUE`
  and :data:`FINER_VALUE` (lambda*), :data:`CONFIRMATION` (a verdict near its
  threshold), :data:`STATE` (the least-energy QP) and :data:`ESTIMATE` (the back end's
  defaults);
* **verification**: every answer is checked against the problem itself before it is
  passed on (:func:`~rigidblocks.solvers.base.residuals`: an optimal answer's primal and
  dual residuals and duality gap, an infeasibility certificate's residual and margin)
  to :data:`VERIFY_TOL`. An answer that fails the check, or an infeasible or unbounded
  status without a certificate to check, is solved again by :data:`FALLBACK` at the
  tight settings; if that answer fails too, the result is returned with
  ``verified=False`` and its residuals, and the methods report the verdict as
  undecided with them (never as a verdict).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace
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
#: user tolerances looser than this are noted in results (verdicts compare with 1e-9)
LOOSE_TOL = 1e-9
_DONE = (OPTIMAL, INFEASIBLE, UNBOUNDED)
#: largest residual (relative, see :func:`~rigidblocks.solvers.base.residuals`) of a
#: verified answer: above what Clarabel leaves at its defaults (1.5e-7 on the corbel
#: dome's relaxation at f = 1, where the tight tolerances are out of its reach), two
#: orders below what SCS leaves at its defaults (1e-4)
VERIFY_TOL = 1e-6
#: smallest relative margin -b'y of a verified infeasibility certificate
CERT_MARGIN = 1e-9


@dataclass(frozen=True)
class Ladder:
    """The settings a solve climbs through for one intent (:meth:`Runner.run`): the
    retries of the module docstring, declared once per intent.

    ``tight``: first at :data:`TIGHT_SETTINGS` (at :data:`NEAR_TIGHT_SETTINGS` once
    those were out of the back end's reach), then at 1e-9, then at the back end's
    defaults; else at the defaults alone. ``value``: a number is read from the answer:
    the tight rungs take :data:`VALUE_SETTINGS` (retried once without them) and are not
    stopped where they stall with an iterate that meets the next rung's tolerances.
    ``finer``: one checked solve at :data:`FINER_SETTINGS` first
    (:meth:`Runner.attempt`). ``refine``: an end short of optimal within
    :data:`REFINE_WITHIN` iterations is retried at :data:`REFINE_SETTINGS`.
    ``confirm``: at the back end's entry of :data:`CONFIRM_BY` (:meth:`Runner.confirm`).
    Every answer is checked, whatever the ladder (module docstring)."""

    intent: str
    tight: bool = False
    value: bool = False
    finer: bool = False
    refine: bool = True
    confirm: bool = False

    @property
    def stall(self) -> bool:
        """Whether a solve is stopped where it stalls with an iterate that meets the next
        rung's tolerances (not for a value: see :data:`VALUE`)."""
        return not self.value


#: a verdict against a threshold (the relaxations): tight, refined, stopped where stalled
VERDICT = Ladder("verdict", tight=True)
#: a number read from the answer (lambda* from the max-load LP): tight with the finer
#: KKT regularisation, never stopped where stalled (on the 20,093- and 50,065-block walls
#: lambda* so stopped at 1e-9 was 1.3e-3 and 4.8e-3 below the 1e-10 answer)
VALUE = Ladder("value", tight=True, value=True)
#: the same, at FINER_SETTINGS first: the max-load LPs of a search whose values
#: VALUE_SETTINGS resolve too coarsely
FINER_VALUE = Ladder("value", tight=True, value=True, finer=True)
#: a verdict left near its threshold, solved again tighter
CONFIRMATION = Ladder("confirmation", confirm=True)
#: the least-energy force state: the back end's defaults, solved once (where the
#: interior-point iteration stalls near a limit, a refined retry stalls too: the
#: 5,006-block wall at f*, AlmostSolved after 200 iterations twice)
STATE = Ladder("state", refine=False)
#: an estimate at the back end's defaults, with the refined retry: the first max-load LP
#: of a search (far from f* as a rule), a bound on the forces of a state
ESTIMATE = Ladder("estimate")


def ladder_of(tight: bool = False, stall: bool = True, refine: bool = True,
              confirm: bool = False) -> Ladder:
    """The ladder of a solve asked for by flags: :data:`CONFIRMATION` (``confirm``),
    :data:`VERDICT` (``tight``), :data:`VALUE` (``tight`` without ``stall``),
    :data:`ESTIMATE`, or :data:`STATE` (without ``refine``); a tight one without
    ``refine`` is that ladder without its refined retry."""
    if confirm:
        return CONFIRMATION
    if not tight:
        return ESTIMATE if refine else STATE
    ladder = VERDICT if stall else VALUE
    return ladder if refine else replace(ladder, refine=False)


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

    def run(self, problem: ConicProblem, what: str, ladder: Ladder = ESTIMATE,
            verify: bool = True) -> SolverResult:
        """Solve ``problem`` (named ``what`` in errors) up the rungs of ``ladder``:
        optimal, infeasible or unbounded; anything else raises :class:`SolverFailure`
        with the back end's status. With ``verify`` the answer is checked (module
        docstring): a failed check is solved again by :data:`FALLBACK` at the tight
        tolerances, and what still fails comes back ``verified=False``."""
        if ladder.confirm:
            return self.confirm(problem, what)
        if ladder.finer:
            res = self.attempt(problem, what, FINER_SETTINGS)
            if res is not None and res.status in (OPTIMAL, INFEASIBLE) and res.verified:
                return res
        if self.progress is not None:
            self.progress.stage = f"{what} problem"
        check = verify and self.verify
        res = None
        try:
            res = self._run(problem, what, ladder, self.solver, self.settings)
        except SolverFailure as exc:
            if not check or self.solver == FALLBACK:
                raise
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
            again = verified(problem, self._run(problem, what, replace(ladder, tight=True),
                                                FALLBACK, {}))
        except SolverFailure:
            if res is None:
                raise
            return res
        self.rejected.append(f"the {what} problem ({rejected})")
        return replace(again, residuals={**again.residuals, "rejected": rejected})

    def _certified(self, problem: ConicProblem, what: str,
                   res: SolverResult) -> SolverResult:
        """An infeasible or unbounded answer of this runner's back end given without its
        certificate, with the one the same back end finds for it
        (:func:`~rigidblocks.solvers.base.certificate_problem`: a negative optimum),
        else as it is."""
        missing = (res.status == INFEASIBLE and res.y is None
                   or res.status == UNBOUNDED and res.z is None)
        # Clarabel's statuses come with its own certificate tests (:func:`verified`)
        cp = certificate_problem(problem, res.status) \
            if missing and self.solver != FALLBACK else None
        if cp is None:
            return res
        try:
            ans = self._run(cp, f"{what} certificate", VERDICT, self.solver, self.settings)
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
        extra = settings.get(self.solver)
        if not extra or self.solver not in TIGHT_SETTINGS:
            return None
        if self.progress is not None:
            self.progress.stage = f"{what} problem"
        res = self._solve(problem, self.solver,
                          {**TIGHT_SETTINGS[self.solver], **extra, **self.settings})
        return verified(problem, res) if res.status in _DONE else res

    def confirm(self, problem: ConicProblem, what: str) -> SolverResult:
        """A tighter, checked solve of a problem whose answer left a verdict near its
        threshold, by this runner's back end at its entry of :data:`CONFIRM_BY` (the
        tight solve again where it has none: HiGHS' simplex answers with a vertex);
        Clarabel's answer (the policy's re-solve, noted) where the back end's own fails
        its check."""
        extra = CONFIRM_BY.get(self.solver)
        if extra is None:
            return self.run(problem, what, VERDICT)
        # Clarabel confirms at its confirming settings alone, whatever the user's
        own = {} if self.solver == FALLBACK else self.settings
        res = self._solve(problem, self.solver, {**own, **extra})
        if res.status not in _DONE:
            res = self._run(problem, what, VERDICT, self.solver, own)
        res = verified(problem, res)
        if res.verified or self.solver == FALLBACK:
            return res
        return self.run(problem, what, VERDICT)

    def _run(self, problem: ConicProblem, what: str, ladder: Ladder, solver: str,
             base: dict) -> SolverResult:
        """The rungs of ``ladder`` with ``solver`` on top of the settings ``base``."""
        tight, stall = ladder.tight, ladder.stall
        if problem.P is not None and solver in LP_ONLY:
            solver, base = FALLBACK, {}
        settings = base
        near = NEAR_TIGHT_SETTINGS.get(solver) if tight else None
        value = VALUE_SETTINGS.get(solver, {}) if tight and not stall and \
            solver not in self.value_out_of_reach else {}
        if tight and solver in TIGHT_SETTINGS:
            settings = {**TIGHT_SETTINGS[solver], **value, **base}
            if near and solver in self.out_of_reach:
                settings, near = {**near, **value, **base}, None
        # the solve that follows where these settings are out of reach, given to the back
        # end: Clarabel stops where it stalls with an iterate that meets its tolerances
        after = None if not stall else {**near, **base} if near else (
            base if settings is not base else None)
        res = self._solve(problem, solver, settings, after)
        refine = REFINE_SETTINGS.get(solver, {})
        if (res.status not in _DONE and ladder.refine and refine
                and res.iterations < REFINE_WITHIN
                and not refine.keys() & base.keys()):
            # not given the next solve: its regularised iterates are not the ones that
            # solve would go through (the extruded 1,009-block wall near f*: one that met
            # 1e-9 after 73 iterations breached the joint laws by 1.8e-5, the 1e-9
            # solve's answer by 3.8e-6, under the threshold of 3.9e-6)
            # a solve with VALUE_SETTINGS is retried without them first (the max-load
            # LP of a 1,009-block wall at f = 1 - 1e-10: AlmostSolved after 44
            # iterations with them, Solved after 43 without, after 196 refined)
            plain = {k: v for k, v in settings.items() if k not in value or k in base}
            for retry_settings in ([plain] if value else []) + [{**plain, **refine}]:
                again = self._solve(problem, solver, retry_settings)
                res = again if again.status in _DONE or not res.next_met else res
                if res.status in _DONE:
                    if retry_settings is plain:
                        self.value_out_of_reach.add(solver)
                    break
        res = _settled(res)
        if res.next_met and near:
            self.out_of_reach.add(solver)
        if res.status not in _DONE and near:
            self.out_of_reach.add(solver)
            # near is set only with tight settings: the defaults' solve follows it
            res = _settled(self._solve(problem, solver, {**near, **value, **base},
                                       base if stall else None))
        if res.status not in _DONE and settings is not base:
            # the tight tolerances were out of reach: the back end's defaults decide
            res = self._solve(problem, solver, base)
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
           "VERIFY_TOL", "Ladder", "Runner", "check_solver", "describe", "ladder_of",
           "verified"]
