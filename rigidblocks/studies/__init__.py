"""Studies built on the analyses: parametric sweeps and geometric safety factors."""

from .thickness import ThicknessResult, min_thickness

__all__ = ["ThicknessResult", "min_thickness"]
