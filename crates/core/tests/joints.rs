//! Continuity at the joints of piecewise curves (`CurveAnalysis::joints`) on joints built
//! with known continuity: a cubic B-spline's simple knots are G2 (C²), a double knot is G1
//! with the curvature jump the curve's own one-sided derivatives give, a triple knot is a
//! kink at the angle its control points were placed at, a circle's seam is G2, a closed
//! spline's seam a kink at its built angle, a modified Bézier curve's bump ends G1 (its
//! bump is C¹, not C²).

use glam::DVec3;
use splinescope_core::analysis::{CurveAnalysis, JointClass};
use splinescope_core::geom::{BSpline, Bezier, ModifiedBezier, Nurbs, ParamCurve};

fn p(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

fn cubic_spline(points: Vec<DVec3>, knots: Vec<f64>) -> BSpline {
    BSpline::try_new(points, knots, 4).expect("a valid cubic B-spline")
}

/// The curvature vector from first and second derivatives.
fn kvec(d1: DVec3, d2: DVec3) -> DVec3 {
    let s2 = d1.length_squared();
    (d2 - d2.dot(d1) / s2 * d1) / s2
}

#[test]
fn simple_knots_are_g2_and_a_double_knot_is_g1_with_its_jump() {
    let pts = vec![
        p(0.0, 0.0),
        p(1.0, 2.0),
        p(2.5, -1.0),
        p(4.0, 1.5),
        p(5.0, 0.0),
        p(6.5, 2.0),
        p(8.0, 0.5),
    ];
    // Simple interior knots: C² everywhere.
    let smooth = cubic_spline(
        pts.clone(),
        vec![0., 0., 0., 0., 1., 2., 3., 4., 4., 4., 4.],
    );
    let joints = CurveAnalysis::new(&smooth).joints().expect("joints");
    assert_eq!(joints.len(), 3, "{joints:?}");
    for j in &joints {
        assert_eq!(j.class, JointClass::G2, "{j:?}");
        assert!(
            j.gap <= 1e-12 && j.angle <= 1e-12 && j.curvature_jump <= 1e-9,
            "{j:?}"
        );
    }
    assert_eq!(
        joints.iter().map(|j| j.t).collect::<Vec<_>>(),
        vec![1.0, 2.0, 3.0]
    );
    // A double knot at 2: C¹ there, the curvature jumps.
    let kinked = cubic_spline(pts, vec![0., 0., 0., 0., 1., 2., 2., 3., 3., 3., 3.]);
    let joints = CurveAnalysis::new(&kinked).joints().expect("joints");
    let j = joints
        .iter()
        .find(|j| j.t == 2.0)
        .expect("a joint at the double knot");
    assert_eq!(j.class, JointClass::G1, "{j:?}");
    // The curve's own derivatives just before and after the knot.
    let e = 1e-9;
    let k1 = kvec(
        kinked.eval_deriv(2.0 - e),
        kinked.eval_second_deriv(2.0 - e),
    );
    let k2 = kvec(
        kinked.eval_deriv(2.0 + e),
        kinked.eval_second_deriv(2.0 + e),
    );
    let want = (k1 - k2).length() / k1.length().max(k2.length());
    assert!(want > 1e-3, "the construction jumps: {want}");
    assert!(
        (j.curvature_jump - want).abs() <= 1e-6 * want.max(1.0),
        "jump {} vs {want}",
        j.curvature_jump
    );
    assert!(j.angle <= 1e-12, "{j:?}");
}

#[test]
fn a_triple_knot_is_a_kink_at_its_built_angle() {
    for deg in [15.0_f64, 30.0, 90.0, 135.0, 170.0] {
        let th = deg.to_radians();
        let c = p(3.0, 1.0);
        let pts = vec![
            p(0.0, 0.0),
            p(1.0, 1.5),
            c - p(1.0, 0.0),
            c,
            c + p(th.cos(), th.sin()),
            c + 2.0 * p(th.cos(), th.sin()) + p(0.0, 0.5),
            c + 3.0 * p(th.cos(), th.sin()),
        ];
        let s = cubic_spline(pts, vec![0., 0., 0., 0., 1., 1., 1., 2., 2., 2., 2.]);
        let joints = CurveAnalysis::new(&s).joints().expect("joints");
        assert_eq!(joints.len(), 1, "{joints:?}");
        let j = joints[0];
        assert_eq!(j.class, JointClass::G0, "{deg}°: {j:?}");
        assert!((j.angle - th).abs() <= 1e-12, "{deg}°: {} vs {th}", j.angle);
        assert!((j.point - c).length() <= 1e-12, "{j:?}");
    }
}

#[test]
fn seams_of_closed_curves() {
    // A circle (a closed NURBS curve): every joint and its seam G2.
    let circle = Nurbs::circle(p(1.0, -2.0), 3.0).expect("circle");
    let joints = CurveAnalysis::new(&circle).joints().expect("joints");
    let seams: Vec<_> = joints.iter().filter(|j| j.seam).collect();
    assert_eq!(seams.len(), 1, "{joints:?}");
    for j in &joints {
        assert_eq!(j.class, JointClass::G2, "{j:?}");
    }
    // A closed cubic Bézier leaving its start at 90° to the way it arrives: the seam is a
    // kink of exactly 90°.
    let loop_ = Bezier::new(vec![p(0.0, 0.0), p(2.0, 0.0), p(0.0, 2.0), p(0.0, 0.0)]);
    let joints = CurveAnalysis::new(&loop_).joints().expect("joints");
    assert_eq!(joints.len(), 1, "{joints:?}");
    let j = joints[0];
    assert!(j.seam && j.class == JointClass::G0, "{j:?}");
    // Arrives along (0, -2) (from (0, 2) to (0, 0)), leaves along (2, 0).
    assert!(
        (j.angle - std::f64::consts::FRAC_PI_2).abs() <= 1e-12,
        "{j:?}"
    );
    // An open curve has no seam.
    let open = Bezier::new(vec![p(0.0, 0.0), p(1.0, 1.0), p(2.0, 0.0)]);
    assert!(
        CurveAnalysis::new(&open)
            .joints()
            .expect("joints")
            .is_empty()
    );
}

#[test]
fn a_modified_bezier_curves_bump_ends_are_g1() {
    let base = Bezier::new(vec![p(0.0, 0.0), p(1.0, 2.0), p(3.0, 2.0), p(4.0, 0.0)]);
    let m = ModifiedBezier::try_new(base, 0.4, p(0.0, 0.8)).expect("bump");
    let joints = CurveAnalysis::new(&m).joints().expect("joints");
    assert!(!joints.is_empty(), "the bump's support ends are joints");
    for j in &joints {
        assert!(j.gap <= 1e-12 && j.angle <= 1e-9, "C¹: one tangent: {j:?}");
        assert!(j.class >= JointClass::G1, "{j:?}");
    }
    assert!(
        joints.iter().any(|j| j.class == JointClass::G1),
        "a C¹ bump jumps the curvature somewhere: {joints:?}"
    );
}

/// At the extremes of the coordinates (1e300, 1e-300) a joint is what it is at unit scale:
/// the same angle and the same relative curvature jump, the same class.
#[test]
fn joints_do_not_depend_on_the_scale() {
    let pts = vec![
        p(0.0, 0.0),
        p(1.0, 1.5),
        p(2.0, 1.0),
        p(3.0, 1.0),
        p(3.0, 2.0),
        p(3.5, 4.0),
        p(5.0, 3.0),
        p(6.0, 5.0),
        p(7.0, 4.0),
    ];
    let knots = vec![0., 0., 0., 0., 1., 1., 1., 2., 2., 3., 3., 3., 3.];
    let unit = CurveAnalysis::new(&cubic_spline(pts.clone(), knots.clone()))
        .joints()
        .expect("joints");
    assert_eq!(unit.len(), 2, "a kink at 1, a curvature jump at 2");
    for scale in [1e300, 1e-300, 1e150, 1e-150] {
        let scaled: Vec<DVec3> = pts.iter().map(|q| *q * scale).collect();
        let joints = CurveAnalysis::new(&cubic_spline(scaled, knots.clone()))
            .joints()
            .expect("joints");
        assert_eq!(joints.len(), unit.len(), "{scale:e}");
        for (j, u) in joints.iter().zip(&unit) {
            assert_eq!(j.class, u.class, "{scale:e}: {j:?} vs {u:?}");
            assert!(
                (j.angle - u.angle).abs() <= 1e-12,
                "{scale:e}: {j:?} vs {u:?}"
            );
            assert!(
                (j.curvature_jump - u.curvature_jump).abs() <= 1e-9 * u.curvature_jump.max(1.0),
                "{scale:e}: {j:?} vs {u:?}"
            );
        }
    }
}
