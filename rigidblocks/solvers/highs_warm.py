"""One linear program solved again and again with changed row bounds: HiGHS's dual
simplex from the last basis (highspy, the ``solvers`` extra), or cold through
scipy.optimize.linprog where highspy is not installed.

The non-associative limit iterations (:mod:`rigidblocks.analyses.na_limit`,
:mod:`rigidblocks.analyses.na_mechanism`) solve the same LP with new right-hand sides
at every step. Only bounds change, so the last optimal basis stays dual feasible and the
dual simplex restarts from it; where the bounds moved far (the first steps of a walk),
the warm solve can take longer than a solve from scratch by the interior-point method
(on the 1,041-block wall: 5 s warm against 1.3 s IPM with crossover): a warm solve that
runs past ``WARM_LIMIT`` simplex iterations is given up and the LP solved by IPM with
crossover, which ends on a basis again; where ``cold_after_give_up`` is set, the solve
after one given up goes to IPM at once, and after each further give-up in a row twice
as many (phase 2 of the mechanisms' walk, whose warm solves are given up in runs).
Every answer is a basic solution, so its row duals are those of a vertex: a row whose
dual is not zero is active in every optimal solution (complementary slackness), which
the mechanism walk relies on.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .base import FAILURE, INFEASIBLE, OPTIMAL, UNBOUNDED

#: a warm dual-simplex solve past this many iterations is solved again from scratch by
#: IPM with crossover (1,041-block wall: the first steps' warm solves ran 12,000 to
#: 30,000 iterations, 5 to 13 s; later ones under 1,000)
WARM_LIMIT = 3000
#: HiGHS's primal and dual feasibility tolerances
FEAS_TOL = 1e-9


def has_highspy() -> bool:
    """Is highspy (the ``solvers`` extra) installed?"""
    from importlib.util import find_spec

    try:
        return find_spec("highspy") is not None
    except ValueError:  # in sys.modules as None: import blocked
        return False


class WarmLp:
    """min c'x  s.t.  row_lower <= A x <= row_upper, x free, in one HiGHS model.

    :meth:`solve` changes the bounds of some rows and solves from the last basis;
    :attr:`x` and :attr:`duals` read the answer (HiGHS's row duals: d objective / d
    bound). ``solves``, ``cold`` and ``given_up`` count the solves, those done by IPM
    and the warm solves given up for IPM; ``iterations`` those of the last solve
    (simplex and interior-point, a warm attempt given up included)."""

    def __init__(self, c: np.ndarray, A: Any, row_lower: np.ndarray,
                 row_upper: np.ndarray):
        import highspy

        self._hs = highspy
        A = A.tocsc()
        n = A.shape[1]
        inf = highspy.kHighsInf
        lp = highspy.HighsLp()
        lp.num_col_, lp.num_row_ = n, A.shape[0]
        lp.col_cost_ = np.asarray(c, dtype=float)
        lp.col_lower_ = np.full(n, -inf)
        lp.col_upper_ = np.full(n, inf)
        lp.row_lower_ = np.maximum(row_lower, -inf)
        lp.row_upper_ = np.minimum(row_upper, inf)
        lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
        lp.a_matrix_.start_ = A.indptr
        lp.a_matrix_.index_ = A.indices
        lp.a_matrix_.value_ = A.data
        try:  # the core object: highspy.Highs() prints a banner before any option is set
            from highspy._core import _Highs as Highs
        except ImportError:  # pragma: no cover - other highspy layouts
            Highs = highspy.Highs
        h = Highs()
        h.setOptionValue("output_flag", False)
        h.setOptionValue("primal_feasibility_tolerance", FEAS_TOL)
        h.setOptionValue("dual_feasibility_tolerance", FEAS_TOL)
        h.passModel(lp)
        self.h = h
        self.warm = False
        self.solves = 0
        self.cold = 0
        #: simplex iterations of a warm solve before it is solved from scratch by IPM
        self.limit = WARM_LIMIT
        #: do the solves after a warm one given up go to IPM at once (one after the
        #: first give-up, twice as many after each further one in a row)?
        self.cold_after_give_up = False
        #: warm solves given up
        self.given_up = 0
        self._cold_left = 0  # solves still to go to IPM at once
        self._backoff = 1  # ... after the next give-up
        self.iterations = 0

    def solve(self, rows: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> str:
        """Set the bounds of ``rows`` and solve: OPTIMAL, INFEASIBLE, UNBOUNDED or
        FAILURE."""
        h, inf = self.h, self._hs.kHighsInf
        h.changeRowsBounds(len(rows), np.asarray(rows, dtype=np.int32),
                           np.maximum(lower, -inf), np.minimum(upper, inf))
        self.solves += 1
        skip = self._cold_left > 0
        self._cold_left = max(self._cold_left - 1, 0)
        self.iterations = 0
        if self.warm and not skip:
            h.setOptionValue("solver", "simplex")
            h.setOptionValue("simplex_iteration_limit", self.limit)
            h.run()
            self.iterations = self._iterations()
            st = self._status()
            if st != FAILURE:
                self._backoff = 1
                return st
            self.given_up += 1
            if self.cold_after_give_up:
                self._cold_left, self._backoff = self._backoff, 2 * self._backoff
        return self._from_scratch()

    def minimise(self, c: np.ndarray) -> str:
        """Change the cost to ``c`` and solve: from the last basis by the primal simplex
        (the rows are unchanged, so that basis stays primal feasible), the first solve
        by IPM with crossover. OPTIMAL, INFEASIBLE, UNBOUNDED or FAILURE."""
        h = self.h
        c = np.asarray(c, dtype=float)
        h.changeColsCost(len(c), np.arange(len(c), dtype=np.int32), c)
        self.solves += 1
        self.iterations = 0
        if not self.warm:
            return self._from_scratch()
        h.setOptionValue("solver", "simplex")
        h.setOptionValue("simplex_strategy", 4)  # primal
        h.setOptionValue("simplex_iteration_limit", 2**31 - 1)
        h.run()
        h.setOptionValue("simplex_strategy", 1)
        self.iterations = self._iterations()
        return self._status()

    def _from_scratch(self) -> str:
        """Solve the model as it stands by IPM with crossover (no iteration limit: a
        warm attempt's does not carry over), counted as cold; the iterations add to
        :attr:`iterations`."""
        h = self.h
        self.cold += 1
        h.clearSolver()
        h.setOptionValue("solver", "ipm")
        h.setOptionValue("simplex_iteration_limit", 2**31 - 1)
        h.run()
        self.iterations += self._iterations()
        st = self._status()
        self.warm = st == OPTIMAL
        return st

    def _iterations(self) -> int:
        info = self.h.getInfo()
        return int(max(info.simplex_iteration_count, 0) + max(info.ipm_iteration_count, 0))

    def _status(self) -> str:
        ms = self._hs.HighsModelStatus
        return {ms.kOptimal: OPTIMAL, ms.kInfeasible: INFEASIBLE,
                ms.kUnbounded: UNBOUNDED,
                ms.kUnboundedOrInfeasible: UNBOUNDED}.get(self.h.getModelStatus(), FAILURE)

    @property
    def x(self) -> np.ndarray:
        return np.asarray(self.h.getSolution().col_value)

    @property
    def duals(self) -> np.ndarray:
        return np.asarray(self.h.getSolution().row_dual)


class ColdLp:
    """:class:`WarmLp`'s interface through scipy.optimize.linprog (HiGHS bundled with
    scipy; no warm start): each solve from scratch, an answer at a vertex (dual simplex
    or IPM with crossover, as HiGHS chooses)."""

    def __init__(self, c: np.ndarray, A: Any, row_lower: np.ndarray,
                 row_upper: np.ndarray):
        self.c = np.asarray(c, dtype=float)
        self.A = A.tocsr()
        self.lower = np.array(row_lower, dtype=float)
        self.upper = np.array(row_upper, dtype=float)
        self._x = self._y = np.zeros(0)
        self.solves = self.cold = self.iterations = 0
        #: :class:`WarmLp`'s; unused (every solve is from scratch)
        self.limit = WARM_LIMIT
        self.cold_after_give_up = False

    def solve(self, rows: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> str:
        from scipy.optimize import linprog

        self.lower[rows], self.upper[rows] = lower, upper
        self.solves += 1
        self.cold += 1
        lo, up = self.lower, self.upper
        eq = lo == up
        le = ~eq & np.isfinite(up)
        ge = ~eq & np.isfinite(lo)
        A = self.A
        A_ub = _vstack(A[le], -A[ge])
        res = linprog(self.c, A_ub=A_ub, b_ub=np.concatenate([up[le], -lo[ge]]),
                      A_eq=A[eq] if eq.any() else None, b_eq=up[eq] if eq.any() else None,
                      bounds=(None, None), method="highs",
                      options={"primal_feasibility_tolerance": FEAS_TOL,
                               "dual_feasibility_tolerance": FEAS_TOL})
        self.iterations = int(getattr(res, "nit", 0) or 0)
        st = {0: OPTIMAL, 2: INFEASIBLE, 3: UNBOUNDED}.get(res.status, FAILURE)
        if st == OPTIMAL:
            self._x = np.asarray(res.x)
            y = np.zeros(len(lo))
            if eq.any():
                y[eq] = res.eqlin.marginals
            ineq = res.ineqlin.marginals
            y[le] += ineq[:int(le.sum())]
            y[ge] -= ineq[int(le.sum()):]
            self._y = y
        return st

    def minimise(self, c: np.ndarray) -> str:
        """Change the cost to ``c`` and solve (from scratch)."""
        self.c = np.asarray(c, dtype=float)
        return self.solve(np.zeros(0, dtype=int), np.zeros(0), np.zeros(0))

    @property
    def x(self) -> np.ndarray:
        return self._x

    @property
    def duals(self) -> np.ndarray:
        return self._y


def _vstack(*blocks: Any) -> Any:
    import scipy.sparse as sp

    return sp.vstack(blocks, format="csr")


def warm_lp(c: np.ndarray, A: Any, row_lower: np.ndarray, row_upper: np.ndarray
            ) -> WarmLp | ColdLp:
    """A :class:`WarmLp` where highspy is installed, else a :class:`ColdLp`."""
    return (WarmLp if has_highspy() else ColdLp)(c, A, row_lower, row_upper)


def nonzero(y: np.ndarray, rel: float) -> np.ndarray:
    """Where |y| exceeds ``rel`` times the largest |y| (and round-off of 1)."""
    big = max(1.0, float(np.abs(y).max(initial=0.0)))
    return np.abs(y) > rel * big if math.isfinite(big) else np.isfinite(y) & (y != 0)


__all__ = ["ColdLp", "WarmLp", "has_highspy", "nonzero", "warm_lp"]
