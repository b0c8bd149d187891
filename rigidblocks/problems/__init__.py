"""The problem builder and the analyses built on it."""

from .analysis import check, max_load_multiplier, min_friction

__all__ = ["check", "max_load_multiplier", "min_friction"]
