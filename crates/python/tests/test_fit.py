"""Fitting against scipy and NumPy (independent implementations): fit_bezier's control
points are NumPy's least-squares solution on the Bernstein design matrix; fit_bspline on
given knots is scipy's make_lsq_spline; with a smoothing budget s its sum of squared
residuals is at most s with no more knots than scipy's make_splprep at the same s; bad
inputs are refused naming them."""

from math import comb

import numpy as np
import pytest
from scipy.interpolate import make_lsq_spline, make_splprep

import splinescope as ss

RNG = np.random.default_rng(0)
TH = np.linspace(0, 6 * np.pi, 1500)
SPIRAL = np.c_[TH * np.cos(TH), TH * np.sin(TH)] + RNG.normal(0, 0.05, (1500, 2))
X = np.linspace(-1, 1, 800)
PARABOLA = np.c_[X, X**2 + RNG.normal(0, 0.01, 800)]


def _chord(pts):
    d = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))]
    return d / d[-1]


def test_fit_bezier_is_the_least_squares_solution():
    pts = PARABOLA
    t = _chord(pts)
    for degree in (2, 3, 5):
        curve, res = ss.fit_bezier(pts, degree)
        # NumPy: the same problem with the ends free (no constraint either way).
        design = np.stack([comb(degree, i) * t**i * (1 - t) ** (degree - i) for i in range(degree + 1)], axis=1)
        want, *_ = np.linalg.lstsq(design, pts, rcond=None)
        assert np.abs(curve.control_points - want).max() <= 1e-9
        assert np.allclose(res, np.linalg.norm(design @ want - pts, axis=1), atol=1e-12)


def test_fit_bspline_on_given_knots_is_scipys_least_squares_spline():
    pts = SPIRAL
    t = _chord(pts)
    interior = [0.1, 0.2, 0.35, 0.5, 0.65, 0.8, 0.9]
    w = RNG.uniform(0.5, 2.0, len(pts))
    curve, res = ss.fit_bspline(pts, 3, knots=interior, weights=w)
    full = np.r_[[0.0] * 4, interior, [1.0] * 4]
    theirs = make_lsq_spline(t, pts, full, k=3, w=w)
    assert np.abs(curve.control_points - theirs.c).max() <= 1e-8


@pytest.mark.parametrize("pts,sigma", [(SPIRAL, 0.05), (PARABOLA, 0.01)], ids=["spiral", "parabola"])
def test_smoothing_meets_the_budget_with_no_more_knots_than_scipy(pts, sigma):
    for s in (2 * len(pts) * sigma**2, 0.5 * len(pts) * sigma**2):
        curve, res = ss.fit_bspline(pts, 3, smoothing=s)
        assert float(np.sum(res**2)) <= s
        spl, _ = make_splprep([pts[:, 0], pts[:, 1]], s=s, k=3)
        ours, theirs = len(curve.knots) - 8, len(spl.t) - 8
        assert ours <= theirs, (ours, theirs)
    # s = 0: through every point.
    few = PARABOLA[::40]
    curve, res = ss.fit_bspline(few, 3, smoothing=0)
    assert res.max() <= 1e-10


def test_bad_inputs_are_refused_naming_them():
    with pytest.raises(ss.CurveError, match=r"points\[1\]"):
        ss.fit_bezier([[0, 0], [np.nan, 1], [2, 0], [3, 1]], 3)
    with pytest.raises(ss.CurveError, match="at least 4"):
        ss.fit_bezier([[0, 0], [1, 1]], 3)
    with pytest.raises(ss.CurveError, match=r"knots\[0\]"):
        ss.fit_bspline(SPIRAL, 3, knots=[1.5])
    with pytest.raises(ss.CurveError, match="smoothing"):
        ss.fit_bspline(SPIRAL, 3, smoothing=-1.0)
    with pytest.raises(ss.CurveError, match=r"weights\[2\]"):
        ss.fit_bezier(PARABOLA[:5], 2, weights=[1, 1, 0, 1, 1])
    with pytest.raises(ss.CurveError, match="params"):
        ss.fit_bezier(PARABOLA, 2, params="uniformish")
    with pytest.raises(ss.CurveError, match="cannot pin down"):
        ss.fit_bspline(PARABOLA[:10], 3, knots=[0.001, 0.002, 0.003])


def test_fit_path_keeps_the_points_within_the_tolerance_and_the_corners():
    # A square drawn by a pen: four sides, densely sampled; four corners kept.
    side = np.linspace(0, 1, 60, endpoint=False)
    square = np.concatenate([
        np.c_[side, 0 * side], np.c_[1 + 0 * side, side], np.c_[1 - side, 1 + 0 * side], np.c_[0 * side, 1 - side]
    ])
    square = np.vstack([square, square[:1]])
    path, res = ss.fit_path(square, 1e-6)
    assert res.max() <= 1e-6
    assert len(path.segments()) == 4
    # Measured independently: NumPy samples of each cubic lie on the square's sides.
    for s in path.segments():
        c = np.asarray(s[2])[:, :2]
        t = np.linspace(0, 1, 50)[:, None]
        pts = (1 - t) ** 3 * c[0] + 3 * (1 - t) ** 2 * t * c[1] + 3 * (1 - t) * t**2 * c[2] + t**3 * c[3]
        off = np.minimum.reduce([np.abs(pts[:, 0]), np.abs(pts[:, 0] - 1), np.abs(pts[:, 1]), np.abs(pts[:, 1] - 1)])
        assert off.max() <= 1e-6
    with pytest.raises(ss.CurveError, match="tolerance"):
        ss.fit_path(square, -1.0)
