"""The convex path: verdicts from the relaxation R(f, lambda) (:mod:`.relaxation`), f* by
Newton steps on R (:mod:`.friction_search`) or, under a live load, on lambda*(f)
(:mod:`.load_search`), lambda* from one LP (SOCP in 3D), the force state from the
least-energy QP (:mod:`.force_state`).

The relaxations are scaled block by block (:meth:`Scaling.per_block`); the max-load
problem too where the blocks' loads span more than two orders. Every back end's answer
is checked by the solver policy. The problems come from
:mod:`rigidblocks.problems.formulation`; the back ends and their policy from
:mod:`rigidblocks.solvers`.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any

import numpy as np

from ..equilibrium import EquilibriumSystem, mechanism
from ..errors import InputError
from ..problems.formulation import Scaling
from ..results import fmt_bracket
from ..scene.model import Scene
from ..solvers import INFEASIBLE, UNBOUNDED, Runner, SolverResult
from ..solvers.policy import FALLBACK, Ladder, describe, ladder_of
from .base import ADMISSIBLE, Limit, Method, Progress, Timings, Verdict
from .force_state import STATE_SLACK, ForceStates
from .friction_search import FrictionSearch
from .load_search import LoadSearch
from .relaxation import (
    ADMISSIBLE_TOL,
    FRICTION_ATOL,
    NEAR_ADMISSIBLE_TOL,
    NO_EQUILIBRIUM,
    SPREAD_MARGIN,
    UNHELD_TOL,
    VERDICT_RTOL,
    Relaxation,
    Verdicts,
    dual_work,
    near_threshold,
)
from .vertex import face_allowance, vertex_dual

#: the default accuracy of f* and lambda* (``rtol``: a number only where its certified
#: bracket is this narrow, relative): three significant figures, the tightest accuracy
#: at which every wall of the speed-accuracy chart gets a number (docs/methods.md: the
#: 20,051-block wall at load factor 0.2 reaches 1.1e-3 at its solver's resolution)
FRICTION_RTOL = 2e-3
#: a mechanism drawn from an extreme point next to the optimal face that balances at a
#: multiplier more than this (relative, plus the restricted problem's own allowance,
#: :func:`~rigidblocks.methods.vertex.face_allowance`, and ADMISSIBLE_TOL) above lambda*
#: is said so
OFF_FACE = 1e-6


class ConvexMethod(Verdicts, ForceStates, FrictionSearch, LoadSearch, Method):
    """The convex path with one back end (:mod:`rigidblocks.solvers`)."""

    name = "clarabel"
    setting_keys = None  # the back end checks its own settings

    def __init__(self, scene: Scene, system: EquilibriumSystem, timings: Timings, *,
                 solver: str = "clarabel", settings: dict | None = None,
                 pyramid: int | None = None, progress: Progress | None = None):
        super().__init__(scene, system, timings, progress)
        self.runner = Runner(solver, settings or {}, scene.source or "",
                             progress=self.progress)
        self.solver = self.runner.solver
        self._rejected_noted = False
        self._near_noted = False
        self._coarse_noted = False
        with timings.stage("build"):
            #: the scaling of the relaxations (verdicts, f*) and their states: block by
            #: block (:meth:`Scaling.per_block`); ``lscaling`` that of the max-load
            #: problem (:meth:`Scaling.for_system`: uniform on scenes of like blocks, where
            #: the interior-point lambda* is closer to the simplex one); ``scaling``, the
            #: uniform one, that of problems other modules build on this system
            self.vscaling = Scaling.per_block(system)
            self.lscaling = Scaling.for_system(system)
            self.scaling = Scaling.of(system)
        self.pyramid = pyramid
        #: relaxation problems by load factor, with the uniform friction as parameter
        self._relax: dict[float, tuple[Any, Any]] = {}
        if pyramid is not None:
            if scene.dimension != 3:
                raise InputError("the friction pyramid is an option of 3D scenes only")
            if int(pyramid) < 3:
                raise InputError(f"a friction pyramid needs at least 3 facets, got {pyramid}")
            self.pyramid = int(pyramid)
            self.notes.append(f"friction cones linearised as inscribed {int(pyramid)}-facet "
                              "pyramids (an approximation: not the Coulomb cone)")
        # (not where every bonded joint's own friction is infinite; the analyses drop it
        # where the friction they are asked at is: core._fields)
        if cones_close_under_tension(system.contacts, self.f_joint(0.0)):
            self.notes.append(TENSION_3D_NOTE)
        loose = self.runner.loose_settings()
        if loose:
            self.notes.append(f"solver tolerances looser than 1e-9 ({', '.join(loose)}): "
                              "verdicts rest on a relaxation compared with 1e-9 of the "
                              "largest force and may be wrong near a limit")

    # -- work done -------------------------------------------------------------------
    @property
    def n_solves(self) -> int:
        return self.runner.n_solves

    @property
    def solve_time(self) -> float:
        return self.runner.solve_time

    @property
    def answered_by(self) -> tuple[str, ...]:
        return tuple(self.runner.answered_by)

    @property
    def rejected(self) -> tuple[str, ...]:
        return tuple(self.runner.rejected)

    @property
    def iterations(self) -> int:
        return self.runner.iterations

    @contextmanager
    def _solve_stage(self) -> Iterator[None]:
        """Time what the runner solves inside as the "solve" stage (its own wall time,
        and this process's CPU time)."""
        w0, c0 = self.runner.wall_time, time.process_time()
        try:
            yield
        finally:
            self.timings.add("solve", self.runner.wall_time - w0, time.process_time() - c0)

    def count_solve(self, solver: str, what: str, solve: Callable[[], tuple[Any, int]]
                    ) -> Any:
        """``solve()``, a solve by ``solver`` made outside the runner (the
        non-associative limit iteration's warm-started simplex LPs), returning its
        answer and its iterations: as the "solve" stage, shown in the progress line, and
        counted with the runner's solves (time, iterations, the back ends that
        answered); the answer is returned."""
        self.progress.stage = f"{what} problem ({solver})"
        with self._solve_stage():
            t0 = time.perf_counter()
            out, iterations = solve()
            self.runner.record(solver, time.perf_counter() - t0, iterations)
        return out

    def solve(self, problem: Any, what: str, ladder: Ladder | None = None, *,
              tight: bool = False, stall: bool = True, refine: bool = True,
              confirm: bool = False) -> SolverResult:
        """Solve ``problem`` (named ``what`` in notes) through the runner up the rungs of
        ``ladder`` (:class:`~rigidblocks.solvers.policy.Ladder`; where it is not given,
        the one of the flags ``tight``, ``stall``, ``refine`` and ``confirm``,
        :func:`~rigidblocks.solvers.policy.ladder_of`), as the "solve" stage; the notes
        say once where tolerances went out of reach or a back end's answers were solved
        again. For problems built on this method's system by other modules too (the
        non-associative analysis)."""
        ladder = ladder or ladder_of(tight, stall, refine, confirm)
        with self._solve_stage():
            n = len(self.runner.rejected)
            try:
                res = self.runner.run(problem, what, ladder)
            except InputError as err:  # a back end that does not take the problem
                if err.where is None and self.scene.source:
                    raise err.located(self.scene.source) from None
                raise
            if self.runner.out_of_reach and not self._near_noted:
                self._near_noted = True
                # the back end that went on at 1e-9 (the fallback's, where another
                # back end's answers were solved again by it), not necessarily self.solver
                gone = ", ".join(sorted(self.runner.out_of_reach))
                self.notes.append(f"the tight solver tolerances (1e-10) were out of "
                                  f"{gone}'s reach on this scene: its later solves "
                                  "ran at 1e-9, and their verdicts compare the breach of "
                                  f"the joint laws with {NEAR_ADMISSIBLE_TOL:g} of the "
                                  "largest force")
            if len(self.runner.rejected) > n and not self._rejected_noted:
                self._rejected_noted = True
                first = self.runner.rejected[n]
                again_by = getattr(first, "again_by", None)
                by = (f"by {again_by}" if again_by else
                      "at the next settings of its ladder" if self.solver == FALLBACK
                      else f"by {FALLBACK}")
                self.notes.append(f"answers of {self.solver} that failed their check against "
                                  f"the problem were solved again {by} (first: "
                                  f"{self.runner.rejected[n]})")
            return res

    # -- lambda*: one LP ---------------------------------------------------------------
    def load_limit(self, f: float, rtol: float, mechanism_kind: str = "vertex") -> Limit:
        """lambda* from max lambda s.t. A x + F_dead + lambda F_live = 0 and the joint
        laws; by LP duality the multipliers of the equilibrium rows are the virtual
        velocities of the collapse mechanism (associative flow rule, kinematic theorem).
        Solved at the tight tolerances of the relaxations: at Clarabel's defaults (1e-8)
        lambda* of a 1,000-block wall is off by 7e-5 (its toe carries a thousand block
        weights, and the residuals are relative to that), at 1e-10 by 4e-6 of the
        simplex (HiGHS) answer, for 1.4x the interior-point iterations; and with the
        finer KKT regularisation of :data:`~rigidblocks.solvers.policy.VALUE_SETTINGS`
        by 4e-7 (at f = 1.18372, in 49 iterations against 56).

        ``mechanism_kind``: "vertex" (default) picks one mechanism of the optimal face
        (:func:`~rigidblocks.methods.vertex.vertex_dual`); "blend" keeps the
        interior-point duals (the centre of the face)."""
        if self.system.unheld_load(0.0) > UNHELD_TOL:  # (as :meth:`relaxation` reads it)
            self.notes.append(f"the dead load alone is not admissible: {NO_EQUILIBRIUM}")
            return Limit("unstable")
        prob, jr, res = self.max_load(f)
        if res.verified is False:
            self.notes.append(f"the {res.solver} answer to the maximum-load problem "
                              f"({res.status}) fails its check against the problem: "
                              f"{describe(res.residuals)}: undecided")
            return Limit("undecided")
        if res.status == UNBOUNDED:
            dead = self._dead_admissible(f)
            if dead is None:
                return Limit("undecided")
            return Limit("unbounded" if dead else "unstable")
        if res.status == INFEASIBLE:
            return self._unstable_confirmed(f, "the maximum-load problem has no "
                                            "admissible state")
        lam = float(res.z[prob.cols["lambda"]][0])
        if lam < -ADMISSIBLE_TOL:
            return self._unstable_confirmed(f, f"the largest admissible multiplier is "
                                            f"negative ({lam:.6g})")
        dead = self._dead_admissible(f)
        if dead is None:
            return Limit("undecided", None, None, lam)
        if not dead:
            self.notes.append(f"largest admissible multiplier {lam:.6g}, but only with the "
                              "live load propping the structure up")
            return Limit("unstable")
        y_eq, kind = self.mechanism_duals(prob, res, lam, mechanism_kind, "lambda*")
        with self.timings.stage("state"):
            mech = mechanism(self.system, self.lscaling.row, y_eq, kind,
                             self.lscaling.forces(res.z[prob.cols["x"]]))
        sliding = tuple(k for k, md in enumerate(mech.modes) if md.startswith("slide"))
        # lambda* is read from the solver's answer, whose state carries it; above it,
        # what the duals' residual could account for (SPREAD_MARGIN times its work on
        # that state, as for the f* searches' values): where that exceeds rtol, the
        # result gives the bracket and says so (the 50,065-block wall: 0.3679 with
        # Clarabel's default regularisation, 0.3790 with VALUE_SETTINGS)
        reach = SPREAD_MARGIN * dual_work(prob, res)[1]
        scale = max(abs(lam), 1.0)
        upper = lam
        if reach > rtol * scale:
            upper = lam + reach
            self.notes.append(
                f"lambda* = {lam:.10g} is the solver's answer (its state carries it); "
                f"what the residual of its duals could account for ({SPREAD_MARGIN:g} "
                f"times its work on that state) allows lambda* above it: lambda* is in "
                f"{fmt_bracket(lam, upper)}, the upper end by value, not certified")
        return Limit("collapse", lam, lam, upper, governing=sliding, mechanism=mech,
                     at=Verdict(ADMISSIBLE, 0.0, (), (res, prob)), resolution=reach / scale)

    def mechanism_duals(self, prob: Any, res: SolverResult, lam: float, kind: str,
                        what: str) -> tuple[np.ndarray, str]:
        """The equilibrium rows' duals of a solved limit problem ``prob`` (multiplier
        ``lam``, named ``what`` in notes) to draw as its mechanism, and which they are:
        with ``kind`` "vertex" one mechanism of the optimal face
        (:func:`~rigidblocks.methods.vertex.vertex_dual`; the blend, with a note, where
        none is found), with "blend" the interior-point duals."""
        eq = prob.rows["equilibrium"]
        if kind != "vertex":
            return res.y[eq], "blend"
        self.progress.stage = "vertex mechanism"
        with self.timings.stage("mechanism"):
            vd = vertex_dual(prob, res, eq, self.system.dofs)
        if vd is None:
            self.notes.append("mechanism: the blend of the optimal face (no vertex could "
                              "be found)")
            return res.y[eq], "blend"
        work_at = float(prob.b @ vd[0])
        if work_at > lam * (1 + OFF_FACE) + face_allowance(lam) + ADMISSIBLE_TOL:
            # a reason, not a solver note: its joints need not be those at lambda* (the
            # corbel dome: the whole dome sliding on its slab, at 0.6 against lambda* =
            # 0.599985, printed as the governing joints beside "other collapse
            # mechanisms reach the same multiplier: the one drawn is one of them")
            self.notes.append(f"{OFF_FACE_NOTE} balances at lambda = {work_at:.6g}, "
                              f"{work_at / lam - 1:.1e} (relative) above {what}: it is the "
                              "nearest that can be drawn, not a collapse mechanism at "
                              f"{what}, whose joints may be others (their blend: "
                              "`rigidblocks load --mechanism blend`)")
        elif _other_mechanisms(res.y[eq], vd[0][eq]):
            self.notes.append(OTHER_MECHANISMS)
        return vd[0][eq], vd[1]

    def _unstable_confirmed(self, f: float, why: str) -> Limit:
        """"unstable" where the maximum-load problem says that no multiplier is
        admissible (``why``) and the dead load's own verdict agrees; "undecided" where
        that verdict cannot decide or finds the dead load admissible (a block of weight
        1e-10 of the 10 kN it carries: lambda* = -1.37e-6 by the LP, the dead load
        undecided, where lambda* = 5 without the weight)."""
        dead = self._dead_admissible(f)
        if dead is False:
            self.notes.append(f"{why}: the dead load alone is not admissible")
            return Limit("unstable")
        if dead:
            self.notes.append(f"{why}, yet the dead load alone is admissible: the "
                              "maximum-load problem is not resolved (forces far above "
                              "the loads of the blocks they act on)")
        return Limit("undecided")

    def _dead_admissible(self, f: float) -> bool | None:
        """Is lambda = 0 admissible? The admissible multipliers form an interval, which
        may lie wholly above 0 when the live load props up a structure that cannot stand
        under its dead load alone. One relaxation solve (none without a dead load); None
        (with a note) when that verdict is undecided."""
        if not np.any(self.system.dead):
            return True
        rx = self.relaxation(f, 0.0)
        if not rx.decided:
            self.notes.append(f"under the dead load alone: "
                              f"{rx.unresolved or near_threshold(rx)}")
            return None
        if not rx.zero:
            self.notes.append("the dead load alone is not admissible")
            return False
        return True


#: the start of the reason given where the mechanism drawn is off the optimal face
OFF_FACE_NOTE = "the mechanism drawn (its joints the governing ones)"
#: the note of a 3D scene with a tensile strength: each contact point has its own Coulomb
#: cone, so a point pulls only as far as its cohesion keeps the cone open, where in 2D the
#: shear row sums the joint's points (a 1 x 1.5 x 2 box bonded by a tensile strength of
#: 20 at f = 5: lambda* = 0.5 in 3D, 0.75 in 2D, docs/methods.md)
TENSION_3D_NOTE = ("in 3D each contact point has its own Coulomb cone, |T_k| <= f N_k + "
                   "c a_k, so a point pulls at most c a_k / f however large the tensile "
                   "strength: without cohesion a tensile strength gives a joint no bending "
                   "capacity here, where in 2D it does (there |T| <= f (N1 + N2) + c a over "
                   "the joint): with finite friction the answers may lie below the 2D "
                   "scene's (on the safe side)")
#: ... and at infinite friction, in 2D and 3D alike: the law has no shear row there
TENSION_INFINITE_NOTE = ("at infinite friction a bonded joint has no shear row, so its net "
                         "tension is bounded by its tensile strength alone; at any finite "
                         "f the row |T| <= f (N1 + N2) + c a keeps it below c a / f (none "
                         "without cohesion): where the answer rests on a bonded joint's net "
                         "pull, no large finite f gives it (a 1 x 2 block bonded by 10, W "
                         "= 40, lifts at lambda* = 1.25 here and at 1 for every finite f; "
                         "a bending capacity, one link pulling while the other pushes, is "
                         "the same at every f; docs/methods.md)")


def bonds_pull_without_friction(contacts: Any, f_joint: np.ndarray) -> bool:
    """Does :data:`TENSION_INFINITE_NOTE` apply: a joint with a tensile strength and
    infinite friction (``f_joint``, per joint)?"""
    return bool(np.any((contacts.tensile_strength > 0) & ~np.isfinite(f_joint)))


def cones_close_under_tension(contacts: Any, f_joint: np.ndarray) -> bool:
    """Does :data:`TENSION_3D_NOTE` apply: a 3D joint with a tensile strength and a
    finite friction (``f_joint``, per joint)?"""
    return contacts.dimension == 3 and bool(np.any((contacts.tensile_strength > 0)
                                                   & np.isfinite(f_joint)))


#: the note where the mechanism drawn is one of several optimal ones
OTHER_MECHANISMS = ("other collapse mechanisms reach the same multiplier: the one drawn is "
                    "one of them (their blend: `rigidblocks load --mechanism blend`)")
#: the interior-point duals (the centre of the optimal face) and the vertex drawn are one
#: mechanism where their velocities, each scaled to its largest, agree to this
SAME_MECHANISM = 1e-3


def _other_mechanisms(y_blend: np.ndarray, y_vertex: np.ndarray) -> bool:
    """Does the optimal face hold other mechanisms than the vertex drawn: is the centre
    of the face, which moves as every optimal mechanism does in part, not the vertex
    itself (to SAME_MECHANISM)? The symmetric reference model drew one side's sliding
    with nothing said of its mirror image."""
    a, b = np.asarray(y_blend, dtype=float), np.asarray(y_vertex, dtype=float)
    na, nb = float(np.abs(a).max(initial=0.0)), float(np.abs(b).max(initial=0.0))
    if na == 0 or nb == 0:
        return False
    a, b = a / na, b / nb
    return float(min(np.abs(a - b).max(), np.abs(a + b).max())) > SAME_MECHANISM


__all__ = ["ADMISSIBLE_TOL", "ConvexMethod", "FRICTION_ATOL", "FRICTION_RTOL", "Relaxation",
           "STATE_SLACK", "VERDICT_RTOL"]
