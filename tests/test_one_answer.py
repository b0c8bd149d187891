"""One question, one answer: every command that answers it gives the same one.

Each bundled example (examples/*.json) goes through ``check``, ``friction`` and ``load``
(their JSON is the reference), and through the commands that answer the same question
with their own defaults: ``plot`` (the SVG's title), ``report`` (the HTML page),
``export-dxf`` (the drawing's text), a sweep (the study's row) and, in 2D, ``path``
(the load path of the distortion method). Nothing is given on the command line, so each
command must take the load factor, the friction and the flow from the scene (the
examples write ``load_factor`` 0: the dead load alone for check and friction).

Reference for ``path``: its states are admissible equilibrium states of the
associative problem at every step (static theorem), so its collapse load is at most
lambda*; it locates the collapse between steps and bisects it, to within 1 % here, or
says it is undecided where the iteration stalls before the limit (the vertical-joint
flat arch: admissible at 0.2484, undecided at 0.2492, lambda* = 0.2496).
"""

from __future__ import annotations

import json
import math
import re

import ezdxf
import matplotlib
import pytest
from conftest import EXAMPLES

matplotlib.use("Agg")

from rigidblocks import min_friction  # noqa: E402
from rigidblocks.cli.main import main  # noqa: E402
from rigidblocks.io import read_scene  # noqa: E402

FILES = sorted(EXAMPLES.glob("*.json"))
VERDICT = {"admissible": "ADMISSIBLE: it stands", "inadmissible": "NOT ADMISSIBLE",
           "stable": "STANDS", "unstable": "UNSTABLE", "collapse": "COLLAPSE",
           "unbounded": "UNBOUNDED"}
NUMBER = {"check": None, "friction": "friction_factor", "load": "load_multiplier"}


def run_json(capsys, argv):
    capsys.readouterr()
    main(argv + ["--json"])
    return json.loads(capsys.readouterr().out)


def number_text(value: float, ref: dict | None = None, key: str = "") -> str:
    """The number as every command writes it in its answer: 6 significant digits, on
    the safe side of the answer beyond round-off (f* up, lambda* down;
    test_honest_answers.py checks that rounding)."""
    from rigidblocks.answer import fmt_safe

    return fmt_safe(value, 6, key == "friction_factor")


def svg_text(path) -> str:
    """The text of an SVG (matplotlib writes each line of a title as a <text>)."""
    return " ".join(re.sub(r"<[^>]+>", " ", path.read_text()).split())


@pytest.fixture(scope="module")
def answers():
    """The JSON answers of check, friction and load on every example (the reference)."""
    import io
    from contextlib import redirect_stdout

    out = {}
    for f in FILES:
        for cmd in NUMBER:
            buf = io.StringIO()
            with redirect_stdout(buf):
                main([cmd, str(f), "--json"])
            out[f.name, cmd] = json.loads(buf.getvalue())
    return out


@pytest.mark.parametrize("path", FILES, ids=[f.stem for f in FILES])
def test_every_command_gives_the_same_answer(path, answers, tmp_path, capsys):
    scene = read_scene(path)
    for cmd, key in NUMBER.items():
        ref = answers[path.name, cmd]
        words = VERDICT[ref["status"]]
        value = ref.get(key) if key else None
        # the plain-words answer of the command itself
        capsys.readouterr()
        main([cmd, str(path)])
        text = capsys.readouterr().out
        assert words in text, (cmd, text)
        if value is not None:
            assert number_text(value, ref, key) in text, (cmd, text)
        assert "seed" not in text.lower()
        # plot: the title
        svg = tmp_path / f"{cmd}.svg"
        assert main(["plot", str(path), "--analysis", cmd, "-o", str(svg)]) == 0
        title = svg_text(svg)
        assert words in title, (cmd, title)
        if cmd != "load" and scene.has_live_load and not scene.effective_load_factor:
            assert "self-weight only" in title and "self-weight only" in text
        if value is not None:
            assert number_text(value, ref, key) in title, (cmd, title)
        # report: the status and the number
        html = tmp_path / f"{cmd}.html"
        main(["report", str(path), "--analysis", cmd, "-o", str(html)])
        page = html.read_text(encoding="utf-8")
        assert f'data-status="{ref["status"]}"' in page
        if value is not None:
            assert number_text(value, ref, key) in page
        assert "seed" not in re.sub(r"<script.*?</script>", "", page, flags=re.S).lower()
        # export-dxf (2D): the drawing's text
        if scene.dimension == 2:
            dxf = tmp_path / f"{cmd}.dxf"
            assert main(["export-dxf", str(path), "--analysis", cmd, "-o", str(dxf)]) == 0
            notes = " ".join(e.dxf.text for e in ezdxf.readfile(dxf).modelspace()
                             if e.dxftype() == "TEXT" and e.dxf.layer == "RB_TEXT")
            assert words in notes, (cmd, notes)
            if value is not None:
                assert number_text(value, ref, key) in notes, (cmd, notes)


