"""3D collapse mechanisms an engineer can read: one mechanism of the optimal face where
the vertex search finds one, its joints classified by what each mostly does, the
moving blocks grouped into rigid bodies, and pictures that mark the fastest joints.

References:
- a monolithic wall of height h and thickness t on a rigid base under a horizontal
  body force lambda x weight, out of its plane, overturns about its base edge at
  lambda* = t / h when friction exceeds it (rigid-body statics: the weight's lever t/2
  against the load's h/2; docs/validation.md, block on a support); the running bond
  makes the wall act as one body;
- a single-span arch failing by four hinges moves as three rigid bodies (Heyman, The
  Stone Skeleton, 1995: the four-hinge mechanism of an arch);
- the box stack under a horizontal body force tips about the first box's edge: the
  boxes above it move as one body.
"""

from __future__ import annotations

import matplotlib
import numpy as np
import pytest
from conftest import EXAMPLES

matplotlib.use("Agg")

import rigidblocks as rb  # noqa: E402
from rigidblocks.answer import mechanism_groups, rigid_bodies  # noqa: E402
from rigidblocks.generators import build  # noqa: E402
from rigidblocks.plotting.marks import MOST_MARKED_3D, marked_joints  # noqa: E402


def test_out_of_plane_wall_overturns_as_one_body_at_t_over_h():
    """12 courses of 0.2 m (h = 2.4 m), t = 0.3 m, f = 0.6: lambda* = 0.125; the vertex
    search gives one mechanism: the wall turns about its base, the foundation joints
    hinge and every other joint stays closed."""
    sc = build("wall3d", courses=12, blocks_per_course=10)
    res = rb.max_load_multiplier(sc)
    assert res.load_multiplier == pytest.approx(0.3 / 2.4, rel=1e-6)
    m = res.mechanism
    assert m.kind == "vertex"
    groups = dict(mechanism_groups(res))
    assert set(groups) == {"hinging"}
    assert all(name.startswith("foundation-") for name in groups["hinging"])
    (body,) = rigid_bodies(res)
    assert len(body) == len(sc.blocks) - 1


def test_box_stack_mechanism_is_a_vertex_of_one_body():
    res = rb.max_load_multiplier(rb.read_scene(EXAMPLES / "box_stack_3d.json"))
    assert res.mechanism.kind == "vertex"
    assert [name for _, names in mechanism_groups(res) for name in names] == ["box0-box1"]
    assert len(rigid_bodies(res)) == 1


def test_arch_four_hinges_three_bodies():
    res = rb.max_load_multiplier(rb.read_scene(EXAMPLES / "arch.json"))
    assert dict(mechanism_groups(res)).keys() == {"hinging"}
    assert len(dict(mechanism_groups(res))["hinging"]) == 4
    assert len(rigid_bodies(res)) == 3


def test_corbel_dome_mechanism_is_drawn_and_read_not_every_joint_both():
    """The README's dome (`example corbel_dome`): one mechanism of the optimal face
    (not the interior-point blend), at the blend's lambda*; its joints mostly slide, so
    they are not all marked sliding-and-hinging; the picture marks the fastest
    MOST_MARKED_3D joints."""
    sc = build("corbel_dome")
    res = rb.max_load_multiplier(sc)
    blend = rb.max_load_multiplier(sc, mechanism="blend")
    assert res.mechanism.kind != "blend" and blend.mechanism.kind == "blend"
    assert res.load_multiplier == blend.load_multiplier
    modes = res.mechanism.modes
    moving = [m for m in modes if m != "closed"]
    assert moving.count("slide+hinge") < len(moving)
    assert moving.count("slide") >= len(moving) / 3  # 68 of 180 (the blend read: none)
    marks = marked_joints(res, most=MOST_MARKED_3D)
    marked = set(marks["hinge"]) | set(marks["slide"]) | set(marks["open"])
    assert len(marked) == MOST_MARKED_3D
    motion = np.asarray(res.mechanism.rates)
    assert min(motion[list(marked)]) >= max(np.delete(motion, list(marked)))


