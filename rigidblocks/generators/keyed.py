"""A keyed (tongue-and-groove) dry-stack wall: a 3D structure of non-convex blocks.

Interlocking mortarless masonry lays units whose beds carry a tongue on top and a
matching groove underneath: the courses lock together against sliding and rocking out
of plane. Each unit here is a prism along the wall's length over a non-convex section
(a rectangle with the groove cut out of its bed and the tongue standing on its top),
so its end faces, and the head joints between units, are non-convex polygons.
"""

from __future__ import annotations

from typing import Any

from ..errors import InputError
from ..io.scene_file import scene_from_dict
from ..scene.model import Scene
from .arches import _num as _number
from .arches import choice, friction_param, integer, non_negative, positive
from .limits import at_most
from .solids import LOAD_DIRECTIONS, box, prism, solid


def keyed_section(t: float, z0: float, z1: float, w: float, k: float, groove: bool,
                  tongue: bool) -> list[tuple[float, float]]:
    """The unit's section (y, z), counter-clockwise seen from +x: the rectangle
    0 <= y <= t, z0 <= z <= z1, less the groove (width w, depth k, centred) in its bed
    and plus the tongue (the same size) on its top."""
    g0, g1 = (t - w) / 2, (t + w) / 2
    pts = [(0.0, z0)]
    if groove:
        pts += [(g0, z0), (g0, z0 + k), (g1, z0 + k), (g1, z0)]
    pts += [(t, z0), (t, z1)]
    if tongue:
        pts += [(g1, z1), (g1, z1 + k), (g0, z1 + k), (g0, z1)]
    pts += [(0.0, z1)]
    return pts


def keyed_wall(courses: int = 6, blocks_per_course: int = 3, block_length: float = 0.4,
               block_height: float = 0.2, thickness: float = 0.3, key_width: float = 0.1,
               key_height: float = 0.05, base_friction: Any = None,
               load_direction: str = "out_of_plane", horizontal_load: float = 1.0,
               unit_weight: float = 20.0, friction: Any = 0.6) -> Scene:
    """A running-bond wall of tongue-and-groove units on a plain foundation (3D).

    The layout is that of :func:`rigidblocks.generators.solids.wall3d` (wall in the plane
    x-z, thickness t along y, courses of height h, odd courses offset by half a unit
    with half units at the ends, foundation ``"foundation"`` under the whole length).
    Every bed joint between courses is keyed: the unit below carries a tongue of width
    ``key_width`` and height ``key_height`` centred on the thickness along its whole
    length, the unit above the matching groove. The bottom course sits flat on the
    foundation and the top course has a flat top, so the wall fills the box
    0 <= x <= N L, 0 <= y <= t, 0 <= z <= H = C h exactly. ``key_height = 0`` gives
    plain boxes (wall3d's wall). ``base_friction`` (default: ``friction``) is the
    friction of the joints on the foundation (a mortar bed under the first course).

    Notes:
        Out-of-plane collapse (live body force ``[0, H_load, 0]`` x weight), keyed:
        lambda* = min(f_base, t / H). Kinematic side: a tongue in its groove forbids
        any relative motion across the key's walls, so no course can slide or rock out
        of plane on the one below (a rotation about an axis along x moves the groove's
        two walls the same way, into the tongue on one side; a rotation about z moves
        the two ends of a wall opposite ways); the wall moves as one body, and the
        mechanisms left are sliding on the foundation (lambda = f_base) and overturning
        about its edge y = t (lambda W H / 2 = W t / 2). Static side: the state of the
        plain wall (resultant at t/2 + lambda (H - z) / 2 on the bed at height z, head
        joints unloaded) with each bed's shear carried by a key wall in compression:
        the flat strips either side of the tongue span the whole thickness, so the bed
        takes the same resultant. The plain wall (``key_height = 0``) slides on any bed
        joint at lambda = f: lambda* = min(f, f_base, t / H).
    """
    from .walls import FOUNDATION_ID, running_bond_wall, wall_blocks

    g = "keyed_wall"
    direction = choice("load_direction", load_direction, LOAD_DIRECTIONS, g)
    C = integer("courses", courses, g, 1)
    N = integer("blocks_per_course", blocks_per_course, g, 1)
    at_most(g, f"courses {C} x blocks_per_course {N}", wall_blocks(C, N))
    L = positive("block_length", block_length, g)
    h = positive("block_height", block_height, g)
    t = positive("thickness", thickness, g)
    w = positive("key_width", key_width, g)
    k = non_negative("key_height", key_height, g)
    uw = non_negative("unit_weight", unit_weight, g)
    fr = friction_param(friction, g)
    fb = None if base_friction is None else friction_param(base_friction, g, "base_friction")
    H = _number("horizontal_load", horizontal_load, g)
    if k > 0 and not w < t:
        raise InputError(f"{g}: key_width must be < thickness, got {w:g} >= {t:g}")
    if not k < h:
        raise InputError(f"{g}: key_height must be < block_height, got {k:g} >= {h:g}")
    plane = running_bond_wall(C, N, L, h, unit_weight=uw, friction=1.0, depth=t)
    blocks = []
    for b in plane.blocks:
        xs = [x for x, _ in b.vertices]
        zs = [z for _, z in b.vertices]
        x0, x1, z0 = min(xs), max(xs), min(zs)
        if b.id == FOUNDATION_ID:
            blocks.append(solid(b.id, box(x0, 0.0, z0, x1 - x0, t, max(zs) - z0), True))
            continue
        course = round(z0 / h)
        sec = keyed_section(t, z0, z0 + h, w, k, groove=k > 0 and course > 0,
                            tongue=k > 0 and course < C - 1)
        blocks.append(solid(b.id, prism([(x0, y, z) for y, z in sec],
                                        [(x1, y, z) for y, z in sec])))
    lbf = [H, 0.0, 0.0] if direction == "in_plane" else [0.0, H, 0.0]
    keys = f"keys {w:g} x {k:g} m" if k > 0 else "no keys"
    doc: dict[str, Any] = {
        "format": "rigidblocks-scene", "version": 1,
        "name": f"3D keyed wall, {C} courses x {N} units, t = {t:g} m, {keys}, loaded "
                f"{direction.replace('_', ' ')}",
        "dimension": 3, "units": {"length": "m", "force": "kN"}, "unit_weight": uw,
        "friction": fr, "blocks": blocks, "live_body_force": lbf,
        # a seismic body force, for `load`: check and friction answer for the dead load
        # (as every generator with one)
        "load_factor": 0}
    if fb is not None:
        doc["joints"] = [{"blocks": [FOUNDATION_ID, b.id], "friction": fb}
                         for b in plane.blocks
                         if b.id != FOUNDATION_ID and min(z for _, z in b.vertices) == 0]
    return scene_from_dict(doc, source=g)
