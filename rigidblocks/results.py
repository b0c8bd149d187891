"""Result objects of the analyses: immutable, with the numbers an engineer checks.

Forces are reported in the scene's force unit, positions in its length unit. Joint
resultants: N (compression positive), T (along the joint's tangent s), the eccentricity
e of the resultant's point along the joint measured from its midpoint in the direction
of s (|e| <= half the joint length when the state is admissible), and the friction
demand |T|/N.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .contacts import Contacts
from .scene.model import friction_label


@dataclass(frozen=True, eq=False)
class ForceState:
    """An equilibrium state of the joint forces.

    Attributes:
        normal: (P,) normal force at each contact point.
        shear: (P,) or (P, 2) shear at each contact point (2D, one shear per joint: the
            joint's shear shared in proportion to the points' normal forces).
        joint_normal, joint_shear: (m,) resultants per joint (3D: shear magnitude).
        eccentricity: (m,) 2D: position of the resultant along the joint from its
            midpoint, along s; NaN where N is zero.
        demand: (m,) |T| / N (inf where N = 0 and T != 0, 0 where both vanish).
        thrust_points: (m, d) where the resultant crosses each joint.
        thrust_order: joint indices along the structure (a chain of blocks), or all
            joints in detection order when the structure is not a chain.
        method: how the state was chosen, e.g. "least complementary energy".
    """

    normal: np.ndarray
    shear: np.ndarray
    joint_normal: np.ndarray
    joint_shear: np.ndarray
    eccentricity: np.ndarray
    demand: np.ndarray
    thrust_points: np.ndarray
    thrust_order: np.ndarray
    method: str

    @property
    def thrust_line(self) -> np.ndarray:
        """The thrust line's points in order along the structure."""
        return self.thrust_points[self.thrust_order]


@dataclass(frozen=True, eq=False)
class Mechanism:
    """A collapse mechanism: virtual velocities of the free blocks and joint modes.

    ``velocities`` has one row (u, v, omega) per block in 2D (zero rows for supports),
    normalised so that max_b (|(u, v)| + |omega| size_b) = 1 and the live load does
    positive work. ``modes`` gives each joint's behaviour: "closed", "hinge", "open",
    "slide" or "slide+hinge". ``opening`` (P,) and ``slip`` are the relative
    displacements at the contact points / joints.
    """

    velocities: np.ndarray
    opening: np.ndarray
    slip: np.ndarray
    modes: tuple[str, ...]

    def joints_with(self, mode: str) -> np.ndarray:
        return np.array([k for k, m in enumerate(self.modes) if m == mode], dtype=int)


@dataclass(frozen=True, eq=False)
class Result:
    """Common part of every analysis result.

    ``status`` is the verdict (see each analysis); ``solver``, ``n_solves``,
    ``solve_time`` (seconds, all solves) and ``iterations`` describe the work done.
    """

    analysis: str
    status: str
    friction: Any
    load_factor: float | None
    contacts: Contacts = field(repr=False)
    solver: str
    n_solves: int
    solve_time: float
    iterations: int
    units: tuple[str, str] = ("", "")
    state: ForceState | None = field(default=None, repr=False)
    governing: tuple[int, ...] = ()
    notes: tuple[str, ...] = ()
    #: seconds per stage (contacts, assembly, build, solve, state), wall clock and CPU
    timings: dict[str, float] = field(default_factory=dict, repr=False)
    cpu_timings: dict[str, float] = field(default_factory=dict, repr=False)

    @property
    def governing_joints(self) -> list[tuple[str, str]]:
        ids = self.contacts.block_ids
        return [(ids[self.contacts.pairs[k, 0]], ids[self.contacts.pairs[k, 1]])
                for k in self.governing]

    def _common(self) -> dict[str, Any]:
        return {"status": self.status, "solver": self.solver, "n_solves": self.n_solves,
                "solve_time": self.solve_time}

    def to_dict(self) -> dict[str, Any]:  # pragma: no cover - overridden
        raise NotImplementedError


