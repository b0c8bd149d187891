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
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

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


def _cell(v: Any) -> Any:
    return "-" if v is None else v


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--tiny", action="store_true", help="smallest sizes only")
    p.add_argument("--out", default=None, help="results folder")
    args = p.parse_args(argv)
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
          "![lambda against f](results/bench_nonassoc.png)"]
    data = {"walls": wall_rows, "curves": curve}
    write_results(args.out, "bench_nonassoc", data, "\n".join(md))
    return data


if __name__ == "__main__":
    main()
