"""rigidblocks against compas_cra (the peer) on the same structures: verdicts, forces, time.

The question both tools answer is the static one: is there an admissible equilibrium of
the blocks under self-weight (compression-only contacts, Coulomb friction)? The peer
(Kao et al., "Coupled rigid-block analysis: stability-aware design of complex
discrete-element assemblies", CAD 2022, doi:10.1016/j.cad.2022.103216) offers

- RBE, rigid-block equilibrium (its Eq. 6): a quadratic program over per-vertex forces
  with a heavily penalised tensile part (weight 1e6) and friction as an 8-facet pyramid
  whose facets are at distance f N from the axis (the pyramid circumscribes the cone).
  Its verdict here: admissible when the penalised tension is below 1e-4 of the total
  compression (``RBE_TENSION_TOL``), inadmissible otherwise or when IPOPT fails.
- CRA, coupled rigid-block analysis (its Eq. 11): forces and small displacements with
  complementarity, non-associative friction. Its verdict: admissible when IPOPT
  converges, inadmissible when it reports the problem infeasible.

Ours: :func:`rigidblocks.check` with ``load_factor=0`` (self-weight only) on the 2D
scene where the structure is planar, on its extrusion (:func:`rigidblocks.scene.extrude`)
with the exact second-order Coulomb cone, and on the extrusion with an inscribed
8-facet pyramid (``pyramid=8``, the peer's facet count).

Structures: semicircular arches on abutments (radial joints, t/R = 0.15, 10-100
voussoirs, straight intrados and extrados per voussoir so both tools see the same
polyhedra), running-bond walls on a foundation of about 10-1,000 blocks, and the peer's
own sample assemblies (run by the peer; by us too where their blocks are convex). The
wall's foundation is cut, for the peer only, into one fixed piece under each
bottom-course block: the peer's interface search looks for contacts among the ``nmax``
nearest block centroids only, and would miss most of a long foundation; fixed pieces
change nothing in the mechanics.

Times: from blocks to verdict. Ours: the whole ``check`` call (contacts, assembly,
problem, solve) and its solve alone; the peer's: building the assembly, its interface
detection, and its solve (``times`` in the runner's output), each peer run in its own
process under a time limit (``peer_runner.py``, run with the peer's Python:
``--peer-python``, else ``RIGIDBLOCKS_PEER_PYTHON``, else ``/work/venv-peer/bin/python``;
``none`` skips the peer).

    python benchmarks/bench_peer.py [--tiny] [--out DIR] [--peer-python PATH]

``--redraw`` rewrites the tables and chart from an existing ``bench_peer.json``;
``--ours-only`` reruns our side of every structure of that JSON and keeps the peer's
results as they were measured (its date is kept as ``peer_date``): the peer's samples
are loaded by the peer's Python for their geometry only (no peer solve), and the force
comparisons, which need the peer's per-joint forces, are kept from the run that
measured them.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common import (  # noqa: E402
    markdown_table,
    out_dir,
    read_results,
    rewrite_results,
    write_results,
)

from rigidblocks import check  # noqa: E402
from rigidblocks.errors import InputError  # noqa: E402
from rigidblocks.generators import build  # noqa: E402
from rigidblocks.generators.walls import running_bond_wall  # noqa: E402
from rigidblocks.scene.extrude import extrude  # noqa: E402
from rigidblocks.scene.geometry import scene_size  # noqa: E402
from rigidblocks.scene.model import Scene, make_block  # noqa: E402
from rigidblocks.scene.validate import validate_scene  # noqa: E402

NAME = "bench_peer"
RUNNER = Path(__file__).resolve().parent / "peer_runner.py"
DEFAULT_PEER = "/work/venv-peer/bin/python"
RBE_TENSION_TOL = 1e-4
ARCH_T = 0.15
ARCHES = (10, 20, 50, 100)
WALLS = (10, 100, 1_000)
HARD_ARCHES = ((10, 0.2), (20, 0.2))
# CRA's displacement bound and overlap as in the peer's own sample examples (its solver
# defaults are d_bnd = 1e-3, eps = 1e-4); run on the hard arches beside the defaults
CRA_LOOSE = {"d_bnd": 0.1, "eps": 0.0}
TINY = {"arches": (10,), "walls": (10,), "hard": ((10, 0.2),), "samples": ()}
# the peer's samples with the supports, friction and interface settings of its examples
SAMPLES = (
    {"name": "cubes", "sample": "cubes.json", "supports": [0], "mu": 0.84,
     "interfaces": {"nmax": 10, "amin": 1e-2, "tmax": 1e-2}},
    {"name": "bridge", "sample": "bridge.json", "supports": [0, 1], "mu": 0.9, "d_bnd": 0.1,
     "eps": 0.0, "interfaces": {"nmax": 10, "amin": 1e-6, "tmax": 1e-4}},
    {"name": "shelf", "sample": "shelf.json", "supports": [0], "mu": 0.9, "d_bnd": 0.1,
     "eps": 1e-3, "interfaces": {"nmax": 10, "amin": 1e-6, "tmax": 1e-4}},
    {"name": "snake", "sample": "snake.json", "supports": [0], "mu": 0.7, "d_bnd": 0.1,
     "eps": 0.0, "interfaces": {"nmax": 10, "amin": 1e-4, "tmax": 1e-2}},
)
HEYMAN = ("semicircular arch, radial joints, t/R above the minimum 0.1075 "
          "(Milankovitch 1907; Heyman 1969): stands")


def wall_shape(n_blocks: int) -> tuple[int, int]:
    """(courses, blocks per course) of a roughly square wall of about ``n_blocks``."""
    courses = max(1, round(math.sqrt(n_blocks)))
    return courses, max(1, round(n_blocks / courses))


def arch_scene(voussoirs: int, thickness: float) -> Scene:
    """Semicircular arch on abutments, R = 2 m, depth 1 m, friction 0.6, 20 kN/m^3."""
    return build("arch", voussoirs=voussoirs, thickness=thickness, arc_points=1)


def _box(x0: float, x1: float, y0: float, y1: float, z0: float, z1: float) -> tuple:
    verts = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
             (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    faces = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6),
             (3, 0, 4, 7)]
    return verts, faces


def peer_blocks(scene3d: Scene, split_support: str | None = None) -> list[dict]:
    """The 3D scene's blocks for the peer runner (density = unit weight).

    ``split_support``: id of a box-shaped support to replace by one fixed piece under
    each block resting on its top face (see the module notes).
    """
    out = []
    for b in scene3d.blocks:
        w = float(b.unit_weight if b.unit_weight is not None else scene3d.effective_unit_weight)
        if b.id == split_support:
            v = np.asarray(b.vertices)
            lo, hi = v.min(axis=0), v.max(axis=0)
            for o in scene3d.blocks:
                ov = np.asarray(o.vertices)
                if o.support or abs(ov[:, 2].min() - hi[2]) > 1e-9:
                    continue
                verts, faces = _box(ov[:, 0].min(), ov[:, 0].max(), lo[1], hi[1], lo[2], hi[2])
                out.append({"id": f"{b.id}@{o.id}", "vertices": verts, "faces": faces,
                            "support": True, "density": w})
            continue
        out.append({"id": b.id, "vertices": [list(p) for p in b.vertices],
                    "faces": [list(f) for f in b.faces], "support": bool(b.support),
                    "density": w})
    return out


def structures(sizes: dict) -> list[dict]:
    """Every structure: our 2D and 3D scenes and the peer's case."""
    out = []
    for n in sizes["arches"]:
        s2 = arch_scene(n, ARCH_T)
        s3 = extrude(s2)
        out.append({"name": f"arch {n} v, t/R {ARCH_T}", "kind": "arch", "blocks": n,
                    "scene2d": s2, "scene3d": s3, "expected": "admissible", "basis": HEYMAN,
                    "peer": {"mu": 0.6, "blocks": peer_blocks(s3)}})
    for n, t in sizes["hard"]:
        s2 = arch_scene(n, t)
        s3 = extrude(s2)
        out.append({"name": f"arch {n} v, t/R {t}", "kind": "hard arch", "blocks": n,
                    "scene2d": s2, "scene3d": s3, "expected": "admissible", "basis": HEYMAN,
                    "peer": {"mu": 0.6, "blocks": peer_blocks(s3)}})
    for n in sizes["walls"]:
        courses, per = wall_shape(n)
        s2 = running_bond_wall(courses, per)
        s3 = extrude(s2)
        out.append({"name": f"wall {len(s2.blocks) - 1} blocks", "kind": "wall",
                    "blocks": len(s2.blocks) - 1, "scene2d": s2, "scene3d": s3,
                    "expected": "admissible",
                    "basis": "dry-stacked running bond on a foundation, self-weight only: "
                             "full bed joints, no horizontal force",
                    "peer": {"mu": 0.6, "blocks": peer_blocks(s3, "foundation")}})
    for case in sizes["samples"]:
        out.append({"name": f"peer sample {case['name']}", "kind": "peer sample",
                    "blocks": None, "scene2d": None, "scene3d": None, "expected": None,
                    "basis": "", "peer": dict(case)})
    return out


