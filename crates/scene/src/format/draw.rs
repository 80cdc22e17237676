//! The draw list: everything a scene shows besides its curves — control polygons and
//! points, the families' explaining polylines (dual polygons, tangent handles, the bump
//! vector), a 3D axis triad, annotations — with each stroke's colour, width and dash
//! resolved from the scene's styles. GPU-free: the GPU layer only packs and draws it.

use glam::DVec3;

use super::{AnnotationShape, Scene, SceneCurve};
use splinescope_encoding::Color;

// The list's types are the encoding's; what is built from a scene is here.
use splinescope_encoding::draw as ed;

/// Curve `sc`'s overlay polylines and point sets under `switches` (its entries of
/// [`draw_list_with`]).
#[must_use]
pub fn curve_overlays(sc: &SceneCurve, switches: ed::Switches) -> ed::CurveOverlays {
    let (mut lines, mut points) = (Vec::new(), Vec::new());
    if sc.style.show_polygon && switches.polygons {
        for overlay in splinescope_present::Present::overlays(&sc.curve) {
            lines.push((
                overlay.points.clone(),
                ed::overlay_style(overlay.kind, sc.style.color),
            ));
            if let Some(style) = ed::overlay_point_style(overlay.kind, sc.style.color) {
                points.push((overlay.points.clone(), style));
            }
        }
    }
    if sc.style.show_points && switches.points {
        let dot = sc.style.color.mix(Color([0.0, 0.0, 0.0, 1.0]), 0.15);
        points.push((
            sc.curve.control_points().to_vec(),
            ed::Stroke::solid(dot, ed::POINT_DIAMETER_PX),
        ));
    }
    (lines, points)
}

/// The 3D axis triad's polylines (none for a planar scene).
#[must_use]
pub fn axis_lines(scene: &Scene) -> Vec<(Vec<DVec3>, ed::Stroke)> {
    if scene.is_planar() {
        return Vec::new();
    }
    ed::axis_polylines(&axis_triad(scene))
}

/// The axis triad at the lowest corner of `scene`'s bounds.
#[must_use]
pub fn axis_triad(scene: &Scene) -> [ed::Axis; 3] {
    let bounds = scene.bounds();
    let length = 0.2 * bounds.diagonal();
    let axis = |name, dir: DVec3, color| ed::Axis {
        name,
        from: bounds.min,
        to: bounds.min + dir * length,
        color,
    };
    [
        axis("x", DVec3::X, Color([0.85, 0.2, 0.2, 1.0])),
        axis("y", DVec3::Y, Color([0.2, 0.6, 0.2, 1.0])),
        axis("z", DVec3::Z, Color([0.2, 0.35, 0.85, 1.0])),
    ]
}

/// The overlay polylines and points of a scene (control polygons, control points, the
/// families' explaining polylines, 3D axes, annotations), each with its resolved stroke,
/// in one pass over the scene.
#[must_use]
pub fn draw_list(scene: &Scene) -> ed::DrawList {
    draw_list_with(scene, ed::Switches::ALL)
}

/// [`draw_list`] with the curves' overlays further limited by `switches` (the scene is
/// not copied to apply them).
#[must_use]
pub fn draw_list_with(scene: &Scene, switches: ed::Switches) -> ed::DrawList {
    let mut list = ed::DrawList::default();
    for sc in &scene.curves {
        let (lines, points) = curve_overlays(sc, switches);
        let (l0, p0) = (list.lines.len(), list.points.len());
        list.lines.extend(lines);
        list.points.extend(points);
        list.curves
            .push((l0..list.lines.len(), p0..list.points.len()));
    }
    let a0 = list.lines.len();
    list.lines.extend(axis_lines(scene));
    list.axes = a0..list.lines.len();
    let (lines, points) = (&mut list.lines, &mut list.points);
    for a in &scene.annotations {
        let style = ed::Stroke::solid(a.color, a.width);
        match &a.shape {
            AnnotationShape::Polyline(p) => lines.push((p.clone(), style)),
            AnnotationShape::Points(p) => points.push((p.clone(), style)),
        }
    }
    list
}

// Deprecated forms of the encoding's draw-list items, which this module re-exported.

/// Deprecated: `splinescope_encoding::draw::Axis`.
#[deprecated(note = "use splinescope_encoding::draw::Axis")]
pub type Axis = ed::Axis;

/// Deprecated: `splinescope_encoding::draw::CurveOverlays`.
#[deprecated(note = "use splinescope_encoding::draw::CurveOverlays")]
pub type CurveOverlays = ed::CurveOverlays;

/// Deprecated: `splinescope_encoding::draw::DrawList`.
#[deprecated(note = "use splinescope_encoding::draw::DrawList")]
pub type DrawList = ed::DrawList;

/// Deprecated: `splinescope_encoding::draw::MarkerKind`.
#[deprecated(note = "use splinescope_encoding::draw::MarkerKind")]
pub type MarkerKind = ed::MarkerKind;

/// Deprecated: `splinescope_encoding::draw::Stroke`.
#[deprecated(note = "use splinescope_encoding::draw::Stroke")]
pub type Stroke = ed::Stroke;

/// Deprecated: `splinescope_encoding::draw::Switches`.
#[deprecated(note = "use splinescope_encoding::draw::Switches")]
pub type Switches = ed::Switches;

/// Deprecated: `splinescope_encoding::draw::COMB_ENVELOPE_ALPHA`.
#[deprecated(note = "use splinescope_encoding::draw::COMB_ENVELOPE_ALPHA")]
pub const COMB_ENVELOPE_ALPHA: f32 = ed::COMB_ENVELOPE_ALPHA;

