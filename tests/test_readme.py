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
