"""What the plane and spatial pictures share: the loads as arrows with their values, the
mechanism's joints worth marking, figures with constrained layout and legends kept
off the axes.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..scene.geometry import scene_size, scene_weights
from ..scene.model import Scene

#: the legend's font size
LEGEND_POINTS = 8.0
DEAD_COLOUR = "#333333"
LIVE_COLOUR = "#c2185b"
MOVING_COLOUR = "#e39a5b"
HINGE_COLOUR = "tab:red"
SLIDE_COLOUR = "tab:blue"
OPEN_COLOUR = "#ff8c00"
#: arrows of the resultant self-weight and live body force, as a fraction of the size
BODY_ARROW_FRACTION = 0.15
#: the largest point load's arrow, as a fraction of the scene's size
POINT_ARROW_FRACTION = 0.12
#: joints whose opening or slip is below this fraction of the mechanism's largest are
#: not marked (an interior-point mechanism spreads small motions over many joints)
MARK_FRACTION = 0.05
#: a 3D mechanism picture marks at most this many joints, the fastest (hinge lines and
#: joint outlines of a distributed mechanism, a dome's, tangle past a dozen)
MOST_MARKED_3D = 12
#: a 3D mechanism of at most this many rigid bodies colours each body (BODY_COLOURS);
#: one of more bodies is coloured by the blocks' speed (a distributed mechanism, a
#: corbel dome's, moves its 61 blocks each on its own: 61 colours cannot be told apart)
MOST_BODIES_COLOURED = 6
BODY_COLOURS = (MOVING_COLOUR, "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#bcbd22")
#: a block's speed colour runs through these, from the slowest moving block's (pale)
#: to the fastest's (dark): hinge (red) and sliding (blue) marks stay visible on both
SPEED_COLOURS = ("#fff3e0", "#f2a35e", "#7a3410")
#: the speeds (share of the fastest) the legend shows a swatch of
SPEED_LEGEND = (0.1, 0.5, 1.0)
LAMBDA = "\N{GREEK SMALL LETTER LAMDA}"
TIMES = "\N{MULTIPLICATION SIGN}"


@dataclass(frozen=True)
class LoadMark:
    """One load arrow: it starts at ``tail`` and points along ``direction`` (unit) for
    ``length``; ``live`` ones are multiplied by lambda; ``label`` gives the value."""

    tail: np.ndarray
    direction: np.ndarray
    length: float
    live: bool
    label: str
    kind: str  # "self-weight", "live body force", "point load"

    @property
    def tip(self) -> np.ndarray:
        return self.tail + self.length * self.direction


def live_applies(result: Any) -> bool:
    """Does the live load act in ``result``: not in a check or a friction search at load
    factor 0 (a picture of the arch's self-weight check drew "live: lambda x 37.69 kN"
    over its ring, where its title said "load factor 0")."""
    return not (getattr(result, "analysis", "") in ("check", "min_friction")
                and not getattr(result, "load_factor", None))


def load_marks(scene: Scene, live: bool = True) -> list[LoadMark]:
    """The self-weight and the live body force as resultants at the free blocks' centre
    of gravity (with their totals), and every point load ending at its point of
    application (length in proportion to its size, the value in the label); the live
    ones only with ``live``."""
    d = scene.dimension
    fu = f" {scene.force_unit}" if scene.force_unit else ""
    size = scene_size(scene)
    w, centroids, _ = scene_weights(scene)
    free = ~scene.support_mask
    out: list[LoadMark] = []
    W = float(w[free].sum())
    down = np.zeros(d)
    down[-1] = -1.0
    if W > 0:
        cg = (w[free, None] * centroids[free]).sum(axis=0) / W
        out.append(LoadMark(cg, down, BODY_ARROW_FRACTION * size, False,
                            f"self-weight {W:.4g}{fu}", "self-weight"))
        lbf = scene.live_body_force
        if live and lbf is not None and any(v != 0 for v in lbf):
            v = np.asarray(lbf, dtype=float)
            mag = float(np.linalg.norm(v))
            out.append(LoadMark(cg, v / mag, BODY_ARROW_FRACTION * size, True,
                                f"live: {LAMBDA} {TIMES} {W * mag:.4g}{fu} "
                                f"(weight {TIMES} {_vec(v)})", "live body force"))
    big = max((float(np.linalg.norm(ld.force)) for ld in scene.loads), default=0.0)
    for ld in scene.loads:
        v = np.asarray(ld.force, dtype=float)
        mag = float(np.linalg.norm(v))
        if mag == 0 or (ld.is_live and not live):
            continue
        at = (centroids[scene.index[ld.block]] if ld.point is None
              else np.asarray(ld.point, dtype=float))
        L = POINT_ARROW_FRACTION * size * mag / big
        lam = f"{LAMBDA} {TIMES} " if ld.is_live else ""
        out.append(LoadMark(at - L * v / mag, v / mag, L, ld.is_live, f"{lam}{mag:.4g}{fu}",
                            "point load"))
    return out


def _vec(v: np.ndarray) -> str:
    return "(" + ", ".join(f"{x:.3g}" for x in v) + ")"


def joint_motion(result: Any) -> np.ndarray:
    """(m,) each joint's largest opening or slip in the mechanism."""
    c = result.contacts
    mech = result.mechanism
    op = np.abs(np.asarray(mech.opening, dtype=float))
    pj = c.point_joint
    out = np.zeros(c.n_joints)
    np.maximum.at(out, pj, op)
    sl = np.abs(np.asarray(mech.slip, dtype=float))
    if sl.size == c.n_joints:  # one slip per joint (2D)
        out = np.maximum(out, sl.ravel())
    elif sl.size and sl.size % len(op) == 0:
        np.maximum.at(out, pj, sl.reshape(len(op), -1).max(axis=1))
    return out


