"""The load path (`load_path`, `rigidblocks path`) under every joint law of the seed
(Heyman, Coulomb's sliding friction, Drucker's plastic shearing: its Fig. 2) and both
flow rules, against closed forms and the convex path.

Closed forms (docs/validation.md; rigidblocks/generators/seed.py for the reference
model): a b x h block under a horizontal body force lambda x weight slides at
lambda = f and tips at b / h; the four-block reference model (seed Fig. 4a, P = 100 N
on the top block, H = 50 N pulling each central block out) collapses when
H lambda = f (P + W_t + W_c), i.e. at lambda = f P / H = 1 at f = 0.5 without
self-weight and at 2 with self-weight (W_t = W_c = 50 N). Events are located to 1e-6
relative (issue 30, item 5).
"""

from __future__ import annotations

import json
import re

import pytest
from conftest import EXAMPLES

import rigidblocks as rb
from rigidblocks.analyses import load_path
from rigidblocks.cli.main import main

EV = 1e-6  # relative accuracy of an event's load
LAWS = [(s, fl) for s in ("plastic", "coulomb") for fl in ("associative", "non-associative")]


def kinds(p):
    return [e.kind for e in p.events]


def joints(e):
    return {frozenset(j) for j in e.joints}


def test_a_hinge_collapse_names_its_hinges():
    """The semicircular arch (examples/arch.json) under a horizontal body force fails
    by four hinges, no joint sliding: the path's collapse names the joints where the
    thrust reaches an edge in its last admissible state, the hinges of the convex
    method's mechanism (computed here), at the convex method's multiplier (to 1e-6).
    Before, it named no joint ("collapse -")."""
    from rigidblocks.contacts import detect_contacts

    scene = rb.read_scene(EXAMPLES / "arch.json")
    ref = rb.max_load_multiplier(scene)
    c = detect_contacts(scene)
    hinges = {frozenset((c.block_ids[c.pairs[k][0]], c.block_ids[c.pairs[k][1]]))
              for k in ref.mechanism.joints_with("hinge")}
    assert len(hinges) == 4
    p = load_path(scene)
    assert p.status == "collapse"
    assert p.collapse_load == pytest.approx(ref.load_multiplier, rel=EV)
    assert kinds(p) == ["collapse"] and joints(p.first("collapse")) == hinges


@pytest.mark.parametrize("sliding, flow", LAWS)
def test_single_block_slides_at_f(block_on_base, sliding, flow):
    """validation.md: lambda* = min(f, b/h); b/h = 0.5 and f = 0.3: it slides at
    lambda = f = 0.3, its bed joint reaching the threshold there."""
    p = load_path(block_on_base(1.0, 2.0, 0.3), steps=7, max_load=1.0, sliding=sliding,
                  flow=flow)
    assert p.status == "collapse" and p.collapse_load == pytest.approx(0.3, rel=EV)
    assert p.first("plastic").load_factor == pytest.approx(0.3, rel=EV)
    assert joints(p.first("collapse")) == {frozenset(("base", "B"))}


@pytest.mark.parametrize("flow", ["associative", "non-associative"])
def test_heyman_block_tips_at_b_over_h_with_no_plastic_joint(block_on_base, flow):
    """Heyman (friction infinite: T unbounded): the block cannot slide and tips at
    lambda = b/h = 0.5 (validation.md); no joint ever has a shear threshold (before:
    every joint was plastic at the first step, a comparison of -inf with -inf)."""
    p = load_path(block_on_base(1.0, 2.0, "infinite"), steps=7, max_load=1.0, flow=flow)
    assert "plastic" not in kinds(p)
    assert p.status == "collapse" and p.collapse_load == pytest.approx(0.5, rel=EV)
    assert joints(p.first("collapse")) == {frozenset(("base", "B"))}  # its toe hinge
    ref = load_path(rb.read_scene(EXAMPLES / "reference_self_weight.json"),
                    friction="infinite", flow=flow)
    assert ref.status == "standing" and ref.events == ()
    assert all(s.at_threshold == () for s in ref.steps)


