"""The analyses: admissibility, minimum friction and maximum load multiplier.

Each is written once, on top of the method interface (:mod:`rigidblocks.methods`):
:func:`check` asks a method for its verdict at (f, lambda); :func:`min_friction` and
:func:`max_load_multiplier` take the method's fast path where it has one and otherwise
bisect on its verdicts (:mod:`.search`). Results are immutable
(:mod:`rigidblocks.results`). Solver failures of the convex path raise
:class:`~rigidblocks.errors.SolverFailure`; "no admissible state" is a status.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import replace
from typing import Any

from ..errors import InputError, SolverFailure, finite_number
from ..methods import ADMISSIBLE, INADMISSIBLE, Limit, Method, Progress, open_method
from ..methods.convex import (
    ADMISSIBLE_TOL,
    FRICTION_ATOL,
    FRICTION_RTOL,
    TENSION_3D_NOTE,
    TENSION_INFINITE_NOTE,
    VERDICT_RTOL,
    bonds_pull_without_friction,
    cones_close_under_tension,
)
from ..results import (
    CheckResult,
    FrictionResult,
    LoadResult,
    fmt_safe,
    relative_width,
    within,
)
from ..scene.model import Scene, friction_label, friction_value, geometry_key, loading_keys
from ..scene.validate import check_live_load, check_load_factor, validate_scene
from .nonassociative import (
    NA_FRICTION_CEILING,
    NA_RTOL,
    check_nonassociative,
    is_nonassociative,
    max_load_nonassociative,
    min_friction_nonassociative,
)
from .notes import friction_governs, interlocking_note, unstable_note
from .search import BRACKET_ATOL, friction_by_bisection, load_by_bisection, no_number_note

#: the default accuracy of lambda*, as f*'s (FRICTION_RTOL, chosen from the chart)
LOAD_RTOL = FRICTION_RTOL


#: the finest f* an interior-point back end certifies (its verdicts' resolution)
F_RTOL_FLOOR = VERDICT_RTOL
#: the back ends whose answers are vertices (the simplex): exact verdicts, no floor
SIMPLEX = ("highs", "cvxpy-highs")


def requested_rtol(rtol: float | None, default: float) -> float:
    """The relative accuracy asked for: ``default`` where None; a number in (0, 1)
    (bad input otherwise)."""
    if rtol is None:
        return default
    if not (isinstance(rtol, int | float) and 0 < rtol < 1):
        raise InputError(f"rtol (the requested relative accuracy) must be a number in "
                         f"(0, 1), got {rtol!r}")
    return float(rtol)


def _fields(m: Method, analysis: str, status: str, friction: Any,
            load_factor: float | None) -> dict[str, Any]:
    """The fields every result shares, from the method's record of its work."""
    notes = tuple(m.notes)
    if friction is not None:
        fj = m.f_joint(friction_value(friction))
        if not cones_close_under_tension(m.system.contacts, fj):
            # (said at infinite friction too, where no cone closes and 3D gives the 2D
            # answer)
            notes = tuple(n for n in notes if n != TENSION_3D_NOTE)
        if bonds_pull_without_friction(m.system.contacts, fj):
            # (a bonded block lifted at 1.25 at infinite friction, at 1 at f = 1e6, which
            # docs/scene-format.md called the same law)
            notes += (TENSION_INFINITE_NOTE,)
    return dict(analysis=analysis, status=status, friction=friction_label(friction),
                load_factor=load_factor, contacts=m.system.contacts, solver=m.solver,
                n_solves=m.n_solves, solve_time=m.solve_time, iterations=m.iterations,
                geometry=geometry_key(m.scene), loading=loading_keys(m.scene),
                units=(m.scene.length_unit, m.scene.force_unit), notes=notes,
                timings=dict(m.timings.wall), cpu_timings=dict(m.timings.cpu),
                answered_by=m.answered_by, rejected=m.rejected)


def _load_factor(scene: Scene, value: Any) -> float:
    """The load factor asked for, or the scene's (``load_factor`` key, default 1),
    at least 0 and checked to keep the live loads it multiplies representable
    (:func:`~rigidblocks.scene.validate.check_load_factor`)."""
    if value is None:
        lf = scene.effective_load_factor
    else:
        lf = finite_number(value, "load factor", strict=True)
        if lf < 0:
            raise InputError(f"load factor must be >= 0, got {value!r}")
    check_load_factor(scene, lf)
    return lf


