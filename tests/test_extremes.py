"""Right or honestly undecided at the extremes: blocks of very different sizes (per-block
scaling), every back end's answer checked, infima reached only with unbounded forces,
the distortion method's inadmissibility certificate, and monotone verdicts on walls.

Every case is worked out by hand in its docstring.
"""

from __future__ import annotations

import math
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest
from conftest import EXAMPLES, make_scene, rect

from rigidblocks import check, max_load_multiplier, min_friction
from rigidblocks.generators.solids import box, solid
from rigidblocks.generators.walls import running_bond_wall
from rigidblocks.io import read_scene, scene_from_dict
from rigidblocks.methods import friction_rules as fr
from rigidblocks.methods import open_method
from rigidblocks.methods.convex import FRICTION_ATOL, FRICTION_RTOL
from rigidblocks.methods.engine import WIDE, Search, Trial, run
from rigidblocks.methods.friction_search import GOVERNING_SHARE, trial_of
from rigidblocks.methods.relaxation import SPREAD_MARGIN, Relaxation
from rigidblocks.scene.model import Load
from rigidblocks.solvers import clarabel_backend, policy
from rigidblocks.solvers.base import SolverResult, normalised
from rigidblocks.solvers.clarabel_backend import (
    STALL_WINDOW,
    _distance,
    _Stall,
    solve_clarabel,
)


def small_on_big(w: float, h: float, x0: float = 0.0, live: bool = True):
    """A w x h block on top of a 1000 x 1000 block, on a support, infinite friction."""
    top = {"live_body_force": [1, 0]} if live else {}
    return make_scene([
        {"id": "base", "vertices": rect(-600, -100, 1200, 100), "support": True},
        {"id": "big", "vertices": rect(-500, 0, 1000, 1000)},
        {"id": "small", "vertices": rect(x0, 1000, w, h)},
    ], unit_weight=20.0, friction="infinite", **top)


# -- 1. a small block on a huge one -------------------------------------------------------

@pytest.mark.parametrize("w", [0.1, 0.01, 1e-3])
def test_small_block_on_huge_one_tips_at_its_own_b_over_h(w):
    """A w x 3w block on a 1000 x 1000 block, infinite friction, horizontal body force
    lambda x weight on both. The small block tips about its downstream toe when the
    moment of lambda W at its centroid (arm 3w/2) exceeds that of W (arm w/2):
    lambda = w / 3w = 1/3. The big block (with the small one on it) tips at about
    b/h = 1, later. So lambda* = 1/3: at 0.3 admissible, at 0.5 not. With one reference
    force for the whole scene the small block's equilibrium (weight 2e-7 of the big
    one's at w = 1e-3) drowned in the big block's round-off and lambda* was 1."""
    s = small_on_big(w, 3 * w)
    r = max_load_multiplier(s, state=False)
    assert r.status == "collapse"
    assert r.load_multiplier == pytest.approx(1 / 3, rel=1e-6)
    assert check(s, load_factor=0.3, state=False).status == "admissible"
    c = check(s, load_factor=0.5, state=False)
    assert c.status == "inadmissible" and c.violation > 0
    hi = max_load_multiplier(s, solver="highs", state=False)
    assert hi.answered_by == ("highs",) and not hi.rejected  # a real cross-check
    assert hi.load_multiplier == pytest.approx(1 / 3, rel=1e-6)


@pytest.mark.parametrize("w", [0.1, 1e-3])
def test_tiny_block_overhanging_the_edge_is_not_admissible(w):
    """A w x 3w block whose centroid lies 0.1 w beyond the big block's right edge
    (x = 500), under its own weight: the contact segment is [500 - 0.4 w, 500], and a
    compression-only resultant within it cannot pass through the centroid's vertical at
    500 + 0.1 w: inadmissible. Moved 0.2 w back (centroid 0.1 w inside the edge) it
    stands."""
    out = small_on_big(w, 3 * w, x0=500 - 0.4 * w, live=False)
    assert check(out, load_factor=0.0, state=False).status == "inadmissible"
    inside = small_on_big(w, 3 * w, x0=500 - 0.6 * w, live=False)
    assert check(inside, load_factor=0.0, state=False).status == "admissible"


def test_small_box_on_huge_cube_3d():
    """3D: a 1 x 1 x 2 box on a 1000 m cube on a support, horizontal body force along
    x, infinite friction: the box tips about its downstream bottom edge at
    lambda = b/h = 1/2 (the cube, b/h = 1, later): lambda* = 0.5."""
    doc = {"format": "rigidblocks-scene", "version": 1, "dimension": 3,
           "unit_weight": 20.0, "friction": "infinite", "live_body_force": [1, 0, 0],
           "blocks": [solid("base", box(-600, -600, -100, 1200, 1200, 100), support=True),
                      solid("cube", box(-500, -500, 0, 1000, 1000, 1000)),
                      solid("box", box(0, 0, 1000, 1, 1, 2))]}
    r = max_load_multiplier(scene_from_dict(doc), state=False)
    assert r.status == "collapse"
    assert r.load_multiplier == pytest.approx(0.5, rel=1e-6)


def test_forces_beyond_resolution_are_undecided():
    """A 1000 x 1000 block (weight 2e7) balanced on a 1e-2 x 1e-2 shim (weight 2e-3)
    centred under it: the shim's joints carry 1e10 times its own load, so its joint laws
    could be judged only to 1e-9 x 1e10 of that load. The verdict is undecided, with the
    reason, rather than a verdict the arithmetic cannot support."""
    s = make_scene([
        {"id": "base", "vertices": rect(-600, -100, 1200, 100), "support": True},
        {"id": "shim", "vertices": rect(-0.005, 0, 0.01, 0.01)},
        {"id": "big", "vertices": [[-500, 0.01], [500, 0.01], [500, 1000.01],
                                   [-500, 1000.01]]},
    ], unit_weight=20.0, friction="infinite")
    c = check(s, load_factor=0.0, state=False)
    assert c.status == "undecided"
    assert any("forces span" in n for n in c.notes)


def _light_block_under_a_point_load(unit_weight):
    """Block A (1 x 0.5) on a base, block B (1 x 0.5) on A, a 10 kN dead point load at
    B's top centre and a 1 kN live horizontal one there, f = 0.6. Weightless, the
    stack tips about the base's edge under A at lambda = 10 x 0.5 / 1 = 5 (B on A at
    10, sliding at 0.6 x 10 = 6): lambda* = 5 (docs/validation.md, block on a
    support)."""
    return make_scene([
        {"id": "base", "vertices": rect(0, 0, 2, 0.5), "support": True},
        {"id": "A", "vertices": rect(0.5, 0.5, 1, 0.5)},
        {"id": "B", "vertices": rect(0.5, 1.0, 1, 0.5)},
    ], unit_weight=unit_weight, friction=0.6, depth=1.0,
        loads=[{"block": "B", "force": [0, -10], "point": [1.0, 1.5]},
               {"block": "B", "force": [1, 0], "point": [1.0, 1.5], "live": True}])


@pytest.mark.parametrize("unit_weight", [1e-13, 1e-10])
def test_a_nearly_weightless_block_carrying_a_load_gets_no_wrong_verdict(unit_weight):
    """Block A weighing 1e-13 (or 1e-10) of the 10 kN it carries: its per-block scale
    left the forces through it 1e13 times its load. The solver then reported the
    relaxation infeasible, read as "the scene is a mechanism" (NOT ADMISSIBLE, and
    `load` and `friction` UNSTABLE), or the maximum-load LP gave lambda* = -1.37e-6
    (UNSTABLE), where the weightless scene collapses at lambda* = 5. A verdict the
    arithmetic cannot support is undecided, with the reason; the right one is
    accepted too."""
    assert max_load_multiplier(_light_block_under_a_point_load(0.0), state=False,
                               compare_dry=False).load_multiplier == pytest.approx(5.0)
    s = _light_block_under_a_point_load(unit_weight)
    for lf in (0.0, 1.0):
        c = check(s, load_factor=lf, state=False, compare_dry=False)
        assert c.status in ("admissible", "undecided"), (lf, c.status, c.notes)
    r = max_load_multiplier(s, state=False, compare_dry=False)
    assert r.status == "undecided" or (
        r.status == "collapse" and r.load_multiplier == pytest.approx(5.0, rel=1e-6)), \
        (r.status, r.load_multiplier, r.notes)
    fr_ = min_friction(s, load_factor=1.0, state=False, compare_dry=False)
    assert fr_.status in ("stable", "undecided"), (fr_.status, fr_.notes)
    if r.status == "undecided":
        assert any("not a mechanism" in n or "forces span" in n or "fails its check" in n
                   for n in r.notes), r.notes


