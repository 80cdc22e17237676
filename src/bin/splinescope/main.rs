//! The `splinescope` command line: view, render, eval, check and bench.

#![forbid(unsafe_code)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result, bail};
use clap::{Parser, Subcommand, ValueEnum};
use glam::DVec3;

use splinescope::geom::{GeomError, Lower, ParamCurve};
use splinescope::gpu::{BackendChoice, ContextOptions, GpuContext};
use splinescope::num::Num;
use splinescope::scene::{Scene, gallery};

mod bench;

/// `println!` that returns the I/O error instead of panicking (a closed pipe, say).
macro_rules! say {
    ($($arg:tt)*) => {
        writeln!(std::io::stdout(), $($arg)*)?
    };
}
pub(crate) use say;

/// A GPU-rendered, real-time viewer and evaluation engine for families of parametric
/// curves. With no command: the gallery in a window, or, with no display, a PNG of it.
#[derive(Debug, Parser)]
#[command(name = "splinescope", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, clap::Args)]
struct GpuArgs {
    /// Graphics API: auto, vulkan, gl, metal or dx12 (default: WGPU_BACKEND, else auto).
    #[arg(long = "gpu-backend", value_name = "API", default_value = "auto", value_parser = parse_backend)]
    gpu_backend: BackendChoice,
}

fn parse_backend(s: &str) -> Result<BackendChoice, String> {
    s.parse()
}

/// Parses `--tolerance-px`.
fn parse_tolerance_px(s: &str) -> Result<f64, String> {
    let v: f64 = s.parse().map_err(|_| format!("{s:?} is not a number"))?;
    splinescope::gpu::adaptive::check_tolerance(v).map_err(|e| e.to_string())
}

fn parse_tolerance(s: &str) -> Result<splinescope::image::Tolerance, String> {
    s.parse()
        .map_err(|e: splinescope::image::ToleranceError| e.to_string())
}

