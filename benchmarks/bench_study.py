"""Throughput of parametric studies: cases per second, one process against local processes.

The sweep: small semicircular arches (:func:`rigidblocks.generators.arches.arch`, radial
joints on fixed abutments, two straight segments per voussoir face) under self-weight
(load factor 0), a grid of 10 voussoir counts (4 to 13) by ``cases / 10`` ring
thicknesses t/R from 0.12 to 0.30; each analysis (``check``: one relaxation LP;
``min_friction``: a few) is run on the whole grid by one process (``workers=1``) and by
local processes (``workers=2``, ...). Run as

    python benchmarks/bench_study.py --cases 1000 --workers 1 2

The rate counts every case from the first submission to the last row written,
including starting the processes and writing the Parquet output.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from rigidblocks.studies.sweep import run

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import load_average, markdown_table, write_results  # noqa: E402

NAME = "bench_study"


def grid(cases: int) -> dict[str, list]:
    """10 voussoir counts by ``cases // 10`` thicknesses (at least one)."""
    n = max(1, cases // 10)
    return {"voussoirs": list(range(4, 14)),
            "thickness": [float(t) for t in np.linspace(0.12, 0.30, n)]}


def bench(cases: int, workers: Sequence[int], analyses: Sequence[str],
          workdir: Path) -> list[dict]:
    """One row per (analysis, workers): cases, seconds, cases per second, failures."""
    rows = []
    for analysis in analyses:
        base = None
        for w in workers:
            out = workdir / f"{analysis}_{w}.parquet"
            res = run("arch", grid=grid(cases), parameters={"load_factor": 0.0,
                                                            "arc_points": 2},
                      analyses=[analysis], workers=w, progress=False, output=out)
            base = base or res.rate
            rows.append({"analysis": analysis, "workers": w, "cases": res.n_run,
                         "seconds": res.elapsed, "cases_per_s": res.rate,
                         "speedup": res.rate / base, "failed": res.n_failed,
                         "solver_s_per_case": float(res.frame["solve_time"].mean()),
                         "case_s": float(res.frame["time"].mean())})
    return rows


def main(argv: Sequence[str] | None = None) -> dict:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--cases", type=int, default=1000, help="cases per sweep (default 1000)")
    p.add_argument("--workers", type=int, nargs="+", default=[1, 2],
                   help="process counts to compare (1: in this process)")
    p.add_argument("--analyses", nargs="+", default=["check", "min_friction"],
                   choices=["check", "min_friction"])
    p.add_argument("--out", default=None, help="results folder (default benchmarks/results)")
    p.add_argument("--tiny", action="store_true", help="20 cases, check only")
    args = p.parse_args(argv)
    if args.cases < 1 or min(args.workers) < 1:
        p.error("--cases and --workers must be >= 1")
    if args.tiny:
        args.cases, args.analyses = 20, ["check"]
    load = load_average()
    with tempfile.TemporaryDirectory() as tmp:
        rows = bench(args.cases, args.workers, args.analyses, Path(tmp))
    load_end = load_average()
    header = ["analysis", "workers", "cases", "seconds", "cases/s", "speed-up", "failed",
              "mean case s", "mean solver s"]
    table = markdown_table(header, [[r["analysis"], r["workers"], r["cases"], r["seconds"],
                                     r["cases_per_s"], r["speedup"], r["failed"],
                                     r["case_s"], r["solver_s_per_case"]] for r in rows])
    md = (f"## Parametric studies: throughput\n\n{args.cases} small arches (10 voussoir "
          "counts x thicknesses, self-weight), one process against local processes "
          "(`python benchmarks/bench_study.py`). Wall-clock rates on a machine of "
          f"{os.cpu_count()} cores shared with other jobs (1-minute load average "
          f"{load:.1f} at the start, {load_end:.1f} at the end): the speed-up of more "
          "processes is bounded by the cores the other jobs leave free.\n\n" + table)
    data = {"cases": args.cases, "workers": args.workers, "rows": rows,
            "load_average": [load, load_end]}
    write_results(args.out, NAME, data, md)
    print(table)
    return data


if __name__ == "__main__":
    main(sys.argv[1:])
