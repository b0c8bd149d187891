"""Parametric studies: many independent analyses of a family of structures.

A sweep is a source of scenes -- a generator of :mod:`rigidblocks.generators` called
with each case's parameters, or one scene whose ``friction``, ``depth`` or
``unit_weight`` a case overrides -- plus the cases (a grid, a list, or random samples
with a seed) and the analyses to run on each: ``check``, ``min_friction``,
``max_load_multiplier``, ``min_thickness``. The reserved parameter ``load_factor``
(default 1, as in :func:`rigidblocks.check`) multiplies the live loads in ``check``
and ``min_friction``; the arch generators carry a live horizontal body force, so
``load_factor = 0`` means self-weight only.

Every case is independent: a case that raises (a generator rejecting its parameters,
a solver failure) is recorded with its error message and the study goes on. Results
are one row per case, identified by ``case_id``, a hash of everything that fixes the
answer (source, parameters, analyses, method). Rows are written in chunks next to the
output file (``OUTPUT.parts/``) as cases finish and merged into the output file at the
end; a study started again with the same output skips the cases already done, so an
interrupted study loses at most the cases in flight.

Executors: one process (``workers=1``), local processes
(:class:`concurrent.futures.ProcessPoolExecutor`, the default, all cores) or a Dask
cluster (``scheduler="tcp://..."`` or ``client=``). Cases go to the workers in
batches, so that the overhead of a task is shared by many small solves.

Example:
    >>> from rigidblocks import study
    >>> res = study.run("flat_arch", grid={"voussoirs": [3, 5]},
    ...                 parameters={"load_factor": 0.0}, analyses=["min_friction"],
    ...                 workers=1, progress=False)
    >>> res.frame["status"].tolist()
    ['ok', 'ok']
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import os
import shutil
import time
import uuid
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..scene.model import INFINITE, Scene

#: analysis name -> options it accepts (given in the analysis entry, not per case)
ANALYSES: dict[str, tuple[str, ...]] = {
    "check": (),
    "min_friction": (),
    "max_load_multiplier": (),
    "min_thickness": ("param", "lo", "hi", "rtol", "friction"),
}
#: answer columns of each analysis (besides ``<analysis>_status``)
ANSWERS: dict[str, tuple[str, ...]] = {
    "check": ("admissible", "violation"),
    "min_friction": ("friction_factor", "friction_angle_deg"),
    "max_load_multiplier": ("load_multiplier",),
    "min_thickness": ("min_thickness", "min_thickness_lower"),
}
#: parameters a scene source accepts (scene fields), besides ``load_factor``
SCENE_PARAMS = ("friction", "depth", "unit_weight")
RESERVED = ("load_factor",)
#: columns of every row besides the parameters and the answers
BASE_COLUMNS = ("case", "case_id", "status", "error", "time", "solve_time")
METHODS = ("clarabel", "distortion")


# -- the sweep -------------------------------------------------------------------------
@dataclass(frozen=True)
class Analysis:
    """One analysis to run on every case, with its options (``min_thickness``: param,
    lo, hi, rtol, friction; see :func:`rigidblocks.min_thickness`)."""

    name: str
    options: tuple[tuple[str, Any], ...] = ()

    def to_json(self) -> Any:
        return {"analysis": self.name, **dict(self.options)} if self.options else self.name


@dataclass(frozen=True)
class Sweep:
    """A parametric study: the scene source, the cases and the analyses.

    Build one with :func:`make_sweep` (or read a spec file with
    :func:`rigidblocks.studies.spec.read_spec`), which validates every parameter.
    ``cases`` are the parameter dictionaries, fixed parameters included, in order.
    """

    generator: str | None
    scene: Scene | None
    cases: tuple[dict[str, Any], ...]
    analyses: tuple[Analysis, ...]
    method: str = "clarabel"
    name: str | None = None
    source: str | None = None

    @property
    def parameter_names(self) -> list[str]:
        names: dict[str, None] = {}
        for c in self.cases:
            names.update(dict.fromkeys(c))
        return list(names)

    @property
    def columns(self) -> list[str]:
        cols = ["case", "case_id", *self.parameter_names, "status", "error", "time",
                "solve_time"]
        for a in self.analyses:
            cols += [f"{a.name}_status", *ANSWERS[a.name]]
        return cols

    def _source_key(self) -> str:
        if self.generator is not None:
            return f"generator:{self.generator}"
        from ..io.scene_file import dumps_scene

        assert self.scene is not None
        return "scene:" + hashlib.sha256(dumps_scene(self.scene).encode()).hexdigest()[:16]

    def case_ids(self) -> list[str]:
        """A stable identifier of each case: a hash of the source (generator name, or
        the scene's canonical text), the case's parameters, the analyses and method."""
        head = {"source": self._source_key(), "method": self.method,
                "analyses": [a.to_json() for a in self.analyses]}
        out = []
        for c in self.cases:
            text = json.dumps({**head, "params": c}, sort_keys=True, default=str)
            out.append(hashlib.sha256(text.encode()).hexdigest()[:16])
        return out


def _plain(v: Any) -> Any:
    """Python scalars from numpy ones (np.float64 -> float)."""
    item = getattr(v, "item", None)
    return item() if callable(item) and not isinstance(v, str | bytes) else v


def _is_number(v: Any) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool)


def _param_specs(generator: str | None) -> dict[str, Any]:
    """Parameter name -> default (the type a value must have)."""
    if generator is None:
        return {"friction": 0.0, "depth": 1.0, "unit_weight": 1.0, "load_factor": 1.0}
    from ..generators import get

    gen = get(generator)
    params = {p.name: p.default for p in gen.params}
    clash = set(params) & set(RESERVED)
    if clash:  # pragma: no cover - no registered generator has one
        raise InputError(f"generator {generator!r} has a parameter named {sorted(clash)[0]!r}, "
                         "which sweeps reserve")
    return {**params, "load_factor": 1.0}


def check_value(name: str, value: Any, default: Any, where: str) -> Any:
    """``value`` checked against the type of ``default`` (an int is a number; friction
    may also be "infinite"); returns it as a plain Python value."""
    v = _plain(value)
    if name == "friction" and (v == INFINITE or (_is_number(v) and math.isinf(v) and v > 0)):
        return INFINITE
    if isinstance(default, bool):
        ok = isinstance(v, bool)
        kind = "true or false"
    elif isinstance(default, int):
        ok = isinstance(v, int) and not isinstance(v, bool)
        kind = "an integer"
    elif isinstance(default, float):
        ok = _is_number(v) and math.isfinite(v)
        kind = 'a number or "infinite"' if name == "friction" else "a finite number"
        v = float(v) if ok else v
    elif isinstance(default, str):
        ok = isinstance(v, str)
        kind = "a string"
    else:
        ok = isinstance(v, str) or _is_number(v) or v is None
        kind = "a string or a number"
    if not ok:
        raise InputError(f"expected {kind}, got {json.dumps(v, default=str)}", where)
    if name in ("friction", "unit_weight", "load_factor") and _is_number(v) and v < 0:
        raise InputError(f"must be >= 0, got {v}", where)
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
                    or len(rng_spec) != 2 or not all(_is_number(_plain(x)) for x in rng_spec)):
                raise InputError(f"expected [low, high], got {rng_spec!r}", where)
            lo, hi = (_plain(x) for x in rng_spec)
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


def _analysis(entry: Any, where: str) -> Analysis:
    if isinstance(entry, Analysis):
        name, opts = entry.name, dict(entry.options)
    elif isinstance(entry, str):
        name, opts = entry, {}
    elif isinstance(entry, Mapping):
        if "analysis" not in entry:
            raise InputError('missing key "analysis"', where)
        opts = dict(entry)
        name = opts.pop("analysis")
    else:
        raise InputError(f"expected an analysis name or object, got {entry!r}", where)
    if name not in ANALYSES:
        raise InputError(f"unknown analysis {name!r} (choose from {', '.join(ANALYSES)})",
                         where)
    for k in opts:
        if k not in ANALYSES[name]:
            allowed = ", ".join(ANALYSES[name]) or "none"
            raise InputError(f'unknown option "{k}" of {name} (allowed: {allowed})', where)
    for k in ("lo", "hi", "rtol"):
        if k in opts and not (_is_number(_plain(opts[k])) and _plain(opts[k]) > 0):
            raise InputError(f"{k} must be a number > 0, got {opts[k]!r}", where)
    if "param" in opts and not isinstance(opts["param"], str):
        raise InputError(f"param must be a string, got {opts['param']!r}", where)
    if "friction" in opts:
        opts["friction"] = check_value("friction", opts["friction"], 0.0, where)
    return Analysis(name, tuple(sorted((k, _plain(v)) for k, v in opts.items())))


def make_sweep(source: str | Scene, *, grid: Mapping[str, Sequence[Any]] | None = None,
               cases: Sequence[Mapping[str, Any]] | None = None,
               random: Mapping[str, Any] | None = None,
               parameters: Mapping[str, Any] | None = None,
               analyses: Sequence[Any] = ("min_friction",), method: str = "clarabel",
               name: str | None = None) -> Sweep:
    """A validated :class:`Sweep`.

    Args:
        source: a generator name (``rigidblocks example --list``), a :class:`Scene`,
            or the path of a scene file.
        grid, cases, random: the cases (exactly one; see :func:`expand_cases`).
        parameters: values fixed for every case.
        analyses: names among check, min_friction, max_load_multiplier, min_thickness,
            or objects ``{"analysis": "min_thickness", "param": ..., "lo": ...}``.
        method: "clarabel" (convex path) or "distortion".

    Raises:
        InputError: unknown generator, parameter or analysis, or a value of the wrong
            type (one line naming the key).
    """
    generator: str | None = None
    scene: Scene | None = None
    src_label = None
    if isinstance(source, Scene):
        scene = source
        src_label = source.source
    elif isinstance(source, str | os.PathLike) and (
            str(source).endswith(".json") or os.sep in str(source)):
        from ..io.scene_file import read_scene

        scene = read_scene(source)
        src_label = str(source)
    elif isinstance(source, str):
        from ..generators import get

        get(source)  # unknown generator -> InputError naming the choices
        generator = source
    else:
        raise InputError(f"expected a generator name, a scene or a scene file, got {source!r}")
    if method not in METHODS:
        raise InputError(f"unknown method {method!r} (choose from {', '.join(METHODS)})",
                         "method")
    specs = _param_specs(generator)
    for k in parameters or {}:
        _known(k, specs, generator, f"parameters.{k}")
    for k in grid if isinstance(grid, Mapping) else ():
        _known(k, specs, generator, f"grid.{k}")
    for i, c in enumerate(cases if isinstance(cases, Sequence) else ()):
        for k in c if isinstance(c, Mapping) else ():
            _known(k, specs, generator, f"cases[{i}].{k}")
    for kind in ("uniform", "integers", "choice"):
        block = random.get(kind) if isinstance(random, Mapping) else None
        for k in block if isinstance(block, Mapping) else ():
            _known(k, specs, generator, f"random.{kind}.{k}")
    all_cases = expand_cases(grid, cases, random, parameters)
    checked = []
    for i, c in enumerate(all_cases):
        out = {}
        for k, v in c.items():
            _known(k, specs, generator, f"case {i}")
            out[k] = check_value(k, v, specs[k], f"{k} (case {i})")
        checked.append(out)
    if not analyses:
        raise InputError("expected at least one analysis", "analyses")
    if isinstance(analyses, str | Mapping):
        analyses = [analyses]
    ans = tuple(_analysis(a, f"analyses[{i}]") for i, a in enumerate(analyses))
    names = [a.name for a in ans]
    for a in ans:
        if names.count(a.name) > 1:
            raise InputError(f"analysis {a.name!r} given twice", "analyses")
        if a.name == "min_thickness":
            if generator is None:
                raise InputError("min_thickness needs a generator, not a scene", "analyses")
            p = dict(a.options).get("param", "thickness")
            if p not in specs:
                raise InputError(f"min_thickness: {generator} has no parameter {p!r}",
                                 "analyses")
            if any(p in c for c in checked):
                raise InputError(f"min_thickness bisects {p!r}: it cannot also be a case "
                                 "parameter", "analyses")
    answer_cols = {c for a in ans for c in (f"{a.name}_status", *ANSWERS[a.name])}
    for k in {k for c in checked for k in c}:
        if k in answer_cols or k in BASE_COLUMNS:
            raise InputError(f"parameter {k!r} has the name of a result column")
    return Sweep(generator, scene, tuple(checked), ans, method, name, src_label)


def _known(k: str, specs: Mapping[str, Any], generator: str | None, where: str) -> None:
    if k not in specs:
        what = f"generator {generator!r}" if generator else "a scene source"
        raise InputError(f"unknown parameter {k!r} for {what} (parameters: "
                         f"{', '.join(sorted(specs))})", where)


# -- one case ----------------------------------------------------------------------------
@dataclass(frozen=True)
class _Job:
    generator: str | None
    scene: Scene | None
    analyses: tuple[Analysis, ...]
    method: str


def _scene_of(job: _Job, params: Mapping[str, Any]) -> Scene:
    if job.generator is not None:
        from ..generators import build

        return build(job.generator, **params)
    assert job.scene is not None
    changes = {k: v for k, v in params.items() if k in SCENE_PARAMS}
    if not changes:
        return job.scene
    scene = job.scene.with_changes(**changes)
    if "depth" in changes or "unit_weight" in changes:
        from ..scene.validate import validate_scene

        validate_scene(scene)
    return scene


def run_case(job: _Job, params: Mapping[str, Any]) -> dict[str, Any]:
    """The answers of one case (never raises: an error is recorded in the row)."""
    from ..problems import check, max_load_multiplier, min_friction

    row: dict[str, Any] = {"status": "ok", "error": None, "solve_time": 0.0}
    for a in job.analyses:
        row[f"{a.name}_status"] = None
        row.update(dict.fromkeys(ANSWERS[a.name]))
    t0 = time.perf_counter()
    lf = float(params.get("load_factor", 1.0))
    gen_params = {k: v for k, v in params.items() if k not in RESERVED}
    try:
        scene = None
        for a in job.analyses:
            opts = dict(a.options)
            if a.name == "min_thickness":
                from .thickness import min_thickness

                th = min_thickness(job.generator, method=job.method,  # type: ignore[arg-type]
                                   **opts, **gen_params)
                row.update(min_thickness_status="ok", min_thickness=th.thickness,
                           min_thickness_lower=th.lower)
                continue
            if scene is None:
                scene = _scene_of(job, gen_params)
            if a.name == "check":
                r = check(scene, load_factor=lf, method=job.method, state=False)
                row.update(check_status=r.status, admissible=bool(r.admissible),
                           violation=float(r.violation))
            elif a.name == "min_friction":
                r = min_friction(scene, load_factor=lf, method=job.method, state=False)
                row.update(min_friction_status=r.status, friction_factor=r.friction_factor,
                           friction_angle_deg=r.friction_angle_deg)
            else:
                r = max_load_multiplier(scene, method=job.method, state=False)
                row.update(max_load_multiplier_status=r.status,
                           load_multiplier=r.load_multiplier)
            row["solve_time"] += float(r.solve_time)
    except Exception as err:  # noqa: BLE001 - every failure is recorded, the study goes on
        row["status"] = "failed"
        row["error"] = f"{type(err).__name__}: {err}"
    row["time"] = time.perf_counter() - t0
    return row


def run_batch(job: _Job, batch: Sequence[tuple[int, str, dict[str, Any]]]) -> list[dict]:
    """Rows of a batch of cases ``(index, case_id, params)`` (a task of an executor)."""
    return [{"case": i, "case_id": cid, **params, **run_case(job, params)}
            for i, cid, params in batch]


# -- executors ---------------------------------------------------------------------------
Batch = list[tuple[int, str, dict[str, Any]]]


def _in_process(job: _Job, batches: Iterator[Batch]) -> Iterator[list[dict]]:
    for b in batches:
        yield run_batch(job, b)


def _processes(job: _Job, batches: Iterator[Batch], workers: int) -> Iterator[list[dict]]:
    ex = ProcessPoolExecutor(max_workers=workers)
    pending: set = set()
    try:
        for b in itertools.islice(batches, 3 * workers):
            pending.add(ex.submit(run_batch, job, b))
        while pending:
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for fut in done:
                for b in itertools.islice(batches, 1):
                    pending.add(ex.submit(run_batch, job, b))
                yield fut.result()
    finally:
        ex.shutdown(wait=not pending, cancel_futures=True)


def _dask(job: _Job, batches: Iterator[Batch], scheduler: str | None,
          client: Any) -> Iterator[list[dict]]:
    from dask.distributed import Client, as_completed

    own = client is None
    if own:
        client = Client(scheduler)
    futures: list = []
    try:
        n = max(1, sum(client.nthreads().values()))
        futures = [client.submit(run_batch, job, b, pure=False)
                   for b in itertools.islice(batches, 3 * n)]
        ac = as_completed(futures)
        for fut in ac:
            for b in itertools.islice(batches, 1):
                new = client.submit(run_batch, job, b, pure=False)
                futures.append(new)
                ac.add(new)
            yield fut.result()
    finally:
        for f in futures:
            if not f.done():
                f.cancel()
        if own:
            client.close()


# -- storage -------------------------------------------------------------------------------
class _Store:
    """Rows on disk: chunk files in ``OUTPUT.parts/``, merged into OUTPUT at the end."""

    def __init__(self, path: str | os.PathLike | None):
        self.path = Path(path) if path is not None else None
        if self.path is not None:
            ext = self.path.suffix.lower()
            if ext not in (".parquet", ".csv"):
                raise InputError(f"output must end in .parquet or .csv, got {ext or 'none'!r}",
                                 str(self.path))
            self.ext = ext
            self.parts = self.path.with_name(self.path.name + ".parts")
        self.memory: list[dict] = []

    def _read(self, p: Path):
        import pandas as pd

        if self.ext == ".parquet":
            return pd.read_parquet(p)
        return pd.read_csv(p, dtype={"case_id": str, "error": str, "status": str})

    def existing(self):
        """Rows already on disk (output file and chunks), one per case id."""
        import pandas as pd

        if self.path is None:
            return pd.DataFrame()
        frames = []
        if self.path.exists():
            frames.append(self._read(self.path))
        if self.parts.is_dir():
            frames += [self._read(p) for p in sorted(self.parts.glob(f"*{self.ext}"))]
        frames = [f for f in frames if len(f)]
        if not frames:
            return pd.DataFrame()
        df = pd.concat(frames, ignore_index=True)
        if "case_id" not in df:
            raise InputError("the existing output has no case_id column: not a study's "
                             "results", str(self.path))
        return df.drop_duplicates("case_id", keep="first")

    def write(self, rows: list[dict], columns: list[str]) -> None:
        if not rows:
            return
        if self.path is None:
            self.memory += rows
            return
        self.parts.mkdir(parents=True, exist_ok=True)
        name = f"part-{time.time_ns():020d}-{uuid.uuid4().hex[:8]}{self.ext}"
        tmp = self.parts / (name + ".tmp")
        _to_file(_frame(rows, columns), tmp, self.ext)
        os.replace(tmp, self.parts / name)

    def merge(self, columns: list[str], ids: Sequence[str]):
        """The sweep's rows in case order; written to OUTPUT (chunks removed)."""
        import pandas as pd

        if self.path is None:
            df = _frame(self.memory, columns)
        else:
            df = self.existing()
            if len(df):
                df = df[df["case_id"].isin(set(ids))]
            df = df.reindex(columns=columns) if len(df) else _frame([], columns)
        order = {cid: i for i, cid in enumerate(ids)}
        df = df.assign(case=[order[c] for c in df["case_id"]]) if len(df) else df
        df = df.sort_values("case", kind="stable").reset_index(drop=True)
        df = _tidy(df)
        if self.path is not None:
            tmp = self.path.with_name(self.path.name + ".tmp")
            _to_file(df, tmp, self.ext)
            os.replace(tmp, self.path)
            shutil.rmtree(self.parts, ignore_errors=True)
        return pd.DataFrame(df)


def _frame(rows: list[dict], columns: list[str]):
    import pandas as pd

    return _tidy(pd.DataFrame(rows, columns=columns))


def _tidy(df):
    """Columns of one type: numbers mixed with strings ("infinite") become strings."""
    for c in df.columns:
        if df[c].dtype == object:
            kinds = {type(v) for v in df[c] if v is not None and v == v}
            if str in kinds and len(kinds) > 1:
                df[c] = [None if (v is None or v != v) else str(v) for v in df[c]]
    return df


def _to_file(df, path: Path, ext: str) -> None:
    if ext == ".parquet":
        df.to_parquet(path, index=False)
    else:
        df.to_csv(path, index=False)


# -- running -----------------------------------------------------------------------------
@dataclass
class StudyResult:
    """The outcome of :func:`run`: one row per case in ``frame``.

    Columns: ``case`` (index in the sweep), ``case_id``, the parameters, ``status``
    ("ok" or "failed"), ``error`` (the exception's type and message of a failed case),
    ``time`` (wall-clock seconds of the case), ``solve_time`` (solver seconds), then per
    analysis ``<analysis>_status`` and its answers: ``admissible``, ``violation``
    (check); ``friction_factor``, ``friction_angle_deg`` (min_friction);
    ``load_multiplier`` (max_load_multiplier); ``min_thickness``,
    ``min_thickness_lower`` (min_thickness).
    """

    frame: Any
    sweep: Sweep
    path: Path | None = None
    n_run: int = 0
    n_skipped: int = 0
    elapsed: float = 0.0
    executor: str = ""
    extra: dict[str, Any] = field(default_factory=dict)

    @property
    def n_cases(self) -> int:
        return len(self.frame)

    @property
    def n_failed(self) -> int:
        return int((self.frame["status"] == "failed").sum()) if len(self.frame) else 0

    @property
    def rate(self) -> float:
        """Cases run per second of wall-clock time (the skipped ones not counted)."""
        return self.n_run / self.elapsed if self.elapsed > 0 else math.nan

    def plot(self, x: str, y: str, hue: str | None = None, ax: Any = None,
             **kwargs: Any) -> Any:
        """Chart of ``y`` against ``x`` (one line per value of ``hue``); see :func:`plot`."""
        return plot(self.frame, x, y, hue=hue, ax=ax, **kwargs)

    def summary(self) -> str:
        where = f", output {self.path}" if self.path else ""
        return (f"cases {self.n_cases} ({self.n_run} run, {self.n_skipped} done before), "
                f"failures {self.n_failed}, time {self.elapsed:.2f} s "
                f"({self.rate:.1f} cases/s, {self.executor}){where}")


def plot(frame: Any, x: str, y: str, hue: str | None = None, ax: Any = None,
         **kwargs: Any) -> Any:
    """Line chart of column ``y`` against ``x`` of a study's frame, one line per value
    of ``hue``; failed cases and missing answers are left out. Returns the Axes.

    Example: ``plot(df, x="centre_depth", y="friction_angle_deg", hue="voussoirs")``.
    """
    import matplotlib.pyplot as plt

    for c in (x, y, hue):
        if c is not None and c not in frame.columns:
            raise InputError(f"no column {c!r} (columns: {', '.join(map(str, frame.columns))})")
    if ax is None:
        _, ax = plt.subplots()
    df = frame
    if "status" in df.columns:
        df = df[df["status"] == "ok"]
    df = df[df[y].notna()]
    groups = [(None, df)] if hue is None else list(df.groupby(hue, sort=True))
    style = {"marker": "o", "markersize": 3, **kwargs}
    for key, g in groups:
        g = g.sort_values(x)
        ax.plot(g[x], g[y].astype(float), label=None if hue is None else f"{hue} = {key}",
                **style)
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    if hue is not None and groups:
        ax.legend()
    ax.grid(True, alpha=0.3)
    return ax


def run(source: str | Scene | Sweep, *, output: str | os.PathLike | None = None,
        workers: int | None = None, scheduler: str | None = None, client: Any = None,
        batch_size: int | None = None, progress: bool = True,
        on_case: Callable[[dict[str, Any]], Any] | None = None,
        flush_every: float = 10.0, **sweep: Any) -> StudyResult:
    """Run a parametric study; rows are written to ``output`` (.parquet or .csv).

    Args:
        source: a :class:`Sweep` (e.g. from a spec file), or what :func:`make_sweep`
            takes (a generator name, a scene or a scene file) with its keywords
            ``grid``/``cases``/``random``, ``parameters``, ``analyses``, ``method``.
        output: the results file. Cases whose ``case_id`` it (or its ``.parts``
            folder of chunks) already holds are skipped.
        workers: local processes (default: every core); 1 runs in this process.
        scheduler, client: run on a Dask cluster (address, or a
            ``dask.distributed.Client``) instead of local processes.
        batch_size: cases per task (default: about 8 tasks per worker, at most 64 cases).
        progress: a tqdm progress bar (cases done, failures, rate).
        on_case: called with each finished case's row, in this process.
        flush_every: seconds between writes of finished rows to the chunk folder (rows
            are also written every 10 batches and whenever the study stops).

    Returns:
        :class:`StudyResult`; ``frame`` holds every case of the sweep that has run, now
        or before, in case order.
    """
    sw = source if isinstance(source, Sweep) else make_sweep(source, **sweep)
    if isinstance(source, Sweep) and sweep:
        raise InputError(f"unexpected arguments with a Sweep: {', '.join(sorted(sweep))}")
    if workers is not None and (not isinstance(workers, int) or workers < 1):
        raise InputError(f"workers must be an integer >= 1, got {workers!r}")
    store = _Store(output)
    columns = sw.columns
    ids = sw.case_ids()
    old = store.existing()
    if len(old):
        foreign = set(old["case_id"]) - set(ids)
        if foreign:
            raise InputError(f"holds {len(foreign)} case(s) of another sweep; choose another "
                             "output file", str(store.path))
    done = set(old["case_id"]) if len(old) else set()
    todo = [(i, cid, c) for i, (cid, c) in enumerate(zip(ids, sw.cases, strict=True))
            if cid not in done]
    job = _Job(sw.generator, sw.scene, sw.analyses, sw.method)

    if client is not None or scheduler is not None:
        executor = "dask"
        n_workers = None
    else:
        n_workers = workers or os.cpu_count() or 1
        executor = "1 process" if n_workers == 1 else f"{n_workers} processes"
    if batch_size is None:
        slots = 8 * (n_workers or 4)
        batch_size = max(1, min(64, math.ceil(len(todo) / slots)))
    elif not isinstance(batch_size, int) or batch_size < 1:
        raise InputError(f"batch_size must be an integer >= 1, got {batch_size!r}")
    batches = iter([todo[k:k + batch_size] for k in range(0, len(todo), batch_size)])
    if executor == "dask":
        stream = _dask(job, batches, scheduler, client)
        if client is None:
            executor = f"dask {scheduler}"
    elif n_workers == 1:
        stream = _in_process(job, batches)
    else:
        stream = _processes(job, batches, n_workers)  # type: ignore[arg-type]

    from tqdm.auto import tqdm

    bar = tqdm(total=len(ids), initial=len(ids) - len(todo), unit="case",
               desc=sw.name or sw.generator or "sweep", disable=not progress)
    failed = int((old["status"] == "failed").sum()) if len(old) else 0
    buffer: list[dict] = []
    last = time.monotonic()
    n_batches = 0
    t0 = time.perf_counter()
    try:
        for rows in stream:
            for row in rows:
                buffer.append(row)
                failed += row["status"] == "failed"
                bar.update(1)
                if on_case is not None:
                    on_case(row)
            bar.set_postfix(failed=failed, refresh=False)
            n_batches += 1
            if n_batches % 10 == 0 or time.monotonic() - last > flush_every:
                store.write(buffer, columns)
                buffer, last = [], time.monotonic()
    finally:
        stream.close()
        store.write(buffer, columns)
        bar.close()
    elapsed = time.perf_counter() - t0
    frame = store.merge(columns, ids)
    return StudyResult(frame, sw, store.path, len(todo), len(ids) - len(todo), elapsed,
                       executor)


__all__ = ["ANALYSES", "ANSWERS", "Analysis", "StudyResult", "Sweep", "check_value",
           "expand_cases", "make_sweep", "plot", "run", "run_batch", "run_case"]