def certified(m: Method, lim: Limit, rtol: float, what: str, atol: float = 0.0) -> Limit:
    """The honesty rule of every limit: a number only where its certified bracket holds
    it to the requested accuracy (no wider than ``rtol`` times its larger end, or than
    ``atol`` within ``atol`` of 0: :func:`~rigidblocks.results.within`, as the searches
    stop;
    a limit with a :attr:`~rigidblocks.methods.Limit.resolution` of its own, that no
    larger than ``rtol``); otherwise "undecided" with the bracket and the accuracy it
    reached, said in the notes. The methods' searches aim at ``rtol`` but may end short
    of it at their solver's resolution."""
    reached = lim.accuracy
    if lim.value is None or reached is None:
        return lim
    if lim.resolution is not None:
        if reached <= rtol:
            return lim
    elif within(lim.lower, lim.upper, rtol, atol):
        return lim
    m.notes.append(no_number_note(what, lim.lower, lim.upper, reached, rtol))
    return replace(lim, status="undecided", value=None, at=None)


def _reached(res: Any, rtol: float | None) -> Any:
    """A result with the accuracy asked for and the one its bracket reached."""
    b = res.bracket
    return replace(res, rtol=rtol, accuracy=relative_width(*b) if b else None)


def _bracket(lim: Limit) -> tuple[float, float] | None:
    if lim.lower is None or lim.upper is None:
        return None
    return (float(lim.lower), float(lim.upper))


#: a collapse multiplier this small, known to as little, is 0: the solvers' round-off
#: of a structure that collapses under any live load (the reference model without
#: friction: 3.5e-11 from Clarabel, accuracy 1.2e-10; the simplex gives 0)
ZERO_MULTIPLIER = 1e-9


def _round_off_of_zero(lam: float, accuracy: float | None) -> float:
    small = 0 < lam <= ZERO_MULTIPLIER and accuracy is not None \
        and accuracy <= ZERO_MULTIPLIER
    return 0.0 if small else lam


def tilt_angle_deg(scene: Scene, load_multiplier: float | None) -> float | None:
    """atan(lambda* |a|) in degrees where the live load is a horizontal body force a
    (in g) and nothing else, the dead load the self-weight alone and the joints purely
    frictional: the tilt of the ground that loads the structure the same way (a
    tilting-table test: the weight turned by theta is cos(theta) times the weight plus
    tan(theta) times it sideways, and only a law without a strength of its own scales
    with it). None otherwise: a dead point load is not turned with the weight, and a
    cohesion or a tensile strength does not shrink with cos(theta) (a block with a
    cohesion of 10 read 19.29 deg, where tilted it slides at 20.11 deg)."""
    a = scene.live_body_force
    if load_multiplier is None or a is None or scene.loads:
        return None
    if any(j.cohesion or j.tensile_strength for j in scene.joints):
        return None
    if abs(a[-1]) > 0:  # a vertical component: not a tilt
        return None
    return math.degrees(math.atan(load_multiplier * math.hypot(*a[:-1])))


#: a friction above this that the solver fails on is named in the failure: the joints'
#: shear capacities f N then span many orders of magnitude beside the forces (a 4 x 4
#: wall: AlmostSolved from f = 3e5, where 1e5 gives lambda* = 2, as infinite friction)
LARGE_FRICTION = 1e4


@contextmanager
def _large_friction_named(f: float) -> Iterator[None]:
    """A solver failure at a very large finite friction says so, and names the law
    meant by it (no sliding: "infinite")."""
    try:
        yield
    except SolverFailure as err:
        if not LARGE_FRICTION < f < math.inf:
            raise
        raise SolverFailure(f"{err} (at f = {f:g}: a friction this large is beyond what "
                            "the solver resolves on this scene; \"infinite\" is the law "
                            "without sliding)", err.solver, err.status) from None


def _lower_by_the_convex_path(res: Any, scene: Scene, friction: Any, flow: str | None,
                              rtol: float, **kw: Any) -> Any:
    """The distortion method's non-associative multiplier, with a note where the convex
    path's limit iteration from X0 reaches a lower one (non-associative collapse states
    are not unique: a 4 x 4 running-bond wall at f = 1, 1 = the associative multiplier
    by the distortion method, 0.636 by the convex path, a corner wedge that rocks)."""
    try:
        other = max_load_nonassociative(scene, friction, "clarabel", flow=flow,
                                        state=False, rtol=rtol, **kw)
    except SolverFailure:
        return res
    lam, low = float(res.load_multiplier), other.load_multiplier
    if other.status == "unstable":
        # (the inclined corbel arch at f = 0.766: lambda* = 0.000534 here, UNSTABLE there,
        # with no word of it)
        return replace(res, notes=(*res.notes, (
            "the default method (the convex path: the same command without --method) "
            "finds it UNSTABLE from X0 (it does not carry even the dead load there): "
            "non-associative collapse states are not unique, and the lower is the safer")))
    if other.status != "collapse" or low is None or \
            not low < lam - rtol * max(abs(lam), 1.0):
        return res
    return replace(res, notes=(*res.notes, (
        "the default method (the convex path: the same command without --method) reaches "
        f"lambda = {fmt_safe(float(low), 6, False)} from X0, "
        "below this answer: non-associative collapse states are not unique, and the lower "
        "is the safer")))


