"""3D pictures (rigidblocks.plotting.plot3d): faces, force arrows, mechanism, files.

Reference values: a box b = 1 wide, h = 2 high (box_stack with one box) under a
horizontal body force lambda W tips about its toe edge at lambda* = b / h = 0.5 (f = 0.6
> 0.5); the bed joint is then a hinge along the edge x = b/2, z = 0 (box_stack
docstring; docs/validation.md).
"""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from conftest import EXAMPLES  # noqa: E402

import rigidblocks as rb  # noqa: E402
from rigidblocks.cli.main import main  # noqa: E402
from rigidblocks.generators.solids import box_stack, corbel_dome  # noqa: E402
from rigidblocks.io import read_scene, write_scene  # noqa: E402
from rigidblocks.plotting.plot3d import displaced_vertices  # noqa: E402


def by_gid(ax, gid):
    return [a for a in ax.get_children() if a.get_gid() == gid]


def n_polys(ax, gid):
    ax.figure.canvas.draw()
    return sum(len(a.get_paths()) for a in by_gid(ax, gid))


@pytest.fixture(autouse=True)
def _close():
    yield
    plt.close("all")


def n_faces(scene, support):
    return sum(len(b.faces) for b in scene.blocks if b.support == support)


def test_scene_faces_are_drawn():
    s = corbel_dome(rings=2, blocks_per_ring=6)
    ax = rb.plot(s)
    assert ax.name == "3d"
    assert n_polys(ax, "rb-blocks") == n_faces(s, False) == 2 * 6 * 6 + 14
    assert n_polys(ax, "rb-supports") == n_faces(s, True) == 6
    assert not by_gid(ax, "rb-forces") and not by_gid(ax, "rb-displaced")


def test_force_arrows_one_per_loaded_joint():
    """Two boxes on a slab under self-weight: each bed joint carries the weight above
    it (2 W and W), so both get an arrow, pointing up (the force on the upper block)."""
    s = box_stack(boxes=2, width=1.0, height=0.5)
    res = rb.check(s, load_factor=0.0)
    ax = rb.plot(s, res)
    (q,) = by_gid(ax, "rb-forces")
    segs = np.asarray(q._segments3d)  # shafts first, each (head, tail)
    assert len(segs) == 2 * 3
    shafts = segs[:2]
    d = shafts[:, 0] - shafts[:, 1]
    # tails at the joints' centres of pressure, the box centres' verticals
    np.testing.assert_allclose(np.sort(shafts[:, 1, 2]), [0.0, 0.5], atol=1e-9)
    np.testing.assert_allclose(shafts[:, 1, :2], 0.0, atol=1e-9)
    assert np.all(d[:, 2] > 0) and np.allclose(d[:, :2], 0, atol=1e-9)
    # arrow lengths in proportion to the joint forces 2 W : W
    lengths = sorted(np.linalg.norm(d, axis=1))
    assert lengths[1] == pytest.approx(2 * lengths[0], rel=1e-6)


def test_mechanism_displaced_blocks_and_hinge_line():
    s = box_stack(boxes=1, width=1.0, length=1.0, height=2.0, friction=0.6)
    res = rb.max_load_multiplier(s)
    assert res.load_multiplier == pytest.approx(0.5, rel=1e-6)
    ax = rb.plot(s, res)
    assert n_polys(ax, "rb-displaced") == 6
    (h,) = by_gid(ax, "rb-hinges")
    (seg,) = np.asarray(h._segments3d)
    # one hinge line, along the toe edge x = 0.5, z = 0, the bed's full length
    np.testing.assert_allclose(seg[:, [0, 2]], [[0.5, 0.0], [0.5, 0.0]], atol=1e-9)
    assert abs(seg[1, 1] - seg[0, 1]) == pytest.approx(1.0)
    # only the joint that moves is marked, and nothing slides
    assert not by_gid(ax, "rb-sliding") and not by_gid(ax, "rb-open")


