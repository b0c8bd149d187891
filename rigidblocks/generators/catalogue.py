"""A catalogue of standard problems with known answers, for testing every method.

Each :class:`Case` is a small scene built in code, the analysis to run on it
(``check``, ``min_friction`` or ``max_load_multiplier``, with its options), the
expected answer (status, value, governing joints, mechanism modes), verdicts of
``check`` that must hold around the limit, a tolerance, and the source of the
reference value: a closed form derived by hand in ``source`` (statics of rigid blocks)
or a published value with its citation. The closed forms are listed in the project's
validation notes (``validation.md``: block on a support, inclined support, harmonic
stack, blocks side by side, the seed's reference model, leaning blocks, their 3D
counterparts); the seed is the paper in ``shared/seed`` (its numerical example 1).

:data:`CASES` maps a case name to its case; :func:`cases` filters them. The test suite
runs every case on every method and back end that applies to it
(``tests/test_catalogue.py``), so a new back end is checked against all of them.

>>> from rigidblocks.generators.catalogue import CASES
>>> case = CASES["seed_model"]
>>> case.analysis, case.value, case.status
('min_friction', 0.5, 'stable')
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from ..scene.model import INFINITE, Scene

RTOL = 1e-6
ANALYSES = ("check", "min_friction", "max_load_multiplier")


# -- scene builders --------------------------------------------------------------------
def rect(x0: float, y0: float, w: float, h: float) -> list[list[float]]:
    """The corners of the rectangle [x0, x0 + w] x [y0, y0 + h], counter-clockwise."""
    return [[x0, y0], [x0 + w, y0], [x0 + w, y0 + h], [x0, y0 + h]]


def scene2d(blocks: list[dict], **top: Any) -> Scene:
    """A validated 2D scene from block dicts and top-level keys of the scene format."""
    from ..io.scene_file import scene_from_dict

    doc = {"format": "rigidblocks-scene", "version": 1, "dimension": 2, "blocks": blocks}
    doc.update(top)
    return scene_from_dict(doc)


def scene3d(blocks: list[dict], **top: Any) -> Scene:
    """A validated 3D scene from block dicts and top-level keys of the scene format."""
    from ..io.scene_file import scene_from_dict

    doc = {"format": "rigidblocks-scene", "version": 1, "dimension": 3, "blocks": blocks}
    doc.update(top)
    return scene_from_dict(doc)


def rotate(pts: list[list[float]], theta: float,
           about: tuple[float, float] = (0.0, 0.0)) -> list[list[float]]:
    """2D points rotated by ``theta`` (radians, counter-clockwise) about ``about``."""
    c, s = math.cos(theta), math.sin(theta)
    ox, oy = about
    return [[ox + c * (x - ox) - s * (y - oy), oy + s * (x - ox) + c * (y - oy)]
            for x, y in pts]


def block_on_base(b: float, h: float, f: Any, **extra: Any) -> Scene:
    """A b x h block (unit weight 1) on a wide support, live horizontal body force."""
    return scene2d([
        {"id": "base", "vertices": rect(-2, -1, 4 + b, 1), "support": True},
        {"id": "B", "vertices": rect(0, 0, b, h)},
    ], unit_weight=1.0, friction=f, live_body_force=[1, 0], **extra)


def inclined(b: float, h: float, theta: float, **extra: Any) -> Scene:
    """Block b x h resting on a support whose top face rises at angle theta.

    The support is the wedge (0,0), (L cos t, L sin t) on top, closed below; the block
    is the rectangle [1, 1+b] x [0, h] in the incline's frame, rotated by theta.
    """
    L = 3.0 + b
    top = [[L * math.cos(theta), L * math.sin(theta)]]
    support = [[0.0, -1.0], [L * math.cos(theta), -1.0], *top, [0.0, 0.0]]
    return scene2d([
        {"id": "ramp", "vertices": support, "support": True},
        {"id": "B", "vertices": rotate(rect(1.0, 0.0, b, h), theta)},
    ], unit_weight=1.0, **extra)


def stack(widths_heights: list[tuple[float, float]], H: float,
          point_load_block: str | None = None, **extra: Any) -> Scene:
    """Blocks stacked flush on a support, horizontal dead point load H at the top."""
    blocks: list[dict] = [{"id": "S", "vertices": rect(-5, -1, 10, 1), "support": True}]
    y = 0.0
    for k, (b, h) in enumerate(widths_heights):
        blocks.append({"id": f"B{k}", "vertices": rect(0, y, b, h)})
        y += h
    top = point_load_block or blocks[-1]["id"]
    b_top = widths_heights[-1][0]
    return scene2d(blocks, unit_weight=1.0,
                   loads=[{"block": top, "force": [H, 0], "point": [b_top / 2, y]}], **extra)


def stack_loaded_in_the_middle(H: float = 0.3) -> Scene:
    """Three 2 x 0.5 blocks (W = 1) on a support, H on the middle block's top face."""
    blocks: list[dict] = [{"id": "S", "vertices": rect(-5, -1, 10, 1), "support": True}]
    for k in range(3):
        blocks.append({"id": f"B{k}", "vertices": rect(0, 0.5 * k, 2, 0.5)})
    return scene2d(blocks, unit_weight=1.0,
                   loads=[{"block": "B1", "force": [H, 0], "point": [1.0, 1.0]}])


