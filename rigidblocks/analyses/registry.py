"""The analyses by name: one registry for the CLI, the pictures and the studies."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..errors import InputError
from ..results import Result
from ..scene.model import Scene
from .core import check, max_load_multiplier, min_friction


@dataclass(frozen=True)
class AnalysisInfo:
    """An analysis: its API name, its CLI command, what it asks and what it answers.

    ``takes`` are the keyword arguments of the question (``friction``,
    ``load_factor``); ``answers`` the result attributes that hold the answer.
    """

    name: str
    command: str
    function: Callable[..., Result]
    help: str
    takes: tuple[str, ...]
    answers: tuple[str, ...]

    def run(self, scene: Scene, *, friction: Any = None, load_factor: float | None = None,
            **options: Any) -> Result:
        """Run on ``scene``; ``friction`` and ``load_factor`` go where the analysis
        takes them (a question that does not take one ignores it; None: the scene's)."""
        given = {"friction": friction, "load_factor": load_factor}
        return self.function(scene, **{k: given[k] for k in self.takes}, **options)


ANALYSES: dict[str, AnalysisInfo] = {a.name: a for a in (
    AnalysisInfo("check", "check", check, "is there an admissible equilibrium state?",
                 ("friction", "load_factor"), ("admissible", "violation")),
    AnalysisInfo("min_friction", "friction", min_friction,
                 "minimum friction coefficient and angle, governing joints",
                 ("load_factor",), ("friction_factor", "friction_angle_deg")),
    AnalysisInfo("max_load_multiplier", "load", max_load_multiplier,
                 "maximum load multiplier and collapse mechanism",
                 ("friction",), ("load_multiplier",)),
)}


def analysis(name: str) -> AnalysisInfo:
    """The analysis named by its API name or its CLI command."""
    for a in ANALYSES.values():
        if name in (a.name, a.command):
            return a
    names = ", ".join(f"{a.command} ({a.name})" for a in ANALYSES.values())
    raise InputError(f"unknown analysis {name!r}: use {names}")


__all__ = ["ANALYSES", "AnalysisInfo", "analysis"]