def test_the_equations_residual_of_a_true_mechanism_is_its_load():
    """The least-squares confirmation leaves a true mechanism as it was: a block drawn
    0.5 m above its support carries its weight (10 N of the 10 N loads) on nothing, so
    the equations miss a solution by all of it; the light block under a point load
    above has a solution (residual round-off). Read on the assembled system: every
    analysis refuses the floating block before it."""
    from rigidblocks.contacts import detect_contacts
    from rigidblocks.equilibrium import assemble

    s = make_scene([
        {"id": "base", "vertices": rect(0, 0, 2, 0.5), "support": True},
        {"id": "A", "vertices": rect(0.5, 1.0, 1, 0.5)},
    ], unit_weight=20.0, friction=0.6)
    system = assemble(s, detect_contacts(s))
    assert system.equations_residual(0.0) == pytest.approx(1.0, rel=1e-9)
    light = _light_block_under_a_point_load(1e-13)
    assert assemble(light, detect_contacts(light)).equations_residual(1.0) < 1e-12


# -- 5. every back end's answer checked ---------------------------------------------------

def _sloppy(solve):
    """A back end wrapper that spoils every optimal answer of "osqp" (the state scaled by
    1 + 1e-3, so that equilibrium fails by 1e-3 of the loads) and of every back end when
    ``everyone`` is set."""
    state = {"everyone": False}

    def spoilt(problem, solver="clarabel", **settings):
        res = solve(problem, solver, **settings)
        if res.z is not None and (solver == "osqp" or state["everyone"]):
            return SolverResult(res.status, res.z * (1 + 1e-3), res.y, res.objective,
                                res.solver, res.raw_status)
        return res

    return spoilt, state


def test_an_answer_failing_its_check_is_solved_again(monkeypatch, block_on_base):
    """A b = 1, h = 2 block with f = 0.4 slides at lambda* = f = 0.4 (it tips at
    b/h = 0.5). A back end whose states miss equilibrium by 1e-3 of the loads is caught
    by the residual check, the problem is solved again by Clarabel, and the result says
    so; when every answer is spoilt the verdict is undecided with the residuals."""
    spoilt, state = _sloppy(policy.solve)
    monkeypatch.setattr(policy, "solve", spoilt)
    s = block_on_base(1.0, 2.0, 0.4)
    r = max_load_multiplier(s, solver="osqp", state=False)
    assert r.load_multiplier == pytest.approx(0.4, rel=1e-6)
    assert any("solved again by clarabel" in n for n in r.notes)
    fr = min_friction(s, load_factor=0.3, solver="osqp", state=False)
    assert fr.friction_factor == pytest.approx(0.3, rel=1e-6)
    state["everyone"] = True
    c = check(s, load_factor=0.2, state=False)
    assert c.status == "undecided"
    assert any("primal residual" in n for n in c.notes)
    r = max_load_multiplier(s, state=False)
    assert r.status == "undecided" and r.load_multiplier is None


@pytest.mark.parametrize("solver", ["clarabel", "highs"])
def test_clarabel_solved_again_by_itself_is_no_fallback(monkeypatch, block_on_base, solver):
    """An answer that fails its check is solved again by Clarabel: by the fallback where
    another back end gave it (the result is then no cross-check of that back end, and
    the answer says so), at the next settings of its own ladder where Clarabel, the
    default, gave it (the flat arch on fixed abutments, `friction --flow
    non-associative`, said "not a cross-check of clarabel by clarabel"). The rejection
    is simulated on the runner (one recorded), the answer itself is the block's
    lambda* = f = 0.4."""
    from rigidblocks.answer import split_notes
    from rigidblocks.methods import open_method

    cv = open_method(block_on_base(1.0, 2.0, 0.4), "clarabel", solver=solver)
    run = cv.runner.run

    def rejecting(problem, what, ladder):
        res = run(problem, what, ladder)
        cv.runner.rejected.append(f"the {what} problem ({solver} infeasible: certificate "
                                  "residual 3.3e-06)")
        return res

    monkeypatch.setattr(cv.runner, "run", rejecting)
    assert cv.load_limit(0.4, 1e-9).value == pytest.approx(0.4, rel=1e-6)
    (note,) = [n for n in cv.notes if "solved again" in n]
    by = "at the next settings of its ladder" if solver == "clarabel" else "by clarabel"
    assert note.startswith(f"answers of {solver} that failed their check against the "
                           f"problem were solved again {by} (first: "), note
    reasons, _ = split_notes(cv.notes)
    denied = [n for n in reasons if "not a cross-check" in n]
    assert denied == ([] if solver == "clarabel" else
                      [f"some answers of {solver} failed their check and were solved again "
                       f"by clarabel: the result is not a cross-check of clarabel by "
                       f"{solver}"])


def test_tight_tolerances_out_of_reach_go_on_at_1e_9(monkeypatch, block_on_base):
    """Where Clarabel cannot reach the tight tolerances (1e-10; the relaxations of a
    20,093-block wall), the retries go on at 1e-9 before its defaults, and the
    analysis's later tight solves start there: the b = 1, h = 2 block under 0.3 times
    its weight still needs f* = 0.3 (it slides; it would tip at b/h = 0.5) and slides
    at lambda* = f = 0.4, 1e-10 is tried once, and the result says so."""
    asked = []
    policy_solve = policy.solve

    def refusing_tight(status: str, iterations: int = 0):
        """A back end that fails at 1e-10 after ``iterations`` and records the asks."""
        def solve(problem, solver="clarabel", **settings):
            asked.append(settings.get("tol_feas"))
            if settings.get("tol_feas") == 1e-10:
                return SolverResult("failure", None, None, math.nan, solver, status,
                                    iterations=iterations)
            return policy_solve(problem, solver, **settings)
        return solve

    no_tight = refusing_tight("InsufficientProgress")
    monkeypatch.setattr(policy, "solve", no_tight)
    s = block_on_base(1.0, 2.0, 0.4)
    fr = min_friction(s, load_factor=0.3, state=False, compare_dry=False)
    assert fr.friction_factor == pytest.approx(0.3, rel=1e-6)
    assert asked[:3] == [1e-10, 1e-10, 1e-9]  # tight, refined, then 1e-9
    # at the defaults only the search on lambda*(f)'s first max-load LP
    assert asked.count(1e-10) == 2 and asked.count(None) == 1
    assert any("ran at 1e-9" in n for n in fr.notes)
    # a failure after many iterations (a large problem) goes to 1e-9 without the
    # refined retry, which would cost as many again
    asked.clear()
    monkeypatch.setattr(policy, "solve",
                        refusing_tight("AlmostSolved", policy.REFINE_WITHIN))
    assert min_friction(s, load_factor=0.3, state=False,
                        compare_dry=False).friction_factor == pytest.approx(0.3, rel=1e-6)
    assert asked[:2] == [1e-10, 1e-9] and asked.count(1e-10) == 1
    monkeypatch.setattr(policy, "solve", no_tight)
    r = max_load_multiplier(s, state=False, compare_dry=False)
    assert r.load_multiplier == pytest.approx(0.4, rel=1e-6)
    # verdicts then compare with 1e-8 of the largest force: ten times the solver's 1e-9
    monkeypatch.setattr(policy, "solve", policy_solve)
    m = open_method(s)
    before = m.relaxation(1.0, 0.3).tol
    m.runner.out_of_reach.add("clarabel")
    assert m.relaxation(1.0, 0.3).tol == pytest.approx(10 * before)


