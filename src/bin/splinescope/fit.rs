//! `splinescope fit`: points (CSV or JSON) fitted by a curve, written as a scene — a
//! B-spline with a smoothing budget (`--smoothing`, 0 through every point), or a path of
//! cubics within a tolerance of every point with its corners kept (`--tolerance`).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use glam::DVec3;

use splinescope_core::geom::Curve;
use splinescope_core::num::Num;
use splinescope_core::ops::{Params, fit_bspline, fit_path};
use splinescope_scene::format::{Scene, SceneCurve, Style};

use crate::say;

/// The arguments of `splinescope fit`.
#[derive(Debug, clap::Args)]
pub struct FitArgs {
    /// The points: CSV (`x,y` or `x,y,z` per line; a first line of names is skipped) or
    /// JSON (`[[x, y], …]`).
    pub points: PathBuf,
    /// Where to write the scene (JSON); replaced atomically.
    #[arg(short, long, value_name = "SCENE.json")]
    pub output: PathBuf,
    /// The B-spline's degree.
    #[arg(long, default_value_t = 3)]
    pub degree: usize,
    /// A B-spline whose sum of squared residuals is at most S (scipy's `s`; 0: through
    /// every point). The default, with 0, when neither this nor --tolerance is given.
    #[arg(
        long,
        value_name = "S",
        conflicts_with = "tolerance",
        allow_hyphen_values = true
    )]
    pub smoothing: Option<f64>,
    /// A path of cubics within T of every point, corners kept (a noise-free polyline).
    #[arg(long, value_name = "T", allow_hyphen_values = true)]
    pub tolerance: Option<f64>,
    /// With --tolerance: turns sharper than this many degrees are corners.
    #[arg(
        long,
        default_value_t = 30.0,
        requires = "tolerance",
        allow_hyphen_values = true
    )]
    pub corner_angle: f64,
}

/// The points of a CSV or JSON file, each error naming the file and the line.
fn read_points(path: &Path) -> Result<Vec<DVec3>> {
    let text = splinescope_io::limits::read_bounded(path)
        .with_context(|| format!("{}", path.display()))?;
    let is_json = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    let mut out = Vec::new();
    let max = splinescope_io::limits::POINTS
        .value()
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    if is_json {
        let v: Vec<Vec<f64>> = serde_json::from_str(&text).with_context(|| {
            format!(
                "{}: not a JSON array of points ([[x, y], …])",
                path.display()
            )
        })?;
        for (i, p) in v.iter().enumerate() {
            if !(2..=3).contains(&p.len()) {
                bail!(
                    "{}: point {i} has {} coordinates (2 or 3)",
                    path.display(),
                    p.len()
                );
            }
            out.push(DVec3::new(p[0], p[1], p.get(2).copied().unwrap_or(0.0)));
        }
    } else {
        for (n, line) in text.lines().enumerate() {
            let line = line.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let fields: Vec<&str> = line
                .split([',', ';', '\t', ' '])
                .filter(|s| !s.is_empty())
                .collect();
            let nums: Result<Vec<f64>, _> = fields.iter().map(|s| s.parse::<f64>()).collect();
            let Ok(nums) = nums else {
                if out.is_empty() && n == 0 {
                    continue; // a header
                }
                bail!(
                    "{}:{}: {line:?} is not two or three numbers",
                    path.display(),
                    n + 1
                );
            };
            if !(2..=3).contains(&nums.len()) {
                bail!(
                    "{}:{}: {} numbers (x,y or x,y,z)",
                    path.display(),
                    n + 1,
                    nums.len()
                );
            }
            out.push(DVec3::new(
                nums[0],
                nums[1],
                nums.get(2).copied().unwrap_or(0.0),
            ));
            if out.len() as u64 > max {
                bail!(
                    "{}:{}: more than {max} points (SPLINESCOPE_MAX_POINTS)",
                    path.display(),
                    n + 1
                );
            }
        }
    }
    if out.len() as u64 > max {
        bail!(
            "{}: {} points, over the limit of {max} (SPLINESCOPE_MAX_POINTS)",
            path.display(),
            out.len()
        );
    }
    Ok(out)
}

/// Runs `splinescope fit`.
///
/// # Errors
/// Points that do not read (naming the file and line), a fit that cannot be made (naming
/// why), or a write that fails.
pub fn run(a: &FitArgs) -> Result<()> {
    let points = read_points(&a.points)?;
    let name = a
        .points
        .file_name()
        .map_or_else(|| "points".to_owned(), |n| n.to_string_lossy().into_owned());
    let (curve, residuals, what) = if let Some(t) = a.tolerance {
        let fit = fit_path(&points, t, a.corner_angle)
            .with_context(|| format!("{}: --tolerance", a.points.display()))?;
        let k = fit.curve.segments().len();
        (
            Curve::Path(fit.curve),
            fit.residuals,
            format!("{k} cubic(s) within {}", Num(t)),
        )
    } else {
        let s = a.smoothing.unwrap_or(0.0);
        let fit = fit_bspline(&points, a.degree, None, Some(s), &Params::Chord, None)
            .with_context(|| format!("{}: --smoothing", a.points.display()))?;
        let knots = fit.curve.knots().knots().len() - 2 * (a.degree + 1);
        (
            Curve::BSpline(fit.curve),
            fit.residuals,
            format!(
                "B-spline of degree {}, {knots} interior knot(s), smoothing {}",
                a.degree,
                Num(s)
            ),
        )
    };
    let mut style = Style::default_for(0);
    style.show_points = false;
    let scene = Scene {
        name: Some(format!("{name} fitted")),
        curves: vec![SceneCurve {
            name: Some(format!("{name} · {what}")),
            curve,
            style,
        }],
        unit: None,
        background: splinescope_encoding::Color::WHITE,
        samples_per_segment: None,
        view: splinescope_scene::format::ViewSpec::Auto,
        annotations: Vec::new(),
    };
    let text = splinescope_scene::format::to_json_string(&scene);
    splinescope_io::files::write_atomic(&a.output, text.as_bytes())
        .with_context(|| format!("{}: cannot write the scene", a.output.display()))?;
    let worst = residuals.iter().copied().fold(0.0, f64::max);
    let rss: f64 = residuals.iter().map(|r| r * r).sum();
    say!(
        "{}: {} points, {what}; largest residual {worst:.3e}, sum of squares {rss:.4e}; written to {}",
        a.points.display(),
        points.len(),
        a.output.display()
    );
    Ok(())
}
