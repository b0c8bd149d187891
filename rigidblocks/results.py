"""Result objects of the analyses: immutable, with the numbers an engineer checks.

Forces are reported in the scene's force unit, positions in its length unit. Joint
resultants: N (compression positive), T (along the joint's tangent s), the eccentricity
e of the resultant's point along the joint measured from its midpoint in the direction
of s (|e| <= half the joint length when the state is admissible), and the friction
demand |T|/N.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from .contacts import Contacts
from .scene.model import Scene, friction_label

#: a contact force below this fraction of the state's largest counts as none (an open
#: joint, or a joint's end that carries nothing): interior-point force states leave
#: round-off of about 1e-5 of the largest force where the exact state has zero (a 2 x 2
#: wall3d's head joint at N = 1.1e-8 kN, T = 2.9e-8 kN: |T|/N = 2.7 in an admissible
#: state at f = 0.6). The joint tables, the report and the pictures all read it
ZERO_FORCE = 1e-4


def eccentricities(c: Contacts, st: Any) -> np.ndarray:
    """Per joint, the eccentricity of the force state ``st``: in 2D its signed e along
    the joint, in 3D the distance of the centre of pressure from the contact polygon's
    centroid (NaN where the joint carries no normal force)."""
    if c.dimension == 2:
        return np.asarray(st.eccentricity, dtype=float)
    cen = c.joint_centres
    tp = np.asarray(st.thrust_points, dtype=float)
    with np.errstate(invalid="ignore"):
        return np.where(np.asarray(st.joint_normal) > 0, np.linalg.norm(tp - cen, axis=1),
                        np.nan)


#: relative round-off below which :func:`fmt_safe` rounds to the nearest either way
ROUND_OFF = 1e-9


def fmt_safe(x: float, digits: int, up: bool) -> str:
    """``x`` to ``digits`` significant figures, rounded to the nearest unless that lands
    on the unsafe side of ``x`` by more than round-off (``ROUND_OFF``, relative): then
    down (a collapse multiplier, ``up`` False) or up (a least friction, ``up`` True), so
    that the printed number is one the answer holds at (a check at the printed lambda* =
    0.176974 of a barrel vault whose lambda* is 0.1769735169 did not stand; nor one at
    the arch's f* = 0.346598, the nearest to the certified 0.3465980065, where an
    accuracy of 1e-3 had let the nearest stand)."""
    if not math.isfinite(x) or x == 0:
        return f"{x:.{digits}g}"
    near = float(f"{x:.{digits}g}")
    tol = ROUND_OFF * abs(x)
    if (near - x > tol) if not up else (x - near > tol):
        from decimal import ROUND_CEILING, ROUND_FLOOR, Decimal

        step = Decimal(1).scaleb(math.floor(math.log10(abs(x))) - digits + 1)
        near = float(Decimal(repr(x)).quantize(step, ROUND_CEILING if up else ROUND_FLOOR))
    return f"{near:.{digits}g}"


def fmt_bracket(lower: float, upper: float, digits: int = 10) -> str:
    """"[lower, upper]", each end on its own side (:func:`fmt_safe`: the lower one down,
    the upper one up) to ``digits`` figures, or to as many more as tell two different
    ends apart: the reference model's lambda* asked to 1e-12 read "in [1.2, 1.2]",
    3.6e-10 wide."""
    lo, hi = float(lower), float(upper)
    for d in range(digits, 18):
        a, b = fmt_safe(lo, d, False), fmt_safe(hi, d, True)
        if a != b or not lo < hi:
            break
    return f"[{a}, {b}]"


def no_force(N: np.ndarray, T: np.ndarray) -> np.ndarray:
    """Joints whose normal and shear forces are both below ``ZERO_FORCE`` of the largest
    of them: round-off of a joint that carries nothing."""
    top = _largest(N, T)
    return (np.abs(N) <= ZERO_FORCE * top) & (np.abs(T) <= ZERO_FORCE * top)


def _largest(N: np.ndarray, T: np.ndarray) -> float:
    """The scale of "no force": the largest joint force of a state, normal or shear."""
    return max(float(np.abs(N).max(initial=0.0)), float(np.abs(T).max(initial=0.0)))


#: a joint whose |T|/N is within this fraction of its friction is at its friction limit
#: (interior-point states reach the limit to about 1e-5)
AT_LIMIT = 1e-4


def unloaded(c: Contacts, st: Any) -> tuple[np.ndarray, np.ndarray]:
    """(m,) the open joints of the force state ``st`` (no compression: a normal force
    below ``ZERO_FORCE`` of its largest joint force, the scale of :func:`no_force`; a
    joint with a tensile strength that carries tension is not open), and (P,) the
    contact points of the other joints that carry nothing. The tables, the report and
    the pictures all read these."""
    N = np.asarray(st.joint_normal, dtype=float)
    tol = ZERO_FORCE * _largest(N, np.asarray(st.joint_shear, dtype=float))
    open_ = (N <= tol) & ~((N < -tol) & (np.asarray(c.tensile_strength) > 0))
    return open_, ~open_[c.point_joint] & (np.abs(np.asarray(st.normal, dtype=float)) <= tol)


def hinging(c: Contacts, open_: np.ndarray, free: np.ndarray) -> np.ndarray:
    """(m,) the joints whose resultant lies on the edge of the contact (where a hinge
    forms), from :func:`unloaded`'s open joints and free points: in 2D a joint one of
    whose ends carries nothing; in 3D one whose loaded points all lie on one line that
    bounds its contact polygon (an edge, or a corner alone). A 3D joint with one free
    corner is not hinging: its resultant lies inside the polygon."""
    pj = c.point_joint
    some = np.bincount(pj, free, minlength=c.n_joints) > 0
    if c.dimension == 2:
        return some & ~open_
    out = np.zeros(c.n_joints, dtype=bool)
    for k in np.flatnonzero(some & ~open_):
        pts = c.points[c.joint_start[k]:c.joint_start[k + 1]]
        on = pts[~free[c.joint_start[k]:c.joint_start[k + 1]]]
        size = max(float(c.lengths[k]), 1e-300)
        if len(on) <= 1:
            out[k] = len(on) == 1
            continue
        d = on - on[0]
        u = d[np.argmax(np.linalg.norm(d, axis=1))]
        u = u / max(float(np.linalg.norm(u)), 1e-300)
        off_line = d - np.outer(d @ u, u)
        if np.linalg.norm(off_line, axis=1).max() > EDGE_TOL * size:
            continue  # the loaded points span an area: the resultant is inside
        w = np.cross(c.normals[k], u)
        side = (pts - on[0]) @ w
        out[k] = bool(side.min() >= -EDGE_TOL * size or side.max() <= EDGE_TOL * size)
    return out


#: a 3D joint's loaded points lie on one line, and that line bounds its contact
#: polygon, to this fraction of the joint's size (:func:`hinging`)
EDGE_TOL = 1e-6


def analysis_friction(result: Any) -> float:
    """The friction the analysis gave the joints without an override of their own (f*
    for a minimum-friction analysis; inf where none or infinite): what a joint's demand
    is compared with."""
    if getattr(result, "analysis", "") == "min_friction" and \
            getattr(result, "friction_factor", None) is not None:
        return float(result.friction_factor)
    f = getattr(result, "friction", None)
    return math.inf if f is None or isinstance(f, str) else float(f)


def joint_frictions(result: Any) -> np.ndarray:
    """(m,) each joint's friction: its override where it has one, otherwise
    :func:`analysis_friction`."""
    over = np.asarray(result.contacts.override_friction, dtype=float)
    return np.where(np.isnan(over), analysis_friction(result), over)


def shear_use(result: Any) -> np.ndarray:
    """(m,) the share of its shear threshold each joint uses in the result's state: |T| /
    (f N + c a), with the joint's own friction (:func:`joint_frictions`) and cohesion; 0
    where friction is infinite, NaN where the threshold is not positive (an open joint
    without cohesion)."""
    c, st = result.contacts, result.state
    fj = joint_frictions(result)
    N = np.asarray(st.joint_normal, dtype=float)
    T = np.abs(np.asarray(st.joint_shear, dtype=float))
    with np.errstate(invalid="ignore", divide="ignore"):
        threshold = np.where(np.isfinite(fj), fj * N, np.inf) + \
            np.asarray(c.cohesion, dtype=float) * np.asarray(c.areas, dtype=float)
        return np.where(threshold > 0, T / threshold, np.nan)


def tension_use(result: Any) -> np.ndarray:
    """(m,) the share of its tensile strength each joint uses in the result's state: the
    largest tension -N_k over its points' strengths t a_k; 0 where it carries none, NaN
    where it has no tensile strength."""
    c, st = result.contacts, result.state
    t = np.asarray(c.tensile_strength, dtype=float)
    pj = c.point_joint
    with np.errstate(invalid="ignore", divide="ignore"):
        use = np.maximum(-np.asarray(st.normal, dtype=float), 0.0) / \
            (t[pj] * c.point_areas)
    out = np.full(c.n_joints, np.nan)
    held = t[pj] > 0
    np.fmax.at(out, pj[held], use[held])
    return out


def force_state_words(result: Any) -> list[str]:
    """Each joint's state in the result's force state: "open" (no compression, see
    :func:`unloaded`; "open, carrying shear" where it carries shear all the same, as
    infinite friction lets it), "in tension" (a bonded joint that carries tension), "hinging"
    (the resultant at the contact's edge, :func:`hinging`), "at friction limit" (|T|
    within ``AT_LIMIT`` of its threshold f N + c a, the joint's own friction and
    cohesion; always where both are 0), both ("hinging, at friction limit"), or
    "closed"; "-" for every joint without a state."""
    c, st = result.contacts, getattr(result, "state", None)
    if st is None:
        return ["-"] * c.n_joints
    open_, free = unloaded(c, st)
    hinge = hinging(c, open_, free)
    N = np.asarray(st.joint_normal, dtype=float)
    # a joint without friction or cohesion is at its limit whatever it carries (the
    # reference model at f = 0 read "closed" at the joints its mechanism slides)
    none = (joint_frictions(result) == 0) & (np.asarray(c.cohesion, dtype=float) == 0)
    # a distortion bisection's state is at an end of its bracket: its joints at the
    # limit to the bracket's width, as its governing line names them (the reference
    # model's four, |T|/N = 0.5996 at f = 0.6, read "closed" beside that line)
    tol = AT_LIMIT
    if getattr(result, "solver", None) == "distortion" and getattr(result, "bracket", None):
        tol = max(tol, float(getattr(result, "accuracy", None) or 0.0))
    limit = (shear_use(result) >= 1 - tol) | none
    # an open joint that carries shear: infinite friction lets it (T free whatever N),
    # which no finite friction does (a block touching a wall, "open" with 80 kN of shear)
    T = np.abs(np.asarray(st.joint_shear, dtype=float))
    sheared = open_ & (T > ZERO_FORCE * _largest(N, T))
    out = []
    for k in range(c.n_joints):
        if open_[k]:
            out.append("open, carrying shear" if sheared[k] else "open")
            continue
        tags = [w for w, on in (("in tension", N[k] < 0), ("hinging", hinge[k]),
                                ("at friction limit", limit[k])) if on]
        out.append(", ".join(tags) or "closed")
    return out


@dataclass(frozen=True, eq=False)
class ForceState:
    """An equilibrium state of the joint forces.

    Attributes:
        normal: (P,) normal force at each contact point.
        shear: (P,) or (P, 2) shear at each contact point (2D, one shear per joint: the
            joint's shear shared in proportion to the points' normal forces).
        joint_normal, joint_shear: (m,) resultants per joint (3D: shear magnitude).
        eccentricity: (m,) 2D: position of the resultant along the joint from its
            midpoint, along s; NaN where N is zero.
        demand: (m,) |T| / N (inf where N = 0 and T != 0, 0 where both vanish).
        thrust_points: (m, d) where the resultant crosses each joint.
        thrust_order: joint indices along the structure (a chain of blocks), or all
            joints in detection order when the structure is not a chain.
        method: how the state was chosen, e.g. "least complementary energy".
        thrust_chain: do the blocks form a chain, so that a thrust line joins the
            thrust points in ``thrust_order``? (Elsewhere the points are resultants,
            one per joint, and a line through them means nothing.)
    """

    normal: np.ndarray
    shear: np.ndarray
    joint_normal: np.ndarray
    joint_shear: np.ndarray
    eccentricity: np.ndarray
    demand: np.ndarray
    thrust_points: np.ndarray
    thrust_order: np.ndarray
    method: str
    thrust_chain: bool = False

    @property
    def thrust_line(self) -> np.ndarray:
        """The thrust line's points in order along the structure."""
        return self.thrust_points[self.thrust_order]


