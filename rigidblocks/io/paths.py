"""Paths of files to write, checked before any work is done."""

from __future__ import annotations

import os
from pathlib import Path

from ..errors import InputError


def output_path(path: str | os.PathLike, suffixes: tuple[str, ...] | None = None,
                option: str = "-o") -> Path:
    """``path`` checked as a file to write: its folder exists and is writable, it is
    not a folder, and (if given) it ends in one of ``suffixes``. Creates nothing.

    Raises:
        InputError: one line naming the path and the option.
    """
    p = Path(path)
    where = f"{option} {os.fspath(path)}"
    if suffixes is not None and p.suffix.lower() not in suffixes:
        raise InputError(f"must end in {' or '.join(suffixes)}", where)
    if p.is_dir():
        raise InputError("is a folder, not a file", where)
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        raise InputError(f"no such folder: {os.fspath(parent)}", where)
    if not os.access(parent, os.W_OK | os.X_OK) or (p.exists() and not os.access(p, os.W_OK)):
        raise InputError("cannot be written (permission denied)", where)
    return p


__all__ = ["output_path"]