@pytest.mark.parametrize("sliding, flow", LAWS)
def test_reference_model_collapses_at_f_p_over_h(sliding, flow):
    """Seed Fig. 4a without self-weight at f = 0.5: the four bed joints reach the
    threshold together and the central blocks slip at lambda = f P / H = 1."""
    scene = rb.read_scene(EXAMPLES / "reference.json")
    p = load_path(scene, friction=0.5, steps=13, sliding=sliding, flow=flow)
    assert p.status == "collapse" and p.collapse_load == pytest.approx(1.0, rel=EV)
    assert p.first("plastic").load_factor == pytest.approx(1.0, rel=EV)
    assert len(joints(p.first("collapse"))) == 4


def test_a_collapse_located_by_a_stall_names_the_load_found_not_admissible():
    """The reference model at f = 0.6 collapses at f P / H = 1.2 (seed Fig. 4a): the
    iteration stalls just above it, and the note said only that (a COLLAPSE that read
    as resting on an undecided trial); it names the first load found not admissible,
    which brackets the collapse within 1e-6."""
    scene = rb.read_scene(EXAMPLES / "reference.json")
    p = load_path(scene)
    assert p.status == "collapse" and p.collapse_load == pytest.approx(1.2, rel=EV)
    note = next(n for n in p.notes if n.startswith("the collapse load is located"))
    hi = float(note.split("so the collapse lies in [")[1].split(", ")[1].split("]")[0])
    assert 1.2 < hi <= 1.2 * (1 + 1e-6), note


def test_the_limit_analyses_say_that_they_keep_the_bonds_and_the_path_does_not(capsys):
    """examples/fig4a_bonded.json: `load` gives 1.2 (the bond's strength counted at
    every load), the path 1 (the crack at 0.4 loses it); neither said why they differ:
    `load` now says that it keeps the bond, the path does not say so."""
    path = str(EXAMPLES / "fig4a_bonded.json")
    assert main(["load", path]) == 0
    out = capsys.readouterr().out
    assert "lambda* = 1.2," in out and "1 joint is bonded" in out
    # the command to run names the scene analysed (it named only the bundled example)
    assert f"`rigidblocks path {path}` follows the cracks" in out
    assert main(["path", path]) == 0
    assert "joint is bonded" not in capsys.readouterr().out


def test_the_table_rounds_as_the_status_line(capsys):
    """examples/arch.json: the status line printed the collapse force 5.64535 kN (down)
    and the table's collapse row 5.64536 (the nearest)."""
    assert main(["path", str(EXAMPLES / "arch.json")]) == 0
    out = capsys.readouterr().out.splitlines()
    status = next(ln for ln in out if ln.startswith("status"))
    row = next(ln for ln in out if " collapse " in ln)
    force = status.split(" = ")[-1].split()[0]
    assert row.split()[1] == force, (status, row)


def test_coulomb_slide_with_self_weight_collapses_where_it_slides():
    """Reference model with self-weight at f = 0.5. The least-energy state's friction
    demand at lambda = 1 (convex path, `check --friction infinite`: 1/3 at left-top)
    puts the top joints' threshold at lambda_s = f / demand = 1.5. With Coulomb's
    sliding friction their shear drops to zero there; each central block then holds
    H lambda_s = 75 N on its bed joint alone, whose capacity is f N_bottom =
    0.5 (75 + 50) = 62.5 N: collapse at lambda_s, naming the joints that slid (before:
    collapse at 1.45, one step early, no joint named)."""
    scene = rb.read_scene(EXAMPLES / "reference_self_weight.json")
    demand = rb.check(scene, friction="infinite", load_factor=1.0).friction_demand[0]
    lam_s = 0.5 / demand
    assert lam_s == pytest.approx(1.5, rel=1e-6)
    for flow in ("associative", "non-associative"):
        p = load_path(scene, friction=0.5, sliding="coulomb", flow=flow)
        assert kinds(p) == ["plastic", "slide", "collapse"], flow
        assert p.collapse_load == pytest.approx(lam_s, rel=EV)
        top = {frozenset(("left", "top")), frozenset(("right", "top"))}
        assert joints(p.first("slide")) == top and top <= joints(p.first("collapse"))
        # where it was located, said (the collapse had no bracket and no why line)
        lo, hi = p.bracket
        assert lo <= p.collapse_load <= hi and lo <= lam_s * (1 + 1e-6) and \
            hi >= lam_s * (1 - 1e-6)
        assert any(n.startswith("the collapse follows the event at lambda = ")
                   for n in p.notes), p.notes


