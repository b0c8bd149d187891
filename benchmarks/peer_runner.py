"""Run compas_cra (the peer) on one assembly of polyhedral blocks; write its answer.

Run with the peer's Python (a separate environment with ``compas_cra`` installed, never
a dependency of rigidblocks), one case and one method per process, so that the caller
can stop a solve that runs too long:

    /path/to/peer/python benchmarks/peer_runner.py CASE.json OUT.json METHOD [cold]

with METHOD one of rbe, cra, cra_penalty, export.

``CASE.json``: ``{"name", "mu", "blocks": [{"id", "vertices": [[x, y, z], ...],
"faces": [[i, j, k, ...], ...], "support": bool, "density": float}, ...],
"interfaces": {"nmax", "tmax", "amin"}}``, gravity along -z, weight = density x volume.

``OUT.json``: ``{"method", "status": "solved" | "failed" | "error", "message",
"times": {"build", "interfaces", "solve", "total"}, "n_blocks", "n_interfaces",
"n_vertices", "joints": [{"pair": [id_i, id_j], "normal": [nx, ny, nz], "fn": N,
"tension": T_penalty, "fu", "fv"}, ...]}``. ``fn`` is the interface's total
compressive normal force (sum of ``c_np``), ``tension`` the total of the penalised
tensile part ``c_nn`` (RBE and CRA-penalty only), ``normal`` the interface frame's z
axis (the direction of ``fn`` on the second block of the pair).

Methods (Kao et al. 2022, doi:10.1016/j.cad.2022.103216): ``rbe`` rigid-block
equilibrium (paper Eq. 6, a quadratic program with a tension penalty, friction as an
8-facet pyramid), ``cra`` coupled rigid-block analysis (Eq. 11, non-associative,
complementarity constraints), ``cra_penalty`` (Eq. 14).

Besides ``blocks``, a case may name one of the peer's own set-ups instead (its samples
and documented examples): ``"sample": FILE`` (a file of ``compas_cra.SAMPLE``), or
``"boxes": [[x, y, z], ...]`` (unit boxes centred there, the first ones the supports
given), or ``"arch": {"height", "span", "thickness", "depth", "num_blocks"}``
(``compas_cra.geometry.Arch``); then ``"rotate": {"axis": [x, y, z], "deg": a}`` (the
whole assembly about the origin, as ``rotate_assembly``), ``"supports"``,
``"density": {node: value}`` (``density_setup``), ``"density_default"`` (the
solver's ``density`` for blocks without one), and ``"interfaces": null`` to keep the
interfaces the sample file carries instead of detecting them. ``"export": PATH`` writes
the prepared assembly (supports, densities, rotation; before its interfaces are
detected) as COMPAS JSON, untimed, for the other tool to read; the method ``export``
does only that (no interfaces, no solve; ``status`` "exported"). ``times`` also has
``setup`` and ``ipopt``: the solver's own problem set-up and IPOPT solve, as its timer
prints them; ``cpu`` has the process CPU seconds of the same stages (``ipopt``: the
IPOPT calls alone). Thread settings come from the environment (the caller sets them).

Before the timed stages a process solves two stacked cubes (:func:`warm_up`), so that
the stages' times leave out first-call costs; with ``cold`` it does not: the process is
then what a user's script pays from start to exit (interpreter, imports, reading the
case file, the stages, writing the answer), timed by the caller from outside.
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import re
import sys
import time
import traceback


def build_assembly(case: dict):
    """The compas_cra assembly of the case's blocks (supports flagged)."""
    from compas.datastructures import Mesh
    from compas_assembly.datastructures import Block
    from compas_cra.datastructures import CRA_Assembly

    assembly = CRA_Assembly()
    keys = {}
    supports = []
    for b in case["blocks"]:
        mesh = Mesh.from_vertices_and_faces(b["vertices"], b["faces"])
        block = Block.from_vertices_and_faces(*mesh.to_vertices_and_faces())
        block.attributes["density"] = float(b["density"])
        key = assembly.add_block(block)
        keys[key] = b["id"]
        if b["support"]:
            supports.append(key)
    assembly.set_boundary_conditions(supports)
    return assembly, keys


