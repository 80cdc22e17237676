"""split, reverse and join from Python: the pieces trace the curve (checked against the
curve's own points and NumPy arc lengths of dense samples), reversal traces it backwards,
joined curves are one path, and bad arguments are refused naming them."""

import numpy as np
import pytest

import splinescope as ss


def _polyline_length(pts):
    return float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())


def _samples(c, n=4001):
    a, b = c.domain()
    return np.asarray(c.eval(np.linspace(a, b, n)))


CURVES = [
    ss.Bezier([[0, 0], [4, 3], [-1, 3], [3, 0]]),
    ss.RationalBezier([[-1, -4], [0, -2], [1.5, -4.5], [3, -3]], [1, 3, 0.5, 2]),
    ss.Nurbs.circle([3.0, 2.0], 1.5),
    ss.BSpline([0, 0, 0, 0, 0.3, 0.5, 1, 1, 1, 1], [[-4, 2.5], [-3, 3.5], [-2, 2], [-1, 3.5], [0, 2.5], [1, 0]], 4),
]


@pytest.mark.parametrize("curve", CURVES, ids=lambda c: type(c).__name__)
def test_split_pieces_trace_the_curve(curve):
    a, b = curve.domain()
    t = a + 0.37 * (b - a)
    left, right = curve.split(t)
    assert np.allclose(left.eval(left.domain()[1]), curve.eval(t), atol=1e-12)
    assert np.allclose(right.eval(right.domain()[0]), curve.eval(t), atol=1e-12)
    whole = _polyline_length(_samples(curve))
    parts = _polyline_length(_samples(left)) + _polyline_length(_samples(right))
    assert abs(whole - parts) <= 1e-4 * whole
    assert abs(left.length() + right.length() - curve.length()) <= 1e-10
    with pytest.raises(ss.CurveError, match="split at t"):
        curve.split(b + 1.0)


@pytest.mark.parametrize("curve", CURVES, ids=lambda c: type(c).__name__)
def test_reverse_traces_backwards(curve):
    r = curve.reverse()
    a, b = curve.domain()
    ts = np.linspace(a, b, 101)
    assert np.allclose(np.asarray(r.eval(a + b - ts)), np.asarray(curve.eval(ts)), atol=1e-12)


def test_join_makes_one_path_and_refuses_a_gap():
    a = ss.Bezier([[0, 0], [1, 1], [2, 0]])
    b = ss.Bezier([[2, 0], [3, -1], [4, 0]])
    c = ss.Bezier([[4, 0], [2, -3], [0, 0]])
    p = ss.join([a, b, c], closed=True)
    assert len(p.segments()) == 3
    assert abs(p.length() - (a.length() + b.length() + c.length())) <= 1e-10
    with pytest.raises(ss.CurveError, match="joint 0"):
        ss.join([a, ss.Bezier([[9, 9], [10, 9]])])
    with pytest.raises(ss.CurveError, match="nothing to join"):
        ss.join([])


def test_remove_knot_and_reduce_degree_from_python():
    # A knot inserted comes out again; a removal that would move the curve is refused
    # naming the bound.
    b = ss.BSpline([0, 0, 0, 0, 0.3, 0.5, 1, 1, 1, 1], [[-4, 2.5], [-3, 3.5], [-2, 2], [-1, 3.5], [0, 2.5], [1, 0]], 4)
    more = b.insert_knot(0.7)
    back, bound = more.remove_knot(0.7, with_error=True)
    ts = np.linspace(0, 1, 201)
    assert np.abs(np.asarray(back.eval(ts)) - np.asarray(b.eval(ts))).max() <= 1e-9
    assert bound <= 1e-9
    with pytest.raises(ss.CurveError, match="would move the curve by up to"):
        b.remove_knot(0.3, tolerance=1e-6)
    with pytest.raises(ss.CurveError, match="not an interior knot"):
        b.remove_knot(0.4)
    # An elevated cubic reduces back to degree 3 within the tolerance (NumPy samples).
    cubic = ss.Bezier([[0, 0], [1, 2], [3, 2], [4, 0]])
    high = cubic.elevate(3)
    low, err = high.reduce_degree(1e-9, with_error=True)
    assert len(low.control_points) == 4 and err <= 1e-9
    assert np.abs(np.asarray(low.eval(ts)) - np.asarray(cubic.eval(ts))).max() <= 1e-9
    with pytest.raises(ss.CurveError, match="is for Bézier curves"):
        b.reduce_degree(0.1)
