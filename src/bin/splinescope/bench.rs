//! `splinescope bench`: tessellation throughput on the CPU (exact f64 path and the f32
//! twin of the kernel, one thread each) and on the GPU (compute only, compute with
//! readback, and whole frames drawn offscreen).

use std::io::Write;
use std::time::{Duration, Instant};

use anyhow::{Context, Result};
use glam::DVec2;

use super::say;

use splinescope_gpu::capture::OFFSCREEN_FORMAT;
use splinescope_gpu::chunks::ChunkLimits;
use splinescope_gpu::layout::GpuVertex;
use splinescope_gpu::layout::{MAX_GPU_DEGREE, TESSELLATE_WORKGROUP_SIZE};
use splinescope_gpu::pack::prepare;
use splinescope_gpu::renderer::{Renderer, camera_uniform};
use splinescope_gpu::tessellator::read_buffer;
use splinescope_gpu::twin;
use splinescope_gpu::{GpuContext, Pipelines};
use splinescope_scene::format::encoding::encode;
use splinescope_scene::format::generate::{StressFamily, StressOptions, random_bezier_scene};

mod compare;
mod plot;

/// Options of `splinescope bench`. Every list is comma-separated; the benchmark runs one
/// row per combination (families × degrees × curves × samples).
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// Numbers of random curves (`1e5` style accepted), e.g. `1e3,1e4,1e5,1e6`.
    #[arg(long, value_delimiter = ',', default_value = "100000", value_parser = parse_count, allow_hyphen_values = true)]
    curves: Vec<u64>,
    /// Degrees, e.g. `3,5,12,31` (above the GPU's maximum of 31 only the CPU rows run).
    #[arg(long = "degrees", visible_alias = "degree", value_delimiter = ',', default_value = "3", value_parser = crate::words::between::<u64>(1, 63), allow_hyphen_values = true)]
    degrees: Vec<u64>,
    /// Families, any of the scene format's: `bezier`, `modified_bezier` (`t* = 1/2`),
    /// `interpolation` (degree + 1 points, cubic pieces), `bspline` (clamped uniform, four
    /// spans), `nubmp` (their standard NUBMP curves), `rational_bezier` and `nurbs`
    /// (weights cycling through 1, 2, ½, 1.5; the NURBS curves clamped uniform, four spans).
    #[arg(long, value_delimiter = ',', default_value = "bezier", value_parser = parse_family)]
    families: Vec<StressFamily>,
    /// Samples per Bézier segment (per curve for Bézier curves), e.g. `16,64,256`.
    #[arg(long, value_delimiter = ',', default_value = "64", value_parser = crate::words::between::<u32>(2, 4096), allow_hyphen_values = true)]
    samples: Vec<u32>,
    /// Timed repetitions of each GPU measurement (after one warm-up).
    #[arg(long, default_value_t = 10, value_parser = crate::words::between::<u32>(1, 10_000), allow_hyphen_values = true)]
    iterations: u32,
    /// Also draw this many whole frames offscreen (compute + lines) at 1920×1080; 0 skips.
    #[arg(long, default_value_t = 5, allow_hyphen_values = true)]
    frames: u32,
    /// Print the results as JSON (one object for one row, else an array) instead of a table.
    #[arg(long)]
    json: bool,
    /// Also write the rows as CSV to this file.
    #[arg(long, value_name = "FILE")]
    csv: Option<std::path::PathBuf>,
    /// Also draw throughput against problem size per path to this file (`.png` or `.svg`).
    #[arg(long, value_name = "FILE")]
    plot: Option<std::path::PathBuf>,
    /// Compare with an earlier `bench --json` output: print each rate's change per row and
    /// exit non-zero when one fell by more than `--threshold`.
    #[arg(long, value_name = "PREVIOUS.json")]
    compare: Option<std::path::PathBuf>,
    /// The largest fall that `--compare` tolerates, in percent (`10%` or `10`).
    #[arg(long, default_value = "10%", value_parser = parse_percent, allow_hyphen_values = true)]
    threshold: f64,
    #[command(flatten)]
    gpu: super::GpuArgs,
}

/// A family on the command line: a name of the family table.
pub(crate) fn parse_family(s: &str) -> Result<StressFamily, String> {
    s.trim()
        .parse()
        .map_err(|e: splinescope_scene::format::generate::UnknownFamily| e.to_string())
}

