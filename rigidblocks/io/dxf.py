"""CAD drawings in and out: DXF files (needs the ``cad`` extra, ezdxf).

Reading (:func:`read_dxf`): each closed polyline (LWPOLYLINE or 2D POLYLINE) is a
block, and so is each closed chain of LINE entities, in world coordinates (the x-y
plane: a polyline's own coordinate system, mirrored in CAD, is applied; one drawn in
another plane is refused), block references (INSERT) exploded, layers switched off or
frozen skipped. Real drawings are never exact, so
the reader repairs, within a snapping tolerance ``snap_tol`` (relative to the drawing's
size), what is only round-off (:mod:`rigidblocks.io.dxf_repair`, which needs no CAD
library):

* a polyline whose last vertex nearly equals its first (or that retraces its first
  vertices, A, B, C, D, A, B) is closed where it first comes back to its start;
* repeated vertices along a polyline are dropped;
* vertices of different blocks that nearly coincide are moved onto one point (the
  mean of the cluster), so shared corners match exactly;
* a vertex lying within the tolerance of a neighbour's edge (a T-junction) is moved
  onto that edge, which removes thin overlaps and gaps along joints.

Everything moved is listed in a :class:`DxfReport`. What is beyond the tolerance is
rejected with an :class:`~rigidblocks.errors.InputError` naming the blocks: vertices
of different blocks that are close but not within the tolerance (``near_miss`` times
it), open polylines that do not come back to their start, curved (bulged) segments,
free blocks touching no other block, and overlapping blocks.

The layers :func:`write_dxf` gives an analysis (thrust line, force arrows, text) are
never read as blocks; ``layers`` names the layers to read in other drawings.

Writing (:func:`write_dxf`): the blocks (supports on their own layer), and, given a
result with a force state, the thrust line (through a chain of blocks; elsewhere a
small circle at each loaded joint's resultant) and the joint force arrows (each on the
lower block of its joint, as the pictures draw them) on layers of their own. The
scene's metadata travels with the drawing: each block's polyline carries its id (XDATA
of application ``RIGIDBLOCKS``), and the scene file without the block vertices
(supports, unit weights, friction, loads, joint overrides, units, depth, load factor
...) is stored in an XRECORD ``RIGIDBLOCKS_SCENE`` of the drawing's root dictionary.
Reading such a drawing restores the same scene: the geometry as written (no repair: it
was a validated scene) when every block still carries its id; values given to
:func:`read_dxf` replace the stored ones.

A drawing read without a unit weight (given or stored) has weightless blocks:
``import-dxf`` warns, and every analysis of a scene whose blocks weigh nothing says so
in its notes.
"""

from __future__ import annotations

import json
import logging
import math
import os
from typing import Any

import numpy as np

from ..answer import answer_block
from ..errors import InputError
from ..results import joint_force_vectors, lower_block_forces, unloaded
from ..scene.geometry import signed_area
from ..scene.model import Scene, Units, block_boxes, make_block
from .dxf_repair import DxfReport, Outline, line_loops, repair

log = logging.getLogger(__name__)

#: default snapping tolerance, relative to the drawing's size (bounding-box diagonal)
DEFAULT_SNAP_TOL = 1e-8
#: vertices of different blocks closer than this many tolerances (but not within one)
#: are taken as a drawing error
DEFAULT_NEAR_MISS = 100.0

LAYERS = {"blocks": "RB_BLOCKS", "supports": "RB_SUPPORTS", "thrust": "RB_THRUST_LINE",
          "forces": "RB_FORCES", "text": "RB_TEXT"}
#: layers of an analysis drawn by :func:`write_dxf`: never read as blocks
ANALYSIS_LAYERS = (LAYERS["thrust"], LAYERS["forces"], LAYERS["text"])
#: XDATA application of the block ids, and the root-dictionary key of the scene metadata
APPID = "RIGIDBLOCKS"
META_KEY = "RIGIDBLOCKS_SCENE"
_CHUNK = 240  # characters per string tag
#: import-dxf's warning where no friction is given
NO_FRICTION_NOTE = ("imported without a friction: the joints have infinite friction (no "
                    "sliding) unless an analysis gives one (give it, e.g. import-dxf "
                    "--friction 0.6)")
#: import-dxf's warning where blocks that weigh are given no depth (the weights and the
#: loads' reach scale with it; a multiplier of their own weights does not)
NO_DEPTH_NOTE = ("imported without a depth: the blocks are 1 {unit} deep out of plane, "
                 "their weights per {unit} of wall (give the depth, e.g. import-dxf "
                 "--depth {example} for {example} {units})")