def test_a_sweep_over_the_examples_gives_the_same_answers(answers):
    """A sweep of one case per example, with nothing given: the scene's defaults."""
    from rigidblocks import study

    for path in FILES:
        row = study.run(str(path), cases=[{}], workers=1, progress=False,
                        analyses=["check", "min_friction", "max_load_multiplier"]
                        ).frame.iloc[0]
        assert row["status"] == "ok", row["error"]
        assert row["check_status"] == answers[path.name, "check"]["status"]
        for cmd, name, key in (("friction", "min_friction", "friction_factor"),
                               ("load", "max_load_multiplier", "load_multiplier")):
            ref = answers[path.name, cmd]
            assert row[f"{name}_status"] == ref["status"], (path.name, cmd)
            if ref[key] is not None:
                assert row[key] == pytest.approx(ref[key], rel=1e-6), (path.name, cmd)


def test_the_load_path_ends_where_load_says(answers, capsys):
    """2D examples: `path` collapses at lambda* to 1 % (never above it: its states are
    admissible), does not collapse within its range (2) where lambda* is beyond it,
    and is unstable, as `load` says, where the dead load alone stands on no admissible
    state (it read "COLLAPSE at lambda = 0" where `load` read "UNSTABLE")."""
    for path in FILES:
        if read_scene(path).dimension != 2:
            continue
        ref = answers[path.name, "load"]
        res = run_json(capsys, ["path", str(path)])
        lam = ref["load_multiplier"]
        if ref["status"] == "unstable":
            assert res["status"] == "unstable" and res["collapse_load"] is None, path.name
        elif lam > 2.0:
            assert res["status"] == "standing", path.name
        elif res["status"] == "undecided":
            # the iteration stalls near the limit: the path says so, with the last
            # admissible load (flat_arch_vertical: 0.24844, undecided at 0.24922,
            # lambda* = 0.2496)
            lo, hi = res["bracket"]
            assert lam * 0.99 <= lo <= lam * (1 + 1e-6) and res["collapse_load"] is None
        else:
            assert res["status"] == "collapse", path.name
            if any(e["kind"] == "crack" for e in res["events"]):
                # a bond cracked on the way (fig4a_bonded): at most lambda* with the
                # bond intact, and lambda* of the dry scene once it has cracked
                assert res["collapse_load"] <= lam * (1 + 1e-6), path.name
                lam = dry_multiplier(read_scene(path))
            assert lam * 0.99 <= res["collapse_load"] <= lam * (1 + 1e-6), path.name


def dry_multiplier(scene) -> float:
    """lambda* of the scene with its joints' tensile strength and cohesion removed."""
    from rigidblocks import max_load_multiplier
    from rigidblocks.io.scene_file import dumps_scene, loads_json, scene_from_dict

    doc = loads_json(dumps_scene(scene))
    for j in doc.get("joints", []):
        j.pop("tensile_strength", None)
        j.pop("cohesion", None)
    return max_load_multiplier(scene_from_dict(doc)).load_multiplier


def test_negative_load_factor_is_refused_everywhere(capsys):
    """A scene file's load_factor must be >= 0; so must the option of every command."""
    f = str(EXAMPLES / "arch.json")
    for argv in (["check", f], ["friction", f], ["plot", f, "--analysis", "check"],
                 ["report", f, "--analysis", "friction"],
                 ["export-dxf", f, "--analysis", "check", "-o", "x.dxf"]):
        assert main(argv + ["--load-factor", "-1"]) == 2, argv
        err = capsys.readouterr().err
        assert "--load-factor" in err and ">= 0" in err, err


