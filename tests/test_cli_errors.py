"""Input failure paths at the command line: a one-line message and exit 2, never a
traceback, and nothing written or created (issue 14 item 3, issue 17 items 2 and 7)."""

from __future__ import annotations

import json
import sys
import time

import pytest
from conftest import EXAMPLES, rect

from rigidblocks.cli.main import build_parser, main
from rigidblocks.cli.options import finite_float

SWEEP = EXAMPLES / "sweeps" / "flat_arch.json"


def write(tmp_path, name, doc):
    p = tmp_path / name
    p.write_text(json.dumps(doc))
    return str(p)


def scene_doc(blocks, **top):
    return {"format": "rigidblocks-scene", "version": 1, "dimension": 2, "blocks": blocks,
            **top}


def one_line_error(capsys, *words):
    err = capsys.readouterr().err
    assert err.startswith("rigidblocks: error: ") and err.count("\n") == 1, err
    assert "Traceback" not in err
    for w in words:
        assert w in err, err
    return err


def test_block_smaller_than_the_contact_tolerance_is_named(tmp_path, capsys):
    """A 1e-5 x 1e-5 block on a 1000 m base: the contact tolerance is 1e-7 x the scene's
    size (about 1.4e-4 here), so the block shrinks to a point (issue 17 item 2)."""
    path = write(tmp_path, "tiny.json", scene_doc([
        {"id": "base", "vertices": rect(-500, -100, 1000, 100), "support": True},
        {"id": "tiny", "vertices": rect(0, 0, 1e-5, 1e-5)},
    ], unit_weight=20.0, friction=0.5, live_body_force=[1, 0]))
    for cmd in ("check", "friction", "load"):
        assert main([cmd, path]) == 2
        one_line_error(capsys, f"{path}: block 'tiny'", "contact tolerance",
                       "lower --contact-tol")


def test_block_smaller_than_the_contact_tolerance_is_named_in_3d(tmp_path, capsys):
    from rigidblocks.generators.solids import box

    bv, bf = box(-500, -500, -100, 1000, 1000, 100)
    tv, tf = box(0, 0, 0, 1e-5, 1e-5, 1e-5)
    path = write(tmp_path, "tiny3d.json", {**scene_doc([
        {"id": "base", "vertices": bv, "faces": bf, "support": True},
        {"id": "tiny", "vertices": tv, "faces": tf},
    ], unit_weight=20.0, live_body_force=[1, 0, 0]), "dimension": 3})
    assert main(["load", path]) == 2
    one_line_error(capsys, f"{path}: block 'tiny'", "contact tolerance")


def test_errors_found_deep_name_the_file(tmp_path, capsys):
    """A 3D scene with --solver highs, and a file that exists but is no DXF: the error
    named no file, and the second said "no such file or cannot read it"."""
    from rigidblocks.generators import build
    from rigidblocks.io import write_scene

    box = tmp_path / "box.json"
    write_scene(build("box_stack"), box)
    assert main(["load", str(box), "--solver", "highs"]) == 2
    one_line_error(capsys, f"{box}: the HiGHS back end solves linear programs only")
    junk = tmp_path / "junk.dxf"
    junk.write_text("garbage\n")
    assert main(["import-dxf", str(junk), "-o", str(tmp_path / "j.json")]) == 2
    one_line_error(capsys, f"{junk}: not a DXF file")


def test_an_option_the_method_does_not_take_is_refused(capsys):
    """`load --mechanism blend --method distortion` was silently ignored (and no
    governing line was printed): the blend is the convex path's (without dilatancy the
    mechanism is the capped laws' LP's, and blends: test_nonassociative.py)."""
    assert main(["load", str(EXAMPLES / "reference.json"), "--mechanism", "blend",
                 "--method", "distortion"]) == 2
    one_line_error(capsys, "--mechanism blend", "not of the distortion method")


