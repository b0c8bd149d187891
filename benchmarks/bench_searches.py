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
what each rule earns.
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
#: ``--walls``: running-bond walls (courses, blocks per course, load factor) run instead
#: of the scenes above (the large walls, a solve of minutes each)
WALLS: list[tuple[int, int, float]] = []


def parse_walls(text: str) -> list[tuple[int, int, float]]:
    """``COURSESxBLOCKS@LOADFACTOR,...`` (e.g. ``100x200@0.2,71x71@1``)."""
    out = []
    for item in filter(None, text.split(",")):
        shape, _, lf = item.partition("@")
        c, _, b = shape.partition("x")
        out.append((int(c), int(b), float(lf or 1.0)))
    return out


def scenes() -> list[tuple[str, Any, float | None]]:
    """(name, scene, load factor or None for the scene's own)."""
    out: list[tuple[str, Any, float | None]] = []
    if WALLS:
        for c, b, lf in WALLS:
            wall = running_bond_wall(c, b)
            out.append((f"wall{len(wall.blocks)}@{lf:g}", wall, lf))
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
    try:
        r = rb.min_friction(scene, load_factor=lf, state=False, rtol=rtol)
    except Exception as exc:  # noqa: BLE001 - recorded as the case's outcome
        return {"name": name, "status": f"error: {type(exc).__name__}: {exc}"}
    return {"name": name, "status": r.status, "f": r.friction_factor,
            "lower": r.lower, "upper": r.upper, "n_solves": r.n_solves}


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
            (load_rules, "STOPS"), (load_rules, "STEPS"), (load_rules, "AMENDS")]


def rule_names(only: list[str] | None = None) -> list[str]:
    """The rules that may be left out (not the accuracy stop or the midpoint, which
    every search needs to end and to converge), or those of them named in ``only``."""
    keep = {"narrow_enough", "midpoint", "midpoint_resolvable"}
    names = [f.__name__ for m, a in _rule_sets() for f in getattr(m, a)]
    names = [n for n in dict.fromkeys(names) if n not in keep]
    if only:
        unknown = sorted(set(only) - set(names))
        if unknown:
            raise SystemExit(f"bench_searches: unknown rules {', '.join(unknown)} "
                             f"(choose from {', '.join(names)})")
        names = [n for n in names if n in only]
    return names


def without(name: str | None) -> None:
    """Leave the rule ``name`` out of every rule set (None: restore them all)."""
    for m, a in _rule_sets():
        full = getattr(m, f"_FULL_{a}", None) or getattr(m, a)
        setattr(m, f"_FULL_{a}", full)
        setattr(m, a, tuple(f for f in full if f.__name__ != name))


def sweep_cases(rtol: float | None) -> list[dict[str, Any]]:
    import time
    rows = []
    for name, scene, lf in scenes():
        t0 = time.process_time()
        rows.append({**run(name, scene, lf, rtol), "seconds": time.process_time() - t0})
    return rows


def ablate(rtol: float | None, out: str, only: list[str] | None = None) -> None:
    """Every rule (or those named in ``only``) left out in turn against the full set
    (see the module docstring); the report keeps the cases' rows and the load average."""
    from common import load_average

    names = rule_names(only)
    load0 = load_average()
    base = sweep_cases(rtol)
    tol = rtol or 2e-3
    report = {"rtol": rtol, "base": {"solves": sum(c.get("n_solves") or 0 for c in base),
                                     "seconds": sum(c["seconds"] for c in base),
                                     "rows": base, "load": [load0, load_average()]},
              "rules": {}}
    for name in names:
        load0 = load_average()
        without(name)
        rows = sweep_cases(rtol)
        without(None)
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
    base = report["base"]
    rows = []
    for name, r in report["rules"].items():
        ds, dt = r["solves"] - base["solves"], r["seconds"] - base["seconds"]
        answers = f"{len(r['changed'])} changed" if r["changed"] else "same"
        for search, kind, case in where.get(name, []):
            rows.append(f"| `{name}` | {search} {kind} | {case} | {ds:+d} | {dt:+.2f} | "
                        f"{answers} |")
    head = ("| rule | search, kind | the case it serves | solves without it | CPU s "
            "without it | answers without it |\n|---|---|---|---|---|---|")
    return head + "\n" + "\n".join(rows)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--compare", default=None)
    ap.add_argument("--rtol", type=float, default=None,
                    help="the requested accuracy (default: the analysis's)")
    ap.add_argument("--without", default=None, help="a rule of the f* searches to leave out")
    ap.add_argument("--ablate", action="store_true",
                    help="leave every rule out in turn; OUT gets what each one earns")
    ap.add_argument("--table", action="store_true",
                    help="print the markdown table of an --ablate report OUT")
    ap.add_argument("--big", action="store_true", help="the 1,009-block wall too")
    ap.add_argument("--walls", default="",
                    help="only these running-bond walls, COURSESxBLOCKS@LOADFACTOR,...")
    ap.add_argument("--rules", default="",
                    help="with --ablate: only these rules (comma-separated names)")
    a = ap.parse_args(argv)
    global BIG, WALLS
    BIG = a.big
    WALLS = parse_walls(a.walls)
    if a.table:
        print(ablation_table(json.loads(Path(a.out).read_text())))
        return 0
    if a.ablate:
        ablate(a.rtol, a.out, [r for r in a.rules.split(",") if r])
        return 0
    if a.without:
        without(a.without)
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
