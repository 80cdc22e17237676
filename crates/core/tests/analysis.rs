//! The analysis engine against independent truth: exact rational arithmetic for the root
//! finder, closed forms for lengths, boxes, areas, inflections, cusps and curvature
//! extrema, invariants (additivity, knot insertion and elevation, both parameters of an
//! intersection giving one point), and dense polylines computed here for intersections.

use std::f64::consts::{FRAC_1_SQRT_2, PI};

use glam::DVec3;
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, ToPrimitive, Zero};
use proptest::prelude::*;

use splinescope_core::analysis::{
    AnalysisError, CurveAnalysis, ExtremumKind, HitKind, all_intersections, bezier_length,
};
use splinescope_core::geom::{BSpline, Bezier, Curve, Lower, Nurbs, ParamCurve, RationalBezier};
use splinescope_core::poly::roots::bernstein_roots;
use splinescope_core::rng::Rng;

fn p2(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

fn bezier(points: &[(f64, f64)]) -> Bezier {
    Bezier::new(points.iter().map(|&(x, y)| p2(x, y)).collect())
}

fn circle(r: f64) -> Nurbs {
    Nurbs::circle(DVec3::ZERO, r).expect("circle")
}

/// A circle of radius `r` about `(cx, cy)`.
fn circle_at(cx: f64, cy: f64, r: f64) -> Nurbs {
    Nurbs::circle(p2(cx, cy), r).expect("circle")
}

// ---------------------------------------------------------------------------------------
// Roots, against exact rational arithmetic.

fn rat(x: f64) -> BigRational {
    BigRational::from_float(x).expect("finite")
}

/// The exact Bernstein coefficients of `Π (t − r_i)` (each `r_i` a binary fraction), then
/// rounded once to `f64`.
fn exact_coefficients(roots: &[f64]) -> Vec<f64> {
    let mut c: Vec<BigRational> = vec![BigRational::one()];
    for &r in roots {
        let r = rat(r);
        let n = c.len() - 1;
        // (t − r) = −r B₀₁ + (1 − r) B₁₁; product at degree n + 1.
        let lin = [-r.clone(), BigRational::one() - r];
        let mut out = vec![BigRational::zero(); n + 2];
        let binom = |n: usize, k: usize| -> BigInt {
            let mut v = BigInt::one();
            for j in 0..k {
                v = v * BigInt::from(n - j) / BigInt::from(j + 1);
            }
            v
        };
        for (i, ci) in c.iter().enumerate() {
            for (j, lj) in lin.iter().enumerate() {
                let w = BigRational::new(binom(n, i) * binom(1, j), binom(n + 1, i + j));
                out[i + j] += w * ci * lj;
            }
        }
        c = out;
    }
    c.iter().map(|v| v.to_f64().expect("finite")).collect()
}

#[test]
fn roots_of_exact_products() {
    for roots in [
        vec![0.125, 0.5, 0.875],
        vec![0.0, 0.25, 0.75, 1.0],
        vec![0.3125, 0.3125, 0.6875],
        vec![0.5, 0.5, 0.5, 0.5],
        vec![1.0 / 1024.0, 1023.0 / 1024.0, 0.5],
    ] {
        let c = exact_coefficients(&roots);
        let found = bernstein_roots(&c);
        let mut distinct = roots.clone();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup();
        let total: usize = found.roots.iter().map(|r| r.multiplicity).sum();
        assert_eq!(total, roots.len(), "{roots:?}: {:?}", found.roots);
        assert_eq!(
            found.roots.len(),
            distinct.len(),
            "{roots:?}: {:?}",
            found.roots
        );
        for (r, want) in found.roots.iter().zip(&distinct) {
            let tol: f64 = if r.multiplicity == 1 { 1e-15 } else { 1e-5 };
            assert!(
                (r.t - want).abs() <= tol.max(r.error),
                "{roots:?}: {} vs {want} (± {})",
                r.t,
                r.error
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Random simple roots at least 1/64 apart (binary fractions, so the exact polynomial
    /// is known): every one found, to within its stated error and 1e-13.
    #[test]
    fn random_simple_roots_are_all_found(picks in proptest::collection::btree_set(1u32..1024, 1..9)) {
        let mut roots: Vec<f64> = picks.iter().map(|k| f64::from(*k) / 1024.0).collect();
        roots.dedup_by(|a, b| (*a - *b).abs() < 1.0 / 64.0);
        let found = bernstein_roots(&exact_coefficients(&roots));
        prop_assert_eq!(found.roots.len(), roots.len(), "{:?} {:?}", roots, found.roots);
        for (r, want) in found.roots.iter().zip(&roots) {
            // The stated bound holds (it covers the rounding of the coefficients too).
            prop_assert!((r.t - want).abs() <= r.error.max(4e-16), "{} vs {} ± {}", r.t, want, r.error);
            prop_assert!((r.t - want).abs() <= 1e-9, "{} vs {}", r.t, want);
        }
    }
}

// ---------------------------------------------------------------------------------------
// Arc length.

/// An independent reference: composite 8-point Gauss–Legendre on `panels` panels of
/// `|C′|` from the curve's own derivative.
fn reference_length(curve: &impl ParamCurve, a: f64, b: f64, panels: usize) -> f64 {
    const X: [f64; 4] = [
        0.183_434_642_495_649_8,
        0.525_532_409_916_329,
        0.796_666_477_413_626_7,
        0.960_289_856_497_536_3,
    ];
    const W: [f64; 4] = [
        0.362_683_783_378_362,
        0.313_706_645_877_887_3,
        0.222_381_034_453_374_5,
        0.101_228_536_290_376_26,
    ];
    let h = (b - a) / panels as f64;
    let mut sum = 0.0;
    for k in 0..panels {
        let c = a + (k as f64 + 0.5) * h;
        for (x, w) in X.iter().zip(W) {
            for s in [-1.0, 1.0] {
                sum += w * curve.eval_deriv(c + s * x * 0.5 * h).length() * 0.5 * h;
            }
        }
    }
    sum
}

#[test]
fn lengths_against_closed_forms() {
    for r in [1.0, 3.5, 1e-3, 1e4] {
        let c = CurveAnalysis::new(&circle(r));
        for acc in [1e-6, 1e-9, 1e-12] {
            let acc = acc * r;
            let quarter = c.length(0.0, 0.25, acc).expect("length");
            assert!(
                (quarter.value - 0.5 * PI * r).abs() <= acc,
                "r = {r}, accuracy {acc}: {} vs {}",
                quarter.value,
                0.5 * PI * r
            );
            let whole = c.length(0.0, 1.0, acc).expect("length");
            assert!((whole.value - 2.0 * PI * r).abs() <= acc, "{whole:?}");
        }
    }
    // A parabola arc: y = x² for x ∈ [0, 2] as the quadratic (0,0), (1,0), (2,4):
    // L = ∫₀² √(1 + 4x²) dx = [x√(1+4x²)/2 + asinh(2x)/4]₀².
    let parabola = CurveAnalysis::new(&bezier(&[(0.0, 0.0), (1.0, 0.0), (2.0, 4.0)]));
    let want = 2.0 * 17f64.sqrt() / 2.0 + 4f64.asinh() / 4.0;
    for acc in [1e-6, 1e-9, 1e-12] {
        let l = parabola.length(0.0, 1.0, acc).expect("length");
        assert!((l.value - want).abs() <= acc, "{} vs {want}", l.value);
    }
    // Straight lines of any degree: the distance between the ends, whatever the spacing.
    for n in 1..=9 {
        let pts: Vec<DVec3> = (0..=n)
            .map(|i| {
                let s = (f64::from(i) / f64::from(n)).powi(2);
                DVec3::new(1.0, 2.0, -0.5) + s * DVec3::new(3.0, -4.0, 12.0)
            })
            .collect();
        let l = CurveAnalysis::new(&Bezier::new(pts))
            .length(0.0, 1.0, 1e-12)
            .expect("length");
        assert!((l.value - 13.0).abs() <= 1e-12, "degree {n}: {}", l.value);
    }
    // A helix-like 3D cubic against the reference.
    let helix = Bezier::new(vec![
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(1.0, 0.55, 0.4),
        DVec3::new(0.55, 1.0, 0.8),
        DVec3::new(0.0, 1.0, 1.2),
    ]);
    let want = reference_length(&helix, 0.0, 1.0, 4000);
    let l = CurveAnalysis::new(&helix)
        .length(0.0, 1.0, 1e-12)
        .expect("length");
    assert!((l.value - want).abs() <= 1e-12, "{} vs {want}", l.value);
}

/// Tanh-sinh (double exponential) quadrature on `[a, b]`: independent of the engine's
/// Gauss–Kronrod rule, and accurate to about `1e−15` even where the integrand has a kink
/// or a square-root behaviour at an end.
fn tanh_sinh(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let h = 1.0 / 256.0;
    let (c, r) = (0.5 * (a + b), 0.5 * (b - a));
    let half_pi = std::f64::consts::FRAC_PI_2;
    let mut sum = 0.0;
    for k in -(256 * 7)..=(256 * 7) {
        let t = f64::from(k) * h;
        let u = half_pi * t.sinh();
        let x = c + r * u.tanh();
        if x > a && x < b {
            sum += half_pi * t.cosh() / u.cosh().powi(2) * f(x);
        }
    }
    sum * h * r
}

/// Arc lengths of 1,000 random cubics (loops, near-cusps and all) and 200 random curves
/// of degree 6 within the requested accuracy — and within the error bound they state — of
/// a tanh-sinh reference, cut where the speed has its minima (so the
/// reference sees the kinks at its interval ends, where it is exact to rounding).
/// `bezier_length` (no analysis built) gives the analysis's length to the bit — value,
/// bound and error — for planar curves of degrees 0–7 (its own path) and for 3D curves
/// and degree 9 (through the analysis), over whole and partial, reversed and empty
/// ranges at three accuracies; and refuses what `length` refuses, naming the same value.
#[test]
fn a_bezier_length_without_the_analysis_is_the_analysis_length() {
    let mut seed = 5_u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let ranges = [
        (0.0, 1.0),
        (0.25, 0.75),
        (0.9, 0.1),
        (0.5, 0.5),
        (0.0, 0.0),
        (1.0, 1.0),
    ];
    for count in 0..400 {
        let points = [1, 2, 3, 4, 4, 4, 5, 6, 7, 8, 10][count % 11];
        let three_d = count % 13 == 0;
        let b = Bezier::new(
            (0..points)
                .map(|_| DVec3::new(4.0 * rnd() - 2.0, rnd(), if three_d { rnd() } else { 0.0 }))
                .collect(),
        );
        let analysis = CurveAnalysis::new(&b);
        for &(t0, t1) in &ranges {
            for accuracy in [1e-6, 1e-9, 1e-12] {
                let want = analysis.length(t0, t1, accuracy);
                let got = bezier_length(&b, t0, t1, accuracy);
                match (&want, &got) {
                    (Ok(w), Ok(g)) => assert!(
                        w.value.to_bits() == g.value.to_bits()
                            && w.error.to_bits() == g.error.to_bits(),
                        "{points} points, [{t0}, {t1}] at {accuracy}: {g:?} vs {w:?}"
                    ),
                    _ => assert_eq!(
                        format!("{want:?}"),
                        format!("{got:?}"),
                        "{points} points, [{t0}, {t1}] at {accuracy}"
                    ),
                }
            }
        }
    }
    let cubic = bezier(&[(0.0, 0.0), (1.0, 2.0), (2.0, -1.0), (3.0, 0.0)]);
    for (t0, t1, accuracy) in [
        (0.0, 1.0, 0.0),
        (0.0, 1.0, f64::NAN),
        (-0.5, 1.0, 1e-9),
        (0.0, f64::NAN, 1e-9),
    ] {
        let err = bezier_length(&cubic, t0, t1, accuracy).expect_err("refused");
        assert_eq!(
            err.to_string(),
            CurveAnalysis::new(&cubic)
                .length(t0, t1, accuracy)
                .expect_err("refused")
                .to_string()
        );
    }
}

#[test]
fn random_cubic_lengths_within_the_accuracy() {
    let mut seed = 11_u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    // 1,000 cubics, then 200 curves of degree 6 (whose speed's roots come from the
    // iterative solver rather than the closed form).
    for count in 0..1200 {
        let points = if count < 1000 { 4 } else { 7 };
        let b = Bezier::new((0..points).map(|_| p2(rnd(), rnd())).collect());
        let speed = |u: f64| b.eval_deriv(u).length();
        // The speed's minima from the power form of d|P′|²/du (a cubic), by bisection on
        // a fine grid: independent of the engine's root finder.
        let slope = |u: f64| 2.0 * b.eval_deriv(u).dot(b.eval_second_deriv(u));
        let mut cuts = vec![0.0];
        let grid = 2000;
        for k in 0..grid {
            let (lo, hi) = (
                f64::from(k) / f64::from(grid),
                f64::from(k + 1) / f64::from(grid),
            );
            if slope(lo) < 0.0 && slope(hi) >= 0.0 {
                let (mut l, mut h) = (lo, hi);
                for _ in 0..60 {
                    let m = 0.5 * (l + h);
                    if slope(m) < 0.0 { l = m } else { h = m }
                }
                cuts.push(0.5 * (l + h));
            }
        }
        cuts.push(1.0);
        let truth: f64 = cuts.windows(2).map(|w| tanh_sinh(&speed, w[0], w[1])).sum();
        let c = CurveAnalysis::new(&b);
        for acc in [1e-2, 1e-3, 1e-4, 1e-6, 1e-9, 1e-12] {
            let l = c.length(0.0, 1.0, acc).expect("length");
            // Within the accuracy, and within the error the engine states (a bound).
            assert!(
                (l.value - truth).abs() <= acc.min(l.error + 1e-14),
                "{:?}, accuracy {acc}: {} vs {truth} (error {})",
                b.points(),
                l.value,
                l.error
            );
        }
    }
}

/// Rational curves whose weights are far apart change on a tiny scale in the parameter.
/// With weights 10⁻³⁰¹ … 10³⁰¹ the curve runs along its control polygon's legs to within
/// far less than an ulp, skipping the control points whose weight terms never dominate:
/// its length is the polygon's through the dominant points (here √5 + √10, P₂ never
/// pulls). Moderate spreads against the composite Gauss reference.
#[test]
fn lengths_of_rational_curves_with_weights_far_apart() {
    let pts = vec![p2(0.0, 0.0), p2(1.0, 2.0), p2(3.0, 0.5), p2(4.0, 3.0)];
    let c =
        RationalBezier::try_new(pts.clone(), vec![9.3e-302, 1.0, 1.0, 1.07e301]).expect("curve");
    let a = CurveAnalysis::new(&c);
    let l = a.length(0.0, 1.0, 1e-12).expect("length");
    let truth = 5.0_f64.sqrt() + 10.0_f64.sqrt();
    assert!((l.value - truth).abs() <= 1e-12, "{l:?} vs {truth}");
    for s in [0.5, 1.0, 2.5, 4.0, 5.3] {
        let t = a.parameter_at_length(s, 1e-12).expect("parameter");
        let back = a.length(0.0, t, 1e-13).expect("length").value;
        assert!((back - s).abs() <= 1e-11, "s {s}: t {t:e} gives {back}");
    }
    for w in [
        vec![1.0, 100.0, 1.0, 1.0],
        vec![1.0, 1e3, 1e-3, 1.0],
        vec![1e-4, 1.0, 1.0, 1e4],
    ] {
        let c = RationalBezier::try_new(pts.clone(), w.clone()).expect("curve");
        let l = CurveAnalysis::new(&c)
            .length(0.0, 1.0, 1e-10)
            .expect("length");
        let truth = reference_length(&c, 0.0, 1.0, 200_000);
        assert!((l.value - truth).abs() <= 1e-9, "{w:?}: {l:?} vs {truth}");
    }
}

#[test]
fn lengths_add_up_and_survive_knot_insertion_and_elevation() {
    let spline = BSpline::try_new(
        [
            (0.0, 0.0),
            (1.0, 2.0),
            (2.5, -1.0),
            (4.0, 3.0),
            (5.0, 0.5),
            (6.5, 2.0),
            (7.0, -1.0),
        ]
        .iter()
        .map(|&(x, y)| p2(x, y))
        .collect(),
        vec![0.0, 0.0, 0.0, 0.0, 0.2, 0.55, 0.7, 1.0, 1.0, 1.0, 1.0],
        4,
    )
    .expect("spline");
    let c = CurveAnalysis::new(&spline);
    let acc = 1e-11;
    let whole = c.length(0.0, 1.0, acc).expect("length").value;
    let parts: f64 = [0.0, 0.13, 0.55, 0.8, 1.0]
        .windows(2)
        .map(|w| c.length(w[0], w[1], acc).expect("length").value)
        .sum();
    assert!((whole - parts).abs() <= 5.0 * acc, "{whole} vs {parts}");
    assert!(
        (c.length(0.8, 0.13, acc).expect("length").value
            + c.length(0.13, 0.8, acc).expect("length").value)
            .abs()
            <= 2.0 * acc
    );
    let inserted = CurveAnalysis::new(&spline.insert_knot(0.37).expect("insert"));
    let elevated = CurveAnalysis::new(&spline.elevate());
    for other in [inserted, elevated] {
        let l = other.length(0.0, 1.0, acc).expect("length").value;
        assert!((l - whole).abs() <= 2.0 * acc, "{l} vs {whole}");
    }
    let b = bezier(&[(0.0, 0.0), (1.0, 3.0), (3.0, -2.0), (4.0, 1.0)]);
    let lb = CurveAnalysis::new(&b)
        .length(0.0, 1.0, acc)
        .expect("length")
        .value;
    let le = CurveAnalysis::new(&b.elevate().elevate())
        .length(0.0, 1.0, acc)
        .expect("length")
        .value;
    assert!((lb - le).abs() <= 2.0 * acc);
}

#[test]
fn parameter_at_length_inverts_the_length() {
    let c = CurveAnalysis::new(&circle(2.0));
    // On a NURBS circle the parameter is not proportional to the angle, so this tests the
    // inverse, not a line.
    for frac in [0.0, 0.1, 0.25, 0.33, 0.5, 0.9, 1.0] {
        let s = frac * 4.0 * PI;
        let t = c.parameter_at_length(s, 1e-12).expect("parameter");
        let back = c.length(0.0, t, 1e-13).expect("length").value;
        assert!((back - s).abs() <= 2e-12, "{frac}: {back} vs {s}");
    }
    let total = c.length(0.0, 1.0, 1e-12).expect("length").value;
    assert!(matches!(
        c.parameter_at_length(total + 1e-6, 1e-12),
        Err(AnalysisError::BeyondLength { .. })
    ));
    assert!(matches!(
        c.parameter_at_length(-1.0, 1e-12),
        Err(AnalysisError::BeyondLength { .. })
    ));
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            c.length(0.0, 1.0, bad),
            Err(AnalysisError::Accuracy(_))
        ));
    }
    let e = c.length(0.0, 1.5, 1e-9).expect_err("outside");
    assert!(
        e.to_string()
            .contains("t1 = 1.5: outside the domain [0, 1]"),
        "{e}"
    );
}

// ---------------------------------------------------------------------------------------
// Extrema, boxes, areas.

#[test]
fn extrema_and_the_tight_box() {
    // x(t) = 3t(1−t)²·2 + … : take the cubic (0,0), (3,3), (−1,3), (2,0): its x′ and y′ are
    // quadratics whose roots the quadratic formula gives.
    let pts = [(0.0, 0.0), (3.0, 3.0), (-1.0, 3.0), (2.0, 0.0)];
    let b = bezier(&pts);
    let c = CurveAnalysis::new(&b);
    let quad_roots = |a: f64, b: f64, c: f64| -> Vec<f64> {
        // a(1−t)² + 2b t(1−t) + c t² = (a − 2b + c) t² + 2(b − a) t + a
        let (qa, qb, qc) = (a - 2.0 * b + c, 2.0 * (b - a), a);
        let disc = (qb * qb - 4.0 * qa * qc).sqrt();
        let mut r = vec![(-qb - disc) / (2.0 * qa), (-qb + disc) / (2.0 * qa)];
        r.retain(|t| *t > 0.0 && *t < 1.0);
        r.sort_by(f64::total_cmp);
        r
    };
    let dx = [3.0, -4.0, 3.0];
    let dy = [3.0, 0.0, -3.0];
    let want_x = quad_roots(dx[0], dx[1], dx[2]);
    let want_y: Vec<f64> = vec![0.5];
    let _ = dy;
    let ex = c.extrema();
    let xs: Vec<f64> = ex.iter().filter(|e| e.axis == 0).map(|e| e.t).collect();
    let ys: Vec<f64> = ex.iter().filter(|e| e.axis == 1).map(|e| e.t).collect();
    assert_eq!(xs.len(), want_x.len());
    for (g, w) in xs.iter().zip(&want_x) {
        assert!((g - w).abs() < 1e-15, "{g} vs {w}");
    }
    assert_eq!(ys.len(), 1);
    assert!((ys[0] - want_y[0]).abs() < 1e-15);
    let bb = c.bounding_box();
    // The box holds dense samples and touches them within 1e-9.
    let samples: Vec<DVec3> = (0..=100_000).map(|k| b.eval(f64::from(k) / 1e5)).collect();
    let lo = samples.iter().fold(DVec3::INFINITY, |m, p| m.min(*p));
    let hi = samples.iter().fold(DVec3::NEG_INFINITY, |m, p| m.max(*p));
    assert!(bb.min.cmple(lo + 1e-15).all() && bb.max.cmpge(hi - 1e-15).all());
    assert!((bb.min - lo).length() < 1e-9 && (bb.max - hi).length() < 1e-9);
    // The exact y maximum: y(0.5) = 2.25.
    assert!((bb.max.y - 2.25).abs() < 1e-15, "{}", bb.max.y);
    // Rational: the NURBS circle's box is the square, the quarter arc's the unit square.
    let cb = CurveAnalysis::new(&circle(2.0)).bounding_box();
    assert!((cb.min - p2(-2.0, -2.0)).length() < 1e-15 && (cb.max - p2(2.0, 2.0)).length() < 1e-15);
    let arc = RationalBezier::try_new(
        vec![p2(1.0, 0.0), p2(1.0, 1.0), p2(0.0, 1.0)],
        vec![1.0, FRAC_1_SQRT_2, 1.0],
    )
    .expect("arc");
    let ab = CurveAnalysis::new(&arc).bounding_box();
    assert_eq!((ab.min, ab.max), (p2(0.0, 0.0), p2(1.0, 1.0)));
}

/// The tight box of polynomial curves of degrees 1–3 (closed-form candidates) against an
/// independent truth: each coordinate's extremes by dense sampling, refined by golden-
/// section search around every sampled local extreme. Random 2D and 3D curves, and
/// constructed hard ones: a coordinate whose derivative has a double root inside (no
/// extremum there), two extrema 10⁻⁹ apart, a constant coordinate, a line that doubles
/// back on itself, a point; and a cubic B-spline of several segments.
#[test]
fn tight_boxes_of_low_degrees_against_sampling() {
    fn extremes(f: &dyn Fn(f64) -> f64) -> (f64, f64) {
        let n = 2000;
        let v: Vec<f64> = (0..=n).map(|k| f(f64::from(k) / f64::from(n))).collect();
        let (mut lo, mut hi) = (v[0].min(v[n as usize]), v[0].max(v[n as usize]));
        for k in 1..n as usize {
            for sign in [1.0, -1.0] {
                if sign * v[k] >= sign * v[k - 1] && sign * v[k] >= sign * v[k + 1] {
                    // Golden-section search for the maximum of sign·f on the bracket.
                    let (mut a, mut b) =
                        ((k - 1) as f64 / f64::from(n), (k + 1) as f64 / f64::from(n));
                    let g = (5f64.sqrt() - 1.0) / 2.0;
                    for _ in 0..120 {
                        let (c, d) = (b - g * (b - a), a + g * (b - a));
                        if sign * f(c) >= sign * f(d) {
                            b = d
                        } else {
                            a = c
                        }
                    }
                    let m = f(0.5 * (a + b)).max(f(a)).max(f(b));
                    let m2 = f(0.5 * (a + b)).min(f(a)).min(f(b));
                    if sign > 0.0 {
                        hi = hi.max(m)
                    } else {
                        lo = lo.min(m2)
                    }
                }
            }
        }
        (lo, hi)
    }
    let check = |curve: &dyn ParamCurve, analysis: &CurveAnalysis, what: &str| {
        let bb = analysis.bounding_box();
        let size = (bb.max - bb.min).length().max(1e-300);
        for axis in 0..3 {
            let (lo, hi) = extremes(&|t| curve.eval(t)[axis]);
            assert!(
                (bb.min[axis] - lo).abs() <= 1e-14 * size
                    && (bb.max[axis] - hi).abs() <= 1e-14 * size,
                "{what}, axis {axis}: box [{}, {}] vs sampled [{lo}, {hi}]",
                bb.min[axis],
                bb.max[axis]
            );
        }
    };
    let mut rng = Rng::new(21);
    let mut rnd = || rng.unit();
    for count in 0..120 {
        let n = 2 + count % 3;
        let three_d = count % 4 == 0;
        let b = Bezier::new(
            (0..n)
                .map(|_| DVec3::new(4.0 * rnd() - 2.0, rnd(), if three_d { rnd() } else { 0.0 }))
                .collect(),
        );
        check(&b, &CurveAnalysis::new(&b), &format!("{:?}", b.points()));
    }
    let hard = [
        // x(t) = (t − 0.4)³ scaled: x′ has a double root at 0.4.
        vec![(-0.064, 0.0), (0.056, 1.0), (-0.024, 1.0), (0.216, 0.0)],
        // x′ with two roots 10⁻⁹ apart around ½ (an extremum pair closer than the samples).
        vec![(0.0, 0.0), (0.5 + 1e-9, 1.0), (0.5 - 1e-9, 1.0), (1.0, 0.0)],
        // A constant coordinate, a line doubling back, a point.
        vec![(0.0, 1.0), (1.0, 1.0), (2.0, 1.0), (3.0, 1.0)],
        vec![(0.0, 0.0), (3.0, 3.0), (-1.0, -1.0), (1.0, 1.0)],
        vec![(0.5, 0.5), (0.5, 0.5), (0.5, 0.5)],
    ];
    for pts in hard {
        let b = bezier(&pts);
        check(&b, &CurveAnalysis::new(&b), &format!("{pts:?}"));
    }
    let spline = BSpline::try_new(
        vec![
            p2(0.0, 0.0),
            p2(1.0, 3.0),
            p2(2.0, -1.0),
            p2(3.0, 2.0),
            p2(2.5, 4.0),
            p2(4.0, 0.0),
            p2(5.0, 1.0),
        ],
        [0.0, 0.0, 0.0, 0.0, 0.2, 0.5, 0.55, 1.0, 1.0, 1.0, 1.0].to_vec(),
        4,
    )
    .expect("spline");
    check(&spline, &CurveAnalysis::new(&spline), "cubic B-spline");
}

#[test]
fn signed_areas() {
    for r in [1.0, 0.3, 5.0] {
        let a = CurveAnalysis::new(&circle(r)).signed_area().expect("area");
        assert!((a - PI * r * r).abs() <= 1e-13 * r * r, "{a}");
    }
    // A closed cubic B-spline against the shoelace formula on a dense polygon.
    let closed = BSpline::try_new(
        [
            (0.0, 0.0),
            (2.0, -1.0),
            (4.0, 1.0),
            (3.0, 4.0),
            (0.0, 3.0),
            (-1.0, 1.0),
            (0.0, 0.0),
        ]
        .iter()
        .map(|&(x, y)| p2(x, y))
        .collect(),
        vec![0., 0., 0., 0., 0.25, 0.5, 0.75, 1., 1., 1., 1.],
        4,
    )
    .expect("spline");
    let c = CurveAnalysis::new(&closed);
    assert!(c.is_closed());
    let n = 400_000;
    let poly: Vec<DVec3> = (0..=n)
        .map(|k| closed.eval(f64::from(k) / f64::from(n)))
        .collect();
    let shoelace: f64 = 0.5
        * poly
            .windows(2)
            .map(|w| w[0].x * w[1].y - w[1].x * w[0].y)
            .sum::<f64>();
    let area = c.signed_area().expect("area");
    assert!(
        (area - shoelace).abs() <= 1e-9 * shoelace.abs(),
        "{area} vs {shoelace}"
    );
    // Reversed, the sign flips; an open curve is closed by its chord: a semicircle's
    // upper half (the quarter arcs from (1,0) to (−1,0)) encloses π/2.
    let upper = Nurbs::try_new(
        circle(1.0).points()[..5].to_vec(),
        vec![1.0, FRAC_1_SQRT_2, 1.0, FRAC_1_SQRT_2, 1.0],
        vec![0., 0., 0., 0.5, 0.5, 1., 1., 1.],
        3,
    )
    .expect("half");
    let a = CurveAnalysis::new(&upper).signed_area().expect("area");
    assert!((a - 0.5 * PI).abs() < 1e-13, "{a}");
    let three = CurveAnalysis::new(&Bezier::new(vec![DVec3::ZERO, DVec3::new(1.0, 1.0, 1.0)]));
    assert!(matches!(
        three.signed_area(),
        Err(AnalysisError::NotPlanar { .. })
    ));
}

// ---------------------------------------------------------------------------------------
// Inflections, cusps, curvature extrema.

#[test]
fn inflections_and_cusps() {
    // The S-shaped cubic symmetric about its middle has its inflection at t = ½.
    let s_curve = CurveAnalysis::new(&bezier(&[(0.0, 0.0), (1.0, 1.0), (2.0, -1.0), (3.0, 0.0)]));
    let inf = s_curve.inflections().expect("inflections");
    assert_eq!(inf.len(), 1);
    assert!((inf[0] - 0.5).abs() < 1e-15, "{inf:?}");
    // A general cubic: x′y″ − y′x″ is a quadratic (power form, written here) whose roots
    // in (0, 1) are the inflections.
    let pts = [(0.0, 0.0), (4.0, 3.0), (-1.0, 2.0), (3.0, -1.0)];
    let b = bezier(&pts);
    let pw = |k: usize| -> [f64; 4] {
        // Power coefficients of the cubic's coordinate k.
        let p: Vec<f64> = pts.iter().map(|q| if k == 0 { q.0 } else { q.1 }).collect();
        [
            p[0],
            3.0 * (p[1] - p[0]),
            3.0 * (p[2] - 2.0 * p[1] + p[0]),
            p[3] - 3.0 * p[2] + 3.0 * p[1] - p[0],
        ]
    };
    let (x, y) = (pw(0), pw(1));
    // x′ = x1 + 2x2 t + 3x3 t², x″ = 2x2 + 6x3 t.
    // x′y″ − y′x″ = (2x1y2 − 2y1x2) + (6x1y3 − 6y1x3) t + (6x2y3 − 6y2x3) t² (t² terms of
    // 12x2y3 − 12y2x3 halve: 2·3 − 3·2 = …) — computed numerically instead:
    let f = |t: f64| {
        let (dx, dy) = (
            x[1] + 2.0 * x[2] * t + 3.0 * x[3] * t * t,
            y[1] + 2.0 * y[2] * t + 3.0 * y[3] * t * t,
        );
        let (ddx, ddy) = (2.0 * x[2] + 6.0 * x[3] * t, 2.0 * y[2] + 6.0 * y[3] * t);
        dx * ddy - dy * ddx
    };
    let (c0, c1) = (f(0.0), f(1.0));
    let cm = f(0.5);
    // A quadratic through three values: a t² + b t + c.
    let qa = 2.0 * (c0 - 2.0 * cm + c1);
    let qb = c1 - c0 - qa;
    let qc = c0;
    let disc = (qb * qb - 4.0 * qa * qc).sqrt();
    let mut want: Vec<f64> = [(-qb - disc) / (2.0 * qa), (-qb + disc) / (2.0 * qa)]
        .into_iter()
        .filter(|t| *t > 0.0 && *t < 1.0)
        .collect();
    want.sort_by(f64::total_cmp);
    let got = CurveAnalysis::new(&b).inflections().expect("inflections");
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() < 1e-12, "{g} vs {w}");
    }
    // The cusp of (0,0), (1,1), (0,1), (1,0) at t = ½ is a cusp, not an inflection.
    let cusp = CurveAnalysis::new(&bezier(&[(0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)]));
    let cs = cusp.cusps().expect("cusps");
    assert_eq!(cs.len(), 1);
    assert!((cs[0] - 0.5).abs() < 1e-7, "{cs:?}");
    assert!(cusp.inflections().expect("inflections").is_empty());
    // A quadratic B-spline (C¹) whose curvature flips sign at a knot: an inflection there.
    let wave = BSpline::try_new(
        [(0.0, 0.0), (1.0, 1.0), (2.0, 0.0), (3.0, 1.0)]
            .iter()
            .map(|&(x, y)| p2(x, y))
            .collect(),
        vec![0., 0., 0., 0.5, 1., 1., 1.],
        3,
    )
    .expect("wave");
    let inf = CurveAnalysis::new(&wave)
        .inflections()
        .expect("inflections");
    assert_eq!(inf, vec![0.5]);
    // 3D curves are refused.
    let helix = CurveAnalysis::new(&Bezier::new(vec![
        DVec3::ZERO,
        DVec3::new(1.0, 0.0, 1.0),
        DVec3::new(1.0, 1.0, 2.0),
    ]));
    let e = helix.inflections().expect_err("3D");
    assert!(e.to_string().contains("planar"), "{e}");
}

