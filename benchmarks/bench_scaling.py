"""Scaling, overhead against the bare solver, and the speed targets.

Scenes: 2D running-bond walls (:func:`rigidblocks.generators.walls.running_bond_wall`,
shape from :func:`bench_foundation.wall_shape`) of about 100 to 50,000 blocks, and the
same walls extruded to 3D prisms (:func:`rigidblocks.scene.extrude`), whose f* and
lambda* equal the 2D ones. Run as

    python benchmarks/bench_scaling.py            # full sizes (minutes)
    python benchmarks/bench_scaling.py --tiny     # seconds

Times are CPU seconds of the measuring process (``--clock wall`` for wall-clock): the
machine is shared, and a busy neighbour stretches wall-clock times but not the work
done; every stage, the solver included, runs on one thread. Stages, timed from the
scene file to the answer: ``read`` (parse and validate the file), ``contacts``,
``assembly``, ``build`` (the conic problems), ``solve`` (the back end's whole call, all
solves) and ``results`` (everything else: scaling, verdict logic, mechanism, force
state). Each case runs in a fresh subprocess, so its peak resident memory
(``getrusage`` maxrss) covers the native solver's allocations too.

The floor ("bare") is one Clarabel solve, default settings, of the plain formulation
of the maximum load multiplier: two unknowns (N, T) per contact point (2D; N, T1, T2
in 3D), the equilibrium rows A x + F_dead + lambda F_live = 0 in the scene's units,
N >= 0 and |T| <= f N per point (a second-order cone per point in 3D), maximise
lambda; the matrices go straight to ``clarabel.DefaultSolver``. Our total / bare
ratio per size is the headline: it does not depend on the machine.

Non-solver stages are timed on their own up to 50,000 blocks (``stages`` cases: read,
contacts, assembly, all three problem builds, and the result post-processing on a
dummy solution); their exponent p (time ~ blocks^p) is the least-squares slope on
log-log axes between 1,000 and 50,000 blocks.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
import resource
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import scipy.sparse as sp

sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_foundation import wall_shape  # noqa: E402
from common import load_average, markdown_table, out_dir, write_results  # noqa: E402

NAME = "bench_scaling"
STAGES = ("read", "contacts", "assembly", "build", "solve", "results")
NON_SOLVER = ("read", "contacts", "assembly", "build", "results")
ANALYSES = ("check", "min_friction", "min_friction_no_state", "max_load_multiplier",
            "max_load_no_state")
SIZES_2D = (100, 1_000, 5_000, 20_000, 50_000)
STAGE_SIZES_2D = (100, 1_000, 5_000, 20_000, 50_000)
SIZES_3D = (100, 1_000, 5_000)
TINY_2D = (12, 40)
TINY_3D = (12,)
#: largest walls per analysis (the rest would take tens of minutes on a shared machine)
LIMITS = {"min_friction": {2: 5_000, 3: 5_000}, "min_friction_no_state": {2: 20_000, 3: 0},
          "check": {2: 50_000, 3: 5_000},
          "max_load_no_state": {2: 20_000, 3: 0}, "max_load_multiplier": {2: 50_000, 3: 5_000},
          "reference": {2: 5_000, 3: 1_000}}
#: the load factor of the minimum-friction cases: the wall's live load (a horizontal body
#: force) at its full value, where f* is about 1.2 and the search takes its most steps
MF_LOAD_FACTOR = 1.0
#: cases above these sizes run last, after the settings trials and the cvxpy comparison
BIG = {2: 5_000, 3: 1_000}
CVXPY_SIZES = (1_000, 5_000)
TARGET_SIZE = 5_000
#: Clarabel settings tried at the target size (max_load without the force state)
TRIALS: dict[str, dict[str, Any]] = {
    "presolve off": {"presolve_enable": False},
    "equilibration off": {"equilibrate_enable": False},
    "direct_solve_method faer": {"direct_solve_method": "faer"},
}
#: the clock: CPU seconds of the process (the machine is shared; a busy neighbour
#: stretches wall-clock times, not CPU times) or wall-clock seconds (``--clock wall``)
CLOCKS = {"cpu": time.process_time, "wall": time.perf_counter}
_clock = ["cpu"]


def _now() -> float:
    return CLOCKS[_clock[0]]()


TARGETS = {"max_load_ratio": 1.5, "min_friction_ratio": 5.0, "non_solver_exponent": 1.1,
           "non_solver_share": 0.10}
#: min_friction against one bare solve of the plain problem at the answer (2D), by size
MF_TARGETS = {5_000: 3.0, 20_000: 5.0}


# -- scenes ------------------------------------------------------------------------------
def make_scene(dim: int, n_blocks: int, shape: Sequence[int] | None = None):
    """The running-bond wall of about ``n_blocks`` blocks, or of ``shape`` (courses,
    blocks per course) where given (3D: extruded to prisms)."""
    from rigidblocks.generators.walls import running_bond_wall

    scene = running_bond_wall(*(shape or wall_shape(n_blocks)))
    if dim == 3:
        from rigidblocks.scene.extrude import extrude

        scene = extrude(scene)
    return scene


def bare_max_load(scene, tight: bool = False) -> dict[str, Any]:
    """The plain max-load problem (see the module docstring) handed straight to Clarabel.

    ``tight``: tolerances 1e-10 instead of Clarabel's defaults (1e-8), a reference
    lambda* to judge both answers by (the time is not the floor then).

    Returns lambda*, the solver's status and iterations, the seconds to build the
    matrices (not part of the floor) and the seconds of ``DefaultSolver`` + ``solve``.
    """
    import clarabel

    from rigidblocks.equilibrium import assemble

    t0 = _now()
    d = scene.dimension
    system = assemble(scene, shear="point") if d == 2 else assemble(scene)
    c = system.contacts
    P = c.n_points
    nx = system.layout.size
    f = np.where(np.isnan(c.override_friction), scene.effective_friction,
                 c.override_friction)[c.point_joint]
    n = nx + 1
    Aeq = sp.hstack([system.A.tocsc(), sp.csc_matrix(system.live[:, None])])
    r = np.arange(P)
    t0c = system.layout.tangential.start
    nonneg = sp.coo_matrix((-np.ones(P), (r, r)), shape=(P, n))
    if d == 2:
        rows = np.concatenate([r, r, r + P, r + P])
        cols = np.concatenate([r, t0c + r, r, t0c + r])
        vals = np.concatenate([-f, np.ones(P), -f, -np.ones(P)])
        fric = sp.coo_matrix((vals, (rows, cols)), shape=(2 * P, n))
        cones = [clarabel.ZeroConeT(system.n_rows), clarabel.NonnegativeConeT(3 * P)]
    else:
        rows = np.concatenate([3 * r, 3 * r + 1, 3 * r + 2])
        cols = np.concatenate([r, t0c + 2 * r, t0c + 2 * r + 1])
        vals = np.concatenate([-f, -np.ones(P), -np.ones(P)])
        fric = sp.coo_matrix((vals, (rows, cols)), shape=(3 * P, n))
        cones = [clarabel.ZeroConeT(system.n_rows), clarabel.NonnegativeConeT(P)] + \
            [clarabel.SecondOrderConeT(3)] * P
    A = sp.vstack([Aeq, nonneg, fric], format="csc")
    b = np.concatenate([-system.dead, np.zeros(A.shape[0] - system.n_rows)])
    cvec = np.zeros(n)
    cvec[-1] = -1.0
    Pm = sp.csc_matrix((n, n))
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    if tight:
        settings.tol_gap_abs = settings.tol_gap_rel = settings.tol_feas = 1e-10
    t_build = _now() - t0
    t0 = _now()
    sol = clarabel.DefaultSolver(Pm, cvec, A, b, cones, settings).solve()
    t_solve = _now() - t0
    return {"lambda": float(sol.x[-1]), "raw_status": str(sol.status).split(".")[-1],
            "iterations": int(sol.iterations), "build": t_build, "solve": t_solve,
            "variables": n, "constraints": int(A.shape[0])}


def _maxrss_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def run_case(spec: dict[str, Any]) -> dict[str, Any]:
    """One measurement (kind ``ours``, ``bare``, ``stages`` or ``cvxpy``) on a scene file."""
    from rigidblocks.io.scene_file import read_scene

    kind, path = spec["kind"], spec["path"]
    _clock[0] = spec.get("clock", "cpu")
    base_mem = _maxrss_mib()
    out: dict[str, Any] = {**spec}
    if kind in ("bare", "reference"):
        scene = read_scene(path)
        out.update(bare_max_load(scene, tight=kind == "reference"))
    elif kind == "stages":
        out["seconds"] = non_solver_stages(path)
    else:
        from rigidblocks.analyses import check, max_load_multiplier, min_friction

        t: dict[str, float] = {}
        t0 = _now()
        scene = read_scene(path)
        t["read"] = _now() - t0
        a = spec["analysis"]
        kw: dict[str, Any] = dict(spec.get("options", {}))
        # the minimum-friction request: rtol None is the analysis' default
        mf = {"rtol": 1e-6, "load_factor": MF_LOAD_FACTOR, **spec.get("mf", {})}
        if kind == "cvxpy":
            kw["solver"] = "cvxpy-CLARABEL"
        if a == "check":
            res = check(scene, **kw)
        elif a == "min_friction":
            res = min_friction(scene, **mf, **kw)
        elif a == "min_friction_no_state":
            res = min_friction(scene, state=False, **mf, **kw)
        elif a == "max_load_no_state":
            res = max_load_multiplier(scene, state=False, **kw)
        else:
            res = max_load_multiplier(scene, **kw)
        total = _now() - t0
        # the analysis' own stage timings (contacts, assembly, build, solve: the back
        # end's whole call; state: post-processing, counted under "results")
        stages = res.timings if _clock[0] == "wall" else res.cpu_timings
        t.update({k: v for k, v in stages.items() if k in STAGES})
        t["results"] = total - sum(v for k, v in t.items() if k != "results")
        out["seconds"] = {s: t.get(s, 0.0) for s in STAGES}
        out["total"] = total
        out.update(status=res.status, n_solves=res.n_solves, iterations=res.iterations,
                   answer=_answer(res), notes=list(res.notes),
                   bracket=list(getattr(res, "bracket", None) or []),
                   accuracy=getattr(res, "accuracy", None))
        if a.startswith("min_friction") and out["answer"]:
            # the floor at the answer, same process: the plain max-load problem at f*
            # (its lambda* is the load factor, up to the solver's accuracy)
            at = bare_max_load(dataclasses.replace(scene, friction=out["answer"]))
            out["bare_at_answer"] = at["solve"]
            out["bare_at_answer_lambda"] = at["lambda"]
            out["bare_at_answer_iterations"] = at["iterations"]
    out["peak_mib"] = _maxrss_mib()
    out["base_mib"] = base_mem
    return out


def _answer(res) -> float | None:
    for attr in ("load_multiplier", "friction_factor"):
        v = getattr(res, attr, None)
        if v is not None:
            return float(v)
    if hasattr(res, "admissible"):
        return float(bool(res.admissible))
    return None


def non_solver_stages(path: str) -> dict[str, float]:
    """Read, contacts, assembly, the three builds of max_load_multiplier's path and the
    result post-processing (mechanism and force state of a dummy solution), no solve."""
    from rigidblocks.contacts import detect_contacts
    from rigidblocks.equilibrium import assemble, force_state, mechanism
    from rigidblocks.io.scene_file import read_scene
    from rigidblocks.problems.formulation import (
        Scaling,
        build_energy_qp,
        build_max_load,
        build_relaxation,
    )

    t: dict[str, float] = {}
    t0 = _now()
    scene = read_scene(path)
    t1 = _now()
    contacts = detect_contacts(scene)
    t2 = _now()
    system = assemble(scene, contacts)
    t3 = _now()
    scaling = Scaling.of(system)
    fj = np.full(contacts.n_joints, scene.effective_friction)
    build_max_load(system, scaling, fj)
    build_relaxation(system, scaling, fj, 0.0)
    build_energy_qp(system, scaling, fj, 1.0)
    t4 = _now()
    rng = np.random.default_rng(0)
    mechanism(system, scaling.row, rng.standard_normal(system.n_rows))
    force_state(system, rng.random(system.layout.size), "dummy")
    t5 = _now()
    t.update(read=t1 - t0, contacts=t2 - t1, assembly=t3 - t2, build=t4 - t3,
             results=t5 - t4)
    return t


def run_isolated(spec: dict[str, Any], timeout: float) -> dict[str, Any]:
    """:func:`run_case` in a fresh interpreter (peak memory of that case alone), with
    when it ran (UTC) and the machine's 1-minute load average at its start and end."""
    when = {"utc": time.strftime("%Y-%m-%d %H:%M", time.gmtime()),
            "load": [round(load_average(), 2)]}

    def done(res: dict[str, Any]) -> dict[str, Any]:
        return {**res, "measured": {**when, "load": [*when["load"],
                                                     round(load_average(), 2)]}}

    try:
        proc = subprocess.run([sys.executable, __file__, "--case", json.dumps(spec)],
                              capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return done({**spec, "error": f"timeout after {timeout:.0f} s"})
    if proc.returncode != 0:
        return done({**spec, "error": proc.stderr.strip().splitlines()[-1] if proc.stderr
                     else f"exit {proc.returncode}"})
    return done(json.loads(proc.stdout.strip().splitlines()[-1]))


# -- analysis of the figures ----------------------------------------------------------------
def fit_exponent(blocks: Sequence[float], seconds: Sequence[float],
                 lo: float = 1_000, hi: float = 50_000) -> float | None:
    """Least-squares slope of log(seconds) on log(blocks) for blocks in [lo, hi]."""
    pts = [(math.log(b), math.log(s)) for b, s in zip(blocks, seconds, strict=True)
           if lo * 0.9 <= b <= hi * 1.1 and s > 0]
    if len(pts) < 2:
        return None
    x, y = np.array(pts).T
    return float(np.polyfit(x, y, 1)[0])


def summarise(cases: list[dict[str, Any]], tiny: bool) -> dict[str, Any]:
    """Ratios to the floor, agreement of the answers, exponents and the targets."""
    bare = {(c["dim"], c["target"]): c for c in cases if c["kind"] == "bare" and "error" not in c}
    ref = {(c["dim"], c["target"]): c for c in cases
           if c["kind"] == "reference" and "error" not in c}
    ours = [c for c in cases if c["kind"] == "ours" and "error" not in c]
    rows = []
    for c in ours:
        b = bare.get((c["dim"], c["target"]))
        r = {"dim": c["dim"], "blocks": c["blocks"], "analysis": c["analysis"],
             "total": c["total"], "seconds": c["seconds"], "n_solves": c["n_solves"],
             "answer": c["answer"], "status": c["status"], "peak_mib": c["peak_mib"]}
        r["non_solver_share"] = 1.0 - c["seconds"]["solve"] / c["total"]
        if c.get("bare_at_answer"):
            r["bare_at_answer"] = c["bare_at_answer"]
            r["ratio_at_answer"] = c["total"] / c["bare_at_answer"]
            r["iterations"] = c["iterations"]
        if b is not None:
            r["bare_solve"] = b["solve"]
            r["ratio"] = c["total"] / b["solve"]
            r["solver_ratio"] = c["seconds"]["solve"] / b["solve"]
            if c["analysis"].startswith("max_load") and c["answer"] is not None:
                r["bare_lambda"] = b["lambda"]
                r["rel_diff"] = abs(c["answer"] - b["lambda"]) / abs(b["lambda"])
        rf = ref.get((c["dim"], c["target"]))
        if rf is not None:
            r["ref_solve"] = rf["solve"]
            r["ratio_ref"] = c["total"] / rf["solve"]
        if rf is not None and c["analysis"].startswith("max_load") and c["answer"] is not None:
            r["ref_lambda"] = rf["lambda"]
            r["rel_err"] = abs(c["answer"] - rf["lambda"]) / abs(rf["lambda"])
            if b is not None:
                r["bare_rel_err"] = abs(b["lambda"] - rf["lambda"]) / abs(rf["lambda"])
        rows.append(r)
    stages = [c for c in cases if c["kind"] == "stages" and "error" not in c and c["dim"] == 2]
    exps: dict[str, Any] = {}
    lo = 0 if tiny else 1_000
    if stages:
        bl = [c["blocks"] for c in stages]
        for s in NON_SOLVER:
            exps[s] = fit_exponent(bl, [c["seconds"][s] for c in stages], lo=lo)
        exps["non_solver"] = fit_exponent(
            bl, [sum(c["seconds"].values()) for c in stages], lo=lo)
    for a in ANALYSES:
        sel = [r for r in rows if r["dim"] == 2 and r["analysis"] == a]
        exps[f"total:{a}"] = fit_exponent([r["blocks"] for r in sel],
                                          [r["total"] for r in sel], lo=lo)
    bsel = sorted((b for b in bare.values() if b["dim"] == 2), key=lambda b: b["blocks"])
    exps["bare_solve"] = fit_exponent([b["blocks"] for b in bsel], [b["solve"] for b in bsel],
                                      lo=lo)
    targets = {}
    at = max((r["blocks"] for r in rows if r["dim"] == 2), default=0) if tiny else None

    def pick(a):
        sel = [r for r in rows if r["dim"] == 2 and r["analysis"] == a and "ratio" in r]
        if not sel:
            return None
        want = at if tiny else TARGET_SIZE
        return min(sel, key=lambda r: abs(math.log(r["blocks"] / want)))
    for a, key in (("max_load_multiplier", "max_load_ratio"),
                   ("max_load_no_state", "max_load_ratio_no_state"),
                   ("min_friction", "min_friction_ratio"),
                   ("min_friction_no_state", "min_friction_ratio_no_state")):
        r = pick(a)
        if r is not None:
            lim = TARGETS[key.removesuffix("_no_state")]
            targets[key] = {"blocks": r["blocks"], "value": r["ratio"], "target": lim,
                            "met": r["ratio"] <= lim}
            if "ratio_ref" in r:
                targets[key + " (vs 1e-10 floor)"] = {
                    "blocks": r["blocks"], "value": r["ratio_ref"], "target": lim,
                    "met": r["ratio_ref"] <= lim}
    for a in ("min_friction", "min_friction_no_state"):
        for n, lim in MF_TARGETS.items():
            sel = [r for r in rows if r["dim"] == 2 and r["analysis"] == a
                   and "ratio_at_answer" in r and abs(math.log(r["blocks"] / n)) < 0.2]
            for r in sel:
                targets[f"{a}_ratio (at the answer)"] = {
                    "blocks": r["blocks"], "value": r["ratio_at_answer"], "target": lim,
                    "met": r["ratio_at_answer"] <= lim}
    if exps.get("non_solver") is not None:
        targets["non_solver_exponent"] = {"value": exps["non_solver"],
                                          "target": TARGETS["non_solver_exponent"],
                                          "met": exps["non_solver"] <= 1.1}
    for a in ANALYSES:
        r = pick(a)
        if r is not None:
            targets[f"non_solver_share:{a}"] = {
                "blocks": r["blocks"], "value": r["non_solver_share"],
                "target": TARGETS["non_solver_share"],
                "met": r["non_solver_share"] < TARGETS["non_solver_share"]}
    return {"rows": rows, "exponents": exps, "targets": targets}


# -- report ----------------------------------------------------------------------------------
def where_time_goes(cases: list[dict[str, Any]], summary: dict[str, Any]) -> list[str]:
    """At the largest 2D wall measured: each analysis' stages as shares of its total,
    its interior-point iterations and seconds per iteration, against the floor's; the
    exponent of the seconds per iteration of the max-load solve; and what halving the
    time would take (from these figures only)."""
    rows = [r for r in summary["rows"] if r["dim"] == 2]
    if not rows:
        return []
    top = max(r["blocks"] for r in rows)
    at = [r for r in rows if r["blocks"] == top]
    ours = {c["analysis"]: c for c in cases if c["kind"] == "ours" and "error" not in c
            and c["dim"] == 2 and c["blocks"] == top}
    bare = next((c for c in cases if c["kind"] == "bare" and "error" not in c
                 and c["dim"] == 2 and c["blocks"] == top), None)
    body = []
    for r in at:
        c = ours[r["analysis"]]
        it = c.get("iterations") or 0
        sh = {k: v / r["total"] for k, v in r["seconds"].items()}
        body.append([r["analysis"], r["total"], *[sh[k] for k in STAGES], r["n_solves"], it,
                     r["seconds"]["solve"] / it if it else "-", round(r["peak_mib"])])
    if bare is not None:
        body.append(["floor (one bare solve)", bare["solve"], *["-"] * len(STAGES), 1,
                     bare["iterations"], bare["solve"] / bare["iterations"],
                     round(bare["peak_mib"])])
    # seconds per iteration of the max-load analysis against size
    ml = sorted((c for c in cases if c["kind"] == "ours" and "error" not in c
                 and c["dim"] == 2 and c.get("analysis") == "max_load_multiplier"
                 and c.get("iterations")), key=lambda c: c["blocks"])
    p_it = fit_exponent([c["blocks"] for c in ml],
                        [c["seconds"]["solve"] / c["iterations"] for c in ml], lo=1_000)
    out = [f"### Where the time goes at {top:,} blocks (2D)", "",
           "Shares of each analysis' total; iterations: interior-point iterations of all "
           "its solves; s/it: solve seconds per iteration.", "",
           markdown_table(["analysis", "total s", *STAGES, "solves", "iterations", "s/it",
                           "peak MiB"], body), ""]
    if p_it is not None:
        out += [f"Seconds per interior-point iteration of the max-load analysis grow as "
                f"blocks^{p_it:.2f} (1,000 blocks and up): the KKT factorisation of each "
                "iteration. Halving a solve means halving its iterations (the verdicts' "
                "tolerance 1e-10 costs more iterations than the floor's default 1e-8, see "
                "the floor table) or the cost of each (the factorisation's fill); every "
                "other stage together is the `read` to `build` and `results` shares "
                "above.", ""]
    return out



def markdown(cases: list[dict[str, Any]], summary: dict[str, Any],
             extra: dict[str, Any]) -> str:
    """The README section."""
    out = ["## Scaling and overhead against the bare solver", "",
           "Running-bond walls (friction 0.6, horizontal live body force), 2D and extruded "
           f"to 3D prisms. {extra.get('clock', 'cpu').upper()} seconds per stage from the "
           "scene file to the answer; `bare` is one "
           "Clarabel solve (default settings) of the plain formulation (N, T per contact "
           "point) of the maximum load multiplier, the floor; `ratio` is our total / bare; "
           "`ratio (1e-10)` our total / the same plain solve to tolerances 1e-10 (the bare "
           "solve's lambda* is off by up to 1e-3 relative at default tolerances on the "
           "larger walls, see the floor table). "
           "min_friction to 1e-6 relative. Peak memory: maxrss of a fresh process per case.",
           ""]
    head = ["dim", "blocks", "analysis", *STAGES, "total", "solves", "bare", "ratio",
            "ratio (1e-10)", "answer", "rel. diff vs bare", "rel. err (ref)", "peak MiB"]
    body = []
    for r in sorted(summary["rows"], key=lambda r: (r["dim"], r["blocks"],
                                                   ANALYSES.index(r["analysis"]))):
        s = r["seconds"]
        body.append([r["dim"], r["blocks"], r["analysis"], *[s[k] for k in STAGES],
                     r["total"], r["n_solves"], r.get("bare_solve", "-"),
                     r.get("ratio", "-"), r.get("ratio_ref", "-"),
                     r["status"] if r["analysis"] == "check" or r["answer"] is None
                     else r["answer"],
                     r.get("rel_diff", "-"), r.get("rel_err", "-"), round(r["peak_mib"])])
    out += [markdown_table(head, body), ""]
    errs = [c for c in cases if "error" in c]
    skipped = extra.get("skipped", [])
    if errs or skipped:
        out.append("Not measured: " + "; ".join(
            [f"{c['kind']} {c.get('analysis', '')} {c['dim']}D {c['target']}: {c['error']}"
             for c in errs] + skipped) + ".")
        out.append("")
    rec = [c for c in cases if "measured" in c]
    if rec:
        utc = sorted(c["measured"]["utc"] for c in rec)
        load = [x for c in rec for x in c["measured"]["load"]]
        if len(rec) == len(cases):
            out.append(f"Run from {utc[0]} to {utc[-1]} UTC, 1-minute load average "
                       f"{min(load):g} to {max(load):g}.")
        else:
            out.append("Cases whose time was recorded (UTC; 1-minute load average at their "
                       "start and end): " + "; ".join(
                           f"{c['kind']} {c.get('analysis', '')} {c['dim']}D "
                           f"{c['target']}: {c['measured']['utc']}, load "
                           f"{c['measured']['load'][0]:g} to {c['measured']['load'][-1]:g}"
                           for c in rec) + "; the others ran earlier, in one run.")
        out.append("")
    mf = [r for r in sorted(summary["rows"], key=lambda r: (r["dim"], r["blocks"]))
          if r["analysis"].startswith("min_friction") and "ratio_at_answer" in r]
    if mf:
        out += ["### Minimum friction against the floor at the answer", "",
                f"Load factor {MF_LOAD_FACTOR:g} (the live load at full value). `floor at f*`: "
                "one bare Clarabel solve (default settings) of the plain max-load problem "
                "with the friction set to our f*, in the same process right after our "
                "analysis; `ratio`: our total / that solve. `solves`: every solve (the "
                "relaxations at f = infinity and 0, the max-load LPs of the Newton steps "
                "on lambda*(f) = 1, the relaxation under the dead load alone at f*, the "
                "force-state QP where one is computed); `it/solve`: interior-point "
                "iterations per solve.", "",
                markdown_table(
                    ["dim", "blocks", "analysis", "f*", "solves", "iterations", "it/solve",
                     "solve s", "total s", "floor at f*", "ratio"],
                    [[r["dim"], r["blocks"], r["analysis"], r["answer"], r["n_solves"],
                      r["iterations"], r["iterations"] / max(1, r["n_solves"]),
                      r["seconds"]["solve"], r["total"], r["bare_at_answer"],
                      r["ratio_at_answer"]] for r in mf]), ""]
    bare = sorted((c for c in cases if c["kind"] == "bare" and "error" not in c),
                  key=lambda c: (c["dim"], c["blocks"]))
    refs = {(c["dim"], c["target"]): c for c in cases
            if c["kind"] == "reference" and "error" not in c}
    out += ["### The floor", "",
            "`lambda* (1e-10)`: the same plain problem solved to tolerances 1e-10, the "
            "reference for the relative errors above.", "", markdown_table(
                ["dim", "blocks", "variables", "constraints", "iterations", "status",
                 "lambda*", "solve s", "peak MiB", "lambda* (1e-10)", "rel. err"],
                [[c["dim"], c["blocks"], c["variables"], c["constraints"], c["iterations"],
                  c["raw_status"], c["lambda"], c["solve"], round(c["peak_mib"]),
                  refs[c["dim"], c["target"]]["lambda"] if (c["dim"], c["target"]) in refs
                  else "-",
                  abs(c["lambda"] / refs[c["dim"], c["target"]]["lambda"] - 1)
                  if (c["dim"], c["target"]) in refs else "-"] for c in bare]), ""]
    st = sorted((c for c in cases if c["kind"] == "stages" and "error" not in c),
                key=lambda c: (c["dim"], c["blocks"]))
    out += ["### Non-solver stages alone", "", markdown_table(
        ["dim", "blocks", *NON_SOLVER, "sum", "peak MiB"],
        [[c["dim"], c["blocks"], *[c["seconds"][k] for k in NON_SOLVER],
          sum(c["seconds"].values()), round(c["peak_mib"])] for c in st]), ""]
    ex = summary["exponents"]
    out += ["### Scaling exponents (2D, time ~ blocks^p, 1,000 to 50,000 blocks)", "",
            markdown_table(["quantity", "p"],
                           [[k, v if v is not None else "-"] for k, v in ex.items()]), ""]
    out += where_time_goes(cases, summary)
    tg = summary["targets"]
    out += ["### Targets (2D wall, 5,000 blocks unless stated)", "", markdown_table(
        ["target", "blocks", "measured", "limit", "met"],
        [[k, v.get("blocks", "1,000-50,000"), v["value"], v["target"],
          "yes" if v["met"] else "**no**"] for k, v in tg.items()]), ""]
    if extra.get("trials"):
        out += ["### Clarabel settings (max_load_multiplier without the force state, "
                f"{extra['trials'][0]['blocks']} blocks)", "", markdown_table(
                    ["settings", "total s", "solve s", "iterations", "lambda*"],
                    [[t["label"], t.get("total", "-"), t.get("seconds", {}).get("solve", "-"),
                      t.get("iterations", "-"), t.get("answer", t.get("error", "-"))]
                     for t in extra["trials"]]), ""]
    if extra.get("cvxpy"):
        out += ["### Native Clarabel against Clarabel through cvxpy "
                "(max_load_multiplier, no force state)", "", markdown_table(
                    ["blocks", "native total s", "cvxpy total s", "cvxpy / native",
                     "lambda* native", "lambda* cvxpy"],
                    [[c["blocks"], c["native"], c["cvxpy"], c["ratio"], c["lambda_native"],
                      c["lambda_cvxpy"]] for c in extra["cvxpy"]]), ""]
    if extra.get("png"):
        out += [f"![time per stage]({extra['png']})", ""]
    return "\n".join(out)


def chart(cases: list[dict[str, Any]], summary: dict[str, Any], path: Path,
          clock: str = "cpu") -> None:
    """Time per stage against blocks (2D, log-log): ours and the bare floor."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5))
    st = sorted((c for c in cases if c["kind"] == "stages" and "error" not in c
                 and c["dim"] == 2), key=lambda c: c["blocks"])
    for s in NON_SOLVER:
        ax.loglog([c["blocks"] for c in st], [max(c["seconds"][s], 1e-6) for c in st],
                  "o--", lw=1, ms=3, label=s)
    for a, style in (("max_load_multiplier", "s-"), ("max_load_no_state", "^-"),
                     ("min_friction", "d-"), ("min_friction_no_state", "D-"),
                     ("check", "v-")):
        sel = sorted((r for r in summary["rows"] if r["dim"] == 2 and r["analysis"] == a),
                     key=lambda r: r["blocks"])
        if sel:
            ax.loglog([r["blocks"] for r in sel], [r["total"] for r in sel], style, lw=2,
                      label=f"ours: {a} total")
    bare = sorted((c for c in cases if c["kind"] == "bare" and "error" not in c
                   and c["dim"] == 2), key=lambda c: c["blocks"])
    if bare:
        ax.loglog([c["blocks"] for c in bare], [c["solve"] for c in bare], "k*-", lw=2,
                  ms=9, label="bare Clarabel solve (floor)")
    ref = sorted((c for c in cases if c["kind"] == "reference" and "error" not in c
                  and c["dim"] == 2), key=lambda c: c["blocks"])
    if ref:
        ax.loglog([c["blocks"] for c in ref], [c["solve"] for c in ref], "k*:", lw=1.5,
                  ms=7, label="bare solve, tolerances 1e-10")
    ax.set_xlabel("blocks (2D running-bond wall)")
    ax.set_ylabel(f"{clock} seconds")
    ax.set_title("Time per stage and in all, against the bare solver")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# -- driver -----------------------------------------------------------------------------------
def plan(tiny: bool, sizes2d: Sequence[int], stage_sizes: Sequence[int],
         sizes3d: Sequence[int]) -> tuple[list[dict[str, Any]], list[str]]:
    """The cases to run (without paths) and the combinations left out on purpose."""
    specs: list[dict[str, Any]] = []
    skipped: list[str] = []
    for n in stage_sizes:
        specs.append({"kind": "stages", "dim": 2, "target": n})
    for dim, sizes in ((2, sizes2d), (3, sizes3d)):
        for n in sizes:
            specs.append({"kind": "bare", "dim": dim, "target": n})
            if tiny or n <= LIMITS["reference"][dim]:
                specs.append({"kind": "reference", "dim": dim, "target": n})
            else:
                skipped.append(f"reference (1e-10) {dim}D {n}")
            for a in ANALYSES:
                if a.endswith("_no_state") and dim == 3:
                    continue
                if not tiny and n > LIMITS[a][dim]:
                    skipped.append(f"{a} {dim}D {n}")
                    continue
                specs.append({"kind": "ours", "dim": dim, "target": n, "analysis": a})
    return specs, skipped


def target(walls: str, rtol: float | None, timeout: float, out: str | None) -> dict[str, Any]:
    """f* (without and with the force state) on the walls ``COURSESxBLOCKS@LOADFACTOR,...``
    at ``rtol`` (None: the analysis' default), each in a fresh process with one bare
    Clarabel solve of the plain problem at its answer in the same process; written to
    bench_scaling_target.{json,md}."""
    from rigidblocks.io.scene_file import write_scene

    cases = []
    with tempfile.TemporaryDirectory() as tmp:
        for item in walls.split(","):
            shape, _, lf = item.partition("@")
            courses, per = (int(v) for v in shape.split("x"))
            scene = make_scene(2, 0, (courses, per))
            path = Path(tmp) / f"wall_{courses}x{per}.json"
            write_scene(scene, path)
            for a in ("min_friction_no_state", "min_friction"):
                spec = {"kind": "ours", "dim": 2, "target": len(scene.blocks), "path": str(path),
                        "blocks": len(scene.blocks), "shape": [courses, per], "analysis": a,
                        "mf": {"rtol": rtol, "load_factor": float(lf or 1.0)}}
                res = run_isolated(spec, timeout)
                print(json.dumps({k: res.get(k) for k in ("analysis", "blocks", "status",
                                                          "answer", "total", "bare_at_answer",
                                                          "error")}, default=float),
                      file=sys.stderr, flush=True)
                cases.append(res)
    write_results(out, f"{NAME}_target", {"cases": cases}, target_markdown(cases))
    return {"cases": cases}


def target_markdown(cases: list[dict[str, Any]]) -> str:
    """The table of :func:`target`'s cases."""
    rows = [[c["blocks"], f"{c['shape'][0]} x {c['shape'][1]}", c["mf"]["load_factor"],
             c["mf"]["rtol"] or "default", c["analysis"].replace("min_friction", "f*"),
             c.get("status", c.get("error")),
             f"{c['answer']:.7g}" if c.get("answer") is not None else "-",
             " - ".join(f"{v:.7g}" for v in c.get("bracket") or []),
             c.get("accuracy"), c.get("n_solves"), c.get("iterations"), c.get("total"),
             c.get("bare_at_answer"), c.get("bare_at_answer_iterations"),
             f"{c['bare_at_answer_lambda']:.7g}" if c.get("bare_at_answer_lambda") else "-",
             c["total"] / c["bare_at_answer"] if c.get("bare_at_answer") else "-",
             round(c.get("peak_mib", 0)), " - ".join(str(v) for v in c["measured"]["load"]),
             c["measured"]["utc"]] for c in cases]
    md = "\n".join([
        "## f* on large walls against one bare solve at the answer", "",
        "CPU seconds, one thread, each case in a fresh process; `bare` is one Clarabel "
        "solve (default settings) of the plain max-load problem at the answer, in the "
        "same process (the ratio: our total over it; `bare lambda*` its multiplier at "
        "the answer, where the load factor is carried); load: 1-minute load average at the "
        "case's start and end.", "",
        markdown_table(["blocks", "wall", "load factor", "rtol", "analysis", "status",
                        "f*", "bracket", "accuracy", "solves", "iterations", "total s",
                        "bare s", "bare iterations", "bare lambda*", "ratio", "peak MiB",
                        "load", "UTC"],
                       rows)])
    return md


def _key(spec: dict[str, Any]) -> str:
    return json.dumps({k: spec.get(k) for k in ("kind", "dim", "target", "analysis",
                                                 "options", "clock")}, sort_keys=True)


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    """Run the benchmark; write bench_scaling.{json,md,png}; return the figures."""
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default=None, help="results folder (default benchmarks/results)")
    p.add_argument("--tiny", action="store_true", help="tiny sizes, in process (seconds)")
    p.add_argument("--sizes2d", type=int, nargs="+", default=None)
    p.add_argument("--stage-sizes", type=int, nargs="+", default=None)
    p.add_argument("--sizes3d", type=int, nargs="*", default=None)
    p.add_argument("--timeout", type=float, default=900.0, help="seconds per case")
    p.add_argument("--no-extras", action="store_true",
                   help="skip the Clarabel settings trials and the cvxpy comparison")
    p.add_argument("--clock", choices=sorted(CLOCKS), default="cpu",
                   help="cpu: CPU seconds of the process (default); wall: wall-clock")
    p.add_argument("--resume", action="store_true",
                   help="reuse the cases already in RESULTS/bench_scaling.cases.jsonl")
    p.add_argument("--cached-only", action="store_true",
                   help="with --resume: report the cached cases, run nothing new")
    p.add_argument("--case", help=argparse.SUPPRESS)
    p.add_argument("--target", default=None, metavar="CxB@LF,...",
                   help="only f* on these running-bond walls (courses x blocks per course "
                        "@ load factor) against a bare solve at the answer: "
                        "bench_scaling_target.{json,md}")
    p.add_argument("--target-rtol", type=float, default=None,
                   help="with --target: the requested accuracy (default: the analysis')")
    args = p.parse_args(argv)
    if args.target:
        return target(args.target, args.target_rtol, args.timeout, args.out)
    if args.case:
        res = run_case(json.loads(args.case))
        print(json.dumps(res, default=float))
        return res
    from rigidblocks.io.scene_file import write_scene

    tiny = args.tiny
    sizes2d = args.sizes2d or (TINY_2D if tiny else SIZES_2D)
    stage_sizes = args.stage_sizes or (TINY_2D if tiny else STAGE_SIZES_2D)
    sizes3d = args.sizes3d if args.sizes3d is not None else (TINY_3D if tiny else SIZES_3D)
    specs, skipped = plan(tiny, sizes2d, stage_sizes, sizes3d)
    d = out_dir(args.out)
    cache_path = d / f"{NAME}.cases.jsonl"
    cache: dict[str, dict[str, Any]] = {}
    if args.resume and cache_path.exists():
        for line in cache_path.read_text().splitlines():
            c = json.loads(line)
            cache[_key(c)] = c
    elif not tiny:
        cache_path.write_text("")

    def runner(spec: dict[str, Any]) -> dict[str, Any]:
        spec = {**spec, "clock": args.clock}
        if _key(spec) in cache:
            return cache[_key(spec)]
        if args.cached_only:
            return {**spec, "error": "not run (time budget)"}
        res = run_case(spec) if tiny else run_isolated(spec, args.timeout)
        if not tiny:
            with cache_path.open("a") as fh:
                fh.write(json.dumps(res, default=float) + "\n")
        return res

    cases: list[dict[str, Any]] = []
    extra: dict[str, Any] = {"skipped": skipped, "clock": args.clock}
    small = [s for s in specs if s["kind"] == "stages" or s["target"] <= BIG[s["dim"]]]
    big = [s for s in specs if s not in small]
    with tempfile.TemporaryDirectory() as tmp:
        paths: dict[tuple[int, int], tuple[str, int]] = {}

        def scene_path(dim: int, n: int) -> tuple[str, int]:
            if (dim, n) not in paths:
                scene = make_scene(dim, n)
                path = Path(tmp) / f"wall{dim}d_{n}.json"
                write_scene(scene, path)
                paths[dim, n] = (str(path), len(scene.blocks))
            return paths[dim, n]

        def run_all(todo: list[dict[str, Any]]) -> None:
            for s in todo:
                path, nb = scene_path(s["dim"], s["target"])
                t0 = time.perf_counter()
                res = runner({**s, "path": path, "blocks": nb})
                print(f"{s['kind']:>9} {s.get('analysis', ''):>20} {s['dim']}D {nb:>6} "
                      f"blocks: {time.perf_counter() - t0:8.2f} s {res.get('error', '')}",
                      file=sys.stderr, flush=True)
                cases.append(res)

        run_all(small)
        if not tiny and not args.no_extras:
            extra["trials"] = []
            if TARGET_SIZE in sizes2d:
                path, nb = scene_path(2, TARGET_SIZE)
                base = next((c for c in cases if c["kind"] == "ours" and c["dim"] == 2
                             and c["target"] == TARGET_SIZE and "error" not in c
                             and c.get("analysis") == "max_load_no_state"), None)
                if base is not None:
                    extra["trials"].append({"label": "default (presolve on, qdldl)", **base})
                for label, st in TRIALS.items():
                    r = runner({"kind": "ours", "dim": 2, "target": TARGET_SIZE, "path": path,
                                "blocks": nb, "analysis": "max_load_no_state",
                                "options": {"settings": st}})
                    extra["trials"].append({"label": label, **r})
            extra["cvxpy"] = []
            for n in CVXPY_SIZES:
                if n not in sizes2d:
                    continue
                path, nb = scene_path(2, n)
                spec = {"dim": 2, "target": n, "path": path, "blocks": nb,
                        "analysis": "max_load_no_state"}
                nat = next((c for c in cases if c["kind"] == "ours" and c["dim"] == 2
                            and c["target"] == n and c.get("analysis") == "max_load_no_state"
                            and "error" not in c), None)
                cv = runner({**spec, "kind": "cvxpy"})
                if nat is None or "error" in cv:
                    continue
                extra["cvxpy"].append({"blocks": nb, "native": nat["total"],
                                       "cvxpy": cv["total"], "ratio": cv["total"] / nat["total"],
                                       "lambda_native": nat["answer"],
                                       "lambda_cvxpy": cv["answer"]})
        run_all(big)
    summary = summarise(cases, tiny)
    png = d / f"{NAME}.png"
    chart(cases, summary, png, args.clock.upper())
    extra["png"] = png.name
    data = {"tiny": tiny, "clock": args.clock, "cases": cases, **summary, "extras": extra}
    write_results(args.out, NAME, data, markdown(cases, summary, extra))
    return data


if __name__ == "__main__":
    main(sys.argv[1:])
    sys.exit(0)
