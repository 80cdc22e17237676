//! What a scene shows of its curves' shape beyond the curves themselves — the curvature
//! comb and the markers a shape designer judges a change by — as the viewer, `render`,
//! `export` and Python ask for it: [`ShapeOptions`]. The comb's hairs are drawn by the
//! GPU (and by figures from [`splinescope_core::analysis::comb`]); the markers are points
//! found by the analysis engine ([`markers`]): inflections and cusps, curvature extrema,
//! intersections between curves and of a curve with itself. Markers need a plane: 3D
//! curves have none.

use glam::DVec3;

use splinescope_core::analysis::comb::{auto_scale, reference_curvature, reference_length};
use splinescope_core::analysis::{CurveAnalysis, ExtremumKind, JointClass, all_intersections};

use super::Scene;
use splinescope_encoding::Color;
use splinescope_encoding::draw as ed;
use splinescope_encoding::draw::{Stroke, marker_style};

/// How long a comb's hairs are.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CombScale {
    /// Chosen for the view: a hair at the scene's reference curvature is
    /// [`splinescope_core::analysis::comb::AUTO_COMB_FRACTION`] of the view's height, or
    /// [`splinescope_core::analysis::comb::AUTO_COMB_CURVE_FRACTION`] of a typical curve's
    /// length where that is shorter.
    Auto,
    /// World length of a hair per unit of curvature (a finite number above 0).
    Fixed(f64),
}

/// A comb scale that is not a finite number above 0.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("comb scale {}: must be a finite number above 0", splinescope_core::num::Num(*.0))]
pub struct CombScaleError(pub f64);

impl CombScale {
    /// A fixed scale given by a user, checked.
    ///
    /// # Errors
    /// [`CombScaleError`] naming the value when it is not a finite number above 0.
    pub fn fixed(scale: f64) -> Result<CombScale, CombScaleError> {
        if scale.is_finite() && scale > 0.0 {
            Ok(CombScale::Fixed(scale))
        } else {
            Err(CombScaleError(scale))
        }
    }

    /// The world length per unit of curvature for `scene` seen `view_height` world units
    /// tall.
    #[must_use]
    pub fn resolve(self, scene: &Scene, view_height: f64) -> f64 {
        match self {
            CombScale::Fixed(s) => s,
            CombScale::Auto => {
                let analyses: Vec<CurveAnalysis> = scene
                    .curves
                    .iter()
                    .map(|c| CurveAnalysis::new(&c.curve))
                    .collect();
                auto_scale(
                    reference_curvature(&analyses),
                    reference_length(&analyses),
                    view_height,
                )
            }
        }
    }
}

/// The longest a comb's hair is drawn, as a fraction of the view's height (a finite
/// number above 0, or no cap at all): a longer hair — near a cusp the curvature has no
/// bound — is cut to it and drawn as capped, its envelope broken
/// ([`splinescope_core::analysis::comb`]). The default is
/// [`splinescope_core::analysis::comb::DEFAULT_COMB_CAP`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CombCap(f64);

impl Default for CombCap {
    fn default() -> CombCap {
        CombCap(splinescope_core::analysis::comb::DEFAULT_COMB_CAP)
    }
}

/// A comb cap that is not a finite number above 0.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error(
    "comb cap {}: must be a finite number above 0 (a fraction of the view's height), or none",
    splinescope_core::num::Num(*.0)
)]
pub struct CombCapError(pub f64);

impl CombCap {
    /// No cap: every hair as long as the scale makes it.
    pub const NONE: CombCap = CombCap(f64::INFINITY);

    /// A cap of `fraction` of the view's height, checked.
    ///
    /// # Errors
    /// [`CombCapError`] naming the value when it is not a finite number above 0.
    pub fn fraction(fraction: f64) -> Result<CombCap, CombCapError> {
        if fraction.is_finite() && fraction > 0.0 {
            Ok(CombCap(fraction))
        } else {
            Err(CombCapError(fraction))
        }
    }