def headline(result: Any, symbols: bool = False) -> str:
    """The answer of a result in one line: what the CLI prints as its verdict, what a
    picture's title and a drawing's note say. ``symbols``: write lambda, phi and the
    degree sign as symbols (pictures) rather than ASCII (text, DXF)."""
    if result is None:
        return ""
    lam, deg, inf = ("\N{GREEK SMALL LETTER LAMDA}", "\N{DEGREE SIGN}", "\N{INFINITY}") \
        if symbols else ("lambda", " deg", "infinite")
    status = getattr(result, "status", "")
    a = getattr(result, "analysis", "")
    if a == "min_friction" and result.friction_factor is not None:
        return (f"minimum friction f* = {result.friction_factor:.4g} "
                f"(friction angle {result.friction_angle_deg:.2f}{deg})")
    if a == "max_load_multiplier" and result.load_multiplier is not None:
        return (f"collapse load multiplier {lam}* = {result.load_multiplier:.4g}, "
                f"f = {_friction_text(result.friction, deg, inf)}")
    if a == "check" and status in ("admissible", "inadmissible"):
        verdict = "admissible" if status == "admissible" else "not admissible"
        return (f"{verdict} at f = {_friction_text(result.friction, deg, inf)}, "
                f"{lam} = {result.load_factor:g}")
    words = {"unstable": "unstable: no friction suffices" if a == "min_friction" else
             "unstable: the dead load alone has no admissible state",
             "unbounded": "unbounded: no multiplier of the live load makes it collapse"}
    return words.get(status, f"{a.replace('_', ' ')}: {status}")


def _friction_text(f: Any, deg: str, inf: str) -> str:
    if f is None or isinstance(f, str) or math.isinf(f):
        return inf
    return f"{float(f):.4g} ({math.degrees(math.atan(float(f))):.2f}{deg})"


@dataclass(frozen=True, eq=False)
class CheckResult(Result):
    """Admissibility at given friction and load factor.

    status: "admissible" or "inadmissible". ``violation`` is the smallest achievable
    violation of the joint laws (force units; 0 when admissible).
    """

    admissible: bool = False
    violation: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        return {**self._common(), "admissible": self.admissible,
                "friction": friction_label(self.friction), "load_factor": self.load_factor,
                "violation": self.violation}


@dataclass(frozen=True, eq=False)
class FrictionResult(Result):
    """Minimum uniform friction.

    status: "stable" (f* found) or "unstable" (no friction suffices: even infinite
    friction admits no equilibrium). ``friction_factor`` is f*, ``friction_angle_deg``
    atan(f*) in degrees, both None when unstable. ``lower``/``upper`` bracket f*.
    """

    friction_factor: float | None = None
    friction_angle_deg: float | None = None
    lower: float | None = None
    upper: float | None = None

    def to_dict(self) -> dict[str, Any]:
        return {**self._common(), "friction_factor": self.friction_factor,
                "friction_angle_deg": self.friction_angle_deg,
                "governing_joints": [list(p) for p in self.governing_joints],
                "load_factor": self.load_factor}


@dataclass(frozen=True, eq=False)
class LoadResult(Result):
    """Maximum load multiplier (associative friction).

    status: "collapse" (finite lambda*), "unbounded" (no multiplier makes it collapse)
    or "unstable" (the dead load alone has no admissible state).
    """

    load_multiplier: float | None = None
    mechanism: Mechanism | None = field(default=None, repr=False)

    def to_dict(self) -> dict[str, Any]:
        out = {**self._common(), "load_multiplier": self.load_multiplier,
               "friction": friction_label(self.friction)}
        if self.mechanism is not None:
            m = self.mechanism
            ids = self.contacts.block_ids
            out["mechanism"] = {
                "hinges": [self._pair(k, ids) for k in m.joints_with("hinge")],
                "sliding": [self._pair(k, ids) for k in range(len(m.modes))
                            if m.modes[k].startswith("slide")],
                "open": [self._pair(k, ids) for k in m.joints_with("open")],
            }
        return out

    def _pair(self, k: int, ids: tuple[str, ...]) -> list[str]:
        a, b = self.contacts.pairs[k]
        return [ids[a], ids[b]]
