"""``example``: list the generators, or write a generated scene file."""

from __future__ import annotations

import argparse
import re
import sys
from collections.abc import Mapping
from typing import Any

from ..errors import InputError
from ..io.paths import output_path


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("generator", nargs="?", help="generator name (see --list)")
    p.add_argument("--list", action="store_true", help="list generators and parameters")
    p.add_argument("-o", "--output", help="scene file to write (default: standard output)")
    p.add_argument("params", nargs=argparse.REMAINDER,
                   help="--PARAM VALUE pairs of the generator")
    from ..generators import GENERATORS

    p.epilog = ("generators: " + ", ".join(GENERATORS) + " (their parameters: "
                "rigidblocks example --list, or rigidblocks example NAME --help)")


def parse_params(gen, tokens: list[str], typed: dict[str, str] | None = None,
                 command: str = "example") -> dict[str, Any]:
    """``--name value`` pairs, converted after the type of each parameter's default.

    ``typed``, when given, receives each parameter's option as the user wrote it
    (``"blocks_per_course" -> "--blocks-per-course"``), for :func:`as_options`;
    errors begin with ``command`` and the generator's name.
    """
    where = f"{command} {gen.name}"
    known = {p.name: p for p in gen.params}
    out: dict[str, Any] = {}
    i = 0
    while i < len(tokens):
        tok = tokens[i]
        if not tok.startswith("--"):
            raise InputError(f"expected --PARAM VALUE, got {tok!r}", where)
        option, value = tok.split("=", 1) if "=" in tok else (tok, None)
        key = parameter_name(option)
        if value is not None:
            i += 1
        else:
            if i + 1 >= len(tokens):
                raise InputError(f"{option} needs a value", where)
            value = tokens[i + 1]
            i += 2
        if key not in known:
            raise InputError(f"unknown parameter {option} ({options(gen)})", where)
        out[key] = convert(where, option, value, known[key].default)
        if typed is not None:
            typed[key] = option
    return out


def parameter_name(option: str) -> str:
    """The generator's parameter an option or name stands for: ``--blocks-per-course``,
    ``blocks-per-course`` and ``blocks_per_course`` are ``blocks_per_course``."""
    return option.removeprefix("--").replace("-", "_")


def options(gen) -> str:
    """``"parameters: --a, --b, ..."``: a generator's parameters as ``--list`` spells
    them."""
    return "parameters: " + ", ".join(f"--{p.name}" for p in gen.params)


def convert(where: str, option: str, value: str, default: Any) -> Any:
    """A command-line string as the type of ``default`` (numbers may also be words like
    "infinite", which the generator then validates); errors begin with ``where``
    (``"example arch"``) and name ``option`` as typed."""
    if isinstance(default, bool):
        low = value.lower()
        if low not in ("true", "false", "1", "0", "yes", "no"):
            raise InputError(f"{option} must be true or false, got {value!r}", where)
        return low in ("true", "1", "yes")
    if isinstance(default, int):
        try:
            return int(value)
        except ValueError:
            raise InputError(f"{option} must be an integer, got {value!r}", where) from None
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
    return value  # (a list's string form 'a,b;c,d' the generator reads)


_PREFIX = re.compile(r"(\w+): ")
_WORD = re.compile(r"(?<![\w#'-])[A-Za-z_]\w*")


def as_options(err: InputError, gen, typed: Mapping[str, str],
               command: str = "example") -> InputError:
    """The generator's error ``err`` in the command line's words.

    A generator's message reads ``"function: parameter must ..."`` (the Python names).
    Here it reads ``"example NAME: --option must ..."`` (``command NAME``): the
    function's name gives way to the command's, and every word of the message that is
    one of the generator's parameters (``key_width must be < thickness``: both) becomes
    its option, spelled as the user typed it (``typed``, from :func:`parse_params`) or,
    when not typed, as ``--list`` shows it. Words in quotes (values, ``got 'courses'``)
    are left alone; the generators word their messages so that a parameter's name is
    never prose (``so that each ring overlaps the one below``, not ``consecutive
    rings``).
    """
    names = {p.name for p in gen.params}
    text = str(err)
    prefix = _PREFIX.match(text)
    if prefix and prefix.group(1) not in names:
        text = text[prefix.end():]

    def option(word: re.Match) -> str:
        name = word.group(0)
        return typed.get(name, f"--{name}") if name in names else name

    return InputError(_WORD.sub(option, text), f"{command} {gen.name}")


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
        # `--list NAME`: that generator alone (an unknown name says which there are)
        print(describe(get(args.generator)) if args.generator else listing())
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
    typed: dict[str, str] = {}
    params = parse_params(gen, tokens, typed)
    try:
        scene = gen(**params)
    except InputError as err:
        raise as_options(err, gen, typed) from None
    if args.output:
        write_scene(scene, args.output)
        print(f"wrote {args.output}: {scene.name} ({len(scene.blocks)} blocks)",
              file=sys.stderr)
    else:
        sys.stdout.write(dumps_scene(scene))
    return 0


__all__ = ["add_args", "run", "parse_params", "parameter_name", "options", "convert",
           "as_options", "listing", "describe"]