def _below_by_the_convex_path(res: Any, scene: Scene, friction: Any, flow: str | None,
                              lf: float, **kw: Any) -> Any:
    """The distortion method's non-associative check that stands at ``lf``, with a note
    where the convex path's limit iteration from X0 collapses below it (the Arpino gate
    at f = 0.6 and lambda = 0.12: ADMISSIBLE here, where `load` by the convex path gives
    0.1187021, the smallest multiplier of any state, `load --safe`)."""
    try:
        other = max_load_nonassociative(scene, friction, "clarabel", flow=flow,
                                        state=False, **kw)
    except SolverFailure:
        return res
    low = other.load_multiplier
    if other.status != "collapse" or low is None or not low < lf:
        return res
    return replace(res, notes=(*res.notes, (
        "the default method (the convex path: the same question to `load` without "
        f"--method) collapses from X0 at lambda = {fmt_safe(float(low), 6, False)}, below "
        f"this load factor {lf:.10g}: non-associative collapse states are not unique, and "
        "the lower is the safer")))


def check(scene: Scene, friction: Any = None, load_factor: float | None = None,
          method: str = "clarabel", *, solver: str | None = None, state: bool = True,
          settings: dict | None = None, pyramid: int | None = None,
          contact_tol: float | None = None, progress: Progress | None = None,
          flow: str | None = None, compare_dry: bool = True) -> CheckResult:
    """Is there an admissible equilibrium state under dead + load_factor x live?

    Admissible: equilibrium of every free block with compression-only contacts (or
    bounded tension where a joint has a tensile strength) and shear within the Coulomb
    limit |T| <= f N + c A (static theorem of limit analysis).

    Args:
        scene: the structure.
        friction: uniform friction coefficient (None: the scene's; "infinite":
            Heyman's no-sliding hypothesis). Joints with an override keep theirs.
        load_factor: lambda multiplying the live loads (None: the scene's
            ``load_factor``, default 1).
        method: "clarabel" (convex path) or "distortion" (the iterative solver); see
            :mod:`rigidblocks.methods`.
        solver: back end of the convex path (see :func:`rigidblocks.solvers.solve`).
        state: compute the force state (least complementary energy) when admissible.
        settings: the back end's settings (convex path), or the distortion method's
            ``tol``, ``max_iter`` and ``anderson``.
        pyramid: 3D only: linearise each Coulomb cone as an inscribed pyramid of this
            many facets (an approximation, labelled in the result's notes).
        contact_tol: contact-detection tolerance relative to the scene's size (None:
            the default 1e-7, see :func:`rigidblocks.contacts.detect_contacts`). Faces
            or edges whose planes (lines) are closer than ``contact_tol x scene size``
            are taken as touching: raise it for geometry with gaps or overlaps from
            rounding (e.g. 1e-5 for coordinates exported to micrometres on a 5 m
            model). Convex path only.
        progress: a :class:`~rigidblocks.methods.Progress` the analysis keeps up to
            date (stage, solves, iterations), for a progress line.
        flow: "associative" or "non-associative" for every joint without its own
            ``flow`` (None: the scene's); see :mod:`.nonassociative`.
        compare_dry: the answer without dilatancy beside it (:data:`DILATANCY_JOINTS`).

    Returns:
        :class:`~rigidblocks.results.CheckResult` with status "admissible",
        "inadmissible", or (distortion method) "undecided" or "failure", and the
        friction demand of its state (the largest |T|/N, and the joint).

    Notes:
        Convex path: posed as the relaxation R = min r over equilibrium states whose
        joint-law violations are all <= r (r >= 0, forces scaled to order one);
        admissible iff R <= 1e-9 of the largest force of the relaxation's state (see
        :mod:`rigidblocks.methods.convex`).
    """
    validate_scene(scene)  # a scene built in code, checked as a file's is
    if is_nonassociative(scene, flow):
        lf = _load_factor(scene, load_factor)
        res = check_nonassociative(scene, friction, lf, method, flow=flow, state=state,
                                   solver=solver, settings=settings, pyramid=pyramid,
                                   contact_tol=contact_tol, progress=progress)
        if method == "distortion" and res.status == ADMISSIBLE and lf > 0 and \
                scene.has_live_load:
            res = _below_by_the_convex_path(res, scene, friction, flow, lf,
                                            pyramid=pyramid, contact_tol=contact_tol)
        return res
    f = friction_value(scene.effective_friction if friction is None else friction)
    lf = _load_factor(scene, load_factor)
    m = open_method(scene, method, solver=solver, settings=settings, pyramid=pyramid,
                    contact_tol=contact_tol, progress=progress)
    interlocking_note(m)
    with _large_friction_named(f):
        v = m.admissible(f, lf, for_state=state)
    m.explain(v)
    if v.status == INADMISSIBLE and state:  # (not in a study's bisection on verdicts)
        note = friction_governs(m, f, lf)
        m.notes += [note] if note else []
    ok = v.status == ADMISSIBLE
    st = m.state(f, lf, v) if (ok and state) else None
    breaches = m.breaches(f, v) if v.status == INADMISSIBLE else ()
    dry = _check_without_dilatancy(scene, m, f, lf, method, dict(
        solver=solver, settings=settings, pyramid=pyramid, contact_tol=contact_tol)) \
        if ok and compare_dry else None
    return CheckResult(**_fields(m, "check", v.status, f, lf), state=st,
                       admissible=v.admissible, violation=0.0 if ok else v.violation,
                       breaches=breaches, without_dilatancy=dry)


