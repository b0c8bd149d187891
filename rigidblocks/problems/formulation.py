"""The problem builder: equilibrium plus joint laws as standard-form conic problems.

Given an :class:`~rigidblocks.equilibrium.EquilibriumSystem`, it poses (in the scaled
variables described below)

* the **relaxation** R(f, lambda) = min r such that an equilibrium state exists whose
  joint forces violate no-tension and friction by at most r (r >= 0). R = 0 exactly
  when the state is admissible (the static theorem's condition); R > 0 measures how far
  from admissible it is. It is always feasible when the equilibrium equations can be
  solved at all, so it is free of the degenerate feasibility problems met right at the
  limit, and its duals give dR/df for the minimum-friction iteration.
* the **maximum load multiplier** max lambda such that A x + F_dead + lambda F_live = 0
  with admissible x; its duals on the equilibrium rows are the collapse mechanism.
* the **force-state QP**: the admissible state of least complementary energy,
  min 1/2 x'Cx, which picks one state out of the set of admissible ones.

Joint laws (design.md): N_k >= -sigma_t a_k; 2D: |T_j| <= f_j sum_k N_k + c_j a_j per
joint (or per point with one shear per point); 3D: ||(T1, T2)_k|| <= f_j N_k + c_j a_k, a
second-order cone per contact point. ``f_j = inf`` (Heyman) leaves the shear free.

Scaling (:class:`Scaling`): each moment row is divided by its block's size; with
:meth:`Scaling.of` x is divided by one reference force F (the largest resultant load on
one block); with :meth:`Scaling.per_block` (the convex path) each block's rows are
divided by its own load and each joint's unknowns and law rows by the load of the
lighter block it touches, so that the numbers are of order one block by block, a light
block's equilibrium is not lost in a heavy block's round-off, and a scene in mm and N
gives the same problem as the same scene in m and kN.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..equilibrium import EquilibriumSystem
from ..solvers.base import ConicProblem
from ..sparse import CscMatrix, hstack, vstack

#: block loads spanning more than this ratio are scaled block by block
#: (:meth:`Scaling.for_system`): a block 100 times lighter than the heaviest is still
#: judged to 1e-7 of its load with one reference force
PER_BLOCK_SPREAD = 100.0


@dataclass(frozen=True, eq=False)
class Scaling:
    """Scaled unknowns and rows: x = ``force`` x ``col`` x x_scaled; equilibrium rows
    multiplied by ``row`` / ``force``; joint-law rows in units of ``force`` x ``col``.

    :meth:`of` is the uniform scaling (``col`` = 1, one reference force for the whole
    scene); :meth:`per_block` scales each block's rows by its own load and each joint's
    unknowns and law rows by the load of the lighter block it touches, so that a light
    block's equilibrium and joint laws are resolved relative to its own forces, not to
    the heaviest block of the scene.
    """

    force: float
    row: np.ndarray
    col: np.ndarray | None = None
    #: (n_free,) each free block's load scale (scene units), per_block only
    block_load: np.ndarray | None = None

    def cols(self, n: int) -> np.ndarray:
        """The column scale of the n unknowns (ones for the uniform scaling)."""
        return np.ones(n) if self.col is None else self.col

    def forces(self, x_scaled: np.ndarray) -> np.ndarray:
        """Scaled unknowns back to forces in the scene's units."""
        return x_scaled * self.force * self.cols(len(x_scaled))

    def scaled(self, forces: np.ndarray) -> np.ndarray:
        """Forces in the scene's units as scaled unknowns (the inverse of :meth:`forces`)."""
        return forces / (self.force * self.cols(len(forces)))

    @property
    def spread(self) -> float:
        """Largest over smallest block load scale (1 for the uniform scaling)."""
        bl = self.block_load
        if bl is None or not bl.size:
            return 1.0
        return float(bl.max() / bl.min())

    @staticmethod
    def _moment_rows(system: EquilibriumSystem) -> np.ndarray:
        d = system.dofs
        nf = system.n_rows // d if d else 0
        sizes = system.sizes[system.free_blocks]
        row = np.ones(system.n_rows)
        if nf:
            mom = np.zeros((nf, d), dtype=bool)
            mom[:, system.contacts.dimension:] = True
            row = np.where(mom, 1.0 / sizes[:, None], 1.0).ravel()
        return row

    @staticmethod
    def _block_loads(system: EquilibriumSystem, row: np.ndarray) -> np.ndarray:
        d = system.dofs
        nf = system.n_rows // d if d else 0
        if not nf:
            return np.zeros(0)
        return np.maximum(np.abs(system.dead * row).reshape(nf, d).max(axis=1),
                          np.abs(system.live * row).reshape(nf, d).max(axis=1))

    @classmethod
    def of(cls, system: EquilibriumSystem) -> Scaling:
        """One reference force F (the largest resultant load on one block) for the
        whole scene; moment rows divided by the block's size."""
        row = cls._moment_rows(system)
        loads = cls._block_loads(system, row)
        force = float(loads.max(initial=0.0))
        if not np.isfinite(force) or force <= 0:
            force = 1.0
        return cls(force=force, row=row)

    @classmethod
    def for_system(cls, system: EquilibriumSystem) -> Scaling:
        """:meth:`per_block` where the blocks' loads span more than ``PER_BLOCK_SPREAD``
        (a light block next to heavy ones), else the uniform :meth:`of`: on scenes of
        blocks of like sizes the interior-point solver reaches lambda* closer with one
        reference force (the 1,000-block wall: 7.5e-9 of the simplex answer against
        1e-7 with per-block rows)."""
        uniform = cls.of(system)
        loads = cls._block_loads(system, uniform.row)
        ok = loads[np.isfinite(loads) & (loads > 0)]
        if ok.size and ok.max() > PER_BLOCK_SPREAD * ok.min():
            return cls.per_block(system)
        return uniform

    @classmethod
    def per_block(cls, system: EquilibriumSystem) -> Scaling:
        """Each free block's rows divided by its own load scale L_b (the largest of its
        dead and live force components and moments over its size; F for a block without
        loads), each joint's unknowns and law rows by s_j = min L_b over the free blocks
        it touches (F = max L_b stays the reference force of reports)."""
        base = cls.of(system)
        F = base.force
        loads = cls._block_loads(system, base.row)
        ok = np.isfinite(loads) & (loads > 0)
        L = np.where(ok, loads, F)
        d = system.dofs
        row = base.row * np.repeat(F / L, d) if L.size else base.row
        c = system.contacts
        lay = system.layout
        # each joint's scale: the lighter free block it touches
        full = np.full(len(system.block_rows), np.inf)
        free = system.free_blocks
        full[free] = L
        sj = np.minimum(full[c.pairs[:, 0]], full[c.pairs[:, 1]]) if c.n_joints else \
            np.zeros(0)
        sj = np.where(np.isfinite(sj), sj, F) / F
        col = np.empty(lay.size)
        col[lay.normal] = sj[c.point_joint]
        if lay.shear == "joint" and c.dimension == 2:
            col[lay.tangential] = sj
        elif c.dimension == 2:
            col[lay.tangential] = sj[c.point_joint]
        else:
            col[lay.tangential] = np.repeat(sj[c.point_joint], 2)
        return cls(force=F, row=row, col=col, block_load=L)


