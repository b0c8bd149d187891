"""How large a scene a generator builds.

Every generator counts the blocks its parameters ask for before it builds any, and
refuses more than its bound with an error naming those parameters (a typo such as
``courses=100000000`` would otherwise fill the memory before anything is said). The
bounds sit far above the largest scenes the benchmarks build (2D walls of 50,051
blocks, 3D walls of 5,026; ``benchmarks/bench_scaling.py``) and below what the
machine's memory takes; the figures are CPU time and peak memory of the generator
alone.
"""

from __future__ import annotations

from ..errors import InputError

#: The most blocks a generator builds. Its blocks go through the scene file's
#: dictionaries and validation, 10-25 kB a block: a 2D arch of 10,000 voussoirs takes
#: 3.6 s and 230 MB, a 3D wall of 100,101 boxes 25 s and 2.3 GB.
MAX_BLOCKS = 100_000

#: The most blocks of the 2D running-bond wall, which builds them as arrays
#: (about 1.3 kB a block: 50,051 blocks in 0.2 s and 94 MB).
MAX_WALL_BLOCKS = 1_000_000

#: The most voussoirs of an arch, a flat arch or a ring of a barrel vault, and blocks in
#: a ring of a corbel dome: the bounding boxes of thin blocks fanning round a centre
#: overlap hundreds of their neighbours, so validation's candidate pairs grow as the
#: square of their number (semicircular arch: 10,000 voussoirs 3.6 s and 230 MB,
#: 20,000 11 s and 680 MB, 40,000 45 s and 2.4 GB; flat arch 10,000: 6.9 s and 390 MB;
#: one ring of a vault 10,000: 6.9 s and 470 MB; a dome of 5 rings of 5,000: 21 s and
#: 770 MB, of 10,000: 71 s and 2.6 GB).
MAX_VOUSSOIRS = 10_000

#: The most straight segments along the intrados of an arch (voussoirs x arc_points):
#: 10 voussoirs of 100,000 segments each take 3.9 s and 710 MB.
MAX_ARC_SEGMENTS = 1_000_000

#: The most voussoirs of an arch with vertical joints: each is clipped from the whole
#: ring, a polygon of 8 x voussoirs x arc_points points, so the work grows as the
#: square of their number (1,000 voussoirs: 5.1 s).
MAX_VERTICAL_VOUSSOIRS = 1_000

#: The most blocks of a box stack (its boxes and the slab): the boxes all overlap in plan,
#: so validation looks at every pair of them (5,000 boxes: 3.8 s and 880 MB, four
#: times 2,500's).
MAX_STACK = 5_000

#: The most blocks in a ring of a capped corbel dome: the cap is a prism over a polygon
#: of 2 x blocks_per_ring sides, and validation checks it against its neighbours with
#: arrays that grow as the square of its size (64: 1.4 s and 640 MB; 128: 18 s and
#: 6.8 GB).
MAX_CAPPED_RING = 64


def count_at_most(gen: str, name: str, n: int, limit: int | None = None,
                  when: str = "") -> None:
    """Refuse a count parameter ``name`` above ``limit`` (default :data:`MAX_VOUSSOIRS`):
    ``InputError("gen: name must be <= limit[ when], got n")``."""
    limit = MAX_VOUSSOIRS if limit is None else limit
    if n > limit:
        raise InputError(f"{gen}: {name} must be <= {limit:,}{when}, got {n}")


def at_most(gen: str, request: str, count: int, limit: int | None = None,
            what: str = "blocks") -> None:
    """Refuse a ``request`` (its parameters and values, in the generator's words, e.g.
    ``"courses 200 x blocks_per_course 10"``) that would make more than ``limit``
    (default :data:`MAX_BLOCKS`) ``what``:
    ``InputError("gen: request would make count what; at most limit")``."""
    limit = MAX_BLOCKS if limit is None else limit
    if count > limit:
        raise InputError(f"{gen}: {request} would make {count:,} {what}; at most {limit:,}")


__all__ = ["MAX_ARC_SEGMENTS", "MAX_BLOCKS", "MAX_CAPPED_RING", "MAX_STACK",
           "MAX_VERTICAL_VOUSSOIRS", "MAX_VOUSSOIRS", "MAX_WALL_BLOCKS", "at_most",
           "count_at_most"]
