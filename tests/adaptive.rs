//! Adaptive tessellation on the GPU against its CPU twins and against the exact curves:
//! the count pass equals the twin's Wang count, the prefix sum and placement equal the
//! twin's exactly, every sample equals the twin's de Casteljau within its own bound, and —
//! the point of it all — every drawn polyline lies within the tolerance, in pixels, of the
//! exact `f64` curve, for every family and random curves up to degree 31, in 2D and 3D, at
//! several zooms. Segments wholly off screen get no samples and really are off screen; a
//! buffer too small for the counts coarsens every curve in proportion without writing
//! outside it. On every backend.

mod common;

use glam::{DMat4, DVec2, DVec3, DVec4};
use splinescope_core::geom::{Bezier, BezierSegment, Curve, Lower};
use splinescope_core::rng::Rng;
use splinescope_encoding::camera::Camera;
use splinescope_gpu::adaptive::{FrameSettings, Stage, read_work};
use splinescope_gpu::layout::{GpuVertex, MAX_SAMPLES_PER_SEGMENT, WORK_HEADER};
use splinescope_gpu::pack::PreparedScene;
use splinescope_gpu::renderer::camera_uniform;
use splinescope_gpu::tessellator::read_buffer;
use splinescope_gpu::twin;
use splinescope_scene::format::{Scene, SceneCurve, Style};

const VIEWPORT: DVec2 = DVec2::new(640.0, 480.0);

fn random_scene(seed: u64, three_d: bool) -> Scene {
    let mut rng = Rng::new(seed);
    let mut scene = splinescope_scene::format::gallery::gallery();
    scene.curves.clear();
    scene.annotations.clear();
    scene.samples_per_segment = None;
    for degree in 1..=31 {
        let origin = DVec3::new(rng.range(-4.0, 4.0), rng.range(-3.0, 3.0), 0.0);
        let points = (0..=degree)
            .map(|_| {
                origin
                    + DVec3::new(
                        rng.range(-1.0, 1.0),
                        rng.range(-1.0, 1.0),
                        if three_d { rng.range(-1.0, 1.0) } else { 0.0 },
                    )
            })
            .collect();
        scene.curves.push(SceneCurve {
            name: None,
            curve: Curve::Bezier(Bezier::new(points)),
            style: Style::default_for(degree),
        });
    }
    scene
}

/// What one chunk's passes produced on the GPU.
struct Run {
    counts: Vec<u32>,
    offsets: Vec<u32>,
    finals: Vec<u32>,
    stats: splinescope_gpu::layout::FrameStats,
    samples: Vec<GpuVertex>,
    requested: Vec<u32>,
    /// The frame uniform the passes read.
    frame: splinescope_gpu::layout::GpuFrame,
}

fn run_chunk(
    backend: &common::Backend,
    chunk: &splinescope_gpu::chunks::TessChunk,
    settings: &FrameSettings,
    capacity: u32,
) -> Run {
    let ctx = &backend.ctx;
    let adaptive = &backend.pipelines.adaptive;
    let a = adaptive.upload(&ctx.device, chunk, capacity, wgpu::BufferUsages::COPY_SRC);
    adaptive.prepare(&ctx.queue, [&a], settings);
    let s = chunk.segments.len();
    let pass = |stage: Stage| {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        adaptive.encode_until(&mut encoder, [&a], None, stage);
        ctx.queue.submit([encoder.finish()]);
        read_work(&ctx.device, &ctx.queue, &a).expect("read work")
    };
    let requested = pass(Stage::Count)[WORK_HEADER..WORK_HEADER + s].to_vec();
    let work = pass(Stage::Tessellate);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    let samples: Vec<GpuVertex> =
        read_buffer(&ctx.device, &ctx.queue, &mut encoder, &a.samples).expect("read samples");
    ctx.check_health().expect("healthy device");
    let scan = WORK_HEADER + s;
    Run {
        counts: requested.clone(),
        finals: work[WORK_HEADER..WORK_HEADER + s].to_vec(),
        offsets: (0..s).map(|i| work[scan + 2 * i]).collect(),
        stats: *bytemuck::from_bytes(bytemuck::cast_slice(&work[..WORK_HEADER])),
        samples,
        requested,
        frame: a.frame_uniform(settings),
    }
}

