//! Batch evaluation against independent truth: Bézier curves of degrees 1–40 against exact
//! rational evaluation (the Bernstein sum in rationals of the same `f64` inputs) within the
//! documented bound; every family's sampler against the family's own evaluation (de Boor
//! for B-splines, the dual form for NUBMP curves, the bump for modified curves); the
//! parallel batch equal to the serial one.

use glam::DVec3;
use num_traits::{One, ToPrimitive, Zero};
use splinescope_core::geom::ParamCurve;
use splinescope_core::geom::batch::{
    CurveSampler, UniformCubicWeights, bezier_into, for_each_sampled, sample_many, uniform,
};
use splinescope_core::geom::exact::{Rational, rational_from_f64};
use splinescope_core::geom::{Bezier, Curve};
use splinescope_core::rng::Rng;

fn exact_bezier(points: &[DVec3], u: f64) -> [f64; 3] {
    exact_bezier_and_scale(points, u).0
}

/// The exact Bernstein sum at the exact `u`, and the exact `Σ|P_i| B_i(u)` per coordinate
/// (the scale of the evaluation's rounding), each rounded to the nearest `f64` once.
fn exact_bezier_and_scale(points: &[DVec3], u: f64) -> ([f64; 3], [f64; 3]) {
    let n = points.len() - 1;
    let t = rational_from_f64(u).expect("finite");
    let s = Rational::one() - t.clone();
    let mut sum = [Rational::zero(), Rational::zero(), Rational::zero()];
    let mut scale = [Rational::zero(), Rational::zero(), Rational::zero()];
    let powers = |x: &Rational| {
        let mut v = vec![Rational::one()];
        for k in 0..n {
            let next = v[k].clone() * x.clone();
            v.push(next);
        }
        v
    };
    let (tp, sp) = (powers(&t), powers(&s));
    let mut binomial = Rational::one();
    for (i, p) in points.iter().enumerate() {
        if i > 0 {
            binomial = binomial * Rational::from_integer((n + 1 - i).into())
                / Rational::from_integer(i.into());
        }
        let w = binomial.clone() * tp[i].clone() * sp[n - i].clone();
        for ((acc, mag), c) in sum.iter_mut().zip(scale.iter_mut()).zip(p.to_array()) {
            *acc = acc.clone() + w.clone() * rational_from_f64(c).expect("finite");
            *mag = mag.clone() + w.clone() * rational_from_f64(c.abs()).expect("finite");
        }
    }
    let f = |r: &Rational| r.to_f64().expect("representable");
    (sum.each_ref().map(f), scale.each_ref().map(f))
}

#[test]
fn bezier_batches_are_within_the_bound_of_exact_evaluation() {
    let mut rng = Rng::new(21);
    for degree in 1..=40usize {
        let points: Vec<DVec3> = (0..=degree)
            .map(|_| {
                DVec3::new(
                    rng.range(-3.0, 3.0),
                    rng.range(-3.0, 3.0),
                    rng.range(-3.0, 3.0),
                )
            })
            .collect();
        let mut us: Vec<f64> = (0..20).map(|_| rng.unit()).collect();
        us.extend([0.0, 1.0, 0.5]);
        let mut out = vec![DVec3::ZERO; us.len()];
        bezier_into(&points, &us, &mut out);
        for (&u, got) in us.iter().zip(&out) {
            let want = exact_bezier(&points, u);
            // 2 n ε Σ |P_i| B_i(u) ≤ 2 n ε max |P_i| (the Bernstein weights sum to 1).
            let scale = points
                .iter()
                .map(|p| p.abs().max_element())
                .fold(0.0, f64::max);
            let bound = 2.0 * degree as f64 * f64::EPSILON / 2.0 * scale;
            for (g, w) in got.to_array().iter().zip(want) {
                assert!(
                    (g - w).abs() <= bound,
                    "degree {degree}, u = {u}: {g} vs exact {w} (bound {bound:e})"
                );
            }
        }
        // The ends are the end points exactly.
        assert_eq!(out[us.len() - 3], points[0]);
        assert_eq!(out[us.len() - 2], points[degree]);
    }
}

