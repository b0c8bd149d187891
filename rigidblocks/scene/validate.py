"""Semantic and geometric validation of a scene.

Checks that a scene file's structure alone cannot catch: duplicate ids, loads on
supports or unknown blocks, supports and free blocks present, simple polygons of
non-zero area, no two blocks whose interiors overlap, and joint overrides only between
blocks in contact, one per joint. Every failure is an :class:`~rigidblocks.errors.InputError` naming
the block(s) at fault.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from .geometry import flat_polygons, polygon_areas_centroids, polygon_diagonals, scene_size
from .model import Scene

#: relative tolerance for geometric coincidence (times the scene's size)
DEFAULT_TOL = 1e-7
#: an overlap smaller than this fraction of the smaller block's area is round-off
OVERLAP_AREA_TOL = 1e-6


def validate_scene(scene: Scene, tol: float = DEFAULT_TOL) -> None:
    """Raise :class:`InputError` if the scene is not a valid structure (ids, loads,
    supports, simple polygons or closed polyhedra, no overlaps). That joint overrides
    name touching blocks is checked where the joints are found
    (:func:`rigidblocks.contacts.detect_contacts`)."""
    _check_ids_and_loads(scene)
    if scene.dimension == 2:
        _check_polygons(scene)
        check_overlaps_2d(scene)
    else:
        from .polyhedra import validate_polyhedra

        validate_polyhedra(scene)


def _check_ids_and_loads(scene: Scene) -> None:
    seen: set[str] = set()
    for b in scene.blocks:
        if b.id in seen:
            raise InputError("duplicate block id", f"block '{b.id}'")
        seen.add(b.id)
    if not any(b.support for b in scene.blocks):
        raise InputError("no support block: mark at least one block with \"support\": true")
    if all(b.support for b in scene.blocks):
        raise InputError("no free block: every block is a support, there is nothing to analyse")
    for i, ld in enumerate(scene.loads):
        if ld.block not in scene.index:
            raise InputError(f"unknown block '{ld.block}'", f"load #{i}")
        if scene.block(ld.block).support:
            raise InputError(f"block '{ld.block}' is a support: loads go on free blocks only",
                             f"load #{i}")
    pairs: set[frozenset[str]] = set()
    for j in scene.joints:
        where = f"joint '{j.blocks[0]}'-'{j.blocks[1]}'"
        for bid in j.blocks:
            if bid not in scene.index:
                raise InputError(f"unknown block '{bid}'", where)
        if frozenset(j.blocks) in pairs:
            raise InputError("overridden twice: give one override per joint", where)
        pairs.add(frozenset(j.blocks))


def _check_polygons(scene: Scene) -> None:
    import shapely

    verts, starts = flat_polygons(scene)
    area, _ = polygon_areas_centroids(verts, starts)
    owner = np.repeat(np.arange(len(scene.blocks)), np.diff(starts))
    diag2 = polygon_diagonals(verts, starts) ** 2
    flat = np.abs(area) <= 1e-10 * diag2
    if flat.any():
        b = scene.blocks[int(np.flatnonzero(flat)[0])]
        raise InputError("polygon has zero area (its vertices are collinear or repeated)",
                         f"block '{b.id}'")
    rings = shapely.linearrings(verts, indices=owner)
    simple = shapely.is_simple(rings)
    if not simple.all():
        b = scene.blocks[int(np.flatnonzero(~simple)[0])]
        raise InputError("polygon is self-intersecting (its edges cross or touch)",
                         f"block '{b.id}'")


def block_polygons(scene: Scene):
    """Shapely polygons of the 2D blocks, in scene order."""
    import shapely

    verts, starts = flat_polygons(scene)
    owner = np.repeat(np.arange(len(scene.blocks)), np.diff(starts))
    return shapely.polygons(shapely.linearrings(verts, indices=owner))


def check_overlaps_2d(scene: Scene) -> None:
    """Raise if the interiors of two blocks overlap by more than round-off."""
    import shapely

    polys = block_polygons(scene)
    tree = shapely.STRtree(polys)
    i, j = tree.query(polys)  # bounding boxes intersect
    keep = i < j
    i, j = i[keep], j[keep]
    if len(i) == 0:
        return
    own = shapely.area(polys)
    # the interiors' common area is at most that of the bounding boxes' intersection:
    # pairs whose boxes share less than the tolerance (blocks side by side, touching
    # along an edge) cannot fail, and skip the exact (costly) tests
    bounds = shapely.bounds(polys)
    w = np.minimum(bounds[i, 2], bounds[j, 2]) - np.maximum(bounds[i, 0], bounds[j, 0])
    h = np.minimum(bounds[i, 3], bounds[j, 3]) - np.maximum(bounds[i, 1], bounds[j, 1])
    box_area = np.clip(w, 0, None) * np.clip(h, 0, None)
    keep = box_area > OVERLAP_AREA_TOL * np.minimum(own[i], own[j])
    i, j = i[keep], j[keep]
    if len(i) == 0:
        return
    inner = shapely.relate_pattern(polys[i], polys[j], "T********")
    i, j = i[inner], j[inner]
    if len(i) == 0:
        return
    areas = shapely.area(shapely.intersection(polys[i], polys[j]))
    bad = areas > OVERLAP_AREA_TOL * np.minimum(own[i], own[j])
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        a, b = scene.blocks[i[k]].id, scene.blocks[j[k]].id
        raise InputError(f"blocks '{a}' and '{b}' overlap (their interiors share an area of "
                         f"{areas[k]:.3g}); blocks may touch but not overlap",
                         f"block '{a}'")


__all__ = ["validate_scene", "check_overlaps_2d", "block_polygons", "scene_size"]
