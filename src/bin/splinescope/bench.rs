//! `splinescope bench`: tessellation throughput on the CPU (exact f64 path and the f32
//! twin of the kernel, one thread each) and on the GPU (compute only, compute with
//! readback, and whole frames drawn offscreen).

use std::io::Write;
use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use glam::DVec2;

use super::say;

use splinescope::gpu::GpuContext;
use splinescope::gpu::layout::GpuVertex;
use splinescope::gpu::offscreen::OFFSCREEN_FORMAT;
use splinescope::gpu::pack::{ChunkLimits, prepare_scene};
use splinescope::gpu::renderer::{Renderer, camera_uniform};
use splinescope::gpu::tessellator::read_buffer;
use splinescope::gpu::twin;
use splinescope::scene::generate::{StressOptions, random_bezier_scene};

/// Options of `splinescope bench`.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// Number of random curves.
    #[arg(long, default_value_t = 100_000, value_parser = clap::value_parser!(u64).range(1..=10_000_000))]
    curves: u64,
    /// Their degree.
    #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=31))]
    degree: u64,
    /// Samples per curve.
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(2..=4096))]
    samples: u32,
    /// Timed repetitions of each GPU measurement (after one warm-up).
    #[arg(long, default_value_t = 10, value_parser = clap::value_parser!(u32).range(1..=10_000))]
    iterations: u32,
    /// Also draw this many whole frames offscreen (compute + lines) at 1920×1080; 0 skips.
    #[arg(long, default_value_t = 5)]
    frames: u32,
    /// Print the results as JSON instead of a table.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    gpu: super::GpuArgs,
}

fn rate(samples: u64, elapsed: Duration) -> f64 {
    samples as f64 / elapsed.as_secs_f64().max(1e-12)
}

/// Runs the benchmark and prints its report.
///
/// # Errors
/// GPU setup or readback errors.
pub fn run(args: &BenchArgs) -> Result<()> {
    // Checked before the scene is generated: curves × samples bounds every buffer.
    splinescope::limits::SAMPLES
        .check(args.curves * u64::from(args.samples))
        .with_context(|| format!("bench --curves {} --samples {}", args.curves, args.samples))?;
    let scene = random_bezier_scene(StressOptions {
        curves: args.curves as usize,
        degree: args.degree as usize,
        samples: args.samples,
        three_d: false,
        seed: 7,
    });
    let ctx = args.gpu.context()?;
    let prepared = prepare_scene(
        &scene,
        ChunkLimits::for_binding_size(ctx.max_binding_bytes()),
    )?;
    let (cpu_f64, cpu_all_cores, cpu_twin) = cpu_rates(&scene, &prepared, args);
    let renderer = Renderer::new(&ctx.device, OFFSCREEN_FORMAT);
    let gpu_scene = renderer.upload(&ctx, &prepared);
    // The kernel's throughput: every record of the packing, fixed counts.
    let records: Vec<_> = prepared
        .chunks
        .iter()
        .map(|c| {
            ctx.tessellator
                .upload(&ctx.device, c, wgpu::BufferUsages::COPY_SRC)
        })
        .collect();
    let (gpu_wall, gpu_pass) = gpu_compute_rates(&ctx, &records, args, Kernel::Tessellate)?;
    let (limit_wall, limit_pass) = gpu_compute_rates(&ctx, &records, args, Kernel::WriteOnly)?;
    // The share of the write-only bound, by timestamps where the adapter has them.
    let share = match (gpu_pass, limit_pass) {
        (Some(k), Some(l)) => k / l,
        _ => gpu_wall / limit_wall,
    };

    // GPU compute + readback of every sample.
    let started = Instant::now();
    let mut read = 0u64;
    ctx.tessellator
        .tessellate_and_read(&ctx.device, &ctx.queue, &prepared.chunks, |_, s| {
            read += s.len() as u64;
        })?;
    let gpu_readback = rate(read, started.elapsed());

    // Whole frames offscreen.
    let frame_fps = if args.frames > 0 {
        Some(draw_frames(
            &ctx,
            &renderer,
            &gpu_scene,
            &scene,
            args.frames,
        )?)
    } else {
        None
    };
    let report = BenchReport {
        adapter: ctx.describe(),
        curves: args.curves,
        degree: args.degree,
        samples_per_curve: args.samples,
        chunks: prepared.chunks.len(),
        cpu_f64_one_thread_samples_per_s: cpu_f64,
        cpu_f64_all_cores_samples_per_s: cpu_all_cores,
        cpu_f32_twin_one_thread_samples_per_s: cpu_twin,
        gpu_compute_wall_samples_per_s: gpu_wall,
        gpu_compute_timestamp_samples_per_s: gpu_pass,
        gpu_write_limit_samples_per_s: limit_pass.unwrap_or(limit_wall),
        gpu_kernel_share_of_write_limit: share,
        gpu_compute_with_readback_samples_per_s: gpu_readback,
        frames_per_s_1920x1080: frame_fps,
    };
    if args.json {
        say!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_report(&report)?;
    }
    Ok(())
}

