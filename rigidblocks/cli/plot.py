"""``plot``: a picture of a scene, optionally with the result of an analysis."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..analyses import ANALYSES
from ..errors import InputError
from ..io import read_scene
from ..plotting import FORMATS
from .analyses import EXIT, add_limit_args, add_question_args, limit_options, question


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("scene", help="scene file (JSON)")
    p.add_argument("--analysis", choices=[a.command for a in ANALYSES.values()],
                   default=None,
                   help="run this analysis and draw its result (forces and thrust line "
                   "for check/friction, the collapse mechanism for load)")
    add_question_args(p, ("friction", "load_factor"))
    add_limit_args(p)
    p.add_argument("--ids", action="store_true", help="write the block ids")
    p.add_argument("-o", "--output", default=None,
                   help="output file, .png, .svg or .pdf (default: SCENE with .png)")


def run(args: argparse.Namespace) -> int:
    out = Path(args.output) if args.output else Path(args.scene).with_suffix(".png")
    if out.suffix.lower() not in FORMATS:
        raise InputError(f"unknown picture format '{out.suffix}': use "
                         f"{', '.join(FORMATS)}", str(out))
    scene = read_scene(args.scene)
    result = analyse(scene, args.analysis, {**question(args), **limit_options(args)})

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..plotting import plot, save_figure

    ax = plot(scene, result, ids=args.ids)
    try:
        save_figure(ax, str(out))
    except OSError as err:
        raise InputError(f"cannot write: {err}", str(out)) from None
    finally:
        plt.close(ax.figure)
    status = getattr(result, "status", None)
    print(f"wrote {out}" + (f" ({args.analysis}: {status})" if status else ""))
    return EXIT.get(status, 0)


def analyse(scene, name: str | None, options: dict):
    """Run the named analysis (None: no analysis) with a force state; ``options`` are
    the question's (:func:`.analyses.question`): what is not given is the scene's, as
    for ``check``, ``friction``, ``load`` and ``report``."""
    from ..analyses import analysis

    if name is None:
        return None
    return analysis(name).run(scene, **options)
