"""Verdicts that are checked where they are weakest, and back ends that answer for
themselves (issue 32 items 1 and 2).

The wedge scene: a block W, trapezoid (-2, 0), (2, 0), (1, 1), (-1, 1), whose slanted
faces rest at 45 degrees against two supports (an inverted keystone: the faces' normal
forces push it down), carrying a block H of ``heavy`` times its weight. Its f* = 1 is an
infimum approached with forces growing as 1 / (f - 1): settled exactly in rational
arithmetic by :func:`exact_state` (an explicit admissible state for every f > 1) and
the argument in :func:`test_wedge_infimum_settled_exactly` (none at f <= 1).
"""

from __future__ import annotations

import json
from fractions import Fraction

import numpy as np
import pytest
from conftest import EXAMPLES

from rigidblocks.analyses import check, max_load_multiplier, min_friction
from rigidblocks.cli.main import main
from rigidblocks.equilibrium import assemble
from rigidblocks.generators.catalogue import scene2d
from rigidblocks.io.scene_file import dumps_scene, read_scene


def wedge(heavy: float, length: float = 1.0, force: float = 1.0) -> object:
    """The wedge scene of the module docstring (unit weight 1: W weighs 3, H 2 heavy),
    its lengths times ``length`` and its forces times ``force``."""
    W = [[-2, 0], [2, 0], [1, 1], [-1, 1]]
    left = [[-4, -1], [-3, -1], [-2, 0], [-1, 1], [-4, 1]]
    right = [[-x, y] for x, y in left][::-1]
    H = [[-1, 1], [1, 1], [1, 2], [-1, 2]]

    def scaled(pts):
        return [[length * x, length * y] for x, y in pts]

    gamma = force / length ** 2
    blocks = [{"id": "L", "vertices": scaled(left), "support": True},
              {"id": "R", "vertices": scaled(right), "support": True},
              {"id": "W", "vertices": scaled(W)},
              {"id": "H", "vertices": scaled(H), "unit_weight": heavy * gamma}]
    return scene2d(blocks, unit_weight=gamma, friction=1.5)


def exact_state(f: Fraction, load: Fraction) -> tuple[Fraction, Fraction]:
    """(N, T) on each slanted face of the wedge, in the face's unnormalised frame
    n = (1, 1), t = (-1, 1) (the right face; the left one mirrors it), carrying the
    total weight ``load`` at friction ``f`` > 1 with T = f N: the force on W from the
    right support is N (-1, -1) + T (-1, 1), so the two faces lift W by 2 (T - N) =
    load and push it sideways by -(N + T) and +(N + T), which cancel; mirrored about
    x = 0, their moments about the axis cancel too."""
    N = load / (2 * (f - 1))
    return N, f * N


@pytest.mark.parametrize("delta", ["1e-2", "1e-6", "1e-12"])
def test_wedge_infimum_settled_exactly(delta):
    """Rational arithmetic: for f = 1 + delta the state of :func:`exact_state` lifts
    the total weight exactly and meets |T| <= f N, with N = load / (2 (f - 1)); for
    f <= 1 no state does, as the lift 2 sum (T - N) over the faces' points needs
    T > N somewhere, i.e. T > f N. So f* = 1 is an infimum and no value."""
    f = 1 + Fraction(delta)
    load = Fraction(3) + 2 * Fraction(10) ** 4
    N, T = exact_state(f, load)
    right = (-N - T, -N + T)  # force on W from the right face
    left = (N + T, -N + T)  # mirrored
    assert right[0] + left[0] == 0 and right[1] + left[1] == load
    assert 0 <= N and abs(T) <= f * N
    assert N == load / (2 * Fraction(delta))  # grows as 1 / (f - 1)


