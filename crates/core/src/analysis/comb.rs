//! The curvature comb a shape designer judges a curve by (Rhino's curvature graph,
//! Alias's comb): at points along the curve a hair from `P` to `P − s K`, where
//! `K = (P″ − (P″·T) T) / |P′|²` is the curvature vector (length `κ`, pointing to the
//! centre of curvature; in the plane `κ` is signed, so the hairs change side at an
//! inflection), and `s` the comb's scale — world length per unit of curvature. The tips
//! joined in order are the comb's envelope. Hairs point away from the centre of
//! curvature, as those tools draw them.
//!
//! A hair longer than the comb's cap is cut to the cap and marked `capped`: near a cusp
//! the curvature grows without bound and an uncut hair would cross the whole view. The
//! envelope is broken at a capped hair (drawn to and from it, it would be a long straight
//! line saying nothing), and the capped hair itself is drawn in the envelope's stronger
//! stroke, so that it reads as "sharper than the comb shows".
//!
//! Hairs sit at uniform parameters of every lowered segment, ends included, about
//! [`COMB_SPACING_PX`] apart along its control polygon on screen ([`hairs_for`]; at most
//! [`COMB_HAIRS_PER_SEGMENT`]) — in the window, in `render`'s PNG and in SVG/PDF figures
//! alike. The GPU
//! computes the same hairs from the same segments every frame (the `comb_*` kernels of
//! `shaders/adaptive.wgsl`, in `f32`); this is the exact `f64` version that figures draw
//! and tests compare with (`docs/math.md` §8).

use glam::DVec3;

use super::CurveAnalysis;

/// The curvature vector from the first two derivatives: `(P″ − (P″·T) T) / |P′|²`;
/// `None` where `P′ = 0` (a cusp: the curvature is unbounded there).
#[must_use]
pub fn curvature_vector(d1: DVec3, d2: DVec3) -> Option<DVec3> {
    let speed2 = d1.length_squared();
    if speed2 <= 0.0 || !speed2.is_finite() {
        return None;
    }
    Some((d2 - (d2.dot(d1) / speed2) * d1) / speed2)
}

/// The most hairs of a comb on one lowered segment, uniform in the segment's parameter,
/// ends included. Twin: `COMB_HAIRS` in `shaders/adaptive.wgsl`.
pub const COMB_HAIRS_PER_SEGMENT: usize = 32;

/// The spacing of a comb's hairs, in pixels of the segment's projected control polygon.
/// Twin: `COMB_SPACING_PX` in `shaders/adaptive.wgsl`.
pub const COMB_SPACING_PX: f64 = 4.0;

/// The hairs a lowered segment gets whose control polygon is `polygon_px` pixels long on
/// screen: one every [`COMB_SPACING_PX`] and one more, from 2 to
/// [`COMB_HAIRS_PER_SEGMENT`] (the most where the length is not finite) — the density
/// the window, `render` and figures all draw. Twin: `comb_hairs_of` in
/// `shaders/adaptive.wgsl`.
#[must_use]
pub fn hairs_for(polygon_px: f64) -> usize {
    if polygon_px.is_nan() || polygon_px >= 1e9 {
        return COMB_HAIRS_PER_SEGMENT;
    }
    ((polygon_px / COMB_SPACING_PX).ceil().max(0.0) as usize + 1).clamp(2, COMB_HAIRS_PER_SEGMENT)
}

/// One hair of a comb.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hair {
    /// The curve parameter.
    pub t: f64,
    /// The point on the curve.
    pub point: DVec3,
    /// The hair's tip, `point − scale · K` (the point itself at a cusp), cut to the cap.
    pub tip: DVec3,
    /// Whether the hair was longer than the cap (its tip is then `cap` from the point).
    pub capped: bool,
}

/// The comb of a curve: `per_segment(k)` hairs (at least 2) at uniform parameters of its
/// lowered segment `k`, ends included, with hairs `scale` world units long per unit of
/// curvature, none longer than `cap` world units (`f64::INFINITY`: no cap).
#[must_use]
pub fn comb(
    analysis: &CurveAnalysis,
    per_segment: &dyn Fn(usize) -> usize,
    scale: f64,
    cap: f64,
) -> Vec<Hair> {
    let mut out = Vec::new();
    for (k, piece) in analysis.pieces().iter().enumerate() {
        let n = per_segment(k).max(2);
        for j in 0..n {
            let u = j as f64 / (n - 1) as f64;
            let t = piece.t0 + u * (piece.t1 - piece.t0);
            let h = piece.t1 - piece.t0;
            let point = piece.point(u);
            let k = curvature_vector(piece.deriv(u) / h, piece.second_deriv(u) / (h * h));
            let hair = -scale * k.unwrap_or(DVec3::ZERO);
            let length = hair.length();
            let capped = length > cap;
            let tip = if capped {
                point + hair * (cap / length)
            } else {
                point + hair
            };
            out.push(Hair {
                t,
                point,
                tip,
                capped,
            });
        }
    }
    out
}