    /// The fraction of the view's height (`inf` for no cap).
    #[must_use]
    pub fn get(self) -> f64 {
        self.0
    }

    /// The longest hair in world units for a view `view_height` world units tall
    /// (`inf` for no cap).
    #[must_use]
    pub fn world(self, view_height: f64) -> f64 {
        let w = self.0 * view_height;
        if w.is_nan() { f64::INFINITY } else { w }
    }
}

/// Which shape overlays are shown.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ShapeOptions {
    /// The curvature comb of every curve, and its scale.
    pub comb: Option<CombScale>,
    /// How long a comb's hair may be.
    pub comb_cap: CombCap,
    /// Inflections (where `P′ × P″` changes sign) and cusps (`P′ = 0`).
    pub inflections: bool,
    /// The local extrema of the signed curvature.
    pub curvature_extrema: bool,
    /// Where curves cross each other or themselves.
    pub intersections: bool,
    /// The joints that are not G2: kinks (G0, gaps) and curvature jumps (G1).
    pub joints: bool,
}

impl ShapeOptions {
    /// The marker kinds these options show, in the legend's order.
    #[must_use]
    pub fn marker_kinds(&self) -> Vec<ed::MarkerKind> {
        ed::MarkerKind::ALL
            .into_iter()
            .filter(|k| match k {
                ed::MarkerKind::Inflection | ed::MarkerKind::Cusp => self.inflections,
                ed::MarkerKind::CurvatureMax | ed::MarkerKind::CurvatureMin => {
                    self.curvature_extrema
                }
                ed::MarkerKind::Intersection | ed::MarkerKind::SelfIntersection => {
                    self.intersections
                }
                ed::MarkerKind::Kink | ed::MarkerKind::CurvatureJump => self.joints,
            })
            .collect()
    }

    /// Whether any marker is asked for.
    #[must_use]
    pub fn any_marker(&self) -> bool {
        self.inflections || self.curvature_extrema || self.intersections || self.joints
    }
}

/// One marker.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Marker {
    /// What it marks.
    pub kind: ed::MarkerKind,
    /// The curve (the first one, for an intersection).
    pub curve: usize,
    /// Its parameter on that curve.
    pub t: f64,
    /// The point.
    pub point: DVec3,
    /// The signed curvature there (curvature extrema).
    pub curvature: Option<f64>,
    /// The other curve and its parameter (intersections).
    pub other: Option<(usize, f64)>,
    /// The angle between the tangents (radians) and the relative curvature jump (joints).
    pub joint: Option<(f64, f64)>,
}

/// The markers `options` asks for on `scene`'s planar curves, by kind then curve then
/// parameter. A curve the analysis refuses (3D, or a degree past its limits) has none.
#[must_use]
pub fn markers(scene: &Scene, options: &ShapeOptions) -> Vec<Marker> {
    let analyses: Vec<CurveAnalysis> = scene
        .curves
        .iter()
        .map(|c| CurveAnalysis::new(&c.curve))
        .collect();
    markers_of(&analyses, options)
}

