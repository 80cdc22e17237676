//! The solvers against independent truth: every solve passes through its targets;
//! minimality (no perturbation in the constraint's null space lowers Σ‖ε‖²); Eq. 8 equals
//! the general minimum-norm solution; tangents are kept; the cubic allowed region agrees
//! with a brute-force scan of the slides; NUBMP solves land P(τ) on q with parameters on
//! the simplex; projection agrees with dense sampling.

use glam::{DVec2, DVec3};
use nalgebra::DMatrix;
use proptest::prelude::*;
use splinescope_core::geom::bernstein::bernstein_all;
use splinescope_core::geom::cubic_region::PolygonType;
use splinescope_core::geom::{BSpline, Bezier, Curve, Nubmp, ParamCurve};
use splinescope_core::rng::Rng;
use splinescope_core::solve::batch::{BatchResult, BatchSingleTarget};
use splinescope_core::solve::linalg::min_norm_solve;
use splinescope_core::solve::nubmp::{constrained, find_tau};
use splinescope_core::solve::region::cubic_region;
use splinescope_core::solve::shape::{
    SingleTargetOptions, multi_target, single_target, tangent_kept,
};
use splinescope_core::solve::{SolveError, nearest};

fn random_curve(rng: &mut Rng, n: usize, three_d: bool) -> Bezier {
    Bezier::new(
        (0..=n)
            .map(|_| {
                DVec3::new(
                    rng.range(-5.0, 5.0),
                    rng.range(-5.0, 5.0),
                    if three_d { rng.range(-5.0, 5.0) } else { 0.0 },
                )
            })
            .collect(),
    )
}

fn size(b: &Bezier) -> f64 {
    b.control_box().diagonal().max(1.0)
}

