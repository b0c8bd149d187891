"""Arches of voussoirs: semicircular, pointed and segmental, flat arches and corbel arches.

Every generator returns a validated :class:`~rigidblocks.scene.Scene` (2D, self-weight,
a horizontal live body force ``[1, 0]`` so that the load multiplier is the collapse
acceleration in g) and raises :class:`~rigidblocks.errors.InputError` with a one-line
message on impossible parameters. Lengths are in metres, forces in kN, unit weights in
kN/m^3.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..errors import InputError, finite_number
from ..io.scene_file import scene_from_dict
from ..scene.model import Scene, friction_label
from .limits import MAX_ARC_SEGMENTS, MAX_VERTICAL_VOUSSOIRS, at_most, count_at_most

Point = tuple[float, float]
JOINTS = ("radial", "vertical")
SPRINGINGS = ("abutments", "piers")
SHAPES = ("semicircular", "pointed", "segmental")


# -- plumbing shared by every generator ----------------------------------------------
def positive(name: str, value: Any, gen: str) -> float:
    v = _num(name, value, gen)
    if not v > 0:
        raise InputError(f"{gen}: {name} must be > 0, got {v:g}")
    return v


def non_negative(name: str, value: Any, gen: str) -> float:
    v = _num(name, value, gen)
    if not v >= 0:
        raise InputError(f"{gen}: {name} must be >= 0, got {v:g}")
    return v


def integer(name: str, value: Any, gen: str, minimum: int) -> int:
    try:
        v = int(value)
    except (TypeError, ValueError):
        raise InputError(f"{gen}: {name} must be an integer, got {value!r}") from None
    if v != float(value) or v < minimum:
        raise InputError(f"{gen}: {name} must be an integer >= {minimum}, got {value!r}")
    return v


def choice(name: str, value: Any, options: Sequence[str], gen: str) -> str:
    if value not in options:
        raise InputError(f"{gen}: {name} must be one of {', '.join(options)}, got {value!r}")
    return str(value)


def friction_param(value: Any, gen: str, name: str = "friction") -> float | str:
    """A generator's friction parameter ``name`` as the scene stores it (a number or
    "infinite"), or an error naming the generator and the parameter."""
    try:
        return friction_label(value)  # type: ignore[return-value]
    except InputError as err:  # "friction must be ...": the parameter's name for its own
        raise InputError(f"{gen}: {str(err).replace('friction', name, 1)}") from None


def items(value: Any) -> list[Any]:
    """The items of a list parameter: a list as given, or the command line's string
    form 'a,b;c,d' read as [["a", "b"], ["c", "d"]] (its items' values are the
    generator's to check)."""
    if value is None or isinstance(value, str) and not value.strip():
        return []
    if isinstance(value, str):
        return [[v.strip() for v in s.split(",")] for s in value.split(";") if s.strip()]
    return list(value)


def _num(name: str, value: Any, gen: str) -> float:
    return finite_number(value, f"{gen}: {name}")


def make_scene(name: str, blocks: list[dict], *, unit_weight: float, friction: Any,
               depth: float = 1.0, loads: list[dict] | None = None,
               live_body_force: Sequence[float] | None = (1.0, 0.0),
               units: dict | None = None, joints: list[dict] | None = None) -> Scene:
    """Build and validate a 2D scene from block dicts (see docs/scene-format.md)."""
    doc: dict[str, Any] = {"format": "rigidblocks-scene", "version": 1, "name": name,
                           "dimension": 2, "units": units or {"length": "m", "force": "kN"},
                           "depth": depth, "unit_weight": unit_weight, "friction": friction,
                           "blocks": blocks}
    if loads:
        doc["loads"] = loads
    if live_body_force is not None:
        # a seismic body force, for `load`: check and friction answer for the dead load
        doc["live_body_force"] = list(live_body_force)
        doc["load_factor"] = 0
    if joints:
        doc["joints"] = joints
    return scene_from_dict(doc, source=name)


def block(block_id: str, pts: Sequence[Sequence[float]], support: bool = False) -> dict:
    verts = [[_r(x), _r(y)] for x, y in pts]
    d: dict[str, Any] = {"id": block_id, "vertices": verts}
    if support:
        d["support"] = True
    return d


def _r(v: float) -> float:
    """Round to 12 significant digits so that files stay readable and shared corners
    computed along different paths coincide exactly."""
    v = float(f"{float(v):.12g}")
    return 0.0 if v == 0 else v


def _arc(cx: float, cy: float, r: float, t0: float, t1: float, k: int) -> list[Point]:
    ts = np.linspace(t0, t1, k + 1)
    return [(cx + r * math.cos(t), cy + r * math.sin(t)) for t in ts]


def _mirror(pts: Sequence[Point]) -> list[Point]:
    return [(-x, y) for x, y in reversed(pts)]


def _springing_blocks(left: tuple[Point, Point], right: tuple[Point, Point], springing: str,
                      pier_width: float, pier_height: float) -> list[dict]:
    """Abutments (supports) or free piers on a ground support under the two springing
    joints; ``right`` is (inner, outer) corner of the right springing joint, ``left``
    its mirror (inner, outer)."""
    (pi, po), (li, lo) = right, left
    out = []
    y_base = min(pi[1], po[1]) - pier_height
    for side, (a, b) in (("right", (pi, po)), ("left", (li, lo))):
        sgn = 1.0 if side == "right" else -1.0
        x_out = b[0] + sgn * pier_width
        pts = [a, (a[0], y_base), (x_out, y_base), (x_out, b[1])]
        if abs(b[1] - a[1]) > 1e-12 or abs(b[0] - x_out) < 1e-12:
            pts.append(b)
        if sgn < 0:
            pts = pts[::-1]
        bid = f"{'abutment' if springing == 'abutments' else 'pier'}_{side[0]}"
        out.append(block(bid, pts, support=springing == "abutments"))
    if springing == "piers":
        x_max = max(abs(p[0]) for p in (pi, po, li, lo)) + pier_width
        g = 0.5 * pier_height
        out.append(block("ground", [(-x_max - g, y_base - g), (x_max + g, y_base - g),
                                    (x_max + g, y_base), (-x_max - g, y_base)], support=True))
    return out


# -- curved arches --------------------------------------------------------------------
def arch(shape: str = "semicircular", voussoirs: int | None = None, thickness: float = 0.15,
         radius: float = 2.0, joints: str = "radial", springing: str = "abutments",
         half_angle: float = 60.0, pointedness: float = 0.25, pier_width: float = 0.6,
         pier_height: float = 1.5, unit_weight: float = 20.0, friction: Any = 0.6,
         depth: float = 1.0, arc_points: int = 8) -> Scene:
    """A semicircular, pointed or segmental arch of ``voussoirs`` blocks.

    Args:
        shape: ``semicircular`` (half circle), ``segmental`` (arc of +-``half_angle``
            degrees about the crown) or ``pointed`` (two arcs of mean radius R whose
            centres lie ``pointedness`` x R either side of the span's axis, meeting at a
            vertical crown joint).
        voussoirs: number of voussoirs (None: 15, or 16 for a pointed arch, which
            needs an even number).
        thickness: ring thickness ratio t / R, R the mean radius.
        radius: mean radius R (m).
        joints: ``radial`` (through the centre) or ``vertical``.
        springing: ``abutments`` (fixed support blocks) or ``piers`` (free piers of
            ``pier_width`` beyond the extrados and ``pier_height`` on a ground support).
        arc_points: straight segments per voussoir along the intrados and extrados.

    Notes:
        With radial joints, self-weight only and infinite friction the thinnest
        semicircular arch has t / R = 0.1075 (Milankovitch 1907; Heyman, *The Stone
        Skeleton*, 1995; Ochsendorf 2002), see :func:`rigidblocks.min_thickness`.
    """
    g = "arch"
    shape = choice("shape", shape, SHAPES, g)
    joints = choice("joints", joints, JOINTS, g)
    springing = choice("springing", springing, SPRINGINGS, g)
    if voussoirs is None:
        voussoirs = 16 if shape == "pointed" else 15
    n = integer("voussoirs", voussoirs, g, 1)
    ratio = positive("thickness", thickness, g)
    R = positive("radius", radius, g)
    if ratio >= 2:
        raise InputError(f"{g}: thickness ratio t/R must be < 2, got {ratio:g}")
    pw, ph = positive("pier_width", pier_width, g), positive("pier_height", pier_height, g)
    uw, d = non_negative("unit_weight", unit_weight, g), positive("depth", depth, g)
    k = integer("arc_points", arc_points, g, 1)
    count_at_most(g, "voussoirs", n)
    if joints == "vertical" and shape != "pointed":
        count_at_most(g, "voussoirs", n, MAX_VERTICAL_VOUSSOIRS, " with joints 'vertical'")
    at_most(g, f"voussoirs {n} x arc_points {k}", n * k, MAX_ARC_SEGMENTS, "arc segments")
    fr = friction_param(friction, g)
    ri, ro = R * (1 - ratio / 2), R * (1 + ratio / 2)
    blocks: list[dict] = []
    if shape in ("semicircular", "segmental"):
        a = math.pi / 2 if shape == "semicircular" else math.radians(
            positive("half_angle", half_angle, g))
        if not a <= math.pi / 2 + 1e-12:
            raise InputError(f"{g}: half_angle must be <= 90 degrees, got {half_angle!r}")
        t0, t1 = math.pi / 2 - a, math.pi / 2 + a
        if joints == "radial":
            ts = np.linspace(t0, t1, n + 1)
            for i in range(n):
                pts = _arc(0, 0, ro, ts[i], ts[i + 1], k) + _arc(0, 0, ri, ts[i + 1], ts[i], k)
                blocks.append(block(f"v{i + 1}", pts))
            right = (_pol(ri, t0), _pol(ro, t0))
            left = (_pol(ri, t1), _pol(ro, t1))
        else:
            blocks, right, left = _vertical_ring(0.0, ri, ro, t0, t1, n, k, g)
    else:
        if joints == "vertical":
            raise InputError(f"{g}: joints must be radial in a pointed arch, got {joints!r}")
        if n % 2:
            raise InputError(f"{g}: voussoirs must be an even number in a pointed arch, got {n}")
        e = R * non_negative("pointedness", pointedness, g)
        if not e < ri:
            raise InputError(f"{g}: pointedness must be < 1 - t/(2R) so that the intrados "
                             f"arcs meet, got {pointedness!r}")
        m = n // 2
        # right half: centre (-e, 0); radial joints at equal angles, closing at x = 0
        tc = math.acos(e / R)
        ts = np.linspace(0.0, tc, m + 1)
        if m > 1 and not math.acos(e / ri) > ts[m - 1]:
            raise InputError(f"{g}: voussoirs: with {n}, the last radial joint of a pointed "
                             "arch passes the crown at the intrados; use fewer voussoirs, "
                             "a thinner ring or a smaller pointedness")
        half = []
        for i in range(m):
            if i < m - 1:
                pts = _arc(-e, 0, ro, ts[i], ts[i + 1], k) + _arc(-e, 0, ri, ts[i + 1], ts[i], k)
            else:
                to, ti = math.acos(e / ro), math.acos(e / ri)
                pts = (_arc(-e, 0, ro, ts[i], to, k) + [(0.0, math.sqrt(ri * ri - e * e))]
                       + _arc(-e, 0, ri, ti, ts[i], k)[1:])
                pts[k] = (0.0, math.sqrt(ro * ro - e * e))
            half.append(pts)
        for i, pts in enumerate(half):
            blocks.append(block(f"v{i + 1}", pts))
        for i, pts in enumerate(reversed(half)):
            blocks.append(block(f"v{m + i + 1}", _mirror(pts)))
        right = ((ri - e, 0.0), (ro - e, 0.0))
        left = ((e - ri, 0.0), (e - ro, 0.0))
    blocks += _springing_blocks(left, right, springing, pw, ph)
    name = (f"{shape} arch, {n} voussoir{'s' if n != 1 else ''}, t/R = {ratio:g}, "
            f"{joints} joints, on {springing}")
    return make_scene(name, blocks, unit_weight=uw, friction=fr, depth=d)


def _pol(r: float, t: float) -> Point:
    return (r * math.cos(t), r * math.sin(t))


def _vertical_ring(cx: float, ri: float, ro: float, t0: float, t1: float, n: int, k: int,
                   g: str):
    """Cut the ring between angles t0 < t1 by n - 1 equally spaced vertical lines."""
    from shapely.geometry import Polygon, box

    m = max(64, 8 * k * n)
    ring = Polygon(_arc(cx, 0, ro, t0, t1, m) + _arc(cx, 0, ri, t1, t0, m))
    x0, x1 = ring.bounds[0], ring.bounds[2]
    y0, y1 = ring.bounds[1] - 1, ring.bounds[3] + 1
    xs = np.linspace(x0, x1, n + 1)
    blocks = []
    for i in range(n):
        piece = ring.intersection(box(xs[i], y0, xs[i + 1], y1))
        if piece.geom_type != "Polygon":
            raise InputError(f"{g}: voussoirs: with joints 'vertical', voussoir {i + 1} is cut in "
                             "pieces; use fewer voussoirs or joints 'radial'")
        pts = list(piece.exterior.coords)[:-1]
        blocks.append(block(f"v{i + 1}", pts))
    right = (_pol(ri, t0), _pol(ro, t0))
    left = (_pol(ri, t1), _pol(ro, t1))
    return blocks, right, left


def stocky_arch(voussoirs: int = 7, thickness: float = 0.6, radius: float = 1.5,
                joints: str = "radial", springing: str = "piers", pier_width: float = 0.6,
                pier_height: float = 1.5, unit_weight: float = 20.0, friction: Any = 0.6,
                depth: float = 1.0) -> Scene:
    """A thick semicircular arch of few voussoirs (the seed's Fig. 7a).

    The seed does not publish the geometry; the defaults (t / R = 0.6, seven voussoirs,
    free piers) are a stocky arch whose thrust line strays far from the ring's axis, so
    that the joints near the haunches carry shear comparable with their normal force.
    """
    return arch("semicircular", voussoirs, thickness, radius, joints, springing,
                pier_width=pier_width, pier_height=pier_height, unit_weight=unit_weight,
                friction=friction, depth=depth).with_changes(
        name=f"stocky arch, {voussoirs} voussoir{'s' if voussoirs != 1 else ''}, "
             f"t/R = {thickness:g}, on {springing}")


# -- flat arch ------------------------------------------------------------------------
def flat_arch(span: float = 2.0, height: float = 0.4, voussoirs: int = 9,
              joints: str = "radial", centre_depth: float = 1.5, pier_width: float = 1.0,
              pier_height: float = 1.0, springing: str = "piers", unit_weight: float = 20.0,
              friction: Any = 0.6, depth: float = 1.0, bonded_piers: bool = False) -> Scene:
    """A flat arch (platband) of ``voussoirs`` blocks, intrados at y = 0.

    Args:
        span: clear span between the skewbacks at the intrados.
        height: depth of the platband.
        joints: ``vertical``, or ``radial``: every joint on a line through the centre
            (0, -``centre_depth``); the end joints then lean by
            atan(span / (2 centre_depth)) from the vertical.
        springing: ``piers`` (free piers of ``pier_width`` beyond the skewback's top and
            ``pier_height`` below the intrados, on a ground support) or ``abutments``
            (fixed; then the thrust is unbounded and the required friction tends to 0).
        bonded_piers: the piers' bed joints on the ground never slide (a joint override
            of infinite friction), so that only the platband's own joints and skewbacks
            enter the friction problem.
    """
    g = "flat_arch"
    L, h = positive("span", span, g), positive("height", height, g)
    n = integer("voussoirs", voussoirs, g, 1)
    joints = choice("joints", joints, JOINTS, g)
    springing = choice("springing", springing, SPRINGINGS, g)
    count_at_most(g, "voussoirs", n)
    c = positive("centre_depth", centre_depth, g)
    pw, ph = positive("pier_width", pier_width, g), positive("pier_height", pier_height, g)
    uw, d = non_negative("unit_weight", unit_weight, g), positive("depth", depth, g)
    fr = friction_param(friction, g)
    xs = np.linspace(-L / 2, L / 2, n + 1)
    top = xs * (c + h) / c if joints == "radial" else xs
    blocks = [block(f"v{i + 1}", [(xs[i], 0), (xs[i + 1], 0), (top[i + 1], h), (top[i], h)])
              for i in range(n)]
    right = ((xs[-1], 0.0), (top[-1], h))
    left = ((xs[0], 0.0), (top[0], h))
    blocks += _flat_springing(left, right, springing, pw, ph)
    extra = f", centre {c:g} below" if joints == "radial" else ""
    name = (f"flat arch, span {L:g}, {n} voussoir{'s' if n != 1 else ''}, {joints} "
            f"joints{extra}, on {springing}")
    overrides = None
    if bonded_piers and springing == "piers":
        overrides = [{"blocks": [p, "ground"], "friction": "infinite"}
                     for p in ("pier_l", "pier_r")]
    return make_scene(name, blocks, unit_weight=uw, friction=fr, depth=d, joints=overrides)


def _flat_springing(left, right, springing, pw, ph) -> list[dict]:
    out = []
    (ri, ro) = right
    y_base = ri[1] - ph
    for side, (a, b) in (("r", right), ("l", left)):
        s = 1.0 if side == "r" else -1.0
        x_out = b[0] + s * pw
        pts = [(a[0], y_base), (x_out, y_base), (x_out, b[1]), b, a]
        if s < 0:
            pts = pts[::-1]
        bid = f"{'abutment' if springing == 'abutments' else 'pier'}_{side}"
        out.append(block(bid, pts, support=springing == "abutments"))
    if springing == "piers":
        x_max = abs(ro[0]) + pw + 0.5 * ph
        out.append(block("ground", [(-x_max, y_base - 0.5 * ph), (x_max, y_base - 0.5 * ph),
                                    (x_max, y_base), (-x_max, y_base)], support=True))
    return out


# -- corbel arches -------------------------------------------------------------------
def _stacks(inner: Sequence[Point], outer_x: float, incl: float, cap: float) -> list[dict]:
    """Two mirrored stacks of courses. ``inner`` lists the inner-face corners P_0..P_m of
    the right stack (P_m on the axis x = 0); bed joint j passes through P_j and rises
    outwards with slope tan(incl) (the base joint j = 0 is horizontal). The top course
    is closed by a vertical crown joint from P_m up to P_m + cap."""
    t = math.tan(incl)

    def bed(j: int, x: float) -> float:
        return inner[j][1] + (0.0 if j == 0 else (x - inner[j][0]) * t)

    m = len(inner) - 1
    right = []
    for j in range(m):
        p, q = inner[j], inner[j + 1]
        pts = [p, (outer_x, bed(j, outer_x))]
        if j < m - 1:
            pts += [(outer_x, bed(j + 1, outer_x)), q]
        else:
            y_top = q[1] + cap
            pts += [(outer_x, max(y_top, bed(j, outer_x) + cap)), (0.0, y_top), q]
        right.append(pts)
    blocks = []
    for j, pts in enumerate(right):
        blocks.append(block(f"r{j + 1}", pts))
        blocks.append(block(f"l{j + 1}", _mirror(pts)))
    x_g = outer_x + cap
    blocks.append(block("ground", [(-x_g, -cap), (x_g, -cap), (x_g, 0), (-x_g, 0)],
                        support=True))
    return blocks


def corbel_arch(opening: float = 2.0, courses: int = 6, course_height: float = 0.3,
                block_length: float = 0.6, pattern: str = "horizontal", inclination: float = 10.0,
                unit_weight: float = 20.0, friction: Any = 0.6, depth: float = 1.0) -> Scene:
    """A corbel (false) arch: two stacks of ``courses`` courses on a ground support,
    each course overhanging the one below by opening / (2 (courses - 1)), the top
    courses meeting at a vertical crown joint (the seed's Fig. 7b, 7c).

    Args:
        opening: clear width at the base.
        block_length: horizontal length of every course block (it must exceed the
            overhang so that consecutive courses overlap).
        pattern: ``horizontal`` bed joints, or ``inclined``: bed joints dip towards the
            opening by ``inclination`` degrees (rising outwards).
    """
    g = "corbel_arch"
    L = positive("opening", opening, g)
    m = integer("courses", courses, g, 2)
    at_most(g, f"courses {m}", 2 * m + 1)
    hc, w = positive("course_height", course_height, g), positive(
        "block_length", block_length, g)
    pattern = choice("pattern", pattern, ("horizontal", "inclined"), g)
    beta = non_negative("inclination", inclination, g) if pattern == "inclined" else 0.0
    if beta >= 45:
        raise InputError(f"{g}: inclination must be < 45 degrees, got {inclination!r}")
    uw, d = non_negative("unit_weight", unit_weight, g), positive("depth", depth, g)
    fr = friction_param(friction, g)
    o = L / (2 * (m - 1))
    if not w > o:
        raise InputError(f"{g}: block_length must exceed the overhang opening / (2 (courses"
                         f" - 1)) = {o:g}, got {w:g}")
    xs = [L / 2 - j * o for j in range(m - 1)] + [0.0]
    blocks = _stepped(xs, w, math.radians(beta), hc)
    name = f"corbel arch, opening {L:g}, {m} courses, {pattern} joints" + (
        f" ({beta:g} deg)" if pattern == "inclined" else "")
    return make_scene(name, blocks, unit_weight=uw, friction=fr, depth=d)


def _stepped(xs: Sequence[float], length: float, incl: float, hc: float) -> list[dict]:
    """Two mirrored stepped stacks: course j (j = 0..m-1) is a block of horizontal
    ``length`` whose inner face is at x = xs[j] (xs[m-1] = 0: the top courses meet at a
    vertical crown joint). Bed joint j (j >= 1) passes through the inner corner
    (xs[j], j hc) and rises outwards with slope tan(incl); the base joint is horizontal
    and the top of the last course passes through (0, m hc)."""
    t = math.tan(incl)
    m = len(xs)
    ref = list(xs) + [0.0]

    def bed(j: int, x: float) -> float:
        return 0.0 if j == 0 else j * hc + (x - ref[j]) * t

    blocks = []
    for j in range(m):
        x, xo = xs[j], xs[j] + length
        pts = [(x, bed(j, x)), (xo, bed(j, xo)), (xo, bed(j + 1, xo)), (x, bed(j + 1, x))]
        blocks.append(block(f"r{j + 1}", pts))
        blocks.append(block(f"l{j + 1}", _mirror(pts)))
    x_g = xs[0] + length + hc
    blocks.append(block("ground", [(-x_g, -hc), (x_g, -hc), (x_g, 0), (-x_g, 0)],
                        support=True))
    return blocks


def arpino_gate(opening: float = 2.4, height: float = 3.6, courses: int = 9,
                joint_inclination: float = 5.0, wall: float = 0.4,
                unit_weight: float = 20.0, friction: Any = 0.6, depth: float = 1.0) -> Scene:
    """A pointed corbelled gate of dry stone (after the gate of Civitavecchia di Arpino,
    the seed's Fig. 8): two stacks of ``courses`` courses whose inner faces follow the
    straight sides of a pointed opening ``opening`` wide at the ground and ``height``
    high at the apex, closed by a capping course with a vertical crown joint; bed
    joints dip towards the opening by ``joint_inclination`` degrees; unit weight
    20 kN/m^3. The survey of the gate is not published in the seed: the defaults are
    indicative proportions.
    """
    g = "arpino_gate"
    L, H = positive("opening", opening, g), positive("height", height, g)
    m = integer("courses", courses, g, 2)
    at_most(g, f"courses {m}", 2 * m + 1)
    beta = non_negative("joint_inclination", joint_inclination, g)
    if beta >= 45:
        raise InputError(f"{g}: joint_inclination must be < 45 degrees, got "
                         f"{joint_inclination!r}")
    w = positive("wall", wall, g)
    uw, d = non_negative("unit_weight", unit_weight, g), positive("depth", depth, g)
    fr = friction_param(friction, g)
    hc = H / m
    inner = [(L / 2 * (1 - j / m), j * hc) for j in range(m + 1)]
    blocks = _stacks(inner, L / 2 + w, math.radians(beta), hc)
    name = (f"pointed corbelled gate (Arpino), opening {L:g}, height {H:g}, {m} courses, "
            f"joints {beta:g} deg")
    return make_scene(name, blocks, unit_weight=uw, friction=fr, depth=d)


__all__ = ["arch", "arpino_gate", "corbel_arch", "flat_arch", "stocky_arch"]
