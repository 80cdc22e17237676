"""The pytest plugin for image regression of scenes (``splinescope.pytest_plugin``,
registered by the package's ``pytest11`` entry point), driven with pytest's own
``pytester`` in fresh processes: a bless then a passing comparison, a failing one with its
images and figures, a missing baseline, blessing all or none (and never deleting a
baseline), the summary page, and plain runs that only check the scenes render."""

import os

import pytest

BACKEND = next(
    (b.strip() for b in os.environ.get("SPLINESCOPE_TEST_BACKENDS", "auto").split(",") if b.strip()),
    "auto",
)

TESTS = '''
import os
import pytest
import splinescope as ss

def arch(height):
    return ss.Scene([ss.Bezier([[0, 0], [1, height], [2, 0]])])

@pytest.mark.splinescope_compare(width=160, height=100)
def test_arch():
    return arch(float(os.environ.get("ARCH_HEIGHT", "2")))

@pytest.mark.splinescope_compare(width=160, height=100, tolerance="channel=24,pixels=0%")
def test_circle():
    return ss.Scene([ss.Nurbs.circle([0, 0], 1.0)])
'''


def run(pytester, *args, env=None):
    if env:
        for k, v in env.items():
            pytester._monkeypatch.setenv(k, v)
    return pytester.runpytest_subprocess(
        "-p", "no:cacheprovider", f"--splinescope-backend={BACKEND}", *args, timeout=300
    )


def baselines(pytester):
    base = pytester.path / "baseline"
    return sorted(p.name for p in base.glob("*.png")) if base.is_dir() else []


def test_bless_then_compare_passes_and_a_change_fails_with_its_images(pytester):
    pytester.makepyfile(test_scenes=TESTS)
    blessed = run(pytester, "--splinescope-bless")
    blessed.assert_outcomes(passed=2)
    assert baselines(pytester) == ["test_scenes__test_arch.png", "test_scenes__test_circle.png"]
    run(pytester, "--splinescope").assert_outcomes(passed=2)
    # A taller arch: its render differs from the baseline.
    changed = run(pytester, "--splinescope", env={"ARCH_HEIGHT": "3"})
    changed.assert_outcomes(passed=1, failed=1)
    changed.stdout.fnmatch_lines(["*test_arch*differs from*px differ*FLIP mean*images:*"])
    results = pytester.path / "splinescope-results"
    for kind in ("actual", "reference", "diff", "flip"):
        assert (results / f"test_scenes__test_arch.{kind}.png").is_file(), kind
    assert not (results / "test_scenes__test_circle.actual.png").exists()


def test_a_missing_baseline_fails_saying_how_to_bless(pytester):
    pytester.makepyfile(test_scenes=TESTS)
    out = run(pytester, "--splinescope")
    out.assert_outcomes(failed=2)
    out.stdout.fnmatch_lines(["*no baseline*--splinescope-bless*"])


def test_blessing_is_all_or_none_and_never_deletes(pytester):
    pytester.makepyfile(
        test_scenes=TESTS
        + '''
@pytest.mark.splinescope_compare()
def test_broken():
    raise ValueError("no scene today")
'''
    )
    base = pytester.path / "baseline"
    base.mkdir()
    keep = base / "someone_elses.png"
    keep.write_bytes(b"not ours")
    out = run(pytester, "--splinescope-bless")
    out.assert_outcomes(passed=2, failed=1)
    out.stdout.fnmatch_lines(["*no baseline written*no scene today*"])
    assert baselines(pytester) == ["someone_elses.png"] and keep.read_bytes() == b"not ours"
    # Without the broken test every baseline is written, and the stranger's is kept.
    out = run(pytester, "--splinescope-bless", "-k", "not broken")
    out.assert_outcomes(passed=2)
    assert baselines(pytester) == [
        "someone_elses.png",
        "test_scenes__test_arch.png",
        "test_scenes__test_circle.png",
    ]


def test_bless_into_a_directory_and_the_summary_page(pytester):
    pytester.makepyfile(test_scenes=TESTS)
    run(pytester, "--splinescope-bless=golden").assert_outcomes(passed=2)
    assert sorted(p.name for p in (pytester.path / "golden").glob("*.png")) == [
        "test_scenes__test_arch.png",
        "test_scenes__test_circle.png",
    ]
    out = run(
        pytester,
        "--splinescope",
        "--splinescope-baseline=golden",
        "--splinescope-summary=html",
        env={"ARCH_HEIGHT": "3"},
    )
    out.assert_outcomes(passed=1, failed=1)
    page = (pytester.path / "splinescope-results" / "index.html").read_text()
    assert "splinescope regression report" in page
    assert "1 differs, 1 match" in page
    assert "test_scenes.py__test_arch.diff.png" in page
    assert (pytester.path / "splinescope-results" / "test_scenes.py__test_circle.reference.png").is_file()


def test_a_test_path_after_bless_is_refused_not_taken_for_a_directory(pytester):
    pytester.makepyfile(test_scenes=TESTS)
    out = run(pytester, "--splinescope-bless", "test_scenes.py")
    assert out.ret == pytest.ExitCode.USAGE_ERROR
    out.stderr.fnmatch_lines(["*--splinescope-bless took 'test_scenes.py' as the directory*"])
    assert not list(pytester.path.rglob("*.png"))
    assert (pytester.path / "test_scenes.py").is_file()
    # After the paths, or with `=`, it blesses as asked.
    run(pytester, "test_scenes.py", "--splinescope-bless").assert_outcomes(passed=2)
    assert len(list((pytester.path / "baseline").glob("*.png"))) == 2


def test_without_flags_scenes_are_only_checked_to_render(pytester):
    pytester.makepyfile(
        test_scenes=TESTS
        + '''
@pytest.mark.splinescope_compare()
def test_not_a_scene():
    return 42
'''
    )
    out = run(pytester)
    out.assert_outcomes(passed=2, failed=1)
    out.stdout.fnmatch_lines(["*returns a splinescope.Scene, not int*"])
    assert baselines(pytester) == []
