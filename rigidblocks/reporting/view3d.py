"""The data of the interactive 3D view, as compact typed arrays for the browser.

Everything the viewer draws is merged into a handful of buffers, whatever the size of
the scene: one indexed triangle mesh for all blocks (flat-shaded in the fragment
shader, so vertices are shared between faces), one set of line segments for their
edges, one for the mechanism's hinge lines and the outlines of the joints that open or
slide, one for the force arrows' shafts and one instanced cone for their heads. A
5,000-block wall is then six draw calls. The mechanism is animated in the browser by
moving each block's vertices with the rigid motion of its virtual velocities (the same
finite motion as :func:`rigidblocks.plotting.plot3d.displaced_vertices`).

Arrays travel as base64 of little-endian float32 / uint32 buffers.
"""

from __future__ import annotations

import base64
from typing import Any

import numpy as np

from ..answer import block_reach
from ..plotting.marks import (
    MOST_MARKED_3D,
    live_applies,
    load_marks,
    marked_joints,
    mechanism_colours,
    scene_weights,
)
from ..plotting.plot2d import DISPLACEMENT_FRACTION, MIN_ARROW_FRACTION
from ..plotting.plot3d import joint_force_vectors_3d, mechanism_joints
from ..scene.geometry import scene_size
from ..scene.model import Scene
from ..scene.polyhedra import outward_faces

#: the largest joint resultant is drawn this long, as a fraction of the scene's size
ARROW_FRACTION = 0.12


def _b64(a: np.ndarray, dtype: str) -> str:
    return base64.b64encode(np.ascontiguousarray(a, dtype=dtype).tobytes()).decode("ascii")


def f32(a: Any) -> str:
    return _b64(np.asarray(a, dtype=float).ravel(), "<f4")


def u32(a: Any) -> str:
    return _b64(np.asarray(a, dtype=np.int64).ravel(), "<u4")


def geometry(scene: Scene) -> dict[str, Any]:
    """Vertices, triangles (fans over the outward faces) and edges of every block."""
    verts, tris, edges, vstart = [], [], [], [0]
    off = 0
    for b in scene.blocks:
        p = b.points
        verts.append(p)
        seen = set()
        for face in outward_faces(b):
            f = [int(i) for i in face]
            for k in range(1, len(f) - 1):
                tris.append((off + f[0], off + f[k], off + f[k + 1]))
            for a, c in zip(f, f[1:] + f[:1], strict=True):
                key = (min(a, c), max(a, c))
                if key not in seen:
                    seen.add(key)
                    edges.append((off + key[0], off + key[1]))
        off += len(p)
        vstart.append(off)
    return {"positions": np.concatenate(verts), "triangles": np.asarray(tris),
            "edges": np.asarray(edges), "vstart": np.asarray(vstart)}


def view_data(scene: Scene, result: Any = None) -> dict[str, Any]:
    """Everything the 3D viewer needs, JSON-ready (arrays as base64 strings)."""
    g = geometry(scene)
    size = scene_size(scene)
    _, centroids, _ = scene_weights(scene)
    sup = scene.support_mask
    pts = g["positions"]
    out: dict[str, Any] = {
        "size": size, "lo": pts.min(axis=0).tolist(), "hi": pts.max(axis=0).tolist(),
        "n_blocks": len(scene.blocks), "ids": [b.id for b in scene.blocks],
        "support": [bool(s) for s in sup],
        "positions": f32(pts), "triangles": u32(g["triangles"]), "edges": u32(g["edges"]),
        "vstart": u32(g["vstart"]), "centroids": f32(centroids),
        "n_triangles": len(g["triangles"]),
        "units": {"length": scene.length_unit, "force": scene.force_unit},
        "loads": _loads(scene, live_applies(result)),
    }
    c = getattr(result, "contacts", None)
    if c is not None and c.n_joints:
        out["joints"] = _joints(scene, result)
    mech = getattr(result, "mechanism", None)
    if mech is not None and c is not None:
        out["mechanism"] = _mechanism(scene, result, centroids, size)
    return out


def _loads(scene: Scene, live: bool = True) -> list[dict[str, Any]]:
    """Load arrows (:func:`rigidblocks.plotting.marks.load_marks`)."""
    return [{"tail": m.tail.tolist(), "tip": m.tip.tolist(), "live": m.live,
             "label": m.label, "kind": m.kind} for m in load_marks(scene, live)]


def _joints(scene: Scene, result: Any) -> dict[str, Any]:
    c = result.contacts
    centres = c.joint_centres
    out: dict[str, Any] = {"n": c.n_joints, "pairs": u32(c.pairs), "centres": f32(centres),
                           "points": f32(c.points), "start": u32(c.joint_start)}
    breaches = tuple(getattr(result, "breaches", ()) or ())
    if breaches:  # a NOT ADMISSIBLE check: the joints it breaches, as its picture marks
        out["breached"] = u32([int(k) for k, _ in breaches])
    st = getattr(result, "state", None)
    if st is not None:
        vec = joint_force_vectors_3d(c, st)
        mag = np.linalg.norm(vec, axis=1)
        top = float(mag.max(initial=0.0))
        tp = np.asarray(st.thrust_points, dtype=float)
        at = np.where(np.all(np.isfinite(tp), axis=1)[:, None]
                      & (np.asarray(st.joint_normal)[:, None] > 0), tp, centres)
        keep = np.flatnonzero(mag >= MIN_ARROW_FRACTION * top) if top > 0 else \
            np.zeros(0, dtype=int)
        scale = ARROW_FRACTION * scene_size(scene) / top if top > 0 else 0.0
        out["forces"] = {"joint": u32(keep), "at": f32(at[keep]),
                         "vec": f32(vec[keep] * scale), "largest": top,
                         "n_small": int(c.n_joints - len(keep))}
    return out


def _mechanism(scene: Scene, result: Any, centroids: np.ndarray, size: float
               ) -> dict[str, Any]:
    mech = result.mechanism
    vel = np.asarray(mech.velocities, dtype=float)
    reach = block_reach(scene, vel, centroids)
    colours, legend = mechanism_colours(scene, result, centroids)
    top = float(reach.max(initial=0.0))
    s = DISPLACEMENT_FRACTION * size / top if top > 0 else 0.0
    marks = mechanism_joints(scene, result)
    segs, follow, kind = [], [], []
    code = {"hinge": 0, "slide": 1, "open": 2}
    for name, (lines, owners) in marks.items():
        for seg, own in zip(lines, owners, strict=True):
            segs.append(seg)
            follow.append((own, own))
            kind.append(code[name])
    return {"velocities": f32(vel), "scale": s,
            "moving": [c is not None for c in colours],
            "colours": colours, "legend": [list(r) for r in legend],
            "segments": f32(np.asarray(segs).reshape(-1, 3) if segs else np.zeros((0, 3))),
            "segment_block": u32(np.asarray(follow).ravel() if follow else np.zeros(0)),
            "segment_kind": u32(np.asarray(kind)),
            "counts": {k: len(v[0]) for k, v in marks.items()},
            "left_out": len(marked_joints(result, most=MOST_MARKED_3D)["left_out"]),
            "modes": list(mech.modes)}


__all__ = ["geometry", "view_data"]
