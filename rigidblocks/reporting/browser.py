"""Open a report in headless Chromium: a screenshot, and the page's state after its
scripts ran (JavaScript errors caught by the page's own hook, the 3D view's timings).

Used by the tests and by ``benchmarks/bench_report.py``; needs a ``chromium`` (or
Chrome) executable on the PATH (Debian: ``apt-get install chromium``). WebGL runs on
the software rasteriser (SwiftShader), so it works without a GPU or a display.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

EXECUTABLES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")
#: virtual time the page gets after its load event before the screenshot or the dump
#: (ms; None: none). The report's scripts all run before the load event, so a budget
#: is not needed, and under one the page's clock (performance.now) stands still.
BUDGET_MS: int | None = None


def find_chromium() -> str | None:
    """The path of a Chromium or Chrome executable, or None."""
    for name in EXECUTABLES:
        path = shutil.which(name)
        if path:
            return path
    return None


@dataclass(frozen=True)
class PageState:
    """What the page said about itself: ``errors`` from its error hook and the
    ``data-*`` attributes of its <html> element (viewer-ready, timings, ...), and
    the DOM."""

    errors: tuple[str, ...]
    data: dict[str, str] = field(default_factory=dict)
    seconds: float = 0.0
    #: the document as the scripts left it
    dom: str = ""


def _run(exe: str, args: list[str], url: str, timeout: float) -> tuple[str, str, float]:
    with tempfile.TemporaryDirectory(prefix="rb-chromium-") as profile:
        cmd = [exe, "--headless", "--hide-scrollbars", "--no-first-run",
               "--no-default-browser-check", "--disable-extensions",
               "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
               # offline: any request for an address would go to a closed local port
               # and fail (the page's error hook reports resources that fail to load)
               "--proxy-server=127.0.0.1:9", "--proxy-bypass-list=<-loopback>",
               f"--user-data-dir={profile}", *args, url]
        if hasattr(os, "geteuid") and os.geteuid() == 0:
            cmd.insert(1, "--no-sandbox")
        t = time.perf_counter()
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout,
                              check=False)
        return proc.stdout, proc.stderr, time.perf_counter() - t


def _budget(ms: int | None) -> list[str]:
    return [] if ms is None else [f"--virtual-time-budget={ms}"]


def _url(path: str | Path, fragment: str = "") -> str:
    u = Path(path).resolve().as_uri()
    return u + (f"#{fragment}" if fragment else "")


def screenshot(html: str | Path, png: str | Path, size: tuple[int, int] = (1280, 1000),
               budget_ms: int | None = BUDGET_MS, exe: str | None = None,
               timeout: float = 180.0) -> float:
    """Save a screenshot of the page ``html`` (a file) to ``png``; returns the seconds
    Chromium took."""
    exe = exe or find_chromium()
    if exe is None:
        raise FileNotFoundError("no chromium executable on the PATH")
    png = Path(png).resolve()
    _, err, secs = _run(exe, [f"--screenshot={png}", f"--window-size={size[0]},{size[1]}",
                              *_budget(budget_ms)], _url(html), timeout)
    if not png.exists():
        raise RuntimeError(f"chromium wrote no screenshot: {err[-2000:]}")
    return secs


def page_state(html: str | Path, fragment: str = "", size: tuple[int, int] = (1280, 1000),
               budget_ms: int | None = BUDGET_MS, exe: str | None = None,
               timeout: float = 180.0) -> PageState:
    """Load the page, let its scripts run, and read the DOM it ends with."""
    exe = exe or find_chromium()
    if exe is None:
        raise FileNotFoundError("no chromium executable on the PATH")
    dom, err, secs = _run(exe, ["--dump-dom", f"--window-size={size[0]},{size[1]}",
                                *_budget(budget_ms)],
                          _url(html, fragment), timeout)
    m = re.search(r"<html([^>]*)>", dom)
    data = dict(re.findall(r'data-([a-z0-9-]+)="([^"]*)"', m.group(1))) if m else {}
    box = re.search(r'<pre id="rb-errors"[^>]*>(.*?)</pre>', dom, flags=re.S)
    errors = tuple(x for x in (box.group(1).splitlines() if box else []) if x.strip())
    if not m:
        errors += (f"no document was dumped: {err[-2000:]}",)
    return PageState(errors, data, secs, dom)


def pixel_spread(png: str | Path) -> float:
    """Standard deviation of the screenshot's grey levels (0 for a blank page)."""
    import matplotlib.image as mpimg
    import numpy as np

    img = np.asarray(mpimg.imread(str(png)), dtype=float)
    grey = img[..., :3].mean(axis=-1) if img.ndim == 3 else img
    return float(grey.std())


__all__ = ["PageState", "find_chromium", "page_state", "pixel_spread", "screenshot"]
