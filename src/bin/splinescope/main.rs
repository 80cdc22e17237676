//! The `splinescope` command line. One module per command, each with its arguments struct
//! and its `run`; this file parses the command line, dispatches, and turns errors into
//! exit codes (1 for a failure, 2 for arguments clap refuses).

#![forbid(unsafe_code)]

use std::process::ExitCode;

use anyhow::{Result, bail};
use clap::{Parser, Subcommand};

use splinescope_gpu::{BackendChoice, ContextOptions, GpuContext, Pipelines};
use splinescope_scene::format::Scene;

mod adapters;
mod analyze;
mod bench;
mod check;
mod diff;
mod eval;
mod export;
mod fit;
mod import;
mod inspect;
mod load;
mod op;
mod regress;
mod render;
mod schema;
mod solve;
mod view;
mod words;

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
    /// What to read of a font file (any command that reads a scene file).
    #[command(flatten)]
    font: import::FontArgs,
}

/// The text a picture carries besides the curves (`render`, `export`).
#[derive(Debug, Clone, Copy, clap::Args)]
struct TextArgs {
    /// Label each curve at its end (name and live shape parameters).
    #[arg(long)]
    labels: bool,
    /// A legend in the top right corner.
    #[arg(long)]
    legend: bool,
    /// Axes with ticks and tick labels in scene units (2D scenes).
    #[arg(long)]
    axes: bool,
    /// A grid at the ticks (2D scenes).
    #[arg(long)]
    grid: bool,
}

impl TextArgs {
    fn options(self) -> splinescope_figure::TextOptions {
        splinescope_figure::TextOptions {
            labels: self.labels,
            legend: self.legend,
            axes: self.axes,
            grid: self.grid,
        }
    }
}

/// What a picture shows of its curves' shape (`render`, `export`): the curvature comb
/// and the markers the analysis finds.
#[derive(Debug, Clone, Copy, clap::Args)]
struct ShapeArgs {
    /// Draw each curve's curvature comb: hairs along the normal, their length SCALE world
    /// units per unit of curvature (omit SCALE for one chosen for the view).
    #[arg(long, value_name = "SCALE", num_args = 0..=1, default_missing_value = "auto", value_parser = parse_comb, allow_negative_numbers = true)]
    comb: Option<splinescope_scene::format::shape::CombScale>,
    /// The longest a comb hair is drawn, as a fraction of the view's height (default
    /// 0.08), or `none`: a longer hair is cut to it, drawn in the envelope's stroke, and
    /// the envelope is broken there.
    #[arg(long, value_name = "FRACTION", value_parser = parse_comb_cap, allow_negative_numbers = true)]
    comb_cap: Option<splinescope_scene::format::shape::CombCap>,
    /// Mark inflections and cusps (2D curves).
    #[arg(long)]
    inflections: bool,
    /// Mark the local extrema of the curvature (2D curves).
    #[arg(long)]
    curvature_extrema: bool,
    /// Mark where curves cross each other or themselves (2D curves).
    #[arg(long)]
    intersections: bool,
    /// Mark the joints that are not G2: kinks (G0) and curvature jumps (G1) (2D curves).
    #[arg(long)]
    joints: bool,
}

impl ShapeArgs {
    fn options(self) -> splinescope_scene::format::shape::ShapeOptions {
        splinescope_scene::format::shape::ShapeOptions {
            comb: self.comb,
            comb_cap: self.comb_cap.unwrap_or_default(),
            inflections: self.inflections,
            curvature_extrema: self.curvature_extrema,
            intersections: self.intersections,
            joints: self.joints,
        }
    }
}

/// A value that is `keyword` (`None`) or a number (`Some`), else a message naming it.
fn keyword_or_number(s: &str, keyword: &str) -> Result<Option<f64>, String> {
    if s.trim() == keyword {
        return Ok(None);
    }
    s.trim()
        .parse()
        .map(Some)
        .map_err(|_| format!("{s:?} is neither a number nor `{keyword}`"))
}

/// `--comb`'s value: `auto`, or a finite number above 0.
fn parse_comb(s: &str) -> Result<splinescope_scene::format::shape::CombScale, String> {
    use splinescope_scene::format::shape::CombScale;
    match keyword_or_number(s, "auto")? {
        None => Ok(CombScale::Auto),
        Some(v) => CombScale::fixed(v).map_err(|e| e.to_string()),
    }
}

/// `--comb-cap`'s value: `none`, or a finite number above 0.
fn parse_comb_cap(s: &str) -> Result<splinescope_scene::format::shape::CombCap, String> {
    use splinescope_scene::format::shape::CombCap;
    match keyword_or_number(s, "none")? {
        None => Ok(CombCap::NONE),
        Some(v) => CombCap::fraction(v).map_err(|e| e.to_string()),
    }
}

#[derive(Debug, clap::Args)]
struct GpuArgs {
    /// Graphics API: auto, vulkan, gl, metal or dx12 (default: WGPU_BACKEND, else auto).
    #[arg(long = "gpu-backend", value_name = "API", default_value = "auto", value_parser = parse_backend)]
    gpu_backend: BackendChoice,
}

fn parse_backend(s: &str) -> Result<BackendChoice, String> {
    s.parse()
        .map_err(|e: splinescope_gpu::context::UnknownBackend| e.to_string())
}

