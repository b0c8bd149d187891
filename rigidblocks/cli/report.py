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

#: command-line option -> keyword argument of the analysis functions
ANALYSIS_OPTIONS = {"friction": "friction", "load_factor": "load_factor", "method": "method",
                    "solver": "solver", "contact_tol": "contact_tol"}


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("scene", help="scene file (JSON, see docs/scene-format.md)")
    p.add_argument("--analysis", choices=[a.command for a in ANALYSES.values()],
                   default=None,
                   help="the question to answer (default: none, the scene alone)")
    p.add_argument("--friction", default=None,
                   help='friction coefficient f, or "infinite", for check and load '
                   "(default: the scene's)")
    p.add_argument("--load-factor", type=float, default=None,
                   help="lambda multiplying the live loads, for check and friction "
                   "(default 1)")
    p.add_argument("--method", default=None,
                   help='"clarabel" (convex path, default) or "distortion"')
    p.add_argument("--solver", default=None,
                   help="back end of the convex path: clarabel, highs, scs, ecos, cvxpy-NAME")
    p.add_argument("--contact-tol", type=float, default=None,
                   help="contact tolerance relative to the scene's size (default 1e-7)")
    p.add_argument("--title", default=None, help="the report's title (default: the scene's name)")
    p.add_argument("-o", "--output", default=None,
                   help="output file, .html (default: SCENE with .html)")


def run(args: argparse.Namespace) -> int:
    out = Path(args.output) if args.output else Path(args.scene).with_suffix(".html")
    if out.suffix.lower() not in (".html", ".htm"):
        raise InputError(f"a report is an HTML file: use .html, not '{out.suffix}'", str(out))
    scene = read_scene(args.scene)
    options = {kw: getattr(args, opt) for opt, kw in ANALYSIS_OPTIONS.items()
               if getattr(args, opt) is not None}
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
    return 0
