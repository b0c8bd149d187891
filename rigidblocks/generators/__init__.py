"""Parametric generators of standard structures (scenes built in code).

:data:`GENERATORS` maps a name to a :class:`Generator`: the function, and its
parameters with defaults and help, so that the command line can list them
(``rigidblocks example --list``) and build any of them
(``rigidblocks example NAME --PARAM VALUE ... -o scene.json``).
:mod:`rigidblocks.generators.catalogue` holds the standard problems with known answers
(closed forms and published values, with their sources) that every method is tested on.
Every generator counts the blocks its parameters ask for and refuses more than its bound
(:mod:`rigidblocks.generators.limits`) before building any.

>>> from rigidblocks.generators import build
>>> scene = build("flat_arch", voussoirs=5, joints="vertical")
>>> len(scene.blocks)
8
"""

from __future__ import annotations

import importlib
import inspect
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..errors import InputError
from ..scene.model import Scene


@dataclass(frozen=True)
class Param:
    """One parameter of a generator: name, default value and a one-line help."""

    name: str
    default: Any
    help: str = ""
    #: the type the generator's signature gives it (e.g. "int | None"), as written
    annotation: str = ""


@dataclass(frozen=True)
class Generator:
    """A named generator: ``module:function``, imported when first used."""

    name: str
    target: str
    summary: str
    helps: tuple[tuple[str, str], ...] = ()

    @property
    def function(self) -> Callable[..., Scene]:
        module, func = self.target.split(":")
        return getattr(importlib.import_module(f"{__name__}.{module}"), func)

    @property
    def params(self) -> tuple[Param, ...]:
        helps = dict(self.helps)
        sig = inspect.signature(self.function)
        return tuple(Param(p.name, p.default, helps.get(p.name, ""),
                           "" if p.annotation is p.empty else str(p.annotation))
                     for p in sig.parameters.values())

    def check_params(self, names: Any) -> None:
        """InputError naming the first of ``names`` that is not a parameter."""
        known = {p.name for p in self.params}
        bad = sorted(set(names) - known)
        if bad:
            raise InputError(f"{self.name}: unknown parameter {bad[0]!r} (parameters: "
                             f"{', '.join(sorted(known))})")

    def __call__(self, **params: Any) -> Scene:
        self.check_params(params)
        return self.function(**params)


_ARCH_HELP = (
    ("thickness", "ring thickness ratio t/R (R the mean radius)"),
    ("voussoirs", "number of voussoirs"),
    ("radius", "mean radius R (m)"),
    ("joints", "radial | vertical"),
    ("springing", "abutments (fixed) | piers (free, on a ground support)"),
    ("pier_width", "pier width beyond the extrados (m)"),
    ("pier_height", "pier height (m)"),
    ("unit_weight", "unit weight (kN/m^3)"),
    ("friction", 'friction coefficient f, or "infinite"'),
    ("depth", "out-of-plane thickness (m)"),
)

