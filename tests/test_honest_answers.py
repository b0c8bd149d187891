"""What the engineer reads: undecided answers never read as verdicts, the reasons are
given, a mechanism that can be drawn, and a first run that answers the usual question.

Closed forms (docs/validation.md): a b x h block on a base under a horizontal body
force lambda x weight has lambda* = min(f, b/h); the seed's reference model at f = 0.6
carries N = P/2 = 50 and |T| = H/2 = 25 on each bed joint of its central blocks in
the state of least complementary energy, so its friction demand is 25/50 = 0.5.
"""

from __future__ import annotations

import csv
import json
import math
import re

import pytest
from conftest import EXAMPLES, make_scene, rect

import rigidblocks as rb
from rigidblocks.cli.main import main
from rigidblocks.generators import build
from rigidblocks.methods import open_method
from rigidblocks.scene.extrude import extrude


def run(capsys, argv):
    code = main(argv)
    out = capsys.readouterr()
    return code, out.out, out.err


def run_json(capsys, argv):
    code, out, err = run(capsys, argv)
    return code, json.loads(out), err


def write(tmp_path, scene, name="s.json"):
    p = tmp_path / name
    rb.write_scene(scene, p)
    return str(p)


# -- undecided and failure ---------------------------------------------------------------
@pytest.fixture
def short_budget(monkeypatch):
    """An iteration budget too small for the distortion method to decide anything away
    from the elastic state (the reference model needs 15 iterations to prove
    admissibility and about 100 to prove inadmissibility)."""
    monkeypatch.setattr("rigidblocks.methods.distortion.MAX_ITER", 10)


def test_undecided_load_is_not_a_verdict_and_exits_3(capsys, short_budget):
    path = str(EXAMPLES / "reference.json")
    code, out, _ = run(capsys, ["load", path, "--method", "distortion"])
    assert code == 3
    assert "UNDECIDED" in out and "UNSTABLE" not in out and "lambda* =" not in out
    assert "\nanswer " not in out  # no number
    assert "hinging" not in out  # no empty mechanism lists that read as "no hinges"
    assert "\nwhy " in out  # the reason
    code, d, _ = run_json(capsys, ["load", path, "--method", "distortion", "--json"])
    assert code == 3
    assert d["status"] == "undecided" and d["load_multiplier"] is None
    assert d["notes"] and "bracket" in d


def test_a_picture_or_drawing_of_an_undecided_analysis_exits_3(tmp_path, capsys,
                                                              short_budget):
    """`plot` and `export-dxf` exit as the analysis they draw does (docs/scene-format.md:
    3 when it ran and is undecided), as `report` does; they exited 0."""
    path = str(EXAMPLES / "reference.json")
    for cmd, out in (("plot", "r.png"), ("export-dxf", "r.dxf")):
        code, text, _ = run(capsys, [cmd, path, "--analysis", "load", "--method",
                                     "distortion", "-o", str(tmp_path / out)])
        assert code == 3 and "(load: undecided)" in text, (cmd, text)
        code, text, _ = run(capsys, [cmd, path, "--analysis", "load",
                                     "-o", str(tmp_path / out)])
        assert code == 0 and "(load: collapse)" in text, (cmd, text)


def test_undecided_check_has_no_admissible_verdict(capsys, short_budget):
    scene = rb.read_scene(EXAMPLES / "reference.json")
    r = rb.check(scene, friction=0.6, method="distortion")
    assert r.status == "undecided" and r.admissible is None and not r.decided
    code, d, _ = run_json(capsys, ["check", str(EXAMPLES / "reference.json"), "--method",
                                   "distortion", "--friction", "0.6", "--json"])
    assert code == 3 and d["admissible"] is None and d["friction_demand"] is None
    code, out, _ = run(capsys, ["check", str(EXAMPLES / "reference.json"), "--method",
                                "distortion", "--friction", "0.6"])
    assert code == 3 and "ADMISSIBLE" not in out and "UNDECIDED" in out


def test_undecided_min_friction_gives_its_bracket(short_budget):
    """The reference model (f* = 0.5) at a budget that decides f = infinite but not the
    trials near f*: either undecided with the bracket the search reached, or decided."""
    scene = rb.read_scene(EXAMPLES / "reference.json")
    r = rb.min_friction(scene, method="distortion")
    if r.status == "undecided":
        assert r.friction_factor is None
        if r.bracket is not None:
            assert r.bracket[0] <= 0.5 <= r.bracket[1] + 1e-9
            assert r.to_dict()["bracket"] == list(r.bracket)


# -- the reasons --------------------------------------------------------------------------
def lifted_beam():
    """A beam drawn 1 mm above its two posts: nothing touches it."""
    return make_scene([
        {"id": "ground", "vertices": rect(-1, -0.5, 6, 0.5), "support": True},
        {"id": "postL", "vertices": rect(0, 0, 0.4, 2)},
        {"id": "postR", "vertices": rect(3, 0, 0.4, 2)},
        {"id": "beam", "vertices": rect(-0.2, 2.001, 3.8, 0.4)},
    ], unit_weight=20.0, friction=0.6)


def unheld_error(capsys, path, *words, commands=("check", "friction", "load")):
    """Every analysis refuses a scene with blocks that nothing holds: one line naming
    them, exit 2 (a verdict, NOT ADMISSIBLE or UNSTABLE, read as the structure's)."""
    for cmd in commands:
        argv = [cmd, path] + (["--load-factor", "0"] if cmd == "check" else [])
        code, out, err = run(capsys, argv)
        assert code == 2 and out == "", (cmd, out)
        assert err.startswith(f"rigidblocks: error: {path}: ") and err.count("\n") == 1, err
        for w in words:
            assert w in err, err


def test_a_block_without_joints_is_named(tmp_path, capsys):
    path = write(tmp_path, lifted_beam())
    unheld_error(capsys, path, "block 'beam' touches no other block", "nothing holds it",
                 commands=("check", "friction"))  # (no live load for `load`)


def test_blocks_that_rest_on_a_floating_block_are_named_and_no_live_load_is_blamed(
        tmp_path, capsys):
    """A stack drawn 1 mm above the ground, with a horizontal live load: no block was
    named (each touches another), and the first why line blamed the live load
    ("--load-factor 0 asks for the self-weight alone"), which changes nothing here; a
    block drawn apart from the rest is named as touching nothing. Both are refused."""
    path = write(tmp_path, make_scene([
        {"id": "ground", "vertices": rect(-1, -0.5, 4, 0.5), "support": True},
        {"id": "b1", "vertices": rect(0, 0.001, 1, 1)},
        {"id": "b2", "vertices": rect(0, 1.001, 1, 1)},
        {"id": "b3", "vertices": rect(0, 2.001, 1, 1)},
    ], unit_weight=20.0, friction=0.6, live_body_force=[0.1, 0]))
    unheld_error(capsys, path, "blocks 'b1', 'b2', 'b3' are joined to no support")
    path = write(tmp_path, make_scene([
        {"id": "ground", "vertices": rect(-1, -0.5, 4, 0.5), "support": True},
        {"id": "b1", "vertices": rect(0, 0, 1, 1)},
        {"id": "b2", "vertices": rect(2, 0.001, 1, 1)},
    ], unit_weight=20.0, friction=0.6, live_body_force=[0.1, 0]))
    unheld_error(capsys, path, "block 'b2' touches no other block")


def test_a_block_on_a_corner_is_said_to_touch_at_a_point(tmp_path, capsys):
    """A square standing on one corner (the catalogue's on_a_point) touches its support
    at a point, which is no joint: it read "touches no other block ... raise the contact
    tolerance", as if it were drawn apart; a block drawn apart still reads so."""
    from rigidblocks.generators.catalogue import on_a_point

    path = write(tmp_path, on_a_point())
    unheld_error(capsys, path, "block 'B' touches block 'S' at a point only (a corner)")
    code, _, err = run(capsys, ["check", path])
    assert code == 2 and "touches no other block" not in err


BOX_FACES = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6],
             [3, 0, 4, 7]]


def box3d(x0, x1, y0, y1, z0, z1):
    return [[x0, y0, z0], [x1, y0, z0], [x1, y1, z0], [x0, y1, z0],
            [x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]]


@pytest.mark.parametrize("where, box", [
    ("along an edge", box3d(2, 3, 0, 1, 0, 1)), ("at a point", box3d(2, 3, 2, 3, 0, 1)),
    ("apart", box3d(0, 1, 0, 1, 0.5, 1.5))])
def test_a_3d_block_on_an_edge_or_a_corner_is_said_to_touch(tmp_path, capsys, where, box):
    """In 3D a joint is a face in common: a box whose base meets its support's top along
    one edge only, or at one corner, read "touches no other block ... raise the contact
    tolerance", as if it were drawn apart; one drawn 0.5 m apart still reads so."""
    scene = {"format": "rigidblocks-scene", "version": 1, "dimension": 3,
             "unit_weight": 20, "friction": 0.6,
             "blocks": [{"id": "S", "vertices": box3d(0, 2, 0, 2, -1, 0),
                         "faces": BOX_FACES, "support": True},
                        {"id": "B", "vertices": box, "faces": BOX_FACES}]}
    path = tmp_path / "s.json"
    path.write_text(json.dumps(scene))
    code, out, err = run(capsys, ["check", str(path)])
    assert code == 2 and out == "" and err.count("\n") == 1, (out, err)
    touch = f"block 'B' touches block 'S' {where} only, and a joint is a face in common"
    assert (touch in err) == (where != "apart"), err
    assert ("touches no other block" in err) == (where == "apart"), err


def test_a_load_applied_off_its_block_is_named(tmp_path, capsys):
    """A horizontal load given at y = 12 on a 2 m block (a slip of the keyboard for
    y = 1.2) is applied there, and its lever of 12 m sets lambda* = (W + P) (b / 2) /
    (H y) = 3 x 0.5 / 12 (about the toe); the answer says that the point lies 10 m off
    the block. A point on the block's face is not named; in 3D, a point off its block,
    and one in the notch of an L-shaped block, inside its bounding box (it was not
    named: the 3D test was the bounding box's)."""
    blocks = [{"id": "G", "vertices": rect(-1, -1, 4, 1), "support": True},
              {"id": "B", "vertices": rect(0, 0, 1, 2)}]
    loads = [{"block": "B", "force": [1, 0], "point": [0.5, 12], "live": True},
             {"block": "B", "force": [0, -1], "point": [0.5, 2]}]
    path = write(tmp_path, make_scene(blocks, loads=loads, unit_weight=1.0,
                                      units={"length": "m", "force": "kN"}))
    code, out, _ = run(capsys, ["load", path])
    assert code == 0 and "lambda* = 0.125," in out, out
    assert "load #0 on block 'B' lies 10 m from it" in out and "load #1" not in out
    loads[0]["point"] = [0.5, 1.2]
    path = write(tmp_path, make_scene(blocks, loads=loads, unit_weight=1.0))
    code, out, _ = run(capsys, ["load", path])
    assert code == 0 and "outside its block" not in out
    solid = extrude(make_scene(blocks, loads=[{"block": "B", "force": [1, 0],
                                               "point": [0.5, 3], "live": True}],
                               unit_weight=1.0), depth=1.0)
    notes = open_method(solid).notes
    assert any("load #0 on block 'B' lies 1 from it" in n for n in notes), notes
    ell = [[0, 0], [3, 0], [3, 1], [1, 1], [1, 3], [0, 3]]  # the notch is x, y in (1, 3)
    solid = extrude(make_scene([{"id": "G", "vertices": rect(-1, -1, 5, 1), "support": True},
                                {"id": "L", "vertices": ell}],
                               loads=[{"block": "L", "force": [1, 0], "point": [2, 2],
                                       "live": True},
                                      {"block": "L", "force": [1, 0], "point": [0.5, 2],
                                       "live": True}], unit_weight=1.0), depth=1.0)
    notes = open_method(solid).notes
    assert any("load #0 on block 'L' lies 1 from it" in n and "load #1" not in n
               for n in notes), notes


def test_the_friction_search_says_why_its_lower_end_does_not_carry(capsys):
    """`friction --flow non-associative --load-factor 0.3` on the flat arch with vertical
    joints: below f* the state reached from X0 under the dead load alone breaches the
    joint laws (no multiplier at all); the note printed "at f = 0.8088357322615443 nan"."""
    code, out, _ = run(capsys, ["friction", str(EXAMPLES / "flat_arch_vertical.json"),
                                "--flow", "non-associative", "--load-factor", "0.3"])
    assert code == 0 and "STANDS" in out
    assert "nan" not in out
    assert "under the dead load alone breaches the joint laws" in out, out
    # the frictions of the trials as the other lines give numbers (it read "at f =
    # 0.8109374999999999 ...; at f = 0.8097656249999998 ...")
    assert not re.search(r"at f = \d\.\d{11,}", out), out


