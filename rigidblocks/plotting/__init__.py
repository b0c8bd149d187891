"""Pictures of scenes and results (needs matplotlib, imported when first used).

:func:`plot` draws a 2D scene with :func:`rigidblocks.plotting.plot2d.plot` and a 3D
scene with :func:`rigidblocks.plotting.plot3d.plot` (same arguments).
"""

from __future__ import annotations

from typing import Any

from ..results import check_result
from ..scene.model import Scene
from ..scene.validate import check_fields
from .plot2d import MAX_ARROWS, displaced_polygons, save_figure
from .plot2d import plot as plot2d

#: the picture files :func:`plot` writes (format from the extension)
FORMATS = (".png", ".svg", ".pdf")


def plot(scene: Scene, result: Any = None, ax: Any = None, *, path: Any = None,
         **kwargs: Any) -> Any:
    """Draw a scene and a result: plane pictures for 2D scenes, mplot3d for 3D ones.

    Keyword arguments (``ids``, ``max_arrows``, ``force_scale``,
    ``displacement_scale``, ``title``, ``colorbar``) are those of
    :func:`rigidblocks.plotting.plot2d.plot`; returns the matplotlib Axes. ``path``:
    also save the figure there (png, svg or pdf, as `rigidblocks plot -o` does; as
    :func:`rigidblocks.report`'s ``path``). Its own figure (``ax`` None) holds the title
    and the legend; in a figure of one's own, give it ``layout="constrained"`` or save
    it with ``bbox_inches="tight"``, as
    :func:`~rigidblocks.plotting.plot2d.save_figure` does, for the legend below it.
    """
    check_fields(scene)  # (units="m" ended in an AttributeError; a bad geometry is drawn)
    check_result(scene, result)
    if path is not None:  # before the drawing: a bad name is told at once
        from ..io.paths import output_path

        output_path(path, FORMATS, "path")
    if scene.dimension == 3:
        from .plot3d import plot as plot3d

        axes = plot3d(scene, result, ax, **kwargs)
    else:
        axes = plot2d(scene, result, ax, **kwargs)
    if path is not None:
        save_figure(axes, path)
    return axes


__all__ = ["FORMATS", "MAX_ARROWS", "displaced_polygons", "plot", "save_figure"]