GENERATORS: dict[str, Generator] = {g.name: g for g in (
    Generator("reference", "seed:reference",
              "the reference paper's four-block model (P on the top block, H pulling the "
              "central blocks apart)",
              (("P", "dead vertical force on the top block (N)"),
               ("H", "live horizontal force on each central block (N)"),
               ("self_weight", "include the blocks' self-weight (true/false)"),
               ("unit_weight", "unit weight (N/m^3) when self_weight"),
               ("block_width", "central block width (m)"),
               ("block_height", "central block height (m)"),
               ("top_height", "top block height (m)"),
               ("depth", "out-of-plane thickness (m)"),
               ("friction", 'friction coefficient f, or "infinite"'),
               ("bond_tensile_strength", "tensile strength of a bonded vertical joint "
                "between the central blocks (N/m^2 over its area; 0: dry), seed Fig. 4b"),
               ("bond_cohesion", "cohesion of that bonded joint (N/m^2 over its area)"))),
    Generator("flat_arch", "arches:flat_arch",
              "flat arch (platband) with vertical or radial joints, on piers or abutments",
              (("span", "clear span at the intrados (m)"),
               ("height", "depth of the platband (m)"),
               ("centre_depth", "radial joints meet at this distance below the intrados (m)"),
               ("bonded_piers", "piers never slide on the ground (true/false)"),
               *_ARCH_HELP)),
    Generator("arch", "arches:arch",
              "semicircular, pointed or segmental arch of n voussoirs",
              (("shape", "semicircular | pointed | segmental"),
               ("half_angle", "segmental: half opening angle (deg)"),
               ("pointedness", "pointed: centre offset / R"),
               ("arc_points", "straight segments per voussoir face"), *_ARCH_HELP,
               ("voussoirs", "number of voussoirs (default 15, 16 for a pointed arch)"))),
    Generator("stocky_arch", "arches:stocky_arch",
              "thick semicircular arch of few voussoirs (the reference paper's Fig. 7a)",
              _ARCH_HELP),
    Generator("corbel_arch", "arches:corbel_arch",
              "corbel arch, horizontal or inward-inclined bed joints (the reference "
              "paper's Fig. 7b, 7c)",
              (("opening", "clear width at the base (m)"), ("courses", "number of courses"),
               ("course_height", "course height (m)"),
               ("block_length", "horizontal length of each block (m)"),
               ("pattern", "horizontal | inclined"),
               ("inclination", "inclined: bed joints dip towards the opening (deg)"),
               *_ARCH_HELP[-3:])),
    Generator("arpino_gate", "arches:arpino_gate",
              "pointed corbelled dry-stone gate (Arpino, the reference paper's Fig. 8)",
              (("opening", "width at the ground (m)"), ("height", "apex height (m)"),
               ("courses", "number of courses"),
               ("joint_inclination", "bed joints dip towards the opening (deg)"),
               ("wall", "wall thickness beyond the opening's base (m)"), *_ARCH_HELP[-3:])),
    Generator("wall", "walls:running_bond_wall",
              "running-bond wall under self-weight and a horizontal live body force",
              (("courses", "number of courses"), ("blocks_per_course", "full blocks per "
               "course"), ("block_length", "block length (m)"),
               ("block_height", "block height (m)"),
               ("horizontal_load", "live body force [h, 0] times the weight"),
               ("openings", "removed blocks: 'course,n_courses,block,n_blocks;...'"),
               *_ARCH_HELP[-3:])),
    Generator("wall3d", "solids:wall3d",
              "3D single-wythe running-bond wall of boxes, loaded in or out of plane",
              (("courses", "number of courses"), ("blocks_per_course", "full blocks per "
               "course"), ("block_length", "block length along x (m)"),
               ("block_height", "block height (m)"), ("thickness", "wall thickness (m)"),
               ("load_direction", "in_plane | out_of_plane"),
               ("horizontal_load", "live body force magnitude times the weight"),
               *_ARCH_HELP[-3:-1])),
    Generator("box_stack", "solids:box_stack",
              "3D stack of equal boxes on a slab under a horizontal live body force",
              (("boxes", "number of boxes"), ("width", "box size along x (m)"),
               ("length", "box size along y (m)"), ("height", "box height (m)"),
               ("offset", "x shift of each box over the one below (m)"),
               ("offsets", "box centres 'dx,dy;dx,dy;...' (one per box)"),
               ("load_azimuth", "direction of the live body force, degrees from +x"),
               *_ARCH_HELP[-3:-1])),
    Generator("corbel_dome", "solids:corbel_dome",
              "3D corbel dome: rings of blocks stepping inwards, with or without a cap",
              (("rings", "number of rings"), ("blocks_per_ring", "blocks in each ring"),
               ("radius", "inner radius of the bottom ring (m)"),
               ("ring_thickness", "radial thickness of the rings (m)"),
               ("ring_height", "ring height (m)"),
               ("overhang", "inward step of each ring (m)"),
               ("cap", "close the top with a keystone (true/false)"),
               *_ARCH_HELP[-3:-1])),
    Generator("barrel_vault", "solids:barrel_vault",
              "3D barrel vault of voussoirs in rings along its axis, stack or running bond",
              (("voussoirs", "voussoirs per ring"), ("thickness", "ring thickness ratio "
               "t/R"), ("radius", "mean radius R (m)"), ("length", "vault length (m)"),
               ("rings", "rings along the length"), ("bond", "stack | running"),
               ("half_angle", "half opening angle (deg; 90 is semicircular)"),
               ("abutment_width", "abutment width beyond the extrados (m)"),
               ("abutment_height", "abutment height (m)"), *_ARCH_HELP[-3:-1])),
    Generator("keyed_wall", "keyed:keyed_wall",
              "3D running-bond wall of tongue-and-groove (non-convex) units, keyed beds",
              (("courses", "number of courses"), ("blocks_per_course", "full units per "
               "course"), ("block_length", "unit length along x (m)"),
               ("block_height", "course height (m)"), ("thickness", "wall thickness (m)"),
               ("key_width", "tongue width (m)"), ("key_height", "tongue height (m); 0: "
               "plain boxes"), ("base_friction", "friction on the foundation (default: "
               "friction)"), ("load_direction", "in_plane | out_of_plane"),
               ("horizontal_load", "live body force magnitude times the weight"),
               *_ARCH_HELP[-3:-1])),
)}


def available() -> dict[str, Generator]:
    """The generators whose module can be imported."""
    out = {}
    for name, g in GENERATORS.items():
        try:
            _ = g.function
        except (ImportError, AttributeError):
            continue
        out[name] = g
    return out


def get(name: str) -> Generator:
    """The generator called ``name`` (InputError if there is none)."""
    gens = available()
    if name not in gens:
        raise InputError(f"unknown example {name!r} (choose from {', '.join(gens)})")
    return gens[name]


def build(name: str, **params: Any) -> Scene:
    """Build the scene of generator ``name`` with ``params`` (the others default)."""
    return get(name)(**params)


__all__ = ["GENERATORS", "Generator", "Param", "available", "build", "get"]
