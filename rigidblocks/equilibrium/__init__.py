"""Equilibrium assembly: the sparse matrix A, load vectors and index maps."""

from .assembly import EquilibriumSystem, Layout, assemble, load_vectors

__all__ = ["EquilibriumSystem", "Layout", "assemble", "load_vectors"]
