"""The collapse states of one mechanism (rigidblocks.analyses.na_mechanism) and the
warm-started LPs they are found with (rigidblocks.solvers.highs_warm)."""

from __future__ import annotations

import json

import numpy as np
import pytest
import scipy.sparse as sp
from conftest import EXAMPLES, down

import rigidblocks as rb
from rigidblocks.analyses import nonassociative
from rigidblocks.analyses.na_limit import CappedLimit, certificate, x0_normals
from rigidblocks.analyses.na_mechanism import Mechanisms, limit_runs
from rigidblocks.generators import build
from rigidblocks.io import read_scene
from rigidblocks.solvers import highs_warm
from rigidblocks.solvers.highs_warm import ColdLp, WarmLp, nonzero

NA = "non-associative"


# -- the warm-started LP ---------------------------------------------------------------
def _lp(seed: int = 4):
    """A random bounded LP: min c'x s.t. lo <= A x <= up, x free (a box among the rows
    keeps it bounded)."""
    rng = np.random.default_rng(seed)
    m, n = 30, 8
    A = sp.vstack([sp.random(m, n, density=0.5, random_state=seed, format="csr"),
                   sp.identity(n, format="csr")]).tocsr()
    lo = np.concatenate([np.full(m, -np.inf), -np.ones(n)])
    up = np.concatenate([rng.uniform(0.5, 2.0, m), np.ones(n)])
    return rng.normal(size=n), A, lo, up


def _changed_bounds(lo, up, n: int):
    """n changes of the random LP's row bounds: its first 30 upper bounds scaled by 0.5
    to 1.5, and one box row (k modulo 8) fixed at 0.3 (an equality) in the k-th."""
    rng = np.random.default_rng(7)
    out = []
    for k in range(n):
        up2 = up.copy()
        up2[:30] = up[:30] * rng.uniform(0.5, 1.5, 30)
        lo2 = lo.copy()
        lo2[30 + k % 8] = up2[30 + k % 8] = 0.3
        out.append((lo2, up2))
    return out


@pytest.mark.parametrize("kind", ["warm", "warm-ipm", "cold"])
def test_warm_lp_follows_changed_bounds(kind, monkeypatch):
    """The same LP with its row bounds changed three times: each optimum equals
    scipy's linprog solving that LP from scratch (to 1e-9), warm-started, by IPM
    with crossover (every warm solve given up: WARM_LIMIT = 0) and through linprog
    (no highspy); the rows with a non-zero dual are active (complementary slackness,
    which the mechanisms' polytopes rest on)."""
    from scipy.optimize import linprog

    if kind == "warm-ipm":
        monkeypatch.setattr(highs_warm, "WARM_LIMIT", 0)
    c, A, lo, up = _lp()
    lp = (ColdLp if kind == "cold" else WarmLp)(c, A, lo, up)
    rows = np.arange(A.shape[0])
    for lo2, up2 in _changed_bounds(lo, up, 3):
        assert lp.solve(rows, lo2, up2) == "optimal"
        ref = linprog(c, A_ub=sp.vstack([A, -A[lo2 > -np.inf]]),
                      b_ub=np.concatenate([up2, -lo2[lo2 > -np.inf]]), bounds=(None, None),
                      method="highs")
        assert ref.status == 0
        assert c @ lp.x == pytest.approx(ref.fun, abs=1e-9)
        act = A @ lp.x
        held = nonzero(lp.duals, 1e-9)
        assert held.any()
        at_bound = np.minimum(np.abs(act - up2), np.abs(act - lo2))
        assert at_bound[held].max() <= 1e-8
    if kind == "warm-ipm":
        assert lp.cold == lp.solves
    elif kind == "warm":
        assert lp.cold == 1


@pytest.mark.parametrize("kind", ["warm", "cold"])
def test_minimise_follows_changed_costs(kind):
    """One LP's feasible set, five costs in turn (the safe multiplier's slack bounds):
    each optimum is linprog's from scratch (the warm model from the last basis by the
    primal simplex)."""
    from scipy.optimize import linprog

    c, A, lo, up = _lp()
    lp = (ColdLp if kind == "cold" else WarmLp)(c, A, lo, up)
    rng = np.random.default_rng(3)
    for _ in range(5):
        cost = rng.normal(size=len(c))
        assert lp.minimise(cost) == "optimal"
        ref = linprog(cost, A_ub=sp.vstack([A, -A[lo > -np.inf]]),
                      b_ub=np.concatenate([up, -lo[lo > -np.inf]]), bounds=(None, None),
                      method="highs")
        assert cost @ lp.x == pytest.approx(ref.fun, abs=1e-9)