def test_thickness_json_gives_the_friction_as_a_number(capsys):
    """`thickness --json` wrote "friction": "0.6" (the option's text), where the other
    commands write a number."""
    assert main(["thickness", "arch", "--friction", "0.6", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["friction"] == 0.6


def test_joint_overridden_twice_is_named(tmp_path, capsys):
    path = write(tmp_path, "twice.json", scene_doc([
        {"id": "base", "vertices": rect(-1, -1, 3, 1), "support": True},
        {"id": "B", "vertices": rect(0, 0, 1, 1)},
    ], unit_weight=1.0, joints=[{"blocks": ["base", "B"], "friction": 0.3},
                                {"blocks": ["B", "base"], "friction": 0.5}]))
    assert main(["check", path]) == 2
    one_line_error(capsys, "joint 'B'-'base'", "overridden twice")


@pytest.mark.parametrize("value", ["inf", "-inf", "nan", "NaN", "1e999"])
def test_non_finite_numbers_are_usage_errors(value, capsys):
    arch = str(EXAMPLES / "arch.json")
    for argv in (["check", arch, f"--load-factor={value}"],
                 ["friction", arch, f"--load-factor={value}"],
                 ["check", arch, f"--contact-tol={value}"],
                 ["export-dxf", arch, "-o", "a.dxf", f"--load-factor={value}"],
                 ["thickness", "arch", "--lo", value]):
        assert main(argv) == 2, argv
        one_line_error(capsys, value)


@pytest.mark.parametrize("value", ["nan", "-1", "x"])
def test_friction_option_names_what_it_takes(value, capsys):
    """--friction takes a number >= 0 or "infinite"; nan is neither (it read "must be
    >= 0, got nan")."""
    assert main(["load", str(EXAMPLES / "arch.json"), f"--friction={value}"]) == 2
    one_line_error(capsys, "friction must be")


def test_a_friction_too_large_to_solve_says_infinite(tmp_path, capsys):
    """--friction 1e10 ended in "solver failure: clarabel could not solve the maximum
    load problem (InsufficientProgress)", exit 1, and a scene's 1e200 in NumericalError:
    a finite friction above 1e6 (the arch solves at 1e8) is a usage error that says how
    to ask for no sliding; 1e6 itself is solved."""
    arch = str(EXAMPLES / "arch.json")
    assert main(["load", arch, "--friction", "1e10"]) == 2
    one_line_error(capsys, "friction 1e+10 is above 1e+06", 'give "infinite"')
    doc = json.loads((EXAMPLES / "arch.json").read_text())
    doc["friction"] = 1e200
    path = write(tmp_path, "a.json", doc)
    assert main(["load", path]) == 2
    one_line_error(capsys, path, '"friction"', "is above 1e+06")
    assert main(["load", arch, "--friction", "1e6"]) == 0


def test_usage_error_names_the_program_once(capsys):
    """A usage error reads "rigidblocks: error: load: argument ..." (it read
    "rigidblocks: error: rigidblocks load: argument ...")."""
    assert main(["load", str(EXAMPLES / "arch.json"), "--rtol=x"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("rigidblocks: error: load: argument --rtol"), err
    assert err.count("rigidblocks") == 1, err
    # an option the command does not know is named with the command (it was not)
    assert main(["load", str(EXAMPLES / "arch.json"), "--frobnicate"]) == 2
    err = capsys.readouterr().err
    assert err == "rigidblocks: error: load: unrecognized arguments: --frobnicate\n", err


def test_a_csv_file_away_from_joints_says_where_it_goes(tmp_path, capsys):
    """`check SCENE --joints --friction 0.5 r.csv`: --joints took no file (the next
    word was an option), and r.csv was only "unrecognized"; the error says that the file
    follows --joints, and nothing is written."""
    out = tmp_path / "r.csv"
    arch = str(EXAMPLES / "arch.json")
    assert main(["check", arch, "--joints", "--friction", "0.5", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.endswith("(the CSV file of --joints follows it: --joints FILE.csv)\n"), err
    assert not out.exists()
    assert main(["check", arch, "--joints", str(out), "--friction", "0.5"]) == 0
    assert out.exists()


def test_every_float_option_of_every_command_is_finite():
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    floats = [(name, a.dest) for name, p in sub.choices.items() for a in p._actions
              if a.type is float]
    assert floats == []
    n = sum(a.type is finite_float for p in sub.choices.values() for a in p._actions)
    assert n >= 8


@pytest.mark.parametrize("argv", [
    ["example", "arch", "-o", "/nonexistent/x.json"],
    ["example", "-o", "/nonexistent/x.json", "arch"],
    ["import-dxf", "DXF", "-o", "/nonexistent/x.json"],
    ["export-dxf", str(EXAMPLES / "arch.json"), "-o", "/nonexistent/a.dxf"],
    ["plot", str(EXAMPLES / "arch.json"), "-o", "/nonexistent/a.png"],
    ["sweep", str(SWEEP), "-o", "/nonexistent/x.parquet"],
], ids=["example", "example-o-first", "import-dxf", "export-dxf", "plot", "sweep"])
def test_unwritable_output_is_refused_before_any_work(argv, tmp_path, capsys, monkeypatch):
    from pathlib import Path

    if "DXF" in argv:
        argv[argv.index("DXF")] = str(tmp_path / "missing.dxf")  # not even read
    calls = []
    monkeypatch.setattr("rigidblocks.generators.Generator.__call__",
                        lambda *a, **k: calls.append(a))
    assert main(argv) == 2
    one_line_error(capsys, "/nonexistent", "no such folder")
    assert not calls and not Path("/nonexistent").exists()


@pytest.mark.parametrize("command, name", [
    ("extrude", "s.json"), ("import-dxf", "d.dxf"), ("import-compas", "c.json")])
def test_an_output_that_is_the_input_is_refused(command, name, tmp_path, capsys):
    """`import-dxf same.dxf -o same.dxf` replaced the drawing by a scene file (exit 0),
    `extrude s.json -o s.json` the 2D scene by its prisms, `import-compas` likewise: an
    output naming a file the command reads is refused before any work, the file kept."""
    import shutil

    src = tmp_path / name
    shutil.copy(EXAMPLES / "wall.json", src)  # (each refused before it is read)
    before = src.read_bytes()
    assert main([command, str(src), "-o", str(tmp_path / "." / name)]) == 2
    one_line_error(capsys, f"-o {tmp_path / '.' / name}: is the file it reads", "give "
                   "another name")
    assert src.read_bytes() == before


@pytest.mark.parametrize("command", ["check", "friction", "load"])
def test_a_joint_table_that_is_the_scene_is_refused(command, tmp_path, capsys):
    """`check io.json --joints io.json` replaced the scene by its joint table (exit 0),
    where -o naming an input is refused."""
    import shutil

    src = tmp_path / "io.json"
    shutil.copy(EXAMPLES / "wall.json", src)
    before = src.read_bytes()
    assert main([command, str(src), "--joints", str(src)]) == 2
    one_line_error(capsys, f"--joints {src}: is the file it reads")
    assert src.read_bytes() == before


def test_output_that_is_a_folder_is_refused(tmp_path, capsys):
    assert main(["example", "arch", "-o", str(tmp_path)]) == 2
    one_line_error(capsys, "is a folder")


def test_write_scene_to_a_missing_folder_is_an_input_error(tmp_path):
    from rigidblocks.errors import InputError
    from rigidblocks.generators import build
    from rigidblocks.io import write_scene

    with pytest.raises(InputError, match="cannot write"):
        write_scene(build("arch"), tmp_path / "no" / "x.json")


def test_sweep_output_folder_is_not_created(tmp_path, capsys):
    out = tmp_path / "no" / "such" / "x.parquet"
    assert main(["sweep", str(SWEEP), "-o", str(out), "--workers", "1",
                 "--no-progress"]) == 2
    one_line_error(capsys, "no such folder")
    assert not (tmp_path / "no").exists()
    from rigidblocks import study
    from rigidblocks.errors import InputError

    with pytest.raises(InputError, match="no such folder"):
        study.run("flat_arch", grid={"voussoirs": [3]}, output=out, workers=1,
                  progress=False)
    assert not (tmp_path / "no").exists()


def test_unreachable_scheduler_fails_within_seconds_naming_it(tmp_path, capsys):
    t0 = time.perf_counter()
    assert main(["sweep", str(SWEEP), "-o", str(tmp_path / "x.parquet"), "--scheduler",
                 "tcp://127.0.0.1:9999", "--no-progress"]) == 2
    assert time.perf_counter() - t0 < 15
    one_line_error(capsys, "tcp://127.0.0.1:9999", "Dask scheduler")
    assert not list(tmp_path.iterdir())


def test_sweep_without_the_study_extra_names_it(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas -> ImportError
    assert main(["sweep", str(SWEEP), "-o", str(tmp_path / "x.parquet")]) == 2
    one_line_error(capsys, "pandas", "pip install 'rigidblocks[study]'")
    from rigidblocks import study
    from rigidblocks.errors import InputError

    with pytest.raises(InputError, match=r"rigidblocks\[study\]"):
        study.run("flat_arch", grid={"voussoirs": [3]}, workers=1, progress=False)


def test_solver_not_installed_says_how_to_install_it(capsys, monkeypatch):
    """ECOS comes with the solvers extra: where it is missing (here made so) the error
    names the extra; a solver no extra installs names its package."""
    import cvxpy as cp

    installed = [s for s in cp.installed_solvers() if s not in ("ECOS", "MOSEK")]
    monkeypatch.setattr(cp, "installed_solvers", lambda: installed)
    assert main(["check", str(EXAMPLES / "arch.json"), "--solver", "ecos"]) == 2
    one_line_error(capsys, "'ecos'", "pip install 'rigidblocks[solvers]'")
    assert main(["check", str(EXAMPLES / "arch.json"), "--solver", "cvxpy-mosek"]) == 2
    one_line_error(capsys, "'mosek'", "pip install mosek")
    # a name cvxpy does not know is a typo, with no package to install (it said "pip
    # install foo")
    assert main(["check", str(EXAMPLES / "arch.json"), "--solver", "cvxpy-FOO"]) == 2
    msg = one_line_error(capsys, "cvxpy has no solver 'foo'", "installed: ")
    assert "pip install" not in msg


def test_dxf_without_the_cad_extra_names_it(tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "ezdxf", None)
    assert main(["import-dxf", str(tmp_path / "a.dxf"), "-o", str(tmp_path / "a.json")]) == 2
    one_line_error(capsys, "ezdxf", "pip install 'rigidblocks[cad]'")


def test_a_solver_failure_at_a_huge_friction_names_it(tmp_path, capsys):
    """The 4 x 4 running-bond wall at f = 1e6 (accepted: at most 1e6): Clarabel ends
    AlmostSolved and the failure named only the status; it names the friction and the
    law meant ("infinite"), which gives lambda* = 2, as f = 1e5 does."""
    from rigidblocks.generators import build
    from rigidblocks.io import write_scene

    path = tmp_path / "w.json"
    write_scene(build("wall", courses=4, blocks_per_course=4), path)
    assert main(["load", str(path), "--friction", "1e6"]) == 1
    err = capsys.readouterr().err
    assert err.startswith("rigidblocks: solver failure: ") and err.rstrip().endswith(
        '(at f = 1e+06: a friction this large is beyond what the solver resolves on this '
        'scene; "infinite" is the law without sliding)'), err
    for f in ("infinite", "1e5"):
        assert main(["load", str(path), "--friction", f]) == 0
        assert "lambda* = 2," in capsys.readouterr().out


def test_an_output_that_cannot_be_written_is_one_line_exit_2():
    """`load --json > /dev/full` ended in an OSError traceback (No space left on
    device), exit 1; the README promises one line and exit 2 for an unwritable output.
    (/dev/full: Linux, where the tests run.)"""
    import subprocess

    with open("/dev/full", "w") as full:
        run = subprocess.run([sys.executable, "-m", "rigidblocks.cli.main", "load",
                              str(EXAMPLES / "arch.json"), "--json"], stdout=full,
                             stderr=subprocess.PIPE, text=True, timeout=300)
    assert run.returncode == 2
    assert run.stderr == ("rigidblocks: error: cannot write: standard output: No space "
                          "left on device\n"), run.stderr
    # the help too (argparse dropped the failed write: exit 0, nothing said)
    with open("/dev/full", "w") as full:
        run = subprocess.run([sys.executable, "-m", "rigidblocks.cli.main", "--help"],
                             stdout=full, stderr=subprocess.PIPE, text=True, timeout=300)
    assert run.returncode == 2 and "cannot write: standard output" in run.stderr


def test_a_scene_no_reader_accepts_is_not_written(tmp_path, capsys):
    """`extrude --depth 1e200` wrote a scene every command then refused (a writer must
    round-trip what a reader accepts); the reader's message called the diagonal cubed
    the box's volume (1e+150 for a box of volume 1e50)."""
    out = tmp_path / "deep.json"
    assert main(["extrude", str(EXAMPLES / "wall.json"), "--depth", "1e200", "-o",
                 str(out)]) == 2
    one_line_error(capsys, "a coordinate reaches 1e+200, beyond 1e+150")
    assert not out.exists()
    assert main(["extrude", str(EXAMPLES / "wall.json"), "--depth", "1e50", "-o",
                 str(out)]) == 2
    one_line_error(capsys, "its volume's bound (its bounding box's diagonal^3) reaches")


def _two_blocks(**top):
    return scene_doc([{"id": "base", "vertices": rect(0, 0, 2, 0.5), "support": True},
                      {"id": "A", "vertices": rect(0.5, 0.5, 1, 0.5)}],
                     unit_weight=20.0, friction=0.6, live_body_force=[1, 0], **top)


def test_a_whole_dimension_written_as_a_float_is_read_as_its_integer(tmp_path, capsys):
    """"dimension": 2.0 (a JSON writer's float) ended in an IndexError from the load
    rows; "version": 1.0 was already read as 1. The block slides at f = 0.6 or tips at
    b/h = 2: lambda* = 0.6."""
    doc = _two_blocks()
    doc["dimension"] = 2.0
    path = write(tmp_path, "float_dim.json", doc)
    assert main(["load", path, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["load_multiplier"] == pytest.approx(0.6)


def test_an_integer_literal_past_the_digit_limit_is_malformed_json(tmp_path, capsys):
    """A 5,000-digit depth: Python's integer conversion raised a ValueError (a traceback);
    in a sweep spec too."""
    doc = _two_blocks()
    path = tmp_path / "big.json"
    path.write_text(json.dumps(doc).replace('"unit_weight": 20.0', '"unit_weight": '
                                            + "9" * 5000))
    assert main(["check", str(path)]) == 2
    one_line_error(capsys, f"{path}: malformed JSON", "4300 digits")
    spec = tmp_path / "big_spec.json"
    spec.write_text('{"format": "rigidblocks-sweep", "version": 1, "generator": "arch", '
                    '"grid": {"voussoirs": [' + "9" * 5000 + ']}, "analyses": ["check"]}')
    assert main(["sweep", str(spec), "-o", str(tmp_path / "o.csv")]) == 2
    one_line_error(capsys, f"{spec}: invalid JSON", "4300 digits")


@pytest.mark.parametrize("span", ["[0.1, 1e400]", "[3, " + "9" * 400 + "]"])
def test_a_random_range_too_wide_to_draw_from_is_refused(span, tmp_path, capsys):
    """numpy raised an OverflowError ("high - low range exceeds valid bounds") for a
    uniform range of [0.1, inf]; a 400-digit integer bound gives no float at all."""
    kind, name = ("uniform", "thickness") if "e400" in span else ("integers", "voussoirs")
    spec = tmp_path / "r.json"
    spec.write_text('{"format": "rigidblocks-sweep", "version": 1, "generator": "arch", '
                    f'"random": {{"samples": 2, "seed": 1, "{kind}": {{"{name}": {span}}}}}, '
                    '"analyses": ["check"]}')
    assert main(["sweep", str(spec), "-o", str(tmp_path / "o.csv")]) == 2
    one_line_error(capsys, f"random.{kind}.{name}: expected finite numbers")


@pytest.mark.parametrize("name, text, said", [
    ("o.parquet", "x\n", "the existing output cannot be read"),
    ("o.csv", "garbage\n", "the existing output has no case_id column"),
])
def test_an_existing_output_that_is_no_results_file_is_refused(name, text, said, tmp_path,
                                                                capsys):
    """A parquet output of 2 bytes ended in pyarrow's ArrowInvalid traceback; a CSV whose
    only line is "garbage" (a header, no rows) was overwritten without a word. Both are
    refused and left as they were."""
    bad = tmp_path / name
    bad.write_text(text)
    assert main(["sweep", str(SWEEP), "-o", str(bad), "--workers", "1",
                 "--no-progress"]) == 2
    one_line_error(capsys, f"{bad}: {said}")
    assert bad.read_text() == text


@pytest.mark.parametrize("argv, words", [
    (["check", str(EXAMPLES / "reference.json"), "--contact-tol", "0"],
     ["argument --contact-tol: must be > 0"]),
    (["sweep", str(SWEEP), "-o", "o.csv", "--workers", "0"],
     ["argument --workers: must be >= 1"]),
    (["sweep", str(SWEEP), "-o", "o.csv", "--batch-size", "0"],
     ["argument --batch-size: must be >= 1"]),
])
def test_option_errors_name_the_option(argv, words, capsys):
    """They read "contact_tol must be a number > 0, got 0.0" and "workers must be an
    integer >= 1", the library's names, after the study had been read."""
    assert main(argv) == 2
    one_line_error(capsys, *words)


def test_an_empty_path_or_a_folder_is_no_scene_file(tmp_path, capsys):
    """`check ''` read "cannot read: [Errno 21] Is a directory: '.'"."""
    assert main(["check", ""]) == 2
    one_line_error(capsys, "no scene file given (an empty path)")
    assert main(["check", str(tmp_path)]) == 2
    one_line_error(capsys, f"{tmp_path}: a folder, not a scene file")
