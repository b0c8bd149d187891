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

3. LMGC90's tilting-table test (contact dynamics, no dilatancy; benchmarks/
   lmgc90_runner.py in the peer environment, ``--lmgc90-python``) and compas_cra's CRA
   on the tilted assembly, beside our associative and non-associative multipliers, on
   single blocks, the pinched block and running-bond walls in and out of plane
   (``bench_nonassoc_lmgc90.json`` and ``.md``; skipped, with the reason, without the
   peer; ``--only lmgc90`` runs this part alone, ``--redraw`` rewrites its table).
   ``--lmgc90-case NAME``, ``--lmgc90-move-tol REL`` and ``--lmgc90-duration S`` run
   chosen cases at another threshold or run time, into ``bench_nonassoc_lmgc90_tol``.

Run as ``python benchmarks/bench_nonassoc.py [--tiny] [--out DIR]``; it writes
``bench_nonassoc.json``, ``bench_nonassoc.md`` and ``bench_nonassoc.png`` (see
benchmarks/common.py).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import shlex
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one thread: the CPU times are comparable
sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import (  # noqa: E402
    cli_process,
    markdown_table,
    out_dir,
    read_results,
    rewrite_results,
    write_results,
)

import rigidblocks as rb  # noqa: E402
from rigidblocks.generators import build  # noqa: E402
from rigidblocks.io.scene_file import scene_from_dict  # noqa: E402
from rigidblocks.scene import Scene  # noqa: E402
from rigidblocks.scene.extrude import extrude  # noqa: E402
from rigidblocks.scene.polyhedra import outward_faces  # noqa: E402

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
        a, ta = _run(rb.max_load_multiplier, scene, state=False, compare_dry=False)
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
            a = rb.max_load_multiplier(scene, state=False, compare_dry=False)
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


# -- LMGC90's tilting-table test ------------------------------------------------------
#: LMGC90 (contact dynamics, benchmarks/lmgc90_runner.py) and compas_cra run in the peer
#: environment, never in ours: ``--lmgc90-python``, else RIGIDBLOCKS_LMGC90_PYTHON,
#: else this path
LMGC90_RUNNER = Path(__file__).resolve().parent / "lmgc90_runner.py"
LMGC90_DEFAULT = "/work/venv-peer/bin/python"
#: the tilting-table test: time step (s), duration (s), bracket width (relative), and
#: the travel over the last quarter of the run that makes a trial move (relative to the
#: smallest free block)
LMGC90_DT = 1e-3
LMGC90_DURATION = 1.0
LMGC90_RTOL = 1e-3
LMGC90_MOVE_TOL = 1e-5
#: the results of runs at another threshold or duration, or of chosen cases
#: (``--lmgc90-move-tol``, ``--lmgc90-duration``, ``--lmgc90-case``), kept apart from
#: the table of the default run
LMGC90_OTHER = "bench_nonassoc_lmgc90_tol"
#: compas_cra's CRA-penalty bisected on the tilt up to this many free blocks
CRA_UP_TO = 12
#: the time steps of the pinched block's series (its bracket depends on dt)
LMGC90_DT_SERIES = (4e-3, 2e-3, 2.5e-4, 1.25e-4)
#: compas_cra's virtual-displacement bound and complementarity relaxation: those of the
#: peer's own loaded examples (snake, bridge); at its default d_bnd = 1e-3 its CRA finds
#: a block on a base at f = 0.6 tilted by atan(0.1) infeasible (CRA-penalty: atan(0.3))
CRA_SETTINGS = {"d_bnd": 0.1, "eps": 0.0}
#: the walls: (courses, blocks per course, in plane / out of plane)
LMGC90_WALLS = ((3, 3, "in_plane"), (3, 3, "out_of_plane"), (5, 5, "in_plane"),
                (5, 5, "out_of_plane"), (10, 10, "in_plane"), (10, 10, "out_of_plane"))
#: our non-associative answer on the extrusion of a 2D scene up to this many blocks
EXTRUDED_UP_TO = 30


def _rect(x0: float, y0: float, w: float, h: float) -> list[list[float]]:
    return [[x0, y0], [x0 + w, y0], [x0 + w, y0 + h], [x0, y0 + h]]


def _scene2d(blocks: list[dict], friction: float) -> Scene:
    return scene_from_dict({"format": "rigidblocks-scene", "version": 1, "dimension": 2,
                            "blocks": blocks, "unit_weight": 20.0, "friction": friction,
                            "live_body_force": [1, 0]})


def lmgc90_block(b: float, h: float, f: float) -> Scene:
    """A b x h block on a wide base under a horizontal body force."""
    return _scene2d([{"id": "base", "vertices": _rect(-1, -1, b + 2, 1), "support": True},
                     {"id": "B", "vertices": _rect(0, 0, b, h)}], f)


def lmgc90_pinched(f: float) -> Scene:
    """The unit block between a fixed base and a fixed lintel, both touching it (the
    scene of tests/conftest.py: pinched)."""
    return _scene2d([{"id": "base", "vertices": _rect(-1, -1, 3, 1), "support": True},
                     {"id": "B", "vertices": _rect(0, 0, 1, 1)},
                     {"id": "lintel", "vertices": _rect(-1, 1, 3, 1), "support": True}], f)