#: the note a scene read without a unit weight carries
NO_UNIT_WEIGHT_NOTE = ("imported from a drawing without a unit weight: the blocks weigh "
                       "nothing, only the loads act (give the unit weight, e.g. "
                       "import-dxf --unit-weight)")


def _ezdxf() -> Any:
    from ..extras import require

    return require("cad", "reading or writing DXF")[0]


# -- reading ------------------------------------------------------------------------
def _xdata_id(e: Any) -> str | None:
    """The block id our writer attached to an entity, if any."""
    try:
        if not e.has_xdata(APPID):
            return None
        tags = e.get_xdata(APPID)
    except Exception:  # noqa: BLE001 - malformed XDATA is no id
        return None
    text = "".join(str(t.value) for t in tags if t.code == 1000)
    return text or None


#: an outline's z may vary by this much of its size: a 2D scene is read from the x-y
#: plane of the world (WCS), and an outline drawn in another plane is refused
PLANE_TOL = 1e-9


def _plane_xy(pts: Any, where: str) -> np.ndarray:
    """The x, y of one outline's points in world coordinates (``pts``, (n, 3)), where
    they lie in a plane z = const; else an InputError naming ``where``."""
    p = np.asarray([tuple(v) for v in pts], dtype=float).reshape(-1, 3)
    bad = np.flatnonzero(~np.isfinite(p).all(axis=1))
    if len(bad):  # (it read "fewer than 3 vertices apart by more than ... nan")
        raise InputError(f"vertex {int(bad[0])} is not a finite number "
                         f"({', '.join(f'{v:g}' for v in p[bad[0]])})", where)
    if len(p):
        size = float(np.ptp(p[:, :2], axis=0).max(initial=0.0))
        dz = float(np.ptp(p[:, 2]))
        if dz > PLANE_TOL * max(size, 1e-300):
            raise InputError(f"not drawn in the x-y plane: its z varies by {dz:.3g} over "
                             f"an outline {size:.3g} across (a 2D scene is read from the "
                             "world's x-y plane: rotate or flatten the drawing in CAD)",
                             where)
    return p[:, :2].copy()


def _entities(msp: Any, report: DxfReport, keep: Any, hidden: Any = None,
              frozen: Any = None
              ) -> tuple[list[Outline], list[tuple[str, str, np.ndarray]], list[str | None]]:
    """The outlines (closed or not) of the polylines, the LINE entities (handle, layer,
    ends (2, 2)) and the block ids our writer attached, of the entities ``msp`` on the
    layers ``keep`` takes, shown (not invisible, not on a layer ``hidden``: switched off
    or frozen), in world coordinates: a polyline's own coordinate system (its extrusion:
    a drawing mirrored in CAD has (0, 0, -1)) is applied, and block references (INSERT,
    MINSERT grids) are placed by their transformation, nested ones too (exploded
    entities lost a rotation under a scale of another axis: a 2 x 1 brick turned by 90
    deg in a reference scaled 2 in y read 2 x 2, where CAD shows 1 x 4), their entities
    on layer 0 on the reference's layer, a reference on a ``frozen`` layer not at all."""
    raws: list[Outline] = []
    lines: list[tuple[str, str, np.ndarray]] = []
    tags: list[str | None] = []

    def skip(kind: str) -> None:
        report.skipped[kind] = report.skipped.get(kind, 0) + 1

    def points(pts: Any, matrix: Any, where: str) -> np.ndarray:
        p = [tuple(v) for v in pts]
        return _plane_xy(p if matrix is None else matrix.transform_vertices(p), where)

    def read(entities: Any, handle: str | None, ref_layer: str | None,
             matrix: Any) -> None:
        for i, e in enumerate(entities):
            kind = e.dxftype()
            # an entity of a block reference: named by the reference, and on its layer
            # where drawn on layer 0 (as CAD shows it)
            h = e.dxf.handle if handle is None else f"{handle}.{i}"
            layer = e.dxf.layer if ref_layer is None or e.dxf.layer != "0" else ref_layer
            if not keep(layer):
                skip(kind)
                continue
            if e.dxf.get("invisible", 0):
                skip(f"{kind} (invisible)")
                continue
            where = f"{report.source}: {kind} #{h}"
            if kind == "INSERT":
                # its layer switched off hides only what it places on layer 0 (checked
                # there); frozen, the whole reference
                if frozen is not None and frozen(layer):
                    skip(f"{kind} (on a frozen layer: {layer})")
                    continue
                try:
                    grid = list(e.multi_insert()) if e.mcount > 1 else [e]
                    placed = [(g.matrix44(), g.block()) for g in grid]
                except Exception as err:  # noqa: BLE001 - ezdxf: a reference it cannot place
                    raise InputError(f"the block reference cannot be placed ({err})",
                                     where) from None
                for k, (m, block) in enumerate(placed):
                    if block is None:
                        raise InputError(f"the block {e.dxf.name!r} it places is not in "
                                         "the drawing", where)
                    read(block, h if len(placed) == 1 else f"{h}[{k}]", layer,
                         m if matrix is None else m @ matrix)
                continue
            if hidden is not None and hidden(layer):
                skip(f"{kind} (on a layer switched off or frozen: {layer})")
                continue
            if kind == "LWPOLYLINE":
                b = np.array([bb for _, _, bb in e.get_points("xyb")], dtype=float)
                if len(b) and np.any(np.abs(b[:-1] if not e.closed else b) > 0):
                    raise InputError("curved (bulged) polyline segments are not "
                                     "supported: replace arcs by straight segments", where)
                raws.append(Outline(h, layer, points(e.vertices_in_wcs(), matrix, where),
                                    bool(e.closed), kind))
                tags.append(_xdata_id(e))
            elif kind == "POLYLINE":
                if not (e.is_2d_polyline or e.is_3d_polyline):
                    skip(kind)
                    continue
                if any(abs(getattr(v.dxf, "bulge", 0.0) or 0.0) > 0 for v in e.vertices):
                    raise InputError("curved (bulged) polyline segments are not supported",
                                     where)
                raws.append(Outline(h, layer, points(e.points_in_wcs(), matrix, where),
                                    bool(e.is_closed), kind))
                tags.append(_xdata_id(e))
            elif kind == "LINE":
                lines.append((h, layer, points([e.dxf.start, e.dxf.end], matrix, where)))
            else:
                skip(kind)

    read(msp, None, None, None)
    return raws, lines, tags


