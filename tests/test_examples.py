"""Structure generators, the ``example`` command and the bundled example scenes."""

from __future__ import annotations

import math
import re

import pytest
from conftest import EXAMPLES

from rigidblocks import check, min_friction, read_scene
from rigidblocks.cli.main import main
from rigidblocks.errors import InputError
from rigidblocks.generators import GENERATORS, available, build
from rigidblocks.io.scene_file import dumps_scene

FAST = {"wall": {"courses": 3, "blocks_per_course": 3}}


@pytest.mark.parametrize("name", sorted(available()))
def test_every_generator_builds_a_valid_scene_with_a_live_load(name):
    scene = build(name, **FAST.get(name, {}))
    assert scene.dimension in (2, 3)
    assert scene.support_mask.any() and not scene.support_mask.all()
    assert scene.has_live_load
    # a seismic body force is for `load`: check and friction answer for the dead load
    # alone (README; keyed_wall wrote none, so that they answered at load factor 1)
    if scene.live_body_force is not None and any(scene.live_body_force):
        assert scene.load_factor == 0, name
    # a generated scene survives the file format unchanged
    from rigidblocks.io.scene_file import loads_json, scene_from_dict

    assert scene_from_dict(loads_json(dumps_scene(scene))) == scene


def test_registry_lists_parameters_with_defaults():
    params = {p.name: p.default for p in GENERATORS["arch"].params}
    assert params["thickness"] == 0.15 and params["joints"] == "radial"
    assert "wall" in GENERATORS


@pytest.mark.parametrize("name, params, word", [
    ("arch", {"voussoirs": 0}, "voussoirs"),
    ("arch", {"thickness": -0.1}, "thickness"),
    ("arch", {"thickness": 2.5}, "thickness"),
    ("arch", {"joints": "diagonal"}, "joints"),
    ("arch", {"shape": "pointed", "voussoirs": 7}, "even"),
    ("arch", {"shape": "pointed", "joints": "vertical"}, "radial"),
    ("arch", {"shape": "pointed", "voussoirs": 40, "thickness": 0.5}, "crown"),
    ("arch", {"shape": "segmental", "half_angle": 120}, "half_angle"),
    ("flat_arch", {"span": 0}, "span"),
    ("flat_arch", {"springing": "air"}, "springing"),
    ("corbel_arch", {"block_length": 0.1}, "block_length"),
    ("corbel_arch", {"courses": 1}, "courses"),
    ("corbel_arch", {"pattern": "inclined", "inclination": 60}, "inclination"),
    ("arpino_gate", {"joint_inclination": -1}, "joint_inclination"),
    ("reference", {"P": -1}, "P"),
    ("reference", {"friction": "lots"}, "friction"),
    ("arch", {"nonsense": 1}, "nonsense"),
])
def test_parameter_validation(name, params, word):
    with pytest.raises(InputError, match=word):
        build(name, **params)


def test_unknown_generator():
    with pytest.raises(InputError, match="unknown example"):
        build("cathedral")


def test_cli_list_names_no_empty_or_none_default(capsys):
    """`example --list` prints no "(default None)" or "(default )": such a parameter's
    help says what happens without it; the arch's voussoirs default to 15, 16 pointed."""
    assert main(["example", "--list"]) == 0
    out = capsys.readouterr().out
    assert "(default None)" not in out and "(default )" not in out
    assert "--voussoirs  number of voussoirs (default 15, 16 for a pointed arch)" in out
    assert len(build("arch").blocks) == 15 + 2
    assert len(build("arch", shape="pointed").blocks) == 16 + 2


def test_cli_list_and_write(tmp_path, capsys):
    assert main(["example", "--list"]) == 0
    out = capsys.readouterr().out
    for name in ("reference", "flat_arch", "arch", "corbel_arch", "arpino_gate"):
        assert f"{name}:" in out
    assert "--thickness" in out
    path = tmp_path / "a.json"
    assert main(["example", "arch", "--voussoirs", "9", "--thickness", "0.2",
                 "--friction", "infinite", "-o", str(path)]) == 0
    scene = read_scene(path)
    assert len(scene.blocks) == 9 + 2 and scene.friction == "infinite"
    assert path.read_text() == dumps_scene(scene)
    assert main(["example", "reference", "--self_weight", "true", "-o",
                 str(tmp_path / "r.json")]) == 0
    assert read_scene(tmp_path / "r.json").unit_weight == 20000.0