def test_the_flags_of_a_solve_name_its_ladder():
    """A solve asked for by flags (ConvexMethod.solve's tight, stall, refine, confirm, as
    the non-associative analysis asks) climbs the ladder declared for that intent: a
    verdict (tight), a value (tight, no stall stop), a confirmation, a force state (no
    refined retry), an estimate at the back end's defaults; a tight solve without the
    refined retry is its ladder without it."""
    assert policy.ladder_of(tight=True) is policy.VERDICT
    assert policy.ladder_of(tight=True, stall=False) is policy.VALUE
    assert policy.ladder_of(confirm=True) is policy.CONFIRMATION
    assert policy.ladder_of(refine=False) is policy.STATE
    assert policy.ladder_of() is policy.ESTIMATE
    bare = policy.ladder_of(tight=True, refine=False)
    assert bare.tight and bare.stall and not bare.refine
    assert not policy.VALUE.stall and policy.VERDICT.stall and not policy.STATE.refine


def _info(iterations, res, gap=None, ktratio=0.0):
    """What Clarabel's termination callback is given, with both residuals ``res``."""
    gap = res if gap is None else gap
    return SimpleNamespace(iterations=iterations, res_primal=res, res_dual=res,
                           gap_abs=gap, gap_rel=gap, ktratio=ktratio)


def test_a_stalled_solve_stops_where_it_meets_the_next_solves_tolerances():
    """The termination callback of a 1e-10 solve whose next solve would be at 1e-9: the
    20,093-block relaxation at f = 1 met 1e-9 after 88 iterations, came within 2.8 of
    1e-10 after 104 and no closer up to its limit of 200."""
    own, nine = (1e-10,) * 3, (1e-9,) * 3
    # residuals halving every iteration: it converges, never stopped
    stall = _Stall(own, nine)
    assert not any(stall(_info(k, 1e-3 * 0.5 ** k)) for k in range(30))
    # stuck at 2.8e-10 from iteration 68: it stops within STALL_WINDOW iterations of that
    stall = _Stall(own, nine)
    stop = next(k for k in range(200) if stall(_info(k, max(1e-3 * 0.8 ** k, 2.8e-10))))
    assert 68 < stop <= 68 + STALL_WINDOW and stall.stopped
    # stuck where only looser tolerances are met (5e-9), or on the way to an
    # infeasibility certificate (kappa/tau above 1): it runs on to its own end
    for res, ktratio in ((5e-9, 0.0), (1e-12, 10.0)):
        stall = _Stall(own, nine)
        assert not any(stall(_info(k, res, ktratio=ktratio)) for k in range(100))
        assert not stall.stopped
    # the gap counts by the closer of its absolute and relative forms, as in Clarabel
    assert _distance(SimpleNamespace(res_primal=0, res_dual=0, gap_abs=1.0, gap_rel=5e-11,
                                     ktratio=0.0), own) == pytest.approx(0.5)


def test_a_stalled_clarabel_solve_answers_at_the_next_solves_tolerances():
    """A real stall: the relaxation of a 20 x 20 running-bond wall at f = 1 under its
    live load, asked of Clarabel at 1e-12, ends AlmostSolved after about 100
    iterations. Given 1e-9 as the next solve's settings, it stops once stalled with an
    answer that meets 1e-9 and passes the policy's check; given Clarabel's defaults
    ({}: whole settings, not changes to the 1e-12 ones), with one that meets 1e-8; where
    it ends short by itself, it carries its last iterate where that meets them."""
    m = open_method(running_bond_wall(20, 20))
    prob, _ = m.relaxation_problem(1.0, 1.0)
    tight = {"tol_feas": 1e-12, "tol_gap_abs": 1e-12, "tol_gap_rel": 1e-12}
    alone = solve_clarabel(prob, **tight)
    assert alone.status == "failure" and alone.iterations >= 100 and not alone.next_met
    nine = {"tol_feas": 1e-9, "tol_gap_abs": 1e-9, "tol_gap_rel": 1e-9}
    res = solve_clarabel(prob, after=nine, **tight)
    assert res.status == "optimal" and res.next_met and "1e-09" in res.raw_status
    assert res.iterations <= alone.iterations // 2
    assert policy.verified(prob, res).verified
    res = solve_clarabel(prob, after={}, **tight)
    assert res.next_met and "1e-08" in res.raw_status and "stalled" in res.raw_status
    # ended short by itself (its iteration limit: AlmostSolved, Clarabel's reduced
    # tolerances met) with a last iterate that meets 1e-8: a failure that carries it
    res = solve_clarabel(prob, after={}, **tight, max_iter=40)
    assert res.status == "failure" and res.next_met and res.iterations == 40
    assert "AlmostSolved" in res.raw_status
    assert policy.verified(prob, replace(res, status="optimal")).verified


def test_a_ctrl_c_inside_the_stall_callback_interrupts_the_solve(monkeypatch):
    """A Ctrl-C that lands in the termination callback (here raised by its distance
    test at the third iteration) reaches the caller as KeyboardInterrupt: raised inside
    Clarabel's call it printed a traceback, was dropped, and the solve answered."""
    m = open_method(running_bond_wall(4, 4))
    prob, _ = m.relaxation_problem(1.0, 1.0)
    calls = []

    def distance(info, tol):
        calls.append(info.iterations)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return 1.0

    monkeypatch.setattr(clarabel_backend, "_distance", distance)
    with pytest.raises(KeyboardInterrupt):
        solve_clarabel(prob, after={})
    assert len(calls) == 3


@pytest.mark.parametrize("status, iterations, asks", [
    ("optimal", 120, 1), ("failure", 150, 1), ("failure", 12, 2)])
def test_a_solve_settled_at_the_next_solves_tolerances_is_not_solved_again(
        monkeypatch, block_on_base, status, iterations, asks):
    """A back end that stops short of 1e-10 with an answer meeting the 1e-9 of the next
    solve it was given (solved here at 1e-9): stalled ("optimal"), or ended by itself with a
    last iterate that meets it ("failure"). The policy takes that answer with no further
    solve (after a failure within REFINE_WITHIN iterations, after the refined retry,
    which fails outright), and later tight solves start at 1e-9, as where 1e-10 failed
    outright. The b = 1, h = 2 block under 0.3 of its weight needs f* = 0.3."""
    asked = []
    policy_solve = policy.solve

    def settling(problem, solver="clarabel", after=None, **settings):
        asked.append(settings.get("tol_feas"))
        if settings.get("tol_feas") == 1e-10:
            if after is None:  # the refined retry: not given the next solve; it fails
                return SolverResult("failure", None, None, math.nan, solver, "AlmostSolved",
                                    iterations=iterations)
            assert after["tol_feas"] == 1e-9
            return replace(policy_solve(problem, solver, **after), status=status,
                           next_met=True, iterations=iterations, raw_status="short of 1e-10")
        # the 1e-9 relaxations that follow are given Clarabel's defaults as the next
        assert settings.get("tol_feas") != 1e-9 or after == {} or "r" not in problem.cols
        return policy_solve(problem, solver, after=after, **settings)

    monkeypatch.setattr(policy, "solve", settling)
    # (the associative search's solves alone: not the comparison without dilatancy)
    fr = min_friction(block_on_base(1.0, 2.0, 0.4), load_factor=0.3, state=False,
                      compare_dry=False)
    assert fr.friction_factor == pytest.approx(0.3, rel=1e-6)
    # at the defaults only the search on lambda*(f)'s first max-load LP
    assert asked[:asks] == [1e-10] * asks and set(asked[asks:]) == {1e-9, None}
    assert asked.count(None) == 1
    assert any("ran at 1e-9" in n for n in fr.notes)


