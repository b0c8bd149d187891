"""rigidblocks: limit analysis of rigid-block masonry with unilateral frictional joints."""

from .contacts import Contacts, detect_contacts
from .equilibrium import EquilibriumSystem, assemble
from .errors import InputError, RigidBlocksError, SolverFailure
from .io import read_scene, write_scene
from .problems import check, max_load_multiplier, min_friction
from .scene import INFINITE, Block, JointOverride, Load, Scene, make_block

__version__ = "0.1.0"

__all__ = [
    "INFINITE", "Block", "Contacts", "EquilibriumSystem", "InputError", "JointOverride",
    "Load", "RigidBlocksError", "Scene", "SolverFailure", "assemble", "detect_contacts",
    "check", "make_block", "max_load_multiplier", "min_friction", "read_scene",
    "write_scene",
]
