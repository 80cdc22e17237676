//! Every curve family through the one GPU kernel: the lowered Bézier segments evaluated by
//! `shaders/tessellate.wgsl` agree with each family's exact `f64` evaluation within the
//! bound of `tests/gpu_tessellation.rs` (1e-6 · S · max(n, 12)/12, with S the larger of the
//! segments' control extent and largest coordinate, n their largest degree). Rational
//! curves are evaluated in homogeneous `f32` and divided: the bound of their weighted
//! points and weights, each relative, is amplified by at most `κ = max w / min w` per
//! segment in the division; their bound is that bound times `2κ`.

mod common;

use std::path::Path;

use glam::DVec3;
use splinescope_core::geom::{
    Aabb, BSpline, Bezier, CubicInterpolation, Curve, Lower, Modification, ModifiedBezier, Nubmp,
    Nurbs, ParamCurve, PathSegment, RationalBezier, Reading,
};
use splinescope_core::rng::Rng;
use splinescope_gpu::GpuContext;
use splinescope_gpu::eval::evaluate;
use splinescope_scene::format::Scene;

fn bound(curve: &Curve) -> f64 {
    let segs = curve.lower();
    let pts: Vec<DVec3> = segs
        .iter()
        .flat_map(|s| s.bezier.points().to_vec())
        .collect();
    let degree = segs.iter().map(|s| s.bezier.degree()).max().unwrap_or(0);
    let extent = Aabb::from_points(&pts).diagonal();
    let radius = pts.iter().map(|p| p.length()).fold(0.0, f64::max);
    let kappa = segs
        .iter()
        .filter_map(|s| s.weights.as_ref())
        .map(|w| {
            let hi = w.iter().copied().fold(0.0, f64::max);
            let lo = w.iter().copied().fold(f64::INFINITY, f64::min);
            2.0 * hi / lo
        })
        .fold(1.0, f64::max);
    1e-6 * extent.max(radius) * (degree.max(12) as f64 / 12.0) * kappa
}

/// Evaluates `curves` on the GPU at 301 parameters over each domain (ends and interior
/// breakpoints included) and compares with the CPU.
fn check(backend: &common::Backend, curves: &[(String, Curve)]) {
    let ctx: &GpuContext = &backend.ctx;
    let lowered: Vec<_> = curves
        .iter()
        .enumerate()
        .map(|(i, (_, c))| (i, c.lower()))
        .collect();
    let params: Vec<Vec<f64>> = curves
        .iter()
        .map(|(_, c)| {
            let (a, b) = c.domain();
            let mut ts: Vec<f64> = (0..=300)
                .map(|k| a + (b - a) * f64::from(k) / 300.0)
                .collect();
            ts.extend(c.lower().iter().map(|s| s.t0));
            ts
        })
        .collect();
    let gpu = evaluate(ctx, &backend.pipelines, &lowered, &params).expect("GPU evaluation");
    for ((name, curve), (ts, got)) in curves.iter().zip(params.iter().zip(&gpu)) {
        assert_eq!(
            ts.len(),
            got.len(),
            "{}: {name}: every parameter evaluated",
            backend.name
        );
        let bound = bound(curve);
        for (&t, g) in ts.iter().zip(got) {
            let err = (*g - curve.eval(t)).length();
            assert!(
                err <= bound,
                "{}: {name} ({}) at t={t}: |GPU − CPU| = {err:e} > {bound:e}",
                backend.name,
                curve.family()
            );
        }
    }
}

#[test]
fn every_scene_curve_matches_on_the_gpu() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut curves = Vec::new();
    for entry in std::fs::read_dir(&dir).expect("scenes") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "json") {
            let scene = Scene::load(&path).expect("valid scene");
            for (i, c) in scene.curves.into_iter().enumerate() {
                curves.push((format!("{}: curves[{i}]", path.display()), c.curve));
            }
        }
    }
    let families: std::collections::BTreeSet<&str> =
        curves.iter().map(|(_, c)| c.family()).collect();
    assert_eq!(
        families.len(),
        Curve::FAMILY_NAMES.len(),
        "the scenes cover every family: {families:?}"
    );
    common::on_each_gpu("every_scene_curve_matches_on_the_gpu", |backend| {
        check(backend, &curves);
    });
}

fn random_points(rng: &mut Rng, n: usize, three_d: bool) -> Vec<DVec3> {
    (0..n)
        .map(|_| {
            DVec3::new(
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
                if three_d { rng.range(-3.0, 3.0) } else { 0.0 },
            )
        })
        .collect()
}

fn random_knots(rng: &mut Rng, order: usize, n: usize) -> Vec<f64> {
    let interior = n - order;
    let mut t = 0.0;
    let mut knots = vec![0.0; order];
    for _ in 0..interior {
        t += rng.range(0.05, 1.0);
        knots.push(t);
    }
    knots.extend(std::iter::repeat_n(t + rng.range(0.05, 1.0), order));
    knots
}

