"""Option types and checks shared by every command.

* :func:`finite_float`, the argparse type of every float option: ``inf`` and ``nan``
  are usage errors (exit 2), never a value;
* :func:`~rigidblocks.io.paths.output_path`, the check of a file a command will write,
  made before any work (:func:`rigidblocks.cli.main.main` checks every command's
  ``-o``): an output whose folder does not exist, is a folder or cannot be written is
  bad input (exit 2), and nothing is created.
"""

from __future__ import annotations

import argparse

from ..errors import finite_number
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


def use_finite_floats(parser: argparse.ArgumentParser) -> None:
    """Give every ``type=float`` option of ``parser`` the type :func:`finite_float`."""
    for action in parser._actions:
        if action.type is float:
            action.type = finite_float


__all__ = ["finite_float", "load_factor", "output_path", "use_finite_floats"]
