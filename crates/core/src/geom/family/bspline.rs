//! [`BSpline`]'s [`Family`] side: knot and order controls, templates, and the `inspect`
//! report — the structure of the standard NUBMP curve on its knots (paper 001 §2).

use glam::DVec3;
#[cfg(feature = "serde")]
use schemars::JsonSchema;
#[cfg(feature = "serde")]
use serde::Serialize;

use super::nubmp::{NubmpDetails, NubmpStructure, SplineDetails, nubmp_at_tau};
use super::{AtTau, Family};
use crate::geom::{BSpline, GeomError, KnotVector};

// The B-spline as a family: it is the standard NUBMP curve on its knots (paper 001, §3),
// so its report and its `at_tau` are that curve's.

impl Family for BSpline {
    const NAME: &'static str = "bspline";
    type Details = BSplineDetails;

    fn inserts_by_knot(&self) -> bool {
        true
    }

    fn with_knot_inserted(&self, t: f64) -> Result<BSpline, GeomError> {
        self.insert_knot(t)
    }

    fn with_point_removed(&self, index: usize) -> Result<BSpline, GeomError> {
        let (points, knots) =
            crate::geom::structure::spline_without(self.points(), self.knots(), index, Self::NAME)?;
        BSpline::try_new(points, knots, self.order())
    }

    fn templates(center: DVec3, size: f64) -> Vec<(&'static str, BSpline)> {
        let points = crate::geom::template::zigzag(center, size, 6);
        BSpline::try_new(points, crate::geom::template::clamped_knots(6, 4), 4)
            .map(|b| vec![("B-spline (cubic)", b)])
            .unwrap_or_default()
    }

    /// The clamped uniform B-spline of order `degree + 1` on `degree + 4` points: four
    /// Bézier segments of `degree`.
    fn generated(degree: usize, point: &mut dyn FnMut() -> DVec3) -> Result<BSpline, GeomError> {
        let points: Vec<DVec3> = (0..degree + 4).map(|_| point()).collect();
        let knots = KnotVector::clamped_uniform(degree + 1, points.len())?;
        BSpline::from_parts(points, knots)
    }

    fn control_points(&self) -> &[DVec3] {
        self.points()
    }

    fn with_control_points(&self, points: Vec<DVec3>) -> Result<BSpline, GeomError> {
        BSpline::from_parts(points, self.knots().clone())
    }

    fn derived_field(&self) -> &'static str {
        "knots"
    }

    fn summary(&self) -> String {
        format!(
            "order {}, knots {}",
            self.order(),
            crate::geom::knots::knots_text(self.knots().knots())
        )
    }

    /// A B-spline is the standard NUBMP curve on its knots: that structure is reported.
    fn details(&self) -> Result<BSplineDetails, GeomError> {
        let standard = self.standard_nubmp()?;
        Ok(BSplineDetails(NubmpDetails {
            spline: SplineDetails::of(self.knots()),
            structure: NubmpStructure::of(&standard),
        }))
    }

    fn at_tau(&self, tau: f64) -> Result<Option<AtTau>, GeomError> {
        nubmp_at_tau(&self.standard_nubmp()?, tau).map(Some)
    }
}

/// What `inspect` reports for a B-spline: the structure of the standard NUBMP curve on its
/// knots.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
#[cfg_attr(feature = "serde", serde(transparent))]
pub struct BSplineDetails(pub NubmpDetails);
