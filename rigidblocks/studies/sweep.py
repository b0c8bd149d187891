"""Parametric studies: many independent analyses of a family of structures.

A sweep is a source of scenes -- a generator of :mod:`rigidblocks.generators` called
with each case's parameters, or one scene whose ``friction``, ``depth`` or
``unit_weight`` a case overrides -- plus the cases (a grid, a list, or random samples
with a seed) and the analyses to run on each: ``check``, ``min_friction``,
``max_load_multiplier``, ``min_thickness``. The reserved parameter ``load_factor``
(default 1, as in :func:`rigidblocks.check`) multiplies the live loads in ``check``,
``min_friction`` and ``min_thickness`` (there default 0); the arch generators carry a
live horizontal body force, so ``load_factor = 0`` means self-weight only.

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

This module defines the sweep and runs it; its parts live beside it:
:mod:`~rigidblocks.studies.cases` (case expansion and value checks),
:mod:`~rigidblocks.studies.execute` (one case, batches, executors),
:mod:`~rigidblocks.studies.storage` (chunks, merge, resume) and
:mod:`~rigidblocks.studies.chart` (charts). Their public names are importable from here.

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
import json
import math
import os
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..methods import METHODS
from ..scene.model import Scene
from ..scene.validate import is_number
from .cases import (
    RANDOM_KEYS,
    RESERVED,
    SCENE_PARAMS,
    _known,
    _plain,
    check_value,
    expand_cases,
    not_bisectable,
    param_specs,
)
from .chart import plot
from .execute import (
    ANALYSES,
    ANSWERS,
    Analysis,
    _dask,
    _in_process,
    _Job,
    _processes,
    connect,
    run_batch,
    run_case,
    terminate_as_interrupt,
)
from .storage import _Store
from .thickness import check_rtol

#: columns of every row besides the parameters and the answers
BASE_COLUMNS = ("case", "case_id", "status", "error", "note", "time", "solve_time")


# -- the sweep -------------------------------------------------------------------------
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
        cols = [*BASE_COLUMNS[:2], *self.parameter_names, *BASE_COLUMNS[2:]]
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
        # (a hi of 1e400, infinite, failed every case: "cannot be built at thickness=inf")
        if k in opts and not (is_number(_plain(opts[k])) and _plain(opts[k]) > 0
                              and math.isfinite(_plain(opts[k]))):
            raise InputError(f"{k} must be a finite number > 0, got {opts[k]!r}", where)
    if "lo" in opts and "hi" in opts and not _plain(opts["lo"]) < _plain(opts["hi"]):
        # (each case failed on its own, the sweep ending with status 0)
        raise InputError(f"lo must be below hi, got lo {opts['lo']!r} and hi "
                         f"{opts['hi']!r}", where)
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
    specs = param_specs(generator)
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
    for i, a in enumerate(ans):  # (every case failed on its own, the sweep exiting 1)
        rtol = dict(a.options).get("rtol")
        if a.name == "min_thickness" and rtol is not None:
            try:
                check_rtol(rtol, method)
            except InputError as err:
                raise InputError(err.detail, f"analyses[{i}]") from None
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
            why = not_bisectable(p, specs[p])
            if why:  # (flat_arch's voussoirs was bisected, case by case)
                raise InputError(f"min_thickness: {p} is {why}", "analyses")
            if any(p in c for c in checked):
                raise InputError(f"min_thickness bisects {p!r}: it cannot also be a case "
                                 "parameter", "analyses")
            both = sorted({k for k in dict(a.options) for c in checked if k in c})
            if both:  # (every case failed with a TypeError)
                raise InputError(f"min_thickness: {', '.join(map(repr, both))} is given "
                                 "both as its option and as a case parameter: give it once",
                                 "analyses")
    answer_cols = {c for a in ans for c in (f"{a.name}_status", *ANSWERS[a.name])}
    for k in {k for c in checked for k in c}:
        if k in answer_cols or k in BASE_COLUMNS:
            raise InputError(f"parameter {k!r} has the name of a result column")
    return Sweep(generator, scene, tuple(checked), ans, method, name, src_label)


# -- running -----------------------------------------------------------------------------
@dataclass
class StudyResult:
    """The outcome of :func:`run`: one row per case in ``frame``.

    Columns: ``case`` (index in the sweep), ``case_id``, the parameters, ``status``
    ("ok" or "failed"), ``error`` (the exception's type and message of a failed case),
    ``time`` (wall-clock seconds of the case), ``solve_time`` (solver seconds), then per
    analysis ``<analysis>_status`` and its answers: ``admissible``, ``violation``
    (check); ``friction_factor``, ``friction_angle_deg``, ``friction_factor_lower``,
    ``friction_factor_upper`` (min_friction: f*'s bracket); ``load_multiplier``,
    ``load_multiplier_accuracy``, ``load_multiplier_lower``, ``load_multiplier_upper``
    (max_load_multiplier; the last two the narrowest bracket known to hold lambda*: its
    search's, else the bounds on every non-associative collapse multiplier);
    ``min_thickness``,
    ``min_thickness_lower``, ``min_thickness_friction`` (min_thickness: the friction it
    bisected at, the scene's unless its options give one).
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
    def outcomes(self) -> dict[str, dict[str, int]]:
        """For each analysis, how many cases ended in each of its statuses (collapse,
        undecided, failed, ...), in the order met."""
        out: dict[str, dict[str, int]] = {}
        for col in self.frame.columns if len(self.frame) else ():
            if col.endswith("_status"):
                counts = self.frame[col].dropna().value_counts(sort=False)
                out[col[:-len("_status")]] = {str(k): int(v) for k, v in counts.items()}
        return out

    @property
    def n_undecided(self) -> int:
        """Cases with an analysis that could not decide (no number: its bracket in its
        columns, where it has one)."""
        cols = [c for c in self.frame.columns if c.endswith("_status")] \
            if len(self.frame) else []
        return int((self.frame[cols] == "undecided").any(axis=1).sum()) if cols else 0

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
                f"failures {self.n_failed}, undecided {self.n_undecided}, time "
                f"{self.elapsed:.2f} s ({rate_text(self.rate)}, {self.executor}){where}")


def rate_text(rate: float) -> str:
    """Cases per second to three figures, or seconds per case below one a second (2
    cases in 48 s read "0.0 cases/s")."""
    if not rate > 0:
        return "no cases run"
    return f"{rate:.3g} cases/s" if rate >= 1 else f"{1 / rate:.3g} s per case"


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
    from ..extras import require

    require("study", "a parametric study")
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
        own = client is None
        if own:
            client = connect(scheduler)  # type: ignore[arg-type]
            executor = f"dask {scheduler}"
        stream = _dask(job, batches, client, own)
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
    with terminate_as_interrupt():  # (a kill ends the workers and keeps the cases)
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


__all__ = ["ANALYSES", "ANSWERS", "RANDOM_KEYS", "RESERVED", "SCENE_PARAMS", "Analysis",
           "StudyResult", "Sweep", "check_value", "expand_cases", "make_sweep", "plot", "run",
           "run_batch", "run_case"]