def joint_forces(result: Any) -> dict[tuple[str, str], float]:
    """Total normal force per joint, keyed by the sorted pair of block ids."""
    if result.state is None:
        return {}
    ids = result.contacts.block_ids
    out: dict[tuple[str, str], float] = {}
    for k, (i, j) in enumerate(result.contacts.pairs):
        key = tuple(sorted((str(ids[i]), str(ids[j]))))
        out[key] = out.get(key, 0.0) + float(result.state.joint_normal[k])
    return out


def run_ours(scene: Scene, pyramid: int | None = None, forces: bool = False,
             contact_tol: float | None = None) -> dict:
    """Time ``check`` (verdict only); with ``forces``, also the state's joint forces."""
    t0 = time.perf_counter()
    res = check(scene, load_factor=0.0, state=False, pyramid=pyramid, contact_tol=contact_tol)
    total = time.perf_counter() - t0
    out = {"verdict": res.status, "total": total, "solve": res.solve_time,
           "joints": res.contacts.n_joints}
    if contact_tol is not None:
        out["contact_tol"] = contact_tol
    if forces and res.status == "admissible":
        state = check(scene, load_factor=0.0, state=True, pyramid=pyramid,
                      contact_tol=contact_tol)
        out["forces"] = joint_forces(state)
    return out