#[test]
fn random_curves_of_every_family_match_up_to_the_maximum_degree() {
    let mut rng = Rng::new(77);
    let mut curves = Vec::new();
    for three_d in [false, true] {
        for n in [1usize, 2, 3, 5, 9, 20, 31] {
            let pts = random_points(&mut rng, n + 1, three_d);
            let v = random_points(&mut rng, 1, three_d)[0];
            let t_star = rng.range(0.05, 0.95);
            curves.push((
                format!("modified degree {n}"),
                Curve::ModifiedBezier(
                    ModifiedBezier::try_new(Bezier::new(pts), t_star, v).expect("valid"),
                ),
            ));
        }
        for reading in [None, Some(Reading::Paper), Some(Reading::BumpAdded)] {
            let pts = random_points(&mut rng, 9, three_d);
            let mut t = 0.0;
            let params: Vec<f64> = (0..9)
                .map(|_| {
                    t += rng.range(0.1, 2.0);
                    t
                })
                .collect();
            let modification = reading.map(|reading| Modification {
                t_star: rng.range(0.1, 0.9),
                v: random_points(&mut rng, 1, three_d)[0],
                reading,
            });
            curves.push((
                format!("interpolation {reading:?}"),
                Curve::Interpolation(
                    CubicInterpolation::try_new(pts, Some(params), modification).expect("valid"),
                ),
            ));
        }
        // B-splines of orders 2..=32 (degree ≤ 31 after lowering), NUBMP of orders 2..=31
        // (the dual spline has degree = order).
        for order in [2usize, 3, 4, 5, 8, 16, 32] {
            let n = order + rng.int(0, 6);
            let knots = random_knots(&mut rng, order, n);
            let pts = random_points(&mut rng, n, three_d);
            curves.push((
                format!("bspline order {order}"),
                Curve::BSpline(BSpline::try_new(pts, knots, order).expect("valid")),
            ));
        }
        for order in [2usize, 3, 4, 5, 7, 12, 31] {
            let n = order + rng.int(0, 5);
            let knots = random_knots(&mut rng, order, n);
            let pts = random_points(&mut rng, n, three_d);
            let mut nub = Nubmp::try_new(pts, knots, order).expect("valid");
            for j in 0..nub.groups().len() {
                let size = nub.groups()[j].members.len();
                let raw: Vec<f64> = (0..size).map(|_| rng.range(0.05, 1.0)).collect();
                let sum: f64 = raw.iter().sum();
                nub.set_group(j, &raw.iter().map(|r| r / sum).collect::<Vec<_>>())
                    .expect("valid parameters");
            }
            curves.push((format!("nubmp order {order}"), Curve::Nubmp(nub)));
        }
    }
    // Rational Bézier curves up to the GPU maximum and NURBS curves, weights in [1/8, 8].
    for three_d in [false, true] {
        for n in [1usize, 2, 3, 4, 7, 15, 31] {
            let pts = random_points(&mut rng, n + 1, three_d);
            let w: Vec<f64> = (0..=n).map(|_| 2f64.powf(rng.range(-3.0, 3.0))).collect();
            curves.push((
                format!("rational Bézier degree {n}"),
                Curve::RationalBezier(RationalBezier::try_new(pts, w).expect("valid")),
            ));
        }
        for order in [2usize, 3, 4, 6, 12] {
            let n = order + rng.int(0, 6);
            let knots = random_knots(&mut rng, order, n);
            let pts = random_points(&mut rng, n, three_d);
            let w: Vec<f64> = (0..n).map(|_| 2f64.powf(rng.range(-3.0, 3.0))).collect();
            curves.push((
                format!("nurbs order {order}"),
                Curve::Nurbs(Nurbs::try_new(pts, w, knots, order).expect("valid")),
            ));
        }
    }
    // Paths of segments of mixed degrees (up to the maximum), polynomial and rational,
    // open and closed.
    for three_d in [false, true] {
        for (degrees, closed) in [
            (vec![1usize, 2, 3, 5], false),
            (vec![3, 3, 1], true),
            (vec![2, 31, 1, 7], false),
        ] {
            let mut segments: Vec<PathSegment> = Vec::new();
            let first = random_points(&mut rng, 1, three_d)[0];
            let mut start = first;
            for (k, &n) in degrees.iter().enumerate() {
                let mut pts = vec![start];
                pts.extend(random_points(&mut rng, n, three_d));
                if closed && k + 1 == degrees.len() {
                    *pts.last_mut().expect("points") = first;
                }
                start = *pts.last().expect("points");
                let weights = (k % 2 == 1)
                    .then(|| (0..=n).map(|_| 2f64.powf(rng.range(-2.0, 2.0))).collect());
                segments.push(PathSegment {
                    points: pts.into(),
                    weights,
                });
            }
            curves.push((
                format!("path of degrees {degrees:?}, closed {closed}"),
                Curve::Path(
                    splinescope_core::geom::Path::try_new(segments, closed).expect("valid"),
                ),
            ));
        }
    }
    common::on_each_gpu(
        "random_curves_of_every_family_match_up_to_the_maximum_degree",
        |backend| check(backend, &curves),
    );
}
