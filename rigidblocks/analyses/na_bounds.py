"""The safe non-associative multiplier: the smallest collapse multiplier over all states.

Under Coulomb friction without dilatancy the collapse multiplier depends on the state
the joints are in (a pinch raises the shear a joint can carry): the analysis of
:mod:`.nonassociative` follows the state reached from the elastic state X0, one of
many. This module computes, for small 2D scenes, the least multiplier at which *some*
state collapses, so that the engineer sees how far the X0 answer is from the worst case.

Notes
-----
A non-associative collapse state at lambda (in the scaled unknowns of
:func:`~rigidblocks.problems.formulation.build_max_load`) is forces x and block
velocities u with

    A x + F_dead + lambda F_live = 0,     s = h - G x >= 0           (equilibrium, laws)
    A^T u + Q^T nu = 0,   nu >= 0,        F_live . u = 1             (flow, a mechanism)
    nu_r s_r = 0 for every law row r                                 (complementarity)

G x <= h are the joint laws (N_k >= -t_k per contact point; +-T_j - f_j sum N_k <= c_j
per joint). A^T u are the relative displacements at the links (opening along N, slip
along T): an opening nu_k >= 0 only where N_k is at its tensile limit, a slip
nu_- - nu_+ only where the shear is at its threshold, against it. Q is G with the
-f_j entries of the non-associative joints removed: their slip opens nothing (no
dilatancy); on the associative joints Q = G (normality). The set of such states is not
convex; the complementarity is written with one binary z_r per law row,

    nu_r <= V z_r,     s_r <= S_r (1 - z_r),

and lambda >= 0 minimised by HiGHS's branch and bound (:func:`scipy.optimize.milp`).
The normalisation F_live . u = 1 (as Ferris & Tin-Loi, Int. J. Mech. Sci. 43, 2001,
write it) leaves out the mechanisms the dead load drives, on which the live load does
no work or which it resists: a second program searches them, with F_dead . u = 1 and
F_live . u <= 0 in its place (the flat arch with vertical joints slides down between
its piers under its own weight, in the state of least thrust), and the answer is the
least of the two (:func:`_combine`).
The constants are stated bounds, not a property of the structure: S on every normal
force (N_k + t_k <= S, whence |T_j| <= f_j sum N_k + c_j bounds the friction rows'
slacks) and V on every opening and slip (per unit work of the live load). The value
is the smallest collapse multiplier *with forces and displacement rates within those
bounds*; the computation is repeated with both doubled, and a value that moves is not
given as the safe one.

Each answer is checked after the solve: with its binaries fixed, the linear program
of that active set (exact complementarity, no bounds) is solved again (a collapse
state of that value, or lower: the bounds then bind) and its equilibrium,
laws and complementarity are measured. Every collapse state is statically admissible,
so lambda <= the associative multiplier (the static theorem; Radenkovic's first
theorem, Drucker, J. Appl. Mech. 21, 1954), and every one is at least the associative
multiplier with the non-associative joints frictionless (Radenkovic's second theorem;
Drucker 1954): both are reported beside the value.

In 3D the Coulomb cone of each contact point is replaced by an inscribed pyramid
(:func:`~rigidblocks.problems.formulation.joint_rows`, ``pyramid``; 8 facets by
default): T . d_i <= f cos(pi / k) N_k, the facets' normals d_i in the tangent plane; its
non-associative flow is a slip sum nu_i d_i with no opening. The answer is that of the
pyramid law, which lies inside the cone (an approximation, said in the notes); the
binaries (k + 1 per contact point) limit it to a few blocks.
"""

from __future__ import annotations

import math
import os
import re
import time
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp
from scipy.optimize import Bounds, LinearConstraint, linprog, milp

from ..equilibrium import force_state, mechanism
from ..errors import InputError
from ..results import ForceState, Mechanism
from ..scene.model import Scene, friction_value
from ..scene.validate import check_live_load
from .na_capacity import (
    MAX_JOINTS,
    _admissible_lps,
    _capacity_bound,
    _Model,
    _model,
)
from .nonassociative import _frictionless_bound, flow_mask

if TYPE_CHECKING:
    from ..methods.convex import ConvexMethod