def marked_joints(result: Any, most: int | None = None) -> dict[str, np.ndarray]:
    """Joints to mark in a mechanism picture: "hinge" (hinge or slide+hinge), "slide"
    (slide, slide+hinge) and "open", each left out when its motion is below
    MARK_FRACTION of the largest, or (``most``) when it moves slower than the ``most``-th
    fastest; "left_out" counts the joints so dropped."""
    mech = result.mechanism
    motion = joint_motion(result)
    top = float(motion.max(initial=0.0))
    big = motion >= MARK_FRACTION * top if top > 0 else np.zeros(len(motion), bool)
    if most is not None and big.sum() > most:  # the fastest, and those as fast
        cut = float(np.sort(motion)[::-1][most - 1])
        big &= motion >= cut * (1 - 1e-6)
    modes = np.array(mech.modes, dtype=object)
    moving = np.array([m != "closed" for m in mech.modes], dtype=bool)
    out = {"hinge": np.flatnonzero(big & np.isin(modes, ["hinge", "slide+hinge"])),
           "slide": np.flatnonzero(big & np.array([m.startswith("slide") for m in modes],
                                                   dtype=bool)),
           "open": np.flatnonzero(big & (modes == "open")),
           "left_out": np.flatnonzero(moving & ~big)}
    return out


def speed_colour(share: float) -> str:
    """The colour of a block moving at ``share`` (0 to 1) of the fastest's speed."""
    rgb = [[int(h[k:k + 2], 16) for k in (1, 3, 5)] for h in SPEED_COLOURS]
    t = min(max(share, 0.0), 1.0) * (len(rgb) - 1)
    i = min(int(t), len(rgb) - 2)
    mix = [a + (t - i) * (b - a) for a, b in zip(rgb[i], rgb[i + 1], strict=True)]
    return "#" + "".join(f"{round(x):02x}" for x in mix)


def mechanism_colours(scene: Scene, result: Any, centroids: np.ndarray
                      ) -> tuple[list[str | None], list[tuple[str, str]]]:
    """The colour of each block in a 3D mechanism picture (None: at rest) and the
    legend's (colour, label) rows: each rigid body its own colour where there are at
    most MOST_BODIES_COLOURED, else each block by its speed (share of the fastest's)."""
    from ..answer import block_reach, rigid_bodies

    reach = block_reach(scene, result.mechanism.velocities, centroids)
    top = float(reach.max(initial=0.0))
    bodies = rigid_bodies(result)
    out: list[str | None] = [None] * len(scene.blocks)
    if not bodies or top <= 0:
        return out, []
    ids = [b.id for b in scene.blocks]
    if len(bodies) <= MOST_BODIES_COLOURED:
        legend = []
        for k, body in enumerate(bodies):
            colour = BODY_COLOURS[k]
            for i in body:
                out[i] = colour
            fast = ids[max(body, key=lambda i: reach[i])]
            what = f"{len(body)} blocks, fastest {fast}" if len(body) > 1 else fast
            legend.append((colour, f"rigid body {k + 1} ({what})" if len(bodies) > 1
                           else f"moving blocks: one rigid body ({what})"))
        return out, legend
    for body in bodies:
        for i in body:
            out[i] = speed_colour(reach[i] / top)
    fastest = ids[int(np.argmax(reach))]
    legend = [(speed_colour(f), f"block speed {100 * f:.0f} % of the fastest's"
               + (f" ({fastest})" if f == 1 else "")) for f in SPEED_LEGEND]
    return out, legend