/// The pixel of a world point, or `None` at or behind the eye.
fn pixel(clip_from_world: &DMat4, p: DVec3) -> Option<DVec2> {
    let c: DVec4 = *clip_from_world * p.extend(1.0);
    if c.w <= 1e-9 {
        return None;
    }
    let ndc = DVec2::new(c.x, c.y) / c.w;
    Some(DVec2::new(
        (ndc.x * 0.5 + 0.5) * VIEWPORT.x,
        (0.5 - ndc.y * 0.5) * VIEWPORT.y,
    ))
}

fn distance_to_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let d = b - a;
    let t = if d.length_squared() > 0.0 {
        ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + t * d - p).length()
}

/// The exact lowered segment behind each adaptive segment of chunk `c` (by its first
/// control point).
fn exact_segments(scene: &Scene, prepared: &PreparedScene, c: usize) -> Vec<(u32, BezierSegment)> {
    let mut out = Vec::new();
    for (curve, places) in prepared.placements.iter().enumerate() {
        let lowered = scene.curves[curve].curve.lower();
        for p in places.iter().filter(|p| p.chunk == c) {
            out.push((p.first_point, lowered[p.segment].clone()));
        }
    }
    out
}

/// Checks one scene under one camera: GPU against twins, and the tolerance.
fn check(backend: &common::Backend, scene: &Scene, camera: &Camera, tolerance_px: f64, what: &str) {
    let ctx = &backend.ctx;
    let prepared = common::pack(ctx, scene);
    let gpu_camera = camera_uniform(camera, VIEWPORT, 1.0);
    let settings = FrameSettings {
        camera: gpu_camera,
        tolerance_px: tolerance_px as f32,
        min_count: 0,
    };
    let clip = camera.clip_from_world(VIEWPORT);
    let mut checked_pieces = 0usize;
    for (ci, chunk) in prepared.chunks.iter().enumerate() {
        if chunk.segments.is_empty() {
            continue;
        }
        let capacity = chunk.segments.len() as u32 * MAX_SAMPLES_PER_SEGMENT;
        let run = run_chunk(backend, chunk, &settings, capacity);
        let frame = run.frame;
        // Count: the twin's Wang count, up to the rounding of a value on an integer.
        for (s, seg) in chunk.segments.iter().enumerate() {
            let want = twin::wang_count(&frame, &chunk.points, seg);
            let got = run.requested[s];
            assert!(
                got == want || got.abs_diff(want) == 1,
                "{what}: segment {s} (degree {}): GPU count {got}, twin {want}",
                seg.degree
            );
        }
        // Scan and placement: exactly the twin's, from the GPU's counts.
        let (offsets, finals, stats) = twin::scan_and_place(&run.counts, capacity);
        assert_eq!(run.offsets, offsets, "{what}: offsets");
        assert_eq!(run.finals, finals, "{what}: final counts");
        assert_eq!(run.stats, stats, "{what}: statistics");
        assert_eq!(stats.capped, 0, "{what}: the buffer was large enough");
        // Samples: the twin's de Casteljau within its own bound.
        assert_samples_match_twin(what, chunk, &offsets, &finals, &run.samples);
        // The tolerance, against the exact curve.
        let exact = exact_segments(scene, &prepared, ci);
        for (s, seg) in chunk.segments.iter().enumerate() {
            let Some((_, bez)) = exact.iter().find(|(fp, _)| *fp == seg.first_point) else {
                panic!("{what}: segment {s} has no exact twin");
            };
            let count = finals[s] as usize;
            let first = offsets[s] as usize;
            if count == 0 {
                // Culled: the curve really is off screen.
                for k in 0..=200 {
                    if let Some(px) = pixel(&clip, bez.eval(f64::from(k) / 200.0)) {
                        let inside =
                            px.x >= 0.0 && px.x <= VIEWPORT.x && px.y >= 0.0 && px.y <= VIEWPORT.y;
                        assert!(!inside, "{what}: culled segment {s} is on screen at {px}");
                    }
                }
                continue;
            }
            if count >= MAX_SAMPLES_PER_SEGMENT as usize {
                continue; // at or behind the eye, or capped by the per-segment maximum
            }
            for j in 0..count - 1 {
                let a = run.samples[first + j].position;
                let b = run.samples[first + j + 1].position;
                let to =
                    |p: [f32; 3]| DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
                let (Some(pa), Some(pb)) = (pixel(&clip, to(a)), pixel(&clip, to(b))) else {
                    continue;
                };
                let (t0, t1) = (
                    j as f64 / (count - 1) as f64,
                    (j + 1) as f64 / (count - 1) as f64,
                );
                for k in 0..=8 {
                    let t = t0 + (t1 - t0) * f64::from(k) / 8.0;
                    let Some(q) = pixel(&clip, bez.eval(t)) else {
                        continue;
                    };
                    let d = distance_to_segment(q, pa, pb);
                    // f32 samples and control points: a hundredth of a pixel of slack.
                    assert!(
                        d <= tolerance_px + 0.01,
                        "{what}: segment {s} (degree {}), piece {j} of {}: the curve is {d:.4} px from the polyline (tolerance {tolerance_px})",
                        seg.degree,
                        count - 1
                    );
                    checked_pieces += 1;
                }
            }
        }
    }
    assert!(checked_pieces > 0, "{what}: nothing was drawn");
}

