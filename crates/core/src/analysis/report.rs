//! What `splinescope analyze` reports (and Python's `analyze`): per curve its length,
//! tight box, extrema, and for planar curves its inflections, cusps, curvature extrema and
//! (closed) signed area; with intersections, every intersecting pair and each curve's
//! self-intersections. Its JSON Schema, generated from these types, is
//! `docs/schemas/analyze.schema.json`.

#[cfg(feature = "serde")]
use schemars::JsonSchema;
#[cfg(feature = "serde")]
use serde::Serialize;

use super::curve::{AnalysisError, CurveAnalysis, ExtremumKind, HitKind};
use super::intersect::{Intersections, all_intersections};
use crate::geom::family::Xyz;
use glam::DVec3;

/// The whole output of `splinescope analyze`.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct AnalyzeOutput {
    /// The unit of length of the scene's coordinates, when its file names one (a STEP
    /// file's `millimetre`): every length, coordinate and area of the report is in it.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub unit: Option<String>,
    /// The accuracy lengths were computed to (absolute, scene units).
    pub accuracy: f64,
    /// One report per selected curve, in scene order.
    pub curves: Vec<CurveAnalysisReport>,
    /// With intersections asked for: every pair of selected curves that meet, `i < j`
    /// (absent otherwise).
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub intersections: Option<Vec<PairReport>>,
    /// With intersections asked for: the groups of selected curves that coincide entirely
    /// (copies: the same segments over the same domain), reported once per group rather
    /// than as pairs (absent otherwise).
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub copies: Option<Vec<CopiesReport>>,
}

/// Curves that coincide entirely.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct CopiesReport {
    /// The curves' indices in the scene, increasing.
    pub curves: Vec<usize>,
    /// The parameter interval they share (each curve's whole domain).
    pub t: [f64; 2],
}

/// One curve's answers.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct CurveAnalysisReport {
    /// The curve's index in the scene.
    pub index: usize,
    /// Its family.
    pub family: &'static str,
    /// Its name, when it has one.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub name: Option<String>,
    /// 2 for a planar curve (`z = 0` everywhere), 3 otherwise.
    pub dimension: usize,
    /// The parameter domain `[a, b]`.
    pub domain: [f64; 2],
    /// The arc length over the domain.
    pub length: f64,
    /// A bound on the length's error.
    pub length_error: f64,
    /// The tight axis-aligned box of the curve.
    pub bounding_box: BoxReport,
    /// Whether the curve ends where it starts.
    pub closed: bool,
    /// The signed area a closed planar curve encloses (positive counter-clockwise);
    /// absent for open or 3D curves.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub signed_area: Option<f64>,
    /// Where a coordinate's derivative vanishes.
    pub extrema: Vec<ExtremumReport>,
    /// Planar curves: where `C′ × C″` changes sign (absent for 3D curves).
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub inflections: Option<Vec<PointReport>>,
    /// Planar curves: where `C′ = 0`.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub cusps: Option<Vec<PointReport>>,
    /// Planar curves: the local extrema of the curvature's magnitude `|κ|`.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub curvature_extrema: Option<Vec<CurvatureReport>>,
    /// With intersections asked for, planar curves: where the curve meets itself.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub self_intersections: Option<IntersectionsReport>,
    /// The joints between its lowered segments, then a closed curve's seam: continuity
    /// at each (`docs/math.md` §9); absent where they cannot be measured in doubles
    /// (`joints_refused` says why).
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub joints: Option<Vec<JointReport>>,
    /// Why the joints are absent.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub joints_refused: Option<String>,
    /// With a point asked about: the curve's point nearest to it.
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub nearest: Option<NearestReport>,
}

/// The point of a curve nearest to a given one ([`CurveAnalysis::nearest`]).
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct NearestReport {
    /// The point asked about.
    pub to: Xyz,
    /// The curve parameter of the nearest point (the smallest among equally near ones).
    pub t: f64,
    /// The nearest point.
    pub point: Xyz,
    /// Its distance.
    pub distance: f64,
    /// A bound on how far `distance` may exceed the true least distance.
    pub error: f64,
}