impl GpuArgs {
    fn context(&self) -> Result<GpuContext> {
        Ok(GpuContext::new(&ContextOptions::from_env(
            self.gpu_backend,
        ))?)
    }
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Open a scene (default: the built-in gallery) in a window, to view and edit (Ctrl+S
    /// saves to the scene's file, or splinescope-scene.json for the gallery).
    View {
        /// Scene file (JSON); omit for the built-in gallery.
        scene: Option<PathBuf>,
        /// Exit after this many presented frames (smoke tests).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
        frames: Option<u64>,
        /// Instead of a scene, show this many random Bézier curves (stress mode).
        #[arg(long, value_parser = clap::value_parser!(u64).range(1..=10_000_000), conflicts_with = "scene")]
        stress: Option<u64>,
        /// Degree of the stress curves.
        #[arg(long, default_value_t = 3, value_parser = clap::value_parser!(u64).range(1..=31), requires = "stress")]
        degree: u64,
        /// With --stress: re-solve every curve each frame (paper 000, one moving target
        /// per curve) and draw the result.
        #[arg(long, requires = "stress")]
        solve: bool,
        /// How far, in pixels, a drawn polyline may stray from its curve (sample counts
        /// are chosen every frame for it; a scene's fixed `samples` still win).
        #[arg(long, default_value_t = splinescope::gpu::adaptive::DEFAULT_TOLERANCE_PX, value_parser = parse_tolerance_px)]
        tolerance_px: f64,
        /// At exit, print one JSON object: frames, fps, samples and line pieces per frame,
        /// milliseconds per stage, adapter (for benchmarking the viewer by script).
        #[arg(long)]
        stats: bool,
        #[command(flatten)]
        gpu: GpuArgs,
    },
    /// Render a scene (default: the built-in gallery) offscreen to a PNG.
    Render {
        /// Scene file (JSON); omit for the built-in gallery.
        scene: Option<PathBuf>,
        /// Output PNG.
        #[arg(short, long, value_name = "PNG")]
        output: PathBuf,
        /// Image width in pixels.
        #[arg(long, default_value_t = 1200, value_parser = clap::value_parser!(u32).range(1..=16384))]
        width: u32,
        /// Image height in pixels.
        #[arg(long, default_value_t = 800, value_parser = clap::value_parser!(u32).range(1..=16384))]
        height: u32,
        /// How far, in pixels, a drawn polyline may stray from its curve.
        #[arg(long, default_value_t = splinescope::gpu::adaptive::DEFAULT_TOLERANCE_PX, value_parser = parse_tolerance_px)]
        tolerance_px: f64,
        #[command(flatten)]
        gpu: GpuArgs,
    },
    /// Evaluate every curve of a scene and print the points as JSON.
    Eval {
        /// Scene file (JSON).
        scene: PathBuf,
        /// Number of uniform parameters over each curve's whole domain (ends included).
        #[arg(long, value_parser = clap::value_parser!(u32).range(2..=10_000_000), conflicts_with = "params")]
        samples: Option<u32>,
        /// Comma-separated parameters, in each curve's own parameter.
        #[arg(long, value_name = "T0,T1,...", allow_hyphen_values = true)]
        params: Option<String>,
        /// Where to evaluate: the exact f64 CPU path, or the GPU kernel (f32).
        #[arg(long, value_enum, default_value_t = EvalBackend::Cpu)]
        backend: EvalBackend,
        /// Only this curve (index in the scene).
        #[arg(long)]
        curve: Option<usize>,
        /// Also print the first derivative P′ (`1`), or P′, P″ and the curvature (`2`), at
        /// each parameter.
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..=2))]
        derivatives: Option<u32>,
        #[command(flatten)]
        gpu: GpuArgs,
    },
    /// Print each curve's derived data as JSON: Bézier segments, tangents and inner points,
    /// refined knots, elevation coefficients, groups, dual points, VD values, ranges.
    Inspect {
        /// Scene file (JSON).
        scene: PathBuf,
        /// Only this curve (index in the scene).
        #[arg(long)]
        curve: Option<usize>,
        /// For B-splines and NUBMP curves, also report P(τ), the groups that act there and
        /// the region each lets P(τ) reach.
        #[arg(long, allow_hyphen_values = true)]
        tau: Option<f64>,
    },
    /// Apply a solve request (docs/solve-format.md) to a scene: print a JSON report and,
    /// with -o, write the modified scene.
    Solve {
        /// Scene file (JSON).
        scene: PathBuf,
        /// Request file (JSON): one request or an array of them, applied in order.
        request: PathBuf,
        /// Where to write the modified scene (written atomically; nothing on error).
        #[arg(short, long, value_name = "SCENE")]
        output: Option<PathBuf>,
        /// Also write the report to this file.
        #[arg(long, value_name = "JSON")]
        report: Option<PathBuf>,
    },
    /// Validate a scene and summarise it (families, segments, GPU compatibility).
    Check {
        /// Scene file (JSON).
        scene: PathBuf,
        /// Print the description as JSON (docs/schemas/check.schema.json).
        #[arg(long)]
        json: bool,
    },
    /// Print the JSON Schema of a format (scene, request, report, inspect, eval, check), or
    /// write them all with --write DIR.
    Schema {
        /// Which schema.
        name: Option<String>,
        /// Write every schema as DIR/<name>.schema.json.
        #[arg(long, value_name = "DIR")]
        write: Option<PathBuf>,
    },
    /// Render every scene (*.json) of SCENES_DIR and compare it with REFS_DIR/<name>.png;
    /// exits 1 when any scene differs, has no reference or fails.
    Regress {
        /// Directory of scene files.
        scenes: PathBuf,
        /// Directory of reference images (created by --bless).
        refs: PathBuf,
        /// Write missing and changed references instead of failing on them.
        #[arg(long)]
        bless: bool,
        /// Render width in pixels.
        #[arg(long, default_value_t = 640, value_parser = clap::value_parser!(u32).range(1..=16384))]
        width: u32,
        /// Render height in pixels.
        #[arg(long, default_value_t = 480, value_parser = clap::value_parser!(u32).range(1..=16384))]
        height: u32,
        /// When images match: channel=N (largest per-channel difference that does not
        /// count), pixels=P% (largest share of differing pixels), flip=F (largest FLIP mean;
        /// unset: reported, not gated).
        #[arg(long, default_value = "channel=24,pixels=0.1%", value_parser = parse_tolerance)]
        tolerance: splinescope::image::Tolerance,
        /// Write an HTML report with the actual, reference, diff and FLIP images here.
        #[arg(long, value_name = "OUT_DIR")]
        report: Option<PathBuf>,
        /// Print the results as JSON.
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        gpu: GpuArgs,
    },
    /// Compare two PNG images (per-channel and NVIDIA FLIP); exits 1 when they differ
    /// beyond the tolerance or their sizes differ.
    Diff {
        /// The image under test.
        actual: PathBuf,
        /// The reference image.
        reference: PathBuf,
        /// Write the diff image (differing pixels in red over a grey reference).
        #[arg(short, long, value_name = "PNG")]
        output: Option<PathBuf>,
        /// Write FLIP's error map as a heat map.
        #[arg(long, value_name = "PNG")]
        flip_map: Option<PathBuf>,
        /// As for `regress`.
        #[arg(long, default_value = "channel=24,pixels=0.1%", value_parser = parse_tolerance)]
        tolerance: splinescope::image::Tolerance,
        /// Print the figures as JSON.
        #[arg(long)]
        json: bool,
    },
    /// List every GPU adapter found: backend, device type, driver, the limits that matter
    /// here, whether its kernels pass the self-test, and which one each command would pick.
    Adapters {
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        gpu: GpuArgs,
    },
    /// Measure evaluation throughput (CPU f64 one thread and all cores, the f32 twin, GPU
    /// kernels against a write-only bound) over a matrix of rows; JSON, CSV, --compare.
    Bench(bench::BenchArgs),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum EvalBackend {
    /// Exact f64 evaluation of each family.
    Cpu,
    /// The WGSL de Casteljau kernel, read back (f32).
    Gpu,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        // The reader went away (`splinescope eval … | head`): nothing left to say.
        Err(e) if is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

fn run(cli: Cli) -> Result<()> {
    match cli.command {
        None => default_job(),
        Some(Command::View {
            scene,
            frames,
            stress,
            degree,
            solve,
            tolerance_px,
            stats,
            gpu,
        }) => view(
            scene,
            frames,
            (stress, degree),
            (solve, stats),
            tolerance_px,
            &gpu,
        ),
        Some(Command::Render {
            scene,
            output,
            width,
            height,
            tolerance_px,
            gpu,
        }) => render(
            scene.as_deref(),
            &output,
            (width, height),
            tolerance_px,
            &gpu,
        ),
        Some(Command::Eval {
            scene,
            samples,
            params,
            backend,
            curve,
            derivatives,
            gpu,
        }) => eval(
            &scene,
            &EvalRequest {
                samples,
                params: params.as_deref(),
                backend,
                only: curve,
                derivatives: derivatives.unwrap_or(0),
            },
            &gpu,
        ),
        Some(Command::Check { scene, json }) => check(&scene, json),
        Some(Command::Schema { name, write }) => schema(name.as_deref(), write.as_deref()),
        Some(Command::Solve {
            scene,
            request,
            output,
            report,
        }) => solve(&scene, &request, output.as_deref(), report.as_deref()),
        Some(Command::Inspect { scene, curve, tau }) => inspect(&scene, curve, tau),
        Some(Command::Bench(args)) => bench::run(&args),
        Some(Command::Adapters { json, gpu }) => adapters(json, &gpu),
        Some(Command::Regress {
            scenes,
            refs,
            bless,
            width,
            height,
            tolerance,
            report,
            json,
            gpu,
        }) => regress(
            &scenes,
            &refs,
            &splinescope::regress::RegressOptions {
                width,
                height,
                tolerance,
                bless,
                report,
            },
            json,
            &gpu,
        ),
        Some(Command::Diff {
            actual,
            reference,
            output,
            flip_map,
            tolerance,
            json,
        }) => diff(
            &actual,
            &reference,
            output.as_deref(),
            flip_map.as_deref(),
            &tolerance,
            json,
        ),
    }
}

/// `view`: a scene (or the gallery, or a generated stress scene) in a window.
fn view(
    scene: Option<PathBuf>,
    frames: Option<u64>,
    (stress, degree): (Option<u64>, u64),
    (solve, print_stats): (bool, bool),
    tolerance_px: f64,
    gpu: &GpuArgs,
) -> Result<()> {
    if !splinescope::app::display_available() {
        bail!(
            "no display found (DISPLAY and WAYLAND_DISPLAY are unset); use `splinescope render` for a PNG, or run under xvfb-run"
        );
    }
    if solve && degree < 2 {
        bail!("--solve needs --degree 2 or more (a line has no interior control point to move)");
    }
    let mut source = None;
    let loaded = match stress {
        Some(n) => {
            splinescope::limits::SAMPLES
                .check(n.saturating_mul(u64::from(
                    splinescope::scene::generate::StressOptions::default().samples,
                )))
                .with_context(|| format!("view --stress {n}"))?;
            let mut generated = splinescope::scene::generate::random_bezier_scene(
                splinescope::scene::generate::StressOptions {
                    curves: n as usize,
                    degree: degree as usize,
                    ..Default::default()
                },
            );
            // Drawn like any scene: sample counts chosen every frame for the tolerance, and
            // control polygons and points shown when P and C turn them on (off at first).
            generated.samples_per_segment = None;
            for c in &mut generated.curves {
                c.style.show_polygon = true;
                c.style.show_points = true;
            }
            generated
        }
        None => match scene.as_deref() {
            Some(p) => {
                let (read, text) = Scene::read(p).with_context(|| format!("{}", p.display()))?;
                source = Some(text);
                read
            }
            None => gallery::gallery(),
        },
    };
    let stats = splinescope::app::run(splinescope::app::ViewOptions {
        scene: loaded,
        source,
        frames,
        backend: gpu.gpu_backend,
        solve,
        tolerance_px,
        overlays_hidden: stress.is_some(),
        path: scene,
    })?;
    if print_stats {
        say!("{}", serde_json::to_string(&stats)?);
    }
    Ok(())
}

/// `render`: a scene (or the gallery) to a PNG.
fn render(
    scene: Option<&Path>,
    output: &Path,
    (width, height): (u32, u32),
    tolerance_px: f64,
    gpu: &GpuArgs,
) -> Result<()> {
    let scene = load_scene_or_gallery(scene)?;
    let ctx = gpu.context()?;
    let image = splinescope::gpu::offscreen::render_scene_with(
        &ctx,
        &scene,
        None,
        (width, height),
        tolerance_px,
    )?;
    image.write_png(output)?;
    say!(
        "rendered {} curve(s) to {} ({width}×{height}, {})",
        scene.curves.len(),
        output.display(),
        ctx.describe()
    );
    Ok(())
}

/// No arguments: the gallery in a window, or with no display a PNG of it.
fn default_job() -> Result<()> {
    let scene = gallery::gallery();
    if splinescope::app::display_available() {
        splinescope::app::run(splinescope::app::ViewOptions {
            scene,
            frames: None,
            backend: BackendChoice::Auto,
            solve: false,
            tolerance_px: splinescope::gpu::adaptive::DEFAULT_TOLERANCE_PX,
            overlays_hidden: false,
            path: None,
            source: None,
        })?;
        return Ok(());
    }
    let ctx = GpuContext::new(&ContextOptions::from_env(BackendChoice::Auto))?;
    let path = std::env::current_dir()
        .context("cannot read the current directory")?
        .join("splinescope-gallery.png");
    render_to(&ctx, &scene, &path, 1600, 1000)?;
    say!(
        "no display found: rendered the gallery ({} curves) to {} (1600×1000, {}).\nOpen it with an image viewer, or run `splinescope view` where a display exists.",
        scene.curves.len(),
        path.display(),
        ctx.describe()
    );
    Ok(())
}

fn load_scene_or_gallery(path: Option<&Path>) -> Result<Scene> {
    match path {
        None => Ok(gallery::gallery()),
        Some(p) => Scene::load(p).with_context(|| format!("{}", p.display())),
    }
}

fn render_to(ctx: &GpuContext, scene: &Scene, path: &Path, width: u32, height: u32) -> Result<()> {
    let image = splinescope::gpu::offscreen::render_scene(ctx, scene, None, width, height)?;
    image.write_png(path)?;
    Ok(())
}

/// Parses `--params`: comma-separated finite numbers.
fn parse_params(text: &str) -> Result<Vec<f64>> {
    text.split(',')
        .enumerate()
        .map(|(i, item)| {
            let item = item.trim();
            match item.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                Ok(v) => bail!("--params[{i}]: {v} is not a finite number"),
                Err(_) => bail!("--params[{i}]: {item:?} is not a number"),
            }
        })
        .collect()
}

