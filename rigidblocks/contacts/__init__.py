"""Contact detection: the joints of a scene, found from its geometry."""

from __future__ import annotations

import numpy as np

from ..scene.model import Scene
from ..scene.validate import DEFAULT_TOL
from .model import Contacts

_CACHE_KEY = "_rigidblocks_contacts"


def detect_contacts(scene: Scene, tol: float = DEFAULT_TOL) -> Contacts:
    """The joints of a scene (cached on the scene object, which is immutable).

    Args:
        scene: a scene (2D or 3D).
        tol: relative geometric tolerance; edges or faces closer than
            ``tol x scene size`` are taken as touching.
    """
    cache = scene.__dict__.setdefault(_CACHE_KEY, {})
    if tol not in cache:
        if scene.dimension == 2:
            from .detect2d import detect_contacts_2d

            cache[tol] = detect_contacts_2d(scene, tol)
        else:
            from .detect3d import detect_contacts_3d

            cache[tol] = detect_contacts_3d(scene, tol)
    return cache[tol]


def point_touches(scene: Scene, ids: list[str], tol: float = DEFAULT_TOL,
                  joined: set[frozenset[str]] | None = None) -> dict[str, tuple[str, str]]:
    """Of the blocks ``ids``, which have no joint, those that meet another block all the
    same, within ``tol x scene size``: at a point in 2D (a corner on an edge), at a
    point or along an edge in 3D. A joint is a common edge (2D) or a face in common
    (3D), so such a block is held by nothing. Each such id maps to the other block's id
    (in 2D the nearest) and where they meet ("at a point only (a corner)", "at a
    point only", "along an edge only"); the pairs in ``joined`` (their ids), which have
    a joint, are not sought."""
    if not ids:
        return {}
    from ..scene.model import scene_size

    eps = tol * scene_size(scene)
    joined = joined or set()
    if scene.dimension == 3:
        return _touches_3d(scene, ids, eps, joined)
    import shapely

    polys = [shapely.Polygon(np.asarray(b.vertices, float)) for b in scene.blocks]
    tree = shapely.STRtree(polys)
    index = {b.id: k for k, b in enumerate(scene.blocks)}
    out = {}
    for i in ids:
        k = index[i]
        near = [j for j in tree.query(polys[k], predicate="dwithin", distance=eps)
                if j != k and frozenset((i, scene.blocks[j].id)) not in joined]
        if near:
            j = min(near, key=lambda j: polys[k].distance(polys[j]))
            out[i] = (scene.blocks[j].id, "at a point only (a corner)")
    return out


def _touches_3d(scene: Scene, ids: list[str], eps: float, joined: set[frozenset[str]]
                ) -> dict[str, tuple[str, str]]:
    """:func:`point_touches` of 3D blocks: the first block (in scene order) within
    ``eps`` of each (:func:`~rigidblocks.scene.polyhedra.blocks_meet`), met along an
    edge where two or more corners of either lie within ``eps`` of the other, else at a
    point."""
    from ..scene.polyhedra import blocks_meet, candidate_pairs, distance_from

    want = {b.id for b in scene.blocks} & set(ids)
    out: dict[str, tuple[str, str]] = {}
    for i, j in candidate_pairs(scene, eps):
        A, B = scene.blocks[i], scene.blocks[j]
        if not ({A.id, B.id} & (want - set(out))) or {A.id, B.id} in joined or \
                not blocks_meet(scene, int(i), int(j), -eps):
            continue
        corners = [p for X, Y in ((A, B), (B, A)) for p in np.asarray(X.points, float)
                   if distance_from(Y, p) <= eps]
        apart = max((float(np.linalg.norm(p - corners[0])) for p in corners), default=0.0)
        where = "along an edge only" if apart > eps else "at a point only"
        for x, y in ((A.id, B.id), (B.id, A.id)):
            if x in want:
                out.setdefault(x, (y, where))
    return out


__all__ = ["Contacts", "detect_contacts", "point_touches"]
