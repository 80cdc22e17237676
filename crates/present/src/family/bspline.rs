//! [`BSpline`]'s words: its summary, the template, and the `inspect` report — the
//! structure of the standard NUBMP curve on its knots (paper 001 §2).

use glam::DVec3;
use schemars::JsonSchema;
use serde::Serialize;
use splinescope_core::geom::{BSpline, GeomError};

use splinescope_core::geom::Family;

use crate::Present;
use crate::controls::{ControlError, ControlId, ControlValue, unknown_control};
use crate::family::nubmp::{NubmpDetails, NubmpStructure, SplineDetails};
use splinescope_encoding::draw::OverlayPolyline;

impl Present for BSpline {
    type Details = BSplineDetails;

    fn templates(center: DVec3, size: f64) -> Vec<(&'static str, BSpline)> {
        let points = crate::template::zigzag(center, size, 6);
        BSpline::try_new(points, crate::template::clamped_knots(6, 4), 4)
            .map(|b| vec![("B-spline (cubic)", b)])
            .unwrap_or_default()
    }

    fn overlays(&self) -> Vec<OverlayPolyline> {
        vec![OverlayPolyline::control_polygon(self.points())]
    }

    fn summary(&self) -> String {
        format!(
            "order {}, knots {}",
            self.order(),
            splinescope_core::geom::knots::knots_text(self.knots().knots())
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

    /// A B-spline has no controls of its own (its points are dragged, its knots typed).
    fn apply_control(&self, id: ControlId, value: ControlValue) -> Result<BSpline, ControlError> {
        Err(unknown_control(Self::NAME, id, value))
    }
}

/// What `inspect` reports for a B-spline: the structure of the standard NUBMP curve on its
/// knots.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[serde(transparent)]
pub struct BSplineDetails(pub NubmpDetails);
