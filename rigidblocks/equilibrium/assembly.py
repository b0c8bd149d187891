"""The equilibrium system ``A x + F_dead + lambda F_live = 0`` of the free blocks.

Conventions (docs/design.md): at contact point k of the joint between blocks i and j
(normal n from i into j), the normal force N_k >= 0 is a compression; the force on j is
``N_k n + T s`` and the force on i its opposite. Every free block has ``d + r`` rows
(2D: Fx, Fy, M; 3D: Fx, Fy, Fz, Mx, My, Mz), moments taken about the block's centroid;
support blocks have no rows.

Columns are named blocks of the vector x (see :class:`Layout`): the normal force at
each contact point, then the shear. In 2D one shear per joint is exact and leaner (the
moment of a force along the joint's line does not depend on where on the line it acts);
one shear per point is available as ``shear="point"``. In 3D there are two tangential
components per contact point.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Literal

import numpy as np

from ..contacts import Contacts, detect_contacts
from ..errors import InputError
from ..scene.geometry import block_weights
from ..scene.model import Scene
from ..scene.validate import DEFAULT_TOL
from ..sparse import CscMatrix

ShearLayout = Literal["joint", "point"]


@dataclass(frozen=True)
class Layout:
    """Where each kind of unknown sits in x.

    ``normal`` covers one column per contact point (in the order of
    ``Contacts.points``); ``shear`` one column per joint (2D, ``shear="joint"``), one
    per point (2D, ``shear="point"``), or two per point (3D, interleaved t1, t2).
    """

    n_points: int
    n_shear: int
    shear: ShearLayout

    @property
    def normal(self) -> slice:
        return slice(0, self.n_points)

    @property
    def tangential(self) -> slice:
        return slice(self.n_points, self.n_points + self.n_shear)

    @property
    def size(self) -> int:
        return self.n_points + self.n_shear


@dataclass(frozen=True, eq=False)
class EquilibriumSystem:
    """Sparse equilibrium matrix, load vectors and index maps.

    Attributes:
        A: (rows, columns) sparse CSC matrix in the scene's units (a
            :class:`~rigidblocks.sparse.CscMatrix`: ``A.tocsc()`` is scipy's).
        dead, live: load vectors (forces and moments about centroids) on the rows.
        layout: the named blocks of columns.
        contacts: the joints the columns belong to.
        block_rows: (n_blocks,) first row of each block; -1 for support blocks.
        dofs: rows per free block (3 in 2D, 6 in 3D).
        centroids: (n_blocks, d) moment reference point of each block.
        weights: (n_blocks,) self-weight of each block.
        sizes: (n_blocks,) bounding-box diagonal of each block.
    """

    A: CscMatrix
    dead: np.ndarray
    live: np.ndarray
    layout: Layout
    contacts: Contacts
    block_rows: np.ndarray
    dofs: int
    centroids: np.ndarray
    weights: np.ndarray
    sizes: np.ndarray

    @property
    def n_rows(self) -> int:
        return self.A.shape[0]

    @property
    def free_blocks(self) -> np.ndarray:
        """Scene indices of the free blocks, in row order."""
        return np.flatnonzero(self.block_rows >= 0)

    @cached_property
    def _adrift(self) -> tuple[np.ndarray, np.ndarray]:
        """The force rows (k, d) of the free blocks joined to no support, and each one's
        group (k,)."""
        from ..contacts.model import block_groups

        comp = block_groups(len(self.block_rows), self.contacts.pairs)
        held = np.isin(comp, comp[self.block_rows < 0])
        adrift = np.flatnonzero((self.block_rows >= 0) & ~held)
        d = self.centroids.shape[1]  # force rows first in each block's rows
        return self.block_rows[adrift][:, None] + np.arange(d), comp[adrift]

    def unheld_load(self, load_factor: float) -> float:
        """The largest resultant force of the loads (dead + ``load_factor`` x live) on a
        group of free blocks joined to one another and to no support, relative to the
        largest block load: above round-off, no equilibrium state exists (the group's
        joint forces cancel in its resultant), whatever the joint laws."""
        rows, group = self._adrift
        if not len(rows):
            return 0.0
        load = (self.dead + load_factor * self.live)[rows]  # (k, d)
        force = self.block_rows[self.block_rows >= 0][:, None] + \
            np.arange(self.centroids.shape[1])
        scale = max(float(np.abs(self.dead[force]).max(initial=0.0)),
                    abs(load_factor) * float(np.abs(self.live[force]).max(initial=0.0)),
                    1e-300)
        _, which = np.unique(group, return_inverse=True)
        sums = np.zeros((int(which.max()) + 1, load.shape[1]))
        np.add.at(sums, which, load)
        return float(np.linalg.norm(sums, axis=1).max()) / scale

    def equations_residual(self, load_factor: float) -> float:
        """How far the equilibrium equations A x + F_dead + ``load_factor`` F_live = 0
        miss a solution, whatever the joint laws: the largest entry of the least-squares
        residual relative to the largest load entry (0 where they have a solution; a
        block's own load is no scale: one that weighs nothing carries what rests on
        it). Independent of the solvers: a solver that reports no equilibrium state is
        confirmed by it (a block of weight 5e-14 under a 10 kN point load read "the
        scene is a mechanism")."""
        from scipy.sparse.linalg import lsqr

        b = -(self.dead + load_factor * self.live)
        if not np.any(b):
            return 0.0
        A = self.A.tocsc()
        x = lsqr(A, b, atol=1e-15, btol=1e-15, conlim=1e16,
                 iter_lim=20 * max(A.shape))[0]
        r = np.abs(A @ x - b)
        return float(r.max(initial=0.0)) / float(np.abs(b).max())

    def rows_of(self, block: int) -> slice:
        r = int(self.block_rows[block])
        if r < 0:
            raise KeyError(f"block {block} is a support and has no rows")
        return slice(r, r + self.dofs)

    def point_columns(self, joint: int) -> np.ndarray:
        """Normal-force columns of a joint's contact points."""
        js = self.contacts.joint_start
        return np.arange(js[joint], js[joint + 1])


def _cross(r: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Moment of force f at arm r: scalar (2D, shape (k, 1)) or vector (3D)."""
    if r.shape[1] == 2:
        return (r[:, 0] * f[:, 1] - r[:, 1] * f[:, 0])[:, None]
    return np.cross(r, f)


def assemble(scene: Scene, contacts: Contacts | None = None, *, shear: ShearLayout = "joint",
             tol: float = DEFAULT_TOL) -> EquilibriumSystem:
    """Assemble the equilibrium system of a scene (vectorised; no loop over contacts)."""
    if contacts is None:
        contacts = detect_contacts(scene, tol)
    d = scene.dimension
    dofs = 3 if d == 2 else 6
    nb = len(scene.blocks)
    support = scene.support_mask
    block_rows = np.full(nb, -1)
    block_rows[~support] = np.arange(int((~support).sum())) * dofs
    n_rows = int((~support).sum()) * dofs
    weights, centroids, sizes = block_weights(scene)

    pj = contacts.point_joint
    P = contacts.n_points
    if d == 2 and shear == "joint":
        first = contacts.joint_start[:-1]
        t_pts = contacts.points[first]
        t_dirs = contacts.tangents[:, 0, :]
        t_joint = np.arange(contacts.n_joints)
    elif d == 2 and shear == "point":
        t_pts = contacts.points
        t_dirs = contacts.tangents[pj, 0, :]
        t_joint = pj
    elif d == 3:
        t_pts = np.repeat(contacts.points, 2, axis=0)
        t_dirs = contacts.tangents[pj].reshape(-1, 3)
        t_joint = np.repeat(pj, 2)
    else:
        raise InputError(f'shear layout must be "joint" or "point", got "{shear}"')
    layout = Layout(P, len(t_pts), "point" if d == 3 else shear)

    # every column: a unit force `dirs` at `pts`, acting on j (+) and on i (-)
    pts = np.concatenate([contacts.points, t_pts])
    dirs = np.concatenate([contacts.normals[pj], t_dirs])
    joint = np.concatenate([pj, t_joint])
    cols = np.arange(layout.size)
    rows_list, cols_list, vals_list = [], [], []
    for side, sign in ((1, 1.0), (0, -1.0)):
        blk = contacts.pairs[joint, side]
        r0 = block_rows[blk]
        on = r0 >= 0
        if not on.any():
            continue
        c, p, f, b = cols[on], pts[on], dirs[on], blk[on]
        mom = _cross(p - centroids[b], f)
        entries = np.concatenate([f, mom], axis=1) * sign  # (k, dofs)
        rows_list.append((r0[on][:, None] + np.arange(dofs)[None, :]).ravel())
        cols_list.append(np.repeat(c, dofs))
        vals_list.append(entries.ravel())
    vals, rows, cols = (np.concatenate(parts) if parts else np.zeros(0, dtype=np.int64)
                        for parts in (vals_list, rows_list, cols_list))
    nz = vals != 0  # zero components of forces and moments are not stored
    A = CscMatrix.from_triplets(vals[nz], rows[nz], cols[nz], (n_rows, layout.size))
    dead, live = load_vectors(scene, block_rows, dofs, weights, centroids)
    return EquilibriumSystem(A=A, dead=dead, live=live, layout=layout, contacts=contacts,
                             block_rows=block_rows, dofs=dofs, centroids=centroids,
                             weights=weights, sizes=sizes)


def load_vectors(scene: Scene, block_rows: np.ndarray, dofs: int, weights: np.ndarray,
                 centroids: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Dead and live load vectors: self-weight, point loads, couples, live body force."""
    d = scene.dimension
    n_rows = int((block_rows >= 0).sum()) * dofs
    dead = np.zeros(n_rows)
    live = np.zeros(n_rows)
    free = block_rows >= 0
    r = block_rows[free]
    # self-weight at the centroid: no moment about it
    dead[r + d - 1] -= weights[free]
    if scene.live_body_force is not None:
        g = np.asarray(scene.live_body_force, dtype=float)
        for k in range(d):
            live[r + k] += weights[free] * g[k]
    idx = scene.index
    for ld in scene.loads:
        b = idx[ld.block]
        r0 = block_rows[b]
        f = np.asarray(ld.force, dtype=float)
        vec = np.zeros(dofs)
        vec[:d] = f
        if ld.point is not None:
            arm = np.asarray(ld.point, dtype=float) - centroids[b]
            vec[d:] += _cross(arm[None, :], f[None, :])[0]
        if ld.moment is not None:
            vec[d:] += np.atleast_1d(np.asarray(ld.moment, dtype=float))
        target = live if ld.is_live else dead
        target[r0:r0 + dofs] += vec
    return dead, live
