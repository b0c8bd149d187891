"""COMPAS interop on assemblies and block models built with the real compas packages.

The packages come with the ``compas`` extra, which the ``test`` extra installs: without
them these tests fail (they are not skipped), with the message naming the extra.
"""

from __future__ import annotations

import importlib.util
import json
import math

import numpy as np
import pytest
from conftest import EXAMPLES

import rigidblocks as rb
from rigidblocks.cli.main import main
from rigidblocks.errors import InputError
from rigidblocks.io import read_scene

pytestmark = pytest.mark.compas

_MISSING = [m for m in ("compas", "compas_assembly", "compas_dem")
            if importlib.util.find_spec(m) is None]
if _MISSING:  # fail every test of this module loudly, never skip it
    @pytest.fixture(autouse=True)
    def _need_extra(request):
        if request.node.name.startswith("test_without_the_extra"):
            return
        pytest.fail(f"{', '.join(_MISSING)} not installed: pip install \".[compas]\" "
                    "(the test extra includes it)")
else:
    import compas
    from compas.geometry import Box, Frame, Rotation, Translation
    from compas_assembly.datastructures import Assembly, Block

from rigidblocks.compas import (  # noqa: E402
    from_compas,
    read_compas,
    scene_to_assembly,
    write_forces,
)


def box_block(x: float = 0.0, y: float = 0.0, z: float = 0.0, size=(1.0, 1.0, 1.0)):
    """A compas_assembly Block: a box centred at (x, y, z)."""
    frame = Frame.worldXY().transformed(Translation.from_vector([x, y, z]))
    return Block.from_shape(Box(*size, frame=frame))


def two_boxes(offset: float, density: float | None = None):
    """A unit cube on a unit-cube support, shifted by ``offset`` along x."""
    a = Assembly()
    a.add_block(box_block(), node=0)
    top = box_block(offset, 0.0, 1.0)
    if density is not None:
        top.attributes["density"] = density
    a.add_block(top, node=1)
    a.graph.node_attribute(0, "is_support", True)
    return a


def test_assembly_to_scene_keeps_blocks_supports_and_weight():
    a = two_boxes(0.3, density=2.5)
    scene = from_compas(a, friction=0.6)
    assert scene.dimension == 3 and [b.id for b in scene.blocks] == ["0", "1"]
    assert [b.support for b in scene.blocks] == [True, False]
    assert scene.friction == 0.6
    assert scene.blocks[1].unit_weight == 2.5 and scene.blocks[0].unit_weight == 1.0
    v, _ = a.graph.node_attribute(1, "block").to_vertices_and_faces()
    assert np.allclose(scene.blocks[1].points, v)


def test_cube_with_offset_stands_and_forces_go_back_into_the_assembly():
    """Cube on cube shifted 0.3: the contact is x in [-0.2, 0.5] and the weight's line
    (x = 0.3) falls inside it, so it stands; the joint carries the weight, 2.5, and its
    resultant crosses the joint at x = 0.3 (moment balance)."""
    a = two_boxes(0.3, density=2.5)
    res = rb.check(from_compas(a, friction=0.6), load_factor=0)
    assert res.status == "admissible"
    counts = write_forces(a, res)
    assert counts == {"interfaces": 1, "edges_added": 1, "edges_cleared": 0}
    (itf,) = a.graph.edge_attribute((0, 1), "interfaces")
    assert np.allclose(list(itf.frame.zaxis), [0, 0, 1])  # from block 0 into block 1
    fn = np.array([f["c_np"] for f in itf.forces])
    pts = np.array([list(p) for p in itf.points])
    assert fn.sum() == pytest.approx(2.5, rel=1e-6)
    assert (fn @ pts[:, 0]) / fn.sum() == pytest.approx(0.3, abs=1e-6)
    assert all(abs(f["c_u"]) < 1e-8 and abs(f["c_v"]) < 1e-8 for f in itf.forces)
    assert sorted(pts[:, 0].round(9).tolist()) == [-0.2, -0.2, 0.5, 0.5]
    # the forces survive COMPAS's own serialisation
    back = compas.json_loads(compas.json_dumps(a))
    (itf2,) = back.graph.edge_attribute((0, 1), "interfaces")
    assert [f["c_np"] for f in itf2.forces] == pytest.approx(fn.tolist())


