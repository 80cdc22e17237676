//! The draw list's types: polylines and point sets with resolved strokes, the overlay
//! switches, the 3D axis triad, and the styles of each overlay kind. Building a list
//! from a scene is the scene layer's (`splinescope_scene::format::draw`).

use glam::DVec3;

use crate::color::Color;

/// What an overlay polyline shows, so that the renderer can style it. Each family says which
/// polylines explain it (`splinescope_present::Present::overlays`); the draw list styles
/// them by kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OverlayKind {
    /// The control polygon the user edits.
    ControlPolygon,
    /// The dual control polygon of a NUBMP curve (`P*_j`).
    DualPolygon,
    /// An interpolation piece's inner Bézier points, joined to its ends (tangent handles).
    TangentHandles,
    /// The vector `v` of a modified curve, drawn from `Q(t*)` to `R(t*) = Q(t*) + v`.
    BumpVector,
}

/// A polyline drawn over a curve to explain it (control polygon, dual polygon, …).
#[derive(Debug, Clone, PartialEq)]
pub struct OverlayPolyline {
    /// What it shows.
    pub kind: OverlayKind,
    /// Its vertices, in order.
    pub points: Vec<DVec3>,
}

impl OverlayPolyline {
    /// The control polygon through `points`.
    #[must_use]
    pub fn control_polygon(points: &[DVec3]) -> OverlayPolyline {
        OverlayPolyline {
            kind: OverlayKind::ControlPolygon,
            points: points.to_vec(),
        }
    }
}

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

/// What a shape marker marks (the viewer's, `render`'s and figures' markers).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum MarkerKind {
    /// An inflection (`P′ × P″` changes sign).
    Inflection,
    /// A cusp (`P′ = 0`).
    Cusp,
    /// A local maximum of the signed curvature.
    CurvatureMax,
    /// A local minimum of the signed curvature.
    CurvatureMin,
    /// Two curves meet.
    Intersection,
    /// A curve meets itself.
    SelfIntersection,
    /// A joint where the tangent turns (G0) or the ends part (a gap).
    Kink,
    /// A joint with one tangent where the curvature jumps (G1).
    CurvatureJump,
}

impl MarkerKind {
    /// Every kind, in the legend's order.
    pub const ALL: [MarkerKind; 8] = [
        MarkerKind::Inflection,
        MarkerKind::Cusp,
        MarkerKind::CurvatureMax,
        MarkerKind::CurvatureMin,
        MarkerKind::Intersection,
        MarkerKind::SelfIntersection,
        MarkerKind::Kink,
        MarkerKind::CurvatureJump,
    ];

    /// The legend's words.
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            MarkerKind::Inflection => "inflection",
            MarkerKind::Cusp => "cusp",
            MarkerKind::CurvatureMax => "curvature maximum",
            MarkerKind::CurvatureMin => "curvature minimum",
            MarkerKind::Intersection => "intersection",
            MarkerKind::SelfIntersection => "self-intersection",
            MarkerKind::Kink => "kink (G0 joint)",
            MarkerKind::CurvatureJump => "curvature jump (G1 joint)",
        }
    }
}

/// A marker's two discs, drawn one over the other: the ring, then the core. Each kind has
/// its own pattern in the curve's colour, so that kinds differ at a glance and a curve's
/// markers match its stroke: inflection — the curve's colour on white; cusp — dark on the
/// curve's colour; curvature maximum — the curve's colour on dark; minimum — white on the
/// curve's colour; intersection — white on dark; self-intersection — white on the curve's
/// colour, larger; kink — dark on orange; curvature jump — white on orange (the joints'
/// own colour, whatever the curve's).
#[must_use]
pub fn marker_style(kind: MarkerKind, curve: Color) -> (Stroke, Stroke) {
    const DARK: Color = Color([0.08, 0.08, 0.1, 1.0]);
    const JOINT: Color = Color([1.0, 0.55, 0.0, 1.0]);
    let (ring, core, outer, inner) = match kind {
        MarkerKind::Inflection => (Color::WHITE, curve, 11.0, 7.0),
        MarkerKind::Cusp => (curve, DARK, 11.0, 5.0),
        MarkerKind::CurvatureMax => (DARK, curve, 9.0, 6.0),
        MarkerKind::CurvatureMin => (curve, Color::WHITE, 9.0, 4.0),
        MarkerKind::Intersection => (DARK, Color::WHITE, 10.0, 6.0),
        MarkerKind::SelfIntersection => (curve, Color::WHITE, 12.0, 6.0),
        MarkerKind::Kink => (JOINT, DARK, 11.0, 5.0),
        MarkerKind::CurvatureJump => (JOINT, Color::WHITE, 10.0, 5.0),
    };
    (Stroke::solid(ring, outer), Stroke::solid(core, inner))
}

/// The opacity of a comb's hairs, relative to their curve's colour.
pub const COMB_HAIR_ALPHA: f32 = 0.45;

/// The opacity of a comb's envelope, relative to its curve's colour.
pub const COMB_ENVELOPE_ALPHA: f32 = 0.9;

/// The width of a comb's hairs and envelope, in pixels.
pub const COMB_WIDTH_PX: f32 = 1.0;

/// The strokes of a comb over a curve of colour `curve`: its hairs, then its envelope.
#[must_use]
pub fn comb_strokes(curve: Color) -> (Stroke, Stroke) {
    let with = |alpha: f32| {
        let [r, g, b, a] = curve.0;
        Stroke::solid(Color([r, g, b, a * alpha]), COMB_WIDTH_PX)
    };
    (with(COMB_HAIR_ALPHA), with(COMB_ENVELOPE_ALPHA))
}