def test_displaced_vertices_rotate_about_the_hinge():
    """Rotation rate omega = (0, w, 0) about the toe line a = (0.5, y, 0) of the box
    centred at c = (0, 0, 1): the centroid moves at u = omega x (c - a) = (w, 0, w/2)
    and the top corner (-0.5, y, 2) at omega x (-1, 0, 2) = (2w, 0, w): towards +x.
    The finite motion is the rotation about the toe line: the toe stays, distances
    are kept."""
    s = box_stack(boxes=1, width=1.0, length=1.0, height=2.0)
    w = 0.3
    omega = np.array([0.0, w, 0.0])
    c = np.array([0.0, 0.0, 1.0])
    u = np.cross(omega, c - np.array([0.5, 0.0, 0.0]))
    vel = np.zeros((2, 6))
    vel[1] = [*u, *omega]
    moved = displaced_vertices(s, vel, 1.0)[1]
    pts = s.blocks[1].points
    toe = np.isclose(pts[:, 0], 0.5) & np.isclose(pts[:, 2], 0.0)
    np.testing.assert_allclose(moved[toe], pts[toe], atol=1e-12)
    d0 = np.linalg.norm(pts[:, None] - pts[None], axis=2)
    d1 = np.linalg.norm(moved[:, None] - moved[None], axis=2)
    np.testing.assert_allclose(d1, d0, atol=1e-12)
    top = pts[:, 2] == 2.0
    assert np.all(moved[top, 0] > pts[top, 0])


def test_png_written_by_api_and_cli(tmp_path, capsys):
    s = box_stack(boxes=2)
    path = tmp_path / "stack.json"
    write_scene(s, path)
    ax = rb.plot(s, rb.max_load_multiplier(s))
    out = tmp_path / "api.png"
    from rigidblocks.plotting import save_figure

    save_figure(ax, str(out))
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    cli_out = tmp_path / "cli.png"
    assert main(["plot", str(path), "--analysis", "load", "-o", str(cli_out)]) == 0
    assert cli_out.stat().st_size > 1000
    assert "wrote" in capsys.readouterr().out


