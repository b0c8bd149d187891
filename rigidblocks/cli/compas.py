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
    p.add_argument("--name", default=None, help="scene name (default: the file's stem)")


def _friction(text: str | None) -> float | None:
    if text is None:
        return None
    try:
        f = float(text)
    except ValueError:
        raise InputError(f"--friction: not a number: '{text}'") from None
    if not f >= 0:
        raise InputError("--friction must be >= 0")
    return f


def run(args: argparse.Namespace) -> int:
    from ..compas import read_compas

    if args.density is not None and not args.density >= 0:
        raise InputError("--density must be >= 0")
    supports = ([s.strip() for s in args.supports.split(",") if s.strip()]
                if args.supports else None)
    scene, rep = read_compas(args.file, friction=_friction(args.friction),
                             density=args.density, supports=supports, name=args.name)
    write_scene(scene, args.output)
    print(rep.summary())
    print(f"wrote {args.output}")
    return 0