/// What `bench --json` prints (rates in samples per second).
#[derive(Debug, serde::Serialize)]
struct BenchReport {
    adapter: String,
    curves: u64,
    degree: u64,
    samples_per_curve: u32,
    chunks: usize,
    cpu_f64_one_thread_samples_per_s: f64,
    cpu_f64_all_cores_samples_per_s: f64,
    cpu_f32_twin_one_thread_samples_per_s: f64,
    gpu_compute_wall_samples_per_s: f64,
    gpu_compute_timestamp_samples_per_s: Option<f64>,
    gpu_write_limit_samples_per_s: f64,
    gpu_kernel_share_of_write_limit: f64,
    gpu_compute_with_readback_samples_per_s: f64,
    frames_per_s_1920x1080: Option<f64>,
}

fn print_report(r: &BenchReport) -> Result<()> {
    let m = |v: f64| format!("{:>10.1} M samples/s", v / 1e6);
    let total = r.curves * u64::from(r.samples_per_curve);
    say!(
        "adapter: {}\n{} curves of degree {}, {} samples each ({} samples, {} chunk(s))",
        r.adapter,
        r.curves,
        r.degree,
        r.samples_per_curve,
        total,
        r.chunks
    );
    say!(
        "  CPU f64 batch evaluator, 1 thread  {}",
        m(r.cpu_f64_one_thread_samples_per_s)
    );
    say!(
        "  CPU f64 batch evaluator, all cores {}",
        m(r.cpu_f64_all_cores_samples_per_s)
    );
    say!(
        "  CPU f32 kernel twin, 1 thread      {}",
        m(r.cpu_f32_twin_one_thread_samples_per_s)
    );
    say!(
        "  GPU compute (wall, submit+wait)    {}",
        m(r.gpu_compute_wall_samples_per_s)
    );
    match r.gpu_compute_timestamp_samples_per_s {
        Some(v) => say!("  GPU compute (timestamps)           {}", m(v)),
        None => say!("  GPU compute (timestamps)           not supported by this adapter"),
    }
    say!(
        "  GPU write-only kernel (the limit)  {}   kernel at {:.0} % of it",
        m(r.gpu_write_limit_samples_per_s),
        100.0 * r.gpu_kernel_share_of_write_limit
    );
    say!(
        "  GPU compute + readback             {}",
        m(r.gpu_compute_with_readback_samples_per_s)
    );
    if let Some(fps) = r.frames_per_s_1920x1080 {
        say!(
            "  whole frames 1920×1080 (compute + {} line pieces) {fps:.2} frames/s",
            total.saturating_sub(r.curves)
        );
    }
    Ok(())
}

/// CPU rates over at most 2M samples each: the batch `f64` evaluator on one thread and on
/// every core, and the `f32` twin of the kernel (one thread) over the first chunk's records.
fn cpu_rates(
    scene: &splinescope::scene::Scene,
    prepared: &splinescope::gpu::pack::PreparedScene,
    args: &BenchArgs,
) -> (f64, f64, f64) {
    use splinescope::geom::batch::{CurveSampler, UniformCubicWeights, for_each_sampled};
    let cpu_curves = (2_000_000 / u64::from(args.samples)).clamp(1, args.curves) as usize;
    let samplers: Vec<CurveSampler> = scene.curves[..cpu_curves]
        .iter()
        .map(|c| CurveSampler::new(&c.curve))
        .collect();
    let count = args.samples as usize;
    let mut out = vec![glam::DVec3::ZERO; count];
    let weights = UniformCubicWeights::new(count);
    let started = Instant::now();
    for s in &samplers {
        s.sample_uniform_with(&weights, &mut out);
        std::hint::black_box(&mut out);
    }
    let cpu_f64 = rate(
        cpu_curves as u64 * u64::from(args.samples),
        started.elapsed(),
    );
    let mut started = Instant::now();
    // A first pass starts rayon's threads; the second is timed.
    for pass in 0..2 {
        if pass == 1 {
            started = Instant::now();
        }
        for_each_sampled(&samplers, count, |_, points| {
            std::hint::black_box(points);
        });
    }
    let cpu_all_cores = rate(
        cpu_curves as u64 * u64::from(args.samples),
        started.elapsed(),
    );
    let chunk = &prepared.chunks[0];
    let records = chunk
        .records
        .len()
        .min((2_000_000 / args.samples as usize).max(1));
    let mut out = vec![
        GpuVertex {
            position: [0.0; 3],
            id: 0
        };
        chunk.sample_count as usize
    ];
    let started = Instant::now();
    twin::tessellate(&chunk.points, &chunk.records[..records], &mut out);
    let cpu_twin = rate(records as u64 * u64::from(args.samples), started.elapsed());
    std::hint::black_box(&out);
    (cpu_f64, cpu_all_cores, cpu_twin)
}

