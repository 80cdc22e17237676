//! [`Path`]'s words: its summary (segments, degrees, rational, closed), one control
//! polygon per segment, the template, and the `inspect` report (closed, each segment's
//! degree).

use glam::DVec3;
use schemars::JsonSchema;
use serde::Serialize;
use splinescope_core::geom::{Family, GeomError, Path, PathSegment};

use crate::Present;
use crate::controls::{ControlError, ControlId, ControlValue, unknown_control};
use splinescope_encoding::draw::OverlayPolyline;

impl Present for Path {
    type Details = PathDetails;

    fn overlays(&self) -> Vec<OverlayPolyline> {
        self.segments()
            .iter()
            .map(|s| OverlayPolyline::control_polygon(&s.points))
            .collect()
    }

    fn summary(&self) -> String {
        let segs = self.segments();
        let lo = segs.iter().map(PathSegment::degree).min().unwrap_or(0);
        let hi = segs.iter().map(PathSegment::degree).max().unwrap_or(0);
        let degrees = if lo == hi {
            format!("degree {lo}")
        } else {
            format!("degrees {lo}–{hi}")
        };
        let count = segs.len();
        let plural = if count == 1 { "" } else { "s" };
        let rational = if segs.iter().any(|s| s.weights.is_some()) {
            ", rational"
        } else {
            ""
        };
        let closed = if self.is_closed() { ", closed" } else { "" };
        format!("{count} segment{plural}, {degrees}{rational}{closed}")
    }

    fn details(&self) -> Result<PathDetails, GeomError> {
        Ok(PathDetails {
            closed: self.is_closed(),
            degrees: self.segments().iter().map(PathSegment::degree).collect(),
        })
    }

    fn apply_control(&self, id: ControlId, value: ControlValue) -> Result<Path, ControlError> {
        Err(unknown_control(Self::NAME, id, value))
    }

    /// A line, a quadratic and a cubic, joined.
    fn templates(center: DVec3, size: f64) -> Vec<(&'static str, Path)> {
        let p = |x: f64, y: f64| center + DVec3::new(x * size, y * size, 0.0);
        let segments = vec![
            PathSegment::polynomial(vec![p(-0.5, -0.2), p(-0.25, 0.2)]),
            PathSegment::polynomial(vec![p(-0.25, 0.2), p(-0.05, 0.45), p(0.1, 0.1)]),
            PathSegment::polynomial(vec![p(0.1, 0.1), p(0.2, -0.2), p(0.4, -0.3), p(0.5, 0.2)]),
        ];
        Path::try_new(segments, false)
            .map(|c| vec![("path", c)])
            .unwrap_or_default()
    }
}

/// What `inspect` reports for a path beyond its segments (which every report lists, with
/// their parameter ranges, points and weights).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct PathDetails {
    /// Whether the last segment ends where the first starts.
    pub closed: bool,
    /// Each segment's degree, in order (segment `k` covers `[k, k + 1]`).
    pub degrees: Vec<usize>,
}