def min_friction(scene: Scene, load_factor: float | None = None,
                 method: str = "clarabel", *,
                 solver: str | None = None, state: bool = True, rtol: float | None = None,
                 settings: dict | None = None, pyramid: int | None = None,
                 contact_tol: float | None = None, progress: Progress | None = None,
                 flow: str | None = None, compare_dry: bool = True) -> FrictionResult:
    """The smallest uniform friction coefficient f* that admits equilibrium (with
    ``flow="non-associative"``: the smallest f at which the non-associative analysis
    finds the structure standing, :func:`.nonassociative.min_friction_nonassociative`).

    Joints with their own friction override keep it. Status "stable" with f*;
    "unstable" (no number) when even infinite friction admits no equilibrium: the
    structure fails by hinging; "undecided" or "failure" where the method says so.

    Notes:
        ``rtol``: the relative accuracy of f*, both the search's target and what a
        number is certified to: f* is given only where its certified bracket is no
        wider than ``rtol`` relative, else the status is "undecided" with the bracket
        and the accuracy it reached (``accuracy``); default FRICTION_RTOL = 2e-3 (three
        significant figures, chosen from the speed-accuracy chart of docs/methods.md),
        with either flow (each trial of the non-associative search is a limit run:
        the 1,041-block wall's f = 0.6 at its multiplier from X0 to 2e-3 in 3 runs,
        47.7 s, to 1e-5 in 4, 65.8 s).
        Convex path: Newton steps on the relaxation R(f), or under a live load on
        lambda*(f) = ``load_factor`` (a few solves reach ``rtol``, see
        :meth:`rigidblocks.methods.convex.ConvexMethod.friction_limit`). Other
        methods: bracketing and bisection on their verdicts to ``rtol`` (at least 1e-9:
        a verdict is only as sharp as its violation tolerance).
        ``compare_dry``: the answer without dilatancy beside it (DILATANCY_JOINTS).
    """
    validate_scene(scene)  # a scene built in code, checked as a file's is
    lf = _load_factor(scene, load_factor)
    na = is_nonassociative(scene, flow)
    rtol = requested_rtol(rtol, FRICTION_RTOL)
    # (without dilatancy too: its search starts at the static f*, found to F_RTOL_FLOOR,
    # and where that f* carries the load it is the answer; at --rtol 1e-9 a wall3d's was
    # given with an accuracy of 5.2e-8)
    if rtol < F_RTOL_FLOOR and method != "distortion" and (solver or method) not in SIMPLEX:
        raise InputError(f"rtol {rtol:g} is finer than an interior-point solver certifies f*: "
                         f"its verdicts hold to 1e-9 of the largest force, about "
                         f"{F_RTOL_FLOOR:g} in f (ask for {F_RTOL_FLOOR:g} or coarser, or "
                         "solver highs in 2D)", scene.source)
    if na:
        return _reached(min_friction_nonassociative(
            scene, lf, method, flow=flow, state=state, solver=solver, settings=settings,
            pyramid=pyramid, contact_tol=contact_tol, progress=progress, rtol=rtol), rtol)
    m = open_method(scene, method, solver=solver, settings=settings, pyramid=pyramid,
                    contact_tol=contact_tol, progress=progress)
    interlocking_note(m)
    if m.contacts.n_joints and not m.uniform.any():
        raise InputError("every joint has its own friction override: there is no uniform "
                         "friction to minimise", scene.source)
    lim = m.friction_limit(lf, rtol) or friction_by_bisection(m, lf, max(rtol, ADMISSIBLE_TOL))
    lim = certified(m, lim, rtol, "f*", FRICTION_ATOL)
    reached = dict(rtol=rtol, accuracy=lim.accuracy)
    if lim.status != "stable":
        return FrictionResult(**_fields(m, "min_friction", lim.status, None, lf),
                              lower=lim.lower, upper=lim.upper, bracket=_bracket(lim),
                              **reached)
    fstar = float(lim.value)
    at = m.at_limit(fstar, lf, lim.at, state)
    gov = lim.governing
    if at is not None:
        m.explain(at)
        gov = gov or m.governing_friction(fstar, at, lim.accuracy or 0.0)
    st = m.state(fstar, lf, at, limit=True) if (state and at is not None) else None
    dry = _friction_without_dilatancy(scene, m, lf, fstar, method, rtol, dict(
        solver=solver, settings=settings, pyramid=pyramid, contact_tol=contact_tol)) \
        if compare_dry else None
    return FrictionResult(**_fields(m, "min_friction", "stable", fstar, lf), state=st,
                          without_dilatancy=dry, governing=gov, friction_factor=fstar,
                          friction_angle_deg=math.degrees(math.atan(fstar)),
                          lower=lim.lower, upper=lim.upper, bracket=_bracket(lim),
                          **reached)


