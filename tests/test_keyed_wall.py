"""The keyed (tongue-and-groove) wall: a generated structure of non-convex blocks whose
out-of-plane collapse multiplier is derived by hand (issue 18, item 5).

Hand derivation (see :func:`rigidblocks.generators.keyed.keyed_wall`, Notes): C courses of
height h (H = C h), thickness t, live body force lambda x weight out of plane (+y).
Every bed joint above the foundation is keyed, so no course can slide or rock on the
one below; the wall moves as one body on its plain foundation joint, of friction
f_base. Its mechanisms are sliding (lambda = f_base) and overturning about the edge
y = t of the foundation (the wall fills the box N L x t x H, so its centroid is at
height H/2 and mid-thickness: lambda W H/2 = W t/2, lambda = t/H). Hence
lambda* = min(f_base, t/H). The same wall of plain boxes (key_height = 0) also slides
on any bed joint between courses, at lambda = f: lambda* = min(f, f_base, t/H).

With C = 6, h = 0.2 (H = 1.2), t = 0.3: t/H = 1/4.
"""

from __future__ import annotations

import pytest

import rigidblocks as rb
from rigidblocks.cli.main import main
from rigidblocks.errors import InputError
from rigidblocks.generators import build
from rigidblocks.generators.keyed import keyed_wall
from rigidblocks.io.scene_file import dumps_scene, loads_json, scene_from_dict
from rigidblocks.scene.geometry import block_weights
from rigidblocks.scene.polyhedra import is_convex


@pytest.mark.parametrize(("f", "f_base", "keyed", "expected"), [
    (0.2, 0.8, True, 0.25),    # keys: the wall overturns, t/H
    (0.2, 0.8, False, 0.2),    # plain: it slides on a bed joint at f
    (0.2, None, True, 0.2),    # keys, uniform f: it slides on the foundation
    (0.6, 0.15, True, 0.15),   # keys, slippery foundation
])
def test_out_of_plane_collapse_matches_hand_derivation(f, f_base, keyed, expected):
    s = keyed_wall(courses=6, blocks_per_course=3, friction=f, base_friction=f_base,
                   key_height=0.05 if keyed else 0.0)
    res = rb.max_load_multiplier(s)
    assert res.status == "collapse"
    assert res.load_multiplier == pytest.approx(expected, rel=1e-6)


def test_units_are_non_convex_and_fill_the_box():
    """Middle-course units carry a tongue and a groove (non-convex); the wall's volume
    is that of the box N L x t x H (each tongue fills a groove), 3 x 0.4 x 0.3 x 1.2."""
    s = keyed_wall(courses=6, blocks_per_course=3, unit_weight=1.0)
    free = [b for b in s.blocks if not b.support]
    assert all(not is_convex(b) for b in free)
    w, _, _ = block_weights(s)
    assert w[~s.support_mask].sum() == pytest.approx(3 * 0.4 * 0.3 * 1.2, rel=1e-12)
    # a head joint between two units of a middle course is their whole non-convex
    # section, t h (the groove cut out and the tongue added have equal areas)
    con = rb.detect_contacts(s)
    head = [a for p, a in zip(con.block_pairs_ids(), con.areas, strict=True)
            if set(p) == {"c2b0", "c2b1"}]
    assert head == pytest.approx([0.3 * 0.2], rel=1e-12)


def test_registered_round_trips_and_cli(tmp_path):
    s = build("keyed_wall", courses=3, blocks_per_course=2)
    assert scene_from_dict(loads_json(dumps_scene(s))) == s
    out = tmp_path / "k.json"
    assert main(["example", "keyed_wall", "--courses", "3", "--base_friction", "0.8",
                 "-o", str(out)]) == 0
    assert rb.read_scene(out).joints


@pytest.mark.parametrize(("params", "word"), [
    ({"key_width": 0.3}, "key_width"),
    ({"key_height": 0.2}, "key_height"),
    ({"key_height": -0.1}, "key_height"),
    ({"load_direction": "up"}, "load_direction"),
])
def test_bad_parameters(params, word):
    with pytest.raises(InputError, match=word):
        keyed_wall(**params)


