"""Repair of 2D drawings into block outlines, independent of any CAD library.

Real drawings are never exact. Given the outlines read from a drawing (polylines as
vertex arrays, and loose LINE segments), these functions make closed, matching block
polygons within a snapping tolerance ``tol`` (absolute, drawing units), and reject what
is beyond it with a one-line :class:`~rigidblocks.errors.InputError` naming the source
entities or blocks:

* :func:`line_loops` joins LINE segments into closed chains (each end shared by
  exactly two segments);
* :func:`close_polyline` closes a polyline that comes back to its start (or retraces
  its first vertices) and drops repeated vertices;
* :func:`repair` does the above for every outline, moves nearly coinciding corners of
  different blocks onto one point (the mean of the cluster), rejects near misses
  (corners close, but not within the tolerance), and moves T-junction vertices onto
  the neighbour's edge.

Everything moved is counted in a :class:`DxfReport`. :mod:`rigidblocks.io.dxf` reads
the entities with ezdxf and calls these; they need numpy, scipy and shapely only.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..errors import InputError


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
        restored: the drawing carried the scene written by
            :func:`rigidblocks.io.dxf.write_dxf`, and it was restored from it.
        declared_unit, unit_conflict: the drawing's own length unit ($INSUNITS), and
            what was done where the unit given differs from it.
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
    restored: bool = False
    #: the length unit the drawing declares ($INSUNITS), None where it declares none
    declared_unit: str | None = None
    #: the header's $INSUNITS code (0: none; one the import does not read: not declared)
    insunits: int = 0
    #: where the length unit given differs from the drawing's: what was done
    unit_conflict: str = ""

    def summary(self) -> str:
        """One line: what was read and what was repaired."""
        skipped = ", ".join(f"{n} {k}" for k, n in sorted(self.skipped.items())) or "none"
        restored = " (scene restored from its rigidblocks metadata)" if self.restored else ""
        ns = len(self.supports)
        return (f"{self.source}{restored}: {self.n_blocks} blocks ({ns} "
                f"{'support' if ns == 1 else 'supports'}: "
                f"{', '.join(self.supports)}); snapped {self.vertices_snapped} corners and "
                f"{self.edges_snapped} T-junction vertices (largest move {self.max_move:.3g}, "
                f"tolerance {self.tol:.3g}, in the drawing's units); closed "
                f"{len(self.closed_by_snap)} polylines by snapping ({len(self.retraced)} "
                f"retracing); dropped "
                f"{self.duplicates_dropped} repeated vertices; {self.reoriented} outlines "
                f"drawn clockwise (kept so: a scene takes either orientation); skipped "
                f"{skipped}")


@dataclass
class Outline:
    """One candidate block read from a drawing: its entity handle(s), layer, vertices
    ((n, 2), an open list without a repeated closing vertex), whether the entity was
    flagged closed, and the entity kind (for messages)."""

    handle: str
    layer: str
    points: np.ndarray
    closed_flag: bool
    kind: str


def line_loops(ends: np.ndarray, handles: list[str], layers: list[str], tol: float,
               report: DxfReport) -> list[Outline]:
    """Closed chains of line segments ``ends`` ((n, 4): x0, y0, x1, y1), each end
    shared by exactly two segments within ``tol``; InputError naming the handles of a
    chain that does not close."""
    ends = np.asarray(ends, dtype=float).reshape(-1, 4)
    if not len(ends):
        return []
    pts = ends.reshape(-1, 2)
    node = cluster(pts, tol)
    a, b = node[0::2], node[1::2]
    adj: dict[int, list[int]] = {}
    for k in range(len(ends)):
        adj.setdefault(int(a[k]), []).append(k)
        adj.setdefault(int(b[k]), []).append(k)
    used = np.zeros(len(ends), bool)
    loops: list[Outline] = []
    centers = np.zeros((node.max() + 1, 2))
    np.add.at(centers, node, pts)
    centers /= np.bincount(node)[:, None]
    for k0 in range(len(ends)):
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
        joined = ",".join(handles[j] for j in chain)
        if not ok or len(nodes) < 3:
            raise InputError("LINE entities that do not form a closed chain (an end meets "
                             "no other line, or more than two, within the tolerance "
                             f"{tol:.3g})", f"{report.source}: LINEs #{joined}")
        loops.append(Outline(joined, layers[k0], centers[nodes], True, "LINE"))
    return loops


def cluster(pts: np.ndarray, tol: float) -> np.ndarray:
    """Label points so that points within ``tol`` of each other (transitively) share one."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    pairs = cKDTree(pts).query_pairs(tol, output_type="ndarray") if len(pts) else \
        np.zeros((0, 2), int)
    n = len(pts)
    g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    return connected_components(g, directed=False)[1]


