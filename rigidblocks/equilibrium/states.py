"""The two readings of the equilibrium matrix A: link forces x as joint resultants
(statics: :func:`force_state`) and the duals of the equilibrium rows as block velocities
(kinematics: :func:`mechanism`)."""

from __future__ import annotations

import numpy as np

from ..results import ZERO_FORCE, ForceState, Mechanism
from .assembly import EquilibriumSystem

#: a joint's opening or slip below this fraction of the mechanism's largest counts as
#: none when joints are classified (interior-point duals spread round-off of the order
#: of the solver's tolerance over every joint)
MODE_TOL = 1e-6
#: a joint slides, or hinges as it slides, when its slip, or the spread of its opening
#: over its points, exceeds this fraction of the joint's own largest motion
MODE_SHARE = 0.1
#: link forces all below this fraction of the largest load on a block are the solver's
#: round-off of a state that carries nothing
NOISE = 1e-9


def force_state(system: EquilibriumSystem, x: np.ndarray, method: str) -> ForceState:
    """Joint resultants, eccentricities and the thrust line of link forces ``x``; where
    nothing loads the blocks (every force below ``NOISE`` of their largest load, or no
    load at all) the state without forces: a weightless drawing without loads gave
    |T|/N = 8.5 from forces of 1e-12."""
    load = _load_scale(system)
    if float(np.abs(x).max(initial=0.0)) <= NOISE * load or load == 0.0:
        x = np.zeros_like(x)
    c = system.contacts
    lay = system.layout
    pj = c.point_joint
    m = c.n_joints
    N = x[lay.normal]
    Nj = np.bincount(pj, N, minlength=m)
    d = c.dimension
    if d == 2:
        if lay.shear == "joint":
            Tj = x[lay.tangential]
            share = np.where(Nj[pj] > 0, N / np.where(Nj[pj] > 0, Nj[pj], 1.0),
                             1.0 / np.diff(c.joint_start)[pj])
            T = Tj[pj] * share
        else:
            T = x[lay.tangential]
            Tj = np.bincount(pj, T, minlength=m)
        mid = 0.5 * (c.points[c.joint_start[:-1]] + c.points[c.joint_start[1:] - 1])
        s = c.tangents[:, 0, :]
        arm = np.einsum("ij,ij->i", c.points - mid[pj], s[pj])
        with np.errstate(invalid="ignore", divide="ignore"):
            ecc = np.bincount(pj, N * arm, minlength=m) / Nj
        ecc = np.where(np.abs(Nj) > 0, ecc, np.nan)
        thrust = mid + np.nan_to_num(ecc)[:, None] * s
        Tabs = np.abs(Tj)
    else:
        T = x[lay.tangential].reshape(-1, 2)
        Tvec = np.zeros((m, 3))
        for k in range(2):
            np.add.at(Tvec, pj, T[:, k:k + 1] * c.tangents[pj, k, :])
        Tabs = np.linalg.norm(Tvec, axis=1)
        Tj = Tabs
        with np.errstate(invalid="ignore", divide="ignore"):
            centre = np.stack([np.bincount(pj, N * c.points[:, k], minlength=m)
                               for k in range(3)], axis=1) / Nj[:, None]
        ecc = np.full(m, np.nan)
        thrust = np.where(np.isfinite(centre), centre, 0.0)
    scale = max(float(np.abs(Nj).max(initial=0.0)), 1e-300)
    with np.errstate(invalid="ignore", divide="ignore"):
        demand = np.where(Nj > 1e-12 * scale, Tabs / np.where(Nj > 0, Nj, 1.0),
                          np.where(Tabs > 1e-12 * scale, np.inf, 0.0))
    walk = chain_walk(system)
    return ForceState(normal=N, shear=T, joint_normal=Nj, joint_shear=Tj, eccentricity=ecc,
                      demand=demand, thrust_points=thrust,
                      thrust_order=np.arange(m) if walk is None else walk, method=method,
                      thrust_chain=walk is not None)


def _load_scale(system: EquilibriumSystem) -> float:
    """The largest load on a block, dead or live (force units)."""
    return max(float(np.abs(system.dead).max(initial=0.0)),
               float(np.abs(system.live).max(initial=0.0)))


def joint_breaches(system: EquilibriumSystem, x: np.ndarray, f_joint: np.ndarray,
                   ) -> np.ndarray:
    """(m,) how far each joint's forces in the state ``x`` (force units) breach its laws,
    as a force: the tension beyond the tensile strength summed over the joint's contact
    points, or the shear beyond f N + c a (per joint in 2D), whichever is larger; in 3D
    (and with one shear per point) the sum over the points of each point's larger breach.
    0 where the laws hold. (The largest point's breach was given: a box short of friction
    by 0.6 read 0.15 on its four corners, less on a finer polygon.)"""
    c = system.contacts
    lay = system.layout
    pj = c.point_joint
    m = c.n_joints
    N = x[lay.normal]
    cap = c.tensile_strength[pj] * c.point_areas
    point = np.maximum(-(N + cap), 0.0)
    fin = np.isfinite(f_joint)
    fj = np.where(fin, f_joint, 0.0)
    if c.dimension == 2 and lay.shear == "joint":
        Nj = np.bincount(pj, N, minlength=m)
        over = np.abs(x[lay.tangential]) - fj * Nj - c.cohesion * c.areas
        out = np.maximum(np.bincount(pj, point, minlength=m), np.where(fin, over, 0.0))
    else:
        T = x[lay.tangential].reshape(len(N), -1)
        over = np.linalg.norm(T, axis=1) - fj[pj] * N - c.cohesion[pj] * c.point_areas
        out = np.bincount(pj, np.maximum(point, np.where(fin[pj], over, 0.0)), minlength=m)
    return np.maximum(out, 0.0)


