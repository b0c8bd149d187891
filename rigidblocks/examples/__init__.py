"""Deprecated alias of :mod:`rigidblocks.generators` (the structure builders).

``rigidblocks.examples`` and its submodules (``rigidblocks.examples.arches`` ...) are
the very modules of :mod:`rigidblocks.generators`; importing them warns once.
"""

from __future__ import annotations

import importlib
import sys
import warnings

from .. import generators as _generators
from ..generators import *  # noqa: F403
from ..generators import __all__  # noqa: F401

warnings.warn("rigidblocks.examples is renamed rigidblocks.generators; import that instead",
              DeprecationWarning, stacklevel=2)

for _name in ("arches", "catalogue", "keyed", "seed", "solids", "walls"):
    try:
        _module = importlib.import_module(f"{_generators.__name__}.{_name}")
    except ImportError:  # pragma: no cover - a module missing from a partial install
        continue
    sys.modules[f"{__name__}.{_name}"] = _module
    globals()[_name] = _module
