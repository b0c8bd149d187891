"""The scene file contract (docs/scene-format.md): strict reading, clear errors, round-trip.

Every rejected input must raise :class:`InputError` with one line that names the file
and the block id or key at fault; the CLI turns it into exit status 2 and one line on
standard error.
"""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path

import numpy as np
import pytest
from conftest import EXAMPLES, make_scene, rect

import rigidblocks as rb
from rigidblocks.cli.main import main
from rigidblocks.contacts import detect_contacts
from rigidblocks.equilibrium import assemble
from rigidblocks.errors import InputError
from rigidblocks.io.scene_file import dumps_scene, read_scene, write_scene


def base_doc() -> dict:
    """The example of docs/scene-format.md: two blocks on a base, with loads."""
    return {
        "format": "rigidblocks-scene", "version": 1, "name": "two blocks on a base",
        "dimension": 2, "units": {"length": "m", "force": "kN"}, "depth": 1.0,
        "unit_weight": 20.0, "friction": 0.6,
        "blocks": [
            {"id": "base", "vertices": rect(0, 0, 2, 0.5), "support": True},
            {"id": "A", "vertices": rect(0.5, 0.5, 1, 0.5)},
            {"id": "B", "vertices": rect(0.5, 1.0, 1, 0.5)},
        ],
        "loads": [
            {"block": "B", "force": [0, -10], "point": [1.0, 1.5]},
            {"block": "B", "force": [1, 0], "point": [1.0, 1.5], "live": True},
        ],
        "joints": [{"blocks": ["A", "B"], "friction": 0.4}],
    }


def write_doc(tmp_path: Path, doc, name: str = "scene.json") -> Path:
    path = tmp_path / name
    path.write_text(doc if isinstance(doc, str) else json.dumps(doc), encoding="utf-8")
    return path


def expect_error(path: Path, *names: str) -> str:
    """Read ``path``, expect an InputError naming the file and every one of ``names``."""
    with pytest.raises(InputError) as info:
        read_scene(path)
    msg = str(info.value)
    assert "\n" not in msg
    assert str(path) in msg, msg
    for n in names:
        assert n in msg, f"{n!r} not in {msg!r}"
    return msg


def test_base_doc_is_valid(tmp_path):
    scene = read_scene(write_doc(tmp_path, base_doc()))
    assert [b.id for b in scene.blocks] == ["base", "A", "B"]
    assert scene.friction == 0.6 and scene.loads[1].is_live


# -- structure --------------------------------------------------------------------------
def test_malformed_json(tmp_path):
    text = json.dumps(base_doc())[:-5]
    msg = expect_error(write_doc(tmp_path, text), "malformed JSON")
    assert "line 1" in msg
    # json's own message ends in "at" before its position ("starting at at line 1")
    msg = expect_error(write_doc(tmp_path, text[:40]), "Unterminated string starting at line 1")
    assert " at at " not in msg


@pytest.mark.parametrize("key, value", [("format", "rigidblocks"), ("version", 2),
                                        ("version", "1"), ("dimension", 4)])
def test_wrong_format_version_dimension(tmp_path, key, value):
    doc = base_doc()
    doc[key] = value
    expect_error(write_doc(tmp_path, doc), f'"{key}"')


def mutate(path_in_doc, key, value=1):
    """A function that adds ``key: value`` to the object at ``path_in_doc``."""

    def apply(doc):
        obj = doc
        for p in path_in_doc:
            obj = obj[p]
        obj[key] = value

    return apply


@pytest.mark.parametrize("where, names", [
    ((), ["frction"]),
    (("blocks", 1), ["frction", "block 'A'"]),
    (("loads", 0), ["frction", "load #0"]),
    (("joints", 0), ["frction", "joint #0"]),
    (("units",), ["frction", "units"]),
])
def test_unknown_key(tmp_path, where, names):
    doc = base_doc()
    mutate(where, "frction", 0.3)(doc)
    expect_error(write_doc(tmp_path, doc), *names)


