"""Semantic and geometric validation of a scene.

Checks that a scene file's structure alone cannot catch: duplicate ids, loads on
supports or unknown blocks, supports and free blocks present, quantities derived from
the numbers (areas, volumes, weights, loads and their moments, and live loads times a
load factor) finite and representable, simple polygons of
non-zero area, no two blocks whose interiors overlap, and joint overrides only between
blocks in contact, one per joint. Every failure is an :class:`~rigidblocks.errors.InputError` naming
the block(s) at fault.
"""

from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from .geometry import flat_polygons, polygon_areas_centroids, polygon_diagonals, scene_size
from .model import Block, Load, Scene, Units, flow_value, friction_value

#: relative tolerance for geometric coincidence (times the scene's size)
DEFAULT_TOL = 1e-7
#: an overlap smaller than this fraction of the smaller block's area is round-off
OVERLAP_AREA_TOL = 1e-6
#: the largest magnitude of a quantity derived from a scene (coordinates, areas and
#: volumes, weights, loads, their moments, live loads times the load factor): the
#: analysis multiplies such quantities in pairs (forces by lever arms, loads by
#: factors) and sums them over blocks, which stays finite below 1e300
LARGEST = 1e150


def validate_scene(scene: Scene, tol: float = DEFAULT_TOL) -> None:
    """Raise :class:`InputError` if the scene is not a valid structure (ids, loads,
    supports, simple polygons or closed polyhedra, no overlaps). That joint overrides
    name touching blocks is checked where the joints are found
    (:func:`rigidblocks.contacts.detect_contacts`).

    A scene is immutable: one that passed at the default tolerance is not checked again
    (a scene file's was checked by its reader, then by the analysis, then by each method
    it opened)."""
    default = tol == DEFAULT_TOL and isinstance(scene, Scene)
    if default and scene.__dict__.get(_VALID):
        return
    check_fields(scene)
    _check_ids_and_loads(scene)
    check_representable(scene)
    if scene.dimension == 2:
        _check_polygons(scene)
        check_overlaps_2d(scene)
    else:
        from .polyhedra import validate_polyhedra

        validate_polyhedra(scene)
    if default:
        scene.__dict__[_VALID] = True


#: the mark of a scene that passed :func:`validate_scene` at the default tolerance
_VALID = "_rigidblocks_valid"


def is_number(v: object) -> bool:
    """A number (not a boolean, not a string): the scene file's values and a Scene's."""
    return isinstance(v, int | float | np.integer | np.floating) and not isinstance(v, bool)