def test_the_solves_after_a_warm_one_given_up_go_to_ipm_at_once():
    """With every warm solve given up (a limit of 0 iterations), nine solves of the
    random LP: without the rule the last eight are each tried warm and given up; with
    ``cold_after_give_up`` the second is given up, the third goes to IPM at once, the
    fourth is given up again, the fifth and sixth go to IPM at once, the seventh is
    given up, the last two go to IPM at once (three given up; four when only the one
    solve after each give-up went to IPM at once). The optima are the same."""
    c, A, lo, up = _lp()
    rows = np.arange(A.shape[0])
    bounds = _changed_bounds(lo, up, 9)
    got = {}
    for rule in (False, True):
        lp = WarmLp(c, A, lo, up)
        lp.limit = 0
        lp.cold_after_give_up = rule
        got[rule] = []
        for lo2, up2 in bounds:
            assert lp.solve(rows, lo2, up2) == "optimal"
            got[rule].append(c @ lp.x)
        assert lp.cold == lp.solves == 9
        assert lp.given_up == (3 if rule else 8)
    assert got[True] == pytest.approx(got[False], abs=1e-9)


# -- the selection step on the optimal face ---------------------------------------------
def test_the_selection_holds_the_simplex_answers_optimal_face(monkeypatch):
    """The 10 x 10 wall at f = 0.8, at the caps of X0's normal forces: held on the rows
    of phase 1's answer with non-zero duals (its optimal face, by complementary
    slackness), the selected state carries the maximum itself (to 1e-10) and holds
    those rows (to 1e-9), with a smaller objective (sum N + |N - N0|^2 / 2) than the
    simplex vertex's on the same face (measured 1422.49 against 1801.17); under the
    bound lambda >= max (1 - 1e-9) instead, the state leaves the face (those rows
    off by 2.4e-4). Every least-squares step of a 2D run selects on its face."""
    from rigidblocks.analyses import na_limit

    scene = build("wall", courses=10, blocks_per_course=10, friction=0.8)
    na, cv = nonassociative._open(scene, "clarabel", NA)
    _, starts = nonassociative._starts(na, cv, cv.load_limit(0.8, 1e-9), 0.8)
    capped = CappedLimit(cv, na.marked, 0.8)
    N0 = starts[0][1]
    b = capped.rhs(N0)
    st, lam, z = capped.solver.maximise(b)
    assert st == "optimal"
    face = capped.solver.held()
    zf = capped.nearest(b, lam, N0, face)
    li, nsl = capped.prob.cols["lambda"].start, capped.nsl
    Aj = capped.prob.A.tocsr()[capped.prob.n_eq:]
    assert zf[li] == pytest.approx(lam, rel=1e-10)
    assert np.abs(Aj[face] @ zf - b[face]).max() <= 1e-9
    assert np.abs(Aj[face] @ z - b[face]).max() <= 1e-9  # the vertex is on the face

    def objective(x):
        return x[nsl].sum() + 0.5 * ((x[nsl] - N0) ** 2).sum()

    assert objective(zf) < objective(z) - 1.0
    zs = capped.nearest(b, lam * (1 - 1e-9), N0)
    assert np.abs(Aj[face] @ zs - b[face]).max() > 1e-6
    faces = []
    select = na_limit._select_problem

    def recording(*args, **kw):
        faces.append(args[5] if len(args) > 5 else kw.get("face"))
        return select(*args, **kw)

    monkeypatch.setattr(na_limit, "_select_problem", recording)
    _walls_mechanism(scene, 0.8)
    assert faces and all(f is not None and f.any() for f in faces)


# -- the collapse states of a mechanism ------------------------------------------------
def _walls_mechanism(scene, f: float):
    """The limit iteration from X0 ended at its mechanism's states, with what it ran on."""
    na, cv = nonassociative._open(scene, "clarabel", NA)
    up = cv.load_limit(f, 1e-9)
    _, starts = nonassociative._starts(na, cv, up, f)
    capped = CappedLimit(cv, na.marked, f)
    mech = Mechanisms(capped)
    run = capped.run(starts[0][1], starts[0][0], settle=mech.settler())
    return cv, capped, mech, run, starts[0][1]


def test_a_mechanisms_states_are_collapse_states():
    """The 10 x 10 running-bond wall at f = 0.8 (106 blocks): the iteration from X0 ends
    at the states of the mechanism it reached. Its answer, and the lowest and highest
    states of that mechanism, each pass the a-posteriori check computed independently
    of the polytope (equilibrium, and Coulomb's law with the state's own normal
    forces, to 1e-7 of its largest force) and are fixed points: at their own caps the
    largest multiplier and the least total normal force are their own. The two ends
    differ (the multiplier of a non-associative collapse state is not unique even for
    one mechanism), and the answer lies between them."""
    scene = build("wall", courses=10, blocks_per_course=10, friction=0.8)
    cv, capped, mech, run, _ = _walls_mechanism(scene, 0.8)
    assert run.converged and run.span is not None
    lo, hi = run.span
    assert lo <= run.lam <= hi and hi > lo * (1 + 1e-5)
    li = capped.prob.cols["lambda"].start
    act = mech.active(capped.rhs(np.maximum(run.x[capped.nsl], 0.0)))
    ends = [mech.extreme(act, 1.0), mech.extreme(act, -1.0)]
    assert [float(z[li]) for z in ends] == pytest.approx([lo, hi], rel=1e-7)
    size = cv.system.layout.size
    for lam, x in [(run.lam, run.x)] + [(float(z[li]), z[:size]) for z in ends]:
        eq, breach = certificate(cv, 0.8, lam, x * cv.scaling.force)
        assert eq <= 1e-7 and breach <= 1e-7
    for z in ends:
        assert mech.check(z) == ""
    z = np.concatenate([run.x, [run.lam]])
    assert mech.check(z) == ""