def new_axes(dimension: int, n_blocks: int) -> Any:
    """A new figure with constrained layout (legends and colour bars get their own room)."""
    import matplotlib.pyplot as plt

    if dimension == 3:
        fig = plt.figure(figsize=(9, 7.5), layout="constrained")
        return fig.add_subplot(projection="3d")
    # "compressed": constrained layout that also closes the gaps around equal-aspect axes
    _, ax = plt.subplots(figsize=(10, 7.5) if n_blocks > 200 else (8, 6.5),
                         layout="compressed")
    return ax


def place_legend(ax: Any, extra: list[Any] | None = None) -> Any:
    """One legend entry per mark, below the figure when it has constrained layout (never
    over the axes or their labels), otherwise below the axes."""
    import textwrap

    from matplotlib.layout_engine import ConstrainedLayoutEngine

    handles, labels = ax.get_legend_handles_labels()
    for h in extra or []:
        handles.append(h)
        labels.append(h.get_label())
    if not handles:
        return None
    fig = ax.figure
    # columns as wide as the figure holds, long labels on two lines or more (a row of
    # three ran past an 8 in figure's edges: "joint force on its lower (or outer)
    # block (key arrow 20 force units, be")
    ncol = min(len(handles), 3)
    chars = int(float(fig.get_size_inches()[0]) * 72 / (0.6 * LEGEND_POINTS) / ncol) - 6
    labels = ["\n".join(textwrap.wrap(t, max(chars, 20), break_on_hyphens=False)) or t
              for t in labels]
    # the figure's own axes, colour bars aside: more than one is a user's figure, where
    # one figure legend per plot would overlap the others (and each plot removed them)
    alone = len([a for a in fig.axes if not hasattr(a, "_colorbar")]) == 1
    if isinstance(fig.get_layout_engine(), ConstrainedLayoutEngine) and alone:
        for old in list(fig.legends):
            if old.get_gid() == "rb-legend":  # a plot's before (not the user's)
                old.remove()
        leg = fig.legend(handles, labels, loc="outside lower center", ncol=ncol,
                         fontsize=LEGEND_POINTS)
    else:  # below its own axes: a colour bar takes their right (notebook 01's overlapped)
        # (its gap in points, under the tick labels and the x label whatever the height)
        leg = ax.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 0.0),
                        ncol=ncol if alone else 1, borderaxespad=4.5,
                        fontsize=LEGEND_POINTS)
    leg.set_gid("rb-legend")
    return leg


def settle_layout(ax: Any) -> bool:
    """Lay out a figure of the plot's own once, without drawing it: the first layout of
    its constrained ("compressed") engine put the x label under the legend below the
    axes (the segmental arch's title of four lines: 7 px of "x [m]" hidden), and every
    later one puts it clear; a picture saved or shown after this one is its second.
    Whether it laid the figure out."""
    from matplotlib.layout_engine import ConstrainedLayoutEngine

    fig = ax.figure
    if isinstance(fig.get_layout_engine(), ConstrainedLayoutEngine) and any(
            leg.get_gid() == "rb-legend" for leg in fig.legends):
        fig.draw_without_rendering()
        return True
    return False


def arrow_handle(colour: str, label: str) -> Any:
    """A legend proxy that looks like an arrow."""
    from matplotlib.lines import Line2D

    return Line2D([], [], color=colour, marker="$\u2192$", markersize=14, linestyle="None",
                  label=label)


def load_legend(kinds: set[bool], extra: list[Any]) -> None:
    """Legend entries for the loads drawn: ``kinds`` holds False for a dead load drawn,
    True for a live one."""
    if False in kinds:
        extra.append(arrow_handle(DEAD_COLOUR, "dead load (value shown)"))
    if True in kinds:
        extra.append(arrow_handle(LIVE_COLOUR, "live load, multiplied by "
                                  "\N{GREEK SMALL LETTER LAMDA}"))


def line_handle(colour: str, label: str, **kw: Any) -> Any:
    from matplotlib.lines import Line2D

    return Line2D([], [], color=colour, label=label, **kw)


__all__ = ["LoadMark", "arrow_handle", "joint_motion", "line_handle",
           "load_marks", "marked_joints", "new_axes", "place_legend", "scene_weights"]
