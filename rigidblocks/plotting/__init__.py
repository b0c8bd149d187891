"""Pictures of scenes and results (needs matplotlib, imported when first used)."""

from .plot2d import MAX_ARROWS, available_friction, displaced_polygons, plot, save_figure

__all__ = ["MAX_ARROWS", "available_friction", "displaced_polygons", "plot", "save_figure"]