def peer_python(arg: str | None) -> str | None:
    """The peer's interpreter, or None when disabled or missing."""
    path = arg or os.environ.get("RIGIDBLOCKS_PEER_PYTHON") or DEFAULT_PEER
    if path.lower() == "none" or not Path(path).exists():
        return None
    return path


def run_peer(python: str, case: dict, method: str, timeout: float, tmp: Path) -> dict:
    """One peer run in its own process; status "timeout" when it exceeds ``timeout`` s."""
    src, dst = tmp / "case.json", tmp / "out.json"
    src.write_text(json.dumps(case))
    dst.unlink(missing_ok=True)
    t0 = time.perf_counter()
    try:
        proc = subprocess.run([python, str(RUNNER), str(src), str(dst), method],
                              capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"method": method, "status": "timeout", "times": {"limit": timeout},
                "message": f"no answer within {timeout:g} s (stopped)", "joints": []}
    wall = time.perf_counter() - t0
    if not dst.exists():
        return {"method": method, "status": "error", "times": {}, "joints": [],
                "message": (proc.stderr or proc.stdout).strip()[-300:]}
    out = json.loads(dst.read_text())
    out["times"]["process"] = wall
    return out


def peer_verdict(out: dict) -> str:
    """admissible / inadmissible / no answer (see the module notes for RBE)."""
    st = out["status"]
    if st == "solved":
        if out["method"] != "rbe":
            return "admissible"
        comp = sum(j["fn"] for j in out["joints"])
        tens = sum(abs(j["tension"]) for j in out["joints"])
        return "admissible" if tens <= RBE_TENSION_TOL * max(comp, 1e-300) else "inadmissible"
    if st == "failed" and "nfeasib" in out.get("message", ""):
        return "inadmissible"
    return "no answer"


