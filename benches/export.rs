//! Figures of the 10,000-curve stress scene (`view --stress`'s): building the figure and
//! writing it as SVG and as PDF, cubics (exact commands) and degree 8 (pieces within the
//! tolerance), planar and 3D (perspective). The bound: under a second each.
#![allow(missing_docs)]

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};

use splinescope_figure::{FigureOptions, build, pdf, svg};
use splinescope_scene::format::generate::{StressOptions, random_bezier_scene};

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("export 10000 curves at 1280x800");
    g.sample_size(10);
    for (name, degree, three_d) in [
        ("cubic 2D", 3, false),
        ("degree 8 2D", 8, false),
        ("cubic 3D", 3, true),
    ] {
        let scene = random_bezier_scene(StressOptions {
            degree,
            three_d,
            ..StressOptions::default()
        });
        let opts = FigureOptions::new(1280, 800);
        g.bench_function(BenchmarkId::new("svg", name), |b| {
            b.iter(|| svg::write(&build(&scene, &opts).expect("figure")).len());
        });
        g.bench_function(BenchmarkId::new("pdf", name), |b| {
            b.iter(|| pdf::write(&build(&scene, &opts).expect("figure")).len());
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
