"""The distortion path: verdicts from the seed's iterative impressed-distortion solver
(:mod:`rigidblocks.solvers.distortion`), 2D scenes with two contact points per joint.

It has no fast path: f* and lambda* come from the analyses' bisection on its verdicts,
and it declares ``undecided`` where its iteration cannot tell (near a limit) and
``failure`` where the linked structure is a mechanism.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..equilibrium import EquilibriumSystem, force_state
from ..errors import InputError
from ..problems.formulation import Scaling, flexibility
from ..results import ForceState
from ..scene.model import Scene
from ..solvers.distortion import MAX_ITER, TOL, DistortionSolver, Run
from .base import ADMISSIBLE, Method, Progress, Timings, Verdict, ranked_breaches

#: a joint is at its friction threshold where its shear is within this fraction of it
AT_THRESHOLD = 1e-5
#: joints whose threshold and normal force are both below this fraction of the largest
#: force (unloaded ones) are at no threshold; a frictionless joint that carries a normal
#: force is at its threshold of 0
LOADED = 1e-6
#: the refusal of a 3D scene, in words for the API and the command line alike
NOT_3D = ("the distortion method is not supported for 3D scenes; use the convex path "
          '(method "clarabel", the default)')


def distortion_solver(scene: Scene, system: EquilibriumSystem) -> DistortionSolver:
    """The distortion solver of a scene's system, after the checks of its model."""
    if scene.dimension != 2:
        raise InputError(NOT_3D, scene.source)
    if np.any(np.diff(system.contacts.joint_start) != 2):
        raise InputError("the distortion method needs two contact points per joint",
                         scene.source)
    return DistortionSolver(system, Scaling.of(system), flexibility(system),
                            tuple(b.id for b in scene.blocks))


