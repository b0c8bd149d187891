"""Model refinement: how f*, lambda* and the time change as the model is refined.

Three refinements, each compared with its finest model; the coarsest adequate model is
the coarsest one from which every finer model is within 1e-3 relative of the finest
("model no more than a scene needs").

* Voussoirs per arch: the semicircular arch generator (t/R = 0.15, radial joints,
  abutments, 8 segments per voussoir face) with N = 6 ... 200 voussoirs; f* under the
  dead load alone, lambda* of the horizontal live body force at f = 0.6.
* Points per 3D joint: the seed reference model extruded to 3D, with every polygon edge
  split into k collinear segments before the extrusion. The 2D contact detection merges
  collinear vertices (still two points per joint), while in 3D each split side face
  becomes its own planar face, so a joint becomes k rectangular contact polygons: 4k
  points per joint. The statics do not change (f* = 0.5 and lambda* = 1.2, seed paper).
* Pyramid facets against the cone: a 3 x 3 running-bond wall extruded to 3D under a
  horizontal live body force in a diagonal direction of the plan, 30 degrees from the
  wall's axis; each Coulomb cone replaced by an inscribed pyramid of k = 4 ... 128
  facets, against the exact second-order cone. An inscribed k-facet pyramid
  under-estimates the friction capacity in the worst direction by the factor
  cos(pi / k). The pyramids' vertices lie at multiples of 360 / k degrees from the
  joint's tangent axes, so a load at 45 degrees would meet a vertex (the exact
  capacity) for every k >= 8; 30 degrees is a vertex of none of k = 4 ... 128.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import markdown_table, out_dir, write_results  # noqa: E402

from rigidblocks.analyses import max_load_multiplier, min_friction  # noqa: E402
from rigidblocks.contacts import detect_contacts  # noqa: E402
from rigidblocks.generators import build  # noqa: E402
from rigidblocks.io.scene_file import read_scene  # noqa: E402
from rigidblocks.scene.extrude import extrude  # noqa: E402
from rigidblocks.scene.model import Scene, make_block  # noqa: E402

NAME = "bench_refinement"
ROOT = Path(__file__).resolve().parents[1]
RTOL = 1e-3
VOUSSOIRS = (6, 8, 10, 12, 15, 20, 25, 30, 40, 50, 60, 80, 100, 150, 200)
SPLITS = (1, 2, 4, 8, 16)
PYRAMIDS = (4, 8, 16, 32, 64, 128)
LOAD_ANGLE = 30.0


def split_edges(scene: Scene, k: int) -> Scene:
    """The same 2D scene with every polygon edge split into ``k`` collinear segments."""
    blocks = []
    for b in scene.blocks:
        P = np.asarray(b.points, dtype=float)
        pts = [tuple(float(v) for v in P[i] + (P[(i + 1) % len(P)] - P[i]) * j / k)
               for i in range(len(P)) for j in range(k)]
        blocks.append(make_block(b.id, pts, support=b.support, unit_weight=b.unit_weight))
    return scene.with_changes(blocks=tuple(blocks))


def diagonal_wall(courses: int = 3, per_course: int = 3, h: float = 1.0,
                  angle_deg: float = LOAD_ANGLE) -> Scene:
    """An extruded running-bond wall under a horizontal live body force of magnitude
    ``h`` times the weight, ``angle_deg`` from the wall's axis in plan."""
    s = extrude(build("wall", courses=courses, blocks_per_course=per_course))
    t = math.radians(angle_deg)
    return s.with_changes(live_body_force=(h * math.cos(t), h * math.sin(t), 0.0))


def _timed(fn: Callable[[], Any]) -> tuple[Any, float]:
    t0 = time.perf_counter()
    v = fn()
    return v, time.perf_counter() - t0


def measure(scene: Scene, lf_friction: float, pyramid: int | None = None) -> dict[str, Any]:
    """f* at load factor ``lf_friction`` and lambda* (scene friction) with their times."""
    kw = {} if pyramid is None else {"pyramid": pyramid}
    fr, tf = _timed(lambda: min_friction(scene, lf_friction, state=False, compare_dry=False,
                                         rtol=1e-7, **kw))
    lr, tl = _timed(lambda: max_load_multiplier(scene, state=False, compare_dry=False,
                                                rtol=1e-6, **kw))
    c = detect_contacts(scene)
    return {"blocks": len(scene.blocks), "joints": int(c.n_joints), "points": int(c.n_points),
            "f*": fr.friction_factor, "lambda*": lr.load_multiplier,
            "seconds_f": tf, "seconds_lambda": tl}


def relative(rows: list[dict[str, Any]]) -> None:
    """Add the relative differences to the last (finest) row."""
    fin = rows[-1]
    for r in rows:
        for q in ("f*", "lambda*"):
            a, b = r[q], fin[q]
            r[f"diff_{q}"] = (abs(a - b) / abs(b) if a is not None and b is not None
                              else math.inf)


def coarsest(rows: list[dict[str, Any]], key: str) -> Any:
    """The coarsest level from which every finer level is within RTOL of the finest."""
    best = rows[-1][key]
    for r in reversed(rows):
        if max(r["diff_f*"], r["diff_lambda*"]) > RTOL:
            break
        best = r[key]
    return best


