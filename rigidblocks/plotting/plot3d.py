"""Pictures of 3D scenes and results with matplotlib (mplot3d).

:func:`plot` draws every face of every block as a polygon (free blocks and supports in
different colours, each face shaded by the angle between its outward normal and a
light direction) and, given a result:

* after :func:`~rigidblocks.check` or :func:`~rigidblocks.min_friction` (a result whose
  ``state`` is a :class:`~rigidblocks.results.ForceState`): the resultant of each
  joint, N n + T (the normal force along the joint's normal and the shear resultant
  in its plane, acting on the joint's second block), as an arrow at the joint's centre
  of pressure, scaled so that the largest is 12 % of the scene's size; the governing
  joints are circled;
* after :func:`~rigidblocks.max_load_multiplier`: the collapse mechanism, each free
  block moved by the rigid motion of its virtual velocities (u, v, w) of the centroid c
  and (wx, wy, wz) rotation: p' = c + R (p - c) + V s u with R = exp(s [w]x) and V the
  matching factor of the exponential of a twist (:func:`displaced_vertices`), s chosen
  so that the largest displacement is about 10 % of the scene's size; the original
  blocks are drawn faded, hinges and sliding joints are marked.

Above ``max_arrows`` joints no arrows are drawn. Every artist carries a ``gid``
(``"rb-blocks"``, ``"rb-supports"``, ``"rb-forces"``, ``"rb-governing"``,
``"rb-displaced"``, ``"rb-hinges"``, ``"rb-sliding"``, ``"rb-open"``, ``"rb-loads"``,
``"rb-legend"``) as in the plane pictures.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..answer import block_reach
from ..scene.geometry import scene_size
from ..scene.model import Scene
from ..scene.polyhedra import outward_faces, polyhedron_volume_centroid
from .marks import (
    DEAD_COLOUR,
    HINGE_COLOUR,
    LIVE_COLOUR,
    MOST_MARKED_3D,
    OPEN_COLOUR,
    SLIDE_COLOUR,
    line_handle,
    live_applies,
    load_legend,
    load_marks,
    marked_joints,
    mechanism_colours,
    new_axes,
    place_legend,
)
from .plot2d import (
    DISPLACEMENT_FRACTION,
    FREE_COLOUR,
    MAX_ARROWS,
    MIN_ARROW_FRACTION,
    SUPPORT_COLOUR,
    _title,
)

#: a hinge's contact point is closed when its opening is below this fraction of the
#: joint's largest opening (above the joint's smallest)
HINGE_CLOSED = 1e-3
#: direction the light comes from (towards the viewer, above)
LIGHT = np.array([-0.4, -0.6, 0.7]) / np.linalg.norm([-0.4, -0.6, 0.7])


def _faces(scene: Scene, idx: np.ndarray, verts: list[np.ndarray] | None = None
           ) -> list[np.ndarray]:
    out = []
    for i in idx:
        b = scene.blocks[i]
        pts = b.points if verts is None else verts[i]
        out.extend(pts[f] for f in outward_faces(b))
    return out


def _shade(faces: list[np.ndarray], colour: str) -> np.ndarray:
    """RGBA per face: the base colour dimmed by Lambert's cosine law (ambient 0.45)."""
    from matplotlib.colors import to_rgba

    base = np.array(to_rgba(colour))
    out = np.empty((len(faces), 4))
    for k, p in enumerate(faces):
        n = np.cross(p[1] - p[0], p[2] - p[0])
        nn = np.linalg.norm(n)
        lit = max(float(n @ LIGHT) / nn, 0.0) if nn > 0 else 0.0
        out[k, :3] = base[:3] * (0.45 + 0.55 * lit)
        out[k, 3] = base[3]
    return out