def check_fields(scene: Scene) -> None:
    """The values a scene file's reader checks (:mod:`rigidblocks.io.scene_file`), for
    a scene built in code (``Scene``, ``make_block``): a dimension of 2 or 3, the blocks
    Blocks with points of that dimension, vectors of that dimension, numbers where
    numbers go, a friction and a flow that are theirs. (A scene built in code with a
    2D live body force of three components, a flow "x" or a unit weight of -1 was
    analysed as given.)"""
    if not isinstance(scene, Scene):
        raise InputError(f"expected a Scene (rigidblocks.read_scene(path), or Scene(...) "
                         f"in code), got {type(scene).__name__}")
    dim = scene.dimension
    if not (is_number(dim) and dim in (2, 3)):
        raise InputError(f"must be 2 or 3, got {dim!r}", "dimension")
    for b in scene.blocks:
        if not isinstance(b, Block):
            raise InputError(f"expected a Block (make_block(...)), got {type(b).__name__}",
                             "blocks")
        if not isinstance(b.id, str):
            raise InputError(f"a block's id is a string, got {b.id!r}", "blocks")
        if not isinstance(b.support, bool):
            # (support="no" made a support, as any non-empty string is true)
            raise InputError(f"support must be True or False, got {b.support!r}",
                             f"block {b.id!r}")
        if not all(_numbers(v, dim) for v in b.vertices):
            raise InputError(f"every vertex must be {dim} numbers in a {dim}D scene",
                             f"block {b.id!r}")
        if len(b.vertices) < dim + 1:
            # (two vertices read "polygon has zero area (its vertices are collinear ...")
            raise InputError(f"needs at least {dim + 1} vertices, got {len(b.vertices)}",
                             f"block {b.id!r}")
        bad = next((c for v in b.vertices for c in v if not math.isfinite(c)), None)
        if bad is not None:
            # (a NaN was "beyond 1e+150 ... give the scene in other units")
            raise InputError(f"expected finite coordinates, got {bad}", f"block {b.id!r}")
        if dim == 2 and b.faces is not None:
            raise InputError('"faces" is for 3D blocks only', f"block {b.id!r}")
        if dim == 3:
            if b.faces is None:
                raise InputError('missing "faces" (required for 3D blocks)',
                                 f"block {b.id!r}")
            check_faces(b.faces, len(b.vertices), f"block {b.id!r}")
            if not (isinstance(b.faces, tuple) and all(isinstance(f, tuple) for f in b.faces)
                    and all(type(i) is int for f in b.faces for i in f)):
                # (a Block built with lists ended in "unhashable type: 'list'")
                raise InputError("a Block's faces are tuples of vertex indices (make_block "
                                 "builds them from lists or arrays)", f"block {b.id!r}")
        if b.unit_weight is not None and not (is_number(b.unit_weight) and b.unit_weight >= 0):
            raise InputError(f"its unit_weight must be a number >= 0, got "
                             f"{b.unit_weight!r}", f"block {b.id!r}")
        _finite(b.unit_weight, "its unit_weight", f"block {b.id!r}")
    for key, low, strict in (("unit_weight", 0.0, False), ("depth", 0.0, True),
                             ("load_factor", 0.0, False)):
        v = getattr(scene, key)
        if v is not None and not (is_number(v) and (v > low if strict else v >= low)):
            raise InputError(f"must be a number {'>' if strict else '>='} {low:g}, got "
                             f"{v!r}", key)
        _finite(v, "it", key)
    units = scene.units
    if units is not None and not (isinstance(units, Units) and all(
            v is None or isinstance(v, str) for v in (units.length, units.force))):
        # ("m" or ("m", "kN") ended in "'str' object has no attribute 'length'")
        raise InputError(f'expected rigidblocks.Units(length="m", force="kN"), got '
                         f'{units!r}', "units")
    if scene.live_body_force is not None and not _numbers(scene.live_body_force, dim):
        raise InputError(f"must be {dim} numbers in a {dim}D scene, got "
                         f"{scene.live_body_force!r}", "live_body_force")
    _finite(scene.live_body_force, "it", "live_body_force")
    if scene.friction is not None:
        _typed_friction(scene.friction, "friction")
    if scene.flow is not None:
        _located(flow_value, scene.flow, "flow")
    for i, ld in enumerate(scene.loads):
        _check_load(ld, dim, f"load #{i}")
    for j in scene.joints:
        if not (isinstance(j.blocks, tuple | list) and len(j.blocks) == 2
                and all(isinstance(x, str) for x in j.blocks)):
            raise InputError(f"a joint override names two block ids, got {j.blocks!r}",
                             "joints")
        where = f"joint {j.blocks[0]!r}-{j.blocks[1]!r}"
        if j.friction is not None:
            _typed_friction(j.friction, where)
        if j.flow is not None:
            _located(flow_value, j.flow, where)
        for key in ("cohesion", "tensile_strength"):
            v = getattr(j, key)
            if v is not None and not (is_number(v) and v >= 0):
                raise InputError(f"{key} must be a number >= 0, got {v!r}", where)
            _finite(v, key, where)  # (infinite: a scipy traceback, or a warning)


def check_faces(faces: object, nv: int, where: str) -> None:
    """A 3D block's faces as the scene format has them: at least 4, each at least 3
    vertex indices in 0..nv-1 (a scene built in code with none ended in a numpy error,
    with an index out of range in an IndexError)."""
    if isinstance(faces, np.ndarray):  # (read as "not a list of at least 4 faces")
        raise InputError("a Block's faces are tuples of vertex indices (make_block builds "
                         "them from lists or arrays)", where)
    if not isinstance(faces, list | tuple) or len(faces) < 4:
        raise InputError('"faces" must be a list of at least 4 faces', where)

    for k, f in enumerate(faces):
        if not (isinstance(f, list | tuple | np.ndarray) and len(f) >= 3 and all(
                isinstance(i, int | np.integer) and not isinstance(i, bool) and 0 <= i < nv
                for i in f)):
            raise InputError(f'"faces"[{k}] must list at least 3 vertex indices in '
                             f"0..{nv - 1}", where)


