"""Command line: ``rigidblocks COMMAND ...``.

Each command is a module in this package with ``add_args(parser)`` and
``run(args) -> int``; this module only wires them up and turns errors into exit codes:
0 when the analysis ran (whatever its verdict), 2 for bad input or usage (one line on
standard error naming the file, block or key), 1 for a solver failure.
"""

from __future__ import annotations

import argparse
import gc
import importlib
import os
import sys
import warnings
from collections.abc import Sequence
from typing import Any

from ..analyses import ANALYSES
from ..errors import InputError, SolverFailure, Terminated
from ..io.paths import output_path
from .options import one_line, use_finite_floats

#: numpy's floating-point warnings (RuntimeWarning)
NUMPY_WARNINGS = r"(overflow|invalid value|divide by zero|underflow) encountered"
#: command name -> (module, one-line help)
COMMANDS: dict[str, tuple[str, str]] = {
    **{a.command: ("analyses", a.help) for a in ANALYSES.values()},
    "example": ("example", "list the structure generators, or write a generated scene file"),
    "thickness": ("thickness", "minimum thickness of a generator's family (bisection)"),
    "path": ("path", "load path of the distortion method (2D; the seed's procedure with "
             "--flow non-associative): cracks, plastic joints, collapse"),
    "plot": ("plot", "draw a scene and an analysis result (png, svg, pdf)"),
    "report": ("report", "one self-contained HTML report: answer, pictures, 3D view, joints"),
    "import-dxf": ("dxf", "read a DXF drawing (closed polylines) into a scene file"),
    "export-dxf": ("dxf", "write a 2D scene, its thrust line and forces to DXF"),
    "import-compas": ("compas", "read a COMPAS Assembly or BlockModel (JSON) into a scene "
                      "file"),
    "extrude": ("extrude", "turn a 2D scene into the 3D scene of its prisms"),
    "sweep": ("sweep", "parametric study from a spec file: many cases, in parallel, resumable"),
}


#: the options that name a file a command writes (their dest, and how they are written)
_OUTPUTS = (("output", "-o"), ("joints", "--joints"))


def _not_an_input(args: argparse.Namespace) -> None:
    """Refuse an output (-o, --joints FILE) that is one of the files the command reads
    (an argument naming an existing file): `import-dxf same.dxf -o same.dxf` replaced
    the drawing by a scene file, `extrude s.json -o s.json` the 2D scene by its prisms,
    `check s.json --joints s.json` the scene by its joint table."""
    for dest, option in _OUTPUTS:
        out = getattr(args, dest, None)
        if not isinstance(out, str) or out == "-" or not os.path.isfile(out):
            continue
        for key, value in vars(args).items():
            if key == dest or not isinstance(value, str) or not os.path.isfile(value):
                continue
            if os.path.samefile(value, out):
                raise InputError(f"is the file it reads ({value}): it would be "
                                 "overwritten; give another name", f"{option} {out}")


class _Parser(argparse.ArgumentParser):
    def error(self, message: str):  # usage errors: one line, exit 2
        # "rigidblocks: error: load: argument ...": the program is named once
        command = self.prog.removeprefix("rigidblocks").strip()
        raise InputError(f"{command}: {message}" if command else message)

    def _print_message(self, message: str, file: Any = None) -> None:
        # the help and the version, written or said not to be (argparse drops a write
        # that fails: --help to a full disk exited 0 with nothing written)
        if message:
            (file or sys.stderr).write(message)


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The parser of every command, or with the options of ``command`` only (the others
    listed by name): a run parses one command, and building the others' options and
    importing their modules cost 5 ms of CPU."""
    parser = _Parser(prog="rigidblocks", description="Limit analysis of rigid-block "
                     "masonry with unilateral frictional joints.")
    from .._version import __version__

    parser.add_argument("--version", action="version", version=f"rigidblocks {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name, (module, help_) in COMMANDS.items():
        p = sub.add_parser(name, help=help_, description=help_)
        if command is not None and name != command:
            continue
        mod = importlib.import_module(f"{__package__}.{module}")
        mod.add_args(p, name)
        use_finite_floats(p)
        p.set_defaults(_run=mod.run)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the CLI; returns the exit status."""
    with warnings.catch_warnings():
        # numpy's floating-point warnings are not for the user: the scene's derived
        # quantities are checked representable before any solve (scene.validate), and
        # a solve's trouble is its status
        warnings.filterwarnings("ignore", NUMPY_WARNINGS, RuntimeWarning)
        return _main(argv)


def _main(argv: Sequence[str] | None) -> int:
    try:
        words = list(sys.argv[1:] if argv is None else argv)
        parser = build_parser(words[0] if words and words[0] in COMMANDS else None)
        args, extra = parser.parse_known_args(words)
        if extra:  # named with the command it was given to
            command = getattr(args, "command", None)
            hint = ""
            if getattr(args, "joints", None) == "-" and \
                    any(w.lower().endswith(".csv") for w in extra):
                # `--joints --friction 0.5 r.csv`: the file given away from its option
                hint = " (the CSV file of --joints follows it: --joints FILE.csv)"
            raise InputError(f"{command + ': ' if command else ''}unrecognized "
                             f"arguments: {' '.join(extra)}{hint}")
        if not getattr(args, "_run", None):
            parser.print_help()
            return 2
        if getattr(args, "output", None):  # every command's -o, before any work
            output_path(args.output)
        _not_an_input(args)
        gc.freeze()  # the imported modules' objects: the collections of the run skip them
        try:
            status = int(args._run(args) or 0)
        finally:
            gc.unfreeze()
        sys.stdout.flush()  # a closed pipe (`| head`) shows here, not at exit
        return status
    except BrokenPipeError:  # the reader stopped reading: not an error of the run
        _silence_stdout()
        return 141  # 128 + SIGPIPE, as a program the pipe ended
    except InputError as err:
        print(f"rigidblocks: error: {one_line(err)}", file=sys.stderr)
        return 2
    except SolverFailure as err:
        print(f"rigidblocks: solver failure: {one_line(err)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt as err:  # pragma: no cover
        if isinstance(err, Terminated):  # SIGTERM during a sweep: 128 + 15
            print("rigidblocks: terminated", file=sys.stderr)
            return 143
        print("rigidblocks: interrupted", file=sys.stderr)
        return 130
    except OSError as err:  # an output that cannot be written (stdout on a full disk
        # ended in a traceback): said in one line, as an unwritable -o is
        _silence_stdout()
        where = f"{err.filename}: " if err.filename else "standard output: "
        print(f"rigidblocks: error: cannot write: {where}{err.strerror or err}",
              file=sys.stderr)
        return 2


def _silence_stdout() -> None:
    """Point standard output at /dev/null, so the interpreter's flush at exit does not
    fail again on the closed pipe."""
    import os

    try:
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except (OSError, ValueError):  # a standard output with no file (a captured one)
        pass


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