@pytest.mark.parametrize("where, key, names", [
    ((), "blocks", ['"blocks"']),
    ((), "format", ['"format"']),
    ((), "dimension", ['"dimension"']),
    (("blocks", 2), "vertices", ['"vertices"', "block 'B'"]),
    (("blocks", 2), "id", ['"id"', "block #2"]),
    (("loads", 1), "force", ['"force"', "load #1"]),
    (("joints", 0), "blocks", ['"blocks"', "joint #0"]),
])
def test_missing_key(tmp_path, where, key, names):
    doc = base_doc()
    obj = doc
    for p in where:
        obj = obj[p]
    del obj[key]
    expect_error(write_doc(tmp_path, doc), *names)


@pytest.mark.parametrize("value", ["0.5", None, [0.5], True])
def test_non_numeric_coordinate(tmp_path, value):
    doc = base_doc()
    doc["blocks"][1]["vertices"][2][0] = value
    expect_error(write_doc(tmp_path, doc), "block 'A'", '"vertices"[2]')


@pytest.mark.parametrize("literal", ["NaN", "Infinity", "-Infinity", "1e999"])
def test_non_finite_coordinate_literal(tmp_path, literal):
    """JSON literals NaN / Infinity (and 1e999, which overflows to inf) are rejected."""
    doc = base_doc()
    doc["blocks"][2]["vertices"][1][1] = 12345.0
    text = json.dumps(doc).replace("12345.0", literal)
    assert literal in text
    expect_error(write_doc(tmp_path, text), "block 'B'", '"vertices"[1]', "finite")


def test_non_finite_load_and_scene_values(tmp_path):
    doc = base_doc()
    doc["loads"][0]["force"][1] = 12345.0
    text = json.dumps(doc).replace("12345.0", "NaN")
    expect_error(write_doc(tmp_path, text), "load #0", '"force"')
    doc = base_doc()
    doc["friction"] = 12345.0
    text = json.dumps(doc).replace("12345.0", "Infinity")
    expect_error(write_doc(tmp_path, text), '"friction"')


def test_non_finite_in_dict_rejected():
    """The same check applies to documents built in code (float('nan'))."""
    with pytest.raises(InputError, match="block 'B'.*finite"):
        make_scene([{"id": "base", "vertices": rect(0, -1, 3, 1), "support": True},
                    {"id": "B", "vertices": [[0, 0], [1, 0], [1, float("nan")], [0, 1]]}])


# -- polygons -----------------------------------------------------------------------------
def test_fewer_than_three_vertices(tmp_path):
    doc = base_doc()
    doc["blocks"][1]["vertices"] = [[0.5, 0.5], [1.5, 0.5]]
    expect_error(write_doc(tmp_path, doc), "block 'A'", "at least 3 vertices")


def test_zero_area_polygon(tmp_path):
    doc = base_doc()
    doc["blocks"][1]["vertices"] = [[0.5, 0.5], [1.0, 0.5], [1.5, 0.5]]
    expect_error(write_doc(tmp_path, doc), "block 'A'", "zero area")


def test_self_intersecting_polygon(tmp_path):
    """A bow tie: edges (0.5,0.5)-(1.5,1) and (1.5,0.5)-(0.5,1) cross (zero net area
    would be caught earlier, so the bow tie is made lopsided)."""
    doc = base_doc()
    doc["blocks"][1]["vertices"] = [[0.5, 0.5], [1.5, 1.0], [1.5, 0.5], [0.5, 0.9]]
    expect_error(write_doc(tmp_path, doc), "block 'A'", "self-intersecting")


# -- semantics ------------------------------------------------------------------------
def test_duplicate_ids(tmp_path):
    doc = base_doc()
    doc["blocks"][2]["id"] = "A"
    expect_error(write_doc(tmp_path, doc), "block 'A'", "duplicate")


