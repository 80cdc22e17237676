"""curve.offset against independent truth computed here with NumPy: the true offset
C(t) + d n(t) sampled densely (the normal from central differences of curve.eval), both
ways against the result (every result point near the true offset, every true offset
point near the result) within the bound, which is within the tolerance; a circle's
offset against its closed form; stroke outlines and trimming; bad arguments refused by
name."""

import numpy as np
import pytest

import splinescope as ss

CURVES = [
    ss.Bezier([[0, 0], [4, 3], [-1, 3], [3, 0]]),
    ss.RationalBezier([[-1, -4], [0, -2], [1.5, -4.5], [3, -3]], [1, 3, 0.5, 2]),
    ss.BSpline([0, 0, 0, 0, 0.3, 0.5, 1, 1, 1, 1], [[-4, 2.5], [-3, 3.5], [-2, 2], [-1, 3.5], [0, 2.5], [1, 0]], 4),
]


def _true_offset(curve, d, n=3000):
    a, b = curve.domain()
    t = np.linspace(a, b, n)
    h = 1e-7 * (b - a)
    lo, hi = np.clip(t - h, a, b), np.clip(t + h, a, b)
    tangent = np.asarray(curve.eval(hi)) - np.asarray(curve.eval(lo))
    tangent /= np.linalg.norm(tangent, axis=1)[:, None]
    normal = np.stack([-tangent[:, 1], tangent[:, 0]], axis=1)
    return np.asarray(curve.eval(t)) + d * normal


def _distance_to_polyline(points, line):
    """Each point's distance to the polyline through `line` (NumPy, segment by segment)."""
    a, b = line[:-1], line[1:]
    ab = b - a
    out = np.full(len(points), np.inf)
    for k in range(0, len(points), 512):
        p = points[k : k + 512, None, :]
        s = np.clip(((p - a) * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-300), 0.0, 1.0)
        out[k : k + 512] = np.linalg.norm(p - (a + s[..., None] * ab), axis=-1).min(axis=1)
    return out


def _samples(curve, n=1500):
    a, b = curve.domain()
    return np.asarray(curve.eval(np.linspace(a, b, n)))


@pytest.mark.parametrize("curve", CURVES, ids=lambda c: type(c).__name__)
@pytest.mark.parametrize("d", [0.3, -0.2])
def test_offset_within_its_bound_both_ways(curve, d):
    tol = 1e-3
    path, bound = curve.offset(d, tol, with_error=True)
    assert isinstance(path, ss.Path)
    assert 0 < bound <= tol
    assert all(len(seg[2]) == 4 for seg in path.segments()), "cubic segments"
    truth = _true_offset(curve, d)
    ours = _samples(path)
    # The polylines' own chord error is far below the tolerance at these densities.
    slack = 2e-5
    assert _distance_to_polyline(ours, truth).max() <= bound + slack
    assert _distance_to_polyline(truth, ours).max() <= bound + slack


def test_a_circles_offset_is_a_circle():
    circle = ss.Nurbs.circle([3.0, 2.0], 1.5)
    for d in (0.4, -0.6):
        path, bound = circle.offset(d, 1e-7, with_error=True)
        r = np.linalg.norm(_samples(path, 5000) - [3.0, 2.0], axis=1)
        assert np.abs(r - (1.5 - d)).max() <= bound + 1e-12


def test_stroke_outline_and_trim():
    segment = ss.Bezier([[0, 0], [1, 0]])
    outline = segment.offset(0.1, 1e-6, caps="round")
    assert isinstance(outline, list) and len(outline) == 1
    pts = _samples(outline[0], 4000)
    nearest_x = np.clip(pts[:, 0], 0.0, 1.0)
    dist = np.hypot(pts[:, 0] - nearest_x, pts[:, 1])
    assert np.abs(dist - 0.1).max() <= 1e-6
    ring = ss.Nurbs.circle([0.0, 0.0], 1.0).offset(0.25, 1e-6, caps="butt")
    assert len(ring) == 2
    parabola = ss.Bezier([[-2, 2], [0, -2], [2, 2]])
    raw = parabola.offset(2.0, 1e-4)
    trimmed = parabola.offset(2.0, 1e-4, trim=True)
    base = _samples(parabola, 20000)
    kept = np.concatenate([_samples(p) for p in trimmed])
    assert _distance_to_polyline(kept, base).min() >= 2.0 - 3e-4
    assert _distance_to_polyline(_samples(raw), base).min() < 1.9, "the raw offset has loops"


def test_bad_arguments_are_named():
    c = ss.Bezier([[0, 0], [1, 1], [2, 0]])
    for kwargs, what in [
        (dict(d=0.1, tolerance=-1.0), "tolerance"),
        (dict(d=float("nan"), tolerance=0.1), "d"),
        (dict(d=0.1, tolerance=0.1, join="sharp"), "join"),
        (dict(d=0.1, tolerance=0.1, caps="flat"), "caps"),
        (dict(d=0.1, tolerance=0.1, miter_limit=0.5), "miter_limit"),
        (dict(d=0.1, tolerance=0.1, caps="round", trim=True), "trim"),
    ]:
        with pytest.raises(ss.CurveError) as e:
            c.offset(**kwargs)
        assert e.value.path == what, (kwargs, e.value)
    with pytest.raises(TypeError, match="d must be a number"):
        c.offset("1", 0.1)
    with pytest.raises(ss.CurveError, match="planar"):
        ss.Bezier([[0, 0, 0], [1, 0, 1]]).offset(0.1, 0.1)
