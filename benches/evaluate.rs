//! Evaluation benchmarks (criterion): `cargo bench --bench evaluate`. The f64 CPU path of
//! each family and the f32 twin of the GPU kernel.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use splinescope_core::geom::{BSpline, Bezier, Curve, Nubmp, ParamCurve};
use splinescope_core::rng::Rng;
use splinescope_gpu::chunks::ChunkLimits;
use splinescope_gpu::layout::GpuVertex;
use splinescope_gpu::pack::prepare;
use splinescope_gpu::twin;
use splinescope_scene::format::encoding::encode;
use splinescope_scene::format::generate::{StressOptions, random_bezier_scene};

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
    let prepared = prepare(&encode(&scene), ChunkLimits::for_binding_size(1 << 27)).unwrap();
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

/// The same 100,000 planar cubics × 64 uniform samples through kurbo, lyon_geom and
/// splinescope's batch evaluator (one thread, then every core), in one run: the ratios
/// are what BENCHMARKS.md records.
fn peers(c: &mut Criterion) {
    use splinescope_core::geom::batch::{
        CurveSampler, UniformCubicWeights, for_each_sampled, sample_many,
    };
    const CURVES: usize = 100_000;
    const SAMPLES: usize = 64;
    let scene = random_bezier_scene(StressOptions {
        curves: CURVES,
        degree: 3,
        samples: SAMPLES as u32,
        ..Default::default()
    });
    let cubics: Vec<[DVec3; 4]> = scene
        .curves
        .iter()
        .map(|c| {
            let p = c.curve.control_points();
            [p[0], p[1], p[2], p[3]]
        })
        .collect();
    let ts: Vec<f64> = (0..SAMPLES)
        .map(|j| j as f64 / (SAMPLES - 1) as f64)
        .collect();
    let mut g = c.benchmark_group("peers");
    g.sample_size(10);
    g.throughput(Throughput::Elements((CURVES * SAMPLES) as u64));
    g.bench_function("kurbo", |b| {
        let curves: Vec<kurbo::CubicBez> = cubics
            .iter()
            .map(|p| {
                let q = p.map(|v| kurbo::Point::new(v.x, v.y));
                kurbo::CubicBez::new(q[0], q[1], q[2], q[3])
            })
            .collect();
        let mut out = vec![kurbo::Point::ZERO; SAMPLES];
        b.iter(|| {
            use kurbo::ParamCurve as _;
            for c in &curves {
                for (o, &t) in out.iter_mut().zip(&ts) {
                    *o = c.eval(t);
                }
                black_box(&mut out);
            }
        });
    });
    g.bench_function("lyon_geom", |b| {
        let curves: Vec<lyon_geom::CubicBezierSegment<f64>> = cubics
            .iter()
            .map(|p| {
                let q = p.map(|v| lyon_geom::point(v.x, v.y));
                lyon_geom::CubicBezierSegment {
                    from: q[0],
                    ctrl1: q[1],
                    ctrl2: q[2],
                    to: q[3],
                }
            })
            .collect();
        let mut out = vec![lyon_geom::point(0.0, 0.0); SAMPLES];
        b.iter(|| {
            for c in &curves {
                for (o, &t) in out.iter_mut().zip(&ts) {
                    *o = c.sample(t);
                }
                black_box(&mut out);
            }
        });
    });
    let samplers: Vec<CurveSampler> = scene
        .curves
        .iter()
        .map(|c| CurveSampler::new(&c.curve))
        .collect();
    g.bench_function("splinescope", |b| {
        let mut out = vec![DVec3::ZERO; SAMPLES];
        let weights = UniformCubicWeights::new(SAMPLES);
        b.iter(|| {
            for c in &samplers {
                c.sample_uniform_with(&weights, &mut out);
                black_box(&mut out);
            }
        });
    });
    g.bench_function("splinescope_all_cores", |b| {
        b.iter(|| {
            for_each_sampled(&samplers, SAMPLES, |_, points| {
                black_box(points);
            });
        });
    });
    g.bench_function("splinescope_all_cores_stored", |b| {
        let mut out = vec![DVec3::ZERO; CURVES * SAMPLES];
        b.iter(|| {
            sample_many(&samplers, SAMPLES, &mut out);
            black_box(out[out.len() / 2])
        });
    });
    g.finish();
}

criterion_group!(benches, bench, peers);
criterion_main!(benches);