@dataclass(frozen=True, eq=False)
class JointRows:
    """The no-tension and friction rows of the standard form, with bookkeeping.

    ``G z + s = h`` with s >= 0 for the linear rows (and s in SOC for the 3D cones).
    ``fric_head`` are the rows whose N coefficients are -f_j (one per friction
    inequality or cone); ``fric_joint`` their joints; ``fric_nsum`` a sparse matrix
    whose row r sums the normal forces in row ``fric_head[r]`` (for dR/df).
    ``f_entries`` (block, row, column, joint, value) locate every coefficient -f_j (x a
    constant) on a normal force: ``block`` 0 for a row of ``G_lin``, 1 of ``G_soc``.
    """

    G_lin: CscMatrix
    h_lin: np.ndarray
    G_soc: CscMatrix
    h_soc: np.ndarray
    soc: tuple[int, ...]
    n_normal_rows: int
    fric_head: np.ndarray
    fric_joint: np.ndarray
    fric_nsum: CscMatrix
    f_entries: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]
    #: the joint of every row of ``G_lin`` and of every cone of ``G_soc``
    lin_joint: np.ndarray | None = None
    soc_joint: np.ndarray | None = None


def joint_rows(system: EquilibriumSystem, scaling: Scaling, f_joint: np.ndarray,
               n_cols: int, relax_col: int | None = None,
               relax_rhs: float = 0.0, pyramid: int | None = None,
               cap: np.ndarray | None = None) -> JointRows:
    """Rows of the joint laws for friction coefficients ``f_joint`` (per joint).

    ``cap`` (P,), scaled force units: an extra shear capacity per contact point, added to
    the friction rows' right-hand sides like a cohesion (per joint, the sum over its
    points). With ``f_joint = 0`` on a joint it makes the cohesion-only law
    |T| <= cap + c a of the non-associative iteration
    (:mod:`rigidblocks.analyses.nonassociative`).

    ``relax_col`` adds -1 x that column to every row (the relaxation variable r);
    ``relax_rhs`` adds a fixed relaxation to every right-hand side instead.
    ``pyramid`` (3D only) replaces each Coulomb cone by the inscribed pyramid of that
    many facets: T . d_i <= f cos(pi / k) N with d_i the facets' outward directions
    in the joint's tangent frame. It is an approximation, never the default.
    """
    c = system.contacts
    lay = system.layout
    pj = c.point_joint
    P = c.n_points
    a_pt = c.point_areas
    # the law rows of a point (joint) are in units of its unknowns' scale
    F_pt = scaling.force * scaling.cols(lay.size)[lay.normal]
    F_joint = np.full(c.n_joints, scaling.force)
    if P:
        F_joint[pj] = F_pt
    tens = c.tensile_strength[pj] * a_pt / F_pt + relax_rhs
    coh_joint = c.cohesion * c.areas / F_joint
    # the extra capacity, given in units of the reference force, in the points' units
    cap_pt = np.zeros(P) if cap is None else \
        np.asarray(cap, dtype=float) * scaling.force / F_pt
    if cap is not None:
        coh_joint = coh_joint + np.bincount(pj, cap_pt, minlength=c.n_joints)
    # -- no tension: -N_k (- r) <= sigma a_k
    nrow = CscMatrix.from_triplets(-np.ones(P), np.arange(P), lay.normal.start + np.arange(P),
                                   (P, n_cols))
    lin_blocks = [nrow]
    h_parts = [tens]
    finite = np.isfinite(f_joint)
    soc_rows = None
    h_soc = np.zeros(0)
    soc: tuple[int, ...] = ()
    t0 = lay.tangential.start
    if c.dimension == 2:
        if lay.shear == "joint":
            # one inequality pair per joint: +-T_j - f_j (N_1 + N_2) <= c_j a_j
            J = np.flatnonzero(finite)
            nJ = len(J)
            ptr = c.joint_start
            cnt = ptr[J + 1] - ptr[J]
            pts = np.concatenate([np.arange(ptr[j], ptr[j + 1]) for j in J]) if nJ else \
                np.zeros(0, int)
            owner = np.repeat(np.arange(nJ), cnt)
            rows_n = np.concatenate([owner, owner + nJ])
            cols_n = np.concatenate([pts, pts])
            vals_n = -np.concatenate([f_joint[J][owner]] * 2)
            rows_t = np.concatenate([np.arange(nJ), np.arange(nJ) + nJ])
            cols_t = np.concatenate([t0 + J, t0 + J])
            vals_t = np.concatenate([np.ones(nJ), -np.ones(nJ)])
            G = CscMatrix.from_triplets(np.concatenate([vals_n, vals_t]),
                                        np.concatenate([rows_n, rows_t]),
                                        np.concatenate([cols_n, cols_t]), (2 * nJ, n_cols))
            lin_blocks.append(G)
            h_parts.append(np.concatenate([coh_joint[J], coh_joint[J]]) + relax_rhs)
            fric_joint = np.concatenate([J, J])
            nsum = CscMatrix.from_triplets(np.ones(2 * len(pts)), rows_n, cols_n,
                                           (2 * nJ, n_cols))
            f_ent = (P + rows_n, cols_n, J[np.concatenate([owner, owner])], vals_n)
        else:
            # one inequality pair per point: +-T_k - f_j N_k <= c_j a_k
            K = np.flatnonzero(finite[pj])
            nK = len(K)
            r = np.arange(nK)
            rows = np.concatenate([r, r + nK, r, r + nK])
            cols = np.concatenate([K, K, t0 + K, t0 + K])
            fk = f_joint[pj[K]]
            vals = np.concatenate([-fk, -fk, np.ones(nK), -np.ones(nK)])
            lin_blocks.append(CscMatrix.from_triplets(vals, rows, cols, (2 * nK, n_cols)))
            hk = c.cohesion[pj[K]] * a_pt[K] / F_pt[K] + cap_pt[K]
            h_parts.append(np.concatenate([hk, hk]) + relax_rhs)
            fric_joint = np.concatenate([pj[K], pj[K]])
            nsum = CscMatrix.from_triplets(np.ones(2 * nK), np.concatenate([r, r + nK]),
                                           np.concatenate([K, K]), (2 * nK, n_cols))
            f_ent = (P + rows[:2 * nK], cols[:2 * nK], fric_joint, vals[:2 * nK])
        n_fric = len(fric_joint)
        fric_head = P + np.arange(n_fric)
    elif pyramid is not None:
        k = int(pyramid)
        K = np.flatnonzero(finite[pj])
        nK = len(K)
        ang = (2 * np.arange(k) + 1) * np.pi / k
        cosk = np.cos(np.pi / k)
        fk = f_joint[pj[K]]
        rows, cols, vals = [], [], []
        for i, a in enumerate(ang):
            r = i * nK + np.arange(nK)
            rows += [r, r, r]
            cols += [K, t0 + 2 * K, t0 + 2 * K + 1]
            vals += [-fk * cosk, np.full(nK, np.cos(a)), np.full(nK, np.sin(a))]
        lin_blocks.append(CscMatrix.from_triplets(np.concatenate(vals), np.concatenate(rows),
                                                  np.concatenate(cols), (k * nK, n_cols)))
        hk = (c.cohesion[pj[K]] * a_pt[K] / F_pt[K] + cap_pt[K]) * cosk
        h_parts.append(np.tile(hk, k) + relax_rhs)
        fric_joint = np.tile(pj[K], k)
        nsum = CscMatrix.from_triplets(np.full(k * nK, cosk), np.arange(k * nK),
                                       np.tile(K, k), (k * nK, n_cols))
        fric_head = P + np.arange(k * nK)
        f_ent = (P + np.arange(k * nK), np.tile(K, k), fric_joint, np.tile(-fk * cosk, k))
    else:
        # 3D: (f N_k + c a_k (+ r), T1_k, T2_k) in SOC(3) for points of finite-f joints
        K = np.flatnonzero(finite[pj])
        nK = len(K)
        r = np.arange(nK) * 3
        fk = f_joint[pj[K]]
        rows = np.concatenate([r, r + 1, r + 2])
        cols = np.concatenate([K, t0 + 2 * K, t0 + 2 * K + 1])
        vals = np.concatenate([-fk, -np.ones(nK), -np.ones(nK)])
        if relax_col is not None:
            rows = np.concatenate([rows, r])
            cols = np.concatenate([cols, np.full(nK, relax_col)])
            vals = np.concatenate([vals, -np.ones(nK)])
        soc_rows = CscMatrix.from_triplets(vals, rows, cols, (3 * nK, n_cols))
        h_soc = np.zeros(3 * nK)
        h_soc[r] = c.cohesion[pj[K]] * a_pt[K] / F_pt[K] + cap_pt[K] + relax_rhs
        soc = (3,) * nK
        fric_joint = pj[K]
        fric_head = None  # set below, after the linear rows are counted
        f_ent = (r, K, fric_joint, -fk)
        nsum = CscMatrix.from_triplets(np.ones(nK), np.arange(nK), K, (nK, n_cols))
    G_lin = vstack(lin_blocks)
    h_lin = np.concatenate(h_parts)
    if relax_col is not None:
        extra = CscMatrix.from_triplets(-np.ones(G_lin.shape[0]), np.arange(G_lin.shape[0]),
                                        np.full(G_lin.shape[0], relax_col), G_lin.shape)
        G_lin = G_lin + extra
    if soc_rows is None:
        soc_rows = CscMatrix.empty((0, n_cols))
        block = np.zeros(len(f_ent[0]), dtype=int)
    else:
        fric_head = G_lin.shape[0] + np.arange(len(fric_joint)) * 3
        block = np.ones(len(f_ent[0]), dtype=int)
    if c.dimension == 3 and pyramid is None:
        lin_joint, soc_joint = pj, fric_joint
    else:
        lin_joint, soc_joint = np.concatenate([pj, fric_joint]), np.zeros(0, dtype=int)
    return JointRows(G_lin=G_lin, h_lin=h_lin, G_soc=soc_rows, h_soc=h_soc, soc=soc,
                     n_normal_rows=P, fric_head=fric_head, fric_joint=fric_joint,
                     fric_nsum=nsum, f_entries=(block, *f_ent), lin_joint=lin_joint,
                     soc_joint=soc_joint)