def test_load_factor_0_is_the_dead_load_where_there_are_dead_point_loads(capsys):
    """The reference model at load factor 0 keeps its dead point load P = 100 N (and
    has no self-weight): it read "under its self-weight only (no self-weight, 1 point
    load of 100 N ...)". The wall example has self-weight alone."""
    code, out, _ = run(capsys, ["check", str(EXAMPLES / "reference.json"),
                                "--load-factor", "0"])
    assert code == 0 and "under its dead load only (no self-weight, 1 point load" in out
    assert "self-weight only" not in out
    code, out, _ = run(capsys, ["check", str(EXAMPLES / "wall.json"), "--load-factor", "0"])
    assert code == 0 and "under its self-weight only (self-weight " in out


def test_starts_that_agree_to_the_cones_accuracy_give_the_same_answer(capsys):
    """examples/box_stack_3d.json, `load --flow non-associative`: the two starts end at
    0.3079191 and 0.3079195 (1.3e-6 apart), inside the 1e-5 to which the cone
    iteration's multipliers hold; the starts line said "the answers differ"."""
    code, out, _ = run(capsys, ["load", str(EXAMPLES / "box_stack_3d.json"), "--flow",
                                "non-associative"])
    assert code == 0
    line = next(ln for ln in out.splitlines() if ln.startswith("starts"))
    assert line.endswith("; the same answer") and "differ" not in line, line


def test_an_unstable_answer_points_to_other_states_only_where_they_exist(capsys):
    """`load --flow non-associative`: the flat arch with vertical joints at f = 0.7 has
    associative states (lambda* = 0.379962) while the state reached from X0 breaches
    the joint laws under the dead load: the verdict points to `check` without --flow.
    The inclined corbel arch has no state at all under its dead load (static problem):
    it pointed there too ("other states may stand"), beside the note that none does."""
    code, out, _ = run(capsys, ["load", str(EXAMPLES / "flat_arch_vertical.json"),
                                "--flow", "non-associative", "--friction", "0.7"])
    assert code == 0 and "other states may stand" in out
    # the starts line names both starts (it left X0 out, naming only the other)
    line = next(ln for ln in out.splitlines() if ln.startswith("starts"))
    assert line.startswith("starts     from the elastic state X0: unstable (") and \
        "; from the associative collapse state: lambda = 0.379961" in line, line
    code, out, _ = run(capsys, ["load", str(EXAMPLES / "corbel_arch_inclined.json"),
                                "--flow", "non-associative"])
    assert code == 0
    assert "verdict    UNSTABLE: the dead load alone has no admissible state\n" in out, out
    assert "other states may stand" not in out


def test_the_simplex_solves_of_the_limit_iteration_are_counted_and_named(capsys):
    """`load --flow non-associative --verbose` on a 6 x 4 wall: the limit iteration's
    LPs are HiGHS's warm-started simplex; the solver line said "clarabel, 14 solve(s)"
    (the Clarabel solves alone), and a 70 x 70 wall's progress line named the last
    Clarabel problem for the 20 minutes its simplex solves took."""
    from rigidblocks.methods import Progress

    scene = build("wall", courses=6, blocks_per_course=4, friction=0.6)
    seen = []

    class Watch(Progress):
        def __setattr__(self, key, value):
            if key == "stage":
                seen.append(value)
            super().__setattr__(key, value)

    res = rb.max_load_multiplier(scene, flow="non-associative", state=False,
                                 progress=Watch())
    assert res.answered_by == ("clarabel", "highs"), res.answered_by
    assert "maximum load (capped laws) problem (highs)" in seen
    assoc = rb.max_load_multiplier(scene, state=False)
    assert assoc.answered_by == ("clarabel",)
    code, out, _ = run(capsys, ["load", str(EXAMPLES / "wall.json"), "--flow",
                                "non-associative", "--verbose"])
    assert code == 0 and "solver     clarabel and highs, " in out


def test_the_question_says_how_many_joints_slide_without_dilatancy(tmp_path, capsys):
    """The reference model with self-weight where one joint alone (left-support) has
    flow non-associative: the question said "sliding without dilatancy" as of every
    joint."""
    doc = json.loads((EXAMPLES / "reference_self_weight.json").read_text())
    doc["joints"] = [{"blocks": ["left", "support"], "flow": "non-associative"}]
    path = tmp_path / "one.json"
    path.write_text(json.dumps(doc))
    code, out, _ = run(capsys, ["load", str(path)])
    assert code == 0 and ", 1 of 5 joints sliding without dilatancy" in out, out
    code, out, _ = run(capsys, ["load", str(path), "--flow", "non-associative"])
    assert code == 0 and ", sliding without dilatancy" in out and " of 5 joints" not in out


def test_the_friction_demand_is_not_read_off_a_joint_the_table_shows_open(capsys):
    """The wall example at load factor 0 (self-weight alone): the check said "|T|/N
    reaches 0.04731 (joint c0b0-c0b1)", a head joint its own table shows open with N = T
    = 0 (forces of 1e-6 of the largest, round-off); under self-weight alone the bed
    joints carry no shear and the demand is round-off too."""
    code, out, _ = run(capsys, ["check", str(EXAMPLES / "wall.json"), "--load-factor",
                                "0", "--joints", "--json"])
    doc = json.loads(out)
    fd = doc["friction_demand"]
    assert fd < 1e-3, fd
    row = next(r for r in doc["joints"] if r["joint"] == doc["friction_demand_joint"])
    assert row["state"] != "open", row


def test_a_multiplier_that_is_round_off_of_zero_reads_zero(capsys):
    """The reference model without friction: its central blocks slide under any live
    load, lambda* = 0 (the simplex gives 0); the interior-point answer 3.5e-11 was
    printed "lambda* = 3.51852e-11"."""
    code, out, _ = run(capsys, ["load", str(EXAMPLES / "reference.json"), "--friction",
                                "0"])
    assert code == 0 and "answer     lambda* = 0, " in out, out
    # and the JSON says the same number (it kept 3.5e-11 where the text said 0)
    code, out, _ = run(capsys, ["load", str(EXAMPLES / "reference.json"), "--friction",
                                "0", "--json"])
    assert code == 0 and json.loads(out)["load_multiplier"] == 0.0, out