def compare_forces(ours: dict[tuple[str, str], float], peer: dict) -> dict | None:
    """Per-joint total normal force, ours against the peer's (compression - tension)."""
    theirs: dict[tuple[str, str], float] = {}
    for j in peer.get("joints", []):
        key = tuple(sorted(str(p).split("@")[0] for p in j["pair"]))
        theirs[key] = theirs.get(key, 0.0) + j["fn"] - j["tension"]
    common = sorted(set(ours) & set(theirs))
    if not common:
        return None
    a = np.array([ours[k] for k in common])
    b = np.array([theirs[k] for k in common])
    scale = max(np.abs(a).max(), np.abs(b).max(), 1e-300)
    return {"joints": len(common), "ours_total": float(a.sum()), "peer_total": float(b.sum()),
            "max_rel_diff": float(np.abs(a - b).max() / scale),
            "median_rel_diff": float(np.median(np.abs(a - b)) / scale)}


def sample_scene(blocks: list[dict], mu: float) -> Scene:
    """Our 3D scene of the peer's exported blocks (unit weight = its density).

    Validated like a scene file (convex polyhedra, no overlaps): a sample with a
    non-convex block raises :class:`InputError` naming it, and is reported as not
    modelled rather than analysed with wrongly oriented faces.
    """
    bl = tuple(make_block(b["id"], b["vertices"], faces=b["faces"], support=b["support"],
                          unit_weight=b["density"]) for b in blocks)
    scene = Scene(dimension=3, blocks=bl, friction=mu, unit_weight=1.0, name="peer sample")
    validate_scene(scene)
    return scene


def sample_contact_tol(scene: Scene, case: dict) -> float:
    """The peer's interface tolerance tmax (a length) as our relative contact tolerance."""
    return float(case["interfaces"]["tmax"]) / scene_size(scene)


def bench(sizes: dict, python: str | None, timeouts: dict, log=sys.stdout) -> list[dict]:
    """Run both sides on every structure; one row per structure."""
    rows = []
    with tempfile.TemporaryDirectory() as tmpd:
        tmp = Path(tmpd)
        for st in structures(sizes):
            row: dict[str, Any] = {k: st[k] for k in ("name", "kind", "blocks", "expected",
                                                      "basis")}
            small = (st["blocks"] or 0) <= 100
            ours: dict[str, Any] = {}
            if st["scene2d"] is not None:
                ours["2d"] = run_ours(st["scene2d"], forces=small)
                ours["3d_cone"] = run_ours(st["scene3d"], forces=small)
                ours["3d_pyr8"] = run_ours(st["scene3d"], pyramid=8)
            peer: dict[str, Any] = {}
            if python is not None:
                big = (st["blocks"] or 0) >= 1_000
                runs = [("rbe", "rbe", {}), ("cra", "cra", {})]
                if st["kind"] == "hard arch":
                    runs.append(("cra_d0.1", "cra", CRA_LOOSE))
                for key, method, extra in runs:
                    lim = timeouts[method + ("_big" if big else "")]
                    peer[key] = run_peer(python, {"name": st["name"], **st["peer"], **extra},
                                         method, lim, tmp)
                    peer[key]["verdict"] = peer_verdict(peer[key])
                    peer[key]["settings"] = extra
                if st["scene3d"] is None and peer["rbe"].get("blocks"):
                    try:
                        s3 = sample_scene(peer["rbe"]["blocks"], st["peer"]["mu"])
                        tol = sample_contact_tol(s3, st["peer"])
                        ours["3d_cone"] = run_ours(s3, forces=True, contact_tol=tol)
                        ours["3d_pyr8"] = run_ours(s3, pyramid=8, contact_tol=tol)
                        row["blocks"] = sum(not b["support"] for b in peer["rbe"]["blocks"])
                    except InputError as exc:
                        ours["3d_cone"] = {"verdict": f"not modelled: {exc}"}
            for m in ("2d", "3d_cone"):
                f = ours.get(m, {}).pop("forces", None)
                if f and peer.get("rbe", {}).get("status") == "solved":
                    row[f"forces_{m}_vs_rbe"] = compare_forces(f, peer["rbe"])
                if f and peer.get("cra", {}).get("status") == "solved":
                    row[f"forces_{m}_vs_cra"] = compare_forces(f, peer["cra"])
            for p in peer.values():
                p.pop("blocks", None)
                p.pop("joints", None)
                p.pop("traceback", None)
            row["ours"], row["peer"] = ours, peer
            rows.append(row)
            print(summary_line(row), file=log, flush=True)
    return rows