def joint_force_vectors(contacts: Contacts, state: ForceState) -> np.ndarray:
    """(m, 2) resultant force on the second block of each 2D joint: N n + T s, with n the
    joint's unit normal (from its first block into its second), s = (-n_y, n_x) its
    tangent, and N, T the joint resultants of ``state``."""
    n = contacts.normals
    s = contacts.tangents[:, 0, :]
    return state.joint_normal[:, None] * n + state.joint_shear[:, None] * s


def lower_block_forces(scene: Scene, contacts: Contacts, state: ForceState) -> np.ndarray:
    """(m, 2) each 2D joint's resultant force on the lower of its two blocks, as the
    pictures and the DXF export draw it (:func:`joint_force_vectors` gives it on the
    second block, as the tables do): in the joints' own order the arrows of an arch's
    two halves pointed opposite ways, up to the crown on one side, down to the abutment
    on the other."""
    vec = joint_force_vectors(contacts, state)
    return np.where(second_is_higher(scene, contacts.pairs)[:, None], -vec, vec)


def second_is_higher(scene: Scene, pairs: np.ndarray) -> np.ndarray:
    """(m,) is each joint's second block the higher of its two (its force is drawn on
    the other)? Where their centroids are level (a flat arch's voussoirs), the one
    nearer the middle of the structure is the higher: the force goes out to the
    supports (one way on one joint, the other on the next, before)."""
    from .scene.geometry import block_weights

    cen = block_weights(scene)[1]
    y, x = cen[:, 1], np.abs(cen[:, 0] - 0.5 * (cen[:, 0].min() + cen[:, 0].max()))
    a, b = pairs[:, 0], pairs[:, 1]
    tol = 1e-9 * max(float(np.ptp(cen[:, 1])), float(np.ptp(cen[:, 0])), 1e-300)
    level = np.abs(y[b] - y[a]) <= tol
    return np.where(level, x[b] < x[a], y[b] > y[a])