/// Every sample the placement gives a segment equals the twin's de Casteljau within the
/// twin's own bound, `8 · n · ε · S` (`ε = 2⁻²⁴`, `S` the larger of the control polygon's
/// extent and radius: fused multiply-adds and the division's 2.5 ulp, as in
/// `tests/gpu_tessellation.rs`), and carries its curve's tag.
fn assert_samples_match_twin(
    what: &str,
    chunk: &splinescope_gpu::chunks::TessChunk,
    offsets: &[u32],
    finals: &[u32],
    samples: &[GpuVertex],
) {
    let mut expected = vec![twin_poison(); samples.len()];
    twin::tessellate_adaptive(
        &chunk.points,
        &chunk.segments,
        offsets,
        finals,
        &mut expected,
    );
    for (s, seg) in chunk.segments.iter().enumerate() {
        let points: Vec<DVec3> = (0..=seg.degree)
            .map(|i| {
                glam::Vec3::from(chunk.points[(seg.first_point + i) as usize].position).as_dvec3()
            })
            .collect();
        let extent = splinescope_core::geom::Aabb::from_points(&points).diagonal();
        let radius = points.iter().map(|p| p.length()).fold(0.0, f64::max);
        let bound =
            8.0 * f64::from(seg.degree.max(1)) * f64::from(f32::EPSILON) / 2.0 * extent.max(radius);
        let first = offsets[s] as usize;
        for j in first..first + finals[s] as usize {
            let (g, w) = (samples[j], expected[j]);
            assert_eq!(g.id, w.id, "{what}: sample {j} tag");
            let d = (glam::Vec3::from(g.position) - glam::Vec3::from(w.position))
                .as_dvec3()
                .length();
            assert!(
                d <= bound,
                "{what}: segment {s} sample {j} is {d:e} from its twin (bound {bound:e})"
            );
        }
    }
}

fn twin_poison() -> GpuVertex {
    GpuVertex {
        position: [f32::NAN; 3],
        id: u32::MAX,
    }
}

/// The camera zoomed by `factor` about a point of the scene's middle curve (so that close
/// views still show curves).
fn zoomed(camera: &Camera, factor: f64, scene: &Scene) -> Camera {
    use splinescope_core::geom::ParamCurve;
    let curve = &scene.curves[scene.curves.len() / 2].curve;
    let (a, b) = curve.domain();
    let at = camera
        .pixel_from_world(curve.eval(a + 0.37 * (b - a)), VIEWPORT)
        .unwrap_or(0.5 * VIEWPORT);
    let mut c = *camera;
    c.zoom_at(factor, at, VIEWPORT);
    c
}

