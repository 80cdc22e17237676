//! The curve families of papers 001 and 002 against independent truth: the papers'
//! printed examples, exact rational arithmetic with an independent (recursive) Cox–de Boor,
//! and invariants (knot insertion, Bézier extraction and degree elevation do not move the
//! curve; NUBMP with standard parameters is the B-spline; both NUBMP evaluations agree).

use glam::DVec3;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};
use proptest::prelude::*;
use splinescope_core::geom::bspline::refine_knots;
use splinescope_core::geom::exact::{format_rational, parse_decimal};
use splinescope_core::geom::modified::bump;
use splinescope_core::geom::{
    BSpline, Bezier, CubicInterpolation, Curve, GeomError, KnotVector, Lower, Modification,
    ModifiedBezier, Nubmp, ParamCurve, Reading, locate,
};
use splinescope_core::rng::Rng;

type Q = BigRational;

fn p2(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

// ---------- paper 002 ----------

fn example_points() -> Vec<DVec3> {
    vec![p2(0., 0.), p2(0., 6.), p2(6., 6.), p2(6., 0.)]
}

fn assert_piece(c: &CubicInterpolation, piece: usize, f: impl Fn(f64) -> (f64, f64)) {
    for k in 0..=50 {
        let u = f64::from(k) / 50.0;
        let want = f(u);
        let t = c.params()[piece] + u * (c.params()[piece + 1] - c.params()[piece]);
        let got = c.eval(t);
        assert!(
            (got.x - want.0).abs() < 1e-12 && (got.y - want.1).abs() < 1e-12,
            "piece {} u={u}: {got} vs {want:?}",
            piece + 1
        );
    }
}

#[test]
fn paper_002_example_1_polynomials() {
    let c =
        CubicInterpolation::try_new(example_points(), Some(vec![0., 1., 2., 3.]), None).unwrap();
    // Printed polynomials (the OCR's leading minus on the x of Q2, Q3 is an artifact).
    assert_piece(&c, 0, |u| (-3.0 * u * (1.0 - u), 3.0 * u * (3.0 - u)));
    assert_piece(&c, 1, |u| {
        (
            3.0 * u * (-2.0 * u * u + 3.0 * u + 1.0),
            3.0 * (-u * u + u + 2.0),
        )
    });
    assert_piece(&c, 2, |u| {
        (3.0 * (-u * u + u + 2.0), 3.0 * (1.0 - u) * (u + 2.0))
    });
    // Tangents: s_0 = −3/2 P0 + 2 P1 − 1/2 P2, s_1 = (P2 − P0)/2 (paper's Example 1).
    let p = example_points();
    assert_eq!(c.tangents()[0], -1.5 * p[0] + 2.0 * p[1] - 0.5 * p[2]);
    assert_eq!(c.tangents()[1], 0.5 * (p[2] - p[0]));
}

#[test]
fn paper_002_example_2_polynomials() {
    let m = Modification {
        t_star: 0.5,
        v: p2(0.0, 0.75),
        reading: Reading::Paper,
    };
    let c =
        CubicInterpolation::try_new(example_points(), Some(vec![0., 1., 2., 3.]), Some(m)).unwrap();
    assert_piece(&c, 0, |u| {
        (-3.0 * u * (1.0 - u), 6.0 * u * (1.0 + u - u * u))
    });
    assert_piece(&c, 1, |u| {
        (
            3.0 * u * (-2.0 * u * u + 3.0 * u + 1.0),
            6.0 * (1.0 + u * u - u * u * u),
        )
    });
    assert_piece(&c, 2, |u| {
        (
            3.0 * (-u * u + u + 2.0),
            6.0 * (1.0 - u + u * u - u * u * u),
        )
    });
    // The paper notes that P̃_{3−2/3} and P̃_{3−1/3} coincide at (7, 4).
    assert_eq!(c.pieces()[2].points()[1], c.pieces()[2].points()[2]);
}

fn central_diff(c: &dyn ParamCurve, t: f64, side: f64) -> DVec3 {
    // One-sided second-order difference: side = −1 from the left, +1 from the right.
    let h = 1e-5 * side;
    (-3.0 * c.eval(t) + 4.0 * c.eval(t + h) - c.eval(t + 2.0 * h)) / (2.0 * h)
}

#[test]
fn both_readings_are_c1_with_their_stated_joint_tangents() {
    let pts = vec![p2(0., 0.), p2(1., 3.), p2(4., 4.), p2(6., 1.), p2(8., 2.)];
    let params = vec![0.0, 1.0, 1.7, 3.0, 3.4];
    for &t_star in &[0.2, 0.5, 0.8] {
        let v = p2(0.4, -0.3);
        for reading in [Reading::Paper, Reading::BumpAdded] {
            let m = Modification { t_star, v, reading };
            let c =
                CubicInterpolation::try_new(pts.clone(), Some(params.clone()), Some(m)).unwrap();
            let plain =
                CubicInterpolation::try_new(pts.clone(), Some(params.clone()), None).unwrap();
            for (i, &t) in params.iter().enumerate() {
                assert!((c.eval(t) - pts[i]).length() < 1e-12, "interpolates P_{i}");
                let want = match reading {
                    Reading::Paper => plain.tangents()[i] - (2.0 / t_star) * v,
                    Reading::BumpAdded => plain.tangents()[i],
                };
                if i > 0 {
                    let left = central_diff(&c, t, -1.0);
                    assert!(
                        (left - want).length() < 1e-6,
                        "{reading:?} t*={t_star} left of P_{i}: {left} vs {want}"
                    );
                }
                if i + 1 < params.len() {
                    let right = central_diff(&c, t, 1.0);
                    assert!(
                        (right - want).length() < 1e-6,
                        "{reading:?} t*={t_star} right of P_{i}"
                    );
                }
            }
            // The lowering is the same curve.
            let segs = c.lower();
            for k in 0..=400 {
                let t = 3.4 * f64::from(k) / 400.0;
                let (s, u) = locate(&segs, t).unwrap();
                assert!((segs[s].bezier.eval(u) - c.eval(t)).length() < 1e-12);
            }
        }
    }
}

#[test]
fn two_points_interpolate_with_a_straight_cubic() {
    let c = CubicInterpolation::try_new(vec![p2(0., 0.), p2(3., 6.)], None, None).unwrap();
    for k in 0..=10 {
        let t = f64::from(k) / 10.0;
        assert!((c.eval(t) - p2(3.0 * t, 6.0 * t)).length() < 1e-14);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(100))]
    #[test]
    fn modified_bezier_lowering_is_exact(seed in any::<u64>(), n in 1usize..12, t_star in 0.02..0.98f64) {
        let mut rng = Rng::new(seed);
        let pts: Vec<DVec3> = (0..=n).map(|_| DVec3::new(rng.range(-5., 5.), rng.range(-5., 5.), rng.range(-5., 5.))).collect();
        let v = DVec3::new(rng.range(-3., 3.), rng.range(-3., 3.), rng.range(-3., 3.));
        let r = ModifiedBezier::try_new(Bezier::new(pts.clone()), t_star, v).unwrap();
        let segs = r.lower();
        prop_assert_eq!(segs.len(), 2);
        prop_assert_eq!(segs[0].bezier.degree(), n.max(2));
        for k in 0..=300 {
            let t = f64::from(k) / 300.0;
            let want = Bezier::new(pts.clone()).eval(t) + bump(t, t_star) * v;
            let (s, u) = locate(&segs, t).unwrap();
            prop_assert!((segs[s].bezier.eval(u) - want).length() < 1e-11);
            prop_assert!((r.eval(t) - want).length() < 1e-13);
        }
    }
}