def test_overhanging_cube_tips():
    """Shifted 0.6, the weight's line (x = 0.6) is outside the contact [0.1, 0.5]."""
    res = rb.check(from_compas(two_boxes(0.6), friction=0.6), load_factor=0)
    assert res.status == "inadmissible"
    with pytest.raises(InputError, match="no force state"):
        write_forces(two_boxes(0.6), res)


def test_reversed_edge_gets_the_frame_of_its_own_direction():
    """An edge stored as (1, 0): its frame points from 1 into 0 and c_np stays
    compression."""
    a = two_boxes(0.0)
    a.graph.add_edge(1, 0, interfaces=[])
    res = rb.check(from_compas(a, friction=0.6), load_factor=0)
    write_forces(a, res)
    (itf,) = a.graph.edge_attribute((1, 0), "interfaces")
    assert np.allclose(list(itf.frame.zaxis), [0, 0, -1])
    assert sum(f["c_np"] for f in itf.forces) == pytest.approx(1.0, rel=1e-6)


def tilted_pair(angle_deg: float):
    """A cube on a support, both turned about y by ``angle_deg`` (an inclined bed)."""
    a = two_boxes(0.0)
    R = Rotation.from_axis_and_angle([0, 1, 0], math.radians(angle_deg))
    for node in a.graph.nodes():
        a.graph.node_attribute(node, "block").transform(R)
    return a


@pytest.mark.parametrize(("friction", "expected"), [(0.45, "admissible"),
                                                    (0.35, "inadmissible")])
def test_inclined_bed_slides_below_tan_angle(friction, expected):
    """tan(21.8 deg) = 0.4: the cube slides when f < 0.4 (and cannot tip: its weight's
    line stays inside the bed)."""
    angle = math.degrees(math.atan(0.4))
    res = rb.check(from_compas(tilted_pair(angle), friction=friction), load_factor=0)
    assert res.status == expected


def test_min_friction_of_inclined_bed_is_its_slope():
    angle = math.degrees(math.atan(0.4))
    res = rb.min_friction(from_compas(tilted_pair(angle)), load_factor=0)
    assert res.friction_factor == pytest.approx(0.4, rel=1e-5)
    a = tilted_pair(angle)
    write_forces(a, res)
    (itf,) = a.graph.edge_attribute((0, 1), "interfaces")
    fn = sum(f["c_np"] for f in itf.forces)
    ft = math.hypot(sum(f["c_u"] for f in itf.forces), sum(f["c_v"] for f in itf.forces))
    assert ft / fn == pytest.approx(0.4, rel=1e-4)


def test_json_file_round_trip_and_cli(tmp_path, capsys):
    a = two_boxes(0.3)
    a.attributes["mu"] = 0.7
    path = tmp_path / "assembly.json"
    compas.json_dump(a, str(path))
    scene, rep = read_compas(path)
    assert scene.friction == 0.7 and "attribute 'mu'" in rep.friction_source
    assert rep.supports == ["0"] and rep.blocks == 2
    out = tmp_path / "scene.json"
    assert main(["import-compas", str(path), "-o", str(out)]) == 0
    assert "2 blocks, 1 supports (0), friction 0.7" in capsys.readouterr().out
    back = read_scene(out)
    assert back.friction == 0.7 and [b.support for b in back.blocks] == [True, False]
    assert rb.check(back, load_factor=0).status == "admissible"


