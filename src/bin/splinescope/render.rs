//! `splinescope render`: a scene (default: the built-in gallery) drawn offscreen to a PNG.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::Result;

use splinescope_render::RenderRequest;
use splinescope_scene::format::{Scene, gallery};

use crate::{GpuArgs, ShapeArgs, TextArgs, parse_tolerance_px, say};

/// The arguments of `splinescope render`.
#[derive(Debug, clap::Args)]
pub struct RenderArgs {
    /// Scene file (JSON), or an SVG file read as path curves; omit for the built-in gallery.
    pub scene: Option<PathBuf>,
    /// Output PNG.
    #[arg(short, long, value_name = "PNG")]
    pub output: PathBuf,
    /// Image width in pixels.
    #[arg(long, default_value_t = 1200, value_parser = crate::words::between::<u32>(1, 16384), allow_hyphen_values = true)]
    pub width: u32,
    /// Image height in pixels.
    #[arg(long, default_value_t = 800, value_parser = crate::words::between::<u32>(1, 16384), allow_hyphen_values = true)]
    pub height: u32,
    /// How far, in pixels, a drawn polyline may stray from its curve.
    #[arg(long, default_value_t = splinescope_gpu::adaptive::DEFAULT_TOLERANCE_PX, value_parser = parse_tolerance_px, allow_hyphen_values = true)]
    pub tolerance_px: f64,
    #[command(flatten)]
    pub text: TextArgs,
    #[command(flatten)]
    pub shape: ShapeArgs,
    #[command(flatten)]
    pub gpu: GpuArgs,
}

/// Runs `splinescope render`.
///
/// # Errors
/// A scene that does not load, a GPU failure, or a file that cannot be written.
pub fn run(a: &RenderArgs) -> Result<()> {
    render(
        a.scene.as_deref(),
        &a.output,
        (a.width, a.height),
        a.tolerance_px,
        (a.text, a.shape),
        &a.gpu,
    )
}

/// `render`: a scene (or the gallery) to a PNG.
fn render(
    scene: Option<&Path>,
    output: &Path,
    (width, height): (u32, u32),
    tolerance_px: f64,
    (text, shape): (TextArgs, ShapeArgs),
    gpu: &GpuArgs,
) -> Result<()> {
    let scene = load_scene_or_gallery(scene)?;
    let (ctx, pipelines) = gpu.context()?;
    let request = RenderRequest::new(width, height)
        .with_tolerance_px(tolerance_px)
        .with_shape(shape.options())
        .with_text(text.options());
    let image = splinescope_render::render(&ctx, &pipelines, &scene, &request)?;
    image.write_png(output)?;
    say!(
        "rendered {} curve(s) to {} ({width}×{height}, {})",
        scene.curves.len(),
        output.display(),
        ctx.describe()
    );
    Ok(())
}

fn load_scene_or_gallery(path: Option<&Path>) -> Result<Scene> {
    match path {
        None => Ok(gallery::gallery()),
        Some(p) => crate::load::scene(p),
    }
}