def seed_model(unit_weight: float = 0.0) -> Scene:
    """The seed's four-block reference model.

    Support S (top at y = 0); central blocks C1 = [0,1]x[0,1] and C2 = [1,2]x[0,1] side
    by side on S; top block T = [0,2]x[1,1.5] over both. Vertical P = 100 down on T at
    its centroid; 50 pulling C1 towards -x and 50 pulling C2 towards +x, at centroids.
    """
    return scene2d([
        {"id": "S", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "C1", "vertices": rect(0, 0, 1, 1)},
        {"id": "C2", "vertices": rect(1, 0, 1, 1)},
        {"id": "T", "vertices": rect(0, 1, 2, 0.5)},
    ], unit_weight=unit_weight, loads=[
        {"block": "T", "force": [0, -100]},
        {"block": "C1", "force": [-50, 0]},
        {"block": "C2", "force": [50, 0]},
    ])


def leaning_pair() -> Scene:
    """Two leaning blocks meeting at a vertical crown joint x = 2 (y in [1.5, 2]).

    Left block L = (0,0), (1,0), (2,1.5), (2,2) on the ground; R its mirror about x = 2.
    """
    L = [[0, 0], [1, 0], [2, 1.5], [2, 2]]
    R = [[4 - x, y] for x, y in L]
    return scene2d([
        {"id": "G", "vertices": rect(-1, -1, 6, 1), "support": True},
        {"id": "L", "vertices": L},
        {"id": "R", "vertices": R},
    ], unit_weight=1.0)


def harmonic(n: int, L: float = 1.0, h: float = 0.25,
             extra: Mapping[int, float] | None = None) -> Scene:
    """n blocks of length L, block k (from the top, k = 1..n) shifted L/(2k) over the one
    below (the bottom one over the support's edge at x = 0); ``extra`` adds shifts."""
    extra = extra or {}
    right = [0.0] * (n + 2)  # right edge of block k; k = n+1 is the support
    for k in range(n, 0, -1):
        right[k] = right[k + 1] + L / (2 * k) + extra.get(k, 0.0)
    blocks: list[dict] = [{"id": "S", "vertices": rect(-5, -1, 5, 1), "support": True}]
    for k in range(n, 0, -1):
        blocks.append({"id": f"k{k}", "vertices": rect(right[k] - L, (n - k) * h, L, h)})
    return scene2d(blocks, unit_weight=1.0, friction="infinite")


def side_by_side(H: float, sign: int, f: Any) -> Scene:
    """A = [0,1]^2 and B = [1,2]x[0,1] (W = 1) on a support; +-H at mid-height (sign +1
    pushes them together, -1 pulls them apart)."""
    return scene2d([
        {"id": "S", "vertices": rect(-1, -1, 4, 1), "support": True},
        {"id": "A", "vertices": rect(0, 0, 1, 1)},
        {"id": "B", "vertices": rect(1, 0, 1, 1)},
    ], unit_weight=1.0, friction=f, loads=[
        {"block": "A", "force": [sign * H, 0], "point": [0.5, 0.5]},
        {"block": "B", "force": [-sign * H, 0], "point": [1.5, 0.5]},
    ])


def floating() -> Scene:
    """A block with no contact at all (1 unit above the support)."""
    return scene2d([
        {"id": "S", "vertices": rect(0, -1, 3, 1), "support": True},
        {"id": "B", "vertices": rect(1, 1, 1, 1)},
    ], unit_weight=1.0, live_body_force=[1, 0])


