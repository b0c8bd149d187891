"""The 3D report view: three.js shipped in the package against plotly's offline bundle.

For each 3D scene (the 3D examples and a running-bond wall of about 5,000 blocks from
``wall3d``, each after ``max_load_multiplier``) the same picture is written twice: by
the report (three.js r169 inlined; all blocks one merged mesh, the mechanism moved in
the browser from the blocks' virtual velocities) and by plotly (``plotly.min.js``
inlined; all blocks one Mesh3d trace, their edges one Scatter3d trace, and the
mechanism as animation frames, each of which has to carry every vertex again). Both
pages are opened in headless Chromium (WebGL on the SwiftShader software rasteriser,
no GPU: the times are upper bounds for a machine with one) and measured:

* the HTML file's size;
* the time to the first drawn frame, read by the page itself (``performance.now()``
  when the view is drawn, counted from navigation), and Chromium's whole run;
* for three.js, the interaction the page times itself (``#rb-bench``): a frame while
  turning the view, a frame while the mechanism slider moves (every vertex moved on
  the CPU, then drawn), a hover's ray cast over the joints' dots.

Run as ``python benchmarks/bench_report.py [--tiny] [--out DIR]`` (needs chromium and,
for the comparison, plotly).
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent))

from common import markdown_table, write_results  # noqa: E402

#: frames of the plotly animation (amplitudes 0 .. 1 of the mechanism)
PLOTLY_FRAMES = 11

PLOTLY_POST = """
var gd = document.getElementById('{plot_id}');
var ds = document.documentElement.dataset;
ds.viewerFirstFrameMs = performance.now().toFixed(1);
ds.viewerReady = '1';
"""

ERROR_HOOK = """<script>window.rbErrors=[];function rbErr(m){window.rbErrors.push(String(m));
var b=document.getElementById('rb-errors');if(b){b.hidden=false;b.textContent+=m+'\\n';}}
window.addEventListener('error',function(e){rbErr('error: '+e.message);},true);
</script>"""


def scenes(tiny: bool) -> list[tuple[str, Any]]:
    import rigidblocks as rb
    from rigidblocks.generators.solids import wall3d

    out = [(p.stem, rb.read_scene(p)) for p in sorted((HERE.parent / "examples").glob("*.json"))]
    out = [(n, s) for n, s in out if s.dimension == 3]
    if tiny:
        out.append(("wall3d 4 x 5", wall3d(courses=4, blocks_per_course=5,
                                           load_direction="in_plane")))
    else:
        out.append(("wall3d 50 x 100", wall3d(courses=50, blocks_per_course=100,
                                              load_direction="in_plane")))
    return out


def plotly_page(scene: Any, result: Any) -> str:
    """The same view with plotly: blocks, edges, and the mechanism as frames."""
    import numpy as np
    import plotly.graph_objects as go

    from rigidblocks.plotting.plot3d import displaced_vertices
    from rigidblocks.reporting.view3d import geometry
    from rigidblocks.scene.geometry import scene_size
    from rigidblocks.scene.polyhedra import polyhedron_volume_centroid

    g = geometry(scene)
    tri = g["triangles"]
    edges = g["edges"]

    def traces(pos: np.ndarray) -> list[Any]:
        ex = np.full((len(edges), 3, 3), np.nan)
        ex[:, 0], ex[:, 1] = pos[edges[:, 0]], pos[edges[:, 1]]
        ex = ex.reshape(-1, 3)
        return [go.Mesh3d(x=pos[:, 0], y=pos[:, 1], z=pos[:, 2], i=tri[:, 0], j=tri[:, 1],
                          k=tri[:, 2], color="#d9c7a7", flatshading=True),
                go.Scatter3d(x=ex[:, 0], y=ex[:, 1], z=ex[:, 2], mode="lines",
                             line={"color": "#222", "width": 1}, hoverinfo="skip")]

    frames = []
    mech = getattr(result, "mechanism", None)
    if mech is not None:
        cen = np.array([polyhedron_volume_centroid(b)[1] for b in scene.blocks])
        vel = np.asarray(mech.velocities, dtype=float)
        reach = max(float(np.linalg.norm(v[:3]) + np.linalg.norm(v[3:6]) *
                          np.linalg.norm(b.points - c, axis=1).max())
                    for b, c, v in zip(scene.blocks, cen, vel, strict=True))
        s_max = 0.1 * scene_size(scene) / reach if reach > 0 else 0.0
        for k in range(PLOTLY_FRAMES):
            t = k / (PLOTLY_FRAMES - 1)
            pos = np.concatenate(displaced_vertices(scene, vel, t * s_max, cen))
            frames.append(go.Frame(data=traces(pos), name=f"{t:.1f}"))
    fig = go.Figure(data=traces(g["positions"]), frames=frames)
    fig.update_layout(scene={"aspectmode": "data"}, showlegend=False,
                      margin={"l": 0, "r": 0, "t": 0, "b": 0}, height=560)
    if frames:
        fig.update_layout(sliders=[{"steps": [
            {"method": "animate", "label": f.name,
             "args": [[f.name], {"mode": "immediate", "frame": {"duration": 0}}]}
            for f in frames]}])
    page = fig.to_html(include_plotlyjs=True, full_html=True, post_script=PLOTLY_POST)
    return page.replace("<head>", "<head>" + ERROR_HOOK, 1).replace(
        "<body>", '<body><pre id="rb-errors" hidden></pre>', 1)


def measure(html: Path, fragment: str = "") -> dict[str, Any]:
    from rigidblocks.reporting.browser import page_state

    st = page_state(html, fragment=fragment, timeout=600)
    d = st.data
    return {"errors": list(st.errors), "chromium_s": st.seconds,
            "first_frame_ms": float(d["viewer-first-frame-ms"])
            if "viewer-first-frame-ms" in d else None,
            "rotate_ms": float(d["bench-rotate-ms"]) if "bench-rotate-ms" in d else None,
            "slider_ms": float(d["bench-slider-ms"]) if "bench-slider-ms" in d else None,
            "still_ms": float(d["bench-still-ms"]) if "bench-still-ms" in d else None,
            "hover_ms": float(d["bench-hover-ms"]) if "bench-hover-ms" in d else None,
            "triangles": int(d["viewer-triangles"]) if "viewer-triangles" in d else None,
            "draw_calls": int(d["viewer-draw-calls"]) if "viewer-draw-calls" in d else None,
            "painted": float(d["viewer-painted"]) if "viewer-painted" in d else None}


def main(argv: Sequence[str] | None = None) -> dict[str, Any]:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tiny", action="store_true", help="small scenes only")
    ap.add_argument("--out", default=None, help="results folder (default benchmarks/results)")
    ap.add_argument("--no-plotly", action="store_true", help="three.js only")
    ap.add_argument("--saved", default=None,
                    help="a pickle of (scene, max_load_multiplier result) for the large "
                    "wall, to measure the pages without solving it again (the solve "
                    "takes minutes and is not what this benchmark measures)")
    args = ap.parse_args(argv)

    import rigidblocks as rb
    from rigidblocks.reporting.browser import find_chromium, page_state

    if find_chromium() is None:
        raise SystemExit("bench_report needs chromium on the PATH")
    try:
        import plotly  # noqa: F401
        with_plotly = not args.no_plotly
    except ImportError:
        with_plotly = False
    rows: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory() as tmp:
        empty = Path(tmp) / "empty.html"
        empty.write_text("<!DOCTYPE html><html><body></body></html>")
        baseline = page_state(empty).seconds
        saved = None
        if args.saved:
            import pickle

            with open(args.saved, "rb") as fh:
                saved = pickle.load(fh)
        for name, scene in scenes(args.tiny):
            t = time.perf_counter()
            if saved is not None and name.startswith("wall3d") and \
                    len(saved[0].blocks) == len(scene.blocks):
                scene, res = saved
            else:
                res = rb.max_load_multiplier(scene)
            solve_s = time.perf_counter() - t
            row: dict[str, Any] = {"scene": name, "blocks": len(scene.blocks),
                                   "joints": res.contacts.n_joints, "status": res.status,
                                   "solve_s": solve_s}
            t = time.perf_counter()
            page = rb.report(scene, res)
            row["three_build_s"] = time.perf_counter() - t
            path = Path(tmp) / "three.html"
            path.write_text(page, encoding="utf-8")
            row["three_bytes"] = path.stat().st_size
            row["three"] = measure(path, "rb-bench")
            if with_plotly:
                t = time.perf_counter()
                ppage = plotly_page(scene, res)
                row["plotly_build_s"] = time.perf_counter() - t
                ppath = Path(tmp) / "plotly.html"
                ppath.write_text(ppage, encoding="utf-8")
                row["plotly_bytes"] = ppath.stat().st_size
                row["plotly"] = measure(ppath)
            rows.append(row)
            print(name, {k: v for k, v in row.items()}, flush=True)
    load = os.getloadavg() if hasattr(os, "getloadavg") else None
    md = markdown(rows, baseline, with_plotly, load)
    write_results(args.out, "bench_report", {"rows": rows, "chromium_baseline_s": baseline,
                                             "plotly_frames": PLOTLY_FRAMES,
                                             "load_average": load}, md)
    return {"rows": rows, "baseline": baseline}


def markdown(rows: list[dict[str, Any]], baseline: float, with_plotly: bool,
             load: Sequence[float] | None = None) -> str:
    def mb(b: int) -> str:
        return f"{b / 1e6:.2f} MB"

    head = ["scene", "blocks", "joints", "three.js HTML", "first frame ms", "Chromium s",
            "turn ms/frame", "slider ms/frame", "still frame ms", "hover ms", "triangles",
            "draw calls"]
    if with_plotly:
        head += ["plotly HTML", "plotly first frame ms", "plotly Chromium s"]
    body = []
    for r in rows:
        t = r["three"]
        line = [r["scene"], r["blocks"], r["joints"], mb(r["three_bytes"]),
                t["first_frame_ms"], t["chromium_s"], t["rotate_ms"], t["slider_ms"],
                t["still_ms"], t["hover_ms"], t["triangles"], t["draw_calls"]]
        if with_plotly:
            p = r.get("plotly", {})
            line += [mb(r["plotly_bytes"]), p.get("first_frame_ms"), p.get("chromium_s")]
        body.append(line)
    return ("## The 3D report view: three.js or plotly\n\n"
            "`python benchmarks/bench_report.py`: each scene after `max_load_multiplier`, "
            "written as the report's three.js view and as the same picture with plotly "
            f"({PLOTLY_FRAMES} animation frames for the mechanism), opened in headless "
            "Chromium with software WebGL (SwiftShader, no GPU; Chromium's start-up on an "
            f"empty page is {baseline:.2f} s). First frame: `performance.now()` when the "
            "view is drawn, from navigation. Turn and slider: a frame while turning the "
            "view and while the mechanism slider moves (every vertex moved on the CPU), "
            "each waited for until drawn; hover: one ray cast over the joints' dots. "
            "Still frame: the full view once it stops moving. Chromium s: the whole headless "
            "run, start-up included. Scenes of more than 20,000 triangles are drawn without "
            "multisampling, and without their edges while the view moves."
            + (f" Load average during the run: {load[0]:.1f} on "
               f"{os.cpu_count()} cores (a shared machine: the times are upper bounds)."
               if load else "") + "\n\n"
            + markdown_table(head, body) + "\n")


if __name__ == "__main__":
    main()
