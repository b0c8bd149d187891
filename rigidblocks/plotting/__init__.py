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


def plot(scene: Scene, result: Any = None, ax: Any = None, **kwargs: Any) -> Any:
    """Draw a scene and a result: plane pictures for 2D scenes, mplot3d for 3D ones.

    Keyword arguments (``ids``, ``max_arrows``, ``force_scale``,
    ``displacement_scale``, ``title``, ``colorbar``) are those of
    :func:`rigidblocks.plotting.plot2d.plot`; returns the matplotlib Axes. Its own
    figure (``ax`` None) holds the title and the legend; in a figure of one's own,
    give it ``layout="constrained"`` or save it with ``bbox_inches="tight"``, as
    :func:`~rigidblocks.plotting.plot2d.save_figure` does, for the legend below it.
    """
    check_fields(scene)  # (units="m" ended in an AttributeError; a bad geometry is drawn)
    check_result(scene, result)
    if scene.dimension == 3:
        from .plot3d import plot as plot3d

        return plot3d(scene, result, ax, **kwargs)
    return plot2d(scene, result, ax, **kwargs)


__all__ = ["MAX_ARROWS", "displaced_polygons", "plot", "save_figure"]
