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
