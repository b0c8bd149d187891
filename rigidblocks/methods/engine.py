"""The limit-search engine: one loop (stop?, propose, evaluate, record) for every limit
the package brackets.

A search keeps a bracket [``bad``, ``good``] (either order: ``good`` is the end certified
on the limit's safe side, f >= f* for a friction, lambda <= lambda* for a load) and the
record of its trials. Each round the **stop rules** are asked in order (the first that
answers ends the search, its name is :attr:`Search.stopped`); then the **step rules**
in order (the first that proposes a point gives the trial; a rule may also end the search
by returning a reason); then the **amend rules** may move or refuse that point; the
**oracle** evaluates it (the only part that knows a solver) and the trial is recorded:
a trial on the good side moves ``good``, one on the bad side ``bad``, an undecided one
neither. A search that runs out of its budget stops with "budget".

Rules are small named functions of the search (``Search -> answer | None``): a rule set
is an ordered list of them next to their constants, and notes are rendered once from the
record (:attr:`Search.trials`, each with the rule that proposed it and the oracle's kind).
:func:`bisection` is the rule set of a bisection on a verdict.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from ..results import within

#: the effort bound at the solver's resolution: where trials near the limit decide
#: nothing, a bracket this narrow (relative) is not narrowed further by stepping past
#: them, and the method gives its certified end with the bracket. Whether that is a
#: number for the engineer is the requested accuracy's call (the analyses give one
#: only where the bracket meets ``rtol``)
WIDE = 1e-3
#: trials a search makes at most where its caller sets no budget of its own
MAX_TRIALS = 200


@dataclass(eq=False)
class Trial:
    """One evaluation: where (``x``), on which side (True: good, False: bad, None: it
    decides nothing), the oracle's kind of answer (its own word: "upper", "lower",
    "threshold", "missed", ...), the residual it read there and its slope (for step
    rules that model it), the oracle's data, why it decides nothing (where it does not),
    and, filled in by the engine, the step rule that proposed it and the bracket it was
    proposed in."""

    x: float
    side: bool | None
    kind: str = ""
    value: float = math.nan
    slope: float = math.nan
    data: Any = None
    why: str = ""
    rule: str = ""
    bracket: tuple[float, float] = (math.nan, math.nan)


@dataclass
class Search:
    """A bracket, its record of trials and the requested accuracy."""

    bad: float
    good: float
    rtol: float
    atol: float = 0.0
    trials: list[Trial] = field(default_factory=list)
    #: the name of the rule that ended the search ("" while it runs)
    stopped: str = ""
    #: the trial the ending rule was about to make, where a step or amend rule ended it
    at: float | None = None

    @property
    def lower(self) -> float:
        return min(self.bad, self.good)

    @property
    def upper(self) -> float:
        return max(self.bad, self.good)

    @property
    def width(self) -> float:
        return abs(self.good - self.bad)

    @property
    def last(self) -> Trial | None:
        return self.trials[-1] if self.trials else None

    def ends(self, side: bool) -> list[Trial]:
        """The trials that moved the ``side`` end (True: good), in order."""
        return [t for t in self.trials if t.side is side]

    def end(self, side: bool) -> Trial | None:
        """The trial at the ``side`` end (None while no trial moved it)."""
        moved = self.ends(side)
        return moved[-1] if moved else None

    def after(self, t: Trial) -> list[Trial]:
        """The trials recorded after ``t``."""
        for i, u in enumerate(self.trials):
            if u is t:
                return self.trials[i + 1:]
        return []

    def of_kind(self, *kinds: str) -> list[Trial]:
        return [t for t in self.trials if t.kind in kinds]

    def trailing(self, kind: str, through: tuple[str, ...] = ()) -> int:
        """How many trials of ``kind`` the latest ones hold in a row (trials of the
        ``through`` kinds among them neither count nor break the row)."""
        n = 0
        for t in reversed(self.trials):
            if t.kind == kind:
                n += 1
            elif t.kind not in through:
                break
        return n

    @property
    def accuracy(self) -> float:
        """The accuracy reached: the bracket's width relative to its larger end (inf
        while an end is infinite)."""
        if not math.isfinite(self.width):
            return math.inf
        scale = max(abs(self.good), abs(self.bad))
        return self.width / scale if scale > 0 else 0.0

    def narrow(self, loosest: float = 0.0) -> bool:
        """|good - bad| <= rtol max(|good|, |bad|) + atol (never with an infinite end);
        with ``loosest``, max(rtol, loosest) in place of rtol."""
        return within(self.good, self.bad, max(self.rtol, loosest), self.atol)

    def record(self, t: Trial) -> None:
        """Keep ``t`` and move the end on its side."""
        if t.side is True:
            self.good = t.x
        elif t.side is False:
            self.bad = t.x
        self.trials.append(t)


#: a rule: Search -> None (pass) or its answer (stop: a reason; step: a point or a
#: reason to stop)
StopRule = Callable[[Search], "str | bool | None"]
StepRule = Callable[[Search], "float | str | None"]
#: an amend rule: (Search, proposed point) -> the point to try, or a reason to stop
AmendRule = Callable[[Search, float], "float | str"]
Oracle = Callable[[float], Trial]


def run(search: Search, oracle: Oracle, stops: Sequence[StopRule],
        steps: Sequence[StepRule], amends: Sequence[AmendRule] = (),
        budget: int = MAX_TRIALS) -> Search:
    """Run ``search`` to its end (see the module docstring); returns it."""
    for _ in range(budget):
        for stop in stops:
            if stop(search):
                search.stopped = stop.__name__
                return search
        point, rule = _propose(search, steps, amends)
        if isinstance(point, str):
            search.stopped = point
            return search
        before = (search.bad, search.good)
        t = oracle(point)
        t.rule, t.bracket = rule, before
        search.record(t)
    search.stopped = "budget"
    return search


def _propose(search: Search, steps: Sequence[StepRule],
             amends: Sequence[AmendRule]) -> tuple[float | str, str]:
    """The first step rule's answer, through the amend rules, and its rule's name."""
    for step in steps:
        point = step(search)
        if point is not None:
            break
    else:
        return "no step", ""
    if isinstance(point, str):
        return point, step.__name__
    for amend in amends:
        moved = amend(search, point)
        if isinstance(moved, str):
            search.at = point
            return moved, step.__name__
        point = moved
    return point, step.__name__


# -- bisection: two step rules, two stop rules -------------------------------------------
#: undecided trials a bisection makes at most: past them the band of x where the method
#: cannot decide is taken to fill what is left of the bracket beside the decided ends
UNDECIDED_TRIALS = 4


def narrow_enough(s: Search) -> bool:
    """The bracket meets the requested accuracy."""
    return s.narrow()


def undecided_trial(s: Search) -> bool:
    """The last trial decided nothing: the bracket stands as it is."""
    return s.last is not None and s.last.side is None


def midpoint(s: Search) -> float:
    """Halve the bracket."""
    return 0.5 * (s.bad + s.good)


def _undecided_inside(s: Search) -> tuple[float, float] | None:
    """The span of the undecided trials strictly inside the bracket (None: none)."""
    xs = [t.x for t in s.trials if t.side is None and s.lower < t.x < s.upper]
    return (min(xs), max(xs)) if xs else None


def undecided_band(s: Search) -> bool:
    """Undecided trials fill the bracket: UNDECIDED_TRIALS of them were made, or the
    parts of the bracket beside them are each narrower than half the requested
    accuracy (what is left is the band where the method cannot decide)."""
    band = _undecided_inside(s)
    if band is None:
        return False
    if sum(t.side is None for t in s.trials) >= UNDECIDED_TRIALS:
        return True
    half = 0.5 * (s.rtol * max(abs(s.good), abs(s.bad)) + s.atol)
    return band[0] - s.lower <= half and s.upper - band[1] <= half


def beside_the_undecided(s: Search) -> float | None:
    """Halve the wider part of the bracket beside its undecided trials (a method that
    cannot decide near the limit still decides farther from it); None where no trial
    inside the bracket is undecided."""
    band = _undecided_inside(s)
    if band is None:
        return None
    if band[0] - s.lower >= s.upper - band[1]:
        return 0.5 * (s.lower + band[0])
    return 0.5 * (band[1] + s.upper)


def bisection(decide: Callable[[float], tuple[bool | None, Any]], bad: float, good: float,
              rtol: float, atol: float = 0.0, steps: int = MAX_TRIALS) -> Search:
    """Halve [bad, good] (either order) on ``decide(x) -> (True: good, False: bad, None:
    undecided; data)`` until it is :meth:`Search.narrow` (stop "narrow_enough"), at most
    ``steps`` times (stop "budget"); past an undecided trial it halves the parts of the
    bracket beside the undecided ones until they fill it (stop "undecided_band")."""
    def oracle(x: float) -> Trial:
        side, data = decide(x)
        return Trial(x, side, data=data)

    return run(Search(bad, good, rtol, atol), oracle, (narrow_enough, undecided_band),
               (beside_the_undecided, midpoint), budget=steps)


__all__ = ["MAX_TRIALS", "UNDECIDED_TRIALS", "WIDE", "AmendRule", "Oracle", "Search",
           "StepRule", "StopRule", "Trial", "beside_the_undecided", "bisection", "midpoint",
           "narrow_enough", "run", "undecided_band", "undecided_trial"]
