"""The ``check``, ``friction`` and ``load`` commands against scene-format.md's contract.

Expected values are the closed forms of the catalogue (validation.md): a b x h block on
a support under a horizontal body force has lambda* = min(f, b/h); the seed's
four-block model without self-weight has f* = 0.5 (26.565 deg).
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import EXAMPLES, rect

import rigidblocks as rb
from rigidblocks.cli.main import main
from rigidblocks.generators import catalogue as cat
from rigidblocks.io import write_scene


def write(tmp_path, name, blocks, **top):
    d = {"format": "rigidblocks-scene", "version": 1, "dimension": 2, "blocks": blocks}
    d.update(top)
    p = tmp_path / name
    p.write_text(json.dumps(d))
    return str(p)


@pytest.fixture
def block_file(tmp_path):
    """1 x 2 block, unit weight 1, f = 0.3, live horizontal body force (catalogue)."""
    path = tmp_path / "block.json"
    write_scene(cat.block_on_base(1.0, 2.0, 0.3), path)
    return str(path)


@pytest.fixture
def seed_file(tmp_path):
    """The seed's reference model (catalogue.seed_model), no self-weight."""
    path = tmp_path / "seed.json"
    write_scene(cat.seed_model(), path)
    return str(path)


def run_json(capsys, argv):
    code = main(argv)
    out = capsys.readouterr()
    lines = [ln for ln in out.out.splitlines() if ln.strip()]
    assert len(lines) == 1, out.out  # exactly one JSON object
    return code, json.loads(lines[0]), out.err


@pytest.mark.parametrize("solver", [[], ["--solver", "highs"]])
def test_friction_json(capsys, seed_file, solver):
    """f* = 0.5 and phi = atan(0.5) = 26.565 deg (seed, validation.md); the governing
    joints are the four horizontal joints of the central blocks."""
    code, d, _ = run_json(capsys, ["friction", seed_file, "--json", *solver])
    assert code == 0
    assert {"status", "friction_factor", "friction_angle_deg", "governing_joints"} <= set(d)
    assert d["status"] == "stable"
    assert abs(d["friction_factor"] - 0.5) <= 1e-6 * 0.5
    assert abs(d["friction_angle_deg"] - math.degrees(math.atan(0.5))) <= 1e-5
    gov = {frozenset(p) for p in d["governing_joints"]}
    assert gov == {frozenset(p) for p in (("S", "C1"), ("S", "C2"), ("C1", "T"),
                                           ("C2", "T"))}


def test_friction_unstable_json(capsys, tmp_path):
    """A block standing on a corner has no joint: bad input (exit 2, naming it), no
    JSON. A structure that no friction makes stand, the stocky arch's thin sister
    hinging under its weight, is "unstable" with the angle null."""
    p = write(tmp_path, "point.json", [
        {"id": "S", "vertices": rect(-1, -1, 2, 1), "support": True},
        {"id": "B", "vertices": [[0, 0], [1, 1], [0, 2], [-1, 1]]},
    ], unit_weight=1.0)
    assert main(["friction", p, "--json"]) == 2
    out, err = capsys.readouterr()
    assert out == "" and "block 'B' touches block 'S' at a point only" in err
    # a 1 x 3 block on a support whose weight acts 1 m beyond its toe: it tips whatever
    # the friction
    p = write(tmp_path, "tips.json", [
        {"id": "S", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "B", "vertices": rect(0, 0, 1, 3)},
    ], unit_weight=1.0, loads=[{"block": "B", "force": [0, -100], "point": [2.0, 3.0]}])
    code, d, _ = run_json(capsys, ["friction", p, "--json"])
    assert code == 0
    assert d["status"] == "unstable"
    assert d["friction_factor"] is None and d["friction_angle_deg"] is None