def _numbers(v: object, n: int) -> bool:
    """A sequence of ``n`` numbers (a point, a vector)."""
    return isinstance(v, tuple | list | np.ndarray) and len(v) == n and \
        all(is_number(c) for c in v)


def _check_load(ld: object, dim: int, where: str) -> None:
    """A load as a scene file's reader takes it: a force and a point of the scene's
    dimension, a moment a number (2D) or 3 numbers (3D), ``live`` True, False or None
    (live="false" was live: a non-empty string is true)."""
    if not isinstance(ld, Load):
        raise InputError(f"expected a Load, got {type(ld).__name__}", where)
    if not isinstance(ld.block, str):
        raise InputError(f"block is a block's id, got {ld.block!r}", where)
    if ld.live is not None and not isinstance(ld.live, bool):
        raise InputError(f"live must be True, False or None, got {ld.live!r}", where)
    for key in ("force", "point"):
        v = getattr(ld, key)
        if (v is not None or key == "force") and not _numbers(v, dim):
            raise InputError(f"{key} must be {dim} numbers, got {v!r}", where)
        _finite(v, key, where)
    m = ld.moment
    if m is not None and not (is_number(m) if dim == 2 else _numbers(m, 3)):
        raise InputError(f"moment must be {'a number' if dim == 2 else '3 numbers'} in a "
                         f"{dim}D scene, got {m!r}", where)
    _finite(m, "moment", where)


def _finite(v: object, key: str, where: str) -> None:
    """A number or vector with no NaN or infinity (a NaN force was "beyond 1e+150 ...
    give the scene in other units")."""
    if v is not None and not np.all(np.isfinite(np.asarray(v, dtype=float))):
        raise InputError(f"{key} must be finite, got {v!r}", where)


def _typed_friction(f: object, where: str) -> None:
    """A friction as a scene holds it: a number, or "infinite" (a string with a number
    in it is an argument's spelling, not a scene's)."""
    if isinstance(f, str) and f.strip().lower() not in ("infinite", "inf"):
        raise InputError(f'friction must be a number >= 0 or "infinite", got {f!r}', where)
    _located(friction_value, f, where)


def _located(check: object, value: object, where: str) -> None:
    """``check(value)``, its InputError said at ``where``."""
    try:
        check(value)  # type: ignore[operator]
    except InputError as err:
        raise err.located(where) from None


def _too_large(value: float) -> bool:
    return not (math.isfinite(value) and abs(value) <= LARGEST)


def _beyond(what: str, value: float, remedy: str = "give the scene in other units") -> str:
    return (f"{what} reaches {value:.3g}, beyond {LARGEST:g}: more than the analysis "
            f"carries in double precision (its products and sums would overflow); {remedy}")


def _block_bounds(scene: Scene) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per block: its largest coordinate, the diagonal of its bounding box, and the
    weight of that box (unit weight x area x depth, or x volume), an upper bound on
    the block's weight computed from coordinates alone (without overflow warnings)."""
    verts = np.concatenate([b.points for b in scene.blocks], axis=0)
    starts = np.concatenate([[0], np.cumsum([len(b.vertices) for b in scene.blocks])])
    gamma = np.array([scene.effective_unit_weight if b.unit_weight is None
                      else float(b.unit_weight) for b in scene.blocks])
    depth = scene.effective_depth if scene.dimension == 2 else 1.0
    with np.errstate(all="ignore"):
        lo = np.minimum.reduceat(verts, starts[:-1], axis=0)
        hi = np.maximum.reduceat(verts, starts[:-1], axis=0)
        big = np.maximum(np.abs(lo), np.abs(hi)).max(axis=1)
        extent = hi - lo
        weight = gamma * np.prod(extent, axis=1) * depth
        return big, np.linalg.norm(extent, axis=1), weight


