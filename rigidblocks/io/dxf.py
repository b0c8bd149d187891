"""CAD drawings in and out: DXF files (needs the ``cad`` extra, ezdxf).

Reading (:func:`read_dxf`): each closed polyline (LWPOLYLINE or 2D POLYLINE) is a
block, and so is each closed chain of LINE entities. Real drawings are never exact, so
the reader repairs, within a snapping tolerance ``snap_tol`` (relative to the drawing's
size), what is only round-off:

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

Writing (:func:`write_dxf`): the blocks (supports on their own layer), and, given a
result with a force state, the thrust line and the joint force arrows on layers of
their own.
"""

from __future__ import annotations

import logging
import os
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import InputError
from ..results import headline
from ..scene.geometry import signed_area
from ..scene.model import Scene, Units, make_block

log = logging.getLogger(__name__)

#: default snapping tolerance, relative to the drawing's size (bounding-box diagonal)
DEFAULT_SNAP_TOL = 1e-8
#: vertices of different blocks closer than this many tolerances (but not within one)
#: are taken as a drawing error
DEFAULT_NEAR_MISS = 100.0

LAYERS = {"blocks": "RB_BLOCKS", "supports": "RB_SUPPORTS", "thrust": "RB_THRUST_LINE",
          "forces": "RB_FORCES", "text": "RB_TEXT"}


def _ezdxf():
    try:
        import ezdxf
    except ImportError:  # pragma: no cover - depends on the environment
        raise InputError("reading or writing DXF needs the ezdxf package: "
                         "pip install 'rigidblocks[cad]'") from None
    return ezdxf


@dataclass
class DxfReport:
    """What the importer found and repaired.

    Attributes:
        source: the file name.
        tol: the absolute snapping tolerance used (drawing units).
        n_blocks: blocks read.
        closed_by_snap: blocks whose polyline came back to its start (within the
            tolerance) and was closed there.
        retraced: blocks whose polyline retraced its first vertices (dropped).
        duplicates_dropped: repeated vertices removed along polylines.
        vertices_snapped: vertices moved onto a neighbour's corner.
        edges_snapped: vertices moved onto a neighbour's edge (T-junctions).
        max_move: largest distance a vertex was moved.
        reoriented: blocks given clockwise (the scene keeps any orientation; counted
            for information).
        skipped: entities that are not blocks, counted by kind (e.g. POINT, TEXT).
        supports: ids of the support blocks.
        blocks: block id -> DXF handle(s) of the entity or entities it came from.
    """

    source: str
    tol: float
    n_blocks: int = 0
    closed_by_snap: list[str] = field(default_factory=list)
    retraced: list[str] = field(default_factory=list)
    duplicates_dropped: int = 0
    vertices_snapped: int = 0
    edges_snapped: int = 0
    max_move: float = 0.0
    reoriented: int = 0
    skipped: dict[str, int] = field(default_factory=dict)
    supports: list[str] = field(default_factory=list)
    blocks: dict[str, str] = field(default_factory=dict)

    def summary(self) -> str:
        """One line: what was read and what was repaired."""
        skipped = ", ".join(f"{n} {k}" for k, n in sorted(self.skipped.items())) or "none"
        return (f"{self.source}: {self.n_blocks} blocks ({len(self.supports)} support: "
                f"{', '.join(self.supports)}); snapped {self.vertices_snapped} corners and "
                f"{self.edges_snapped} T-junction vertices (largest move {self.max_move:.3g}, "
                f"tolerance {self.tol:.3g}); closed {len(self.closed_by_snap)} polylines by "
                f"snapping ({len(self.retraced)} retracing); dropped "
                f"{self.duplicates_dropped} repeated vertices; {self.reoriented} clockwise; "
                f"skipped {skipped}")


# -- reading ------------------------------------------------------------------------
@dataclass
class _Raw:
    handle: str
    layer: str
    points: np.ndarray  # (n, 2), open list (no repeated closing vertex)
    closed_flag: bool
    kind: str