/// The indices `--curve` selects (all when absent), or an error naming the value.
fn select_curves(scene: &Scene, only: Option<usize>) -> Result<Vec<usize>> {
    match only {
        Some(i) if i >= scene.curves.len() => bail!(
            "--curve {i}: the scene has {} curve(s) (indices 0..{})",
            scene.curves.len(),
            scene.curves.len().saturating_sub(1)
        ),
        Some(i) => Ok(vec![i]),
        None => Ok((0..scene.curves.len()).collect()),
    }
}

fn solve(path: &Path, request: &Path, output: Option<&Path>, report: Option<&Path>) -> Result<()> {
    let scene = Scene::load(path).with_context(|| format!("{}", path.display()))?;
    let text = splinescope::limits::read_bounded(request)
        .with_context(|| format!("{}: cannot read the request", request.display()))?;
    let outcome = splinescope::request::apply_text(&scene, &text)
        .with_context(|| format!("{}", request.display()))?;
    let solved = splinescope::request::types::SolveOutput {
        reports: outcome.reports,
    };
    let text = splinescope::scene::pretty_json(&serde_json::to_value(&solved)?);
    // The scene and the report are written all or none.
    let scene_text = splinescope::scene::to_json_string(&outcome.scene);
    if let Some(out) = output {
        // The scene written must be one that `check` passes: it reads back, and the GPU
        // can draw it (a target far beyond f32 would put an annotation there).
        let name = out.display().to_string();
        let reread = splinescope::scene::from_json_str(&scene_text).with_context(|| {
            format!("{name}: the solved scene would not read back; nothing was written")
        })?;
        let problems = splinescope::outputs::CheckOutput::of(&name, &reread).gpu_problems;
        if !problems.is_empty() {
            bail!(
                "{name}: the solved scene would not pass `check` (not drawable on the GPU: {}); nothing was written",
                problems.join("; ")
            );
        }
    }
    let report_text = format!("{text}\n");
    let mut files: Vec<(&Path, &[u8])> = Vec::new();
    if let Some(out) = output {
        files.push((out, scene_text.as_bytes()));
    }
    if let Some(r) = report {
        files.push((r, report_text.as_bytes()));
    }
    splinescope::files::write_all_atomic(&files).context("nothing was written")?;
    say!("{text}");
    Ok(())
}