#: facets of the inscribed pyramid that replaces each 3D Coulomb cone
PYRAMID = 8
#: default bound on the normal forces, times the sum of the blocks' loads
FORCE_FACTOR = 10.0
#: default bound on openings and slips per unit work of the live load, times the
#: largest of the blocks' live loads over the smallest
VELOCITY_FACTOR = 100.0
#: relative (and absolute, in units of the reference force) gap HiGHS must close
MIP_GAP = 1e-6
#: two values of lambda closer than this (relative, absolute below 1) are one value:
#: HiGHS's integrality tolerance (1e-6) lets a binary leak that much of its big-M, which
#: moved the value of examples/fig4a_bonded.json by 1e-6 with the bounds doubled
SAME = 1e-5
#: a complementarity breach, equilibrium residual or law breach above this (in units
#: of the reference force, or of the displacement bound) fails the check
CHECK_TOL = 1e-6

#: the two families of collapse states, searched apart (their mechanisms normalised
#: apart): those the live load drives (F_live . u > 0) and those the dead load drives
#: (F_live . u <= 0: the live load does no work on them, or resists them)
LIVE, DEAD = "live", "dead"

OPTIMAL = "optimal"
BOUND_DEPENDENT = "bound-dependent"
NONE_WITHIN_BOUNDS = "no collapse within the bounds"
UNDECIDED = "undecided"
UNSTABLE = "unstable"


@dataclass(frozen=True, eq=False)
class SafeMultiplier:
    """The smallest non-associative collapse multiplier at lambda >= 0 (see the module
    docstring).

    ``status``: "optimal" (``value`` proven smallest within the bounds, and unchanged
    with the bounds doubled), "bound-dependent" (a smaller state was found with the
    bounds doubled or lifted: ``upper`` is the least found, no value), "no collapse
    within the bounds" (the structure stands until the associative multiplier, where
    no state is admissible any more, unless a collapse state lies beyond the bounds),
    "unstable" (the dead load alone has no admissible state), or "undecided" (the
    solver did not prove optimality: ``lower`` and ``upper`` are its bracket, or None).
    ``lower``: the larger of HiGHS's proven bound and the capacity bound; ``upper``: the
    least collapse state found (``state``, ``mechanism``). ``force_bound`` (scene force
    units) bounds every normal force the admissible states leave unbounded,
    ``velocity_bound`` every opening and slip of a mechanism normalised to a work of the
    live load of one reference force ``reference_force`` times one length unit.
    """

    status: str
    value: float | None
    lower: float | None
    upper: float | None
    friction: float
    frictionless: float | None
    associative: float | None
    #: a lower bound on every collapse multiplier (:func:`_capacity_bound`; None where no
    #: solve was made) and its rounds
    capacity_bound: float | None
    bound_rounds: int
    force_bound: float
    velocity_bound: float
    reference_force: float
    state: ForceState | None = None
    mechanism: Mechanism | None = None
    #: the least value at each pair of bounds tried, (force bound, value or None)
    trials: tuple[tuple[float, float | None], ...] = ()
    solve_time: float = 0.0
    nodes: int = 0
    gap: float | None = None
    n_binaries: int = 0
    #: the largest breach of the checked state: equilibrium, laws, complementarity
    breach: float | None = None
    notes: tuple[str, ...] = field(default_factory=tuple)
    #: the family of the least collapse state found (LIVE or DEAD; None: none found)
    driven_by: str | None = None


def _static_slack_max(m: _Model, lam_hi: float | None, seconds: float = math.inf
                      ) -> tuple[np.ndarray, int]:
    """(L,) the largest slack of each law row over the admissible states at 0 <= lambda
    <= ``lam_hi`` (one LP per row; inf where unbounded or ``lam_hi`` is not finite), and
    how many rows were left at inf because ``seconds`` ran out (the 42-joint wall3d
    loaded out of plane: 1,512 rows, 30 s).

    Every collapse state is admissible at its lambda, and its lambda is at most the
    associative multiplier (the static theorem): where these LPs are bounded they bound
    the slacks of every collapse state, and the force bound is not needed there (an inf
    leaves the force bound to serve)."""
    L, n = m.G.shape
    out = np.full(L, np.inf)
    if lam_hi is None or not math.isfinite(lam_hi):
        return out, 0
    end = time.monotonic() + seconds
    costs = (np.append(m.G[r].toarray().ravel(), 0.0) for r in range(L))  # max h - G x
    for r, (st, fun) in enumerate(_admissible_lps(m, 0.0, float(lam_hi), costs)):
        if st == OPTIMAL:
            out[r] = max(m.h[r] - fun, 0.0)
        if time.monotonic() > end:
            return out, L - r - 1
    return out, 0


