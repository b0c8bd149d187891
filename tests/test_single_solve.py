"""check's single solve: where the structure is admissible, the least-energy QP gives
the verdict and the force state at once (:meth:`ConvexMethod.least_energy`, the joint
laws unrelaxed); elsewhere the relaxation decides. Against the two-solve path (the
relaxation's verdict, then the QP with the laws relaxed by R + 1e-9,
:meth:`ConvexMethod.state`) on scenes 2D and 3D, admissible and not: the same verdict,
one solve where admissible, and the same state to 1e-6 of the largest force up to the
two-solve state's own error against the minimiser (the QP solved to 1e-13), which the
single solve's state does not exceed by more than 1e-6 of it. Both QPs run at the
solver's default tolerances (1e-8): measured, the two-solve state is off the minimiser
by up to 5.8e-5 of the largest force (the 8 x 6 wall at load factor 0.2), the
single-solve state by the same; on the 8-facet pyramid 2.8e-6 and 8.1e-7.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rigidblocks import check
from rigidblocks.equilibrium import force_state
from rigidblocks.generators import build
from rigidblocks.generators.catalogue import block_on_base, box_on_slab, seed_model
from rigidblocks.generators.walls import running_bond_wall
from rigidblocks.methods import ADMISSIBLE, open_method
from rigidblocks.problems.formulation import energy_problem
from rigidblocks.scene.extrude import extrude
from rigidblocks.scene.model import friction_value
from rigidblocks.solvers.registry import solve

#: (name, scene, friction, load factor, pyramid, expected verdict); the expected
#: verdicts by hand: lambda* = min(f, b/h) for the block on its base (validation.md),
#: the seed model's f* = 0.5 at load factor 1 (seed paper, example 1), the arch's
#: minimum thickness t/R = 0.1075 (Milankovitch 1907; Heyman 1969), walls on full bed
#: joints stand under their own weight
SCENES = [
    ("block 2D, lambda 0.3 < f = 0.5", lambda: block_on_base(1.0, 2.0, 0.5), None, 0.3,
     None, "admissible"),
    ("block 2D, lambda 0.6 > f = 0.5", lambda: block_on_base(1.0, 2.0, 0.5), None, 0.6,
     None, "inadmissible"),
    ("seed model, f 0.6", seed_model, 0.6, 1.0, None, "admissible"),
    ("seed model, f 0.4", seed_model, 0.4, 1.0, None, "inadmissible"),
    ("wall 2D 8 x 6, self-weight", lambda: running_bond_wall(8, 6), None, 0.0, None,
     "admissible"),
    ("wall 2D 8 x 6, load factor 0.2", lambda: running_bond_wall(8, 6), None, 0.2, None,
     "admissible"),
    ("arch t/R 0.15", lambda: build("arch", voussoirs=12, thickness=0.15, arc_points=1),
     None, 0.0, None, "admissible"),
    ("arch t/R 0.08", lambda: build("arch", voussoirs=12, thickness=0.08, arc_points=1),
     None, 0.0, None, "inadmissible"),
    ("wall 3D 6 x 5, self-weight", lambda: extrude(running_bond_wall(6, 5)), None, 0.0,
     None, "admissible"),
    ("wall 3D 6 x 5, load factor 0.2", lambda: extrude(running_bond_wall(6, 5)), None,
     0.2, None, "admissible"),
    ("wall 3D 6 x 5, 8-facet pyramid", lambda: extrude(running_bond_wall(6, 5)), None,
     0.2, 8, "admissible"),
    ("box on a 20 deg slope, f 0.5", lambda: box_on_slab(a=2, b=2, h=0.5,
                                                          tilt=math.radians(20.0)),
     0.5, 0.0, None, "admissible"),
    ("box on a 20 deg slope, f 0.3", lambda: box_on_slab(a=2, b=2, h=0.5,
                                                         tilt=math.radians(20.0)),
     0.3, 0.0, None, "inadmissible"),
]


@pytest.mark.parametrize("name,make,friction,lf,pyramid,expected", SCENES,
                         ids=[s[0] for s in SCENES])
def test_one_solve_gives_the_two_solve_verdict_and_state(name, make, friction, lf,
                                                         pyramid, expected):
    scene = make()
    one = check(scene, friction=friction, load_factor=lf, pyramid=pyramid)
    assert one.status == expected
    m = open_method(scene, pyramid=pyramid)
    f = friction_value(scene.effective_friction if friction is None else friction)
    v = m.admissible(f, lf)  # the relaxation alone
    assert v.status == one.status
    if v.status != ADMISSIBLE:
        assert one.state is None
        assert one.violation == pytest.approx(v.violation, rel=1e-6)
        return
    assert one.n_solves == 1
    two = m.state(f, lf, v)
    assert m.n_solves == 2
    assert one.state.method == two.method == "least complementary energy"
    # the minimiser itself: the same QP solved to 1e-13
    prob = energy_problem(m.system, m.vscaling, m.f_joint(f), lf, 0.0, m.pyramid)[0]
    ref = solve(prob, "clarabel", tol_gap_abs=1e-13, tol_gap_rel=1e-13, tol_feas=1e-13,
                max_iter=400)
    assert ref.status == "optimal"
    exact = force_state(m.system, m.vscaling.forces(ref.z[prob.cols["x"]]), "reference")
    x1, x2, xr = (np.concatenate([s.normal, s.shear.ravel()])
                  for s in (one.state, two, exact))
    scale = np.abs(xr).max()
    err1, err2 = np.abs(x1 - xr).max(), np.abs(x2 - xr).max()
    assert err1 <= err2 + 1e-6 * scale  # no less accurate than the two-solve path
    assert np.abs(x1 - x2).max() <= 1e-6 * scale + err2
