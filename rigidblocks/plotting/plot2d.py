"""Pictures of 2D scenes and results with matplotlib.

:func:`plot` draws the blocks (supports shaded differently) and, given a result:

* after :func:`~rigidblocks.check` or :func:`~rigidblocks.min_friction` (a result whose
  ``state`` is a :class:`~rigidblocks.results.ForceState`): the joint force resultants
  as arrows scaled to a reference arrow in the legend, the thrust line (the points
  where the resultants cross the joints, joined in order along the structure when the
  blocks form a chain), the joints coloured by their friction demand |T| / (f N) with
  a colour bar, and the governing joints marked;
* after :func:`~rigidblocks.max_load_multiplier`: the collapse mechanism as the
  displaced configuration: block i, with virtual velocity (u, v, omega) of its
  centroid, turns by s omega about its instantaneous centre (see
  :func:`displaced_polygons`), s chosen so that the largest displacement is about
  10 % of the scene's size; hinges and sliding joints are marked.

Loads are drawn with their values: the self-weight and the live body force as
resultants at the free blocks' centre of gravity (the live one says what lambda
multiplies), point loads as arrows ending at their points (live ones "lambda x F").
Joints that carry no force (open) are dashed, those whose resultant sits on an edge
(hinging) get a dot there; every mark has a legend entry, and the legend goes below
the figure (constrained layout), never over the axes. An inadmissible ``check`` has no
force state: its picture says so in the title and on the axes.

Large scenes stay readable: above ``max_arrows`` joints no arrows are drawn and the
joints are drawn as a heat map instead (colour: friction demand, line width:
normal force); arrows shorter than a twentieth of the largest are left out.

Every artist carries a ``gid`` (``"rb-blocks"``, ``"rb-supports"``, ``"rb-joints"``,
``"rb-forces"``, ``"rb-thrust"``, ``"rb-governing"``, ``"rb-displaced"``,
``"rb-hinges"``, ``"rb-sliding"``, ``"rb-open"``, ``"rb-force-key"``, ``"rb-loads"``,
``"rb-open-joints"``, ``"rb-hinging"``, ``"rb-legend"``, ``"rb-verdict"``,
``"rb-breached"``) so that
programs can find it.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..answer import without_dilatancy
from ..results import (
    DIRECT_STANDS,
    analysis_friction,
    joint_frictions,
    shear_use,
    tension_use,
    unloaded,
)
from ..scene.geometry import block_weights, scene_size
from ..scene.model import Scene
from .marks import (
    DEAD_COLOUR,
    HINGE_COLOUR,
    LIVE_COLOUR,
    MOVING_COLOUR,
    OPEN_COLOUR,
    SLIDE_COLOUR,
    arrow_handle,
    line_handle,
    live_applies,
    load_legend,
    load_marks,
    marked_joints,
    new_axes,
    place_legend,
    scene_weights,
    settle_layout,
)

#: above this many joints no force arrows are drawn (the joints become a heat map)
MAX_ARROWS = 400
#: arrows shorter than this fraction of the largest one are left out
MIN_ARROW_FRACTION = 0.05
#: above this many marked joints of a kind, a mechanism picture draws small marks (hinges)
#: or the joints themselves (sliding) instead of large markers that would bury it
MANY_MARKS = 40
#: the largest mechanism displacement, as a fraction of the scene's size
DISPLACEMENT_FRACTION = 0.1

#: the title's font size (matplotlib's default for axes titles: "large", 12 points)
TITLE_POINTS = 12.0
FREE_COLOUR = "#d9c7a7"
SUPPORT_COLOUR = "#7f7f7f"
#: statuses that are verdicts; any other (undecided, failure, ...) is titled as none
VERDICTS = ("admissible", "inadmissible", "stable", "unstable", "collapse", "unbounded")


def plot(scene: Scene, result: Any = None, ax: Any = None, *, ids: bool = False,
         max_arrows: int = MAX_ARROWS, force_scale: float | None = None,
         displacement_scale: float | None = None, title: str | None = None,
         colorbar: bool = True, loads: bool = True) -> Any:
    """Draw a 2D scene, and a result of an analysis on it.

    Args:
        scene: a 2D scene.
        result: None, or the result of ``check``, ``min_friction`` (with a force
            state) or ``max_load_multiplier`` on this scene.
        ax: matplotlib Axes to draw on (default: a new figure).
        ids: write block ids at the centroids.
        max_arrows: above this many joints, draw a heat map instead of arrows.
        force_scale: drawing length per force unit (default: the largest resultant
            is 12 % of the scene's size).
        displacement_scale: factor s on the mechanism's virtual velocities (default:
            the largest displacement is 10 % of the scene's size).
        title: overrides the title made from the result.
        colorbar: add a colour bar for the friction demand.
        loads: draw the self-weight, the live load's direction and the point loads.

    Returns:
        The matplotlib Axes.
    """
    from matplotlib.collections import LineCollection, PolyCollection

    if scene.dimension != 2:
        from ..errors import InputError

        raise InputError("plot draws 2D scenes only", scene.source)
    if ax is None:
        ax = new_axes(2, len(scene.blocks))
    size = scene_size(scene)
    _, centroids, _ = scene_weights(scene)
    polys = [b.points for b in scene.blocks]
    sup = scene.support_mask
    mech = getattr(result, "mechanism", None)
    faded = mech is not None
    lw = 0.8 if len(polys) < 500 else 0.2
    for mask, colour, gid in ((~sup, FREE_COLOUR, "rb-blocks"), (sup, SUPPORT_COLOUR,
                                                                  "rb-supports")):
        pc = PolyCollection([polys[i] for i in np.flatnonzero(mask)], closed=True,
                            facecolors=colour, edgecolors="k", linewidths=lw,
                            alpha=0.35 if faded and gid == "rb-blocks" else 1.0,
                            hatch="///" if gid == "rb-supports" else None, zorder=1)
        pc.set_gid(gid)
        pc.set_label("support" if gid == "rb-supports" else
                     "block (original position)" if faded else "block")
        ax.add_collection(pc)
    allpts = np.concatenate(polys)
    lo, hi = allpts.min(axis=0), allpts.max(axis=0)

    title_text = _title(scene, result, ax)
    state = getattr(result, "state", None)
    extra: list[Any] = []
    if loads:
        lo, hi = _draw_loads(ax, scene, lo, hi, extra, live_applies(result))
    label_at = centroids
    if mech is not None:
        lo, hi, label_at = _draw_mechanism(ax, scene, result, centroids, size,
                                           displacement_scale, lo, hi, extra)
    elif state is not None and result.contacts.n_joints:
        lo, hi = _draw_forces(ax, scene, result, size, max_arrows, force_scale, colorbar,
                              LineCollection, lo, hi, extra)
    elif result is not None and getattr(result, "status", None) is not None:
        box = _no_state(ax, result, scene.force_unit)
        # room above the drawing for the box (it hid the reference model's load value)
        hi = hi + np.array([0.0, box * (hi - lo)[1] / (1.0 - box)])
    if ids:  # on the blocks as drawn (displaced in a mechanism)
        fs = 8 if len(polys) < 60 else 5
        for b, c in zip(scene.blocks, label_at, strict=True):
            # over the load arrows (zorder 7), on a light box: an arrowhead hid "c1b2"
            ax.text(c[0], c[1], b.id, ha="center", va="center", fontsize=fs, zorder=8,
                    bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none",
                          "alpha": 0.6}).set_gid("rb-ids")
    place_legend(ax, extra)
    pad = 0.05 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal", adjustable="box")
    unit = scene.length_unit
    ax.set_xlabel(f"x [{unit}]" if unit else "x")
    ax.set_ylabel(f"y [{unit}]" if unit else "y")
    ax.set_title(title if title is not None else title_text)
    _clear_load_labels(ax, laid_out=settle_layout(ax))
    return ax


def _clear_load_labels(ax: Any, laid_out: bool = False) -> None:
    """A load's label that lies over a breach's label or a block's id moved to the side
    of its anchor that lies over the fewest (the arch's live load label and two breach
    labels were one blot), once the figure is laid out (here, unless ``laid_out``)."""
    labels = [t for t in ax.texts if t.get_gid() == "rb-loads"]
    others = [t for t in ax.texts if t.get_gid() in ("rb-breached", "rb-ids")]
    if not labels or not others:
        return
    fig = ax.figure
    if not laid_out:
        fig.draw_without_rendering()
    renderer = fig.canvas.get_renderer()
    boxes = [t.get_window_extent(renderer) for t in others]

    def covered(t: Any) -> float:
        bb = t.get_window_extent(renderer)
        return sum(max(0.0, min(bb.x1, o.x1) - max(bb.x0, o.x0))
                   * max(0.0, min(bb.y1, o.y1) - max(bb.y0, o.y0)) for o in boxes)

    for t in labels:
        best = (covered(t), t.get_ha(), t.get_va())
        if best[0] == 0:
            continue
        for ha in (best[1], "left", "right", "center"):
            for va in ("bottom", "top"):
                t.set_ha(ha)
                t.set_va(va)
                area = covered(t)
                if area < best[0]:
                    best = (area, ha, va)
        t.set_ha(best[1])
        t.set_va(best[2])


def _title(scene: Scene, result: Any, ax: Any = None) -> str:
    """The scene's name and the answer's verdict and number
    (:meth:`rigidblocks.answer.AnswerBlock.title`, as the CLI and the report say it),
    and where the mechanism drawn is off the optimal face, that it is no collapse
    mechanism; wrapped to lines of at most 90 characters."""
    import textwrap

    from ..answer import answer_block
    from ..methods.convex import OFF_FACE_NOTE

    name = scene.name or ""
    block = answer_block(scene, result, symbols=True) if result is not None else None
    txt = block.title() if block is not None else ""
    if block is not None and getattr(result, "mechanism", None) is not None and \
            any(r.startswith(OFF_FACE_NOTE) for r in block.reasons):
        # as the answer's reasons say: the picture is not of a collapse mechanism
        txt += "; the mechanism drawn is the nearest that can be drawn, not a collapse " \
            "mechanism at this multiplier"
    elif block is not None and getattr(getattr(result, "mechanism", None), "kind",
                                       "") == "blend":
        # (its picture read as the one mechanism's, where the text says "the blend")
        txt += "; drawn: the blend of every optimal mechanism, not one of them"
    txt = txt.replace("`", "")  # (a terminal's command quotes, literal in a title)
    # as wide as the figure takes at the title's size (a 5 x 4 in figure of one's own
    # cut it at both sides; about 0.55 em a character)
    width = 90
    if ax is not None:
        inches = float(ax.figure.get_size_inches()[0])
        width = max(30, min(90, int(inches * 72 / (0.6 * TITLE_POINTS))))
    # an equation on one line ("at f" / "= 0.6" read apart)
    glued = txt.replace(" = ", "\0=\0")
    txt = "\n".join(textwrap.wrap(glued, width, break_on_hyphens=False)).replace("\0", " ")
    return f"{name}\n{txt}" if (name and txt) else (name or txt)


def _nice(x: float) -> float:
    """1, 2 or 5 times a power of ten, at most x."""
    if x <= 0 or not math.isfinite(x):
        return 1.0
    e = math.floor(math.log10(x))
    for m in (5, 2, 1):
        if m * 10**e <= x:
            return m * 10**e
    return 10**e  # pragma: no cover


def _draw_loads(ax: Any, scene: Scene, lo: np.ndarray, hi: np.ndarray,
                extra: list[Any], live: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """Load arrows with their values (see :func:`rigidblocks.plotting.marks.load_marks`)."""
    from matplotlib.transforms import ScaledTranslation

    marks = load_marks(scene, live)
    kinds = set()
    for m in marks:
        colour = LIVE_COLOUR if m.live else DEAD_COLOUR
        ann = ax.annotate("", xy=m.tip, xytext=m.tail, zorder=7,
                          arrowprops={"arrowstyle": "-|>", "color": colour, "lw": 2.0,
                                      "shrinkA": 0, "shrinkB": 0, "mutation_scale": 16})
        ann.set_gid("rb-loads")
        # beside its arrow: beyond a body load's tip, at a point load's tail, above the
        # middle of a point load nearer horizontal than vertical (the reference model's
        # "λ x 50 N" sat on its own arrowhead); a body load's direction on a line of its
        # own (the Arpino gate's ran past the axes)
        flat = m.kind == "point load" and abs(m.direction[0]) > abs(m.direction[1])
        at = (0.5 * (m.tail + m.tip) if flat else m.tail if m.kind == "point load"
              else m.tip)
        ha = "center" if flat else "left" if m.direction[0] >= 0 else "right"
        va = "bottom" if flat or m.direction[1] >= 0 else "top"
        # (above the arrowhead's half-width too, 6 points)
        lift = ScaledTranslation(0, 6 / 72 if flat else 0, ax.figure.dpi_scale_trans)
        t = ax.text(at[0], at[1], " " + m.label.replace(" (", "\n (", 1), color=colour,
                    fontsize=8, zorder=4.5, ha=ha, va=va, transform=ax.transData + lift,
                    bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none",
                          "alpha": 0.5})
        t.set_gid("rb-loads")
        kinds.add(m.live)
        lo = np.minimum(lo, np.minimum(m.tail, m.tip))
        hi = np.maximum(hi, np.maximum(m.tail, m.tip))
    load_legend(kinds, extra)
    return lo, hi


def _no_state(ax: Any, result: Any, unit: str = "") -> float:
    """A result without a force state: say why on the axes, not just in the title; a
    NOT ADMISSIBLE check draws the joints its breaches name (:func:`_draw_breaches`)."""
    status = getattr(result, "status", "")
    if status == "inadmissible":
        # the verdict is the title's; the box says what is drawn (it gave the title's
        # verdict again, over a picture of the blocks alone)
        msg = "NOT ADMISSIBLE: no force state to draw"
        most = _draw_breaches(ax, result, unit)
        if most:
            whose = ("the state reached from X0" if without_dilatancy(result)
                     else "the state of least breach")
            msg += f"\nin red: the joints breached in {whose} (up to {most})"
        colour = "tab:red"
    elif status in VERDICTS:
        msg = f"{status.upper()}: no force state to draw"
        colour = "tab:red" if status == "unstable" else "k"
    else:
        msg = f"NO VERDICT (status \u201c{status}\u201d): nothing is decided"
        colour = "0.3"
    # on 3D axes, text in the axes' own frame is text2D
    put = getattr(ax, "text2D", ax.text)
    t = put(0.5, 0.97, msg, transform=ax.transAxes, ha="center", va="top", fontsize=10,
            color=colour, zorder=8,
            bbox={"boxstyle": "round", "fc": "white", "ec": colour, "alpha": 0.9})
    t.set_gid("rb-verdict")
    return 0.06 * (msg.count("\n") + 1)  # the box's height, about, of the axes' height


#: breached joints labelled with their breach, the largest first, at most
BREACH_LABELS = 12
BREACH_COLOUR = "tab:red"


def _draw_breaches(ax: Any, result: Any, unit: str) -> str:
    """The joints a NOT ADMISSIBLE check's state breaches (``result.breaches``, the
    largest first): in 2D their segments, in 3D their centres, red, the first
    ``BREACH_LABELS`` labelled with their breach; the largest breach with its unit, ""
    where none is named."""
    br = tuple(getattr(result, "breaches", ()) or ())
    c = getattr(result, "contacts", None)
    if not br or c is None:
        return ""
    ks = np.array([k for k, _ in br], dtype=int)
    first, last = c.points[c.joint_start[ks]], c.points[c.joint_start[ks + 1] - 1]
    label = "breached joint (its breach)"
    if c.dimension == 2:
        from matplotlib.collections import LineCollection

        art = LineCollection(np.stack([first, last], axis=1), colors=BREACH_COLOUR,
                             linewidths=4, zorder=5, label=label)
        ax.add_collection(art)
        at = 0.5 * (first + last)
    else:
        at = c.joint_centres[ks]
        art = ax.scatter(*at.T, s=40, c=BREACH_COLOUR, marker="X", zorder=5, label=label)
    art.set_gid("rb-breached")
    # in 2D along its joint (the flat arch's ten vertical joints, side by side, had
    # their labels run into one another in a row)
    d = last - first if c.dimension == 2 else np.zeros_like(at)
    turn = np.degrees(np.arctan2(d[:, 1], d[:, 0])) if c.dimension == 2 else \
        np.zeros(len(at))
    turn = 90.0 - (90.0 - turn) % 180.0  # upright: in (-90, 90], read upwards
    kw = {"rotation_mode": "anchor", "ha": "center", "va": "center"} \
        if c.dimension == 2 else {}
    for (_, v), p, r in zip(br[:BREACH_LABELS], at[:BREACH_LABELS], turn[:BREACH_LABELS],
                            strict=True):
        rot = {"rotation": float(r)} if c.dimension == 2 else {}
        lead = "" if c.dimension == 2 else " "  # (centred on its joint in 2D)
        t = ax.text(*p, f"{lead}{v:.3g} {unit}".rstrip(), color=BREACH_COLOUR, fontsize=8,
                    zorder=8, bbox={"boxstyle": "round,pad=0.15", "fc": "white",
                                    "ec": "none", "alpha": 0.7}, **kw, **rot)
        t.set_gid("rb-breached")
    return f"{max(v for _, v in br):.3g} {unit}".rstrip()


def _draw_forces(ax: Any, scene: Scene, result: Any, size: float, max_arrows: int,
                 force_scale: float | None, colorbar: bool, LineCollection: Any,
                 lo: np.ndarray, hi: np.ndarray, extra: list[Any]
                 ) -> tuple[np.ndarray, np.ndarray]:
    from ..results import lower_block_forces

    c = result.contacts
    st = result.state
    m = c.n_joints
    seg = np.stack([c.points[c.joint_start[:-1]], c.points[c.joint_start[1:] - 1]], axis=1)
    f = analysis_friction(result)
    fj = joint_frictions(result)
    if np.any(c.tensile_strength > 0):
        # a bond at its whole tensile strength read as unused beside the shear alone
        # (examples/fig4a_bonded.json at 1.1: its vertical joint, which cracks first)
        val = np.fmax(shear_use(result), tension_use(result))
        word = "strength used"
        label = f"{word}: shear |T|/(fN+ca) or tension -N/(ta)"
    elif np.any(np.isfinite(fj) & (fj > 0)) or np.any(c.cohesion > 0):
        # each joint against its own threshold (its friction override, its cohesion)
        val = shear_use(result)
        own = np.any(fj != f) or np.any(c.cohesion > 0)
        word = "shear threshold used" if own else "friction demand"
        label = (f"{word} |T| / (f N + c a), each joint's own f and c" if own
                 else f"{word} |T| / (f N), f = {f:.4g}")
    else:
        val = st.demand
        word = "friction demand"
        label = f"{word} |T| / N"
    val = np.where(np.isfinite(val), val, 1e3)
    # (not where the state shown stands and the limit run from X0 collapses below the
    # load: the Arpino gate at f = 0.6 and 0.11871 read "least-violation state, NOT
    # admissible" beside the text's "the state reached from X0 ... is admissible")
    inadmissible = getattr(result, "status", "") == "inadmissible"
    direct = inadmissible and getattr(result, "cause", "") == DIRECT_STANDS
    not_admissible = inadmissible and not direct
    heat = m > max_arrows
    Nj = np.abs(st.joint_normal)
    nmax = Nj.max(initial=0.0)
    is_open, carried = unloaded(c, st)
    widths = (0.5 + 3.5 * Nj / nmax) if (heat and nmax > 0) else (2.5 if m < 200 else 1.5)
    from matplotlib import colormaps

    lc = LineCollection(seg, cmap=colormaps["RdYlGn_r"].with_extremes(bad=(0, 0, 0, 0)),
                        linewidths=widths, zorder=3,
                        label=f"joint (colour: {word})")
    lc.set_array(np.where(is_open, np.nan, val))
    lc.set_clim(0.0, 1.0)
    lc.set_gid("rb-joints")
    ax.add_collection(lc)
    if is_open.any():
        oc = LineCollection(seg[is_open], colors="0.35", linewidths=1.5, linestyles="--",
                            zorder=3, label="open joint (no force)")
        oc.set_gid("rb-open-joints")
        ax.add_collection(oc)
    # a contact point that carries nothing while its joint does: the resultant is on the
    # joint's other end (a hinge forming)
    pj = c.point_joint
    if carried.any():
        other = np.flatnonzero(carried)
        # the loaded end of the same joint
        ends = np.where(other == c.joint_start[pj[other]], c.joint_start[pj[other] + 1] - 1,
                        c.joint_start[pj[other]])
        hp = c.points[ends]
        sc = ax.scatter(hp[:, 0], hp[:, 1], s=22, c=HINGE_COLOUR, marker="o", zorder=6,
                        label="resultant at the joint's edge (hinging)")
        sc.set_gid("rb-hinging")
    if colorbar:
        ax.figure.colorbar(lc, ax=ax, label=label, shrink=0.8, extend="max")
    # thrust line
    pts = st.thrust_points
    # only through a chain of blocks (the reference model, whose central blocks have
    # three joints, drew a "thrust line" across its open middle joint)
    line = st.thrust_line
    # the state drawn beside a NOT ADMISSIBLE verdict that stands says so (the legend
    # said nothing of it beside the title's verdict)
    suffix = (" (least-violation state, NOT admissible)" if not_admissible else
              " (state reached from X0 at this load: it stands)" if direct else "")
    if st.thrust_chain:
        (tl,) = ax.plot(line[:, 0], line[:, 1], "-", color="tab:red", lw=1.5, zorder=4,
                        label="thrust line" + suffix)
    else:  # the joints that carry a force (an open joint's dot sat on its middle)
        ms = 3 if m < 500 else 1
        (tl,) = ax.plot(pts[~is_open, 0], pts[~is_open, 1], "o", color="tab:red", ms=ms,
                        zorder=4, label="resultant on joint" + suffix)
    tl.set_gid("rb-thrust")
    # governing joints
    gov = np.asarray(result.governing, dtype=int)
    if len(gov):
        mid = seg[gov].mean(axis=1)
        sc = ax.scatter(mid[:, 0], mid[:, 1], s=90, facecolors="none", edgecolors="k",
                        linewidths=1.8, zorder=5, label="governing joint")
        sc.set_gid("rb-governing")
    # force arrows, scaled to a reference arrow drawn below the structure
    if not heat:
        # each on the lower of its joint's two blocks (its second block's in the tables)
        vec = lower_block_forces(scene, c, st)
        mag = np.linalg.norm(vec, axis=1)
        top = mag.max(initial=0.0)
        if top > 0:
            scale = force_scale if force_scale is not None else 0.12 * size / top
            keep = (mag >= MIN_ARROW_FRACTION * top) & np.all(np.isfinite(pts), axis=1)
            q = ax.quiver(pts[keep, 0], pts[keep, 1], vec[keep, 0], vec[keep, 1],
                          angles="xy", scale_units="xy", scale=1.0 / scale,
                          color="tab:blue", width=0.004, zorder=5)
            q.set_gid("rb-forces")
            ref = _nice(top)
            unit = scene.force_unit or "force units"
            y = lo[1] - 0.08 * size
            # its tip at its point (labelpos "E" pivots the arrow on its tip): its tail
            # at the structure's left edge (placed as if centred, it ran half its length
            # past the axes' edge, over the tick labels)
            key = ax.quiverkey(q, lo[0] + ref * scale, y, ref, f"{ref:g} {unit}",
                               labelpos="E",
                               coordinates="data", fontproperties={"size": 8})
            key.set_gid("rb-force-key")
            lo = np.minimum(lo, [lo[0], y - 0.03 * size])
            hi = np.maximum(hi, [lo[0] + ref * scale + 0.15 * size, y])
            extra.append(arrow_handle("tab:blue", f"joint force on its lower (or outer) "
                                      f"block (key arrow {ref:g} {unit}, below)"))
    return lo, hi


def displaced_polygons(scene: Scene, velocities: np.ndarray, s: float,
                       centroids: np.ndarray | None = None,
                       points: list[np.ndarray] | None = None,
                       contacts: Any = None) -> list[np.ndarray]:
    """Block polygons (or other ``points`` of each block) moved by s times their virtual
    velocities (u, v, omega).

    (u, v) is the velocity of the block's centroid c. A block that turns (omega != 0)
    is rotated by s omega about its instantaneous centre p0 = c + (-v, u) / omega, the
    point of zero velocity: p' = p0 + R(s omega) (p - p0); one that does not is
    translated by s (u, v). To first order in s both are p + s (u - omega (y - c_y),
    v + omega (x - c_x)). A hinge to a block at rest stays closed so; one between two
    turning blocks opens at second order in s (the arch's hinge between its two upper
    bodies: 0.17 m apart for a largest displacement of 0.55 m). Given the ``contacts``,
    the blocks' rotations and shifts are then corrected, least squares, so that the
    contact points of zero relative velocity stay together (:func:`_close_hinges`)."""
    if centroids is None:
        centroids = block_weights(scene)[1]
    theta, shift = _finite_motions(scene, np.asarray(velocities, dtype=float), s, centroids)
    if contacts is not None:
        theta, shift = _close_hinges(scene, contacts, np.asarray(velocities, dtype=float),
                                     centroids, theta, shift)
    rots = _rotations(theta)
    return [(b.points if points is None else points[k]) @ rots[k].T + shift[k]
            for k, b in enumerate(scene.blocks)]


def _finite_motions(scene: Scene, vel: np.ndarray, s: float, centroids: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Each block's rigid motion p' = R(theta) p + shift of :func:`displaced_polygons`:
    turned by s omega about its instantaneous centre, or translated."""
    n = len(scene.blocks)
    theta, shift = np.zeros(n), np.zeros((n, 2))
    for k, (b, c, (u, v, w)) in enumerate(zip(scene.blocks, centroids, vel, strict=True)):
        r = float(np.linalg.norm(b.points - c, axis=1).max())
        if abs(w) * r <= 1e-12 * max(math.hypot(u, v), 1e-300):
            shift[k] = s * np.array([u, v])
            continue
        p0 = c + np.array([-v, u]) / w
        theta[k] = s * w
        shift[k] = p0 - _rotations(theta[k:k + 1])[0] @ p0
    return theta, shift