def _slack_bounds(m: _Model, S: float, s_max: np.ndarray) -> np.ndarray:
    """(L,) the big-M of each law row's slack: ``s_max`` where the admissible states
    bound it (with a margin of 1e-6 of the largest), else the slack's largest value
    when every N_k + t_k <= S: S on the no-tension rows, ``slack_factor`` (h_r + f N)
    on the friction rows."""
    P = m.n_points
    t = m.h[:P]
    Nmax = np.zeros(m.G.shape[1])
    Nmax[m.normal] = S - t
    fric = abs(m.G[P:]) @ Nmax
    stated = np.concatenate([np.full(P, S), m.slack_factor * (m.h[P:] + fric)])
    fin = np.isfinite(s_max)
    top = float(s_max[fin].max(initial=1.0))
    return np.where(fin, s_max + 1e-6 * max(top, 1.0), stated)


def _columns(m: _Model) -> tuple[int, int, int, int]:
    n, ne, L = m.A.shape[1], m.A.shape[0], m.G.shape[0]
    return n, ne, L, n + 1 + ne + L


def _common_rows(m: _Model, family: str = LIVE
                 ) -> tuple[sp.csr_matrix, np.ndarray, np.ndarray]:
    """Rows lo <= E (x, lambda, u, nu) <= hi: equilibrium, flow, and the mechanism's
    normalisation by its ``family``: F_live . u = 1 (LIVE), or F_dead . u = 1 and
    F_live . u <= 0 (DEAD)."""
    n, ne, L, _ = _columns(m)
    Z = sp.csr_matrix
    eq = sp.hstack([m.A, Z(m.live[:, None]), Z((ne, ne)), Z((ne, L))])
    flow = sp.hstack([Z((n, n)), Z((n, 1)), m.A.T, m.Q.T])

    def work(load: np.ndarray) -> sp.csr_matrix:
        return sp.hstack([Z((1, n)), Z((1, 1)), Z(load[None, :]), Z((1, L))])

    rhs = np.concatenate([m.b, np.zeros(n), [1.0]])
    if family == LIVE:
        return sp.vstack([eq, flow, work(m.live)], format="csr"), rhs, rhs
    E = sp.vstack([eq, flow, work(-m.b), work(m.live)], format="csr")  # (m.b: -F_dead)
    return E, np.append(rhs, -np.inf), np.append(rhs, 0.0)


@contextmanager
def _quiet() -> Iterator[None]:
    """The process's standard output and error (file descriptors 1 and 2) pointed at
    /dev/null: the HiGHS bundled with scipy writes a debugging line from its branch and
    bound ("HighsMipSolverData::transformNewIntegerFeasibleSolution tmpSolver.run();"),
    which would land in the middle of a report or a JSON answer."""
    import sys

    for stream in (sys.stdout, sys.stderr):
        stream.flush()
    saved: list[tuple[int, int]] = []
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        for fd in (1, 2):
            try:
                saved.append((fd, os.dup(fd)))
            except OSError:  # no such descriptor
                continue
            os.dup2(null, fd)
        yield
    finally:
        for fd, copy in saved:
            os.dup2(copy, fd)
            os.close(copy)
        os.close(null)


def _message(text: str) -> str:
    """scipy's message of a HiGHS solve without its repetition: "Time limit reached.
    (HiGHS Status 13: Time limit reached)" read as two messages."""
    m = re.fullmatch(r"\s*(.*?)\.?\s*\(HiGHS Status (\d+): (.*?)\)\s*", text)
    if m and m.group(1).rstrip(".").lower() == m.group(3).rstrip(".").lower():
        return f"{m.group(3).rstrip('.')} (HiGHS status {m.group(2)})"
    return text