def test_wedge_exact_state_balances_the_assembled_model():
    """The project's own equilibrium matrix carries the state of :func:`exact_state`
    (normal forces split between each joint's two points, the shears solved for, H on
    W by its weight at two points): residual at round-off, shears within f N."""
    heavy, f = 1e4, 1.000001
    s = wedge(heavy)
    sysm = assemble(s)
    c = sysm.contacts
    load = 3.0 + 2.0 * heavy
    N, _ = exact_state(Fraction(f), Fraction(load))
    lay = sysm.layout
    x = np.zeros(lay.size)
    normal = np.zeros(c.n_points)
    ids = c.block_ids
    for k, (a, b) in enumerate(c.pairs):
        pts = np.flatnonzero(c.point_joint == k)
        names = {ids[a], ids[b]}
        # per point: half the face's normal force, |n| = sqrt(2) in the unnormalised frame
        normal[pts] = float(N) * np.sqrt(2.0) / 2 if "H" not in names else heavy
    x[lay.normal] = normal
    F = sysm.dead + sysm.live
    shear = lay.tangential
    rest = sysm.A[:, shear].toarray()
    t, *_ = np.linalg.lstsq(rest, -(sysm.A @ x + F), rcond=None)
    x[shear] = t
    assert np.abs(sysm.A @ x + F).max() <= 1e-9 * load
    joint_n = np.bincount(c.point_joint, normal, minlength=c.n_joints)
    assert np.all(np.abs(t) <= f * joint_n * (1 + 1e-9))


@pytest.mark.parametrize("heavy", [1e2, 1e4, 1e6])
@pytest.mark.parametrize("delta", [1e-2, 1e-4, 1e-6, 1e-7])
def test_check_above_an_infimum_is_never_inadmissible(heavy, delta):
    """Above f* = 1 an admissible state exists (exactly, above), with forces
    (1 + 2 heavy / 3) / (2 sqrt 2 delta) times W's load: admissible, or undecided where
    those are beyond what the solver resolves, never inadmissible. At heavy = 1e4,
    delta = 1e-6 Clarabel's dual bound certified a breach of 4.7e3 (its certificate
    holds at f = 1 and excludes forces up to 2.2e9 only): "inadmissible" before."""
    r = check(wedge(heavy), friction=1.0 + delta, state=False)
    assert r.status in ("admissible", "undecided"), (r.status, r.notes)
    if r.status == "undecided":
        assert r.notes


@pytest.mark.parametrize("length,force,extruded", [(1e3, 1e-6, False), (1e-2, 1e5, False),
                                                   (1.0, 1.0, True)])
def test_check_above_an_infimum_rescaled_and_extruded(length, force, extruded):
    """The same verdict on copies in other units and on the extruded 3D scene (prisms
    of depth 1, the same statics): at f = 1 + 1e-6 never inadmissible, at 1 - 1e-6
    inadmissible."""
    from rigidblocks.scene.extrude import extrude

    s = wedge(1e4, length, force)
    s = extrude(s) if extruded else s
    assert check(s, friction=1.0 + 1e-6, state=False).status in ("admissible", "undecided")
    assert check(s, friction=1.0 - 1e-6, state=False).status == "inadmissible"


@pytest.mark.parametrize("heavy", [0.0, 1e4])
@pytest.mark.parametrize("delta", [1e-4, 1e-6])
def test_check_below_an_infimum_stays_inadmissible(heavy, delta):
    """Below f* = 1 no state exists at any scale (exactly, above): inadmissible."""
    r = check(wedge(heavy), friction=1.0 - delta, state=False)
    assert r.status == "inadmissible", r.notes


def test_cli_check_above_an_infimum_exits_undecided_with_the_reason(tmp_path, capsys):
    """The command line: exit 3 and the certificate's reason."""
    path = tmp_path / "wedge.json"
    path.write_text(dumps_scene(wedge(1e4)))
    assert main(["check", str(path), "--friction", "1.000001"]) == 3
    out = capsys.readouterr().out
    assert "certificate of inadmissibility" in out and "infimum" in out


