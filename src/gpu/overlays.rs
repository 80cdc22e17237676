//! What is drawn over the curves, and in which style: control polygons and points, the
//! families' explaining polylines (dual polygons, inner points), 3D axes and annotations.

use glam::DVec3;

use super::chunks::{BatchBuilder, ChunkLimits, LineBatch};
use super::layout::GpuLineStyle;
use crate::geom::OverlayKind;
use crate::scene::{AnnotationShape, Color, Scene};

impl GpuLineStyle {
    /// A solid style.
    #[must_use]
    pub fn solid(color: Color, width_px: f32) -> GpuLineStyle {
        GpuLineStyle {
            color: color.0,
            width_px,
            dash_px: 0.0,
            _padding0: 0,
            _padding1: 0,
        }
    }
}

/// Width in pixels of control polygons.
pub const POLYGON_WIDTH_PX: f32 = 1.25;
/// Diameter in pixels of control points.
pub const POINT_DIAMETER_PX: f32 = 7.0;

/// Diameter in pixels of derived points (dual control points, inner Bézier points).
pub const DERIVED_POINT_DIAMETER_PX: f32 = 5.0;
/// The colour of NUBMP dual polygons and points.
pub const DUAL_COLOR: Color = Color([0.95, 0.55, 0.05, 0.95]);

/// The style of an overlay polyline of `kind` over a curve of colour `curve`.
#[must_use]
pub fn overlay_style(kind: OverlayKind, curve: Color) -> GpuLineStyle {
    let grey = Color([0.55, 0.55, 0.55, 1.0]);
    match kind {
        OverlayKind::ControlPolygon => {
            let mut c = curve.mix(grey, 0.55);
            c.0[3] = 0.9;
            GpuLineStyle::solid(c, POLYGON_WIDTH_PX)
        }
        OverlayKind::DualPolygon => GpuLineStyle {
            dash_px: 8.0,
            ..GpuLineStyle::solid(DUAL_COLOR, POLYGON_WIDTH_PX)
        },
        OverlayKind::TangentHandles => {
            let mut c = curve.mix(grey, 0.7);
            c.0[3] = 0.85;
            GpuLineStyle::solid(c, 1.0)
        }
        OverlayKind::BumpVector => GpuLineStyle {
            dash_px: 6.0,
            ..GpuLineStyle::solid(curve.mix(Color([0.0, 0.0, 0.0, 1.0]), 0.3), 2.0)
        },
    }
}

/// The style of the derived points shown with an overlay of `kind`, if any.
#[must_use]
pub fn overlay_point_style(kind: OverlayKind, curve: Color) -> Option<GpuLineStyle> {
    match kind {
        OverlayKind::DualPolygon => {
            Some(GpuLineStyle::solid(DUAL_COLOR, DERIVED_POINT_DIAMETER_PX))
        }
        OverlayKind::TangentHandles => Some(GpuLineStyle::solid(
            curve.mix(Color([0.55, 0.55, 0.55, 1.0]), 0.6),
            DERIVED_POINT_DIAMETER_PX - 1.0,
        )),
        OverlayKind::ControlPolygon | OverlayKind::BumpVector => None,
    }
}

/// The overlay polylines and points of a scene (control polygons, control points, the
/// families' explaining polylines, annotations): rebuilt on their own when curves are
/// edited in place.
#[must_use]
pub fn prepare_overlays(scene: &Scene, limits: ChunkLimits) -> (Vec<LineBatch>, Vec<LineBatch>) {
    let mut lines = BatchBuilder::new(limits);
    let mut points = BatchBuilder::new(limits);
    for sc in &scene.curves {
        if sc.style.show_polygon {
            for overlay in sc.curve.overlays() {
                lines.push(&overlay.points, overlay_style(overlay.kind, sc.style.color));
                if let Some(style) = overlay_point_style(overlay.kind, sc.style.color) {
                    points.push(&overlay.points, style);
                }
            }
        }
        if sc.style.show_points {
            let dot = sc.style.color.mix(Color([0.0, 0.0, 0.0, 1.0]), 0.15);
            points.push(
                sc.curve.control_points(),
                GpuLineStyle::solid(dot, POINT_DIAMETER_PX),
            );
        }
    }
    if !scene.is_planar() {
        // An axis triad at the scene's lowest corner: x red, y green, z blue.
        let bounds = scene.bounds();
        let length = 0.2 * bounds.diagonal();
        for (axis, color) in [
            (DVec3::X, Color([0.85, 0.2, 0.2, 1.0])),
            (DVec3::Y, Color([0.2, 0.6, 0.2, 1.0])),
            (DVec3::Z, Color([0.2, 0.35, 0.85, 1.0])),
        ] {
            lines.push(
                &[bounds.min, bounds.min + axis * length],
                GpuLineStyle::solid(color, 2.0),
            );
        }
    }
    for a in &scene.annotations {
        let style = GpuLineStyle::solid(a.color, a.width);
        match &a.shape {
            AnnotationShape::Polyline(p) => lines.push(p, style),
            AnnotationShape::Points(p) => points.push(p, style),
        }
    }
    (lines.finish(), points.finish())
}
