"""The analysis methods against an independent peer and closed forms: intersections and
lengths against the `bezier` package (random pairs, degree 3 to 7, and constructed hard
pairs: tangent, touching at endpoints, near-parallel, coincident), lengths, boxes, areas
and curvature against closed forms; bad arguments refused naming them."""

import math

import numpy as np
import pytest

import splinescope as ss

try:
    import bezier  # the independent peer; scripts/python-dev installs it from PyPI
except ImportError as e:  # pragma: no cover - a missing peer fails, it does not skip
    raise ImportError(
        "the analysis tests compare with the `bezier` package: pip install bezier "
        "(scripts/python-dev does)"
    ) from e


def peer(points):
    pts = np.asarray(points, dtype=np.float64)
    return bezier.Curve(np.asfortranarray(pts.T), degree=len(pts) - 1)


def peer_pairs(a, b):
    """The bezier package's intersections, as sorted (s, t) rows."""
    st = peer(a).intersect(peer(b))
    st = np.asarray(st).T if st.size else np.zeros((0, 2))
    return st[np.argsort(st[:, 0])] if len(st) else st


def test_random_pairs_agree_with_the_bezier_package():
    rng = np.random.default_rng(20261202)
    compared = 0
    for degree in (3, 4, 5, 7):
        for _ in range(60):
            a = rng.uniform(0, 1, size=(degree + 1, 2))
            b = rng.uniform(0, 1, size=(degree + 1, 2))
            try:
                want = peer_pairs(a, b)
            except (NotImplementedError, ValueError):
                continue  # the peer gives up (tangencies); tested below by construction
            got = ss.Bezier(a).intersect(ss.Bezier(b))
            assert got.shape == want.shape, (degree, a.tolist(), b.tolist(), got, want)
            np.testing.assert_allclose(got, want, atol=1e-9)
            # Both parameters give one point, to a few ulps.
            pa, pb = ss.Bezier(a).eval(got[:, 0]), ss.Bezier(b).eval(got[:, 1])
            assert np.all(np.abs(pa - pb) <= 1e-14) if len(got) else True
            compared += 1
    assert compared > 150


def test_constructed_hard_pairs():
    # Crossing at a shared end point.
    a = [[0, 0], [1, 2], [2, 0]]
    b = [[2, 0], [3, 1], [4, -1]]
    st = ss.Bezier(a).intersect(ss.Bezier(b))
    assert st.tolist() == [[1.0, 0.0]]
    np.testing.assert_allclose(peer_pairs(a, b), st, atol=1e-12)
    # Near-parallel lines crossing at a small angle.
    a = [[0, 0], [1, 1e-6 * 1], [2, 2e-6]]
    b = [[0, 1e-6], [1, 1e-6], [2, 1e-6]]
    st, kinds = ss.Bezier(a).intersect(ss.Bezier(b), kinds=True)
    np.testing.assert_allclose(st, peer_pairs(a, b), atol=1e-9)
    assert kinds == ["crossing"]
    # A tangency: the parabola y = x² − 1 … touching y = −1 at x = 0 (t = ½ on both).
    a = [[-1, 0], [0, -2], [1, 0]]
    b = [[-1, -1], [0, -1], [1, -1]]
    st, kinds = ss.Bezier(a).intersect(ss.Bezier(b), kinds=True)
    assert kinds == ["tangent"]
    np.testing.assert_allclose(st, [[0.5, 0.5]], atol=1e-12)
    # Coincident: a cubic and a piece of itself — an overlap, no cloud of points.
    cubic = ss.Bezier([[0, 0], [1, 3], [2, -2], [3, 1]])
    piece = ss.Bezier(
        peer([[0, 0], [1, 3], [2, -2], [3, 1]]).specialize(0.25, 0.75).nodes.T
    )
    assert cubic.intersect(piece).shape == (0, 2)
    ((s0, s1), (t0, t1)), = cubic.overlaps(piece)
    assert abs(s0 - 0.25) < 1e-9 and abs(s1 - 0.75) < 1e-9
    assert abs(t0) < 1e-9 and abs(t1 - 1) < 1e-9


