"""Joints between blocks: contact points, local frames, areas and joint laws."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def block_groups(n_blocks: int, pairs: np.ndarray) -> np.ndarray:
    """(n_blocks,) each block's group of blocks joined to one another (by ``pairs``, the
    joints' block index pairs): the smallest index of the group, spread along the
    joints and by pointer jumping (numpy alone: `check` imports no more than it
    uses)."""
    pairs = np.asarray(pairs, dtype=int).reshape(-1, 2)
    comp = np.arange(n_blocks)
    while len(pairs):
        low = np.minimum(comp[pairs[:, 0]], comp[pairs[:, 1]])
        new = comp.copy()
        np.minimum.at(new, pairs[:, 0], low)
        np.minimum.at(new, pairs[:, 1], low)
        new = new[new]
        if np.array_equal(new, comp):
            break
        comp = new
    return comp


@dataclass(frozen=True, eq=False)
class Contacts:
    """Every joint of a scene, as flat arrays (dimension-generic).

    A joint is one contact segment (2D) or polygon (3D) between blocks ``pairs[k, 0]``
    (i) and ``pairs[k, 1]`` (j). Its unit normal points from i into j; in 2D its tangent
    is ``s = (-n_y, n_x)``, in 3D it has two tangents. The contact points of joint k are
    ``points[joint_start[k]:joint_start[k + 1]]``: the two end points of the segment in
    2D, the vertices of the contact polygon in 3D.

    Attributes:
        pairs: (m, 2) block indices into ``scene.blocks``.
        normals: (m, d) unit normals from i into j.
        tangents: (m, d - 1, d) unit tangents.
        points: (P, d) contact points.
        joint_start: (m + 1,) offsets of each joint's points.
        areas: (m,) contact area (2D: segment length x depth).
        lengths: (m,) segment length (2D) or square root of the polygon's area (3D).
        override_friction: (m,) the joint's own friction from a scene override; NaN
            where the joint takes the uniform (scene or analysis) value; inf is
            "infinite".
        cohesion: (m,) cohesion (stress) of each joint.
        tensile_strength: (m,) tensile strength (stress) of each joint.
        block_ids: ids of the scene's blocks, for messages and reports.
    """

    dimension: int
    pairs: np.ndarray
    normals: np.ndarray
    tangents: np.ndarray
    points: np.ndarray
    joint_start: np.ndarray
    areas: np.ndarray
    lengths: np.ndarray
    override_friction: np.ndarray
    cohesion: np.ndarray
    tensile_strength: np.ndarray
    block_ids: tuple[str, ...]

    @property
    def n_joints(self) -> int:
        return len(self.pairs)

    @property
    def n_points(self) -> int:
        return len(self.points)

    @property
    def point_joint(self) -> np.ndarray:
        """(P,) the joint of each contact point."""
        return np.repeat(np.arange(self.n_joints), np.diff(self.joint_start))

    @property
    def joint_centres(self) -> np.ndarray:
        """(m, d) the mean of each joint's contact points (in 3D the corners of its
        contact polygon)."""
        counts = np.diff(self.joint_start)
        return np.stack([np.bincount(self.point_joint, self.points[:, k],
                                     minlength=self.n_joints)
                         for k in range(self.points.shape[1])], axis=1) / counts[:, None]

    @property
    def point_areas(self) -> np.ndarray:
        """(P,) each point's share of its joint's area (equal shares)."""
        counts = np.diff(self.joint_start)
        return np.repeat(self.areas / counts, counts)

    def opposed_pairs(self, cos: float = -0.99) -> list[tuple[int, int]]:
        """The block pairs that touch on faces facing each other's opposite ways (two
        of their joints' normals at a cosine below ``cos``): a key in its groove. Along
        those faces the blocks cannot slide with friction that dilates (opening one
        face closes the other)."""
        if not self.n_joints:
            return []
        lo, hi = self.pairs.min(axis=1), self.pairs.max(axis=1)
        # each normal from the pair's lower block into its higher one
        n = np.where((self.pairs[:, 0] == lo)[:, None], self.normals, -self.normals)
        key = lo.astype(np.int64) * (int(hi.max()) + 1) + hi
        order = np.argsort(key, kind="stable")
        _, start, count = np.unique(key[order], return_index=True, return_counts=True)
        out = []
        for s0, k in zip(start[count > 1], count[count > 1], strict=True):
            js = order[s0:s0 + k]  # the joints of one pair that touches on several faces
            if float(np.min(n[js] @ n[js].T)) < cos:
                out.append((int(js.min()), int(lo[js[0]]), int(hi[js[0]])))
        return [(a, b) for _, a, b in sorted(out)]  # in the order of their first joints

    def block_pairs_ids(self) -> list[tuple[str, str]]:
        """(id_i, id_j) of every joint."""
        ids = self.block_ids
        return [(ids[a], ids[b]) for a, b in self.pairs]

    def joint_label(self, k: int) -> str:
        a, b = self.pairs[k]
        return f"{self.block_ids[a]}-{self.block_ids[b]}"
