//! Bézier math against independent truth: exact rational arithmetic through the power
//! basis (not de Casteljau), finite differences, and invariants (split and elevation do
//! not move the curve).

use glam::DVec3;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, ToPrimitive, Zero};
use proptest::prelude::*;
use splinescope_core::geom::Bezier;

type Q = BigRational;

fn q(n: i64, d: i64) -> Q {
    Q::new(BigInt::from(n), BigInt::from(d))
}

fn binom(n: usize, k: usize) -> BigInt {
    (0..k).fold(BigInt::one(), |acc, j| {
        acc * BigInt::from(n - j) / BigInt::from(j + 1)
    })
}

/// Exact power-basis coefficients a_k of one coordinate:
/// P(t) = Σ_k a_k t^k, a_k = C(n,k) Σ_{i≤k} (−1)^{k−i} C(k,i) P_i.
fn monomial(coords: &[Q]) -> Vec<Q> {
    let n = coords.len() - 1;
    (0..=n)
        .map(|k| {
            let mut s = Q::zero();
            for (i, p) in coords.iter().enumerate().take(k + 1) {
                let term = p * Q::from(binom(k, i));
                if (k - i) % 2 == 0 {
                    s += term;
                } else {
                    s -= term;
                }
            }
            s * Q::from(binom(n, k))
        })
        .collect()
}

fn horner(a: &[Q], t: &Q) -> Q {
    a.iter().rev().fold(Q::zero(), |acc, c| acc * t + c)
}

fn derivative(a: &[Q]) -> Vec<Q> {
    a.iter()
        .enumerate()
        .skip(1)
        .map(|(k, c)| c * Q::from(BigInt::from(k)))
        .collect()
}

fn to_f64(x: &Q) -> f64 {
    x.to_f64().expect("finite")
}

/// A curve with small integer coordinates (exact in f64 and in Q).
fn integer_curve(seed: u64, n: usize) -> (Bezier, [Vec<Q>; 3]) {
    let mut rng = splinescope_core::rng::Rng::new(seed);
    let mut pts = Vec::new();
    let mut exact: [Vec<Q>; 3] = Default::default();
    for _ in 0..=n {
        let c: [i64; 3] = std::array::from_fn(|_| rng.int(0, 40) as i64 - 20);
        pts.push(DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64));
        for (axis, v) in c.iter().enumerate() {
            exact[axis].push(q(*v, 1));
        }
    }
    (Bezier::new(pts), exact)
}

#[test]
fn de_casteljau_matches_exact_power_basis_values() {
    for n in 1..=25 {
        let (b, exact) = integer_curve(n as u64, n);
        let mono: Vec<Vec<Q>> = exact.iter().map(|c| monomial(c)).collect();
        for (num, den) in [(0, 1), (1, 3), (1, 2), (5, 7), (3, 4), (99, 100), (1, 1)] {
            let t = q(num, den);
            let got = b.eval(num as f64 / den as f64);
            let scale = 20.0;
            for axis in 0..3 {
                let want = to_f64(&horner(&mono[axis], &t));
                // The only inexact inputs are t itself (≤ 1 ulp) and the f64 roundings of
                // n de Casteljau levels: far below 1e-12 of the coordinate range.
                assert!(
                    (got[axis] - want).abs() <= 1e-12 * scale,
                    "n={n} t={num}/{den} axis={axis}: {} vs {want}",
                    got[axis]
                );
            }
        }
    }
}

#[test]
fn derivatives_match_exact_power_basis_derivatives() {
    for n in 1..=20 {
        let (b, exact) = integer_curve(100 + n as u64, n);
        let mono: Vec<Vec<Q>> = exact.iter().map(|c| monomial(c)).collect();
        let d1: Vec<Vec<Q>> = mono.iter().map(|a| derivative(a)).collect();
        let d2: Vec<Vec<Q>> = d1.iter().map(|a| derivative(a)).collect();
        for (num, den) in [(0, 1), (1, 3), (2, 5), (1, 1)] {
            let t = q(num, den);
            let tf = num as f64 / den as f64;
            let (g1, g2) = (b.eval_deriv(tf), b.eval_second_deriv(tf));
            for axis in 0..3 {
                let w1 = to_f64(&horner(&d1[axis], &t));
                let w2 = to_f64(&horner(&d2[axis], &t));
                let s1 = 20.0 * n as f64;
                let s2 = 20.0 * (n * n) as f64;
                assert!((g1[axis] - w1).abs() <= 1e-11 * s1, "P' n={n} t={tf}");
                assert!((g2[axis] - w2).abs() <= 1e-11 * s2, "P'' n={n} t={tf}");
            }
        }
    }
}