def test_the_check_rejects_a_state_off_its_own_caps():
    """The fixed-point check can fail: the answer's state with its multiplier raised by
    1e-4, or its normal forces scaled by 1.01 (caps that are not its own), is not a
    fixed point at its own caps."""
    scene = build("wall", courses=5, blocks_per_course=3, friction=0.8)
    _, capped, mech, run, _ = _walls_mechanism(scene, 0.8)
    z = np.concatenate([run.x, [run.lam]])
    assert mech.check(z) == ""
    raised = z.copy()
    raised[-1] *= 1 + 1e-4
    assert mech.check(raised).startswith("at its own caps the multiplier is")
    scaled = z.copy()
    scaled[capped.nsl] *= 1.01
    assert mech.check(scaled) != ""


def test_a_solver_failure_on_a_polytope_is_not_an_empty_polytope(monkeypatch):
    """A mechanism is recorded as one without collapse states (not sought again) where
    its polytope is empty, not where the solver fails on it: the 1,041-block wall3d in
    plane at f = 0.6 stalled at lambda 0.411038 for about 100 least-squares steps after
    Clarabel ended one lowest state AlmostSolved (issue #30). On the 5 x 3 wall at
    f = 0.8, the reached mechanism with that solve failing gives no state and is not
    recorded; sought again, it gives the run's span; with every joint row held its
    polytope is empty and is recorded."""
    from rigidblocks.errors import SolverFailure

    scene = build("wall", courses=5, blocks_per_course=3, friction=0.8)
    cv, capped, _, run, _ = _walls_mechanism(scene, 0.8)
    N = np.maximum(run.x[capped.nsl], 0.0)
    bj = capped.rhs(N)
    mech = Mechanisms(capped)
    assert capped.solver.maximise(bj)[0] == "optimal"
    act = mech.active(bj)
    solve = cv.solve

    def failing(prob, what, *a, **k):
        if what == "collapse states of one mechanism":
            raise SolverFailure("no answer")
        return solve(prob, what, *a, **k)

    monkeypatch.setattr(cv, "solve", failing)
    assert mech.states(act, N) is None and not mech.tried(act)
    monkeypatch.setattr(cv, "solve", solve)
    got = mech.states(act, N)
    assert got is not None and got[1] == pytest.approx(run.span, rel=1e-7)
    every = np.ones_like(act)
    assert mech.states(every, N) is None and mech.tried(every)


def test_the_iterations_own_fixed_point_is_a_state_of_the_mechanism():
    """Cross-check of the two ends of one run: the limit iteration run to its own fixed
    point (no polytope, change of the normal forces below 1e-7, the algorithm before
    the polytopes) on the 10 x 10 wall at f = 0.6 from X0 settles on a multiplier inside
    the span of the mechanism the polytope gives, to 1e-6."""
    scene = build("wall", courses=10, blocks_per_course=10, friction=0.6)
    _, capped, _, run, n0 = _walls_mechanism(scene, 0.6)
    own = capped.run(n0, "X0")
    assert own.converged
    lo, hi = run.span
    assert lo * (1 - 1e-6) <= own.lam <= hi * (1 + 1e-6)
    assert own.iterations > run.iterations


def test_vertex_steps_end_at_a_checked_state(monkeypatch):
    """Where the least-squares path has not reached a mechanism with collapse states
    within PATH_STEPS steps, the run goes on by vertex steps; with PATH_STEPS = 1 on the
    20 x 15 wall at f = 0.8 (311 blocks) every step of both starts is one: each ends
    at a collapse state (equilibrium and Coulomb's law with its own normal forces to
    1e-7 of its largest force, checked here independently) inside its mechanism's span
    and the reason says how it was reached."""
    from rigidblocks.analyses import na_mechanism

    monkeypatch.setattr(na_mechanism, "PATH_STEPS", 1)
    scene = build("wall", courses=20, blocks_per_course=15, friction=0.8)
    na, cv = nonassociative._open(scene, "clarabel", NA)
    up = cv.load_limit(0.8, 1e-9)
    _, starts = nonassociative._starts(na, cv, up, 0.8)
    capped = CappedLimit(cv, na.marked, 0.8)
    mech = Mechanisms(capped)
    for name, n in starts:
        run = capped.run(n, name, settle=mech.settler())
        assert run.converged
        assert (f"after {run.iterations} limit solves ({run.iterations} of them by steps "
                "to the least confined state after 0 least-squares") in run.reason
        assert run.span[0] <= run.lam <= run.span[1] < up.value
        eq, breach = certificate(cv, 0.8, run.lam, run.x * cv.scaling.force)
        assert eq <= 1e-7 and breach <= 1e-7