fn inspect(path: &Path, only: Option<usize>, tau: Option<f64>) -> Result<()> {
    let scene = Scene::load(path).with_context(|| format!("{}", path.display()))?;
    if let Some(t) = tau
        && !t.is_finite()
    {
        bail!("--tau {t}: not a finite number");
    }
    // Streamed curve by curve: memory holds the scene and one report, however many curves.
    // Reports are built before anything is printed for them, so a failing curve stops the
    // output at a curve boundary with the error on stderr (and exit 1).
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    write!(out, "{{\n  \"curves\": [")?;
    for (k, i) in select_curves(&scene, only)?.into_iter().enumerate() {
        let c = &scene.curves[i];
        let mut report = splinescope::inspect::curve_report(i, c.name.as_deref(), &c.curve)
            .with_context(|| format!("{}: curves[{i}]", path.display()))?;
        if let Some(t) = tau {
            report.at_tau = c.curve.at_tau(t).map_err(|e| match e {
                GeomError::ParameterOutsideDomain { start, end, .. } => anyhow::anyhow!(
                    "--tau {} is outside the domain [{}, {}] of curves[{i}]",
                    Num(t),
                    Num(start),
                    Num(end)
                ),
                other => {
                    anyhow::Error::new(other).context(format!("{}: curves[{i}]", path.display()))
                }
            })?;
        }
        let report = serde_json::to_value(&report)?;
        let text = splinescope::scene::pretty_json(&report);
        writeln!(out, "{}", if k == 0 { "" } else { "," })?;
        for (l, line) in text.lines().enumerate() {
            if l > 0 {
                writeln!(out)?;
            }
            write!(out, "    {line}")?;
        }
    }
    writeln!(out, "\n  ]\n}}")?;
    out.flush()?;
    Ok(())
}