def test_load_on_support(tmp_path):
    doc = base_doc()
    doc["loads"][1]["block"] = "base"
    expect_error(write_doc(tmp_path, doc), "load #1", "'base'", "support")


def test_load_on_unknown_block(tmp_path):
    doc = base_doc()
    doc["loads"][0]["block"] = "Z"
    expect_error(write_doc(tmp_path, doc), "load #0", "'Z'", "unknown")


def test_no_support_block(tmp_path):
    doc = base_doc()
    del doc["blocks"][0]["support"]
    expect_error(write_doc(tmp_path, doc), "no support block", '"support"')


def test_no_blocks_at_all(tmp_path):
    """An empty blocks list says so (it read "no support block")."""
    doc = base_doc()
    doc["blocks"] = []
    doc["loads"] = []
    expect_error(write_doc(tmp_path, doc), "no blocks", '"blocks" list is empty')


def test_no_free_block(tmp_path):
    doc = base_doc()
    for b in doc["blocks"]:
        b["support"] = True
    del doc["loads"]
    expect_error(write_doc(tmp_path, doc), "no free block")


def test_overlapping_blocks_names_both(tmp_path):
    doc = base_doc()
    doc["blocks"][2]["vertices"] = rect(0.5, 0.9, 1, 0.5)  # 0.1 into A
    expect_error(write_doc(tmp_path, doc), "'A'", "'B'", "overlap")


def test_touching_blocks_are_not_overlapping(tmp_path):
    doc = base_doc()
    doc["blocks"].append({"id": "C", "vertices": rect(1.5, 0.5, 0.5, 0.5)})  # beside A
    read_scene(write_doc(tmp_path, doc))


def test_joint_override_between_non_touching_blocks(tmp_path):
    doc = base_doc()
    doc["joints"] = [{"blocks": ["base", "B"], "friction": 0.2}]
    expect_error(write_doc(tmp_path, doc), "'base'", "'B'", "not in contact")


def test_joint_override_unknown_block(tmp_path):
    doc = base_doc()
    doc["joints"] = [{"blocks": ["A", "Q"]}]
    expect_error(write_doc(tmp_path, doc), "'Q'", "unknown")


# -- CLI ---------------------------------------------------------------------------------
@pytest.mark.parametrize("case", ["unknown_key", "overlap", "missing_file", "nan"])
def test_cli_bad_input_exit_2_one_line(tmp_path, capsys, case):
    doc = base_doc()
    if case == "unknown_key":
        doc["blocks"][1]["frction"] = 0.1
        path, names = write_doc(tmp_path, doc), ["frction", "block 'A'"]
    elif case == "overlap":
        doc["blocks"][2]["vertices"] = rect(0.5, 0.9, 1, 0.5)
        path, names = write_doc(tmp_path, doc), ["'A'", "'B'"]
    elif case == "nan":
        doc["blocks"][2]["vertices"][1][1] = 12345.0
        path = write_doc(tmp_path, json.dumps(doc).replace("12345.0", "NaN"))
        names = ["block 'B'"]
    else:
        path, names = tmp_path / "absent.json", ["no such file"]
    assert main(["check", str(path)]) == 2
    out, err = capsys.readouterr()
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    assert str(path) in lines[0]
    for n in names:
        assert n in lines[0]


# -- round trip ----------------------------------------------------------------------
def example_files() -> list[Path]:
    return sorted(EXAMPLES.glob("*.json"))


@pytest.mark.parametrize("path", example_files(), ids=lambda p: p.name)
def test_examples_round_trip(path):
    """write(read(file)) reproduces every bundled example's text exactly."""
    text = path.read_text(encoding="utf-8")
    scene = read_scene(path)
    assert dumps_scene(scene) == text


def test_generated_scene_round_trip(tmp_path):
    """A scene written by the writer reads back equal and re-writes to the same text
    (always runs, whether or not examples/ holds any file yet)."""
    first = write_doc(tmp_path, base_doc(), "input.json")
    scene = read_scene(first)
    out = tmp_path / "canonical.json"
    write_scene(scene, out)
    text = out.read_text(encoding="utf-8")
    again = read_scene(out)
    assert again == scene
    assert dumps_scene(again) == text
    # the canonical layout: one block per line
    assert sum(1 for line in text.splitlines() if '"id"' in line) == 3