// ---------- B-splines: exact references ----------

/// N_{i,k}(t) by the recursive definition, exactly (0/0 = 0). Independent of the library's
/// triangular Cox–de Boor.
fn cox_de_boor(knots: &[Q], i: usize, k: usize, t: &Q) -> Q {
    if k == 1 {
        return if knots[i] <= *t && *t < knots[i + 1] {
            Q::from_integer(1.into())
        } else {
            Q::zero()
        };
    }
    let mut s = Q::zero();
    let d1 = &knots[i + k - 1] - &knots[i];
    if !d1.is_zero() {
        s += (t - &knots[i]) / d1 * cox_de_boor(knots, i, k - 1, t);
    }
    let d2 = &knots[i + k] - &knots[i + 1];
    if !d2.is_zero() {
        s += (&knots[i + k] - t) / d2 * cox_de_boor(knots, i + 1, k - 1, t);
    }
    s
}

fn decimals(ks: &[&str]) -> Vec<Q> {
    ks.iter().map(|s| parse_decimal(s).unwrap()).collect()
}

fn span_midpoints(knots: &[Q]) -> Vec<Q> {
    knots
        .windows(2)
        .filter(|w| w[0] < w[1])
        .flat_map(|w| {
            let d = &w[1] - &w[0];
            [1, 2, 3].map(|n| &w[0] + &d * Q::new(BigInt::from(n), BigInt::from(4)))
        })
        .collect()
}