def _solve_milp(m: _Model, Sr: np.ndarray, V: float, time_limit: float,
                lam_lo: float = 0.0, node_limit: int | None = None,
                family: str = LIVE) -> dict:
    """min lambda >= ``lam_lo`` over the collapse states of a ``family`` within the
    bounds (``Sr`` on the law rows' slacks, V on openings and slips): HiGHS's answer as
    a dict."""
    n, ne, L, nc = _columns(m)
    E, elo, ehi = _common_rows(m, family)
    Z = sp.csr_matrix
    laws = sp.hstack([m.G, Z((L, 1 + ne + L)), Z((L, L))])  # G x <= h
    cap_nu = sp.hstack([Z((L, n + 1 + ne)), sp.identity(L), -V * sp.identity(L)])  # nu <= V z
    # s = h - G x <= S_r (1 - z)
    cap_s = sp.hstack([-m.G, Z((L, 1 + ne + L)), sp.diags(Sr)])
    Ein = sp.hstack([E, Z((E.shape[0], L))])
    cons = [LinearConstraint(Ein, elo, ehi),
            LinearConstraint(laws, -np.inf, m.h),
            LinearConstraint(cap_nu, -np.inf, 0.0),
            LinearConstraint(cap_s, -np.inf, Sr - m.h)]
    lo = np.concatenate([np.full(n, -np.inf), [lam_lo], np.full(ne, -np.inf),
                         np.zeros(2 * L)])
    hi = np.concatenate([np.full(n + 1 + ne, np.inf), np.full(L, V), np.ones(L)])
    cost = np.zeros(nc + L)
    cost[n] = 1.0
    integ = np.concatenate([np.zeros(nc), np.ones(L)])
    t0 = time.perf_counter()
    opts = {"time_limit": float(time_limit), "mip_rel_gap": MIP_GAP, "presolve": True}
    if node_limit is not None:
        opts["node_limit"] = int(node_limit)
    with _quiet():
        res = milp(cost, constraints=cons, integrality=integ, bounds=Bounds(lo, hi),
                   options=opts)
    out = {"status": int(res.status), "message": _message(str(res.message)),
           "time": time.perf_counter() - t0,
           "nodes": int(getattr(res, "mip_node_count", 0) or 0),
           "dual": getattr(res, "mip_dual_bound", None),
           "gap": getattr(res, "mip_gap", None), "z": None, "value": None}
    if res.x is not None:
        out["value"] = float(res.x[n])
        out["z"] = np.round(res.x[nc:]).astype(bool)
    return out


def _polish(m: _Model, active: np.ndarray, family: str = LIVE
            ) -> tuple[float, np.ndarray] | None:
    """The least lambda of the active set ``active`` (law rows held at equality, the
    others with nu = 0), without bounds: exact complementarity. (lambda, the solution
    over (x, lambda, u, nu)), or None when HiGHS finds no solution."""
    n, ne, L, nc = _columns(m)
    E, elo, ehi = _common_rows(m, family)
    Z = sp.csr_matrix
    laws = sp.hstack([m.G, Z((L, 1 + ne + L))], format="csr")
    tie = elo == ehi  # (the others: F_live . u <= 0)
    A_ub = sp.vstack([laws[~active], E[~tie]], format="csr")
    b_ub = np.concatenate([m.h[~active], ehi[~tie]])
    A_eq = sp.vstack([E[tie], laws[active]], format="csr")
    b_eq = np.concatenate([ehi[tie], m.h[active]])
    bounds = [(None, None)] * n + [(0.0, None)] + [(None, None)] * ne + \
        [(0.0, None) if a else (0.0, 0.0) for a in active]
    cost = np.zeros(nc)
    cost[n] = 1.0
    res = linprog(cost, A_ub=A_ub if A_ub.shape[0] else None,
                  b_ub=b_ub if A_ub.shape[0] else None, A_eq=A_eq, b_eq=b_eq,
                  bounds=bounds, method="highs")
    if res.status != 0:
        return None
    return float(res.x[n]), res.x


