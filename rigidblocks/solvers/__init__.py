"""Solver back ends behind one interface (:func:`solve`), and the policy that drives
them (:mod:`.policy`). The distortion iteration (:mod:`.distortion`) is the other solver:
it solves the force-state QP by impressed distortions."""

from __future__ import annotations

from .base import FAILURE, INFEASIBLE, OPTIMAL, UNBOUNDED, ConicProblem, SolverResult
from .policy import Runner, check_solver
from .registry import SOLVERS, solve

__all__ = ["FAILURE", "INFEASIBLE", "OPTIMAL", "UNBOUNDED", "ConicProblem", "Runner",
           "SOLVERS", "SolverResult", "check_solver", "solve"]
