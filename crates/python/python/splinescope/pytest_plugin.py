"""Image regression of curve scenes in pytest (registered through the ``pytest11`` entry
point, so installing the package is enough).

Mark a test that returns a :class:`splinescope.Scene`::

    @pytest.mark.splinescope_compare(tolerance="channel=24,pixels=0.1%", width=400, height=300)
    def test_arch():
        return splinescope.Scene([splinescope.Bezier([[0, 0], [1, 2], [2, 0]])])

* ``pytest --splinescope-bless`` renders each marked test's scene and writes it as the
  baseline (``baseline/<module>__<test>.png`` beside the test file, or under
  ``--splinescope-bless=DIR`` / ``--splinescope-baseline=DIR``). As ``splinescope regress
  --bless``: all or none — when any marked test fails to give or render its scene, no
  baseline is written — and a baseline is only ever replaced, never deleted.
* ``pytest --splinescope`` compares each render with its baseline by ``splinescope
  diff``'s rules (per channel and NVIDIA FLIP, the marker's ``tolerance``); a failure
  names the figures and writes the actual, reference, diff and FLIP images into
  ``--splinescope-results`` (default ``splinescope-results``), which are also attached to
  the test report's ``user_properties``. A missing baseline fails, saying how to bless.
* Without either, the marked tests run and their scenes are only checked to render.
* ``--splinescope-summary=html`` writes the same page as ``splinescope regress --report``
  (``index.html`` with every marked test's images) into the results directory.
"""

import json
import os
import re
import tempfile
from pathlib import Path
from typing import Any, Dict, List, Optional, Tuple

import pytest

MARKER = "splinescope_compare"
DEFAULTS: Dict[str, Any] = {
    "tolerance": "channel=24,pixels=0.1%",
    "width": 400,
    "height": 300,
    "backend": None,
    "filename": None,
}


def pytest_addoption(parser: Any) -> None:
    group = parser.getgroup("splinescope", "image regression of curve scenes (splinescope)")
    group.addoption(
        "--splinescope",
        action="store_true",
        default=False,
        help="compare the scenes returned by tests marked splinescope_compare with their baselines",
    )
    group.addoption(
        "--splinescope-bless",
        nargs="?",
        const="",
        default=None,
        metavar="DIR",
        help="write the baselines (all or none), into DIR when given",
    )
    group.addoption(
        "--splinescope-baseline",
        default=None,
        metavar="DIR",
        help="where baselines are read (and blessed): default baseline/ beside each test file",
    )
    group.addoption(
        "--splinescope-results",
        default="splinescope-results",
        metavar="DIR",
        help="where the actual, reference, diff and FLIP images of comparisons go",
    )
    group.addoption(
        "--splinescope-summary",
        default=None,
        choices=["html"],
        help="write the regression report page (as `splinescope regress --report`) into the results directory",
    )
    group.addoption(
        "--splinescope-backend",
        default="auto",
        metavar="API",
        help="graphics API for the renders: auto, vulkan, gl, metal or dx12",
    )


def pytest_configure(config: Any) -> None:
    config.addinivalue_line(
        "markers",
        f"{MARKER}(tolerance='channel=24,pixels=0.1%', width=400, height=300, backend=None, "
        "filename=None): the test returns a splinescope.Scene, rendered and compared with "
        "its baseline (--splinescope, --splinescope-bless)",
    )
    config.pluginmanager.register(_Regression(config), "splinescope-regression")


def _stem(nodeid: str) -> str:
    """A file stem from a test id: ``test_a.py::test_b[gl]`` → ``test_a__test_b_gl_``."""
    path, _, name = nodeid.partition("::")
    module = Path(path).stem
    return re.sub(r"[^A-Za-z0-9_.-]", "_", f"{module}__{name}")


def _write_atomic(path: Path, data: bytes) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


