"""Values against independent truth: scipy's B-splines, exact rational arithmetic
(fractions) for Bézier and modified Bézier curves, the command line's own numbers."""

import json
from fractions import Fraction

import numpy as np
import pytest
from scipy.interpolate import BSpline as ScipyBSpline

import splinescope as ss

from conftest import SCENES


def random_knots(rng, n, k, clamped, repeat=True):
    inner = np.sort(rng.uniform(0.0, 10.0, n - k))
    # A repeated interior knot (multiplicity < k keeps the curve continuous).
    if repeat and n - k >= 3 and k >= 3:
        inner[1] = inner[2]
    if clamped:
        return np.concatenate([[0.0] * k, inner, [10.0] * k])
    lo = np.sort(rng.uniform(-3.0, 0.0, k))
    hi = np.sort(rng.uniform(10.0, 13.0, k))
    return np.concatenate([lo, inner, hi])


@pytest.mark.parametrize("order", [2, 3, 4, 5, 7])
@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("clamped", [True, False])
def test_bspline_equals_scipy(order, dim, clamped):
    rng = np.random.default_rng(order * 10 + dim + clamped)
    n = 12
    k = order
    knots = random_knots(rng, n, k, clamped)
    points = rng.uniform(-5, 5, (n, dim))
    ours = ss.BSpline(knots, points, order)
    ref = ScipyBSpline(knots, points, order - 1)
    a, b = ours.domain()
    assert (a, b) == (knots[k - 1], knots[n])
    t = np.linspace(a, b, 2001)
    scale = np.abs(points).max()
    np.testing.assert_allclose(ours.eval(t), ref(t), rtol=0, atol=1e-12 * scale)
    # Derivatives on simple knots (scipy does not differentiate across repeated ones).
    knots = random_knots(rng, n, k, clamped, repeat=False)
    ours = ss.BSpline(knots, points, order)
    ref = ScipyBSpline(knots, points, order - 1)
    t = np.linspace(*ours.domain(), 2001)
    for order_d in (1, 2):
        if order_d >= order:
            continue
        d_ref = ref.derivative(order_d)
        # Away from the knots (one-sided derivatives differ there at lower continuity).
        tt = t[np.min(np.abs(t[:, None] - knots[None, :]), axis=1) > 1e-6]
        got = ours.derivative(tt, order_d)
        want = d_ref(tt)
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-9 * np.abs(want).max())
    # Scalars give one point of the input's dimension.
    assert ours.eval(float(t[7])).shape == (dim,)
    np.testing.assert_allclose(ours.eval(t[7]), ref(t[7]), rtol=0, atol=1e-12 * scale)


def test_scipy_round_trip_and_interpolating_spline():
    from scipy.interpolate import make_interp_spline

    x = np.linspace(0, 2 * np.pi, 40)
    y = np.column_stack([np.cos(x), np.sin(2 * x)])
    spl = make_interp_spline(x, y, k=3)
    ours = ss.BSpline.from_scipy(spl)
    assert ours.order == 4
    np.testing.assert_allclose(ours.eval(x), y, atol=1e-12)
    back = ours.to_scipy()
    np.testing.assert_array_equal(back.t, spl.t)
    np.testing.assert_array_equal(back.c, spl.c)
    assert back.k == 3


def casteljau_exact(points, t):
    pts = [list(p) for p in points]
    while len(pts) > 1:
        pts = [[(1 - t) * a + t * b for a, b in zip(p, q)] for p, q in zip(pts, pts[1:])]
    return pts[0]


@pytest.mark.parametrize("degree", [1, 2, 3, 5, 9, 17])
def test_bezier_equals_exact_rationals(degree):
    rng = np.random.default_rng(degree)
    # Dyadic coordinates are exact in float64, so the rational value is the true one.
    points = np.round(rng.uniform(-8, 8, (degree + 1, 3)) * 64) / 64
    curve = ss.Bezier(points)
    exact_pts = [[Fraction(float(c)) for c in p] for p in points]
    ts = [Fraction(j, 64) for j in range(65)]
    got = curve.eval(np.array([float(t) for t in ts]))
    for t, g in zip(ts, got):
        want = casteljau_exact(exact_pts, t)
        for gc, wc in zip(g, want):
            assert abs(Fraction(float(gc)) - wc) <= Fraction(1, 2**40), (t, gc, float(wc))