def test_round_trip_keeps_optional_keys_absent(tmp_path):
    doc = {"format": "rigidblocks-scene", "version": 1, "dimension": 2,
           "blocks": [{"id": "s", "vertices": rect(0, -1, 2, 1), "support": True},
                      {"id": "b", "vertices": rect(0, 0, 1, 1), "unit_weight": 3}]}
    scene = read_scene(write_doc(tmp_path, doc))
    assert scene.friction is None and scene.depth is None
    out = json.loads(dumps_scene(scene))
    assert out == doc


# -- orientation ---------------------------------------------------------------------
def _stack_doc(clockwise: set[str]) -> dict:
    doc = base_doc()
    for b in doc["blocks"]:
        if b["id"] in clockwise:
            b["vertices"] = b["vertices"][::-1]
    return doc


def _contact_set(scene):
    c = detect_contacts(scene)
    out = []
    for k in range(c.n_joints):
        pts = c.points[c.joint_start[k]:c.joint_start[k + 1]]
        out.append((tuple(c.pairs[k]), tuple(np.round(c.normals[k], 12)),
                    tuple(sorted(map(tuple, np.round(pts, 12)))), round(c.areas[k], 12)))
    return sorted(out)


@pytest.mark.parametrize("clockwise", [{"A"}, {"base", "B"}, {"base", "A", "B"}])
def test_clockwise_and_counter_clockwise_agree(tmp_path, clockwise):
    """Orientation is normalised by the reader: same joints, normals, points, areas and
    the same equilibrium system (up to the order of columns within a joint)."""
    ccw = read_scene(write_doc(tmp_path, _stack_doc(set()), "ccw.json"))
    cw = read_scene(write_doc(tmp_path, _stack_doc(clockwise), "cw.json"))
    assert _contact_set(ccw) == _contact_set(cw)
    s1, s2 = assemble(ccw), assemble(cw)
    np.testing.assert_allclose(s1.dead, s2.dead, atol=1e-12)
    np.testing.assert_allclose(s1.live, s2.live, atol=1e-12)
    np.testing.assert_allclose(s1.centroids, s2.centroids, atol=1e-12)
    cols1 = sorted(map(tuple, np.round(s1.A.toarray().T, 12)))
    cols2 = sorted(map(tuple, np.round(s2.A.toarray().T, 12)))
    assert cols1 == cols2
    # and the same least-squares reactions of A x = -F (unique: A is square here)
    x1 = np.linalg.lstsq(s1.A.toarray(), -s1.dead, rcond=None)[0]
    x2 = np.linalg.lstsq(s2.A.toarray(), -s2.dead, rcond=None)[0]
    np.testing.assert_allclose(np.sort(x1), np.sort(x2), atol=1e-9)


def test_clockwise_same_min_friction(tmp_path):
    """The minimum friction of a pulled block does not depend on vertex order."""
    from rigidblocks.analyses import min_friction

    doc = copy.deepcopy(_stack_doc(set()))
    del doc["joints"]
    a = min_friction(read_scene(write_doc(tmp_path, doc, "a.json")), state=False)
    doc_cw = _stack_doc({"A", "B", "base"})
    del doc_cw["joints"]
    b = min_friction(read_scene(write_doc(tmp_path, doc_cw, "b.json")), state=False)
    assert a.status == b.status
    assert a.friction_factor == pytest.approx(b.friction_factor, rel=1e-6, abs=1e-9)


def test_block_inside_another_is_an_overlap(tmp_path):
    """A small block wholly inside A (no edge crossing) still overlaps it."""
    doc = base_doc()
    doc["blocks"].append({"id": "C", "vertices": rect(0.8, 0.6, 0.2, 0.2)})
    expect_error(write_doc(tmp_path, doc), "'A'", "'C'", "overlap")


