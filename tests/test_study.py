"""Parametric studies (rigidblocks.study): executors, failures, resume, specs, CLI.

Closed forms used (seed paper /work/shared/seed/000_12fc8c16f038a4e5.txt, section on
the reference model): four blocks, a top block carrying P, two central blocks each
pulled outwards by H, on a support. Without self-weight each central block has N = P/2
on its top and bottom joints, so sliding needs H <= f (P/2 + P/2): f* = H / P, the
seed's f = 0.5 (26.56 deg) for P = 100 N, H = 50 N; with the blocks' self-weight (top
block 50 N, central blocks 50 N each) f* = H / (P + W_top + W_c) = 50 / 200 = 0.25, the
seed's 14.03 deg. The maximum multiplier of H at friction f is fP / H.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pandas as pd
import pytest
from conftest import EXAMPLES, ROOT

import rigidblocks as rb
from rigidblocks import study
from rigidblocks.cli.main import main
from rigidblocks.errors import InputError
from rigidblocks.generators import build

ANSWERS = ["status", "error", "check_status", "admissible", "violation",
           "min_friction_status", "friction_factor", "friction_angle_deg"]

# 50 flat arches on piers (seed Fig. 6 family): 5 voussoir counts x 10 load factors of
# the live horizontal body force; about one in five cannot stand
FLAT_GRID = {"voussoirs": [3, 4, 5, 6, 7],
             "load_factor": [0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45]}


def flat_study(**kw):
    return study.run("flat_arch", grid=FLAT_GRID, analyses=["check"], progress=False,
                     **kw)


def same_answers(a: pd.DataFrame, b: pd.DataFrame, tol: float = 1e-9) -> None:
    """Same cases with the same statuses and numbers (to ``tol``), case by case."""
    a = a.sort_values("case_id").reset_index(drop=True)
    b = b.sort_values("case_id").reset_index(drop=True)
    assert list(a["case_id"]) == list(b["case_id"])
    for col in ANSWERS:
        if col not in a.columns:
            assert col not in b.columns
            continue
        x, y = a[col], b[col]
        if col in ("violation", "friction_factor", "friction_angle_deg"):
            x, y = x.to_numpy(float), y.to_numpy(float)
            assert np.array_equal(np.isnan(x), np.isnan(y)), col
            ok = ~np.isnan(x)
            assert np.allclose(x[ok], y[ok], rtol=tol, atol=tol), col
        else:
            assert list(x.astype(object).where(x.notna(), None)) == \
                list(y.astype(object).where(y.notna(), None)), col


# -- executors -------------------------------------------------------------------------
@pytest.fixture(scope="module")
def dask_client():
    import dask.distributed as distributed

    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                       dashboard_address=None)
    client = distributed.Client(cluster)
    yield client
    client.close()
    cluster.close()


def test_executors_agree_case_by_case(dask_client):
    """One process, 2 local processes and a 2-worker Dask LocalCluster give the same
    verdict and violation for each of 50 flat arches, to 1e-9."""
    one = flat_study(workers=1)
    assert len(one.frame) == 50 and one.n_failed == 0
    verdicts = one.frame["check_status"].value_counts()
    assert verdicts["admissible"] > 10 and verdicts["inadmissible"] > 5
    procs = flat_study(workers=2, batch_size=4)
    dask = flat_study(client=dask_client, batch_size=4)
    assert procs.executor == "2 processes" and dask.executor == "dask"
    same_answers(one.frame, procs.frame)
    same_answers(one.frame, dask.frame)
    # the rows come back in case order whatever the order they finished in
    assert list(dask.frame["case"]) == list(range(50))
    # and the answers are those of the direct call on the generated scene
    for k in (7, 48):
        row = one.frame.iloc[k]
        scene = build("flat_arch", voussoirs=int(row["voussoirs"]))
        direct = rb.check(scene, load_factor=float(row["load_factor"]), state=False)
        assert row["check_status"] == direct.status
        assert row["violation"] == pytest.approx(direct.violation, rel=1e-9, abs=1e-12)


# -- failures ----------------------------------------------------------------------------
def test_an_analysis_that_raises_leaves_the_others_answered():
    """At f = 0.3 the 9-voussoir arch does not stand at min_thickness's upper bound
    (thickness 1), which raises; the check after it was left empty as if the case had
    failed as a whole. Now that analysis alone reads failed, the others are answered and
    match direct calls."""
    res = study.run("arch", cases=[{"voussoirs": 9}],
                    parameters={"friction": 0.3, "load_factor": 0.0},
                    analyses=["min_friction", "min_thickness", "check"], progress=False)
    row = res.frame.iloc[0]
    assert row["status"] == "failed" and row["min_thickness_status"] == "failed"
    assert row["error"].startswith("min_thickness: InputError: min_thickness: arch is not "
                                   "admissible at the upper bound"), row["error"]
    assert pd.isna(row["min_thickness"])
    scene = build("arch", voussoirs=9, friction=0.3)
    direct = rb.check(scene, load_factor=0.0, state=False)
    assert row["check_status"] == direct.status and \
        bool(row["admissible"]) == (direct.status == "admissible")
    f = rb.min_friction(scene, load_factor=0.0, state=False)
    assert row["friction_factor"] == pytest.approx(f.friction_factor, rel=1e-9)


def test_bad_cases_are_recorded_and_the_rest_correct():
    """Voussoir counts the generators reject (0, -2; an odd count for a pointed arch)
    fail with the generator's message; the other cases match direct calls."""
    cases = [{"shape": "semicircular", "voussoirs": 5}, {"shape": "semicircular",
                                                         "voussoirs": 0},
             {"shape": "pointed", "voussoirs": 6}, {"shape": "pointed", "voussoirs": 7},
             {"shape": "semicircular", "voussoirs": -2},
             {"shape": "segmental", "voussoirs": 4}]
    res = study.run("arch", cases=cases, parameters={"load_factor": 0.0, "arc_points": 2},
                    analyses=["min_friction", "check"], workers=2, batch_size=2,
                    progress=False)
    df = res.frame
    assert list(df["status"]) == ["ok", "failed", "ok", "failed", "failed", "ok"]
    assert res.n_failed == 3
    assert df.loc[1, "error"].startswith("InputError: arch: voussoirs")
    assert "voussoirs must be an even number" in df.loc[3, "error"]
    assert df.loc[df["status"] == "failed", "friction_factor"].isna().all()
    for i in (0, 2, 5):
        c = cases[i]
        scene = build("arch", arc_points=2, **c)
        direct = rb.min_friction(scene, load_factor=0.0, state=False)
        assert df.loc[i, "friction_factor"] == pytest.approx(direct.friction_factor,
                                                             rel=1e-9)
        assert df.loc[i, "check_status"] == rb.check(scene, load_factor=0.0,
                                                     state=False).status
        assert pd.isna(df.loc[i, "error"])


