"""The equilibrium system A x + F_dead + lambda F_live = 0, checked against statics by hand.

Statics used: each free rigid block is in equilibrium when the resultant force and the
resultant moment about its centroid vanish (Newton-Euler for a body at rest; e.g.
Meriam & Kraige, *Engineering Mechanics: Statics*, ch. 3). The contact force at point
p of the joint between i and j is N n + T s on j and its opposite on i, so its column
in A is [n; (p - c_j) x n] on j's rows and the negative (with c_i) on i's rows: the
equilibrium matrix of Livesley, "Limit analysis of structures formed from rigid
blocks", Int. J. Numer. Meth. Eng. 12 (1978), in the sign convention of
docs/design.md (compression positive, moments about centroids, 2D cross product
r x f = r_x f_y - r_y f_x).
"""

from __future__ import annotations

import numpy as np
import pytest
from conftest import make_scene, rect

from rigidblocks.equilibrium import assemble
from rigidblocks.errors import InputError


def single_block(b=1.0, h=2.0, gamma=3.0, depth=0.5, **top):
    """A b x h block on [0, b] x [0, h], on a wide base."""
    return make_scene([
        {"id": "base", "vertices": rect(-1, -1, b + 2, 1), "support": True},
        {"id": "B", "vertices": rect(0, 0, b, h)},
    ], unit_weight=gamma, depth=depth, **top)


def test_single_block_weight_and_columns():
    """W = gamma b h t = 3 x 1 x 2 x 0.5 = 3; its rows are [0, -W, 0] (the weight acts at
    the centroid (0.5, 1), so no moment about it). The joint base-B has normal +y (from
    the base into B) and points (0, 0) and (1, 0): normal columns [0, 1, x - 0.5], i.e.
    [0, 1, -0.5] and [0, 1, +0.5]; the joint's shear (s = (-1, 0)) at y = 0 has column
    [-1, 0, -(0 - 1) x (-1)] = [-1, 0, -1]."""
    sys = assemble(single_block())
    assert sys.A.shape == (3, 3)
    np.testing.assert_allclose(sys.dead, [0.0, -3.0, 0.0])
    np.testing.assert_allclose(sys.live, 0.0)
    np.testing.assert_allclose(sys.centroids[1], [0.5, 1.0])
    np.testing.assert_allclose(sys.weights[1], 3.0)
    assert sys.block_rows.tolist() == [-1, 0]
    A = sys.A.toarray()
    pts = sys.contacts.points
    for k in range(2):
        x = pts[k, 0]
        np.testing.assert_allclose(A[:, sys.layout.normal][:, k], [0, 1, x - 0.5], atol=1e-12)
    assert sorted(pts[:, 0].tolist()) == [0.0, 1.0]
    np.testing.assert_allclose(A[:, sys.layout.tangential][:, 0], [-1, 0, -1], atol=1e-12)


def test_single_block_reactions():
    """Least squares of A x = -F (A square and regular): N = W/2 at each corner, T = 0.
    Under a live horizontal body force lambda W (lambda = 0.2) at the centroid height
    h/2 = 1: the joint pushes B back with -lambda W along x, so T = +lambda W with
    s = (-1, 0); moment about
    the joint centre: (b/2)(N_right - N_left) = lambda W h/2, so
    N_right - N_left = lambda W h / b = 1.2 and N_left + N_right = W = 3."""
    sys = assemble(single_block(live_body_force=[1, 0]))
    A = sys.A.toarray()
    lam = 0.2
    x = np.linalg.solve(A, -(sys.dead + lam * sys.live))
    N = x[sys.layout.normal]
    order = np.argsort(sys.contacts.points[:, 0])
    n_left, n_right = N[order]
    assert n_left == pytest.approx(1.5 - 0.6)
    assert n_right == pytest.approx(1.5 + 0.6)
    assert x[sys.layout.tangential][0] == pytest.approx(0.2 * 3.0)