def test_friction_on_the_wedge_reports_the_infimum():
    """The same scene's f* comes with the bracket from 1 and the infimum note; the
    bracket (6.7e-3 wide: beyond it the forces exceed what the solver resolves) does
    not meet the default accuracy (2e-3), so no number is given."""
    r = min_friction(wedge(1e4), state=False)
    assert r.bracket[0] >= 1.0 - 1e-7 and r.bracket[1] > 1.0
    assert r.status == ("stable" if r.accuracy <= 2e-3 else "undecided")
    assert any("infimum" in n for n in r.notes)



# -- every back end answers for itself --------------------------------------------------
def tiny(c, rows, b, ne, nl, soc=()):
    import scipy.sparse as sp

    from rigidblocks.solvers.base import ConicProblem

    return ConicProblem(c=np.asarray(c, float), A=sp.csc_matrix(np.asarray(rows, float)),
                        b=np.asarray(b, float), n_eq=ne, n_nonneg=nl, soc=tuple(soc))


CVXPY = ("cvxpy-clarabel", "cvxpy-scs", "cvxpy-highs")


@pytest.mark.parametrize("solver", CVXPY)
def test_cvxpy_duals_follow_the_kkt_convention(solver):
    """base.py's convention, P z + c + A'y = 0: min z s.t. z == 1 has y = -1 (Clarabel
    gives -1, and so does cvxpy: the back end negated it, and every answer failed its
    check); min z s.t. -z <= -1 has y = +1; min t s.t. (t, 3, 4) in SOC(3) has
    y = (1, -0.6, -0.8) (t = 5)."""
    from rigidblocks.solvers import solve

    settings = {"eps_abs": 1e-9, "eps_rel": 1e-9} if solver == "cvxpy-scs" else {}
    eq = solve(tiny([1.0], [[1.0]], [1.0], 1, 0), solver, **settings)
    assert eq.y == pytest.approx([-1.0], abs=1e-6)
    ineq = solve(tiny([1.0], [[-1.0]], [-1.0], 0, 1), solver, **settings)
    assert ineq.y == pytest.approx([1.0], abs=1e-6)
    if solver != "cvxpy-highs":  # HiGHS takes no cones
        cone = solve(tiny([1.0], [[-1.0], [0.0], [0.0]], [0.0, 3.0, 4.0], 0, 0, (3,)),
                     solver, **settings)
        assert cone.z == pytest.approx([5.0], abs=1e-5)
        assert cone.y == pytest.approx([1.0, -0.6, -0.8], abs=1e-5)


INFEASIBLE_LP = ([1.0, 0.0], [[1.0, 1.0], [-1.0, 0.0], [0.0, -1.0], [1.0, 1.0]],
                 [1.0, 0.0, 0.0, 0.5], 1, 3)  # z0 + z1 = 1, z >= 0, z0 + z1 <= 0.5
UNBOUNDED_LP = ([-1.0, 0.0], [[0.0, 1.0], [-1.0, 0.0]], [1.0, 0.0], 1, 1)  # max z0 >= 0


@pytest.mark.parametrize("solver", ["clarabel", "highs", "osqp", "scs", "cvxpy-clarabel",
                                    "cvxpy-highs"])
@pytest.mark.parametrize("kind", ["infeasible", "unbounded"])
def test_every_back_end_certifies_its_own_statuses(solver, kind):
    """An infeasible or unbounded status is passed on with its certificate checked (the
    back end's own, or one it finds for the problem of base.certificate_problem), not
    solved again by Clarabel: before, every back end but Clarabel and OSQP's
    infeasible ones came without one."""
    from rigidblocks.solvers import Runner
    from rigidblocks.solvers.policy import VERDICT

    prob = tiny(*(INFEASIBLE_LP if kind == "infeasible" else UNBOUNDED_LP))
    runner = Runner(solver)
    res = runner.run(prob, "tiny", VERDICT)
    assert res.status == kind
    assert not runner.rejected and runner.answered_by == [solver], runner.rejected
    if solver != "clarabel" or kind == "infeasible":  # Clarabel's rays are its own
        assert res.verified and res.residuals["margin"] > 0