def lmgc90_cases(tiny: bool) -> list[dict[str, Any]]:
    """The cases: name, scene (2D ones are extruded for LMGC90), and the closed form
    with its argument where there is one."""
    cases: list[dict[str, Any]] = [
        {"name": "squat block 1 x 0.5", "scene": lmgc90_block(1.0, 0.5, 0.6),
         "closed": 0.6, "basis": "slides at lambda = f = 0.6 (tips at b/h = 2)"},
        {"name": "slender block 0.5 x 2", "scene": lmgc90_block(0.5, 2.0, 0.6),
         "closed": 0.25, "basis": "tips at lambda = b/h = 0.25 (slides at f = 0.6)"}]
    if tiny:
        return cases[:1]
    cases.append({"name": "pinched block", "scene": lmgc90_pinched(0.8), "closed": None,
                  "basis": "non-associative from the unloaded state (no pinch): "
                           "lambda = f = 0.8 (validation.md)",
                  "dt_series": LMGC90_DT_SERIES})
    for c, n, way in LMGC90_WALLS:
        if way == "in_plane":
            scene = build("wall", courses=c, blocks_per_course=n, friction=WALL_FRICTION)
            closed, basis = None, ""
        else:
            scene = build("wall3d", courses=c, blocks_per_course=n, friction=WALL_FRICTION,
                          load_direction=way)
            closed = min(WALL_FRICTION, 0.3 / (0.2 * c))
            basis = "min(f, t/H), the whole wall overturning (wall3d's notes)"
        cases.append({"name": f"wall {c} x {n} {way.replace('_', ' ')}", "scene": scene,
                      "closed": closed, "basis": basis})
    return cases


def lmgc90_python(arg: str | None) -> tuple[str | None, str]:
    """The peer interpreter that has compas_lmgc90, or None and the reason why not."""
    path = arg or os.environ.get("RIGIDBLOCKS_LMGC90_PYTHON") or LMGC90_DEFAULT
    if path.lower() == "none":
        return None, "LMGC90 part not run (--lmgc90-python none)"
    if not Path(path).exists():
        return None, f"LMGC90 part skipped: no peer Python at {path}"
    probe = subprocess.run([path, "-c", "import compas_lmgc90, compas_cra"],
                           capture_output=True, text=True)
    if probe.returncode != 0:
        return None, (f"LMGC90 part skipped: {path} cannot import compas_lmgc90 and "
                      "compas_cra (pip install compas-lmgc90 compas_cra there)")
    return path, ""


def lmgc90_blocks(scene3d: Scene) -> list[dict[str, Any]]:
    """The 3D scene's blocks as polyhedra for the peer processes, faces outward (a
    generated scene's need not be: wall3d's caps face inwards, which LMGC90 takes for a
    body of a third of the volume)."""
    w = scene3d.effective_unit_weight
    return [{"id": b.id, "vertices": [list(map(float, p)) for p in b.vertices],
             "faces": [[int(i) for i in f] for f in outward_faces(b)],
             "support": bool(b.support),
             "density": float(b.unit_weight if b.unit_weight is not None else w)}
            for b in scene3d.blocks]


