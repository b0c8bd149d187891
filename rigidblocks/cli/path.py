"""``path``: the load path of the distortion solver (cracks, plasticity, collapse)."""

from __future__ import annotations

import argparse
import json

from ..analyses import load_path
from ..io import read_scene
from .analyses import EXIT, _jsonable
from .options import finite_float


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("scene", help="scene file (JSON, see docs/scene-format.md)")
    p.add_argument("--steps", type=int, default=40, help="number of load steps (default 40)")
    p.add_argument("--max-load", type=finite_float, default=2.0,
                   help="largest live-load multiplier of the path (default 2)")
    p.add_argument("--friction", help='friction coefficient f, or "infinite" '
                   "(default: the scene's)")
    p.add_argument("--sliding", choices=("plastic", "coulomb"), default="plastic",
                   help="shear links: plastic (Drucker, default) or coulomb (shear drops "
                   "to zero after sliding)")
    p.add_argument("--json", action="store_true", help="print one JSON object")


def run(args: argparse.Namespace) -> int:
    scene = read_scene(args.scene)
    res = load_path(scene, steps=args.steps, max_load=args.max_load, friction=args.friction,
                    sliding=args.sliding)
    if args.json:
        print(json.dumps(_jsonable(res.to_dict())))
        return EXIT.get(res.status, 0)
    lines = [f"scene      {scene.name or scene.source}",
             f"sliding    {res.sliding}   friction {res.friction}",
             f"status     {res.status.upper()}"
             + (f" at load factor {res.collapse_load:.6g}" if res.collapse_load is not None
                else "")]
    for e in res.events:
        joints = ", ".join(f"{a}-{b}" for a, b in e.joints) or "-"
        lines.append(f"  {e.load_factor:12.6g}  {e.kind:8s}  {joints}")
    lines.append(f"work       {res.n_solves} runs, {res.iterations} iterations, "
                 f"{res.solve_time:.3g} s")
    lines.extend(f"note       {n}" for n in res.notes)
    print("\n".join(lines))
    return EXIT.get(res.status, 0)
