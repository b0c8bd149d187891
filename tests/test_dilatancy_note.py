"""An associative `load` beside the same question without dilatancy, on small scenes.

Associative sliding opens a joint by f times its slip (normality). A block standing
against a fixed wall, touching it without pressure, and pulled away from it: dry joints
let it tip about its far toe at lambda = b/h (a block on a level base tips at b/h:
validation.md), while the associative collapse rubs the block up the wall as it tips
(the wall joint compressed and at its friction limit) and needs more. The answer said
nothing of it: an engineer read 0.548387 for a block that tips at 0.5.
"""

from __future__ import annotations

import json

import pytest
from conftest import EXAMPLES, make_scene, rect

import rigidblocks as rb
from rigidblocks.cli.main import main


def against_wall(f=0.6):
    """A b x h = 1 x 2 block on a ground, its right face on a fixed wall, under a
    horizontal body force lambda W away from the wall."""
    return make_scene([
        {"id": "ground", "vertices": rect(-2, -1, 3, 1), "support": True},
        {"id": "wall", "vertices": rect(1, -1, 1, 4), "support": True},
        {"id": "B", "vertices": rect(0, 0, 1, 2)}],
        unit_weight=20.0, friction=f, live_body_force=[-1.0, 0.0])


def test_a_block_against_a_wall_is_said_to_tip_lower_without_dilatancy():
    r = rb.max_load_multiplier(against_wall())
    assert r.status == "collapse" and r.load_multiplier > 0.54  # associative: 0.548387
    st, low = r.without_dilatancy
    assert st == "collapse" and low == pytest.approx(0.5, abs=1e-7)  # b/h
    note = next(n for n in r.notes if n.startswith("without dilatancy"))
    assert "it collapses at lambda = 0.5 from the elastic state X0, 8.8 % lower" in note
    assert "open by f times their slip (associative flow)" in note
    assert r.to_dict()["without_dilatancy"] == {"status": "collapse", "load_multiplier": low}


def test_no_word_where_dry_joints_give_the_same(capsys):
    """The 4 x 4 wall slides on its foundation at f = 0.6 either way, and the arch's
    collapse hinges either way (computed, equal: no note); not computed on the
    non-associative question itself."""
    for name in ("wall.json", "arch.json"):
        r = rb.max_load_multiplier(rb.read_scene(EXAMPLES / name))
        assert r.without_dilatancy[0] == "collapse"
        assert r.without_dilatancy[1] == pytest.approx(r.load_multiplier, rel=1e-6)
        assert not any("without dilatancy" in n for n in r.notes)
    na = rb.max_load_multiplier(against_wall(), flow="non-associative")
    assert na.without_dilatancy is None and "without_dilatancy" not in na.to_dict()


def test_at_infinite_friction_and_whatever_the_associative_mechanism():
    """At infinite friction the block against the wall read UNBOUNDED with no word: the
    wall joint, open, carried shear (a large finite friction and dry joints: it tips at
    b/h = 0.5). A block pinched under a lintel at f = 0.3 beside a block that hinges at
    0.5 (its base joint of infinite friction) collapsed associatively at 0.5 by that
    hinge, with no word (no joint slides in that mechanism), where dry joints let the
    pinched one slide at f = 0.3 (validation.md: the pinched block)."""
    r = rb.max_load_multiplier(against_wall(), friction="infinite")
    assert r.status == "unbounded" and r.without_dilatancy[0] == "collapse"
    assert r.without_dilatancy[1] == pytest.approx(0.5, abs=1e-7)
    assert any(n.startswith("with friction 10 where it is infinite and without dilatancy")
               and "it collapses at lambda = 0.5 from the elastic state X0" in n
               for n in r.notes), r.notes
    s = make_scene([
        {"id": "ground", "vertices": rect(-1, -1, 6, 1), "support": True},
        {"id": "lintel", "vertices": rect(-1, 1, 3, 1), "support": True},
        {"id": "P", "vertices": rect(0, 0, 1, 1)},
        {"id": "Q", "vertices": rect(3, 0, 1, 2)}],
        unit_weight=10.0, friction=0.3, live_body_force=[1.0, 0.0],
        joints=[{"blocks": ["ground", "Q"], "friction": "infinite"}])
    r = rb.max_load_multiplier(s)
    assert r.load_multiplier == pytest.approx(0.5, rel=1e-6)
    assert r.without_dilatancy[1] == pytest.approx(0.3, rel=1e-6)
    assert any("it collapses at lambda = 0.3 from the elastic state X0, 40.0 % lower" in n
               for n in r.notes), r.notes