/// Deprecated: `splinescope_encoding::draw::COMB_HAIR_ALPHA`.
#[deprecated(note = "use splinescope_encoding::draw::COMB_HAIR_ALPHA")]
pub const COMB_HAIR_ALPHA: f32 = ed::COMB_HAIR_ALPHA;

/// Deprecated: `splinescope_encoding::draw::COMB_WIDTH_PX`.
#[deprecated(note = "use splinescope_encoding::draw::COMB_WIDTH_PX")]
pub const COMB_WIDTH_PX: f32 = ed::COMB_WIDTH_PX;

/// Deprecated: `splinescope_encoding::draw::DERIVED_POINT_DIAMETER_PX`.
#[deprecated(note = "use splinescope_encoding::draw::DERIVED_POINT_DIAMETER_PX")]
pub const DERIVED_POINT_DIAMETER_PX: f32 = ed::DERIVED_POINT_DIAMETER_PX;

/// Deprecated: `splinescope_encoding::draw::DUAL_COLOR`.
#[deprecated(note = "use splinescope_encoding::draw::DUAL_COLOR")]
pub const DUAL_COLOR: Color = ed::DUAL_COLOR;

/// Deprecated: `splinescope_encoding::draw::POINT_DIAMETER_PX`.
#[deprecated(note = "use splinescope_encoding::draw::POINT_DIAMETER_PX")]
pub const POINT_DIAMETER_PX: f32 = ed::POINT_DIAMETER_PX;

/// Deprecated: `splinescope_encoding::draw::POLYGON_WIDTH_PX`.
#[deprecated(note = "use splinescope_encoding::draw::POLYGON_WIDTH_PX")]
pub const POLYGON_WIDTH_PX: f32 = ed::POLYGON_WIDTH_PX;

/// Deprecated: `splinescope_encoding::draw::axis_polylines`.
#[deprecated(note = "use splinescope_encoding::draw::axis_polylines")]
#[must_use]
pub fn axis_polylines(axes: &[ed::Axis]) -> Vec<(Vec<DVec3>, ed::Stroke)> {
    ed::axis_polylines(axes)
}

/// Deprecated: `splinescope_encoding::draw::overlay_style`.
#[deprecated(note = "use splinescope_encoding::draw::overlay_style")]
#[must_use]
pub fn overlay_style(kind: ed::OverlayKind, curve: Color) -> ed::Stroke {
    ed::overlay_style(kind, curve)
}

/// Deprecated: `splinescope_encoding::draw::overlay_point_style`.
#[deprecated(note = "use splinescope_encoding::draw::overlay_point_style")]
#[must_use]
pub fn overlay_point_style(kind: ed::OverlayKind, curve: Color) -> Option<ed::Stroke> {
    ed::overlay_point_style(kind, curve)
}

/// Deprecated: `splinescope_encoding::draw::marker_style`.
#[deprecated(note = "use splinescope_encoding::draw::marker_style")]
#[must_use]
pub fn marker_style(kind: ed::MarkerKind, curve: Color) -> (ed::Stroke, ed::Stroke) {
    ed::marker_style(kind, curve)
}

/// Deprecated: `splinescope_encoding::draw::comb_strokes`.
#[deprecated(note = "use splinescope_encoding::draw::comb_strokes")]
#[must_use]
pub fn comb_strokes(curve: Color) -> (ed::Stroke, ed::Stroke) {
    ed::comb_strokes(curve)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_draw_list_follows_the_scene_styles() {
        let scene = crate::format::from_json_str(
            r##"{"version": 1, "curves": [
                {"type": "bezier", "points": [[0, 0, 0], [1, 2, 1], [2, 0, 0]],
                 "style": {"polygon": true, "points": false}},
                {"type": "bezier", "points": [[0, 0, 0], [1, 1, 0]],
                 "style": {"polygon": false, "points": true}}
             ],
             "annotations": [{"points": [[5, 5, 0]], "color": "#ff0000", "width": 9}]}"##,
        )
        .expect("valid scene");
        let list = draw_list(&scene);
        // Curve 0's polygon, then the three axes (the scene is not planar).
        assert_eq!(list.lines.len(), 4);
        assert_eq!(
            list.lines[0].0,
            scene.curves[0].curve.control_points().to_vec()
        );
        assert_eq!(list.lines[0].1.width_px, ed::POLYGON_WIDTH_PX);
        // Curve 1's control points, then the annotation with its own stroke.
        assert_eq!(list.points.len(), 2);
        assert_eq!(list.points[0].1.width_px, ed::POINT_DIAMETER_PX);
        assert_eq!(list.points[1].0, vec![DVec3::new(5.0, 5.0, 0.0)]);
        assert_eq!(
            list.points[1].1,
            ed::Stroke::solid(Color([1.0, 0.0, 0.0, 1.0]), 9.0)
        );
    }

    /// Switching overlays off draws what the same scene with those styles turned off
    /// draws (what the viewer used to build by copying the scene), without a copy.
    #[test]
    fn switches_draw_what_the_styles_turned_off_would() {
        let scene = crate::format::gallery::gallery();
        for (polygons, points) in [(true, true), (false, true), (true, false), (false, false)] {
            let mut styled = scene.clone();
            for c in &mut styled.curves {
                c.style.show_polygon &= polygons;
                c.style.show_points &= points;
            }
            let want = draw_list(&styled);
            let got = draw_list_with(&scene, ed::Switches { polygons, points });
            assert_eq!(
                got.lines, want.lines,
                "polygons {polygons}, points {points}"
            );
            assert_eq!(
                got.points, want.points,
                "polygons {polygons}, points {points}"
            );
        }
        let none = draw_list_with(
            &scene,
            ed::Switches {
                polygons: false,
                points: false,
            },
        );
        assert!(none.lines.len() < draw_list(&scene).lines.len());
    }
}
