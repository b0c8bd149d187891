"""Contact detection in 2D: joints are the shared stretches of block boundaries.

Expected values are from the geometry by hand: a joint between blocks i and j is a
segment where their boundaries coincide; its contact points are the ends of the shared
stretch, its normal is the outward normal of i's edge (pointing from i into j), its
tangent s = (-n_y, n_x) and its area = length x depth (docs/scene-format.md, "Joints").
"""

from __future__ import annotations

import numpy as np
import pytest
from conftest import make_scene, rect

from rigidblocks.contacts import detect_contacts
from rigidblocks.contacts.detect2d import detect_contacts_2d
from rigidblocks.errors import InputError
from rigidblocks.generators import build
from rigidblocks.generators.walls import block_id, joint_count, running_bond_wall
from rigidblocks.scene.geometry import scene_size
from rigidblocks.scene.model import Block


def joints_by_ids(scene, tol: float = 1e-7) -> dict:
    """{(id_i, id_j): [(points (2,2) sorted, normal, tangent, length, area), ...]}."""
    c = detect_contacts(scene, tol)
    out: dict = {}
    for k, (a, b) in enumerate(c.pairs):
        pts = c.points[c.joint_start[k]:c.joint_start[k + 1]]
        pts = pts[np.lexsort((pts[:, 1], pts[:, 0]))]
        key = (scene.blocks[a].id, scene.blocks[b].id)
        out.setdefault(key, []).append((pts, c.normals[k], c.tangents[k, 0], c.lengths[k],
                                        c.areas[k]))
    return out


def test_partial_overlap_of_edges():
    """A 1-wide block over [0.7, 1.7] on a base over [0, 1]: shared stretch [0.7, 1]."""
    scene = make_scene([
        {"id": "base", "vertices": rect(0, -1, 1, 1), "support": True},
        {"id": "B", "vertices": rect(0.7, 0, 1, 0.5)},
    ], depth=0.3)
    j = joints_by_ids(scene)
    assert list(j) == [("base", "B")]
    (pts, n, s, length, area), = j[("base", "B")]
    np.testing.assert_allclose(pts, [[0.7, 0.0], [1.0, 0.0]], atol=1e-12)
    np.testing.assert_allclose(n, [0, 1], atol=1e-12)
    np.testing.assert_allclose(s, [-1, 0], atol=1e-12)
    assert length == pytest.approx(0.3)
    assert area == pytest.approx(0.3 * 0.3)


def test_two_points_per_joint_in_tangent_order():
    """Points of a 2D joint are the two ends, the first at the smaller s coordinate."""
    scene = make_scene([
        {"id": "base", "vertices": rect(0, -1, 4, 1), "support": True},
        {"id": "B", "vertices": rect(1, 0, 2, 1)},
    ])
    c = detect_contacts(scene)
    assert c.n_joints == 1 and c.n_points == 2
    s = c.tangents[0, 0]
    p0, p1 = c.points
    assert np.dot(p1 - p0, s) == pytest.approx(2.0)


def test_one_long_edge_touching_several_blocks():
    """Running bond in miniature: the top edge of the base carries three blocks and a
    block of the second course spans two of them: one joint per shared stretch."""
    scene = make_scene([
        {"id": "base", "vertices": rect(0, -1, 3, 1), "support": True},
        {"id": "a", "vertices": rect(0, 0, 1, 1)},
        {"id": "b", "vertices": rect(1, 0, 1, 1)},
        {"id": "c", "vertices": rect(2, 0, 1, 1)},
        {"id": "top", "vertices": rect(0.5, 1, 2, 1)},
    ], depth=2.0)
    j = joints_by_ids(scene)
    assert set(j) == {("base", "a"), ("base", "b"), ("base", "c"), ("a", "b"), ("b", "c"),
                      ("a", "top"), ("b", "top"), ("c", "top")}
    assert all(len(v) == 1 for v in j.values())
    for x0, bid in enumerate("abc"):
        pts = j[("base", bid)][0][0]
        np.testing.assert_allclose(pts, [[x0, 0], [x0 + 1, 0]], atol=1e-12)
    np.testing.assert_allclose(j[("a", "top")][0][0], [[0.5, 1], [1, 1]], atol=1e-12)
    np.testing.assert_allclose(j[("b", "top")][0][0], [[1, 1], [2, 1]], atol=1e-12)
    np.testing.assert_allclose(j[("c", "top")][0][0], [[2, 1], [2.5, 1]], atol=1e-12)
    # head joint a-b: normal from a (left) into b (right) = +x, tangent (0, 1)
    _, n, s, length, area = j[("a", "b")][0]
    np.testing.assert_allclose(n, [1, 0], atol=1e-12)
    np.testing.assert_allclose(s, [0, 1], atol=1e-12)
    assert length == pytest.approx(1.0) and area == pytest.approx(2.0)