@dataclass(frozen=True, eq=False)
class Mechanism:
    """A collapse mechanism: virtual velocities of the free blocks and joint modes.

    ``velocities`` has one row (u, v, omega) per block in 2D (zero rows for supports),
    normalised so that max_b (|(u, v)| + |omega| size_b) = 1 and the live load does
    positive work. ``modes`` gives each joint's behaviour: "closed", "hinge", "open",
    "slide" or "slide+hinge". ``opening`` (P,) and ``slip`` are the relative
    displacements at the contact points / joints.
    """

    velocities: np.ndarray
    opening: np.ndarray
    slip: np.ndarray
    modes: tuple[str, ...]
    #: (m,) each joint's largest relative velocity (opening or slip), same units
    rates: np.ndarray | None = None
    #: "vertex" (one mechanism of the optimal face, which can be drawn) or "blend" (the
    #: interior-point dual: the centre of the optimal face, a mix of every optimal one)
    kind: str = "blend"

    def joints_with(self, mode: str) -> np.ndarray:
        return np.array([k for k, m in enumerate(self.modes) if m == mode], dtype=int)

    @property
    def ranking(self) -> tuple[int, ...]:
        """The joints that move (not "closed"), fastest first."""
        moving = [k for k, m in enumerate(self.modes) if m != "closed"]
        if self.rates is None:
            return tuple(moving)
        return tuple(sorted(moving, key=lambda k: -float(self.rates[k])))