#[test]
fn curvature_extrema_at_known_vertices() {
    // The parabola y = x² (quadratic (−1, 1), (0, −1), (1, 1)) has its vertex at x = 0,
    // t = ½, with κ = 2.
    let p = CurveAnalysis::new(&bezier(&[(-1.0, 1.0), (0.0, -1.0), (1.0, 1.0)]));
    let ex = p.curvature_extrema().expect("extrema");
    assert_eq!(ex.len(), 1, "{ex:?}");
    assert!((ex[0].t - 0.5).abs() < 1e-12 && (ex[0].curvature - 2.0).abs() < 1e-9);
    assert_eq!(ex[0].kind, ExtremumKind::Maximum);
    // An ellipse x²/9 + y²/4 = 1 as four rational quadratic arcs: vertices at the ends of
    // the axes — κ = a/b² = 0.75 at (±3, 0), b/a² = 2/9 at (0, ±2).
    let (a, bb) = (3.0, 2.0);
    let c = circle(1.0);
    let ellipse = Nurbs::try_new(
        c.points().iter().map(|q| p2(a * q.x, bb * q.y)).collect(),
        c.weights().to_vec(),
        c.knots().knots().to_vec(),
        3,
    )
    .expect("ellipse");
    let ex = CurveAnalysis::new(&ellipse)
        .curvature_extrema()
        .expect("extrema");
    let at = |x: f64, y: f64| ex.iter().find(|e| (e.point - p2(x, y)).length() < 1e-9);
    let top = at(0.0, bb).expect("vertex (0, 2)");
    assert!((top.curvature - bb / (a * a)).abs() < 1e-9 && top.kind == ExtremumKind::Minimum);
    let left = at(-a, 0.0).expect("vertex (−3, 0)");
    assert!((left.curvature - a / (bb * bb)).abs() < 1e-9 && left.kind == ExtremumKind::Maximum);
    assert!(at(0.0, -bb).is_some());
    // A circle: constant curvature, no extrema.
    assert!(
        CurveAnalysis::new(&circle(2.0))
            .curvature_extrema()
            .expect("extrema")
            .is_empty()
    );
    // Traversed the other way, each curve turns right (κ < 0): the sharpest point is still
    // the maximum — the extrema are of |κ| — and the signed κ says which way it turns.
    let down = CurveAnalysis::new(&bezier(&[(1.0, 1.0), (0.0, -1.0), (-1.0, 1.0)]));
    let ex = down.curvature_extrema().expect("extrema");
    assert_eq!(ex.len(), 1, "{ex:?}");
    assert!((ex[0].curvature + 2.0).abs() < 1e-9, "{ex:?}");
    assert_eq!(ex[0].kind, ExtremumKind::Maximum);
    let reversed = Nurbs::try_new(
        ellipse.points().iter().rev().copied().collect(),
        ellipse.weights().iter().rev().copied().collect(),
        ellipse
            .knots()
            .knots()
            .iter()
            .rev()
            .map(|k| 1.0 - k)
            .collect(),
        3,
    )
    .expect("reversed ellipse");
    let ex = CurveAnalysis::new(&reversed)
        .curvature_extrema()
        .expect("extrema");
    let at = |x: f64, y: f64| ex.iter().find(|e| (e.point - p2(x, y)).length() < 1e-9);
    let top = at(0.0, bb).expect("vertex (0, 2)");
    assert!((top.curvature + bb / (a * a)).abs() < 1e-9 && top.kind == ExtremumKind::Minimum);
    let left = at(-a, 0.0).expect("vertex (−3, 0)");
    assert!((left.curvature + a / (bb * bb)).abs() < 1e-9 && left.kind == ExtremumKind::Maximum);
    // An S curve: a bend each way, both sharpest points maxima, κ of opposite signs; the
    // inflection between them is no minimum.
    let s = CurveAnalysis::new(&bezier(&[(0.0, 0.0), (1.0, 2.0), (2.0, -2.0), (3.0, 0.0)]));
    let ex = s.curvature_extrema().expect("extrema");
    let maxima: Vec<f64> = ex
        .iter()
        .filter(|e| e.kind == ExtremumKind::Maximum)
        .map(|e| e.curvature)
        .collect();
    assert_eq!(maxima.len(), 2, "{ex:?}");
    assert!(maxima[0] * maxima[1] < 0.0, "{ex:?}");
    let inflection = s.inflections().expect("inflections")[0];
    assert!(ex.iter().all(|e| (e.t - inflection).abs() > 1e-6), "{ex:?}");
}