@pytest.mark.parametrize("solver", [[], ["--solver", "highs"]])
def test_load_json(capsys, block_file, solver):
    """lambda* = min(f, b/h) = 0.3 with the scene's f; 0.5 (tipping, b/h) with
    --friction infinite."""
    code, d, _ = run_json(capsys, ["load", block_file, "--json", *solver])
    assert code == 0
    assert {"status", "load_multiplier", "friction"} <= set(d)
    assert d["status"] == "collapse" and d["friction"] == 0.3
    assert abs(d["load_multiplier"] - 0.3) <= 1e-6 * 0.3
    code, d, _ = run_json(capsys, ["load", block_file, "--json", "--friction", "infinite",
                                   *solver])
    assert code == 0 and d["friction"] == "infinite"
    assert abs(d["load_multiplier"] - 0.5) <= 1e-6 * 0.5


@pytest.mark.parametrize("name", ["segmental_arch.json", "arpino_gate.json"])
def test_load_json_governing_joints_are_those_its_governing_line_names(capsys, name):
    """`load --json`'s governing_joints are the joints the governing line names, in its
    order: the segmental arch's four hinges (it gave [], the sliding joints alone), the
    Arpino gate's two hinges and one sliding joint (it gave the sliding one)."""
    path = str(EXAMPLES / name)
    assert main(["load", path]) == 0
    line = next(x for x in capsys.readouterr().out.splitlines()
                if x.startswith("governing"))
    named = [j for group in line.split(None, 1)[1].split("; ")
             for j in group.split("(", 1)[1].rstrip(")").split(", ")]
    code, d, _ = run_json(capsys, ["load", path, "--json"])
    assert code == 0 and len(named) >= 3
    assert ["-".join(p) for p in d["governing_joints"]] == named
    m = d["mechanism"]
    assert {tuple(p) for p in d["governing_joints"]} == \
        {tuple(p) for p in m["hinges"] + m["sliding"] + m["open"]}


def test_load_unbounded_json(capsys, tmp_path):
    """A live force straight down with infinite friction never causes collapse."""
    p = write(tmp_path, "down.json", [
        {"id": "S", "vertices": rect(0, -1, 3, 1), "support": True},
        {"id": "B", "vertices": rect(1, 0, 1, 1)},
    ], unit_weight=1.0, live_body_force=[0, -1])
    code, d, _ = run_json(capsys, ["load", p, "--json"])
    assert code == 0 and d["status"] == "unbounded" and d["load_multiplier"] is None


@pytest.mark.parametrize("lf,ok", [(0.3 * (1 - 1e-4), True), (0.3 * (1 + 1e-4), False)])
def test_check_json(capsys, block_file, lf, ok):
    """Admissible just below lambda* = f = 0.3, not just above; exit 0 either way."""
    code, d, _ = run_json(capsys, ["check", block_file, "--json", "--load-factor", str(lf)])
    assert code == 0
    assert d["admissible"] is ok
    assert d["status"] == ("admissible" if ok else "inadmissible")


def test_check_friction_infinite(capsys, block_file):
    """With infinite friction the block only tips at b/h = 0.5: lambda = 0.4 passes."""
    code, d, _ = run_json(capsys, ["check", block_file, "--json", "--friction", "infinite",
                                   "--load-factor", "0.4", "--solver", "highs"])
    assert code == 0 and d["admissible"] is True


def test_load_without_live_load_exits_2(capsys, tmp_path):
    """scene-format.md: load on a scene with no live load is a usage error (exit 2,
    one line on standard error that says so)."""
    p = write(tmp_path, "dead.json", [
        {"id": "S", "vertices": rect(0, -1, 3, 1), "support": True},
        {"id": "B", "vertices": rect(1, 0, 1, 1)},
    ], unit_weight=1.0)
    code = main(["load", p, "--json"])
    out = capsys.readouterr()
    assert code == 2
    assert out.out == ""
    err = out.err.strip().splitlines()
    assert len(err) == 1 and "live" in err[0]



@pytest.mark.parametrize("command", [["load"], ["load", "--flow", "non-associative"],
                                     ["load", "--method", "distortion"], ["path"]])