def test_vertex_search_is_bounded_by_work_not_time(monkeypatch):
    """The same command gives the same mechanism at any load of the machine: the vertex
    search passes its solvers iteration budgets and no time limit, and a clock that
    runs 1,000 s per reading (a machine so loaded that any time limit would pass) leaves
    the corbel dome's mechanism as it is (one of the face, with the same rates)."""
    import time

    import scipy.optimize

    import rigidblocks.methods.vertex as vertex

    sc = build("corbel_dome")
    first = rb.max_load_multiplier(sc)
    seen: list[dict] = []
    linprog, solve = scipy.optimize.linprog, vertex.solve

    def lp(*a, **k):
        seen.append(k.get("options", {}))
        return linprog(*a, **k)

    def cone(p, name, **k):
        seen.append(k)
        return solve(p, name, **k)

    clock = [time.perf_counter()]

    def slow() -> float:
        clock[0] += 1000.0
        return clock[0]

    monkeypatch.setattr(scipy.optimize, "linprog", lp)
    monkeypatch.setattr(vertex, "solve", cone)
    monkeypatch.setattr(time, "perf_counter", slow)
    monkeypatch.setattr(time, "monotonic", slow)
    again = rb.max_load_multiplier(sc)
    assert seen and not any("time_limit" in s for s in seen)
    assert {s.get("maxiter", s.get("max_iter")) for s in seen} <= {
        vertex.LP_ITERATIONS, vertex.CONE_ITERATIONS}
    assert again.mechanism.kind == first.mechanism.kind != "blend"
    np.testing.assert_array_equal(again.mechanism.rates, first.mechanism.rates)


def test_dome_blocks_coloured_by_speed_and_named_fastest_first():
    """The dome's 61 blocks each move on their own: 61 body colours could not be told
    apart, so each block is coloured by its speed (pale for the slowest, SPEED_COLOURS'
    last for the fastest), the legend gives the scale, and the answer names the fastest
    blocks, with "and N more", the same block first as the legend."""
    from rigidblocks.answer import answer_block, block_reach
    from rigidblocks.plotting.marks import SPEED_COLOURS, mechanism_colours, speed_colour
    from rigidblocks.scene.geometry import scene_weights

    sc = build("corbel_dome")
    res = rb.max_load_multiplier(sc)
    cen = scene_weights(sc)[1]
    colours, legend = mechanism_colours(sc, res, cen)
    reach = block_reach(sc, res.mechanism.velocities, cen)
    fastest = int(np.argmax(reach))
    assert colours[fastest] == SPEED_COLOURS[-1] == speed_colour(1.0)
    assert colours[int(np.flatnonzero(sc.support_mask)[0])] is None
    assert len({c for c in colours if c}) > 10  # a scale, not one colour
    assert [lab.split(" %")[0] for _, lab in legend] == [
        "block speed 10", "block speed 50", "block speed 100"]
    assert sc.blocks[fastest].id in legend[-1][1]
    (why,) = [r for r in answer_block(sc, res).reasons if "on its own" in r]
    assert why.split("fastest: ")[1].startswith(sc.blocks[fastest].id + ", ")
    assert why.endswith(" and 56 more")


def test_few_bodies_coloured_each_and_named():
    """The arch's three bodies (Heyman's four-hinge mechanism) get three colours, the
    answer names each by its two fastest blocks; the box stack's one body is one colour."""
    from rigidblocks.answer import block_reach, bodies_text
    from rigidblocks.plotting.marks import BODY_COLOURS, mechanism_colours
    from rigidblocks.scene.geometry import scene_weights

    sc = rb.read_scene(EXAMPLES / "arch.json")
    res = rb.max_load_multiplier(sc)
    colours, legend = mechanism_colours(sc, res, scene_weights(sc)[1])
    bodies = rigid_bodies(res)
    assert [c for c, _ in legend] == list(BODY_COLOURS[:3])
    for k, body in enumerate(bodies):
        assert {colours[i] for i in body} == {BODY_COLOURS[k]}
    text = bodies_text(res, sc)
    assert text.count(";") == 2 and "3 rigid bodies" in text
    reach = block_reach(sc, res.mechanism.velocities)
    for named, body in zip(text.split(": ", 1)[1].split("; "), bodies, strict=True):
        fastest = sc.blocks[max(body, key=lambda i: reach[i])].id
        assert named.startswith(fastest + ", ")
        assert named.endswith(f" and {len(body) - 2} more") or len(body) == 2
    box = rb.read_scene(EXAMPLES / "box_stack_3d.json")
    rbox = rb.max_load_multiplier(box)
    colours, legend = mechanism_colours(box, rbox, scene_weights(box)[1])
    assert len(legend) == 1 and "one rigid body" in legend[0][1]
    assert {c for c in colours if c} == {BODY_COLOURS[0]}


