"""The module's arguments are untrusted input: sample counts and elevations within the
command line's limits (checked before any work), rational curves whose weights leave
f64 refused naming the parameter, solves that cannot meet their target refused, whole
numbers and curves checked with the argument and the method named, and NaN inside a dict
named by its path — never an abort, an internal exception or a silent miss."""

import math

import numpy as np
import pytest

import splinescope as ss


def quintic():
    return ss.Bezier([[0, 0], [1, 2], [3, 0], [4, 3], [5, -1]])


def test_sample_counts_have_the_command_lines_limit():
    c = quintic()
    for n in (2**40, 2**27 + 1):
        with pytest.raises(ss.CurveError) as e:
            c.sample(n)
        assert e.value.path == "n"
        assert "SPLINESCOPE_MAX_SAMPLES" in str(e.value) and str(n) in str(e.value)
    with pytest.raises(ss.CurveError) as e:
        ss.eval_many([c, c], 2**26 + 1)
    assert "2 curves" in str(e.value) and "SPLINESCOPE_MAX_SAMPLES" in str(e.value)
    with pytest.raises(ss.CurveError, match="sample: n = 1 is below 2"):
        c.sample(1)
    assert c.sample(5).shape == (5, 2)


def test_elevation_is_checked_before_the_work():
    b = quintic()
    for times in (30000, 2**31, 2**62):
        with pytest.raises(ss.CurveError) as e:
            b.elevate(times)
        assert e.value.path == "times"
        assert f"elevate(times={times})" in str(e.value)
        assert "SPLINESCOPE_MAX_DEGREE" in str(e.value)
    assert b.elevate(995).degree == 999
    s = ss.BSpline("clamped_uniform", np.random.default_rng(2).uniform(size=(6, 2)), 4)
    with pytest.raises(ss.CurveError, match="SPLINESCOPE_MAX_ORDER") as e:
        s.elevate(61)  # order 65
    assert e.value.path == "times"
    top = s.elevate(60)  # order 64: the module reads back what it returns
    assert top.order == 64
    again = ss.Curve.from_dict(top.to_dict())
    assert again.order == 64
    circle = ss.Nurbs.circle()
    with pytest.raises(ss.CurveError, match="SPLINESCOPE_MAX_ORDER"):
        circle.elevate(62)
    assert ss.Scene.from_json(ss.Scene([circle.elevate(61)]).to_json()).curves[0].order == 64


