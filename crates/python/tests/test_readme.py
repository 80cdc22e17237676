"""The README's Python example, run as written from the repository root."""

import os
import re

from conftest import ROOT


def test_the_readme_example_runs_as_written():
    text = (ROOT / "README.md").read_text()
    section = text.split("## Python", 1)[1].split("\n## ", 1)[0]
    blocks = re.findall(r"```python\n(.*?)```", section, re.S)
    assert blocks, "the README's Python section has an example"
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        exec(compile(blocks[0], "README.md (Python example)", "exec"), {})
    finally:
        os.chdir(cwd)