#[test]
fn gpu_counts_scan_and_samples_match_the_twins_and_stay_within_the_tolerance() {
    common::on_each_gpu(
        "gpu_counts_scan_and_samples_match_the_twins_and_stay_within_the_tolerance",
        |backend| {
            let gallery = splinescope_scene::format::gallery::gallery();
            let scenes = [
                ("gallery", gallery),
                ("random 2D", random_scene(11, false)),
                ("random 3D", random_scene(12, true)),
            ];
            for (name, scene) in &scenes {
                let base = scene.camera(VIEWPORT);
                for factor in [0.4, 1.0, 3.0, 20.0] {
                    for tolerance in [0.25, 1.0] {
                        check(
                            backend,
                            scene,
                            &zoomed(&base, factor, scene),
                            tolerance,
                            &format!(
                                "{} {name}, zoom {factor}, tolerance {tolerance}",
                                backend.name
                            ),
                        );
                    }
                }
            }
        },
    );
}

#[test]
fn a_full_buffer_coarsens_every_curve_in_proportion_and_writes_nothing_outside() {
    common::on_each_gpu(
        "a_full_buffer_coarsens_every_curve_in_proportion_and_writes_nothing_outside",
        |backend| {
            let ctx = &backend.ctx;
            let scene = random_scene(13, false);
            let prepared = common::pack(ctx, &scene);
            let camera = zoomed(&scene.camera(VIEWPORT), 3.0, &scene);
            let settings = FrameSettings {
                camera: camera_uniform(&camera, VIEWPORT, 1.0),
                tolerance_px: 0.1,
                min_count: 0,
            };
            let chunk = &prepared.chunks[0];
            let s = chunk.segments.len() as u32;
            let roomy = run_chunk(backend, chunk, &settings, s * MAX_SAMPLES_PER_SEGMENT);
            let capacity = 2 * s + roomy.stats.requested / 3;
            let run = run_chunk(backend, chunk, &settings, capacity);
            let what = format!(
                "{}: capacity {capacity} for {} requested",
                backend.name, roomy.stats.requested
            );
            assert_eq!(run.stats.capped, 1, "{what}");
            assert_eq!(run.stats.requested, roomy.stats.requested, "{what}");
            assert!(
                run.stats.drawn <= capacity,
                "{what}: drew {}",
                run.stats.drawn
            );
            assert!(
                run.stats.drawn + 2 * s >= capacity - s,
                "{what}: the buffer is used"
            );
            let mut end = 0;
            for (i, (&o, &c)) in run.offsets.iter().zip(&run.finals).enumerate() {
                assert_eq!(o, end, "{what}: segment {i} starts where the last ended");
                end = o + c;
                if run.counts[i] > 0 && i + 1 < run.offsets.len() {
                    assert!(c >= 2, "{what}: a drawn segment keeps 2 samples, got {c}");
                    assert!(c <= run.counts[i], "{what}: capping never adds samples");
                }
            }
            assert!(end <= capacity, "{what}");
            // The twin's placement, within one sample (the GPU may divide within 2.5 ulp).
            let (offsets, _, stats) = twin::scan_and_place(&run.counts, capacity);
            for (g, w) in run.offsets.iter().zip(&offsets) {
                assert!(g.abs_diff(*w) <= 1, "{what}: offset {g} vs twin {w}");
            }
            assert!(run.stats.drawn.abs_diff(stats.drawn) <= 1, "{what}");
            // Every drawn sample lies on its curve: coarser, never garbage.
            assert_samples_match_twin(&what, chunk, &run.offsets, &run.finals, &run.samples);
        },
    );
}

