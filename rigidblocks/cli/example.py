"""``example``: list the generators, or write a generated scene file."""

from __future__ import annotations

import argparse
import sys
from typing import Any

from ..errors import InputError
from ..io.paths import output_path


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("generator", nargs="?", help="generator name (see --list)")
    p.add_argument("--list", action="store_true", help="list generators and parameters")
    p.add_argument("-o", "--output", help="scene file to write (default: standard output)")
    p.add_argument("params", nargs=argparse.REMAINDER,
                   help="--PARAM VALUE pairs of the generator")


def parse_params(gen, tokens: list[str]) -> dict[str, Any]:
    """``--name value`` pairs, converted after the type of each parameter's default."""
    known = {p.name: p for p in gen.params}
    out: dict[str, Any] = {}
    i = 0
    while i < len(tokens):
        tok = tokens[i]
        if not tok.startswith("--"):
            raise InputError(f"example {gen.name}: expected --PARAM VALUE, got {tok!r}")
        key = tok[2:].replace("-", "_")
        if "=" in key:
            key, value = key.split("=", 1)
            i += 1
        else:
            if i + 1 >= len(tokens):
                raise InputError(f"example {gen.name}: --{key} needs a value")
            value = tokens[i + 1]
            i += 2
        if key not in known:
            raise InputError(f"example {gen.name}: unknown parameter --{key} (parameters: "
                             f"{', '.join(known)})")
        out[key] = convert(gen.name, key, value, known[key].default)
    return out


def convert(gen: str, key: str, value: str, default: Any) -> Any:
    """A command-line string as the type of ``default`` (numbers may also be words like
    "infinite", which the generator then validates)."""
    if isinstance(default, bool):
        low = value.lower()
        if low not in ("true", "false", "1", "0", "yes", "no"):
            raise InputError(f"example {gen}: --{key} must be true or false, got {value!r}")
        return low in ("true", "1", "yes")
    if isinstance(default, int):
        try:
            return int(value)
        except ValueError:
            raise InputError(f"example {gen}: --{key} must be an integer, got {value!r}") \
                from None
    if isinstance(default, float):
        try:
            return float(value)
        except ValueError:
            return value
    if default is None:  # an optional number: as written
        for kind in (int, float):
            try:
                return kind(value)
            except ValueError:
                pass
        return value
    if isinstance(default, tuple | list):
        try:
            return [tuple(int(v) for v in item.split(",")) for item in value.split(";")
                    if item.strip()]
        except ValueError:
            raise InputError(f"example {gen}: --{key} must look like 'a,b,c,d;a,b,c,d', got "
                             f"{value!r}") from None
    return value


def listing() -> str:
    from ..generators import available

    return "\n".join(describe(gen) for gen in available().values())


def describe(gen) -> str:
    """A generator's name, summary and parameters (with their defaults)."""
    lines = [f"{gen.name}: {gen.summary}"]
    for p in gen.params:
        # None and empty defaults mean "none" or "see the help": not printed as such
        shown = p.default is not None and p.default not in ((), [], "")
        default = f" (default {p.default})" if shown else ""
        lines.append(f"    --{p.name}{default}  {p.help}".rstrip())
    return "\n".join(lines)


def run(args: argparse.Namespace) -> int:
    from ..generators import get
    from ..io.scene_file import dumps_scene, write_scene

    if args.list:
        print(listing())
        return 0
    if not args.generator:
        raise InputError("example: give a generator name, or --list")
    gen = get(args.generator)
    tokens = list(args.params)
    if "-h" in tokens or "--help" in tokens:
        print(f"usage: rigidblocks example {gen.name} [--PARAM VALUE ...] [-o SCENE.json]\n")
        print(describe(gen))
        return 0
    if "-o" in tokens or "--output" in tokens:  # an -o given after the parameters
        k = tokens.index("-o") if "-o" in tokens else tokens.index("--output")
        if k + 1 >= len(tokens):
            raise InputError("example: -o needs a file name")
        args.output = tokens[k + 1]
        del tokens[k:k + 2]
    if args.output:
        output_path(args.output)  # before any work
    scene = gen(**parse_params(gen, tokens))
    if args.output:
        write_scene(scene, args.output)
        print(f"wrote {args.output}: {scene.name} ({len(scene.blocks)} blocks)",
              file=sys.stderr)
    else:
        sys.stdout.write(dumps_scene(scene))
    return 0


__all__ = ["add_args", "run", "parse_params", "convert", "listing", "describe"]
