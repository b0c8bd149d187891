"""Studies built on the analyses: parametric sweeps and geometric safety factors."""

from .spec import read_spec
from .sweep import StudyResult, Sweep, make_sweep
from .thickness import ThicknessResult, min_thickness

__all__ = ["StudyResult", "Sweep", "ThicknessResult", "make_sweep", "min_thickness",
           "read_spec"]
