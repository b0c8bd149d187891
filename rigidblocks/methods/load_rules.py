"""The rules of the search for f* on lambda*(f): Newton steps on the max-load LP.

Under a live load at a load factor lf > 0, f* is where lambda*(f), the largest
admissible multiplier of the live load at friction f, reaches lf. The search
(:mod:`.engine`) keeps [lower, upper] = [bad, good]; each trial carries the residual
lambda*(f) - lf (``value``) and dlambda*/df (``slope``), and its oracle
(:mod:`~rigidblocks.methods.load_search`, the max-load LP) names it: **upper**
(a state carries the live load at lambda >= lf), **lower** (lambda* below lf by more
than its resolution; -inf where no multiplier is admissible), **unresolved** (within
that resolution: f* is about there) or **hand-back** (an answer that cannot be used:
the search on R(f) takes over). ``data`` holds ``margin`` (what lambda*'s duals could
account for, its resolution at that trial), ``tight`` (solved at the tight
tolerances) and ``finer`` (this trial put the later ones at finer settings).

The rules, in the order they are asked: stop where the oracle hands back, at the
requested accuracy (:data:`STOPS`); step above and below the first unresolved trial, to
a first upper end (Newton's step up), down from the upper end, just below the upper end,
to the midpoint, each moved where lambda* is predicted resolvable (:data:`STEPS`); at
most BUDGET trials.
"""

from __future__ import annotations

import math

from .engine import WIDE, Search, StepRule, Trial, narrow_enough
from .friction_rules import CERTIFY_OFFSET, THRESHOLD_TRIALS, root_step

#: an upper end is sought where lambda* is predicted this fraction of its resolution
#: (SPREAD_MARGIN times the dual residual's work) above the load factor: about the
#: work itself, by which the solver's lambda* falls short of lambda* (the 5,006-block
#: wall at f = 1.25: 1.0002615 with dual residual work 9.4e-6 at VALUE_SETTINGS,
#: 1.0002645 with 2.2e-6 at tolerances 1e-12)
UP_REACH = 0.125
#: a lower end is sought where lambda* is predicted this many times its resolution
#: below the load factor: the largest resolution seen, as it varies twofold from trial
#: to trial (2.4e-6 to 5.2e-6 on the 1,009-block wall near f*)
LOW_REACH = 1.5
#: trials (the first may take two solves: at the defaults, then tight) before the
#: search hands back ("budget")
BUDGET = 40
#: the trial above the first unresolved one goes this much (relative) further than
#: predicted, to certify from above: CERTIFY_OFFSET x 1e-7, as tuned at that accuracy.
#: In units of a coarse accuracy it overshot the bracket it was to close: on the
#: 20,051-block wall at load factor 0.2 asked for 2e-3 it put the upper end at
#: 0.2142895 (bracket 2.1e-3, undecided) where 0.2140755 gives 1.1e-3
ABOVE_OFFSET = 5e-8


# -- what the rules read from the record -------------------------------------------------
def reach(s: Search, upto: Trial | None = None) -> float:
    """lambda*'s resolution: the largest margin of the tight trials (up to ``upto``),
    since the one that put the later solves at finer settings."""
    out = 0.0
    for t in s.trials:
        if t.data.tight:
            out = 0.0 if t.data.finer else max(out, t.data.margin)
        if t is upto:
            break
    return out


def _unresolved(s: Search) -> list[Trial]:
    """The unresolved trials that count (the first THRESHOLD_TRIALS)."""
    return s.of_kind("unresolved")[:THRESHOLD_TRIALS]


def _newton(s: Search) -> float:
    """Newton's step up from the lower end (with the convex model of
    :func:`~.friction_rules.root_step`), moved up by CERTIFY_OFFSET x rtol where it
    is that close to it; infinite without a lower end of positive slope."""
    lows = s.ends(False)
    if not lows or not lows[-1].slope > 0:
        return math.inf
    lo = lows[-1]
    prev = (lows[-2].x, lows[-2].slope) if len(lows) > 1 and lows[-2].slope > 0 else None
    newton = lo.x + root_step(-lo.value, lo.slope, lo.x, prev, convex=True)
    if newton - s.bad <= CERTIFY_OFFSET * s.rtol * newton:
        newton = s.bad * (1.0 + CERTIFY_OFFSET * s.rtol)
    return newton


def _on_chord(s: Search, value: float) -> float:
    """Where the chord between the ends reaches the residual ``value`` (NaN where there
    is none)."""
    lo, hi = s.end(False), s.end(True)
    if lo is None or not (math.isfinite(lo.value) and hi.value > lo.value):
        return math.nan
    return s.bad + (value - lo.value) * (s.good - s.bad) / (hi.value - lo.value)