/// A count such as `100000` or `1e5` (a whole number of at least 1).
fn parse_count(s: &str) -> Result<u64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("{s:?} is not a number"))?;
    if !(v.is_finite() && v >= 1.0 && v.fract() == 0.0 && v <= 1e9) {
        return Err(format!(
            "{s:?}: the number of curves must be a whole number from 1 to 1e9"
        ));
    }
    Ok(v as u64)
}

/// A percentage such as `10%` or `10`, as a fraction (one `%` at most).
fn parse_percent(s: &str) -> Result<f64, String> {
    let number = s.trim();
    let number = number.strip_suffix('%').unwrap_or(number).trim_end();
    let v: f64 = number
        .parse()
        .map_err(|_| format!("{s:?} is not a percentage (such as 10% or 10)"))?;
    if !(v.is_finite() && (0.0..=1000.0).contains(&v)) {
        return Err(format!("{s:?}: the threshold must be between 0% and 1000%"));
    }
    Ok(v / 100.0)
}

fn rate(samples: u64, elapsed: Duration) -> f64 {
    samples as f64 / elapsed.as_secs_f64().max(1e-12)
}

/// One row of the matrix.
#[derive(Debug, Clone, Copy)]
struct Row {
    family: StressFamily,
    curves: u64,
    degree: u64,
    samples: u32,
}

impl Row {
    /// Bézier segments per curve.
    fn segments(self) -> u64 {
        self.family.segments(self.degree as usize) as u64
    }

    /// The degree of those segments.
    fn segment_degree(self) -> u64 {
        self.family.segment_degree(self.degree as usize) as u64
    }

    fn total_samples(self) -> u64 {
        self.curves * self.segments() * u64::from(self.samples)
    }
}

impl std::fmt::Display for Row {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "--families {} --curves {} --degrees {} --samples {}",
            self.family.name(),
            self.curves,
            self.degree,
            self.samples
        )
    }
}

/// Runs the benchmark and prints its report.
///
/// # Errors
/// A row beyond the limits (before anything is allocated), GPU setup or readback errors,
/// an unreadable `--compare` file, or a regression beyond `--threshold`.
pub fn run(args: &BenchArgs) -> Result<()> {
    let mut rows = Vec::new();
    for &f in &args.families {
        for &degree in &args.degrees {
            for &curves in &args.curves {
                for &samples in &args.samples {
                    rows.push(Row {
                        family: f,
                        curves,
                        degree,
                        samples,
                    });
                }
            }
        }
    }
    // Every row is checked before the first one allocates anything.
    for row in &rows {
        splinescope_io::limits::SAMPLES
            .check(row.total_samples())
            .with_context(|| format!("bench row {row}: {} samples", row.total_samples()))?;
        splinescope_io::limits::CURVES
            .check(row.curves)
            .with_context(|| format!("bench row {row}"))?;
    }
    if let Some(path) = &args.plot {
        plot::check_path(path)?;
    }
    let previous = match &args.compare {
        Some(path) => Some(compare::read(path)?),
        None => None,
    };
    let (ctx, pipelines) = args.gpu.context()?;
    let meta = Meta::collect(&ctx);
    let progress = indicatif::ProgressBar::with_draw_target(
        Some(rows.len() as u64),
        indicatif::ProgressDrawTarget::stderr(),
    );
    let mut reports = Vec::with_capacity(rows.len());
    for row in &rows {
        progress.set_message(row.to_string());
        reports.push(run_row(&ctx, &pipelines, *row, args, &meta)?);
        progress.inc(1);
    }
    progress.finish_and_clear();
    if args.json {
        if let [one] = reports.as_slice() {
            say!("{}", serde_json::to_string_pretty(one)?);
        } else {
            say!("{}", serde_json::to_string_pretty(&reports)?);
        }
    } else {
        for r in &reports {
            print_report(r)?;
        }
    }
    // The CSV and the plot are written all or none.
    let mut outputs: Vec<(&std::path::Path, Vec<u8>)> = Vec::new();
    if let Some(path) = &args.csv {
        outputs.push((path, csv(&reports).into_bytes()));
    }
    if let Some(path) = &args.plot {
        outputs.push((path, plot::encode(path, &reports)?));
    }
    let files: Vec<(&std::path::Path, &[u8])> =
        outputs.iter().map(|(p, b)| (*p, b.as_slice())).collect();
    splinescope_io::files::write_all_atomic(&files).context("nothing was written")?;
    if let Some(previous) = previous {
        let regressions = compare::print(&previous, &reports, args.threshold)?;
        if !regressions.is_empty() {
            anyhow::bail!(
                "{} rate(s) fell by more than {:.0} %: {}",
                regressions.len(),
                args.threshold * 100.0,
                regressions.join("; ")
            );
        }
    }
    Ok(())
}