def run_arches(levels: tuple[int, ...]) -> list[dict[str, Any]]:
    rows = []
    for n in levels:
        r = measure(build("arch", voussoirs=n, thickness=0.15), 0.0)
        rows.append({"voussoirs": n, **r})
    relative(rows)
    return rows


def run_splits(levels: tuple[int, ...]) -> list[dict[str, Any]]:
    ref = read_scene(ROOT / "examples" / "reference.json")
    rows = []
    for k in levels:
        r = measure(extrude(split_edges(ref, k)), 1.0)
        joints2d = detect_contacts(ref).n_joints
        rows.append({"split": k, "points_per_joint": r["points"] / joints2d, **r})
    relative(rows)
    return rows


def run_pyramids(levels: tuple[int, ...], size: tuple[int, int]) -> list[dict[str, Any]]:
    scene = diagonal_wall(*size)
    rows = [{"facets": k, **measure(scene, 0.5, k)} for k in levels]
    rows.append({"facets": "cone", **measure(scene, 0.5, None)})
    relative(rows)
    return rows


def chart(arch: list, split: list, pyr: list, path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    floor = 1e-12

    def panel(ax, xs, rows, xlabel, title, logx=True):
        for q, m in (("f*", "o-"), ("lambda*", "s-")):
            ax.plot(xs, [max(r[f"diff_{q}"], floor) for r in rows], m, label=f"{q}")
        ax.axhline(RTOL, color="red", ls="--", lw=1, label="1e-3")
        ax.set_yscale("log")
        if logx:
            ax.set_xscale("log")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(f"relative difference to the finest (floor {floor:g})")
        ax.set_title(title, fontsize=10)
        tx = ax.twinx()
        tx.plot(xs, [r["seconds_f"] + r["seconds_lambda"] for r in rows], "k:", marker=".",
                label="seconds (f* + lambda*)")
        tx.set_ylabel("seconds (f* + lambda*)")
        tx.set_yscale("log")
        h1, l1 = ax.get_legend_handles_labels()
        h2, l2 = tx.get_legend_handles_labels()
        ax.legend(h1 + h2, l1 + l2, fontsize=8, loc="lower left")

    panel(axes[0], [r["voussoirs"] for r in arch], arch, "voussoirs N",
          f"semicircular arch t/R = 0.15: finest N = {arch[-1]['voussoirs']}")
    panel(axes[1], [r["points_per_joint"] for r in split], split, "points per 3D joint",
          "reference model extruded, edges split", logx=False)
    xs = [r["facets"] for r in pyr[:-1]]
    panel(axes[2], xs, pyr[:-1], "pyramid facets k",
          f"extruded wall, load at {LOAD_ANGLE:g} deg: pyramid vs SOC cone")
    k = np.array(xs, dtype=float)
    axes[2].plot(k, 1 - np.cos(np.pi / k), color="grey", lw=0.8, label="1 - cos(pi/k)")
    h1, l1 = axes[2].get_legend_handles_labels()
    h2, l2 = fig.axes[-1].get_legend_handles_labels()
    axes[2].legend(h1 + h2, l1 + l2, fontsize=8, loc="lower left")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default=None, help="results folder (default benchmarks/results)")
    p.add_argument("--tiny", action="store_true", help="few refinement levels")
    a = p.parse_args(argv)
    arch = run_arches((6, 10, 20) if a.tiny else VOUSSOIRS)
    split = run_splits((1, 2, 4) if a.tiny else SPLITS)
    pyr = run_pyramids((4, 16, 64) if a.tiny else PYRAMIDS, (2, 2) if a.tiny else (3, 3))
    d = out_dir(a.out)
    chart(arch, split, pyr, d / f"{NAME}.png")
    coarse = {"arch_voussoirs": coarsest(arch, "voussoirs"),
              "points_per_3d_joint": coarsest(split, "points_per_joint"),
              "pyramid_facets": coarsest(pyr, "facets")}
    cols = ["f*", "lambda*", "diff_f*", "diff_lambda*", "seconds_f", "seconds_lambda"]

    def tab(rows, key):
        return markdown_table([key, "points", *cols],
                              [[r[key], r["points"], *[r[c] for c in cols]] for r in rows])

    md = (f"## Model refinement ({NAME}.py)\n\n![refinement]({NAME}.png)\n\n"
          "Relative differences to the finest model of each series; the coarsest adequate "
          f"model is the coarsest from which every finer one is within {RTOL:g}.\n\n"
          f"- arch voussoirs: coarsest adequate N = {coarse['arch_voussoirs']} "
          f"(finest {arch[-1]['voussoirs']})\n"
          f"- points per 3D joint: coarsest adequate {coarse['points_per_3d_joint']:g} "
          "(the statics do not depend on collinear extra points; the time does)\n"
          f"- pyramid facets: coarsest adequate k = {coarse['pyramid_facets']} against "
          "the exact cone\n\n"
          f"### Arch voussoirs\n\n{tab(arch, 'voussoirs')}\n\n"
          f"### Points per 3D joint\n\n{tab(split, 'points_per_joint')}\n\n"
          f"### Pyramid facets vs cone (f* at load factor 0.5)\n\n{tab(pyr, 'facets')}\n")
    data = {"arch": arch, "points_per_joint": split, "pyramid": pyr, "coarsest": coarse,
            "rtol": RTOL}
    write_results(a.out, NAME, data, md)
    return data


if __name__ == "__main__":
    res = main()
    print(res["coarsest"])