def test_a_rejected_answer_is_solved_again_and_said():
    """A back end whose answer fails its check (SCS stopped after 20 iterations by the
    user's setting) is solved again by Clarabel for the user: the answer stands, the
    result names both and what was rejected, and the notes say so."""
    from rigidblocks.generators.catalogue import CASES

    case = CASES["seed_model"]
    r = min_friction(case.scene(), solver="scs", settings={"max_iters": 20}, state=False)
    assert r.friction_factor == pytest.approx(case.value, rel=1e-6)
    assert r.rejected and "scs" in r.rejected[0]
    assert "clarabel" in r.answered_by
    assert any("solved again by clarabel" in n for n in r.notes)


def test_at_the_brink_of_the_dead_load_highs_load_agrees_with_check():
    """The inclined corbel arch at f = 0.7651297, 4.8e-9 above its f* (HiGHS at
    --rtol 1e-9: [0.7651296944, 0.7651296952]; at f = 0.7651298 HiGHS's lambda* is
    6.09e-8): `check` stands, but HiGHS's maximum-load LP was infeasible with a
    certificate of margin 1.4e-9 (its residual 1e-15), and `load` said UNSTABLE. A
    certificate counts only with a margin ten times the tolerance at which a state
    stands (ADMISSIBLE_TOL, 1e-9): this one fails, Clarabel answers, lambda* = 0 (to
    its accuracy) as Clarabel's `load` alone gives, and the result says so."""
    scene = read_scene(EXAMPLES / "corbel_arch_inclined.json")
    assert check(scene, friction=0.7651297, solver="highs").status == "admissible"
    r = max_load_multiplier(scene, friction=0.7651297, solver="highs", state=False)
    assert r.status == "collapse"
    assert r.load_multiplier == pytest.approx(0.0, abs=1e-6)
    assert "clarabel" in r.answered_by and r.rejected
    assert any("solved again by clarabel" in n for n in r.notes)
    # well below f*, the dead load is not carried: a certificate that counts
    low = max_load_multiplier(scene, friction=0.76, solver="highs", state=False)
    assert low.status == "unstable" and tuple(low.answered_by) == ("highs",)


# -- non-associative answers on closed forms ---------------------------------------------
@pytest.mark.parametrize("name", ["inclined_20deg_b1_h2", "inclined_10deg_b0.5_h2",
                                  "box_on_20deg_slope_azimuth_0.4"])
def test_nonassociative_friction_of_a_block_on_an_incline_is_tan_theta(name):
    """A single block sliding down an incline does not dilate under either flow rule:
    the non-associative f* is the static one, tan theta (validation.md; the catalogue
    case's source). Before, the search answered 1e-5 above it (0.36397387 for
    tan 20 deg = 0.36397023) with the note that it "equals the static f*"."""
    from rigidblocks.generators.catalogue import CASES

    case = CASES[name]
    static = min_friction(case.scene(), state=False, rtol=1e-7)  # as the analysis asks
    r = min_friction(case.scene(), flow="non-associative", state=False)
    assert r.status == "stable"
    assert r.friction_factor == pytest.approx(case.value, rel=1e-6)
    assert r.bracket is not None and r.bracket[0] <= r.friction_factor
    equal = [n for n in r.notes if "equals the static f*" in n]
    assert equal and r.friction_factor == static.friction_factor


@pytest.mark.parametrize("f,expect", [(0.4, 0.4), (0.3, 0.3), (0.8, 0.5)])
def test_nonassociative_load_of_a_single_block_is_the_associative_one(f, expect):
    """A block b = 1, h = 2 on a base under a horizontal body force: lambda* = min(f,
    b/h) (validation.md), the same without dilatancy (a slide of one block on a level
    joint does not open it). The answer is that value, not (1 - 1e-6) times it
    (0.3999996 before); the bounds hold for every state: the capacity bound (the block's
    normal force is its weight in every state, so that the cohesion-only law f W gives
    min(f, b/h) again; the answer is no lower bound in general:
    tests/test_nonassociative.py, test_lower_bound_holds_for_every_state) and the
    associative multiplier."""
    from rigidblocks.generators.catalogue import block_on_base

    r = max_load_multiplier(block_on_base(1.0, 2.0, f), flow="non-associative",
                            state=False)
    assert r.status == "collapse"
    assert r.load_multiplier == pytest.approx(expect, rel=1e-9)
    lo, hi = r.load_multiplier_bounds
    assert lo == pytest.approx(expect, rel=1e-8) and lo <= r.load_multiplier
    assert hi == pytest.approx(expect, rel=1e-9)
    assert any("equals the associative" in n for n in r.notes)