def close_polyline(raw: Outline, tol: float, bid: str, report: DxfReport) -> np.ndarray:
    """The closed vertex array of one outline (block ``bid``); see the module."""
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
    elif not raw.closed_flag and len(pts) >= 3:
        gap = float(np.linalg.norm(pts[-1] - pts[0]))
        raise InputError(f"open polyline: its ends are {gap:.6g} apart, more than the "
                         f"snapping tolerance {tol:.3g}", f"{report.source}: {raw.kind} "
                         f"#{raw.handle} (block '{bid}')")
    if len(pts) < 3:
        raise InputError(f"{'closed ' if raw.closed_flag else ''}polyline with fewer than "
                         f"3 vertices apart by more than the snapping tolerance {tol:.3g}",
                         f"{report.source}: {raw.kind} #{raw.handle} (block '{bid}')")
    return pts


def snap_to_edges(polys: list[np.ndarray], tol: float, report: DxfReport) -> None:
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


def repair(outlines: list[Outline], ids: list[str], tol: float, near_miss: float,
           report: DxfReport, src: str) -> list[np.ndarray]:
    """The repaired polygon of each outline (block ``ids``), see the module; ``src``
    names the drawing in messages."""
    polys = [close_polyline(r, tol, bid, report) for r, bid in zip(outlines, ids, strict=True)]
    # snap corners of different blocks together
    owner = np.concatenate([np.full(len(p), i) for i, p in enumerate(polys)])
    pts = np.concatenate(polys)
    lab = cluster(pts, tol)
    centers = np.zeros((lab.max() + 1, 2))
    np.add.at(centers, lab, pts)
    centers /= np.bincount(lab)[:, None]
    moved = np.linalg.norm(centers[lab] - pts, axis=1)
    report.vertices_snapped = int((moved > 0).sum())
    report.max_move = float(moved.max(initial=0.0))
    pts = centers[lab]
    misses = _near_misses(pts, owner, tol, near_miss, ids)
    if misses:
        a, b, d = min(misses, key=lambda m: m[2])
        pairs = sorted({tuple(sorted(m[:2])) for m in misses})
        more = f" (and {len(pairs) - 1} more pairs)" if len(pairs) > 1 else ""
        raise InputError(f"blocks '{a}' and '{b}' have corners {d:.3g} apart: more than the "
                         f"snapping tolerance {tol:.3g} but less than {near_miss:g} times it"
                         f"{more}; fix the drawing or raise snap_tol", src)
    polys = [np.array(p) for p in np.split(pts, np.cumsum([len(p) for p in polys])[:-1])]
    snap_to_edges(polys, tol, report)
    # drop vertices that became repeated
    for i, p in enumerate(polys):
        keep = np.linalg.norm(p - np.roll(p, 1, axis=0), axis=1) > 0
        if not keep.all():
            report.duplicates_dropped += int((~keep).sum())
            polys[i] = p[keep]
        if len(polys[i]) < 3:
            raise InputError("block degenerates to fewer than 3 vertices after snapping",
                             f"{src}: block '{ids[i]}'")
    return polys


__all__ = ["DxfReport", "Outline", "close_polyline", "cluster", "line_loops", "repair",
           "snap_to_edges"]
