//! Offset curves against independent truth: the true offset `C(t) + d n(t)` sampled densely
//! (the normal from central differences of the curve's own evaluation, not the code under
//! test) and compared both ways with the result — every point of the result near the true
//! offset, every point of the true offset near the result — within the bound reported,
//! which is within the tolerance; a circle's offset against its closed form; the parabola's
//! cusps where `d κ = 1`; joins and caps against the square, rectangle and stadium they
//! make; trimmed loops; bad arguments refused.

use glam::DVec3;
use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::{
    BSpline, Bezier, Curve, Nurbs, ParamCurve, Path, PathSegment, RationalBezier,
};
use splinescope_core::ops::{Cap, Join, OffsetOptions, OpError, offset};

fn p(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

/// The true offset at `t` (the normal from central differences of `eval`).
fn true_offset(c: &Curve, t: f64, d: f64) -> DVec3 {
    let (a, b) = c.domain();
    let h = 1e-6 * (b - a);
    let (t0, t1) = ((t - h).max(a), (t + h).min(b));
    let tangent = (c.eval(t1) - c.eval(t0)).normalize();
    c.eval(t) + d * DVec3::new(-tangent.y, tangent.x, 0.0)
}

/// The distance from `q` to the true offset: dense samples, then golden-section search
/// around every local minimum of the sampled distance that comes near the least (near a
/// cusp the offset folds back, and the nearest sample need not bracket the nearest point).
fn distance_to_offset(c: &Curve, d: f64, q: DVec3, samples: &[(f64, DVec3)]) -> f64 {
    let dist: Vec<f64> = samples.iter().map(|(_, s)| (*s - q).length()).collect();
    let least = dist.iter().copied().fold(f64::INFINITY, f64::min);
    let f = |t: f64| (true_offset(c, t, d) - q).length();
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let n = dist.len();
    let mut best = least;
    for i in 0..n {
        let local = (i == 0 || dist[i] <= dist[i - 1]) && (i + 1 == n || dist[i] <= dist[i + 1]);
        if !local || dist[i] > least + 0.05 * (1.0 + d.abs()) {
            continue;
        }
        let (mut lo, mut hi) = (
            samples[i.saturating_sub(1)].0,
            samples[(i + 1).min(n - 1)].0,
        );
        for _ in 0..60 {
            let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
            if f(x1) < f(x2) {
                hi = x2;
            } else {
                lo = x1;
            }
        }
        best = best.min(f(0.5 * (lo + hi)));
    }
    best
}

/// Checks an offset both ways against the true one; returns the largest distance seen.
fn check_both_ways(c: &Curve, d: f64, tol: f64) -> f64 {
    check_with_kinks(c, d, tol, &[])
}

/// The same, for a curve with kinks at `kinks`: there the offset is the round join's
/// arc, the points at `|d|` from the kink.
fn check_with_kinks(c: &Curve, d: f64, tol: f64, kinks: &[DVec3]) -> f64 {
    let o = offset(c, d, tol, &OffsetOptions::default())
        .unwrap_or_else(|e| panic!("offset of {c:?} by {d}: {e}"));
    assert!(
        o.error <= tol,
        "bound {} above the tolerance {tol}",
        o.error
    );
    assert_eq!(o.paths.len(), 1);
    let path = &o.paths[0];
    for s in path.segments() {
        assert_eq!(s.points.len(), 4, "cubic segments only");
    }
    let (a, b) = c.domain();
    let n = 3000;
    let samples: Vec<(f64, DVec3)> = (0..=n)
        .map(|i| {
            let t = a + (b - a) * f64::from(i) / f64::from(n);
            (t, true_offset(c, t, d))
        })
        .collect();
    let slack = 1e-7 * (1.0 + d.abs());
    let mut worst: f64 = 0.0;
    // Every point of the result near the true offset.
    let rc = Curve::Path(path.clone());
    let (ra, rb) = rc.domain();
    for i in 0..=600 {
        let t = ra + (rb - ra) * f64::from(i) / 600.0;
        let q = rc.eval(t);
        let arcs = kinks.iter().map(|k| ((q - *k).length() - d.abs()).abs());
        let dist = arcs.fold(distance_to_offset(c, d, q, &samples), f64::min);
        worst = worst.max(dist);
        assert!(
            dist <= o.error + slack,
            "result point {t} is {dist} from the true offset (bound {}) for {c:?} by {d}",
            o.error
        );
    }
    // Every point of the true offset near the result.
    let analysis = CurveAnalysis::new(&rc);
    for (t, q) in samples.iter().step_by(5) {
        // At a kink itself the normal is not defined (the join's arc stands for it).
        if kinks.iter().any(|k| (c.eval(*t) - *k).length() < 1e-6) {
            continue;
        }
        let near = analysis.nearest(*q).expect("nearest");
        worst = worst.max(near.distance);
        assert!(
            near.distance <= o.error + slack,
            "true offset at {t} is {} from the result (bound {}) for {c:?} by {d}",
            near.distance,
            o.error
        );
    }
    worst
}

fn bezier(pts: &[(f64, f64)]) -> Curve {
    Curve::Bezier(Bezier::new(pts.iter().map(|&(x, y)| p(x, y)).collect()))
}

struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn random_cubics_both_ways_within_the_bound() {
    let mut rng = Lcg(7);
    for k in 0..60 {
        let pts: Vec<(f64, f64)> = (0..4).map(|_| (rng.next(), rng.next())).collect();
        let d = (0.01 + 0.2 * rng.next()) * if k % 2 == 0 { 1.0 } else { -1.0 };
        check_both_ways(&bezier(&pts), d, 1e-3);
    }
    // Farther out, where most offsets have cusps, and tighter.
    let mut cusps = 0;
    for k in 0..30 {
        let pts: Vec<(f64, f64)> = (0..4).map(|_| (rng.next(), rng.next())).collect();
        let d = (0.2 + 0.8 * rng.next()) * if k % 2 == 0 { 1.0 } else { -1.0 };
        let c = bezier(&pts);
        cusps += offset(&c, d, 1e-4, &OffsetOptions::default())
            .expect("offset")
            .cusps;
        check_both_ways(&c, d, 1e-4);
    }
    assert!(cusps >= 10, "the cases reach cusps ({cusps})");
}

#[test]
fn the_hard_cases_both_ways() {
    let tol = 1e-4;
    let cases: Vec<(Curve, f64)> = vec![
        // Zero speed at both ends.
        (
            bezier(&[(0.0, 0.0), (0.0, 0.0), (1.0, 1.0), (1.0, 1.0)]),
            0.2,
        ),
        (
            bezier(&[(0.0, 0.0), (0.0, 0.0), (1.0, 0.0), (1.0, 1.0)]),
            -0.3,
        ),
        // Straight: the offset is the line moved.
        (
            bezier(&[(0.0, 0.0), (1.0, 1.0), (2.0, 2.0), (3.0, 3.0)]),
            0.5,
        ),
        // A tight turn: cusps on the inner side.
        (
            bezier(&[(0.0, 0.0), (1.0, 0.0), (1.0, 0.2), (0.0, 0.2)]),
            0.3,
        ),
        (
            bezier(&[(0.0, 0.0), (1.0, 0.0), (1.0, 0.2), (0.0, 0.2)]),
            -0.3,
        ),
        // A tiny distance and a large one.
        (
            bezier(&[(0.0, 0.0), (0.3, 1.0), (0.7, -1.0), (1.0, 0.0)]),
            1e-6,
        ),
        (
            bezier(&[(0.0, 0.0), (0.3, 1.0), (0.7, -1.0), (1.0, 0.0)]),
            5.0,
        ),
        // Degree 7, a rational cubic with extreme weights, a B-spline.
        (
            Curve::Bezier(Bezier::new(
                (0..8)
                    .map(|i| p(f64::from(i) / 7.0, if i % 2 == 0 { 0.0 } else { 0.4 }))
                    .collect(),
            )),
            0.05,
        ),
        (
            Curve::RationalBezier(
                RationalBezier::try_new(
                    vec![p(0.0, 0.0), p(0.5, 1.0), p(1.0, 1.0), p(1.5, 0.0)],
                    vec![1.0, 40.0, 0.05, 1.0],
                )
                .expect("rational"),
            ),
            0.1,
        ),
        (
            Curve::BSpline(
                BSpline::try_new(
                    vec![
                        p(0.0, 0.0),
                        p(1.0, 1.0),
                        p(2.0, -1.0),
                        p(3.0, 1.0),
                        p(4.0, 0.0),
                    ],
                    vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0],
                    4,
                )
                .expect("spline"),
            ),
            -0.15,
        ),
    ];
    for (c, d) in &cases {
        check_both_ways(c, *d, tol);
    }
    // A stationary point inside (a cusp of the curve itself, at t = 1/2): a kink joined
    // round.
    let cusp = bezier(&[(0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)]);
    let at = cusp.eval(0.5);
    for d in [0.1, -0.1] {
        check_with_kinks(&cusp, d, tol, &[at]);
    }
    // Far from the origin and at a large scale: the same shape, the same count.
    let small = bezier(&[(0.0, 0.0), (0.3, 1.0), (0.7, -1.0), (1.0, 0.0)]);
    let big = bezier(&[(1e6, 1e6), (1e6 + 3e5, 2e6), (1e6 + 7e5, 0.0), (2e6, 1e6)]);
    let a = offset(&small, 0.1, 1e-4, &OffsetOptions::default()).expect("small");
    let b = offset(&big, 1e5, 1e2, &OffsetOptions::default()).expect("big");
    assert!(b.error <= 1e2);
    assert_eq!(a.paths[0].segments().len(), b.paths[0].segments().len());
}