def on_a_point() -> Scene:
    """A square standing on one corner (diamond): it touches the support at a point."""
    return scene2d([
        {"id": "S", "vertices": rect(-1, -1, 2, 1), "support": True},
        {"id": "B", "vertices": [[0, 0], [1, 1], [0, 2], [-1, 1]]},
    ], unit_weight=1.0, live_body_force=[1, 0])


def pressed_down() -> Scene:
    """A unit block on a support, infinite friction, live body force straight down."""
    return scene2d([
        {"id": "S", "vertices": rect(0, -1, 3, 1), "support": True},
        {"id": "B", "vertices": rect(1, 0, 1, 1)},
    ], unit_weight=1.0, friction="infinite", live_body_force=[0, -1])


def box_on_slab(a: float = 1.0, b: float = 2.0, h: float = 2.0, tilt: float = 0.0,
                azimuth: float = 0.0, **top: Any) -> Scene:
    """A box a x b x h (centred on the z axis) on a 6 x 6 x 1 slab, the whole rotated by
    ``tilt`` so that the slab's top slopes down towards ``azimuth`` (radians from +x)."""
    import numpy as np

    from .solids import box

    bv, bf = box(-a / 2, -b / 2, 0, a, b, h)
    sv, sf = box(-3, -3, -1, 6, 6, 1)
    axis = np.array([-math.sin(azimuth), math.cos(azimuth), 0.0])  # horizontal axis
    # Rodrigues: the rotation by `tilt` about `axis` takes +z towards the downhill side
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    R = np.eye(3) + math.sin(tilt) * K + (1 - math.cos(tilt)) * K @ K

    def rot(pts: list) -> list:
        return (np.asarray(pts, dtype=float) @ R.T).tolist()

    return scene3d([{"id": "slab", "vertices": rot(sv), "faces": sf, "support": True},
                    {"id": "box", "vertices": rot(bv), "faces": bf}], unit_weight=1.0, **top)


# -- the cases -------------------------------------------------------------------------
@dataclass(frozen=True)
class Verdict:
    """A ``check`` that must answer ``admissible`` (True/False) on the case's scene with
    these options (``friction``, ``load_factor``), or on ``scene`` when given."""

    admissible: bool
    options: tuple[tuple[str, Any], ...] = ()
    scene: Callable[[], Scene] | None = None


@dataclass(frozen=True)
class Case:
    """One standard problem with its known answer.

    Attributes:
        name: unique name.
        scene: builds the scene.
        analysis: ``check``, ``min_friction`` or ``max_load_multiplier``.
        status: the expected status (``admissible``/``inadmissible``, ``stable``/
            ``unstable``, ``collapse``/``unbounded``/``unstable``).
        value: the expected f* or lambda* (None when the status has no number).
        options: keywords of the analysis (``friction``, ``load_factor``,
            ``pyramid``).
        rtol: relative tolerance on ``value`` (exact closed forms: 1e-6).
        atol: absolute tolerance on ``value`` (for a reference value of 0).
        governing: the governing joints, as block-id pairs (None: not part of the
            answer).
        governing_any_vertex: a simplex (vertex) solution may certify with a non-empty
            subset of ``governing`` (symmetric cases), an interior-point one with all.
        modes: the collapse mechanism's modes (``("slide",)``, ``("hinge",)``).
        angle_deg: the expected friction angle atan(f*) in degrees, where the source
            quotes it.
        verdicts: checks around the limit that must hold.
        max_solves: the most solves the convex path may take.
        source: the derivation of the reference value, or its citation.
    """

    name: str
    scene: Callable[[], Scene]
    analysis: str
    status: str
    value: float | None = None
    options: tuple[tuple[str, Any], ...] = ()
    rtol: float = RTOL
    atol: float = 0.0
    governing: frozenset[frozenset[str]] | None = None
    governing_any_vertex: bool = False
    modes: tuple[str, ...] | None = None
    angle_deg: float | None = None
    verdicts: tuple[Verdict, ...] = ()
    max_solves: int | None = None
    source: str = ""
    tags: tuple[str, ...] = field(default=())

    @property
    def dimension(self) -> int:
        return self.scene().dimension

    @property
    def kwargs(self) -> dict[str, Any]:
        return dict(self.options)

    @property
    def is_lp(self) -> bool:
        """Is the problem a linear program: 2D, or 3D with friction pyramids or without
        friction limits (infinite friction: no cones)?"""
        if self.dimension == 2 or "pyramid" in self.kwargs:
            return True
        if self.analysis == "min_friction":  # f is the unknown: the cones are there
            return False
        scene = self.scene()
        friction = self.kwargs.get("friction", scene.effective_friction)
        return friction == INFINITE and not any(j.friction is not None for j in scene.joints)