def _entities(msp: Any, report: DxfReport) -> tuple[list[_Raw], list[Any]]:
    raws: list[_Raw] = []
    lines: list[Any] = []
    for e in msp:
        kind = e.dxftype()
        if kind == "LWPOLYLINE":
            pts = np.array([(x, y, b) for x, y, b in e.get_points("xyb")], dtype=float)
            if len(pts) and np.any(np.abs(pts[:-1, 2] if not e.closed else pts[:, 2]) > 0):
                raise InputError("curved (bulged) polyline segments are not supported: "
                                 "replace arcs by straight segments",
                                 f"{report.source}: LWPOLYLINE #{e.dxf.handle}")
            raws.append(_Raw(e.dxf.handle, e.dxf.layer, pts[:, :2].copy(), bool(e.closed),
                             kind))
        elif kind == "POLYLINE":
            if not (e.is_2d_polyline or e.is_3d_polyline):
                report.skipped[kind] = report.skipped.get(kind, 0) + 1
                continue
            verts = list(e.vertices)
            if any(abs(getattr(v.dxf, "bulge", 0.0) or 0.0) > 0 for v in verts):
                raise InputError("curved (bulged) polyline segments are not supported",
                                 f"{report.source}: POLYLINE #{e.dxf.handle}")
            pts = np.array([(v.dxf.location[0], v.dxf.location[1]) for v in verts], float)
            raws.append(_Raw(e.dxf.handle, e.dxf.layer, pts.reshape(-1, 2), bool(e.is_closed),
                             kind))
        elif kind == "LINE":
            lines.append(e)
        else:
            report.skipped[kind] = report.skipped.get(kind, 0) + 1
    return raws, lines


def _line_loops(lines: list[Any], tol: float, report: DxfReport) -> list[_Raw]:
    """Closed chains of LINE entities (each end shared by exactly two lines)."""
    if not lines:
        return []
    ends = np.array([[e.dxf.start[0], e.dxf.start[1], e.dxf.end[0], e.dxf.end[1]]
                     for e in lines], dtype=float)
    pts = ends.reshape(-1, 2)
    node = _cluster(pts, tol)
    a, b = node[0::2], node[1::2]
    adj: dict[int, list[int]] = {}
    for k in range(len(lines)):
        adj.setdefault(int(a[k]), []).append(k)
        adj.setdefault(int(b[k]), []).append(k)
    used = np.zeros(len(lines), bool)
    loops: list[_Raw] = []
    centers = np.zeros((node.max() + 1, 2))
    np.add.at(centers, node, pts)
    centers /= np.bincount(node)[:, None]
    for k0 in range(len(lines)):
        if used[k0]:
            continue
        chain, nodes, k, cur = [k0], [int(a[k0])], k0, int(b[k0])
        used[k0] = True
        ok = True
        while cur != nodes[0]:
            nxt = [j for j in adj[cur] if not used[j]]
            if len(adj[cur]) != 2 or not nxt:
                ok = False
                break
            k = nxt[0]
            used[k] = True
            chain.append(k)
            nodes.append(cur)
            cur = int(b[k]) if int(a[k]) == cur else int(a[k])
        handles = ",".join(lines[j].dxf.handle for j in chain)
        if not ok or len(nodes) < 3:
            raise InputError("LINE entities that do not form a closed chain (an end meets "
                             "no other line, or more than two, within the tolerance "
                             f"{tol:.3g})", f"{report.source}: LINEs #{handles}")
        loops.append(_Raw(handles, lines[k0].dxf.layer, centers[nodes], True, "LINE"))
    return loops


