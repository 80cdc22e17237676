//! `splinescope check`: validate a scene and summarise it (families, segments, GPU compatibility).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Result, bail};

use splinescope_core::num::Num;

use crate::say;

/// The arguments of `splinescope check`.
#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// Scene file (JSON), or an SVG file read as path curves.
    pub scene: PathBuf,
    /// Print the description as JSON (docs/schemas/check.schema.json).
    #[arg(long)]
    pub json: bool,
}

/// Runs `splinescope check`.
///
/// # Errors
/// A scene that does not load, or one the GPU cannot draw.
pub fn run(a: &CheckArgs) -> Result<()> {
    check(&a.scene, a.json)
}

fn check(path: &Path, json: bool) -> Result<()> {
    let scene = crate::load::scene(path)?;
    let report = splinescope::outputs::CheckOutput::of(&path.display().to_string(), &scene);
    if json {
        say!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        say!(
            "{}: valid scene, {} curve(s){}{}",
            path.display(),
            report.curves.len(),
            report
                .name
                .as_ref()
                .map(|n| format!(" ({n})"))
                .unwrap_or_default(),
            report
                .unit
                .as_ref()
                .map(|u| format!(", lengths in {u}"))
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
