"""The accuracy the engineer asks for: ``rtol=`` of the analyses and ``--rtol`` of the
commands that bracket a limit (friction, load, thickness).

Reference values: the Arpino gate's f* = 0.0905191 (examples/arpino_gate.json, certified
at the default 1e-7 in tests/test_examples.py), the seed's f* = 0.5 (seed paper,
numerical example 1; validation.md)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import rigidblocks as rb
from rigidblocks.cli.main import main
from rigidblocks.errors import InputError
from rigidblocks.generators import catalogue as cat

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
ARPINO = 0.0905191  # f* of the Arpino gate to 7 figures (the default accuracy)


@pytest.mark.parametrize("rtol", [1e-3, 1e-5])
def test_a_coarser_accuracy_brackets_f_star_to_it_in_fewer_solves(rtol):
    scene = rb.read_scene(EXAMPLES / "arpino_gate.json")
    fine = rb.min_friction(scene, state=False)
    r = rb.min_friction(scene, state=False, rtol=rtol)
    assert r.status == "stable" and r.friction_factor == r.upper
    assert r.lower <= fine.friction_factor <= r.upper  # the fine f* is in the bracket
    assert r.upper - r.lower <= rtol * r.upper + 1e-9
    assert abs(r.friction_factor - ARPINO) <= rtol * ARPINO + 1e-7
    assert r.n_solves < fine.n_solves


def test_the_non_associative_friction_search_takes_the_accuracy():
    """f* = 0.5 (seed): the model stands at its static f* without dilatancy, so the
    answer is the static one, bracketed to the accuracy asked for (0.5 inside to
    round-off)."""
    r = rb.min_friction(cat.seed_model(), state=False, rtol=1e-2, flow="non-associative")
    assert r.status == "stable" and r.lower - 1e-9 <= 0.5 <= r.upper + 1e-9
    assert r.upper - r.lower <= 1e-2 * r.upper


@pytest.mark.parametrize("rtol", [0, 1, -1e-3, 2.0, "1e-3", float("nan")])
def test_an_accuracy_outside_0_1_is_bad_input(rtol):
    scene = rb.read_scene(EXAMPLES / "reference.json")
    with pytest.raises(InputError, match=r"rtol .* in \(0, 1\)"):
        rb.min_friction(scene, rtol=rtol)
    with pytest.raises(InputError, match=r"rtol .* in \(0, 1\)"):
        rb.max_load_multiplier(scene, rtol=rtol)


def test_friction_and_load_take_rtol_on_the_command_line(capsys):
    path = str(EXAMPLES / "arpino_gate.json")
    assert main(["friction", path, "--rtol", "1e-3", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    lower, upper = d["bracket"]
    assert upper - lower <= 1e-3 * upper + 1e-9 and d["friction_factor"] == upper
    assert abs(d["friction_factor"] - ARPINO) <= 1e-3 * ARPINO + 1e-7
    ref = str(EXAMPLES / "reference.json")
    assert main(["load", ref, "--rtol", "1e-3", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["status"] == "collapse"


@pytest.mark.parametrize("argv", [["friction", "arch.json", "--rtol", "0"],
                                  ["load", "reference.json", "--rtol", "1"],
                                  ["friction", "arch.json", "--rtol", "abc"],
                                  ["thickness", "arch", "--rtol", "2"]])
def test_a_bad_rtol_on_the_command_line_is_a_one_line_error(capsys, argv):
    if argv[0] != "thickness":
        argv[1] = str(EXAMPLES / argv[1])
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert "--rtol" in err[-1] and "Traceback" not in "\n".join(err)