@pytest.mark.parametrize("live", ["weightless", "zero"])
def test_load_of_a_live_load_that_is_nothing_exits_2(capsys, tmp_path, command, live):
    """A live load that is nothing is no live load: a live body force on blocks that
    weigh nothing (a scene without unit_weight, carried by a dead point load) or a live
    point load of force [0, 0] read UNBOUNDED ("no multiple of the live load makes it
    collapse"), exit 0, no note. scene-format.md: a usage error, one line."""
    blocks = [{"id": "S", "vertices": rect(-1, -1, 4, 1), "support": True},
              {"id": "B", "vertices": rect(0, 0, 1, 2)}]
    dead = {"block": "B", "force": [0, -10]}
    p = write(tmp_path, "nothing.json", blocks, friction=0.4, loads=[dead],
              live_body_force=[1, 0]) if live == "weightless" else \
        write(tmp_path, "nothing.json", blocks, friction=0.4, unit_weight=20.0,
              loads=[dead, {"block": "B", "force": [0, 0], "live": True}])
    code = main([*command, p])
    out = capsys.readouterr()
    assert code == 2 and out.out == ""
    err = out.err.strip().splitlines()
    assert len(err) == 1 and "nothing to" in err[0] and "nothing.json" in err[0]
    assert ("weigh nothing" if live == "weightless" else "all zero") in err[0]
    if live == "weightless" and command == ["load"]:
        # check and friction answer, and say the live body force adds nothing
        code, d, _ = run_json(capsys, ["check", p, "--json"])
        assert code == 0 and any("adds nothing" in n for n in d["notes"])


def test_friction_all_overridden_exits_2(capsys, tmp_path):
    """scene-format.md: friction on a scene whose every joint has its own friction is a
    usage error (exit 2, one line)."""
    p = write(tmp_path, "over.json", [
        {"id": "S", "vertices": rect(0, -1, 3, 1), "support": True},
        {"id": "B", "vertices": rect(1, 0, 1, 1)},
    ], unit_weight=1.0, joints=[{"blocks": ["S", "B"], "friction": 0.4}])
    code = main(["friction", p, "--json"])
    out = capsys.readouterr()
    assert code == 2
    err = out.err.strip().splitlines()
    assert len(err) == 1 and "override" in err[0]