def test_slight_overlap_of_side_by_side_blocks(tmp_path):
    """Blocks side by side whose boxes share a sliver of 1e-3 x their height: an
    overlap of 1e-4 of the smaller block's area is more than round-off."""
    doc = base_doc()
    doc["blocks"].append({"id": "C", "vertices": rect(1.499, 0.5, 0.5, 0.5)})
    expect_error(write_doc(tmp_path, doc), "'A'", "'C'", "overlap")


def _cube_doc(faces) -> dict:
    """A 3D scene: a unit cube with the given faces on a support slab."""
    cube = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
            [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]
    good = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6],
            [3, 0, 4, 7]]
    slab = [[x, y, z - 1] for x, y, z in cube]
    return {"format": "rigidblocks-scene", "version": 1, "dimension": 3,
            "unit_weight": 1.0, "friction": 0.6,
            "blocks": [{"id": "slab", "vertices": slab, "faces": good, "support": True},
                       {"id": "cube", "vertices": cube, "faces": faces}]}


@pytest.mark.parametrize("bad,k", [(8, 2), (-1, 2), (True, 2), (1.0, 2), ("1", 2)])
def test_a_bad_vertex_index_of_a_face_is_named(tmp_path, bad, k):
    faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, bad, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6],
             [3, 0, 4, 7]]
    expect_error(write_doc(tmp_path, _cube_doc(faces)), "block 'cube'", f'"faces"[{k}]',
                 "0..7")


@pytest.mark.parametrize("face", [[0, 1], "0 1 2", None])
def test_a_face_that_is_not_a_list_of_three_indices_is_named(tmp_path, face):
    faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], face, [2, 3, 7, 6], [3, 0, 4, 7]]
    expect_error(write_doc(tmp_path, _cube_doc(faces)), "block 'cube'", '"faces"[3]')


def _in_code(**changes):
    """A block 1 x 2 on a base, built in code as the Python API's users do."""
    from rigidblocks import make_block

    base = make_block("base", [[-1, -1], [4, -1], [4, 0], [-1, 0]], support=True)
    b = make_block("B", [[0, 0], [1, 0], [1, 2], [0, 2]])
    d = dict(dimension=2, blocks=(base, b), unit_weight=20.0, friction=0.8,
             live_body_force=(1.0, 0.0))
    return rb.Scene(**{**d, **changes})