// ---------------------------------------------------------------------------------------
// Intersections.

/// Where two dense polylines cross (independent of the engine): approximate points.
fn polyline_crossings(a: &impl ParamCurve, b: &impl ParamCurve, n: usize) -> Vec<DVec3> {
    let pa: Vec<DVec3> = (0..=n)
        .map(|k| a.eval(a.domain().0 + (a.domain().1 - a.domain().0) * k as f64 / n as f64))
        .collect();
    let pb: Vec<DVec3> = (0..=n)
        .map(|k| b.eval(b.domain().0 + (b.domain().1 - b.domain().0) * k as f64 / n as f64))
        .collect();
    let mut out = Vec::new();
    for s in pa.windows(2) {
        for t in pb.windows(2) {
            let (d, e) = (s[1] - s[0], t[1] - t[0]);
            let det = d.x * e.y - d.y * e.x;
            if det == 0.0 {
                continue;
            }
            let r = t[0] - s[0];
            let al = (r.x * e.y - r.y * e.x) / det;
            let be = (r.x * d.y - r.y * d.x) / det;
            if (0.0..1.0).contains(&al) && (0.0..1.0).contains(&be) {
                out.push(s[0] + al * d);
            }
        }
    }
    out
}

#[test]
fn curve_curve_crossings_against_polylines() {
    let a = bezier(&[(0.0, 0.0), (1.0, 3.0), (2.0, -2.0), (3.0, 1.0)]);
    let b = bezier(&[(0.0, 1.0), (1.5, -2.0), (2.0, 3.0), (3.0, -0.5)]);
    let (ca, cb) = (CurveAnalysis::new(&a), CurveAnalysis::new(&b));
    let found = ca.intersect(&cb).expect("planar");
    let rough = polyline_crossings(&a, &b, 2000);
    assert_eq!(found.hits.len(), rough.len(), "{found:?} vs {rough:?}");
    for h in &found.hits {
        assert_eq!(h.kind, HitKind::Crossing);
        // Both parameters give the same point, to a few ulps of the size.
        assert!((a.eval(h.s) - b.eval(h.t)).length() <= 1e-14, "{h:?}");
        assert!(rough.iter().any(|p| (*p - h.point).length() < 1e-5));
    }
    // A rational curve and a B-spline, against the polyline too.
    let c = circle_at(1.5, 0.5, 1.2);
    let cc = CurveAnalysis::new(&c);
    let found = cc.intersect(&ca).expect("planar");
    let rough = polyline_crossings(&c, &a, 4000);
    assert_eq!(found.hits.len(), rough.len(), "{found:?} vs {rough:?}");
    for h in &found.hits {
        assert!((c.eval(h.s) - a.eval(h.t)).length() <= 1e-13, "{h:?}");
    }
}

