"""f*, its bracket and the solves that found it, on every example and catalogue scene.

The acceptance figures of a change to the limit searches: ``min_friction`` (Clarabel,
no force state) on every scene of ``examples/`` (at its own load factor, and under its
dead load alone where it has a live load), on every scene of the catalogue
(:mod:`rigidblocks.generators.catalogue`, at its own load factor), and on the 106-block
running-bond wall (2D and extruded to 3D) at load factor 1. Run as

    python benchmarks/bench_searches.py OUT.json [--compare BEFORE.json] [--rtol R]

It writes status, f*, bracket and solves per case; with ``--compare`` it prints the
cases whose f* moved by more than 1e-7 relative or whose solves differ by more than one.
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


def scenes() -> list[tuple[str, Any, float | None]]:
    """(name, scene, load factor or None for the scene's own)."""
    out: list[tuple[str, Any, float | None]] = []
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


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--compare", default=None)
    ap.add_argument("--rtol", type=float, default=None,
                    help="the requested accuracy (default: the analysis's)")
    a = ap.parse_args(argv)
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