def check_result(scene: Any, result: Any) -> None:
    """:class:`InputError` where ``result`` is not the result of an analysis
    (``check``, ``min_friction``, ``max_load_multiplier``) of ``scene``: a picture or a
    report of another object said "NO VERDICT: status unknown", and of another scene's
    result ended in "zip() argument 3 is shorter than arguments 1-2"."""
    from .errors import InputError

    if result is None:
        return
    if not isinstance(result, Result):
        raise InputError("result: expected the result of check, min_friction or "
                         f"max_load_multiplier, got {type(result).__name__}")
    from .scene.model import geometry_key

    ids = tuple(b.id for b in scene.blocks)
    other = result.geometry is not None and result.geometry != geometry_key(scene)
    theirs = tuple(result.contacts.block_ids)
    if theirs != ids or other:
        # (a block 3 x 1 drawn with the result of one 1 x 2 of the same id: hinging at
        # 0.5 at its middle, where it slides at 0.6)
        how = ("its blocks' ids are this scene's, their corners are not" if theirs == ids
               else f"{len(theirs)} blocks, this scene has {len(ids)}"
               if len(theirs) != len(ids) else "other block ids")
        raise InputError(f"result: the result of a {result.analysis} of another scene "
                         f"({how}): analyse this scene again")
    if result.loading is not None:
        from .scene.model import loading_keys

        mine = loading_keys(scene)
        changed = [k for k, v in result.loading.items() if mine.get(k) != v]
        if changed:
            # (an arch whose live load was halved reported with the old result: "0.149764
            # x 18.85 kN", the old multiplier of the new load)
            what = " and ".join([", ".join(changed[:-1])] * (len(changed) > 1) + changed[-1:])
            raise InputError(f"result: the result of a {result.analysis} of this scene's "
                             f"blocks under other values of {what}: analyse this scene again")


