"""The tilting-table test in LMGC90 (contact dynamics): the multiplier at which an
assembly of polyhedral blocks starts to move; one case per process.

Run with the Python of an environment that has ``compas_lmgc90`` (the COMPAS binding of
LMGC90; never a dependency of rigidblocks):

    /path/to/peer/python benchmarks/lmgc90_runner.py CASE.json OUT.json

``CASE.json``: ``{"name", "mu", "blocks": [{"id", "vertices": [[x, y, z], ...],
"faces": [[i, j, k, ...], ...], "support": bool}, ...], "direction": [dx, dy, dz],
"dt", "duration", "rtol", "guess", "density", "move_tol_rel"}``, gravity along -z
(LMGC90's, g = 9.81 m/s^2). The contact law is IQS_CLB_g0 (unilateral contact, Coulomb
friction ``mu``, no dilatancy). Every support has its six velocities held at zero.

A trial at multiplier ``lam`` puts the constant force ``lam m g direction`` on each free
block (m its mass: ``density`` x volume; LMGC90 has one material, so one density) and
runs ``duration`` seconds at the time step ``dt`` from rest. The trial **moves** when
some block's centroid travels more than ``move_tol_rel`` (default 1e-5) times the
smallest free block's size over the last quarter of the run: a slip that arrests does
not count, a block that keeps going does (above the limit it accelerates, so it travels
further in the last quarter than in any earlier one). The multiplier is bracketed from ``guess``
(trials at guess times or divided by 1.03, 1.06, 1.13, 1.27, 1.6, ... until one
stands and one moves) and bisected until the bracket's width is at most ``rtol`` of
its upper end. With ``"check": [lo, hi]`` only those two trials run: "confirmed" when
lo stands and hi moves (a bracket found at another time step holds at this one).

``OUT.json``: ``{"status": "bracketed" | "no bracket" | "confirmed" | "changed" |
"error", "bracket": [lo, hi], "move_tol" (the length), "move_tol_rel", "dt", "duration",
"trials": [{"lam", "moves", "last_quarter", "third_quarter", "total", "block",
"seconds"}, ...], "steps", "seconds", "version", "message"}`` with the lengths in
the scene's units (the largest centroid displacement over the last and the third
quarter of the run and over the whole run, and the block that travelled furthest).
"""

from __future__ import annotations

import json
import math
import sys
import time
import traceback

import numpy as np

G = 9.81  # LMGC90's gravity (m/s^2), along -z


def volume(vertices: np.ndarray, faces: list[list[int]]) -> float:
    """The volume of a closed polyhedron with outward faces (divergence theorem)."""
    v = 0.0
    for f in faces:
        a = vertices[f[0]]
        for k in range(1, len(f) - 1):
            v += float(np.dot(a, np.cross(vertices[f[k]], vertices[f[k + 1]])))
    return v / 6.0


