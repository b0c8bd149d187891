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
``"rb-displaced"``, ``"rb-hinges"``, ``"rb-sliding"``) as in the plane pictures.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..scene.geometry import scene_size
from ..scene.model import Scene
from ..scene.polyhedra import outward_faces, polyhedron_volume_centroid
from .plot2d import (
    DISPLACEMENT_FRACTION,
    FREE_COLOUR,
    MAX_ARROWS,
    MIN_ARROW_FRACTION,
    SUPPORT_COLOUR,
    _title,
)

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
                       centroids: np.ndarray | None = None) -> list[np.ndarray]:
    """Block vertices moved by s times their virtual velocities (u, v, w, wx, wy, wz).

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
    for b, c, vel in zip(scene.blocks, centroids, np.asarray(velocities, float),
                         strict=True):
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
        out.append(c + (b.points - c) @ R.T + V @ (s * u))
    return out


def plot(scene: Scene, result: Any = None, ax: Any = None, *, ids: bool = False,
         max_arrows: int = MAX_ARROWS, force_scale: float | None = None,
         displacement_scale: float | None = None, title: str | None = None,
         colorbar: bool = True) -> Any:
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

    Returns:
        The matplotlib 3D Axes.
    """
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    if scene.dimension != 3:
        from ..errors import InputError

        raise InputError("plot3d draws 3D scenes only", scene.source)
    if ax is None:
        import matplotlib.pyplot as plt

        fig = plt.figure(figsize=(9, 7))
        ax = fig.add_subplot(projection="3d")
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
        pc.set_label("support" if gid == "rb-supports" else "block")
        ax.add_collection3d(pc)
    if ids:
        fs = 7 if len(scene.blocks) < 60 else 4
        for b, c in zip(scene.blocks, centroids, strict=True):
            ax.text(c[0], c[1], c[2], b.id, fontsize=fs, ha="center", va="center")
    allpts = np.concatenate([b.points for b in scene.blocks])
    lo, hi = allpts.min(axis=0), allpts.max(axis=0)
    if mech is not None:
        moved = _draw_mechanism(ax, scene, result, centroids, size, displacement_scale,
                                Poly3DCollection)
        if moved is not None:
            lo, hi = np.minimum(lo, moved.min(axis=0)), np.maximum(hi, moved.max(axis=0))
    elif getattr(result, "state", None) is not None and result.contacts.n_joints:
        _draw_forces(ax, scene, result, size, max_arrows, force_scale)
    _limits(ax, lo, hi)
    unit = scene.length_unit
    for name, setter in (("x", ax.set_xlabel), ("y", ax.set_ylabel), ("z", ax.set_zlabel)):
        setter(f"{name} [{unit}]" if unit else name)
    ax.set_title(title if title is not None else _title(scene, result))
    return ax


def _limits(ax: Any, lo: np.ndarray, hi: np.ndarray) -> None:
    """Equal scales on the three axes around the box [lo, hi]."""
    mid = 0.5 * (lo + hi)
    half = 0.55 * float((hi - lo).max())
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_zlim(mid[2] - half, mid[2] + half)
    ax.set_box_aspect((1, 1, 1))


def joint_force_vectors_3d(contacts: Any, state: Any) -> np.ndarray:
    """(m, 3) resultant on the second block of each joint: N n + sum of T_k t_k."""
    pj = contacts.point_joint
    T = np.asarray(state.shear, dtype=float).reshape(-1, 2)
    vec = state.joint_normal[:, None] * contacts.normals
    for k in range(2):
        np.add.at(vec, pj, T[:, k:k + 1] * contacts.tangents[pj, k, :])
    return vec


def _joint_centres(c: Any) -> np.ndarray:
    counts = np.diff(c.joint_start)
    return np.stack([np.bincount(c.point_joint, c.points[:, k], minlength=c.n_joints)
                     for k in range(3)], axis=1) / counts[:, None]


def _draw_forces(ax: Any, scene: Scene, result: Any, size: float, max_arrows: int,
                 force_scale: float | None) -> None:
    c = result.contacts
    st = result.state
    centres = _joint_centres(c)
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
    ax.legend(loc="upper left", fontsize=8)


def _draw_mechanism(ax: Any, scene: Scene, result: Any, centroids: np.ndarray, size: float,
                    displacement_scale: float | None, Poly3DCollection: Any
                    ) -> np.ndarray | None:
    mech = result.mechanism
    vel = np.asarray(mech.velocities, dtype=float)
    reach = 0.0
    for b, c, v in zip(scene.blocks, centroids, vel, strict=True):
        r = np.linalg.norm(b.points - c, axis=1).max()
        reach = max(reach, float(np.linalg.norm(v[:3]) + np.linalg.norm(v[3:6]) * r))
    s = displacement_scale if displacement_scale is not None else (
        DISPLACEMENT_FRACTION * size / reach if reach > 0 else 0.0)
    moved = displaced_vertices(scene, vel, s, centroids)
    free = np.flatnonzero(~scene.support_mask)
    faces = _faces(scene, free, moved)
    pc = Poly3DCollection(faces, facecolors=_shade(faces, FREE_COLOUR),
                          edgecolors=(0, 0, 0, 0.7), linewidths=0.4, zorder=3)
    pc.set_gid("rb-displaced")
    pc.set_label("collapse mechanism (displaced)")
    ax.add_collection3d(pc)
    c = result.contacts
    centres = _joint_centres(c) if c.n_joints else np.zeros((0, 3))
    for mode, gid, marker, colour, label in (("hinge", "rb-hinges", "o", "tab:red", "hinge"),
                                             ("slide", "rb-sliding", "D", "tab:blue",
                                              "sliding joint")):
        ks = np.array([k for k, md in enumerate(mech.modes)
                       if (md == mode if mode == "hinge" else md.startswith(mode))],
                      dtype=int)
        if len(ks) and mode == "hinge":
            # the contact points that stay closed: the hinge line (or point)
            op = np.asarray(mech.opening, dtype=float)
            tol = 1e-6 * max(float(np.abs(op).max(initial=0.0)), 1e-300)
            on = np.isin(c.point_joint, ks) & (op <= tol)
            p = c.points[on] if on.any() else centres[ks]
        elif len(ks):
            p = centres[ks]
        if len(ks):
            sc = ax.scatter(p[:, 0], p[:, 1], p[:, 2], s=30, c=colour, marker=marker,
                            label=label, zorder=5, depthshade=False)
            sc.set_gid(gid)
    ax.legend(loc="upper left", fontsize=8)
    return np.concatenate([moved[i] for i in free]) if len(free) else None


__all__ = ["displaced_vertices", "joint_force_vectors_3d", "plot"]