def _metadata(doc: Any, src: str) -> dict | None:
    """The scene metadata our writer stored in the drawing, if any."""
    try:
        xrec = doc.rootdict.get(META_KEY)
    except Exception:  # noqa: BLE001 - a drawing without our dictionary entry
        return None
    if xrec is None or not hasattr(xrec, "tags"):
        return None
    text = "".join(str(t.value) for t in xrec.tags if t.code == 1)
    try:
        meta = json.loads(text)
    except json.JSONDecodeError:
        raise InputError(f"the {META_KEY} metadata is not valid JSON", src) from None
    if not isinstance(meta, dict) or not isinstance(meta.get("blocks"), list):
        raise InputError(f"the {META_KEY} metadata is not a scene without vertices", src)
    return meta


#: the length units of the DXF header's $INSUNITS codes (AutoCAD's; 0: unitless)
INSUNITS = {1: "in", 2: "ft", 4: "mm", 5: "cm", 6: "m", 7: "km", 10: "yd", 14: "dm"}
#: ... in metres
METRES = {"in": 0.0254, "ft": 0.3048, "mm": 1e-3, "cm": 1e-2, "m": 1.0, "km": 1e3,
          "yd": 0.9144, "dm": 0.1}
#: other spellings of ``METRES``' units (--length-unit meter was taken as a unit of
#: its own: no span in metres, no doubt of the blocks' size)
SPELLINGS = {**{w: "m" for w in ("meter", "meters", "metre", "metres")},
             **{w: "mm" for w in ("millimeter", "millimeters", "millimetre", "millimetres")},
             **{w: "cm" for w in ("centimeter", "centimeters", "centimetre", "centimetres")},
             **{w: "dm" for w in ("decimeter", "decimeters", "decimetre", "decimetres")},
             **{w: "km" for w in ("kilometer", "kilometers", "kilometre", "kilometres")},
             "inch": "in", "inches": "in", "\"": "in", "foot": "ft", "feet": "ft",
             "'": "ft", "yard": "yd", "yards": "yd"}


def length_unit(text: str) -> str:
    """A length unit given for a drawing as its short name (``METRES``' keys): "metre"
    is "m", "inches" "in"; a unit none of them names is refused (a furlong was written
    into the scene as its unit)."""
    u = _unit_key(str(text))
    if u not in METRES:
        raise InputError(f"unknown length unit {text!r} (known: {', '.join(METRES)})",
                         "--length-unit")
    return u


#: the sizes of masonry blocks, in metres, outside which a drawing's unit is doubted
#: (:func:`unit_doubt`): bricks and stones from a few centimetres to a few metres
BLOCK_SIZES = (0.02, 3.0)


def _unit_key(unit: str) -> str:
    """A length unit's short name where it is a spelling of one (``SPELLINGS``), else as
    given, lower case."""
    u = unit.strip().lower()
    return SPELLINGS.get(u, u)


