//! The derived data of each curve (`splinescope inspect`): its Bézier segments and, per
//! family, what the papers define on it ([`crate::Present::details`]). The format is
//! documented in `docs/inspect-format.md`; its JSON Schema, generated from these types, is
//! `docs/schemas/inspect.schema.json`.

use schemars::JsonSchema;
use serde::Serialize;

use splinescope_core::geom::{AtTau, Curve, GeomError, Lower, ParamCurve, Xyz, xyz};

use crate::{FamilyDetails, Present};

/// The whole output of `splinescope inspect`.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct InspectOutput {
    /// One report per selected curve, in scene order.
    pub curves: Vec<CurveReport>,
}

/// The report of one curve.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct CurveReport {
    /// The curve's index in the scene.
    pub index: usize,
    /// Its family (`"bezier"`, …).
    pub family: &'static str,
    /// Its name, when it has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The parameter domain `[a, b]`.
    pub domain: [f64; 2],
    /// The exact lowering: Bézier segments with their parameter ranges.
    pub segments: Vec<SegmentReport>,
    /// The family's own data.
    #[serde(flatten)]
    pub details: FamilyDetails,
    /// With `--tau`, for B-splines and NUBMP curves: what the structure allows there.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at_tau: Option<AtTau>,
}

/// One Bézier segment of a lowering.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct SegmentReport {
    /// The curve parameter where the segment starts.
    pub t0: f64,
    /// Where it ends.
    pub t1: f64,
    /// Its degree.
    pub degree: usize,
    /// Its control points.
    pub points: Vec<Xyz>,
    /// A rational segment's weights (absent for a polynomial one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<f64>>,
}

/// The report of one curve (without `at_tau`).
///
/// # Errors
/// A B-spline whose standard NUBMP structure overflows `f64`
/// ([`GeomError::DerivedNotFinite`]).
pub fn curve_report(
    index: usize,
    name: Option<&str>,
    curve: &Curve,
) -> Result<CurveReport, GeomError> {
    let (a, b) = curve.domain();
    Ok(CurveReport {
        index,
        family: curve.family(),
        name: name.map(str::to_owned),
        domain: [a, b],
        segments: curve
            .lower()
            .iter()
            .map(|s| SegmentReport {
                t0: s.t0,
                t1: s.t1,
                degree: s.bezier.degree(),
                points: xyz(s.bezier.points()),
                weights: s.weights.clone(),
            })
            .collect(),
        details: curve.details()?,
        at_tau: None,
    })
}
