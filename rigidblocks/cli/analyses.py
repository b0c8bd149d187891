"""``check``, ``friction`` and ``load``: the analyses on a scene file."""

from __future__ import annotations

import argparse
import json
import math
import sys
from dataclasses import replace
from typing import Any

from ..analyses import analysis
from ..analyses.nonassociative import (
    SPREAD_NOTE,
    is_nonassociative,
)
from ..answer import accuracy_text, answer_block, flow_lines, live_load_doc, method_text
from ..errors import InputError
from ..io import read_scene
from ..methods import METHODS, Progress
from ..results import fmt_safe
from ..scene.model import INFINITE, friction_label
from .options import (
    add_rtol,
    finite_float,
    friction_option,
    one_line,
    positive_float,
    relative_tolerance,
)
from .options import load_factor as load_factor_type
from .progress import run_interruptible

#: options of the question an analysis answers: command-line name -> keyword argument
QUESTION_OPTIONS = ("friction", "load_factor", "method", "solver", "contact_tol", "flow")


def add_question_args(p: argparse.ArgumentParser, takes: tuple[str, ...]) -> None:
    """The options of the question asked (``takes``: friction and/or load_factor)."""
    if "friction" in takes:
        p.add_argument("--friction", type=friction_option,
                       help='friction coefficient f, or "infinite" '
                       "(default: the scene's)")
    if "load_factor" in takes:
        p.add_argument("--load-factor", type=load_factor_type, default=None,
                       help="lambda multiplying the live loads (default: the scene's "
                       "load_factor, or 1)")
    p.add_argument("--method", default=None,
                   help=" or ".join(f'"{m}"' for m in METHODS)
                   + ' (default "clarabel", also "convex": the convex path; "distortion": '
                   "the seed's "
                   "impressed-distortion iteration, its procedure with --flow "
                   "non-associative, a cross-check of the convex path otherwise); a back "
                   "end's name is the convex path with that back end, as --solver")
    p.add_argument("--solver", default=None,
                   help="back end of the convex path: clarabel, highs, osqp, scs, ecos, "
                   "cvxpy-NAME")
    p.add_argument("--contact-tol", type=positive_float, default=None,
                   help="contact tolerance relative to the scene's size (default 1e-7): "
                   "faces this close count as touching")
    p.add_argument("--flow", choices=("associative", "non-associative"), default=None,
                   help="sliding rule of every joint without its own (default: the "
                   "scene's flow, else associative)")


def add_limit_args(p: argparse.ArgumentParser) -> None:
    """The options of a limit's search that a picture or a report of any analysis takes
    (``--rtol``, ``--mechanism``), refused by :func:`limit_options` where the analysis
    has no such limit (a report could not reproduce `load --rtol 1e-5`)."""
    p.add_argument("--rtol", type=relative_tolerance, default=None,
                   help="with --analysis friction or load: the relative accuracy of the "
                   "limit (default: the command's, see `rigidblocks friction --help`)")
    add_mechanism(p, None, "with --analysis load: ")


def add_mechanism(p: argparse.ArgumentParser, default: str | None, lead: str = "") -> None:
    """The ``--mechanism`` option (of `load`, and of a picture or a report of one)."""
    p.add_argument("--mechanism", choices=("vertex", "blend"), default=default,
                   help=f"{lead}vertex: one collapse mechanism, joints ranked by relative "
                   "velocity (default); blend: the interior-point mix of every optimal "
                   "mechanism")


def limit_options(args: argparse.Namespace) -> dict[str, Any]:
    """The options of :func:`add_limit_args` given, as keyword arguments of the analysis
    ``args.analysis``; an option it does not take is an :class:`InputError`."""
    out: dict[str, Any] = {}
    for key, takes in (("rtol", ("friction", "load")), ("mechanism", ("load",))):
        value = getattr(args, key, None)
        if value is None:
            continue
        if args.analysis not in takes:
            raise InputError(f"--{key} is an option of --analysis "
                             + " or ".join(takes) + (f", not {args.analysis}"
                                                     if args.analysis else ""))
        out[key] = value
    return out


