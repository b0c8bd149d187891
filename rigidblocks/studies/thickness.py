"""Geometric safety: the minimum thickness of a parametric family of structures.

The thickness parameter t of a generator is bisected on the admissibility of the
structure under its dead load alone (lambda = 0), or under the dead load plus a given
multiple of its live load: an equilibrium state in compression
within the joints (and within the friction cones when friction is finite) exists for
t >= t_min and not below. Admissibility is monotone in t for the usual arch families
(a thicker ring contains every thrust line of a thinner one), which bisection requires.

Reference: for a semicircular arch of radial joints under self-weight with no sliding,
t_min / R = 0.1075 (R the mean radius), approached from below as the number of voussoirs
grows (Milankovitch 1907; Heyman, *The Stone Skeleton*, Cambridge University Press 1995;
Ochsendorf, PhD thesis, Cambridge 2002).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..analyses import bisect, check, min_friction
from ..errors import InputError
from ..results import fmt_safe
from ..scene.model import Scene, friction_label, friction_value

#: the status of a search whose lower bound stands already
AT_LOWER_BOUND = "at_lower_bound"


@dataclass(frozen=True)
class ThicknessResult:
    """The minimum thickness found by bisection.

    Attributes:
        thickness: the upper end of the final bracket (the thinnest admissible value
            found); the true minimum lies in ``[lower, thickness]``.
        lower: the largest value found inadmissible.
        param: the generator's parameter that was varied.
        n_checks: number of admissibility checks solved.
        params: the generator's other parameters.
        status: "found" (the bracket is ``rtol`` wide), "at_lower_bound" (it stands
            at ``lo``: the minimum is at most ``thickness`` = lo, ``lower`` 0), or
            "undecided" when a check could not decide (the distortion method near the
            limit): the bracket ``[lower, thickness]`` is then wider, and ``notes`` say
            where it stopped.
        load_factor, solve_time: the multiple of the live load the checks stood under,
            and the seconds they spent in the solvers.
    """

    generator: str
    param: str
    thickness: float
    lower: float
    n_checks: int
    friction: Any
    params: dict[str, Any] = field(default_factory=dict)
    status: str = "found"
    notes: tuple[str, ...] = ()
    #: the load factor of the live load the checks stood under (0: dead load only)
    load_factor: float = 0.0
    #: seconds spent in the solvers by the checks
    solve_time: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        # (why: the terminal's note lines, as every command's JSON has them)
        return {"status": self.status, "notes": list(self.notes), "why": list(self.notes),
                "generator": self.generator, "param": self.param,
                "min_thickness": self.thickness, "lower": self.lower,
                "n_checks": self.n_checks, "friction": friction_label(self.friction),
                "load_factor": self.load_factor, "solve_time": self.solve_time,
                "params": dict(self.params)}


def builds(gen: Callable[..., Scene], params: dict[str, Any], param: str, t: float) -> bool:
    """Does the family ``gen`` build with ``params`` and ``param`` = ``t``?"""
    try:
        gen(**params, **{param: t})
    except InputError:
        return False
    return True


def check_rtol(rtol: float, method: str) -> None:
    """Refuse an ``rtol`` finer than the checks of ``method`` hold, as f*'s (`friction`):
    --rtol 1e-9 printed a bracket whose two ends read alike."""
    from ..analyses.core import F_RTOL_FLOOR, SIMPLEX

    if rtol < F_RTOL_FLOOR and method != "distortion" and method not in SIMPLEX:
        raise InputError(f"min_thickness: rtol {rtol:g} is finer than an interior-point "
                         f"solver certifies its checks (their verdicts hold to 1e-9 of the "
                         f"largest force): ask for {F_RTOL_FLOOR:g} or coarser, or method "
                         "highs in 2D")


def thinner(gen: Callable[..., Scene], params: dict[str, Any], param: str, lo: float
            ) -> float | None:
    """The largest of 1/2, 1/4, ... above ``lo`` at which the family ``gen`` builds, where
    it builds at ``lo`` (else its other parameters are at fault: None)."""
    if not builds(gen, params, param, lo):
        return None
    hi = 0.5
    while hi > lo:  # (with lo = 0.6 it gave 0.5 and "got lo=0.6, hi=0.5")
        if builds(gen, params, param, hi):
            return hi
        hi /= 2
    return None


def min_thickness(generator: str | Callable[..., Scene], param: str = "thickness",
                  lo: float = 0.01, hi: float | None = None, rtol: float = 1e-4,
                  friction: Any = "infinite", method: str = "clarabel",
                  load_factor: float = 0.0, **params: Any) -> ThicknessResult:
    """Smallest value of ``param`` for which ``generator(**params)`` admits equilibrium
    under its dead load plus ``load_factor`` times its live load (0: the dead load
    alone), by bisection to a relative bracket ``rtol``.

    Args:
        generator: a registered generator name (:mod:`rigidblocks.generators`) or a
            function returning a scene.
        param: the thickness parameter (``thickness`` is t / R for :func:`arch`).
        lo, hi: the initial bracket; ``hi`` must be admissible and ``lo`` not. ``hi``
            by default is 1, or where the family is not built at 1 the largest of 1/2,
            1/4, ... above ``lo`` at which it is (a note says so).
        friction: friction coefficient for every joint without its own (default: no
            sliding), or None: the scene's own (the generator's ``friction`` parameter,
            as ``check`` reads it), which the result records.
        method: the method deciding admissibility (see :func:`rigidblocks.check`).
        load_factor: the multiple of the live load it must carry (a wall's lateral
            load; default 0, its dead load alone).

    Example:
        >>> r = min_thickness("arch", voussoirs=20, rtol=1e-3)
        >>> 0.09 < r.thickness < 0.11
        True
    """
    if isinstance(generator, str):
        from ..generators import get

        gen: Callable[..., Scene] = get(generator)
        name = generator
    else:
        gen, name = generator, getattr(generator, "__name__", "generator")
    if not (0 < lo < (1.0 if hi is None else hi)):
        raise InputError(f"min_thickness: need 0 < lo < hi, got lo={lo!r}, hi={hi!r}")
    if not (0 < rtol < 1):
        raise InputError(f"min_thickness: rtol must be in (0, 1), got {rtol!r}")
    check_rtol(rtol, method)
    if param in params:
        raise InputError(f"min_thickness: {param!r} is the bisected parameter; do not "
                         "give it")
    check_params = getattr(gen, "check_params", None)  # a registered generator's
    if check_params is not None:
        # before a build (it said "cannot be built at thickness=1 ...; give a smaller
        # upper bound", which no upper bound mends)
        try:
            check_params([*params, param])
        except InputError as err:
            raise InputError(f"min_thickness: {err.detail}") from None
        from .cases import not_bisectable, param_specs

        why = not_bisectable(param, param_specs(name)[param])
        if why:  # (the arch's voussoirs, None by default, was bisected from 2 to 10)
            raise InputError(f"min_thickness: {param} is {why}")
    if not (math.isfinite(load_factor) and load_factor >= 0):
        raise InputError(f"min_thickness: load_factor must be >= 0, got {load_factor!r}")
    bound: tuple[str, ...] = ()  # the note of a default upper bound below 1
    if hi is None:
        hi = 1.0
        try:
            gen(**params, **{param: hi})
        except InputError as err:  # (a pointed arch of 16 voussoirs is not built at 1)
            smaller = thinner(gen, params, param, lo)
            if smaller is not None:
                bound = (f"the upper bound is {param} = {smaller:g}: the family is not "
                         f"built at 1 ({err.detail})",)
                hi = smaller
    n = 0
    spent = 0.0

    def build(t: float) -> Scene:
        try:
            return gen(**params, **{param: t})
        except InputError as err:
            # (where it fails at the lower bound too, the other parameters are at
            # fault: voussoirs=2.5 was told to give a smaller upper bound)
            # and at the lower bound, where the upper one builds: a larger one (the
            # corbel dome's ring_thickness at 0.01, below its overhang, had no advice)
            advice = ("; give a smaller upper bound (hi, --hi)"
                      if t == hi and builds(gen, params, param, lo) else
                      f"; give a larger lower bound (lo, --lo): it is built at "
                      f"{param}={hi:g}" if t == lo and builds(gen, params, param, hi)
                      else "")
            raise InputError(f"min_thickness: {name} cannot be built at {param}={t:g} "
                             f"({err}){advice}") from None

    def admissible(t: float) -> tuple[bool | None, str]:
        nonlocal n, spent
        n += 1
        scene = build(t)
        try:
            r = check(scene, friction=friction, load_factor=load_factor, method=method,
                      state=False, compare_dry=False)
        except InputError as err:  # the question, not the family (its name left out)
            raise InputError(f"min_thickness: {err.detail}") from None
        spent += float(r.solve_time)
        return {"admissible": True, "inadmissible": False}.get(r.status), r.status

    if friction is None:  # the scene's own, as the result shows it
        friction = build(hi).effective_friction
    at_hi = admissible(hi)[0]
    if at_hi is not True:
        def thicker() -> str:
            """Where the family cannot be built much thicker (t/R < 2 for an arch),
            that; else the advice to raise the upper bound."""
            try:
                gen(**params, **{param: 1.5 * hi})
            except InputError as err:
                return (f", and it cannot be built at {param}={1.5 * hi:g} ({err}): an "
                        "upper bound between the two is all that is left" +
                        (", or a smaller load factor" if load_factor else ""))
            return "; raise the upper bound (hi, --hi)"

        def thinner_stands() -> str:
            """At a finite friction, the first of hi / sqrt(2), hi / 2, ... above lo at
            which it stands ({param}=value); else ""."""
            t = hi / math.sqrt(2.0)
            while t > lo:
                if builds(gen, params, param, t) and admissible(t)[0]:
                    return f"{param}={t:.6g}"
                t /= math.sqrt(2.0)
            return ""

        raise InputError(_not_at_hi(build(hi), name, f"{param}={hi:g}", at_hi, friction,
                                    method, load_factor, thicker, thinner_stands))
    at_lo, status = admissible(lo)
    if at_lo:
        # an answer, not an error: the 3-voussoir arch (four joints) stands however thin,
        # and "lower the lower bound" could never end
        note = (f"it stands at the lower bound {param}={lo:g}: the minimum is at most "
                "that (no thinner value was tried; a smaller lo, --lo, finds it where it "
                "lies above 0)")
        return ThicknessResult(name, param, lo, 0.0, n, friction, dict(params),
                               status=AT_LOWER_BOUND, notes=(*bound, note),
                               load_factor=load_factor, solve_time=spent)
    if at_lo is None:
        raise InputError(f"min_thickness: {name} is {status}, not certified "
                         f"inadmissible, at the lower bound {param}={lo:g}; lower the lower "
                         "bound (lo, --lo)")
    br = bisect(admissible, lo, hi, rtol)
    if br.undecided_at is not None:
        note = (f"the check could not decide at {param}={br.undecided_at:.6g}: the minimum "
                f"is bracketed in [{br.bad:.6g}, {br.good:.6g}]")
        return ThicknessResult(name, param, br.good, br.bad, n, friction, dict(params),
                               status="undecided", notes=(*bound, note),
                               load_factor=load_factor, solve_time=spent)
    return ThicknessResult(name, param, br.good, br.bad, n, friction, dict(params),
                           notes=bound, load_factor=load_factor, solve_time=spent)


def _not_at_hi(scene: Scene, name: str, where: str, at_hi: bool | None, friction: Any,
               method: str, load_factor: float, thicker: Callable[[], str],
               thinner: Callable[[], str]) -> str:
    """Why the search cannot start at its upper bound ``where``, and what to change: the
    bound where the structure falls by rotation, the friction where it stands there
    without sliding, or the bound: the friction a ring needs falls with its thickness,
    then stops falling (the semicircular arch under its self-weight: f* = 0.347 at t/R =
    0.15, 0.309 at 0.3 and at 1), so that at f = 0.35 an upper bound of 0.12 is too
    thin (it needs 0.378 there; the minimum is 0.1466), while at f = 0.3 none helps.
    ``thicker()`` ends the last case: raise the bound, or why that cannot help. The
    friction needed can also rise with the thickness (the flat arch on piers: f* = 0.22
    at a depth of 0.4, 0.27 at 1), so that a thinner one may stand where the bound
    does not: ``thinner()`` names one, or "" (the advice was to raise the bound alone,
    which at f = 0.25 never helps, while depths from 0.32 stand)."""
    head = f"min_thickness: {name} is not admissible at the upper bound {where}"
    if at_hi is None:
        return (f"min_thickness: {name} could not be decided at the upper bound {where}; "
                "give another upper bound (hi, --hi)")
    if friction_value(friction) != math.inf:
        stands = check(scene, friction="infinite", load_factor=load_factor, method=method,
                       state=False, compare_dry=False).status == "admissible"
        if stands:
            need = min_friction(scene, load_factor=load_factor, state=False,
                                compare_dry=False)
            f = f"f >= {fmt_safe(need.friction_factor, 4, True)}" \
                if need.status == "stable" else "a larger f"
            lower = thinner()
            if lower:
                return (f"{head} with f = {friction_label(friction)} (it needs {f} there), "
                        f"but stands at {lower}: the f it needs rises with the "
                        f"{where.split('=')[0]} there; an upper bound at {lower} (hi, "
                        "--hi) bisects below it")
            return (f"{head} with f = {friction_label(friction)}, although it stands "
                    f"there without sliding (it needs {f} there), nor at any of the "
                    "smaller values tried down to the lower bound: a thicker one may need "
                    "a smaller f (raise the upper bound: hi, --hi) or as large (give a "
                    "larger f: friction)")
    return head + thicker()


__all__ = ["AT_LOWER_BOUND", "ThicknessResult", "builds", "check_rtol", "min_thickness"]