/// The general path (degrees 4 to 31) against exact rational evaluation and its bound
/// `γ_{2n} Σ|P_i| B_i(u)` taken at each parameter — tight where cancellation makes the
/// curve's value small against its control points: clustered control points far from the
/// origin, alternating ones, random ones, planar and not; parameters at and near both ends
/// and random. Where the CPU has no fused multiply-add the path is de Casteljau, whose
/// bound with `1 − u` rounded is `γ_{3n}`.
#[test]
fn high_degrees_are_within_their_bound_of_exact_evaluation() {
    let fused = cfg!(target_arch = "x86_64") && fma_available();
    let mut rng = Rng::new(33);
    let mut us: Vec<f64> = vec![0.0, 1.0, 0.5, 1e-9, 1.0 - 1e-9, 0.25, 0.75, 1e-300];
    us.extend((0..24).map(|_| rng.unit()));
    assert_eq!(
        us.len() % 4,
        0,
        "whole groups of four: every parameter on the lanes"
    );
    for degree in 4..=31usize {
        let cases: [(&str, Vec<DVec3>); 4] = [
            (
                "clustered far from the origin",
                (0..=degree)
                    .map(|_| {
                        DVec3::new(
                            1e6 + rng.range(-1e-3, 1e-3),
                            -3e5 + rng.range(-1e-3, 1e-3),
                            7e4 + rng.range(-1e-3, 1e-3),
                        )
                    })
                    .collect(),
            ),
            (
                "alternating",
                (0..=degree)
                    .map(|i| {
                        let sign = if i % 2 == 0 { 1.0 } else { -1.0 };
                        sign * DVec3::new(1e3, 1.0 + rng.unit(), 1e-3)
                    })
                    .collect(),
            ),
            (
                "random",
                (0..=degree)
                    .map(|_| {
                        DVec3::new(
                            rng.range(-3.0, 3.0),
                            rng.range(-3.0, 3.0),
                            rng.range(-3.0, 3.0),
                        )
                    })
                    .collect(),
            ),
            (
                "planar",
                (0..=degree)
                    .map(|_| DVec3::new(rng.range(-5.0, 5.0), rng.range(-5.0, 5.0), 0.0))
                    .collect(),
            ),
        ];
        let rounds = if fused { 2 * degree } else { 3 * degree } as f64;
        let unit = f64::EPSILON / 2.0;
        let gamma = rounds * unit / (1.0 - rounds * unit);
        for (name, points) in &cases {
            let mut out = vec![DVec3::ZERO; us.len()];
            bezier_into(points, &us, &mut out);
            for (&u, got) in us.iter().zip(&out) {
                let (want, scale) = exact_bezier_and_scale(points, u);
                for ((g, w), m) in got.to_array().iter().zip(want).zip(scale) {
                    // The bound, and the rounding of the exact value to f64.
                    let bound = gamma * m * (1.0 + 1e-12) + unit * w.abs();
                    assert!(
                        (g - w).abs() <= bound,
                        "degree {degree}, {name}, u = {u}: {g} vs exact {w} (bound {bound:e})"
                    );
                }
            }
            assert_eq!(
                out[0], points[0],
                "degree {degree}, {name}: the start exactly"
            );
            assert_eq!(
                out[1], points[degree],
                "degree {degree}, {name}: the end exactly"
            );
        }
    }
}

#[cfg(target_arch = "x86_64")]
fn fma_available() -> bool {
    std::arch::is_x86_feature_detected!("fma")
}

#[cfg(not(target_arch = "x86_64"))]
fn fma_available() -> bool {
    false
}

