"""Scenes: the plain-data description of a block structure, and its geometry."""

from .model import INFINITE, Block, JointOverride, Load, Scene, Units, make_block

__all__ = ["INFINITE", "Block", "JointOverride", "Load", "Scene", "Units", "make_block"]
