"""COMPAS interop: assemblies and block models in, interface forces out.

Needs the optional extra ``pip install "rigidblocks[compas]"`` (the ``compas``,
``compas_assembly`` and ``compas_dem`` packages). Two kinds of COMPAS object are read:

- a ``compas_assembly`` :class:`Assembly` (or a subclass such as compas_cra's
  ``CRA_Assembly``): one block (a closed mesh) per graph node, supports flagged by the
  node attribute ``is_support``, weight = volume x the block's ``density`` attribute
  (compas_cra's convention; ``density`` otherwise, 1 by default, as compas_cra's
  solvers), gravity along -z;
- a ``compas_dem`` :class:`BlockModel`: one element per block (its model geometry),
  supports flagged by ``element.is_support``, weight = volume x density x 9.81 when the
  element's material gives a density (compas_dem's own scaling), else volume x
  ``density``.

Friction comes from the file when it has one: a ``compas_dem`` ``Problem`` stored beside
the model (its contact model's ``mu``), or an ``mu`` / ``friction`` attribute of the
assembly; otherwise from the caller (``friction=``), else the scene keeps no friction
(``"infinite"``, Heyman's hypothesis) and :func:`read_compas`'s report says so.

Block ids are the graph node keys as strings. The blocks' faces go through the scene's
own validation, so a block our 3D model cannot take today (a non-convex one) is an
:class:`~rigidblocks.errors.InputError` naming it, converted faithfully rather than
convexified. Faces are written outward (counter-clockwise seen from outside, as the
scene files rigidblocks writes give them): a mesh whose faces all turn inward (negative
signed volume) is reversed, and the report names it; one whose faces turn both ways
(two faces running through their common edge in the same direction) is an
:class:`~rigidblocks.errors.InputError` naming the block, the faces and the edge.

The way back: :func:`write_forces` writes a result's contact forces into the
assembly's (or model's) own interface objects, in COMPAS's convention (per interface
point ``{"c_np", "c_nn", "c_u", "c_v"}`` in the interface frame, the frame's z axis
pointing from the edge's first block into its second, the force acting on the second
block), so that COMPAS viewers and scripts read them like compas_cra's.

Example::

    import compas
    import rigidblocks as rb
    from rigidblocks.compas import from_compas, write_forces

    assembly = compas.json_load("wall.json")
    scene = from_compas(assembly, friction=0.6)
    result = rb.check(scene, load_factor=0)
    write_forces(assembly, result)
    compas.json_dump(assembly, "wall-forces.json")
"""

from __future__ import annotations

import importlib.util
import json
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from .errors import InputError
from .scene.model import Scene, make_block
from .scene.polyhedra import face_orientation
from .scene.validate import validate_scene

EXTRA = "compas"
#: gravity compas_dem multiplies its densities by
G_DEM = 9.81
_CRA_DTYPE = "compas_cra.datastructures/CRA_Assembly"
_ASSEMBLY_DTYPE = "compas_assembly.datastructures/Assembly"


def _require() -> None:
    """Raise a one-line InputError naming the extra when COMPAS is missing."""
    missing = [m for m in ("compas", "compas_assembly")
               if importlib.util.find_spec(m) is None]
    if missing:
        raise InputError(f"COMPAS interop needs the '{EXTRA}' extra ({', '.join(missing)} "
                         f"not installed): pip install \"rigidblocks[{EXTRA}]\"")


@dataclass
class ImportReport:
    """What a conversion found: counts, where supports and friction came from, notes."""

    kind: str
    blocks: int = 0
    supports: list[str] = field(default_factory=list)
    friction: Any = None
    friction_source: str = "none"
    interfaces_in_file: int = 0
    notes: list[str] = field(default_factory=list)

    def summary(self) -> str:
        f = ("none in the file: friction infinite unless given (--friction)"
             if self.friction is None else f"{self.friction:g} ({self.friction_source})")
        lines = [f"{self.kind}: {self.blocks} blocks, {len(self.supports)} supports "
                 f"({', '.join(self.supports) or 'none'}), friction {f}"]
        if self.interfaces_in_file:
            lines.append(f"{self.interfaces_in_file} interfaces in the file (not used: "
                         "joints are found from the geometry)")
        lines += self.notes
        return "\n".join(lines)


