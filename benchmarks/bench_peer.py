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
- CRA, coupled rigid-block analysis (its Eq. 11; Eq. 14 with a tension penalty):
  forces and small displacements with complementarity, non-associative friction. Its
  verdict: admissible when IPOPT converges, inadmissible when it reports the problem
  infeasible, no answer otherwise.

Ours: :func:`rigidblocks.check` with ``load_factor=0`` (self-weight only) and its force
state (the work RBE does: it always returns its forces) on the 2D scene where the
structure is planar, on its extrusion (:func:`rigidblocks.scene.extrude`) with the exact
second-order Coulomb cone, and on the extrusion with an inscribed 8-facet pyramid
(``pyramid=8``, the peer's facet count). The peer has no 2D mode: our 2D figures are
set against its RBE on the extrusion.

Structures: semicircular arches on abutments (radial joints, t/R = 0.15, 10-100
voussoirs, straight intrados and extrados per voussoir so both tools see the same
polyhedra), running-bond walls on a foundation of about 10-1,000 blocks, and every
sample and documented example of the peer (``PEER_EXAMPLES``: its set-up, supports,
densities, rotation, friction, interface tolerances and solver as in its docs), read
on our side from the COMPAS file of the prepared assembly through
:mod:`rigidblocks.compas`. The wall's foundation is cut, for the peer only, into one
fixed piece under each bottom-course block: the peer's interface search looks for
contacts among the ``nmax`` nearest block centroids only, and would miss most of a long
foundation; fixed pieces change nothing in the mechanics.

Protocol: both sides in one session, with the same thread settings (``THREADS``: one
BLAS / OpenMP thread, set in this process before numpy loads and passed to every
process it starts), interleaved per structure (its RBE, ours, our whole processes, its
whole process, its RBE, ...), ``--repeats`` times (at least 3); each figure is the
minimum over the repeats, and the machine's load average is recorded at the start and
end of the run and of each structure. Both sides do the same work, the verdict and the
forces, timed two ways. In-process: ours from the block data (the scene dict; the
COMPAS file for the peer's examples) to the verdict and the force state (reading and
validating the blocks, contacts, assembly, problem, solve, state); the peer's from the
block data (building its assembly, its interface detection, its solver's set-up and
solve; ``times`` in the runner's output), after a warm-up solve in its process. Whole
process (arches and walls), what a user pays from the interpreter's start to its exit:
ours ``rigidblocks check FILE --load-factor 0 --json`` on the scene file (our modules
compiled to bytecode first, as an installed package's are: :func:`compile_package`), the
peer's runner on its case file without the warm-up. Solve only: our Clarabel solve against its
IPOPT solve. Times are CPU seconds of each process (``cpu``; a whole process's from
``resource.getrusage(RUSAGE_CHILDREN)``; one thread per side, so the machine's load
stretches wall-clock times but hardly these; wall-clock times are kept in the JSON),
stage by stage on our side (read, contacts, assembly, build, solve, state), which gives
the 3D profile. The peer's own method (CRA or CRA-penalty) runs once per structure for
its verdict.

Non-associative friction (section "non-associative", ``--only nonassoc`` runs it alone
and keeps the static figures of an earlier run in bench_peer.json, ``--only static``
the converse): its CRA and CRA-penalty, which model friction without dilatancy with
complementarity and small displacements, against our ``check(..., flow=
"non-associative")`` at self-weight, on small arches and walls and the peer's examples;
with the static f* and our non-associative friction (``min_friction``) to show how far
each structure is from the verdict's threshold, and the differences explained from the
run's data where they can be (see :func:`na_differences`).

    python benchmarks/bench_peer.py [--tiny] [--out DIR] [--peer-python PATH] [--repeats N]
                                    [--only static|nonassoc]

The peer's Python: ``--peer-python``, else ``RIGIDBLOCKS_PEER_PYTHON``, else
``/work/venv-peer/bin/python``; ``none`` skips the peer. It is a separate environment,
never a dependency of rigidblocks (compas_cra ships its own IPOPT and OpenBLAS)::

    python -m venv /work/venv-peer
    /work/venv-peer/bin/pip install compas_cra==0.8.0 compas_assembly==0.7.1 compas==2.15.1

Our side reads the peer's examples through :mod:`rigidblocks.compas`, so it runs with
the ``compas`` extra installed (without it those rows say "not modelled" and why).

``--redraw`` rewrites the tables and the chart from the run's ``bench_peer.json``. A
full run into the default results folder also regenerates ``benchmarks/README.md``
(``make_readme.py``), so that the README's claims come from this run only.
"""

from __future__ import annotations

import os
import sys

#: the thread settings of both sides
THREADS = {"OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
if __name__ == "__main__":  # before numpy loads its BLAS
    os.environ.update(THREADS)

import argparse  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import subprocess  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from collections.abc import Sequence  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from common import (  # noqa: E402
    child_cpu,
    cli_process,
    machine,
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
from rigidblocks.io.scene_file import scene_from_dict, scene_to_dict  # noqa: E402
from rigidblocks.scene.extrude import extrude  # noqa: E402
from rigidblocks.scene.geometry import scene_size  # noqa: E402
from rigidblocks.scene.model import Scene  # noqa: E402
from rigidblocks.scene.polyhedra import POLY_TOL  # noqa: E402

NAME = "bench_peer"
RUNNER = Path(__file__).resolve().parent / "peer_runner.py"
DEFAULT_PEER = "/work/venv-peer/bin/python"
RBE_TENSION_TOL = 1e-4
ARCH_T = 0.15
ARCHES = (10, 20, 50, 100)
WALLS = (10, 100, 1_000)
HARD_ARCHES = ((10, 0.2), (20, 0.2))
REPEATS = 3
# CRA's displacement bound and overlap as in the peer's own sample examples (its solver
# defaults are d_bnd = 1e-3, eps = 1e-4); run on the hard arches beside the defaults
CRA_LOOSE = {"d_bnd": 0.1, "eps": 0.0}
TINY = {"arches": (10,), "walls": (10,), "hard": ((10, 0.2),), "examples": ()}
_DET = {"nmax": 10, "amin": 1e-2, "tmax": 1e-2}
_FINE = {"nmax": 10, "amin": 1e-6, "tmax": 1e-4}
_Y = [0, 1, 0]
#: the peer's samples and documented examples (docs/examples/NN_*.py of compas_cra),
#: with its own supports, densities, rotations, friction, interface tolerances and
#: solver; ``interfaces: None`` keeps the interfaces its sample file carries (it does
#: not detect them there); the four wedge types and the shelf variants are run with
#: the settings of the example that uses one of them
PEER_EXAMPLES: tuple[dict, ...] = (
    {"name": "00 simple cube", "boxes": [[0, 0, 0], [0, 0, 1]], "supports": [0],
     "mu": 0.84, "method": "cra", "interfaces": _FINE},
    {"name": "01 cubes, 48 deg, mu 0.1", "boxes": [[0, 0, 0], [0, 0, 1]], "supports": [0],
     "rotate": {"axis": _Y, "deg": 48.0}, "mu": 0.1, "method": "rbe", "interfaces": _FINE},
    {"name": "02 cubes", "sample": "cubes.json", "supports": [0], "mu": 0.84,
     "method": "cra", "interfaces": _DET},
    {"name": "03 cubes, 40 deg, offset 0.75", "boxes": [[0, 0, 0], [0.75, 0, 1]],
     "supports": [0], "rotate": {"axis": _Y, "deg": 40.0}, "mu": 0.84,
     "method": "cra_penalty", "interfaces": _FINE},
    {"name": "04 stacks, 20 deg", "boxes": [[0, 0, 0], [0, 0, 1], [0, 0, 2]],
     "supports": [0], "rotate": {"axis": _Y, "deg": 20.0}, "mu": 0.84, "method": "cra",
     "interfaces": _FINE},
    *({"name": f"05 wedge {t}, 90 deg", "sample": f"{t}.json", "supports": [0, 1],
       "rotate": {"axis": _Y, "deg": 90.0}, "mu": 0.84, "method": "cra", "d_bnd": 1e-2,
       "interfaces": _DET} for t in ("type-a", "type-b", "type-c", "type-d")),
    {"name": "06 arch", "arch": {"height": 5, "span": 10, "thickness": 0.5, "depth": 0.5,
                                 "num_blocks": 20, "extra_support": False},
     "supports": None, "mu": 0.7, "method": "cra", "interfaces": _DET},
    {"name": "06 arch, extra support", "arch": {"height": 5, "span": 10, "thickness": 0.5,
                                                "depth": 0.5, "num_blocks": 20,
                                                "extra_support": True},
     "supports": None, "mu": 0.7, "method": "cra_penalty", "interfaces": _DET},
    *({"name": f"07 {s}", "sample": f"{s}.json", "supports": [0], "mu": 0.9,
       "method": "cra_penalty", "d_bnd": 0.1, "eps": 1e-3, "interfaces": _FINE}
      for s in ("shelf", "shelf-stable", "shelf-s1", "shelf-s2", "shelf-s3")),
    {"name": "08 snake", "sample": "snake.json", "supports": [0], "mu": 0.7,
     "method": "cra_penalty", "d_bnd": 0.1, "eps": 0.0,
     "interfaces": {"nmax": 10, "amin": 1e-4, "tmax": 1e-2}},
    {"name": "09 bridge", "sample": "bridge.json", "supports": [0, 1], "mu": 0.9,
     "density": {str(k): 3.51 for k in (11, 12, 13, 14, 15)},
     "method": "cra_penalty", "d_bnd": 0.1, "eps": 0.0, "interfaces": _FINE},
    {"name": "10 armadillo", "sample": "armadillo_cra.json", "supports": None, "mu": 0.84,
     "method": "rbe", "interfaces": None},
    {"name": "11 concave-short, 40 deg", "sample": "concave-short.json", "supports": [0],
     "rotate": {"axis": _Y, "deg": 40.0}, "mu": 0.84, "method": "cra", "d_bnd": 1e-2,
     "eps": 1e-3, "interfaces": None},
    {"name": "12 concave-long, 50 deg", "sample": "concave-long.json", "supports": [0],
     "rotate": {"axis": _Y, "deg": 50.0}, "mu": 0.84, "method": "cra", "d_bnd": 1e-2,
     "eps": 1e-3, "interfaces": None},
    {"name": "13 curve-3-blocks", "sample": "curve-3-blocks.json", "supports": [0],
     "mu": 0.84, "method": "cra", "interfaces": None},
    {"name": "14 cube-curve-short", "sample": "cube-curve-short.json", "supports": [0],
     "mu": 0.84, "density_default": 0.1, "method": "cra", "interfaces": None},
    {"name": "15 cube-curve-tall", "sample": "cube-curve-tall.json", "supports": [0],
     "mu": 0.84, "density_default": 0.1, "method": "cra", "interfaces": None},
    {"name": "16 A", "sample": "A.json", "supports": [0, 1], "mu": 0.84, "method": "rbe",
     "interfaces": _DET},
    {"name": "16 H", "sample": "H.json", "supports": [0, 1], "mu": 0.84, "method": "rbe",
     "interfaces": _DET},
)
HEYMAN = ("semicircular arch, radial joints, t/R above the minimum 0.1075 "
          "(Milankovitch 1907; Heyman 1969): stands")
#: the goals at the largest wall, the peer's RBE CPU seconds over ours, the same work
#: on both sides (verdict and forces), in-process and whole process
GOALS = {"2d": {"in_process": 60.0, "process": 30.0},
         "3d_cone": {"in_process": 10.0, "process": 8.0}}


def loadavg() -> list[float]:
    """The machine's 1, 5 and 15 minute load averages."""
    try:
        return [round(x, 2) for x in os.getloadavg()]
    except OSError:  # pragma: no cover
        return []


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
    for case in sizes["examples"]:
        out.append({"name": f"peer {case['name']}", "kind": "peer example",
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


def run_ours(make_scene: Any, pyramid: int | None = None, forces: bool = False,
             contact_tol: Any = None) -> dict:
    """Time one ``check`` from the block data: ``make_scene()`` reads and validates the
    blocks (the scene dict, or the COMPAS file), then the verdict and the force state
    (the work the peer's RBE does: it always returns its forces); ``contact_tol`` may
    be a function of the scene. Wall-clock seconds (``total``, ``read``, ``check``,
    ``solve``: Clarabel's own) and CPU seconds per stage (``cpu``: read, contacts,
    assembly, build, solve, total). With ``forces``, also the state's joint forces."""
    c0, t0 = time.process_time(), time.perf_counter()
    scene = make_scene()
    tol = contact_tol(scene) if callable(contact_tol) else contact_tol
    c1, t1 = time.process_time(), time.perf_counter()
    res = check(scene, load_factor=0.0, state=True, compare_dry=False, pyramid=pyramid,
                contact_tol=tol)
    c2, t2 = time.process_time(), time.perf_counter()
    stages = dict(res.cpu_timings)  # contacts, assembly, build, solve (CPU seconds)
    out = {"verdict": res.status, "total": t2 - t0, "read": t1 - t0, "check": t2 - t1,
           "solve": res.solve_time, "joints": res.contacts.n_joints,
           "points": res.contacts.n_points,
           "cpu": {"read": c1 - c0, **stages, "check": c2 - c1, "total": c2 - c0}}
    if tol is not None:
        out["contact_tol"] = tol
    if forces and res.state is not None:
        out["forces"] = joint_forces(res)
    return out


def compile_package() -> str:
    """Compile our package's modules to bytecode (``__pycache__`` beside them), as
    ``pip install`` leaves an installed package and as the peer's and the libraries'
    modules are in their environments: a whole process then pays what a user's does
    from the second run on, not the compilation of every module (about 0.09 CPU s, which
    an environment with PYTHONDONTWRITEBYTECODE, or a read-only checkout, pays on every
    run). Returns the folder compiled."""
    import compileall

    import rigidblocks

    here = Path(rigidblocks.__file__).resolve().parent
    compileall.compile_dir(str(here), quiet=1)
    return str(here)


def run_ours_process(path: Path) -> dict:
    """One whole ``rigidblocks check FILE --load-factor 0 --json`` process, what a user
    pays: interpreter start, imports, reading and validating the scene file, contacts,
    the verdict and the force state, the JSON answer written; one thread (``THREADS``).
    Its CPU seconds (the finished child's user + system time) and wall seconds."""
    proc, cpu, wall = cli_process(["check", str(path), "--load-factor", "0", "--json"],
                                  THREADS)
    try:
        verdict = json.loads(proc.stdout)["status"]
    except (ValueError, KeyError):
        verdict = f"error: {(proc.stderr or proc.stdout).strip()[-200:]}"
    return {"verdict": verdict, "cpu": cpu, "wall": wall}


def peer_python(arg: str | None) -> str | None:
    """The peer's interpreter, or None when disabled or missing."""
    path = arg or os.environ.get("RIGIDBLOCKS_PEER_PYTHON") or DEFAULT_PEER
    if path.lower() == "none" or not Path(path).exists():
        return None
    return path


def run_peer(python: str, case: dict, method: str, timeout: float, tmp: Path,
             cold: bool = False) -> dict:
    """One peer run in its own process (thread settings ``THREADS``); status "timeout"
    when it exceeds ``timeout`` s. ``cold``: without the runner's warm-up solve, the
    whole process as a user's script pays it (see peer_runner.py); its CPU seconds (the
    finished child's user + system time) are ``process_cpu``, its wall seconds
    ``times["process"]``."""
    src, dst = tmp / "case.json", tmp / "out.json"
    src.write_text(json.dumps(case))
    dst.unlink(missing_ok=True)
    env = {**os.environ, **THREADS}
    c0, t0 = child_cpu(), time.perf_counter()
    try:
        proc = subprocess.run([python, str(RUNNER), str(src), str(dst), method,
                               *(["cold"] if cold else [])],
                              capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return {"method": method, "status": "timeout", "times": {"limit": timeout},
                "message": f"no answer within {timeout:g} s (stopped)", "joints": []}
    wall, cpu = time.perf_counter() - t0, child_cpu() - c0
    if not dst.exists():
        return {"method": method, "status": "error", "times": {}, "joints": [],
                "message": (proc.stderr or proc.stdout).strip()[-300:]}
    out = json.loads(dst.read_text())
    out["times"]["process"] = wall
    out["process_cpu"] = cpu
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


def rbe_tension_ratio(out: dict) -> float | None:
    """RBE's penalised tension over its total compression."""
    if out.get("status") != "solved" or out.get("method") not in ("rbe", "cra_penalty"):
        return None
    comp = sum(j["fn"] for j in out["joints"])
    return sum(abs(j["tension"]) for j in out["joints"]) / max(comp, 1e-300)


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
    mine, its = sorted(set(ours) - set(theirs)), sorted(set(theirs) - set(ours))
    return {"joints": len(common), "ours_only": len(mine), "peer_only": len(its),
            "ours_only_pairs": [list(k) for k in mine[:20]],
            "peer_only_pairs": [list(k) for k in its[:20]],
            "ours_total": float(a.sum()), "peer_total": float(b.sum()),
            "max_rel_diff": float(np.abs(a - b).max() / scale),
            "median_rel_diff": float(np.median(np.abs(a - b)) / scale)}


def _min_runs(runs: list[dict]) -> dict:
    """The first run's answer with every time the minimum over the runs, and the runs'
    totals kept as ``runs``."""
    out = dict(runs[0])
    for key in ("total", "read", "check", "solve"):
        vals = [r[key] for r in runs if r.get(key) is not None]
        if vals:
            out[key] = min(vals)
    out["runs"] = [r.get("total") for r in runs]
    out["cpu"] = _min_dict([r.get("cpu", {}) for r in runs])
    verdicts = {r["verdict"] for r in runs}
    if len(verdicts) > 1:
        out["verdict"] = "varies: " + ", ".join(sorted(verdicts))
    return out


def _min_process(runs: list[dict]) -> dict:
    """Whole processes: the minimum CPU and wall seconds over the runs, each run's CPU
    seconds, and the verdict (or "varies: ...")."""
    cpu = [r["cpu"] for r in runs if r.get("cpu") is not None]
    wall = [r["wall"] for r in runs if r.get("wall") is not None]
    verdicts = sorted({r["verdict"] for r in runs})
    return {"cpu": min(cpu) if cpu else None, "wall": min(wall) if wall else None,
            "runs_cpu": cpu,
            "verdict": verdicts[0] if len(verdicts) == 1 else "varies: " + ", ".join(
                verdicts)}


def _min_peer(runs: list[dict]) -> dict:
    out = dict(runs[0])
    times: dict[str, float] = {}
    for r in runs:
        for k, v in r.get("times", {}).items():
            if isinstance(v, int | float):
                times[k] = min(times.get(k, math.inf), v)
    out["times"] = times
    out["cpu"] = _min_dict([r.get("cpu", {}) for r in runs])
    out["runs"] = [r.get("times", {}).get("total") for r in runs]
    return out


def _min_dict(ds: list[dict]) -> dict:
    """Per key, the minimum over the dicts that have it."""
    out: dict[str, float] = {}
    for d in ds:
        for k, v in d.items():
            if isinstance(v, int | float):
                out[k] = min(out.get(k, math.inf), v)
    return out


def _example_reader(path: Path, case: dict) -> tuple[Any, Any]:
    """(make_scene, contact_tol) for one of the peer's examples, read from the COMPAS
    file of its prepared assembly; raises InputError when we cannot model it."""
    from rigidblocks.compas import read_compas

    def make() -> Scene:
        return read_compas(path, friction=float(case["mu"]),
                           density=float(case.get("density_default", 1.0)))[0]

    opts = case.get("interfaces")
    tol = (None if opts is None else
           (lambda s: float(opts["tmax"]) / scene_size(s)))
    make()  # raises InputError (a face that is not planar, say) before anything is timed
    return make, tol


def bench(sizes: dict, python: str | None, timeouts: dict, repeats: int,
          log=sys.stdout) -> list[dict]:
    """Both sides on every structure, interleaved; one row per structure."""
    rows = []
    compile_package()  # our whole processes start from bytecode, as the peer's do
    with tempfile.TemporaryDirectory() as tmpd:
        tmp = Path(tmpd)
        for st in structures(sizes):
            row: dict[str, Any] = {k: st[k] for k in ("name", "kind", "blocks", "expected",
                                                      "basis")}
            row["loadavg_start"] = loadavg()
            big = (st["blocks"] or 0) >= 1_000
            variants: dict[str, tuple[Any, dict]] = {}
            files: dict[str, Path] = {}  # the scene files of our whole processes
            if st["scene2d"] is not None:
                d2, d3 = scene_to_dict(st["scene2d"]), scene_to_dict(st["scene3d"])
                variants["2d"] = (lambda d=d2: scene_from_dict(d), {"forces": True})
                variants["3d_cone"] = (lambda d=d3: scene_from_dict(d), {"forces": True})
                variants["3d_pyr8"] = (lambda d=d3: scene_from_dict(d), {"pyramid": 8})
                for m, d in (("2d", d2), ("3d_cone", d3)):
                    files[m] = tmp / f"scene_{m}.json"
                    files[m].write_text(json.dumps(d))
            case = {"name": st["name"], **st["peer"]}
            ours_runs: dict[str, list[dict]] = {m: [] for m in variants}
            procs: dict[str, list[dict]] = {m: [] for m in files}
            rbe_runs: list[dict] = []
            cold_runs: list[dict] = []
            not_modelled = None
            for rep in range(repeats):
                # a peer run that reached its time limit is not repeated
                if python is not None and not (rbe_runs and rbe_runs[-1]["status"] in
                                               ("timeout", "error")):
                    if st["scene2d"] is None and rep == 0:
                        case["export"] = str(tmp / "prepared.json")
                    rbe_runs.append(run_peer(python, case, "rbe", timeouts["rbe"], tmp))
                    case.pop("export", None)
                if st["scene2d"] is None and rep == 0:
                    prepared = tmp / "prepared.json"
                    try:
                        if not prepared.exists():
                            raise InputError("the peer's set-up was not exported")
                        make, tol = _example_reader(prepared, st["peer"])
                        variants["3d_cone"] = (make, {"forces": True, "contact_tol": tol})
                        variants["3d_pyr8"] = (make, {"pyramid": 8, "contact_tol": tol})
                        ours_runs = {m: [] for m in variants}
                        blocks = make().blocks
                        row["blocks"] = sum(not b.support for b in blocks)
                        row["supports"] = [str(b.id) for b in blocks if b.support]
                    except (InputError, ImportError) as exc:
                        not_modelled = f"not modelled: {getattr(exc, 'detail', exc)}"
                for m, (make, kw) in variants.items():
                    ours_runs[m].append(run_ours(make, **{**kw, "forces": kw.get(
                        "forces", False) and rep == 0}))
                # whole processes, a user's cost: ours, then the peer's without warm-up
                for m, path in files.items():
                    procs[m].append(run_ours_process(path))
                if files and python is not None and not (
                        cold_runs and cold_runs[-1]["status"] in ("timeout", "error")) \
                        and rbe_runs[-1]["status"] not in ("timeout", "error"):
                    cold_runs.append(run_peer(python, case, "rbe", timeouts["rbe"], tmp,
                                              cold=True))
            ours = {m: _min_runs(r) for m, r in ours_runs.items() if r}
            for m, r in procs.items():
                ours[m]["process"] = _min_process(r)
            if not_modelled:
                ours["3d_cone"] = {"verdict": not_modelled}
            peer: dict[str, Any] = {}
            if rbe_runs:
                peer["rbe"] = _min_peer(rbe_runs)
                if cold_runs:
                    peer["rbe"]["process"] = _min_process([
                        {"verdict": peer_verdict(c), "cpu": c.get("process_cpu"),
                         "wall": c.get("times", {}).get("process")} for c in cold_runs])
                peer["rbe"]["verdict"] = peer_verdict(rbe_runs[0])
                peer["rbe"]["tension_ratio"] = rbe_tension_ratio(rbe_runs[0])
                peer["rbe"]["settings"] = {}
                others = []
                own = st["peer"].get("method", "cra")
                if own != "rbe":
                    others.append(("cra" if own == "cra" else own, own, {}))
                if st["kind"] == "hard arch":
                    others.append(("cra_d0.1", "cra", CRA_LOOSE))
                for key, method, extra in others:
                    lim = timeouts["cra_big" if big else "cra"]
                    p = run_peer(python, {**case, **extra}, method, lim, tmp)
                    p["verdict"] = peer_verdict(p)
                    p["settings"] = extra
                    if method == "cra_penalty":
                        p["tension_ratio"] = rbe_tension_ratio(p)
                    peer[key] = p
            for m in ("2d", "3d_cone"):
                f = ours.get(m, {}).pop("forces", None)
                if f and peer.get("rbe", {}).get("status") == "solved":
                    row[f"forces_{m}_vs_rbe"] = compare_forces(f, peer["rbe"])
                for other in ("cra", "cra_penalty"):
                    if f and peer.get(other, {}).get("status") == "solved":
                        row[f"forces_{m}_vs_{other}"] = compare_forces(f, peer[other])
            for p in peer.values():
                p.pop("blocks", None)
                p.pop("joints", None)
                p.pop("traceback", None)
            row["ours"], row["peer"] = ours, peer
            row["loadavg_end"] = loadavg()
            rows.append(row)
            print(summary_line(row), file=log, flush=True)
    return rows


# -- non-associative friction: its CRA and CRA-penalty against our flow="non-associative" --
#: the structures of the non-associative section besides the peer's examples
NA_SIZES = {"arches": (10, 20), "hard": ((10, 0.2),), "walls": (10, 30)}
NA_TINY = {"arches": (10,), "hard": (), "walls": (10,), "examples": ()}
#: 1 / cos(22.5 deg): how much more friction than f the peer's 8-facet pyramid, whose
#: facets lie at f N from its axis, allows along the facets' bisectors
PYRAMID_EXCESS = 1.0 / math.cos(math.pi / 8)
NA = "non-associative"


def run_ours_na(make_scene: Any, contact_tol: Any = None) -> dict:
    """Time one non-associative ``check`` at load factor 0 from the block data (as
    :func:`run_ours`); its verdict, fixed-point iterations and reason."""
    from rigidblocks.errors import SolverFailure

    c0, t0 = time.process_time(), time.perf_counter()
    scene = make_scene()
    tol = contact_tol(scene) if callable(contact_tol) else contact_tol
    try:
        res = check(scene, load_factor=0.0, state=False, contact_tol=tol, flow=NA)
    except SolverFailure as exc:
        return {"verdict": "failure", "reason": str(exc)[:200],
                "total": time.perf_counter() - t0, "cpu": {}}
    c1, t1 = time.process_time(), time.perf_counter()
    reason = [n for n in res.notes if not n.startswith("non-associative sliding")]
    return {"verdict": res.status, "total": t1 - t0, "solve": res.solve_time,
            "iterations": res.iterations, "converged": res.converged,
            "violation": res.violation if res.status == "inadmissible" else 0.0,
            "reason": "; ".join(reason)[:300], "joints": res.contacts.n_joints,
            "points": res.contacts.n_points, "cpu": {"total": c1 - c0}}


def friction_na(scene: Scene, contact_tol: float | None) -> dict:
    """At load factor 0: the static f* and the non-associative friction (the smallest f
    at which the state reached from the elastic state stands), with their times."""
    from rigidblocks import min_friction
    from rigidblocks.errors import SolverFailure

    out: dict[str, Any] = {}
    for key, flow in (("static", None), ("na", NA)):
        t0 = time.perf_counter()
        try:
            r = min_friction(scene, load_factor=0.0, state=False, compare_dry=False,
                             contact_tol=contact_tol, flow=flow)
            out[key] = {"status": r.status, "f": r.friction_factor,
                        "bracket": list(r.bracket) if r.bracket else None}
        except SolverFailure as exc:
            out[key] = {"status": "failure", "f": None, "bracket": None,
                        "reason": str(exc)[:200]}
        out[key]["time"] = time.perf_counter() - t0
    return out


def peer_na_verdict(out: dict) -> str:
    """The verdict of its CRA or CRA-penalty: as :func:`peer_verdict`, and a
    CRA-penalty state counts as admissible under the rule RBE's does (penalised tension
    below ``RBE_TENSION_TOL`` of the compression)."""
    v = peer_verdict(out)
    tr = rbe_tension_ratio(out)
    if v == "admissible" and out.get("method") == "cra_penalty" and tr is not None \
            and tr > RBE_TENSION_TOL:
        return "inadmissible"
    return v


def bench_nonassoc(sizes: dict, python: str | None, timeouts: dict, repeats: int,
                   log=sys.stdout) -> list[dict]:
    """Self-weight verdicts without dilatancy, ours against the peer's CRA and
    CRA-penalty, on small arches and walls and the peer's examples; interleaved per
    structure (ours, its CRA, ours, its CRA-penalty, ours, ...), ours ``repeats`` times
    (the minimum time), each peer method once, as its CRA runs in :func:`bench`."""
    rows = []
    with tempfile.TemporaryDirectory() as tmpd:
        tmp = Path(tmpd)
        for st in structures(sizes):
            row: dict[str, Any] = {k: st[k] for k in ("name", "kind", "blocks")}
            row["mu"] = float(st["peer"]["mu"])
            row["d_bnd"] = float(st["peer"].get("d_bnd", 1e-3))
            row["eps"] = float(st["peer"].get("eps", 1e-4))
            row["loadavg_start"] = loadavg()
            case = {"name": st["name"], **st["peer"]}
            variants: dict[str, tuple[Any, Any]] = {}
            if st["scene2d"] is not None:
                d2, d3 = scene_to_dict(st["scene2d"]), scene_to_dict(st["scene3d"])
                variants["2d"] = (lambda d=d2: scene_from_dict(d), None)
                variants["3d_cone"] = (lambda d=d3: scene_from_dict(d), None)
            else:
                prepared = tmp / "prepared.json"
                prepared.unlink(missing_ok=True)
                if python is not None:
                    run_peer(python, {**case, "export": str(prepared)}, "export",
                             timeouts["cra"], tmp)
                try:
                    if not prepared.exists():
                        raise InputError("the peer's set-up was not exported")
                    make, tol = _example_reader(prepared, st["peer"])
                    variants["3d_cone"] = (make, tol)
                    blocks = make().blocks
                    row["blocks"] = sum(not b.support for b in blocks)
                except (InputError, ImportError) as exc:
                    row["ours"] = {"3d_cone": {
                        "verdict": f"not modelled: {getattr(exc, 'detail', exc)}"[:200]}}
                    row["peer"] = {}
                    row["loadavg_end"] = loadavg()
                    rows.append(row)
                    print(f"{row['name']:<28}  not modelled", file=log, flush=True)
                    continue
            peer_runs: list[tuple[str, str, dict]] = []
            if python is not None:
                peer_runs = [("cra", "cra", {}), ("cra_penalty", "cra_penalty", {})]
                if st["kind"] in ("arch", "hard arch"):
                    peer_runs.append(("cra_d0.1", "cra", CRA_LOOSE))
            runs: dict[str, list[dict]] = {m: [] for m in variants}
            peer: dict[str, Any] = {}
            for rep in range(max(repeats, len(peer_runs))):
                if rep < repeats:
                    for m, (make, tol) in variants.items():
                        runs[m].append(run_ours_na(make, tol))
                if rep < len(peer_runs):
                    key, method, extra = peer_runs[rep]
                    p = run_peer(python, {**case, **extra}, method, timeouts["cra"], tmp)
                    p["verdict"] = peer_na_verdict(p)
                    p["settings"] = extra
                    p["tension_ratio"] = rbe_tension_ratio(p)
                    for k in ("blocks", "joints", "traceback"):
                        p.pop(k, None)
                    peer[key] = p
            ours = {}
            for m, r in runs.items():
                o = dict(r[0])
                o["total"] = min(x["total"] for x in r)
                o["runs"] = [x["total"] for x in r]
                if len({x["verdict"] for x in r}) > 1:
                    o["verdict"] = "varies: " + ", ".join(sorted({x["verdict"] for x in r}))
                ours[m] = o
            make, tol = variants["3d_cone"]
            scene = make()
            row["friction"] = friction_na(scene, tol(scene) if callable(tol) else tol)
            row["ours"], row["peer"] = ours, peer
            row["loadavg_end"] = loadavg()
            row["notes"] = na_differences(row)
            rows.append(row)
            print(na_summary_line(row), file=log, flush=True)
    return rows


def run_nonassoc(sizes: dict, python: str | None, timeouts: dict, repeats: int) -> dict:
    """The non-associative section's run: its rows, agreement counts and session."""
    started, la0 = time.strftime("%Y-%m-%d %H:%M:%S %Z"), loadavg()
    rows = bench_nonassoc(sizes, python, timeouts, repeats)
    return {"date": time.strftime("%Y-%m-%d"), "machine": machine(), "argv": sys.argv[1:],
            "started": started, "loadavg_start": la0,
            "finished": time.strftime("%Y-%m-%d %H:%M:%S %Z"), "loadavg_end": loadavg(),
            "threads": {k: os.environ.get(k) for k in THREADS}, "repeats": repeats,
            "timeouts_s": {"cra": timeouts["cra"]},
            "peer_version": next((p.get("version") for r in rows
                                  for p in r["peer"].values() if p.get("version")), None),
            "rows": rows, "agreement": na_agreement(rows)}


def na_summary_line(row: dict) -> str:
    parts = [f"{row['name']:<28}"]
    for m, r in row["ours"].items():
        parts.append(f"{m}={r['verdict'][:30]}/{r.get('total', float('nan')):.3g}s")
    fr = row.get("friction", {}).get("na", {})
    if fr.get("f") is not None:
        parts.append(f"f_na={fr['f']:.4g}")
    for m, r in row["peer"].items():
        parts.append(f"{m}={r['verdict']}/{r['times'].get('total', float('nan')):.3g}s")
    return "  ".join(parts)


def _decided(v: str) -> bool:
    return v in ("admissible", "inadmissible")


def na_agreement(rows: list[dict]) -> dict:
    """Counts over the rows where our 3D verdict (the peer's geometry) is decided:
    agreements and disagreements with its CRA and its CRA-penalty where they decide, and
    how often either side gives no decided answer."""
    out: dict[str, Any] = {}
    for key in ("cra", "cra_penalty", "cra_d0.1"):
        agree = disagree = ours_open = peer_open = 0
        for r in rows:
            o = r["ours"].get("3d_cone", {}).get("verdict", "")
            if key not in r["peer"] or o.startswith("not modelled"):
                continue
            p = r["peer"][key]["verdict"]
            if not _decided(o):
                ours_open += 1
            elif not _decided(p):
                peer_open += 1
            elif o == p:
                agree += 1
            else:
                disagree += 1
        if agree + disagree + ours_open + peer_open:
            out[key] = {"agree": agree, "disagree": disagree, "ours_undecided": ours_open,
                        "peer_no_answer": peer_open}
    return out


def na_differences(row: dict) -> list[str]:
    """Why our non-associative verdict and the peer's differ, from the run's data."""
    o = row["ours"].get("3d_cone", {})
    mine = o.get("verdict", "")
    fr = row.get("friction", {})
    fs, fn = fr.get("static", {}).get("f"), fr.get("na", {}).get("f")
    mu = row["mu"]
    out = []
    if not _decided(mine):
        out.append(f"ours is {mine}: {o.get('reason', '')}")
    for key, p in row["peer"].items():
        v = p["verdict"]
        if v == mine or not _decided(mine):
            continue
        name = {"cra": "CRA", "cra_penalty": "CRA-penalty",
                "cra_d0.1": "CRA (d_bnd 0.1, eps 0)"}[key]
        if v == "no answer":
            out.append(f"its {name} gave no answer ({p.get('message', '')[:80]})")
            continue
        tr = p.get("tension_ratio")
        if key == "cra_penalty" and tr is not None and tr > RBE_TENSION_TOL:
            out.append(f"its {name} state carries tension {tr:.2g} of its compression "
                       "(penalised, not forbidden): inadmissible by the rule RBE's state "
                       f"is read by ({RBE_TENSION_TOL:g})")
            continue
        if v == "admissible" and mine == "inadmissible":
            why = [f"its {name} finds a state (any force state that some small "
                   "displacement, bounded by d_bnd, makes complementary: a pinch no load "
                   "causes is allowed), ours follows the one state reached from the "
                   "elastic state"]
            if fs is not None and fs <= mu:
                why.append(f"a static state exists (f* = {fs:.4g} <= f = {mu:g})")
            if fn is not None:
                rel = "within" if fn <= mu * PYRAMID_EXCESS else "beyond"
                why.append(f"ours needs f = {fn:.4g} without dilatancy, {fn / mu:.3g} "
                           f"times the f = {mu:g} given: {rel} the {PYRAMID_EXCESS - 1:.1%}"
                           " more friction its circumscribed 8-facet pyramid allows")
            if o.get("violation"):
                why.append(f"our state breaches the joint laws by {o['violation']:.3g}")
            out.append("; ".join(why))
        elif v == "inadmissible" and mine == "admissible":
            extra = p.get("settings") or {}
            d_bnd = extra.get("d_bnd", row.get("d_bnd", 1e-3))
            eps = extra.get("eps", row.get("eps", 1e-4))
            out.append(f"its {name} reports the problem infeasible where ours stands: its "
                       f"displacements are bounded by d_bnd = {d_bnd:g} and a contact "
                       f"carries force only where it closes to an overlap of eps = {eps:g}, "
                       "so a state that needs larger settlements (or no overlap) is out of "
                       "its reach"
                       + (f"; with d_bnd 0.1 and eps 0 it answers "
                          f"{row['peer']['cra_d0.1']['verdict']}"
                          if "cra_d0.1" in row["peer"] and key != "cra_d0.1" else ""))
    return out


def _fval(fr: dict, key: str) -> Any:
    """A friction of the non-associative table: the value, or the status and bracket."""
    d = fr.get(key, {})
    if d.get("f") is not None:
        return float(d["f"])
    b = d.get("bracket")
    if b:
        return f"{d.get('status')} [{b[0]:.4g}, {b[1]:.4g}]"
    return d.get("status", "-")


def na_markdown(na: dict) -> list[str]:
    """The non-associative section of bench_peer.md."""
    rows = na["rows"]
    lines = ["### Non-associative friction: its CRA against our `flow=\"non-associative\"`",
             ""]
    thr = ", ".join(f"{k}={v}" for k, v in (na.get("threads") or {}).items())
    lines += [f"One session ({na.get('started', '?')} to {na.get('finished', '?')}, load "
              f"average {na.get('loadavg_start')} to {na.get('loadavg_end')}), the same "
              f"thread settings ({thr}). Both sides answer at self-weight (load factor "
              "0) with friction that does not dilate. Ours: `check(..., flow="
              "\"non-associative\")`, the state reached from the elastic state by the "
              "convex path's fixed-point iteration (2D and the 3D extrusion with the "
              "exact cone; the peer's examples read from its prepared assembly as above), "
              f"minimum of {na.get('repeats')} runs, block data to verdict; and, once, "
              "the static f* and the non-associative friction f_na (`min_friction`, the "
              "smallest f at which that state stands). Its CRA (Eq. 11) and CRA-penalty "
              "(Eq. 14), once each, with the example's own d_bnd and eps (the solver's "
              "defaults 1e-3 and 1e-4 on the arches and walls, where CRA also runs with "
              "d_bnd 0.1, eps 0); a CRA-penalty state counts as admissible when its "
              f"penalised tension is below {RBE_TENSION_TOL:g} of its compression, as "
              "RBE's does.", ""]
    head = ["structure", "f", "ours 2D", "ours 3D", "ours 3D s", "iterations", "f*",
            "f_na", "CRA", "CRA s", "CRA-penalty (tension)", "CRA-penalty s",
            "CRA d_bnd 0.1"]
    body = []
    for r in rows:
        o, p = r["ours"], r["peer"]
        fr = r.get("friction", {})
        c3 = o.get("3d_cone", {})
        pen = p.get("cra_penalty", {})
        tr = pen.get("tension_ratio")
        body.append([
            r["name"], r["mu"], _v(o, "2d"),
            c3.get("verdict", "-") if "total" in c3 else "not modelled",
            _t(c3), c3.get("iterations", "-"), _fval(fr, "static"), _fval(fr, "na"),
            _v(p, "cra"), _t(p.get("cra", {}).get("times", {})),
            (pen["verdict"] + (f" ({tr:.2g})" if tr is not None else "")) if pen else "-",
            _t(pen.get("times", {})), _v(p, "cra_d0.1")])
    lines += [markdown_table(head, body), ""]
    ag = na.get("agreement") or {}
    if ag:
        name = {"cra": "its CRA", "cra_penalty": "its CRA-penalty",
                "cra_d0.1": "its CRA with d_bnd 0.1, eps 0"}
        lines += ["Agreement with our 3D verdict where both decide: " + "; ".join(
            f"{name[k]}: {a['agree']} agree, {a['disagree']} disagree"
            + (f", {a['peer_no_answer']} without its answer" if a["peer_no_answer"] else "")
            + (f", {a['ours_undecided']} where ours is undecided" if a["ours_undecided"]
               else "")
            for k, a in ag.items()) + ".", ""]
    notes = [(r["name"], r.get("notes") or []) for r in rows]
    notes = [(n, d) for n, d in notes if d]
    if notes:
        lines += ["Where the verdicts differ or one side gives none:", ""]
        lines += [f"- {n}: " + "; ".join(d) + "." for n, d in notes]
        lines += [""]
    nm = [r["name"] for r in rows if "total" not in r["ours"].get("3d_cone", {})]
    if nm:
        lines += ["Not modelled on our side (faces not planar, as above), so not run on "
                  "its side either: " + ", ".join(n.removeprefix("peer ") for n in nm)
                  + ".", ""]
    lines += ["The two answer different questions: its CRA asks whether some force state "
              "and some small displacement field (bounded by d_bnd, contacts carrying "
              "force only where they overlap by eps, friction opposing the slip) are "
              "consistent; ours whether the one state reached from the elastic state, "
              "with no pinch the loads do not cause, stands. Non-associative answers are "
              "not unique, so where it finds a state ours does not reach, both can be "
              "right; where its displacement bound or overlap leaves it no state, ours "
              "may still stand."]
    return lines


def summary_line(row: dict) -> str:
    """One line per structure: verdicts and total times."""
    parts = [f"{row['name']:<28}"]
    for m, r in row["ours"].items():
        parts.append(f"{m}={r['verdict'][:40]}/{r.get('total', float('nan')):.3g}s")
    for m, r in row["peer"].items():
        parts.append(f"{m}={r['verdict']}/{r['times'].get('total', float('nan')):.3g}s")
    parts.append(f"load {row.get('loadavg_start')} -> {row.get('loadavg_end')}")
    return "  ".join(parts)


def targets(rows: list[dict]) -> dict | None:
    """The claims at the largest wall, each side doing the same work (the verdict and
    the forces), in CPU seconds (one thread each side, so the machine's load stretches
    the wall clock, not these): in-process (ours: :func:`run_ours`, from the block data;
    its RBE: from its assembly to its forces, after its warm-up) and whole processes
    (:func:`run_ours_process` and its runner without warm-up); the peer's time over
    ours, 2D (ours: the plane problem; its: the extrusion, as it has no 2D mode) and 3D
    exact cone."""
    walls = [r for r in rows if r["kind"] == "wall" and r["peer"].get("rbe", {}).get(
        "status") == "solved"]
    if not walls:
        return None
    w = max(walls, key=lambda r: r["blocks"])
    rbe = w["peer"]["rbe"]
    rc, rt = rbe.get("cpu") or {}, rbe["times"]
    out = {"case": w["name"], "blocks": w["blocks"],
           "loadavg_start": w.get("loadavg_start"), "loadavg_end": w.get("loadavg_end"),
           "rbe_cpu_s": rc.get("total"), "rbe_ipopt_cpu_s": rc.get("ipopt"),
           "rbe_interfaces_cpu_s": rc.get("interfaces"), "rbe_build_cpu_s": rc.get("build"),
           "rbe_setup_s": rt.get("setup"), "rbe_ipopt_s": rt.get("ipopt"),
           "rbe_process_cpu_s": (rbe.get("process") or {}).get("cpu"),
           "goals": GOALS, "cpu_profile_3d": w["ours"]["3d_cone"].get("cpu")}
    for m in ("2d", "3d_cone"):
        o = w["ours"][m]
        c = (o.get("cpu") or {}).get("total")
        pc = (o.get("process") or {}).get("cpu")
        out[f"ours_{m}_cpu_s"], out[f"ours_{m}_process_cpu_s"] = c, pc
        out[f"ours_{m}_solve_cpu_s"] = (o.get("cpu") or {}).get("solve")
        for key, theirs, mine in (("in_process", out["rbe_cpu_s"], c),
                                  ("process", out["rbe_process_cpu_s"], pc)):
            ratio = theirs / mine if theirs and mine else None
            out[f"ratio_{m}_{key}"] = ratio
            out[f"met_{m}_{key}"] = ratio is not None and ratio >= GOALS[m][key]
    return out


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


def differences(row: dict) -> list[str]:
    """Why our verdict and the peer's differ on one of its examples, from the models:
    the interfaces and contact points each side found, and the friction laws."""
    o, p = row["ours"].get("3d_cone", {}), row["peer"]
    if not p:
        return []
    if "total" not in o:  # not modelled here: where its own two methods disagree
        rbe, others = p.get("rbe", {}), [k for k in p if k != "rbe"]
        tr = rbe.get("tension_ratio")
        if (rbe.get("verdict") == "inadmissible" and tr is not None and tr < 1e-2
                and any(p[k]["verdict"] == "admissible" for k in others)):
            return [f"its RBE state carries tension {tr:.2g} of its compression, above "
                    f"the {RBE_TENSION_TOL:g} this comparison allows: its quadratic "
                    "objective trades a little penalised tension for smaller forces, so "
                    "RBE's verdict here is the threshold's, while its CRA finds a state "
                    "without tension"]
        return []
    mine = o["verdict"]
    theirs = {k: v["verdict"] for k, v in p.items()}
    if all(v == mine for v in theirs.values()):
        return []
    rbe = p.get("rbe", {})
    out = [f"joints: ours {o.get('joints')} with {o.get('points')} contact points, its "
           f"{rbe.get('n_interfaces', '-')} interfaces with {rbe.get('n_vertices', '-')} "
           "vertices"]
    pyr = row["ours"].get("3d_pyr8", {}).get("verdict")
    if pyr is not None and pyr != mine:
        out.append(f"our inscribed 8-facet pyramid answers {pyr}: the verdict sits "
                   "between the inscribed and the circumscribed pyramid")
    tr = rbe.get("tension_ratio")
    if theirs.get("rbe") == "admissible" and mine == "inadmissible":
        out.append("its RBE pyramid circumscribes the cone (up to 8% more friction "
                   "than f along the facets' bisectors)"
                   + (f" and it carries tension {tr:.2g} of its compression"
                      if tr else ""))
    own = {k: v for k, v in theirs.items() if k != "rbe"}
    for k, v in own.items():
        if v == mine:
            continue
        tr = p[k].get("tension_ratio")
        if k == "cra_penalty" and v == "admissible" and tr and tr > RBE_TENSION_TOL:
            out.append(f"its CRA-penalty ({v}) penalises tension instead of forbidding it: "
                       f"its state carries tension {tr:.2g} of its compression")
        elif v == "no answer":
            out.append(f"its {k.upper()} gave no answer "
                       f"({p[k].get('message', '')[:80]})")
        else:
            out.append(f"its {k.upper()} ({v}) is non-associative with displacements "
                       "bounded by d_bnd: a different question than the static theorem")
    return out


def model_notes(row: dict) -> list[str]:
    """How the two models of one of its examples differ where the counts of interfaces
    or contact points differ, and why the forces differ where they do, from the run's
    data (the verdicts may agree)."""
    o, rbe = row["ours"].get("3d_cone", {}), row["peer"].get("rbe", {})
    if "total" not in o or not rbe:
        return []
    out = []
    mj, mp = o.get("joints"), o.get("points")
    tj, tp = rbe.get("n_interfaces"), rbe.get("n_vertices")
    fr = row.get("forces_3d_cone_vs_rbe")
    pairs = ""
    if fr:
        n = fr["joints"]
        pairs = (f" on the same {n} block pair{'s' if n != 1 else ''}"
                 if not fr["ours_only"] and not fr["peer_only"] else
                 f" ({n} block pairs in common, {fr['ours_only']} ours only, "
                 f"{fr['peer_only']} its only)")
    sup = set(row.get("supports") or ())
    extra = (fr or {}).get("ours_only_pairs") or []
    if tj is not None and mj is not None and tj > mj:
        out.append(f"its {tj} interfaces against our {mj} joints{pairs}: it has one "
                   "interface of each pair of touching faces of its meshes (a plane of "
                   "contact covered by several mesh faces gives several), we make one "
                   "joint of each plane two blocks share (the union of their faces in it, "
                   "in one or more pieces)")
    elif tj is not None and mj is not None and mj > tj:
        why = ""
        if extra and sup and all(set(k) <= sup for k in extra) and not fr["peer_only"]:
            why = (": ours also joins two supports (" + ", ".join("-".join(k) for k in extra)
                   + "), a joint that carries nothing the verdict depends on")
        out.append(f"our {mj} joints against its {tj} interfaces{pairs}{why}")
    if tp is not None and mp is not None and tp > mp:
        out.append(f"its {tp} interface vertices against our {mp} contact points: its "
                   "forces sit at every vertex of each interface polygon, ours at the "
                   "corners of the convex hull of each joint's region (the same resultants "
                   "for a no-tension joint)")
    if (fr and fr["max_rel_diff"] > 1e-2 and mp and row.get("blocks")
            and 3 * mp > 6 * row["blocks"]):
        out.append(f"forces differ by up to {fr['max_rel_diff']:.2g} of the largest joint "
                   f"force (median {fr['median_rel_diff']:.2g}): with more force "
                   f"components ({3 * mp}, three at each of our contact points) than "
                   f"equilibrium equations ({6 * row['blocks']}) the admissible state need "
                   "not be unique, and the two sides pick "
                   "different ones (ours: least complementary energy over our contact "
                   "points; its RBE: its quadratic objective over its vertex forces, "
                   "tension penalised)")
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
    ax.set_ylabel("seconds, blocks to verdict and forces (min of runs)")
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


def _ratio(a: Any, b: Any) -> Any:
    if isinstance(a, float) and isinstance(b, float) and b > 0:
        return f"{a / b:.3g}x"
    return "-"


def _cpu(d: dict, key: str = "total") -> Any:
    x = (d.get("cpu") or {}).get(key)
    return "-" if x is None else float(x)


def _proc(d: dict) -> Any:
    x = (d.get("process") or {}).get("cpu")
    if x is None and "limit" in d.get("times", {}):
        return f"> {d['times']['limit']:g} (stopped)"
    return "-" if x is None else float(x)


def timing_markdown(gen: list[dict], tg: dict | None) -> list[str]:
    """The time tables of the generated structures and the claims at the largest wall:
    both sides doing the same work (the verdict and the forces), in CPU seconds."""
    head = ["structure", "ours 2D", "ours 3D cone", "ours 3D 8-pyr", "RBE", "RBE / 2D",
            "RBE / 3D cone", "ours 2D solve", "ours 3D solve", "RBE IPOPT",
            "ours 2D process", "ours 3D process", "RBE process", "RBE / 2D process",
            "RBE / 3D process", "CRA"]
    body = []
    for r in gen:
        o, p = r["ours"], r["peer"]
        rb = p.get("rbe", {})
        a2, a3, ap = (_cpu(o.get(m, {})) for m in ("2d", "3d_cone", "3d_pyr8"))
        rt = _cpu(rb) if "cpu" in rb else _t(rb.get("times", {}))
        w2, w3, wr = _proc(o.get("2d", {})), _proc(o.get("3d_cone", {})), _proc(rb)
        body.append([r["name"], a2, a3, ap, rt, _ratio(rt, a2), _ratio(rt, a3),
                     _cpu(o.get("2d", {}), "solve"), _cpu(o.get("3d_cone", {}), "solve"),
                     _cpu(rb, "ipopt"), w2, w3, wr, _ratio(wr, w2), _ratio(wr, w3),
                     _t(p.get("cra", {}).get("times", {}))])
    lines = ["The verdict and the forces on both sides (the peer's RBE always returns its "
             "forces; ours is `check` with its force state, the state of least "
             "complementary energy), CPU seconds of each process (one thread each side, "
             "so the machine's load stretches the wall clock, hardly these). In-process: "
             "ours from the block data (the scene dict: reading and validating the "
             "blocks, contacts, assembly, problem, solve, force state), its RBE from its "
             "assembly (building it, its interface detection, its solver's set-up and "
             "IPOPT solve, after a warm-up solve in the same process); solve: our "
             "Clarabel call against its IPOPT calls. Process: the whole command as a "
             "user runs it, from the interpreter's start to its exit (imports, reading "
             "the file, the answer written): ours `rigidblocks check FILE --load-factor "
             "0 --json` (its modules compiled to bytecode beforehand, as an installed "
             "package's are and as the peer's are in its environment), its runner on the "
             "case file without the warm-up. 2D: our plane "
             "problem against its RBE on the extrusion of the same blocks (it has no 2D "
             "mode), the same RBE figure as in the 3D columns; 8-pyr: our extrusion with "
             "an inscribed 8-facet pyramid, in-process only (the command line has no "
             "pyramid). CRA: its own method, once, wall seconds.", "",
             markdown_table(head, body), ""]
    if not tg:
        return lines
    lines += [f"Claims at the {tg['case']} (CPU seconds, the minimum of the runs, load "
              f"average {tg['loadavg_start']} to {tg['loadavg_end']}; its RBE in-process "
              f"{tg['rbe_cpu_s']:.3g} s = build {tg['rbe_build_cpu_s']:.3g} + interfaces "
              f"{tg['rbe_interfaces_cpu_s']:.3g} + set-up and IPOPT "
              f"{tg['rbe_cpu_s'] - tg['rbe_build_cpu_s'] - tg['rbe_interfaces_cpu_s']:.3g}"
              + (f", its whole process {tg['rbe_process_cpu_s']:.3g} s"
                 if tg.get("rbe_process_cpu_s") else "") + "):"]
    for m, label in (("2d", "2D (ours: the plane problem; its: the extrusion)"),
                     ("3d_cone", "3D exact cone")):
        parts = []
        for key, what in (("in_process", "in-process"), ("process", "whole process")):
            ratio = tg.get(f"ratio_{m}_{key}")
            mine = tg.get(f"ours_{m}_cpu_s" if key == "in_process" else
                          f"ours_{m}_process_cpu_s")
            if ratio is None:
                continue
            goal = tg["goals"][m][key]
            parts.append(f"{ratio:.3g}x {what} ({mine:.3g} s; goal >= {goal:g}x: "
                         f"{'met' if ratio >= goal else 'NOT met'})")
        lines.append(f"- {label}, verdict and forces: " + "; ".join(parts))
    lines.append("")
    prof = tg.get("cpu_profile_3d")
    if prof:
        keys = ("read", "contacts", "assembly", "build", "solve", "state", "total")
        lines += [f"Where our 3D time goes at the {tg['case']} (exact cone, in-process, "
                  "CPU seconds, each stage's minimum over the runs; read: the scene's "
                  "blocks to a validated scene; build: the problem; solve: the Clarabel "
                  "call, one least-energy QP where the structure is admissible; state: "
                  "the joint resultants):", "",
                  markdown_table(list(keys), [[prof.get(k, 0.0) for k in keys]]), ""]
    return lines


def markdown(data: dict) -> str:
    """The results section for benchmarks/README.md, from one run's data."""
    rows, tg, hard = data["rows"], data.get("targets"), data.get("hard_cases") or []
    python = data["peer_python"] if data.get("peer_available") else None
    lines = ["## The peer: compas_cra", ""]
    if not rows:  # the non-associative section alone
        return "\n".join(lines + na_markdown(data.get("nonassoc") or {"rows": []}))
    thr = ", ".join(f"{k}={v}" for k, v in (data.get("threads") or {}).items())
    la0, la1 = data.get("loadavg_start"), data.get("loadavg_end")
    lines += [f"One session ({data.get('started', '?')} to {data.get('finished', '?')}), "
              f"both sides with the same thread settings ({thr}), interleaved per "
              "structure (its RBE, ours, our whole processes, its whole process, its "
              f"RBE, ...), {data.get('repeats')} runs each; every time is the minimum "
              "over the runs. Load average (1, 5, 15 min) "
              f"at the start {la0} and at the end {la1} (each structure's in "
              f"bench_peer.json). compas_cra {data.get('peer_version') or '-'}, its "
              "solvers on its bundled IPOPT.", ""]
    if python is None:
        lines += ["The peer was not available in this run: our side only.", ""]
    gen = [r for r in rows if r["kind"] != "peer example"]
    head = ["structure", "blocks", "ours 2D", "ours 3D cone", "ours 3D 8-pyr", "RBE",
            "CRA"]
    lines += ["Verdicts (self-weight):", "", markdown_table(head, [
        [r["name"], r["blocks"], _v(r["ours"], "2d"), _v(r["ours"], "3d_cone"),
         _v(r["ours"], "3d_pyr8"), _v(r["peer"], "rbe"), _v(r["peer"], "cra")]
        for r in gen]), ""]
    lines += timing_markdown(gen, tg)
    if hard:
        lines += ["Hard cases:", "", markdown_table(
            ["method", "case", "expected", "answer", "grade"],
            [[h["method"], h["case"], h["expected"], h["answer"], h["grade"]]
             for h in hard]), ""]
    loose = [h for h in hard if "d_bnd" in h["method"]]
    if loose:
        lines += ["CRA's verdict on the arches depends on its displacement bound: with its "
                  "solver defaults (d_bnd = 0.001, eps = 0.0001) it answers "
                  + ", ".join(sorted({h["answer"] for h in hard
                                      if h["method"] == "compas_cra CRA"
                                      and h["case"].startswith("arch")}))
                  + "; with the bound of its own examples (d_bnd = 0.1, eps = 0) it answers "
                  + ", ".join(sorted({h["answer"] for h in loose})) + ".", ""]
    ex = [r for r in rows if r["kind"] == "peer example"]
    if ex:
        head = ["example", "free blocks", "ours joints / points", "its interfaces / "
                "vertices", "ours cone", "ours 8-pyr", "RBE", "its method", "forces vs RBE "
                "(max rel. diff.)", "ours s", "RBE s"]
        body = []
        for r in ex:
            o, p = r["ours"], r["peer"]
            c = o.get("3d_cone", {})
            rbe = p.get("rbe", {})
            own = [k for k in p if k != "rbe"]
            fr = r.get("forces_3d_cone_vs_rbe")
            body.append([
                r["name"].removeprefix("peer "), r["blocks"] if r["blocks"] else "-",
                f"{c['joints']} / {c['points']}" if "joints" in c else "-",
                f"{rbe.get('n_interfaces', '-')} / {rbe.get('n_vertices', '-')}",
                c.get("verdict", "-") if "total" in c else "not modelled",
                _v(o, "3d_pyr8"), _v(p, "rbe"),
                f"{own[0].upper()}: {p[own[0]]['verdict']}" if own else "(RBE)",
                f"{fr['max_rel_diff']:.2g} on {fr['joints']}" if fr else "-",
                _t(c), _t(rbe.get("times", {}))])
        lines += ["The peer's samples and documented examples, each with its own set-up "
                  "(supports, densities, rotation, friction, interface tolerances, solver), "
                  "read on our side from the COMPAS file of the prepared assembly "
                  "(`rigidblocks.compas`; contact tolerance: its tmax over the scene "
                  "size):", "", markdown_table(head, body), ""]
        nm = [r for r in ex if "total" not in r["ours"].get("3d_cone", {})]
        if nm:
            lines += ["Refused by our scene validation (3D blocks are closed polyhedra with "
                      "planar faces, convex or not; a face whose vertices lie off its plane "
                      f"by more than {POLY_TOL:g} x the block's size is refused with the "
                      "deviation stated, not triangulated), in its own words: " + "; ".join(
                          f"{r['name'].removeprefix('peer ')} "
                          "(" + r["ours"].get("3d_cone", {}).get("verdict", "")
                          .removeprefix("not modelled: ") + ")"
                          for r in nm), ""]
        notes = [(r["name"].removeprefix("peer "), model_notes(r)) for r in ex]
        notes = [(n, d) for n, d in notes if d]
        if notes:
            lines += ["Where the two models of an example differ (interfaces, contact "
                      "points) or their forces do:", ""]
            lines += [f"- {n}: " + "; ".join(d) + "." for n, d in notes]
            lines += [""]
        diffs = [(r["name"].removeprefix("peer "), differences(r)) for r in ex]
        diffs = [(n, d) for n, d in diffs if d]
        if diffs:
            lines += ["Where the verdicts differ, the models (on the examples we do not "
                      "model, where its RBE and its CRA differ):", ""]
            lines += [f"- {n}: " + "; ".join(d) + "." for n, d in diffs]
            lines += [""]
    lines += ["RBE counts as admissible when its penalised tension is below "
              f"{RBE_TENSION_TOL:g} of the total compression; its 8-facet pyramid "
              "circumscribes the Coulomb cone, ours (`pyramid=8`) is inscribed. Time limits "
              "stop peer runs that take too long (see bench_peer.json)."]
    if data.get("nonassoc"):
        lines += [""] + na_markdown(data["nonassoc"])
    return "\n".join(lines)


def _write(data: dict, d: Path) -> None:
    (d / f"{NAME}.md").write_text(markdown(data).rstrip() + "\n")
    if data["rows"]:
        chart(data["rows"], d / f"{NAME}.png")


def redraw(out: str | Path | None) -> dict:
    """Rewrite bench_peer.md and the PNG from the run's bench_peer.json."""
    d = out_dir(out)
    data = json.loads((d / f"{NAME}.json").read_text())
    data["targets"], data["hard_cases"] = targets(data["rows"]), hard_cases(data["rows"])
    na = data.get("nonassoc")
    if na:
        for r in na["rows"]:
            if r.get("peer"):
                r["notes"] = na_differences(r)
        na["agreement"] = na_agreement(na["rows"])
    (d / f"{NAME}.json").write_text(json.dumps(data, indent=1) + "\n")
    _write(data, d)
    return data


def main(argv: Sequence[str] | None = None) -> dict:
    """Run the comparison, write bench_peer.{json,md,png}; return the results."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=None, help="results folder")
    parser.add_argument("--tiny", action="store_true", help="smallest sizes only")
    parser.add_argument("--peer-python", default=None,
                        help="the peer's Python ('none': our side only)")
    parser.add_argument("--repeats", type=int, default=REPEATS,
                        help=f"runs per structure and side (default {REPEATS})")
    parser.add_argument("--rbe-timeout", type=float, default=300.0)
    parser.add_argument("--cra-timeout", type=float, default=150.0)
    parser.add_argument("--big-cra-timeout", type=float, default=120.0,
                        help="time limit of CRA on the 1,000-block wall")
    parser.add_argument("--no-examples", action="store_true",
                        help="leave out the peer's samples and examples")
    parser.add_argument("--redraw", action="store_true",
                        help="rewrite the tables and chart from the existing JSON")
    parser.add_argument("--only", choices=("static", "nonassoc"), default=None,
                        help="run one section: the static comparison, or non-associative "
                        "friction (its CRA and CRA-penalty against our flow=\"non-"
                        "associative\"); the other section's figures in bench_peer.json "
                        "are kept")
    args = parser.parse_args(argv)
    if args.redraw:
        return redraw(args.out)
    if args.repeats < 1:
        parser.error("--repeats must be >= 1")
    sizes = dict(TINY) if args.tiny else {
        "arches": ARCHES, "walls": WALLS, "hard": HARD_ARCHES,
        "examples": () if args.no_examples else PEER_EXAMPLES}
    na_sizes = dict(NA_TINY) if args.tiny else {
        **NA_SIZES, "examples": () if args.no_examples else PEER_EXAMPLES}
    python = peer_python(args.peer_python)
    if python is None:
        print("peer unavailable: our side only", file=sys.stderr)
    timeouts = {"rbe": args.rbe_timeout, "cra": args.cra_timeout,
                "cra_big": args.big_cra_timeout}
    d = out_dir(args.out)
    earlier = (read_results(d, NAME) if (args.only and (d / f"{NAME}.json").exists())
               else None)
    if args.only == "nonassoc":
        na = run_nonassoc(na_sizes, python, timeouts, args.repeats)
        data = earlier or {"peer_available": python is not None, "peer_python": python,
                           "peer_version": na["peer_version"], "rows": [],
                           "targets": None, "hard_cases": []}
        data["nonassoc"] = na
        if earlier is None:
            write_results(d, NAME, data, markdown(data))
        else:
            rewrite_results(d, NAME, data, markdown(data))
        if args.out is None and not args.tiny:
            import make_readme

            make_readme.main([])
        return data
    started, la0 = time.strftime("%Y-%m-%d %H:%M:%S %Z"), loadavg()
    rows = bench(sizes, python, timeouts, args.repeats)
    data = {"peer_available": python is not None, "peer_python": python,
            "peer_version": next((p.get("version") for r in rows
                                  for p in r["peer"].values() if p.get("version")), None),
            "threads": {k: os.environ.get(k) for k in THREADS},
            "peer_threads": next((p.get("threads") for r in rows
                                  for p in r["peer"].values() if p.get("threads")), None),
            "repeats": args.repeats, "started": started, "loadavg_start": la0,
            "finished": time.strftime("%Y-%m-%d %H:%M:%S %Z"), "loadavg_end": loadavg(),
            "timeouts_s": timeouts, "rbe_tension_tol": RBE_TENSION_TOL,
            "rows": rows}
    data["targets"], data["hard_cases"] = targets(rows), hard_cases(rows)
    if args.only is None:
        data["nonassoc"] = run_nonassoc(na_sizes, python, timeouts, args.repeats)
    elif earlier and earlier.get("nonassoc"):
        data["nonassoc"] = earlier["nonassoc"]
    write_results(d, NAME, data, markdown(data))
    chart(rows, d / f"{NAME}.png")
    if args.out is None and not args.tiny:
        import make_readme

        make_readme.main([])
    return data


if __name__ == "__main__":
    main()