def _skew(w: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def displaced_vertices(scene: Scene, velocities: np.ndarray, s: float,
                       centroids: np.ndarray | None = None,
                       points: list[np.ndarray] | None = None) -> list[np.ndarray]:
    """Block vertices (or other ``points`` of each block) moved by s times their virtual
    velocities (u, v, w, wx, wy, wz).

    The velocity field of block b is u + omega x (p - c), c its centroid; the finite
    motion is its exponential: p' = c + R (p - c) + V s u, with K = s [omega]x,
    theta = |s omega|, R = I + sin(theta)/theta K + (1 - cos(theta))/theta^2 K^2 and
    V = I + (1 - cos(theta))/theta^2 K + (theta - sin(theta))/theta^3 K^2. A rotation
    about a fixed axis stays that rotation, so hinges stay closed in the picture; to
    first order p' = p + s (u + omega x (p - c)).
    """
    if centroids is None:
        centroids = np.array([polyhedron_volume_centroid(b)[1] for b in scene.blocks])
    out = []
    for k, (b, c, vel) in enumerate(zip(scene.blocks, centroids,
                                        np.asarray(velocities, float), strict=True)):
        pts = b.points if points is None else points[k]
        u, w = vel[:3], vel[3:6]
        K = _skew(s * w)
        th = float(np.linalg.norm(s * w))
        if th < 1e-9:
            R = np.eye(3) + K
            V = np.eye(3) + 0.5 * K
        else:
            R = np.eye(3) + math.sin(th) / th * K + (1 - math.cos(th)) / th**2 * K @ K
            V = np.eye(3) + (1 - math.cos(th)) / th**2 * K + \
                (th - math.sin(th)) / th**3 * K @ K
        out.append(c + (pts - c) @ R.T + V @ (s * u))
    return out


def plot(scene: Scene, result: Any = None, ax: Any = None, *, ids: bool = False,
         max_arrows: int = MAX_ARROWS, force_scale: float | None = None,
         displacement_scale: float | None = None, title: str | None = None,
         colorbar: bool = True, loads: bool = True) -> Any:
    """Draw a 3D scene, and a result of an analysis on it.

    Args:
        scene: a 3D scene.
        result: None, or the result of ``check``, ``min_friction`` (with a force
            state) or ``max_load_multiplier`` on this scene.
        ax: a matplotlib 3D Axes (``projection="3d"``) to draw on (default: a new
            figure).
        ids: write block ids at the centroids.
        max_arrows: above this many joints no force arrows are drawn.
        force_scale: drawing length per force unit (default: the largest resultant is
            12 % of the scene's size).
        displacement_scale: factor s on the mechanism's virtual velocities (default:
            the largest displacement is 10 % of the scene's size).
        title: overrides the title made from the result.
        colorbar: accepted for the plane pictures' signature; 3D pictures have none.
        loads: draw the self-weight, the live load's direction and the point loads.

    Returns:
        The matplotlib 3D Axes.
    """
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    if scene.dimension != 3:
        from ..errors import InputError

        raise InputError("plot3d draws 3D scenes only", scene.source)
    if ax is None:
        ax = new_axes(3, len(scene.blocks))
    # collections are drawn in a fixed order (supports, blocks, displaced blocks,
    # markers): mplot3d sorts polygons by depth within a collection only, and a support
    # slab's large faces would otherwise hide what stands on it
    ax.computed_zorder = False
    size = scene_size(scene)
    centroids = np.array([polyhedron_volume_centroid(b)[1] for b in scene.blocks])
    sup = scene.support_mask
    mech = getattr(result, "mechanism", None)
    lw = 0.4 if len(scene.blocks) < 500 else 0.1
    for mask, colour, gid in ((~sup, FREE_COLOUR, "rb-blocks"),
                              (sup, SUPPORT_COLOUR, "rb-supports")):
        faces = _faces(scene, np.flatnonzero(mask))
        if not faces:
            continue
        fc = _shade(faces, colour)
        if mech is not None and gid == "rb-blocks":
            fc[:, 3] = 0.15
        pc = Poly3DCollection(faces, facecolors=fc, edgecolors=(0, 0, 0, 0.6),
                              linewidths=lw, zorder=1 if gid == "rb-supports" else 2)
        pc.set_gid(gid)
        pc.set_label("support" if gid == "rb-supports" else
                     "block (original position)" if mech is not None else "block")
        ax.add_collection3d(pc)
    allpts = np.concatenate([b.points for b in scene.blocks])
    lo, hi = allpts.min(axis=0), allpts.max(axis=0)
    extra: list[Any] = []
    if loads:
        lo, hi = _draw_loads(ax, scene, lo, hi, extra, live_applies(result))
    label_at = centroids
    if mech is not None:
        moved, label_at = _draw_mechanism(ax, scene, result, centroids, size,
                                          displacement_scale, Poly3DCollection, extra)
        if moved is not None:
            lo, hi = np.minimum(lo, moved.min(axis=0)), np.maximum(hi, moved.max(axis=0))
    elif getattr(result, "state", None) is not None and result.contacts.n_joints:
        _draw_forces(ax, scene, result, size, max_arrows, force_scale)
    elif result is not None and getattr(result, "status", None) is not None:
        from .plot2d import _no_state

        _no_state(ax, result, scene.force_unit)
    if ids:  # on the blocks as drawn (displaced in a mechanism)
        fs = 7 if len(scene.blocks) < 60 else 4
        for b, c in zip(scene.blocks, label_at, strict=True):
            ax.text(c[0], c[1], c[2], b.id, fontsize=fs, ha="center", va="center")
    place_legend(ax, extra)
    _limits(ax, lo, hi)
    unit = scene.length_unit
    for name, setter in (("x", ax.set_xlabel), ("y", ax.set_ylabel), ("z", ax.set_zlabel)):
        setter(f"{name} [{unit}]" if unit else name)
    ax.set_title(title if title is not None else _title(scene, result, ax))
    return ax


def _limits(ax: Any, lo: np.ndarray, hi: np.ndarray) -> None:
    """Equal scales on the three axes around the box [lo, hi], each axis as long as the
    box is along it (at least a fifth of its longest side): a cube around an arch 5.5 m
    wide and 1 m deep left most of the picture empty."""
    mid = 0.5 * (lo + hi)
    half = 0.55 * np.maximum(hi - lo, 0.2 * float((hi - lo).max()))
    ax.set_xlim(mid[0] - half[0], mid[0] + half[0])
    ax.set_ylim(mid[1] - half[1], mid[1] + half[1])
    ax.set_zlim(mid[2] - half[2], mid[2] + half[2])
    ax.set_box_aspect(tuple(2 * half))
    from matplotlib.ticker import MaxNLocator

    # ticks as many as an axis's length holds (a short one's labels ran together)
    for axis, h in zip((ax.xaxis, ax.yaxis, ax.zaxis), half, strict=True):
        axis.set_major_locator(MaxNLocator(max(2, round(7 * h / half.max()))))


def joint_force_vectors_3d(contacts: Any, state: Any) -> np.ndarray:
    """(m, 3) resultant on the second block of each joint: N n + sum of T_k t_k."""
    pj = contacts.point_joint
    T = np.asarray(state.shear, dtype=float).reshape(-1, 2)
    vec = state.joint_normal[:, None] * contacts.normals
    for k in range(2):
        np.add.at(vec, pj, T[:, k:k + 1] * contacts.tangents[pj, k, :])
    return vec


def _draw_forces(ax: Any, scene: Scene, result: Any, size: float, max_arrows: int,
                 force_scale: float | None) -> None:
    c = result.contacts
    st = result.state
    centres = c.joint_centres
    pts = np.where(np.all(np.isfinite(st.thrust_points), axis=1)[:, None]
                   & (st.joint_normal[:, None] > 0), st.thrust_points, centres)
    gov = np.asarray(getattr(result, "governing", ()), dtype=int)
    if len(gov):
        g = centres[gov]
        sc = ax.scatter(g[:, 0], g[:, 1], g[:, 2], s=80, facecolors="none",
                        edgecolors="k", linewidths=1.5, label="governing joint", zorder=5,
                        depthshade=False)
        sc.set_gid("rb-governing")
    if c.n_joints > max_arrows:
        return
    vec = joint_force_vectors_3d(c, st)
    mag = np.linalg.norm(vec, axis=1)
    top = mag.max(initial=0.0)
    if top <= 0:
        return
    scale = force_scale if force_scale is not None else 0.12 * size / top
    keep = mag >= MIN_ARROW_FRACTION * top
    p, v = pts[keep], vec[keep] * scale
    q = ax.quiver(p[:, 0], p[:, 1], p[:, 2], v[:, 0], v[:, 1], v[:, 2], color="tab:blue",
                  linewidths=1.2, arrow_length_ratio=0.2, zorder=4,
                  label=f"joint resultants (largest {top:.3g} {scene.force_unit})")
    q.set_gid("rb-forces")


def _draw_loads(ax: Any, scene: Scene, lo: np.ndarray, hi: np.ndarray,
                extra: list[Any], live: bool = True) -> tuple[np.ndarray, np.ndarray]:
    kinds = set()
    for m in load_marks(scene, live):
        colour = LIVE_COLOUR if m.live else DEAD_COLOUR
        d = m.tip - m.tail
        q = ax.quiver(*m.tail, *d, color=colour, linewidths=2.0, arrow_length_ratio=0.15,
                      zorder=7)
        q.set_gid("rb-loads")
        at = m.tip if m.kind != "point load" else m.tail
        # (on two lines: "live: λ × 40 kN (weight × (0.866, 0.5, 0))" ran over the z
        # axis's label)
        # on a light box: drawn over a block's faces or an arrow ("self-weight 50 kN"
        # on its own arrowhead, the live load's label across the moving block) it was
        # hard to read
        t = ax.text(*at, " " + m.label.replace(" (", "\n (", 1), color=colour, fontsize=8,
                    zorder=7, bbox=dict(facecolor="white", alpha=0.75, edgecolor="none",
                                        pad=1.0))
        t.set_gid("rb-loads")
        kinds.add(m.live)
        lo = np.minimum(lo, np.minimum(m.tail, m.tip))
        hi = np.maximum(hi, np.maximum(m.tail, m.tip))
    load_legend(kinds, extra)
    return lo, hi


def mechanism_joints(scene: Scene, result: Any
                     ) -> dict[str, tuple[list[np.ndarray], list[int]]]:
    """The joints a 3D mechanism picture marks, as line segments ((2, 3) arrays) with the
    block each segment moves with (the joint's first block):

    * "hinge": the hinge line of each hinging joint, between the two farthest contact
      points that stay closed (a single closed point gives a zero-length segment);
    * "slide" and "open": the outline of each sliding or opening joint's polygon.

    Joints whose motion is below 5 % of the largest are left out, and all but the
    MOST_MARKED_3D fastest (:func:`rigidblocks.plotting.marks.marked_joints`).
    """
    c = result.contacts
    marks = marked_joints(result, most=MOST_MARKED_3D)
    op = np.asarray(result.mechanism.opening, dtype=float)
    out: dict[str, tuple[list[np.ndarray], list[int]]] = {}
    for name in ("hinge", "slide", "open"):
        segs: list[np.ndarray] = []
        owners: list[int] = []
        for k in marks[name]:
            a, b = c.joint_start[k], c.joint_start[k + 1]
            p = c.points[a:b]
            owner = int(c.pairs[k, 0])
            if name == "hinge":
                # closed: the points whose opening is round-off next to the joint's
                # largest (the interior-point mechanism leaves ~1e-7 of it)
                o = op[a:b]
                closed = p[o <= o.min() + HINGE_CLOSED * (o.max() - o.min())]
                if not len(closed):
                    closed = p[[int(np.argmin(op[a:b]))]]
                d = np.linalg.norm(closed[:, None] - closed[None], axis=2)
                i, j = np.unravel_index(int(np.argmax(d)), d.shape)
                segs.append(np.stack([closed[i], closed[j]]))
                owners.append(owner)
            else:
                for i in range(len(p)):
                    segs.append(np.stack([p[i], p[(i + 1) % len(p)]]))
                    owners.append(owner)
        out[name] = (segs, owners)
    return out


def _draw_mechanism(ax: Any, scene: Scene, result: Any, centroids: np.ndarray, size: float,
                    displacement_scale: float | None, Poly3DCollection: Any,
                    extra: list[Any]) -> tuple[np.ndarray | None, np.ndarray]:
    """The displaced blocks, their joints' marks and the legend rows: the displaced
    vertices of the free blocks (None without any) and every block's displaced
    centroid (where its id goes)."""
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    vel = np.asarray(result.mechanism.velocities, dtype=float)
    reach = block_reach(scene, vel, centroids)
    top = float(reach.max(initial=0.0))
    s = displacement_scale if displacement_scale is not None else (
        DISPLACEMENT_FRACTION * size / top if top > 0 else 0.0)
    moved = displaced_vertices(scene, vel, s, centroids)
    free = np.flatnonzero(~scene.support_mask)
    colour_of, legend = mechanism_colours(scene, result, centroids)
    faces, colours = [], []
    for i in free:
        fs = _faces(scene, np.array([i]), moved)
        faces.extend(fs)
        colours.extend([colour_of[i] or FREE_COLOUR] * len(fs))
    fc = np.concatenate([_shade([f], col) for f, col in zip(faces, colours, strict=True)]) \
        if faces else np.zeros((0, 4))
    pc = Poly3DCollection(faces, facecolors=fc, edgecolors=(0, 0, 0, 0.7), linewidths=0.4,
                          zorder=3)
    pc.set_gid("rb-displaced")
    # the moving blocks' colours have their own legend rows (a swatch of the
    # collection would show the colour of its first face only)
    pc.set_label("_collapse mechanism (displaced)" if legend else
                 "collapse mechanism (displaced)")
    ax.add_collection3d(pc)
    if legend:
        from matplotlib.patches import Patch

        extra.extend(Patch(facecolor=col, edgecolor="k", label=lab) for col, lab in legend)
        if any(colour_of[i] is None for i in free):  # as the 2D picture's
            extra.append(Patch(facecolor=FREE_COLOUR, edgecolor="k",
                               label="block at rest in the mechanism"))
    styles = {"hinge": (HINGE_COLOUR, 3.0, "hinge line", "rb-hinges"),
              "slide": (SLIDE_COLOUR, 1.8, "sliding joint (outline)", "rb-sliding"),
              "open": (OPEN_COLOUR, 1.8, "opening joint (outline)", "rb-open")}
    for name, (segs, owners) in mechanism_joints(scene, result).items():
        if not segs:
            continue
        colour, lw, label, gid = styles[name]
        # the marks move with their joint's first block
        segs_m = [_move(scene, moved, o, sg) for sg, o in zip(segs, owners, strict=True)]
        lc = Line3DCollection(segs_m, colors=colour, linewidths=lw, zorder=6, label=label)
        lc.set_gid(gid)
        ax.add_collection3d(lc)
    left = marked_joints(result, most=MOST_MARKED_3D)["left_out"]
    if len(left):
        extra.append(line_handle("none", f"{len(left)} slower joint(s) not marked (the "
                                 f"{MOST_MARKED_3D} fastest are, down to 5 % of the "
                                 "largest)"))
    at = displaced_vertices(scene, vel, s, centroids, [c[None, :] for c in centroids])
    return ((np.concatenate([moved[i] for i in free]) if len(free) else None),
            np.array([a[0] for a in at]))


def _move(scene: Scene, moved: list[np.ndarray], owner: int, seg: np.ndarray) -> np.ndarray:
    """Carry points of block ``owner`` with its rigid motion (least squares on its
    vertices: exact for a rigid motion)."""
    p0 = scene.blocks[owner].points
    p1 = moved[owner]
    c0, c1 = p0.mean(axis=0), p1.mean(axis=0)
    u, _, vt = np.linalg.svd((p0 - c0).T @ (p1 - c1))
    d = np.sign(np.linalg.det(vt.T @ u.T))
    R = vt.T @ np.diag([1.0, 1.0, d]) @ u.T
    return c1 + (seg - c0) @ R.T


__all__ = ["displaced_vertices", "joint_force_vectors_3d", "mechanism_joints", "plot"]