impl NearestReport {
    /// The report of the point of `c` nearest to `to`.
    ///
    /// # Errors
    /// [`AnalysisError::NotFinitePoint`] for a point that is not finite.
    pub fn of(c: &CurveAnalysis, to: DVec3) -> Result<NearestReport, AnalysisError> {
        let n = c.nearest(to)?;
        Ok(NearestReport {
            to: to.to_array(),
            t: n.t,
            point: c.point(n.t).to_array(),
            distance: n.distance,
            error: n.error,
        })
    }
}

/// Continuity at one joint ([`crate::analysis::joints`]).
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct JointReport {
    /// The curve parameter.
    pub t: f64,
    /// The point.
    pub point: Xyz,
    /// `G2`, `G1`, `G0` (a kink) or `gap`.
    pub class: &'static str,
    /// The distance between the two ends that meet there.
    pub gap: f64,
    /// The angle between the tangents, in degrees (0 to 180).
    pub angle_deg: f64,
    /// The relative jump of the curvature vector, `|K⁻ − K⁺| / max(|K⁻|, |K⁺|)` (0 to
    /// 2); absent where a speed vanishes (the curvature is unbounded there).
    #[cfg_attr(feature = "serde", serde(skip_serializing_if = "Option::is_none"))]
    pub curvature_jump: Option<f64>,
    /// Whether this is a closed curve's seam.
    pub seam: bool,
}

/// An axis-aligned box.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct BoxReport {
    /// The smallest corner.
    pub min: Xyz,
    /// The largest corner.
    pub max: Xyz,
}

/// A parameter and its point.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct PointReport {
    /// The curve parameter.
    pub t: f64,
    /// The point.
    pub point: Xyz,
}

/// A coordinate extremum.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct ExtremumReport {
    /// The curve parameter.
    pub t: f64,
    /// The coordinate whose derivative vanishes: `x`, `y` or `z`.
    pub axis: &'static str,
    /// The point.
    pub point: Xyz,
}

/// A curvature extremum.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct CurvatureReport {
    /// The curve parameter.
    pub t: f64,
    /// The curvature's magnitude `|κ|` there (what `kind` is an extremum of).
    pub abs_curvature: f64,
    /// The signed curvature there (positive where the curve turns left).
    pub curvature: f64,
    /// Which way the curve turns there: `left` (`κ > 0`) or `right`.
    pub side: &'static str,
    /// `maximum` or `minimum` of `|κ|` (the sharpest point of a bend is a maximum,
    /// whichever way it turns).
    pub kind: &'static str,
    /// The point.
    pub point: Xyz,
}

/// Points and overlaps two curves (or one curve and itself) have in common.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct IntersectionsReport {
    /// The points.
    pub points: Vec<HitReport>,
    /// The coincident stretches.
    pub overlaps: Vec<OverlapReport>,
}

/// One intersection point.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct HitReport {
    /// The first curve's parameter.
    pub s: f64,
    /// The second curve's parameter.
    pub t: f64,
    /// The point.
    pub point: Xyz,
    /// `crossing` or `tangent`.
    pub kind: &'static str,
    /// A bound on the error of `s` (a crossing: the evaluations' rounding over the speed
    /// and the sine of the crossing angle; a tangency: its band).
    pub error_s: f64,
    /// A bound on the error of `t`.
    pub error_t: f64,
}

/// A coincident stretch.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct OverlapReport {
    /// The first curve's parameter interval.
    pub s: [f64; 2],
    /// The second curve's (`t[0]` meets `s[0]`).
    pub t: [f64; 2],
}

/// One intersecting pair.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
pub struct PairReport {
    /// The two curves' indices in the scene, `[i, j]` with `i < j`.
    pub curves: [usize; 2],
    /// What they have in common (`s` is curve `i`'s parameter).
    #[cfg_attr(feature = "serde", serde(flatten))]
    pub found: IntersectionsReport,
}

const AXES: [&str; 3] = ["x", "y", "z"];

impl From<&Intersections> for IntersectionsReport {
    fn from(found: &Intersections) -> IntersectionsReport {
        IntersectionsReport {
            points: found
                .hits
                .iter()
                .map(|h| HitReport {
                    s: h.s,
                    t: h.t,
                    point: h.point.to_array(),
                    kind: kind_name(h.kind),
                    error_s: h.error_s,
                    error_t: h.error_t,
                })
                .collect(),
            overlaps: found
                .overlaps
                .iter()
                .map(|o| OverlapReport {
                    s: [o.s.0, o.s.1],
                    t: [o.t.0, o.t.1],
                })
                .collect(),
        }
    }
}

