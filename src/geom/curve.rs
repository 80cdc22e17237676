//! The closed set of curve families splinescope draws, behind one enum.

use glam::DVec3;

use super::{Aabb, Bezier, BezierSegment, Lower, ParamCurve};

/// Every curve family splinescope knows. Each one evaluates exactly in `f64`
/// ([`ParamCurve`]) and lowers exactly to Bézier segments ([`Lower`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Curve {
    /// A Bézier curve of any degree (see [`Bezier`]).
    Bezier(Bezier),
}

/// What an overlay polyline shows, so that the renderer can style it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OverlayKind {
    /// The control polygon the user edits.
    ControlPolygon,
}

/// A polyline drawn over a curve to explain it (control polygon, dual polygon, …).
#[derive(Debug, Clone, PartialEq)]
pub struct OverlayPolyline {
    /// What it shows.
    pub kind: OverlayKind,
    /// Its vertices, in order.
    pub points: Vec<DVec3>,
}

impl Curve {
    /// The family's name as written in scene files (`"bezier"`, …).
    #[must_use]
    pub fn family(&self) -> &'static str {
        match self {
            Curve::Bezier(_) => "bezier",
        }
    }

    /// The control points the user places (drawn as dots).
    #[must_use]
    pub fn control_points(&self) -> &[DVec3] {
        match self {
            Curve::Bezier(b) => b.points(),
        }
    }

    /// The polylines that explain the curve: its control polygon, and per family more.
    #[must_use]
    pub fn overlays(&self) -> Vec<OverlayPolyline> {
        vec![OverlayPolyline {
            kind: OverlayKind::ControlPolygon,
            points: self.control_points().to_vec(),
        }]
    }

    /// A box holding the whole curve (the control points' box: the curve lies in their
    /// convex hull for every family here).
    #[must_use]
    pub fn control_box(&self) -> Aabb {
        Aabb::from_points(self.control_points())
    }

    /// Whether every point has `z = 0`.
    #[must_use]
    pub fn is_planar(&self) -> bool {
        self.control_points().iter().all(|p| p.z == 0.0)
    }
}

impl ParamCurve for Curve {
    fn domain(&self) -> (f64, f64) {
        match self {
            Curve::Bezier(b) => b.domain(),
        }
    }
    fn eval(&self, t: f64) -> DVec3 {
        match self {
            Curve::Bezier(b) => b.eval(t),
        }
    }
    fn eval_deriv(&self, t: f64) -> DVec3 {
        match self {
            Curve::Bezier(b) => b.eval_deriv(t),
        }
    }
    fn eval_second_deriv(&self, t: f64) -> DVec3 {
        match self {
            Curve::Bezier(b) => b.eval_second_deriv(t),
        }
    }
}

impl Lower for Curve {
    fn lower(&self) -> Vec<BezierSegment> {
        match self {
            Curve::Bezier(b) => b.lower(),
        }
    }
}