def test_bad_friction_and_path_options_name_the_option(capsys):
    """A negative or non-numeric --friction, --steps 0 and --max-load 0 are usage errors
    (exit 2) naming the option, as every other option's (before: "friction must be
    >= 0" named no option, "load_path needs steps >= 1" a Python function); so is
    --steps 1e9, which ran on for hours."""
    f = str(EXAMPLES / "arch.json")
    for argv, opt in ((["check", f, "--friction", "-1"], "--friction"),
                      (["load", f, "--friction", "abc"], "--friction"),
                      (["path", f, "--friction", "-0.5"], "--friction"),
                      (["plot", f, "--analysis", "load", "--friction", "-1"], "--friction"),
                      (["path", f, "--steps", "0"], "--steps"),
                      (["path", f, "--steps", "1000000000"], "--steps"),
                      (["path", f, "--max-load", "0"], "--max-load")):
        assert main(argv) == 2, argv
        err = capsys.readouterr().err
        assert f"argument {opt}:" in err and len(err.strip().splitlines()) == 1, err
    assert main(["check", f, "--friction", "infinite"]) == 0
    capsys.readouterr()


def test_mechanism_counts_are_one_counting(capsys):
    """The joints `load` says hinge, slide, slide and hinge, or open are those the
    report's joint table marks so (each joint in one group), on the 3D examples."""
    from rigidblocks import max_load_multiplier
    from rigidblocks.answer import mechanism_groups
    from rigidblocks.reporting import content

    for name in ("box_stack_3d.json", "corbel_dome.json"):
        scene = read_scene(EXAMPLES / name)
        res = max_load_multiplier(scene)
        states = content.joint_table(res)["state"]
        groups = dict(mechanism_groups(res))
        for mode, word in (("hinge", "hinging"), ("slide", "sliding"),
                           ("slide+hinge", "sliding and hinging"), ("open", "opening")):
            assert len(groups.get(word, [])) == states.count(mode), (name, mode)
        capsys.readouterr()
        main(["load", str(EXAMPLES / name)])
        line = next(ln for ln in capsys.readouterr().out.splitlines()
                    if ln.startswith("governing"))
        for word, names in groups.items():
            assert re.search(rf"\b{len(names)} {word}\b", line), (name, word, line)


def test_non_associative_friction_is_printed_inside_its_bracket(capsys):
    """friction --flow non-associative on the arch: the f* printed lies inside the
    bracket the answer gives for it (in the JSON), which holds the static f* (the arch
    stands at it without dilatancy: the note says they are equal)."""
    capsys.readouterr()
    main(["friction", str(EXAMPLES / "arch.json"), "--flow", "non-associative", "--json"])
    data = json.loads(capsys.readouterr().out)
    lo, hi = data["bracket"]
    static = min_friction(read_scene(EXAMPLES / "arch.json"))
    assert lo <= static.friction_factor <= hi
    main(["friction", str(EXAMPLES / "arch.json"), "--flow", "non-associative"])
    out = capsys.readouterr().out
    printed = float(re.search(r"^answer\s+f\* = ([0-9.e+-]+)", out, re.M).group(1))
    # printed to 6 significant figures on the safe side: at or above f* (the bracket's
    # upper end), by less than one unit of the sixth figure
    fs = data["friction_factor"]
    unit = 10.0 ** (math.floor(math.log10(fs)) - 5)
    assert lo <= fs <= printed < fs + unit, (printed, lo, hi)


def test_solver_notes_are_verbose_and_a_fallback_is_a_reason(capsys):
    """Notes on the solver go under --verbose (the JSON keeps them); a back end whose
    answers were solved again by Clarabel is said in the answer (no cross-check)."""
    from rigidblocks.answer import split_notes

    note = ("answers of scs that failed their check against the problem were solved "
            "again by clarabel (first: the relaxation problem (cvxpy-scs optimal: primal "
            "residual 1e-05))")
    reasons, notes = split_notes([note, "block 'beam' touches no other block"])
    assert notes == (note,)
    assert len(reasons) == 2 and "block 'beam' touches no other block" in reasons
    assert any("not a cross-check of clarabel by scs" in r for r in reasons)
    # the arch's load without dilatancy comes with a note on the accuracy of its
    # associative bound
    f = str(EXAMPLES / "arch.json")
    capsys.readouterr()
    main(["load", f, "--flow", "non-associative"])
    quiet = capsys.readouterr().out
    main(["load", f, "--flow", "non-associative", "--verbose"])
    loud = capsys.readouterr().out
    assert "\nnote " not in quiet and "\nnote " in loud and "\nsolver " in loud
    assert set(quiet.splitlines()) <= set(loud.splitlines())


