"""Exceptions of rigidblocks.

Two kinds of trouble are kept apart:

* :class:`InputError` -- the user's scene, file or arguments are wrong. The message is
  one line that names the file, block or key at fault; the CLI prints it and exits 2.
* :class:`SolverFailure` -- a solver could not give a trustworthy answer (iteration
  limit, numerical error, "almost" statuses). The message carries the solver's own
  status; the CLI exits 1. "No admissible equilibrium" is *not* a failure: it is a
  result, returned as a status.

:func:`finite_number` is the one check of a number given by the user (a parameter, a
key, an option): it raises :class:`InputError` (or the caller's error type) when the
value is not a finite number.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any


class RigidBlocksError(Exception):
    """Base class of every error raised on purpose by rigidblocks."""


class InputError(RigidBlocksError, ValueError):
    """Bad input: a malformed scene, an invalid parameter or a usage error.

    ``where`` is prefixed to the message (a file name, or ``block 'A'``), so that the
    single line printed by the CLI says what is wrong and where.
    """

    def __init__(self, message: str, where: str | None = None):
        self.where = where
        self.detail = message
        super().__init__(f"{where}: {message}" if where else message)

    def located(self, where: str) -> InputError:
        """The same error with an outer location (e.g. the file name) prefixed."""
        inner = f"{self.where}: {self.detail}" if self.where else self.detail
        return InputError(inner, where)


class SolverFailure(RigidBlocksError, RuntimeError):
    """A solver did not reach a trustworthy answer; ``status`` is its own word for it."""

    def __init__(self, message: str, solver: str = "", status: str = ""):
        self.solver = solver
        self.status = status
        super().__init__(message)


def finite_number(value: Any, what: str = "value", *, strict: bool = False,
                  message: str = "{what} must be {kind}, got {value!r}",
                  error: Callable[[str], Exception] = InputError) -> float:
    """``value`` as a float if it is a finite number, else ``error(message)``.

    Args:
        value: what the user gave.
        what: the thing named in the message (e.g. ``"load factor"``, or
            ``"arch: rise"``).
        strict: only ``int`` and ``float`` instances (numpy floats among them) are
            numbers; bools, strings and the rest are refused. Otherwise anything
            ``float()`` takes is: ``True``, ``"0.5"``, numpy scalars.
        message: the wording; ``{what}``, ``{kind}`` (``"a number"``, or with
            ``strict`` ``"an int or float"``, when ``value`` is not one; ``"a finite
            number"`` when it is infinite, NaN or too large for a float) and
            ``{value!r}`` are filled in.
        error: the exception type raised with the message (e.g.
            ``argparse.ArgumentTypeError`` for an argparse type).
    """
    kind = "an int or float" if strict else "a number"
    if not strict or (isinstance(value, int | float) and not isinstance(value, bool)):
        try:
            v = float(value)
        except (TypeError, ValueError):
            pass
        except OverflowError:  # an int beyond the float range
            kind = "a finite number"
        else:
            if math.isfinite(v):
                return v
            kind = "a finite number"
    raise error(message.format(what=what, kind=kind, value=value))


class Terminated(KeyboardInterrupt):
    """SIGTERM while a study runs (a batch system's time limit, ``kill``): it ends as at
    Ctrl-C, its workers stopped and its finished cases kept
    (:func:`rigidblocks.studies.execute.terminate_as_interrupt`)."""