def test_a_3d_check_that_fails_is_drawn_and_says_so(tmp_path, capsys):
    """A 3D check without an admissible state is drawn with its verdict on the axes, as
    in 2D (it ended in a traceback: 3D axes take that text as text2D); on the command
    line too, a stack pushed at 5 times its weight. A joint's breach is its points'
    summed: 22 kN at each of the four corners, 88 kN (the largest point's was given)."""
    s = box_stack(boxes=2)
    res = rb.check(s, load_factor=5.0)
    assert res.status == "inadmissible"
    ax = rb.plot(s, res)
    (msg,) = [t for t in ax.texts if t.get_gid() == "rb-verdict"]
    assert msg.get_text().splitlines() == [
        "NOT ADMISSIBLE: no force state to draw",
        "in red: the joints breached in the state of least breach (up to 88 kN)"]
    # the joints breached, at their centres, each with its breach
    marks = [a for a in ax.collections if a.get_gid() == "rb-breached"]
    labels = [t.get_text().strip() for t in ax.texts if t.get_gid() == "rb-breached"]
    assert len(marks) == 1 and len(marks[0].get_offsets()) == len(res.breaches) == 2
    assert labels == [f"{v:.3g} kN" for _, v in res.breaches]
    path = tmp_path / "stack.json"
    write_scene(s, path)
    out = tmp_path / "check.png"
    assert main(["plot", str(path), "--analysis", "check", "--load-factor", "5",
                 "-o", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    plt.close("all")


def test_a_mechanism_off_its_optimal_face_is_said_so_in_the_title():
    """The corbel dome's mechanism drawn balances at 0.6, above lambda* = 0.599985 (see
    test_mechanism3d.py): the answer says it is no collapse mechanism, and the picture's
    title, which read COLLAPSE alone above it, says so too; a mechanism on its face
    (the box stack's) is not so marked."""
    sc = read_scene(EXAMPLES / "corbel_dome.json")
    ax = rb.plot(sc, rb.max_load_multiplier(sc))
    assert "the mechanism drawn is the nearest that can be drawn, not a collapse " \
        "mechanism" in ax.get_title().replace("\n", " ")
    s = box_stack(boxes=2)
    assert "nearest that can be drawn" not in rb.plot(s, rb.max_load_multiplier(s)).get_title()
    plt.close("all")


def test_a_3d_mechanism_names_the_blocks_at_rest_in_its_legend():
    """The box stack (examples/box_stack_3d.json) tips above its first box, which stays:
    the 3D legend now has the 2D picture's row for blocks at rest (it had none); the
    wall3d, which moves as one body, has none."""
    from rigidblocks.generators import build

    def labels(sc):
        ax = rb.plot(sc, rb.max_load_multiplier(sc))
        return [t.get_text() for lg in ax.figure.legends for t in lg.get_texts()]

    assert "block at rest in the mechanism" in labels(
        read_scene(EXAMPLES / "box_stack_3d.json"))
    assert "block at rest in the mechanism" not in labels(build("wall3d"))


def test_3d_block_ids_sit_on_the_displaced_blocks_of_a_mechanism():
    """`plot --ids` of a 3D collapse: the ids sat at the original centroids, inside the
    drawn (displaced) blocks, where they could not be seen; now at the displaced ones."""
    from rigidblocks.answer import rigid_bodies
    from rigidblocks.scene.polyhedra import polyhedron_volume_centroid

    sc = box_stack(boxes=3, offset=0.2, friction=0.8)
    res = rb.max_load_multiplier(sc)
    ax = rb.plot(sc, res, ids=True)
    at = {t.get_text(): np.array(t.get_position_3d()) for t in ax.texts}
    moving = {sc.blocks[i].id for body in rigid_bodies(res) for i in body}
    assert moving
    for b in sc.blocks:
        still = np.allclose(at[b.id], polyhedron_volume_centroid(b)[1])
        assert still == (b.id not in moving), b.id


def test_a_3d_picture_is_saved_without_a_layout_warning(tmp_path, recwarn):
    """`rigidblocks plot` of a 4 x 4 wall3d in plane (its legend below the 3D Axes)
    printed matplotlib's "constrained_layout not applied" warning, with this package's
    file path, to the terminal; the picture is framed all the same."""
    from rigidblocks.generators import build

    scene = build("wall3d", courses=4, blocks_per_course=4, load_direction="in_plane")
    path = tmp_path / "wall3d.json"
    write_scene(scene, path)
    assert main(["plot", str(path), "--analysis", "load", "-o", str(tmp_path / "w.png")]) == 0
    assert (tmp_path / "w.png").stat().st_size > 10_000
    assert not [w for w in recwarn if "constrained_layout" in str(w.message)]


def test_the_live_loads_label_is_on_two_lines():
    """examples/box_stack_3d.json: "live: λ × 40 kN (weight × (0.866, 0.5, 0))" on one
    line ran over the z axis's label; its direction goes on a line of its own."""
    s = rb.read_scene(EXAMPLES / "box_stack_3d.json")
    ax = rb.plot(s, rb.max_load_multiplier(s, state=False))
    (live,) = [t.get_text() for t in ax.texts
               if t.get_gid() == "rb-loads" and "live" in t.get_text()]
    assert live == " live: \N{GREEK SMALL LETTER LAMDA} \N{MULTIPLICATION SIGN} 40 kN\n " \
        "(weight \N{MULTIPLICATION SIGN} (0.866, 0.5, 0))"
    plt.close("all")


def test_a_3d_picture_is_as_deep_as_its_scene():
    """The extruded semicircular arch (5.5 m wide, 1 m deep, 3.65 m high with its
    abutments) was drawn in a cube 5.5 m along every axis: most of the picture empty.
    Each axis is now as long as the scene along it (equal scales: the box's sides in the
    ratio of the axes' ranges), with no more ticks than its length holds."""
    from rigidblocks.scene.extrude import extrude

    arch = extrude(read_scene(EXAMPLES / "arch.json"))
    ax = rb.plot(arch)
    spans = np.array([np.ptp(ax.get_xlim()), np.ptp(ax.get_ylim()), np.ptp(ax.get_zlim())])
    box = np.asarray(ax.get_box_aspect(), dtype=float)
    assert np.allclose(box / box.max(), spans / spans.max())  # equal scales
    assert spans[1] < 0.4 * spans[0] and spans[2] < 0.8 * spans[0]
    assert len([t for t in ax.get_yticks() if ax.get_ylim()[0] <= t <= ax.get_ylim()[1]]) <= 3
