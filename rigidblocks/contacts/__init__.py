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


def point_touches(scene: Scene, ids: list[str], tol: float = DEFAULT_TOL) -> dict[str, str]:
    """Of the 2D blocks ``ids``, which have no joint, those that meet another block all
    the same, at a point (a corner on an edge, within ``tol x scene size``): a joint is a
    common edge, so such a block is held by nothing. Each such id maps to the other
    block's id (the nearest); 3D scenes give none."""
    if scene.dimension != 2 or not ids:
        return {}
    import shapely

    from ..scene.model import scene_size

    polys = [shapely.Polygon(np.asarray(b.vertices, float)) for b in scene.blocks]
    tree = shapely.STRtree(polys)
    eps = tol * scene_size(scene)
    index = {b.id: k for k, b in enumerate(scene.blocks)}
    out = {}
    for i in ids:
        k = index[i]
        near = [j for j in tree.query(polys[k], predicate="dwithin", distance=eps)
                if j != k]
        if near:
            j = min(near, key=lambda j: polys[k].distance(polys[j]))
            out[i] = scene.blocks[j].id
    return out


__all__ = ["Contacts", "detect_contacts", "point_touches"]
