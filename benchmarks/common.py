"""What every benchmark script shares: where results go, the machine, and timers.

Each script ``benchmarks/NAME.py`` is runnable as ``python benchmarks/NAME.py`` and
has ``main(argv) -> dict``; ``--out DIR`` (default ``benchmarks/results``) receives
``NAME.json`` (the raw figures), PNG charts and ``NAME.md`` (a markdown section that
``benchmarks/make_readme.py`` collects into ``benchmarks/README.md``); ``--tiny``
runs the smallest sizes only (what the default test run does).
"""

from __future__ import annotations

import json
import os
import platform
import sys
import time
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

RESULTS = Path(__file__).resolve().parent / "results"


def machine() -> dict[str, Any]:
    """The machine and the versions the figures were measured with."""
    import clarabel
    import numpy
    import scipy

    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        mem = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**30
    except (ValueError, OSError, AttributeError):
        mem = float("nan")
    return {"cpu": cpu, "cores": os.cpu_count(), "memory_gib": round(mem, 1),
            "python": platform.python_version(), "platform": platform.platform(),
            "numpy": numpy.__version__, "scipy": scipy.__version__,
            "clarabel": clarabel.__version__}


def child_cpu() -> float:
    """CPU seconds (user + system) of this process's finished children so far."""
    import resource

    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def cli_process(args: list[str], env: dict[str, str] | None = None) -> tuple[Any, float,
                                                                              float]:
    """One whole ``rigidblocks ARGS`` process, as a user runs it, of this run's package
    (first on its path), with ``env`` added to the environment: the finished process
    (its output captured), its CPU seconds (user + system) and its wall seconds."""
    import subprocess

    import rigidblocks

    env = {**os.environ, **(env or {})}
    here = str(Path(rigidblocks.__file__).resolve().parents[1])  # this run's package
    env["PYTHONPATH"] = os.pathsep.join(p for p in (here, env.get("PYTHONPATH")) if p)
    cmd = [sys.executable, "-m", "rigidblocks.cli.main", *args]
    c0, t0 = child_cpu(), time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env)
    return proc, child_cpu() - c0, time.perf_counter() - t0


def out_dir(path: str | Path | None) -> Path:
    """The results folder (created); ``None`` means ``benchmarks/results``."""
    d = Path(path) if path is not None else RESULTS
    d.mkdir(parents=True, exist_ok=True)
    return d


def write_results(out: str | Path | None, name: str, data: dict[str, Any],
                  markdown: str) -> Path:
    """Write ``NAME.json`` (with the machine) and the ``NAME.md`` section; return the folder."""
    d = out_dir(out)
    doc = {"benchmark": name, "date": time.strftime("%Y-%m-%d"), "machine": machine(),
           "argv": sys.argv[1:], **data}
    (d / f"{name}.json").write_text(json.dumps(doc, indent=1, default=_jsonable) + "\n")
    (d / f"{name}.md").write_text(markdown.rstrip() + "\n")
    return d


def read_results(out: str | Path | None, name: str) -> dict[str, Any]:
    """The ``NAME.json`` of an earlier run (to redraw or extend it)."""
    return json.loads((out_dir(out) / f"{name}.json").read_text())


def rewrite_results(out: str | Path | None, name: str, data: dict[str, Any],
                    markdown: str) -> Path:
    """Write ``NAME.json`` and ``NAME.md`` of results measured earlier (``data`` keeps
    its own machine, date and argv); return the folder."""
    d = out_dir(out)
    (d / f"{name}.json").write_text(json.dumps(data, indent=1, default=_jsonable) + "\n")
    (d / f"{name}.md").write_text(markdown.rstrip() + "\n")
    return d


def load_average() -> float:
    """The 1-minute load average (NaN where the platform has none): how busy the shared
    machine was while the figures were taken."""
    return os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")


def _jsonable(x: Any) -> Any:
    try:
        return x.item()  # numpy scalars
    except AttributeError:
        return str(x)


@contextmanager
def timed(store: dict[str, float], key: str) -> Iterator[None]:
    """Add the wall-clock seconds of the block to ``store[key]``."""
    t0 = time.perf_counter()
    try:
        yield
    finally:
        store[key] = store.get(key, 0.0) + time.perf_counter() - t0


def markdown_table(header: list[str], rows: list[list[Any]]) -> str:
    """A GitHub markdown table; floats with 4 significant digits."""
    def cell(v: Any) -> str:
        if isinstance(v, float):
            return f"{v:.4g}"
        return str(v)
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(cell(v) for v in r) + " |" for r in rows]
    return "\n".join(lines)


def text_table(header: list[str], rows: list[list[Any]], width: int = 9,
               digits: int = 3) -> str:
    """A fixed-width text table for the terminal: right-aligned columns, floats with
    ``digits`` decimals, a rule under the header."""
    def cell(v: Any) -> str:
        return f"{v:>{width}.{digits}f}" if isinstance(v, float) else f"{v!s:>{width}}"
    head = " ".join(f"{h:>{width}}" for h in header)
    return "\n".join([head, "-" * len(head), *(" ".join(cell(v) for v in r) for r in rows)])