const PAPER_KNOTS: [&str; 11] = ["0", "0", "0", "0", "0.3", "0.5", "0.89", "1", "1", "1", "1"];

#[test]
fn bspline_values_match_exact_cox_de_boor() {
    let kq = decimals(&PAPER_KNOTS);
    let kf: Vec<f64> = kq.iter().map(|q| q.to_f64().unwrap()).collect();
    let pts: Vec<DVec3> = [(0, 0), (1, 3), (2, -1), (4, 5), (5, 0), (7, 2), (8, -3)]
        .map(|(x, y)| p2(f64::from(x), f64::from(y)))
        .to_vec();
    let b = BSpline::try_new(pts.clone(), kf, 4).unwrap();
    for t in span_midpoints(&kq) {
        let mut want = [Q::zero(), Q::zero()];
        for (i, p) in pts.iter().enumerate() {
            let n = cox_de_boor(&kq, i, 4, &t);
            want[0] += &n * Q::from_float(p.x).unwrap();
            want[1] += &n * Q::from_float(p.y).unwrap();
        }
        let got = b.eval(t.to_f64().unwrap());
        assert!((got.x - want[0].to_f64().unwrap()).abs() < 1e-13, "t={t}");
        assert!((got.y - want[1].to_f64().unwrap()).abs() < 1e-13, "t={t}");
    }
}

#[test]
fn uniform_cubic_bspline_matches_its_closed_form() {
    // On uniform knots the cubic B-spline basis on a span is
    // ((1−u)³, 3u³ − 6u² + 4, −3u³ + 3u² + 3u + 1, u³) / 6.
    let kv: Vec<f64> = (0..10).map(f64::from).collect();
    let pts: Vec<DVec3> = (0..6)
        .map(|i| p2(f64::from(i * i), f64::from(3 - i)))
        .collect();
    let b = BSpline::try_new(pts.clone(), kv, 4).unwrap();
    for span in 3..6 {
        for k in 0..8 {
            let u = f64::from(k) / 8.0;
            let w = [
                (1.0 - u).powi(3) / 6.0,
                (3.0 * u.powi(3) - 6.0 * u * u + 4.0) / 6.0,
                (-3.0 * u.powi(3) + 3.0 * u * u + 3.0 * u + 1.0) / 6.0,
                u.powi(3) / 6.0,
            ];
            let want: DVec3 = (0..4).map(|r| w[r] * pts[span - 3 + r]).sum();
            assert!((b.eval(span as f64 + u) - want).length() < 1e-13);
        }
    }
}