def check_representable(scene: Scene) -> None:
    """Raise :class:`InputError` naming the block or key where a quantity derived from
    the scene is not finite or exceeds :data:`LARGEST`: a block's coordinates, the area
    (volume) and weight of its bounding box (bounds on the block's own, computed
    without an invalid geometry), the live body force on it and the moment of its
    weight, a load's force and moment and the moment of its force about the block.
    Checked before any geometry is computed from them (coordinates of 1e300 gave "zero
    area" after overflow warnings) and so before any solve."""
    if not scene.blocks:
        return
    big, diag, weight = _block_bounds(scene)
    g = max((abs(x) for x in scene.live_body_force or ()), default=0.0)
    name = "its area" if scene.dimension == 2 else "its volume"
    with np.errstate(all="ignore"):
        # (the diagonal to the dimension bounds the box's area or volume: a box
        # 2 x 1e50 x 0.5 read "its volume (bounding box) reaches 1e+150")
        checks = (("a coordinate", big),
                  (f"{name}'s bound (its bounding box's diagonal^{scene.dimension})",
                   diag ** scene.dimension),
                  ("its weight (unit weight x bounding box)", weight),
                  ('its live body force ("live_body_force" x weight)', weight * g),
                  ("the moment of its weight", weight * big))
    free = ~scene.support_mask  # a support's weight is not a load
    for k, (what, values) in enumerate(checks):
        bad = ~(np.abs(values) <= LARGEST) & (free if k >= 2 else True)
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            raise InputError(_beyond(what, float(values[k])),
                             f"block {scene.blocks[k].id!r}")
    reach = dict(zip((b.id for b in scene.blocks), big + diag, strict=True))
    for i, ld in enumerate(scene.loads):
        force = float(np.abs(ld.force).max(initial=0.0))
        arm = reach.get(ld.block, 0.0)
        if ld.point is not None:
            arm += float(np.abs(ld.point).max(initial=0.0))
        moment = float(np.abs(np.atleast_1d(ld.moment)).max(initial=0.0)) \
            if ld.moment is not None else 0.0
        for what, value in (("its force", force), ("its moment", moment),
                            ("the moment of its force about the block", force * arm)):
            if _too_large(value):
                raise InputError(_beyond(what, value), f"load #{i} on block {ld.block!r}")


def check_load_factor(scene: Scene, load_factor: float, what: str = "load factor") -> None:
    """Raise :class:`InputError` where ``load_factor`` times the largest live load (a
    force or moment, or the live body force on a block's weight bound, as
    :func:`check_representable` has them) is not finite or exceeds :data:`LARGEST`
    (``check --load-factor 1e308`` ended in a solver's NumericalError; ``path
    --max-load 1e300`` in an SVD that did not converge). ``what``: the factor's name."""
    live = [float(np.abs(ld.force).max(initial=0.0)) for ld in scene.loads if ld.is_live]
    live += [float(np.abs(np.atleast_1d(ld.moment)).max(initial=0.0))
             for ld in scene.loads if ld.is_live and ld.moment is not None]
    if scene.live_body_force is not None and scene.blocks:
        g = max(abs(x) for x in scene.live_body_force)
        live.append(float(_block_bounds(scene)[2][~scene.support_mask].max(initial=0.0)) * g)
    with np.errstate(all="ignore"):
        top = max(live, default=0.0) * float(load_factor)
    if _too_large(top):
        raise InputError(_beyond(f"{what} = {load_factor:.10g} times the largest live "
                                 "load", top, f"give a smaller {what}"), what)


