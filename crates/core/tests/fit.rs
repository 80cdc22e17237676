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