def _is_assembly(obj: Any) -> bool:
    try:
        from compas_assembly.datastructures import Assembly
    except ImportError:  # pragma: no cover - _require guards
        return False
    return isinstance(obj, Assembly)


def _is_blockmodel(obj: Any) -> bool:
    if importlib.util.find_spec("compas_dem") is None:
        return False
    from compas_dem.models import BlockModel

    return isinstance(obj, BlockModel)


def _is_problem(obj: Any) -> bool:
    if importlib.util.find_spec("compas_dem") is None:
        return False
    from compas_dem.problem import Problem

    return isinstance(obj, Problem)


def _walk(obj: Any) -> Iterable[Any]:
    """The object and, for a dict or list, its values (one level)."""
    yield obj
    if isinstance(obj, dict):
        yield from obj.values()
    elif isinstance(obj, list | tuple):
        yield from obj


def _positive_friction(value: Any, where: str) -> float:
    try:
        f = float(value)
    except (TypeError, ValueError):
        raise InputError(f"friction is not a number: {value!r}", where) from None
    if not f >= 0 or math.isinf(f):
        raise InputError(f"friction must be a finite number >= 0, not {value!r}", where)
    return f


def _block_polyhedron(mesh: Any, where: str
                      ) -> tuple[list[list[float]], list[list[int]], bool]:
    """The mesh's vertices and faces, the faces outward, and whether they were turned
    (all inward in the mesh); faces turning both ways are an error naming them."""
    try:
        verts, faces = mesh.to_vertices_and_faces()
    except Exception as exc:  # a node without a mesh, or a broken one
        raise InputError(f"no block mesh ({type(exc).__name__}: {exc})", where) from None
    if len(verts) < 4 or len(faces) < 4:
        raise InputError(f"a block needs a closed mesh: {len(verts)} vertices, "
                         f"{len(faces)} faces", where)
    verts = [[float(c) for c in v] for v in verts]
    faces = [[int(i) for i in f] for f in faces]
    way, bad = face_orientation(verts, faces)
    if way == "mixed" and bad is not None:
        f, g, (a, b) = bad
        raise InputError(f"faces {f} and {g} run through their common edge ({a}, {b}) in "
                         "the same direction: the mesh's faces do not all turn the same "
                         "way (outward, counter-clockwise seen from outside); unify them "
                         "(COMPAS: mesh.unify_cycles())", where)
    if way == "inward":
        return verts, [f[::-1] for f in faces], True
    return verts, faces, False


def _note_turned(rep: ImportReport, turned: list[str]) -> None:
    """Say which blocks' faces were reversed (their mesh's faces all turned inward)."""
    if turned:
        shown = ", ".join(turned[:10]) + (", ..." if len(turned) > 10 else "")
        rep.notes.append(f"faces reversed to point outward in {len(turned)} block(s) "
                         f"whose mesh had them all inward: {shown}")


def _supports_given(supports: Sequence[Any] | None, keys: Sequence[Any]) -> set[str]:
    if supports is None:
        return set()
    known = {str(k) for k in keys}
    out = {str(s) for s in supports}
    unknown = sorted(out - known)
    if unknown:
        raise InputError(f"support {unknown[0]!r} is not a block of the file "
                         f"(blocks: {', '.join(sorted(known)[:10])}"
                         f"{', ...' if len(known) > 10 else ''})", "supports")
    return out


def _scene(blocks: list[Any], friction: float | None, name: str | None,
           validate: bool) -> Scene:
    scene = Scene(dimension=3, blocks=tuple(blocks), friction=friction, unit_weight=1.0,
                  name=name)
    if validate:
        validate_scene(scene)
    return scene


