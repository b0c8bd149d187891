"""Joint resultants of a force state as vectors (mechanics shared by pictures and CAD)."""

from __future__ import annotations

from typing import Any

import numpy as np


def joint_force_vectors(contacts: Any, state: Any) -> np.ndarray:
    """(m, 2) resultant force on the second block of each 2D joint: N n + T s, with n the
    joint's unit normal (from its first block into its second), s = (-n_y, n_x) its
    tangent, and N, T the joint resultants of ``state``."""
    n = contacts.normals
    s = contacts.tangents[:, 0, :]
    return state.joint_normal[:, None] * n + state.joint_shear[:, None] * s


__all__ = ["joint_force_vectors"]
