"""``import-compas``: a COMPAS Assembly or BlockModel JSON file to a scene file."""

from __future__ import annotations

import argparse

from ..errors import InputError
from ..io import write_scene


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("file", help="COMPAS JSON: a compas_assembly Assembly (compas_cra's "
                   "CRA_Assembly too) or a compas_dem BlockModel")
    p.add_argument("-o", "--output", required=True, help="scene file to write (JSON)")
    p.add_argument("--friction", default=None,
                   help="friction f of every joint (default: the file's, else infinite)")
    p.add_argument("--density", type=float, default=1.0,
                   help="weight per volume of blocks that give none (default 1, as "
                   "compas_cra)")
    p.add_argument("--supports", default=None,
                   help="node keys to fix besides the file's supports, e.g. '0,1'")
    p.add_argument("--live-body-force", default=None, metavar="'AX AY [AZ]'",
                   help="the live load of `rigidblocks load`: every free block's weight "
                   "times this vector times lambda, e.g. '1 0' (a horizontal "
                   "acceleration of lambda g along x; AZ defaults to 0). The scene's "
                   "load_factor is then written 0, so check and friction answer for "
                   "the weight alone (--load-factor asks for more)")
    p.add_argument("--name", default=None, help="scene name (default: the file's stem)")


def _friction(text: str | None) -> float | None:
    """``--friction`` read as every other command reads it (a number >= 0, or
    "infinite"; NaN read "must be >= 0")."""
    from ..scene.model import friction_value

    if text is None:
        return None
    try:
        return friction_value(text)
    except InputError as err:
        raise InputError(f"--friction: {err}") from None


def _body_force(text: str | None) -> tuple[float, float, float] | None:
    """'AX AY' or 'AX AY AZ' (commas or spaces) as a 3D vector, not all zero."""
    if text is None:
        return None
    from .options import finite_float

    try:
        vals = [finite_float(v) for v in text.replace(",", " ").split()]
    except argparse.ArgumentTypeError:
        vals = []
    if len(vals) not in (2, 3) or not any(vals):
        raise InputError(f"--live-body-force: give two or three numbers, not all zero, "
                         f"e.g. '1 0', got '{text}'")
    return (vals[0], vals[1], vals[2] if len(vals) == 3 else 0.0)


def run(args: argparse.Namespace) -> int:
    from ..compas import read_compas

    if args.density is not None and not args.density >= 0:
        raise InputError("--density must be >= 0")
    supports = ([s.strip() for s in args.supports.split(",") if s.strip()]
                if args.supports else None)
    live = _body_force(args.live_body_force)
    scene, rep = read_compas(args.file, friction=_friction(args.friction),
                             density=args.density, supports=supports, name=args.name)
    if live is not None:
        scene = scene.with_changes(live_body_force=live, load_factor=0.0)
    write_scene(scene, args.output)
    print(rep.summary())
    if live is not None:
        print(f"live load  weight x ({live[0]:g}, {live[1]:g}, {live[2]:g}) x lambda "
              "(load factor 0 written: check and friction answer for the weight alone)")
    print(f"wrote {args.output}")
    return 0