@dataclass(frozen=True, eq=False)
class Result:
    """Common part of every analysis result.

    ``status`` is the verdict (see each analysis); ``solver``, ``n_solves``,
    ``solve_time`` (seconds, all solves) and ``iterations`` describe the work done.
    """

    analysis: str
    status: str
    friction: Any
    load_factor: float | None
    contacts: Contacts = field(repr=False)
    solver: str
    n_solves: int
    solve_time: float
    iterations: int
    units: tuple[str, str] = ("", "")
    state: ForceState | None = field(default=None, repr=False)
    #: joint indices whose friction governs: those f* rests on (`friction`), those at
    #: their friction limit (`load`; a collapse by hinging alone has none). The joints the
    #: answer names, a mechanism's moving ones included, are ``governing_joints``
    governing: tuple[int, ...] = ()
    notes: tuple[str, ...] = ()
    #: [lower, upper] around the answer where the method bracketed it (None otherwise)
    bracket: tuple[float, float] | None = None
    #: the relative accuracy asked for (``rtol``; None for an analysis that brackets
    #: nothing) and the one reached: the certified bracket's width relative to its
    #: larger end (:func:`relative_width`; for lambda* from one LP, what the duals'
    #: residual leaves open above it). A number is given only where ``accuracy <=
    #: rtol``; an undecided answer gives the accuracy its bracket reached
    rtol: float | None = None
    accuracy: float | None = None
    #: seconds per stage (contacts, assembly, build, solve, state), wall clock and CPU
    timings: dict[str, float] = field(default_factory=dict, repr=False)
    cpu_timings: dict[str, float] = field(default_factory=dict, repr=False)
    #: the sliding rule of the analysis ("associative", or "non-associative" where some
    #: joint slides without dilatancy); ``converged`` and ``history`` describe the
    #: non-associative iteration (its trials, each a dict with its status and
    #: iterations; a check's one trial also with the changes of its iterations)
    flow: str = "associative"
    #: the joints that slide without dilatancy, where some do (None: every joint of a
    #: non-associative analysis, or an associative one)
    sliding_joints: int | None = None
    converged: bool | None = None
    history: tuple = field(default=(), repr=False)
    #: the back ends that answered the solves (``solver`` alone where it answered every
    #: one itself), and the answers of ``solver`` that failed their check against the
    #: problem and were solved again by another (the notes say so too)
    answered_by: tuple[str, ...] = ()
    rejected: tuple[str, ...] = ()
    #: the analysed scene's blocks (:func:`~rigidblocks.scene.model.geometry_key`), for
    #: the pictures and reports to tell another scene's result (None: not recorded)
    geometry: str | None = field(default=None, repr=False, compare=False)
    #: ... and its loads, unit weights and joint laws
    #: (:func:`~rigidblocks.scene.model.loading_keys`)
    loading: dict[str, str] | None = field(default=None, repr=False, compare=False)
    #: why a non-associative status is what it is, where its notes give it in words and
    #: the answer's verdict depends on it: BELOW_DEAD_LOAD ("unstable" `load`: the limit
    #: fixed point from X0 is below 0), DIRECT_STANDS ("inadmissible" `check`: the state
    #: reached from X0 at the load stands, the limit fixed point from X0 collapses below
    #: it), BOUND_STANDS ("admissible" `check`: a lower bound on every collapse state
    #: carries the load, whichever state the iterations from X0 reach), STATIC_UNSTABLE
    #: ("unstable" `friction`: no friction admits a state at all); "" otherwise
    cause: str = ""
    #: associative `check`, `friction` and `load` on a small scene
    #: (rigidblocks.analyses.core.DILATANCY_JOINTS): (status, number) of the same
    #: question without dilatancy, from the elastic state X0 (None: not computed)
    without_dilatancy: tuple[str, float | None] | None = None

    #: the statuses that are not verdicts: the method could not decide, or broke down
    UNDECIDED: ClassVar[tuple[str, ...]] = ("undecided", "failure")

    @property
    def decided(self) -> bool:
        """False when the status is "undecided" or "failure": no verdict, no number."""
        return self.status not in self.UNDECIDED

    def joint_name(self, k: int) -> tuple[str, str]:
        ids = self.contacts.block_ids
        return ids[self.contacts.pairs[k, 0]], ids[self.contacts.pairs[k, 1]]

    @property
    def solvers(self) -> str:
        """The back ends that answered the solves, in words ("clarabel and highs": the
        non-associative limit iteration's LPs are HiGHS's simplex), else ``solver``."""
        names = list(self.answered_by) or [self.solver]
        return " and ".join(names)

    @property
    def governing_joints(self) -> list[tuple[str, str]]:
        return [self.joint_name(k) for k in self.governing]

    def joint_table(self) -> list[dict[str, Any]]:
        """One row per joint: its blocks, N, T, eccentricity e and |T|/N (None where the
        joint is open), its ``state`` in the force state (:func:`force_state_words`)
        and its ``mode`` in the mechanism, if any, and its law in the analysis: its
        ``friction`` (its override, else the analysis's: :func:`joint_frictions`; inf
        where infinite), ``cohesion`` and ``tensile_strength`` (stresses); empty
        without a state. An open
        joint's forces that are round-off of none (:func:`no_force`: N = -6e-17 N, T =
        1.9e-9 N on the reference model's vertical joint) are 0."""
        st = self.state
        if st is None:
            return []
        mech = getattr(self, "mechanism", None)
        c = self.contacts
        states = force_state_words(self)
        none = no_force(np.asarray(st.joint_normal), np.asarray(st.joint_shear))
        ecc = eccentricities(c, st)
        fj = joint_frictions(self)
        # round-off of 0 in a loaded joint's shear and eccentricity reads 0 (the bonded
        # joint of fig4a_bonded: T = -1.9e-15 N beside N = -10 N, e = -1.5e-16 m)
        big = float(max(np.abs(st.joint_normal).max(initial=0.0),
                        np.abs(st.joint_shear).max(initial=0.0)))
        size = np.asarray(c.lengths if c.dimension == 2 else np.sqrt(c.areas), dtype=float)
        rows = []
        for k in range(c.n_joints):
            a, b = self.joint_name(k)
            N, T = float(st.joint_normal[k]), float(st.joint_shear[k])
            T = 0.0 if abs(T) <= TABLE_ZERO * big else T
            e = float(ecc[k])
            e = 0.0 if abs(e) <= TABLE_ZERO * size[k] else e
            open_ = states[k].startswith("open")
            rows.append({"joint": [a, b], "N": 0.0 if none[k] else N,
                         "T": 0.0 if none[k] else T,
                         "eccentricity": e if math.isfinite(e) and not open_ else None,
                         "demand": None if open_ else (float(st.demand[k]) if T else 0.0),
                         "state": states[k],
                         "mode": mech.modes[k] if mech is not None else None,
                         "friction": float(fj[k]), "cohesion": float(c.cohesion[k]),
                         "tensile_strength": float(c.tensile_strength[k])})
        return rows

    def _common(self) -> dict[str, Any]:
        return {"status": self.status, "notes": list(self.notes),
                "bracket": list(self.bracket) if self.bracket is not None else None,
                "rtol": self.rtol, "accuracy": _finite_or_none(self.accuracy),
                "solver": self.solver, "n_solves": self.n_solves,
                "solve_time": self.solve_time, "answered_by": list(self.answered_by),
                "rejected": list(self.rejected),
                **self._dry_dict(),
                # the units of every force and length in it, as the scene gives them
                # (None where it gives none: "force units"); a JSON reader had no way to
                # tell kN from N
                "units": {"length": self.units[0] or None, "force": self.units[1] or None}}

    def _dry_dict(self) -> dict[str, Any]:
        """``without_dilatancy`` as the JSON gives it, where computed."""
        if self.without_dilatancy is None:
            return {}
        st, v = self.without_dilatancy
        if self.analysis == "check":  # (its status says it: admissible or not)
            return {"without_dilatancy": {"status": st}}
        key = "friction_factor" if self.analysis == "min_friction" else "load_multiplier"
        return {"without_dilatancy": {"status": st, key: v}}

    def to_dict(self, joints: bool = False) -> dict[str, Any]:
        """The result as plain data (the CLI's ``--json``); ``joints`` adds the
        per-joint table (:meth:`joint_table`)."""
        out = {**self._common(), **self._answer()}
        if joints:
            out["joints"] = self.joint_table()
        return out

    def _answer(self) -> dict[str, Any]:  # pragma: no cover - overridden
        raise NotImplementedError

    def _flow_dict(self) -> dict[str, Any]:
        """The keys of a non-associative analysis (none for an associative one)."""
        if self.flow == "associative":
            return {}
        return {"flow": self.flow, "sliding_joints": sliding_count(self),
                "iterations": self.iterations, "converged": self.converged,
                "history": [dict(h) if isinstance(h, dict) else h for h in self.history]}


