//! The CPU solvers (`f64`): closest points, least-squares shape modification of Bézier
//! curves (paper 000) and constrained modification of NUBMP curves (paper 001, §5.2), one
//! at a time or in parallel batches.

pub mod batch;
pub mod linalg;
pub mod nubmp;
pub mod project;
pub mod rational;
pub mod region;
pub mod roots;
pub mod shape;

use thiserror::Error;

use crate::geom::GeomError;

pub use project::{Nearest, nearest};

/// Why a solve request cannot be carried out.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SolveError {
    /// A target coordinate is NaN or infinite.
    #[error("target {index}: not a finite number ({value})")]
    NonFiniteTarget {
        /// Which target.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A multi-target request without targets.
    #[error("no targets given")]
    NoTargets,
    /// Parameters given do not match the targets.
    #[error("{params} parameters for {targets} targets")]
    ParamCount {
        /// Targets.
        targets: usize,
        /// Parameters.
        params: usize,
    },
    /// A parameter outside the curve's domain.
    #[error("parameter {value} is outside the domain [{start}, {end}]")]
    ParameterOutsideDomain {
        /// The parameter.
        value: f64,
        /// The domain's start.
        start: f64,
        /// The domain's end.
        end: f64,
    },
    /// A start parameter at a fixed end.
    #[error(
        "target {index}: t = {value} is an end of the curve; the end points are fixed, so no interior control point can move P(t)"
    )]
    ParameterAtEnd {
        /// Which target.
        index: usize,
        /// The parameter.
        value: f64,
    },
    /// A target whose projection is a fixed end point.
    #[error(
        "target {index} projects onto the fixed end point (t = {t}): it cannot be met with the ends fixed; give its parameter explicitly"
    )]
    TargetAtEnd {
        /// Which target.
        index: usize,
        /// The projected parameter.
        t: f64,
    },
    /// None of the points the solve may move has any influence at the target's parameter
    /// (their basis functions are 0 there, in `f64`): no move of them can reach it.
    #[error(
        "target {index}: the control points it may move ({moved}) do not move the curve at t = {} (their basis functions are 0 there); {influence}",
        crate::num::Num(*value)
    )]
    NoInfluence {
        /// Which target.
        index: usize,
        /// Its parameter.
        value: f64,
        /// The points that may move, listed (`P_1..P_3`).
        moved: String,
        /// Which interior points do move the curve there, or why none does.
        influence: String,
    },
    /// Reaching a target needs moves beyond `f64` (its moved points' basis values are
    /// tiny there).
    #[error(
        "target {index}: reaching it at t = {} needs moves beyond f64 (the moved points barely move the curve there); choose a parameter further inside",
        crate::num::Num(*value)
    )]
    MovesOverflow {
        /// Which target.
        index: usize,
        /// Its parameter.
        value: f64,
    },
    /// The solution misses a target it should meet by more than `1e−9` of the target's and
    /// the curve's size there (rounding on an ill-conditioned system): refused rather than
    /// returned.
    #[error(
        "target {index}: the solution misses it by {residual:e} at t = {}: the moves the targets need are too large for f64 to keep this one (an ill-conditioned system: targets far apart in size, or a parameter next to an end)",
        crate::num::Num(*value)
    )]
    Missed {
        /// Which target.
        index: usize,
        /// Its parameter.
        value: f64,
        /// `|C̃(t) − T|`.
        residual: f64,
    },
    /// The window of moved points leaves the interior.
    #[error(
        "moving P_l..P_(l+m-1) with l = {first}, m = {count}: they must lie between 1 and {max} (the ends stay fixed)"
    )]
    WindowOutOfRange {
        /// `l`.
        first: usize,
        /// `m`.
        count: usize,
        /// `n − 1`.
        max: usize,
    },
    /// The method needs a higher degree.
    #[error("{method} needs degree ≥ {min}, the curve has degree {degree}")]
    DegreeTooLow {
        /// The method.
        method: &'static str,
        /// The curve's degree.
        degree: usize,
        /// The least degree.
        min: usize,
    },
    /// The cubic region needs a cubic.
    #[error(
        "the allowed region of paper 000 §2.3 is defined for cubics; the curve has degree {degree}"
    )]
    NotCubic {
        /// The curve's degree.
        degree: usize,
    },
    /// An end point coincides with its neighbour.
    #[error("no tangent direction at the {end}: the end tangent cannot be kept")]
    NoTangent {
        /// Which end.
        end: &'static str,
    },
    /// The group's dual B-spline vanishes at `τ`.
    #[error(
        "group {group} does not move P(τ) at τ = {tau} (its dual B-spline is 0 there); groups that do: {active}"
    )]
    GroupInactive {
        /// The group.
        group: usize,
        /// `τ`.
        tau: f64,
        /// The groups that do, listed.
        active: String,
    },
    /// `q` is outside what the group can reach.
    #[error(
        "q is outside the region P(τ) can reach by changing group {group} (it is {distance:.6} away; the region's vertices are {vertices})"
    )]
    OutsideRegion {
        /// The group.
        group: usize,
        /// Distance from `q` to the region.
        distance: f64,
        /// The region's vertices, listed.
        vertices: String,
    },
    /// Reaching `q` would break a VD condition.
    #[error(
        "reaching q needs parameters that break the variation-diminishing condition of group {group} (Theorem 1 value {value:.6} > 1)"
    )]
    BreaksVd {
        /// The group whose condition fails.
        group: usize,
        /// Its Theorem 1 value.
        value: f64,
    },
    /// No parameter τ puts `q` in reach of the group.
    #[error("no τ in the group's support lets group {group} move the curve through q")]
    NoTau {
        /// The group.
        group: usize,
    },
    /// A curve-level error (group or member indices, values).
    #[error(transparent)]
    Geom(#[from] GeomError),
}
