//! The nearest point of a curve, against independent truth: dense sampling refined by
//! golden-section search on every family (the answer is never farther than the sampled
//! best, nor nearer than the refined minimum less its bound), and constructed cases whose
//! answer is known in closed form — a circle's centre (every point equally near), a
//! point on the curve, points past the ends, two symmetric nearest points, a point
//! beside a cusp, 3D curves and a 2D curve seen from off its plane.

use glam::DVec3;
use splinescope_core::analysis::{AnalysisError, CurveAnalysis};
use splinescope_core::geom::{
    BSpline, Bezier, Curve, ModifiedBezier, Nurbs, ParamCurve, Path, PathSegment, RationalBezier,
};
use splinescope_core::rng::Rng;

fn p(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

/// One curve of every family, some with several segments, one in 3D.
fn curves() -> Vec<Curve> {
    let base = Bezier::new(vec![p(-3.0, 0.0), p(-2.0, 2.0), p(0.0, 2.0), p(1.0, 0.5)]);
    vec![
        Curve::Bezier(Bezier::new(vec![
            p(-4.0, -2.0),
            p(-2.0, 1.0),
            p(-1.0, -3.0),
            p(1.0, -1.0),
        ])),
        // A loop (self-intersecting cubic): many local minima.
        Curve::Bezier(Bezier::new(vec![
            p(0.0, 0.0),
            p(4.0, 3.0),
            p(-1.0, 3.0),
            p(3.0, 0.0),
        ])),
        Curve::Bezier(Bezier::new(
            (0..=9)
                .map(|i| {
                    let t = f64::from(i) / 9.0;
                    p(4.0 * t - 2.0, (5.0 * t).sin())
                })
                .collect(),
        )),
        Curve::ModifiedBezier(ModifiedBezier::try_new(base, 0.4, p(0.0, 0.6)).expect("bump")),
        Curve::RationalBezier(
            RationalBezier::try_new(
                vec![p(-1.0, -4.0), p(0.0, -2.0), p(1.5, -4.5), p(3.0, -3.0)],
                vec![1.0, 30.0, 0.05, 2.0],
            )
            .expect("rational cubic"),
        ),
        Curve::Nurbs(Nurbs::circle(p(3.0, 2.0), 1.5).expect("circle")),
        Curve::BSpline(
            BSpline::try_new(
                vec![
                    p(-4.0, 2.5),
                    p(-3.0, 3.5),
                    p(-2.0, 2.0),
                    p(-1.0, 3.5),
                    p(0.0, 2.5),
                    p(1.0, 0.0),
                ],
                vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 1.0, 1.0, 1.0, 1.0],
                4,
            )
            .expect("spline"),
        ),
        Curve::Bezier(Bezier::new(vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 1.0),
            DVec3::new(2.0, -1.0, 2.0),
            DVec3::new(3.0, 1.0, -1.0),
            DVec3::new(4.0, 0.0, 0.5),
        ])),
        Curve::Path(
            Path::try_new(
                vec![
                    PathSegment::polynomial(vec![p(0.0, 0.0), p(2.0, 0.0)]),
                    PathSegment::rational(
                        vec![p(2.0, 0.0), p(3.0, 0.0), p(3.0, 1.0)],
                        vec![1.0, 0.5f64.sqrt(), 1.0],
                    ),
                    PathSegment::polynomial(vec![
                        p(3.0, 1.0),
                        p(3.0, 3.0),
                        p(1.0, 2.0),
                        p(0.0, 0.0),
                    ]),
                ],
                true,
            )
            .expect("a path"),
        ),
    ]
}

/// The least distance by sampling the domain densely, then refining the best sample's
/// neighbourhood by golden-section search: an independent estimate of the minimum.
fn sampled_minimum(c: &Curve, q: DVec3) -> (f64, f64) {
    let (t0, t1) = c.domain();
    let n = 4000;
    let d = |t: f64| (c.eval(t) - q).length();
    let (mut best_t, mut best) = (t0, d(t0));
    for i in 0..=n {
        let t = t0 + (t1 - t0) * f64::from(i) / f64::from(n);
        let v = d(t);
        if v < best {
            (best_t, best) = (t, v);
        }
    }
    let h = (t1 - t0) / f64::from(n);
    let (mut a, mut b) = ((best_t - h).max(t0), (best_t + h).min(t1));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..200 {
        let (x1, x2) = (b - g * (b - a), a + g * (b - a));
        if d(x1) < d(x2) {
            b = x2;
        } else {
            a = x1;
        }
    }
    let t = 0.5 * (a + b);
    (t, d(t).min(best))
}

