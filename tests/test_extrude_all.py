"""Every 2D example and every 2D generator, extruded to 3D, gives the 2D f* and lambda*.

An extruded scene (rigidblocks.scene.extrude) is the plane problem spread over the
depth: averaging any admissible 3D state with its mirror image about the mid-plane
gives a plane admissible state, and a plane state spread evenly over the depth is
admissible in 3D (the Coulomb cone contains the in-plane segment |T| <= f N), so the
static theorem gives the same f* and lambda* (issue #5; docs/validation.md).

3D blocks are convex. A non-convex 2D block (a voussoir with curved intrados and
extrados) is cut into convex pieces glued together: joints with infinite friction and a
tensile strength 1e4 x unit weight x scene size (as a stress), far above any stress the
loads can cause, so the pieces act as one rigid block.
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import replace

import numpy as np
import pytest
import shapely
from conftest import EXAMPLES

import rigidblocks as rb
from rigidblocks.generators import available, build
from rigidblocks.io.scene_file import read_scene
from rigidblocks.scene.extrude import extrude
from rigidblocks.scene.geometry import ccw, scene_size
from rigidblocks.scene.model import Block, JointOverride, Scene

RTOL = 1e-5
#: cases with non-convex blocks: many glued pieces, a few seconds each
SLOW = {"examples/arch.json", "examples/pointed_arch.json", "examples/segmental_arch.json",
        "generator/arch", "generator/stocky_arch"}


def _scene_files() -> list[str]:
    out = []
    for p in sorted(EXAMPLES.glob("*.json")):
        doc = json.loads(p.read_text())
        if doc.get("format") == "rigidblocks-scene" and doc.get("dimension") == 2:
            out.append(f"examples/{p.name}")
    return out


@functools.cache
def _generators() -> list[str]:
    return [f"generator/{name}" for name in sorted(available()) if build(name).dimension == 2]


def _load(case: str) -> Scene:
    kind, name = case.split("/")
    return read_scene(EXAMPLES / name) if kind == "examples" else build(name)


def _cases():
    for case in _scene_files() + _generators():
        marks = [pytest.mark.slow] if case in SLOW else []
        yield pytest.param(case, marks=marks, id=case)


def _convex(poly: shapely.Polygon) -> bool:
    return poly.convex_hull.area - poly.area <= 1e-12 * poly.area


def convex_pieces(points: np.ndarray) -> list[shapely.Polygon]:
    """A simple polygon cut into convex pieces: a constrained Delaunay triangulation whose
    neighbouring pieces are merged while their union stays convex (Hertel-Mehlhorn)."""
    pieces = list(shapely.constrained_delaunay_triangles(shapely.Polygon(points)).geoms)
    merged = True
    while merged:
        merged = False
        for i in range(len(pieces)):
            for j in range(i + 1, len(pieces)):
                if pieces[i].intersection(pieces[j]).length <= 0:
                    continue
                u = shapely.union(pieces[i], pieces[j])
                if u.geom_type == "Polygon" and _convex(u):
                    pieces[i] = shapely.normalize(u.simplify(0))
                    del pieces[j]
                    merged = True
                    break
            if merged:
                break
    return pieces


def glued_convex(scene: Scene) -> Scene:
    """The scene with every non-convex block cut into convex pieces glued together."""
    strength = 1e4 * max(scene.effective_unit_weight, 1.0) * scene_size(scene)
    blocks, glue = [], []
    for b in scene.blocks:
        pts = ccw(b.points)
        if _convex(shapely.Polygon(pts)):
            blocks.append(b)
            continue
        pieces = convex_pieces(pts)
        ids = [f"{b.id}.{k}" for k in range(len(pieces))]
        for bid, pc in zip(ids, pieces, strict=True):
            corners = tuple(tuple(map(float, p)) for p in np.asarray(pc.exterior.coords)[:-1])
            blocks.append(Block(bid, corners, None, b.support, b.unit_weight))
        for i in range(len(pieces)):
            for j in range(i + 1, len(pieces)):
                if pieces[i].intersection(pieces[j]).length > 0:
                    glue.append(JointOverride((ids[i], ids[j]), "infinite", None, strength))
    if not glue:
        return scene
    return scene.with_changes(blocks=tuple(blocks), joints=scene.joints + tuple(glue))


def test_the_catalogue_is_covered():
    cases = _scene_files() + _generators()
    assert "examples/reference.json" in cases and "generator/wall" in cases
    assert len([c for c in cases if c not in SLOW]) >= len(cases) / 2


def _same(a: float | None, b: float | None) -> bool:
    if a is None or b is None:
        return a is None and b is None
    return math.isclose(a, b, rel_tol=RTOL, abs_tol=RTOL * 1e-3)


@pytest.mark.parametrize("case", list(_cases()))
def test_extruded_scene_gives_the_plane_answers(case):
    s2 = _load(case)
    s3 = extrude(glued_convex(s2))
    assert s3.dimension == 3
    for lf in (0.0, 1.0):
        f2 = rb.min_friction(s2, load_factor=lf, state=False)
        f3 = rb.min_friction(s3, load_factor=lf, state=False)
        assert f3.status == f2.status, (case, lf)
        if f2.friction_factor is not None:  # both to the default accuracy, 2e-3
            assert f3.lower <= f2.upper * (1 + RTOL) and f2.lower <= f3.upper * (1 + RTOL)
            assert math.isclose(f3.friction_factor, f2.friction_factor, rel_tol=2e-3,
                                abs_tol=1e-8), (case, lf, f2.friction_factor,
                                                f3.friction_factor)
    if s2.has_live_load:
        l2 = rb.max_load_multiplier(s2, state=False)
        l3 = rb.max_load_multiplier(s3, state=False)
        assert l3.status == l2.status, case
        assert _same(l3.load_multiplier, l2.load_multiplier), (case, l2.load_multiplier,
                                                               l3.load_multiplier)


def test_glued_pieces_keep_the_plane_answer():
    """The glue is strong enough: the cut 2D arch has the uncut arch's lambda*."""
    s2 = build("stocky_arch")
    cut = glued_convex(s2)
    assert len(cut.blocks) > len(s2.blocks)
    l_cut = rb.max_load_multiplier(cut, state=False).load_multiplier
    assert l_cut == pytest.approx(rb.max_load_multiplier(s2, state=False).load_multiplier,
                                  rel=RTOL)