#[test]
fn every_family_samples_like_its_own_evaluation() {
    let scene = splinescope_scene::format::gallery::gallery();
    for (i, c) in scene.curves.iter().enumerate() {
        let sampler = CurveSampler::new(&c.curve);
        let (a, b) = c.curve.domain();
        assert_eq!(sampler.domain(), (a, b), "curves[{i}]");
        let count = 257;
        let mut out = vec![DVec3::ZERO; count];
        sampler.sample_uniform_into(count, &mut out);
        let scale = c
            .curve
            .control_points()
            .iter()
            .map(|p| p.length())
            .fold(1.0, f64::max);
        for (j, got) in out.iter().enumerate() {
            let t = uniform(a, b, j, count);
            let want = c.curve.eval(t);
            assert!(
                (*got - want).length() <= 1e-12 * scale,
                "curves[{i}] ({}) at t = {t}: {got} vs {want}",
                c.curve.family()
            );
        }
        // Unsorted parameters, repeated ones, and ones outside the domain (extrapolated
        // from the end segments, as the family does for a Bézier curve).
        let ts = [b, a, 0.5 * (a + b), a, b];
        let mut out = [DVec3::ZERO; 5];
        sampler.eval_into(&ts, &mut out);
        for (t, got) in ts.iter().zip(out) {
            assert!(
                (got - c.curve.eval(*t)).length() <= 1e-12 * scale,
                "curves[{i}] at {t}"
            );
        }
    }
}

/// Runs of parameters in one segment are found from the previous run's segment for
/// sorted input, by a search otherwise: either way every parameter, sorted or shuffled,
/// at a knot exactly, between knots, repeated or outside the domain, evaluates to the same
/// bits as when it is passed alone (where only the search runs), for a B-spline with
/// repeated interior knots (a zero-length segment) and a NURBS curve.
#[test]
fn runs_of_sorted_and_shuffled_parameters_equal_lone_evaluation() {
    use splinescope_core::geom::{BSpline, Lower, Nurbs, locate};
    let mut rng = Rng::new(7);
    let points: Vec<DVec3> = (0..12)
        .map(|_| DVec3::new(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0), 0.0))
        .collect();
    let knots = vec![
        0.0, 0.0, 0.0, 0.0, 0.1, 0.25, 0.25, 0.4, 0.55, 0.7, 0.7, 0.85, 1.0, 1.0, 1.0, 1.0,
    ];
    let weights: Vec<f64> = (0..12).map(|i| 0.5 + f64::from(i % 4) * 0.5).collect();
    let curves: [Curve; 2] = [
        BSpline::try_new(points.clone(), knots.clone(), 4)
            .expect("valid")
            .into(),
        Nurbs::try_new(points, weights, knots.clone(), 4)
            .expect("valid")
            .into(),
    ];
    let mut ts: Vec<f64> = knots.clone();
    ts.extend((0..600).map(|_| rng.unit()));
    ts.extend([-0.25, 1.5, 0.25, 0.25]);
    let mut sorted = ts.clone();
    sorted.sort_by(f64::total_cmp);
    for curve in &curves {
        let sampler = CurveSampler::new(curve);
        let segments = curve.lower();
        for params in [&ts, &sorted] {
            let mut batch = vec![DVec3::ZERO; params.len()];
            sampler.eval_into(params, &mut batch);
            for (&t, got) in params.iter().zip(&batch) {
                let mut lone = [DVec3::ZERO];
                sampler.eval_into(&[t], &mut lone);
                assert_eq!(
                    got.to_array().map(f64::to_bits),
                    lone[0].to_array().map(f64::to_bits),
                    "{} at t = {t}",
                    curve.family()
                );
                // The polynomial curve also against its segment found by the library's
                // search and evaluated at that segment's own local parameter.
                if matches!(curve, Curve::BSpline(_)) {
                    let (index, u) = locate(&segments, t).expect("segments");
                    let mut want = [DVec3::ZERO];
                    bezier_into(segments[index].points(), &[u], &mut want);
                    assert_eq!(
                        got.to_array().map(f64::to_bits),
                        want[0].to_array().map(f64::to_bits),
                        "B-spline at t = {t}: segment {index}, u = {u}"
                    );
                }
            }
        }
    }
}

