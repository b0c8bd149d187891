"""HTML reports: what they say, that they name no address, and that they work in a
real browser (headless Chromium: a screenshot that is not blank, no JavaScript error).

Reference values as in tests/test_plot.py: the block on a support under a horizontal
body force lambda W collapses at lambda* = min(f, b/h); its minimum friction at load
factor lambda is f* = lambda.
"""

from __future__ import annotations

import re
from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")

import pytest  # noqa: E402
from conftest import EXAMPLES, make_scene, rect  # noqa: E402

import rigidblocks as rb  # noqa: E402
from rigidblocks.cli.main import main  # noqa: E402
from rigidblocks.generators.solids import box_stack  # noqa: E402
from rigidblocks.io import read_scene  # noqa: E402
from rigidblocks.reporting import Report, content  # noqa: E402
from rigidblocks.reporting.browser import (  # noqa: E402
    page_state,
    pixel_spread,
    screenshot,
)

# CI (.ci/run installs chromium) must run the browser tests; elsewhere they are skipped
# when no browser is installed (the fixture ``chromium`` of conftest.py)
needs_chromium = pytest.mark.usefixtures("chromium")


def addresses(page: str) -> list[str]:
    return re.findall(r"""(?:https?|ftp|wss?)://[^\s"'<>)]*""", page)


def assert_offline(page: str) -> None:
    """No address but XML namespace names (identifiers, never fetched), no external
    script, style sheet, image or font."""
    assert all(a.startswith("http://www.w3.org/") for a in addresses(page)), \
        set(addresses(page))
    assert not re.search(r"<(script|img|iframe)[^>]*\ssrc=", page)
    assert "<link" not in page and "@import" not in page
    assert not re.search(r"url\((?!#)", page)  # only the SVG's own clip paths


# -- what the report says ---------------------------------------------------------------
@pytest.mark.parametrize("status", ["undecided", "failure", "inaccurate", ""])
def test_no_verdict_never_reads_as_one(status):
    scene = box_stack(boxes=1)
    res = SimpleNamespace(analysis="check", status=status, notes=("the solver stalled",),
                          friction=0.6, load_factor=1.0, admissible=None)
    ans = content.answer(scene, res)
    assert not ans.verdict and ans.tone == "none"
    assert ans.headline.startswith("NO VERDICT")
    for word in ("ADMISSIBLE", "stands", "stable", "collapse", "UNSTABLE"):
        assert word not in ans.headline
    assert ans.details == ("the solver stalled",)  # the reason, shown, never hidden


def test_verdicts_and_parameters(block_on_base):
    sc = block_on_base(b=1.0, h=2.0, friction=0.4)
    load = rb.max_load_multiplier(sc)
    ans = content.answer(sc, load)
    assert ans.verdict and ans.tone == "warn" and "0.4" in ans.headline
    assert any("sliding" in d for d in ans.details)
    fr = content.answer(sc, rb.min_friction(sc, load_factor=0.3))
    assert fr.verdict and "f* = 0.3" in fr.headline
    bad = content.answer(sc, rb.check(sc, friction=0.1, load_factor=0.3))
    assert bad.tone == "bad" and bad.headline.startswith("NOT ADMISSIBLE")
    q = content.question(sc, load)
    assert "(1, 0)" in q and "f = 0.4" in q  # what lambda multiplies, and the friction


def test_joint_table_and_states(block_on_base):
    """The bed joint of the tipping block (f = 0.9 > b/h): a hinge; at lambda = 0.3 in a
    check, N = W = 2, T = 0.6, |T|/N = 0.3."""
    sc = block_on_base(b=1.0, h=2.0, friction=0.9)
    t = content.joint_table(rb.max_load_multiplier(sc))
    assert t["n"] == 1 and t["state"] == ["hinge"]
    t = content.joint_table(rb.check(sc, load_factor=0.3))
    assert t["N"][0] == pytest.approx(2.0, rel=1e-6)
    assert abs(t["T"][0]) == pytest.approx(0.6, rel=1e-6)
    assert t["demand"][0] == pytest.approx(0.3, rel=1e-6)
    assert t["state"] == ["closed"]


