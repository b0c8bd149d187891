"""The scene: blocks, supports, loads and joint laws as plain, validated data.

Types are frozen dataclasses that keep the values exactly as they were given (so that a
scene file round-trips); derived geometry (oriented polygons, areas, centroids) lives in
:mod:`rigidblocks.scene.geometry`. The same types describe 2D blocks (polygons) and 3D
blocks (closed polyhedra, convex or not, given by vertices and faces).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import Any, Literal

import numpy as np

from ..errors import InputError

INFINITE = "infinite"
Friction = float | Literal["infinite"]
ASSOCIATIVE = "associative"
NON_ASSOCIATIVE = "non-associative"
#: the sliding rules of a joint (the scene's and a joint's ``flow``)
FLOWS = (ASSOCIATIVE, NON_ASSOCIATIVE)
Flow = Literal["associative", "non-associative"]


def flow_value(flow: object) -> str:
    """The sliding rule named by ``flow``: "associative" or "non-associative" (also
    spelt with an underscore or without the hyphen, any case); anything else is an
    :class:`InputError`."""
    if isinstance(flow, str):
        v = flow.strip().lower().replace("_", "-")
        v = {"nonassociative": NON_ASSOCIATIVE}.get(v, v)
        if v in FLOWS:
            return v
    raise InputError(f'flow must be "associative" or "non-associative", got {flow!r}')


#: the largest finite friction coefficient accepted: the convex back ends solve the
#: arch (examples/arch.json) at f = 1e8 and fail at 1e10 (InsufficientProgress), and a
#: scene's 1e200 ends in NumericalError; no joint law tells 1e6 from infinite friction
MAX_FRICTION = 1e6


def friction_value(f: object, bounded: bool = True) -> float:
    """The friction coefficient as a float: ``math.inf`` for ``"infinite"`` (or
    ``"inf"``, any case), a number or a numeric string otherwise; >= 0 and not NaN, and
    (``bounded``) not above ``MAX_FRICTION`` unless infinite.

    The one converter from user input (API arguments, CLI options, scene values) to the
    number the analyses use; :func:`friction_label` goes back.
    """
    if isinstance(f, bool):  # (True ran as f = 1)
        raise InputError(f'friction must be a number >= 0 or "infinite", got {f!r}')
    if isinstance(f, str):
        if f.strip().lower() in (INFINITE, "inf"):
            return math.inf
        try:
            f = float(f)
        except ValueError:
            raise InputError(f'friction must be a number >= 0 or "infinite", got {f!r}') \
                from None
    try:
        v = float(f)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InputError(f'friction must be a number >= 0 or "infinite", got {f!r}') \
            from None
    if math.isnan(v):
        raise InputError('friction must be a number >= 0 or "infinite", got nan')
    if not (v >= 0):
        raise InputError(f"friction must be >= 0, got {v}")
    if bounded and MAX_FRICTION < v < math.inf:
        raise InputError(f"friction {v:g} is above {MAX_FRICTION:g}, beyond what the solvers "
                         'resolve: give "infinite" for joints that do not slide')
    return v


def friction_label(f: object) -> Friction | None:
    """The friction as results and files show it: ``"infinite"``, a float, or None."""
    if f is None:
        return None
    v = friction_value(f, bounded=False)
    return INFINITE if math.isinf(v) else v


@dataclass(frozen=True, eq=False)
class Block:
    """A rigid block.

    Attributes:
        id: unique name within the scene.
        vertices: 2D polygon corners (either orientation, convex or not) or 3D
            polyhedron corners (convex or not), as given.
        faces: 3D only: faces as tuples of vertex indices.
        support: a support block is fixed and has no equilibrium equations.
        unit_weight: overrides the scene's unit weight when not None.
    """

    id: str
    vertices: tuple[tuple[float, ...], ...]
    faces: tuple[tuple[int, ...], ...] | None = None
    support: bool = False
    unit_weight: float | None = None

    @cached_property
    def points(self) -> np.ndarray:
        """The vertices as an (n, d) float array."""
        return np.asarray(self.vertices, dtype=float)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Block) and (
            self.id, self.vertices, self.faces, self.support, self.unit_weight
        ) == (other.id, other.vertices, other.faces, other.support, other.unit_weight)

    __hash__ = None  # type: ignore[assignment]


@dataclass(frozen=True)
class Load:
    """A point load on a free block.

    ``point`` None means the block's centroid. ``moment`` is a scalar couple in 2D and a
    3-vector in 3D. A live load is multiplied by the load factor lambda.
    """

    block: str
    force: tuple[float, ...]
    point: tuple[float, ...] | None = None
    moment: float | tuple[float, ...] | None = None
    live: bool | None = None

    @property
    def is_live(self) -> bool:
        return bool(self.live)


@dataclass(frozen=True)
class JointOverride:
    """The law of the joint(s) between two blocks, overriding the scene's defaults.

    ``friction`` None keeps the scene's f; cohesion and tensile strength are stresses
    over the contact area (None means 0, a dry joint); ``flow`` None keeps the scene's
    sliding rule.
    """

    blocks: tuple[str, str]
    friction: Friction | None = None
    cohesion: float | None = None
    tensile_strength: float | None = None
    flow: Flow | None = None


@dataclass(frozen=True)
class Units:
    length: str | None = None
    force: str | None = None


@dataclass(frozen=True, eq=False)
class Scene:
    """A rigid-block structure with its supports, loads and joint laws.

    Optional scene-level values are kept as given (None when absent from the file);
    the ``effective_*`` properties give the values that apply.
    """

    dimension: int
    blocks: tuple[Block, ...]
    loads: tuple[Load, ...] = ()
    joints: tuple[JointOverride, ...] = ()
    name: str | None = None
    units: Units | None = None
    depth: float | None = None
    unit_weight: float | None = None
    friction: Friction | None = None
    live_body_force: tuple[float, ...] | None = None
    #: lambda at which check and friction evaluate dead + lambda x live when the caller
    #: gives none (None: 1)
    load_factor: float | None = None
    flow: Flow | None = None
    # where the scene came from, for messages (a file name); not part of the scene
    source: str | None = field(default=None, compare=False)

    # -- effective values -------------------------------------------------------------
    @property
    def effective_depth(self) -> float:
        return 1.0 if self.depth is None else float(self.depth)

    @property
    def effective_unit_weight(self) -> float:
        return 0.0 if self.unit_weight is None else float(self.unit_weight)

    @property
    def effective_load_factor(self) -> float:
        return 1.0 if self.load_factor is None else float(self.load_factor)

    @property
    def effective_friction(self) -> Friction:
        return INFINITE if self.friction is None else self.friction

    @property
    def effective_flow(self) -> str:
        """The sliding rule of every joint without its own: "associative" by default."""
        return ASSOCIATIVE if self.flow is None else self.flow

    @property
    def slides_dry(self) -> bool:
        """Does some joint slide without dilatancy by the scene's own rules (its ``flow``,
        or a joint's override)? ``is_nonassociative`` with no flow asked."""
        return self.effective_flow == NON_ASSOCIATIVE or \
            any(j.flow == NON_ASSOCIATIVE for j in self.joints)

    @property
    def length_unit(self) -> str:
        return (self.units.length if self.units and self.units.length else "") or ""

    @property
    def force_unit(self) -> str:
        return (self.units.force if self.units and self.units.force else "") or ""

    # -- lookups ------------------------------------------------------------------
    @cached_property
    def index(self) -> dict[str, int]:
        """Block id -> position in ``blocks``."""
        return {b.id: i for i, b in enumerate(self.blocks)}

    @cached_property
    def support_mask(self) -> np.ndarray:
        return np.array([b.support for b in self.blocks], dtype=bool)

    def block(self, block_id: str) -> Block:
        return self.blocks[self.index[block_id]]

    @property
    def has_live_load(self) -> bool:
        lbf = self.live_body_force
        body = lbf is not None and any(v != 0 for v in lbf)
        return body or any(ld.is_live for ld in self.loads)

    def with_changes(self, **changes: object) -> Scene:
        """A copy with some fields replaced (scenes are immutable)."""
        return replace(self, **changes)  # type: ignore[arg-type]

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Scene):
            return NotImplemented
        names = ("dimension", "blocks", "loads", "joints", "name", "units", "depth",
                 "unit_weight", "friction", "live_body_force", "load_factor", "flow")
        return all(getattr(self, n) == getattr(other, n) for n in names)

    __hash__ = None  # type: ignore[assignment]