def _run_peer_script(python: str, script: Path, args: list[str], case: dict,
                     tmp: Path, timeout: float) -> dict:
    src, dst = tmp / "case.json", tmp / "out.json"
    src.write_text(json.dumps(case))
    dst.unlink(missing_ok=True)
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    try:
        proc = subprocess.run([python, str(script), str(src), str(dst), *args],
                              capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return {"status": "timeout", "message": f"no answer within {timeout:g} s"}
    if not dst.exists():
        return {"status": "error", "message": (proc.stderr or proc.stdout).strip()[-300:]}
    return json.loads(dst.read_text())


def lmgc90_tilt(python: str, scene3d: Scene, guess: float, dt: float, tmp: Path,
                timeout: float, check: Sequence[float] | None = None,
                move_tol: float = LMGC90_MOVE_TOL, duration: float = LMGC90_DURATION
                ) -> dict:
    """LMGC90's bracket of the multiplier at which the scene starts to move (with
    ``check``: only whether that bracket holds at this time step)."""
    direction = [float(x) for x in scene3d.live_body_force]
    case = {"name": scene3d.name, "mu": float(scene3d.friction),
            "blocks": lmgc90_blocks(scene3d), "direction": direction, "dt": dt,
            "duration": duration, "move_tol_rel": move_tol, "rtol": LMGC90_RTOL,
            "guess": guess,
            "density": 1000.0 * scene3d.effective_unit_weight / 9.81,
            **({"check": list(check)} if check else {})}
    out = _run_peer_script(python, LMGC90_RUNNER, [], case, tmp, timeout)
    out.pop("traceback", None)
    return out


def _tilted(blocks: list[dict], lam: float, direction: Sequence[float]) -> list[dict]:
    """The blocks turned so that gravity (-z) has, in the blocks' frame, lam times the
    vertical weight along ``direction``: the tilting table (Rodrigues' rotation taking
    the unit vector of z - lam d to z)."""
    import numpy as np

    d = np.asarray(direction, dtype=float)
    u = np.array([0.0, 0.0, 1.0]) - lam * d
    u /= np.linalg.norm(u)
    z = np.array([0.0, 0.0, 1.0])
    k = np.cross(u, z)
    s, c = np.linalg.norm(k), float(u @ z)
    if s < 1e-15:
        rot = np.eye(3)
    else:
        k /= s
        kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
        rot = np.eye(3) + s * kx + (1 - c) * kx @ kx
    return [{**b, "vertices": (np.asarray(b["vertices"]) @ rot.T).tolist()} for b in blocks]


def _cra(python: str, scene3d: Scene, blocks: list[dict], lam: float, method: str,
         tmp: Path, timeout: float) -> dict:
    """One compas_cra run on the assembly tilted by atan(lam)."""
    from bench_peer import RUNNER, rbe_tension_ratio

    case = {"name": scene3d.name, "mu": float(scene3d.friction),
            "blocks": _tilted(blocks, lam, scene3d.live_body_force),
            "interfaces": {"nmax": 10, "tmax": 1e-6, "amin": 1e-6}, **CRA_SETTINGS}
    out = _run_peer_script(python, RUNNER, [method], case, tmp, timeout)
    stands = {"solved": True}.get(out.get("status"))
    if out.get("status") == "failed" and "nfeasib" in out.get("message", ""):
        stands = False
    return {"lam": lam, "method": method, "status": out.get("status"), "stands": stands,
            "tension_ratio": rbe_tension_ratio({"method": method, "joints": [], **out}),
            "seconds": out.get("times", {}).get("total")}


def cra_tilt(python: str, scene3d: Scene, guess: float, tmp: Path, timeout: float
             ) -> dict:
    """compas_cra on the tilted assembly: CRA (Kao et al. 2022, Eq. 11, complementarity
    without dilatancy; infeasible = no state stands) bisected on the tilt lam =
    tan(angle), and CRA-penalty (Eq. 14) at the bracket's ends: its penalised tension
    over its compression (its admissibility rule in bench_peer: below 1e-4)."""
    blocks = lmgc90_blocks(scene3d)
    trials: list[dict] = []

    def stands(lam: float) -> bool | None:
        trials.append(_cra(python, scene3d, blocks, lam, "cra", tmp, timeout))
        return trials[-1]["stands"]

    lo, hi, lam = 0.0, math.inf, guess
    for _ in range(8):
        v = stands(lam)
        if v is None:
            return {"status": "no answer", "trials": trials}
        lo, hi = (lam, hi) if v else (lo, lam)
        if lo > 0.0 and hi < math.inf:
            break
        lam = 2.0 * lam if v else 0.5 * lam
    else:
        return {"status": "no bracket", "trials": trials}
    while hi - lo > LMGC90_RTOL * hi:
        mid = 0.5 * (lo + hi)
        v = stands(mid)
        if v is None:
            return {"status": "no answer", "bracket": [lo, hi], "trials": trials}
        lo, hi = (mid, hi) if v else (lo, mid)
    penalty = [_cra(python, scene3d, blocks, x, "cra_penalty", tmp, timeout)
               for x in (lo, hi)]
    return {"status": "bracketed", "bracket": [lo, hi], "trials": trials,
            "penalty": penalty}


def lmgc90_ours(scene: Scene, extruded: bool) -> dict[str, Any]:
    """Our associative and non-associative multipliers (and on the extrusion)."""
    out: dict[str, Any] = {}
    a, out["assoc_seconds"] = _run(rb.max_load_multiplier, scene, state=False,
                                   compare_dry=False)
    out["assoc"], out["assoc_status"] = a.load_multiplier, a.status
    v, out["na_seconds"] = _run(rb.max_load_multiplier, scene, flow=NA, state=False)
    out["na"], out["na_status"] = v.load_multiplier, v.status
    out["na_bounds"] = list(v.load_multiplier_bounds) if v.load_multiplier_bounds else None
    if scene.dimension == 2:
        d = rb.max_load_multiplier(scene, flow=NA, method="distortion", state=False)
        out["na_distortion"], out["na_distortion_status"] = d.load_multiplier, d.status
        if extruded:
            e, out["na_3d_seconds"] = _run(rb.max_load_multiplier, extrude(scene),
                                           flow=NA, state=False)
            out["na_3d"], out["na_3d_status"] = e.load_multiplier, e.status
    return out


def _finite(x: Any) -> float | None:
    return x if isinstance(x, float) and math.isfinite(x) else None


def lmgc90_rows(python: str, tiny: bool, timeout: float, log=sys.stdout,
                done: Any = None, cases: Sequence[dict[str, Any]] | None = None,
                move_tol: float = LMGC90_MOVE_TOL, duration: float = LMGC90_DURATION
                ) -> list[dict[str, Any]]:
    """Every case (or those of ``cases``): ours, LMGC90 at dt and dt / 2 (and the
    case's series of time steps), CRA (small cases); ``done(rows)`` after each case.
    ``move_tol`` and ``duration``: the trials' threshold and run time."""
    from bench_peer import loadavg

    rows = []
    trial = {"move_tol": move_tol, "duration": duration}
    with tempfile.TemporaryDirectory() as tmpd:
        tmp = Path(tmpd)
        for case in lmgc90_cases(tiny) if cases is None else cases:
            scene = case["scene"]
            s3 = extrude(scene) if scene.dimension == 2 else scene
            free = sum(not b.support for b in scene.blocks)
            row: dict[str, Any] = {"name": case["name"], "blocks": free,
                                   "friction": float(scene.friction),
                                   "closed": case["closed"], "basis": case["basis"],
                                   "dimension": scene.dimension, **trial,
                                   "loadavg_start": loadavg()}
            row["ours"] = lmgc90_ours(scene, extruded=free <= EXTRUDED_UP_TO)
            # the first trial off our answer, so that no bracket end is ours
            guess = 1.01 * (_finite(row["ours"]["na"]) or _finite(row["ours"]["assoc"])
                            or 1.0)
            row["lmgc90"] = lmgc90_tilt(python, s3, guess, LMGC90_DT, tmp, timeout,
                                        **trial)
            # halving the time step: the bracket's two ends again, bisected anew only
            # where they no longer hold
            row["lmgc90_half"] = lmgc90_tilt(python, s3, guess, LMGC90_DT / 2, tmp, timeout,
                                             check=row["lmgc90"].get("bracket"), **trial)
            if row["lmgc90_half"].get("status") == "changed":
                row["lmgc90_half"] = lmgc90_tilt(python, s3, guess, LMGC90_DT / 2, tmp,
                                                 timeout, **trial)
            row["lmgc90_series"] = [
                {"dt": dt, "bracket": lmgc90_tilt(python, s3, guess, dt, tmp,
                                                  timeout, **trial).get("bracket")}
                for dt in case.get("dt_series", ())]
            if free <= CRA_UP_TO:
                row["cra"] = cra_tilt(python, s3, guess, tmp, timeout)
            row["loadavg_end"] = loadavg()
            rows.append(row)
            if done is not None:
                done(rows)
            print(f"{row['name']}: LMGC90 {row['lmgc90'].get('bracket')}, dt/2 "
                  f"{row['lmgc90_half'].get('bracket')}, CRA "
                  f"{row.get('cra', {}).get('bracket')}, ours {row['ours']['assoc']} / "
                  f"{row['ours']['na']}", file=log, flush=True)
    return rows


def _bracket(r: dict | None) -> str:
    if not r:
        return "-"
    b = r.get("bracket")
    if b:
        same = " (same)" if r.get("status") == "confirmed" else ""
        return f"[{b[0]:.5f}, {b[1]:.5f}]{same}"
    held = [t["lam"] for t in r.get("trials", ())
            if t.get("stands") or t.get("moves") is False]
    if r.get("status") == "no bracket" and len(held) == len(r["trials"]) > 0:
        return f"stands to {max(held):.4g}"
    return r.get("status", "-")


def _verdicts(row: dict[str, Any]) -> str:
    """Each of our non-associative multipliers against LMGC90's bracket."""
    keys = (("na", "convex"), ("na_distortion", "distortion"), ("na_3d", "extruded"))
    out = [f"{label}: {lmgc90_verdict(row, k)}" for k, label in keys
           if row["ours"].get(k) is not None]
    return "; ".join(out) if len(out) > 1 else lmgc90_verdict(row, "na")


def _first_mover(r: dict) -> str:
    """The block that travelled furthest in the trial at the bracket's upper end."""
    b = r.get("bracket")
    hit = [t for t in r.get("trials", ()) if b and t["lam"] == b[1]]
    return f"{hit[0]['block']} ({hit[0]['total']:.2g} m)" if hit else "-"


def _penalty(r: dict | None) -> str:
    p = (r or {}).get("penalty")
    if not p:
        return "-"
    return " / ".join("-" if q["tension_ratio"] is None else f"{q['tension_ratio']:.1e}"
                      for q in p)


def _tol(x: float) -> str:
    """A threshold as 1e-5, 2e-6, 1.5e-4 (two digits)."""
    if not math.isfinite(x):
        return "-"
    m, e = f"{x:.1e}".split("e")
    return f"{m.rstrip('0').rstrip('.')}e{int(e)}"


def _num(x: Any, status: str = "-") -> str:
    if x is None:
        return status
    return f"{x:.5f}" if math.isfinite(x) else "unbounded"


def _percent(gap: float) -> str:
    """A relative gap in percent, to 0.1% (0.01% below 0.05%, which would read 0.0%)."""
    return f"{gap:.1%}" if gap >= 5e-4 else f"{gap:.2%}"


def lmgc90_verdict(row: dict[str, Any], key: str) -> str:
    """Where our multiplier ``key`` lies against LMGC90's bracket (both time steps):
    inside, below (safe side) or above (unsafe side), with the relative gap."""
    x = row["ours"].get(key)
    br = [row[k].get("bracket") for k in ("lmgc90", "lmgc90_half")]
    if x is None or not all(br):
        return "-"
    lo, hi = min(b[0] for b in br), max(b[1] for b in br)
    if not math.isfinite(x):
        return "above (unbounded)"
    if x < lo:
        return f"below by {_percent((lo - x) / lo)}"
    if x > hi:
        return f"above by {_percent((x - hi) / hi)}"
    return "inside"


def lmgc90_ours_again(out: str | None) -> dict[str, Any]:
    """Our columns of bench_nonassoc_lmgc90 computed again on the current code, the
    LMGC90 and CRA brackets kept (answers, not timings: they do not depend on the run)."""
    doc = read_results(out, "bench_nonassoc_lmgc90")
    cases = {c["name"]: c for c in lmgc90_cases(tiny=False)}
    for row in doc["rows"]:
        scene = cases[row["name"]]["scene"]
        row["ours"] = lmgc90_ours(scene, extruded=row["blocks"] <= EXTRUDED_UP_TO)
        print(row["name"], row["ours"]["na"], flush=True)
    doc["ours_again"] = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    rewrite_results(out, "bench_nonassoc_lmgc90", doc,
                    lmgc90_markdown(doc["rows"], doc["skipped"], doc["ours_again"]))
    return doc


def lmgc90_markdown(rows: list[dict[str, Any]], skipped: str,
                    ours_again: str | None = None) -> str:
    md = ["## Non-associative multipliers against LMGC90's tilting-table test", ""]
    if skipped:
        return "\n".join([*md, skipped])
    if ours_again:
        md += [f"Our columns computed again on {ours_again} (`--ours-again`: the current "
               "code's answers; LMGC90's and CRA's brackets from the run whose load "
               "average is given below).", ""]
    md += [f"LMGC90 (compas_lmgc90 {rows[0]['lmgc90'].get('version', '?')}, contact law "
           "IQS_CLB_g0: unilateral contact, Coulomb friction, no dilatancy) on the "
           "polyhedral blocks (2D scenes extruded): a constant horizontal force lambda "
           "times each free block's weight, from rest, "
           f"{LMGC90_DURATION:g} s at dt = {LMGC90_DT:g} s; at dt / 2 the two ends of "
           "that bracket are run again (\"same\": the lower end stands and the upper "
           "one moves at dt / 2 too; else a new bisection at dt / 2); a trial "
           f"moves when a block's centroid travels more than {_tol(LMGC90_MOVE_TOL)} of "
           "the smallest block over the last quarter of the run (a slip that arrests "
           "does not count); "
           f"bisection to {LMGC90_RTOL:g} relative. CRA: compas_cra (Kao et al. 2022, "
           "Eq. 11, d_bnd = 0.1, eps = 0) on the assembly tilted by atan(lambda), "
           "bisected on its verdict (solved: stands; infeasible: collapses), cases up "
           f"to {CRA_UP_TO} blocks; CRA-penalty (Eq. 14): its penalised tension over its "
           "compression at the two ends of CRA's bracket. Ours: `max_load` "
           "associative, non-associative (convex path; "
           "distortion path and the extrusion for 2D scenes).", "",
           markdown_table(
               ["case", "f", "closed form", "LMGC90 dt", "LMGC90 dt/2", "CRA",
                "CRA-penalty tension",
                "ours assoc", "ours non-assoc", "distortion", "extruded", "non-assoc vs "
                "LMGC90", "LMGC90 moves first"],
               [[r["name"], r["friction"], _num(r["closed"]), _bracket(r["lmgc90"]),
                 _bracket(r["lmgc90_half"]), _bracket(r.get("cra")), _penalty(r.get("cra")),
                 _num(r["ours"]["assoc"], r["ours"]["assoc_status"]),
                 _num(r["ours"]["na"], r["ours"]["na_status"]),
                 _num(r["ours"].get("na_distortion")), _num(r["ours"].get("na_3d")),
                 _verdicts(r), _first_mover(r["lmgc90"])] for r in rows]), "",
           *[f"{r['name']}: LMGC90's bracket against the time step: " + ", ".join(
               f"dt = {x['dt']:g}: {_bracket(x)}" for x in r["lmgc90_series"]) + "."
             for r in rows if r["lmgc90_series"]], "",
           "Load average (1, 5, 15 min) at the start and end: "
           f"{rows[0]['loadavg_start']} / {rows[-1]['loadavg_end']}.", "",
           f"Chosen cases at another threshold or run time: `{LMGC90_OTHER}.md` "
           "(`--lmgc90-case`, `--lmgc90-move-tol`, `--lmgc90-duration`)."]
    return "\n".join(md)


def lmgc90_other_markdown(rows: list[dict[str, Any]]) -> str:
    """The markdown of :data:`LMGC90_OTHER`: one row per case and setting."""
    def trials(r: dict) -> str:
        return ", ".join(f"{t['lam']:.5f} {'moves' if t['moves'] else 'stands'} "
                         f"({t['last_quarter']:.2g} m)" for t in r.get("trials", ()))

    md = ["## LMGC90's tilting-table test at other thresholds and durations", "",
          "The test of `bench_nonassoc_lmgc90.md` on chosen cases, with another threshold "
          "(the travel over the last quarter of the run that makes a trial move, relative "
          "to the smallest block, and in metres) or run time; dt = "
          f"{LMGC90_DT:g} s and dt / 2 as there (\"same\": the dt bracket's ends hold at "
          "dt / 2; else a new bisection at dt / 2). Each row's command is given (run from "
          "the repository's root).", "",
          markdown_table(
              ["case", "f", "threshold", "duration (s)", "LMGC90 dt", "LMGC90 dt/2",
               "ours non-assoc", "non-assoc vs LMGC90", "load average start / end",
               "date"],
              [[r["name"], r["friction"],
                f"{_tol(r['move_tol'])} ({_tol(r['lmgc90'].get('move_tol', math.nan))} m)",
                f"{r['duration']:g}", _bracket(r["lmgc90"]), _bracket(r["lmgc90_half"]),
                _num(r["ours"]["na"], r["ours"]["na_status"]), _verdicts(r),
                f"{r['loadavg_start']} / {r['loadavg_end']}", r["date"]] for r in rows]),
          ""]
    for r in rows:
        md += [f"{r['name']}, threshold {_tol(r['move_tol'])}, {r['duration']:g} s: "
               f"`{r['command']}`; trials (lambda, verdict, largest travel over the last "
               f"quarter) at dt: {trials(r['lmgc90'])}; at dt / 2: "
               f"{trials(r['lmgc90_half'])}.", ""]
    return "\n".join(md)


def lmgc90_other(out: str | None, python: str, rows: list[dict[str, Any]]
                 ) -> dict[str, Any]:
    """Add ``rows`` to :data:`LMGC90_OTHER` (replacing earlier rows of the same case,
    threshold and duration) and write it."""
    key = lambda r: (r["name"], r["move_tol"], r["duration"])  # noqa: E731
    try:
        kept = read_results(out, LMGC90_OTHER)["rows"]
    except FileNotFoundError:
        kept = []
    new = {key(r) for r in rows}
    merged = [r for r in kept if key(r) not in new] + rows
    data = {"lmgc90_python": python, "dt": LMGC90_DT, "rtol": LMGC90_RTOL,
            "rows": merged}
    write_results(out, LMGC90_OTHER, data, lmgc90_other_markdown(merged))
    return data


def lmgc90_section(out: str | None, python_arg: str | None, tiny: bool,
                   timeout: float = 1800.0, cases: Sequence[str] | None = None,
                   move_tol: float | None = None, duration: float | None = None,
                   command: str = "") -> dict[str, Any]:
    """Run the LMGC90 comparison (or say why not) and write bench_nonassoc_lmgc90;
    with chosen ``cases`` (names), ``move_tol`` or ``duration``, add those runs (and
    the ``command`` that ran them) to :data:`LMGC90_OTHER` instead."""
    python, skipped = lmgc90_python(python_arg)
    other = bool(cases or move_tol or duration)
    if python is None and other:
        print(skipped, flush=True)  # the recorded tables are left as they are
        return {"skipped": skipped, "rows": []}
    if other:
        chosen = [c for c in lmgc90_cases(tiny) if not cases or c["name"] in cases]
        stamp = {"command": command,
                 "date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())}

        def add(rows: list[dict[str, Any]]) -> dict[str, Any]:
            return lmgc90_other(out, python, [{**r, **stamp} for r in rows])

        rows = lmgc90_rows(python, tiny, timeout, done=add, cases=chosen,
                           move_tol=move_tol or LMGC90_MOVE_TOL,
                           duration=duration or LMGC90_DURATION)
        return add(rows)

    def write(rows: list[dict[str, Any]]) -> dict[str, Any]:
        data = {"lmgc90_python": python, "skipped": skipped, "dt": LMGC90_DT,
                "duration": LMGC90_DURATION, "rtol": LMGC90_RTOL, "rows": rows}
        write_results(out, "bench_nonassoc_lmgc90", data, lmgc90_markdown(rows, skipped))
        return data

    if python is None:
        print(skipped, flush=True)
        try:  # a table measured with the peer is not replaced by "skipped"
            recorded = read_results(out, "bench_nonassoc_lmgc90")
        except (OSError, ValueError):
            recorded = {}
        if recorded.get("rows"):
            print("the recorded LMGC90 table is kept", flush=True)
            return recorded
        return write([])
    return write(lmgc90_rows(python, tiny, timeout, done=write))


#: the large walls (courses, blocks per course) at both frictions, and the largest wall
#: run by default (70 x 70 with --large-walls 5000)
LARGE_WALLS = ((10, 10), (20, 15), (32, 32), (70, 70))
#: ``--walls3d``: wall3d (courses, blocks per course, load direction), Coulomb's cones
LARGE_WALLS3D = ((20, 24, "in_plane"), (20, 24, "out_of_plane"), (32, 31, "in_plane"),
                 (32, 31, "out_of_plane"))
LARGE_FRICTIONS = (0.6, 0.8)
LARGE_UP_TO = 1100
TINY_LARGE = ((3, 3),)


def _cpu(fn: Any, *args: Any, **kw: Any) -> tuple[Any, float]:
    """fn(*args, **kw) and the CPU seconds it took (this process, one thread when the
    script runs with OMP_NUM_THREADS=1 etc., as it sets by default)."""
    t0 = time.process_time()
    r = fn(*args, **kw)
    return r, time.process_time() - t0


def _command_cpu(scene: Scene, *options: str) -> tuple[float, int]:
    """The CPU seconds (user + system) of ``rigidblocks load SCENE OPTIONS`` as a user
    runs it, one whole process (imports, contacts, the analysis, its state and the
    printed answer), and its exit code."""
    from rigidblocks.io.scene_file import write_scene

    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "wall.json"
        write_scene(scene, path)
        proc, cpu, _ = cli_process(["load", str(path), *options])
    return cpu, proc.returncode


def large_walls(sizes: Sequence[tuple], frictions: Sequence[float],
                up_to: int, friction_too: bool = True, commands: bool = True
                ) -> list[dict[str, Any]]:
    """Non-associative load and friction on running-bond walls against the associative
    load in the same run (CPU seconds): the limit iteration from X0 and from the
    associative collapse state (the spread), the friction whose answer from X0
    carries the multiplier found at f (it should give f back), and (``commands``) both
    `load` answers again as whole commands (:func:`_command_cpu`). ``sizes``: (courses,
    blocks per course) of 2D walls, or with a third item the load direction of a
    wall3d."""
    warm = build("wall", courses=2, blocks_per_course=2, friction=0.6)
    rb.max_load_multiplier(warm, state=False)  # imports and first calls out of the timing
    rb.max_load_multiplier(warm, flow=NA, state=False)
    rows = []
    for c, n, *direction in sizes:
        for f in frictions:
            if direction:
                scene = build("wall3d", courses=c, blocks_per_course=n, friction=f,
                              load_direction=direction[0])
            else:
                scene = build("wall", courses=c, blocks_per_course=n, friction=f)
            if len(scene.blocks) > up_to:
                continue
            a, ta = _cpu(rb.max_load_multiplier, scene, state=False, compare_dry=False)
            v, tv = _cpu(rb.max_load_multiplier, scene, flow=NA, state=False)
            # a start's multiplier only where its run settled (the history keeps the
            # last iterate of an undecided one)
            starts = {h.get("start"): h.get("load_factor") if h.get("converged")
                      else "undecided" for h in v.history}
            spans = {h.get("start"): h.get("span") for h in v.history}
            # True where a start ended at states of the maximum-load problem's rows
            # alone, not at the least confined one of its mechanism
            loose = {h.get("start"): not h.get("least_confined", True) for h in v.history}
            lf = v.load_multiplier if v.status == "collapse" else 0.9 * a.load_multiplier
            fr, tf = _cpu(rb.min_friction, scene, load_factor=lf, flow=NA, state=False) \
                if friction_too else (None, None)
            # the same two answers as whole `load` commands, one process each in turn
            cli_a, code_a = _command_cpu(scene) if commands else (None, None)
            cli_v, code_v = _command_cpu(scene, "--flow", NA) if commands else (None, None)
            row = {"courses": c, "per_course": n, "blocks": len(scene.blocks),
                   "wall": f"{c} x {n}" + (f" wall3d {direction[0].replace('_', ' ')}"
                                           if direction else ""),
                   "friction": f, "assoc_lambda": a.load_multiplier, "assoc_cpu": ta,
                   "na_status": v.status, "na_lambda": v.load_multiplier, "na_cpu": tv,
                   "na_from_assoc": starts.get("the associative collapse state"),
                   "na_span": spans.get("the elastic state X0"),
                   "na_from_assoc_span": spans.get("the associative collapse state"),
                   "na_loose": loose.get("the elastic state X0", False),
                   "na_from_assoc_loose": loose.get("the associative collapse state", False),
                   "load_average": os.getloadavg()[0],
                   "na_steps": v.iterations, "na_ratio": tv / ta if ta else None,
                   "friction_load_factor": lf,
                   "friction_status": fr.status if fr else "not run",
                   "na_friction": fr.friction_factor if fr else None,
                   "friction_bracket": fr.bracket if fr else None, "friction_cpu": tf,
                   "friction_ratio": tf / ta if ta and tf is not None else None,
                   "command_assoc_cpu": cli_a, "command_na_cpu": cli_v,
                   "command_exit_codes": [code_a, code_v],
                   "command_ratio": cli_v / cli_a if cli_a and cli_v is not None else None}
            rows.append(row)
            print(f"{row['wall']} f={f}: assoc {a.load_multiplier:.6g} ({ta:.2f} s), "
                  f"non-assoc {v.status} {v.load_multiplier} ({tv:.2f} s), friction "
                  f"{row['friction_status']} {row['na_friction']} ({tf} s)", flush=True)
    return rows


def large_walls_md(rows: list[dict[str, Any]]) -> list[str]:
    """The markdown of :func:`large_walls`."""
    header = ["wall", "blocks", "f", "lambda assoc", "CPU s", "lambda non-assoc (X0)",
              "its mechanism's states", "from the assoc. state", "its mechanism's states",
              "CPU s", "x assoc", "limit steps", "f non-assoc at lambda non-assoc", "CPU s",
              "x assoc", "`load` commands CPU s", "x", "load"]
    body = [[r.get("wall", f"{r['courses']} x {r['per_course']}"), r["blocks"], r["friction"],
             r["assoc_lambda"], r["assoc_cpu"], _cell(r["na_lambda"]) if r["na_status"]
             == "collapse" else r["na_status"], _span(r.get("na_span"), r.get("na_loose")),
             _cell(r["na_from_assoc"]),
             _span(r.get("na_from_assoc_span"), r.get("na_from_assoc_loose")), r["na_cpu"],
             _cell(r["na_ratio"]), r["na_steps"], _cell(r["na_friction"]) if
             r["friction_status"] == "stable" else r["friction_status"], _cell(r["friction_cpu"]),
             _cell(r["friction_ratio"]), _commands(r), _cell(r.get("command_ratio")),
             _cell(r.get("load_average"))] for r in rows]
    return ["### Running-bond walls: the limit fixed point against the associative load", "",
            "Non-associative `load` (the limit iteration from the elastic state X0, and "
            "from the associative collapse state, each ended at the collapse states of the "
            "mechanism it reaches: the answer, the nearest of them, and their range; "
            "a range marked * holds states of the maximum-load problem's rows alone, "
            "where no least confined state was reached) and "
            "`friction` at the multiplier found (f back, or a lower f where the answer "
            "from X0, not unique, carries that multiplier too; to its default accuracy, "
            "2e-3), CPU seconds in "
            "one process on one thread, with the associative `load` of the same run; "
            "then the two answers as whole `rigidblocks load` commands (the associative "
            "one, then `--flow non-associative`), one process each in turn, their CPU "
            "seconds (imports, contacts, the analysis, its state and the printed answer) "
            "and their ratio.", "",
            markdown_table(header, body)]


def _commands(r: dict[str, Any]) -> str:
    """The two `load` commands' CPU seconds, "assoc / non-assoc" (with their exit codes
    where one is not 0), or "-" in a row measured without them."""
    if r.get("command_na_cpu") is None:
        return "-"
    codes = r.get("command_exit_codes") or [0, 0]
    exits = "" if not any(codes) else f" (exit {codes[0]} / {codes[1]})"
    return f"{r['command_assoc_cpu']:.3g} / {r['command_na_cpu']:.4g}{exits}"


def _span(v: Any, loose: bool | None = False) -> str:
    """A mechanism's span of multipliers, or "-"; marked * where ``loose`` (states of
    the maximum-load problem's rows alone)."""
    return "-" if not v else f"[{v[0]:.7g}, {v[1]:.7g}]" + ("*" if loose else "")


def _cell(v: Any) -> Any:
    return "-" if v is None else v


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--tiny", action="store_true", help="smallest sizes only")
    p.add_argument("--out", default=None, help="results folder")
    p.add_argument("--lmgc90-python", default=None,
                   help="Python with compas_lmgc90 and compas_cra ('none' skips them)")
    p.add_argument("--only", choices=("walls", "lmgc90"), default=None,
                   help="run one part only")
    p.add_argument("--redraw", action="store_true",
                   help="rewrite bench_nonassoc_lmgc90.md (and "
                   f"{LMGC90_OTHER}.md) from its JSON (no runs)")
    p.add_argument("--ours-again", action="store_true",
                   help="compute our columns of bench_nonassoc_lmgc90 again, keeping "
                   "LMGC90's and CRA's brackets")
    p.add_argument("--walls3d", action="store_true",
                   help="the wall3d walls of LARGE_WALLS3D (load only), into "
                        "bench_nonassoc_walls3d")
    p.add_argument("--large-walls", type=int, default=LARGE_UP_TO,
                   help="largest wall (blocks) of the large-walls table")
    p.add_argument("--lmgc90-case", action="append", default=None, metavar="NAME",
                   help="run only this LMGC90 case (repeatable; results added to "
                   f"{LMGC90_OTHER}.json and .md; implies --only lmgc90)")
    p.add_argument("--lmgc90-move-tol", type=float, default=None, metavar="REL",
                   help="a trial moves when a centroid travels more than REL times the "
                   f"smallest block over the last quarter of the run (default "
                   f"{_tol(LMGC90_MOVE_TOL)}; results to {LMGC90_OTHER}; implies --only lmgc90)")
    p.add_argument("--lmgc90-duration", type=float, default=None, metavar="S",
                   help=f"each trial's run time in seconds (default {LMGC90_DURATION:g}; "
                   f"results to {LMGC90_OTHER}; implies --only lmgc90)")
    args = p.parse_args(argv)
    names = [c["name"] for c in lmgc90_cases(args.tiny)]
    for name in args.lmgc90_case or ():
        if name not in names:
            p.error(f"--lmgc90-case: no case {name!r} (cases: {', '.join(names)})")
    for opt in ("lmgc90_move_tol", "lmgc90_duration"):
        v = getattr(args, opt)
        if v is not None and not (math.isfinite(v) and v > 0):
            p.error(f"--{opt.replace('_', '-')}: must be a positive number, not {v:g}")
    other = {"cases": args.lmgc90_case, "move_tol": args.lmgc90_move_tol,
             "duration": args.lmgc90_duration}
    command = shlex.join(["python", "benchmarks/bench_nonassoc.py",
                          *(sys.argv[1:] if argv is None else argv)])
    if args.redraw:
        doc = read_results(args.out, "bench_nonassoc_lmgc90")
        rewrite_results(args.out, "bench_nonassoc_lmgc90", doc,
                        lmgc90_markdown(doc["rows"], doc["skipped"],
                                        doc.get("ours_again")))
        if (out_dir(args.out) / f"{LMGC90_OTHER}.json").exists():
            other_doc = read_results(args.out, LMGC90_OTHER)
            rewrite_results(args.out, LMGC90_OTHER, other_doc,
                            lmgc90_other_markdown(other_doc["rows"]))
        return {"lmgc90": doc}
    if args.ours_again:
        return {"lmgc90": lmgc90_ours_again(args.out)}
    if args.only == "lmgc90" or any(v is not None for v in other.values()):
        return {"lmgc90": lmgc90_section(args.out, args.lmgc90_python, args.tiny,
                                         command=command, **other)}
    if args.walls3d:
        rows3 = large_walls(LARGE_WALLS3D, LARGE_FRICTIONS, args.large_walls, False,
                            False)
        doc = {"walls3d": rows3, "command": command}
        write_results(args.out, "bench_nonassoc_walls3d", doc,
                      "\n".join(["## Non-associative sliding on wall3d walls (Coulomb's "
                                 "cones)", ""] + large_walls_md(rows3)[2:]))
        return doc
    large = large_walls(TINY_LARGE if args.tiny else LARGE_WALLS, LARGE_FRICTIONS,
                        args.large_walls)
    sizes = TINY_WALLS if args.tiny else WALLS
    wall_rows = walls(sizes, DISTORTION_UP_TO)
    curve = curves(TINY_STRUCTURES if args.tiny else STRUCTURES,
                   TINY_FRICTIONS if args.tiny else FRICTIONS)
    d = out_dir(args.out)
    chart(curve, d / "bench_nonassoc.png")
    header = ["wall", "blocks", "lambda assoc", "s", "lambda non-assoc (convex)", "s",
              "convex iterations", "trials", "lambda non-assoc (distortion)", "s",
              "distortion iterations"]
    rows = [[f"{r['courses']} x {r['per_course']}", r["blocks"], r["assoc_lambda"],
             r["assoc_seconds"], _cell(r["convex_lambda"]), r["convex_seconds"],
             r["convex_iterations"], r["trials"], _cell(r.get("distortion_lambda")),
             _cell(r.get("distortion_seconds")), _cell(r.get("distortion_iterations"))]
            for r in wall_rows]
    md = ["## Non-associative sliding: cost and lambda against f", "",
          f"Running-bond walls at f = {WALL_FRICTION} under a horizontal body force: the "
          "associative multiplier (one LP) against the non-associative one: on the convex "
          "path the fixed point of the capped limit problem (iterations: its limit "
          "problems; trials: its starts, the elastic state X0 and the associative "
          "collapse state), on the distortion path a bisection on the verdicts of the "
          "state its iteration with separate links reaches from X0 (iterations: "
          "distortion steps). Wall-clock seconds. `bench_nonassoc.png`: the collapse multiplier "
          "against f under both flow rules on the seed's structures (convex path).", "",
          markdown_table(header, rows), "",
          "![lambda against f](results/bench_nonassoc.png)", ""] + large_walls_md(large)
    data = {"walls": wall_rows, "curves": curve, "large_walls": large}
    write_results(args.out, "bench_nonassoc", data, "\n".join(md))
    if args.only is None:
        data["lmgc90"] = lmgc90_section(args.out, args.lmgc90_python, args.tiny)
    return data


if __name__ == "__main__":
    main()
