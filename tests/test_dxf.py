"""DXF import (with the repairs real drawings need) and export.

References: the stack of two equal-width blocks (total height h, width b) on a support
under a horizontal body force lambda x weight tips as one body about its toe at
lambda* = b / h when f > b / h (docs/validation.md, block on a support). The LACT3
drawings and their published collapse tilt angles are described in
../shared/data/lact3/README.md (Milani, LACT3_v1.0 sample models).
"""

from __future__ import annotations

import json
import math

import ezdxf
import numpy as np
import pytest
from conftest import EXAMPLES, SHARED, require_shared

import rigidblocks as rb
from rigidblocks.cli.main import main
from rigidblocks.errors import InputError
from rigidblocks.io import read_scene, write_scene
from rigidblocks.scene.geometry import signed_area

LACT3 = SHARED / "data" / "lact3"
E = 1e-12  # CAD round-off


def quirky_drawing(path, *, gap=E, extra=()):
    """Base (layer SUPPORT) 4 x 1, block A 1 x 2 on it, block B 1 x 1 on A, block C
    (four LINEs) 1 x 1 on the base; with round-off, open ends, retracing, clockwise
    order and a collinear extra vertex."""
    doc = ezdxf.new()
    msp = doc.modelspace()
    msp.add_lwpolyline([(-1, -1), (3, -1), (3, 0), (-1, 0)], close=True,
                       dxfattribs={"layer": "SUPPORT"})
    # A: not flagged closed, last vertex 1e-13 off the first, clockwise, extra vertex
    msp.add_lwpolyline([(0, 0), (0, 2 + E), (0.5, 2), (1, 2 - E), (1 + E, 0), (1e-13, 0)])
    # B: retraces its first two vertices, corners off by `gap`
    msp.add_lwpolyline([(gap, 2), (1, 2 + gap), (1, 3), (0, 3), (gap, 2), (1, 2 + gap)])
    # C: a closed chain of LINEs, drawn in scrambled order and directions
    for a, b in [((2, 0), (2.5, 0)), ((2.5, 1), (2.5, 0)), ((2, 1), (2.5, 1)),
                 ((2, 0), (2, 1 + E))]:
        msp.add_line(a, b)
    msp.add_point((5, 5))
    for pts in extra:
        msp.add_lwpolyline(pts, close=True)
    doc.saveas(path)
    return path


def test_quirky_drawing_is_repaired_and_reported(tmp_path):
    path = quirky_drawing(tmp_path / "q.dxf")
    sc, rep = rb.read_dxf(path, supports="layer:SUPPORT", unit_weight=1.0, friction=0.9,
                          live_body_force=(1, 0), units=("m", "kN"), report=True)
    assert [b.id for b in sc.blocks] == ["b1", "b2", "b3", "b4"]
    assert [b.support for b in sc.blocks] == [True, False, False, False]
    assert rep.n_blocks == 4 and rep.supports == ["b1"]
    assert rep.retraced == ["b3"] and set(rep.closed_by_snap) >= {"b2", "b3"}
    assert rep.vertices_snapped > 0 and 0 < rep.max_move < 1e-11
    assert rep.skipped == {"POINT": 1}
    assert len(sc.blocks[2].vertices) == 4  # retraced vertices dropped
    # shared corners now coincide exactly
    a = {tuple(p) for p in sc.blocks[1].vertices}
    b = {tuple(p) for p in sc.blocks[2].vertices}
    assert len(a & b) == 2
    assert "4 blocks" in rep.summary() and "snapped" in rep.summary()
    assert "(1 support: b1)" in rep.summary() and rep.reoriented >= 1
    # kept as drawn (it read "turned ... counter-clockwise", and the scene file kept them
    # clockwise all the same)
    assert f"{rep.reoriented} outlines drawn clockwise (kept so" in rep.summary()
    assert sum(signed_area(np.asarray(b.vertices)) < 0 for b in sc.blocks) == rep.reoriented
    # A + B tip together about the toe (1, 0): lambda* = b / h = 1 / 3
    res = rb.max_load_multiplier(sc)
    assert res.load_multiplier == pytest.approx(1 / 3, rel=1e-6)
    # "lowest" picks the same support
    low = rb.read_dxf(path)
    assert [b.support for b in low.blocks] == [True, False, False, False]
    assert rb.read_dxf(path, supports="largest").blocks[0].support


def test_near_miss_beyond_tolerance_names_the_blocks(tmp_path):
    # size 4 sqrt(2): tolerance 5.7e-8, near-miss band up to 5.7e-6
    path = quirky_drawing(tmp_path / "q.dxf", gap=2e-6)
    with pytest.raises(InputError, match="'b2' and 'b3'|'b3' and 'b2'"):
        rb.read_dxf(path)
    sc = rb.read_dxf(path, snap_tol=1e-6)  # a looser tolerance accepts it
    assert len(sc.blocks) == 4