def test_a_stalled_force_state_qp_is_solved_once(monkeypatch, block_on_base):
    """Where the least-energy QP stalls (the 5,006-block wall at f*: AlmostSolved after
    200 iterations, and again with refined settings), it is not retried: the state of
    the solved limit problem serves, and the result says so. The b = 1, h = 2 block
    under 0.3 times its weight: f* = 0.3, the state carries that shear on its base."""
    qp = []

    def stalled(problem, solver="clarabel", **settings):
        if problem.P is not None:
            qp.append(settings)
            return SolverResult("failure", None, None, math.nan, solver, "AlmostSolved")
        return policy_solve(problem, solver, **settings)

    policy_solve = policy.solve
    monkeypatch.setattr(policy, "solve", stalled)
    fr = min_friction(block_on_base(1.0, 2.0, 0.4), load_factor=0.3,
                      compare_dry=False)
    assert fr.friction_factor == pytest.approx(0.3, rel=1e-6) and len(qp) == 1
    assert fr.state is not None and fr.state.method == "solution of the limit problem"
    assert any("least-energy QP ended with status AlmostSolved" in n for n in fr.notes)
    assert float(np.sum(np.abs(fr.state.joint_shear))) == pytest.approx(0.3 * 2.0,
                                                                          rel=1e-6)


def _duals_changed(change):
    """The policy's back end with ``change(y)`` applied to the duals of every answer."""
    solve = policy.solve

    def changed(problem, solver="clarabel", **settings):
        res = solve(problem, solver, **settings)
        if res.y is None:
            return res
        return SolverResult(res.status, res.z, change(res.y), res.objective, res.solver,
                            res.raw_status)

    return changed


def test_friction_trial_failing_its_check_decides_by_itself(monkeypatch, block_on_base):
    """A trial of the f* search whose answer fails the residual check (1e-3 added to
    each of its duals: more than a scale, which the check undoes) is still read where it
    decides by itself: at f = 1 (f* = 0.3, see above) its state is admissible, at
    f = 0.1 its dual bound stays above the threshold (R = 0.2 of the block's weight,
    relative to it); a plain relaxation with the same answer is undecided."""
    monkeypatch.setattr(policy, "solve", _duals_changed(lambda y: y + 1e-3))
    m = open_method(block_on_base(1.0, 2.0, 0.4))
    for f, decided in ((1.0, "zero"), (0.1, "positive")):
        rx = m.relaxation(f, 0.3, confirm=False, self_certified=True)
        assert rx.res.verified is False and getattr(rx, decided)
        assert not m.relaxation(f, 0.3, confirm=False).decided


def _cone_duals_raised(by):
    """The policy's back end with ``by`` added to the duals of the inequality rows whose
    right-hand side is 0: the duals stay in their cone and the dual objective -b'y is
    unchanged, so only the dual residual fails the check."""
    def change(problem, y):
        y = y.copy()
        rows = problem.b == 0
        rows[:problem.n_eq] = False
        y[rows] += by
        return y

    solve = policy.solve

    def raised(problem, solver="clarabel", **settings):
        res = solve(problem, solver, **settings)
        if res.y is None:
            return res
        return replace(res, y=change(problem, res.y))

    return raised


def test_friction_trial_failing_on_its_duals_alone_steers_by_value(monkeypatch,
                                                                  block_on_base):
    """A trial of the f* search whose answer fails the check on its dual residual alone
    (state and gap pass) is read by its value where that exceeds what the residual could
    account for (SPREAD_MARGIN = 4 times its spread), like a checked answer whose dual
    bound is too weak: the 20,093-block wall at f = 1.2573 left R = 0.570 with a spread
    of 0.120 and a dual residual of 6.3e-5. The b = 1, h = 2 block under 0.3 of its
    weight (f* = 0.3) at f = 0.1 has R = 0.2 of its weight; 0.03 added to its cone rows'
    duals leaves the dual bound below 0 and a spread of 0.066: R is 3 times that, not a
    lower point (with a margin of 2 it would be); 0.1 added, a spread of 0.22: nothing
    either way. A state that misses equilibrium is never read by value."""
    from rigidblocks.methods import relaxation

    clean = policy.solve

    def read(by):
        monkeypatch.setattr(policy, "solve", clean)
        monkeypatch.setattr(policy, "solve", _cone_duals_raised(by))
        m = open_method(block_on_base(1.0, 2.0, 0.4))
        return m, m.relaxation(0.1, 0.3, confirm=False, self_certified=True)

    m, rx = read(0.03)
    r = rx.res.residuals
    assert rx.res.verified is False and r["dual"] > 1e-2
    assert max(r["primal"], r["gap"]) < 1e-9
    assert rx.unresolved and not rx.by_value  # 3 times its spread
    monkeypatch.setattr(relaxation, "SPREAD_MARGIN", 2.0)
    m, rx = read(0.03)
    assert not rx.positive and rx.by_value and not rx.unresolved
    assert rx.R == pytest.approx(0.2, rel=1e-6) and rx.spread == pytest.approx(0.066, rel=1e-3)
    assert not m.relaxation(0.1, 0.3, confirm=False).decided  # a plain verdict: undecided
    m, rx = read(0.1)
    assert rx.unresolved and not rx.by_value
    monkeypatch.setattr(policy, "solve", clean)
    spoilt, state = _sloppy(_cone_duals_raised(0.03))
    state["everyone"] = True
    monkeypatch.setattr(policy, "solve", spoilt)
    rx = open_method(block_on_base(1.0, 2.0, 0.4)).relaxation(0.1, 0.3, confirm=False,
                                                              self_certified=True)
    assert rx.res.residuals["primal"] > 1e-6 and rx.unresolved and not rx.by_value


def test_duals_off_by_a_scale_are_normalised_not_rejected(monkeypatch, block_on_base):
    """An answer whose duals are right but for their scale (x (1 + 1e-3): the dual
    residual of the relaxation variable 1e-3, as an interior-point solver leaves it at
    5e-6 on a 1,000-block wall near f*) passes the check once normalised: the verdicts
    at f = 1 (admissible) and f = 0.1 (R = 0.2, certified by the dual bound) are those
    of the clean answer, and the residual before normalisation is kept. A problem with
    more than one variable in its objective is not normalised."""
    m = open_method(block_on_base(1.0, 2.0, 0.4))
    clean = {f: m.relaxation(f, 0.3, confirm=False) for f in (1.0, 0.1)}
    scaled = _duals_changed(lambda y: y * (1 + 1e-3))
    monkeypatch.setattr(policy, "solve", scaled)
    m = open_method(block_on_base(1.0, 2.0, 0.4))
    for f, decided in ((1.0, "zero"), (0.1, "positive")):
        rx = m.relaxation(f, 0.3, confirm=False)
        assert rx.res.verified is True and getattr(rx, decided)
        assert rx.res.residuals["normalised"] > 1e-4
        assert rx.res.residuals["dual"] < 1e-9
        assert rx.R == pytest.approx(clean[f].R, abs=1e-9)
        assert rx.low == pytest.approx(clean[f].low, rel=1e-6, abs=1e-9)
    prob, _ = m.relaxation_problem(0.1, 0.3)
    two = type(prob)(**{**prob.__dict__, "c": prob.c + 1.0})
    assert normalised(two, scaled(prob)) is None


TOL = 1e-9  # the threshold of the synthetic relaxations below


def _rx(f: float, R: float | None, low: float = -1.0, spread: float = 0.0,
        unresolved: str = "") -> Relaxation:
    """The numbers of a relaxation at f (no solve): value R, dual bound ``low``, slope 1
    (R = f* - f below f*), threshold TOL."""
    return Relaxation(R, 1.0, None, None, None, TOL, f, low, 0.0, unresolved, spread)


def _certified(fs: float):
    """R(f) = (fs - f)+ with slope 1, every trial certified (an admissible state above
    fs, the dual bound at R below)."""
    def relax(f: float) -> Relaxation:
        R = max(0.0, fs - f)
        return _rx(f, R, low=R)
    return relax


