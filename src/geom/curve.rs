//! The closed set of curve families splinescope draws, behind one enum.

use glam::DVec3;

use super::{
    Aabb, BSpline, Bezier, BezierSegment, CubicInterpolation, GeomError, Lower, ModifiedBezier,
    Nubmp, ParamCurve,
};

/// Every curve family splinescope knows. Each one evaluates exactly in `f64`
/// ([`ParamCurve`]) and lowers exactly to Bézier segments ([`Lower`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Curve {
    /// A Bézier curve of any degree (all papers).
    Bezier(Bezier),
    /// `R(t) = Q(t) + S(t) v` (paper 002, §4).
    Modified(ModifiedBezier),
    /// Cubic Bézier interpolation, plain or modified (paper 002, §5).
    Interpolation(CubicInterpolation),
    /// A non-uniform B-spline of any order (paper 001, §2).
    BSpline(BSpline),
    /// A B-spline with multiple shape parameters (paper 001, §3–5).
    Nubmp(Nubmp),
}

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

/// Calls `$body` with `$c` bound to the family inside a [`Curve`].
macro_rules! each_family {
    ($curve:expr, $c:ident => $body:expr) => {
        match $curve {
            Curve::Bezier($c) => $body,
            Curve::Modified($c) => $body,
            Curve::Interpolation($c) => $body,
            Curve::BSpline($c) => $body,
            Curve::Nubmp($c) => $body,
        }
    };
}

impl Curve {
    /// Checks the values derived from the input: every control point of the lowering
    /// (interpolation tangents and inner points, B-spline extraction, NUBMP dual points)
    /// must be a finite number, or the curve is refused with what overflowed. Scenes run
    /// this on every curve they load and every edit they accept, so nothing downstream
    /// (evaluation, drawing, reports) meets a non-finite value.
    ///
    /// # Errors
    /// [`GeomError::DerivedNotFinite`] naming the segment and point.
    pub fn check_derived(&self) -> Result<(), GeomError> {
        // The input the overflow most likely comes from; interpolation tangents depend on
        // points and parameters alike, so the curve itself is named.
        let field = match self {
            Curve::Interpolation(_) => "",
            Curve::BSpline(_) | Curve::Nubmp(_) => "knots",
            _ => "points",
        };
        for (s, seg) in self.lower().iter().enumerate() {
            for (j, p) in seg.bezier.points().iter().enumerate() {
                if let Some(&value) = p.to_array().iter().find(|v| !v.is_finite()) {
                    return Err(GeomError::DerivedNotFinite {
                        field,
                        what: format!("control point {j} of lowered Bézier segment {s}"),
                        value,
                    });
                }
            }
            if !(seg.t0.is_finite() && seg.t1.is_finite()) {
                return Err(GeomError::DerivedNotFinite {
                    field,
                    what: format!("the parameter range of lowered Bézier segment {s}"),
                    value: if seg.t0.is_finite() { seg.t1 } else { seg.t0 },
                });
            }
        }
        Ok(())
    }

