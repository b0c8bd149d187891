"""3D contact detection: one planar contact polygon per pair of touching convex blocks,
the contact tolerance, and a non-convex support against its convex pieces.

Closed forms:
- Two convex bodies with disjoint interiors are separated by a plane H (separating
  hyperplane theorem), so their intersection lies in H and equals (A n H) n (B n H), an
  intersection of two convex polygons: one convex contact polygon per block pair.
- A unit square and the same square turned by 45 degrees about its centre overlap in a
  regular octagon of area 2 (sqrt 2 - 1) (the square minus four corner triangles of legs
  1 - 1/sqrt 2).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidblocks import check
from rigidblocks.contacts import detect_contacts
from rigidblocks.errors import InputError
from rigidblocks.scene.model import Scene, make_block
from rigidblocks.scene.validate import validate_scene

BOX_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6),
             (3, 0, 4, 7)]


def box(x0, x1, y0, y1, z0, z1):
    """Corners and faces of an axis-aligned box."""
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    return v, BOX_FACES


def prism(base_xy, z0, z1):
    """A vertical prism over a convex or non-convex polygon (counter-clockwise)."""
    n = len(base_xy)
    v = [(x, y, z0) for x, y in base_xy] + [(x, y, z1) for x, y in base_xy]
    faces = [tuple(range(n - 1, -1, -1)), tuple(range(n, 2 * n))]
    faces += [(k, (k + 1) % n, n + (k + 1) % n, n + k) for k in range(n)]
    return v, faces


def scene3d(*blocks) -> Scene:
    """Blocks given as (id, (vertices, faces), support); validated like a scene file."""
    bl = tuple(make_block(i, v, faces=f, support=s) for i, (v, f), s in blocks)
    scene = Scene(dimension=3, blocks=bl, friction=0.6, unit_weight=1.0)
    validate_scene(scene)
    return scene


def rotate(scene: Scene, R: np.ndarray) -> Scene:
    bl = tuple(make_block(b.id, [tuple(R @ p) for p in b.points], faces=b.faces,
                          support=b.support) for b in scene.blocks)
    return scene.with_changes(blocks=bl)


def test_turned_cube_touches_in_one_octagon():
    """A unit cube turned by 45 degrees on a unit cube: one joint, a regular octagon of
    area 2 (sqrt 2 - 1) with 8 corners (convex blocks: one contact polygon)."""
    c, s = math.cos(math.pi / 4), math.sin(math.pi / 4)
    sq = [(0.5 + c * x - s * y, 0.5 + s * x + c * y)
          for x, y in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]]
    scene = scene3d(("base", box(0, 1, 0, 1, -1, 0), True), ("top", prism(sq, 0, 1), False))
    con = detect_contacts(scene)
    assert con.n_joints == 1
    assert con.areas[0] == pytest.approx(2 * (math.sqrt(2) - 1), rel=1e-12)
    assert np.diff(con.joint_start)[0] == 8
    assert np.allclose(np.abs(con.normals[0]), [0, 0, 1])
    assert np.allclose(con.points[:, 2], 0.0)


def test_face_split_into_coplanar_triangles_keeps_the_area():
    """A base whose top face is cut into two coplanar triangles (still a convex
    polyhedron): the unit block above touches both, joints of area 1/2 each, total 1;
    the statics do not change (the stack stands under self-weight)."""
    v, _ = box(0, 1, 0, 1, -1, 0)
    faces = [f for f in BOX_FACES if f != (4, 5, 6, 7)] + [(4, 5, 6), (4, 6, 7)]
    scene = scene3d(("base", (v, faces), True), ("top", box(0, 1, 0, 1, 0, 1), False))
    con = detect_contacts(scene)
    assert con.n_joints == 2
    assert np.allclose(con.areas, [0.5, 0.5], rtol=1e-12)
    assert check(scene, state=False).admissible


@pytest.mark.parametrize("turned", [False, True])
def test_gap_needs_the_contact_tolerance(turned):
    """Two unit cubes 1e-6 apart in a scene of size sqrt 6 (the bounding-box diagonal):
    the default tolerance 1e-7 x sqrt 6 = 2.4e-7 sees no contact (the top cube has no
    joint: the scene is refused, naming it); contact_tol = 1e-5 (2.4e-5) sees a joint of
    area 1 and the stack stands. Turned by an arbitrary rotation, the same (the plane
    offsets are compared along any normal)."""
    g = 1e-6
    scene = scene3d(("base", box(0, 1, 0, 1, -1, 0), True),
                    ("top", box(0, 1, 0, 1, g, 1 + g), False))
    if turned:
        a, b = 0.3, 1.1
        Rz = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0],
                       [0, 0, 1]])
        Rx = np.array([[1, 0, 0], [0, math.cos(b), -math.sin(b)],
                       [0, math.sin(b), math.cos(b)]])
        scene = rotate(scene, Rz @ Rx)
    assert detect_contacts(scene).n_joints == 0
    loose = detect_contacts(scene, tol=1e-5)
    assert loose.n_joints == 1
    assert loose.areas[0] == pytest.approx(1.0, rel=1e-9)
    if not turned:
        with pytest.raises(InputError, match="block 'top' touches no other block.*raise "
                           "the contact tolerance"):
            check(scene, state=False)
        assert check(scene, state=False, contact_tol=1e-5).admissible


def test_contact_tol_must_be_positive():
    scene = scene3d(("base", box(0, 1, 0, 1, -1, 0), True),
                    ("top", box(0, 1, 0, 1, 0, 1), False))
    with pytest.raises(InputError, match="contact_tol"):
        check(scene, contact_tol=0.0)


def test_non_convex_support_touches_like_its_convex_pieces():
    """A U-shaped support (a shelf's frame, a non-convex block) and the same frame cut
    into three convex boxes: the block standing in the slot touches the slot's floor
    and both its walls over 1 x 1 each, either way (the faces of the U, oriented by
    walking its surface, are the boxes' faces in the same planes)."""
    u = [(0, 0), (3, 0), (3, 2), (2, 2), (2, 1), (1, 1), (1, 2), (0, 2)]
    v = [(x, 0.0, z) for x, z in u] + [(x, 1.0, z) for x, z in u]
    n = len(u)
    faces = [tuple(range(n)), tuple(range(2 * n - 1, n - 1, -1))]
    faces += [(k, n + k, n + (k + 1) % n, (k + 1) % n) for k in range(n)]
    whole = scene3d(("shelf", (v, faces), True), ("item", box(1, 2, 0, 1, 1, 2), False))
    cut = scene3d(("bottom", box(0, 3, 0, 1, 0, 1), True),
                  ("left", box(0, 1, 0, 1, 1, 2), True),
                  ("right", box(2, 3, 0, 1, 1, 2), True),
                  ("item", box(1, 2, 0, 1, 1, 2), False))
    for scene, expected in ((cut, {frozenset({"item", "bottom"}): 1.0,
                                   frozenset({"item", "left"}): 1.0,
                                   frozenset({"item", "right"}): 1.0}),
                            (whole, {(0.0, 0.0, 1.0): 1.0, (1.0, 0.0, 0.0): 1.0,
                                     (-1.0, 0.0, 0.0): 1.0})):
        con = detect_contacts(scene)
        item = scene.index["item"]
        if scene is cut:
            got = {frozenset(scene.blocks[k].id for k in p): a
                   for p, a in zip(con.pairs, con.areas, strict=True) if item in p}
        else:  # one block pair, three planes: keyed by the normal from shelf to item
            got = {tuple(np.round(nv + 0.0, 9)): a
                   for nv, a in zip(con.normals, con.areas, strict=True)}
        assert got == pytest.approx(expected)


def test_a_block_smaller_than_the_contact_tolerance_is_named():
    """Contacts are judged at 1e-7 x the scene's size (here 2.5e-6): a block 1e-7 across
    cannot have a joint of its own, and the error names it and its size."""
    scene = scene3d(("base", box(0, 10, 0, 10, -1, 0), True),
                    ("big", box(0, 10, 0, 10, 0, 10), False),
                    ("dust", box(20, 20 + 1e-7, 0, 1e-7, 0, 1e-7), False))
    with pytest.raises(InputError, match=r"block 'dust'.*\(1e-07 across\) is smaller than "
                       r"the contact tolerance 2\.49e-06"):
        detect_contacts(scene)