def _breach(m: _Model, sol: np.ndarray, family: str = LIVE) -> float:
    """The largest breach of a solution over (x, lambda, u, nu): equilibrium and flow
    residuals, law breaches, complementarity (min(nu_r, s_r) over the rows, relative
    to the largest nu and the largest force)."""
    n, ne, L, nc = _columns(m)
    E, elo, ehi = _common_rows(m, family)
    Es = E @ sol[:nc]
    x, nu = sol[:n], sol[n + 1 + ne:nc]
    s = m.h - m.G @ x
    top_nu = max(float(np.abs(nu).max(initial=0.0)), 1.0)
    top_x = max(float(np.abs(x).max(initial=0.0)), 1.0)
    comp = np.minimum(nu / top_nu, s / top_x)
    return float(max(np.maximum(elo - Es, Es - ehi).max(initial=0.0),
                     (-s).max(initial=0.0), (-nu).max(initial=0.0),
                     comp.max(initial=0.0)))


def _bounds_of(cv: ConvexMethod) -> tuple[float, float, float]:
    """Default (S, V, V_dead) in scaled units: S = FORCE_FACTOR x the blocks' total
    load, V = VELOCITY_FACTOR / the smallest nonzero live load of a block (so that a
    mechanism that moves that block alone fits, VELOCITY_FACTOR times over), V_dead the
    same of the dead loads (for the mechanisms the dead load drives)."""
    sysm, sc = cv.system, cv.scaling
    d = sysm.dofs
    dead = np.abs(sc.row * sysm.dead / sc.force).reshape(-1, d).max(axis=1)
    live = np.abs(sc.row * sysm.live / sc.force).reshape(-1, d).max(axis=1)
    total = float(np.maximum(dead, live).sum())

    def per_unit_work(load: np.ndarray) -> float:
        pos = load[load > 0]
        return VELOCITY_FACTOR / (float(pos.min()) if pos.size else 1.0)

    return FORCE_FACTOR * max(total, 1.0), per_unit_work(live), per_unit_work(dead)


def _tol(a: float) -> float:
    return SAME * max(1.0, abs(a))


def _same(a: float, b: float) -> bool:
    return abs(a - b) <= SAME * max(1.0, abs(a), abs(b))


def _checked(m: _Model, run: dict, family: str = LIVE
             ) -> tuple[float, np.ndarray, float] | None:
    """The polished state of a run's answer, (lambda, solution, breach); None without
    an answer or when its active set has no solution."""
    if run["z"] is None:
        return None
    got = _polish(m, run["z"], family)
    if got is None:
        return None
    lam, sol = got
    return lam, sol, _breach(m, sol, family)