#[test]
fn elevation_coefficients_are_exact_on_the_papers_knots() {
    let kq = decimals(&PAPER_KNOTS);
    let kf: Vec<f64> = kq.iter().map(|q| q.to_f64().unwrap()).collect();
    let knots = KnotVector::try_new(kf, 4, 7)
        .unwrap()
        .with_exact(kq.clone());
    let pts: Vec<DVec3> = (0..7).map(|i| p2(f64::from(i), 0.0)).collect();
    let n = Nubmp::standard(pts, knots).expect("finite");
    let e = n.exact_coefficients();
    // T* computed here independently: every distinct knot once more.
    let mut refined: Vec<Q> = Vec::new();
    for (idx, t) in kq.iter().enumerate() {
        refined.push(t.clone());
        if kq.get(idx + 1) != Some(t) {
            refined.push(t.clone());
        }
    }
    assert_eq!(e.refined, refined);
    assert_eq!(refine_knots(&kq), refined);
    // N_{i,4}(t) = Σ_j c^i_j N*_{j,5}(t), exactly, inside every span.
    for t in span_midpoints(&kq) {
        for (i, row) in e.rows.iter().enumerate() {
            let lhs = cox_de_boor(&kq, i, 4, &t);
            let mut rhs = Q::zero();
            for (jj, c) in row.values.iter().enumerate() {
                rhs += c * cox_de_boor(&refined, row.first + jj, 5, &t);
            }
            assert_eq!(lhs, rhs, "i={i} t={t}");
        }
    }
    // Non-negative, and each group sums to exactly 1.
    let n_star = refined.len() - 5;
    let mut sums = vec![Q::zero(); n_star];
    for row in &e.rows {
        for (jj, c) in row.values.iter().enumerate() {
            assert!(*c > Q::zero(), "c must be positive inside its range");
            sums[row.first + jj] += c;
        }
    }
    for (j, s) in sums.iter().enumerate() {
        assert_eq!(*s, Q::from_integer(1.into()), "group {j}");
    }
    // The values of paper 001's example: c^1_j for j = 1, 2, 3 is 3/4, 7/10, 1/10.
    let shown: Vec<String> = e.rows[1].values.iter().map(format_rational).collect();
    assert_eq!(shown, vec!["3/4", "7/10", "1/10"]);
}

// ---------- random splines for property tests ----------

struct RandomSpline {
    points: Vec<DVec3>,
    knots: Vec<f64>,
    order: usize,
}

fn random_spline(seed: u64) -> RandomSpline {
    let mut rng = Rng::new(seed);
    let order = rng.int(2, 6);
    let clamped = rng.int(0, 1) == 0;
    let mut interior = Vec::new();
    let distinct = rng.int(0, 5);
    let mut t = 0.0;
    for _ in 0..distinct {
        t += rng.range(0.05, 1.0);
        let mult = rng.int(1, order - 1);
        interior.extend(std::iter::repeat_n(t, mult));
    }
    let end = t + rng.range(0.05, 1.0);
    let knots: Vec<f64> = if clamped {
        let mut k = vec![0.0; order];
        k.extend(&interior);
        k.extend(std::iter::repeat_n(end, order));
        k
    } else {
        // Distinct knots beyond both ends.
        let mut k: Vec<f64> = (1..order).rev().map(|i| -0.3 * i as f64).collect();
        k.push(0.0);
        k.extend(&interior);
        k.push(end);
        k.extend((1..order).map(|i| end + 0.4 * i as f64));
        k
    };
    let n = knots.len() - order;
    let three_d = rng.int(0, 1) == 1;
    let points = (0..n)
        .map(|_| {
            DVec3::new(
                rng.range(-10., 10.),
                rng.range(-10., 10.),
                if three_d { rng.range(-10., 10.) } else { 0.0 },
            )
        })
        .collect();
    RandomSpline {
        points,
        knots,
        order,
    }
}

fn dense(domain: (f64, f64)) -> impl Iterator<Item = f64> {
    (0..=500).map(move |k| domain.0 + (domain.1 - domain.0) * f64::from(k) / 500.0)
}

