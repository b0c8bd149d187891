"""Speed against accuracy: the error in f* and lambda* against the time to the answer.

For every method and each of its tolerance settings, the minimum friction f*
(:func:`rigidblocks.min_friction`) and the maximum load multiplier lambda*
(:func:`rigidblocks.max_load_multiplier`) of a few scenes of different size are
computed from the scene object to the answer (assembly, problem build, solves) and
compared with a reference solved to 1e-10: HiGHS (simplex, an exact vertex up to
round-off) with primal and dual feasibility tolerances 1e-10 and f* bisected to 1e-10
relative, cross-checked against Clarabel with every tolerance at 1e-10. The error
is relative, |x - x_ref| / |x_ref|; an answer with the wrong status (no number where
the reference has one) counts as a failure and is drawn at the top of the chart.

Settings swept:

* Clarabel: ``tol_gap_abs = tol_gap_rel = tol_feas = t`` for t = 1e-3 ... 1e-10, with
  the friction bisection to ``max(t, 1e-7)`` relative; "default" is the call without
  settings (the analyses' own defaults).
* HiGHS: its defaults through the same problem builder.
* SCS (through cvxpy): ``eps_abs = eps_rel = e`` for e = 1e-3, 1e-5, 1e-7.
* The distortion solver (2D, :mod:`rigidblocks.solvers.distortion`): violation
  tolerance ``tol`` 1e-5 / 1e-7 / 1e-9 with bisection ``rtol`` 1e-3 / 1e-5 / 1e-6.

The default settings are on the Pareto front of a scene and quantity when no other
setting answers both at least 10 % faster (timing noise) and at least as accurately
(errors below 1e-8 count as equal: f* is bisected to 1e-7 by default, and the two
references differ by up to ~1e-9). A Clarabel setting that returns bit for bit the
default's answer is the same computation (Clarabel's own defaults are 1e-8) and does
not count. Times are CPU seconds of the process (``time.process_time``: the machine is
shared, and a busy neighbour stretches wall-clock times but not the work done), the
best of 3 to 30 runs (more runs until 0.2 s have accumulated) after one untimed
warm-up call per scene and quantity; a run longer than 5 s is timed once.

``--rtol-sweep`` charts the accuracy the engineer asks for instead: f* and lambda* at
every requested accuracy ``rtol`` of :data:`RTOLS` (1e-2 to 1e-8) with the default
settings, on every catalogue case with a closed form and on running-bond walls of about
1,000 and 5,000 blocks (``--blocks``; 20,000 where time allows), each run once from
the scene object to the answer (CPU seconds, the 1-minute load average recorded at its
start and end). Per run: the status (a number, or UNDECIDED where the certified bracket
does not meet ``rtol``), the accuracy reached (the bracket's relative width) and, where
there is an exact reference (the catalogue's closed forms; HiGHS' simplex on the
1,009-block wall), the error against it. ``--docs`` writes its table and chart into
docs/methods.md between the markers of :data:`DOCS_MARK`.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import load_average, machine, markdown_table, out_dir, write_results  # noqa: E402

from rigidblocks.analyses import max_load_multiplier, min_friction  # noqa: E402
from rigidblocks.analyses.core import F_RTOL_FLOOR  # noqa: E402
from rigidblocks.errors import InputError  # noqa: E402
from rigidblocks.generators import build  # noqa: E402
from rigidblocks.io.scene_file import read_scene  # noqa: E402
from rigidblocks.scene.model import Scene  # noqa: E402

NAME = "bench_accuracy"
ROOT = Path(__file__).resolve().parents[1]
ERR_FLOOR = 1e-8
HIGHS_TIGHT = {"primal_feasibility_tolerance": 1e-10, "dual_feasibility_tolerance": 1e-10}
CLARABEL_TOLS = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10)
SCS_EPS = (1e-3, 1e-5, 1e-7)
WARM = {"method": "clarabel", "kw": {}}
DISTORTION = ((1e-5, 1e-3), (1e-7, 1e-5), (1e-9, 1e-6))
#: timing: at least MIN_RUNS runs, more until BUDGET CPU seconds, at most MAX_RUNS; a run
#: longer than LONG seconds is timed once
MIN_RUNS, MAX_RUNS, BUDGET, LONG = 3, 30, 0.2, 5.0
#: the default is dominated only by a setting at least this much faster (timing noise)
MARGIN = 0.10


def clarabel_tol(t: float) -> dict[str, float | bool]:
    # verify=False: the back end's own answer at this tolerance, not the checked and
    # (where the check fails) re-solved one of the solver policy
    return {"tol_gap_abs": t, "tol_gap_rel": t, "tol_feas": t, "verify": False}


def scenes(tiny: bool) -> list[dict[str, Any]]:
    """(name, scene, which quantities, distortion allowed) of the benchmark."""
    ref = read_scene(ROOT / "examples" / "reference.json")
    out = [dict(name="reference (4 blocks)", scene=ref, lf=1.0, qty=("f*", "lambda*"),
                distortion=True)]
    out.append(dict(name="arch, 30 voussoirs", lf=0.0, qty=("f*", "lambda*"),
                    scene=build("arch", voussoirs=30, thickness=0.15), distortion=True))
    if tiny:
        return out
    out.append(dict(name="wall 10x10 (106 blocks)", lf=1.0, qty=("f*", "lambda*"),
                    scene=build("wall", courses=10, blocks_per_course=10), distortion=False))
    out.append(dict(name="wall 32x31 (1009 blocks)", lf=1.0, qty=("lambda*",),
                    scene=build("wall", courses=32, blocks_per_course=31), distortion=False))
    return out


def settings_list(tiny: bool, with_distortion: bool, big: bool = False
                  ) -> list[dict[str, Any]]:
    """Every (method, label, default?, keyword arguments) of one scene.

    ``big``: HiGHS and SCS below eps 1e-3 are left out (each takes 40-150 s on the
    1,009-block wall on this machine)."""
    out: list[dict[str, Any]] = [dict(method="clarabel", label="default", default=True,
                                      kw={})]
    tols = (1e-3, 1e-6, 1e-10) if tiny else CLARABEL_TOLS
    for t in tols:
        out.append(dict(method="clarabel", label=f"tol {t:.0e}", default=False,
                        kw=dict(settings=clarabel_tol(t)), rtol=max(t, 1e-7)))
    if not big:
        out.append(dict(method="highs", label="default", default=False, kw={}))
    for e in SCS_EPS[:1] if (tiny or big) else SCS_EPS:
        out.append(dict(method="scs", label=f"eps {e:.0e}", default=False,
                        kw=dict(settings={"eps_abs": e, "eps_rel": e, "verify": False})))
    if with_distortion:
        for tol, rtol in DISTORTION[:1] if tiny else DISTORTION:
            out.append(dict(method="distortion", label=f"tol {tol:.0e}, rtol {rtol:.0e}",
                            default=False, tol=tol, rtol=rtol))
    return out


def answer(scene: Scene, qty: str, lf: float, s: dict[str, Any]) -> float | None:
    """f* or lambda* with the setting ``s`` (None when the status has no number)."""
    if s["method"] == "distortion":
        if qty == "f*":
            r = min_friction(scene, lf, method="distortion", state=False, rtol=s["rtol"],
                             settings={"tol": s["tol"]})
            return r.friction_factor
        r = max_load_multiplier(scene, method="distortion", state=False, rtol=s["rtol"],
                                settings={"tol": s["tol"]})
        return r.load_multiplier
    kw = dict(s["kw"])
    if qty == "f*":
        if "rtol" in s:
            kw["rtol"] = s["rtol"]
        return min_friction(scene, lf, method=s["method"], state=False, compare_dry=False,
                            **kw).friction_factor
    return max_load_multiplier(scene, method=s["method"], state=False, compare_dry=False,
                               **kw).load_multiplier


def timed_answer(fn: Callable[[], float | None], min_runs: int = MIN_RUNS,
                 max_runs: int = MAX_RUNS) -> tuple[float | None, float, str, int]:
    """(answer, fewest CPU seconds, error text, runs) of repeated calls.

    At least ``min_runs`` calls, more until ``BUDGET`` CPU seconds have accumulated, at
    most ``max_runs``; a first call longer than ``LONG`` seconds is not repeated."""
    times: list[float] = []
    val, err = None, ""
    while len(times) < max_runs:
        t0 = time.process_time()
        try:
            val = fn()
        except Exception as e:  # a failure is a data point of this benchmark
            val, err = None, f"{type(e).__name__}: {str(e)[:80]}"
        times.append(time.process_time() - t0)
        if times[0] > LONG or (len(times) >= min_runs and sum(times) >= BUDGET):
            break
    return val, min(times), err, len(times)


def reference(scene: Scene, qty: str, lf: float) -> tuple[float, float, str]:
    """(reference value, relative spread between the two references, which one).

    HiGHS at 1e-10 when it solves the problem (tried up to 500 blocks), else Clarabel
    at 1e-10."""
    def value(method: str, settings: dict[str, float]) -> float | None:
        try:
            if qty == "f*":
                # the simplex certifies f* to 1e-10; Clarabel to F_RTOL_FLOOR
                return min_friction(scene, lf, method=method, state=False, compare_dry=False,
                                    rtol=1e-10 if method == "highs" else F_RTOL_FLOOR,
                                    settings=settings).friction_factor
            return max_load_multiplier(scene, method=method, state=False, compare_dry=False,
                                       settings=settings).load_multiplier
        except Exception:  # the other reference decides
            return None

    a = value("highs", HIGHS_TIGHT) if len(scene.blocks) <= 500 else None
    b = value("clarabel", clarabel_tol(1e-10))
    if a is None and b is None:
        raise RuntimeError(f"no reference for {qty} of {scene.name}")
    if a is None:
        return float(b), math.nan, "clarabel 1e-10 (HiGHS failed)"
    spread = abs(a - b) / abs(a) if b is not None else math.nan
    return float(a), spread, "highs 1e-10"


def pareto_verdict(rows: list[dict[str, Any]]) -> dict[str, Any]:
    """Is the default row of one scene and quantity on the Pareto front?"""
    d = next(r for r in rows if r["default"])
    de = max(d["error"], ERR_FLOOR)
    dominated_by = [f'{r["method"]} {r["label"]}' for r in rows
                    if not r["default"] and math.isfinite(r["error"])
                    and not (r["method"] == d["method"] and r["value"] == d["value"])
                    and r["seconds"] <= (1 - MARGIN) * d["seconds"]
                    and max(r["error"], ERR_FLOOR) <= de]
    return {"on_front": not dominated_by, "dominated_by": dominated_by,
            "default_error": d["error"], "default_seconds": d["seconds"]}


def chart(rows: list[dict[str, Any]], path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(dict.fromkeys(r["scene"] for r in rows))
    fig, axes = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
    markers = {"clarabel": "o", "highs": "s", "scs": "^", "distortion": "D"}
    colours = dict(zip(names, plt.rcParams["axes.prop_cycle"].by_key()["color"], strict=False))
    top = 1e1
    for ax, qty in zip(axes, ("f*", "lambda*"), strict=True):
        for r in rows:
            if r["quantity"] != qty:
                continue
            err = r["error"] if math.isfinite(r["error"]) else top
            err = max(err, ERR_FLOOR)
            kw = dict(marker=markers[r["method"]], color=colours[r["scene"]], alpha=0.8,
                      ms=6, ls="none")
            if r["default"]:
                kw.update(ms=16, mfc="none", mew=2.5, alpha=1.0)
            ax.plot(r["seconds"], err, **kw)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.axhline(top, color="grey", lw=0.5, ls=":")
        ax.set_title(f"{qty}: relative error vs time to the answer")
        ax.set_xlabel("CPU seconds (scene to answer, best of 3-30 runs)")
        ax.grid(True, which="both", lw=0.3)
    axes[0].set_ylabel(f"relative error (floor {ERR_FLOOR:g}; failures at {top:g})")
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], marker=m, ls="none", color="k", label=k)
               for k, m in markers.items()]
    handles += [Line2D([], [], marker="o", ls="none", color=colours[n], label=n)
                for n in names]
    handles.append(Line2D([], [], marker="o", ls="none", mfc="none", mew=2.5, ms=14,
                          color="k", label="default settings"))
    axes[1].legend(handles=handles, fontsize=8, loc="center right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default=None, help="results folder (default benchmarks/results)")
    p.add_argument("--tiny", action="store_true", help="smallest scenes and few settings")
    a = p.parse_args(argv)
    rows: list[dict[str, Any]] = []
    refs: dict[str, dict[str, Any]] = {}
    verdicts: list[dict[str, Any]] = []
    for sc in scenes(a.tiny):
        scene = sc["scene"]
        for qty in sc["qty"]:
            ref, spread, which = reference(scene, qty, sc["lf"])
            refs[f'{sc["name"]} {qty}'] = {"value": ref, "clarabel_vs_highs": spread,
                                           "reference": which}
            group = []
            lf = sc["lf"]
            timed_answer(lambda sc_=scene, q=qty, lf=lf: answer(sc_, q, lf, WARM), 1, 1)
            big = len(scene.blocks) > 500
            for s in settings_list(a.tiny, sc["distortion"], big):
                val, sec, err, runs = timed_answer(
                    lambda s=s, sc_=scene, q=qty, lf=lf: answer(sc_, q, lf, s))
                e = abs(val - ref) / abs(ref) if val is not None else math.inf
                row = dict(scene=sc["name"], blocks=len(scene.blocks), quantity=qty,
                           method=s["method"], label=s["label"], default=s["default"],
                           value=val, reference=ref, error=e, seconds=sec, runs=runs, failure=err)
                rows.append(row)
                group.append(row)
            v = pareto_verdict(group)
            verdicts.append({"scene": sc["name"], "quantity": qty, **v})
    d = out_dir(a.out)
    chart(rows, d / f"{NAME}.png")
    table = markdown_table(
        ["scene", "qty", "method", "setting", "value", "rel. error", "CPU s", "runs"],
        [[r["scene"], r["quantity"], r["method"], r["label"] + (" **(default)**"
          if r["default"] else ""), "—" if r["value"] is None else r["value"],
          r["error"], r["seconds"], r["runs"]] for r in rows])
    vt = markdown_table(["scene", "qty", "default on Pareto front", "dominated by",
                         "default error", "default CPU s"],
                        [[v["scene"], v["quantity"], "yes" if v["on_front"] else "**no**",
                          ", ".join(v["dominated_by"]) or "—", v["default_error"],
                          v["default_seconds"]] for v in verdicts])
    md = (f"## Speed against accuracy ({NAME}.py)\n\n"
          f"![error vs time]({NAME}.png)\n\n"
          "Relative error of f* and lambda* against a reference (HiGHS at 1e-10, or "
          "Clarabel at 1e-10 where HiGHS fails; f* bisected to 1e-10; the spread of the "
          "two references is in the JSON) vs "
          "CPU seconds (`time.process_time`) from the scene object to the answer: the "
          f"best of N CPU-time runs, N = {MIN_RUNS} to {MAX_RUNS} (more runs until "
          f"{BUDGET:g} s have accumulated; a run over {LONG:g} s is timed once; N per row "
          "in the last column), after an untimed warm-up. "
          "HiGHS and SCS below eps 1e-3 are not run on the 1,009-block wall "
          "(40-150 s each). "
          f"The default is dominated only when another setting is at least "
          f"{MARGIN:.0%} faster and at least as accurate (errors below {ERR_FLOOR:g} are "
          "equal; a Clarabel setting returning the default's answer bit for bit is the "
          f"same computation and does not count).\n\n{vt}\n\n"
          f"<details><summary>all rows</summary>\n\n{table}\n\n</details>\n")
    data = {"rows": rows, "references": refs, "pareto": verdicts}
    write_results(a.out, NAME, data, md)
    return data


# -- the requested accuracy (rtol): time against the accuracy reached ---------------------
RTOLS = (1e-2, 2e-3, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8)
SWEEP = "bench_accuracy_rtol"
DOCS = ROOT / "docs" / "methods.md"
DOCS_MARK = ("<!-- bench_accuracy --rtol-sweep: begin -->",
             "<!-- bench_accuracy --rtol-sweep: end -->")


def sweep_cases(blocks: tuple[int, ...], catalogue: bool) -> list[dict[str, Any]]:
    """(name, scene factory, quantity, options, exact reference or None, its source)."""
    from rigidblocks.generators import catalogue as cat
    from rigidblocks.generators.walls import running_bond_wall

    out: list[dict[str, Any]] = []
    if catalogue:
        for case in cat.CASES.values():
            if case.analysis == "check" or case.value is None:
                continue
            qty = "f*" if case.analysis == "min_friction" else "lambda*"
            out.append(dict(name=f"cat:{case.name}", scene=case.scene, qty=qty,
                            kw=case.kwargs, ref=case.value, ref_source="closed form",
                            group="catalogue"))
    for n in blocks:
        courses = max(1, round(math.sqrt(n)))
        per = max(1, round(n / courses))
        for qty, kw in (("f*", {"load_factor": 1.0}), ("lambda*", {})):
            out.append(dict(name=f"wall {courses}x{per}", qty=qty, kw=kw, ref=None,
                            ref_source="", group=f"wall ~{n}",
                            scene=lambda c=courses, p=per: running_bond_wall(c, p)))
    return out


def sweep_run(case: dict[str, Any], scene: Scene, rtol: float) -> dict[str, Any]:
    """One analysis at ``rtol``: status, value, bracket, accuracy, solves, CPU s, load."""
    load0, t0 = load_average(), time.process_time()
    val = None
    try:
        if case["qty"] == "f*":
            r = min_friction(scene, state=False, compare_dry=False, rtol=rtol, **case["kw"])
            val = r.friction_factor
        else:
            r = max_load_multiplier(scene, state=False, compare_dry=False, rtol=rtol, **case["kw"])
            val = r.load_multiplier
        row = dict(status=r.status, value=val, bracket=r.bracket, accuracy=r.accuracy,
                   n_solves=r.n_solves)
    except InputError:  # finer than the back end certifies (F_RTOL_FLOOR): refused
        row = dict(status="refused", value=None, bracket=None, accuracy=None,
                   n_solves=None)
    except Exception as e:  # noqa: BLE001 - a failure is a data point
        row = dict(status=f"error: {type(e).__name__}", value=None, bracket=None,
                   accuracy=None, n_solves=None)
    row.update(seconds=time.process_time() - t0, load=(load0, load_average()))
    ref = case["ref"]
    row["error"] = (abs(val - ref) / max(abs(ref), 1e-300) if ref else abs(val - ref)) \
        if (val is not None and ref is not None) else None
    return row


def highs_reference(case: dict[str, Any], scene: Scene) -> tuple[float | None, str]:
    """HiGHS' simplex lambda* (an exact vertex up to round-off: one LP), where it
    finishes; f* on a wall (a search of several such LPs, minutes each at 1,000
    blocks on this machine) has none."""
    if case["qty"] != "lambda*":
        return None, ""
    try:
        return (max_load_multiplier(scene, state=False, solver="highs",
                                    settings=HIGHS_TIGHT, rtol=0.5,
                                    **case["kw"]).load_multiplier, "HiGHS simplex (lambda*)")
    except Exception:  # noqa: BLE001 - no reference
        return None, ""


def sweep_chart(rows: list[dict[str, Any]], path: Path) -> None:
    """CPU seconds against the accuracy reached (left: bracket width; right: error
    against the exact reference), one line per case through its rtols; undecided runs
    hollow, the default rtol ringed."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rigidblocks.methods.convex import FRICTION_RTOL

    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    groups = list(dict.fromkeys(r["group"] for r in rows))
    colours = dict(zip(groups, plt.rcParams["axes.prop_cycle"].by_key()["color"],
                       strict=False))
    for i, qty in enumerate(("f*", "lambda*")):
        for j, key in enumerate(("accuracy", "error")):
            ax = axes[i, j]
            cases = dict.fromkeys(r["name"] for r in rows if r["qty"] == qty)
            for name in cases:
                rs = [r for r in rows if r["qty"] == qty and r["name"] == name
                      and r.get(key) is not None]
                if not rs:
                    continue
                c = colours[rs[0]["group"]]
                xs = [max(r[key], 1e-16) for r in rs]
                ys = [max(r["seconds"], 1e-4) for r in rs]
                ax.plot(xs, ys, "-", color=c, lw=0.6, alpha=0.5)
                for r, x, y in zip(rs, xs, ys, strict=True):
                    decided = r["value"] is not None
                    ax.plot(x, y, "o", color=c, mfc=c if decided else "none", ms=5)
                    if r["rtol"] == FRICTION_RTOL:
                        ax.plot(x, y, "o", color="k", mfc="none", ms=12, mew=1.5)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.grid(True, which="both", lw=0.3)
            what = "accuracy reached (bracket's relative width)" if key == "accuracy" \
                else "relative error against the exact reference"
            ax.set_xlabel(what)
            ax.set_ylabel("CPU seconds, scene to answer")
            ax.set_title(f"{qty}: time against {key}")
    from matplotlib.lines import Line2D
    handles = [Line2D([], [], marker="o", ls="none", color=colours[g], label=g)
               for g in groups]
    handles += [Line2D([], [], marker="o", ls="none", color="grey", mfc="none",
                       label="undecided (bracket short of rtol)"),
                Line2D([], [], marker="o", ls="none", color="k", mfc="none", ms=12,
                       label=f"default rtol {FRICTION_RTOL:g}")]
    axes[0, 1].legend(handles=handles, fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def sweep_markdown(rows: list[dict[str, Any]], meta: dict[str, Any]) -> str:
    """The table of the sweep: per group, quantity and rtol, the cases decided, the
    largest accuracy reached and error, and the CPU seconds (sum over the group)."""
    keys = list(dict.fromkeys((r["group"], r["qty"], r["rtol"]) for r in rows))
    table = []
    for g, q, rt in keys:
        rs = [r for r in rows if (r["group"], r["qty"], r["rtol"]) == (g, q, rt)]
        dec = [r for r in rs if r["value"] is not None]
        acc = [r["accuracy"] for r in rs if r["accuracy"] is not None]
        err = [r["error"] for r in dec if r["error"] is not None]
        load = [x for r in rs for x in r["load"]]
        table.append([g, q, f"{rt:.0e}", f"{len(dec)}/{len(rs)}",
                      f"{max(acc):.1e}" if acc else "-", f"{max(err):.1e}" if err else "-",
                      sum(r["n_solves"] or 0 for r in rs), f"{sum(r['seconds'] for r in rs):.3g}",
                      f"{min(load):.1f}-{max(load):.1f}"])
    head = ["cases", "qty", "rtol", "numbers", "worst accuracy reached", "worst error",
            "solves", "CPU s", "load"]
    m = meta["machine"]
    return (f"![time against accuracy]({meta['png']})\n\n"
            f"Measured {meta['date']} on {m['cpu']} ({m['cores']} cores, shared; the "
            f"1-minute load average per group in the last column), Clarabel "
            f"{m['clarabel']}, each run once (CPU seconds, scene to answer, no force "
            f"state). Exact references: {meta['references']}. \"numbers\": runs whose "
            "certified bracket met rtol (the others are undecided, with the accuracy "
            "they reached).\n\n" + markdown_table(head, table))


def sweep(argv: list[str]) -> dict[str, Any]:
    p = argparse.ArgumentParser(description="time against the requested accuracy")
    p.add_argument("--rtol-sweep", action="store_true")
    p.add_argument("--out", default=None)
    p.add_argument("--blocks", default="1000,5000",
                   help="wall sizes (comma separated; empty: none)")
    p.add_argument("--no-catalogue", action="store_true")
    p.add_argument("--no-highs", action="store_true", help="no HiGHS reference on walls")
    p.add_argument("--merge", action="store_true",
                   help="add to the rows of an earlier run (same cases replaced)")
    p.add_argument("--docs", action="store_true", help="write the section of methods.md")
    a = p.parse_args(argv)
    d = out_dir(a.out)
    blocks = tuple(int(b) for b in a.blocks.split(",") if b)
    rows: list[dict[str, Any]] = []
    refs: dict[str, Any] = {}
    if a.merge and (d / f"{SWEEP}.json").exists():
        import json
        old = json.loads((d / f"{SWEEP}.json").read_text())
        rows, refs = old["rows"], old.get("references", {})
    for case in sweep_cases(blocks, not a.no_catalogue):
        scene = case["scene"]()
        key = f"{case['name']} {case['qty']}"
        if case["ref"] is None and not a.no_highs and len(scene.blocks) <= 1100:
            case["ref"], case["ref_source"] = highs_reference(case, scene)
        refs[key] = {"value": case["ref"], "source": case["ref_source"]}
        rows = [r for r in rows if (r["name"], r["qty"]) != (case["name"], case["qty"])]
        for rtol in RTOLS:
            row = dict(name=case["name"], qty=case["qty"], group=case["group"],
                       blocks=len(scene.blocks), rtol=rtol, reference=case["ref"],
                       **sweep_run(case, scene, rtol))
            rows.append(row)
            print(f"{key} rtol {rtol:.0e}: {row['status']} {row['value']} acc "
                  f"{row['accuracy']} err {row['error']} {row['n_solves']} solves "
                  f"{row['seconds']:.3g} s load {row['load']}", flush=True)
    sources = sorted({v["source"] for v in refs.values() if v["source"]})
    meta = dict(date=time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), machine=machine(),
                png=f"../benchmarks/results/{SWEEP}.png",
                references=", ".join(sources) or "none")
    sweep_chart(rows, d / f"{SWEEP}.png")
    md = sweep_markdown(rows, meta)
    write_results(a.out, SWEEP, {"rows": rows, "references": refs, "meta": meta}, md)
    if a.docs:
        text = DOCS.read_text()
        i, j = text.index(DOCS_MARK[0]), text.index(DOCS_MARK[1])
        DOCS.write_text(text[:i + len(DOCS_MARK[0])] + "\n\n" + md + "\n\n" + text[j:])
    return {"rows": rows}


if __name__ == "__main__":
    if "--rtol-sweep" in sys.argv[1:]:
        sweep(sys.argv[1:])
        sys.exit(0)
    res = main()
    for v in res["pareto"]:
        print(v["scene"], v["quantity"], "on front" if v["on_front"] else
              f"dominated by {v['dominated_by']}")
