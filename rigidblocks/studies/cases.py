"""Case expansion of a sweep: the cases (a grid, a list or random samples) and the
check of each parameter value against its generator's defaults."""

from __future__ import annotations

import itertools
import json
import math
from collections.abc import Iterable, Mapping, Sequence
from typing import Any

from ..errors import InputError
from ..scene.model import INFINITE
from ..scene.validate import is_number

#: parameters a scene source accepts (scene fields), besides ``load_factor``
SCENE_PARAMS = ("friction", "depth", "unit_weight")
RESERVED = ("load_factor", "flow")


def _plain(v: Any) -> Any:
    """Python scalars from numpy ones (np.float64 -> float)."""
    item = getattr(v, "item", None)
    return item() if callable(item) and not isinstance(v, str | bytes) else v


def param_specs(generator: str | None) -> dict[str, Any]:
    """Parameter name -> default (the type a value must have)."""
    if generator is None:
        return {"friction": 0.0, "depth": 1.0, "unit_weight": 1.0, "load_factor": 1.0,
                "flow": "associative"}
    from ..generators import get

    gen = get(generator)
    params = {p.name: _typed_default(p.default, p.annotation) for p in gen.params}
    clash = set(params) & set(RESERVED)
    if clash:  # pragma: no cover - no registered generator has one
        raise InputError(f"generator {generator!r} has a parameter named {sorted(clash)[0]!r}, "
                         "which sweeps reserve")
    return {**params, "load_factor": 1.0, "flow": "associative"}


class Optional:
    """The spec of a parameter whose default is None (automatic), given a value of the
    type of ``example`` or null: the arch's ``voussoirs: int | None`` took 5.5 (each case
    then failed) and "5" (run as 5, and as another case beside 5)."""

    def __init__(self, example: Any):
        self.example = example


def _typed_default(default: Any, annotation: str) -> Any:
    """A parameter's spec: its default, or where that is None, :class:`Optional` of the
    type its annotation names first (int or float), else None (any string or number)."""
    if default is not None:
        return default
    kind = annotation.split("|")[0].strip()
    return Optional({"int": 0, "float": 0.0}[kind]) if kind in ("int", "float") else None


#: parameters a minimum-thickness bisection cannot vary though they are sizes: the
#: friction its checks are asked at (bisected as a family's parameter, it was ignored:
#: "min <= 0.1" of an arch that needs f = 0.347), the weights' scale
NOT_BISECTED = {"friction": "the friction its checks are asked at (the friction command, "
                            "min_friction, answers how much a structure needs)",
                "unit_weight": "a scale of every weight, which no admissibility depends "
                               "on without point loads",
                "depth": "a scale of every weight and strength"}


def not_bisectable(name: str, spec: Any) -> str:
    """Why a minimum-thickness search cannot bisect the parameter ``name`` of this spec
    (:func:`param_specs`), or "": a count or a switch (an integer, possibly None by
    default, or a boolean), a choice (a string), or one of ``NOT_BISECTED``."""
    if name in NOT_BISECTED:
        return NOT_BISECTED[name]
    example = spec.example if isinstance(spec, Optional) else spec
    if isinstance(example, int | bool):
        return "a count or a switch, not a size to bisect"
    if isinstance(example, str):
        return "a choice, not a size to bisect"
    return ""


def check_value(name: str, value: Any, default: Any, where: str) -> Any:
    """``value`` checked against the type of ``default`` (an int is a number; friction
    may also be "infinite"; an :class:`Optional` one's, or null); returns it as a plain
    Python value."""
    v = _plain(value)
    if isinstance(default, Optional):
        return None if v is None else check_value(name, v, default.example, where)
    if name == "friction" and (v == INFINITE or (is_number(v) and math.isinf(v) and v > 0)):
        return INFINITE
    if isinstance(default, bool):
        ok = isinstance(v, bool)
        kind = "true or false"
    elif isinstance(default, int):
        ok = isinstance(v, int) and not isinstance(v, bool)
        kind = "an integer"
    elif isinstance(default, float):
        ok = is_number(v) and math.isfinite(v)
        kind = 'a number or "infinite"' if name == "friction" else "a finite number"
        v = float(v) if ok else v
    elif isinstance(default, str):
        ok = isinstance(v, str)
        kind = "a string"
    else:
        ok = isinstance(v, str) or is_number(v) or v is None
        kind = "a string or a number"
    if not ok:
        raise InputError(f"expected {kind}, got {json.dumps(v, default=str)}", where)
    if name in ("friction", "unit_weight", "load_factor") and is_number(v) and v < 0:
        raise InputError(f"must be >= 0, got {v}", where)
    if name == "flow" and v not in ("associative", "non-associative"):
        raise InputError(f'must be "associative" or "non-associative", got {json.dumps(v)}',
                         where)
    return v


