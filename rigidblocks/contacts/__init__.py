"""Contact detection: the joints of a scene, found from its geometry."""

from __future__ import annotations

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


__all__ = ["Contacts", "detect_contacts"]
