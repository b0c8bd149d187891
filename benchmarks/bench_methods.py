"""The two methods compared on the bundled example scenes: agreement, cost, solves.

For each 2D scene of ``examples/`` (and, unless ``--tiny``, the generated 106-block
running-bond wall) the minimum friction f* is computed

* by the convex path with Clarabel (default), HiGHS and SCS through the same builder
  (``min_friction(..., solver=...)``): the Newton strategy on the relaxation R(f);
* by plain bisection over ``check()`` verdicts (Clarabel) to the same 1e-6 relative,
  to count the solves the Newton strategy saves;
* by the impressed-distortion solver (``method="distortion"``): bisection over its
  verdicts, with its iteration count.

Scenes that are not stable at load factor 1 (the arches carry a live load they cannot
take) are analysed under their dead load alone (load factor 0). Run as

    python benchmarks/bench_methods.py [--tiny] [--out DIR]

and it writes ``bench_methods.json`` and ``bench_methods.md`` (see benchmarks/common.py).
"""

from __future__ import annotations

import argparse
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import load_average, markdown_table, write_results  # noqa: E402

import rigidblocks as rb  # noqa: E402
from rigidblocks.analyses.search import friction_by_bisection  # noqa: E402
from rigidblocks.io import read_scene  # noqa: E402
from rigidblocks.methods import open_method  # noqa: E402
from rigidblocks.scene.model import Scene  # noqa: E402

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
#: the scenes of the ``--tiny`` run
TINY = ("reference.json", "reference_self_weight.json")
#: relative accuracy of f* asked of every method
RTOL = 1e-6
#: ... the distortion method's (its bisection stops at an undecided verdict short of RTOL)
DISTORTION_RTOL = 1e-5


def scenes(tiny: bool) -> list[tuple[str, Scene]]:
    """(name, scene) of the 2D example files (the tiny set only with ``tiny``)."""
    out = []
    for path in sorted(EXAMPLES.glob("*.json")):
        if tiny and path.name not in TINY:
            continue
        try:
            scene = read_scene(path)
        except rb.InputError:
            continue  # not a scene file (e.g. a sweep description)
        if scene.dimension == 2:
            out.append((path.stem, scene))
    if not tiny:
        from rigidblocks.generators import build

        out.append(("wall (generated, 106 blocks)", build("wall")))
    return out


def bisection(scene: Scene, load_factor: float, rtol: float = RTOL) -> tuple[float | None, int]:
    """f* by plain bisection over Clarabel's verdicts (the analyses' own search for
    methods without a fast path, on the convex method): (f*, number of solves).

    f = infinite must be admissible; f = 0 is tried, then f = 1, 2, 4, ... brackets
    f*, then the bracket is halved until hi - lo <= rtol hi.
    """
    m = open_method(scene)
    lim = friction_by_bisection(m, load_factor, rtol)
    return (lim.value if lim.status == "stable" else None), m.n_solves


def timed_min_friction(scene: Scene, load_factor: float, **kw: Any) -> dict[str, Any]:
    """min_friction with its wall-clock time, status, f*, solves and iterations: f*
    alone on every method (no state; no answer without dilatancy beside the convex
    path's, which `friction` adds on scenes of up to 50 joints and the distortion
    method does not)."""
    t0 = time.perf_counter()
    try:
        r = rb.min_friction(scene, load_factor=load_factor, state=False,
                            rtol=kw.pop("rtol", RTOL), compare_dry=False, **kw)
    except rb.SolverFailure as err:
        return {"status": "failure", "fstar": None, "seconds": time.perf_counter() - t0,
                "solves": None, "iterations": None, "notes": [str(err)]}
    return {"status": r.status, "fstar": r.friction_factor,
            "seconds": time.perf_counter() - t0, "solves": r.n_solves,
            "iterations": r.iterations, "notes": list(r.notes),
            # (None: not computed, as the other methods do not compute it)
            "without_dilatancy": r.without_dilatancy}


