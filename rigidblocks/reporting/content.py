"""What a report says, as plain data: the scene's summary, the question, the answer and
the per-joint table. No HTML here (see :mod:`rigidblocks.reporting.html`), so that every
sentence can be tested without a browser.

Results are read defensively (``getattr`` with a default) so that fields added to the
result objects later (a ``bracket``, an ``admissible`` that may be None, timings) are
shown when present and never needed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..answer import (
    MODE_WORDS,
    accuracy_text,
    answer_block,
    flow_lines,
    live_load_text,
    method_text,
    without_dilatancy,
)
from ..plotting.marks import scene_weights
from ..results import DIRECT_STANDS, angle_text, force_state_words
from ..scene.model import Scene

#: statuses that answer the question, and how the answer reads (tone of the badge)
VERDICT_TONES = {
    "admissible": "ok", "stable": "ok", "unbounded": "ok",
    "inadmissible": "bad", "unstable": "bad", "collapse": "warn",
}
QUESTIONS = {
    "check": "Does it stand?",
    "min_friction": "What friction does it need?",
    "max_load_multiplier": "How much live load does it take, and how does it fail?",
}


@dataclass(frozen=True)
class Answer:
    """The answer to the question: ``verdict`` False means the analysis did not decide
    (an undecided or failed solve), and nothing in the headline may read as a verdict."""

    status: str
    verdict: bool
    tone: str
    headline: str
    details: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()


@dataclass(frozen=True)
class Summary:
    """The scene at a glance: (label, value) rows."""

    title: str
    rows: tuple[tuple[str, str], ...]
    loads: tuple[str, ...] = field(default=())


def fmt(x: Any, digits: int = 4) -> str:
    """A number for people: 4 significant digits, infinity as the sign, None as '-'."""
    if x is None:
        return "-"
    if isinstance(x, str):
        return "\N{INFINITY}" if x == "infinite" else x
    x = float(x)
    if math.isnan(x):
        return "-"
    if math.isinf(x):
        return "\N{INFINITY}" if x > 0 else "-\N{INFINITY}"
    return f"{x:.{digits}g}"


def fmt_friction(f: Any) -> str:
    if f is None:
        return "-"
    if isinstance(f, str) or math.isinf(float(f)):
        return "\N{INFINITY} (no sliding)"
    return f"{float(f):.4g} (friction angle {angle_text(f)}\N{DEGREE SIGN})"


def _vec(v: Any) -> str:
    return "(" + ", ".join(fmt(c) for c in v) + ")"


def summary(scene: Scene, result: Any = None) -> Summary:
    """The scene's summary: size, units, weights, joint laws and loads."""
    lu = scene.length_unit or "(no unit given)"
    fu = scene.force_unit or "(no unit given)"
    n = len(scene.blocks)
    ns = int(scene.support_mask.sum())
    w, _, _ = scene_weights(scene)
    pts = np.concatenate([b.points for b in scene.blocks])
    ext = pts.max(axis=0) - pts.min(axis=0)
    rows = [("dimension", f"{scene.dimension}D"),
            ("blocks", f"{n} ({n - ns} free, {ns} support{'s' if ns != 1 else ''})")]
    contacts = getattr(result, "contacts", None)
    if contacts is not None:
        rows.append(("joints", str(contacts.n_joints)))
    rows += [("units", f"length {lu}, force {fu}"),
             ("extent", " \N{MULTIPLICATION SIGN} ".join(fmt(e) for e in ext)
              + (f" {scene.length_unit}" if scene.length_unit else ""))]
    if scene.dimension == 2:
        rows.append(("depth (out of plane)", fmt(scene.effective_depth)))
    uw_unit = (f" {scene.force_unit}/{scene.length_unit}\N{SUPERSCRIPT THREE}"
               if scene.force_unit and scene.length_unit else "")
    rows.append(("unit weight", fmt(scene.effective_unit_weight) + uw_unit
                 + ("" if scene.unit_weight is not None else " (not given: 0)")))
    total = float(w[~scene.support_mask].sum())
    rows.append(("weight of the free blocks", f"{fmt(total)} {scene.force_unit}".strip()))
    if total == 0:
        rows.append(("warning", "the free blocks weigh nothing: every answer comes from "
                     "the point loads alone"))
    rows.append(("friction (scene)", fmt_friction(scene.effective_friction)))
    if scene.joints:
        rows.append(("joint overrides", str(len(scene.joints))))
    rows.append(("live load (what \N{GREEK SMALL LETTER LAMDA} multiplies)",
                 live_load_text(scene, symbols=True)))
    loads = []
    for ld in scene.loads:
        at = "its centroid" if ld.point is None else _vec(ld.point)
        kind = "live" if ld.is_live else "dead"
        loads.append(f"{kind}: {_vec(ld.force)} {scene.force_unit} on block {ld.block} at {at}"
                     .replace("  ", " "))
    return Summary(scene.name or scene.source or "scene", tuple(rows), tuple(loads))