def test_the_json_answer_names_the_back_ends_that_answered(tmp_path, capsys):
    """``--json`` carries ``answered_by`` and ``rejected``: a user relying on a
    cross-check sees which back end answered."""
    from rigidblocks.generators.catalogue import CASES

    path = tmp_path / "seed.json"
    path.write_text(dumps_scene(CASES["seed_model"].scene()))
    assert main(["friction", str(path), "--solver", "scs", "--json", "--rtol", "1e-4"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["answered_by"] == ["scs"] and out["rejected"] == []
    assert out["friction_factor"] == pytest.approx(0.5, rel=1e-4)  # as asked (--rtol)
    # the distortion iteration answers by itself, with either flow
    for flow in ("associative", "non-associative"):
        assert main(["check", str(path), "--method", "distortion", "--flow", flow,
                     "--json"]) == 0
        assert json.loads(capsys.readouterr().out)["answered_by"] == ["distortion"]


@pytest.mark.parametrize("argv, key", [(["load"], "load_multiplier"),
                                       (["friction"], "friction_factor")])
def test_a_distortion_answer_that_is_a_convex_bound_names_its_back_end(capsys, argv, key):
    """The reference model with self-weight without dilatancy: the state reached from X0
    by the distortion iteration stands at the associative lambda* = f (P + W) / H = 2.4
    (f = 0.6, generators/seed.py) and at the static f* = 0.25 (seed Fig. 4a with
    self-weight), so the answer is that bound, to Clarabel's digits; the JSON named the
    distortion iteration alone as the back end that answered."""
    path = str(EXAMPLES / "reference_self_weight.json")
    docs = {}
    for method in ("convex", "distortion"):
        assert main([*argv, path, "--method", method, "--flow", "non-associative",
                     "--json"]) == 0
        docs[method] = json.loads(capsys.readouterr().out)
    conv, dist = docs["convex"], docs["distortion"]
    assert dist[key] == pytest.approx({"load": 2.4, "friction": 0.25}[argv[0]], rel=1e-6)
    said = {"load": "equals the associative one", "friction": "equals the static f*"}
    assert any(said[argv[0]] in n for n in dist["notes"]), dist["notes"]
    assert dist[key] == conv[key]  # the bound's own number, so its back end answered too
    assert dist["answered_by"] == ["distortion", "clarabel"], dist["answered_by"]


@pytest.mark.parametrize("argv", [["check", "reference.json"],
                                  ["friction", "segmental_arch.json", "--flow",
                                   "non-associative"]])
def test_an_lp_only_back_end_says_which_solved_the_other_problems(capsys, argv):
    """HiGHS solves linear programs only: `check` hands its state of least complementary
    energy, the non-associative analyses their selection steps, to Clarabel. The JSON
    said so (answered_by) but the printed answer did not, so that `--solver highs`
    read as HiGHS's answer alone; a why line says it now. With Clarabel alone, no
    such line."""
    path = str(EXAMPLES / argv[1])
    line = ("why        highs solves linear programs only: clarabel solved the other "
            "problems of this analysis (its quadratic or conic ones)")
    assert main([argv[0], path, *argv[2:], "--solver", "highs"]) == 0
    assert line in capsys.readouterr().out.splitlines()
    assert main([argv[0], path, *argv[2:], "--solver", "highs", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["answered_by"] == ["highs", "clarabel"]
    assert main([argv[0], path, *argv[2:]]) == 0
    assert "solves linear programs only" not in capsys.readouterr().out
