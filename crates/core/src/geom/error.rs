//! The error type of curve construction and editing.

use thiserror::Error;

/// Why a curve could not be built from its data, or an edit was refused.
///
/// Each variant knows the field it concerns, relative to the curve ([`GeomError::field`]),
/// so that the scene layer can name the full path, e.g. `curves[3].knots[5]`.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GeomError {
    /// A value computed from the input is not a finite number: the input is too extreme
    /// for `f64` (knots or parameters too close together, coordinates too large).
    #[error("{what} is not a finite number ({value_}): the input is too extreme for f64 arithmetic (knots or parameters too close together, or coordinates too large)", value_ = crate::num::Num(*.value))]
    DerivedNotFinite {
        /// The input field the value was computed from, relative to the curve
        /// (`knots`, `points`; empty for the curve as a whole).
        field: &'static str,
        /// What was computed, e.g. "degree-elevation coefficient c^2_3".
        what: String,
        /// The value.
        value: f64,
    },
    /// A list of control points is shorter than the family requires.
    #[error("needs at least {min} points, found {found}")]
    TooFewPoints {
        /// The smallest valid count.
        min: usize,
        /// The count given.
        found: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("not a finite number ({value_})", value_ = crate::num::Num(*.value))]
    NonFinitePoint {
        /// Index of the offending point.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// `t*` of a modified curve is not inside `(0, 1)`.
    #[error("t* = {value_} is not inside the open interval (0, 1)", value_ = crate::num::Num(*.value))]
    TStarOutside {
        /// The value given.
        value: f64,
    },
    /// The vector `v` of a modified curve has a non-finite coordinate.
    #[error("not a finite number ({value_})", value_ = crate::num::Num(*.value))]
    NonFiniteVector {
        /// The value given.
        value: f64,
    },
    /// Interpolation parameters do not match the points.
    #[error("{found} parameters for {expected} points")]
    ParamCount {
        /// The number of points.
        expected: usize,
        /// The number of parameters.
        found: usize,
    },
    /// Interpolation parameters are not strictly increasing.
    #[error("parameters must increase strictly: {value_} follows {previous_}", value_ = crate::num::Num(*.value), previous_ = crate::num::Num(*.previous))]
    ParamsNotIncreasing {
        /// Index of the offending parameter.
        index: usize,
        /// Its value.
        value: f64,
        /// The one before it.
        previous: f64,
    },
    /// An interpolation parameter is NaN or infinite.
    #[error("not a finite number ({value_})", value_ = crate::num::Num(*.value))]
    NonFiniteParam {
        /// Index of the offending parameter.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// The order of a B-spline is below 2.
    #[error("order {order} is below 2 (order = degree + 1)")]
    OrderTooLow {
        /// The order given.
        order: usize,
    },
    /// The knot count does not match `n + k`.
    #[error(
        "{found} knots for {points} control points of order {order}: expected n + k = {expected}"
    )]
    KnotCount {
        /// `n + k`.
        expected: usize,
        /// The count given.
        found: usize,
        /// `n`.
        points: usize,
        /// `k`.
        order: usize,
    },
    /// A knot is NaN or infinite.
    #[error("not a finite number ({value_})", value_ = crate::num::Num(*.value))]
    NonFiniteKnot {
        /// Index of the offending knot.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// Knots decrease.
    #[error("knots must not decrease: {value_} follows {previous_}", value_ = crate::num::Num(*.value), previous_ = crate::num::Num(*.previous))]
    KnotsDecreasing {
        /// Index of the offending knot.
        index: usize,
        /// Its value.
        value: f64,
        /// The knot before it.
        previous: f64,
    },
    /// A knot repeats too often.
    #[error("knot {value_} has multiplicity {multiplicity}; at most {max} allowed {}",
        if *interior { "inside the domain (order − 1 keeps the curve continuous)" } else { "at the domain's ends (the order)" }, value_ = crate::num::Num(*.value))]
    KnotMultiplicity {
        /// Index of the first copy over the limit.
        index: usize,
        /// The knot's value.
        value: f64,
        /// How many copies there are.
        multiplicity: usize,
        /// How many are allowed.
        max: usize,
        /// Whether the knot is strictly inside the domain.
        interior: bool,
    },
    /// The domain `[t_{k−1}, t_n]` is empty.
    #[error("the domain [t_(k-1), t_n] = [{start_}, {end_}] is empty", start_ = crate::num::Num(*.start), end_ = crate::num::Num(*.end))]
    EmptyDomain {
        /// `t_{k−1}`.
        start: f64,
        /// `t_n`.
        end: f64,
    },
    /// A knot to insert lies outside the domain.
    #[error("{value_} is outside the domain [{start_}, {end_}]", value_ = crate::num::Num(*.value), start_ = crate::num::Num(*.start), end_ = crate::num::Num(*.end))]
    KnotOutsideDomain {
        /// The knot.
        value: f64,
        /// The domain's start.
        start: f64,
        /// The domain's end.
        end: f64,
    },
    /// A control point index does not exist.
    #[error("control point {index} does not exist (the curve has {count})")]
    NoSuchPoint {
        /// The index given.
        index: usize,
        /// How many control points there are.
        count: usize,
    },
    /// A shape parameter group index does not exist.
    #[error("group {group} does not exist (groups 0..{groups})")]
    NoSuchGroup {
        /// The index given.
        group: usize,
        /// How many groups there are.
        groups: usize,
    },
    /// A shape parameter is addressed by a control point that is not in the group.
    #[error("control point {member} is not in group {group} (members: {members})")]
    NotInGroup {
        /// The group.
        group: usize,
        /// The control point index given.
        member: usize,
        /// The members, listed.
        members: String,
    },
    /// A group's values have the wrong count.
    #[error("group {group} has {expected} parameters, found {found} values")]
    GroupSize {
        /// The group.
        group: usize,
        /// Its size.
        expected: usize,
        /// The values given.
        found: usize,
    },
    /// A shape parameter is negative or not finite.
    #[error("shape parameter a^{member}_{group} = {value_} must be finite and ≥ 0", value_ = crate::num::Num(*.value))]
    NegativeParameter {
        /// The group.
        group: usize,
        /// The control point index.
        member: usize,
        /// The value.
        value: f64,
    },
    /// A group's parameters do not sum to 1.
    #[error("group {group} sums to {sum_}, not 1 (tolerance {tolerance:e})", sum_ = crate::num::Num(*.sum))]
    GroupSum {
        /// The group.
        group: usize,
        /// Its sum.
        sum: f64,
        /// The tolerance used.
        tolerance: f64,
    },
    /// A one-parameter edit asks for more than the two members hold together.
    #[error("a^{member}_{group} = {value_} is more than a^{member}_{group} + a^{absorber}_{group} = {pair_}: the absorbing a^{absorber}_{group} would become negative", value_ = crate::num::Num(*.value), pair_ = crate::num::Num(*.pair))]
    AbsorberNegative {
        /// The group.
        group: usize,
        /// The changed member.
        member: usize,
        /// The absorbing member.
        absorber: usize,
        /// The value asked for.
        value: f64,
        /// The two members' sum.
        pair: f64,
    },
    /// A one-parameter edit named the same member to change and to absorb.
    #[error("the absorbing member must differ from the changed one (both {member})")]
    SameAbsorber {
        /// The member.
        member: usize,
    },
    /// A group lies wholly outside the curve's domain (unclamped knots): its parameters do
    /// not change the curve and are kept at their standard values.
    #[error("group {group} does not affect the curve on its domain (unclamped knots)")]
    GroupOutsideDomain {
        /// The group.
        group: usize,
    },
    /// A parameter outside the curve's domain.
    #[error("{value_} is outside the domain [{start_}, {end_}]", value_ = crate::num::Num(*.value), start_ = crate::num::Num(*.start), end_ = crate::num::Num(*.end))]
    ParameterOutsideDomain {
        /// The parameter.
        value: f64,
        /// The domain's start.
        start: f64,
        /// The domain's end.
        end: f64,
    },
    /// A structural edit (inserting or removing a point) the curve cannot take.
    #[error("{family}: {reason}")]
    StructureRefused {
        /// The curve's family.
        family: &'static str,
        /// Why, in words.
        reason: String,
    },
    /// A rational curve with a weight count that differs from its point count.
    #[error("{weights} weights for {points} control points: one weight per point")]
    WeightCount {
        /// Weights given.
        weights: usize,
        /// Control points.
        points: usize,
    },
    /// A weight that is not a finite number greater than 0.
    #[error("weight {value} of point {index}: a weight must be a finite number greater than 0")]
    BadWeight {
        /// The point's index.
        index: usize,
        /// The weight.
        value: f64,
    },
    /// A path with no segment.
    #[error("a path needs at least one segment")]
    NoSegments,
    /// A path's segment that breaks a segment's rules (too few points, a non-finite
    /// coordinate, bad weights).
    #[error("segment {segment}: {error}")]
    InSegment {
        /// The segment's index.
        segment: usize,
        /// What is wrong with it.
        error: Box<GeomError>,
    },
    /// Consecutive segments of a path that do not share their end point (beyond rounding).
    #[error(
        "joint {joint} (the end of segment {joint}, the start of segment {next}): the two points are {} apart; consecutive segments must share their end point (a gap starts a new curve)",
        crate::num::Num(*gap)
    )]
    PathGap {
        /// The segment whose end does not meet the next one's start.
        joint: usize,
        /// The next segment (0 for a closed path's last joint).
        next: usize,
        /// The distance between the two points.
        gap: f64,
    },
    /// A panel control the curve does not have, or a value of the wrong kind for it.
    /// No longer made: the panel's controls live in the presentation layer, whose
    /// `splinescope_present::ControlError::Unknown` says this.
    #[deprecated(
        since = "0.1.0",
        note = "panel controls are the presentation layer's: splinescope_present::ControlError::Unknown"
    )]
    #[error("{family} curves have no control {control}")]
    UnknownControl {
        /// The curve's family.
        family: &'static str,
        /// The control and the value given.
        control: String,
    },
}