def joint_violations(problem: ConicProblem, jr: JointRows, z: np.ndarray, n_joints: int,
                     relax: float = 0.0) -> np.ndarray:
    """(n_joints,) the largest breach of each joint's laws by the unknowns x of the
    solution ``z`` of ``problem`` (0 where the laws hold), in the units of the joint's
    law rows: read from the problem's own rows (its friction parameter included), with
    every column but x left out (the relaxation r) and ``relax`` (a relaxation added to
    the right-hand sides when the rows were built) taken back."""
    out = np.zeros(n_joints)
    rows = problem.rows["joints"]
    xs = problem.cols["x"]
    x = np.zeros(problem.n)
    x[xs] = z[xs]
    v = problem.b[rows] - relax - (problem.A @ x)[rows]  # slacks: >= 0 when the laws hold
    nl = jr.G_lin.shape[0]
    if nl:
        np.maximum.at(out, jr.lin_joint, np.maximum(-v[:nl], 0.0))
    if jr.soc:
        q = v[nl:].reshape(-1, 3)
        np.maximum.at(out, jr.soc_joint,
                      np.maximum(np.hypot(q[:, 1], q[:, 2]) - q[:, 0], 0.0))
    return out


def friction_parameter(A: CscMatrix, jr: JointRows, first_joint_row: int,
                       f_joint: np.ndarray, uniform: np.ndarray,
                       ) -> tuple[np.ndarray, np.ndarray]:
    """Positions in ``A.data`` and coefficients of the entries proportional to the
    uniform friction (the -f N terms of the joints marked ``uniform``), for
    :meth:`~rigidblocks.solvers.base.ConicProblem.with_parameter`.

    ``A`` has sorted indices; ``first_joint_row`` is the row of A where ``G_lin``
    starts (``G_soc`` follows it). The problem must have been built with a finite,
    nonzero f on the uniform joints.
    """
    block, rows, cols, joint, vals = jr.f_entries
    keep = uniform[joint]
    rows = rows[keep] + first_joint_row + block[keep] * jr.G_lin.shape[0]
    cols, coef = cols[keep], vals[keep] / f_joint[joint[keep]]
    counts = np.diff(A.indptr)
    keys = np.repeat(np.arange(A.shape[1], dtype=np.int64), counts) * A.shape[0] + A.indices
    pos = np.searchsorted(keys, cols.astype(np.int64) * A.shape[0] + rows)
    return pos, coef


