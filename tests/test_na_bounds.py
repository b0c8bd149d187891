"""The safe non-associative multiplier (rigidblocks.analyses.na_bounds): the smallest
collapse multiplier over all states of a 2D scene, as a mixed-integer LP.

Every answer is checked here independently of the module: the state it returns is
put back into the equilibrium system assembled afresh and the mechanism's relative
displacements are recomputed from its block velocities (:func:`collapse_state_holds`).
The values are checked against closed forms (validation.md, "Closed forms"; derived
in each test) and against the theorems that bracket every non-associative collapse
multiplier: the associative multiplier with the non-associative joints frictionless
below (Radenkovic's second theorem; Drucker, "Coulomb friction, plasticity, and limit
loads", J. Appl. Mech. 21, 1954) and the associative multiplier above (the static
theorem: every collapse state is admissible), with the multiplier of the state reached
from the elastic state (``max_load_multiplier(flow="non-associative")``), one of the
collapse states, in between.
"""

from __future__ import annotations

import numpy as np
import pytest
from conftest import EXAMPLES, make_scene, pinched, rect

import rigidblocks as rb
from rigidblocks.analyses.na_bounds import safe_multiplier
from rigidblocks.equilibrium import assemble
from rigidblocks.errors import InputError
from rigidblocks.generators import build
from rigidblocks.io import read_scene

NA = "non-associative"
#: closed forms are exact for rigid blocks; the MILP's states are exact LP solutions
RTOL = 1e-7