@pytest.mark.parametrize("changes,said", [
    ({"blocks": "overlap"}, "block 'B': blocks 'B' and 'C' overlap"),
    ({"blocks": "twice"}, "block 'B': duplicate block id"),
    ({"unit_weight": -1}, "unit_weight: must be a number >= 0, got -1"),
    ({"unit_weight": math.nan}, "unit_weight: must be a number >= 0, got nan"),
    # (each was "... reaches nan, beyond 1e+150 ... give the scene in other units")
    ({"unit_weight": math.inf}, "unit_weight: it must be finite, got inf"),
    ({"live_body_force": (math.nan, 0.0)}, "live_body_force: it must be finite, got (nan"),
    ({"loads": (rb.Load("B", (math.nan, 0.0)),)}, "load #0: force must be finite"),
    ({"loads": (rb.Load("B", (1.0, 0.0), point=(math.nan, 0.0)),)},
     "load #0: point must be finite"),
    # (a scipy traceback, or answers with a RuntimeWarning)
    ({"joints": (rb.JointOverride(("base", "B"), cohesion=math.inf),)},
     "joint 'base'-'B': cohesion must be finite, got inf"),
    ({"joints": (rb.JointOverride(("base", "B"), tensile_strength=math.inf),)},
     "joint 'base'-'B': tensile_strength must be finite, got inf"),
    ({"live_body_force": (1, 0, 0)}, "live_body_force: must be 2 numbers in a 2D scene"),
    ({"flow": "x"}, 'flow: flow must be "associative" or "non-associative", got \'x\''),
    ({"friction": "0.3"}, 'friction: friction must be a number >= 0 or "infinite"'),
    ({"dimension": 4}, "dimension: must be 2 or 3, got 4"),
    ({"loads": (rb.Load("Z", (0.0, -1.0)),)}, "load #0: unknown block 'Z'"),
    ({"blocks": ()}, 'blocks: no blocks: the scene\'s "blocks" list is empty'),
    # (live="false" was live, lambda* 2.67 for 2.0; support="no" made a support; a 2D
    # scene's 3D moment ended in a numpy broadcast error)
    ({"loads": (rb.Load("B", (0.0, -10.0), live="false"),)},
     "load #0: live must be True, False or None, got 'false'"),
    ({"blocks": "support no"}, "block 'B': support must be True or False, got 'no'"),
    ({"loads": (rb.Load("B", (1.0, 0.0), moment=(0, 0, 1)),)},
     "load #0: moment must be a number in a 2D scene, got (0, 0, 1)"),
    ({"joints": (rb.JointOverride("Bbase"),)},
     "joints: a joint override names two block ids, got 'Bbase'"),
    # ("'str' object has no attribute 'length'": the tuple is what a result's units are)
    ({"units": "m"}, "units: expected rigidblocks.Units(length=\"m\", force=\"kN\"), got 'm'"),
    ({"units": ("m", "kN")}, "units: expected rigidblocks.Units("),
    ({"units": rb.Units("m", 1)}, "got Units(length='m', force=1)"),
    # (read "polygon has zero area (its vertices are collinear ...": the reader's words)
    ({"blocks": "two vertices"}, "block 'B': needs at least 3 vertices, got 2"),
])
def test_a_scene_built_in_code_is_checked_as_a_files_is(changes, said):
    """The analyses took a scene built in code as given: two overlapping blocks
    collapsed at 0.5 and stood at load factor 0, a block given twice was analysed with
    its joint twice, a unit weight of -1 or NaN, a 2D scene's 3D live body force or a
    flow "x" gave answers, and an unknown block, no blocks or dimension 4 ended in
    tracebacks (KeyError, ValueError) where a scene file's reader names the fault in one
    line. Every analysis now checks its scene as the reader does."""
    from rigidblocks import make_block

    if changes.get("blocks") == "overlap":
        base, b = _in_code().blocks
        changes = {"blocks": (base, b, make_block("C", [[0.5, 0], [1.5, 0], [1.5, 2],
                                                        [0.5, 2]]))}
    elif changes.get("blocks") == "twice":
        base, b = _in_code().blocks
        changes = {"blocks": (base, b, b)}
    elif changes.get("blocks") == "two vertices":
        changes = {"blocks": (_in_code().blocks[0], make_block("B", [[0, 0], [1, 0]]))}
    elif changes.get("blocks") == "support no":
        base, b = _in_code().blocks
        changes = {"blocks": (base, make_block("B", b.vertices, support="no"))}
    scene = _in_code(**changes)
    for analysis in (rb.check, rb.min_friction, rb.max_load_multiplier, rb.load_path):
        with pytest.raises(InputError) as err:
            analysis(scene)
        assert said in str(err.value), (analysis.__name__, str(err.value))
    assert rb.max_load_multiplier(_in_code()).load_multiplier == pytest.approx(0.5)


@pytest.mark.parametrize("given", ["examples/arch.json", {}])
def test_an_analysis_of_what_is_not_a_scene_says_so(given):
    """`rb.check("examples/arch.json")` ended in AttributeError ('str' object has no
    attribute 'effective_flow')."""
    with pytest.raises(InputError, match=r"expected a Scene \(rigidblocks.read_scene\(path\), "
                       rf"or Scene\(...\) in code\), got {type(given).__name__}"):
        rb.check(given)


