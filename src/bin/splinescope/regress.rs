//! `splinescope regress`: render every scene of a directory and compare it with its reference image.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Result, bail};

use crate::{GpuArgs, parse_tolerance, say};

/// The arguments of `splinescope regress`.
#[derive(Debug, clap::Args)]
pub struct RegressArgs {
    /// Directory of scene files.
    pub scenes: PathBuf,
    /// Directory of reference images (created by --bless).
    pub refs: PathBuf,
    /// Write missing and changed references instead of failing on them.
    #[arg(long)]
    pub bless: bool,
    /// Render width in pixels.
    #[arg(long, default_value_t = 640, value_parser = crate::words::between::<u32>(1, 16384), allow_hyphen_values = true)]
    pub width: u32,
    /// Render height in pixels.
    #[arg(long, default_value_t = 480, value_parser = crate::words::between::<u32>(1, 16384), allow_hyphen_values = true)]
    pub height: u32,
    /// When images match: channel=N (largest per-channel difference that does not
    /// count), pixels=P% (largest share of differing pixels), flip=F (largest FLIP mean;
    /// unset: reported, not gated).
    #[arg(long, default_value = "channel=24,pixels=0.1%", value_parser = parse_tolerance, allow_hyphen_values = true)]
    pub tolerance: splinescope_image::compare::Tolerance,
    /// Write an HTML report with the actual, reference, diff and FLIP images here.
    #[arg(long, value_name = "OUT_DIR")]
    pub report: Option<PathBuf>,
    /// Print the results as JSON.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub gpu: GpuArgs,
}

/// Runs `splinescope regress`.
///
/// # Errors
/// Unusable directories, a GPU failure, or any scene that differs, is missing or fails.
pub fn run(a: &RegressArgs) -> Result<()> {
    regress(
        &a.scenes,
        &a.refs,
        &splinescope::regress::RegressOptions {
            width: a.width,
            height: a.height,
            tolerance: a.tolerance,
            bless: a.bless,
            report: a.report.clone(),
        },
        a.json,
        &a.gpu,
    )
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
    let (ctx, pipelines) = gpu.context()?;
    let report = splinescope::regress::run(&ctx, &pipelines, scenes, refs, opts)?;
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
