"""The README's Python examples, each run as written from the repository root, as a
script of its own (so that an `if __name__ == "__main__":` guard runs, as it does for a
user), in a fresh interpreter with a time limit."""

import re
import subprocess
import sys

import pytest

from conftest import ROOT


def blocks():
    text = (ROOT / "README.md").read_text()
    section = text.split("## Python", 1)[1].split("\n## ", 1)[0]
    return re.findall(r"```python\n(.*?)```", section, re.S)


def test_the_python_section_has_examples():
    assert len(blocks()) >= 2, "the README's Python section has its examples"


@pytest.mark.parametrize("index", range(len(blocks())))
def test_the_readme_example_runs_as_written(index, tmp_path):
    script = tmp_path / f"readme_example_{index}.py"
    script.write_text(blocks()[index])
    run = subprocess.run(
        [sys.executable, str(script)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert run.returncode == 0, f"README example {index} failed:\n{run.stdout}\n{run.stderr}"