def test_a_load_factor_is_a_number_not_its_spelling():
    """`rb.check(scene, load_factor="0.6")` ran as 0.6 and `load_factor=True` as 1,
    where the type hint says float and a scene file refuses "0.5"."""
    for given in ("0.6", True):
        with pytest.raises(InputError, match="load factor must be an int or float"):
            rb.check(_in_code(), load_factor=given)
    # a friction may be spelt (the command line gives "0.3" or "infinite"), not a bool
    with pytest.raises(InputError, match='friction must be a number >= 0 or "infinite", '
                       "got True"):
        rb.check(_in_code(), friction=True)
    assert rb.check(_in_code(), friction="0.3", load_factor=0.2).status == "admissible"


def test_make_block_refuses_points_of_unequal_length():
    """A point of three numbers among 2D ones ended in numpy's "setting an array
    element with a sequence"."""
    from rigidblocks import make_block

    with pytest.raises(InputError, match="block 'B': vertices must be a list of points "
                       "of equal length, each of numbers"):
        make_block("B", [[0, 0], [1, 0, 0], [1, 2], [0, 2]])


@pytest.mark.parametrize("faces,nan,said", [
    # (1.9 was taken as 1 and answered; a string or None ended in ValueError, TypeError)
    ("1.9", False, "block 'B': a face's vertex index must be an integer, got 1.9"),
    ("x", False, "block 'B': \"faces\"[0] must list at least 3 vertex indices in 0..7"),
    ("none", False, "block 'B': \"faces\"[0] must list at least 3 vertex indices in 0..7"),
    (5, False, "block 'B': \"faces\" must be a list of at least 4 faces"),
    (None, False, "block 'B': missing \"faces\" (required for 3D blocks)"),
    ((), False, "block 'B': \"faces\" must be a list of at least 4 faces"),
    ("range", False, "block 'B': \"faces\"[0] must list at least 3 vertex indices in 0..7"),
    ("box", True, "block 'B': expected finite coordinates, got nan"),
])
def test_a_3d_block_built_in_code_is_checked_as_a_files_is(faces, nan, said):
    """A 3D block made in code without faces ended in numpy's "need at least one array
    to concatenate", a face index out of range in an IndexError, and a NaN coordinate
    was "beyond 1e+150 ... give the scene in other units"; the scene file's reader names
    each in one line, as the analyses now do."""
    from rigidblocks import make_block
    from rigidblocks.generators.solids import box

    v, f = box(0, 0, 0, 1, 1, 1)
    if nan:
        v = [[math.nan, 0.0, 0.0], *v[1:]]
    given = {"box": f, "range": [[0, 3, 2, 99], *f[1:]], "1.9": [[0, 3, 2, 1.9], *f[1:]],
             "x": [[0, 3, 2, "x"], *f[1:]], "none": [[0, 3, 2, None], *f[1:]]}.get(
        faces, faces) if isinstance(faces, str | type(None)) else faces
    bv, bf = box(-1, -1, -1, 3, 3, 1)
    with pytest.raises(InputError) as err:
        scene = rb.Scene(dimension=3, blocks=(make_block("base", bv, support=True, faces=bf),
                                              make_block("B", v, faces=given)),
                         unit_weight=1.0, friction=0.5, live_body_force=(1.0, 0.0, 0.0))
        rb.max_load_multiplier(scene)
    assert said in str(err.value), str(err.value)
    # a Block built with lists of lists, an array, a tuple of arrays (make_block builds
    # tuples; an array read as "not a list of at least 4 faces", arrays in a tuple as a
    # bad face 0)
    import numpy as np

    verts = tuple(map(tuple, box(0, 0, 0, 1, 1, 1)[0]))
    for faces in ([list(x) for x in f], np.array(f), tuple(np.array(x) for x in f)):
        with pytest.raises(InputError, match="a Block's faces are tuples of vertex indices"):
            rb.check(rb.Scene(dimension=3, blocks=(make_block(
                "base", bv, support=True, faces=bf), rb.Block("B", verts, faces))))
    # make_block takes arrays, and names a fractional index as a number
    with pytest.raises(InputError, match="a face's vertex index must be an integer, got 0.5$"):
        make_block("B", verts, faces=np.array(f, float) + 0.5)