/// Which compute pass [`gpu_compute_rates`] times.
#[derive(Debug, Clone, Copy)]
enum Kernel {
    /// The de Casteljau kernels.
    Tessellate,
    /// The write-only kernel over the same records: the bound for this output.
    WriteOnly,
}

/// The compute pass alone: by wall clock (submit and wait) and, where the adapter has
/// them, by timestamps.
fn gpu_compute_rates(
    ctx: &GpuContext,
    records: &[splinescope::gpu::tessellator::ChunkBuffers],
    args: &BenchArgs,
    kernel: Kernel,
) -> Result<(f64, Option<f64>)> {
    let total = args.curves * u64::from(args.samples);
    let timestamps = Timestamps::new(ctx);
    let mut gpu_pass_ns = Vec::new();
    let mut wall = Duration::ZERO;
    for i in 0..=args.iterations {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let writes = timestamps.as_ref().map(Timestamps::writes);
        match kernel {
            Kernel::Tessellate => ctx.tessellator.encode(&mut encoder, records, writes),
            Kernel::WriteOnly => ctx
                .tessellator
                .encode_write_only(&mut encoder, records, writes),
        }
        let started = Instant::now();
        if let Some(ts) = &timestamps {
            let ns = ts.resolve_and_read(ctx, encoder)?;
            if i > 0 {
                gpu_pass_ns.push(ns);
            }
        } else {
            ctx.queue.submit([encoder.finish()]);
            ctx.device
                .poll(wgpu::PollType::wait_indefinitely())
                .map_err(|e| anyhow::anyhow!("{e}"))?;
        }
        if i > 0 {
            wall += started.elapsed();
        }
    }
    let gpu_wall = rate(total * u64::from(args.iterations), wall);
    let gpu_pass = (!gpu_pass_ns.is_empty()).then(|| {
        let mean = gpu_pass_ns.iter().sum::<f64>() / gpu_pass_ns.len() as f64;
        total as f64 / (mean * 1e-9)
    });
    Ok((gpu_wall, gpu_pass))
}

fn draw_frames(
    ctx: &GpuContext,
    renderer: &Renderer,
    gpu_scene: &splinescope::gpu::renderer::GpuScene,
    scene: &splinescope::scene::Scene,
    frames: u32,
) -> Result<f64> {
    let (w, h) = (1920, 1080);
    let viewport = DVec2::new(f64::from(w), f64::from(h));
    let camera = camera_uniform(&scene.camera(viewport), viewport, 1.0);
    renderer.set_camera(&ctx.queue, &camera);
    gpu_scene.prepare_frame(
        ctx,
        &splinescope::gpu::adaptive::FrameSettings {
            camera,
            tolerance_px: splinescope::gpu::adaptive::DEFAULT_TOLERANCE_PX as f32,
        },
    );
    let texture = ctx.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("bench target"),
        size: wgpu::Extent3d {
            width: w,
            height: h,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: OFFSCREEN_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    let mut elapsed = Duration::ZERO;
    for i in 0..=frames {
        let started = Instant::now();
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        renderer.encode_frame(ctx, &mut encoder, gpu_scene, &view);
        ctx.queue.submit([encoder.finish()]);
        ctx.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| anyhow::anyhow!("{e}"))?;
        if i > 0 {
            elapsed += started.elapsed();
        }
    }
    Ok(f64::from(frames) / elapsed.as_secs_f64().max(1e-12))
}

/// GPU timestamps around the compute pass, when the adapter supports them.
struct Timestamps {
    set: wgpu::QuerySet,
    resolve: wgpu::Buffer,
    period_ns: f32,
}

impl Timestamps {
    fn new(ctx: &GpuContext) -> Option<Timestamps> {
        if !ctx
            .device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
        {
            return None;
        }
        Some(Timestamps {
            set: ctx.device.create_query_set(&wgpu::QuerySetDescriptor {
                label: Some("tessellate timestamps"),
                ty: wgpu::QueryType::Timestamp,
                count: 2,
            }),
            resolve: ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("timestamps"),
                size: 16,
                usage: wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
            period_ns: ctx.queue.get_timestamp_period(),
        })
    }

    fn writes(&self) -> wgpu::ComputePassTimestampWrites<'_> {
        wgpu::ComputePassTimestampWrites {
            query_set: &self.set,
            beginning_of_pass_write_index: Some(0),
            end_of_pass_write_index: Some(1),
        }
    }

    /// Submits `encoder` with the timestamps resolved, waits, and returns the pass's
    /// duration in nanoseconds.
    fn resolve_and_read(&self, ctx: &GpuContext, mut encoder: wgpu::CommandEncoder) -> Result<f64> {
        encoder.resolve_query_set(&self.set, 0..2, &self.resolve, 0);
        let ticks: Vec<u64> = read_buffer(&ctx.device, &ctx.queue, &mut encoder, &self.resolve)?;
        Ok(ticks[1].saturating_sub(ticks[0]) as f64 * f64::from(self.period_ns))
    }
}
