//! Evaluation benchmarks (criterion): `cargo bench --bench evaluate`. The f64 CPU path of
//! each family and the f32 twin of the GPU kernel.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use splinescope::geom::{BSpline, Bezier, Curve, Nubmp, ParamCurve};
use splinescope::gpu::layout::GpuVertex;
use splinescope::gpu::pack::{ChunkLimits, prepare_scene};
use splinescope::gpu::twin;
use splinescope::scene::generate::{Rng, StressOptions, random_bezier_scene};

fn bench(c: &mut Criterion) {
    let mut rng = Rng::new(2);
    let pts: Vec<DVec3> = (0..8)
        .map(|_| DVec3::new(rng.range(-5., 5.), rng.range(-5., 5.), 0.0))
        .collect();
    let knots = vec![0., 0., 0., 0., 0.2, 0.35, 0.5, 0.7, 1., 1., 1., 1.];
    let curves = [
        Curve::Bezier(Bezier::new(pts[..4].to_vec())),
        Curve::Bezier(Bezier::new(pts.clone())),
        Curve::BSpline(BSpline::try_new(pts.clone(), knots.clone(), 4).unwrap()),
        Curve::Nubmp(Nubmp::try_new(pts.clone(), knots, 4).unwrap()),
    ];
    let mut g = c.benchmark_group("eval 1000 params (f64)");
    g.throughput(Throughput::Elements(1000));
    for (name, curve) in ["bezier3", "bezier7", "bspline4", "nubmp4"]
        .iter()
        .zip(&curves)
    {
        let (a, b) = curve.domain();
        g.bench_with_input(BenchmarkId::from_parameter(name), curve, |bch, c| {
            bch.iter(|| {
                let mut s = DVec3::ZERO;
                for k in 0..1000 {
                    s += c.eval(a + (b - a) * f64::from(k) / 999.0);
                }
                black_box(s)
            });
        });
    }
    g.finish();

    let scene = random_bezier_scene(StressOptions {
        curves: 1000,
        degree: 3,
        samples: 64,
        ..Default::default()
    });
    let prepared = prepare_scene(&scene, ChunkLimits::for_binding_size(1 << 27)).unwrap();
    let chunk = &prepared.chunks[0];
    let mut out = vec![
        GpuVertex {
            position: [0.0; 3],
            id: 0
        };
        chunk.sample_count as usize
    ];
    let mut g = c.benchmark_group("kernel twin (f32)");
    g.throughput(Throughput::Elements(u64::from(chunk.sample_count)));
    g.bench_function("1000 cubics x 64 samples", |bch| {
        bch.iter(|| twin::tessellate(&chunk.points, &chunk.records, black_box(&mut out)));
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
