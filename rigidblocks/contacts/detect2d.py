"""Contact detection between 2D polygonal blocks.

Two blocks are in contact where their boundaries share a segment of positive length:
an edge of one and an edge of the other that are collinear (within a tolerance relative
to the scene size), run in opposite directions (both polygons counter-clockwise) and
overlap. Candidate edge pairs come from a spatial index (shapely's STRtree over the
edges' bounding boxes); the geometric tests are vectorised, so a 50,000-block wall takes
seconds.
"""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..scene.geometry import flat_polygons, polygon_areas_centroids, scene_size, simplify_polygon
from ..scene.model import Scene
from .model import Contacts


def oriented_polygons(scene: Scene, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """Counter-clockwise polygons without repeated or straight-angle vertices.

    Returns flat vertices and offsets as :func:`rigidblocks.scene.geometry.flat_polygons`.

    Raises:
        InputError: naming a block that is smaller than ``tol`` (absolute), so that
            fewer than three distinct corners are left of it.
    """
    verts, starts = flat_polygons(scene)
    area, _ = polygon_areas_centroids(verts, starts)
    counts = np.diff(starts)
    # reverse clockwise polygons in place (vectorised)
    owner = np.repeat(np.arange(len(counts)), counts)
    local = np.arange(len(verts)) - starts[owner]
    rev = area[owner] < 0
    src = np.where(rev, starts[owner] + counts[owner] - 1 - local, np.arange(len(verts)))
    verts = verts[src]
    # drop redundant vertices where any may exist (cheap test first)
    nxt = np.arange(len(verts)) + 1
    nxt[starts[1:] - 1] = starts[:-1]
    prv = np.arange(len(verts)) - 1
    prv[starts[:-1]] = starts[1:] - 1
    e1 = verts[nxt] - verts
    e0 = verts - verts[prv]
    cross = e0[:, 0] * e1[:, 1] - e0[:, 1] * e1[:, 0]
    len1 = np.linalg.norm(e1, axis=1)
    len0 = np.linalg.norm(e0, axis=1)
    suspect = (len1 <= tol) | (np.abs(cross) <= tol * np.maximum(len0 + len1, tol))
    if not suspect.any():
        return verts, starts
    # simplify only the suspect blocks; the runs of clean blocks between them are
    # copied as whole slices
    pieces = []
    done = 0
    for b in np.unique(owner[suspect]).tolist():
        pieces.append(verts[done:starts[b]])
        simple = simplify_polygon(verts[starts[b]:starts[b + 1]], tol)
        if len(simple) < 3:
            size = float(np.ptp(verts[starts[b]:starts[b + 1]], axis=0).max())
            raise InputError(f"the block ({size:.3g} across) is smaller than the contact "
                             f"tolerance {tol:.3g} (--contact-tol, relative, x the scene's "
                             "size): lower --contact-tol, or enlarge or remove the block",
                             block_where(scene, scene.blocks[b].id))
        pieces.append(simple)
        counts[b] = len(simple)
        done = starts[b + 1]
    pieces.append(verts[done:])
    return np.concatenate(pieces), np.concatenate([[0], np.cumsum(counts)])


def detect_contacts_2d(scene: Scene, tol: float) -> Contacts:
    """Find every joint of a 2D scene.

    Args:
        scene: a validated 2D scene.
        tol: relative tolerance; coincidence is judged at ``tol x scene size``.
    """
    import shapely

    L = scene_size(scene)
    eps = tol * L
    verts, starts = oriented_polygons(scene, eps)
    nb = len(scene.blocks)
    counts = np.diff(starts)
    owner = np.repeat(np.arange(nb), counts)
    nxt = np.arange(len(verts)) + 1
    nxt[starts[1:] - 1] = starts[:-1]
    a0, a1 = verts, verts[nxt]
    d = a1 - a0
    length = np.linalg.norm(d, axis=1)
    u = d / length[:, None]

    # candidates: edges whose bounding boxes, grown by eps, intersect (the exact tests
    # below decide; a plain envelope query is several times faster than "dwithin")
    box_lo = np.minimum(a0, a1) - eps
    box_hi = np.maximum(a0, a1) + eps
    boxes = shapely.box(box_lo[:, 0], box_lo[:, 1], box_hi[:, 0], box_hi[:, 1])
    ea, eb = shapely.STRtree(boxes).query(boxes)
    # (two supports have no joint: neither moves, nor has an equation its force enters)
    fixed = scene.support_mask
    keep = (owner[ea] < owner[eb]) & ~(fixed[owner[ea]] & fixed[owner[eb]])
    ea, eb = ea[keep], eb[keep]

    # opposite directions, and each edge's end points on the other's line
    anti = np.einsum("ij,ij->i", u[ea], u[eb]) < 0

    def off_line(p, a):  # distance of points p from the line of edge a
        r = p - a0[a]
        return np.abs(u[a, 0] * r[:, 1] - u[a, 1] * r[:, 0])

    # project b's end points on a's line (parameter along a)
    t0 = np.einsum("ij,ij->i", a0[eb] - a0[ea], u[ea])
    t1 = np.einsum("ij,ij->i", a1[eb] - a0[ea], u[ea])
    lo = np.maximum(0.0, np.minimum(t0, t1))
    hi = np.minimum(length[ea], np.maximum(t0, t1))
    # collinearity is checked on the shared stretch only (end points clipped to it)
    pa_lo = a0[ea] + lo[:, None] * u[ea]
    pa_hi = a0[ea] + hi[:, None] * u[ea]
    colin = (off_line(pa_lo, eb) <= eps) & (off_line(pa_hi, eb) <= eps)
    ok = anti & colin & (hi - lo > eps)
    ea, eb, lo, hi = ea[ok], eb[ok], lo[ok], hi[ok]

    bi, bj = owner[ea], owner[eb]
    order = np.lexsort((lo, ea, bj, bi))
    ea, eb, lo, hi, bi, bj = (x[order] for x in (ea, eb, lo, hi, bi, bj))
    n_out = np.stack([u[ea, 1], -u[ea, 0]], axis=1)  # outward normal of i's edge: i -> j
    tangent = np.stack([-n_out[:, 1], n_out[:, 0]], axis=1)
    # contact points: the ends of the shared stretch, in the order of the tangent s
    # (s = u_a for a counter-clockwise polygon i, so the point at lo comes first)
    p_first = a0[ea] + lo[:, None] * u[ea]
    p_second = a0[ea] + hi[:, None] * u[ea]
    m = len(ea)
    points = np.empty((2 * m, 2))
    points[0::2] = p_first
    points[1::2] = p_second
    seg = hi - lo
    depth = scene.effective_depth
    pairs = np.stack([bi, bj], axis=1)
    override_f, coh, ts = joint_laws(scene, pairs)
    return Contacts(
        dimension=2, pairs=pairs, normals=n_out, tangents=tangent[:, None, :],
        points=points, joint_start=np.arange(0, 2 * m + 1, 2), areas=seg * depth,
        lengths=seg, override_friction=override_f, cohesion=coh, tensile_strength=ts,
        block_ids=tuple(b.id for b in scene.blocks))


def joint_laws(scene: Scene, pairs: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per-joint (override friction or NaN, cohesion, tensile strength)."""
    from ..scene.model import friction_value

    m = len(pairs)
    fr = np.full(m, np.nan)
    coh = np.zeros(m)
    ts = np.zeros(m)
    if not scene.joints:
        return fr, coh, ts
    idx = scene.index
    table = {}
    for j in scene.joints:
        table[frozenset((idx[j.blocks[0]], idx[j.blocks[1]]))] = j
    found = set()
    for k, (a, b) in enumerate(pairs):
        key = frozenset((int(a), int(b)))
        j = table.get(key)
        if j is None:
            continue
        found.add(key)
        if j.friction is not None:
            fr[k] = friction_value(j.friction)
        coh[k] = j.cohesion or 0.0
        ts[k] = j.tensile_strength or 0.0
    fixed = {k for k, b in enumerate(scene.blocks) if b.support}
    for key, j in table.items():
        # two supports have no joint (they touch or not, nothing there is computed): a
        # generator's override of its foundation's joint stays valid where the block on
        # it is made a support
        if key not in found and not key <= fixed:
            raise InputError(f"blocks {j.blocks[0]!r} and {j.blocks[1]!r} are not in "
                             "contact, so their joint cannot be overridden",
                             f"joint {j.blocks[0]!r}-{j.blocks[1]!r}")
    return fr, coh, ts


def block_where(scene: Scene, block: str) -> str:
    """A block named in an error, after its scene's file where it has one."""
    return f"{scene.source}: block {block!r}" if scene.source else f"block {block!r}"