/// Where and how the figures were taken.
#[derive(Debug, Clone, serde::Serialize)]
struct Meta {
    adapter: String,
    cpu_model: String,
    cores: usize,
    build: String,
    date: String,
}

impl Meta {
    fn collect(ctx: &GpuContext) -> Meta {
        let cpu_model = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split_once(':'))
                    .map(|(_, v)| v.trim().to_owned())
            })
            .unwrap_or_else(|| std::env::consts::ARCH.to_owned());
        Meta {
            adapter: ctx.describe(),
            cpu_model,
            cores: std::thread::available_parallelism().map_or(1, std::num::NonZero::get),
            build: format!(
                "splinescope {} ({})",
                env!("CARGO_PKG_VERSION"),
                if cfg!(debug_assertions) {
                    "debug"
                } else {
                    "release"
                }
            ),
            date: utc_now(),
        }
    }
}

/// The current UTC time as `YYYY-MM-DDTHH:MM:SSZ` (civil date from days since 1970).
fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let (days, rem) = ((secs / 86_400) as i64, secs % 86_400);
    // Howard Hinnant's days-to-civil.
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

/// One row: CPU rates always, GPU rates unless the segments' degree is over the GPU's
/// maximum (then `notes` says so).
fn run_row(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    row: Row,
    args: &BenchArgs,
    meta: &Meta,
) -> Result<BenchReport> {
    let scene = random_bezier_scene(StressOptions {
        curves: row.curves as usize,
        degree: row.degree as usize,
        samples: row.samples,
        three_d: false,
        seed: 7,
        family: row.family,
    });
    let per_curve = (row.segments() * u64::from(row.samples)) as usize;
    let (cpu_f64, cpu_all_cores) = cpu_rates(&scene, per_curve);
    let mut report = BenchReport {
        family: row.family.name(),
        curves: row.curves,
        degree: row.degree,
        samples_per_curve: per_curve as u32,
        chunks: None,
        cpu_f64_one_thread_samples_per_s: cpu_f64,
        cpu_f64_all_cores_samples_per_s: cpu_all_cores,
        cpu_f32_twin_one_thread_samples_per_s: None,
        gpu_compute_wall_samples_per_s: None,
        gpu_compute_timestamp_samples_per_s: None,
        gpu_write_limit_samples_per_s: None,
        gpu_kernel_share_of_write_limit: None,
        gpu_compute_with_readback_samples_per_s: None,
        frames_per_s_1920x1080: None,
        notes: Vec::new(),
        meta: meta.clone(),
    };
    if row.segment_degree() > MAX_GPU_DEGREE as u64 {
        report.notes.push(format!(
            "GPU rows skipped: the curves' Bézier segments have degree {}, over the GPU maximum of {MAX_GPU_DEGREE}",
            row.segment_degree()
        ));
        return Ok(report);
    }
    gpu_rates(ctx, pipelines, &scene, row, args, &mut report)?;
    Ok(report)
}

