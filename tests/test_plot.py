"""Pictures: structure of the drawn figure (patches, arrows, markers, limits), files.

Reference values: the block on a support under a horizontal body force lambda x W
collapses at lambda* = min(f, b/h) (see docs/validation.md); with f < b/h it slides on
its bed joint, with f > b/h it tips about its toe (one hinge). Its minimum friction
at load factor lambda is f* = lambda (the bed joint carries H = lambda W, N = W).
"""

from __future__ import annotations

import math

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from conftest import EXAMPLES, make_scene, rect  # noqa: E402
from matplotlib.quiver import Quiver  # noqa: E402

import rigidblocks as rb  # noqa: E402
from rigidblocks import generators  # noqa: E402
from rigidblocks.cli.main import main  # noqa: E402
from rigidblocks.io import read_scene, write_scene  # noqa: E402
from rigidblocks.plotting import displaced_polygons  # noqa: E402


def by_gid(ax, gid):
    return [a for a in ax.get_children() if a.get_gid() == gid]


def n_paths(ax, gid):
    return sum(len(a.get_paths()) for a in by_gid(ax, gid))


def arrows(ax):
    return sum(q.N for q in ax.collections if isinstance(q, Quiver))


def assert_contains_blocks(ax, polys):
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    pts = np.concatenate(polys)
    assert x0 <= pts[:, 0].min() and pts[:, 0].max() <= x1
    assert y0 <= pts[:, 1].min() and pts[:, 1].max() <= y1