def safe_multiplier(scene: Scene, friction: float | str | None = None, *,
                    flow: str | None = None, max_joints: int = MAX_JOINTS,
                    force_bound: float | None = None, velocity_bound: float | None = None,
                    time_limit: float = 60.0, node_limit: int | None = None,
                    double_check: bool = True, cut: bool = True, pyramid: int | None = None,
                    collapse_at: float | None = None) -> SafeMultiplier:
    """The smallest non-associative collapse multiplier over all states at lambda >= 0,
    as a mixed-integer LP solved by HiGHS (see the module docstring); a collapse state
    below 0 (under a reversed live load) is not sought.

    ``friction``, ``flow``: as for :func:`rigidblocks.analyses.max_load_multiplier`
    (``flow`` None: the scene's, with its joints' overrides; the associative joints
    keep normality). ``force_bound`` (scene force units; default ``FORCE_FACTOR``
    times the blocks' total load) bounds every normal force, ``velocity_bound`` every
    opening and slip per unit work of the live load (see :class:`SafeMultiplier`);
    ``double_check`` solves again with both doubled and gives no value if it moves.
    ``time_limit`` (s) and ``node_limit`` (branch-and-bound nodes, None: no limit) per
    mixed-integer solve. ``cut``: lambda >= the capacity bound
    (:func:`_capacity_bound`, a theorem) is a constraint of the mixed-integer LP, which
    then prunes below it; without it the MILP's value is independent of the bound.
    ``pyramid`` (3D only; default ``PYRAMID``): the Coulomb cones are replaced by
    inscribed pyramids of that many facets (a linear law: the answer is that law's, and
    a note says so). ``collapse_at``: the multiplier of a collapse state known already
    (the limit iteration's checked answer), the upper end of an undecided bracket where
    HiGHS found no lower one. Scenes of more than ``max_joints`` joints are refused
    with an :class:`InputError`.
    """
    from ..methods import open_method

    if scene.dimension == 3 and pyramid is None:
        pyramid = PYRAMID
    check_live_load(scene)
    f = friction_value(scene.effective_friction if friction is None else friction)
    cv = open_method(scene, "clarabel", pyramid=pyramid)
    c = cv.contacts
    if c.n_joints > max_joints:
        raise InputError(f"{c.n_joints} joints: the safe non-associative multiplier (a "
                         f"mixed-integer LP, one binary per joint law) is computed for "
                         f"at most {max_joints} (max_joints)", scene.source)
    marked = flow_mask(scene, c, flow)
    m = _model(cv, marked, f)
    F = cv.scaling.force
    S, V, V_dead = _bounds_of(cv)
    if force_bound is not None:
        S = float(force_bound) / F
    if velocity_bound is not None:
        V = V_dead = float(velocity_bound)
    if not (S > 0 and V > 0 and math.isfinite(S) and math.isfinite(V)):
        raise InputError("force_bound and velocity_bound must be finite numbers > 0")
    up = cv.load_limit(f, 1e-9)
    if up.status not in ("collapse", "unbounded"):
        ctx = _Context(m, cv, f, S, V, None, None, np.zeros(0), 0.0, 0, cut)
        if up.status == "unstable":
            ctx.notes.append("the dead load alone has no admissible state (static "
                             "problem): the structure does not stand, under either flow "
                             "rule")
            return _result(ctx, UNSTABLE, None, None, None, None)
        ctx.notes.append(f"the associative multiplier is undecided ({up.status}): no "
                         "bounds to search between")
        return _result(ctx, UNDECIDED, None, None, None, None)
    assoc = up.value if up.status == "collapse" else math.inf
    low = _frictionless_bound(cv, marked, f)
    s_max, skipped = _static_slack_max(m, assoc, time_limit)
    every, rounds, live = _capacity_bound(m, cv, marked, f, max(low or 0.0, 0.0), assoc,
                                          live_too=True)
    runs = []
    for family, v, cap in ((LIVE, V, live), (DEAD, V_dead, every)):
        # (the live load's mechanisms collapse at or above the capacity bound of theirs;
        # the dead load's at or above the bound on every state only)
        ctx = _Context(m, cv, f, S, v, low, assoc, s_max, cap, rounds, cut, node_limit,
                       collapse_at=collapse_at, family=family)
        runs.append(_decide(ctx, time_limit, double_check))
    notes = [n for n in cv.notes if n.startswith("friction cones linearised")]
    if skipped:
        notes.append(f"the largest slacks of {skipped} of the {len(s_max)} joint-law rows "
                     f"were not computed within the time limit ({time_limit:g} s): the "
                     "force bound bounds them")
    return _combine(*runs, every, notes)


def _combine(live: SafeMultiplier, dead: SafeMultiplier, every: float,
             notes: list[str]) -> SafeMultiplier:
    """The least collapse state over the two families (LIVE, DEAD), each searched by
    :func:`_decide`: proven where the least value found lies at or below the other
    family's lower end; ``every`` the capacity bound on every state."""
    runs = {LIVE: live, DEAD: dead}
    found = sorted((r.upper, fam) for fam, r in runs.items() if r.upper is not None)
    least = found[0][1] if found else None
    lows = [math.inf if r.status == NONE_WITHIN_BOUNDS else
            (every if r.lower is None else r.lower) for r in runs.values()]
    statuses = {live.status, dead.status}
    value = None
    if BOUND_DEPENDENT in statuses:
        status = BOUND_DEPENDENT
    elif statuses <= {OPTIMAL, NONE_WITHIN_BOUNDS}:
        status = OPTIMAL if OPTIMAL in statuses else NONE_WITHIN_BOUNDS
    else:
        status = UNDECIDED
    if least is not None and runs[least].status == OPTIMAL and \
            min(lows) >= runs[least].value - _tol(runs[least].value):
        status, value = OPTIMAL, runs[least].value
    elif status == OPTIMAL:  # (an optimum above the other family's undecided bracket)
        status = UNDECIDED
    base = runs[least] if least is not None else live
    words = {LIVE: "the live load's mechanisms: ", DEAD: "the dead load's mechanisms: "}
    merged = [words[fam] + n for fam in ([least] if least else []) +
              [k for k in runs if k != least] for n in runs[fam].notes] + notes
    upper = found[0][0] if found else None
    lower = min(lows + ([upper] if upper is not None else []))
    return replace(base, status=status, value=value,
                   lower=lower if math.isfinite(lower) else every, upper=upper,
                   capacity_bound=every,
                   solve_time=live.solve_time + dead.solve_time,
                   nodes=live.nodes + dead.nodes, notes=tuple(merged), driven_by=least)


