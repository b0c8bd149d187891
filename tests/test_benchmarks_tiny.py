"""The foundation benchmark runs, on tiny sizes, and reports consistent counts.

Expected counts are the running-bond closed forms of rigidblocks.examples.walls:
blocks = 1 + N C + floor(C / 2), joints = N (3C - 1) - ceil(C / 2), two contact points
per joint, 3 equilibrium rows per free block.
"""

from __future__ import annotations

import importlib.util
import io

import pytest
from conftest import ROOT


def load_bench():
    spec = importlib.util.spec_from_file_location(
        "bench_foundation", ROOT / "benchmarks" / "bench_foundation.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_bench_foundation_tiny():
    bench = load_bench()
    out = io.StringIO()
    rows = bench.main([4, 30], out=out)
    assert [(r["courses"], r["per_course"]) for r in rows] == [(2, 2), (5, 6)]
    for r in rows:
        C, N = r["courses"], r["per_course"]
        assert r["blocks"] == 1 + N * C + C // 2
        assert r["joints"] == N * (3 * C - 1) - (C + 1) // 2
        assert r["points"] == 2 * r["joints"]
        assert r["rows"] == 3 * (r["blocks"] - 1)
        assert set(r["seconds"]) == set(bench.STAGES)
        assert all(v >= 0 for v in r["seconds"].values())
    table = out.getvalue().splitlines()
    assert table[0].split()[:3] == ["blocks", "joints", "points"]
    assert len(table) == 2 + len(rows)
    assert table[2].split()[:3] == ["6", "9", "18"]  # C = N = 2: 1 + 4 + 1 blocks, 9 joints


def test_bench_cli_sizes(capsys):
    bench = load_bench()
    assert bench._cli(["--sizes", "3"]) == 0
    assert "blocks" in capsys.readouterr().out
    with pytest.raises(SystemExit):
        bench._cli(["--sizes", "0"])


@pytest.mark.slow
def test_bench_foundation_full_sizes():
    """The 50,000-block wall goes through every stage in seconds, not minutes."""
    rows = load_bench().main([50_000])
    assert sum(rows[0]["seconds"].values()) < 60


def load_peer_bench():
    spec = importlib.util.spec_from_file_location(
        "bench_peer", ROOT / "benchmarks" / "bench_peer.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_bench_peer_tiny_our_side(tmp_path):
    """Our side of the peer comparison, the peer disabled.

    A semicircular arch with radial joints under self-weight stands when its thickness
    ratio exceeds the minimum t/R = 0.1075 (Milankovitch 1907; Heyman, "The safety of
    masonry arches", Int. J. Mech. Sci. 11, 1969; Heyman, The Stone Skeleton, 1995), so
    t/R = 0.15 and 0.2 stand in the 2D model, its extrusion with the Coulomb cone and
    with an 8-facet pyramid; at t/R = 0.07, well below it, no thrust line fits. A
    running-bond wall under self-weight alone carries every block straight down its
    full bed joints.
    """
    bench = load_peer_bench()
    data = bench.main(["--tiny", "--peer-python", "none", "--out", str(tmp_path)])
    assert data["peer_available"] is False and data["targets"] is None
    names = {r["name"]: r for r in data["rows"]}
    assert set(names) == {"arch 10 v, t/R 0.15", "arch 10 v, t/R 0.2", "wall 10 blocks"}
    for r in data["rows"]:
        assert r["peer"] == {}
        assert {m: o["verdict"] for m, o in r["ours"].items()} == {
            "2d": "admissible", "3d_cone": "admissible", "3d_pyr8": "admissible"}
    hard = data["hard_cases"]
    assert {h["method"] for h in hard} == {"rigidblocks 2d", "rigidblocks 3d_cone",
                                           "rigidblocks 3d_pyr8"}
    assert all(h["grade"] == "right" for h in hard)
    for ext in ("json", "md", "png"):
        assert (tmp_path / f"bench_peer.{ext}").stat().st_size > 0
    thin = bench.arch_scene(10, 0.07)
    assert bench.run_ours(thin)["verdict"] == "inadmissible"
    assert bench.run_ours(bench.extrude(thin))["verdict"] == "inadmissible"
