"""f* under a live load as the friction where lambda*(f) reaches the load factor: the
max-load LP as the oracle of the search on lambda*(f) (:mod:`.load_rules` on the
engine, :mod:`.engine`), and the limit and its state rendered from its record."""

from __future__ import annotations

import math
from dataclasses import replace
from types import SimpleNamespace
from typing import Any

import numpy as np

from ..errors import SolverFailure
from ..problems.formulation import build_max_load
from ..results import fmt_bracket
from ..solvers import INFEASIBLE, UNBOUNDED, SolverResult
from ..solvers.policy import ESTIMATE, FINER_VALUE, VALUE, Ladder
from . import load_rules
from .base import ADMISSIBLE, Limit, Verdict
from .engine import WIDE, Search, Trial, run
from .relaxation import (
    FORCE_WARN,
    FRICTION_ATOL,
    SPREAD_MARGIN,
    dual_work,
    threshold,
)

#: in the search for f* on lambda*(f), a tight solve whose value resolves f to more
#: than this fraction of :data:`WIDE` (its resolution over its slope) puts the later
#: ones at :data:`~rigidblocks.solvers.policy.FINER_SETTINGS` first: the
#: 20,093-block wall at f = 1.2877647 resolves lambda* to 1.2e-3 at VALUE_SETTINGS,
#: about 1e-3 in f, where the bracket takes about 1/8 + 1.5 times that
FINER_WHEN = 0.25
#: forces of the state at f* found from lambda*(f) above FORCE_WARN are the structure's
#: scale, not an infimum's, where they grew from the first upper end's by at least this
#: many times less than an infimum's 1 / (f - f*) growth would
GROWTH_SPAN = 4.0


class LoadSearch:
    """The search for f* of :class:`~rigidblocks.methods.convex.ConvexMethod` on
    lambda*(f) (a part of it)."""

    def max_load(self, f: float,
                  ladder: Ladder = VALUE) -> tuple[Any, Any, SolverResult]:
        """The max-load LP (SOCP) at uniform friction ``f``, solved up ``ladder`` and
        checked: lambda* is read from it (:data:`~rigidblocks.solvers.policy.VALUE`;
        :data:`~rigidblocks.solvers.policy.FINER_VALUE` where a search's values need
        finer settings, :data:`~rigidblocks.solvers.policy.ESTIMATE` for the first
        trial of a search, far from f* as a rule)."""
        with self.timings.stage("build"):
            prob, jr = build_max_load(self.system, self.lscaling, self.f_joint(f),
                                      self.pyramid)
        return prob, jr, self.solve(prob, "maximum load", ladder)

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
        (:func:`infimum_growth`; the relaxation search says whether f* is one; where
        they did not, the notes give them), where no upper end is found in 40 trials,
        or where no trial gave a lower end and the bracket is wider than WIDE.
        """
        search = Search(0.0, math.inf, rtol, FRICTION_ATOL)
        run(search, lambda f: self._load_trial(f, lf, search), load_rules.STOPS,
            (load_rules.start_at(first), *load_rules.STEPS), budget=load_rules.BUDGET)
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
        while True:
            data = SimpleNamespace(tight=tight, margin=0.0, finer=False, at=None,
                                   by_value=False)
            try:
                prob, jr, res = self.max_load(f, (FINER_VALUE if finer else VALUE)
                                               if tight else ESTIMATE)
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
            admissible = max(self._breach(prob, jr, z)) <= threshold(x)
            allowance, spread = dual_work(prob, res)
            slope = float(np.sum(self.friction_shares(res, jr, prob)))
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
                f"f* from lambda*(f) = {lf:.10g} (the maximum-load LP): f* is bracketed in "
                f"[{lo:.10g}, {hi:.10g}] (relative width {(hi - lo) / hi:.1e}), where "
                f"lambda* is within {SPREAD_MARGIN:g} times what its duals' residual "
                f"could account for of {lf:.10g}; the bracket is wider than "
                f"{max(search.rtol, WIDE):g} (relative): no number is given")
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
                f"factor {lf:.10g} (f* from lambda*(f) = {lf:.10g}, the largest load "
                f"multiplier at friction f). Below, f* is bracketed in "
                f"{fmt_bracket(lo, hi)} (relative width {(hi - lo) / hi:.1e}) by lambda*'s "
                f"value at "
                f"the lower end ({lower.value + lf:.10g}: below {lf:.10g} by more than "
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
        if infimum_growth((f_far, big_far), hi, lo, big):
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


def infimum_growth(far: tuple[float, float], hi: float, lo: float, big: float) -> bool:
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


__all__ = ["FINER_WHEN", "GROWTH_SPAN", "LoadSearch", "infimum_growth"]