def block(b=1.0, h=2.0, f=0.3):
    return make_scene([
        {"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "B", "vertices": rect(0, 0, b, h)},
    ], unit_weight=20.0, friction=f, live_body_force=[1, 0], flow=NA)


def stack(n=3, f=0.3):
    blocks = [{"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True}]
    blocks += [{"id": f"B{k}", "vertices": rect(0, k, 1, 1)} for k in range(n)]
    return make_scene(blocks, unit_weight=20.0, friction=f, live_body_force=[1, 0],
                      flow=NA)


def collapse_state_holds(scene, res, tol=1e-7, dilatancy=False):
    """Is ``res`` a non-associative collapse state at ``res.upper``? Checked on the
    equilibrium system assembled afresh (design.md, "Statics conventions"):
    equilibrium, N_k >= -t a_k, |T_j| <= f (N_1 + N_2) + c a_j; relative displacements
    A^T v of the mechanism's block velocities v: openings >= 0 and only where N_k is at
    its tensile limit, slips only where |T| is at its limit and against T (no
    dilatancy asked: a slip need not open); the live load does positive work, or where
    the dead load drives the mechanism (``res.driven_by``), the dead load does and the
    live load does none or resists it. With
    ``dilatancy`` (associative flow) a slip opens the joint by f |slip| at each point
    (normality), and only the opening beyond that needs the tensile limit. Returns the
    joints that slip."""
    sysm = assemble(scene)
    c = sysm.contacts
    lay = sysm.layout
    st, mech, lam, f = res.state, res.mechanism, res.upper, res.friction
    x = np.concatenate([st.normal, st.joint_shear])
    scale = max(float(np.abs(x).max()), float(np.abs(sysm.dead).max()))
    assert np.abs(sysm.A @ x + sysm.dead + lam * sysm.live).max() <= tol * scale
    N, Nj, T = st.normal, st.joint_normal, st.joint_shear
    Nmin = -c.tensile_strength[c.point_joint] * c.point_areas
    cap = f * Nj + c.cohesion * c.areas
    assert (Nmin - N).max() <= tol * scale
    assert (np.abs(T) - cap).max() <= tol * scale
    v = mech.velocities[sysm.free_blocks].ravel()
    if res.driven_by == "dead":
        assert v @ sysm.dead > 0 and v @ sysm.live <= tol * np.abs(v).max()
    else:
        assert v @ sysm.live > 0
    delta = sysm.A.T @ v
    opening, slip = delta[lay.normal], delta[lay.tangential]
    vs = float(np.abs(delta).max())
    if dilatancy:
        opening = opening - f * np.abs(slip)[c.point_joint]
    assert opening.min() >= -tol * vs
    assert np.all((N - Nmin)[opening > tol * vs] <= tol * scale)
    slides = np.flatnonzero(np.abs(slip) > tol * vs)
    assert np.all(np.abs(T[slides]) >= cap[slides] - tol * scale)
    assert np.all(slip[slides] * T[slides] <= tol * scale * vs)
    assert len(c.pairs) == len(T)
    return slides


def bracketed(res, x0=None):
    """frictionless bound <= capacity bound <= the safe value <= X0's answer (a
    LoadResult: the upper end of its bisection's bracket) <= associative (see the
    module docstring), to 1e-7 (the LPs' accuracy)."""
    v = res.value
    if res.frictionless is not None:
        assert res.frictionless <= res.capacity_bound + 1e-7 * max(1.0, v)
    assert res.capacity_bound <= v + 1e-7 * max(1.0, v)
    if x0 is not None:
        assert x0.status == "collapse"
        top = x0.bracket[1] if x0.bracket else x0.load_multiplier
        assert v <= top + 1e-7 * max(1.0, top)
    if res.associative is not None:
        assert v <= res.associative + 1e-7 * max(1.0, v)


# -- closed forms -----------------------------------------------------------------------
@pytest.mark.parametrize("f, value, mode", [(0.3, 0.3, "slide"), (0.8, 0.5, "hinge")])
def test_single_block(f, value, mode):
    """A block b = 1 wide, h = 2 tall on a support under a horizontal body force lambda W
    (validation.md): it slides at lambda = f when f < b/h, tips about its toe at b/h =
    0.5 otherwise. One joint, one state: every state gives the same answer, and the
    capacity bound reaches it (the block's bed joint carries at least its weight).
    Solved without the bound as a cut, so that the MILP's value is its own."""
    res = safe_multiplier(block(f=f), cut=False)
    assert res.capacity_bound == pytest.approx(value, rel=RTOL)
    assert res.status == "optimal"
    assert res.value == pytest.approx(value, rel=RTOL)
    assert res.mechanism.modes == (mode,)
    collapse_state_holds(block(f=f), res)
    bracketed(res, rb.max_load_multiplier(block(f=f), state=False))


@pytest.mark.parametrize("f, value", [(0.3, 0.3), (0.5, 1 / 3)])
def test_three_block_stack(f, value):
    """Three unit blocks stacked on a support, body force lambda W each: every bed joint
    carries the weight of the blocks above it and the live load on them, so each slides
    at lambda = f; the stack of height H tips about its toe at b / H, the top k blocks at
    b / k (validation.md): min(f, 1/3). The capacity bound reaches it."""
    res = safe_multiplier(stack(f=f), cut=False)
    assert res.capacity_bound == pytest.approx(value, rel=RTOL)
    assert res.status == "optimal"
    assert res.value == pytest.approx(value, rel=RTOL)
    collapse_state_holds(stack(f=f), res)
    bracketed(res, rb.max_load_multiplier(stack(f=f), state=False))


def test_pinched_block_safe_value_is_f():
    """The unit block pinched between a fixed base and a fixed lintel at f = 0.8
    (tests/test_nonassociative.py; validation.md, "A block pinched between two fixed
    parallel faces").

    Associative: no mechanism (every slip would have to dilate against the other face),
    lambda unbounded. Non-associative, a translation sliding on both faces at once opens
    nothing; it needs lambda W = f (N_base + N_lintel) with N_base = W + N_lintel, so the
    least collapse multiplier is that of the state without lintel force: lambda = f =
    0.8, and that state is admissible: the base resultant lies lambda W (h/2) / W = 0.4
    from the block's centre, inside its half-width 0.5. The elastic state reaches the
    same state (its lintel link would hang W/2 in tension, which the no-tension law
    clears), so its answer is 0.8 too, to its bisection's 1e-5. LMGC90's tilt test gives
    1.28 (issue 30): the sudden load clamps the block dynamically, a lintel force L =
    0.3 W, and lambda W = f (N_base + L) = 0.8 (1.3 W + 0.3 W) = 1.28 W. The pinch is a
    state choice: every lintel force L >= 0 gives a collapse state at f (1 + 2 L / W),
    and the least is the safe value. The frictionless bound is 0 (the block slides
    freely on frictionless faces); the capacity bound reaches 0.8 (the base carries at
    least W in every admissible state)."""
    scene = pinched(0.8, flow=NA)
    res = safe_multiplier(scene, cut=False)
    assert res.capacity_bound == pytest.approx(0.8, rel=RTOL)
    assert res.status == "optimal"
    assert res.value == pytest.approx(0.8, rel=RTOL)
    assert res.associative == np.inf and res.frictionless == 0.0
    collapse_state_holds(scene, res)
    c = assemble(scene).contacts
    lintel = [k for k, (a, b) in enumerate(c.pairs) if "lintel" in
              (scene.blocks[a].id, scene.blocks[b].id)]
    assert res.state.joint_normal[lintel] == pytest.approx([0.0], abs=1e-9)
    base = [k for k in range(c.n_joints) if k not in lintel]
    assert abs(res.state.eccentricity[base][0]) == pytest.approx(0.4, rel=1e-7)
    x0 = rb.max_load_multiplier(scene, flow=NA, state=False)
    assert x0.status == "collapse"
    bracketed(res, x0)


# -- the seed's examples ------------------------------------------------------------------
@pytest.mark.parametrize("name, value", [
    # the pulled blocks of the reference model carry no load of their own without
    # self-weight, and the top block can stand on the corner of the right one: in that
    # state the left block holds nothing and slides away at the smallest pull
    ("reference.json", 0.0),
    # with self-weight (20 kN/m3 x 0.1 x 0.1 x 0.25 m = 50 N) the left block, unloaded by
    # the top as above, slides on its own weight: lambda 50 N = 0.6 x 50 N
    ("reference_self_weight.json", 0.6),
    ("fig4a_bonded.json", None), ("stocky_arch.json", None), ("arch.json", None)])
def test_examples_between_the_bounds(name, value):
    """frictionless bound <= safe value <= the answer from the elastic state <=
    associative, on the seed's small examples, every joint non-associative; the state
    returned is a collapse state (checked independently). Where the safe value is a
    closed form it is derived beside it. Without the capacity bound as a cut: the
    MILP's value is its own, and the bound is checked against it."""
    scene = read_scene(EXAMPLES / name)
    res = safe_multiplier(scene, flow=NA, cut=False)
    assert res.status == "optimal" and res.value is not None
    assert res.lower <= res.value
    if value is not None:
        assert res.value == pytest.approx(value, abs=1e-9, rel=RTOL)
    collapse_state_holds(scene, res)
    x0 = rb.max_load_multiplier(scene, flow=NA, state=False)
    bracketed(res, x0)
    # `load`'s own lower bound (the capacity bound, computed by itself) is one too
    assert x0.load_multiplier_bounds[0] <= res.value + 1e-9 * max(1.0, res.value)


@pytest.mark.parametrize("name", ["reference_self_weight.json", "fig4a_bonded.json",
                                  "arpino_gate.json"])
def test_associative_flow_gives_the_associative_multiplier(name):
    """With every joint associative (Q = G: normality) every collapse state has the one
    associative multiplier (the limit theorems), so the least over the states, found by
    branch and bound over the same binaries, is the maximum-load LP's value (Clarabel):
    two solvers and two formulations, one number (validation.md, "Cross-checks that need
    no reference value"). Without the capacity bound as a cut (with no non-associative
    joint it is the associative multiplier itself)."""
    scene = read_scene(EXAMPLES / name)
    res = safe_multiplier(scene, flow="associative", cut=False)
    assert res.status == "optimal"
    assert res.value == pytest.approx(res.associative, rel=1e-7)
    collapse_state_holds(scene, res, dilatancy=True)


def test_bounds_that_bind_give_no_value():
    """The pinched block with every normal force bounded by W/2 (W = 10; a pinch makes
    the admissible forces unbounded, so the stated bound applies): the base's two points
    must carry W plus the lintel force, W only with the resultant at the centre, which
    cannot balance the load's moment: no state fits. With the bound doubled (W) the
    state of the safe value (N_base = W at 0.4 from the centre: 9 on the front point)
    fits. The answer moves with the bound: no safe value, the least state found (0.8)
    as ``upper``."""
    scene = pinched(0.8, flow=NA)
    res = safe_multiplier(scene, force_bound=5.0)
    assert res.status == "bound-dependent" and res.value is None
    assert res.upper == pytest.approx(0.8, rel=RTOL)
    assert res.trials == ((5.0, None), (10.0, pytest.approx(0.8, rel=RTOL)))
    collapse_state_holds(scene, res)


def test_the_3x3_wall_collapses_at_5_7_in_some_state():
    """The 3 x 3 running-bond wall at f = 0.8 (issue 30: LMGC90's tilt test [0.7139,
    0.7148], the answer from the elastic state 0.7468, associative 0.7705).

    A collapse state at 5/7, by hand: blocks 0.4 x 0.2 (half blocks 0.2 x 0.2) of
    weight 20 per unit area; the right end of the middle course is the half block c1b3
    (weight 0.8, centroid (1.1, 0.3)) under the top course's end block c2b2 (weight 1.6,
    centroid (1.0, 0.5)), which also rests on c1b2. In the state where c2b2 rests on
    c1b3 alone (the base resultant at x = 1.0 + 0.1 lambda, inside c1b3's top [1.0,
    1.2]) and the head joint c1b2-c1b3 carries nothing, the two blocks overturn together
    about c1b3's toe (1.2, 0.2) when lambda (0.8 x 0.1 + 1.6 x 0.3) = 0.8 x 0.1 + 1.6 x
    0.2, lambda = 0.40 / 0.56 = 5/7 = 0.714286, inside LMGC90's bracket; c2b2 slides off
    c1b2 and c2b1 without dilatancy (their normal forces are zero), and the toe's
    shear 5/7 x 2.4 = 1.71 is below f N = 0.8 x 2.4 = 1.92. The answer from the elastic
    state, 0.7468, rests on a head-joint thrust that this state does not have: it is
    above the least collapse state by 4.6%.

    The mixed-integer LP finds this state within 1,000 branch-and-bound nodes but does
    not prove it least: its complementarity relaxes so weakly that HiGHS's lower bound
    stays 0 (after 127,000 nodes, 2 minutes), and the capacity bound is 0 too (c0b1 can
    hang from its neighbours by head-joint friction in some admissible state, the top
    course's blocks from either block below): undecided, no value."""
    scene = build("wall", courses=3, blocks_per_course=3, friction=0.8)
    res = safe_multiplier(scene, flow=NA, node_limit=1000)
    assert res.status == "undecided" and res.value is None
    assert any("did not prove" in n for n in res.notes)
    assert res.lower == 0.0 and res.capacity_bound == 0.0
    assert res.upper == pytest.approx(5 / 7, rel=1e-9)
    collapse_state_holds(scene, res)
    ids = [b.id for b in scene.blocks]
    v = res.mechanism.velocities
    moving = {ids[k] for k in np.flatnonzero(np.abs(v).max(axis=1) > 1e-9)}
    assert moving == {"c1b3", "c2b2"}
    # one rigid rotation of both about (1.2, 0.2): v = omega x (centroid - pivot)
    for k, centroid in ((ids.index("c1b3"), (1.1, 0.3)), (ids.index("c2b2"), (1.0, 0.5))):
        w = v[k, 2]
        assert v[k, :2] == pytest.approx([-w * (centroid[1] - 0.2), w * (centroid[0] - 1.2)],
                                         abs=1e-9)
    x0 = rb.max_load_multiplier(scene, flow=NA, state=False)
    assert x0.status == "collapse" and x0.load_multiplier >= res.upper


@pytest.mark.parametrize("f, value", [(0.3, 0.3), (0.8, 0.8)])
def test_single_box_3d_with_a_pyramid(f, value):
    """3D: a 1 x 1 x 1 box on a slab under a horizontal body force along x (box_stack
    with one box) slides at lambda = f when f < b/h = 1 (validation.md). The cones are
    replaced by inscribed 8-facet pyramids whose facets' normals lie at (2i + 1) pi / 8
    from the contacts' first tangent, x here: x is a pyramid edge, where the pyramid
    meets the cone, so the pyramid law's multiplier along x is f exactly, as the
    associative LP with the same pyramids gives it. The capacity bound is 0 in 3D
    (each contact point can be unloaded in some admissible state; the laws are per
    point)."""
    scene = build("box_stack", boxes=1, friction=f)
    res = safe_multiplier(scene, flow=NA)
    assert res.status == "optimal"
    assert res.value == pytest.approx(value, rel=RTOL)
    assert res.associative == pytest.approx(value, rel=1e-9)
    assert any("8-facet pyramids" in n for n in res.notes)
    assert res.capacity_bound == 0.0


def test_the_pinched_block_in_3d_turns_about_an_edge_at_0():
    """The pinched block in 3D (the 2D one extruded 1 deep, f = 0.8): its safe value is
    0, not the 2D f, and that is right. In 3D the pinch may run along one vertical edge
    of the block alone, the base pushing up there with W + L and the lintel down with L:
    the weight's overturning moment is then held by the couple of the shears at the
    edge's two ends, 2 |T| = W sqrt(2) / 2 for the unit cube's centre half a diagonal
    from the edge, within f (N_base + N_lintel) for a large enough L. Every other contact
    point is unloaded, so the block turns about that vertical edge with no slip where a
    force acts: no dissipation, and the live load's work lambda times a positive rate
    balances it at lambda = 0. In 2D no such state exists (a turn about one point moves
    the other face's point). (A new user's trial read 0 as a defect: "any slip dissipates
    f N > 0".)"""
    from rigidblocks.methods import open_method
    from rigidblocks.scene.extrude import extrude

    scene = extrude(pinched(0.8, flow=NA))
    res = safe_multiplier(scene)
    assert res.status == "optimal" and res.value == 0.0 and res.driven_by == "live"
    # the state: two loaded points, one on each face, on one vertical line
    n = np.asarray(res.state.normal)
    loaded = np.flatnonzero(n > 1e-6 * n.max())
    assert len(loaded) == 2
    pts = open_method(scene).contacts.points[loaded]
    assert np.allclose(pts[0, :2], pts[1, :2]) and pts[0, 2] != pts[1, 2]
    # the mechanism: a turn about the vertical axis (no rotation about x or y, no rise)
    u = res.mechanism.velocities[1]
    assert abs(u[2]) < 1e-9 and abs(u[3]) < 1e-9 and abs(u[4]) < 1e-9 and abs(u[5]) > 0


# -- refusals -------------------------------------------------------------------------------
@pytest.mark.parametrize("f", [0.7652, 0.8])
def test_the_dead_load_drives_collapse_states_of_the_inclined_corbel_arch(f):
    """The seed's inclined corbel arch (Fig. 7c) just above its static f* = 0.7651 and
    at 0.8 has non-associative collapse states whose mechanism the live load resists:
    the dead load drives them. The mixed-integer LP normalised by the live load's work
    alone (F_live . u = 1, as Ferris & Tin-Loi 2001 write it) cannot see them, and the
    capacity bound (Radenkovic's second theorem through the kinematic theorem) bounds
    the live load's mechanisms only: both said that no state collapses below the
    associative multiplier (4.314e-5, 0.0212988), and `load` answered it. At 0.7652 the
    state found is the mirror image of the limit fixed point from X0, which lies at
    lambda = -2.7061015e-5 under the same mechanism pushed the other way (the arch is
    symmetric, the live load horizontal): two algorithms, one value up to its sign."""
    scene = read_scene(EXAMPLES / "corbel_arch_inclined.json")
    res = safe_multiplier(scene, friction=f, flow=NA)
    assert res.status == "optimal" and res.driven_by == "dead"
    collapse_state_holds(scene, res)
    assert 0.0 < res.value < 0.7 * res.associative
    # no bound claims more: the bound on every state stays at 0 (its first round's
    # capped structure does not carry the dead load alone)
    assert res.capacity_bound == 0.0
    na = rb.max_load_multiplier(scene, friction=f, flow=NA, state=False)
    lo = na.load_multiplier_bounds[0]
    assert lo is None or lo <= res.value
    if f == 0.7652:
        x0 = na.history[0]["load_factor"]
        assert x0 < 0 and res.value == pytest.approx(-x0, rel=1e-8)


def test_refusals():
    wall = build("wall", courses=3, blocks_per_course=3, friction=0.8)
    with pytest.raises(InputError, match=r"22 joints.*at most 10 \(max_joints\)"):
        safe_multiplier(wall, max_joints=10)
    with pytest.raises(InputError, match="3D scenes only"):
        safe_multiplier(block(), pyramid=4)
    with pytest.raises(InputError, match="no live load"):
        safe_multiplier(block().with_changes(live_body_force=None))
    with pytest.raises(InputError, match="force_bound"):
        safe_multiplier(block(), force_bound=-1.0)


def test_bench_na_bounds_tiny(tmp_path):
    """The benchmark runs on its tiny cases: the single block at f = 0.3 (slides at f)
    and the pinched block at f = 0.8 (safe value f, see above), with its table."""
    import importlib.util

    from conftest import ROOT

    spec = importlib.util.spec_from_file_location(
        "bench_na_bounds", ROOT / "benchmarks" / "bench_na_bounds.py")
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    data = bench.main(["--tiny", "--out", str(tmp_path)])
    got = {r["case"]: r["safe"] for r in data["rows"]}
    assert got == {"block 1 x 2, f = 0.3": pytest.approx(0.3, rel=RTOL),
                   "pinched block, f = 0.8": pytest.approx(0.8, rel=RTOL)}
    md = (tmp_path / "bench_na_bounds.md").read_text()
    assert md.startswith("## The safe non-associative multiplier")


def test_the_documented_example(capsys):
    """docs/safe-multiplier.md's example prints what the page says it prints."""
    import re

    from conftest import ROOT

    text = (ROOT / "docs" / "safe-multiplier.md").read_text()
    code = re.search(r"```python\n(.*?)```", text, re.S).group(1)
    said = [ln[2:] for ln in code.splitlines() if ln.startswith("# ")]
    run = "\n".join(ln for ln in code.splitlines() if not ln.startswith("# "))
    run = run.replace('"examples/', f'"{EXAMPLES}/')
    exec(compile(run, "safe-multiplier.md", "exec"), {})
    printed = [ln for ln in capsys.readouterr().out.splitlines()
               if not ln.startswith("HighsMip")]
    assert printed == said


def test_the_bounds_lps_keep_the_time_limit():
    """The slack bounds' LPs (one per joint-law row) run within --safe-time-limit too:
    a wall3d of 42 joints loaded out of plane took 293 s with a limit of 10 s (1,512
    LPs solved from scratch, 150 s, then more); now one warm-started model (30 s), and
    the rows left when the time runs out keep the force bound. At 1e-9 s the reference
    model with self-weight solves one of its 20 rows, and says so."""
    res = safe_multiplier(read_scene(EXAMPLES / "reference_self_weight.json"),
                          flow="non-associative", time_limit=1e-9)
    assert any(n.startswith("the largest slacks of 19 of the 20 joint-law rows were not "
                            "computed within the time limit") for n in res.notes), res.notes
    full = safe_multiplier(read_scene(EXAMPLES / "reference_self_weight.json"),
                           flow="non-associative")
    assert full.status == "optimal" and full.value == pytest.approx(0.6, rel=1e-9)
    assert not any("were not computed" in n for n in full.notes)


def test_cli_load_safe(capsys, tmp_path):
    """`load --flow non-associative --safe`: the reference model with self-weight has a
    collapse state at 0.6 below the answer from X0, 2.4 (the top block on the right
    block alone, the left block sliding out under its own weight: 50 N = f x 100 N),
    proven the smallest; undecided in its time limit, its bracket ends at the answer
    (a checked collapse state); a scene of more than 50 joints gets the reason, and the
    analysis' own answer and exit status are unchanged."""
    import json

    from rigidblocks.cli.main import main

    path = str(EXAMPLES / "reference_self_weight.json")
    assert main(["load", path, "--flow", "non-associative", "--safe"]) == 0
    out = capsys.readouterr().out
    assert "safe       lambda = 0.6: the smallest non-associative collapse multiplier" in out
    assert "safe       BELOW the answer lambda* = 2.4" in out
    # with associative joints the multiplier is unique: no "safe" value is claimed
    assert main(["load", path, "--safe"]) == 0
    out = capsys.readouterr().out
    assert "safe       not computed: no joint slides without dilatancy" in out
    assert main(["load", path, "--flow", "non-associative", "--safe", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["load_multiplier"] == pytest.approx(2.4, rel=1e-6)
    assert doc["safe_multiplier"]["status"] == "optimal"
    assert doc["safe_multiplier"]["value"] == pytest.approx(0.6, rel=1e-6)
    # --safe-time-limit reaches HiGHS: at 1e-9 s nothing is proven, the status says so
    assert main(["load", path, "--flow", "non-associative", "--safe",
                 "--safe-time-limit", "1e-9"]) == 0
    line = next(s for s in capsys.readouterr().out.splitlines() if s.startswith("safe"))
    assert line.startswith("safe       undecided: bracket [") and "Time limit" in line
    # its upper end, with no state from HiGHS, is the answer's checked collapse state
    assert ", 2.4] (mixed-integer LP" in line and "(2.4: the answer's collapse state)" in line
    assert main(["load", path, "--safe-time-limit", "0"]) == 2
    assert "--safe-time-limit: not a number of seconds > 0" in capsys.readouterr().err
    from rigidblocks.io import write_scene

    wall = tmp_path / "wall.json"  # 10 x 10: 106 blocks, 285 joints
    write_scene(build("wall", courses=10, blocks_per_course=10), wall)
    main(["load", str(wall), "--flow", "non-associative", "--safe"])
    assert "safe       not computed:" in capsys.readouterr().out


def test_cli_safe_line_is_rounded_on_the_safe_side(capsys):
    """The inclined corbel arch at f = 1 without dilatancy: the limit iteration's answer
    from X0 is the smallest multiplier over all states (0.0592032278: the mixed-integer
    LP proves it). The `safe` line read 0.05920323, above the answer's 0.0592032 and the
    starts line's 0.05920322 for the same value; a smallest multiplier is rounded down,
    as every collapse multiplier."""
    import json
    import re

    from rigidblocks.cli.main import main

    path = str(EXAMPLES / "corbel_arch_inclined.json")
    args = ["load", path, "--flow", "non-associative", "--friction", "1"]
    assert main([*args, "--json"]) == 0
    lam = json.loads(capsys.readouterr().out)["load_multiplier"]
    assert main([*args, "--safe"]) == 0
    out = capsys.readouterr().out
    safe = float(re.search(r"safe       lambda = ([0-9.e+-]+):", out).group(1))
    starts = float(re.search(r"from the elastic state X0: lambda = ([0-9.e+-]+)", out)
                   .group(1))
    assert safe == starts <= lam and lam - safe < 1e-6 * lam  # seven figures


def test_cli_safe_line_above_a_bisected_answer_says_where_it_lies():
    """The inclined corbel arch at f = 0.8 without dilatancy (examples/
    corbel_arch_inclined.json): `load` reads its answer off the states reached from X0
    by bisection, lambda* = 0.0127922 in [0.01279220942, 0.0127926969], and `--safe`
    proves 0.01279269 (inside that bracket). The safe line printed the proven least
    above the answer with no word on it; a safe value above the whole bracket says the
    answer is not a collapse state."""
    from rigidblocks.cli.analyses import _safe_line

    safe = {"status": "optimal", "value": 0.0127926900, "driven_by": "dead"}
    line = _safe_line(safe, 0.01279220942, (0.01279220942, 0.0127926969))
    assert "\nsafe       above the answer lambda* = 0.0127922, within its bracket " \
        "[0.0127922, 0.0127927]: to the answer's accuracy they are one value" in line
    line = _safe_line(dict(safe, value=0.013), 0.01279220942, (0.01279220942, 0.0127926969))
    assert "above the answer lambda* = 0.0127922: the state reached from X0 breaches" in line
    assert "BELOW" not in _safe_line(safe, 0.01279269, None).split("proven")[1]
    # a positive least multiplier whose mechanism the dead load drives: why not 0
    assert ("; the dead load drives its mechanism (the live load does no work on it or "
            "resists it): the live load's part is to change the normal forces, and with "
            "them the friction f N the joints can give, until the dead load can move it"
            ) in line
    assert "collapses under the dead load alone" in _safe_line(dict(safe, value=0.0), 0.0)


def test_highs_messages_are_not_repeated():
    """`load --flow non-associative --safe` on a 4 x 4 wall with a short time limit read
    "(Time limit reached. (HiGHS Status 13: Time limit reached), N nodes ...": scipy's
    message with HiGHS's own words twice. Other messages are kept as they are."""
    from rigidblocks.analyses.na_bounds import _message

    assert _message("Time limit reached. (HiGHS Status 13: Time limit reached)") == \
        "Time limit reached (HiGHS status 13)"
    other = "Optimization terminated successfully. (HiGHS Status 7: Optimal)"
    assert _message(other) == other


def test_where_the_bounds_meet_the_distortion_path_gives_their_answer():
    """Seed Fig. 4a with its vertical joint bonded in tension only (no cohesion), at
    f = 0.5: the capacity bound and the associative multiplier meet at f P / H =
    0.5 x 100 / 50 = 1 (generators/seed.py), so every collapse state lies at 1. The
    distortion path's state from X0 does not settle there (here within a budget of 500
    iterations, as at its default 20,000) and it read UNDECIDED with a bracket
    [0, 0.999999] below its own lower bound; the convex path answered 1."""
    import json

    from rigidblocks.io.scene_file import scene_from_dict

    doc = json.loads((EXAMPLES / "fig4a_bonded.json").read_text())
    doc["joints"][0].pop("cohesion")
    scene = scene_from_dict(doc)
    r = rb.max_load_multiplier(scene, method="distortion", flow="non-associative",
                               settings={"max_iter": 500})
    assert r.status == "collapse" and r.load_multiplier == pytest.approx(1.0, rel=1e-6)
    lo, hi = r.load_multiplier_bounds
    assert lo <= r.load_multiplier <= hi
    assert any("meets the associative multiplier" in n for n in r.notes), r.notes
    assert r.answered_by[0] == "distortion" and "clarabel" in r.answered_by


def test_where_a_bound_carries_the_load_an_undecided_distortion_check_stands():
    """The same scene at lambda = 0.5, below its capacity bound 1: the distortion path's
    state from X0 decides nothing (within 500 iterations here), and `check` said
    UNDECIDED where the theorem says that every state stands (Radenkovic's second
    theorem, docs/safe-multiplier.md); the verdict is the bound's, and says so."""
    import json

    from rigidblocks.io.scene_file import scene_from_dict

    doc = json.loads((EXAMPLES / "fig4a_bonded.json").read_text())
    doc["joints"][0].pop("cohesion")
    r = rb.check(scene_from_dict(doc), load_factor=0.5, method="distortion",
                 flow="non-associative", settings={"max_iter": 500})
    assert r.status == "admissible" and r.admissible
    assert any("capacity bound on every collapse state" in n for n in r.notes), r.notes
    assert "clarabel" in r.answered_by
