//! `splinescope solve`: apply solve requests (docs/solve-format.md) to a scene.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use crate::say;

/// The arguments of `splinescope solve`.
#[derive(Debug, clap::Args)]
pub struct SolveArgs {
    /// Scene file (JSON), or an SVG file read as path curves.
    pub scene: PathBuf,
    /// Request file (JSON): one request or an array of them, applied in order.
    pub request: PathBuf,
    /// Where to write the modified scene (written atomically; nothing on error).
    #[arg(short, long, value_name = "SCENE")]
    pub output: Option<PathBuf>,
    /// Also write the report to this file.
    #[arg(long, value_name = "JSON")]
    pub report: Option<PathBuf>,
}

/// Runs `splinescope solve`.
///
/// # Errors
/// A scene or request that does not load, a solve that fails, an output not written.
pub fn run(a: &SolveArgs) -> Result<()> {
    solve(
        &a.scene,
        &a.request,
        a.output.as_deref(),
        a.report.as_deref(),
    )
}

fn solve(path: &Path, request: &Path, output: Option<&Path>, report: Option<&Path>) -> Result<()> {
    let scene = crate::load::scene(path)?;
    let text = splinescope_io::limits::read_bounded(request)
        .with_context(|| format!("{}: cannot read the request", request.display()))?;
    let outcome = splinescope_scene::request::apply_text(&scene, &text)
        .with_context(|| format!("{}", request.display()))?;
    let solved = splinescope_scene::request::types::SolveOutput {
        reports: outcome.reports,
    };
    let text = splinescope_scene::format::pretty_json(&serde_json::to_value(&solved)?);
    // The scene and the report are written all or none.
    let scene_text = splinescope_scene::format::to_json_string(&outcome.scene);
    if let Some(out) = output {
        // The scene written must be one that `check` passes: it reads back, and the GPU
        // can draw it (a target far beyond f32 would put an annotation there).
        let name = out.display().to_string();
        let reread = splinescope_scene::format::from_json_str(&scene_text).with_context(|| {
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
    splinescope_io::files::write_all_atomic(&files).context("nothing was written")?;
    say!("{text}");
    Ok(())
}