def test_lengths_agree_with_the_bezier_package_and_closed_forms():
    rng = np.random.default_rng(7)
    for degree in (2, 3, 5, 9):
        for _ in range(20):
            pts = rng.uniform(-1, 1, size=(degree + 1, 2))
            assert abs(ss.Bezier(pts).length(accuracy=1e-12) - peer(pts).length) < 1e-9
    circle = ss.Nurbs.circle([0.0, 0.0], 2.5)
    assert abs(circle.length() - 5 * math.pi) < 1e-12
    assert abs(circle.length(0, 0.25) - 1.25 * math.pi) < 1e-12
    t = circle.parameter_at_length(math.pi)
    assert abs(circle.length(0, t) - math.pi) < 1e-11
    np.testing.assert_allclose(circle.bbox(), [[-2.5, -2.5], [2.5, 2.5]], atol=1e-15)
    assert abs(circle.signed_area() - math.pi * 6.25) < 1e-12
    assert circle.is_closed()


def test_shape_answers():
    s_curve = ss.Bezier([[0, 0], [1, 1], [2, -1], [3, 0]])
    np.testing.assert_allclose(s_curve.inflections(), [0.5], atol=1e-15)
    parabola = ss.Bezier([[-1, 1], [0, -1], [1, 1]])
    ex = parabola.curvature_extrema()
    assert ex.shape == (1, 4)
    np.testing.assert_allclose(ex[0], [0.5, 2.0, 2.0, 1.0], atol=1e-9)
    # Traversed turning right: the vertex is still the maximum of |κ|; the signed κ and
    # curvature(t, signed=True) agree on its sign, the plain curvature is |κ|.
    down = ss.Bezier([[1, 1], [0, -1], [-1, 1]])
    ex = down.curvature_extrema()
    np.testing.assert_allclose(ex[0], [0.5, 2.0, -2.0, 1.0], atol=1e-9)
    assert down.curvature(0.5) == pytest.approx(2.0)
    assert down.curvature(0.5, signed=True) == pytest.approx(-2.0)
    np.testing.assert_allclose(
        down.curvature(np.array([0.25, 0.5]), signed=True), -down.curvature(np.array([0.25, 0.5]))
    )
    with pytest.raises(TypeError, match="signed"):
        down.curvature(0.5, signed="yes")
    cusp = ss.Bezier([[0, 0], [1, 1], [0, 1], [1, 0]])
    np.testing.assert_allclose(cusp.cusps(), [0.5], atol=1e-7)
    loop = ss.Bezier([[0, 0], [1.5, 1], [-0.5, 1], [1, 0]])
    st = loop.self_intersections()
    assert st.shape == (1, 2) and abs(st[0].sum() - 1) < 1e-13
    # extrema per axis: y of the parabola at ½.
    np.testing.assert_allclose(parabola.extrema(axis=1), [0.5])
    report = s_curve.analyze()
    assert report["inflections"][0]["t"] == pytest.approx(0.5)
    # Every pair among curves, on every core.
    found = ss.intersections([s_curve, parabola, loop])
    assert all(f["i"] < f["j"] for f in found)
    one = [f for f in found if (f["i"], f["j"]) == (0, 1)]
    assert len(one) == 1
    np.testing.assert_allclose(one[0]["params"], s_curve.intersect(parabola))


def test_bad_arguments_name_the_value():
    c = ss.Bezier([[0, 0], [1, 2], [2, 0]])
    with pytest.raises(ss.CurveError) as e:
        c.length(accuracy=0)
    assert e.value.path == "accuracy" and "accuracy 0" in str(e.value)
    with pytest.raises(ss.CurveError) as e:
        c.length(t1=1.5)
    assert e.value.path == "t1" and "outside the domain" in str(e.value)
    with pytest.raises(ss.CurveError) as e:
        c.parameter_at_length(100.0)
    assert e.value.path == "s"
    with pytest.raises(TypeError, match="length: accuracy must be a number"):
        c.length(accuracy="fine")
    space = ss.Bezier([[0, 0, 0], [1, 1, 1], [2, 0, 2]])
    for method in ("inflections", "cusps", "curvature_extrema", "signed_area", "self_intersections"):
        with pytest.raises(ss.CurveError, match="planar"):
            getattr(space, method)()
    with pytest.raises(ss.CurveError, match="planar"):
        space.intersect(c)
    with pytest.raises(TypeError, match="other must be a Curve"):
        c.intersect(None)
    with pytest.raises(ss.CurveError, match=r"curves\[1\] is not planar"):
        ss.intersections([c, space])
    with pytest.raises(ss.CurveError):
        c.extrema(axis=2)


