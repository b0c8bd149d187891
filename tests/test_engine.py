"""The limit-search engine (rigidblocks.methods.engine) on synthetic oracles: what a
search finds, where it stops and what its record says, with no solver involved.

Reference values are the oracles' own closed forms (a verdict that changes at a known
x*, a linear or concave residual with a known root)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from rigidblocks.methods import friction_rules as fr
from rigidblocks.methods import load_rules as lr
from rigidblocks.methods.engine import WIDE, Search, Trial, bisection, run


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


def test_the_bisection_narrows_the_bracket_beside_undecided_trials():
    """A solver that cannot tell within w of x* = 0.4993 (the 7th midpoint of [0, 0.77]
    falls 3.1e-6 from it): the first undecided trial used to stop the search with the
    bracket it had (0.012 wide for w = 1e-5, 0.048 for w = 0.01). Past it the
    bisection halves the parts of the bracket beside the undecided trials: where the band
    is narrower than the requested accuracy the answer is a number as without the noise
    (w = 1e-5 at rtol = 1e-3 and 1e-4); where it is wider, the bracket ends at the band
    plus at most the accuracy (w = 0.01: within 0.03, at most UNDECIDED_TRIALS
    undecided trials)."""
    from rigidblocks.methods.engine import UNDECIDED_TRIALS

    x_star = 0.4993

    def noisy(w):
        def decide(x):
            return (None if abs(x - x_star) < w else x >= x_star), None
        return decide

    for rtol in (1e-3, 1e-4):
        s = bisection(noisy(1e-5), 0.0, 0.77, rtol)
        assert any(t.side is None for t in s.trials)  # the case the rule is for
        assert s.stopped == "narrow_enough", (rtol, s.stopped)
        assert s.bad < x_star <= s.good and s.width <= rtol * s.upper
    s = bisection(noisy(0.01), 0.0, 0.77, 1e-9)
    assert s.stopped == "undecided_band"
    assert sum(t.side is None for t in s.trials) <= UNDECIDED_TRIALS
    assert s.bad < x_star <= s.good and 0.02 <= s.width < 0.03


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


# -- the rules of f* on R(f) (rigidblocks.methods.friction_rules) on synthetic R ----------
TOL = 1e-12  # the synthetic solver's admissibility threshold


def _trial(f: float, R: float, slope: float, spread: float = 0.0) -> Trial:
    data = SimpleNamespace(by_value_floor=max(10 * TOL, 4 * spread), shortfall=spread)
    if R <= TOL:
        return Trial(f, True, "upper", data=data)
    return Trial(f, False, "lower", R, slope, data)


def newton_search(oracle, R0: float, s0: float, rtol: float = 1e-7,
                  spread: float = 0.0) -> Search:
    """The search of ConvexMethod.friction_limit after its first two trials: infinite
    friction admissible, f = 0 a lower point with R(0) = R0 and slope s0."""
    s = Search(0.0, math.inf, rtol, 1e-9)
    s.record(Trial(math.inf, True, "upper"))
    s.record(_trial(0.0, R0, s0, spread))
    return run(s, oracle, fr.STOPS, fr.STEPS, fr.AMENDS, budget=100)


def test_a_linear_R_is_solved_by_one_newton_step_and_certified_from_both_sides():
    """R(f) = 2 (0.4 - f)+: Newton's step from f = 0 lands on f* = 0.4 (an upper end);
    one probe just below certifies the bracket to rtol."""
    fs = 0.4

    def oracle(f):
        return _trial(f, max(0.0, 2.0 * (fs - f)), 2.0)

    s = newton_search(oracle, 0.8, 2.0)
    assert s.stopped == "narrow_enough"
    assert s.bad < fs <= s.good and s.width <= 1e-7 * s.good + 1e-9
    assert len(s.trials) - 2 <= 2


def test_a_concave_R_converges_from_below_in_a_few_steps():
    """R(f) = (f* - f)(f* + f + 1/2) (concave: the slope grows towards f*, Newton
    overshoots and the quadratic model corrects it); f* = 0.7."""
    fs = 0.7

    def oracle(f):
        return _trial(f, max(0.0, (fs - f) * (fs + f + 0.5)), 2.0 * f + 0.5)

    s = newton_search(oracle, fs * (fs + 0.5), 0.5)
    assert s.stopped == "narrow_enough" and s.bad < fs <= s.good
    assert s.width <= 1e-7 * s.good + 1e-9
    assert len(s.trials) - 2 <= 12


def _noisy(fs: float, band: float):
    """R = (f* - f)+ that the solver leaves at the threshold within ``band`` of f*."""
    def oracle(f):
        R = max(0.0, fs - f)
        if 0 < R <= band or 0 < f - fs <= band:
            return Trial(f, None, "threshold", R + band, 1.0, None)
        return _trial(f, R, 1.0, spread=band)
    return oracle


def test_a_noisy_solver_ends_at_its_resolution_with_a_bracket():
    """A solver whose R carries 3e-6 of noise (its duals' spread says so) and that
    cannot decide within it of f* = 0.3 (trials at the threshold): the search ends where
    R below the upper end is predicted below that resolution, with f* in a bracket
    within WIDE, no trial repeated, in a few solves."""
    fs, band = 0.3, 3e-6
    oracle = _noisy(fs, band)

    s = newton_search(oracle, fs, 1.0, spread=band)
    assert s.stopped == "resolution_reached"
    assert s.bad < fs <= s.good and s.width <= WIDE * s.good
    xs = [t.x for t in s.trials]
    assert len(xs) == len(set(xs)) and len(xs) - 2 <= 5


def test_a_failing_solver_near_f_star_gives_up_after_missed_limit_trials():
    """Every solve within 1e-3 of f* = 0.5 fails (no checked answer): after
    MISSED_LIMIT + 1 such trials in a row the search stops with its bracket."""
    fs = 0.5

    def oracle(f):
        if abs(f - fs) <= 1e-3:
            return Trial(f, None, "missed", why="failed")
        return _trial(f, max(0.0, fs - f), 1.0)

    s = newton_search(oracle, fs, 1.0)
    assert s.stopped in ("missed_too_often", "undecided_there_before")
    assert s.bad < fs <= s.good
    if s.stopped == "missed_too_often":
        assert s.trailing("missed") == fr.MISSED_LIMIT + 1


def test_an_infimum_stops_where_forces_go_beyond_resolution():
    """f* = 0.2 approached with forces growing without bound: R > 0 up to f* (R >= 1e-9
    there), and within 1e-4 above it the forces are beyond what the solver resolves. The
    search stops at the first such trial with f* as its lower end and no certified upper
    end (the method reports no number)."""
    fs = 0.2

    def oracle(f):
        if fs < f < fs + 1e-4:
            return Trial(f, None, "forces-span", why="forces span")
        return _trial(f, max(fs - f, 1e-9), 1.0)

    s = newton_search(oracle, fs, 1.0)
    assert s.stopped == "forces_beyond_resolution"
    assert s.bad == fs and s.good == math.inf and s.last.x > fs


# -- the rules of f* on lambda*(f) (rigidblocks.methods.load_rules) ----------------------
def load_search(lam, dlam, lf: float, first: float, margin: float = 0.0,
                rtol: float = 1e-7) -> Search:
    """The search of LoadSearch._friction_by_load on a synthetic lambda*(f) whose
    solver resolves it to ``margin``."""
    def oracle(f):
        data = SimpleNamespace(tight=True, margin=margin, finer=False, at=None,
                               by_value=False)
        r = lam(f) - lf
        if r >= 0:
            return Trial(f, True, "upper", r, dlam(f), data)
        if r + margin < 0:
            return Trial(f, False, "lower", r, dlam(f), data)
        return Trial(f, None, "unresolved", r, dlam(f), data)

    s = Search(0.0, math.inf, rtol, 1e-9)
    return run(s, oracle, lr.STOPS, (lr.start_at(first), *lr.STEPS), budget=lr.BUDGET)


def test_a_concave_lambda_star_is_bracketed_to_rtol_from_both_sides():
    """lambda*(f) = 2 sqrt(f) (concave: Newton's step up falls short, the convex model
    and the step down from the upper end close in); lambda* = 1 at f* = 0.25."""
    s = load_search(lambda f: 2 * math.sqrt(f), lambda f: 1 / math.sqrt(f), 1.0, 0.01)
    assert s.stopped == "narrow_enough"
    assert s.bad < 0.25 <= s.good and s.width <= 1e-7 * s.good + 1e-9
    assert len(s.trials) <= 8


def test_a_lambda_star_resolved_coarsely_stops_with_its_bracket():
    """lambda*(f) = f resolved to 1e-4 only, lf = 0.5: trials within that of lf decide
    nothing; the search ends with f* in a bracket within WIDE, not at rtol."""
    s = load_search(lambda f: f, lambda f: 1.0, 0.5, 0.1, margin=1e-4)
    assert s.stopped in ("unresolved_bracket", "ends_within_resolution", "narrow_enough")
    assert s.bad < 0.5 <= s.good and s.width <= WIDE * s.good
    assert len(s.trials) <= 4  # Newton lands on f*: a probe below, not a bisection


def test_the_lambda_star_search_hands_back_within_its_budget():
    """A solver whose every answer is unusable (hand-back) ends the search at once; one
    whose lambda* never reaches lf runs out of its budget of trials."""
    def unusable(f):
        return Trial(f, None, "hand-back", data=SimpleNamespace(tight=True, margin=0.0,
                                                                finer=False))

    s = Search(0.0, math.inf, 1e-7, 1e-9)
    run(s, unusable, lr.STOPS, (lr.start_at(0.3), *lr.STEPS))
    assert s.stopped == "handed_back" and len(s.trials) == 1
    s = load_search(lambda f: 0.5 * (1 - math.exp(-f)), lambda f: 0.5 * math.exp(-f), 1.0,
                    0.1)
    assert s.stopped == "budget" and len(s.trials) == lr.BUDGET


def test_no_admissible_multiplier_below_f_star_is_followed_by_doubling():
    """No multiplier is admissible below f = 0.2 (the max-load LP infeasible: a lower end
    of residual -inf and slope 0), lambda*(f) = 5 (f - 0.2) above: the search doubles
    from the first trial (to 1 at least), then Newton's step down from there lands on
    f* = 0.4 (lambda* = lf = 1) and a probe just below it certifies the bracket."""
    def lam(f):
        return -math.inf if f < 0.2 else 5 * (f - 0.2)

    s = load_search(lam, lambda f: 0.0 if f < 0.2 else 5.0, 1.0, 0.1)
    assert s.stopped == "narrow_enough" and s.bad < 0.4 <= s.good
    assert s.trials[1].x == 1.0 and s.trials[1].rule == "first_upper_end"
    assert len(s.trials) == 4


# -- the requested accuracy: the search's target and what a number is certified to ------
@pytest.mark.parametrize("rtol", [1e-2, 1e-4, 1e-7])
def test_the_requested_accuracy_is_the_target_of_the_newton_search(rtol):
    """R(f) = (f* - f)(f* + f + 1/2), f* = 0.7 (concave): the search ends at the
    requested accuracy, with the accuracy reached (the bracket's relative width) within
    it, in fewer trials for a coarser accuracy."""
    fs = 0.7

    def oracle(f):
        return _trial(f, max(0.0, (fs - f) * (fs + f + 0.5)), 2.0 * f + 0.5)

    s = newton_search(oracle, fs * (fs + 0.5), 0.5, rtol=rtol)
    fine = newton_search(oracle, fs * (fs + 0.5), 0.5, rtol=1e-9)
    assert s.stopped == "narrow_enough" and s.narrow() and s.accuracy <= rtol
    assert s.bad < fs <= s.good and s.accuracy == pytest.approx(s.width / s.good)
    assert len(s.trials) <= len(fine.trials)


def test_a_search_stopped_at_its_solver_resolution_reports_the_accuracy_reached():
    """The noisy solver of above (R resolved to 3e-6 about f* = 0.3): asked for 1e-7
    the search ends short of it (not narrow: the analyses give no number) with the
    accuracy it reached; asked for 1e-3, the accuracy it reaches, it ends narrow."""
    fs, band = 0.3, 3e-6
    oracle = _noisy(fs, band)

    tight = newton_search(oracle, fs, 1.0, spread=band)
    assert not tight.narrow() and 1e-7 < tight.accuracy <= WIDE
    assert tight.bad < fs <= tight.good
    coarse = newton_search(oracle, fs, 1.0, rtol=1e-3, spread=band)
    assert coarse.stopped == "narrow_enough" and coarse.accuracy <= 1e-3
    assert coarse.bad < fs <= coarse.good


def test_a_lambda_star_resolved_coarsely_decides_at_an_accuracy_it_reaches():
    """lambda*(f) = f resolved to 1e-4, lf = 0.5: asked for 1e-7 the search ends short
    (accuracy above 1e-7); asked for 1e-2 it ends narrow, f* = 0.5 in the bracket."""
    tight = load_search(lambda f: f, lambda f: 1.0, 0.5, 0.1, margin=1e-4)
    assert not tight.narrow() and tight.accuracy > 1e-7
    coarse = load_search(lambda f: f, lambda f: 1.0, 0.5, 0.1, margin=1e-4, rtol=1e-2)
    assert coarse.narrow() and coarse.accuracy <= 1e-2
    assert coarse.bad < 0.5 <= coarse.good


def test_a_number_only_where_the_bracket_meets_the_requested_accuracy():
    """The analyses' rule on a limit a method found (analyses.core.certified): f* = 1.0
    bracketed in [0.999, 1.0] (accuracy 1e-3) is a number at rtol = 2e-3, and undecided
    with its bracket at 1e-4, the note giving both accuracies; a point (f* = 0 found at
    f = 0) and a bracket within the absolute floor are numbers."""
    from rigidblocks.analyses.core import certified
    from rigidblocks.methods import Limit

    m = SimpleNamespace(notes=[])
    lim = Limit("stable", 1.0, 0.999, 1.0)
    assert certified(m, lim, 2e-3, "f*") is lim and not m.notes
    out = certified(m, lim, 1e-4, "f*")
    assert out.status == "undecided" and out.value is None
    assert (out.lower, out.upper) == (0.999, 1.0) and out.accuracy == pytest.approx(1e-3)
    assert "accuracy 1.0e-03 reached, 1.0e-04 requested" in m.notes[-1]
    assert certified(m, Limit("stable", 0.0, 0.0, 0.0), 1e-9, "f*").value == 0.0
    assert certified(m, Limit("stable", 1e-9, 0.0, 1e-9), 1e-3, "f*", 1e-9).value == 1e-9
