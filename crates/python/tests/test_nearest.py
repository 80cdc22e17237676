"""curve.nearest: the global nearest point, against dense sampling refined by scipy's
bounded scalar minimisation (an independent computation), one point and many at once,
with bad points refused naming them."""

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

import splinescope as ss


def _curves():
    loop = ss.Bezier([[0, 0], [4, 3], [-1, 3], [3, 0]])
    wiggle = ss.Bezier([[x, np.sin(3 * x)] for x in np.linspace(-2, 2, 8)])
    circle = ss.Nurbs.circle([1.0, -1.0], 2.0)
    rational = ss.RationalBezier([[-1, -4], [0, -2], [1.5, -4.5], [3, -3]], [1, 3, 0.5, 2])
    space = ss.Bezier([[0, 0, 0], [1, 2, 1], [2, -1, 2], [3, 1, -1]])
    return [loop, wiggle, circle, rational, space]


def _reference(curve, q):
    t0, t1 = curve.domain()
    ts = np.linspace(t0, t1, 4001)
    pts = np.asarray(curve.eval(ts))
    d = np.linalg.norm(pts - q[: pts.shape[1]], axis=1) if len(q) == pts.shape[1] else None
    if d is None:
        full = np.zeros((len(ts), 3))
        full[:, : pts.shape[1]] = pts
        d = np.linalg.norm(full - q, axis=1)
    i = int(np.argmin(d))
    lo, hi = ts[max(i - 1, 0)], ts[min(i + 1, len(ts) - 1)]

    def f(t):
        p = np.zeros(3)
        v = np.asarray(curve.eval(t))
        p[: len(v)] = v
        qq = np.zeros(3)
        qq[: len(q)] = q
        return float(np.linalg.norm(p - qq))

    r = minimize_scalar(f, bounds=(lo, hi), method="bounded", options={"xatol": 1e-12})
    return min(float(d[i]), float(r.fun))


def test_nearest_is_never_beaten_by_sampling_and_refinement():
    rng = np.random.default_rng(48)
    for c in _curves():
        dim = np.asarray(c.eval(c.domain()[0])).shape[0]
        for _ in range(40):
            q = rng.uniform(-5, 5, size=dim)
            t, d = c.nearest(q)
            ref = _reference(c, q)
            assert d <= ref + 1e-12 * (1 + ref), (c, q, d, ref)
            assert ref - d <= 1e-7, (c, q, d, ref)
            assert abs(np.linalg.norm(np.asarray(c.eval(t)) - q) - d) <= 1e-12 * (1 + d)


def test_many_points_answer_as_one_by_one_and_shapes_are_kept():
    c = _curves()[0]
    rng = np.random.default_rng(1)
    pts = rng.uniform(-2, 5, size=(300, 2))
    ts, ds = c.nearest(pts)
    assert ts.shape == (300,) and ds.shape == (300,)
    for q, t, d in zip(pts, ts, ds):
        assert (t, d) == c.nearest(q)
    # A 2-D curve and 3-D points: the distance counts z.
    t, d = c.nearest([*np.asarray(c.eval(0.3)), 2.0])
    assert abs(d - 2.0) <= 1e-12


def test_bad_points_are_refused_naming_them():
    c = _curves()[0]
    with pytest.raises(ss.CurveError, match=r"p\[1\] = \(1, NaN\)"):
        c.nearest([[0.0, 0.0], [1.0, np.nan]])
    with pytest.raises(ss.CurveError, match="shape"):
        c.nearest([1.0, 2.0, 3.0, 4.0])
    with pytest.raises(TypeError):
        c.nearest("origin")