def check_live_load(scene: Scene, verb: str = "multiply") -> None:
    """Raise :class:`InputError` where the scene has no live load for a limit analysis
    to ``verb``: none declared, or one that is nothing (live point loads of zero force
    and moment, a live body force on free blocks that weigh nothing: a scene without a
    unit weight read UNBOUNDED, as if no load could make it collapse)."""
    if not scene.has_live_load:
        raise InputError("the scene has no live load (no \"live\": true load and no "
                         f"live_body_force): there is nothing to {verb}", scene.source)
    live = [ld for ld in scene.loads if ld.is_live]
    if any(np.any(np.asarray(ld.force, dtype=float) != 0) for ld in live) or \
            any(ld.moment is not None and np.any(np.atleast_1d(ld.moment) != 0)
                for ld in live):
        return
    lbf = scene.live_body_force
    if lbf is not None and any(v != 0 for v in lbf):
        from .geometry import scene_weights

        if np.any(scene_weights(scene)[0][~scene.support_mask] > 0):
            return
        raise InputError("the live body force acts on the free blocks' weight, and they "
                         "weigh nothing (no unit_weight, or 0): there is nothing to "
                         f"{verb}; give the scene a unit_weight, or a live point load",
                         scene.source)
    raise InputError("the scene's live loads are all zero (no force and no moment): "
                     f"there is nothing to {verb}", scene.source)


def _check_ids_and_loads(scene: Scene) -> None:
    seen: set[str] = set()
    for b in scene.blocks:
        if b.id in seen:
            raise InputError("duplicate block id", f"block {b.id!r}")
        seen.add(b.id)
    if not scene.blocks:
        raise InputError("no blocks: the scene's \"blocks\" list is empty", "blocks")
    if not any(b.support for b in scene.blocks):
        raise InputError("no support block: mark at least one block with \"support\": true")
    if all(b.support for b in scene.blocks):
        raise InputError("no free block: every block is a support, there is nothing to analyse")
    for i, ld in enumerate(scene.loads):
        if ld.block not in scene.index:
            raise InputError(f"unknown block {ld.block!r}", f"load #{i}")
        if scene.block(ld.block).support:
            raise InputError(f"block {ld.block!r} is a support: loads go on free blocks only",
                             f"load #{i}")
    pairs: set[frozenset[str]] = set()
    for j in scene.joints:
        where = f"joint {j.blocks[0]!r}-{j.blocks[1]!r}"
        for bid in j.blocks:
            if bid not in scene.index:
                raise InputError(f"unknown block {bid!r}", where)
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
        raise InputError("polygon has zero area (its vertices are collinear or repeated, "
                         "or its outline crosses itself into equal and opposite halves)",
                         f"block {b.id!r}")
    rings = shapely.linearrings(verts, indices=owner)
    simple = shapely.is_simple(rings)
    if not simple.all():
        b = scene.blocks[int(np.flatnonzero(~simple)[0])]
        raise InputError("polygon is self-intersecting (its edges cross or touch)",
                         f"block {b.id!r}")


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
        raise InputError(f"blocks {a!r} and {b!r} overlap (their interiors share an area of "
                         f"{areas[k]:.3g}); blocks may touch but not overlap",
                         f"block {a!r}")


#: a load's point further than this fraction of its block's size from the block is
#: off the block (beyond round-off of a point given on a face)
OFF_BLOCK_TOL = 1e-6


def loads_off_their_blocks(scene: Scene) -> list[tuple[int, str, float]]:
    """The loads whose point lies outside their block: (the load's index in the scene's
    ``loads``, from 0 as the errors count them, the block, the point's distance from it;
    in 3D :func:`~rigidblocks.scene.polyhedra.distance_from`). A load without a point
    acts at its block's centroid and is never off it."""
    found = []
    for k, ld in enumerate(scene.loads):
        if ld.point is None or ld.block not in scene.index:
            continue
        block = scene.block(ld.block)
        pts = np.asarray(block.points, dtype=float)
        p = np.asarray(ld.point, dtype=float)
        size = float(np.linalg.norm(pts.max(axis=0) - pts.min(axis=0)))
        if scene.dimension == 2:
            import shapely

            dist = float(shapely.distance(shapely.Polygon(pts), shapely.Point(p)))
        else:
            from .polyhedra import distance_from

            dist = distance_from(block, p)
        if dist > OFF_BLOCK_TOL * size:
            found.append((k, block.id, dist))
    return found


__all__ = ["validate_scene", "check_overlaps_2d", "block_polygons", "loads_off_their_blocks",
           "scene_size"]

