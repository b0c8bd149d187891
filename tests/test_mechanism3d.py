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