def question(scene: Scene, result: Any) -> str:
    """The question the analysis asked, with its parameters (the CLI's "asked")."""
    if result is None:
        return "No analysis: the scene only."
    text = answer_block(scene, result, symbols=True).asked
    return text[:1].upper() + text[1:] + ("" if text.endswith("?") else ".")


def answer(scene: Scene, result: Any) -> Answer:
    """The answer (:func:`rigidblocks.answer.answer_block`, as the CLI prints it): a
    verdict only for a status that is one (see VERDICT_TONES); ``notes`` are the
    solver's and the accuracy's, with the work done."""
    status = str(getattr(result, "status", "") or "")
    block = answer_block(scene, result, symbols=True)
    tone = VERDICT_TONES.get(status)
    if tone is None:
        return Answer(status or "unknown", False, "none", block.title(),
                      block.reasons + block.notes)
    details = [f"governing joints: {block.governing}"] if block.governing else []
    method = method_text(result)
    details += [f"method: {method}"] if method else []
    details += block.reasons
    if without_dilatancy(result):  # its iterations and bounds, as the terminal's lines
        # (the answers from each start are among the reasons already)
        details += [f"{ln[:10].strip()}: {ln[11:].strip()}" for ln in flow_lines(result)
                    if not ln.startswith("starts")]
    notes = list(block.notes)
    accuracy = accuracy_text(result)
    notes += [f"accuracy {accuracy}"] if accuracy else []
    solver = getattr(result, "solver", None)
    if solver:
        t = getattr(result, "solve_time", None)
        names = getattr(result, "solvers", None) or solver
        notes.append(f"solver {names}, {getattr(result, 'n_solves', '?')} solve(s)"
                     + (f", {float(t):.3g} s" if t is not None else ""))
    timings = getattr(result, "timings", None) or getattr(result, "stage_times", None)
    if isinstance(timings, dict) and timings:
        notes.append("stages: " + ", ".join(f"{k} {float(v):.3g} s"
                                            for k, v in timings.items()))
    return Answer(status, True, tone, block.title(), tuple(details), tuple(notes))


def forces_shown(result: Any) -> str | None:
    """What the force state drawn and tabled is, beside the verdict (None without one):
    the collapse state at lambda* of `load` and the state at f* of `friction` are states
    at a limit, and the state reached from X0 beside a NOT ADMISSIBLE that comes from
    the limit fixed point is one that stands (a collapse state read "one admissible
    state")."""
    st = getattr(result, "state", None)
    if st is None:
        return None
    how = getattr(st, "method", "")
    analysis = getattr(result, "analysis", "")
    if analysis == "max_load_multiplier" and getattr(result, "status", "") == "collapse":
        # the picture draws the mechanism then: the forces are the table's
        where = "Forces shown" if getattr(result, "mechanism", None) is None else \
            "Forces in the joint table (the picture draws the collapse mechanism)"
        return (f"{where}: one state at the collapse load \u03bb* ({how}); the "
                "states at collapse are not unique" + (
                    ", nor, without dilatancy, the multiplier." if without_dilatancy(result)
                    else ", the multiplier is."))
    if analysis == "min_friction" and getattr(result, "status", "") == "stable":
        return (f"Forces shown: one admissible state at f* ({how}); the states at f* are "
                "not unique.")
    if getattr(result, "status", "") == "inadmissible":
        if getattr(result, "cause", "") == DIRECT_STANDS:
            return (f"Forces shown: the state reached from X0 at this load ({how}), which "
                    "stands; the verdict is that of the limit fixed point from X0, which "
                    "collapses below the load.")
        return f"Forces shown: the state of least violation ({how}), NOT admissible."
    return (f"Forces shown: one admissible state ({how}); statically admissible states "
            "are not unique.")


