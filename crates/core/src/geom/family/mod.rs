//! What every curve family provides, behind one trait: [`Family`]. Each family implements
//! it in its own file here (`bezier.rs`, `modified.rs`, `interpolation.rs`, `bspline.rs`,
//! `nubmp.rs`, `rational.rs`), apart from its math file in `geom` (evaluation, lowering,
//! structure edits — no serde, no words for a person);
//! [`crate::geom::Curve`] dispatches to it, and the scene codec, `inspect`, the viewer's
//! panel and the solver requests go through [`crate::geom::Curve`] — nothing else matches
//! on the family. The README's "Adding a family" section lists the files a new one needs.

pub mod bezier;
pub mod bspline;
pub mod interpolation;
pub mod modified;
pub mod nubmp;
pub mod rational;

use glam::DVec3;
#[cfg(feature = "serde")]
use schemars::JsonSchema;
#[cfg(feature = "serde")]
use serde::Serialize;

use crate::geom::aabb::Aabb;
use crate::geom::{GeomError, Lower, ParamCurve};

/// What an overlay polyline shows, so that the renderer can style it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OverlayKind {
    /// The control polygon the user edits.
    ControlPolygon,
    /// The dual control polygon of a NUBMP curve (`P*_j`).
    DualPolygon,
    /// An interpolation piece's inner Bézier points, joined to its ends (tangent handles).
    TangentHandles,
    /// The vector `v` of a modified curve, drawn from `Q(t*)` to `R(t*) = Q(t*) + v`.
    BumpVector,
}

/// A polyline drawn over a curve to explain it (control polygon, dual polygon, …).
#[derive(Debug, Clone, PartialEq)]
pub struct OverlayPolyline {
    /// What it shows.
    pub kind: OverlayKind,
    /// Its vertices, in order.
    pub points: Vec<DVec3>,
}

/// A curve family: exact `f64` evaluation ([`ParamCurve`]), exact lowering to Bézier
/// segments ([`Lower`]), and what the editor, the reports and the drawing need.
pub trait Family: ParamCurve + Lower + Clone + std::fmt::Debug {
    /// The family's name as written in scene files (`"bezier"`, …).
    const NAME: &'static str;

    /// What `splinescope inspect` reports for this family beyond the common fields
    /// (`docs/inspect-format.md`).
    #[cfg(feature = "serde")]
    type Details: Serialize + JsonSchema;
    /// The family's own facts for `inspect`.
    #[cfg(not(feature = "serde"))]
    type Details;

    /// The points the user places (drawn as dots): control points, or the interpolated
    /// points.
    fn control_points(&self) -> &[DVec3];

    /// The same curve with new [`Family::control_points`] (same count); every other
    /// property (parameters, knots, shape parameters, `t*`, `v`) is kept.
    ///
    /// # Errors
    /// The family's own error when the points break it (non-finite values, derived values
    /// that overflow).
    fn with_control_points(&self, points: Vec<DVec3>) -> Result<Self, GeomError>;

    /// The polylines that explain the curve; by default its control polygon.
    fn overlays(&self) -> Vec<OverlayPolyline> {
        vec![OverlayPolyline {
            kind: OverlayKind::ControlPolygon,
            points: self.control_points().to_vec(),
        }]
    }

    /// A box holding the whole curve; by default the box of the control points (the
    /// convex-hull property).
    fn control_box(&self) -> Aabb {
        Aabb::from_points(self.control_points())
    }

    /// Whether every point of the curve has `z = 0`.
    fn is_planar(&self) -> bool {
        self.control_points().iter().all(|p| p.z == 0.0)
    }

