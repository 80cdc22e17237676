//! `splinescope diff`: compare two PNG images (per-channel and NVIDIA FLIP).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use crate::{parse_tolerance, say};

/// The arguments of `splinescope diff`.
#[derive(Debug, clap::Args)]
pub struct DiffArgs {
    /// The image under test.
    pub actual: PathBuf,
    /// The reference image.
    pub reference: PathBuf,
    /// Write the diff image (differing pixels in red over a grey reference).
    #[arg(short, long, value_name = "PNG")]
    pub output: Option<PathBuf>,
    /// Write FLIP's error map as a heat map.
    #[arg(long, value_name = "PNG")]
    pub flip_map: Option<PathBuf>,
    /// As for `regress`.
    #[arg(long, default_value = "channel=24,pixels=0.1%", value_parser = parse_tolerance, allow_hyphen_values = true)]
    pub tolerance: splinescope_image::compare::Tolerance,
    /// Print the figures as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Runs `splinescope diff`.
///
/// # Errors
/// An image that cannot be read, sizes that differ, or images that differ beyond the
/// tolerance.
pub fn run(a: &DiffArgs) -> Result<()> {
    diff(
        &a.actual,
        &a.reference,
        a.output.as_deref(),
        a.flip_map.as_deref(),
        &a.tolerance,
        a.json,
    )
}

fn diff(
    actual: &Path,
    reference: &Path,
    output: Option<&Path>,
    flip_map: Option<&Path>,
    tolerance: &splinescope_image::compare::Tolerance,
    json: bool,
) -> Result<()> {
    use splinescope_image::RgbaImage;
    use splinescope_image::compare::compare_images;
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
    splinescope_io::files::write_all_atomic(&borrowed).context("nothing was written")?;
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