def test_corner_only_touch_is_not_a_joint():
    scene = make_scene([
        {"id": "base", "vertices": rect(0, -1, 3, 1), "support": True},
        {"id": "a", "vertices": rect(0, 0, 1, 1)},
        {"id": "b", "vertices": rect(1, 1, 1, 1)},  # touches a at (1, 1) only
        {"id": "c", "vertices": rect(3, 0, 1, 1)},  # touches base at (3, 0) only
    ])
    assert set(joints_by_ids(scene)) == {("base", "a")}


@pytest.mark.parametrize("offset, found", [(1e-9, True), (-1e-9, True), (1e-3, False)])
def test_nearly_collinear_edges(offset, found):
    """Tolerance is relative to the scene size (default 1e-7 x size): a gap or tilt of
    1e-9 x size is a contact, a gap of 1e-3 x size is not."""
    blocks = [{"id": "base", "vertices": rect(0, -1, 2, 1), "support": True},
              {"id": "B", "vertices": rect(0.5, 0, 1, 1)}]
    size = scene_size(make_scene(blocks))
    gap = offset * size
    if gap < 0:  # a slight tilt instead of a gap: one corner up, one exactly on the base
        blocks[1]["vertices"] = [[0.5, 0], [1.5, -gap], [1.5, 1], [0.5, 1]]
    else:
        blocks[1]["vertices"] = rect(0.5, gap, 1, 1)
    scene = make_scene(blocks)
    j = joints_by_ids(scene)
    assert (("base", "B") in j) is found
    if found:
        assert j[("base", "B")][0][3] == pytest.approx(1.0, rel=1e-8)


def test_tolerance_argument_scales():
    """A gap of 1e-5 x size is found with tol=1e-4 and missed with the default."""
    blocks = [{"id": "base", "vertices": rect(0, -1, 2, 1), "support": True},
              {"id": "B", "vertices": rect(0.5, 0, 1, 1)}]
    size = scene_size(make_scene(blocks))
    blocks[1]["vertices"] = rect(0.5, 1e-5 * size, 1, 1)
    scene = make_scene(blocks)
    assert detect_contacts(scene).n_joints == 0
    assert detect_contacts(scene, tol=1e-4).n_joints == 1


