"""``import-dxf`` and ``export-dxf``: CAD drawings to scene files and back."""

from __future__ import annotations

import argparse
import sys

from ..errors import InputError
from ..io import read_scene, write_scene
from ..scene.model import friction_label
from .options import finite_float


def _pair(text: str) -> tuple[float, float]:
    try:
        vals = tuple(finite_float(v) for v in text.replace(",", " ").split())
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(f"not two numbers: '{text}'") from None
    if len(vals) != 2:
        raise argparse.ArgumentTypeError(f"not two numbers: '{text}'")
    if not any(vals):  # (as import-compas: a live load of nothing has no multiplier)
        raise argparse.ArgumentTypeError(f"not both zero: '{text}'")
    return vals  # type: ignore[return-value]


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    if name == "import-dxf":
        from ..io.dxf import DEFAULT_NEAR_MISS, DEFAULT_SNAP_TOL

        p.add_argument("dxf", help="DXF drawing: one block per closed polyline")
        p.add_argument("-o", "--output", required=True, help="scene file to write (JSON)")
        p.add_argument("--supports", default=None,
                       help="'lowest', 'largest', 'layer:NAME' or 'ids:b1,b2' (default: the "
                       "supports stored by export-dxf, else 'lowest')")
        p.add_argument("--layers", default=None, metavar="L1,L2",
                       help="read only these layers (default: every layer but the analysis "
                       "layers export-dxf writes)")
        p.add_argument("--unit-weight", type=finite_float, default=None,
                       help="unit weight, force per cubed length unit (a drawing in mm "
                            "with forces in kN: 25e-9 for 25 kN/m^3)")
        p.add_argument("--depth", type=finite_float, default=None,
                       help="out-of-plane depth, in the length unit (default 1)")
        p.add_argument("--friction", default=None, help='friction f or "infinite"')
        p.add_argument("--length-unit", default=None,
                       help="e.g. mm (default: the unit the drawing declares, $INSUNITS)")
        p.add_argument("--force-unit", default=None, help="e.g. kN")
        p.add_argument("--live-body-force", type=_pair, default=None, metavar="'FX FY'",
                       help="live body force vector, e.g. '1 0' (the live load of "
                       "`rigidblocks load`: every free block's weight times it times "
                       "lambda); the scene's load_factor is then written 0, so check and "
                       "friction answer for the weight alone (--load-factor asks for "
                       "more)")
        p.add_argument("--name", default=None, help="scene name")
        p.add_argument("--snap-tol", type=finite_float, default=DEFAULT_SNAP_TOL,
                       help="snapping tolerance relative to the drawing size "
                       f"(default {DEFAULT_SNAP_TOL:g})")
        p.add_argument("--near-miss", type=finite_float, default=DEFAULT_NEAR_MISS,
                       help="reject corners closer than this many tolerances but not "
                       f"within one (default {DEFAULT_NEAR_MISS:g}; 0 disables)")
    else:
        p.add_argument("scene", help="scene file (JSON)")
        p.add_argument("-o", "--output", required=True, help="DXF file to write")
        p.add_argument("--analysis", choices=("check", "friction", "load"), default=None,
                       help="add the thrust line and force arrows of this analysis")
        from .analyses import add_question_args

        add_question_args(p, ("friction", "load_factor"))


def _layers(text: str | None) -> list[str] | None:
    if text is None:
        return None
    names = [t.strip() for t in text.split(",") if t.strip()]
    if not names:
        raise InputError("--layers: give layer names, e.g. --layers WALLS,PIERS")
    return names


def _friction(text: str | None):
    if text is None:
        return None
    try:
        return friction_label(text)
    except InputError as err:
        raise err.located("--friction") from None