def stack(n=3, b=1.0, h=0.5, gamma=2.0, **top):
    blocks = [{"id": "base", "vertices": rect(-1, -1, b + 2, 1), "support": True}]
    blocks += [{"id": f"s{k}", "vertices": rect(0, k * h, b, h)} for k in range(n)]
    return make_scene(blocks, unit_weight=gamma, **top)


@pytest.mark.parametrize("n", [2, 3])
def test_stack_columns_on_both_blocks(n):
    """A joint between two free blocks: the column is +[n; (p - c_j) x n] on j (upper)
    and -[n; (p - c_i) x n] on i (lower)."""
    scene = stack(n)
    sys = assemble(scene)
    c = sys.contacts
    A = sys.A.toarray()
    k = next(k for k in range(c.n_joints) if c.pairs[k].tolist() == [1, 2])
    i, j = c.pairs[k]
    nrm = c.normals[k]
    np.testing.assert_allclose(nrm, [0, 1])
    for col in sys.point_columns(k):
        p = c.points[col]
        for blk, sign in ((j, 1.0), (i, -1.0)):
            r = p - sys.centroids[blk]
            expect = sign * np.array([nrm[0], nrm[1], r[0] * nrm[1] - r[1] * nrm[0]])
            np.testing.assert_allclose(A[sys.rows_of(blk), col], expect, atol=1e-12)
        others = np.ones(A.shape[0], bool)
        others[sys.rows_of(i)] = others[sys.rows_of(j)] = False
        assert np.all(A[others, col] == 0)


@pytest.mark.parametrize("n", [2, 3])
def test_stack_reactions_by_hand(n):
    """Stack of n blocks b x h (weight W = gamma b h t = 2 x 1 x 0.5 x 1 = 1 each), live
    body force lambda W horizontally. Below the m-th block from the top, the joint
    carries the m blocks above it: N_left + N_right = m W, a horizontal reaction
    -m lambda W on the blocks above (T = +m lambda W with s = (-1, 0)), and the
    overturning moment about the joint's centre
    sum_k lambda W (k - 1/2) h = lambda W h m^2 / 2, balanced by (b/2)(N_right - N_left)."""
    lam, W, h, b = 0.25, 1.0, 0.5, 1.0
    scene = stack(n, live_body_force=[1, 0])
    sys = assemble(scene)
    A = sys.A.toarray()
    assert A.shape == (3 * n, 3 * n)
    x = np.linalg.lstsq(A, -(sys.dead + lam * sys.live), rcond=None)[0]
    np.testing.assert_allclose(A @ x, -(sys.dead + lam * sys.live), atol=1e-12)
    c = sys.contacts
    N = x[sys.layout.normal]
    T = x[sys.layout.tangential]
    for k in range(c.n_joints):
        lower = int(c.pairs[k, 0])  # base = 0, s0 = 1, ...
        m = n - lower  # blocks above the joint
        cols = sys.point_columns(k)
        xs = c.points[cols, 0]
        n_left, n_right = N[cols][np.argsort(xs)]
        assert n_left + n_right == pytest.approx(m * W)
        assert n_right - n_left == pytest.approx(lam * W * h * m**2 / b)
        assert T[k] == pytest.approx(m * lam * W)


def test_bottom_bed_joint_carries_all_weight_centred():
    """Self-weight only: every bed joint's normal force is centred (N_left = N_right)
    and the bottom one carries the whole stack 3 W = 3."""
    sys = assemble(stack(3))
    x = np.linalg.solve(sys.A.toarray(), -sys.dead)
    c = sys.contacts
    bottom = next(k for k in range(c.n_joints) if c.pairs[k, 0] == 0)
    N = x[sys.point_columns(bottom)]
    np.testing.assert_allclose(N, [1.5, 1.5])
    np.testing.assert_allclose(x[sys.layout.tangential], 0.0, atol=1e-12)