def stack(n=5, shift=0.0):
    """n unit blocks stacked on a support; a live horizontal body force."""
    blocks = [{"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True}]
    blocks += [{"id": f"s{k}", "vertices": rect(k * shift, k * 0.5, 1, 0.5)}
               for k in range(n)]
    return make_scene(blocks, unit_weight=1.0, friction=0.3, live_body_force=[1, 0],
                      units={"length": "m", "force": "kN"}, name="stack")


def grid_wall(nx, ny):
    """A running-bond wall of nx x ny bricks (2 x 1), one support below."""
    blocks = [{"id": "base", "vertices": rect(-1, -1, 2 * nx + 3, 1), "support": True}]
    for j in range(ny):
        off = 1.0 if j % 2 else 0.0
        for i in range(nx):
            blocks.append({"id": f"w{i}_{j}", "vertices": rect(off + 2 * i, j, 2, 1)})
    return make_scene(blocks, unit_weight=1.0, friction=0.7, live_body_force=[1, 0])


def teardown_function():
    plt.close("all")


def test_scene_only_counts_patches_and_limits():
    sc = stack(5, shift=0.1)
    ax = rb.plot(sc, ids=True)
    assert n_paths(ax, "rb-blocks") == 5
    assert n_paths(ax, "rb-supports") == 1
    # the block ids; the loads' arrows and values carry their own gid
    assert len([t for t in ax.texts if t.get_gid() != "rb-loads"]) == 6
    assert arrows(ax) == 0
    assert_contains_blocks(ax, [b.points for b in sc.blocks])
    assert ax.get_aspect() == 1.0


def test_min_friction_forces_thrust_and_governing(block_on_base):
    """Block on a base at lambda = 0.3: f* = 0.3 on the one bed joint, which governs."""
    sc = block_on_base(b=1.0, h=2.0, friction=0.5).with_changes(
        units=rb.scene.Units("m", "kN"))
    res = rb.min_friction(sc, load_factor=0.3)
    assert res.friction_factor == pytest.approx(0.3, rel=1e-5)
    ax = rb.plot(sc, res)
    assert arrows(ax) == 1
    assert n_paths(ax, "rb-joints") == 1
    gov = by_gid(ax, "rb-governing")
    assert len(gov) == 1 and len(gov[0].get_offsets()) == 1
    assert len(by_gid(ax, "rb-thrust")) == 1
    assert "f* = 0.3" in ax.get_title() and "16.699" in ax.get_title()  # atan 0.3 = 16.6992 deg
    # the joint is coloured at full demand |T|/(f* N) = 1
    (lc,) = by_gid(ax, "rb-joints")
    assert lc.get_array()[0] == pytest.approx(1.0, rel=1e-4)
    # the reference arrow names the force unit
    (key,) = by_gid(ax, "rb-force-key")
    assert key.text.get_text().endswith(" kN") and key.U <= res.state.joint_normal.max() * 2


def test_check_result_draws_arrows_per_loaded_joint():
    sc = stack(5)
    res = rb.check(sc, friction=0.6, load_factor=0.1)
    assert res.admissible
    ax = rb.plot(sc, res)
    assert n_paths(ax, "rb-joints") == res.contacts.n_joints == 5
    assert arrows(ax) == 5
    (line,) = by_gid(ax, "rb-thrust")
    assert len(line.get_xdata()) == 5  # a chain: one point per joint
    assert "ADMISSIBLE: it stands" in ax.get_title()


@pytest.mark.parametrize("f,mode", [(0.2, "rb-sliding"), (0.9, "rb-hinges")])
def test_mechanism_sliding_or_tipping(block_on_base, f, mode):
    """b/h = 0.5: f = 0.2 slides (lambda* = f), f = 0.9 tips (lambda* = b/h)."""
    sc = block_on_base(b=1.0, h=2.0, friction=f)
    res = rb.max_load_multiplier(sc)
    assert res.load_multiplier == pytest.approx(min(f, 0.5), rel=1e-5)
    ax = rb.plot(sc, res)
    marks = by_gid(ax, mode)
    assert len(marks) == 1 and len(marks[0].get_offsets()) == 1
    other = "rb-hinges" if mode == "rb-sliding" else "rb-sliding"
    assert not by_gid(ax, other)
    assert n_paths(ax, "rb-displaced") == 1
    assert f"{min(f, 0.5):.4g}" in ax.get_title()
    moved = by_gid(ax, "rb-displaced")[0].get_paths()[0].vertices
    assert_contains_blocks(ax, [b.points for b in sc.blocks] + [moved])
    if mode == "rb-hinges":  # tipping about the toe (1, 0): it stays put
        assert np.min(np.linalg.norm(moved - [1.0, 0.0], axis=1)) < 1e-9
        (h,) = by_gid(ax, "rb-hinges")
        assert np.allclose(h.get_offsets()[0], [1.0, 0.0])


def test_displaced_polygons_rigid_rotation():
    """A pure rotation omega about the centroid keeps the centroid and edge lengths."""
    sc = stack(1)
    vel = np.array([[0, 0, 0], [0, 0, 1.0]])
    moved = displaced_polygons(sc, vel, math.pi / 2)
    p = sc.blocks[1].points
    assert np.allclose(moved[1].mean(axis=0), p.mean(axis=0))
    # rotating (0,0) by 90 deg about (0.5, 0.25) gives (0.75, -0.25)
    assert np.allclose(moved[1][0], [0.75, -0.25])
    assert np.allclose(moved[0], sc.blocks[0].points)


def test_a_block_that_only_slides_is_drawn_translated():
    """The flat arch on piers collapses with its right pier sliding on the ground, a
    translation (its velocity's turn is 0), beside a hinge to the last voussoir, which
    turns. Closing that hinge in the picture turned the pier 2.9 deg (its base lifted
    0.27 m at one end and 0.33 m at the other): drawn tipping as it slid. A translated
    block keeps every edge's direction."""
    from rigidblocks.scene.geometry import block_weights

    scene = generators.build("flat_arch")
    res = rb.max_load_multiplier(scene)
    vel = np.asarray(res.mechanism.velocities, dtype=float)
    k = scene.index["pier_r"]
    assert abs(vel[k, 2]) <= 1e-9 * np.abs(vel).max() < np.abs(vel[k, :2]).max()
    cen = block_weights(scene)[1]
    moved = displaced_polygons(scene, vel, 0.3 / np.abs(vel).max(), cen,
                               contacts=res.contacts)
    d = moved[k] - scene.blocks[k].points
    assert np.abs(d - d[0]).max() <= 1e-9 * np.abs(d).max()


@pytest.mark.parametrize("name", ["arch", "pointed_arch", "segmental_arch"])
def test_hinges_between_moving_bodies_stay_closed_in_the_picture(name):
    """Each body of the arch's four-hinge mechanism was turned by s omega about its own
    instantaneous centre: a hinge between two moving bodies opened at second order in
    s (the semicircular arch's two upper hinges 0.026 and 0.093 m apart, a largest
    displacement of 0.4 m). Corrected, every drawn point of zero relative velocity is
    one point again (to 1e-5 of the displacement), each block stays rigid (its edges'
    lengths), and the bodies still turn the mechanism's way, by about as much."""
    from rigidblocks.scene.geometry import block_weights

    scene = read_scene(EXAMPLES / f"{name}.json")
    res = rb.max_load_multiplier(scene)
    vel = np.asarray(res.mechanism.velocities, dtype=float)
    cen = block_weights(scene)[1]
    s = 0.3 / np.abs(vel).max()
    c = res.contacts
    pj = np.repeat(np.arange(c.n_joints), np.diff(c.joint_start))
    a, b = c.pairs[pj, 0], c.pairs[pj, 1]

    def speed(i):
        d = c.points - cen[i]
        return np.stack([vel[i, 0] - vel[i, 2] * d[:, 1], vel[i, 1] + vel[i, 2] * d[:, 0]], 1)

    held = np.linalg.norm(speed(b) - speed(a), axis=1) <= 1e-9 * np.abs(vel).max() * 10

    def gaps(moved):
        out = []
        for k in np.flatnonzero(held):
            ia = np.argmin(np.linalg.norm(scene.blocks[a[k]].points - c.points[k], axis=1))
            ib = np.argmin(np.linalg.norm(scene.blocks[b[k]].points - c.points[k], axis=1))
            if max(np.linalg.norm(scene.blocks[i].points[v] - c.points[k])
                   for i, v in ((a[k], ia), (b[k], ib))) < 1e-9:  # a corner of both
                out.append(np.linalg.norm(moved[a[k]][ia] - moved[b[k]][ib]))
        return np.array(out)

    plain = displaced_polygons(scene, vel, s, cen)
    closed = displaced_polygons(scene, vel, s, cen, contacts=c)
    reach = max(np.linalg.norm(m - bl.points, axis=1).max()
                for m, bl in zip(closed, scene.blocks, strict=True))
    assert gaps(plain).max() > 0.02 * reach  # the old picture's open hinges
    assert gaps(closed).max() <= 1e-5 * reach
    for m, bl in zip(closed, scene.blocks, strict=True):
        edge = lambda q: np.linalg.norm(np.roll(q, -1, axis=0) - q, axis=1)  # noqa: E731
        assert np.allclose(edge(m), edge(bl.points), atol=1e-12)
    for m, p, bl in zip(closed, plain, scene.blocks, strict=True):
        d0, d1 = (p - bl.points).mean(axis=0), (m - bl.points).mean(axis=0)
        if np.linalg.norm(d0) > 0.1 * reach:  # a moving block: the same way, about as far
            assert d1 @ d0 > 0.8 * np.linalg.norm(d1) * np.linalg.norm(d0)
            assert 0.5 < np.linalg.norm(d1) / np.linalg.norm(d0) < 1.5


def test_large_scene_switches_to_heat_map():
    sc = grid_wall(30, 12)
    res = rb.check(sc, friction=0.7, load_factor=0.05)
    assert res.admissible and res.contacts.n_joints > rb.plotting.MAX_ARROWS
    ax = rb.plot(sc, res)
    assert arrows(ax) == 0
    assert n_paths(ax, "rb-joints") == res.contacts.n_joints
    assert n_paths(ax, "rb-blocks") == 360
    assert_contains_blocks(ax, [b.points for b in sc.blocks])
    ax2 = rb.plot(sc, res, max_arrows=10**6)
    assert 0 < arrows(ax2) <= res.contacts.n_joints


@pytest.mark.parametrize("ext", ["png", "svg", "pdf"])
def test_cli_writes_each_format(tmp_path, ext):
    path = tmp_path / "s.json"
    write_scene(stack(3), path)
    out = tmp_path / f"s.{ext}"
    assert main(["plot", str(path), "--analysis", "friction", "--load-factor", "0.1",
                 "-o", str(out)]) == 0
    assert out.stat().st_size > 100


def test_cli_load_and_bad_format(tmp_path, capsys):
    path = tmp_path / "s.json"
    write_scene(stack(3), path)
    out = tmp_path / "m.png"
    assert main(["plot", str(path), "--analysis", "load", "-o", str(out)]) == 0
    assert out.stat().st_size > 100
    assert main(["plot", str(path), "-o", str(tmp_path / "x.gif")]) == 2
    assert "gif" in capsys.readouterr().err


def example_files():
    files = sorted(EXAMPLES.glob("*.json")) if EXAMPLES.is_dir() else []
    return [pytest.param(f, id=f.name) for f in files]


@pytest.mark.parametrize("path", example_files() + [pytest.param(None, id="built-stack")])
def test_render_every_example(path, tmp_path):
    sc = stack(4, shift=0.05) if path is None else read_scene(path)
    ax = rb.plot(sc)
    if sc.dimension == 3:  # one polygon per face (tests/test_plot3d.py checks the rest)
        ax.figure.canvas.draw()
        drawn = sum(len(a.get_paths()) for a in ax.get_children()
                    if a.get_gid() in ("rb-blocks", "rb-supports"))
        assert drawn == sum(len(b.faces) for b in sc.blocks)
    else:
        assert n_paths(ax, "rb-blocks") + n_paths(ax, "rb-supports") == len(sc.blocks)
        assert_contains_blocks(ax, [b.points for b in sc.blocks])
    if sc.has_live_load:
        res = rb.max_load_multiplier(sc)
        ax = rb.plot(sc, res)
        if res.status == "collapse" and sc.dimension == 2:
            assert n_paths(ax, "rb-displaced") == int((~sc.support_mask).sum())
    out = tmp_path / "x.png"
    ax.figure.savefig(out)
    assert out.stat().st_size > 0


def test_legend_and_labels_keep_off_the_axes(tmp_path):
    """``plot flat_arch_vertical.json --analysis friction --load-factor 0``: the legend
    (one entry per mark, the force arrows included) sits below the figure and overlaps
    neither the axes nor the x label."""
    sc = read_scene(EXAMPLES / "flat_arch_vertical.json")
    res = rb.min_friction(sc, load_factor=0.0)
    ax = rb.plot(sc, res)
    fig = ax.figure
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    (leg,) = [a for a in fig.legends if a.get_gid() == "rb-legend"]
    lb = leg.get_window_extent(r)
    assert not lb.overlaps(ax.get_window_extent(r))
    assert not lb.overlaps(ax.xaxis.label.get_window_extent(r))
    labels = [t.get_text().replace("\n", " ") for t in leg.get_texts()]  # (wrapped)
    for want in ("thrust line", "governing joint", "joint force on its lower (or outer) "
                 "block", "dead load"):
        assert any(want in t for t in labels), (want, labels)
    assert not any("live load" in t for t in labels)  # not at load factor 0


def test_loads_drawn_with_values():
    sc = stack(3)
    ax = rb.plot(sc)
    texts = [t.get_text() for t in ax.texts if t.get_gid() == "rb-loads"]
    # 3 blocks of 1 x 0.5 at unit weight 1: W = 1.5 kN, live body force W x (1, 0)
    assert any("self-weight 1.5 kN" in t for t in texts)
    assert any(t.strip().startswith("live: \N{GREEK SMALL LETTER LAMDA} \N{MULTIPLICATION SIGN}"
                                    " 1.5 kN") for t in texts)
    sc2 = make_scene([{"id": "base", "vertices": rect(-1, -1, 3, 1), "support": True},
                      {"id": "B", "vertices": rect(0, 0, 1, 1)}],
                     loads=[{"block": "B", "force": [0, -10], "point": [0.5, 1.0]},
                            {"block": "B", "force": [2, 0], "point": [0, 0.5], "live": True}],
                     units={"length": "m", "force": "kN"})
    texts = [t.get_text().strip() for t in rb.plot(sc2).texts if t.get_gid() == "rb-loads"]
    assert "10 kN" in texts and "\N{GREEK SMALL LETTER LAMDA} \N{MULTIPLICATION SIGN} 2 kN" in texts


def test_inadmissible_check_says_so(block_on_base):
    sc = block_on_base(b=1.0, h=2.0, friction=0.1)
    res = rb.check(sc, load_factor=0.3)
    assert res.status == "inadmissible"
    ax = rb.plot(sc, res)
    assert "NOT ADMISSIBLE" in ax.get_title()
    (msg,) = [t for t in ax.texts if t.get_gid() == "rb-verdict"]
    assert "NOT ADMISSIBLE" in msg.get_text()


def test_an_inadmissible_check_draws_its_breached_joints_clear_of_the_loads():
    """The reference model at f = 0.3 (NOT ADMISSIBLE, its five joints breached by 5 N
    of tension or shear beyond friction at a contact, the vertical joint at both of its
    points: 10 N there, as the terminal's governing line names them): the picture drew the blocks
    alone under a box that gave the title's verdict again and hid the point load's
    value (100 N). The breached joints are drawn, each with its breach, and the box says
    what is drawn, clear of the loads' values."""
    sc = read_scene(EXAMPLES / "reference.json")
    res = rb.check(sc, friction=0.3)
    assert res.status == "inadmissible" and len(res.breaches) == 5
    ax = rb.plot(sc, res)
    (msg,) = [t for t in ax.texts if t.get_gid() == "rb-verdict"]
    assert msg.get_text().splitlines() == [
        "NOT ADMISSIBLE: no force state to draw",
        "in red: the joints breached in the state of least breach (up to 10 N)"]
    (lines,) = [a for a in ax.collections if a.get_gid() == "rb-breached"]
    c = res.contacts
    want = {tuple(np.round(np.r_[c.points[c.joint_start[k]],
                                 c.points[c.joint_start[k + 1] - 1]], 9))
            for k, _ in res.breaches}
    assert {tuple(np.round(np.ravel(s), 9)) for s in lines.get_segments()} == want
    assert [t.get_text().strip() for t in ax.texts if t.get_gid() == "rb-breached"] == \
        ["10 N"] + ["5 N"] * 4
    fig = ax.figure
    fig.canvas.draw()
    box = msg.get_bbox_patch().get_window_extent()
    for t in ax.texts:
        if t.get_gid() == "rb-loads":
            assert not box.overlaps(t.get_window_extent()), t.get_text()
    plt.close(fig)


def test_svg_keeps_text_as_text(tmp_path):
    path = tmp_path / "s.json"
    write_scene(stack(3), path)
    out = tmp_path / "s.svg"
    assert main(["plot", str(path), "--analysis", "load", "-o", str(out)]) == 0
    svg = out.read_text()
    assert "<text" in svg and "COLLAPSE: λ* = " in svg
    assert 'id="DejaVuSans' not in svg  # no glyphs stored as paths


def test_the_moving_blocks_drawn_are_those_the_answer_counts():
    """The 2D mechanism colours as moving the blocks the answer's text counts as moving
    (its rigid bodies), and the others in the colour of blocks at rest, each with its
    legend row: a block at rest was drawn in the colour the legend called "collapse
    mechanism (displaced)", and blocks moving at less than 1 % of the fastest's speed
    were drawn at rest while the text counted them as moving."""
    from matplotlib.colors import to_hex

    from rigidblocks.answer import rigid_bodies
    from rigidblocks.plotting.plot2d import FREE_COLOUR, MOVING_COLOUR

    sc = read_scene(EXAMPLES / "arch.json")  # four hinges: the springers rest
    res = rb.max_load_multiplier(sc)
    ax = rb.plot(sc, res)
    (pc,) = by_gid(ax, "rb-displaced")
    free = np.flatnonzero(~sc.support_mask)
    colours = [to_hex(c) for c in pc.get_facecolors()]
    moving = {i for body in rigid_bodies(res) for i in body}
    assert 0 < len(moving) < len(free)
    pairs = list(zip(free, colours, strict=True))
    assert {int(i) for i, c in pairs if c == MOVING_COLOUR} == moving
    assert all(c == FREE_COLOUR for i, c in pairs if int(i) not in moving)
    legends = list(ax.figure.legends) + ([ax.get_legend()] if ax.get_legend() else [])
    labels = [t.get_text() for lg in legends for t in lg.get_texts()]
    assert "moving block (displaced)" in labels
    assert "block at rest in the mechanism" in labels
    assert not any("collapse mechanism" in t for t in labels)


def test_a_thrust_line_only_through_a_chain_of_blocks():
    """The reference model's central blocks have three joints each (not a chain): it
    drew a "thrust line" from left-top to support-right across the open middle joint;
    now the resultants alone. The arch, a chain, keeps its thrust line."""
    for name, label in (("reference", "resultant on joint"), ("arch", "thrust line")):
        sc = read_scene(EXAMPLES / f"{name}.json")
        ax = rb.plot(sc, rb.min_friction(sc))
        assert [ln.get_label() for ln in by_gid(ax, "rb-thrust")] == [label]


def test_no_live_load_arrow_where_it_does_not_act():
    """A check or a friction search at load factor 0 (the arch under its self-weight)
    drew "live: lambda x 37.69 kN" over its ring, its title saying "load factor 0"; the
    live load is drawn where it acts (a check at 0.1, the collapse)."""
    sc = read_scene(EXAMPLES / "arch.json")

    def labels(res):
        return [t.get_text() for t in rb.plot(sc, res).texts if t.get_gid() == "rb-loads"
                and "live" in t.get_text()]

    assert labels(rb.check(sc)) == [] and labels(rb.min_friction(sc)) == []
    assert len(labels(rb.check(sc, load_factor=0.1))) == 1
    assert len(labels(rb.max_load_multiplier(sc))) == 1


def test_force_arrows_act_on_the_lower_block_of_each_joint():
    """The arch under its self-weight: each joint's arrow is the force on its lower block,
    so all point down the ring towards the abutments on both halves (drawn on each
    joint's second block, the arrows of one half pointed up to the crown)."""
    sc = read_scene(EXAMPLES / "arch.json")
    ax = rb.plot(sc, rb.min_friction(sc))
    (q,) = by_gid(ax, "rb-forces")
    assert len(q.V) > 10 and all(v < 0 for v in q.V)


def test_block_ids_sit_on_the_displaced_blocks_of_a_mechanism():
    """`plot --ids` of a collapse: each id at its block's displaced centroid (they sat at
    the original centroids, on the corners and edges of the moved blocks)."""
    from rigidblocks.scene.geometry import block_weights

    sc = read_scene(EXAMPLES / "wall.json")
    res = rb.max_load_multiplier(sc)
    ax = rb.plot(sc, res, ids=True)
    moved = by_gid(ax, "rb-displaced")[0].get_paths()
    free = [b for b in sc.blocks if not b.support]
    at = {t.get_text(): np.array(t.get_position()) for t in ax.texts}
    centroids = block_weights(sc)[1]
    far = 0
    for b, path in zip(free, moved, strict=True):
        poly = path.vertices[:-1] if len(path.vertices) > len(b.points) else path.vertices
        assert np.allclose(at[b.id], poly.mean(axis=0), atol=1e-8), b.id
        far += not np.allclose(at[b.id], centroids[sc.index[b.id]], atol=1e-6)
    assert far > 0  # some blocks moved


def test_two_plots_in_one_figure_keep_their_legends_off_everything():
    """Notebook 01 draws the arch's friction state and its collapse in two axes of one
    figure (no constrained layout): each legend sat right of its axes, under the
    friction state's colour bar; now below its own axes, clear of the axes, their x
    label and the colour bar."""
    sc = read_scene(EXAMPLES / "arch.json")
    fig, axes = plt.subplots(2, 1, figsize=(9, 10))
    rb.plot(sc, rb.min_friction(sc, load_factor=0.0), ax=axes[0])
    rb.plot(sc, rb.max_load_multiplier(sc), ax=axes[1])
    fig.tight_layout()
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    bars = [a for a in fig.axes if a not in axes]
    assert bars  # the friction state's colour bar
    for ax in axes:
        lb = ax.get_legend().get_window_extent(r)
        assert not lb.overlaps(ax.get_window_extent(r))
        assert not lb.overlaps(ax.xaxis.label.get_window_extent(r))
        assert not any(lb.overlaps(b.get_window_extent(r)) for b in bars)
    plt.close(fig)


def test_force_arrows_on_a_level_course_point_out_to_the_supports():
    """The flat arch's voussoirs are level: "the lower block" of a joint between two of
    them is the outer one, so each half's arrows point out to its pier (they pointed in
    at some joints and out at the next)."""
    sc = read_scene(EXAMPLES / "flat_arch_radial.json")
    ax = rb.plot(sc, rb.check(sc))
    (q,) = by_gid(ax, "rb-forces")
    assert all(u * x > 0 for x, u in zip(q.X, q.U, strict=True) if abs(x) > 1e-9)


def test_no_resultant_dot_on_an_open_joint():
    """The reference model's middle joint left-right is open (N = 0, drawn dashed as
    "open joint (no force)"): a "resultant on joint" dot sat on its middle."""
    sc = read_scene(EXAMPLES / "reference.json")
    res = rb.check(sc)
    ax = rb.plot(sc, res)
    (dots,) = by_gid(ax, "rb-thrust")
    c = res.contacts
    k = next(i for i, (a, b) in enumerate(res.contacts.block_pairs_ids())
             if {a, b} == {"left", "right"})
    mid = 0.5 * (c.points[c.joint_start[k]] + c.points[c.joint_start[k + 1] - 1])
    xy = np.column_stack([dots.get_xdata(), dots.get_ydata()])
    assert len(xy) == c.n_joints - 1
    assert not np.any(np.all(np.isclose(xy, mid), axis=1))


def test_plots_in_a_users_constrained_figure_keep_every_legend():
    """Two plots in a user's figure with constrained layout: each removed every figure
    legend, the user's and the other plot's; now each has its own below its axes, and
    the user's stays."""
    import warnings

    sc = read_scene(EXAMPLES / "arch.json")
    fig, axs = plt.subplots(1, 2, layout="constrained", figsize=(12, 7))
    mine = fig.legend(["mine"], loc="upper right")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # (constrained layout collapsed with wide legends)
        rb.plot(sc, rb.max_load_multiplier(sc), ax=axs[0])
        rb.plot(sc, rb.check(sc), ax=axs[1])
        fig.canvas.draw()
    assert fig.legends == [mine]
    r = fig.canvas.get_renderer()
    boxes = [a.get_legend().get_window_extent(r) for a in axs]
    assert not boxes[0].overlaps(boxes[1])
    for a, lb in zip(axs, boxes, strict=True):
        assert not lb.overlaps(a.get_window_extent(r))
    plt.close(fig)


def test_load_labels_lie_under_the_force_arrows_and_ids():
    """The reference model's "lambda x 50 N" boxes hid its live-load arrowheads, the
    joint forces' arrows and the ids "left" and "right": the labels now lie under them."""
    sc = read_scene(EXAMPLES / "reference.json")
    ax = rb.plot(sc, rb.check(sc), ids=True)
    labels = [t for t in ax.texts if t.get_gid() == "rb-loads" and t.get_text().strip()]
    (forces,) = by_gid(ax, "rb-forces")
    ids = [t for t in ax.texts if t.get_text() in ("left", "right")]
    assert labels and len(ids) == 2
    assert max(t.get_zorder() for t in labels) < min(forces.get_zorder(),
                                                     *(t.get_zorder() for t in ids))


def test_a_state_that_stands_is_not_drawn_as_not_admissible():
    """The Arpino gate (examples/arpino_gate.json) at f = 0.6 and lambda = 0.11871
    without dilatancy: the state reached from X0 at this load is admissible (the state
    shown) while the limit run from X0 collapses below it (NOT ADMISSIBLE). The thrust
    line's legend read "least-violation state, NOT admissible", and the title showed
    the terminal's command quotes (`load`'s)."""
    sc = read_scene(EXAMPLES / "arpino_gate.json")
    res = rb.check(sc, load_factor=0.11871, flow="non-associative")
    assert res.status == "inadmissible" and res.cause == "direct_stands"
    ax = rb.plot(sc, res)
    labels = [ln.get_label() for ln in by_gid(ax, "rb-thrust")]
    assert labels and not any("NOT admissible" in x for x in labels), labels
    # and it says the state drawn stands (beside the title's NOT ADMISSIBLE)
    assert labels == ["thrust line (state reached from X0 at this load: it stands)"], labels
    assert "load's answer" in ax.get_title() and "`" not in ax.get_title()


def test_a_bond_at_its_tensile_strength_is_drawn_as_used():
    """examples/fig4a_bonded.json at load factor 1.1: its bonded vertical joint carries
    10 N of tension, its whole strength (400 N/m^2 x 0.025 m^2), and is the joint that
    cracks first on the load path; the picture coloured it by its shear alone, dark
    green (unused). It is coloured by the larger share of shear or tension used."""
    sc = read_scene(EXAMPLES / "fig4a_bonded.json")
    res = rb.check(sc, load_factor=1.1)
    assert res.status == "admissible"
    ax = rb.plot(sc, res)
    (lc,) = by_gid(ax, "rb-joints")
    k = next(i for i, p in enumerate(res.contacts.block_pairs_ids())
             if set(p) == {"left", "right"})
    assert res.state.joint_normal[k] == pytest.approx(-10.0, rel=1e-6)
    assert lc.get_array()[k] == pytest.approx(1.0, rel=1e-6)
    assert "strength used" in lc.get_label()
    # and the title says what it was asked at (a picture of a keyed wall read
    # "COLLAPSE: lambda* = 0.6" without dilatancy and 0.8 with, nothing telling why)
    assert ax.get_title().rstrip().endswith("the live load, at f = 0.5"), ax.get_title()
    na = rb.max_load_multiplier(read_scene(EXAMPLES / "reference.json"),
                                flow="non-associative")
    title = rb.plot(read_scene(EXAMPLES / "reference.json"), na).get_title()
    assert title.replace("\n", " ").endswith("at f = 0.6, sliding without dilatancy"), title


def test_a_picture_saved_as_it_is_holds_its_title_and_legend(tmp_path):
    """`rb.plot(...)` then `ax.figure.savefig(...)` without bbox_inches: the legend's
    row of three ran past both edges of the 8 in figure ("ck", "pport", "joint force on
    its lower (or outer) block (key arrow 20 force units, be"). Long labels now wrap,
    and the title and the legend lie within the figure."""
    sc = make_scene([{"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
                     {"id": "B", "vertices": rect(0, 0, 1, 2)}],
                    unit_weight=20.0, friction=0.4, live_body_force=[1, 0])
    ax = rb.plot(sc, rb.check(sc, load_factor=0.2))
    fig = ax.figure
    fig.savefig(tmp_path / "p.png")
    r = fig.canvas.get_renderer()
    page = fig.bbox
    for art in (*fig.legends, ax.title):
        box = art.get_window_extent(r)
        assert page.x0 <= box.x0 and box.x1 <= page.x1 and box.y1 <= page.y1, art
    plt.close(fig)


def test_a_title_keeps_its_equations_on_one_line():
    """A title wrapped inside "at f = 0.6" ("... horizontal, at f" / "= 0.6")."""
    sc = make_scene([{"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
                     {"id": "B", "vertices": rect(0, 0, 1, 2)}],
                    unit_weight=20.0, friction=0.6, live_body_force=[1, 0])
    res = rb.max_load_multiplier(sc)
    for size in (4.0, 5.0, 6.0, 7.0, 8.0):
        fig = plt.figure(figsize=(size, 4))
        title = rb.plot(sc, res, ax=fig.add_subplot()).get_title()
        lines = title.splitlines()
        assert not any(ln.startswith("= ") or ln.endswith(" =") for ln in lines), title
        plt.close(fig)


def test_the_force_key_arrow_starts_at_the_structures_left_edge():
    """The key arrow was placed as if centred on its point, but labelpos "E" pivots it on
    its tip: its tail ran half its length past the structure's left edge, over the
    axes' edge and the tick labels (examples/arch.json: tail at -3.14, axes from
    -3.025)."""
    sc = read_scene(EXAMPLES / "arch.json")
    ax = rb.plot(sc, rb.check(sc, load_factor=0.0))
    (key,) = by_gid(ax, "rb-force-key")
    tail = key.X - key.U / key.Q.scale
    left = min(min(x for x, _ in b.vertices) for b in sc.blocks)
    assert tail == pytest.approx(left, abs=1e-9)
    assert ax.get_xlim()[0] < tail


def test_a_point_loads_label_is_clear_of_its_arrow():
    """The reference model's "λ x 50 N" labels sat on their own arrowheads (their boxes
    over the arrows by 27-35 x 4 px); a horizontal point load's label stands above its
    arrow's middle. The Arpino gate's live body force label ran 66 px past the axes'
    right edge; its direction now goes on a line of its own, inside the axes."""
    sc = read_scene(EXAMPLES / "reference.json")
    ax = rb.plot(sc, rb.max_load_multiplier(sc))
    ax.figure.canvas.draw()
    labels = [t for t in by_gid(ax, "rb-loads") if hasattr(t, "get_text")
              and "\N{GREEK SMALL LETTER LAMDA}" in t.get_text()
              and not hasattr(t, "arrow_patch")]
    arrows = [a.arrow_patch for a in by_gid(ax, "rb-loads")
              if getattr(a, "arrow_patch", None) is not None]
    assert len(labels) == 2 and len(arrows) == 3
    for t in labels:
        box = t.get_window_extent()
        assert not any(box.overlaps(a.get_window_extent()) for a in arrows), t.get_text()
    assert not labels[0].get_window_extent().overlaps(labels[1].get_window_extent())
    sc = read_scene(EXAMPLES / "arpino_gate.json")
    ax = rb.plot(sc, rb.max_load_multiplier(sc))
    ax.figure.canvas.draw()
    (live,) = [t for t in by_gid(ax, "rb-loads") if not hasattr(t, "arrow_patch")
               and "live" in t.get_text()]
    assert live.get_window_extent().x1 <= ax.get_window_extent().x1


def test_the_legend_leaves_the_x_label_clear_in_a_saved_picture(tmp_path):
    """examples/segmental_arch.json, a check without dilatancy (a title of four lines):
    the first layout of the figure put the x label 7 px under the legend below the axes,
    as a saved picture showed it; later layouts put it clear."""
    sc = read_scene(EXAMPLES / "segmental_arch.json")
    ax = rb.plot(sc, rb.check(sc, load_factor=0.0, flow="non-associative"))
    fig = ax.figure
    fig.savefig(tmp_path / "a.png", dpi=100, bbox_inches="tight")
    r = fig.canvas.get_renderer()
    (leg,) = fig.legends
    assert leg.get_window_extent(r).y1 < ax.xaxis.label.get_window_extent(r).y0


def test_breach_labels_lie_along_their_joints_and_apart():
    """examples/flat_arch_vertical.json without dilatancy, NOT ADMISSIBLE under its
    self-weight: its ten breached vertical joints, side by side on the soffit, had their
    labels in one row, running into one another ("6.46 4.69 2.91 1.94 kN3 3 ..."). Each
    lies along its joint, read upwards, clear of the others."""
    sc = read_scene(EXAMPLES / "flat_arch_vertical.json")
    ax = rb.plot(sc, rb.check(sc, load_factor=0.0, flow="non-associative"))
    ax.figure.canvas.draw()
    labels = [t for t in by_gid(ax, "rb-breached") if hasattr(t, "get_text")]
    assert len(labels) == 10 and {t.get_rotation() for t in labels} == {90.0}
    boxes = [t.get_window_extent() for t in labels]
    assert not any(a.overlaps(b) for i, a in enumerate(boxes) for b in boxes[i + 1:])


def test_a_checks_title_leaves_the_breachs_explanation_to_the_answer():
    """The arch's check at load factor 0.2 had a title of six lines over its picture:
    the breach's explanation in parentheses (150 characters) is the answer's text, not
    the title's; a short aside (f*'s friction angle) stays."""
    arch = read_scene(EXAMPLES / "arch.json")
    title = rb.plot(arch, rb.check(arch, load_factor=0.2)).get_title()
    assert "smallest breach of the joint laws 0.6906 kN, under the dead load" in title
    assert "asks of one contact" not in title and title.count("\n") <= 3, title
    plt.close("all")
    ref = read_scene(EXAMPLES / "reference.json")
    assert "(friction angle 26.5651" in rb.plot(ref, rb.min_friction(ref)).get_title()
    plt.close("all")


def test_a_load_label_keeps_clear_of_breach_labels_and_ids():
    """The arch's check at load factor 0.2: the live load's label lay over two breach
    labels (0.527 and 0.691 kN), one blot; it now goes to the side of its anchor that
    lies over none. Block ids (``ids=True``) count too."""
    arch = read_scene(EXAMPLES / "arch.json")
    for ids in (False, True):
        ax = rb.plot(arch, rb.check(arch, load_factor=0.2), ids=ids)
        fig = ax.figure
        fig.draw_without_rendering()
        r = fig.canvas.get_renderer()
        others = [t.get_window_extent(r) for t in ax.texts
                  if t.get_gid() in ("rb-breached", "rb-ids")]
        assert len(others) >= 6
        for t in ax.texts:
            if t.get_gid() == "rb-loads":
                bb = t.get_window_extent(r)
                assert not any(bb.overlaps(o) for o in others), t.get_text()
        plt.close("all")


def test_a_blend_of_mechanisms_is_drawn_as_one(tmp_path):
    """`plot --analysis load --mechanism blend` had the title of the one mechanism's
    picture while it drew the interior-point mix of every optimal mechanism (which the
    text calls "the blend"); the title says so now, in 2D and 3D."""
    from rigidblocks.scene.extrude import extrude

    ref = read_scene(EXAMPLES / "reference.json")
    for scene in (ref, extrude(ref)):
        said = "drawn: the blend of every optimal mechanism, not one of them"
        title = rb.plot(scene, rb.max_load_multiplier(scene, mechanism="blend")).get_title()
        assert said in " ".join(title.split()), title
        assert said not in " ".join(rb.plot(scene, rb.max_load_multiplier(scene))
                                    .get_title().split())
        plt.close("all")


def test_block_ids_and_breach_labels_lie_over_the_load_arrows():
    """The 3 x 3 wall's live arrowhead hid the id c1b2 and the self-weight's c0b1 (ids
    at zorder 6, arrows at 7); a breach label lay under the self-weight's shaft."""
    from rigidblocks.generators import build

    wall = build("wall", courses=3, blocks_per_course=3, friction=0.8)
    arch = read_scene(EXAMPLES / "arch.json")
    for ax in (rb.plot(wall, rb.max_load_multiplier(wall), ids=True),
               rb.plot(arch, rb.check(arch, load_factor=0.3))):
        arrows = [a.get_zorder() for a in ax.texts if a.get_gid() == "rb-loads"
                  and getattr(a, "arrow_patch", None) is not None]
        marks = [t.get_zorder() for t in ax.texts if t.get_gid() in ("rb-ids", "rb-breached")]
        assert arrows and marks and min(marks) > max(arrows)
        plt.close("all")


def test_the_api_plot_saves_where_it_is_told(tmp_path):
    """`rb.plot(scene, result, path=...)` raised a TypeError where `rb.report` takes
    ``path``: it saves the figure there (png, svg or pdf), and refuses another kind
    before drawing."""
    scene = rb.read_scene(EXAMPLES / "reference.json")
    out = tmp_path / "ref.svg"
    ax = rb.plot(scene, rb.min_friction(scene), path=out)
    assert ax is not None and out.read_text().lstrip().startswith("<?xml")
    with pytest.raises(rb.InputError, match=r"path .*ref.txt: must end in .png or .svg"):
        rb.plot(scene, path=tmp_path / "ref.txt")


def test_3d_load_labels_lie_on_a_light_box():
    """A 3D picture's load labels were drawn bare over the blocks' faces and their own
    arrows (the self-weight's value on its arrowhead, the live load's across the moving
    block), hard to read: each lies on a light box."""
    scene = rb.read_scene(EXAMPLES / "box_stack_3d.json")
    ax = rb.plot(scene, rb.max_load_multiplier(scene))
    labels = [t for t in ax.texts if t.get_gid() == "rb-loads"]
    assert labels and all(t.get_bbox_patch() is not None for t in labels)
    plt.close(ax.figure)
