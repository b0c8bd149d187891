"""Bracket and bisect: the one search on a monotone verdict, and the limits found by it.

:func:`bisect` serves every search of the package on a verdict that changes once along
a parameter (friction, load factor, thickness, a load step): it keeps a bracket
[bad, good] and stops at a relative width, or at the first trial its ``decide`` cannot
tell (an undecided verdict), leaving the bracket as it is. :func:`friction_by_bisection`
and :func:`load_by_bisection` find f* and lambda* for a method without a fast path.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..methods import FAILURE, Limit, Method, Verdict
from ..methods.engine import (
    MAX_TRIALS,
    WIDE,
    Oracle,
    Search,
    StepRule,
    Trial,
    beside_the_undecided,
    bisection,
    midpoint,
    narrow_enough,
    run,
    undecided_band,
)
from ..results import fmt_bracket, within

#: a bisection stopped by an undecided trial with a bracket wider than the requested
#: accuracy (relative), or than BRACKET_ATOL where it reaches within that of 0 (f* or
#: lambda* = 0), gives no number;
#: BRACKET_RTOL, the engine's WIDE, is the default of :meth:`Bracket.too_wide`
BRACKET_RTOL = WIDE
BRACKET_ATOL = 1e-6
#: largest friction tried when bracketing f* from above
FRICTION_CEILING = 1e8
#: largest load multiplier tried when bracketing lambda* (beyond it: "unbounded")
UNBOUNDED_AT = 1e6
#: trials of a search on verdicts (doubling to a ceiling, then bisection)
BUDGET = 300

#: decide(x) -> (True: good, False: bad, None: undecided; anything to keep with it)
Decide = Callable[[float], tuple[bool | None, Any]]


@dataclass(frozen=True)
class Bracket:
    """Where a bisection stopped: ``bad`` fails, ``good`` passes; ``good_data`` is what
    ``decide`` returned with the last passing trial (None if no trial passed);
    ``undecided_at`` the trial that stopped it undecided (None if it ran to the end)."""

    bad: float
    good: float
    good_data: Any = None
    undecided_at: float | None = None

    @property
    def lower(self) -> float:
        return min(self.bad, self.good)

    @property
    def upper(self) -> float:
        return max(self.bad, self.good)

    def too_wide(self, rtol: float = BRACKET_RTOL, atol: float = BRACKET_ATOL) -> bool:
        """Wider than ``rtol`` relative to its upper end, or than ``atol`` where it
        reaches within ``atol`` of 0 (:func:`~rigidblocks.results.within`, the rule of
        every search's accuracy): the floor once counted whatever the answer's size (the
        inclined corbel arch without dilatancy at f = 0.8 gave 0.0127922 with a relative
        width of 3.8e-5 for 1e-5 asked)."""
        return not within(self.lower, self.upper, rtol, atol)


def no_number_note(what: str, lower: float, upper: float, reached: float,
                   rtol: float) -> str:
    """Why a limit bracketed in [lower, upper] to the accuracy ``reached`` gives no
    number where ``rtol`` was asked (every limit's note, and the non-associative answer
    at the associative multiplier's)."""
    return (f"{what} is bracketed in {fmt_bracket(lower, upper)}: accuracy {reached:.1e} "
            f"reached, {rtol:.1e} requested (rtol): no number is given")


def bisect(decide: Decide, bad: float, good: float, rtol: float, atol: float = 0.0,
           steps: int = MAX_TRIALS) -> Bracket:
    """Halve [bad, good] (either order) until |good - bad| <= rtol max(|good|, |bad|) +
    atol, at most ``steps`` times; past undecided trials it narrows the bracket beside
    them until they fill it (the engine's
    :func:`~rigidblocks.methods.engine.bisection`)."""
    s = bisection(decide, bad, good, rtol, atol, steps)
    passed = s.end(True)
    return Bracket(s.bad, s.good, passed.data if passed else None, _undecided_at(s))


def _undecided_at(s: Search) -> float | None:
    """The latest undecided trial of a search that its undecided trials ended."""
    if s.stopped != "undecided_band":
        return None
    return next(t.x for t in reversed(s.trials) if t.side is None)


def _verdicts(m: Method, call: Callable[[float], Verdict]) -> Decide:
    def decide(x: float) -> tuple[bool | None, Verdict]:
        v = call(x)
        if v.status == FAILURE:
            m.explain(v)
        return v.admissible, v
    return decide


def _oracle(decide: Decide) -> Oracle:
    def oracle(x: float) -> Trial:
        side, v = decide(x)
        return Trial(x, side, "failure" if v.status == FAILURE else "", data=v)
    return oracle


# -- bracketing, then bisection: the rules of the searches on verdicts -------------------
def _bracketing(s: Search) -> bool:
    """The last trial was made before both ends were finite."""
    return s.last is not None and not all(map(math.isfinite, s.last.bracket))


def failed_while_bracketing(s: Search) -> bool:
    """The method failed on a trial made before f* or lambda* was bracketed."""
    return _bracketing(s) and s.last.kind == "failure"


def undecided_while_bracketing(s: Search) -> bool:
    """A lambda* trial made before an inadmissible upper end was found decided nothing:
    lambda* is not bracketed (friction trials go on doubling past such a trial)."""
    return _bracketing(s) and s.last.side is None and s.bad > s.good


STOPS = (failed_while_bracketing, undecided_while_bracketing, narrow_enough,
         undecided_band)


def doubling(ceiling: float) -> StepRule:
    """Double from 1 while an end is infinite; beyond ``ceiling`` the search stops
    ("beyond_ceiling")."""
    def double_up(s: Search) -> float | str | None:
        if all(map(math.isfinite, (s.bad, s.good))):
            return None
        trial = 2.0 * s.last.x if s.trials and s.last.x > 0 else 1.0
        return "beyond_ceiling" if trial > ceiling else trial
    return double_up


def friction_by_bisection(m: Method, load_factor: float, rtol: float) -> Limit:
    """f* by bracketing and bisection on the method's verdicts.

    f = infinite first (not admissible: "unstable"; undecided or failed: so stated),
    then f = 0, then doubling from 1 to bracket f* (an undecided trial does not raise the
    lower end), then bisection to ``rtol`` (the engine's rules :data:`STOPS` and
    :func:`doubling`). Past an undecided trial the bisection halves the parts of the
    bracket beside the undecided ones until they fill it: f* is the upper
    (certified admissible) end of the bracket, which goes into ``lower``, ``upper`` and
    the notes; if it is wider than ``rtol`` relative (plus ``BRACKET_ATOL``)
    the status is "undecided" and no f* is given.
    """
    lf = load_factor
    decide = _verdicts(m, lambda f: m.admissible(f, lf))
    ok_inf, v_inf = decide(math.inf)
    if ok_inf is not True:
        m.explain(v_inf)
        if v_inf.status == FAILURE:
            return Limit(FAILURE)
        return Limit("unstable" if ok_inf is False else "undecided")
    ok0, v0 = decide(0.0)
    if ok0 is True:
        return Limit("stable", 0.0, 0.0, 0.0, at=v0)
    s = run(Search(0.0, math.inf, rtol), _oracle(decide), STOPS,
            (doubling(FRICTION_CEILING), beside_the_undecided, midpoint), budget=BUDGET)
    for t in s.trials:
        if _bracket_trial(t) and t.side is None and t.kind != "failure":
            m.notes.append(f"the iteration could not decide at f = {t.x:.9g}")
    if s.stopped == "failed_while_bracketing":
        return Limit(FAILURE)
    if s.stopped == "beyond_ceiling":
        if s.last.side is not False:  # some trial was undecided: nothing is certified
            m.notes.append(f"no finite friction up to {FRICTION_CEILING:g} is certified "
                           f"admissible; f = {s.bad:.9g} is not admissible")
            return Limit("undecided")
        m.notes.append(f"no finite friction up to {FRICTION_CEILING:g} is admissible")
        return Limit("unstable")
    return _limit(m, s, "f", "stable")


def load_by_bisection(m: Method, f: float, rtol: float) -> Limit:
    """lambda* by bracketing and bisection on the method's verdicts.

    lambda = 0 must be admissible (else "unstable", or undecided/failure as declared);
    lambda is doubled from 1 until inadmissible ("unbounded" beyond ``UNBOUNDED_AT``),
    then bisected to ``rtol``; lambda* is the lower (certified admissible) end. Where a
    trial is undecided the status says so, with the reason in the notes and no number:
    at lambda = 0, while doubling (no inadmissible upper end), or when an undecided
    bisection trial leaves a bracket wider than ``rtol`` relative plus
    ``BRACKET_ATOL`` (a narrower one is reported in the notes).
    """
    decide = _verdicts(m, lambda lam: m.admissible(f, lam))
    ok0, v0 = decide(0.0)
    if v0.status == FAILURE:
        return Limit(FAILURE)
    if ok0 is not True:
        m.explain(v0)
        return Limit("undecided" if ok0 is None else "unstable")
    s = Search(math.inf, 0.0, rtol)
    s.record(Trial(0.0, True, data=v0))
    run(s, _oracle(decide), STOPS, (doubling(UNBOUNDED_AT), beside_the_undecided, midpoint),
        budget=BUDGET)
    if s.stopped == "failed_while_bracketing":
        return Limit(FAILURE)
    if s.stopped == "undecided_while_bracketing":  # lambda* is not bracketed
        m.explain(s.last.data)
        m.notes.append(f"the iteration could not decide at lambda = {s.last.x:.9g}; "
                       f"lambda = {s.good:.9g} is admissible, no upper bound is certified")
        return Limit("undecided", None, s.good, None)
    if s.stopped == "beyond_ceiling":
        return Limit("unbounded")
    return _limit(m, s, "lambda", "collapse")


def _bracket_trial(t: Trial) -> bool:
    """``t`` was made before both ends were finite."""
    return not all(map(math.isfinite, t.bracket))


def _limit(m: Method, s: Search, name: str, status: str) -> Limit:
    """The limit a search found: its certified end (``good``), or "undecided" when an
    undecided bisection trial stopped it with a bracket wider than the requested
    accuracy (plus ``BRACKET_ATOL``); the bracket goes into the notes either way."""
    br = Bracket(s.bad, s.good, s.end(True).data, _undecided_at(s))
    if br.undecided_at is not None:
        m.notes.append(f"the iteration could not decide at {name} = {br.undecided_at:.9g}: "
                       f"{name}* is bracketed in {fmt_bracket(br.lower, br.upper, 9)}")
        if br.too_wide(max(s.rtol, BRACKET_RTOL)):
            m.notes.append(f"accuracy {s.accuracy:.1e} reached, {s.rtol:.1e} requested "
                           "(rtol): undecided")
            return Limit("undecided", None, br.lower, br.upper)
    return Limit(status, br.good, br.lower, br.upper, at=br.good_data)


__all__ = ["BRACKET_ATOL", "BRACKET_RTOL", "Bracket", "bisect", "friction_by_bisection",
           "load_by_bisection"]