def r_search(relax, rtol: float = 1e-7) -> Search:
    """The search on R(f) of ConvexMethod.friction_limit on the relaxations ``relax(f)``
    (infinite friction admissible, f = 0 from ``relax``), each read by trial_of."""
    s = Search(0.0, math.inf, rtol, FRICTION_ATOL)
    s.record(Trial(math.inf, True, "upper"))
    s.record(trial_of(0.0, relax(0.0)))
    return run(s, lambda f: trial_of(f, relax(f)), fr.STOPS, fr.STEPS, fr.AMENDS,
               budget=fr.BUDGET)


def test_a_relaxation_value_within_its_spread_is_no_lower_point():
    """The f* search takes a relaxation's value far above the threshold for a lower
    point even where the dual bound cannot certify it, but not where the duals'
    residual could account for that value (its spread, sum |d_j z_j| on the state): on
    the extruded 5,006-block wall at 1e-9, R = 8.4e-4 = 51 thresholds where the plane
    wall's state of R = 0 exists, with a spread of 6.0e-3. A value of 100 thresholds
    with no dual bound is a lower point by value where it exceeds SPREAD_MARGIN times its
    spread, and decides nothing within it (with the reason). R(f) = (0.3 - f)+ with such
    values on [0.3, 0.45]: the bracket still holds f* = 0.3 (taking them as lower
    points would bracket f* at 0.45), they are trials that decide nothing, and the
    search ends without a bracket narrow enough for a number."""
    far = 100 * TOL
    within = trial_of(0.4, _rx(0.4, far, spread=far / SPREAD_MARGIN * 1.01))
    assert within.side is None and within.kind == "missed"
    assert "its duals' residual could account for" in within.why
    beyond = trial_of(0.4, _rx(0.4, far, spread=far / SPREAD_MARGIN * 0.99))
    assert beyond.side is False and beyond.kind == "lower-by-value"
    assert trial_of(0.4, _rx(0.4, far, low=2 * TOL, spread=1.0)).kind == "lower"
    assert trial_of(0.4, _rx(0.4, 5 * TOL, spread=0.0)).kind == "threshold"  # not far

    exact = _certified(0.3)

    def relax(f):
        return _rx(f, far, spread=1.0) if 0.3 - 1e-9 <= f <= 0.45 else exact(f)

    s = r_search(relax)
    assert s.bad <= 0.3 < 0.45 < s.good
    assert s.of_kind("missed") and not s.of_kind("lower-by-value")
    assert s.stopped == "missed_too_often" or not s.narrow(WIDE)


def test_osqp_at_its_defaults_is_checked():
    """The flat arch with vertical joints needs f* = 0.4714045 under its own weight
    (Clarabel, HiGHS). OSQP at its defaults answered relaxations loosely enough to
    report 0.851; checked and re-solved, its answer is Clarabel's."""
    s = read_scene(EXAMPLES / "flat_arch_vertical.json")
    ref = min_friction(s, load_factor=0.0, state=False).friction_factor
    r = min_friction(s, load_factor=0.0, solver="osqp", state=False)
    assert r.friction_factor == pytest.approx(ref, rel=1e-6)


# -- 6. an infimum reached only with unbounded forces -------------------------------------

def pinched(t: float = 0.5, h: float = 1.0, a: float = 0.5):
    """A trapezoid block hanging between two supports whose faces overhang it: its sides
    lean inwards by d = t h over its height h, it has nothing below it."""
    d = t * h
    return make_scene([
        {"id": "L", "vertices": [[-a - d - 1, 0], [-a - d, 0], [-a, h], [-a - d - 1, h]],
         "support": True},
        {"id": "R", "vertices": [[a + d, 0], [a + d + 1, 0], [a + d + 1, h], [a, h]],
         "support": True},
        {"id": "B", "vertices": [[-a - d, 0], [a + d, 0], [a, h], [-a, h]]},
    ], unit_weight=1.0, friction=1.0)


def test_friction_infimum_with_unbounded_forces_is_said_to_be_one():
    """Each overhanging face (length L = sqrt(h^2 + d^2)) pushes the block with N,
    inwards and downwards (vertical part N d / L), and holds it with friction T <= f N
    along the face (vertical part T h / L). Vertical equilibrium of the weight W:
    2 (T h - N d) / L = W, so N >= W L / (2 (f h - d)): admissible for every
    f > d / h = 0.5, with forces growing like 1 / (f - 0.5), and never at f = 0.5. f* =
    0.5 is an infimum that is not attained; the answer says so, and a check at
    f = 0.5 (1 + 1e-5), with N = 1.1e5 W, says how large the forces are."""
    s = pinched()
    r = min_friction(s, state=False, rtol=1e-7)
    assert r.status == ("stable" if r.accuracy <= 1e-7 else "undecided")
    assert 0.5 <= r.upper <= 0.5 * (1 + 1e-3)
    assert any("infimum" in n for n in r.notes)
    assert check(s, friction=0.5, state=False).status == "inadmissible"
    c = check(s, friction=0.5 * (1 + 1e-5), state=False)
    assert c.status == "admissible"
    assert any("times the loads" in n for n in c.notes)


# -- 4. the distortion method's certificate -----------------------------------------------

def pushed_block(H: float):
    """A 1 x 1 block (weight W = 1) on a base, pushed by a live horizontal force H at
    its centroid height."""
    return make_scene([
        {"id": "base", "vertices": rect(-2, -1, 5, 1), "support": True},
        {"id": "B", "vertices": rect(0, 0, 1, 1)},
    ], unit_weight=1.0, friction=0.3,
        loads=[{"block": "B", "force": [H, 0], "point": [0.5, 0.5], "live": True}])


@pytest.mark.parametrize("k", [1.001, 1.01])
def test_distortion_never_calls_inadmissible_just_above_f_star(k):
    """Sliding on the bed joint needs f >= H / W; tipping about the toe needs
    H (1/2) <= W (1/2), H <= W: with H = 0.3 W, f* = 0.3 (a slab that does not tip).
    Just above f* (0.1 % and 1 %) an admissible state exists; the distortion method may
    find it or stay undecided, but never certifies that none exists. Below f*, at 0.9
    f*, its certificate holds."""
    s = pushed_block(0.3)
    c = check(s, friction=0.3 * k, method="distortion", state=False)
    assert c.status in ("admissible", "undecided")
    assert check(s, friction=0.27, method="distortion", state=False).status == \
        "inadmissible"


def test_mechanism_certificate_rejects_a_motion_that_breaches_the_flow_rule(monkeypatch):
    """The block of the previous test under H = 0.3 W. At f = 0.2 (< f* = 0.3), sliding
    to the right while lifting by f times the slip (velocity (1, 0.2), no rotation)
    follows the associative flow rule exactly, and the loads do work H - 0.2 W = 0.1 W
    > 0 on it: no admissible state exists (Farkas' lemma). The same motion without the
    lift slides without opening: it breaches the flow rule at both contact points by
    f x slip = 0.2, so an admissible state would only need forces of the order of
    0.1 / 0.4 of the loads: unpolished it certifies nothing, polished (the lift added)
    it is the mechanism above. At f = 0.4 (> f*) every motion that follows the flow
    rule takes work: H - 0.4 W < 0 for the sliding one, and nothing certifies."""
    from rigidblocks.solvers import distortion

    m = open_method(pushed_block(0.3), "distortion")
    ds = m.solver_
    b = ds.rhs(1.0)

    def cert(f, vel):
        # duals y = -v (scaled rows), and the drift g with C g = A^T y
        y = -np.array(vel) / ds.scaling.row
        return ds.mechanism_of(ds.laws(m.f_joint(f)), ds.gather(ds.K * (ds.AsT @ y)), b,
                               1.0)

    exact = cert(0.2, (1.0, 0.2, 0.0))
    assert exact is not None
    assert exact[0] == pytest.approx(0.1 / ds.scaling.force, rel=1e-9)
    assert cert(0.2, (1.0, 0.0, 0.0)) is not None  # polished into the exact one
    assert cert(0.4, (1.0, 0.4, 0.0)) is None
    assert cert(0.4, (1.0, 0.0, 0.0)) is None
    monkeypatch.setattr(distortion, "POLISH", 0)
    assert cert(0.2, (1.0, 0.0, 0.0)) is None
    assert cert(0.2, (1.0, 0.2, 0.0)) is not None


