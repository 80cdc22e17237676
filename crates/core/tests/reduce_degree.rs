//! Degree reduction: an elevated curve comes back to its degree, every reduction is within
//! its bound and the tolerance (the Hausdorff distance measured both ways with the
//! nearest point), lower tolerances never give lower degrees, and what cannot be reduced
//! is refused naming the best bound.

use glam::DVec3;
use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::{Bezier, Curve, ParamCurve};
use splinescope_core::ops::{OpError, reduce_degree};
use splinescope_core::rng::Rng;

fn hausdorff(a: &Curve, b: &Curve) -> f64 {
    let one = |x: &Curve, y: &Curve| {
        let ay = CurveAnalysis::new(y);
        (0..=400)
            .map(|i| {
                ay.nearest(x.eval(f64::from(i) / 400.0))
                    .expect("nearest")
                    .distance
            })
            .fold(0.0, f64::max)
    };
    one(a, b).max(one(b, a))
}

#[test]
fn an_elevated_curve_comes_back_to_its_degree() {
    let cubic = Bezier::new(vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 2.0, 0.5),
        DVec3::new(3.0, 2.0, -0.5),
        DVec3::new(4.0, 0.0, 0.0),
    ]);
    let mut high = cubic.clone();
    for _ in 0..4 {
        high = high.elevate();
    }
    assert_eq!(high.degree(), 7);
    let r = reduce_degree(&high, 1e-9).expect("reduces");
    assert_eq!(r.curve.degree(), 3);
    for (a, b) in r.curve.points().iter().zip(cubic.points()) {
        assert!((*a - *b).length() <= 1e-9, "{a} {b}");
    }
}

#[test]
fn reductions_stay_within_their_bound_and_the_tolerance() {
    let mut rng = Rng::new(48);
    for _ in 0..40 {
        let n = rng.int(4, 9);
        // Gentle curves (points near a parabola) reduce well; some do not at all.
        let noise = [0.01, 0.1, 1.0][rng.int(0, 2)];
        let pts: Vec<DVec3> = (0..=n)
            .map(|i| {
                let x = i as f64 / n as f64 * 4.0;
                DVec3::new(x, 0.5 * x * (4.0 - x) + rng.range(-noise, noise), 0.0)
            })
            .collect();
        let c = Bezier::new(pts);
        let mut last_degree = 0;
        for tol in [0.5, 0.05, 0.005] {
            match reduce_degree(&c, tol) {
                Ok(r) => {
                    assert!(r.curve.degree() < n && r.error <= tol);
                    assert!(
                        r.curve.degree() >= last_degree,
                        "a lower tolerance gave a lower degree"
                    );
                    last_degree = r.curve.degree();
                    assert_eq!(r.curve.points()[0], c.points()[0]);
                    assert_eq!(r.curve.points()[r.curve.degree()], c.points()[n]);
                    let h = hausdorff(&Curve::Bezier(c.clone()), &Curve::Bezier(r.curve.clone()));
                    assert!(
                        h <= r.error + 1e-12,
                        "measured {h} over the bound {}",
                        r.error
                    );
                }
                Err(OpError::NoLowerDegree { best: Some(b), .. }) => {
                    assert!(b > tol);
                    last_degree = n;
                }
                Err(e) => panic!("{e}"),
            }
        }
    }
}

#[test]
fn what_cannot_be_reduced_is_refused_naming_the_best_bound() {
    let wiggle = Bezier::new(
        (0..=6)
            .map(|i| DVec3::new(f64::from(i), if i % 2 == 0 { 0.0 } else { 3.0 }, 0.0))
            .collect(),
    );
    let e = reduce_degree(&wiggle, 1e-6).unwrap_err();
    assert!(e.to_string().contains("the closest, degree 5"), "{e}");
    let line = Bezier::new(vec![DVec3::ZERO, DVec3::X]);
    assert!(
        reduce_degree(&line, 1.0)
            .unwrap_err()
            .to_string()
            .contains("a line")
    );
    assert!(matches!(
        reduce_degree(&wiggle, -1.0),
        Err(OpError::Tolerance(_))
    ));
}
