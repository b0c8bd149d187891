"""Reading and writing scene files (format ``rigidblocks-scene``, version 1).

The format is specified in ``docs/scene-format.md``. The reader is strict: every key is
checked, unknown keys are errors, and every error is one line naming the file and the
block id or key at fault. The writer emits a canonical layout (one block, load or joint
per line) that the reader reads back to an equal scene, so that
``write(read(file)) == file`` for files the writer made.
"""

from __future__ import annotations

import json
import math
import os
import re
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..scene.model import (
    FLOWS,
    INFINITE,
    Block,
    JointOverride,
    Load,
    Scene,
    Units,
    friction_value,
)
from ..scene.validate import check_faces, is_number

FORMAT = "rigidblocks-scene"
VERSION = 1

TOP_KEYS = {"format", "version", "name", "dimension", "units", "depth", "unit_weight",
            "friction", "blocks", "loads", "live_body_force", "joints", "load_factor",
            "flow"}
TOP_REQUIRED = ("format", "version", "dimension", "blocks")
BLOCK_KEYS = {"id", "vertices", "faces", "support", "unit_weight"}
LOAD_KEYS = {"block", "force", "point", "moment", "live"}
JOINT_KEYS = {"blocks", "friction", "cohesion", "tensile_strength", "flow"}
UNIT_KEYS = {"length", "force"}
#: how deeply a scene document nests lists and objects: the scene, "blocks", a block,
#: "vertices" (or "faces"), a point
SCENE_DEPTH = 5
#: a document nested deeper is refused before it is read as a scene (a value nested a
#: little too deep is named by the reader with its block and key)
NESTING_LIMIT = 32


# -- small strict parsers -------------------------------------------------------------
def _number(v: Any, where: str, *, minimum: float | None = None, positive: bool = False):
    if not is_number(v):
        raise InputError(f"expected a number, got {json.dumps(v)}", where)
    if not math.isfinite(v):
        raise InputError(f"expected a finite number, got {v}", where)
    if positive and not v > 0:
        raise InputError(f"must be > 0, got {v}", where)
    if minimum is not None and v < minimum:
        raise InputError(f"must be >= {minimum:g}, got {v}", where)
    return v


def _vector(v: Any, n: int, where: str) -> tuple:
    if not isinstance(v, list) or len(v) != n:
        raise InputError(f"expected a list of {n} numbers, got {json.dumps(v)}", where)
    return tuple(_number(c, where) for c in v)


def _plain_points(points: list, dim: int) -> bool:
    """Is every point a list of ``dim`` finite JSON numbers (the common case, checked
    without building an error location per coordinate)?"""
    kinds = (int, float)
    return (all(type(p) is list and len(p) == dim for p in points)
            and all(type(c) in kinds for p in points for c in p)
            and all(map(math.isfinite, (c for p in points for c in p))))


def _friction(v: Any, where: str):
    if v == INFINITE:
        return INFINITE
    if isinstance(v, str):
        raise InputError(f'expected a number >= 0 or "infinite", got "{v}"', where)
    f = _number(v, where, minimum=0)
    try:
        friction_value(f)
    except InputError as err:
        raise InputError(str(err), where) from None
    return f


def _flow(v: Any, where: str) -> str:
    if v not in FLOWS:
        raise InputError(f'expected "associative" or "non-associative", got {json.dumps(v)}',
                         where)
    return v


def _bool(v: Any, where: str) -> bool:
    if not isinstance(v, bool):
        raise InputError(f"expected true or false, got {json.dumps(v)}", where)
    return v


def _string(v: Any, where: str) -> str:
    if not isinstance(v, str):
        raise InputError(f"expected a string, got {json.dumps(v)}", where)
    return v


def _keys(obj: Any, allowed: set[str], required: tuple[str, ...], where: str) -> dict:
    if not isinstance(obj, dict):
        raise InputError(f"expected an object, got {json.dumps(obj)[:40]}", where)
    for k in obj:
        if k not in allowed:
            raise InputError(f'unknown key "{k}" (allowed: {", ".join(sorted(allowed))})',
                             where)
    for k in required:
        if k not in obj:
            raise InputError(f'missing key "{k}"', where)
    return obj