def sliding_count(result: Any) -> int | None:
    """How many joints slide without dilatancy in ``result`` (an analysis's or a load
    path's): its ``sliding_joints``, whose None means every joint of a non-associative
    analysis and none of an associative one (the JSON said null for both, and left the
    key out where 2 of 5 joints slid so)."""
    if result.flow == "associative":
        return 0
    if result.sliding_joints is not None:
        return int(result.sliding_joints)
    return int(result.contacts.n_joints) if result.contacts is not None else None


#: a loaded joint's shear or eccentricity this small against the largest joint force or
#: the joint's size is round-off of 0 in the joint table (floating point's, not a
#: solver's: ZERO_FORCE is that)
TABLE_ZERO = 1e-12

#: a mechanism's joint modes, in the words of the answer (exclusive groups, in the order
#: the answer's governing line gives them)
MODE_WORDS = (("hinge", "hinging"), ("slide", "sliding"),
              ("slide+hinge", "sliding and hinging"), ("open", "opening"))

#: the values of :attr:`Result.cause`
BELOW_DEAD_LOAD = "below_dead_load"
DIRECT_STANDS = "direct_stands"
BOUND_STANDS = "bound_stands"
STATIC_UNSTABLE = "static_unstable"

#: forces below this fraction of the largest joint force count as zero in the demand
DEMAND_TOL = 1e-7


#: demands within this (relative) of the largest count as the same (see max_demand)
DEMAND_TIE = 1e-7


def max_demand(st: ForceState | None, among: np.ndarray | None = None,
               cap: np.ndarray | None = None) -> tuple[float, int] | None:
    """The largest |T|/N over the joints of a force state (those where ``among`` is
    True, if given) and its joint (None without a state or such joints); with ``cap``,
    each joint's ratio at most its entry (an admitted state's joint frictions).

    Forces below ``DEMAND_TOL`` of the largest joint force are round-off of the solver
    (an iterative method stops at a violation of about 1e-9 of it): a joint whose N is
    that small carries nothing and needs no friction unless its |T| is larger. A joint
    whose forces are both round-off of none (:func:`no_force`, the tables' open joints
    with N = T = 0) needs none: the wall example's head joint at N = 1e-6 and T = 5e-8
    of the largest force was said to need 0.047.
    """
    if st is None or not len(st.joint_normal) or (among is not None and not among.any()):
        return None
    N, T = st.joint_normal, np.abs(st.joint_shear)
    big = max(float(np.abs(N).max(initial=0.0)), float(T.max(initial=0.0)), 1e-300)
    none = no_force(np.asarray(N), T)
    N, T = np.where(none, 0.0, N), np.where(none, 0.0, T)
    loaded = N > DEMAND_TOL * big
    with np.errstate(divide="ignore", invalid="ignore"):
        d = np.where(loaded, T / np.where(loaded, N, 1.0),
                     np.where(T > DEMAND_TOL * big, np.inf, 0.0))
    if cap is not None:
        d = np.minimum(d, cap)
    if among is not None:
        d = np.where(among, d, -1.0)
    top = float(d.max())
    # joints that need the same friction to round-off (symmetric structures): the first
    # of them, so that the joint named does not flip with the solver's last digits
    k = int(np.flatnonzero(d >= top * (1.0 - DEMAND_TIE))[0]) if np.isfinite(top) \
        else int(np.argmax(d))
    return float(d[k]), k


