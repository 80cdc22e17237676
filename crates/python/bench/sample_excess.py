"""How many samples the drawing bound asks for the stress curves of each family, against
the fewest uniform samples per segment that truly keep every polyline within the
tolerance.

The viewer's stress mode puts each curve in a unit cell of a square grid; a 100 × 100
grid in an 800-pixel-high canvas is 8 pixels a unit. For every Bézier segment the curve
lowers to (``Curve.segments()``), in pixels:

* the bound's count: ``N = ⌈√(n(n − 1)(M_xy + R M_w) / (8 τ W))⌉`` intervals, the formula of
  ``docs/math.md`` §5 (``shaders/adaptive.wgsl``'s ``wang_count``) in ``f64``;
* the truth: the smallest ``N`` whose uniform polyline stays within ``τ`` of the curve,
  the distance from each of 24 points per interval to its chord measured exactly.

Prints one JSON object: per family the samples (intervals + 1) of both and their ratio.
Run with the project's virtual environment: ``.venv/bin/python
crates/python/bench/sample_excess.py [curves]``.
"""

import json
import math
import sys
from math import comb

import numpy as np

import splinescope

TOLERANCE_PX = 0.25
PIXELS_PER_UNIT = 8.0


def weight_floor(w):
    """The lower bound of the weight's polynomial on [0, 1] that §5 uses: the smallest
    Bernstein coefficient of its two halves split at ½, never below the least weight."""
    n = len(w) - 1
    low = min(w[0], w[-1])
    for k in range(1, n + 1):
        left = sum(comb(k, j) * w[j] for j in range(k + 1)) / 2**k
        right = sum(comb(k, j) * w[n - k + j] for j in range(k + 1)) / 2**k
        low = min(low, left, right)
    return max(min(w), low)


def bound_intervals(p, w):
    """§5's count for the segment with pixel points ``p`` (rows) and weights ``w``."""
    n = len(w) - 1
    if n < 2:
        return 1
    lo, hi = p.min(0), p.max(0)
    centre = 0.5 * (lo + hi)
    r = np.max(np.linalg.norm(p - centre, axis=1))
    h = np.c_[p * w[:, None], w]
    d = h[:-2] - 2.0 * h[1:-1] + h[2:]
    m_xy = np.max(np.linalg.norm(d[:, :2] - centre * d[:, 2:3], axis=1))
    m_w = np.max(np.abs(d[:, 2]))
    return max(1, math.ceil(math.sqrt(n * (n - 1) * (m_xy + r * m_w) / (8.0 * TOLERANCE_PX * weight_floor(w)))))


def point(p, w, t):
    n = len(w) - 1
    b = np.array([comb(n, i) * t**i * (1.0 - t) ** (n - i) for i in range(n + 1)])
    return ((b * w[:, None]).T @ p) / (b.T @ w)[:, None]


def deviation(p, w, intervals):
    """The farthest any of 24 points per interval lies from that interval's chord."""
    knots = np.linspace(0.0, 1.0, intervals + 1)
    ends = point(p, w, knots)
    worst = 0.0
    for k in range(intervals):
        q = point(p, w, np.linspace(knots[k], knots[k + 1], 24))
        a, b = ends[k], ends[k + 1]
        ab = b - a
        length2 = float(ab @ ab)
        s = np.clip(((q - a) @ ab) / length2, 0.0, 1.0) if length2 > 0.0 else np.zeros(len(q))
        worst = max(worst, float(np.max(np.linalg.norm(q - (a + s[:, None] * ab), axis=1))))
    return worst


def true_intervals(p, w, most):
    n = 1
    while n < most and deviation(p, w, n) > TOLERANCE_PX:
        n += 1
    return n


def main():
    curves = int(sys.argv[1]) if len(sys.argv) > 1 else 300
    out = {"curves": curves, "tolerance_px": TOLERANCE_PX, "pixels_per_unit": PIXELS_PER_UNIT}
    for family in ["bezier", "rational_bezier", "bspline", "nurbs", "nubmp", "interpolation", "modified_bezier"]:
        scene = splinescope.stress_scene(curves, family, 3, 1)
        bound = truth = 0
        for curve in scene.curves:
            for segment in curve.segments():
                p = np.asarray(segment[2])[:, :2] * PIXELS_PER_UNIT
                w = np.asarray(segment[3]) if len(segment) > 3 and segment[3] is not None else np.ones(len(p))
                n_bound = bound_intervals(p, w)
                bound += n_bound + 1
                truth += true_intervals(p, w, n_bound) + 1
        out[family] = {"bound_samples": bound, "true_samples": truth, "ratio": round(bound / truth, 3)}
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
