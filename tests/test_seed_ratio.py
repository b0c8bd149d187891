"""Where the seed's ratio of 23 falls on the flat arch (seed Fig. 6: radial joints need
a friction angle 23 times lower than vertical joints), docs/seed-examples.md.

The generator docs/make_seed_examples.py locates each crossing of 23 by bisection on
the radial joints' centre depth c. Checked here, on the cheapest reading (the friction
demand of the least-energy state, one solve per scene) on fixed abutments, without the
generator's own side test: at the two ends of each located interval, 1e-3 m apart,
the ratio of friction angles computed directly from ``rigidblocks.check`` lies on
either side of 23; and the page shows the crossings this run locates.
"""

from __future__ import annotations

import importlib.util
import math
import sys

import pytest
from conftest import ROOT

import rigidblocks as rb
from rigidblocks.generators import build


@pytest.fixture(scope="module")
def seed():
    spec = importlib.util.spec_from_file_location(
        "make_seed_examples", ROOT / "docs" / "make_seed_examples.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    yield module
    sys.modules.pop(spec.name, None)


def demand_deg(**params) -> float:
    """The friction angle (deg) the least-energy no-tension state of the flat arch
    needs under self-weight."""
    f = rb.check(build("flat_arch", springing="abutments", **params),
                 friction="infinite", load_factor=0.0).friction_demand[0]
    return math.degrees(math.atan(f))


@pytest.fixture(scope="module")
def sweep(seed):
    return seed.ratio_sweep("demand", "fixed abutments")


def test_each_located_crossing_of_23_is_one(seed, sweep):
    vertical = demand_deg(joints="vertical")
    assert sweep.crossings, "the demand on fixed abutments crosses 23 (page)"
    for x in sweep.crossings:
        assert x.sb is not None and 0.0 < x.b - x.a <= seed.RATIO_TOL
        below, above = (x.a, x.b) if x.sa == -1 else (x.b, x.a)
        assert vertical / demand_deg(centre_depth=below) < 23.0
        assert vertical / demand_deg(centre_depth=above) > 23.0


def test_the_page_shows_the_crossings_this_run_locates(seed, sweep):
    text = (ROOT / "docs" / "seed-examples.md").read_text()
    assert seed.RATIO_HEADING in text and f"]({seed.RATIO_CHART})" in text
    assert (ROOT / "docs" / seed.RATIO_CHART).is_file()
    row = "| " + " | ".join(seed.ratio_row(sweep)) + " |"
    assert row in text
