"""rigidblocks: limit analysis of rigid-block masonry with unilateral frictional joints."""

from typing import Any as _Any

from ._version import __version__
from .analyses import check, load_path, max_load_multiplier, min_friction
from .contacts import Contacts, detect_contacts
from .equilibrium import EquilibriumSystem, assemble
from .errors import InputError, RigidBlocksError, SolverFailure
from .io import read_scene, write_scene
from .scene import INFINITE, Block, JointOverride, Load, Scene, Units, make_block


def __getattr__(name: str) -> _Any:
    """``rigidblocks.study`` (the studies package, also ``import rigidblocks.study``, see
    :mod:`rigidblocks.study`) and ``min_thickness``, imported when first asked for: the
    sweeps' modules are not part of an analysis' start-up (about 25 ms)."""
    if name == "study":
        import importlib

        return importlib.import_module(f"{__name__}.study")
    if name == "min_thickness":
        from .studies import min_thickness

        return min_thickness
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def plot(scene: Scene, result: object = None, ax: object = None, **kwargs: object) -> object:
    """Draw a 2D or 3D scene and a result; see :func:`rigidblocks.plotting.plot`."""
    from .plotting import plot as _plot

    return _plot(scene, result, ax, **kwargs)


def report(scene: object, result: object = None, **kwargs: object) -> str:
    """A self-contained HTML report (a ``str`` that shows itself in a notebook); see
    :func:`rigidblocks.reporting.report`."""
    from .reporting import report as _report

    return _report(scene, result, **kwargs)  # type: ignore[arg-type]


def read_dxf(path: object, **kwargs: object) -> object:
    """Read a DXF drawing as a scene; see :func:`rigidblocks.io.dxf.read_dxf` (needs ezdxf)."""
    from .io.dxf import read_dxf as _read_dxf

    return _read_dxf(path, **kwargs)  # type: ignore[arg-type]


__all__ = [
    "__version__", "INFINITE", "Block", "Contacts", "EquilibriumSystem", "InputError",
    "JointOverride",
    "Load", "RigidBlocksError", "Scene", "SolverFailure", "Units", "assemble", "detect_contacts",
    "check", "make_block", "max_load_multiplier", "min_friction", "plot", "read_dxf", "report",
    "read_scene", "write_scene", "load_path", "min_thickness",
]
