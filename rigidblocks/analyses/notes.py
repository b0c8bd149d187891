"""Notes the analyses of both flow rules attach to their results."""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Any

from ..methods import ADMISSIBLE, Method


def friction_governs(m: Method, f: float, load_factor: float, na: bool = False
                     ) -> str | None:
    """Where no state is admissible at a finite friction ``f``, a note saying whether
    one is without sliding (the joints' friction infinite, their overrides kept; the
    flow rule is then moot): then friction governs, not the geometry (the inclined
    corbel arch at f = 0.6 under its self-weight: it stands from f* = 0.7654), and the
    command that gives the friction needed (``na``: without dilatancy)."""
    if not math.isfinite(f):
        return None
    v = m.admissible(math.inf, load_factor)
    if v.status != ADMISSIBLE:
        return None
    where = "under its dead load alone" if load_factor == 0 else "at this load"
    flow = " --flow non-associative" if na else ""
    command = (f"`rigidblocks friction {m.scene.source or 'SCENE'} --load-factor "
               f"{load_factor:.10g}{flow}`")
    if na:
        # infinite friction is another joint law, not the limit of large ones: without
        # dilatancy a joint with no normal force carries no shear at any finite f (the
        # 8 x 8 wall at 0.7 stands at infinite friction, and no f up to 10 carries it)
        return (f"without sliding (infinite friction) it stands {where}, a joint law no "
                f"finite friction reaches without dilatancy (a joint without compression "
                f"carries shear there); {command} searches the least finite friction that "
                "carries it (up to 10)")
    return (f"without sliding (infinite friction) it stands {where}: friction governs, not "
            f"the geometry; {command} gives the least friction that carries it")


def unstable_note(scene: Any) -> str:
    """Where the dead load alone has no admissible state (friction does not govern),
    the command that names the joints it breaches."""
    return (f"`rigidblocks check {scene.source or 'SCENE'} --load-factor 0` names the "
            "joints the dead load breaches")


def with_friction_governs(res: Any, m: Method, f: float, load_factor: float) -> Any:
    """A non-associative result that found no admissible state, with the note of
    :func:`friction_governs` (a static check without sliding by the method ``m``, which
    the flow rule does not enter; made after the result, so that what it adds to ``m``'s
    notes stays out of it)."""
    note = friction_governs(m, f, load_factor, na=True)
    return replace(res, notes=(*res.notes, note)) if note else res


def interlocking_note(m: Method) -> None:
    """A note for the associative analyses where blocks touch on opposed faces (keys in
    grooves, :meth:`~rigidblocks.contacts.model.Contacts.opposed_pairs`): friction that
    dilates cannot slide along them, and the answer may rest on that clamping (the
    keyed wall in plane at f = 0.05: lambda* = 1, tipping; 0.05 without dilatancy)."""
    pairs = m.contacts.opposed_pairs()
    if not pairs:
        return
    ids = m.contacts.block_ids
    named = ", ".join(f"{ids[a]}-{ids[b]}" for a, b in pairs[:3])
    more = f" and {len(pairs) - 3} more" if len(pairs) > 3 else ""
    m.notes.append(f"blocks touch on opposed faces ({named}{more}: keys or interlocking): "
                   "with associative friction (dilatancy) they cannot slide along them, "
                   "which may carry what dry joints that do not dilate do not; compare "
                   "`--flow non-associative`")