def _cluster(pts: np.ndarray, tol: float) -> np.ndarray:
    """Label points so that points within ``tol`` of each other (transitively) share one."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    pairs = cKDTree(pts).query_pairs(tol, output_type="ndarray") if len(pts) else \
        np.zeros((0, 2), int)
    n = len(pts)
    g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    return connected_components(g, directed=False)[1]


def _close_polyline(raw: _Raw, tol: float, bid: str, report: DxfReport) -> np.ndarray:
    pts = raw.points
    # repeated consecutive vertices
    if len(pts) > 1:
        keep = np.r_[True, np.linalg.norm(np.diff(pts, axis=0), axis=1) > tol]
        report.duplicates_dropped += int((~keep).sum())
        pts = pts[keep]
    # where does it come back to its start?
    back = np.flatnonzero(np.linalg.norm(pts - pts[0], axis=1) <= tol)
    back = back[back >= 3]
    if len(back):
        k = int(back[0])
        tail = pts[k:]
        if k < len(pts) - 1:
            # retracing: the rest must follow the first vertices again
            n = len(tail)
            idx = np.arange(n) % k
            if np.any(np.linalg.norm(tail - pts[idx], axis=1) > tol):
                raise InputError("polyline comes back to its start and then goes on along "
                                 "a different path", f"{report.source}: {raw.kind} "
                                 f"#{raw.handle} (block '{bid}')")
            report.retraced.append(bid)
        report.closed_by_snap.append(bid)
        pts = pts[:k]
    elif not raw.closed_flag:
        gap = float(np.linalg.norm(pts[-1] - pts[0])) if len(pts) else 0.0
        raise InputError(f"open polyline: its ends are {gap:.6g} apart, more than the "
                         f"snapping tolerance {tol:.3g}", f"{report.source}: {raw.kind} "
                         f"#{raw.handle} (block '{bid}')")
    if len(pts) < 3:
        raise InputError("closed polyline with fewer than 3 distinct vertices",
                         f"{report.source}: {raw.kind} #{raw.handle} (block '{bid}')")
    return pts


def _snap_to_edges(polys: list[np.ndarray], tol: float, report: DxfReport) -> None:
    """Move vertices lying within ``tol`` of another block's edge onto that edge."""
    import shapely

    owner_e, a_list, b_list = [], [], []
    for i, p in enumerate(polys):
        owner_e.append(np.full(len(p), i))
        a_list.append(p)
        b_list.append(np.roll(p, -1, axis=0))
    owner_e = np.concatenate(owner_e)
    a = np.concatenate(a_list)
    b = np.concatenate(b_list)
    vowner = owner_e
    vidx = np.concatenate([np.arange(len(p)) for p in polys])
    verts = a
    tree = shapely.STRtree(shapely.linestrings(np.stack([a, b], axis=1)))
    vi, ei = tree.query(shapely.points(verts), predicate="dwithin", distance=tol)
    m = vowner[vi] != owner_e[ei]
    vi, ei = vi[m], ei[m]
    if not len(vi):
        return
    d = b[ei] - a[ei]
    L2 = np.einsum("ij,ij->i", d, d)
    t = np.einsum("ij,ij->i", verts[vi] - a[ei], d) / np.where(L2 > 0, L2, 1.0)
    proj = a[ei] + np.clip(t, 0, 1)[:, None] * d
    dist = np.linalg.norm(verts[vi] - proj, axis=1)
    inner = (t > 0) & (t < 1) & (dist > 0)
    for v, p, dd in zip(vi[inner], proj[inner], dist[inner], strict=True):
        blk, k = int(vowner[v]), int(vidx[v])
        # move each vertex once, onto the nearest edge
        if np.linalg.norm(polys[blk][k] - verts[v]) == 0:
            polys[blk][k] = p
            report.edges_snapped += 1
            report.max_move = max(report.max_move, float(dd))


def _near_misses(pts: np.ndarray, owner: np.ndarray, tol: float, near_miss: float,
                 ids: list[str]) -> list[tuple[str, str, float]]:
    from scipy.spatial import cKDTree

    if near_miss <= 1:
        return []
    pairs = cKDTree(pts).query_pairs(near_miss * tol, output_type="ndarray")
    if not len(pairs):
        return []
    d = np.linalg.norm(pts[pairs[:, 0]] - pts[pairs[:, 1]], axis=1)
    bad = (d > 0) & (owner[pairs[:, 0]] != owner[pairs[:, 1]])
    out = []
    for (i, j), dd in zip(pairs[bad], d[bad], strict=True):
        out.append((ids[owner[i]], ids[owner[j]], float(dd)))
    return out