def _block_size(scene: Scene) -> float:
    """The blocks' median size: their bounding boxes' largest side, in the scene's
    length unit; the free blocks' where there are any (a 1 x 2 m block on a 5 m base
    read "3.5 m across")."""
    lo, hi = block_boxes(scene)
    size = (hi - lo).max(axis=1)
    free = ~np.asarray(scene.support_mask, dtype=bool)
    return float(np.median(size[free] if free.any() else size))


def _metres(scene: Scene) -> float | None:
    """The scene's length unit in metres (None where it is not one of ``METRES``)."""
    return METRES.get(_unit_key(scene.length_unit))


def span_text(scene: Scene) -> str:
    """The scene's width and height in its length unit, and in metres where that unit
    is known: "1247 x 447.7 in (31.66 x 11.37 m)"."""
    lo, hi = block_boxes(scene)
    w, h = (hi.max(axis=0) - lo.min(axis=0))[:2]
    unit = scene.length_unit or "units"  # ("2500 x 1940 )" where it had none)
    metres = _metres(scene)
    inm = f" ({w * metres:.4g} x {h * metres:.4g} m)" if metres not in (None, 1.0) else ""
    return f"{w:.4g} x {h:.4g} {unit}{inm}"


def unit_doubt(scene: Scene) -> str:
    """Where the blocks' median size (their bounding boxes' largest side) in the
    scene's length unit is no masonry block's size in metres (``BLOCK_SIZES``), what to
    check, else "": a drawing in millimetres whose header declares inches (as some do)
    has blocks metres across, and weighs 25.4^3 times as much per unit weight."""
    metres = _metres(scene)
    if metres is None or not scene.blocks:
        return ""
    size = _block_size(scene)
    low, high = BLOCK_SIZES
    if low <= size * metres <= high:
        return ""
    # (in metres too where the unit is another: "250 m across (the median), 250 m")
    inm = f", {size * metres:.3g} m" if metres != 1.0 else ""
    # the units that make them a block's size, not the one given ("1.5 mm across ...
    # give it with --length-unit (e.g. mm)" to a drawing read in mm)
    own = _unit_key(scene.length_unit)
    fits = [f"{u} ({size * m:.3g} m)" for u, m in METRES.items()
            if u not in ("km", "yd", "dm", own) and low <= size * m <= high]
    which = f"in {' or '.join(fits)}" if fits else "in another unit"
    return (f"the blocks are {size:.4g} {scene.length_unit} across (the median){inm}: if "
            f"the drawing is {which}, give it with --length-unit")


def unit_guess(scene: Scene, code: int = 0) -> str:
    """For a drawing that declares no unit and was given none: the blocks' median size
    in its own units and the units in which that is a masonry block's size
    (``BLOCK_SIZES``): "the blocks are 350 units across (the median): in mm 0.35 m"."""
    if not scene.blocks:
        return ""
    size = _block_size(scene)
    low, high = BLOCK_SIZES
    fits = [f"in {u} {size * m:.3g} m" for u, m in METRES.items()
            if u not in ("km", "yd", "dm") and low <= size * m <= high]
    read = ("; ".join(fits) + ": give the drawing's unit with --length-unit") if fits else \
        "in no common unit a masonry block's size"
    return (f"the drawing declares no length unit this import reads ($INSUNITS {code}) "
            f"and none was given: its lengths are read as they are, the blocks {size:.4g} "
            f"units across (the median): {read}")


def depth_note(scene: Scene) -> str:
    """NO_DEPTH_NOTE in the scene's length unit, its example a wall 0.3 m deep in that
    unit (it read "--depth 300 for 300 m" for a drawing in metres)."""
    metres = _metres(scene)
    if metres:  # two figures: 300 mm, 30 cm, 0.3 m, 12 in, 0.98 ft
        x = 0.3 / metres
    elif scene.blocks:  # no unit: a block's size ("--depth 300 for 300 length unit"
        # of a drawing whose blocks are 3 units across)
        x = _block_size(scene)
    else:
        x = 1.0
    example = f"{round(x, 1 - math.floor(math.log10(x))):g}"
    unit = scene.length_unit
    return NO_DEPTH_NOTE.format(unit=unit or "length unit", units=unit or "length units",
                                example=example)


