"""The load path: the live load increased step by step, the state at every step the
distortion iteration's (the admissible state closest to the elastic one) under the joint
laws as the history has left them.

Joint behaviours for :func:`load_path` (the seed's Fig. 2 and 5):

* normal links are rigid-brittle: with a tensile strength they carry tension up to
  it; at the load step where a link reaches it, the joint cracks and from then on it
  carries no tension and no cohesion (compression only);
* shear links are rigid-plastic (Drucker, ``sliding="plastic"``): the shear is capped
  at the threshold f N + c a and stays there while the joint plasticises; or they follow
  Coulomb's sliding friction (``sliding="coulomb"``): once a joint reaches the threshold
  the block slides and the joint's shear drops to zero for the rest of the path.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..errors import InputError
from ..methods import open_method
from ..scene.model import Scene, friction_label, friction_value
from ..solvers.distortion import TOL, Run
from .search import bisect


@dataclass(frozen=True)
class PathEvent:
    """Something that happens to joints on the load path, at ``load_factor``.

    ``kind``: "crack" (a normal link reached its tensile strength and broke),
    "plastic" (a shear link reached its friction threshold), "slide" (Coulomb option:
    the shear dropped to zero), "collapse" (no admissible state beyond this load; the
    joints listed are those at their threshold in the last admissible state).
    """

    kind: str
    load_factor: float
    joints: tuple[tuple[str, str], ...]


@dataclass(frozen=True)
class PathStep:
    """The state at one load step: verdict, cracked and plastic joints, work done."""

    load_factor: float
    status: str
    cracked: tuple[tuple[str, str], ...]
    at_threshold: tuple[tuple[str, str], ...]
    iterations: int


@dataclass(frozen=True)
class PathResult:
    """A load path: status "collapse" (with ``collapse_load``), "standing" (admissible up
    to the last step), "unstable" (no admissible state under the dead load alone: no
    path), "undecided" or "failure" (reason in ``notes``)."""

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

    def first(self, kind: str) -> PathEvent | None:
        return next((e for e in self.events if e.kind == kind), None)

    def to_dict(self) -> dict[str, Any]:
        return {"status": self.status, "sliding": self.sliding,
                "friction": friction_label(self.friction), "collapse_load": self.collapse_load,
                "events": [{"kind": e.kind, "load_factor": e.load_factor,
                            "joints": [list(j) for j in e.joints]} for e in self.events],
                "steps": [{"load_factor": s.load_factor, "status": s.status,
                           "cracked": [list(j) for j in s.cracked],
                           "at_threshold": [list(j) for j in s.at_threshold],
                           "iterations": s.iterations} for s in self.steps],
                "solver": "distortion", "n_solves": self.n_solves,
                "iterations": self.iterations, "solve_time": self.solve_time,
                "notes": list(self.notes)}


def load_path(scene: Scene, steps: int = 40, max_load: float = 2.0, friction: Any = None,
              method: str = "distortion", sliding: str = "plastic", refine: int = 30,
              tol: float = TOL) -> PathResult:
    """Increase the live load in ``steps`` equal steps up to ``max_load`` x live.

    At every step the state is the distortion iteration's (the admissible state closest
    to the elastic one) under the joint laws as the history has left them: a joint whose
    normal link reached its tensile strength has cracked (brittle: no tension and no
    cohesion from then on); with ``sliding="coulomb"`` a joint that reached its friction
    threshold has slid and carries no shear from then on, while with
    ``sliding="plastic"`` (Drucker) its shear stays capped at the threshold. Every change
    of law is followed by a new iteration at the same load, so that cascades show up at
    the step they happen. The load of each event is refined by ``refine`` bisection
    steps inside its load step. The path stops at the first load with no admissible
    state ("collapse"). These states depend on the order of events (which joints
    cracked or slid before): a single convex problem, which only asks whether some
    admissible state exists, cannot express that.
    """
    if method != "distortion":
        raise InputError(f'load_path supports method="distortion" only, got {method!r}')
    if sliding not in ("plastic", "coulomb"):
        raise InputError(f'sliding must be "plastic" or "coulomb", got {sliding!r}')
    if steps < 1 or not (max_load > 0):
        raise InputError("load_path needs steps >= 1 and max_load > 0")
    if scene.dimension != 2:
        raise InputError("the load path follows the distortion method, which is 2D only; "
                         "for a 3D scene, lambda* and its mechanism are the maximum load "
                         "multiplier's (`rigidblocks load`)", scene.source)
    if not scene.has_live_load:
        raise InputError("the scene has no live load: there is nothing to increase",
                         scene.source)
    f = friction_value(scene.effective_friction if friction is None else friction)
    w = open_method(scene, "distortion")
    ds = w.solver_
    c = ds.system.contacts
    ids = c.block_ids
    F = ds.scaling.force
    names = [(ids[a], ids[b]) for a, b in c.pairs]
    fj = w.f_joint(f).astype(float)
    tension = c.tensile_strength.astype(float).copy()
    cohesion = c.cohesion.astype(float).copy()
    events: list[PathEvent] = []
    out_steps: list[PathStep] = []
    plastic_seen: set[int] = set()
    slid: set[int] = set()

    def solve_at(lam: float) -> Run:
        return w.run(ds.laws(fj, tension, cohesion), lam, tol=tol)

    def at_cap(r: Run) -> list[int]:
        cap = tension[c.point_joint] * c.point_areas / F
        n = r.x[:ds.P]
        hit = (cap > 0) & (n <= -cap * (1 - 1e-6))
        return sorted({int(j) for j in c.point_joint[hit]})

    def at_threshold(r: Run) -> list[int]:
        laws = ds.laws(fj, tension, cohesion)
        v = ds.gather(r.x)
        thr = np.abs(fj * (v[:, 0] + v[:, 1]) + laws.h[:, 2])
        thr = np.where(np.isfinite(fj), thr, np.inf)
        gap = np.where(np.isfinite(fj), laws.rows(v)[:, 2:].max(axis=1), -np.inf)
        big = float(np.abs(v).max(initial=0.0))
        hit = (gap >= -1e-5 * np.maximum(thr, 1e-9 * big)) & (thr > 1e-6 * big)
        return [int(j) for j in np.flatnonzero(hit)]

    def refine_load(a: float, b: float, pred) -> float:
        """Smallest load in (a, b] where pred(run) holds (pred false at a, true at b)."""
        def decide(lam: float) -> tuple[bool | None, Run]:
            r = solve_at(lam)
            return (None if r.status == "undecided" else bool(pred(r))), r

        return bisect(decide, a, b, 0.0, steps=refine).good

    def ok(r: Run) -> bool:
        return r.status == "admissible"

    prev = 0.0
    r = solve_at(0.0)
    status = ""
    collapse = None
    if r.status == "failure":
        w.notes.append(r.reason)
        status = "failure"
    elif not ok(r):
        w.notes.append("the dead load alone has no admissible state")
        status = "unstable"  # the word of max_load_multiplier for the same finding
    for k in range(1, steps + 1) if not status else ():
        lam = max_load * k / steps
        its0 = w.iterations
        for _cascade in range(ds.m + 2):
            r = solve_at(lam)
            if not ok(r):
                break
            cracks = [j for j in at_cap(r)]
            if cracks:
                lam_e = refine_load(prev, lam, lambda q: not ok(q) or bool(at_cap(q)))
                events.append(PathEvent("crack", lam_e, tuple(names[j] for j in cracks)))
                tension[cracks] = 0.0
                cohesion[cracks] = 0.0
                continue
            new = [j for j in at_threshold(r) if j not in plastic_seen and j not in slid]
            if new:
                events.append(PathEvent("plastic", lam, tuple(names[j] for j in new)))
                plastic_seen.update(new)
                if sliding == "coulomb":
                    events.append(PathEvent("slide", lam, tuple(names[j] for j in new)))
                    slid.update(new)
                    fj[new] = 0.0
                    cohesion[new] = 0.0
                    continue
            break
        if r.status == "failure":
            w.notes.append(r.reason)
            status = "failure"
            break
        if not ok(r):
            last = solve_at(prev)
            lam_c = prev
            if refine and ok(last):
                def decide(lam: float) -> tuple[bool | None, Run]:
                    q = solve_at(lam)
                    return (None if q.status == "undecided" else ok(q)), q

                br = bisect(decide, lam, prev, 0.0, steps=refine)
                lam_c, last = br.good, br.good_data or last
            gov = at_threshold(last) if ok(last) else []
            new = [j for j in gov if j not in plastic_seen]
            if new:
                events.append(PathEvent("plastic", lam_c, tuple(names[j] for j in new)))
            events.append(PathEvent("collapse", lam_c, tuple(names[j] for j in gov)))
            out_steps.append(PathStep(lam, r.status, (), (), w.iterations - its0))
            if r.status != "inadmissible":
                w.notes.append(f"at load {lam:.6g}: {r.reason}")
            status, collapse = "collapse", lam_c
            break
        cracked = tuple(names[j] for j in range(ds.m) if tension[j] == 0 and
                        c.tensile_strength[j] > 0)
        out_steps.append(PathStep(lam, r.status, cracked,
                                  tuple(names[j] for j in at_threshold(r)),
                                  w.iterations - its0))
        prev = lam
    if not status:
        status = "standing"
    return PathResult(status, sliding, friction_label(f), tuple(out_steps), tuple(events),
                      collapse, w.n_solves, w.iterations, w.solve_time, tuple(w.notes))
