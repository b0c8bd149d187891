"""Small samples of the peer tool compas_cra (0.8.0) that benchmarks/bench_peer.py
compares against (``--only nonassoc``), written here as scenes of our own so that the
tests need neither the peer nor COMPAS: "16 H" and "16 A" (its samples H.json and
A.json: one block between two fixed blocks) and "05 wedge type-c" (type-c.json, rotated
90 degrees about y as in its example).

The 2D samples are prisms of depth 1 along y of the polygons in (x, z) below, unit
weight 1, friction 0.84 as in the peer's examples.
"""

from __future__ import annotations

import math

import pytest

import rigidblocks as rb
from rigidblocks.generators.solids import make_scene3d, prism, solid

NA = "non-associative"
S3 = math.sqrt(3.0)


def extruded(name, polygons, supports):
    """A 3D scene of prisms y in [0, 1] of the (x, z) polygons (dict id -> polygon)."""
    blocks = []
    for bid, poly in polygons.items():
        bottom = [(x, 0.0, z) for x, z in poly]
        top = [(x, 1.0, z) for x, z in poly]
        blocks.append(solid(bid, prism(bottom, top), support=bid in supports))
    return make_scene3d(name, blocks, unit_weight=1.0, friction=0.84, live_body_force=None)


def sample_h():
    """compas_cra's H.json: a 1.8 x 0.8 block between two fixed posts, touching both
    along vertical faces."""
    return extruded("H", {
        "left": [(-1.1, -1.0), (-0.9, -1.0), (-0.9, 1.4), (-1.1, 1.4)],
        "B": [(-0.9, -0.2), (0.9, -0.2), (0.9, 0.6), (-0.9, 0.6)],
        "right": [(0.9, -1.0), (1.1, -1.0), (1.1, 1.4), (0.9, 1.4)]}, {"left", "right"})


def sample_a():
    """compas_cra's A.json: a trapezoid wider at its base (faces at 60 degrees from the
    horizontal) hung between two fixed slanted posts that overhang it."""
    def post(sign):
        # a 0.2 thick parallelogram whose inner face lies on the block's side face
        lo, hi = (-1.05, 1.4614737)
        on = [(sign * (2 / S3 + (-0.2 - z) / S3), z) for z in (lo, hi)]
        n = (sign * S3 / 2, 0.5)
        out = [(x + 0.2 * n[0], z + 0.2 * n[1]) for x, z in on]
        return [on[0], on[1], out[1], out[0]][::sign]
    return extruded("A", {
        "left": post(-1),
        "B": [(-2 / S3, -0.2), (2 / S3, -0.2), (0.4 * S3, 0.6), (-0.4 * S3, 0.6)],
        "right": post(1)}, {"left", "right"})


def sample_wedge_c():
    """compas_cra's type-c.json rotated 90 degrees about y: a wedge whose tip points
    into a V notch between two fixed blocks, faces at 60 degrees from the horizontal."""
    a = 0.5 + 1 / S3
    r = 2.338119784648299
    return extruded("wedge type-c", {
        "upper": [(0.0, 0.0), (0.5, 0.0), (a, 1.0), (a, 2.0), (0.0, 2.0)],
        "B": [(0.5, 0.0), (a, -1.0), (r, -1.0), (r, 1.0), (a, 1.0)],
        "lower": [(0.0, -2.0), (a, -2.0), (a, -1.0), (0.5, 0.0), (0.0, 0.0)]},
        {"upper", "lower"})


def test_h_static_infimum_and_no_nonassociative_friction():
    """16 H. Static: the block hangs on two vertical joints by friction alone, T = W/2
    on each; with a pinch N (a normal force no load causes) f N >= W/2 holds for any
    f > 0, so f* = 0 is an infimum approached with ever larger forces. Non-associative:
    the loads cause no normal force on vertical joints (X0 and every state after it have
    N = 0 there: no horizontal load), so f N = 0 whatever f and no friction makes it
    stand: "unstable", never a friction (the search found 6283 before, on normal forces
    of 2e-5 W the state problems leave at the bound N = 0)."""
    sc = sample_h()
    st = rb.min_friction(sc, load_factor=0.0, state=False)
    # bracketed in [0, ~1e-7] where the forces go beyond what the solver resolves: no
    # number at a relative accuracy, the bracket says it needs no friction
    assert st.bracket[0] == 0.0 and st.bracket[1] < 1e-5
    assert any("infimum" in n for n in st.notes)
    na = rb.min_friction(sc, load_factor=0.0, state=False, flow=NA)
    assert na.status == "unstable" and na.friction_factor is None
    assert any("does not depend on f" in n and "pinch" in n for n in na.notes)
    # at a large friction the state stands only on round-off: not admissible
    big = rb.check(sc, friction=8388.0, load_factor=0.0, state=False, flow=NA)
    assert big.status != "admissible"
    assert any("below the solver's resolution" in n for n in big.notes)


def test_a_inverted_wedge_falls_without_dilatancy():
    """16 A. Static (hand derivation): on each face, normal N pushing the block down
    (0.5 N) and friction T <= f N holding it up (cos 30 T): 2 (cos 30 T - 0.5 N) = W
    needs N (f cos 30 - 0.5) >= W/2, so f* = tan 30 deg, an infimum (N grows without
    bound as f -> f*). Non-associative: the least-energy state would need tension on both
    faces; with none, N = 0 there and the capped laws carry nothing whatever f (a drop
    of the block opens both joints): "unstable", with the same breach at every f."""
    sc = sample_a()
    st = rb.min_friction(sc, load_factor=0.0, state=False, rtol=1e-5)
    assert st.status == "stable"
    assert st.friction_factor == pytest.approx(math.tan(math.radians(30)), rel=1e-5)
    na = rb.min_friction(sc, load_factor=0.0, state=False, flow=NA)
    assert na.status == "unstable"
    assert any("does not depend on f" in n for n in na.notes)
    assert rb.check(sc, friction=100.0, load_factor=0.0, flow=NA).status == "inadmissible"


def test_wedge_c_topples_without_dilatancy():
    """05 wedge type-c. Static: the contact forces of both faces push the wedge out of
    the notch (0.866 N each); friction along the faces holds it in (0.5 T), so
    f* = tan 60 deg (both faces at their limit). Non-associative: the weight acts
    outside the lower face, so the wedge is held by friction at its tip on the upper
    face; the rotation about the lower face's outer edge opens that contact (opening
    0.577 per unit of slip), and without dilatancy the opening contact carries nothing:
    the least-energy state has N = 0 on the upper face at every f, "unstable"."""
    sc = sample_wedge_c()
    st = rb.min_friction(sc, load_factor=0.0, state=False, rtol=1e-5)
    assert st.status == "stable"
    assert st.friction_factor == pytest.approx(S3, rel=1e-5)
    na = rb.min_friction(sc, load_factor=0.0, state=False, flow=NA)
    assert na.status == "unstable"
    assert any("does not depend on f" in n for n in na.notes)
