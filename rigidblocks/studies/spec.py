"""Reading sweep spec files (format ``rigidblocks-sweep``, version 1).

The format is specified in ``docs/sweep-format.md``. Like the scene reader, the reader
is strict: unknown keys are errors, and every error is one line naming the file and the
key at fault (an unknown generator, generator parameter or analysis, a value of the
wrong type).
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..io.scene_file import unique_keys
from .sweep import Sweep, make_sweep

FORMAT = "rigidblocks-sweep"
VERSION = 1
TOP_KEYS = ("format", "version", "name", "generator", "scene", "parameters", "grid",
            "cases", "random", "analyses", "method")
TOP_REQUIRED = ("format", "version", "analyses")


def spec_from_dict(doc: Any, source: str | None = None,
                   base: str | os.PathLike | None = None) -> Sweep:
    """A validated :class:`~rigidblocks.studies.sweep.Sweep` from a parsed spec;
    ``base`` is the folder a relative ``scene`` path is taken from."""
    try:
        return _parse(doc, Path(base) if base is not None else Path("."), source)
    except InputError as err:
        raise (err.located(source) if source else err) from None


def _parse(doc: Any, base: Path, source: str | None) -> Sweep:
    if not isinstance(doc, dict):
        raise InputError(f"expected an object, got {json.dumps(doc)[:40]}", "sweep")
    for k in doc:
        if k not in TOP_KEYS:
            raise InputError(f'unknown key "{k}" (allowed: {", ".join(TOP_KEYS)})')
    for k in TOP_REQUIRED:
        if k not in doc:
            raise InputError(f'missing key "{k}"')
    if doc["format"] != FORMAT:
        raise InputError(f'"format" must be "{FORMAT}", got {json.dumps(doc["format"])}')
    if doc["version"] != VERSION or isinstance(doc["version"], bool):
        raise InputError(f'unsupported "version" {json.dumps(doc["version"])} (this reader '
                         f"knows version {VERSION})")
    has = [k for k in ("generator", "scene") if k in doc]
    if len(has) != 1:
        raise InputError('give exactly one of "generator" and "scene"')
    for k in ("name", "generator", "scene", "method"):
        if k in doc and not isinstance(doc[k], str):
            raise InputError(f"expected a string, got {json.dumps(doc[k])}", f'"{k}"')
    for k in ("parameters", "grid", "random"):
        if k in doc and not isinstance(doc[k], dict):
            raise InputError(f"expected an object, got {json.dumps(doc[k])[:40]}", f'"{k}"')
    if "cases" in doc and not isinstance(doc["cases"], list):
        raise InputError(f"expected a list, got {json.dumps(doc['cases'])[:40]}", '"cases"')
    if not isinstance(doc["analyses"], list):
        raise InputError(f"expected a list, got {json.dumps(doc['analyses'])[:40]}",
                         '"analyses"')
    if "generator" in doc:
        src: Any = doc["generator"]
    else:
        from ..io.scene_file import read_scene

        path = Path(doc["scene"])
        if not path.is_absolute():
            path = base / path
        if not path.exists():
            raise InputError(f"scene file {str(path)!r} not found", '"scene"')
        src = read_scene(path)
    return make_sweep(src, grid=doc.get("grid"), cases=doc.get("cases"),
                      random=doc.get("random"), parameters=doc.get("parameters"),
                      analyses=doc["analyses"], method=doc.get("method", "clarabel"),
                      name=doc.get("name"))


def _reject_constant(name: str) -> float:
    raise InputError(f"{name} is not a number in JSON")


def read_spec(path: str | os.PathLike) -> Sweep:
    """Read and validate a sweep spec file.

    Raises:
        InputError: unreadable file, bad JSON, or an invalid spec (one line naming the
            file and the key).
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8-sig")  # (a BOM: Windows editors)
    except OSError as err:
        raise InputError(f"cannot read: {err.strerror or err}", str(p)) from None
    try:
        doc = json.loads(text, parse_constant=_reject_constant,
                         object_pairs_hook=unique_keys)
    except json.JSONDecodeError as err:
        raise InputError(f"invalid JSON at line {err.lineno} column {err.colno}: {err.msg}",
                         str(p)) from None
    except InputError as err:
        raise err.located(str(p)) from None
    except RecursionError:
        raise InputError("invalid JSON: nested deeper than the decoder can follow",
                         str(p)) from None
    except ValueError as err:  # an integer literal past Python's digit limit
        why = str(err).splitlines()[0].split(";")[0]
        raise InputError(f"invalid JSON: {why}", str(p)) from None
    return spec_from_dict(doc, str(p), p.parent)


__all__ = ["FORMAT", "VERSION", "read_spec", "spec_from_dict"]