#[test]
fn tangencies_overlaps_and_shared_ends() {
    // Two unit circles touching at the origin: one tangent point.
    let (l, r) = (circle_at(-1.0, 0.0, 1.0), circle_at(1.0, 0.0, 1.0));
    let found = CurveAnalysis::new(&l)
        .intersect(&CurveAnalysis::new(&r))
        .expect("planar");
    assert_eq!(found.hits.len(), 1, "{found:?}");
    let h = found.hits[0];
    assert_eq!(h.kind, HitKind::Tangent);
    assert!(h.point.length() < 1e-7, "{h:?}");
    // The circle and its tangent line y = 1 (a straight cubic): tangent at (0, 1).
    let line = bezier(&[(-2.0, 1.0), (-1.0, 1.0), (1.0, 1.0), (2.0, 1.0)]);
    let found = CurveAnalysis::new(&circle(1.0))
        .intersect(&CurveAnalysis::new(&line))
        .expect("planar");
    assert_eq!(found.hits.len(), 1, "{found:?}");
    assert_eq!(found.hits[0].kind, HitKind::Tangent);
    assert!((found.hits[0].point - p2(0.0, 1.0)).length() < 1e-7);
    // A cubic and a piece of itself: one overlap, s ∈ [0.2, 0.7], t ∈ [0, 1].
    let a = bezier(&[(0.0, 0.0), (1.0, 3.0), (2.0, -2.0), (3.0, 1.0)]);
    let piece = a.subsegment(0.2, 0.7);
    let found = CurveAnalysis::new(&a)
        .intersect(&CurveAnalysis::new(&piece))
        .expect("planar");
    assert!(found.hits.is_empty(), "{found:?}");
    assert_eq!(found.overlaps.len(), 1, "{found:?}");
    let o = found.overlaps[0];
    assert!(
        (o.s.0 - 0.2).abs() < 1e-9 && (o.s.1 - 0.7).abs() < 1e-9,
        "{o:?}"
    );
    assert!(o.t.0.abs() < 1e-9 && (o.t.1 - 1.0).abs() < 1e-9, "{o:?}");
    // Curves meeting at their end points: one crossing at (s, t) = (1, 0).
    let b = bezier(&[(3.0, 1.0), (4.0, 0.0), (5.0, 2.0)]);
    let found = CurveAnalysis::new(&a)
        .intersect(&CurveAnalysis::new(&b))
        .expect("planar");
    assert_eq!(found.hits.len(), 1, "{found:?}");
    assert!((found.hits[0].s - 1.0).abs() < 1e-12 && found.hits[0].t.abs() < 1e-12);
}