def test_path_table_has_headers_with_units(capsys):
    """`path` prints its events under column headers with units: lambda, the live load
    it means in the force unit (lambda x 37.69 kN for the arch), the event, the joints."""
    capsys.readouterr()
    assert main(["path", str(EXAMPLES / "arch.json")]) == 0
    lines = capsys.readouterr().out.splitlines()
    header = next(i for i, ln in enumerate(lines) if "lambda [-]" in ln)
    assert "live [kN]" in lines[header] and "event" in lines[header]
    lam, live = (float(x) for x in lines[header + 1].split()[:2])
    assert live == pytest.approx(lam * 37.69, rel=1e-3)


def test_path_standing_at_its_end_says_how_far_it_went(capsys):
    """The reference model with self-weight carries more than the path's default end,
    lambda = 2 (the convex path's lambda*, checked here, is 2.4), so its path ends
    standing: the status says at which lambda, and the live load that means in the
    force unit (2 x 100 N, the two 50 N pulls)."""
    from rigidblocks import max_load_multiplier

    scene = read_scene(EXAMPLES / "reference_self_weight.json")
    assert max_load_multiplier(scene).load_multiplier > 2.0
    capsys.readouterr()
    assert main(["path", str(EXAMPLES / "reference_self_weight.json")]) == 0
    status = next(ln for ln in capsys.readouterr().out.splitlines()
                  if ln.startswith("status"))
    assert status.startswith("status     STANDING at lambda = 2 (200 N), the end of the "
                             "path")
    assert "at its end joints" not in status  # nothing happens at lambda = 2
    # the bonded model's path to lambda = 1 ends where its bed joints become plastic,
    # and the path to 2 collapses at 1: STANDING at 1 said nothing of it
    assert main(["path", str(EXAMPLES / "fig4a_bonded.json"), "--max-load", "1",
                 "--steps", "5"]) == 0
    status = next(ln for ln in capsys.readouterr().out.splitlines()
                  if ln.startswith("status"))
    assert status.endswith("; at its end joints became plastic: it may collapse at once "
                           "beyond"), status
    assert main(["path", str(EXAMPLES / "fig4a_bonded.json")]) == 0
    assert "status     COLLAPSE at lambda = 1" in capsys.readouterr().out


def test_check_friction_demand_is_not_called_what_the_structure_needs(capsys):
    """The flat arch with vertical joints: the state of least complementary energy
    reaches |T|/N = f = 0.6 at a pier, while f* = 0.4714 (`friction`, below 0.6): the
    structure does not need 0.6, and `check` must not say it does; `friction` names its
    one governing joint in the singular when it has one."""
    path = EXAMPLES / "flat_arch_vertical.json"
    fstar = min_friction(read_scene(path)).friction_factor
    capsys.readouterr()
    assert main(["check", str(path)]) == 0
    why = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("why")]
    demand = float(re.search(r"\|T\|/N reaches (?:the friction limit f = )?([0-9.]+)",
                             why[0]).group(1))
    assert fstar < demand - 0.1
    assert "needs |T|/N" not in why[0] and "the least friction any state needs is f*" \
        in why[0]
    assert main(["friction", str(EXAMPLES / "arch.json"), "--load-factor", "0.1"]) == 0
    gov = next(ln for ln in capsys.readouterr().out.splitlines()
               if ln.startswith("governing"))
    assert gov.endswith("v1-abutment_r (f* rests on its friction)")


