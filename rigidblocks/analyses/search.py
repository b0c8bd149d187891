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
from ..methods.engine import WIDE, bisection

#: a bisection stopped by an undecided trial with a bracket wider than BRACKET_RTOL
#: relative plus BRACKET_ATOL gives no number (the floor: f* or lambda* = 0); the
#: engine's WIDE, as for every search
BRACKET_RTOL = WIDE
BRACKET_ATOL = 1e-6
#: largest friction tried when bracketing f* from above
FRICTION_CEILING = 1e8
#: largest load multiplier tried when bracketing lambda* (beyond it: "unbounded")
UNBOUNDED_AT = 1e6

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
        """Wider than ``rtol`` relative to its upper end plus ``atol``."""
        return self.upper - self.lower > rtol * abs(self.upper) + atol


def bisect(decide: Decide, bad: float, good: float, rtol: float, atol: float = 0.0,
           steps: int = 200) -> Bracket:
    """Halve [bad, good] (either order) until |good - bad| <= rtol max(|good|, |bad|) +
    atol, at most ``steps`` times; an undecided trial stops it (the engine's
    :func:`~rigidblocks.methods.engine.bisection`)."""
    s = bisection(decide, bad, good, rtol, atol, steps)
    passed = s.end(True)
    return Bracket(s.bad, s.good, passed.data if passed else None,
                   s.last.x if s.stopped == "undecided_trial" else None)


def _verdicts(m: Method, call: Callable[[float], Verdict]) -> Decide:
    def decide(x: float) -> tuple[bool | None, Verdict]:
        v = call(x)
        if v.status == FAILURE:
            m.explain(v)
        return v.admissible, v
    return decide


def friction_by_bisection(m: Method, load_factor: float, rtol: float) -> Limit:
    """f* by bracketing and bisection on the method's verdicts.

    f = infinite first (not admissible: "unstable"; undecided or failed: so stated),
    then f = 0, then doubling from 1 to bracket f* (an undecided trial does not raise the
    lower end), then bisection to ``rtol``. An undecided trial ends the bisection: f* is
    the upper (certified admissible) end of the bracket, which goes into ``lower``,
    ``upper`` and the notes; if it is wider than ``BRACKET_RTOL`` relative (plus
    ``BRACKET_ATOL``) the status is "undecided" and no f* is given.
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
    lo, hi, best = 0.0, 1.0, None
    while True:
        ok, v = decide(hi)
        if v.status == FAILURE:
            return Limit(FAILURE)
        if ok is True:
            best = v
            break
        if ok is False:
            lo = hi
        else:
            m.notes.append(f"the iteration could not decide at f = {hi:.9g}")
        hi = 2 * hi
        if hi > FRICTION_CEILING:
            if lo < hi / 2:  # some trial was undecided: nothing is certified
                m.notes.append(f"no finite friction up to {FRICTION_CEILING:g} is certified "
                               f"admissible; f = {lo:.9g} is not admissible")
                return Limit("undecided")
            m.notes.append(f"no finite friction up to {FRICTION_CEILING:g} is admissible")
            return Limit("unstable")
    return _limit(m, bisect(decide, lo, hi, rtol), "f", "stable", best)


def load_by_bisection(m: Method, f: float, rtol: float) -> Limit:
    """lambda* by bracketing and bisection on the method's verdicts.

    lambda = 0 must be admissible (else "unstable", or undecided/failure as declared);
    lambda is doubled from 1 until inadmissible ("unbounded" beyond ``UNBOUNDED_AT``),
    then bisected to ``rtol``; lambda* is the lower (certified admissible) end. Where a
    trial is undecided the status says so, with the reason in the notes and no number:
    at lambda = 0, while doubling (no inadmissible upper end), or when an undecided
    bisection trial leaves a bracket wider than ``BRACKET_RTOL`` relative plus
    ``BRACKET_ATOL`` (a narrower one is reported in the notes).
    """
    decide = _verdicts(m, lambda lam: m.admissible(f, lam))
    ok0, v0 = decide(0.0)
    if v0.status == FAILURE:
        return Limit(FAILURE)
    if ok0 is not True:
        m.explain(v0)
        return Limit("undecided" if ok0 is None else "unstable")
    lo, hi, best = 0.0, 1.0, v0
    while True:
        ok, v = decide(hi)
        if v.status == FAILURE:
            return Limit(FAILURE)
        if ok is None:  # no inadmissible upper end: lambda* is not bracketed
            m.explain(v)
            m.notes.append(f"the iteration could not decide at lambda = {hi:.9g}; "
                           f"lambda = {lo:.9g} is admissible, no upper bound is certified")
            return Limit("undecided", None, lo, None)
        if ok is False:
            break
        lo, best = hi, v
        hi *= 2
        if hi > UNBOUNDED_AT:
            return Limit("unbounded")
    return _limit(m, bisect(decide, hi, lo, rtol), "lambda", "collapse", best)


def _limit(m: Method, br: Bracket, name: str, status: str, best: Verdict | None) -> Limit:
    """The limit a bisection found: its certified end (``good``), or "undecided" when an
    undecided trial stopped it with a bracket wider than ``BRACKET_RTOL``; the bracket
    goes into the notes either way."""
    if br.undecided_at is not None:
        m.notes.append(f"the iteration could not decide at {name} = {br.undecided_at:.9g}: "
                       f"{name}* is bracketed in [{br.lower:.9g}, {br.upper:.9g}]")
        if br.too_wide():
            m.notes.append(f"bracket wider than {BRACKET_RTOL:g} relative: undecided")
            return Limit("undecided", None, br.lower, br.upper)
    return Limit(status, br.good, br.lower, br.upper, at=br.good_data or best)


__all__ = ["BRACKET_ATOL", "BRACKET_RTOL", "Bracket", "bisect", "friction_by_bisection",
           "load_by_bisection"]