def _pairs(*pairs: tuple[str, str]) -> frozenset[frozenset[str]]:
    return frozenset(frozenset(p) for p in pairs)


def _around(value: float, key: str, margin: float = 1e-4) -> tuple[Verdict, Verdict]:
    """Admissible just below the limit ``value`` of option ``key``, not just above."""
    below, above = value * (1 - margin), value * (1 + margin)
    if key == "friction":  # more friction helps
        return (Verdict(False, ((key, below),)), Verdict(True, ((key, above),)))
    return (Verdict(True, ((key, below),)), Verdict(False, ((key, above),)))


_BOB = ("validation.md, closed forms (block on a support): lambda* = min(f, b/h). "
        "N = W and T = lambda W; sliding needs |T| <= f N, so lambda <= f; the resultant "
        "must stay in the base, eccentricity lambda W (h/2) / W <= b/2, so lambda <= b/h. "
        "Associative flow: a slide lifts at v/u = f; a rotation about the downstream toe "
        "(b, 0).")
_INCLINED = ("validation.md (inclined support): in the incline's frame the weight has "
             "components W cos t (normal) and W sin t (downhill), so T/N = tan t in every "
             "state: f* = tan t; the resultant passes through the centroid's projection, "
             "within the base iff b/h >= tan t.")
_SEED = ("Seed paper (shared/seed/000_12fc8c16f038a4e5.txt), numerical example 1: "
         "\"a friction factor equal to 0.5 ... 26.56 deg\"; validation.md. By hand: T's "
         "horizontal equilibrium makes the shears t from C1 and C2 equal; C1 carries "
         "50 = t + b (top and bed shears) with N_top = N_bed = N1; N1 + N2 = 100, so "
         "f >= 50 / (2 N1) and 50 / (2 N2): best N1 = N2 = 50, f* = 0.5. The four "
         "horizontal joints of the central blocks govern; the vertical joint opens.")
_SEED_WEIGHT = ("The seed's model with unit weight gamma (depth 1): W_T = W_C = gamma "
                "(both areas 1). N on C1's top joint is (100 + W_T)/2, on its bed joint "
                "(100 + W_T)/2 + W_C, so f* = 50 / (100 + W_T + W_C) = 50 / (100 + "
                "2 gamma).")
_LEANING = ("validation.md (symmetric three-hinged arrangement), by hand: left block "
            "area 5/4, centroid (17/15, 23/30). Symmetry and the crown's horizontal "
            "equilibrium force a horizontal crown force H at the crown's top (2, 2) "
            "(largest lever, smallest H); moments about the inner base corner (1, 0): "
            "2 H = W (17/15 - 1), H = W/15. Base joints: N = W, T = H, f* = 1/15.")
_HARMONIC = ("validation.md (harmonic stack): block k from the top shifted L/(2k), so "
             "the centroid of the k blocks above each joint lies exactly over its edge: "
             "admissible with infinite friction at the limit; 1e-3 L more on any block "
             "is not.")
_SIDE = ("validation.md (two blocks side by side): pushed together, the forces cancel "
         "through the vertical joint, so f = 0 suffices; pulled apart, each block's bed "
         "joint carries H: f* = H / W = 0.4 (no tipping: H h/2 = 0.2 <= W b/2 = 0.5).")
_CONE = ("validation.md (3D inclined plane): a block on a plane sloping at theta needs "
         "f* = tan(theta) with the Coulomb cone, whatever the downhill azimuth (the 2 x 2 "
         "x 0.5 box is squat enough not to tip: 2/0.5 >= tan 20 deg).")
_TIP3D = ("By hand: box a x b x h, horizontal body force lambda W at azimuth alpha, "
          "infinite friction. The resultant of W and lambda W at the centroid (height "
          "h/2) meets the base at lambda h/2 (cos alpha, sin alpha) from its centre; it "
          "must stay inside the a x b base: lambda* = min(a / (h cos alpha), b / (h sin "
          "alpha)); a=1, b=2, h=2, alpha=30 deg: lambda* = 1/(2 cos 30 deg), tipping "
          "about the edge x = a/2.")


