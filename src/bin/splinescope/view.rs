//! `splinescope view`: a scene in a window to view and edit; and the default job (the gallery, or its PNG without a display).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use splinescope_figure::TextOptions;
use splinescope_gpu::{BackendChoice, ContextOptions, GpuContext, Pipelines};
use splinescope_render::RenderRequest;
use splinescope_scene::format::{Scene, gallery};

use crate::{GpuArgs, parse_tolerance_px, say};

/// The arguments of `splinescope view`.
#[derive(Debug, clap::Args)]
pub struct ViewArgs {
    /// Scene file (JSON), or an SVG file read as path curves; omit for the built-in gallery.
    pub scene: Option<PathBuf>,
    /// Exit after this many presented frames (smoke tests).
    #[arg(long, value_parser = crate::words::at_least::<u64>(1), allow_hyphen_values = true)]
    pub frames: Option<u64>,
    /// Destroy the GPU device after this many presented frames: the device-failure path's
    /// smoke test (not for use).
    #[arg(long, hide = true, value_name = "N", value_parser = crate::words::at_least::<u64>(1))]
    pub lose_device_after_frames: Option<u64>,
    /// Instead of a scene, show this many random curves (stress mode; Bézier unless
    /// --family says otherwise).
    #[arg(long, value_parser = crate::words::between::<u64>(1, 10_000_000), conflicts_with = "scene", allow_hyphen_values = true)]
    pub stress: Option<u64>,
    /// Family of the stress curves (a name of the family table: bezier, modified_bezier,
    /// interpolation, bspline, nubmp, rational_bezier, nurbs).
    #[arg(long, default_value = "bezier", value_parser = crate::bench::parse_family, requires = "stress")]
    pub family: splinescope_scene::format::generate::StressFamily,
    /// Degree of the stress curves.
    #[arg(long, default_value_t = 3, value_parser = crate::words::between::<u64>(1, 31), requires = "stress", allow_hyphen_values = true)]
    pub degree: u64,
    /// With --stress: re-solve every curve each frame (paper 000, one moving target
    /// per curve) and draw the result.
    #[arg(long, requires = "stress")]
    pub solve: bool,
    /// How far, in pixels, a drawn polyline may stray from its curve (sample counts
    /// are chosen every frame for it; a scene's fixed `samples` still win).
    #[arg(long, default_value_t = splinescope_gpu::adaptive::DEFAULT_TOLERANCE_PX, value_parser = parse_tolerance_px, allow_hyphen_values = true)]
    pub tolerance_px: f64,
    /// At exit, print one JSON object: frames, fps, samples and line pieces per frame,
    /// milliseconds per stage, adapter (for benchmarking the viewer by script).
    #[arg(long)]
    pub stats: bool,
    /// Start with every curve's curvature comb on (`K` toggles it): hairs SCALE world
    /// units long per unit of curvature (omit SCALE for one chosen for the view).
    #[arg(long, value_name = "SCALE", num_args = 0..=1, default_missing_value = "auto", value_parser = crate::parse_comb, allow_negative_numbers = true)]
    pub comb: Option<splinescope_scene::format::shape::CombScale>,
    /// The longest a comb hair is drawn, as a fraction of the view's height (default
    /// 0.08), or `none` (the panel's "cap" field changes it).
    #[arg(long, value_name = "FRACTION", value_parser = crate::parse_comb_cap, allow_negative_numbers = true)]
    pub comb_cap: Option<splinescope_scene::format::shape::CombCap>,
    #[command(flatten)]
    pub gpu: GpuArgs,
}

/// Runs `splinescope view`.
///
/// # Errors
/// No display, a scene that does not load, or a window or GPU failure.
pub fn run(a: &ViewArgs) -> Result<()> {
    view(
        a.scene.clone(),
        (a.frames, a.lose_device_after_frames),
        (a.stress, a.degree, a.family),
        (a.solve, a.stats),
        (a.tolerance_px, a.comb, a.comb_cap.unwrap_or_default()),
        &a.gpu,
    )
}

