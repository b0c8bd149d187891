"""``report``: one self-contained HTML file with the question, the answer, the pictures
(2D as SVG, 3D as an interactive view) and the per-joint table.

The analysis options are collected into one dict and handed to
:func:`rigidblocks.reporting.run_analysis` as keyword arguments of the analysis, so an
option the analyses gain (a flow rule, say) is one more ``add_argument`` here and
nothing else.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from ..analyses import ANALYSES
from ..errors import InputError
from ..io import read_scene
from .analyses import EXIT, add_limit_args, add_question_args, limit_options, question


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("scene", help="scene file (JSON, see docs/scene-format.md)")
    p.add_argument("--analysis", choices=[a.command for a in ANALYSES.values()],
                   default=None,
                   help="the question to answer (default: none, the scene alone)")
    add_question_args(p, ("friction", "load_factor"))
    add_limit_args(p)
    p.add_argument("--title", default=None, help="the report's title (default: the scene's name)")
    p.add_argument("-o", "--output", default=None,
                   help="output file, .html (default: SCENE with .html)")


def run(args: argparse.Namespace) -> int:
    out = Path(args.output) if args.output else Path(args.scene).with_suffix(".html")
    if out.suffix.lower() not in (".html", ".htm"):
        raise InputError(f"a report is an HTML file: use .html, not '{out.suffix}'", str(out))
    scene = read_scene(args.scene)
    options = {**question(args), **limit_options(args)}
    if args.analysis is None and options:
        raise InputError("--" + ", --".join(sorted(o.replace("_", "-") for o in options))
                         + " need --analysis")

    import matplotlib

    matplotlib.use("Agg")
    from ..reporting import report, run_analysis

    result = run_analysis(scene, args.analysis, **options) if args.analysis else None
    page = report(scene, result, title=args.title)
    page.save(out)
    status = getattr(result, "status", None)
    print(f"wrote {out}" + (f" ({args.analysis}: {status})" if status else "")
          + f"; open it in a browser, e.g. file://{out.resolve()}")
    return EXIT.get(status, 0)
