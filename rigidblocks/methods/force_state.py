"""The force state of the convex path: the admissible state of least complementary
energy (a QP), and how large the forces of an admissible state must be."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..equilibrium import force_state
from ..errors import SolverFailure
from ..problems.formulation import energy_problem
from ..results import ForceState
from ..solvers import OPTIMAL, SolverResult
from ..solvers.policy import ESTIMATE, LP_ONLY, STATE, Ladder, describe
from .base import Verdict
from .relaxation import FORCE_WARN, Relaxation

#: slack (reference-force units) granted to the force-state QP at a limit state, where
#: the admissible set shrinks to a point and round-off would make it empty
STATE_SLACK = 1e-9


class ForceStates:
    """The force states of :class:`~rigidblocks.methods.convex.ConvexMethod` (a part of
    it)."""

    def least_energy(self, f: float, load_factor: float) -> Relaxation | None:
        """The verdict and the force state from one solve, where the structure is
        admissible: the least-energy QP with the joint laws themselves (not relaxed),
        infeasible exactly when no admissible state exists. Its answer, checked by the
        solver policy, is read as a relaxation's: R is its state's breach of the laws,
        compared, as its equilibrium residual is, with ADMISSIBLE_TOL x its largest
        force. None where that does not certify an admissible state (infeasible,
        failed, a breach or residual above the threshold, forces beyond resolution):
        the relaxation then decides. The 1,009-block wall at self-weight: one QP (13
        iterations) instead of the relaxation (10) and the QP; extruded, its breach 0
        and residual 8e-14. The laws are not relaxed by :data:`STATE_SLACK` as
        :meth:`state` relaxes them: on the extruded 6 x 5 wall at load factor 0.2 the
        state would use that slack and breach the laws by 1.05 times the threshold
        (by 2e-12 of it unrelaxed). Not tried without unknowns (no contacts), nor with
        a back end that solves LPs only (its verdicts are asked for, not those of the
        back end that takes its QPs)."""
        if self.system.layout.size == 0 or self.solver in LP_ONLY:
            return None
        with self.timings.stage("build"):
            prob, jr = energy_problem(self.system, self.vscaling, self.f_joint(f),
                                      load_factor, 0.0, self.pyramid)
        res = self._checked_state(prob, STATE)
        if res is None:
            return None
        breach, residual = self._breach(prob, jr, res.z)
        tol, unresolved = self._resolution(res.z[prob.cols["x"]])
        rx = Relaxation(breach, 0.0, res, jr, prob, tol, f, residual=residual,
                        unresolved=unresolved, least_energy=True)
        return rx if rx.zero else None

    def state(self, f: float, load_factor: float, verdict: Verdict,
              limit: bool = False) -> ForceState | None:
        """The admissible state of least complementary energy (a QP).

        At a limit state (``limit``) the QP's energy is scaled by the limit problem's
        state (:func:`~rigidblocks.problems.formulation.energy_problem`): there it
        saves iterations (5,006-block wall at f*: 71 instead of a stall at 200), away
        from limits it costs one or two (the same wall at f = 0.6 under its own
        weight: 15 instead of 13). At a limit state the admissible set shrinks to
        (nearly) one point and the QP can be out of the interior-point solver's reach
        (3D cones sliding all round a bed joint); the state of the solved limit problem
        (an admissible state, not the least-energy one) is then returned, and the
        result's notes say so. The QP is solved once, without the policy's retry with
        refined settings.
        """
        data = verdict.data
        if isinstance(data, Relaxation) and data.least_energy:
            with self.timings.stage("state"):
                return force_state(self.system,
                                   self.vscaling.forces(data.res.z[data.prob.cols["x"]]),
                                   "least complementary energy")
        if isinstance(data, Relaxation):
            relax, solved, limit_x = data.R + STATE_SLACK, data.res, data.prob.cols["x"]
            scaling = self.vscaling
        else:  # the max-load LP: (result, problem)
            res, prob = data
            relax, solved, limit_x = STATE_SLACK, res, prob.cols["x"]
            scaling = self.lscaling
        with self.timings.stage("build"):
            prob = energy_problem(self.system, scaling, self.f_joint(f), load_factor,
                                  relax, self.pyramid,
                                  reference=solved.z[limit_x] if limit else None)[0]
        try:
            # solved once: where the interior-point iteration stalls near a limit, a
            # retry with other settings stalls too (5,006-block wall at f*: AlmostSolved
            # after 200 iterations, twice), and the solved problem's state serves
            res = self.solve(prob, "force-state", STATE)
            status = res.raw_status if res.status != OPTIMAL else None
            if status is None and res.verified is False:
                status = f"{res.raw_status}, failing its check ({describe(res.residuals)})"
        except SolverFailure as exc:
            status = exc.status
        with self.timings.stage("state"):
            if status is None:
                return force_state(self.system, scaling.forces(res.z[prob.cols["x"]]),
                                   "least complementary energy")
            self.notes.append(f"force state: the solution of the limit problem (the "
                              f"least-energy QP ended with status {status})")
            return force_state(self.system, scaling.forces(solved.z[limit_x]),
                               "solution of the limit problem")

    def force_ratio(self, f: float, load_factor: float, rx: Relaxation) -> float:
        """How many times the loads of the blocks they act on the forces of an admissible
        state at (f, lambda) must be: the relaxation's state gives an upper bound, and
        where that exceeds FORCE_WARN the least-energy state (forces no larger than
        needed) decides."""
        if rx.res.z is None:
            return 0.0
        big = float(np.abs(rx.res.z[rx.prob.cols["x"]]).max(initial=0.0))
        if big <= FORCE_WARN or rx.least_energy:
            return big
        with self.timings.stage("build"):
            prob = energy_problem(self.system, self.vscaling, self.f_joint(f), load_factor,
                                  rx.R + STATE_SLACK, self.pyramid,
                                  reference=rx.res.z[rx.prob.cols["x"]])[0]
        res = self._checked_state(prob, ESTIMATE)
        if res is None:
            return big
        return min(big, float(np.abs(res.z[prob.cols["x"]]).max(initial=0.0)))

    def _checked_state(self, prob: Any, ladder: Ladder) -> SolverResult | None:
        """The force-state QP ``prob`` solved up ``ladder``: its answer where that is a
        checked optimum, else None."""
        try:
            res = self.solve(prob, "force-state", ladder)
        except SolverFailure:
            return None
        return res if res.status == OPTIMAL and res.verified is not False else None


__all__ = ["STATE_SLACK", "ForceStates"]