def trial(case: dict, lam: float, dt: float, duration: float) -> dict:
    """One run from rest at multiplier ``lam``: the centroids' displacements."""
    from compas_lmgc90.solver import Solver

    rho = float(case.get("density", 2000.0))
    solver = Solver(dt=dt, density=rho)
    blocks = case["blocks"]
    solver.geometry_from_v_f([{"vertices": b["vertices"], "faces": b["faces"]}
                              for b in blocks])
    solver.supports = [bool(b["support"]) for b in blocks]
    d = np.asarray(case["direction"], dtype=float)
    free = [i for i, b in enumerate(blocks) if not b["support"]]
    for i, b in enumerate(blocks):
        if b["support"]:
            solver.v_drvdof[i] = {k: np.zeros([6]) for k in range(1, 7)}
            continue
        w = rho * G * volume(np.asarray(b["vertices"], dtype=float), b["faces"])
        for k, comp in enumerate(("Fx", "Fy", "Fz")):
            if d[k] != 0.0:
                solver.apply_force(i, comp, float(lam * w * d[k]))
    solver.contact_law("IQS_CLB_g0", float(case["mu"]))
    solver.preprocess()
    n = int(round(duration / dt))
    marks = {n // 2: "half", (3 * n) // 4: "three", n: "end"}
    x0 = np.array([solver.init_coor[i] for i in free], dtype=float)
    at: dict[str, np.ndarray] = {}
    t0 = time.perf_counter()
    for k in range(1, n + 1):
        r = solver.lmgc90.compute_one_step()
        if k in marks:
            at[marks[k]] = np.array([r.bodies[i] for i in free], dtype=float)
    seconds = time.perf_counter() - t0
    solver.finalize()

    def travel(a: np.ndarray, b: np.ndarray) -> np.ndarray:
        return np.linalg.norm(b - a, axis=1)

    total = travel(x0, at["end"])
    return {"lam": lam, "last_quarter": float(travel(at["three"], at["end"]).max()),
            "third_quarter": float(travel(at["half"], at["three"]).max()),
            "total": float(total.max()), "block": blocks[free[int(total.argmax())]]["id"],
            "seconds": seconds, "steps": n}


def size(case: dict) -> float:
    """The smallest free block's smallest bounding-box side."""
    sides = [np.ptp(np.asarray(b["vertices"], dtype=float), axis=0).min()
             for b in case["blocks"] if not b["support"]]
    return float(min(sides))


def bisect(case: dict) -> dict:
    """Bracket and bisect the multiplier at which the assembly moves."""
    dt, duration = float(case.get("dt", 1e-3)), float(case.get("duration", 1.0))
    rtol = float(case.get("rtol", 1e-3))
    rel = float(case.get("move_tol_rel", 1e-5))
    tol = rel * size(case)
    trials: list[dict] = []

    def moves(lam: float) -> bool:
        t = trial(case, lam, dt, duration)
        t["moves"] = t["last_quarter"] > tol
        trials.append(t)
        return t["moves"]

    out = {"status": "no bracket", "bracket": None, "trials": trials, "move_tol": tol,
           "move_tol_rel": rel, "dt": dt, "duration": duration, "rtol": rtol}
    if case.get("check"):  # only the two ends of a bracket found before
        lo, hi = (float(x) for x in case["check"])
        same = not moves(lo) and moves(hi)
        out.update(status="confirmed" if same else "changed", bracket=[lo, hi])
        return out
    guess, ratio = float(case.get("guess", 1.0)), 1.03
    lo, hi = 0.0, math.inf
    lam = guess
    for _ in range(int(case.get("max_expand", 10))):
        if moves(lam):
            hi = lam
            lam = guess / ratio if lo == 0.0 else lam
        else:
            lo = lam
            lam = guess * ratio if hi == math.inf else lam
        if lo > 0.0 and hi < math.inf:
            break
        ratio *= ratio  # 1.03, 1.06, 1.13, 1.27, 1.6, 2.6, ...
    else:
        return out
    while hi - lo > rtol * hi:
        mid = 0.5 * (lo + hi)
        if moves(mid):
            hi = mid
        else:
            lo = mid
    out.update(status="bracketed", bracket=[lo, hi])
    return out


def main(argv: list[str]) -> int:
    """``lmgc90_runner.py CASE.json OUT.json``; exit 0 when OUT.json was written."""
    if len(argv) != 2:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    with open(argv[0]) as fh:
        case = json.load(fh)
    t0 = time.perf_counter()
    try:
        out = bisect(case)
    except Exception as exc:  # LMGC90's own error, reported rather than raised
        out = {"status": "error", "message": f"{type(exc).__name__}: {exc}"[:300],
               "traceback": traceback.format_exc()[-2000:], "trials": []}
    out["name"] = case.get("name")
    out["seconds"] = time.perf_counter() - t0
    try:
        import compas_lmgc90
        out["version"] = compas_lmgc90.__version__
    except ImportError:
        pass
    with open(argv[1], "w") as fh:
        json.dump(out, fh)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