def test_a_walk_that_finds_no_state_goes_on_by_least_squares(monkeypatch):
    """Vertex steps that reach no mechanism with collapse states within WALK_STEPS hand
    the run back to least-squares steps, and the run counts both (one vertex step
    cannot settle: settling compares two). The 10 x 10 wall at f = 0.8 from X0 by
    vertex steps alone has no settled mechanism with states within 2 steps."""
    from rigidblocks.analyses import na_mechanism

    monkeypatch.setattr(na_mechanism, "PATH_STEPS", 1)
    monkeypatch.setattr(na_mechanism, "WALK_STEPS", 2)
    scene = build("wall", courses=10, blocks_per_course=10, friction=0.8)
    na, cv = nonassociative._open(scene, "clarabel", NA)
    capped = CappedLimit(cv, na.marked, 0.8)
    mech = Mechanisms(capped)
    walked = []
    walk = mech.walk
    monkeypatch.setattr(mech, "walk", lambda N: walked.append(walk(N)) or walked[-1])
    run = capped.run(x0_normals(na), "X0", settle=mech.settler())
    assert walked[0][0] is None and walked[0][2] == (
        "no mechanism with collapse states within 2 vertex steps after 0 least-squares "
        "steps")
    assert run.converged
    assert f"after {run.iterations} limit solves" in run.reason
    assert run.iterations == len(run.history) + 1 + 1  # its steps, the walk's second


def test_a_walk_that_wanders_ends_before_unsettled_walk(monkeypatch):
    """The 10 x 10 wall at f = 0.956 from X0: each vertex step of its walk changes many
    of its 254 to 278 rows, and the walk never settles; a walk none of whose steps
    changed fewer than WANDER of its rows ends at WANDER_STEPS (15) instead of
    UNSETTLED_WALK (20), and the run reaches the same collapse state as with the
    20-step walk (0.5428571, one state), in 5 limit solves fewer. The smallest share a
    step changes follows the simplex path, which differs between machines (6.8 % on one,
    5.4 % on another, around WANDER = 6 %): WANDER is set to 0 here, so that the walk
    wanders on every machine."""
    from rigidblocks.analyses import na_mechanism

    f = 0.956
    scene = build("wall", courses=10, blocks_per_course=10, friction=f)
    na, cv = nonassociative._open(scene, "clarabel", NA)
    monkeypatch.setattr(na_mechanism, "WANDER", 0.0)
    got = {}
    for steps in (na_mechanism.WANDER_STEPS, 10**9):
        monkeypatch.setattr(na_mechanism, "WANDER_STEPS", steps)
        capped = CappedLimit(cv, na.marked, f)
        mech = Mechanisms(capped)
        walked: list = []
        monkeypatch.setattr(mech, "walk", lambda N, walk=mech.walk, walked=walked:
                            walked.append(walk(N)) or walked[-1])
        run = capped.run(x0_normals(na), "X0", settle=mech.settler())
        assert run.converged and walked[0][0] is None
        got[steps] = run, walked[0][2]
    (short, why), (long, why_long) = got[15], got[10**9]
    import re

    share = re.fullmatch(r"the mechanism did not settle within 15 vertex steps, each step "
                         r"changing at least ([0-9.]+)% of its rows after 4 least-squares "
                         r"steps", why)
    assert share and float(share.group(1)) > 0, why
    assert why_long.startswith("the mechanism did not settle within 20 vertex steps")
    assert short.lam == pytest.approx(long.lam, rel=1e-12)
    assert long.lam == pytest.approx(0.5428571, abs=1e-7)
    assert short.iterations == long.iterations - 5


def test_states_of_the_first_phase_rows_alone_end_a_run_that_finds_none_else():
    """The 10 x 10 wall at f = 0.956: from X0 the run reaches a mechanism with one
    collapse state (0.5428571) in least-squares steps after a walk that found none (its
    mechanism did not settle within UNSETTLED_WALK vertex steps); from the associative
    state no polytope of both phases' rows has states within its budget (undecided
    before), and LOOSE_AFTER steps after its walk it ends at states of the
    maximum-load problem's rows alone, which its reason says. That state is checked
    independently of the polytope: equilibrium and Coulomb's law with its own normal
    forces to 1e-7 of its largest force, and at the caps of its own normal forces a
    fresh maximum-load LP (its own HiGHS model, solved from scratch) carries exactly its
    multiplier: a non-associative collapse state, below the associative multiplier."""
    from rigidblocks.analyses.na_mechanism import LOOSE, PATH_STEPS, WALK_STEPS

    f = 0.956
    scene = build("wall", courses=10, blocks_per_course=10, friction=f)
    na, cv = nonassociative._open(scene, "clarabel", NA)
    up = cv.load_limit(f, 1e-9)
    _, starts = nonassociative._starts(na, cv, up, f)
    capped = CappedLimit(cv, na.marked, f)
    x0, assoc = limit_runs(capped, starts)
    assert x0.converged and LOOSE not in x0.reason
    assert x0.lam == pytest.approx(0.5428571, abs=1e-7)
    assert x0.span[0] == pytest.approx(x0.span[1], rel=1e-12)
    assert x0.iterations < PATH_STEPS + WALK_STEPS  # the walk ended at UNSETTLED_WALK
    assert assoc.converged and assoc.reason.endswith(f"{LOOSE} has collapse states")
    assert assoc.span[0] <= assoc.lam <= assoc.span[1] < up.value
    eq, breach = certificate(cv, f, assoc.lam, assoc.x * cv.scaling.force)
    assert eq <= 1e-7 and breach <= 1e-7
    fresh = CappedLimit(cv, na.marked, f)
    st, lam, _ = fresh.solver.maximise(fresh.rhs(np.maximum(assoc.x[fresh.nsl], 0.0)))
    assert st == "optimal" and lam == pytest.approx(assoc.lam, rel=1e-7)