def _equilibrium(system: EquilibriumSystem, scaling: Scaling) -> CscMatrix:
    return system.A.scaled(scaling.row, scaling.col)


def _stack(eq_A, eq_b, jr: JointRows, extra_lin=None, extra_h=None):
    blocks = [eq_A]
    rhs = [eq_b]
    if extra_lin is not None:  # extra linear rows come first, before the joint rows
        blocks.append(extra_lin)
        rhs.append(extra_h)
    blocks.append(jr.G_lin)
    rhs.append(jr.h_lin)
    blocks.append(jr.G_soc)
    rhs.append(jr.h_soc)
    return vstack(blocks), np.concatenate(rhs)


def build_relaxation(system: EquilibriumSystem, scaling: Scaling, f_joint: np.ndarray,
                     load_factor: float, pyramid: int | None = None,
                     uniform: np.ndarray | None = None,
                     cap: np.ndarray | None = None) -> tuple[ConicProblem, JointRows]:
    """min r  s.t.  equilibrium at ``load_factor``, joint laws relaxed by r, r >= 0.

    ``cap``: extra shear capacity per contact point (see :func:`joint_rows`).

    ``uniform`` (a mask of joints, with finite nonzero ``f_joint`` there) makes their
    friction the problem's parameter "f" (:func:`friction_parameter`), so that the
    relaxation at another uniform f is ``problem.with_parameter("f", f)``.
    """
    n = system.layout.size
    nc = n + 1
    Aeq = hstack([_equilibrium(system, scaling), CscMatrix.empty((system.n_rows, 1))])
    beq = -scaling.row * (system.dead + load_factor * system.live) / scaling.force
    jr = joint_rows(system, scaling, f_joint, nc, relax_col=n, pyramid=pyramid, cap=cap)
    r_nonneg = CscMatrix.from_triplets([-1.0], [0], [n], (1, nc))
    A, b = _stack(Aeq, beq, jr, r_nonneg, np.zeros(1))
    cvec = np.zeros(nc)
    cvec[n] = 1.0
    ne, nl = system.n_rows, jr.G_lin.shape[0] + 1
    params = {}
    if uniform is not None and np.any(uniform & np.isfinite(f_joint)):
        params["f"] = friction_parameter(A, jr, ne + 1, f_joint, uniform)
    prob = ConicProblem(c=cvec, A=A, b=b, n_eq=ne, n_nonneg=nl, soc=jr.soc,
                        cols={"x": slice(0, n), "r": slice(n, n + 1)},
                        rows={"equilibrium": slice(0, ne), "joints": slice(ne + 1, len(b))},
                        params=params)
    return prob, jr


