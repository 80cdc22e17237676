//! `splinescope op`: operations that make curves from a scene's curves — approximation
//! by cubics or quadratics, knot removal, each within a tolerance (with a proven bound) —
//! written as a scene:
//! each result after its original, named after it and the operation, or in its place
//! with `--replace`.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};

use splinescope::geom::Curve;
use splinescope::num::Num;
use splinescope::ops::{Approximation, reduce_degree, remove_knot, to_cubics, to_quadratics};
use splinescope::scene::SceneCurve;

use crate::{say, select_curves};

/// The arguments of `splinescope op`.
#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("operation").required(true).args(["to_cubics", "to_quadratics", "reduce_degree", "remove_knot"])))]
pub struct OpArgs {
    /// Scene file (JSON), or a file splinescope imports.
    pub scene: PathBuf,
    /// Only this curve (index in the scene); every curve otherwise.
    #[arg(long, allow_hyphen_values = true)]
    pub curve: Option<usize>,
    /// Each curve as a path of cubic segments within this tolerance (scene units; the
    /// Hausdorff distance, a proven bound).
    #[arg(long, value_name = "T", value_parser = crate::words::number("tolerance", true), allow_hyphen_values = true)]
    pub to_cubics: Option<f64>,
    /// Each curve as a path of quadratic segments within this tolerance.
    #[arg(long, value_name = "T", value_parser = crate::words::number("tolerance", true), allow_hyphen_values = true)]
    pub to_quadratics: Option<f64>,
    /// Each Bézier curve at the lowest degree within this tolerance (its ends kept; a
    /// proven bound).
    #[arg(long, value_name = "T", value_parser = crate::words::number("tolerance", true), allow_hyphen_values = true)]
    pub reduce_degree: Option<f64>,
    /// Each curve (B-spline or NURBS) with the knot U removed (`--times` times) when it
    /// moves by at most `--tolerance` (a proven bound; else refused naming the bound).
    #[arg(long, value_name = "U", allow_hyphen_values = true)]
    pub remove_knot: Option<f64>,
    /// How many times to remove the knot.
    #[arg(long, default_value_t = 1, requires = "remove_knot")]
    pub times: usize,
    /// How far `--remove-knot` may move the curve (scene units; 0: only where it does not
    /// move, up to rounding).
    #[arg(long, default_value_t = 0.0, requires = "remove_knot", value_parser = crate::words::number("tolerance", false), allow_hyphen_values = true)]
    pub tolerance: f64,
    /// Put each result in its original's place (by default it is added after it).
    #[arg(long)]
    pub replace: bool,
    /// Where to write the scene (JSON); replaced atomically.
    #[arg(short, long, value_name = "OUT.json")]
    pub output: PathBuf,
}

/// Runs `splinescope op`.
///
/// # Errors
/// A scene that does not load, a curve index out of range, an operation that cannot be
/// done on a curve (naming it), the output being the input, or a write that fails.
pub fn run(a: &OpArgs) -> Result<()> {
    if splinescope::files::resolved(&a.scene) == splinescope::files::resolved(&a.output) {
        bail!(
            "{}: the output is the scene being read; write the result to another file",
            a.output.display()
        );
    }
    let mut scene = crate::load::scene(&a.scene)?;
    let indices = select_curves(&scene, a.curve)?;
    let (what, tolerance) = match (a.to_cubics, a.to_quadratics, a.reduce_degree, a.remove_knot) {
        (Some(t), ..) => ("to cubics".to_owned(), t),
        (_, Some(t), ..) => ("to quadratics".to_owned(), t),
        (_, _, Some(t), _) => ("degree reduced".to_owned(), t),
        (.., Some(u)) => (format!("knot {} removed", Num(u)), a.tolerance),
        _ => unreachable!("clap requires one operation"),
    };
    let mut made: Vec<(usize, SceneCurve, f64)> = Vec::with_capacity(indices.len());
    for &i in &indices {
        let sc = &scene.curves[i];
        let (curve, error) = if a.reduce_degree.is_some() {
            let Curve::Bezier(b) = &sc.curve else {
                bail!(
                    "curves[{i}]: --reduce-degree is for Bézier curves, not {} curves (--to-cubics approximates any curve)",
                    sc.curve.family()
                );
            };
            let r = reduce_degree(b, tolerance)
                .with_context(|| format!("curves[{i}]: --reduce-degree"))?;
            (Curve::Bezier(r.curve), r.error)
        } else if let Some(u) = a.remove_knot {
            let r = remove_knot(&sc.curve, u, a.times, a.tolerance)
                .with_context(|| format!("curves[{i}]: --remove-knot {}", Num(u)))?;
            (r.curve, r.error)
        } else {
            let op = if a.to_cubics.is_some() {
                to_cubics
            } else {
                to_quadratics
            };
            let Approximation { path, error } = op(&sc.curve, tolerance)
                .with_context(|| format!("curves[{i}]: --{}", what.replace(' ', "-")))?;
            (Curve::Path(path), error)
        };
        let base = sc
            .name
            .clone()
            .unwrap_or_else(|| format!("{} {i}", sc.curve.family()));
        let mut style = sc.style.clone();
        style.show_polygon = a.remove_knot.is_some() && style.show_polygon;
        let name = if a.remove_knot.is_some() || a.reduce_degree.is_some() {
            format!("{base} · {what}")
        } else {
            format!("{base} · {what} {}", Num(tolerance))
        };
        made.push((
            i,
            SceneCurve {
                name: Some(name),
                curve,
                style,
            },
            error,
        ));
    }
    // Results in place or after their originals, from the last so indices hold.
    for (i, curve, _) in made.iter().rev() {
        if a.replace {
            scene.curves[*i] = curve.clone();
        } else {
            scene.curves.insert(i + 1, curve.clone());
        }
    }
    splinescope::limits::CURVES
        .check(scene.curves.len() as u64)
        .map_err(|e| anyhow::anyhow!("{}: {e}", a.output.display()))?;
    let text = splinescope::scene::to_json_string(&scene);
    splinescope::files::write_atomic(&a.output, text.as_bytes())
        .with_context(|| format!("{}: cannot write the scene", a.output.display()))?;
    for (i, curve, error) in &made {
        let parts = match &curve.curve {
            Curve::Path(p) => format!("{} segment(s)", p.segments().len()),
            other => format!("{} control points", other.control_points().len()),
        };
        say!(
            "curves[{i}] {what}: {parts}, within {error:.3e} (tolerance {})",
            Num(tolerance)
        );
    }
    say!(
        "{} curve(s) written to {}",
        scene.curves.len(),
        a.output.display()
    );
    Ok(())
}
