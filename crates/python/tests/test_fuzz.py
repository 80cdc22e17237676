"""The module under fuzzing (fuzz_module.py): a bounded run from a fixed seed in a child
process, its address space capped at 8 GiB and its time at 10 minutes, must end with no
failure — only the module's exceptions, TypeError or ValueError; finite output for finite
input in the domain; solves that meet their targets; no call slower than its bound."""

import json
import os
import resource
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
MEMORY = 8 << 30


def _cap_memory():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY, MEMORY))


def test_the_module_under_fuzzing():
    out = subprocess.run(
        [sys.executable, str(HERE / "fuzz_module.py"), "--cases", "1500"],
        capture_output=True,
        text=True,
        timeout=600,
        preexec_fn=_cap_memory,
        env={**os.environ, "PYTHONHASHSEED": "0"},
    )
    lines = out.stdout.strip().splitlines()
    assert lines, f"no summary (exit {out.returncode}): {out.stderr[-4000:]}"
    summary = json.loads(lines[-1])
    assert out.returncode == 0 and not summary["failures"], (
        f"{len(summary['failures'])} failure(s) from seed {summary['seed']}; the first:\n"
        + (summary["failures"] or [out.stderr[-4000:]])[0]
    )
    assert summary["cases"] == 1500
    # A fuzzer whose calls all fail or all succeed tests little: both must occur often.
    calls = summary["outcomes"]
    assert calls["returned"] > 0.2 * summary["calls"], calls
    assert calls["refused"] > 0.05 * summary["calls"], calls