fn change_sq(a: &Bezier, b: &Bezier) -> f64 {
    a.points()
        .iter()
        .zip(b.points())
        .map(|(p, q)| (*p - *q).length_squared())
        .sum()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn single_target_passes_through_and_equals_the_general_minimum_norm_solution(
        seed in any::<u64>(), n in 2usize..16, t_s in 0.02..0.98f64, three_d in any::<bool>(),
    ) {
        let mut rng = Rng::new(seed);
        let b = random_curve(&mut rng, n, three_d);
        let target = DVec3::new(rng.range(-6., 6.), rng.range(-6., 6.), if three_d { rng.range(-6., 6.) } else { 0.0 });
        let m = rng.int(1, n - 1);
        let l = rng.int(1, n - m);
        let weight: f64 = bernstein_all(n, t_s)[l..l + m].iter().map(|v| v * v).sum();
        // Windows of negligible Bernstein weight need enormous moves (ill-conditioned).
        prop_assume!(weight > 1e-8);
        let s = single_target(&b, target, &SingleTargetOptions { t_s: Some(t_s), window: Some((l, m)), accuracy: None }).unwrap();
        // Passes through T at t_s.
        prop_assert!(s.residual <= 1e-9 * size(&b), "residual {}", s.residual);
        prop_assert!((s.curve.eval(t_s) - target).length() <= 1e-9 * size(&b));
        // Ends and the points outside the window do not move.
        for i in (0..l).chain(l + m..=n) {
            prop_assert_eq!(s.curve.points()[i], b.points()[i]);
        }
        // Eq. 8 is the minimum-norm solution of Σ ε_i B_i(t_s) = T − S.
        let bern = bernstein_all(n, t_s);
        let a = DMatrix::from_row_slice(1, m, &bern[l..l + m]);
        let diff = target - b.eval(t_s);
        let rhs = DMatrix::from_row_slice(1, 3, &[diff.x, diff.y, diff.z]);
        let general = min_norm_solve(&a, &rhs);
        for k in 0..m {
            let e = s.deltas[k];
            let g = DVec3::new(general.x[(k, 0)], general.x[(k, 1)], general.x[(k, 2)]);
            prop_assert!((e - g).length() <= 1e-9 * g.length().max(diff.length()).max(1.0));
        }
        // Minimality: a perturbation δ with Σ δ_i B_i = 0 keeps the constraint and can only
        // increase Σ‖ε‖².
        if m >= 2 {
            let (i, j) = (rng.int(0, m - 1), rng.int(0, m - 1));
            if i != j && bern[l + j] > 1e-12 {
                let v = DVec3::new(rng.range(-1., 1.), rng.range(-1., 1.), rng.range(-1., 1.));
                let mut perturbed: Vec<DVec3> = s.deltas.clone();
                perturbed[i] += v * 1e-3;
                perturbed[j] -= v * 1e-3 * bern[l + i] / bern[l + j];
                let base: f64 = s.deltas.iter().map(|e| e.length_squared()).sum();
                let other: f64 = perturbed.iter().map(|e| e.length_squared()).sum();
                prop_assert!(other >= base - 1e-15 * base.max(1.0));
            }
        }
    }

    #[test]
    fn tangent_kept_passes_through_keeps_tangents_and_is_minimal(
        seed in any::<u64>(), n in 4usize..14, t_s in 0.05..0.95f64, three_d in any::<bool>(),
    ) {
        let mut rng = Rng::new(seed);
        let b = random_curve(&mut rng, n, three_d);
        let target = DVec3::new(rng.range(-6., 6.), rng.range(-6., 6.), if three_d { rng.range(-6., 6.) } else { 0.0 });
        let s = tangent_kept(&b, target, Some(t_s), None).unwrap();
        prop_assert!(!s.least_squares);
        prop_assert!(s.residual <= 1e-9 * size(&b), "residual {}", s.residual);
        let (p, q) = (b.points(), s.curve.points());
        prop_assert_eq!(q[0], p[0]);
        prop_assert_eq!(q[n], p[n]);
        // P'_1 stays on the line P0P1, P'_(n-1) on PnP(n-1).
        let e1 = (p[1] - p[0]).normalize();
        let e2 = (p[n - 1] - p[n]).normalize();
        prop_assert!((q[1] - p[0]).cross(e1).length() <= 1e-9 * size(&b));
        prop_assert!((q[n - 1] - p[n]).cross(e2).length() <= 1e-9 * size(&b));
        // Minimality: the objective is ‖x‖² of the min-norm solution; compare with a
        // feasible alternative (the solution plus a null-space direction of the system).
        let bern = bernstein_all(n, t_s);
        if bern[2] > 1e-9 {
            // Shift μ1 by δ and compensate with ε_2 (one null-space direction).
            let delta = 1e-3;
            let mut eps2 = s.deltas[0];
            eps2 -= delta * bern[1] / bern[2] * e1;
            let base = s.mu[0].powi(2) + s.mu[1].powi(2) + s.deltas.iter().map(|e| e.length_squared()).sum::<f64>();
            let other = (s.mu[0] + delta).powi(2) + s.mu[1].powi(2) + eps2.length_squared()
                + s.deltas[1..].iter().map(|e| e.length_squared()).sum::<f64>();
            prop_assert!(other >= base - 1e-12 * base.max(1.0));
        }
    }

    #[test]
    fn several_targets_are_met_exactly_when_the_system_allows(
        seed in any::<u64>(), n in 3usize..14, three_d in any::<bool>(),
    ) {
        let mut rng = Rng::new(seed);
        let b = random_curve(&mut rng, n, three_d);
        let count = rng.int(1, n - 1);
        // Distinct parameters, given.
        let mut params: Vec<f64> = (0..count).map(|k| (k as f64 + rng.range(0.2, 0.8)) / count as f64).collect();
        params.sort_by(f64::total_cmp);
        let targets: Vec<DVec3> = params.iter().map(|&t| b.eval(t) + DVec3::new(rng.range(-1., 1.), rng.range(-1., 1.), if three_d { rng.range(-1., 1.) } else { 0.0 })).collect();
        let s = multi_target(&b, &targets, Some(&params), None).unwrap();
        prop_assert!(!s.least_squares);
        for r in &s.residuals {
            prop_assert!(*r <= 1e-9 * size(&b), "residual {}", r);
        }
        // Minimality against a null-space perturbation (exists when count < n − 1).
        if count < n - 1 {
            let mut m = DMatrix::zeros(count, n - 1);
            for (l, &t) in params.iter().enumerate() {
                let bern = bernstein_all(n, t);
                for i in 1..n {
                    m[(l, i - 1)] = bern[i];
                }
            }
            // A null-space vector: a random y minus its projection on the row space.
            let y = DMatrix::from_iterator(n - 1, 1, (0..n - 1).map(|_| rng.range(-1., 1.)));
            let row_part = min_norm_solve(&m, &(&m * &y)).x;
            let null: Vec<f64> = (&y - &row_part).iter().copied().collect();
            let check = &m * DMatrix::from_column_slice(n - 1, 1, &null);
            prop_assert!(check.norm() < 1e-10);
            let dir = DVec3::new(rng.range(-1., 1.), rng.range(-1., 1.), rng.range(-1., 1.));
            let base: f64 = s.deltas.iter().map(|e| e.length_squared()).sum();
            let other: f64 = s.deltas.iter().zip(&null).map(|(e, w)| (*e + 1e-3 * w * dir).length_squared()).sum();
            prop_assert!(other >= base - 1e-12 * base.max(1.0));
        }
    }
}