/// Parses `--tolerance-px`.
fn parse_tolerance_px(s: &str) -> Result<f64, String> {
    let v: f64 = s.parse().map_err(|_| format!("{s:?} is not a number"))?;
    splinescope_gpu::adaptive::check_tolerance(v).map_err(|e| e.to_string())
}

fn parse_tolerance(s: &str) -> Result<splinescope_image::compare::Tolerance, String> {
    s.parse()
        .map_err(|e: splinescope_image::compare::ToleranceError| e.to_string())
}

impl GpuArgs {
    fn context(&self) -> Result<(GpuContext, Pipelines)> {
        Ok(GpuContext::new(&ContextOptions::from_env(
            self.gpu_backend,
        ))?)
    }
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Open a scene (default: the built-in gallery) in a window, to view and edit (Ctrl+S
    /// saves to the scene's file; the gallery asks where).
    View(view::ViewArgs),
    /// Render a scene (default: the built-in gallery) offscreen to a PNG.
    Render(render::RenderArgs),
    /// Export a scene (default: the built-in gallery) as a figure: SVG or PDF with exact
    /// curves, or a PNG.
    Export(export::ExportArgs),
    /// Evaluate every curve of a scene and print the points as JSON.
    Eval(eval::EvalArgs),
    /// The questions a curve answers: length, tight box, extrema, inflections, cusps,
    /// curvature extrema, signed area; with --intersections every intersecting pair.
    Analyze(analyze::AnalyzeArgs),
    /// Print each curve's derived data as JSON: Bézier segments, tangents and inner points,
    /// refined knots, elevation coefficients, groups, dual points, VD values, ranges.
    Inspect(inspect::InspectArgs),
    /// Apply a solve request (docs/solve-format.md) to a scene: print a JSON report and,
    /// with -o, write the modified scene.
    Solve(solve::SolveArgs),
    /// Validate a scene and summarise it (families, segments, GPU compatibility).
    Check(check::CheckArgs),
    /// Read a file of another format (SVG, a font) and write it as a scene (JSON): each
    /// subpath or glyph contour one path curve, arcs exact, quadratics kept.
    Import(import::ImportArgs),
    /// Make curves from a scene's curves — as cubics or quadratics within a tolerance (a
    /// proven Hausdorff bound) — and write the scene with the results after their
    /// originals (or in their place with --replace).
    Op(op::OpArgs),
    /// Fit a curve to points (CSV or JSON) and write it as a scene: a B-spline within a
    /// smoothing budget (--smoothing, 0 through every point) or a path of cubics within a
    /// tolerance of every point, corners kept (--tolerance).
    Fit(fit::FitArgs),
    /// Print the JSON Schema of a format (scene, request, report, inspect, analyze, eval,
    /// check); without a name, list them; write them all with --write DIR.
    Schema(schema::SchemaArgs),
    /// Render every scene of SCENES_DIR (*.json, and the files splinescope imports: an
    /// imported file's reference is REFS_DIR/<file name>.png) and compare it with REFS_DIR/<name>.png;
    /// exits 1 when any scene differs, has no reference or fails.
    Regress(regress::RegressArgs),
    /// Compare two PNG images (per-channel and NVIDIA FLIP); exits 1 when they differ
    /// beyond the tolerance or their sizes differ.
    Diff(diff::DiffArgs),
    /// List every GPU adapter found: backend, device type, driver, the limits that matter
    /// here, whether its kernels pass the self-test, and which one each command would pick.
    Adapters(adapters::AdaptersArgs),
    /// Measure evaluation throughput (CPU f64 one thread and all cores, the f32 twin, GPU
    /// kernels against a write-only bound) over a matrix of rows; JSON, CSV, --compare.
    Bench(bench::BenchArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        // The reader went away (`splinescope eval … | head`): nothing left to say.
        Err(e) if is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            // A closed or full stderr loses the message, not the exit code.
            let _ =
                std::io::Write::write_fmt(&mut std::io::stderr(), format_args!("error: {e:#}\n"));
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
    load::set_options(cli.font.options());
    match cli.command {
        None => view::default_job(),
        Some(Command::View(a)) => view::run(&a),
        Some(Command::Render(a)) => render::run(&a),
        Some(Command::Export(a)) => export::run(&a),
        Some(Command::Eval(a)) => eval::run(&a),
        Some(Command::Inspect(a)) => inspect::run(&a),
        Some(Command::Analyze(a)) => analyze::run(&a),
        Some(Command::Solve(a)) => solve::run(&a),
        Some(Command::Check(a)) => check::run(&a),
        Some(Command::Import(a)) => import::run(&a),
        Some(Command::Op(a)) => op::run(&a),
        Some(Command::Fit(a)) => fit::run(&a),
        Some(Command::Schema(a)) => schema::run(&a),
        Some(Command::Regress(a)) => regress::run(&a),
        Some(Command::Diff(a)) => diff::run(&a),
        Some(Command::Adapters(a)) => adapters::run(&a),
        Some(Command::Bench(args)) => bench::run(&args),
    }
}

/// The indices `--curve` selects (all when absent), or an error naming the value.
fn select_curves(scene: &Scene, only: Option<usize>) -> Result<Vec<usize>> {
    match only {
        Some(i) if i >= scene.curves.len() => bail!(
            "--curve {i}: the scene has {} curve(s) (indices 0 to {})",
            scene.curves.len(),
            scene.curves.len().saturating_sub(1)
        ),
        Some(i) => Ok(vec![i]),
        None => Ok((0..scene.curves.len()).collect()),
    }
}
