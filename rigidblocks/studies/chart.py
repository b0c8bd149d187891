"""Charts of a study's results."""

from __future__ import annotations

from typing import Any

import numpy as np

from ..errors import InputError


def plot(frame: Any, x: str, y: str, hue: str | None = None, ax: Any = None,
         **kwargs: Any) -> Any:
    """Line chart of column ``y`` against ``x`` of a study's frame, one line per value
    of ``hue``. A case without a number in ``y`` (failed, undecided, unstable, ...)
    breaks its line and is marked with an x at the foot of the axes, and a note counts
    them by status (such cases were left out and the line drawn straight across them,
    as if it were data). Returns the Axes.

    Example: ``plot(df, x="centre_depth", y="friction_angle_deg", hue="voussoirs")``.
    """
    import matplotlib.pyplot as plt

    for c in (x, y, hue):
        if c is not None and c not in frame.columns:
            raise InputError(f"no column {c!r} (columns: {', '.join(map(str, frame.columns))})")
    if ax is None:
        _, ax = plt.subplots()
    df = frame
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
    # a number that is only a bound (an undecided search's bracket end, a thickness at
    # most the lower bound searched) is no point of the curve
    status = _status_of(df, y)
    if status is not None:
        df = df.assign(**{y: df[y].where(~status.isin(BOUNDS_ONLY))})
    missing = df[y].isna()
    # (a case without a hue value, a parameter some cases leave to the default, was
    # dropped by groupby without a word)
    groups = [(None, df)] if hue is None else list(df.groupby(hue, sort=True, dropna=False))
    style = {"marker": "o", "markersize": 3, **kwargs}
    for key, g in groups:
        g = g.sort_values(x)
        # (a series without a number had a legend entry and nothing to see)
        label = None if hue is None else f"{hue} = {key}" + (
            " (no number: x at the foot)" if g[y].isna().all() else "")
        (line,) = ax.plot(g[x], g[y].astype(float), label=label, **style)
        gone = g[g[y].isna()]
        if len(gone):  # at the foot of the axes, in the line's colour
            ax.plot(gone[x], np.full(len(gone), 0.02), "x", color=line.get_color(),
                    transform=ax.get_xaxis_transform(), clip_on=False)
    notes = []
    if missing.any():
        why = _why_missing(df[missing], y)
        notes.append(f"no {y} (x on the axis): " + ", ".join(f"{v} {k}"
                                                               for k, v in why.items()))
    if left_out:
        notes.append(f"not drawn: {left_out} case(s) at {x} = infinite")
    if notes:  # in the axes (the title is the user's)
        ax.text(0.01, 0.99, "\n".join(notes), transform=ax.transAxes, ha="left", va="top",
                fontsize=8)
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    if hue is not None and groups:
        ax.legend()
    ax.grid(True, alpha=0.3)
    return ax


#: statuses whose answer column holds a bound, not the answer
BOUNDS_ONLY = ("undecided", "at_lower_bound")


def _status_of(frame: Any, y: str) -> Any:
    """The status column of the analysis that answers ``y`` (None where there is none)."""
    from .execute import ANSWERS

    name = next((a for a, cols in ANSWERS.items() if y in cols), None)
    col = f"{name}_status"
    return frame[col] if col in frame.columns else None


def _why_missing(rows: Any, y: str) -> dict[str, int]:
    """How many of ``rows`` (cases without a number in ``y``) ended in each status of
    the analysis that answers ``y`` (failed, undecided, unstable, ...), or of the case."""
    import pandas as pd

    status = _status_of(rows, y)
    if status is None:
        status = pd.Series(None, index=rows.index, dtype=object)
    if "status" in rows.columns:  # a case whose scene was not built: its analyses None
        status = status.where(status.notna(), rows["status"].where(rows["status"] != "ok"))
    counts = status.fillna("not computed").value_counts(sort=False)
    return {str(k): int(v) for k, v in counts.items()}


def _numbers(col: Any) -> Any:
    """A column of numbers, inf or "infinite" (a friction grid) as floats; None where
    it holds other words (drawn as they are)."""
    import pandas as pd

    if pd.api.types.is_numeric_dtype(col):  # (a sweep's friction: inf where infinite)
        return col.to_numpy(dtype=float)
    out = pd.to_numeric(col.replace({"infinite": np.inf, "inf": np.inf}), errors="coerce")
    return None if out.isna().any() else out.to_numpy(dtype=float)


__all__ = ["plot"]
