"""Overflow and nesting are bad input (issue 32 item 4): quantities derived from a scene
(areas, volumes, weights, loads, their moments, live loads times the load factor) are
checked finite and below scene.validate.LARGEST before any solve, with exit 2 and one
line naming the block or key, and no numpy warning on the way; deeply nested JSON is an
error, not a RecursionError; ids are printed with repr; a multiplier is never
negative."""

from __future__ import annotations

import json

import pytest

from rigidblocks.analyses import check, max_load_multiplier
from rigidblocks.cli.main import main
from rigidblocks.errors import InputError
from rigidblocks.generators.catalogue import block_on_base, rect, scene2d, scene3d


def doc(blocks, dimension=2, **top):
    return {"format": "rigidblocks-scene", "version": 1, "dimension": dimension,
            "blocks": blocks, **top}


BASE = {"id": "S", "vertices": rect(-2, -1, 5, 1), "support": True}
BLOCK = {"id": "B", "vertices": rect(0, 0, 1, 1)}


def run(tmp_path, capsys, document, *args, command="check"):
    """The CLI on ``document`` (a dict, or JSON text): exit status and standard error."""
    p = tmp_path / "scene.json"
    p.write_text(document if isinstance(document, str) else json.dumps(document))
    code = main([command, str(p), *args])
    return code, capsys.readouterr().err


def one_line_error(code, err, *words):
    assert code == 2, err
    assert err.startswith("rigidblocks: error: ") and err.count("\n") == 1, err
    assert "Warning" not in err and "Traceback" not in err
    for w in words:
        assert w in err, err


@pytest.mark.parametrize("document,words", [
    # unit weight 1e308 on a 2 x 2 block: the weight overflows to inf (the solver's
    # NumericalError and RuntimeWarning lines before)
    (doc([BASE, {"id": "B", "vertices": rect(0, 0, 2, 2)}], unit_weight=1e308),
     ["block 'B'", "weight", "inf"]),
    # coordinates of 1e300: "zero area" after five overflow warnings before
    (doc([{"id": "S", "vertices": [[1e300 * x, 1e300 * y] for x, y in rect(-2, -1, 5, 1)],
           "support": True}, BLOCK], unit_weight=1.0), ["block 'S'", "coordinate"]),
    # coordinates of 1e100: finite, but the area is 1e200
    (doc([BASE, {"id": "B", "vertices": [[1e100 * x, 1e100 * y] for x, y in rect(0, 0, 1, 1)]}],
         unit_weight=1.0), ["block 'B'", "area"]),
    # a live force of 1e308 ("collapse" at -5.7e-12 before)
    (doc([BASE, BLOCK], unit_weight=1.0, loads=[{"block": "B", "force": [1e308, 0],
                                                  "live": True}]),
     ["load #0 on block 'B'", "force"]),
    # a live body force of 1e308 times the weights
    (doc([BASE, BLOCK], unit_weight=10.0, live_body_force=[1e308, 0]),
     ["block 'B'", "live body force"]),
    # a moment of a modest force about a far block
    (doc([BASE, BLOCK], unit_weight=1.0, loads=[{"block": "B", "force": [1e100, 0],
                                                  "point": [1e60, 0]}]),
     ["load #0 on block 'B'", "moment"]),
])
def test_derived_quantities_beyond_double_precision_are_bad_input(tmp_path, capsys,
                                                                 document, words):
    one_line_error(*run(tmp_path, capsys, document), *words)


def test_a_3d_volume_beyond_double_precision_is_bad_input():
    """A cube of side 1e60: coordinates finite, the volume 1e180."""
    s = 1e60
    cube = [[0, 0, 0], [s, 0, 0], [s, s, 0], [0, s, 0],
            [0, 0, s], [s, 0, s], [s, s, s], [0, s, s]]
    faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6],
             [3, 0, 4, 7]]
    base = [[x, y, z - s] for x, y, z in cube]
    with pytest.raises(InputError, match="volume"):
        scene3d([{"id": "S", "vertices": base, "faces": faces, "support": True},
                 {"id": "B", "vertices": cube, "faces": faces}], unit_weight=1.0)