def test_rejections(tmp_path):
    # a floating block
    path = quirky_drawing(tmp_path / "f.dxf", extra=[[(10, 10), (11, 10), (11, 11)]])
    with pytest.raises(InputError, match="b4 touch no other block"):
        rb.read_dxf(path)
    # an overlap
    path = quirky_drawing(tmp_path / "o.dxf", extra=[[(0.5, 0.5), (1.5, 0.5), (1.5, 1.5)]])
    with pytest.raises(InputError, match="b2|b5"):
        rb.read_dxf(path)
    # an open polyline
    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline([(0, 0), (1, 0), (1, 1), (0, 1)])
    doc.saveas(tmp_path / "open.dxf")
    with pytest.raises(InputError, match="block 'b1'.*open polyline"):
        rb.read_dxf(tmp_path / "open.dxf")
    path = quirky_drawing(tmp_path / "q.dxf")
    with pytest.raises(InputError, match="no block on layer 'NOPE'"):
        rb.read_dxf(path, supports="layer:NOPE")
    with pytest.raises(InputError, match="unknown supports option"):
        rb.read_dxf(path, supports="top")
    with pytest.raises(InputError, match="no such file"):
        rb.read_dxf(tmp_path / "missing.dxf")


@pytest.mark.parametrize("cut", [100, 3000])
def test_a_drawing_cut_short_is_no_valid_dxf(cut, tmp_path, capsys):
    """A drawing cut after 100 or 3,000 bytes (a download or a copy broken off) ended in
    ezdxf's StopIteration, a traceback; cut elsewhere it read "not a valid DXF file"."""
    whole = quirky_drawing(tmp_path / "q.dxf").read_bytes()
    cut_short = tmp_path / "cut.dxf"
    cut_short.write_bytes(whole[:cut])
    assert main(["import-dxf", str(cut_short), "-o", str(tmp_path / "s.json")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"{cut_short}: not a valid DXF file" in err, err
    assert not (tmp_path / "s.json").exists()


def test_a_vertex_that_is_no_number_is_named(tmp_path):
    """A polyline vertex at NaN read "closed polyline with fewer than 3 vertices apart by
    more than the snapping tolerance nan"."""
    path = quirky_drawing(tmp_path / "n.dxf",
                          extra=[[(10, 0), (11, 0), (math.nan, 1), (10, 1)]])
    with pytest.raises(InputError, match=r"LWPOLYLINE #\w+: vertex 2 is not a finite number"):
        rb.read_dxf(path)


def test_cli_import_and_export(tmp_path, capsys):
    path = quirky_drawing(tmp_path / "q.dxf")
    out = tmp_path / "q.json"
    assert main(["import-dxf", str(path), "-o", str(out), "--unit-weight", "1",
                 "--friction", "0.9", "--live-body-force", "1 0", "--length-unit", "m",
                 "--force-unit", "kN", "--supports", "layer:SUPPORT"]) == 0
    text = capsys.readouterr().out
    assert "4 blocks" in text and "snapped" in text
    sc = read_scene(out)
    assert len(sc.blocks) == 4 and sc.friction == 0.9
    dxf_out = tmp_path / "r.dxf"
    assert main(["export-dxf", str(out), "-o", str(dxf_out), "--analysis", "friction",
                 "--load-factor", "0.1"]) == 0
    doc = ezdxf.readfile(dxf_out)
    msp = doc.modelspace()
    on = {lay: [e for e in msp if e.dxf.layer == lay] for lay in
          ("RB_BLOCKS", "RB_SUPPORTS", "RB_THRUST_LINE", "RB_FORCES")}
    assert len(on["RB_BLOCKS"]) == 3 and len(on["RB_SUPPORTS"]) == 1
    # block A carries B and stands on the base beside C: not a chain of blocks, so no
    # thrust line, a circle at each loaded joint's resultant (it drew a line from A's
    # base up to A-B and down to C's base)
    assert {e.dxftype() for e in on["RB_THRUST_LINE"]} == {"CIRCLE"}
    n_joints = rb.detect_contacts(sc).n_joints
    assert len(on["RB_THRUST_LINE"]) == n_joints
    assert len(on["RB_FORCES"]) == 3 * n_joints  # shaft + two head strokes each
    # the exported blocks read back as the same scene geometry
    back = rb.read_dxf(dxf_out, layers=["RB_BLOCKS", "RB_SUPPORTS"],
                       supports="layer:RB_SUPPORTS")
    for b0, b1 in zip(sc.blocks, back.blocks, strict=True):
        assert np.allclose(b0.points, b1.points)
    assert main(["import-dxf", str(tmp_path / "missing.dxf"), "-o", str(out)]) == 2


def test_roundtrip_scene_file(tmp_path):
    sc = rb.read_dxf(quirky_drawing(tmp_path / "q.dxf"), unit_weight=2.0, depth=0.5)
    write_scene(sc, tmp_path / "s.json")
    assert read_scene(tmp_path / "s.json") == sc


LACT3_CASES = [("Portal.dxf", 41, 30.0, 27.30), ("wall.dxf", 183, 26.0, 16.73),
               ("arch_1.dxf", 26, 30.0, 17.10)]


@pytest.mark.parametrize("name,n_blocks,phi,theta", LACT3_CASES,
                         ids=[c[0] for c in LACT3_CASES])
def test_lact3_import_and_collapse_multiplier(name, n_blocks, phi, theta):
    """LACT3 sample models (GabrieleMilani/LACT3_v1.0, see the README in the data
    folder): published collapse tilt angle theta*, lambda* = tan(theta*) for a
    horizontal body force lambda x weight, associative friction tan(phi), zero
    cohesion; the angles were found on a grid of about 1/128 degree (about 0.1 %)."""
    sc, rep = rb.read_dxf(require_shared(LACT3 / name), unit_weight=25e-9, units=("mm", "kN"),
                          friction=math.tan(math.radians(phi)), live_body_force=(1, 0),
                          report=True)
    assert len(sc.blocks) == n_blocks
    assert int(sc.support_mask.sum()) == 1
    (sup,) = [b for b in sc.blocks if b.support]
    assert sup.points[:, 1].min() == pytest.approx(0.0, abs=1e-9)
    res = rb.max_load_multiplier(sc)
    assert res.status == "collapse"
    assert res.load_multiplier == pytest.approx(math.tan(math.radians(theta)), rel=2e-3)


# -- round trip of our own drawings --------------------------------------------------------
def test_export_import_round_trip_restores_scene_and_lambda(tmp_path, capsys):
    """Issue 15 item 4: `export-dxf arch.json --analysis check -o a.dxf && import-dxf
    a.dxf -o b.json` restores the scene (ids, supports, unit weight, friction, loads,
    units) and lambda*; the analysis layers (thrust line, arrows, text) are not read as
    blocks."""
    from conftest import EXAMPLES

    for name, extra in (("arch.json", []), ("arch.json", ["--load-factor", "0"]),
                        ("reference.json", []), ("flat_arch_radial.json", [])):
        src = EXAMPLES / name
        a, b = tmp_path / "a.dxf", tmp_path / "b.json"
        assert main(["export-dxf", str(src), "--analysis", "check", "-o", str(a),
                     *extra]) == 0
        assert main(["import-dxf", str(a), "-o", str(b)]) == 0
        out = capsys.readouterr()
        assert "restored" in out.out and "warning" not in out.err
        sc0, sc1 = read_scene(src), read_scene(b)
        assert sc1 == sc0, name
        assert b.read_text() == src.read_text()
        if sc0.has_live_load:
            assert (rb.max_load_multiplier(sc1).load_multiplier
                    == rb.max_load_multiplier(sc0).load_multiplier)
        if extra:  # the arch stands at load factor 0: its arrows were drawn, and skipped
            layers = {e.dxf.layer for e in ezdxf.readfile(a).modelspace()}
            assert {"RB_FORCES", "RB_THRUST_LINE"} <= layers


def test_round_trip_keeps_loads_joint_overrides_and_block_weights(tmp_path):
    from conftest import make_scene, rect

    sc = make_scene([
        {"id": "ground", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "P", "vertices": rect(0, 0, 1, 2), "unit_weight": 30.0},
        {"id": "Q", "vertices": rect(0, 2, 1, 1)},
    ], name="two", units={"length": "m", "force": "kN"}, depth=0.5, unit_weight=20.0,
        friction=0.7, joints=[{"blocks": ["P", "Q"], "friction": 0.3, "cohesion": 1.5}],
        loads=[{"block": "Q", "force": [2.0, -1.0], "point": [0.5, 3.0], "live": True},
               {"block": "P", "force": [0.0, -4.0], "moment": 0.25}])
    rb.io.dxf.write_dxf(sc, tmp_path / "s.dxf", rb.max_load_multiplier(sc))
    back, rep = rb.read_dxf(tmp_path / "s.dxf", report=True)
    assert rep.restored and back == sc
    # values given on import replace the stored ones
    heavier = rb.read_dxf(tmp_path / "s.dxf", unit_weight=25.0, friction=0.8)
    assert heavier.unit_weight == 25.0 and heavier.friction == 0.8
    assert heavier.loads == sc.loads and heavier.joints == sc.joints


def test_drawing_edited_in_cad_is_repaired_and_keeps_its_metadata(tmp_path):
    """A block moved by 1e-12 in CAD and a new block without an id: the repair path
    runs, stored ids and loads still apply, the new block gets a fresh id."""
    from conftest import make_scene, rect

    sc = make_scene([
        {"id": "ground", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "P", "vertices": rect(0, 0, 1, 2)},
    ], unit_weight=20.0, friction=0.6, live_body_force=[1, 0])
    path = tmp_path / "s.dxf"
    rb.io.dxf.write_dxf(sc, path)
    doc = ezdxf.readfile(path)
    doc.modelspace().add_lwpolyline([(2, 0), (2.5, 0), (2.5, 1 + E), (2, 1)], close=True)
    doc.saveas(path)
    back, rep = rb.read_dxf(path, report=True)
    assert [b.id for b in back.blocks] == ["ground", "P", "b1"]
    assert back.unit_weight == 20.0 and back.live_body_force == (1.0, 0.0)
    assert back.blocks[2].points[2, 1] == pytest.approx(1.0, abs=1e-11)


def test_analysis_layers_are_skipped_and_other_layers_can_be_chosen(tmp_path):
    """Another program's drawing with force arrows drawn as LINEs on an analysis layer,
    and blocks on two layers: the default skips only our analysis layers; --layers
    names the layers to read."""
    doc = ezdxf.new()
    msp = doc.modelspace()
    msp.add_lwpolyline([(-1, -1), (3, -1), (3, 0), (-1, 0)], close=True,
                       dxfattribs={"layer": "GROUND"})
    msp.add_lwpolyline([(0, 0), (1, 0), (1, 2), (0, 2)], close=True,
                       dxfattribs={"layer": "STONES"})
    for lay in ("RB_FORCES", "ARROWS"):
        msp.add_line((0.5, 1), (0.9, 1.3), dxfattribs={"layer": lay})
    doc.saveas(tmp_path / "o.dxf")
    with pytest.raises(InputError, match="LINE entities that do not form a closed chain"):
        rb.read_dxf(tmp_path / "o.dxf")  # ARROWS is not ours: read, and it fails
    sc = rb.read_dxf(tmp_path / "o.dxf", layers=["GROUND", "STONES"], unit_weight=1.0)
    assert len(sc.blocks) == 2 and sc.unit_weight == 1.0
    out = tmp_path / "o.json"
    assert main(["import-dxf", str(tmp_path / "o.dxf"), "-o", str(out), "--layers",
                 "GROUND,STONES", "--unit-weight", "1"]) == 0
    assert len(read_scene(out).blocks) == 2


def test_import_without_unit_weight_warns_and_every_analysis_says_so(tmp_path, capsys):
    """A drawing imported without a unit weight has weightless blocks: import-dxf warns
    (and where no friction is given, that its joints do not slide),
    and an analysis of the scene says in its notes that the blocks weigh nothing (a
    weightless check is trivially admissible and must not read as a verdict on the
    structure's own weight)."""
    path = quirky_drawing(tmp_path / "q.dxf")
    out = tmp_path / "q.json"
    assert main(["import-dxf", str(path), "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "warning" in err and "without a unit weight" in err
    # nor a friction: infinite (no sliding) unless an analysis gives one; it said nothing
    assert "imported without a friction: the joints have infinite friction" in err
    assert main(["import-dxf", str(path), "-o", str(out), "--friction", "0.6"]) == 0
    assert "without a friction" not in capsys.readouterr().err
    assert main(["import-dxf", str(path), "-o", str(out)]) == 0
    capsys.readouterr()
    sc = read_scene(out)
    assert sc.unit_weight is None
    r = rb.check(sc, load_factor=0)
    assert any("weigh nothing" in n for n in r.notes)
    assert main(["check", str(out), "--json"]) == 0
    assert any("weigh nothing" in n for n in json.loads(capsys.readouterr().out)["notes"])
    sc2 = rb.read_dxf(path, unit_weight=20.0)
    assert not any("weigh nothing" in n for n in rb.check(sc2, load_factor=0).notes)


def test_import_of_weighing_blocks_without_a_depth_warns(tmp_path, capsys):
    """Blocks given a unit weight and no depth are 1 length unit deep (a drawing in mm:
    1 mm, its self-weight 0.066 kN where the wall weighs hundreds): import-dxf said
    nothing of it; with a depth, or without a unit weight (no weight to scale), no such
    warning."""
    path = quirky_drawing(tmp_path / "q.dxf")
    out = str(tmp_path / "q.json")
    base = ["import-dxf", str(path), "-o", out, "--length-unit", "mm", "--friction", "0.6"]
    assert main(base + ["--unit-weight", "25e-9"]) == 0
    assert "imported without a depth: the blocks are 1 mm deep out of plane" in \
        capsys.readouterr().err
    assert main(base + ["--unit-weight", "25e-9", "--depth", "300"]) == 0
    assert "without a depth" not in capsys.readouterr().err
    assert read_scene(out).depth == 300
    assert main(base) == 0
    assert "without a depth" not in capsys.readouterr().err


def test_a_weightless_scene_without_loads_has_no_forces_and_needs_no_friction(tmp_path):
    """A weightless drawing with no load carries nothing: its state has no forces and
    needs no friction, and the note says that nothing loads it (the round-off of the
    solver, forces of 1e-12, read as |T|/N = 8.5 at one of its joints)."""
    path = quirky_drawing(tmp_path / "q.dxf")
    r = rb.check(rb.read_dxf(path), load_factor=0)
    assert r.status == "admissible"
    assert r.friction_demand == (0.0, 0)
    assert not np.any(r.state.joint_normal) and not np.any(r.state.joint_shear)
    assert any("no load acts: every force is zero" in n for n in r.notes)
    # with its weight the state carries it, and the note is not given
    r2 = rb.check(rb.read_dxf(path, unit_weight=20.0), load_factor=0)
    assert np.abs(r2.state.joint_normal).max() > 1.0
    assert not any("no load acts" in n for n in r2.notes)


@pytest.mark.parametrize("args,said", [
    (["--unit-weight", "-1"], "unit_weight must be >= 0, got -1"),
    (["--depth", "0"], "depth must be > 0, got 0"),
    (["--depth", "-5"], "depth must be > 0, got -5"),
    (["--snap-tol", "1"], "snap_tol must be > 0 and at most 0.01"),
    (["--snap-tol", "0"], "snap_tol must be > 0 and at most 0.01"),
    (["--near-miss", "-1"], "near_miss must be >= 0, got -1")])
def test_import_refuses_numbers_the_scene_file_would_refuse(tmp_path, capsys, args, said):
    """A unit weight of -1 or a depth of 0 was written into the scene, which every
    analysis then refused; a snapping tolerance of the drawing's size merged every
    block's corners and said "its ends are 0 apart, more than the snapping tolerance"."""
    path = quirky_drawing(tmp_path / "q.dxf")
    out = tmp_path / "q.json"
    assert main(["import-dxf", str(path), "-o", str(out), *args]) == 2
    err = capsys.readouterr().err
    assert said in err and str(path) in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


def test_import_reads_the_drawings_length_unit_and_warns_where_another_is_given(
        tmp_path, capsys):
    """A drawing that declares millimetres ($INSUNITS 4) is read in millimetres where no
    length unit is given (the scene recorded none), and where metres are given the
    import says that it reads the coordinates as metres (a 1 x 2 m block drawn in mm,
    1000 x 2000, then weighs 1e9 times as much, 4e+07 at 20 per m^3: said nothing)."""
    doc = ezdxf.new()
    doc.header["$INSUNITS"] = 4
    msp = doc.modelspace()
    msp.add_lwpolyline([(-1000, -1000), (3000, -1000), (3000, 0), (-1000, 0)], close=True)
    msp.add_lwpolyline([(0, 0), (1000, 0), (1000, 2000), (0, 2000)], close=True)
    path = tmp_path / "mm.dxf"
    doc.saveas(path)
    out = tmp_path / "mm.json"
    assert main(["import-dxf", str(path), "-o", str(out), "--force-unit", "kN"]) == 0
    said = capsys.readouterr()
    assert ("lengths in mm, as the drawing declares ($INSUNITS; it spans 4000 x 3000 mm "
            "(4 x 3 m)): give the unit weight per mm^3 and the depth in mm") in said.out
    assert "warning: the drawing declares" not in said.err
    assert "across" not in said.err  # blocks of 1 m and 4 m: masonry sizes
    sc = read_scene(out)
    assert (sc.units.length, sc.units.force) == ("mm", "kN")
    assert main(["import-dxf", str(path), "-o", str(out), "--length-unit", "m"]) == 0
    err = capsys.readouterr().err
    assert ("warning: the drawing declares its lengths in mm ($INSUNITS 4), the length "
            "unit given is m: its coordinates are read as m") in err
    assert read_scene(out).units.length == "m"
    assert main(["import-dxf", str(path), "-o", str(out), "--length-unit", "mm"]) == 0
    assert "declares" not in capsys.readouterr().err


def test_import_doubts_a_declared_unit_that_makes_blocks_metres_across(tmp_path, capsys):
    """LACT3's wall.dxf is drawn in millimetres (its README) and declares inches
    ($INSUNITS 1): read as declared, its blocks were 250 in (6.35 m) across and the
    import said only "lengths in in, as the drawing declares"; it now gives the
    drawing's span in metres and warns of blocks no masonry has."""
    path = require_shared(LACT3 / "wall.dxf")
    out = tmp_path / "w.json"
    assert main(["import-dxf", str(path), "-o", str(out)]) == 0
    said = capsys.readouterr()
    assert "lengths in in, as the drawing declares ($INSUNITS; it spans 2521 x 1650 in " \
           "(64.03 x 41.91 m))" in said.out
    # the units that make them a block's size, not the one it was read in (a drawing
    # read in mm was told "give it with --length-unit (e.g. mm)")
    assert ("warning: the blocks are 250 in across (the median), 6.35 m: if the drawing "
            "is in mm (0.25 m) or cm (2.5 m), give it with --length-unit") in said.err
    assert main(["import-dxf", str(path), "-o", str(out), "--length-unit", "mm",
                 "--unit-weight", "25e-9"]) == 0
    said = capsys.readouterr()
    assert "across" not in said.err  # 250 mm blocks
    # the span in the unit given too (it was said only for a declared one), and a depth
    # example in that unit (it read "--depth 300 for 300 m" in metres)
    assert "lengths in mm, as given (the drawing spans 2521 x 1650 mm (2.521 x 1.65 m))" \
        in said.out
    assert "e.g. import-dxf --depth 300 for 300 mm)" in said.err
    assert main(["import-dxf", str(path), "-o", str(out), "--length-unit", "m",
                 "--unit-weight", "25"]) == 0
    err = capsys.readouterr().err
    assert "e.g. import-dxf --depth 0.3 for 0.3 m)" in err
    # blocks of 250 m said once in metres (it read "250 m across (the median), 250 m")
    assert "the blocks are 250 m across (the median): if the drawing" in err


def test_import_without_a_unit_guesses_it_and_reads_unit_spellings(tmp_path, capsys):
    """A drawing that declares no unit ($INSUNITS 0), of 350 x 200 blocks, and given
    none: the import said nothing of units (its scene then weighed 350 mm blocks as 350
    m ones); it says the lengths are the drawing's own, and in which units the blocks
    are a masonry block's size. --length-unit meter, inches ... were units of their own
    (no span in metres, no doubt of the size) and furlong was written into the scene:
    the spellings are read, an unknown unit refused."""
    doc = ezdxf.new()
    doc.header["$INSUNITS"] = 0
    msp = doc.modelspace()
    msp.add_lwpolyline([(-500, -200), (1000, -200), (1000, 0), (-500, 0)], close=True)
    for k in range(3):
        msp.add_lwpolyline([(0, 200 * k), (350, 200 * k), (350, 200 * k + 200),
                            (0, 200 * k + 200)], close=True)
    path = tmp_path / "u0.dxf"
    doc.saveas(path)
    out = tmp_path / "u0.json"
    assert main(["import-dxf", str(path), "-o", str(out)]) == 0
    said = capsys.readouterr()
    assert "lengths in the drawing's own units, none declared (it spans 1500 x 800 units)" \
        in said.out, said.out
    assert ("warning: the drawing declares no length unit this import reads ($INSUNITS "
            "0) and none was given: its lengths are read as they are, the blocks 350 units "
            "across (the median): in mm 0.35 m: give the drawing's unit with --length-unit"
            ) in said.err
    for given, unit in (("millimetres", "mm"), ("Meter", "m"), ("inches", "in")):
        assert main(["import-dxf", str(path), "-o", str(out), "--length-unit", given]) == 0
        assert read_scene(out).units.length == unit
        capsys.readouterr()
    assert main(["import-dxf", str(path), "-o", str(out), "--length-unit", "furlong"]) == 2
    assert "unknown length unit 'furlong' (known: in, ft, mm, cm, m, km, yd, dm)" in \
        capsys.readouterr().err
    # its depth example is a block's size in its units ("--depth 300 for 300 length unit"
    # of any drawing without a unit)
    assert main(["import-dxf", str(path), "-o", str(out), "--unit-weight", "1"]) == 0
    assert "e.g. import-dxf --depth 350 for 350 length units)" in capsys.readouterr().err
    # a unit the header gives that the import does not read ($INSUNITS 3, miles) was
    # "($INSUNITS 0)", "none declared"
    doc.header["$INSUNITS"] = 3
    doc.saveas(path)
    assert main(["import-dxf", str(path), "-o", str(out)]) == 0
    said = capsys.readouterr()
    assert "own units, $INSUNITS 3, no unit this import reads (it spans" in said.out
    assert "no length unit this import reads ($INSUNITS 3)" in said.err
    # a scene in feet exported and imported again: its unit in the header and back
    scene = read_scene(out)
    from dataclasses import replace as _replace

    from rigidblocks.io import write_scene
    from rigidblocks.scene.model import Units

    feet = tmp_path / "ft.json"
    write_scene(_replace(scene, units=Units("ft", "lbf")), feet)
    assert main(["export-dxf", str(feet), "-o", str(tmp_path / "ft.dxf")]) == 0
    assert ezdxf.readfile(tmp_path / "ft.dxf").header["$INSUNITS"] == 2
    capsys.readouterr()
    assert main(["import-dxf", str(tmp_path / "ft.dxf"), "-o", str(out)]) == 0
    assert "lengths in ft, as the drawing's scene records them" in capsys.readouterr().out


def test_export_of_a_3d_scene_is_refused_before_its_analysis(tmp_path, capsys, monkeypatch):
    """`export-dxf` of a 3D scene: one line, exit 2, and no analysis run first (it
    took the corbel dome's load analysis, 1.1 s CPU against 0.5 s, to say no)."""
    import rigidblocks.cli.plot as cli_plot

    def analyse(*args, **kwargs):
        raise AssertionError("the analysis ran before the refusal")

    monkeypatch.setattr(cli_plot, "analyse", analyse)
    assert main(["export-dxf", str(EXAMPLES / "box_stack_3d.json"), "--analysis", "load",
                 "-o", str(tmp_path / "a.dxf")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.endswith("DXF export is for 2D scenes") and len(err.splitlines()) == 1
    assert not (tmp_path / "a.dxf").exists()


def test_export_draws_the_thrust_line_of_a_chain_and_forces_on_the_lower_blocks(tmp_path):
    """The arch under its self-weight, a chain of voussoirs: one thrust line, and each
    joint's force arrow on its lower block, pointing down the ring to the abutments on
    both halves, as the pictures draw them (the export drew it on each joint's second
    block, up to the crown on one half)."""
    sc = read_scene(EXAMPLES / "arch.json")
    out = tmp_path / "arch.dxf"
    rb.io.dxf.write_dxf(sc, out, rb.min_friction(sc))
    msp = ezdxf.readfile(out).modelspace()
    (line,) = [e for e in msp if e.dxf.layer == "RB_THRUST_LINE"]
    assert line.dxftype() == "LWPOLYLINE"
    n = rb.detect_contacts(sc).n_joints
    assert len(line.get_points()) == n
    strokes = [e for e in msp if e.dxf.layer == "RB_FORCES"]
    shafts = strokes[::3]  # a shaft, then its two head strokes, per joint
    assert len(shafts) == n
    assert all(e.dxf.end[1] < e.dxf.start[1] for e in shafts)


def test_export_draws_no_arrow_on_an_open_joint(tmp_path):
    """The reference model with self-weight at its collapse: the joint between the two
    central blocks opens (no force but round-off), and drew an arrow of three strokes
    of no length; each loaded joint keeps its arrow and its resultant's circle."""
    from rigidblocks.results import unloaded

    sc = read_scene(EXAMPLES / "reference_self_weight.json")
    res = rb.max_load_multiplier(sc)
    is_open = unloaded(res.contacts, res.state)[0]
    assert is_open.any() and not is_open.all()
    out = tmp_path / "ref.dxf"
    rb.io.dxf.write_dxf(sc, out, res)
    msp = ezdxf.readfile(out).modelspace()
    strokes = [e for e in msp if e.dxf.layer == "RB_FORCES"]
    assert len(strokes) == 3 * int((~is_open).sum())
    assert all(math.dist(e.dxf.start, e.dxf.end) > 0 for e in strokes)
    assert len([e for e in msp if e.dxf.layer == "RB_THRUST_LINE"]) == int((~is_open).sum())


def test_a_layer_that_holds_nothing_and_a_drawing_given_as_a_scene_are_named(
        tmp_path, capsys):
    """--layers NOPE said "no polylines or lines: nothing to make blocks of" of a
    drawing full of them (on layer 0); `load drawing.dxf` said "malformed JSON: Extra
    data at line 2 column 1". Each names what is wrong and what to do."""
    doc = ezdxf.new()
    msp = doc.modelspace()
    msp.add_lwpolyline([(-1, -1), (3, -1), (3, 0), (-1, 0)], close=True)
    msp.add_lwpolyline([(0, 0), (1, 0), (1, 2), (0, 2)], close=True)
    path = tmp_path / "d.dxf"
    doc.saveas(path)
    assert main(["import-dxf", str(path), "-o", str(tmp_path / "d.json"), "--layers",
                 "NOPE"]) == 2
    assert f"{path}: layers: no polylines or lines on the layer(s) NOPE (layers with " \
        "some: 0)" in capsys.readouterr().err
    # one of several named empty (it was read without a word), and names as DXF compares
    # them, without case
    assert main(["import-dxf", str(path), "-o", str(tmp_path / "d.json"), "--layers",
                 "0,NOPE"]) == 2
    assert "no polylines or lines on the layer(s) NOPE" in capsys.readouterr().err
    doc.layers.add("WALLS")
    for e in msp:
        e.dxf.layer = "WALLS"
    doc.saveas(path)
    assert main(["import-dxf", str(path), "-o", str(tmp_path / "d.json"), "--layers",
                 "walls"]) == 0
    assert main(["load", str(path)]) == 2
    assert f"{path}: a DXF drawing, not a scene file: make its scene with `rigidblocks " \
        f"import-dxf {path} -o SCENE.json`" in capsys.readouterr().err
    # one that opens with a comment, and a binary one (malformed JSON; cannot read)
    commented = tmp_path / "c.dxf"
    commented.write_bytes(b"999\r\ndxfrw 0.6.3\r\n" + path.read_bytes())
    binary = tmp_path / "b.dxf"
    doc.saveas(binary, fmt="bin")
    for drawing in (commented, binary):
        assert main(["check", str(drawing)]) == 2
        assert "a DXF drawing, not a scene file" in capsys.readouterr().err


def _wall(msp, mirror=False, **attribs):
    """A base 3 x 1 and a block 1 x 2 standing on it at x in [0, 1] (world
    coordinates); ``mirror``: each drawn as CAD draws it mirrored, in the coordinate
    system of the extrusion (0, 0, -1), whose x is the world's -x."""
    s = -1.0 if mirror else 1.0
    extra = {"extrusion": (0, 0, -1)} if mirror else {}
    for pts in ([(-1, -1), (2, -1), (2, 0), (-1, 0)], [(0, 0), (1, 0), (1, 2), (0, 2)]):
        msp.add_lwpolyline([(s * x, y) for x, y in pts], close=True,
                           dxfattribs={**attribs, **extra})


def test_a_mirrored_polyline_is_read_where_it_lies_in_the_world(tmp_path):
    """A polyline CAD drew in a mirrored coordinate system (extrusion (0, 0, -1)) was
    read in its own coordinates: the mirror image of the drawing, the LACT3 portal's
    multiplier 0.528994 where the drawing's is 0.516365, with no word. Its world
    coordinates are read; one drawn in another plane (a vertical one) is refused."""
    for mirror in (False, True):
        doc = ezdxf.new()
        _wall(doc.modelspace(), mirror)
        doc.saveas(tmp_path / "w.dxf")
        sc = rb.read_dxf(tmp_path / "w.dxf")
        xs = sorted(float(np.asarray(b.vertices)[:, 0].min()) for b in sc.blocks)
        assert xs == [-1.0, 0.0], (mirror, xs)
    doc = ezdxf.new()
    doc.modelspace().add_lwpolyline([(0, 0), (1, 0), (1, 1), (0, 1)], close=True,
                                    dxfattribs={"extrusion": (0, 1, 0)})
    doc.saveas(tmp_path / "v.dxf")
    with pytest.raises(InputError, match=r"LWPOLYLINE #\w+: not drawn in the x-y plane: "
                                         r"its z varies by 1 over an outline 1 across"):
        rb.read_dxf(tmp_path / "v.dxf")


def test_block_references_are_read_and_hidden_layers_are_not(tmp_path):
    """A block reference (INSERT of a brick drawn once) was skipped, its bricks missing
    (counted only in the summary line; with one polyline beside two references: "no
    free block"); a layer switched off in CAD (construction lines) was read as blocks.
    References are exploded (placed, scaled, mirrored as CAD places them), hidden
    layers skipped and counted; a layer named with --layers is read all the same."""
    doc = ezdxf.new()
    msp = doc.modelspace()
    msp.add_lwpolyline([(-1, -1), (3, -1), (3, 0), (-1, 0)], close=True)
    brick = doc.blocks.new("BRICK")
    brick.add_lwpolyline([(0, 0), (1, 0), (1, 0.5), (0, 0.5)], close=True)
    msp.add_blockref("BRICK", (0, 0))
    msp.add_blockref("BRICK", (2, 0), dxfattribs={"xscale": -1})  # mirrored: x in [1, 2]
    doc.layers.add("DRAFT").off()
    msp.add_lwpolyline([(0, 0), (3, 0), (3, 3)], close=True, dxfattribs={"layer": "DRAFT"})
    doc.saveas(tmp_path / "r.dxf")
    sc, rep = rb.read_dxf(tmp_path / "r.dxf", report=True)
    xs = [np.asarray(b.vertices)[:, 0] for b in sc.blocks if not b.support]
    boxes = sorted((float(x.min()), float(x.max())) for x in xs)
    assert boxes == [(0.0, 1.0), (1.0, 2.0)]
    assert rep.skipped == {"LWPOLYLINE (on a layer switched off or frozen: DRAFT)": 1}
    with pytest.raises(InputError, match="overlap"):  # named: read, the triangle overlaps
        rb.read_dxf(tmp_path / "r.dxf", layers=["0", "DRAFT"])


def test_a_unit_given_to_a_restored_scene_is_checked_against_its_own(tmp_path, capsys):
    """`import-dxf P.dxf --force-unit N` of a drawing exported from a scene in mm and kN
    wrote units {"force": "N"}: the length unit dropped and the unit weight, stored in kN,
    relabelled (`load` said 0.06642 N for 0.06642 kN). A unit that differs from the
    stored scene's is refused; one that agrees keeps the other."""
    dxf = tmp_path / "w.dxf"
    assert main(["export-dxf", str(EXAMPLES / "wall.json"), "-o", str(dxf)]) == 0
    out = tmp_path / "w.json"
    assert main(["import-dxf", str(dxf), "-o", str(out), "--force-unit", "N"]) == 2
    err = capsys.readouterr().err
    assert "the drawing's scene is in kN (force unit): --force-unit N would relabel" in err
    assert main(["import-dxf", str(dxf), "-o", str(out), "--length-unit", "mm"]) == 2
    assert main(["import-dxf", str(dxf), "-o", str(out), "--force-unit", "kN"]) == 0
    assert json.loads(out.read_text())["units"] == {"length": "m", "force": "kN"}


def test_import_with_a_live_body_force_writes_load_factor_0(tmp_path, capsys):
    """import-compas and the generators write load_factor 0 beside a seismic body force,
    so that check and friction answer for the weight alone; import-dxf wrote none (1),
    and `check` right after importing a drawing said NOT ADMISSIBLE (at 1 g sideways).
    A body force of nothing is refused, as import-compas refuses it."""
    path = quirky_drawing(tmp_path / "q.dxf")
    out = tmp_path / "q.json"
    assert main(["import-dxf", str(path), "-o", str(out), "--supports", "layer:SUPPORT",
                 "--unit-weight", "1", "--live-body-force", "1 0"]) == 0
    assert "load factor 0 written" in capsys.readouterr().out
    assert read_scene(out).load_factor == 0.0
    assert main(["import-dxf", str(path), "-o", str(out), "--live-body-force", "0 0"]) == 2
    assert "not both zero" in capsys.readouterr().err


def test_references_are_placed_by_their_transformation_and_grids_expanded(tmp_path):
    """A 2 x 1 brick turned by 90 deg inside a reference scaled 2 in y: CAD shows a 1 x 4
    pier, the exploded entities read a 2 x 2 block (at infinite friction lambda* = 1
    where the pier tips at 0.25); a MINSERT grid of 2 x 2 bricks read one brick, with
    "skipped none"; an invisible entity was read; a reference on a layer switched off
    hid the bricks it places on their own visible layer, which CAD shows."""
    doc = ezdxf.new()
    msp = doc.modelspace()
    msp.add_lwpolyline([(-3, -1), (3, -1), (3, 0), (-3, 0)], close=True)
    r = doc.blocks.new("R")
    r.add_lwpolyline([(0, 0), (2, 0), (2, 1), (0, 1)], close=True)
    s = doc.blocks.new("S")
    s.add_blockref("R", (0, 0), dxfattribs={"rotation": 90})
    msp.add_blockref("S", (0, 0), dxfattribs={"yscale": 2})
    doc.saveas(tmp_path / "nest.dxf")
    (b,) = [b for b in rb.read_dxf(tmp_path / "nest.dxf").blocks if not b.support]
    v = np.asarray(b.vertices)
    assert np.allclose([v[:, 0].min(), v[:, 0].max(), v[:, 1].min(), v[:, 1].max()],
                       [-1, 0, 0, 4], atol=1e-12)
    doc = ezdxf.new()
    msp = doc.modelspace()
    msp.add_lwpolyline([(-2, -1), (3, -1), (3, 0), (-2, 0)], close=True)
    q = doc.blocks.new("Q")
    doc.layers.add("STONE")
    q.add_lwpolyline([(0, 0), (0.5, 0), (0.5, 0.5), (0, 0.5)], close=True,
                     dxfattribs={"layer": "STONE"})
    doc.layers.add("OFF").off()
    msp.add_blockref("Q", (0, 0), dxfattribs={"column_count": 2, "column_spacing": 0.5,
                                               "row_count": 2, "row_spacing": 0.5,
                                               "layer": "OFF"})
    msp.add_lwpolyline([(2, 0), (2.5, 0), (2.5, 1), (2, 1)], close=True,
                       dxfattribs={"invisible": 1})
    doc.saveas(tmp_path / "grid.dxf")
    sc, rep = rb.read_dxf(tmp_path / "grid.dxf", report=True)
    assert sum(not b.support for b in sc.blocks) == 4
    assert rep.skipped == {"LWPOLYLINE (invisible)": 1}


def test_the_block_size_doubt_reads_the_free_blocks(tmp_path, capsys):
    """A 1 x 2 m block on a 5 m base, drawn in metres: "the blocks are 3.5 m across (the
    median)" counted the base, and warned of blocks no masonry has."""
    doc = ezdxf.new()
    doc.header["$INSUNITS"] = 6
    msp = doc.modelspace()
    msp.add_lwpolyline([(-2, -1), (3, -1), (3, 0), (-2, 0)], close=True)
    msp.add_lwpolyline([(0, 0), (1, 0), (1, 2), (0, 2)], close=True)
    doc.saveas(tmp_path / "b.dxf")
    assert main(["import-dxf", str(tmp_path / "b.dxf"), "-o", str(tmp_path / "b.json"),
                 "--unit-weight", "20"]) == 0
    assert "across (the median)" not in capsys.readouterr().err