/// What `eval` was asked for.
struct EvalRequest<'a> {
    samples: Option<u32>,
    params: Option<&'a str>,
    backend: EvalBackend,
    only: Option<usize>,
    /// 0: points only; 1: and P′; 2: and P″ and the curvature.
    derivatives: u32,
}

fn eval(path: &Path, req: &EvalRequest<'_>, gpu: &GpuArgs) -> Result<()> {
    let EvalRequest {
        samples,
        params,
        backend,
        only,
        derivatives,
    } = *req;
    let scene = Scene::load(path).with_context(|| format!("{}", path.display()))?;
    let indices = select_curves(&scene, only)?;
    let given = params.map(parse_params).transpose()?;
    if given.is_none() && samples.is_none() {
        bail!("give --samples N or --params T0,T1,...");
    }
    let per = given
        .as_ref()
        .map_or_else(|| u64::from(samples.unwrap_or(0)), |g| g.len() as u64);
    splinescope::limits::SAMPLES
        .check(per.saturating_mul(indices.len() as u64))
        .with_context(|| {
            format!(
                "{} curve(s) × {per} parameter(s) to evaluate",
                indices.len()
            )
        })?;
    let mut per_curve = Vec::with_capacity(indices.len());
    for &i in &indices {
        let (a, b) = scene.curves[i].curve.domain();
        let ts = match (&given, samples) {
            (Some(ts), _) => {
                for (k, &t) in ts.iter().enumerate() {
                    if !(a..=b).contains(&t) {
                        bail!(
                            "--params[{k}] = {} is outside the domain [{}, {}] of curves[{i}]",
                            Num(t),
                            Num(a),
                            Num(b)
                        );
                    }
                }
                ts.clone()
            }
            (None, Some(n)) => (0..n as usize)
                .map(|j| splinescope::geom::batch::uniform(a, b, j, n as usize))
                .collect(),
            (None, None) => unreachable!("checked above"),
        };
        per_curve.push(ts);
    }
    // values[0]: the points; values[k]: the k-th derivative.
    let values: Vec<Vec<Vec<DVec3>>> = match backend {
        EvalBackend::Cpu => (0..=derivatives)
            .map(|k| {
                indices
                    .iter()
                    .zip(&per_curve)
                    .map(|(&i, ts)| {
                        let c = &scene.curves[i].curve;
                        if k == 0 {
                            // Points: the batch evaluator over the exact lowering.
                            let mut out = vec![DVec3::ZERO; ts.len()];
                            splinescope::geom::batch::CurveSampler::new(c).eval_into(ts, &mut out);
                            return out;
                        }
                        ts.iter()
                            .map(|&t| match k {
                                1 => c.eval_deriv(t),
                                _ => c.eval_second_deriv(t),
                            })
                            .collect()
                    })
                    .collect()
            })
            .collect(),
        EvalBackend::Gpu => {
            let ctx = gpu.context()?;
            let lowered: Vec<_> = indices
                .iter()
                .map(|&i| (i, scene.curves[i].curve.lower()))
                .collect();
            let mut v = vec![splinescope::gpu::eval::evaluate(
                &ctx, &lowered, &per_curve,
            )?];
            for k in 1..=derivatives {
                v.push(splinescope::gpu::eval::evaluate_derivative(
                    &ctx, &lowered, &per_curve, k,
                )?);
            }
            v
        }
    };
    // Every number printed is finite, or the command fails naming where it overflowed.
    for (k, pts_all) in values.iter().enumerate() {
        for ((&i, ts), pts) in indices.iter().zip(&per_curve).zip(pts_all) {
            if let Some((t, p)) = ts.iter().zip(pts).find(|(_, p)| !p.is_finite()) {
                bail!(
                    "{}: curves[{i}] at t = {t}: the {} {p} is not finite (the curve's coordinates are too large for this computation in {})",
                    path.display(),
                    ["value", "first derivative", "second derivative"][k],
                    if backend == EvalBackend::Gpu {
                        "f32"
                    } else {
                        "f64"
                    }
                );
            }
        }
    }
    // κ = |P′ × P″| / |P′|³ from the values above, scaled so that it underflows nowhere:
    // null only where P′ = 0; a curvature beyond f64 fails like any other value.
    let curvatures: Option<Vec<Vec<Option<f64>>>> = (values.len() == 3).then(|| {
        values[1]
            .iter()
            .zip(&values[2])
            .map(|(d1s, d2s)| {
                d1s.iter()
                    .zip(d2s)
                    .map(|(d1, d2)| splinescope::geom::curvature(*d1, *d2))
                    .collect()
            })
            .collect()
    });
    for ((&i, ts), ks) in indices
        .iter()
        .zip(&per_curve)
        .zip(curvatures.iter().flatten())
    {
        if let Some((t, k)) = ts
            .iter()
            .zip(ks)
            .find_map(|(t, k)| k.filter(|k| !k.is_finite()).map(|k| (t, k)))
        {
            bail!(
                "{}: curves[{i}] at t = {t}: the curvature {k} is beyond f64 (P′ is nearly zero where P″ is not)",
                path.display()
            );
        }
    }
    let stdout = std::io::stdout();
    let mut out = std::io::BufWriter::new(stdout.lock());
    write_eval_json(
        &mut out,
        &indices,
        &values,
        curvatures.as_deref(),
        backend == EvalBackend::Gpu,
    )?;
    out.flush()?;
    Ok(())
}