# -- closed forms -------------------------------------------------------------------------
def test_reference_model_closed_form_in_a_study():
    """Seed reference model: f* = H / P (0.5 at H = 50, P = 100) and lambda* = f P / H."""
    H = [10.0, 25.0, 50.0, 80.0]
    res = study.run("reference", grid={"H": H}, parameters={"P": 100.0, "friction": 0.6},
                    analyses=["min_friction", "max_load_multiplier"], workers=1,
                    progress=False)
    df = res.frame
    assert np.allclose(df["friction_factor"], np.array(H) / 100.0, rtol=1e-6)
    assert df.loc[2, "friction_angle_deg"] == pytest.approx(26.565, abs=1e-3)
    assert np.allclose(df["load_multiplier"], 0.6 * 100.0 / np.array(H), rtol=1e-6)
    sw = study.run("reference", cases=[{"self_weight": True}], analyses=["min_friction"],
                   workers=1, progress=False).frame
    assert sw.loc[0, "friction_factor"] == pytest.approx(0.25, rel=1e-6)
    assert sw.loc[0, "friction_angle_deg"] == pytest.approx(14.036, abs=1e-3)


def test_scene_file_source_with_friction_override(tmp_path):
    """examples/reference.json (H = 50 N, P = 100 N, no self-weight) is admissible at
    load factor 1 exactly when f >= 0.5; at load factor 0 always (no shear)."""
    fr = [0.3, 0.49, 0.51, 0.8, "infinite"]
    res = study.run(str(EXAMPLES / "reference.json"),
                    grid={"load_factor": [1.0, 0.0], "friction": fr},
                    analyses=["check"], workers=1, progress=False,
                    output=tmp_path / "ref.csv")
    df = pd.read_csv(tmp_path / "ref.csv")
    assert res.n_cases == len(df) == 10
    assert list(df["check_status"]) == ["inadmissible"] * 2 + ["admissible"] * 8
    # (numbers, inf for "infinite": a column of text, where d[d.friction == 0.5] found
    # nothing)
    assert list(df["friction"])[:5] == [0.3, 0.49, 0.51, 0.8, math.inf]
    assert res.frame["friction"].dtype.kind == "f"
    with pytest.raises(InputError, match="min_thickness needs a generator"):
        study.make_sweep(str(EXAMPLES / "reference.json"), grid={"friction": [0.5]},
                         analyses=["min_thickness"])


def test_flow_is_a_sweep_parameter(tmp_path):
    """A 1 x 2 block on a base (f = 0.3, horizontal body force): both flow rules give
    lambda* = min(f, b/h) = 0.3 (docs/validation.md; the non-associative law only
    changes what a pinched joint can carry). A misspelt flow is refused at expansion."""
    from conftest import make_scene, rect

    path = tmp_path / "block.json"
    rb.write_scene(make_scene([
        {"id": "base", "vertices": rect(-2, -1, 5, 1), "support": True},
        {"id": "B", "vertices": rect(0, 0, 1, 2)},
    ], unit_weight=1.0, friction=0.3, live_body_force=[1, 0]), path)
    res = study.run(str(path), grid={"flow": ["associative", "non-associative"]},
                    analyses=["max_load_multiplier"], workers=1, progress=False)
    df = res.frame
    assert list(df["flow"]) == ["associative", "non-associative"]
    assert np.allclose(df["load_multiplier"], 0.3, rtol=1e-4)
    with pytest.raises(InputError, match="non-associative"):
        study.make_sweep(str(path), grid={"flow": ["nonassociative"]},
                         analyses=["max_load_multiplier"])


# -- resume -------------------------------------------------------------------------------
class Stop(Exception):
    pass


def stop_after(n: int):
    seen = []

    def hook(row):
        seen.append(row["case_id"])
        if len(seen) == n:
            raise Stop(f"stopped after {n} cases")
    return hook, seen


