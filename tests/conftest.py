"""Shared fixtures: small scenes built in code, and paths to bundled and shared data."""

from __future__ import annotations

import math
import os
from pathlib import Path

import pytest

from rigidblocks.io.scene_file import scene_from_dict

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
SHARED = ROOT.parent / "shared"


def in_ci() -> bool:
    """CI sets CI=true (and has ../shared beside the checkout, and Chromium)."""
    return os.environ.get("CI", "").strip().lower() in ("true", "1", "yes")


def require(present: bool, reason: str) -> None:
    """A test that needs something outside the repository (shared data, a browser):
    skipped with ``reason`` where it is missing, failed instead under CI=true, where
    it must be there."""
    if present:
        return
    if in_ci():
        pytest.fail(f"{reason} (CI=true: it must be there)")
    pytest.skip(reason)


def require_shared(path: Path) -> Path:
    """``path`` under ../shared (beside the checkout), or skip (fail under CI)."""
    require(path.exists(), f"outside data {path} is missing (../shared beside the "
            "checkout)")
    return path


def require_chromium() -> str:
    """The Chromium executable, or skip (fail under CI)."""
    from rigidblocks.reporting.browser import find_chromium

    exe = find_chromium()
    require(exe is not None, "no chromium on the PATH (the browser tests need it)")
    return exe


@pytest.fixture
def chromium() -> str:
    """The Chromium executable; the test is skipped without one (failed under CI)."""
    return require_chromium()


def rect(x0, y0, w, h):
    return [[x0, y0], [x0 + w, y0], [x0 + w, y0 + h], [x0, y0 + h]]


def make_scene(blocks, **top):
    doc = {"format": "rigidblocks-scene", "version": 1, "dimension": 2, "blocks": blocks}
    doc.update(top)
    return scene_from_dict(doc)


def pinched(f=0.3, **top):
    """A unit block between a fixed base and a fixed lintel, both touching it, under a
    horizontal body force lambda W (W = 10): validation.md, "A block pinched between two
    fixed parallel faces". ``top``: more scene keys (e.g. ``flow``)."""
    return make_scene([
        {"id": "base", "vertices": rect(-1, -1, 3, 1), "support": True},
        {"id": "B", "vertices": rect(0, 0, 1, 1)},
        {"id": "lintel", "vertices": rect(-1, 1, 3, 1), "support": True},
    ], unit_weight=10.0, friction=f, live_body_force=[1, 0], **top)


@pytest.fixture
def block_on_base():
    """A b x h block on a wide support, unit weight 1, live horizontal body force."""

    from rigidblocks.generators.catalogue import block_on_base as build_block

    def build(b=1.0, h=2.0, friction=0.5, **extra):
        return build_block(b, h, friction, **extra)

    return build


def down(x: float, digits: int = 7) -> str:
    """``x`` cut (not rounded) to ``digits`` significant figures: what the CLI prints of
    a multiplier known to round-off, on the safe side (a check stands at it)."""
    from decimal import ROUND_FLOOR, Decimal

    step = Decimal(1).scaleb(math.floor(math.log10(abs(x))) - digits + 1)
    return f"{float(Decimal(repr(x)).quantize(step, ROUND_FLOOR)):.{digits}g}"