/// Writes [`EvalOutput`](splinescope::outputs::EvalOutput), streamed curve by curve
/// (scenes may be large), with `"d1"` (P′), `"d2"` (P″) and `"curvature"` when derivatives
/// were asked for. GPU values are `f32`: they are printed in their shortest `f32` form.
fn write_eval_json(
    out: &mut impl Write,
    indices: &[usize],
    values: &[Vec<Vec<DVec3>>],
    curvatures: Option<&[Vec<Option<f64>>]>,
    from_f32: bool,
) -> Result<()> {
    let shortest = |p: DVec3| -> [f64; 3] {
        p.to_array().map(|v| {
            if from_f32 {
                shortest_f32_precision(v)
            } else {
                v
            }
        })
    };
    let list = |pts: &[DVec3]| pts.iter().copied().map(shortest).collect::<Vec<_>>();
    write!(out, "{{\"curves\":[")?;
    for (k, &index) in indices.iter().enumerate() {
        if k > 0 {
            write!(out, ",")?;
        }
        let curvature = curvatures.map(|ks| {
            ks[k]
                .iter()
                .map(|kappa| kappa.map(|v| shortest(DVec3::splat(v))[0]))
                .collect()
        });
        let curve = splinescope::outputs::EvalCurve {
            index,
            samples: list(&values[0][k]),
            d1: values.get(1).map(|v| list(&v[k])),
            d2: values.get(2).map(|v| list(&v[k])),
            curvature,
        };
        writeln!(out)?;
        serde_json::to_writer(&mut *out, &curve)?;
    }
    writeln!(out, "\n]}}")?;
    Ok(())
}