@pytest.mark.parametrize("ext,workers", [(".parquet", 1), (".csv", 2)])
def test_resume_after_interruption(tmp_path, ext, workers):
    """A study stopped after 7 cases keeps them; the rerun runs only the others, and the
    output holds each case once, equal to a clean run."""
    grid = {"voussoirs": [3, 5, 7, 9], "load_factor": [0.0, 0.1, 0.2, 0.4]}
    kw = dict(grid=grid, analyses=["check"], progress=False, workers=workers,
              batch_size=3)
    out = tmp_path / f"r{ext}"
    hook, seen = stop_after(7)
    with pytest.raises(Stop):
        study.run("flat_arch", output=out, on_case=hook, flush_every=0.0, **kw)
    parts = list((tmp_path / f"r{ext}.parts").glob(f"*{ext}"))
    kept = pd.concat([pd.read_parquet(p) if ext == ".parquet" else
                      pd.read_csv(p, dtype={"case_id": str}) for p in parts])
    assert len(kept) >= 7 and set(seen) <= set(kept["case_id"])
    ran = []
    res = study.run("flat_arch", output=out, on_case=lambda r: ran.append(r["case_id"]),
                    **kw)
    assert res.n_skipped == len(kept) and res.n_run == 16 - len(kept)
    assert not set(ran) & set(kept["case_id"])
    assert not (tmp_path / f"r{ext}.parts").exists()
    final = pd.read_parquet(out) if ext == ".parquet" else pd.read_csv(
        out, dtype={"case_id": str})
    assert len(final) == 16 and final["case_id"].is_unique
    assert list(final["case"]) == list(range(16))
    clean = study.run("flat_arch", output=tmp_path / f"clean{ext}", **kw)
    same_answers(final, clean.frame)
    # a third run has nothing to do
    again = study.run("flat_arch", output=out, **kw)
    assert again.n_run == 0 and len(again.frame) == 16
    # another sweep is refused on this output
    with pytest.raises(InputError, match="another sweep"):
        study.run("flat_arch", output=out, **{**kw, "grid": {"voussoirs": [11]}})


# -- cases, random, plot -------------------------------------------------------------------
def test_expand_cases_grid_order_and_random_seed():
    g = study.expand_cases(grid={"a": [1, 2], "b": ["x", "y", "z"]}, parameters={"c": 0})
    assert g[:2] == [{"c": 0, "a": 1, "b": "x"}, {"c": 0, "a": 1, "b": "y"}]
    assert len(g) == 6
    spec = {"samples": 40, "seed": 3, "uniform": {"centre_depth": [0.5, 4.0]},
            "integers": {"voussoirs": [3, 9]}}
    r1, r2 = study.expand_cases(random=spec), study.expand_cases(random=spec)
    assert r1 == r2 and len(r1) <= 40
    assert all(0.5 <= c["centre_depth"] < 4.0 and 3 <= c["voussoirs"] <= 9 for c in r1)
    assert {c["voussoirs"] for c in r1} == set(range(3, 10))  # 40 draws cover 7 values
    assert r1 != study.expand_cases(random={**spec, "seed": 4})
    with pytest.raises(InputError, match="exactly one"):
        study.expand_cases(grid={"a": [1]}, cases=[{"a": 2}])


def test_plot_friction_angle_vs_joint_inclination():
    import matplotlib

    matplotlib.use("Agg")
    res = study.run("flat_arch", grid={"voussoirs": [3, 5, 0], "centre_depth": [1.0, 2.0]},
                    parameters={"load_factor": 0.0}, workers=1, progress=False)
    ax = res.plot(x="centre_depth", y="friction_angle_deg", hue="voussoirs")
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    # the failed voussoirs = 0 cases: no number, marked at the foot of the axes in their
    # line's colour and counted in a note (they were left out without a word)
    # (its legend entry says it has no number: it had a marker and nothing to see)
    zero = "voussoirs = 0 (no number: x at the foot)"
    assert set(lines) >= {zero, "voussoirs = 3", "voussoirs = 5"}
    assert np.isnan(lines[zero].get_ydata().astype(float)).all()
    marks = [ln for ln in ax.get_lines() if ln.get_marker() == "x"]
    assert len(marks) == 1 and list(marks[0].get_xdata()) == [1.0, 2.0]
    assert marks[0].get_color() == lines[zero].get_color()
    assert [t.get_text() for t in ax.texts] == [
        "no friction_angle_deg (x on the axis): 2 failed"]
    assert ax.get_xlabel() == "centre_depth"
    y = lines["voussoirs = 3"].get_ydata()
    assert np.allclose(y, res.frame["friction_angle_deg"].iloc[:2])
    with pytest.raises(InputError, match="no column"):
        res.plot(x="nope", y="friction_factor")
    # a case without a number between two with one breaks the line there (it was drawn
    # straight across, as if it were data)
    frame = res.frame[res.frame["voussoirs"] == 3].copy()
    mid = frame.iloc[:1].assign(centre_depth=1.5, friction_angle_deg=np.nan,
                                min_friction_status="undecided")
    ax = study.plot(pd.concat([frame, mid]), x="centre_depth", y="friction_angle_deg")
    line = ax.get_lines()[0]
    assert list(line.get_xdata()) == [1.0, 1.5, 2.0]
    assert np.isnan(line.get_ydata().astype(float)[1])
    assert [t.get_text() for t in ax.texts] == [
        "no friction_angle_deg (x on the axis): 1 undecided"]


# -- spec files and the CLI ---------------------------------------------------------------
def write(tmp_path, doc, name="s.json"):
    p = tmp_path / name
    p.write_text(json.dumps(doc))
    return p


BASE = {"format": "rigidblocks-sweep", "version": 1, "generator": "flat_arch",
        "grid": {"voussoirs": [3]}, "analyses": ["min_friction"]}


@pytest.mark.parametrize("change,match", [
    ({"colour": 1}, r'unknown key "colour"'),
    ({"generator": "bridge"}, r"unknown example 'bridge'"),
    ({"grid": {"vousoirs": [3]}}, r"grid\.vousoirs: unknown parameter 'vousoirs'"),
    ({"grid": {"voussoirs": [2.5]}}, r"voussoirs \(case 0\): expected an integer"),
    ({"grid": {"voussoirs": 3}}, r"grid\.voussoirs: expected a list"),
    ({"analyses": ["min_fricton"]}, r"analyses\[0\]: unknown analysis 'min_fricton'"),
    ({"analyses": [{"analysis": "min_thickness", "step": 1}]}, r'unknown option "step"'),
    ({"format": "rigidblocks-scene"}, r'"format" must be'),
    ({"random": {"samples": 3, "seed": 1}}, r"exactly one of grid, cases, random"),
    ({"cases": [{"voussoirs": 3}], "grid": None}, r'"grid": expected an object'),
    ({"parameters": {"friction": -1}}, r"must be >= 0"),
])
def test_spec_errors_name_file_and_key(tmp_path, change, match):
    p = write(tmp_path, {**BASE, **change})
    with pytest.raises(InputError, match=match) as err:
        study.read_spec(p)
    msg = str(err.value)
    assert msg.startswith(str(p)) and "\n" not in msg


