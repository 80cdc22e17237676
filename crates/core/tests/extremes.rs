//! The analysis at the extremes of the double range: weights far apart, coordinates near
//! 1e300 and 1e200, a line's direction near the smallest double, and many copies of one
//! curve — each answered correctly, refused with a typed error, or bounded.

use glam::DVec3;
use splinescope_core::analysis::{AnalysisError, CurveAnalysis, HitKind, all_intersections};
use splinescope_core::geom::{Bezier, RationalBezier};

const P: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 2.0), (3.0, -1.0), (4.0, 1.0)];

fn points(scale: f64) -> Vec<DVec3> {
    P.iter()
        .map(|&(x, y)| DVec3::new(x * scale, y * scale, 0.0))
        .collect()
}

fn rational(weights: [f64; 4]) -> CurveAnalysis {
    CurveAnalysis::new(&RationalBezier::try_new(points(1.0), weights.to_vec()).expect("weights"))
}

#[test]
fn a_length_with_weights_1e600_apart_is_within_its_bound() {
    // The curve runs from P0 towards P1 and on to P2 within u ≈ 1e−300, stays at P2, and
    // leaves for P3 at 1 − u ≈ 1e−600 (a parameter no double holds). The truth,
    // 6.25795609860453899107…, is the integral of |dC/dσ| over the logistic parameter to
    // 50 digits (mpmath), by a method independent of this one's rules and cuts.
    let truth = 6.257_956_098_604_539;
    let c = rational([1e-300, 1.0, 1e300, 1e-300]);
    let l = c.length(0.0, 1.0, 1e-12).expect("length");
    assert!(
        (l.value - truth).abs() <= l.error + 4.0 * f64::EPSILON * truth,
        "{l:?} against {truth}"
    );
    // Never below the chord nor above the control polygon.
    let chord = 17f64.sqrt();
    let polygon = 5f64.sqrt() + 13f64.sqrt() + 5f64.sqrt();
    assert!(
        l.value + l.error >= chord && l.value - l.error <= polygon,
        "{l:?}"
    );
}

#[test]
fn a_box_with_weights_1e300_apart_reaches_the_point_it_is_pulled_to() {
    // With w1 = w3 = 1e300 the curve is pulled to P1 = (1, 2) at once and runs straight to
    // P3 = (4, 1): its box is [0, 4] × [0, 2] (y comes within rounding of 2).
    let c = rational([1.0, 1e300, 1.0, 1e300]);
    let b = c.bounding_box();
    assert_eq!((b.min.x, b.min.y, b.max.x), (0.0, 0.0, 4.0), "{b:?}");
    assert!((b.max.y - 2.0).abs() <= 1e-12, "{b:?}");
    // Every extremum lies on the curve's path: on the segment P1 P3 or at P1.
    for e in c.extrema() {
        assert!((e.point.y - 2.0).abs() <= 1e-9, "{e:?}");
    }
    // x = 2 meets it once, on P1 P3 at (2, 5/3) — not at t = 0, where the curve is (0, 0).
    let hits = c
        .intersect_line(DVec3::new(2.0, 0.0, 0.0), DVec3::new(2.0, 1.0, 0.0))
        .expect("line")
        .hits;
    assert_eq!(hits.len(), 1, "{hits:?}");
    assert!(
        (hits[0].point - DVec3::new(2.0, 5.0 / 3.0, 0.0)).length() <= 1e-12,
        "{hits:?}"
    );
    assert_eq!(hits[0].kind, HitKind::Crossing);
}

