"""The solver interface: a conic problem in, a canonical status and solution out.

Problems are posed in one standard form (Clarabel's)::

    minimise    1/2 z'Pz + c'z
    subject to  A z + s = b,   s in K = {0}^n_eq x R+^n_nonneg x SOC(k_1) x ... x SOC(k_r)

Every back end maps its own statuses onto four canonical ones: ``optimal``,
``infeasible`` (no z satisfies the constraints: for us, no admissible equilibrium; a
result, not an error), ``unbounded`` and ``failure`` (iteration limit, numerical
trouble, "almost" answers). A failure carries the solver's own status words and is
raised as :class:`~rigidblocks.errors.SolverFailure` by the analyses, never passed on
as a number.

Duals ``y`` follow the sign convention of the KKT condition ``P z + c + A' y = 0``
(y >= 0 on the nonnegative rows), whatever the back end.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import scipy.sparse as sp

OPTIMAL = "optimal"
INFEASIBLE = "infeasible"
UNBOUNDED = "unbounded"
FAILURE = "failure"


@dataclass(frozen=True, eq=False)
class ConicProblem:
    """A problem in standard conic form (see the module docstring).

    ``cols`` and ``rows`` name blocks of variables and of constraint rows, so that
    callers read solutions and duals by name, not by stride arithmetic.
    """

    c: np.ndarray
    A: sp.csc_matrix
    b: np.ndarray
    n_eq: int
    n_nonneg: int
    soc: tuple[int, ...] = ()
    P: sp.csc_matrix | None = None
    cols: dict[str, slice] = field(default_factory=dict)
    rows: dict[str, slice] = field(default_factory=dict)
    #: parametric entries of A by name: (positions in ``A.data``, coefficients), so that
    #: ``with_parameter(name, p)`` sets those entries to ``coefficients * p``
    params: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)

    @property
    def n(self) -> int:
        return len(self.c)

    def with_parameter(self, name: str, value: float) -> ConicProblem:
        """The same problem with the entries of parameter ``name`` set for ``value``
        (a copy of ``A.data``; the sparsity pattern is shared)."""
        pos, coef = self.params[name]
        A = self.A.tocsc()
        data = A.data.copy()
        data[pos] = coef * value
        return replace(self, A=sp.csc_matrix((data, A.indices, A.indptr), shape=A.shape))

    @property
    def is_lp(self) -> bool:
        return not self.soc and (self.P is None or self.P.nnz == 0)


@dataclass(frozen=True, eq=False)
class SolverResult:
    """What a back end returns: canonical status, primal z, duals y and diagnostics."""

    status: str
    z: np.ndarray | None
    y: np.ndarray | None
    objective: float
    solver: str
    raw_status: str
    iterations: int = 0
    solve_time: float = 0.0

    @property
    def ok(self) -> bool:
        return self.status == OPTIMAL
