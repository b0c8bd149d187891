"""f*, its bracket and the solves that found it, on every example and catalogue scene.

The acceptance figures of a change to the limit searches: ``min_friction`` (Clarabel,
no force state) on every scene of ``examples/`` (at its own load factor, and under its
dead load alone where it has a live load), on every scene of the catalogue
(:mod:`rigidblocks.generators.catalogue`, at its own load factor), and on the 106-block
running-bond wall (2D and extruded to 3D) at load factor 1. Run as

    python benchmarks/bench_searches.py OUT.json [--compare BEFORE.json] [--rtol R]

It writes status, f*, bracket and solves per case; with ``--compare`` it prints the
cases whose f* moved by more than 1e-7 relative or whose solves differ by more than one.
``--without RULE`` runs them with that rule of the f* searches left out (a stop, step
or amend rule of :mod:`rigidblocks.methods.friction_rules` or
:mod:`rigidblocks.methods.load_rules`, by name); ``--ablate`` runs every such rule left
out in turn and writes, per rule, the cases whose answer changed (status, or f* by more
than the requested accuracy), the solves and the CPU seconds against the full rule set:
what each rule earns. ``--without-rung RETRY`` and ``--ablate-rungs`` do the same for
the solver policy's retries (:data:`RETRIES`). ``--tests PATHS`` (with either ablation)
also runs those test files with each rule or retry left out, in a fresh interpreter
each, and records the tests that fail.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

import numpy as np

import rigidblocks as rb
from rigidblocks.generators import catalogue as cat
from rigidblocks.generators.walls import running_bond_wall
from rigidblocks.scene.extrude import extrude

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


#: ``--big``: the 1,009-block running-bond wall too, at load factors 1 and 0.5, where
#: the solver's resolution near f* steers the searches (3 to 4 s each)
BIG = False
#: ``--walls``: running-bond walls (courses, blocks per course, load factor, whether its
#: live load is made a dead load) run instead of the scenes above (the large walls, a
#: solve of minutes each)
WALLS: list[tuple[int, int, float, bool]] = []


def parse_walls(text: str) -> list[tuple[int, int, float, bool]]:
    """``COURSESxBLOCKS@LOADFACTOR[:dead],...`` (e.g. ``100x200@0.2,71x71@1:dead``):
    with ``:dead`` the wall's horizontal body force at that factor is a dead load, so
    that f* is sought on R(f), not on lambda*(f)."""
    out = []
    for item in filter(None, text.split(",")):
        shape, _, lf = item.partition("@")
        lf, _, dead = lf.partition(":")
        c, _, b = shape.partition("x")
        out.append((int(c), int(b), float(lf or 1.0), dead == "dead"))
    return out


def as_dead(scene: Any, load_factor: float) -> Any:
    """``scene`` with its live body force at ``load_factor`` made a dead load on every
    free block."""
    from rigidblocks.methods import open_method
    from rigidblocks.scene.model import Load
    system = open_method(scene).system
    v = np.asarray(scene.live_body_force, float)
    dead = tuple(Load(scene.blocks[b].id, tuple(float(system.weights[b] * load_factor) * v),
                      live=False) for b in system.free_blocks)
    return scene.with_changes(loads=scene.loads + dead, live_body_force=None)


def scenes() -> list[tuple[str, Any, float | None]]:
    """(name, scene, load factor or None for the scene's own)."""
    out: list[tuple[str, Any, float | None]] = []
    if WALLS:
        for c, b, lf, dead in WALLS:
            wall = running_bond_wall(c, b)
            name = f"wall{len(wall.blocks)}@{lf:g}"
            out.append((f"{name}:dead", as_dead(wall, lf), 0.0) if dead else (name, wall, lf))
        return out
    for p in sorted(EXAMPLES.glob("*.json")):
        s = rb.read_scene(p)
        out.append((p.stem, s, None))
        if s.has_live_load:
            out.append((f"{p.stem}@0", s, 0.0))
    seen = set()
    for case in cat.CASES.values():
        if case.name in seen:
            continue
        seen.add(case.name)
        lf = dict(case.options).get("load_factor")
        out.append((f"cat:{case.name}", case.scene(), lf))
    wall = running_bond_wall(10, 10)
    out += [("wall106", wall, 1.0), ("wall106-3d", extrude(wall), 1.0)]
    if BIG:
        big = running_bond_wall(32, 31)
        out += [("wall1009", big, 1.0), ("wall1009@0.5", big, 0.5)]
    return out


def run(name: str, scene: Any, lf: float | None, rtol: float | None = None
        ) -> dict[str, Any]:
    """One case: status, f*, bracket, solves and, under ``fired``, how often each rule
    of the f* searches answered (a stop rule ended the search, a step rule proposed the
    trial, an amend rule moved or refused it)."""
    without(LEFT_OUT)
    _trace_rungs()
    FIRED.clear()
    SOLVED.clear()
    try:
        r = rb.min_friction(scene, load_factor=lf, state=False, compare_dry=False, rtol=rtol)
    except Exception as exc:  # noqa: BLE001 - recorded as the case's outcome
        return {"name": name, "status": f"error: {type(exc).__name__}: {exc}",
                "fired": dict(FIRED), "rungs": dict(SOLVED)}
    return {"name": name, "status": r.status, "f": r.friction_factor,
            "lower": r.lower, "upper": r.upper, "n_solves": r.n_solves,
            "fired": dict(FIRED), "rungs": dict(SOLVED)}


def compare(now: list[dict], before: list[dict]) -> int:
    old = {c["name"]: c for c in before}
    bad = 0
    ds = []
    for c in now:
        o = old.get(c["name"])
        if o is None:
            continue
        moved = c["status"] != o["status"]
        if c.get("f") is not None and o.get("f") is not None:
            moved |= abs(c["f"] - o["f"]) > 1e-7 * max(abs(o["f"]), 1e-9)
        elif (c.get("f") is None) != (o.get("f") is None):
            moved = True
        dn = (c.get("n_solves") or 0) - (o.get("n_solves") or 0)
        ds.append(dn)
        if moved or abs(dn) > 1:
            bad += 1
            print(f"{c['name']}: {o.get('status')} {o.get('f')} [{o.get('lower')}, "
                  f"{o.get('upper')}] {o.get('n_solves')} solves -> {c.get('status')} "
                  f"{c.get('f')} [{c.get('lower')}, {c.get('upper')}] {c.get('n_solves')}")
    values, counts = np.unique(ds, return_counts=True)
    print(f"{len(ds)} cases; solves {sum(c.get('n_solves') or 0 for c in before)} before, "
          f"{sum(c.get('n_solves') or 0 for c in now)} after; differing by more than one "
          f"or moved: {bad}; solve differences (after - before: cases) "
          f"{dict(zip(values.tolist(), counts.tolist(), strict=True))}")
    return bad


def _rule_sets() -> list[tuple[Any, str]]:
    """(module, attribute) of every rule tuple the f* searches read at run time."""
    from rigidblocks.methods import friction_search, load_rules
    return [(friction_search, "STOPS"), (friction_search, "STEPS"),
            (friction_search, "AMENDS"),
            (load_rules, "STOPS"), (load_rules, "STEPS")]


def rule_names(only: list[str] | None = None) -> list[str]:
    """The rules that may be left out (not the accuracy stop or the midpoint, which
    every search needs to end and to converge), or those of them named in ``only``; a
    rule of the same name in both searches may also be named ``friction_rules.NAME`` or
    ``load_rules.NAME``, to leave it out of that search alone."""
    keep = {"narrow_enough", "midpoint", "midpoint_resolvable"}
    names = [f.__name__ for m, a in _rule_sets() for f in getattr(m, a)]
    shared = [n for n in dict.fromkeys(names) if names.count(n) > 1 and n not in keep]
    names = [n for n in dict.fromkeys(names) if n not in keep]
    names += [f"{m}.{n}" for n in shared for m in ("friction_rules", "load_rules")]
    if only:
        unknown = sorted(set(only) - set(names))
        if unknown:
            raise SystemExit(f"bench_searches: unknown rules {', '.join(unknown)} "
                             f"(choose from {', '.join(names)})")
        names = [n for n in names if n in only]
    return names


#: how often each rule answered in the current case (:func:`run`)
FIRED: dict[str, int] = {}
#: the rule left out (None: none)
LEFT_OUT: str | None = None


def _counted(rule: Any, amend: bool = False) -> Any:
    """``rule`` counting its answers in FIRED, under its own name."""
    import functools

    @functools.wraps(rule)
    def counted(*args: Any) -> Any:
        out = rule(*args)
        if (out != args[1]) if amend else (out is not None and out is not False):
            FIRED[rule.__name__] = FIRED.get(rule.__name__, 0) + 1
        return out
    return counted


#: the solves of the current case by the rung of the solver policy that made them, and
#: under "stalled" the answers taken at the next rung's tolerances (:func:`run`)
SOLVED: dict[str, int] = {}


def _trace_rungs() -> None:
    """``Runner._solve`` counting its solves in SOLVED by the rung its caller climbs
    (the ``rung`` of ``Runner._climb``, or of ``Runner.run`` for a rung solved alone)."""
    from rigidblocks.solvers import policy
    solve = policy.Runner._solve
    if getattr(solve, "traced", False):
        return

    def traced(runner: Any, problem: Any, solver: str, settings: dict,
               after: dict | None = None) -> Any:
        res = solve(runner, problem, solver, settings, after)
        caller = sys._getframe(1)
        rung = caller.f_locals.get("rung") or caller.f_back.f_locals.get("rung")
        key = rung.name if rung is not None else "other"
        SOLVED[key] = SOLVED.get(key, 0) + 1
        if res.next_met:
            SOLVED["stalled"] = SOLVED.get("stalled", 0) + 1
        return res

    traced.traced = True  # type: ignore[attr-defined]
    policy.Runner._solve = traced  # type: ignore[method-assign]


def without(name: str | None) -> None:
    """Leave the rule ``name`` (or the comma-separated rules) out of every rule set
    (None: restore them all), where the searches read them and where the tests'
    synthetic searches do (:mod:`rigidblocks.methods.friction_rules`); the rules kept
    count their answers."""
    global LEFT_OUT
    from rigidblocks.methods import friction_rules
    LEFT_OUT = name
    sets = _rule_sets() + [(friction_rules, a) for a in ("STOPS", "STEPS", "AMENDS")]
    out = (name or "").split(",")
    for m, a in sets:
        full = getattr(m, f"_FULL_{a}", None) or getattr(m, a)
        setattr(m, f"_FULL_{a}", full)
        search = "load_rules" if m.__name__.endswith("load_rules") else "friction_rules"
        setattr(m, a, tuple(_counted(f, a == "AMENDS") for f in full
                            if f.__name__ not in out and f"{search}.{f.__name__}" not in out))


#: the solver policy's retries that ``--without-rung`` / ``--ablate-rungs`` leave out
#: (:mod:`rigidblocks.solvers.policy`): the refined retry (REFINED), the retry without
#: VALUE_SETTINGS (WITHOUT_VALUE), the 1e-9 rungs (NEAR_TIGHT, NEAR_TIGHT_VALUE), the
#: defaults after tight rungs (DEFAULTS where a rung before it applies), the stall
#: stop (no rung given the next one's settings), FINER_SETTINGS for the max-load LP
#: (FINER_FIRST, never asked: load_search.FINER_WHEN infinite) and the confirming solve
#: (CONFIRMING: a verdict near its threshold is not solved again tighter)
RETRIES = ("refined", "without-value", "near-tight", "defaults-after-tight", "stall",
           "finer", "confirming")
#: the retries whose runs are those of the full set where none of these rungs solved
#: (a retry is never given as the next rung's settings; the confirming rung is a
#: ladder's first): ``--fired-only`` does not run them again
RETRY_RUNGS = {"refined": ("refined",), "without-value": ("without VALUE_SETTINGS",),
               "confirming": ("confirming",)}
_LADDERS: dict[int, tuple[Any, tuple, tuple | None]] = {}


def _kept(name: str, rungs: tuple) -> tuple:
    """``rungs`` without the retry ``name`` (see :data:`RETRIES`)."""
    from dataclasses import replace

    from rigidblocks.solvers import policy as p
    drop = {"refined": (p.REFINED,), "without-value": (p.WITHOUT_VALUE,),
            "near-tight": (p.NEAR_TIGHT, p.NEAR_TIGHT_VALUE), "finer": (p.FINER_FIRST,),
            "confirming": (p.CONFIRMING,)}.get(name, ())
    out = []
    for r in rungs:
        if any(r is d for d in drop):
            continue
        out.append(replace(r, stall=False) if name == "stall" else r)
    return tuple(out)


def without_rung(name: str | None) -> None:
    """Leave the retry ``name`` (:data:`RETRIES`) out of every ladder of the solver
    policy, in place, so that every module holding a ladder reads it so (None: restore
    them all)."""
    from rigidblocks.methods import load_search
    from rigidblocks.solvers import policy as p
    if name is not None and name not in RETRIES:
        raise SystemExit(f"bench_searches: unknown retry {name} (choose from "
                         f"{', '.join(RETRIES)})")
    for ladder in (v for v in vars(p).values() if isinstance(v, p.Ladder)):
        _LADDERS.setdefault(id(ladder), (ladder, ladder.rungs, ladder.again))
    _LADDERS.setdefault(0, (load_search, load_search.FINER_WHEN, None))
    for key, (ladder, rungs, again) in _LADDERS.items():
        if key == 0:
            ladder.FINER_WHEN = float("inf") if name == "finer" else rungs
            continue
        # the ladders are frozen: they are changed where every module holds them
        object.__setattr__(ladder, "rungs", _kept(name, rungs) if name else rungs)
        object.__setattr__(ladder, "again",
                           _kept(name, again) if name and again is not None else again)
    _STEPS.setdefault("steps", p._steps)
    p._steps = _without_defaults if name == "defaults-after-tight" else _STEPS["steps"]


_STEPS: dict[str, Any] = {}


def _without_defaults(rungs: tuple, at: Any) -> list:
    """The policy's steps of a climb without DEFAULTS where a rung before it applies to
    the climb's back end (those without tight settings keep it: it is their only
    rung)."""
    from rigidblocks.solvers import policy as p
    steps = _STEPS["steps"](rungs, at)
    names = [rung.name for rung, _, _ in steps if not rung.retry]
    if p.DEFAULTS.name in names[1:]:
        return _STEPS["steps"](tuple(r for r in rungs if r is not p.DEFAULTS), at)
    return steps


def sweep_cases(rtol: float | None) -> list[dict[str, Any]]:
    import time
    rows = []
    for name, scene, lf in scenes():
        t0 = time.process_time()
        rows.append({**run(name, scene, lf, rtol), "seconds": time.process_time() - t0})
    return rows


def tests_without(leave_out: str, name: str | None, paths: list[str]) -> dict[str, Any]:
    """The test files ``paths`` run (pytest, in a fresh interpreter, from the checkout)
    with ``leave_out`` ("without" or "without_rung") of ``name`` (None: nothing left
    out): the tests that fail and pytest's summary line."""
    import subprocess
    args = ["-q", "-rfE", "-p", "no:cacheprovider", *paths]
    code = (f"import sys; sys.path.insert(0, {str(Path(__file__).parent)!r}); "
            f"import bench_searches as b; b.{leave_out}({name!r}); import pytest; "
            f"sys.exit(pytest.main({args!r}))")
    done = subprocess.run([sys.executable, "-c", code], cwd=EXAMPLES.parent,
                          capture_output=True, text=True, check=False)
    lines = done.stdout.splitlines()
    failed = [ln.split(" ", 1)[1].split(" - ")[0] for ln in lines
              if ln.startswith(("FAILED ", "ERROR "))]
    return {"failed": failed, "summary": lines[-1] if lines else done.stderr[-500:]}


def trace_tests(paths: list[str], out: str) -> None:
    """The test files ``paths`` run (in this interpreter) with every rule counting its
    answers: OUT gets, per test, how often each rule of the f* searches answered."""
    import pytest

    per_test: dict[str, dict[str, int]] = {}

    class Tracer:
        @pytest.hookimpl(hookwrapper=True)
        def pytest_runtest_call(self, item: Any) -> Any:
            FIRED.clear()
            yield
            if FIRED:
                per_test[item.nodeid] = dict(FIRED)

    without(None)
    pytest.main(["-q", "-p", "no:cacheprovider", *paths], plugins=[Tracer()])
    Path(out).write_text(json.dumps(per_test, indent=1))


def ablate(rtol: float | None, out: str, names: list[str], leave_out: str = "without",
           tests: list[str] | None = None, fired_only: bool = False) -> None:
    """Every rule (``leave_out`` "without") or retry ("without_rung") of ``names`` left
    out in turn against the full set (see the module docstring), on the scenes and, with
    ``tests``, on those test files; the report keeps the cases' rows and the load
    average. With ``fired_only``, a rule that answered in no case of the full set is not
    run again (its runs are those of the full set: the rules are functions of the
    record, the solves deterministic) and is listed under ``never_fired``."""
    from common import load_average

    drop = globals()[leave_out]
    load0 = load_average()
    base = sweep_cases(rtol)
    tol = rtol or 2e-3
    report: dict[str, Any] = {
        "rtol": rtol, "left_out": leave_out, "tests": tests or [],
        "base": {"solves": sum(c.get("n_solves") or 0 for c in base),
                 "seconds": sum(c["seconds"] for c in base), "rows": base,
                 "load": [load0, load_average()]},
        "rules": {}}
    if tests:
        report["base"]["tests"] = tests_without(leave_out, None, tests)
    if fired_only:
        fired = {n for c in base for n in c.get("fired", {})} if leave_out == "without" \
            else {r for c in base for n in c.get("rungs", {}) for r, rungs in
                  RETRY_RUNGS.items() if n in rungs} | (set(RETRIES) - set(RETRY_RUNGS))
        report["never_fired"] = [n for n in names if n not in fired]
        names = [n for n in names if n in fired]
    Path(out).write_text(json.dumps(report, indent=1))
    for name in names:
        load0 = load_average()
        drop(name)
        rows = sweep_cases(rtol)
        drop(None)
        changed = []
        for b, c in zip(base, rows, strict=True):
            moved = b["status"] != c["status"]
            if b.get("f") is not None and c.get("f") is not None:
                moved |= abs(b["f"] - c["f"]) > tol * max(abs(b["f"]), 1e-9)
            if moved:
                changed.append(f"{c['name']}: {b['status']} {b.get('f')} -> {c['status']} "
                               f"{c.get('f')}")
        report["rules"][name] = {
            "solves": sum(c.get("n_solves") or 0 for c in rows),
            "seconds": sum(c["seconds"] for c in rows), "changed": changed,
            "rows": rows, "load": [load0, load_average()]}
        if tests:
            report["rules"][name]["tests"] = tests_without(leave_out, name, tests)
            report["rules"][name]["load"].append(load_average())
        print(name, json.dumps(report["rules"][name]), flush=True)
        Path(out).write_text(json.dumps(report, indent=1))


def ablation_table(report: dict[str, Any]) -> str:
    """The markdown table of an ``--ablate`` report: per rule, its search and kind, the
    case it serves (its docstring's first sentence) and what leaving it out costs."""
    from rigidblocks.methods import friction_search

    where: dict[str, list[tuple[str, str, str]]] = {}
    for m, a in _rule_sets():
        search = "R(f)" if m is friction_search else "lambda*(f)"
        for f in getattr(m, a):
            doc = " ".join((f.__doc__ or "").split())
            where.setdefault(f.__name__, []).append(
                (search, a.lower()[:-1], doc.split(". ")[0].rstrip(".")))
    for name in RETRIES:
        where[name] = [("solver policy", "retry", "")]
    base = report["base"]
    rows = []
    for name, r in report["rules"].items():
        ds, dt = r["solves"] - base["solves"], r["seconds"] - base["seconds"]
        answers = f"{len(r['changed'])} changed" if r["changed"] else "same"
        failed = ", ".join(t.split("::")[-1] for t in r.get("tests", {}).get("failed", []))
        for search, kind, case in where.get(name, []):
            rows.append(f"| `{name}` | {search} {kind} | {case} | {ds:+d} | {dt:+.2f} | "
                        f"{answers} | {failed or '-'} |")
    head = ("| rule | search, kind | the case it serves | solves without it | CPU s "
            "without it | answers without it | tests failing without it |\n"
            "|---|---|---|---|---|---|---|")
    return head + "\n" + "\n".join(rows)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--compare", default=None)
    ap.add_argument("--rtol", type=float, default=None,
                    help="the requested accuracy (default: the analysis's)")
    ap.add_argument("--without", default=None,
                    help="rules of the f* searches to leave out (comma-separated)")
    ap.add_argument("--ablate", action="store_true",
                    help="leave every rule out in turn; OUT gets what each one earns")
    ap.add_argument("--table", action="store_true",
                    help="print the markdown table of an --ablate report OUT")
    ap.add_argument("--big", action="store_true", help="the 1,009-block wall too")
    ap.add_argument("--walls", default="",
                    help="only these running-bond walls, COURSESxBLOCKS@LOADFACTOR,...")
    ap.add_argument("--rules", default="",
                    help="with --ablate or --ablate-rungs: only these rules or retries "
                         "(comma-separated names)")
    ap.add_argument("--without-rung", default=None,
                    help=f"a retry of the solver policy to leave out ({', '.join(RETRIES)})")
    ap.add_argument("--ablate-rungs", action="store_true",
                    help="leave every retry of the solver policy out in turn")
    ap.add_argument("--fired-only", action="store_true",
                    help="leave out only the rules that answered in the full set's runs "
                         "(with --ablate-rungs: the retries of RETRY_RUNGS only where "
                         "they solved)")
    ap.add_argument("--trace-tests", default="",
                    help="run these test files (comma-separated) and write to OUT how "
                         "often each rule answered in each test")
    ap.add_argument("--tests", default="",
                    help="with --ablate or --ablate-rungs: also run these test files "
                         "(comma-separated) with each one left out")
    a = ap.parse_args(argv)
    global BIG, WALLS
    BIG = a.big
    WALLS = parse_walls(a.walls)
    if a.table:
        print(ablation_table(json.loads(Path(a.out).read_text())))
        return 0
    if a.trace_tests:
        trace_tests(a.trace_tests.split(","), a.out)
        return 0
    only = [r for r in a.rules.split(",") if r]
    tests = [t for t in a.tests.split(",") if t]
    if a.ablate:
        ablate(a.rtol, a.out, rule_names(only), "without", tests, a.fired_only)
        return 0
    if a.ablate_rungs:
        unknown = sorted(set(only) - set(RETRIES))
        if unknown:
            raise SystemExit(f"bench_searches: unknown retries {', '.join(unknown)}")
        ablate(a.rtol, a.out, [r for r in RETRIES if not only or r in only],
               "without_rung", tests, a.fired_only)
        return 0
    if a.without:
        without(a.without)
    if a.without_rung:
        without_rung(a.without_rung)
    rows = []
    for name, scene, lf in scenes():
        rows.append(run(name, scene, lf, a.rtol))
        print(json.dumps(rows[-1]), flush=True)
    Path(a.out).write_text(json.dumps(rows, indent=1))
    if a.compare:
        return 1 if compare(rows, json.loads(Path(a.compare).read_text())) else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