impl GeomError {
    /// [`GeomError::StructureRefused`]: a structural edit `family` does not allow.
    #[must_use]
    pub fn refused(family: &'static str, reason: impl Into<String>) -> GeomError {
        GeomError::StructureRefused {
            family,
            reason: reason.into(),
        }
    }

    /// The field this error concerns, relative to the curve (e.g. `points[2]`, `knots[5]`).
    #[must_use]
    #[allow(deprecated)] // the deprecated variant is matched, not made
    pub fn field(&self) -> String {
        match self {
            GeomError::TooFewPoints { .. } => "points".to_owned(),
            GeomError::DerivedNotFinite { field, .. } => (*field).to_owned(),
            GeomError::NonFinitePoint { index, .. } | GeomError::NoSuchPoint { index, .. } => {
                format!("points[{index}]")
            }
            GeomError::TStarOutside { .. } => "t_star".to_owned(),
            GeomError::NonFiniteVector { .. } => "v".to_owned(),
            GeomError::ParamCount { .. } => "params".to_owned(),
            GeomError::ParamsNotIncreasing { index, .. }
            | GeomError::NonFiniteParam { index, .. } => {
                format!("params[{index}]")
            }
            GeomError::OrderTooLow { .. } => "order".to_owned(),
            GeomError::WeightCount { .. } => "weights".to_owned(),
            GeomError::BadWeight { index, .. } => format!("weights[{index}]"),
            GeomError::KnotCount { .. } | GeomError::EmptyDomain { .. } => "knots".to_owned(),
            GeomError::NonFiniteKnot { index, .. }
            | GeomError::KnotsDecreasing { index, .. }
            | GeomError::KnotMultiplicity { index, .. } => format!("knots[{index}]"),
            GeomError::KnotOutsideDomain { .. } => "knots".to_owned(),
            GeomError::NoSuchGroup { .. }
            | GeomError::NotInGroup { .. }
            | GeomError::GroupSize { .. }
            | GeomError::NegativeParameter { .. }
            | GeomError::GroupSum { .. }
            | GeomError::SameAbsorber { .. }
            | GeomError::AbsorberNegative { .. }
            | GeomError::GroupOutsideDomain { .. } => "shape".to_owned(),
            GeomError::NoSegments | GeomError::PathGap { .. } => "segments".to_owned(),
            GeomError::InSegment { segment, error } => {
                let inner = error.field();
                if inner.is_empty() {
                    format!("segments[{segment}]")
                } else {
                    format!("segments[{segment}].{inner}")
                }
            }
            GeomError::ParameterOutsideDomain { .. }
            | GeomError::UnknownControl { .. }
            | GeomError::StructureRefused { .. } => String::new(),
        }
    }
}
