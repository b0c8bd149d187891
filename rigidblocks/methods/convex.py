"""The convex path: verdicts from the relaxation R(f, lambda), f* by Newton steps on R,
lambda* from one LP (SOCP in 3D), the force state from the least-energy QP.

The relaxations are scaled block by block (:meth:`Scaling.per_block`): each block's
rows by its own load, each joint's forces and law rows by its lighter block's load; the
max-load problem too where the blocks' loads span more than two orders.
Admissible iff the relaxation's own state breaches the joint laws and equilibrium by at
most 1e-9 of its largest scaled force (the interior-point solver's accuracy is relative
to the size of its solution); inadmissible iff the duals bound R above that; between the
two a tighter solve decides, or the verdict is undecided, as it is where the forces span
more orders than the solver can resolve (:data:`RESOLVE_LIMIT`). Every back end's answer
is checked by the solver policy. The relaxation is always feasible when the equilibrium
equations can be met, so it avoids the degenerate feasibility problems at the limit.
The problems come from
:mod:`rigidblocks.problems.formulation`; the back ends and their policy from
:mod:`rigidblocks.solvers`.
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, replace
from types import SimpleNamespace
from typing import Any

import numpy as np

from ..equilibrium import EquilibriumSystem, force_state, mechanism
from ..errors import InputError, SolverFailure
from ..problems.formulation import (
    Scaling,
    build_max_load,
    build_relaxation,
    energy_problem,
    joint_violations,
)
from ..results import ForceState
from ..scene.model import Scene
from ..solvers import INFEASIBLE, OPTIMAL, UNBOUNDED, Runner, SolverResult
from ..solvers.policy import FINER_SETTINGS, LP_ONLY, VERIFY_TOL, describe
from . import friction_rules, load_rules
from .base import (
    ADMISSIBLE,
    INADMISSIBLE,
    UNDECIDED,
    Limit,
    Method,
    Progress,
    Timings,
    Verdict,
    ranked_breaches,
)
from .engine import WIDE, Search, Trial, run
from .friction_rules import AMENDS, STEPS, STOPS, UNDECIDED_KINDS
from .vertex import vertex_dual

#: a relaxation below this fraction of the largest force of its state counts as zero
#: (interior-point residuals are relative to the size of the solution: a 30-course wall
#: carries 30 block weights at its base, and R carries round-off of that order)
ADMISSIBLE_TOL = 1e-9
#: the same where the tight tolerances were out of the solver's reach and it solves at
#: 1e-9 (:data:`~rigidblocks.solvers.policy.NEAR_TIGHT_SETTINGS`): ten times the
#: solver's tolerance, as ADMISSIBLE_TOL is to the tight 1e-10 (on the extruded
#: 5,006-block wall above f*, the states solved at 1e-9 breach the laws by 1.1e-9 to
#: 1.6e-9 of the largest force)
NEAR_ADMISSIBLE_TOL = 1e-8
#: the default accuracy of f* and lambda* (``rtol``: a number only where its certified
#: bracket is this narrow, relative): three significant figures, the tightest accuracy
#: at which every wall of the speed-accuracy chart gets a number (docs/methods.md: the
#: 20,051-block wall at load factor 0.2 reaches 1.1e-3 at its solver's resolution)
FRICTION_RTOL = 2e-3
#: absolute accuracy of the minimum friction: a structure that stands with f <= 1e-9
#: needs no friction (round-off keeps R(0) just above the threshold)
FRICTION_ATOL = 1e-9
#: the finest relative accuracy in f that the interior-point verdicts resolve: a
#: certified end is admissible to ADMISSIBLE_TOL of the largest force, coarser in f than
#: 1e-8 (the 3D box on a 20 degree slope asked for 1e-8 came out with a 1.2e-8 bracket
#: 1.06e-7 below tan 20 degrees; the extruded 106-block wall at 1e-7 certified an end
#: 5.6e-8 below f* = 1, within it). An inadmissibility certificate that holds only more
#: than this below f is no verdict (:meth:`ConvexMethod._certificate_checked`: the
#: 1,000-block wall's sits 6.9e-9 below f)
VERDICT_RTOL = 1e-7
#: slack (reference-force units) granted to the force-state QP at a limit state, where
#: the admissible set shrinks to a point and round-off would make it empty
STATE_SLACK = 1e-9
#: a verdict whose threshold ADMISSIBLE_TOL x (largest scaled force) exceeds this
#: (relative to the lightest blocks' loads) is undecided: the forces span more orders
#: than the solver's tolerance and double precision can resolve (a joint carrying a
#: million times the load of the lighter block it touches); above RESOLVE_NOTE (forces
#: 1e4 times those loads, beyond the base of a 100-course wall) the
#: verdict says how coarsely it resolves the lightest blocks
RESOLVE_LIMIT = 1e-3
RESOLVE_NOTE = 1e-5
#: in the search for f*, a relaxation whose value exceeds this many times the threshold,
#: and SPREAD_MARGIN times the work of its dual residual on its own state
#: (:attr:`Relaxation.spread`), is a lower point even where its dual bound cannot
#: certify it
CLEARLY = 10.0
#: the spread is an estimate (the optimal state is not known): on the extruded
#: 5,006-block wall at 1e-9, values of 1.13 and 0.14 times their spread came back where
#: the plane wall has an admissible state (R = 0.025 at f = 1.2500114, 8.4e-4 at
#: f = 1.2497654); below f* the values were 1.27 times it at f = 1.247, 18 and 330 times
#: it on the plane wall
SPREAD_MARGIN = 4.0
#: in the search for f* on lambda*(f), a tight solve whose value resolves f to more
#: than this fraction of :data:`WIDE` (its resolution over its slope) puts the later
#: ones at :data:`~rigidblocks.solvers.policy.FINER_SETTINGS` first: the
#: 20,093-block wall at f = 1.2877647 resolves lambda* to 1.2e-3 at VALUE_SETTINGS,
#: about 1e-3 in f, where the bracket takes about 1/8 + 1.5 times that
FINER_WHEN = 0.25
#: the share of an inadmissibility certificate (|g|_1, :func:`certificate_shift`)
#: that its friction rows must carry for the friction it holds at to be read: the
#: certificates of f* on the catalogue carry 1.0 to 2.0, those of a block that tips
#: under its load 1.6e-7 (round-off)
CERTIFICATE_FRICTION = 1e-3
#: beginning of the reason of a verdict undecided for that reason
FORCES_SPAN = "forces span"
#: an admissible state at a limit whose forces exceed this many times the loads of the
#: blocks they act on is noted: the limit is an ill-conditioned infimum (the forces grow
#: without bound as the limit is approached), not a value with moderate forces
FORCE_WARN = 1e4
#: forces of the state at f* found from lambda*(f) above FORCE_WARN are the structure's
#: scale, not an infimum's, where they grew from the first upper end's by at least this
#: many times less than an infimum's 1 / (f - f*) growth would
GROWTH_SPAN = 4.0
#: the note of a relaxation whose equilibrium equations have no solution
NO_EQUILIBRIUM = ("the equilibrium equations have no solution with these joints (the "
                  "scene is a mechanism)")


@dataclass(frozen=True, eq=False)
class Relaxation:
    """One relaxation solve: R(f), dR/df, and what the analyses read from it.

    ``R`` is the larger of the solver's r and the largest breach of the joint laws by its
    own state (per joint, relative to the joint's scale, see
    :meth:`~rigidblocks.problems.formulation.Scaling.per_block`); ``low`` the lower bound
    on R from the duals (the dual objective); ``residual`` the state's largest
    equilibrium residual (per-block units). ``zero``: the state itself is admissible to
    ``tol``; ``positive``: the dual bound certifies R > ``tol``; neither: undecided.
    """

    R: float | None  # None: the equilibrium equations have no solution
    slope: float
    res: SolverResult
    jr: Any
    prob: Any
    tol: float  # R <= tol counts as zero (ADMISSIBLE_TOL, or NEAR_ADMISSIBLE_TOL at 1e-9
    # solves, x the largest scaled force)
    f: float = math.nan
    low: float = math.inf
    residual: float = 0.0
    #: why the verdict cannot be decided ("" when it can)
    unresolved: str = ""
    #: how far the value may lie from the optimum by the duals' residual d: sum |d_j z_j|
    #: on the state z (an estimate: the optimal state is not known). On the extruded
    #: 5,006-block wall at 1e-9, R = 8.4e-4 (51 times the threshold) where a state of
    #: R = 0 exists (the plane wall's at f = 1.2497654), with a spread of 6.0e-3
    spread: float = 0.0
    #: the state is the least-energy QP's (:meth:`ConvexMethod.least_energy`), not a
    #: relaxation's: R is its breach of the laws, and it is the force state
    least_energy: bool = False

    @property
    def zero(self) -> bool:
        return (not self.unresolved and self.R is not None and self.R <= self.tol
                and self.residual <= self.tol)

    @property
    def positive(self) -> bool:
        return not self.unresolved and self.R is not None and self.low > self.tol

    @property
    def decided(self) -> bool:
        return self.R is None and not self.unresolved or self.zero or self.positive

    @property
    def far(self) -> bool:
        """Its value is far above the threshold (:data:`CLEARLY` times it)."""
        return not self.unresolved and self.R is not None and self.R > CLEARLY * self.tol

    @property
    def by_value(self) -> bool:
        """Its value is far above the threshold and its spread (:data:`SPREAD_MARGIN`
        times): a lower point of the f* search where its dual bound cannot certify it."""
        return self.far and self.R > SPREAD_MARGIN * self.spread

    @property
    def by_value_floor(self) -> float:
        """The smallest value taken as a lower point on its value near this one
        (:data:`CLEARLY` times its threshold, :data:`SPREAD_MARGIN` times its spread)."""
        return max(CLEARLY * self.tol, SPREAD_MARGIN * self.spread)

    @property
    def shortfall(self) -> float:
        """How far its dual bound falls short of its value."""
        return self.R - self.low


class ConvexMethod(Method):
    """The convex path with one back end (:mod:`rigidblocks.solvers`)."""

    name = "clarabel"
    setting_keys = None  # the back end checks its own settings

    def __init__(self, scene: Scene, system: EquilibriumSystem, timings: Timings, *,
                 solver: str = "clarabel", settings: dict | None = None,
                 pyramid: int | None = None, progress: Progress | None = None):
        super().__init__(scene, system, timings, progress)
        self.runner = Runner(solver, settings or {}, scene.source or "",
                             progress=self.progress)
        self.solver = self.runner.solver
        self._rejected_noted = False
        self._near_noted = False
        self._coarse_noted = False
        with timings.stage("build"):
            #: the scaling of the relaxations (verdicts, f*) and their states: block by
            #: block (:meth:`Scaling.per_block`); ``lscaling`` that of the max-load
            #: problem (:meth:`Scaling.for_system`: uniform on scenes of like blocks, where
            #: the interior-point lambda* is closer to the simplex one); ``scaling``, the
            #: uniform one, that of problems other modules build on this system
            self.vscaling = Scaling.per_block(system)
            self.lscaling = Scaling.for_system(system)
            self.scaling = Scaling.of(system)
        self.pyramid = pyramid
        #: relaxation problems by load factor, with the uniform friction as parameter
        self._relax: dict[float, tuple[Any, Any]] = {}
        if pyramid is not None:
            if scene.dimension != 3:
                raise InputError("the friction pyramid is an option of 3D scenes only")
            if int(pyramid) < 3:
                raise InputError(f"a friction pyramid needs at least 3 facets, got {pyramid}")
            self.pyramid = int(pyramid)
            self.notes.append(f"friction cones linearised as inscribed {int(pyramid)}-facet "
                              "pyramids (an approximation: not the Coulomb cone)")
        loose = self.runner.loose_settings()
        if loose:
            self.notes.append(f"solver tolerances looser than 1e-9 ({', '.join(loose)}): "
                              "verdicts rest on a relaxation compared with 1e-9 of the "
                              "largest force and may be wrong near a limit")

    # -- work done -------------------------------------------------------------------
    @property
    def n_solves(self) -> int:
        return self.runner.n_solves

    @property
    def solve_time(self) -> float:
        return self.runner.solve_time

    @property
    def answered_by(self) -> tuple[str, ...]:
        return tuple(self.runner.answered_by)

    @property
    def rejected(self) -> tuple[str, ...]:
        return tuple(self.runner.rejected)

    @property
    def iterations(self) -> int:
        return self.runner.iterations

    @contextmanager
    def _solve_stage(self) -> Iterator[None]:
        """Time what the runner solves inside as the "solve" stage (its own wall time,
        and this process's CPU time)."""
        w0, c0 = self.runner.wall_time, time.process_time()
        try:
            yield
        finally:
            self.timings.add("solve", self.runner.wall_time - w0, time.process_time() - c0)

    def solve(self, problem: Any, what: str, tight: bool = False,
              confirm: bool = False, refine: bool = True, stall: bool = True) -> SolverResult:
        """Solve ``problem`` (named ``what`` in notes) through the runner and its policy,
        as the "solve" stage: at the tight tolerances (``tight``), the confirming ones
        (``confirm``), with or without the policy's refined retry (``refine``) and stall
        stop (``stall``); the notes say once where tolerances went out of reach or a
        back end's answers were solved again. For problems built on this method's
        system by other modules (the non-associative analysis)."""
        with self._solve_stage():
            n = len(self.runner.rejected)
            res = (self.runner.confirm(problem, what) if confirm
                   else self.runner.run(problem, what, tight, refine=refine, stall=stall))
            if self.runner.out_of_reach and not self._near_noted:
                self._near_noted = True
                # the back end that went on at 1e-9 (the fallback's, where another
                # back end's answers were solved again by it), not necessarily self.solver
                gone = ", ".join(sorted(self.runner.out_of_reach))
                self.notes.append(f"the tight solver tolerances (1e-10) were out of "
                                  f"{gone}'s reach on this scene: its later solves "
                                  "ran at 1e-9, and their verdicts compare the breach of "
                                  f"the joint laws with {NEAR_ADMISSIBLE_TOL:g} of the "
                                  "largest force")
            if len(self.runner.rejected) > n and not self._rejected_noted:
                self._rejected_noted = True
                self.notes.append(f"answers of {self.solver} that failed their check against "
                                  f"the problem were solved again by clarabel (first: "
                                  f"{self.runner.rejected[n]})")
            return res

    # -- the relaxation ----------------------------------------------------------------
    def _relaxation_problem(self, f: float, load_factor: float) -> tuple[Any, Any]:
        """The relaxation at uniform friction ``f``: built once per load factor with the
        uniform friction as a parameter of the problem (its -f N coefficients), so that
        later values of f only set those entries."""
        if not math.isfinite(f):
            with self.timings.stage("build"):
                return build_relaxation(self.system, self.vscaling, self.f_joint(f),
                                        load_factor, self.pyramid)
        cached = self._relax.get(load_factor)
        if cached is None:
            with self.timings.stage("build"):
                cached = build_relaxation(self.system, self.vscaling, self.f_joint(1.0),
                                          load_factor, self.pyramid, uniform=self.uniform)
            self._relax[load_factor] = cached
        prob, jr = cached
        if "f" in prob.params:
            prob = prob.with_parameter("f", f)
        return prob, jr

    def relaxation(self, f: float, load_factor: float, confirm: bool = True,
                   self_certified: bool = False) -> Relaxation:
        """R(f) and dR/df (from the duals of the friction rows of the uniform joints).

        The back end's answer is checked by the solver policy; with ``confirm``, a
        verdict it leaves near the threshold (the state's own breach above ``tol`` but
        the dual bound below it) is confirmed by a tighter solve
        (:meth:`~rigidblocks.solvers.Runner.confirm`) before it is called undecided.
        With ``self_certified`` an answer that fails the policy's check is still read
        where it decides by itself: its state is admissible (breach and residual
        computed here) or its dual bound, which carries its dual residual, is above
        the threshold."""
        prob, jr = self._relaxation_problem(f, load_factor)
        rx = self._read(prob, jr, self.solve(prob, "relaxation", tight=True), f,
                        self_certified)
        return self._confirmed(rx) if confirm else rx

    def _confirmed(self, rx: Relaxation) -> Relaxation:
        """An undecided relaxation solved again at the confirming tolerances."""
        if rx.decided or rx.unresolved.startswith(FORCES_SPAN):
            return rx
        again = self._read(rx.prob, rx.jr, self.solve(rx.prob, "relaxation", confirm=True),
                           rx.f)
        return again if again.decided or not rx.unresolved else rx

    def _read(self, prob: Any, jr: Any, res: SolverResult, f: float,
              self_certified: bool = False) -> Relaxation:
        """The relaxation's numbers from one checked solve (see :class:`Relaxation`);
        with ``self_certified``, from an answer that failed its check where they decide
        by themselves (:meth:`relaxation`)."""
        if res.verified is False:
            why = (f"the {res.solver} answer ({res.status}) fails its check against the "
                   f"problem: {describe(res.residuals)}")
            failed = Relaxation(None, 0.0, res, jr, prob, ADMISSIBLE_TOL, f, unresolved=why)
            if not self_certified or res.status != OPTIMAL:
                return failed
            rx = self._read(prob, jr, replace(res, verified=None), f)
            r = res.residuals
            # an answer whose state and gap pass, failing on its dual residual alone: its
            # value, where it exceeds what that residual could account for (the spread),
            # steers the f* search as a checked answer's would (20,093-block wall at
            # f = 1.2573: R = 0.570, spread 0.120, dual residual 6.3e-5)
            dual_only = max(r.get("primal", math.inf), r.get("gap", math.inf)) <= VERIFY_TOL
            if rx.zero or rx.positive or dual_only and rx.by_value:
                return replace(rx, res=res)
            return failed
        if res.status != OPTIMAL:
            return Relaxation(None, 0.0, res, jr, prob, ADMISSIBLE_TOL, f)
        z, y = res.z, res.y
        x = z[prob.cols["x"]]
        breach, residual = self._breach(prob, jr, z)
        R = max(float(z[prob.cols["r"]][0]), breach, 0.0)
        # the dual objective bounds R below up to the dual residual's work on the state
        allowance, spread = _dual_work(prob, res)
        low = float(-prob.b @ y) - allowance
        near = NEAR_ADMISSIBLE_TOL / ADMISSIBLE_TOL if res.solver in self.runner.out_of_reach \
            else 1.0
        tol, unresolved = self._resolution(x)
        slope = float(np.sum(self._friction_shares(res, jr, prob)))
        return Relaxation(R, slope, res, jr, prob, near * tol, f, low, residual, unresolved,
                          spread)

    def _resolution(self, x: np.ndarray) -> tuple[float, str]:
        """The threshold of a state ``x`` (scaled forces): ADMISSIBLE_TOL x its largest
        force, and why a verdict on it cannot be decided ("" where it can; noted where
        the lightest blocks are resolved coarsely)."""
        big = float(np.max(np.abs(x), initial=0.0))
        tol = ADMISSIBLE_TOL * max(1.0, big)
        unresolved = ""
        if tol > RESOLVE_NOTE and not self._coarse_noted:
            self._coarse_noted = True
            self.notes.append(f"forces reach {big:.1e} times the loads of the lightest "
                              "blocks they act on: the joint laws of those blocks are "
                              f"resolved to {tol:.1e} of their loads")
        if tol > RESOLVE_LIMIT:
            unresolved = (f"{FORCES_SPAN} {big:.1e} times the loads of the lightest blocks "
                          f"they act on: their joint laws are resolved only to {tol:.1e} "
                          "of those loads (double precision and the solver's tolerance "
                          "cannot separate admissible from inadmissible there)")
        return tol, unresolved

    def _breach(self, prob: Any, jr: Any, z: np.ndarray,
                relax: float = 0.0) -> tuple[float, float]:
        """The largest breach of the joint laws by a solution ``z`` of a relaxation,
        max-load or least-energy problem (``relax``: the relaxation its rows were built
        with, taken back), and its largest equilibrium residual (scaled units)."""
        viol = joint_violations(prob, jr, z, self.system.contacts.n_joints, relax)
        eq = prob.rows["equilibrium"]
        return (float(viol.max(initial=0.0)),
                float(np.abs((prob.A @ z)[eq] - prob.b[eq]).max(initial=0.0)))

    def _violation_force(self, rx: Relaxation) -> float:
        """The largest breach of the joint laws by the relaxation's state, force units."""
        z = rx.res.z
        c = self.system.contacts
        viol = joint_violations(rx.prob, rx.jr, z, c.n_joints)
        lay = self.system.layout
        sj = np.ones(c.n_joints)
        if c.n_points:
            sj[c.point_joint] = self.vscaling.cols(lay.size)[lay.normal]
        top = float((viol * sj).max(initial=0.0))
        return max(top, rx.R * float(sj.min(initial=1.0))) * self.vscaling.force

    def _verdict(self, rx: Relaxation) -> Verdict:
        if rx.unresolved:
            return Verdict(UNDECIDED, math.nan, (rx.unresolved,), rx)
        if rx.R is None:  # equilibrium equations cannot be met at all: a mechanism
            return Verdict(INADMISSIBLE, math.inf, (NO_EQUILIBRIUM,), rx)
        if rx.zero:
            return Verdict(ADMISSIBLE, 0.0, (), rx)
        if rx.positive:
            return Verdict(INADMISSIBLE, self._violation_force(rx), (), rx)
        return Verdict(UNDECIDED, self._violation_force(rx), (near_threshold(rx),), rx)

    def admissible(self, f: float, load_factor: float, for_state: bool = False) -> Verdict:
        rx = (self.least_energy(f, load_factor) if for_state else None) \
            or self.relaxation(f, load_factor)
        v = self._verdict(rx)
        if v.status == INADMISSIBLE and rx.R is not None:
            v = self._certificate_checked(v, rx)
        if v.status == ADMISSIBLE:
            ratio = self.force_ratio(f, load_factor, rx)
            if ratio > FORCE_WARN:
                note = (f"admissible only with forces {ratio:.1e} times the loads of the "
                        "blocks they act on: near a limit approached with ever larger "
                        "forces (an infimum), an ill-conditioned verdict")
                v = Verdict(v.status, v.violation, (*v.notes, note), v.data)
        return v

    def _certificate_checked(self, v: Verdict, rx: Relaxation) -> Verdict:
        """An inadmissible verdict from the relaxation's dual bound, checked against the
        friction its certificate holds at (:func:`certificate_shift`): undecided where
        that lies below f by more than the verdicts resolve (VERDICT_RTOL f +
        FRICTION_ATOL), as above a limit approached with ever larger forces (an
        infimum), where an admissible state needs forces the certificate does not
        exclude."""
        shift, scale = certificate_shift(rx)
        if -shift <= VERDICT_RTOL * rx.f + FRICTION_ATOL:
            return v
        why = (f"the certificate of inadmissibility (the relaxation's duals) holds at "
               f"f = {rx.f + shift:.10g}, {-shift / rx.f:.1e} (relative) below the friction "
               f"asked for, and at f = {rx.f:.10g} excludes admissible states only with "
               f"forces up to {scale:.1e} times the loads of the blocks they act on: above "
               "a limit approached with ever larger forces (an infimum) an admissible "
               "state needs larger ones, which round-off cannot tell from none: undecided")
        return Verdict(UNDECIDED, v.violation, (*v.notes, why), rx)

    def breaches(self, f: float, verdict: Verdict) -> tuple[tuple[int, float], ...]:
        rx = verdict.data
        if not isinstance(rx, Relaxation) or rx.R is None:
            return ()
        x = self.vscaling.forces(rx.res.z[rx.prob.cols["x"]])
        return ranked_breaches(self.system, x, self.f_joint(f))

    # -- the force state ---------------------------------------------------------------
    def least_energy(self, f: float, load_factor: float) -> Relaxation | None:
        """The verdict and the force state from one solve, where the structure is
        admissible: the least-energy QP with the joint laws themselves (not relaxed),
        infeasible exactly when no admissible state exists. Its answer, checked by the
        solver policy, is read as a relaxation's: R is its state's breach of the laws,
        compared, as its equilibrium residual is, with ADMISSIBLE_TOL x its largest
        force. None where that does not certify an admissible state (infeasible,
        failed, a breach or residual above the threshold, forces beyond resolution):
        the relaxation then decides. The 1,009-block wall at self-weight: one QP (13
        iterations) instead of the relaxation (10) and the QP; extruded, its breach 0
        and residual 8e-14. The laws are not relaxed by :data:`STATE_SLACK` as
        :meth:`state` relaxes them: on the extruded 6 x 5 wall at load factor 0.2 the
        state would use that slack and breach the laws by 1.05 times the threshold
        (by 2e-12 of it unrelaxed). Not tried without unknowns (no contacts), nor with
        a back end that solves LPs only (its verdicts are asked for, not those of the
        back end that takes its QPs)."""
        if self.system.layout.size == 0 or self.solver in LP_ONLY:
            return None
        with self.timings.stage("build"):
            prob, jr = energy_problem(self.system, self.vscaling, self.f_joint(f),
                                      load_factor, 0.0, self.pyramid)
        try:
            res = self.solve(prob, "force-state", refine=False)
        except SolverFailure:
            return None
        if res.status != OPTIMAL or res.verified is False:
            return None
        breach, residual = self._breach(prob, jr, res.z)
        tol, unresolved = self._resolution(res.z[prob.cols["x"]])
        rx = Relaxation(breach, 0.0, res, jr, prob, tol, f, residual=residual,
                        unresolved=unresolved, least_energy=True)
        return rx if rx.zero else None

    def state(self, f: float, load_factor: float, verdict: Verdict,
              limit: bool = False) -> ForceState | None:
        """The admissible state of least complementary energy (a QP).

        At a limit state (``limit``) the QP's energy is scaled by the limit problem's
        state (:func:`~rigidblocks.problems.formulation.energy_problem`): there it
        saves iterations (5,006-block wall at f*: 71 instead of a stall at 200), away
        from limits it costs one or two (the same wall at f = 0.6 under its own
        weight: 15 instead of 13). At a limit state the admissible set shrinks to
        (nearly) one point and the QP can be out of the interior-point solver's reach
        (3D cones sliding all round a bed joint); the state of the solved limit problem
        (an admissible state, not the least-energy one) is then returned, and the
        result's notes say so. The QP is solved once, without the policy's retry with
        refined settings.
        """
        data = verdict.data
        if isinstance(data, Relaxation) and data.least_energy:
            with self.timings.stage("state"):
                return force_state(self.system,
                                   self.vscaling.forces(data.res.z[data.prob.cols["x"]]),
                                   "least complementary energy")
        if isinstance(data, Relaxation):
            relax, solved, limit_x = data.R + STATE_SLACK, data.res, data.prob.cols["x"]
            scaling = self.vscaling
        else:  # the max-load LP: (result, problem)
            res, prob = data
            relax, solved, limit_x = STATE_SLACK, res, prob.cols["x"]
            scaling = self.lscaling
        with self.timings.stage("build"):
            prob = energy_problem(self.system, scaling, self.f_joint(f), load_factor,
                                  relax, self.pyramid,
                                  reference=solved.z[limit_x] if limit else None)[0]
        try:
            # solved once: where the interior-point iteration stalls near a limit, a
            # retry with other settings stalls too (5,006-block wall at f*: AlmostSolved
            # after 200 iterations, twice), and the solved problem's state serves
            res = self.solve(prob, "force-state", refine=False)
            status = res.raw_status if res.status != OPTIMAL else None
            if status is None and res.verified is False:
                status = f"{res.raw_status}, failing its check ({describe(res.residuals)})"
        except SolverFailure as exc:
            status = exc.status
        with self.timings.stage("state"):
            if status is None:
                return force_state(self.system, scaling.forces(res.z[prob.cols["x"]]),
                                   "least complementary energy")
            self.notes.append(f"force state: the solution of the limit problem (the "
                              f"least-energy QP ended with status {status})")
            return force_state(self.system, scaling.forces(solved.z[limit_x]),
                               "solution of the limit problem")

    # -- f*: Newton steps on R(f) ------------------------------------------------------
    def friction_limit(self, load_factor: float, rtol: float) -> Limit:
        """f* by safeguarded Newton steps on R(f).

        R(f), the smallest violation of the joint laws at friction f, is zero for
        f >= f* and positive below. Starting from f = 0, Newton steps
        f <- f + R(f) / (-dR/df) use the derivative from the duals of the friction rows
        (dR/df = -sum_r y_r N_r, envelope theorem), with a bracket [lower, upper] and
        bisection as a safeguard (the rules of :mod:`.friction_rules` on the search
        engine, :mod:`.engine`). Every step solves an always feasible LP (SOCP in 3D);
        a few solves reach ``rtol``. Under a live load at a load factor above 0, once
        R(0) > 0, f* is sought where lambda*(f) equals the load factor instead
        (:meth:`_friction_by_load`); this search on R(f) is for the dead load alone
        and where that one hands over.
        """
        lf = load_factor
        rx = self.relaxation(math.inf, lf)
        if not rx.decided:
            self.notes.append(f"at infinite friction: {rx.unresolved or near_threshold(rx)}")
            return Limit("undecided")
        if not rx.zero:
            if rx.R is None:
                self.notes.append(NO_EQUILIBRIUM)
            return Limit("unstable")
        search = Search(0.0, math.inf, rtol, FRICTION_ATOL)
        search.record(Trial(math.inf, True, "upper", data=rx))
        rx = self.relaxation(0.0, lf)
        if rx.unresolved or not rx.decided and rx.R is None:
            self.notes.append(f"at f = 0: {rx.unresolved or near_threshold(rx)}")
            return Limit("undecided")
        if rx.R is None:
            raise SolverFailure("the relaxation at f = 0 has no solution although infinite "
                                "friction has one", self.solver, rx.res.raw_status)
        search.record(Trial(0.0, True, "upper", data=rx) if rx.zero
                      else Trial(0.0, False, "lower", rx.R, rx.slope, rx))
        if not rx.zero and lf > 0 and np.any(self.system.live):
            first = rx.R / rx.slope if rx.slope > 0 else 1.0
            by_load = self._friction_by_load(lf, rtol, first)
            if by_load is not None:
                return by_load
        run(search, lambda f: self._friction_trial(f, lf), STOPS, STEPS, AMENDS,
            budget=friction_rules.BUDGET)
        return self._friction_end(search, lf)

    def _friction_trial(self, f: float, lf: float) -> Trial:
        """The oracle of the search on R(f): one relaxation at ``f``, its kind of trial
        (:mod:`.friction_rules`)."""
        try:
            rx = self.relaxation(f, lf, confirm=False, self_certified=True)
        except SolverFailure as exc:
            # near f* the relaxation can be too degenerate for the interior-point solver
            return Trial(f, None, "missed", data=exc,
                         why=f"{self.solver} ended with status {exc.status}")
        if not rx.decided and rx.far:
            if rx.by_value:
                # far above the threshold and above what its duals' residual could
                # account for, though its dual bound is too weak to certify it: a lower
                # point (f* is reported at the certified upper end either way)
                return Trial(f, False, "lower-by-value", rx.R, rx.slope, rx)
            # within that spread the value may be that of an admissible state's
            # neighbourhood: it decides nothing, as an answer that fails its check
            return Trial(f, None, "missed", data=rx, why=(
                f"the relaxation's value {rx.R:.1e} is within {SPREAD_MARGIN:g} times the "
                f"{rx.spread:.1e} its duals' residual could account for"))
        if rx.unresolved and not rx.unresolved.startswith(FORCES_SPAN):
            return Trial(f, None, "missed", data=rx, why=rx.unresolved)
        if not rx.decided:
            if rx.unresolved:
                return Trial(f, None, "forces-span", data=rx, why=rx.unresolved)
            return Trial(f, None, "threshold", rx.R, rx.slope, rx)
        if rx.R is None:
            raise SolverFailure("relaxation problem lost its solution", self.solver,
                                rx.res.raw_status)
        if rx.zero:
            return Trial(f, True, "upper", data=rx)
        return Trial(f, False, "lower", rx.R, rx.slope, rx)

    def _friction_end(self, search: Search, lf: float) -> Limit:
        """The limit a search on R(f) found, with its notes, rendered from its record."""
        lo, hi, last, why = search.bad, search.good, search.last, search.stopped
        upper = hi if math.isfinite(hi) else None
        if why == "budget":
            raise SolverFailure(f"minimum friction did not converge in "
                                f"{friction_rules.BUDGET} solves", self.solver,
                                "iteration limit")
        if why == "missed_too_often":
            if isinstance(last.data, SolverFailure) and upper is None:
                raise last.data
            self.notes.append(f"at f = {last.x:.10g}: {last.why}; f* is bracketed in "
                              f"[{lo:.10g}, {hi:.10g}]")
            return Limit("undecided", None, lo, upper)
        unresolved_below = None
        if why == "forces_beyond_resolution":
            if upper is None:  # forces beyond resolution, no upper end: nothing to go on
                self.notes.append(f"at f = {last.x:.10g}: {last.why}")
                return Limit("undecided", None, lo, None)
            # below the certified upper end the states need forces beyond what can be
            # resolved: f* is an infimum approached by unbounded forces
            unresolved_below = last.x
        lower = search.end(False)
        if why == "resolution_reached":
            rx, below = lower.data, lower.slope * 0.5 * search.rtol * hi
            self.notes.append(
                f"below the certified upper end f = {hi:.10g} the relaxation is about "
                f"{below:.1e} (slope {lower.slope:.4g}), below what the solver certifies "
                f"there (its dual bound was {rx.shortfall:.1e} short at f = {lo:.10g}): "
                f"f* is bracketed in [{lo:.10g}, {hi:.10g}] (relative width "
                f"{(hi - lo) / hi:.1e}), certified at the upper end")
        if search.of_kind(*UNDECIDED_KINDS) and not self._bracket_note(search):
            return Limit("undecided", None, lo, upper)
        if search.of_kind("lower-by-value") and lo > 0:
            self.notes.append(f"the lower end of f*'s bracket ({lo:.10g}) rests on the "
                              "relaxation's value, far above the threshold but not "
                              "certified by its dual bound; f* is the certified upper end")
        at_hi = search.end(True).data
        self._infimum_note(hi, lf, at_hi, lo, unresolved_below)
        governing = self._governing(lower.data.res, lower.data.jr, lower.data.prob) \
            if lower is not None else ()
        return Limit("stable", hi, lo, hi, governing=governing, at=self._verdict(at_hi))

    def _bracket_note(self, search: Search) -> bool:
        """The note on f*'s bracket where trials near f* decided nothing (a trial left at
        the threshold bounds nothing: R may be zero there with a state the solver cannot
        certify; extruded 5,006-block wall: one at f = 1.2502445, where the plane wall
        certifies f* <= 1.2497654); False where that leaves the bracket wider than the
        requested accuracy and WIDE (no number)."""
        lo, hi = search.bad, search.good
        t = search.of_kind(*UNDECIDED_KINDS)[-1]
        if t.kind == "threshold":
            status = "undecided (near the threshold)"
        elif isinstance(t.data, SolverFailure):
            status = t.data.status
        else:
            status = (f"{t.data.res.raw_status}, "
                      + ("failing its check" if t.data.unresolved
                         else "its value within its duals' spread"))
        wide = not search.narrow(WIDE)
        under = [u.x for u in search.of_kind("threshold") if u.x < hi]
        at = ""
        if under and math.isfinite(hi):
            top = max(under)
            at = (f" (the last at f = {top:.10g}, {(hi - top) / hi:.1e} below the "
                  f"certified upper end{'' if wide else ', which is reported'})")
        self.notes.append(f"near f* some relaxations ended with status {status}{at}; "
                          f"f* is bracketed in [{lo:.10g}, {hi:.10g}] (relative width "
                          f"{(hi - lo) / hi:.1e})")
        if wide:
            self.notes.append(f"the bracket is wider than {max(search.rtol, WIDE):g} "
                              "(relative): no number is given")
        return not wide

    def _friction_shares(self, res: SolverResult, jr: Any, prob: Any) -> np.ndarray:
        """Each friction row's share y_r N_r of the derivative with respect to the uniform
        friction of a solved problem's objective (-dR/df, or dlambda*/df; envelope
        theorem), 0 on joints with friction of their own."""
        head = prob.rows["joints"].start + jr.fric_head
        return res.y[head] * (jr.fric_nsum @ res.z) * self.uniform[jr.fric_joint]

    def _governing(self, res: SolverResult, jr: Any, prob: Any) -> tuple[int, ...]:
        """The uniform joints that govern f* below it, ranked by their share of
        :meth:`_friction_shares` (largest first: a long list is read from its head;
        shares equal to 1e-6 of the largest in the joints' order), those above 1e-3 of
        the largest; a joint whose normal force vanishes (an opening joint carrying only
        a relaxation's slack) does not govern."""
        w = self._friction_shares(res, jr, prob)
        if not (w.size and w.max() > 0):
            return ()
        strong = w > 1e-3 * w.max()
        share = np.bincount(jr.fric_joint[strong], w[strong])
        joints = np.flatnonzero(share)
        # shares equal to 1e-6 (symmetric joints, round-off apart) keep the joints' order
        rank = np.round(share[joints] / share.max(), 6)
        return tuple(int(j) for j in joints[np.argsort(-rank, kind="stable")])

    def _max_load(self, f: float, tight: bool = True,
                  finer: bool = False) -> tuple[Any, Any, SolverResult]:
        """The max-load LP (SOCP) at uniform friction ``f``, solved and checked: lambda* is
        read from it, at the tight tolerances and without a stall stop (``tight``), else
        at the back end's defaults; with ``finer``, first at
        :data:`~rigidblocks.solvers.policy.FINER_SETTINGS` (where that solve ends short
        of a checked optimum, as usual after it)."""
        with self.timings.stage("build"):
            prob, jr = build_max_load(self.system, self.lscaling, self.f_joint(f),
                                      self.pyramid)
        if tight and finer:
            with self._solve_stage():
                res = self.runner.attempt(prob, "maximum load", FINER_SETTINGS)
            if res is not None and res.status in (OPTIMAL, INFEASIBLE) and res.verified:
                return prob, jr, res
        return prob, jr, self.solve(prob, "maximum load", tight=tight, stall=not tight)

    def _friction_by_load(self, lf: float, rtol: float, first: float) -> Limit | None:
        """f* at load factor ``lf`` > 0 as the friction where lambda*(f) = ``lf`` (the
        rules of :mod:`.load_rules` on the search engine, :mod:`.engine`).

        lambda*(f), the largest admissible multiplier of the live load at friction f,
        grows with f; lf is admissible at f where lambda*(f) >= lf and the dead load
        alone is admissible (the admissible multipliers form an interval). Newton steps
        on lambda*(f) - lf from ``first`` use dlambda*/df from the duals of the
        friction rows (as dR/df for the relaxation), with the curvature model of
        :func:`~.friction_rules.root_step` where lambda* is concave (Newton falls
        short). Each step solves the max-load LP, better conditioned near f* than the
        relaxation: on the 5,006-block wall its value near f* is resolved to 4e-5
        (SPREAD_MARGIN times the work of its dual residual on its state), where the
        relaxation's lower points stopped 5.4e-4 below the certified upper end.

        An upper end is a trial whose state carries the live load at lambda >= lf
        within the admissibility threshold (breach and equilibrium residual computed on
        the state); a lower end one where the dual bound on lambda* (with the dual
        residual's work on forces up to the state's largest, as the relaxation's) is
        below lf, or else lambda* plus that resolution is: on its value, as the
        relaxation's lower points by value, and the notes say so. Where the next step
        would land where lambda*, predicted with the upper end's slope, is within that
        resolution of lf (no end to expect), the trial goes where it is predicted
        UP_REACH times the resolution above lf (on the chord from the lower end) while
        the upper end is above lf by more than twice it, else 1.5 times it below lf;
        where neither moves an end, the bracket stands. A trial within that resolution
        is followed the same way from itself. A bracket left wider than WIDE is
        undecided, with no number; where a trial resolves f more coarsely than
        FINER_WHEN times WIDE, the later ones are solved at FINER_SETTINGS first. The
        first trial, far from f* as a rule, is solved at the back end's defaults, and
        again at the tight tolerances where that answer decides no end. The state at lf
        is the combination of the upper end's state and an admissible state under the
        dead load alone there (one relaxation). None, for the relaxation search, where a
        solve is not checked or unbounded, where the dead load alone is not admissible
        at the upper end, where the state at f* needs forces above FORCE_WARN times
        the loads that may have grown from the first upper end's as towards an infimum
        (:func:`_infimum_growth`; the relaxation search says whether f* is one; where
        they did not, the notes give them), where no upper end is found in 40 solves,
        or where no trial gave a lower end and the bracket is wider than WIDE.
        """
        search = Search(0.0, math.inf, rtol, FRICTION_ATOL)
        run(search, lambda f: self._load_trial(f, lf, search), load_rules.STOPS,
            (load_rules.start_at(first), *load_rules.STEPS), load_rules.AMENDS,
            budget=load_rules.BUDGET)
        if search.stopped in ("handed_back", "budget"):
            return None
        return self._by_load_end(search, lf)

    def _load_trial(self, f: float, lf: float, search: Search) -> Trial:
        """The oracle of the search on lambda*(f): the max-load LP at ``f`` and its kind
        of trial (:mod:`.load_rules`). The first trial, far from f* as a rule, is
        solved at the back end's defaults, and again at the tight tolerances where
        that answer decides no end; once a tight solve resolves f more coarsely than
        FINER_WHEN times WIDE, the later ones are solved at FINER_SETTINGS first."""
        tight = bool(search.trials)
        finer = any(t.data.finer for t in search.trials)
        attempts = 0
        while True:
            attempts += 1
            data = SimpleNamespace(attempts=attempts, tight=tight, margin=0.0, finer=False,
                                   at=None, by_value=False)
            try:
                prob, jr, res = self._max_load(f, tight, finer)
            except SolverFailure:
                if tight:
                    raise
                tight = True
                continue
            if res.verified is False or res.status == UNBOUNDED:
                if not tight:
                    tight = True
                    continue
                return Trial(f, None, "hand-back", data=data)
            if res.status == INFEASIBLE:  # no multiplier at all is admissible there
                return Trial(f, False, "lower", -math.inf, 0.0, data)
            z, y = res.z, res.y
            lam = float(z[prob.cols["lambda"]][0])
            x = z[prob.cols["x"]]
            tol = ADMISSIBLE_TOL * max(1.0, float(np.abs(x).max(initial=0.0)))
            admissible = max(self._breach(prob, jr, z)) <= tol
            allowance, spread = _dual_work(prob, res)
            slope = float(np.sum(self._friction_shares(res, jr, prob)))
            data.margin, data.at = SPREAD_MARGIN * spread, (prob, jr, res)
            # lambda* resolves f too coarsely here for a bracket within WIDE
            data.finer = tight and not finer and slope > 0 and \
                data.margin / slope > FINER_WHEN * WIDE * f
            if lam >= lf and admissible:
                return Trial(f, True, "upper", lam - lf, slope, data)
            if lam + data.margin < lf:
                # on its value where the dual bound on lambda*, with the dual residual's
                # work on forces up to the state's largest, does not certify it
                data.by_value = float(prob.b @ y) + allowance >= lf
                return Trial(f, False, "lower", lam - lf, slope, data)
            if not tight:  # the defaults' answer decides only ends away from lf
                tight = True
                continue
            if not admissible or slope <= 0:
                return Trial(f, None, "hand-back", data=data)
            # within what lambda* resolves of lf: f* is about here
            return Trial(f, None, "unresolved", lam - lf, slope, data)

    def _by_load_end(self, search: Search, lf: float) -> Limit | None:
        """The limit a search on lambda*(f) found (None: the search on R(f) decides),
        with the state at lf: theta (state at lambda) + (1 - theta) (dead load alone)."""
        lo, hi = search.bad, search.good
        upper, lower = search.end(True), search.end(False)
        at_lo = lower.data.at if lower is not None else None
        if upper is None or at_lo is None and hi - lo > WIDE * hi:
            return None
        if not search.narrow(WIDE):
            self.notes.append(
                f"f* from lambda*(f) = {lf:g} (the maximum-load LP): f* is bracketed in "
                f"[{lo:.10g}, {hi:.10g}] (relative width {(hi - lo) / hi:.1e}), where "
                f"lambda* is within {SPREAD_MARGIN:g} times what its duals' residual "
                f"could account for of {lf:g}; the bracket is wider than {WIDE:g} "
                "(relative): no number is given")
            return Limit("undecided", None, lo, hi)
        prob, jr, res = upper.data.at
        theta = lf / (upper.value + lf)
        x = res.z[prob.cols["x"]]
        if theta < 1.0 and np.any(self.system.dead):
            rx0 = self.relaxation(hi, 0.0)
            if not rx0.zero:
                return None
            x0 = self.vscaling.forces(rx0.res.z[rx0.prob.cols["x"]])
            x = theta * x + (1.0 - theta) * self.lscaling.scaled(x0)
        big = float(np.abs(self._per_block(x)).max(initial=0.0))
        if big > FORCE_WARN and not self._not_an_infimum(search, big):
            return None
        z = res.z.copy()
        z[prob.cols["x"]] = x
        z[prob.cols["lambda"]] = lf
        if lower is not None and lower.data.by_value:
            self.notes.append(
                f"f* is certified from above: at f = {hi:.10g} a state carries the load "
                f"factor {lf:g} (f* from lambda*(f) = {lf:g}, the largest load "
                f"multiplier at friction f). Below, f* is bracketed in [{lo:.10g}, "
                f"{hi:.10g}] (relative width {(hi - lo) / hi:.1e}) by lambda*'s value at "
                f"the lower end ({lower.value + lf:.10g}: below {lf:g} by more than "
                f"{SPREAD_MARGIN:g} times the solver's resolution there), not by a "
                "certified bound")
        governing = self._governing(at_lo[2], at_lo[1], at_lo[0]) if at_lo else ()
        return Limit("stable", hi, lo, hi, governing=governing,
                     at=Verdict(ADMISSIBLE, 0.0, (), (replace(res, z=z), prob)))

    def _not_an_infimum(self, search: Search, big: float) -> bool:
        """Whether forces of ``big`` times the loads at f* are the structure's own scale
        (they grew from the first upper end's less than an infimum's would, with a note),
        or may be an infimum's growth (the relaxation search says whether f* is one)."""
        lo, hi = search.bad, search.good
        first = search.ends(True)[0]
        prob, _, res = first.data.at
        f_far = first.x
        big_far = float(np.abs(self._per_block(res.z[prob.cols["x"]])).max(initial=0.0))
        if _infimum_growth((f_far, big_far), hi, lo, big):
            return False
        self.notes.append(
            f"the state at f* carries forces up to {big:.1e} times the loads of the "
            f"blocks they act on; at f = {f_far:.6g}, {(f_far - hi) / (hi - lo):.0f} "
            f"times further above f* than the bracket's width, {big_far:.1e}: forces "
            "that do not grow as f* is approached (not an infimum)")
        return True

    def _per_block(self, x: np.ndarray) -> np.ndarray:
        """Forces of a max-load state in units of the loads of the blocks they act on (as
        the relaxation's unknowns)."""
        return self.vscaling.scaled(self.lscaling.forces(x))

    def force_ratio(self, f: float, load_factor: float, rx: Relaxation) -> float:
        """How many times the loads of the blocks they act on the forces of an admissible
        state at (f, lambda) must be: the relaxation's state gives an upper bound, and
        where that exceeds FORCE_WARN the least-energy state (forces no larger than
        needed) decides."""
        if rx.res.z is None:
            return 0.0
        big = float(np.abs(rx.res.z[rx.prob.cols["x"]]).max(initial=0.0))
        if big <= FORCE_WARN or rx.least_energy:
            return big
        with self.timings.stage("build"):
            prob = energy_problem(self.system, self.vscaling, self.f_joint(f), load_factor,
                                  rx.R + STATE_SLACK, self.pyramid,
                                  reference=rx.res.z[rx.prob.cols["x"]])[0]
        try:
            res = self.solve(prob, "force-state")
        except SolverFailure:
            return big
        if res.status != OPTIMAL or res.verified is False:
            return big
        return min(big, float(np.abs(res.z[prob.cols["x"]]).max(initial=0.0)))

    def _infimum_note(self, hi: float, load_factor: float, at_hi: Relaxation, lo: float,
                      unresolved_below: float | None) -> None:
        """Say so when f* is an ill-conditioned infimum (module docstring of
        :data:`FORCE_WARN`)."""
        if not math.isfinite(hi) or not at_hi.zero:
            return
        ratio = self.force_ratio(hi, load_factor, at_hi)
        if unresolved_below is not None:
            self.notes.append(
                f"f* is an infimum approached with ever larger forces: at f = "
                f"{unresolved_below:.10g} an admissible state would need forces beyond "
                f"what the solver can resolve, at f = {hi:.10g} (reported) forces "
                f"{ratio:.1e} times the loads of the blocks they act on; the infimum lies "
                f"in [{lo:.10g}, {hi:.10g}]")
        elif ratio > FORCE_WARN:
            self.notes.append(
                f"the state at f* needs forces {ratio:.1e} times the loads of the blocks "
                "they act on: f* is an infimum approached with ever larger forces (the "
                "value is ill-conditioned; below it no state is admissible, near it only "
                "states with forces growing without bound)")

    # -- lambda*: one LP ---------------------------------------------------------------
    def load_limit(self, f: float, rtol: float, mechanism_kind: str = "vertex") -> Limit:
        """lambda* from max lambda s.t. A x + F_dead + lambda F_live = 0 and the joint
        laws; by LP duality the multipliers of the equilibrium rows are the virtual
        velocities of the collapse mechanism (associative flow rule, kinematic theorem).
        Solved at the tight tolerances of the relaxations: at Clarabel's defaults (1e-8)
        lambda* of a 1,000-block wall is off by 7e-5 (its toe carries a thousand block
        weights, and the residuals are relative to that), at 1e-10 by 4e-6 of the
        simplex (HiGHS) answer, for 1.4x the interior-point iterations; and with the
        finer KKT regularisation of :data:`~rigidblocks.solvers.policy.VALUE_SETTINGS`
        by 4e-7 (at f = 1.18372, in 49 iterations against 56).

        ``mechanism_kind``: "vertex" (default) picks one mechanism of the optimal face
        (:func:`~rigidblocks.methods.vertex.vertex_dual`); "blend" keeps the
        interior-point duals (the centre of the face)."""
        prob, jr, res = self._max_load(f)
        if res.verified is False:
            self.notes.append(f"the {res.solver} answer to the maximum-load problem "
                              f"({res.status}) fails its check against the problem: "
                              f"{describe(res.residuals)}: undecided")
            return Limit("undecided")
        if res.status == UNBOUNDED:
            dead = self._dead_admissible(f)
            if dead is None:
                return Limit("undecided")
            return Limit("unbounded" if dead else "unstable")
        if res.status == INFEASIBLE:
            return Limit("unstable")
        lam = float(res.z[prob.cols["lambda"]][0])
        if lam < -ADMISSIBLE_TOL:
            self.notes.append(f"the largest admissible multiplier is negative ({lam:.6g}): "
                              "the dead load alone is not admissible")
            return Limit("unstable")
        dead = self._dead_admissible(f)
        if dead is None:
            return Limit("undecided", None, None, lam)
        if not dead:
            self.notes.append(f"largest admissible multiplier {lam:.6g}, but only with the "
                              "live load propping the structure up")
            return Limit("unstable")
        y_eq, kind = self.mechanism_duals(prob, res, lam, mechanism_kind, "lambda*")
        with self.timings.stage("state"):
            mech = mechanism(self.system, self.lscaling.row, y_eq, kind)
        sliding = tuple(k for k, md in enumerate(mech.modes) if md.startswith("slide"))
        # lambda* is read from the solver's answer, whose state carries it; above it,
        # what the duals' residual could account for (SPREAD_MARGIN times its work on
        # that state, as for the f* searches' values): where that exceeds rtol, the
        # result gives the bracket and says so (the 50,065-block wall: 0.3679 with
        # Clarabel's default regularisation, 0.3790 with VALUE_SETTINGS)
        reach = SPREAD_MARGIN * _dual_work(prob, res)[1]
        scale = max(abs(lam), 1.0)
        upper = lam
        if reach > rtol * scale:
            upper = lam + reach
            self.notes.append(
                f"lambda* = {lam:.7g} is the solver's answer (its state carries it); "
                f"what the residual of its duals could account for ({SPREAD_MARGIN:g} "
                f"times its work on that state) allows lambda* up to {upper:.7g}: "
                f"lambda* is in [{lam:.7g}, {upper:.7g}], the upper end by value, not "
                "certified")
        return Limit("collapse", lam, lam, upper, governing=sliding, mechanism=mech,
                     at=Verdict(ADMISSIBLE, 0.0, (), (res, prob)), resolution=reach / scale)

    def mechanism_duals(self, prob: Any, res: SolverResult, lam: float, kind: str,
                        what: str) -> tuple[np.ndarray, str]:
        """The equilibrium rows' duals of a solved limit problem ``prob`` (multiplier
        ``lam``, named ``what`` in notes) to draw as its mechanism, and which they are:
        with ``kind`` "vertex" one mechanism of the optimal face
        (:func:`~rigidblocks.methods.vertex.vertex_dual`; the blend, with a note, where
        none is found), with "blend" the interior-point duals."""
        eq = prob.rows["equilibrium"]
        if kind != "vertex":
            return res.y[eq], "blend"
        self.progress.stage = "vertex mechanism"
        with self.timings.stage("mechanism"):
            vd = vertex_dual(prob, res, eq, self.system.dofs)
        if vd is None:
            self.notes.append("mechanism: the blend of the optimal face (no vertex could "
                              "be found)")
            return res.y[eq], "blend"
        work_at = float(prob.b @ vd[0])
        if work_at > lam * (1 + 1e-6) + 1e-9:
            self.notes.append(f"mechanism: the one drawn (an extreme point next to the "
                              f"optimal face) balances at lambda = {work_at:.6g}, "
                              f"{work_at / lam - 1:.1e} (relative) above {what}")
        return vd[0][eq], vd[1]

    def _dead_admissible(self, f: float) -> bool | None:
        """Is lambda = 0 admissible? The admissible multipliers form an interval, which
        may lie wholly above 0 when the live load props up a structure that cannot stand
        under its dead load alone. One relaxation solve (none without a dead load); None
        (with a note) when that verdict is undecided."""
        if not np.any(self.system.dead):
            return True
        rx = self.relaxation(f, 0.0)
        if not rx.decided:
            self.notes.append(f"under the dead load alone: "
                              f"{rx.unresolved or near_threshold(rx)}")
            return None
        if not rx.zero:
            self.notes.append("the dead load alone is not admissible")
            return False
        return True


def near_threshold(rx: Relaxation) -> str:
    """Why a relaxation near the admissibility threshold decides nothing."""
    return (f"near the admissibility threshold even after a tighter solve: the state "
            f"found breaches the joint laws by {rx.R:.2e} and its equilibrium by "
            f"{rx.residual:.2e}, the duals bound the smallest breach below by "
            f"{rx.low:.2e}, and the threshold is {rx.tol:.2e} (relative to each joint's "
            "scale): undecided")


def certificate_shift(rx: Relaxation) -> tuple[float, float]:
    """Where the dual certificate of a relaxation at uniform friction f holds best, and
    the largest forces it excludes there.

    The duals' residual d = c + A^T y of the relaxation at f changes with the friction
    by g = (dA/df)^T y (the -f N entries of the uniform joints): the first value is the
    friction change -d.g / g.g that removes the part of d along g (0 where the friction
    rows carry no more than :data:`CERTIFICATE_FRICTION` of the certificate, whose
    multipliers of the relaxed rows sum to 1: a block that tips leaves 1.6e-7 there,
    in the direction of round-off, and its verdict does not rest on the friction),
    the second (-b^T y - tol) / |d|_1, the largest
    forces (relaxation units) of states the dual bound shows to breach the laws by more
    than the threshold. Below an infimum f* the certificate is exact at f; just above
    it, the residual is that of the certificate at f* (a block wedged between faces at
    45 degrees under a block 1e4 times heavier, at f = 1 + 1e-6: -5.2e-7, where the
    certificates of regular limits leave below 1e-9)."""
    prob, res = rx.prob, rx.res
    d = prob.c + prob.A.T @ res.y
    margin = float(-prob.b @ res.y) - rx.tol
    scale = margin / float(np.abs(d).sum()) if np.any(d) else math.inf
    if "f" not in prob.params:
        return 0.0, scale
    A = prob.A if prob.A.format == "csc" else prob.A.tocsc()
    pos, coef = prob.params["f"]
    cols = np.searchsorted(A.indptr, pos, side="right") - 1
    g = np.bincount(cols, coef * res.y[A.indices[pos]], minlength=A.shape[1])
    if float(np.abs(g).sum()) <= CERTIFICATE_FRICTION:
        return 0.0, scale
    return -float(d @ g) / float(g @ g), scale


def _dual_work(prob: Any, res: SolverResult) -> tuple[float, float]:
    """What the residual d = c + A^T y of a solved problem's duals could do to its
    value: at most |d|_1 max(1, max |z|) on states no larger than its own (the dual
    bound's allowance), and sum |d_j z_j| on its own state (its spread, an estimate)."""
    d = np.abs(prob.c + prob.A.T @ res.y)
    za = np.abs(res.z)
    return float(d.sum()) * max(1.0, float(za.max(initial=0.0))), float(d @ za)


def _infimum_growth(far: tuple[float, float], hi: float, lo: float, big: float) -> bool:
    """Whether the largest force ``big`` of the state at the upper end ``hi`` of f*'s
    bracket [``lo``, ``hi``] may have grown from ``far`` = (f, largest force) at an upper
    end further above as forces do towards an infimum, at least as 1 / (f - f*): by
    (f_far - hi) / (hi - lo) at least. False where it grew GROWTH_SPAN times less than
    that: the structure's own scale (the base of a 20,093-block wall carries 1.40e4 times
    the loads of its blocks at f* = 1.2772487, 1.43e4 at f = 1.3432768)."""
    f_far, big_far = far
    if not (hi > lo and f_far > hi and big_far > 0):
        return True
    return (f_far - hi) / (hi - lo) < GROWTH_SPAN * big / big_far


__all__ = ["ADMISSIBLE_TOL", "ConvexMethod", "FRICTION_ATOL", "FRICTION_RTOL", "Relaxation",
           "STATE_SLACK", "VERDICT_RTOL"]
