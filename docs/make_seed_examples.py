"""Write the bundled example scenes (examples/*.json) and docs/seed-examples.md.

Run from the repository root: ``python docs/make_seed_examples.py``. Every number in
the generated page is computed here, by the convex path and (when
:mod:`rigidblocks.solvers.distortion` is available) by the impressed-distortion solver.
``python docs/make_seed_examples.py --ratio-only`` recomputes only the flat arch's ratio
of 23 (section and docs/flat_arch_ratio.png), e.g. after a change of the non-associative
algorithm.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any, NamedTuple

from rigidblocks import check, min_friction
from rigidblocks.generators import available, build
from rigidblocks.io import write_scene

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"

#: file name -> (generator, parameters)
EXAMPLE_FILES: dict[str, tuple[str, dict[str, Any]]] = {
    "arch.json": ("arch", {}),
    "reference.json": ("reference", {}),
    "reference_self_weight.json": ("reference", {"self_weight": True}),
    "fig4a_bonded.json": ("reference", {"friction": 0.5, "bond_tensile_strength": 400.0,
                                        "bond_cohesion": 400.0}),
    "flat_arch_vertical.json": ("flat_arch", {"joints": "vertical"}),
    "flat_arch_radial.json": ("flat_arch", {"joints": "radial"}),
    "stocky_arch.json": ("stocky_arch", {}),
    "corbel_arch_horizontal.json": ("corbel_arch", {"pattern": "horizontal"}),
    "corbel_arch_inclined.json": ("corbel_arch", {"pattern": "inclined"}),
    "arpino_gate.json": ("arpino_gate", {}),
    "pointed_arch.json": ("arch", {"shape": "pointed", "voussoirs": 16}),
    "segmental_arch.json": ("arch", {"shape": "segmental", "springing": "piers"}),
    "wall.json": ("wall", {"courses": 4, "blocks_per_course": 4}),
}


#: which method is the seed's (the readings section)
WHICH_METHOD = (
    "Which method is the seed's: `--method distortion` is the distortion iteration of "
    "its Eq. 1-4. With the associative law (the default flow) it computes the convex "
    "path's state by another algorithm, a cross-check of the convex path; with "
    "`--flow non-associative` (shear links capped at f N, normal links unchanged: Eq. 4) "
    "it is the seed's procedure, the last column of the table below.")

#: the seed's Fig. 4b-c load path on examples/fig4a_bonded.json (docs/methods.md)
FIG4_PATH = (
    "The seed's test on this model (Fig. 4b-c: the vertical joint cracks when the pull "
    "overcomes its tensile strength, then the horizontal joints plasticise and the "
    "structure fails) is `rigidblocks path examples/fig4a_bonded.json`: the vertical "
    "joint bonded by a tensile strength and a cohesion of 400 N/m^2 (5 N per link), "
    "f = 0.5. It prints the crack of left-right at lambda = 0.4 (pull 20 N), the four "
    "horizontal joints at their threshold at lambda = 1 (pull 50 N = f P) and the "
    "collapse there; `--sliding coulomb` (the shear drops to zero after a slip, Fig. 2a) "
    "and `--flow non-associative` give the same sequence and loads on this model, "
    "tests/test_load_path.py. Without cohesion a tensile strength gives the joint no net "
    "tension (the shear row |T| <= f (N1 + N2) + c keeps N1 + N2 >= 0): docs/methods.md.")


def write_examples() -> list[str]:
    EXAMPLES.mkdir(exist_ok=True)
    gens = available()
    written = []
    for fname, (gen, params) in EXAMPLE_FILES.items():
        if gen not in gens:
            continue
        write_scene(build(gen, **params), EXAMPLES / fname)
        written.append(fname)
    return written


def _has_distortion() -> bool:
    try:
        import rigidblocks.solvers.distortion  # noqa: F401
    except ImportError:
        return False
    return True


DISTORTION = _has_distortion()


def friction(gen: str, load_factor: float = 0.0, both: bool = True,
             **params: Any) -> dict[str, Any]:
    """Minimum friction by both methods (``both``) or the convex path only."""
    scene = build(gen, **params)
    out: dict[str, Any] = {}
    # (to TABLE_RTOL, as the readings table: at the default 2e-3 the two tables gave
    # 0.4714 and 0.4719 for the same f*)
    r = min_friction(scene, load_factor=load_factor, state=False, rtol=TABLE_RTOL)
    out["convex"] = r
    out["distortion"] = None
    if DISTORTION and both:
        try:
            out["distortion"] = min_friction(scene, load_factor=load_factor,
                                             method="distortion", state=False,
                                             rtol=TABLE_RTOL)
        except Exception as err:  # noqa: BLE001 - reported as n/a in the table
            print(f"distortion failed on {gen} {params}: {err}", file=sys.stderr)
    if out["distortion"] is not None:
        _SEEN.append((gen, params, r, out["distortion"]))
    return out


def fmt(r) -> str:
    if r is None:
        return "n/a"
    if r.status == "undecided":
        lo, hi = r.lower, r.upper
        return "undecided" + (f" [{lo:.4g}, {hi:.4g}]" if lo is not None and hi is not None
                              else "")
    if r.status != "stable":
        return "unstable"
    return f"{r.friction_factor:.4f} ({r.friction_angle_deg:.2f} deg)"


def deg(r) -> float:
    return r.friction_angle_deg if (r is not None and r.status == "stable") else math.nan


def gov(r) -> str:
    if r is None or r.status != "stable" or not r.governing_joints:
        return "-"
    return ", ".join(f"{a}-{b}" for a, b in r.governing_joints[:4]) + (
        " ..." if len(r.governing_joints) > 4 else "")


def ratio(a: float, b: float) -> str:
    if not (math.isfinite(a) and math.isfinite(b)):
        return "n/a"
    if b <= 1e-6:
        return "inf (radial needs no friction)"
    return f"{a / b:.2f}"


_SEEN: list[tuple[str, dict, Any, Any]] = []


def _disagreements() -> str:
    bad = [(g, p, a, b) for g, p, a, b in _SEEN if b is not None and a.status == "stable"
           and (b.status != "stable" or abs(a.friction_factor - b.friction_factor)
                > 1e-3 * max(1.0, a.friction_factor))]
    if not bad:
        return ("The two methods agree on the associative f* of every case above that "
                "both computed (to 1e-3); the non-associative answers are compared in the "
                "table of what the seed computes (the first of docs/seed-examples.md), "
                "where the distortion iteration leaves one undecided (the note beneath "
                "it).")
    rows = "; ".join(f"{g} {p}: convex {fmt(a)}, distortion {fmt(b)}" for g, p, a, b in bad)
    return ("Where the methods differ the convex path's value is the optimum of a convex "
            "problem (an admissible state exists at it, none below), while the "
            f"distortion iteration can stop above it: {rows}.")


#: one table: header cells and rows of cells
Table = tuple[list[str], list[list[str]]]
#: joint inclinations (deg) of the corbel arch and Arpino gate sweeps
INCLINATIONS = (0.0, 5.0, 10.0, 15.0)


def markdown(table: Table) -> list[str]:
    """The lines of a markdown table."""
    header, rows = table
    return (["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
            + ["| " + " | ".join(r) + " |" for r in rows])


def reference_table(both: bool = True) -> tuple[Table, dict[str, Any]]:
    """Seed Fig. 4a: the reference model without and with self-weight; the table and
    the two :func:`friction` answers (keys ``no self-weight``, ``self-weight``)."""
    a = friction("reference", load_factor=1.0, both=both)
    b = friction("reference", load_factor=1.0, both=both, self_weight=True)
    header = ["case", "seed", "by hand", "convex path", "distortion", "scene"]
    rows = [["no self-weight", "0.5 (26.56 deg)", "0.5 (26.57 deg)", fmt(a["convex"]),
             fmt(a["distortion"]), "`examples/reference.json`"],
            ["self-weight", "0.25 (14.03 deg)", "0.25 (14.04 deg)", fmt(b["convex"]),
             fmt(b["distortion"]), "`examples/reference_self_weight.json`"]]
    return (header, rows), {"no self-weight": a, "self-weight": b}


def flat_arch_table(both: bool = True) -> tuple[Table, dict[str, Any]]:
    """Seed Fig. 6: the flat arch with vertical and radial joints; the table and the two
    :func:`friction` answers (keys ``vertical``, ``radial``)."""
    v = friction("flat_arch", both=both, joints="vertical")
    r = friction("flat_arch", both=both, joints="radial")
    header = ["joints", "seed", "convex path", "distortion", "governing joints", "scene"]
    rows = [["vertical", "phi_v", fmt(v["convex"]), fmt(v["distortion"]), gov(v["convex"]),
             "`examples/flat_arch_vertical.json`"],
            ["radial, c = 1.5 m", "phi_v / 23", fmt(r["convex"]), fmt(r["distortion"]),
             gov(r["convex"]), "`examples/flat_arch_radial.json`"]]
    return (header, rows), {"vertical": v, "radial": r}


def flat_arch_sweep(vertical: Any,
                    centre_depths: Sequence[float] = (0.5, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0,
                                                      10.0, 20.0)) -> Table:
    """Radial joints converging at each centre depth c, on free and bonded piers, against
    the vertical joints (``vertical``: the convex path's answer on free piers)."""
    header = ["c (m)", "skewback angle from vertical (deg)", "phi radial, free piers",
              "ratio", "phi radial, bonded piers", "phi vertical, bonded piers", "ratio"]
    vb = friction("flat_arch", both=False, joints="vertical", bonded_piers=True)["convex"]
    rows = []
    for c in centre_depths:
        rf = friction("flat_arch", both=False, centre_depth=c)["convex"]
        rb = friction("flat_arch", both=False, centre_depth=c, bonded_piers=True)["convex"]
        rows.append([f"{c:g}", f"{math.degrees(math.atan(1.0 / c)):.1f}", f"{deg(rf):.2f}",
                     ratio(deg(vertical), deg(rf)), f"{deg(rb):.2f}", f"{deg(vb):.2f}",
                     ratio(deg(vb), deg(rb))])
    return header, rows


# -- the seed's ratio of 23 on the flat arch -------------------------------------------
#: the seed's ratio of friction angles, vertical over radial joints (Fig. 6)
SEED_RATIO = 23.0
#: the readings of the seed's "friction needed" (section "What the seed computes")
RATIO_READINGS = ("static", "demand", "non-associative")
#: support conditions of the flat arch: label -> generator parameters
SUPPORTS: dict[str, dict[str, Any]] = {
    "free piers": {}, "bonded piers": {"bonded_piers": True},
    "fixed abutments": {"springing": "abutments"}}
#: centre depths c (m) of the radial joints swept: 0.1 to 50 m, ratio 1.04 between steps
RATIO_DEPTHS: tuple[float, ...] = tuple(
    round(0.1 * (500.0 ** (i / 160)), 6) for i in range(161))
#: width of the interval of c (m) to which a crossing of 23 is located
RATIO_TOL = 1e-3
#: relative accuracy asked of each friction value in the ratio sweeps
RATIO_RTOL = 1e-5
#: the chart of the ratio against c, next to the page, and the ratio drawn at its top
RATIO_CHART = "flat_arch_ratio.png"
RATIO_CAP = 300.0

#: a friction angle as a bracket (lower, upper) in degrees; None: no bracket
Angle = tuple[float, float] | None


def angle(reading: str, **params: Any) -> Angle:
    """The friction angle (deg) that ``reading`` gives the flat arch
    ``build("flat_arch", **params)`` under self-weight, as a bracket: the static f*
    and the non-associative friction to :data:`RATIO_RTOL` (the ends of their search),
    the least-energy state's demand exactly (one solve). None when no bracket."""
    scene = build("flat_arch", **params)
    if reading == "demand":
        d = check(scene, friction="infinite", load_factor=0.0).friction_demand
        if d is None:
            return None
        a = math.degrees(math.atan(d[0]))
        return a, a
    flow = "non-associative" if reading == "non-associative" else None
    try:
        r = min_friction(scene, load_factor=0.0, state=False, rtol=RATIO_RTOL, flow=flow)
    except Exception as err:  # noqa: BLE001 - reported as a gap in the sweep
        print(f"{reading} failed on flat_arch {params}: {err}", file=sys.stderr)
        return None
    if r.lower is None or r.upper is None:
        return None
    return math.degrees(math.atan(r.lower)), math.degrees(math.atan(r.upper))


def decided(a: Angle) -> bool:
    """A bracket narrow enough to stand for a value (relative width 1e-3 at most; an
    undecided search leaves a wider one)."""
    return a is not None and a[1] - a[0] <= 1e-3 * a[1] + 1e-9


def _mid(a: Angle) -> float:
    """The bracket's midpoint, nan when not :func:`decided`."""
    return 0.5 * (a[0] + a[1]) if decided(a) else math.nan


def side(radial: Angle, target: tuple[float, float]) -> int | None:
    """+1 if phi_vertical / phi_radial is above 23 for every value in the brackets
    (``target`` = phi_vertical / 23), -1 if below, None if the brackets overlap."""
    if radial is None:
        return None
    if radial[1] < target[0]:
        return 1
    if radial[0] > target[1]:
        return -1
    return None


class Crossing(NamedTuple):
    """Where the ratio passes 23 between centre depths ``a`` and ``b`` (m): the side of
    23 at each (+1 above, -1 below; ``sb`` None: the bisection met a value it could
    not place, at ``b``) and the radial angle brackets there."""

    a: float
    b: float
    sa: int
    sb: int | None
    phi_a: Angle
    phi_b: Angle


class RatioSweep(NamedTuple):
    """One reading on one support: the vertical joints' angle, the radial joints' angle
    at each depth, and the located crossings of 23."""

    reading: str
    support: str
    vertical: Angle
    depths: tuple[float, ...]
    radial: list[Angle]
    crossings: list[Crossing]

    @property
    def target(self) -> tuple[float, float] | None:
        v = self.vertical
        return None if v is None or v[0] <= 0.0 else (v[0] / SEED_RATIO, v[1] / SEED_RATIO)

    def ratios(self) -> list[float]:
        """phi_vertical / phi_radial at each depth (bracket midpoints; inf where the
        radial joints need no friction, nan where undecided)."""
        v = _mid(self.vertical)
        return [math.inf if decided(r) and r[1] <= 1e-9 else v / _mid(r)
                for r in self.radial]


def locate(reading: str, params: dict[str, Any], target: tuple[float, float],
           a: float, sa: int, b: float, tol: float = RATIO_TOL) -> Crossing:
    """Bisect c between ``a`` (side ``sa``) and ``b`` (the other side) to ``tol``."""
    phi_a = phi_b = None
    while b - a > tol:
        m = 0.5 * (a + b)
        phi = angle(reading, centre_depth=m, **params)
        s = side(phi, target)
        if s is None:
            return Crossing(a, m, sa, None, phi_a, phi)
        if s == sa:
            a, phi_a = m, phi
        else:
            b, phi_b = m, phi
    phi_a = phi_a or angle(reading, centre_depth=a, **params)
    phi_b = phi_b or angle(reading, centre_depth=b, **params)
    return Crossing(a, b, sa, -sa, phi_a, phi_b)


def _golden(fun: Any, a: float, b: float, n: int = 24) -> float:
    """The c in [a, b] at which ``fun`` is least, by golden-section search (``n`` steps:
    the interval shrinks to 0.618^n of its width; a local least value where ``fun`` is
    not unimodal)."""
    g = (math.sqrt(5.0) - 1.0) / 2.0
    x1, x2 = b - g * (b - a), a + g * (b - a)
    f1, f2 = fun(x1), fun(x2)
    for _ in range(n):
        if f1 <= f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - g * (b - a)
            f1 = fun(x1)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + g * (b - a)
            f2 = fun(x2)
    return x1 if f1 <= f2 else x2


def refine(reading: str, params: dict[str, Any], target: tuple[float, float],
           depths: list[float], radial: list[Angle]) -> tuple[list[float], list[Angle]]:
    """Look between the grid's depths for the bands a grid step can hide: at each depth
    where the radial angle is at a local extreme on the side of 23 away from it (a
    least angle with the ratio below 23, a largest with it above), search the two
    steps around it for the extreme (:func:`_golden`) and add that depth to the grid
    (the crossings are then located on either side of it if it lies across 23)."""
    mids = [_mid(r) for r in radial]
    extra = []
    for i in range(1, len(depths) - 1):
        s = side(radial[i], target)
        sign = {-1: 1.0, 1: -1.0}.get(s) if s is not None else None
        if sign is None or not all(math.isfinite(mids[j]) for j in (i - 1, i, i + 1)):
            continue
        here, around = sign * mids[i], (sign * mids[i - 1], sign * mids[i + 1])
        if here > min(around) or here == max(around):
            continue
        c = _golden(lambda x, k=sign: k * _mid(angle(reading, centre_depth=x, **params)),
                    depths[i - 1], depths[i + 1])
        extra.append((c, angle(reading, centre_depth=c, **params)))
    pairs = sorted([*zip(depths, radial, strict=True), *extra], key=lambda p: p[0])
    return [c for c, _ in pairs], [r for _, r in pairs]


def ratio_sweep(reading: str, support: str,
                depths: Sequence[float] = RATIO_DEPTHS) -> RatioSweep:
    """The ratio phi_vertical / phi_radial of friction ANGLES for one reading and
    support over the centre depths, with every crossing of 23 between two depths of
    the grid located by bisection (a band narrower than the grid's step can be missed
    where the ratio enters and leaves it between two depths)."""
    params = SUPPORTS[support]
    vertical = angle(reading, joints="vertical", **params)
    radial = [angle(reading, centre_depth=c, **params) for c in depths]
    sweep = RatioSweep(reading, support, vertical, tuple(depths), radial, [])
    target = sweep.target
    if target is None:
        return sweep
    depths, radial = refine(reading, params, target, list(depths), radial)
    sweep = RatioSweep(reading, support, vertical, tuple(depths), radial, [])
    last = None  # (depth, side) of the last depth placed
    for c, phi in zip(depths, radial, strict=True):
        s = side(phi, target)
        if s is None:
            continue
        if last is not None and s != last[1]:
            sweep.crossings.append(locate(reading, params, target, last[0], last[1], c))
        last = (c, s)
    return sweep


def ratio_sweeps(readings: Sequence[str] = RATIO_READINGS,
                 depths: Sequence[float] = RATIO_DEPTHS) -> list[RatioSweep]:
    """:func:`ratio_sweep` for each reading and every support."""
    return [ratio_sweep(r, s, depths) for r in readings for s in SUPPORTS]


def nonassociative_ratio_sweeps(depths: Sequence[float] = RATIO_DEPTHS) -> list[RatioSweep]:
    """The non-associative reading alone (the expensive one), on every support."""
    return ratio_sweeps(("non-associative",), depths)




def _crossing(x: Crossing) -> str:
    if x.sb is None:
        return (f"between {x.a:.4f} and {x.b:.4f} (undecided at {x.b:.4f}: "
                f"phi_r {_mid(x.phi_b):.3f} deg)")
    return (f"{0.5 * (x.a + x.b):.4f} (phi_r {_mid(x.phi_a):.3f} -> "
            f"{_mid(x.phi_b):.3f} deg)")


def bands(s: RatioSweep) -> list[tuple[float, float]]:
    """The intervals of c where the ratio is at least 23 (ends at the crossings'
    midpoints, or at the sweep's ends)."""
    target = s.target
    if target is None:
        return []
    sides = [side(r, target) for r in s.radial]
    placed = [(c, x) for c, x in zip(s.depths, sides, strict=True) if x is not None]
    if not placed:
        return []
    out, start = [], s.depths[0] if placed[0][1] == 1 else None
    for x in s.crossings:
        c = 0.5 * (x.a + x.b)
        if x.sa == -1:
            start = c
        elif start is not None:
            out.append((start, c))
            start = None
    if start is not None:
        out.append((start, s.depths[-1]))
    return out


def _largest(s: RatioSweep) -> str:
    finite = [(q, c) for q, c in zip(s.ratios(), s.depths, strict=True)
              if math.isfinite(q)]
    if not finite:
        return "-"
    q, c = max(finite)
    return f"{q:.2f} at c = {c:g}"


def _end(s: RatioSweep, c: float) -> str:
    return f"{c:g} (end of the sweep)" if c in (s.depths[0], s.depths[-1]) else f"{c:.4f}"


def ratio_row(s: RatioSweep) -> list[str]:
    v = s.vertical
    if s.target is None:
        return [s.reading, s.support, "0 (undefined ratio)" if v else "n/a", "-",
                "none: phi vertical is 0, the ratio is not defined", "-"]
    b = bands(s)
    where = ", ".join(f"{_end(s, lo)} to {_end(s, hi)}" for lo, hi in b)
    crossings = "; ".join(_crossing(x) for x in s.crossings) or "none"
    gaps = [(c, side(r, s.target)) for c, r in zip(s.depths, s.radial, strict=True)
            if not decided(r)]
    if gaps:
        crossings += ("; phi_r undecided at c = " + ", ".join(f"{c:g}" for c, _ in gaps)
                      + ", " + ("each bracket on one side of 23" if all(
                          x is not None for _, x in gaps) else "not all placed"))
    return [s.reading, s.support, f"{_mid(v):.3f}", f"{_mid(s.target):.4f}", crossings,
            where or f"never (largest ratio {_largest(s)})"]


def ratio_table(sweeps: Sequence[RatioSweep]) -> Table:
    header = ["reading", "support", "phi vertical (deg)", "phi vertical / 23 (deg)",
              "ratio crosses 23 at c (m)", "ratio >= 23 for c (m)"]
    return header, [ratio_row(s) for s in sweeps]


def ratio_chart(sweeps: Sequence[RatioSweep], path: Path, cap: float = RATIO_CAP) -> None:
    """phi_vertical / phi_radial against c, one panel per support, one line per
    reading, the seed's 23 dashed; ratios above ``cap`` (or infinite) drawn at it."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    supports = list(dict.fromkeys(s.support for s in sweeps))
    fig, axes = plt.subplots(1, len(supports), figsize=(5 * len(supports), 4.2),
                             sharey=True, squeeze=False)
    for ax, sup in zip(axes[0], supports, strict=True):
        for s in (s for s in sweeps if s.support == sup):
            if s.target is None:
                continue
            q = [min(x, cap) for x in s.ratios()]
            ax.plot(s.depths, q, label=s.reading, lw=1.2,
                    color=f"C{RATIO_READINGS.index(s.reading)}")
        ax.axhline(SEED_RATIO, color="k", ls="--", lw=0.8)
        ax.set(xscale="log", yscale="log", ylim=(0.8, cap * 1.2),
               xlabel="centre depth c of the radial joints (m)", title=sup)
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=8)
    axes[0][0].set_ylabel("phi vertical / phi radial (angles)")
    fig.suptitle(f"flat arch: ratio of friction angles (dashed: the seed's 23; "
                 f"at the top: {cap:g} or more, or no friction needed)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


#: the heading of the ratio section, where --ratio-only splices the page
RATIO_HEADING = "### Where the seed's ratio of 23 falls"


def ratio_section(sweeps: Sequence[RatioSweep]) -> list[str]:
    """The page's section on the ratio of 23: how it is computed, the table, the chart
    (written next to the page)."""
    d = RATIO_DEPTHS
    L = [RATIO_HEADING, "",
         "The ratio phi_vertical / phi_radial of friction ANGLES (degrees, as everywhere "
         "on this page), for each reading of the seed's friction (section \"What the seed "
         "computes\") on each support: free piers, bonded piers (`bonded_piers`: the "
         "piers never slide on the ground) and fixed abutments (`springing abutments`). "
         "phi_vertical is the same reading on the vertical-joint platband on the same "
         f"support; phi_radial is computed at {len(d)} centre depths c from {d[0]:g} m to "
         f"{d[-1]:g} m (skewbacks {math.degrees(math.atan(1 / d[0])):.1f} to "
         f"{math.degrees(math.atan(1 / d[-1])):.1f} deg from the vertical, steps of "
         f"{100 * (d[1] / d[0] - 1):.0f} %), the static f* and the non-associative f each "
         f"to a relative {RATIO_RTOL:g}, the demand in one solve. Where the ratio passes "
         f"23 between two depths, c is bisected to {RATIO_TOL:g} m; a crossing is the "
         "midpoint of the last interval, with phi_radial at its two ends (a jump between "
         "them is a change of mechanism). A depth is placed on one side of 23 only when "
         "the brackets of both angles are; around each local extreme of phi_radial on "
         "the grid a golden-section search looks for a band narrower than a step. The "
         "ratio is infinite where the radial joints need no friction, so a band includes "
         "those depths. The demand is the same on free and bonded piers: with no friction "
         "limit no joint slides, so the bond changes nothing.",
         ""]
    L.extend(markdown(ratio_table(sweeps)))
    L += ["", f"![ratio against c]({RATIO_CHART})", "",
          "A gap in a curve is a depth where that value is undecided (listed in the "
          f"table); a ratio of {RATIO_CAP:g} or more, or an infinite one, is drawn at "
          f"{RATIO_CAP:g}.", ""]
    return L


def update_ratio_section(readings: Sequence[str] = RATIO_READINGS) -> float:
    """Recompute the ratio sweeps and splice their section and chart into the existing
    page (``--ratio-only``: after a change of the non-associative algorithm, without
    the rest of the page); the CPU seconds the sweeps took."""
    path = ROOT / "docs" / "seed-examples.md"
    text = path.read_text()
    start = text.index(RATIO_HEADING)
    end = text.find("\n## ", start)
    t0 = time.process_time()
    sweeps = [s for r in readings for s in (
        nonassociative_ratio_sweeps() if r == "non-associative" else ratio_sweeps((r,)))]
    cpu = time.process_time() - t0
    ratio_chart(sweeps, ROOT / "docs" / RATIO_CHART)
    path.write_text(text[:start] + "\n".join(ratio_section(sweeps)).rstrip("\n")
                    + "\n" + text[end:])
    return cpu


def seven_table(both: bool = True) -> Table:
    """Seed Fig. 7: the stocky arch and the corbel arches."""
    header = ["structure", "seed", "convex path", "distortion", "governing joints", "scene"]
    rows = []
    for label, gen, params, fname in (
            ("stocky arch (7a)", "stocky_arch", {}, "stocky_arch.json"),
            ("corbel arch, horizontal joints (7b)", "corbel_arch",
             {"pattern": "horizontal"}, "corbel_arch_horizontal.json"),
            ("corbel arch, inclined joints (7c)", "corbel_arch", {"pattern": "inclined"},
             "corbel_arch_inclined.json")):
        x = friction(gen, both=both, **params)
        rows.append([label, "friction governs (no value given)", fmt(x["convex"]),
                     fmt(x["distortion"]), gov(x["convex"]), f"`examples/{fname}`"])
    return header, rows


def corbel_sweep(block_lengths: Sequence[float] = (0.45, 0.6, 0.8, 1.0),
                 inclinations: Sequence[float] = INCLINATIONS) -> Table:
    """Corbel arch: required friction angle (deg, convex path) against block length
    (rows) and bed-joint inclination (columns)."""
    header = ["block length (m)"] + [f"{b:g} deg" for b in inclinations]
    rows = []
    for bl in block_lengths:
        cells = [f"{bl:g}"]
        for b in inclinations:
            p = {"pattern": "inclined", "inclination": b} if b else {}
            x = friction("corbel_arch", both=False, block_length=bl, **p)["convex"]
            cells.append(f"{deg(x):.2f}")
        rows.append(cells)
    return header, rows


def arpino_table(both: bool = True) -> Table:
    """Seed Fig. 8: the Arpino gate with the generator's defaults."""
    x = friction("arpino_gate", both=both)
    header = ["case", "seed", "convex path", "distortion", "governing joints", "scene"]
    rows = [["default (wall 0.4 m, joints 5 deg)", "0.40 (21.80 deg)", fmt(x["convex"]),
             fmt(x["distortion"]), gov(x["convex"]), "`examples/arpino_gate.json`"]]
    return header, rows


def arpino_sweep(walls: Sequence[float] = (0.2, 0.3, 0.4, 0.6, 1.0),
                 inclinations: Sequence[float] = INCLINATIONS) -> Table:
    """Arpino gate: required friction angle (deg, convex path) against wall thickness
    (rows) and bed-joint inclination towards the inside (columns)."""
    header = ["wall (m)"] + [f"{b:g} deg" for b in inclinations]
    rows = []
    for wall in walls:
        rows.append([f"{wall:g}"] + [f"{deg(x['convex']):.2f}" for x in (
            friction("arpino_gate", both=False, wall=wall, joint_inclination=b)
            for b in inclinations)])
    return header, rows


#: the distortion iteration's tolerance tried where its default leaves an answer undecided
TIGHT_DISTORTION = 1e-10


#: the accuracy of the readings table's friction values (the static f* a lower bound of the
#: others: at the default 2e-3 its bracket's upper end, 0.2985 for the stocky arch, read
#: above the non-associative 0.2982; at 1e-6 the Arpino gate's is undecided, its bracket
#: 1.4e-6 wide)
TABLE_RTOL = 1e-5


def _na_friction(scene: Any, load_factor: float, method: str, **kw: Any) -> Any:
    try:
        return min_friction(scene, load_factor=load_factor, method=method, state=False,
                            flow="non-associative", **kw)
    except Exception as err:  # noqa: BLE001 - reported as n/a in the table
        print(f"non-associative {method} failed on {scene.name}: {err}", file=sys.stderr)
        return None


def readings(gen: str, load_factor: float = 0.0, **params: Any) -> dict[str, Any]:
    """The three quantities that may stand for the seed's "friction needed": the static
    f* (a lower bound on any state's need), the friction demand of the least-energy
    state with no-tension links only (infinite friction: the state the seed's procedure
    computes before any shear link yields), and the non-associative friction (the
    smallest f at which the state reached from X0 stands) by both algorithms."""
    scene = build(gen, **params)
    static = min_friction(scene, load_factor=load_factor, state=False, rtol=TABLE_RTOL)
    demand = check(scene, friction="infinite", load_factor=load_factor)
    out = {"static": static, "demand": demand,
           "na_convex": _na_friction(scene, load_factor, "clarabel", rtol=TABLE_RTOL),
           "na_distortion": _na_friction(scene, load_factor, "distortion", rtol=TABLE_RTOL)
           if DISTORTION else None}
    d = out["na_distortion"]
    if d is not None and d.friction_factor is None:
        out["na_distortion_tight"] = _na_friction(
            scene, load_factor, "distortion", settings={"tol": TIGHT_DISTORTION},
            rtol=TABLE_RTOL)
        # what `rigidblocks friction --flow non-associative --method distortion` gives
        out["na_distortion_default"] = _na_friction(scene, load_factor, "distortion")
    return out


def fmt_demand(c: Any) -> str:
    if c is None or c.friction_demand is None:
        return "n/a"
    f, k = c.friction_demand
    if not math.isfinite(f):
        return "infinite"
    a, b = c.joint_name(k)
    return f"{f:.4f} ({math.degrees(math.atan(f)):.2f} deg) at {a}-{b}"


#: the cases of the readings table: label, seed's value, generator, load factor, params
READINGS: tuple[tuple[str, str, str, float, dict[str, Any]], ...] = (
    ("reference, no self-weight (4a)", "0.5 (26.56 deg)", "reference", 1.0, {}),
    ("reference, self-weight (4a)", "0.25 (14.03 deg)", "reference", 1.0,
     {"self_weight": True}),
    ("flat arch, vertical joints, piers (6a)", "phi_v", "flat_arch", 0.0,
     {"joints": "vertical"}),
    ("flat arch, radial joints, piers (6b)", "phi_v / 23", "flat_arch", 0.0,
     {"joints": "radial"}),
    ("flat arch, vertical joints, fixed abutments (6a)", "phi_v", "flat_arch", 0.0,
     {"joints": "vertical", "springing": "abutments"}),
    ("flat arch, radial joints, fixed abutments (6b)", "phi_v / 23", "flat_arch", 0.0,
     {"joints": "radial", "springing": "abutments"}),
    ("stocky arch (7a)", "-", "stocky_arch", 0.0, {}),
    ("corbel arch, horizontal joints (7b)", "-", "corbel_arch", 0.0,
     {"pattern": "horizontal"}),
    ("corbel arch, inclined joints (7c)", "-", "corbel_arch", 0.0, {"pattern": "inclined"}),
    ("Arpino gate, default 3.6 m high (8)", "0.40 (21.80 deg)", "arpino_gate", 0.0, {}),
    ("Arpino gate, 4.2 m high (8)", "0.40 (21.80 deg)", "arpino_gate", 0.0,
     {"height": 4.2}),
)


def readings_table() -> tuple[Table, dict[str, dict[str, Any]]]:
    header = ["structure", "seed", "static f* (lower bound)",
              "demand of the least-energy state", "non-associative f (convex)",
              "non-associative f (distortion)"]
    rows, got = [], {}
    for label, seed, gen, lf, params in READINGS:
        r = readings(gen, lf, **params)
        got[label] = r
        rows.append([label, seed, fmt(r["static"]), fmt_demand(r["demand"]),
                     fmt(r["na_convex"]), fmt(r["na_distortion"])])
    return (header, rows), got


def demand_weight(target: float = 0.25) -> float:
    """The unit weight (N/m^3) at which the reference model's least-energy state needs
    ``target`` (bisection; the demand falls as the blocks get heavier)."""
    lo, hi = 1.0e3, 1.0e6
    for _ in range(60):
        mid = math.sqrt(lo * hi)
        d = check(build("reference", self_weight=True, unit_weight=mid),
                  friction="infinite", load_factor=1.0).friction_demand[0]
        lo, hi = (mid, hi) if d > target else (lo, mid)
    return math.sqrt(lo * hi)


def _ratio_deg(a: Any, b: Any) -> str:
    fa = getattr(a, "friction_demand", None)
    fb = getattr(b, "friction_demand", None)
    if fa is None or fb is None:
        return "n/a"
    return ratio(math.degrees(math.atan(fa[0])), math.degrees(math.atan(fb[0])))


def readings_section() -> list[str]:
    L: list[str] = []
    w = L.append
    w("## What the seed computes, and which of our quantities corresponds")
    w("")
    w("The seed reads its friction off the state its procedure computes: from the "
      "elastic state X0 it nullifies tensile normal links and caps the shear links at f "
      "times their normal force (Eq. 4), so a shear slip never opens a joint "
      "(non-associative sliding), and the friction it reports is what that state needs. "
      "Three of our quantities can stand for it:")
    w("")
    w("- **static f*** (`rigidblocks friction`): the smallest f for which *some* "
      "admissible state exists. Every state needs at least this much: it is a lower "
      "bound on the seed's number.")
    w("- **demand of the least-energy state** (`rigidblocks check --friction infinite "
      "--json`, key `friction_demand`): the largest |T|/N of the state of least "
      "complementary energy with no-tension links only, i.e. the state the seed's "
      "procedure reaches before any shear link yields. The seed's number if no joint "
      "slips.")
    w("- **non-associative friction** (`rigidblocks friction --flow non-associative`): "
      "the smallest f at which the state reached from X0, with shear links that slip "
      "without dilatancy, stands; this is the seed's procedure carried to its fixed "
      "point, by two algorithms (a sequence of convex problems, and the distortion "
      "iteration with separate links). Not unique in general: it is the answer reached "
      "from X0.")
    w("")
    w("static f* <= non-associative f always (no state stands below f*), and at "
      "f = demand the least-energy no-tension state is itself a fixed point of the "
      "non-associative iteration, so the non-associative f is at most the demand where "
      "the verdicts change once along f.")
    w("")
    w(WHICH_METHOD)
    w("")
    table, got = readings_table()
    L.extend(markdown(table))
    w("")
    uw = demand_weight()
    w("Reference model with self-weight: with the generator's blocks (W_top = W_central = "
      "50 N) the static f* is H / (P + W_top + W_central) = 0.25, the seed's value, but "
      "the least-energy state needs "
      f"{got[READINGS[1][0]]['demand'].friction_demand[0]:.4f}; the demand reading gives 0.25 "
      f"when the blocks are {uw / 20000.0:.3g} times as heavy (unit weight "
      f"{uw / 1000:.4g} kN/m^3 with these sizes). The seed does not give its blocks' "
      "sizes, so both readings fit a geometry; the non-associative friction equals the "
      "static f* here.")
    w("")
    v = got[READINGS[4][0]]["demand"]
    r = got[READINGS[5][0]]["demand"]
    sv = got[READINGS[4][0]]["static"]
    w("Flat arch on fixed abutments: the static f* is 0 for both joint patterns (the "
      "abutments can pinch the platband as hard as needed; for the vertical joints the "
      f"search stops at the bracket [{sv.lower:.2g}, {sv.upper:.2g}]), so the seed's "
      "finite ratio "
      "cannot be a ratio of static values there; it points at a state quantity. The "
      f"demands give a ratio of friction angles of {_ratio_deg(v, r)} (vertical over "
      "radial) with this geometry; on piers the static values give the ratio in the "
      "flat-arch section below.")
    w("")
    for label, r in got.items():
        t = r.get("na_distortion_tight")
        if t is None:
            continue
        d = r.get("na_distortion_default")
        default = (f" At the command's default accuracy (--rtol 2e-3) its bisection "
                   f"meets no such trial: {fmt(d)}, bracket [{d.bracket[0]:.6g}, "
                   f"{d.bracket[1]:.6g}]." if d is not None and d.bracket else "")
        w(f"{label}: asked to {TABLE_RTOL:g}, as the whole table, the distortion iteration "
          f"at its default tolerance (1e-9) leaves the non-associative friction "
          f"{fmt(r['na_distortion'])} (it stalls at a trial near the answer); at "
          f"tolerance {TIGHT_DISTORTION:g} it gives {fmt(t)}, the convex path "
          f"{fmt(r['na_convex'])}.{default}")
        w("")
    w("Arpino gate: the seed gives no survey; the published height of about 4.2 m is "
      "in the last row (the opening, course count and wall thickness stay the "
      "generator's defaults). Neither reading reaches the seed's 21.80 deg with these "
      "proportions; nothing was tuned to it.")
    w("")
    return L


def page() -> str:
    L: list[str] = []
    w = L.append
    w("# The seed's examples, reproduced")
    w("")
    w("Generated by `docs/make_seed_examples.py`; do not edit by hand. Every friction "
      "value is the minimum uniform Coulomb coefficient f* = tan(phi*) for which an "
      "admissible equilibrium state exists (dry joints, no tension), computed by the "
      "convex path and by the impressed-distortion solver"
      + ("" if DISTORTION else " (not available when this page was made: n/a)") + ". "
      "Except for the reference model, whose loads are the seed's, the structures are "
      "analysed under self-weight only (`--load-factor 0`; the example files carry a "
      "horizontal live body force [1, 0] for `rigidblocks load`).")
    w("")
    L.extend(readings_section())
    # -- reference model
    table, ref = reference_table()
    w("## Reference mechanical model (seed Fig. 4a)")
    w("")
    w("P = 100 N down on the top block, H = 50 N pulling each central block outwards. By "
      "hand (see `rigidblocks/generators/seed.py`): f* = H / (P + W_top + W_central), so "
      "0.5 without self-weight and 0.25 when W_top + W_central = 100 N. The seed does "
      "not publish its block sizes; the generator's defaults (central blocks "
      "0.10 x 0.10 m, top block 0.20 x 0.05 m, depth 0.25 m, 20 kN/m^3) weigh "
      "W_top = W_central = 50 N.")
    w("")
    L.extend(markdown(table))
    w("")
    w(f"Governing joints: {gov(ref['no self-weight']['convex'])}.")
    w("")
    w(FIG4_PATH)
    w("")
    # -- flat arch
    w("## Flat arch (seed Fig. 6)")
    w("")
    w("Span 2 m, depth 0.4 m, 9 voussoirs, 20 kN/m^3, on free piers 1.0 m wide and "
      "1.0 m high standing on the ground. The seed reports that radial joints need a "
      "friction angle 23 times lower than vertical joints; it does not publish the "
      "geometry (span, depth, where the radial joints converge, the abutments), and the "
      "ratio depends on all of them, so the tables show that dependence instead of "
      "one tuned number. Radial joints converge at `centre_depth` c below the intrados; "
      "the skewbacks lean by atan(span / 2c) from the vertical.")
    w("")
    table, flat = flat_arch_table()
    L.extend(markdown(table))
    w("")
    w(f"Ratio phi_vertical / phi_radial (convex path): "
      f"{ratio(deg(flat['vertical']['convex']), deg(flat['radial']['convex']))}. With "
      "free piers the piers' own "
      "sliding on the ground governs the radial case; with piers that cannot slide "
      "(`bonded_piers`) only the platband's joints count:")
    w("")
    L.extend(markdown(flat_arch_sweep(flat["vertical"]["convex"])))
    w("")
    w("Between the joint slopes that need no friction at all and the nearly vertical "
      "ones, the ratio sweeps every value from 1 to infinity; the seed's 23 lies on "
      "that range, at a joint slope its paper does not give; where, for each reading "
      "and support, is the next section.")
    w("")
    sweeps = ratio_sweeps()
    ratio_chart(sweeps, ROOT / "docs" / RATIO_CHART)
    L.extend(ratio_section(sweeps))
    # -- stocky and corbel arches
    w("## Stocky arch and corbel arches (seed Fig. 7)")
    w("")
    w("Geometry not published in the seed. Stocky arch: semicircular, mean radius "
      "1.5 m, t/R = 0.6, 7 voussoirs, on free piers. Corbel arch: opening 2 m, 6 "
      "courses 0.3 m high, blocks 0.6 m long, each course overhanging by 0.2 m, the top "
      "courses meeting at a vertical crown joint; pattern 7b horizontal bed joints, 7c "
      "bed joints dipping 10 deg towards the opening.")
    w("")
    L.extend(markdown(seven_table()))
    w("")
    w("Corbel arch: required friction angle (deg, convex path) against block length "
      "and joint inclination:")
    w("")
    L.extend(markdown(corbel_sweep()))
    w("")
    # -- Arpino
    w("## Arched gate of Arpino (seed Fig. 8)")
    w("")
    w("The seed reports a friction angle of 21.80 deg (f = 0.40) at 20 kN/m^3, with "
      "joints slightly inclined towards the inside, but not the survey of the gate. "
      "The generator builds a pointed corbelled gate, 2.4 m wide at the ground and "
      "3.6 m high at the apex, of 9 courses, with a capping course closed by a vertical "
      "crown joint; the wall thickness beyond the opening and the joint inclination are "
      "the unknown parameters swept below.")
    w("")
    L.extend(markdown(arpino_table()))
    w("")
    w("Required friction angle (deg, convex path) against wall thickness and bed-joint "
      "inclination towards the inside:")
    w("")
    L.extend(markdown(arpino_sweep()))
    w("")
    w("In a slender gate, whose two stacks lean on each other at the crown, the "
      "required friction first falls as the joints incline towards the inside (the "
      "crown thrust meets the inclined bed joints closer to their normal), then rises "
      "again once the blocks' own tendency to slide inwards down the inclined joints "
      "governs. In a thick gate each stack stands by itself and inclined joints only "
      "invite the blocks to slide inwards. None of these proportions reaches the "
      "seed's 21.80 deg: its model must differ (backing, block shapes, "
      "proportions) in ways the paper does not record, and no parameter here was "
      "tuned to that number.")
    w("")
    w(_disagreements())
    w("")
    return "\n".join(L)


def main(argv: Sequence[str] | None = None) -> int:
    args = sys.argv[1:] if argv is None else list(argv)
    if args == ["--ratio-only"]:
        cpu = update_ratio_section()
        print(f"updated the ratio section of docs/seed-examples.md and docs/{RATIO_CHART}"
              f" ({cpu:.1f} s CPU)")
        return 0
    if args:
        print(f"usage: python docs/make_seed_examples.py [--ratio-only]; got {args}",
              file=sys.stderr)
        return 2
    t = time.time()
    files = write_examples()
    text = page()
    (ROOT / "docs" / "seed-examples.md").write_text(text)
    print(f"wrote {len(files)} examples and docs/seed-examples.md in {time.time() - t:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