def test_spec_random_and_scene(tmp_path):
    doc = {**BASE, "grid": None}
    del doc["grid"]
    doc["random"] = {"samples": 5, "seed": 0, "uniform": {"centre_depth": [1.0, 2.0]}}
    sw = study.read_spec(write(tmp_path, doc))
    assert len(sw.cases) == 5 and sw.generator == "flat_arch"
    scene_doc = {"format": "rigidblocks-sweep", "version": 1,
                 "scene": str(EXAMPLES / "reference.json"),
                 "cases": [{"friction": 0.4}, {"friction": "infinite"}],
                 "analyses": ["check"]}
    sw = study.read_spec(write(tmp_path, scene_doc, "scene.json"))
    assert sw.scene is not None and sw.cases[1]["friction"] == "infinite"
    bad = {**scene_doc, "cases": [{"voussoirs": 3}]}
    with pytest.raises(InputError, match="unknown parameter 'voussoirs' for a scene"):
        study.read_spec(write(tmp_path, bad, "bad.json"))


def test_cli_sweep_end_to_end(tmp_path, capsys):
    spec = EXAMPLES / "sweeps" / "flat_arch.json"
    out = tmp_path / "flat.parquet"
    assert main(["sweep", str(spec), "-o", str(out), "--workers", "1",
                 "--no-progress"]) == 0
    text = capsys.readouterr().out
    assert "cases     15 (15 run, 0 done before)" in text and str(out) in text
    df = pd.read_parquet(out)
    assert len(df) == 15 and (df["status"] == "ok").all()
    # steeper radial joints (centre nearer the intrados) need less friction
    for _, g in df.groupby("voussoirs"):
        f = g.sort_values("centre_depth")["friction_factor"].to_numpy()
        assert np.all(np.diff(f) >= -1e-9)
    assert main(["sweep", str(spec), "-o", str(out), "--workers", "1",
                 "--no-progress"]) == 0
    assert "(0 run, 15 done before)" in capsys.readouterr().out
    bad = write(tmp_path, {**BASE, "colour": 1})
    assert main(["sweep", str(bad), "-o", str(tmp_path / "x.parquet")]) == 2
    err = capsys.readouterr().err
    assert 'unknown key "colour"' in err and err.count("\n") == 1
    assert main(["sweep", str(spec), "-o", str(tmp_path / "x.txt")]) == 2


def test_doc_example_is_the_example_file():
    """docs/sweep-format.md shows the keys of examples/sweeps/flat_arch.json."""
    doc = json.loads((EXAMPLES / "sweeps" / "flat_arch.json").read_text())
    text = (ROOT / "docs" / "sweep-format.md").read_text()
    assert '"generator": "flat_arch"' in text and doc["generator"] == "flat_arch"
    assert study.read_spec(EXAMPLES / "sweeps" / "flat_arch.json").cases[0]["voussoirs"] == 3


# -- throughput -----------------------------------------------------------------------------
@pytest.mark.slow
def test_thousand_small_arches_throughput(tmp_path):
    """1,000 semicircular arches, t/R from 0.12 to 0.30, no sliding, self-weight, on 2
    processes: every one admissible, since t/R >= 0.12 exceeds Heyman's minimum 0.1075
    (The Stone Skeleton, 1995), which finite voussoir counts approach from below."""
    res = study.run("arch", grid={"voussoirs": list(range(4, 14)),
                                  "thickness": list(np.linspace(0.12, 0.3, 100))},
                    parameters={"load_factor": 0.0, "arc_points": 2,
                                "friction": "infinite"},
                    analyses=["check"], workers=2, progress=False,
                    output=tmp_path / "k.parquet")
    assert len(res.frame) == 1000 and res.n_failed == 0
    assert (res.frame["check_status"] == "admissible").all()
    assert res.rate > 5 and math.isfinite(res.elapsed)


def test_bench_study_tiny(tmp_path):
    """The throughput benchmark runs on its tiny size and writes its JSON and markdown."""
    import importlib.util

    spec = importlib.util.spec_from_file_location("bench_study",
                                                  ROOT / "benchmarks" / "bench_study.py")
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    data = bench.main(["--tiny", "--workers", "1", "--out", str(tmp_path)])
    (row,) = data["rows"]
    assert row["cases"] == 20 and row["failed"] == 0 and row["cases_per_s"] > 0
    doc = json.loads((tmp_path / "bench_study.json").read_text())
    assert doc["benchmark"] == "bench_study" and doc["rows"][0]["cases"] == 20
    assert "| check | 1 | 20 |" in (tmp_path / "bench_study.md").read_text()


def test_study_is_the_studies_package():
    """``from rigidblocks import study`` and ``import rigidblocks.study`` give the one
    home of the study API, rigidblocks.studies, with the names sweep.py exports."""
    import importlib

    import rigidblocks
    import rigidblocks.studies as studies
    from rigidblocks import study
    from rigidblocks.studies import sweep

    assert study is studies is importlib.import_module("rigidblocks.study")
    assert rigidblocks.study.run is sweep.run and study.read_spec is studies.spec.read_spec
    for name in ("ANALYSES", "ANSWERS", "RANDOM_KEYS", "RESERVED", "SCENE_PARAMS",
                 "Analysis", "StudyResult", "Sweep", "check_value", "expand_cases",
                 "make_sweep", "plot", "run", "run_batch", "run_case"):
        assert hasattr(sweep, name), name


