#![doc = include_str!("../README.md")]
#![forbid(unsafe_code)]

pub mod camera;
mod color;
pub mod draw;

pub use color::Color;

use glam::DVec3;
use splinescope_core::geom::{Aabb, BezierSegment};

use draw::{DrawList, Switches};

/// With automatic sampling, the largest distance between a segment and its polyline,
/// relative to the segment's control-box diagonal (2e-4: a fifth of a pixel when the
/// segment spans a thousand).
pub const AUTO_SAMPLES_TOLERANCE: f64 = 2e-4;
/// The most samples one segment may ask for.
pub const MAX_SAMPLES_PER_SEGMENT: u32 = 4096;

/// The automatic sample count of a Bézier segment: enough uniform samples that the
/// polyline stays within [`AUTO_SAMPLES_TOLERANCE`] of the segment, relative to its
/// control-box diagonal. From `|P(u) − polyline| ≤ h²/8 · max|P″|` with
/// `|P″| ≤ n(n−1) · max_i |P_{i+2} − 2P_{i+1} + P_i|` and `h = 1/(samples − 1)`, rounded up
/// to the ladder 2, 3, 4, 6, 8, 12, 16, 24, … (so that small edits keep the count and can be
/// written in place); between 2 (a straight segment) and [`MAX_SAMPLES_PER_SEGMENT`].
#[must_use]
pub fn auto_samples(points: &[glam::DVec3]) -> u32 {
    let n = points.len().saturating_sub(1);
    let size = Aabb::from_points(points).diagonal();
    if n < 2 || size == 0.0 {
        return 2;
    }
    let second = points
        .windows(3)
        .map(|w| (w[2] - 2.0 * w[1] + w[0]).length())
        .fold(0.0, f64::max);
    let bound = (n * (n - 1)) as f64 * second;
    let intervals = (bound / (8.0 * AUTO_SAMPLES_TOLERANCE * size))
        .sqrt()
        .ceil();
    let needed = (intervals + 1.0).clamp(2.0, f64::from(MAX_SAMPLES_PER_SEGMENT)) as u32;
    let mut rung = 2;
    while rung < needed {
        // 2, 3, 4, 6, 8, 12, …: alternately ×1.5 and ×4/3.
        rung = if rung.is_power_of_two() {
            rung + rung / 2
        } else {
            rung / 3 * 4
        };
    }
    rung.min(MAX_SAMPLES_PER_SEGMENT)
}

// A stroke's ends (`Cap`, SVG's `stroke-linecap`) and corners (`Join`, SVG's
// `stroke-linejoin`) are the core's own, which its offsets and stroke outlines take too.
use splinescope_core::ops;

/// Deprecated: a stroke's ends are `splinescope_core::ops::Cap`.
#[deprecated(note = "use splinescope_core::ops::Cap")]
pub type Cap = ops::Cap;
/// Deprecated: a stroke's corners are `splinescope_core::ops::Join`.
#[deprecated(note = "use splinescope_core::ops::Join")]
pub type Join = ops::Join;

/// The largest miter limit a stroke takes (a limit this long draws a spike 1,000 widths
/// long only where the stroke turns back by less than 0.12°).
pub const MAX_MITER_LIMIT: f64 = 1000.0;

/// A stroke's ends and corners: SVG's `stroke-linecap`, `stroke-linejoin` and
/// `stroke-miterlimit` (the ratio of a miter's length to the stroke's width past which
/// the corner is bevelled; at least 1, at most [`MAX_MITER_LIMIT`]; SVG's default 4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrokeShape {
    /// The ends of an open curve.
    pub cap: ops::Cap,
    /// The corners.
    pub join: ops::Join,
    /// The miter limit.
    pub miter_limit: f64,
}

impl Default for StrokeShape {
    /// Round ends and corners (what the renderer always drew), SVG's miter limit 4.
    fn default() -> StrokeShape {
        StrokeShape {
            cap: ops::Cap::Round,
            join: ops::Join::Round,
            miter_limit: 4.0,
        }
    }
}

impl StrokeShape {
    /// Whether this is the all-round shape (ends and corners drawn as discs).
    #[must_use]
    pub fn is_round(&self) -> bool {
        self.cap == ops::Cap::Round && self.join == ops::Join::Round
    }
}

/// One curve as drawn: its lowering and how it is stroked.
#[derive(Debug, Clone, PartialEq)]
pub struct EncodedCurve {
    /// Its exact Bézier segments (the family's lowering).
    pub segments: Vec<BezierSegment>,
    /// Fixed samples per segment, or `None` for counts chosen for the view.
    pub samples: Option<u32>,
    /// Its colour.
    pub color: Color,
    /// Its line width: pixels, or scene units when `width_in_scene`.
    pub width: f32,
    /// Whether `width` is in scene units.
    pub width_in_scene: bool,
    /// Its ends and corners.
    pub stroke: StrokeShape,
    /// Whether it ends where it starts as a closed curve (its ends then join, with no
    /// caps: a closed path).
    pub closed: bool,
}

/// A scene as drawn (see the module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct Encoding {
    /// Every curve, in the scene's order (drawn in that order).
    pub curves: Vec<EncodedCurve>,
    /// The overlays: polylines and point sets with their strokes, each curve's entries,
    /// the 3D axis triad's and the annotations'.
    pub overlays: DrawList,
    /// The overlay switches the overlays were drawn with.
    pub switches: Switches,
    /// Each annotation's points (their range is checked before drawing).
    pub annotations: Vec<Vec<DVec3>>,
    /// The clear colour.
    pub background: Color,
    /// The curvature comb of every curve, when drawn: the world length of a hair per unit
    /// of curvature (the hairs and their envelope are computed by the GPU every frame).
    pub comb: Option<f64>,
    /// The longest comb hair, in world units (`inf`: no cap); longer ones are cut to it.
    pub comb_cap: f64,
}
