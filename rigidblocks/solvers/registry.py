"""The back ends by name: :func:`solve` dispatches a standard-form problem to one."""

from __future__ import annotations

from ..errors import InputError
from .base import ConicProblem, SolverResult

#: back ends by name; "cvxpy-NAME" reaches any solver installed for cvxpy
SOLVERS = ("clarabel", "highs", "osqp", "scs", "ecos")


def solve(problem: ConicProblem, solver: str = "clarabel", after: dict | None = None,
          **settings) -> SolverResult:
    """Solve a standard-form problem with the named back end.

    Names: ``clarabel`` (native, default), ``highs`` (scipy's HiGHS, LPs), ``osqp``
    (QPs and LPs with linear constraints), ``scs`` / ``ecos`` (through cvxpy), or
    ``cvxpy-NAME`` for any solver cvxpy has installed. ``after``: the settings of
    the solve the caller would try next, where the solve may stop once it stalls
    (:mod:`~rigidblocks.solvers.clarabel_backend`; the other back ends run to their
    own end).
    """
    name = solver.lower()
    if name == "clarabel":
        from .clarabel_backend import solve_clarabel

        return solve_clarabel(problem, after=after, **settings)
    if name == "highs":
        from .highs_backend import solve_highs

        return solve_highs(problem, **settings)
    if name == "osqp":
        from .osqp_backend import solve_osqp

        return solve_osqp(problem, **settings)
    if name in ("scs", "ecos") or name.startswith("cvxpy-"):
        from .cvxpy_backend import solve_cvxpy

        return solve_cvxpy(problem, name.removeprefix("cvxpy-"), **settings)
    raise InputError(f"unknown solver {solver!r} (choose from {', '.join(SOLVERS)} "
                     "or cvxpy-NAME)")