def test_one_function_maps_an_analysis_name_to_its_answer():
    """studies.execute.answer is the one dispatch on the analysis name: a name it does
    not know is an error, never a silent default."""
    from rigidblocks.errors import InputError
    from rigidblocks.studies.execute import Analysis, _Job, answer

    job = _Job("flat_arch", None, (), "clarabel")
    scene = build("flat_arch", voussoirs=3)
    row, _ = answer(Analysis("min_friction"), job, {}, 0.0, lambda: scene)
    assert row["min_friction_status"] == "stable" and row["friction_factor"] > 0
    with pytest.raises(InputError, match="unknown analysis 'nope'"):
        answer(Analysis("nope"), job, {}, 0.0, lambda: scene)


def test_a_friction_grid_with_infinite_is_drawn_on_a_numeric_axis():
    """A friction grid with "infinite" holds strings: its chart spaced the frictions
    evenly as categories (0.05, 0.1, 0.2, ... drawn as equal steps bent the line
    lambda = f of a block that slides); now on a numeric axis, the infinite case left
    out and named. Several cases at one x without a hue are refused (they were joined
    in one zig-zag line)."""
    import matplotlib

    matplotlib.use("Agg")

    from rigidblocks.errors import InputError
    from rigidblocks.studies import plot

    df = pd.DataFrame({"friction": [0.05, 0.1, 0.2, "infinite"], "status": ["ok"] * 4,
                       "load_multiplier": [0.05, 0.1, 0.2, 0.5]})
    ax = plot(df, x="friction", y="load_multiplier")
    (line,) = ax.get_lines()
    assert list(line.get_xdata()) == [0.05, 0.1, 0.2]
    assert list(line.get_ydata()) == [0.05, 0.1, 0.2]
    assert any(t.get_text() == "not drawn: 1 case(s) at friction = infinite" for t in ax.texts)
    # a sweep's own column: numbers, inf where infinite
    ax = study.plot(df.assign(friction=[0.05, 0.1, 0.2, math.inf]), x="friction",
                    y="load_multiplier")
    assert any(t.get_text() == "not drawn: 1 case(s) at friction = infinite" for t in ax.texts)
    two = pd.DataFrame({"d": [1.0, 1.0, 2.0, 2.0], "n": [5, 9, 5, 9],
                        "f": [0.1, 0.2, 0.3, 0.4]})
    with pytest.raises(InputError, match="several cases share a value of 'd': give hue"):
        plot(two, x="d", y="f")
    assert len(plot(two, x="d", y="f", hue="n").get_lines()) == 2