@pytest.mark.parametrize("argv", [
    ["example", "arch", "--voussoirs", "-2"],
    ["example", "arch", "--voussoirs", "many"],
    ["example", "arch", "--colour", "red"],
    ["example", "arch", "--thickness"],
    ["example", "nowhere"],
    ["example"],
])
def test_cli_bad_parameters_exit_2(argv, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("rigidblocks: error:") and err.count("\n") == 1


def _invalid(default):
    """A value no parameter with this default takes (booleans, counts >= 1, finite
    sizes, a choice among words, the wall's openings and the stack's offsets)."""
    if isinstance(default, bool):
        return "maybe"
    if isinstance(default, int) or default is None:  # None: a count or a friction
        return "-1"
    if isinstance(default, float):
        return "nan"
    return "nope"


#: the options that make a parameter count (it is ignored otherwise)
_MODE = {("reference", "unit_weight"): ["--self-weight", "true"],
         ("arch", "half_angle"): ["--shape", "segmental"],
         ("arch", "pointedness"): ["--shape", "pointed"],
         ("corbel_arch", "inclination"): ["--pattern", "inclined"]}
_EVERY_PARAMETER = [(g.name, p.name) for g in available().values() for p in g.params]


@pytest.mark.parametrize("name, param", _EVERY_PARAMETER,
                         ids=[f"{g}-{p}" for g, p in _EVERY_PARAMETER])
def test_cli_error_names_the_option_as_typed(name, param, capsys):
    """`example NAME --some-param BAD` says `example NAME: --some-param ...` on one line
    and exits 2: the option the user typed, not the Python function or argument
    (`running_bond_wall: blocks_per_course must be ...`)."""
    gen = GENERATORS[name]
    option = "--" + param.replace("_", "-")
    value = _invalid(next(p.default for p in gen.params if p.name == param))
    assert main(["example", name, *_MODE.get((name, param), []), option, value]) == 2
    err = capsys.readouterr().err
    head = f"rigidblocks: error: example {name}: {option} "
    assert err.startswith(head) and err.count("\n") == 1, err
    function, rest = gen.target.split(":")[1], err[len(head):]
    assert f"{function}:" not in rest, err
    # every parameter the message names is an option, not a plain word
    plain = {p.name for p in gen.params} & set(re.findall(r"(?<![-\w'])\w+", rest))
    assert not plain, err


@pytest.mark.parametrize("argv, line", [
    (["wall", "--blocks_per_course=0"],
     "example wall: --blocks_per_course must be an integer >= 1, got 0"),
    (["corbel_dome", "--overhang", "0.6"],  # a parameter not typed: as --list spells it
     "example corbel_dome: --overhang must be < --ring_thickness (0.5) so that each ring "
     "overlaps the one below, got 0.6"),
    # every parameter a message names is an option, those without an underscore too
    (["keyed_wall", "--key-width", "0.4", "--thickness", "0.3"],
     "example keyed_wall: --key-width must be < --thickness, got 0.4 >= 0.3"),
    (["corbel_arch", "--block-length", "0.1"],
     "example corbel_arch: --block-length must exceed the overhang --opening / (2 (--courses "
     "- 1)) = 0.2, got 0.1"),
    (["barrel_vault", "--bond", "running", "--voussoirs", "1"],
     "example barrel_vault: --voussoirs must be >= 2 with --bond 'running', got 1"),
    (["keyed_wall", "--base-friction", "-1"],  # not the scene's friction
     "example keyed_wall: --base-friction must be >= 0, got -1.0"),
    (["box_stack", "--offset", "1.5"],
     "example box_stack: --offset: box1 does not overlap box0 (shift (1.5, 0), a box is "
     "1 x 1)"),
    # N C + floor(C/2) + 1 = 10 x 1e8 + 5e7 + 1 (walls.wall_blocks): refused before any
    # block is built (the wall used to fill the memory)
    (["wall", "--courses", "100000000", "--blocks-per-course", "10"],
     "example wall: --courses 100000000 x --blocks-per-course 10 would make 1,050,000,001 "
     "blocks; at most 1,000,000"),
    (["wall3d", "--courses=40000"],  # 4 x 40,000 + 20,000 + 1
     "example wall3d: --courses 40000 x --blocks_per_course 4 would make 180,001 blocks; "
     "at most 100,000"),
    (["flat_arch", "--voussoirs", "20000"],  # 29 s and 1.4 GB to build
     "example flat_arch: --voussoirs must be <= 10,000, got 20000"),
    (["arch", "--arc-points", "100000000"],  # 15 voussoirs of 1e8 segments each
     "example arch: --voussoirs 15 x --arc-points 100000000 would make 1,500,000,000 arc "
     "segments; at most 1,000,000"),
    (["arch", "--joints", "vertical", "--voussoirs", "1001"],
     "example arch: --voussoirs must be <= 1,000 with --joints 'vertical', got 1001"),
    (["corbel_dome", "--blocks-per-ring", "65"],
     "example corbel_dome: --blocks-per-ring must be <= 64 with --cap true (the keystone "
     "over them has 2 x --blocks-per-ring sides), got 65"),
])
def test_cli_error_lines(argv, line, capsys):
    assert main(["example", *argv]) == 2
    assert capsys.readouterr().err == f"rigidblocks: error: {line}\n"


#: each generator with parameters that make a small scene of it, and the bound it is held
#: to (the module and name of the constant); the reference model has no size parameter
_SIZED = [
    ("wall", {"courses": 3, "blocks_per_course": 4}, "walls.MAX_WALL_BLOCKS",
     "courses 3 x blocks_per_course 4"),
    ("wall3d", {"courses": 3, "blocks_per_course": 2}, "limits.MAX_BLOCKS",
     "courses 3 x blocks_per_course 2"),
    ("keyed_wall", {"courses": 2, "blocks_per_course": 2}, "limits.MAX_BLOCKS",
     "courses 2 x blocks_per_course 2"),
    ("corbel_arch", {"courses": 3}, "limits.MAX_BLOCKS", "courses 3"),
    ("arpino_gate", {"courses": 3}, "limits.MAX_BLOCKS", "courses 3"),
    ("box_stack", {"boxes": 3}, "solids.MAX_STACK", "boxes 3"),
    ("corbel_dome", {"rings": 2, "blocks_per_ring": 4}, "limits.MAX_BLOCKS",
     "rings 2 x blocks_per_ring 4"),
    ("corbel_dome", {"rings": 2, "blocks_per_ring": 4, "cap": False}, "limits.MAX_BLOCKS",
     "rings 2 x blocks_per_ring 4"),
    ("barrel_vault", {"rings": 3, "voussoirs": 4}, "limits.MAX_BLOCKS", "rings 3 x voussoirs 4"),
    ("barrel_vault", {"rings": 3, "voussoirs": 4, "bond": "running"}, "limits.MAX_BLOCKS",
     "rings 3 x voussoirs 4"),
]


#: the arches' size is their number of voussoirs, a dome's also the blocks in a ring
#: (the parameter, the bound, and the words after it)
_FANS = [
    ("arch", {"voussoirs": 5}, "voussoirs", "limits.MAX_VOUSSOIRS", ""),
    ("arch", {"shape": "pointed", "voussoirs": 6}, "voussoirs", "limits.MAX_VOUSSOIRS", ""),
    ("arch", {"voussoirs": 5, "joints": "vertical"}, "voussoirs",
     "arches.MAX_VERTICAL_VOUSSOIRS", " with joints 'vertical'"),
    ("stocky_arch", {"voussoirs": 5}, "voussoirs", "limits.MAX_VOUSSOIRS", ""),
    ("flat_arch", {"voussoirs": 5}, "voussoirs", "limits.MAX_VOUSSOIRS", ""),
    ("barrel_vault", {"voussoirs": 5, "rings": 2}, "voussoirs", "limits.MAX_VOUSSOIRS", ""),
    ("corbel_dome", {"blocks_per_ring": 5, "cap": False}, "blocks_per_ring",
     "limits.MAX_VOUSSOIRS", ""),
    ("corbel_dome", {"blocks_per_ring": 5}, "blocks_per_ring", "solids.MAX_CAPPED_RING",
     " with cap true (the keystone over them has 2 x blocks_per_ring sides)"),
]


def test_every_generator_with_a_size_has_a_bound():
    assert {name for name, *_ in _SIZED + _FANS} == set(available()) - {"reference"}


@pytest.mark.parametrize("name, params, param, bound, when", _FANS,
                         ids=[f"{n}-{'-'.join(map(str, p.values()))}" for n, p, *_ in _FANS])
def test_fans_of_blocks_bound_their_number(name, params, param, bound, when, monkeypatch):
    """A fan of thin blocks round a centre (an arch's voussoirs, a dome's ring) is
    refused above its bound, at the bound built."""
    n = params[param]
    target = f"rigidblocks.generators.{bound}"
    monkeypatch.setattr(target, n)
    assert build(name, **params)
    monkeypatch.setattr(target, n - 1)
    with pytest.raises(InputError, match=re.escape(
            f": {param} must be <= {n - 1}{when}, got {n}")):
        build(name, **params)


@pytest.mark.parametrize("name, params, bound, asked", _SIZED,
                         ids=[f"{n}-{'-'.join(map(str, p.values()))}" for n, p, *_ in _SIZED])
def test_generator_counts_its_blocks_before_building(name, params, bound, asked,
                                                     monkeypatch):
    """With the bound set to the scene's own number of blocks the scene is built; one
    less, and it is refused naming its parameters and that number: the count made
    before building is the count built."""
    n = len(build(name, **params).blocks)
    module, constant = bound.split(".")
    monkeypatch.setattr(f"rigidblocks.generators.{module}.{constant}", n)
    assert len(build(name, **params).blocks) == n
    monkeypatch.setattr(f"rigidblocks.generators.{module}.{constant}", n - 1)
    with pytest.raises(InputError, match=re.escape(
            f": {asked} would make {n:,} blocks; at most {n - 1:,}")):
        build(name, **params)



def _example_files():
    return sorted(EXAMPLES.glob("*.json"))


def test_the_bundled_examples_exist():
    names = {p.name for p in _example_files()}
    assert {"arch.json", "reference.json", "reference_self_weight.json",
            "flat_arch_vertical.json", "flat_arch_radial.json", "stocky_arch.json",
            "corbel_arch_horizontal.json", "corbel_arch_inclined.json",
            "arpino_gate.json"} <= names


@pytest.mark.parametrize("path", _example_files(), ids=lambda p: p.name)
def test_example_file_is_canonical_and_runs(path, capsys):
    scene = read_scene(path)
    assert path.read_text() == dumps_scene(scene)
    for cmd in ("check", "friction"):
        assert main([cmd, str(path), "--json", "--load-factor", "0"]) == 0
    capsys.readouterr()


def test_readme_first_command(capsys):
    assert main(["load", str(EXAMPLES / "arch.json"), "--json"]) == 0
    assert '"status": "collapse"' in capsys.readouterr().out


def test_reference_model_without_self_weight():
    """Seed (reference model, Fig. 4a): P = 100 N, H = 50 N, no self-weight -> f = 0.5
    (26.56 deg). By hand: each central block carries N = P/2 on its top and bottom bed
    joints, the vertical joint opens, so H = f (P/2 + P/2) and f* = H/P = 0.5."""
    r = min_friction(build("reference"))
    assert r.status == "stable"
    assert r.friction_factor == pytest.approx(0.5, rel=1e-6)
    assert r.friction_angle_deg == pytest.approx(math.degrees(math.atan(0.5)), abs=1e-4)


def test_reference_model_with_self_weight():
    """Seed: with self-weight f = 0.25 (14.03 deg). By hand f* = H / (P + W_t + W_c) with
    W_t = 20000 N/m^3 x 0.20 x 0.05 x 0.25 m^3 = 50 N and W_c = 20000 x 0.10 x 0.10 x 0.25
    = 50 N, so f* = 50 / 200 = 0.25. With other sizes the same formula holds: a top block
    0.1 m high weighs 100 N and f* = 50 / 250 = 0.2."""
    r = min_friction(build("reference", self_weight=True))
    assert r.friction_factor == pytest.approx(0.25, rel=1e-6)
    r2 = min_friction(build("reference", self_weight=True, top_height=0.1))
    assert r2.friction_factor == pytest.approx(0.2, rel=1e-6)


def test_flat_arch_radial_joints_need_less_friction_than_vertical():
    """Seed, Fig. 6: radial joints need a (23 times) lower friction angle than vertical
    joints. The factor depends on unpublished geometry; the ordering does not."""
    v = min_friction(build("flat_arch", joints="vertical"), load_factor=0, state=False)
    r = min_friction(build("flat_arch", joints="radial"), load_factor=0, state=False)
    assert v.status == r.status == "stable"
    assert r.friction_factor < v.friction_factor


def test_flat_arch_vertical_joints_shear_at_skewbacks_by_hand():
    """Vertical joints, bonded piers: the skewback carries V = W/2 and, at the largest
    thrust the piers allow, H; with the piers bonded the largest thrust is bounded by
    pier overturning about the outer toe, so f* = (W/2) / H_max, and the governing joints
    are the two skewbacks."""
    r = min_friction(build("flat_arch", joints="vertical", bonded_piers=True),
                     load_factor=0, state=False)
    assert {tuple(sorted(j)) for j in r.governing_joints} == {("pier_l", "v1"),
                                                              ("pier_r", "v9")}


def test_semicircular_arch_needs_friction_only_at_horizontal_springings():
    """Radial joints on abutments: the springing joints are horizontal, so the minimum
    friction is H / (W/2) at the springings, larger than at any inclined joint."""
    r = min_friction(build("arch"), load_factor=0, state=False)
    assert {tuple(sorted(j)) for j in r.governing_joints} == {("abutment_r", "v1"),
                                                              ("abutment_l", "v15")}


def test_corbel_arch_inclined_joints_need_less_friction():
    """Seed Fig. 7b/7c: inclining the bed joints towards the opening lowers the friction
    the corbel arch needs (the crown thrust meets the joints closer to their normal)."""
    h = min_friction(build("corbel_arch"), load_factor=0, state=False)
    i = min_friction(build("corbel_arch", pattern="inclined"), load_factor=0, state=False)
    assert i.friction_factor < h.friction_factor


def test_admissible_with_infinite_friction():
    for name in ("arch", "stocky_arch", "flat_arch", "corbel_arch", "arpino_gate"):
        assert check(build(name), friction="infinite", load_factor=0, state=False).admissible


def test_old_package_name_is_a_deprecated_alias():
    """rigidblocks.examples (the generators' former name) still imports, with its
    submodules and names, as the very objects of rigidblocks.generators."""
    import importlib
    import sys
    import warnings

    import rigidblocks.generators as gen
    import rigidblocks.generators.walls as walls

    for name in [m for m in sys.modules if m.startswith("rigidblocks.examples")]:
        del sys.modules[name]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        old = importlib.import_module("rigidblocks.examples")
    assert any(issubclass(w.category, DeprecationWarning) for w in caught)
    assert old.build is gen.build and old.GENERATORS is gen.GENERATORS
    assert importlib.import_module("rigidblocks.examples.walls") is walls
    from rigidblocks.examples.walls import running_bond_wall

    assert running_bond_wall is walls.running_bond_wall


def test_every_generator_parameter_has_its_help():
    """`rigidblocks example NAME --help` lists each parameter with what it is: the
    reference model's bond_tensile_strength and bond_cohesion were listed bare."""
    from rigidblocks.generators import GENERATORS

    bare = [f"{g.name} {p.name}" for g in GENERATORS.values() for p in g.params
            if not p.help.strip()]
    assert bare == []