def _catalogue() -> list[Case]:
    out: list[Case] = []
    # block on a support under a horizontal body force: lambda* = min(f, b/h)
    for b, h, f in ((1.0, 2.0, 0.3), (1.0, 2.0, 0.8), (1.5, 1.0, 1.2), (1.5, 1.0, 0.25),
                    (1.0, 2.0, 1.0), (1.0, 2.0, 0.0)):
        lam = min(f, b / h)
        slides = f < b / h
        out.append(Case(
            f"block_on_base_b{b:g}_h{h:g}_f{f:g}",
            lambda b=b, h=h, f=f: block_on_base(b, h, f),
            "max_load_multiplier", "collapse", lam, atol=1e-10 if lam == 0 else 0.0,
            governing=_pairs(("base", "B")) if slides and f > 0 else None,
            modes=(("slide",) if slides else ("hinge",)) if f > 0 else None,
            verdicts=_around(lam, "load_factor") if lam > 0 else (),
            source=_BOB, tags=("block_on_base",)))
    # inclined support: f* = tan(theta) unless it tips
    for deg, b, h in ((20.0, 1.0, 2.0), (30.0, 1.0, 1.0), (10.0, 0.5, 2.0)):
        fs = math.tan(math.radians(deg))
        out.append(Case(
            f"inclined_{deg:g}deg_b{b:g}_h{h:g}",
            lambda deg=deg, b=b, h=h: inclined(b, h, math.radians(deg)),
            "min_friction", "stable", fs, governing=_pairs(("ramp", "B")),
            angle_deg=deg, max_solves=15, verdicts=_around(fs, "friction"),
            source=_INCLINED))
    out.append(Case(
        "inclined_30deg_tips", lambda: inclined(0.5, 1.0, math.radians(30.0)),
        "min_friction", "unstable",
        verdicts=(Verdict(False, (("friction", "infinite"),)),),
        source=_INCLINED + " Here b/h = 0.5 < tan 30 deg = 0.577: it tips, no friction "
        "helps."))
    # stacks under a horizontal point load
    out.append(Case(
        "two_block_stack", lambda: stack([(2.0, 0.5), (2.0, 0.5)], 0.3),
        "min_friction", "stable", 0.3, governing=_pairs(("B0", "B1")), max_solves=15,
        verdicts=_around(0.3, "friction"),
        source="By hand: two 2 x 0.5 blocks (W = 1 each), H = 0.3 at the top: f* = H / "
        "(weight above). Top joint: T = H, N = 1 -> 0.3; base joint: T = H, N = 2 -> "
        "0.15; the top joint governs. No tipping: H h_above <= W_above b/2 at both "
        "joints (0.15 <= 1, 0.3 <= 2)."))
    out.append(Case(
        "three_block_stack", lambda: stack([(2.0, 0.5), (1.0, 0.5), (1.0, 1.0)], 0.2),
        "min_friction", "stable", 0.2, governing=_pairs(("B1", "B2")),
        verdicts=_around(0.2, "friction"),
        source="By hand: blocks 2 x 0.5 (W = 1), 1 x 0.5 (W = 0.5), 1 x 1 (W = 1); H = 0.2 "
        "at the top. Ratios H / (weight above): top joint 0.2/1, middle 0.2/1.5, base "
        "0.2/2.5; the largest governs: f* = 0.2 at B1-B2. Tipping margins hold."))
    out.append(Case(
        "three_block_stack_load_on_middle", stack_loaded_in_the_middle,
        "min_friction", "stable", 0.15, governing=_pairs(("B0", "B1")),
        verdicts=_around(0.15, "friction"),
        source="By hand: H = 0.3 on the middle block (top face centre) of three 2 x 0.5 "
        "blocks (W = 1). The joint above it carries no shear (the top block has no "
        "horizontal load); middle-bottom: 0.3/2; base: 0.3/3. f* = 0.15 at B0-B1."))
    # harmonic stack: exactly at the limit
    out.append(Case("harmonic_4", lambda: harmonic(4), "check", "admissible",
                    source=_HARMONIC, verdicts=tuple(
                        Verdict(False, scene=lambda k=k: harmonic(4, extra={k: 1e-3}))
                        for k in (1, 2, 4))))
    out.append(Case("harmonic_4_shifted", lambda: harmonic(4, extra={2: 1e-3}), "check",
                    "inadmissible", source=_HARMONIC))
    # two blocks side by side
    out.append(Case("side_by_side_push", lambda: side_by_side(0.4, +1, 0.0),
                    "min_friction", "stable", 0.0, atol=1e-7,
                    verdicts=(Verdict(True),), source=_SIDE))
    out.append(Case("side_by_side_pull", lambda: side_by_side(0.4, -1, 0.0),
                    "min_friction", "stable", 0.4,
                    governing=_pairs(("S", "A"), ("S", "B")),
                    verdicts=(Verdict(False), *_around(0.4, "friction")), source=_SIDE))
    # the seed's reference model
    central = _pairs(("S", "C1"), ("S", "C2"), ("C1", "T"), ("C2", "T"))
    out.append(Case("seed_model", seed_model, "min_friction", "stable", 0.5,
                    governing=central, angle_deg=math.degrees(math.atan(0.5)), max_solves=15,
                    verdicts=_around(0.5, "friction"), source=_SEED))
    out.append(Case("seed_model_weight_50", lambda: seed_model(50.0), "min_friction",
                    "stable", 0.25, governing=central, verdicts=_around(0.25, "friction"),
                    source=_SEED_WEIGHT + " f* = 0.25 for gamma = 50."))
    out.append(Case("seed_model_weight_25", lambda: seed_model(25.0), "min_friction",
                    "stable", 50.0 / 150.0, source=_SEED_WEIGHT + " f* = 1/3 for gamma = 25."))
    # leaning pair
    out.append(Case("leaning_pair", leaning_pair, "min_friction", "stable", 1.0 / 15.0,
                    governing=_pairs(("G", "L"), ("G", "R")), governing_any_vertex=True,
                    verdicts=(Verdict(False, (("friction", 0.0),)),
                              *_around(1.0 / 15.0, "friction")), source=_LEANING))
    # statuses without a number (a block that nothing holds, floating() or
    # on_a_point(), is no case: every analysis refuses it as bad input)
    out.append(Case("pressed_down", pressed_down, "max_load_multiplier", "unbounded",
                    source="A live force straight down through the centroid with infinite "
                    "friction only presses the block onto its support: every lambda >= 0 "
                    "is admissible (scene format: status \"unbounded\")."))
    out.append(Case(
        "propped_up_by_the_live_load",
        lambda: inclined(0.5, 1.0, math.radians(30.0), live_body_force=[1.0, 0.0],
                         friction="infinite"),
        "max_load_multiplier", "unstable",
        verdicts=(Verdict(False, (("load_factor", 0.0),)),),
        source="Scene format: \"unstable\" when the dead load alone has no admissible "
        "state. The 0.5 x 1 block on the 30 deg ramp tips under its weight (b/h < tan 30 "
        "deg); a live body force uphill can prop it up, so admissible multipliers exist, "
        "but lambda = 0 is not one of them."))
    # 3D
    for az in (0.0, 0.4, math.pi / 4, 2.0):
        th = math.radians(20.0)
        out.append(Case(
            f"box_on_20deg_slope_azimuth_{az:.3g}",
            lambda az=az, th=th: box_on_slab(a=2, b=2, h=0.5, tilt=th, azimuth=az),
            "min_friction", "stable", math.tan(th), source=_CONE))
    alpha = math.radians(30.0)
    out.append(Case(
        "box_tips_about_an_edge",
        lambda: box_on_slab(a=1, b=2, h=2, friction="infinite",
                            live_body_force=[math.cos(alpha), math.sin(alpha), 0]),
        "max_load_multiplier", "collapse", 1 / (2 * math.cos(alpha)), modes=("hinge",),
        source=_TIP3D))
    return out


#: case name -> case
CASES: dict[str, Case] = {c.name: c for c in _catalogue()}


def cases(analysis: str | None = None, dimension: int | None = None) -> list[Case]:
    """The cases, optionally those of one analysis or dimension."""
    return [c for c in CASES.values()
            if (analysis is None or c.analysis == analysis)
            and (dimension is None or c.dimension == dimension)]


__all__ = ["ANALYSES", "CASES", "Case", "Verdict", "block_on_base", "box_on_slab", "cases",
           "floating", "harmonic", "inclined", "leaning_pair", "on_a_point", "pressed_down",
           "rect", "rotate", "scene2d", "scene3d", "seed_model", "side_by_side", "stack",
           "stack_loaded_in_the_middle"]