def assembly_to_scene(assembly: Any, *, friction: float | None = None,
                      density: float = 1.0, supports: Sequence[Any] | None = None,
                      name: str | None = None, validate: bool = True,
                      report: ImportReport | None = None) -> Scene:
    """The 3D scene of a ``compas_assembly`` Assembly (compas_cra's data structure).

    Args:
        assembly: an Assembly or a subclass (``CRA_Assembly``).
        friction: f for every joint; None takes the assembly's ``mu`` / ``friction``
            attribute when it has one.
        density: weight per volume of blocks without a ``density`` attribute (1, as
            compas_cra's solvers).
        supports: node keys to fix besides those flagged ``is_support``.
        name: scene name (default: the assembly's name).
        validate: validate the scene (convex closed polyhedra, no overlaps).
        report: filled in with what was found.
    """
    _require()
    rep = report if report is not None else ImportReport(kind="")
    rep.kind = type(assembly).__name__
    graph = assembly.graph
    nodes = list(graph.nodes())
    extra = _supports_given(supports, nodes)
    blocks, turned = [], []
    for node in nodes:
        where = f"block '{node}'"
        mesh = graph.node_attribute(node, "block")
        if mesh is None:
            raise InputError("the node has no block", where)
        verts, faces, flipped = _block_polyhedron(mesh, where)
        if flipped:
            turned.append(str(node))
        attrs = getattr(mesh, "attributes", {}) or {}
        w = float(attrs["density"]) if attrs.get("density") is not None else float(density)
        sup = bool(graph.node_attribute(node, "is_support")) or str(node) in extra
        if sup:
            rep.supports.append(str(node))
        blocks.append(make_block(str(node), verts, faces=faces, support=sup, unit_weight=w))
    f_src = "given"
    if friction is None:
        attrs = assembly.attributes or {}
        for key in ("mu", "friction"):
            if attrs.get(key) is not None:
                friction = _positive_friction(attrs[key], f"assembly attribute '{key}'")
                f_src = f"the assembly's attribute '{key}'"
                break
    elif friction is not None:
        friction = _positive_friction(friction, "friction")
    rep.friction, rep.friction_source = friction, f_src
    rep.blocks = len(blocks)
    _note_turned(rep, turned)
    rep.interfaces_in_file = sum(len(graph.edge_attribute(e, "interfaces") or [])
                                 for e in graph.edges())
    return _scene(blocks, friction, name or (assembly.attributes or {}).get("name"), validate)


def blockmodel_to_scene(model: Any, *, friction: float | None = None, density: float = 1.0,
                        supports: Sequence[Any] | None = None, name: str | None = None,
                        problem: Any = None, validate: bool = True,
                        report: ImportReport | None = None) -> Scene:
    """The 3D scene of a ``compas_dem`` BlockModel.

    ``problem``: a compas_dem ``Problem`` whose contact model gives the friction (used
    when ``friction`` is None). Other arguments as :func:`assembly_to_scene`; a block
    whose material has a density weighs volume x density x 9.81 (compas_dem's scaling).
    """
    _require()
    rep = report if report is not None else ImportReport(kind="")
    rep.kind = type(model).__name__
    elements = list(model.elements())
    extra = _supports_given(supports, [e.graphnode for e in elements])
    blocks, turned = [], []
    for el in elements:
        key = str(el.graphnode)
        where = f"block '{key}'"
        verts, faces, flipped = _block_polyhedron(el.modelgeometry, where)
        if flipped:
            turned.append(key)
        mat = getattr(el, "material", None)
        rho = getattr(mat, "density", None) if mat is not None else None
        w = float(rho) * G_DEM if rho else float(density)
        sup = bool(getattr(el, "is_support", False)) or key in extra
        if sup:
            rep.supports.append(key)
        blocks.append(make_block(key, verts, faces=faces, support=sup, unit_weight=w))
    f_src = "given"
    if friction is None and problem is not None:
        cm = getattr(problem.contact_properties, "contact_model", None)
        if cm is not None and getattr(cm, "mu", None) is not None:
            friction = _positive_friction(cm.mu, "problem contact model")
            f_src = f"the problem's contact model {type(cm).__name__}"
    elif friction is not None:
        friction = _positive_friction(friction, "friction")
    rep.friction, rep.friction_source = friction, f_src
    rep.blocks = len(blocks)
    _note_turned(rep, turned)
    rep.interfaces_in_file = sum(len(model.graph.edge_attribute(e, "contacts") or [])
                                 for e in model.graph.edges())
    return _scene(blocks, friction, name or getattr(model, "name", None), validate)


def from_compas(obj: Any, *, friction: float | None = None, density: float = 1.0,
                supports: Sequence[Any] | None = None, name: str | None = None,
                validate: bool = True, report: ImportReport | None = None) -> Scene:
    """The 3D scene of an Assembly, a BlockModel, or a dict / list holding one of them
    (and, for a BlockModel, optionally its compas_dem Problem, which gives the friction).
    """
    _require()
    kw = {"friction": friction, "density": density, "supports": supports, "name": name,
          "validate": validate, "report": report}
    found = list(_walk(obj))
    for item in found:
        if _is_assembly(item):
            return assembly_to_scene(item, **kw)
    for item in found:
        if _is_blockmodel(item):
            problem = next((p for p in found if _is_problem(p)
                            and p.model_id == str(item.guid)), None)
            return blockmodel_to_scene(item, problem=problem, **kw)
    raise InputError(f"not a compas_assembly Assembly or a compas_dem BlockModel: "
                     f"{type(obj).__name__}")


