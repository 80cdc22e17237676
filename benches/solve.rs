//! Solver benchmarks (criterion): `cargo bench --bench solve`.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec3;
use splinescope_core::geom::Bezier;
use splinescope_core::rng::Rng;
use splinescope_core::solve::batch::{BatchResult, BatchSingleTarget};
use splinescope_core::solve::nearest;
use splinescope_core::solve::shape::{
    SingleTargetOptions, multi_target, single_target, tangent_kept,
};

fn curve(rng: &mut Rng, n: usize) -> Bezier {
    Bezier::new(
        (0..=n)
            .map(|_| DVec3::new(rng.range(-5., 5.), rng.range(-5., 5.), 0.0))
            .collect(),
    )
}

fn bench(c: &mut Criterion) {
    let mut rng = Rng::new(1);
    let mut g = c.benchmark_group("single_target");
    for n in [3usize, 7, 15] {
        let b = curve(&mut rng, n);
        let target = b.eval(0.4) + DVec3::new(0.3, 0.2, 0.0);
        let given = SingleTargetOptions {
            t_s: Some(0.4),
            ..Default::default()
        };
        g.bench_with_input(BenchmarkId::new("t_s given", n), &n, |bch, _| {
            bch.iter(|| single_target(black_box(&b), black_box(target), &given).unwrap());
        });
        g.bench_with_input(BenchmarkId::new("t_s projected", n), &n, |bch, _| {
            bch.iter(|| {
                single_target(
                    black_box(&b),
                    black_box(target),
                    &SingleTargetOptions::default(),
                )
            })
        });
    }
    g.finish();

    let b7 = curve(&mut rng, 7);
    let target = b7.eval(0.4) + DVec3::new(0.3, 0.2, 0.0);
    c.bench_function("tangent_kept degree 7", |bch| {
        bch.iter(|| tangent_kept(black_box(&b7), black_box(target), Some(0.4), None).unwrap());
    });

    let b20 = curve(&mut rng, 20);
    let params: Vec<f64> = (0..10).map(|k| (f64::from(k) + 0.5) / 10.0).collect();
    let targets: Vec<DVec3> = params
        .iter()
        .map(|&t| b20.eval(t) + DVec3::new(0.1, -0.1, 0.0))
        .collect();
    c.bench_function("multi_target 10 targets degree 20 (params given)", |bch| {
        bch.iter(|| {
            multi_target(black_box(&b20), black_box(&targets), Some(&params), None).unwrap()
        });
    });
    c.bench_function("multi_target 10 targets degree 20 (projected)", |bch| {
        bch.iter(|| multi_target(black_box(&b20), black_box(&targets), None, None));
    });

    let mut g = c.benchmark_group("nearest");
    for n in [3usize, 7] {
        let b = curve(&mut rng, n);
        let q = DVec3::new(0.5, 0.5, 0.0);
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |bch, _| {
            bch.iter(|| nearest(black_box(&b), black_box(q), None))
        });
    }
    g.finish();

    let mut g = c.benchmark_group("batch 10000 curves");
    g.sample_size(30);
    for n in [3usize, 7] {
        let curves = 10_000;
        let points: Vec<DVec3> = (0..curves * (n + 1))
            .map(|_| DVec3::new(rng.range(-1., 1.), rng.range(-1., 1.), 0.0))
            .collect();
        let targets: Vec<DVec3> = (0..curves)
            .map(|_| DVec3::new(rng.range(-1., 1.), rng.range(-1., 1.), 0.0))
            .collect();
        let ts: Vec<f64> = (0..curves).map(|_| rng.range(0.1, 0.9)).collect();
        let batch = BatchSingleTarget::new(n).unwrap();
        let mut out = vec![DVec3::ZERO; points.len()];
        let mut results = vec![BatchResult::default(); curves];
        g.bench_with_input(BenchmarkId::new("t_s given", n), &n, |bch, _| {
            bch.iter(|| batch.solve(&points, &targets, Some(&ts), &mut out, &mut results));
        });
        g.bench_with_input(BenchmarkId::new("t_s projected", n), &n, |bch, _| {
            bch.iter(|| batch.solve(&points, &targets, None, &mut out, &mut results));
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