fn scale(points: &[DVec3]) -> f64 {
    points.iter().map(|p| p.length()).fold(1.0, f64::max)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(150))]

    #[test]
    fn knot_insertion_does_not_move_the_curve(seed in any::<u64>(), f in 0.0..1.0f64) {
        let s = random_spline(seed);
        let b = BSpline::try_new(s.points.clone(), s.knots.clone(), s.order).unwrap();
        let (a, e) = b.domain();
        let t = a + f * (e - a);
        // A new knot value always inserts; an existing one up to its maximum multiplicity.
        let ins = match b.insert_knot(t) {
            Ok(ins) => ins,
            Err(e) => {
                prop_assert!(b.knots().multiplicity(t) > 0, "inserting {} failed: {}", t, e);
                return Ok(());
            }
        };
        prop_assert_eq!(ins.points().len(), b.points().len() + 1);
        for x in dense((a, e)) {
            prop_assert!((ins.eval(x) - b.eval(x)).length() <= 1e-12 * scale(&s.points));
        }
    }

    #[test]
    fn bezier_extraction_does_not_move_the_curve(seed in any::<u64>()) {
        let s = random_spline(seed);
        let b = BSpline::try_new(s.points.clone(), s.knots.clone(), s.order).unwrap();
        let segs = b.lower();
        prop_assert_eq!(segs.len(), b.knots().breakpoints().len() - 1);
        for seg in &segs {
            prop_assert_eq!(seg.bezier.degree(), s.order - 1);
        }
        for x in dense(b.domain()) {
            let (i, u) = locate(&segs, x).unwrap();
            prop_assert!((segs[i].bezier.eval(u) - b.eval(x)).length() <= 1e-12 * scale(&s.points));
        }
    }

    #[test]
    fn degree_elevation_does_not_move_the_curve(seed in any::<u64>()) {
        let s = random_spline(seed);
        let b = BSpline::try_new(s.points.clone(), s.knots.clone(), s.order).unwrap();
        let e = b.elevate();
        prop_assert_eq!(e.order(), s.order + 1);
        let refined = refine_knots(&s.knots);
        prop_assert_eq!(e.knots().knots(), refined.as_slice());
        for x in dense(b.domain()) {
            prop_assert!((e.eval(x) - b.eval(x)).length() <= 1e-12 * scale(&s.points));
        }
    }

    #[test]
    fn nubmp_standard_is_the_bspline_and_random_parameters_agree_both_ways(seed in any::<u64>()) {
        let s = random_spline(seed);
        let b = BSpline::try_new(s.points.clone(), s.knots.clone(), s.order).unwrap();
        let mut n = Nubmp::try_new(s.points.clone(), s.knots.clone(), s.order).unwrap();
        for x in dense(b.domain()) {
            prop_assert!((n.eval(x) - b.eval(x)).length() <= 1e-12 * scale(&s.points));
        }
        // Coefficients: non-negative; effective groups sum to 1 (clamped or not).
        for g in n.groups() {
            prop_assert!(g.standard.iter().all(|&c| c >= 0.0));
            if g.effective {
                let sum: f64 = g.standard.iter().sum();
                prop_assert!((sum - 1.0).abs() < 1e-12, "group sums to {}", sum);
            }
        }
        // Random valid parameters on every effective group.
        let mut rng = Rng::new(seed ^ 0x5eed);
        for j in 0..n.groups().len() {
            let g = &n.groups()[j];
            if !g.effective {
                continue;
            }
            let raw: Vec<f64> = g.members.iter().map(|_| rng.range(0.01, 1.0)).collect();
            let total: f64 = raw.iter().sum();
            let values: Vec<f64> = raw.iter().map(|r| r / total).collect();
            n.set_group(j, &values).unwrap();
        }
        for x in dense(b.domain()) {
            prop_assert!((n.eval(x) - n.eval_by_basis(x)).length() <= 1e-12 * scale(&s.points));
            let basis_sum: f64 = n.basis(x).iter().map(|&(_, w)| w).sum();
            prop_assert!((basis_sum - 1.0).abs() < 1e-12);
        }
        // The lowering is the same curve.
        let segs = n.lower();
        for x in dense(b.domain()) {
            let (i, u) = locate(&segs, x).unwrap();
            prop_assert!((segs[i].bezier.eval(u) - n.eval(x)).length() <= 1e-12 * scale(&s.points));
        }
    }

    #[test]
    fn one_group_moves_the_curve_locally_along_scaled_parallel_segments(seed in any::<u64>()) {
        let s = random_spline(seed);
        let n0 = Nubmp::try_new(s.points.clone(), s.knots.clone(), s.order).unwrap();
        let Some(j) = (0..n0.groups().len()).find(|&j| n0.groups()[j].effective && n0.groups()[j].members.len() >= 2) else {
            return Ok(());
        };
        let g = &n0.groups()[j];
        let (i0, i1) = (g.members[0], g.members[1]);
        let mut n1 = n0.clone();
        n1.set_parameter(j, i0, 0.0, i1).unwrap();
        // Paper 001, Eq. 11–12: P̃(t) = P(t) + N*_j(t) d, d = Δa (P_{i0} − P_{i1}).
        let delta = n1.groups()[j].value(i0).unwrap() - g.value(i0).unwrap();
        let d = delta * (s.points[i0] - s.points[i1]);
        let spans = n0.affected_spans(j);
        prop_assert!(spans.len() <= s.order / 2 + 1, "{} spans for order {}", spans.len(), s.order);
        for x in dense(n0.domain()) {
            let want = n0.eval(x) + n0.dual_basis_value(j, x) * d;
            prop_assert!((n1.eval(x) - want).length() <= 1e-11 * scale(&s.points));
            let inside = spans.iter().any(|&(a, b)| x >= a && x <= b);
            if !inside {
                prop_assert!((n1.eval(x) - n0.eval(x)).length() <= 1e-12 * scale(&s.points));
            }
        }
    }
}

