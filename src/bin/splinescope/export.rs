//! `splinescope export`: a scene (default: the built-in gallery) as a figure — SVG or PDF
//! with exact curves (splinescope-figure), the PNG `render` draws, or DXF (every curve an
//! exact `SPLINE`).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use splinescope_scene::format::{Scene, gallery};

use crate::{GpuArgs, ShapeArgs, TextArgs, say};

/// The arguments of `splinescope export`.
#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// Scene file (JSON), or an SVG file read as path curves; omit for the built-in gallery.
    pub scene: Option<PathBuf>,
    /// Output: a figure (`.svg`, `.pdf`, `.png`) or the curves as DXF (`.dxf`: binary,
    /// every number exact, unless `--ascii`).
    #[arg(short, long, value_name = "FIG")]
    pub output: PathBuf,
    /// Width in points (pixels for a PNG).
    #[arg(long, default_value_t = 1200, value_parser = crate::words::between::<u32>(1, 16384), allow_hyphen_values = true)]
    pub width: u32,
    /// Height in points (pixels for a PNG).
    #[arg(long, default_value_t = 800, value_parser = crate::words::between::<u32>(1, 16384), allow_hyphen_values = true)]
    pub height: u32,
    /// Largest distance, in output points, between a written piece and the exact curve
    /// (segments of degree ≤ 3 in a 2D view are written exactly).
    #[arg(long, default_value_t = splinescope_figure::DEFAULT_TOLERANCE, value_parser = parse_tolerance, allow_hyphen_values = true)]
    pub tolerance: f64,
    /// The camera, instead of the scene's own view, as the scene format's `view` object
    /// (JSON): `{"kind": "2d", "center": [x, y], "height": h}` or `{"kind": "3d",
    /// "target": [x, y, z], "distance": d, "yaw_deg": …, "pitch_deg": …}`.
    #[arg(long, value_name = "JSON")]
    pub view: Option<String>,
    /// Write DXF as ASCII (the `dxf` crate writes numbers to 12 decimals, so a curve read
    /// back is not bit for bit the same) instead of binary.
    #[arg(long)]
    pub ascii: bool,
    #[command(flatten)]
    pub text: TextArgs,
    #[command(flatten)]
    pub shape: ShapeArgs,
    #[command(flatten)]
    pub gpu: GpuArgs,
}

/// A tolerance: a finite number of at least [`splinescope_figure::MIN_TOLERANCE`].
fn parse_tolerance(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("{s:?} is not a number"))?;
    splinescope_figure::check_tolerance(v).map_err(|e| e.to_string())
}

/// `scene` seen through `view` (the scene format's `view` object), checked as a scene
/// file's view is.
fn with_view(scene: &Scene, view: &str) -> Result<Scene> {
    let value: serde_json::Value =
        serde_json::from_str(view).with_context(|| format!("--view: {view:?} is not JSON"))?;
    let mut doc: serde_json::Value =
        serde_json::from_str(&splinescope_scene::format::to_json_string(scene))?;
    doc["view"] = value;
    splinescope_scene::format::from_json_str(&doc.to_string()).map_err(|e| {
        anyhow::anyhow!(
            "--view: {}",
            e.to_string()
                .replacen("view", "", 1)
                .trim_start_matches(['.', ':', ' '])
        )
    })
}

/// The figure formats, by the output's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Format {
    Svg,
    Pdf,
    Png,
    Dxf,
}

fn format_of(path: &Path) -> Result<Format> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("svg") => Ok(Format::Svg),
        Some("pdf") => Ok(Format::Pdf),
        Some("png") => Ok(Format::Png),
        Some("dxf") => Ok(Format::Dxf),
        other => bail!(
            "{}: unknown output format {} (expected .svg, .pdf, .png or .dxf)",
            path.display(),
            other.map_or_else(|| "(no extension)".to_owned(), |e| format!(".{e}"))
        ),
    }
}

/// Runs `splinescope export`.
///
/// # Errors
/// An unknown extension, a scene that does not load, a GPU failure (PNG), or a file that
/// cannot be written (nothing partial is left).
pub fn run(a: &ExportArgs) -> Result<()> {
    let format = format_of(&a.output)?;
    if a.ascii && format != Format::Dxf {
        bail!(
            "--ascii is for DXF output; {} is not a .dxf file",
            a.output.display()
        );
    }
    let mut scene = match &a.scene {
        None => gallery::gallery(),
        Some(p) => crate::load::scene(p)?,
    };
    if let Some(view) = &a.view {
        scene = with_view(&scene, view)?;
    }
    let bytes = match format {
        Format::Dxf if a.ascii => splinescope_import::dxf::write_ascii(&scene)?,
        Format::Dxf => splinescope_import::dxf::write(&scene)?,
        Format::Png => {
            let (ctx, pipelines) = a.gpu.context()?;
            let request = splinescope_render::RenderRequest::new(a.width, a.height)
                .with_shape(a.shape.options())
                .with_text(a.text.options());
            splinescope_render::render(&ctx, &pipelines, &scene, &request)?.png_bytes(&a.output)?
        }
        Format::Svg | Format::Pdf => {
            let mut opts = splinescope_figure::FigureOptions::new(a.width, a.height)
                .with_text(a.text.options());
            opts.tolerance = a.tolerance;
            opts.shape = a.shape.options();
            let fig = splinescope_figure::build(&scene, &opts)?;
            if format == Format::Svg {
                splinescope_figure::svg::write(&fig).into_bytes()
            } else {
                splinescope_figure::pdf::write(&fig)
            }
        }
    };
    splinescope_io::files::write_atomic(&a.output, &bytes)
        .with_context(|| format!("cannot write {}", a.output.display()))?;
    if format == Format::Dxf {
        say!(
            "exported {} curve(s) to {} as exact SPLINE entities ({} DXF)",
            scene.curves.len(),
            a.output.display(),
            if a.ascii { "ASCII" } else { "binary" }
        );
    } else {
        say!(
            "exported {} curve(s) to {} ({}×{})",
            scene.curves.len(),
            a.output.display(),
            a.width,
            a.height
        );
    }
    Ok(())
}
