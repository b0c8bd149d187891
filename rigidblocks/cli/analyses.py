"""``check``, ``friction`` and ``load``: the analyses on a scene file."""

from __future__ import annotations

import argparse
import json
import math
from typing import Any

from ..analyses import analysis
from ..errors import InputError
from ..io import read_scene
from ..methods import METHODS
from ..results import headline


def add_args(p: argparse.ArgumentParser, name: str) -> None:
    p.add_argument("scene", help="scene file (JSON, see docs/scene-format.md)")
    if name in ("check", "load"):
        p.add_argument("--friction", help='friction coefficient f, or "infinite" '
                       "(default: the scene's)")
    if name in ("check", "friction"):
        p.add_argument("--load-factor", type=float, default=1.0,
                       help="lambda multiplying the live loads (default 1)")
    p.add_argument("--method", default="clarabel",
                   help=" or ".join(f'"{m}"' for m in METHODS)
                   + ' (default "clarabel": the convex path)')
    p.add_argument("--solver", default=None,
                   help="back end of the convex path: clarabel, highs, scs, ecos, "
                   "cvxpy-NAME")
    p.add_argument("--contact-tol", type=float, default=None,
                   help="contact tolerance relative to the scene's size (default 1e-7): "
                   "faces this close count as touching")
    p.add_argument("--json", action="store_true", help="print one JSON object")


def run(args: argparse.Namespace) -> int:
    scene = read_scene(args.scene)
    res = analysis(args.command).run(
        scene, friction=getattr(args, "friction", None),
        load_factor=getattr(args, "load_factor", 1.0), method=args.method,
        solver=args.solver, state=False, contact_tol=args.contact_tol)
    out = res.to_dict()
    if args.json:
        print(json.dumps(_jsonable(out)))
    else:
        print(report(scene, res))
    return 0


def _jsonable(v: Any) -> Any:
    if isinstance(v, float) and not math.isfinite(v):
        return None if math.isnan(v) else ("infinite" if v > 0 else "-infinite")
    if isinstance(v, dict):
        return {k: _jsonable(x) for k, x in v.items()}
    if isinstance(v, list | tuple):
        return [_jsonable(x) for x in v]
    return v


def report(scene, res) -> str:
    """A short human-readable table of a result."""
    fu = scene.force_unit or "force units"
    lines = [f"scene      {scene.name or scene.source}",
             f"blocks     {len(scene.blocks)} ({int(scene.support_mask.sum())} supports), "
             f"joints {res.contacts.n_joints}"]
    d = res.to_dict()
    if res.analysis == "check":
        f = d["friction"]
        lines.append(f"friction   {f if f is not None else '-'}   load factor {res.load_factor:g}")
        verdict = {"admissible": "ADMISSIBLE", "inadmissible": "NOT ADMISSIBLE"}
        lines.append(f"verdict    {verdict.get(res.status, headline(res).upper())}")
        if res.status == "inadmissible" and math.isfinite(res.violation):
            lines.append(f"violation  {res.violation:.4g} {fu} (smallest possible breach "
                         "of the joint laws)")
        if res.status == "inadmissible":
            lines += _live_hint(scene, res)
    elif res.analysis == "min_friction":
        lines.append(f"lambda     {res.load_factor:g}   (load factor)")
        if res.status == "stable":
            lines.append(f"f*         {res.friction_factor:.6g}   (friction angle "
                         f"{res.friction_angle_deg:.4f} deg)")
            lines.append(f"governing  {_joint_list(res.governing_joints)}")
        else:
            lines.append(f"verdict    {headline(res).upper()}")
            if res.status == "unstable":
                lines += _live_hint(scene, res)
    else:
        lines.append(f"friction   {d['friction']}")
        if res.status == "collapse":
            lines.append(f"lambda*    {res.load_multiplier:.6g}")
            mech = d.get("mechanism", {})
            for key in ("hinges", "sliding", "open"):
                lines.append(f"{key:<10} {_joint_list(mech.get(key, []))}")
        else:
            lines.append(f"verdict    {headline(res).upper()}")
    lines.append(f"solver     {res.solver}, {res.n_solves} solve(s), {res.solve_time:.3g} s")
    return "\n".join(lines)


def _joint_list(joints, most: int = 12) -> str:
    """Joints as ``a-b`` names; a long list is cut, with its length (``--json`` has all)."""
    names = [f"{a}-{b}" for a, b in joints]
    if len(names) <= most:
        return ", ".join(names) or "-"
    return f"{len(names)} joints: " + ", ".join(names[:most]) + ", ... (--json lists all)"


def _live_hint(scene, res) -> list[str]:
    """Where live loads at a nonzero load factor made the verdict, say how to ask the
    two questions an engineer usually means."""
    if not (scene.has_live_load and res.load_factor):
        return []
    src = scene.source or "SCENE"
    return [f"hint       the live loads are included at load factor {res.load_factor:g}; "
            f"--load-factor 0 for the dead load alone, `rigidblocks load {src}` for the "
            "collapse multiplier"]


__all__ = ["add_args", "run", "report", "InputError"]
