"""Which back end reaches which accuracy on the catalogue, on its own answers.

Every case of the catalogue (:mod:`rigidblocks.generators.catalogue`: closed forms and
published values) is run with each back end that applies to it (HiGHS and OSQP: the 2D
cases, linear programs; the cvxpy back ends that are installed: all), through the
analyses with their default policy (tight settings, every answer checked against the
problem). Per back end: the runs, those whose every solve it answered itself (no answer
rejected by the check and solved again by Clarabel, ``result.rejected``), those with the
expected status, and the largest relative error of f* or lambda* against the case's
reference value (absolute where that is 0), over all runs and over the runs it
answered itself, and the verdicts of ``check`` the case lists around its limit
(1e-4 relative either side as a rule) that come out right from the back end's own
answers. The force state
(a QP) is not asked for: HiGHS takes no QP. Times are CPU seconds (process time) of
the whole catalogue per back end, one run each.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import markdown_table, write_results  # noqa: E402

from rigidblocks.analyses import check, max_load_multiplier, min_friction  # noqa: E402
from rigidblocks.errors import SolverFailure  # noqa: E402
from rigidblocks.generators.catalogue import CASES  # noqa: E402
from rigidblocks.solvers.cvxpy_backend import installed_cvxpy_solvers  # noqa: E402

NAME = "bench_backends"
ANALYSES = {"check": check, "min_friction": min_friction,
            "max_load_multiplier": max_load_multiplier}
LP_ONLY = ("highs", "osqp", "cvxpy-highs", "cvxpy-osqp")


def backends() -> list[str]:
    cv = [s.lower() for s in installed_cvxpy_solvers()]
    out = ["clarabel", "highs", "osqp"]
    out += [f"cvxpy-{s}" for s in ("clarabel", "highs", "scs", "ecos", "osqp") if s in cv]
    return out


def value_of(r) -> float | None:
    return getattr(r, "friction_factor", None) if r.analysis == "min_friction" else \
        getattr(r, "load_multiplier", None)


def run_one(case, solver: str) -> dict:
    kw = {**case.kwargs, "solver": solver, "state": False}
    t0 = time.process_time()
    try:
        r = ANALYSES[case.analysis](case.scene(), **kw)
    except SolverFailure as exc:
        return {"case": case.name, "solver": solver, "status": "failure", "error": None,
                "own": False, "ok": False, "cpu": time.process_time() - t0,
                "why": str(exc)}
    verdicts = own_verdicts = 0
    for vd in case.verdicts:
        scene = vd.scene() if vd.scene is not None else case.scene()
        opts = {**{k: x for k, x in case.kwargs.items()
                   if k != "pyramid" or scene.dimension == 3}, **dict(vd.options)}
        try:
            c = check(scene, state=False, compare_dry=False, solver=solver, **opts)
        except SolverFailure:
            continue
        verdicts += c.admissible is vd.admissible
        own_verdicts += c.admissible is vd.admissible and not c.rejected \
            and set(c.answered_by) <= {solver}
    cpu = time.process_time() - t0
    v = value_of(r)
    err = None
    if case.value is not None and v is not None:
        err = abs(v - case.value) / (abs(case.value) if case.value else 1.0)
    own = not r.rejected and set(r.answered_by) <= {solver}
    return {"case": case.name, "solver": solver, "status": r.status, "error": err,
            "own": own, "ok": r.status == case.status, "cpu": cpu,
            "verdicts": len(case.verdicts), "right": verdicts, "own_right": own_verdicts,
            "answered_by": list(r.answered_by), "rejected": list(r.rejected)}


def main(argv: list[str] | None = None) -> dict:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--solvers", nargs="*", default=None)
    ap.add_argument("--out", default=None)
    ap.add_argument("--tiny", action="store_true", help="the first four cases only")
    args = ap.parse_args(argv)
    cases = list(CASES.values())[:4] if args.tiny else list(CASES.values())
    rows, table = [], []
    for solver in args.solvers or backends():
        runs = [run_one(c, solver) for c in cases if c.is_lp or solver not in LP_ONLY]
        rows += runs
        errs = [r["error"] for r in runs if r["error"] is not None]
        own_errs = [r["error"] for r in runs if r["error"] is not None and r["own"]]
        table.append([solver, len(runs), sum(r["own"] for r in runs),
                      sum(r["ok"] for r in runs),
                      f"{max(errs):.1e}" if errs else "-",
                      f"{max(own_errs):.1e}" if own_errs else "-",
                      f"{sum(r.get('own_right', 0) for r in runs)} / "
                      f"{sum(r.get('verdicts', 0) for r in runs)}",
                      f"{sum(r['cpu'] for r in runs):.1f}"])
        print(table[-1], flush=True)
    head = ["back end", "runs", "own answers", "expected status", "max rel. error",
            "max rel. error (own)", "verdicts right (own)", "CPU s"]
    md = "\n".join([
        "## Back ends on the catalogue", "",
        "Generated by `python benchmarks/bench_backends.py`: every catalogue case on "
        "every back end that applies, each answer checked against the problem; \"own\" "
        "counts the runs and verdicts no answer of which was solved again by Clarabel.",
        "", markdown_table(head, table)])
    print(md)
    data = {"rows": rows, "table": table}
    write_results(args.out, NAME, data, md)
    return data


if __name__ == "__main__":
    main()