def build_max_load(system: EquilibriumSystem, scaling: Scaling, f_joint: np.ndarray,
                   pyramid: int | None = None,
                   cap: np.ndarray | None = None) -> tuple[ConicProblem, JointRows]:
    """max lambda  s.t.  A x + F_dead + lambda F_live = 0, joint laws (``cap``: extra
    shear capacity per contact point, see :func:`joint_rows`)."""
    n = system.layout.size
    nc = n + 1
    live = (scaling.row * system.live / scaling.force)[:, None]
    Aeq = hstack([_equilibrium(system, scaling), CscMatrix.from_dense(live)])
    beq = -scaling.row * system.dead / scaling.force
    jr = joint_rows(system, scaling, f_joint, nc, pyramid=pyramid, cap=cap)
    A, b = _stack(Aeq, beq, jr)
    cvec = np.zeros(nc)
    cvec[n] = -1.0
    ne = system.n_rows
    prob = ConicProblem(c=cvec, A=A, b=b, n_eq=ne, n_nonneg=jr.G_lin.shape[0], soc=jr.soc,
                        cols={"x": slice(0, n), "lambda": slice(n, n + 1)},
                        rows={"equilibrium": slice(0, ne), "joints": slice(ne, len(b))})
    return prob, jr


def flexibility(system: EquilibriumSystem) -> np.ndarray:
    """Diagonal link flexibility C (scaled units): 1 per normal link and per shear link.

    With one shear per 2D joint the shear link stands for the two point links in
    parallel, so its flexibility is 1/2: both layouts then give the same state.
    """
    lay = system.layout
    C = np.ones(lay.size)
    if lay.shear == "joint" and system.contacts.dimension == 2:
        C[lay.tangential] = 0.5
    return C


