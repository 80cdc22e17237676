//! The error type of curve construction.

use thiserror::Error;

/// Why a curve could not be built from its data.
///
/// Each variant knows the field it concerns, relative to the curve ([`GeomError::field`]),
/// so that the scene layer can name the full path, e.g. `curves[3].points[2]`.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GeomError {
    /// A list of control points is shorter than the family requires.
    #[error("needs at least {min} points, found {found}")]
    TooFewPoints {
        /// The smallest valid count.
        min: usize,
        /// The count given.
        found: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("not a finite number ({value})")]
    NonFinitePoint {
        /// Index of the offending point.
        index: usize,
        /// The offending value.
        value: f64,
    },
}

impl GeomError {
    /// The field this error concerns, relative to the curve (e.g. `points[2]`).
    #[must_use]
    pub fn field(&self) -> String {
        match self {
            GeomError::TooFewPoints { .. } => "points".to_owned(),
            GeomError::NonFinitePoint { index, .. } => format!("points[{index}]"),
        }
    }
}