def expand_cases(grid: Mapping[str, Sequence[Any]] | None = None,
                 cases: Sequence[Mapping[str, Any]] | None = None,
                 random: Mapping[str, Any] | None = None,
                 parameters: Mapping[str, Any] | None = None) -> list[dict[str, Any]]:
    """The cases of a sweep, each the fixed ``parameters`` updated with its own values.

    Exactly one of:

    * ``grid``: name -> list of values; the cartesian product, the last name varying
      fastest;
    * ``cases``: a list of parameter dictionaries;
    * ``random``: ``{"samples": n, "seed": s, "uniform": {name: [lo, hi]},
      "integers": {name: [lo, hi]} (inclusive), "choice": {name: [values]}}``, drawn
      with :func:`numpy.random.default_rng` (seed) in that order of kinds, then of names.

    A case repeating an earlier one (same parameters) is dropped.
    """
    given = [k for k, v in (("grid", grid), ("cases", cases), ("random", random))
             if v is not None]
    if len(given) != 1:
        raise InputError("give exactly one of grid, cases, random"
                         + (f" (got {', '.join(given)})" if given else ""))
    fixed = dict(parameters or {})
    out: list[dict[str, Any]] = []
    if grid is not None:
        if not isinstance(grid, Mapping) or not grid:
            raise InputError("expected a non-empty object of parameter -> list of values",
                             "grid")
        names = list(grid)
        for n in names:
            vals = grid[n]
            if isinstance(vals, str) or not isinstance(vals, Iterable):
                raise InputError(f"expected a list of values, got {vals!r}", f"grid.{n}")
        lists = [[_plain(v) for v in grid[n]] for n in names]
        for n, vals in zip(names, lists, strict=True):
            if not vals:
                raise InputError("expected at least one value", f"grid.{n}")
        out = [{**fixed, **dict(zip(names, combo, strict=True))}
               for combo in itertools.product(*lists)]
    elif cases is not None:
        if isinstance(cases, Mapping | str) or not isinstance(cases, Iterable):
            raise InputError("expected a list of objects", "cases")
        for i, c in enumerate(cases):
            if not isinstance(c, Mapping):
                raise InputError(f"expected an object, got {c!r}", f"cases[{i}]")
            out.append({**fixed, **{k: _plain(v) for k, v in c.items()}})
        if not out:
            raise InputError("expected at least one case", "cases")
    else:
        out = _random_cases(random, fixed)  # type: ignore[arg-type]
    seen: set[str] = set()
    unique = []
    for c in out:
        key = json.dumps(c, sort_keys=True, default=str)
        if key not in seen:
            seen.add(key)
            unique.append(c)
    return unique


RANDOM_KEYS = ("samples", "seed", "uniform", "integers", "choice")


def _random_cases(spec: Mapping[str, Any], fixed: dict[str, Any]) -> list[dict[str, Any]]:
    import numpy as np

    if not isinstance(spec, Mapping):
        raise InputError("expected an object", "random")
    for k in spec:
        if k not in RANDOM_KEYS:
            raise InputError(f'unknown key "{k}" (allowed: {", ".join(RANDOM_KEYS)})',
                             "random")
    for k in ("samples", "seed"):
        v = _plain(spec.get(k))
        if not isinstance(v, int) or isinstance(v, bool) or v < (1 if k == "samples" else 0):
            raise InputError(f"expected an integer >= {1 if k == 'samples' else 0}, got "
                             f"{json.dumps(v, default=str)}", f"random.{k}")
    n = int(spec["samples"])
    rng = np.random.default_rng(int(spec["seed"]))
    cols: dict[str, list[Any]] = {}
    for kind in ("uniform", "integers", "choice"):
        block = spec.get(kind, {})
        if not isinstance(block, Mapping):
            raise InputError("expected an object of parameter -> values", f"random.{kind}")
        for name, rng_spec in block.items():
            where = f"random.{kind}.{name}"
            if name in cols:
                raise InputError("parameter drawn twice", where)
            if kind == "choice":
                if isinstance(rng_spec, str) or not isinstance(rng_spec, Sequence) \
                        or not rng_spec:
                    raise InputError("expected a non-empty list of values", where)
                idx = rng.integers(0, len(rng_spec), n)
                cols[name] = [_plain(rng_spec[i]) for i in idx]
                continue
            if (isinstance(rng_spec, str) or not isinstance(rng_spec, Sequence)
                    or len(rng_spec) != 2 or not all(is_number(_plain(x)) for x in rng_spec)):
                raise InputError(f"expected [low, high], got {rng_spec!r}", where)
            lo, hi = (_plain(x) for x in rng_spec)
            if not _finite_span(lo, hi):  # (numpy draws over no such range)
                raise InputError(f"expected finite numbers, got [{lo}, {hi}]", where)
            if not lo <= hi:
                raise InputError(f"expected low <= high, got [{lo}, {hi}]", where)
            if kind == "uniform":
                cols[name] = [float(x) for x in rng.uniform(lo, hi, n)]
            else:
                if not (isinstance(lo, int) and isinstance(hi, int)):
                    raise InputError(f"expected integer bounds, got [{lo}, {hi}]", where)
                cols[name] = [int(x) for x in rng.integers(lo, hi + 1, n)]
    if not cols:
        raise InputError("nothing to draw: give uniform, integers or choice", "random")
    return [{**fixed, **{k: v[i] for k, v in cols.items()}} for i in range(n)]


def _finite_span(lo: float, hi: float) -> bool:
    """Is hi - lo a finite float (a JSON integer of 400 digits is none)?"""
    try:
        return math.isfinite(float(hi) - float(lo))
    except OverflowError:
        return False


def _known(k: str, specs: Mapping[str, Any], generator: str | None, where: str) -> None:
    if k not in specs:
        what = f"generator {generator!r}" if generator else "a scene source"
        raise InputError(f"unknown parameter {k!r} for {what} (parameters: "
                         f"{', '.join(sorted(specs))})", where)


__all__ = ["NOT_BISECTED", "RANDOM_KEYS", "RESERVED", "SCENE_PARAMS", "check_value",
           "expand_cases", "not_bisectable"]
