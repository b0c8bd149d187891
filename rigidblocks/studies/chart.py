"""Charts of a study's results."""

from __future__ import annotations

from typing import Any

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


__all__ = ["plot"]