def build_energy_qp(system: EquilibriumSystem, scaling: Scaling, f_joint: np.ndarray,
                    load_factor: float, relax: float = 0.0,
                    pyramid: int | None = None, cap: np.ndarray | None = None,
                    reference: np.ndarray | None = None) -> ConicProblem:
    """The least-energy QP of :func:`energy_problem`, without its joint rows."""
    return energy_problem(system, scaling, f_joint, load_factor, relax, pyramid, cap,
                          reference)[0]


def energy_problem(system: EquilibriumSystem, scaling: Scaling, f_joint: np.ndarray,
                   load_factor: float, relax: float = 0.0,
                   pyramid: int | None = None, cap: np.ndarray | None = None,
                   reference: np.ndarray | None = None) -> tuple[ConicProblem, JointRows]:
    """min 1/2 x'Cx  s.t.  equilibrium at ``load_factor``, joint laws relaxed by ``relax``
    (``cap``: extra shear capacity per contact point, see :func:`joint_rows`); the
    problem and its joint rows (for :func:`joint_violations`).

    ``reference``: a state (scaled forces) of about the solution's energy, such as the
    limit problem's; the energy is then scaled to at most one per force component
    there. The minimiser is the same; the interior-point path is not: unscaled, the
    energy of a 5,006-block wall at f* is 4.0e7 and Clarabel stalls (AlmostSolved after
    200 iterations, 40 s); scaled so, it solves in 71 (18 s), and the 1,009-block wall's
    in 65 iterations instead of 82 (extruded: 73 instead of 87).
    """
    n = system.layout.size
    Aeq = _equilibrium(system, scaling)
    beq = -scaling.row * (system.dead + load_factor * system.live) / scaling.force
    jr = joint_rows(system, scaling, f_joint, n, relax_rhs=relax, pyramid=pyramid, cap=cap)
    A, b = _stack(Aeq, beq, jr)
    col = scaling.cols(n)
    w = (col / col.max(initial=1.0)) ** 2 if n else col  # energy of the unscaled forces
    diag = flexibility(system) * w
    if reference is not None:
        energy = 0.5 * float(diag @ reference ** 2)
        if energy > n:
            diag = diag * (n / energy)
    P = CscMatrix.diagonal_of(diag)
    ne = system.n_rows
    return ConicProblem(c=np.zeros(n), A=A, b=b, n_eq=ne, n_nonneg=jr.G_lin.shape[0],
                        soc=jr.soc, P=P, cols={"x": slice(0, n)},
                        rows={"equilibrium": slice(0, ne), "joints": slice(ne, len(b))}), jr