def load_sample(case: dict):
    """One of compas_cra's own sample assemblies (``case["sample"]``, a file name)."""

    import compas
    import compas_cra
    from compas_cra.datastructures import CRA_Assembly

    assembly = compas.json_load(os.path.join(compas_cra.SAMPLE, case["sample"]))
    assembly = assembly.copy(cls=CRA_Assembly)
    supports = case.get("supports", [0])
    if supports is not None:  # None: the file's own
        assembly.set_boundary_conditions(supports)
    keys = {k: str(k) for k in assembly.graph.nodes()}
    return assembly, keys


def prepare(case: dict):
    """The assembly of a case: its blocks, or one of the peer's samples or examples."""
    from compas_cra.datastructures import CRA_Assembly

    if "sample" in case:
        assembly, keys = load_sample(case)
    elif "boxes" in case:
        from compas.geometry import Box, Frame, Translation
        from compas_assembly.datastructures import Block

        assembly = CRA_Assembly()
        for k, c in enumerate(case["boxes"]):
            frame = Frame.worldXY().transformed(Translation.from_vector(c))
            assembly.add_block(Block.from_shape(Box(1, 1, 1, frame=frame)), node=k)
        assembly.set_boundary_conditions(case.get("supports", [0]))
        keys = {k: str(k) for k in assembly.graph.nodes()}
    elif "arch" in case:
        from compas_cra.geometry import Arch

        assembly = Arch(**case["arch"]).assembly().copy(cls=CRA_Assembly)
        supports = case.get("supports")
        if supports is not None:
            assembly.set_boundary_conditions(supports)
        keys = {k: str(k) for k in assembly.graph.nodes()}
    else:
        return build_assembly(case)
    if case.get("density"):
        from compas_cra.equilibrium import density_setup

        density_setup(assembly, {int(k): float(v) for k, v in case["density"].items()})
    if case.get("rotate"):
        rot = case["rotate"]
        assembly.rotate_assembly([0, 0, 0], rot["axis"], rot["deg"])
    if case.get("export"):
        import compas

        compas.json_dump(assembly, case["export"])
    return assembly, keys


def export_blocks(assembly, keys) -> list[dict]:
    """The assembly's blocks as polyhedra (so that another tool can model them)."""
    blocks = []
    for node in assembly.graph.nodes():
        block = assembly.graph.node_attribute(node, "block")
        verts, faces = block.to_vertices_and_faces()
        blocks.append({"id": keys[node], "vertices": [list(map(float, v)) for v in verts],
                       "faces": [list(f) for f in faces],
                       "support": bool(assembly.graph.node_attribute(node, "is_support")),
                       "density": float(block.attributes.get("density", 1.0))})
    return blocks


def warm_up() -> None:
    """Solve two stacked cubes once, so that first-call costs are not timed."""
    from compas_cra.algorithms import assembly_interfaces_numpy
    from compas_cra.equilibrium import rbe_solve

    cube = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1],
            [0, 1, 1]]
    faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6],
             [3, 0, 4, 7]]
    blocks = [{"id": str(k), "vertices": [[x, y, z + k] for x, y, z in cube], "faces": faces,
               "support": k == 0, "density": 1.0} for k in range(2)]
    assembly, _ = build_assembly({"blocks": blocks})
    with contextlib.redirect_stdout(io.StringIO()):
        assembly_interfaces_numpy(assembly, nmax=2, tmax=1e-6, amin=1e-6)
        rbe_solve(assembly, mu=0.6)


def _time_ipopt() -> list[float]:
    """Record the CPU seconds of each IPOPT solve of the peer's solvers (its
    ``solve_nlp`` as its solver module calls it, wrapped); returns the list it fills."""
    from compas_cra.equilibrium import cra_native

    spent: list[float] = []
    inner = getattr(cra_native.solve_nlp, "__wrapped__", cra_native.solve_nlp)

    def timed(*args, **kwargs):
        c0 = time.process_time()
        try:
            return inner(*args, **kwargs)
        finally:
            spent.append(time.process_time() - c0)

    timed.__wrapped__ = inner
    cra_native.solve_nlp = timed
    return spent


