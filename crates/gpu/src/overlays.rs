//! Packing the scene's draw list ([`crate::scene::draw`]) for the GPU: strokes become
//! [`GpuLineStyle`] table entries, polylines and points binding-sized batches.

use super::chunks::{BatchBuilder, ChunkLimits, LineBatch};
use super::layout::GpuLineStyle;
use crate::scene::draw::{Stroke, Switches, draw_list_with};
use crate::scene::{Color, Scene};

impl GpuLineStyle {
    /// A solid style.
    #[must_use]
    pub fn solid(color: Color, width_px: f32) -> GpuLineStyle {
        GpuLineStyle::from(Stroke::solid(color, width_px))
    }
}

impl From<Stroke> for GpuLineStyle {
    fn from(s: Stroke) -> GpuLineStyle {
        GpuLineStyle {
            color: s.color.0,
            width_px: s.width_px,
            dash_px: s.dash_px,
            _padding0: 0,
            _padding1: 0,
        }
    }
}

/// The scene's overlay polylines and points, batched: rebuilt on their own when curves are
/// edited in place.
#[must_use]
pub fn prepare_overlays(scene: &Scene, limits: ChunkLimits) -> (Vec<LineBatch>, Vec<LineBatch>) {
    prepare_overlays_with(scene, Switches::ALL, limits)
}

/// [`prepare_overlays`] with the curves' overlays limited by `switches`.
#[must_use]
pub fn prepare_overlays_with(
    scene: &Scene,
    switches: Switches,
    limits: ChunkLimits,
) -> (Vec<LineBatch>, Vec<LineBatch>) {
    let list = draw_list_with(scene, switches);
    let mut lines = BatchBuilder::new(limits);
    let mut points = BatchBuilder::new(limits);
    for (pts, stroke) in &list.lines {
        lines.push(pts, GpuLineStyle::from(*stroke));
    }
    for (pts, stroke) in &list.points {
        points.push(pts, GpuLineStyle::from(*stroke));
    }
    (lines.finish(), points.finish())
}