    /// The input field that a non-finite derived value most likely comes from (`"points"`,
    /// `"knots"`; empty: the curve as a whole), for error paths.
    fn derived_field(&self) -> &'static str {
        "points"
    }

    /// One line describing the curve's structure for the panel ("degree 3", …).
    fn summary(&self) -> String;

    /// The curve's shape parameters as they are now, for labels that must not go stale
    /// when they are edited (`t* = 0.3, v = (1, 2)`; a NUBMP curve's parameters that
    /// differ from the standard curve's). `None` for families without parameters.
    fn parameter_text(&self) -> Option<String> {
        None
    }

    /// The family's derived data, as `inspect` reports it.
    ///
    /// # Errors
    /// [`GeomError::DerivedNotFinite`] when a derived structure overflows `f64`.
    fn details(&self) -> Result<Self::Details, GeomError>;

    /// What the structure allows at the parameter `τ` (the NUBMP regions of paper 001);
    /// `Ok(None)` for families without such a structure.
    ///
    /// # Errors
    /// [`GeomError::ParameterOutsideDomain`] for `τ` outside the domain; a derived
    /// structure that overflows.
    fn at_tau(&self, tau: f64) -> Result<Option<AtTau>, GeomError> {
        let _ = tau;
        Ok(None)
    }

    /// The panel's controls for this curve's own parameters, as data: the viewer draws
    /// them and applies changes through [`Family::apply_control`]; tests drive them the
    /// same way.
    fn controls(&self) -> Vec<Control> {
        Vec::new()
    }

    /// The curve with control `id` set to `value`.
    ///
    /// # Errors
    /// [`GeomError::UnknownControl`] for a control the curve does not have or a value of
    /// the wrong kind; otherwise the family's error for a value it refuses (nothing is
    /// clamped).
    fn apply_control(&self, id: ControlId, value: ControlValue) -> Result<Self, GeomError> {
        Err(unknown_control(Self::NAME, id, value))
    }

    /// Whether points are inserted by knot insertion at a curve parameter
    /// ([`Family::with_knot_inserted`]) rather than on the control polygon
    /// ([`Family::with_point_on_polygon`]).
    fn inserts_by_knot(&self) -> bool {
        false
    }

    /// The curve with a new control point `at`, placed on the control polygon's leg
    /// nearest to it; the curve and the new point's index ([`super::structure`]).
    ///
    /// # Errors
    /// [`GeomError::StructureRefused`] for families that insert by knot (the default),
    /// [`GeomError::NonFinitePoint`], or the family's own error.
    fn with_point_on_polygon(&self, at: DVec3) -> Result<(Self, usize), GeomError> {
        let _ = at;
        Err(GeomError::refused(
            Self::NAME,
            "points are inserted by knot insertion at a curve parameter",
        ))
    }

    /// The curve with the knot `t` inserted: one more control point and the same curve
    /// (Boehm).
    ///
    /// # Errors
    /// [`GeomError::StructureRefused`] for families that insert on the control polygon
    /// (the default); the knot vector's error for a `t` it refuses.
    fn with_knot_inserted(&self, t: f64) -> Result<Self, GeomError> {
        let _ = t;
        Err(GeomError::refused(
            Self::NAME,
            "points are inserted on the control polygon",
        ))
    }

    /// The curve without control point `index` ([`super::structure`] says how each
    /// family loses a point).
    ///
    /// # Errors
    /// [`GeomError::NoSuchPoint`], [`GeomError::StructureRefused`] (too few points left,
    /// shape parameters in the way) or the family's own error.
    fn with_point_removed(&self, index: usize) -> Result<Self, GeomError>;

    /// The starting curves the editor offers for this family (label and curve), centred
    /// on `center`, about `size` wide, in the plane `z = center.z`.
    fn templates(center: DVec3, size: f64) -> Vec<(&'static str, Self)>;

    /// A curve of this family for generated scenes (the stress scenes and the throughput
    /// benchmark) of `degree` (the family's own degree: a NUBMP curve lowers one higher),
    /// its control points drawn one after another from `point`.
    ///
    /// # Errors
    /// The family's error when the points break it (non-finite values).
    fn generated(degree: usize, point: &mut dyn FnMut() -> DVec3) -> Result<Self, GeomError>;
}

/// The error for a control a family does not have (or a value of the wrong kind).
#[must_use]
pub fn unknown_control(family: &'static str, id: ControlId, value: ControlValue) -> GeomError {
    GeomError::UnknownControl {
        family,
        control: format!("{id} = {value:?}"),
    }
}

/// Names one control of a curve: a key and up to two indices (`a^i_j` is `("a", [i, j])`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ControlId {
    /// What the control sets (`"t_star"`, `"v"`, `"a"`, `"elevate"`, …).
    pub key: &'static str,
    /// Indices, for controls that come in families (`[member, group]`); zeros otherwise.
    pub index: [usize; 2],
}

impl ControlId {
    /// A control without indices.
    #[must_use]
    pub const fn new(key: &'static str) -> ControlId {
        ControlId { key, index: [0, 0] }
    }
}

impl std::fmt::Display for ControlId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.index == [0, 0] {
            write!(f, "{}", self.key)
        } else {
            write!(f, "{}[{}, {}]", self.key, self.index[0], self.index[1])
        }
    }
}

/// A value given to a control.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ControlValue {
    /// For [`ControlKind::Number`].
    Number(f64),
    /// For [`ControlKind::Vector`].
    Vector(DVec3),
    /// For [`ControlKind::Toggle`].
    Toggle(bool),
    /// For [`ControlKind::Choice`]: the index of the option.
    Choice(usize),
    /// For [`ControlKind::Action`].
    Press,
}

