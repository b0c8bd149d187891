"""Execution of a sweep: one case (its analyses), a batch of cases, and the executors
that run batches in this process, on local processes or on a Dask cluster."""

from __future__ import annotations

import itertools
import math
import os
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

from ..answer import VERDICTS, undecided_why
from ..errors import InputError, Terminated
from ..scene.model import INFINITE, Scene, friction_value
from .cases import RESERVED, SCENE_PARAMS

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
    "min_friction": ("friction_factor", "friction_angle_deg", "friction_factor_lower",
                     "friction_factor_upper"),
    "max_load_multiplier": ("load_multiplier", "load_multiplier_accuracy",
                            "load_multiplier_lower", "load_multiplier_upper"),
    "min_thickness": ("min_thickness", "min_thickness_lower", "min_thickness_friction",
                      "min_thickness_param"),
}
#: the result's attribute behind an answer column, where it is not the column's name:
#: the bracket of f* (its ends, also where the search could not decide), the relative
#: accuracy lambda* reached (its bracket's width), and the narrowest bracket known to
#: hold lambda*: its search's where it left one (an undecided answer's: the columns were
#: empty, the number too, and nothing said where lambda* lay), else the bounds on every
#: non-associative collapse multiplier (an end of ``load_multiplier_bounds``)
ATTRIBUTE: dict[str, str | tuple[tuple[str, ...], int]] = {
    "friction_factor_lower": "lower", "friction_factor_upper": "upper",
    "load_multiplier_accuracy": "accuracy",
    "load_multiplier_lower": (("bracket", "load_multiplier_bounds"), 0),
    "load_multiplier_upper": (("bracket", "load_multiplier_bounds"), 1)}


def _column(result: Any, column: str) -> Any:
    """The value of an answer column from an analysis result (:data:`ATTRIBUTE`; a pair
    from the first of its attributes the result has)."""
    at = ATTRIBUTE.get(column, column)
    if isinstance(at, tuple):
        pair = next((p for p in (getattr(result, a, None) for a in at[0]) if p is not None),
                    None)
        return None if pair is None else pair[at[1]]
    return getattr(result, at)


@dataclass(frozen=True)
class Analysis:
    """One analysis to run on every case, with its options (``min_thickness``: param,
    lo, hi, rtol, friction; see :func:`rigidblocks.min_thickness`)."""

    name: str
    options: tuple[tuple[str, Any], ...] = ()

    def to_json(self) -> Any:
        return {"analysis": self.name, **dict(self.options)} if self.options else self.name


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


def answer(analysis: Analysis, job: _Job, params: Mapping[str, Any],
           load_factor: float | None, scene: Callable[[], Scene], flow: str | None = None,
           ) -> tuple[dict[str, Any], float]:
    """The row entries of one analysis of a case and its solve time: the one place where
    a sweep maps an analysis name to the function that answers it.

    ``params`` are the generator's (or scene's) parameters, ``scene`` builds the case's
    scene (once, on first call); ``load_factor`` and ``flow`` None are the scene's. An
    undecided check leaves ``admissible`` empty (None), as its status says.
    """
    name, method = analysis.name, job.method
    if name == "min_thickness":
        from .thickness import min_thickness

        opts = dict(analysis.options)
        if "friction" not in opts and "friction" not in params:
            opts["friction"] = None  # the scene's, as check and max_load_multiplier
        th = min_thickness(job.generator, method=method,  # type: ignore[arg-type]
                           load_factor=load_factor or 0.0, **opts, **params)
        return {"min_thickness_status": th.status, "min_thickness": th.thickness,
                "min_thickness_lower": th.lower,
                "min_thickness_friction": float(friction_value(th.friction)),
                # which parameter the two columns before are (a pier width read as t/R)
                "min_thickness_param": th.param}, \
            th.solve_time
    if name not in ANALYSES:
        raise InputError(f"unknown analysis {name!r} (choose from {', '.join(ANALYSES)})")
    from ..analyses import analysis as registered

    extra = {"flow": flow} if flow is not None else {}
    extra["compare_dry"] = False  # (no column holds it: time for nothing)
    r = registered(name).run(scene(), load_factor=load_factor, method=method, state=False,
                             **extra)
    row = {f"{name}_status": r.status}
    row.update({k: _column(r, k) for k in ANSWERS[name]})
    if r.status not in VERDICTS:  # why it could not decide (the summary named no case)
        row["note"] = f"{name}: {undecided_why(scene(), r)}"
    return row, float(r.solve_time)


class _NoScene(Exception):
    """The case's scene could not be built (``cause``: why)."""

    def __init__(self, cause: Exception):
        super().__init__(str(cause))
        self.cause = cause