def _resolvable(s: Search, trial: float) -> float | str:
    """``trial``, or where lambda* there, predicted with the upper end's slope, is
    within its resolution of lf (no end to expect): where the upper end is above lf by
    more than twice that, a trial where lambda* is predicted UP_REACH times it above lf
    (on the chord from the lower end, which stays below lambda* where it is concave),
    else one where it is predicted LOW_REACH times it below lf (on the tangent at the
    upper end, which stays above it); neither, where the ends are that close: the
    bracket stands ("ends_within_resolution"). (1,009-block wall: a trial 4.8e-8 below
    the upper end, lambda* 7e-8 below lf with a resolution of 4.1e-6, decided
    nothing.)"""
    up, r = s.end(True), reach(s)
    lo, hi = s.bad, s.good
    if not (up.slope > 0 and trial > hi - (up.value + r) / up.slope):
        return trial
    trial = _on_chord(s, UP_REACH * r) if up.value > 2.0 * r else math.nan
    if lo < trial < hi * (1.0 - CERTIFY_OFFSET * s.rtol):
        return trial
    trial = hi - (up.value + LOW_REACH * r) / up.slope
    if lo * (1.0 + CERTIFY_OFFSET * s.rtol) < trial < hi:
        return trial
    return "ends_within_resolution"


# -- stop rules --------------------------------------------------------------------------
def handed_back(s: Search) -> bool:
    """The last answer cannot be used (not checked, unbounded, or within lambda*'s
    resolution without an admissible state or a positive slope)."""
    return s.last is not None and s.last.kind == "hand-back"


STOPS = (handed_back, narrow_enough)


# -- step rules --------------------------------------------------------------------------
def start_at(first: float) -> StepRule:
    """The step rule of the first trial, at ``first``."""
    def first_trial(s: Search) -> float | None:
        return first if not s.trials else None
    return first_trial


def above_the_unresolved(s: Search) -> float | None:
    """Right after the first unresolved trial: where lambda*, predicted with its slope,
    is UP_REACH times its resolution above lf, then ABOVE_OFFSET (or half the requested
    accuracy, if finer) further (if inside the bracket)."""
    first = _unresolved(s)
    if not first or s.last is not first[0]:
        return None
    t = first[0]
    trial = t.x + (-t.value + UP_REACH * reach(s, t)) / t.slope \
        + min(CERTIFY_OFFSET * s.rtol, ABOVE_OFFSET) * t.x
    return trial if s.bad < trial < s.good else None


def below_the_unresolved(s: Search) -> float | str | None:
    """Once a trial is unresolved: where lambda*, predicted with the latest one's slope,
    is LOW_REACH times its resolution below lf, once, while the bracket is wider than
    WIDE; else the bracket stands ("unresolved_bracket")."""
    counted = _unresolved(s)
    if not counted:
        return None
    t = counted[-1]
    tried = any(u.rule == "below_the_unresolved" for u in s.after(t))
    below = t.x - (t.value + LOW_REACH * max(reach(s, t), t.data.margin)) / t.slope
    if tried or not s.bad < below < s.good or s.width <= WIDE * s.good:
        return "unresolved_bracket"
    return below


def first_upper_end(s: Search) -> float | None:
    """No upper end yet: Newton's step, or doubling the last trial where there is
    none."""
    if math.isfinite(s.good):
        return None
    newton = _newton(s)
    return newton if math.isfinite(newton) else max(2.0 * s.last.x, 1.0)


def down_from_upper_end(s: Search) -> float | str | None:
    """Newton's step down from the upper end (below the root where lambda* is concave,
    as Newton's step up falls short of it elsewhere: the chord would stay above it and
    move the upper end slowly)."""
    up = s.end(True)
    down = s.good - up.value / up.slope if up.slope > 0 else -math.inf
    return _resolvable(s, down) if s.bad < down < s.good else None


def probe_below_upper_end(s: Search) -> float | str | None:
    """Where Newton's step and the step down land at or past the upper end (lambda*
    about linear with its root at the upper end): once after each
    midpoint, a probe CERTIFY_OFFSET x rtol below it, to certify the bracket from
    below (moved where lambda* is resolvable)."""
    rules = [t.rule for t in s.trials if t.rule in ("probe_below_upper_end",
                                                      "midpoint_resolvable")]
    if rules and rules[-1] == "probe_below_upper_end" or _newton(s) < s.good:
        return None
    return _resolvable(s, s.good * (1.0 - CERTIFY_OFFSET * s.rtol))


def midpoint_resolvable(s: Search) -> float | str:
    """Halve the bracket."""
    return _resolvable(s, 0.5 * (s.bad + s.good))


STEPS = (above_the_unresolved, below_the_unresolved, first_upper_end, down_from_upper_end,
         probe_below_upper_end, midpoint_resolvable)


__all__ = ["BUDGET", "LOW_REACH", "STEPS", "STOPS", "UP_REACH", "reach",
           "start_at"]