def load_compas(path: str | Path) -> Any:
    """Load a COMPAS JSON file (``compas.json_load``).

    A compas_cra ``CRA_Assembly`` loads as a plain ``compas_assembly`` Assembly when
    compas_cra is not installed (it adds methods only, no data).
    """
    _require()
    import compas

    p = Path(path)
    try:
        text = p.read_text()
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror or exc}", str(path)) from None
    if _CRA_DTYPE in text and importlib.util.find_spec("compas_cra") is None:
        text = text.replace(_CRA_DTYPE, _ASSEMBLY_DTYPE)
    try:
        return compas.json_loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"not JSON: {exc}", str(path)) from None
    except Exception as exc:  # compas's decoder: an unknown dtype, a missing package
        raise InputError(f"not a COMPAS data file this installation reads "
                         f"({type(exc).__name__}: {str(exc).splitlines()[0][:200]})",
                         str(path)) from None


def read_compas(path: str | Path, *, friction: float | None = None, density: float = 1.0,
                supports: Sequence[Any] | None = None, name: str | None = None,
                validate: bool = True) -> tuple[Scene, ImportReport]:
    """A COMPAS JSON file (Assembly or BlockModel) as a scene, with its import report."""
    obj = load_compas(path)
    rep = ImportReport(kind="")
    try:
        scene = from_compas(obj, friction=friction, density=density, supports=supports,
                            name=name or Path(path).stem, validate=validate, report=rep)
    except InputError as err:
        raise err.located(str(path)) from None
    return scene, rep


# --------------------------------------------------------------------------- way back


def _frame(normal: np.ndarray, tangent: np.ndarray, origin: np.ndarray) -> Any:
    from compas.geometry import Frame

    y = np.cross(normal, tangent)
    return Frame([float(c) for c in origin], [float(c) for c in tangent],
                 [float(c) for c in y])


def _edge_key(graph: Any, u: Any, v: Any) -> tuple[Any, Any] | None:
    if graph.has_edge((u, v)):
        return (u, v)
    if graph.has_edge((v, u)):
        return (v, u)
    return None


def _node_keys(target: Any) -> dict[str, Any]:
    """Block id -> graph node: the node key as a string, or a block's own unique name
    (the ids :func:`scene_to_assembly` keeps in the names)."""
    graph = target.graph
    keys = {str(n): n for n in graph.nodes()}
    names: dict[str, list[Any]] = {}
    for n in graph.nodes():
        blk = graph.node_attribute(n, "block") if _is_assembly(target) else None
        nm = getattr(blk, "name", None)
        if nm:
            names.setdefault(str(nm), []).append(n)
    for nm, ns in names.items():
        if len(ns) == 1 and nm not in keys:
            keys[nm] = ns[0]
    return keys