def run(case: dict, method: str, cold: bool = False) -> dict:
    """Build, detect interfaces and solve; the answer as a JSON-ready dict (``cold``:
    without the warm-up solve)."""
    from compas_cra.algorithms import assembly_interfaces_numpy
    from compas_cra.equilibrium import cra_penalty_solve, cra_solve, rbe_solve

    solvers = {"rbe": rbe_solve, "cra": cra_solve, "cra_penalty": cra_penalty_solve}
    out: dict = {"method": method, "case": case.get("name"), "times": {}, "cold": cold}
    if not cold:
        warm_up()
    out["cpu"] = {}
    c_all = time.process_time()
    t_all = time.perf_counter()
    t0, c0 = time.perf_counter(), time.process_time()
    if "blocks" in case:
        assembly, keys = build_assembly(case)
    else:
        export, case["export"] = case.get("export"), None
        assembly, keys = prepare(case)
    out["times"]["build"] = time.perf_counter() - t0
    out["cpu"]["build"] = time.process_time() - c0
    if "blocks" not in case and export:
        import compas

        compas.json_dump(assembly, export)  # untimed: the prepared assembly
    opts = case.get("interfaces", {})
    t0, c0 = time.perf_counter(), time.process_time()
    if opts is not None:
        assembly_interfaces_numpy(assembly, nmax=int(opts.get("nmax", 10)),
                                  tmax=float(opts.get("tmax", 1e-6)),
                                  amin=float(opts.get("amin", 1e-6)))
    out["times"]["interfaces"] = time.perf_counter() - t0
    out["cpu"]["interfaces"] = time.process_time() - c0
    edges = list(assembly.graph.edges())
    out["n_blocks"] = assembly.graph.number_of_nodes()
    out["n_interfaces"] = sum(len(assembly.graph.edge_attribute(e, "interfaces"))
                              for e in edges)
    out["n_vertices"] = sum(len(i.points) for e in edges
                            for i in assembly.graph.edge_attribute(e, "interfaces"))
    kwargs = {"mu": float(case["mu"]), "density": float(case.get("density_default", 1.0))}
    if method != "rbe":
        kwargs.update(d_bnd=float(case.get("d_bnd", 1e-3)), eps=float(case.get("eps", 1e-4)))
    ipopt_cpu = _time_ipopt()
    t0, c0 = time.perf_counter(), time.process_time()
    log = io.StringIO()
    try:
        with contextlib.redirect_stdout(log):
            solvers[method](assembly, timer=True, **kwargs)
        out["status"] = "solved"
        out["message"] = ""
    except ValueError as exc:
        out["status"] = "failed"
        out["message"] = str(exc).splitlines()[0][:300]
    out["times"]["solve"] = time.perf_counter() - t0
    out["cpu"]["solve"] = time.process_time() - c0
    if ipopt_cpu:
        out["cpu"]["ipopt"] = sum(ipopt_cpu)
    for label, key in (("set up", "setup"), ("solving", "ipopt")):
        m = re.search(rf"--- {label} time: ([0-9.eE+-]+) seconds ---", log.getvalue())
        if m:
            out["times"][key] = float(m.group(1))
    out["times"]["total"] = time.perf_counter() - t_all
    out["cpu"]["total"] = time.process_time() - c_all
    joints = []
    if out["status"] == "solved":
        for u, v in edges:
            for itf in assembly.graph.edge_attribute((u, v), "interfaces"):
                forces = itf.forces or []
                joints.append({
                    "pair": [keys[u], keys[v]],
                    "normal": [float(c) for c in itf.frame.zaxis],
                    "area": float(itf.size),
                    "fn": sum(f["c_np"] for f in forces),
                    "tension": sum(f["c_nn"] for f in forces),
                    "fu": sum(f["c_u"] for f in forces),
                    "fv": sum(f["c_v"] for f in forces),
                })
    out["joints"] = joints
    out["threads"] = {k: os.environ.get(k) for k in
                      ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}
    return out


def main(argv: list[str]) -> int:
    """``peer_runner.py CASE.json OUT.json METHOD [cold]``; exit 0 when OUT.json was
    written."""
    cold = argv[3:] == ["cold"]
    if len(argv) != 3 and not cold:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    case_path, out_path, method = argv[:3]
    with open(case_path) as fh:
        case = json.load(fh)
    try:
        if method == "export":
            prepare(case)
            out = {"method": method, "case": case.get("name"), "status": "exported",
                   "times": {}, "joints": []}
        else:
            out = run(case, method, cold)
    except Exception as exc:  # the peer's own error, reported rather than raised
        out = {"method": method, "case": case.get("name"), "status": "error",
               "message": f"{type(exc).__name__}: {exc}"[:300],
               "traceback": traceback.format_exc()[-2000:], "times": {}, "joints": []}
    try:
        import compas_cra
        out["version"] = compas_cra.__version__
    except ImportError:
        pass
    with open(out_path, "w") as fh:
        json.dump(out, fh)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
