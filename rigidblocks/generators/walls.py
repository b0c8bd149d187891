"""Running-bond masonry walls: a standard, scalable family of 2D scenes.

A wall of ``courses`` courses stands on one support block (the foundation) that runs
under its whole length. Even courses (0, 2, ...; course 0 on the foundation) hold
``blocks_per_course`` full blocks; odd courses are offset by half a block and hold one
half block at each end and ``blocks_per_course - 1`` full blocks in between, so both
ends of the wall are straight. The wall is loaded by its self-weight (dead) and by a
live horizontal body force ``horizontal_load x weight`` on every block (a seismic
coefficient times the load multiplier). Units are m and kN.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..errors import InputError, finite_number
from ..scene.model import Block, Scene, Units
from .arches import items
from .limits import MAX_WALL_BLOCKS, at_most

FOUNDATION_ID = "foundation"


def block_id(course: int, index: int) -> str:
    """Id of block ``index`` (counted from the left, from 0) of course ``course``."""
    return f"c{course}b{index}"


def _finite(name: str, value: float) -> float:
    """An int or float (not a bool) that is finite."""
    return finite_number(value, f"running_bond_wall: {name}", strict=True)


def _positive(name: str, value: float) -> float:
    v = _finite(name, value)
    if not v > 0:
        raise InputError(f"running_bond_wall: {name} must be > 0, got {value!r}")
    return v


def _count(name: str, value: int, minimum: int = 1) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < minimum:
        raise InputError(f"running_bond_wall: {name} must be an integer >= {minimum}, "
                         f"got {value!r}")
    return int(value)


def _whole(v: object) -> object:
    """An opening's number, read from the command line's string form where it is one
    (what is not an integer is left for the check to name)."""
    if isinstance(v, str):
        try:
            return int(v)
        except ValueError:
            return v
    return v


def running_bond_wall(courses: int = 10, blocks_per_course: int = 10, block_length: float = 0.4,
                      block_height: float = 0.2, unit_weight: float = 20.0,
                      friction: float = 0.6, depth: float = 1.0, horizontal_load: float = 1.0,
                      openings: Sequence[tuple[int, int, int, int]] | str = ()
                      ) -> Scene:
    """A running-bond wall of rectangular blocks on a foundation (a 2D scene).

    Args:
        courses: number of courses C >= 1.
        blocks_per_course: N >= 1 full blocks in each even course (odd courses have two
            half blocks and N - 1 full blocks, N + 1 blocks in all).
        block_length, block_height: size of a full block (m).
        unit_weight: weight per unit volume (kN/m^3).
        friction: Coulomb friction coefficient of every joint (>= 0).
        depth: out-of-plane thickness (m).
        horizontal_load: the live body force is ``[horizontal_load, 0]`` times each block's
            weight.
        openings: rectangles of removed blocks, each ``(first_course, n_courses,
            first_block, n_blocks)``: in every course ``c`` with ``first_course <= c <
            first_course + n_courses`` the blocks of index ``first_block <= b <
            first_block + n_blocks`` are left out, the index counted from the left end of
            that course from 0 (so in odd courses index 0 is the left half block). The
            rectangle must lie inside the wall (``first_block + n_blocks <= N`` even in
            odd courses, whose last index is N); openings may overlap.

    Returns:
        A scene with the foundation (id ``"foundation"``, a support of height
        ``block_height`` under ``0 <= x <= N x block_length``) first, then the blocks
        course by course from the left, with ids ``c{course}b{index}``
        (:func:`block_id`).

    Notes:
        Joint count of the full wall (no openings). A joint is one shared segment
        between two blocks. Bed joints: the N blocks of course 0 each sit on the
        foundation (N); between two consecutive courses the block ends of both courses
        (every L and every L/2 offset by L) cut the length N L into 2N stretches
        (2N each, C - 1 interfaces). Head joints: N - 1 in each of the ceil(C/2) even
        courses and N in each of the floor(C/2) odd courses. Altogether

        .. math::

            J = N + 2N(C - 1) + \\lceil C/2 \\rceil (N - 1) + \\lfloor C/2 \\rfloor N
              = N (3C - 1) - \\lceil C/2 \\rceil ,

        with two contact points per joint. For C = N = 1, J = 1 (one block on the
        foundation); for C = 2, N = 1, J = 4. See :func:`joint_count`.
    """
    C = _count("courses", courses)
    N = _count("blocks_per_course", blocks_per_course)
    at_most("running_bond_wall", f"courses {C} x blocks_per_course {N}", wall_blocks(C, N),
            MAX_WALL_BLOCKS)
    L = _positive("block_length", block_length)
    h = _positive("block_height", block_height)
    depth = _positive("depth", depth)
    for name, v in (("unit_weight", unit_weight), ("friction", friction),
                    ("horizontal_load", horizontal_load)):
        _finite(name, v)
    if unit_weight < 0 or friction < 0:
        bad = "unit_weight" if unit_weight < 0 else "friction"
        raise InputError(f"running_bond_wall: {bad} must be >= 0, "
                         f"got {unit_weight if bad == 'unit_weight' else friction!r}")

    # every block of every course: course, index within course, left/right x
    course_of = np.repeat(np.arange(C), np.where(np.arange(C) % 2 == 0, N, N + 1))
    starts = np.concatenate([[0], np.cumsum(np.where(np.arange(C) % 2 == 0, N, N + 1))])
    index = np.arange(len(course_of)) - starts[course_of]
    odd = course_of % 2 == 1
    # block ends in units of half a block: even course [2i, 2i + 2], odd [2i - 1, 2i + 1]
    # clipped to the wall [0, 2N]
    left2 = np.where(odd, np.maximum(2 * index - 1, 0), 2 * index)
    right2 = np.where(odd, np.minimum(2 * index + 1, 2 * N), 2 * index + 2)

    keep = np.ones(len(course_of), dtype=bool)
    for k, op in enumerate(items(openings)):
        if isinstance(op, Sequence) and not isinstance(op, str):
            op = tuple(_whole(v) for v in op)
        if not (isinstance(op, Sequence) and len(op) == 4 and all(
                isinstance(v, int | np.integer) and not isinstance(v, bool) for v in op)):
            raise InputError(f"running_bond_wall: openings item #{k} must be 4 integers "
                             f"(first_course, n_courses, first_block, n_blocks), got {op!r}")
        c0, nc, b0, nbk = (int(v) for v in op)
        if c0 < 0 or nc < 1 or b0 < 0 or nbk < 1 or c0 + nc > C or b0 + nbk > N + 1:
            raise InputError(f"running_bond_wall: openings item #{k} {tuple(op)!r} does not fit "
                             f"the wall of courses {C} x blocks_per_course {N} (need "
                             f"first_course >= 0, n_courses >= 1, first_course + n_courses <= "
                             f"{C}, first_block >= 0, n_blocks >= 1, first_block + n_blocks "
                             f"<= {N} in an even course, {N + 1} in an odd one)")
        if b0 + nbk > N and np.any((np.arange(c0, c0 + nc) % 2) == 0):
            raise InputError(f"running_bond_wall: openings item #{k} {tuple(op)!r} reaches block "
                             f"index {b0 + nbk - 1}, past the last block ({N - 1}) of an even "
                             "course")
        hit = ((course_of >= c0) & (course_of < c0 + nc) & (index >= b0) & (index < b0 + nbk))
        keep &= ~hit
    if not keep.any():
        raise InputError("running_bond_wall: openings remove every block")
    course_of, index, left2, right2 = course_of[keep], index[keep], left2[keep], right2[keep]

    half = 0.5 * L
    x0 = left2 * half
    x1 = right2 * half
    y0 = course_of * h
    y1 = (course_of + 1) * h
    corners = np.stack([np.stack([x0, y0], 1), np.stack([x1, y0], 1),
                        np.stack([x1, y1], 1), np.stack([x0, y1], 1)], axis=1).tolist()
    ids = [f"c{c}b{i}" for c, i in zip(course_of.tolist(), index.tolist(), strict=True)]
    blocks = [Block(FOUNDATION_ID, ((0.0, -h), (N * L, -h), (N * L, 0.0), (0.0, 0.0)),
                    None, True, None)]
    blocks.extend(Block(bid, tuple(map(tuple, quad)), None, False, None)
                  for bid, quad in zip(ids, corners, strict=True))
    return Scene(dimension=2, blocks=tuple(blocks),
                 name=f"running-bond wall, {C} courses x {N} blocks",
                 units=Units("m", "kN"), depth=depth, unit_weight=float(unit_weight),
                 friction=float(friction),
                 live_body_force=(float(horizontal_load), 0.0), load_factor=0.0)


def wall_blocks(courses: int, blocks_per_course: int) -> int:
    """Blocks of a full running-bond wall, the foundation among them:
    ``N C + floor(C / 2) + 1`` (the odd courses hold one block more)."""
    return blocks_per_course * courses + courses // 2 + 1


def joint_count(courses: int, blocks_per_course: int) -> int:
    """Closed-form joint count ``N (3C - 1) - ceil(C / 2)`` of a full running-bond wall."""
    C, N = courses, blocks_per_course
    return N * (3 * C - 1) - (C + 1) // 2


__all__ = ["FOUNDATION_ID", "block_id", "joint_count", "running_bond_wall", "wall_blocks"]
