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
