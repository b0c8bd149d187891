"""Reports an engineer can hand on: one self-contained HTML file per analysis.

:func:`report` (also ``rigidblocks.report``) runs an analysis when asked and writes the
scene's summary and units, the question and the answer with its status and notes, the
governing joints, a sortable per-joint table, and the pictures: 2D scenes as inline
SVG, 3D scenes as an interactive three.js view (turn, zoom, layers, the mechanism
animated by a slider, a joint's forces on hover). The file makes no network request.

In a notebook the returned :class:`Report` shows itself (an ``<iframe srcdoc>``, so
the report's scripts and styles stay apart from the notebook's).

Example:
    >>> import rigidblocks as rb
    >>> from rigidblocks.generators.solids import box_stack
    >>> page = rb.report(box_stack(boxes=1), analysis="load")
    >>> page.startswith("<!DOCTYPE html>") and "collapse" in page
    True
"""

from __future__ import annotations

import html as _html
from pathlib import Path
from typing import Any

from ..errors import InputError
from ..results import check_result
from ..scene.model import Scene


class Report(str):
    """The HTML document (a ``str``) that shows itself in a notebook."""

    #: height of the frame a notebook shows it in (CSS)
    frame_height = "900px"

    def __repr__(self) -> str:
        # (a plain Python prompt echoed the whole document, 750 kB with a 3D view)
        return (f"<rigidblocks report: one HTML document of {len(self):,} characters; "
                ".save(path) writes it, str(report) is the document>")

    def _repr_html_(self) -> str:
        return ('<div class="rb-report-frame">'
                f'<iframe srcdoc="{_html.escape(str(self), quote=True)}" '
                f'style="width:100%;height:{self.frame_height};border:1px solid #ddd" '
                'title="rigidblocks report"></iframe></div>')

    def to_ipython(self) -> Any:
        """The report as an ``IPython.display.HTML`` object (needs IPython)."""
        from IPython.display import HTML

        return HTML(self._repr_html_())

    def save(self, path: str | Path) -> Path:
        """Write the report to ``path`` (UTF-8); returns the path."""
        p = Path(path)
        try:
            p.write_text(str(self), encoding="utf-8")
        except OSError as err:
            raise InputError(f"cannot write: {err}", str(p)) from None
        return p


def _registered(name: str) -> Any:
    """The analysis registered under ``name`` (:func:`rigidblocks.analyses.analysis`)."""
    from ..analyses import analysis

    return analysis(name)


def run_analysis(scene: Scene, analysis: str, **options: Any) -> Any:
    """Run ``analysis`` ("check", "friction" or "load", or the function names) with a
    force state; every option (friction, load_factor, method, solver, ...) goes to the
    analysis function as it is, so an option the analyses add later needs no change
    here. Options an analysis does not take are an error that names them."""
    info = _registered(analysis)
    opts = {k: v for k, v in options.items() if v is not None}
    for key in ("friction", "load_factor"):
        if key in opts and key not in info.takes:
            # (the API's keyword and the command line's option: it named the option)
            raise InputError(f"the {info.command} analysis takes no {key} "
                             f"(--{key.replace('_', '-')})")
    return info.function(scene, **opts)


def report(scene: Scene | str | Path, result: Any = None, *, analysis: str | None = None,
           path: str | Path | None = None, title: str | None = None,
           **options: Any) -> Report:
    """A self-contained HTML report of a scene and an analysis.

    Args:
        scene: a scene, or the path of a scene file.
        result: the result of ``check``, ``min_friction`` or ``max_load_multiplier`` on
            this scene; None with ``analysis`` runs that analysis, None without it
            reports the scene alone.
        analysis: "check", "friction" or "load", run when ``result`` is None.
        path: also write the report to this file.
        title: the report's title (default: the scene's name).
        **options: passed to the analysis (``friction``, ``load_factor``, ``method``,
            ``solver``, ...).

    Returns:
        The HTML document, a :class:`Report` (a ``str`` that a notebook shows).
    """
    from ..io import read_scene
    from ..scene.validate import check_fields
    from .html import render

    if not isinstance(scene, Scene):
        scene = read_scene(scene)
    check_fields(scene)  # (units="m" ended in an AttributeError without an analysis)
    if result is None and analysis is not None:
        result = run_analysis(scene, analysis, **options)
    elif options:
        raise InputError("analysis options (" + ", ".join(sorted(options)) + ") need "
                         "analysis=... and no result")
    else:
        check_result(scene, result)
        if analysis is not None and result is not None \
                and _registered(analysis).name != result.analysis:
            # (a check's result with analysis="load" gave the check's page, no word)
            raise InputError(f"analysis={analysis!r} with the result of a "
                             f"{result.analysis}: give one or the other")
    page = Report(render(scene, result, title=title))
    if path is not None:
        page.save(path)
    return page


__all__ = ["Report", "report", "run_analysis"]