# -- 8. monotone verdicts on walls of growing size ----------------------------------------

WALLS = [(1, 2), (3, 4), (8, 12), (20, 25)]


@pytest.mark.parametrize("courses,per_course", WALLS)
def test_wall_verdicts_are_monotone(courses, per_course):
    """Admissibility is monotone in f (a state admissible at f is admissible at any
    larger f) and in the load factor below lambda* (the admissible multipliers form an
    interval containing 0 when the dead load stands). On running-bond walls of growing
    size: with lambda* at f = 0.6 from the LP, lambda* (1 - 1e-4) is admissible at f =
    0.6, 1 and infinite; lambda* (1 + 1e-4) is not at f = 0.6; f* at lambda* (1 - 1e-4)
    is at most 0.6."""
    s = running_bond_wall(courses=courses, blocks_per_course=per_course, friction=0.6)
    lam = max_load_multiplier(s, state=False).load_multiplier
    below, above = lam * (1 - 1e-4), lam * (1 + 1e-4)
    for f in (0.6, 1.0, "infinite"):
        assert check(s, friction=f, load_factor=below, state=False).status == "admissible"
    assert check(s, friction=0.6, load_factor=above, state=False).status == "inadmissible"
    fr = min_friction(s, load_factor=below, state=False, rtol=1e-7)
    assert fr.upper <= 0.6 * (1 + 1e-7)  # the certified end


@pytest.mark.slow
@pytest.mark.parametrize("courses,per_course", [(50, 100), (100, 200)])
def test_big_wall_verdicts_are_monotone(courses, per_course):
    """The 5,000- and 20,000-block running-bond walls (0.4 x 0.2 m blocks, f = 0.6,
    horizontal live body force): lambda* at f = 0.6 is 0.385 (20,000 blocks), so at load
    factor 0.2 the wall stands at f = 0.6 and, a fortiori, with infinite friction (the
    20,000-block wall was called inadmissible there, violation 1e-8); the friction it
    needs there is at most 0.6 (checked on the 5,000-block wall: min_friction on the
    20,000-block one takes more than half an hour on two shared cores)."""
    s = running_bond_wall(courses=courses, blocks_per_course=per_course, friction=0.6)
    assert check(s, friction="infinite", load_factor=0.2, state=False).status == "admissible"
    assert check(s, friction=0.6, load_factor=0.2, state=False).status == "admissible"
    if courses * per_course <= 5000:
        fr = min_friction(s, load_factor=0.2, state=False, rtol=1e-7)
        assert fr.upper <= 0.6


# -- property: hand limits of free-standing top blocks bound lambda* ----------------------

def top_block_bound(scene, f: float) -> float:
    """The smallest of min(f, b/h) over the free-standing top blocks of a scene of
    rectangles under a horizontal body force (+x): a block that touches nothing but the
    blocks it rests on, over its whole width (horizontal bed joints), slides at
    lambda = f and tips about its right toe at lambda = (b/2) / (h/2) = b/h with
    everything else held still. Each is a mechanism (a neighbour at its side would
    resist the slip of the tipping block on their head joint, and is excluded), so
    lambda* <= min(f, b/h)."""
    boxes = {}
    for blk in scene.blocks:
        p = np.asarray(blk.points)
        boxes[blk.id] = (p[:, 0].min(), p[:, 1].min(), p[:, 0].max(), p[:, 1].max(),
                         blk.support)
    bound = math.inf
    for bid, (x0, y0, x1, y1, sup) in boxes.items():
        if sup:
            continue
        eps = 1e-9 * max(x1 - x0, y1 - y0)
        covered = side = False
        rests = 0.0
        for oid, (a0, b0, a1, b1, _) in boxes.items():
            if oid == bid:
                continue
            if abs(b0 - y1) <= eps and a1 > x0 + eps and a0 < x1 - eps:
                covered = True
            if (abs(a0 - x1) <= eps or abs(a1 - x0) <= eps) and b1 > y0 + eps and \
                    b0 < y1 - eps:
                side = True
            if abs(b1 - y0) <= eps:
                rests += max(0.0, min(x1, a1) - max(x0, a0))
        if covered or side or rests < (x1 - x0) * (1 - 1e-9):
            continue
        bound = min(bound, f, (x1 - x0) / (y1 - y0))
    return bound


def random_stack(rng, n: int, f: float):
    """n rectangles stacked on a support, sizes log-uniform over four orders of
    magnitude, each wholly on the one below (offset at random within it)."""
    blocks = [{"id": "base", "vertices": rect(-1e3, -10, 2e3, 10), "support": True}]
    x, y, w_below = -50.0, 0.0, 100.0
    for i in range(n):
        w = min(w_below, 10 ** rng.uniform(-1.5, 2.0))
        h = 10 ** rng.uniform(-1.5, 2.0)
        x = x + rng.uniform(0, w_below - w)
        blocks.append({"id": f"s{i}", "vertices": rect(x, y, w, h)})
        y, w_below = y + h, w
    return make_scene(blocks, unit_weight=20.0, friction=f, live_body_force=[1, 0])


@pytest.mark.parametrize("seed", range(12))
def test_top_block_limits_bound_lambda_star_on_random_stacks(seed):
    """Property (see :func:`top_block_bound`): lambda* <= min(f, b/h) of the top block
    of a random stack, whatever the spread of the block sizes below it."""
    rng = np.random.default_rng(seed)
    f = float(rng.uniform(0.2, 1.5))
    s = random_stack(rng, int(rng.integers(1, 7)), f)
    bound = top_block_bound(s, f)
    assert math.isfinite(bound)
    r = max_load_multiplier(s, state=False)
    if r.status == "collapse":
        assert r.load_multiplier <= bound * (1 + 1e-7)
    else:
        assert r.status in ("unstable", "undecided")


@pytest.mark.parametrize("courses,per_course", [(1, 1), (2, 3), (4, 10), (12, 30), (25, 40)])
def test_top_block_limits_bound_lambda_star_on_walls(courses, per_course):
    """Property (see :func:`top_block_bound`) on running-bond walls of many sizes and
    block proportions, with every other block of the top course left out so that the
    others stand free: each slides at f and tips at b/h (a half block at b/h / 2)."""
    top = courses - 1
    gaps = [(top, 1, i, 1) for i in range(1, per_course, 2)]
    for f, (bl, bh) in ((0.6, (0.4, 0.2)), (0.9, (0.2, 0.5))):
        s = running_bond_wall(courses=courses, blocks_per_course=per_course, friction=f,
                              block_length=bl, block_height=bh, openings=gaps)
        bound = top_block_bound(s, f)
        assert math.isfinite(bound)
        r = max_load_multiplier(s, state=False)
        assert r.status == "collapse"
        assert r.load_multiplier <= bound * (1 + 1e-7)


def as_dead(scene, load_factor: float):
    """``scene`` with its live body force times ``load_factor`` applied as dead loads at
    the blocks' centroids (the same loads): its f* is sought on R(f) alone, as under
    the dead load (the search on lambda*(f) is for live loads)."""
    system = open_method(scene).system
    v = np.asarray(scene.live_body_force, float)
    dead = tuple(Load(scene.blocks[b].id, tuple(float(system.weights[b] * load_factor) * v),
                      live=False) for b in system.free_blocks)
    return scene.with_changes(loads=scene.loads + dead, live_body_force=None)


