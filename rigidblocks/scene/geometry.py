"""Geometry of blocks: areas, centroids, oriented polygons, scene size.

Pure numpy (and shapely for validity checks); no solver is imported here.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .model import Block, Scene, scene_size  # noqa: F401 - scene_size is used from here too


def signed_area(poly: np.ndarray) -> float:
    """Signed area of a 2D polygon (positive when counter-clockwise)."""
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def polygon_centroid(poly: np.ndarray) -> np.ndarray:
    """Centroid of a simple 2D polygon of non-zero area (either orientation)."""
    p = poly - poly[0]  # shift for round-off
    x, y = p[:, 0], p[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    a = 0.5 * cross.sum()
    cx = ((x + xn) * cross).sum() / (6.0 * a)
    cy = ((y + yn) * cross).sum() / (6.0 * a)
    return np.array([cx, cy]) + poly[0]


def ccw(poly: np.ndarray) -> np.ndarray:
    """The polygon's vertices in counter-clockwise order."""
    return poly if signed_area(poly) > 0 else poly[::-1].copy()


def simplify_polygon(poly: np.ndarray, tol: float) -> np.ndarray:
    """Drop repeated vertices and vertices lying on the straight line of their neighbours.

    ``tol`` is a length: a vertex closer than ``tol`` to the chord through its
    neighbours is removed. The result keeps the input's orientation.
    """
    pts = np.asarray(poly, dtype=float)
    changed = True
    while changed and len(pts) > 3:
        changed = False
        nxt = np.roll(pts, -1, axis=0)
        keep = np.linalg.norm(nxt - pts, axis=1) > tol
        if not keep.all():
            pts = pts[keep]
            changed = True
            continue
        prv = np.roll(pts, 1, axis=0)
        nxt = np.roll(pts, -1, axis=0)
        chord = nxt - prv
        clen = np.linalg.norm(chord, axis=1)
        dist = np.abs(chord[:, 0] * (pts[:, 1] - prv[:, 1]) - chord[:, 1] * (pts[:, 0] - prv[:, 0]))
        dist = dist / np.where(clen > 0, clen, 1.0)
        # a vertex is redundant if it lies on the chord between its neighbours
        t = np.einsum("ij,ij->i", pts - prv, chord) / np.where(clen > 0, clen**2, 1.0)
        redundant = (dist <= tol) & (t > 0) & (t < 1)
        if redundant.any():
            # remove one at a time from each run to stay safe with consecutive ones
            first = int(np.flatnonzero(redundant)[0])
            pts = np.delete(pts, first, axis=0)
            changed = True
    return pts


def block_measure(block: Block, dimension: int) -> tuple[float, np.ndarray]:
    """(area, centroid) of a 2D block; (volume, centroid) of a 3D block."""
    if dimension == 2:
        poly = block.points
        return abs(signed_area(poly)), polygon_centroid(poly)
    from .polyhedra import polyhedron_volume_centroid  # 3D only

    return polyhedron_volume_centroid(block)


def flat_polygons(scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """All 2D block polygons as one (V, 2) array of vertices and the start offsets.

    Block ``i`` owns ``verts[starts[i]:starts[i + 1]]`` (``starts`` has n + 1 entries),
    in the order given in the scene.
    """
    counts = np.array([len(b.vertices) for b in scene.blocks])
    starts = np.concatenate([[0], np.cumsum(counts)])
    verts = np.concatenate([b.points for b in scene.blocks], axis=0)
    return verts, starts


def polygon_areas_centroids(verts: np.ndarray, starts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Signed areas and centroids of many polygons at once (see :func:`flat_polygons`)."""
    n = len(starts) - 1
    owner = np.repeat(np.arange(n), np.diff(starts))
    nxt_idx = np.arange(len(verts)) + 1
    nxt_idx[starts[1:] - 1] = starts[:-1]
    origin = verts[starts[:-1]][owner]  # shift for round-off
    p = verts - origin
    q = verts[nxt_idx] - origin
    cross = p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]
    area2 = np.bincount(owner, cross, minlength=n)
    cx = np.bincount(owner, (p[:, 0] + q[:, 0]) * cross, minlength=n)
    cy = np.bincount(owner, (p[:, 1] + q[:, 1]) * cross, minlength=n)
    with np.errstate(divide="ignore", invalid="ignore"):
        cent = np.stack([cx, cy], axis=1) / (3.0 * area2[:, None])
    return 0.5 * area2, cent + verts[starts[:-1]]


def polygon_diagonals(verts: np.ndarray, starts: np.ndarray) -> np.ndarray:
    """Bounding-box diagonal of each polygon (see :func:`flat_polygons`)."""
    lo = np.minimum.reduceat(verts, starts[:-1], axis=0)
    hi = np.maximum.reduceat(verts, starts[:-1], axis=0)
    return np.linalg.norm(hi - lo, axis=1)


_WEIGHTS: dict[int, tuple[Any, tuple[np.ndarray, np.ndarray, np.ndarray]]] = {}


def scene_weights(scene: Scene) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`block_weights`, remembered for the last scene asked about (an answer, a
    picture and a report ask for them several times; a 3D block's volume and centroid
    take a fraction of a millisecond each, seconds for thousands)."""
    import weakref

    hit = _WEIGHTS.get(id(scene))
    if hit is not None and hit[0]() is scene:
        return hit[1]
    value = block_weights(scene)
    _WEIGHTS.clear()
    _WEIGHTS[id(scene)] = (weakref.ref(scene), value)
    return value


def block_weights(scene: Scene) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(weights, centroids, sizes) of every block, in the scene's units.

    Weight = unit weight x area x depth (2D) or x volume (3D); size is the diagonal of
    the block's bounding box.
    """
    gamma = np.array([scene.effective_unit_weight if b.unit_weight is None
                      else float(b.unit_weight) for b in scene.blocks])
    if scene.dimension == 2:
        verts, starts = flat_polygons(scene)
        area, centroids = polygon_areas_centroids(verts, starts)
        sizes = polygon_diagonals(verts, starts)
        return gamma * np.abs(area) * scene.effective_depth, centroids, sizes
    from .polyhedra import block_size, polyhedra_volumes_centroids  # 3D only

    meas, centroids = polyhedra_volumes_centroids(scene.blocks)
    sizes = np.array([block_size(b) for b in scene.blocks])  # cached by validation
    return gamma * meas, centroids, sizes
