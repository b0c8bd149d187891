"""The iterative impressed-distortion solver of the seed paper, as a projection method.

The seed (Eq. 1-4) writes the joints as links: one normal link per contact point and
one shear link per 2D joint. Equilibrium is ``A X + F = 0`` (Eq. 1). With a diagonal
link flexibility C (:func:`rigidblocks.problems.formulation.flexibility`) and the
stiffness K = C^-1, the elastic solution of the linked structure is (Eq. 3)::

    X0  = Ã (A Ã)^-1 (-F),          Ã = K A^T
    X_N = (I - Ã (A Ã)^-1 A) delta   (self-stress of impressed distortions delta)

X0 is the equilibrium state of least complementary energy 1/2 X'CX, and X0 + X_N
(any delta) is again in equilibrium: the second line is the C-orthogonal projector
onto the self-stress states, ``A X_N = 0``. The seed iterates on delta until no normal
link is in tension and no shear link exceeds its friction threshold (Eq. 2, 4).

The fixed point the seed's iteration seeks, the admissible state closest to the
elastic one, is the quadratic program

    min 1/2 ||X - X0||_C^2   s.t.   A X + F = 0,  X in K,

K being the joint laws (per joint: N_k >= -sigma_t a_k, |T| <= f (N_1 + N_2) + c a);
for X in E = {A X + F = 0} the objective differs from the complementary energy
1/2 X'CX by a constant, so this is :func:`rigidblocks.problems.formulation.build_energy_qp`.
The iteration here is the alternating direction method of multipliers (ADMM, a
Douglas-Rachford splitting) on E and K in the metric of C, each step being a step of
the seed's method:

    delta_k  = rho / (1 + rho) (Z_k - U_k - X0)          an impressed distortion
    X_{k+1}  = X0 + (I - Ã (A Ã)^-1 A) delta_k           its self-stress added to X0
    Z_{k+1}  = P_K(alpha X_{k+1} + (1 - alpha) Z_k + U_k)  the joint laws applied
    U_{k+1}  = U_k + alpha X_{k+1} + (1 - alpha) Z_k - Z_{k+1}

(over-relaxation alpha = 1.6; U accumulates the part of the distortion the joint laws
reject). X_k is always in equilibrium; the verdict is on its violation of K. Because
the quadratic term and the penalty share the metric C, the projector does not depend on
rho, which is rebalanced (primal against dual residual) at iterations 20, 40, 80, ...
at no cost. Dykstra's alternating projections, which the seed's iteration amounts to
when the distortion is simply the rejected part, converge to the same state but much
more slowly (tens of thousands of iterations on a 100-block wall). ``P_K`` is exact and
in closed form per joint (:meth:`_Laws.project`). ``P_E`` uses one sparse LU
factorisation of A K A^T (K = C^-1) per scene, reused by every iteration and every
trial f or lambda; no dense projector is formed.

Verdicts (status of a run, with a reason):

* ``admissible``: X_k violates no joint law by more than ``tol`` (reference-force
  units of :class:`~rigidblocks.problems.formulation.Scaling`); with ``optimal`` the
  step of X and the dual residual must also be below ``max(tol, STATE_TOL)``, so that
  X_k is the QP's state (to about that, relative to the largest force). If the budget
  ends first, the last admissible iterate is returned, with a note.
* ``inadmissible``: when E and K do not meet, the violation tends to a positive limit
  and U drifts by the shortest vector g from K to E per iteration. Every ``window``
  iterations (from ``2 window`` on) the limit is extrapolated from the violations at
  k/2 and k as if they fell like 1/sqrt(k) (slower than a converging run does), and
  the drift g is turned into block velocities y = (A K A^T)^-1 A g. The run stops as
  inadmissible when the extrapolated limit exceeds half the violation and ``GAP`` x
  tol, and y is a collapse mechanism checked as Farkas' certificate to a tolerance that
  scales with the problem: the loads do net work on it beyond what the links resist,
  well above round-off, and its breach of the associative flow rule is so small that
  an admissible state would need forces ``CERT_FORCE`` times those of the iteration
  (see :meth:`mechanism_of`). Both tests together: a feasible run can pass through
  plateaus of the violation, but its drift is then no such mechanism.
* ``undecided``: near f* (or lambda*) the gap between E and K shrinks to zero and the
  iteration needs of the order of 1/gap iterations to see it. A run that stalls with a
  violation below ``GAP`` x tol (less than 1% decrease between k/2 and k) is "stalled";
  a run that uses its budget is "no convergence within the iteration budget". Both are
  reported as undecided, never as a number.
* ``failure``: A K A^T singular or ill-conditioned: a mechanism of the bilateral
  linked structure (a block motion that stretches no link).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..equilibrium import EquilibriumSystem

#: violation (reference-force units) below which a state counts as admissible
TOL = 1e-9
#: iteration budget of one run
MAX_ITER = 20000
#: iterations between two stalling tests
WINDOW = 50
#: a violation above this fraction of its value at half the iterations counts as stalled
STALL = 0.99
#: a stalled violation above GAP x tol is a gap between equilibrium and the joint laws
GAP = 100.0
SQRT2 = math.sqrt(2.0)
#: a mechanism certifies inadmissibility only if every admissible state would need forces
#: above CERT_FORCE times the largest force of the iteration (see :meth:`mechanism_of`);
#: with ROUNDOFF that certifies down to a relative distance of about 1e-9 from the limit
CERT_FORCE = 1e5
#: ... and if the net work of the loads on it exceeds this fraction of sum |y_i b_i| (five
#: orders above its round-off; the net work falls with the distance to the limit)
WORK_RTOL = 1e-10
#: relative round-off of the joint deformations w = A^T y, added to the flow-rule breach
ROUNDOFF = 1e-14
#: alternating steps between block motions and the flow rule's cone that polish a drift
#: into a certificate (:meth:`DistortionSolver.mechanism_of`); on the 106-block wall
#: example at f = 0.96 (f* = 1) the bound grows by a factor 50 every 25 steps and
#: certifies after 45; a polish whose bound grows by less than 10% in 10 steps stops
POLISH = 100
#: step and dual residual below which an admissible iterate is the QP's state
STATE_TOL = 1e-8
#: last iteration at which the penalty may be rebalanced
ADAPT_LAST = MAX_ITER
#: memory of the Anderson acceleration (0: none; see :meth:`DistortionSolver.run`)
ANDERSON = 5
#: largest Anderson correction, in units of the plain step
AA_STEP = 1e4
#: iteration budget of the accelerated phase of a run (see :meth:`DistortionSolver.run`)
AA_BUDGET = 5000
#: plain iterations before the accelerated phase (see :meth:`DistortionSolver.run`)
PLAIN_FIRST = 1000
#: the accelerated phase ends from here on when its best violation no longer halves
AA_GIVE_UP = 500
#: initial penalty of the iteration (the ratio of the two terms of the x step)
RHO = 1.0
#: over-relaxation of the iteration (1: none; 1.6 as usual for ADMM)
ALPHA = 1.6
#: iterations at which the penalty is first rebalanced (then at twice as many, ...)
ADAPT = 20
#: reciprocal condition estimate of A K A^T below which the scene counts as a mechanism
RCOND_MIN = 1e-12


@dataclass(eq=False)
class _Iterate:
    """The state of a run between iterations, from which a partial run is resumed
    (``first_ok`` and the acceleration's memory ``aa`` start afresh with each call)."""

    z: np.ndarray
    u: np.ndarray
    v: np.ndarray
    rho: float
    hist: list[float]
    k: int = 0
    next_adapt: int = ADAPT
    last_ok: np.ndarray | None = None
    step: float = math.inf
    dual: float = math.inf
    first_ok: int | None = None
    aa: dict[str, Any] = field(default_factory=dict)


@dataclass
class Run:
    """One iteration run at fixed joint laws and load factor (scaled units).

    ``status``: "admissible", "inadmissible", "undecided" or "failure"; ``reason``
    explains the last two and the limit estimate of "inadmissible". ``violation`` is the
    largest breach of a joint law by X, ``residual`` the largest equilibrium residual
    |A X + F| (both scaled); ``history`` the violation after every iteration.
    """

    status: str
    x: np.ndarray
    iterations: int
    violation: float
    residual: float
    reason: str = ""
    history: list[float] = field(default_factory=list)
    time: float = 0.0
    resume: _Iterate | None = field(default=None, repr=False)


class DistortionSolver:
    """The factorised linked structure of one scene (2D, one shear link per joint)."""

    def __init__(self, system: EquilibriumSystem, scaling: Any, flexibility: np.ndarray,
                 block_ids: tuple[str, ...] = ()):
        """The linked structure of ``system`` (2D, one shear link per joint, two contact
        points per joint), in the scaled units of ``scaling`` (a
        :class:`~rigidblocks.problems.formulation.Scaling`), with link flexibilities
        ``flexibility`` (C); ``block_ids`` name blocks without joints in messages."""
        import scipy.sparse as sp

        self.system = system
        sysm = system
        c = sysm.contacts
        self.scaling = scaling
        self.C = np.asarray(flexibility, dtype=float)
        self.K = 1.0 / self.C
        self.As = sp.diags(self.scaling.row) @ sysm.A.tocsr()
        self.AsT = self.As.T.tocsr()
        self.P = c.n_points
        self.m = c.n_joints
        self.i0 = c.joint_start[:-1]
        self.it = self.P + np.arange(self.m)
        self.mechanism = ""
        self.loose_rows = np.zeros(0, dtype=bool)
        self.lu = None
        n = self.As.shape[0]
        if n:
            M = (self.As @ sp.diags(self.K) @ self.AsT).tocsc()
            from scipy.sparse.linalg import splu  # here: 60 ms of start-up
            try:
                lu = splu(M)
                d = np.abs(lu.U.diagonal())
                if d.size and (d.min() <= RCOND_MIN * d.max() or not np.all(np.isfinite(d))):
                    raise RuntimeError("ill-conditioned")
                self.lu = lu
            except RuntimeError:
                free = sysm.free_blocks
                ids = [block_ids[b] if b < len(block_ids) else str(b) for b in free]
                rows = np.asarray(abs(self.As).sum(axis=1)).ravel().reshape(-1, sysm.dofs)
                loose = [ids[k] for k in range(len(ids)) if np.all(rows[k] == 0)]
                self.loose_rows = np.repeat(np.all(rows == 0, axis=1), sysm.dofs)
                extra = f" (blocks without joints: {', '.join(loose)})" if loose else ""
                self.mechanism = ("A C^-1 A^T is singular or ill-conditioned: the linked "
                                  "structure is a mechanism" + extra)

    # -- the two projections ---------------------------------------------------------
    def rhs(self, load_factor: float) -> np.ndarray:
        s = self.system
        return -self.scaling.row * (s.dead + load_factor * s.live) / self.scaling.force

    def project_equilibrium(self, y: np.ndarray, b: np.ndarray) -> np.ndarray:
        """P_E(y) = y - K A^T (A K A^T)^-1 (A y - b), the C-metric projection onto E."""
        if self.lu is None:
            return y
        u = self.lu.solve(self.As @ y - b)
        return y - self.K * (self.AsT @ u)

    def elastic(self, load_factor: float) -> np.ndarray:
        """X0 = K A^T (A K A^T)^-1 (-F): the elastic (least-energy) equilibrium state."""
        return self.project_equilibrium(np.zeros(self.P + self.m), self.rhs(load_factor))

    def laws(self, f_joint: np.ndarray, tension: np.ndarray | None = None,
             cohesion: np.ndarray | None = None,
             nonassociative: np.ndarray | None = None) -> _Laws:
        """Per-joint rows G v <= h (v = N1, N2, T) and the candidate maps of P_K.

        ``nonassociative`` (m,) marks joints whose sliding does not dilate: their
        projection caps the shear at the friction threshold and leaves the normal forces
        as they are (the seed's separate normal and shear links, :class:`_NonAssocLaws`).
        """
        c = self.system.contacts
        F = self.scaling.force
        a = c.point_areas
        ts = c.tensile_strength if tension is None else tension
        co = c.cohesion if cohesion is None else cohesion
        args = (f_joint, ts[c.point_joint] * a / F, co * c.areas / F,
                np.array([self.C[self.i0], self.C[self.i0 + 1], self.C[self.it]]).T)
        if nonassociative is not None and np.any(nonassociative):
            return _NonAssocLaws(*args, np.asarray(nonassociative, dtype=bool))
        return _Laws(*args)

    def gather(self, x: np.ndarray) -> np.ndarray:
        return np.stack([x[self.i0], x[self.i0 + 1], x[self.it]], axis=1)

    def scatter(self, v: np.ndarray) -> np.ndarray:
        x = np.empty(self.P + self.m)
        x[self.i0], x[self.i0 + 1], x[self.it] = v[:, 0], v[:, 1], v[:, 2]
        return x

    def mechanism_of(self, laws: _Laws, g: np.ndarray, b: np.ndarray,
                     scale: float = 1.0) -> tuple[float, float] | None:
        """The virtual motion read off the iteration's drift, if it certifies that no
        admissible state exists (Farkas' lemma, the kinematic theorem), checked to a
        tolerance that scales with the problem.

        When equilibrium E and the joint laws K do not meet, the multiplier increment
        g = x_hat - z (per iteration) tends to the C-shortest vector from K to E, and
        C g = A^T y with block velocities y = (A K A^T)^-1 A g. Their joint deformations
        w = A^T y split per contact point into a part that follows the associative flow
        rule (w_N + f |w_T| <= 0: the joint opens by at least f times its slip; no slip
        where f is infinite) and a breach e (the excess w_N + f |w_T| > 0, and |w_T|
        where f is infinite). For every state X in E, y'b = w'X; the part that follows
        the flow rule does at most the dissipation D = sum_k t_k (-w_N - f |w_T|)_k +
        sum_j c_j |w_T|_j on a state within the joint laws (tensile strength t, cohesion
        c), and the breach at most ||e||_1 ||X||_inf. So an admissible state needs

            ||X||_inf >= (y'b - D) / ||e||_1 = X_req.

        The motion certifies inadmissibility when the net work y'b - D exceeds
        ``WORK_RTOL`` of sum |y_i b_i| (well above its round-off) and X_req exceeds
        ``CERT_FORCE`` x ``scale`` (``scale``: the largest force of the iteration's
        states, at least the loads): no admissible state has forces within 1e5 times
        those of the problem (beyond FORCE_WARN = 1e4 of the convex path, where a state
        is noted as ill-conditioned). Returned as (net work, X_req / scale), else None.

        A drift near a mechanism is polished first (at most ``POLISH`` steps): its joint
        deformations are mapped into the flow rule's cone and back to the nearest block
        motion, alternately; only the motion that passes the check counts, so polishing
        cannot certify a scene that has an admissible state.
        """
        if self.lu is None:
            return None
        y = self.lu.solve(self.As @ self.scatter(g))
        best = 0.0  # the best ratio ten steps ago, to stop a polish that stagnates
        for k in range(POLISH + 1):
            wv = self.gather(self.AsT @ y)
            if not float(np.abs(wv).max(initial=0.0)) > 0:
                return None
            breach, resist = laws.flow(wv)
            # the round-off of w = A^T y on top of the breach
            breach += ROUNDOFF * float(np.abs(wv).sum())
            work = float(y @ b) - resist
            if not work > WORK_RTOL * float(np.abs(y * b).sum() + abs(resist)):
                return None
            ratio = work / breach / max(scale, 1.0)
            if ratio >= CERT_FORCE:
                return work, ratio
            if k == POLISH:
                return None
            if k % 10 == 0:
                if ratio < 1.1 * best:
                    return None  # the polish stagnates: no mechanism nearby
                best = ratio
            # polish: w mapped into the flow rule's cone and back to the nearest block
            # motion (C metric)
            y = self.lu.solve(self.As @ (self.K * self.scatter(laws.to_cone(wv))))
        return None

    @staticmethod
    def _anderson(aa: dict[str, Any], z: np.ndarray, u: np.ndarray, zn: np.ndarray,
                  un: np.ndarray, memory: int) -> tuple[np.ndarray, np.ndarray]:
        """Anderson acceleration (type II) of the fixed-point map (z, u) -> (zn, un).

        With the last ``memory`` differences of the iterates s and of the residuals
        g = T(s) - s, the next iterate is s + g - (dS + dG) gamma, gamma the least-squares
        solution of dG gamma = g. Safeguards: when the residual more than doubles, or
        the correction (dS + dG) gamma exceeds ``AA_STEP`` times the residual, the memory
        is dropped and the plain step taken. ``memory = 0``: the plain iteration.
        """
        if memory <= 0:
            return zn, un
        s = np.concatenate([z.ravel(), u.ravel()])
        g = np.concatenate([zn.ravel(), un.ravel()]) - s
        gn = float(np.linalg.norm(g))
        S, G = aa["S"], aa["G"]
        if gn > 2.0 * aa["g"] and S:
            S.clear()
            G.clear()
            aa["restarts"] += 1
        aa["g"] = gn
        S.append(s)
        G.append(g)
        if len(S) > memory + 1:
            S.pop(0)
            G.pop(0)
        if len(S) < 2:
            return zn, un
        dS = np.diff(np.array(S), axis=0).T
        dG = np.diff(np.array(G), axis=0).T
        gamma = np.linalg.lstsq(dG, g, rcond=1e-10)[0]
        corr = (dS + dG) @ gamma
        if not np.all(np.isfinite(corr)) or np.linalg.norm(corr) > AA_STEP * gn:
            # an extrapolation far beyond the plain step (a drifting, infeasible run)
            S.clear()
            G.clear()
            return zn, un
        nxt = s + g - corr
        return nxt[:z.size].reshape(z.shape), nxt[z.size:].reshape(u.shape)

    # -- the iteration -----------------------------------------------------------------
    def run(self, laws: _Laws, load_factor: float, tol: float = TOL,
            max_iter: int = MAX_ITER, window: int = WINDOW, keep_history: bool = False,
            optimal: bool = True, rho: float = RHO, alpha: float = ALPHA,
            anderson: int | None = None) -> Run:
        """One run: plain, then an accelerated phase that can only prove admissibility,
        then the plain iteration resumed where it stopped.

        With ``anderson > 0``: the plain iteration first runs for ``PLAIN_FIRST``
        iterations, with all its verdicts (the inadmissible and stalled runs of a
        bisection are decided there). If it has not decided, the iteration starts again
        from X0 with Anderson acceleration for at most ``AA_BUDGET`` iterations and stops
        there only if it finds an admissible state (a certificate whatever the path to
        it: X in equilibrium, checked, and within the joint laws; with ``optimal`` also
        settled). The phase is abandoned early when, from ``AA_GIVE_UP`` iterations on,
        its best violation has not halved between k/2 and k, or when an admissible state
        has not settled within ``PLAIN_FIRST`` more iterations. Acceleration
        extrapolates the drift of a run whose sets do not meet, so otherwise the plain
        iteration is resumed from its own state with the rest of the budget and decides
        as without acceleration (an unsettled admissible state of the accelerated phase
        is still returned if the plain iteration ends without one). ``anderson = 0``: the
        plain iteration only; None: ``ANDERSON``.
        """
        if anderson is None:
            anderson = ANDERSON
        if anderson <= 0 or self.mechanism or max_iter <= PLAIN_FIRST:
            return self._iterate(laws, load_factor, tol, max_iter, window, keep_history,
                                 optimal, rho, alpha, 0, decide=True)
        first = self._iterate(laws, load_factor, tol, PLAIN_FIRST, window, keep_history,
                              optimal, rho, alpha, 0, decide=True, partial=True)
        if first.status:
            return first
        acc = self._iterate(laws, load_factor, tol, min(AA_BUDGET, max_iter - PLAIN_FIRST),
                            window, False, optimal, rho, alpha, anderson, decide=False)
        acc.iterations += first.iterations
        acc.time += first.time
        if acc.status == "admissible" and not acc.reason:
            acc.history = first.history + acc.history if keep_history else []
            return acc
        rest = self._iterate(laws, load_factor, tol, max_iter - acc.iterations + PLAIN_FIRST,
                             window, keep_history, optimal, rho, alpha, 0, decide=True,
                             resume=first.resume)
        if acc.status == "admissible" and rest.status != "admissible":
            # an admissible state (not yet the least-energy one) is still a certificate
            return acc
        rest.iterations += acc.iterations - PLAIN_FIRST
        rest.time += acc.time
        return rest

    def _iterate(self, laws: _Laws, load_factor: float, tol: float, max_iter: int,
                 window: int, keep_history: bool, optimal: bool, rho: float,
                 alpha: float, anderson: int, decide: bool, partial: bool = False,
                 resume: _Iterate | None = None) -> Run:
        """The (accelerated) distortion iteration from the elastic solution.

        See the module docstring. ``optimal=False`` stops at the first iterate that is
        admissible within ``tol`` (enough for a verdict); ``optimal=True`` goes on until
        the step and the dual residual are below ``max(tol, STATE_TOL)`` too, so that
        the state is the least-energy one. ``partial``: a run that reaches ``max_iter``
        undecided returns status "" and its state in ``resume``, from which a later call
        (``resume=``, ``max_iter`` counted from the start) goes on.
        """
        stol = max(tol, STATE_TOL)
        t0 = time.perf_counter()
        b = self.rhs(load_factor)
        v0 = self._elastic_start(b, t0)
        if isinstance(v0, Run):
            return v0
        viol = laws.violation(v0)
        status, reason = ("admissible" if viol <= tol else ""), ""
        it = resume if resume is not None else _Iterate(laws.project(v0), np.zeros_like(v0),
                                                        v0, rho, [viol])
        it.first_ok, it.aa = None, {"S": [], "G": [], "g": math.inf, "restarts": 0}
        while not status and it.k < max_iter:
            viol, du = self._iteration(it, laws, v0, alpha, anderson)
            if self._admissible_at(it, viol, b, tol) and \
                    (not optimal or (it.step <= stol and it.dual <= stol)):
                status = "admissible"
                break
            if anderson and self._acceleration_spent(it, window):
                break
            if it.k == it.next_adapt and not anderson:  # the accelerated phase keeps rho
                self._balance(it)
            if decide and it.k % window == 0 and it.k >= 2 * window:
                status, reason = self._gap_verdict(laws, it, viol, du, b, v0, tol)
        return self._ended(it, laws, b, status, reason, viol, max_iter, partial,
                           keep_history, t0)

    def _elastic_start(self, b: np.ndarray, t0: float) -> np.ndarray | Run:
        """The elastic solution's joint forces (gathered), or the run that ends before
        any iteration: a mechanism, or an elastic solution out of equilibrium."""
        n = self.P + self.m
        if self.mechanism:
            if self.loose_rows.any() and np.any(b[self.loose_rows] != 0):
                # a loaded block without joints: no equilibrium state at all
                return Run("inadmissible", np.full(n, np.nan), 0, math.inf, math.inf,
                           self.mechanism + ", and they carry loads: no equilibrium state",
                           time=time.perf_counter() - t0)
            return Run("failure", np.full(n, np.nan), 0, math.inf, math.inf, self.mechanism,
                       time=time.perf_counter() - t0)
        x0 = self.project_equilibrium(np.zeros(n), b)
        res0 = float(np.abs(self.As @ x0 - b).max(initial=0.0))
        if res0 > 1e-6 * max(1.0, float(np.abs(b).max(initial=0.0))):
            return Run("failure", x0, 0, math.inf, res0, "mechanism: the elastic solution "
                       "does not meet the equilibrium equations (A C^-1 A^T nearly singular)",
                       time=time.perf_counter() - t0)
        return self.gather(x0)

    def _iteration(self, it: _Iterate, laws: _Laws, v0: np.ndarray, alpha: float,
                   anderson: int) -> tuple[float, np.ndarray]:
        """One iteration of ``it`` (its step and dual residual recorded): the violation
        of the new state and the step of the scaled duals."""
        rho, z, u = it.rho, it.z, it.u
        # distortion delta = rho/(1+rho) (z - u - X0); its self-stress via the projector
        delta = self.scatter(rho / (1.0 + rho) * (z - u - v0))
        xs = self.project_equilibrium(delta, np.zeros(self.As.shape[0]))
        vn = v0 + self.gather(xs)
        vh = alpha * vn + (1.0 - alpha) * z
        zn = laws.project(vh + u)
        du = vh - zn
        it.dual = rho * float(np.abs(zn - z).max(initial=0.0))
        it.step = float(np.abs(vn - it.v).max(initial=0.0))
        it.z, it.u = self._anderson(it.aa, z, u, zn, u + du, anderson)
        it.v = vn
        viol = laws.violation(vn)
        it.k += 1
        it.hist.append(viol)
        return viol, du

    def _admissible_at(self, it: _Iterate, viol: float, b: np.ndarray, tol: float) -> bool:
        """Whether the state of ``it`` is admissible (within ``tol`` of the joint laws, in
        equilibrium), recorded as its last admissible state."""
        if viol <= tol and float(np.abs(self.As @ self.scatter(it.v) - b).max()) <= \
                1e-9 * (1.0 + float(np.abs(b).max(initial=0.0))):
            it.last_ok = it.v
            it.first_ok = it.k if it.first_ok is None else it.first_ok
            return True
        return False

    @staticmethod
    def _acceleration_spent(it: _Iterate, window: int) -> bool:
        """The accelerated phase ends: admissible but not settling (the plain iteration
        settles it), or its best violation has not halved since k/2 (no help from
        here)."""
        k, hist = it.k, it.hist
        if it.first_ok is not None and k - it.first_ok >= PLAIN_FIRST:
            return True
        return k % window == 0 and k >= AA_GIVE_UP and \
            min(hist[k // 2:]) > 0.5 * min(hist[:k // 2 + 1])

    @staticmethod
    def _balance(it: _Iterate) -> None:
        """Residual balancing of rho (the projector does not depend on rho: same
        metric), at the iterations ADAPT, 2 ADAPT, ... up to ADAPT_LAST."""
        prim = float(np.abs(it.v - it.z).max(initial=0.0))
        dual, rho = it.dual, it.rho
        if dual > 0 and prim > 0 and not 0.2 < prim / dual < 5.0:
            new = min(max(rho * math.sqrt(prim / dual), 1e-4), 1e4)
            it.u *= rho / new
            it.rho = new
            it.aa["S"].clear()
            it.aa["G"].clear()
        it.next_adapt = 2 * it.next_adapt if it.next_adapt < ADAPT_LAST else -1

    def _gap_verdict(self, laws: _Laws, it: _Iterate, viol: float, du: np.ndarray,
                     b: np.ndarray, v0: np.ndarray, tol: float) -> tuple[str, str]:
        """The verdict of a run that has not reached admissibility, with its reason:
        "inadmissible" where the violation tends to a positive limit and a mechanism
        certifies it, "undecided" where it stalls within GAP x tol, else none ("")."""
        k, v = it.k, it.v
        half = it.hist[k // 2]
        # the limit of the violation if it fell like 1/sqrt(k) (slower than the
        # iteration does when the sets meet): a positive limit is a gap
        limit = (SQRT2 * viol - half) / (SQRT2 - 1.0)
        scale = max(1.0, float(np.abs(v).max(initial=0.0)),
                    float(np.abs(v0).max(initial=0.0)))
        cert = (self.mechanism_of(laws, du, b, scale)
                if viol > GAP * tol and limit > 0.5 * viol else None)
        if cert is not None:
            return "inadmissible", (
                f"the violation tends to {limit:.3g} > 0 (reference-force "
                f"units; {half:.3g} at iteration {k // 2}, {viol:.3g} at {k}) "
                f"and the loads do net work {cert[0]:.3g} on a virtual motion "
                "whose breach of the flow rule leaves no admissible state "
                f"with forces below {cert[1]:.2g} times those of the "
                "iteration: equilibrium and joint laws do not meet")
        if viol <= GAP * tol and viol > STALL * half:
            return "undecided", (
                f"stalled: the violation stays at {viol:.3g}, within {GAP:g} "
                "x tol of admissibility: a limit state the method cannot "
                "decide")
        return "", ""

    def _ended(self, it: _Iterate, laws: _Laws, b: np.ndarray, status: str, reason: str,
               viol: float, max_iter: int, partial: bool, keep_history: bool,
               t0: float) -> Run:
        """The run of ``it`` as it ended: undecided at its budget (with its state to
        resume where ``partial``), or admissible at its last admissible state where it
        did not settle."""
        v, k, hist = it.v, it.k, it.hist
        x = self.scatter(v)
        residual = float(np.abs(self.As @ x - b).max(initial=0.0))
        if partial and not status:
            return Run("", x, k, viol, residual, "", list(hist) if keep_history else [],
                       time.perf_counter() - t0, resume=it)
        if not status and it.last_ok is not None:
            status, v = "admissible", it.last_ok
            x = self.scatter(v)
            viol = laws.violation(v)
            residual = float(np.abs(self.As @ x - b).max(initial=0.0))
            reason = (f"admissible; the iteration budget ({max_iter}) ended before the "
                      f"state settled (last step {it.step:.2g}, dual residual "
                      f"{it.dual:.2g})")
        if not status:
            status = "undecided"
            reason = (f"no convergence within the iteration budget ({max_iter} iterations, "
                      f"violation {viol:.3g})")
        return Run(status, x, k, viol, residual, reason, hist if keep_history else [],
                   time.perf_counter() - t0)


def _clip_root(alpha: np.ndarray, beta: np.ndarray, w: np.ndarray, y: np.ndarray,
               p: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Root theta of g = alpha - beta theta - w sum_i max(y_i + p_i theta, -t_i), i = 1, 2.

    g is continuous, piecewise linear and decreasing (beta >= 0, w > 0, p > 0), with
    breakpoints (-t_i - y_i) / p_i; slopes -beta below both, -beta - w p_i between them,
    -beta - w (p_1 + p_2) above. The root is found on its segment. Where g has no root
    below the first breakpoint with beta = 0, the breakpoint is returned.
    """
    br = (-t - y) / p
    first = np.argmin(br, axis=1)
    idx = np.arange(len(alpha))
    blo, bhi = br[idx, first], br[idx, 1 - first]

    def g(th):
        return alpha - beta * th - w * np.maximum(y + p * th[:, None], -t).sum(axis=1)

    g_lo, g_hi = g(blo), g(bhi)
    s1 = -beta - w * p[idx, first]
    s2 = -beta - w * p.sum(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        below = np.where(beta > 0, blo + g_lo / np.where(beta > 0, beta, 1.0), blo)
        mid = blo - g_lo / s1
        above = bhi - g_hi / s2
    return np.where(g_lo <= 0, below, np.where(g_hi <= 0, mid, above))


class _Laws:
    """The joint laws of one run: rows G v <= h per joint (v = N1, N2, T) and P_K.

    Rows: -N_k <= t_k (no tension beyond the tensile capacity t_k), +-T - f (N1 + N2)
    <= c (friction with cohesion capacity c); f = inf drops the friction rows.
    """

    def __init__(self, f: np.ndarray, t: np.ndarray, c: np.ndarray, cflex: np.ndarray):
        m = len(f)
        fin = np.isfinite(f)
        ff = np.where(fin, f, 0.0)
        G = np.zeros((m, 4, 3))
        G[:, 0, 0] = -1.0
        G[:, 1, 1] = -1.0
        G[:, 2] = np.stack([-ff, -ff, np.ones(m)], axis=1)
        G[:, 3] = np.stack([-ff, -ff, -np.ones(m)], axis=1)
        G[~fin, 2:] = 0.0
        h = np.stack([t[0::2], t[1::2], c, c], axis=1)
        h[~fin, 2:] = 0.0
        self.f = f
        self.fin, self.ff = fin, ff
        self.G, self.h, self.active = G, h, np.stack([np.ones(m, bool)] * 2 + [fin] * 2, 1)
        self.cw = cflex  # the C metric: weights C on the joint's (N1, N2, T)

    def flow(self, wv: np.ndarray) -> tuple[float, float]:
        """(breach of the flow rule, resistance sigma_K(w)) of joint deformations ``wv``
        (per joint w_N1, w_N2, w_T) under the associative flow rule: per point
        w_N + f |w_T| <= 0 (opening by at least f times the slip; no slip where f is
        infinite), resisted by the tensile strengths and the cohesion. The breach is the
        l1 norm of the part of w outside the rule's cone (the excess w_N + f |w_T| > 0,
        and |w_T| where f is infinite), which bounds its work on a state by
        breach x ||X||_inf."""
        fin = np.isfinite(self.f)
        aw = np.abs(wv[:, 2])
        s = wv[:, :2] + np.where(fin, self.f, 0.0)[:, None] * aw[:, None]
        breach = float(np.maximum(s, 0.0).sum() + np.where(fin, 0.0, aw).sum())
        resist = float(np.sum(self.h[:, :2] * np.maximum(-s, 0.0))
                       + np.sum(np.where(fin, self.h[:, 2], 0.0) * aw))
        return breach, resist

    def to_cone(self, wv: np.ndarray) -> np.ndarray:
        """Joint deformations mapped into the flow rule's cone: the slip dropped where f
        is infinite, the opening raised to f times the slip where it falls short."""
        out = wv.copy()
        out[:, 2] = np.where(self.fin, wv[:, 2], 0.0)
        out[:, :2] = np.minimum(wv[:, :2], -(self.ff * np.abs(out[:, 2]))[:, None])
        return out

    def thresholds(self, v: np.ndarray) -> np.ndarray:
        """Per joint of the forces ``v`` (N1, N2, T): the friction threshold
        f (N1 + N2) + c (0 where f is infinite: no friction rows)."""
        return self.ff * (v[:, 0] + v[:, 1]) + self.h[:, 2]

    def rows(self, v: np.ndarray) -> np.ndarray:
        G = self.G
        r = G[..., 0] * v[:, None, 0] + G[..., 1] * v[:, None, 1] + G[..., 2] * v[:, None, 2]
        return np.where(self.active, r - self.h, -np.inf)

    def violation(self, v: np.ndarray) -> float:
        return float(np.maximum(self.rows(v), 0.0).max(initial=0.0))

    def project(self, y: np.ndarray) -> np.ndarray:
        """Exact C-metric projection of every joint's (N1, N2, T) onto its law, in closed form.

        With weights (a1, a2, a_T) = C and the friction row's multiplier mu >= 0 the KKT
        conditions give N_i = max(y_i + f mu / a_i, -t_i), |T| = |y_T| - mu / a_T, and mu
        is the root of the decreasing piecewise-linear |T| - f (N1 + N2) - c (or 0 when
        that is <= 0 at mu = 0). If this makes |T| < 0 the projection is the cone's apex
        edge T = 0, N1 + N2 = -c / f, with N_i = max(y_i + lam / a_i, -t_i).
        """
        a = self.cw[:, :2]
        at = self.cw[:, 2]
        t = self.h[:, :2]
        c = self.h[:, 2]
        f = self.ff
        n = np.maximum(y[:, :2], -t)
        tabs = np.abs(y[:, 2])
        sg = np.where(y[:, 2] < 0, -1.0, 1.0)
        phi = tabs - f * n.sum(axis=1) - c
        need = self.fin & (phi > 0)
        out = np.column_stack([n, y[:, 2]])
        if not need.any():
            return out
        k = np.flatnonzero(need)
        fk, ak = f[k], a[k]
        pos = fk > 0
        mu = (tabs[k] - c[k]) * at[k]  # f = 0: the shear alone is clipped to c
        if pos.any():
            kp = k[pos]
            mu[pos] = _clip_root(tabs[kp] - c[kp], 1.0 / at[kp], fk[pos], y[kp, :2],
                                 fk[pos, None] / ak[pos], t[kp])
        mu = np.maximum(mu, 0.0)
        nk = np.maximum(y[k, :2] + fk[:, None] * mu[:, None] / ak, -t[k])
        tk = tabs[k] - mu / at[k]
        apex = tk < 0
        if apex.any():
            j = np.flatnonzero(apex)
            s0 = -c[k][j] / np.where(fk[j] > 0, fk[j], 1.0)
            lam = _clip_root(s0, np.zeros(j.size), np.ones(j.size), y[k[j], :2],
                             1.0 / ak[j], t[k[j]])
            nk[j] = np.maximum(y[k[j], :2] + lam[:, None] / ak[j], -t[k[j]])
            tk[j] = 0.0
        out[k, :2] = nk
        out[k, 2] = sg[k] * tk
        return out


class _NonAssocLaws(_Laws):
    """Joint laws where the marked joints slide without dilatancy (the seed's links).

    The seed's joint has separate links: normal links that carry no tension (beyond a
    tensile strength) and shear links capped at f times the normal force. Its
    projection (Eq. 4: "nullify all tensile forces in the links orthogonal to the joints
    and ... lower, until equal to their threshold value, all the shear forces") is, per
    marked joint, N_i <- max(N_i, -t_i), then T <- clip(T, +-(f (N_1 + N_2) + c)): the
    shear is capped without changing the normal forces. This is not the metric
    projection onto the Coulomb set (that one raises N: dilatancy); a fixed point of
    the iteration with it is a state whose plastic distortions are openings where N is
    at its tensile limit and slips without dilatancy where |T| is at its threshold.
    Unmarked joints keep the associative projection of :class:`_Laws`.
    """

    def __init__(self, f: np.ndarray, t: np.ndarray, c: np.ndarray, cflex: np.ndarray,
                 marked: np.ndarray):
        super().__init__(f, t, c, cflex)
        self.marked = marked
        #: the normal-force sums of the last projection (the dissipation of a slip)
        self.nsum = np.zeros(len(f))

    def project(self, y: np.ndarray) -> np.ndarray:
        out = super().project(y)
        k = self.marked
        n = np.maximum(y[k, :2], -self.h[k, :2])
        cap = np.where(self.fin[k], np.maximum(self.ff[k] * n.sum(axis=1) + self.h[k, 2],
                                               0.0), np.inf)
        out[k, :2] = n
        out[k, 2] = np.clip(y[k, 2], -cap, cap)
        self.nsum = out[:, 0] + out[:, 1]
        return out

    def flow(self, wv: np.ndarray) -> tuple[float, float]:
        """The flow rule without dilatancy on the marked joints: no closing (w_N <= 0
        per point) and any slip, resisted by the shear threshold at the current normal
        forces, (f (N_1 + N_2) + c) |w_T|; the associative rule on the others."""
        breach, resist = super().flow(np.where(self.marked[:, None], 0.0, wv))
        k = self.marked
        w = wv[k]
        aw = np.abs(w[:, 2])
        fin = self.fin[k]
        breach += float(np.maximum(w[:, :2], 0.0).sum())
        thr = np.maximum(self.ff[k] * self.nsum[k] + self.h[k, 2], 0.0)
        resist += float(np.sum(self.h[k, :2] * np.maximum(-w[:, :2], 0.0))
                        + np.sum(np.where(fin, thr * aw, 0.0)))
        breach += float(np.where(fin, 0.0, aw).sum())
        return breach, resist

    def to_cone(self, wv: np.ndarray) -> np.ndarray:
        """The associative map on the unmarked joints; on the marked ones no closing and
        no slip where f is infinite."""
        out = super().to_cone(wv)
        k = self.marked
        out[k, 2] = np.where(self.fin[k], wv[k, 2], 0.0)
        out[k, :2] = np.minimum(wv[k, :2], 0.0)
        return out