/// [`markers`] for curves already analysed.
#[must_use]
pub fn markers_of(analyses: &[CurveAnalysis], options: &ShapeOptions) -> Vec<Marker> {
    let mut out = Vec::new();
    let at = |kind, curve, t: f64, point| Marker {
        kind,
        curve,
        t,
        point,
        curvature: None,
        other: None,
        joint: None,
    };
    for (i, a) in analyses.iter().enumerate().filter(|(_, a)| a.is_planar()) {
        if options.inflections {
            for t in a.inflections().unwrap_or_default() {
                out.push(at(ed::MarkerKind::Inflection, i, t, a.point(t)));
            }
            for t in a.cusps().unwrap_or_default() {
                out.push(at(ed::MarkerKind::Cusp, i, t, a.point(t)));
            }
        }
        if options.curvature_extrema {
            for e in a.curvature_extrema().unwrap_or_default() {
                let kind = match e.kind {
                    ExtremumKind::Maximum => ed::MarkerKind::CurvatureMax,
                    ExtremumKind::Minimum => ed::MarkerKind::CurvatureMin,
                };
                out.push(Marker {
                    curvature: Some(e.curvature),
                    ..at(kind, i, e.t, e.point)
                });
            }
        }
        if options.intersections {
            for h in a.self_intersections().map(|f| f.hits).unwrap_or_default() {
                out.push(Marker {
                    other: Some((i, h.t)),
                    ..at(ed::MarkerKind::SelfIntersection, i, h.s, h.point)
                });
            }
        }
        if options.joints {
            for j in a.joints().unwrap_or_default() {
                let kind = match j.class {
                    JointClass::G2 => continue,
                    JointClass::G1 => ed::MarkerKind::CurvatureJump,
                    JointClass::G0 | JointClass::Gap => ed::MarkerKind::Kink,
                };
                out.push(Marker {
                    joint: Some((j.angle, j.curvature_jump)),
                    ..at(kind, i, j.t, j.point)
                });
            }
        }
    }
    if options.intersections {
        let planar: Vec<usize> = (0..analyses.len())
            .filter(|&i| analyses[i].is_planar())
            .collect();
        // The planar curves alone.
        let pairs = if planar.len() == analyses.len() {
            all_intersections(analyses)
        } else {
            let subset: Vec<&CurveAnalysis> = planar.iter().map(|&i| &analyses[i]).collect();
            all_intersections(&subset)
        };
        let all = pairs.unwrap_or_default();
        for pair in all.pairs {
            let (i, j) = (planar[pair.i], planar[pair.j]);
            for h in pair.found.hits {
                out.push(Marker {
                    other: Some((j, h.t)),
                    ..at(ed::MarkerKind::Intersection, i, h.s, h.point)
                });
            }
        }
        // Copies coincide entirely: one marker per group, at the start of its first curve.
        for g in all.copies {
            let (i, j) = (planar[g.curves[0]], planar[g.curves[1]]);
            let t = g.domain.0;
            out.push(Marker {
                other: Some((j, t)),
                ..at(ed::MarkerKind::Intersection, i, t, analyses[i].point(t))
            });
        }
    }
    out.sort_by(|a, b| {
        (a.kind, a.curve)
            .cmp(&(b.kind, b.curve))
            .then(a.t.total_cmp(&b.t))
    });
    out
}

/// `scene` encoded for the GPU with the shape overlays of `options`: the comb's scale
/// resolved for a view `view_height` world units tall, the markers appended to the draw
/// list's points (over everything else).
#[must_use]
pub fn encode_shaped(
    scene: &Scene,
    view_height: f64,
    options: &ShapeOptions,
) -> splinescope_encoding::Encoding {
    encode_shaped_with(scene, view_height, options, ed::Switches::ALL)
}

/// [`encode_shaped`] with the curves' overlays further limited by `switches` (the
/// window's `P` and `C`).
#[must_use]
pub fn encode_shaped_with(
    scene: &Scene,
    view_height: f64,
    options: &ShapeOptions,
    switches: ed::Switches,
) -> splinescope_encoding::Encoding {
    let mut encoding = super::encoding::encode_with(scene, switches);
    encoding.comb = options.comb.map(|c| c.resolve(scene, view_height));
    encoding.comb_cap = options.comb_cap.world(view_height);
    if options.any_marker() {
        let found = markers(scene, options);
        encoding
            .overlays
            .points
            .extend(marker_points(scene, &found));
    }
    encoding
}

