"""Turn a 2D scene into the equivalent 3D scene of prisms."""

from __future__ import annotations

from ..errors import InputError
from .geometry import ccw, signed_area
from .model import Block, Load, Scene
from .polyhedra import prism_faces


def extrude(scene: Scene, depth: float | None = None) -> Scene:
    """The 3D scene of a 2D one: each polygon becomes a prism of the scene's depth.

    The 2D plane (x, y) becomes the vertical plane (x, z) of the 3D scene; the depth
    runs along y from 0 to ``depth``; gravity stays vertical (-z). Forces (fx, fy)
    become (fx, 0, fy), points (x, y) become (x, depth / 2, y), and a couple m (about
    the 2D out-of-plane axis, counter-clockwise positive) becomes (0, -m, 0). Weights,
    friction and joint laws are unchanged, so f* and lambda* are the same; at another
    ``depth`` than the scene's the weights and the joints' strengths (stresses) scale
    with it and the point loads do not.
    A non-convex polygon becomes a non-convex prism (its two caps non-convex faces).
    """
    if scene.dimension != 2:
        raise InputError("extrude takes a 2D scene")
    t = scene.effective_depth if depth is None else float(depth)
    if not t > 0:
        raise InputError(f"depth must be > 0, got {t}")
    blocks = []
    for b in scene.blocks:
        poly = ccw(b.points)
        if signed_area(poly) <= 0:
            raise InputError("polygon has zero area", f"block {b.id!r}")
        front = [(float(x), 0.0, float(y)) for x, y in poly]
        back = [(float(x), t, float(y)) for x, y in poly]
        faces = tuple(map(tuple, prism_faces(front, back)))
        blocks.append(Block(b.id, (*front, *back), faces, b.support, b.unit_weight))

    def v3(v):
        return None if v is None else (float(v[0]), 0.0, float(v[1]))

    loads = []
    for ld in scene.loads:
        pt = None if ld.point is None else (float(ld.point[0]), t / 2, float(ld.point[1]))
        mom = None if ld.moment is None else (0.0, -float(ld.moment), 0.0)
        loads.append(Load(ld.block, v3(ld.force), pt, mom, ld.live))
    return Scene(dimension=3, blocks=tuple(blocks), loads=tuple(loads), joints=scene.joints,
                 name=scene.name, units=scene.units, depth=None,
                 unit_weight=scene.unit_weight if scene.unit_weight is not None else None,
                 friction=scene.friction, live_body_force=v3(scene.live_body_force),
                 load_factor=scene.load_factor, flow=scene.flow, source=scene.source)