def _declared_units(doc: Any, units: tuple[str, str] | str | None, rep: DxfReport,
                    adopt: bool = True) -> tuple[str | None, str | None] | None:
    """The scene's units: the drawing's own length unit ($INSUNITS) where none is given
    (and ``adopt``: not where the drawing carries its scene's units); where one is given
    that differs, the one given, said in ``rep.unit_conflict`` (a drawing in millimetres
    read as metres weighs 1e9 times as much)."""
    if isinstance(units, str):
        units = (units, None)
    code = doc.header.get("$INSUNITS", 0)
    declared = INSUNITS.get(int(code)) if isinstance(code, int | float) else None
    rep.declared_unit = declared
    rep.insunits = int(code) if isinstance(code, int | float) else 0
    if declared is None:
        return units
    given = units[0] if units else None
    if given is None:
        if not adopt:
            rep.declared_unit = None
            return units
        return (declared, units[1] if units else None)
    if given.strip().lower() != declared:
        rep.unit_conflict = (f"the drawing declares its lengths in {declared} ($INSUNITS "
                             f"{int(code)}), the length unit given is {given}: its "
                             f"coordinates are read as {given}")
    return units


#: the largest snapping tolerance taken: one that merges corners a hundredth of the
#: drawing's size apart merges its blocks
MAX_SNAP_TOL = 1e-2


def _check_numbers(src: str, *, unit_weight: float | None, depth: float | None,
                   snap_tol: float, near_miss: float) -> None:
    """The import's numbers, as the scene file would take them (a unit weight of -1 was
    written and then refused by every analysis of the scene)."""
    if unit_weight is not None and not unit_weight >= 0:
        raise InputError(f"unit_weight must be >= 0, got {unit_weight:g}", src)
    if depth is not None and not depth > 0:
        raise InputError(f"depth must be > 0, got {depth:g}", src)
    if not 0 < snap_tol <= MAX_SNAP_TOL:
        raise InputError(f"snap_tol must be > 0 and at most {MAX_SNAP_TOL:g} (relative to "
                         f"the drawing's size), got {snap_tol:g}", src)
    if not near_miss >= 0:
        raise InputError(f"near_miss must be >= 0, got {near_miss:g}", src)