def test_associative_answers_on_keys_say_that_dilatancy_clamps_them():
    """In plane, along its keys, the keyed wall at f = 0.05 (foundation f = 1) carries
    lambda* = 1 with friction that dilates: a key cannot slide in its groove, since
    opening one side face closes the other, and the wall tips as one body about its
    foundation's end (lambda W H/2 = W L/2, the wall as long as high, 1.2 m: lambda = 1;
    sliding on the foundation, f = 1, gives 1 too). Dry joints that do not dilate slide
    at f = 0.05, as the plain wall does with either flow (a bed joint slides at
    lambda = f). The answer says so; the plain wall's does not."""
    keyed = keyed_wall(courses=6, blocks_per_course=3, friction=0.05, base_friction=1.0,
                       load_direction="in_plane")
    res = rb.max_load_multiplier(keyed)
    assert res.load_multiplier == pytest.approx(1.0, rel=1e-5)
    assert any("blocks touch on opposed faces" in n and "--flow non-associative" in n
               for n in res.notes)
    plain = keyed_wall(courses=6, blocks_per_course=3, friction=0.05, base_friction=1.0,
                       load_direction="in_plane", key_height=0.0)
    res = rb.max_load_multiplier(plain)
    assert res.load_multiplier == pytest.approx(0.05, rel=1e-5)
    assert not any("opposed faces" in n for n in res.notes)
    assert not any("opposed faces" in n for n in rb.check(keyed, load_factor=0.0,
                                                           flow="non-associative").notes)


def test_a_pair_of_keyed_blocks_is_named_once_with_its_faces(tmp_path, capsys):
    """Two keyed blocks touch on four faces (bed, key top and its two sides), four
    joints of one pair: the governing line named the pair four times in a row
    ("c0b0-c1b0 (sliding), c0b0-c1b0 (sliding), ..."); now once, with its faces."""
    from rigidblocks.answer import joint_list
    from rigidblocks.io import write_scene

    assert joint_list(["a-b", "a-b", "c-d"]) == "a-b (2 faces), c-d"
    keyed = keyed_wall(courses=6, blocks_per_course=3, friction=0.05, base_friction=1.0,
                       load_direction="in_plane")
    res = rb.max_load_multiplier(keyed, flow="non-associative")
    assert res.load_multiplier == pytest.approx(0.05, rel=1e-4)  # a bed joint slides at f
    path = tmp_path / "k.json"
    write_scene(keyed, path)
    assert main(["load", str(path), "--flow", "non-associative"]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines()
                if ln.startswith("governing"))
    assert "c0b0-c1b0 (sliding, 4 faces)" in line
    assert line.count("c0b0-c1b0") == 1


def test_a_key_in_its_groove_is_counted_as_one_joint(tmp_path, capsys):
    """Two blocks touching on several faces (a key in its groove: shoulders, the key's
    top and its two sides) are one joint. The keyed wall loaded along its length at f =
    0.2 without dilatancy slides on its keyed beds at lambda = 0.2 (the associative law
    locks them: the key's two sides cannot both open); its answer read "16 joints move:
    16 sliding" for 4 pairs of blocks, and with one unit free "1 sliding" read "4
    sliding (c0b0-c1b0 (4 faces))"."""
    import dataclasses

    import numpy as np

    wall = keyed_wall(courses=3, blocks_per_course=2, friction=0.2, base_friction=0.8,
                      load_direction="in_plane")
    one = keyed_wall(courses=2, blocks_per_course=1, friction=0.2, base_friction=0.8)
    one = dataclasses.replace(one, live_body_force=np.array([-1.0, 0.0, 0.0]), blocks=tuple(
        dataclasses.replace(b, support=b.support or b.id in ("c0b0", "c1b1"))
        for b in one.blocks))
    out = {}
    for name, scene in (("wall", wall), ("one", one)):
        path = tmp_path / f"{name}.json"
        path.write_text(dumps_scene(scene))
        main(["load", str(path), "--flow", "non-associative"])
        out[name] = capsys.readouterr().out
    assert "lambda* = 0.2," in out["wall"] and "lambda* = 0.2," in out["one"]
    assert "governing  4 joints move, on 16 faces: 16 sliding; fastest: " in out["wall"], \
        out["wall"]
    assert "governing  1 sliding (c0b0-c1b0 (4 faces)); 1 opening (c1b0-c1b1)" in out["one"], \
        out["one"]