def _load_nonassociative(scene: Scene, friction: Any, method: str, flow: str | None,
                         rtol: float, *, state: bool, progress: Progress | None,
                         mechanism: str, **opened: Any) -> LoadResult:
    """:func:`max_load_multiplier` without dilatancy
    (:func:`.nonassociative.max_load_nonassociative`), with the notes and the round-off
    of 0 of the analyses."""
    res = max_load_nonassociative(scene, friction, method, flow=flow, state=state,
                                  progress=progress, mechanism=mechanism, rtol=rtol,
                                  **opened)
    # a collapse state reached by the iteration has no bracket: no accuracy was asked of
    # it (bisection on the distortion method's verdicts has one)
    res = _reached(res, rtol if res.bracket else None)
    if method == "distortion" and res.status == "collapse":
        res = _lower_by_the_convex_path(res, scene, friction, flow, rtol,
                                        pyramid=opened.get("pyramid"),
                                        contact_tol=opened.get("contact_tol"))
    if res.status != "collapse":
        return replace(res, tilt_angle_deg=None)
    lam = float(res.load_multiplier)
    bounds = res.load_multiplier_bounds
    if bounds is not None and bounds[1] is not None and 0 <= bounds[1] <= ZERO_MULTIPLIER:
        # the associative multiplier, an upper bound, is round-off of 0, and so is every
        # multiplier below it (the reference model without friction: 3.5e-11)
        lam, bounds = 0.0, (bounds[0] if bounds[0] is None else 0.0, 0.0)
    else:
        lam = _round_off_of_zero(lam, res.accuracy)
    return replace(res, load_multiplier=lam, load_multiplier_bounds=bounds,
                   tilt_angle_deg=tilt_angle_deg(scene, lam))


#: the largest scene (joints) on which an associative `check`, `friction` or `load`
#: (their ``compare_dry``, True by default; False: a thickness search's checks, a sweep,
#: whose rows do not hold it) answers the same question without dilatancy from X0
#: (``without_dilatancy``, and a note where that stands less:
#: :func:`_check_without_dilatancy`, :func:`_friction_without_dilatancy`,
#: :func:`_without_dilatancy`; the capacity bound's limit: 0.01 to 0.7 s more on the
#: examples and trial scenes up to 42 joints, 1.85 s on a 2-ring vault of 47)
DILATANCY_JOINTS = 50
#: ... and a multiplier this much lower (relative) is said to be
DILATANCY_RTOL = 1e-4
#: the friction an answer without dilatancy is compared at where it is infinite
LARGE_FRICTION = 10.0
#: ... and an f* this much larger (beyond the accuracy asked of it): the stocky arch's
#: 0.298746 dry, 1e-3 above its static 0.298455, to that accuracy the same
DILATANCY_FRICTION_RTOL = 2e-3