def read_dxf(path: str | os.PathLike, *, supports: str | None = None,
             unit_weight: float | None = None, depth: float | None = None,
             friction: Any = None, units: tuple[str, str] | str | None = None,
             live_body_force: tuple[float, float] | None = None, name: str | None = None,
             snap_tol: float = DEFAULT_SNAP_TOL, near_miss: float = DEFAULT_NEAR_MISS,
             layers: list[str] | None = None, report: bool = False) -> Any:
    """Read a 2D DXF drawing as a scene: one block per closed polyline.

    Args:
        path: the DXF file.
        supports: which blocks are supports: ``"lowest"`` (every block reaching the
            lowest y of the drawing, within the tolerance), ``"largest"`` (the block
            of largest area), ``"layer:NAME"`` (every block on layer NAME) or
            ``"ids:b1,b2"`` (block ids as numbered by the reader). Default: the
            supports stored by :func:`write_dxf`, else ``"lowest"``.
        unit_weight, depth, friction, live_body_force, name: scene values (see the
            scene format); None keeps the stored value, or leaves them out.
        units: the length unit, or (length, force), e.g. ``("mm", "kN")``.
        snap_tol: snapping tolerance relative to the drawing's size (bounding-box
            diagonal).
        near_miss: vertices of different blocks closer than ``near_miss x`` the
            tolerance, but not within it, are rejected as a drawing error (0 disables).
        layers: read only entities on these layers (default: every layer but the
            analysis layers :data:`ANALYSIS_LAYERS`).
        report: also return the :class:`DxfReport`.

    Returns:
        The validated :class:`~rigidblocks.scene.Scene` (block ids as stored by
        :func:`write_dxf`, else ``b1``, ``b2``, ... in drawing order), or
        ``(scene, report)`` when ``report`` is true.

    Raises:
        InputError: a message naming the file and the block(s) or entities at fault.
    """
    ezdxf = _ezdxf()
    src = str(path)
    _check_numbers(src, unit_weight=unit_weight, depth=depth, snap_tol=snap_tol,
                   near_miss=near_miss)
    try:
        doc = ezdxf.readfile(src)
    except OSError:
        if os.path.isfile(src) and os.access(src, os.R_OK):  # there, but no DXF
            raise InputError("not a DXF file", src) from None
        if os.path.isdir(src):
            raise InputError("a folder, not a DXF file", src) from None
        raise InputError("no such file or cannot read it", src) from None
    except ezdxf.DXFError as err:
        raise InputError(f"not a valid DXF file: {err}", src) from None
    except (StopIteration, EOFError, ValueError):  # ezdxf's tag reader at a cut-off file
        raise InputError("not a valid DXF file: it ends before its sections do, or holds "
                         "values it cannot read", src) from None
    rep = DxfReport(source=os.path.basename(src), tol=0.0)
    if layers is not None:
        # layer names as DXF compares them, without case; each named must hold lines
        # (WALLS,NOPE read WALLS alone without a word, walls nothing)
        wanted = {name.lower() for name in layers}
        have = sorted({e.dxf.layer for e in doc.modelspace()
                       if e.dxftype() in ("LWPOLYLINE", "POLYLINE", "LINE")})
        drawn = {layer.lower() for layer in have}
        empty = [name for name in layers if name.lower() not in drawn]
        if empty:
            raise InputError(f"no polylines or lines on the layer(s) {', '.join(empty)} "
                             f"(layers with some: {', '.join(have) or 'none'})",
                             f"{src}: layers")

        def keep(layer: str) -> bool:
            return layer.lower() in wanted
        hidden = None  # (layers named are read as named)
    else:
        def keep(layer: str) -> bool:
            return layer not in ANALYSIS_LAYERS

        def hidden(layer: str, off: bool = True) -> bool:
            """Is the layer switched off (``off``) or frozen: not shown in CAD?"""
            try:
                lay = doc.layers.get(layer)
            except Exception:  # noqa: BLE001 - a layer without a table entry is shown
                return False
            return bool((off and lay.is_off()) or lay.is_frozen())
    raws, lines, tags = _entities(doc.modelspace(), rep, keep, hidden,
                                  None if hidden is None else
                                  (lambda layer: hidden(layer, off=False)))
    meta = _metadata(doc, src)
    units = _declared_units(doc, units, rep, adopt=meta is None or "units" not in meta)
    allpts = [r.points for r in raws] + [
        ends for _, _, ends in lines]
    if not allpts:
        raise InputError("no polylines or lines: nothing to make blocks of", src)
    cat = np.concatenate(allpts)
    size = float(np.linalg.norm(cat.max(axis=0) - cat.min(axis=0)))
    tol = snap_tol * size
    rep.tol = tol
    ends = np.array([e.ravel() for _, _, e in lines], dtype=float).reshape(-1, 4)
    loops = line_loops(ends, [h for h, _, _ in lines], [layer for _, layer, _ in lines],
                       tol, rep)
    raws += loops
    tags += [None] * len(loops)
    ids = _ids(tags)
    exact = meta is not None and all(t is not None for t in tags) and not loops
    if exact:  # our own drawing, untouched: the geometry as written
        polys = [r.points for r in raws]
    else:
        polys = repair(raws, ids, tol, near_miss, rep, src)
    rep.reoriented = sum(signed_area(p) < 0 for p in polys)

    if meta is not None:
        rep.restored = True
        scene = _with_metadata(meta, ids, polys, raws, tol, src, supports=supports,
                               unit_weight=unit_weight, depth=depth, friction=friction,
                               units=units, live_body_force=live_body_force, name=name)
        if not exact:
            _validate(scene, tol, size, src)
    else:
        is_support = _supports(supports or "lowest", raws, polys, ids, tol, src)
        blocks = [make_block(bid, p, support=bool(s))
                  for bid, p, s in zip(ids, polys, is_support, strict=True)]
        if isinstance(units, str):
            units = (units, None)
        scene = Scene(dimension=2, blocks=tuple(blocks), name=name,
                      units=Units(*units) if units else None, depth=depth,
                      unit_weight=unit_weight, friction=friction,
                      live_body_force=None if live_body_force is None
                      else tuple(float(v) for v in live_body_force),
                      source=src)
        _validate(scene, tol, size, src)
    rep.n_blocks = len(scene.blocks)
    rep.supports = [b.id for b in scene.blocks if b.support]
    rep.blocks = {bid: r.handle for bid, r in zip(ids, raws, strict=True)}
    log.info("%s", rep.summary())
    return (scene, rep) if report else scene


def _ids(tags: list[str | None]) -> list[str]:
    """Stored ids where present, else b1, b2, ... (skipping ids already taken)."""
    taken = {t for t in tags if t is not None}
    out: list[str] = []
    k = 0
    for t in tags:
        if t is None:
            k += 1
            while f"b{k}" in taken:
                k += 1
            t = f"b{k}"
        out.append(t)
    return out