def run_case(job: _Job, params: Mapping[str, Any]) -> dict[str, Any]:
    """The answers of one case (never raises: an error is recorded in the row)."""
    row: dict[str, Any] = {"status": "ok", "error": None, "note": None, "solve_time": 0.0}
    for a in job.analyses:
        row[f"{a.name}_status"] = None
        row.update(dict.fromkeys(ANSWERS[a.name]))
    t0 = time.perf_counter()
    lf = params.get("load_factor")
    lf = None if lf is None else float(lf)
    gen_params = {k: v for k, v in params.items() if k not in RESERVED}
    built: list[Scene] = []

    def scene() -> Scene:
        if not built:
            try:
                built.append(_scene_of(job, gen_params))
            except Exception as err:
                raise _NoScene(err) from err
        return built[0]

    errors, notes = [], []
    for a in job.analyses:
        # each analysis on its own: one that raises leaves the others' answers; a scene
        # that cannot be built fails the case, and every analysis of it (their statuses
        # were left empty: the outcomes did not count the case)
        try:
            entries, solve_time = answer(a, job, gen_params, lf, scene, params.get("flow"))
        except _NoScene as err:
            errors = [f"{type(err.cause).__name__}: {err.cause}"]
            row.update({f"{b.name}_status": "failed" for b in job.analyses})
            break
        except Exception as err:  # noqa: BLE001 - every failure is recorded, the study goes on
            row[f"{a.name}_status"] = "failed"
            errors.append(f"{a.name}: {type(err).__name__}: {err}")
            continue
        notes += [entries.pop("note")] if "note" in entries else []
        row.update(entries)
        row["solve_time"] += solve_time
    row["note"] = "; ".join(notes) or None
    if errors:
        row["status"] = "failed"
        row["error"] = "; ".join(errors)
    row["time"] = time.perf_counter() - t0
    return row


def run_batch(job: _Job, batch: Sequence[tuple[int, str, dict[str, Any]]]) -> list[dict]:
    """Rows of a batch of cases ``(index, case_id, params)`` (a task of an executor)."""
    return [{"case": i, "case_id": cid, **_numeric(params), **run_case(job, params)}
            for i, cid, params in batch]


def _numeric(params: Mapping[str, Any]) -> dict[str, Any]:
    """A case's parameters as its row gives them: an infinite friction as the number inf
    (the spelling "infinite" made the column text, where d[d.friction == 0.5] found
    nothing)."""
    return {k: math.inf if k == "friction" and v == INFINITE else v
            for k, v in params.items()}


# -- executors ---------------------------------------------------------------------------
Batch = list[tuple[int, str, dict[str, Any]]]


def _in_process(job: _Job, batches: Iterator[Batch]) -> Iterator[list[dict]]:
    for b in batches:
        yield run_batch(job, b)


def _worker_start(parent: int) -> None:
    """A worker's start: Ctrl-C is the main process's to handle (it ends the workers);
    caught in a worker, inside a solver's callback, it printed a traceback there. On
    Linux the worker is killed when the process ``parent`` that started it ends: killed
    by SIGKILL, it cannot end them, and they ran on, orphaned, for minutes, holding its
    output pipe."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # the main process's SIGTERM handler, copied by the fork, is not the worker's: its
    # end by the main process (terminate) raised inside a solver's callback, a traceback
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    try:
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):  # pragma: no cover - not Linux
        return
    if os.getppid() != parent:  # it ended before the line above
        os._exit(1)


@contextmanager
def terminate_as_interrupt() -> Iterator[None]:
    """SIGTERM (a batch system's time limit, ``kill``) raised as
    :class:`~rigidblocks.errors.Terminated`, a KeyboardInterrupt, in the main thread
    while a study runs: its workers are ended and its finished cases written, as at
    Ctrl-C (the workers were left running, orphaned, and no case was saved)."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum: int, frame: Any) -> None:
        raise Terminated()

    old = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, old)


def _processes(job: _Job, batches: Iterator[Batch], workers: int) -> Iterator[list[dict]]:
    ex = ProcessPoolExecutor(max_workers=workers, initializer=_worker_start,
                             initargs=(os.getpid(),))
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
    except KeyboardInterrupt:
        # end the workers now: left to finish their cases, Ctrl-C took 9 to 14 s; then
        # wait for the pool's own thread to see them gone (not waited for, the
        # interpreter's exit wrote to its closed wake-up pipe now and then: a traceback
        # after "rigidblocks: interrupted")
        for proc in list((getattr(ex, "_processes", None) or {}).values()):
            proc.terminate()
        pending = set()
        raise
    finally:
        ex.shutdown(wait=not pending, cancel_futures=True)


#: seconds to wait for a Dask scheduler to answer
CONNECT_TIMEOUT = 5.0


def connect(scheduler: str, timeout: float = CONNECT_TIMEOUT) -> Any:
    """A ``dask.distributed.Client`` of the scheduler at ``scheduler``; InputError naming
    the address when nothing answers there within ``timeout`` seconds."""
    from ..extras import require

    require("study", "a study on a Dask cluster", ("distributed",))
    from dask.distributed import Client

    try:
        return Client(scheduler, timeout=timeout)
    except OSError:
        raise InputError(f"cannot reach the Dask scheduler at {scheduler}: no answer "
                         f"within {timeout:g} s", "--scheduler") from None
    except (ValueError, TypeError) as err:
        msg = str(err).splitlines()[0] if str(err) else type(err).__name__
        raise InputError(f"not a Dask scheduler address: {scheduler!r} ({msg})",
                         "--scheduler") from None


def _dask(job: _Job, batches: Iterator[Batch], client: Any,
          own: bool = False) -> Iterator[list[dict]]:
    """Batches run on a Dask ``client`` (closed at the end when ``own``)."""
    from dask.distributed import as_completed

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


__all__ = ["ANALYSES", "ANSWERS", "Analysis", "answer", "connect", "run_batch", "run_case"]