#[test]
fn an_offscreen_render_grows_a_buffer_the_view_outgrew_and_draws_uncapped() {
    use splinescope_gpu::adaptive::{DEFAULT_TOLERANCE_PX, read_stats};
    use splinescope_gpu::capture::{OFFSCREEN_FORMAT, render_uploaded};
    use splinescope_gpu::renderer::Renderer;
    common::on_each_gpu(
        "an_offscreen_render_grows_a_buffer_the_view_outgrew_and_draws_uncapped",
        |backend| {
            let ctx = &backend.ctx;
            let scene = random_scene(14, false);
            let prepared = common::pack(ctx, &scene);
            let renderer = Renderer::new(&ctx.device, &backend.pipelines, OFFSCREEN_FORMAT);
            let mut gpu = renderer.upload(ctx, &prepared);
            let before = gpu.capacity();
            // A large image at the finest tolerance: far more samples than the object-space
            // estimate the buffers started with.
            let big = DVec2::new(4096.0, 3072.0);
            render_uploaded(
                ctx,
                &renderer,
                &mut gpu,
                &scene.camera(big),
                (4096, 3072),
                0.01,
            )
            .expect("render");
            let stats =
                read_stats(&ctx.device, &ctx.queue, &gpu.chunks[0].adaptive).expect("stats");
            let what = format!("{}: capacity {before} → {}", backend.name, gpu.capacity());
            assert!(gpu.capacity() > before, "{what}: the buffer grew");
            assert_eq!(stats.capped, 0, "{what}: the final frame was not capped");
            assert_eq!(stats.drawn, stats.requested, "{what}");
            // Back to the default tolerance and view: the excess is given back (never below
            // what the buffers started with), and the same view again reallocates nothing.
            let grown = gpu.capacity();
            let small = |gpu: &mut splinescope_gpu::renderer::GpuScene| {
                render_uploaded(
                    ctx,
                    &renderer,
                    gpu,
                    &scene.camera(VIEWPORT),
                    (VIEWPORT.x as u32, VIEWPORT.y as u32),
                    DEFAULT_TOLERANCE_PX,
                )
                .expect("render");
            };
            small(&mut gpu);
            let shrunk = gpu.capacity();
            assert!(shrunk < grown && shrunk >= before, "{what} → {shrunk}");
            small(&mut gpu);
            assert_eq!(gpu.capacity(), shrunk, "{what}");
            let stats =
                read_stats(&ctx.device, &ctx.queue, &gpu.chunks[0].adaptive).expect("stats");
            assert_eq!(stats.capped, 0, "{what}: the small view fits what is left");
        },
    );
}

#[test]
fn buffers_grow_within_the_scene_budget_and_past_it_the_frame_is_capped() {
    use splinescope_gpu::adaptive::read_stats;
    use splinescope_gpu::capture::{OFFSCREEN_FORMAT, render_uploaded};
    use splinescope_gpu::renderer::{Renderer, SAMPLE_BUDGET};
    // A zoom into the middle of many curves asks for ever more samples: however far, the
    // buffers stop at the budget (the memory of a session is bounded), and the frames past
    // it are drawn capped, within the buffers, saying so.
    const { assert!(SAMPLE_BUDGET >= 1 << 22, "a 4K screen's worth") };
    common::on_each_gpu(
        "buffers_grow_within_the_scene_budget_and_past_it_the_frame_is_capped",
        |backend| {
            let ctx = &backend.ctx;
            let scene = random_scene(14, false);
            let prepared = common::pack(ctx, &scene);
            let renderer = Renderer::new(&ctx.device, &backend.pipelines, OFFSCREEN_FORMAT);
            let mut gpu = renderer.upload(ctx, &prepared);
            let before = gpu.capacity();
            let budget = before + 5000;
            gpu.set_sample_budget(budget);
            let size = DVec2::new(2048.0, 2048.0);
            let mut capped = false;
            for zoom in [1.0, 4.0, 16.0, 64.0] {
                let camera = zoomed(&scene.camera(size), zoom, &scene);
                render_uploaded(ctx, &renderer, &mut gpu, &camera, (2048, 2048), 0.01)
                    .expect("render");
                let what = format!("{}: zoom {zoom}: {}", backend.name, gpu.capacity());
                assert!(gpu.capacity() <= budget, "{what} > {budget}");
                let stats =
                    read_stats(&ctx.device, &ctx.queue, &gpu.chunks[0].adaptive).expect("stats");
                assert!(stats.drawn <= gpu.chunks[0].adaptive.capacity, "{what}");
                if stats.requested > gpu.chunks[0].adaptive.capacity {
                    assert_eq!(stats.capped, 1, "{what}: a capped frame says so");
                    capped = true;
                }
            }
            assert!(capped, "{}: the zoom outgrew the budget", backend.name);
        },
    );
}