def test_friction_bracket_ends_where_the_solver_stops_resolving():
    """A 17 x 18 running-bond wall under its horizontal body force at full value (as a
    dead load, so f* is sought on R(f)): Newton's steps on R(f) end with a narrow
    bracket whose lower end is not certified by the dual bound; just below the
    certified upper end R is predicted under what the solver certifies, so the search
    stops there and says so instead of a last probe that could not decide. The answer
    agrees with the simplex back end (HiGHS: exact duals, so its bracket is tight):
    f* = 1.0753989 there, and our certified upper end lies within 1e-6 above it; lambda*
    by HiGHS at f = 1.075399 is >= 1 (the wall stands), at 1.07539 below 1."""
    wall = running_bond_wall(17, 18)
    r = min_friction(as_dead(wall, 1.0), load_factor=0.0, state=False, rtol=1e-7)
    exact = min_friction(wall, load_factor=1.0, state=False, solver="highs", rtol=1e-7)
    assert exact.answered_by == ("highs",) and not exact.rejected  # a real cross-check
    lo, hi = exact.bracket
    assert hi - lo <= 1e-6 * hi
    assert lo <= r.upper <= hi * (1 + 1e-6)
    assert r.bracket[0] <= lo and r.bracket[1] == r.upper
    assert r.status == ("stable" if r.accuracy <= 1e-7 else "undecided")
    assert any("below what the solver certifies" in n for n in r.notes)
    assert not any("lambda*(f)" in n for n in r.notes)  # found on R(f)
    assert r.n_solves <= 6


def test_friction_search_steps_past_a_trial_without_a_checked_answer():
    """R(f) = (0.3 - f)+ (a b = 1, h = 2 block under 0.3 times its weight slides at
    f* = 0.3; it would tip at b/h = 0.5). Newton's first step from f = 0 lands on 0.3,
    where the relaxation comes back without a checked answer (as when the solver's
    answer fails its check near a degenerate f*): the search steps up to a certified
    upper end and closes the bracket around the unsolved trial, so f* is bracketed
    within 1e-3 (a number at the default accuracy), and the unsolved trial is not
    solved again (Newton's step from f = 0 and the midpoint of the bracket [0, 0.6]
    both land on it again); where no trial has a checked answer, the search gives up
    with no certified upper end: never a number."""
    exact = _certified(0.3)
    spoilt: list[float] = []

    def relax(f):
        if abs(f - 0.3) < 1e-12:
            spoilt.append(f)
            return _rx(f, None, unresolved="the answer fails its check (spoilt)")
        return exact(f)

    s = r_search(relax, rtol=FRICTION_RTOL)
    assert len(spoilt) == 1 and s.of_kind("missed")[0].x == spoilt[0]
    assert s.bad <= 0.3 <= s.good <= 0.3 * (1 + 1e-3)
    assert s.narrow() and s.narrow(WIDE) and s.stopped == "narrow_enough"
    s = r_search(lambda f: _rx(f, None, unresolved="spoilt") if 0 < f < math.inf
                 else exact(f), rtol=FRICTION_RTOL)
    assert s.stopped == "missed_too_often" and s.good == math.inf
    assert "spoilt" in s.last.why


@pytest.mark.parametrize("top", [0.3000001, 0.30001, 0.3015, 0.33, 0.6])
def test_a_trial_left_at_the_threshold_bounds_nothing(top):
    """A trial the solver leaves at the threshold (its state's breach above the
    threshold, its dual bound below) does not bracket f* from below: R may be zero there
    with a state the solver cannot certify. On the extruded 5,006-block wall one such
    trial at f = 1.2502445, 7.8e-4 below the certified upper end 1.2512172, made that
    upper end the reported f* where the plane wall certifies f* <= 1.2497654. Here
    R(f) = (0.3 - f)+ (the b = 1, h = 2 block under 0.3 times its weight: it slides at
    f* = 0.3, before it tips at b/h = 0.5) is left so on [0.3, top] (twice the
    threshold, no dual bound). The bracket holds f* = 0.3. Where the band is narrower
    than 1e-3 (relative), the search goes on below the lowest trial at the threshold
    and brackets f* within three times the band, in at most 12 trials (stepping past
    those trials alone took 15 to 20 and stopped at 9.8e-4 whatever the band); a wider
    band ends the search in a few trials however wide it is."""
    exact = _certified(0.3)

    def relax(f):
        return _rx(f, 2 * TOL) if 0.3 - 1e-9 <= f <= top else exact(f)

    s = r_search(relax)
    assert s.bad <= 0.3 < top < s.good and len(s.trials) <= 12
    assert s.of_kind("threshold") and not s.narrow()  # short of 1e-7
    band = (top - 0.3) / 0.3
    if band < 1e-3:  # bracketed to the band, short of 1e-7
        assert 1e-7 < s.accuracy <= 3 * band
    else:  # wider than WIDE: no number
        assert not s.narrow(WIDE)


def test_the_probe_below_the_upper_end_lands_where_the_solver_resolves():
    """Where the lower end's Newton step lands at the certified upper end (R about
    linear across the bracket), the probe below that end goes where R is twice what is
    taken as a lower point on its value, not to the end's round-off distance, where it
    ends near the threshold. The bundled Arpino gate: R falls linearly with slope 1.65
    (0.0042745 at f = 0.0879295, 0.0021373 at 0.0892243, both certified), and its f*
    is bracketed to 1.4e-6 by a certified lower point instead of to 1.4e-2 with a
    trial left at the threshold. The bracket holds the simplex solver's (HiGHS, a
    vertex of the LP: [0.0905191183, 0.0905191262])."""
    scene = read_scene(EXAMPLES / "arpino_gate.json")
    r = min_friction(scene, state=False, rtol=1e-7)
    simplex = min_friction(scene, state=False, solver="highs", rtol=1e-7)
    assert simplex.answered_by == ("highs",) and not simplex.rejected  # a real cross-check
    assert r.status == "undecided" and simplex.status == "stable"  # 1.4e-6, short of 1e-7
    lo, hi = r.bracket
    assert r.upper == hi and (hi - lo) / hi < 1e-5
    assert lo <= simplex.bracket[0] <= simplex.bracket[1] <= hi


def test_lambda_star_is_not_stopped_where_its_solve_stalls(monkeypatch, block_on_base):
    """The max-load LP is solved to its own tolerances, never stopped where it stalls
    with an iterate that meets the next solve's: lambda* is a number read from the
    answer, not a verdict against a threshold that follows the tolerances (on the
    20,093- and 50,065-block walls lambda* so stopped at 1e-9 came out 1.3e-3 and
    4.8e-3 below the 1e-10 answers, 0.3784787 and 0.3679230). The relaxations of the
    verdicts are given the next solve's tolerances. Only the max-load LP is solved with
    the finer KKT regularisation of VALUE_SETTINGS (the relaxations fail with it)."""
    given = []
    policy_solve = policy.solve

    def recording(problem, solver="clarabel", after=None, **settings):
        reg = settings.get("static_regularization_constant")
        given.append(("lambda" in problem.cols, "r" in problem.cols, after, reg))
        return policy_solve(problem, solver, after=after, **settings)

    monkeypatch.setattr(policy, "solve", recording)
    r = max_load_multiplier(block_on_base(1.0, 2.0, 0.3))
    assert r.load_multiplier == pytest.approx(0.3, rel=1e-6)  # slides at lambda = f
    assert any(lp for lp, _, _, _ in given)
    fine = policy.VALUE_SETTINGS["clarabel"]["static_regularization_constant"]
    assert all(after is None and reg == fine for lp, _, after, reg in given if lp)
    check(block_on_base(1.0, 2.0, 0.3), load_factor=0.2)
    assert any(after is not None for _, rx, after, _ in given if rx)
    assert all(reg is None for _, rx, _, reg in given if rx)