def test_load_factor_beyond_double_precision_is_bad_input(tmp_path, capsys):
    """``check --load-factor 1e308`` exited 1 (a solver failure) before."""
    d = doc([BASE, BLOCK], unit_weight=1.0, live_body_force=[1, 0])
    one_line_error(*run(tmp_path, capsys, d, "--load-factor", "1e308"), "load factor")
    with pytest.raises(InputError, match="load factor"):
        check(block_on_base(1.0, 2.0, 0.5), load_factor=1e300)
    # a large but representable one is a verdict
    assert check(block_on_base(1.0, 2.0, 0.5), load_factor=1e3, state=False).status \
        == "inadmissible"


def test_deeply_nested_json_is_bad_input(tmp_path, capsys):
    """100,000 nested lists ended in a RecursionError traceback; 40 are refused before
    the reader; a value nested one level too deep is named by the reader."""
    head = '{"format": "rigidblocks-scene", "version": 1, "dimension": 2, "blocks": '
    code, err = run(tmp_path, capsys, head + "[" * 100_000 + "]" * 100_000 + "}")
    one_line_error(code, err, "nested")
    code, err = run(tmp_path, capsys, head + "[" * 40 + "]" * 40 + "}")
    one_line_error(code, err, "nested more than 32")
    d = doc([BASE, {"id": "B", "vertices": [[[0], 0], [1, 0], [1, 1], [0, 1]]}])
    one_line_error(*run(tmp_path, capsys, d), "block 'B'", "vertices")


def test_brackets_inside_strings_are_not_nesting(tmp_path, capsys):
    """The nesting is counted on the brackets outside string literals: ids and a name
    that hold 40 opening brackets, closing ones and escaped quotes are read as they are
    (a scene nests 5 levels)."""
    deep = "[" * 40 + '\\"{' * 40
    d = doc([{**BASE, "id": deep}, {**BLOCK, "id": "]" * 40 + '"}'}], name=deep)
    code = main(["check", str(_write(tmp_path, d)), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["status"] == "admissible", out


def _write(tmp_path, document):
    p = tmp_path / "scene.json"
    p.write_text(json.dumps(document))
    return p


@pytest.mark.parametrize("bad_id", ["B\nx", "B\rx", "B\tx"])
def test_ids_with_control_characters_make_one_line_errors(tmp_path, capsys, bad_id):
    """Ids are printed with repr: a newline in one made a two-line error."""
    d = doc([BASE, {"id": bad_id, "vertices": rect(0, 0, 1, 1)},
             {"id": bad_id, "vertices": rect(1, 0, 1, 1)}])
    one_line_error(*run(tmp_path, capsys, d), repr(bad_id), "duplicate")
    d = doc([BASE, BLOCK], loads=[{"block": bad_id, "force": [1, 0]}])
    one_line_error(*run(tmp_path, capsys, d), repr(bad_id), "unknown block")


@pytest.mark.parametrize("solver", ["clarabel", "highs", "osqp", "scs"])
def test_a_multiplier_is_never_negative(solver):
    """A frictionless block on a level base slides at once: lambda* = 0 (validation.md,
    block on a support, min(f, b/h) with f = 0). Round-off put it at -3.4e-11 (Clarabel)
    and -4.8e-10 (OSQP), reported as "collapse" at a negative multiplier, and the
    non-associative analysis with the bounds [0, -4.8e-10]."""
    for flow in ("associative", "non-associative"):
        r = max_load_multiplier(block_on_base(1.0, 2.0, 0.0), solver=solver, state=False,
                                flow=flow)
        assert r.status == "collapse"
        assert 0.0 <= r.load_multiplier <= 1e-9 and str(r.load_multiplier)[0] != "-"
        for pair in (r.bracket, r.load_multiplier_bounds):
            if pair is not None and pair[0] is not None:
                assert 0.0 <= pair[0] <= pair[1]


def test_realistic_units_pass():
    """Millimetres and newtons (coordinates 1e4, unit weight 2.4e-5 N/mm^3, a load of
    1e7 N): well within the bound."""
    s = scene2d([{"id": "S", "vertices": rect(-2e4, -1e3, 5e4, 1e3), "support": True},
                 {"id": "B", "vertices": rect(0, 0, 1e4, 2e4)}], unit_weight=2.4e-5,
                depth=1e3, friction=0.6,
                loads=[{"block": "B", "force": [1e7, 0], "point": [5e3, 2e4],
                        "live": True}])
    assert check(s, load_factor=0.0, state=False).admissible
