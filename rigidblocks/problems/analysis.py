"""Deprecated home of the analyses: see :mod:`rigidblocks.analyses` (and, for the
convex path's settings and tolerances, :mod:`rigidblocks.methods.convex` and
:mod:`rigidblocks.solvers.policy`)."""

from __future__ import annotations

import warnings

from ..analyses import check, max_load_multiplier, min_friction
from ..equilibrium import chain_order, force_state, mechanism

warnings.warn("rigidblocks.problems.analysis moved to rigidblocks.analyses",
              DeprecationWarning, stacklevel=2)

__all__ = ["chain_order", "check", "force_state", "max_load_multiplier", "mechanism",
           "min_friction"]
