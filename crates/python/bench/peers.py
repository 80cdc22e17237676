"""splinescope's Python module against its peers, in one run (ratios, not absolute
figures, are what survives a noisy machine). Run by scripts/bench-python, which
installs the peers (scipy, bezier, geomdl) into the project's virtual environment.

Cases (array conversion included in every timing):
  1. cubic B-spline, 2-D, 1,000 control points, 1,000,000 sorted parameters:
     scipy.interpolate.BSpline.__call__ vs BSpline.eval, one thread and two;
  2. interpolating 1,000 points and evaluating at 1,000,000 parameters:
     scipy's make_interp_spline (+ call) vs Interpolation (paper 002's cubic
     interpolation: a different interpolant for the same task);
  3. Bézier curves, cubic and degree 12, 1,000,000 parameters: bezier's
     Curve.evaluate_multi vs Bezier.eval;
  4. geomdl's evaluate_list (pure Python, on 20,000 parameters, per point) vs
     BSpline.eval;
  5. the floor: writing a fresh (1,000,000, 2) array (numpy), which no method returning
     one can beat;
  6. the binding's overhead: BSpline.eval against the same evaluation made in Rust
     (splinescope._splinescope.rust_eval_seconds), 1,000,000 points;
  8. BSpline.eval(t, out=…) into an array allocated once, one thread and two (case 1's
     curve and parameters);
  7. curve–curve intersection per pair, bezier's Curve.intersect vs Curve.intersect
     (cubics crossing three times, a tangency, degree 7 crossing), and arc length
     (bezier's Curve.length vs Curve.length at 1e-12) on 200 random cubics;
  9. every pair among 10,000 and 100,000 small cubics scattered in a square (about 1.5
     crossing pairs per cubic): splinescope.intersections against the bezier package's
     time per pair on 300 of the pairs that meet, times their number.
Prints one JSON object; `--threads N` pins the module to N threads (RAYON_NUM_THREADS).
"""

import json
import os
import platform
import subprocess
import sys
import time

import numpy as np


def best(f, repeats=7):
    f()  # warm up
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        f()
        times.append(time.perf_counter() - t0)
    return min(times)


def _try(ca, cb):
    """The bezier package's intersection, or None where it gives up (tangencies)."""
    try:
        return ca.intersect(cb)
    except (NotImplementedError, ValueError):
        return None


