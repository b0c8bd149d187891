"""The rules of the search for f* on R(f): safeguarded Newton steps on the relaxation.

R(f), the smallest violation of the joint laws at friction f, is zero for f >= f* and
positive below. The search (:mod:`.engine`) keeps [lower, upper] = [bad, good]: an
**upper** trial has an admissible state, a **lower** one a certified R > 0 (or, "lower
by value", a value far above what its duals could account for). Its oracle
(:func:`~rigidblocks.methods.friction_search.trial_of`) names the other kinds
of trial: **threshold** (near the admissibility threshold after a tighter solve),
**missed** (no checked answer, or a value within its duals' spread) and
**forces-span** (forces beyond what the solver resolves). Each trial carries R and
-dR/df (``value``, ``slope``) and, as ``data``, an object with ``by_value_floor`` (the
smallest value read as a lower point on its value) and ``shortfall`` (how far its dual
bound fell short of its value), read by the rules below.

The rules, in the order they are asked: stop at the requested accuracy, after too many
trials without a checked answer or at the threshold, or where forces go beyond
resolution (:data:`STOPS`); step below trials at the threshold, past an undecided
trial, to a first upper end, by Newton, to a probe just below the upper end, to the
midpoint (:data:`STEPS`); never again where the solver decided nothing
(:data:`AMENDS`).
"""

from __future__ import annotations

import math

from .engine import WIDE, Search, Trial, midpoint, narrow_enough

#: trials in a row whose relaxation has no checked answer (the solver failed, or its
#: answer fails the check; lower points by value, unchecked too, do not break the row)
#: before the search gives up: undecided with the bracket, or a failure where the solver
#: failed before any upper end was certified
MISSED_LIMIT = 4
#: trials left at the threshold (in all) after which the search ends with its bracket
THRESHOLD_TRIALS = 8
#: relaxations the search may solve before it gives up (a failure: it did not converge)
BUDGET = 100
#: relative offset of a trial from a point it must lie above or below, in units of the
#: requested accuracy: a Newton step that lands this close to the lower end is moved up
#: by it (to certify from above), a probe goes this far below the upper end
CERTIFY_OFFSET = 0.5
#: a trial the solver left undecided this close (relative) below the certified upper
#: end is followed below it, not above (1e3 times the requested accuracy when that was
#: 1e-7: in units of a coarse accuracy it took every such trial as close, and the
#: 4-voussoir arch of thickness 0.3 ended undecided, bracketed to 4e-2, at 1e-3)
CLOSE_BELOW = 1e-4
#: each trial followed above one the solver left undecided goes this many times further
#: than the previous one
PAST_GROWTH = 4.0
#: two trials this close (relative) are the same point (a Newton step or a midpoint
#: computed again from the same bracket, to round-off)
SAME_POINT = 1e-12
#: the kinds of trial that decide nothing and are stepped past
UNDECIDED_KINDS = ("missed", "threshold")


# -- what the rules read from the record -------------------------------------------------
def _lower(s: Search) -> Trial | None:
    return s.end(False)


def _newton(s: Search) -> float:
    """The root estimated from the lower end (:func:`root_step`), infinite where its
    slope is not positive."""
    lo = _lower(s)
    if lo is None or not lo.slope > 0:
        return math.inf
    lows = s.ends(False)
    prev = (lows[-2].x, lows[-2].slope) if len(lows) > 1 else None
    return lo.x + root_step(lo.value, lo.slope, lo.x, prev)


def _inside(s: Search) -> list[float]:
    """The trials left at the threshold strictly inside the bracket."""
    return [t.x for t in s.of_kind("threshold") if s.bad < t.x < s.good]


def _above_thresholds(s: Search) -> bool:
    """The upper end is certified within half of WIDE above a trial at the threshold
    but bounds nothing from below (R may be zero there with a state the solver cannot
    certify), and the bracket is wider than WIDE."""
    inside = _inside(s)
    return bool(inside) and math.isfinite(s.good) and s.good - max(inside) \
        <= 0.5 * WIDE * s.good and s.width > WIDE * s.good