#[test]
fn lengths_of_a_curve_scaled_by_1e300_scale_and_refuse_what_is_beyond() {
    let unit = CurveAnalysis::new(&Bezier::new(points(1.0)));
    let huge = CurveAnalysis::new(&Bezier::new(points(1e300)));
    let (lu, lh) = (
        unit.length(0.0, 1.0, 1e-12).expect("unit").value,
        huge.length(0.0, 1.0, 1e-12).expect("huge").value,
    );
    assert!((lh / 1e300 - lu).abs() <= 1e-13 * lu, "{lh} against {lu}");
    // The parameter at a third of the length is the unit curve's (a length and its
    // parameter do not depend on the scale).
    let (tu, th) = (
        unit.parameter_at_length(lu / 3.0, 1e-12).expect("unit"),
        huge.parameter_at_length(lh / 3.0, 1e-12).expect("huge"),
    );
    assert!((tu - th).abs() <= 1e-12, "{th} against {tu}");
    assert!(
        (tu - 1.0 / 3.0).abs() > 1e-3,
        "the parameter is not a third: {tu}"
    );
    for s in [2.0 * lh, 1e308, f64::INFINITY, f64::NAN, -1.0] {
        assert!(
            matches!(
                huge.parameter_at_length(s, 1e-12),
                Err(AnalysisError::BeyondLength { .. })
            ),
            "s = {s}: {:?}",
            huge.parameter_at_length(s, 1e-12)
        );
    }
    // And a curve near the smallest doubles alike.
    let tiny = CurveAnalysis::new(&Bezier::new(points(1e-300)));
    let lt = tiny.length(0.0, 1.0, 1e-320).expect("tiny").value;
    assert!((lt / 1e-300 - lu).abs() <= 1e-12 * lu, "{lt} against {lu}");
}

#[test]
fn an_open_curve_near_1e200_is_open() {
    for scale in [1e150, 1e155, 1e200, 1e300] {
        let c = CurveAnalysis::new(&Bezier::new(points(scale)));
        assert!(!c.is_closed(), "scale {scale}");
        // Its length is finite and it has no area to report.
        assert!(
            c.length(0.0, 1.0, 1e-12 * scale)
                .expect("length")
                .value
                .is_finite()
        );
    }
    let mut closed = points(1e200);
    closed[3] = closed[0];
    assert!(CurveAnalysis::new(&Bezier::new(closed)).is_closed());
}

#[test]
fn a_line_through_two_points_a_denormal_apart_is_measured_or_refused() {
    let c = CurveAnalysis::new(&Bezier::new(points(1.0)));
    let reference = c
        .intersect_line(DVec3::new(0.0, 0.5, 0.0), DVec3::new(1.0, 0.5, 0.0))
        .expect("line")
        .hits;
    for d in [1e-300, 1e-200, 1e-100] {
        let hits = c
            .intersect_line(DVec3::new(0.0, 0.5, 0.0), DVec3::new(d, 0.5, 0.0))
            .expect("line")
            .hits;
        assert_eq!(hits.len(), reference.len(), "{d}: {hits:?}");
        for (h, r) in hits.iter().zip(&reference) {
            assert!(
                (h.t - r.t).abs() <= 1e-15 && h.kind == r.kind,
                "{d}: {h:?} {r:?}"
            );
            // p + λ (q − p) is the point.
            assert!(
                ((h.lambda * d) - h.point.x).abs() <= 1e-14,
                "{d}: λ = {} for {:?}",
                h.lambda,
                h.point
            );
        }
    }
    assert!(matches!(
        c.intersect_line(DVec3::new(0.0, 0.5, 0.0), DVec3::new(5e-324, 0.5, 0.0)),
        Err(AnalysisError::ShortLine { .. })
    ));
    assert!(matches!(
        c.intersect_line(DVec3::new(0.0, 0.5, 0.0), DVec3::new(0.0, 0.5, 0.0)),
        Err(AnalysisError::DegenerateLine { .. })
    ));
}

#[test]
fn copies_are_one_group_not_pairs() {
    // 300 copies of a cubic, and a line crossing it twice.
    let c = CurveAnalysis::new(&Bezier::new(points(1.0)));
    let line = CurveAnalysis::new(&Bezier::new(vec![
        DVec3::new(-1.0, 0.5, 0.0),
        DVec3::new(5.0, 0.5, 0.0),
    ]));
    let mut curves: Vec<&CurveAnalysis> = vec![&c; 300];
    curves.insert(150, &line);
    let all = all_intersections(&curves).expect("planar");
    assert_eq!(all.copies.len(), 1, "{:?}", all.copies);
    let group = &all.copies[0];
    assert_eq!(group.curves.len(), 300);
    assert!(!group.curves.contains(&150));
    assert_eq!(group.domain, (0.0, 1.0));
    // Each copy meets the line as the curve does; no pair of copies is listed.
    let one = c.intersect(&line).expect("planar");
    assert_eq!(all.pairs.len(), 300);
    for p in &all.pairs {
        assert!(p.i == 150 || p.j == 150, "{} {}", p.i, p.j);
        assert_eq!(p.found.hits.len(), one.hits.len());
    }
}
