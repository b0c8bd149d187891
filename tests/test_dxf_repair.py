"""DXF repair (rigidblocks.io.dxf_repair) on plain arrays: no CAD library needed.

The drawings are the test_dxf.py quirks written as vertex arrays: round-off of 1e-12
at corners, a polyline closed by coming back to its start, one that retraces its first
vertices, LINE segments in scrambled order and direction, a T-junction, near misses.
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from rigidblocks.errors import InputError
from rigidblocks.io.dxf_repair import (
    DxfReport,
    Outline,
    close_polyline,
    cluster,
    line_loops,
    repair,
)

E = 1e-12
TOL = 1e-9


def outline(points, closed=True, handle="1"):
    return Outline(handle, "0", np.array(points, dtype=float), closed, "LWPOLYLINE")


def test_module_does_not_import_a_cad_library():
    code = ("import sys, rigidblocks.io.dxf_repair; "
            "sys.exit('ezdxf' in sys.modules)")
    assert subprocess.run([sys.executable, "-c", code]).returncode == 0


def test_cluster_labels_points_within_tolerance_together():
    pts = np.array([[0, 0], [E, 0], [1, 1], [1, 1 + 2 * E], [5, 5]])
    lab = cluster(pts, TOL)
    assert lab[0] == lab[1] and lab[2] == lab[3] and len(set(lab.tolist())) == 3


def test_close_polyline_snaps_and_drops_retraced_vertices():
    rep = DxfReport("d", TOL)
    # comes back to its start within the tolerance, not flagged closed, repeated vertex
    p = close_polyline(outline([(0, 0), (1, 0), (1, 0), (1, 1), (0, 1), (E, 0)], False),
                       TOL, "A", rep)
    assert len(p) == 4 and rep.closed_by_snap == ["A"] and rep.duplicates_dropped == 1
    # retraces its first two vertices
    p = close_polyline(outline([(0, 0), (1, 0), (1, 1), (0, 1), (0, 0), (1, 0)], False),
                       TOL, "B", rep)
    assert len(p) == 4 and rep.retraced == ["B"]
    with pytest.raises(InputError, match="block 'C'.*goes on along a different path"):
        close_polyline(outline([(0, 0), (1, 0), (1, 1), (0, 0), (5, 5)], False), TOL, "C",
                       rep)
    with pytest.raises(InputError, match="block 'D'.*open polyline"):
        close_polyline(outline([(0, 0), (1, 0), (1, 1), (0, 1)], False), TOL, "D", rep)
    with pytest.raises(InputError, match="fewer than 3"):
        close_polyline(outline([(0, 0), (1, 0)], True), TOL, "F", rep)


def test_line_loops_join_scrambled_segments_and_name_open_chains():
    rep = DxfReport("d", TOL)
    ends = np.array([[2, 0, 2.5, 0], [2.5, 1, 2.5, 0], [2, 1, 2.5, 1], [2, 0, 2, 1 + E]])
    (loop,) = line_loops(ends, ["a", "b", "c", "d"], ["0"] * 4, TOL, rep)
    assert loop.kind == "LINE" and len(loop.points) == 4 and loop.handle == "a,b,c,d"
    assert {tuple(np.round(p, 9)) for p in loop.points} == {(2, 0), (2.5, 0), (2.5, 1),
                                                          (2, 1)}
    with pytest.raises(InputError, match=r"LINEs #a,b"):
        line_loops(ends[:3], ["a", "b", "c"], ["0"] * 3, TOL, rep)
    assert line_loops(np.zeros((0, 4)), [], [], TOL, rep) == []


def test_repair_snaps_corners_and_t_junctions_and_names_near_misses():
    rep = DxfReport("d", TOL)
    base = outline([(-1, -1), (3, -1), (3, 0), (-1, 0)])
    a = outline([(-1 + E, E), (0, 0), (0, 2), (-1, 2)])  # a corner 1e-12 off the base's
    # B's corner (1.5, 0 + E/2) lies on the base's top edge: a T-junction
    b = outline([(1.5, E / 2), (2.5, 0), (2.5, 1), (1.5, 1)])
    polys = repair([base, a, b], ["g", "A", "B"], TOL, 100.0, rep, "d.dxf")
    assert rep.vertices_snapped == 2  # both moved onto their mean
    assert np.array_equal(polys[1][0], polys[0][3])
    assert rep.edges_snapped >= 1
    p, q = polys[0][2], polys[0][3]  # the base's top edge, after the corner snap
    d, v = q - p, polys[2][0] - p
    assert abs(d[0] * v[1] - d[1] * v[0]) / np.linalg.norm(d) < 1e-15  # B's corner on it
    assert 0 < rep.max_move <= TOL
    gap = outline([(-1, 2e-8), (0, 2e-8), (0, 2), (-1, 2)])  # corner 20 tolerances off
    with pytest.raises(InputError, match="blocks 'g' and 'A'|blocks 'A' and 'g'"):
        repair([base, gap], ["g", "A"], TOL, 100.0, DxfReport("d", TOL), "d.dxf")
