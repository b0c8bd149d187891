"""Catalogue of closed-form cases for the convex analyses (check, min_friction, max_load).

Every expected value below is derived by hand in the test's docstring (statics of rigid
blocks) or taken from /work/shared/docs/validation.md; tolerances are 1e-6 relative for
the interior-point and simplex back ends and looser for SCS (first-order method).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import make_scene, rect

from rigidblocks.equilibrium import assemble
from rigidblocks.errors import InputError
from rigidblocks.problems import check, max_load_multiplier, min_friction

RTOL = 1e-6
#: the back ends every case is run with; SCS is a first-order method, checked loosely
SOLVERS = ["clarabel", "highs", "cvxpy-highs"]
SCS_RTOL = 1e-3


def close(a: float, b: float, rtol: float = RTOL) -> bool:
    return abs(a - b) <= rtol * max(abs(b), 1e-12)


def pair_set(pairs) -> set[frozenset[str]]:
    return {frozenset(p) for p in pairs}


# -- scenes ------------------------------------------------------------------------------
def block_on_base(b: float, h: float, f, **extra):
    """A b x h block (unit weight 1) on a wide support, live horizontal body force."""
    return make_scene([
        {"id": "base", "vertices": rect(-2, -1, 4 + b, 1), "support": True},
        {"id": "B", "vertices": rect(0, 0, b, h)},
    ], unit_weight=1.0, friction=f, live_body_force=[1, 0], **extra)


def rotate(pts, theta, about=(0.0, 0.0)):
    c, s = math.cos(theta), math.sin(theta)
    ox, oy = about
    return [[ox + c * (x - ox) - s * (y - oy), oy + s * (x - ox) + c * (y - oy)]
            for x, y in pts]


def inclined(b: float, h: float, theta: float):
    """Block b x h resting on a support whose top face rises at angle theta.

    The support is the wedge (0,0), (L cos t, L sin t) on top, closed below; the block
    is the rectangle [1, 1+b] x [0, h] in the incline's frame, rotated by theta.
    """
    L = 3.0 + b
    top = [[L * math.cos(theta), L * math.sin(theta)]]
    support = [[0.0, -1.0], [L * math.cos(theta), -1.0], *top, [0.0, 0.0]]
    block = rotate(rect(1.0, 0.0, b, h), theta)
    return make_scene([
        {"id": "ramp", "vertices": support, "support": True},
        {"id": "B", "vertices": block},
    ], unit_weight=1.0)


def stack(widths_heights, H, point_load_block: str | None = None, **extra):
    """Blocks stacked flush on a support, horizontal dead point load H at the top."""
    blocks = [{"id": "S", "vertices": rect(-5, -1, 10, 1), "support": True}]
    y = 0.0
    for k, (b, h) in enumerate(widths_heights):
        blocks.append({"id": f"B{k}", "vertices": rect(0, y, b, h)})
        y += h
    top = point_load_block or blocks[-1]["id"]
    b_top = widths_heights[-1][0]
    return make_scene(blocks, unit_weight=1.0,
                      loads=[{"block": top, "force": [H, 0], "point": [b_top / 2, y]}],
                      **extra)


def seed_model(unit_weight: float = 0.0):
    """The seed's four-block reference model.

    Support S (top at y = 0); central blocks C1 = [0,1]x[0,1] and C2 = [1,2]x[0,1] side
    by side on S; top block T = [0,2]x[1,1.5] over both. Vertical P = 100 down on T at
    its centroid; 50 pulling C1 towards -x and 50 pulling C2 towards +x, at centroids.
    """
    return make_scene([
        {"id": "S", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "C1", "vertices": rect(0, 0, 1, 1)},
        {"id": "C2", "vertices": rect(1, 0, 1, 1)},
        {"id": "T", "vertices": rect(0, 1, 2, 0.5)},
    ], unit_weight=unit_weight, loads=[
        {"block": "T", "force": [0, -100]},
        {"block": "C1", "force": [-50, 0]},
        {"block": "C2", "force": [50, 0]},
    ])


def leaning_pair():
    """Two leaning blocks meeting at a vertical crown joint x = 2 (y in [1.5, 2]).

    Left block L = (0,0), (1,0), (2,1.5), (2,2) on the ground; R its mirror about x = 2.
    """
    L = [[0, 0], [1, 0], [2, 1.5], [2, 2]]
    R = [[4 - x, y] for x, y in L]
    return make_scene([
        {"id": "G", "vertices": rect(-1, -1, 6, 1), "support": True},
        {"id": "L", "vertices": L},
        {"id": "R", "vertices": R},
    ], unit_weight=1.0)


def harmonic(n: int, L: float = 1.0, h: float = 0.25, extra: dict[int, float] | None = None):
    """n blocks of length L, block k (from the top, k = 1..n) shifted L/(2k) over the one
    below (the bottom one over the support's edge at x = 0); ``extra`` adds shifts."""
    extra = extra or {}
    right = [0.0] * (n + 2)  # right edge of block k; k = n+1 is the support
    for k in range(n, 0, -1):
        right[k] = right[k + 1] + L / (2 * k) + extra.get(k, 0.0)
    blocks = [{"id": "S", "vertices": rect(-5, -1, 5, 1), "support": True}]
    for k in range(n, 0, -1):
        blocks.append({"id": f"k{k}", "vertices": rect(right[k] - L, (n - k) * h, L, h)})
    return make_scene(blocks, unit_weight=1.0, friction="infinite")


# -- block on a support under a horizontal body force -------------------------------------
@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("b,h,f", [(1.0, 2.0, 0.3), (1.0, 2.0, 0.8), (1.5, 1.0, 1.2),
                                   (1.5, 1.0, 0.25)])
def test_block_on_base_load_multiplier(b, h, f, solver):
    """lambda* = min(f, b/h) (validation.md, closed forms).

    Derivation: N = W, T = lambda W. Sliding needs |T| <= f N, so lambda <= f; the
    resultant must stay in the base, its eccentricity lambda W h/2 / W <= b/2, so
    lambda <= b/h. Kinematics (associative flow rule): a slide lifts at v/u = f; a
    rotation about the downstream toe (b, 0) moves the centroid perpendicular to the arm
    from the toe.
    """
    s = block_on_base(b, h, f)
    r = max_load_multiplier(s, solver=solver)
    lam = min(f, b / h)
    assert r.status == "collapse"
    assert close(r.load_multiplier, lam)
    u, v, om = r.mechanism.velocities[s.index["B"]]
    if f < b / h:
        assert r.mechanism.modes == ("slide",)
        assert u > 0 and close(v / u, f, 1e-5) and abs(om) < 1e-6 * abs(u)
        assert [tuple(p) for p in r.governing_joints] == [("base", "B")]
    else:
        assert r.mechanism.modes == ("hinge",)
        # velocity of the centroid = omega k x (c - toe), toe = (b, 0), c = (b/2, h/2)
        arm = np.array([-b / 2, h / 2])
        expect = om * np.array([-arm[1], arm[0]])
        assert om < 0 and np.allclose([u, v], expect, rtol=1e-5, atol=1e-7 * abs(om))
    for lf, ok in ((lam * (1 - 1e-4), True), (lam * (1 + 1e-4), False)):
        c = check(s, load_factor=lf, solver=solver, state=False)
        assert c.admissible is ok and c.status == ("admissible" if ok else "inadmissible")


def test_block_on_base_scs():
    """Same closed form lambda* = min(f, b/h), with SCS at a first-order tolerance."""
    for f in (0.3, 0.8):
        r = max_load_multiplier(block_on_base(1.0, 2.0, f), solver="scs", state=False)
        assert r.status == "collapse" and close(r.load_multiplier, min(f, 0.5), SCS_RTOL)


# -- inclined support -----------------------------------------------------------------
@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("deg,b,h", [(20.0, 1.0, 2.0), (30.0, 1.0, 1.0), (10.0, 0.5, 2.0)])
def test_inclined_support_min_friction(deg, b, h, solver):
    """f* = tan(theta) when b/h >= tan(theta) (validation.md).

    Derivation: in the incline's frame the weight W has components W cos t (normal) and
    W sin t (downhill), so T/N = tan t whatever the state; the resultant passes through
    the centroid's projection, within the base iff b/h >= tan t.
    """
    s = inclined(b, h, math.radians(deg))
    r = min_friction(s, solver=solver)
    fstar = math.tan(math.radians(deg))
    assert r.status == "stable"
    assert close(r.friction_factor, fstar)
    assert close(r.friction_angle_deg, deg)
    assert [frozenset(p) for p in r.governing_joints] == [frozenset(("ramp", "B"))]
    assert r.n_solves <= 15


@pytest.mark.parametrize("solver", SOLVERS)
def test_inclined_support_tips(solver):
    """b/h = 0.5 < tan 30 deg = 0.577: the weight's line of action leaves the base, no
    friction helps (validation.md): min_friction is "unstable", check inadmissible."""
    s = inclined(0.5, 1.0, math.radians(30.0))
    r = min_friction(s, solver=solver)
    assert r.status == "unstable" and r.friction_factor is None
    assert r.friction_angle_deg is None
    assert not check(s, friction="infinite", solver=solver).admissible


# -- stacks ---------------------------------------------------------------------------
@pytest.mark.parametrize("solver", SOLVERS)
def test_two_block_stack_min_friction(solver):
    """Two 2 x 0.5 blocks (W = 1 each), H = 0.3 at the top: f* = H / (weight above).

    Top joint: T = H, N = 1 -> 0.3; base joint: T = H, N = 2 -> 0.15. The top joint
    governs: f* = 0.3. No tipping: H h_above <= W_above b/2 at both joints
    (0.15 <= 1, 0.3 <= 2).
    """
    s = stack([(2.0, 0.5), (2.0, 0.5)], 0.3)
    r = min_friction(s, solver=solver)
    assert r.status == "stable" and close(r.friction_factor, 0.3)
    assert pair_set(r.governing_joints) == {frozenset(("B0", "B1"))}
    assert r.n_solves <= 15


@pytest.mark.parametrize("solver", SOLVERS)
def test_three_block_stack_min_friction(solver):
    """Three blocks 2 x 0.5 (W = 1), 1 x 0.5 (W = 0.5), 1 x 1 (W = 1); H = 0.2 at the
    top. Ratios H / (weight above): top joint 0.2/1 = 0.2, middle 0.2/1.5, base 0.2/2.5;
    the largest governs: f* = 0.2 at joint B1-B2. Tipping margins hold (H h <= W b/2)."""
    s = stack([(2.0, 0.5), (1.0, 0.5), (1.0, 1.0)], 0.2)
    r = min_friction(s, solver=solver)
    assert r.status == "stable" and close(r.friction_factor, 0.2)
    assert pair_set(r.governing_joints) == {frozenset(("B1", "B2"))}


@pytest.mark.parametrize("solver", SOLVERS)
def test_three_block_stack_load_on_middle(solver):
    """H = 0.3 on the middle block (top face centre) of three 2 x 0.5 blocks (W = 1).
    Joint above the middle block carries no shear (the top block has no horizontal
    load); middle-bottom: 0.3/2; base: 0.3/3. f* = 0.15 at B0-B1."""
    blocks = [{"id": "S", "vertices": rect(-5, -1, 10, 1), "support": True}]
    for k in range(3):
        blocks.append({"id": f"B{k}", "vertices": rect(0, 0.5 * k, 2, 0.5)})
    s = make_scene(blocks, unit_weight=1.0,
                   loads=[{"block": "B1", "force": [0.3, 0], "point": [1.0, 1.0]}])
    r = min_friction(s, solver=solver)
    assert r.status == "stable" and close(r.friction_factor, 0.15)
    assert pair_set(r.governing_joints) == {frozenset(("B0", "B1"))}


@pytest.mark.parametrize("solver", SOLVERS)
def test_harmonic_stack(solver):
    """Harmonic stack of 4 blocks (validation.md): block k from the top shifted L/(2k),
    so the centroid of the k blocks above each joint lies exactly over its edge. At the
    limit it is admissible with infinite friction; 1e-3 L more on any block is not."""
    assert check(harmonic(4), solver=solver).admissible
    for k in (1, 2, 4):
        assert not check(harmonic(4, extra={k: 1e-3}), solver=solver).admissible


# -- two blocks side by side -------------------------------------------------------------
def side_by_side(H: float, sign: int, f):
    """A = [0,1]^2 and B = [1,2]x[0,1] (W = 1) on a support; +-H at mid-height."""
    return make_scene([
        {"id": "S", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "A", "vertices": rect(0, 0, 1, 1)},
        {"id": "B", "vertices": rect(1, 0, 1, 1)},
    ], unit_weight=1.0, friction=f, loads=[
        {"block": "A", "force": [sign * H, 0], "point": [0.5, 0.5]},
        {"block": "B", "force": [-sign * H, 0], "point": [1.5, 0.5]},
    ])


@pytest.mark.parametrize("solver", SOLVERS)
def test_side_by_side(solver):
    """validation.md: pushed together, the forces cancel through the vertical joint, so
    f = 0 suffices; pulled apart, each block's bed joint carries H: f* = H / W = 0.4
    (no tipping: H h/2 = 0.2 <= W b/2 = 0.5)."""
    push = side_by_side(0.4, +1, 0.0)
    assert check(push, solver=solver).admissible
    pull = side_by_side(0.4, -1, 0.0)
    assert not check(pull, solver=solver).admissible
    r = min_friction(pull, solver=solver)
    assert r.status == "stable" and close(r.friction_factor, 0.4)
    assert pair_set(r.governing_joints) == {frozenset(("S", "A")), frozenset(("S", "B"))}
    assert min_friction(push, solver=solver).friction_factor <= 1e-7


# -- the seed's reference model -----------------------------------------------------------
CENTRAL_HORIZONTAL = {frozenset(("S", "C1")), frozenset(("S", "C2")),
                      frozenset(("C1", "T")), frozenset(("C2", "T"))}


@pytest.mark.parametrize("solver", SOLVERS)
def test_seed_reference_model(solver):
    """Seed paper (/work/shared/seed, validation.md): f* = 0.5, phi = 26.565 deg.

    Derivation: T's horizontal equilibrium makes the shears t from C1 and C2 equal; C1
    carries 50 = t + b (top and bed shears) with N_top = N_bed = N1; N1 + N2 = 100, so
    f >= 50 / (2 N1) and 50 / (2 N2): best N1 = N2 = 50, f* = 0.5. The four horizontal
    joints of the central blocks govern; the vertical joint C1-C2 opens.
    """
    r = min_friction(seed_model(), solver=solver)
    assert r.status == "stable"
    assert close(r.friction_factor, 0.5)
    assert close(r.friction_angle_deg, math.degrees(math.atan(0.5)))
    assert abs(r.friction_angle_deg - 26.565) < 5e-4
    assert pair_set(r.governing_joints) == CENTRAL_HORIZONTAL
    assert r.n_solves <= 15


@pytest.mark.parametrize("solver", SOLVERS)
def test_seed_reference_model_with_weight(solver):
    """With unit weight gamma (depth 1): W_T = W_C = gamma (both areas 1). N on C1's top
    joint is (100 + W_T)/2, on its bed joint (100 + W_T)/2 + W_C, so
    f* = 50 / (100 + W_T + W_C) = 50 / (100 + 2 gamma); f* = 0.25 for gamma = 50."""
    r = min_friction(seed_model(50.0), solver=solver)
    assert close(r.friction_factor, 0.25)
    assert pair_set(r.governing_joints) == CENTRAL_HORIZONTAL
    r = min_friction(seed_model(25.0), solver=solver)
    assert close(r.friction_factor, 50.0 / 150.0)


# -- symmetric three-hinged arrangement ----------------------------------------------------
@pytest.mark.parametrize("solver", SOLVERS)
def test_leaning_pair_thrust(solver):
    """Two leaning blocks meeting at a vertical crown joint (see ``leaning_pair``).

    Left block: area (shoelace) 5/4, centroid (17/15, 23/30). Symmetry and the crown's
    horizontal equilibrium force a horizontal crown force H (any crown shear S would
    need H = (2W/15 + S)/y on one side and (2W/15 - S)/y on the other). Moments of the
    left block about the inner base corner (1, 0) with the crown force at the top (2, 2)
    (largest lever, smallest H): 2 H = W (17/15 - 1), H = W/15. Supports: N = W,
    T = H, so f* = H/V = 1/15, at the two base joints.
    """
    s = leaning_pair()
    assert not check(s, friction=0.0, solver=solver).admissible
    r = min_friction(s, solver=solver)
    assert r.status == "stable" and close(r.friction_factor, 1.0 / 15.0)
    base_joints = {frozenset(("G", "L")), frozenset(("G", "R"))}
    if solver == "clarabel":  # interior point: strictly complementary duals, both bases
        assert pair_set(r.governing_joints) == base_joints
    else:  # simplex: a vertex dual may certify with one of the two symmetric joints
        assert pair_set(r.governing_joints) and pair_set(r.governing_joints) <= base_joints
    st = r.state
    crown = [k for k, (a, b) in enumerate(r.contacts.pairs)
             if {r.contacts.block_ids[a], r.contacts.block_ids[b]} == {"L", "R"}][0]
    W = 1.25
    assert close(st.joint_normal[crown], W / 15.0, 1e-5)
    assert abs(st.joint_shear[crown]) < 1e-6 * W
    # the crown force acts at the top of the crown joint, y = 2
    assert abs(st.thrust_points[crown][1] - 2.0) < 1e-5


# -- status mapping -------------------------------------------------------------------
def floating():
    """A block with no contact at all (1 unit above the support)."""
    return make_scene([
        {"id": "S", "vertices": rect(0, -1, 3, 1), "support": True},
        {"id": "B", "vertices": rect(1, 1, 1, 1)},
    ], unit_weight=1.0, live_body_force=[1, 0])


def on_a_point():
    """A square standing on one corner (diamond): it touches the support at a point."""
    return make_scene([
        {"id": "S", "vertices": rect(-1, -1, 2, 1), "support": True},
        {"id": "B", "vertices": [[0, 0], [1, 1], [0, 2], [-1, 1]]},
    ], unit_weight=1.0, live_body_force=[1, 0])


@pytest.mark.parametrize("solver", SOLVERS)
@pytest.mark.parametrize("build", [floating, on_a_point])
def test_mechanism_statuses(build, solver):
    """A free block without a joint cannot be in equilibrium under its weight: check is
    inadmissible, min_friction "unstable", max_load "unstable", never a number."""
    s = build()
    c = check(s, friction="infinite", solver=solver)
    assert c.status == "inadmissible" and c.admissible is False
    f = min_friction(s, solver=solver)
    assert f.status == "unstable" and f.friction_factor is None
    m = max_load_multiplier(s, solver=solver)
    assert m.status == "unstable" and m.load_multiplier is None


def test_max_load_without_live_load():
    """scene-format.md: "load" on a scene with no live load is a usage error."""
    s = make_scene([
        {"id": "S", "vertices": rect(0, -1, 3, 1), "support": True},
        {"id": "B", "vertices": rect(1, 0, 1, 1)},
    ], unit_weight=1.0)
    with pytest.raises(InputError):
        max_load_multiplier(s)


@pytest.mark.parametrize("solver", SOLVERS)
def test_unbounded_when_live_load_presses_down(solver):
    """A live force straight down through the centroid with infinite friction only
    presses the block onto its support: every lambda >= 0 is admissible."""
    s = make_scene([
        {"id": "S", "vertices": rect(0, -1, 3, 1), "support": True},
        {"id": "B", "vertices": rect(1, 0, 1, 1)},
    ], unit_weight=1.0, friction="infinite", live_body_force=[0, -1])
    r = max_load_multiplier(s, solver=solver)
    assert r.status == "unbounded" and r.load_multiplier is None


# -- the force state ---------------------------------------------------------------
@pytest.mark.parametrize("scene,f", [(seed_model(50.0), 0.3), (leaning_pair(), 0.1),
                                     (side_by_side(0.4, -1, 0.5), None)])
def test_energy_state_admissible_and_in_equilibrium(scene, f):
    """The least-complementary-energy state satisfies A x + F = 0 (equilibrium.assemble:
    compression positive) and the joint laws N >= 0, |T| <= f N (design.md)."""
    r = check(scene, friction=f)
    assert r.admissible
    st = r.state
    sysm = assemble(scene)
    x = np.zeros(sysm.layout.size)
    x[sysm.layout.normal] = st.normal
    x[sysm.layout.tangential] = st.joint_shear
    F = sysm.dead + sysm.live
    scale = np.abs(F).max()
    assert np.abs(sysm.A @ x + F).max() <= 1e-6 * scale
    fr = scene.effective_friction if f is None else f
    assert st.normal.min() >= -1e-7 * scale
    assert np.all(np.abs(st.joint_shear) <= fr * st.joint_normal + 1e-7 * scale)


@pytest.mark.parametrize("build,expect", [
    (lambda: seed_model(), 0.5), (lambda: seed_model(50.0), 0.25),
    (leaning_pair, 1.0 / 15.0), (lambda: inclined(1.0, 2.0, math.radians(20.0)),
                                 math.tan(math.radians(20.0))),
    (lambda: side_by_side(0.4, -1, 0.0), 0.4)])
def test_min_friction_scs(build, expect):
    """The catalogue's f* (closed forms above) with SCS, a first-order conic solver:
    same verdict, f* to SCS's precision."""
    r = min_friction(build(), solver="scs", state=False)
    assert r.status == "stable" and close(r.friction_factor, expect, SCS_RTOL)
    assert r.n_solves <= 15


@pytest.mark.parametrize("solver", SOLVERS)
def test_max_load_unstable_when_live_load_props_up(solver):
    """scene-format.md: "unstable" when the dead load alone has no admissible state.
    The 0.5 x 1 block on the 30 deg ramp tips under its weight (b/h < tan 30 deg); a
    live body force towards +x (uphill) can prop it up, so admissible multipliers exist,
    but lambda = 0 is not one of them: no collapse multiplier is reported."""
    s = inclined(0.5, 1.0, math.radians(30.0)).with_changes(live_body_force=(1.0, 0.0),
                                                              friction="infinite")
    assert not check(s, load_factor=0.0, solver=solver).admissible
    r = max_load_multiplier(s, solver=solver)
    assert r.status == "unstable" and r.load_multiplier is None


def test_large_wall_verdicts_hold_across_the_admissible_interval():
    """The admissible load multipliers form an interval [0, lambda*] (the admissible
    set is convex and the dead load alone stands), so every check below lambda* must
    say admissible, however large the scene. On a 990-block wall the relaxation's
    round-off (~1e-9 of a block weight) once exceeded a threshold fixed in block-weight
    units and called lambda*/2 inadmissible."""
    from rigidblocks.generators.walls import running_bond_wall

    wall = running_bond_wall(30, 33)
    lam = max_load_multiplier(wall, state=False).load_multiplier
    for k in (0.0, 0.5, 0.999):
        assert check(wall, load_factor=k * lam, state=False).admissible, k
    assert not check(wall, load_factor=1.01 * lam, state=False).admissible


@pytest.mark.parametrize("voussoirs,thickness", [(4, 0.3), (7, 0.2), (13, 0.2)])
def test_min_friction_of_thick_arches_in_few_solves(voussoirs, thickness):
    """R(f) of these arches is slightly concave below f*, so plain Newton overshoots and
    a bracket shrinks by halves (about 30 solves); the curvature-corrected step needs
    fewer than 10. The answer is certified by admissibility on either side of it."""
    from rigidblocks.generators import build

    arch = build("arch", voussoirs=voussoirs, thickness=thickness)
    r = min_friction(arch, load_factor=0.0, state=False)
    assert r.status == "stable" and r.n_solves <= 10
    f = r.friction_factor
    assert check(arch, friction=f * (1 + 1e-6), load_factor=0.0, state=False).admissible
    assert not check(arch, friction=f * (1 - 1e-6), load_factor=0.0, state=False).admissible


@pytest.mark.slow
def test_large_wall_collapse_multiplier_agrees_with_the_simplex():
    """lambda* of a 32-course wall of 992 blocks by the default path agrees with HiGHS's
    simplex vertex to 1e-5 (at Clarabel's default tolerances it was 7e-5 off). ~30 s."""
    from rigidblocks.generators import build

    wall = build("wall", courses=32, blocks_per_course=31)
    ours = max_load_multiplier(wall, state=False).load_multiplier
    simplex = max_load_multiplier(wall, solver="highs", state=False).load_multiplier
    assert ours == pytest.approx(simplex, rel=1e-5)


def test_loose_solver_tolerances_are_noted(block_on_base):
    """Tolerances given by the user go to the verdict problems too; looser than the
    verdict threshold (1e-9), the result says its verdicts may be wrong near a limit."""
    scene = block_on_base()
    r = check(scene, settings={"tol_feas": 1e-6}, state=False)
    assert any("tol_feas" in n and "may be wrong" in n for n in r.notes)
    r = check(scene, settings={"tol_feas": 1e-10}, state=False)
    assert not any("may be wrong" in n for n in r.notes)
