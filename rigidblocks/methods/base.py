"""The method interface: what a solution method must answer for the analyses.

A method (the convex path, the distortion iteration) is opened on one scene and answers
one question, :meth:`Method.admissible`: is there an admissible equilibrium state at
uniform friction f and load factor lambda? Its answer is a :class:`Verdict` with a
declared status:

* ``admissible`` / ``inadmissible``: decided (with the smallest violation found);
* ``undecided``: the method could not tell, with its reason (never a verdict);
* ``failure``: the method broke down (a mechanism of its own model, a solver status).

The analyses (:mod:`rigidblocks.analyses`) are written once on top of that question.
A method may also override the fast paths: :meth:`Method.friction_limit` (f* directly,
e.g. Newton steps on the relaxation R(f)) and :meth:`Method.load_limit` (lambda*
directly, e.g. one LP); returning None leaves the analyses to bisect on verdicts.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..equilibrium import EquilibriumSystem, joint_breaches
from ..results import ForceState, Mechanism, relative_width
from ..scene.model import Scene

ADMISSIBLE = "admissible"
INADMISSIBLE = "inadmissible"
UNDECIDED = "undecided"
FAILURE = "failure"


@dataclass(frozen=True, eq=False)
class Verdict:
    """A method's answer at one (f, lambda).

    ``violation``: the smallest breach of the joint laws found (force units; 0 when
    admissible, inf when the equilibrium equations have no solution). ``notes``: what
    the method wants the user to read with this answer. ``data``: the method's own
    record (a solved relaxation, an iteration run) for its state and governing joints.
    """

    status: str
    violation: float = 0.0
    notes: tuple[str, ...] = ()
    data: Any = field(default=None, repr=False)

    @property
    def admissible(self) -> bool | None:
        """True or False when decided, None when undecided or failed."""
        return {ADMISSIBLE: True, INADMISSIBLE: False}.get(self.status)


@dataclass(frozen=True, eq=False)
class Limit:
    """A limit found by a method's fast path (f* or lambda*).

    ``status``: the analysis' status (min_friction: stable, unstable, undecided,
    failure; max_load_multiplier: collapse, unbounded, unstable, undecided, failure).
    ``value``: f* or lambda* (None unless decided); ``lower``/``upper``: its bracket;
    ``at``: the verdict at the value (an admissible one, for the force state);
    ``state_hint``: the relaxation level the state may use (convex path);
    ``resolution``: the accuracy reached where it is not the bracket's width (lambda*
    from one LP: what its duals' residual leaves open above it), see :attr:`accuracy`.
    """

    status: str
    value: float | None = None
    lower: float | None = None
    upper: float | None = None
    governing: tuple[int, ...] = ()
    mechanism: Mechanism | None = None
    at: Verdict | None = None
    resolution: float | None = None

    @property
    def accuracy(self) -> float | None:
        """The relative accuracy reached: the bracket's :func:`relative_width` (or
        :attr:`resolution` where given); None where nothing was bracketed."""
        if self.resolution is not None:
            return self.resolution
        return relative_width(self.lower, self.upper)


class Timings:
    """Seconds spent per stage (wall clock and process CPU), e.g. contacts, assembly,
    build, solve, state; the analyses copy them into results."""

    def __init__(self) -> None:
        self.wall: dict[str, float] = {}
        self.cpu: dict[str, float] = {}

    def add(self, stage: str, wall: float, cpu: float) -> None:
        self.wall[stage] = self.wall.get(stage, 0.0) + wall
        self.cpu[stage] = self.cpu.get(stage, 0.0) + cpu

    @contextmanager
    def stage(self, name: str) -> Iterator[None]:
        w, c = time.perf_counter(), time.process_time()
        try:
            yield
        finally:
            self.add(name, time.perf_counter() - w, time.process_time() - c)


class Progress:
    """What a running analysis is doing, for a progress line: the current stage, the
    solves (or iteration runs) done, their interior-point (or ADMM) iterations, and the
    time since the start. Methods update it; a reader in another thread shows it."""

    def __init__(self) -> None:
        self.started = time.perf_counter()
        self.stage = "contacts"
        #: what the stages serve where it outlasts them (one run of an iteration of
        #: solves, its step and value), shown before them; "" where none
        self.context = ""
        self.solves = 0
        self.iterations = 0

    def text(self, width: int | None = None) -> str:
        """The line; within ``width`` characters the counts give way to the context (the
        step of a long run), which is shortened last, and the stage and the time, which
        change, stay in view."""
        secs = f"{time.perf_counter() - self.started:.0f} s"
        tail = f"{self.stage}, solve {self.solves + 1}, {self.iterations} iterations " \
            f"so far, {secs}"
        head = f"{self.context}: " if self.context else ""
        if width is None or len(head) + len(tail) <= width:
            return head + tail
        tail = f"{self.stage}, {secs}"
        if head and len(head) + len(tail) > width:
            room = width - len(tail) - 3
            head = f"{self.context[:room]}…: " if room >= 12 else ""
        return (head + tail)[:width]


class Method:
    """One solution method opened on one scene (see the module docstring).

    Subclasses set ``name`` and ``solver`` and implement :meth:`admissible` and
    :meth:`state`; they may implement the fast paths and the governing-joint hooks.
    ``notes`` collects what every result of this method must say; ``n_solves``,
    ``solve_time`` and ``iterations`` count the work done so far.
    """

    name = ""
    #: keys of ``settings`` the method accepts (None: any, checked by the back end)
    setting_keys: tuple[str, ...] | None = ()

    def __init__(self, scene: Scene, system: EquilibriumSystem, timings: Timings,
                 progress: Progress | None = None):
        self.scene = scene
        self.system = system
        self.timings = timings
        self.progress = progress if progress is not None else Progress()
        self.notes: list[str] = []
        self.solver = self.name

    # -- the question --------------------------------------------------------------
    def admissible(self, f: float, load_factor: float, for_state: bool = False) -> Verdict:
        """Is there an admissible state at uniform friction ``f`` and ``load_factor``?
        ``for_state``: the verdict's data will be used for the force state."""
        raise NotImplementedError

    def state(self, f: float, load_factor: float, verdict: Verdict,
              limit: bool = False) -> ForceState | None:
        """The force state that goes with an admissible verdict (``limit``: at a limit
        state, f* or lambda*)."""
        raise NotImplementedError

    # -- fast paths (None: the analyses bisect on verdicts) ----------------------------
    def friction_limit(self, load_factor: float, rtol: float) -> Limit | None:
        return None

    def load_limit(self, f: float, rtol: float, mechanism_kind: str = "vertex",
                   ) -> Limit | None:
        return None

    def at_limit(self, f: float, load_factor: float, verdict: Verdict | None,
                 state: bool) -> Verdict | None:
        """The verdict at a limit (f*, lambda*) to read the state and the governing
        joints from; ``verdict`` is the one found by the search."""
        return verdict

    def breaches(self, f: float, verdict: Verdict) -> tuple[tuple[int, float], ...]:
        """Where an inadmissible verdict's least-violation state breaches the joint
        laws: (joint, breach in force units), largest first (see :func:`ranked_breaches`)."""
        return ()

    # -- governing joints after a bisection --------------------------------------------
    def governing_friction(self, f: float, verdict: Verdict, rel: float = 0.0
                           ) -> tuple[int, ...]:
        """Joints that govern f* (at their friction limit in the state at f*, to the
        relative accuracy ``rel`` of f*: a bisection's state is at the end of its
        bracket, not at the limit itself)."""
        return ()

    def governing_load(self, f: float, verdict: Verdict, rel: float = 0.0,
                       width: float = 0.0) -> tuple[int, ...]:
        """Joints at their friction limit in the state at lambda* (to the relative
        accuracy ``rel`` of lambda*, and within the shear that ``width``, the bracket's
        width in lambda, times the live load could add)."""
        return ()

    # -- bookkeeping -------------------------------------------------------------------
    @property
    def contacts(self) -> Any:
        return self.system.contacts

    @property
    def uniform(self) -> np.ndarray:
        """Joints that take the uniform friction (no override of their own)."""
        return np.isnan(self.contacts.override_friction)

    def f_joint(self, f_uniform: float) -> np.ndarray:
        o = self.contacts.override_friction
        return np.where(np.isnan(o), f_uniform, o)

    @property
    def n_solves(self) -> int:
        raise NotImplementedError

    @property
    def answered_by(self) -> tuple[str, ...]:
        """The back ends that answered this method's solves (none named by default)."""
        return ()

    @property
    def rejected(self) -> tuple[str, ...]:
        """Answers of the method's back end that failed their check and were solved
        again by another (what each problem was and why)."""
        return ()

    @property
    def solve_time(self) -> float:
        raise NotImplementedError

    @property
    def iterations(self) -> int:
        raise NotImplementedError

    def explain(self, verdict: Verdict) -> None:
        """Add a verdict's notes to the notes every result of this method carries."""
        self.notes.extend(n for n in verdict.notes if n not in self.notes)


#: the breaches a verdict lists: down to this fraction of the largest
BREACH_SHARE = 1e-3


def ranked_breaches(system: EquilibriumSystem, x: np.ndarray, f_joint: np.ndarray,
                    rel: float = BREACH_SHARE) -> tuple[tuple[int, float], ...]:
    """(joint, breach) of the state ``x`` (force units), largest first, down to ``rel``
    of the largest breach."""
    if not np.all(np.isfinite(x)):
        return ()
    b = joint_breaches(system, x, f_joint)
    top = float(b.max(initial=0.0))
    if not top > 0:
        return ()
    k = np.flatnonzero(b >= rel * top)
    k = k[np.argsort(-b[k], kind="stable")]
    return tuple((int(j), float(b[j])) for j in k)


__all__ = ["ADMISSIBLE", "FAILURE", "INADMISSIBLE", "Limit", "Method", "Progress", "Timings",
           "BREACH_SHARE", "UNDECIDED", "Verdict", "ranked_breaches"]