/// The shortest decimal that reads back as `v` rounded to `f32`'s 24 significant bits, at
/// `v`'s own binary exponent — so a GPU value (an `f32` that `eval` may have scaled by a
/// power of two to keep it out of `f32`'s subnormal range) prints as few digits as an `f32`
/// does, whatever its magnitude.
fn shortest_f32_precision(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() || v.abs() < f64::MIN_POSITIVE {
        return v;
    }
    let exponent = ((v.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    // Exact: a power of two (subnormal for exponent 1023, still exact) into [1, 2).
    let scale = 2f64.powi(-exponent);
    let target = (v * scale) as f32;
    for digits in 0..9 {
        let x: f64 = format!("{v:.digits$e}").parse().unwrap_or(v);
        if (x * scale) as f32 == target {
            return x;
        }
    }
    v
}

fn check(path: &Path, json: bool) -> Result<()> {
    let scene = Scene::load(path).with_context(|| format!("{}", path.display()))?;
    let report = splinescope::outputs::CheckOutput::of(&path.display().to_string(), &scene);
    if json {
        say!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        say!(
            "{}: valid scene, {} curve(s){}",
            path.display(),
            report.curves.len(),
            report
                .name
                .as_ref()
                .map(|n| format!(" ({n})"))
                .unwrap_or_default()
        );
        for c in &report.curves {
            say!(
                "  curves[{}] {}{}: domain [{}, {}], {} Bézier segment(s), max degree {}",
                c.index,
                c.family,
                c.name
                    .as_ref()
                    .map(|n| format!(" {n:?}"))
                    .unwrap_or_default(),
                Num(c.domain[0]),
                Num(c.domain[1]),
                c.segments,
                c.max_degree
            );
        }
    }
    if report.gpu_problems.is_empty() {
        if !json {
            say!("every curve fits the GPU kernel");
        }
        Ok(())
    } else {
        bail!(
            "not drawable on the GPU:\n  {}",
            report.gpu_problems.join("\n  ")
        )
    }
}

/// Prints one schema, or writes every schema into `dir`.
fn schema(name: Option<&str>, write: Option<&Path>) -> Result<()> {
    let all = splinescope::schemas::all();
    if let Some(dir) = write {
        // All or none: every schema is staged beside its target before any is moved into
        // place; a directory made for them is removed again when that fails.
        let made = !dir.exists();
        std::fs::create_dir_all(dir).with_context(|| format!("{}", dir.display()))?;
        let texts: Vec<(PathBuf, String)> = all
            .iter()
            .map(|(stem, schema)| {
                (
                    dir.join(format!("{stem}.schema.json")),
                    splinescope::schemas::to_text(schema),
                )
            })
            .collect();
        let files: Vec<(&Path, &[u8])> = texts
            .iter()
            .map(|(p, t)| (p.as_path(), t.as_bytes()))
            .collect();
        if let Err(e) = splinescope::files::write_all_atomic(&files) {
            if made {
                let _ = std::fs::remove_dir(dir);
            }
            return Err(anyhow::Error::new(e).context("nothing was written"));
        }
        for (path, _) in &texts {
            say!("wrote {}", path.display());
        }
        return Ok(());
    }
    let names: Vec<&str> = all.iter().map(|(n, _)| *n).collect();
    let Some(name) = name else {
        bail!("name a schema ({}) or give --write DIR", names.join(", "));
    };
    let Some((_, schema)) = all.iter().find(|(n, _)| *n == name) else {
        bail!(
            "unknown schema {name:?} (expected one of: {})",
            names.join(", ")
        );
    };
    print!("{}", splinescope::schemas::to_text(schema));
    Ok(())
}
/// What `adapters --json` prints.
#[derive(serde::Serialize)]
struct AdaptersOutput<'a, A: serde::Serialize> {
    backends: String,
    adapter_name_filter: Option<String>,
    adapters: &'a [A],
}

fn adapters(json: bool, gpu: &GpuArgs) -> Result<()> {
    let opts = ContextOptions::from_env(gpu.gpu_backend);
    let found = splinescope::gpu::context::survey(&opts);
    let chosen = found.iter().find(|a| a.chosen);
    if json {
        say!(
            "{}",
            serde_json::to_string_pretty(&AdaptersOutput {
                backends: splinescope::gpu::context::backend_names(opts.backend.backends()),
                adapter_name_filter: opts.adapter_name.clone(),
                adapters: &found,
            })?
        );
    } else {
        say!(
            "adapters for backends {}{} (most preferred first; * = chosen):",
            splinescope::gpu::context::backend_names(opts.backend.backends()),
            opts.adapter_name
                .as_ref()
                .map(|n| format!(", name containing {n:?}"))
                .unwrap_or_default()
        );
        for a in &found {
            let mib = |b: u64| b as f64 / (1024.0 * 1024.0);
            say!(
                "{} {} ({}, {}){}",
                if a.chosen { "*" } else { " " },
                a.name,
                a.backend,
                a.device_type,
                if a.driver.is_empty() {
                    String::new()
                } else {
                    format!(", driver {}", a.driver)
                }
            );
            say!(
                "    max storage binding {:.0} MiB, max buffer {:.0} MiB, {} workgroups per dimension, timestamps {}",
                mib(a.max_storage_binding_bytes),
                mib(a.max_buffer_bytes),
                a.max_workgroups_per_dimension,
                if a.timestamps { "yes" } else { "no" }
            );
            say!("    kernel self-test: {}", a.self_test);
        }
        match chosen {
            Some(a) => say!(
                "render, eval --backend gpu, bench and the headless gallery use: {} ({})\nview uses the first adapter in this list that passes and can present to its window",
                a.name,
                a.backend
            ),
            None => say!("no usable adapter"),
        }
    }
    if found.is_empty() {
        bail!(
            "no GPU adapter found; {}",
            splinescope::gpu::context::INSTALL_HINT
        );
    }
    if chosen.is_none() {
        bail!("no adapter passed the kernel self-test (see above)");
    }
    Ok(())
}

fn regress(
    scenes: &Path,
    refs: &Path,
    opts: &splinescope::regress::RegressOptions,
    json: bool,
    gpu: &GpuArgs,
) -> Result<()> {
    // Bad directories and sizes are refused before a GPU is opened.
    splinescope::regress::check_options(scenes, refs, opts)?;
    let ctx = gpu.context()?;
    let report = splinescope::regress::run(&ctx, scenes, refs, opts)?;
    if json {
        say!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        for r in &report.scenes {
            let figures = r.comparison.as_ref().map_or_else(String::new, |m| {
                format!(
                    " {} px differ ({:.3} %), FLIP mean {:.4}",
                    m.differing_pixels,
                    m.differing_fraction * 100.0,
                    m.flip_mean
                )
            });
            let status = format!("{:?}", r.status).to_lowercase();
            say!(
                "{status:<8} {}{figures}{}",
                r.scene,
                r.message
                    .as_ref()
                    .map(|m| format!(" — {m}"))
                    .unwrap_or_default()
            );
        }
        say!("regress on {}: {}", ctx.describe(), report.summary());
        if let Some(page) = &report.report_page {
            say!("report: {}", page.display());
        }
    }
    if report.failed() {
        bail!(
            "{} of {} scene(s) failed{}",
            report.scenes.iter().filter(|r| r.failed()).count(),
            report.scenes.len(),
            report
                .report_page
                .as_ref()
                .map(|p| format!("; see {}", p.display()))
                .unwrap_or_default()
        );
    }
    Ok(())
}

fn diff(
    actual: &Path,
    reference: &Path,
    output: Option<&Path>,
    flip_map: Option<&Path>,
    tolerance: &splinescope::image::Tolerance,
    json: bool,
) -> Result<()> {
    use splinescope::image::{RgbaImage, compare_images};
    let a = RgbaImage::read_png(actual)?;
    let b = RgbaImage::read_png(reference)?;
    let (c, pictures) = compare_images(&a, &b, tolerance)
        .with_context(|| format!("{} vs {}", actual.display(), reference.display()))?;
    // Both images or neither.
    let mut files: Vec<(&Path, Vec<u8>)> = Vec::new();
    if let Some(out) = output {
        files.push((out, pictures.diff.png_bytes(out)?));
    }
    if let Some(out) = flip_map {
        files.push((out, pictures.flip.png_bytes(out)?));
    }
    let borrowed: Vec<(&Path, &[u8])> = files.iter().map(|(p, b)| (*p, b.as_slice())).collect();
    splinescope::files::write_all_atomic(&borrowed).context("nothing was written")?;
    if json {
        say!("{}", serde_json::to_string_pretty(&c)?);
    } else {
        say!(
            "{}: {} px of {} differ ({:.3} %; largest channel difference {}), FLIP mean {:.4}, max {:.4} (tolerance {})",
            if c.matches { "match" } else { "differ" },
            c.differing_pixels,
            u64::from(c.width) * u64::from(c.height),
            c.differing_fraction * 100.0,
            c.max_channel_diff,
            c.flip_mean,
            c.flip_max,
            tolerance
        );
    }
    if !c.matches {
        bail!(
            "{} differs from {} beyond the tolerance {tolerance}",
            actual.display(),
            reference.display()
        );
    }
    Ok(())
}
