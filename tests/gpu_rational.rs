//! Rational curves on the GPU, against closed forms, on every backend: the quarter circle
//! and the nine-point NURBS circle evaluated in homogeneous coordinates stay on the circle
//! within the documented `f32` bound (README, "Rational curves": `2κ · 10⁻⁶ · S` with
//! `κ = max w / min w` of a segment and `S` the larger of its control extent and largest
//! coordinate), and the derivatives the GPU path gives by the quotient rule match the
//! circle's exact tangent and curvature.

mod common;

use glam::DVec3;
use splinescope_core::geom::{Curve, Lower, Nurbs, ParamCurve, RationalBezier};
use splinescope_gpu::eval::{evaluate, evaluate_derivative};

const HALF_SQRT2: f64 = std::f64::consts::FRAC_1_SQRT_2;

fn circles() -> Vec<(String, Curve, DVec3, f64)> {
    let mut out = vec![(
        "quarter circle".to_owned(),
        Curve::RationalBezier(
            RationalBezier::try_new(
                vec![DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
                vec![1.0, HALF_SQRT2, 1.0],
            )
            .expect("quarter circle"),
        ),
        DVec3::ZERO,
        1.0,
    )];
    for (c, r) in [
        (DVec3::ZERO, 1.0),
        (DVec3::new(3.0, -2.0, 0.0), 2.5),
        (DVec3::new(0.0, 0.0, 4.0), 1e-3),
        (DVec3::ZERO, 1e6),
    ] {
        out.push((
            format!("nine-point circle about {c}, radius {r}"),
            Curve::Nurbs(Nurbs::circle(c, r).expect("circle")),
            c,
            r,
        ));
    }
    out
}

/// The documented bound for a rational curve's GPU values.
fn bound(curve: &Curve) -> f64 {
    curve
        .lower()
        .iter()
        .map(|s| {
            let pts = s.points();
            let lo = pts
                .iter()
                .fold(DVec3::splat(f64::INFINITY), |a, p| a.min(*p));
            let hi = pts
                .iter()
                .fold(DVec3::splat(f64::NEG_INFINITY), |a, p| a.max(*p));
            let radius = pts.iter().map(|p| p.length()).fold(0.0, f64::max);
            let w = s.weights.as_deref().unwrap_or(&[1.0]);
            let kappa = w.iter().copied().fold(0.0, f64::max)
                / w.iter().copied().fold(f64::INFINITY, f64::min);
            2.0 * kappa * 1e-6 * (hi - lo).length().max(radius)
        })
        .fold(0.0, f64::max)
}

#[test]
fn circles_stay_on_the_circle_within_the_f32_bound() {
    let cases = circles();
    let params: Vec<Vec<f64>> = cases
        .iter()
        .map(|_| (0..=4000).map(|j| f64::from(j) / 4000.0).collect())
        .collect();
    let lowered: Vec<_> = cases
        .iter()
        .enumerate()
        .map(|(i, (_, c, _, _))| (i, c.lower()))
        .collect();
    // Every segment is rational (evaluated in homogeneous coordinates).
    assert!(
        lowered
            .iter()
            .all(|(_, s)| s.iter().all(|s| s.is_rational()))
    );
    common::on_each_gpu(
        "circles_stay_on_the_circle_within_the_f32_bound",
        |backend| {
            let got = evaluate(&backend.ctx, &backend.pipelines, &lowered, &params).expect("GPU");
            for ((name, curve, c, r), (ts, values)) in cases.iter().zip(params.iter().zip(&got)) {
                let b = bound(curve);
                assert_eq!(values.len(), ts.len(), "{}: {name}", backend.name);
                for (&t, p) in ts.iter().zip(values) {
                    let off = ((*p - *c).length() - r).abs();
                    assert!(
                        off <= b,
                        "{}: {name} at t = {t}: ||P − C| − R| = {off:e} > {b:e}",
                        backend.name
                    );
                }
            }
        },
    );
}

#[test]
fn gpu_derivatives_of_circles_are_tangent_and_give_the_curvature() {
    let cases: Vec<_> = circles()
        .into_iter()
        .filter(|(_, _, _, r)| *r == 1.0 || *r == 2.5)
        .collect();
    let params: Vec<Vec<f64>> = cases
        .iter()
        .map(|_| (1..200).map(|j| f64::from(j) / 200.0).collect())
        .collect();
    let lowered: Vec<_> = cases
        .iter()
        .enumerate()
        .map(|(i, (_, c, _, _))| (i, c.lower()))
        .collect();
    common::on_each_gpu(
        "gpu_derivatives_of_circles_are_tangent_and_give_the_curvature",
        |backend| {
            let (ctx, pipes) = (&backend.ctx, &backend.pipelines);
            let p = evaluate(ctx, pipes, &lowered, &params).expect("points");
            let d1 = evaluate_derivative(ctx, pipes, &lowered, &params, 1).expect("P′");
            let d2 = evaluate_derivative(ctx, pipes, &lowered, &params, 2).expect("P″");
            for (k, (name, curve, c, r)) in cases.iter().enumerate() {
                for (j, &t) in params[k].iter().enumerate() {
                    let (q, a, b) = (p[k][j], d1[k][j], d2[k][j]);
                    let (a_cpu, b_cpu) = (curve.eval_deriv(t), curve.eval_second_deriv(t));
                    // f32 values through the quotient rule: within 1e-4 of the derivatives'
                    // size.
                    assert!(
                        (a - a_cpu).length() <= 1e-4 * a_cpu.length(),
                        "{}: {name} at t = {t}: P′ {a} vs {a_cpu}",
                        backend.name
                    );
                    assert!(
                        (b - b_cpu).length() <= 1e-4 * b_cpu.length().max(a_cpu.length()),
                        "{}: {name} at t = {t}: P″ {b} vs {b_cpu}",
                        backend.name
                    );
                    // The circle's exact tangent (⟂ radius) and curvature 1/R.
                    assert!(
                        a.dot(q - *c).abs() <= 1e-4 * a.length() * r,
                        "{}: {name} at t = {t}: tangent not ⟂ radius",
                        backend.name
                    );
                    let kappa = a.cross(b).length() / a.length().powi(3);
                    assert!(
                        (kappa * r - 1.0).abs() <= 1e-3,
                        "{}: {name} at t = {t}: curvature {kappa} vs {}",
                        backend.name,
                        1.0 / r
                    );
                }
            }
        },
    );
}