def test_the_command_says_it_and_the_flat_arch_on_piers_does_not_stand_dry(tmp_path,
                                                                             capsys):
    """The flat arch with vertical joints: its pier joints slide under its own weight
    without dilatancy (test_nonassociative), so dry it has no admissible state at all."""
    assert main(["load", str(EXAMPLES / "flat_arch_vertical.json"), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["without_dilatancy"] == {"status": "unstable", "load_multiplier": None}
    assert any("the dead load alone has no admissible state reached from the elastic "
               "state X0" in w for w in doc["why"])


def test_joints_between_supports_are_none_and_an_open_joint_that_carries_shear_says_so(
        capsys):
    """The block against the wall at infinite friction under 3 x its weight away from
    the wall: `check` admitted it, its table reading wall-B "open" with 48 (here 80 in
    3D) of shear, hung on the wall by shear alone (it tips at b/h = 0.5 with any finite
    friction and dry joints). The joint reads "open, carrying shear" and a why line says
    what lets it. The ground and the wall, both supports, had a joint of their own
    ("ground-wall 0 0 open"), counted among the joints: two supports have none."""
    s = against_wall()
    r = rb.check(s, friction="infinite", load_factor=3.0)
    assert r.status == "admissible" and r.contacts.n_joints == 2
    assert sorted("-".join(r.joint_name(k)) for k in range(2)) == ["ground-B", "wall-B"]
    rows = {"-".join(row["joint"]): row for row in r.joint_table()}
    assert rows["wall-B"]["state"] == "open, carrying shear" and rows["wall-B"]["T"] > 40
    from rigidblocks.answer import answer_block

    why = answer_block(s, r).reasons
    assert any(w.startswith("wall-B carries shear with no compression in this state: "
                            "infinite friction (no sliding) lets an open joint carry "
                            "shear") for w in why), why
    assert rb.max_load_multiplier(s, friction=0.6, flow="non-associative") \
        .load_multiplier == pytest.approx(0.5, abs=1e-7)


def test_friction_says_where_dry_joints_need_more(capsys):
    """The flat arch with vertical joints on piers needs f* = 0.4714 (0.4719 to 2e-3),
    and without dilatancy 0.8100 (docs/seed-examples.md, the seed's reading: its
    friction angle of 39 deg): the associative answer, 42 % lower, said nothing of it.
    The block against the wall under its weight away from it stood associatively from
    f = 1.0002 (rubbing up the wall) and tips dry at any friction (b/h = 0.5 < 1)."""
    assert main(["friction", str(EXAMPLES / "flat_arch_vertical.json"), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    st, f = doc["without_dilatancy"]["status"], doc["without_dilatancy"]["friction_factor"]
    assert st == "stable" and 0.8099 < f < 0.8113, f
    assert any(w.startswith("without dilatancy (dry joints slide without opening: --flow "
                            "non-associative) the state reached from the elastic state X0 "
                            "needs f >= 0.811, 71.9 % more") for w in doc["why"]), doc["why"]
    r = rb.min_friction(against_wall(), load_factor=1.0, state=False)
    assert r.status == "stable" and r.friction_factor > 1.0
    assert r.without_dilatancy == ("unstable", None)
    assert any("no friction tried up to 10 makes the state reached from the elastic state "
               "X0 stand" in n for n in r.notes)
    ref = rb.min_friction(rb.read_scene(EXAMPLES / "reference.json"), state=False)
    assert ref.without_dilatancy[0] == "stable"  # the seed's f* = 0.5 either way: no word
    assert not any(n.startswith("without dilatancy") for n in ref.notes)


def test_check_says_where_dry_joints_do_not_stand(capsys):
    """The block against the wall under 0.52 of its weight away from it at f = 0.6 was
    ADMISSIBLE with no word (associatively it rubs up the wall; dry it tips at b/h =
    0.5); the flat arch with vertical joints at its own f = 0.6 likewise (dry it needs
    0.81). A check that needs no friction at all says nothing (the reference model at
    its f = 0.6, f* = 0.5 either way)."""
    r = rb.check(against_wall(), load_factor=0.52, state=False)
    assert r.status == "admissible" and r.without_dilatancy == ("inadmissible", None)
    assert any("the state reached from the elastic state X0 does not stand at this load"
               in n for n in r.notes), r.notes
    assert r.to_dict()["without_dilatancy"] == {"status": "inadmissible"}
    assert main(["check", str(EXAMPLES / "flat_arch_vertical.json"), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["without_dilatancy"] == {"status": "inadmissible"}
    ref = rb.check(rb.read_scene(EXAMPLES / "reference.json"), state=False)
    assert ref.without_dilatancy[0] == "admissible"
    assert not any("without dilatancy" in n for n in ref.notes)
    assert rb.check(against_wall(), load_factor=0.45, state=False).without_dilatancy[0] \
        == "admissible"