def summary_line(row: dict) -> str:
    """One line per structure: verdicts and total times."""
    parts = [f"{row['name']:<24}"]
    for m, r in row["ours"].items():
        parts.append(f"{m}={r['verdict']}/{r.get('total', float('nan')):.3g}s")
    for m, r in row["peer"].items():
        parts.append(f"{m}={r['verdict']}/{r['times'].get('total', float('nan')):.3g}s")
    return "  ".join(parts)


def targets(rows: list[dict]) -> dict | None:
    """The two ratios at the largest wall: peer RBE time over ours (2D, 3D cone)."""
    walls = [r for r in rows if r["kind"] == "wall" and r["peer"].get("rbe", {}).get(
        "status") == "solved"]
    if not walls:
        return None
    w = max(walls, key=lambda r: r["blocks"])
    rbe = w["peer"]["rbe"]["times"]
    o2, o3 = w["ours"]["2d"], w["ours"]["3d_cone"]
    return {"case": w["name"], "blocks": w["blocks"],
            "rbe_total_s": rbe["total"], "rbe_solve_s": rbe["solve"],
            "rbe_interfaces_s": rbe["interfaces"],
            "ours_2d_total_s": o2["total"], "ours_3d_cone_total_s": o3["total"],
            "ratio_2d_total": rbe["total"] / o2["total"],
            "ratio_2d_solve": rbe["solve"] / o2["solve"],
            "ratio_3d_total": rbe["total"] / o3["total"],
            "ratio_3d_solve": rbe["solve"] / o3["solve"],
            "ratio_2d_total_vs_rbe_solve": rbe["solve"] / o2["total"],
            "ratio_3d_total_vs_rbe_solve": rbe["solve"] / o3["total"],
            "target_2d": 20.0, "target_3d": 1.0,
            "met_2d": rbe["total"] / o2["total"] >= 20.0,
            "met_3d": rbe["total"] / o3["total"] >= 1.0}


def hard_cases(rows: list[dict]) -> list[dict]:
    """Rows for the hard-case table: the peer's answers and ours where they are tested."""
    out = []
    for r in rows:
        hard = r["kind"] == "hard arch" or (r["kind"] == "wall" and r["blocks"] >= 1_000)
        if not hard or r["expected"] is None:
            continue
        answers = [(f"rigidblocks {m}", o["verdict"], "") for m, o in r["ours"].items()]
        answers += [(f"compas_cra {p.get('method', m).upper()}" + "".join(
            f" {k}={v:g}" for k, v in p.get("settings", {}).items()), p["verdict"],
            p.get("message", "")) for m, p in r["peer"].items()]
        for method, ans, msg in answers:
            grade = ("flagged" if ans == "no answer" else
                     "right" if ans == r["expected"] else "wrong")
            out.append({"method": method, "case": r["name"], "expected": r["expected"],
                        "basis": r["basis"], "answer": ans, "grade": grade,
                        "message": msg})
    return out


