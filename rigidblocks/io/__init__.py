"""Files in and out: scene files (and, with extras, CAD drawings)."""

from .scene_file import dumps_scene, read_scene, scene_from_dict, scene_to_dict, write_scene

__all__ = ["dumps_scene", "read_scene", "scene_from_dict", "scene_to_dict", "write_scene"]