def test_a_friction_that_no_joint_has_is_not_echoed_as_the_joints(tmp_path, capsys):
    """A block on a base whose one joint has its own friction 0.3: `load --friction 5`
    echoed "at friction f = 5 (78.69 deg)" beside lambda* = 0.3, the override's; the
    question now says the joints' own friction decides, and what it is (it named none)."""
    path = write(tmp_path, make_scene([
        {"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "B", "vertices": rect(0, 0, 1, 2)},
    ], unit_weight=20.0, friction=0.4, live_body_force=[1, 0],
        joints=[{"blocks": ["B", "base"], "friction": 0.3}]))
    code, out, _ = run(capsys, ["load", path, "--friction", "5"])
    asked = next(ln for ln in out.splitlines() if ln.startswith("asked"))
    assert asked.endswith("at each joint's own friction (every joint has an override: "
                          "base-B f = 0.3; f = 5 applies to none)"), asked
    assert "lambda* = 0.3," in out  # sliding at the override's f (a 1 x 2 block: tips at 0.5)


def test_the_distortion_methods_breach_is_not_called_the_smallest(capsys):
    """The arch at load factor 0.1498 (above lambda* = 0.1497649): the convex path's
    breach, 0.0004825 kN, is the least over all states; the distortion iteration's,
    0.0006584 kN, that of the state it stopped at, was also called the smallest."""
    path = str(EXAMPLES / "arch.json")
    _, out, _ = run(capsys, ["check", path, "--load-factor", "0.1498"])
    convex = next(ln for ln in out.splitlines() if ln.startswith("answer"))
    _, out, _ = run(capsys, ["check", path, "--load-factor", "0.1498", "--method",
                             "distortion"])
    iteration = next(ln for ln in out.splitlines() if ln.startswith("answer"))
    assert convex.startswith("answer     smallest breach of the joint laws 0.000482")
    assert iteration.startswith("answer     the distortion iteration's breach of the "
                                "joint laws"), iteration


def test_failing_check_names_the_breached_joints(capsys):
    """examples/arch.json at load factor 1 (a 1 g horizontal body force on a ring of
    t/R = 0.15): no thrust line fits, and the report names the joints breached in the
    least-violation state, with the amounts."""
    code, d, _ = run_json(capsys, ["check", str(EXAMPLES / "arch.json"), "--load-factor", "1",
                                   "--json"])
    assert code == 0 and d["status"] == "inadmissible" and d["admissible"] is False
    assert d["breaches"] and all(b["breach"] > 0 for b in d["breaches"])
    assert d["breaches"][0]["breach"] == pytest.approx(d["violation"], rel=1e-6)
    code, out, _ = run(capsys, ["check", str(EXAMPLES / "arch.json"), "--load-factor", "1"])
    assert "breached" in out


def test_check_reports_the_friction_demand_of_its_state(capsys):
    code, d, _ = run_json(capsys, ["check", str(EXAMPLES / "reference.json"), "--friction",
                                   "0.6", "--json"])
    assert code == 0 and d["admissible"] is True
    assert d["friction_demand"] == pytest.approx(0.5, rel=1e-6)
    assert d["notes"] == [] and d["bracket"] is None


def test_the_json_friction_demand_of_an_admitted_state_is_not_above_f(tmp_path, capsys):
    """The 8 x 8 running-bond wall at f = 0.6 and load factor 0.3 without dilatancy is
    admitted (its text: "|T|/N reaches the friction limit f = 0.6"), and its JSON gave
    friction_demand 0.6000396, above the f it was admitted at: a joint carrying little
    of the largest force (0.0092 kN) over f by the verdict's tolerance. It reads f."""
    path = str(tmp_path / "w88.json")
    rb.write_scene(build("wall", courses=8, blocks_per_course=8, friction=0.6), path)
    code, d, _ = run_json(capsys, ["check", path, "--flow", "non-associative",
                                   "--load-factor", "0.3", "--json"])
    assert code == 0 and d["admissible"] is True
    assert d["friction_demand"] == pytest.approx(0.6, rel=1e-6)
    assert d["friction_demand"] <= 0.6, d["friction_demand"]
    res = rb.check(rb.read_scene(path), load_factor=0.3, flow="non-associative")
    from rigidblocks.results import max_demand
    assert max_demand(res.state)[0] > 0.6  # the round-off itself is still there
    # the text names the joint the JSON names
    code, out, _ = run(capsys, ["check", path, "--flow", "non-associative",
                                "--load-factor", "0.3"])
    a, b = d["friction_demand_joint"]
    assert f"reaches the friction limit f = 0.6 (joint {a}-{b})" in out, out


def test_joint_table_on_request(tmp_path, capsys):
    path = str(EXAMPLES / "reference.json")
    code, d, _ = run_json(capsys, ["check", path, "--friction", "0.6", "--joints", "--json"])
    rows = {tuple(r["joint"]): r for r in d["joints"]}
    assert len(rows) == 5
    # each bed joint of the central blocks: N = 50, |T| = 25 (module docstring)
    bed = rows[("support", "left")]
    assert bed["N"] == pytest.approx(50, rel=1e-6) and abs(bed["T"]) == pytest.approx(25)
    assert bed["demand"] == pytest.approx(0.5, rel=1e-6)
    csv_path = tmp_path / "joints.csv"
    assert main(["friction", path, "--joints", str(csv_path)]) == 0
    with open(csv_path) as fh:
        table = list(csv.DictReader(fh))
    assert len(table) == 5 and {"N", "T", "eccentricity", "demand", "state"} <= set(table[0])
    # with its units (the reference model's: N and m)
    assert {(r["force_unit"], r["length_unit"]) for r in table} == {("N", "m")}
    # at f* = 0.5 the four bed joints are at their friction limit
    assert sum("at friction limit" in r["state"] for r in table) == 4
    assert main(["friction", path, "--joints", str(tmp_path / "no" / "x.csv")]) == 2


def test_an_open_joint_shows_no_force_and_no_demand(capsys):
    """The reference model with self-weight, `load --flow non-associative`: its vertical
    joint left-right is open in the collapse state. Its forces are round-off about 0,
    with no eccentricity and no |T|/N: the table shows N = T = 0 and "-" (it showed
    N = -6.17e-17, T = 1.93e-9, e = -0.03844 and |T|/N = inf)."""
    path = str(EXAMPLES / "reference_self_weight.json")
    assert main(["load", path, "--flow", "non-associative", "--joints"]) == 0
    row = next(s for s in capsys.readouterr().out.splitlines()
               if s.startswith("left-right "))
    cells = row.split()
    assert cells[1:6] == ["0", "0", "-", "-", "open"], row


def test_tilt_angle_beside_lambda(capsys):
    """The wall example's live load is a horizontal body force of 1 g: lambda* = f = 0.6
    (base sliding) is a tilt of atan(0.6) = 30.96375653 deg, printed to 4 decimals on the
    safe side as lambda* is, 30.9637 (the arch's 8.5175910 was printed 8.5176)."""
    code, d, _ = run_json(capsys, ["load", str(EXAMPLES / "wall.json"), "--json"])
    assert d["load_multiplier"] == pytest.approx(0.6, rel=1e-6)
    assert d["tilt_angle_deg"] == pytest.approx(math.degrees(math.atan(0.6)), rel=1e-6)
    code, out, _ = run(capsys, ["load", str(EXAMPLES / "wall.json")])
    assert "tilt angle atan(lambda* a) = 30.9637 deg" in out
    code, out, _ = run(capsys, ["load", str(EXAMPLES / "arch.json")])
    assert "tilt angle atan(lambda* a) = 8.5175 deg" in out
    # point loads: no tilt
    code, d, _ = run_json(capsys, ["load", str(EXAMPLES / "reference.json"), "--json"])
    assert d["tilt_angle_deg"] is None


# -- mechanisms ----------------------------------------------------------------------------
def _sliding_pairs(d):
    return {tuple(sorted(p)) for p in d["mechanism"]["sliding"]}


@pytest.mark.parametrize("dim", [2, 3])
def test_base_sliding_is_drawn_as_base_sliding(dim):
    """A 3 x 3 running-bond wall, f = 0.6 < t/h: at lambda* = f every bed joint could
    slide at once with everything above it (the optimal face holds all of them); the
    vertex mechanism is one of them, the wall sliding on its foundation, and the
    interior-point blend lists many more joints."""
    wall = build("wall", courses=3, blocks_per_course=3)
    scene = wall if dim == 2 else extrude(wall)
    r = rb.max_load_multiplier(scene, state=False)
    assert r.load_multiplier == pytest.approx(0.6, rel=1e-6)
    d = r.to_dict()
    assert d["mechanism"]["kind"] in ("vertex", "extreme")
    assert _sliding_pairs(d) == {("c0b0", "foundation"), ("c0b1", "foundation"),
                                 ("c0b2", "foundation")}
    assert d["mechanism"]["hinges"] == [] and d["mechanism"]["open"] == []
    blend = rb.max_load_multiplier(scene, state=False, mechanism="blend").to_dict()
    assert blend["mechanism"]["kind"] == "blend"
    assert len(blend["mechanism"]["sliding"]) > 3


def test_arch_collapses_with_four_hinges(capsys):
    """A semicircular ring under a horizontal body force fails by a four-hinge
    mechanism (Heyman, The Stone Skeleton, 1995); the vertex lists exactly four, ranked
    by their relative rotation rate."""
    code, d, _ = run_json(capsys, ["load", str(EXAMPLES / "arch.json"), "--json"])
    m = d["mechanism"]
    assert m["kind"] == "vertex" and len(m["hinges"]) == 4
    assert m["sliding"] == [] and m["open"] == []
    rates = [j["rate"] for j in m["ranked"]]
    assert len(rates) == 4 and rates == sorted(rates, reverse=True)


# -- first run -------------------------------------------------------------------------------
def test_generated_structures_answer_for_their_own_weight(tmp_path, capsys):
    """Generators that attach a seismic body force write load_factor 0: check and
    friction answer for the structure's own weight, load for the body force."""
    code, out, _ = run(capsys, ["check", str(EXAMPLES / "arpino_gate.json")])
    assert code == 0 and "ADMISSIBLE" in out and "NOT" not in out and "load factor 0" in out
    code, d, _ = run_json(capsys, ["friction", str(EXAMPLES / "arpino_gate.json"), "--json"])
    assert d["status"] == "stable" and 0 < d["friction_factor"] < 0.6
    p = tmp_path / "a.json"
    assert main(["example", "arch", "-o", str(p)]) == 0
    capsys.readouterr()
    assert rb.read_scene(p).load_factor == 0
    code, d, _ = run_json(capsys, ["check", str(p), "--json"])
    assert d["admissible"] is True and d["load_factor"] == 0


def test_every_generator_builds_with_its_defaults():
    from rigidblocks.generators import available

    for name in available():
        build(name)
    assert len(build("arch", shape="pointed").blocks) == 16 + 2  # even default


def test_thickness_says_what_it_minimised_and_what_to_change(capsys):
    code, out, _ = run(capsys, ["thickness", "arch", "--voussoirs", "10", "--rtol", "1e-2"])
    assert code == 0 and "t/R" in out
    code, _, err = run(capsys, ["thickness", "arch", "--shape", "pointed", "--voussoirs",
                                "10", "--hi", "1"])
    assert code == 2 and "--hi" in err and "Traceback" not in err
    # without --hi the default bound is one the family builds (tests/test_thickness.py)
    code, out, _ = run(capsys, ["thickness", "arch", "--shape", "pointed", "--voussoirs",
                                "10", "--rtol", "1e-2"])
    assert code == 0 and "note       the upper bound is thickness = 0.5" in out, out


def test_printed_multiplier_and_friction_are_on_the_safe_side(tmp_path, capsys):
    """A number printed to 6 figures is rounded to the nearest unless that lands beyond
    the answer by more than its accuracy: lambda* then rounds down, f* up, so that the
    printed number is one the answer holds at. The 1-ring barrel vault of 5 voussoirs:
    lambda* = 0.1769735169 (the JSON) was printed 0.176974, and `check` at that load
    factor did not stand; now 0.176973, where it stands."""
    from rigidblocks.answer import fmt_safe
    from rigidblocks.io import write_scene

    assert fmt_safe(0.17697351692998153, 6, False) == "0.176973"
    assert fmt_safe(0.17697351692998153, 6, True) == "0.176974"
    assert fmt_safe(0.2500012, 6, True) == "0.250002"
    assert fmt_safe(0.2500012, 6, False) == "0.250001"
    # round-off within the accuracy is not pushed to the next digit
    assert fmt_safe(0.4999999997, 6, False) == "0.5"
    assert fmt_safe(0.5000000003, 6, True) == "0.5"
    # the arch's f* (the upper end of its bracket [0.3462514085, 0.3465980065] at the
    # default accuracy 1e-3) is printed up: the nearest, 0.346598, breached by 7.8e-8 kN
    assert fmt_safe(0.3465980065, 6, True) == "0.346599"
    scene = build("barrel_vault", rings=1, voussoirs=5, friction=0.6)
    f = tmp_path / "vault.json"
    write_scene(scene, f)
    assert main(["load", str(f), "--json"]) == 0
    lam = json.loads(capsys.readouterr().out)["load_multiplier"]
    assert main(["load", str(f)]) == 0
    printed = next(ln for ln in capsys.readouterr().out.splitlines()
                   if ln.startswith("answer")).split("= ")[1].split(",")[0]
    assert printed == "0.176973" and float(printed) <= lam
    assert main(["check", str(f), "--load-factor", printed]) == 0
    assert "ADMISSIBLE: it stands" in capsys.readouterr().out


def test_the_starts_line_prints_multipliers_a_check_stands_at(tmp_path, capsys):
    """The 6 x 5 running-bond wall at f = 0.6 without dilatancy: both starts reach
    lambda = 11/19 = 0.57894737 (sliding of its upper courses), printed 0.5789474 to the
    nearest, at which `check` does not stand; the starts line now rounds it down as the
    answer line does (0.5789473), and `check` at that load factor stands."""
    from rigidblocks.io import write_scene

    f = tmp_path / "wall.json"
    write_scene(build("wall", courses=6, blocks_per_course=5, friction=0.6), f)
    assert main(["load", str(f), "--flow", "non-associative", "--json"]) == 0
    lam = json.loads(capsys.readouterr().out)["load_multiplier"]
    assert lam == pytest.approx(11 / 19, rel=1e-9)
    assert main(["load", str(f), "--flow", "non-associative"]) == 0
    starts = next(ln for ln in capsys.readouterr().out.splitlines()
                  if ln.startswith("starts"))
    assert "from the elastic state X0: lambda = 0.5789473 (" in starts, starts
    for lf, verdict in (("0.5789473", "ADMISSIBLE"), ("0.5789474", "NOT ADMISSIBLE")):
        assert main(["check", str(f), "--flow", "non-associative", "--load-factor",
                     lf]) == 0
        out = capsys.readouterr().out
        assert f"verdict    {verdict}" in out
    # the asked load factor as given, beside the multiplier that falls short of it
    assert "collapses at lambda = 0.5789473 < 0.5789474 (the limit" in out


def test_a_check_at_the_printed_non_associative_friction_stands(tmp_path, capsys):
    """The default barrel vault (3D, 1 ring of 9 voussoirs) for its dead load alone:
    `friction --flow non-associative` gives f* = 0.3382856382 (printed 0.338286). `check`
    at 0.338286 said NOT ADMISSIBLE, its limit run from X0 having reached lambda =
    -5.2e-14, round-off of 0, which did not carry the load factor 0; a multiplier now
    carries a load factor below 1 to its accuracy in units of the live load. f* is
    printed to the figures its bracket resolves (0.338285638; rounded up, as every
    least friction)."""
    from rigidblocks.io import write_scene

    f = tmp_path / "vault.json"
    write_scene(build("barrel_vault"), f)
    assert main(["friction", str(f), "--flow", "non-associative"]) == 0
    printed = next(ln for ln in capsys.readouterr().out.splitlines()
                   if ln.startswith("answer")).split()[3]
    assert printed == "0.338285638"
    assert main(["check", str(f), "--flow", "non-associative", "--friction", printed]) == 0
    out = capsys.readouterr().out
    assert "verdict    ADMISSIBLE" in out and "carries lambda = " in out
    # and at the 6 figures printed before, by the multiplier's accuracy
    assert main(["check", str(f), "--flow", "non-associative", "--friction", "0.338286"]) == 0
    out = capsys.readouterr().out
    assert "verdict    ADMISSIBLE" in out
    assert "carries lambda = " in out and "= 0 to the accuracy of its multiplier" in out


def test_a_check_whose_limit_run_is_undecided_says_so_in_its_flow_line(capsys,
                                                                         monkeypatch):
    """The inclined corbel arch without dilatancy at f = 0.8: the state reached from X0
    at the dead load converges, the limit run from it does not (the capped laws carry
    nothing at one step), and without the capacity bound (not computed here: the bound
    decides it) the check is undecided. The flow line said "converged" beside NO
    VERDICT; it names the run's outcome. At f = 0.9 both settle and it stands."""
    from rigidblocks.analyses import na_capacity

    monkeypatch.setattr(na_capacity, "MAX_JOINTS", 0)
    path = str(EXAMPLES / "corbel_arch_inclined.json")
    na = ["--flow", "non-associative", "--load-factor", "0"]
    assert main(["check", path, "--friction", "0.8", *na]) == 3
    flow = next(x for x in capsys.readouterr().out.splitlines() if x.startswith("flow"))
    assert ", converged; then " in flow and flow.endswith("loading from X0, undecided")
    assert main(["check", path, "--friction", "0.9", *na]) == 0
    flow = next(x for x in capsys.readouterr().out.splitlines() if x.startswith("flow"))
    assert flow.endswith("loading from X0")


def test_a_non_associative_fixed_point_below_0_is_unstable_from_x0(capsys):
    """The inclined corbel arch (examples/corbel_arch_inclined.json) under its dead load
    without dilatancy: `friction --load-factor 0` gives f* = 0.7651297008 (in a bracket
    8.6e-8 wide; the static f* is 0.76536 to 2e-3, 0.7651 to 1e-5). Just above it, at
    f = 0.7652, the limit fixed point from X0 lies at lambda = -2.7e-5, which `load`
    printed as "COLLAPSE, lambda* = -2.70611e-05"; then the capacity bound, which met
    the associative multiplier 4.314e-5, made it "COLLAPSE at 4.314e-5". That bound
    covers the live load's mechanisms only: the mirror image of the fixed point (the
    arch is symmetric) collapses at +2.7e-5 by a mechanism the live load resists
    (test_na_bounds.py). It is UNSTABLE from X0, with no lower bound. f* was printed
    0.76513, where `check` said NOT ADMISSIBLE (lambda = -1.2e-7); it is printed to the
    figures its bracket resolves, where `check` stands."""
    path = str(EXAMPLES / "corbel_arch_inclined.json")
    na = ["--flow", "non-associative"]
    assert main(["load", path, "--friction", "0.7652", *na]) == 0
    out = capsys.readouterr().out
    assert "verdict    UNSTABLE: loaded from X0 it collapses below the dead load alone" in out
    assert "it collapses at lambda = -2.706102e-05 < 0" in out
    assert "bounds     [-, 4.31401e-05]" in out
    assert main(["friction", path, "--load-factor", "0", *na]) == 0
    printed = next(ln for ln in capsys.readouterr().out.splitlines()
                   if ln.startswith("answer")).split()[3]
    assert printed == "0.7651297008"
    assert main(["check", path, "--load-factor", "0", "--friction", printed, *na]) == 0
    assert "verdict    ADMISSIBLE" in capsys.readouterr().out
    # a friction given is printed as given (the demand line read "f = 0.76513")
    assert main(["check", path, "--load-factor", "0", "--friction", printed]) == 0
    assert f"reaches the friction limit f = {printed} " in capsys.readouterr().out


def test_a_limit_step_whose_caps_carry_nothing_steps_back(capsys):
    """The inclined corbel arch at f = 1 and 1.5 without dilatancy: the limit iteration's
    second step, at the caps of the first step's state, had no equilibrium at all ("the
    capped laws carry not even the dead load") from both starts, and `load` was
    UNDECIDED. The caps that carry the dead load are a convex set that holds the first
    step's: the step goes halfway back towards them. Now decided, at or below the
    associative multiplier (Radenkovic's bound), and `check` at the printed lambda*
    stands, as the associative multiplier's does not."""
    path = str(EXAMPLES / "corbel_arch_inclined.json")
    for f in ("1", "1.5"):
        assert main(["load", path, "--friction", f, "--flow", "non-associative",
                     "--json"]) == 0
        d = json.loads(capsys.readouterr().out)
        assert d["status"] == "collapse", d["notes"]
        lam, hi = d["load_multiplier"], d["load_multiplier_bounds"][1]
        assert 0 < lam < hi
        assert main(["load", path, "--friction", f, "--flow", "non-associative"]) == 0
        shown = re.search(r"lambda\* = ([0-9.e+-]+)", capsys.readouterr().out).group(1)
        for lf, stands in ((shown, True), (f"{hi:.10g}", False)):
            main(["check", path, "--friction", f, "--flow", "non-associative",
                  "--load-factor", lf])
            out = capsys.readouterr().out
            assert ("verdict    ADMISSIBLE" in out) is stands, (f, lf, out)


def test_non_associative_friction_keeps_the_accuracy_asked(capsys):
    """The arch at load factor 0.1 without dilatancy: its f* is the static one. Asked to
    1e-9 by HiGHS it printed 0.4450388805 with "accuracy 5.0e-08 ... requested 1e-09" (the
    static f* searched to 1e-7 whatever was asked), while `friction` without --flow gives
    0.4450388585 to 6.2e-10; by Clarabel, which `friction` refuses at 1e-9 (an
    interior-point solver certifies about 1e-7), it gave a number. Now the same f* to the
    accuracy asked, and the same refusal."""
    path = str(EXAMPLES / "arch.json")
    ask = ["--load-factor", "0.1", "--rtol", "1e-9", "--json"]
    assert main(["friction", path, "--solver", "highs", *ask]) == 0
    static = json.loads(capsys.readouterr().out)
    assert main(["friction", path, "--solver", "highs", "--flow", "non-associative",
                 *ask]) == 0
    na = json.loads(capsys.readouterr().out)
    assert na["accuracy"] <= 1e-9 and na["friction_factor"] == static["friction_factor"]
    for flow in ([], ["--flow", "non-associative"]):
        assert main(["friction", path, *ask, *flow]) == 2
        assert "finer than an interior-point solver certifies f*" in capsys.readouterr().err


def test_no_finite_friction_is_not_said_of_infinite_friction(tmp_path, capsys):
    """An 8 x 6 running-bond wall with an opening (courses 2-4, blocks 2-3) under its
    dead load: the state reached from X0 has joints that must carry shear with no
    normal force, so no friction up to the search's ceiling (10) makes it stand
    without dilatancy (the breach, 0.2667, does not depend on f), while with infinite
    friction (no sliding at all) it stands. The verdict said "even infinite friction
    admits no equilibrium state"; it now names the ceiling."""
    from rigidblocks.io import write_scene

    f = tmp_path / "wall.json"
    write_scene(build("wall", courses=8, blocks_per_course=6, openings=[(2, 3, 2, 2)]), f)
    assert main(["friction", str(f), "--flow", "non-associative", "--load-factor", "0",
                 "-v"]) == 0
    out = capsys.readouterr().out
    assert ("verdict    UNSTABLE: no friction tried up to 10 suffices without dilatancy (in "
            "the state reached from the elastic state X0)") in out
    assert "infinite" not in out and "at any finite friction" in out
    assert main(["check", str(f), "--flow", "non-associative", "--friction", "infinite",
                 "--load-factor", "0"]) == 0
    assert "verdict    ADMISSIBLE" in capsys.readouterr().out


def test_numbers_given_are_echoed_as_given_and_the_path_rounds_safe(capsys):
    """The arch (examples/arch.json): `check --friction 0.346598` echoed "friction f =
    0.3466", the line of `check --friction 0.3466`, which stands where 0.346598 does not
    (f* = 0.3465980065); `path` printed its collapse load 0.1497649 as 0.149765, above
    lambda* (check at it does not stand), now 0.149764895 (to nine figures, cut down),
    the number it multiplies too (it multiplied 0.149764)."""
    path = str(EXAMPLES / "arch.json")
    code, out, _ = run(capsys, ["check", path, "--friction", "0.346598"])
    assert "at friction f = 0.346598 (" in out and "verdict    NOT ADMISSIBLE" in out
    code, out, _ = run(capsys, ["path", path])
    status = next(ln for ln in out.splitlines() if ln.startswith("status"))
    assert status.startswith("status     COLLAPSE at lambda = 0.149764895: ") and \
        ": 0.149764895 x 37.6948 kN = 5.6453" in status, status
    code, out, _ = run(capsys, ["check", path, "--load-factor", "0.149764895"])
    assert "verdict    ADMISSIBLE" in out


def test_a_check_beyond_every_state_says_so_under_either_flow(capsys):
    """The arch (examples/arch.json, lambda* = 0.1497649 by the convex path) at load
    factor 0.2: no state stands at all, so the non-associative check's verdict is the
    static one, not "the state reached from X0 does not stand (...; another state may
    stand)" beside "no admissible state exists at all"; its hint for the collapse
    multiplier keeps the flow."""
    from rigidblocks.answer import NA_INADMISSIBLE

    path = str(EXAMPLES / "arch.json")
    assert main(["check", path, "--flow", "non-associative", "--load-factor", "0.2"]) == 0
    out = capsys.readouterr().out
    assert ("verdict    NOT ADMISSIBLE: no equilibrium state keeps every joint in "
            "compression and within friction") in out and NA_INADMISSIBLE not in out
    assert f"`rigidblocks load {path} --flow non-associative` for the collapse" in out


def test_joint_table_round_off_of_an_interior_point_state_is_no_force():
    """A 2 x 2 wall3d in plane, non-associative check at load factor 0.5 (admissible):
    Clarabel leaves its open head joints at N = 1.1e-8 kN and -1.4e-9 kN, T = 2.9e-8 kN,
    which the table printed as forces with |T|/N = 2.7 "friction limit" at f = 0.6.
    Forces below ZERO_FORCE (1e-4) of the largest are none (the report's rule): no
    negative normal force, no demand above f in a state that stands, and the 3D
    eccentricities (distance of the centre of pressure from the contact's centroid)
    given, as the report gives them."""
    scene = build("wall3d", courses=2, blocks_per_course=2, friction=0.6,
                  load_direction="in_plane")
    res = rb.check(scene, load_factor=0.5, flow="non-associative")
    assert res.status == "admissible"
    rows = res.joint_table()
    big = max(r["N"] for r in rows)
    assert all(r["N"] >= 0 for r in rows)
    # within friction to the verdict's tolerance (a small force's |T|/N may pass f by
    # more: c1b1-c1b2 at N = 5e-3 of the largest has 0.6000287)
    assert all(abs(r["T"]) <= 0.6 * r["N"] + 1e-6 * big for r in rows)
    assert any(r["state"] == "open" for r in rows)
    assert all(r["eccentricity"] is not None for r in rows if r["state"] != "open")


def test_the_joint_table_shows_each_joints_own_law(tmp_path, capsys):
    """Two blocks stacked on a base, the lower joint with its own friction 0.3, the upper
    bonded (cohesion 5 kN/m^2): the table showed N, T and |T|/N against thresholds it
    did not show. Each joint's f, c and ft are now in the JSON and CSV rows, and in the
    text table where the joints differ; at f* the override keeps its own f."""
    path = write(tmp_path, make_scene([
        {"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "A", "vertices": rect(0, 0, 1, 1)},
        {"id": "B", "vertices": rect(0, 1, 1, 1)},
    ], unit_weight=20.0, friction=0.6, live_body_force=[0.1, 0],
        joints=[{"blocks": ["A", "base"], "friction": 0.3},
                {"blocks": ["A", "B"], "cohesion": 5.0}]))
    code, out, _ = run(capsys, ["check", path, "--joints"])
    lines = out.splitlines()
    head = next(ln for ln in lines if ln.startswith("joint "))
    assert " f " in f" {head} " and "c [force/length^2]" in head and "ft" not in head, head
    row = {ln.split()[0]: ln.split() for ln in lines if ln.startswith(("A-", "B-", "base-"))}
    lower = next(v for k, v in row.items() if "base" in k)
    upper = next(v for k, v in row.items() if "base" not in k)
    assert lower[5:7] == ["0.3", "0"] and upper[5:7] == ["0.6", "5"], (lower, upper)
    # at f* the joints without an override have f*, the override keeps its own
    _, doc, _ = run_json(capsys, ["friction", path, "--joints", "--json"])
    fstar = doc["friction_factor"]
    got = {tuple(sorted(r["joint"])): (r["friction"], r["cohesion"]) for r in doc["joints"]}
    assert got[("A", "base")] == (0.3, 0.0) and got[("A", "B")] == (fstar, 5.0), got
    # infinite friction reads "infinite" in JSON, and every column is in the CSV
    _, doc, _ = run_json(capsys, ["check", path, "--friction", "infinite", "--joints",
                                  "--json"])
    assert {r["friction"] for r in doc["joints"]} == {"infinite", 0.3}
    # ... and in the terminal's table and the CSV (they wrote "inf")
    code, out, _ = run(capsys, ["check", path, "--friction", "infinite", "--joints"])
    assert sorted(ln.split()[5] for ln in out.splitlines()
                  if ln.startswith(("A-", "B-", "base-"))) == ["0.3", "infinite"]
    csv_path = tmp_path / "j.csv"
    assert main(["check", path, "--friction", "infinite", "--joints", str(csv_path)]) == 0
    with open(csv_path) as fh:
        rows = list(csv.DictReader(fh))
    assert {r["cohesion"] for r in rows} == {"0.0", "5.0"} and \
        {r["tensile_strength"] for r in rows} == {"0.0"} and \
        {r["friction"] for r in rows} == {"0.3", "infinite"}


def test_a_joint_without_friction_or_cohesion_is_at_its_limit(capsys):
    """The reference model at f = 0: the loaded joints, which its mechanism slides,
    read "closed" (their threshold f N is 0, the share of it undefined); a joint with
    neither friction nor cohesion is at its limit whatever it carries."""
    code, out, _ = run(capsys, ["load", str(EXAMPLES / "reference.json"), "--friction",
                                "0", "--joints"])
    rows = {ln.split()[0]: ln for ln in out.splitlines()
            if ln.startswith(("support-", "left-", "right-"))}
    assert "open" in rows["left-right"]
    assert all("at friction limit" in rows[j] for j in ("support-left", "support-right",
                                                        "left-top", "right-top")), rows


def test_a_structure_that_slides_under_its_dead_load_is_told_friction_governs(capsys):
    """The inclined corbel arch (examples/corbel_arch_inclined.json) at its own f = 0.6:
    `load` said only "UNSTABLE: the dead load alone has no admissible state" and `check`
    "NOT ADMISSIBLE", as of a structure that cannot stand. Without sliding it stands: the
    note says so and names the command that gives the friction it needs, f* = 0.76536
    (to 2e-3; docs/seed-examples.md gives 0.7651 to 1e-5, the seed no value), at which
    `check` stands.
    The arch at load factor 0.2, above its hinging multiplier 0.1498, breaches the laws
    without sliding too: no such note."""
    path = str(EXAMPLES / "corbel_arch_inclined.json")
    note = ("without sliding (infinite friction) it stands {}: friction governs, not the "
            f"geometry; `rigidblocks friction {path} --load-factor 0` gives the least "
            "friction that carries it")
    code, out, _ = run(capsys, ["load", path])
    assert "verdict    UNSTABLE" in out and note.format("under its dead load alone") in out
    code, out, _ = run(capsys, ["check", path, "--load-factor", "0"])
    assert "NOT ADMISSIBLE" in out and note.format("under its dead load alone") in out
    # without dilatancy too (without sliding the flow rule is moot), the command with it;
    # infinite friction is another law there, not the limit of large ones (the 8 x 8 wall
    # at 0.7 stands at infinite friction, and no f up to 10 carries it): "friction
    # governs" pointed to a search that found none
    for cmd in (["load", path], ["check", path, "--load-factor", "0"]):
        code, out, _ = run(capsys, cmd + ["--flow", "non-associative"])
        assert ("without sliding (infinite friction) it stands under its dead load alone, a "
                "joint law no finite friction reaches without dilatancy (a joint without "
                f"compression carries shear there); `rigidblocks friction {path} "
                "--load-factor 0 --flow non-associative` searches the least finite "
                "friction that carries it (up to 10)") in out, out
        assert "friction governs" not in out
    code, out, _ = run(capsys, ["check", path, "--load-factor", "0.1"])
    assert "it stands at this load: friction governs" in out and "--load-factor 0.1`" in out
    code, out, _ = run(capsys, ["friction", path, "--load-factor", "0"])
    assert "answer     f* = 0.76536 " in out
    code, out, _ = run(capsys, ["check", path, "--load-factor", "0", "--friction",
                                "0.76536"])
    assert "verdict    ADMISSIBLE" in out
    code, out, _ = run(capsys, ["check", str(EXAMPLES / "arch.json"), "--load-factor",
                                "0.2"])
    assert "NOT ADMISSIBLE" in out and "friction governs" not in out


def _stack_with_own_laws(tmp_path, joints, name="s.json"):
    """Three 1 x 0.5 m blocks stacked on a base, 20 kN/m^3, a horizontal body force of
    0.3 g: each bed joint carries |T|/N = 0.3 (statics)."""
    return write(tmp_path, make_scene([
        {"id": "base", "vertices": rect(-1, -0.5, 4, 0.5), "support": True},
        {"id": "A", "vertices": rect(0, 0, 1, 0.5)},
        {"id": "B", "vertices": rect(0, 0.5, 1, 0.5)},
        {"id": "C", "vertices": rect(0, 1.0, 1, 0.5)},
    ], unit_weight=20.0, friction=0.6, live_body_force=[1, 0], load_factor=0.3,
        joints=joints), name)


def test_the_friction_demand_line_reads_the_joints_held_to_the_friction_asked(
        tmp_path, capsys):
    """A stack under 0.3 g whose bed joint on the base has its own f = 0.25 and
    cohesion 10 kN/m^2 (it carries |T| = 9 kN of its 0.25 x 30 + 10 = 17.5): `check
    --friction 0.2` stands, and said "|T|/N reaches the friction limit f = 0.2 (joint
    base-A)", a limit that joint does not have. The line reads the joints held to the f
    asked, and says so where others have laws of their own: A-B at 0.3 (statics)."""
    path = _stack_with_own_laws(tmp_path, [
        {"blocks": ["base", "A"], "friction": 0.25, "cohesion": 10.0},
        {"blocks": ["B", "C"], "cohesion": 2.0, "tensile_strength": 5.0}])
    code, out, _ = run(capsys, ["check", path, "--friction", "0.35"])
    assert "verdict    ADMISSIBLE" in out
    assert ("|T|/N reaches 0.3 among the joints without a law of their own (joint A-B)"
            in out), out
    everyone = _stack_with_own_laws(tmp_path, [
        {"blocks": ["base", "A"], "friction": 0.25, "cohesion": 10.0},
        {"blocks": ["A", "B"], "friction": "infinite"},
        {"blocks": ["B", "C"], "cohesion": 2.0, "tensile_strength": 5.0}], "all.json")
    code, out, _ = run(capsys, ["check", everyone, "--friction", "0.2"])
    assert "verdict    ADMISSIBLE" in out and "reaches" not in out, out


def test_no_friction_suffices_names_the_joints_that_keep_their_own(tmp_path, capsys):
    """The stack under 0.3 g with its bed joint on the base at its own f = 0.1: `friction`
    said "no friction suffices (even infinite friction admits no equilibrium state)", as
    of a structure that cannot stand; the other joints' friction cannot help while that
    joint keeps 0.1 (`load` gives lambda* = 0.1 = its f, the block sliding there).
    Without dilatancy it said "no friction up to 10 suffices without dilatancy (in the
    state reached from X0)": no state stands at any friction (the static problem), and
    the joint that keeps its own is the cause, as with associative flow."""
    path = _stack_with_own_laws(tmp_path, [{"blocks": ["base", "A"], "friction": 0.1}])
    for flow in ([], ["--flow", "non-associative"]):
        code, out, _ = run(capsys, ["friction", path, "--load-factor", "0.3", *flow])
        assert ("verdict    UNSTABLE: no friction of the other joints suffices (even "
                "infinite friction there admits no equilibrium state) while the joints with "
                "a friction of their own keep it: base-A (f = 0.1)") in out, out
    res = rb.min_friction(rb.read_scene(path), load_factor=0.3, flow="non-associative",
                          state=False)
    assert res.cause == "static_unstable"
    code, out, _ = run(capsys, ["load", path])
    assert "lambda* = 0.1," in out


def test_a_non_associative_multiplier_that_is_round_off_of_zero_reads_zero(capsys):
    """The reference model without friction under --flow non-associative: lambda* =
    3.51852e-11 (the associative multiplier, itself round-off of 0, upper bound [0,
    3.5e-11]) and the starts 3.3e-15 and 3.9e-15 "differ"; now 0, bounds [0, 0], the
    same answer."""
    argv = ["load", str(EXAMPLES / "reference.json"), "--friction", "0", "--flow",
            "non-associative"]
    code, out, _ = run(capsys, argv)
    assert "answer     lambda* = 0, " in out and "bounds     [0, 0]" in out, out
    assert "the same answer" in out and "differ" not in out
    _, doc, _ = run_json(capsys, argv + ["--json"])
    assert doc["load_multiplier"] == 0.0 and doc["load_multiplier_bounds"] == [0.0, 0.0]


def test_the_joint_table_prints_no_round_off_of_zero(capsys):
    """examples/fig4a_bonded.json: the bonded joint read T = -1.8544e-15 N beside N = -10
    N, and the bed joints e = -1.51e-16 m (floating point's round-off of 0); the box
    stack's |T|/N 9.7e-15 where T is round-off of 0. They read 0."""
    _, doc, _ = run_json(capsys, ["check", str(EXAMPLES / "fig4a_bonded.json"), "--joints",
                                  "--json"])
    rows = {tuple(r["joint"]): r for r in doc["joints"]}
    assert rows[("left", "right")]["T"] == 0.0 and rows[("left", "right")]["N"] < -9
    assert all(r["eccentricity"] == 0.0 for r in rows.values()), rows
    _, doc, _ = run_json(capsys, ["check", str(EXAMPLES / "box_stack_3d.json"), "--joints",
                                  "--json"])
    assert all(r["T"] == 0.0 and r["demand"] == 0.0 for r in doc["joints"]), doc["joints"]


def test_the_mode_column_comes_with_a_mechanism(capsys):
    """`check --joints` printed a mode column of dashes (a check has no mechanism); it
    comes with `load`'s collapse, whose hinges it names."""
    arch = str(EXAMPLES / "arch.json")
    _, out, _ = run(capsys, ["check", arch, "--joints"])
    head = next(ln for ln in out.splitlines() if ln.startswith("joint "))
    assert head.endswith("state"), head
    _, out, _ = run(capsys, ["load", arch, "--joints"])
    lines = out.splitlines()
    assert next(ln for ln in lines if ln.startswith("joint ")).endswith(" mode")
    assert sum(ln.endswith(" hinge") for ln in lines) == 4


def test_a_non_associative_friction_that_rests_on_numerically_zero_forces_is_none(
        tmp_path, capsys):
    """The 4 x 4 running-bond wall under 0.7 of its weight: `friction --flow
    non-associative` gave f* = 2939.57 (89.98 deg). Its answer is 0.636 (a corner wedge
    that rocks) at every f from 1 to 1e5 but about 3,000, where the caps f N of the head
    joints' elastic normal forces, 1e-5 of the largest (numerically zero), reach a third
    of the largest force: it now finds no friction up to 10 (f x 1e-4, the forces'
    resolution, is 1e-3 there), and an answer at f = 3000 says what it rests on."""
    from rigidblocks.io import write_scene

    f = tmp_path / "wall.json"
    write_scene(build("wall", courses=4, blocks_per_course=4), f)
    code, out, _ = run(capsys, ["friction", str(f), "--flow", "non-associative",
                                "--load-factor", "0.7"])
    assert "verdict    UNSTABLE: no friction tried up to 10 suffices without dilatancy" in out
    for fr in ("1", "10"):
        code, out, _ = run(capsys, ["load", str(f), "--flow", "non-associative",
                                    "--friction", fr])
        assert "lambda* = 0.636363," in out and "numerically zero" not in out
    code, out, _ = run(capsys, ["load", str(f), "--flow", "non-associative", "--friction",
                                "3000"])
    assert ("at f = 3000 the caps f N of normal forces that are numerically zero (up to "
            "0.0001 of the largest force) reach 0.3 of it: without dilatancy an answer "
            "above f = 10 rests on them") in out, out
    # infinite friction is Heyman's law, not the limit of large f: 2, not 0.636
    code, out, _ = run(capsys, ["load", str(f), "--flow", "non-associative", "--friction",
                                "infinite"])
    assert "lambda* = 2," in out and ("that law lets a joint without compression carry "
                                      "shear, which no finite friction does without "
                                      "dilatancy: a large finite f may give less (compare "
                                      "--friction 10)") in out, out


def test_the_breach_says_what_it_measures(tmp_path, capsys):
    """A 20 kN parallelogram block (base 0.5 m, leaning 45 degrees to 2 m) under its
    weight and the same again sideways: "smallest breach of the joint laws 70 kN" read
    as a misprint beside 20 kN. About its toe the loads turn 20 x 0.75 + 20 x 1 = 35 kNm,
    held only by tension at its heel 0.5 m away: 70 kN. The line says what it measures."""
    path = write(tmp_path, make_scene([
        {"id": "ground", "vertices": rect(-1, -0.5, 5, 0.5), "support": True},
        {"id": "lean", "vertices": [[0, 0], [0.5, 0], [2.5, 2], [2, 2]]},
    ], unit_weight=20.0, friction=0.6, live_body_force=[1, 0],
        units={"length": "m", "force": "kN"}))
    code, out, _ = run(capsys, ["check", path, "--friction", "infinite"])
    assert ("answer     smallest breach of the joint laws 70 kN (the most tension, or shear "
            "beyond friction, it asks of one contact; a joint's, summed over its contact "
            "points, is named with it; 0 would stand)") in out, out


def test_a_linear_program_clarabel_cannot_solve_is_answered_by_highs(capsys):
    """The inclined corbel arch at f = 0.7651, below its static f* = 0.7651297008 (the
    least friction any state needs; docs/seed-examples.md): no state is admissible at
    any multiplier, so `load` is UNSTABLE under either flow rule. Clarabel ended at
    MaxIterations on that maximum-load LP and `load` printed "solver failure" (exit 1);
    HiGHS's simplex answers the LP, with its infeasibility certificate checked, and the
    answer says that another back end solved it."""
    path = str(EXAMPLES / "corbel_arch_inclined.json")
    for flow in ([], ["--flow", "non-associative"]):
        assert main(["load", path, "--friction", "0.7651", *flow]) == 0
        assert "verdict    UNSTABLE" in capsys.readouterr().out
    res = rb.max_load_multiplier(rb.read_scene(path), friction=0.7651, state=False)
    assert res.status == "unstable"
    assert all("highs answered it" in r for r in res.rejected)
    assert any("were solved again by highs" in n for n in res.notes), res.notes


def test_starts_within_the_checks_resolution_of_zero_give_the_same_answer():
    """The inclined corbel arch at its static f* = 0.7651297008 (examples/
    corbel_arch_inclined.json; the associative multiplier there is 9.5e-12): the runs
    from X0 and from the associative collapse state end at 4.197021e-08 and
    1.186472e-10, both within the fixed points' own check (1e-7 of the live load) of
    the answer lambda* = 0; the starts line read "the answers differ: [1.186472e-10,
    4.197021e-08] (the answer is X0's)" beside it. Answers 1e-5 apart still differ, and
    so do the 20 x 15 wall's at f = 0.6 (4.4e-7 apart, 1e-6 relative)."""
    from rigidblocks.analyses.nonassociative import compare_starts

    def history(a: float, b: float) -> list[dict]:
        return [{"start": s, "load_factor": v, "status": "converged", "converged": True}
                for s, v in (("X0", a), ("the associative collapse state", b))]

    assert compare_starts(history(4.197021e-08, 1.186472e-10))[1] is None
    assert compare_starts(history(0.4110464, 0.41104642))[1] is None
    assert compare_starts(history(0.43742304, 0.43742348))[1] == (0.43742304, 0.43742348)
    assert compare_starts(history(1e-5, 2e-5))[1] == (1e-5, 2e-5)
    assert compare_starts(history(0.4110464, 0.4116458))[1] == (0.4110464, 0.4116458)


def test_the_collapse_at_the_brink_names_its_mechanism(capsys):
    """The inclined corbel arch at its static f* = 0.7651297008 without dilatancy: `load`
    says COLLAPSE at lambda* = 0 and gave no mechanism, with the note "with the normal
    forces of the computed state as fixed shear capacities the multiplier would be
    5.5e-07: no collapse mechanism is given": 5.5e-7 is 0 to the answers' absolute
    floor (1e-6 of the live load), and that problem's mechanism is the collapse's (three
    hinges and a slip, as the least state's at f = 0.8 in docs/safe-multiplier.md).
    Where the state is not a collapse state of its caps (f = 0.8, read off the states
    from X0: 0.0594714 against 0.0127922, at --rtol 4e-5, its bracket's accuracy: at the
    default 1e-5 it is undecided) the note says so, with both numbers."""
    path = str(EXAMPLES / "corbel_arch_inclined.json")
    code, out, _ = run(capsys, ["load", path, "--flow", "non-associative", "--friction",
                                "0.7651297008"])
    assert code == 0 and "answer     lambda* = 0," in out
    assert "governing  3 hinging (" in out and "; 1 sliding (" in out, out
    assert "multiplier would be" not in out and "no collapse mechanism" not in out
    code, out, _ = run(capsys, ["load", path, "--flow", "non-associative", "--friction",
                                "0.8", "--rtol", "4e-5"])
    assert ("no collapse mechanism is given: the computed state is not a collapse state "
            "of its own caps (with its normal forces as fixed shear capacities f N the "
            "multiplier is 0.0594714, not 0.0127922)") in out, out


def test_the_flow_line_of_a_dead_load_breach_says_no_run_converged(capsys):
    """examples/flat_arch_vertical.json at f = 0.6, `load --flow non-associative`: the
    state reached from X0 breaches the joint laws under the dead load (UNSTABLE, no
    limit step from X0) and the run from the associative collapse state ends
    infeasible; the flow line read "8 limit step(s) over 2 start(s) (0 + 8), converged"."""
    code, out, _ = run(capsys, ["load", str(EXAMPLES / "flat_arch_vertical.json"),
                                "--flow", "non-associative", "--friction", "0.6"])
    assert code == 0 and "verdict    UNSTABLE" in out
    flow = next(ln for ln in out.splitlines() if ln.startswith("flow"))
    # (the steps the line counts are its starts': 13 read beside "(0 + 8)" once the
    # breached joints were listed from the state's run again)
    assert flow.endswith(": 8 limit step(s) over 2 start(s) (0 + 8), decided under the "
                         "dead load, before any limit step from X0"), flow


def test_at_infinite_friction_the_bounds_meet_at_the_associative_multiplier(capsys):
    """examples/arch.json, `load --flow non-associative --friction infinite`: no joint
    slides, so every collapse state's mechanism only hinges and opens (normality of the
    no-tension law) and collapses at the associative multiplier 0.1497648 (the
    kinematic theorem). The bounds line read "[-, 0.149765] (lower, -: none with the
    joints without dilatancy frictionless)": the frictionless arch does not carry its
    dead load, which says nothing at infinite friction."""
    code, out, _ = run(capsys, ["load", str(EXAMPLES / "arch.json"), "--flow",
                                "non-associative", "--friction", "infinite", "--json"])
    assert code == 0
    d = json.loads(out)
    lo, hi = d["load_multiplier_bounds"]
    assert d["lower_bound_by"] == "no sliding" and lo == hi
    assert abs(d["load_multiplier"] - hi) <= 1e-9 * hi and abs(hi - 0.1497648) < 1e-6


def test_load_check_and_friction_read_a_fixed_point_at_the_associative_one_alike(
        tmp_path, capsys):
    """The reference model (examples/reference.json) with the joint left-top without
    dilatancy: `load` reads the limit fixed point from X0, 1.199999975, as the
    associative multiplier 1.2 (within the checks' 1e-6; the seed's closed form is
    lambda = 2 f = 1.2 at f = 0.6) and prints lambda* = 1.2; `check` at 1.2 said NOT
    ADMISSIBLE ("collapses at lambda = 1.199999 < 1.2") and `friction` at 1.2 gave
    f* = 0.60006 ("f = 0.6 is NOT enough")."""
    scene = json.loads((EXAMPLES / "reference.json").read_text())
    scene["joints"] = [{"blocks": ["left", "top"], "flow": "non-associative"}]
    path = tmp_path / "one_joint.json"
    path.write_text(json.dumps(scene))
    code, out, _ = run(capsys, ["load", str(path), "--json"])
    assert code == 0 and abs(json.loads(out)["load_multiplier"] - 1.2) < 1e-9
    code, out, _ = run(capsys, ["check", str(path), "--load-factor", "1.2"])
    assert code == 0 and out.split("verdict    ")[1].startswith("ADMISSIBLE"), out
    code, out, _ = run(capsys, ["friction", str(path), "--load-factor", "1.2", "--json"])
    d = json.loads(out)
    assert code == 0 and d["status"] == "stable" and d["friction_factor"] <= 0.6 + 1e-9, d


def test_an_unstable_path_without_dilatancy_does_not_say_no_state_stands(capsys):
    """examples/flat_arch_vertical.json, `path --flow non-associative` at its f = 0.6: the
    state the distortion method reaches from X0 breaches the joint laws under the dead
    load, while `check --load-factor 0` admits a state (associative lambda* = 0.2496);
    the path said "the dead load alone has no admissible state"."""
    path = str(EXAMPLES / "flat_arch_vertical.json")
    code, out, _ = run(capsys, ["path", path, "--flow", "non-associative"])
    assert code == 0 and "status     UNSTABLE" in out
    assert "no admissible state" not in out and "breaches the joint laws" in out, out
    code, out, _ = run(capsys, ["check", path, "--load-factor", "0"])
    assert out.split("verdict    ")[1].startswith("ADMISSIBLE"), out


def test_no_friction_up_to_the_ceiling_is_said_once_the_ceiling_was_tried(tmp_path,
                                                                          capsys):
    """A 6 x 6 running-bond wall at f = 0.7 under 0.6 of its weight, `friction --flow
    non-associative`: the limit fixed point from X0 carries 0.5789473 (11/19) at every
    friction tried; the search doubled from the static f* 0.65755 to 5.26 and answered
    "no friction up to 10 suffices" without trying 10. The ceiling is tried now, and
    the verdict says the frictions were tried (lambda need not grow with f between
    them)."""
    from rigidblocks.io import write_scene

    f = tmp_path / "wall.json"
    write_scene(build("wall", courses=6, blocks_per_course=6, friction=0.7), f)
    args = ["friction", str(f), "--flow", "non-associative", "--load-factor", "0.6"]
    code, out, _ = run(capsys, [*args, "--json"])
    d = json.loads(out)
    assert d["status"] == "unstable"
    tried = [h["friction"] for h in d["history"]]
    assert max(tried) == 10.0 and all(abs(h["load_factor"] - 11 / 19) < 1e-9
                                      for h in d["history"]), d["history"]
    code, out, _ = run(capsys, args)
    assert "verdict    UNSTABLE: no friction tried up to 10 suffices" in out


def test_a_check_whose_state_does_not_settle_reads_the_collapse_from_x0(tmp_path, capsys):
    """The 6 x 6 running-bond wall at f = 2 under 0.6 of its weight, `check --flow
    non-associative`: the state reached from X0 at 0.6 does not settle within 300
    solves, and the check said UNDECIDED, while `load` at f = 2 collapses from X0 at
    0.5789473 (11/19) < 0.6, as the check itself says at f = 5.6 and 10."""
    from rigidblocks.io import write_scene

    f = tmp_path / "wall.json"
    write_scene(build("wall", courses=6, blocks_per_course=6, friction=0.7), f)
    code, out, _ = run(capsys, ["load", str(f), "--flow", "non-associative", "--friction",
                                "2", "--json"])
    assert abs(json.loads(out)["load_multiplier"] - 11 / 19) < 1e-9
    code, out, _ = run(capsys, ["check", str(f), "--flow", "non-associative", "--friction",
                                "2", "--load-factor", "0.6", "--json"])
    d = json.loads(out)
    assert code == 0 and d["status"] == "inadmissible" and d["breaches"] == [], d["status"]
    assert any("collapses at lambda = 0.5789473 < 0.6" in n for n in d["notes"])


def test_a_friction_at_the_brink_says_a_margin_above_it_does_not_stand(capsys):
    """examples/corbel_arch_inclined.json under its dead load, `friction --flow
    non-associative`: f* = 0.7651297008 is the static f*, where one state alone is
    admissible; just above it, from 0.7652 to 0.76666, the state reached from X0
    collapses below the dead load (`load --friction 0.7652`: UNSTABLE), and it stands
    again from about 0.767 (`load --friction 0.767`: lambda* = 0.000718). The answer
    said only that a larger f need not carry more."""
    path = str(EXAMPLES / "corbel_arch_inclined.json")
    code, out, _ = run(capsys, ["friction", path, "--flow", "non-associative"])
    assert code == 0 and "answer     f* = 0.7651297008 " in out
    m = re.search(r"just above it, at f = ([0-9.]+), the state reached from X0 does not "
                  r"carry the load, and carries it again at f = ([0-9.]+) ", out)
    assert m, out
    low, high = float(m.group(1)), float(m.group(2))
    assert 0.7652 < low < high < 0.770
    code, out, _ = run(capsys, ["load", path, "--flow", "non-associative", "--friction",
                                m.group(1)])
    assert "verdict    UNSTABLE" in out
    code, out, _ = run(capsys, ["load", path, "--flow", "non-associative", "--friction",
                                m.group(2)])
    assert "verdict    COLLAPSE" in out


def test_a_distortion_answer_names_an_unstable_answer_of_the_default_method(capsys):
    """examples/corbel_arch_inclined.json at f = 0.766 without dilatancy: the distortion
    method's state from X0 collapses at lambda* = 0.000534, while the convex path's limit
    run from X0 does not carry even the dead load (UNSTABLE). At f = 0.8 the answer
    named the convex path's lower multiplier; here it said nothing of it."""
    path = str(EXAMPLES / "corbel_arch_inclined.json")
    args = ["load", path, "--flow", "non-associative", "--friction", "0.766"]
    code, out, _ = run(capsys, args)
    assert "verdict    UNSTABLE" in out
    code, out, _ = run(capsys, [*args, "--method", "distortion"])
    assert "verdict    COLLAPSE" in out
    assert "the default method (the convex path: the same command without --method) " \
        "finds it UNSTABLE from X0" in out, out


def test_a_bisection_with_a_trial_that_did_not_settle_is_not_called_converged(capsys):
    """examples/corbel_arch_inclined.json at f = 0.8 without dilatancy: `load` reads its
    answer off the states reached from X0 by bisection, one of whose trials (at lambda =
    0.0127925344) did not settle; the flow line said "converged". The bracket it left,
    [0.01279220942, 0.0127926969], is 3.8e-5 wide relative to its ends, for 1e-5 asked:
    it was decided by an absolute floor of 1e-6 that the associative searches count only
    within 1e-6 of 0 (results.within); now UNDECIDED, exit 3, as theirs would be. At
    --rtol 4e-5 the bisection stops at that bracket before the trial that does not
    settle: a number, "requested 4e-05" (3.9e-5 was printed as 4e-05)."""
    args = ["load", str(EXAMPLES / "corbel_arch_inclined.json"), "--flow",
            "non-associative", "--friction", "0.8"]
    code, out, _ = run(capsys, args)
    flow = next(ln for ln in out.splitlines() if ln.startswith("flow"))
    assert code == 3 and "UNDECIDED" in out and flow.endswith("not converged"), out
    assert "answer     lambda* in [0.01279220942, 0.0127926969]" in out, out
    assert "accuracy 3.8e-05 reached, 1.0e-05 requested" in out, out
    for rtol in ("4e-5", "3.9e-5"):
        code, out, _ = run(capsys, args + ["--rtol", rtol])
        assert code == 0 and "COLLAPSE" in out and (
            "accuracy   3.8e-05 (bracket [0.01279220942, 0.0127926969], relative width; "
            f"requested {float(rtol):.2g})") in out, out


def test_safe_is_pointed_to_only_where_it_runs(tmp_path, capsys):
    """An 8 x 8 running-bond wall at f = 0.6 (180 joints) without dilatancy: `check` at
    0.539 (it stands from X0) and `friction` pointed to `rigidblocks load ... --safe`,
    which answers "not computed" beyond 50 joints; they now say so. The Arpino gate (32
    joints) keeps the command."""
    from rigidblocks.io import write_scene

    f = tmp_path / "wall.json"
    write_scene(build("wall", courses=8, blocks_per_course=8, friction=0.6), f)
    code, out, _ = run(capsys, ["check", str(f), "--flow", "non-associative",
                                "--load-factor", "0.5"])
    assert code == 0 and "--safe`) may lie" not in out
    assert "`rigidblocks load --safe` computes it on scenes of up to 50 joints; this one " \
        "has 180" in out, out
    code, out, _ = run(capsys, ["check", str(EXAMPLES / "arpino_gate.json"), "--flow",
                                "non-associative", "--method", "distortion",
                                "--load-factor", "0.12"])
    assert "(`rigidblocks load --flow non-associative --safe`) may lie" in out, out


def test_a_distortion_answer_at_the_associative_multiplier_has_its_accuracy(capsys):
    """examples/arpino_gate.json, `load --flow non-associative --method distortion`: the
    state reached from X0 stands at the associative multiplier, which is the answer
    (0.122797); it had no accuracy line and a JSON bracket, rtol and accuracy of null,
    where the associative multiplier itself is certified to 1.6e-7."""
    args = ["load", str(EXAMPLES / "arpino_gate.json"), "--flow", "non-associative",
            "--method", "distortion"]
    code, out, _ = run(capsys, [*args, "--json"])
    d = json.loads(out)
    lo, hi = d["bracket"]
    assert code == 0 and lo == d["load_multiplier"] < hi < lo * (1 + 1e-6)
    assert d["accuracy"] is not None and d["accuracy"] < 1e-6


def test_an_unstable_load_from_x0_names_the_joints_it_breaches(capsys, monkeypatch):
    """examples/flat_arch_vertical.json at f = 0.6 without dilatancy: the state reached
    from X0 breaches the joint laws under the dead load, and `load` said only that,
    where `check --load-factor 0` names the joints (v1-pier_l, 6.46 kN, first). It
    names them from that state, without running its fixed point again."""
    from rigidblocks.analyses.nonassociative import ConvexNonAssociative

    runs: list[float] = []
    plain = ConvexNonAssociative.fixed_point

    def counted(self, f, load_factor):
        runs.append(load_factor)
        return plain(self, f, load_factor)

    monkeypatch.setattr(ConvexNonAssociative, "fixed_point", counted)
    path = str(EXAMPLES / "flat_arch_vertical.json")
    args = ["--flow", "non-associative", "--friction", "0.6"]
    code, out, _ = run(capsys, ["check", path, *args, "--load-factor", "0"])
    first = re.search(r"governing  breached at ([^ ]+) \(([0-9.]+) kN\)", out)
    assert first, out
    code, out, _ = run(capsys, ["load", path, *args])
    assert "verdict    UNSTABLE" in out
    assert (f"under the dead load alone breaches the joint laws (at {first.group(1)}, "
            in out and f"; by up to {first.group(2)} kN): it does not stand" in out), out
    assert runs == [0.0, 0.0], runs  # one for `check`, one for `load`


def test_the_verdict_of_a_bonded_scene_names_the_bond(capsys):
    """examples/fig4a_bonded.json at load factor 1.1: `check` said "an equilibrium state
    with every joint in compression and within friction exists" above a joint table
    whose bond carries 10 N of tension (all its strength); and the note on bonded
    joints quoted that example's own numbers ("collapses on its load path at lambda =
    1, against 1.2") beside runs at other settings, where they are not this run's."""
    path = str(EXAMPLES / "fig4a_bonded.json")
    code, out, _ = run(capsys, ["check", path, "--load-factor", "1.1", "--joints"])
    assert ("verdict    ADMISSIBLE: it stands (an equilibrium state with every joint in "
            "compression or within its tensile strength, and within friction and "
            "cohesion exists)") in out, out
    assert "in tension" in out  # the table's bond
    code, out, _ = run(capsys, ["load", path, "--friction", "0.3"])
    assert "(an example, not this run: the bundled fig4a_bonded.json at its own " \
        "friction 0.5 collapses on its load path at lambda = 1" in out, out
    # a scene without bonds keeps the plain words
    code, out, _ = run(capsys, ["check", str(EXAMPLES / "reference.json"), "--load-factor",
                                "1.1"])
    assert "every joint in compression and within friction exists" in out


def test_the_question_names_the_joints_with_a_friction_of_their_own(tmp_path, capsys):
    """A keyed wall loaded in plane whose foundation joints have f = 0.8 (the others the
    scene's 0.6): `load` slides on the foundation at lambda* = 0.8 beside "at friction
    f = 0.6 (30.96 deg)", with no word of the joints that carry their own friction."""
    path = str(tmp_path / "kwi.json")
    assert main(["example", "keyed_wall", "--courses", "3", "--blocks_per_course", "2",
                 "--load_direction", "in_plane", "--base_friction", "0.8", "-o",
                 path]) == 0
    capsys.readouterr()
    code, out, _ = run(capsys, ["load", path])
    assert "answer     lambda* = 0.8," in out
    assert ("at friction f = 0.6 (30.96 deg), 2 joints at a friction of their own "
            "(foundation-c0b0 f = 0.8, foundation-c0b1 f = 0.8)") in out, out


def test_a_path_collapse_at_zero_is_decided_by_the_absolute_floor(capsys):
    """examples/reference.json at f = 0: `path` read UNDECIDED (exit 3), "admissible up to
    lambda = 0, not decided at 9.53674316e-08", where `load` gives lambda* = 0: a bracket
    within 1e-6 of the live load near 0 is decided, as `load`'s are. A collapse put at
    the lower end of such a bracket has it in the JSON (examples/fig4a_bonded.json:
    "bracket": null beside the note "the collapse lies in [1, 1.00000076]")."""
    code, d, _ = run_json(capsys, ["path", str(EXAMPLES / "reference.json"), "--friction",
                                   "0", "--json"])
    assert code == 0 and d["status"] == "collapse" and d["collapse_load"] == 0.0, d
    lo, hi = d["bracket"]
    assert lo == 0.0 and 0.0 < hi <= 1e-6
    # the frictionless joints that carry a normal force are at their threshold of 0: the
    # collapse names them (it named no joint: a threshold f N = 0 read as unloaded)
    collapse = [e for e in d["events"] if e["kind"] == "collapse"]
    assert {tuple(j) for j in collapse[0]["joints"]} == {
        ("support", "left"), ("support", "right"), ("left", "top"), ("right", "top")}, d
    code, d, _ = run_json(capsys, ["path", str(EXAMPLES / "fig4a_bonded.json"), "--json"])
    assert code == 0 and d["status"] == "collapse" and d["collapse_load"] == 1.0
    lo, hi = d["bracket"]
    assert lo == 1.0 and 1.0 < hi < 1.0 + 1e-6


def test_picture_titles_read_joints_of_infinite_friction_as_their_own():
    """The short case of a title said "(some joints their own)" only where a joint's own
    friction was finite: an override "infinite" (a keyed joint) was not counted, while
    the question line named it; where every joint has its own, the title read the
    uniform f that applies to none."""
    from rigidblocks.answer import answer_block
    from rigidblocks.scene.model import JointOverride

    stack = make_scene([
        {"id": "ground", "vertices": rect(-1, -0.5, 4, 0.5), "support": True},
        {"id": "b1", "vertices": rect(0, 0, 1, 1)},
        {"id": "b2", "vertices": rect(0, 1, 1, 1)},
    ], unit_weight=20.0, friction=0.3, live_body_force=[0.1, 0])
    one = stack.with_changes(joints=(JointOverride(("b1", "b2"), friction="infinite"),))
    r = rb.check(one, load_factor=0.1)
    assert answer_block(one, r).case.endswith("at f = 0.3 (some joints their own)")
    both = one.with_changes(joints=(*one.joints,
                                    JointOverride(("ground", "b1"), friction=0.5)))
    r = rb.check(both, load_factor=0.1)
    assert answer_block(both, r).case.endswith("at each joint's own friction")


def test_a_state_at_the_friction_limit_is_not_read_as_a_margin(capsys):
    """The flat arch with vertical joints stands at f = 0.6, and its state of least
    complementary energy is at the friction limit at one joint, while f* = 0.47: the
    line read as if the arch were on the edge of sliding; it says now that it is not a
    margin, other states needing less."""
    code, out, _ = run(capsys, ["check", str(EXAMPLES / "flat_arch_vertical.json")])
    assert code == 0 and "ADMISSIBLE" in out
    assert "reaches the friction limit f = 0.6 (joint v1-pier_l): not a margin against " \
        "sliding, as other states may need less; the least friction any state needs is " \
        "f*" in out, out
    assert rb.min_friction(rb.read_scene(EXAMPLES / "flat_arch_vertical.json"),
                           state=False).friction_factor < 0.5
    # the JSON has the line too (its notes are the result's own: here only that dry
    # joints would not stand, test_dilatancy_note)
    code, d, _ = run_json(capsys, ["check", str(EXAMPLES / "flat_arch_vertical.json"),
                                   "--json"])
    assert code == 0 and all(n.startswith("without dilatancy") for n in d["notes"])
    assert any("not a margin against sliding" in w for w in d["why"]), d["why"]


def test_a_3d_group_joined_to_no_support_has_no_equilibrium(tmp_path, capsys):
    """A box on its support's edge with another on it: the pair is joined to no
    support, so its weight has no equilibrium, whatever the joint laws (its joint
    forces cancel in its resultant). In 3D the relaxation's cone program was not
    certified infeasible: `check` ended "solver failure ... InsufficientProgress" (exit
    1), `load` and `friction` undecided; then NOT ADMISSIBLE, UNSTABLE, UNSTABLE; now,
    as in 2D, refused as bad input, saying where the box meets its support."""
    blocks = [{"id": "base", "vertices": box3d(0, 2, 0, 2, -1, 0), "faces": BOX_FACES,
               "support": True},
              {"id": "top", "vertices": box3d(2, 3, 0, 1, 0, 1), "faces": BOX_FACES},
              {"id": "cap", "vertices": box3d(2, 3, 0, 1, 1, 2), "faces": BOX_FACES}]
    scene = {"format": "rigidblocks-scene", "version": 1, "dimension": 3,
             "unit_weight": 20, "friction": 0.6, "live_body_force": [1, 0, 0],
             "blocks": blocks}
    path = tmp_path / "s.json"
    path.write_text(json.dumps(scene))
    unheld_error(capsys, str(path), "block 'top' touches block 'base' along an edge only",
                 "blocks 'top', 'cap' are joined to no support")


def test_no_state_at_all_says_so_without_the_x0_caveat(tmp_path, capsys):
    """The 9-voussoir arch at f = 0.3 has no admissible state under its dead load (its
    static f* is 0.3336): without dilatancy `load` and `check` said "the answer is the
    one reached from the elastic state X0 ... other states, and so other answers, may
    exist" beside it, while no state stands at all: no other state gives another
    answer."""
    path = str(tmp_path / "a9.json")
    rb.write_scene(build("arch", voussoirs=9, friction=0.3), path)
    for argv in (["load", path], ["check", path, "--load-factor", "0"]):
        code, out, _ = run(capsys, [*argv, "--flow", "non-associative"])
        assert code == 0 and "static problem" in out, out
        assert "other states, and so other answers, may exist" not in out, out


def test_a_suggested_command_keeps_the_load_factor_given(capsys):
    """README: "a load factor you give is printed as given". The check of the flat arch
    with vertical joints at load factor 0.2495975 (just above its collapse multiplier
    0.2495974) suggested `rigidblocks friction ... --load-factor 0.249597`, another
    question, below the collapse multiplier."""
    path = str(EXAMPLES / "flat_arch_vertical.json")
    assert main(["check", path, "--load-factor", "0.2495975"]) == 0
    out = capsys.readouterr().out
    assert f"`rigidblocks friction {path} --load-factor 0.2495975` gives" in out
    assert "0.249597`" not in out


def test_the_tilt_angle_is_given_only_where_a_tilt_loads_it_the_same_way():
    """A 1 x 2 block (40 kN) on its base: the tilt line is atan(lambda*) where its
    self-weight is all its dead load and its joint purely frictional (slides at f =
    0.4: 21.8 deg, the tilting table's atan(f)). With 40 kN more on its top (a dead
    point load the live body force does not multiply) lambda* = 0.8 read "38.66 deg: the
    ground tilted by this angle loads it the same way", where tilted it slides at
    atan(0.4); with a cohesion of 10 kN/m^2 at f = 0.1 it read 19.29 deg, where tilted
    it slides at 20.11 deg (40 sin t = 0.1 x 40 cos t + 10, its joint 1 m long). Those
    give no tilt angle now."""
    from rigidblocks.answer import answer_block

    blocks = [{"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
              {"id": "B", "vertices": rect(0, 0, 1, 2)}]
    top = dict(unit_weight=20.0, live_body_force=[1, 0])
    plain = rb.max_load_multiplier(make_scene(blocks, friction=0.4, **top))
    assert plain.load_multiplier == pytest.approx(0.4)
    assert plain.tilt_angle_deg == pytest.approx(math.degrees(math.atan(0.4)))
    dead = rb.max_load_multiplier(make_scene(
        blocks, friction=0.4, loads=[{"block": "B", "force": [0, -40], "point": [0.5, 2]}],
        **top))
    assert dead.load_multiplier == pytest.approx(0.8) and dead.tilt_angle_deg is None
    bonded = rb.max_load_multiplier(make_scene(
        blocks, friction=0.1, joints=[{"blocks": ["base", "B"], "cohesion": 10.0}], **top))
    assert bonded.load_multiplier == pytest.approx(0.35) and bonded.tilt_angle_deg is None
    assert "tilt angle" not in "\n".join(answer_block(
        make_scene(blocks, friction=0.1, joints=[{"blocks": ["base", "B"],
                                                 "cohesion": 10.0}], **top),
        bonded).reasons)


def test_governing_joints_below_their_limit_in_the_state_shown_are_not_called_at_it(capsys):
    """The stocky arch's f* for its dead load, 0.298455 (bracket [0.2981565, 0.2984547]),
    rests on four joints (the certificate below f* names them), but its state at f*, the
    least-energy one of many, has |T|/N = 0.29798 at the two pier joints: the table read
    "closed" there beside a governing line "at their friction limit, to f*'s accuracy".
    The line now says what f* rests on and the |T|/N the state shown has there; where the
    state has each governing joint at its limit (the reference model) it says so."""
    from rigidblocks.results import force_state_words

    path = str(EXAMPLES / "stocky_arch.json")
    res = rb.min_friction(rb.read_scene(path), load_factor=0)
    words = force_state_words(res)
    names = ["-".join(res.joint_name(k)) for k in res.governing]
    assert set(names) == {"v7-pier_l", "v1-pier_r", "v5-v6", "v2-v3"}
    assert [words[k] for k in res.governing].count("closed") == 2
    text = run(capsys, ["friction", path, "--load-factor", "0", "--joints"])[1]
    line = next(x for x in text.splitlines() if x.startswith("governing"))
    lo = min(float(res.state.demand[k]) for k in res.governing)
    assert 0.2979 < lo < 0.2981
    assert line.endswith(f"(f* rests on their friction; the state shown at f*, one of many, "
                         f"has |T|/N = {lo:.6g} to 0.298455 there)"), line
    ref = str(EXAMPLES / "reference.json")
    assert "(at their friction limit)" in run(capsys, ["friction", ref, "--joints"])[1]
    # without a state to show them in, what the certificate says, --joints or not alike
    # (the stocky arch's line was "at their friction limit" without --joints)
    for argv in ([path, "--load-factor", "0"], [ref]):
        out = run(capsys, ["friction", *argv])[1]
        assert "(f* rests on their friction)" in out, out


def test_a_bond_that_pulls_only_at_infinite_friction_is_said_to(tmp_path, capsys):
    """A 1 x 2 block (W = 40) bonded to its base by a tensile strength of 10 under an
    upward live body force: at infinite friction it lifts at (W + sigma_t a) / W = 1.25
    (no shear row: the bond pulls up to sigma_t a = 10), at every finite f at 1 (the row
    |T| <= f (N1 + N2) + c a keeps N1 + N2 >= 0 without cohesion), f = 1e6 included,
    which docs/scene-format.md called the same law as infinite friction. The answer at
    infinite friction now says so; at finite f there is nothing to say."""
    path = write(tmp_path, make_scene(
        [{"id": "base", "vertices": rect(-2, -1, 6, 1), "support": True},
         {"id": "B", "vertices": rect(0, 0, 1, 2)}],
        unit_weight=20.0, friction="infinite", live_body_force=[0, 1],
        joints=[{"blocks": ["base", "B"], "tensile_strength": 10.0}]))
    note = "at infinite friction a bonded joint has no shear row"
    for f, lam, said in (("infinite", 1.25, True), ("1e6", 1.0, False), ("0.6", 1.0, False)):
        code, doc, _ = run_json(capsys, ["load", path, "--friction", f, "--json"])
        assert code == 0 and doc["load_multiplier"] == pytest.approx(lam, rel=1e-6)
        assert any(note in w for w in doc["why"]) is said, (f, doc["why"])


def test_a_scene_without_depth_beside_point_loads_is_said_to_be_a_slice(tmp_path, capsys):
    """A 1 x 2 m block in mm and N (unit weight 2e-5 N/mm^3) under a point load of 40 kN
    on its top: without a depth it is 1 mm deep and weighs 40 N, and it tipped at
    lambda* = 500.5 with no word; with its depth of 1000 mm it weighs 40 kN and tips at
    (W + P) b / (W h) = 1 (P = W, b/h = 1/2). The answer now says the blocks are a 1 mm
    slice beside the point loads."""
    def scene(**top):  # a key given as None is left out
        keys = {"units": {"length": "mm", "force": "N"}, "unit_weight": 2e-5,
                "friction": "infinite", "live_body_force": [1, 0],
                "loads": [{"block": "B", "force": [0, -40000], "point": [500, 2000]}],
                **top}
        return write(tmp_path, make_scene(
            [{"id": "base", "vertices": rect(-2000, -1000, 6000, 1000), "support": True},
             {"id": "B", "vertices": rect(0, 0, 1000, 2000)}],
            **{k: v for k, v in keys.items() if v is not None}))

    said = "the scene gives no depth: its blocks are 1 mm deep"
    code, doc, _ = run_json(capsys, ["load", scene(), "--json"])
    assert doc["load_multiplier"] == pytest.approx(500.5) and any(said in w for w in doc["why"])
    code, doc, _ = run_json(capsys, ["load", scene(depth=1000), "--json"])
    assert doc["load_multiplier"] == pytest.approx(1.0)
    assert not any(said in w for w in doc["why"]), doc["why"]
    # weightless blocks beside point loads: the depth changes nothing, nothing to say.
    # The live body force would act on nothing (a one-line error says so); a live point
    # load of 10 kN at the top tips the block at 40 kN x 0.5 m / (10 kN x 2 m) = 1
    code, out, err = run(capsys, ["load", scene(unit_weight=0), "--json"])
    assert code == 2 and "weigh nothing" in err and said not in err + out, (out, err)
    push = {"block": "B", "force": [10000, 0], "point": [500, 2000], "live": True}
    weightless = scene(unit_weight=0, live_body_force=None, loads=[
        {"block": "B", "force": [0, -40000], "point": [500, 2000]}, push])
    code, doc, _ = run_json(capsys, ["load", weightless, "--json"])
    assert code == 0 and doc["load_multiplier"] == pytest.approx(1.0, rel=1e-6)
    assert not any(said in w for w in doc["why"]), doc["why"]


def test_f_star_of_a_bonded_scene_is_no_bound_for_every_larger_f(tmp_path, capsys):
    """A 1 x 2 block (W = 40) bonded to its base by a tensile strength of 10, pulled up by
    1.1 W: at f = 0 the row |T| <= f (N1 + N2) + c a caps nothing and the bond pulls (up
    to 10 > 4), at every f > 0 it keeps N1 + N2 >= 0 and the block lifts. `friction` said
    "STANDS with friction f >= f*, f* = 0", false for every f above it; it now says the
    structure stands at f*, and why a larger f need not carry more."""
    path = write(tmp_path, make_scene(
        [{"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
         {"id": "B", "vertices": rect(0, 0, 1, 2)}],
        unit_weight=20.0, friction="infinite", live_body_force=[0, 1],
        joints=[{"blocks": ["base", "B"], "tensile_strength": 10.0}]))
    code, out, _ = run(capsys, ["friction", path, "--load-factor", "1.1"])
    assert code == 0 and "verdict    STANDS at friction f = f*\n" in out, out
    assert "why        with bonded joints a larger f need not carry more" in out
    code, out, _ = run(capsys, ["check", path, "--load-factor", "1.1", "--friction", "0.5"])
    assert "verdict    NOT ADMISSIBLE" in out  # the caveat's case
    code, out, _ = run(capsys, ["friction", str(EXAMPLES / "reference.json")])
    assert "verdict    STANDS with friction f >= f*\n" in out  # no bond: a bound


def test_an_associative_answer_of_a_non_associative_scene_says_which_flow(tmp_path,
                                                                           capsys):
    """The reference model with "flow": "non-associative", asked with --flow associative
    (lambda* = 1.2 with dilatancy): the question named no flow, and a report of the
    result read as the scene's own flow."""
    scene = rb.read_scene(EXAMPLES / "reference.json").with_changes(flow="non-associative")
    path = tmp_path / "ref_na.json"
    rb.write_scene(scene, path)
    code, out, _ = run(capsys, ["load", str(path), "--flow", "associative"])
    assert code == 0 and "lambda* = 1.2," in out
    assert "at friction f = 0.6 (30.96 deg), sliding with dilatancy (associative; not the " \
           "scene's flow)" in out, out
    code, out, _ = run(capsys, ["load", str(EXAMPLES / "reference.json")])
    assert "with dilatancy" not in out


def test_an_unstable_load_answer_points_to_the_check_that_names_the_joints(tmp_path,
                                                                           capsys):
    """A block overhanging its support: `load` said "UNSTABLE: the dead load alone has no
    admissible state" with no why line (JSON why []), where `path` pointed to the check
    that names the breached joints; `load` does too."""
    p = tmp_path / "over.json"
    p.write_text(json.dumps({
        "format": "rigidblocks-scene", "version": 1, "dimension": 2, "unit_weight": 10,
        "friction": 0.6, "live_body_force": [1, 0],
        "blocks": [{"id": "S", "vertices": rect(0, -1, 1, 1), "support": True},
                   {"id": "A", "vertices": rect(0.8, 0, 1, 1)}]}))
    assert main(["load", str(p), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["status"] == "unstable"
    assert f"`rigidblocks check {p} --load-factor 0` names the joints the dead load " \
        "breaches" in doc["why"]
    assert main(["check", str(p), "--load-factor", "0"]) == 0
    assert "breached at S-A" in capsys.readouterr().out


@pytest.mark.parametrize("depth, said", [
    (300.0, "the scene's depth 300 m is 76.8 times the scene's size (3.91 m)"),
    (0.0001, "the scene's depth 0.0001 m is 2.5e+04 times thinner than its blocks (2.5 m)")])
def test_a_depth_far_from_the_scenes_size_is_doubted(depth, said):
    """A scene in metres with point loads and "depth": 300 (meant in mm) collapsed at
    lambda* = 1920.6 where 0.3 m gives 3.8, with no word: the depth scales the weights,
    not the point loads."""
    s = make_scene([
        {"id": "base", "vertices": rect(-1, -0.5, 3, 0.5), "support": True},
        {"id": "B", "vertices": rect(0, 0, 1, 2)}],
        units={"length": "m", "force": "kN"}, unit_weight=20.0, friction=0.6,
        depth=depth,
        loads=[{"block": "B", "force": [1, 0], "point": [0.5, 2], "live": True}])
    r = rb.max_load_multiplier(s, state=False)
    assert any(n.startswith(said) for n in r.notes), r.notes
    ok = rb.max_load_multiplier(make_scene(
        [{"id": "base", "vertices": rect(-1, -0.5, 3, 0.5), "support": True},
         {"id": "B", "vertices": rect(0, 0, 1, 2)}], unit_weight=20.0, friction=0.6,
        depth=0.3, loads=[{"block": "B", "force": [1, 0], "point": [0.5, 2],
                           "live": True}]), state=False)
    assert not any("depth" in n for n in ok.notes)