def test_modified_bezier_closed_form_in_rationals():
    pts = [[0, 0], [1, 3], [3, 3], [4, 0]]
    t_star, v = Fraction(3, 10), [Fraction(1, 2), Fraction(-1)]
    curve = ss.ModifiedBezier(pts, float(t_star), [float(x) for x in v])
    exact = [[Fraction(c) for c in p] for p in pts]

    def bump(t):
        if t <= t_star:
            return (2 * t * t_star - t * t) / t_star**2
        return (2 * t * t_star - t * t - 2 * t_star + 1) / (t_star - 1) ** 2

    for j in range(41):
        t = Fraction(j, 40)
        q = casteljau_exact(exact, t)
        want = [q[i] + bump(t) * v[i] for i in range(2)]
        got = curve.eval(float(t))
        for gc, wc in zip(got, want):
            assert abs(float(gc) - float(wc)) <= 1e-14 * 4, (t, got, want)
    # The bump peaks at t*: R(t*) = Q(t*) + v.
    q = casteljau_exact(exact, t_star)
    np.testing.assert_allclose(curve.eval(0.3), [float(q[0] + v[0]), float(q[1] + v[1])], atol=1e-14)


def test_interpolation_passes_through_its_points():
    pts = np.array([[0, 0], [1, 2], [3, 1], [4, 4], [6, 0]], dtype=float)
    params = np.array([0, 1, 2.5, 3, 5], dtype=float)
    curve = ss.Interpolation(pts, params)
    np.testing.assert_allclose(curve.eval(params), pts, atol=1e-12)
    np.testing.assert_array_equal(curve.params, params)


def test_standard_nubmp_is_its_bspline():
    rng = np.random.default_rng(5)
    knots = random_knots(rng, 9, 4, True)
    pts = rng.uniform(-1, 1, (9, 2))
    n = ss.Nubmp(pts, knots, 4)
    ref = ScipyBSpline(knots, pts, 3)
    t = np.linspace(*n.domain(), 777)
    np.testing.assert_allclose(n.eval(t), ref(t), atol=1e-12)


def test_knot_insertion_and_elevation_keep_the_curve():
    rng = np.random.default_rng(9)
    knots = random_knots(rng, 10, 4, True)
    b = ss.BSpline(knots, rng.uniform(-1, 1, (10, 3)), 4)
    t = np.linspace(*b.domain(), 501)
    inserted = b.insert_knot(4.321)
    assert len(inserted.control_points) == 11
    np.testing.assert_allclose(inserted.eval(t), b.eval(t), atol=1e-12)
    elevated = b.elevate()
    assert elevated.order == 5
    np.testing.assert_allclose(elevated.eval(t), b.eval(t), atol=1e-12)
    bez = ss.Bezier(rng.uniform(-1, 1, (5, 2)))
    e2 = bez.elevate(3)
    assert e2.degree == 7
    tt = np.linspace(0, 1, 101)
    np.testing.assert_allclose(e2.eval(tt), bez.eval(tt), atol=1e-13)


def test_curvature_of_a_circle_like_arc_and_segments():
    # A Bézier arc of a parabola y = x²: κ(0) = 2 exactly.
    p = ss.Bezier([[-1, 1], [0, -1], [1, 1]])
    assert p.curvature(0.5) == pytest.approx(2.0, rel=1e-14)
    k = p.curvature(np.array([0.0, 0.5, 1.0]))
    assert k.shape == (3,)
    # A straight line's P″ = 0; a degenerate point P′ = 0 gives NaN.
    assert ss.Bezier([[0, 0], [1, 1]]).curvature(0.5) == 0.0
    assert np.isnan(ss.Bezier([[0, 0], [0, 0], [1, 1]]).curvature(0.0))
    segs = ss.BSpline("clamped_uniform", np.eye(6, 2), 3).segments()
    assert [s[:2] for s in segs] == [(0.0, 0.25), (0.25, 0.5), (0.5, 0.75), (0.75, 1.0)]
    assert all(s[2].shape == (3, 2) for s in segs)


def test_module_values_equal_the_command_lines(cli, tmp_path):
    for path in sorted(SCENES.glob("*.json")):
        out = json.loads(cli("eval", path, "--samples", 33, "--derivatives", 2).stdout)
        scene = ss.load(path)
        curves = scene.curves
        for report in out["curves"]:
            c = curves[report["index"]]
            a, b = c.domain()
            t = np.array([a + (b - a) * j / 32 for j in range(33)])
            t[-1] = b
            got = c.eval(t)
            want = np.array(report["samples"])[:, : c.dim]
            np.testing.assert_array_equal(got, want, err_msg=f"{path.name} curve {report['index']}")
            # Derivatives: the module differentiates each exact Bézier segment (its
            # hodograph), the command line the family's own formula; equal up to rounding.
            for key, order in (("d1", 1), ("d2", 2)):
                want_d = np.array(report[key])[:, : c.dim]
                scale = max(np.abs(want_d).max(), 1.0)
                np.testing.assert_allclose(
                    c.derivative(t, order), want_d, rtol=0, atol=1e-11 * scale
                )
            want_k = np.array([np.nan if k is None else k for k in report["curvature"]])
            np.testing.assert_allclose(c.curvature(t), want_k, rtol=1e-9, atol=1e-12)
            np.testing.assert_array_equal(c.sample(33), got)