#[test]
fn eq_8_reproduces_a_hand_computed_cubic_case() {
    // Cubic, t_s = 1/2, window P_1..P_2: B = (1/8, 3/8, 3/8, 1/8), Σ B² over the window =
    // 9/32, so ε_1 = ε_2 = (3/8)/(9/32) (T − S) = (4/3)(T − S).
    let b = Bezier::new(vec![
        DVec3::ZERO,
        DVec3::new(1., 2., 0.),
        DVec3::new(3., 2., 0.),
        DVec3::new(4., 0., 0.),
    ]);
    let target = DVec3::new(2.0, 2.5, 0.0);
    let s = single_target(
        &b,
        target,
        &SingleTargetOptions {
            t_s: Some(0.5),
            window: Some((1, 2)),
            accuracy: None,
        },
    )
    .unwrap();
    let start = b.eval(0.5);
    assert_eq!(start, DVec3::new(2.0, 1.5, 0.0));
    for e in &s.deltas {
        assert!((*e - (4.0 / 3.0) * (target - start)).length() < 1e-15);
    }
}

#[test]
fn default_window_is_the_one_needing_least_movement() {
    let mut rng = Rng::new(3);
    let b = random_curve(&mut rng, 9, false);
    let target = DVec3::new(1.0, 7.0, 0.0);
    let def = single_target(
        &b,
        target,
        &SingleTargetOptions {
            t_s: Some(0.3),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(def.deltas.len(), 3);
    for l in 1..=6 {
        let other = single_target(
            &b,
            target,
            &SingleTargetOptions {
                t_s: Some(0.3),
                window: Some((l, 3)),
                accuracy: None,
            },
        )
        .unwrap();
        assert!(
            change_sq(&def.curve, &b) <= change_sq(&other.curve, &b) + 1e-12,
            "window {l}"
        );
    }
}

#[test]
fn projected_start_parameter_is_the_nearest_point() {
    let mut rng = Rng::new(11);
    let b = random_curve(&mut rng, 5, false);
    let target = b.eval(0.37) + DVec3::new(0.3, -0.2, 0.0);
    let s = single_target(&b, target, &SingleTargetOptions::default()).unwrap();
    let n = nearest(&b, target, None);
    assert_eq!(s.t_s, n.t);
    assert!(s.residual < 1e-12);
}

#[test]
fn cubic_tangent_kept_is_square_in_the_plane_and_least_squares_in_3d() {
    let b = Bezier::new(vec![
        DVec3::ZERO,
        DVec3::new(1., 2., 0.),
        DVec3::new(3., 2., 0.),
        DVec3::new(4., 0., 0.),
    ]);
    let planar = tangent_kept(&b, DVec3::new(2.0, 2.2, 0.0), Some(0.5), None).unwrap();
    assert!(!planar.least_squares && planar.residual < 1e-12);
    // Off the plane: only μ1, μ2 (in the plane) are free; the z error remains.
    let off = tangent_kept(&b, DVec3::new(2.0, 2.2, 0.7), Some(0.5), None).unwrap();
    assert!(off.least_squares);
    assert!((off.residual - 0.7).abs() < 1e-12, "{}", off.residual);
    // The same μ as the planar solve (up to rounding: the systems differ).
    for (o, p) in off.mu.iter().zip(planar.mu) {
        assert!(
            (o - p).abs() <= 1e-12 * p.abs(),
            "{:?} vs {:?}",
            off.mu,
            planar.mu
        );
    }
}

#[test]
fn over_determined_and_repeated_targets_are_solved_in_least_squares() {
    let b = Bezier::new(vec![
        DVec3::ZERO,
        DVec3::new(1., 2., 0.),
        DVec3::new(3., 2., 0.),
        DVec3::new(4., 0., 0.),
    ]);
    // Two targets at the same parameter, different places: rank 1 < 2 conditions.
    let targets = [DVec3::new(2.0, 2.0, 0.0), DVec3::new(2.0, 1.0, 0.0)];
    let s = multi_target(&b, &targets, Some(&[0.5, 0.5]), None).unwrap();
    assert!(s.least_squares);
    assert_eq!(s.rank, 1);
    // The best compromise is their mean.
    assert!((s.curve.eval(0.5) - DVec3::new(2.0, 1.5, 0.0)).length() < 1e-12);
    assert!((s.residuals[0] - 0.5).abs() < 1e-12 && (s.residuals[1] - 0.5).abs() < 1e-12);
    // Three targets on a cubic (two free points): least squares.
    let s = multi_target(
        &b,
        &[
            DVec3::new(1., 1., 0.),
            DVec3::new(2., 2., 0.),
            DVec3::new(3., 1., 0.),
        ],
        Some(&[0.25, 0.5, 0.75]),
        None,
    )
    .unwrap();
    assert!(s.least_squares);
}

#[test]
fn bad_requests_are_typed_errors() {
    let b = Bezier::new(vec![
        DVec3::ZERO,
        DVec3::new(1., 2., 0.),
        DVec3::new(3., 2., 0.),
        DVec3::new(4., 0., 0.),
    ]);
    let o = |t_s, window| SingleTargetOptions {
        t_s,
        window,
        accuracy: None,
    };
    let nan = DVec3::new(f64::NAN, 0., 0.);
    assert!(matches!(
        single_target(&b, nan, &o(Some(0.5), None)),
        Err(SolveError::NonFiniteTarget { .. })
    ));
    assert!(matches!(
        single_target(&b, DVec3::ONE, &o(Some(0.0), None)),
        Err(SolveError::ParameterAtEnd { .. })
    ));
    assert!(matches!(
        single_target(&b, DVec3::ONE, &o(Some(1.5), None)),
        Err(SolveError::ParameterOutsideDomain { .. })
    ));
    assert!(matches!(
        single_target(&b, DVec3::ONE, &o(Some(0.5), Some((0, 2)))),
        Err(SolveError::WindowOutOfRange { .. })
    ));
    assert!(matches!(
        single_target(&b, DVec3::ONE, &o(Some(0.5), Some((2, 2)))),
        Err(SolveError::WindowOutOfRange { .. })
    ));
    // A target beyond the start projects onto the fixed end.
    assert!(matches!(
        single_target(&b, DVec3::new(-3.0, -1.0, 0.0), &o(None, None)),
        Err(SolveError::TargetAtEnd { index: 0, .. })
    ));
    let line = Bezier::new(vec![DVec3::ZERO, DVec3::X]);
    assert!(matches!(
        single_target(&line, DVec3::ONE, &o(Some(0.5), None)),
        Err(SolveError::DegreeTooLow { .. })
    ));
    let quad = Bezier::new(vec![DVec3::ZERO, DVec3::Y, DVec3::X]);
    assert!(matches!(
        tangent_kept(&quad, DVec3::ONE, Some(0.5), None),
        Err(SolveError::DegreeTooLow { min: 3, .. })
    ));
    assert!(matches!(
        multi_target(&b, &[], None, None),
        Err(SolveError::NoTargets)
    ));
    assert!(matches!(
        multi_target(&b, &[DVec3::ONE], Some(&[0.2, 0.3]), None),
        Err(SolveError::ParamCount { .. })
    ));
}

// ---------- cubic allowed region ----------

/// Brute force: is T = (B0+B1)P0 + (B2+B3)P3 + s B1 e1 + r B2 e2 for some t on a fine grid
/// and s, r ≥ 0 (≤ the limits)? A 2×2 solve per t; for parallel legs, the parameter where
/// T − base is parallel to the legs is bracketed on the grid.
fn brute_reachable(
    p0: DVec3,
    p3: DVec3,
    e1: DVec3,
    e2: DVec3,
    t: DVec3,
    limits: Option<(f64, f64)>,
) -> bool {
    let (e1, e2) = (DVec2::new(e1.x, e1.y), DVec2::new(e2.x, e2.y));
    if e1.perp_dot(e2).abs() < 1e-12 {
        let side = |u: f64| {
            let b = bernstein_all(3, u);
            let base = (b[0] + b[1]) * p0 + (b[2] + b[3]) * p3;
            DVec2::new(t.x - base.x, t.y - base.y)
        };
        for k in 1..20_000 {
            let (u0, u1) = (f64::from(k - 1) / 20_000.0, f64::from(k) / 20_000.0);
            let (c0, c1) = (side(u0).perp_dot(e1), side(u1).perp_dot(e1));
            if k > 1 && c0.signum() != c1.signum() {
                // Along the legs: s B1 + r B2 (same direction) must be ≥ 0; any (opposite).
                let along = side(u1).dot(e1);
                return e1.dot(e2) < 0.0 || along >= 0.0;
            }
        }
        return false;
    }
    for k in 1..20_000 {
        let u = f64::from(k) / 20_000.0;
        let b = bernstein_all(3, u);
        let base = (b[0] + b[1]) * p0 + (b[2] + b[3]) * p3;
        let w = DVec2::new(t.x - base.x, t.y - base.y);
        let (a1, a2) = (b[1] * e1, b[2] * e2);
        let det = a1.perp_dot(a2);
        if det.abs() < 1e-14 {
            continue;
        }
        let s = w.perp_dot(a2) / det;
        let r = a1.perp_dot(w) / det;
        let ok = s >= 0.0 && r >= 0.0 && limits.is_none_or(|(sm, rm)| s <= sm && r <= rm);
        if ok {
            return true;
        }
    }
    false
}

#[test]
fn cubic_reachability_agrees_with_a_brute_force_scan() {
    let mut rng = Rng::new(2026);
    let mut counts = [[0usize; 2]; 3];
    for case in 0..90 {
        let mut pts: Vec<DVec3> = (0..4)
            .map(|_| DVec3::new(rng.range(-4., 4.), rng.range(-4., 4.), 0.0))
            .collect();
        // Every third polygon gets parallel legs (type 1), either way round.
        if case % 3 == 0 {
            let sign = if case % 2 == 0 { 1.0 } else { -1.0 };
            pts[2] = pts[3] + sign * rng.range(0.3, 1.5) * (pts[1] - pts[0]);
        }
        let b = Bezier::new(pts.clone());
        let region = cubic_region(&b).unwrap();
        let (e1, e2) = (region.e1, region.e2);
        for _ in 0..40 {
            let t = DVec3::new(rng.range(-8., 8.), rng.range(-8., 8.), 0.0);
            // Skip targets within a small margin of the boundary (grid resolution).
            let near_boundary = [
                t + DVec3::X * 0.02,
                t - DVec3::X * 0.02,
                t + DVec3::Y * 0.02,
                t - DVec3::Y * 0.02,
            ]
            .iter()
            .any(|&q| region.contains(q) != region.contains(t));
            if near_boundary {
                continue;
            }
            let want = brute_reachable(pts[0], pts[3], e1, e2, t, None);
            assert_eq!(region.contains(t), want, "{:?} target {t}", region.kind);
            counts[(region.kind.number() - 1) as usize][usize::from(want)] += 1;
        }
    }
    // Every type met, with targets inside and outside.
    for (k, c) in counts.iter().enumerate() {
        assert!(c[0] > 0 && c[1] > 0, "type {}: {c:?}", k + 1);
    }
}

#[test]
fn parallel_legs_give_a_strip_or_half_strip() {
    // U shape (legs point the same way): a half-strip above the segment.
    let u = Bezier::new(vec![
        DVec3::ZERO,
        DVec3::new(0., 1., 0.),
        DVec3::new(3., 1., 0.),
        DVec3::new(3., 0., 0.),
    ]);
    let r = cubic_region(&u).unwrap();
    assert_eq!(r.kind, PolygonType::Parallel);
    assert!(r.contains(DVec3::new(1.5, 100.0, 0.0)));
    assert!(!r.contains(DVec3::new(1.5, -0.5, 0.0)));
    assert!(!r.contains(DVec3::new(3.5, 1.0, 0.0)));
    // Z shape (legs opposite): the whole strip.
    let z = Bezier::new(vec![
        DVec3::ZERO,
        DVec3::new(0., 1., 0.),
        DVec3::new(3., -1., 0.),
        DVec3::new(3., 0., 0.),
    ]);
    let r = cubic_region(&z).unwrap();
    assert!(r.contains(DVec3::new(1.5, -50.0, 0.0)) && r.contains(DVec3::new(1.5, 50.0, 0.0)));
    assert!(!r.contains(DVec3::new(-0.5, 1.0, 0.0)));
}

#[test]
fn limited_type_2_region_is_bounded_by_the_apex_cubic() {
    let b = Bezier::new(vec![
        DVec3::ZERO,
        DVec3::new(1., 1., 0.),
        DVec3::new(3., 1., 0.),
        DVec3::new(4., 0., 0.),
    ]);
    let r = cubic_region(&b).unwrap();
    let PolygonType::Converging { apex } = r.kind else {
        panic!("type 2 expected")
    };
    let limits = Some(((apex - r.p0).length(), (apex - r.p3).length()));
    let mut rng = Rng::new(8);
    let mut inside = 0;
    for _ in 0..400 {
        let t = DVec3::new(rng.range(-0.5, 4.5), rng.range(-0.5, 2.5), 0.0);
        let margin = [
            t + DVec3::X * 0.01,
            t - DVec3::X * 0.01,
            t + DVec3::Y * 0.01,
            t - DVec3::Y * 0.01,
        ]
        .iter()
        .any(|&q| r.contains_limited(q) != r.contains_limited(t));
        if margin {
            continue;
        }
        let want = brute_reachable(r.p0, r.p3, r.e1, r.e2, t, limits);
        assert_eq!(r.contains_limited(t), Some(want), "target {t}");
        inside += usize::from(want);
    }
    assert!(inside > 20);
    // The apex cubic's midpoint is the farthest reachable point on the axis.
    let peak = Bezier::new(vec![r.p0, apex, apex, r.p3]).eval(0.5);
    assert_eq!(r.contains_limited(peak - DVec3::Y * 1e-3), Some(true));
    assert_eq!(r.contains_limited(peak + DVec3::Y * 1e-3), Some(false));
}

// ---------- projection ----------

#[test]
fn projection_agrees_with_dense_sampling_for_every_family() {
    let mut rng = Rng::new(21);
    let pts: Vec<DVec3> = (0..8)
        .map(|_| DVec3::new(rng.range(-5., 5.), rng.range(-5., 5.), 0.0))
        .collect();
    let curves = vec![
        Curve::Bezier(Bezier::new(pts.clone())),
        Curve::BSpline(
            BSpline::try_new(
                pts.clone(),
                vec![0., 0., 0., 0., 0.2, 0.4, 0.7, 0.9, 1., 1., 1., 1.],
                4,
            )
            .unwrap(),
        ),
        Curve::Nubmp(
            Nubmp::try_new(
                pts.clone(),
                vec![0., 0., 0., 0.2, 0.3, 0.35, 0.6, 0.8, 1., 1., 1.],
                3,
            )
            .unwrap(),
        ),
    ];
    for c in &curves {
        let (a, b) = c.domain();
        for _ in 0..30 {
            let q = DVec3::new(rng.range(-7., 7.), rng.range(-7., 7.), 0.0);
            let n = nearest(c, q, None);
            let mut brute = f64::INFINITY;
            for k in 0..=50_000 {
                let t = a + (b - a) * f64::from(k) / 50_000.0;
                brute = brute.min((c.eval(t) - q).length());
            }
            assert!(
                n.distance <= brute + 1e-12,
                "{}: {} > {brute}",
                c.family(),
                n.distance
            );
            assert!((c.eval(n.t) - n.point).length() < 1e-15);
            // First-order optimality: (P − q)·P′ = 0 unless at an end of the domain.
            if n.t > a && n.t < b {
                let g = (n.point - q).dot(c.eval_deriv(n.t));
                assert!(
                    g.abs() <= 1e-7 * c.eval_deriv(n.t).length().max(1.0),
                    "{}: g = {g}",
                    c.family()
                );
            }
        }
    }
}

// ---------- NUBMP ----------

fn paper_nubmp() -> Nubmp {
    let pts = [
        (0., -1.),
        (0.5, 2.),
        (2., 2.8),
        (3., 0.2),
        (4., 2.8),
        (5.5, 2.),
        (6., -1.),
    ]
    .map(|(x, y)| DVec3::new(x, y, 0.0));
    Nubmp::try_new(
        pts.to_vec(),
        vec![0., 0., 0., 0., 0.3, 0.5, 0.89, 1., 1., 1., 1.],
        4,
    )
    .unwrap()
}

#[test]
fn constrained_solves_land_on_q_with_parameters_on_the_simplex() {
    let n = paper_nubmp();
    let mut rng = Rng::new(5);
    let mut solved = 0;
    for _ in 0..200 {
        let tau = rng.range(0.01, 0.99);
        let groups = n.groups_at(tau);
        let j = groups[rng.int(0, groups.len() - 1)];
        let region = n.reachable_region(tau, j).unwrap();
        // A random point of the region (barycentric weights).
        let raw: Vec<f64> = region.iter().map(|_| rng.range(0.0, 1.0)).collect();
        let total: f64 = raw.iter().sum();
        let q: DVec3 = region.iter().zip(&raw).map(|(v, w)| *v * (w / total)).sum();
        let s = constrained(&n, tau, j, q, false).unwrap();
        assert!(s.residual <= 1e-9, "residual {}", s.residual);
        assert!((s.curve.eval(tau) - q).length() <= 1e-9);
        assert!(s.values.iter().all(|&v| v >= 0.0));
        assert!((s.values.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        // Only group j changed.
        for (h, g) in s.curve.groups().iter().enumerate() {
            if h != j {
                assert_eq!(g.values, n.groups()[h].values);
            }
        }
        solved += 1;
    }
    assert_eq!(solved, 200);
}

#[test]
fn q_outside_the_region_is_an_error_with_its_distance() {
    let n = paper_nubmp();
    let tau = 0.42;
    let j = n.groups_at(tau)[0];
    let region = n.reachable_region(tau, j).unwrap();
    let far = region[0] + DVec3::new(0.0, 50.0, 0.0);
    match constrained(&n, tau, j, far, false) {
        Err(SolveError::OutsideRegion {
            group, distance, ..
        }) => {
            assert_eq!(group, j);
            assert!(distance > 1.0);
        }
        other => panic!("{other:?}"),
    }
    // A group that does not touch τ.
    let inactive = (0..n.groups().len())
        .find(|g| !n.groups_at(tau).contains(g))
        .unwrap();
    assert!(matches!(
        constrained(&n, tau, inactive, far, false),
        Err(SolveError::GroupInactive { .. })
    ));
    assert!(matches!(
        constrained(&n, 1.5, j, far, false),
        Err(SolveError::ParameterOutsideDomain { .. })
    ));
}

#[test]
fn respecting_vd_refuses_targets_that_break_theorem_1() {
    let n = paper_nubmp();
    // Group 4 = {2, 3}: a^2_4 = 0.05 is below its permissible minimum 0.1254.
    let tau = 0.4;
    let mut m = n.clone();
    m.set_parameter(4, 2, 0.05, 3).unwrap();
    let q = m.eval(tau);
    assert!(constrained(&n, tau, 4, q, false).is_ok());
    assert!(matches!(
        constrained(&n, tau, 4, q, true),
        Err(SolveError::BreaksVd { group: 5, .. })
    ));
}

#[test]
fn find_tau_returns_parameters_where_the_constrained_solve_succeeds() {
    let n = paper_nubmp();
    // A point reached by changing group 3 (three members: a triangle path) at τ = 0.25.
    let mut m = n.clone();
    m.set_group(3, &[0.3, 0.5, 0.2]).unwrap();
    let q = m.eval(0.25);
    let found = find_tau(&n, 3, q).unwrap();
    assert!(
        found
            .intervals
            .iter()
            .any(|&(a, b)| a <= 0.25 + 1e-6 && b >= 0.25 - 1e-6),
        "{found:?}"
    );
    let s = constrained(&n, found.best, 3, q, false).unwrap();
    assert!(s.residual < 1e-9);
    // A group of two in the plane: q lies on segment paths at isolated τ.
    let mut m = n.clone();
    m.set_parameter(4, 2, 0.3, 3).unwrap();
    let q = m.eval(0.45);
    let found = find_tau(&n, 4, q).unwrap();
    let s = constrained(&n, found.best, 4, q, false).unwrap();
    assert!(s.residual < 1e-7, "{found:?} {}", s.residual);
    assert!(matches!(
        find_tau(&n, 4, DVec3::new(0.0, 40.0, 0.0)),
        Err(SolveError::NoTau { .. })
    ));
}

// ---------- batch ----------

#[test]
fn the_batch_solver_equals_single_solves() {
    let mut rng = Rng::new(17);
    for degree in [2usize, 3, 5, 7] {
        let curves: Vec<Bezier> = (0..500)
            .map(|_| {
                let three_d = rng.int(0, 1) == 1;
                random_curve(&mut rng, degree, three_d)
            })
            .collect();
        let targets: Vec<DVec3> = curves
            .iter()
            .map(|c| c.eval(0.5) + DVec3::new(rng.range(-1., 1.), rng.range(-1., 1.), 0.0))
            .collect();
        let ts: Vec<f64> = (0..500).map(|_| rng.range(0.05, 0.95)).collect();
        let flat: Vec<DVec3> = curves.iter().flat_map(|c| c.points().to_vec()).collect();
        let batch = BatchSingleTarget::new(degree).unwrap();
        let mut out = vec![DVec3::ZERO; flat.len()];
        let mut results = vec![BatchResult::default(); 500];
        batch.solve(&flat, &targets, Some(&ts), &mut out, &mut results);
        for (c, curve) in curves.iter().enumerate() {
            let single = single_target(
                curve,
                targets[c],
                &SingleTargetOptions {
                    t_s: Some(ts[c]),
                    ..Default::default()
                },
            )
            .unwrap();
            for (k, p) in single.curve.points().iter().enumerate() {
                assert!((out[c * (degree + 1) + k] - *p).length() < 1e-12);
            }
            assert!(results[c].solved && results[c].residual < 1e-9);
        }
        // Projected start parameters: the batch's sampled projection finds the nearest point.
        batch.solve(&flat, &targets, None, &mut out, &mut results);
        for (c, curve) in curves.iter().enumerate() {
            let n = nearest(curve, targets[c], None);
            let r = results[c];
            assert!(
                (curve.eval(r.t_s) - targets[c]).length() <= n.distance + 1e-9,
                "curve {c}"
            );
        }
    }
}