def test_bad_friction_option_exits_2(capsys, block_file):
    """--friction must be a number >= 0 or "infinite": exit 2 with one line."""
    code = main(["check", block_file, "--friction", "-1"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and "friction" in err[0]


def test_human_report(capsys, seed_file):
    """Without --json a short table with f* to six digits is printed."""
    assert main(["friction", seed_file]) == 0
    out = capsys.readouterr().out
    assert "0.5" in out and "26.5651" in out


def test_unstable_under_live_load_hints_at_the_two_usual_questions(capsys):
    """A horizontal body force of 1 g tilts the gravity field by 45 degrees; a thin
    semicircular ring (t/R = 0.15, barely above Milankovitch's 0.1075 for vertical
    gravity) cannot contain a thrust line under it, so `friction` at load factor 1 is
    unstable, and the report names --load-factor 0 and the `load` command.
    Under self-weight alone the arch stands (t/R > 0.1075) and needs finite friction."""
    from rigidblocks.cli.main import main

    path = str(EXAMPLES / "arch.json")
    assert main(["friction", path, "--load-factor", "1"]) == 0
    out = capsys.readouterr().out
    assert "UNSTABLE" in out and "--load-factor 0" in out and "rigidblocks load" in out
    assert main(["friction", path, "--load-factor", "0"]) == 0
    out = capsys.readouterr().out
    assert "f*" in out and "hint" not in out


def test_contact_tolerance_option(tmp_path, capsys):
    """A 1 x 2 block drawn 1e-6 above its base (scene size about 5.4, so the gap is
    2e-7 of it): at the default tolerance (1e-7 of the size) it does not touch and is
    refused, naming the option; with --contact-tol 1e-6 it rests on the base and
    stands (lambda = 0, f = 0.3: its weight goes straight down)."""
    path = write(tmp_path, "gap.json", [
        {"id": "base", "vertices": rect(-2, -1, 5, 1), "support": True},
        {"id": "B", "vertices": rect(0, 1e-6, 1, 2)},
    ], unit_weight=1.0, friction=0.3)
    assert main(["check", path, "--json"]) == 2
    assert "raise the contact tolerance" in capsys.readouterr().err
    assert main(["check", path, "--contact-tol", "1e-6", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["status"] == "admissible"
    assert main(["check", path, "--contact-tol", "0"]) == 2
    assert "--contact-tol" in capsys.readouterr().err


# -- small things a user meets ----------------------------------------------------------
def test_extrude_command_keeps_the_answers(tmp_path, capsys, block_file):
    """`extrude` turns the 1 x 2 block (f = 0.3) into prisms: lambda* = min(f, b/h) =
    0.3 in 3D as in 2D (the extruded problem is the plane one spread over the depth)."""
    from rigidblocks.io import read_scene
    from rigidblocks.scene import extrude

    out = tmp_path / "block3d.json"
    assert main(["extrude", block_file, "-o", str(out), "--depth", "0.5"]) == 0
    assert "2 prisms 0.5 deep" in capsys.readouterr().out
    solid = read_scene(out)
    assert solid.dimension == 3 and solid == extrude(read_scene(block_file), 0.5)
    assert main(["load", str(out), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["load_multiplier"] == pytest.approx(0.3,
                                                                                 rel=1e-6)
    assert main(["extrude", str(out), "-o", str(tmp_path / "x.json")]) == 2
    assert "2D scene" in capsys.readouterr().err


def test_extrude_to_another_depth_says_that_point_loads_do_not_scale(tmp_path, capsys):
    """The reference model with self-weight (depth 0.25) extruded 0.5 deep: its weights
    double and its point loads do not, so its lambda* is not the 2D scene's (2.4 in 2D,
    3.6 extruded; the 2D scene's own depth keeps it): the message said it was."""
    from rigidblocks.io import read_scene

    src = str(EXAMPLES / "reference_self_weight.json")
    out = tmp_path / "r3.json"
    assert main(["extrude", src, "-o", str(out), "--depth", "0.5"]) == 0
    said = capsys.readouterr().out
    assert "f* and lambda* are not the 2D scene's unless the loads are scaled by 2" in said
    lam = rb.max_load_multiplier(read_scene(out)).load_multiplier
    assert lam == pytest.approx(3.6, rel=1e-5)
    assert main(["extrude", src, "-o", str(out)]) == 0
    assert "f* and lambda* are the 2D scene's, each to its search's accuracy)" in \
        capsys.readouterr().out
    assert rb.max_load_multiplier(read_scene(out)).load_multiplier == pytest.approx(
        2.4, rel=1e-5)  # the seed's reference model with self-weight


def test_example_help_shows_the_generator_parameters(capsys):
    assert main(["example", "wall", "--help"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: rigidblocks example wall") and "--courses" in out
    # and `example --help` names the generators (it said "see --list")
    with pytest.raises(SystemExit):
        main(["example", "--help"])
    out = " ".join(capsys.readouterr().out.split())
    assert "generators: reference, flat_arch, arch," in out and "keyed_wall" in out


def test_output_piped_into_head_ends_quietly(tmp_path):
    """A reader that stops after one line (`| head -1`) ends the run without a
    traceback (exit 141, as a program the pipe ended)."""
    import os
    import subprocess
    import sys

    from conftest import ROOT

    env = dict(os.environ, PYTHONPATH=str(ROOT))
    cmd = [sys.executable, "-m", "rigidblocks.cli.main", "check",
           str(EXAMPLES / "wall.json"), "--joints"]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    proc.stdout.close()  # the reader is gone before the answer is printed
    err = proc.stderr.read().decode()
    assert proc.wait() == 141 and "Traceback" not in err and "BrokenPipe" not in err, err


def test_a_check_process_imports_only_what_it_uses(tmp_path):
    """``rigidblocks check`` of a 2D wall and of its extrusion, with the force state, in
    a fresh interpreter: neither scipy (0.1 CPU s to import scipy.sparse) nor the
    modules of the other commands are imported. (A wall above DILATANCY_JOINTS: on a
    smaller one the answer without dilatancy beside it is an iteration of sparse
    problems, which imports scipy.)"""
    from rigidblocks.analyses.core import DILATANCY_JOINTS
    from rigidblocks.contacts import detect_contacts
    from rigidblocks.generators.walls import running_bond_wall
    from rigidblocks.scene.extrude import extrude

    wall = running_bond_wall(6, 6)
    assert detect_contacts(wall).n_joints > DILATANCY_JOINTS
    files = [tmp_path / "wall.json", tmp_path / "wall3d.json"]
    write_scene(wall, files[0])
    write_scene(extrude(wall), files[1])
    code = ("import sys\n"
            "from rigidblocks.cli.main import main\n"
            "for f in sys.argv[1:]:\n"
            "    assert main(['check', f, '--load-factor', '0', '--json']) == 0\n"
            "print(sorted(m for m in sys.modules if m.split('.')[0] == 'scipy'\n"
            "             or m.startswith(('rigidblocks.cli.', 'rigidblocks.io.dxf'))))\n")
    root = Path(__file__).resolve().parents[1]
    out = subprocess.run([sys.executable, "-c", code, *map(str, files)], capture_output=True,
                         text=True, env={**os.environ, "PYTHONPATH": str(root)}, cwd=root,
                         timeout=300)
    assert out.returncode == 0, out.stderr
    answers = [json.loads(line) for line in out.stdout.splitlines()[:-1]]
    assert [a["status"] for a in answers] == ["admissible", "admissible"]
    assert out.stdout.splitlines()[-1] == str(["rigidblocks.cli.analyses", "rigidblocks.cli.main",
                                               "rigidblocks.cli.options",
                                               "rigidblocks.cli.progress"])


def test_example_list_with_a_name_lists_that_generator(capsys):
    """`example --list arch` lists the arch generator alone (it listed all twelve)."""
    assert main(["example", "--list", "arch"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("arch: ") and "wall:" not in out and "--voussoirs" in out
    assert main(["example", "--list"]) == 0
    assert "wall:" in capsys.readouterr().out
    assert main(["example", "--list", "archx"]) == 2
    assert "unknown example 'archx'" in capsys.readouterr().err


def test_export_dxf_refuses_another_extension(tmp_path, capsys):
    """`export-dxf -o x.txt` wrote a DXF named .txt (plot, report and sweep refuse a
    wrong extension); nothing is written."""
    out = tmp_path / "x.txt"
    assert main(["export-dxf", str(EXAMPLES / "arch.json"), "-o", str(out)]) == 2
    assert "use .dxf, not '.txt'" in capsys.readouterr().err and not out.exists()


def test_the_json_says_its_units_and_what_lambda_1_is(capsys):
    """`load --json` gave the multiplier alone: neither the units nor the live load it
    multiplies (the answer line's "0.6 x 25.6 kN = 15.36 kN"), so that a program could
    not recover either without reading the scene; the joints' N and T had no unit."""
    assert main(["load", str(EXAMPLES / "wall.json"), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["units"] == {"length": "m", "force": "kN"}
    assert doc["live_load"]["size"] == pytest.approx(25.6)
    assert doc["live_load"]["direction"] == "horizontal"
    assert main(["check", str(EXAMPLES / "reference.json"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["units"] == {"length": "m", "force": "N"}


def test_several_dead_point_loads_are_given_in_all(tmp_path, capsys):
    """Dead point loads of 3 and 5 kN read "2 point loads of 8 kN" (8 kN each?)."""
    p = tmp_path / "pl.json"
    p.write_text(json.dumps({
        "format": "rigidblocks-scene", "version": 1, "dimension": 2,
        "units": {"length": "m", "force": "kN"}, "friction": 0.6,
        "blocks": [{"id": "g", "support": True, "vertices": rect(-1, -1, 4, 1)},
                   {"id": "b", "vertices": rect(0, 0, 1, 1)}],
        "loads": [{"block": "b", "force": [0, -3]}, {"block": "b", "force": [0, -5]},
                  {"block": "b", "force": [1, 0], "live": True}]}))
    assert main(["load", str(p)]) == 0
    assert "(no self-weight, 2 point loads, 8 kN in all)" in capsys.readouterr().out


def test_an_id_with_a_newline_keeps_the_answer_one_line_per_row_and_is_not_drawn(
        tmp_path, capsys):
    """A block id "A\\nx": the answer's governing line broke in two ("(base, ground-A" then
    "x)"), and export-dxf wrote a file that neither it nor ezdxf could read. The answer
    writes it as Python does, as the errors give ids; the export refuses it."""
    p = tmp_path / "nl.json"
    p.write_text(json.dumps({
        "format": "rigidblocks-scene", "version": 1, "dimension": 2, "unit_weight": 10,
        "live_body_force": [1, 0],
        "blocks": [{"id": "ground", "support": True, "vertices": rect(-1, -1, 3, 1)},
                   {"id": "A\nx", "vertices": rect(0, 0, 1, 2)}]}))
    assert main(["load", str(p)]) == 0
    out = capsys.readouterr().out
    assert "ground-A\\nx" in out and all(
        line[:10].strip() for line in out.splitlines())  # every line labelled
    assert main(["export-dxf", str(p), "-o", str(tmp_path / "nl.dxf")]) == 2
    assert "block 'A\\nx': its id holds a control character" in capsys.readouterr().err
    assert not (tmp_path / "nl.dxf").exists()


def test_forces_in_newtons_are_written_without_an_exponent(tmp_path, capsys):
    """A 1 x 2 m block of 16 kN/m^3 drawn in mm and N: "32000 N" read "3.2e+04 N" and
    the answer "= 1.81e+04 N", where the same block in kN read "32 kN"."""
    p = tmp_path / "mm.json"
    p.write_text(json.dumps({
        "format": "rigidblocks-scene", "version": 1, "dimension": 2,
        "units": {"length": "mm", "force": "N"}, "unit_weight": 16e-6, "depth": 1000,
        "friction": 0.6, "live_body_force": [1, 0],
        "blocks": [{"id": "g", "support": True, "vertices": rect(-1000, -500, 3000, 500)},
                   {"id": "b", "vertices": rect(0, 0, 1000, 2000)}]}))
    assert main(["load", str(p)]) == 0
    out = capsys.readouterr().out
    assert "32000 N horizontal" in out and "= 16000 N horizontal" in out, out
    assert "e+0" not in out


def test_the_json_live_load_has_its_resultant_and_path_and_thickness_their_units(
        tmp_path, capsys):
    """`live_load` read "horizontal" for a pull along -x as along +x (the direction in
    words only) and size 0 for live couples; `path --json` and `thickness --json` had no
    units."""
    p = tmp_path / "pull.json"
    p.write_text(json.dumps({
        "format": "rigidblocks-scene", "version": 1, "dimension": 2, "unit_weight": 10,
        "units": {"length": "m", "force": "kN"}, "friction": 0.6,
        "live_body_force": [-1, 0],
        "blocks": [{"id": "g", "support": True, "vertices": rect(-1, -1, 3, 1)},
                   {"id": "b", "vertices": rect(0, 0, 1, 2)}]}))
    assert main(["load", str(p), "--json"]) == 0
    live = json.loads(capsys.readouterr().out)["live_load"]
    assert live["resultant"] == [-20.0, 0.0] and live["moment"] is None
    assert main(["path", str(EXAMPLES / "reference.json"), "--json"]) in (0, 3)
    assert json.loads(capsys.readouterr().out)["units"] == {"length": "m", "force": "N"}
    assert main(["thickness", "arch", "--rtol", "1e-2", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["units"] == {"length": "m", "force": "kN"}


def test_no_friction_needed_reads_an_angle_of_0(capsys, block_file):
    """A block under its weight alone needs no friction: f* = 0, whose angle read
    "0.0000 deg" (and 0.00 deg in a picture's title), figures of a number that is 0."""
    assert main(["friction", block_file, "--load-factor", "0"]) == 0
    answer = next(ln for ln in capsys.readouterr().out.splitlines()
                  if ln.startswith("answer"))
    assert answer.split(None, 1)[1] == "f* = 0 (friction angle 0 deg)"
    from rigidblocks.io import read_scene
    from rigidblocks.results import headline

    res = rb.min_friction(read_scene(block_file), load_factor=0.0)
    assert "(friction angle 0\N{DEGREE SIGN})" in headline(res, symbols=True)