def _resolved_below(s: Search, end: float) -> float:
    """Where R, predicted with the lower end's slope, is twice what is taken as a lower
    point on its value below ``end``."""
    lo = _lower(s)
    return end - 2.0 * lo.data.by_value_floor / lo.slope


def _certified_from_above(s: Search, trial: float, cap: float = math.inf) -> float:
    """A trial moved up by CERTIFY_OFFSET x rtol where it is that close to the lower end
    (capped at ``cap``)."""
    if trial - s.bad <= CERTIFY_OFFSET * s.rtol * trial:
        return min(trial * (1.0 + CERTIFY_OFFSET * s.rtol), cap)
    return trial


def _past(s: Search, t: Trial) -> float | None:
    """The trial after ``t``, which decided nothing: close below the certified upper
    end, PAST_GROWTH times further below it (None where that is below the lower end);
    elsewhere up to ``t``'s own reach (twice its distance from the lower end; for a
    trial at the threshold, twice its Newton step), at least by a relative offset that
    grows PAST_GROWTH-fold at every such trial, never past the midpoint to a certified
    upper end: a few solves reach a certified point."""
    lo, hi = t.bracket
    if _close_below(s, t):
        below = hi - PAST_GROWTH * (hi - t.x)
        return below if below > lo else None
    if t.kind == "missed":
        up = 2.0 * t.x - lo
    else:
        up = t.x + 2.0 * t.value / t.slope if t.slope > 0 else t.x
    ups = 0  # earlier trials stepped past upwards
    for u in s.trials:
        if u is t:
            break
        if u.kind in UNDECIDED_KINDS and not _close_below(s, u):
            ups += 1
    nxt = max(t.x * (1.0 + s.rtol * PAST_GROWTH ** ups), up)
    return min(nxt, 0.5 * (t.x + hi)) if math.isfinite(hi) else nxt


def _close_below(s: Search, t: Trial) -> bool:
    """``t`` lay within CLOSE_BELOW below the certified upper end of its time."""
    hi = t.bracket[1]
    return math.isfinite(hi) and t.x >= hi * (1.0 - CLOSE_BELOW)


def _among(f: float, trials: list[float]) -> bool:
    """Whether ``f`` is one of ``trials``, to round-off (a Newton step or a midpoint
    computed again from the same bracket)."""
    return any(abs(f - t) <= SAME_POINT * max(abs(t), 1.0) for t in trials)


# -- stop rules --------------------------------------------------------------------------
def missed_too_often(s: Search) -> bool:
    """More than MISSED_LIMIT trials in a row without a checked answer."""
    return s.trailing("missed", through=("lower-by-value",)) > MISSED_LIMIT


def too_many_at_threshold(s: Search) -> bool:
    """More than THRESHOLD_TRIALS trials left at the threshold."""
    return s.last is not None and s.last.kind == "threshold" \
        and len(s.of_kind("threshold")) > THRESHOLD_TRIALS


def forces_beyond_resolution(s: Search) -> bool:
    """The last trial needs forces beyond what the solver resolves: below a certified
    upper end, f* is an infimum approached by unbounded forces; without one, nothing
    to go on."""
    return s.last is not None and s.last.kind == "forces-span"


STOPS = (narrow_enough, missed_too_often, too_many_at_threshold, forces_beyond_resolution)


# -- step rules --------------------------------------------------------------------------
def below_the_thresholds(s: Search) -> float | None:
    """Under :func:`_above_thresholds`: below the lowest trial at the threshold (Newton's
    step where it lands there, else the midpoint to the lower end, at least where R is
    predicted resolved below it)."""
    if not _above_thresholds(s):
        return None
    below, lo = min(_inside(s)), _lower(s)
    newton = _newton(s)
    if s.bad < newton < below * (1.0 - CERTIFY_OFFSET * s.rtol):
        return newton
    trial = 0.5 * (s.bad + below)
    if lo is not None and lo.slope > 0:
        trial = max(trial, _resolved_below(s, below))
    return trial


