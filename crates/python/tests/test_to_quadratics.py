"""curve.to_quadratics and to_cubics against fontTools' cu2qu on every cubic of a CFF font
(Debian's Cantarell): no more segments than cu2qu's curve_to_quadratic at the same
tolerance, and every result within the tolerance of its cubic — measured by NumPy on
dense samples of both (an independent computation), not by the bound."""

import numpy as np
import pytest

import splinescope as ss

try:
    from fontTools.cu2qu import curve_to_quadratic
except ImportError:  # pragma: no cover - scripts/python-dev installs it
    pytest.fail("fonttools is missing: it is a test extra, scripts/python-dev installs it", pytrace=False)

CANTARELL = "/usr/share/fonts/opentype/cantarell/Cantarell-Regular.otf"


def _cubics():
    scene = ss.load(CANTARELL)
    out = []
    for c in scene.curves:
        for s in c.segments():
            pts = np.asarray(s[2])[:, :2]
            if len(pts) == 4:
                out.append(pts)
    return out


def _sample(ctrl, n):
    """Points of the Bézier curve with control points `ctrl` at n uniform parameters
    (Bernstein form, NumPy)."""
    from math import comb

    d = len(ctrl) - 1
    t = np.linspace(0.0, 1.0, n)[:, None]
    return sum(comb(d, i) * t**i * (1 - t) ** (d - i) * ctrl[i] for i in range(d + 1))


def _distance_to_polyline(points, line):
    """Each point's distance to the polyline through `line` (upper bound of the distance
    to the curve it samples, up to its chords' sag)."""
    a, b = line[:-1], line[1:]
    ab = b - a
    best = np.full(len(points), np.inf)
    for i in range(len(a)):
        ap = points - a[i]
        denom = max(float(ab[i] @ ab[i]), 1e-300)
        s = np.clip(ap @ ab[i] / denom, 0.0, 1.0)
        d = np.linalg.norm(ap - s[:, None] * ab[i], axis=1)
        best = np.minimum(best, d)
    return best


@pytest.mark.parametrize("tolerance", [1.0, 0.1])
def test_no_more_quadratics_than_cu2qu_on_every_cubic_of_a_cff_font(tolerance):
    cubics = _cubics()
    assert len(cubics) > 5000
    ours = sum(len(ss.Bezier(p).to_quadratics(tolerance).segments()) for p in cubics)
    theirs = sum(len(curve_to_quadratic([tuple(q) for q in p], tolerance)) - 2 for p in cubics)
    assert ours <= theirs, (ours, theirs)


def test_each_result_is_within_the_tolerance_measured_on_samples():
    rng = np.random.default_rng(5)
    cubics = _cubics()
    for idx in rng.choice(len(cubics), 30, replace=False):
        ctrl = cubics[idx]
        for tol, method in [(0.5, "to_quadratics"), (0.05, "to_cubics")]:
            path, bound = getattr(ss.Bezier(ctrl), method)(tol, with_error=True)
            assert bound <= tol
            pieces = [np.asarray(s[2])[:, :2] for s in path.segments()]
            ours = np.concatenate([_sample(q, 400) for q in pieces])
            theirs = _sample(ctrl, 4000)
            # Chord sag of 4000 samples of a glyph cubic (a few hundred units) is far below
            # the tolerances here; the comparison is both ways.
            assert _distance_to_polyline(ours, theirs).max() <= tol * 1.0001
            assert _distance_to_polyline(theirs, ours).max() <= tol * 1.0001


def test_bad_tolerances_are_refused_naming_them():
    c = ss.Bezier([[0, 0], [1, 2], [3, -1], [4, 1]])
    for bad in (0.0, -1.0, float("nan")):
        with pytest.raises(ss.CurveError, match="tolerance"):
            c.to_quadratics(bad)
    with pytest.raises(TypeError, match="tolerance"):
        c.to_cubics("small")