def test_states_of_the_first_phase_rows_alone_are_named(tmp_path, capsys):
    """`load --flow non-associative` on the 10 x 10 wall at f = 0.956: the starts line
    and the report's note say that the answer from the associative state rests on
    states of the maximum-load problem's rows alone (not the least confined), and
    the answer from X0 (the least confined state of its mechanism) is not so named."""
    from rigidblocks.cli.main import main
    from rigidblocks.io.scene_file import dumps_scene

    p = tmp_path / "wall.json"
    p.write_text(dumps_scene(build("wall", courses=10, blocks_per_course=10,
                                   friction=0.956)))
    assert main(["load", str(p), "--flow", NA, "--json"]) == 0
    res = json.loads(capsys.readouterr().out)
    assert [h["least_confined"] for h in res["history"]] == [True, False]
    note = next(n for n in res["notes"] if "from the associative collapse state" in n)
    x0, assoc = note.split("; from the associative collapse state")
    assert "not least confined" in assoc and "not least confined" not in x0
    assert main(["load", str(p), "--flow", NA]) == 0
    line = next(s for s in capsys.readouterr().out.splitlines() if s.startswith("starts"))
    x0, assoc = line.split("; from the associative collapse state")
    assert "not least confined" not in x0
    assert "(its mechanism's states optimal under their own caps, not least confined, [" \
        in assoc


def test_the_safe_multiplier_is_the_lowest_state_of_the_mechanism_reached():
    """The seed's reference model with self-weight: the iteration from X0 reaches the
    associative multiplier 2.4 (the seed's load path), and the mechanism it reaches has
    collapse states down to 0.6, the smallest non-associative collapse multiplier over
    all states, proven by the mixed-integer LP of rigidblocks.analyses.na_bounds
    (docs/safe-multiplier.md): the span the answer prints names the worst case here."""
    from rigidblocks.analyses.na_bounds import safe_multiplier

    scene = read_scene(EXAMPLES / "reference_self_weight.json")
    res = rb.max_load_multiplier(scene, flow=NA, state=False)
    assert res.load_multiplier == pytest.approx(2.4, rel=1e-9)
    span = res.history[0]["span"]
    safe = safe_multiplier(scene, flow=NA)
    assert safe.status == "optimal"
    assert span == pytest.approx([safe.value, 2.4], rel=1e-7)


def test_the_span_is_printed(tmp_path, capsys):
    """`load --flow non-associative` names the span of the mechanism each start reached
    (10 x 10 wall at f = 0.6: both starts reach one mechanism) and the spread of the
    starts' answers where they differ; on the reference model with self-weight
    the answer line is followed by the warning that it is no lower bound (the same
    mechanism collapses from 0.6). The spread is said once (it was a "why" line too)."""
    from rigidblocks.cli.main import main
    from rigidblocks.io.scene_file import dumps_scene

    p = tmp_path / "wall.json"
    p.write_text(dumps_scene(build("wall", courses=10, blocks_per_course=10, friction=0.6)))
    assert main(["load", str(p), "--flow", NA]) == 0
    out = capsys.readouterr().out.splitlines()
    flow = next(s for s in out if s.startswith("flow"))
    # the steps of each start, summed (it printed every LP and QP as an iteration)
    assert " limit step(s) over 2 start(s) (" in flow and " + " in flow, flow
    line = next(s for s in out if s.startswith("starts"))
    # said once: the note that carries the same to the report is not a "why" line too
    assert not [s for s in out if "collapse states: from the elastic state" in s]
    assert "from the elastic state X0: lambda = " in line
    assert "(its mechanism's states [" in line and "(the same mechanism)" in line
    # both starts reach one mechanism; the states they end at follow the simplex path,
    # which differs between machines (0.5096328 from both on one, apart on another)
    lams = [float(x.split()[0].rstrip(";")) for x in line.split("lambda = ")[1:]]
    assert ("; the answers differ: [" in line) == (abs(lams[0] - lams[1]) > 1e-7 * lams[0])
    spread = nonassociative.starts_text([
        {"start": "the elastic state X0", "load_factor": 0.5096328, "converged": True,
         "span": [0.5095833, 0.5097181]},
        {"start": "the associative collapse state", "load_factor": 0.5097, "converged": True,
         "span": [0.5095833, 0.5097181]}])
    assert spread.endswith("; the answers differ: [0.5096328, 0.5097] (the answer is X0's)")
    assert main(["load", str(EXAMPLES / "reference_self_weight.json"), "--flow", NA]) == 0
    why = [s for s in capsys.readouterr().out.splitlines() if s.startswith("why")]
    assert why[1].startswith("why        not a lower bound: collapse states of the same "
                             "mechanism carry lambda from 0.6 ")