class _Regression:
    """The session's regression run: settings from the command line, pending baselines
    (blessing is all or none), and the rows of the summary page."""

    def __init__(self, config: Any) -> None:
        self.config = config
        self.compare = bool(config.getoption("--splinescope"))
        bless = config.getoption("--splinescope-bless")
        if bless and (bless.endswith(".py") or "::" in bless or Path(bless).is_file()):
            # `--splinescope-bless test_x.py` reads the test file as the directory to bless
            # into (the option's value is optional); refuse rather than write there.
            raise pytest.UsageError(
                f"--splinescope-bless took {bless!r} as the directory to write baselines into; "
                f"write --splinescope-bless=DIR for a directory, or put --splinescope-bless "
                f"after the test paths"
            )
        self.bless = bless is not None
        self.bless_dir = Path(bless) if bless else None
        base = config.getoption("--splinescope-baseline")
        self.baseline_dir = Path(base) if base else None
        self.results = Path(config.getoption("--splinescope-results"))
        self.summary = config.getoption("--splinescope-summary")
        self.backend = config.getoption("--splinescope-backend")
        self.pending: List[Tuple[Path, bytes]] = []
        self.errors: List[str] = []
        self.rows: List[Tuple[str, str, str, str, List[Any]]] = []
        self.messages: List[str] = []

    # -- where things go -----------------------------------------------------------

    def baseline_path(self, item: Any, options: Dict[str, Any], blessing: bool) -> Path:
        name = options["filename"] or f"{_stem(item.nodeid)}.png"
        if blessing and self.bless_dir is not None:
            return self.bless_dir / name
        if self.baseline_dir is not None:
            return self.baseline_dir / name
        return Path(str(item.fspath)).parent / "baseline" / name

    # -- the test call -------------------------------------------------------------

    @pytest.hookimpl(tryfirst=True)
    def pytest_pyfunc_call(self, pyfuncitem: Any) -> Optional[bool]:
        marker = pyfuncitem.get_closest_marker(MARKER)
        if marker is None:
            return None
        import splinescope as ss

        options = dict(DEFAULTS)
        unknown = set(marker.kwargs) - set(DEFAULTS)
        if unknown or marker.args:
            raise pytest.UsageError(
                f"{pyfuncitem.nodeid}: {MARKER} takes {', '.join(DEFAULTS)} as keywords; "
                f"got {sorted(unknown) or list(marker.args)}"
            )
        options.update(marker.kwargs)
        args = {a: pyfuncitem.funcargs[a] for a in pyfuncitem._fixtureinfo.argnames}
        try:
            scene = pyfuncitem.obj(**args)
            if not isinstance(scene, ss.Scene):
                raise TypeError(
                    f"a test marked {MARKER} returns a splinescope.Scene, not {type(scene).__name__}"
                )
            backend = options["backend"] or self.backend
            actual = scene.render(options["width"], options["height"], backend=backend)
        except Exception as e:  # pytest's skip and xfail outcomes pass through unrecorded
            self.errors.append(f"{pyfuncitem.nodeid}: {e}")
            self.rows.append((pyfuncitem.nodeid, "error", "", str(e), [None] * 4))
            raise
        if self.bless:
            path = self.baseline_path(pyfuncitem, options, blessing=True)
            self.pending.append((path, scene.png(options["width"], options["height"], backend=backend)))
            self.rows.append((pyfuncitem.nodeid, "blessed", "", str(path), [None, actual, None, None]))
            return True
        if self.compare:
            self.check(pyfuncitem, options, actual)
        else:
            self.rows.append((pyfuncitem.nodeid, "rendered", "", "", [None, actual, None, None]))
        return True

    def check(self, item: Any, options: Dict[str, Any], actual: Any) -> None:
        from . import _splinescope as native

        path = self.baseline_path(item, options, blessing=False)
        if not path.is_file():
            self.rows.append((item.nodeid, "missing", "", f"no baseline {path}", [None, actual, None, None]))
            pytest.fail(
                f"no baseline {path}: run `pytest --splinescope-bless` to write it", pytrace=False
            )
        reference = native.read_png(str(path))
        try:
            text, diff, flip = native.compare_pictures(actual, reference, options["tolerance"])
        except ValueError as e:
            self.rows.append((item.nodeid, "differs", "", str(e), [reference, actual, None, None]))
            pytest.fail(f"{item.nodeid}: {e} (baseline {path})", pytrace=False)
        c = json.loads(text)
        figures = (
            f"{c['differing_pixels']} px differ ({100 * c['differing_fraction']:.3f} %), "
            f"largest channel difference {c['max_channel_diff']}, FLIP mean {c['flip_mean']:.4f}, "
            f"max {c['flip_max']:.4f}"
        )
        status = "match" if c["matches"] else "differs"
        self.rows.append((item.nodeid, status, figures, "", [reference, actual, diff, flip]))
        if c["matches"]:
            return
        stem = _stem(item.nodeid)
        self.results.mkdir(parents=True, exist_ok=True)
        written = []
        for kind, image in (("actual", actual), ("reference", reference), ("diff", diff), ("flip", flip)):
            out = self.results / f"{stem}.{kind}.png"
            native.write_png(str(out), image)
            item.user_properties.append((f"splinescope_{kind}", str(out)))
            written.append(str(out))
        pytest.fail(
            f"{item.nodeid}: the render differs from {path} beyond {options['tolerance']}: "
            f"{figures}; images: {', '.join(written)}",
            pytrace=False,
        )

    # -- the end of the session ----------------------------------------------------

    def pytest_sessionfinish(self, session: Any) -> None:
        def say(text: str) -> None:
            self.messages.append(text)

        if self.bless:
            if self.errors:
                say(
                    f"splinescope: no baseline written ({len(self.pending)} pending): "
                    + "; ".join(self.errors)
                )
                session.exitstatus = session.exitstatus or 1
            else:
                for path, data in self.pending:
                    _write_atomic(path, data)
                say(f"splinescope: blessed {len(self.pending)} baseline(s)")
        if self.summary == "html":
            from . import _splinescope as native

            self.results.mkdir(parents=True, exist_ok=True)
            counts: Dict[str, int] = {}
            for row in self.rows:
                counts[row[1]] = counts.get(row[1], 0) + 1
            summary = ", ".join(f"{n} {s}" for s, n in sorted(counts.items())) or "no marked tests"
            native.write_report(str(self.results), summary, [tuple(r) for r in self.rows])
            say(f"splinescope: report in {self.results / 'index.html'}")

    def pytest_terminal_summary(self, terminalreporter: Any) -> None:
        # Said here, after the progress line has ended, each on a line of its own.
        for text in self.messages:
            terminalreporter.write_line(text)
