//! What is drawn, as the GPU layer takes it — no [`Scene`]: every curve's exact Bézier
//! segments with its sample count and stroke, the overlays with their resolved strokes
//! (the draw list, with each curve's entries), the annotations' points and the
//! background. Built once from a scene ([`encode`]); the viewer re-encodes only the
//! curve an edit changed ([`encode_curve`], [`super::draw::curve_overlays`]). Points
//! are `f64` here; the GPU layer packs them into `f32`.

use glam::DVec3;

use super::draw::draw_list_with;
use super::{AnnotationShape, Scene};
use splinescope_core::geom::Lower;

use splinescope_encoding as enc;
use splinescope_encoding::draw::Switches;

/// Curve `index` of `scene`, lowered.
///
/// # Panics
/// When `index` is not a curve of `scene` (a bug in the caller).
#[must_use]
pub fn encode_curve(scene: &Scene, index: usize) -> enc::EncodedCurve {
    let sc = &scene.curves[index];
    enc::EncodedCurve {
        segments: sc.curve.lower(),
        samples: scene.samples_for(index),
        color: sc.style.color,
        width: sc.style.width,
        width_in_scene: sc.style.width_in_scene,
        stroke: sc.style.stroke,
        // A closed path's ends join; every other family's are its two ends.
        closed: matches!(&sc.curve, splinescope_core::geom::Curve::Path(p) if p.is_closed()),
    }
}

/// Everything `scene` draws, its overlays as the curves' styles ask.
#[must_use]
pub fn encode(scene: &Scene) -> enc::Encoding {
    encode_with(scene, Switches::ALL)
}

/// [`encode`] with the curves' overlays further limited by `switches`.
#[must_use]
pub fn encode_with(scene: &Scene, switches: Switches) -> enc::Encoding {
    enc::Encoding {
        curves: (0..scene.curves.len())
            .map(|i| encode_curve(scene, i))
            .collect(),
        overlays: draw_list_with(scene, switches),
        switches,
        annotations: annotation_points(scene),
        background: scene.background,
        comb: None,
        comb_cap: f64::INFINITY,
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
/// Deprecated: `splinescope_encoding::EncodedCurve`.
#[deprecated(note = "use splinescope_encoding::EncodedCurve")]
pub type EncodedCurve = enc::EncodedCurve;
/// Deprecated: `splinescope_encoding::Encoding`.
#[deprecated(note = "use splinescope_encoding::Encoding")]
pub type Encoding = enc::Encoding;