def test_cone_mechanisms_of_the_extruded_wall():
    """The 10 x 10 wall at f = 0.8 extruded to 3D (Coulomb's cones, 4 points a joint):
    the limit iteration ends at the collapse states of the mechanism it reaches (the
    cones' duals fix each sliding contact's direction), whose range is the 2D wall's
    to 1e-7 (one mechanism, in plane), and its answer is the 2D answer to 1e-3 (issue
    #30: a wall and its extrusion agree to 1e-3); the answer is a checked collapse
    state."""
    from rigidblocks.scene.extrude import extrude

    wall = build("wall", courses=10, blocks_per_course=10, friction=0.8)
    r2 = rb.max_load_multiplier(wall, flow=NA, state=False)
    r3 = rb.max_load_multiplier(extrude(wall), flow=NA, state=False)
    assert r3.status == "collapse" and r3.history[0]["span"] is not None
    assert r3.history[0]["span"] == pytest.approx(r2.history[0]["span"], rel=1e-7)
    assert r3.load_multiplier == pytest.approx(r2.load_multiplier, rel=1e-3)
    assert not any("fails its check" in n for n in r3.notes)


def test_a_solver_failure_on_a_mechanism_is_not_the_mechanisms():
    """The 204-block wall3d (14 x 14) in plane at f = 0.6: from X0 Clarabel fails on the
    nearest state of a settled mechanism at two steps (NumericalError); sought again at
    the next settled steps, the run ends at a checked state of its mechanism after 19
    limit solves, inside its span (it ended as a plain fixed point after 26 when such a
    failure was recorded as the mechanism's and the mechanisms near it were not tried
    again); the answer is the 2D wall's to 1e-3 (issue #30: measured 6e-5, 0.4678560
    and 0.4678844)."""
    _wall3d_in_plane_at_its_mechanisms_states(14, 14, 0.6)


def _wall3d_in_plane_at_its_mechanisms_states(courses: int, per_course: int,
                                              f: float) -> None:
    """A wall3d in plane: from X0 the run ends at a checked state of its mechanism,
    least confined, inside its span, and the answer is the 2D wall's to 1e-3."""
    r2 = rb.max_load_multiplier(build("wall", courses=courses, blocks_per_course=per_course,
                                      friction=f), flow=NA, state=False)
    r3 = rb.max_load_multiplier(build("wall3d", courses=courses, blocks_per_course=per_course,
                                      friction=f, load_direction="in_plane"),
                                flow=NA, state=False)
    x0 = r3.history[0]
    assert r3.status == "collapse" and r3.converged
    assert x0["start"] == "the elastic state X0" and x0["least_confined"]
    assert x0["span"] is not None and x0["span"][0] <= x0["load_factor"] <= x0["span"][1]
    assert r3.load_multiplier == pytest.approx(r2.load_multiplier, rel=1e-3)


def test_corbel_dome_decided_by_its_cone_steps():
    """The corbel dome (42 blocks, 500 contact points, Coulomb's cones): its cone steps
    settle only to the interior-point solver's accuracy (runs end at changes of 1e-6,
    3e-6 of the largest force; with the selection 1e-9 below each step's maximum
    Clarabel failed 111 of 121 selections, and the run reported phase 1's multiplier
    beside a state carrying less: equilibrium residual 4.8e-6). Both starts reach a
    fixed point whose state, recomputed here, is in equilibrium at the run's
    multiplier to 1e-7 of its largest force and meets Coulomb's law with its own
    normal forces to f times its settling; the analysis answers from X0, below the
    associative multiplier (Radenkovic)."""
    scene = read_scene(EXAMPLES / "corbel_dome.json")
    f = scene.friction
    na, cv = nonassociative._open(scene, "clarabel", NA)
    up = cv.load_limit(f, 1e-9)
    _, starts = nonassociative._starts(na, cv, up, f)
    runs = limit_runs(CappedLimit(cv, na.marked, f), starts)
    assert [r.status for r in runs] == ["converged", "converged"]
    for run in runs:
        assert 0 < run.resolution <= 1e-5
        eq, breach = certificate(cv, f, run.lam, run.x * cv.scaling.force)
        assert eq <= 1e-7 and breach <= 1e-8 + f * run.resolution
    res = rb.max_load_multiplier(scene, flow=NA, state=False)
    assert res.status == "collapse"
    assert res.load_multiplier == runs[0].lam <= res.load_multiplier_bounds[1]
    # the notes on a mechanism are on the one shown, the answer's: the associative
    # bound's ("on the associative multiplier lambda_a ...: the mechanism drawn ... is not
    # a collapse mechanism at lambda_a") stood beside it, of a mechanism not drawn
    drawn = [n for n in res.notes if "the mechanism drawn" in n]
    assert len(drawn) == 1 and drawn[0].startswith("the mechanism drawn") and \
        "the capped laws' multiplier" in drawn[0], drawn


