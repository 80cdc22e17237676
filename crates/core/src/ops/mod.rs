//! Operations that make curves from curves: approximation by lower degree (cubics,
//! quadratics) within a tolerance, each result with a proven bound on its distance from
//! the curve it came from; and the exact small ones — a curve as a path of its segments,
//! split, reversed, curves joined.

use thiserror::Error;

use crate::geom::{Curve, GeomError, Lower};
use crate::num::Num;

pub mod approx;
pub mod fit;
pub mod knots;
pub mod offset;
pub mod reduce;
pub mod structure;

pub use approx::{Approximation, Target};
pub use fit::{Fit, Params, fit_bezier, fit_bspline, fit_path};
pub use knots::{Removed, remove_knot};
pub use offset::{Cap, Join, Offset, OffsetOptions, offset};
pub use reduce::{Reduced, reduce_degree};
pub use structure::{as_path, join, reverse, split};

/// Why an operation cannot be done.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum OpError {
    /// A tolerance that is not a finite number greater than 0.
    #[error("tolerance {}: must be a finite number greater than 0", Num(*.0))]
    Tolerance(f64),
    /// A segment that would need more pieces than the limit at this tolerance.
    #[error(
        "a segment needs more than {limit} pieces within tolerance {}: ask for a larger tolerance",
        Num(*tolerance)
    )]
    TooManyPieces {
        /// The most pieces one segment may become.
        limit: usize,
        /// The tolerance asked for.
        tolerance: f64,
    },
    /// A knot that is not an interior knot of the curve, or is there fewer times than
    /// asked.
    #[error(
        "knot {}: {} (remove it at most as many times as it is there)",
        Num(*u),
        if *present == 0 { "not an interior knot of the curve".to_owned() } else { format!("there {present} time(s), not {times}") }
    )]
    NotAKnot {
        /// The knot asked for.
        u: f64,
        /// How many times to remove it.
        times: usize,
        /// How many times it is there (0: not an interior knot).
        present: usize,
    },
    /// A removal that would move the curve more than the tolerance.
    #[error(
        "removing knot {} {times} time(s) would move the curve by up to {} (a proven bound), more than the tolerance {}",
        Num(*u), Num(*bound), Num(*tolerance)
    )]
    WouldMove {
        /// The knot.
        u: f64,
        /// How many times.
        times: usize,
        /// The bound on how far the curve would move.
        bound: f64,
        /// The tolerance asked for.
        tolerance: f64,
    },
    /// An operation for other families.
    #[error("{operation} is for {families}, not {family} curves")]
    Unsupported {
        /// The operation.
        operation: &'static str,
        /// The curve's family.
        family: &'static str,
        /// The families it is for.
        families: &'static str,
    },
    /// No lower degree is within the tolerance.
    #[error(
        "degree {degree}: {}",
        match best {
            Some(b) => format!("no lower degree is within the tolerance {}; the closest, degree {} ends kept, is within {} (a proven bound)", Num(*tolerance), degree - 1, Num(*b)),
            None => "a line has no lower degree with both its ends".to_owned(),
        }
    )]
    NoLowerDegree {
        /// The curve's degree.
        degree: usize,
        /// The least bound reached (at degree − 1).
        best: Option<f64>,
        /// The tolerance asked for.
        tolerance: f64,
    },
    /// A fit's input that cannot be fitted (named in the message).
    #[error("{0}")]
    Fit(String),
    /// A tolerance finer than an offset can be proven to in `f64` for this curve (a
    /// relative floor of its size and distance).
    #[error(
        "tolerance {}: finer than an offset of this curve can be proven to ({} of its size and distance: {}); ask for at least that",
        Num(*tolerance), Num(*relative), Num(*floor)
    )]
    BelowPrecision {
        /// The tolerance asked for.
        tolerance: f64,
        /// The floor relative to the curve's size and distance.
        relative: f64,
        /// The least tolerance allowed for this curve.
        floor: f64,
    },
    /// An offset distance that is not finite (or 0 for a stroke outline).
    #[error("offset distance {}: must be a finite number (not 0 for a stroke outline)", Num(*.0))]
    Distance(f64),
    /// A miter limit below 1 or not finite.
    #[error("miter limit {}: must be a finite number of at least 1", Num(*.0))]
    MiterLimit(f64),
    /// A planar operation asked of a curve that leaves the plane.
    #[error("{operation} is defined for planar (2D) curves; this curve leaves the plane z = 0")]
    NotPlanar {
        /// The operation.
        operation: &'static str,
    },
    /// A curve the operation cannot be done on (named in the message).
    #[error("{0}")]
    Degenerate(&'static str),
    /// Trimming asked together with caps.
    #[error(
        "trim removes an offset's loops; a stroke outline (caps given) is not trimmed: ask for one or the other"
    )]
    TrimWithCaps,
    /// The analysis an operation relies on failed (its message).
    #[error("{0}")]
    Analysis(String),
    /// A join of no curves.
    #[error("nothing to join: give at least one curve")]
    NothingToJoin,
    /// The result is not a valid curve.
    #[error("{0}")]
    Geom(GeomError),
}

/// Whether a curve's stroke closes: a closed path.
fn closed(curve: &Curve) -> bool {
    matches!(curve, Curve::Path(p) if p.is_closed())
}

/// `curve` as a path of cubic segments within `tolerance` (Hausdorff distance, proven:
/// [`approx`]).
///
/// # Errors
/// See [`approx::approximate`].
pub fn to_cubics(curve: &Curve, tolerance: f64) -> Result<Approximation, OpError> {
    approx::approximate(&curve.lower(), closed(curve), Target::Cubic, tolerance)
}

/// `curve` as a path of quadratic segments within `tolerance` (what a TrueType font
/// stores).
///
/// # Errors
/// See [`approx::approximate`].
pub fn to_quadratics(curve: &Curve, tolerance: f64) -> Result<Approximation, OpError> {
    approx::approximate(&curve.lower(), closed(curve), Target::Quadratic, tolerance)
}
