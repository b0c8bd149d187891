"""The problem builder: equilibrium plus joint laws as standard-form conic problems
(:mod:`.formulation`).

The analyses that used to live here are in :mod:`rigidblocks.analyses`;
``rigidblocks.problems.check`` and the like still work and warn.
"""

from __future__ import annotations

import importlib
import warnings
from typing import Any

from .formulation import Scaling, build_energy_qp, build_max_load, build_relaxation

_MOVED = ("check", "max_load_multiplier", "min_friction")


def __getattr__(name: str) -> Any:
    if name in _MOVED:
        warnings.warn(f"rigidblocks.problems.{name} moved to rigidblocks.analyses.{name} "
                      f"(or rigidblocks.{name})", DeprecationWarning, stacklevel=2)
        return getattr(importlib.import_module("rigidblocks.analyses"), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["Scaling", "build_energy_qp", "build_max_load", "build_relaxation"]
