//! `splinescope op`: operations that make curves from a scene's curves — offsets and
//! stroke outlines, approximation by cubics or quadratics, degree reduction, knot removal, each within a tolerance (with a proven bound) —
//! written as a scene:
//! each result after its original, named after it and the operation, or in its place
//! with `--replace`.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};

use splinescope_core::geom::Curve;
use splinescope_core::num::Num;
use splinescope_core::ops::{
    Approximation, Cap, Join, OffsetOptions, offset, reduce_degree, remove_knot, to_cubics,
    to_quadratics,
};
use splinescope_scene::format::SceneCurve;

use crate::{say, select_curves};

/// The arguments of `splinescope op`.
#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("operation").required(true).args(["offset", "to_cubics", "to_quadratics", "reduce_degree", "remove_knot"])))]
pub struct OpArgs {
    /// Scene file (JSON), or a file splinescope imports.
    pub scene: PathBuf,
    /// Only this curve (index in the scene); every curve otherwise.
    #[arg(long, allow_hyphen_values = true)]
    pub curve: Option<usize>,
    /// Each curve's offset by D (scene units; D > 0 to the left of the direction of travel
    /// in y-up coordinates, which is the right on screen in y-down ones): a path of cubic
    /// segments within `--tolerance` of the true offset (the Hausdorff distance, a proven
    /// bound), with cusps where D passes the radius of curvature.
    #[arg(long, value_name = "D", allow_hyphen_values = true)]
    pub offset: Option<f64>,
    /// The join at kinks of an offset: round, miter or bevel.
    #[arg(long, value_enum, default_value = "round", requires = "offset")]
    pub join: JoinArg,
    /// How far a miter may reach, as a multiple of |D| (beyond it the join is bevelled).
    #[arg(long, default_value_t = 4.0, requires = "offset", value_parser = crate::words::number("miter limit", true))]
    pub miter_limit: f64,
    /// The outline of a stroke of half width |D| instead of one offset, its open ends
    /// closed by these caps: butt, round or square.
    #[arg(long, value_enum, requires = "offset")]
    pub caps: Option<CapArg>,
    /// Remove the loops of the offset (the parts closer to the curve than |D|).
    #[arg(long, requires = "offset", conflicts_with = "caps")]
    pub trim: bool,
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
    /// Each curve (B-spline, NURBS or standard NUBMP) with the knot U removed (`--times` times) when it
    /// moves by at most `--tolerance` (a proven bound; else refused naming the bound).
    #[arg(long, value_name = "U", allow_hyphen_values = true)]
    pub remove_knot: Option<f64>,
    /// How many times to remove the knot.
    #[arg(long, default_value_t = 1, requires = "remove_knot")]
    pub times: usize,
    /// How far `--remove-knot` may move the curve (scene units; 0, the default: only where
    /// it does not move, up to rounding), or how close `--offset`'s result is to the true
    /// offset (required there, greater than 0).
    #[arg(long, value_parser = crate::words::number("tolerance", false), allow_hyphen_values = true)]
    pub tolerance: Option<f64>,
    /// Put each result in its original's place (by default it is added after it).
    #[arg(long)]
    pub replace: bool,
    /// Where to write the scene (JSON); replaced atomically.
    #[arg(short, long, value_name = "OUT.json")]
    pub output: PathBuf,
}

/// A join, as the command line names it.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum JoinArg {
    /// A circular arc.
    Round,
    /// The sides extended (bevelled past `--miter-limit`).
    Miter,
    /// A straight line.
    Bevel,
}

/// A cap, as the command line names it.
#[derive(Debug, Clone, Copy, clap::ValueEnum)]
pub enum CapArg {
    /// A line across the end.
    Butt,
    /// A half circle.
    Round,
    /// The sides extended by the half width.
    Square,
}