#[test]
fn a_circles_offset_is_the_circle_of_radius_r_minus_d() {
    let circle = Curve::Nurbs(Nurbs::circle(p(3.0, 2.0), 1.5).expect("circle"));
    for (d, tol) in [(0.4, 1e-6), (-0.7, 1e-5), (1.2, 1e-8)] {
        let o = offset(&circle, d, tol, &OffsetOptions::default()).expect("offset");
        assert!(o.error <= tol);
        assert_eq!(o.cusps, 0);
        let path = &o.paths[0];
        assert!(path.is_closed(), "a closed curve's offset is closed");
        let rc = Curve::Path(path.clone());
        let (a, b) = rc.domain();
        for i in 0..=2000 {
            let q = rc.eval(a + (b - a) * f64::from(i) / 2000.0);
            let r = (q - p(3.0, 2.0)).length();
            assert!(
                (r - (1.5 - d)).abs() <= o.error + 1e-12,
                "radius {r}, not {} within {}",
                1.5 - d,
                o.error
            );
        }
    }
}

/// The parabola `y = x²/2` on `[−2, 2]`: curvature `1 / (1 + x²)^{3/2}`, so an offset by
/// `d = 2` toward its centres has cusps at `x = ±√(2^{2/3} − 1)`.
#[test]
fn the_parabolas_cusps_are_where_d_kappa_is_1() {
    let parabola = bezier(&[(-2.0, 2.0), (0.0, -2.0), (2.0, 2.0)]);
    let o = offset(&parabola, 2.0, 1e-5, &OffsetOptions::default()).expect("offset");
    assert_eq!(o.cusps, 2);
    let x = (2f64.powf(2.0 / 3.0) - 1.0).sqrt();
    let analysis = CurveAnalysis::new(&Curve::Path(o.paths[0].clone()));
    for xc in [-x, x] {
        let slope = xc; // y′ = x
        let norm = (1.0 + slope * slope).sqrt();
        let cusp = p(xc, 0.5 * xc * xc) + 2.0 * DVec3::new(-slope / norm, 1.0 / norm, 0.0);
        let near = analysis.nearest(cusp).expect("nearest");
        assert!(
            near.distance <= o.error + 1e-9,
            "cusp {cusp} is {} away",
            near.distance
        );
    }
    check_both_ways(&parabola, 2.0, 1e-4);
    let none = offset(&parabola, 0.5, 1e-5, &OffsetOptions::default()).expect("offset");
    assert_eq!(none.cusps, 0);
    let other_side = offset(&parabola, -2.0, 1e-5, &OffsetOptions::default()).expect("offset");
    assert_eq!(
        other_side.cusps, 0,
        "away from the centres there is no cusp"
    );
}

