"""Rational curves from Python against closed forms: the exact circle, the quarter
circle, weights 1 as the polynomial families, weights checked as in scene files, and
paper 000's solves with the weights held fixed."""

import numpy as np
import pytest

import splinescope as ss

EPS = np.finfo(np.float64).eps


@pytest.mark.parametrize("center,radius", [((0.0, 0.0), 1.0), ((3.0, -2.0), 2.5), ((0.0, 0.0), 1e6)])
def test_nurbs_circle_is_exact_with_its_tangent_and_curvature(center, radius):
    c = ss.Nurbs.circle(center, radius)
    t = np.linspace(0.0, 1.0, 10001)
    p = c.eval(t)
    assert p.shape == (10001, 2)
    r = np.linalg.norm(p - np.asarray(center), axis=1)
    # 4εR about the origin; off it the points' own rounding scales with |C| + R.
    assert np.max(np.abs(r - radius)) <= 4 * EPS * (radius + np.linalg.norm(center))
    d = c.derivative(t)
    # Tangent ⟂ radius; curvature 1/R (away from the knots' one-sided values).
    dots = np.einsum("ij,ij->i", d, p - np.asarray(center))
    assert np.max(np.abs(dots) / (np.linalg.norm(d, axis=1) * radius)) < 1e-12
    k = c.curvature(t[1:-1])
    assert np.allclose(k * radius, 1.0, rtol=1e-9)


def test_quarter_circle_and_weights_one_are_the_polynomial_curves():
    h = np.sqrt(0.5)
    q = ss.RationalBezier([[1, 0], [1, 1], [0, 1]], [1, h, 1])
    assert q.degree == 2
    m = q.eval(0.5)
    assert np.allclose(m, [h, h], atol=4 * EPS)
    pts = np.array([[0, 0], [1, 2], [3, 2.5], [5, 1], [6, 0]], dtype=float)
    t = np.linspace(0, 1, 257)
    assert np.array_equal(ss.RationalBezier(pts, np.ones(5)).eval(t), ss.Bezier(pts).eval(t))
    knots = [0, 0, 0, 0.4, 1, 1, 1]
    assert np.array_equal(
        ss.Nurbs(knots, pts[:4], 3, np.ones(4)).eval(t), ss.BSpline(knots, pts[:4], 3).eval(t)
    )


def test_weights_are_checked_and_set_as_in_scene_files():
    c = ss.RationalBezier([[0, 0], [1, 1], [2, 0]], [1, 2, 1])
    assert np.array_equal(c.weights, [1.0, 2.0, 1.0])
    with pytest.raises(ss.SceneError) as e:
        c.weights = [1, 0, 1]
    assert e.value.path.endswith("weights[1]")
    assert "greater than 0" in str(e.value)
    assert np.array_equal(c.weights, [1.0, 2.0, 1.0]), "a refused value changes nothing"
    with pytest.raises(ss.SceneError) as e:
        ss.Nurbs("clamped_uniform", [[0, 0], [1, 1], [2, 0], [3, 1]], 3, [1, 2, 1])
    assert "3 weights for 4 control points" in str(e.value)
    c.weights = [1, 0.25, 1]
    assert c.inspect()["conic"] == "ellipse"
    segs = c.segments()
    assert len(segs) == 1 and len(segs[0]) == 4
    assert np.array_equal(segs[0][3], [1.0, 0.25, 1.0])


def test_elevation_and_knot_insertion_keep_the_rational_curve():
    c = ss.Nurbs.circle((1.0, 2.0), 3.0)
    t = np.linspace(0, 1, 1001)
    for other in (c.elevate(), c.insert_knot(0.6), ss.Curve.from_dict(c.to_dict())):
        assert np.max(np.linalg.norm(other.eval(t) - c.eval(t), axis=1)) < 1e-13
    assert c.elevate().order == 4


def test_pass_through_keeps_weights_and_meets_the_targets():
    c = ss.Nurbs(
        "clamped_uniform",
        [[0, 0], [1, 2], [2, 0], [3, 2], [4, 0], [5, 2]],
        4,
        [1, 3, 0.5, 3, 0.5, 1],
    )
    moved, report = c.pass_through([2.5, 2.0], t=0.5)
    assert np.allclose(moved.eval(0.5), [2.5, 2.0], atol=1e-12)
    assert np.array_equal(moved.weights, c.weights)
    both, report = c.pass_through_all([[1, 1.5], [4, 1.5]], params=[0.2, 0.8])
    assert report["max_residual"] < 1e-12
    kept, report = c.pass_through_keeping_tangents([2.5, 2.0], t=0.5)
    assert np.allclose(kept.eval(0.5), [2.5, 2.0], atol=1e-12)
    # P₁ stays on the line P₀P₁.
    d = kept.control_points[1] - kept.control_points[0]
    assert abs(d[0] * 2.0 - d[1] * 1.0) < 1e-12
