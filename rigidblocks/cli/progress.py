"""Long analyses on the command line: a progress line, and Ctrl-C that acts at once.

The analysis runs in a worker thread (the solvers release the interpreter while they
work), so the main thread stays free to show what the analysis is doing and to take
Ctrl-C: the run then ends within a fraction of a second with exit status 130 and no
traceback, whatever solve is under way.
"""

from __future__ import annotations

import os
import shutil
import sys
import threading
import time
from collections.abc import Callable
from typing import TypeVar

from ..methods import Progress

T = TypeVar("T")
#: seconds before the progress line appears (short analyses print nothing)
DELAY = 2.0
#: seconds between two updates of the line
EVERY = 0.5


def run_interruptible(work: Callable[[], T], progress: Progress | None = None,
                      show: bool = False) -> T:
    """``work()`` in a worker thread; with ``show`` (a terminal), a progress line on
    standard error from ``DELAY`` seconds on; Ctrl-C exits at once with status 130."""
    box: dict[str, object] = {}

    def target() -> None:
        try:
            box["value"] = work()
        except BaseException as err:  # noqa: BLE001 - re-raised in the main thread
            box["error"] = err

    worker = threading.Thread(target=target, name="rigidblocks-analysis", daemon=True)
    t0 = time.perf_counter()
    worker.start()
    shown = False
    last = 0.0
    try:
        while worker.is_alive():
            worker.join(0.1)
            now = time.perf_counter()
            if show and progress is not None and now - t0 >= DELAY and now - last >= EVERY:
                width = shutil.get_terminal_size((80, 20)).columns - 1
                sys.stderr.write("\r" + progress.text(width).ljust(width))
                sys.stderr.flush()
                shown, last = True, now
    except KeyboardInterrupt:
        if shown:
            sys.stderr.write("\n")
        sys.stderr.write("rigidblocks: interrupted\n")
        sys.stderr.flush()
        sys.stdout.flush()
        os._exit(130)  # the worker is inside a native solve: end the process now
    if shown:
        width = shutil.get_terminal_size((80, 20)).columns - 1
        sys.stderr.write("\r" + " " * width + "\r")
        sys.stderr.flush()
    if "error" in box:
        raise box["error"]  # type: ignore[misc]
    return box["value"]  # type: ignore[return-value]


__all__ = ["run_interruptible"]