#[test]
fn trimming_removes_the_loops_and_keeps_the_distance() {
    let parabola = bezier(&[(-2.0, 2.0), (0.0, -2.0), (2.0, 2.0)]);
    let tol = 1e-4;
    let options = OffsetOptions {
        trim: true,
        ..OffsetOptions::default()
    };
    let raw = offset(&parabola, 2.0, tol, &OffsetOptions::default()).expect("raw");
    let raw_hits = CurveAnalysis::new(&Curve::Path(raw.paths[0].clone()))
        .self_intersections()
        .expect("self");
    assert!(!raw_hits.hits.is_empty(), "the raw offset crosses itself");
    let trimmed = offset(&parabola, 2.0, tol, &options).expect("trimmed");
    let base = CurveAnalysis::new(&parabola);
    let mut length_kept = 0usize;
    for path in &trimmed.paths {
        let rc = Curve::Path(path.clone());
        let hits = CurveAnalysis::new(&rc).self_intersections().expect("self");
        assert!(
            hits.hits.is_empty(),
            "a trimmed path crosses itself: {:?}",
            hits.hits
        );
        let (a, b) = rc.domain();
        for i in 0..=400 {
            let q = rc.eval(a + (b - a) * f64::from(i) / 400.0);
            let near = base.nearest(q).expect("nearest");
            assert!(
                near.distance >= 2.0 - 3.0 * tol,
                "a kept point {q} is {} from the curve",
                near.distance
            );
        }
        length_kept += path.segments().len();
    }
    assert!(length_kept > 0 && length_kept < raw.paths[0].segments().len());
}

