"""``thickness``: the minimum thickness of a generator's family by bisection."""

from __future__ import annotations

import argparse
import json
import math

from ..errors import InputError
from ..results import fmt_safe
from .options import add_rtol, finite_float, friction_option, load_factor, relative_tolerance


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("generator", help="generator name (see `rigidblocks example --list`)")
    p.add_argument("--param", default="thickness", help="parameter to bisect, as "
                   "`example NAME --help` lists it (default: thickness)")
    p.add_argument("--lo", type=finite_float, default=0.01,
                   help="a value at which the structure does not stand (default %(default)g)")
    p.add_argument("--hi", type=finite_float, default=None,
                   help="a value at which it stands (default 1); where the family is not "
                   "built at 1 and none is given, the largest of 1/2, 1/4, ... at which it is")
    add_rtol(p, "thickness", 1e-4)
    p.add_argument("--friction", type=friction_option, default="infinite",
                   help='friction coefficient f, or "infinite" (default)')
    p.add_argument("--method", default="clarabel",
                   help='"clarabel" (default), "distortion", or a back end of the convex '
                   'path (highs, scs, ecos, cvxpy-NAME)')
    p.add_argument("--load-factor", type=load_factor, default=0.0,
                   help="the multiple of the live load it must carry besides its dead "
                   "load (a wall's lateral load; default 0: the dead load alone)")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.add_argument("params", nargs=argparse.REMAINDER,
                   help="--PARAM VALUE pairs of the generator")


def run(args: argparse.Namespace) -> int:
    from ..generators import get
    from ..methods import method_name
    from ..studies import min_thickness
    from ..studies.thickness import AT_LOWER_BOUND, thinner
    from .example import as_options, describe, options, parameter_name, parse_params

    gen = get(args.generator)
    where = f"thickness {gen.name}"
    tokens = _own_options(args, list(args.params))
    if "-h" in tokens or "--help" in tokens:
        print(f"usage: rigidblocks thickness {gen.name} [--param NAME] [--lo LO] [--hi HI] "
              "[--PARAM VALUE ...]\n")
        print(describe(gen))
        return 0
    param, shown = parameter_name(args.param), args.param  # shown: as the user named it
    default = {p.name: p.default for p in gen.params}
    if param not in default:
        raise InputError(f"--param {shown}: no such parameter ({options(gen)})", where)
    from ..studies.cases import not_bisectable, param_specs

    why = not_bisectable(param, param_specs(gen.name)[param])
    if why:  # bisection takes every real in between, of the family's own sizes
        raise InputError(f"--param {shown} is {why}", where)
    try:
        method, backend = method_name(args.method)  # before the generator is tried at --hi
    except InputError as err:
        raise InputError(f"--method: {err.detail}", where) from None
    typed: dict[str, str] = {}
    params = parse_params(gen, tokens, typed, "thickness")
    if param in params:
        raise InputError(f"{typed[param]} is the parameter bisected (--param {shown}) "
                         "between --lo and --hi; do not give it", where)
    typed[param] = shown
    hi, halved = (1.0 if args.hi is None else args.hi), ""
    built = None
    try:
        built = gen(**params, **{param: hi})  # the user's parameters, before any solve
    except InputError as err:
        why = as_options(err, gen, typed).detail
        hi = thinner(gen, params, param, args.lo) if args.hi is None else None
        if hi is None:
            raise InputError(f"at the upper bound {shown} = {args.hi or 1.0:g} (--hi): {why}",
                             where) from None
        halved = why  # (a pointed arch of 16 voussoirs is not built at t/R = 1)
    args.hi = hi
    try:
        res = min_thickness(args.generator, param=param, lo=args.lo, hi=args.hi,
                            rtol=args.rtol, friction=args.friction, method=args.method,
                            load_factor=args.load_factor, **params)
    except InputError as err:
        raise as_options(err, gen, typed, "thickness") from None
    bound = (f"the upper bound is {shown} = {hi:g}: the family is not built at 1 "
             f"({halved})") if halved else ""
    if args.json:
        doc = res.to_dict()
        if built is not None:  # the family's units: the parameter's and the answer's
            doc["units"] = {"length": built.length_unit, "force": built.force_unit}
        if bound:
            doc["notes"] = [bound, *doc["notes"]]
            doc["why"] = [bound, *doc["why"]]
        print(json.dumps(doc))
    else:
        extra = " ".join(f"{typed[k]} {v}" for k, v in params.items()) or "defaults"
        what = next((p.help for p in gen.params if p.name == param), "") or shown
        print(f"generator  {res.generator} ({extra})")
        lf = args.load_factor
        print(f"friction   {res.friction}   load factor " + (
            f"{lf:.10g} (the dead load plus {lf:.10g} x the live load)" if lf else
            "0 (dead load only)"))
        print(f"method     {method}" + (f" (back end {backend})" if backend else ""))
        print(f"minimised  {shown}: {what}")
        # as many figures as its width needs (at --rtol 1e-9 both ends read alike)
        d = max(10, 3 - math.floor(math.log10(args.rtol)))
        bracket = f"[{res.lower:.{d}g}, {res.thickness:.{d}g}]"
        if res.status == "undecided":
            print("status     UNDECIDED: a check could not decide; the minimum is only "
                  "bracketed")
            print(f"{shown:<10} in {bracket}   ({res.n_checks} checks)")
        elif res.status == AT_LOWER_BOUND:
            print(f"{shown:<10} min <= {res.thickness:.10g}   (it stands at the lower bound "
                  f"--lo; {res.n_checks} checks)")
        else:
            # the thinnest that stands, rounded up (a check at the printed value stands)
            print(f"{shown:<10} min {fmt_safe(res.thickness, 6, True)}   (bracket "
                  f"{bracket}, {res.n_checks} checks)")
        if res.status != AT_LOWER_BOUND:  # (as friction and load say it)
            width = (res.thickness - res.lower) / res.thickness
            print(f"accuracy   {width:.1e} (bracket relative width; requested "
                  f"{args.rtol:g})")
        for n in ([bound] if bound else []) + list(res.notes):
            print(f"note       {n}")
    return 3 if res.status == "undecided" else 0


_OWN = {"--param": str, "--lo": finite_float, "--hi": finite_float,
        "--rtol": relative_tolerance,
        "--friction": friction_option, "--method": str, "--load-factor": load_factor}


def _own_options(args: argparse.Namespace, tokens: list[str]) -> list[str]:
    """Take this command's own options out of the tokens that follow the generator."""
    rest = []
    i = 0
    while i < len(tokens):
        tok = tokens[i]
        if tok == "--json":
            args.json = True
            i += 1
        elif tok in _OWN:
            if i + 1 >= len(tokens):
                raise InputError(f"thickness: {tok} needs a value")
            try:
                setattr(args, tok[2:].replace("-", "_"), _OWN[tok](tokens[i + 1]))
            except (ValueError, argparse.ArgumentTypeError) as err:
                raise InputError(f"thickness: {tok}: {err}") from None
            i += 2
        else:
            rest.append(tok)
            i += 1
    return rest


__all__ = ["add_args", "run"]