def test_joint_and_point_shear_layouts_agree():
    """shear="point" has one shear column per contact point; each equals its joint's
    single column of shear="joint" (the moment of a force along the joint's line does
    not depend on where on the line it acts), so both describe the same equilibrium:
    a solution of one, with the joint shear split over the points, solves the other."""
    scene = stack(3, live_body_force=[1, 0])
    sj = assemble(scene, shear="joint")
    sp_ = assemble(scene, shear="point")
    assert sp_.layout.n_shear == sj.contacts.n_points
    assert sj.layout.n_shear == sj.contacts.n_joints
    Aj, Ap = sj.A.toarray(), sp_.A.toarray()
    np.testing.assert_allclose(Aj[:, sj.layout.normal], Ap[:, sp_.layout.normal])
    pj = sj.contacts.point_joint
    np.testing.assert_allclose(Ap[:, sp_.layout.tangential],
                               Aj[:, sj.layout.tangential][:, pj], atol=1e-12)
    F = sj.dead + 0.3 * sj.live
    xj = np.linalg.solve(Aj, -F)
    xp = np.concatenate([xj[sj.layout.normal],
                         np.repeat(xj[sj.layout.tangential], 2) * np.tile([0.25, 0.75], 3)])
    np.testing.assert_allclose(Ap @ xp, -F, atol=1e-12)
    np.testing.assert_allclose(sp_.dead, sj.dead)
    np.testing.assert_allclose(sp_.live, sj.live)


def test_unknown_shear_layout_rejected():
    with pytest.raises(InputError, match="shear"):
        assemble(stack(2), shear="edge")


def test_point_loads_with_point_and_moment():
    """Block of test_single_block (centroid (0.5, 1), W = 3). Dead load F = (2, -4) at
    p = (1, 2) with a couple 0.7: rows [2, -4 - 3, (0.5)(-4) - (1)(2) + 0.7] =
    [2, -7, -3.3]. Live load (1, 0) at the centroid (no point given): [1, 0, 0]. A second
    live couple -0.4 alone: [0, 0, -0.4]."""
    scene = single_block(loads=[
        {"block": "B", "force": [2, -4], "point": [1, 2], "moment": 0.7},
        {"block": "B", "force": [1, 0], "live": True},
        {"block": "B", "force": [0, 0], "moment": -0.4, "live": True},
    ])
    sys = assemble(scene)
    np.testing.assert_allclose(sys.dead, [2.0, -7.0, -3.3])
    np.testing.assert_allclose(sys.live, [1.0, 0.0, -0.4])


def test_live_body_force():
    """live_body_force g = (0.3, -0.1): live rows W g = (0.9, -0.3), no moment about the
    centroid (the body force acts there); support blocks get no rows."""
    sys = assemble(single_block(live_body_force=[0.3, -0.1]))
    np.testing.assert_allclose(sys.live, [0.9, -0.3, 0.0])
    np.testing.assert_allclose(sys.dead, [0.0, -3.0, 0.0])


def test_block_unit_weight_override_and_nonconvex_centroid():
    """An L-shaped block (2 x 1 foot + 1 x 1 upright, area 3, centroid ((2 x 1 + 0.5 x 1)
    / 3, (2 x 0.5 + 1 x 1.5) / 3) = (5/6, 5/6)) with its own unit weight 2: W = 6."""
    L = [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]
    scene = make_scene([
        {"id": "base", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "L", "vertices": L, "unit_weight": 2.0},
    ], unit_weight=5.0)
    sys = assemble(scene)
    np.testing.assert_allclose(sys.weights[1], 6.0)
    np.testing.assert_allclose(sys.centroids[1], [5 / 6, 5 / 6])
    np.testing.assert_allclose(sys.dead, [0, -6, 0])
    A = sys.A.toarray()
    for col in range(2):
        p = sys.contacts.points[col]
        np.testing.assert_allclose(A[:, col], [0, 1, p[0] - 5 / 6], atol=1e-12)
