//! Curve mathematics in `f64`: Bernstein polynomials, Bézier curves of any degree, the
//! modified Bézier curve and cubic interpolation of paper 002, non-uniform B-splines and
//! the NUBMP curves of paper 001, and the lowering of every family to a list of Bézier
//! segments (the one representation the GPU sees).
//!
//! Points are [`glam::DVec3`]; planar curves have `z = 0`. Nothing in this module knows
//! about the GPU.

pub mod batch;
pub mod bernstein;
pub mod bezier;
pub mod bspline;
pub mod cubic_region;
pub mod curve;
pub mod error;
pub mod exact;
pub mod family;
pub mod interp;
pub mod knots;
pub mod lowering;
pub mod modified;
pub mod nubmp;
pub mod structure;

pub use bezier::{Aabb, Bezier};
pub use bspline::BSpline;
pub(crate) use curve::each_family;
pub use curve::{Curve, OverlayKind, OverlayPolyline};
pub use error::GeomError;
pub use family::{Control, ControlId, ControlKind, ControlValue, Family, FamilyDetails};
pub use interp::{CubicInterpolation, Modification, Reading};
pub use knots::KnotVector;
pub use lowering::{BezierSegment, Lower, locate};
pub use modified::ModifiedBezier;
pub use nubmp::Nubmp;

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
