"""Invariance of f* and lambda* under rigid motions, mirroring, units and joint splitting.

validation.md ("cross-checks that need no reference value"): the statics of rigid
blocks does not depend on where the structure stands, on the units, or on how a
straight joint is cut into collinear pieces.

Rotation: self-weight always acts along -y (scene-format.md), so a rotated scene with
self-weight is a different physical problem (gravity would have to rotate with it).
The rotation tests therefore use scenes whose every force is a point load (dead weight
given as a point load at the centroid) and rotate the geometry, the points of
application and the force vectors together: that is a rigid motion of the whole
statical system and must leave f* and lambda* unchanged. Translation and mirroring
(x -> -x) leave gravity unchanged and are applied to scenes with self-weight.
"""

from __future__ import annotations

import copy
import math

import pytest
from conftest import rect

from rigidblocks.analyses import max_load_multiplier, min_friction
from rigidblocks.io.scene_file import scene_from_dict

RTOL = 1e-6


def doc(blocks, **top):
    d = {"format": "rigidblocks-scene", "version": 1, "dimension": 2, "blocks": blocks}
    d.update(top)
    return d


def seed_doc(unit_weight: float = 0.0):
    """The seed's four-block model (see test_catalogue.seed_model): f* = 0.5 without
    self-weight, 50 / (100 + 2 gamma) with unit weight gamma."""
    return doc([
        {"id": "S", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "C1", "vertices": rect(0, 0, 1, 1)},
        {"id": "C2", "vertices": rect(1, 0, 1, 1)},
        {"id": "T", "vertices": rect(0, 1, 2, 0.5)},
    ], unit_weight=unit_weight, loads=[
        {"block": "T", "force": [0, -100], "point": [1.0, 1.25]},
        {"block": "C1", "force": [-50, 0], "point": [0.5, 0.5]},
        {"block": "C2", "force": [50, 0], "point": [1.5, 0.5]},
    ])


def block_doc(b=1.0, h=2.0, f=0.3, split: float | None = None):
    """b x h block, unit weight 1, live horizontal body force: lambda* = min(f, b/h).
    ``split`` cuts the support under the block at x = split into two support blocks
    whose top edges are collinear."""
    if split is None:
        sup = [{"id": "base", "vertices": rect(-2, -1, 4 + b, 1), "support": True}]
    else:
        sup = [{"id": "base", "vertices": rect(-2, -1, 2 + split, 1), "support": True},
               {"id": "base2", "vertices": rect(split, -1, 2 + b - split, 1),
                "support": True}]
    return doc([*sup, {"id": "B", "vertices": rect(0, 0, b, h)}], unit_weight=1.0,
               friction=f, live_body_force=[1, 0])


def point_block_doc(b=1.0, h=2.0, f=0.3):
    """As block_doc without self-weight: dead (0, -1) and live (1, 0) point loads at the
    centroid, so lambda* = min(f, b/h) again."""
    c = [b / 2, h / 2]
    return doc([{"id": "base", "vertices": rect(-2, -1, 4 + b, 1), "support": True},
                {"id": "B", "vertices": rect(0, 0, b, h)}], friction=f,
               loads=[{"block": "B", "force": [0, -1], "point": c},
                      {"block": "B", "force": [1, 0], "point": c, "live": True}])


def leaning_doc():
    """Two leaning blocks at a crown (see test_catalogue.leaning_pair): f* = 1/15."""
    L = [[0, 0], [1, 0], [2, 1.5], [2, 2]]
    return doc([{"id": "G", "vertices": rect(-1, -1, 6, 1), "support": True},
                {"id": "L", "vertices": L},
                {"id": "R", "vertices": [[4 - x, y] for x, y in L]}], unit_weight=1.0)


def transform(d, point, vector, moment_sign=1.0, force_scale=1.0):
    """Map every vertex and load point by ``point``, every force by ``vector``."""
    d = copy.deepcopy(d)
    for b in d["blocks"]:
        b["vertices"] = [list(point(v)) for v in b["vertices"]]
    for ld in d.get("loads", []):
        if "point" in ld:
            ld["point"] = list(point(ld["point"]))
        ld["force"] = [force_scale * c for c in vector(ld["force"])]
        if "moment" in ld:
            ld["moment"] *= moment_sign
    if "live_body_force" in d:
        d["live_body_force"] = list(vector(d["live_body_force"]))
    return d


def translated(d, dx=123.4, dy=-56.7):
    return transform(d, lambda p: (p[0] + dx, p[1] + dy), lambda v: v)


def rotated(d, theta):
    c, s = math.cos(theta), math.sin(theta)
    rot = lambda v: (c * v[0] - s * v[1], s * v[0] + c * v[1])  # noqa: E731
    return transform(d, rot, rot)


