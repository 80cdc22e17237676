//! Questions a curve answers — arc length and its inverse, extrema and the tight
//! bounding box, signed area, inflections, cusps and curvature extrema, intersections
//! with lines, other curves and itself — written once, on the exact Bézier segments every
//! family lowers to (polynomial or rational), so they hold for every family in 2D and 3D.
//!
//! The engine under them is one root finder for polynomials in Bernstein form
//! ([`crate::poly::roots::bernstein_roots`]) on the Bernstein arithmetic of
//! [`crate::poly`] — below `geom`, which uses them too. The algorithms and
//! their bounds are stated in `docs/math.md` §7.

pub mod comb;
pub mod curve;
pub mod gauss;
pub mod intersect;
pub mod joints;
pub mod piece;
pub mod quadrature;
pub mod report;

use crate::poly::roots as poly_roots;
pub use curve::{
    AnalysisError, CurvatureExtremum, CurveAnalysis, DEFAULT_ACCURACY, Extremum, ExtremumKind,
    HitKind, Length, LineHit, LineIntersections, Nearest, bezier_length,
};
pub use intersect::{Hit, Intersections, Overlap, PairIntersections, all_intersections};
pub use joints::{Joint, JointClass};

/// Moved below `geom`: [`crate::poly`].
#[deprecated(note = "moved to splinescope_core::poly")]
pub mod poly {
    pub use crate::poly::*;
}

/// Moved below `geom`: [`crate::poly::roots`].
#[deprecated(note = "moved to splinescope_core::poly::roots")]
pub mod roots {
    pub use crate::poly::roots::*;
}

/// Deprecated: `splinescope_core::poly::roots::Root`.
#[deprecated(note = "use splinescope_core::poly::roots::Root")]
pub type Root = poly_roots::Root;

/// Deprecated: `splinescope_core::poly::roots::Roots`.
#[deprecated(note = "use splinescope_core::poly::roots::Roots")]
pub type Roots = poly_roots::Roots;

/// Deprecated: `splinescope_core::poly::roots::bernstein_roots`.
#[deprecated(note = "use splinescope_core::poly::roots::bernstein_roots")]
#[must_use]
pub fn bernstein_roots(c: &[f64]) -> poly_roots::Roots {
    poly_roots::bernstein_roots(c)
}

/// Deprecated: `splinescope_core::poly::roots::bernstein_roots_with_noise`.
#[deprecated(note = "use splinescope_core::poly::roots::bernstein_roots_with_noise")]
#[must_use]
pub fn bernstein_roots_with_noise(c: &[f64], noise: f64) -> poly_roots::Roots {
    poly_roots::bernstein_roots_with_noise(c, noise)
}