def run(args: argparse.Namespace) -> int:
    from ..io.dxf import read_dxf, require_2d, write_dxf

    if args.command == "import-dxf":
        from ..io.dxf import length_unit

        units = None
        if args.length_unit:
            args.length_unit = length_unit(args.length_unit)
        if args.length_unit or args.force_unit:
            units = (args.length_unit, args.force_unit)
        scene, rep = read_dxf(args.dxf, supports=args.supports, unit_weight=args.unit_weight,
                              depth=args.depth, friction=_friction(args.friction),
                              units=units, live_body_force=args.live_body_force,
                              name=args.name, snap_tol=args.snap_tol,
                              near_miss=args.near_miss, report=True,
                              layers=_layers(args.layers))
        lbf = args.live_body_force is not None and scene.load_factor is None
        if lbf:  # as import-compas and the generators: check and friction at the weight
            scene = scene.with_changes(load_factor=0.0)
        write_scene(scene, args.output)
        print(rep.summary())
        if lbf:
            ax, ay = args.live_body_force
            print(f"live load  weight x ({ax:g}, {ay:g}) x lambda (load factor 0 written: "
                  "check and friction answer for the weight alone)")
        from ..io.dxf import (
            NO_FRICTION_NOTE,
            NO_UNIT_WEIGHT_NOTE,
            depth_note,
            span_text,
            unit_doubt,
            unit_guess,
        )

        if rep.unit_conflict:
            print(f"rigidblocks: warning: {rep.unit_conflict}", file=sys.stderr)
        if rep.declared_unit and not args.length_unit:
            print(f"lengths in {rep.declared_unit}, as the drawing declares ($INSUNITS; "
                  f"it spans {span_text(scene)}): give the unit weight per "
                  f"{rep.declared_unit}^3 and the depth in {rep.declared_unit}")
        elif args.length_unit:  # (the span was said only for a declared unit)
            print(f"lengths in {scene.length_unit}, as given (the drawing spans "
                  f"{span_text(scene)})")
        elif scene.length_unit:  # the units of the scene export-dxf stored in it
            print(f"lengths in {scene.length_unit}, as the drawing's scene records them (it "
                  f"spans {span_text(scene)})")
        else:  # (nothing was said, nor doubted: 350 mm blocks weighed as 350 m ones)
            which = (f"$INSUNITS {rep.insunits}, no unit this import reads" if rep.insunits
                     else "none declared")
            print(f"lengths in the drawing's own units, {which} (it spans "
                  f"{span_text(scene)})")
        # (not of a scene restored with its units: --length-unit, which it advised,
        # is refused there)
        doubt = "" if rep.restored and scene.length_unit else \
            unit_doubt(scene) or (unit_guess(scene, rep.insunits)
                                  if not scene.length_unit else "")
        if doubt:
            print(f"rigidblocks: warning: {doubt}", file=sys.stderr)
        if scene.unit_weight is None:
            print(f"rigidblocks: warning: {NO_UNIT_WEIGHT_NOTE}", file=sys.stderr)
        elif scene.depth is None:
            print(f"rigidblocks: warning: {depth_note(scene)}", file=sys.stderr)
        if scene.friction is None:
            print(f"rigidblocks: warning: {NO_FRICTION_NOTE}", file=sys.stderr)
        print(f"wrote {args.output}")
        return 0
    from pathlib import Path

    from .analyses import EXIT, question
    from .plot import analyse

    if Path(args.output).suffix.lower() != ".dxf":
        raise InputError(f"a drawing is a DXF file: use .dxf, not "
                         f"'{Path(args.output).suffix}'", str(args.output))
    scene = read_scene(args.scene)
    require_2d(scene)  # before the analysis, which a 3D scene would wait for in vain
    result = analyse(scene, args.analysis, question(args))
    if result is not None and getattr(result, "state", None) is None and args.analysis:
        print(f"{args.analysis}: {result.status}, no force state to draw")
    write_dxf(scene, args.output, result)
    status = getattr(result, "status", None)
    print(f"wrote {args.output}" + (f" ({args.analysis}: {status})" if status else ""))
    return EXIT.get(status, 0)
