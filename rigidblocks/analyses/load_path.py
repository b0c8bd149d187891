"""The load path: the live load increased step by step, the state at every load the
distortion iteration's (the admissible state closest to the elastic one) under the joint
laws as the history has left them.

Joint behaviours for :func:`load_path` (the seed's Fig. 2 and 5):

* normal links are rigid-brittle: with a tensile strength they carry tension up to
  it; at the load where a link reaches it, the joint cracks and from then on it
  carries no tension and no cohesion (compression only). The shear row
  |T| <= f (N1 + N2) + c a keeps the joint's net normal force N1 + N2 >= -c a / f: a
  tensile strength without cohesion lets one link pull while the other pushes (a
  bending capacity), not a net tension; with cohesion the joint carries a net tension
  up to c a / f (and up to the links' tensile strengths);
* shear links are Heyman's (f infinite: never at a threshold), rigid-plastic
  (Drucker, ``sliding="plastic"``: the shear is capped at the threshold f N + c a and
  stays there while the joint plasticises), or follow Coulomb's sliding friction
  (``sliding="coulomb"``: once a joint reaches the threshold the block slides and the
  joint's shear drops to zero for the rest of the path);
* ``flow``: "non-associative" caps the shear links without changing the normal links
  (the seed's Eq. 4, its procedure), "associative" projects onto the Coulomb set
  (normality, a cross-check of the convex path); None: the scene's.

Events are located at the load that causes them: the loads between two steps are
bisected, and a crack or a threshold is placed where its margin, affine in lambda
while no other link changes state, reaches zero. Joints with no normal force under the
dead load that are at their threshold under the first load are plastic from the start:
one event at lambda = 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import InputError
from ..methods import Progress, open_method
from ..methods.distortion import AT_THRESHOLD, LOADED
from ..methods.engine import MAX_TRIALS
from ..results import sliding_count
from ..scene.model import Scene, friction_label, friction_value
from ..scene.validate import check_live_load, check_load_factor, validate_scene
from ..solvers.distortion import TOL, Run
from .nonassociative import _UNSETTLED, flow_mask
from .search import BRACKET_ATOL, bisect

#: how far (relative) below a path's collapse load the convex path's non-associative
#: multiplier from X0 is said to lie (:func:`_lower_from_x0`): both are located to 1e-5
#: or better
LOWER_RTOL = 1e-4
#: relative step below an event's bracket over which its margin is extrapolated
EXTRAPOLATE = 1e-4
#: an event is first bracketed to this (relative) by bisection, then its load is
#: extrapolated from the states below it (over EXTRAPOLATE, as from a finer bracket)
#: and kept where it falls within the bracket (to its width); else the bisection goes on
#: to ``refine`` steps
COARSE = 1e-4
#: the bisection then goes on until the event's bracket is within FINE of its load (or
#: FLOOR of the live load near 0), or for ``refine`` halvings of the step in all: a
#: step of 2.5e10 (``max_load`` 1e12) had left 30 halvings 23 wide and the reference
#: model collapsing at 0 instead of 2.4
FINE, FLOOR = 1e-9, 1e-12
#: the most load steps a path takes (``--steps 1e9`` ran on for hours)
MAX_STEPS = 10_000
#: an undecided run within this (relative) of an admissible load puts the collapse at
#: that load, with a note; farther above it, the path is undecided
LIMIT_RTOL = 1e-6
#: a joint that carries no normal force under the dead load and is at its friction
#: threshold at this fraction of the first step's load is plastic from the first load
#: on (no normal force, no shear): its event is put at lambda = 0 (the head joints of a
#: running-bond wall, each of which was otherwise reported where its normal force
#: passed LOADED of the largest force: lambda = 4e-6 to 2e-5 on the 4 x 4 wall, 2.6e-4
#: on the 2 x 3 one)
FIRST_LOAD = 1e-2
#: the reason of an admissible iterate that is not the settled state (associative flow)
UNSETTLED = ("an admissible iterate (the structure stands), not the settled state, whose "
             "events are not read: ")

Joint = tuple[str, str]


@dataclass(frozen=True)
class PathEvent:
    """Something that happens to joints on the load path, at ``load_factor``.

    ``kind``: "crack" (a normal link reached its tensile strength and broke),
    "plastic" (a shear link reached its friction threshold), "slide" (Coulomb option:
    the shear dropped to zero), "collapse" (no admissible state beyond this load; the
    joints listed are those of the event that caused it, those at their threshold in
    the last admissible state, and its hinges there: loaded joints with one point's
    normal force at zero, the thrust at the joint's edge).
    """

    kind: str
    load_factor: float
    joints: tuple[Joint, ...]
    #: a collapse's joints, each what it does in the last admissible state: "cracked"
    #: (the event that caused it), "at friction limit", "thrust at an edge" (a hinge of
    #: the state, not necessarily of the mechanism), or two of them
    #: (empty for the other events: their kind says it)
    modes: tuple[str, ...] = ()


@dataclass(frozen=True)
class PathStep:
    """The state at one load step: verdict, cracked and plastic joints, work done."""

    load_factor: float
    status: str
    cracked: tuple[Joint, ...]
    at_threshold: tuple[Joint, ...]
    iterations: int


@dataclass(frozen=True)
class PathResult:
    """A load path: status "collapse" (with ``collapse_load``), "unstable" (no admissible
    state under the dead load alone: no path), "standing" (admissible up
    to the last step), "undecided" (with ``bracket``: admissible at its lower end, not
    decided at its upper end) or "failure" (reason in ``notes``). A collapse put at the
    last admissible load below an undecided run has the ``bracket`` it lies in."""

    status: str
    sliding: str
    friction: Any
    steps: tuple[PathStep, ...]
    events: tuple[PathEvent, ...]
    collapse_load: float | None
    n_solves: int
    iterations: int
    solve_time: float
    notes: tuple[str, ...] = ()
    flow: str = "associative"
    bracket: tuple[float, float] | None = None
    #: the joints (their laws: friction overrides), and how many slide without dilatancy
    #: where some do but not all (None: all, or none)
    contacts: Any = field(default=None, repr=False, compare=False)
    sliding_joints: int | None = None

    def joint_name(self, k: int) -> tuple[str, str]:
        ids = self.contacts.block_ids
        return ids[self.contacts.pairs[k, 0]], ids[self.contacts.pairs[k, 1]]

    def first(self, kind: str) -> PathEvent | None:
        return next((e for e in self.events if e.kind == kind), None)

    def to_dict(self) -> dict[str, Any]:
        return {"status": self.status, "sliding": self.sliding, "flow": self.flow,
                "friction": friction_label(self.friction), "collapse_load": self.collapse_load,
                "bracket": list(self.bracket) if self.bracket else None,
                "events": [{"kind": e.kind, "load_factor": e.load_factor,
                            "joints": [list(j) for j in e.joints],
                            **({"modes": list(e.modes)} if e.modes else {})}
                           for e in self.events],
                "steps": [{"load_factor": s.load_factor, "status": s.status,
                           "cracked": [list(j) for j in s.cracked],
                           "at_threshold": [list(j) for j in s.at_threshold],
                           "iterations": s.iterations} for s in self.steps],
                "sliding_joints": sliding_count(self),
                "solver": "distortion", "n_solves": self.n_solves,
                "iterations": self.iterations, "solve_time": self.solve_time,
                "notes": list(self.notes)}


class _End(Exception):
    """The path ends: ``status`` "collapse", "unstable", "undecided" or "failure" at
    ``load``."""

    def __init__(self, status: str, load: float, bracket: tuple[float, float] | None = None):
        super().__init__(status)
        self.status, self.load, self.bracket = status, load, bracket


class _Path:
    """The joint laws as the history has left them, and the runs under them."""

    def __init__(self, scene: Scene, f: float, flow: str | None, sliding: str,
                 refine: int, tol: float, progress: Progress | None = None):
        self.w = open_method(scene, "distortion", bonds_kept=False, progress=progress)
        self.ds = ds = self.w.solver_
        self.c = c = ds.system.contacts
        self.names = [(c.block_ids[a], c.block_ids[b]) for a, b in c.pairs]
        self.fj = self.w.f_joint(f).astype(float)
        self.tension = c.tensile_strength.astype(float).copy()
        self.cohesion = c.cohesion.astype(float).copy()
        self.marked = flow_mask(scene, c, flow)
        self.sliding, self.refine, self.tol = sliding, refine, tol
        self.events: list[PathEvent] = []
        self.steps: list[PathStep] = []
        self.seen: set[int] = set()
        #: joints that slid (Coulomb sliding friction: no shear left)
        self.slid: set[int] = set()

    # -- runs and what they show -------------------------------------------------------
    def laws(self) -> Any:
        return self.ds.laws(self.fj, self.tension, self.cohesion,
                            nonassociative=self.marked)

    def solve(self, lam: float) -> Run:
        """A run at ``lam``; without dilatancy, an admissible iterate that has not
        settled on its fixed point is undecided (the state is not the one reached)."""
        r = self.w.run(self.laws(), lam, tol=self.tol)
        if self.marked.any():
            if r.status == "admissible" and r.reason.startswith(_UNSETTLED):
                r.status = "undecided"
                r.reason = "the iteration did not settle on its fixed point: " + r.reason
        elif r.status == "undecided":
            # associative: any admissible iterate certifies that the structure stands
            q = self.w.run(self.laws(), lam, tol=self.tol, optimal=False)
            if q.status == "admissible":
                q.reason = UNSETTLED + r.reason
                return q
        return r

    def crack_margins(self, r: Run) -> np.ndarray:
        """Per contact point: N + cap (<= 0 at its tensile strength), +inf without one."""
        cap = self.tension[self.c.point_joint] * self.c.point_areas / self.ds.scaling.force
        return np.where(cap > 0, r.x[:self.ds.P] + cap, np.inf)

    def cracks(self, r: Run) -> list[int]:
        cap = self.tension[self.c.point_joint] * self.c.point_areas / self.ds.scaling.force
        hit = self.crack_margins(r) <= AT_THRESHOLD * cap
        return sorted({int(j) for j in self.c.point_joint[hit]})

    def thresholds(self, r: Run) -> np.ndarray:
        """Per joint: the friction threshold f (N1 + N2) + c a of the state ``r`` under
        the laws as they are (0 where f is infinite)."""
        return self.laws().thresholds(self.ds.gather(r.x))

    def threshold_margins(self, r: Run) -> np.ndarray:
        """Per joint: |T| - (f (N1 + N2) + c a) (0 at the threshold), -inf where f is
        infinite."""
        m = np.abs(self.ds.gather(r.x)[:, 2]) - self.thresholds(r)
        return np.where(np.isfinite(self.fj), m, -np.inf)

    def from_the_start(self, r0: Run, lam: float) -> None:
        """The joints plastic from the first load on (see ``FIRST_LOAD``): unloaded in
        the state ``r0`` under the dead load, at their threshold at ``lam``; one event
        at lambda = 0."""
        r = self.solve(lam)
        if r.status != "admissible" or r.reason.startswith(UNSETTLED):
            return
        big = float(np.abs(r0.x).max(initial=0.0))
        unloaded = np.abs(self.thresholds(r0)) <= LOADED * big
        joints = [j for j in self.at_threshold(r) if j not in self.seen and unloaded[j]]
        if joints:
            n = len(joints)
            self.w.notes.append(
                f"{n} joint{'s carry' if n > 1 else ' carries'} no force under the dead load "
                f"and {'reach their' if n > 1 else 'reaches its'} friction threshold at the "
                "first load (no normal force, no shear capacity): the event is put at "
                "lambda = 0" + ("; with Coulomb sliding friction a joint that slides keeps "
                               "no shear, even once it is compressed" if self.sliding ==
                               "coulomb" else ""))
        if joints and self.apply(0.0, [], joints):
            self.cascade(0.0, self.solve(0.0), r0, joints)

    def at_threshold(self, r: Run) -> list[int]:
        """Joints at their threshold, to AT_THRESHOLD of it and the run's tolerance (the
        accuracy of its forces: without dilatancy the 2 x 3 wall's head joint c1b1-c1b2
        stays 3e-10 below its threshold, 1e-4 of it at lambda = 5e-4)."""
        return list(self.w.at_threshold(r, 0.0, AT_THRESHOLD, laws=self.laws(),
                                        floor=self.tol))

    def hinging(self, r: Run) -> list[int]:
        """Loaded joints with one point's normal force at zero (within ``AT_THRESHOLD``
        of the largest force): the thrust at the joint's edge, a hinge of the mechanism
        near collapse (the semicircular arch of examples/arch.json: the four joints the
        convex method's mechanism hinges at, at 2.4e-8 and less, the next at 1.1e-2)."""
        v = self.ds.gather(r.x)
        big = float(np.abs(v).max(initial=0.0))
        top = np.maximum(v[:, 0], v[:, 1])
        low = np.minimum(v[:, 0], v[:, 1])
        return [int(j) for j in np.flatnonzero((top > LOADED * big)
                                                & (low <= AT_THRESHOLD * big))]

    def new(self, r: Run) -> tuple[list[int], list[int]]:
        """(joints that crack, joints newly at their threshold) in the state of ``r``."""
        cracks = self.cracks(r)
        if cracks:
            return cracks, []
        return [], [j for j in self.at_threshold(r) if j not in self.seen]

    def happens(self, r: Run) -> bool:
        if r.reason.startswith(UNSETTLED):
            return False  # admissible, but its state is not the one that shows events
        return r.status != "admissible" or any(self.new(r))

    # -- locating an event --------------------------------------------------------------
    def locate(self, a: float, b: float, rtol: float = 0.0, steps: int | None = None,
               atol: float = 0.0) -> tuple[float, float, Run | None]:
        """(lo, hi, run at hi): the first load in (a, b] where something happens is in
        [lo, hi], bisected to ``rtol`` (relative) + ``atol`` or ``steps`` (``refine``);
        nothing happens at lo. An undecided trial ends the path."""
        def decide(lam: float) -> tuple[bool | None, Run]:
            q = self.solve(lam)
            if q.status == "failure":
                raise self.failed(q, lam)
            return (None if q.status == "undecided" else self.happens(q)), q

        br = bisect(decide, a, b, rtol, atol, steps=steps or self.refine)
        u = br.undecided_at
        if u is not None:
            why = f"at lambda = {u:.9g}: {self.solve(u).reason}"
            # (and to the answers' absolute floor near 0: the reference model at f = 0
            # read UNDECIDED, admissible at 0 and not decided at 9.5e-8, where `load`
            # gives lambda* = 0)
            if u - br.bad > LIMIT_RTOL * u + BRACKET_ATOL:
                self.w.notes.append(why)
                raise _End("undecided", br.bad, (br.bad, u))
            g = br.good_data
            top = br.good if g is not None and g.status == "inadmissible" else u
            above = (f"; the first load found not admissible: {br.good:.9g}, so the "
                     f"collapse lies in [{br.bad:.9g}, {br.good:.9g}], at its lower end by "
                     "the stall" if top != u else "")
            self.w.notes.append(f"the collapse load is located to {LIMIT_RTOL:g} (relative, "
                                f"and {BRACKET_ATOL:g} of the live load near 0): "
                                f"admissible at {br.bad:.9g}, undecided {why}{above}")
            raise self.collapse(br.bad, [], self.solve(br.bad), (br.bad, top))
        if rtol > 0 and abs(br.good - br.bad) > rtol * max(abs(br.good), abs(br.bad)) + atol:
            # (the trial budget spent: a step of 2.5e98, --max-load 1e100, left a block
            # that slides at 0.3 "COLLAPSE at lambda = 0")
            self.w.notes.append(
                f"an event between lambda = {br.bad:.9g} and {br.good:.9g} could not be "
                f"located to {rtol:g} within {steps or self.refine} halvings of the step: "
                "a smaller max_load (--max-load) locates it")
            raise _End("undecided", br.bad, (br.bad, br.good))
        return br.bad, br.good, br.good_data

    def event(self, a: float, b: float, r: Run
              ) -> tuple[float, tuple[float, float], Run, list[int], list[int]]:
        """The first event in (a, b] (``r`` the state at b, where something happens): its
        load, the bracket it was located in and the state at its upper end, and its
        cracks and joints. Bracketed to ``COARSE`` and extrapolated (:meth:`extrapolate`), else
        bisected on to ``refine`` steps in all; a state that is not admissible at the
        bracket's upper end is a collapse at its lower end."""
        lo, hi, rh = (self.locate(a, b, COARSE, MAX_TRIALS, FLOOR) if self.refine
                      else self.locate(a, b))
        rh = rh if rh is not None else r
        if rh.status == "admissible":
            cracks, joints = self.new(rh)
            lam = self.extrapolate(lo, hi, b, cracks, joints, coarse=True)
            if lam is not None:
                return lam, (lo, hi), rh, cracks, joints
        used = math.ceil(math.log2((b - a) / (hi - lo))) if hi > lo else self.refine
        fine = math.ceil(math.log2((hi - lo) / (FINE * hi + FLOOR))) if hi > lo else 0
        lo, hi, rf = self.locate(lo, hi, steps=max(self.refine - used, fine, 1))
        rh = rf if rf is not None else rh
        if rh.status != "admissible":
            raise self.collapse(lo, [], self.solve(lo))
        cracks, joints = self.new(rh)
        lam = self.extrapolate(lo, hi, b, cracks, joints)
        return (hi if lam is None else lam), (lo, hi), rh, cracks, joints

    def extrapolate(self, lo: float, hi: float, top: float, cracks: list[int],
                    joints: list[int], coarse: bool = False) -> float | None:
        """The load where the margins of the event's links reach zero, extrapolated from
        two states below the event (affine in lambda while no link changes state). The
        bisection's ``hi`` counts a link within ``AT_THRESHOLD`` of its limit as there,
        so the event may lie above it, up to ``top`` (the step's end); from a
        ``coarse`` bracket, only within [lo, 2 hi - lo] (else the event is bisected
        further). None where it cannot be extrapolated."""
        if not self.refine or lo <= 0:
            return None
        h = max(hi - lo, EXTRAPOLATE * hi)
        a = max(lo - h, 0.0)
        ra, rb = self.solve(a), self.solve(lo)
        if ra.status != "admissible" or rb.status != "admissible" or a >= lo:
            return None

        def margins(r: Run) -> np.ndarray:
            pts = np.isin(self.c.point_joint, cracks)
            return np.concatenate([-self.crack_margins(r)[pts],
                                   self.threshold_margins(r)[joints]])

        ma, mb = margins(ra), margins(rb)
        with np.errstate(divide="ignore", invalid="ignore"):
            roots = lo - mb * (lo - a) / (mb - ma)
        ok = np.isfinite(roots) & (mb > ma)
        if not ok.any():
            return None
        lam = float(np.clip(roots[ok].min(), a, top))
        return lam if not coarse or lo <= lam <= 2 * hi - lo else None

    def failed(self, r: Run, lam: float) -> _End:
        self.w.notes.append(f"at lambda = {lam:.9g}: {r.reason}")
        return _End("failure", lam)

    # -- the path -----------------------------------------------------------------------
    def apply(self, lam: float, cracks: list[int], joints: list[int]) -> bool:
        """Record the events at ``lam`` and change the laws; True if they changed."""
        n = self.names
        if cracks:
            self.events.append(PathEvent("crack", lam, tuple(n[j] for j in cracks)))
            self.tension[cracks] = 0.0
            self.cohesion[cracks] = 0.0
            return True
        self.events.append(PathEvent("plastic", lam, tuple(n[j] for j in joints)))
        self.seen.update(joints)
        if self.sliding != "coulomb":
            return False
        self.events.append(PathEvent("slide", lam, tuple(n[j] for j in joints)))
        self.slid.update(joints)
        self.fj[joints] = 0.0
        self.cohesion[joints] = 0.0
        return True

    def collapse(self, lam: float, cause: list[int], last: Run | None,
                 bracket: tuple[float, float] | None = None) -> _End:
        at = self.at_threshold(last) if last else []
        gov = list(cause) + [j for j in at if j not in cause]
        # plastic: the joints at their threshold not yet so (a crack that causes the
        # collapse is no plasticity: a block bonded to its base, at infinite friction,
        # read "crack", then "plastic" at |T|/N = 0.75)
        new = [j for j in at if j not in self.seen]
        if new:
            self.events.append(PathEvent("plastic", lam, tuple(self.names[j] for j in new)))
        hinges = self.hinging(last) if last else []
        gov += [j for j in hinges if j not in gov]
        # (a block that slid and one that tipped read alike: "collapse base-B")
        cracked = [j for j in cause if j not in self.seen and j not in at]
        # (the state's, not the mechanism's: "hinging" named head joints of a wall that
        # moves as one body; a joint that slid, its shear 0 at a threshold of 0, read
        # "at friction limit")
        modes = tuple(", ".join(w for w, on in (("cracked", j in cracked),
                                                ("slid: no shear left", j in self.slid),
                                                ("at friction limit",
                                                 j in at and j not in self.slid),
                                                ("thrust at an edge", j in hinges)) if on)
                      for j in gov)
        self.events.append(PathEvent("collapse", lam, tuple(self.names[j] for j in gov),
                                     modes))
        return _End("collapse", lam, bracket)

    def cascade(self, lam: float, r: Run, last: Run | None,
                cause: list[int] | None = None,
                located: tuple[float, float] | None = None) -> Run:
        """Apply the events of the state ``r`` at ``lam`` and solve again, until the
        state shows no new event; a lost admissibility is a collapse at ``lam``
        (``cause``: the joints of the event that changed the laws before ``r``;
        ``located``: the bracket that event was located in, the collapse's)."""
        cause = list(cause or [])
        for _ in range(self.ds.m + 2):
            if r.status == "failure":
                raise self.failed(r, lam)
            if r.status == "undecided":
                self.w.notes.append(f"at lambda = {lam:.9g}, after the events there: "
                                    f"{r.reason}")
                raise _End("undecided", lam, (lam, lam))
            if r.status != "admissible":
                # (a collapse that follows an event, a Coulomb slide, is where that event
                # was located: it was given with no bracket and no word of its accuracy)
                if located is not None:
                    lo, hi = min(located[0], lam), max(located[1], lam)
                    self.w.notes.append(
                        f"the collapse follows the event at lambda = {lam:.9g}, which lies "
                        f"in [{lo:.9g}, {hi:.9g}] (the bracket its bisection left; its load "
                        "within it where the margins of its links, extrapolated, reach 0)")
                    raise self.collapse(lam, cause, last, (lo, hi))
                raise self.collapse(lam, cause, last)
            cracks, joints = self.new(r)
            if not (cracks or joints) or not self.apply(lam, cracks, joints):
                return r
            cause = cracks or joints
            last, r = r, self.solve(lam)
        return r

    def advance(self, a: float, b: float) -> Run:
        """From the settled state at ``a`` to ``b``: every event in between located,
        applied at its load and followed to its cascade; the state at ``b``."""
        while True:
            r = self.solve(b)
            if r.status == "failure":
                raise self.failed(r, b)
            if not self.happens(r):
                if r.reason.startswith(UNSETTLED):
                    self.w.notes.append(f"at lambda = {b:.9g}: {r.reason}")
                return r
            lam, located, rh, cracks, joints = self.event(a, b, r)
            if self.apply(lam, cracks, joints):
                self.cascade(lam, self.solve(lam), rh, cracks or joints, located)
                a = lam
            else:
                a = max(located[1], lam)

    def step(self, lam: float, r: Run, its: int) -> None:
        cracked = tuple(self.names[j] for j in range(self.ds.m)
                        if self.tension[j] == 0 and self.c.tensile_strength[j] > 0)
        self.steps.append(PathStep(lam, r.status, cracked,
                                   tuple(self.names[j] for j in self.at_threshold(r)), its))


def load_path(scene: Scene, steps: int = 40, max_load: float = 2.0, friction: Any = None,
              method: str = "distortion", sliding: str = "plastic", refine: int = 30,
              tol: float = TOL, flow: str | None = None,
              progress: Progress | None = None) -> PathResult:
    """Increase the live load in ``steps`` equal steps up to ``max_load`` x live.

    At every load the state is the distortion iteration's (the admissible state closest
    to the elastic one) under the joint laws as the history has left them (see the
    module docstring): cracked joints carry no tension and no cohesion; with
    ``sliding="coulomb"`` a joint that reached its friction threshold carries no shear.
    Every event is located at the load that causes it (``refine`` bisection steps,
    then the margins extrapolated to zero) and followed by a new iteration at that
    load, so that cascades show up where they happen. The path stops at the first load
    with no admissible state ("collapse") or where a run cannot decide ("undecided",
    with the bracket). These states depend on the order of events (which joints
    cracked or slid before): a single convex problem, which only asks whether some
    admissible state exists, cannot express that. ``progress``: kept up to date with
    the step and its runs (:class:`~rigidblocks.methods.Progress`), for a progress
    line.
    """
    validate_scene(scene)  # a scene built in code, checked as a file's is
    f = _check_args(scene, steps, max_load, friction, method, sliding)
    p = _Path(scene, f, flow, sliding, refine, tol, progress)
    status, collapse, bracket = "standing", None, None
    where = p.w.progress
    try:
        where.context = "load path: under the dead load"
        try:
            r0 = p.cascade(0.0, _at_zero(p), None)
        finally:  # (also where they collapse it at once: Coulomb sliding friction)
            dead = sum(len(e.joints) for e in p.events if e.kind == "plastic")
            if dead:
                # (the flat arch with vertical joints: its two pier joints at |T|/N = 0.6
                # of f = 0.6 under its self-weight, an event at lambda = 0 with no word)
                p.w.notes.append(
                    f"{dead} joint{'s are' if dead > 1 else ' is'} at the friction "
                    "threshold under the dead load alone (in the state reached from the "
                    "elastic state X0): plastic from lambda = 0" + (
                        "; with Coulomb sliding friction they slide and keep no shear"
                        if sliding == "coulomb" else ""))
        p.from_the_start(r0, FIRST_LOAD * max_load / steps)
        prev = 0.0
        for k in range(1, steps + 1):
            lam, its = max_load * k / steps, p.w.iterations
            where.context = (f"load path: step {k} of {steps} (lambda to {lam:.6g}), "
                             f"{len(p.events)} events")
            p.step(lam, p.advance(prev, lam), p.w.iterations - its)
            prev = lam
    except _End as end:
        status, bracket = end.status, end.bracket
        collapse = end.load if end.status == "collapse" else None
    finally:
        where.context = ""
    flow_name = "non-associative" if p.marked.any() else "associative"
    if p.marked.any() and math.isfinite(f) and status in ("collapse", "standing"):
        p.w.notes += _lower_from_x0(scene, f, flow, collapse if status == "collapse"
                                    else max_load, status == "collapse")
    some = int(p.marked.sum()) if 0 < p.marked.sum() < len(p.marked) else None
    return PathResult(status, sliding, friction_label(f), tuple(p.steps), tuple(p.events),
                      collapse, p.w.n_solves, p.w.iterations, p.w.solve_time,
                      tuple(p.w.notes), flow_name, bracket, p.c, some)


def _lower_from_x0(scene: Scene, f: float, flow: str | None, lam: float,
                   collapsed: bool) -> list[str]:
    """Without dilatancy, a note where the convex path's limit iteration from X0 (`load
    --flow non-associative`) collapses below the path's collapse load, or below the end
    of a path that stands (``lam``): the 3 x 3 running-bond wall at f = 0.8 collapsed on
    the path at 0.749241, 4.9 % above `load`'s 0.714285 (and LMGC90's [0.7136, 0.7143]),
    and the Arpino gate at 0.122798 for 0.118702, with no word of it."""
    from ..errors import SolverFailure
    from ..results import fmt_safe
    from .nonassociative import max_load_nonassociative

    try:
        other = max_load_nonassociative(scene, f, "clarabel", flow=flow, state=False)
    except SolverFailure:
        return []
    low = other.load_multiplier
    if other.status != "collapse" or low is None or not low < lam * (1 - LOWER_RTOL):
        return []
    where = "this path's collapse load" if collapsed else \
        f"the end of this path, lambda = {lam:g}, where it stands"
    # (no word of the terminal's solver notes: "iteration" hid it behind --verbose)
    at = "" if friction_value(scene.effective_friction) == f else f" --friction {f:g}"
    return [f"`rigidblocks load --flow non-associative{at}` (the convex path, from X0) "
            f"collapses at lambda = {fmt_safe(float(low), 6, False)}, below "
            f"{where}: non-associative collapse states are not unique, and the lower is "
            "the safer"]


def _at_zero(p: _Path) -> Run:
    r = p.solve(0.0)
    if r.status == "inadmissible":  # no path: the word of max_load_multiplier
        # without dilatancy the iteration's state is one of many: others may stand (the
        # flat arch with vertical joints at f = 0.6, which `check` admits at lambda = 0,
        # read "the dead load alone has no admissible state")
        p.w.notes.append("the state reached from the elastic state X0 under the dead load "
                         "alone breaches the joint laws (without dilatancy: whether "
                         "another state stands, `rigidblocks check --load-factor 0` without "
                         "--flow says)" if p.marked.any()
                         else "the dead load alone has no admissible state (`rigidblocks "
                         "check --load-factor 0` names the joints it breaches)")
        raise _End("unstable", 0.0)
    return r


def _check_args(scene: Scene, steps: int, max_load: float, friction: Any, method: str,
                sliding: str) -> float:
    if method != "distortion":
        raise InputError(f'load_path supports method="distortion" only, got {method!r}')
    if sliding not in ("plastic", "coulomb"):
        raise InputError(f'sliding must be "plastic" or "coulomb", got {sliding!r}')
    if not (max_load > 0):
        raise InputError(f"load_path needs max_load > 0, got {max_load!r}", "max_load")
    if not 1 <= steps <= MAX_STEPS:
        raise InputError(f"the path takes 1 to {MAX_STEPS} steps, got {steps}: each step "
                         "is a solve at least, and finer steps locate no event better "
                         f"(each is located to {FINE:g} of its load whatever the step)",
                         "steps")
    if scene.dimension != 2:
        raise InputError("the load path follows the distortion method, which is 2D only; "
                         "for a 3D scene, lambda* and its mechanism are the maximum load "
                         "multiplier's (`rigidblocks load`)", scene.source)
    check_live_load(scene, "increase")
    check_load_factor(scene, max_load, "max_load")
    return friction_value(scene.effective_friction if friction is None else friction)
