//! `splinescope inspect`: each curve's derived data as JSON (docs/inspect-format.md).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use splinescope_core::geom::GeomError;
use splinescope_core::num::Num;

use crate::select_curves;

/// The arguments of `splinescope inspect`.
#[derive(Debug, clap::Args)]
pub struct InspectArgs {
    /// Scene file (JSON), or an SVG file read as path curves.
    pub scene: PathBuf,
    /// Only this curve (index in the scene).
    #[arg(long, allow_hyphen_values = true)]
    pub curve: Option<usize>,
    /// For B-splines and NUBMP curves, also report P(τ), the groups that act there and
    /// the region each lets P(τ) reach.
    #[arg(long, allow_hyphen_values = true)]
    pub tau: Option<f64>,
}

/// Runs `splinescope inspect`.
///
/// # Errors
/// A scene that does not load, or a derived value that overflows.
pub fn run(a: &InspectArgs) -> Result<()> {
    inspect(&a.scene, a.curve, a.tau)
}

fn inspect(path: &Path, only: Option<usize>, tau: Option<f64>) -> Result<()> {
    let scene = crate::load::scene(path)?;
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
        let mut report = splinescope_present::inspect::curve_report(i, c.name.as_deref(), &c.curve)
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
        let text = splinescope_scene::format::pretty_json(&report);
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