def test_ctrl_c_ends_a_sweep_with_a_message_and_no_traceback(tmp_path):
    """Ctrl-C (SIGINT to the process group, as a terminal sends it) ends a sweep on
    worker processes with status 130 and "rigidblocks: interrupted": it printed a
    worker's traceback (KeyboardInterrupt inside a solve) and waited for the workers'
    cases (11 s)."""
    import os
    import signal
    import subprocess
    import sys
    import time

    spec = tmp_path / "walls.json"
    spec.write_text(json.dumps({
        "format": "rigidblocks-sweep", "version": 1, "generator": "wall",
        "parameters": {"load_factor": 1.0},
        "grid": {"courses": [10, 20, 30], "blocks_per_course": [10, 20, 30, 40],
                 "friction": [0.4, 0.6]},
        "analyses": ["max_load_multiplier", "min_friction"]}))
    out = tmp_path / "walls.csv"
    p = subprocess.Popen([sys.executable, "-m", "rigidblocks.cli.main", "sweep", str(spec),
                          "-o", str(out), "--no-progress", "--workers", "2"],
                         start_new_session=True, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    time.sleep(6)
    os.killpg(p.pid, signal.SIGINT)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130, err
    assert "rigidblocks: interrupted" in err and "Traceback" not in err, err


def _children(pid):
    """The processes whose parent is ``pid`` (Linux /proc)."""
    import os

    kids = []
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                with open(f"/proc/{d}/stat") as fh:
                    if int(fh.read().rsplit(")", 1)[1].split()[1]) == pid:
                        kids.append(int(d))
            except (OSError, ValueError, IndexError):
                pass
    return kids


def _alive(pid):
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.skipif(not __import__("sys").platform.startswith("linux"), reason="/proc")
@pytest.mark.parametrize("sig", ["SIGTERM", "SIGKILL"])
def test_a_killed_sweep_leaves_no_workers(tmp_path, sig):
    """`kill` (SIGTERM, a batch system's time limit) ended a sweep with status 143 and
    no word, its two workers left running for minutes with their parent gone (holding
    the output pipe, so that a script waiting on it hung), no case saved; SIGKILL the
    same. SIGTERM now ends it as Ctrl-C does, its finished cases kept ("rigidblocks:
    terminated", 143); the workers die with their parent either way."""
    import os
    import signal
    import subprocess
    import sys
    import time

    spec = tmp_path / "arches.json"
    spec.write_text(json.dumps({
        "format": "rigidblocks-sweep", "version": 1, "generator": "arch",
        "grid": {"thickness": [0.12 + 0.01 * k for k in range(30)],
                 "voussoirs": list(range(40, 56))},
        "analyses": ["min_friction", "max_load_multiplier"]}))
    out = tmp_path / "arches.parquet"
    p = subprocess.Popen([sys.executable, "-m", "rigidblocks.cli.main", "sweep", str(spec),
                          "-o", str(out), "--no-progress", "--workers", "2",
                          "--batch-size", "1"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    t0 = time.monotonic()
    while len(_children(p.pid)) < 2 and time.monotonic() - t0 < 60:
        time.sleep(0.2)
    kids = _children(p.pid)
    assert len(kids) >= 2, kids
    time.sleep(2)  # some cases done (480 take some 40 s)
    os.kill(p.pid, getattr(signal, sig))
    _, err = p.communicate(timeout=60)
    t0 = time.monotonic()
    while any(_alive(k) for k in kids) and time.monotonic() - t0 < 20:
        time.sleep(0.2)
    assert not any(_alive(k) for k in kids)
    if sig == "SIGTERM":
        assert p.returncode == 143 and "rigidblocks: terminated" in err, err
        assert "Traceback" not in err
        # (Ctrl-C said "interrupted" alone: nothing of the cases kept or how to go on)
        assert "the cases it finished are kept in" in err and \
            "arches.parquet.parts/; the same command resumes from them" in err
        assert list(tmp_path.glob("arches.parquet*/*.parquet"))  # the cases done


def test_min_thickness_friction_given_twice_is_a_spec_error():
    """A case parameter friction beside min_thickness's own friction option failed every
    case with "min_thickness() got multiple values for keyword argument 'friction'"."""
    from rigidblocks.errors import InputError

    with pytest.raises(InputError, match="'friction' is given both as its option and as "
                                         "a case parameter"):
        study.make_sweep("arch", grid={"voussoirs": [9, 11]}, parameters={"friction": 0.6},
                         analyses=["check", {"analysis": "min_thickness", "friction": 0.6}])


def test_min_thickness_reads_the_scene_friction_as_check_does():
    """Without a friction of its own, a sweep's min_thickness bisects at the scene's
    friction (the arch generator's f = 0.6), as check in the same row reads it, and says
    which in its column: the 15-voussoir arch at load factor 0.3 read 0.20599 (no
    sliding) while check found 0.206 not admissible at f = 0.6."""
    sw = study.make_sweep("arch", grid={"voussoirs": [15], "load_factor": [0.3]},
                          analyses=["min_thickness"])
    row = study.run(sw).frame.iloc[0]
    assert row["min_thickness_status"] == "found" and row["min_thickness_friction"] == 0.6
    for t, stands in ((row["min_thickness"], "admissible"),
                      (row["min_thickness_lower"], "inadmissible")):
        r = rb.check(build("arch", voussoirs=15, thickness=t), load_factor=0.3,
                     state=False)
        assert r.status == stands, (t, r.status)
    no_sliding = study.make_sweep("arch", grid={"voussoirs": [15], "load_factor": [0.3]},
                                  analyses=[{"analysis": "min_thickness",
                                             "friction": "infinite"}])
    row_inf = study.run(no_sliding).frame.iloc[0]
    assert row_inf["min_thickness_friction"] == math.inf
    assert row_inf["min_thickness"] < row["min_thickness_lower"]


def test_min_friction_and_load_rows_carry_their_accuracy():
    """A sweep's f* is the upper end of a bracket 2e-3 wide (the default accuracy): the
    row gives both ends (the 15-voussoir arch under self-weight: f* in [0.34625,
    0.34660], no state at the lower end), and lambda* its accuracy reached; the rows
    gave f* alone, with nothing to tell 0.3466 from 0.3463."""
    sw = study.make_sweep("arch", grid={"voussoirs": [15], "load_factor": [0]},
                          analyses=["min_friction", "max_load_multiplier"])
    row = study.run(sw).frame.iloc[0]
    lo, hi = row["friction_factor_lower"], row["friction_factor_upper"]
    assert lo < hi == row["friction_factor"] and (hi - lo) / hi <= 2e-3
    scene = build("arch", voussoirs=15)
    assert rb.check(scene, friction=lo, load_factor=0, state=False).status == "inadmissible"
    assert rb.check(scene, friction=hi, load_factor=0, state=False).status == "admissible"
    assert 0 < row["load_multiplier_accuracy"] <= 2e-3


def test_non_associative_load_rows_carry_the_bounds_on_every_state():
    """With flow non-associative a lambda* row gives the bounds on every collapse
    multiplier that `load` prints on its bounds line (the 9-voussoir arch at f = 0.4:
    [0.061316, 0.0613163]); it gave an empty accuracy and no bounds. With associative
    flow the bounds are empty and the accuracy is given."""
    sw = study.make_sweep("arch", grid={"voussoirs": [9], "friction": [0.4],
                                        "flow": ["associative", "non-associative"]},
                          analyses=["max_load_multiplier"])
    df = study.run(sw).frame.set_index("flow")
    na, assoc = df.loc["non-associative"], df.loc["associative"]
    direct = rb.max_load_multiplier(build("arch", voussoirs=9, friction=0.4),
                                    flow="non-associative", state=False)
    lo, hi = direct.load_multiplier_bounds
    assert (na["load_multiplier_lower"], na["load_multiplier_upper"]) == (lo, hi)
    assert lo <= na["load_multiplier"] <= hi and 0 < lo
    assert pd.isna(na["load_multiplier_accuracy"])
    assert pd.isna(assoc["load_multiplier_lower"]) and pd.isna(assoc["load_multiplier_upper"])
    assert 0 < assoc["load_multiplier_accuracy"] <= 2e-3
    assert hi == pytest.approx(assoc["load_multiplier"], rel=2e-3)


def test_a_sweeps_summary_counts_its_outcomes_and_its_exit_says_them(tmp_path, capsys,
                                                                     monkeypatch):
    """A sweep whose every case was undecided printed "failures 0" and exited 0, as one
    whose every case failed did (its failures counted, still 0): a script could not tell
    either from a sweep that answered. The summary counts each analysis's outcomes and
    the undecided cases, and the exit status is an analysis command's: 1 where a case
    failed, 3 where one is undecided. An undecided lambda* keeps its bracket in the
    lower and upper columns (they were empty, the number too: the distortion method on
    LACT3's Portal gave lambda* in [0.5127, 0.5195] alone, a sweep nothing)."""
    from dataclasses import replace

    from rigidblocks.analyses import registry

    doc = {**BASE, "generator": "wall", "grid": {"courses": [3]},
           "parameters": {"blocks_per_course": 3}, "analyses": ["max_load_multiplier"]}
    spec = write(tmp_path, doc)
    assert main(["sweep", str(spec), "-o", str(tmp_path / "a.csv"), "--workers", "1",
                 "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "outcomes  max_load_multiplier: collapse 1" in out and "undecided" not in out
    assert "cases/s" in out or "s per case" in out
    # the method's own result, undecided with its bracket
    info = registry.analysis("max_load_multiplier")

    def undecided(scene, **kw):
        r = info.function(scene, **kw)
        return replace(r, status="undecided", load_multiplier=None,
                       bracket=(0.5, 0.625))

    monkeypatch.setitem(registry.ANALYSES, "max_load_multiplier",
                        replace(info, function=undecided))
    assert main(["sweep", str(spec), "-o", str(tmp_path / "u.csv"), "--workers", "1",
                 "--no-progress"]) == 3
    out = capsys.readouterr().out
    assert "outcomes  max_load_multiplier: undecided 1" in out and "failures  0" in out
    assert "undecided 1 case(s) with an analysis that could not decide" in out
    row = pd.read_csv(tmp_path / "u.csv").iloc[0]
    assert pd.isna(row["load_multiplier"])
    assert (row["load_multiplier_lower"], row["load_multiplier_upper"]) == (0.5, 0.625)
    # every case failed (the generator refuses 0 courses)
    bad = write(tmp_path, {**doc, "grid": {"courses": [0]}}, "bad.json")
    assert main(["sweep", str(bad), "-o", str(tmp_path / "f.csv"), "--workers", "1",
                 "--no-progress"]) == 1
    assert "failures  1 (the first, case 0:" in capsys.readouterr().out


@pytest.mark.parametrize("grid, said", [
    ({"voussoirs": [5.5]}, "voussoirs (case 0): expected an integer, got 5.5"),
    ({"voussoirs": ["5"]}, 'voussoirs (case 0): expected an integer, got "5"'),
    ({"voussoirs": [5, 5.0]}, "voussoirs (case 1): expected an integer, got 5.0"),
])
def test_an_optional_integer_parameter_is_an_integer(grid, said):
    """The arch's voussoirs (None by default: automatic) took any string or number: 5.5
    failed each case at run time (the sweep exiting 0), "5" ran as 5, and [5, 5.0] ran
    twice with two case ids. Its signature's type (int | None) now types it, null
    allowed; a min_thickness whose lo is not below its hi is refused before any case."""
    with pytest.raises(InputError, match=re.escape(said)):
        study.make_sweep("arch", grid=grid)
    assert study.make_sweep("arch", grid={"voussoirs": [5, 5, None]}).cases == (
        {"voussoirs": 5}, {"voussoirs": None})
    with pytest.raises(InputError, match="lo must be below hi, got lo 0.3 and hi 0.1"):
        study.make_sweep("arch", grid={"voussoirs": [5]}, analyses=[
            {"analysis": "min_thickness", "lo": 0.3, "hi": 0.1}])
    # an infinite hi failed every case ("cannot be built at thickness=inf", exit 1)
    with pytest.raises(InputError, match="hi must be a finite number > 0, got inf"):
        study.make_sweep("arch", grid={"voussoirs": [5]}, analyses=[
            {"analysis": "min_thickness", "hi": math.inf}])


def test_the_sweep_commands_progress_bar_is_for_a_terminal(tmp_path, capsys):
    """Off a terminal (a log, a pipe) the progress bar filled standard error with its
    carriage-return lines; it is drawn only on a terminal, as the analyses' progress."""
    spec = write(tmp_path, BASE)
    assert main(["sweep", str(spec), "-o", str(tmp_path / "a.csv"), "--workers", "1"]) == 0
    assert capsys.readouterr().err == ""


def test_a_thickness_that_is_only_a_bound_is_no_point_of_the_curve():
    """A min_thickness row standing at its lower bound holds lo in min_thickness (the
    minimum is at most that), an undecided one its bracket's upper end: drawn, the
    3-voussoir arch's 0.02 was a point of the curve. They are marked as cases without a
    number, by status."""
    import matplotlib

    matplotlib.use("Agg")
    df = pd.DataFrame({"voussoirs": [3, 5, 9, 15], "status": ["ok"] * 4,
                       "min_thickness": [0.02, 0.0963, 0.102, 0.1063],
                       "min_thickness_status": ["at_lower_bound", "found", "undecided",
                                                "found"]})
    ax = study.plot(df, x="voussoirs", y="min_thickness")
    line = ax.get_lines()[0]
    assert list(line.get_xdata()) == [3, 5, 9, 15]
    assert np.isnan(line.get_ydata().astype(float)[[0, 2]]).all()
    assert [t.get_text() for t in ax.texts] == [
        "no min_thickness (x on the axis): 1 at_lower_bound, 1 undecided"]


def test_an_undecided_non_associative_row_keeps_its_bracket_and_a_failed_case_counts():
    """The inclined corbel arch without dilatancy at f = 0.8 is undecided, lambda* in
    [0.01279220942, 0.0127926969] (`load`); its sweep row gave the bounds on every
    state instead, [-, 0.0213], 66 % above it, beside "its bracket in its lower and upper
    columns". A case whose scene cannot be built left its analyses' statuses empty (the
    outcomes did not count it); they read failed."""
    sw = study.make_sweep("corbel_arch", cases=[
        {"pattern": "inclined", "flow": "non-associative", "friction": 0.8},
        {"pattern": "inclined", "courses": 0}], analyses=["max_load_multiplier"])
    res = study.run(sw, workers=1, progress=False)
    row, bad = res.frame.iloc[0], res.frame.iloc[1]
    assert row["max_load_multiplier_status"] == "undecided"
    assert (row["load_multiplier_lower"], row["load_multiplier_upper"]) == pytest.approx(
        (0.01279220942, 0.0127926969), rel=1e-9)
    assert bad["status"] == "failed" and bad["max_load_multiplier_status"] == "failed"
    assert res.outcomes == {"max_load_multiplier": {"undecided": 1, "failed": 1}}


def test_a_case_without_a_hue_value_is_drawn():
    """A case that leaves the hue parameter to its default (friction not given) has an
    empty hue: groupby dropped it, its number not drawn and not said."""
    import matplotlib

    matplotlib.use("Agg")
    df = pd.DataFrame({"thickness": [0.15, 0.15, 0.2], "status": ["ok"] * 3,
                       "friction": [np.nan, 0.4, 0.4],
                       "friction_factor": [0.3466, 0.35, 0.33]})
    ax = study.plot(df, x="thickness", y="friction_factor", hue="friction")
    drawn = {ln.get_label(): list(ln.get_ydata()) for ln in ax.get_lines()}
    assert drawn == {"friction = nan": [0.3466], "friction = 0.4": [0.35, 0.33]}


def test_an_undecided_case_says_why_in_its_note_and_the_summary_names_it(tmp_path,
                                                                          capsys):
    """Two cases of the 15-voussoir arch near its limit thickness, by the distortion
    method at infinite friction, are undecided: the summary said only "undecided 2
    case(s)", no case named, the error column empty and no reason anywhere (a single
    `load` gives it). Each row's note says why, and the summary names the first."""
    from rigidblocks.cli.main import main

    spec = tmp_path / "near.json"
    spec.write_text(json.dumps({
        "format": "rigidblocks-sweep", "version": 1, "generator": "arch",
        "method": "distortion", "parameters": {"friction": "infinite", "voussoirs": 15},
        "grid": {"thickness": [0.106264, 0.12]}, "analyses": ["max_load_multiplier"]}))
    out = tmp_path / "near.csv"
    assert main(["sweep", str(spec), "-o", str(out), "--workers", "1",
                 "--no-progress"]) == 3
    text = capsys.readouterr().out
    assert "(the first, case 0: max_load_multiplier: lambda* in [" in text
    assert "every one in the output's note column)" in text
    import pandas as pd

    d = pd.read_csv(out)
    assert d.loc[0, "max_load_multiplier_status"] == "undecided"
    assert d.loc[0, "note"].startswith("max_load_multiplier: lambda* in [")
    assert "undecided" in d.loc[0, "note"]
    assert d.loc[1, "max_load_multiplier_status"] == "collapse" and pd.isna(d.loc[1, "note"])


def test_min_thickness_rows_name_the_parameter_they_bisect():
    """A pier width bisected landed in the min_thickness column with nothing saying it
    was a pier width in metres and not t/R."""
    sw = study.make_sweep("flat_arch", grid={"friction": [0.6]}, analyses=[
        {"analysis": "min_thickness", "param": "pier_width", "lo": 0.05, "hi": 2.0,
         "rtol": 1e-2}])
    row = study.run(sw).frame.iloc[0]
    assert row["min_thickness_param"] == "pier_width" and row["min_thickness"] > 0.05


def test_an_undecided_note_gives_the_reason_not_the_description(tmp_path):
    """A block against a wall bonded to it (cohesion and tensile strength 4 kPa), f =
    0.3, without dilatancy: undecided in [0.458, 0.542] (the capacity bound and the
    associative multiplier) because its fixed point breaks Coulomb's law. The sweep's
    note read the analysis's description ("non-associative sliding (no dilatancy): the
    answer is a collapse state reached ..."), the first reason, not that."""
    from conftest import make_scene, rect

    from rigidblocks.answer import undecided_why

    s = make_scene([
        {"id": "ground", "vertices": rect(-2, -1, 3, 1), "support": True},
        {"id": "wall", "vertices": rect(1, -1, 1, 4), "support": True},
        {"id": "B", "vertices": rect(0, 0, 1, 2)}],
        unit_weight=20.0, friction=0.3, live_body_force=[-1.0, 0.0], flow="non-associative",
        joints=[{"blocks": ["wall", "B"], "cohesion": 4.0, "tensile_strength": 4.0}])
    r = rb.max_load_multiplier(s, state=False)
    assert r.status == "undecided" and r.bracket is not None
    why = undecided_why(s, r)
    assert "non-associative sliding (no dilatancy): the answer is" not in why
    assert "fails its check" in why or "is below the capacity bound" in why, why


def test_a_min_thickness_rtol_finer_than_its_checks_is_refused_by_the_spec():
    """A sweep's min_thickness at rtol 1e-9 with Clarabel failed every case on its own
    (the sweep exiting 1), where `thickness` and min_thickness refuse it at once."""
    from rigidblocks.errors import InputError

    with pytest.raises(InputError, match=r"analyses\[0\]: min_thickness: rtol 1e-09 is "
                                         "finer than an interior-point solver"):
        study.make_sweep("arch", grid={"voussoirs": [9]},
                         analyses=[{"analysis": "min_thickness", "rtol": 1e-9}])
    study.make_sweep("arch", grid={"voussoirs": [9]}, method="distortion",
                     analyses=[{"analysis": "min_thickness", "rtol": 1e-9}])