def relative_width(lower: float | None, upper: float | None) -> float | None:
    """The accuracy a bracket [lower, upper] holds its limit to: its width relative to
    its larger end (0 for a point, inf where an end is infinite; None without ends)."""
    if lower is None or upper is None:
        return None
    lo, hi = float(lower), float(upper)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return math.inf
    scale = max(abs(lo), abs(hi))
    return abs(hi - lo) / scale if scale > 0 else 0.0


def within(lower: float, upper: float, rtol: float, atol: float = 0.0) -> bool:
    """Whether the bracket [lower, upper] (either order) is no wider than ``rtol`` times
    its larger end, or than ``atol`` where its smaller end is within ``atol`` of zero (a
    structure that stands at f <= 1e-9 needs no friction): the accuracy test of the
    searches' stop and of the numbers they give (never met with an infinite end). The
    ``atol`` once counted everywhere: the arch's f* at --rtol 1e-9 by the simplex was
    given with a relative width of 2.3e-9."""
    lo, hi = float(lower), float(upper)
    width = abs(hi - lo)
    near_zero = min(abs(lo), abs(hi)) <= atol
    return math.isfinite(width) and (width <= rtol * max(abs(lo), abs(hi), 1e-300)
                                     or (near_zero and width <= atol))


def _finite_or_none(x: float | None) -> float | None:
    """JSON has no infinity: an unbounded accuracy reads null."""
    return x if x is not None and math.isfinite(x) else None


def headline(result: Any, symbols: bool = False) -> str:
    """The answer of a result in one line: what the CLI prints as its verdict, what a
    picture's title, a report's answer and a drawing's note say. A status that is not a
    verdict (undecided, failure) reads "NO VERDICT". ``symbols``: write lambda, infinity
    and the degree sign as symbols (pictures, reports) rather than ASCII (text, DXF)."""
    if result is None:
        return ""
    lam, deg, inf = ("\N{GREEK SMALL LETTER LAMDA}", "\N{DEGREE SIGN}", "\N{INFINITY}") \
        if symbols else ("lambda", " deg", "infinite")
    status = getattr(result, "status", "")
    a = getattr(result, "analysis", "")
    lf = getattr(result, "load_factor", None)
    at = "" if lf is None else f" at {lam} = {float(lf):g}"
    if status in Result.UNDECIDED:
        return f"{a.replace('_', ' ')}: NO VERDICT ({status})"
    if a == "min_friction":
        if result.friction_factor is None:
            return f"unstable: no friction suffices{at}"
        return (f"minimum friction f* = {result.friction_factor:.4g} "
                f"(friction angle {angle_text(result.friction_factor)}{deg}){at}")
    if a == "max_load_multiplier":
        if result.load_multiplier is not None:
            return (f"collapse load multiplier {lam}* = {result.load_multiplier:.4g}, "
                    f"f = {_friction_text(result.friction, deg, inf)}")
        return {"unstable": "unstable: the dead load alone has no admissible state",
                "unbounded": "unbounded: no multiplier of the live load makes it collapse",
                }.get(status, f"maximum load multiplier: {status}")
    if a == "check":
        verdict = {"admissible": "admissible", "inadmissible": "NOT ADMISSIBLE"}.get(
            status, status)
        return f"{verdict} at f = {_friction_text(result.friction, deg, inf)}, {lam} = {lf:.10g}"
    return f"{a.replace('_', ' ')}: {status}"


def _friction_text(f: Any, deg: str, inf: str) -> str:
    if f is None or isinstance(f, str) or math.isinf(f):
        return inf
    return f"{float(f):.4g} ({angle_text(f)}{deg})"


def angle_text(f: Any, decimals: int = 2) -> str:
    """The friction angle atan(f) in degrees to ``decimals`` places, or "0" for f = 0
    (it read 0.0000 deg beside f* = 0)."""
    return "0" if float(f) == 0 else f"{math.degrees(math.atan(float(f))):.{decimals}f}"


