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


_FACE_CACHE = "_rigidblocks_faces"


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Row-wise cross product of (n, 3) arrays."""
    return np.stack([a[:, 1] * b[:, 2] - a[:, 2] * b[:, 1],
                     a[:, 2] * b[:, 0] - a[:, 0] * b[:, 2],
                     a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]], axis=1)


def _oriented(block: Block) -> tuple[list[np.ndarray], np.ndarray]:
    """Faces ordered counter-clockwise seen from outside, and their Newell normals.

    All faces in one vectorised pass (Newell's normal summed per face with bincount),
    cached on the block (blocks are immutable). A face is reversed when its normal
    points towards the mean of the block's vertices: right for convex blocks, which is
    what :func:`validate_polyhedra` demands (a non-convex block fails its convexity
    test whichever way its faces are oriented).
    """
    cached = block.__dict__.get(_FACE_CACHE)
    if cached is not None:
        return cached
    pts = block.points
    faces = [np.asarray(f, dtype=int) for f in block.faces or ()]
    if not faces:
        out: tuple[list[np.ndarray], np.ndarray] = ([], np.zeros((0, 3)))
        block.__dict__[_FACE_CACHE] = out
        return out
    cnt = np.array([len(f) for f in faces])
    starts = np.concatenate([[0], np.cumsum(cnt)])
    flat = np.concatenate(faces)
    owner = np.repeat(np.arange(len(faces)), cnt)
    nxt = np.arange(len(flat)) + 1
    nxt[starts[1:] - 1] = starts[:-1]
    p, q = pts[flat], pts[flat[nxt]]
    comp = [(p[:, 1] - q[:, 1]) * (p[:, 2] + q[:, 2]),
            (p[:, 2] - q[:, 2]) * (p[:, 0] + q[:, 0]),
            (p[:, 0] - q[:, 0]) * (p[:, 1] + q[:, 1])]
    k = len(faces)
    normals = np.stack([np.bincount(owner, c, minlength=k) for c in comp], axis=1)
    centres = np.stack([np.bincount(owner, p[:, j], minlength=k) for j in range(3)],
                       axis=1) / cnt[:, None]
    flip = np.einsum("ij,ij->i", normals, centres - pts.mean(axis=0)) < 0
    normals[flip] *= -1.0
    out = ([f[::-1] if fl else f for f, fl in zip(faces, flip, strict=True)], normals)
    block.__dict__[_FACE_CACHE] = out
    return out


def outward_faces(block: Block) -> list[np.ndarray]:
    """The block's faces as vertex-index arrays ordered counter-clockwise seen from outside."""
    return list(_oriented(block)[0])


def polyhedron_volume_centroid(block: Block) -> tuple[float, np.ndarray]:
    """Volume and centroid of a closed polyhedron (faces oriented outward).

    Divergence theorem on a fan triangulation of each face: tetrahedra (o, a, b, c)
    with o the mean vertex, V = sum a.(b x c) / 6, centroid = o + sum V_t (a+b+c)/4 / V.
    """
    pts = block.points
    o = pts.mean(axis=0)
    tri = [np.stack([np.full(len(f) - 2, f[0]), f[1:-1], f[2:]], axis=1)
           for f in _oriented(block)[0]]
    t = np.concatenate(tri) if tri else np.zeros((0, 3), dtype=int)
    a, b, c = pts[t[:, 0]] - o, pts[t[:, 1]] - o, pts[t[:, 2]] - o
    v = (a * _cross(b, c)).sum(axis=1) / 6.0
    # running sums in face order (the same round-off as summing tetrahedron by tetrahedron)
    vol = float(np.cumsum(v)[-1]) if len(v) else 0.0
    mom = np.cumsum(v[:, None] * (a + b + c) / 4.0, axis=0)[-1] if len(v) else np.zeros(3)
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
            for a, c in zip(f, f[1:] + f[:1], strict=True):
                key = (min(a, c), max(a, c))
                edges[key] = edges.get(key, 0) + 1
        faces, normals = _oriented(b)  # same order as b.faces
        nn = np.linalg.norm(normals, axis=1)
        small = np.flatnonzero(nn <= 1e-12 * size**2)
        if small.size:
            raise InputError(f"face {small[0]} has zero area", where)
        nhat = normals / nn[:, None]
        first = pts[[f[0] for f in faces]]
        offset = np.einsum("ij,ij->i", first, nhat)
        # planarity: every vertex of a face on the face's plane
        owner = np.repeat(np.arange(len(faces)), [len(f) for f in faces])
        flat = np.concatenate(faces)
        dev = np.abs(np.einsum("ij,ij->i", pts[flat], nhat[owner]) - offset[owner])
        worst = np.zeros(len(faces))
        np.maximum.at(worst, owner, dev)
        off = np.flatnonzero(worst > tol)
        if off.size:
            raise InputError(f"face {off[0]} is not planar", where)
        if any(v != 2 for v in edges.values()):
            raise InputError("the faces do not close the polyhedron (every edge must belong "
                             "to exactly two faces)", where)
        used = {i for f in b.faces or () for i in f}
        if len(used) != len(pts):
            raise InputError("some vertices belong to no face", where)
        # convexity: no vertex outside the plane of any (outward) face
        outside = np.flatnonzero((pts @ nhat.T - offset).max(axis=0) > tol)
        if outside.size:
            raise InputError(f"the polyhedron is not convex (vertices lie outside the "
                             f"plane of face {outside[0]}); split it into convex blocks",
                             where)
        vol, _ = polyhedron_volume_centroid(b)
        if vol <= 1e-12 * size**3:
            raise InputError("polyhedron has zero volume", where)
    check_overlaps_3d(scene)


def block_planes(block: Block) -> tuple[np.ndarray, np.ndarray]:
    """Outward unit normals (k, 3) and offsets (k,) of the block's face planes."""
    faces, normals = _oriented(block)
    n = normals / np.linalg.norm(normals, axis=1)[:, None]
    first = np.array([f[0] for f in faces], dtype=int)
    return n, np.einsum("ij,ij->i", n, block.points[first])


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
    """Separating-axis test on every candidate pair of convex blocks.

    The face normals of both blocks are tried first (they separate every pair of blocks
    that merely touch face to face, the common case); the cross products of edge
    directions only where they do not.
    """
    from .geometry import scene_size

    tol = POLY_TOL * scene_size(scene)
    edges: dict[int, np.ndarray] = {}

    def separated(pa: np.ndarray, pb: np.ndarray, axes: np.ndarray) -> bool:
        a, b = pa @ axes.T, pb @ axes.T
        return bool(np.any((a.max(axis=0) <= b.min(axis=0) + tol)
                           | (b.max(axis=0) <= a.min(axis=0) + tol)))

    for i, j in candidate_pairs(scene, 0.0):
        A, B = scene.blocks[i], scene.blocks[j]
        pa, pb = A.points, B.points
        faces = np.vstack([block_planes(A)[0], block_planes(B)[0]])
        if separated(pa, pb, faces):
            continue
        for k, blk in ((i, A), (j, B)):
            if k not in edges:
                edges[k] = np.array(_edge_dirs(blk)).reshape(-1, 3)
        w = np.cross(edges[i][:, None, :], edges[j][None, :, :]).reshape(-1, 3)
        nw = np.linalg.norm(w, axis=1)
        w = w[nw > 1e-9] / nw[nw > 1e-9, None]
        if not (len(w) and separated(pa, pb, w)):
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
