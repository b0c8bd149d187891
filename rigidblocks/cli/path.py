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
    p.add_argument("--verbose", "-v", action="store_true",
                   help="also print the work done and the solver's notes")


def _status_tail(res, max_load: float, live: float, fu: str) -> str:
    """What the status line says after the status: the collapse load, or the end of the
    path a structure still standing has reached."""
    if res.collapse_load is not None:
        return (f" at lambda = {res.collapse_load:.6g}: {res.collapse_load:.4g} x "
                f"{live:.4g} {fu} = {res.collapse_load * live:.4g} {fu}")
    if res.status == "standing":
        return (f" at lambda = {max_load:g} ({max_load * live:.4g} {fu}), the end of the "
                "path (--max-load goes further)")
    return ""


def run(args: argparse.Namespace) -> int:
    scene = read_scene(args.scene)
    res = load_path(scene, steps=args.steps, max_load=args.max_load, friction=args.friction,
                    sliding=args.sliding)
    if args.json:
        print(json.dumps(_jsonable(res.to_dict())))
        return EXIT.get(res.status, 0)
    from ..answer import live_load_size, live_load_text

    fu = scene.force_unit or "force units"
    live = live_load_size(scene)
    lines = [f"scene      {scene.name or scene.source}",
             f"asked      the load path of the distortion method from lambda = 0 to "
             f"{args.max_load:g} in {args.steps} steps, lambda multiplying the live load "
             f"({live_load_text(scene)}); {res.sliding} sliding, friction {res.friction}",
             f"status     {res.status.upper()}" + _status_tail(res, args.max_load, live, fu)]
    if res.events:
        lines.append(f"  {'lambda [-]':>12}  {'live [' + fu + ']':>12}  {'event':8s}  "
                     "joints (blocks a-b)")
    for e in res.events:
        joints = ", ".join(f"{a}-{b}" for a, b in e.joints) or "-"
        lines.append(f"  {e.load_factor:12.6g}  {e.load_factor * live:12.4g}  "
                     f"{e.kind:8s}  {joints}")
    if args.verbose:
        lines.append(f"work       {res.n_solves} runs, {res.iterations} iterations, "
                     f"{res.solve_time:.3g} s")
    from ..answer import split_notes

    reasons, notes = split_notes(res.notes)
    lines.extend(f"why        {n}" for n in reasons)
    if args.verbose:
        lines.extend(f"note       {n}" for n in notes)
    print("\n".join(lines))
    return EXIT.get(res.status, 0)
