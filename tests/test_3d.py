"""3D scenes: convex polyhedra, contact polygons and Coulomb cones (SOCP).

References: docs/validation.md (closed forms; the inclined plane and the box tipping
about an edge are cases of rigidblocks.generators.catalogue, run by test_catalogue.py);
the equivalence of an extruded 2D scene with the plane problem follows from symmetry
about the mid-plane (every 3D admissible state averaged with its mirror image is a
plane state, and a plane state spread evenly over the depth is admissible in 3D).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import EXAMPLES, make_scene, rect

import rigidblocks as rb
from rigidblocks.errors import InputError
from rigidblocks.generators.catalogue import box_on_slab
from rigidblocks.generators.solids import box
from rigidblocks.io.scene_file import scene_from_dict
from rigidblocks.scene.extrude import extrude


def scene3d(blocks, **top):
    doc = {"format": "rigidblocks-scene", "version": 1, "dimension": 3, "blocks": blocks}
    doc.update(top)
    return scene_from_dict(doc)


def test_contact_polygon_of_box_on_slab():
    s = box_on_slab()
    c = rb.detect_contacts(s)
    assert c.n_joints == 1
    assert c.areas[0] == pytest.approx(2.0)
    assert np.diff(c.joint_start)[0] == 4
    np.testing.assert_allclose(c.normals[0], [0, 0, 1], atol=1e-12)


def test_pyramid_depends_on_direction_and_converges_to_cone():
    """An inscribed k-facet pyramid is smaller than the cone: it needs f* >= tan(theta)
    (f* = tan(theta) / cos(pi/k) when the slip points at a facet's middle), so the
    answer depends on the direction, and it tends to tan(theta) as k grows."""
    theta = math.radians(20)
    exact = math.tan(theta)
    f4 = [rb.min_friction(box_on_slab(a=2, b=2, h=0.5, tilt=theta, azimuth=az), state=False,
                          pyramid=4).friction_factor for az in (0.0, 0.3, math.pi / 4)]
    assert min(f4) >= exact * (1 - 1e-6)
    assert max(f4) - min(f4) > 1e-3 * exact
    assert max(f4) <= exact / math.cos(math.pi / 4) * (1 + 1e-6)
    errs = []
    for k in (4, 8, 16, 64):
        f = rb.min_friction(box_on_slab(a=2, b=2, h=0.5, tilt=theta, azimuth=0.3),
                            state=False, pyramid=k)
        assert any("pyramid" in n for n in f.notes)
        errs.append(f.friction_factor - exact)
    assert all(e >= -1e-7 for e in errs)
    assert errs[-1] < errs[0] and errs[-1] <= exact * (1 / math.cos(math.pi / 64) - 1) + 1e-7


def test_extruded_2d_scene_gives_same_answers():
    """Every 2D answer holds for the extruded 3D scene (to 1e-5)."""
    s2 = make_scene([
        {"id": "base", "vertices": rect(-2, -1, 6, 1), "support": True},
        {"id": "A", "vertices": rect(0, 0, 1, 0.5)},
        {"id": "B", "vertices": rect(0.1, 0.5, 0.8, 0.8)},
        {"id": "C", "vertices": [[1.0, 0.0], [2.0, 0.0], [1.8, 0.6], [1.0, 0.5]]},
    ], unit_weight=20.0, friction=0.7, live_body_force=[1, 0], depth=0.5,
        loads=[{"block": "B", "force": [0, -3], "point": [0.5, 1.3]},
               {"block": "C", "force": [-1, 0], "point": [1.5, 0.3], "live": True}])
    s3 = extrude(s2)
    assert s3.dimension == 3
    l2 = rb.max_load_multiplier(s2, state=False).load_multiplier
    l3 = rb.max_load_multiplier(s3, state=False).load_multiplier
    assert l3 == pytest.approx(l2, rel=1e-5)
    f2 = rb.min_friction(s2, load_factor=0.3, state=False).friction_factor
    f3 = rb.min_friction(s3, load_factor=0.3, state=False).friction_factor
    assert f3 == pytest.approx(f2, rel=1e-5)


def test_3d_validation_errors():
    v, f = box(0, 0, 0, 1, 1, 1)
    base_v, base_f = box(-1, -1, -1, 3, 3, 1)
    ok = {"id": "base", "vertices": base_v, "faces": base_f, "support": True}
    with pytest.raises(InputError, match="faces"):
        scene3d([ok, {"id": "b", "vertices": v, "faces": f[:-1]}])
    bent = [list(p) for p in v]
    bent[6] = [1.0, 1.0, 1.3]
    with pytest.raises(InputError, match="block 'b'.*planar"):
        scene3d([ok, {"id": "b", "vertices": bent, "faces": f}])
    with pytest.raises(InputError, match="missing key \"faces\""):
        scene3d([ok, {"id": "b", "vertices": v}])
    sunk = box(0, 0, -0.5, 1, 1, 1)
    with pytest.raises(InputError, match="overlap"):
        scene3d([ok, {"id": "b", "vertices": sunk[0], "faces": sunk[1]}])


def test_nonconvex_block_extruded_gives_the_plane_answer():
    """An L-shaped block (2 x 1 foot, 1 x 1 upright, centroid (5/6, 5/6)) on a base,
    pushed along +x: it tips about its toe x = 2 at lambda* = (2 - 5/6) / (5/6) = 7/5
    with infinite friction (plane closed form). Its extrusion is a non-convex prism
    with non-convex caps, and gives the same lambda* (symmetry about the mid-plane, as
    for convex blocks)."""
    s2 = make_scene([
        {"id": "base", "vertices": rect(-2, -1, 6, 1), "support": True},
        {"id": "L", "vertices": [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]},
    ], unit_weight=1.0, live_body_force=[1, 0])
    s3 = extrude(s2)
    lam2 = rb.max_load_multiplier(s2).load_multiplier
    lam3 = rb.max_load_multiplier(s3).load_multiplier
    assert lam2 == pytest.approx(7 / 5, rel=1e-6)
    assert lam3 == pytest.approx(7 / 5, rel=1e-6)


def test_limit_state_of_a_dome_sliding_all_round_has_a_force_state():
    """At the collapse of the bundled corbel dome (f = 0.6) the least-energy QP is out
    of the interior-point solver's reach (the admissible set is nearly one point); the
    result then carries the limit problem's own state, says so, and that state is in
    equilibrium: the bed joint on the slab carries the dome's weight W vertically and
    lambda* W horizontally, against the load (global equilibrium of the free blocks)."""
    from rigidblocks.scene.geometry import block_weights

    s = rb.read_scene(EXAMPLES / "corbel_dome.json")
    r = rb.max_load_multiplier(s)
    assert r.status == "collapse" and r.state is not None
    if r.state.method != "least complementary energy":
        assert any("limit problem" in n for n in r.notes)
    c = r.contacts
    sup = s.support_mask
    W = block_weights(s)[0][~sup].sum()
    # force on the free block at each point: N n + T1 t1 + T2 t2 (n from pairs[:, 0] into
    # pairs[:, 1]), summed over the joints with the slab
    pj = c.point_joint
    F = (r.state.normal[:, None] * c.normals[pj]
         + np.einsum("pk,pkd->pd", r.state.shear, c.tangents[pj]))
    first_is_support = sup[c.pairs[:, 0]]
    on_slab = first_is_support | sup[c.pairs[:, 1]]
    sign = np.where(first_is_support, 1.0, -1.0)[pj]
    total = (F * sign[:, None])[on_slab[pj]].sum(axis=0)
    direction = np.array(s.live_body_force, float) / np.linalg.norm(s.live_body_force)
    assert total[2] == pytest.approx(W, rel=1e-6)
    assert -total @ direction == pytest.approx(r.load_multiplier * W
                                              * np.linalg.norm(s.live_body_force), rel=1e-5)


@pytest.mark.parametrize("gap,overlaps", [(0.05, False), (-0.05, True)])
def test_overlap_decided_by_an_edge_edge_axis(gap, overlaps):
    """Two cubes standing on an edge, turned 90 degrees to each other, the upper one's
    bottom edge (along y) crossing the lower one's top edge (along x) at a distance
    ``gap``. No face normal of either cube separates them (checked below by projection);
    only the cross product of the two edges (the vertical) does, so the separating-axis
    test must try edge pairs: apart at gap > 0, overlapping at gap < 0."""
    r = math.sqrt(0.5)
    # cube of side 1 turned 45 degrees about x: its top edge runs along x at z = 2r
    sec = [[0, -r, r], [0, 0, 2 * r], [0, r, r], [0, 0, 0]]
    lower = [[x, y, z] for x in (-0.5, 0.5) for _, y, z in sec]
    # the same turned about y and lifted: its bottom edge runs along y at z = 2r + gap
    upper = [[y, x, z + 2 * r + gap] for x in (-0.5, 0.5) for _, y, z in sec]
    faces = [[0, 1, 2, 3], [7, 6, 5, 4], [0, 4, 5, 1], [1, 5, 6, 2], [2, 6, 7, 3],
             [3, 7, 4, 0]]
    pl, pu = np.array(lower), np.array(upper)
    normals = [np.array(n) / np.linalg.norm(n) for n in
               ([1, 0, 0], [0, 1, 1], [0, 1, -1], [0, 1, 0], [1, 0, 1], [1, 0, -1])]
    for n in normals:  # no face normal separates them
        a, b = pl @ n, pu @ n
        assert a.max() > b.min() and b.max() > a.min()
    base_v, base_f = box(-3, -3, -2, 6, 6, 1)
    blocks = [{"id": "base", "vertices": base_v, "faces": base_f, "support": True},
              {"id": "lower", "vertices": lower, "faces": faces},
              {"id": "upper", "vertices": upper, "faces": faces}]
    if overlaps:
        with pytest.raises(InputError, match="'lower' and 'upper' overlap"):
            scene3d(blocks)
    else:
        assert len(scene3d(blocks).blocks) == 3


def test_min_friction_where_the_relaxation_below_f_star_is_degenerate():
    """A 10 x 10 running-bond wall extruded to 3D under a horizontal body force equal to
    its weight: the foundation joint carries the weight W and the horizontal force W,
    so f* >= 1, and a state with |T| = N on every bed joint reaches it (f* = 1, as in
    2D). Just below f* the relaxation is too degenerate for Clarabel (AlmostSolved); the
    analysis probes further below and brackets f* = 1, not a failure: a number at
    rtol = 1e-4, undecided with its bracket (1.0e-6) and that accuracy at 1e-7."""
    from rigidblocks.generators.walls import running_bond_wall
    from rigidblocks.scene.extrude import extrude

    wall = extrude(running_bond_wall(10, 10))
    r = rb.min_friction(wall, load_factor=1.0, rtol=1e-4, state=False)
    assert r.status == "stable" and r.accuracy <= 1e-4
    assert r.friction_factor == pytest.approx(1.0, rel=1e-4)
    assert r.lower <= 1.0 <= r.upper * (1 + 1e-9)
    r = rb.min_friction(wall, load_factor=1.0, rtol=1e-7, state=False)
    assert r.status == "undecided" and 1e-7 < r.accuracy <= 1e-4
    # its certified end 0.99999994 is admissible to the verdict's threshold (1e-9 of the
    # largest force), 5.6e-8 below f* = 1: that threshold, not the search, sets this
    assert r.lower <= 1.0 <= r.upper * (1 + 1e-7)


@pytest.mark.parametrize("sides", [4, 8, 32])
def test_a_joints_breach_is_its_points_summed(sides):
    """A regular prism (circumradius 1, height 2) on a slab at f = 0.29 under 0.3 of its
    weight sideways: it is short of friction by (0.3 - 0.29) W, whatever its polygon.
    Each contact point's law is relaxed by the same amount, so the smallest breach, per
    point, is that over the number of points; the joint's breach, named beside it, was
    the largest point's (0.200, 0.141, 0.039 for 4, 8, 32 sides, the deficit 0.8, 1.13,
    1.25), and is now their sum, the deficit."""
    from rigidblocks.generators.solids import make_scene3d, prism, solid

    ang = 2 * np.pi * np.arange(sides) / sides
    ring = [(float(np.cos(a)), float(np.sin(a))) for a in ang]
    scene = make_scene3d("prism", [
        solid("base", box(-2, -2, -1, 4, 4, 1), support=True),
        solid("P", prism([(x, y, 0.0) for x, y in ring], [(x, y, 2.0) for x, y in ring]))],
        unit_weight=20.0, friction=0.29)
    res = rb.check(scene, load_factor=0.3)
    weight = 20.0 * 2 * 0.5 * sides * np.sin(2 * np.pi / sides)
    assert res.status == "inadmissible" and len(res.breaches) == 1
    (_, breach), = res.breaches
    assert breach == pytest.approx(0.01 * weight, rel=1e-4)
    assert res.violation == pytest.approx(0.01 * weight / sides, rel=1e-4)
    # the terminal says which is which, in 2D too (a block lifted off its two points read
    # 10 on the answer line and 20 beside its joint, unexplained)
    from rigidblocks.answer import answer_block

    assert "a joint's, summed over its contact points, is named with it" in \
        answer_block(scene, res).number