def test_rational_curves_with_extreme_weights():
    pts = [[0, 0], [1, 2], [3, 0.5], [4, 3]]
    base = np.array([1.0, 0.5, 2.0, 1.0])
    ref = ss.RationalBezier(pts, base)
    t = np.linspace(0, 1, 33)
    for scale in (1e300, 1e-300, 2.0**1000):
        c = ss.RationalBezier(pts, base * scale)
        np.testing.assert_allclose(c.eval(t), ref.eval(t), rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(c.derivative(t), ref.derivative(t), rtol=1e-11, atol=1e-11)
        np.testing.assert_allclose(
            c.derivative(t, 2), ref.derivative(t, 2), rtol=1e-10, atol=1e-10
        )
        np.testing.assert_allclose(c.curvature(t), ref.curvature(t), rtol=1e-10)
    # Weights 2^±1000 apart: where the derivative leaves f64, refused naming t;
    # everywhere else finite, and the curvature never negative.
    wild = ss.RationalBezier(pts, [2.0**-1000, 1.0, 1.0, 2.0**1000])
    for method in ("eval", "derivative", "curvature"):
        for k, tk in enumerate(t):
            try:
                v = getattr(wild, method)(float(tk))
            except ss.CurveError as e:
                assert e.path == "t" and "not a finite number" in str(e), str(e)
                continue
            v = np.asarray(v)
            assert np.all(np.isfinite(v)) or (method == "curvature" and np.isnan(v)), (
                method,
                tk,
                v,
            )
            if method == "curvature" and not np.isnan(v):
                assert v >= 0
        try:
            out = getattr(wild, method)(t)
        except ss.CurveError as e:
            assert e.path.startswith("t[") and "not a finite number" in str(e)
        else:
            assert np.all(np.isfinite(out) | np.isnan(out))


def test_nurbs_solves_meet_their_target_or_are_refused():
    circle = ss.Nurbs.circle()
    target = [1.5, 0.5]
    # A window whose basis is 0 at t: refused, naming the points that do move it.
    with pytest.raises(ss.SolveError) as e:
        circle.pass_through([-1.5, 0.2], t=0.5, first=1, count=1)
    assert "P_1" in str(e.value) and "P_4" in str(e.value) and e.value.path == "t"
    # The default window at the same knot: the target is met.
    moved, report = circle.pass_through([-1.5, 0.2], t=0.5)
    assert np.linalg.norm(moved.eval(0.5) - [-1.5, 0.2]) < 1e-12
    assert report["residual"] < 1e-12
    # Next to an end, where the interior points barely (or in f64 not at all) move the
    # curve: the target is met, however far the points move, or the solve is refused
    # naming the parameter.
    refused = 0
    for t in (5e-324, 1e-300, 1e-200, 1e-100, 1e-20, 1.0 - 2.0**-53):
        try:
            moved, report = circle.pass_through(target, t=t)
        except ss.SolveError as e:
            assert e.path == "t" and "t = " in str(e), str(e)
            refused += 1
            continue
        assert np.all(np.isfinite(moved.control_points))
        assert np.linalg.norm(moved.eval(t) - target) <= 1e-9, (t, report)
    assert refused >= 1
    # Everywhere else, the target is met.
    for t in np.linspace(0.01, 0.99, 37):
        moved, report = circle.pass_through(target, t=float(t))
        assert np.linalg.norm(moved.eval(float(t)) - target) <= 1e-9, (t, report)
    # The same for a Bézier curve and the other methods.
    b = quintic()
    with pytest.raises(ss.SolveError):
        b.pass_through([2, 2], t=1e-300)
    moved, _ = b.pass_through_all([[1, 1], [3, 2]], params=[0.3, 0.7])
    assert np.allclose(moved.eval(np.array([0.3, 0.7])), [[1, 1], [3, 2]], atol=1e-12)
    with pytest.raises(ss.SolveError) as e:
        b.pass_through_all([[1, 1], [3, 2]], params=[0.3, 1e-300])
    assert e.value.path == "params[1]"


def test_whole_numbers_are_checked_naming_the_argument_and_method():
    c = quintic()
    cases = [
        (lambda: c.sample(-1), ss.CurveError, "sample: n = -1"),
        (lambda: c.sample(2**70), ss.CurveError, "sample: n = "),
        (lambda: c.sample(5.0), TypeError, "sample: n must be a whole number"),
        (lambda: c.sample(True), TypeError, "sample: n must be a whole number"),
        (lambda: c.sample("5"), TypeError, "sample: n must be a whole number"),
        (lambda: c.derivative(0.5, order=1.5), TypeError, "derivative: order"),
        (lambda: c.remove_point(-1), ss.CurveError, "remove_point: index = -1"),
        (lambda: c.remove_point(2**64), ss.CurveError, "remove_point: index"),
        (lambda: c.elevate(-2), ss.CurveError, "elevate: times = -2"),
        (lambda: c.elevate(1.0), TypeError, "elevate: times"),
        (lambda: ss.eval_many([c], -3), ss.CurveError, "eval_many: n = -3"),
        (lambda: ss.eval_many([c], None), TypeError, "eval_many: n"),
        (lambda: c.pass_through([1, 1], first=-1), ss.CurveError, "pass_through: first = -1"),
        (lambda: c.pass_through([1, 1], count=1.5), TypeError, "pass_through: count"),
        (lambda: ss.Scene([c]).render(width=-1), ss.CurveError, "render: width = -1"),
        (lambda: ss.Scene([c]).png(height=10**9), ss.CurveError, "png: height"),
        (lambda: ss.Scene([c]).export("x.svg", width=2.5), TypeError, "export: width"),
        (lambda: ss.Scene([c]).export("x.svg", labels="yes"), TypeError, "export: labels"),
        (lambda: ss.Curve.from_dict(c.to_dict(), dim=4), ss.CurveError, "from_dict: dim = 4"),
        (lambda: c.eval(10**400), ValueError, "t = 1000"),
    ]
    for call, cls, says in cases:
        with pytest.raises(cls) as e:
            call()
        assert type(e.value) is cls or isinstance(e.value, cls)
        assert says in str(e.value), (says, str(e.value))
        assert not isinstance(e.value, OverflowError)


def test_no_internal_exception_leaks():
    c = quintic()
    with pytest.raises(TypeError, match=r"curves\[0\] must be a Curve"):
        ss.Scene([None])
    with pytest.raises(TypeError, match=r"curves\[1\] must be a Curve"):
        ss.eval_many([c, None], 3)
    with pytest.raises(TypeError, match="curves must be a sequence"):
        ss.Scene(5)
    with pytest.raises(TypeError, match="name must be a string"):
        ss.Scene([c], name=3)
    with pytest.raises(ss.SceneError) as e:
        ss.Nurbs.circle([0], 1)
    assert e.value.path == "center"
    with pytest.raises(ss.SceneError) as e:
        ss.Scene([c], name="a\x01b")
    assert e.value.path == "name" and "U+0001" in str(e.value)
    with pytest.raises(ss.SceneError) as e:
        ss.Curve.from_dict({"type": "bezier", "name": "\ufffe", "points": [[0, 0], [1, 1]]})
    assert e.value.path == "name"
    with pytest.raises(TypeError, match="obj must be a dict"):
        ss.Curve.from_dict([1, 2])
    with pytest.raises(TypeError, match="modification must be a dict"):
        ss.Interpolation([[0, 0], [1, 1], [2, 0]], modification="bump")
    with pytest.raises(TypeError, match="solve: scene must be a Scene"):
        ss.solve(None, {})


def test_nan_inside_a_dict_is_named_by_its_path():
    with pytest.raises(ss.SceneError) as e:
        ss.Curve.from_dict({"type": "bezier", "points": [[0, 0], [math.nan, 1]]})
    assert e.value.path == "points[1][0]" and "nan is not a finite number" in str(e.value)
    n = ss.Nubmp(np.random.default_rng(1).uniform(size=(7, 2)), "clamped_uniform", 4)
    with pytest.raises(ss.SceneError) as e:
        n.shape = [{"group": 2, "values": [math.nan, 0.5]}]
    assert e.value.path == "shape[0].values[0]"
    with pytest.raises(ss.SceneError) as e:
        quintic().solve("single_target", target=[1.0, math.inf])
    assert e.value.path == "target[1]"
    with pytest.raises(ss.SceneError) as e:
        ss.solve(ss.Scene([quintic()]), {"curve": 0, "method": "multi_target", "targets": [[1, 1]], "params": [np.float64("nan")]})
    assert e.value.path == "params[0]"
    with pytest.raises(TypeError, match=r"points\[0\]: object"):
        ss.Curve.from_dict({"type": "bezier", "points": [object(), [1, 1]]})