def test_corbel_dome_friction_trials_run_as_load_does():
    """The corbel dome's non-associative f* under lambda = 0.3: each trial runs as
    `load` at its friction does (Runner.afresh), so the trial at the scene's own
    f = 0.6 carries exactly the multiplier `load` gives there (before, it ran without
    the solver settings the solves at f = 0.3 had found out of reach and did not
    settle: undecided). f* is decided to the requested 1e-5, at or above the static f*
    (lambda_nonassoc <= lambda_assoc at every f; Radenkovic), which is 0.3 here: the
    dome slides on its base at lambda = f (the associative lambda*(f) = f)."""
    scene = read_scene(EXAMPLES / "corbel_dome.json")
    res = rb.min_friction(scene, load_factor=0.3, flow=NA, state=False)
    assert res.status == "stable", res.notes
    assert 0.3 * (1 - 1e-9) <= res.friction_factor <= 0.3 * (1 + 2e-5)
    assert rb.max_load_multiplier(scene, friction=0.3, state=False).load_multiplier == \
        pytest.approx(0.3, rel=1e-6)
    own = [t for t in res.history if t["friction"] == scene.friction]
    assert own and own[0]["converged"]
    load = rb.max_load_multiplier(scene, flow=NA, state=False)
    assert own[0]["load_factor"] == load.load_multiplier  # the same computation


@pytest.mark.slow
@pytest.mark.parametrize("courses, per_course, f", [(20, 15, 0.6), (32, 32, 0.6),
                                                     (32, 32, 0.8)])
def test_large_walls_decided_from_both_starts(courses, per_course, f):
    """The 20 x 15 (311 blocks) and 32 x 32 (1,041 blocks) running-bond walls at
    f = 0.6: the plain fixed-point iteration ended undecided from both starts (the
    311-block wall 2e-7 from a fixed point after 500 steps; the 1,041-block one after
    500 steps); ended at their mechanisms' states both starts are decided, within the
    frictionless and associative bounds (Drucker 1954; Radenkovic), each start's
    answer inside its span, and the spread between them is named. The 1,041-block
    wall at f = 0.8, undecided from both starts with the polytopes of both phases'
    rows alone, is decided at states of phase 1's rows."""
    scene = build("wall", courses=courses, blocks_per_course=per_course, friction=f)
    res = rb.max_load_multiplier(scene, flow=NA, state=False)
    assert res.status == "collapse" and res.converged
    assert [h["status"] for h in res.history] == ["converged", "converged"]
    lo, hi = res.load_multiplier_bounds
    assert lo <= res.load_multiplier <= hi
    for h in res.history:
        assert h["span"][0] <= h["load_factor"] <= h["span"][1]
    lams = [h["load_factor"] for h in res.history]
    named = (f"; the answers differ: [{down(min(lams))}, {down(max(lams))}]"
             if max(lams) > min(lams) * (1 + 1e-6) else "; the same answer")
    assert any(named in n for n in res.notes)


@pytest.mark.slow
def test_wall3d_in_plane_ends_at_its_mechanisms_states():
    """The 491-block wall3d (20 courses x 24) in plane at f = 0.6: from X0 the cone
    iteration ends at the states of the mechanism it reaches, checked to the
    interior-point solver's accuracy (CONE_FIXED_TOL; to 1e-7 their checks failed by
    8.4e-7 to 1.5e-6 and both runs ended as plain fixed points, without a span), and
    the answer is the 2D wall's to 1e-3 (issue #30: a wall and its extrusion agree to
    1e-3; measured 2e-6: 0.4374261 and 0.4374252)."""
    _wall3d_in_plane_at_its_mechanisms_states(20, 24, 0.6)


@pytest.mark.slow
def test_wall3d_of_1041_blocks_in_plane_decided_from_x0():
    """The 1,041-block wall3d (32 x 32) in plane at f = 0.6 (issue #30: wall3d at about
    1,000 blocks decided): from X0 the cone iteration ends at checked states of the
    mechanism it reaches (phase 1's rows alone; measured 0.4110370 in [0.4108544,
    0.4110587] after 42 limit solves, about 9 minutes), and the answer is the 2D
    wall's to 1e-3 (measured 2.3e-5: 0.4110464). Its run stalled with the check at
    1e-6 (its state failed it by 2.6e-6), and before that with a solver failure on
    one lowest state recorded as an empty polytope."""
    f = 0.6
    r2 = rb.max_load_multiplier(build("wall", courses=32, blocks_per_course=32,
                                      friction=f), flow=NA, state=False)
    scene = build("wall3d", courses=32, blocks_per_course=32, friction=f,
                  load_direction="in_plane")
    na, cv = nonassociative._open(scene, "clarabel", NA)
    up = cv.load_limit(f, 1e-9)
    _, starts = nonassociative._starts(na, cv, up, f)
    assert starts[0][0] == "the elastic state X0"
    (run,) = limit_runs(CappedLimit(cv, na.marked, f), starts[:1])
    assert run.converged and run.span is not None
    assert run.span[0] <= run.lam <= run.span[1]
    assert run.lam == pytest.approx(r2.history[0]["load_factor"], rel=1e-3)


