"""The analyses: admissibility, minimum friction and maximum load multiplier.

Each function takes a scene, builds the problem (:mod:`.formulation`), hands it to a
back end (:mod:`rigidblocks.solvers`) and returns an immutable result
(:mod:`rigidblocks.results`). Solver failures raise
:class:`~rigidblocks.errors.SolverFailure`; "no admissible state" is a status.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
import scipy.sparse as sp

from ..contacts import Contacts
from ..equilibrium import EquilibriumSystem, assemble
from ..errors import InputError, SolverFailure
from ..results import CheckResult, ForceState, FrictionResult, LoadResult, Mechanism
from ..scene.model import INFINITE, Scene
from ..solvers import INFEASIBLE, OPTIMAL, UNBOUNDED, SolverResult, solve
from .formulation import Scaling, build_energy_qp, build_max_load, build_relaxation

#: a relaxation below this fraction of the largest force of its state counts as zero
#: (interior-point residuals are relative to the size of the solution: a 30-course wall
#: carries 30 block weights at its base, and R carries round-off of that order)
ADMISSIBLE_TOL = 1e-9
#: solver tolerances for the relaxation problems (tight: R decides verdicts near 0)
RELAX_SETTINGS = {"tol_gap_abs": 1e-10, "tol_gap_rel": 1e-10, "tol_feas": 1e-10}
#: the same for other back ends whose defaults are looser than the verdict threshold
TIGHT_SETTINGS = {
    "clarabel": RELAX_SETTINGS,
    "cvxpy-highs": {"primal_feasibility_tolerance": 1e-10,
                    "dual_feasibility_tolerance": 1e-10},
    "cvxpy-clarabel": RELAX_SETTINGS,
}
#: retry settings when a solve ends short of optimal: KKT systems regularised and refined
#: further. Where the interior-point iteration is near-degenerate a rounding decides
#: between "Solved" and "AlmostSolved" (the max-load SOCP of the extruded stocky arch with
#: glued pieces, tests/test_extrude_all.py, shifted by 1e-12 or by (3, 2)); a static
#: regularisation of 1e-7 (default 1e-8) with refined linear solves settles it.
REFINE_SETTINGS = {"clarabel": {"static_regularization_constant": 1e-7,
                                "iterative_refinement_reltol": 1e-14,
                                "iterative_refinement_abstol": 1e-14}}
#: relative accuracy of the minimum friction
FRICTION_RTOL = 1e-7
#: absolute accuracy of the minimum friction: a structure that stands with f <= 1e-9
#: needs no friction (round-off keeps R(0) just above the threshold)
FRICTION_ATOL = 1e-9
METHODS = ("clarabel", "distortion")
#: slack (reference-force units) granted to the force-state QP at a limit state, where
#: the admissible set shrinks to a point and round-off would make it empty
STATE_SLACK = 1e-9
#: a joint's opening or slip below this fraction of the mechanism's largest counts as
#: none when joints are classified (interior-point duals spread round-off of the order
#: of the solver's tolerance over every joint)
MODE_TOL = 1e-6
#: back ends that solve linear programs only (the force-state QP goes to Clarabel)
LP_ONLY = ("highs",)


# -- shared plumbing ------------------------------------------------------------------
def resolve_friction(scene: Scene, friction: Any) -> float:
    """The uniform friction coefficient to use (``math.inf`` for "infinite")."""
    f = scene.effective_friction if friction is None else friction
    if isinstance(f, str):
        if f.strip().lower() in ("infinite", "inf"):
            return math.inf
        try:
            f = float(f)
        except ValueError:
            raise InputError(f'friction must be a number >= 0 or "infinite", got {f!r}') \
                from None
    f = float(f)
    if not (f >= 0):
        raise InputError(f"friction must be >= 0, got {f}")
    return f


def friction_label(f: float) -> Any:
    return INFINITE if math.isinf(f) else f


def split_method(method: str, solver: str | None) -> tuple[str, str]:
    """(path, solver) from the ``method`` and ``solver`` arguments."""
    m = method.lower()
    if m == "distortion":
        return "distortion", "distortion"
    if m in ("clarabel", "convex"):
        return "convex", (solver or "clarabel")
    from ..solvers import SOLVERS

    if m in SOLVERS or m.startswith("cvxpy-"):
        return "convex", m
    raise InputError(f"unknown method {method!r} (choose from {', '.join(METHODS)}, or a "
                     "solver name for the convex path)")


@dataclass
class _Context:
    scene: Scene
    system: EquilibriumSystem
    scaling: Scaling
    solver: str
    settings: dict
    pyramid: int | None = None
    n_solves: int = 0
    solve_time: float = 0.0
    iterations: int = 0
    notes: list[str] = field(default_factory=list)
    #: relaxation problems by load factor, with the entries proportional to f
    relax_cache: dict = field(default_factory=dict)

    @property
    def contacts(self) -> Contacts:
        return self.system.contacts

    def f_joint(self, f_uniform: float) -> np.ndarray:
        o = self.contacts.override_friction
        return np.where(np.isnan(o), f_uniform, o)

    @property
    def uniform(self) -> np.ndarray:
        return np.isnan(self.contacts.override_friction)

    def run(self, problem, what: str, tight: bool = False) -> SolverResult:
        settings = self.settings
        solver = self.solver
        if problem.P is not None and solver in LP_ONLY:
            # the force state is a QP: an LP-only back end hands it to Clarabel
            solver, settings = "clarabel", {}
        if tight and solver in TIGHT_SETTINGS:
            settings = {**TIGHT_SETTINGS[solver], **settings}
        base = self.settings if solver == self.solver else {}
        res = solve(problem, solver, **settings)
        refine = REFINE_SETTINGS.get(solver, {})
        if res.status not in (OPTIMAL, INFEASIBLE, UNBOUNDED) and refine and \
                not refine.keys() & settings.keys():
            self.n_solves += 1
            self.solve_time += res.solve_time
            self.iterations += res.iterations
            res = solve(problem, solver, **{**settings, **refine})
        if res.status not in (OPTIMAL, INFEASIBLE, UNBOUNDED) and settings is not base:
            # the tight tolerances were out of reach: the solver's defaults decide
            self.n_solves += 1
            self.solve_time += res.solve_time
            self.iterations += res.iterations
            res = solve(problem, solver, **base)
        self.n_solves += 1
        self.solve_time += res.solve_time
        self.iterations += res.iterations
        if res.status not in (OPTIMAL, INFEASIBLE, UNBOUNDED):
            raise SolverFailure(f"{res.solver} could not solve the {what} problem of "
                                f"{self.scene.source or 'the scene'}: status "
                                f"{res.raw_status}", res.solver, res.raw_status)
        return res

    def common(self, analysis: str, status: str, friction: Any, load_factor: float | None):
        return dict(analysis=analysis, status=status, friction=friction,
                    load_factor=load_factor, contacts=self.contacts, solver=self.solver,
                    n_solves=self.n_solves, solve_time=self.solve_time,
                    iterations=self.iterations,
                    units=(self.scene.length_unit, self.scene.force_unit),
                    notes=tuple(self.notes))


def _context(scene: Scene, solver: str, settings: dict | None,
             pyramid: int | None = None, contact_tol: float | None = None) -> _Context:
    if contact_tol is None:
        system = assemble(scene)
    else:
        tol = float(contact_tol)
        if not (tol > 0 and math.isfinite(tol)):
            raise InputError(f"contact_tol must be a number > 0, got {contact_tol!r}")
        system = assemble(scene, tol=tol)
    ctx = _Context(scene, system, Scaling.of(system), solver, dict(settings or {}),
                   pyramid=pyramid)
    if pyramid is not None:
        if scene.dimension != 3:
            raise InputError("the friction pyramid is an option of 3D scenes only")
        if int(pyramid) < 3:
            raise InputError(f"a friction pyramid needs at least 3 facets, got {pyramid}")
        ctx.notes.append(f"friction cones linearised as inscribed {int(pyramid)}-facet "
                         "pyramids (an approximation: not the Coulomb cone)")
    loose = sorted(k for k, v in ctx.settings.items()
                   if k.startswith("tol") and isinstance(v, int | float) and v > 1e-9)
    if loose:
        ctx.notes.append(f"solver tolerances looser than 1e-9 ({', '.join(loose)}): "
                         "verdicts rest on a relaxation compared with 1e-9 of the largest "
                         "force and may be wrong near a limit")
    return ctx


def _no_contact_tol(contact_tol: float | None) -> None:
    if contact_tol is not None:
        raise InputError("contact_tol is an option of the convex path, not of the "
                         "distortion method")


# -- relaxation ----------------------------------------------------------------------
@dataclass(frozen=True)
class _Relax:
    """One relaxation solve: R(f), dR/df, and what the analyses read from it."""

    R: float | None  # None: the equilibrium equations have no solution
    slope: float
    res: SolverResult
    jr: Any
    prob: Any
    tol: float  # R <= tol counts as zero (ADMISSIBLE_TOL x the largest scaled force)

    @property
    def zero(self) -> bool:
        return self.R is not None and self.R <= self.tol


def _relaxation_problem(ctx: _Context, f_uniform: float, load_factor: float):
    """The relaxation at friction ``f_uniform``, built once per load factor.

    The uniform friction enters the constraint matrix only as coefficients proportional
    to f (the f N term of each friction row): from the second finite f at a load factor
    on, the problem is built at f = 1 and f = 2, the entries that double are located,
    and later values of f only rescale them.
    """
    def build(f: float):
        return build_relaxation(ctx.system, ctx.scaling, ctx.f_joint(f), load_factor,
                                ctx.pyramid)

    if not math.isfinite(f_uniform):
        return build(f_uniform)
    cached = ctx.relax_cache.get(load_factor)
    if cached is None:  # a single check builds once; a second f builds the template
        ctx.relax_cache[load_factor] = "seen"
        return build(f_uniform)
    if cached == "seen":
        (p1, jr), (p2, _) = build(1.0), build(2.0)
        A1, A2 = p1.A, p2.A
        same = (np.array_equal(A1.indptr, A2.indptr) and np.array_equal(A1.indices, A2.indices)
                and np.array_equal(p1.b, p2.b))
        mask = A1.data != A2.data if same else None
        if same and np.allclose(A2.data[mask], 2.0 * A1.data[mask], rtol=1e-14, atol=0):
            cached = (p1, jr, mask, A1.data[mask])
        else:
            cached = False
        ctx.relax_cache[load_factor] = cached
    if not cached:
        return build(f_uniform)
    p1, jr, mask, coef = cached
    data = p1.A.data.copy()
    data[mask] = coef * f_uniform
    A = sp.csc_matrix((data, p1.A.indices, p1.A.indptr), shape=p1.A.shape)
    return replace(p1, A=A), jr


def _relaxation(ctx: _Context, f_uniform: float, load_factor: float) -> _Relax:
    """R(f) and dR/df (from the duals of the friction rows of the uniform joints)."""
    prob, jr = _relaxation_problem(ctx, f_uniform, load_factor)
    res = ctx.run(prob, "relaxation", tight=True)
    if res.status != OPTIMAL:
        return _Relax(None, 0.0, res, jr, prob, ADMISSIBLE_TOL)
    z, y = res.z, res.y
    R = max(float(z[prob.cols["r"]][0]), 0.0)
    x = z[prob.cols["x"]]
    tol = ADMISSIBLE_TOL * max(1.0, float(np.max(np.abs(x), initial=0.0)))
    head = prob.rows["joints"].start + jr.fric_head
    uni = ctx.uniform[jr.fric_joint]
    nsum = jr.fric_nsum @ z
    slope = float(np.sum(y[head][uni] * nsum[uni]))
    return _Relax(R, slope, res, jr, prob, tol)


def _state(ctx: _Context, f_uniform: float, load_factor: float, relax: float,
           limit: SolverResult, limit_x: slice) -> ForceState:
    """The admissible state of least complementary energy (a QP).

    At a limit state the admissible set shrinks to (nearly) one point and the QP can be
    out of the interior-point solver's reach (3D cones sliding all round a bed joint);
    the state of the solved limit problem ``limit`` (an admissible state, not the
    least-energy one) is then returned, and the result's notes say so.
    """
    prob = build_energy_qp(ctx.system, ctx.scaling, ctx.f_joint(f_uniform), load_factor,
                           relax, ctx.pyramid)
    try:
        res = ctx.run(prob, "force-state")
        status = res.raw_status if res.status != OPTIMAL else None
    except SolverFailure as exc:
        status = exc.status
    if status is None:
        return force_state(ctx.system, res.z[prob.cols["x"]] * ctx.scaling.force,
                           "least complementary energy")
    ctx.notes.append(f"force state: the solution of the limit problem (the "
                     f"least-energy QP ended with status {status})")
    return force_state(ctx.system, limit.z[limit_x] * ctx.scaling.force,
                       "solution of the limit problem")


def force_state(system: EquilibriumSystem, x: np.ndarray, method: str) -> ForceState:
    """Joint resultants, eccentricities and the thrust line of link forces ``x``."""
    c = system.contacts
    lay = system.layout
    pj = c.point_joint
    m = c.n_joints
    N = x[lay.normal]
    Nj = np.bincount(pj, N, minlength=m)
    d = c.dimension
    if d == 2:
        if lay.shear == "joint":
            Tj = x[lay.tangential]
            share = np.where(Nj[pj] > 0, N / np.where(Nj[pj] > 0, Nj[pj], 1.0),
                             1.0 / np.diff(c.joint_start)[pj])
            T = Tj[pj] * share
        else:
            T = x[lay.tangential]
            Tj = np.bincount(pj, T, minlength=m)
        mid = 0.5 * (c.points[c.joint_start[:-1]] + c.points[c.joint_start[1:] - 1])
        s = c.tangents[:, 0, :]
        arm = np.einsum("ij,ij->i", c.points - mid[pj], s[pj])
        with np.errstate(invalid="ignore", divide="ignore"):
            ecc = np.bincount(pj, N * arm, minlength=m) / Nj
        ecc = np.where(np.abs(Nj) > 0, ecc, np.nan)
        thrust = mid + np.nan_to_num(ecc)[:, None] * s
        Tabs = np.abs(Tj)
    else:
        T = x[lay.tangential].reshape(-1, 2)
        Tvec = np.zeros((m, 3))
        for k in range(2):
            np.add.at(Tvec, pj, T[:, k:k + 1] * c.tangents[pj, k, :])
        Tabs = np.linalg.norm(Tvec, axis=1)
        Tj = Tabs
        with np.errstate(invalid="ignore", divide="ignore"):
            centre = np.stack([np.bincount(pj, N * c.points[:, k], minlength=m)
                               for k in range(3)], axis=1) / Nj[:, None]
        ecc = np.full(m, np.nan)
        thrust = np.where(np.isfinite(centre), centre, 0.0)
    scale = max(float(np.abs(Nj).max(initial=0.0)), 1e-300)
    with np.errstate(invalid="ignore", divide="ignore"):
        demand = np.where(Nj > 1e-12 * scale, Tabs / np.where(Nj > 0, Nj, 1.0),
                          np.where(Tabs > 1e-12 * scale, np.inf, 0.0))
    return ForceState(normal=N, shear=T, joint_normal=Nj, joint_shear=Tj, eccentricity=ecc,
                      demand=demand, thrust_points=thrust,
                      thrust_order=chain_order(system), method=method)


def chain_order(system: EquilibriumSystem) -> np.ndarray:
    """Joints in order along the structure when the blocks form a chain (an arch).

    A chain: every free block has exactly two joints, to different neighbours, and the
    walk from a support reaches every joint. Otherwise joints keep detection order.
    """
    c = system.contacts
    m = c.n_joints
    fallback = np.arange(m)
    free = system.block_rows >= 0
    deg = np.bincount(c.pairs.ravel(), minlength=len(free))
    if m == 0 or np.any(deg[free] != 2):
        return fallback
    by_block: dict[int, list[int]] = {}
    for k, (a, b) in enumerate(c.pairs):
        by_block.setdefault(int(a), []).append(k)
        by_block.setdefault(int(b), []).append(k)
    starts = [k for k in range(m) if not (free[c.pairs[k, 0]] and free[c.pairs[k, 1]])]
    if not starts:
        return fallback
    k = starts[0]
    a, b = c.pairs[k]
    here = int(b) if free[b] else int(a)
    order = [k]
    used = {k}
    while free[here]:
        nxt = [j for j in by_block[here] if j not in used]
        if len(nxt) != 1:
            return fallback
        k = nxt[0]
        used.add(k)
        order.append(k)
        a, b = c.pairs[k]
        here = int(b) if int(a) == here else int(a)
    return np.array(order) if len(order) == m else fallback


# -- check ---------------------------------------------------------------------------
def check(scene: Scene, friction: Any = None, load_factor: float = 1.0,
          method: str = "clarabel", *, solver: str | None = None, state: bool = True,
          settings: dict | None = None, pyramid: int | None = None,
          contact_tol: float | None = None) -> CheckResult:
    """Is there an admissible equilibrium state under dead + load_factor x live?

    Admissible: equilibrium of every free block with compression-only contacts (or
    bounded tension where a joint has a tensile strength) and shear within the Coulomb
    limit |T| <= f N + c A (static theorem of limit analysis).

    Args:
        scene: the structure.
        friction: uniform friction coefficient (None: the scene's; "infinite":
            Heyman's no-sliding hypothesis). Joints with an override keep theirs.
        load_factor: lambda multiplying the live loads.
        method: "clarabel" (convex path) or "distortion" (the iterative solver).
        solver: back end of the convex path (see :func:`rigidblocks.solvers.solve`).
        state: compute the force state (least complementary energy) when admissible.
        pyramid: 3D only: linearise each Coulomb cone as an inscribed pyramid of this
            many facets (an approximation, labelled in the result's notes).
        contact_tol: contact-detection tolerance relative to the scene's size (None:
            the default 1e-7, see :func:`rigidblocks.contacts.detect_contacts`). Faces
            or edges whose planes (lines) are closer than ``contact_tol x scene size``
            are taken as touching: raise it for geometry with gaps or overlaps from
            rounding (e.g. 1e-5 for coordinates exported to micrometres on a 5 m
            model). Convex path only.

    Returns:
        :class:`~rigidblocks.results.CheckResult` with status "admissible" or
        "inadmissible".

    Notes:
        Posed as the relaxation R = min r over equilibrium states whose joint-law
        violations are all <= r (r >= 0, forces scaled to order one); admissible iff
        R <= 1e-9 of the largest force of the relaxation's state (the interior-point
        solver's accuracy is relative to the size of its solution). The relaxation is
        always feasible when the equilibrium equations can be met, so it avoids the
        degenerate feasibility problems at the limit.
    """
    path, solver = split_method(method, solver)
    f = resolve_friction(scene, friction)
    if path == "distortion":
        from ..solvers.distortion import check_distortion

        _no_contact_tol(contact_tol)
        return check_distortion(scene, f, float(load_factor), state=state)
    ctx = _context(scene, solver, settings, pyramid, contact_tol)
    rx = _relaxation(ctx, f, float(load_factor))
    if rx.R is None:  # equilibrium equations cannot be met at all: a mechanism
        ctx.notes.append("the equilibrium equations have no solution with these joints "
                         "(the scene is a mechanism)")
        ok, viol = False, math.inf
    else:
        ok, viol = rx.zero, rx.R * ctx.scaling.force
    st = (_state(ctx, f, float(load_factor), rx.R + STATE_SLACK, rx.res, rx.prob.cols["x"])
          if (ok and state) else None)
    return CheckResult(**ctx.common("check", "admissible" if ok else "inadmissible",
                                    friction_label(f), float(load_factor)),
                       state=st, admissible=ok, violation=0.0 if ok else viol)


# -- minimum friction ------------------------------------------------------------------
def min_friction(scene: Scene, load_factor: float = 1.0, method: str = "clarabel", *,
                 solver: str | None = None, state: bool = True, rtol: float = FRICTION_RTOL,
                 settings: dict | None = None, pyramid: int | None = None,
                 contact_tol: float | None = None) -> FrictionResult:
    """The smallest uniform friction coefficient f* that admits equilibrium.

    Joints with their own friction override keep it. Status "unstable" (no number)
    when even infinite friction admits no equilibrium: the structure fails by hinging.

    Notes:
        R(f), the smallest violation of the joint laws at friction f (see
        :func:`check`), is zero for f >= f* and positive below. Starting from f = 0,
        Newton steps f <- f + R(f) / (-dR/df) use the derivative from the duals of the
        friction rows (dR/df = -sum_r y_r N_r, envelope theorem), with a bracket
        [lower, upper] and bisection as a safeguard. Every step solves an always
        feasible LP (SOCP in 3D); a few solves reach ``rtol``.
    """
    path, solver = split_method(method, solver)
    lf = float(load_factor)
    if path == "distortion":
        from ..solvers.distortion import min_friction_distortion

        _no_contact_tol(contact_tol)
        return min_friction_distortion(scene, lf, state=state, rtol=rtol)
    ctx = _context(scene, solver, settings, pyramid, contact_tol)
    if ctx.contacts.n_joints and not ctx.uniform.any():
        raise InputError("every joint has its own friction override: there is no uniform "
                         "friction to minimise", scene.source)
    rx = _relaxation(ctx, math.inf, lf)
    if not rx.zero:
        if rx.R is None:
            ctx.notes.append("the equilibrium equations have no solution (mechanism)")
        return FrictionResult(**ctx.common("min_friction", "unstable", None, lf))
    lo, hi, at_hi = 0.0, math.inf, rx  # at_hi: the relaxation at the upper end
    rx = _relaxation(ctx, 0.0, lf)
    if rx.R is None:
        raise SolverFailure("the relaxation at f = 0 has no solution although infinite "
                            "friction has one", ctx.solver, rx.res.raw_status)
    last = None
    if rx.zero:
        hi, at_hi = 0.0, rx
    else:
        last = rx
    R_lo, s_lo = rx.R, rx.slope
    prev: tuple[float, float] | None = None  # (f, slope) of the previous lower point
    probe_below_hi = True  # next time Newton lands on or past hi, probe just below hi
    forced: float | None = None  # the next trial, after a relaxation the solver missed
    undecided = ""  # the solver's status where it could not decide near f*
    for _ in range(100):
        if math.isfinite(hi) and hi - lo <= rtol * hi + FRICTION_ATOL:
            break
        newton = lo + _root_step(R_lo, s_lo, lo, prev) if s_lo > 0 else math.inf
        if forced is not None:
            trial, forced = forced, None
        elif math.isinf(hi):
            trial = newton if math.isfinite(newton) else max(2.0 * lo, 1.0)
            if trial - lo <= 0.5 * rtol * trial:
                trial = trial * (1.0 + 0.5 * rtol)  # certify from above
        elif lo < newton < hi * (1.0 - 0.5 * rtol):
            trial = newton
            if trial - lo <= 0.5 * rtol * trial:
                trial = min(trial * (1.0 + 0.5 * rtol), hi * (1.0 - 0.25 * rtol))
        elif probe_below_hi:
            trial = hi * (1.0 - 0.5 * rtol)
            probe_below_hi = False
        else:
            trial = 0.5 * (lo + hi)
            probe_below_hi = True
        try:
            rx = _relaxation(ctx, trial, lf)
        except SolverFailure as exc:
            # just below f* the relaxation can be too degenerate for the interior-point
            # solver: probe four times further below the certified upper end
            if not math.isfinite(hi) or trial < hi * (1.0 - 1e3 * rtol):
                raise
            undecided = exc.status
            forced = hi - 4.0 * (hi - trial)
            if forced <= lo:
                break
            continue
        if rx.R is None:
            raise SolverFailure("relaxation problem lost its solution", ctx.solver,
                                rx.res.raw_status)
        if rx.zero:
            hi, at_hi = trial, rx
        else:
            prev = (lo, s_lo)
            lo, R_lo, s_lo = trial, rx.R, rx.slope
            last = rx
    else:
        raise SolverFailure("minimum friction did not converge in 100 solves", ctx.solver,
                            "iteration limit")
    if undecided:
        ctx.notes.append(f"near f* some relaxations ended with status {undecided}; f* is "
                         f"bracketed in [{lo:.10g}, {hi:.10g}] (relative width "
                         f"{(hi - lo) / hi:.1e})")
    fstar = hi
    governing: tuple[int, ...] = ()
    if last is not None:
        res, jr, prob = last.res, last.jr, last.prob
        head = prob.rows["joints"].start + jr.fric_head
        # each friction row's share of -dR/df, y_r N_r: a joint whose normal force
        # vanishes (an opening joint carrying only the relaxation's slack) does not govern
        w = res.y[head] * (jr.fric_nsum @ res.z) * ctx.uniform[jr.fric_joint]
        if w.size and w.max() > 0:
            strong = w > 1e-3 * w.max()
            governing = tuple(sorted({int(j) for j in jr.fric_joint[strong]}))
    st = (_state(ctx, fstar, lf, at_hi.R + STATE_SLACK, at_hi.res, at_hi.prob.cols["x"])
          if state else None)
    return FrictionResult(**ctx.common("min_friction", "stable", fstar, lf), state=st,
                          governing=governing, friction_factor=fstar,
                          friction_angle_deg=math.degrees(math.atan(fstar)),
                          lower=lo, upper=hi)


def _root_step(R: float, s: float, f: float, prev: tuple[float, float] | None) -> float:
    """Step from a lower point (R(f) = R > 0, -dR/df = s > 0) to the estimated root.

    Newton's step R / s, or, where the slope has grown since the previous lower point
    (R concave there, so Newton overshoots), the root of the quadratic model
    R - s d - c d^2 / 2 with the curvature c = ds/df from the two slopes.
    """
    if prev is not None and f > prev[0] and s > prev[1]:
        c = (s - prev[1]) / (f - prev[0])
        return 2.0 * R / (s + math.sqrt(s * s + 2.0 * c * R))
    return R / s


# -- maximum load multiplier -------------------------------------------------------------
def max_load_multiplier(scene: Scene, friction: Any = None, method: str = "clarabel", *,
                        solver: str | None = None, state: bool = True,
                        settings: dict | None = None, pyramid: int | None = None,
                        contact_tol: float | None = None) -> LoadResult:
    """The largest multiplier lambda* of the live loads (associative friction).

    Status "collapse" with lambda* and the collapse mechanism; "unbounded" when no
    multiplier makes the structure collapse; "unstable" when the dead load alone has no
    admissible state.

    Notes:
        One LP (SOCP in 3D): max lambda s.t. A x + F_dead + lambda F_live = 0 and the
        joint laws. By LP duality the multipliers of the equilibrium rows are the
        virtual velocities of a mechanism whose joint displacements satisfy the
        associative flow rule (normal opening >= f |slip|) and in which the loads do
        no net work (kinematic theorem). Solved at the tight tolerances of the
        relaxations: at Clarabel's defaults (1e-8) lambda* of a 1,000-block wall is off
        by 7e-5 (its toe carries a thousand block weights, and the residuals are
        relative to that), at 1e-10 by 4e-6 of the simplex (HiGHS) answer, for 1.4x
        the interior-point iterations.
    """
    if not scene.has_live_load:
        raise InputError("the scene has no live load (no \"live\": true load and no "
                         "live_body_force): there is nothing to multiply", scene.source)
    path, solver = split_method(method, solver)
    f = resolve_friction(scene, friction)
    if path == "distortion":
        from ..solvers.distortion import max_load_distortion

        _no_contact_tol(contact_tol)
        return max_load_distortion(scene, f, state=state)
    ctx = _context(scene, solver, settings, pyramid, contact_tol)
    prob, jr = build_max_load(ctx.system, ctx.scaling, ctx.f_joint(f), ctx.pyramid)
    res = ctx.run(prob, "maximum load", tight=True)
    label = friction_label(f)
    if res.status == UNBOUNDED:
        status = "unbounded" if _dead_admissible(ctx, f) else "unstable"
        return LoadResult(**ctx.common("max_load_multiplier", status, label, None))
    if res.status == INFEASIBLE:
        return LoadResult(**ctx.common("max_load_multiplier", "unstable", label, None))
    lam = float(res.z[prob.cols["lambda"]][0])
    if lam < -ADMISSIBLE_TOL:
        ctx.notes.append(f"the largest admissible multiplier is negative ({lam:.6g}): the "
                         "dead load alone is not admissible")
        return LoadResult(**ctx.common("max_load_multiplier", "unstable", label, None))
    if not _dead_admissible(ctx, f):
        ctx.notes.append(f"largest admissible multiplier {lam:.6g}, but only with the live "
                         "load propping the structure up")
        return LoadResult(**ctx.common("max_load_multiplier", "unstable", label, None))
    mech = mechanism(ctx.system, ctx.scaling, res.y[prob.rows["equilibrium"]])
    sliding = tuple(k for k, md in enumerate(mech.modes) if md.startswith("slide"))
    st = _state(ctx, f, lam, STATE_SLACK, res, prob.cols["x"]) if state else None
    return LoadResult(**ctx.common("max_load_multiplier", "collapse", label, lam), state=st,
                      governing=sliding, load_multiplier=lam, mechanism=mech)


def _dead_admissible(ctx: _Context, f: float) -> bool:
    """Is lambda = 0 admissible? The admissible multipliers form an interval, which may
    lie wholly above 0 when the live load props up a structure that cannot stand under
    its dead load alone. One relaxation solve (none when there is no dead load)."""
    if not np.any(ctx.system.dead):
        return True
    if not _relaxation(ctx, f, 0.0).zero:
        ctx.notes.append("the dead load alone is not admissible")
        return False
    return True


def mechanism(system: EquilibriumSystem, scaling: Scaling, y_eq: np.ndarray) -> Mechanism:
    """Virtual velocities from the duals of the (scaled) equilibrium rows."""
    v = scaling.row * y_eq
    if v @ system.live < 0:
        v = -v
    d = system.dofs
    free = system.free_blocks
    vb = v.reshape(-1, d)
    nd = system.contacts.dimension
    mag = np.linalg.norm(vb[:, :nd], axis=1) + np.linalg.norm(vb[:, nd:], axis=1) * \
        system.sizes[free]
    top = mag.max(initial=0.0)
    if top > 0:
        v = v / top
    vel = np.zeros((len(system.block_rows), d))
    vel[free] = v.reshape(-1, d)
    delta = system.A.T @ v  # relative displacements at the links
    lay = system.layout
    c = system.contacts
    opening = delta[lay.normal]
    slip = delta[lay.tangential]
    tol = MODE_TOL * max(np.abs(delta).max(initial=0.0), 1e-300)
    modes = []
    for k in range(c.n_joints):
        pts = slice(c.joint_start[k], c.joint_start[k + 1])
        dn = opening[pts]
        if lay.shear == "joint" and nd == 2:
            ds = abs(slip[k])
        else:
            ds = float(np.abs(slip.reshape(len(opening), -1)[pts]).max())
        uneven = dn.max() - dn.min() > tol
        if ds > tol:
            modes.append("slide+hinge" if uneven else "slide")
        elif dn.max() > tol:
            modes.append("hinge" if dn.min() <= tol else "open")
        else:
            modes.append("closed")
    return Mechanism(velocities=vel, opening=opening, slip=slip, modes=tuple(modes))