fn polyline(points: &[(f64, f64)], closed: bool) -> Curve {
    let segs: Vec<PathSegment> = points
        .windows(2)
        .map(|w| PathSegment::polynomial(vec![p(w[0].0, w[0].1), p(w[1].0, w[1].1)]))
        .collect();
    Curve::Path(Path::try_new(segs, closed).expect("path"))
}

fn sample(path: &Path, n: u32) -> Vec<DVec3> {
    let rc = Curve::Path(path.clone());
    let (a, b) = rc.domain();
    (0..=n)
        .map(|i| rc.eval(a + (b - a) * f64::from(i) / f64::from(n)))
        .collect()
}

#[test]
fn joins_make_the_square_they_should() {
    // A counter-clockwise square: d < 0 offsets outward.
    let square = polyline(
        &[
            (-1.0, -1.0),
            (1.0, -1.0),
            (1.0, 1.0),
            (-1.0, 1.0),
            (-1.0, -1.0),
        ],
        true,
    );
    let with = |join: Join, limit: f64| OffsetOptions {
        join,
        miter_limit: limit,
        ..OffsetOptions::default()
    };
    let tol = 1e-6;
    let miter = offset(&square, -0.1, tol, &with(Join::Miter, 4.0)).expect("miter");
    let pts = sample(&miter.paths[0], 4000);
    for q in &pts {
        assert!(
            (q.x.abs().max(q.y.abs()) - 1.1).abs() < 1e-12,
            "{q} off the 2.2 square"
        );
    }
    let corners = miter.paths[0].segments().iter().map(|s| s.points[0]);
    assert_eq!(
        corners
            .filter(|q| (q.x.abs() - 1.1).abs() < 1e-12 && (q.y.abs() - 1.1).abs() < 1e-12)
            .count(),
        4,
        "the four corners reached"
    );
    // Past the limit (a square's miter is √2): bevelled.
    let bevel = offset(&square, -0.1, tol, &with(Join::Miter, 1.2)).expect("bevel");
    for q in sample(&bevel.paths[0], 4000) {
        assert!(q.x.abs().max(q.y.abs()) <= 1.1 + 1e-12);
        assert!(q.x.abs() + q.y.abs() <= 2.1 + 1e-12, "{q} past the bevel");
    }
    // Round: every point 0.1 from the square.
    let round = offset(&square, -0.1, tol, &with(Join::Round, 4.0)).expect("round");
    for q in sample(&round.paths[0], 4000) {
        let dx = (q.x.abs() - 1.0).max(0.0);
        let dy = (q.y.abs() - 1.0).max(0.0);
        let dist = dx.hypot(dy);
        assert!(
            (dist - 0.1).abs() <= round.error + 1e-12,
            "{q} is {dist} from the square"
        );
    }
}