def test_a_scene_built_in_code_is_checked_before_it_is_drawn_reported_or_written(tmp_path):
    """`Scene(..., units="m")` was refused by the analyses but ended in an AttributeError
    in `rb.plot`, `rb.report` without an analysis and `rb.write_scene`; a block of two
    vertices was written and then refused by the reader. Each names the fault now (a
    geometry that overlaps is still drawn: a picture shows what is wrong)."""
    from rigidblocks import make_block

    bad = (_in_code(units="m"), "units: expected rigidblocks.Units(")
    short = (_in_code(blocks=(_in_code().blocks[0], make_block("B", [[0, 0], [1, 0]]))),
             "block 'B': needs at least 3 vertices, got 2")
    import re

    for scene, said in (bad, short):
        for act, more in ((rb.plot, ()), (rb.report, ()),
                          (rb.write_scene, (tmp_path / "s.json",))):
            with pytest.raises(InputError, match=re.escape(said)):
                act(scene, *more)
    assert not (tmp_path / "s.json").exists()
    from rigidblocks.scene.model import make_block as mb

    base, b = _in_code().blocks
    overlap = _in_code(blocks=(base, b, mb("C", [[0.5, 0], [1.5, 0], [1.5, 2], [0.5, 2]])))
    rb.plot(overlap)  # drawn, for its maker to see
    import matplotlib.pyplot as plt

    plt.close("all")


def test_a_key_given_twice_is_refused(tmp_path):
    """`"friction": 0.6, "friction": 0.1` in one scene was read as 0.1 (the decoder keeps
    the last): `load` answered 0.0999999 with no word. A key given twice in any object
    of a scene or a sweep spec is an error naming it (and the block)."""
    from rigidblocks.studies.spec import read_spec

    doc = ('{"format": "rigidblocks-scene", "version": 1, "dimension": 2, '
           '"friction": 0.6, "friction": 0.1, "blocks": []}')
    p = tmp_path / "s.json"
    p.write_text(doc)
    with pytest.raises(InputError, match=r's.json: the key "friction" appears twice in one '
                                         r'object \(in the object with the keys "format", '
                                         r'"version", "dimension", "friction", "blocks"\): '
                                         r"which value is meant\? give it once"):
        read_scene(p)
    p.write_text(doc.replace('"friction": 0.1, "blocks": []', '"blocks": [{"id": "b", '
                             '"support": true, "support": false}]'))
    with pytest.raises(InputError, match=r'the key "support" appears twice in one object '
                                         r"\(in the object with id 'b'\)"):
        read_scene(p)
    p.write_text('{"format": "rigidblocks-sweep", "version": 1, "version": 1}')
    with pytest.raises(InputError, match='the key "version" appears twice'):
        read_spec(p)


def test_a_scene_saved_with_a_byte_order_mark_is_read(tmp_path):
    """A scene saved by a Windows editor with a UTF-8 byte-order mark was refused with
    Python's hint ("decode using utf-8-sig"); scenes and sweep specs read it."""
    p = tmp_path / "bom.json"
    p.write_bytes(b"\xef\xbb\xbf" + (EXAMPLES / "wall.json").read_bytes())
    assert len(read_scene(p).blocks) == 19


def test_a_scene_in_utf16_is_told_to_be_utf8(tmp_path):
    """A scene saved as UTF-16 read Python's "'utf-8' codec can't decode byte 0xff in
    position 0: invalid start byte"."""
    p = tmp_path / "u16.json"
    p.write_bytes((EXAMPLES / "wall.json").read_text().encode("utf-16"))
    with pytest.raises(InputError, match=r"u16.json: not UTF-8 text \(a scene is a JSON "
                                         r"file in UTF-8: save it so"):
        read_scene(p)