def past_the_undecided(s: Search) -> float | None:
    """After a trial that decided nothing: step past it (:func:`_past`)."""
    if s.last is not None and s.last.kind in UNDECIDED_KINDS:
        return _past(s, s.last)
    return None


def first_upper_end(s: Search) -> float | None:
    """No upper end certified yet: Newton's step (doubling where there is none)."""
    if math.isfinite(s.good):
        return None
    newton = _newton(s)
    trial = newton if math.isfinite(newton) else max(2.0 * s.bad, 1.0)
    return _certified_from_above(s, trial)


def newton_step(s: Search) -> float | None:
    """Newton's step where it lands inside the bracket, short of the upper end."""
    newton = _newton(s)
    if not s.bad < newton < s.good * (1.0 - CERTIFY_OFFSET * s.rtol):
        return None
    return _certified_from_above(s, newton, s.good * (1.0 - 0.5 * CERTIFY_OFFSET * s.rtol))


def probe_below_upper_end(s: Search) -> float | str | None:
    """Once after each midpoint: a probe just below the upper end, or, where R is about
    linear across a bracket narrower than WIDE and predicted below what the solver
    certifies there, the end ("resolution_reached"); where Newton's step lands about
    at the upper end, no closer than where R is predicted resolved (:func:`midpoint` if
    that is below the midpoint)."""
    rules = [t.rule for t in s.trials if t.rule in ("probe_below_upper_end", "midpoint")]
    if rules and rules[-1] == "probe_below_upper_end":
        return None
    lo, hi, lower = s.bad, s.good, _lower(s)
    trial = hi * (1.0 - CERTIFY_OFFSET * s.rtol)
    newton = _newton(s)
    if lower is None or newton > 2 * hi - lo:
        return trial
    predicted = lower.slope * (hi - trial)
    if hi - lo <= WIDE * hi and predicted < lower.data.by_value_floor \
            and predicted < lower.data.shortfall:
        return "resolution_reached"
    trial = min(trial, _resolved_below(s, hi))
    return trial if trial > 0.5 * (lo + hi) else None


STEPS = (below_the_thresholds, past_the_undecided, first_upper_end, newton_step,
         probe_below_upper_end, midpoint)


# -- amend rule --------------------------------------------------------------------------
def not_again(s: Search, trial: float) -> float | str:
    """A trial where the solver decided nothing before is not repeated: the midpoint, or
    halfway from it on to the upper end; neither new (or no finite upper end, or a
    bracket within WIDE): the bracket stands ("undecided_there_before")."""
    before = [t.x for t in s.of_kind(*UNDECIDED_KINDS)]
    if not _among(trial, before):
        return trial
    if not math.isfinite(s.good) or s.width <= WIDE * s.good:
        return "undecided_there_before"
    mid = 0.5 * (s.bad + s.good)
    return next((t for t in (mid, 0.5 * (mid + s.good)) if not _among(t, before)),
                "undecided_there_before")


AMENDS = (not_again,)


def root_step(R: float, s: float, f: float, prev: tuple[float, float] | None,
              convex: bool = False) -> float:
    """Step from a lower point (R(f) = R > 0, -dR/df = s > 0) to the estimated root.

    Newton's step R / s, or, where the slope has grown since the previous lower point
    (R concave there, so Newton overshoots), the root of the quadratic model
    R - s d - c d^2 / 2 with the curvature c = ds/df from the two slopes. With
    ``convex``, the same model where the slope has shrunk (R convex, so Newton falls
    short), where it has a root.
    """
    if prev is not None and f > prev[0] and (s > prev[1] or convex and s < prev[1]):
        c = (s - prev[1]) / (f - prev[0])
        disc = s * s + 2.0 * c * R
        if disc >= 0:
            return 2.0 * R / (s + math.sqrt(disc))
    return R / s


__all__ = ["AMENDS", "BUDGET", "MISSED_LIMIT", "STEPS", "STOPS",
           "THRESHOLD_TRIALS", "UNDECIDED_KINDS", "root_step"]