def unique_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """A JSON object from its ``pairs`` (``json.loads``'s ``object_pairs_hook``), refused
    where a key appears twice: the decoder keeps the last, and a slip of editing
    ("friction": 0.6 ... "friction": 0.1) changed the answer without a word."""
    out: dict[str, Any] = {}
    for k, v in pairs:
        if k in out:
            ident = out.get("id", v if k == "id" else None)
            names = list(dict.fromkeys(p for p, _ in pairs))[:6]
            keys = ", ".join(f'"{name}"' for name in names)
            where = f" (in the object with id {ident!r})" if isinstance(ident, str) else \
                f" (in the object with the keys {keys})"
            raise InputError(f"the key \"{k}\" appears twice in one object{where}: which "
                             "value is meant? give it once")
        out[k] = v
    return out


def _nonfinite_constant(name: str) -> float:
    # NaN / Infinity literals are read as floats so that the strict value checks reject
    # them with the block and key they stand in (every number goes through _number)
    return float(name)


# -- reading --------------------------------------------------------------------------
def scene_from_dict(doc: Any, source: str | None = None, *, validate: bool = True) -> Scene:
    """Build a :class:`Scene` from a parsed JSON document, checking every key.

    With ``validate`` (the default) the geometry is checked too (simple polygons, no
    overlaps, supports present, joint overrides on touching blocks): see
    :func:`rigidblocks.scene.validate.validate_scene`.
    """
    try:
        scene = _parse(doc, source)
        if validate:
            from ..contacts import detect_contacts
            from ..scene.validate import validate_scene

            validate_scene(scene)
            if scene.joints:  # overrides must name touching blocks
                detect_contacts(scene)
    except InputError as err:
        raise (err.located(source) if source else err) from None
    return scene


def _parse(doc: Any, source: str | None) -> Scene:
    top = _keys(doc, TOP_KEYS, TOP_REQUIRED, "scene")
    if top["format"] != FORMAT:
        raise InputError(f'"format" must be "{FORMAT}", got {json.dumps(top["format"])}')
    if top["version"] != VERSION or isinstance(top["version"], bool):
        raise InputError(f'unsupported "version" {json.dumps(top["version"])} '
                         f"(this reader knows version {VERSION})")
    dim = top["dimension"]
    if dim not in (2, 3) or isinstance(dim, bool):
        raise InputError(f'"dimension" must be 2 or 3, got {json.dumps(dim)}')
    dim = int(dim)  # (2.0 is 2, as "version" 1.0 is 1; a float indexed the load rows)
    name = _string(top["name"], '"name"') if "name" in top else None
    units = None
    if "units" in top:
        u = _keys(top["units"], UNIT_KEYS, (), '"units"')
        units = Units(*(_string(u[k], f'"units.{k}"') if k in u else None
                        for k in ("length", "force")))
    depth = None
    if "depth" in top:
        if dim == 3:
            raise InputError('"depth" is for 2D scenes only')
        depth = _number(top["depth"], '"depth"', positive=True)
    unit_weight = (_number(top["unit_weight"], '"unit_weight"', minimum=0)
                   if "unit_weight" in top else None)
    friction = _friction(top["friction"], '"friction"') if "friction" in top else None
    lbf = (_vector(top["live_body_force"], dim, '"live_body_force"')
           if "live_body_force" in top else None)
    load_factor = (_number(top["load_factor"], '"load_factor"', minimum=0)
                   if "load_factor" in top else None)
    flow = _flow(top["flow"], '"flow"') if "flow" in top else None

    if not isinstance(top["blocks"], list):
        raise InputError('"blocks" must be a list of blocks')
    blocks = tuple(_parse_block(b, i, dim) for i, b in enumerate(top["blocks"]))
    loads = tuple(_parse_load(ld, i, dim) for i, ld in enumerate(_list(top, "loads")))
    joints = tuple(_parse_joint(j, i) for i, j in enumerate(_list(top, "joints")))
    return Scene(dimension=dim, blocks=blocks, loads=loads, joints=joints, name=name,
                 units=units, depth=depth, unit_weight=unit_weight, friction=friction,
                 live_body_force=lbf, load_factor=load_factor, flow=flow,
                 source=source)


