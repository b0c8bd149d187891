"""Timing of the foundation stages on running-bond walls of growing size.

Stages: building the scene (:func:`rigidblocks.generators.walls.running_bond_wall`),
writing and reading the scene file, validation (polygons and the overlap check),
contact detection and assembly of the equilibrium matrix. Run as

    python benchmarks/bench_foundation.py --sizes 100 1000 10000 50000

Each size is a target number of blocks; the wall has about as many courses as blocks
per course (C = round(sqrt(n)), N = round(n / C)), so the actual count
``N C + floor(C / 2)`` (plus the foundation) is close to, not exactly, the target.
"""

from __future__ import annotations

import argparse
import math
import sys
import tempfile
from collections.abc import Sequence
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import text_table, timed  # noqa: E402

from rigidblocks.contacts.detect2d import detect_contacts_2d
from rigidblocks.equilibrium import assemble
from rigidblocks.generators.walls import joint_count, running_bond_wall
from rigidblocks.io.scene_file import read_scene, write_scene
from rigidblocks.scene.validate import DEFAULT_TOL, validate_scene

DEFAULT_SIZES = (100, 1_000, 10_000, 50_000)
STAGES = ("build", "file", "validate", "detect", "assemble")


def wall_shape(n_blocks: int) -> tuple[int, int]:
    """(courses, blocks per course) of a roughly square wall of about ``n_blocks``."""
    courses = max(1, round(math.sqrt(n_blocks)))
    return courses, max(1, round(n_blocks / courses))


def bench_one(n_blocks: int, workdir: Path) -> dict:
    """Time every stage for one wall; returns counts and seconds per stage."""
    courses, per_course = wall_shape(n_blocks)
    t: dict[str, float] = {}
    with timed(t, "build"):
        scene = running_bond_wall(courses, per_course)
    path = workdir / f"wall_{n_blocks}.json"
    with timed(t, "file"):
        write_scene(scene, path)
        scene = read_scene(path, validate=False)
    with timed(t, "validate"):
        validate_scene(scene)
    with timed(t, "detect"):
        contacts = detect_contacts_2d(scene, DEFAULT_TOL)
    with timed(t, "assemble"):
        system = assemble(scene, contacts)

    if contacts.n_joints != joint_count(courses, per_course):
        raise RuntimeError(f"wall {courses} x {per_course}: {contacts.n_joints} joints, "
                           f"closed form {joint_count(courses, per_course)}")
    return {"target": n_blocks, "courses": courses, "per_course": per_course,
            "blocks": len(scene.blocks), "joints": contacts.n_joints,
            "points": contacts.n_points, "rows": system.n_rows,
            "columns": system.layout.size, "seconds": t}


def format_table(rows: Sequence[dict]) -> str:
    """The results as a fixed-width text table (seconds per stage)."""
    return text_table(["blocks", "joints", "points", *STAGES, "total"],
                      [[r["blocks"], r["joints"], r["points"],
                        *(float(r["seconds"][s]) for s in STAGES),
                        float(sum(r["seconds"].values()))] for r in rows])


def main(sizes: Sequence[int] = DEFAULT_SIZES, out=None) -> list[dict]:
    """Run the benchmark for each size, print the table, return the rows."""
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            rows.append(bench_one(int(n), Path(tmp)))
    print(format_table(rows), file=out or sys.stdout)
    return rows


def _cli(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=list(DEFAULT_SIZES),
                        help="target numbers of blocks (default: %(default)s)")
    args = parser.parse_args(argv)
    if any(n < 1 for n in args.sizes):
        parser.error("--sizes must be positive integers")
    main(args.sizes)
    return 0


if __name__ == "__main__":
    sys.exit(_cli())
