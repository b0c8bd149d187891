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
  tol, and y is a collapse mechanism: the loads do positive work on it beyond what the
  links resist, and its joint deformations follow the associative flow rule to within
  ``FLOW_TOL`` of the largest (Farkas' certificate, see :meth:`mechanism_of`). Both
  tests together: a feasible run can pass through plateaus of the violation, but its
  drift is then no mechanism.
* ``undecided``: near f* (or lambda*) the gap between E and K shrinks to zero and the
  iteration needs of the order of 1/gap iterations to see it. A run that stalls with a
  violation below ``GAP`` x tol (less than 1% decrease between k/2 and k) is "stalled";
  a run that uses its budget is "no convergence within the iteration budget". Both are
  reported as undecided, never as a number.
* ``failure``: A K A^T singular or ill-conditioned: a mechanism of the bilateral
  linked structure (a block motion that stretches no link).

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

import itertools
import math
import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from ..equilibrium import EquilibriumSystem, assemble
from ..errors import InputError
from ..results import CheckResult, FrictionResult, LoadResult
from ..scene.model import Scene

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
#: relative breach of the flow rule accepted in a mechanism certifying inadmissibility
FLOW_TOL = 0.02
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
#: a bisection stopped by an undecided trial with a bracket wider than BRACKET_RTOL
#: relative plus BRACKET_ATOL gives no number (the floor: f* or lambda* = 0)
BRACKET_RTOL = 1e-3
BRACKET_ATOL = 1e-6

_SUBSETS = [s for k in range(4) for s in itertools.combinations(range(4), k)]


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
    resume: dict[str, Any] | None = field(default=None, repr=False)


class DistortionSolver:
    """The factorised linked structure of one scene (2D, one shear link per joint)."""

    def __init__(self, scene: Scene, system: EquilibriumSystem | None = None):
        from ..problems.formulation import Scaling, flexibility

        if scene.dimension != 2:
            raise InputError("the distortion method is not supported for 3D scenes; use "
                             "method='clarabel' (the convex path)",
                             scene.source)
        self.scene = scene
        self.system = system if system is not None else assemble(scene)
        sysm = self.system
        c = sysm.contacts
        if np.any(np.diff(c.joint_start) != 2):
            raise InputError("the distortion method needs two contact points per joint",
                             scene.source)
        self.scaling = Scaling.of(sysm)
        self.C = flexibility(sysm)
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
            try:
                lu = spla.splu(M)
                d = np.abs(lu.U.diagonal())
                if d.size and (d.min() <= RCOND_MIN * d.max() or not np.all(np.isfinite(d))):
                    raise RuntimeError("ill-conditioned")
                self.lu = lu
            except RuntimeError:
                free = sysm.free_blocks
                ids = [scene.blocks[b].id for b in free]
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
             cohesion: np.ndarray | None = None) -> _Laws:
        """Per-joint rows G v <= h (v = N1, N2, T) and the candidate maps of P_K."""
        c = self.system.contacts
        F = self.scaling.force
        a = c.point_areas
        ts = c.tensile_strength if tension is None else tension
        co = c.cohesion if cohesion is None else cohesion
        return _Laws(f_joint, ts[c.point_joint] * a / F, co * c.areas / F,
                     np.array([self.C[self.i0], self.C[self.i0 + 1], self.C[self.it]]).T)

    def gather(self, x: np.ndarray) -> np.ndarray:
        return np.stack([x[self.i0], x[self.i0 + 1], x[self.it]], axis=1)

    def scatter(self, v: np.ndarray) -> np.ndarray:
        x = np.empty(self.P + self.m)
        x[self.i0], x[self.i0 + 1], x[self.it] = v[:, 0], v[:, 1], v[:, 2]
        return x

    def mechanism_of(self, laws: _Laws, g: np.ndarray, b: np.ndarray,
                     flow_tol: float = FLOW_TOL) -> tuple[float, float] | None:
        """The virtual motion read off the iteration's drift, if it is a collapse mechanism.

        When equilibrium E and the joint laws K do not meet, the multiplier increment
        g = x_hat - z (per iteration) tends to the C-shortest vector from K to E, and
        C g = A^T y with block velocities y = (A K A^T)^-1 A g: a motion whose joint
        deformations w = A^T y satisfy the associative flow rule (per point
        w_N + f |w_T| <= 0: the joint opens by at least f times its slip; no slip where
        f is infinite) and on which the loads do positive work beyond what the links can
        resist, y'b - sigma_K(w) > 0, with sigma_K(w) = sum_k t_k (-w_N - f |w_T|)_k
        + sum_j c_j |w_T|_j (tensile strength t, cohesion c). That is Farkas' certificate
        (the kinematic theorem). Returned as (work, breach) when the work is positive and
        the flow rule holds to ``flow_tol`` of the largest deformation, else None.
        """
        if self.lu is None:
            return None
        y = self.lu.solve(self.As @ self.scatter(g))
        wv = self.gather(self.AsT @ y)
        scale = float(np.abs(wv).max(initial=0.0))
        if not scale > 0:
            return None
        fin = np.isfinite(laws.f)
        aw = np.abs(wv[:, 2])
        s = wv[:, :2] + np.where(fin, laws.f, 0.0)[:, None] * aw[:, None]
        breach = max(float(np.maximum(s, 0.0).max(initial=0.0)),
                     float(np.where(fin, 0.0, aw).max(initial=0.0))) / scale
        resist = float(np.sum(laws.h[:, :2] * np.maximum(-s, 0.0))
                       + np.sum(np.where(fin, laws.h[:, 2], 0.0) * aw))
        work = float(y @ b) - resist
        if work <= 0 or breach > flow_tol:
            return None
        return work, breach

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
                 resume: dict[str, Any] | None = None) -> Run:
        """The (accelerated) distortion iteration from the elastic solution.

        See the module docstring. ``optimal=False`` stops at the first iterate that is
        admissible within ``tol`` (enough for a verdict); ``optimal=True`` goes on until
        the step and the dual residual are below ``max(tol, STATE_TOL)`` too, so that
        the state is the least-energy one. ``partial``: a run that reaches ``max_iter``
        undecided returns status "" and its state in ``resume``, from which a later call
        (``resume=``, ``max_iter`` counted from the start) goes on.
        """
        stol = max(tol, STATE_TOL)
        last_ok = None
        t0 = time.perf_counter()
        n = self.P + self.m
        b = self.rhs(load_factor)
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
        v0 = self.gather(x0)
        v = v0
        z = laws.project(v0)
        u = np.zeros_like(v0)
        viol = laws.violation(v)
        hist = [viol]
        status, reason, k = "", "", 0
        if viol <= tol:
            status = "admissible"
        next_adapt = ADAPT
        step = dual = math.inf
        first_ok: int | None = None
        if resume is not None:
            z, u, v, rho, hist = resume["z"], resume["u"], resume["v"], resume["rho"], \
                resume["hist"]
            k, next_adapt, last_ok = resume["k"], resume["next_adapt"], resume["last_ok"]
            step, dual = resume["step"], resume["dual"]
        aa: dict[str, Any] = {"S": [], "G": [], "g": math.inf, "restarts": 0}
        while not status and k < max_iter:
            # distortion delta = rho/(1+rho) (z - u - X0); its self-stress via the projector
            delta = self.scatter(rho / (1.0 + rho) * (z - u - v0))
            xs = self.project_equilibrium(delta, np.zeros(self.As.shape[0]))
            vn = v0 + self.gather(xs)
            vh = alpha * vn + (1.0 - alpha) * z
            zn = laws.project(vh + u)
            du = vh - zn
            dual = rho * float(np.abs(zn - z).max(initial=0.0))
            step = float(np.abs(vn - v).max(initial=0.0))
            z, u = self._anderson(aa, z, u, zn, u + du, anderson)
            v = vn
            viol = laws.violation(v)
            k += 1
            hist.append(viol)
            if viol <= tol and float(np.abs(self.As @ self.scatter(v) - b).max()) <= \
                    1e-9 * (1.0 + float(np.abs(b).max(initial=0.0))):
                last_ok = v
                first_ok = k if first_ok is None else first_ok
                if not optimal or (step <= stol and dual <= stol):
                    status = "admissible"
                    break
            if anderson and first_ok is not None and k - first_ok >= PLAIN_FIRST:
                break  # admissible but not settling: the plain iteration settles it
            if anderson and k % window == 0 and k >= AA_GIVE_UP and \
                    min(hist[k // 2:]) > 0.5 * min(hist[:k // 2 + 1]):
                break  # the best violation has not halved since k/2: no help from here
            if k == next_adapt and not anderson:  # the accelerated phase keeps rho
                # residual balancing: the projector does not depend on rho (same metric)
                prim = float(np.abs(v - z).max(initial=0.0))
                if dual > 0 and prim > 0 and not 0.2 < prim / dual < 5.0:
                    new = min(max(rho * math.sqrt(prim / dual), 1e-4), 1e4)
                    u *= rho / new
                    rho = new
                    aa["S"].clear()
                    aa["G"].clear()
                next_adapt = 2 * next_adapt if next_adapt < ADAPT_LAST else -1
            if decide and k % window == 0 and k >= 2 * window:
                half = hist[k // 2]
                # the limit of the violation if it fell like 1/sqrt(k) (slower than the
                # iteration does when the sets meet): a positive limit is a gap
                limit = (SQRT2 * viol - half) / (SQRT2 - 1.0)
                cert = (self.mechanism_of(laws, du, b)
                        if viol > GAP * tol and limit > 0.5 * viol else None)
                if cert is not None:
                    status = "inadmissible"
                    reason = (f"the violation tends to {limit:.3g} > 0 (reference-force "
                              f"units; {half:.3g} at iteration {k // 2}, {viol:.3g} at {k}) "
                              f"and the loads do work {cert[0]:.3g} on a virtual motion "
                              f"that follows the flow rule to {cert[1]:.2g} of its largest "
                              "joint deformation: equilibrium and joint laws do not meet")
                elif viol <= GAP * tol and viol > STALL * half:
                    status = "undecided"
                    reason = (f"stalled: the violation stays at {viol:.3g}, within {GAP:g} "
                              "x tol of admissibility: a limit state the method cannot "
                              "decide")
        x = self.scatter(v)
        residual = float(np.abs(self.As @ x - b).max(initial=0.0))
        if partial and not status:
            state = {"z": z, "u": u, "v": v, "rho": rho, "hist": hist, "k": k,
                     "next_adapt": next_adapt, "last_ok": last_ok, "step": step,
                     "dual": dual}
            return Run("", x, k, viol, residual, "", list(hist) if keep_history else [],
                       time.perf_counter() - t0, resume=state)
        if not status and last_ok is not None:
            status, v = "admissible", last_ok
            x = self.scatter(v)
            viol = laws.violation(v)
            residual = float(np.abs(self.As @ x - b).max(initial=0.0))
            reason = (f"admissible; the iteration budget ({max_iter}) ended before the "
                      f"state settled (last step {step:.2g}, dual residual {dual:.2g})")
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

    def project_enumerated(self, y: np.ndarray) -> np.ndarray:
        """The same projection by enumerating the 15 active sets (reference for tests)."""
        m = len(y)
        winv = 1.0 / self.cw
        best = np.full((m, 3), np.nan)
        dist = np.full(m, np.inf)
        for S in _SUBSETS:
            S = list(S)
            V = y.copy()
            if S:
                GS, hS = self.G[:, S, :], self.h[:, S]
                Q = winv[:, :, None] * np.swapaxes(GS, 1, 2)
                Q = Q @ np.linalg.pinv(GS @ Q)
                V = y - np.einsum("mik,mk->mi", Q, np.einsum("mkj,mj->mk", GS, y) - hS)
            ok = np.all(self.active[:, S], axis=1) & np.all(
                self.rows(V) <= 1e-10 * (1.0 + np.abs(y).max(axis=1))[:, None], axis=1)
            d = np.where(ok, np.sum((V - y) ** 2 * self.cw, axis=1), np.inf)
            take = d < dist
            best[take], dist[take] = V[take], d[take]
        return best


# -- analyses ------------------------------------------------------------------------------
class _Work:
    def __init__(self, scene: Scene):
        self.solver = DistortionSolver(scene)
        self.runs = 0
        self.iterations = 0
        self.time = 0.0
        self.notes: list[str] = []

    @property
    def uniform(self) -> np.ndarray:
        return np.isnan(self.solver.system.contacts.override_friction)

    def f_joint(self, f: float) -> np.ndarray:
        o = self.solver.system.contacts.override_friction
        return np.where(np.isnan(o), f, o)

    def run(self, f: float, lam: float, **kw: Any) -> Run:
        r = self.solver.run(self.solver.laws(self.f_joint(f)), lam, **kw)
        self.runs += 1
        self.iterations += r.iterations
        self.time += r.time
        return r

    def common(self, analysis: str, status: str, friction: Any, lam: float | None) -> dict:
        s = self.solver.scene
        notes = list(self.notes)
        return dict(analysis=analysis, status=status, friction=friction, load_factor=lam,
                    contacts=self.solver.system.contacts, solver="distortion",
                    n_solves=self.runs, solve_time=self.time, iterations=self.iterations,
                    units=(s.length_unit, s.force_unit), notes=tuple(notes))

    def state(self, r: Run):
        from ..problems.analysis import force_state

        return force_state(self.solver.system, r.x * self.solver.scaling.force,
                           "impressed distortions")

    def at_threshold(self, r: Run, f: float, rel: float = 1e-5) -> tuple[int, ...]:
        """Loaded joints whose shear is at the friction threshold (within ``rel``)."""
        fj = self.f_joint(f)
        laws = self.solver.laws(fj)
        v = self.solver.gather(r.x)
        fin = np.isfinite(fj)
        thr = np.where(fin, np.abs(np.where(fin, fj, 0.0) * (v[:, 0] + v[:, 1])
                                   + laws.h[:, 2]), 0.0)
        gap = laws.rows(v)[:, 2:].max(axis=1)
        big = float(np.abs(v).max(initial=0.0))
        hit = fin & (thr > 1e-6 * big) & (gap >= -rel * thr)
        return tuple(int(j) for j in np.flatnonzero(hit))

    def describe(self, r: Run) -> None:
        F = self.solver.scaling.force
        self.notes.append(f"{r.iterations} iterations, equilibrium residual "
                          f"{r.residual * F:.3g}, joint-law violation {r.violation * F:.3g}")
        if r.reason:
            self.notes.append(r.reason)


def _label(f: float) -> Any:
    from ..problems.analysis import friction_label

    return friction_label(f)


def check_distortion(scene: Scene, f: float, load_factor: float, state: bool = True,
                     tol: float = TOL, max_iter: int = MAX_ITER) -> CheckResult:
    """Admissibility at friction ``f`` and load factor by the distortion iteration.

    Status "admissible", "inadmissible", "undecided" (a limit state the iteration cannot
    resolve within its budget) or "failure" (mechanism, budget); the reason and the
    final residuals (force units) are in ``notes``. ``violation`` is the joint-law
    violation of the last iterate (an upper bound of the smallest one).
    """
    w = _Work(scene)
    r = w.run(f, load_factor, tol=tol, max_iter=max_iter, optimal=state)
    w.describe(r)
    ok = r.status == "admissible"
    st = w.state(r) if (ok and state) else None
    viol = 0.0 if ok else r.violation * w.solver.scaling.force
    return CheckResult(**w.common("check", r.status, _label(f), load_factor), state=st,
                       admissible=ok, violation=viol)


def _bisect(decide, bad: float, good: float, rtol: float):
    """Shrink the bracket until |good - bad| <= rtol max(|good|, |bad|).

    ``bad`` is not admissible, ``good`` is. ``decide(x)`` returns (True | False | None,
    run); an undecided trial (None) stops the bisection and leaves the bracket as it is.
    """
    last = None
    for _ in range(200):
        if abs(good - bad) <= rtol * max(abs(good), abs(bad), 1e-300):
            break
        mid = 0.5 * (bad + good)
        verdict, run = decide(mid)
        if verdict is None:
            return bad, good, last, mid
        if verdict:
            good, last = mid, run
        else:
            bad = mid
    return bad, good, last, None


def min_friction_distortion(scene: Scene, load_factor: float = 1.0, state: bool = True,
                            rtol: float = 1e-6, tol: float = TOL) -> FrictionResult:
    """Smallest uniform f admitting equilibrium, by bisection on the iteration's verdict.

    f = infinite first (if not admissible: status "unstable"), then f = 0, then doubling
    from 1 to bracket f*, then bisection to ``rtol`` (at least 1e-9: the verdict is only
    as sharp as the violation tolerance). An undecided trial while doubling does not
    raise the lower end. An undecided trial ends the bisection: f* is then the upper
    (certified admissible) end of the bracket, the bracket is in ``lower``/``upper`` and
    the notes; if it is wider than ``BRACKET_RTOL`` relative (plus ``BRACKET_ATOL``), the
    status is "undecided" and no f* is given. Undecided at f = infinite: status "undecided".
    """
    rtol = max(rtol, 1e-9)
    w = _Work(scene)
    if w.solver.m and not w.uniform.any():
        raise InputError("every joint has its own friction override: there is no uniform "
                         "friction to minimise", scene.source)
    lf = float(load_factor)

    def decide(f: float):
        r = w.run(f, lf, tol=tol, optimal=False)
        if r.status == "failure":
            w.describe(r)
            return "failure", r
        return {"admissible": True, "inadmissible": False}.get(r.status), r

    v_inf, r_inf = decide(math.inf)
    if v_inf is not True:
        if v_inf == "failure" or v_inf is None:
            status = "failure" if v_inf == "failure" else "undecided"
            if v_inf is None:
                w.describe(r_inf)
            return FrictionResult(**w.common("min_friction", status, None, lf))
        w.describe(r_inf)
        return FrictionResult(**w.common("min_friction", "unstable", None, lf))
    v0, r0 = decide(0.0)
    if v0 is True:
        lo, hi, best = 0.0, 0.0, r0
    else:
        lo, hi, best = 0.0, 1.0, None
        while True:
            v, r = decide(hi)
            if v == "failure":
                return FrictionResult(**w.common("min_friction", "failure", None, lf))
            if v is True:
                best = r
                break
            if v is False:
                lo = hi
            else:
                w.notes.append(f"the iteration could not decide at f = {hi:.9g}")
            hi = 2 * hi
            if hi > 1e8:
                if lo < hi / 2:  # some trial was undecided: nothing is certified
                    w.notes.append(f"no finite friction up to 1e8 is certified admissible; "
                                   f"f = {lo:.9g} is not admissible")
                    return FrictionResult(**w.common("min_friction", "undecided", None, lf))
                w.notes.append("no finite friction up to 1e8 is admissible")
                return FrictionResult(**w.common("min_friction", "unstable", None, lf))

        def dec2(f):
            v, r = decide(f)
            return (None if v == "failure" else v), r

        lo, hi, last, und = _bisect(dec2, lo, hi, rtol)
        best = last or best
        if und is not None:
            w.notes.append(f"the iteration could not decide at f = {und:.9g}: f* is "
                           f"bracketed in [{lo:.9g}, {hi:.9g}]")
            if hi - lo > BRACKET_RTOL * hi + BRACKET_ATOL:
                w.notes.append(f"bracket wider than {BRACKET_RTOL:g} relative: undecided")
                return FrictionResult(**w.common("min_friction", "undecided", None, lf),
                                      lower=lo, upper=hi)
    fstar = hi
    final = w.run(fstar, lf, tol=tol) if state else best
    w.describe(final)
    gov = w.at_threshold(final, fstar) if fstar > 0 else ()
    gov = tuple(j for j in gov if w.uniform[j])
    st = w.state(final) if (state and final.status == "admissible") else None
    return FrictionResult(**w.common("min_friction", "stable", fstar, lf), state=st,
                          governing=gov, friction_factor=fstar,
                          friction_angle_deg=math.degrees(math.atan(fstar)), lower=lo,
                          upper=hi)


def max_load_distortion(scene: Scene, f: float, state: bool = True, rtol: float = 1e-6,
                        tol: float = TOL, unbounded_at: float = 1e6) -> LoadResult:
    """Largest live-load multiplier by bisection on lambda over admissibility.

    lambda = 0 must be admissible (else "unstable"); lambda is doubled from 1 until
    inadmissible ("unbounded" if still admissible at ``unbounded_at``), then bisected to
    ``rtol``. lambda* is the lower (certified admissible) end of the bracket. Where the
    iteration cannot decide the status says so, with the reason in the notes and no
    number: "undecided" at lambda = 0, while doubling (no inadmissible upper end), or
    when an undecided bisection trial leaves a bracket wider than ``BRACKET_RTOL``
    relative plus ``BRACKET_ATOL`` (a narrower one is reported in the notes). No
    collapse mechanism is returned (the iteration has no dual variables); ``governing``
    lists the joints at their friction threshold at lambda*.
    """
    w = _Work(scene)
    label = _label(f)

    def decide(lam: float):
        r = w.run(f, lam, tol=tol, optimal=False)
        if r.status == "failure":
            w.describe(r)
        return {"admissible": True, "inadmissible": False}.get(r.status), r

    v0, r0 = decide(0.0)
    if r0.status == "failure":
        return LoadResult(**w.common("max_load_multiplier", "failure", label, None))
    if v0 is not True:
        w.describe(r0)
        status = "undecided" if v0 is None else "unstable"
        return LoadResult(**w.common("max_load_multiplier", status, label, None))
    lo, hi, best = 0.0, 1.0, r0
    while True:
        v, r = decide(hi)
        if r.status == "failure":
            return LoadResult(**w.common("max_load_multiplier", "failure", label, None))
        if v is None:
            # no inadmissible upper end: lambda* is not bracketed
            w.describe(r)
            w.notes.append(f"the iteration could not decide at lambda = {hi:.9g}; "
                           f"lambda = {lo:.9g} is admissible, no upper bound is certified")
            return LoadResult(**w.common("max_load_multiplier", "undecided", label, None))
        if v is False:
            break
        lo, best = hi, r
        hi *= 2
        if hi > unbounded_at:
            return LoadResult(**w.common("max_load_multiplier", "unbounded", label, None))
    # admissible at lo, not at hi: reuse _bisect with the verdict reversed
    hi, lo, last, und = _bisect(decide, hi, lo, rtol)
    lam = lo
    if und is not None:
        w.notes.append(f"the iteration could not decide at lambda = {und:.9g}: lambda* is "
                       f"bracketed in [{lo:.9g}, {hi:.9g}]")
        if hi - lo > BRACKET_RTOL * hi + BRACKET_ATOL:
            w.notes.append(f"bracket wider than {BRACKET_RTOL:g} relative: undecided")
            return LoadResult(**w.common("max_load_multiplier", "undecided", label, None))
    final = w.run(f, lam, tol=tol) if state else (last or best)
    w.describe(final)
    gov = w.at_threshold(final, f) if math.isfinite(f) else ()
    st = w.state(final) if (state and final.status == "admissible") else None
    return LoadResult(**w.common("max_load_multiplier", "collapse", label, lam), state=st,
                      governing=gov, load_multiplier=lam)


# -- the load path ----------------------------------------------------------------------------
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
    to the last step), "undecided" or "failure" (reason in ``notes``)."""

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
        from ..results import _friction_json

        return {"status": self.status, "sliding": self.sliding,
                "friction": _friction_json(self.friction), "collapse_load": self.collapse_load,
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
    from ..problems.analysis import resolve_friction

    if method != "distortion":
        raise InputError(f'load_path supports method="distortion" only, got {method!r}')
    if sliding not in ("plastic", "coulomb"):
        raise InputError(f'sliding must be "plastic" or "coulomb", got {sliding!r}')
    if steps < 1 or not (max_load > 0):
        raise InputError("load_path needs steps >= 1 and max_load > 0")
    if not scene.has_live_load:
        raise InputError("the scene has no live load: there is nothing to increase",
                         scene.source)
    f = resolve_friction(scene, friction)
    w = _Work(scene)
    ds = w.solver
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
        r = ds.run(ds.laws(fj, tension, cohesion), lam, tol=tol)
        w.runs += 1
        w.iterations += r.iterations
        w.time += r.time
        return r

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
        for _ in range(refine):
            mid = 0.5 * (a + b)
            r = solve_at(mid)
            if r.status == "undecided":
                break
            if pred(r):
                b = mid
            else:
                a = mid
        return b

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
        status = "collapse"
        collapse = 0.0
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
                a, b = prev, lam
                for _ in range(refine):
                    mid = 0.5 * (a + b)
                    q = solve_at(mid)
                    if q.status == "undecided":
                        break
                    if ok(q):
                        a, last = mid, q
                    else:
                        b = mid
                lam_c = a
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
    return PathResult(status, sliding, _label(f), tuple(out_steps), tuple(events), collapse,
                      w.runs, w.iterations, w.time, tuple(w.notes))