/// `view`: a scene (or the gallery, or a generated stress scene) in a window.
fn view(
    scene: Option<PathBuf>,
    (frames, lose_device_after_frames): (Option<u64>, Option<u64>),
    (stress, degree, family): (
        Option<u64>,
        u64,
        splinescope_scene::format::generate::StressFamily,
    ),
    (solve, print_stats): (bool, bool),
    (tolerance_px, comb, comb_cap): (
        f64,
        Option<splinescope_scene::format::shape::CombScale>,
        splinescope_scene::format::shape::CombCap,
    ),
    gpu: &GpuArgs,
) -> Result<()> {
    use splinescope_scene::format::shape::CombScale;
    let comb = comb.map(|c| match c {
        CombScale::Auto => None,
        CombScale::Fixed(s) => Some(s),
    });
    if !splinescope_viewer::display_available() {
        bail!(
            "no display found (DISPLAY and WAYLAND_DISPLAY are unset); use `splinescope render` for a PNG, or run under xvfb-run"
        );
    }
    if solve && family.name() != "bezier" {
        bail!(
            "--solve re-solves Bézier curves (paper 000's single target): --family {} cannot be solved in stress mode",
            family.name()
        );
    }
    if solve && degree < 2 {
        bail!("--solve needs --degree 2 or more (a line has no interior control point to move)");
    }
    let mut source = None;
    let mut save_to = scene.clone();
    let loaded = match stress {
        Some(n) => {
            splinescope_io::limits::SAMPLES
                .check(n.saturating_mul(u64::from(
                    splinescope_scene::format::generate::StressOptions::default().samples,
                )))
                .with_context(|| format!("view --stress {n}"))?;
            let mut generated = splinescope_scene::format::generate::random_bezier_scene(
                splinescope_scene::format::generate::StressOptions {
                    curves: n as usize,
                    degree: degree as usize,
                    family,
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
            Some(p) if splinescope_import::is_scene_file(p) => {
                let (read, text) = Scene::read(p).with_context(|| format!("{}", p.display()))?;
                source = Some(text);
                read
            }
            Some(p) => {
                // Another format: saved as a scene beside it, never over it (and never over
                // a scene already there).
                let read = crate::load::scene(p)?;
                let beside = p.with_extension("json");
                save_to = (!beside.exists()).then_some(beside);
                read
            }
            None => gallery::gallery(),
        },
    };
    let stats = splinescope_viewer::run(splinescope_viewer::ViewOptions {
        scene: loaded,
        source,
        frames,
        backend: gpu.gpu_backend,
        solve,
        tolerance_px,
        overlays_hidden: stress.is_some(),
        path: save_to,
        comb,
        comb_cap,
        lose_device_after_frames,
    })?;
    if print_stats {
        say!("{}", serde_json::to_string(&stats)?);
    }
    Ok(())
}

/// No arguments: the gallery in a window, or with no display a PNG of it.
pub fn default_job() -> Result<()> {
    let scene = gallery::gallery();
    if splinescope_viewer::display_available() {
        splinescope_viewer::run(splinescope_viewer::ViewOptions {
            scene,
            frames: None,
            backend: BackendChoice::Auto,
            solve: false,
            tolerance_px: splinescope_gpu::adaptive::DEFAULT_TOLERANCE_PX,
            overlays_hidden: false,
            path: None,
            source: None,
            comb: None,
            comb_cap: splinescope_scene::format::shape::CombCap::default(),
            lose_device_after_frames: None,
        })?;
        return Ok(());
    }
    let (ctx, pipelines) = GpuContext::new(&ContextOptions::from_env(BackendChoice::Auto))?;
    let path = std::env::current_dir()
        .context("cannot read the current directory")?
        .join("splinescope-gallery.png");
    render_to(&ctx, &pipelines, &scene, &path, 1600, 1000)?;
    say!(
        "no display found: rendered the gallery ({} curves) to {} (1600×1000, {}).\nOpen it with an image viewer, or run `splinescope view` where a display exists.",
        scene.curves.len(),
        path.display(),
        ctx.describe()
    );
    Ok(())
}

fn render_to(
    ctx: &GpuContext,
    pipelines: &Pipelines,
    scene: &Scene,
    path: &Path,
    width: u32,
    height: u32,
) -> Result<()> {
    // The headless gallery names its curves.
    let request = RenderRequest::new(width, height).with_text(TextOptions {
        labels: true,
        ..Default::default()
    });
    splinescope_render::render(ctx, pipelines, scene, &request)?.write_png(path)?;
    Ok(())
}
