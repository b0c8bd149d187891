"""Shared fixtures: small scenes built in code, and paths to bundled and shared data."""

from __future__ import annotations

from pathlib import Path

import pytest

from rigidblocks.io.scene_file import scene_from_dict

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
SHARED = ROOT.parent / "shared"


def rect(x0, y0, w, h):
    return [[x0, y0], [x0 + w, y0], [x0 + w, y0 + h], [x0, y0 + h]]


def make_scene(blocks, **top):
    doc = {"format": "rigidblocks-scene", "version": 1, "dimension": 2, "blocks": blocks}
    doc.update(top)
    return scene_from_dict(doc)


@pytest.fixture
def block_on_base():
    """A b x h block on a wide support, unit weight 1, live horizontal body force."""

    from rigidblocks.generators.catalogue import block_on_base as build_block

    def build(b=1.0, h=2.0, friction=0.5, **extra):
        return build_block(b, h, friction, **extra)

    return build