def test_import_with_a_live_body_force_gives_load_its_question(tmp_path, capsys):
    """--live-body-force '1 0': a unit cube on a support under lambda x its weight
    along x tips about its edge at lambda* = (b/2)/(h/2) = 1 where f > 1, and slides at
    lambda* = f below (docs/validation.md, block on a support); the load factor written
    is 0, so check answers for the weight alone."""
    path = tmp_path / "assembly.json"
    compas.json_dump(two_boxes(0.0), str(path))
    for f, expected in (("2", 1.0), ("0.4", 0.4)):
        out = tmp_path / f"scene{f}.json"
        assert main(["import-compas", str(path), "-o", str(out), "--friction", f,
                     "--live-body-force", "1 0"]) == 0
        assert "load factor 0 written" in capsys.readouterr().out
        scene = read_scene(out)
        assert scene.live_body_force == (1.0, 0.0, 0.0) and scene.load_factor == 0
        res = rb.max_load_multiplier(scene)
        assert res.load_multiplier == pytest.approx(expected, rel=1e-6)
        assert rb.check(scene).status == "admissible"
    assert main(["import-compas", str(path), "-o", str(tmp_path / "x.json"),
                 "--live-body-force", "0 0"]) == 2
    assert "--live-body-force" in capsys.readouterr().err


def test_cra_assembly_dtype_reads_without_compas_cra(tmp_path):
    """compas_cra saves CRA_Assembly; it adds methods only, so it reads as an Assembly."""
    text = compas.json_dumps(two_boxes(0.3)).replace(
        "compas_assembly.datastructures/Assembly", "compas_cra.datastructures/CRA_Assembly")
    path = tmp_path / "cra.json"
    path.write_text(text)
    scene, rep = read_compas(path, friction=0.6)
    assert len(scene.blocks) == 2 and rep.supports == ["0"]


