"""3D structures of convex polyhedral blocks: walls, box stacks, corbel domes, vaults.

Every generator returns a validated 3D :class:`~rigidblocks.scene.Scene` (z up, gravity
-z) with self-weight as the dead load and a horizontal live body force, so that the
load multiplier is a collapse acceleration in g; impossible parameters raise
:class:`~rigidblocks.errors.InputError` with a one-line message. Lengths are in metres,
forces in kN, unit weights in kN/m^3. Every block is a convex polyhedron given by its
corners and its faces, each counter-clockwise seen from outside.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import InputError
from ..io.scene_file import scene_from_dict
from ..scene.model import Scene
from ..scene.polyhedra import prism_faces
from .arches import _num as _number
from .arches import _r, choice, friction_param, integer, items, non_negative, positive
from .limits import MAX_CAPPED_RING, MAX_STACK, at_most, count_at_most

LOAD_DIRECTIONS = ("in_plane", "out_of_plane")
BONDS = ("stack", "running")


# -- plumbing ------------------------------------------------------------------------
def prism(bottom: Sequence[Sequence[float]], top: Sequence[Sequence[float]]) -> tuple[
        list[list[float]], list[list[int]]]:
    """Vertices and faces of the solid between two congruent polygons.

    ``bottom[k]`` and ``top[k]`` are joined by an edge; the faces are the two caps and
    one quadrilateral per side, each counter-clockwise seen from outside
    (:func:`~rigidblocks.scene.polyhedra.prism_faces`).
    """
    verts = [[_r(c) for c in p] for p in (*bottom, *top)]
    return verts, prism_faces(verts[:len(bottom)], verts[len(bottom):])


def box(x0: float, y0: float, z0: float, a: float, b: float, c: float) -> tuple[
        list[list[float]], list[list[int]]]:
    """Vertices and faces of the box [x0, x0+a] x [y0, y0+b] x [z0, z0+c]."""
    base = [(x0, y0, z0), (x0 + a, y0, z0), (x0 + a, y0 + b, z0), (x0, y0 + b, z0)]
    return prism(base, [(x, y, z0 + c) for x, y, _ in base])


def solid(block_id: str, geom: tuple[list, list], support: bool = False) -> dict:
    d: dict[str, Any] = {"id": block_id, "vertices": geom[0], "faces": geom[1]}
    if support:
        d["support"] = True
    return d


def make_scene3d(name: str, blocks: list[dict], *, unit_weight: float, friction: Any,
                 live_body_force: Sequence[float] | None = (1.0, 0.0, 0.0),
                 loads: list[dict] | None = None) -> Scene:
    """Build and validate a 3D scene from block dicts (see docs/scene-format.md)."""
    doc: dict[str, Any] = {"format": "rigidblocks-scene", "version": 1, "name": name,
                           "dimension": 3, "units": {"length": "m", "force": "kN"},
                           "unit_weight": unit_weight, "friction": friction,
                           "blocks": blocks}
    if live_body_force is not None:
        # a seismic body force, for `load`: check and friction answer for the dead load
        doc["live_body_force"] = [float(v) for v in live_body_force]
        doc["load_factor"] = 0
    if loads:
        doc["loads"] = loads
    return scene_from_dict(doc, source=name)


# -- walls ---------------------------------------------------------------------------
def wall3d(courses: int = 6, blocks_per_course: int = 4, block_length: float = 0.4,
           block_height: float = 0.2, thickness: float = 0.3,
           load_direction: str = "out_of_plane", horizontal_load: float = 1.0,
           unit_weight: float = 20.0, friction: Any = 0.6) -> Scene:
    """A single-wythe running-bond wall of boxes on a foundation slab (3D).

    The wall lies in the plane x-z: courses of height h = ``block_height`` stacked along
    z, blocks of length L = ``block_length`` along x, the thickness t along y
    (0 <= y <= t). The bond is that of :func:`rigidblocks.generators.walls.
    running_bond_wall`: even courses hold N = ``blocks_per_course`` full blocks, odd
    courses are offset by L/2 with a half block at each end. The foundation (id
    ``"foundation"``, a support) is the box 0 <= x <= N L, 0 <= y <= t, -h <= z <= 0.
    Block ids are ``c{course}b{index}`` as in 2D.

    Args:
        load_direction: ``in_plane`` (live body force ``[H, 0, 0]`` times each block's
            weight, H = ``horizontal_load``) or ``out_of_plane`` (``[0, H, 0]``).

    Notes:
        Joints: the same J = N (3C - 1) - ceil(C/2) as the plane wall (every joint a
        rectangle, 4 contact points), see :func:`joint_count3d`.

        Out-of-plane collapse of the free-standing wall of height H = C h:
        lambda* = min(f, t / H). Kinematic side: the whole wall overturning about the
        foundation's edge y = t does the work lambda W H / 2 against W t / 2; sliding
        on the foundation gives lambda = f. Static side: the state that is uniform
        along x (each course carries, per unit length, the weight and body force of the
        wall above it, head joints unloaded) puts the resultant on the bed joint at
        height z at t/2 + lambda (H - z) / 2 <= t from the face and needs |T| / N =
        lambda <= f: admissible for lambda <= min(f, t / H).
    """
    from .walls import FOUNDATION_ID, running_bond_wall, wall_blocks

    g = "wall3d"
    direction = choice("load_direction", load_direction, LOAD_DIRECTIONS, g)
    C = integer("courses", courses, g, 1)
    N = integer("blocks_per_course", blocks_per_course, g, 1)
    at_most(g, f"courses {C} x blocks_per_course {N}", wall_blocks(C, N))
    L = positive("block_length", block_length, g)
    h = positive("block_height", block_height, g)
    t = positive("thickness", thickness, g)
    uw = non_negative("unit_weight", unit_weight, g)
    fr = friction_param(friction, g)
    H = _number("horizontal_load", horizontal_load, g)
    plane = running_bond_wall(C, N, L, h, unit_weight=uw, friction=1.0, depth=t)
    blocks = []
    for b in plane.blocks:
        xs = [x for x, _ in b.vertices]
        zs = [z for _, z in b.vertices]
        x0, z0 = min(xs), min(zs)
        blocks.append(solid(b.id, box(x0, 0.0, z0, max(xs) - x0, t, max(zs) - z0),
                            support=b.id == FOUNDATION_ID))
    lbf = (H, 0.0, 0.0) if direction == "in_plane" else (0.0, H, 0.0)
    return make_scene3d(f"3D running-bond wall, {C} courses x {N} blocks, t = {t:g} m, "
                        f"loaded {direction.replace('_', ' ')}", blocks, unit_weight=uw,
                        friction=fr, live_body_force=lbf)


def joint_count3d(courses: int, blocks_per_course: int) -> int:
    """Joints of :func:`wall3d`: ``N (3C - 1) - ceil(C / 2)``, as the plane wall."""
    from .walls import joint_count

    return joint_count(courses, blocks_per_course)


# -- box stacks ----------------------------------------------------------------------
def _offsets(offsets: Any, n: int, g: str) -> list[tuple[float, float]]:
    given = items(offsets)
    if not given:
        return []
    out = []
    for k, it in enumerate(given):
        try:
            dx, dy = (float(v) for v in it)
        except (TypeError, ValueError):
            raise InputError(f"{g}: offsets item #{k} must be two numbers 'dx,dy', got "
                             f"{it!r}") from None
        if not (math.isfinite(dx) and math.isfinite(dy)):
            raise InputError(f"{g}: offsets item #{k} must be finite, got {it!r}")
        out.append((dx, dy))
    if len(out) != n:
        raise InputError(f"{g}: offsets must give one 'dx,dy' per box ({n}), got {len(out)}")
    return out


def box_stack(boxes: int = 4, width: float = 1.0, length: float = 1.0,
              height: float = 0.5, offset: float = 0.0, offsets: Any = "",
              load_azimuth: float = 0.0, unit_weight: float = 20.0,
              friction: Any = 0.6) -> Scene:
    """A stack of ``boxes`` equal boxes on a support slab, under a horizontal live load.

    Box k (k = 0 at the bottom, ids ``box0``, ``box1``, ...) spans width b along x,
    length a along y and height h along z, from z = k h, centred at
    (k x ``offset``, 0) (a staircase when offset != 0) or at ``offsets[k]`` =
    (dx, dy) when given ("dx,dy;dx,dy;..." on the command line, one per box). The slab
    (id ``"slab"``, a support) is a box of height h under the whole stack, larger than
    it by b + a on every side. Each pair of consecutive boxes must overlap.

    The live body force is ``[cos az, sin az, 0]`` times each box's weight,
    az = ``load_azimuth`` in degrees from +x.

    Notes:
        Equal centred boxes, load along x, height H = n h: the resultant of the boxes
        above a bed joint meets it at lambda x (their height) / 2 from its centre, so
        the base joint governs and tipping needs lambda = b / H; sliding needs
        lambda = f (|T| / N = lambda on every bed joint), hence
        lambda* = min(f, b / H); for a load at azimuth az,
        lambda* = min(f, b / (H |cos az|), a / (H |sin az|)).
    """
    g = "box_stack"
    n = integer("boxes", boxes, g, 1)
    at_most(g, f"boxes {n}", n + 1, MAX_STACK)
    b = positive("width", width, g)
    a = positive("length", length, g)
    h = positive("height", height, g)
    s = _number("offset", offset, g)
    az = math.radians(_number("load_azimuth", load_azimuth, g))
    uw = non_negative("unit_weight", unit_weight, g)
    fr = friction_param(friction, g)
    given = _offsets(offsets, n, g)
    centres = given or [(k * s, 0.0) for k in range(n)]
    for k in range(1, n):
        (x0, y0), (x1, y1) = centres[k - 1], centres[k]
        if abs(x1 - x0) >= b or abs(y1 - y0) >= a:
            shift = "offsets" if given else "offset"
            raise InputError(f"{g}: {shift}: box{k} does not overlap box{k - 1} (shift "
                             f"({x1 - x0:g}, {y1 - y0:g}), a box is {b:g} x {a:g})")
    xs = [c[0] for c in centres]
    ys = [c[1] for c in centres]
    mx, my = b + a, b + a
    lo_x, hi_x = min(xs) - b / 2 - mx, max(xs) + b / 2 + mx
    lo_y, hi_y = min(ys) - a / 2 - my, max(ys) + a / 2 + my
    blocks = [solid("slab", box(lo_x, lo_y, -h, hi_x - lo_x, hi_y - lo_y, h), support=True)]
    for k, (cx, cy) in enumerate(centres):
        blocks.append(solid(f"box{k}", box(cx - b / 2, cy - a / 2, k * h, b, a, h)))
    # (to 1e-12 absolute, a unit vector's resolution: at 90 deg cos read 6.12323e-17 in
    # the scene and in the answer's "weight x (6.12323e-17, 1, 0)")
    lbf = (_r(round(math.cos(az), 12)), _r(round(math.sin(az), 12)), 0.0)
    return make_scene3d(f"stack of {n} boxes {b:g} x {a:g} x {h:g} m", blocks,
                        unit_weight=uw, friction=fr, live_body_force=lbf)


# -- corbel dome ---------------------------------------------------------------------
def _sector(ri: float, ro: float, t0: float, t1: float, z0: float, z1: float) -> tuple[
        list, list]:
    """Annular sector between angles t0 < t1 with flat (chord) inner and outer faces."""
    quad = [(ri * math.cos(t0), ri * math.sin(t0)), (ro * math.cos(t0), ro * math.sin(t0)),
            (ro * math.cos(t1), ro * math.sin(t1)), (ri * math.cos(t1), ri * math.sin(t1))]
    return prism([(x, y, z0) for x, y in quad], [(x, y, z1) for x, y in quad])


def corbel_dome(rings: int = 5, blocks_per_ring: int = 12, radius: float = 2.0,
                ring_thickness: float = 0.5, ring_height: float = 0.3,
                overhang: float = 0.15, cap: bool = True, unit_weight: float = 20.0,
                friction: Any = 0.6) -> Scene:
    """A corbel dome: rings of blocks, each ring stepping inwards, on a support slab.

    Ring j (j = 0 at the bottom) spans heights j h <= z <= (j + 1) h, h =
    ``ring_height``, between the inner radius r_j = R - j o (R = ``radius``,
    o = ``overhang``) and r_j + w (w = ``ring_thickness``). It is cut into
    k = ``blocks_per_ring`` blocks by radial planes; odd rings are turned by half a
    block (running bond). Each block is an annular sector with flat inner and outer
    faces (the chords of its arcs): a convex hexahedron of 8 corners; ids
    ``r{j}b{i}``. The slab (id ``"slab"``, a support) is a square of side
    2 (R + w) + 2 w under the dome, of thickness h. With ``cap`` a keystone (id
    ``"cap"``), a 2k-gon prism of height h and circumradius r_top + w/2 (r_top the
    inner radius of the top ring), closes the top; otherwise the top is open.

    The live body force is ``[1, 0, 0]`` times each block's weight.

    Notes:
        Joints (with the cap): k head joints in every ring, k bed joints on the slab,
        2k between consecutive rings (each block straddles two below), and k under
        the cap: J = k (rings + 1 + 2 (rings - 1) + 1); see :func:`dome_joint_count`.
        Needs o < w so that consecutive rings overlap, and r_top > 0.
    """
    g = "corbel_dome"
    n = integer("rings", rings, g, 1)
    k = integer("blocks_per_ring", blocks_per_ring, g, 3)
    R = positive("radius", radius, g)
    w = positive("ring_thickness", ring_thickness, g)
    h = positive("ring_height", ring_height, g)
    o = non_negative("overhang", overhang, g)
    uw = non_negative("unit_weight", unit_weight, g)
    fr = friction_param(friction, g)
    if not isinstance(cap, bool | np.bool_):
        raise InputError(f"{g}: cap must be true or false, got {cap!r}")
    at_most(g, f"rings {n} x blocks_per_ring {k}", n * k + 1 + int(cap))
    count_at_most(g, "blocks_per_ring", k)
    if cap:
        count_at_most(g, "blocks_per_ring", k, MAX_CAPPED_RING,
                      " with cap true (the keystone over them has 2 x blocks_per_ring sides)")
    d = 2 * math.pi / k
    if not o < w:
        raise InputError(f"{g}: overhang must be < ring_thickness ({w:g}) so that each "
                         f"ring overlaps the one below, got {o:g}")
    r_top = R - (n - 1) * o
    if not r_top > 0:
        raise InputError(f"{g}: rings: the top ring would close past the axis (its inner "
                         f"face at {r_top:g} <= 0 from it); use fewer rings or a smaller "
                         "overhang")
    side = R + 2 * w
    blocks = [solid("slab", box(-side, -side, -h, 2 * side, 2 * side, h), support=True)]
    for j in range(n):
        ri = R - j * o
        phase = 0.5 * d * (j % 2)
        for i in range(k):
            t0 = phase + i * d
            blocks.append(solid(f"r{j}b{i}", _sector(ri, ri + w, t0, t0 + d, j * h,
                                                     (j + 1) * h)))
    if cap:
        rc = r_top + 0.5 * w
        ts = [(i + 0.5) * d / 2 for i in range(2 * k)]
        poly = [(rc * math.cos(t), rc * math.sin(t)) for t in ts]
        blocks.append(solid("cap", prism([(x, y, n * h) for x, y in poly],
                                         [(x, y, (n + 1) * h) for x, y in poly])))
    return make_scene3d(f"corbel dome, {n} rings x {k} blocks", blocks, unit_weight=uw,
                        friction=fr)


def dome_joint_count(rings: int, blocks_per_ring: int, cap: bool = True) -> int:
    """Joints of :func:`corbel_dome`: ``k (3 rings - 1 + cap)``."""
    return blocks_per_ring * (3 * rings - 1 + int(cap))


# -- barrel vault --------------------------------------------------------------------
def barrel_vault(voussoirs: int = 9, thickness: float = 0.15, radius: float = 2.0,
                 length: float = 2.0, rings: int = 1, bond: str = "stack",
                 half_angle: float = 90.0, abutment_width: float = 0.6,
                 abutment_height: float = 1.0, unit_weight: float = 20.0,
                 friction: Any = 0.6) -> Scene:
    """A barrel vault: an arch of voussoirs extruded along its axis y, in rings.

    The arch of mean radius R = ``radius`` and thickness t = ``thickness`` x R lies in
    the plane x-z, centred on the y axis, over the angles 90 - a ... 90 + a degrees
    (a = ``half_angle``: 90 is semicircular, less is segmental). Each voussoir has flat
    (chord) intrados and extrados and radial joints: a convex hexahedron. The vault's
    length along y (0 <= y <= ``length``) is cut into ``rings`` equal rings. With
    ``bond = "stack"`` every ring has the same ``voussoirs`` equal voussoirs; with
    ``"running"`` the odd rings are turned by half a voussoir (a half voussoir at each
    springing and voussoirs - 1 full ones between), so that each radial joint of a ring
    is bridged by the neighbouring rings. Ids ``g{ring}v{index}``, index from the
    springing at +x. Two abutments (supports, ids ``abutment_r`` and ``abutment_l``) of
    width ``abutment_width`` beyond the extrados and height ``abutment_height`` run
    under the springing joints along the whole length.

    The live body force is ``[1, 0, 0]`` times each voussoir's weight.

    Notes:
        With one ring (or stack bond) the vault is the 2D arch of the same voussoirs
        (``arch`` with ``arc_points=1``) extruded to depth = length: the same f* and
        lambda* (symmetry about the mid-plane). With running bond, a lower bound of
        lambda* is the smaller of the two rings' own multipliers (the state with no
        force between rings is admissible in the bonded vault).
    """
    g = "barrel_vault"
    n = integer("voussoirs", voussoirs, g, 1)
    ratio = positive("thickness", thickness, g)
    R = positive("radius", radius, g)
    ln = positive("length", length, g)
    m = integer("rings", rings, g, 1)
    bond = choice("bond", bond, BONDS, g)
    count_at_most(g, "voussoirs", n)
    at_most(g, f"rings {m} x voussoirs {n}", m * n + (m // 2 if bond == "running" else 0) + 2)
    a = positive("half_angle", half_angle, g)
    if a > 90 + 1e-12:
        raise InputError(f"{g}: half_angle must be <= 90 degrees, got {half_angle!r}")
    pw = positive("abutment_width", abutment_width, g)
    ph = positive("abutment_height", abutment_height, g)
    uw = non_negative("unit_weight", unit_weight, g)
    fr = friction_param(friction, g)
    if ratio >= 2:
        raise InputError(f"{g}: thickness ratio t/R must be < 2, got {ratio:g}")
    if bond == "running" and n < 2:
        raise InputError(f"{g}: voussoirs must be >= 2 with bond 'running', got {n}")
    ri, ro = R * (1 - ratio / 2), R * (1 + ratio / 2)
    a = math.radians(a)
    t0, t1 = math.pi / 2 - a, math.pi / 2 + a
    d = (t1 - t0) / n
    dy = ln / m
    full = [t0 + i * d for i in range(n + 1)]
    half = [t0, *(t0 + (i + 0.5) * d for i in range(n)), t1]

    def pt(r: float, t: float, y: float) -> tuple[float, float, float]:
        return (r * math.cos(t), y, r * math.sin(t))

    blocks = []
    for g_ in range(m):
        ts = half if (bond == "running" and g_ % 2 == 1) else full
        y0, y1 = g_ * dy, (g_ + 1) * dy
        for i in range(len(ts) - 1):
            quad = [(ri, ts[i]), (ro, ts[i]), (ro, ts[i + 1]), (ri, ts[i + 1])]
            blocks.append(solid(f"g{g_}v{i + 1}", prism([pt(r, t, y0) for r, t in quad],
                                                        [pt(r, t, y1) for r, t in quad])))
    # abutments: the springing joints are the radial segments at t0 and t1
    for side, t in (("r", t0), ("l", t1)):
        sgn = 1.0 if side == "r" else -1.0
        pi, po = (ri * math.cos(t), ri * math.sin(t)), (ro * math.cos(t), ro * math.sin(t))
        zb = min(pi[1], po[1]) - ph
        xo = po[0] + sgn * pw
        poly = [pi, (pi[0], zb), (xo, zb), (xo, po[1])]
        if abs(po[1] - pi[1]) > 1e-12 * R:
            poly.append(po)
        blocks.insert(0 if side == "r" else 1, solid(
            f"abutment_{side}", prism([(x, 0.0, z) for x, z in poly],
                                      [(x, ln, z) for x, z in poly]), support=True))
    kind = "semicircular" if abs(a - math.pi / 2) < 1e-12 else "segmental"
    rings_word = "ring" if m == 1 else "rings"
    return make_scene3d(f"{kind} barrel vault, {m} {rings_word} x {n} voussoirs, {bond} bond",
                        blocks, unit_weight=uw, friction=fr)


__all__ = ["barrel_vault", "box", "box_stack", "corbel_dome", "dome_joint_count",
           "joint_count3d", "make_scene3d", "prism", "wall3d"]
