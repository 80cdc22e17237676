//! The closed set of curve families splinescope draws, behind one enum.

use glam::DVec3;

use schemars::JsonSchema;
use serde::Serialize;

use super::bezier::BezierDetails;
use super::family::{AtTau, Control, ControlId, ControlValue, Family, OverlayPolyline};
use super::interp::InterpolationDetails;
use super::modified::ModifiedDetails;
use super::nubmp::{BSplineDetails, NubmpDetails};
use super::{
    Aabb, BSpline, Bezier, BezierSegment, CubicInterpolation, GeomError, Lower, ModifiedBezier,
    Nubmp, ParamCurve,
};

/// Every curve family splinescope knows. Each one implements [`Family`] in its own file:
/// it evaluates exactly in `f64` ([`ParamCurve`]), lowers exactly to Bézier segments
/// ([`Lower`]) and describes its overlays, reports and panel controls. This enum and its
/// dispatch macro are the only places that list the families.
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

/// The per-family part of an `inspect` report (flattened into the curve's object).
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[serde(untagged)]
pub enum FamilyDetails {
    /// A Bézier curve.
    Bezier(BezierDetails),
    /// A modified Bézier curve.
    Modified(ModifiedDetails),
    /// An interpolating spline.
    Interpolation(InterpolationDetails),
    /// A B-spline (with the structure of the standard NUBMP curve on its knots).
    BSpline(BSplineDetails),
    /// A NUBMP curve.
    Nubmp(NubmpDetails),
}

impl From<BezierDetails> for FamilyDetails {
    fn from(d: BezierDetails) -> FamilyDetails {
        FamilyDetails::Bezier(d)
    }
}

impl From<ModifiedDetails> for FamilyDetails {
    fn from(d: ModifiedDetails) -> FamilyDetails {
        FamilyDetails::Modified(d)
    }
}

impl From<InterpolationDetails> for FamilyDetails {
    fn from(d: InterpolationDetails) -> FamilyDetails {
        FamilyDetails::Interpolation(d)
    }
}

impl From<BSplineDetails> for FamilyDetails {
    fn from(d: BSplineDetails) -> FamilyDetails {
        FamilyDetails::BSpline(d)
    }
}

impl From<NubmpDetails> for FamilyDetails {
    fn from(d: NubmpDetails) -> FamilyDetails {
        FamilyDetails::Nubmp(d)
    }
}

/// Calls `$body` with `$c` bound to the family inside a [`Curve`] (for the layers above,
/// which dispatch one generic call over every family the same way).
#[doc(hidden)]
#[macro_export]
macro_rules! each_family {
    ($curve:expr, $c:ident => $body:expr) => {
        match $curve {
            $crate::geom::Curve::Bezier($c) => $body,
            $crate::geom::Curve::Modified($c) => $body,
            $crate::geom::Curve::Interpolation($c) => $body,
            $crate::geom::Curve::BSpline($c) => $body,
            $crate::geom::Curve::Nubmp($c) => $body,
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
        // The input the overflow most likely comes from.
        let field = each_family!(self, c => c.derived_field());
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

    /// The family's name as written in scene files (`"bezier"`, …): [`Family::NAME`].
    #[must_use]
    pub fn family(&self) -> &'static str {
        fn name<F: Family>(_: &F) -> &'static str {
            F::NAME
        }
        each_family!(self, c => name(c))
    }

    /// Every family's name ([`Family::NAME`]), in the order of the variants: what the
    /// layers above check their own lists against (the scene codecs, the schema, the
    /// viewer's templates).
    pub const FAMILY_NAMES: [&'static str; 5] = [
        Bezier::NAME,
        ModifiedBezier::NAME,
        CubicInterpolation::NAME,
        BSpline::NAME,
        Nubmp::NAME,
    ];

    /// The variant's position in [`Curve::FAMILY_NAMES`] (an exhaustive match: a new
    /// variant does not compile until it has a place there).
    #[must_use]
    pub fn family_index(&self) -> usize {
        match self {
            Curve::Bezier(_) => 0,
            Curve::Modified(_) => 1,
            Curve::Interpolation(_) => 2,
            Curve::BSpline(_) => 3,
            Curve::Nubmp(_) => 4,
        }
    }

    /// The points the user places (drawn as dots): [`Family::control_points`].
    #[must_use]
    pub fn control_points(&self) -> &[DVec3] {
        each_family!(self, c => c.control_points())
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
        self.with_control_points(pts)
    }

    /// The same curve with every [`Curve::control_points`] replaced (same count); every
    /// other property is kept.
    ///
    /// # Errors
    /// [`GeomError::NonFinitePoint`] for a non-finite point, or the family's own error.
    pub fn with_control_points(&self, pts: Vec<DVec3>) -> Result<Curve, GeomError> {
        crate::geom::bezier::check_finite(&pts)?;
        each_family!(self, c => c.with_control_points(pts).map(Into::into))
    }

    /// The polylines that explain the curve: [`Family::overlays`].
    #[must_use]
    pub fn overlays(&self) -> Vec<OverlayPolyline> {
        each_family!(self, c => c.overlays())
    }

    /// A box holding the whole curve: [`Family::control_box`].
    #[must_use]
    pub fn control_box(&self) -> Aabb {
        each_family!(self, c => c.control_box())
    }

    /// Whether every point has `z = 0`.
    #[must_use]
    pub fn is_planar(&self) -> bool {
        each_family!(self, c => c.is_planar())
    }

    /// One line describing the curve's structure: [`Family::summary`].
    #[must_use]
    pub fn summary(&self) -> String {
        each_family!(self, c => c.summary())
    }

    /// The shape parameters as they are now: [`Family::parameter_text`].
    #[must_use]
    pub fn parameter_text(&self) -> Option<String> {
        each_family!(self, c => c.parameter_text())
    }

    /// The family's derived data for `inspect`: [`Family::details`].
    ///
    /// # Errors
    /// A derived structure that overflows `f64`.
    pub fn details(&self) -> Result<FamilyDetails, GeomError> {
        each_family!(self, c => c.details().map(Into::into))
    }

    /// What the structure allows at `τ`: [`Family::at_tau`].
    ///
    /// # Errors
    /// `τ` outside the domain, or a derived structure that overflows.
    pub fn at_tau(&self, tau: f64) -> Result<Option<AtTau>, GeomError> {
        each_family!(self, c => c.at_tau(tau))
    }

    /// The panel's controls: [`Family::controls`].
    #[must_use]
    pub fn controls(&self) -> Vec<Control> {
        each_family!(self, c => c.controls())
    }

    /// The curve with a control changed: [`Family::apply_control`].
    ///
    /// # Errors
    /// An unknown control, or a value the family refuses.
    pub fn apply_control(&self, id: ControlId, value: ControlValue) -> Result<Curve, GeomError> {
        each_family!(self, c => c.apply_control(id, value).map(Into::into))
    }
}

/// Each family converts into the enum.
macro_rules! into_curve {
    ($($family:ident => $variant:ident),* $(,)?) => {
        $(impl From<$family> for Curve {
            fn from(c: $family) -> Curve {
                Curve::$variant(c)
            }
        })*
    };
}

into_curve!(
    Bezier => Bezier,
    ModifiedBezier => Modified,
    CubicInterpolation => Interpolation,
    BSpline => BSpline,
    Nubmp => Nubmp,
);

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
