"""3D generators (rigidblocks.generators.solids): geometry, joint counts, closed forms.

Closed forms are derived in the generators' docstrings and restated in each test; the
lower-bound (static) and upper-bound (kinematic) theorems of limit analysis make them
exact when both sides agree (Heyman, *The Stone Skeleton*, 1995; Livesley 1978).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.spatial import ConvexHull

import rigidblocks as rb
from rigidblocks.cli.main import main
from rigidblocks.errors import InputError
from rigidblocks.generators import available, build
from rigidblocks.generators.catalogue import box_on_slab
from rigidblocks.generators.solids import (
    barrel_vault,
    box_stack,
    corbel_dome,
    dome_joint_count,
    joint_count3d,
    wall3d,
)
from rigidblocks.io.scene_file import dumps_scene, loads_json, scene_from_dict
from rigidblocks.scene.extrude import extrude
from rigidblocks.scene.polyhedra import polyhedron_volume_centroid


# -- wall3d ------------------------------------------------------------------------
@pytest.mark.parametrize("C, N", [(1, 1), (2, 1), (3, 2), (4, 3)])
def test_wall3d_joint_count(C, N):
    """Same joints as the plane running-bond wall, J = N (3C - 1) - ceil(C/2), each a
    rectangle with 4 corners: J = 1 for C = N = 1 (one block on the foundation), J = 4
    for C = 2, N = 1 (two halves over one block: 2 bed + 1 head + 1 base)."""
    s = wall3d(courses=C, blocks_per_course=N)
    c = rb.detect_contacts(s)
    assert c.n_joints == joint_count3d(C, N) == N * (3 * C - 1) - (C + 1) // 2
    assert c.n_points == 4 * c.n_joints
    assert len(s.blocks) == 1 + N * C + C // 2


@pytest.mark.parametrize("C, N, t, h, f, expected", [
    (6, 4, 0.3, 0.2, 0.6, 0.3 / 1.2),   # overturning: t / H
    (3, 2, 0.3, 0.2, 0.6, 0.5),         # overturning: t / H = 0.3 / 0.6
    (6, 4, 0.3, 0.2, 0.2, 0.2),         # sliding: f < t / H
])
def test_wall3d_out_of_plane_overturning(C, N, t, h, f, expected):
    """Free-standing wall of thickness t and height H = C h under an out-of-plane body
    force lambda W: lambda* = min(f, t / H). Kinematic: the whole wall turning about the
    foundation edge y = t does work lambda W H/2 against W t/2 (any part above a bed
    joint needs t / H_part > t / H); sliding gives lambda = f. Static: the state uniform
    along x, head joints unloaded, puts the resultant on the bed joint at height z at
    t/2 + lambda (H - z)/2 <= t and needs |T|/N = lambda <= f (wall3d docstring)."""
    s = wall3d(courses=C, blocks_per_course=N, thickness=t, block_height=h, friction=f)
    assert s.live_body_force == (0.0, 1.0, 0.0)
    res = rb.max_load_multiplier(s, state=False)
    assert res.status == "collapse"
    assert res.load_multiplier == pytest.approx(expected, rel=1e-6)


def test_wall3d_in_plane_equals_plane_wall():
    """Loaded in plane, the wall is the plane running-bond wall of depth t (symmetry
    about the mid-plane y = t/2): the same lambda* and f*."""
    kw = dict(courses=3, blocks_per_course=3, block_length=0.4, block_height=0.2)
    s3 = wall3d(**kw, thickness=0.3, load_direction="in_plane", friction=0.6)
    s2 = build("wall", **kw, depth=0.3, friction=0.6)
    l3 = rb.max_load_multiplier(s3, state=False).load_multiplier
    l2 = rb.max_load_multiplier(s2, state=False).load_multiplier
    assert l3 == pytest.approx(l2, rel=1e-5)
    f3 = rb.min_friction(s3, load_factor=0.4, state=False).friction_factor
    f2 = rb.min_friction(s2, load_factor=0.4, state=False).friction_factor
    assert f3 == pytest.approx(f2, rel=1e-5)


# -- box stack ----------------------------------------------------------------------
@pytest.mark.parametrize("n, f, expected", [(4, 0.6, 0.5), (2, 0.6, 0.6), (4, 0.3, 0.3)])
def test_box_stack_tipping_or_sliding(n, f, expected):
    """n equal centred boxes b = 1 wide, h = 0.5 high, load along x: the resultant of
    the boxes above a bed joint lies lambda x (their height)/2 from its centre, so the
    base joint governs: tipping at lambda = b / (n h); sliding at lambda = f. With
    n = 4: b/H = 0.5; n = 2: b/H = 1 > f = 0.6."""
    s = box_stack(boxes=n, width=1.0, length=1.0, height=0.5, friction=f)
    res = rb.max_load_multiplier(s, state=False)
    assert res.status == "collapse"
    assert res.load_multiplier == pytest.approx(expected, rel=1e-6)
    assert rb.detect_contacts(s).n_joints == n


def test_box_stack_diagonal_load():
    """Load at azimuth az on boxes b x a: the resultant at the base leaves the b x a
    rectangle through the nearer side: lambda* = min(b / (H cos az), a / (H sin az)).
    b = 1, a = 2, H = 4 x 0.5 = 2, az = 30 deg: 1 / (2 cos 30) = 0.57735 < 2 / (2 sin 30)
    = 2 (and < f = 0.9)."""
    s = box_stack(boxes=4, width=1.0, length=2.0, height=0.5, load_azimuth=30.0,
                  friction=0.9)
    res = rb.max_load_multiplier(s, state=False)
    assert res.load_multiplier == pytest.approx(1 / (2 * math.cos(math.radians(30))),
                                                rel=1e-6)


def test_box_stack_staircase():
    """Boxes b wide, h high, box k centred at x = k s (leaning towards +x), load +x,
    infinite friction. Above joint k (between box k-1 and box k) the boxes k..n-1 have
    their centroid at x = s (k + n - 1)/2, height (n - k) h / 2 above the joint, whose
    contact strip ends at x = (k - 1) s + b/2; the base joint (k = 0) ends at b/2.
    Tipping: lambda_0 = (b - s (n - 1)) / (n h), lambda_k = (b - s (n - k + 1)) /
    ((n - k) h); every resultant inside its strip is admissible, so lambda* = min_k.
    n = 4, b = 1, h = 0.5, s = 0.2: (0.2, 0.1333, 0.4, 1.2): lambda* = 2/15, joint 1."""
    n, b, h, s = 4, 1.0, 0.5, 0.2
    lam = [(b - s * (n - 1)) / (n * h)]
    lam += [(b - s * (n - k + 1)) / ((n - k) * h) for k in range(1, n)]
    scene = box_stack(boxes=n, width=b, height=h, offset=s, friction="infinite")
    res = rb.max_load_multiplier(scene)
    assert res.load_multiplier == pytest.approx(min(lam), rel=1e-6)
    assert min(lam) == pytest.approx(2 / 15)
    ids = rb.detect_contacts(scene).block_ids
    hinges = [tuple(sorted((ids[a], ids[b_]))) for (a, b_), md in
              zip(res.contacts.pairs, res.mechanism.modes, strict=True) if md == "hinge"]
    assert hinges == [("box0", "box1")]


def test_box_stack_offsets_string_and_errors():
    s = box_stack(boxes=2, offsets="0,0;0.1,0.2")
    cx = [polyhedron_volume_centroid(s.block(f"box{k}"))[1] for k in range(2)]
    np.testing.assert_allclose(cx[1][:2], [0.1, 0.2], atol=1e-12)
    with pytest.raises(InputError, match="box_stack: offsets must give one"):
        box_stack(boxes=3, offsets="0,0;0.1,0.2")
    with pytest.raises(InputError, match="box1 does not overlap box0"):
        box_stack(boxes=2, offset=1.5)
    with pytest.raises(InputError, match="box_stack: boxes must be an integer >= 1"):
        box_stack(boxes=0)


# -- corbel dome --------------------------------------------------------------------
@pytest.mark.parametrize("rings, k, cap", [(1, 6, False), (3, 8, True), (4, 12, False)])
def test_corbel_dome_geometry(rings, k, cap):
    """k blocks per ring, 8 corners each; J = k (rings head joint groups + 1 on the
    slab + 2 (rings - 1) between staggered rings + cap) (corbel_dome docstring)."""
    s = corbel_dome(rings=rings, blocks_per_ring=k, cap=cap)
    assert len(s.blocks) == 1 + rings * k + int(cap)
    assert all(len(b.vertices) == 8 for b in s.blocks if b.id.startswith("r"))
    c = rb.detect_contacts(s)
    assert c.n_joints == dome_joint_count(rings, k, cap) == k * (3 * rings - 1 + int(cap))


def test_corbel_dome_stands_and_obeys_upper_bounds():
    """Under self-weight the dome stands (f* finite at lambda = 0). Two kinematic upper
    bounds on lambda*: the whole dome sliding on the slab with dilatancy (lambda = f)
    and overturning as one body about the line x = R + w (the outer corner of the
    bottom ring at angle 0, the footprint's extreme point): lambda = (R + w) / z_G with
    z_G the dome's centroid height."""
    R, w, f = 2.0, 0.5, 0.6
    s = corbel_dome(rings=4, blocks_per_ring=10, radius=R, ring_thickness=w, friction=f)
    fr = rb.min_friction(s, load_factor=0.0, state=False)
    assert fr.status == "stable" and fr.friction_factor < f
    vc = [polyhedron_volume_centroid(b) for b in s.blocks if not b.support]
    zg = sum(v * c[2] for v, c in vc) / sum(v for v, _ in vc)
    res = rb.max_load_multiplier(s, state=False)
    assert res.status == "collapse"
    assert 0 < res.load_multiplier <= min(f, (R + w) / zg) * (1 + 1e-6)


def test_corbel_dome_errors():
    with pytest.raises(InputError, match="overhang must be < ring_thickness"):
        corbel_dome(overhang=0.6, ring_thickness=0.5)
    with pytest.raises(InputError, match="past the axis"):
        corbel_dome(rings=10, radius=1.0, overhang=0.2)
    with pytest.raises(InputError, match="blocks_per_ring must be an integer >= 3"):
        corbel_dome(blocks_per_ring=2)


# -- barrel vault -------------------------------------------------------------------
@pytest.mark.parametrize("rings", [1, 3])
def test_barrel_vault_stack_bond_equals_plane_arch(rings):
    """With stack bond the rings carry their own loads alone; each ring is the plane
    arch of the same voussoirs (arc_points = 1: straight intrados and extrados)
    extruded, so lambda* and f* are those of the 2D arch of depth = length."""
    kw = dict(voussoirs=9, thickness=0.15, radius=2.0, friction=0.6)
    s3 = barrel_vault(**kw, length=1.5, rings=rings, abutment_width=0.6,
                      abutment_height=1.0)
    s2 = build("arch", **kw, arc_points=1, depth=1.5, pier_width=0.6, pier_height=1.0)
    l3 = rb.max_load_multiplier(s3, state=False).load_multiplier
    l2 = rb.max_load_multiplier(s2, state=False).load_multiplier
    assert l3 == pytest.approx(l2, rel=1e-5)
    f3 = rb.min_friction(s3, load_factor=0.0, state=False).friction_factor
    f2 = rb.min_friction(s2, load_factor=0.0, state=False).friction_factor
    assert f3 == pytest.approx(f2, rel=1e-5)
    assert f"{rings} {'ring' if rings == 1 else 'rings'} x 9 voussoirs" in s3.name


def test_barrel_vault_running_bond_at_least_its_rings():
    """Running bond: the state without forces between rings is admissible in the bonded
    vault whenever each ring is admissible alone, so lambda*(vault) >= min over the two
    ring types of their own lambda* (static theorem). Between two rings, each voussoir
    overlaps two of the staggered ring: 2n joints per interface."""
    n = 9
    s = barrel_vault(voussoirs=n, rings=3, bond="running", length=1.5)
    c = rb.detect_contacts(s)
    assert c.n_joints == 2 * (n + 1) + (n + 2) + 2 * 2 * n
    lam = rb.max_load_multiplier(s, state=False).load_multiplier
    own = []
    for g in (0, 1):
        keep = tuple(b for b in s.blocks if b.support or b.id.startswith(f"g{g}v"))
        own.append(rb.max_load_multiplier(s.with_changes(blocks=keep),
                                          state=False).load_multiplier)
    assert len([b for b in s.blocks if b.id.startswith("g1v")]) == n + 1
    assert lam >= min(own) * (1 - 1e-6)


def test_barrel_vault_errors():
    with pytest.raises(InputError, match="barrel_vault: bond must be one of stack, running"):
        barrel_vault(bond="flemish")
    with pytest.raises(InputError, match="half_angle must be <= 90"):
        barrel_vault(half_angle=100)
    with pytest.raises(InputError, match="thickness ratio"):
        barrel_vault(thickness=2.5)


# -- registry and command line ------------------------------------------------------
@pytest.mark.parametrize("name", ["wall3d", "box_stack", "corbel_dome", "barrel_vault"])
def test_registered_and_round_trips(name):
    s = build(name)
    assert s.dimension == 3 and s.has_live_load
    assert scene_from_dict(loads_json(dumps_scene(s))) == s


def test_cli_builds_3d_example(tmp_path, capsys):
    out = tmp_path / "stack.json"
    assert main(["example", "box_stack", "--boxes", "3", "--offsets", "0,0;0.1,0;0.2,0",
                 "-o", str(out)]) == 0
    assert rb.read_scene(out).dimension == 3
    assert main(["example", "wall3d", "--load_direction", "sideways", "-o",
                 str(tmp_path / "w.json")]) == 2
    assert "load_direction must be one of" in capsys.readouterr().err


# -- the distortion method is 2D only -----------------------------------------------
def test_distortion_method_refuses_3d_scenes(tmp_path, capsys):
    """The impressed-distortion solver has one shear link per 2D joint: 3D scenes get a
    one-line InputError (CLI exit 2), raised before any work."""
    s = box_stack(boxes=2)
    for run in (lambda: rb.check(s, method="distortion"),
                lambda: rb.min_friction(s, method="distortion"),
                lambda: rb.max_load_multiplier(s, method="distortion")):
        with pytest.raises(InputError, match="not supported for 3D scenes; use the "
                                             'convex path \\(method "clarabel"'):
            run()
    path = tmp_path / "stack.json"
    rb.write_scene(s, path)
    capsys.readouterr()
    for cmd in ("check", "friction", "load"):
        assert main([cmd, str(path), "--method", "distortion", "--json"]) == 2
        err = capsys.readouterr().err.strip()
        assert "not supported for 3D scenes" in err and "Traceback" not in err
        assert len(err.splitlines()) == 1
    # `path` has no convex path to turn to: it names the command that answers in 3D
    assert main(["path", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "2D only" in err and "`rigidblocks load`" in err and "clarabel" not in err
    assert len(err.splitlines()) == 1


@pytest.mark.parametrize("fname, gen, params", [
    ("box_stack_3d.json", "box_stack", {"boxes": 4, "offset": 0.15, "load_azimuth": 30.0}),
    ("corbel_dome.json", "corbel_dome", {"rings": 4, "blocks_per_ring": 10}),
])
def test_bundled_3d_examples_are_the_generators_output(fname, gen, params):
    from conftest import EXAMPLES

    scene = rb.read_scene(EXAMPLES / fname)
    assert scene.dimension == 3
    assert dumps_scene(build(gen, **params)) == (EXAMPLES / fname).read_text()


# -- face orientation of the written files --------------------------------------------
def _written_3d_scenes() -> list[tuple[str, str]]:
    """(name, scene file text) of every 3D generator at small sizes and of `extrude` of
    every 2D one: the files as written, before any reader orients them."""
    small = {"wall3d": {"courses": 2, "blocks_per_course": 2},
             "keyed_wall": {"courses": 3, "blocks_per_course": 2},
             "corbel_dome": {"rings": 2, "blocks_per_ring": 6},
             "barrel_vault": {"voussoirs": 5, "rings": 2, "bond": "running"},
             "wall": {"courses": 2, "blocks_per_course": 2}}
    out = []
    for name in sorted(available()):
        scene = build(name, **small.get(name, {}))
        if scene.dimension == 2:
            out.append((f"extrude({name})", dumps_scene(extrude(scene))))
        else:
            out.append((name, dumps_scene(scene)))
    out.append(("box_on_slab tilted", dumps_scene(box_on_slab(tilt=0.3, azimuth=1.0))))
    return out


_WRITTEN = _written_3d_scenes()


@pytest.mark.parametrize("name, text", _WRITTEN, ids=[n for n, _ in _WRITTEN])
def test_written_faces_are_counter_clockwise_seen_from_outside(name, text):
    """Each face of each block of the file, read with json alone, turns
    counter-clockwise seen from outside: every edge is run once each way (one
    orientation for the whole surface) and the signed volume sum (a . (b x c)) / 6 over
    the faces' fan triangles is positive, equal to the volume of the convex hull where
    the block is convex; there, each face's Newell normal points away from the block's
    centroid too."""
    blocks = json.loads(text)["blocks"]
    assert blocks and all("faces" in b for b in blocks)
    convex = 0
    for b in blocks:
        v = np.asarray(b["vertices"], dtype=float)
        v = v - v.mean(axis=0)  # the vertex mean: inside a convex block
        faces = b["faces"]
        edges = [(f[i], f[(i + 1) % len(f)]) for f in faces for i in range(len(f))]
        assert len(set(edges)) == len(edges) and set(edges) == {(j, i) for i, j in edges}
        vol = sum(v[f[0]] @ np.cross(v[f[i]], v[f[i + 1]])
                  for f in faces for i in range(1, len(f) - 1)) / 6.0
        assert vol > 0, (name, b["id"], vol)
        hull = ConvexHull(v).volume
        convex += abs(hull - vol) <= 1e-9 * hull
        if abs(hull - vol) <= 1e-9 * hull:
            for f in faces:
                p = v[f]
                normal = np.cross(p - np.roll(p, -1, axis=0), p + np.roll(p, -1, axis=0)
                                  ).sum(axis=0)  # Newell: twice the area vector
                assert normal @ p.mean(axis=0) > 0, (name, b["id"], f)
    # the keyed wall's units all carry a tongue or a groove: its foundation alone is
    # convex; so are the 3D generators' other blocks
    if name == "keyed_wall":
        assert convex == 1
    elif not name.startswith("extrude"):
        assert convex == len(blocks)


@pytest.mark.parametrize("azimuth, direction", [(90, (0.0, 1.0, 0.0)), (180, (-1.0, 0.0, 0.0)),
                                                (270, (0.0, -1.0, 0.0))])
def test_a_box_stacks_load_direction_has_no_rounding_noise(azimuth, direction):
    """box_stack at load_azimuth 90 wrote (6.12323399574e-17, 1, 0) into the scene and
    the answer read "weight x (6.12323e-17, 1, 0)"."""
    from rigidblocks.generators.solids import box_stack

    assert box_stack(load_azimuth=azimuth).live_body_force == direction