#[test]
fn self_intersections_and_lines() {
    // A symmetric loop: P = (0,0), (1.5,1), (−0.5,1), (1,0) crosses itself on x = ½ at
    // parameters s and 1 − s.
    let loop_ = bezier(&[(0.0, 0.0), (1.5, 1.0), (-0.5, 1.0), (1.0, 0.0)]);
    let found = CurveAnalysis::new(&loop_)
        .self_intersections()
        .expect("planar");
    assert_eq!(found.hits.len(), 1, "{found:?}");
    let h = found.hits[0];
    assert!(
        (h.s + h.t - 1.0).abs() < 1e-13 && (h.point.x - 0.5).abs() < 1e-13,
        "{h:?}"
    );
    assert!((loop_.eval(h.s) - loop_.eval(h.t)).length() < 1e-14);
    // A closed circle does not meet itself at its start; nor does an ellipse whose
    // extrema fall (to the last bit) on its segments' joints.
    assert!(
        CurveAnalysis::new(&circle(1.0))
            .self_intersections()
            .expect("planar")
            .hits
            .is_empty()
    );
    let c = circle(1.0);
    let ellipse = Nurbs::try_new(
        c.points()
            .iter()
            .map(|q| p2(24.0 + 4.5 * q.x, -25.5 + 2.5 * q.y))
            .collect(),
        c.weights().to_vec(),
        c.knots().knots().to_vec(),
        3,
    )
    .expect("ellipse");
    let found = CurveAnalysis::new(&ellipse)
        .self_intersections()
        .expect("planar");
    assert!(
        found.hits.is_empty() && found.overlaps.is_empty(),
        "{found:?}"
    );
    // The circle and the line y = ½: crossings at x = ±√¾; the line y = 1: one tangent.
    let c = CurveAnalysis::new(&circle(1.0));
    let found = c.intersect_line(p2(0.0, 0.5), p2(1.0, 0.5)).expect("line");
    let (hits, overlaps) = (found.hits, found.overlaps);
    assert!(overlaps.is_empty());
    let mut xs: Vec<f64> = hits.iter().map(|h| h.point.x).collect();
    xs.sort_by(f64::total_cmp);
    assert_eq!(xs.len(), 2);
    assert!((xs[0] + 0.75f64.sqrt()).abs() < 1e-15 && (xs[1] - 0.75f64.sqrt()).abs() < 1e-15);
    let hits = c
        .intersect_line(p2(0.0, 1.0), p2(1.0, 1.0))
        .expect("line")
        .hits;
    assert_eq!(hits.len(), 1);
    assert_eq!(hits[0].kind, HitKind::Tangent);
    // A polyline (order-2 B-spline) with a leg on the line: an overlap.
    let zig = BSpline::try_new(
        [(0.0, 0.0), (1.0, 1.0), (2.0, 1.0), (3.0, 0.0)]
            .iter()
            .map(|&(x, y)| p2(x, y))
            .collect(),
        vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0],
        2,
    )
    .expect("polyline");
    let found = CurveAnalysis::new(&zig)
        .intersect_line(p2(0.0, 1.0), p2(5.0, 1.0))
        .expect("line");
    assert!(found.hits.is_empty(), "{:?}", found.hits);
    assert_eq!(found.overlaps, vec![(1.0, 2.0)]);
    assert!(c.intersect_line(p2(1.0, 1.0), p2(1.0, 1.0)).is_err());
}