#: the weight of a hinge's gap against a block's departure from its own finite motion
#: (:func:`_close_hinges`): the gaps left are about 1/HINGE_WEIGHT^2 of the first ones
HINGE_WEIGHT = 1e3
#: ... and the Gauss-Newton steps that correct them at most
GAUSS_NEWTON_STEPS = 20


def _close_hinges(scene: Scene, contacts: Any, vel: np.ndarray, centroids: np.ndarray,
                  theta: np.ndarray, shift: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The blocks' rigid motions (``theta``, ``shift``: p' = R(theta) p + shift)
    corrected so that every contact point whose two blocks have the same velocity there
    (a hinge, a closed joint) stays one point: least squares of those gaps (weighted
    ``HINGE_WEIGHT``) and of each moving block's departure from its motion (its centroid's
    shift, its turn times its size; a block that only slides held to no turn). A finite
    motion of a linkage keeps its hinges closed (the arch's four-hinge mechanism), and
    where none does (a mechanism that is one to first order only) the gaps are made as
    small as the motions allow. Unchanged where no such point opened by more than 1e-3 of
    the largest displacement."""
    from scipy.sparse import csr_matrix
    from scipy.sparse.linalg import spsolve

    c = contacts
    pj = np.repeat(np.arange(c.n_joints), np.diff(c.joint_start))
    a, b = c.pairs[pj, 0], c.pairs[pj, 1]
    p = np.asarray(c.points, dtype=float)

    def speed(i: np.ndarray) -> np.ndarray:
        u, v, w = vel[i, 0], vel[i, 1], vel[i, 2]
        d = p - centroids[i]
        return np.stack([u - w * d[:, 1], v + w * d[:, 0]], axis=1)

    va, vb = speed(a), speed(b)
    top = float(np.abs(vel).max(initial=0.0))
    moving = np.abs(vel).max(axis=1) > 1e-9 * top
    fastest = float(np.linalg.norm(np.concatenate([va, vb]), axis=1).max(initial=0.0))
    keep = (np.linalg.norm(vb - va, axis=1) <= 1e-6 * max(fastest, 1e-300)) \
        & (moving[a] | moving[b])
    if not keep.any():
        return theta, shift
    pk = p[keep]

    def place(th: np.ndarray, sh: np.ndarray, i: np.ndarray) -> np.ndarray:
        return np.einsum("kij,kj->ki", _rotations(th[i]), pk) + sh[i]

    ka, kb = a[keep], b[keep]
    at_a, at_b = place(theta, shift, ka), place(theta, shift, kb)
    gaps = np.linalg.norm(at_b - at_a, axis=1)
    moved = np.linalg.norm(np.concatenate([at_a - pk, at_b - pk]), axis=1).max(initial=0.0)
    if gaps.max(initial=0.0) <= 1e-3 * max(moved, 1e-300):
        return theta, shift
    free = np.flatnonzero(moving)
    col = np.full(len(scene.blocks), -1)
    col[free] = np.arange(len(free))
    size = np.array([float(np.linalg.norm(scene.blocks[i].points - centroids[i],
                                          axis=1).max()) for i in free])
    # a block that only slides keeps its turn: closing a hinge beside it turned the
    # flat arch's sliding pier 2.9 deg, drawn tipping as it slid
    turn = size * np.where(np.abs(vel[free, 2]) * size <= 1e-9 * top, HINGE_WEIGHT ** 2, 1.0)
    c0 = np.einsum("kij,kj->ki", _rotations(theta[free]), centroids[free]) + shift[free]

    def unpack(q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        th, sh = theta.copy(), shift.copy()
        th[free] = q[0::3]
        sh[free] = np.stack([q[1::3], q[2::3]], axis=1)
        return th, sh

    def residuals(q: np.ndarray) -> np.ndarray:
        th, sh = unpack(q)
        gap = (place(th, sh, kb) - place(th, sh, ka)) * HINGE_WEIGHT
        ci = np.einsum("kij,kj->ki", _rotations(th[free]), centroids[free]) + sh[free]
        return np.concatenate([gap.ravel(), (ci - c0).ravel(),
                               (th[free] - theta[free]) * turn])

    m, nf = int(keep.sum()), len(free)
    rows = np.arange(2 * m).reshape(m, 2)

    def jacobian(q: np.ndarray) -> Any:
        th, _ = unpack(q)
        r_i, c_i, v_i = [], [], []
        for blk, sign in ((kb, 1.0), (ka, -1.0)):
            on = col[blk] >= 0
            cs, sn = np.cos(th[blk[on]]), np.sin(th[blk[on]])
            x, y = pk[on, 0], pk[on, 1]
            base = 3 * col[blk[on]]
            for comp, d_th in ((0, -sn * x - cs * y), (1, cs * x - sn * y)):
                r_i += [rows[on, comp]] * 2
                c_i += [base, base + 1 + comp]
                v_i += [sign * HINGE_WEIGHT * d_th, np.full(on.sum(), sign * HINGE_WEIGHT)]
        cs, sn = np.cos(th[free]), np.sin(th[free])
        x, y = centroids[free, 0], centroids[free, 1]
        k = np.arange(nf)
        for comp, d_th in ((0, -sn * x - cs * y), (1, cs * x - sn * y)):
            r_i += [2 * m + 2 * k + comp] * 2
            c_i += [3 * k, 3 * k + 1 + comp]
            v_i += [d_th, np.ones(nf)]
        r_i.append(2 * m + 2 * nf + k)
        c_i.append(3 * k)
        v_i.append(turn)
        return csr_matrix((np.concatenate(v_i), (np.concatenate(r_i), np.concatenate(c_i))),
                          shape=(2 * m + 3 * nf, 3 * nf))

    # Gauss-Newton steps (the regularisation keeps J'J positive definite) until the gaps
    # are 1e-5 of the largest displacement (a penalty leaves about 1/HINGE_WEIGHT^2 of
    # the departures: 4e-7 on the arches)
    q = np.stack([theta[free], shift[free, 0], shift[free, 1]], axis=1).ravel()
    for _ in range(GAUSS_NEWTON_STEPS):
        r = residuals(q)
        if np.abs(r[:2 * m]).max(initial=0.0) <= 1e-5 * HINGE_WEIGHT * moved:
            break
        J = jacobian(q)
        q = q - spsolve((J.T @ J).tocsc(), J.T @ r)
    return unpack(q)


def _rotations(t: np.ndarray) -> np.ndarray:
    """(n, 2, 2) the rotation matrices of the angles ``t``."""
    cs, sn = np.cos(t), np.sin(t)
    return np.stack([np.stack([cs, -sn], axis=1), np.stack([sn, cs], axis=1)], axis=1)


def _draw_mechanism(ax: Any, scene: Scene, result: Any, centroids: np.ndarray, size: float,
                    displacement_scale: float | None, lo: np.ndarray, hi: np.ndarray,
                    extra: list[Any]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The displaced blocks, their joints' marks and the legend rows: the bounds drawn
    and the blocks' displaced centroids (where their ids go)."""
    from matplotlib.collections import LineCollection, PolyCollection

    mech = result.mechanism
    vel = np.asarray(mech.velocities, dtype=float)
    # largest displacement of any vertex per unit s (small-rotation estimate)
    reach = np.zeros(len(scene.blocks))
    for i, (b, c, (u, v, w)) in enumerate(zip(scene.blocks, centroids, vel, strict=True)):
        r = np.linalg.norm(b.points - c, axis=1).max()
        reach[i] = math.hypot(u, v) + abs(w) * r
    top = float(reach.max(initial=0.0))
    s = displacement_scale if displacement_scale is not None else (
        DISPLACEMENT_FRACTION * size / top if top > 0 else 0.0)
    moved = displaced_polygons(scene, vel, s, centroids, contacts=result.contacts)
    free = ~scene.support_mask
    # the blocks the answer's text counts as moving (:func:`~rigidblocks.answer.rigid_bodies`)
    from ..answer import rigid_bodies

    moving = np.zeros_like(free)
    moving[[i for body in rigid_bodies(result) for i in body]] = True
    pc = PolyCollection([moved[i] for i in np.flatnonzero(free)], closed=True,
                        facecolors=[MOVING_COLOUR if moving[i] else FREE_COLOUR
                                    for i in np.flatnonzero(free)], edgecolors="k",
                        linewidths=0.8 if len(moved) < 500 else 0.2, zorder=2)
    pc.set_gid("rb-displaced")
    # a legend row per colour (a collection's swatch shows its first block's colour)
    pc.set_label("_collapse mechanism")
    ax.add_collection(pc)
    from matplotlib.patches import Patch

    if moving.any():
        extra.append(Patch(facecolor=MOVING_COLOUR, edgecolor="k",
                           label="moving block (displaced)"))
    if (free & ~moving).any():
        extra.append(Patch(facecolor=FREE_COLOUR, edgecolor="k",
                           label="block at rest in the mechanism"))
    c = result.contacts
    first = c.points[c.joint_start[:-1]]
    last = c.points[c.joint_start[1:] - 1]
    marks = marked_joints(result)
    hinge = marks["hinge"]
    if len(hinge):
        op = np.asarray(mech.opening)
        pick = np.where(op[c.joint_start[hinge]] <= op[c.joint_start[hinge + 1] - 1],
                        c.joint_start[hinge], c.joint_start[hinge + 1] - 1)
        hp = c.points[pick]
        sc = ax.scatter(hp[:, 0], hp[:, 1], s=40 if len(hinge) <= MANY_MARKS else 8,
                        c=HINGE_COLOUR, marker="o", zorder=5, label="hinge")
        sc.set_gid("rb-hinges")
    slide = marks["slide"]
    if len(slide) > MANY_MARKS:  # many: the sliding joints themselves, drawn in blue
        lc = LineCollection(np.stack([first[slide], last[slide]], axis=1),
                            colors=SLIDE_COLOUR, linewidths=1.5, zorder=4,
                            label="sliding joint")
        lc.set_gid("rb-sliding")
        ax.add_collection(lc)
    elif len(slide):
        mid = 0.5 * (first[slide] + last[slide])
        sc = ax.scatter(mid[:, 0], mid[:, 1], s=60, c=SLIDE_COLOUR, marker="D", zorder=5,
                        label="sliding joint")
        sc.set_gid("rb-sliding")
    opn = marks["open"]
    if len(opn):
        lc = LineCollection(np.stack([first[opn], last[opn]], axis=1), colors=OPEN_COLOUR,
                            linewidths=3.0, zorder=4, label="opening joint")
        lc.set_gid("rb-open")
        ax.add_collection(lc)
    if len(marks["left_out"]):
        extra.append(line_handle("none", f"{len(marks['left_out'])} joint(s) moving "
                                 "< 5 % of the largest: not marked"))
    allm = np.concatenate(moved)
    at = displaced_polygons(scene, vel, s, centroids, [c[None, :] for c in centroids],
                            contacts=result.contacts)
    return (np.minimum(lo, allm.min(axis=0)), np.maximum(hi, allm.max(axis=0)),
            np.array([a[0] for a in at]))


def save_figure(ax: Any, path: Any) -> None:
    """Save the Axes' figure (format from the file extension: png, svg, pdf); SVG text
    stays text (``svg.fonttype = 'none'``), so it can be searched and edited."""
    import warnings

    import matplotlib

    with matplotlib.rc_context({"svg.fonttype": "none"}), warnings.catch_warnings():
        # a 3D Axes with its legend below: matplotlib's layout engine gives up and says
        # so with a warning naming this file, while the tight bounding box frames the
        # picture all the same (`plot` of a wall3d printed it to the terminal)
        warnings.filterwarnings("ignore", message="constrained_layout not applied")
        ax.figure.savefig(path, dpi=150, bbox_inches="tight")


__all__ = ["MAX_ARROWS", "displaced_polygons", "plot", "save_figure"]
