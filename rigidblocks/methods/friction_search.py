"""f* by safeguarded Newton steps on the relaxation R(f): the oracle of the search on
R(f) (:mod:`.friction_rules` on the engine, :mod:`.engine`) and the limit rendered from
its record, with the joints that govern it."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..errors import SolverFailure
from ..results import fmt_bracket
from ..solvers import SolverResult
from . import friction_rules
from .base import Limit
from .engine import WIDE, Search, Trial, run
from .friction_rules import AMENDS, STEPS, STOPS, UNDECIDED_KINDS
from .relaxation import (
    FORCE_WARN,
    FORCES_SPAN,
    FRICTION_ATOL,
    NO_EQUILIBRIUM,
    SPREAD_MARGIN,
    Relaxation,
    near_threshold,
)

#: a uniform joint governs f* where its share of dR/df (or dlambda*/df) exceeds this
#: fraction of the largest joint's
GOVERNING_SHARE = 1e-3
#: joints whose shares agree to this many digits (relative to the largest) are ranked
#: in the joints' order (symmetric joints, round-off apart)
TIE_DIGITS = 6


class FrictionSearch:
    """The search for f* of :class:`~rigidblocks.methods.convex.ConvexMethod` on R(f)
    (a part of it)."""

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
            try:
                by_load = self._friction_by_load(lf, rtol, first)
            except SolverFailure as exc:
                # the search on R(f) goes on where a max-load trial fails (a 3D block
                # bonded by a tensile strength, its cones closing under tension: a solver
                # failure where the relaxations answer)
                self.notes.append(f"the search on lambda*(f) stopped ({exc.solver} ended "
                                  f"with status {exc.status} at a maximum-load trial): f* "
                                  "is searched on the relaxations instead")
                by_load = None
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
        return trial_of(f, rx, self.solver)

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
            rx, below = lower.data, lower.slope * friction_rules.CERTIFY_OFFSET * search.rtol * hi
            self.notes.append(
                f"below the certified upper end f = {hi:.10g} the relaxation is about "
                f"{below:.1e} (slope {lower.slope:.4g}), below what the solver certifies "
                f"there (its dual bound was {rx.shortfall:.1e} short at f = {lo:.10g}): "
                f"f* is bracketed in {fmt_bracket(lo, hi)} (relative width "
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
                          f"f* is bracketed in {fmt_bracket(lo, hi)} (relative width "
                          f"{(hi - lo) / hi:.1e})")
        if wide:
            self.notes.append(f"the bracket is wider than {max(search.rtol, WIDE):g} "
                              "(relative): no number is given")
        return not wide

    def friction_shares(self, res: SolverResult, jr: Any, prob: Any) -> np.ndarray:
        """Each friction row's share y_r N_r of the derivative with respect to the uniform
        friction of a solved problem's objective (-dR/df, or dlambda*/df; envelope
        theorem), 0 on joints with friction of their own."""
        head = prob.rows["joints"].start + jr.fric_head
        return res.y[head] * (jr.fric_nsum @ res.z) * self.uniform[jr.fric_joint]

    def _governing(self, res: SolverResult, jr: Any, prob: Any) -> tuple[int, ...]:
        """The uniform joints that govern f* below it, ranked by their share of
        :meth:`friction_shares` (largest first: a long list is read from its head;
        shares equal to TIE_DIGITS digits in the joints' order), those above
        GOVERNING_SHARE of the largest; a joint whose normal force vanishes (an opening
        joint carrying only a relaxation's slack) does not govern."""
        w = self.friction_shares(res, jr, prob)
        if not (w.size and w.max() > 0):
            return ()
        strong = w > GOVERNING_SHARE * w.max()
        share = np.bincount(jr.fric_joint[strong], w[strong])
        joints = np.flatnonzero(share)
        rank = np.round(share[joints] / share.max(), TIE_DIGITS)
        return tuple(int(j) for j in joints[np.argsort(-rank, kind="stable")])

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


def trial_of(f: float, rx: Relaxation, solver: str = "") -> Trial:
    """The trial a relaxation ``rx`` at friction ``f`` makes in the search on R(f)
    (the kinds of :mod:`.friction_rules`): "upper" (an admissible state), "lower" (R
    certified positive by the dual bound), "lower-by-value" (R far above the threshold
    and :data:`~.relaxation.SPREAD_MARGIN` times what its duals' residual could
    account for), "missed" (no checked answer, or a far value within that spread),
    "forces-span" (forces beyond what the solver resolves) or "threshold" (near the
    threshold). A relaxation without a solution that counts as decided raises
    :class:`SolverFailure` (of ``solver``)."""
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
        raise SolverFailure("relaxation problem lost its solution", solver,
                            rx.res.raw_status)
    if rx.zero:
        return Trial(f, True, "upper", data=rx)
    return Trial(f, False, "lower", rx.R, rx.slope, rx)


__all__ = ["GOVERNING_SHARE", "TIE_DIGITS", "FrictionSearch", "trial_of"]
