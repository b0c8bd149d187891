"""The seed paper's four-block reference mechanical model (its Fig. 4a).

A support block; two central blocks side by side on it; a top block over both. A dead
vertical force P acts down on the top block at mid-width and two live horizontal forces H
pull the central blocks outwards (at their centroids).

Without self-weight, by symmetry each central block carries N = P / 2 on its top and on
its bottom joint; the vertical joint between them cannot carry tension, so H is resisted
by friction on the two horizontal joints only and the minimum friction coefficient is

    f* = H / (N_top + N_bottom) = H / P = 0.5   (P = 100 N, H = 50 N; seed: 0.5, 26.57 deg)

With self-weight W_t (top block) and W_c (each central block),
N_top = (P + W_t) / 2 and N_bottom = N_top + W_c, so

    f* = H / (P + W_t + W_c).

The seed reports f* = 0.25 (14.03 deg) with self-weight, i.e. W_t + W_c = 100 N. The
default blocks (central 0.10 x 0.10 m, top 0.20 x 0.05 m, depth 0.25 m, unit weight
20 kN/m^3 = 20000 N/m^3) weigh W_t = W_c = 50 N, which gives exactly that. The seed does
not publish its block sizes; these are one choice consistent with its number.
"""

from __future__ import annotations

from ..scene.model import Scene
from .arches import block, make_scene, non_negative, positive


def reference(P: float = 100.0, H: float = 50.0, self_weight: bool = False,
              unit_weight: float = 20000.0, block_width: float = 0.1,
              block_height: float = 0.1, top_height: float = 0.05, depth: float = 0.25,
              friction: float | str = 0.6, bond_tensile_strength: float = 0.0,
              bond_cohesion: float = 0.0) -> Scene:
    """The four-block reference model (forces in N, lengths in m).

    Args:
        P: dead vertical force on the top block (N).
        H: live horizontal force pulling each central block outwards (N).
        self_weight: include the blocks' weight (``unit_weight`` in N/m^3).
        block_width, block_height: size of each central block; the top block is
            2 ``block_width`` wide and ``top_height`` high.
        bond_tensile_strength, bond_cohesion: a bonded vertical joint between the
            central blocks (stresses in N/m^2 over its area; 0: a dry joint), the
            seed's Fig. 4b: it cracks when the pull overcomes its tensile strength.
    """
    g = "reference"
    P, H = non_negative("P", P, g), non_negative("H", H, g)
    if isinstance(self_weight, str):
        if self_weight.lower() not in ("true", "false", "1", "0", "yes", "no"):
            from ..errors import InputError

            raise InputError(f"{g}: self_weight must be true or false, got {self_weight!r}")
        self_weight = self_weight.lower() in ("true", "1", "yes")
    uw = non_negative("unit_weight", unit_weight, g) if self_weight else 0.0
    b, h = positive("block_width", block_width, g), positive("block_height", block_height, g)
    ht, d = positive("top_height", top_height, g), positive("depth", depth, g)
    from .arches import friction_param

    fr = friction_param(friction, g)
    blocks = [
        block("support", [(-2 * b, -h), (2 * b, -h), (2 * b, 0), (-2 * b, 0)], support=True),
        block("left", [(-b, 0), (0, 0), (0, h), (-b, h)]),
        block("right", [(0, 0), (b, 0), (b, h), (0, h)]),
        block("top", [(-b, h), (b, h), (b, h + ht), (-b, h + ht)]),
    ]
    loads = [
        {"block": "top", "force": [0.0, -P], "point": [0.0, h + ht]},
        {"block": "left", "force": [-H, 0.0], "live": True},
        {"block": "right", "force": [H, 0.0], "live": True},
    ]
    name = f"four-block reference model, P = {P:g} N, H = {H:g} N" + (
        ", with self-weight" if self_weight else ", no self-weight")
    bt = non_negative("bond_tensile_strength", bond_tensile_strength, g)
    bc = non_negative("bond_cohesion", bond_cohesion, g)
    joints = None
    if bt or bc:
        name += f", bonded vertical joint (tensile strength {bt:g}, cohesion {bc:g} N/m^2)"
        joints = [{"blocks": ["left", "right"], "tensile_strength": bt, "cohesion": bc}]
    return make_scene(name, blocks, unit_weight=uw, friction=fr, depth=d, loads=loads,
                      live_body_force=None, units={"length": "m", "force": "N"},
                      joints=joints)


__all__ = ["reference"]