/// `crossing` or `tangent`.
#[must_use]
pub fn kind_name(kind: HitKind) -> &'static str {
    match kind {
        HitKind::Crossing => "crossing",
        HitKind::Tangent => "tangent",
    }
}

/// `maximum` or `minimum`.
#[must_use]
pub fn extremum_name(kind: ExtremumKind) -> &'static str {
    match kind {
        ExtremumKind::Maximum => "maximum",
        ExtremumKind::Minimum => "minimum",
    }
}

/// One curve's report: `index` and `name` as given, the answers from `c`; its
/// self-intersections when `intersections` and the curve is planar.
///
/// # Errors
/// [`AnalysisError::Accuracy`] for an accuracy that is not a positive number.
pub fn curve_analysis_report(
    index: usize,
    family: &'static str,
    name: Option<&str>,
    c: &CurveAnalysis,
    accuracy: f64,
    intersections: bool,
) -> Result<CurveAnalysisReport, AnalysisError> {
    let (a, b) = c.domain();
    let length = c.length(a, b, accuracy)?;
    let bbox = c.bounding_box();
    let planar = c.is_planar();
    let closed = c.is_closed();
    let points = |ts: Vec<f64>| -> Vec<PointReport> {
        ts.into_iter()
            .map(|t| PointReport {
                t,
                point: c.point(t).to_array(),
            })
            .collect()
    };
    let (inflections, cusps, curvature_extrema, signed_area, self_intersections) = if planar {
        (
            Some(points(c.inflections()?)),
            Some(points(c.cusps()?)),
            Some(
                c.curvature_extrema()?
                    .into_iter()
                    .map(|e| CurvatureReport {
                        t: e.t,
                        abs_curvature: e.curvature.abs(),
                        curvature: e.curvature,
                        side: if e.curvature < 0.0 { "right" } else { "left" },
                        kind: extremum_name(e.kind),
                        point: e.point.to_array(),
                    })
                    .collect(),
            ),
            if closed { Some(c.signed_area()?) } else { None },
            if intersections {
                Some(IntersectionsReport::from(&c.self_intersections()?))
            } else {
                None
            },
        )
    } else {
        (None, None, None, None, None)
    };
    let joints = c.joints();
    Ok(CurveAnalysisReport {
        nearest: None,
        index,
        family,
        name: name.map(str::to_owned),
        dimension: if planar { 2 } else { 3 },
        domain: [a, b],
        length: length.value,
        length_error: length.error,
        bounding_box: BoxReport {
            min: bbox.min.to_array(),
            max: bbox.max.to_array(),
        },
        closed,
        signed_area,
        extrema: c
            .extrema()
            .into_iter()
            .map(|e| ExtremumReport {
                t: e.t,
                axis: AXES[e.axis],
                point: e.point.to_array(),
            })
            .collect(),
        inflections,
        cusps,
        curvature_extrema,
        self_intersections,
        joints: joints.as_ref().ok().map(|joints| {
            joints
                .iter()
                .map(|j| JointReport {
                    t: j.t,
                    point: j.point.to_array(),
                    class: j.class.name(),
                    gap: j.gap,
                    angle_deg: j.angle.to_degrees(),
                    curvature_jump: j.curvature_jump.is_finite().then_some(j.curvature_jump),
                    seam: j.seam,
                })
                .collect()
        }),
        joints_refused: joints.err().map(|e| e.to_string()),
    })
}

/// Every intersecting pair among the curves (scene indices `indices`), as reported.
///
/// # Errors
/// [`AnalysisError::NotPlanar`] when a curve is 3D.
pub fn pair_reports(
    indices: &[usize],
    curves: &[CurveAnalysis],
) -> Result<(Vec<PairReport>, Vec<CopiesReport>), AnalysisError> {
    let all = all_intersections(curves)?;
    let pairs = all
        .pairs
        .iter()
        .map(|p| PairReport {
            curves: [indices[p.i], indices[p.j]],
            found: IntersectionsReport::from(&p.found),
        })
        .collect();
    let copies = all
        .copies
        .iter()
        .map(|g| CopiesReport {
            curves: g.curves.iter().map(|&i| indices[i]).collect(),
            t: [g.domain.0, g.domain.1],
        })
        .collect();
    Ok((pairs, copies))
}
