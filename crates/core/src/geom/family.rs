//! What every curve family provides, behind one trait: [`Family`] — its control points
//! and what replacing them means, the polylines that explain it, its box, its structure
//! edits, the curves generated for stress scenes. Each family implements it at the end of
//! its math file (`bezier.rs`, `modified.rs`, `interpolation.rs`, `bspline.rs`,
//! `nubmp.rs`, `rational.rs`); no serde, no words for a person — those are in the
//! presentation layer above core. [`crate::geom::Curve`] dispatches to it, and the scene
//! codec, the reports, the viewer's panel and the solver requests go through
//! [`crate::geom::Curve`] — nothing else matches on the family. The README's "Adding a
//! family" section lists the files a new one needs.

use glam::DVec3;
#[cfg(feature = "serde")]
use schemars::JsonSchema;
#[cfg(feature = "serde")]
use serde::Serialize;

use crate::geom::aabb::Aabb;
use crate::geom::{GeomError, Lower, ParamCurve};

/// A curve family: exact `f64` evaluation ([`ParamCurve`]), exact lowering to Bézier
/// segments ([`Lower`]), and what the editor and the drawing need of its structure.
pub trait Family: ParamCurve + Lower + Clone + std::fmt::Debug {
    /// The family's name as written in scene files (`"bezier"`, …).
    const NAME: &'static str;

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

    /// A curve of this family for generated scenes (the stress scenes and the throughput
    /// benchmark) of `degree` (the family's own degree: a NUBMP curve lowers one higher),
    /// its control points drawn one after another from `point`.
    ///
    /// # Errors
    /// The family's error when the points break it (non-finite values).
    fn generated(degree: usize, point: &mut dyn FnMut() -> DVec3) -> Result<Self, GeomError>;
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

/// The control box of a curve bounded by its lowered pieces' control points.
pub(crate) fn lowered_box(curve: &impl Lower) -> Aabb {
    curve
        .lower()
        .iter()
        .fold(Aabb::EMPTY, |b, s| b.union(s.bezier.control_box()))
}