def _dry(scene: Scene, f: float) -> tuple[Scene, float, bool]:
    """The scene and friction an answer without dilatancy is compared at: infinite
    friction (the scene's, the one asked, a joint's own) replaced by ``LARGE_FRICTION``,
    since infinite friction lets a joint carry shear whatever its compression, an open
    one too, which no finite friction does (a block touching a wall, pulled away from
    it, read UNBOUNDED at infinite friction and tips at b/h = 0.5 at f = 10, dry); and
    whether any was replaced."""
    import dataclasses

    joints = tuple(dataclasses.replace(j, friction=LARGE_FRICTION)
                   if j.friction is not None and friction_value(j.friction) == math.inf
                   else j for j in scene.joints)
    replaced = not math.isfinite(f) or joints != scene.joints
    return (dataclasses.replace(scene, joints=joints) if joints != scene.joints else scene,
            f if math.isfinite(f) else LARGE_FRICTION, replaced)


def _dry_words(replaced: bool) -> tuple[str, str]:
    """How an answer without dilatancy was reached, and what the associative one
    assumes that it does not."""
    if replaced:
        return (f"with friction {LARGE_FRICTION:g} where it is infinite and without "
                "dilatancy (dry joints slide without opening: --flow non-associative)",
                "infinite friction lets a joint carry shear whatever its compression, an "
                "open one too, and associative sliding opens a joint by f times its slip: "
                "dry joints do neither")
    return ("without dilatancy (dry joints slide without opening: --flow "
            "non-associative)",
            "this answer lets its sliding joints open by f times their slip (associative "
            "flow), which dry joints do not")


def _dry_answer(m: Method, method: str, run: Callable[[], Any]) -> Any:
    """The answer without dilatancy that ``run`` gives, where one is compared (the convex
    path, a scene of up to DILATANCY_JOINTS joints); None elsewhere, or where it fails."""
    if method == "distortion" or m.system.contacts.n_joints > DILATANCY_JOINTS:
        return None
    try:
        return run()
    except (InputError, SolverFailure):
        return None


def _without_dilatancy(scene: Scene, m: Method, f: float, method: str, status: str,
                       lam: float | None, opened: dict[str, Any], on: bool = True
                       ) -> tuple[str, float | None] | None:
    """The answer of `load` without dilatancy (from the elastic state X0) beside an
    associative one (``status``, ``lam``) on a small scene, at a large finite friction
    where it is infinite (:func:`_dry`): (its status, its multiplier), its note added
    to the method's where it is lower (:func:`_dilatancy_note`); None where not
    computed. Associative sliding opens a joint by f times its slip: a block standing
    against a wall (touching it, unloaded) at f = 0.6 collapsed at 0.548387 by rubbing up
    the wall as it tipped, and dry joints let it tip at 0.5; at f = 0.5 sideways along
    the wall, 0.57735 for 0.4. Whatever its own mechanism: a block pinched under a lintel
    at f = 0.3 beside one that hinges at 0.5 collapsed associatively at 0.5 (the pinched
    one cannot slide with dilatancy), dry at 0.3. ``on`` False: not computed."""
    if not on or status not in ("collapse", "unbounded"):
        return None
    dry, fr, replaced = _dry(scene, f)
    na = _dry_answer(m, method, lambda: _load_nonassociative(
        dry, fr, method, "non-associative", NA_RTOL, state=False, progress=None,
        mechanism="vertex", **opened))
    if na is None:
        return None
    note = _dilatancy_note(na, lam, replaced)
    m.notes += [note] if note else []
    return na.status, na.load_multiplier


def _check_without_dilatancy(scene: Scene, m: Method, f: float, lf: float, method: str,
                             opened: dict[str, Any]) -> tuple[str, float | None] | None:
    """As :func:`_without_dilatancy` for an associative "admissible": whether the state
    reached from X0 without dilatancy stands at the load factor ``lf`` (its status), its
    note added where it does not, or cannot tell (a block against a wall, pulled away
    from it at 0.52 of its weight with f = 0.6: admissible associatively, rubbing up the
    wall; dry, it tips at 0.5)."""
    dry, fr, replaced = _dry(scene, f)
    na = _dry_answer(m, method, lambda: check_nonassociative(
        dry, fr, lf, method, flow="non-associative", state=False, **opened))
    if na is None:
        return None
    how, why = _dry_words(replaced)
    if na.status == INADMISSIBLE:
        m.notes.append(f"{how} the state reached from the elastic state X0 does not stand "
                       f"at this load: {why}")
    elif na.status != ADMISSIBLE:
        m.notes.append(f"{how} whether the state reached from the elastic state X0 stands "
                       f"at this load is undecided: {why}")
    return na.status, None


