"""``sweep``: run a parametric study from a spec file (``docs/sweep-format.md``)."""

from __future__ import annotations

import argparse

from .options import positive_int


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("spec", help="sweep spec file (JSON, see docs/sweep-format.md)")
    p.add_argument("-o", "--output", required=True,
                   help="results file, .parquet or .csv (cases it holds are skipped)")
    p.add_argument("--workers", type=positive_int, default=None,
                   help="local processes (default: every core; 1: this process)")
    p.add_argument("--scheduler", default=None,
                   help="Dask scheduler address (tcp://HOST:PORT) instead of local processes")
    p.add_argument("--batch-size", type=positive_int, default=None, help="cases per task")
    p.add_argument("--no-progress", action="store_true",
                   help="no progress bar (drawn only where standard error is a terminal)")


def run(args: argparse.Namespace) -> int:
    from ..extras import require

    require("study", "sweep")
    from ..studies.spec import read_spec
    from ..studies.sweep import rate_text
    from ..studies.sweep import run as run_sweep

    sweep = read_spec(args.spec)
    try:
        res = run_sweep(sweep, output=args.output, workers=args.workers,
                        scheduler=args.scheduler, batch_size=args.batch_size,
                        progress=not args.no_progress and _terminal())
    except KeyboardInterrupt:  # Ctrl-C or SIGTERM: what is kept, and how to go on
        import sys

        print(f"rigidblocks: sweep stopped: the cases it finished are kept in "
              f"{args.output}.parts/; the same command resumes from them", file=sys.stderr)
        raise
    print(f"cases     {res.n_cases} ({res.n_run} run, {res.n_skipped} done before)")
    for i, (name, counts) in enumerate(res.outcomes.items()):
        print(f"{'' if i else 'outcomes':10s}{name}: "
              + ", ".join(f"{k} {v}" for k, v in counts.items()))
    print(f"failures  {res.n_failed}" + _first_failure(res.frame))
    if res.n_undecided:
        print(f"undecided {res.n_undecided} case(s) with an analysis that could not decide: "
              "no number, its bracket in its lower and upper columns where it has one"
              + _first_note(res.frame))
    print(f"time      {res.elapsed:.2f} s ({rate_text(res.rate)}, {res.executor})")
    print(f"output    {res.path}")
    # as an analysis's command: 1 where a case failed, 3 where one is undecided
    return 1 if res.n_failed else 3 if res.n_undecided else 0


def _terminal() -> bool:
    """Is standard error a terminal? The progress bar is drawn there only (a log
    filled with its carriage-return lines), as the analyses' progress lines are."""
    import sys

    return sys.stderr.isatty()


def _first_note(frame) -> str:
    """Where an analysis of a case could not decide, the first such case's reason (the
    others are in the output's ``note`` column; the summary named no case)."""
    if "note" not in frame or not len(frame):
        return ""
    noted = frame[frame["note"].notna() & (frame["note"].astype(str) != "")]
    if not len(noted):
        return ""
    row = noted.iloc[0]
    return f" (the first, case {int(row['case'])}: {row['note']}; every one in the " \
        "output's note column)"


def _first_failure(frame) -> str:
    """Where cases failed, the first one's error (the others are in the output's
    ``error`` column)."""
    failed = frame[frame["status"] == "failed"] if len(frame) else frame
    if not len(failed):
        return ""
    row = failed.iloc[0]
    return f" (the first, case {int(row['case'])}: {row['error']}; every one in the " \
        "output's error column)"


__all__ = ["add_args", "run"]