// ---------- NUBMP specifics ----------

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
    .map(|(x, y)| p2(x, y));
    Nubmp::try_new(
        pts.to_vec(),
        vec![0., 0., 0., 0., 0.3, 0.5, 0.89, 1., 1., 1., 1.],
        4,
    )
    .unwrap()
}

#[test]
fn paper_001_structure_on_its_knots() {
    let n = paper_nubmp();
    // n* = n + m − 1 = 7 + 5 − 1 = 11 groups; Eq. 8 gives 12 free parameters.
    assert_eq!(n.groups().len(), 11);
    assert_eq!(n.free_parameter_count(), 12);
    let sizes: Vec<usize> = n.groups().iter().map(|g| g.members.len()).collect();
    assert_eq!(sizes, vec![1, 2, 2, 3, 2, 3, 2, 3, 2, 2, 1]);
    // Fig. 1a: P*_1 lies on P_0 P_1 (group 1 = {0, 1}).
    assert_eq!(n.groups()[1].members, vec![0, 1]);
    // Standard curve: every Theorem 1 value is ≤ 1.
    for j in [3, 5, 7] {
        assert!(n.vd_value(j).unwrap() <= 1.0);
    }
}

#[test]
fn paper_001_fig_1b_permissible_range() {
    // The parameter of Fig. 1b: a^2_4 (0-based; the paper's 1-based a^3_5) in the group
    // {a^2_4, a^3_4}, a^3_4 absorbing. Its range is bounded by the Theorem 1 conditions of
    // the neighbouring groups of three: group 3 (a^3_4 is its denominator) gives the
    // maximum, group 5 (a^2_4 is its denominator) the minimum. We compute
    // [0.125427, 0.901685]; the paper prints [0.1245, 0.9017]: the maximum agrees to four
    // digits; the printed minimum reads as 0.1254 with two digits transposed.
    let n = paper_nubmp();
    let r = n.permissible_range(4, 2, 3).unwrap().unwrap();
    assert!((r.max - 0.9017).abs() < 5e-5, "{r:?}");
    assert!((r.min - 0.1254).abs() < 5e-5, "{r:?}");
    // Independently, from the two conditions in closed form:
    // max: c^1_3/c^1_2 + c^3_3/(1 − s) = 1  →  s = 1 − c^3_3 / (1 − c^1_3/c^1_2)
    // min: c^2_5/s + c^4_5/c^4_6 = 1      →  s = c^2_5 / (1 − c^4_5/c^4_6)
    let g = |j: usize, i: usize| n.groups()[j].value(i).unwrap();
    let max = 1.0 - g(3, 3) / (1.0 - g(3, 1) / g(2, 1));
    let min = g(5, 2) / (1.0 - g(5, 4) / g(6, 4));
    assert!(
        (r.max - max).abs() < 1e-12 && (r.min - min).abs() < 1e-12,
        "{r:?} vs [{min}, {max}]"
    );
    // At the ends the conditions hold with equality; beyond them they fail.
    let mut at = n.clone();
    at.set_parameter(4, 2, r.min, 3).unwrap();
    assert!((at.vd_value(5).unwrap() - 1.0).abs() < 1e-9);
    at.set_parameter(4, 2, r.min - 1e-3, 3).unwrap();
    assert!(at.vd_value(5).unwrap() > 1.0);
}