def _with_metadata(meta: dict, ids: list[str], polys: list[np.ndarray], raws: list[Outline],
                   tol: float, src: str, *, supports: str | None, **given: Any) -> Scene:
    """The scene stored in the drawing, with the drawing's geometry and the values
    ``given`` (those not None) in place of the stored ones."""
    from .scene_file import scene_from_dict

    stored = {b.get("id"): b for b in meta["blocks"] if isinstance(b, dict)}
    seen: set[str] = set()
    blocks = []
    for bid, p in zip(ids, polys, strict=True):
        if bid in seen:
            raise InputError(f"two outlines carry the block id '{bid}'", src)
        seen.add(bid)
        entry = {k: v for k, v in stored.get(bid, {"id": bid}).items() if k != "vertices"}
        entry["vertices"] = [[float(x), float(y)] for x, y in p]
        blocks.append(entry)
    missing = [b for b in stored if b not in seen]
    if missing:
        raise InputError(f"block(s) {', '.join(map(str, missing[:10]))} of the stored scene "
                         "are not in the drawing (on a layer not read?)", src)
    doc = {**meta, "blocks": blocks}
    if supports is not None:
        mask = _supports(supports, raws, polys, ids, tol, src)
        for entry, s in zip(blocks, mask, strict=True):
            entry.pop("support", None)
            if s:
                entry["support"] = True
    units = given.pop("units")
    if isinstance(units, str):
        units = (units, None)
    if units:
        # the stored scene's values are in its own units: a unit given that differs
        # would relabel them unconverted (--force-unit N on a scene in kN: its unit weight
        # 2.5e-8 kN/mm^3 read as N, every force 1000 times too small), and the other unit
        # is kept (it was dropped)
        had = meta.get("units") if isinstance(meta.get("units"), dict) else {}
        for key, v in zip(("length", "force"), units, strict=True):
            if v is not None and had.get(key) not in (None, v):
                opt = "--length-unit" if key == "length" else "--force-unit"
                raise InputError(f"the drawing's scene is in {had[key]} ({key} unit): "
                                 f"{opt} {v} would relabel its values without converting "
                                 f"them; omit {opt}, or convert the scene and export it "
                                 "again", src)
        doc["units"] = {**had, **{k: v for k, v in zip(("length", "force"), units,
                                                      strict=True) if v is not None}}
    lbf = given.pop("live_body_force")
    if lbf is not None:
        doc["live_body_force"] = [float(v) for v in lbf]
    doc.update({k: v for k, v in given.items() if v is not None})
    return scene_from_dict(doc, src)


def _supports(spec: str, raws: list[Outline], polys: list[np.ndarray], ids: list[str],
              tol: float, src: str) -> np.ndarray:
    n = len(polys)
    if spec == "lowest":
        ymin = np.array([p[:, 1].min() for p in polys])
        return ymin <= ymin.min() + tol
    if spec == "largest":
        areas = np.array([abs(signed_area(p)) for p in polys])
        return np.arange(n) == int(np.argmax(areas))
    if spec.startswith("layer:"):
        layer = spec[6:]
        mask = np.array([r.layer == layer for r in raws])
        if not mask.any():
            have = sorted({r.layer for r in raws})
            raise InputError(f"no block on layer '{layer}' (layers: {', '.join(have)})",
                             f"{src}: supports")
        return mask
    if spec.startswith("ids:"):
        want = [s.strip() for s in spec[4:].split(",") if s.strip()]
        unknown = [w for w in want if w not in ids]
        if unknown:
            raise InputError(f"unknown block id(s) {', '.join(unknown)} (blocks are b1.."
                             f"b{n})", f"{src}: supports")
        return np.array([i in want for i in ids])
    raise InputError(f"unknown supports option '{spec}': use 'lowest', 'largest', "
                     "'layer:NAME' or 'ids:b1,b2'", f"{src}: supports")


def _validate(scene: Scene, tol: float, size: float, src: str) -> None:
    from ..contacts import detect_contacts
    from ..scene.validate import validate_scene

    try:
        validate_scene(scene)
    except InputError as err:
        raise err.located(src) from None
    rel = max(tol / size, 1e-7) if size > 0 else 1e-7
    c = detect_contacts(scene, tol=rel)
    touched = np.zeros(len(scene.blocks), bool)
    touched[c.pairs.ravel()] = True
    lonely = [b.id for b, t in zip(scene.blocks, touched, strict=True)
              if not t and not b.support]
    if lonely:
        raise InputError(f"block(s) {', '.join(lonely[:10])}{' ...' if len(lonely) > 10 else ''}"
                         " touch no other block within the tolerance: a gap in the drawing",
                         src)


# -- writing ------------------------------------------------------------------------
def _chunks(text: str) -> list[str]:
    return [text[k:k + _CHUNK] for k in range(0, len(text), _CHUNK)] or [""]


def require_2d(scene: Scene) -> None:
    """Refuse a 3D scene: a drawing holds 2D blocks (callers check before analysing)."""
    if scene.dimension != 2:
        raise InputError("DXF export is for 2D scenes", scene.source)