/// The markers as point sets for the draw list: per marker kind and curve, its rings then
/// its cores ([`marker_style`]), in the curve's colour (an intersection's first curve's).
#[must_use]
pub fn marker_points(scene: &Scene, markers: &[Marker]) -> Vec<(Vec<DVec3>, Stroke)> {
    let mut rings = Vec::new();
    let mut cores = Vec::new();
    let mut k = 0;
    while k < markers.len() {
        let (kind, curve) = (markers[k].kind, markers[k].curve);
        let end = k + markers[k..]
            .iter()
            .take_while(|m| m.kind == kind && m.curve == curve)
            .count();
        let color = scene
            .curves
            .get(curve)
            .map_or(Color::WHITE, |c| c.style.color);
        let (ring, core) = marker_style(kind, color);
        let points: Vec<DVec3> = markers[k..end].iter().map(|m| m.point).collect();
        rings.push((points.clone(), ring));
        cores.push((points, core));
        k = end;
    }
    rings.extend(cores);
    rings
}

/// Deprecated: `splinescope_encoding::draw::MarkerKind`.
#[deprecated(note = "use splinescope_encoding::draw::MarkerKind")]
pub type MarkerKind = ed::MarkerKind;

#[cfg(test)]
mod tests {
    use super::*;
    use splinescope_core::geom::{Bezier, Curve};

    fn p(x: f64, y: f64) -> DVec3 {
        DVec3::new(x, y, 0.0)
    }

    fn scene_of(curves: Vec<Curve>) -> Scene {
        Scene::of_curves(curves)
    }

    #[test]
    fn an_s_and_a_line_through_it_give_the_markers_the_analysis_finds() {
        // An antisymmetric S about (1, 0): its inflection is at t = 1/2, the point (1, 0),
        // and the x axis crosses it there and at two other points.
        let s = Curve::Bezier(Bezier::new(vec![
            p(0.0, 0.0),
            p(1.0, 2.0),
            p(1.0, -2.0),
            p(2.0, 0.0),
        ]));
        let line = Curve::Bezier(Bezier::new(vec![p(-1.0, 0.0), p(3.0, 0.0)]));
        let scene = scene_of(vec![s, line]);
        let all = ShapeOptions {
            comb: None,
            comb_cap: CombCap::default(),
            inflections: true,
            curvature_extrema: true,
            intersections: true,
            joints: true,
        };
        let found = markers(&scene, &all);
        let of = |k: ed::MarkerKind| found.iter().filter(|m| m.kind == k).collect::<Vec<_>>();
        let inflections = of(ed::MarkerKind::Inflection);
        assert_eq!(inflections.len(), 1, "{found:?}");
        assert!((inflections[0].t - 0.5).abs() < 1e-12);
        assert!((inflections[0].point - p(1.0, 0.0)).length() < 1e-12);
        // y(t) = 6t(1−t)(1−2t) vanishes at t = 0, 1/2, 1: three crossings with the axis.
        let crossings = of(ed::MarkerKind::Intersection);
        assert_eq!(crossings.len(), 3, "{crossings:?}");
        for (m, want) in crossings.iter().zip([0.0, 0.5, 1.0]) {
            assert_eq!((m.curve, m.other.map(|o| o.0)), (0, Some(1)));
            assert!((m.t - want).abs() < 1e-9, "{m:?}");
        }
        // Curvature extrema carry κ, and every marker lies on its curve.
        for m in &found {
            let on = scene.curves[m.curve].curve.clone();
            let q = splinescope_core::geom::ParamCurve::eval(&on, m.t);
            assert!((q - m.point).length() < 1e-9, "{m:?}");
            if matches!(
                m.kind,
                ed::MarkerKind::CurvatureMax | ed::MarkerKind::CurvatureMin
            ) {
                assert!(m.curvature.is_some());
            }
        }
        assert!(markers(&scene, &ShapeOptions::default()).is_empty());
    }

    #[test]
    fn a_comb_scale_must_be_a_positive_finite_number() {
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = CombScale::fixed(bad).unwrap_err();
            assert!(e.to_string().contains("comb scale"), "{e}");
        }
        assert_eq!(CombScale::fixed(2.5), Ok(CombScale::Fixed(2.5)));
    }
}
