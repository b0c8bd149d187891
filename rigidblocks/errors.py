"""Exceptions of rigidblocks.

Two kinds of trouble are kept apart:

* :class:`InputError` -- the user's scene, file or arguments are wrong. The message is
  one line that names the file, block or key at fault; the CLI prints it and exits 2.
* :class:`SolverFailure` -- a solver could not give a trustworthy answer (iteration
  limit, numerical error, "almost" statuses). The message carries the solver's own
  status; the CLI exits 1. "No admissible equilibrium" is *not* a failure: it is a
  result, returned as a status.
"""

from __future__ import annotations


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
