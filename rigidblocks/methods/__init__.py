"""Solution methods behind one interface (:class:`~.base.Method`), by name.

``clarabel`` (alias ``convex``): the convex path (relaxation, LP/SOCP), with any back end
of :mod:`rigidblocks.solvers` as ``solver``. ``distortion``: the seed's iterative
solver (2D). :func:`open_method` opens one on a scene (contacts and assembly included)
and refuses options that do not apply to it.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..contacts import detect_contacts, point_touches
from ..contacts.model import block_groups
from ..equilibrium import assemble
from ..errors import InputError
from ..scene.model import Scene
from ..scene.validate import DEFAULT_TOL, loads_off_their_blocks, validate_scene
from ..solvers import SOLVERS
from .base import (
    ADMISSIBLE,
    FAILURE,
    INADMISSIBLE,
    UNDECIDED,
    Limit,
    Method,
    Progress,
    Timings,
    Verdict,
)
from .convex import ConvexMethod
from .distortion import NOT_3D, DistortionMethod

#: the methods by name, with what each is
METHODS: dict[str, str] = {
    "clarabel": "the convex path (relaxation and LP/SOCP); back end chosen by solver=",
    "distortion": "the iterative impressed-distortion solver of the reference paper (2D)",
}
_ALIASES = {"convex": "clarabel"}


def method_name(method: str, solver: str | None = None) -> tuple[str, str | None]:
    """(method, back end) from the ``method`` and ``solver`` arguments.

    A back end's name given as the method (``method="highs"``) means the convex path
    with that back end, as before there was a ``solver`` argument.
    """
    m = str(method).lower()
    m = _ALIASES.get(m, m)
    if m in METHODS:
        return m, solver
    if m in SOLVERS or m.startswith("cvxpy-"):
        if solver is not None and solver.lower() != m:
            raise InputError(f"method {method!r} is a back end of the convex path, and "
                             f"solver={solver!r} names another")
        return "clarabel", m
    names = (m + "".join(f" (or {a})" for a, b in _ALIASES.items() if b == m)
             for m in METHODS)
    raise InputError(f"unknown method {method!r} (choose from {', '.join(names)}, or a "
                     "solver name for the convex path)")


#: the words of the notes on blocks that nothing holds (:func:`open_method`), which the
#: answer reads (:meth:`rigidblocks.answer._Words.live_hint`)
NOTHING_HOLDS = "nothing holds"


def unsupported_blocks(scene: Scene, contacts: object) -> tuple[list[str], list[str]]:
    """Ids of the free blocks without a single joint, and of those with joints that
    reach no support (a group of blocks resting on one that touches nothing)."""
    n = len(scene.blocks)
    pairs = np.asarray(contacts.pairs, dtype=int).reshape(-1, 2)  # type: ignore[attr-defined]
    touched = np.bincount(pairs.ravel(), minlength=n)
    comp = block_groups(n, pairs)
    held = set(comp[np.asarray(scene.support_mask, dtype=bool)].tolist())
    alone, adrift = [], []
    for k, (b, sup) in enumerate(zip(scene.blocks, scene.support_mask, strict=True)):
        if sup:
            continue
        if touched[k] == 0:
            alone.append(b.id)
        elif comp[k] not in held:
            adrift.append(b.id)
    return alone, adrift


def _names(ids: list[str], most: int = 5) -> str:
    head = ", ".join(f"'{i}'" for i in ids[:most])
    more = f" and {len(ids) - most} more" if len(ids) > most else ""
    return f"block{'s' if len(ids) > 1 else ''} {head}{more}"


def _weighs(scene: Scene) -> bool:
    """Do the scene's blocks weigh anything (its unit weight, or a block's own)?"""
    return bool(scene.effective_unit_weight) or any(b.unit_weight for b in scene.blocks)


def _weightless(scene: Scene, system: Any) -> list[str]:
    """The note on blocks that weigh nothing (and on a scene that nothing loads, or
    whose live body force, a multiple of the weights, is nothing)."""
    if _weighs(scene):
        return []
    if np.any(system.dead):
        lbf = scene.live_body_force
        return ["the blocks weigh nothing (no unit_weight): the live body force, a "
                "multiple of their weights, adds nothing; only the point loads act"] \
            if lbf is not None and any(v != 0 for v in lbf) else []
    return ["the blocks weigh nothing (no unit_weight): self-weight is not part of this "
            "analysis, only the loads act" + ("; and no load acts: every force is zero (set "
                                             "unit_weight, or add loads)"
                                             if not np.any(system.live) else "")]


def _no_depth(scene: Scene, system: Any) -> list[str]:
    """The note on a 2D scene with weights and point loads but no depth: its blocks are
    1 length unit deep, which in millimetres weighs a wall a thousandth of its weight
    beside point loads on the whole wall (a 1 x 2 m block in mm and N under a 40 kN
    load lifted at lambda* = 500.5, 1 with its depth of 1000 mm, with no word)."""
    if scene.dimension != 2 or scene.depth is not None or not scene.loads or \
            not _weighs(scene):
        return []  # (weightless blocks beside point loads: the depth changes nothing)
    unit = scene.length_unit or "length unit"
    return [f"the scene gives no depth: its blocks are 1 {unit} deep, their weights those "
            f"of a slice 1 {unit} thick, beside point loads given as they are: where those "
            "act on the whole wall, give its \"depth\""]


#: a 2D scene's depth beyond this many times its size, or below this fraction of its
#: blocks' median size, is said to be doubtful where point loads stand beside weights
DEPTH_DOUBT = (50.0, 1e-3)


def _odd_depth(scene: Scene, system: Any) -> list[str]:
    """The note on a 2D scene with weights and point loads whose depth is far from its
    size: given in another unit, it scales the weights beside the point loads (a scene
    in metres with a depth of 300, meant in mm, collapsed at lambda* = 1920.6 for 3.8,
    with no word)."""
    if scene.dimension != 2 or scene.depth is None or not scene.loads or \
            not _weighs(scene):
        return []
    from ..scene.model import block_boxes

    lo, hi = block_boxes(scene)
    size = float(np.linalg.norm(hi.max(axis=0) - lo.min(axis=0)))
    block = float(np.median((hi - lo).max(axis=1)))
    depth = float(scene.depth)
    unit = scene.length_unit or "length units"
    if depth > DEPTH_DOUBT[0] * size:
        how = f"{depth / size:.3g} times the scene's size ({size:.3g} {unit})"
    elif depth < DEPTH_DOUBT[1] * block:
        how = f"{block / depth:.3g} times thinner than its blocks ({block:.3g} {unit})"
    else:
        return []
    return [f"the scene's depth {depth:g} {unit} is {how}: its blocks' weights scale with "
            "it, its point loads do not; is the depth in the scene's length unit?"]


def _unheld(scene: Scene, contacts: Any, tol: float) -> list[str]:
    """The notes on the blocks that nothing holds (:func:`unsupported_blocks`): one that
    touches another at a point only (:func:`~rigidblocks.contacts.point_touches`), one
    that touches nothing, and groups joined to no support."""
    notes: list[str] = []
    loose, adrift = unsupported_blocks(scene, contacts)
    points = point_touches(scene, loose, tol)
    common = "an edge in common" if scene.dimension == 2 else "a face in common"
    for b, (other, where) in points.items():
        notes.append(f"block '{b}' touches block '{other}' {where}, and a joint is "
                     f"{common}: {NOTHING_HOLDS} it; check the geometry")
    if adrift:
        # a group joined to no support may meet one where it has no joint (a box on its
        # support's edge, another on it); the joined pairs only where there is one to
        # read them (every analysis opens here)
        ids = contacts.block_ids
        joined = {frozenset((ids[a], ids[b])) for a, b in contacts.pairs}
        for b, (other, where) in point_touches(scene, adrift, tol, joined).items():
            notes.append(f"block '{b}' touches block '{other}' {where}, and a joint is "
                         f"{common}: no joint there")
    loose = [b for b in loose if b not in points]
    if loose:
        one = len(loose) == 1
        notes.append(f"{_names(loose)} touch{'es' if one else ''} no other block (no "
                     f"joint within the contact tolerance): {NOTHING_HOLDS} "
                     f"{'it' if one else 'them'}; check the geometry, or raise the "
                     "contact tolerance for gaps from rounding")
    if adrift:
        notes.append(f"{_names(adrift)} {'is' if len(adrift) == 1 else 'are'} joined to "
                     f"no support (their joints reach only free blocks): {NOTHING_HOLDS} "
                     "them; check the geometry where they should meet a support")
    return notes


def open_method(scene: Scene, method: str = "clarabel", *, solver: str | None = None,
                settings: dict | None = None, pyramid: int | None = None,
                contact_tol: float | None = None, progress: Progress | None = None,
                bonds_kept: bool = True) -> Method:
    """The named method on ``scene``: contacts detected, equilibrium assembled.

    Options that the method does not take are refused with an :class:`InputError`:
    ``solver``, ``pyramid`` and ``contact_tol`` are options of the convex path; the
    distortion method takes the settings ``tol``, ``max_iter`` and ``anderson``.
    ``progress`` (a :class:`~.base.Progress`) is kept up to date while it works.
    ``bonds_kept``: the analysis counts a bonded joint's strength at every load (the
    limit analyses, noted where the scene has such joints); False for the load path,
    where a crack loses it.
    """
    # a scene built in code is checked as a scene file is (once: validate_scene marks
    # a scene that passed)
    validate_scene(scene)
    name, solver = method_name(method, solver)
    if name == "distortion":
        given = [k for k, v in (("solver", solver), ("pyramid", pyramid),
                                ("contact_tol", contact_tol)) if v is not None]
        if given:
            raise InputError(f"{', '.join(given)}: an option of the convex path, not of "
                             "the distortion method")
        unknown = sorted(set(settings or {}) - set(DistortionMethod.setting_keys))
        if unknown:
            raise InputError(f"unknown setting(s) of the distortion method: "
                             f"{', '.join(unknown)} (it takes "
                             f"{', '.join(DistortionMethod.setting_keys)})")
        if scene.dimension != 2:
            raise InputError(NOT_3D, scene.source)
    timings = Timings()
    kw = {}
    if contact_tol is not None:
        tol = float(contact_tol)
        if not (tol > 0 and math.isfinite(tol)):
            raise InputError(f"contact_tol must be a number > 0, got {contact_tol!r}")
        kw["tol"] = tol
    with timings.stage("contacts"):
        contacts = detect_contacts(scene, **kw)
    with timings.stage("assembly"):
        system = assemble(scene, contacts)
    if name == "distortion":
        m: Method = DistortionMethod(scene, system, timings, settings=settings,
                                     progress=progress)
    else:
        m = ConvexMethod(scene, system, timings, solver=solver or "clarabel",
                         settings=settings, pyramid=pyramid, progress=progress)
    m.notes.extend(_weightless(scene, system) + _no_depth(scene, system)
                   + _odd_depth(scene, system))
    unheld = _unheld(scene, contacts, kw.get("tol", DEFAULT_TOL))
    if unheld:
        # a mechanism by its geometry is bad input, as a DXF import refuses it: a verdict
        # (NOT ADMISSIBLE, UNSTABLE) on blocks that nothing holds read as the structure's
        raise InputError("; ".join(unheld), scene.source)
    bonded = int(np.count_nonzero((contacts.tensile_strength > 0) | (contacts.cohesion > 0)))
    if bonds_kept and bonded:
        # (the load path is a 2D command: a 3D scene's note pointed to it)
        follow = (f"`rigidblocks path {scene.source or 'SCENE'}` follows the cracks"
                  if scene.dimension == 2 else "the load path that follows the cracks "
                  "(`rigidblocks path`) is computed for 2D scenes only")
        m.notes.append(f"{bonded} joint{'s are' if bonded > 1 else ' is'} bonded (tensile "
                       "strength or cohesion): this analysis counts the bond's strength "
                       "at every load, as plastic capacity; a bond that cracks on the way "
                       f"up is lost, which can lower the collapse load: {follow} (an "
                       "example, not this run: the bundled fig4a_bonded.json at its own "
                       "friction 0.5 collapses on its load path at lambda = 1, against 1.2 "
                       "by `load`)")
    off = loads_off_their_blocks(scene)
    if off:
        unit = f" {scene.length_unit}" if scene.length_unit else ""
        said = "; ".join(f"load #{k} on block '{b}' lies {d:.3g}{unit} from it"
                         for k, b, d in off[:3])
        more = f" (and {len(off) - 3} more)" if len(off) > 3 else ""
        m.notes.append(f"a load's point is outside its block: {said}{more}; the analysis "
                       "applies the load there, as if the block reached it (its lever "
                       "counts in full): check the point")
    return m


__all__ = ["ADMISSIBLE", "FAILURE", "INADMISSIBLE", "METHODS", "NOTHING_HOLDS", "UNDECIDED",
           "ConvexMethod", "DistortionMethod", "Limit", "Method", "Progress", "Timings",
           "Verdict", "method_name", "open_method"]
