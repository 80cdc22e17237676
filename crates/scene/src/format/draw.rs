//! The draw list: everything a scene shows besides its curves — control polygons and
//! points, the families' explaining polylines (dual polygons, tangent handles, the bump
//! vector), a 3D axis triad, annotations — with each stroke's colour, width and dash
//! resolved from the scene's styles. GPU-free: the GPU layer only packs and draws it.

use glam::DVec3;

use super::{AnnotationShape, Color, Scene, SceneCurve};

// The list's types are the encoding's; what is built from a scene is here.
pub use splinescope_encoding::draw::{
    Axis, COMB_ENVELOPE_ALPHA, COMB_HAIR_ALPHA, COMB_WIDTH_PX, CurveOverlays,
    DERIVED_POINT_DIAMETER_PX, DUAL_COLOR, DrawList, MarkerKind, POINT_DIAMETER_PX,
    POLYGON_WIDTH_PX, Stroke, Switches, axis_polylines, comb_strokes, marker_style,
    overlay_point_style, overlay_style,
};

/// Curve `sc`'s overlay polylines and point sets under `switches` (its entries of
/// [`draw_list_with`]).
#[must_use]
pub fn curve_overlays(sc: &SceneCurve, switches: Switches) -> CurveOverlays {
    let (mut lines, mut points) = (Vec::new(), Vec::new());
    if sc.style.show_polygon && switches.polygons {
        for overlay in splinescope_present::Present::overlays(&sc.curve) {
            lines.push((
                overlay.points.clone(),
                overlay_style(overlay.kind, sc.style.color),
            ));
            if let Some(style) = overlay_point_style(overlay.kind, sc.style.color) {
                points.push((overlay.points.clone(), style));
            }
        }
    }
    if sc.style.show_points && switches.points {
        let dot = sc.style.color.mix(Color([0.0, 0.0, 0.0, 1.0]), 0.15);
        points.push((
            sc.curve.control_points().to_vec(),
            Stroke::solid(dot, POINT_DIAMETER_PX),
        ));
    }
    (lines, points)
}

/// The 3D axis triad's polylines (none for a planar scene).
#[must_use]
pub fn axis_lines(scene: &Scene) -> Vec<(Vec<DVec3>, Stroke)> {
    if scene.is_planar() {
        return Vec::new();
    }
    axis_polylines(&axis_triad(scene))
}

/// The axis triad at the lowest corner of `scene`'s bounds.
#[must_use]
pub fn axis_triad(scene: &Scene) -> [Axis; 3] {
    let bounds = scene.bounds();
    let length = 0.2 * bounds.diagonal();
    let axis = |name, dir: DVec3, color| Axis {
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
pub fn draw_list(scene: &Scene) -> DrawList {
    draw_list_with(scene, Switches::ALL)
}

/// [`draw_list`] with the curves' overlays further limited by `switches` (the scene is
/// not copied to apply them).
#[must_use]
pub fn draw_list_with(scene: &Scene, switches: Switches) -> DrawList {
    let mut list = DrawList::default();
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
        let style = Stroke::solid(a.color, a.width);
        match &a.shape {
            AnnotationShape::Polyline(p) => lines.push((p.clone(), style)),
            AnnotationShape::Points(p) => points.push((p.clone(), style)),
        }
    }
    list
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
        assert_eq!(list.lines[0].1.width_px, POLYGON_WIDTH_PX);
        // Curve 1's control points, then the annotation with its own stroke.
        assert_eq!(list.points.len(), 2);
        assert_eq!(list.points[0].1.width_px, POINT_DIAMETER_PX);
        assert_eq!(list.points[1].0, vec![DVec3::new(5.0, 5.0, 0.0)]);
        assert_eq!(
            list.points[1].1,
            Stroke::solid(Color([1.0, 0.0, 0.0, 1.0]), 9.0)
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
            let got = draw_list_with(&scene, Switches { polygons, points });
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
            Switches {
                polygons: false,
                points: false,
            },
        );
        assert!(none.lines.len() < draw_list(&scene).lines.len());
    }
}
