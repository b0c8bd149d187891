"""Scenes: the plain-data description of a block structure, and its geometry.

``rigidblocks.scene.extrude`` is the function :func:`.extrude.extrude` (2D scene to the
3D scene of its prisms); its module stays importable as ``from
rigidblocks.scene.extrude import extrude``.
"""

from .extrude import extrude
from .model import INFINITE, Block, JointOverride, Load, Scene, Units, make_block

__all__ = ["INFINITE", "Block", "JointOverride", "Load", "Scene", "Units", "extrude",
           "make_block"]
