//! The draw list: everything a scene shows besides its curves — control polygons and
//! points, the families' explaining polylines (dual polygons, tangent handles, the bump
//! vector), a 3D axis triad, annotations — with each stroke's colour, width and dash
//! resolved from the scene's styles. GPU-free: the GPU layer only packs and draws it.

use glam::DVec3;

use super::{AnnotationShape, Color, Scene, SceneCurve};
use crate::geom::OverlayKind;

/// How a polyline or a point set is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke {
    /// Straight-alpha sRGB colour.
    pub color: Color,
    /// Line width, or point diameter, in logical pixels.
    pub width_px: f32,
    /// Dash period in pixels (0 = solid).
    pub dash_px: f32,
}

impl Stroke {
    /// A solid stroke.
    #[must_use]
    pub fn solid(color: Color, width_px: f32) -> Stroke {
        Stroke {
            color,
            width_px,
            dash_px: 0.0,
        }
    }
}

/// Polylines and point sets with their strokes.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DrawList {
    /// Polylines.
    pub lines: Vec<(Vec<DVec3>, Stroke)>,
    /// Point sets (drawn as discs of the stroke's width).
    pub points: Vec<(Vec<DVec3>, Stroke)>,
    /// Per curve, which entries of `lines` and `points` are its overlays (so that an edit
    /// of one curve can rewrite its overlays alone).
    pub curves: Vec<(std::ops::Range<usize>, std::ops::Range<usize>)>,
    /// The entries of `lines` that are the 3D axis triad (which follows the scene's
    /// bounds, so any edit may move it).
    pub axes: std::ops::Range<usize>,
}

/// One curve's overlays as the draw list holds them: its polylines and point sets.
pub type CurveOverlays = (Vec<(Vec<DVec3>, Stroke)>, Vec<(Vec<DVec3>, Stroke)>);

/// Curve `sc`'s overlay polylines and point sets under `switches` (its entries of
/// [`draw_list_with`]).
#[must_use]
pub fn curve_overlays(sc: &SceneCurve, switches: Switches) -> CurveOverlays {
    let (mut lines, mut points) = (Vec::new(), Vec::new());
    if sc.style.show_polygon && switches.polygons {
        for overlay in sc.curve.overlays() {
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

/// The polylines that draw `axes` (for a caller that keeps the triad already).
#[must_use]
pub fn axis_polylines(axes: &[Axis]) -> Vec<(Vec<DVec3>, Stroke)> {
    axes.iter()
        .map(|axis| (vec![axis.from, axis.to], Stroke::solid(axis.color, 2.0)))
        .collect()
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
pub fn overlay_style(kind: OverlayKind, curve: Color) -> Stroke {
    let grey = Color([0.55, 0.55, 0.55, 1.0]);
    match kind {
        OverlayKind::ControlPolygon => {
            let mut c = curve.mix(grey, 0.55);
            c.0[3] = 0.9;
            Stroke::solid(c, POLYGON_WIDTH_PX)
        }
        OverlayKind::DualPolygon => Stroke {
            dash_px: 8.0,
            ..Stroke::solid(DUAL_COLOR, POLYGON_WIDTH_PX)
        },
        OverlayKind::TangentHandles => {
            let mut c = curve.mix(grey, 0.7);
            c.0[3] = 0.85;
            Stroke::solid(c, 1.0)
        }
        OverlayKind::BumpVector => Stroke {
            dash_px: 6.0,
            ..Stroke::solid(curve.mix(Color([0.0, 0.0, 0.0, 1.0]), 0.3), 2.0)
        },
    }
}

/// The style of the derived points shown with an overlay of `kind`, if any.
#[must_use]
pub fn overlay_point_style(kind: OverlayKind, curve: Color) -> Option<Stroke> {
    match kind {
        OverlayKind::DualPolygon => Some(Stroke::solid(DUAL_COLOR, DERIVED_POINT_DIAMETER_PX)),
        OverlayKind::TangentHandles => Some(Stroke::solid(
            curve.mix(Color([0.55, 0.55, 0.55, 1.0]), 0.6),
            DERIVED_POINT_DIAMETER_PX - 1.0,
        )),
        OverlayKind::ControlPolygon | OverlayKind::BumpVector => None,
    }
}

/// One axis of the triad drawn in 3D scenes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Axis {
    /// `"x"`, `"y"` or `"z"`.
    pub name: &'static str,
    /// Where it starts (the scene's lowest corner).
    pub from: DVec3,
    /// Where it ends (a fifth of the scene's diagonal along the axis).
    pub to: DVec3,
    /// x red, y green, z blue.
    pub color: Color,
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

/// Which curve overlays are drawn, over and above each curve's own style: the viewer's
/// `P` (control polygons and the families' explaining polylines) and `C` (control points)
/// switches. A curve's overlay is drawn when its style and the switch both ask for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Switches {
    /// Control polygons and explaining polylines.
    pub polygons: bool,
    /// Control points.
    pub points: bool,
}

impl Switches {
    /// Everything the curves' styles ask for.
    pub const ALL: Switches = Switches {
        polygons: true,
        points: true,
    };
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
        let scene = crate::scene::from_json_str(
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
        let scene = crate::scene::gallery::gallery();
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