#[test]
fn caps_outline_a_stroke() {
    let segment = bezier(&[(0.0, 0.0), (1.0, 0.0)]);
    let with = |cap: Cap| OffsetOptions {
        caps: Some(cap),
        ..OffsetOptions::default()
    };
    let tol = 1e-6;
    let butt = offset(&segment, 0.1, tol, &with(Cap::Butt)).expect("butt");
    assert_eq!(butt.paths.len(), 1);
    assert!(butt.paths[0].is_closed());
    for q in sample(&butt.paths[0], 2000) {
        let on_side = (q.y.abs() - 0.1).abs() < 1e-12 && (-1e-12..=1.0 + 1e-12).contains(&q.x);
        let on_end = (q.x.abs() < 1e-12 || (q.x - 1.0).abs() < 1e-12) && q.y.abs() <= 0.1 + 1e-12;
        assert!(on_side || on_end, "{q} off the rectangle");
    }
    let square = offset(&segment, 0.1, tol, &with(Cap::Square)).expect("square");
    for q in sample(&square.paths[0], 2000) {
        let on_side =
            (q.y.abs() - 0.1).abs() < 1e-12 && (-0.1 - 1e-12..=1.1 + 1e-12).contains(&q.x);
        let on_end =
            ((q.x + 0.1).abs() < 1e-12 || (q.x - 1.1).abs() < 1e-12) && q.y.abs() <= 0.1 + 1e-12;
        assert!(on_side || on_end, "{q} off the extended rectangle");
    }
    let round = offset(&segment, 0.1, tol, &with(Cap::Round)).expect("round");
    let pts = sample(&round.paths[0], 4000);
    for q in &pts {
        let dist = (q - p(q.x.clamp(0.0, 1.0), 0.0)).length();
        assert!(
            (dist - 0.1).abs() <= round.error + 1e-12,
            "{q} is {dist} from the segment"
        );
    }
    assert!(
        pts.iter().any(|q| (q.x - 1.1).abs() < 1e-6),
        "the end cap reaches out"
    );
    assert!(
        pts.iter().any(|q| (q.x + 0.1).abs() < 1e-6),
        "the start cap reaches out"
    );
    // A closed curve's outline: its two offsets.
    let circle = Curve::Nurbs(Nurbs::circle(p(0.0, 0.0), 1.0).expect("circle"));
    let ring = offset(&circle, 0.25, 1e-6, &with(Cap::Butt)).expect("ring");
    assert_eq!(ring.paths.len(), 2);
    let radii: Vec<f64> = ring
        .paths
        .iter()
        .map(|p| sample(p, 10)[3].length())
        .collect();
    assert!(
        (radii[0] - 0.75).abs() < 1e-5 && (radii[1] - 1.25).abs() < 1e-5,
        "{radii:?}"
    );
}

#[test]
fn bad_arguments_are_refused_by_name() {
    let c = bezier(&[(0.0, 0.0), (1.0, 1.0), (2.0, 0.0)]);
    let o = OffsetOptions::default();
    assert_eq!(offset(&c, 0.1, -1.0, &o), Err(OpError::Tolerance(-1.0)));
    assert!(matches!(
        offset(&c, 0.1, f64::NAN, &o),
        Err(OpError::Tolerance(_))
    ));
    assert!(matches!(
        offset(&c, f64::NAN, 0.1, &o),
        Err(OpError::Distance(_))
    ));
    assert!(matches!(
        offset(&c, f64::INFINITY, 0.1, &o),
        Err(OpError::Distance(_))
    ));
    let bad_limit = OffsetOptions {
        join: Join::Miter,
        miter_limit: 0.5,
        ..o
    };
    assert_eq!(
        offset(&c, 0.1, 0.1, &bad_limit),
        Err(OpError::MiterLimit(0.5))
    );
    let both = OffsetOptions {
        trim: true,
        caps: Some(Cap::Round),
        ..o
    };
    assert_eq!(offset(&c, 0.1, 0.1, &both), Err(OpError::TrimWithCaps));
    let caps_zero = OffsetOptions {
        caps: Some(Cap::Butt),
        ..o
    };
    assert_eq!(
        offset(&c, 0.0, 0.1, &caps_zero),
        Err(OpError::Distance(0.0))
    );
    let spatial = Curve::Bezier(Bezier::new(vec![DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0)]));
    assert!(matches!(
        offset(&spatial, 0.1, 0.1, &o),
        Err(OpError::NotPlanar { .. })
    ));
    let point = bezier(&[(1.0, 1.0), (1.0, 1.0), (1.0, 1.0)]);
    let e = offset(&point, 0.1, 0.1, &o).expect_err("a point");
    assert!(matches!(e, OpError::Degenerate(_)), "{e}");
    assert!(e.to_string().contains("single point"));
    // Within half the tolerance the curve itself is the offset, as cubics (each point of
    // either |d| from the other): a curve, a closed one, and outlines of both.
    for (curve, d) in [(&c, 1e-9), (&c, -4e-4)] {
        let o = offset(curve, d, 1e-3, &o).expect("tiny");
        assert!(o.error <= 1e-3);
        check_both_ways(curve, d, 1e-3);
    }
    let circle = Curve::Nurbs(Nurbs::circle(p(0.0, 0.0), 1.0).expect("circle"));
    for caps in [None, Some(Cap::Round)] {
        let opts = OffsetOptions { caps, ..o };
        for curve in [&c, &circle] {
            let r = offset(curve, 1e-9, 1e-3, &opts).expect("tiny");
            assert!(r.error <= 1e-3);
            assert!(r.paths.iter().all(|p| p.is_closed() || caps.is_none()));
        }
    }
    // d = 0 is the curve itself, as cubics.
    let same = offset(&c, 0.0, 1e-9, &o).expect("zero");
    assert!(same.error <= 1e-9);
}