def question(args: argparse.Namespace) -> dict[str, Any]:
    """The question's options given on the command line, as keyword arguments."""
    return {k: getattr(args, k) for k in QUESTION_OPTIONS
            if getattr(args, k, None) is not None}


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("scene", help="scene file (JSON, see docs/scene-format.md)")
    add_question_args(p, analysis(name).takes)
    if name == "load":
        add_mechanism(p, "vertex")
        p.add_argument("--safe", action="store_true",
                       help="with non-associative joints, scenes of up to 50 joints: also "
                       "the smallest non-associative collapse multiplier over all states "
                       "(a mixed-integer LP solved by HiGHS, at most --safe-time-limit "
                       "per solve; docs/safe-multiplier.md)")
        p.add_argument("--safe-time-limit", type=_seconds, default=60.0, metavar="S",
                       help="the time limit of each mixed-integer solve of --safe, and of "
                       "the bounds' LPs before them, in seconds (default 60); past it "
                       "the safe multiplier is a bracket")
    if name in ("friction", "load"):
        add_rtol(p, name)
    p.add_argument("--joints", nargs="?", const="-", default=None, metavar="CSV",
                   help="the per-joint table (N, T, eccentricity, |T|/N, state, mode, and "
                   "each joint's friction, cohesion and tensile strength): in the JSON "
                   "with --json, else printed, or written to the CSV file given")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("--verbose", "-v", action="store_true",
                   help="also print the solver's and the accuracy's notes (the JSON "
                   "always has them)")


#: exit status by result status: 3 undecided, 1 failure, 0 decided
EXIT = {"undecided": 3, "failure": 1}


def run(args: argparse.Namespace) -> int:
    csv_path = args.joints if args.joints not in (None, "-") else None
    if csv_path is not None:
        _writable(csv_path)
    scene = read_scene(args.scene)
    options = {"mechanism": args.mechanism} if args.command == "load" else {}
    if options.get("mechanism") == "blend" and getattr(args, "method", None) == "distortion" \
            and not is_nonassociative(scene, getattr(args, "flow", None)):
        # without dilatancy the mechanism is the capped laws' LP's, which blends
        raise InputError("--mechanism blend: an option of the convex path (the interior-point "
                         "mix of its optimal mechanisms), not of the distortion method")
    if getattr(args, "rtol", None) is not None:
        options["rtol"] = args.rtol
    # check reports the friction demand of its force state; the others compute a state
    # only for the joint table
    state = args.command == "check" or args.joints is not None
    progress = Progress()
    res = run_interruptible(lambda: analysis(args.command).run(
        scene, state=state, progress=progress, **question(args), **options), progress,
        show=not args.json and sys.stderr.isatty())
    if csv_path is not None:
        _write_csv(res, csv_path, scene)
    safe = _safe(scene, args, res) if getattr(args, "safe", False) else None
    if args.json:
        doc = res.to_dict(joints=args.joints == "-")
        # the terminal's "why" lines: its notes' reasons and what the answer reads off
        # the result (a check's friction at its limit was in neither), not the starts'
        # spread, which the terminal gives on its starts line
        doc["why"] = list(_answer(scene, res)[0].reasons)
        if getattr(res, "analysis", "") == "max_load_multiplier" and scene.has_live_load:
            # what lambda = 1 is, in the force unit: the answer line's "x 32 kN = 16 kN"
            doc["live_load"] = live_load_doc(scene)
        if safe is not None:
            doc["safe_multiplier"] = safe
        print(json.dumps(_jsonable(doc)))
    else:
        print(report(scene, res, joints=args.joints == "-", verbose=args.verbose))
        if safe is not None:
            print(_safe_line(safe, getattr(res, "load_multiplier", None),
                             getattr(res, "bracket", None)))
        if csv_path is not None:
            print(f"wrote {csv_path}")
    return EXIT.get(res.status, 0)


def _seconds(text: str) -> float:
    """argparse type of ``--safe-time-limit``: a number of seconds > 0."""
    value = finite_float(text)
    if not value > 0:
        raise argparse.ArgumentTypeError(f"not a number of seconds > 0: {text!r}")
    return value


def _safe(scene: Any, args: argparse.Namespace, res: Any) -> dict[str, Any]:
    """The safe multiplier of ``load --safe`` as a dict: status, value, bracket, notes
    (or the reason it was not computed); the answer ``res``, where the limit iteration
    ended at a checked collapse state, bounds it from above."""
    from ..analyses.na_bounds import safe_multiplier
    from ..analyses.nonassociative import collapse_state_at, is_nonassociative
    from ..results import BELOW_DEAD_LOAD

    q = question(args)
    if res.cause == BELOW_DEAD_LOAD:
        # the mixed-integer LP seeks collapse multipliers from its capacity bound up: it
        # said "no collapse within the bounds: bracket [4.3e-05, -]" beside a collapse
        # state at -2.7e-5 (the inclined corbel arch at f = 0.7652)
        return {"status": "not computed",
                "reason": "the limit fixed point from X0 collapses below the dead load "
                          "alone (the answer): the smallest multiplier over all states is "
                          "at most its lambda, below 0, where the mixed-integer LP does not "
                          "seek"}
    if not is_nonassociative(scene, q.get("flow")):
        return {"status": "not computed",
                "reason": "no joint slides without dilatancy (give --flow "
                          "non-associative): with associative joints the collapse "
                          "multiplier is unique, the answer above"}
    try:
        r = safe_multiplier(scene, friction=q.get("friction"), flow=q.get("flow"),
                            time_limit=args.safe_time_limit,
                            collapse_at=collapse_state_at(res))
    except InputError as err:
        return {"status": "not computed", "reason": str(err).split(": ", 1)[-1]}
    return {"status": r.status, "value": r.value, "lower": r.lower, "upper": r.upper,
            "associative": r.associative, "nodes": r.nodes, "solve_time": r.solve_time,
            "driven_by": r.driven_by, "notes": list(r.notes)}