#[test]
fn many_curves_agree_with_every_pair() {
    // Random cubics in a 4×4 square: every pair intersected one by one against the sweep.
    let mut seed = 7_u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    // Half of them B-splines of three segments: a pair of curves is one entry, however
    // many of their segments meet.
    let curves: Vec<Curve> = (0..40)
        .map(|k| {
            if k % 2 == 0 {
                Curve::Bezier(Bezier::new(
                    (0..4).map(|_| p2(4.0 * rnd(), 4.0 * rnd())).collect(),
                ))
            } else {
                Curve::BSpline(
                    BSpline::try_new(
                        (0..6).map(|_| p2(4.0 * rnd(), 4.0 * rnd())).collect(),
                        vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.7, 1.0, 1.0, 1.0, 1.0],
                        4,
                    )
                    .expect("cubic B-spline"),
                )
            }
        })
        .collect();
    let analyses: Vec<CurveAnalysis> = curves.iter().map(CurveAnalysis::new).collect();
    let all = all_intersections(&analyses).expect("planar").pairs;
    for w in all.windows(2) {
        assert!(
            (w[0].i, w[0].j) < (w[1].i, w[1].j),
            "pair ({}, {}) reported twice or out of order",
            w[1].i,
            w[1].j
        );
    }
    let mut count = 0;
    for i in 0..curves.len() {
        for j in (i + 1)..curves.len() {
            let one = analyses[i].intersect(&analyses[j]).expect("planar");
            let swept = all.iter().find(|p| p.i == i && p.j == j);
            match swept {
                None => assert!(one.hits.is_empty(), "{i} {j}: {one:?}"),
                Some(p) => {
                    assert_eq!(p.found.hits.len(), one.hits.len(), "{i} {j}");
                    for (x, y) in p.found.hits.iter().zip(&one.hits) {
                        assert!((x.s - y.s).abs() < 1e-12 && (x.t - y.t).abs() < 1e-12);
                    }
                }
            }
            count += one.hits.len();
            let rough = polyline_crossings(&curves[i], &curves[j], 600);
            assert_eq!(one.hits.len(), rough.len(), "{i} {j}: {one:?} vs {rough:?}");
        }
    }
    assert!(count > 50, "{count}");
}