class DistortionMethod(Method):
    """Verdicts of the distortion iteration (see the module docstring).

    Settings: ``tol`` (violation counted as zero, reference-force units, default 1e-9),
    ``max_iter`` (iteration budget of one run) and ``anderson`` (memory of the
    acceleration; 0 for the plain iteration).
    """

    name = "distortion"
    setting_keys = ("tol", "max_iter", "anderson")

    def __init__(self, scene: Scene, system: EquilibriumSystem, timings: Timings, *,
                 settings: dict | None = None, progress: Progress | None = None):
        super().__init__(scene, system, timings, progress)
        s = dict(settings or {})
        self.tol = float(s.get("tol", TOL))
        self.max_iter = int(s.get("max_iter", MAX_ITER))
        self.anderson = s.get("anderson")
        with timings.stage("build"):
            self.solver_ = distortion_solver(scene, system)
        self.runs = 0
        self._iterations = 0
        self._time = 0.0

    @property
    def n_solves(self) -> int:
        return self.runs

    @property
    def solve_time(self) -> float:
        return self._time

    @property
    def answered_by(self) -> tuple[str, ...]:
        """The distortion iteration itself, once it has run."""
        return (self.name,) if self.runs else ()

    @property
    def iterations(self) -> int:
        return self._iterations

    def run(self, laws: Any, load_factor: float, **kw: Any) -> Run:
        """One iteration run (counted) at the given joint laws and load factor."""
        kw.setdefault("tol", self.tol)
        kw.setdefault("max_iter", self.max_iter)
        if self.anderson is not None:
            kw.setdefault("anderson", self.anderson)
        self.progress.stage = f"iteration run at lambda = {load_factor:.6g}"
        with self.timings.stage("solve"):
            r = self.solver_.run(laws, load_factor, **kw)
        self.runs += 1
        self._iterations += r.iterations
        self._time += r.time
        self.progress.solves = self.runs
        self.progress.iterations = self._iterations
        return r

    def describe(self, r: Run) -> tuple[str, ...]:
        F = self.solver_.scaling.force
        out = [f"{r.iterations} iterations, equilibrium residual {r.residual * F:.3g}, "
               f"joint-law violation {r.violation * F:.3g}"]
        if r.reason:
            out.append(r.reason)
        return tuple(out)

    def admissible(self, f: float, load_factor: float, for_state: bool = False) -> Verdict:
        r = self.run(self.solver_.laws(self.f_joint(f)), load_factor, optimal=for_state)
        viol = 0.0 if r.status == ADMISSIBLE else r.violation * self.solver_.scaling.force
        return Verdict(r.status, viol, self.describe(r), r)

    def state(self, f: float, load_factor: float, verdict: Verdict,
              limit: bool = False) -> ForceState | None:
        if verdict.status != ADMISSIBLE:
            return None
        with self.timings.stage("state"):
            return force_state(self.system, verdict.data.x * self.solver_.scaling.force,
                               "impressed distortions")

    def breaches(self, f: float, verdict: Verdict) -> tuple[tuple[int, float], ...]:
        if verdict.data is None:
            return ()
        x = verdict.data.x * self.solver_.scaling.force
        return ranked_breaches(self.system, x, self.f_joint(f))

    def at_limit(self, f: float, load_factor: float, verdict: Verdict | None,
                 state: bool) -> Verdict | None:
        """With a state wanted, a run at the limit to the settled (least-energy) state;
        the bisection's runs stop at the first admissible iterate."""
        if state and verdict is not None:
            return self.admissible(f, load_factor, for_state=True)
        return verdict

    def at_threshold(self, r: Run, f: float, rel: float = AT_THRESHOLD,
                     laws: Any = None, floor: float = 0.0) -> tuple[int, ...]:
        """Loaded joints whose shear is at the friction threshold (within ``rel`` of it,
        plus ``floor`` in the solver's scaled forces), under uniform friction ``f`` or,
        given, the joint ``laws`` of the run (``f`` unused); joints with infinite
        friction (Heyman) have no threshold."""
        ds = self.solver_
        laws = ds.laws(self.f_joint(f)) if laws is None else laws
        v = ds.gather(r.x)
        fin = laws.fin
        thr = np.where(fin, np.abs(laws.thresholds(v)), 0.0)
        gap = laws.rows(v)[:, 2:].max(axis=1)
        big = float(np.abs(v).max(initial=0.0))
        # (loaded by its threshold or by its normal force: the reference model at f = 0
        # collapsed at lambda = 0 on a path whose collapse named no joint)
        loaded = (thr > LOADED * big) | (v[:, 0] + v[:, 1] > LOADED * big)
        hit = fin & loaded & (gap >= -rel * thr - floor)
        return tuple(int(j) for j in np.flatnonzero(hit))

    def governing_friction(self, f: float, verdict: Verdict, rel: float = 0.0
                           ) -> tuple[int, ...]:
        if f <= 0 or verdict.data is None:
            return ()
        return tuple(j for j in self.at_threshold(verdict.data, f, max(AT_THRESHOLD, rel))
                     if self.uniform[j])

    def governing_load(self, f: float, verdict: Verdict, rel: float = 0.0,
                       width: float = 0.0) -> tuple[int, ...]:
        # the state at the bracket's lower end: the reference model's joints at
        # lambda = 1.19921875 of 1.2 are 6.5e-4 below their thresholds. A joint's
        # shear may also rise by up to the live load's own size times the bracket's
        # width before lambda*: the wall example's fourth foundation joint, where its
        # state puts the slack (0.01 kN, 2.7e-3 of its threshold in a bracket 1.6e-3
        # wide), was left out
        if not np.isfinite(f) or verdict.data is None:
            return ()
        live = self.system.live.reshape(-1, self.system.dofs)[:, :2]
        floor = width * float(np.hypot(live[:, 0], live[:, 1]).sum()) / \
            self.solver_.scaling.force
        return self.at_threshold(verdict.data, f, max(AT_THRESHOLD, rel), floor=floor)


__all__ = ["AT_THRESHOLD", "LOADED", "DistortionMethod", "distortion_solver"]
