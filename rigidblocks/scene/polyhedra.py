"""Convex polyhedral blocks (3D): validation, outward faces, volume and centroid."""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from .model import Block, Scene

#: relative tolerance for planarity and convexity (times the block's size)
POLY_TOL = 1e-7


def _size(block: Block) -> float:
    p = block.points
    return float(np.linalg.norm(p.max(axis=0) - p.min(axis=0)))


def face_normal(pts: np.ndarray) -> np.ndarray:
    """Newell's normal of a polygon (unnormalised; its length is twice the area)."""
    nxt = np.roll(pts, -1, axis=0)
    return np.array([
        np.sum((pts[:, 1] - nxt[:, 1]) * (pts[:, 2] + nxt[:, 2])),
        np.sum((pts[:, 2] - nxt[:, 2]) * (pts[:, 0] + nxt[:, 0])),
        np.sum((pts[:, 0] - nxt[:, 0]) * (pts[:, 1] + nxt[:, 1])),
    ])


def outward_faces(block: Block) -> list[np.ndarray]:
    """The block's faces as vertex-index arrays ordered counter-clockwise seen from outside."""
    pts = block.points
    inside = pts.mean(axis=0)
    out = []
    for f in block.faces or ():
        idx = np.asarray(f)
        n = face_normal(pts[idx])
        if np.dot(n, pts[idx].mean(axis=0) - inside) < 0:
            idx = idx[::-1]
        out.append(idx)
    return out


def polyhedron_volume_centroid(block: Block) -> tuple[float, np.ndarray]:
    """Volume and centroid of a closed polyhedron (faces oriented outward)."""
    pts = block.points
    o = pts.mean(axis=0)
    vol = 0.0
    mom = np.zeros(3)
    for idx in outward_faces(block):
        p = pts[idx]
        for k in range(1, len(idx) - 1):
            a, b, c = p[0] - o, p[k] - o, p[k + 1] - o
            v = np.dot(a, np.cross(b, c)) / 6.0
            vol += v
            mom += v * (a + b + c) / 4.0
    return abs(vol), o + mom / vol


def validate_polyhedra(scene: Scene) -> None:
    """Closed, planar, convex polyhedra of positive volume; no two overlapping."""
    for b in scene.blocks:
        where = f"block '{b.id}'"
        pts = b.points
        size = _size(b)
        tol = POLY_TOL * max(size, 1e-300)
        edges: dict[tuple[int, int], int] = {}
        for k, f in enumerate(b.faces or ()):
            if len(set(f)) != len(f):
                raise InputError(f"face {k} repeats a vertex", where)
            p = pts[list(f)]
            n = face_normal(p)
            nn = np.linalg.norm(n)
            if nn <= 1e-12 * size**2:
                raise InputError(f"face {k} has zero area", where)
            if np.abs((p - p[0]) @ (n / nn)).max() > tol:
                raise InputError(f"face {k} is not planar", where)
            for a, c in zip(f, f[1:] + f[:1], strict=True):
                key = (min(a, c), max(a, c))
                edges[key] = edges.get(key, 0) + 1
        if any(v != 2 for v in edges.values()):
            raise InputError("the faces do not close the polyhedron (every edge must belong "
                             "to exactly two faces)", where)
        used = {i for f in b.faces or () for i in f}
        if len(used) != len(pts):
            raise InputError("some vertices belong to no face", where)
        for k, idx in enumerate(outward_faces(b)):
            p = pts[idx]
            n = face_normal(p)
            n = n / np.linalg.norm(n)
            if ((pts - p[0]) @ n).max() > tol:
                raise InputError(f"the polyhedron is not convex (vertices lie outside the "
                                 f"plane of face {k}); split it into convex blocks", where)
        vol, _ = polyhedron_volume_centroid(b)
        if vol <= 1e-12 * size**3:
            raise InputError("polyhedron has zero volume", where)
    check_overlaps_3d(scene)


def block_planes(block: Block) -> tuple[np.ndarray, np.ndarray]:
    """Outward unit normals (k, 3) and offsets (k,) of the block's face planes."""
    pts = block.points
    normals, offsets = [], []
    for idx in outward_faces(block):
        n = face_normal(pts[idx])
        n = n / np.linalg.norm(n)
        normals.append(n)
        offsets.append(float(n @ pts[idx[0]]))
    return np.array(normals), np.array(offsets)


def candidate_pairs(scene: Scene, pad: float) -> np.ndarray:
    """Block pairs (i < j) whose bounding boxes, grown by ``pad``, intersect."""
    import shapely

    lo = np.array([b.points.min(axis=0) for b in scene.blocks]) - pad
    hi = np.array([b.points.max(axis=0) for b in scene.blocks]) + pad
    boxes = shapely.box(lo[:, 0], lo[:, 1], hi[:, 0], hi[:, 1])
    tree = shapely.STRtree(boxes)
    i, j = tree.query(boxes, predicate="intersects")
    keep = (i < j) & (lo[i, 2] <= hi[j, 2]) & (lo[j, 2] <= hi[i, 2])
    return np.stack([i[keep], j[keep]], axis=1)


def check_overlaps_3d(scene: Scene) -> None:
    """Separating-axis test on every candidate pair of convex blocks."""
    from .geometry import scene_size

    tol = POLY_TOL * scene_size(scene)
    for i, j in candidate_pairs(scene, 0.0):
        A, B = scene.blocks[i], scene.blocks[j]
        axes = [*block_planes(A)[0], *block_planes(B)[0]]
        ea = _edge_dirs(A)
        eb = _edge_dirs(B)
        for u in ea:
            for v in eb:
                w = np.cross(u, v)
                nw = np.linalg.norm(w)
                if nw > 1e-9:
                    axes.append(w / nw)
        pa, pb = A.points, B.points
        separated = False
        for ax in axes:
            a = pa @ ax
            b = pb @ ax
            if a.max() <= b.min() + tol or b.max() <= a.min() + tol:
                separated = True
                break
        if not separated:
            raise InputError(f"blocks '{A.id}' and '{B.id}' overlap; blocks may touch but "
                             "not overlap", f"block '{A.id}'")


def _edge_dirs(block: Block) -> list[np.ndarray]:
    pts = block.points
    dirs: dict[tuple, np.ndarray] = {}
    for f in block.faces or ():
        for a, c in zip(f, f[1:] + f[:1], strict=True):
            d = pts[c] - pts[a]
            d = d / np.linalg.norm(d)
            if d[np.argmax(np.abs(d))] < 0:
                d = -d
            dirs[tuple(np.round(d, 9))] = d
    return list(dirs.values())
