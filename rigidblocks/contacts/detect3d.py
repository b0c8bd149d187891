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
from ..scene.model import Scene, block_boxes
from ..scene.polyhedra import block_planes, blocks_in, candidate_pairs, shape
from .detect2d import block_where, joint_laws
from .model import Contacts


def plane_frame(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit tangents (t1, t2) with (n, t1, t2) right-handed."""
    t1, t2 = plane_frames(np.asarray(n, dtype=float)[None, :])
    return t1[0], t2[0]


def plane_frames(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`plane_frame` of many unit normals (m, 3) at once: (m, 3) t1 and t2."""
    x, y, z = n[:, 0], n[:, 1], n[:, 2]
    # n x e1 where n is far from e1, else n x e2
    far = np.abs(x) < 0.9
    zero = np.zeros_like(x)
    t1 = np.where(far[:, None], np.stack([zero, z, -y], axis=1),
                  np.stack([-z, zero, x], axis=1))
    t1 /= np.linalg.norm(t1, axis=1)[:, None]
    t2 = np.stack([y * t1[:, 2] - z * t1[:, 1], z * t1[:, 0] - x * t1[:, 2],
                   x * t1[:, 1] - y * t1[:, 0]], axis=1)
    return t1, t2


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
        add([key], np.array([i]), np.array([j]), n[None, :], t1[None, :], t2[None, :],
            o + ring[:, :1] * t1 + ring[:, 1:2] * t2, np.array([len(ring)]),
            np.array([area[k]]))


def _polygons(rings: list[np.ndarray]):
    """Shapely polygons of 2D rings, built in one call."""
    return _rings_polygons(np.concatenate(rings),
                           np.repeat(np.arange(len(rings)), [len(r) for r in rings]))


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


def _clip_faces(found: dict, eps: float, add) -> None:
    """The joints of coplanar faces of convex blocks, all at once.

    ``found`` (see :func:`_facing_faces`): per face pair its key, blocks i and j, i's
    face normal n, the plane's frame (t1, t2) and origin o (the first vertex of i's
    face), and the two faces in the plane's 2D frame (``ring_a``/``ring_b`` coordinates,
    ``own_a``/``own_b`` the face pair of each vertex). Each contact is the
    intersection of the two convex faces (a convex polygon, simplified at ``eps / 2``),
    kept where its area exceeds eps^2.
    """
    import shapely

    inter = shapely.intersection(_rings_polygons(found["ring_a"], found["own_a"]),
                                 _rings_polygons(found["ring_b"], found["own_b"]))
    ok = np.flatnonzero((shapely.get_type_id(inter) == 3) & ~shapely.is_empty(inter)
                        & (shapely.area(inter) > eps * eps))
    if not len(ok):
        return
    poly = shapely.simplify(inter[ok], eps * 0.5)
    area = shapely.area(poly)
    coords, idx = shapely.get_coordinates(shapely.get_exterior_ring(poly),
                                          return_index=True)
    cnt = np.bincount(idx, minlength=len(poly))
    pos = np.arange(len(idx)) - np.repeat(np.cumsum(cnt) - cnt, cnt)
    good = cnt - 1 >= 3  # rings of three vertices or more, without the closing one
    keep = good[idx] & (pos < cnt[idx] - 1)
    g = ok[idx[keep]]
    x, y = coords[keep, :1], coords[keep, 1:2]
    points = found["o"][g] + x * found["t1"][g] + y * found["t2"][g]
    sel = ok[good]
    add([found["key"][k] for k in sel], found["i"][sel], found["j"][sel], found["n"][sel],
        found["t1"][sel], found["t2"][sel], points, cnt[good] - 1, area[good])


def _rings_polygons(coords: np.ndarray, owner: np.ndarray):
    """Shapely polygons of 2D rings given as one coordinate array and each vertex's
    ring (in order), built in one call."""
    import shapely

    return shapely.polygons(shapely.linearrings(coords, indices=owner))


def _face_table(scene: Scene, shapes: list, blocks: np.ndarray) -> dict:
    """Padded per-block arrays of the convex blocks ``blocks``: unit normals (nb, F, 3)
    and offsets (nb, F) of their face planes (from each block's origin), which faces
    exist, and where each face's vertices are in one flat table of global vertex
    indices (into the scene's points, concatenated)."""
    nb = len(scene.blocks)
    nf = max((len(shapes[k].faces) for k in blocks), default=0)
    N = np.zeros((nb, nf, 3))
    D = np.zeros((nb, nf))
    has = np.zeros((nb, nf), dtype=bool)
    first = np.zeros((nb, nf), dtype=int)
    count = np.zeros((nb, nf), dtype=int)
    npts = np.array([len(b.points) for b in scene.blocks])
    base = np.concatenate([[0], np.cumsum(npts)[:-1]])
    flat, at = [], 0
    for k in blocks:
        n, d = block_planes(scene.blocks[k])
        faces = shapes[k].faces
        N[k, :len(n)], D[k, :len(d)], has[k, :len(n)] = n, d, True
        cnt = [len(f) for f in faces]
        count[k, :len(cnt)] = cnt
        first[k, :len(cnt)] = at + np.concatenate([[0], np.cumsum(cnt)[:-1]])
        flat.append(np.concatenate(faces) + base[k])
        at += sum(cnt)
    return {"N": N, "D": D, "has": has, "first": first, "count": count,
            "flat": np.concatenate(flat) if flat else np.zeros(0, dtype=int)}


def _facing_faces(scene: Scene, shapes: list, pairs: np.ndarray, pks: np.ndarray,
                  eps: float, chunk: int = 4096) -> dict | None:
    """Every pair of opposite coplanar faces (normals opposite to 1e-9, planes within
    ``eps``) of the convex block pairs ``pairs`` (their candidate numbers ``pks``), in
    the order of the pairs and, per pair, of i's and j's faces; each with its plane's
    frame and both faces' vertices in it (see :func:`_clip_faces`). None if there are
    none."""
    used = blocks_in(pairs, len(scene.blocks))
    tab = _face_table(scene, shapes, used)
    N, D, has = tab["N"], tab["D"], tab["has"]
    origins = np.zeros((len(scene.blocks), 3))
    origins[used] = [shapes[k].origin for k in used]
    hits = []
    for c in range(0, len(pairs), chunk):
        i, j = pairs[c:c + chunk, 0], pairs[c:c + chunk, 1]
        # j's planes in i's coordinates: n_j . (x - o_i) = d_j + n_j . (o_j - o_i)
        dj_i = D[j] + np.einsum("pfk,pk->pf", N[j], origins[j] - origins[i])
        dots = np.einsum("pak,pbk->pab", N[i], N[j])
        mask = ((dots < -1.0 + 1e-9) & (np.abs(D[i][:, :, None] + dj_i[:, None, :]) <= eps)
                & has[i][:, :, None] & has[j][:, None, :])
        p, fi, fj = np.nonzero(mask)
        hits.append((p + c, fi, fj))
    p = np.concatenate([h[0] for h in hits])
    if not len(p):
        return None
    fi, fj = np.concatenate([h[1] for h in hits]), np.concatenate([h[2] for h in hits])
    i, j = pairs[p, 0], pairs[p, 1]
    # the face's number among its pair's (the joints' order key)
    fk = np.arange(len(p)) - np.searchsorted(p, p)
    n = N[i, fi]
    t1, t2 = plane_frames(n)
    pts = np.concatenate([b.points for b in scene.blocks])
    out = {"key": [(int(a), int(b)) for a, b in zip(pks[p], fk, strict=True)],
           "i": i, "j": j, "n": n, "t1": t1, "t2": t2}
    out["o"] = pts[tab["flat"][tab["first"][i, fi]]]
    for side, blk, f in (("a", i, fi), ("b", j, fj)):
        cnt = tab["count"][blk, f]
        own = np.repeat(np.arange(len(p)), cnt)
        idx = tab["flat"][np.repeat(tab["first"][blk, f], cnt)
                          + np.arange(int(cnt.sum())) - np.repeat(np.cumsum(cnt) - cnt, cnt)]
        rel = pts[idx] - out["o"][own]
        out[f"ring_{side}"] = np.stack([np.einsum("vk,vk->v", rel, t1[own]),
                                        np.einsum("vk,vk->v", rel, t2[own])], axis=1)
        out[f"own_{side}"] = own
    return out


def detect_contacts_3d(scene: Scene, tol: float) -> Contacts:
    """Find every joint of a 3D scene.

    Args:
        scene: a validated 3D scene.
        tol: relative tolerance; coincidence is judged at ``tol x scene size``.
    """

    L = scene_size(scene)
    eps = tol * L
    lo, hi = block_boxes(scene)
    across = (hi - lo).max(axis=1)
    for k in np.flatnonzero(across <= eps)[:1]:
        raise InputError(f"the block ({across[k]:.3g} across) is smaller than the contact "
                         f"tolerance {eps:.3g} (--contact-tol, relative, x the scene's size): "
                         "lower --contact-tol, or enlarge or remove the block",
                         block_where(scene, scene.blocks[k].id))
    planes = [block_planes(b) for b in scene.blocks]
    shapes = [shape(b) for b in scene.blocks]
    pairs, normals, tangents, polys, areas, order = [], [], [], [], [], []
    pending: list[tuple] = []  # planes of pairs with a non-convex block, done together

    def add(keys: list[tuple[int, int]], i: np.ndarray, j: np.ndarray, n: np.ndarray,
            t1: np.ndarray, t2: np.ndarray, points: np.ndarray, counts: np.ndarray,
            area: np.ndarray) -> None:
        """Joints: their order keys, blocks, normals (k, 3), tangents, contact points
        (all joints' in one array, ``counts`` per joint) and areas."""
        order.extend(keys)
        pairs.extend(zip(i.tolist(), j.tolist(), strict=True))
        normals.extend(n)
        tangents.extend(np.stack([t1, t2], axis=1))
        polys.extend(np.split(points, np.cumsum(counts)[:-1]))
        areas.extend(area.tolist())

    cand = candidate_pairs(scene, eps)
    # (two supports have no joint: neither moves, nor has an equation its force enters)
    fixed = scene.support_mask
    cand = cand[~(fixed[cand[:, 0]] & fixed[cand[:, 1]])] if len(cand) else cand
    convex = np.array([s.convex for s in shapes], dtype=bool)
    both = convex[cand[:, 0]] & convex[cand[:, 1]] if len(cand) else np.zeros(0, bool)
    # coplanar face pairs of convex blocks, found and clipped together
    found = _facing_faces(scene, shapes, cand[both], np.flatnonzero(both), eps) \
        if both.any() else None
    for pk in np.flatnonzero(~both):
        i, j = (int(x) for x in cand[pk])
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
            pending.append(((int(pk), gk), i, j, ni[f0], si.faces[f0][0],
                            sorted(set(fi_all[g].tolist())), sorted(set(fj_all[g].tolist()))))
    if found is not None:
        _clip_faces(found, eps, add)
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