def _friction_without_dilatancy(scene: Scene, m: Method, lf: float, fstar: float,
                                method: str, rtol: float, opened: dict[str, Any]
                                ) -> tuple[str, float | None] | None:
    """As :func:`_without_dilatancy` for f*: the friction the state reached from X0
    needs without dilatancy, on a small scene, its note added where it needs more (the
    flat arch with vertical joints: f* = 0.4719, and dry joints 0.8109, the seed's
    point; a block against a wall stood associatively from f = 1.0002, dry at none)."""
    dry, _, replaced = _dry(scene, 0.0)  # (the joints' own infinite friction)
    na = _dry_answer(m, method, lambda: min_friction_nonassociative(
        dry, lf, method, flow="non-associative", state=False, rtol=max(rtol, NA_RTOL),
        **opened))
    if na is None:
        return None
    how, why = _dry_words(replaced)
    if na.status == "unstable":
        m.notes.append(f"{how} no friction tried up to {NA_FRICTION_CEILING:g} makes the "
                       f"state reached from the elastic state X0 stand: {why}")
    elif na.status == "stable" and na.friction_factor is not None and \
            na.friction_factor > fstar * (1.0 + max(rtol, DILATANCY_FRICTION_RTOL)):
        more = 100.0 * (na.friction_factor - fstar) / fstar if fstar > 0 else math.inf
        m.notes.append(f"{how} the state reached from the elastic state X0 needs f >= "
                       f"{fmt_safe(na.friction_factor, 4, True)}"
                       + (f", {more:.1f} % more" if math.isfinite(more) else "")
                       + f": {why}")
    return na.status, na.friction_factor


def _dilatancy_note(na: LoadResult, lam: float | None, replaced: bool = False) -> str:
    """What the answer without dilatancy ``na`` says beside the associative multiplier
    ``lam`` (None: unbounded): where it collapses lower, does not stand, or is undecided
    (its bracket, where it reaches below); else "" (``replaced``: reached at a large
    finite friction where it is infinite)."""
    how, why = _dry_words(replaced)
    if na.status == "undecided" and na.bracket is not None and \
            (lam is None or na.bracket[0] < lam * (1.0 - DILATANCY_RTOL)):
        lo, hi = na.bracket
        return (f"{how} the collapse from the elastic state X0 is undecided in "
                f"[{fmt_safe(lo, 6, False)}, {fmt_safe(hi, 6, True)}]: {why}")
    if na.status == "unstable":
        return (f"{how} the dead load alone has no admissible state reached from the "
                f"elastic state X0: {why}")
    if na.status != "collapse" or na.load_multiplier is None:
        return ""
    low = float(na.load_multiplier)
    shown = fmt_safe(low, 6, False)  # (on the safe side, as the answer: 0.0500022 read
    # beside --flow non-associative's 0.0500021)
    if lam is None:
        return f"{how} it collapses at lambda = {shown} from the elastic state X0: {why}"
    if low < lam * (1.0 - DILATANCY_RTOL):
        return (f"{how} it collapses at lambda = {shown} from the elastic state X0, "
                f"{100.0 * (lam - low) / lam:.1f} % lower: {why}")
    return ""


