"""``extrude``: a 2D scene file to the 3D scene file of its prisms."""

from __future__ import annotations

import argparse

from ..errors import InputError
from ..io import read_scene, write_scene
from .options import finite_float


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("scene", help="2D scene file (JSON)")
    p.add_argument("-o", "--output", required=True, help="3D scene file to write (JSON)")
    p.add_argument("--depth", type=finite_float, default=None,
                   help="length of the prisms, in the scene's length unit (default: the "
                   "scene's depth, else 1)")


def run(args: argparse.Namespace) -> int:
    from ..scene.extrude import extrude

    scene = read_scene(args.scene)
    try:
        solid = extrude(scene, args.depth)
    except InputError as err:
        raise err.located(args.scene) from None
    write_scene(solid, args.output)
    depth = scene.effective_depth if args.depth is None else args.depth
    unit = f" {scene.length_unit}" if scene.length_unit else ""
    # (the stocky arch's f* printed 0.298455 in 2D, 0.298157 extruded: both within the
    # search's 1e-3, beside "are the 2D scene's")
    same = "f* and lambda* are the 2D scene's, each to its search's accuracy"
    if depth != scene.effective_depth and scene.loads:
        ratio = depth / scene.effective_depth
        same = (f"its {len(scene.loads)} point load(s) are kept as given while the weights "
                f"and the joints' strengths scale with the depth ({ratio:g} times the "
                f"scene's {scene.effective_depth:g}{unit}): f* and lambda* are not the 2D "
                f"scene's unless the loads are scaled by {ratio:g} too")
    if any(j.tensile_strength for j in scene.joints):
        same += ("; with the joints' tensile strength counted as in 2D only at infinite "
                 "friction (3D cones per contact point: a tensile strength without "
                 "cohesion gives no bending capacity there, docs/methods.md)")
    print(f"wrote {args.output}: {len(solid.blocks)} prisms {depth:g}{unit} deep (the 2D "
          f"plane x-y is the vertical plane x-z; {same})")
    return 0
