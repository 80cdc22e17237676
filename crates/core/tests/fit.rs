//! Fitting, against constructions with known answers: points on a cubic at its own
//! parameters give back its control points; points on a B-spline at given parameters,
//! fitted on its knots, give back its control points; a smoothing budget is met; the
//! points themselves (s = 0) are interpolated. (Against scipy and NumPy:
//! `crates/python/tests/test_fit.py`.)

use glam::DVec3;
use splinescope_core::geom::{BSpline, Bezier};
use splinescope_core::ops::{OpError, Params, fit_bezier, fit_bspline};

#[test]
fn exact_data_gives_back_the_curve() {
    let cubic = Bezier::new(vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 3.0, 1.0),
        DVec3::new(3.0, -1.0, 2.0),
        DVec3::new(4.0, 1.0, 0.0),
    ]);
    let ts: Vec<f64> = (0..50).map(|i| (f64::from(i) / 49.0).powf(1.3)).collect();
    let pts: Vec<DVec3> = ts.iter().map(|&t| cubic.eval(t)).collect();
    let fit = fit_bezier(&pts, 3, &Params::Given(ts.clone()), None).expect("fit");
    for (a, b) in fit.curve.points().iter().zip(cubic.points()) {
        assert!((*a - *b).length() <= 1e-10, "{a} {b}");
    }
    assert!(fit.residuals.iter().all(|r| *r <= 1e-10));
    let spline = BSpline::try_new(
        (0..7)
            .map(|i| DVec3::new(f64::from(i), f64::from(i % 3), 0.0))
            .collect(),
        vec![0.0, 0.0, 0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0],
        4,
    )
    .expect("spline");
    let ts: Vec<f64> = (0..80).map(|i| f64::from(i) / 79.0).collect();
    let pts: Vec<DVec3> = ts.iter().map(|&t| spline.eval(t)).collect();
    let fit = fit_bspline(
        &pts,
        3,
        Some(&[0.25, 0.5, 0.75]),
        None,
        &Params::Given(ts),
        None,
    )
    .expect("fit");
    for (a, b) in fit.curve.points().iter().zip(spline.points()) {
        assert!((*a - *b).length() <= 1e-10, "{a} {b}");
    }
}

#[test]
fn a_smoothing_budget_is_met_and_zero_interpolates() {
    let pts: Vec<DVec3> = (0..300)
        .map(|i| {
            let x = f64::from(i) / 30.0;
            DVec3::new(x, x.sin() + 0.01 * (f64::from(i) * 12.9898).sin(), 0.0)
        })
        .collect();
    for s in [1.0, 0.1, 0.01, 0.001] {
        let fit = fit_bspline(&pts, 3, None, Some(s), &Params::Chord, None).expect("fit");
        assert!(
            fit.sum_of_squares(None) <= s,
            "{s}: {}",
            fit.sum_of_squares(None)
        );
    }
    let few = &pts[..12];
    let fit = fit_bspline(few, 3, None, Some(0.0), &Params::Centripetal, None).expect("fit");
    assert!(
        fit.residuals.iter().all(|r| *r <= 1e-10),
        "{:?}",
        fit.residuals
    );
    let e = fit_bspline(few, 3, None, None, &Params::Chord, None).unwrap_err();
    assert!(
        matches!(e, OpError::Fit(_)) && e.to_string().contains("either knots"),
        "{e}"
    );
}

#[test]
fn a_polyline_becomes_a_few_cubics_within_the_tolerance_with_its_corners_kept() {
    use splinescope_core::analysis::CurveAnalysis;
    use splinescope_core::geom::{Curve, ParamCurve};
    use splinescope_core::ops::fit_path;
    // A pen stroke: a line, a right-angled corner, a half circle, another corner, a line;
    // dense, free of noise.
    let mut pts = Vec::new();
    // Up to (5, 0), then the half circle about (5, 2) leaves along +x: a 90° corner.
    for i in 0..=100 {
        pts.push(DVec3::new(5.0, -5.0 + f64::from(i) * 0.05, 0.0));
    }
    for i in 1..=200 {
        let a = std::f64::consts::PI * f64::from(i) / 200.0;
        pts.push(DVec3::new(5.0 + 2.0 * a.sin(), 2.0 - 2.0 * a.cos(), 0.0));
    }
    // It arrives at (5, 4) along −x; the line leaves upwards: another 90° corner.
    for i in 1..=100 {
        pts.push(DVec3::new(5.0, 4.0 + f64::from(i) * 0.05, 0.0));
    }
    for tol in [1e-2, 1e-3] {
        let fit = fit_path(&pts, tol, 30.0).expect("fit");
        assert!(fit.residuals.iter().all(|r| *r <= tol), "{tol}");
        // Every point within the tolerance of the path itself (its nearest point).
        let a = CurveAnalysis::new(&Curve::Path(fit.curve.clone()));
        for p in &pts {
            assert!(a.nearest(*p).expect("nearest").distance <= tol * (1.0 + 1e-9));
        }
        let k = fit.curve.segments().len();
        assert!(k <= 14, "{tol}: {k} segments");
        // The two corners are joints with a turn of 90°; the others are smooth.
        let c = Curve::Path(fit.curve.clone());
        let segs = fit.curve.segments();
        let mut kinks = 0;
        for j in 1..segs.len() {
            let (s, n) = (&segs[j - 1].points, &segs[j].points);
            let out = (s[3] - s[2]).normalize();
            let inn = (n[1] - n[0]).normalize();
            let angle = out.dot(inn).clamp(-1.0, 1.0).acos().to_degrees();
            if angle > 1e-6 {
                kinks += 1;
                assert!((angle - 90.0).abs() < 1.0, "{angle}");
            }
        }
        assert_eq!(kinks, 2, "{tol}");
        assert!((c.eval(0.0) - pts[0]).length() == 0.0);
    }
    // A closed polyline (a circle) gives a closed, smooth path.
    let circle: Vec<DVec3> = (0..=360)
        .map(|i| {
            let a = f64::from(i).to_radians();
            DVec3::new(a.cos(), a.sin(), 0.0)
        })
        .collect();
    let mut circle = circle;
    let first = circle[0];
    *circle.last_mut().expect("points") = first;
    let fit = fit_path(&circle, 1e-4, 30.0).expect("fit");
    assert!(fit.curve.is_closed());
    assert!(fit.residuals.iter().all(|r| *r <= 1e-4));
    // Bad arguments.
    assert!(fit_path(&circle, 0.0, 30.0).is_err());
    assert!(fit_path(&circle, 1e-3, 200.0).is_err());
    assert!(fit_path(&circle[..1], 1e-3, 30.0).is_err());
}