def make_block(block_id: str, vertices: Sequence[Sequence[float]], *, support: bool = False,
               unit_weight: float | None = None,
               faces: Sequence[Sequence[int]] | None = None) -> Block:
    """Convenience constructor that accepts lists or arrays of numbers."""
    try:
        pts = np.asarray(vertices, dtype=float)
    except (TypeError, ValueError):  # (numpy's "setting an array element with a sequence")
        raise InputError("vertices must be a list of points of equal length, each of "
                         "numbers", f"block {block_id!r}") from None
    if pts.ndim != 2:
        raise InputError("vertices must be a list of points of equal length, each of "
                         "numbers", f"block {block_id!r}")
    verts = tuple(tuple(float(c) for c in v) for v in pts)
    return Block(block_id, verts, None if faces is None else _faces(block_id, faces),
                 support, unit_weight)


def _faces(block_id: str, faces: Any) -> Any:
    """Faces as tuples of indices, where each is an integer (1.9 was taken as 1, a
    string or None ended in a ValueError or TypeError); what is not a list of lists of
    integers is kept as given, for the scene's check to name."""
    def index(i: Any) -> Any:
        if isinstance(i, bool) or not isinstance(i, int | np.integer | float | np.floating):
            return i
        if not float(i).is_integer():
            raise InputError(f"a face's vertex index must be an integer, got {float(i):g}",
                             f"block {block_id!r}")
        return int(i)

    if isinstance(faces, str) or not isinstance(faces, Sequence | np.ndarray):
        return faces
    return tuple(tuple(index(i) for i in f) if isinstance(f, Sequence | np.ndarray)
                 and not isinstance(f, str) else f for f in faces)


