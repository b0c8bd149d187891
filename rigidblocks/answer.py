"""The answer to an analysis in plain words: written once, read in the CLI, the HTML
report and a picture's title.

An :class:`AnswerBlock` says what was asked (the dead load, the live load and what the
load factor lambda multiplies, in the scene's force unit; "self-weight only", or "dead
load only" where there are dead point loads, where lambda is 0), the verdict, the number
with its unit and the force it means, the governing joints (the first few, "and N
more") and the reasons an engineer acts on. The solver's and the accuracy's notes are
kept apart (``notes``): the CLI shows them under ``--verbose``, the JSON always.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from typing import Any

import numpy as np

from .results import (
    BELOW_DEAD_LOAD,
    BOUND_STANDS,
    DIRECT_STANDS,
    MODE_WORDS,
    STATIC_UNSTABLE,
    Result,
    angle_text,
    fmt_bracket,
    fmt_safe,
)
from .scene.geometry import scene_weights
from .scene.model import Scene, friction_value
from .solvers.policy import LP_ONLY

#: the statuses that are verdicts (any other is none: undecided, failure, ...)
VERDICTS = ("admissible", "inadmissible", "stable", "unstable", "collapse", "unbounded")
#: how many joints a list names before "and N more"
FIRST = 5
#: notes about the solver and the accuracy of a number (shown with --verbose); every
#: other note is a reason an engineer acts on
_SOLVER_NOTE = re.compile(
    r"solver|dual|relaxation|bracket|residual|certif|round-off|interior-point|"
    r"clarabel|highs|\bscs\b|ecos|osqp|cvxpy|slope|solved again|\bsolve[sd]?\b|"
    r"iteration|extreme point|\bLPs?\b|\bSOCPs?\b|mechanism: ", re.I)


#: the verdict of a non-associative check that fails
NA_INADMISSIBLE = ("NOT ADMISSIBLE: the state reached from the elastic state X0 does not "
                   "stand (sliding without dilatancy; another state may stand)")
#: ... where the state reached from X0 at the load stands but the limit fixed point
#: from X0 collapses below it (two "states reached from X0" were read as one)
NA_BELOW_LOAD = ("NOT ADMISSIBLE: loaded from X0 it collapses below this load (the limit "
                 "fixed point from X0, `load`'s answer; sliding without dilatancy)")
#: ... and where it stands: without dilatancy no static theorem makes an admissible
#: state a proof (the Arpino gate at f = 0.6: the distortion method's state reached from
#: X0 at lambda = 0.12 is admissible, while 0.1187021 is the smallest multiplier of any
#: state, `load --safe`)
#: the bounds line's words for the capacity bound (rigidblocks.analyses.na_capacity)
#: (it read "every collapse state at lambda >= 0" as if the bound were 0)
CAPACITY_LOWER = ("lower: capacity bound, no collapse state at lambda >= 0 lies below it "
                  "(Radenkovic's second theorem with each joint's least normal force)")
NO_SLIDING_LOWER = ("lower: associative, every collapse state (infinite friction: no joint "
                    "without dilatancy slides, and the flow rule plays no part)")
NA_BOUND_STANDS = ("ADMISSIBLE: no collapse state without dilatancy lies at or below this "
                   "load (a lower bound on every one carries it): it stands whatever state "
                   "it is in")
#: what an admissible state keeps every joint within, where no joint is bonded
#: (:func:`within_laws`)
PLAIN_LAWS = "every joint in compression and within friction"
NA_ADMISSIBLE = ("ADMISSIBLE: it stands in the state reached from the elastic state X0 "
                 f"({PLAIN_LAWS}; sliding without dilatancy: another state may collapse "
                 "at a lower load)")
NA_ADMISSIBLE_WHY = ("without dilatancy an admissible state is no proof of safety: the "
                     "smallest collapse multiplier over all states ({safe}) may lie below "
                     "this load factor")


def within_laws(contacts: Any) -> str:
    """What an admissible state keeps every joint within: :data:`PLAIN_LAWS`, or with
    bonded joints their tensile strength and cohesion too (examples/fig4a_bonded.json
    at 1.1: "every joint in compression" above a joint table whose bond carries 10 N
    of tension, all its strength)."""
    if contacts is None:
        return PLAIN_LAWS
    tension = bool((np.asarray(contacts.tensile_strength, dtype=float) > 0).any())
    cohesion = bool((np.asarray(contacts.cohesion, dtype=float) > 0).any())
    if not (tension or cohesion):
        return PLAIN_LAWS
    return ("every joint " + ("in compression or within its tensile strength," if tension
                              else "in compression")
            + (" and within friction and cohesion" if cohesion else " and within friction"))


def safe_command(res: Any, command: str) -> str:
    """``command`` (a `load --safe` command line, in backticks) where `--safe` computes
    the smallest collapse multiplier over all states on the result's scene, else what
    it takes (the 8 x 8 wall, 180 joints: `check` and `friction` pointed to `--safe`,
    which answered "not computed")."""
    from .analyses.na_capacity import MAX_JOINTS

    n = res.contacts.n_joints
    return command if n <= MAX_JOINTS else (
        f"`rigidblocks load --safe` computes it on scenes of up to {MAX_JOINTS} joints; "
        f"this one has {n}")


def without_dilatancy(result: Any) -> bool:
    """Was ``result`` analysed with joints that slide without dilatancy (its answer is
    the state reached from X0, not one over every state)?"""
    return getattr(result, "flow", "associative") != "associative"


_SOLVED_AGAIN = re.compile(r"answers of (\S+) that failed their check .*? solved again "
                           r"by (\w+)")


#: the longest closing aside of an answer's number that a picture's title keeps
TITLE_ASIDE = 60


@dataclass(frozen=True)
class AnswerBlock:
    """One answer, in words (see the module's docstring). ``decided`` is False for an
    undecided or failed analysis: then ``verdict`` says so and no number is given."""

    asked: str
    verdict: str
    number: str = ""
    governing: str = ""
    reasons: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()
    decided: bool = True
    #: the load case in a few words for a title ("under its self-weight only (load
    #: factor 0)")
    case: str = ""

    def lines(self, verbose: bool = False, width: int = 10) -> list[str]:
        """Labelled lines for a terminal (``verbose``: with the solver's notes)."""
        rows = [("asked", self.asked), ("verdict", self.verdict), ("answer", self.number),
                ("governing", self.governing)]
        rows += [("why", r) for r in self.reasons]
        if verbose:
            rows += [("note", n) for n in self.notes]
        return [f"{k:<{width}} {v}" for k, v in rows if v]

    def title(self) -> str:
        """A picture's title: the verdict, the number and the load case; the number
        without a closing explanation in parentheses longer than TITLE_ASIDE characters
        (a check's breach: the arch's title ran to six lines over its picture)."""
        number = self.number
        aside = re.search(r" \(([^()]*)\)$", number)
        if aside and len(aside.group(1)) > TITLE_ASIDE:
            number = number[:aside.start()]
        text = f"{self.verdict}: {number}" if number else self.verdict
        return f"{text}, {self.case}" if self.case else text


def answer_block(scene: Scene, result: Any, symbols: bool = False) -> AnswerBlock:
    """The answer of ``result`` (an analysis of ``scene``) in words; ``symbols``: write
    lambda and the degree sign as symbols (reports, pictures) rather than ASCII."""
    w = _Words(scene, symbols)
    a = getattr(result, "analysis", "")
    reasons, notes = split_notes(getattr(result, "notes", ()) or ())
    reasons += _other_back_ends(result) + _sheared_open(result)
    asked = w.asked(result)
    if getattr(result, "status", "") not in VERDICTS:
        return AnswerBlock(asked, *w.undecided(result), reasons=reasons + notes,
                           decided=False)
    build = {"check": w.check, "min_friction": w.friction,
             "max_load_multiplier": w.load}.get(a)
    if build is None:
        return AnswerBlock(asked, str(getattr(result, "status", "")).upper(),
                           reasons=reasons, notes=notes)
    verdict, number, governing, why = build(result)
    return AnswerBlock(asked, verdict, number, governing, tuple(why) + reasons, notes,
                       case=w.short_case(result))


#: words of the reasons that say why an analysis could not decide (beside those that
#: describe the analysis, which came first: a sweep's note read the non-associative
#: analysis's description, not that its fixed point failed its check)
UNDECIDED_WORDS = ("could not decide", "fails its check", "undecided", "is below",
                   "no fixed point", "requested (rtol)", "not settle", "gave no answer")


def undecided_why(scene: Scene, result: Any) -> str:
    """Why ``result``, an analysis of ``scene`` that could not decide, gives no number,
    in one line (a sweep's ``note``): its bracket and the reasons that say why (else
    its first)."""
    block = answer_block(scene, result)
    why = [r for r in block.reasons if any(w in r for w in UNDECIDED_WORDS)][:2] or \
        list(block.reasons[:1])
    return "; ".join(x for x in (block.number, *why) if x) or block.verdict


def _sheared_open(result: Any) -> tuple[str, ...]:
    """Where the result's state has open joints that carry shear (infinite friction lets
    them: a block touching a wall hung on it by 80 kN of shear, its joint read "open"),
    a why line naming them."""
    if getattr(result, "state", None) is None or getattr(result, "contacts", None) is None:
        return ()
    from .results import force_state_words

    words = force_state_words(result)
    names = ["-".join(result.joint_name(k)) for k, w in enumerate(words)
             if w == "open, carrying shear"]
    if not names:
        return ()
    return (f"{joint_list(names)} carr{'ies' if len(names) == 1 else 'y'} shear with no "
            "compression in this state: infinite friction (no sliding) lets an open joint "
            "carry shear, which no finite friction does; with a finite one (--friction) "
            "and without dilatancy (--flow non-associative) it may carry less",)


def _joints_own_friction(contacts: Any) -> np.ndarray | None:
    """Which joints have a friction of their own (a scene's joint override, finite or
    infinite; NaN where the analysis's f applies); None without joints."""
    if contacts is None or not contacts.n_joints:
        return None
    return ~np.isnan(np.asarray(contacts.override_friction, dtype=float))


def live_load_text(scene: Scene, symbols: bool = False) -> str:
    """What lambda multiplies, in words, with its size in the scene's force unit."""
    return _Words(scene, symbols).live_text()


def live_load_size(scene: Scene) -> tuple[float, str]:
    """The live load's size in the scene's force unit (its resultant, or where its
    point loads balance, the sum of their sizes): what lambda = 1 means; and its
    direction in words ("horizontal", "in all (balanced: no resultant)", ...)."""
    w = _Words(scene, False)
    return w.live_size, w.direction()


def live_load_measure(scene: Scene) -> tuple[float, str, str]:
    """What lambda = 1 means as a table's column gives it: the live load's size, its
    unit and its direction in words (:func:`live_load_size`); where the live load is
    couples alone, their summed size in force x length units, "of couples" (a path
    under a live couple read "1.6 x 0 kN = 0 kN")."""
    w = _Words(scene, False)
    if w.live_moment:
        return w.live_moment, w.mu, "of couples"
    return w.live_size, scene.force_unit or "force units", w.direction()


def live_load_doc(scene: Scene) -> dict[str, Any]:
    """What lambda = 1 is, as a `load --json` gives it: the size and direction the
    answer line reads (:func:`live_load_size`), the resultant force (its components: a
    pull along -x read "horizontal" as one along +x) and, where the live load is couples
    alone, their summed size (force x length; the size is then 0)."""
    w = _Words(scene, False)
    return {"size": w.live_size, "direction": w.direction(),
            "resultant": [float(c) for c in w.live],
            "moment": w.live_moment if w.live_moment else None}


def split_notes(notes: Any) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """(reasons, solver notes): a note on the solver or the accuracy of a number is for
    ``--verbose``; the others (weightless blocks, a block touching nothing, the
    non-associative answer's starting state, ...) are reasons."""
    reasons, solver = [], []
    for n in notes:
        (solver if _SOLVER_NOTE.search(str(n)) else reasons).append(str(n))
        again = _SOLVED_AGAIN.match(str(n))
        if again:  # the answer is not the chosen back end's: it is no cross-check
            reasons.append(f"some answers of {again[1]} failed their check and were "
                           f"solved again by {again[2]}: the result is not a "
                           f"cross-check of {again[2]} by {again[1]}")
    return tuple(reasons), tuple(solver)


def _other_back_ends(res: Any) -> tuple[str, ...]:
    """Where back ends other than the one chosen answered some solves without its
    answers failing a check (an LP-only back end hands quadratic and conic problems on:
    `check --solver highs` has its state of least complementary energy, the
    non-associative analyses their selection steps, solved by Clarabel), a reason that
    says so: the result is not that back end's alone."""
    solver = getattr(res, "solver", "")
    others = [n for n in getattr(res, "answered_by", ()) or () if n != solver]
    if not others or getattr(res, "rejected", ()) or solver not in LP_ONLY:
        return ()
    return (f"{solver} solves linear programs only: {' and '.join(others)} solved the "
            "other problems of this analysis (its quadratic or conic ones)",)


def _own_friction(res: Any, f: Any) -> str:
    """Whether the scene's friction ``f`` suffices without dilatancy, from the trial the
    search made at it (lambda(f) need not grow with f, so f* does not tell)."""
    t = next((t for t in res.history if isinstance(t, dict) and t.get("friction") == f),
             None)
    if t is None:  # not tried: below the static f*, where no state stands at all
        return ("NOT enough: below the static f* no equilibrium state stands" if
                res.lower is not None and f < res.lower else "not tried (without "
                "dilatancy f* does not tell whether it is enough)")
    if "load_factor" in t:  # a limit run: the multiplier the state from X0 carries
        lam, st = t["load_factor"], t["status"]
        if st in ("infeasible", "unbounded", "unstable"):
            ok = st == "unbounded"
            there = {"unbounded": "there no multiple of the live load makes it collapse",
                     "infeasible": ("there a step's shear caps, f N of the last state's normal "
                                    "forces, carry not even the dead load"),
                     "unstable": "there the state reached from X0 under the dead load "
                                 "alone breaches the joint laws"}[st]
        elif st != "converged" or lam is None:
            return "not decided (the limit iteration did not settle there)"
        elif "carries" not in t:  # the search read no side from it either
            return "not decided (the state the limit iteration reached there failed its check)"
        else:
            from .analyses.na_limit import carried_text

            ok, lf = bool(t.get("carries")), float(res.load_factor)
            there = (f"there the state reached from X0 carries lambda = "
                     f"{fmt_safe(lam, 7, False)} "
                     f"({carried_text(lam, lf, t['carry_tol']) if ok else f'< {lf:.10g}'})")
    elif t["status"] in ("admissible", "inadmissible"):
        ok = t["status"] == "admissible"
        there = ("there the state reached from X0 " +
                 ("stands" if ok else "breaches the joint laws"))
    else:
        return "not decided (the iteration did not settle there)"
    # below f*'s bracket, not within it (f* = 0.6 at the scene's f = 0.6 of a wall3d
    # was "enough ... although below f*")
    low = res.lower if res.lower is not None else res.friction_factor
    below = (" although below f*: without dilatancy the frictions that carry the load "
             "need not be one interval") if ok and f < low else ""
    return f"{'enough' if ok else 'NOT enough'}: {there}{below}"


def _figures(x: float, up: bool, rtol: float | None, digits: int = 6) -> str:
    """An answer to ``digits`` figures on the safe side (:func:`fmt_safe`), or to as
    many more as keep the rounding within the accuracy ``rtol`` asked of it: the
    reference model's lambda* = 1.1999998, asked to 1e-6, was printed 1.19999 (8e-6
    below); now 1.199999."""
    for d in range(digits, 16):
        shown = fmt_safe(x, d, up)
        if not rtol or not math.isfinite(x) or abs(float(shown) - x) <= rtol * abs(x):
            return shown
    return repr(x)


def _within(x: float, bracket: Any, digits: int = 6) -> str:
    """A non-associative f*, rounded up (as :func:`fmt_safe`) to ``digits`` figures, or
    to two more than its bracket's relative width resolves, up to 10: the answer stands
    at f* (the bracket's upper end), and a larger f need not carry more. The inclined
    corbel arch's f* = 0.7651297008 for its dead load, in a bracket 8.6e-8 wide, was
    printed 0.76513, where it collapses under its dead load alone (lambda = -1.2e-7),
    as at 0.76512971 (-3.3e-9); at 0.7651297008 it stands."""
    if bracket and math.isfinite(x) and x > 0:
        width = (float(bracket[1]) - float(bracket[0])) / x
        if width > 0:
            digits = min(10, max(digits, math.ceil(-math.log10(width)) + 2))
    return fmt_safe(x, digits, True)


def _governing_tail(res: Any) -> str:
    """What f*'s governing joints are: " (f* rests on their friction)" without a state
    (the certificate below f* names them; the line said "at their friction limit" of a
    state that `--joints` then showed below it), " (at their friction limit[, to f*'s
    accuracy])" where the state shown has each at it (the joint table's words,
    :func:`~rigidblocks.results.force_state_words`), else the range of their |T|/N in that
    state: f* rests on their friction (the certificate below it names them), while the
    state at f*, one of many, may leave some below it (the stocky arch's pier joints at
    0.29798 for f* = 0.298455, "closed" in the table beside "at their friction limit")."""
    from .results import force_state_words

    k = list(res.governing)
    if not k:
        return ""
    one = len(k) == 1
    if res.state is None:  # no state to show them in: what the certificate says
        return f" (f* rests on {'its' if one else 'their'} friction)"
    words = force_state_words(res)
    if all("at friction limit" in words[j] for j in k):
        return (" (at its friction limit" if one else " (at their friction limit") + \
            _to_accuracy(res, "f*") + ")"
    demand = np.asarray(res.state.demand, dtype=float)[k]
    lo, hi = float(demand.min()), float(demand.max())
    span = f"{lo:.6g}" if one or f"{lo:.6g}" == f"{hi:.6g}" else f"{lo:.6g} to {hi:.6g}"
    return (f" (f* rests on {'its' if one else 'their'} friction; the state shown at f*, "
            f"one of many, has |T|/N = {span} there)")


def _to_accuracy(res: Any, symbol: str) -> str:
    """How far a bisection's governing joints are from their friction limit: its state
    is at an end of the answer's bracket, not at the limit itself, and the joints are
    those within the bracket's width of it where that is wider than AT_THRESHOLD."""
    from .methods.distortion import AT_THRESHOLD

    wide = res.bracket and (res.accuracy or 0.0) > AT_THRESHOLD
    return f", to {symbol}'s accuracy" if wide else ""


def joint_list(names: list[str], first: int = FIRST) -> str:
    """``a-b, c-d, ... and N more`` (the first ``first``); a name that comes back (two
    blocks touching on several faces: a key in its groove) once, with how many faces."""
    count: dict[str, int] = {}
    for n in names:
        count[n] = count.get(n, 0) + 1
    names = [n if k == 1 else f"{n} ({k} faces)" for n, k in count.items()]
    if len(names) <= first:
        return ", ".join(names)
    return ", ".join(names[:first]) + f" and {len(names) - first} more"


def fmt(x: float, digits: int = 4) -> str:
    return f"{x:.{digits}g}"


def plain(x: float, digits: int = 4) -> str:
    """``x`` to ``digits`` significant figures without an exponent from 1e-3 to 1e6 (a
    force of 32000 N read "3.2e+04 N", where 32 kN read "32 kN")."""
    if x == 0 or not (1e-3 <= abs(x) < 1e6):
        return fmt(x, digits)
    return np.format_float_positional(x, precision=digits, unique=False, fractional=False,
                                      trim="-")


class _Words:
    """The phrases of one scene (its loads in its force unit)."""

    def __init__(self, scene: Scene, symbols: bool):
        self.scene = scene
        self.lam = "\N{GREEK SMALL LETTER LAMDA}" if symbols else "lambda"
        self.deg = "\N{DEGREE SIGN}" if symbols else " deg"
        self.x = "\N{MULTIPLICATION SIGN}" if symbols else "x"
        self.fu = scene.force_unit or "force units"
        w, _, _ = scene_weights(scene)
        free = ~scene.support_mask
        self.weight = float(w[free].sum())
        dim = scene.dimension
        live = np.zeros(dim)
        lbf = scene.live_body_force
        if lbf is not None:
            live += self.weight * np.asarray(lbf, dtype=float)[:dim]
        dead_pts = [ld for ld in scene.loads if not ld.is_live and ld.force is not None]
        live_pts = [np.asarray(ld.force, dtype=float)[:dim] for ld in scene.loads
                    if ld.is_live and ld.force is not None]
        for f in live_pts:
            live += f
        self.live = live
        #: the live load's size: its resultant, or where its point loads balance (two
        #: equal and opposite pulls) the sum of their sizes
        self.live_size = float(np.linalg.norm(live))
        self.live_balanced = False
        total = self.live_size + sum(float(np.linalg.norm(f)) for f in live_pts)
        if live_pts and self.live_size <= 1e-9 * total:
            self.live_size, self.live_balanced = total, True
        self.n_dead_points = len(dead_pts)
        self.dead_points = float(sum(np.linalg.norm(ld.force) for ld in dead_pts))
        #: the live couples' sizes summed (force x length), where the live load is
        #: couples alone (no force: its size above is 0)
        self.live_moment = 0.0
        if self.live_size == 0:
            self.live_moment = float(sum(np.linalg.norm(np.atleast_1d(ld.moment))
                                         for ld in scene.loads
                                         if ld.is_live and ld.moment is not None))
        lu = scene.length_unit
        self.mu = f"{scene.force_unit} {lu}" if scene.force_unit and lu else \
            "force x length units"

    # -- the loads --------------------------------------------------------------------
    def force(self, v: float) -> str:
        return f"{plain(v)} {self.fu}"

    def direction(self) -> str:
        """The live load's resultant direction in words."""
        v = self.live
        size = float(np.linalg.norm(v))
        if self.live_balanced:
            return "in all (balanced: no resultant)"
        if size == 0:
            return ""
        if abs(v[-1]) <= 1e-12 * size:
            return "horizontal"
        if float(np.linalg.norm(v[:-1])) <= 1e-12 * size:
            return "vertical, downwards" if v[-1] < 0 else "vertical, upwards"
        return "along (" + ", ".join(fmt(c / size, 3) for c in v) + ")"

    def dead(self) -> str:
        text = f"self-weight {self.force(self.weight)}" if self.weight else "no self-weight"
        if self.n_dead_points:
            # (sizes summed: "2 point loads of 8 kN" read as 8 kN each for 3 and 5 kN)
            text += (f", 1 point load of {self.force(self.dead_points)}"
                     if self.n_dead_points == 1 else
                     f", {self.n_dead_points} point loads, {self.force(self.dead_points)} in "
                     "all")
        return text

    def live_text(self) -> str:
        """What lambda multiplies: the live load and its resultant."""
        sc = self.scene
        parts = []
        lbf = sc.live_body_force
        if lbf is not None and any(v != 0 for v in lbf):
            vec = ", ".join(f"{v:g}" for v in lbf)
            parts.append(f"each free block's weight {self.x} ({vec})")
        n = sum(ld.is_live for ld in sc.loads)
        if self.live_moment:
            return (f"{n} live couple{'s' if n > 1 else ''}, no force: "
                    f"{fmt(self.live_moment)} {self.mu}")
        if n:
            parts.append(f"{n} live point load{'s' if n > 1 else ''}")
        if not parts:
            return "no live load"
        return " and ".join(parts) + f": {self.force(self.live_size)} {self.direction()}".rstrip()

    def load_case(self, lf: float | None) -> str:
        """Dead + lambda x live at the result's load factor, in words."""
        if not self.scene.has_live_load:
            return f"its dead load ({self.dead()}; there is no live load)"
        if not lf:
            return f"its {self.dead_word()} only ({self.dead()}; load factor 0: no live load)"
        text = (f"its dead load ({self.dead()}) plus {self.lam} = {lf:.10g} {self.x} the live "
                f"load ({self.live_text()})")
        if lf == 1:
            return text
        size = self.live_size * float(lf)
        return f"{text}, that is {self.force(size)} {self.direction()}".rstrip()

    def dead_word(self) -> str:
        """What the load factor 0 leaves: "self-weight" where the scene has no dead
        point load, else "dead load" (the point loads stay)."""
        return "dead load" if any(not ld.is_live for ld in self.scene.loads) else \
            "self-weight"

    def short_case(self, result: Any) -> str:
        """The load case of check and friction in a few words (load: none, lambda is
        its answer), and what the answer was asked at: the friction (not of `friction`,
        whose answer it is) and the flow rule without dilatancy (`load`'s picture of a
        keyed wall read "COLLAPSE: lambda* = 0.6" without it and 0.8 with normality,
        nothing in either title telling why)."""
        a = getattr(result, "analysis", "")
        if a not in ("check", "min_friction", "max_load_multiplier"):
            return ""
        parts = []
        if a != "max_load_multiplier" and self.scene.has_live_load:
            lf = getattr(result, "load_factor", None)
            parts.append(f"under the dead load + {lf:.10g} {self.x} the live load" if lf
                         else f"under its {self.dead_word()} only (load factor 0)")
        f = getattr(result, "friction", None)
        if a != "min_friction" and f is not None:
            v = friction_value(f)
            own = _joints_own_friction(getattr(result, "contacts", None))
            parts.append("at each joint's own friction" if own is not None and own.all()
                         else ("at infinite friction" if math.isinf(v) else f"at f = {v:.6g}")
                         + (" (some joints their own)" if own is not None and own.any()
                            else ""))
        if a != "check" and without_dilatancy(result):  # (check's verdicts say it)
            parts.append("sliding without dilatancy")
        return ", ".join(parts)

    def friction_text(self, f: Any) -> str:
        if f is None or isinstance(f, str) or math.isinf(float(f)):
            return "infinite friction (no sliding)"
        f = float(f)
        return f"friction f = {f:.10g} ({angle_text(f)}{self.deg})"

    def joint_friction_text(self, result: Any) -> str:
        """The friction the joints of ``result`` have: the uniform one, or where every
        joint has its own (a scene's joint overrides), that, with the uniform f that
        applies to none (`load --friction 5` on such a scene echoed "at friction f = 5"
        beside a multiplier that f had no part in); where some have their own, which (a
        keyed wall whose foundation joints have f = 0.8 slid there at lambda* = 0.8
        beside "at friction f = 0.6", with no word of theirs)."""
        f = getattr(result, "friction", None)
        c = getattr(result, "contacts", None)
        mask = _joints_own_friction(c)
        if mask is None:
            return self.friction_text(f)
        over = np.asarray(c.override_friction, dtype=float)
        own = np.flatnonzero(mask)
        if not len(own):
            return self.friction_text(f)
        names = [f"{'-'.join(result.joint_name(k))} "
                 + ("infinite" if math.isinf(over[k]) else f"f = {over[k]:g}")
                 for k in own]
        if len(own) < c.n_joints:
            n = len(set(names))
            return (f"{self.friction_text(f)}, {n} joint{'s' if n > 1 else ''} at a "
                    f"friction of {'their' if n > 1 else 'its'} own ({joint_list(names)})")
        v = friction_value(f) if f is not None else math.inf
        uniform = "infinite friction" if math.isinf(v) else f"f = {v:.10g}"
        # (their values too: the question named none of them)
        return f"each joint's own friction (every joint has an override: " \
               f"{joint_list(names)}; {uniform} applies to none)"

    def asked(self, result: Any) -> str:
        a = getattr(result, "analysis", "")
        lf = getattr(result, "load_factor", None)
        rule = ""
        if without_dilatancy(result):
            k = getattr(result, "sliding_joints", None)
            rule = ", sliding without dilatancy" if k is None else \
                f", {k} of {result.contacts.n_joints} joints sliding without dilatancy"
        elif self.scene.slides_dry:
            # (an associative answer of a scene that asks for none read as the scene's)
            rule = ", sliding with dilatancy (associative; not the scene's flow)"
        friction = self.joint_friction_text(result)
        if a == "check":
            return f"does it stand under {self.load_case(lf)}, at {friction}{rule}?"
        if a == "min_friction":
            return (f"the smallest friction f* at which it stands under "
                    f"{self.load_case(lf)}{rule}")
        if a == "max_load_multiplier":
            return (f"the largest multiple {self.lam}* of the live load "
                    f"({self.live_text()}) it carries on top of its dead load "
                    f"({self.dead()}), at {friction}{rule}")
        return a.replace("_", " ")

    # -- the answers ------------------------------------------------------------------
    def undecided(self, result: Any) -> tuple[str, str]:
        status = str(getattr(result, "status", "") or "unknown")
        solver = getattr(result, "solver", None)
        by = f"the {solver} method" if solver else "the analysis"
        word = status.upper() if status in Result.UNDECIDED else f"status {status}"
        verdict = f"NO VERDICT: {word} ({by} could not decide; no number is given)"
        br = getattr(result, "bracket", None)
        what = {"min_friction": "f*", "max_load_multiplier": f"{self.lam}*"}.get(
            getattr(result, "analysis", ""), "")
        number = f"{what} in {fmt_bracket(*br)}" if br is not None else ""
        return verdict, number

    def check(self, res: Any) -> tuple[str, str, str, list[str]]:
        why: list[str] = []
        na = without_dilatancy(res)
        if res.status == "admissible":
            # the joints that follow the friction asked (no friction or cohesion of their
            # own): the others are held to their own laws, not to f (a joint of its own
            # f = 0.25 and cohesion at |T|/N = 0.3 read "reaches the friction limit f =
            # 0.2")
            c = res.contacts
            plain = np.isnan(np.asarray(c.override_friction, dtype=float)) & \
                (np.asarray(c.cohesion, dtype=float) == 0)
            fd = res.demand(plain)
            state = ("the state reached from the elastic state X0" if na and "elastic"
                     in getattr(res.state, "method", "elastic")
                     else "the state of least complementary energy")
            among = "" if plain.all() else " among the joints without a law of their own"
            if fd is not None and fd[0] > 1e-9:
                a, b = res.joint_name(fd[1])
                f = friction_value(res.friction) if res.friction is not None else math.inf
                # a ratio above f within the verdict's tolerance (of the largest force:
                # |T|/N = 0.60008 at f = 0.6 on a joint carrying 6e-4 of it) is f
                reach = (f"the friction limit f = {f:.10g}" if fd[0] >= f * (1 - 1e-4)
                         else f"{fd[0]:.4g}")
                # not "needs": another admissible state may do with less (f*)
                # (`friction --flow non-associative` gives the state reached from X0's)
                # (the corbel dome read as on the edge of sliding beside its f* = 0)
                why.append(f"in {state} |T|/N reaches {reach}{among} (joint {a}-{b}): not a "
                           "margin against sliding, as other states may need less; the "
                           "least friction any state needs is f* (`rigidblocks friction`"
                           + (" without --flow)" if na else ")"))
            elif fd is not None:
                why.append(f"{state} uses no friction")
            if na and res.cause == BOUND_STANDS:
                return NA_BOUND_STANDS, "", "", why
            if na:
                return NA_ADMISSIBLE.replace(PLAIN_LAWS, within_laws(c)), "", "", [
                    *why, NA_ADMISSIBLE_WHY.format(
                    safe=safe_command(res, "`rigidblocks load --flow non-associative "
                                           "--safe`"))]
            return (f"ADMISSIBLE: it stands (an equilibrium state with {within_laws(c)} "
                    "exists)", "", "", why)
        number = ""
        if math.isfinite(res.violation):
            # the convex path's is the least over all states; the distortion
            # iteration's is that of the state it stopped at (0.0006584 kN on the arch at
            # load factor 0.1498, where the least is 0.0004825 kN)
            whose = "its" if na else ("the distortion iteration's"
                                      if getattr(res, "solver", "") == "distortion"
                                      else "smallest")
            # what it measures: a 20 kN block leaning beyond its base, under its weight
            # again sideways, "breached" by 70 kN read as a misprint (about its toe the
            # loads turn 35 kNm, held by 70 kN of tension at its heel 0.5 m away)
            # (each contact point's law, or in 2D each joint's shear, is relaxed by it: a
            # 3D box short of friction by 0.6 read 0.15, a quarter, beside its joint, a
            # 2D block lifted off its two points 10 beside its joint's 20)
            number = (f"{whose} breach of the joint laws {self.force(res.violation)} (the "
                      "most tension, or shear beyond friction, it asks of one contact; a "
                      "joint's, summed over its contact points, is named with it; 0 would "
                      "stand)")
        names = [f"{a}-{b} ({fmt(v, 3)} {self.fu})" for a, b, v in
                 ((*res.joint_name(k), v) for k, v in res.breaches)]
        why += self.live_hint(res)
        # without dilatancy only the state reached from X0 is judged: other states may
        # stand (the associative check, over every state, says whether one does), unless
        # the static problem has none at all (no trial was made: no state stands under
        # either flow rule)
        verdict = (NA_INADMISSIBLE if na and res.history else "NOT ADMISSIBLE: no "
                   f"equilibrium state keeps {within_laws(res.contacts)}")
        if na and res.cause == DIRECT_STANDS:
            # two "states reached from X0": the one at this load stands, the limit
            # fixed point from X0 (`load`'s answer) collapses below it
            verdict = NA_BELOW_LOAD
        return (verdict, number, ("breached at " + joint_list(names)) if names else "", why)

    def friction(self, res: Any) -> tuple[str, str, str, list[str]]:
        from .analyses.nonassociative import NA_FRICTION_CEILING

        static = not without_dilatancy(res) or res.cause == STATIC_UNSTABLE
        if res.status != "stable" and not static:
            # the search stops at a finite ceiling: infinite friction (no sliding at
            # all) is another joint law, which may stand (a running-bond wall with
            # openings, whose state from X0 has joints with no normal force)
            return (f"UNSTABLE: no friction tried up to {NA_FRICTION_CEILING:g} suffices "
                    "without dilatancy (in the state reached from the elastic state X0)",
                    "", "",
                    self.live_hint(res))
        if res.status != "stable":  # no state at any friction (either flow rule)
            own = np.flatnonzero(np.isfinite(np.asarray(res.contacts.override_friction,
                                                        dtype=float)))
            if len(own):
                # f* scales the other joints only: those keep their own friction
                names = ", ".join(f"{'-'.join(res.joint_name(k))} (f = "
                                  f"{float(res.contacts.override_friction[k]):g})"
                                  for k in own[:FIRST])
                more = f" and {len(own) - FIRST} more" if len(own) > FIRST else ""
                return ("UNSTABLE: no friction of the other joints suffices (even infinite "
                        "friction there admits no equilibrium state) while the joints "
                        f"with a friction of their own keep it: {names}{more}", "", "",
                        self.live_hint(res))
            return ("UNSTABLE: no friction suffices (even infinite friction admits no "
                    "equilibrium state)", "", "", self.live_hint(res))
        fs = float(res.friction_factor)
        na = without_dilatancy(res)
        shown = _within(fs, res.bracket) if na else _figures(fs, True, res.rtol)
        number = (f"f* = {shown} (friction angle "
                  f"{angle_text(shown, 4)}{self.deg})")
        why = []
        f = self.scene.effective_friction
        # a bond's net pull is capped by c a / f: more friction may carry less (a block
        # bonded without cohesion and pulled up stood at f* = 0, and at no f above it)
        bonded = not na and bool(np.any(np.asarray(res.contacts.tensile_strength) > 0))
        if not isinstance(f, str) and math.isfinite(float(f)):
            lo = res.lower if res.lower is not None else fs
            if na:
                enough = _own_friction(res, f)
            elif bonded and float(f) > fs:
                enough = "above f* (whether it carries the load: `rigidblocks check`)"
            elif lo < float(f) < fs:
                enough = (f"within f*'s bracket [{lo:.9g}, {fs:.9g}]: at the limit, not "
                          "decided at this accuracy")
            else:
                enough = "enough" if float(f) >= fs else "NOT enough"
            why.append(f"the scene's friction f = {float(f):.10g} is {enough}")
        if na:
            why.append("without dilatancy a larger f need not carry more, and another state "
                       "may need more: f* is where the state reached from X0 carries the "
                       "load, not a bound for every f above it nor for every state ("
                       + safe_command(res, "check a given f with `rigidblocks load "
                                           "--friction F --safe`") + ")")
        if bonded:
            why.append("with bonded joints a larger f need not carry more: the row |T| <= "
                       "f (N1 + N2) + c a caps a joint's net tension at c a / f (without "
                       "cohesion none for any f > 0, while at f = 0 it caps nothing): check "
                       "the friction the joints have with `rigidblocks check --friction F`")
        names = [f"{a}-{b}" for a, b in res.governing_joints]
        verdict = "STANDS at friction f = f*" if na or bonded else \
            "STANDS with friction f >= f*"
        return (verdict, number, joint_list(names) + _governing_tail(res), why)

    def load(self, res: Any) -> tuple[str, str, str, list[str]]:
        if res.status == "unbounded":
            return ("UNBOUNDED: no multiple of the live load makes it collapse", "", "", [])
        if res.status != "collapse":
            bounds = getattr(res, "load_multiplier_bounds", None)
            if without_dilatancy(res) and bounds is not None and bounds[1] is not None:
                # (the associative analysis has a state: the upper bound; without one,
                # no state stands under the dead load at all)
                what = ("loaded from X0 it collapses below the dead load alone, lambda* "
                        "< 0" if res.cause == BELOW_DEAD_LOAD else
                        "the state reached from X0 under the dead load alone breaches the "
                        "joint laws")
                return (f"UNSTABLE: {what} (without dilatancy; other states may stand: "
                        "`rigidblocks check` without --flow)", "", "", [])
            return ("UNSTABLE: the dead load alone has no admissible state", "", "", [])
        lm = float(res.load_multiplier)
        size = self.live_size
        shown = _figures(lm, False, res.rtol)
        if self.live_moment:
            number = (f"{self.lam}* = {shown}, that is {shown} {self.x} "
                      f"{fmt(self.live_moment)} {self.mu} = "
                      f"{fmt_safe(lm * self.live_moment, 4, False)} {self.mu} of couples")
        else:
            number = (f"{self.lam}* = {shown}, that is {shown} {self.x} {self.force(size)} = "
                      f"{plain(float(fmt_safe(lm * size, 4, False)))} {self.fu} "
                      f"{self.direction()}").rstrip()
        why = []
        if res.tilt_angle_deg is not None:
            a = float(np.linalg.norm(np.asarray(self.scene.live_body_force)[:-1]))
            # to 4 decimals, down as lambda* (a tilt at the printed angle stands)
            t = float(res.tilt_angle_deg)
            tilt = fmt_safe(t, max(1, math.floor(math.log10(t)) + 5), False) if t > 0 \
                else f"{t:g}"
            why.append(f"tilt angle atan({self.lam}* a) = {tilt}{self.deg}, "
                       f"a = {a:g} the horizontal body force per unit weight (in g): the "
                       "ground tilted by this angle loads it the same way")
        span = next((h.get("span") for h in (res.history or ())
                     if isinstance(h, dict) and h.get("span")), None)
        # (not below the lower bound: the mechanism's states below it lie at lambda < 0,
        # under a reversed live load, where no collapse state at lambda >= 0 lies)
        bounds = getattr(res, "load_multiplier_bounds", None)
        low = span[0] if span else None
        if low is not None and bounds is not None and bounds[0] is not None:
            low = max(low, bounds[0])
        if low is not None and low < lm - max(1e-6 * abs(lm), 1e-8):
            why.append(f"not a lower bound: collapse states of the same mechanism carry "
                       f"{self.lam} from {fmt_safe(low, 6, False)} (the answer is the "
                       "state reached from X0; "
                       + safe_command(res, "`--safe` gives the smallest over all states")
                       + ")")
        lf = self.scene.load_factor
        if lf:
            ok = "carries" if lm >= lf else "does NOT carry"
            why.append(f"it {ok} the scene's load factor {self.lam} = {lf:.10g}")
        mech = res.mechanism
        if mech is None:
            names = [f"{a}-{b}" for a, b in res.governing_joints]
            at = _to_accuracy(res, f"{self.lam}*")
            return ("COLLAPSE", number,
                    (f"joints at their friction limit{at}: " + joint_list(names)) if names
                    else "", why)
        body = bodies_text(res, self.scene)
        return "COLLAPSE", number, mechanism_text(res), ([body] if body else []) + why

    def live_hint(self, res: Any) -> list[str]:
        """Where the live loads at a nonzero load factor made the verdict, how to ask
        the two questions an engineer usually means."""
        if not (self.scene.has_live_load and res.load_factor):
            return []
        from .methods import NOTHING_HOLDS

        if any(NOTHING_HOLDS in n for n in (res.notes or ())):
            return []  # the verdict is the geometry's: a block that nothing holds
        src = self.scene.source or "SCENE"
        flow = " --flow non-associative" if without_dilatancy(res) else ""
        return [f"the live load is included at load factor {res.load_factor:.10g}; "
                f"--load-factor 0 asks for the {self.dead_word()} alone, `rigidblocks load {src}"
                f"{flow}` for the collapse multiplier"]


def mechanism_groups(res: Any) -> list[tuple[str, list[str]]]:
    """The moving joints of a result's mechanism by mode (hinging, sliding, sliding and
    hinging, opening; each joint in one group), fastest first: the one counting of the
    CLI, the report and the pictures."""
    m = res.mechanism
    order = m.ranking
    out = []
    for mode, word in MODE_WORDS:
        names = [f"{a}-{b}" for a, b in (res.joint_name(k) for k in order
                                          if m.modes[k] == mode)]
        if names:
            out.append((word, names))
    return out


def rigid_bodies(res: Any) -> list[list[int]]:
    """The free blocks that move, grouped into the rigid bodies they form: blocks joined
    by a joint that stays closed move together (largest body first)."""
    m = res.mechanism
    c = res.contacts
    vel = np.abs(np.asarray(m.velocities, dtype=float)).max(axis=1)
    top = float(vel.max(initial=0.0))
    n = len(vel)
    parent = list(range(n))

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for k, mode in enumerate(m.modes):
        if mode == "closed":
            a, b = (int(x) for x in c.pairs[k])
            parent[root(a)] = root(b)
    support = {root(i) for i in range(n) if vel[i] <= 1e-9 * top}  # at rest
    groups: dict[int, list[int]] = {}
    for i in range(n):
        if vel[i] > 1e-9 * top and root(i) not in support:
            groups.setdefault(root(i), []).append(i)
    return sorted(groups.values(), key=len, reverse=True)


def block_reach(scene: Scene, velocities: np.ndarray, centroids: np.ndarray | None = None
                ) -> np.ndarray:
    """(n,) each block's largest point speed in a mechanism (an upper bound): |u| +
    |omega| r, with u its centroid's velocity, omega its rotation rate and r the
    distance of its farthest vertex from its centroid."""
    vel = np.asarray(velocities, dtype=float)
    d = scene.dimension
    if centroids is None:
        centroids = scene_weights(scene)[1]
    out = np.zeros(len(scene.blocks))
    for i, (b, c, v) in enumerate(zip(scene.blocks, centroids, vel, strict=True)):
        r = np.linalg.norm(b.points - c, axis=1).max()
        out[i] = float(np.linalg.norm(v[:d]) + np.linalg.norm(v[d:]) * r)
    return out


def bodies_text(res: Any, scene: Scene | None = None) -> str:
    """How the moving blocks move, in words: as how many rigid bodies, and (given the
    ``scene``) which: the fastest blocks first, with "and N more"."""
    groups = rigid_bodies(res)
    if not groups:
        return ""
    n = sum(len(g) for g in groups)
    if len(groups) == 1:
        if n == 1:
            return "one block moves"
        return f"the {n} moving blocks move as one rigid body"
    speed = None if scene is None else block_reach(scene, res.mechanism.velocities)
    ids = res.contacts.block_ids

    def fastest(blocks: list[int]) -> list[str]:
        return [ids[i] for i in sorted(blocks, key=lambda i: -speed[i])]

    if len(groups) == n:
        text = f"the {n} moving blocks move each on its own (no two together)"
        if speed is None:
            return text
        return text + "; fastest: " + joint_list(fastest([g[0] for g in groups]))
    if speed is None:
        sizes = ", ".join(str(len(g)) for g in groups[:FIRST])
        more = f", and {len(groups) - FIRST} more" if len(groups) > FIRST else ""
        return (f"the {n} moving blocks form {len(groups)} rigid bodies (of {sizes} "
                f"blocks{more})")
    named = [joint_list(fastest(g), 2) for g in groups[:FIRST]]
    more = f"; and {len(groups) - FIRST} more bodies" if len(groups) > FIRST else ""
    return (f"the {n} moving blocks form {len(groups)} rigid bodies, each named by its "
            f"fastest blocks: " + "; ".join(named) + more)


def mechanism_text(res: Any) -> str:
    """The mechanism in words: each group with its joints where few joints move; where
    more than FIRST do, how many of each kind and the fastest FIRST (a distributed
    mechanism, a dome's, is read from its head)."""
    groups = mechanism_groups(res)
    m = res.mechanism
    kind = ("the blend of every optimal mechanism: " if m.kind == "blend" else "")
    if not groups:
        return kind + "no joint moves"
    order = m.ranking
    if len(order) <= FIRST:
        # a pair of blocks on several faces (a key in its groove) is one joint: "4
        # sliding (c2b2-c3b3 (4 faces))" counted its faces
        return kind + "; ".join(f"{len(set(n))} {w} ({joint_list(n, len(n))})"
                                for w, n in groups)
    word = dict(MODE_WORDS)
    # the fastest FIRST joints, a pair's faces of one mode once (a key in its groove)
    faces: dict[str, int] = {}
    shown = 0
    for k in order:
        a, b = res.joint_name(k)
        label = f"{a}-{b} ({word[m.modes[k]]})"
        if label not in faces and len(faces) == FIRST:
            break
        faces[label] = faces.get(label, 0) + 1
        shown += 1
    fastest = [lab if n == 1 else f"{lab[:-1]}, {n} faces)" for lab, n in faces.items()]
    pairs = len({res.joint_name(k) for k in order})
    moving = (f"{pairs} joints move" if pairs == len(order)
              else f"{pairs} joints move, on {len(order)} faces")
    return (kind + f"{moving}: "
            + ", ".join(f"{len(n)} {w}" for w, n in groups)
            + "; fastest: " + ", ".join(fastest)
            + (f" and {len(order) - shown} more" if len(order) > shown else "")
            + (" faces" if len(order) > shown and pairs < len(order) else ""))


def accuracy_text(res: Any) -> str | None:
    """The accuracy reached (the bracket's relative width) against the one requested
    (None where the result has none): a terminal's accuracy line, a report's note."""
    accuracy, rtol = getattr(res, "accuracy", None), getattr(res, "rtol", None)
    if accuracy is None or rtol is None:
        return None
    bracket = getattr(res, "bracket", None)
    if bracket is not None and getattr(res, "decided", False):
        where = f"bracket [{bracket[0]:.10g}, {bracket[1]:.10g}], "
    else:
        where = ""
    near_zero = ""
    if where and accuracy > rtol:  # decided by an absolute floor near 0
        # (the rule itself: "near 0" read as a claim about a multiplier of 0.0128)
        from .analyses.search import BRACKET_ATOL

        near_zero = (f"; decided by its width {bracket[1] - bracket[0]:.1e} <= "
                     f"{BRACKET_ATOL:g}, the absolute floor for answers within it of 0")
    return f"{accuracy:.1e} ({where}relative width; requested {rtol:g}{near_zero})"


def method_text(res: Any) -> str | None:
    """What the distortion method's answer is (None for the convex path's, the default):
    the seed's iteration, its procedure with the seed's joint law, a cross-check of the
    convex path with associative friction."""
    if getattr(res, "solver", None) != "distortion":
        return None
    what = ("the seed's procedure (joints that slide without dilatancy)"
            if without_dilatancy(res) else
            "with associative friction a cross-check of the default convex path "
            "(`--method clarabel`)")
    return ("distortion: the seed's iterative impressed-distortion solver (its Eq. 1-4), "
            f"from the elastic state X0; {what}")


def joint_friction_words(scene: Scene, result: Any) -> str:
    """The friction the joints of ``result`` have, as the answers' question says it
    (the uniform f, and the joints at a friction of their own): a load path's too."""
    return _Words(scene, False).joint_friction_text(result)


def flow_lines(res: Any) -> list[str]:
    """The non-associative analysis in labelled lines: its iterations ("flow"), its
    bounds and the answers from each start (a terminal's and a report's)."""
    from .analyses.nonassociative import start_entries, starts_text

    starts = start_entries(res.history)
    done = "converged" if res.converged else "not converged"
    if res.status == "collapse" and not res.converged:
        done += (" at one trial (the bracket it left meets the accuracy)"
                 if getattr(res, "bracket", None) else
                 " (the bounds meet: they give the answer)")
    if starts and starts[0].get("status") == "unstable" and not starts[0].get("iterations"):
        # no limit step from X0: the state it reaches breaches under the dead load (the
        # flat arch with vertical joints at f = 0.6 read "(0 + 8), converged" beside
        # the other start's infeasible run)
        done = "decided under the dead load, before any limit step from X0"
    if starts:  # the limit iteration: its steps, summed over the starts
        steps = " + ".join(str(h.get("iterations", "?")) for h in starts)
        each = f" ({steps})" if len(starts) > 1 else ""
        out = [f"flow       {res.flow}: {res.iterations} limit step(s) over "
               f"{len(starts)} start(s){each}, {done}"]
    elif len(res.history) == 1 and res.history[0].get("limit_steps") is not None:
        # a check at its load factor, then `load`'s limit run from X0
        # (the limit run's outcome too: "converged" alone stood beside its UNDECIDED)
        t = res.history[0]
        run = ", undecided" if t.get("limit_status") == "undecided" else ""
        out = [f"flow       {res.flow}: {t.get('iterations', '?')} iteration(s) at lambda "
               f"= {t['load_factor']:.10g}, {done}; then {t['limit_steps']} limit step(s) "
               f"loading from X0{run}"]
    elif res.iterations == 0 and res.converged and res.status == "admissible":
        # (it read "0 iteration(s), converged")
        out = [f"flow       {res.flow}: the elastic state X0 meets the joint laws as it is "
               "(no iteration needed)"]
    else:
        out = [f"flow       {res.flow}: {res.iterations} iteration(s), {done}"]
    b = getattr(res, "load_multiplier_bounds", None)
    if b is not None:
        # each bound on its own safe side: the lower one down, the upper one up (the
        # associative multiplier read 0.583757 here beside `load`'s 0.583756, as if two)
        lo = "-" if b[0] is None else fmt_safe(b[0], 6, False)
        hi = "-" if b[1] is None else fmt_safe(b[1], 6, True)
        what = ["rounded outward"] if b[0] is not None or b[1] is not None else []
        by = getattr(res, "lower_bound_by", None)
        what.append(CAPACITY_LOWER if by == "capacity" else NO_SLIDING_LOWER
                    if by == "no sliding" else
                    "lower: the joints without dilatancy frictionless" if b[0] is not None
                    else "lower, -: none with the joints without dilatancy frictionless")
        what.append("upper: associative" if b[1] is not None else
                    "upper, -: the associative analysis gives none")
        out.append(f"bounds     [{lo}, {hi}]   ({'; '.join(what)})")
    if starts:
        out.append("starts     " + starts_text(starts))
    return out


__all__ = ["NA_BELOW_LOAD", "NA_INADMISSIBLE", "AnswerBlock", "accuracy_text", "answer_block",
           "block_reach", "bodies_text", "flow_lines", "joint_list", "live_load_doc",
           "live_load_size", "live_load_text", "mechanism_groups", "mechanism_text",
           "method_text", "rigid_bodies", "split_notes",
           "undecided_why", "without_dilatancy"]