/// The default cap of a comb's hairs, as a fraction of the view's height.
pub const DEFAULT_COMB_CAP: f64 = 0.05;

/// The fraction of the view's height the automatic comb scale gives a hair at the reference
/// curvature ([`reference_curvature`]): under the default cap ([`DEFAULT_COMB_CAP`]), so
/// that the bulk of the hairs is drawn uncapped and only the sharpest tenth can reach it.
pub const AUTO_COMB_FRACTION: f64 = 0.04;

/// The most the automatic comb scale gives that hair, as a fraction of a typical curve's
/// length ([`reference_length`]): on a scene of many small curves the combs stay the size
/// of their curves instead of a fixed part of the view each.
pub const AUTO_COMB_CURVE_FRACTION: f64 = 0.5;

/// Samples per segment the automatic scale measures the curvature at.
const REFERENCE_SAMPLES: usize = 16;

/// The curvature an automatic comb scale is set against: the 90th percentile of `|κ|` at
/// 16 uniform parameters of every segment of every curve (robust to the unbounded
/// curvature near a cusp, which a maximum is not); `None` when every sample is straight
/// or at a cusp.
#[must_use]
pub fn reference_curvature<'a>(curves: impl IntoIterator<Item = &'a CurveAnalysis>) -> Option<f64> {
    let mut ks: Vec<f64> = Vec::new();
    for analysis in curves {
        for piece in analysis.pieces() {
            let h = piece.t1 - piece.t0;
            for j in 0..REFERENCE_SAMPLES {
                let u = j as f64 / (REFERENCE_SAMPLES - 1) as f64;
                if let Some(k) =
                    curvature_vector(piece.deriv(u) / h, piece.second_deriv(u) / (h * h))
                {
                    let k = k.length();
                    if k > 0.0 && k.is_finite() {
                        ks.push(k);
                    }
                }
            }
        }
    }
    if ks.is_empty() {
        return None;
    }
    let rank = (ks.len() - 1) * 9 / 10;
    let (_, k, _) = ks.select_nth_unstable_by(rank, f64::total_cmp);
    Some(*k)
}

/// A typical curve's length for the automatic comb scale: the median over the curves of
/// their control polygons' lengths (each at least the curve's length); `None` without a
/// curve of positive length.
#[must_use]
pub fn reference_length<'a>(curves: impl IntoIterator<Item = &'a CurveAnalysis>) -> Option<f64> {
    let mut lengths: Vec<f64> = curves
        .into_iter()
        .map(|a| a.pieces().iter().map(|p| p.polygon_length()).sum::<f64>())
        .filter(|l| *l > 0.0 && l.is_finite())
        .collect();
    if lengths.is_empty() {
        return None;
    }
    let middle = lengths.len() / 2;
    let (_, l, _) = lengths.select_nth_unstable_by(middle, f64::total_cmp);
    Some(*l)
}