def max_load_multiplier(scene: Scene, friction: Any = None, method: str = "clarabel", *,
                        solver: str | None = None, state: bool = True,
                        settings: dict | None = None, pyramid: int | None = None,
                        contact_tol: float | None = None, rtol: float | None = None,
                        mechanism: str = "vertex", progress: Progress | None = None,
                        flow: str | None = None, compare_dry: bool = True) -> LoadResult:
    """The largest multiplier lambda* of the live loads (associative friction; with
    ``flow="non-associative"`` see :func:`.nonassociative.max_load_nonassociative`).

    Status "collapse" with lambda* and (convex path) the collapse mechanism; "unbounded"
    when no multiplier makes the structure collapse; "unstable" when the dead load alone
    has no admissible state; "undecided" or "failure" where the method says so.

    Notes:
        ``rtol``: the relative accuracy of lambda*; default LOAD_RTOL = 2e-3 (as f*'s),
        NA_RTOL = 1e-5 for the non-associative analysis. The convex path's one solve is
        at its tight tolerances whatever it is; where what its duals' residual could
        account for leaves lambda* open by more than ``rtol``, the status is
        "undecided" with that bracket and accuracy.
        Convex path: one LP (SOCP in 3D), max lambda s.t. A x + F_dead + lambda F_live
        = 0 and the joint laws; its duals on the equilibrium rows are the mechanism (see
        :meth:`rigidblocks.methods.convex.ConvexMethod.load_limit`). Other methods:
        bisection on their verdicts to ``rtol``, without a mechanism; ``governing``
        lists the joints at their friction threshold at lambda*. ``mechanism``:
        "vertex" (default) gives one mechanism of the optimal face, which can be drawn,
        its joints ranked by relative velocity; "blend" the interior-point duals (a mix
        of every optimal mechanism where there are several). ``compare_dry``: the
        answer without dilatancy beside it (DILATANCY_JOINTS).
    """
    validate_scene(scene)  # a scene built in code, checked as a file's is
    if mechanism not in ("vertex", "blend"):
        raise InputError(f'mechanism must be "vertex" or "blend", got {mechanism!r}')
    check_live_load(scene)
    if is_nonassociative(scene, flow):
        return _load_nonassociative(scene, friction, method, flow, requested_rtol(
            rtol, NA_RTOL), state=state, progress=progress, mechanism=mechanism,
            solver=solver, settings=settings, pyramid=pyramid, contact_tol=contact_tol)
    rtol = requested_rtol(rtol, LOAD_RTOL)
    f = friction_value(scene.effective_friction if friction is None else friction)
    m = open_method(scene, method, solver=solver, settings=settings, pyramid=pyramid,
                    contact_tol=contact_tol, progress=progress)
    interlocking_note(m)
    with _large_friction_named(f):
        lim: Limit = m.load_limit(f, rtol, mechanism) or load_by_bisection(m, f, rtol)
    lim = certified(m, lim, rtol, "lambda*", BRACKET_ATOL)  # (the searches' floor at 0)
    reached = dict(rtol=rtol, accuracy=lim.accuracy)
    if lim.status == "unstable":  # (rare: one more relaxation, whatever ``state``)
        # where friction does not govern, the command that names the joints breached
        # (the answer said no more than "the dead load alone has no admissible state")
        m.notes.append(friction_governs(m, f, 0.0) or unstable_note(m.scene))
    opened = dict(solver=solver, settings=settings, pyramid=pyramid, contact_tol=contact_tol)
    if lim.status != "collapse":
        dry = _without_dilatancy(scene, m, f, method, lim.status, None, opened, compare_dry)
        return LoadResult(**_fields(m, "max_load_multiplier", lim.status, f, None),
                          bracket=_bracket(lim), without_dilatancy=dry, **reached)
    # a multiplier within round-off below 0 (the methods call one below -1e-9 unstable)
    # is 0: the dead load alone is at its limit (a frictionless block on a level base:
    # -3.4e-11 from Clarabel, -4.8e-10 from OSQP)
    lam = float(lim.value) if lim.value > 0 else 0.0  # not -0.0 either
    if lim.lower is not None and lim.lower < 0.0:
        lim = replace(lim, lower=0.0, upper=max(float(lim.upper), 0.0))
    at = m.at_limit(f, lam, lim.at, state)
    gov = lim.governing
    if at is not None:
        m.explain(at)
        if lim.mechanism is None:
            width = 0.0 if lim.lower is None or lim.upper is None else \
                float(lim.upper) - float(lim.lower)
            gov = gov or m.governing_load(f, at, lim.accuracy or 0.0, width)
    st = m.state(f, lam, at, limit=True) if (state and at is not None) else None
    lam = _round_off_of_zero(lam, lim.accuracy)  # (its state is the solver's)
    dry = _without_dilatancy(scene, m, f, method, "collapse", lam, opened, compare_dry)
    return LoadResult(**_fields(m, "max_load_multiplier", "collapse", f, lam), state=st,
                      without_dilatancy=dry,
                      governing=gov, load_multiplier=lam, mechanism=lim.mechanism,
                      bracket=_bracket(lim) if lim.lower != lim.upper else None,
                      tilt_angle_deg=tilt_angle_deg(scene, lam), **reached)


__all__ = ["check", "max_load_multiplier", "min_friction"]
