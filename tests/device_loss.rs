//! Device failure is forced on purpose: a destroyed device and an uncaptured validation
//! error. Offscreen rendering and GPU evaluation must return a clear error — never panic,
//! hang, or hand back pixels or samples computed after the failure.

mod common;

use std::time::{Duration, Instant};

use common::render_scene;
use splinescope_core::geom::Lower;
use splinescope_gpu::{BackendChoice, ContextOptions, GpuContext, GpuError, Pipelines};
use splinescope_scene::format::gallery;

fn fresh(backend: &common::Backend) -> (GpuContext, Pipelines) {
    let choice: BackendChoice = backend.name.parse().expect("backend name");
    GpuContext::new(&ContextOptions::from_env(choice)).expect("a second device")
}

fn assert_failed_cleanly<T: std::fmt::Debug>(what: &str, r: Result<T, GpuError>, took: Duration) {
    match r {
        Err(GpuError::DeviceLost(m)) => assert!(!m.is_empty(), "{what}"),
        Err(GpuError::Readback(m)) => assert!(!m.is_empty(), "{what}"),
        other => panic!("{what}: expected a device error, got {other:?}"),
    }
    assert!(took < Duration::from_secs(60), "{what} took {took:?}");
}

#[test]
fn a_destroyed_device_gives_an_error_not_a_panic_or_a_hang() {
    common::on_each_gpu("destroyed device", |backend| {
        let (ctx, pipelines) = fresh(backend);
        assert!(ctx.check_health().is_ok());
        ctx.device.destroy();
        let scene = gallery::gallery();
        let start = Instant::now();
        let r = render_scene(&ctx, &pipelines, &scene, None, 64, 48);
        assert_failed_cleanly(&format!("{}: render", backend.name), r, start.elapsed());
        let lowered = vec![(0, scene.curves[0].curve.lower())];
        let start = Instant::now();
        let r = splinescope_gpu::eval::evaluate(&ctx, &pipelines, &lowered, &[vec![0.0, 0.5, 1.0]]);
        assert_failed_cleanly(&format!("{}: eval", backend.name), r, start.elapsed());
        let e = ctx.check_health().expect_err("the loss is recorded");
        assert!(e.to_string().contains("the GPU device failed"), "{e}");
    });
}

#[test]
fn an_uncaptured_validation_error_is_recorded_and_stops_the_work() {
    common::on_each_gpu("uncaptured validation error", |backend| {
        let (ctx, pipelines) = fresh(backend);
        // MAP_READ may only be combined with COPY_DST: an invalid buffer, outside any
        // error scope (wgpu's default handler would panic here).
        let _bad = ctx.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("invalid on purpose"),
            size: 16,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });
        let _ = ctx.device.poll(wgpu::PollType::wait_indefinitely());
        let e = ctx.check_health().expect_err("the error is recorded");
        assert!(matches!(e, GpuError::DeviceLost(_)), "{e:?}");
        let start = Instant::now();
        let r = render_scene(&ctx, &pipelines, &gallery::gallery(), None, 64, 48);
        assert_failed_cleanly(&format!("{}: render", backend.name), r, start.elapsed());
    });
}