#[test]
fn reachable_region_vertices_are_reached_at_the_simplex_corners() {
    let n = paper_nubmp();
    let tau = 0.42;
    let groups = n.groups_at(tau);
    assert!(!groups.is_empty() && groups.len() <= 5);
    for j in groups {
        let region = n.reachable_region(tau, j).unwrap();
        let g = &n.groups()[j];
        assert_eq!(region.len(), g.members.len());
        for (corner, vertex) in region.iter().enumerate() {
            let mut values = vec![0.0; g.members.len()];
            values[corner] = 1.0;
            let mut m = n.clone();
            m.set_group(j, &values).unwrap();
            assert!(
                (m.eval(tau) - *vertex).length() < 1e-12,
                "group {j} corner {corner}"
            );
        }
    }
}

#[test]
fn unclamped_effective_groups_sum_to_one_and_outside_groups_cannot_be_set() {
    let knots: Vec<f64> = (0..9).map(f64::from).collect();
    let pts: Vec<DVec3> = (0..5).map(|i| p2(f64::from(i), f64::from(i % 2))).collect();
    let mut n = Nubmp::try_new(pts, knots, 4).unwrap();
    let outside: Vec<usize> = (0..n.groups().len())
        .filter(|&j| !n.groups()[j].effective)
        .collect();
    assert!(!outside.is_empty());
    for g in n.groups().iter().filter(|g| g.effective) {
        assert!((g.standard.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    }
    let j = outside[0];
    let k = n.groups()[j].members.len();
    let mut values = vec![0.0; k];
    values[0] = 1.0;
    if values != n.groups()[j].standard {
        assert!(n.set_group(j, &values).is_err());
    }
}

#[test]
fn moving_one_control_point_keeps_everything_else_and_rejects_bad_indices() {
    let pts: Vec<DVec3> = (0..5)
        .map(|i| DVec3::new(f64::from(i), f64::from(i % 2), 0.0))
        .collect();
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0];
    let curve = Curve::BSpline(BSpline::try_new(pts.clone(), knots.clone(), 4).unwrap());
    let moved = curve
        .with_control_point(2, DVec3::new(2.0, 5.0, 0.0))
        .unwrap();
    let Curve::BSpline(b) = &moved else {
        panic!("the family changed: {}", moved.family());
    };
    assert_eq!(b.knots().knots(), knots.as_slice());
    let mut want = pts.clone();
    want[2] = DVec3::new(2.0, 5.0, 0.0);
    assert_eq!(b.points(), want.as_slice());

    let err = curve.with_control_point(5, DVec3::ZERO).unwrap_err();
    assert!(
        matches!(err, GeomError::NoSuchPoint { index: 5, count: 5 }),
        "{err:?}"
    );
    assert_eq!(err.field(), "points[5]");
    assert!(
        err.to_string().contains("control point 5 does not exist"),
        "{err}"
    );
    let err = curve
        .with_control_point(1, DVec3::new(f64::NAN, 0.0, 0.0))
        .unwrap_err();
    assert!(
        matches!(err, GeomError::NonFinitePoint { index: 1, .. }),
        "{err:?}"
    );
}

/// Every family is listed in each place that lists families — a scene codec, an entry in
/// the scene schema, a viewer template — and nothing lists a family the core lacks. A new
/// `Curve` variant without one of them fails here.
#[test]
fn every_family_has_a_codec_a_schema_entry_and_a_template() {
    use splinescope_core::geom::Curve;
    use splinescope_viewer::interaction::Template;
    let names = Curve::FAMILY_NAMES;
    // The core's own list agrees with its variants.
    for t in Template::all() {
        let c = t.curve(glam::DVec3::ZERO, 1.0);
        assert_eq!(names[c.family_index()], c.family(), "{}", t.label());
    }
    // Templates: at least one per family, every family, no label twice.
    let mut templates: Vec<&str> = Template::all()
        .iter()
        .map(|t| t.curve(glam::DVec3::ZERO, 1.0).family())
        .collect();
    templates.dedup();
    assert_eq!(
        templates,
        names.to_vec(),
        "templates of every family, in the table's order"
    );
    let mut labels: Vec<&str> = Template::all().iter().map(|t| t.label()).collect();
    labels.sort_unstable();
    let count = labels.len();
    labels.dedup();
    assert_eq!(labels.len(), count, "template labels are distinct");
    // Codecs: the reader knows each family (a missing field, not an unknown type), and
    // knows no other (its list of types is exactly the families).
    for name in names {
        let text = format!(r#"{{"version": 1, "curves": [{{"type": "{name}"}}]}}"#);
        let e = splinescope_scene::format::from_json_str(&text)
            .unwrap_err()
            .to_string();
        assert!(
            !e.contains("unknown curve type"),
            "{name} has no codec: {e}"
        );
    }
    let e = splinescope_scene::format::from_json_str(
        r#"{"version": 1, "curves": [{"type": "no_such_family"}]}"#,
    )
    .unwrap_err()
    .to_string();
    let listed = e
        .split("expected one of: ")
        .nth(1)
        .unwrap_or_else(|| panic!("the reader lists its families: {e}"));
    let mut listed: Vec<&str> = listed
        .trim_end_matches(')')
        .split(", ")
        .map(str::trim)
        .collect();
    listed.sort_unstable();
    let mut want = names.to_vec();
    want.sort_unstable();
    assert_eq!(listed, want, "the codecs are exactly the families");
    // The generated scene schema has each family's `type`.
    let schema = splinescope::schemas::all()
        .into_iter()
        .find(|(n, _)| *n == "scene")
        .expect("scene schema")
        .1;
    let text = serde_json::to_string(&schema).unwrap();
    for name in names {
        assert!(
            text.contains(&format!("\"const\":\"{name}\"")),
            "the scene schema has no entry for {name}"
        );
    }
}

/// The stress generator makes curves of every family in the table (what `bench
/// --families` and `view --stress` take), deterministic, valid, and of the structure its
/// segment counts promise.
#[test]
fn the_stress_generator_makes_valid_curves_of_every_family() {
    use splinescope_scene::format::generate::{StressFamily, StressOptions, random_bezier_scene};
    let all: Vec<StressFamily> = StressFamily::all().collect();
    assert_eq!(
        all.iter().map(|f| f.name()).collect::<Vec<_>>(),
        splinescope_core::geom::Curve::FAMILY_NAMES.to_vec()
    );
    for family in all {
        for degree in [2, 3, 5] {
            let opts = StressOptions {
                curves: 9,
                degree,
                family,
                three_d: degree == 5,
                ..StressOptions::default()
            };
            let scene = random_bezier_scene(opts);
            assert_eq!(
                scene,
                random_bezier_scene(opts),
                "{} is deterministic",
                family.name()
            );
            assert_eq!(scene.curves.len(), 9);
            for c in &scene.curves {
                assert_eq!(c.curve.family(), family.name());
                c.curve.check_derived().expect("finite lowering");
                let lowered = c.curve.lower();
                assert_eq!(lowered.len(), family.segments(degree), "{}", family.name());
                assert_eq!(
                    lowered.iter().map(|s| s.bezier.degree()).max(),
                    Some(family.segment_degree(degree)),
                    "{}",
                    family.name()
                );
                assert_eq!(c.curve.control_points().len(), family.points(degree));
            }
        }
    }
    let e = "conic".parse::<StressFamily>().unwrap_err().to_string();
    assert!(e.contains("\"conic\"") && e.contains("nubmp"), "{e}");
}