def test_inspect_equals_the_command_lines(cli):
    path = SCENES / "paper001_fig1.json"
    out = json.loads(cli("inspect", path).stdout)
    for report, c in zip(out["curves"], ss.load(path).curves):
        mine = c.inspect()
        for key in ("family", "domain", "segments"):
            assert mine[key] == report[key], key
        assert set(report) - {"index", "name"} <= set(mine)


def test_eval_many_matches_each_curve():
    rng = np.random.default_rng(3)
    curves = [ss.Bezier(rng.uniform(-1, 1, (d + 1, 2))) for d in (1, 3, 3, 6)]
    curves.append(ss.BSpline("clamped_uniform", rng.uniform(-1, 1, (7, 2)), 4))
    many = ss.eval_many(curves, 50)
    assert many.shape == (5, 50, 2)
    for c, m in zip(curves, many):
        np.testing.assert_allclose(m, c.sample(50), atol=1e-14)


def test_inputs_of_other_dtypes_and_orders_are_converted():
    c = ss.Bezier(np.asfortranarray(np.array([[0, 0], [1, 2], [3, -1]], dtype=np.int32)))
    t32 = np.linspace(0, 1, 11, dtype=np.float32)
    strided = np.linspace(0, 1, 22)[::2]
    np.testing.assert_array_equal(c.eval(t32), c.eval(t32.astype(np.float64)))
    np.testing.assert_array_equal(c.eval(strided), c.eval(np.ascontiguousarray(strided)))
    np.testing.assert_array_equal(c.eval([0.0, 0.5]), c.eval(np.array([0.0, 0.5])))


def test_a_scene_is_a_sequence_of_curves():
    a = ss.Curve.from_dict({"type": "bezier", "name": "arch", "points": [[0, 0], [1, 2], [2, 0]]})
    b = ss.Bezier([[0, 1], [3, 1]])
    c = ss.Nurbs.circle([0.0, 0.0], 1.0)
    scene = ss.Scene([a, b, c], name="three")
    assert len(scene) == 3
    assert scene[0] == a and scene[-1] == c and scene[1] == b
    assert scene[1:] == [b, c] and scene[::-1] == [c, b, a]
    assert list(scene) == [a, b, c]
    assert a in scene and ss.Bezier([[9, 9], [8, 8]]) not in scene and "arch" not in scene
    with pytest.raises(IndexError, match="curve index 3 is out of range: the scene has 3"):
        scene[3]
    with pytest.raises(IndexError, match="-4"):
        scene[-4]
    with pytest.raises(TypeError, match="integers or slices"):
        scene["0"]
    assert len(ss.Scene()) == 0 and list(ss.Scene()) == []


def test_reprs_show_family_name_and_numbers():
    a = ss.Curve.from_dict({"type": "bezier", "name": "arch", "points": [[0, 0], [1, 2], [2, 0]]})
    r = repr(a)
    assert r.startswith("Bezier('arch', ") and "dim=2" in r, r
    assert "points=[[0, 0], [1, 2], [2, 0]]" in r.replace(".", ""), r
    # Long point lists elided, numpy-style, on one line.
    long = ss.Bezier(np.column_stack([np.arange(12.0), np.zeros(12)]))
    r = repr(long)
    assert "..." in r and "\n" not in r and "[11, 0]" in r.replace(".", ""), r
    scene = ss.Scene([a, a, ss.Nurbs.circle([0.0, 0.0], 1.0)], name="s")
    assert repr(scene) == "Scene('s', 3 curves: bezier ×2, nurbs)"
    assert repr(ss.Scene()) == "Scene(0 curves)"


def test_strings_where_numbers_go_are_type_errors():
    c = ss.Bezier([[0, 0], [1, 2], [2, 0]])
    for bad in ("0.5", b"0.5", ["0.5"], np.array(["0.5"]), None, [None]):
        with pytest.raises(TypeError, match="t must be numbers"):
            c.eval(bad)
    with pytest.raises(TypeError):
        ss.Bezier([["0", "0"], ["1", "1"]])
    # Numbers of every numeric dtype still go.
    for good in (0.5, np.float32(0.5), np.array([0, 1], dtype=np.int8), [0.25, 1]):
        c.eval(good)
    # Ranges are said in words.
    with pytest.raises(ss.CurveError, match="order = 3 is not between 1 and 2"):
        c.derivative(0.5, order=3)