def _safe_line(safe: dict[str, Any], answer: float | None,
               bracket: Any = None) -> str:
    """The ``safe`` line: the safe multiplier ``safe`` (:func:`_safe`) beside the
    answer ``answer`` and the answer's ``bracket`` (a bisection's, or None)."""
    from ..analyses.na_bounds import NONE_WITHIN_BOUNDS

    def num(v: Any, up: bool = False) -> str:
        # on the safe side, as the answer's: the smallest multiplier rounded down (it
        # read 0.05920323 above the answer's 0.0592032, one value 0.0592032278)
        return "-" if v is None else fmt_safe(float(v), 7, up)

    st = safe["status"]
    if st == "not computed":
        return f"safe       not computed: {safe['reason']}"
    if st == "optimal":
        line = (f"safe       lambda = {num(safe['value'])}: the smallest non-associative "
                "collapse multiplier over all states (mixed-integer LP, proven)")
        if safe.get("driven_by") == "dead":
            # why a multiplier above 0 then (the corbel arch at f = 0.8: 0.0128): the
            # live load changes the normal forces, and so the friction f N they allow
            line += ("; the dead load drives its mechanism (the live load does no work on "
                     "it or resists it)" + (": some state collapses under the dead load "
                                            "alone" if safe["value"] <= 0 else
                                            ": the live load's part is to change the "
                                            "normal forces, and with them the friction "
                                            "f N the joints can give, until the dead "
                                            "load can move it"))
        if answer is not None and safe["value"] < answer * (1.0 - 1e-6):
            line += (f"\nsafe       BELOW the answer lambda* = {num(answer)}, which is the "
                     "state reached from the elastic state X0: the joints have another "
                     f"state that collapses at {num(safe['value'])}")
        elif answer is not None and safe["value"] > answer * (1.0 + 1e-6) + 1e-12:
            # the answer is a bisection's lower end (the inclined corbel arch at f = 0.8:
            # lambda* = 0.0127922 in [0.0127922, 0.0127927] beside the safe 0.01279269,
            # which read as a proven least above the answer)
            held = bracket is not None and safe["value"] <= bracket[1] * (1 + 1e-9) + 1e-12
            line += (f"\nsafe       above the answer lambda* = {num(answer)}" +
                     (f", within its bracket [{num(bracket[0])}, {num(bracket[1], True)}]: "
                      "to the answer's accuracy they are one value" if held else
                      ": the state reached from X0 breaches the joint laws at a load no "
                      "collapse state reaches (the answer is the seed's procedure's, not a "
                      "collapse state)"))
        return line
    if st == NONE_WITHIN_BOUNDS and safe.get("associative") is not None:
        # (it read "no collapse within the bounds: bracket [lo, -]" beside a collapse at
        # the associative multiplier, where no state is admissible above it)
        return (f"safe       lambda = {num(safe['associative'])}, the associative "
                "multiplier: no collapse state lies below it (mixed-integer LP, within its "
                "bounds on the forces and rates) and no state is admissible above it")
    why = f"; {safe['notes'][0]}" if safe.get("notes") else ""
    return (f"safe       {st}: bracket [{num(safe['lower'])}, {num(safe['upper'], True)}] "
            f"(mixed-integer LP{why})")


def _writable(path: str) -> None:
    """Refuse an output path before any work is done."""
    import os

    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise InputError(f"cannot write: no folder {folder}", path)
    if not os.access(folder, os.W_OK):
        raise InputError(f"cannot write: folder {folder} is not writable", path)


def _write_csv(res: Any, path: str, scene: Any) -> None:
    """The joint table as CSV, with the scene's units in every row (a file opened later
    did not say whether its forces were N or kN)."""
    import csv

    rows = res.joint_table()
    units = [scene.force_unit or "", scene.length_unit or ""]
    try:
        with open(path, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["block_a", "block_b", "N", "T", "eccentricity", "demand", "state",
                        "mode", "friction", "cohesion", "tensile_strength", "force_unit",
                        "length_unit"])
            for r in rows:
                w.writerow([*r["joint"], r["N"], r["T"], r["eccentricity"], r["demand"],
                            r["state"], r["mode"], friction_label(r["friction"]),
                            r["cohesion"], r["tensile_strength"], *units])
    except OSError as err:
        raise InputError(f"cannot write: {err}", path) from None