/// Runs `splinescope op`.
///
/// # Errors
/// A scene that does not load, a curve index out of range, an operation that cannot be
/// done on a curve (naming it), the output being the input, or a write that fails.
pub fn run(a: &OpArgs) -> Result<()> {
    if splinescope_io::files::resolved(&a.scene) == splinescope_io::files::resolved(&a.output) {
        bail!(
            "{}: the output is the scene being read; write the result to another file",
            a.output.display()
        );
    }
    let mut scene = crate::load::scene(&a.scene)?;
    let indices = select_curves(&scene, a.curve)?;
    if a.tolerance.is_some() && a.remove_knot.is_none() && a.offset.is_none() {
        bail!(
            "--tolerance is for --offset and --remove-knot; the other operations take theirs as their value"
        );
    }
    let knot_tolerance = a.tolerance.unwrap_or(0.0);
    let (what, tolerance) = match (
        a.offset,
        a.to_cubics,
        a.to_quadratics,
        a.reduce_degree,
        a.remove_knot,
    ) {
        (Some(d), ..) => {
            let t = a.tolerance.filter(|&t| t > 0.0).ok_or_else(|| {
                anyhow::anyhow!("--offset {} needs --tolerance T greater than 0 (how close to the true offset, scene units)", Num(d))
            })?;
            let kind = if a.caps.is_some() {
                "stroke outline"
            } else {
                "offset"
            };
            (format!("{kind} {}", Num(d)), t)
        }
        (_, Some(t), ..) => ("to cubics".to_owned(), t),
        (_, _, Some(t), ..) => ("to quadratics".to_owned(), t),
        (_, _, _, Some(t), _) => ("degree reduced".to_owned(), t),
        (.., Some(u)) => (format!("knot {} removed", Num(u)), knot_tolerance),
        _ => unreachable!("clap requires one operation"),
    };
    let mut made: Vec<(usize, SceneCurve, f64)> = Vec::with_capacity(indices.len());
    for &i in &indices {
        let sc = &scene.curves[i];
        if let Some(d) = a.offset {
            let options = OffsetOptions {
                join: match a.join {
                    JoinArg::Round => Join::Round,
                    JoinArg::Miter => Join::Miter,
                    JoinArg::Bevel => Join::Bevel,
                },
                miter_limit: a.miter_limit,
                caps: a.caps.map(|c| match c {
                    CapArg::Butt => Cap::Butt,
                    CapArg::Round => Cap::Round,
                    CapArg::Square => Cap::Square,
                }),
                trim: a.trim,
            };
            let o = offset(&sc.curve, d, tolerance, &options)
                .with_context(|| format!("curves[{i}]: --offset {}", Num(d)))?;
            let base = sc
                .name
                .clone()
                .unwrap_or_else(|| format!("{} {i}", sc.curve.family()));
            let mut style = sc.style.clone();
            style.show_polygon = false;
            let count = o.paths.len();
            for (k, path) in o.paths.into_iter().enumerate() {
                let name = if count == 1 {
                    format!("{base} · {what}")
                } else {
                    format!("{base} · {what} ({} of {count})", k + 1)
                };
                made.push((
                    i,
                    SceneCurve {
                        name: Some(name),
                        curve: Curve::Path(path),
                        style: style.clone(),
                    },
                    o.error,
                ));
            }
            continue;
        }
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
            let r = remove_knot(&sc.curve, u, a.times, knot_tolerance)
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
    // Results in place or after their originals, from the last so indices hold (an
    // original with several results: all of them, in order, in its place or after it).
    let mut k = made.len();
    while k > 0 {
        let i = made[k - 1].0;
        let mut first = k - 1;
        while first > 0 && made[first - 1].0 == i {
            first -= 1;
        }
        let group: Vec<SceneCurve> = made[first..k].iter().map(|m| m.1.clone()).collect();
        let at = if a.replace {
            scene.curves.remove(i);
            i
        } else {
            i + 1
        };
        for (j, c) in group.into_iter().enumerate() {
            scene.curves.insert(at + j, c);
        }
        k = first;
    }
    splinescope_io::limits::CURVES
        .check(scene.curves.len() as u64)
        .map_err(|e| anyhow::anyhow!("{}: {e}", a.output.display()))?;
    let text = splinescope_scene::format::to_json_string(&scene);
    splinescope_io::files::write_atomic(&a.output, text.as_bytes())
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