#[test]
fn elevation_formula_preserves_the_exact_polynomial() {
    // Q_i = (i/(n+1)) P_{i−1} + (1 − i/(n+1)) P_i gives the same polynomial (exactly),
    // and the library's f64 elevation is that formula to rounding.
    for n in 1..=12 {
        let (b, exact) = integer_curve(200 + n as u64, n);
        let e = b.elevate();
        assert_eq!(e.degree(), n + 1);
        for axis in 0..3 {
            let p = &exact[axis];
            let m = q((n + 1) as i64, 1);
            let mut qe = vec![p[0].clone()];
            for i in 1..=n {
                let a = q(i as i64, 1) / &m;
                qe.push(&a * &p[i - 1] + (Q::one() - &a) * &p[i]);
            }
            qe.push(p[n].clone());
            let mut orig = monomial(p);
            orig.push(Q::zero());
            assert_eq!(monomial(&qe), orig, "n={n} axis={axis}");
            for (got, want) in e.points().iter().zip(&qe) {
                assert!((got[axis] - to_f64(want)).abs() <= 1e-14 * 20.0);
            }
        }
    }
}

#[test]
fn derivatives_agree_with_central_differences() {
    let (b, _) = integer_curve(7, 9);
    let h = 1e-5;
    for k in 1..20 {
        let t = k as f64 / 20.0;
        let fd = (b.eval(t + h) - b.eval(t - h)) / (2.0 * h);
        let fd2 = (b.eval(t + h) - 2.0 * b.eval(t) + b.eval(t - h)) / (h * h);
        let d = b.eval_deriv(t);
        let d2 = b.eval_second_deriv(t);
        assert!((fd - d).length() <= 1e-5 * d.length().max(1.0), "t={t}");
        assert!((fd2 - d2).length() <= 1e-2 * d2.length().max(1.0), "t={t}");
    }
}

fn arb_curve() -> impl Strategy<Value = Bezier> {
    (1usize..=20).prop_flat_map(|n| {
        prop::collection::vec((-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64), n + 1)
            .prop_map(|v| Bezier::new(v.into_iter().map(|(x, y, z)| DVec3::new(x, y, z)).collect()))
    })
}

fn scale(b: &Bezier) -> f64 {
    b.control_box().diagonal().max(1.0)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn split_pieces_trace_the_curve(b in arb_curve(), t in 0.01..0.99f64) {
        let (left, right) = b.split(t);
        for k in 0..=40 {
            let u = k as f64 / 40.0;
            let l = left.eval(u) - b.eval(t * u);
            let r = right.eval(u) - b.eval(t + u * (1.0 - t));
            prop_assert!(l.length() <= 1e-12 * scale(&b));
            prop_assert!(r.length() <= 1e-12 * scale(&b));
        }
        prop_assert_eq!(left.points()[0], b.points()[0]);
        prop_assert_eq!(*right.points().last().unwrap(), *b.points().last().unwrap());
    }

    #[test]
    fn subsegment_is_the_reparametrised_piece(b in arb_curve(), t0 in 0.0..1.0f64, t1 in 0.0..1.0f64) {
        let s = b.subsegment(t0, t1);
        for k in 0..=20 {
            let u = k as f64 / 20.0;
            let d = s.eval(u) - b.eval(t0 + u * (t1 - t0));
            prop_assert!(d.length() <= 1e-11 * scale(&b), "{}", d.length());
        }
    }

    #[test]
    fn elevation_does_not_move_the_curve(b in arb_curve(), times in 1usize..6) {
        let e = b.elevated_to(b.degree() + times);
        prop_assert_eq!(e.degree(), b.degree() + times);
        for k in 0..=200 {
            let t = k as f64 / 200.0;
            prop_assert!((e.eval(t) - b.eval(t)).length() <= 1e-12 * scale(&b));
        }
    }

    #[test]
    fn bounding_box_is_tight(b in arb_curve()) {
        let bb = b.bounding_box();
        let mut dense = splinescope_core::geom::Aabb::EMPTY;
        for k in 0..=20_000 {
            dense = dense.including(b.eval(k as f64 / 20_000.0));
        }
        let tol = 1e-9 * scale(&b);
        // Holds every sample, and no side is further out than sampling can explain
        // (h = 5e-5: the sampled extreme is within |P''| h² / 8 of the true one).
        let slack = 1e-8 * scale(&b) * (b.degree() * b.degree()) as f64;
        for axis in 0..3 {
            prop_assert!(bb.min[axis] <= dense.min[axis] + tol);
            prop_assert!(bb.max[axis] >= dense.max[axis] - tol);
            prop_assert!(dense.min[axis] - bb.min[axis] <= slack, "axis {axis}");
            prop_assert!(bb.max[axis] - dense.max[axis] <= slack, "axis {axis}");
        }
    }
}
