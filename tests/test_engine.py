"""The limit-search engine (rigidblocks.methods.engine) on synthetic oracles: what a
search finds, where it stops and what its record says, with no solver involved.

Reference values are the oracles' own closed forms (a verdict that changes at a known
x*, a linear or concave residual with a known root)."""

from __future__ import annotations

import math

import pytest

from rigidblocks.methods.engine import Search, Trial, bisection, run


def test_bisection_brackets_a_verdict_to_the_requested_accuracy():
    """Admissible from x* = 0.3 upwards: the bracket holds x*, meets rtol, and every
    trial halves it (so it took ceil(log2(width / (rtol x*))) trials)."""
    xs = 0.3
    s = bisection(lambda x: (x >= xs, x), 0.0, 1.0, 1e-6)
    assert s.stopped == "narrow_enough"
    assert s.bad < xs <= s.good and s.width <= 1e-6 * s.good
    assert len(s.trials) == math.ceil(math.log2(1.0 / (1e-6 * s.good)))
    assert s.end(True).data == s.good  # the data of the last passing trial
    assert all(t.rule == "midpoint" for t in s.trials)


def test_bisection_of_a_decreasing_verdict_keeps_its_order():
    """A load multiplier: admissible up to lambda* = 2.5, bracket given as [bad, good] =
    [8, 0]: the good end stays below lambda*, the bad end above."""
    s = bisection(lambda lam: (lam <= 2.5, None), 8.0, 0.0, 1e-9)
    assert s.good <= 2.5 < s.bad and s.upper - s.lower <= 1e-9 * 2.5 + 1e-15


def test_an_undecided_trial_stops_the_bisection_with_its_bracket():
    """A solver that cannot tell within 0.01 of x* = 0.5: the search stops at the first
    such trial, with the bracket it had (still holding x*) and that trial last."""
    def noisy(x):
        return (None if abs(x - 0.5) < 0.01 else x >= 0.5), None

    s = bisection(noisy, 0.0, 0.77, 1e-9)
    assert s.stopped == "undecided_trial"
    assert s.last.side is None and abs(s.last.x - 0.5) < 0.01
    assert s.bad < 0.5 <= s.good and s.width > 1e-9


def test_a_failing_oracle_propagates_its_error_and_a_budget_ends_a_search():
    def failing(x):
        raise RuntimeError("solver failed")

    with pytest.raises(RuntimeError, match="solver failed"):
        bisection(failing, 0.0, 1.0, 1e-6)
    s = bisection(lambda x: (x >= 0.3, None), 0.0, 1.0, 0.0, steps=5)
    assert s.stopped == "budget" and len(s.trials) == 5 and s.width == 1.0 / 32


def test_rules_in_order_first_answer_wins_and_names_the_stop():
    """A stop rule ends the search by its name; the first step rule that proposes a
    point is recorded as the trial's rule; an amend rule may refuse the point."""
    def enough(s: Search) -> bool:
        return len(s.trials) >= 3

    def never(s: Search) -> None:
        return None

    def quarter(s: Search) -> float:
        return s.bad + 0.25 * (s.good - s.bad)

    s = run(Search(0.0, 1.0, 0.0), lambda x: Trial(x, False), (enough,), (never, quarter))
    assert s.stopped == "enough" and [t.rule for t in s.trials] == ["quarter"] * 3
    assert s.trials[1].bracket == (0.25, 1.0) and s.bad == pytest.approx(1 - 0.75 ** 3)

    def refuse(s: Search, x: float) -> str:
        return "refused"

    s = run(Search(0.0, 1.0, 0.0), lambda x: Trial(x, False), (), (quarter,), (refuse,))
    assert s.stopped == "refused" and s.at == 0.25 and not s.trials