def bench_scene(name: str, scene: Scene) -> dict[str, Any]:
    """All methods on one scene."""
    lf = 1.0
    clar = timed_min_friction(scene, lf)
    if clar["status"] != "stable":
        lf = 0.0
        clar = timed_min_friction(scene, lf)
    row: dict[str, Any] = {"scene": name, "blocks": len(scene.blocks), "load_factor": lf,
                           "clarabel": clar, "load_average": load_average()}
    for solver in ("highs", "scs"):
        row[solver] = timed_min_friction(scene, lf, solver=solver)
    t0 = time.perf_counter()
    fb, calls = bisection(scene, lf)
    row["bisection"] = {"fstar": fb, "solves": calls, "seconds": time.perf_counter() - t0}
    # the distortion bisection stops at an undecided verdict short of 1e-6: asked 1e-5
    row["distortion"] = timed_min_friction(scene, lf, method="distortion",
                                           rtol=DISTORTION_RTOL)
    a, b = clar["fstar"], row["distortion"]["fstar"]
    row["relative_difference"] = (abs(a - b) / max(abs(a), 1e-12)
                                  if a is not None and b is not None else None)
    return row


def markdown(rows: list[dict[str, Any]]) -> str:
    """The summary table of docs/methods.md."""
    def f(x: Any) -> Any:
        return "-" if x is None else x

    head = ["scene", "blocks", "lambda", "f* Clarabel", "f* distortion", "rel. diff.",
            "Clarabel solves / s", "HiGHS s", "SCS f* / s", "bisection solves / s",
            "distortion runs / iterations / s"]
    body = []
    for r in rows:
        c, d, h, s, b = (r["clarabel"], r["distortion"], r["highs"], r["scs"],
                         r["bisection"])
        body.append([r["scene"], r["blocks"], r["load_factor"],
                     f(c["fstar"]) if c["status"] == "stable" else c["status"],
                     f(d["fstar"]) if d["status"] == "stable" else d["status"],
                     f"{r['relative_difference']:.1e}"
                     if r["relative_difference"] is not None else "-",
                     f"{c['solves']} / {c['seconds']:.3f}", f"{h['seconds']:.3f}",
                     f"{s['fstar']:.6g} / {s['seconds']:.3f}" if s["fstar"] is not None
                     else f"{s['status']} / {s['seconds']:.3f}",
                     f"{b['solves']} / {b['seconds']:.3f}",
                     f"{d['solves']} / {d['iterations']} / {d['seconds']:.2f}"])
    return ("## Methods: minimum friction by each method\n\n"
            "f* at load factor lambda (0: dead load alone, where the live load makes "
            f"the scene unstable), every method asked for {RTOL:g} relative but the "
            f"distortion method, asked for {DISTORTION_RTOL:g} (its bisection stops at "
            "an undecided verdict short of 1e-6); a method that cannot certify f* to "
            "that accuracy gives no number (undecided). Each method computes f* alone "
            "(no state, no answer without dilatancy beside it). Seconds are wall-clock "
            "per f*, including problem building; the 1-minute load average is in the "
            "JSON, per scene.\n\n"
            + markdown_table(head, body))


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    """Run the comparison, write the results, return them."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="results folder (default "
                        "benchmarks/results)")
    parser.add_argument("--tiny", action="store_true", help="the two reference scenes only")
    args = parser.parse_args(argv)
    todo = scenes(args.tiny)
    if todo:  # load every back end once so that no timing includes an import
        for solver in ("clarabel", "highs", "scs"):
            timed_min_friction(todo[0][1], 1.0, solver=solver)
    rows = [bench_scene(name, scene) for name, scene in todo]
    data = {"rtol": RTOL, "tiny": args.tiny, "rows": rows}
    md = markdown(rows)
    write_results(args.out, "bench_methods", data, md)
    print(md)
    return data


if __name__ == "__main__":
    main()