def test_joint_states_read_each_joints_own_friction(capsys):
    """A unit block on a base, its bed joint given f = 0.2 by an override (the scene's f
    = 0.9), checked at lambda = 0.2: |T|/N = 0.2 is the joint's own friction limit. The
    report's table said "closed" (it compared with the scene's 0.9); the terminal's
    table and the report's now agree."""
    sc = make_scene([
        {"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "a", "vertices": rect(0, 0, 1, 1)},
    ], unit_weight=1.0, friction=0.9, live_body_force=[1, 0],
        joints=[{"blocks": ["base", "a"], "friction": 0.2}])
    res = rb.check(sc, load_factor=0.2)
    assert res.status == "admissible"
    assert content.joint_table(res)["state"] == ["at friction limit"]
    assert [r["state"] for r in res.joint_table()] == ["at friction limit"]
    res = rb.check(sc, load_factor=0.1)
    assert content.joint_table(res)["state"] == ["closed"]


def test_joint_states_read_cohesion_and_the_picture_each_joints_threshold():
    """The same block, its bed joint given f = 0.2 and cohesion 0.1 (contact area 1, so
    its shear threshold is 0.2 N + 0.1 = 0.3): at lambda = 0.2 it uses 2/3 of it
    ("closed": the table said "at friction limit", reading |T|/N = f alone), at 0.3 all
    of it. The picture colours the joint by that share (it coloured by |T|/N over the
    scene's f = 0.9)."""
    sc = make_scene([
        {"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "a", "vertices": rect(0, 0, 1, 1)},
    ], unit_weight=1.0, friction=0.9, live_body_force=[1, 0],
        joints=[{"blocks": ["base", "a"], "friction": 0.2, "cohesion": 0.1}])
    for lf, state, share in ((0.2, "closed", 2 / 3), (0.3, "at friction limit", 1.0)):
        res = rb.check(sc, load_factor=lf)
        assert res.status == "admissible"
        assert [r["state"] for r in res.joint_table()] == [state]
        assert content.joint_table(res)["state"] == [state]
        ax = rb.plot(sc, res)
        (lc,) = [a for a in ax.get_children() if a.get_gid() == "rb-joints"]
        assert float(lc.get_array()[0]) == pytest.approx(share, rel=1e-4)
        matplotlib.pyplot.close("all")


def test_a_3d_joint_with_one_unloaded_corner_is_not_hinging():
    """examples/box_stack_3d.json at lambda = 0.25 (below its lambda* = 0.308): in the
    least-energy state a corner of the two lowest joints carries nothing, but their
    resultants lie inside the contact (e = 0.459 and 0.399 m from the centroid): "closed"
    (the tables said "hinging" whenever one corner carried nothing). At lambda* the
    joint the mechanism hinges (box0-box1, "hinge") has its loaded corners on one edge:
    "hinging"."""
    scene = read_scene(EXAMPLES / "box_stack_3d.json")
    res = rb.check(scene, load_factor=0.25)
    assert res.status == "admissible"
    assert [r["state"] for r in res.joint_table()] == ["closed"] * 4
    assert content.joint_table(res)["state"] == ["closed"] * 4
    res = rb.max_load_multiplier(scene)
    modes = content.joint_table(res)["state"]
    words = [r["state"] for r in res.joint_table()]
    assert modes.count("hinge") == 1
    assert words[modes.index("hinge")] == "hinging"


def test_the_report_highlights_the_joints_the_mechanism_moves():
    """examples/arch.json, `load`: the answer names four hinges (the arch's mechanism);
    the report's table flagged none of them as governing (only joints at their
    friction limit were), though the page says governing joints are highlighted."""
    res = rb.max_load_multiplier(read_scene(EXAMPLES / "arch.json"))
    t = content.joint_table(res)
    flagged = {j for j, g in zip(t["joint"], t["governing"], strict=True) if g}
    hinges = {j for j, s in zip(t["joint"], t["state"], strict=True) if s == "hinge"}
    assert len(hinges) == 4 and hinges <= flagged, (hinges, flagged)


def test_open_joint_in_table_and_picture():
    """Two blocks side by side on a base under their weight: the head joint between them
    carries nothing (open), the bed joints are closed."""
    sc = make_scene([
        {"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "a", "vertices": rect(0, 0, 1, 1)},
        {"id": "b", "vertices": rect(1, 0, 1, 1)},
    ], unit_weight=1.0, friction=0.5)
    res = rb.check(sc, load_factor=0.0)
    t = content.joint_table(res)
    head = t["joint"].index("a\N{EN DASH}b")
    assert t["state"][head] == "open"
    assert t["state"].count("closed") == 2
    ax = rb.plot(sc, res)
    (oc,) = [a for a in ax.get_children() if a.get_gid() == "rb-open-joints"]
    assert len(oc.get_paths()) == 1
    matplotlib.pyplot.close("all")


# -- the document --------------------------------------------------------------------------
def test_2d_report_document(tmp_path, block_on_base):
    sc = block_on_base(b=1.0, h=2.0, friction=0.5).with_changes(
        units=rb.scene.Units("m", "kN"), name="block <on> base")
    out = tmp_path / "r.html"
    page = rb.report(sc, analysis="friction", load_factor=0.3, path=out)
    assert isinstance(page, Report) and out.read_text(encoding="utf-8") == page
    assert page.startswith("<!DOCTYPE html>")
    assert "block &lt;on&gt; base" in page  # names are escaped
    assert 'data-status="stable"' in page and "f* = 0.3" in page
    assert "<svg" in page and "<text" in page  # text kept as text
    assert "rb-table-data" in page and "three" not in page.lower().split("<svg")[0][-200:]
    assert "window.THREE" not in page  # 2D reports carry no three.js
    assert_offline(page)


def test_3d_report_document():
    page = rb.report(box_stack(boxes=2), analysis="load")
    assert 'id="rb-view"' in page and "window.THREE = Object.freeze" in page
    assert 'data-status="collapse"' in page
    assert_offline(page)
    assert len(page) < 1_000_000  # three.js (~690 kB) and a small scene


def test_scene_only_and_option_errors(tmp_path):
    page = rb.report(EXAMPLES / "reference.json")
    assert "rb-answer" not in page and "<svg" in page
    with pytest.raises(rb.InputError):
        rb.report(box_stack(boxes=1), friction=0.5)  # options without an analysis
    with pytest.raises(rb.InputError, match="unknown analysis"):
        rb.report(box_stack(boxes=1), analysis="thickness")


def test_notebook_view():
    page = rb.report(box_stack(boxes=1))
    frame = page._repr_html_()
    assert "<iframe srcdoc=" in frame and "&lt;!DOCTYPE html&gt;" in frame
    pytest.importorskip("IPython")
    assert page.to_ipython().data == frame


def test_a_report_echoed_at_a_prompt_is_one_line():
    """A plain Python prompt echoes repr(): it was the whole document (750 kB with a 3D
    view); it is one line that says what the report is and how to write it, while the
    report is still the document (a str)."""
    page = rb.report(box_stack(boxes=1))
    assert "\n" not in repr(page) and len(repr(page)) < 200 and ".save(path)" in repr(page)
    assert str(page).startswith("<!DOCTYPE html>") and f"{len(page):,}" in repr(page)


def test_cli(tmp_path, capsys):
    out = tmp_path / "flat.html"
    scene = str(EXAMPLES / "flat_arch_vertical.json")
    assert main(["report", scene, "--analysis", "check", "--friction", "infinite",
                 "--load-factor", "0", "-o", str(out)]) == 0
    assert "wrote" in capsys.readouterr().out
    assert 'data-status="admissible"' in out.read_text(encoding="utf-8")
    assert main(["report", scene, "-o", str(tmp_path / "x.pdf")]) == 2
    assert main(["report", scene, "--friction", "0.5", "-o", str(out)]) == 2
    assert main(["report", scene, "--analysis", "load", "--load-factor", "1",
                 "-o", str(out)]) == 2
    assert "--load-factor" in capsys.readouterr().err


# -- in a real browser ------------------------------------------------------------------------
@needs_chromium
def test_2d_report_in_chromium(tmp_path):
    html = tmp_path / "flat.html"
    rb.report(EXAMPLES / "flat_arch_vertical.json", analysis="friction", load_factor=0,
              path=html)
    st = page_state(html)
    assert st.errors == ()
    assert int(st.data["table-rows"]) == 12  # the table was built by its script
    png = tmp_path / "flat.png"
    screenshot(html, png, size=(1200, 1400))
    assert pixel_spread(png) > 0.05


@needs_chromium
def test_the_report_table_shows_the_joints_own_laws(tmp_path):
    """Fig. 4a with its bonded vertical joint: the report's table has the columns of
    the joints' cohesion and tensile strength (they differ), not their friction (the
    same f = 0.5 everywhere), and the bonded joint's row shows 400 in both."""
    html = tmp_path / "fig4a.html"
    rb.report(EXAMPLES / "fig4a_bonded.json", analysis="check", path=html)
    st = page_state(html)
    assert st.errors == () and int(st.data["table-rows"]) == 5
    heads = re.findall(r"""<th data-key=["'](\w+)["']""", st.dom)
    assert "cohesion" in heads and "tensile_strength" in heads and "friction" not in heads
    # a title with an apostrophe is whole (it ended the attribute: "the joint")
    assert 'title="the joint\'s cohesion (stress)"' in st.dom
    assert 'title="shear along the joint\'s tangent"' in st.dom
    row = next(r for r in re.findall(r"<tr[^>]*>(.*?)</tr>", st.dom, flags=re.S)
               if "left\N{EN DASH}right" in r)
    cells = re.findall(r"<td[^>]*>(.*?)</td>", row)
    assert cells[heads.index("cohesion")] == cells[heads.index("tensile_strength")] == "400"


@needs_chromium
def test_3d_report_in_chromium(tmp_path):
    html = tmp_path / "stack.html"
    rb.report(EXAMPLES / "box_stack_3d.json", analysis="load", path=html)
    st = page_state(html)
    assert st.errors == ()
    assert st.data.get("viewer-ready") == "1"
    # every control once (layers, slider, play, reset, a table row, a joint's forces)
    ctl = page_state(html, fragment="rb-selftest")
    assert ctl.errors == () and ctl.data.get("selftest") == "done"
    assert ctl.data["selftest-tip"].startswith("joint ") and "state:" in ctl.data["selftest-tip"]
    assert float(st.data["viewer-painted"]) > 0.02  # the view drew the blocks
    assert int(st.data["viewer-draw-calls"]) <= 16
    png = tmp_path / "stack.png"
    screenshot(html, png, size=(1200, 1100))
    assert pixel_spread(png) > 0.05


@needs_chromium
def test_3d_check_report_has_no_mechanism_controls(tmp_path):
    """A check has no mechanism: its 3D view showed the legend "moving block
    (mechanism)", a mechanism layer, slider and play button (disabled). They are left
    out, and the page runs its self-test without them."""
    html = tmp_path / "check.html"
    rb.report(EXAMPLES / "box_stack_3d.json", analysis="check", path=html)
    page = html.read_text(encoding="utf-8")
    for gone in ("moving block (mechanism)", 'class="rb-play"', 'class="rb-amp"',
                 'data-layer="mechanism"', "hinge line (dots", "mechanism's displacements"):
        assert gone not in page, gone
    assert "joint resultant" in page
    st = page_state(html)
    assert st.errors == () and st.data.get("viewer-ready") == "1"
    ctl = page_state(html, fragment="rb-selftest")
    assert ctl.errors == () and ctl.data.get("selftest") == "done"


@needs_chromium
def test_browser_check_sees_javascript_errors(tmp_path):
    """The page's own hook catches errors, so a clean run above means something."""
    page = rb.report(box_stack(boxes=1))
    html = tmp_path / "bad.html"
    html.write_text(page.replace("</body>", "<script>undefinedFunction();</script></body>"),
                    encoding="utf-8")
    st = page_state(html)
    assert any("undefinedFunction" in e for e in st.errors)


def test_undecided_result_reads_as_no_verdict_everywhere(block_on_base):
    """A status the analyses may add (undecided, failure): the badge, the headline and
    the picture all say that nothing was decided."""
    import dataclasses

    sc = block_on_base(b=1.0, h=2.0, friction=0.5)
    res = dataclasses.replace(rb.check(sc, load_factor=0.3), status="undecided", state=None,
                              notes=("the bracket did not close",))
    page = rb.report(sc, res)
    assert 'data-verdict="no"' in page and ">no verdict<" in page
    assert "NO VERDICT" in page  # the picture's title and message
    assert "ADMISSIBLE" not in page.replace("NOT ADMISSIBLE", "")
    assert "the bracket did not close" in page


def test_a_non_associative_report_gives_its_flow_and_bounds(tmp_path, capsys):
    """The terminal's "flow" and "bounds" lines of a non-associative answer are in the
    page too (the reference model with self-weight: bounds [0.6, 2.4], 0.6 the capacity
    bound, the least multiplier of any state, derived in test_na_bounds.py, 2.4
    associative); the page had neither."""
    import html

    src = str(EXAMPLES / "reference_self_weight.json")
    assert main(["load", src, "--flow", "non-associative"]) == 0
    said = capsys.readouterr().out
    bounds = next(ln for ln in said.splitlines() if ln.startswith("bounds"))[11:].strip()
    out = tmp_path / "r.html"
    assert main(["report", src, "--analysis", "load", "--flow", "non-associative", "-o",
                 str(out)]) == 0
    text = html.unescape(re.sub(r"<[^>]+>", " ", out.read_text()))
    assert f"bounds: {bounds}" in text and bounds.startswith("[0.6, 2.4]")
    assert "flow: non-associative: " in text


def test_the_report_says_what_state_its_forces_are():
    """The line on the forces shown names the state the result carries: after `load`
    the collapse state at lambda* (it read "one admissible state" beside COLLAPSE), after
    `friction` the state at f*, and beside a non-associative NOT ADMISSIBLE from the
    limit fixed point the state reached from X0 that stands (the inclined corbel arch
    at f = 0.7652 under its dead load: tests/test_honest_answers.py)."""
    arch = read_scene(EXAMPLES / "arch.json")
    load = rb.max_load_multiplier(arch)
    # the picture draws the mechanism: the forces are the table's, whose state column
    # holds the mechanism's modes (a joint at its friction limit that does not move reads
    # "closed" there)
    assert content.forces_shown(load).startswith(
        "Forces in the joint table (the picture draws the collapse mechanism): one state "
        "at the collapse load \u03bb* (least complementary energy)")
    assert content.joint_table(load)["state_label"] == "in the mechanism"
    assert content.joint_table(rb.check(arch, load_factor=0.1))["state_label"] == "state"
    na = rb.max_load_multiplier(arch, flow="non-associative")
    assert "nor, without dilatancy, the multiplier" in content.forces_shown(na)
    assert "one admissible state at f*" in content.forces_shown(rb.min_friction(arch))
    assert "one admissible state (least" in content.forces_shown(
        rb.check(arch, load_factor=0.1))
    corbel = read_scene(EXAMPLES / "corbel_arch_inclined.json")
    direct = rb.check(corbel, friction=0.7652, load_factor=0, flow="non-associative")
    assert direct.status == "inadmissible"
    assert "the state reached from X0 at this load" in content.forces_shown(direct)
    assert content.forces_shown(rb.check(arch, load_factor=0.3, state=False)) is None


def test_the_report_gives_the_accuracy_and_its_commands_as_code(tmp_path, capsys):
    """The report's notes give the accuracy line the terminal prints (the distortion
    method's lambda* = 1.19921 on the reference model, against the convex path's 1.2,
    stood there without its bracket [1.19921875, 1.201171875]); the terminal's
    backticks around a command are code, not literal."""
    out = tmp_path / "ref.html"
    ref = str(EXAMPLES / "reference.json")
    assert main(["report", ref, "--analysis", "load", "--method", "distortion",
                 "-o", str(out)]) == 0
    page = out.read_text(encoding="utf-8")
    assert "accuracy 1.6e-03 (bracket [1.19921875, 1.201171875], relative width" in page
    assert "<code>--method clarabel</code>" in page
    assert "`" not in re.sub(r"<script.*?</script>", "", page, flags=re.S)
    capsys.readouterr()
    assert main(["load", ref, "--method", "distortion"]) == 0
    assert "accuracy   1.6e-03 (bracket [1.19921875, 1.201171875]" in capsys.readouterr().out


def test_a_report_of_a_result_it_cannot_show_says_so():
    """`rb.report(scene, check_result, analysis="load")` gave the check's page without a
    word; `rb.report(scene, "hello")` a page saying "NO VERDICT: status unknown (the
    analysis could not decide ...)"; `rb.plot` of another scene's result ended in
    "zip() argument 3 is shorter than arguments 1-2"; an option the analysis does not
    take was named as the command line's (--load-factor) to a Python caller."""
    from rigidblocks.errors import InputError

    scene = rb.read_scene(EXAMPLES / "reference.json")
    res = rb.check(scene, load_factor=0.2)
    with pytest.raises(InputError, match="analysis='load' with the result of a check: "
                       "give one or the other"):
        rb.report(scene, res, analysis="load")
    with pytest.raises(InputError, match="result: expected the result of check, "
                       "min_friction or max_load_multiplier, got str"):
        rb.report(scene, "hello")
    other = rb.read_scene(EXAMPLES / "arch.json")
    for show in (rb.report, rb.plot):
        with pytest.raises(InputError, match="result: the result of a check of another "
                           "scene"):
            show(other, res)
    # the same ids, another block: a 3 x 1 block drawn with the result of a 1 x 2 one
    # (hinging at its middle at 0.5, where it slides at 0.6)
    one = make_scene([{"id": "base", "vertices": rect(-5, -1, 10, 1), "support": True},
                      {"id": "B", "vertices": rect(0, 0, 1, 2)}],
                     unit_weight=20.0, friction=0.6, live_body_force=[1, 0])
    wide = make_scene([{"id": "base", "vertices": rect(-5, -1, 10, 1), "support": True},
                       {"id": "B", "vertices": rect(0, 0, 3, 1)}],
                      unit_weight=20.0, friction=0.6, live_body_force=[1, 0])
    for show in (rb.report, rb.plot):
        with pytest.raises(InputError, match=r"another scene \(its blocks' ids are this "
                           r"scene's, their corners are not\)"):
            show(wide, rb.max_load_multiplier(one))
    # the same blocks, another load: the arch's live load halved was reported with the
    # old result, "0.149764 x 18.85 kN" (the new load's lambda* is 0.2995), and a doubled
    # unit weight beside the old forces
    arch = rb.read_scene(EXAMPLES / "arch.json")
    got = rb.max_load_multiplier(arch)
    for changes, named in (({"live_body_force": (0.5, 0.0)}, "live_body_force"),
                           ({"unit_weight": 40.0, "depth": 2.0},
                            "unit_weight and depth"),
                           ({"loads": (rb.Load("v3", (0.0, -1.0)),)}, "loads")):
        for show in (rb.report, rb.plot):
            with pytest.raises(InputError, match="result: the result of a max_load_multiplier"
                               " of this scene's blocks under other values of " + named):
                show(arch.with_changes(**changes), got)
    # what the result records itself, and equal values spelt otherwise, are no change
    rb.report(arch.with_changes(friction=0.3, live_body_force=(1, 0)), got)
    with pytest.raises(InputError, match=r"the load analysis takes no load_factor "
                       r"\(--load-factor\)"):
        rb.report(scene, analysis="load", load_factor=0.2)
    assert "ADMISSIBLE" in rb.report(scene, res, analysis="check")


def test_the_joint_table_of_a_check_that_fails_names_its_breaches():
    """The reference model at f = 0.3, NOT ADMISSIBLE, each joint breached by 5 N at a
    contact, 10 N on the vertical joint (5 at each of its points; the answer's governing
    line and the picture name them): the report's table read "-" for every joint, none
    highlighted, under "governing joints are highlighted"."""
    scene = rb.read_scene(EXAMPLES / "reference.json")
    res = rb.check(scene, friction=0.3)
    table = content.joint_table(res)
    assert table["state_label"] == "in the state of least breach"
    assert all(table["governing"])
    assert dict(zip(table["joint"], table["state"], strict=True)) == {
        "left\u2013right": "breached by 10 N", **{j: "breached by 5 N" for j in table["joint"]
                                             if j != "left\u2013right"}}


def test_the_3d_view_of_a_check_that_fails_marks_its_breaches():
    """examples/box_stack_3d.json at load factor 2, NOT ADMISSIBLE, its four joints
    breached (the answer and the PNG name them): the interactive view marked none, and
    its legend read "joint resultant" over a view with no forces."""
    from rigidblocks.reporting.view3d import view_data

    scene = rb.read_scene(EXAMPLES / "box_stack_3d.json")
    res = rb.check(scene, load_factor=2.0)
    assert res.status == "inadmissible" and len(res.breaches) == 4
    data = view_data(scene, res)
    assert "breached" in data["joints"] and "forces" not in data["joints"]
    page = rb.report(scene, res)
    assert "breached joint (its breach in the table)" in page
    assert "joint resultant" not in page
    ok = rb.report(scene, rb.check(scene, load_factor=0.0))
    assert "joint resultant" in ok and "breached joint" not in ok


@needs_chromium
def test_3d_report_of_a_check_that_fails_runs_in_chromium(tmp_path):
    """The view with its breached joints marked runs without errors, its self-test
    too."""
    html = tmp_path / "fails.html"
    rb.report(EXAMPLES / "box_stack_3d.json", analysis="check", load_factor=2.0, path=html)
    st = page_state(html)
    assert st.errors == () and st.data.get("viewer-ready") == "1"
    ctl = page_state(html, fragment="rb-selftest")
    assert ctl.errors == () and ctl.data.get("selftest") == "done"


def test_a_report_of_a_result_without_its_force_state_says_so():
    """`rb.report(scene, rb.min_friction(scene, state=False))`: the joint table was a row
    per joint, each "joint -", under "sorted by highest friction demand"; it now says
    that the result has no force state and how to get one."""
    arch = rb.read_scene(EXAMPLES / "arch.json")
    page = rb.report(arch, rb.min_friction(arch, state=False))
    assert "No joint forces: the result was made without its force state (state=False)" \
        in page and 'id="rb-table"' not in page
    page = rb.report(arch, rb.min_friction(arch))
    assert "No joint forces" not in page and 'id="rb-table"' in page


def test_a_report_and_a_picture_take_the_limits_options(tmp_path, capsys):
    """`report` and `plot` had no --rtol and no --mechanism: a report could not give the
    answer of `load --rtol 1e-5` (its accuracy line read "requested 0.002"). Now they
    take both, and refuse them with an analysis that has no such limit."""
    arch = str(EXAMPLES / "arch.json")
    out = tmp_path / "arch.html"
    assert main(["report", arch, "--analysis", "load", "--rtol", "1e-5", "-o",
                 str(out)]) == 0
    assert "requested 1e-05" in out.read_text(encoding="utf-8")
    assert main(["plot", arch, "--analysis", "load", "--mechanism", "blend", "-o",
                 str(tmp_path / "arch.png")]) == 0
    capsys.readouterr()
    for argv, said in (
            (["report", arch, "--analysis", "check", "--rtol", "1e-5"],
             "--rtol is an option of --analysis friction or load, not check"),
            (["plot", arch, "--analysis", "friction", "--mechanism", "blend"],
             "--mechanism is an option of --analysis load, not friction"),
            (["report", arch, "--rtol", "1e-5"], "--rtol is an option of --analysis")):
        assert main(argv + ["-o", str(tmp_path / ("x" + (".png" if argv[0] == "plot"
                                                          else ".html")))]) == 2
        assert said in capsys.readouterr().err