/// The automatic comb scale for a view `view_height` world units tall: a hair at the
/// reference curvature ([`reference_curvature`]) is [`AUTO_COMB_FRACTION`] of the view
/// tall, or [`AUTO_COMB_CURVE_FRACTION`] of the typical curve's length
/// ([`reference_length`]) where that is shorter; 1 when there is no curvature to measure.
#[must_use]
pub fn auto_scale(reference: Option<f64>, typical_length: Option<f64>, view_height: f64) -> f64 {
    match reference {
        Some(k) if view_height.is_finite() && view_height > 0.0 => {
            let reach = AUTO_COMB_FRACTION * view_height;
            let reach = typical_length.map_or(reach, |l| reach.min(AUTO_COMB_CURVE_FRACTION * l));
            reach / k
        }
        _ => 1.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Bezier, Nurbs};

    #[test]
    fn a_circles_hairs_point_outward_by_scale_over_radius() {
        // κ = 1/r along the whole circle, K towards the centre: tips at r + s/r.
        let r = 2.0;
        let circle = Nurbs::circle(DVec3::new(1.0, -1.0, 0.0), r).expect("circle");
        let hairs = comb(&CurveAnalysis::new(&circle), &|_| 9, 0.5, f64::INFINITY);
        assert!(hairs.len() >= 9);
        for h in hairs {
            let out = h.point - DVec3::new(1.0, -1.0, 0.0);
            let tip = h.tip - DVec3::new(1.0, -1.0, 0.0);
            assert!((out.length() - r).abs() < 1e-12, "{h:?}");
            assert!((tip.length() - (r + 0.5 / r)).abs() < 1e-12, "{h:?}");
            assert!(tip.normalize().dot(out.normalize()) > 1.0 - 1e-12, "{h:?}");
        }
    }

    #[test]
    fn a_line_has_no_hairs_and_a_cusp_none_either() {
        let line = Bezier::new(vec![DVec3::ZERO, DVec3::X, DVec3::new(2.0, 0.0, 0.0)]);
        for h in comb(&CurveAnalysis::new(&line), &|_| 5, 3.0, 1.0) {
            assert_eq!(h.tip, h.point);
        }
        assert_eq!(reference_curvature([&CurveAnalysis::new(&line)]), None);
        // P′(1/2) = 0 for this symmetric cubic: no hair there, a finite one elsewhere.
        let cusp = Bezier::new(vec![
            DVec3::ZERO,
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
        ]);
        let hairs = comb(&CurveAnalysis::new(&cusp), &|_| 5, 1.0, f64::INFINITY);
        assert_eq!(hairs[2].tip, hairs[2].point);
        assert!(hairs.iter().all(|h| h.tip.is_finite()));
    }

    #[test]
    fn hairs_follow_the_polygons_length_on_screen() {
        assert_eq!(hairs_for(0.0), 2);
        assert_eq!(hairs_for(4.0), 2);
        assert_eq!(hairs_for(4.5), 3);
        assert_eq!(hairs_for(40.0), 11);
        assert_eq!(hairs_for(1e6), COMB_HAIRS_PER_SEGMENT);
        assert_eq!(hairs_for(f64::NAN), COMB_HAIRS_PER_SEGMENT);
        assert_eq!(hairs_for(f64::INFINITY), COMB_HAIRS_PER_SEGMENT);
    }

    #[test]
    fn hairs_past_the_cap_are_cut_to_it_and_marked() {
        // A circle of radius 2 with s = 4: every hair 4 / 2 = 2 long, exactly.
        let circle = Nurbs::circle(DVec3::ZERO, 2.0).expect("circle");
        let a = CurveAnalysis::new(&circle);
        for (cap, capped) in [(1.5, true), (2.5, false), (f64::INFINITY, false)] {
            for h in comb(&a, &|_| 7, 4.0, cap) {
                let length = (h.tip - h.point).length();
                assert_eq!(h.capped, capped, "cap {cap}: {h:?}");
                let want = if capped { cap } else { 2.0 };
                assert!((length - want).abs() < 1e-12, "cap {cap}: {length} {h:?}");
                // Still along the outward radius.
                let (out, hair) = (h.point.normalize(), (h.tip - h.point).normalize());
                assert!(out.dot(hair) > 1.0 - 1e-12, "{h:?}");
            }
        }
        // Near a cusp the curvature runs away: with a cap, no hair is longer, whatever the
        // scale.
        let near_cusp = Bezier::new(vec![
            DVec3::ZERO,
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(0.0, 1.001, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
        ]);
        let hairs = comb(&CurveAnalysis::new(&near_cusp), &|_| 101, 1e6, 0.3);
        assert!(hairs.iter().any(|h| h.capped));
        assert!(
            hairs
                .iter()
                .all(|h| (h.tip - h.point).length() <= 0.3 * (1.0 + 1e-12))
        );
    }

    #[test]
    fn the_automatic_scale_makes_the_reference_hair_a_fraction_of_the_view() {
        let r = 4.0;
        let circle = Nurbs::circle(DVec3::ZERO, r).expect("circle");
        let k = reference_curvature([&CurveAnalysis::new(&circle)]).expect("curved");
        assert!((k - 1.0 / r).abs() < 1e-12);
        let l = reference_length([&CurveAnalysis::new(&circle)]).expect("long");
        let s = auto_scale(Some(k), Some(l), 10.0);
        assert!((s * k - AUTO_COMB_FRACTION * 10.0).abs() < 1e-12);
        assert_eq!(auto_scale(None, Some(l), 10.0), 1.0);
    }

    #[test]
    fn the_automatic_scale_keeps_small_curves_combs_their_size() {
        // Three cubics whose control polygons are 3, 5 and 7 long (legs 1, 1, 1 to 3, 3,
        // 1 — right angles, lengths exact): the median is 5. In a view 1,000 tall the view's
        // fraction would be 40; half the typical curve, 2.5, is what the hair gets.
        let cubic = |a: f64, b: f64| {
            Bezier::new(vec![
                DVec3::ZERO,
                DVec3::new(a, 0.0, 0.0),
                DVec3::new(a, b, 0.0),
                DVec3::new(a - 1.0, b, 0.0),
            ])
        };
        let curves = [cubic(1.0, 1.0), cubic(2.0, 2.0), cubic(3.0, 3.0)];
        let analyses: Vec<CurveAnalysis> = curves.iter().map(CurveAnalysis::new).collect();
        assert_eq!(reference_length(&analyses), Some(5.0));
        let k = reference_curvature(&analyses).expect("curved");
        let s = auto_scale(Some(k), reference_length(&analyses), 1000.0);
        assert!((s * k - 2.5).abs() < 1e-12, "{}", s * k);
        // Zoomed in until the view's fraction is shorter, the view decides again.
        let s = auto_scale(Some(k), Some(5.0), 10.0);
        assert!((s * k - AUTO_COMB_FRACTION * 10.0).abs() < 1e-12);
        assert_eq!(reference_length(&[]), None);
    }
}