@dataclass
class _Context:
    """What the verdict is made of: the model, its bounds, the runs so far."""

    m: _Model
    cv: ConvexMethod
    f: float
    S: float
    V: float
    low: float | None
    assoc: float | None
    #: (L,) the largest slack of each law row over the admissible states (inf: unbounded)
    s_max: np.ndarray
    #: the capacity bound (:func:`_capacity_bound`), its rounds, and whether it is a cut
    cap: float
    rounds: int
    cut: bool
    node_limit: int | None = None
    #: the multiplier of a collapse state known already (see :func:`safe_multiplier`)
    collapse_at: float | None = None
    #: the family of collapse states searched (LIVE or DEAD)
    family: str = LIVE
    #: a mixed-integer solve was made
    ran: bool = False
    trials: list[tuple[float, float | None]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    elapsed: float = 0.0
    nodes: int = 0
    gap: float | None = None


def _decide(ctx: _Context, time_limit: float, double_check: bool) -> SafeMultiplier:
    """Solve at the bounds (S, V) and, with ``double_check``, at twice them; each
    answer polished (its active set's exact LP, :func:`_polish`); the verdict (see
    :class:`SafeMultiplier`)."""
    m, F = ctx.m, ctx.cv.scaling.force
    best: tuple[float, np.ndarray, float] | None = None
    dual: float | None = None
    raw: list[float] = []
    for k in (1.0, 2.0) if double_check else (1.0,):
        run = _solve_milp(m, _slack_bounds(m, k * ctx.S, ctx.s_max), k * ctx.V,
                          time_limit, ctx.cap if ctx.cut else 0.0, ctx.node_limit,
                          ctx.family)
        ctx.ran = True
        ctx.nodes += run["nodes"]
        ctx.elapsed += run["time"]
        ctx.gap = run["gap"]
        got = _checked(m, run, ctx.family)
        if got is not None and got[2] > CHECK_TOL:
            ctx.notes.append(f"the state HiGHS found fails its check: with its active set "
                             f"fixed it breaches equilibrium, laws or complementarity by "
                             f"{got[2]:.3g}")
            got = None
        if run["status"] == 1 and got is not None and got[0] <= ctx.cap + _tol(ctx.cap):
            # the least state found meets a lower bound: proven without HiGHS's bound
            ctx.notes.append(f"HiGHS stopped ({run['message']}) on a collapse state at "
                             f"{got[0]:.9g}, which the capacity bound {ctx.cap:.9g} "
                             "proves least")
            run = dict(run, status=0, dual=ctx.cap)
        if run["status"] not in (0, 2) or (run["status"] == 0 and got is None):
            up = None if got is None else got[0]
            found = "a collapse state found"
            known = ctx.collapse_at
            if known is not None and (up is None or known < up):
                up, found = known, "the answer's collapse state"
            lo = ctx.cap if run["dual"] is None else max(float(run["dual"]), ctx.cap)
            gap = "" if run["gap"] is None else f", gap {100 * float(run['gap']):.3g}%"
            ctx.notes.append(f"HiGHS did not prove the least multiplier ({run['message']}"
                             f", {run['nodes']} nodes{gap}) within the bounds"
                             f"{' doubled' if k > 1 else ''}: it lies in [{_fmt(lo)}, "
                             f"{_fmt(up)}]" + ("" if up is None else
                                              f" ({_fmt(up)}: {found})"))
            return _result(ctx, UNDECIDED, None, run["dual"], up, got)
        ctx.trials.append((k * ctx.S * F, None if got is None else got[0]))
        if got is None:
            continue
        raw.append(run["value"])
        if best is None:
            best, dual = got, run["dual"]
        elif got[0] < best[0]:
            best = got
    if best is None:
        ctx.notes.append(f"HiGHS finds no collapse state within the bounds (nor doubled) "
                         f"at 0 <= lambda <= {_fmt(ctx.assoc)} (the associative "
                         "multiplier, above which no state is admissible); no certificate "
                         "that none exists beyond the bounds")
        return _result(ctx, NONE_WITHIN_BOUNDS, None, None, None, None)
    values = [v for _, v in ctx.trials] + raw
    if not all(v is not None and _same(v, best[0]) for v in values):
        ctx.notes.append("the least multiplier depends on the bounds: "
                         + ", ".join(f"{_fmt(v)} with {what}" for (_, v), what in
                                     zip(ctx.trials, ("them", "them doubled"), strict=False))
                         + f" (HiGHS's values {', '.join(_fmt(v) for v in raw)}, each "
                           "answer's joint states solved again without bounds): no safe "
                           "value, only the least collapse state found")
        return _result(ctx, BOUND_DEPENDENT, None, None, best[0], best)
    lower = best[0] if dual is None else min(float(dual), best[0])
    return _result(ctx, OPTIMAL, best[0], lower, best[0], best)


def _fmt(v: float | None) -> str:
    return "none" if v is None else f"{v:.9g}"


def _result(ctx: _Context, status: str, value: float | None, lower: float | None,
            upper: float | None, best: tuple[float, np.ndarray, float] | None
            ) -> SafeMultiplier:
    cv, notes = ctx.cv, ctx.notes
    F = cv.scaling.force
    sysm = cv.system
    n, ne = sysm.layout.size, sysm.n_rows
    st = mech = None
    if best is not None:
        sol = best[1]
        st = force_state(sysm, sol[:n] * F, "a non-associative collapse state of the "
                         "least multiplier over all states")
        mech = mechanism(sysm, cv.scaling.row, sol[n + 1:n + 1 + ne], "vertex", sol[:n] * F,
                         sysm.dead if ctx.family == DEAD else None)
    tol = SAME * max(1.0, abs(upper or 0.0))
    if upper is not None and ctx.low is not None and upper < ctx.low - tol:
        notes.append(f"the state found ({upper:.9g}) is below the frictionless bound "
                     f"{ctx.low:.9g} (Drucker 1954): a defect")
    if upper is not None and ctx.assoc is not None and upper > ctx.assoc + tol:
        notes.append(f"the state found ({upper:.9g}) is above the associative multiplier "
                     f"{ctx.assoc:.9g} (static theorem): a defect")
    if not ctx.ran:  # decided before any mixed-integer solve
        return SafeMultiplier(status=status, value=None, lower=None, upper=None,
                              friction=ctx.f, frictionless=None, associative=ctx.assoc,
                              capacity_bound=None, bound_rounds=0, force_bound=ctx.S * F,
                              velocity_bound=ctx.V, reference_force=F, notes=tuple(notes))
    k = 2.0 if len(ctx.trials) > 1 else 1.0
    free = int(np.sum(~np.isfinite(ctx.s_max)))
    forces = (f"normal forces up to {k * ctx.S * F:.6g} on the {free} of {len(ctx.s_max)} "
              "joint laws the admissible states do not bound, " if free else
              "normal forces as large as any admissible state's (bounded by the "
              "structure: the force bound does not enter) and ")
    notes.append(f"smallest over the collapse states with {forces}openings or slips up to "
                 f"{k * ctx.V:.6g} per unit work of the {ctx.family} load (in units of "
                 f"{F:.6g} x "
                 "one length unit)")
    lower = ctx.cap if lower is None or not math.isfinite(lower) else \
        max(float(lower), ctx.cap)
    if upper is not None:
        lower = min(lower, upper)
    return SafeMultiplier(status=status, value=value, lower=lower, upper=upper,
                          friction=ctx.f, frictionless=ctx.low, associative=ctx.assoc,
                          capacity_bound=ctx.cap, bound_rounds=ctx.rounds,
                          force_bound=k * ctx.S * F, velocity_bound=k * ctx.V,
                          reference_force=F, state=st, mechanism=mech,
                          trials=tuple(ctx.trials), solve_time=ctx.elapsed,
                          nodes=ctx.nodes, gap=ctx.gap, n_binaries=ctx.m.G.shape[0],
                          breach=None if best is None else best[2], notes=tuple(notes))


__all__ = ["SafeMultiplier", "safe_multiplier"]
