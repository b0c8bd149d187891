"""Long analyses on the command line: a progress line on a terminal (quiet otherwise),
and Ctrl-C that ends the run within a second or two with exit 130 and no traceback."""

from __future__ import annotations

import signal
import subprocess
import sys
import time

import rigidblocks as rb
from rigidblocks.cli import progress as cli_progress
from rigidblocks.generators import build
from rigidblocks.methods import Progress


def test_progress_line_after_the_delay(monkeypatch, capsys):
    monkeypatch.setattr(cli_progress, "DELAY", 0.2)
    monkeypatch.setattr(cli_progress, "EVERY", 0.05)
    p = Progress()
    p.stage = "maximum load problem"

    def work():
        time.sleep(0.6)
        return 42

    assert cli_progress.run_interruptible(work, p, show=True) == 42
    err = capsys.readouterr().err
    assert "maximum load problem, solve 1" in err
    assert err.endswith("\r")  # the line is wiped before the report


def test_a_long_line_keeps_its_step_stage_and_time_in_view():
    """On an 80-column terminal the path's line was cut at its end: "load path: step 3
    of 40, lambda 0.1 to 0.15, 0 events so far: iteration run at " stood still while the
    run's lambda, solves and time changed beyond the edge. Within the width the counts
    go first, then the context's end."""
    p = Progress()
    p.context = "load path: step 3 of 40 (lambda to 0.15), 0 events"
    p.stage = "iteration run at lambda = 0.149764"
    p.solves, p.iterations = 20, 21791
    assert p.text() == (f"{p.context}: {p.stage}, solve 21, 21791 iterations so far, 0 s")
    assert p.text(120) == f"{p.context}: {p.stage}, 0 s"
    narrow = p.text(79)
    assert len(narrow) <= 79 and narrow.startswith("load path: step 3 of 40") and \
        narrow.endswith("\N{HORIZONTAL ELLIPSIS}: " + f"{p.stage}, 0 s"), narrow
    p.context = "limit run from the elastic state X0: step 5 of at most 200, lambda 0.33"
    assert p.text(79).endswith(f": {p.stage}, 0 s") and len(p.text(79)) <= 79


def test_quiet_when_not_shown_and_errors_pass_through(capsys):
    def fail():
        raise rb.InputError("bad")

    try:
        cli_progress.run_interruptible(fail, Progress(), show=False)
    except rb.InputError as err:
        assert str(err) == "bad"
    else:  # pragma: no cover
        raise AssertionError("the worker's error must reach the caller")
    assert capsys.readouterr().err == ""


def test_analyses_keep_the_progress_up_to_date():
    p = Progress()
    scene = build("wall", courses=4, blocks_per_course=4)
    r = rb.min_friction(scene, load_factor=0.2, progress=p)
    assert p.solves == r.n_solves and p.iterations == r.iterations > 0


def test_a_limit_run_names_its_start_and_step():
    """The non-associative limit iteration runs for minutes on walls of thousands of
    blocks: the progress line names the run (its start), its step and the last
    multiplier before the stage of the solve under way, and forgets them after."""
    seen: list[str] = []

    class Recording(Progress):
        def __setattr__(self, name, value):
            if name == "context" and value:
                seen.append(f"{value}: {self.stage}")
            super().__setattr__(name, value)

    p = Recording()
    scene = build("wall", courses=4, blocks_per_course=4, friction=0.8)
    r = rb.max_load_multiplier(scene, flow="non-associative", progress=p, state=False)
    assert r.status == "collapse"
    assert seen[0].startswith("limit run from the elastic state X0: step 1 of at most 200:")
    assert any(t.startswith("limit run from the associative collapse state: step 2 of at "
                            "most 200, lambda 0.") for t in seen)
    assert p.context == "" and "limit run" not in p.text()


def test_the_load_path_names_its_step(monkeypatch, capsys):
    """`path` printed nothing while it ran (92 s on a 19-block wall): the progress line
    names the load step, the load it goes to and the events so far, then the iteration
    run under way, and forgets the step after; the command shows it on a terminal."""
    from conftest import EXAMPLES

    from rigidblocks.analyses import load_path
    from rigidblocks.cli import path as cli_path
    from rigidblocks.io import read_scene

    seen: list[str] = []

    class Recording(Progress):
        def __setattr__(self, name, value):
            if name == "stage" and getattr(self, "context", ""):
                seen.append(f"{self.context}: {value}")
            super().__setattr__(name, value)

    p = Recording()
    res = load_path(read_scene(EXAMPLES / "reference.json"), progress=p)
    assert res.status == "collapse"
    assert seen[0].startswith("load path: under the dead load: iteration run at lambda = 0")
    assert "load path: step 2 of 40 (lambda to 0.1), 0 events: iteration run at lambda = "\
        "0.1" in seen
    assert p.context == "" and "load path" not in p.text()
    shown = []
    monkeypatch.setattr(cli_path, "run_interruptible",
                        lambda work, progress, show: shown.append(show) or work())
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True)
    from rigidblocks.cli.main import main

    main(["path", str(EXAMPLES / "reference.json")])
    main(["path", str(EXAMPLES / "reference.json"), "--json"])
    capsys.readouterr()
    assert shown == [True, False]  # the line on a terminal, never within JSON output


def test_ctrl_c_ends_a_long_solve_at_once(tmp_path):
    """A 4,000-block wall's maximum-load solve takes several seconds; SIGINT two seconds
    in ends the process within 2 s with status 130 and a one-line message."""
    path = tmp_path / "wall.json"
    rb.write_scene(build("wall", courses=40, blocks_per_course=100), path)
    proc = subprocess.Popen([sys.executable, "-m", "rigidblocks.cli.main", "load", str(path)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(2.5)
    assert proc.poll() is None, "the analysis ended before it could be interrupted"
    t0 = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=30)
    assert time.perf_counter() - t0 < 2.0
    assert proc.returncode == 130
    assert "interrupted" in err and "Traceback" not in err
