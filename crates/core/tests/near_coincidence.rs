//! Curves that run within the resolution of each other for a long stretch without
//! coinciding: an edited copy of a high-degree curve (one control point moved, so that the
//! two share their first and last control points and part like `s^k` from each end), and
//! a copy moved by less than the subdivision's flatness. Each is answered — one tangent
//! point at each shared end, a crossing wherever the displacement is along the curve —
//! or refused with [`AnalysisError::Crowded`] naming where, in bounded work; never a
//! partial answer returned as if it were all.

use glam::DVec3;
use splinescope_core::analysis::{AnalysisError, CurveAnalysis, HitKind, all_intersections};
use splinescope_core::geom::Bezier;

/// A spiral's control points: `r = 4 + i/2` at `θ = i/2`.
fn spiral(n: usize) -> Vec<DVec3> {
    (0..=n)
        .map(|i| {
            let (th, r) = (0.5 * i as f64, 4.0 + 0.5 * i as f64);
            DVec3::new(r * th.cos(), r * th.sin(), 0.0)
        })
        .collect()
}

/// The parameters in `(0, 1)` where `x′(t)` changes sign (the tangent is vertical), from
/// the derivative's Bernstein form sampled densely: where a copy moved along `y` crosses
/// the original (to first order in the move).
fn vertical_tangents(p: &[DVec3]) -> Vec<f64> {
    let n = p.len() - 1;
    let binom = |n: usize, k: usize| (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64);
    let dx = |t: f64| -> f64 {
        (0..n)
            .map(|i| {
                binom(n - 1, i)
                    * t.powi(i as i32)
                    * (1.0 - t).powi((n - 1 - i) as i32)
                    * (p[i + 1].x - p[i].x)
            })
            .sum::<f64>()
            * n as f64
    };
    const N: usize = 20_000;
    let s: Vec<f64> = (0..=N).map(|k| dx(k as f64 / N as f64)).collect();
    (0..N)
        .filter(|&k| (s[k] < 0.0) != (s[k + 1] < 0.0))
        .map(|k| (k as f64 + 0.5) / N as f64)
        .collect()
}

fn analysis(p: Vec<DVec3>) -> CurveAnalysis {
    CurveAnalysis::new(&Bezier::new(p))
}

/// The edited copy: point `k` moved by `d` along `y`.
fn edited(n: usize, k: usize, d: f64) -> (CurveAnalysis, CurveAnalysis, Vec<f64>) {
    let p = spiral(n);
    let mut q = p.clone();
    q[k].y += d;
    let vertical = vertical_tangents(&p);
    (analysis(p), analysis(q), vertical)
}

#[test]
fn an_edited_copy_touches_at_both_shared_ends_and_crosses_where_the_tangent_is_vertical() {
    // (degree, moved point, distance): contacts of order 4 to 12 at the ends.
    for (n, k, d) in [(9, 5, 1e-1), (9, 5, 1e-3), (31, 13, 1e-1), (31, 13, 1e-6)] {
        let (a, b, vertical) = edited(n, k, d);
        let found = a
            .intersect(&b)
            .unwrap_or_else(|e| panic!("degree {n}, point {k} moved {d}: {e}"));
        let case = format!("degree {n}, point {k} moved by {d}: {found:?}");
        assert!(found.overlaps.is_empty(), "{case}");
        // One tangent point at each end, exactly there.
        let start: Vec<_> = found.hits.iter().filter(|h| h.s == 0.0).collect();
        let end: Vec<_> = found.hits.iter().filter(|h| h.s == 1.0).collect();
        assert!(
            start.len() == 1 && start[0].kind == HitKind::Tangent && start[0].t == 0.0,
            "{case}"
        );
        assert!(
            end.len() == 1 && end[0].kind == HitKind::Tangent && end[0].t == 1.0,
            "{case}"
        );
        let (band0, band1) = (start[0].error_s, 1.0 - end[0].error_s);
        // No two hits are one point.
        for (i, x) in found.hits.iter().enumerate() {
            for y in &found.hits[i + 1..] {
                assert!(
                    (x.s - y.s).abs() > x.error_s + y.error_s,
                    "two hits in one band: {x:?} {y:?} ({case})"
                );
            }
        }
        // Between the ends' bands: a crossing at each vertical tangent, and nothing else.
        let inner: Vec<_> = found
            .hits
            .iter()
            .filter(|h| h.s != 0.0 && h.s != 1.0)
            .collect();
        let expected: Vec<f64> = vertical
            .iter()
            .copied()
            .filter(|&t| t > band0 + 1e-3 && t < band1 - 1e-3)
            .collect();
        for &t in &expected {
            assert!(
                inner
                    .iter()
                    .any(|h| h.kind == HitKind::Crossing && (h.s - t).abs() <= 2e-3 + h.error_s),
                "the crossing near the vertical tangent at {t} is missed ({case})"
            );
        }
        for h in &inner {
            assert!(
                vertical
                    .iter()
                    .any(|&t| (h.s - t).abs() <= 2e-3 + h.error_s),
                "a hit where the copy does not cross: {h:?} ({case})"
            );
        }
    }
}

