"""Option types and checks shared by every command.

* :func:`finite_float`, the argparse type of every float option: ``inf`` and ``nan``
  are usage errors (exit 2), never a value;
* :func:`add_rtol`, the ``--rtol`` option of every command that brackets a limit
  (``friction``, ``load``, ``thickness``): the relative accuracy asked for;
* :func:`~rigidblocks.io.paths.output_path`, the check of a file a command will write,
  made before any work (:func:`rigidblocks.cli.main.main` checks every command's
  ``-o``): an output whose folder does not exist, is a folder or cannot be written is
  bad input (exit 2), and nothing is created.
"""

from __future__ import annotations

import argparse

from ..errors import InputError, finite_number
from ..io.paths import output_path


def finite_float(text: str) -> float:
    """argparse type: a finite number (``inf``, ``nan`` and non-numbers refused)."""
    return finite_number(text, message="not {kind}: {value!r}",
                         error=argparse.ArgumentTypeError)


def load_factor(text: str) -> float:
    """argparse type of ``--load-factor``: a finite number >= 0, as a scene file's
    ``load_factor`` must be."""
    v = finite_float(text)
    if v < 0:
        raise argparse.ArgumentTypeError(f"must be >= 0 (it multiplies the live loads, as "
                                         f"a scene's load_factor), got {text!r}")
    return v


def friction_option(text: str) -> str:
    """argparse type of ``--friction``: a number >= 0 or "infinite" (checked as a scene's
    friction is), kept as given."""
    from ..scene.model import friction_value

    try:
        friction_value(text)
    except InputError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    return text


def positive_int(text: str) -> int:
    """argparse type: a whole number >= 1."""
    try:
        v = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text!r}") from None
    if v < 1:
        raise argparse.ArgumentTypeError(f"must be >= 1, got {text!r}")
    return v


def positive_float(text: str) -> float:
    """argparse type: a finite number > 0."""
    v = finite_float(text)
    if not v > 0:
        raise argparse.ArgumentTypeError(f"must be > 0, got {text!r}")
    return v


def relative_tolerance(text: str) -> float:
    """argparse type: a relative accuracy, a number in (0, 1)."""
    value = finite_float(text)
    if not 0 < value < 1:
        raise argparse.ArgumentTypeError(f"not a relative accuracy in (0, 1): {text!r}")
    return value


#: the default accuracy of each command's limit, as its help gives it
RTOL_DEFAULTS = {
    "friction": "2e-3, three significant figures (with either flow)",
    "load": "2e-3 (the convex path's one solve is at its tight tolerances whatever it "
            "is, and its duals tell how far lambda* may lie above its answer); with "
            "--flow non-associative 1e-5 for a bisection (the distortion method's, and "
            "the convex path's on small scenes where its limit run stops), with an "
            "absolute floor of 1e-6 of the live load for answers near 0, while the convex "
            "path's answer is otherwise a collapse state checked to 1e-7 (1e-5 with "
            "Coulomb's cones in 3D), no bracket",
    "thickness": "1e-4",
}


def add_rtol(parser: argparse.ArgumentParser, command: str,
             default: float | None = None) -> None:
    """The ``--rtol`` option of ``command`` (a key of :data:`RTOL_DEFAULTS`)."""
    parser.add_argument("--rtol", type=relative_tolerance, default=default,
                        help="relative accuracy of the limit: the search's target, and a "
                        "number is given only where its certified bracket is this narrow "
                        "(relative), else UNDECIDED with the bracket and the accuracy "
                        f"reached; default {RTOL_DEFAULTS[command]}")


def one_line(message: object) -> str:
    """``message`` with its unprintable characters escaped as Python writes them (a
    block id with a newline stays on an error's one line, and on an answer's row)."""
    return "".join(c if c.isprintable() else repr(c)[1:-1] for c in str(message))


def use_finite_floats(parser: argparse.ArgumentParser) -> None:
    """Give every ``type=float`` option of ``parser`` the type :func:`finite_float`."""
    for action in parser._actions:
        if action.type is float:
            action.type = finite_float


__all__ = ["RTOL_DEFAULTS", "add_rtol", "finite_float", "friction_option", "one_line",
           "output_path", "positive_float", "positive_int", "relative_tolerance",
           "use_finite_floats"]