/// The GPU rows of `report`: the kernels, the write-only bound, readback, whole frames.
fn gpu_rates(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scene: &splinescope_scene::format::Scene,
    row: Row,
    args: &BenchArgs,
    report: &mut BenchReport,
) -> Result<()> {
    let prepared = prepare(
        &encode(scene),
        ChunkLimits::for_binding_size(ctx.max_binding_bytes()),
    )?;
    report.chunks = Some(prepared.chunks.len());
    report.cpu_f32_twin_one_thread_samples_per_s = Some(twin_rate(&prepared));
    let total = row.total_samples();
    let records: Vec<_> = prepared
        .chunks
        .iter()
        .map(|c| {
            pipelines
                .tessellator
                .upload(&ctx.device, c, wgpu::BufferUsages::COPY_SRC)
        })
        .collect();
    let (wall, pass, pass_note) = gpu_compute_rates(
        ctx,
        pipelines,
        &records,
        total,
        args.iterations,
        Kernel::Tessellate,
    )?;
    let (limit_wall, limit_pass, limit_note) = gpu_compute_rates(
        ctx,
        pipelines,
        &records,
        total,
        args.iterations,
        Kernel::WriteOnly,
    )?;
    drop(records);
    report.notes.extend(pass_note.into_iter().chain(limit_note));
    report.gpu_compute_wall_samples_per_s = Some(wall);
    report.gpu_compute_timestamp_samples_per_s = pass;
    report.gpu_write_limit_samples_per_s = Some(limit_pass.unwrap_or(limit_wall));
    // The share of the write-only bound, by timestamps where the adapter has them.
    report.gpu_kernel_share_of_write_limit = Some(match (pass, limit_pass) {
        (Some(k), Some(l)) => k / l,
        _ => wall / limit_wall,
    });
    let started = Instant::now();
    let mut read = 0u64;
    pipelines.tessellator.tessellate_and_read(
        &ctx.device,
        &ctx.queue,
        &prepared.chunks,
        |_, s| {
            read += s.len() as u64;
        },
    )?;
    report.gpu_compute_with_readback_samples_per_s = Some(rate(read, started.elapsed()));
    if args.frames > 0 {
        let renderer = Renderer::new(&ctx.device, pipelines, OFFSCREEN_FORMAT);
        let mut gpu_scene = renderer.upload(ctx, &prepared);
        report.frames_per_s_1920x1080 = Some(draw_frames(
            ctx,
            &renderer,
            &mut gpu_scene,
            scene,
            args.frames,
        )?);
    }
    Ok(())
}

/// What `bench --json` prints per row (rates in samples per second; `null` where a path
/// did not run, with the reason in `notes`).
#[derive(Debug, serde::Serialize)]
struct BenchReport {
    family: &'static str,
    curves: u64,
    degree: u64,
    samples_per_curve: u32,
    chunks: Option<usize>,
    cpu_f64_one_thread_samples_per_s: f64,
    cpu_f64_all_cores_samples_per_s: f64,
    cpu_f32_twin_one_thread_samples_per_s: Option<f64>,
    gpu_compute_wall_samples_per_s: Option<f64>,
    gpu_compute_timestamp_samples_per_s: Option<f64>,
    gpu_write_limit_samples_per_s: Option<f64>,
    gpu_kernel_share_of_write_limit: Option<f64>,
    gpu_compute_with_readback_samples_per_s: Option<f64>,
    frames_per_s_1920x1080: Option<f64>,
    notes: Vec<String>,
    #[serde(flatten)]
    meta: Meta,
}