def _list(top: dict, key: str) -> list:
    v = top.get(key, [])
    if not isinstance(v, list):
        raise InputError(f'"{key}" must be a list')
    return v


def _parse_block(b: Any, i: int, dim: int) -> Block:
    where = f"block #{i}"
    if isinstance(b, dict) and isinstance(b.get("id"), str):
        where = f"block {b['id']!r}"
    b = _keys(b, BLOCK_KEYS, ("id", "vertices"), where)
    bid = _string(b["id"], f'{where} "id"')
    if bid == "":
        raise InputError('"id" must not be empty', where)
    verts = b["vertices"]
    if not isinstance(verts, list):
        raise InputError('"vertices" must be a list of points', where)
    minimum = 3 if dim == 2 else 4
    if len(verts) < minimum:
        raise InputError(f"needs at least {minimum} vertices, got {len(verts)}", where)
    if _plain_points(verts, dim):
        vertices = tuple(map(tuple, verts))
    else:  # the slow path finds and names the bad vertex
        vertices = tuple(_vector(v, dim, f'{where} "vertices"[{k}]')
                         for k, v in enumerate(verts))
    faces = None
    if "faces" in b:
        if dim == 2:
            raise InputError('"faces" is for 3D blocks only', where)
        faces = _parse_faces(b["faces"], len(vertices), where)
    elif dim == 3:
        raise InputError('missing key "faces" (required for 3D blocks)', where)
    support = _bool(b["support"], f'{where} "support"') if "support" in b else None
    uw = (_number(b["unit_weight"], f'{where} "unit_weight"', minimum=0)
          if "unit_weight" in b else None)
    return Block(bid, vertices, faces, bool(support), uw)


def _plain_faces(faces: list, nv: int) -> bool:
    """Is every face a list of at least 3 JSON integers in 0..nv-1 (the common case,
    checked without a test per index)?"""
    if not all(type(f) is list and len(f) >= 3 for f in faces):
        return False
    flat = [i for f in faces for i in f]
    return all(type(i) is int for i in flat) and 0 <= min(flat) and max(flat) < nv


def _parse_faces(faces: Any, nv: int, where: str) -> tuple[tuple[int, ...], ...]:
    if isinstance(faces, list) and len(faces) >= 4 and _plain_faces(faces, nv):
        return tuple(map(tuple, faces))
    check_faces(faces, nv, where)  # names the bad face
    return tuple(map(tuple, faces))


def _parse_load(ld: Any, i: int, dim: int) -> Load:
    where = f"load #{i}"
    ld = _keys(ld, LOAD_KEYS, ("block", "force"), where)
    block = _string(ld["block"], f'{where} "block"')
    where = f"load #{i} on block {block!r}"
    force = _vector(ld["force"], dim, f'{where} "force"')
    point = _vector(ld["point"], dim, f'{where} "point"') if "point" in ld else None
    moment = None
    if "moment" in ld:
        moment = (_number(ld["moment"], f'{where} "moment"') if dim == 2
                  else _vector(ld["moment"], 3, f'{where} "moment"'))
    live = _bool(ld["live"], f'{where} "live"') if "live" in ld else None
    return Load(block, force, point, moment, live)


def _parse_joint(j: Any, i: int) -> JointOverride:
    where = f"joint #{i}"
    j = _keys(j, JOINT_KEYS, ("blocks",), where)
    pair = j["blocks"]
    if not (isinstance(pair, list) and len(pair) == 2 and all(isinstance(s, str) for s in pair)):
        raise InputError('"blocks" must be a list of two block ids', where)
    if pair[0] == pair[1]:
        raise InputError(f"a joint needs two different blocks, got {pair[0]!r} twice", where)
    where = f"joint {pair[0]!r}-{pair[1]!r}"
    friction = _friction(j["friction"], f'{where} "friction"') if "friction" in j else None
    coh = (_number(j["cohesion"], f'{where} "cohesion"', minimum=0)
           if "cohesion" in j else None)
    ts = (_number(j["tensile_strength"], f'{where} "tensile_strength"', minimum=0)
          if "tensile_strength" in j else None)
    flow = _flow(j["flow"], f'{where} "flow"') if "flow" in j else None
    return JointOverride((pair[0], pair[1]), friction, coh, ts, flow)


