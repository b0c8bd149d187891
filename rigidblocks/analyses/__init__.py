"""The analyses, written once on top of the method interface: admissibility, minimum
friction, maximum load multiplier (:mod:`.core`), the load path (:mod:`.load_path`),
the bracket-and-bisect search (:mod:`.search`) and their registry (:mod:`.registry`)."""

from .core import check, max_load_multiplier, min_friction
from .load_path import PathEvent, PathResult, PathStep, load_path
from .registry import ANALYSES, AnalysisInfo, analysis
from .search import Bracket, bisect

__all__ = ["ANALYSES", "AnalysisInfo", "Bracket", "PathEvent", "PathResult", "PathStep",
           "analysis", "bisect", "check", "load_path", "max_load_multiplier", "min_friction"]