/// The rows as CSV: one header line, one line per row, empty cells where a path did not
/// run.
fn csv(reports: &[BenchReport]) -> String {
    let mut out = String::new();
    for (i, r) in reports.iter().enumerate() {
        let Ok(serde_json::Value::Object(map)) = serde_json::to_value(r) else {
            continue;
        };
        if i == 0 {
            out.push_str(&map.keys().cloned().collect::<Vec<_>>().join(","));
            out.push('\n');
        }
        let cells: Vec<String> = map
            .values()
            .map(|v| {
                let text = match v {
                    serde_json::Value::Null => String::new(),
                    serde_json::Value::String(s) => s.clone(),
                    serde_json::Value::Array(a) => a
                        .iter()
                        .filter_map(|x| x.as_str())
                        .collect::<Vec<_>>()
                        .join(" | "),
                    other => other.to_string(),
                };
                if text.contains([',', '"', '\n']) {
                    format!("\"{}\"", text.replace('"', "\"\""))
                } else {
                    text
                }
            })
            .collect();
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

fn print_report(r: &BenchReport) -> Result<()> {
    let m = |v: f64| format!("{:>10.1} M samples/s", v / 1e6);
    let total = r.curves * u64::from(r.samples_per_curve);
    say!(
        "adapter: {}\n{} {} curves of degree {}, {} samples each ({} samples{})",
        r.meta.adapter,
        r.curves,
        r.family,
        r.degree,
        r.samples_per_curve,
        total,
        r.chunks
            .map_or(String::new(), |c| format!(", {c} chunk(s)"))
    );
    say!(
        "  CPU f64 batch evaluator, 1 thread  {}",
        m(r.cpu_f64_one_thread_samples_per_s)
    );
    say!(
        "  CPU f64 batch evaluator, all cores {}",
        m(r.cpu_f64_all_cores_samples_per_s)
    );
    for note in &r.notes {
        say!("  {note}");
    }
    let (Some(twin), Some(wall), Some(limit), Some(share), Some(readback)) = (
        r.cpu_f32_twin_one_thread_samples_per_s,
        r.gpu_compute_wall_samples_per_s,
        r.gpu_write_limit_samples_per_s,
        r.gpu_kernel_share_of_write_limit,
        r.gpu_compute_with_readback_samples_per_s,
    ) else {
        return Ok(());
    };
    say!("  CPU f32 kernel twin, 1 thread      {}", m(twin));
    say!("  GPU compute (wall, submit+wait)    {}", m(wall));
    match r.gpu_compute_timestamp_samples_per_s {
        Some(v) => say!("  GPU compute (timestamps)           {}", m(v)),
        None if r.notes.iter().any(|n| n.starts_with(TIMESTAMPS_REFUSED)) => {
            say!("  GPU compute (timestamps)           none: they do not bracket the work (above)");
        }
        None => say!("  GPU compute (timestamps)           not supported by this adapter"),
    }
    say!(
        "  GPU write-only kernel (the limit)  {}   kernel at {:.0} % of it",
        m(limit),
        100.0 * share
    );
    say!("  GPU compute + readback             {}", m(readback));
    if let Some(fps) = r.frames_per_s_1920x1080 {
        say!("  whole frames 1920×1080 (compute + lines) {fps:.2} frames/s");
    }
    Ok(())
}

/// Timed passes of each CPU rate in [`cpu_rates`].
const CPU_PASSES: usize = 3;

/// CPU rates over at most 2M samples: the batch `f64` evaluator on one thread and on
/// every core, `per_curve` uniform samples of each curve; each the best of
/// [`CPU_PASSES`] timed passes after an untimed one (one pass of a few milliseconds moves
/// by a fifth between runs on a busy machine).
fn cpu_rates(scene: &splinescope_scene::format::Scene, per_curve: usize) -> (f64, f64) {
    use splinescope_core::geom::batch::{CurveSampler, UniformCubicWeights, for_each_sampled};
    let cpu_curves = (2_000_000 / per_curve).clamp(1, scene.curves.len());
    let samplers: Vec<CurveSampler> = scene.curves[..cpu_curves]
        .iter()
        .map(|c| CurveSampler::new(&c.curve))
        .collect();
    let total = (cpu_curves * per_curve) as u64;
    let mut out = vec![glam::DVec3::ZERO; per_curve];
    let weights = UniformCubicWeights::new(per_curve);
    let mut one_thread = || {
        for s in &samplers {
            s.sample_uniform_with(&weights, &mut out);
            std::hint::black_box(&mut out);
        }
    };
    let mut all_cores = || {
        for_each_sampled(&samplers, per_curve, |_, points| {
            std::hint::black_box(points);
        });
    };
    // A first pass of each warms the caches and starts rayon's threads.
    let best = |pass: &mut dyn FnMut()| {
        pass();
        (0..CPU_PASSES)
            .map(|_| {
                let started = Instant::now();
                pass();
                rate(total, started.elapsed())
            })
            .fold(0.0, f64::max)
    };
    (best(&mut one_thread), best(&mut all_cores))
}

/// The `f32` twin of the kernel, one thread, over at most 2M samples of the first chunk.
fn twin_rate(prepared: &splinescope_gpu::pack::PreparedScene) -> f64 {
    let chunk = &prepared.chunks[0];
    // A record writes at most one workgroup's worth of its segment's samples.
    let written = |r: &splinescope_gpu::layout::GpuRecord| {
        u64::from((r.sample_count - r.sample_offset).min(TESSELLATE_WORKGROUP_SIZE))
    };
    let mut samples = 0u64;
    let records: Vec<_> = chunk
        .records
        .iter()
        .take_while(|r| {
            samples += written(r);
            samples <= 2_000_000
        })
        .copied()
        .collect();
    let mut out = vec![
        GpuVertex {
            position: [0.0; 3],
            id: 0
        };
        chunk.sample_count as usize
    ];
    let started = Instant::now();
    twin::tessellate(&chunk.points, &records, &mut out);
    let elapsed = started.elapsed();
    std::hint::black_box(&out);
    rate(records.iter().map(written).sum(), elapsed)
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
    pipelines: &Pipelines,
    records: &[splinescope_gpu::tessellator::ChunkBuffers],
    total: u64,
    iterations: u32,
    kernel: Kernel,
) -> Result<(f64, Option<f64>, Option<String>)> {
    let timestamps = Timestamps::new(ctx);
    let mut gpu_pass_ns = Vec::new();
    let mut wall = Duration::ZERO;
    for i in 0..=iterations {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let writes = timestamps.as_ref().map(Timestamps::writes);
        match kernel {
            Kernel::Tessellate => pipelines.tessellator.encode(&mut encoder, records, writes),
            Kernel::WriteOnly => {
                pipelines
                    .tessellator
                    .encode_write_only(&ctx.device, &mut encoder, records, writes)
            }
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
    let gpu_wall = rate(total * u64::from(iterations), wall);
    let mut note = None;
    let gpu_pass = if gpu_pass_ns.is_empty() {
        None
    } else {
        let mean = gpu_pass_ns.iter().sum::<f64>() / gpu_pass_ns.len() as f64;
        let wall_ns = wall.as_secs_f64() * 1e9 / f64::from(iterations.max(1));
        if timestamps_bracket_the_work(mean, wall_ns) {
            Some(total as f64 / (mean * 1e-9))
        } else {
            note = Some(format!(
                "{TIMESTAMPS_REFUSED} the {} pass at {:.3} ms against {:.1} ms by the wall clock: they do not bracket its work, so no timestamp rate is given",
                match kernel {
                    Kernel::Tessellate => "kernel",
                    Kernel::WriteOnly => "write-only",
                },
                mean * 1e-6,
                wall_ns * 1e-6
            ));
            None
        }
    };
    Ok((gpu_wall, gpu_pass, note))
}

/// How a row's note refusing the adapter's timestamps begins (the summary refers to it).
const TIMESTAMPS_REFUSED: &str = "the adapter's timestamps put";

/// Whether a pass's timestamped duration can be the duration of its work, given the wall
/// clock around its submission and wait (`wall_ns`, which also holds the submission and
/// the readback of the timestamps). Where the wall clock is long enough not to be
/// overhead (over 5 ms) and the timestamps account for less than a tenth of it, they did
/// not bracket the work: software adapters (lavapipe) run large dispatches on worker
/// threads the timestamps do not wait for, and report a duration that does not grow with
/// the work.
fn timestamps_bracket_the_work(pass_ns: f64, wall_ns: f64) -> bool {
    pass_ns.is_finite() && pass_ns > 0.0 && (wall_ns <= 5e6 || pass_ns * 10.0 >= wall_ns)
}

fn draw_frames(
    ctx: &GpuContext,
    renderer: &Renderer,
    gpu_scene: &mut splinescope_gpu::renderer::GpuScene,
    scene: &splinescope_scene::format::Scene,
    frames: u32,
) -> Result<f64> {
    let (w, h) = (1920, 1080);
    let viewport = DVec2::new(f64::from(w), f64::from(h));
    let camera = camera_uniform(&scene.camera(viewport), viewport, 1.0);
    renderer.set_camera(&ctx.queue, &camera);
    gpu_scene.prepare_frame(
        ctx,
        renderer,
        &splinescope_gpu::adaptive::FrameSettings {
            camera,
            tolerance_px: splinescope_gpu::adaptive::DEFAULT_TOLERANCE_PX as f32,
            min_count: gpu_scene.min_count(),
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
        renderer.encode_frame(&mut encoder, gpu_scene, &view);
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

#[cfg(test)]
mod tests {
    use super::timestamps_bracket_the_work;

    #[test]
    fn timestamps_that_do_not_grow_with_the_work_are_not_taken() {
        // lavapipe, 100,000 cubics: 0.09 ms by timestamps against 140 ms by the wall.
        assert!(!timestamps_bracket_the_work(0.09e6, 140e6));
        // A hardware adapter: the pass is most of a long wall clock.
        assert!(timestamps_bracket_the_work(4.0e6, 6.0e6));
        assert!(timestamps_bracket_the_work(0.7e6, 7.0e6));
        // A short dispatch: the wall clock is mostly submission and readback.
        assert!(timestamps_bracket_the_work(0.05e6, 1.5e6));
        // No duration at all is never a measurement.
        assert!(!timestamps_bracket_the_work(0.0, 1.0e6));
        assert!(!timestamps_bracket_the_work(f64::NAN, 1.0e6));
    }
}