def joint_states(result: Any) -> list[str]:
    """Each joint's state: from the mechanism after a collapse (closed, hinge, open,
    slide, slide+hinge), otherwise from the force state
    (:func:`~rigidblocks.results.force_state_words`: open, hinging, at friction limit,
    closed)."""
    mech = getattr(result, "mechanism", None)
    if mech is not None and len(mech.modes) == result.contacts.n_joints:
        return list(mech.modes)
    return force_state_words(result)


def joint_table(result: Any) -> dict[str, Any]:
    """Per-joint rows (joint, N, T, e, |T|/N, state, governing: the joints of the
    result's ``governing``, and after a collapse those its mechanism moves; the joints'
    friction, cohesion and tensile strength where they differ) as columns
    of lists, ready for JSON: the rows of the result's own table
    (:meth:`~rigidblocks.results.Result.joint_table`). 3D: T is the shear's magnitude
    and e the distance of the centre of pressure from the contact polygon's
    centroid."""
    c = getattr(result, "contacts", None)
    if c is None or not c.n_joints:
        return {"n": 0}
    ids = c.block_ids
    names = [f"{ids[a]}\N{EN DASH}{ids[b]}" for a, b in c.pairs]
    gov = set(int(k) for k in (getattr(result, "governing", ()) or ()))
    mech = getattr(result, "mechanism", None)
    if mech is not None and len(mech.modes) == c.n_joints:
        # a collapse is governed by the joints its mechanism moves (the answer's
        # "governing" line): hinges too, not only the joints at their friction limit
        moving = {mode for mode, _ in MODE_WORDS}
        gov |= {k for k, mode in enumerate(mech.modes) if mode in moving}
    rows = result.joint_table()
    states = joint_states(result)
    label = ("in the mechanism" if mech is not None and len(mech.modes) == c.n_joints
             else "state")  # after a collapse the column holds the mechanism's modes
    breaches = tuple(getattr(result, "breaches", ()) or ())
    if breaches and not rows:
        # a NOT ADMISSIBLE check: the joints its answer names as breached, as its
        # picture marks them (the table read "-" for every joint, none highlighted)
        unit = (getattr(result, "units", ("", "")) or ("", ""))[1]
        for k, v in breaches:
            states[int(k)] = f"breached by {v:.3g} {unit}".rstrip()
        gov |= {int(k) for k, _ in breaches}
        label = ("in the state reached from X0" if without_dilatancy(result)
                 else "in the state of least breach")
    out: dict[str, Any] = {"n": c.n_joints, "joint": names, "state": states,
                           "state_label": label,
                           "governing": [k in gov for k in range(c.n_joints)],
                           "has_forces": bool(rows)}
    if not rows:
        return out

    def col(key: str) -> list[float | str | None]:
        vals = [r[key] for r in rows]
        return [None if x is None or math.isnan(x) else
                ("inf" if math.isinf(x) else float(f"{x:.6g}")) for x in vals]

    # the joints' own laws, where they are not all the same (the terminal's table too)
    out.update({key: col(key) for key in ("friction", "cohesion", "tensile_strength")
                if len({r[key] for r in rows}) > 1})
    out.update({"N": col("N"), "T": col("T"), "e": col("eccentricity"),
                "demand": col("demand"),
                "half_length": [float(f"{x:.6g}") for x in
                                (0.5 * np.asarray(c.lengths, dtype=float)).tolist()]})
    return out


__all__ = ["Answer", "Summary", "answer", "fmt", "joint_states", "joint_table",
           "live_load_text", "question", "summary"]