def test_the_answer_line_multiplies_the_number_it_prints(tmp_path, capsys):
    """The answer line multiplies lambda* as printed (it repeated it to 4 figures, cut
    down: "lambda* = 0.0749999, that is 0.07499 x 192 kN"), and a live load of couples
    alone is given as a moment (it read "20 x 0 force units = 0 force units in all").
    The block 1 x 2 (weight 40) under a live couple of 1 tips at lambda* = 20: the
    weight's lever 0.5 times 40 against lambda times 1 (rigid-body statics)."""
    from rigidblocks.io import write_scene
    from rigidblocks.io.scene_file import scene_from_dict

    assert main(["load", str(EXAMPLES / "arch.json")]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines()
                if ln.startswith("answer"))
    m = re.match(r"answer +lambda\* = ([0-9.]+), that is ([0-9.]+) x ", line)
    assert m and m.group(1) == m.group(2), line
    doc = {"format": "rigidblocks-scene", "version": 1, "dimension": 2,
           "units": {"length": "m", "force": "kN"}, "unit_weight": 20.0, "friction": 0.6,
           "blocks": [{"id": "base", "vertices": [[-1, -1], [3, -1], [3, 0], [-1, 0]],
                       "support": True},
                      {"id": "B", "vertices": [[0, 0], [1, 0], [1, 2], [0, 2]]}],
           "loads": [{"block": "B", "force": [0, 0], "moment": 1.0, "live": True}]}
    path = tmp_path / "couple.json"
    write_scene(scene_from_dict(doc), path)
    assert main(["load", str(path)]) == 0
    out = capsys.readouterr().out
    assert "1 live couple, no force: 1 kN m" in out
    assert "lambda* = 20, that is 20 x 1 kN m = 20 kN m of couples" in out


def test_a_mechanism_that_is_one_of_several_says_so(capsys):
    """The reference model is symmetric: it collapses at lambda* = 1.2 (the seed's Fig.
    4) as its central blocks slide out to the left or to the right, and the vertex drawn
    is one of those mechanisms (it named support-left and right-top only, with nothing
    said of the others). The arch's four-hinge mechanism is the only one: no note."""
    assert main(["load", str(EXAMPLES / "reference.json")]) == 0
    out = capsys.readouterr().out
    assert "answer     lambda* = 1.2," in out
    assert "why        other collapse mechanisms reach the same multiplier: the one drawn" in out
    assert main(["load", str(EXAMPLES / "arch.json")]) == 0
    assert "other collapse mechanisms" not in capsys.readouterr().out


def test_the_path_says_what_its_live_load_is(capsys):
    """The reference model's two pulls of 50 N balance: the path's collapse line said
    "1.2 x 100 N = 120 N" where `load` says "in all (balanced: no resultant)" (the seed
    pulls each central block with 50 N, the 100 N is their sum)."""
    assert main(["path", str(EXAMPLES / "reference.json")]) == 0
    status = next(ln for ln in capsys.readouterr().out.splitlines()
                  if ln.startswith("status"))
    assert status == ("status     COLLAPSE at lambda = 1.2: 1.2 x 100 N = 120 N in all "
                      "(balanced: no resultant)")


def test_other_mechanisms_are_said_once_and_where_the_vertex_is_off_the_face(tmp_path,
                                                                             capsys):
    """The note on other optimal mechanisms: on the in-plane wall3d at f = 0.05 (any bed
    joint slides at lambda = f; the vertex drawn balances 2.4e-5 above lambda*, said with
    --verbose) it was not given; without dilatancy it came twice, once on the
    associative bound's mechanism, which is not the one drawn, and with --mechanism
    blend too."""
    from rigidblocks.generators import build
    from rigidblocks.io import write_scene

    path = tmp_path / "w.json"
    write_scene(build("wall3d", load_direction="in_plane", friction=0.05), path)
    assert main(["load", str(path)]) == 0
    assert "other collapse mechanisms reach the same multiplier" in capsys.readouterr().out
    ref = str(EXAMPLES / "reference.json")
    assert main(["load", ref, "--flow", "non-associative"]) == 0
    assert capsys.readouterr().out.count("other collapse mechanisms") == 1
    assert main(["load", ref, "--flow", "non-associative", "--mechanism", "blend"]) == 0
    assert "other collapse mechanisms" not in capsys.readouterr().out


@pytest.mark.parametrize("name", ["segmental_arch.json", "arch.json", "reference.json"])
def test_the_governing_joints_attribute_is_what_the_json_names(name):
    """`LoadResult.governing_joints` gave the sliding joints alone: [] for the segmental
    arch's four hinges, where its JSON and the terminal's governing line name them."""
    from rigidblocks import max_load_multiplier

    res = max_load_multiplier(read_scene(EXAMPLES / name))
    named = [list(p) for p in res.governing_joints]
    assert named and named == res.to_dict()["governing_joints"]
    from rigidblocks.answer import MODE_WORDS

    moving = {mode for mode, _ in MODE_WORDS}
    assert len(named) == sum(mode in moving for mode in res.mechanism.modes)