def test_nonassociative_friction_claims_no_bound_above(tmp_path, capsys):
    """Without dilatancy lambda(f) need not grow with f (the 10 x 10 wall at f = 0.8:
    0.5288166 at f = 0.79915, 0.5287345 at 0.7993): `friction --flow non-associative`
    says it stands at f*, not for every f above it, and whether the scene's friction
    suffices is read from a run at that friction, not from f*: at the multiplier `load`
    found at f = 0.6, f = 0.6 is enough (the same run), and f* is at most 0.6 (the
    search tries the scene's friction first; doubling up from the static f* it found
    a crossing at 0.600233 above it)."""
    from rigidblocks.cli.main import main
    from rigidblocks.io.scene_file import dumps_scene

    p = tmp_path / "wall.json"
    p.write_text(dumps_scene(build("wall", courses=10, blocks_per_course=10, friction=0.6)))
    assert main(["load", str(p), "--flow", NA, "--json"]) == 0
    import json

    lam = json.loads(capsys.readouterr().out)["load_multiplier"]
    assert main(["friction", str(p), "--flow", NA, "--load-factor", repr(lam)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert next(s for s in out if s.startswith("verdict")) == \
        "verdict    STANDS at friction f = f*"
    enough = next(s for s in out if "the scene's friction" in s)
    assert f"is enough: there the state reached from X0 carries lambda = {down(lam)}" in enough
    # the scene's friction is tried first, and f* sought below it where it carries
    fstar = float(next(s for s in out if s.startswith("answer")).split()[3])
    assert fstar <= 0.6
    assert any("a larger f need not carry more" in s for s in out)


def test_check_names_the_state_it_judges():
    """`check --flow non-associative` judges the state reached from X0, not the state of
    least complementary energy, and a ratio |T|/N above f by round-off (0.60008 at f =
    0.6 on a joint carrying 6e-4 of the largest force, 10 x 10 wall at load factor 0.4)
    reads as the friction limit, not as 0.6001 > f."""
    from rigidblocks.answer import answer_block
    from rigidblocks.results import max_demand

    scene = build("wall", courses=10, blocks_per_course=10, friction=0.6)
    res = rb.check(scene, load_factor=0.4, flow=NA)
    assert res.status == "admissible"
    assert max_demand(res.state)[0] > 0.6  # the round-off the words must not show
    assert res.friction_demand[0] <= 0.6  # nor the JSON
    why = answer_block(scene, res).reasons[0]
    assert why.startswith("in the state reached from the elastic state X0 |T|/N reaches "
                          "the friction limit f = 0.6 (joint "), why
    assoc = answer_block(scene, rb.check(scene, load_factor=0.4)).reasons[0]
    assert assoc.startswith("in the state of least complementary energy |T|/N reaches "), assoc


def test_a_failed_non_associative_check_claims_no_more_than_its_state():
    """The flat arch with vertical joints under self-weight: the state reached from X0
    breaches the laws without dilatancy, while the associative check finds an admissible
    state; the non-associative verdict must not say that no equilibrium state exists (it
    did: "no equilibrium state keeps every joint in compression and within friction")."""
    from rigidblocks.answer import answer_block

    scene = read_scene(EXAMPLES / "flat_arch_vertical.json")
    na = rb.check(scene, load_factor=0.0, flow=NA)
    assert na.status == "inadmissible"
    assert rb.check(scene, load_factor=0.0).status == "admissible"
    block = answer_block(scene, na)
    assert block.verdict.startswith("NOT ADMISSIBLE: the state reached from the elastic "
                                    "state X0 does not stand"), block.verdict
    assert "no equilibrium state" not in block.verdict
    assert block.number.startswith("its breach of the joint laws")


@pytest.mark.parametrize("f", [0.2, 0.3])
def test_scene_friction_judged_by_its_own_run(tmp_path, capsys, f):
    """`friction --flow non-associative` says whether the scene's friction suffices from
    a run at that friction: on the reference model with self-weight at load factor 1
    (static f* = 0.25), f = 0.2 is below the static f* (no state at all), and at
    f = 0.3 the state reached from X0 carries what `load --friction 0.3` finds."""
    import json

    from rigidblocks.cli.main import main

    src = json.loads((EXAMPLES / "reference_self_weight.json").read_text())
    src["friction"] = f
    p = tmp_path / "ref.json"
    p.write_text(json.dumps(src))
    assert main(["friction", str(p), "--flow", NA, "--load-factor", "1"]) == 0
    line = next(s for s in capsys.readouterr().out.splitlines()
                if "the scene's friction" in s)
    if f < 0.25:
        assert line.endswith("is NOT enough: below the static f* no equilibrium state "
                             "stands")
        return
    assert main(["load", str(p), "--flow", NA, "--json"]) == 0
    lam = json.loads(capsys.readouterr().out)["load_multiplier"]
    assert lam >= 1
    assert f"is enough: there the state reached from X0 carries lambda = {down(lam)}" in line
