"""The impressed-distortion solver (seed paper, Eq. 1-4) against closed forms, the seed's
reference model and the convex path."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import make_scene, rect

import rigidblocks as rb
from rigidblocks.problems.formulation import build_energy_qp
from rigidblocks.solvers import solve
from rigidblocks.solvers.distortion import DistortionSolver, load_path


def reference_model(friction=0.5, joints=None):
    """Seed paper, Fig. 4a: support, two central blocks side by side, a top block;
    P = 100 down on the top block, 50 pulling each central block outward (live), no
    self-weight."""
    extra = {"joints": joints} if joints else {}
    return make_scene([
        {"id": "base", "vertices": rect(0, 0, 2, 0.5), "support": True},
        {"id": "L", "vertices": rect(0, 0.5, 1, 0.5)},
        {"id": "R", "vertices": rect(1, 0.5, 1, 0.5)},
        {"id": "T", "vertices": rect(0, 1, 2, 0.5)},
    ], friction=friction, loads=[
        {"block": "T", "force": [0, -100], "point": [1, 1.5]},
        {"block": "L", "force": [-50, 0], "live": True},
        {"block": "R", "force": [50, 0], "live": True},
    ], **extra)


def lintel(friction=0.6):
    """A block bridging two supports with an eccentric live load: hyperstatic links."""
    return make_scene([
        {"id": "s1", "vertices": rect(0, 0, 1, 1), "support": True},
        {"id": "s2", "vertices": rect(2, 0, 1, 1), "support": True},
        {"id": "B", "vertices": rect(0, 1, 3, 0.5)},
    ], unit_weight=1.0, friction=friction,
        loads=[{"block": "B", "force": [0.3, -1.0], "point": [0.5, 1.5], "live": True}])


def test_reference_model_min_friction():
    """Seed paper, numerical example 1: "a friction factor equal to 0.5 ... 26.56 deg"
    without self-weight (each central block: 50 = f (50 + 50) over its two joints)."""
    res = rb.min_friction(reference_model(), method="distortion")
    assert res.status == "stable"
    assert res.friction_factor == pytest.approx(0.5, rel=1e-5)
    assert res.friction_angle_deg == pytest.approx(26.565, abs=1e-3)
    assert res.solver == "distortion" and res.n_solves > 1 and res.iterations > 0
    gov = {frozenset(p) for p in res.governing_joints}
    assert gov == {frozenset(p) for p in (("base", "L"), ("base", "R"), ("L", "T"), ("R", "T"))}


@pytest.mark.parametrize("b,h,f", [(1.0, 2.0, 0.3), (1.0, 2.0, 1.0)])
def test_block_on_base_max_load(block_on_base, b, h, f):
    """Rigid block b x h on a base under a horizontal body force lambda W: it slides at
    lambda = f and overturns about its toe at lambda = b / h (moments about the toe)."""
    res = rb.max_load_multiplier(block_on_base(b=b, h=h, friction=f), method="distortion")
    assert res.status == "collapse"
    assert res.load_multiplier == pytest.approx(min(f, b / h), rel=1e-5)


@pytest.mark.parametrize("case", [
    ("bob", 0.5, 0.3), ("bob", 0.5, 0.6), ("bob", "infinite", 0.45), ("bob", "infinite", 0.55),
    ("ref", 0.45, 1.0), ("ref", 0.55, 1.0), ("lintel", 0.6, 1.0), ("lintel", 0.2, 1.0),
])
def test_verdict_agrees_with_convex_path(block_on_base, case):
    """Same verdict as the convex path (Clarabel) on either side of the limit state."""
    name, f, lam = case
    scene = {"bob": lambda: block_on_base(b=1.0, h=2.0), "ref": reference_model,
             "lintel": lintel}[name]()
    a = rb.check(scene, friction=f, load_factor=lam, method="distortion", state=False)
    b = rb.check(scene, friction=f, load_factor=lam, state=False)
    assert a.status == b.status


@pytest.mark.parametrize("name,f,lam", [("ref", 0.6, 1.0), ("ref", 0.5, 1.0),
                                        ("lintel", 0.6, 1.0), ("lintel", 0.35, 1.0)])
def test_forces_match_energy_qp(name, f, lam):
    """Dykstra's iteration from X0 converges to the C-metric projection of X0 onto the
    admissible equilibrium states: the least-complementary-energy QP."""
    scene = reference_model() if name == "ref" else lintel()
    ds = DistortionSolver(scene)
    fj = np.full(ds.m, f)
    run = ds.run(ds.laws(fj), lam)
    assert run.status == "admissible"
    assert run.residual < 1e-10
    prob = build_energy_qp(ds.system, ds.scaling, fj, lam)
    for solver in ("clarabel", "osqp"):
        qp = solve(prob, solver)
        xq = qp.z[prob.cols["x"]]
        assert np.abs(run.x - xq).max() <= 1e-4 * np.abs(xq).max()


def test_convergence_property():
    """The violation falls by orders of magnitude along the iteration, and the distance
    to the QP's state shrinks as the tolerance is tightened."""
    scene = reference_model()
    ds = DistortionSolver(scene)
    fj = np.full(ds.m, 0.6)
    prob = build_energy_qp(ds.system, ds.scaling, fj, 1.0)
    xq = solve(prob, "clarabel", tol_gap_abs=1e-12, tol_gap_rel=1e-12, tol_feas=1e-12).z
    errs = []
    for tol in (1e-4, 1e-7, 1e-10):
        run = ds.run(ds.laws(fj), 1.0, tol=tol, keep_history=True)
        h = np.array(run.history)
        assert h[0] > 1e3 * h[-1] and h[-1] <= tol
        errs.append(np.abs(run.x - xq[:len(run.x)]).max())
    assert errs[0] > errs[1] > errs[2]
    assert errs[2] < 1e-7


