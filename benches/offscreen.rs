//! Offscreen frames (criterion): `cargo bench --bench offscreen`. One `render_uploaded`
//! call — the adaptive tessellation, the render pass and the image read back — for the
//! 10,000-curve stress scene at 1280×800, drawn as the viewer draws it (sample counts
//! chosen for the 0.25 px tolerance) and with the generator's fixed 64 samples per curve.
//! Compare with the window's frame time of the same scene and adapter:
//! `xvfb-run -a -s "-screen 0 1280x800x24" splinescope view --stress 10000 --frames 120 --stats`.
#![allow(missing_docs)]

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use glam::DVec2;
use splinescope_gpu::capture::{OFFSCREEN_FORMAT, render_uploaded};
use splinescope_gpu::chunks::ChunkLimits;
use splinescope_gpu::pack::prepare;
use splinescope_gpu::renderer::Renderer;
use splinescope_gpu::{BackendChoice, ContextOptions, GpuContext};
use splinescope_scene::format::encoding::encode;
use splinescope_scene::format::generate::{StressOptions, random_bezier_scene};

fn bench(c: &mut Criterion) {
    let (ctx, pipelines) = GpuContext::new(&ContextOptions::from_env(BackendChoice::Auto))
        .unwrap_or_else(|e| panic!("the offscreen benchmark needs a GPU adapter: {e}"));
    let (width, height) = (1280, 800);
    let mut g = c.benchmark_group(format!("offscreen frame 1280x800 ({})", ctx.describe()));
    g.sample_size(10);
    for (name, adaptive) in [
        ("10000 cubics, adaptive", true),
        ("10000 cubics, 64 fixed", false),
    ] {
        let mut scene = random_bezier_scene(StressOptions::default());
        if adaptive {
            // As `view --stress` draws it.
            scene.samples_per_segment = None;
        }
        let prepared = prepare(
            &encode(&scene),
            ChunkLimits::for_binding_size(ctx.max_binding_bytes()),
        )
        .expect("the stress scene packs");
        let renderer = Renderer::new(&ctx.device, &pipelines, OFFSCREEN_FORMAT);
        let mut gpu_scene = renderer.upload(&ctx, &prepared);
        let camera = scene.camera(DVec2::new(f64::from(width), f64::from(height)));
        g.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| {
                render_uploaded(
                    &ctx,
                    &renderer,
                    &mut gpu_scene,
                    &camera,
                    (width, height),
                    0.25,
                )
                .expect("offscreen frame")
            });
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