@dataclass(frozen=True, eq=False)
class CheckResult(Result):
    """Admissibility at given friction and load factor.

    status: "admissible" or "inadmissible"; "undecided" or "failure" when the method
    could not tell (``admissible`` is then None). ``violation`` is the smallest
    achievable violation of the joint laws (force units; 0 when admissible).
    ``breaches``: where the joint laws are breached in that least-violation state,
    (joint, breach in force units: the joint's, summed over its contact points where
    their laws are per point), largest first.
    ``friction_demand`` (a property): the largest |T|/N of the force state and
    its joint; under non-associative sliding the state is the one reached from X0.
    """

    admissible: bool | None = False
    violation: float = 0.0
    breaches: tuple[tuple[int, float], ...] = ()

    @property
    def friction_demand(self) -> tuple[float, int] | None:
        """The largest |T|/N over the joints of the force state and its joint (None
        without a state): the friction the state of least complementary energy needs.
        In an admitted state a joint without cohesion is within its friction: a ratio
        above it is the verdict's round-off, which is of the largest force (the 8 x 8
        wall's JSON read 0.6000396 at f = 0.6 beside "admissible")."""
        return self.demand()

    def demand(self, among: np.ndarray | None = None) -> tuple[float, int] | None:
        """:attr:`friction_demand` over the joints where ``among`` is True."""
        cap = None
        if self.admissible and self.state is not None:
            cap = np.where(np.asarray(self.contacts.cohesion, dtype=float) == 0,
                           joint_frictions(self), np.inf)
        return max_demand(self.state, among, cap)

    def _answer(self) -> dict[str, Any]:
        fd = self.friction_demand
        return {"admissible": self.admissible, "friction": friction_label(self.friction),
                "load_factor": self.load_factor, "violation": self.violation,
                "friction_demand": fd[0] if fd else None,
                "friction_demand_joint": list(self.joint_name(fd[1])) if fd else None,
                "breaches": [{"joint": list(self.joint_name(k)), "breach": v}
                             for k, v in self.breaches], **self._flow_dict()}


@dataclass(frozen=True, eq=False)
class FrictionResult(Result):
    """Minimum uniform friction.

    status: "stable" (f* found) or "unstable" (no friction suffices: even infinite
    friction admits no equilibrium). ``friction_factor`` is f*, ``friction_angle_deg``
    atan(f*) in degrees, both None when unstable. ``lower``/``upper`` bracket f*.
    """

    friction_factor: float | None = None
    friction_angle_deg: float | None = None
    lower: float | None = None
    upper: float | None = None

    def _answer(self) -> dict[str, Any]:
        return {"friction_factor": self.friction_factor,
                "friction_angle_deg": self.friction_angle_deg,
                "governing_joints": [list(p) for p in self.governing_joints],
                "load_factor": self.load_factor, **self._flow_dict()}


@dataclass(frozen=True, eq=False)
class LoadResult(Result):
    """Maximum load multiplier (associative friction, or non-associative with ``flow``).

    status: "collapse" (finite lambda*), "unbounded" (no multiplier makes it collapse)
    or "unstable" (the dead load alone has no admissible state); "undecided" or
    "failure" when the method could not tell (no number). ``tilt_angle_deg``: where the
    live load is a horizontal body force a (in g), the tilt angle atan(lambda* |a|) of
    the ground that loads the structure the same way (a tilting-table test).
    """

    load_multiplier: float | None = None
    mechanism: Mechanism | None = field(default=None, repr=False)
    tilt_angle_deg: float | None = None
    #: non-associative: [lo, hi], bounds on every non-associative collapse multiplier:
    #: hi the associative multiplier, lo the frictionless one (None where it is not
    #: defined) or the capacity bound (``lower_bound_by``); the answer reached from X0
    #: is not a lower bound (other states may collapse earlier:
    #: rigidblocks.analyses.na_bounds)
    load_multiplier_bounds: tuple[float | None, float | None] | None = None
    #: what lo is: "frictionless" (the associative multiplier with the joints without
    #: dilatancy frictionless: every collapse state) or "capacity" (the capacity bound,
    #: :func:`rigidblocks.analyses.na_bounds.capacity_bound`: every collapse state at
    #: lambda >= 0)
    lower_bound_by: str | None = None

    @property
    def governing_joints(self) -> list[tuple[str, str]]:
        """The joints the "governing" line names: the mechanism's moving joints by mode,
        fastest first (the sliding ones alone were named: none for the segmental arch's
        four hinges); a method without a mechanism, those at their friction limit in its
        state."""
        m = self.mechanism
        named = self.governing if m is None else \
            [k for mode, _ in MODE_WORDS for k in m.ranking if m.modes[k] == mode]
        return [self.joint_name(k) for k in named]

    def _answer(self) -> dict[str, Any]:
        out = {"load_multiplier": self.load_multiplier,
               "friction": friction_label(self.friction),
               "tilt_angle_deg": self.tilt_angle_deg, **self._flow_dict()}
        if self.flow != "associative":
            b = self.load_multiplier_bounds
            out["load_multiplier_bounds"] = None if b is None else list(b)
            out["lower_bound_by"] = self.lower_bound_by

        out["governing_joints"] = [list(p) for p in self.governing_joints]
        m = self.mechanism
        if m is not None:
            order = m.ranking
            out["mechanism"] = {
                "kind": m.kind,
                "hinges": [list(self.joint_name(k)) for k in order if m.modes[k] == "hinge"],
                "sliding": [list(self.joint_name(k)) for k in order
                            if m.modes[k].startswith("slide")],
                "open": [list(self.joint_name(k)) for k in order if m.modes[k] == "open"],
                "ranked": [{"joint": list(self.joint_name(k)), "mode": m.modes[k],
                            "rate": float(m.rates[k]) if m.rates is not None else None}
                           for k in order],
            }
        return out