def mirrored(d):
    flip = lambda v: (-v[0], v[1])  # noqa: E731
    return transform(d, flip, flip, moment_sign=-1.0)


def in_mm_and_N(d):
    """m, kN -> mm, N: lengths x 1000, forces x 1000, moments x 1e6, unit weight
    (kN/m^3 -> N/mm^3) x 1e-6, depth (a length) x 1000."""
    out = transform(d, lambda p: (1000.0 * p[0], 1000.0 * p[1]), lambda v: v,
                    moment_sign=1e6, force_scale=1000.0)
    out["units"] = {"length": "mm", "force": "N"}
    out["unit_weight"] = d.get("unit_weight", 0.0) * 1e-6
    out["depth"] = d.get("depth", 1.0) * 1000.0
    return out


def fstar(d) -> float:
    r = min_friction(scene_from_dict(d), state=False, rtol=RTOL / 10)
    assert r.status == "stable"
    return r.friction_factor


def lamstar(d) -> float:
    r = max_load_multiplier(scene_from_dict(d), state=False)
    assert r.status == "collapse"
    return r.load_multiplier


def close(a, b, rtol=RTOL):
    return abs(a - b) <= rtol * abs(b)


FRICTION_CASES = [(seed_doc(), 0.5), (seed_doc(50.0), 0.25), (leaning_doc(), 1.0 / 15.0)]
LOAD_CASES = [(block_doc(f=0.3), 0.3), (block_doc(f=0.8), 0.5)]


@pytest.mark.parametrize("d,expect", FRICTION_CASES)
def test_translation_min_friction(d, expect):
    """Moving the scene by (123.4, -56.7) changes no force: f* as in the catalogue."""
    assert close(fstar(translated(d)), expect)


@pytest.mark.parametrize("d,expect", LOAD_CASES)
def test_translation_load(d, expect):
    """Translation: lambda* = min(f, b/h) still."""
    assert close(lamstar(translated(d)), expect)


@pytest.mark.parametrize("deg", [30.0, 90.0, 157.0])
def test_rotation_point_loads(deg):
    """Rotating geometry and every (point) force together: seed f* = 0.5, block
    lambda* = min(f, b/h) (no self-weight, see the module docstring)."""
    t = math.radians(deg)
    assert close(fstar(rotated(seed_doc(), t)), 0.5)
    assert close(lamstar(rotated(point_block_doc(f=0.3), t)), 0.3)
    assert close(lamstar(rotated(point_block_doc(f=0.8), t)), 0.5)


@pytest.mark.parametrize("d,expect", FRICTION_CASES)
def test_mirror_min_friction(d, expect):
    """x -> -x with the loads mirrored (gravity is unchanged by the mirror)."""
    assert close(fstar(mirrored(d)), expect)


@pytest.mark.parametrize("d,expect", LOAD_CASES)
def test_mirror_load(d, expect):
    """Mirrored block, body force towards -x: lambda* = min(f, b/h)."""
    assert close(lamstar(mirrored(d)), expect)


@pytest.mark.parametrize("d,expect", FRICTION_CASES)
def test_units_min_friction(d, expect):
    """The same scene in mm and N (validation.md, units cross-check)."""
    assert close(fstar(in_mm_and_N(d)), expect)


@pytest.mark.parametrize("d,expect", LOAD_CASES)
def test_units_load(d, expect):
    """lambda* is dimensionless: the same in m, kN and mm, N."""
    assert close(lamstar(in_mm_and_N(d)), expect)


@pytest.mark.parametrize("split", [0.25, 0.5, 0.9])
@pytest.mark.parametrize("f", [0.3, 0.8])
def test_split_joint(split, f):
    """The bed joint cut into two collinear pieces (two support blocks meeting under the
    block): the union of the pieces is the same joint, lambda* = min(f, b/h)."""
    s = scene_from_dict(block_doc(f=f, split=split))
    r = max_load_multiplier(s, state=False)
    ib = s.index["B"]
    assert int((r.contacts.pairs == ib).any(axis=1).sum()) == 2  # B sits on both pieces
    assert close(r.load_multiplier, min(f, 0.5))


def test_split_joint_seed():
    """The seed model with its support cut under C1 (x = 0.5) and at the C1-C2 line
    (x = 1): f* stays 0.25 with unit weight 50."""
    d = seed_doc(50.0)
    d["blocks"][0] = {"id": "S", "vertices": rect(-1, -1, 1.5, 1), "support": True}
    d["blocks"].insert(1, {"id": "S2", "vertices": rect(0.5, -1, 0.5, 1), "support": True})
    d["blocks"].insert(2, {"id": "S3", "vertices": rect(1, -1, 2, 1), "support": True})
    assert close(fstar(d), 0.25)
