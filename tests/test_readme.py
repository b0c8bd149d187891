"""The README's worked example runs and prints what its comments say."""

from __future__ import annotations

import re
import subprocess
import sys

from conftest import ROOT


def test_readme_python_example_output_matches_comments():
    """Each ``print(...)  # value`` line of the README prints the commented value.

    Closed form (docs/validation.md): a block b x h under a horizontal body force
    lambda x weight has lambda* = min(f, b/h); with b/h = 0.5 and f = 0.4 it slides.
    """
    text = (ROOT / "README.md").read_text()
    code = re.search(r"```python\n(.*?)```", text, re.S).group(1)
    expected = [m.group(1).split(":")[0].split(" = ")[0].strip()
                for m in re.finditer(r"^print\(.*?#\s*(.+)$", code, re.M)]
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=ROOT).stdout.splitlines()
    assert len(out) == len(expected) == 3
    for got, want in zip(out, expected, strict=True):
        assert got.strip() == want


def test_readme_keeps_its_commands_and_states_what_the_tests_need():
    """The first two command lines stay the ones a new user types; the requirements are
    stated; every notebook in notebooks/ is listed."""
    text = (ROOT / "README.md").read_text()
    block = re.search(r"```bash\n(.*?)```", text, re.S).group(1).splitlines()
    assert block[:2] == ['pip install . && rigidblocks friction examples/reference.json',
                         'pip install ".[test]" && python -m pytest -q']
    for need in ("Python >= 3.11", "virtual environment", "Chromium", "../shared",
                 "CI=true"):
        assert need in text, need
    notebooks = sorted(p.stem for p in (ROOT / "notebooks").glob("*.ipynb"))
    assert len(notebooks) == 5
    assert all(f"`{name}`" in text for name in notebooks)


def test_readme_answer_block_is_what_load_prints(capsys):
    """The README's example answer is `rigidblocks load examples/arch.json` as printed
    (lambda* = 0.149765 of the 15-voussoir arch, t/R = 0.15; tests/test_one_answer.py
    checks it against the other commands)."""
    from rigidblocks.cli.main import main

    text = (ROOT / "README.md").read_text()
    block = re.search(r"```text\n(.*?)```", text, re.S).group(1).splitlines()
    assert main(["load", str(ROOT / "examples" / "arch.json")]) == 0
    printed = capsys.readouterr().out.splitlines()
    assert printed[2:] == block


def test_readme_non_associative_figures_claim(capsys):
    """The README's sentence on the figures of a non-associative f*: the inclined corbel
    arch (examples/corbel_arch_inclined.json) under its dead load stands at the printed
    f* = 0.7651297008 and not at 0.7652 from X0 by the limit iteration, while the
    distortion iteration reaches a state that stands at 0.7652 (it read "not at 0.76513",
    where `check` stands since a multiplier within 1e-6 of the live load of 0 is 0)."""
    from rigidblocks.cli.main import main

    text = " ".join((ROOT / "README.md").read_text().split())
    assert ("stands under its dead load at f* = 0.7651297008 but not at 0.7652, from X0 "
            "by the limit iteration (the distortion iteration reaches a state that stands "
            "there") in text
    path = str(ROOT / "examples" / "corbel_arch_inclined.json")
    args = ["check", path, "--load-factor", "0", "--flow", "non-associative"]
    verdicts = {}
    for f, method in (("0.7651297008", "clarabel"), ("0.7652", "clarabel"),
                      ("0.7652", "distortion")):
        assert main([*args, "--friction", f, "--method", method]) == 0
        out = capsys.readouterr().out
        verdicts[f, method] = next(ln for ln in out.splitlines()
                                   if ln.startswith("verdict")).split()[1].rstrip(":")
    assert verdicts == {("0.7651297008", "clarabel"): "ADMISSIBLE",
                        ("0.7652", "clarabel"): "NOT",
                        ("0.7652", "distortion"): "ADMISSIBLE"}