def test_finer_regularisation_out_of_reach_is_not_asked_again(monkeypatch):
    """On small problems Clarabel fails with VALUE_SETTINGS (the max-load LP of the
    19-block example wall: AlmostSolved at every f the search on lambda*(f) tries) and
    answers without them; once that has happened, the runner's later max-load LPs go
    without them: one failure in the search, not one per trial (12 solves before, 9)."""
    asked = []
    policy_solve = policy.solve

    def recording(problem, solver="clarabel", after=None, **settings):
        res = policy_solve(problem, solver, after=after, **settings)
        asked.append((settings.get("static_regularization_constant"), res.status))
        return res

    monkeypatch.setattr(policy, "solve", recording)
    wall = read_scene(EXAMPLES / "wall.json")
    r = min_friction(wall, load_factor=1.0, state=False, rtol=1e-7, compare_dry=False)
    assert r.upper == pytest.approx(1.0, rel=1e-6)
    fine = policy.VALUE_SETTINGS["clarabel"]["static_regularization_constant"]
    assert [status for reg, status in asked if reg == fine] == ["failure"]
    assert sum(reg is None for reg, _ in asked) >= 4  # the max-load LPs after it


def test_lambda_star_of_a_large_wall_agrees_with_the_simplex():
    """lambda* of the 1,009-block running-bond wall (32 courses of 31 blocks) at
    f = 1.18372000405 (its f* at load factor 1), against HiGHS' dual simplex on the same
    LP (``max_load_multiplier(..., solver="highs")``, 2026-11-23: 1.0000009251763409).
    With Clarabel's default KKT regularisation (1e-8) lambda* came out 0.9999956, 5.3e-6
    below it: its dual residual (1.9e-8), times forces of 641 block loads, bounds the
    accuracy of the objective; with VALUE_SETTINGS (1e-10) 1.0000005."""
    r = max_load_multiplier(running_bond_wall(32, 31), friction=1.1837200040466043,
                            compare_dry=False)
    assert r.status == "collapse"
    assert r.load_multiplier == pytest.approx(1.0000009251763409, rel=1e-6)


def test_the_energy_is_scaled_at_limit_states_only(monkeypatch, block_on_base):
    """The least-energy QP's energy is scaled by the limit problem's state at f* and
    lambda*, where unscaled Clarabel stalled on a 5,006-block wall (200 iterations
    against 71), and not for a verdict away from a limit, where scaling costs an
    iteration or two (13 against 15 on the same wall at f = 0.6)."""
    from rigidblocks.methods import force_state

    given = []
    build = force_state.energy_problem

    def recording(*args, reference=None, **kw):
        given.append(reference is not None)
        return build(*args, reference=reference, **kw)

    monkeypatch.setattr(force_state, "energy_problem", recording)
    scene = block_on_base(1.0, 2.0, 0.5)
    for analysis, at_limit in ((lambda: check(scene, load_factor=0.2), False),
                               (lambda: min_friction(scene, load_factor=0.2), True),
                               (lambda: max_load_multiplier(scene), True)):
        given.clear()
        assert analysis().state is not None
        assert given == [at_limit]


def test_friction_from_lambda_star_agrees_with_the_simplex():
    """Under a live load, f* is found where lambda*(f) = the load factor (Newton steps on
    the max-load LP, far better conditioned near f* than the relaxation). The 17 x 18
    running-bond wall at load factor 1: HiGHS (exact duals) brackets f* within 1e-6
    about 1.0753988 (test_friction_bracket_ends_where_the_solver_stops_resolving); our
    upper end, where a state carries lambda >= 1, lies within 1e-6 above it, and the
    lower end, read on lambda*'s value, below it."""
    wall = running_bond_wall(17, 18)
    r = min_friction(wall, load_factor=1.0, state=False, rtol=1e-7)
    exact = min_friction(wall, load_factor=1.0, state=False, solver="highs", rtol=1e-7)
    assert exact.answered_by == ("highs",) and not exact.rejected  # a real cross-check
    lo, hi = exact.bracket
    assert hi - lo <= 1e-6 * hi
    assert lo <= r.upper <= hi * (1 + 1e-6)
    assert r.status == ("stable" if r.accuracy <= 1e-7 else "undecided")
    assert r.bracket[0] <= lo and r.bracket[1] == r.upper
    assert any("lambda*(f) = 1" in n for n in r.notes)
    assert r.n_solves <= 9  # f = inf and 0, six max-load LPs, the dead load at f*


def test_the_state_at_f_star_from_lambda_star_carries_the_load_factor(monkeypatch):
    """The upper end of the search on lambda*(f) has a state at lambda* >= the load
    factor; the state reported at f* is combined with one under the dead load alone
    (theta = lf / lambda*), so it carries the load factor itself. Shown where the
    least-energy QP fails (a back end that refuses every QP) and that state is
    reported: on the 17 x 18 running-bond wall at load factor 1 (live load: the blocks'
    weights, horizontal), the joints on the support carry a shear of 1 times their
    normal force, where lambda* at the f* reported is above 1 (1 + 7.0e-8 when found)."""
    policy_solve = policy.solve

    def no_qp(problem, solver="clarabel", **settings):
        if problem.P is not None:
            return SolverResult("failure", None, None, math.nan, solver, "refused")
        return policy_solve(problem, solver, **settings)

    monkeypatch.setattr(policy, "solve", no_qp)
    wall = running_bond_wall(17, 18)
    r = min_friction(wall, load_factor=1.0)
    monkeypatch.setattr(policy, "solve", policy_solve)
    at_hi = max_load_multiplier(wall, friction=r.friction_factor, state=False)
    assert at_hi.load_multiplier > 1 + 1e-8
    st = r.state
    assert st.method == "solution of the limit problem"
    pairs = open_method(wall).system.contacts.pairs
    base = np.isin(pairs, np.flatnonzero(wall.support_mask)).any(axis=1)
    assert base.any()
    ratio = st.joint_shear[base].sum() / st.joint_normal[base].sum()
    assert abs(ratio) == pytest.approx(1.0, rel=1e-10)


def test_forces_that_grow_as_towards_an_infimum_are_told_from_a_structures_scale():
    """Towards an infimum f0 the forces of the states grow at least as 1 / (f - f0)
    (the pinched block above: N = W L / (2 (f h - d))). From an upper end at f = 1.5 to
    one at 1.0001 above a lower end at 1.0, forces ~ 1 / (f - 1) grow 5,000 times, at
    least (f_far - hi) / (hi - lo) = 4,999 times: they may be an infimum's. Forces that
    stay about the same there (the structure's own scale: a tall wall's base) are not,
    nor those that grew 10 times, far less than that; with no upper end further above,
    nothing tells them apart."""
    from rigidblocks.methods.load_search import infimum_growth

    lo, hi, f_far = 1.0, 1.0001, 1.5
    assert infimum_growth((f_far, 1.0 / (f_far - lo)), hi, lo, 1.0 / (hi - lo))
    assert not infimum_growth((f_far, 1.0e4), hi, lo, 1.4e4)
    assert not infimum_growth((f_far, 1.0e4), hi, lo, 1.0e5)
    assert infimum_growth((hi, 1.0e4), hi, lo, 1.0e4)


def test_governing_joints_are_ranked_by_their_share():
    """The joints that govern f* come ranked by their share y_r N_r of dlambda*/df (the
    friction rows' duals times their normal forces), largest first: a long list (the
    19-block example wall under a horizontal load at 0.3: 28 joints) is read from its
    head, not in the order of the joints' numbers."""
    wall = read_scene(EXAMPLES / "wall.json")
    r = min_friction(wall, load_factor=0.3, state=False)
    gov = r.governing
    assert len(gov) > 12 and list(gov) != sorted(gov)
    m = open_method(wall)
    prob, jr, res = m.max_load(r.bracket[0])
    w = m.friction_shares(res, jr, prob)
    strong = w > GOVERNING_SHARE * w.max()
    share = np.bincount(jr.fric_joint[strong], w[strong], minlength=m.system.contacts.n_joints)
    assert set(gov) == set(np.flatnonzero(share))
    rank = np.round(share / share.max(), 6)
    assert all(rank[a] > rank[b] or rank[a] == rank[b] and a < b
               for a, b in zip(gov, gov[1:], strict=False))