def geometry_key(scene: Scene) -> str:
    """A digest of the scene's blocks (ids, supports, corners): equal for the same
    blocks, and different where a block was moved, reshaped or renamed."""
    import hashlib

    h = hashlib.sha1(str(scene.dimension).encode())
    for b in scene.blocks:
        h.update(f"{b.id}\0{b.support}\0".encode())
        h.update(np.asarray(b.vertices, dtype=float).tobytes())
    return h.hexdigest()


#: what of a scene besides its blocks a result depends on (:func:`loading_keys`): the
#: friction, the flow and the load factor are the result's own (an analysis' options
#: override them), recorded in it
LOADING = ("unit_weight", "depth", "loads", "joints", "live_body_force", "units")


def loading_keys(scene: Scene) -> dict[str, str]:
    """A digest of each of the scene's ``LOADING`` values (the blocks' own unit weights
    with the scene's), numbers compared as floats (1 and 1.0 alike): a result drawn or
    reported with a scene whose loads changed drew the new loads beside the old
    answer's forces."""
    import hashlib
    from dataclasses import fields, is_dataclass

    def canonical(v: Any) -> Any:
        if isinstance(v, bool) or v is None or isinstance(v, str):
            return v
        if isinstance(v, int | float | np.integer | np.floating):
            return float(v)
        if is_dataclass(v):
            return (type(v).__name__,) + tuple(canonical(getattr(v, f.name))
                                               for f in fields(v))
        if isinstance(v, Sequence | np.ndarray):
            return tuple(canonical(x) for x in v)
        return repr(v)

    values = {k: getattr(scene, k) for k in LOADING}
    values["unit_weight"] = (scene.unit_weight, tuple(b.unit_weight for b in scene.blocks))
    return {k: hashlib.sha1(repr(canonical(v)).encode()).hexdigest()
            for k, v in values.items()}


def block_boxes(scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """(n, d) lowest and highest corners of every block's bounding box, in one pass."""
    starts = np.cumsum([0] + [len(b.vertices) for b in scene.blocks[:-1]])
    pts = np.concatenate([b.points for b in scene.blocks], axis=0)
    return np.minimum.reduceat(pts, starts, axis=0), np.maximum.reduceat(pts, starts, axis=0)


def scene_size(scene: Scene) -> float:
    """A characteristic length of the scene: the diagonal of its bounding box."""
    allpts = np.concatenate([b.points for b in scene.blocks], axis=0)
    return float(np.linalg.norm(allpts.max(axis=0) - allpts.min(axis=0)))