def test_l_shape_touches_along_two_segments():
    """An L-shaped block [0,2]x[0,1] + [0,1]x[1,2] and a square [1,2]x[1,2] in its
    re-entrant corner share two segments: y = 1 for x in [1, 2] (normal +y from L into
    the square) and x = 1 for y in [1, 2] (normal +x)."""
    L = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]
    scene = make_scene([
        {"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "L", "vertices": L},
        {"id": "sq", "vertices": rect(1, 1, 1, 1)},
    ])
    j = joints_by_ids(scene)
    assert set(j) == {("base", "L"), ("L", "sq")}
    two = sorted(j[("L", "sq")], key=lambda t: tuple(t[1]))
    assert len(two) == 2
    (p_bed, n_bed, s_bed, *_), (p_side, n_side, s_side, *_) = two
    np.testing.assert_allclose(n_side, [1, 0], atol=1e-12)
    np.testing.assert_allclose(p_side, [[1, 1], [1, 2]], atol=1e-12)
    np.testing.assert_allclose(s_side, [0, 1], atol=1e-12)
    np.testing.assert_allclose(n_bed, [0, 1], atol=1e-12)
    np.testing.assert_allclose(p_bed, [[1, 1], [2, 1]], atol=1e-12)
    np.testing.assert_allclose(s_bed, [-1, 0], atol=1e-12)


def test_u_shape_holds_a_block_on_three_sides():
    """A U (outer [0,3]x[0,2], notch [1,2]x[1,2]) holding a unit square in its notch:
    three joints, normals from the U (lower index) into the square: +x, +y, -x."""
    U = [[0, 0], [3, 0], [3, 2], [2, 2], [2, 1], [1, 1], [1, 2], [0, 2]]
    scene = make_scene([
        {"id": "base", "vertices": rect(0, -1, 3, 1), "support": True},
        {"id": "U", "vertices": U[::-1]},  # clockwise on purpose
        {"id": "key", "vertices": rect(1, 1, 1, 1)},
    ])
    j = joints_by_ids(scene)
    normals = sorted(tuple(np.round(t[1], 12)) for t in j[("U", "key")])
    assert normals == [(-1.0, 0.0), (0.0, 1.0), (1.0, 0.0)]
    assert all(t[3] == pytest.approx(1.0) for t in j[("U", "key")])
    (pts, n, *_), = j[("base", "U")]
    np.testing.assert_allclose(pts, [[0, 0], [3, 0]], atol=1e-12)


def test_normals_point_from_i_into_j_and_frame_is_right_handed():
    """For every joint of a small wall: n points from i's centroid side into j's, n is
    a unit vector and s = (-n_y, n_x)."""
    scene = running_bond_wall(4, 3)
    c = detect_contacts(scene)
    np.testing.assert_allclose(np.linalg.norm(c.normals, axis=1), 1.0)
    s = c.tangents[:, 0]
    np.testing.assert_allclose(s, np.stack([-c.normals[:, 1], c.normals[:, 0]], 1))
    cent = np.array([b.points.mean(axis=0) for b in scene.blocks])  # rectangles
    mid = 0.5 * (c.points[0::2] + c.points[1::2])
    i, j = c.pairs[:, 0], c.pairs[:, 1]
    assert np.all(np.einsum("ij,ij->i", mid - cent[i], c.normals) > 0)
    assert np.all(np.einsum("ij,ij->i", cent[j] - mid, c.normals) > 0)


def test_areas_are_length_times_depth():
    scene = running_bond_wall(3, 4, block_length=0.5, block_height=0.25, depth=0.35)
    c = detect_contacts(scene)
    seg = np.linalg.norm(c.points[1::2] - c.points[0::2], axis=1)
    np.testing.assert_allclose(c.lengths, seg)
    np.testing.assert_allclose(c.areas, 0.35 * seg)
    # bed joints are 0.25 or 0.5 long (half or full block), head joints 0.25 high
    assert set(np.round(c.lengths, 12)) <= {0.25, 0.5}


def test_redundant_vertices_are_ignored():
    """A base whose top edge has extra collinear vertices (and a repeated vertex) gives
    the same joints as a plain rectangle."""
    base = [[0, -1], [3, -1], [3, 0], [2, 0], [2, 0], [1.5, 0], [1, 0], [0, 0]]
    scene = make_scene([
        {"id": "base", "vertices": base, "support": True},
        {"id": "B", "vertices": rect(0.5, 0, 2, 1)},
    ])
    (pts, *_), = joints_by_ids(scene)[("base", "B")]
    np.testing.assert_allclose(pts, [[0.5, 0], [2.5, 0]], atol=1e-12)


# -- running-bond walls: closed-form joint count ------------------------------------------
@pytest.mark.parametrize("courses, per_course", [(1, 1), (2, 1), (1, 5), (3, 4), (7, 2),
                                                  (10, 10), (11, 6)])
def test_running_bond_joint_count(courses, per_course):
    """J = N (3C - 1) - ceil(C/2): N bed joints on the foundation, 2N between every two
    courses, N - 1 head joints in even and N in odd courses (rigidblocks.generators.walls).
    Hand check: C = N = 1 gives 1; C = 2, N = 1 gives 1 + 2 + 0 + 1 = 4."""
    scene = running_bond_wall(courses, per_course)
    c = detect_contacts(scene)
    expected = per_course * (3 * courses - 1) - (courses + 1) // 2
    assert joint_count(courses, per_course) == expected
    assert c.n_joints == expected
    assert c.n_points == 2 * expected
    assert len(scene.blocks) == 1 + per_course * courses + courses // 2


def _count_joints_by_bookkeeping(courses, N, removed):
    """Independent count from block intervals (in half-block units), no geometry:
    head joints between horizontal neighbours, bed joints between overlapping blocks
    of consecutive courses, one bed joint per block of course 0 on the foundation."""
    rows = []
    for c in range(courses):
        if c % 2 == 0:
            iv = [(2 * i, 2 * i + 2) for i in range(N)]
        else:
            iv = [(max(2 * i - 1, 0), min(2 * i + 1, 2 * N)) for i in range(N + 1)]
        rows.append({i: v for i, v in enumerate(iv) if (c, i) not in removed})
    count = len(rows[0])
    for c, row in enumerate(rows):
        count += sum(1 for i in row if i + 1 in row)
        if c + 1 < courses:
            above = rows[c + 1]
            count += sum(1 for a in row.values() for b in above.values()
                         if min(a[1], b[1]) - max(a[0], b[0]) > 0)
    return count


@pytest.mark.parametrize("courses, N, openings", [
    (6, 5, [(2, 2, 2, 1)]),
    (6, 5, [(1, 3, 1, 2), (4, 1, 3, 2)]),
    (5, 4, [(0, 1, 0, 1)]),
    (8, 6, [(3, 4, 0, 6)]),
])
def test_running_bond_joint_count_with_openings(courses, N, openings):
    """With openings: the bookkeeping count; and, for a one-block opening inside an even
    course (course 2, block 2 of a 6 x 5 wall), the full count minus the 6 joints that
    block had (2 head joints, 2 bed joints below and 2 above)."""
    removed = {(c, b) for c0, nc, b0, nb in openings
               for c in range(c0, c0 + nc) for b in range(b0, b0 + nb)}
    scene = running_bond_wall(courses, N, openings=openings)
    assert len(scene.blocks) == 1 + N * courses + courses // 2 - len(removed)
    assert {block_id(c, b) for c, b in removed}.isdisjoint(b.id for b in scene.blocks)
    n = detect_contacts(scene).n_joints
    assert n == _count_joints_by_bookkeeping(courses, N, removed)
    if openings == [(2, 2, 2, 1)]:
        # course 2 block 2 (6 joints) and course 3 block 2 (2 head + 2 below, minus the
        # one shared with the first, + 2 above) -> 6 + 5 = 11 fewer
        assert n == joint_count(courses, N) - 11
    # the command line's string form, documented in the generator's help, is read in
    # Python too (build("wall", openings="2,2,2,1") read "2" as an item)
    typed = ";".join(",".join(str(v) for v in op) for op in openings)
    assert build("wall", courses=courses, blocks_per_course=N, openings=typed) == scene


def test_bookkeeping_count_agrees_with_closed_form():
    for C, N in [(1, 1), (2, 3), (9, 4)]:
        assert _count_joints_by_bookkeeping(C, N, set()) == joint_count(C, N)


def test_wall_geometry_and_loads():
    scene = running_bond_wall(3, 2, block_length=0.4, block_height=0.2, unit_weight=20.0,
                              horizontal_load=0.3, depth=0.5)
    assert scene.blocks[0].support and scene.blocks[0].id == "foundation"
    assert scene.live_body_force == (0.3, 0.0)
    assert scene.length_unit == "m" and scene.force_unit == "kN"
    xs = {b.id: (b.points[:, 0].min(), b.points[:, 0].max()) for b in scene.blocks}
    assert xs["c1b0"] == pytest.approx((0.0, 0.2))  # half block at the left end
    assert xs["c1b2"] == pytest.approx((0.6, 0.8))  # half block at the right end
    assert xs["c1b1"] == pytest.approx((0.2, 0.6))
    assert xs["foundation"] == pytest.approx((0.0, 0.8))


@pytest.mark.parametrize("kwargs, word", [
    ({"courses": 0}, "courses"), ({"blocks_per_course": 2.5}, "blocks_per_course"),
    ({"block_length": -1}, "block_length"), ({"block_height": float("nan")}, "block_height"),
    ({"depth": 0}, "depth"), ({"unit_weight": -1}, "unit_weight"),
    ({"friction": -0.1}, "friction"), ({"horizontal_load": float("inf")}, "horizontal_load"),
    ({"openings": [(0, 1, 0)]}, "openings item #0"),
    ({"openings": "0,1,x,1"}, "openings item #0"), ({"openings": "0,1,0,1;0,1"},
                                                    "openings item #1"),
    ({"openings": [(9, 2, 0, 1)]}, "openings item #0"),
    ({"openings": [(0, 1, 9, 2)]}, "openings item #0"),
    ({"openings": [(0, 1, 3, 1)]}, "even course"),
    ({"openings": [(0, 1, 0, 3), (1, 1, 0, 4), (2, 1, 0, 3)]}, "every block"),
])
def test_wall_parameters_are_checked(kwargs, word):
    args = {"courses": 3, "blocks_per_course": 3} | kwargs
    with pytest.raises(InputError, match=word) as info:
        running_bond_wall(**args)
    assert "\n" not in str(info.value)


def test_many_suspect_blocks_simplified():
    """Every block with an extra vertex mid-way along its bottom edge: same joints as
    the plain wall (the simplification runs on each of them)."""
    scene = running_bond_wall(6, 5)
    blocks = [scene.blocks[0]]
    for b in scene.blocks[1:]:
        v = b.vertices
        mid = ((v[0][0] + v[1][0]) / 2, v[0][1])
        blocks.append(Block(b.id, (v[0], mid) + v[1:]))
    busy = scene.with_changes(blocks=tuple(blocks))
    c = detect_contacts_2d(busy, 1e-7)
    assert c.n_joints == joint_count(6, 5)
    plain = detect_contacts_2d(scene, 1e-7)
    np.testing.assert_allclose(np.sort(c.lengths), np.sort(plain.lengths))