def read_dxf(path: str | os.PathLike, *, supports: str = "lowest",
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
            ``"ids:b1,b2"`` (block ids as numbered by the reader).
        unit_weight, depth, friction, live_body_force, name: scene values (see the
            scene format); None leaves them out.
        units: the length unit, or (length, force), e.g. ``("mm", "kN")``.
        snap_tol: snapping tolerance relative to the drawing's size (bounding-box
            diagonal).
        near_miss: vertices of different blocks closer than ``near_miss x`` the
            tolerance, but not within it, are rejected as a drawing error (0 disables).
        layers: read only entities on these layers (default: all).
        report: also return the :class:`DxfReport`.

    Returns:
        The validated :class:`~rigidblocks.scene.Scene` (block ids ``b1``, ``b2``, ...
        in drawing order), or ``(scene, report)`` when ``report`` is true.

    Raises:
        InputError: a message naming the file and the block(s) or entities at fault.
    """
    ezdxf = _ezdxf()
    src = str(path)
    try:
        doc = ezdxf.readfile(src)
    except OSError:
        raise InputError("no such file or cannot read it", src) from None
    except ezdxf.DXFError as err:
        raise InputError(f"not a valid DXF file: {err}", src) from None
    rep = DxfReport(source=os.path.basename(src), tol=0.0)
    raws, lines = _entities(doc.modelspace(), rep)
    if layers is not None:
        keep = set(layers)
        raws = [r for r in raws if r.layer in keep]
        lines = [e for e in lines if e.dxf.layer in keep]
    allpts = [r.points for r in raws] + [
        np.array([[e.dxf.start[0], e.dxf.start[1]], [e.dxf.end[0], e.dxf.end[1]]])
        for e in lines]
    if not allpts:
        raise InputError("no polylines or lines: nothing to make blocks of", src)
    cat = np.concatenate(allpts)
    size = float(np.linalg.norm(cat.max(axis=0) - cat.min(axis=0)))
    tol = snap_tol * size
    rep.tol = tol
    raws += _line_loops(lines, tol, rep)
    ids = [f"b{i + 1}" for i in range(len(raws))]
    polys = [_close_polyline(r, tol, bid, rep) for r, bid in zip(raws, ids, strict=True)]

    # snap corners of different blocks together
    owner = np.concatenate([np.full(len(p), i) for i, p in enumerate(polys)])
    pts = np.concatenate(polys)
    lab = _cluster(pts, tol)
    centers = np.zeros((lab.max() + 1, 2))
    np.add.at(centers, lab, pts)
    centers /= np.bincount(lab)[:, None]
    moved = np.linalg.norm(centers[lab] - pts, axis=1)
    rep.vertices_snapped = int((moved > 0).sum())
    rep.max_move = float(moved.max(initial=0.0))
    pts = centers[lab]
    misses = _near_misses(pts, owner, tol, near_miss, ids)
    if misses:
        a, b, d = min(misses, key=lambda m: m[2])
        pairs = sorted({tuple(sorted(m[:2])) for m in misses})
        more = f" (and {len(pairs) - 1} more pairs)" if len(pairs) > 1 else ""
        raise InputError(f"blocks '{a}' and '{b}' have corners {d:.3g} apart: more than the "
                         f"snapping tolerance {tol:.3g} but less than {near_miss:g} times it"
                         f"{more}; fix the drawing or raise snap_tol", src)
    polys = np.split(pts, np.cumsum([len(p) for p in polys])[:-1])
    polys = [np.array(p) for p in polys]
    _snap_to_edges(polys, tol, rep)
    # drop vertices that became repeated
    for i, p in enumerate(polys):
        keep = np.linalg.norm(p - np.roll(p, 1, axis=0), axis=1) > 0
        if not keep.all():
            rep.duplicates_dropped += int((~keep).sum())
            polys[i] = p[keep]
        if len(polys[i]) < 3:
            raise InputError("block degenerates to fewer than 3 vertices after snapping",
                             f"{src}: block '{ids[i]}'")
        if signed_area(polys[i]) < 0:
            rep.reoriented += 1

    is_support = _supports(supports, raws, polys, ids, tol, src)
    blocks = [make_block(bid, p, support=bool(s))
              for bid, p, s in zip(ids, polys, is_support, strict=True)]
    if isinstance(units, str):
        units = (units, None)
    scene = Scene(dimension=2, blocks=tuple(blocks), name=name,
                  units=Units(*units) if units else None, depth=depth,
                  unit_weight=unit_weight, friction=friction,
                  live_body_force=None if live_body_force is None
                  else tuple(float(v) for v in live_body_force), source=src)
    _validate(scene, tol, size, src)
    rep.n_blocks = len(blocks)
    rep.supports = [b.id for b in blocks if b.support]
    rep.blocks = {bid: r.handle for bid, r in zip(ids, raws, strict=True)}
    log.info("%s", rep.summary())
    return (scene, rep) if report else scene


def _supports(spec: str, raws: list[_Raw], polys: list[np.ndarray], ids: list[str],
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
def write_dxf(scene: Scene, path: str | os.PathLike, result: Any = None, *,
              force_scale: float | None = None) -> None:
    """Write the scene's blocks and, if ``result`` has a force state, its forces.

    Layers: ``RB_BLOCKS`` and ``RB_SUPPORTS`` (closed polylines), ``RB_THRUST_LINE``
    (a polyline through the points where the joint resultants cross the joints),
    ``RB_FORCES`` (one arrow per joint: a line along the resultant force on the second
    block of the joint, drawn from its point of application, plus a two-stroke head),
    ``RB_TEXT`` (block ids and the result's headline). ``force_scale`` is the drawing
    length per force unit (default: the largest resultant is 10 % of the scene's
    size).
    """
    ezdxf = _ezdxf()
    if scene.dimension != 2:
        raise InputError("DXF export is for 2D scenes", scene.source)
    doc = ezdxf.new("R2010")
    doc.header["$INSUNITS"] = {"mm": 4, "cm": 5, "m": 6}.get(scene.length_unit, 0)
    for key, lay in LAYERS.items():
        colour = {"blocks": 7, "supports": 8, "thrust": 1, "forces": 5, "text": 3}[key]
        doc.layers.add(lay, color=colour)
    msp = doc.modelspace()
    for b in scene.blocks:
        msp.add_lwpolyline([tuple(p) for p in b.points], close=True,
                           dxfattribs={"layer": LAYERS["supports" if b.support else "blocks"]})
    state = getattr(result, "state", None)
    if state is not None:
        from ..scene.geometry import scene_size

        c = result.contacts
        line = state.thrust_line
        if len(line) > 1:
            msp.add_lwpolyline([tuple(p) for p in line], dxfattribs={"layer": LAYERS["thrust"]})
        force = joint_force_vectors(c, state)
        mag = np.linalg.norm(force, axis=1)
        size = scene_size(scene)
        if force_scale is None:
            top = mag.max(initial=0.0)
            force_scale = 0.1 * size / top if top > 0 else 0.0
        for p, fvec, m in zip(state.thrust_points, force, mag, strict=True):
            if m <= 0 or not np.all(np.isfinite(p)):
                continue
            q = p + force_scale * fvec
            msp.add_line(tuple(p), tuple(q), dxfattribs={"layer": LAYERS["forces"]})
            head = 0.25 * force_scale * m
            u = fvec / m
            nrm = np.array([-u[1], u[0]])
            for sgn in (1, -1):
                msp.add_line(tuple(q), tuple(q - head * u + sgn * 0.4 * head * nrm),
                             dxfattribs={"layer": LAYERS["forces"]})
    title = headline(result)
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


def joint_force_vectors(contacts: Any, state: Any) -> np.ndarray:
    """(m, 2) resultant force on the second block of each joint: N n + T s."""
    n = contacts.normals
    s = contacts.tangents[:, 0, :]
    return state.joint_normal[:, None] * n + state.joint_shear[:, None] * s


__all__ = ["DEFAULT_SNAP_TOL", "DxfReport", "LAYERS", "joint_force_vectors", "read_dxf",
           "write_dxf"]
