"""Contact detection between polyhedral blocks (3D), convex or not.

Two blocks touch where a face of one and a face of the other are coplanar with
opposite outward normals and their polygons overlap with positive area. Candidate
block pairs come from a spatial index on bounding boxes. Planes are compared in
coordinates relative to the blocks' own origins (:func:`~rigidblocks.scene.polyhedra.
block_origin`), so the test does not lose precision far from the scene's origin.

Between two convex blocks the contact is the intersection of two convex faces (shapely,
in the plane's 2D frame), a convex polygon whose vertices are the contact points.

Where a block is not convex, the contact region in one plane is the intersection of
the union of one block's faces in that plane with the union of the other's: it may be
non-convex, have holes or be in several pieces (shapely handles all three), and it is
one joint. Its contact points are the vertices of the region's convex hull: a
no-tension joint's resultant can lie anywhere in the hull (a positive combination of
forces at points of the region), and the hull's vertices are points of the region, so
forces at the hull's vertices reach every resultant the region can carry, with the
same Coulomb cone at each point as on a convex joint. The joint's area is the region's
own area.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..scene.geometry import scene_size
from ..scene.model import Scene
from ..scene.polyhedra import block_planes, candidate_pairs, shape
from .detect2d import joint_laws
from .model import Contacts


def plane_frame(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit tangents (t1, t2) with (n, t1, t2) right-handed."""
    x, y, z = float(n[0]), float(n[1]), float(n[2])
    # n x e1 when n is far from e1, else n x e2
    t1 = np.array([0.0, z, -y]) if abs(x) < 0.9 else np.array([-z, 0.0, x])
    t1 /= np.linalg.norm(t1)
    return t1, np.array([y * t1[2] - z * t1[1], z * t1[0] - x * t1[2], x * t1[1] - y * t1[0]])


def _polygonal(geom):
    """The polygons of a shapely geometry (lines and points of a touching set dropped)."""
    import shapely

    parts = shapely.get_parts(geom)
    polys = [p for p in parts if p.geom_type == "Polygon" and not p.is_empty]
    return shapely.MultiPolygon(polys) if polys else None


def _regions(scene: Scene, shapes: list, pending: list[tuple], eps: float, add) -> None:
    """The joints of planes shared by a non-convex block and another, all at once.

    ``pending`` holds (key, i, j, normal, first vertex of i's face, i's faces in the
    plane, j's faces in it). Each side's faces are united (shapely), the two unions
    intersected, and the region's convex hull gives the contact points.
    """
    import shapely

    rings_a, rings_b, frames = [], [], []
    for _, i, j, n, v0, fa, fb in pending:
        t1, t2 = plane_frame(n)
        o = scene.blocks[i].points[v0]
        frame = np.stack([t1, t2], axis=1)
        frames.append((t1, t2, o))
        rings_a.append([(scene.blocks[i].points[shapes[i].faces[f]] - o) @ frame for f in fa])
        rings_b.append([(scene.blocks[j].points[shapes[j].faces[f]] - o) @ frame for f in fb])

    def united(rings: list[list[np.ndarray]]) -> np.ndarray:
        owner = np.repeat(np.arange(len(rings)), [len(rs) for rs in rings])
        faces = _polygons([r for rs in rings for r in rs])
        out = np.empty(len(rings), dtype=object)
        first = np.concatenate([[0], np.cumsum([len(rs) for rs in rings])[:-1]])
        out[:] = faces[first]
        for g in np.flatnonzero(np.bincount(owner, minlength=len(rings)) > 1):
            out[g] = shapely.union_all(faces[owner == g])
        return out

    A, B = united(rings_a), united(rings_b)
    lo_a, lo_b = shapely.bounds(A), shapely.bounds(B)
    w = np.minimum(lo_a[:, 2], lo_b[:, 2]) - np.maximum(lo_a[:, 0], lo_b[:, 0])
    h = np.minimum(lo_a[:, 3], lo_b[:, 3]) - np.maximum(lo_a[:, 1], lo_b[:, 1])
    live = np.flatnonzero((w > 0) & (h > 0) & (w * h > eps * eps))
    if not len(live):
        return
    region = shapely.intersection(A[live], B[live])
    mixed = np.flatnonzero(shapely.get_type_id(region) == 7)  # polygons with lines
    for k in mixed:
        parts = _polygonal(region[k])
        region[k] = shapely.Polygon() if parts is None else parts
    area = shapely.area(region)
    ok = area > eps * eps
    live, region, area = live[ok], region[ok], area[ok]
    hull = shapely.simplify(shapely.convex_hull(region), eps * 0.5)
    poly = shapely.get_type_id(hull) == 3
    live, hull, area = live[poly], hull[poly], area[poly]
    for k, g, ring in _exteriors(hull, live):
        key, i, j, n = pending[g][:4]
        t1, t2, o = frames[g]
        add(key, i, j, n, t1, t2, o, ring, float(area[k]))


def _polygons(rings: list[np.ndarray]):
    """Shapely polygons of 2D rings, built in one call."""
    import shapely

    counts = [len(r) for r in rings]
    return shapely.polygons(shapely.linearrings(
        np.concatenate(rings), indices=np.repeat(np.arange(len(rings)), counts)))


def _exteriors(polys, which: np.ndarray):
    """(k, which[k], exterior ring without its closing vertex) of each polygon whose
    ring has at least three vertices."""
    import shapely

    coords, idx = shapely.get_coordinates(shapely.get_exterior_ring(polys), return_index=True)
    starts = np.concatenate([[0], np.cumsum(np.bincount(idx, minlength=len(polys)))])
    for k, g in enumerate(which):
        ring = coords[starts[k]:starts[k + 1] - 1]
        if len(ring) >= 3:
            yield k, g, ring


