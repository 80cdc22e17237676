"""Shared fixtures: the repository's paths and the command-line program the module is
compared with."""

import os
import subprocess
from pathlib import Path

import pytest

# pytest's own fixture for testing plugins (the image-regression plugin's tests).
pytest_plugins = ["pytester"]

ROOT = Path(__file__).resolve().parents[3]
SCENES = ROOT / "scenes"


def cli_path() -> Path:
    """The release binary the test command builds first (``cargo test --release``)."""
    return Path(os.environ.get("SPLINESCOPE_BIN", ROOT / "target" / "release" / "splinescope"))


@pytest.fixture(scope="session")
def cli():
    path = cli_path()
    if not path.exists():
        pytest.fail(
            f"the command-line program is not built at {path}: run `cargo build --release` "
            "(scripts/test does) or set SPLINESCOPE_BIN"
        )

    def run(*args, check=True):
        out = subprocess.run([str(path), *map(str, args)], capture_output=True, text=True)
        if check and out.returncode != 0:
            raise AssertionError(f"splinescope {' '.join(map(str, args))} failed: {out.stderr}")
        return out

    return run


def gpu_or_fail(test: str) -> bool:
    """Whether GPU tests run: without an adapter they fail with how to install one,
    unless SPLINESCOPE_SKIP_GPU_TESTS=1 asks to skip (and then say so)."""
    return os.environ.get("SPLINESCOPE_SKIP_GPU_TESTS") != "1"


def no_adapter(e: Exception, what: str = "rendering"):
    """A GPU error in a test: skip when SPLINESCOPE_SKIP_GPU_TESTS=1 asks and there is no
    adapter (saying so), else fail saying how to install the software adapters."""
    if os.environ.get("SPLINESCOPE_SKIP_GPU_TESTS") == "1" and "no GPU adapter" in str(e):
        print(f"SKIPPED: {e}; SPLINESCOPE_SKIP_GPU_TESTS=1 asked to skip")
        pytest.skip("no GPU adapter and SPLINESCOPE_SKIP_GPU_TESTS=1")
    pytest.fail(
        f"{what} needs a GPU adapter: {e}\nInstall the software ones (Debian/Ubuntu: "
        "sudo apt-get install mesa-vulkan-drivers libvulkan1 libegl1 libgl1-mesa-dri) or "
        "set SPLINESCOPE_SKIP_GPU_TESTS=1 to skip GPU tests explicitly."
    )