def chart(rows: list[dict], path: Path) -> None:
    """Time from blocks to verdict against wall size, both tools (log-log)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    walls = sorted((r for r in rows if r["kind"] == "wall"), key=lambda r: r["blocks"])
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    n = [r["blocks"] for r in walls]
    for key, label in (("2d", "rigidblocks 2D"), ("3d_cone", "rigidblocks 3D cone"),
                       ("3d_pyr8", "rigidblocks 3D 8-pyramid")):
        ax.loglog(n, [r["ours"][key]["total"] for r in walls], "o-", label=label)
    for m, label in (("rbe", "compas_cra RBE"), ("cra", "compas_cra CRA")):
        pts = [(r["blocks"], r["peer"][m]["times"].get("total")) for r in walls
               if m in r["peer"]]
        pts = [(a, b) for a, b in pts if b is not None]
        if pts:
            ax.loglog(*zip(*pts, strict=True), "s--", label=label + " (total)")
        stops = [(r["blocks"], r["peer"][m]["times"]["limit"]) for r in walls
                 if r["peer"].get(m, {}).get("status") == "timeout"]
        if stops:
            ax.scatter(*zip(*stops, strict=True), marker="x", s=60, color="k",
                       label=f"compas_cra {m.upper()} stopped at the time limit", zorder=5)
    ax.set_xlabel("blocks (running-bond wall, self-weight)")
    ax.set_ylabel("seconds, blocks to verdict")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _v(d: dict, k: str) -> str:
    return d[k]["verdict"] if k in d else "-"


def _t(d: dict, key: str = "total") -> Any:
    x = d.get(key)
    if x is None and "limit" in d:
        return f"> {d['limit']:g} (stopped)"
    return "-" if x is None else float(x)


def markdown(rows: list[dict], tg: dict | None, hard: list[dict], python: str | None,
             data: dict | None = None) -> str:
    """The results section for benchmarks/README.md (``data``: the run's provenance)."""
    lines = ["## The peer: compas_cra", ""]
    if data and data.get("ours_date"):
        lines += [f"Two runs: the peer's results (verdicts, times, its forces) were measured "
                  f"on {data['peer_date']} (`bench_peer.py "
                  f"{' '.join(data.get('peer_argv') or [])}`); our side was rerun on "
                  f"{data['ours_date']} (`--ours-only`, the peer unchanged). The force "
                  "comparisons (in bench_peer.json), which need its per-joint forces, are those "
                  "of its run, with our forces of that date. The machine is shared and its "
                  "load differed between the two runs, so the time ratios carry that "
                  "difference too (our side alone varied by up to 2x between runs)."
                  + (f" Our side of {', '.join(data['ours_kept'])} is kept from the earlier "
                     "run (the peer's Python was not available to load them)."
                     if data.get("ours_kept") else ""), ""]
    if python is None:
        lines += ["The peer was not available in this run: our side only.", ""]
    head = ["structure", "blocks", "ours 2D", "ours 3D cone", "ours 3D 8-pyr",
            "RBE", "CRA", "ours 2D s", "ours 3D s", "RBE solve s", "RBE total s",
            "CRA total s"]
    body = []
    for r in rows:
        o, p = r["ours"], r["peer"]

        body.append([r["name"], r["blocks"] if r["blocks"] is not None else "-",
                     _v(o, "2d"), _v(o, "3d_cone"), _v(o, "3d_pyr8"), _v(p, "rbe"),
                     _v(p, "cra"), _t(o.get("2d", {})), _t(o.get("3d_cone", {})),
                     _t(p.get("rbe", {}).get("times", {}), "solve"),
                     _t(p.get("rbe", {}).get("times", {})),
                     _t(p.get("cra", {}).get("times", {}))])
    lines += [markdown_table(head, body), ""]
    if tg:
        lines += [f"Targets at the {tg['case']} (blocks to verdict, peer RBE total "
                  f"{tg['rbe_total_s']:.3g} s of which solve {tg['rbe_solve_s']:.3g} s):",
                  f"- 2D model >= 20x faster than its RBE: {tg['ratio_2d_total']:.3g}x "
                  f"(solve only {tg['ratio_2d_solve']:.3g}x): "
                  f"{'met' if tg['met_2d'] else 'NOT met'}",
                  f"- 3D exact cone at least as fast as its RBE: {tg['ratio_3d_total']:.3g}x "
                  f"(solve only {tg['ratio_3d_solve']:.3g}x): "
                  f"{'met' if tg['met_3d'] else 'NOT met'}",
                  f"- without the peer's interface detection ({tg['rbe_interfaces_s']:.3g} s), "
                  f"its RBE solve alone against our whole check: 2D "
                  f"{tg['ratio_2d_total_vs_rbe_solve']:.3g}x, 3D cone "
                  f"{tg['ratio_3d_total_vs_rbe_solve']:.3g}x", ""]
    if hard:
        lines += ["Hard cases:", "", markdown_table(
            ["method", "case", "expected", "answer", "grade"],
            [[h["method"], h["case"], h["expected"], h["answer"], h["grade"]]
             for h in hard]), ""]
    samples = [r for r in rows if r["kind"] == "peer sample" and "3d_cone" in r["ours"]]
    if samples:
        lines += ["The peer's samples as convex polyhedra in our 3D model: joints found by "
                  "our contact detection (tolerance: the peer's tmax over the scene size; "
                  "a sample with a non-convex block is not modelled) against the peer's "
                  "interfaces "
                  "(its tolerances tmax of 1e-4 to 1e-2, several interfaces per pair on "
                  "curved or stepped contacts): " + "; ".join(
                      f"{r['name'].split()[-1]} {r['ours']['3d_cone'].get('joints', '-')} vs "
                      f"{r['peer'].get('rbe', {}).get('n_interfaces', '-')}"
                      for r in samples)
                  + ". Where these differ the verdicts compare different models, not "
                  "methods.", ""]
    loose = [h for h in hard if "d_bnd" in h["method"]]
    if loose:
        lines += ["CRA's verdict on the arches depends on its displacement bound: with its "
                  "solver defaults (d_bnd = 0.001, eps = 0.0001) it answers "
                  + ", ".join(sorted({h["answer"] for h in hard
                                      if h["method"] == "compas_cra CRA"
                                      and h["case"].startswith("arch")}))
                  + "; with the bound of its own examples (d_bnd = 0.1, eps = 0) it answers "
                  + ", ".join(sorted({h["answer"] for h in loose})) + ".", ""]
    lines += ["RBE counts as admissible when its penalised tension is below "
              f"{RBE_TENSION_TOL:g} of the total compression; its 8-facet pyramid "
              "circumscribes the Coulomb cone, ours (`pyramid=8`) is inscribed. Time limits "
              "stop peer runs that take too long (see bench_peer.json)."]
    return "\n".join(lines)


def sample_blocks(python: str, case: dict) -> list[dict]:
    """The peer's sample assembly as polyhedra, loaded by the peer's Python (no solve)."""
    code = ("import json, sys; sys.path.insert(0, sys.argv[1]); import peer_runner as p; "
            "a, k = p.load_sample(json.loads(sys.argv[2])); "
            "print(json.dumps(p.export_blocks(a, k)))")
    proc = subprocess.run([python, "-c", code, str(RUNNER.parent), json.dumps(case)],
                          capture_output=True, text=True, timeout=300, check=True)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def structure_named(name: str) -> dict:
    """The structure of :func:`structures` called ``name`` (only that one is built)."""
    empty: dict = {"arches": (), "walls": (), "hard": (), "samples": ()}
    candidates = ([("arches", n) for n in ARCHES] + [("hard", h) for h in HARD_ARCHES]
                  + [("samples", c) for c in SAMPLES] + [("walls", n) for n in WALLS])
    for key, item in candidates:
        if key == "arches" and name != f"arch {item} v, t/R {ARCH_T}":
            continue
        if key == "hard" and name != f"arch {item[0]} v, t/R {item[1]}":
            continue
        if key == "samples" and name != f"peer sample {item['name']}":
            continue
        if key == "walls" and not name.startswith("wall "):
            continue
        st = structures({**empty, key: (item,)})[0]
        if st["name"] == name:
            return st
    raise ValueError(f"{name!r} of bench_peer.json is not a known structure")


def ours_only(out: str | Path | None, python: str | None, log=sys.stdout) -> dict:
    """Rerun our side of every structure of an existing bench_peer.json; keep the peer's.

    Structures are rebuilt from their names' sizes (arches, walls) or, for the peer's
    samples, from the blocks its Python exports; without the peer's Python a sample's
    previous our-side results are kept and marked so. Force comparisons need the peer's
    per-joint forces, which the JSON does not keep: they stay as measured before."""
    d = out_dir(out)
    data = read_results(d, NAME)
    previous = data.get("ours_date", data["date"])
    data.setdefault("peer_date", data["date"])
    data.setdefault("peer_argv", data.get("argv"))
    kept: list[str] = []
    for row in data["rows"]:
        st = structure_named(row["name"])
        ours: dict[str, Any] = {}
        if st["scene2d"] is not None:
            ours["2d"] = run_ours(st["scene2d"])
            ours["3d_cone"] = run_ours(st["scene3d"])
            ours["3d_pyr8"] = run_ours(st["scene3d"], pyramid=8)
        elif python is not None:
            try:
                s3 = sample_scene(sample_blocks(python, st["peer"]), st["peer"]["mu"])
                tol = sample_contact_tol(s3, st["peer"])
                ours["3d_cone"] = run_ours(s3, contact_tol=tol)
                ours["3d_pyr8"] = run_ours(s3, pyramid=8, contact_tol=tol)
            except InputError as exc:
                ours["3d_cone"] = {"verdict": f"not modelled: {exc}"}
        else:
            kept.append(row["name"])
            ours = {m: {**o, "kept_from": previous} for m, o in row["ours"].items()}
        for m, o in ours.items():
            old = row["ours"].get(m, {})
            if "verdict" in old and old["verdict"] != o["verdict"]:
                print(f"{row['name']} {m}: verdict {old['verdict']} -> {o['verdict']}",
                      file=log)
        row["ours"] = ours
        print(summary_line(row), file=log, flush=True)
    data["ours_date"] = time.strftime("%Y-%m-%d %H:%M %Z")
    data["ours_kept"] = kept
    data["targets"], data["hard_cases"] = targets(data["rows"]), hard_cases(data["rows"])
    data["date"] = time.strftime("%Y-%m-%d")
    pyth = data["peer_python"] if data["peer_available"] else None
    rewrite_results(d, NAME, data, markdown(data["rows"], data["targets"],
                                            data["hard_cases"], pyth, data))
    chart(data["rows"], d / f"{NAME}.png")
    return data


def redraw(out: str | Path | None) -> dict:
    """Rewrite bench_peer.md, the PNG and the targets from an existing bench_peer.json."""
    d = out_dir(out)
    data = read_results(d, NAME)
    rows = data["rows"]
    data["targets"], data["hard_cases"] = targets(rows), hard_cases(rows)
    python = data["peer_python"] if data["peer_available"] else None
    rewrite_results(d, NAME, data, markdown(rows, data["targets"], data["hard_cases"],
                                            python, data))
    chart(rows, d / f"{NAME}.png")
    return data


def main(argv: Sequence[str] | None = None) -> dict:
    """Run the comparison, write bench_peer.{json,md,png}; return the results."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="results folder")
    parser.add_argument("--tiny", action="store_true", help="smallest sizes only")
    parser.add_argument("--peer-python", default=None,
                        help="the peer's Python ('none': our side only)")
    parser.add_argument("--rbe-timeout", type=float, default=300.0)
    parser.add_argument("--cra-timeout", type=float, default=150.0)
    parser.add_argument("--big-cra-timeout", type=float, default=600.0,
                        help="time limit of CRA on the 1,000-block wall")
    parser.add_argument("--redraw", action="store_true",
                        help="rewrite the tables and chart from the existing JSON")
    parser.add_argument("--ours-only", action="store_true",
                        help="rerun our side of the existing JSON's structures, keep the "
                             "peer's results as measured")
    args = parser.parse_args(argv)
    if args.redraw:
        return redraw(args.out)
    if args.ours_only:
        return ours_only(args.out, peer_python(args.peer_python))
    sizes = dict(TINY) if args.tiny else {"arches": ARCHES, "walls": WALLS,
                                          "hard": HARD_ARCHES, "samples": SAMPLES}
    python = peer_python(args.peer_python)
    if python is None:
        print("peer unavailable: our side only", file=sys.stderr)
    timeouts = {"rbe": args.rbe_timeout, "cra": args.cra_timeout,
                "rbe_big": args.rbe_timeout, "cra_big": args.big_cra_timeout}
    rows = bench(sizes, python, timeouts)
    tg, hard = targets(rows), hard_cases(rows)
    data = {"peer_available": python is not None, "peer_python": python,
            "peer_version": next((p.get("version") for r in rows
                                  for p in r["peer"].values() if p.get("version")), None),
            "timeouts_s": timeouts, "rbe_tension_tol": RBE_TENSION_TOL,
            "rows": rows, "targets": tg, "hard_cases": hard}
    d = out_dir(args.out)
    write_results(d, NAME, data, markdown(rows, tg, hard, python))
    chart(rows, d / f"{NAME}.png")
    return data


if __name__ == "__main__":
    main()