#: what a DXF drawing given where a scene file goes is told
DXF_GIVEN = ("a DXF drawing, not a scene file: make its scene with `rigidblocks import-dxf "
             "{} -o SCENE.json` (rigidblocks.read_dxf in Python)")


def _is_dxf(text: str) -> bool:
    """Does the text open as a DXF drawing: group code 0 and SECTION, after any 999
    comments (a drawing that opened with one read as malformed JSON)?"""
    lines = [ln.strip() for ln in text.lstrip()[:2000].splitlines()]
    while lines[:1] == ["999"]:  # a comment: its code's line and its text's
        lines = lines[2:]
    return lines[:2] == ["0", "SECTION"]


def loads_json(text: str, source: str | None = None) -> Any:
    """Parse JSON text; errors are InputError.

    NaN and Infinity literals parse as non-finite floats, which :func:`scene_from_dict`
    rejects naming the block and key where they stand.
    """
    try:
        doc = json.loads(text, parse_constant=_nonfinite_constant,
                         object_pairs_hook=unique_keys)
    except json.JSONDecodeError as err:
        if _is_dxf(text):  # (it read "malformed JSON: Extra data ...")
            raise InputError(DXF_GIVEN.format(source or "DRAWING.dxf"), source) from None
        raise InputError(f"malformed JSON: {err.msg.removesuffix(' at')} at line "
                         f"{err.lineno} column {err.colno}",
                         source) from None
    except InputError as err:
        raise (err.located(source) if source else err) from None
    except RecursionError:  # the decoder's own recursion, thousands of levels deep
        raise InputError(f"JSON nested deeper than the decoder can follow; a scene "
                         f"nests {SCENE_DEPTH} levels at most", source) from None
    except ValueError as err:  # an integer literal past Python's digit limit
        why = str(err).splitlines()[0].split(";")[0]
        raise InputError(f"malformed JSON: {why}", source) from None
    depth = _depth(text)
    if depth > NESTING_LIMIT:
        raise InputError(f"JSON nested more than {NESTING_LIMIT} levels deep; a scene nests "
                         f"{SCENE_DEPTH} at most (scene, blocks, block, vertices, point)",
                         source)
    return doc


#: a JSON string literal (with its escapes), or a run of text that holds neither a
#: bracket nor a string
_NOT_BRACKET = re.compile(r'"[^"\\]*(?:\\.[^"\\]*)*"|[^\[\]{}"]+')
#: an innermost list or object, once only the brackets are left
_INNERMOST = re.compile(r"\[\]|\{\}")


def _depth(text: str) -> int:
    """How deeply lists and objects nest in a JSON text that parses (a number: 0).

    Only the brackets outside string literals are kept; each pass takes away every list
    and object that holds no other, so the passes needed to take them all are the depth
    (counted up to one past :data:`NESTING_LIMIT`). All in the regular-expression engine:
    on the extruded 1,009-block wall's file (360 kB) 3-5 ms of CPU, against 12-13 ms for
    a walk through the parsed document (its 2D file: 1-2 against 4 ms)."""
    left = _NOT_BRACKET.sub("", text)
    depth = 0
    while left and depth <= NESTING_LIMIT:
        left = _INNERMOST.sub("", left)
        depth += 1
    return depth


def read_scene(path: str | os.PathLike, *, validate: bool = True) -> Scene:
    """Read and validate a scene file.

    Raises:
        InputError: with a one-line message naming the file and the block or key at
            fault.
    """
    name = str(path)
    if not name.strip():  # (Path("") is the working folder: "Is a directory: '.'")
        raise InputError("no scene file given (an empty path)")
    if Path(path).is_dir():
        raise InputError("a folder, not a scene file", name)
    try:
        text = Path(path).read_text(encoding="utf-8-sig")  # (a BOM: Windows editors)
    except FileNotFoundError:
        raise InputError("no such file", name) from None
    except UnicodeDecodeError:
        if Path(path).read_bytes()[:18] == b"AutoCAD Binary DXF":
            raise InputError(DXF_GIVEN.format(name), name) from None
        # (it gave Python's "'utf-8' codec can't decode byte 0xff in position 0")
        raise InputError("not UTF-8 text (a scene is a JSON file in UTF-8: save it so, "
                         "e.g. not as UTF-16)", name) from None
    except OSError as err:
        raise InputError(f"cannot read: {err}", name) from None
    return scene_from_dict(loads_json(text, name), name, validate=validate)