def _jsonable(v: Any) -> Any:
    if isinstance(v, float) and not math.isfinite(v):
        return None if math.isnan(v) else ("infinite" if v > 0 else "-infinite")
    if isinstance(v, dict):
        return {k: _jsonable(x) for k, x in v.items()}
    if isinstance(v, list | tuple):
        return [_jsonable(x) for x in v]
    return v


def _answer(scene, res) -> tuple[Any, list[str]]:
    """The answer block the terminal prints and its flow lines: the spread of the
    starts said once, on its own line, not among the why lines too."""
    block = answer_block(scene, res)
    flow = flow_lines(res) if res.flow != "associative" else []
    if any(line.startswith("starts ") for line in flow):  # the spread note, once
        block = replace(block, reasons=tuple(r for r in block.reasons
                                             if not r.startswith(SPREAD_NOTE)))
    return block, flow


def report(scene, res, joints: bool = False, verbose: bool = False) -> str:
    """The answer in words (:func:`rigidblocks.answer.answer_block`, as the HTML report
    and the pictures give it); ``joints``: with the joint table; ``verbose``: with the
    solver's and the accuracy's notes."""
    supports = _count(int(scene.support_mask.sum()), "support")
    lines = [f"scene      {scene.name or scene.source}",
             f"blocks     {len(scene.blocks)} ({supports}), "
             f"joints {res.contacts.n_joints}"]
    block, flow = _answer(scene, res)
    lines += block.lines(verbose)
    method = method_text(res)
    lines += [f"method     {method}"] if method else []
    accuracy = accuracy_text(res)
    lines += [f"accuracy   {accuracy}"] if accuracy else []
    lines += flow
    if joints:
        lines += _table(res, scene)
    if verbose:
        lines.append(f"solver     {res.solvers}, {res.n_solves} solve(s), "
                     f"{res.solve_time:.3g} s")
    # a block id with a newline broke its line ("governing  1 hinging (base, ground-A"
    # then "x)"): escaped as the errors give it
    return "\n".join(one_line(line) for line in lines)


def _count(n: int, word: str) -> str:
    return f"{n} {word}" + ("" if n == 1 else "s")


def _table(res, scene) -> list[str]:
    rows = res.joint_table()
    if not rows:
        if res.status == "unbounded":  # admissible at every lambda: no limit state
            return ["joints     no force state (unbounded: no collapse state to show)"]
        return ["joints     no force state (the analysis found no admissible state)"]
    fu, lu = f"[{scene.force_unit or 'force'}]", f"[{scene.length_unit or 'length'}]"
    # 3D: the shear's size (its direction lies in the joint's plane)
    t_head = ("|T| " if scene.dimension == 3 else "T ") + fu
    # the joints' own laws, where they are not all the same: their f, c and ft
    su = f"[{scene.force_unit or 'force'}/{scene.length_unit or 'length'}^2]"
    law = [(key, head, fmt) for key, head, fmt in
           (("friction", "f", "{:.4g}"), ("cohesion", "c " + su, "{:.4g}"),
            ("tensile_strength", "ft " + su, "{:.4g}"))
           if len({r[key] for r in rows}) > 1]
    # the mechanism's mode of each joint, after a collapse only
    modes = any(r["mode"] for r in rows)
    out = [(f"{'joint':<24} {'N ' + fu:>12} {t_head:>12} {'e ' + lu:>10} {'|T|/N':>8}  "
            + "".join(f"{head:>{max(len(head), 8)}}  " for _, head, _ in law)
            + f"{'state':<26} " + ("mode" if modes else "")).rstrip()]
    for r in rows:
        e = "-" if r["eccentricity"] is None else f"{r['eccentricity']:.4g}"
        d = "-" if r["demand"] is None else f"{r['demand']:.4g}"
        name = "-".join(r["joint"])
        own = "".join(f"{_own(fmt, r[key]):>{max(len(head), 8)}}  "
                      for key, head, fmt in law)
        out.append((f"{name:<24} {r['N']:12.5g} {r['T']:12.5g} {e:>10} {d:>8}  {own}"
                    f"{r['state']:<26} " + ((r["mode"] or "-") if modes else "")).rstrip())
    return out


def _own(fmt: str, value: float) -> str:
    """A joint's law in the table: "infinite" as in the scene file."""
    return INFINITE if math.isinf(value) else fmt.format(value)


__all__ = ["add_args", "run", "report", "InputError"]
