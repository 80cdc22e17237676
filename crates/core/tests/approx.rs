//! Approximation by cubics and quadratics: every curve of every family within the
//! tolerance, measured independently of the bound (the Hausdorff distance sampled both
//! ways with the nearest point, and a circle's approximation against its closed form),
//! exact where the curve already is of the target degree, and bad tolerances refused.

use glam::DVec3;
use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::{
    BSpline, Bezier, Curve, ModifiedBezier, Nurbs, ParamCurve, Path, PathSegment, RationalBezier,
};
use splinescope_core::ops::{OpError, to_cubics, to_quadratics};

fn p(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

fn curves() -> Vec<Curve> {
    let base = Bezier::new(vec![p(-3.0, 0.0), p(-2.0, 2.0), p(0.0, 2.0), p(1.0, 0.5)]);
    vec![
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
                vec![1.0, 3.0, 0.5, 2.0],
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
    ]
}

/// The Hausdorff distance between two curves, measured: each one sampled densely, every
/// sample's nearest point on the other.
fn hausdorff(a: &Curve, b: &Curve) -> f64 {
    let one_way = |x: &Curve, y: &Curve| {
        let ay = CurveAnalysis::new(y);
        let (t0, t1) = x.domain();
        (0..=600)
            .map(|i| {
                let t = t0 + (t1 - t0) * f64::from(i) / 600.0;
                ay.nearest(x.eval(t)).expect("nearest").distance
            })
            .fold(0.0, f64::max)
    };
    one_way(a, b).max(one_way(b, a))
}

#[test]
fn every_family_is_within_the_tolerance_and_its_bound() {
    for c in curves() {
        for tol in [1e-2, 1e-4, 1e-7] {
            for (what, made) in [
                ("cubics", to_cubics(&c, tol)),
                ("quadratics", to_quadratics(&c, tol)),
            ] {
                let made = made.unwrap_or_else(|e| panic!("{} {what} {tol}: {e}", c.family()));
                let degree = if what == "cubics" { 3 } else { 2 };
                assert!(
                    made.path
                        .segments()
                        .iter()
                        .all(|s| s.degree() == degree && s.weights.is_none())
                );
                assert!(
                    made.error <= tol,
                    "{} {what}: bound {} over {tol}",
                    c.family(),
                    made.error
                );
                let measured = hausdorff(&c, &Curve::Path(made.path.clone()));
                assert!(
                    measured <= made.error + 1e-12,
                    "{} {what} at {tol}: measured {measured} over the bound {}",
                    c.family(),
                    made.error
                );
            }
        }
    }
}

#[test]
fn a_circle_stays_within_the_tolerance_of_its_radius() {
    let circle = Curve::Nurbs(Nurbs::circle(p(0.0, 0.0), 10.0).expect("circle"));
    for tol in [1e-3, 1e-6, 1e-9] {
        for made in [
            to_cubics(&circle, tol).expect("cubics"),
            to_quadratics(&circle, tol).expect("quadratics"),
        ] {
            let path = Curve::Path(made.path.clone());
            assert!(
                made.path.is_closed()
                    || (path.eval(0.0) - path.eval(path.domain().1)).length() < 1e-12
            );
            let (t0, t1) = path.domain();
            for i in 0..=4000 {
                let t = t0 + (t1 - t0) * f64::from(i) / 4000.0;
                let off = (path.eval(t).length() - 10.0).abs();
                assert!(off <= made.error + 1e-13 && off <= tol, "tol {tol}: {off}");
            }
        }
    }
    // Fewer segments for looser tolerances.
    let counts: Vec<usize> = [1e-1, 1e-3, 1e-6, 1e-9]
        .iter()
        .map(|&tol| {
            to_cubics(&circle, tol)
                .expect("cubics")
                .path
                .segments()
                .len()
        })
        .collect();
    assert!(counts.windows(2).all(|w| w[0] <= w[1]), "{counts:?}");
    assert!(counts[0] <= 8, "{counts:?}");
}

#[test]
fn curves_of_the_target_degree_are_kept_exactly() {
    let cubic = Curve::Bezier(Bezier::new(vec![
        p(0.0, 0.0),
        p(1.0, 2.0),
        p(3.0, 2.0),
        p(4.0, 0.0),
    ]));
    let made = to_cubics(&cubic, 1e-9).expect("cubics");
    assert_eq!(made.error, 0.0);
    assert_eq!(
        made.path.segments()[0].points.to_vec(),
        cubic.control_points().to_vec()
    );
    // A path of a line and a quadratic raised exactly to cubics.
    let path = Curve::Path(
        Path::try_new(
            vec![
                PathSegment::polynomial(vec![p(0.0, 0.0), p(3.0, 0.0)]),
                PathSegment::polynomial(vec![p(3.0, 0.0), p(4.0, 1.0), p(3.0, 2.0)]),
            ],
            false,
        )
        .expect("path"),
    );
    let made = to_cubics(&path, 1e-9).expect("cubics");
    assert_eq!(made.error, 0.0);
    assert_eq!(
        made.path.segments()[0].points.to_vec(),
        vec![p(0.0, 0.0), p(1.0, 0.0), p(2.0, 0.0), p(3.0, 0.0)]
    );
    let made = to_quadratics(&path, 1e-9).expect("quadratics");
    assert_eq!(
        made.path.segments()[1].points.to_vec(),
        vec![p(3.0, 0.0), p(4.0, 1.0), p(3.0, 2.0)]
    );
}

#[test]
fn bad_tolerances_are_refused_naming_them() {
    let c = &curves()[0];
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = to_cubics(c, bad).unwrap_err();
        assert!(matches!(e, OpError::Tolerance(_)), "{e}");
        assert!(e.to_string().contains("tolerance"), "{e}");
    }
    let e = to_quadratics(c, 1e-300).unwrap_err();
    assert!(matches!(e, OpError::TooManyPieces { .. }), "{e}");
}
