"""The verdict of the convex path: the relaxation R(f, lambda), the numbers read from
one solve of it (:class:`Relaxation`), and the verdict with its certificate checks.

The relaxations are scaled block by block (:meth:`Scaling.per_block`): each block's
rows by its own load, each joint's forces and law rows by its lighter block's load.
Admissible iff the relaxation's own state breaches the joint laws and equilibrium by at
most 1e-9 of its largest scaled force (the interior-point solver's accuracy is relative
to the size of its solution); inadmissible iff the duals bound R above that; between the
two a tighter solve decides, or the verdict is undecided, as it is where the forces span
more orders than the solver can resolve (:data:`RESOLVE_LIMIT`). The relaxation is
always feasible when the equilibrium equations can be met, so it avoids the degenerate
feasibility problems at the limit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..problems.formulation import build_relaxation, joint_violations
from ..solvers import INFEASIBLE, OPTIMAL, SolverResult
from ..solvers.policy import CONFIRMATION, VERDICT, VERIFY_TOL, describe
from .base import ADMISSIBLE, INADMISSIBLE, UNDECIDED, Verdict, ranked_breaches

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
#: absolute accuracy of the minimum friction: a structure that stands with f <= 1e-9
#: needs no friction (round-off keeps R(0) just above the threshold)
FRICTION_ATOL = 1e-9
#: the finest relative accuracy in f that the interior-point verdicts resolve: a
#: certified end is admissible to ADMISSIBLE_TOL of the largest force, coarser in f than
#: 1e-8 (the 3D box on a 20 degree slope asked for 1e-8 came out with a 1.2e-8 bracket
#: 1.06e-7 below tan 20 degrees; the extruded 106-block wall at 1e-7 certified an end
#: 5.6e-8 below f* = 1, within it). An inadmissibility certificate that holds only more
#: than this below f is no verdict (:meth:`Verdicts._certificate_checked`: the
#: 1,000-block wall's sits 6.9e-9 below f)
VERDICT_RTOL = 1e-7
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
#: the resultant (relative to the largest block load) of the loads on a group of blocks
#: joined to no support above which the equilibrium equations have no solution
#: (:meth:`~rigidblocks.equilibrium.EquilibriumSystem.unheld_load`)
UNHELD_TOL = 1e-9
UNHELD_RAW = "a group of blocks joined to no support carries a resultant load"
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
    #: the state is the least-energy QP's (:meth:`ForceStates.least_energy`), not a
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


class Verdicts:
    """The verdicts of :class:`~rigidblocks.methods.convex.ConvexMethod` (a part of it):
    the relaxation at (f, lambda), solved, checked and read."""

    def relaxation_problem(self, f: float, load_factor: float) -> tuple[Any, Any]:
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
        prob, jr = self.relaxation_problem(f, load_factor)
        if self.system.unheld_load(load_factor) > UNHELD_TOL:
            # a group joined to no support carries a resultant: no equilibrium, without a
            # solve (Clarabel did not certify it in 3D: a box on its support's edge, a
            # box on it, read "solver failure ... InsufficientProgress")
            return Relaxation(None, 0.0, SolverResult(INFEASIBLE, None, None, math.nan,
                                                      "equilibrium", UNHELD_RAW), jr, prob,
                              ADMISSIBLE_TOL, f)
        rx = self._read(prob, jr, self.solve(prob, "relaxation", VERDICT), f,
                        self_certified)
        return self._no_equilibrium_checked(self._confirmed(rx) if confirm else rx,
                                            load_factor)

    def _confirmed(self, rx: Relaxation) -> Relaxation:
        """An undecided relaxation solved again at the confirming tolerances."""
        if rx.decided or rx.unresolved.startswith(FORCES_SPAN):
            return rx
        again = self._read(rx.prob, rx.jr, self.solve(rx.prob, "relaxation", CONFIRMATION),
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
        allowance, spread = dual_work(prob, res)
        low = float(-prob.b @ y) - allowance
        near = NEAR_ADMISSIBLE_TOL / ADMISSIBLE_TOL if res.solver in self.runner.out_of_reach \
            else 1.0
        tol, unresolved = self._resolution(x)
        slope = float(np.sum(self.friction_shares(res, jr, prob)))
        return Relaxation(R, slope, res, jr, prob, near * tol, f, low, residual, unresolved,
                          spread)

    def _no_equilibrium_checked(self, rx: Relaxation, load_factor: float) -> Relaxation:
        """A relaxation the solver calls infeasible, undecided where the equilibrium
        equations have a solution after all: the relaxation is feasible exactly where
        they have one, and where their least-squares residual
        (:meth:`~rigidblocks.equilibrium.EquilibriumSystem.equations_residual`) is
        round-off, the solver's certificate failed in the scaled problem (a block that
        weighs 1e-13 of the 10 kN it carries read "the scene is a mechanism")."""
        if rx.R is not None or rx.unresolved or rx.res.status != INFEASIBLE:
            return rx
        miss = self.system.equations_residual(load_factor)
        if miss > UNHELD_TOL:
            return rx
        return replace(rx, unresolved=(
            f"{rx.res.solver} found no equilibrium state, yet the equilibrium equations "
            f"have solutions (least-squares residual {miss:.1e} of the loads): the "
            "blocks' loads span more than the solver resolves (a block far lighter than "
            "the loads it carries), not a mechanism"))

    def _resolution(self, x: np.ndarray) -> tuple[float, str]:
        """The threshold of a state ``x`` (scaled forces): ADMISSIBLE_TOL x its largest
        force, and why a verdict on it cannot be decided ("" where it can; noted where
        the lightest blocks are resolved coarsely)."""
        big = float(np.max(np.abs(x), initial=0.0))
        tol = threshold(x)
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


def threshold(x: np.ndarray) -> float:
    """The admissibility threshold of a state ``x`` (scaled forces): ADMISSIBLE_TOL times
    its largest force, and no less than ADMISSIBLE_TOL."""
    return ADMISSIBLE_TOL * max(1.0, float(np.max(np.abs(x), initial=0.0)))


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


def dual_work(prob: Any, res: SolverResult) -> tuple[float, float]:
    """What the residual d = c + A^T y of a solved problem's duals could do to its
    value: at most |d|_1 max(1, max |z|) on states no larger than its own (the dual
    bound's allowance), and sum |d_j z_j| on its own state (its spread, an estimate)."""
    d = np.abs(prob.c + prob.A.T @ res.y)
    za = np.abs(res.z)
    return float(d.sum()) * max(1.0, float(za.max(initial=0.0))), float(d @ za)


__all__ = ["ADMISSIBLE_TOL", "CLEARLY", "FORCE_WARN", "FORCES_SPAN", "FRICTION_ATOL",
           "NEAR_ADMISSIBLE_TOL", "NO_EQUILIBRIUM", "Relaxation", "SPREAD_MARGIN",
           "VERDICT_RTOL", "Verdicts", "certificate_shift", "dual_work", "near_threshold",
           "threshold"]