#[test]
fn the_parallel_batch_equals_the_serial_one() {
    let scene = splinescope_scene::format::generate::random_bezier_scene(
        splinescope_scene::format::generate::StressOptions {
            curves: 3000,
            degree: 5,
            ..Default::default()
        },
    );
    let samplers: Vec<CurveSampler> = scene
        .curves
        .iter()
        .map(|c| CurveSampler::new(&c.curve))
        .collect();
    let count = 33;
    let mut parallel = vec![DVec3::ZERO; samplers.len() * count];
    sample_many(&samplers, count, &mut parallel);
    for (c, s) in samplers.iter().enumerate() {
        let mut serial = vec![DVec3::ZERO; count];
        s.sample_uniform_into(count, &mut serial);
        assert_eq!(
            &parallel[c * count..(c + 1) * count],
            serial.as_slice(),
            "curve {c}"
        );
    }
}

#[test]
fn shared_cubic_weights_sample_within_the_bound_of_exact_evaluation() {
    let mut rng = Rng::new(77);
    for count in [2usize, 3, 17, 64, 65, 1000] {
        let weights = UniformCubicWeights::new(count);
        assert_eq!(weights.count(), count);
        for trial in 0..20 {
            // Coordinates far from the origin too: the bound scales with them.
            let offset = if trial % 2 == 0 { 0.0 } else { 1e6 };
            let points: Vec<DVec3> = (0..4)
                .map(|_| {
                    DVec3::new(
                        offset + rng.range(-3.0, 3.0),
                        rng.range(-3.0, 3.0),
                        -offset + rng.range(-3.0, 3.0),
                    )
                })
                .collect();
            let sampler = CurveSampler::new(&Curve::Bezier(Bezier::new(points.clone())));
            let mut out = vec![DVec3::ZERO; count];
            sampler.sample_uniform_with(&weights, &mut out);
            let scale = points
                .iter()
                .map(|p| p.abs().max_element())
                .fold(0.0, f64::max);
            let bound = 3.0 * f64::EPSILON * scale;
            for (j, got) in out.iter().enumerate() {
                let u = uniform(0.0, 1.0, j, count);
                let want = exact_bezier(&points, u);
                for (g, w) in got.to_array().iter().zip(want) {
                    assert!(
                        (g - w).abs() <= bound,
                        "count {count}, sample {j}: {g} vs exact {w} (bound {bound:e})"
                    );
                }
            }
            assert_eq!(out[0], points[0], "the start exactly");
            assert_eq!(out[count - 1], points[3], "the end exactly");
        }
    }
}

#[test]
fn streamed_samples_equal_the_serial_ones_curve_by_curve() {
    let mut curves = splinescope_scene::format::generate::random_bezier_scene(
        splinescope_scene::format::generate::StressOptions {
            curves: 2000,
            degree: 3,
            ..Default::default()
        },
    )
    .curves;
    // Other families and degrees take the general path.
    curves.extend(splinescope_scene::format::gallery::gallery().curves);
    let samplers: Vec<CurveSampler> = curves.iter().map(|c| CurveSampler::new(&c.curve)).collect();
    let count = 40;
    let weights = UniformCubicWeights::new(count);
    let seen = std::sync::Mutex::new(vec![None; samplers.len()]);
    for_each_sampled(&samplers, count, |i, points| {
        let mut seen = seen.lock().expect("lock");
        assert!(seen[i].is_none(), "curve {i} handed over twice");
        seen[i] = Some(points.to_vec());
    });
    for (i, (s, got)) in samplers
        .iter()
        .zip(seen.into_inner().expect("lock"))
        .enumerate()
    {
        let mut serial = vec![DVec3::ZERO; count];
        s.sample_uniform_with(&weights, &mut serial);
        assert_eq!(got.as_deref(), Some(serial.as_slice()), "curve {i}");
    }
}
