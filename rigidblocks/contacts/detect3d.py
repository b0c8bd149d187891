"""Contact detection between convex polyhedral blocks (3D).

Two blocks touch where a face of one and a face of the other are coplanar with
opposite outward normals and their polygons overlap with positive area. The contact
polygon is the intersection of the two faces (shapely, in the plane's 2D frame); its
vertices are the contact points. Candidate block pairs come from a spatial index on
bounding boxes.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..scene.geometry import scene_size
from ..scene.model import Scene
from ..scene.polyhedra import block_planes, candidate_pairs, outward_faces
from .detect2d import joint_laws
from .model import Contacts


def plane_frame(n: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Two unit tangents (t1, t2) with (n, t1, t2) right-handed."""
    x, y, z = float(n[0]), float(n[1]), float(n[2])
    # n x e1 when n is far from e1, else n x e2
    t1 = np.array([0.0, z, -y]) if abs(x) < 0.9 else np.array([-z, 0.0, x])
    t1 /= np.linalg.norm(t1)
    return t1, np.array([y * t1[2] - z * t1[1], z * t1[0] - x * t1[2], x * t1[1] - y * t1[0]])


def detect_contacts_3d(scene: Scene, tol: float) -> Contacts:
    import shapely

    L = scene_size(scene)
    eps = tol * L
    for b in scene.blocks:
        size = float(np.ptp(b.points, axis=0).max())
        if size <= eps:
            raise InputError(f"the block ({size:.3g} across) is smaller than the contact "
                             f"tolerance {eps:.3g} (relative tolerance x scene size): "
                             "enlarge or remove it, or analyse it in a scene of its own "
                             "size", f"block '{b.id}'")
    planes = [block_planes(b) for b in scene.blocks]
    faces = [outward_faces(b) for b in scene.blocks]
    pairs, normals, tangents, polys, areas = [], [], [], [], []
    for i, j in candidate_pairs(scene, eps):
        ni, di = planes[i]
        nj, dj = planes[j]
        dots = ni @ nj.T
        for fi, fj in zip(*np.nonzero(dots < -1.0 + 1e-9), strict=True):
            if abs(di[fi] + dj[fj]) > eps:
                continue
            n = ni[fi]
            t1, t2 = plane_frame(n)
            pa = scene.blocks[i].points[faces[i][fi]]
            pb = scene.blocks[j].points[faces[j][fj]]
            o = pa[0]
            A = shapely.Polygon(np.stack([(pa - o) @ t1, (pa - o) @ t2], axis=1))
            B = shapely.Polygon(np.stack([(pb - o) @ t1, (pb - o) @ t2], axis=1))
            inter = shapely.intersection(A, B)
            if inter.is_empty or inter.geom_type != "Polygon" or inter.area <= eps * eps:
                continue
            inter = shapely.simplify(inter, eps * 0.5)
            ring = np.asarray(inter.exterior.coords)[:-1]
            if len(ring) < 3:
                continue
            pts = o + ring[:, :1] * t1 + ring[:, 1:2] * t2
            pairs.append((i, j))
            normals.append(n)
            tangents.append(np.stack([t1, t2]))
            polys.append(pts)
            areas.append(inter.area)
    m = len(pairs)
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
