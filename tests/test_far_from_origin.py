"""Scenes far from the origin: the same joints and answers as at the origin.

validation.md, "Geometry: translating the scene ... leave[s] every answer unchanged",
with the closed form "block on a support whose top face slopes at theta: f* =
tan(theta) when it does not tip" (3D: whatever the downhill azimuth, for the Coulomb
cone). A box 1 x 1 x 0.5 on a 25 degree slope has b/h = 2 > tan 25 = 0.466, so it does
not tip and f* = tan 25 deg.

The coplanarity of two faces was judged on plane offsets n . p taken from the scene's
origin: far from it, the offsets are large numbers whose sum cancels, and the round-off
of n (about 1e-16 |p| / size) times |p| exceeds the contact tolerance (1e-7 x the scene
size) from |p| ~ 1e5 on, so joints were lost. Offsets are now taken from each block's
own origin. The inputs themselves carry a round-off of 2e-9 m at 1e7 m, well inside the
tolerance (5e-7 m here), so 1e7 must hold too.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import rigidblocks as rb
from rigidblocks.generators.solids import box
from rigidblocks.io.scene_file import scene_from_dict

THETA = math.radians(25.0)


def incline3d(azimuth_deg: float, shift: float):
    """Slab 4 x 4 x 1 with its top on the slope, box 1 x 1 x 0.5 on it, turned to the
    azimuth and moved by ``shift`` along x, y and z."""
    c, s = math.cos(THETA), math.sin(THETA)
    tilt = np.array([[c, 0, -s], [0, 1, 0], [s, 0, c]])
    a = math.radians(azimuth_deg)
    turn = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0],
                     [0, 0, 1]])
    R = turn @ tilt

    def place(v):
        return (np.asarray(v, dtype=float) @ R.T + shift).tolist()

    sv, sf = box(-2, -2, -1, 4, 4, 1)
    bv, bf = box(-0.5, -0.5, 0, 1, 1, 0.5)
    return scene_from_dict({
        "format": "rigidblocks-scene", "version": 1, "dimension": 3, "unit_weight": 20.0,
        "blocks": [{"id": "slope", "vertices": place(sv), "faces": sf, "support": True},
                   {"id": "box", "vertices": place(bv), "faces": bf}]})


@pytest.mark.parametrize("shift", [0.0, 1e5, 1e6, 1e7])
@pytest.mark.parametrize("azimuth", [0.0, 17.0, 45.0, 90.0, 133.0, 200.0, 290.0])
def test_box_on_slope_far_from_origin(shift, azimuth):
    scene = incline3d(azimuth, shift)
    con = rb.detect_contacts(scene)
    assert con.n_joints == 1
    assert con.areas[0] == pytest.approx(1.0, rel=1e-6)
    res = rb.min_friction(scene, state=False)
    assert res.status == "stable"
    assert res.friction_factor == pytest.approx(math.tan(THETA), rel=1e-6)


@pytest.mark.parametrize("shift", [0.0, 1e5, 1e6, 1e7])
def test_2d_block_on_slope_far_from_origin(shift):
    """The same in 2D (its collinearity test already works relative to an edge's end)."""
    c, s = math.cos(THETA), math.sin(THETA)

    def place(pts):
        return [[c * x - s * y + shift, s * x + c * y + shift] for x, y in pts]

    scene = scene_from_dict({
        "format": "rigidblocks-scene", "version": 1, "dimension": 2, "unit_weight": 20.0,
        "blocks": [
            {"id": "slope", "vertices": place([[-2, -1], [2, -1], [2, 0], [-2, 0]]),
             "support": True},
            {"id": "block", "vertices": place([[-0.5, 0], [0.5, 0], [0.5, 0.5],
                                               [-0.5, 0.5]])}]})
    assert rb.detect_contacts(scene).n_joints == 1
    res = rb.min_friction(scene, state=False)
    assert res.friction_factor == pytest.approx(math.tan(THETA), rel=1e-6)