def measure():
    import splinescope as ss
    from scipy.interpolate import BSpline as SciBSpline
    from scipy.interpolate import make_interp_spline

    rng = np.random.default_rng(1)
    out = {}
    n_pts, n_eval = 1000, 1_000_000

    # 1. cubic B-spline.
    knots = np.concatenate([[0.0] * 4, np.sort(rng.uniform(0, 1, n_pts - 4)), [1.0] * 4])
    ctrl = rng.uniform(-1, 1, (n_pts, 2))
    t = np.sort(rng.uniform(0, 1, n_eval))
    sci = SciBSpline(knots, ctrl, 3)
    ours = ss.BSpline(knots, ctrl, 4)
    assert np.allclose(sci(t), ours.eval(t), atol=1e-12)
    # The floor of any method returning a fresh (N, 2) float64 array: writing one.
    out["write_limit_s"] = best(lambda: np.multiply.outer(t, [1.0, 1.0]))
    out["bspline_scipy_s"] = best(lambda: sci(t))
    out["bspline_splinescope_s"] = best(lambda: ours.eval(t))
    # 8. the same into an array allocated once (out=): a loop's steady state.
    buf = np.empty((n_eval, 2))
    out["bspline_splinescope_out_s"] = best(lambda: ours.eval(t, out=buf))

    # 5. the binding's overhead on the same case.
    native = ours._c
    out["bspline_rust_s"] = min(
        ss._splinescope.rust_eval_seconds(native, t, 1) for _ in range(7)
    )

    # 2. interpolation.
    x = np.linspace(0, 100, n_pts)
    y = np.column_stack([np.sin(x / 7), np.cos(x / 11)])
    tt = np.linspace(0, 100, n_eval)
    out["interp_scipy_s"] = best(lambda: make_interp_spline(x, y, k=3)(tt))
    out["interp_splinescope_s"] = best(lambda: ss.Interpolation(y, x).eval(tt))

    # 3. Bézier curves.
    try:
        import bezier

        for degree in (3, 12):
            nodes = rng.uniform(-1, 1, (degree + 1, 2))
            s = np.linspace(0, 1, n_eval)
            peer = bezier.Curve(np.asfortranarray(nodes.T), degree=degree)
            mine = ss.Bezier(nodes)
            assert np.allclose(peer.evaluate_multi(s).T, mine.eval(s), atol=1e-12)
            out[f"bezier{degree}_peer_s"] = best(lambda: peer.evaluate_multi(s).T, 5)
            out[f"bezier{degree}_splinescope_s"] = best(lambda: mine.eval(s), 5)
    except ImportError:
        out["bezier_missing"] = True

    # 7. intersections and lengths against the bezier package.
    try:
        import bezier

        def pkg(p):
            p = np.asarray(p, dtype=np.float64)
            return bezier.Curve(np.asfortranarray(p.T), degree=len(p) - 1)

        # Two degree-7 curves crossing three times (fixed points, found by a random draw).
        seven_a = [[0.131, 0.514], [0.25, 0.343], [0.817, 0.398], [0.784, 0.013],
                   [0.999, 0.955], [0.679, 0.197], [0.657, 0.19], [0.373, 0.035]]
        seven_b = [[0.07, 0.158], [0.182, 0.838], [0.244, 0.825], [0.006, 0.058],
                   [0.061, 0.932], [0.817, 0.016], [0.932, 0.227], [0.265, 0.584]]
        cases = {
            "cubic_crossing": (
                [[0, 0], [1, 3], [2, -2], [3, 1]],
                [[0, 1], [1.5, -2], [2, 3], [3, -0.5]],
            ),
            "cubic_tangent": (
                [[-1, 0], [-0.5, -1.0], [0.5, -1.0], [1, 0]],
                [[-1, -0.75], [-0.3, -0.75], [0.3, -0.75], [1, -0.75]],
            ),
            "degree7_crossing": (seven_a, seven_b),
        }
        for name, (pa, pb) in cases.items():
            ca, cb = pkg(pa), pkg(pb)
            ma, mb = ss.Bezier(pa), ss.Bezier(pb)
            try:
                want = np.asarray(ca.intersect(cb)).T
                got = ma.intersect(mb)
                order = np.argsort(want[:, 0])
                assert np.allclose(got, want[order], atol=1e-8), (name, got, want)
                out[f"intersect_{name}_peer_s"] = best(lambda: ca.intersect(cb), 5)
            except (NotImplementedError, ValueError) as e:
                out[f"intersect_{name}_peer_error"] = str(e)[:80]
            out[f"intersect_{name}_splinescope_s"] = best(lambda: ma.intersect(mb), 5)
        cubics = [rng.uniform(0, 1, (4, 2)) for _ in range(200)]
        peers = [pkg(c) for c in cubics]
        mine = [ss.Bezier(c) for c in cubics]
        for p_, m_ in zip(peers, mine):
            assert abs(p_.length - m_.length()) < 1e-9
        out["length_200_cubics_peer_s"] = best(lambda: [p_.length for p_ in peers], 5)
        out["length_200_cubics_splinescope_s"] = best(
            lambda: [m_.length(accuracy=1e-12) for m_ in mine], 5
        )
        # 9. every pair among small cubics scattered in a square (so that they cross):
        # splinescope.intersections on 10,000 and 100,000, against the bezier package's
        # time per pair on a sample of the pairs that meet, times their number (what the
        # peer's narrow phase alone would take, with no broad phase at all).
        for n in (10_000, 100_000):
            side = np.sqrt(n) * 0.35
            pts = rng.uniform(0, side, (n, 1, 2)) + rng.uniform(-0.5, 0.5, (n, 4, 2))
            curves = [ss.Bezier(p) for p in pts]
            found = ss.intersections(curves)
            pairs = [f for f in found if "i" in f]
            out[f"scatter_{n}_pairs"] = len(pairs)
            out[f"scatter_{n}_points"] = sum(len(f["kinds"]) for f in pairs)
            out[f"scatter_{n}_splinescope_s"] = best(lambda: ss.intersections(curves), 3)
            sample = [pairs[k] for k in rng.choice(len(pairs), 300, replace=False)]
            peer_pairs = [(pkg(pts[f["i"]]), pkg(pts[f["j"]])) for f in sample]
            # The two agree on how many points each sampled pair has (where the peer
            # answers): a disagreement is counted and printed, not hidden.
            out[f"scatter_{n}_count_disagreements"] = sum(
                1
                for f, (ca, cb) in zip(sample, peer_pairs)
                if (r := _try(ca, cb)) is not None and np.asarray(r).shape[1] != len(f["kinds"])
            )
            per_pair = best(lambda: [_try(ca, cb) for ca, cb in peer_pairs], 3) / 300
            out[f"scatter_{n}_peer_s"] = per_pair * len(pairs)
    except ImportError:
        out["bezier_missing"] = True

    # 4. geomdl (pure Python): per point, on fewer points.
    try:
        from geomdl import BSpline as GeoBSpline

        g = GeoBSpline.Curve()
        g.degree = 3
        g.ctrlpts = ctrl.tolist()
        g.knotvector = knots.tolist()
        few = t[:: n_eval // 20_000].tolist()
        t0 = time.perf_counter()
        res = g.evaluate_list(few)
        out["geomdl_per_point_s"] = (time.perf_counter() - t0) / len(few)
        assert np.allclose(np.asarray(res), ours.eval(np.asarray(few)), atol=1e-9)
        out["splinescope_per_point_s"] = out["bspline_splinescope_s"] / n_eval
    except ImportError:
        out["geomdl_missing"] = True
    return out


def main():
    if "--threads" in sys.argv:
        print(json.dumps(measure()))
        return
    runs = {}
    for threads in (1, 2):
        env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
        res = subprocess.run(
            [sys.executable, __file__, "--threads", str(threads)],
            env=env,
            capture_output=True,
            text=True,
            check=True,
        )
        runs[threads] = json.loads(res.stdout.strip().splitlines()[-1])
    one, two = runs[1], runs[2]
    ratios = {
        "bspline_vs_scipy_1_thread": one["bspline_scipy_s"] / one["bspline_splinescope_s"],
        "bspline_vs_scipy_2_threads": two["bspline_scipy_s"] / two["bspline_splinescope_s"],
        "bspline_2_threads_over_1": one["bspline_splinescope_s"] / two["bspline_splinescope_s"],
        "bspline_out_vs_scipy_1_thread": one["bspline_scipy_s"] / one["bspline_splinescope_out_s"],
        "bspline_out_vs_scipy_2_threads": two["bspline_scipy_s"] / two["bspline_splinescope_out_s"],
        "interp_vs_scipy_1_thread": one["interp_scipy_s"] / one["interp_splinescope_s"],
        "binding_overhead_1_thread": one["bspline_splinescope_s"] / one["bspline_rust_s"] - 1,
        "binding_overhead_2_threads": two["bspline_splinescope_s"] / two["bspline_rust_s"] - 1,
    }
    ratios["write_limit_vs_scipy_bspline"] = one["bspline_scipy_s"] / one["write_limit_s"]
    for d in (3, 12):
        if f"bezier{d}_peer_s" in one:
            ratios[f"write_limit_vs_bezier{d}_pkg"] = one[f"bezier{d}_peer_s"] / one["write_limit_s"]
            ratios[f"bezier{d}_vs_bezier_pkg_1_thread"] = (
                one[f"bezier{d}_peer_s"] / one[f"bezier{d}_splinescope_s"]
            )
    for name in ("cubic_crossing", "cubic_tangent", "degree7_crossing"):
        if f"intersect_{name}_peer_s" in one:
            ratios[f"intersect_{name}_vs_bezier_pkg"] = (
                one[f"intersect_{name}_peer_s"] / one[f"intersect_{name}_splinescope_s"]
            )
    for n in (10_000, 100_000):
        for threads, run in runs.items():
            if f"scatter_{n}_peer_s" in run:
                ratios[f"scatter_{n}_vs_bezier_pkg_{threads}_threads"] = (
                    run[f"scatter_{n}_peer_s"] / run[f"scatter_{n}_splinescope_s"]
                )
    if "length_200_cubics_peer_s" in one:
        ratios["length_vs_bezier_pkg"] = (
            one["length_200_cubics_peer_s"] / one["length_200_cubics_splinescope_s"]
        )
    if "geomdl_per_point_s" in one:
        ratios["bspline_vs_geomdl_1_thread"] = (
            one["geomdl_per_point_s"] / one["splinescope_per_point_s"]
        )
    print(
        json.dumps(
            {
                "machine": f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}",
                "runs": runs,
                "ratios": ratios,
            },
            indent=1,
        )
    )


if __name__ == "__main__":
    main()