def write_forces(target: Any, result: Any) -> dict[str, int]:
    """Write a result's contact forces into an Assembly's or a BlockModel's interfaces.

    For every joint of ``result`` (a 3D result with a force state: ``check`` when
    admissible, ``min_friction``, ``max_load_multiplier``), the graph edge of its two
    blocks (added when missing) gets one interface per joint: an
    ``compas_assembly`` ``Interface`` (Assembly, edge attribute ``interfaces``) or a
    ``compas_dem`` ``FrictionContact`` (BlockModel, edge attribute ``contacts``) whose
    points are the joint's contact points and whose ``forces`` are the point forces in
    its frame (``c_np`` compression, ``c_nn`` 0, ``c_u`` and ``c_v`` the shear), the
    frame's z axis from the edge's first block into its second. The interfaces the
    edge had are replaced (our joints are found from the geometry and may differ from
    the file's); edges of the graph with no joint of ours keep their interfaces with
    their ``forces`` cleared. Forces are in the scene's force unit (volume x density
    for a compas_cra assembly, as its own solvers report them).

    Returns counts: ``interfaces`` written, ``edges_added``, ``edges_cleared``.
    """
    _require()
    state = getattr(result, "state", None)
    contacts = result.contacts
    if state is None:
        raise InputError(f"the result has no force state (status '{result.status}'): "
                         "nothing to write")
    if contacts.dimension != 3:
        raise InputError("write_forces needs a 3D result (a scene from an assembly)")
    if _is_assembly(target):
        attr = "interfaces"
        from compas_assembly.datastructures import Interface as Itf

        def make(points: list[list[float]], size: float, frame: Any) -> Any:
            return Itf(points=points, size=size, frame=frame)
    elif _is_blockmodel(target):
        attr = "contacts"
        from compas_dem.interactions import FrictionContact

        def make(points: list[list[float]], size: float, frame: Any) -> Any:
            return FrictionContact(points=points, frame=frame, size=size)
    else:
        raise InputError(f"not an Assembly or a BlockModel: {type(target).__name__}")
    graph = target.graph
    keys = _node_keys(target)
    ids = contacts.block_ids
    missing = [i for i in {ids[a] for a, _ in contacts.pairs} | {ids[b] for _, b in
               contacts.pairs} if i not in keys]
    if missing:
        raise InputError(f"block '{missing[0]}' of the result is not a node of the "
                         f"{type(target).__name__}: was the scene made from it?")
    normal = np.asarray(state.normal, dtype=float)
    shear = np.asarray(state.shear, dtype=float).reshape(len(normal), -1)
    per_edge: dict[tuple[Any, Any], list[Any]] = {}
    added = 0
    for k, (a, b) in enumerate(contacts.pairs):
        u, v = keys[ids[a]], keys[ids[b]]
        edge = _edge_key(graph, u, v)
        if edge is None:
            graph.add_edge(u, v, **{attr: []})
            edge, added = (u, v), added + 1
        sign = 1.0 if edge == (u, v) else -1.0
        s, e = contacts.joint_start[k], contacts.joint_start[k + 1]
        n = contacts.normals[k] * sign
        t1 = contacts.tangents[k, 0] * sign
        pts = contacts.points[s:e]
        frame = _frame(n, t1, pts.mean(axis=0))
        x, y = np.asarray(frame.xaxis, dtype=float), np.asarray(frame.yaxis, dtype=float)
        forces = []
        for p in range(s, e):
            # the force on the edge's second block (ours acts on pair[1] along +normal)
            f = normal[p] * contacts.normals[k] + shear[p] @ contacts.tangents[k]
            f = f * sign
            forces.append({"c_np": float(f @ n), "c_nn": 0.0, "c_u": float(f @ x),
                           "c_v": float(f @ y)})
        itf = make([[float(c) for c in q] for q in pts], float(contacts.areas[k]), frame)
        itf.forces = forces
        per_edge.setdefault(edge, []).append(itf)
    cleared = 0
    for edge in list(graph.edges()):
        if edge in per_edge:
            graph.edge_attribute(edge, attr, per_edge[edge])
            continue
        for itf in graph.edge_attribute(edge, attr) or []:
            itf.forces = None
            cleared += 1
    return {"interfaces": sum(len(v) for v in per_edge.values()), "edges_added": added,
            "edges_cleared": cleared}


def scene_to_assembly(scene: Scene) -> Any:
    """A ``compas_assembly`` Assembly of a 3D scene (node keys: the block ids when they
    are integers, else 0, 1, ... with the id in the block's ``name``), supports flagged
    and each block's unit weight as its ``density`` attribute."""
    _require()
    from compas_assembly.datastructures import Assembly, Block

    if scene.dimension != 3:
        raise InputError("scene_to_assembly needs a 3D scene (extrude a 2D one first)")
    assembly = Assembly(name=scene.name or "rigidblocks")
    numeric = all(b.id.isdigit() for b in scene.blocks)
    for k, b in enumerate(scene.blocks):
        blk = Block.from_vertices_and_faces([list(p) for p in b.vertices],
                                            [list(f) for f in b.faces or ()])
        blk.name = b.id
        w = b.unit_weight if b.unit_weight is not None else scene.effective_unit_weight
        blk.attributes["density"] = float(w)
        node = int(b.id) if numeric else k
        assembly.add_block(blk, node=node)
        assembly.graph.node_attribute(node, "is_support", bool(b.support))
    if isinstance(scene.friction, float | int):
        assembly.attributes["mu"] = float(scene.friction)
    return assembly
