"""``path``: the load path of the distortion method (cracks, plasticity, collapse)."""

from __future__ import annotations

import argparse
import json
import sys

from ..analyses import load_path
from ..analyses.load_path import FINE, MAX_STEPS
from ..io import read_scene
from ..methods import Progress
from ..results import fmt_safe
from .analyses import EXIT, _jsonable
from .options import friction_option, positive_float, positive_int
from .progress import run_interruptible


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("scene", help="scene file (JSON, see docs/scene-format.md)")
    p.add_argument("--steps", type=_steps, default=40,
                   help=f"number of load steps, 1 to {MAX_STEPS} (default 40)")
    p.add_argument("--max-load", type=positive_float, default=2.0,
                   help="largest live-load multiplier of the path (default 2)")
    p.add_argument("--friction", type=friction_option,
                   help='friction coefficient f, or "infinite" '
                   "(Heyman: no sliding; default: the scene's)")
    p.add_argument("--sliding", choices=("plastic", "coulomb"), default="plastic",
                   help="shear links at their threshold: plastic (Drucker: the shear "
                   "stays at f N + c, default) or coulomb (sliding friction: the shear "
                   "drops to zero for the rest of the path)")
    p.add_argument("--flow", choices=("associative", "non-associative"), default=None,
                   help="non-associative: shear capped without changing the normal "
                   "forces, the seed's procedure; associative: a cross-check of the "
                   "convex path (default: the scene's flow, else associative)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--verbose", "-v", action="store_true",
                   help="also print the work done and the solver's notes")


def _steps(text: str) -> int:
    """argparse type of ``--steps``: a whole number from 1 to MAX_STEPS."""
    v = positive_int(text)
    if v > MAX_STEPS:
        raise argparse.ArgumentTypeError(f"at most {MAX_STEPS} (each step is a solve at "
                                         f"least; events are located to {FINE:g} of their "
                                         f"load whatever the step), got {text!r}")
    return v


def run(args: argparse.Namespace) -> int:
    scene = read_scene(args.scene)
    progress = Progress()
    res = run_interruptible(lambda: load_path(
        scene, steps=args.steps, max_load=args.max_load, friction=args.friction,
        sliding=args.sliding, flow=args.flow, progress=progress), progress,
        show=not args.json and sys.stderr.isatty())
    if args.json:
        # the terminal's "why" lines and the units, as every analysis's JSON has them
        # (None where the scene gives none: "force units" in the text)
        doc = {**res.to_dict(), "why": list(_why(res)[0]),
               "units": {"length": scene.length_unit or None,
                         "force": scene.force_unit or None}}
        print(json.dumps(_jsonable(doc)))
        return EXIT.get(res.status, 0)
    print("\n".join(_lines(scene, res, args)))
    return EXIT.get(res.status, 0)