@pytest.mark.parametrize("steps, top", [(7, 2.5), (13, 2.5), (40, 2.5), (40, 1e12)])
def test_plastic_shearing_with_self_weight_events_at_their_loads(steps, top):
    """Drucker: the top joints plasticise at lambda_s = 1.5 (as above) and stay at their
    threshold; the structure collapses at the static multiplier
    f (P + W_t + W_c) / H = 0.5 x 200 / 50 = 2 (generators/seed.py), whatever the step
    (before: 1.53846 with 13 steps, the end of the step; and with steps of 2.5e10 to
    max_load = 1e12, a collapse at 0, its first bracket left 23 wide)."""
    scene = rb.read_scene(EXAMPLES / "reference_self_weight.json")
    p = load_path(scene, friction=0.5, steps=steps, max_load=top)
    first = p.first("plastic")
    assert first.load_factor == pytest.approx(1.5, rel=EV)
    assert joints(first) == {frozenset(("left", "top")), frozenset(("right", "top"))}
    assert p.status == "collapse" and p.collapse_load == pytest.approx(2.0, rel=EV)


def test_fig4a_bonded_cracks_then_plasticises_then_collapses(capsys):
    """examples/fig4a_bonded.json, seed Fig. 4b-c: "When the force F overcomes the
    tensile strength of the vertical joint, a crack occurs ... Subsequently, when force
    F equals the value of the friction reaction, horizontal joints undergo a
    plasticization process and the structure fails". Tensile strength 400 N/m^2 over
    each link's half of the 0.1 x 0.25 m joint: 5 N per link. Below the crack the state
    is the least-energy one, linear in lambda (the dead load puts no normal force on
    the vertical joint): the crack is at 5 / |N(lambda = 0.2)| x 0.2, N from the convex
    path's least-energy state (QP to its default tolerance: 1e-3). After it the model
    is the dry one: collapse at f P / H = 1."""
    path = EXAMPLES / "fig4a_bonded.json"
    scene = rb.read_scene(path)
    p = load_path(scene)
    assert kinds(p) == ["crack", "plastic", "collapse"]
    crack, plastic = p.first("crack"), p.first("plastic")
    assert joints(crack) == {frozenset(("left", "right"))}
    assert joints(plastic) == {frozenset(j) for j in (("support", "left"),
                               ("support", "right"), ("left", "top"), ("right", "top"))}
    st = rb.check(scene, load_factor=0.2).state
    n_v = st.normal[scene_points(scene, "left", "right")].min()
    assert crack.load_factor == pytest.approx(0.2 * 5.0 / -n_v, rel=1e-3)
    assert p.collapse_load == pytest.approx(1.0, rel=EV)
    assert plastic.load_factor == pytest.approx(1.0, rel=EV)
    assert main(["path", str(path)]) == 0
    out = capsys.readouterr().out
    # the two opposing pulls have no resultant: the column is their sum, "in all"
    assert "lambda [-]" in out and "live in all [N]" in out
    rows = [ln.split()[2] for ln in out.splitlines() if ln.startswith("  ") and
            ln.split()[0][0].isdigit()]
    assert rows == ["crack", "plastic", "collapse"]


def scene_points(scene, a, b):
    """The contact points of the joint between blocks a and b."""
    from rigidblocks.methods import open_method

    c = open_method(scene, "distortion").contacts
    ids = c.block_ids
    k = next(k for k, (i, j) in enumerate(c.pairs) if {ids[i], ids[j]} == {a, b})
    return [int(i) for i in range(len(c.point_joint)) if c.point_joint[i] == k]


