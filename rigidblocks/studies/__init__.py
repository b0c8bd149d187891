"""Studies built on the analyses: parametric sweeps and geometric safety factors.

Also reachable as ``from rigidblocks import study``: ``study.run(...)`` runs a sweep (a
generator or a scene, the cases and the analyses) on local processes or a Dask cluster
and returns a :class:`StudyResult` whose ``frame`` is a pandas DataFrame (one row per
case) and whose ``plot(x=..., y=...)`` draws a chart; ``study.read_spec(path)`` reads a
sweep spec file (``docs/sweep-format.md``). See :mod:`rigidblocks.studies.sweep`.
Sweeps need the ``study`` extra (pandas, pyarrow, tqdm; dask[distributed] for clusters).
"""

from .spec import read_spec, spec_from_dict
from .sweep import (
    ANALYSES,
    Analysis,
    StudyResult,
    Sweep,
    expand_cases,
    make_sweep,
    plot,
    run,
)
from .thickness import ThicknessResult, min_thickness

__all__ = ["ANALYSES", "Analysis", "StudyResult", "Sweep", "ThicknessResult",
           "expand_cases", "make_sweep", "min_thickness", "plot", "read_spec", "run",
           "spec_from_dict"]
