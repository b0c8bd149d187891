"""The cost of the non-associative answer, and lambda against f under both flow rules.

1. Running-bond walls of growing size (f = 0.8, horizontal live body force): the
   associative collapse multiplier (one LP) against the non-associative one, computed
   by the convex path's sequence of cohesion-capped problems and by the distortion
   iteration with separate normal and shear links (the smaller walls only): wall-clock
   seconds, fixed-point iterations (convex solves, or distortion iterations), bisection
   trials, and the two multipliers.
2. The collapse multiplier against the friction coefficient, associative and
   non-associative (convex path), on the seed's structures that carry a live load:
   the reference model (H as the live load) and the flat arch, stocky arch and Arpino
   gate under a horizontal body force; one chart.

Run as ``python benchmarks/bench_nonassoc.py [--tiny] [--out DIR]``; it writes
``bench_nonassoc.json``, ``bench_nonassoc.md`` and ``bench_nonassoc.png`` (see
benchmarks/common.py).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one thread: the CPU times are comparable
sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import markdown_table, out_dir, write_results  # noqa: E402

import rigidblocks as rb  # noqa: E402
from rigidblocks.generators import build  # noqa: E402

NA = "non-associative"
#: (courses, blocks per course) of the walls; the distortion iteration on the first few
WALLS = ((2, 2), (3, 3), (4, 4), (6, 4), (8, 5))
DISTORTION_UP_TO = 3
TINY_WALLS = ((2, 2),)
WALL_FRICTION = 0.8
#: friction coefficients of the lambda-f chart
FRICTIONS = (0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0)
TINY_FRICTIONS = (0.3, 0.6)
#: the seed's structures of the chart: label, generator, parameters
STRUCTURES = (("reference model (4a)", "reference", {}),
              ("flat arch, radial joints, piers (6b)", "flat_arch", {"joints": "radial"}),
              ("stocky arch (7a)", "stocky_arch", {}),
              ("Arpino gate (8)", "arpino_gate", {}))
TINY_STRUCTURES = STRUCTURES[:1]


def _run(fn: Any, *args: Any, **kw: Any) -> tuple[Any, float]:
    t0 = time.perf_counter()
    r = fn(*args, **kw)
    return r, time.perf_counter() - t0


def walls(sizes: Sequence[tuple[int, int]], distortion_up_to: int) -> list[dict[str, Any]]:
    rows = []
    for k, (c, n) in enumerate(sizes):
        scene = build("wall", courses=c, blocks_per_course=n, friction=WALL_FRICTION)
        a, ta = _run(rb.max_load_multiplier, scene, state=False)
        v, tv = _run(rb.max_load_multiplier, scene, flow=NA, state=False)
        row = {"courses": c, "per_course": n, "blocks": len(scene.blocks),
               "assoc_lambda": a.load_multiplier, "assoc_seconds": ta,
               "assoc_solves": a.n_solves, "convex_lambda": v.load_multiplier,
               "convex_status": v.status, "convex_seconds": tv,
               "convex_iterations": v.iterations, "trials": len(v.history),
               "convex_solves": v.n_solves}
        if k < distortion_up_to:
            d, td = _run(rb.max_load_multiplier, scene, flow=NA, method="distortion",
                         state=False)
            row.update(distortion_lambda=d.load_multiplier, distortion_status=d.status,
                       distortion_seconds=td, distortion_iterations=d.iterations)
        rows.append(row)
        print(f"wall {c}x{n}: assoc {a.load_multiplier:.5g} ({ta:.2f} s), "
              f"non-assoc {v.load_multiplier} ({tv:.2f} s, {v.iterations} solves)",
              flush=True)
    return rows


def curves(structures: Sequence[tuple[str, str, dict]], frictions: Sequence[float]
           ) -> list[dict[str, Any]]:
    out = []
    for label, gen, params in structures:
        pts = []
        for f in frictions:
            scene = build(gen, friction=f, **params)
            if not scene.has_live_load:
                scene = scene.with_changes(live_body_force=(1.0, 0.0))
            a = rb.max_load_multiplier(scene, state=False)
            v = rb.max_load_multiplier(scene, flow=NA, state=False)
            pts.append({"friction": f, "assoc": a.load_multiplier, "assoc_status": a.status,
                        "nonassoc": v.load_multiplier, "nonassoc_status": v.status,
                        "bounds": v.load_multiplier_bounds})
        out.append({"structure": label, "points": pts})
        print(f"{label}: done", flush=True)
    return out


def chart(data: list[dict[str, Any]], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(data)
    fig, axes = plt.subplots(1, n, figsize=(3.6 * n, 3.4), squeeze=False)
    for ax, d in zip(axes[0], data, strict=True):
        pts = d["points"]
        fs = [p["friction"] for p in pts]
        for key, style, label in (("assoc", "o-", "associative"),
                                  ("nonassoc", "s--", "non-associative")):
            ys = [p[key] if p[key] is not None else float("nan") for p in pts]
            ax.plot(fs, ys, style, label=label, ms=4)
        ax.set_title(d["structure"], fontsize=9)
        ax.set_xlabel("friction coefficient f")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("collapse load multiplier")
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


#: the large walls (courses, blocks per course) at both frictions, and the largest wall
#: run by default (70 x 70 with --large-walls 5000)
LARGE_WALLS = ((10, 10), (20, 15), (32, 32), (70, 70))
LARGE_FRICTIONS = (0.6, 0.8)
LARGE_UP_TO = 1100
TINY_LARGE = ((3, 3),)


def _cpu(fn: Any, *args: Any, **kw: Any) -> tuple[Any, float]:
    """fn(*args, **kw) and the CPU seconds it took (this process, one thread when the
    script runs with OMP_NUM_THREADS=1 etc., as it sets by default)."""
    t0 = time.process_time()
    r = fn(*args, **kw)
    return r, time.process_time() - t0


def large_walls(sizes: Sequence[tuple[int, int]], frictions: Sequence[float],
                up_to: int) -> list[dict[str, Any]]:
    """Non-associative load and friction on running-bond walls against the associative
    load in the same run (CPU seconds): the limit fixed point from X0 and from the
    associative collapse state (the spread), and the friction whose fixed point from X0
    carries the multiplier found at f (it should give f back)."""
    warm = build("wall", courses=2, blocks_per_course=2, friction=0.6)
    rb.max_load_multiplier(warm, state=False)  # imports and first calls out of the timing
    rb.max_load_multiplier(warm, flow=NA, state=False)
    rows = []
    for c, n in sizes:
        for f in frictions:
            scene = build("wall", courses=c, blocks_per_course=n, friction=f)
            if len(scene.blocks) > up_to:
                continue
            a, ta = _cpu(rb.max_load_multiplier, scene, state=False)
            v, tv = _cpu(rb.max_load_multiplier, scene, flow=NA, state=False)
            starts = {h.get("start"): h.get("load_factor") for h in v.history}
            lf = v.load_multiplier if v.status == "collapse" else 0.9 * a.load_multiplier
            fr, tf = _cpu(rb.min_friction, scene, load_factor=lf, flow=NA, state=False)
            row = {"courses": c, "per_course": n, "blocks": len(scene.blocks),
                   "friction": f, "assoc_lambda": a.load_multiplier, "assoc_cpu": ta,
                   "na_status": v.status, "na_lambda": v.load_multiplier, "na_cpu": tv,
                   "na_from_assoc": starts.get("the associative collapse state"),
                   "na_solves": v.iterations, "na_ratio": tv / ta if ta else None,
                   "friction_load_factor": lf, "friction_status": fr.status,
                   "na_friction": fr.friction_factor,
                   "friction_bracket": fr.bracket, "friction_cpu": tf,
                   "friction_ratio": tf / ta if ta else None}
            rows.append(row)
            print(f"wall {c}x{n} f={f}: assoc {a.load_multiplier:.6g} ({ta:.2f} s), "
                  f"non-assoc {v.status} {v.load_multiplier} ({tv:.2f} s), friction "
                  f"{fr.status} {fr.friction_factor} ({tf:.2f} s)", flush=True)
    return rows


def large_walls_md(rows: list[dict[str, Any]]) -> list[str]:
    """The markdown of :func:`large_walls`."""
    header = ["wall", "blocks", "f", "lambda assoc", "CPU s", "lambda non-assoc (X0)",
              "from the assoc. state", "CPU s", "x assoc", "limit solves",
              "f non-assoc at lambda non-assoc", "CPU s", "x assoc"]
    body = [[f"{r['courses']} x {r['per_course']}", r["blocks"], r["friction"],
             r["assoc_lambda"], r["assoc_cpu"], _cell(r["na_lambda"]) if r["na_status"]
             == "collapse" else r["na_status"], _cell(r["na_from_assoc"]), r["na_cpu"],
             _cell(r["na_ratio"]), r["na_solves"], _cell(r["na_friction"]) if
             r["friction_status"] == "stable" else r["friction_status"], r["friction_cpu"],
             _cell(r["friction_ratio"])] for r in rows]
    return ["### Running-bond walls: the limit fixed point against the associative load", "",
            "Non-associative `load` (the fixed point of the capped limit problem from the "
            "elastic state X0, and from the associative collapse state: the spread) and "
            "`friction` at the multiplier found (which should give f back), CPU seconds in "
            "one process on one thread, with the associative `load` of the same run.", "",
            markdown_table(header, body)]


def _cell(v: Any) -> Any:
    return "-" if v is None else v


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--tiny", action="store_true", help="smallest sizes only")
    p.add_argument("--out", default=None, help="results folder")
    p.add_argument("--large-walls", type=int, default=LARGE_UP_TO,
                   help="largest wall (blocks) of the large-walls table")
    args = p.parse_args(argv)
    large = large_walls(TINY_LARGE if args.tiny else LARGE_WALLS, LARGE_FRICTIONS,
                        args.large_walls)
    sizes = TINY_WALLS if args.tiny else WALLS
    wall_rows = walls(sizes, DISTORTION_UP_TO)
    curve = curves(TINY_STRUCTURES if args.tiny else STRUCTURES,
                   TINY_FRICTIONS if args.tiny else FRICTIONS)
    d = out_dir(args.out)
    chart(curve, d / "bench_nonassoc.png")
    header = ["wall", "blocks", "lambda assoc", "s", "lambda non-assoc (convex)", "s",
              "convex iterations (QPs)", "trials", "lambda non-assoc (distortion)", "s",
              "distortion iterations"]
    rows = [[f"{r['courses']} x {r['per_course']}", r["blocks"], r["assoc_lambda"],
             r["assoc_seconds"], _cell(r["convex_lambda"]), r["convex_seconds"],
             r["convex_iterations"], r["trials"], _cell(r.get("distortion_lambda")),
             _cell(r.get("distortion_seconds")), _cell(r.get("distortion_iterations"))]
            for r in wall_rows]
    md = ["## Non-associative sliding: cost and lambda against f", "",
          f"Running-bond walls at f = {WALL_FRICTION} under a horizontal body force: the "
          "associative multiplier (one LP) against the non-associative one, reached from "
          "the elastic state, by bisection on the verdicts of the convex path's "
          "cohesion-capped problems (each iteration one QP) and of the distortion "
          "iteration with separate links. `bench_nonassoc.png`: the collapse multiplier "
          "against f under both flow rules on the seed's structures (convex path).", "",
          markdown_table(header, rows), "",
          "![lambda against f](results/bench_nonassoc.png)", ""] + large_walls_md(large)
    data = {"walls": wall_rows, "curves": curve, "large_walls": large}
    write_results(args.out, "bench_nonassoc", data, "\n".join(md))
    return data


if __name__ == "__main__":
    main()