#[test]
fn a_copy_moved_by_less_than_the_flatness_is_answered_or_refused_never_half_answered() {
    for (n, d) in [(31, 1e-11), (31, 1e-9), (9, 1e-10)] {
        let p = spiral(n);
        let q: Vec<DVec3> = p.iter().map(|&x| x + DVec3::new(0.0, d, 0.0)).collect();
        let vertical = vertical_tangents(&p);
        match analysis(p).intersect(&analysis(q)) {
            Ok(found) => {
                // Answered: then a crossing near every vertical tangent (at most its error
                // band away).
                for &t in &vertical {
                    assert!(
                        found
                            .hits
                            .iter()
                            .any(|h| (h.s - t).abs() <= 2e-3 + h.error_s)
                            || found.overlaps.iter().any(|o| {
                                t >= o.s.0.min(o.s.1) - 2e-3 && t <= o.s.0.max(o.s.1) + 2e-3
                            }),
                        "degree {n} moved by {d}: the crossing at {t} is missing from an answer: {found:?}"
                    );
                }
            }
            Err(e @ AnalysisError::Crowded { .. }) => {
                let AnalysisError::Crowded { pair, s, t, leaves } = e else {
                    unreachable!()
                };
                assert_eq!(pair, None);
                assert!(leaves > 0);
                for (lo, hi) in [s, t] {
                    assert!(
                        (0.0..=1.0).contains(&lo) && (0.0..=1.0).contains(&hi) && lo <= hi,
                        "degree {n} moved by {d}: the refusal names [{lo}, {hi}]"
                    );
                }
                let text = e.to_string();
                assert!(
                    text.contains("cannot be separated") && text.contains("near s ∈ ["),
                    "{text}"
                );
            }
            Err(e) => panic!("degree {n} moved by {d}: an unexpected error {e}"),
        }
    }
}

#[test]
fn a_refusal_among_many_curves_names_the_pair() {
    let p = spiral(31);
    let q: Vec<DVec3> = p.iter().map(|&x| x + DVec3::new(0.0, 1e-11, 0.0)).collect();
    let far = vec![DVec3::new(100.0, 100.0, 0.0), DVec3::new(101.0, 100.0, 0.0)];
    let one = analysis(p.clone()).intersect(&analysis(q.clone()));
    let Err(AnalysisError::Crowded { s, t, .. }) = one else {
        panic!("the pair alone is answered ({one:?}): this test needs a refused pair");
    };
    let curves = [analysis(far), analysis(p), analysis(q)];
    match all_intersections(&curves) {
        Err(AnalysisError::Crowded {
            pair: Some(pair),
            s: s2,
            t: t2,
            ..
        }) => {
            assert_eq!(pair, (1, 2));
            assert_eq!((s2, t2), (s, t), "the parameters in the pair's own order");
        }
        other => panic!("expected the pair (1, 2) refused, got {other:?}"),
    }
}
