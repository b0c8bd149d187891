"""Non-convex 3D blocks: validation, volume and centroid, overlaps, and joints whose
contact region is non-convex or in several pieces (issue 18, items 1 and 2).

Statics of such a joint: a dry joint carries any resultant that is a positive
combination of compressive forces at points of the contact region, so its resultant
can lie anywhere in the region's convex hull; the hull's vertices are points of the
region, so forces at the hull's vertices reach every such resultant. A block on a
non-convex or split footprint therefore tips about an edge of the footprint's hull,
which may span a notch or a gap where no material touches.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import rigidblocks as rb
from rigidblocks.errors import InputError
from rigidblocks.generators.solids import box, prism
from rigidblocks.io.scene_file import scene_from_dict
from rigidblocks.scene.polyhedra import convex_pieces, is_convex, polyhedron_volume_centroid

L_PLAN = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]
U_PLAN = [(0, 0), (3, 0), (3, 3), (2, 3), (2, 1), (1, 1), (1, 3), (0, 3)]


def scene3d(blocks, **top):
    doc = {"format": "rigidblocks-scene", "version": 1, "dimension": 3,
           "unit_weight": 1.0, "blocks": blocks}
    doc.update(top)
    return scene_from_dict(doc)


def vprism(plan, z0, z1):
    """A vertical prism over a plan polygon, from z0 to z1."""
    return prism([(x, y, z0) for x, y in plan], [(x, y, z1) for x, y in plan])


def solid(bid, geom, support=False):
    d = {"id": bid, "vertices": geom[0], "faces": geom[1]}
    if support:
        d["support"] = True
    return d


def l_on_slab(h=2.0, **top):
    return scene3d([solid("slab", box(-1, -1, -1, 4, 4, 1), True),
                    solid("L", vprism(L_PLAN, 0, h))], **top)


def test_l_prism_volume_centroid_and_pieces():
    """The L (area 3, plan centroid (5/6, 5/6): see test_assembly's plane L) extruded to
    height 2: volume 6, centroid (5/6, 5/6, 1), whatever the orientation in which its
    faces are given (the reader orients them). Cut by the planes of its two reflex
    faces (x = 1 and y = 1) its hull gives four cells, three of them inside."""
    v, f = vprism(L_PLAN, 0, 2)
    rng = np.random.default_rng(3)
    flipped = [list(reversed(face)) if rng.random() < 0.5 else face for face in f]
    for faces in (f, flipped):
        s = scene3d([solid("slab", box(-1, -1, -1, 4, 4, 1), True),
                     solid("L", (v, faces))])
        blk = s.block("L")
        assert not is_convex(blk)
        vol, c = polyhedron_volume_centroid(blk)
        assert vol == pytest.approx(6.0, rel=1e-12)
        np.testing.assert_allclose(c, [5 / 6, 5 / 6, 1.0], rtol=1e-12)
        pieces = convex_pieces(blk)
        assert len(pieces) == 3
        total = sum(np.prod(p.points.max(axis=0) - p.points.min(axis=0)) for p in pieces)
        assert total == pytest.approx(6.0, rel=1e-12)


def test_l_shaped_contact_tips_about_the_hull_edge_across_the_notch():
    """An L-shaped block (plan L_PLAN, height h = 2) on a slab, infinite friction, live
    body force lambda x weight along the diagonal d = (1, 1) / sqrt 2.

    Hand derivation: the contact is the L itself (area 3, five hull corners (0, 0),
    (2, 0), (2, 1), (1, 2), (0, 2); the notch corner (1, 1) is not a contact point).
    The resultant of weight W and lambda W d meets the bed at the plan centroid
    (5/6, 5/6) shifted by lambda (h/2) along d; it must stay in the hull. Along d it
    leaves the hull through the edge x + y = 3 from (2, 1) to (1, 2), which spans the
    notch, at (3/2, 3/2): lambda (h/2) = sqrt 2 (3/2 - 5/6) = 2 sqrt 2 / 3, so
    lambda* = 4 sqrt 2 / (3 h) = 2 sqrt 2 / 3 = 0.942809 for h = 2: the block tips about
    that edge. (Were the resultant kept inside the L itself, lambda would stop at the
    notch corner (1, 1): sqrt 2 / 6 = 0.2357.) With f = 0.5 it slides first:
    lambda* = f."""
    d = [1 / math.sqrt(2), 1 / math.sqrt(2), 0.0]
    s = l_on_slab(live_body_force=d)
    con = rb.detect_contacts(s)
    assert con.n_joints == 1
    assert con.areas[0] == pytest.approx(3.0, rel=1e-12)
    pts = {tuple(np.round(p[:2], 9)) for p in con.points}
    assert pts == {(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 2.0), (0.0, 2.0)}
    res = rb.max_load_multiplier(s)
    assert res.status == "collapse"
    assert res.load_multiplier == pytest.approx(2 * math.sqrt(2) / 3, rel=1e-6)
    slide = rb.max_load_multiplier(l_on_slab(live_body_force=d, friction=0.5))
    assert slide.load_multiplier == pytest.approx(0.5, rel=1e-6)


def u_on_bar(h=1.0, **top):
    """A U-shaped block (plan U_PLAN: 3 x 3 with the notch [1, 2] x [1, 3]) of height h
    on a bar 1 <= y <= 1.5 that crosses both arms."""
    return scene3d([solid("bar", box(-1, 1, -1, 5, 0.5, 1), True),
                    solid("U", vprism(U_PLAN, 0, h))], **top)


@pytest.mark.parametrize(("direction", "expected"), [(+1, 2 / 7), (-1, 5 / 7)])
def test_two_piece_contact_tips_about_the_hull_edge_across_the_gap(direction, expected):
    """The U on the bar touches it in two pieces, [0, 1] x [1, 1.5] and [2, 3] x
    [1, 1.5] (area 1/2 each): one joint of area 1 whose hull is [0, 3] x [1, 1.5]
    (four corners). Infinite friction, live body force lambda x weight along +-y.

    Hand derivation: the U has area 9 - 2 = 7 and plan centroid x = 3/2 (over the gap
    between the pieces), y = (9 x 3/2 - 2 x 2) / 7 = 19/14, inside 1 <= y <= 3/2; its
    centroid is h/2 above the bar. Along +y the resultant leaves the hull through the
    edge y = 3/2, which spans the gap x in (1, 2): lambda (h/2) = 3/2 - 19/14 = 1/7, so
    lambda* = 2 / (7 h) = 2/7 for h = 1. Along -y, through y = 1:
    lambda (h/2) = 19/14 - 1 = 5/14, lambda* = 5/7."""
    s = u_on_bar(live_body_force=[0.0, float(direction), 0.0])
    con = rb.detect_contacts(s)
    assert con.n_joints == 1
    assert con.areas[0] == pytest.approx(1.0, rel=1e-12)
    pts = {tuple(np.round(p[:2], 9)) for p in con.points}
    assert pts == {(0.0, 1.0), (3.0, 1.0), (3.0, 1.5), (0.0, 1.5)}
    res = rb.max_load_multiplier(s)
    assert res.load_multiplier == pytest.approx(expected, rel=1e-6)
    assert rb.check(s, load_factor=0.99 * expected, state=False).admissible
    assert not rb.check(s, load_factor=1.01 * expected, state=False).admissible


def test_block_in_the_notch_touches_without_overlap():
    """A unit cube set in the L's notch touches the L on two faces (x = 1 and y = 1,
    area 1 x 1 each) and the slab: no overlap, although it lies inside the L's convex
    hull. Sunk 0.1 into the L's arm, it overlaps, and the
    error names both blocks."""
    s = scene3d([solid("slab", box(-1, -1, -1, 4, 4, 1), True),
                 solid("L", vprism(L_PLAN, 0, 2)),
                 solid("cube", box(1, 1, 0, 1, 1, 1))])
    con = rb.detect_contacts(s)
    ids = [frozenset(p) for p in con.block_pairs_ids()]
    assert frozenset({"L", "cube"}) in ids and frozenset({"slab", "cube"}) in ids
    lc = [a for p, a in zip(ids, con.areas, strict=True) if p == frozenset({"L", "cube"})]
    assert sorted(lc) == pytest.approx([1.0, 1.0])
    with pytest.raises(InputError, match=r"blocks 'L' and 'cube' overlap"):
        scene3d([solid("slab", box(-1, -1, -1, 4, 4, 1), True),
                 solid("L", vprism(L_PLAN, 0, 2)),
                 solid("cube", box(0.9, 1, 0, 1, 1, 1))])


def test_two_coplanar_feet_are_one_joint():
    """A table-like block (a slab 4 x 1 x 0.5 on two legs 1 x 1 x 1 at its ends, one
    closed surface whose two feet are separate coplanar faces) on a slab: one joint
    of area 2 whose hull is [0, 4] x [0, 1]. Live body force along +y, infinite
    friction: weight 4 x 0.5 + 2 x 1 = 4 with centroid height (2 x 1.25 + 2 x 0.5) / 4
    = 7/8 and plan y = 1/2; it tips about the hull edge y = 1 (it spans the gap between
    the feet) at lambda* = (1/2) / (7/8) = 4/7."""
    xz = [(0, 0), (1, 0), (1, 1), (3, 1), (3, 0), (4, 0), (4, 1.5), (0, 1.5)]
    n = len(xz)
    v = [[x, 0.0, z] for x, z in xz] + [[x, 1.0, z] for x, z in xz]
    faces = [list(range(n)), list(range(2 * n - 1, n - 1, -1))]
    faces += [[k, n + k, n + (k + 1) % n, (k + 1) % n] for k in range(n)]
    s = scene3d([solid("slab", box(-1, -1, -1, 6, 3, 1), True), solid("table", (v, faces))],
                live_body_force=[0, 1, 0])
    con = rb.detect_contacts(s)
    assert con.n_joints == 1
    assert con.areas[0] == pytest.approx(2.0, rel=1e-12)
    assert np.diff(con.joint_start)[0] == 4
    res = rb.max_load_multiplier(s)
    assert res.load_multiplier == pytest.approx(4 / 7, rel=1e-6)


def bad(blocks):
    return scene3d([solid("slab", box(-5, -5, -1, 10, 10, 1), True), *blocks])


def test_warped_face_is_rejected_with_its_deviation():
    """A face out of its plane by 1e-4 (the tolerance is 1e-7 x the block's size): the
    error names the block, the face and the vertex, and states the deviation: at most
    the 1e-4 lift, more than a tenth of it (the face's Newell plane through its first
    vertex tilts with the lift and takes up part of it)."""
    v, f = vprism(L_PLAN, 0, 2)
    v = [list(p) for p in v]
    v[9][2] += 1e-4  # a corner of the top face
    with pytest.raises(InputError, match=r"block 'L': face 1 is not planar: vertex 9 "
                                         r"lies \S+ off") as err:
        bad([solid("L", (v, f))])
    dev = float(str(err.value).split(" lies ")[1].split()[0])
    assert 1e-5 < dev <= 1e-4 * (1 + 1e-3)


def test_self_intersecting_faces_are_rejected():
    """A cap whose corners are listed out of order (a bow tie: its edges no longer
    match the sides', so the surface is open), and a prism over a plan whose edges
    cross (its caps are self-intersecting polygons)."""
    v, f = vprism(L_PLAN, 0, 1)
    f_bow = [list(face) for face in f]
    f_bow[0] = [5, 4, 3, 1, 2, 0]
    with pytest.raises(InputError, match=r"block 'L': the faces do not close"):
        bad([solid("L", (v, f_bow))])
    crossed = [(0, 0), (2, 0), (2, 1), (1, 1), (3, 0.5), (0, 2)]
    with pytest.raises(InputError, match=r"block 'X': face 0 is self-intersecting"):
        bad([solid("X", vprism(crossed, 0, 1))])


def test_open_or_split_surfaces_are_rejected():
    v, f = vprism(L_PLAN, 0, 1)
    with pytest.raises(InputError, match=r"block 'L'.*do not close.*edge"):
        bad([solid("L", (v, f[:-1]))])
    # two separate cubes given as one block
    a, fa = box(0, 0, 0, 1, 1, 1)
    b, fb = box(2, 0, 0, 1, 1, 1)
    faces = [list(x) for x in fa] + [[i + 8 for i in x] for x in fb]
    with pytest.raises(InputError, match=r"block 'two'.*one closed"):
        bad([solid("two", (a + b, faces))])


def test_convex_blocks_keep_their_fast_path():
    """A box is convex: one piece, the block itself."""
    s = scene3d([solid("slab", box(-1, -1, -1, 4, 4, 1), True),
                 solid("b", box(0, 0, 0, 1, 1, 1))])
    assert is_convex(s.block("b"))
    assert len(convex_pieces(s.block("b"))) == 1


@pytest.mark.parametrize("shift", [1e6, 1e7])
def test_two_piece_contact_far_from_origin(shift):
    """The U on its bar moved by 1e6 or 1e7 m along x, y and z: the same joint (area 1,
    four hull corners) and lambda* = 2/7 (translation invariance, validation.md)."""
    s = u_on_bar(live_body_force=[0.0, 1.0, 0.0])
    moved = scene3d([solid(b.id, ([[c + shift for c in p] for p in b.vertices],
                                  [list(f) for f in b.faces]), b.support)
                     for b in s.blocks], live_body_force=[0.0, 1.0, 0.0])
    con = rb.detect_contacts(moved)
    assert con.n_joints == 1 and np.diff(con.joint_start)[0] == 4
    assert con.areas[0] == pytest.approx(1.0, rel=1e-6)
    res = rb.max_load_multiplier(moved)
    assert res.load_multiplier == pytest.approx(2 / 7, rel=1e-6)


def dented_box(depth):
    """A 2 x 2 x 1 box whose top is four triangles dipping to an apex ``depth`` below
    it, at the centre: every face planar, every edge in two faces."""
    v = [[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0], [0, 0, 1], [2, 0, 1], [2, 2, 1],
         [0, 2, 1], [1, 1, 1 - depth]]
    f = [[0, 1, 2, 3], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7], [4, 5, 8],
         [5, 6, 8], [6, 7, 8], [7, 4, 8]]
    return solid("D", (v, f))


def test_surface_through_itself_is_rejected():
    """The dent 0.5 deep is a valid non-convex block (volume 4 - 4 x 0.5 / 3 = 10/3);
    1 deep, its apex touches the bottom face; 1.5 deep, its edges pass through it."""
    ok = bad([dented_box(0.5)])
    assert polyhedron_volume_centroid(ok.block("D"))[0] == pytest.approx(10 / 3, rel=1e-12)
    with pytest.raises(InputError, match=r"block 'D'.*intersects itself: vertex 8 touches"):
        bad([dented_box(1.0)])
    with pytest.raises(InputError, match=r"block 'D'.*intersects itself: edge \(\d, 8\) "
                                         r"crosses face 0"):
        bad([dented_box(1.5)])


def test_hooked_l_blocks_overlap_only_when_they_do():
    """Two L prisms, the second the first turned by 180 degrees about (3/2, 3/2): the
    first fills [0, 2]^2 less [1, 2]^2, the second [1, 3]^2 less [1, 2]^2, so their
    convex hulls overlap (in [1, 2]^2) but they do not. Moved by (-0.1, -0.1), the
    second's foot [1.9, 2.9] x [0.9, 1.9] enters the first's foot [0, 2] x [0, 1] over
    0.1 x 0.1: an overlap that names both blocks."""
    turned = [(3 - x, 3 - y) for x, y in L_PLAN]
    s = scene3d([solid("slab", box(-1, -1, -1, 5, 5, 1), True),
                 solid("L1", vprism(L_PLAN, 0, 1)), solid("L2", vprism(turned, 0, 1))])
    assert {frozenset(p) for p in rb.detect_contacts(s).block_pairs_ids()} == {
        frozenset({"slab", "L1"}), frozenset({"slab", "L2"})}
    moved = [(x - 0.1, y - 0.1) for x, y in turned]
    with pytest.raises(InputError, match=r"blocks 'L1' and 'L2' overlap"):
        scene3d([solid("slab", box(-1, -1, -1, 5, 5, 1), True),
                 solid("L1", vprism(L_PLAN, 0, 1)), solid("L2", vprism(moved, 0, 1))])


def test_cli_reports_a_warped_face_in_one_line(tmp_path, capsys):
    """Bad input on the command line: exit 2 and one line naming the file, the block,
    the face and the deviation; the valid L scene runs (exit 0)."""
    import json

    from rigidblocks.cli.main import main

    v, f = vprism(L_PLAN, 0, 2)
    doc = {"format": "rigidblocks-scene", "version": 1, "dimension": 3, "unit_weight": 1.0,
           "live_body_force": [1.0, 0.0, 0.0],
           "blocks": [solid("slab", box(-1, -1, -1, 4, 4, 1), True), solid("L", (v, f))]}
    good = tmp_path / "l.json"
    good.write_text(json.dumps(doc))
    assert main(["load", str(good), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["status"] == "collapse"
    v = [list(p) for p in v]
    v[9][2] += 1e-3
    doc["blocks"][1] = solid("L", (v, f))
    bad_file = tmp_path / "warped.json"
    bad_file.write_text(json.dumps(doc))
    assert main(["load", str(bad_file)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "warped.json" in err and "block 'L'" in err and "face 1 is not planar" in err


def well_block():
    """A 3 x 3 x 1 support with a 1 x 1 square hole through it (a closed surface of
    genus 1: its top and bottom are four trapezoids each around the hole)."""
    outer = [(0, 0), (3, 0), (3, 3), (0, 3)]
    inner = [(1, 1), (2, 1), (2, 2), (1, 2)]
    v = ([[x, y, -1.0] for x, y in outer] + [[x, y, 0.0] for x, y in outer]
         + [[x, y, -1.0] for x, y in inner] + [[x, y, 0.0] for x, y in inner])
    f = []
    for k in range(4):
        m = (k + 1) % 4
        f += [[k, m, 4 + m, 4 + k], [8 + k, 8 + m, 12 + m, 12 + k],
              [4 + k, 4 + m, 12 + m, 12 + k], [k, m, 8 + m, 8 + k]]
    return solid("well", (v, f), True)


def test_contact_with_a_hole():
    """A box 2 x 2 x 2 centred over the well's hole touches it on [0.5, 2.5]^2 less the
    hole [1, 2]^2: one joint of area 4 - 1 = 3 whose hull is the box's whole base (four
    corners). The well's volume is 9 - 1 = 8. Pushed along +x with infinite friction,
    the box tips about the hull edge x = 2.5: lambda* = (b/2) / (h/2) = 1, as on a full
    bed (the hull is the same)."""
    s = scene3d([well_block(), solid("box", box(0.5, 0.5, 0, 2, 2, 2))],
                live_body_force=[1.0, 0.0, 0.0])
    assert polyhedron_volume_centroid(s.block("well"))[0] == pytest.approx(8.0, rel=1e-12)
    assert len(convex_pieces(s.block("well"))) == 8
    con = rb.detect_contacts(s)
    assert con.n_joints == 1
    assert con.areas[0] == pytest.approx(3.0, rel=1e-12)
    pts = {tuple(np.round(p[:2], 9)) for p in con.points}
    assert pts == {(0.5, 0.5), (2.5, 0.5), (2.5, 2.5), (0.5, 2.5)}
    assert rb.max_load_multiplier(s).load_multiplier == pytest.approx(1.0, rel=1e-6)