@pytest.mark.parametrize("dx,dy", [(1e-12, 0.0), (0.0, 1e-12), (3.0, 2.0), (10.0, 0.0)])
def test_glued_extruded_arch_is_not_decided_by_rounding(dx, dy):
    """The extruded stocky arch cut into glued pieces, moved by (dx, dy): the same
    lambda* as the plane arch (static theorem, as above). Its max-load SOCP is
    near-degenerate at the optimum: moved by any of these, Clarabel ended it
    "AlmostSolved" at its default and tight tolerances alike, and the analysis raised
    SolverFailure, until such a solve was retried with a stronger static regularisation
    and refined KKT solves (REFINE_SETTINGS in rigidblocks/solvers/policy.py)."""
    s2 = build("stocky_arch")
    moved = s2.with_changes(
        blocks=tuple(replace(b, vertices=tuple((x + dx, y + dy) for x, y in b.vertices))
                     for b in s2.blocks),
        loads=tuple(replace(ld, point=None if ld.point is None else
                            (ld.point[0] + dx, ld.point[1] + dy)) for ld in s2.loads))
    l3 = rb.max_load_multiplier(extrude(glued_convex(moved)), state=True)
    l2 = rb.max_load_multiplier(s2, state=False)
    assert l3.status == l2.status == "collapse"
    assert _same(l3.load_multiplier, l2.load_multiplier)
    assert l3.state is not None


def test_extrusion_keeps_the_scene_keys():
    """The extruded scene keeps the plane scene's load factor and flow rule: a running-bond
    wall generated with load factor 0 (self-weight only) stands in 3D as in 2D, and a
    non-associative wall stays non-associative."""
    from rigidblocks.generators.walls import running_bond_wall
    from rigidblocks.scene.extrude import extrude

    wall = running_bond_wall(3, 3)
    assert wall.load_factor == 0.0
    e = extrude(wall)
    assert e.load_factor == 0.0
    assert rb.check(wall, state=False).status == rb.check(e, state=False).status == "admissible"
    na = extrude(replace(wall, flow="non-associative", load_factor=0.5))
    assert (na.flow, na.load_factor) == ("non-associative", 0.5)


def test_a_tensile_strength_without_cohesion_is_a_bending_capacity_in_2d_only(
        tmp_path, capsys):
    """A 1 x 2 block, 1.5 deep (unit weight 20: W = 60), bonded to its base by a tensile
    strength of 20 (no cohesion), f = 5, under a horizontal body force: in 2D the shear row
    |T| <= f (N1 + N2) lets the heel pull while the toe pushes, and it tips at
    (b + sigma_t d b^2 / W) / h = (1 + 20 x 1.5 / 60) / 2 = 0.75 (moments about the toe:
    lambda W h/2 = W b/2 + sigma_t d b x b/2). Extruded, each contact point has its own
    cone, |T_k| <= f N_k, which closes where N_k < 0: it tips at b/h = 0.5, on the safe
    side, with a note saying why (it was said nowhere, and `extrude` promised the 2D
    lambda*); at infinite friction (no cone) both give 0.75."""
    from conftest import make_scene, rect

    from rigidblocks.cli.main import main
    from rigidblocks.io import write_scene
    from rigidblocks.methods.convex import TENSION_3D_NOTE

    plane = make_scene([{"id": "base", "vertices": rect(-2, -1, 5, 1), "support": True},
                        {"id": "B", "vertices": rect(0, 0, 1, 2)}],
                       unit_weight=20, depth=1.5, friction=5, live_body_force=[1, 0],
                       joints=[{"blocks": ["B", "base"], "tensile_strength": 20}])
    solid = extrude(plane)
    two = rb.max_load_multiplier(plane, state=False)
    three = rb.max_load_multiplier(solid, state=False)
    assert two.load_multiplier == pytest.approx(0.75, rel=1e-6)
    assert three.load_multiplier == pytest.approx(0.5, rel=1e-6)
    assert TENSION_3D_NOTE in three.notes and TENSION_3D_NOTE not in two.notes
    for scene in (plane, solid):
        res = rb.max_load_multiplier(scene, friction="infinite", state=False)
        assert res.load_multiplier == pytest.approx(0.75, rel=1e-6)
        # (no cone closes there: the note was said at infinite friction too)
        assert TENSION_3D_NOTE not in res.notes
    # at a load factor of 0.6, above the 3D tipping multiplier, no finite friction keeps
    # the cones open and infinite friction stands: the search on lambda*(f) ended in a
    # solver failure (InsufficientProgress), now the relaxations' search answers as it can
    res = rb.min_friction(solid, load_factor=0.6, state=False)
    assert res.status == "undecided" and any(
        "f* is searched on the relaxations instead" in n for n in res.notes)
    path = tmp_path / "plane.json"
    write_scene(plane, path)
    assert main(["extrude", str(path), "-o", str(tmp_path / "solid.json")]) == 0
    out = capsys.readouterr().out
    assert "f* and lambda* are the 2D scene's, each to its search's accuracy; with the " \
        "joints' tensile strength counted as in 2D only at infinite friction" in out, out