#[test]
fn the_nearest_point_is_the_global_minimum_on_every_family() {
    let mut rng = Rng::new(48);
    let mut worst_gap: f64 = 0.0;
    for c in curves() {
        let a = CurveAnalysis::new(&c);
        let planar = c.eval(0.5 * (c.domain().0 + c.domain().1)).z == 0.0 && a.is_planar();
        for _ in 0..150 {
            let mut q = p(rng.range(-6.0, 6.0), rng.range(-6.0, 6.0));
            if !planar {
                q.z = rng.range(-2.0, 2.0);
            }
            let n = a.nearest(q).expect("nearest");
            let (_, sampled) = sampled_minimum(&c, q);
            // Never farther than a sampled point (it is the global minimum) …
            assert!(
                n.distance <= sampled + 1e-12 * (1.0 + sampled),
                "{}: {q}: {} > sampled {sampled}",
                c.family(),
                n.distance
            );
            // … nor nearer than the curve allows: it is the distance of C(t).
            assert!(((c.eval(n.t) - q).length() - n.distance).abs() <= 1e-12 * (1.0 + n.distance));
            assert!(
                n.error >= 0.0 && n.error <= 1e-7,
                "{}: error {}",
                c.family(),
                n.error
            );
            worst_gap = worst_gap.max(sampled - n.distance);
        }
    }
    // Golden-section refinement finds the same minima to its own precision.
    assert!(worst_gap <= 1e-7, "sampling beat by {worst_gap}");
}

#[test]
fn constructed_cases_have_their_closed_form_answers() {
    // A circle's centre: every point is at the radius (the numerator is zero throughout).
    let circle = Curve::Nurbs(Nurbs::circle(p(3.0, 2.0), 1.5).expect("circle"));
    let a = CurveAnalysis::new(&circle);
    let n = a.nearest(p(3.0, 2.0)).expect("nearest");
    assert!((n.distance - 1.5).abs() <= 1e-14, "{n:?}");
    // Any point: its distance is |q − centre| − r, at the point on the ray.
    for q in [p(10.0, 2.0), p(3.0, -7.0), p(3.3, 2.4), p(-1.0, 5.0)] {
        let n = a.nearest(q).expect("nearest");
        let want = ((q - p(3.0, 2.0)).length() - 1.5).abs();
        assert!((n.distance - want).abs() <= 1e-13, "{q}: {n:?} want {want}");
    }
    // A point on the curve: distance 0 at its parameter.
    let cubic = Curve::Bezier(Bezier::new(vec![
        p(0.0, 0.0),
        p(1.0, 2.0),
        p(3.0, 2.0),
        p(4.0, 0.0),
    ]));
    let a = CurveAnalysis::new(&cubic);
    for t in [0.0, 0.1, 0.5, 0.77, 1.0] {
        let n = a.nearest(cubic.eval(t)).expect("nearest");
        assert!(n.distance <= 1e-14, "t = {t}: {n:?}");
        assert!((n.t - t).abs() <= 1e-7, "t = {t}: {n:?}");
    }
    // Past the ends: the end points.
    let n = a.nearest(p(-3.0, -1.0)).expect("nearest");
    assert_eq!(n.t, 0.0);
    let n = a.nearest(p(7.0, -1.0)).expect("nearest");
    assert_eq!(n.t, 1.0);
    // Below the arch on its axis: the two ends are equally near; the smaller parameter.
    let n = a.nearest(p(2.0, -5.0)).expect("nearest");
    assert_eq!(n.t, 0.0);
    assert!((n.distance - 29f64.sqrt()).abs() <= 1e-14, "{n:?}");
    // Above it: the top.
    let n = a.nearest(p(2.0, 10.0)).expect("nearest");
    assert!(
        (n.t - 0.5).abs() <= 1e-9 && (n.distance - 8.5).abs() <= 1e-12,
        "{n:?}"
    );
    // Beyond the top's centre of curvature (radius 1.6875 below it): the top is a local
    // maximum of the distance, and two symmetric points are nearest; the smaller
    // parameter is returned.
    let inside = p(2.0, -0.2);
    let n = a.nearest(inside).expect("nearest");
    let d_mirror = (cubic.eval(1.0 - n.t) - inside).length();
    assert!(n.t < 0.5 && n.distance < 1.7, "{n:?}");
    assert!(
        (d_mirror - n.distance).abs() <= 1e-12,
        "{n:?} against {d_mirror}"
    );
    // A 2D curve seen from off its plane: the distance counts z.
    let n = a.nearest(DVec3::new(2.0, 1.5, 2.0)).expect("nearest");
    assert!((n.distance - 2.0).abs() <= 1e-12, "{n:?}");
    // A cusp (a cubic whose inner control points cross): the nearest point to the cusp
    // itself is the cusp.
    let cusp = Curve::Bezier(Bezier::new(vec![
        p(0.0, 0.0),
        p(3.0, 2.0),
        p(0.0, 2.0),
        p(3.0, 0.0),
    ]));
    let a = CurveAnalysis::new(&cusp);
    let n = a.nearest(cusp.eval(0.5)).expect("nearest");
    assert!(n.distance <= 1e-12, "{n:?}");
    // Not a point: refused, naming it.
    let e = a.nearest(DVec3::new(f64::NAN, 0.0, 0.0)).unwrap_err();
    assert!(matches!(e, AnalysisError::NotFinitePoint { .. }), "{e}");
    assert!(e.to_string().contains("NaN"), "{e}");
}

#[test]
fn many_points_at_once_answer_as_one_by_one() {
    let c = &curves()[1];
    let a = CurveAnalysis::new(c);
    let mut rng = Rng::new(7);
    let points: Vec<DVec3> = (0..500)
        .map(|_| p(rng.range(-2.0, 5.0), rng.range(-2.0, 4.0)))
        .collect();
    let many = a.nearest_many(&points);
    for (q, n) in points.iter().zip(many) {
        assert_eq!(n.expect("nearest"), a.nearest(*q).expect("nearest"));
    }
}