def test_each_point_carries_its_error_bound():
    # Two lines crossing at (½, ½): parameters exactly ½; the bound is a few ulps.
    a, b = ss.Bezier([[0, 0], [1, 1]]), ss.Bezier([[0, 1], [1, 0]])
    st, kinds, errors = a.intersect(b, kinds=True, errors=True)
    assert st.tolist() == [[0.5, 0.5]] and kinds == ["crossing"]
    assert errors.shape == (1, 2) and np.all(errors > 0) and np.all(errors < 1e-14)
    # At a small angle the bound grows with the crossing's condition number (1 / sin θ).
    shallow = ss.Bezier([[0, 0.5 - 1e-6], [1, 0.5 + 1e-6]])
    _, e_shallow = ss.Bezier([[0, 0.5], [1, 0.5]]).intersect(shallow, errors=True)
    assert e_shallow.shape == (1, 2) and e_shallow[0, 0] > 1e4 * errors[0, 0]
    # A tangency is known to its band, far wider than a crossing's ulps, and holds the
    # exact touching point (t = ½ on both) within it.
    p, line = ss.Bezier([[-1, 0], [0, -2], [1, 0]]), ss.Bezier([[-1, -1], [0, -1], [1, -1]])
    st, kinds, errors = p.intersect(line, kinds=True, errors=True)
    assert kinds == ["tangent"]
    assert np.all(np.abs(st - 0.5) <= errors) and np.all(errors > 1e-12)
    # The same bounds from the many-curve sweep, when asked for.
    found = ss.intersections([a, b, p, line], errors=True)
    pair = [f for f in found if (f["i"], f["j"]) == (0, 1)][0]
    np.testing.assert_array_equal(pair["errors"], a.intersect(b, errors=True)[1])
    assert "errors" not in ss.intersections([a, b])[0]
    with pytest.raises(TypeError, match="errors"):
        a.intersect(b, errors=1)


def test_copies_are_one_group_not_pairs():
    c = ss.Bezier([[0, 0], [1, 2], [2, -1], [3, 1]])
    line = ss.Bezier([[0, 1], [3, 0]])
    found = ss.intersections([c, line, c, c, line])
    assert [g["copies"] for g in found if "copies" in g] == [[0, 2, 3], [1, 4]]
    assert all(g["interval"] == (0.0, 1.0) for g in found if "copies" in g)
    # Every member of one group meets every member of the other as the first curves do;
    # no pair within a group.
    want = c.intersect(line)
    pairs = {(f["i"], f["j"]): f for f in found if "i" in f}
    assert sorted(pairs) == [(0, 1), (0, 4), (1, 2), (1, 3), (2, 4), (3, 4)]
    for (i, j), f in pairs.items():
        got = f["params"] if i in (0, 2, 3) else f["params"][:, ::-1]
        np.testing.assert_array_equal(got[np.argsort(got[:, 0])], want)


def test_joints_report_the_continuity_built_into_them():
    import math

    import numpy as np
    import splinescope as ss

    # A triple knot at 1 with the tangents built 60° apart: one kink of exactly 60°.
    th = math.radians(60)
    c = np.array([3.0, 1.0])
    d = np.array([math.cos(th), math.sin(th)])
    pts = [[0, 0], [1, 1.5], c - [1, 0], c, c + d, c + 2 * d + [0, 0.5], c + 3 * d]
    kinked = ss.BSpline([0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2], pts, 4)
    j = kinked.joints()
    assert j.shape == (1, 4)
    assert j[0, 0] == 1.0 and j[0, 1] <= 1e-12
    assert abs(j[0, 2] - th) <= 1e-12
    # Simple knots: C², every joint within rounding.
    smooth = ss.BSpline([0, 0, 0, 0, 1, 2, 3, 3, 3, 3], [[0, 0], [1, 2], [2, -1], [3, 1], [4, 0], [5, 2]], 4)
    j = smooth.joints()
    assert j.shape == (2, 4)
    assert (j[:, 1] <= 1e-12).all() and (j[:, 2] <= 1e-12).all() and (j[:, 3] <= 1e-9).all()
    # A circle: its three inner joints and its seam, all G2; an open Bézier curve: none.
    circle = ss.Nurbs.circle([0.0, 0.0], 2.0)
    j = circle.joints()
    assert len(j) >= 2 and j[-1, 0] == circle.domain()[1]
    assert (j[:, 2] <= 1e-9).all() and (j[:, 3] <= 1e-8).all()
    assert ss.Bezier([[0, 0], [1, 1], [2, 0]]).joints().shape == (0, 4)