def test_undecided_is_said_with_exit_3(tmp_path, capsys):
    """Tensile strength without cohesion on the vertical joint: the shear row
    |T| <= f (N1 + N2) keeps the joint's net force compressive, so the static collapse
    is the dry one, lambda = f P / H = 1 (the convex path: below). The distortion
    iteration cannot certify the collapse there: the path must say undecided (exit 3,
    with its bracket, which holds 1), or collapse at 1 (before: "COLLAPSE at 0.99375")."""
    scene = rb.read_scene(EXAMPLES / "reference.json")
    from rigidblocks.io import write_scene
    from rigidblocks.io.scene_file import dumps_scene, loads_json, scene_from_dict

    doc = loads_json(dumps_scene(scene))
    doc["friction"] = 0.5
    doc["joints"] = [{"blocks": ["left", "right"], "tensile_strength": 400.0}]
    dry = scene_from_dict(doc)
    assert rb.max_load_multiplier(dry).load_multiplier == pytest.approx(1.0, rel=1e-6)
    f = tmp_path / "t.json"
    write_scene(dry, f)
    code = main(["path", str(f), "--json"])
    res = json.loads(capsys.readouterr().out)
    if res["status"] == "collapse":
        assert code == 0 and res["collapse_load"] == pytest.approx(1.0, rel=EV)
    else:
        assert res["status"] == "undecided" and code == 3
        lo, hi = res["bracket"]
        assert lo <= 1.0 <= hi * (1 + EV) and res["collapse_load"] is None
        assert main(["path", str(f)]) == 3
        assert "UNDECIDED: admissible up to lambda" in capsys.readouterr().out


def test_cli_flow_option_and_json(capsys):
    f = str(EXAMPLES / "reference.json")
    assert main(["path", f, "--flow", "non-associative", "--friction", "0.5", "--json"]) == 0
    res = json.loads(capsys.readouterr().out)
    assert res["flow"] == "non-associative" and res["collapse_load"] == pytest.approx(1.0)
    main(["path", f, "--flow", "non-associative"])
    assert "non-associative flow (no dilatancy: the seed's procedure)" in \
        capsys.readouterr().out


@pytest.mark.parametrize("flow", ["associative", "non-associative"])
def test_a_wall_slides_on_its_foundation_at_f_with_its_head_joints_plastic_from_the_start(
        flow):
    """A 2 x 3 running-bond wall under a horizontal body force lambda x weight at
    f = 0.6: the base joints carry lambda W against f W, so it slides at lambda = f =
    0.6 (validation.md's sliding block; the convex path's multiplier, asserted here).
    Its head joints carry no normal force under the dead load, hence no shear: those
    the first load reaches are plastic from the start, one event at lambda = 0 (before,
    each was reported where its normal force passed 1e-6 of the largest force, at
    lambda = 5e-6 to 2.6e-4, and without dilatancy c1b1-c1b2 at 4.6e-3, where its
    margin, 3e-10 below the threshold, passed 1e-5 of it). The 4 x 4 wall's path ended
    undecided at 0.59999."""
    from rigidblocks.generators import build

    scene = build("wall", courses=2, blocks_per_course=3, friction=0.6)
    assert rb.max_load_multiplier(scene).load_multiplier == pytest.approx(0.6, rel=1e-6)
    p = load_path(scene, flow=flow)
    assert p.status == "collapse" and p.collapse_load == pytest.approx(0.6, rel=EV)
    first = p.first("plastic")
    head = {frozenset((f"c{k}b{i}", f"c{k}b{i + 1}")) for k, n in ((0, 3), (1, 4))
            for i in range(n - 1)}
    bottom = {j for j in head if "c0b0" in j or "c0b1" in j}
    assert first.load_factor == 0.0 and bottom <= joints(first) <= head
    loads = [e.load_factor for e in p.events]
    assert loads == sorted(loads) and all(x == 0.0 or x > 0.1 for x in loads)
    # and it says why joints that carry nothing are plastic at lambda = 0
    n = len(joints(first))
    assert any(f"{n} joint{'s carry' if n > 1 else ' carries'} no force under the dead "
               "load" in note for note in p.notes), p.notes


