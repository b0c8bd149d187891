"""Optional dependencies: which extra (or package) to install for what."""

from __future__ import annotations

import importlib
from types import ModuleType

from .errors import InputError

#: extra -> the modules it provides
EXTRAS: dict[str, tuple[str, ...]] = {
    "cad": ("ezdxf",),
    "study": ("pandas", "pyarrow", "tqdm"),
    "solvers": ("highspy", "ecos"),
}
#: solvers reached through cvxpy that no extra installs -> how to install them
SOLVER_PACKAGES: dict[str, str] = {"ecos": "ecos", "scs": "scs", "highs": "highspy",
                                   "osqp": "osqp", "clarabel": "clarabel",
                                   "gurobi": "gurobipy", "mosek": "mosek"}


def require(extra: str, what: str, modules: tuple[str, ...] | None = None) -> list[ModuleType]:
    """Import the modules of ``extra`` (or ``modules``); if one is missing, an
    InputError saying that ``what`` needs it and ``pip install 'rigidblocks[extra]'``."""
    out = []
    for name in modules if modules is not None else EXTRAS[extra]:
        try:
            out.append(importlib.import_module(name))
        except ImportError:
            raise InputError(f"{what} needs the {name} package: "
                             f"pip install 'rigidblocks[{extra}]'") from None
    return out


def solver_install_hint(solver: str) -> str:
    """How to install a convex solver for cvxpy, e.g. ``pip install ecos``."""
    name = solver.lower().removeprefix("cvxpy-")
    if name in ("highs", "ecos"):
        return "pip install 'rigidblocks[solvers]'"
    return f"pip install {SOLVER_PACKAGES.get(name, name)}"


__all__ = ["EXTRAS", "require", "solver_install_hint"]