def _clip_faces(faces: list[tuple], eps: float, add) -> None:
    """The joints of coplanar faces of convex blocks, all at once.

    ``faces`` holds (key, i, j, normal, t1, t2, origin, i's face, j's face), the faces
    in the plane's 2D frame. Each contact is the intersection of the two convex faces
    (a convex polygon, simplified at ``eps / 2``), kept where its area exceeds eps^2.
    """
    import shapely

    inter = shapely.intersection(_polygons([f[7] for f in faces]),
                                 _polygons([f[8] for f in faces]))
    ok = np.flatnonzero((shapely.get_type_id(inter) == 3) & ~shapely.is_empty(inter)
                        & (shapely.area(inter) > eps * eps))
    if not len(ok):
        return
    poly = shapely.simplify(inter[ok], eps * 0.5)
    area = shapely.area(poly)
    for k, g, ring in _exteriors(poly, ok):
        key, i, j, n, t1, t2, o = faces[g][:7]
        add(key, i, j, n, t1, t2, o, ring, float(area[k]))


def detect_contacts_3d(scene: Scene, tol: float) -> Contacts:
    """Find every joint of a 3D scene.

    Args:
        scene: a validated 3D scene.
        tol: relative tolerance; coincidence is judged at ``tol x scene size``.
    """

    L = scene_size(scene)
    eps = tol * L
    for b in scene.blocks:
        size = float(np.ptp(b.points, axis=0).max())
        if size <= eps:
            raise InputError(f"the block ({size:.3g} across) is smaller than the contact "
                             f"tolerance {eps:.3g} (relative tolerance x scene size): "
                             "enlarge or remove it, or analyse it in a scene of its own "
                             "size", f"block {b.id!r}")
    planes = [block_planes(b) for b in scene.blocks]
    shapes = [shape(b) for b in scene.blocks]
    pairs, normals, tangents, polys, areas, order = [], [], [], [], [], []
    pending: list[tuple] = []  # planes of pairs with a non-convex block, done together
    faces: list[tuple] = []  # coplanar face pairs of convex blocks, clipped together

    def add(key: tuple[int, int], i: int, j: int, n: np.ndarray, t1: np.ndarray,
            t2: np.ndarray, o: np.ndarray, ring: np.ndarray, area: float) -> None:
        order.append(key)
        pairs.append((i, j))
        normals.append(n)
        tangents.append(np.stack([t1, t2]))
        polys.append(o + ring[:, :1] * t1 + ring[:, 1:2] * t2)
        areas.append(area)

    for pk, (i, j) in enumerate(candidate_pairs(scene, eps)):
        si, sj = shapes[i], shapes[j]
        ni, di = planes[i]
        nj, dj = planes[j]
        # face fj's plane, n_j . (x - o_i) = dj + n_j . (o_j - o_i), in i's coordinates
        dj_i = dj + nj @ (sj.origin - si.origin)
        dots = ni @ nj.T
        fi_all, fj_all = np.nonzero(dots < -1.0 + 1e-9)
        keep = np.abs(di[fi_all] + dj_i[fj_all]) <= eps
        fi_all, fj_all = fi_all[keep], fj_all[keep]
        if not len(fi_all):
            continue
        if si.convex and sj.convex:
            for fk, (fi, fj) in enumerate(zip(fi_all, fj_all, strict=True)):
                n = ni[fi]
                t1, t2 = plane_frame(n)
                pa = scene.blocks[i].points[si.faces[fi]]
                pb = scene.blocks[j].points[sj.faces[fj]]
                o = pa[0]
                frame = np.stack([t1, t2], axis=1)
                faces.append(((pk, fk), i, j, n, t1, t2, o, (pa - o) @ frame,
                              (pb - o) @ frame))
            continue
        # a non-convex block: one joint per plane, the faces of each side in it united
        groups: list[list[int]] = []
        for k, fi in enumerate(fi_all):
            for g in groups:
                f0 = fi_all[g[0]]
                if ni[f0] @ ni[fi] > 1.0 - 1e-9 and abs(di[f0] - di[fi]) <= eps:
                    g.append(k)
                    break
            else:
                groups.append([k])
        for gk, g in enumerate(groups):
            f0 = fi_all[g[0]]
            pending.append(((pk, gk), i, j, ni[f0], si.faces[f0][0],
                            sorted(set(fi_all[g].tolist())), sorted(set(fj_all[g].tolist()))))
    if faces:
        _clip_faces(faces, eps, add)
    if pending:
        _regions(scene, shapes, pending, eps, add)
    m = len(pairs)
    if pending:  # joints in the order of the candidate pairs and their faces
        perm = sorted(range(m), key=order.__getitem__)
        pairs, normals, tangents, polys, areas = (
            [x[k] for k in perm] for x in (pairs, normals, tangents, polys, areas))
    counts = np.array([len(p) for p in polys], dtype=int)
    pairs_a = np.array(pairs, dtype=int).reshape(m, 2)
    override_f, coh, ts = joint_laws(scene, pairs_a)
    area = np.array(areas, dtype=float)
    return Contacts(
        dimension=3, pairs=pairs_a, normals=np.array(normals).reshape(m, 3),
        tangents=np.array(tangents).reshape(m, 2, 3),
        points=np.concatenate(polys) if m else np.zeros((0, 3)),
        joint_start=np.concatenate([[0], np.cumsum(counts)]).astype(int), areas=area,
        lengths=np.sqrt(area), override_friction=override_f, cohesion=coh,
        tensile_strength=ts, block_ids=tuple(b.id for b in scene.blocks))
