//! What is drawn, as the GPU layer takes it — no [`Scene`]: every curve's exact Bézier
//! segments with its sample count and stroke, the overlays with their resolved strokes
//! (the draw list, with each curve's entries), the annotations' points and the
//! background. Built once from a scene ([`Encoding::of`]); the viewer re-encodes only the
//! curve an edit changed ([`EncodedCurve::of`], [`super::draw::curve_overlays`]). Points
//! are `f64` here; the GPU layer packs them into `f32`.

use glam::DVec3;

use super::draw::{DrawList, Switches, draw_list_with};
use super::{AnnotationShape, Color, Scene};
use crate::geom::{BezierSegment, Lower};

/// One curve as drawn: its lowering and how it is stroked.
#[derive(Debug, Clone, PartialEq)]
pub struct EncodedCurve {
    /// Its exact Bézier segments (the family's lowering).
    pub segments: Vec<BezierSegment>,
    /// Fixed samples per segment, or `None` for counts chosen for the view.
    pub samples: Option<u32>,
    /// Its colour.
    pub color: Color,
    /// Its line width in pixels.
    pub width: f32,
}

impl EncodedCurve {
    /// Curve `index` of `scene`, lowered.
    ///
    /// # Panics
    /// When `index` is not a curve of `scene` (a bug in the caller).
    #[must_use]
    pub fn of(scene: &Scene, index: usize) -> EncodedCurve {
        let sc = &scene.curves[index];
        EncodedCurve {
            segments: sc.curve.lower(),
            samples: scene.samples_for(index),
            color: sc.style.color,
            width: sc.style.width,
        }
    }
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
}

impl Encoding {
    /// Everything `scene` draws, its overlays as the curves' styles ask.
    #[must_use]
    pub fn of(scene: &Scene) -> Encoding {
        Encoding::with(scene, Switches::ALL)
    }

    /// [`Encoding::of`] with the curves' overlays further limited by `switches`.
    #[must_use]
    pub fn with(scene: &Scene, switches: Switches) -> Encoding {
        Encoding {
            curves: (0..scene.curves.len())
                .map(|i| EncodedCurve::of(scene, i))
                .collect(),
            overlays: draw_list_with(scene, switches),
            switches,
            annotations: annotation_points(scene),
            background: scene.background,
        }
    }
}

/// Each annotation's points, in order (what the GPU's range check takes).
#[must_use]
pub fn annotation_points(scene: &Scene) -> Vec<Vec<DVec3>> {
    scene
        .annotations
        .iter()
        .map(|a| {
            let (AnnotationShape::Polyline(p) | AnnotationShape::Points(p)) = &a.shape;
            p.clone()
        })
        .collect()
}
