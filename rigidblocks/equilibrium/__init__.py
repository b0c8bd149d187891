"""Equilibrium assembly: the sparse matrix A, load vectors and index maps; link forces
read as joint resultants and duals read as block velocities."""

from .assembly import EquilibriumSystem, Layout, assemble, load_vectors
from .states import chain_order, force_state, joint_breaches, mechanism

__all__ = ["EquilibriumSystem", "Layout", "assemble", "chain_order", "force_state",
           "joint_breaches", "load_vectors", "mechanism"]