def write_dxf(scene: Scene, path: str | os.PathLike, result: Any = None, *,
              force_scale: float | None = None) -> None:
    """Write the scene's blocks and metadata and, if ``result`` has a force state, its
    forces.

    Layers: ``RB_BLOCKS`` and ``RB_SUPPORTS`` (closed polylines, each with its block id
    as XDATA), ``RB_THRUST_LINE`` (a polyline through the points where the joint
    resultants cross the joints), ``RB_FORCES`` (one arrow per joint: a line along the
    resultant force on the second block of the joint, drawn from its point of
    application, plus a two-stroke head), ``RB_TEXT`` (the result's headline).
    ``force_scale`` is the drawing length per force unit (default: the largest
    resultant is 10 % of the scene's size). The scene file without the vertices is
    stored in the XRECORD ``RIGIDBLOCKS_SCENE`` (see the module), so that
    :func:`read_dxf` restores the scene.
    """
    ezdxf = _ezdxf()
    from .scene_file import scene_to_dict

    require_2d(scene)
    for b in scene.blocks:  # (a newline in an id wrote a file no reader opens)
        if any(ord(ch) < 32 or ord(ch) == 127 for ch in b.id):
            raise InputError("its id holds a control character (a newline, a tab), which "
                             "a DXF string cannot carry: rename the block",
                             f"block {b.id!r}")
    doc = ezdxf.new("R2010")
    # (every unit the import reads: a scene in ft or dm was written unitless)
    code = {u: k for k, u in INSUNITS.items()}.get(_unit_key(scene.length_unit))
    doc.header["$INSUNITS"] = code or 0
    doc.appids.add(APPID)
    for key, lay in LAYERS.items():
        colour = {"blocks": 7, "supports": 8, "thrust": 1, "forces": 5, "text": 3}[key]
        doc.layers.add(lay, color=colour)
    msp = doc.modelspace()
    for b in scene.blocks:
        pl = msp.add_lwpolyline([tuple(p) for p in b.points], close=True,
                                dxfattribs={"layer": LAYERS["supports" if b.support
                                                           else "blocks"]})
        pl.set_xdata(APPID, [(1000, c) for c in _chunks(b.id)])
    meta = scene_to_dict(scene)
    meta["blocks"] = [{k: v for k, v in bd.items() if k != "vertices"}
                      for bd in meta["blocks"]]
    xrec = doc.rootdict.add_xrecord(META_KEY)
    xrec.reset([(1, c) for c in _chunks(json.dumps(meta, allow_nan=False))])
    state = getattr(result, "state", None)
    if state is not None:
        from ..scene.geometry import scene_size

        c = result.contacts
        size = scene_size(scene)
        is_open = unloaded(c, state)[0]
        if state.thrust_chain:
            msp.add_lwpolyline([tuple(p) for p in state.thrust_line],
                               dxfattribs={"layer": LAYERS["thrust"]})
        else:  # not a chain of blocks: each loaded joint's resultant, as the pictures
            for p in state.thrust_points[~is_open]:
                if np.all(np.isfinite(p)):
                    msp.add_circle(tuple(p), 0.005 * size,
                                   dxfattribs={"layer": LAYERS["thrust"]})
        force = lower_block_forces(scene, c, state)
        mag = np.linalg.norm(force, axis=1)
        if force_scale is None:
            top = mag.max(initial=0.0)
            force_scale = 0.1 * size / top if top > 0 else 0.0
        for p, fvec, m, off in zip(state.thrust_points, force, mag, is_open, strict=True):
            # (an open joint's round-off drew an arrow of three strokes of no length)
            if m <= 0 or off or not np.all(np.isfinite(p)):
                continue
            q = p + force_scale * fvec
            msp.add_line(tuple(p), tuple(q), dxfattribs={"layer": LAYERS["forces"]})
            head = 0.25 * force_scale * m
            u = fvec / m
            nrm = np.array([-u[1], u[0]])
            for sgn in (1, -1):
                msp.add_line(tuple(q), tuple(q - head * u + sgn * 0.4 * head * nrm),
                             dxfattribs={"layer": LAYERS["forces"]})
    title = answer_block(scene, result).title() if result is not None else ""
    if title:
        allpts = np.concatenate([b.points for b in scene.blocks])
        hi = allpts.max(axis=0)
        lo = allpts.min(axis=0)
        h = 0.03 * float(np.linalg.norm(hi - lo))
        msp.add_text(title, height=h, dxfattribs={"layer": LAYERS["text"]}).set_placement(
            (float(lo[0]), float(hi[1] + h)))
    try:
        doc.saveas(os.fspath(path))
    except OSError as err:
        raise InputError(f"cannot write: {err}", str(path)) from None


__all__ = ["ANALYSIS_LAYERS", "DEFAULT_SNAP_TOL", "DxfReport", "LAYERS",
           "NO_UNIT_WEIGHT_NOTE", "joint_force_vectors", "read_dxf", "write_dxf"]