# -- writing --------------------------------------------------------------------------
def scene_to_dict(scene: Scene) -> dict:
    """The scene as a JSON-ready dict, optional keys only where they were given."""
    doc: dict[str, Any] = {"format": FORMAT, "version": VERSION}
    if scene.name is not None:
        doc["name"] = scene.name
    doc["dimension"] = scene.dimension
    if scene.units is not None:
        doc["units"] = {k: v for k, v in (("length", scene.units.length),
                                          ("force", scene.units.force)) if v is not None}
    for key in ("depth", "unit_weight", "friction"):
        if getattr(scene, key) is not None:
            doc[key] = getattr(scene, key)
    doc["blocks"] = [_block_dict(b) for b in scene.blocks]
    if scene.loads:
        doc["loads"] = [_drop_none({"block": ld.block, "force": list(ld.force),
                                    "point": _maybe_list(ld.point),
                                    "moment": _maybe_list(ld.moment), "live": ld.live})
                        for ld in scene.loads]
    if scene.live_body_force is not None:
        doc["live_body_force"] = list(scene.live_body_force)
    if scene.load_factor is not None:
        doc["load_factor"] = scene.load_factor
    if scene.flow is not None:
        doc["flow"] = scene.flow
    if scene.joints:
        doc["joints"] = [_drop_none({"blocks": list(j.blocks), "friction": j.friction,
                                     "cohesion": j.cohesion,
                                     "tensile_strength": j.tensile_strength,
                                     "flow": j.flow})
                         for j in scene.joints]
    return doc


def _maybe_list(v):
    return list(v) if isinstance(v, tuple) else v


def _drop_none(d: dict) -> dict:
    return {k: v for k, v in d.items() if v is not None}


def _block_dict(b: Block) -> dict:
    d: dict[str, Any] = {"id": b.id, "vertices": [list(v) for v in b.vertices]}
    if b.faces is not None:
        d["faces"] = [list(f) for f in b.faces]
    if b.support:
        d["support"] = True
    if b.unit_weight is not None:
        d["unit_weight"] = b.unit_weight
    return d


def dumps_scene(scene: Scene) -> str:
    """The canonical text of a scene file: one block, load or joint per line."""
    doc = scene_to_dict(scene)
    lines = ["{"]
    items = list(doc.items())
    for k, (key, value) in enumerate(items):
        comma = "," if k < len(items) - 1 else ""
        if isinstance(value, list) and value and isinstance(value[0], dict):
            lines.append(f"  {json.dumps(key)}: [")
            for m, item in enumerate(value):
                c = "," if m < len(value) - 1 else ""
                lines.append(f"    {_compact(item)}{c}")
            lines.append(f"  ]{comma}")
        else:
            lines.append(f"  {json.dumps(key)}: {_compact(value)}{comma}")
    lines.append("}")
    return "\n".join(lines) + "\n"


def _compact(value: Any) -> str:
    return json.dumps(value, separators=(", ", ": "), allow_nan=False)


def write_scene(scene: Scene, path: str | os.PathLike) -> None:
    """Write a scene file in the canonical layout (see :func:`dumps_scene`).

    Raises:
        InputError: the file cannot be written (its folder is missing, say).
    """
    from ..scene.validate import check_fields, check_representable

    check_fields(scene)  # (a block of two vertices was written, and refused when read)
    # (extrude --depth 1e200 wrote a scene that every command then refused)
    check_representable(scene)
    text = dumps_scene(scene)
    try:
        Path(path).write_text(text, encoding="utf-8")
    except OSError as err:
        raise InputError(f"cannot write: {err.strerror or err}", str(path)) from None