#[test]
fn families_are_answered_through_their_segments() {
    // A modified Bézier curve and a NUBMP curve have lengths and boxes like any other.
    let m = splinescope_core::geom::ModifiedBezier::try_new(
        bezier(&[(0.0, 0.0), (1.0, 2.0), (3.0, 2.0), (4.0, 0.0)]),
        0.4,
        p2(0.0, 1.0),
    )
    .expect("modified");
    let c = CurveAnalysis::new(&m);
    let l = c.length(0.0, 1.0, 1e-12).expect("length");
    let want = reference_length(&m, 0.0, 0.4, 3000) + reference_length(&m, 0.4, 1.0, 3000);
    assert!((l.value - want).abs() < 1e-11, "{} vs {want}", l.value);
    let bb = c.bounding_box();
    for k in 0..=1000 {
        let p = m.eval(f64::from(k) / 1000.0);
        assert!(bb.min.cmple(p + 1e-12).all() && bb.max.cmpge(p - 1e-12).all());
    }
    let segments = m.lower().len();
    assert_eq!(segments, 2);
}

#[test]
fn a_shared_end_where_a_speed_vanishes_is_one_point_with_a_finite_error() {
    // A cubic whose first two control points coincide has zero speed at its start: the
    // crossing's condition number is infinite there, yet the point is one point, and its
    // error a number (measured from where the curves part), never NaN.
    let a = bezier(&[(0.0, 0.0), (0.0, 0.0), (1.0, 2.0), (3.0, 0.0)]);
    for (far, repeated) in [
        ((3.0, 3.0), false),
        ((-2.0, 1.0), false),
        ((2.0, -1.0), true),
    ] {
        let b = if repeated {
            bezier(&[(0.0, 0.0), (0.0, 0.0), far])
        } else {
            bezier(&[(0.0, 0.0), (1.0, 0.25), far])
        };
        let found = CurveAnalysis::new(&a)
            .intersect(&CurveAnalysis::new(&b))
            .expect("planar");
        let at_start: Vec<_> = found
            .hits
            .iter()
            .filter(|h| h.s.abs() < 1e-6 && h.t.abs() < 1e-6)
            .collect();
        assert_eq!(at_start.len(), 1, "{far:?}: {:?}", found.hits);
        for h in &found.hits {
            assert!(
                h.error_s.is_finite() && h.error_t.is_finite(),
                "{far:?}: {h:?}"
            );
        }
    }
    // Quartics from one start, one of them with its first two control points equal (as
    // paper 001's Fig. 1 curves lower to).
    let pts = [
        (24.0, -19.35),
        (24.75, -14.85),
        (27.0, -13.65),
        (28.5, -17.55),
        (30.0, -13.65),
    ];
    let mut q = pts.to_vec();
    q[1] = q[0];
    let found = CurveAnalysis::new(&bezier(&pts))
        .intersect(&CurveAnalysis::new(&bezier(&q)))
        .expect("planar");
    assert_eq!(
        found
            .hits
            .iter()
            .filter(|h| h.s == 0.0 && h.t == 0.0)
            .count(),
        1,
        "{:?}",
        found.hits
    );
    for h in &found.hits {
        assert!(h.error_s.is_finite() && h.error_t.is_finite(), "{h:?}");
    }
    // Through a cusp (zero speed at t = ½, the point (½, ¾)), by lines at several slopes.
    let cusp = bezier(&[(0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)]);
    for (dx, dy) in [(1.0, 0.0), (1.0, 0.5), (0.25, 1.0), (0.0, 1.0), (1.0, -1.0)] {
        let line = bezier(&[(0.5 - dx, 0.75 - dy), (0.5 + dx, 0.75 + dy)]);
        let found = CurveAnalysis::new(&cusp)
            .intersect(&CurveAnalysis::new(&line))
            .expect("planar");
        let at_cusp = found
            .hits
            .iter()
            .filter(|h| (h.s - 0.5).abs() < 1e-4 && (h.t - 0.5).abs() < 1e-4)
            .count();
        assert_eq!(at_cusp, 1, "({dx}, {dy}): {:?}", found.hits);
        for h in &found.hits {
            assert!(
                h.error_s.is_finite() && h.error_t.is_finite(),
                "({dx}, {dy}): {h:?}"
            );
            assert!(
                (h.s - 0.5).abs() > 1e-4 || (h.s - 0.5).abs() <= h.error_s.max(1e-8),
                "{h:?}"
            );
        }
    }
}