def test_supports_from_the_command_line(tmp_path, capsys):
    a = two_boxes(0.3)
    a.graph.node_attribute(0, "is_support", False)
    path = tmp_path / "a.json"
    compas.json_dump(a, str(path))
    out = tmp_path / "s.json"
    assert main(["import-compas", str(path), "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "a.json" in err and "support" in err
    assert main(["import-compas", str(path), "-o", str(out), "--supports", "0",
                 "--friction", "0.5"]) == 0
    assert read_scene(out).blocks[0].support
    assert main(["import-compas", str(path), "-o", str(out), "--supports", "9"]) == 2
    assert "'9' is not a block" in capsys.readouterr().err


def test_bad_files_are_one_line_errors(tmp_path, capsys):
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    assert main(["import-compas", str(bad), "-o", str(tmp_path / "x.json")]) == 2
    other = tmp_path / "other.json"
    other.write_text(json.dumps({"a": 1}))
    assert main(["import-compas", str(other), "-o", str(tmp_path / "x.json")]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 2 and "not JSON" in lines[0] and "not a compas_assembly" in lines[1]


def test_without_the_extra_a_one_line_error_names_it(tmp_path, capsys, monkeypatch):
    real = importlib.util.find_spec
    monkeypatch.setattr(importlib.util, "find_spec",
                        lambda name, *a: None if name.startswith("compas") else real(name, *a))
    path = tmp_path / "a.json"
    path.write_text("{}")
    assert main(["import-compas", str(path), "-o", str(tmp_path / "s.json")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and 'pip install "rigidblocks[compas]"' in err


def test_blockmodel_with_problem_friction_and_forces_back():
    """A compas_dem BlockModel with a Problem (Mohr-Coulomb mu) saved beside it."""
    from compas_dem.models import BlockModel
    from compas_dem.problem import Problem

    boxes = [Box(1, 1, 1), Box(1, 1, 1, frame=Frame.worldXY().transformed(
        Translation.from_vector([0.3, 0, 1])))]
    model = BlockModel.from_boxes(boxes)
    model.add_support(next(iter(model.elements())).graphnode)
    problem = Problem(model)
    problem.set_contact_model("MohrCoulomb", mu=0.55)
    doc = compas.json_loads(compas.json_dumps({"model": model, "problem": problem}))
    scene = from_compas(doc)
    assert scene.friction == 0.55 and sum(b.support for b in scene.blocks) == 1
    res = rb.check(scene, load_factor=0)
    assert res.status == "admissible"
    model2 = doc["model"]
    counts = write_forces(model2, res)
    assert counts["interfaces"] == 1
    (contact,) = list(model2.contacts())
    fn = np.array([f["c_np"] for f in contact.forces])
    pts = np.array([list(p) for p in contact.points])
    assert fn.sum() == pytest.approx(1.0, rel=1e-6)
    assert (fn @ pts[:, 0]) / fn.sum() == pytest.approx(0.3, abs=1e-6)


def test_blockmodel_material_density_times_g():
    from compas_dem.models import BlockModel

    model = BlockModel.from_boxes([Box(1, 1, 1), Box(1, 1, 1, frame=Frame.worldXY()
                                                     .transformed(Translation.from_vector(
                                                         [0, 0, 1])))])
    from compas_model.materials import Concrete

    els = list(model.elements())
    els[0].is_support = True
    concrete = Concrete(fck=30, density=2000.0)
    model.add_material(concrete)
    model.assign_material(concrete, element=els[1])
    model = compas.json_loads(compas.json_dumps(model))
    scene = from_compas(model, friction=0.6)
    assert scene.blocks[1].unit_weight == pytest.approx(2000.0 * 9.81)
    assert scene.blocks[0].unit_weight == 1.0 and scene.blocks[0].support


def test_scene_to_assembly_and_back():
    scene = read_scene(EXAMPLES / "box_stack_3d.json")
    a = scene_to_assembly(scene)
    assert a.graph.number_of_nodes() == len(scene.blocks)
    back = from_compas(a, friction=scene.friction)
    assert [b.support for b in back.blocks] == [b.support for b in scene.blocks]
    r1 = rb.check(scene, load_factor=0)
    r2 = rb.check(back, load_factor=0)
    assert r1.status == r2.status
    assert np.allclose(np.sort(r1.state.joint_normal), np.sort(r2.state.joint_normal),
                       rtol=1e-5, atol=1e-8)
    assert write_forces(a, r2)["interfaces"] == r2.contacts.n_joints


def l_prism():
    """An L-shaped prism (non-convex): the L in x-z, extruded along y."""
    from compas.datastructures import Mesh

    L = [(0, 0), (2, 0), (2, 1), (1, 1), (1, 2), (0, 2)]
    verts = [[x, 0.0, z] for x, z in L] + [[x, 1.0, z] for x, z in L]
    n = len(L)
    faces = [list(range(n)),
             [n + i for i in range(n)][::-1]]
    faces += [[i, (i + 1) % n, n + (i + 1) % n, n + i][::-1] for i in range(n)]
    return Mesh.from_vertices_and_faces(verts, faces)


def test_non_convex_block_converted_faithfully_validation_decides():
    """Non-convex blocks are converted as they are; today's validation (convex 3D
    blocks) refuses them naming the block; once non-convex blocks are accepted the same
    conversion gives a scene."""
    a = Assembly()
    a.add_block(box_block(1.0, 0.5, -0.5, size=(4.0, 2.0, 1.0)), node=0)
    a.add_block(l_prism().copy(cls=Block), node=1)
    a.graph.node_attribute(0, "is_support", True)
    scene = from_compas(a, friction=0.6, validate=False)
    v, f = a.graph.node_attribute(1, "block").to_vertices_and_faces()
    assert np.allclose(scene.blocks[1].points, v)
    assert [list(x) for x in scene.blocks[1].faces] == f
    try:
        checked = from_compas(a, friction=0.6)
    except InputError as err:
        assert "block '1'" in str(err) and "convex" in str(err)
    else:
        assert rb.check(checked, load_factor=0).status == "admissible"


def _newell_normals_point_out(vertices, faces) -> bool:
    """Every face's (Newell) normal points away from the block's mean vertex: the faces
    turn counter-clockwise seen from outside (the test is exact for convex blocks)."""
    pts = np.asarray(vertices, dtype=float)
    centre = pts.mean(axis=0)
    for f in faces:
        p = pts[list(f)]
        n = np.cross(p, np.roll(p, -1, axis=0)).sum(axis=0)
        if not n @ (p.mean(axis=0) - centre) > 0:
            return False
    return True


def _turned(block, faces):
    """A copy of a compas_assembly Block with the given faces (vertex keys as indices)."""
    v, _ = block.to_vertices_and_faces()
    return Block.from_vertices_and_faces(v, faces)


def test_inward_faces_are_written_outward_and_said(tmp_path, capsys):
    """A block meshed with every face inward (negative signed volume) is imported with
    its faces reversed, the report saying which; the scene file then has every face
    counter-clockwise seen from outside, as docs/scene-format.md says of the files
    rigidblocks writes."""
    a = two_boxes(0.3)
    top = a.graph.node_attribute(1, "block")
    _, faces = top.to_vertices_and_faces()
    assert _newell_normals_point_out(*top.to_vertices_and_faces())  # COMPAS's box: out
    a.graph.node_attribute(1, "block", _turned(top, [f[::-1] for f in faces]))
    path = tmp_path / "inward.json"
    compas.json_dump(a, str(path))
    out = tmp_path / "scene.json"
    assert main(["import-compas", str(path), "-o", str(out), "--friction", "0.6"]) == 0
    assert ("faces reversed to point outward in 1 block(s) whose mesh had them all "
            "inward: 1") in capsys.readouterr().out
    doc = json.loads(out.read_text())
    for b in doc["blocks"]:
        assert _newell_normals_point_out(b["vertices"], b["faces"]), b["id"]
    assert rb.check(read_scene(out), load_factor=0).status == "admissible"


def test_faces_turning_both_ways_are_refused_naming_the_block(tmp_path, capsys):
    """One face of a closed mesh reversed: no single way to turn it outward is implied
    by the mesh, so the import stops with one line naming the file, the block, the two
    faces and their common edge."""
    a = two_boxes(0.3)
    top = a.graph.node_attribute(1, "block")
    _, faces = top.to_vertices_and_faces()
    faces = [list(f) for f in faces]
    faces[2] = faces[2][::-1]
    a.graph.node_attribute(1, "block", _turned(top, faces))
    with pytest.raises(InputError, match=r"block '1': faces (\d+ and 2|2 and \d+) run through "
                       r"their common edge \(\d+, \d+\) in the same direction"):
        from_compas(a)
    path = tmp_path / "mixed.json"
    compas.json_dump(a, str(path))
    assert main(["import-compas", str(path), "-o", str(tmp_path / "s.json")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"rigidblocks: error: {path}: block '1': faces ") and \
        err.count("\n") == 1 and "unify_cycles" in err, err
    assert not (tmp_path / "s.json").exists()


def test_inward_non_convex_block_is_turned_by_its_signed_volume():
    """The L prism (non-convex: no face plane keeps every vertex on one side) meshed
    inward: the sign of its volume decides, and every face is reversed; meshed outward
    it is kept as given."""
    from rigidblocks.compas import ImportReport, assembly_to_scene

    mesh = l_prism()
    v, f = mesh.to_vertices_and_faces()
    for faces, turned in ((f, False), ([x[::-1] for x in f], True)):
        a = Assembly()
        a.add_block(Block.from_vertices_and_faces(v, faces), node=0)
        rep = ImportReport(kind="")
        scene = assembly_to_scene(a, validate=False, report=rep)
        assert [list(x) for x in scene.blocks[0].faces] == [list(x) for x in f]
        assert bool(rep.notes) == turned