def chain_order(system: EquilibriumSystem) -> np.ndarray:
    """Joints in order along the structure when the blocks form a chain (an arch), else
    in detection order (:func:`chain_walk` tells which)."""
    order = chain_walk(system)
    return np.arange(system.contacts.n_joints) if order is None else order


def chain_walk(system: EquilibriumSystem) -> np.ndarray | None:
    """Joints in order along the structure where the blocks form a chain, else None.

    A chain: every free block has exactly two joints, to different neighbours, and the
    walk from a support reaches every joint.
    """
    c = system.contacts
    m = c.n_joints
    free = system.block_rows >= 0
    deg = np.bincount(c.pairs.ravel(), minlength=len(free))
    if m < 2 or np.any(deg[free] != 2):
        return None
    by_block: dict[int, list[int]] = {}
    for k, (a, b) in enumerate(c.pairs):
        by_block.setdefault(int(a), []).append(k)
        by_block.setdefault(int(b), []).append(k)
    starts = [k for k in range(m) if not (free[c.pairs[k, 0]] and free[c.pairs[k, 1]])]
    if not starts:
        return None
    k = starts[0]
    a, b = c.pairs[k]
    here = int(b) if free[b] else int(a)
    order = [k]
    used = {k}
    while free[here]:
        nxt = [j for j in by_block[here] if j not in used]
        if len(nxt) != 1:
            return None
        k = nxt[0]
        used.add(k)
        order.append(k)
        a, b = c.pairs[k]
        here = int(b) if int(a) == here else int(a)
    return np.array(order) if len(order) == m else None


def mechanism(system: EquilibriumSystem, row_scale: np.ndarray, y_eq: np.ndarray,
              kind: str = "blend", x: np.ndarray | None = None,
              driver: np.ndarray | None = None) -> Mechanism:
    """Virtual velocities from the duals ``y_eq`` of the equilibrium rows, scaled by
    ``row_scale`` (the rows' scaling in the problem, :class:`Scaling` ``.row``);
    ``kind`` says how the duals were chosen (see :class:`Mechanism`).

    ``x``, the link forces (force units) of the state the duals go with: a joint slides
    only where it slips at contact points that carry force or stay shut. Where a point
    carries none, the joint law admits any motion that opens it (with friction that
    dilates, opening at least f times the slip), and a vertex of the duals may take
    such a slip: a block lifted off its base read "sliding", a box tipping over its
    corner at |T|/N = 0.71 < f = 1 "sliding and hinging".

    The duals' sign is chosen so that ``driver`` (the live load by default; the dead
    load for a mechanism the dead load drives) does positive work on the motion."""
    v = row_scale * y_eq
    if v @ (system.live if driver is None else driver) < 0:
        v = -v
    d = system.dofs
    free = system.free_blocks
    vb = v.reshape(-1, d)
    nd = system.contacts.dimension
    mag = np.linalg.norm(vb[:, :nd], axis=1) + np.linalg.norm(vb[:, nd:], axis=1) * \
        system.sizes[free]
    top = mag.max(initial=0.0)
    if top > 0:
        v = v / top
    vel = np.zeros((len(system.block_rows), d))
    vel[free] = v.reshape(-1, d)
    delta = system.A.T @ v  # relative displacements at the links
    lay = system.layout
    c = system.contacts
    opening = delta[lay.normal]
    slip = delta[lay.tangential]
    tol = MODE_TOL * max(np.abs(delta).max(initial=0.0), 1e-300)
    pressed = np.ones(len(opening), dtype=bool)
    if x is not None:
        # a point carries force as the tables say a joint does (ZERO_FORCE of the largest
        # joint force: a wall's joint at 2.6e-5 of it read "slide+hinge" beside "open")
        N = np.asarray(x)[lay.normal]
        Nj = np.bincount(c.point_joint, N, minlength=c.n_joints)
        pressed = N > ZERO_FORCE * max(float(np.abs(Nj).max(initial=0.0)),
                                       MODE_TOL * _load_scale(system))
    per_point = np.abs(slip.reshape(len(opening), -1)).max(axis=1) \
        if not (lay.shear == "joint" and nd == 2) else None
    modes = []
    rates = np.zeros(c.n_joints)
    for k in range(c.n_joints):
        pts = slice(c.joint_start[k], c.joint_start[k + 1])
        dn = opening[pts]
        moved = abs(slip[k]) if per_point is None else float(per_point[pts].max())
        rates[k] = max(moved, float(np.abs(dn).max(initial=0.0)))
        # what the joint does is what makes up more than MODE_SHARE of its motion (a
        # sliding joint of a 3D mechanism also turns a little: it slides)
        share = max(tol, MODE_SHARE * rates[k])
        # its slip counts at points that carry force or stay shut (a block may slide out
        # from under another that rests elsewhere: in contact, without force), not at
        # points that open without force
        counts = pressed[pts] | (dn <= share)
        if per_point is None:
            ds = moved if counts.any() else 0.0
        else:
            ds = float(per_point[pts][counts].max(initial=0.0))
        uneven = dn.max() - dn.min() > share
        if ds > share:
            modes.append("slide+hinge" if uneven else "slide")
        elif dn.max() > tol:
            modes.append("hinge" if dn.min() <= share else "open")
        else:
            modes.append("closed")
    return Mechanism(velocities=vel, opening=opening, slip=slip, modes=tuple(modes),
                     rates=rates, kind=kind)