def test_report_legend_and_view_colour_the_dome_by_speed():
    """The report's 3D view gets each block's colour and its legend the speed scale."""
    from rigidblocks.reporting.html import render
    from rigidblocks.reporting.view3d import view_data

    sc = build("corbel_dome")
    res = rb.max_load_multiplier(sc)
    m = view_data(sc, res)["mechanism"]
    assert len(m["colours"]) == len(sc.blocks) and m["colours"][0] is None  # the slab
    assert m["moving"] == [c is not None for c in m["colours"]]
    page = render(sc, res)
    for colour, label in m["legend"]:
        assert f'background:{colour}"></span>{label.replace(chr(39), "&#x27;")}' in page
    assert "moving block (mechanism)" not in page


@pytest.mark.parametrize("f,mode", [(1.0, "hinge"), (5.0, "hinge")])
def test_a_box_tipping_over_its_corner_hinges(f, mode):
    """A 1 x 1 x 2 box loaded at 45 degrees in plan tips over its corner at
    lambda* = (b / sqrt 2) / (h / 2) ... = 0.7071 (the weight's lever to the corner
    against the load's, rigid-body statics), below f: its bed joint hinges, with
    |T|/N = 0.7071 < f. Its contact points that lift carry no force, and the vertex of
    the duals may let them slip as they open: at f = 1 the joint read "slide+hinge"
    (at f = 5 "hinge")."""
    sc = build("box_stack", boxes=1, height=2.0, load_azimuth=45.0, friction=f)
    res = rb.max_load_multiplier(sc)
    assert res.load_multiplier == pytest.approx(1 / np.sqrt(2), rel=1e-5)
    assert res.mechanism.modes == (mode,)


def test_a_block_lifted_off_its_base_opens():
    """A block under an upward live body force lifts off at lambda* = 1 (the load equal
    to its weight): its bed joint carries nothing and opens; it read "sliding" at
    f = 0.6 (the duals' vertex slips as it lifts)."""
    from conftest import make_scene, rect

    sc = make_scene([{"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
                     {"id": "B", "vertices": rect(0, 0, 1, 2)}],
                    unit_weight=20.0, friction=0.6, live_body_force=[0, 1])
    res = rb.max_load_multiplier(sc)
    assert res.load_multiplier == pytest.approx(1.0, rel=1e-6)
    assert res.mechanism.modes == ("open",)


def test_a_joint_the_table_calls_open_does_not_slide():
    """The 10 x 10 wall's collapse: a joint whose force is round-off for the table (N =
    2.6e-5 of the largest joint force, "open") read "slide+hinge" in the mechanism; the
    mechanism's modes now count a point's slip where the table counts its force."""
    res = rb.max_load_multiplier(build("wall", courses=10, blocks_per_course=10))
    rows = res.joint_table()
    assert rows and not [r["joint"] for r in rows
                         if r["state"] == "open" and (r["mode"] or "").startswith("slide")]


def test_a_mechanism_drawn_off_the_optimal_face_is_a_reason_not_a_solver_note():
    """examples/corbel_dome.json (4 rings x 10 blocks) at f = 0.6: lambda* = 0.599985
    (certified to 3e-10), and the mechanism drawn, the whole dome sliding on its slab,
    balances at 0.6 exactly (its velocities' dead-load work over the live load's).
    That was a --verbose note only, while the answer named the slab joints as governing
    and said "other collapse mechanisms reach the same multiplier: the one drawn is one
    of them"; `friction` at lambda* names interior joints."""
    from rigidblocks.answer import answer_block
    from rigidblocks.io import read_scene

    sc = read_scene(EXAMPLES / "corbel_dome.json")
    res = rb.max_load_multiplier(sc)
    assert res.load_multiplier == pytest.approx(0.599985, abs=1e-6)
    reasons = answer_block(sc, res).reasons
    off = [r for r in reasons if r.startswith("the mechanism drawn (its joints the "
                                              "governing ones) balances at lambda = 0.6, ")]
    assert off and "not a collapse mechanism at lambda*" in off[0], reasons
    assert not any(r.startswith("other collapse mechanisms reach") for r in reasons)