    /// The family's name as written in scene files (`"bezier"`, …).
    #[must_use]
    pub fn family(&self) -> &'static str {
        match self {
            Curve::Bezier(_) => "bezier",
            Curve::Modified(_) => "modified_bezier",
            Curve::Interpolation(_) => "interpolation",
            Curve::BSpline(_) => "bspline",
            Curve::Nubmp(_) => "nubmp",
        }
    }

    /// The points the user places (drawn as dots): control points, or the interpolated
    /// points.
    #[must_use]
    pub fn control_points(&self) -> &[DVec3] {
        match self {
            Curve::Bezier(b) => b.points(),
            Curve::Modified(m) => m.base().points(),
            Curve::Interpolation(c) => c.points(),
            Curve::BSpline(b) => b.points(),
            Curve::Nubmp(n) => n.points(),
        }
    }

    /// The same curve with control point `index` (as listed by [`Curve::control_points`])
    /// moved to `p`; every other property (parameters, knots, shape parameters, `t*`, `v`)
    /// is kept.
    ///
    /// # Errors
    /// [`GeomError::NoSuchPoint`] for an index out of range, [`GeomError::NonFinitePoint`]
    /// for a non-finite `p`, or the family's own error when the moved point breaks it.
    pub fn with_control_point(&self, index: usize, p: DVec3) -> Result<Curve, GeomError> {
        let count = self.control_points().len();
        if index >= count {
            return Err(GeomError::NoSuchPoint { index, count });
        }
        let mut pts = self.control_points().to_vec();
        pts[index] = p;
        crate::geom::bezier::check_finite(&pts)?;
        Ok(match self {
            Curve::Bezier(_) => Curve::Bezier(Bezier::new(pts)),
            Curve::Modified(m) => Curve::Modified(ModifiedBezier::try_new(
                Bezier::new(pts),
                m.t_star(),
                m.v(),
            )?),
            Curve::Interpolation(c) => Curve::Interpolation(CubicInterpolation::try_new(
                pts,
                Some(c.params().to_vec()),
                c.modification(),
            )?),
            Curve::BSpline(b) => Curve::BSpline(BSpline::from_parts(pts, b.knots().clone())?),
            Curve::Nubmp(n) => Curve::Nubmp(n.with_points(pts)?),
        })
    }

    /// The polylines that explain the curve: its control polygon, and per family more
    /// (the dual polygon, tangent handles, the bump vector).
    #[must_use]
    pub fn overlays(&self) -> Vec<OverlayPolyline> {
        let polygon = |points: &[DVec3]| OverlayPolyline {
            kind: OverlayKind::ControlPolygon,
            points: points.to_vec(),
        };
        match self {
            Curve::Bezier(b) => vec![polygon(b.points())],
            Curve::BSpline(b) => vec![polygon(b.points())],
            Curve::Modified(m) => {
                let q = m.base().eval(m.t_star());
                vec![
                    polygon(m.base().points()),
                    OverlayPolyline {
                        kind: OverlayKind::BumpVector,
                        points: vec![q, q + m.v()],
                    },
                ]
            }
            Curve::Interpolation(c) => c
                .pieces()
                .iter()
                .map(|p| OverlayPolyline {
                    kind: OverlayKind::TangentHandles,
                    points: p.points().to_vec(),
                })
                .collect(),
            Curve::Nubmp(n) => vec![
                polygon(n.points()),
                OverlayPolyline {
                    kind: OverlayKind::DualPolygon,
                    points: n.dual_points().to_vec(),
                },
            ],
        }
    }

    /// A box holding the whole curve. Bézier, B-spline and NUBMP curves lie in the convex
    /// hull of their control points; the modified and interpolating curves are bounded by
    /// their lowered pieces' control points.
    #[must_use]
    pub fn control_box(&self) -> Aabb {
        match self {
            Curve::Modified(_) | Curve::Interpolation(_) => self
                .lower()
                .iter()
                .fold(Aabb::EMPTY, |b, s| b.union(s.bezier.control_box())),
            _ => Aabb::from_points(self.control_points()),
        }
    }

    /// Whether every point has `z = 0`.
    #[must_use]
    pub fn is_planar(&self) -> bool {
        let planar = |pts: &[DVec3]| pts.iter().all(|p| p.z == 0.0);
        match self {
            Curve::Modified(m) => planar(m.base().points()) && m.v().z == 0.0,
            Curve::Interpolation(c) => {
                planar(c.points()) && c.modification().is_none_or(|m| m.v.z == 0.0)
            }
            _ => planar(self.control_points()),
        }
    }
}

impl ParamCurve for Curve {
    fn domain(&self) -> (f64, f64) {
        each_family!(self, c => c.domain())
    }
    fn eval(&self, t: f64) -> DVec3 {
        each_family!(self, c => ParamCurve::eval(c, t))
    }
    fn eval_deriv(&self, t: f64) -> DVec3 {
        each_family!(self, c => ParamCurve::eval_deriv(c, t))
    }
    fn eval_second_deriv(&self, t: f64) -> DVec3 {
        each_family!(self, c => ParamCurve::eval_second_deriv(c, t))
    }
}

impl Lower for Curve {
    fn lower(&self) -> Vec<BezierSegment> {
        each_family!(self, c => c.lower())
    }
}