def test_inadmissible_detected_by_stalling():
    """Below f* the violation stalls at a positive value: status inadmissible."""
    res = rb.check(reference_model(), friction=0.3, method="distortion")
    assert res.status == "inadmissible" and not res.admissible and res.violation > 0
    assert any("stalls" in n for n in res.notes)


def test_mechanism_is_a_failure_with_reason():
    """A free block with no joint: A C^-1 A^T is singular (the block is a mechanism)."""
    scene = make_scene([
        {"id": "base", "vertices": rect(0, 0, 2, 0.5), "support": True},
        {"id": "A", "vertices": rect(0, 0.5, 1, 0.5)},
        {"id": "F", "vertices": rect(5, 5, 1, 1)},
    ], unit_weight=1.0, friction=0.5)
    res = rb.check(scene, method="distortion")
    assert res.status == "failure" and not res.admissible
    assert any("mechanism" in n and "F" in n for n in res.notes)


@pytest.mark.parametrize("sliding", ["plastic", "coulomb"])
def test_load_path_reference_model(sliding):
    """Seed paper, Fig. 4b-c: with a weak bond in the vertical joint, the vertical joint
    cracks first; the horizontal joints then plasticise and the central blocks slip when
    the pull equals the friction reaction, 50 lambda = f (50 + 50), lambda = 2 f = 1."""
    scene = reference_model(joints=[{"blocks": ["L", "R"], "tensile_strength": 2.0,
                                     "cohesion": 2.0}])
    path = load_path(scene, steps=40, max_load=1.5, sliding=sliding)
    assert path.status == "collapse"
    kinds = [e.kind for e in path.events]
    assert kinds[0] == "crack" and kinds[-1] == "collapse"
    crack, plastic = path.first("crack"), path.first("plastic")
    assert {frozenset(j) for j in crack.joints} == {frozenset(("L", "R"))}
    assert {frozenset(j) for j in plastic.joints} == {
        frozenset(p) for p in (("base", "L"), ("base", "R"), ("L", "T"), ("R", "T"))}
    assert 0 < crack.load_factor < plastic.load_factor
    assert path.collapse_load == pytest.approx(1.0, rel=1e-4)
    assert plastic.load_factor == pytest.approx(1.0, rel=1e-4)


def test_path_cli(tmp_path, capsys):
    from rigidblocks.cli.main import main
    from rigidblocks.io import write_scene

    p = tmp_path / "ref.json"
    write_scene(reference_model(joints=[{"blocks": ["L", "R"], "tensile_strength": 2.0,
                                         "cohesion": 2.0}]), p)
    assert main(["path", str(p), "--steps", "20", "--max-load", "1.5", "--json"]) == 0
    import json

    out = json.loads(capsys.readouterr().out)
    assert out["status"] == "collapse" and out["events"][0]["kind"] == "crack"
    assert math.isclose(out["collapse_load"], 1.0, rel_tol=1e-4)
