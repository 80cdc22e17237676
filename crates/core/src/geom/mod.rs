//! Curve mathematics in `f64`: Bernstein polynomials, Bézier curves of any degree, the
//! modified Bézier curve and cubic interpolation of paper 002, non-uniform B-splines and
//! the NUBMP curves of paper 001, and the lowering of every family to a list of Bézier
//! segments (the one representation the GPU sees).
//!
//! Points are [`glam::DVec3`]; planar curves have `z = 0`. Nothing in this module knows
//! about the GPU.

pub mod aabb;
pub mod batch;
pub mod bernstein;
pub mod bezier;
pub mod bspline;
pub mod cubic_region;
pub mod curve;
pub mod error;
pub mod exact;
pub mod family;
pub mod interpolation;
pub mod knots;
pub mod lowering;
pub mod modified;
pub mod nubmp;
pub mod nurbs_form;
pub mod path;
pub mod rational;
pub mod structure;

pub use aabb::Aabb;
pub use bezier::Bezier;
pub use bspline::BSpline;
pub use curve::Curve;
pub use error::GeomError;
pub use family::{AtTau, Family, GroupAtTau, Xyz, xyz};
pub use interpolation::{CubicInterpolation, Modification, Reading};
pub use knots::KnotVector;
pub use lowering::{BezierSegment, Lower, locate, max_degree};
pub use modified::ModifiedBezier;
pub use nubmp::Nubmp;
pub use nurbs_form::NurbsForm;
pub use path::{Path, PathSegment, SegmentPoints};
pub use rational::{Conic, Nurbs, RationalBezier};

use glam::DVec3;

/// A curve evaluated by a parameter over a closed domain (kurbo's `ParamCurve`, in 3D and
/// `f64`).
pub trait ParamCurve {
    /// The parameter domain `[a, b]` of the curve.
    fn domain(&self) -> (f64, f64);
    /// The point at parameter `t` (`t` in [`ParamCurve::domain`]).
    fn eval(&self, t: f64) -> DVec3;
    /// The first derivative with respect to `t`.
    fn eval_deriv(&self, t: f64) -> DVec3;
    /// The second derivative with respect to `t`.
    fn eval_second_deriv(&self, t: f64) -> DVec3;
}

/// The curvature `κ = |P′ × P″| / |P′|³` from the first and second derivatives, or `None`
/// where `P′ = 0` (no tangent, no curvature).
///
/// Computed without intermediate underflow or overflow: each derivative is scaled by its
/// largest component before the cross product and the cube, and the scales are put back
/// by their binary exponents at the end. So a subnormal but nonzero `P′` still has a
/// curvature, and the result is `+∞` or `0` only when the curvature itself is beyond
/// `f64`'s range.
#[must_use]
pub fn curvature(d1: DVec3, d2: DVec3) -> Option<f64> {
    let m1 = d1.abs().max_element();
    if m1 == 0.0 {
        return None;
    }
    let m2 = d2.abs().max_element();
    if m2 == 0.0 {
        return Some(0.0);
    }
    // u, w have largest component ±1: |u| ∈ [1, √3], |u × w| ≤ 2.
    let (u, w) = (d1 / m1, d2 / m2);
    let c = u.cross(w).length() / u.length().powi(3);
    if c == 0.0 {
        return Some(0.0);
    }
    // κ = c · m2 / m1², each factor split into a mantissa in [1, 2) and a binary exponent.
    let split = crate::num::split_exponent;
    let ((fc, ec), (f2, e2), (f1, e1)) = (split(c), split(m2), split(m1));
    Some(crate::num::scale_by_power_of_two(
        fc * f2 / (f1 * f1),
        ec + e2 - 2 * e1,
    ))
}

#[cfg(test)]
mod curvature_tests {
    use super::*;

    #[test]
    fn curvature_of_a_circle_at_any_scale() {
        // P(t) = r (cos t, sin t): P′ = r(−sin, cos), P″ = −r(cos, sin), κ = 1/r, whatever
        // r is — subnormal, tiny, huge — as long as 1/r is an f64.
        for r in [1.0, 3.0, 1e-300, 1e-308, 6e-309, 1e-111, 1e300] {
            let t = 0.7_f64;
            let d1 = DVec3::new(-t.sin(), t.cos(), 0.0) * r;
            let d2 = DVec3::new(-t.cos(), -t.sin(), 0.0) * r;
            let k = curvature(d1, d2).unwrap();
            // Subnormal r holds few bits: the tolerance follows the precision left.
            let bits_left = if r < f64::MIN_POSITIVE {
                (r / 5e-324).log2()
            } else {
                52.0
            };
            let tol = 4.0 * 2f64.powf(-bits_left);
            assert!(
                ((k * r) - 1.0).abs() <= tol,
                "r = {r:e}: κ = {k:e}, want {:e}",
                1.0 / r
            );
        }
        // A straight line: zero; no tangent: none.
        assert_eq!(curvature(DVec3::X, DVec3::X * 5.0), Some(0.0));
        assert_eq!(curvature(DVec3::X, DVec3::ZERO), Some(0.0));
        assert_eq!(curvature(DVec3::ZERO, DVec3::Y), None);
        // Beyond f64: infinite, not NaN or a silent zero (1/r > f64::MAX for this r).
        let k = curvature(DVec3::X * 5e-324, DVec3::Y * 1e300).unwrap();
        assert!(k.is_infinite(), "{k}");
        let r = 5e-320;
        let k = curvature(DVec3::Y * r, DVec3::X * -r).unwrap();
        assert!(k.is_infinite() && k > 0.0, "{k}");
    }
}