def _lines(scene, res, args: argparse.Namespace) -> list[str]:
    from ..answer import joint_friction_words, live_load_measure, live_load_text

    live, fu, direction = live_load_measure(scene)
    some = res.sliding_joints
    # (a scene's one joint without dilatancy read "non-associative flow" for them all,
    # and a joint's own friction went unsaid beside "friction infinite")
    flow = ("non-associative flow (no dilatancy: the seed's procedure)" if some is None
            else f"{some} of {res.contacts.n_joints} joints sliding without dilatancy "
            "(the seed's procedure), the others associative") \
        if res.flow == "non-associative" else "associative flow"
    if res.flow == "non-associative" and _no_joint_slides(res):
        # (it read "non-associative flow (no dilatancy ...)" beside "infinite friction
        # (no sliding)")
        flow += ", idle: no joint slides at infinite friction"
    lines = [f"scene      {scene.name or scene.source}",
             f"asked      the load path of the distortion method from lambda = 0 to "
             f"{args.max_load:g} in {args.steps} steps, lambda multiplying the live load "
             f"({live_load_text(scene)}); {res.sliding} sliding, {flow}, "
             f"{joint_friction_words(scene, res)}",
             f"status     {res.status.upper()}" + _status_tail(res, live, fu, direction)]
    # a balanced live load (the reference model's two opposing pulls) has no
    # resultant: its column is the sum of its sizes, as the status line says
    head = ("live in all [" if direction.startswith("in all") else "live [") + fu + "]"
    width = max(12, len(head))  # ("live in all [N]" stood 3 columns right of its column)
    if res.events:
        lines.append(f"  {'lambda [-]':>14}  {head:>{width}}  {'event':8s}  "
                     "joints (blocks a-b)")
    for e in res.events:
        modes = e.modes or ("",) * len(e.joints)
        joints = ", ".join(f"{a}-{b}" + (f" ({m})" if m else "")
                           for (a, b), m in zip(e.joints, modes, strict=True)) or "-"
        # down, as the status line's collapse: an event happens at or above its load
        lines.append(f"  {fmt_safe(e.load_factor, 9, False):>14}  "
                     f"{fmt_safe(e.load_factor * live, 6, False):>{width}}  {e.kind:8s}  "
                     f"{joints}")
    if args.verbose:
        lines.append(f"work       {res.n_solves} runs, {res.iterations} iterations, "
                     f"{res.solve_time:.3g} s")
    reasons, notes = _why(res)
    lines.extend(f"why        {n}" for n in reasons)
    if args.verbose:
        lines.extend(f"note       {n}" for n in notes)
    return lines


def _no_joint_slides(res) -> bool:
    """Is every joint's friction infinite (the uniform one where it has none of its
    own), so that the flow rule has nothing to act on?"""
    import numpy as np

    over = np.asarray(res.contacts.override_friction, dtype=float)
    uniform = np.inf if res.friction == "infinite" else float(res.friction)
    return bool(np.all(np.isinf(np.where(np.isnan(over), uniform, over))))


def _why(res) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(reasons, solver notes) of a path (:func:`~rigidblocks.answer.split_notes`), where
    what happened at a load ("at lambda = ...: no convergence within the iteration
    budget ...", the reason an undecided path stops) is a reason: it read only with -v."""
    from ..answer import split_notes

    reasons, notes = split_notes(res.notes)
    at = tuple(n for n in notes if n.startswith("at lambda = "))
    return (reasons + at, tuple(n for n in notes if n not in at))


def _status_tail(res, live: float, fu: str, direction: str = "") -> str:
    """What the status line says after the status: the collapse load, the bracket of an
    undecided run, or the end of the path a structure still standing has reached."""
    if res.collapse_load is not None:
        lam = res.collapse_load
        # the collapse load is the last admissible one: rounded on its safe side, and
        # multiplied as printed (it read "lambda = 0.149764895: 0.149764 x 37.6948 kN")
        shown = fmt_safe(lam, 9, False)
        return (f" at lambda = {shown}: {shown} x {live:.6g} {fu} = "
                f"{fmt_safe(lam * live, 6, False)} {fu} {direction}").rstrip()
    if res.status == "undecided" and res.bracket:
        lo, hi = res.bracket
        if hi > lo:
            return (f": admissible up to lambda = {lo:.9g}, not decided at {hi:.9g} "
                    "(no verdict beyond)")
        return f": not decided at lambda = {lo:.9g} (no verdict beyond)"
    if res.status == "standing" and res.steps:
        end = res.steps[-1].load_factor
        # (the bonded reference model to --max-load 1: STANDING at 1 beside its bed
        # joints' plasticisation there, where the path to 2 collapses)
        done = {"crack": "cracked", "plastic": "became plastic", "slide": "slid"}
        last = sorted({done.get(e.kind, e.kind) for e in res.events
                       if e.load_factor >= end * (1 - 1e-9)})
        at_end = (f"; at its end joints {' and '.join(last)}: it may collapse at once "
                  "beyond" if last else "")
        # (to 10 figures: "STANDING at lambda = 0.149765", its 0.149764895 rounded up
        # above the collapse load the path to 0.15 gives)
        return (f" at lambda = {end:.10g} ({end * live:.4g} {fu}), the end of the path "
                f"(--max-load goes further){at_end}")
    return ""