/// What a control edits, and how.
#[derive(Debug, Clone, PartialEq)]
pub enum ControlKind {
    /// A number with a suggested range (typed values outside it are given to the family,
    /// which accepts or refuses them: never clamped).
    Number {
        /// The current value.
        value: f64,
        /// The slider's range.
        range: (f64, f64),
        /// The bands of values with a wanted property (a NUBMP parameter's
        /// variation-diminishing ranges), drawn on the slider; empty when there are none.
        bands: Vec<(f64, f64)>,
    },
    /// A vector.
    Vector {
        /// The current value.
        value: DVec3,
    },
    /// On or off.
    Toggle {
        /// The current value.
        value: bool,
    },
    /// One of several named options.
    Choice {
        /// The options' labels.
        options: Vec<&'static str>,
        /// The selected option's index.
        selected: usize,
    },
    /// A button.
    Action,
    /// Text only (what the structure is, a warning).
    Note {
        /// Whether the note warns (drawn in red).
        warning: bool,
    },
}

impl ControlKind {
    /// Whether a change through this control is one step on its own (a button, a toggle,
    /// a choice), rather than one of a stream of drags that undo merges.
    #[must_use]
    pub fn is_discrete(&self) -> bool {
        matches!(
            self,
            ControlKind::Toggle { .. } | ControlKind::Choice { .. } | ControlKind::Action
        )
    }
}

/// One of the panel's controls for a curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Control {
    /// Which control.
    pub id: ControlId,
    /// Its label (for a note, the text).
    pub label: String,
    /// A longer explanation shown on hover, or a range shown beside it.
    pub hint: Option<String>,
    /// What it edits.
    pub kind: ControlKind,
}

impl Control {
    /// The "elevate degree" button: the same curve with one more control point.
    #[must_use]
    pub fn elevate() -> Control {
        Control {
            id: ControlId::new("elevate"),
            label: "elevate degree".into(),
            hint: Some("the same curve with one more control point".into()),
            kind: ControlKind::Action,
        }
    }

    /// A text line.
    #[must_use]
    pub fn note(text: impl Into<String>, warning: bool) -> Control {
        Control {
            id: ControlId::new("note"),
            label: text.into(),
            hint: None,
            kind: ControlKind::Note { warning },
        }
    }
}

/// A point as reports write it: `[x, y, z]`.
pub type Xyz = [f64; 3];

/// Points as reports write them.
#[must_use]
pub fn xyz(points: &[DVec3]) -> Vec<Xyz> {
    points.iter().map(|p| p.to_array()).collect()
}

/// What a NUBMP curve (or a B-spline, as the standard NUBMP curve) allows at `τ` (paper
/// 001, §4): the point `P(τ)` and, per group whose dual B-spline is non-zero there, its
/// weight and the region `P(τ)` reaches by changing that group alone.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct AtTau {
    /// `τ`.
    pub tau: f64,
    /// `P(τ)`.
    pub point: Xyz,
    /// The groups that move `P(τ)`.
    pub groups: Vec<GroupAtTau>,
}

/// One group's reach at `τ`.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct GroupAtTau {
    /// The group `j`.
    pub group: usize,
    /// Its members `i` (control points `P_i`).
    pub members: Vec<usize>,
    /// `N*_j(τ)`.
    pub weight: f64,
    /// The vertices of the reachable region (segment, triangle, …).
    pub region: Vec<Xyz>,
}

/// A number for a label: at most four decimals, trailing zeros dropped (`0.3`, `1`,
/// `0.1255`).
#[must_use]
pub fn short_number(x: f64) -> String {
    crate::num::fixed(x, 4)
}

/// `t* = …, v = (…)` for the bump families (no z for a planar `v`).
pub(crate) fn bump_text(t_star: f64, v: DVec3) -> String {
    let n = short_number;
    if v.z == 0.0 {
        format!("t* = {}, v = ({}, {})", n(t_star), n(v.x), n(v.y))
    } else {
        format!(
            "t* = {}, v = ({}, {}, {})",
            n(t_star),
            n(v.x),
            n(v.y),
            n(v.z)
        )
    }
}
/// The control box of a curve bounded by its lowered pieces' control points.
pub(crate) fn lowered_box(curve: &impl Lower) -> Aabb {
    curve
        .lower()
        .iter()
        .fold(Aabb::EMPTY, |b, s| b.union(s.bezier.control_box()))
}