def test_path_json_gives_the_terminals_why_lines(capsys):
    """`path --json` had `notes` but no `why`, which docs/scene-format.md gives every
    command's JSON: the flat arch with vertical joints without dilatancy is UNSTABLE
    from X0, and the JSON did not say that it is the state reached from X0 that
    breaches, whether or not another state stands."""
    f = str(EXAMPLES / "flat_arch_vertical.json")
    args = ["path", f, "--flow", "non-associative"]
    assert main(args) == 0
    why = [ln[len("why        "):] for ln in capsys.readouterr().out.splitlines()
           if ln.startswith("why ")]
    assert main([*args, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["status"] == "unstable" and d["why"] == why
    assert d["why"][0].startswith("the state reached from the elastic state X0 under the "
                                  "dead load alone breaches the joint laws")


def test_a_path_without_dilatancy_names_the_lower_collapse_of_the_convex_path(tmp_path,
                                                                                capsys):
    """The non-associative path of the 3 x 3 running-bond wall at f = 0.8 collapsed at
    0.749241, 4.9 % above `load --flow non-associative` (0.714286, within LMGC90's
    [0.7136, 0.7143], docs/methods.md), and the Arpino gate's at 0.122798 above 0.118702,
    with no word of it: the path now names the lower collapse (the safer)."""
    from rigidblocks.generators import build
    from rigidblocks.io import write_scene

    wall = tmp_path / "w33.json"
    write_scene(build("wall", courses=3, blocks_per_course=3, friction=0.8), wall)
    for path, low in ((str(wall), "0.714285"),
                      (str(EXAMPLES / "arpino_gate.json"), "0.118702")):
        assert main(["path", path, "--flow", "non-associative"]) == 0
        out = capsys.readouterr().out
        assert "status     COLLAPSE at lambda = " in out
        assert (f"why        `rigidblocks load --flow non-associative` (the convex path, "
                f"from X0) collapses at lambda = {low}, below this path's collapse load: "
                "non-associative collapse states are not unique, and the lower is the "
                "safer") in out, out
    # associative: no such word (the convex path's is the one multiplier)
    assert main(["path", str(wall), "--max-load", "0.7"]) == 0
    assert "the convex path, from X0" not in capsys.readouterr().out


def test_an_undecided_path_says_why(capsys, monkeypatch):
    """An undecided path (exit 3) printed its reason, the run's iteration budget, with -v
    alone, and its JSON's why was [] (the 3 x 3 wall at f = 0.8: undecided at 0.770410156,
    "no convergence within the iteration budget (19300 iterations ..."). Here the budget
    is cut to 10 iterations so that the reference model's path is undecided at once."""
    monkeypatch.setattr("rigidblocks.methods.distortion.MAX_ITER", 10)
    ref = str(EXAMPLES / "reference.json")
    assert main(["path", ref]) == 3
    out = capsys.readouterr().out
    assert "status     UNDECIDED" in out
    assert any(x.startswith("why        at lambda = ") and "no convergence" in x
               for x in out.splitlines()), out
    assert main(["path", ref, "--json"]) == 3
    doc = json.loads(capsys.readouterr().out)
    assert any("no convergence" in w for w in doc["why"]), doc["why"]


def test_a_paths_question_names_the_joints_own_laws(tmp_path, capsys):
    """A stack whose middle joint has f = 0.2 of its own, at --friction infinite, read
    "friction infinite" and then slid there at 0.2; with that joint alone without
    dilatancy and --flow associative, "non-associative flow" for the whole path. The
    question now says what `load`'s says: the joint's own friction, and how many joints
    slide without dilatancy."""
    from conftest import make_scene, rect

    from rigidblocks.io import write_scene

    def stack(joint):
        path = tmp_path / f"stack{len(list(tmp_path.iterdir()))}.json"
        write_scene(make_scene(
            [{"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
             {"id": "A", "vertices": rect(0, 0, 1, 1)}, {"id": "B", "vertices": rect(0, 1, 1, 1)}],
            unit_weight=20.0, friction=0.6, live_body_force=[1, 0],
            joints=[{"blocks": ["A", "B"], **joint}]), path)
        return str(path)

    assert main(["path", stack({"friction": 0.2}), "--friction", "infinite"]) == 0
    out = capsys.readouterr().out
    assert "associative flow, infinite friction (no sliding), 1 joint at a friction of " \
           "its own (A-B f = 0.2)" in out, out
    assert "status     COLLAPSE at lambda = 0.2" in out
    assert main(["path", stack({"flow": "non-associative"}), "--flow", "associative"]) == 0
    out = capsys.readouterr().out
    assert "1 of 2 joints sliding without dilatancy (the seed's procedure), the others " \
           "associative, friction f = 0.6" in out, out
    assert main(["path", stack({"flow": "non-associative"}), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["sliding_joints"] == 1
    # the count in every JSON (null read "all" and "none" alike, and `load` left it out)
    for argv, count in ((["path", stack({}), "--json"], 0),
                        (["path", stack({}), "--flow", "non-associative", "--json"], 2),
                        (["load", stack({"flow": "non-associative"}), "--json"], 1),
                        (["check", stack({"flow": "non-associative"}), "--load-factor", "0.3",
                          "--json"], 1),
                        (["load", stack({}), "--flow", "non-associative", "--json"], 2)):
        main(argv)
        assert json.loads(capsys.readouterr().out)["sliding_joints"] == count, argv


def test_a_collapse_says_what_each_of_its_joints_does(tmp_path, capsys):
    """A 1 x 2 block bonded to its base (tensile strength 20, depth 1.5, W = 60) at
    infinite friction tips at (b + sigma_t d b^2 / W) / h = (1 + 20 x 1.5 / 60) / 2 = 0.75
    when its bond cracks: the path read "crack", then "plastic" (its |T|/N is 0.75,
    against no friction limit), then "collapse base-B"; and the same block unbonded read
    "collapse base-B" whether it slid (f = 0.4) or tipped (f = 0.6, b/h = 0.5). The
    collapse's joints now say what each does in the last state (a hinge of the state, its
    thrust at an edge, not necessarily the mechanism's), and a crack is no plasticity."""
    from conftest import make_scene, rect

    from rigidblocks.io import write_scene

    def block(**top):
        path = tmp_path / "block.json"
        write_scene(make_scene([{"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
                                {"id": "B", "vertices": rect(0, 0, 1, 2)}],
                               unit_weight=20.0, live_body_force=[1, 0], **top), path)
        return str(path)

    bonded = block(friction=5.0, depth=1.5,
                   joints=[{"blocks": ["base", "B"], "tensile_strength": 20.0}])
    assert main(["path", bonded, "--friction", "infinite", "--json"]) == 0
    events = json.loads(capsys.readouterr().out)["events"]
    assert [(e["kind"], e["load_factor"]) for e in events] == [("crack", pytest.approx(0.75)),
                                                              ("collapse", pytest.approx(0.75))]
    assert events[1]["modes"] == ["cracked, thrust at an edge"]
    for f, lam, mode in ((0.4, 0.4, "at friction limit"), (0.6, 0.5, "thrust at an edge")):
        assert main(["path", block(friction=f)]) == 0
        out = capsys.readouterr().out
        assert f"collapse  base-B ({mode})" in out and f"COLLAPSE at lambda = {lam}" in out, out


def test_joints_plastic_under_the_dead_load_are_said_to_be(capsys):
    """The flat arch with vertical joints on piers at f = 0.6: its two pier joints are at
    the friction threshold under its self-weight, an event at lambda = 0 that nothing
    explained (the one note at lambda = 0 is for joints that carry no force)."""
    assert main(["path", str(EXAMPLES / "flat_arch_vertical.json")]) == 0
    out = capsys.readouterr().out
    assert "               0             0  plastic   v1-pier_l, v9-pier_r" in out, out
    assert ("why        2 joints are at the friction threshold under the dead load alone (in "
            "the state reached from the elastic state X0): plastic from lambda = 0") in out


def test_an_unstable_path_says_where_its_breached_joints_are_named(capsys):
    """The corbel arch with horizontal joints at f = 0.6 has no admissible state under
    its self-weight: the path said so and named no joint, where `check --load-factor 0`
    names the five it breaches; it now points there."""
    path = str(EXAMPLES / "corbel_arch_horizontal.json")
    assert main(["path", path]) == 0
    out = capsys.readouterr().out
    assert "status     UNSTABLE" in out
    assert ("why        the dead load alone has no admissible state (`rigidblocks check "
            "--load-factor 0` names the joints it breaches)") in out, out


def test_joints_that_slide_at_once_under_the_dead_load_are_said_to(capsys):
    """`path --sliding coulomb` on the flat arch with vertical joints: its pier joints are
    at the friction threshold under its self-weight, slide and keep no shear, and the
    path collapses at lambda = 0; the note on joints plastic under the dead load was not
    given where the collapse came at once (no why line at all)."""
    assert main(["path", str(EXAMPLES / "flat_arch_vertical.json"), "--sliding",
                 "coulomb"]) == 0
    out = capsys.readouterr().out
    assert "status     COLLAPSE at lambda = 0" in out
    assert ("why        2 joints are at the friction threshold under the dead load alone (in "
            "the state reached from the elastic state X0): plastic from lambda = 0; with "
            "Coulomb sliding friction they slide and keep no shear") in out, out


def test_a_max_load_beyond_what_double_precision_carries_is_one_line(capsys):
    """max_load x the largest live load must stay below 1e150 (docs/scene-format.md,
    "Limits"), as the load factor of `check` must: --max-load 1e300 ended in a
    traceback (an SVD that did not converge)."""
    code = main(["path", str(EXAMPLES / "reference_self_weight.json"), "--max-load", "1e300"])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and "max_load" in err, err
    assert "Traceback" not in err


def test_a_path_of_more_steps_than_it_takes_is_refused():
    """--steps 1e9 ran on for hours; the path takes at most MAX_STEPS = 10,000 steps
    (events are located to 1e-9 of their load whatever the step)."""
    from rigidblocks.errors import InputError

    scene = rb.read_scene(EXAMPLES / "reference.json")
    with pytest.raises(InputError, match="1 to 10000 steps"):
        load_path(scene, steps=10**9)


def test_an_event_the_steps_are_too_coarse_to_locate_is_undecided(block_on_base):
    """The block slides at f = 0.3 (validation.md); a path to max_load = 1e100 in 40
    steps (each 2.5e98 wide) cannot bisect its first step down to 0.3 within the trial
    budget, and said "COLLAPSE at lambda = 0" with no word. It is undecided, with the
    reason; a path to 1e40 still locates the slide at 0.3."""
    scene = block_on_base(1.0, 2.0, 0.3)
    p = load_path(scene, max_load=1e40, flow="non-associative")
    assert p.status == "collapse" and p.collapse_load == pytest.approx(0.3, rel=EV)
    p = load_path(scene, max_load=1e100, flow="non-associative")
    assert p.status == "undecided" and p.collapse_load is None
    assert any("could not be located" in n for n in p.notes), p.notes


def test_a_path_under_a_live_couple_gives_it_in_force_x_length(tmp_path, capsys):
    """A 0.4 x 1 m block of 20 kN/m^3 (W = 8 kN) under a live couple of 1 kN m tips at
    W b / 2 = 8 x 0.2 = 1.6 kN m, lambda = 1.6 (validation.md, tipping about a toe):
    the path said "1.6 x 0 kN = 0 kN", the couple's size being no force. Its table's
    headers stand over their columns."""
    doc = {"format": "rigidblocks-scene", "version": 1, "dimension": 2,
           "units": {"length": "m", "force": "kN"}, "depth": 1.0, "unit_weight": 20.0,
           "friction": 0.6, "blocks": [
               {"id": "base", "vertices": [[-1, -0.2], [1, -0.2], [1, 0], [-1, 0]],
                "support": True},
               {"id": "B", "vertices": [[0, 0], [0.4, 0], [0.4, 1.0], [0, 1.0]]}],
           "loads": [{"block": "B", "force": [0, 0], "moment": 1.0, "live": True}]}
    path = tmp_path / "couple.json"
    path.write_text(json.dumps(doc))
    assert main(["path", str(path), "--flow", "non-associative"]) == 0
    out = capsys.readouterr().out.splitlines()
    status = next(ln for ln in out if ln.startswith("status"))
    assert "1.6 x 1 kN m = 1.6 kN m of couples" in status, status
    head = next(i for i, ln in enumerate(out) if "lambda [-]" in ln)
    assert "live [kN m]" in out[head]

    def ends(line):  # where each of a row's words ends
        return [m.end() for m in re.finditer(r"\S+", line)]

    # right-aligned: each header ends where its column's figures end
    assert out[head].index("  event") == ends(out[head + 1])[1]
    assert out[head].index("lambda [-]") + 10 == ends(out[head + 1])[0]
    # the reference model's balanced pulls: "live in all [N]", 15 wide, stood 3 columns
    # right of its 12-wide column
    assert main(["path", str(EXAMPLES / "reference.json")]) == 0
    out = capsys.readouterr().out.splitlines()
    head = next(i for i, ln in enumerate(out) if "lambda [-]" in ln)
    assert "live in all [N]" in out[head]
    assert out[head].index("  event") == ends(out[head + 1])[1]
    # the end of a path that stands, as given (it read 1.23457, rounded up)
    assert main(["path", str(path), "--max-load", "1.23456789", "--steps", "2"]) == 0
    assert "STANDING at lambda = 1.23456789 " in capsys.readouterr().out


def test_joints_that_slid_are_said_to_carry_no_shear(capsys):
    """Coulomb's sliding friction on the reference model (f = 0.5): the four joints
    slide together at f P / H = 1 (generators/seed.py) and keep no shear; the collapse
    that follows named them "at friction limit", a threshold of f x 0 = 0 that their
    shear of 0 meets."""
    scene = rb.read_scene(EXAMPLES / "reference.json")
    p = load_path(scene, friction=0.5, sliding="coulomb", max_load=2.0)
    end = p.first("collapse")
    assert p.status == "collapse" and p.collapse_load == pytest.approx(1.0, rel=EV)
    assert joints(end) == joints(p.first("slide")) and len(end.joints) == 4
    assert set(end.modes) == {"slid: no shear left"}, end.modes


def test_a_non_associative_path_at_infinite_friction_says_its_flow_rule_is_idle(capsys):
    """Heyman's law (no sliding) leaves the flow rule nothing to act on: the question
    read "non-associative flow (no dilatancy ...)" beside "infinite friction (no
    sliding)" with no word; at finite friction nothing more is said."""
    ref = str(EXAMPLES / "reference.json")
    idle = "idle: no joint slides at infinite friction"
    assert main(["path", ref, "--friction", "infinite", "--flow", "non-associative"]) == 0
    assert idle in capsys.readouterr().out
    assert main(["path", ref, "--flow", "non-associative"]) == 0
    assert idle not in capsys.readouterr().out


def test_json_units_of_a_scene_without_units_read_as_every_analysis_reads_them(
        tmp_path, capsys):
    """A scene with no units: `load --json` gives them as null ("force units" in the
    text); the path's JSON gave "" for the same scene."""
    from rigidblocks.io.scene_file import loads_json

    doc = loads_json((EXAMPLES / "reference.json").read_text())
    doc.pop("units")
    f = tmp_path / "plain.json"
    f.write_text(json.dumps(doc))
    assert main(["load", str(f), "--json"]) == 0
    expected = json.loads(capsys.readouterr().out)["units"]
    assert expected == {"length": None, "force": None}
    assert main(["path", str(f), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["units"] == expected
