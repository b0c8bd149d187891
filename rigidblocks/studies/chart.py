"""Charts of a study's results."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import InputError


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
    # a friction grid with "infinite" is a column of strings: drawn as numbers (an axis
    # of categories spaced evenly bent the line lambda = f), the infinite ones left out
    xs = _numbers(df[x])
    left_out = 0
    if xs is not None:
        left_out = int((~np.isfinite(xs)).sum())
        df = df.assign(**{x: xs})[np.isfinite(xs)]
    if hue is None and df[x].duplicated().any():
        raise InputError(f"several cases share a value of {x!r}: give hue, the parameter "
                         "that varies besides it (one line each)")
    groups = [(None, df)] if hue is None else list(df.groupby(hue, sort=True))
    style = {"marker": "o", "markersize": 3, **kwargs}
    for key, g in groups:
        g = g.sort_values(x)
        ax.plot(g[x], g[y].astype(float), label=None if hue is None else f"{hue} = {key}",
                **style)
    if left_out:  # in the axes (the title is the user's)
        ax.text(0.01, 0.99, f"not drawn: {left_out} case(s) at {x} = infinite",
                transform=ax.transAxes, ha="left", va="top", fontsize=8)
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    if hue is not None and groups:
        ax.legend()
    ax.grid(True, alpha=0.3)
    return ax


def _numbers(col: Any) -> Any:
    """A column of numbers and "infinite" (a friction grid) as floats; None where it
    holds other words (drawn as they are)."""
    import pandas as pd

    if pd.api.types.is_numeric_dtype(col):
        return None
    out = pd.to_numeric(col.replace({"infinite": np.inf, "inf": np.inf}), errors="coerce")
    return None if out.isna().any() else out.to_numpy(dtype=float)


__all__ = ["plot"]
