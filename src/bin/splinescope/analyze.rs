//! `splinescope analyze`: the questions a curve answers — length, tight box, extrema,
//! inflections, cusps, curvature extrema, signed area — and, with `--intersections`,
//! every intersecting pair and each curve's self-intersections; text or JSON.

use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result};

use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::analysis::report::{
    AnalyzeOutput, CurveAnalysisReport, IntersectionsReport, NearestReport, curve_analysis_report,
    pair_reports,
};
use splinescope_core::num::{Num, shortest_within};

use crate::{say, select_curves};

/// The arguments of `splinescope analyze`.
#[derive(Debug, clap::Args)]
pub struct AnalyzeArgs {
    /// Scene file (JSON), or an SVG file read as path curves.
    pub scene: PathBuf,
    /// Only this curve (index in the scene).
    #[arg(long, allow_hyphen_values = true)]
    pub curve: Option<usize>,
    /// Also every intersecting pair of curves and each curve's self-intersections
    /// (planar curves).
    #[arg(long)]
    pub intersections: bool,
    /// Absolute accuracy of arc lengths, in scene units.
    #[arg(long, default_value_t = splinescope_core::analysis::DEFAULT_ACCURACY, value_parser = crate::words::number("accuracy", true), allow_hyphen_values = true)]
    pub accuracy: f64,
    /// Also each curve's point nearest to this one (`X,Y` or `X,Y,Z`): the global
    /// minimum of the distance, its parameter and a bound on the distance's error.
    #[arg(long, value_name = "X,Y[,Z]", value_parser = parse_point, allow_hyphen_values = true)]
    pub nearest: Option<glam::DVec3>,
    /// Print JSON (docs/schemas/analyze.schema.json) instead of text.
    #[arg(long)]
    pub json: bool,
}

/// A point: two or three finite numbers separated by commas.
fn parse_point(s: &str) -> Result<glam::DVec3, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    if !(2..=3).contains(&parts.len()) {
        return Err(format!(
            "{s:?}: a point is X,Y or X,Y,Z (two or three numbers separated by commas)"
        ));
    }
    let mut xyz = [0.0; 3];
    for (k, part) in parts.iter().enumerate() {
        let v: f64 = part
            .parse()
            .map_err(|_| format!("{s:?}: {part:?} is not a number"))?;
        if !v.is_finite() {
            return Err(format!("{s:?}: {part} is not a finite number"));
        }
        xyz[k] = v;
    }
    Ok(glam::DVec3::from_array(xyz))
}

/// Runs `splinescope analyze`.
///
/// # Errors
/// A scene that does not load, a curve index out of range, or intersections asked of 3D
/// curves.
pub fn run(a: &AnalyzeArgs) -> Result<()> {
    let scene = crate::load::scene(&a.scene)?;
    let indices = select_curves(&scene, a.curve)?;
    let analyses: Vec<CurveAnalysis> = indices
        .iter()
        .map(|&i| CurveAnalysis::new(&scene.curves[i].curve))
        .collect();
    if a.intersections
        && let Some(k) = analyses.iter().position(|c| !c.is_planar())
    {
        anyhow::bail!(
            "--intersections: curves[{}] is not planar (it leaves z = 0); intersections are computed for planar curves",
            indices[k]
        );
    }
    let mut curves = Vec::with_capacity(indices.len());
    for (&i, c) in indices.iter().zip(&analyses) {
        let sc = &scene.curves[i];
        let mut report = curve_analysis_report(
            i,
            sc.curve.family(),
            sc.name.as_deref(),
            c,
            a.accuracy,
            a.intersections,
        )
        .with_context(|| format!("curves[{i}]"))?;
        if let Some(p) = a.nearest {
            report.nearest =
                Some(NearestReport::of(c, p).with_context(|| format!("curves[{i}]: --nearest"))?);
        }
        curves.push(report);
    }
    let (intersections, copies) = if a.intersections {
        let (pairs, copies) = pair_reports(&indices, &analyses)?;
        (Some(pairs), Some(copies))
    } else {
        (None, None)
    };
    let out = AnalyzeOutput {
        unit: scene.unit.clone(),
        accuracy: a.accuracy,
        curves,
        intersections,
        copies,
    };
    if a.json {
        let value = serde_json::to_value(&out)?;
        say!("{}", splinescope_scene::format::pretty_json(&value));
    } else {
        say!("{}", text(&out));
    }
    Ok(())
}

/// How many digits the text shows: each value as the shortest decimal within what is
/// known of it — coordinates within `1e-12` of the curve's size (its box, or its largest
/// coordinate far from the origin), parameters within `1e-12` of the domain, `κ` within
/// `1e-12` of itself, lengths within their stated error — so rounding noise
/// (`-22.999999999999996`, `1.5e-15` for 0) is not shown. `--json` keeps every digit.
#[derive(Debug, Clone, Copy)]
struct Digits {
    /// The size coordinates are measured against.
    size: f64,
    /// The domain's width.
    domain: f64,
}

impl Digits {
    fn of(c: &CurveAnalysisReport) -> Digits {
        let (lo, hi) = (c.bounding_box.min, c.bounding_box.max);
        let diagonal = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
        let far = (0..3)
            .map(|k| lo[k].abs().max(hi[k].abs()))
            .fold(0.0, f64::max);
        Digits {
            size: diagonal.max(far),
            domain: c.domain[1] - c.domain[0],
        }
    }

    /// Two curves' coordinates and parameters at once (an intersection's).
    fn both(a: Digits, b: Digits) -> Digits {
        Digits {
            size: a.size.max(b.size),
            domain: a.domain.min(b.domain),
        }
    }

    fn coord(self, x: f64) -> String {
        shortest_within(x, 1e-12 * self.size)
    }

    fn param(self, t: f64) -> String {
        shortest_within(t, 1e-12 * self.domain)
    }

    fn point(self, p: [f64; 3], planar: bool) -> String {
        if planar {
            format!("({}, {})", self.coord(p[0]), self.coord(p[1]))
        } else {
            format!(
                "({}, {}, {})",
                self.coord(p[0]),
                self.coord(p[1]),
                self.coord(p[2])
            )
        }
    }
}

fn list(items: &[String]) -> String {
    if items.is_empty() {
        "none".to_owned()
    } else {
        items.join("; ")
    }
}

/// Points and overlaps; each point's parameters within their stated errors.
fn hits(found: &IntersectionsReport, d: Digits) -> String {
    let mut parts: Vec<String> = found
        .points
        .iter()
        .map(|h| {
            format!(
                "{} at (s, t) = ({}, {}) {}",
                h.kind,
                shortest_within(h.s, h.error_s.max(1e-12 * d.domain * f64::EPSILON)),
                shortest_within(h.t, h.error_t.max(1e-12 * d.domain * f64::EPSILON)),
                d.point(h.point, true)
            )
        })
        .collect();
    parts.extend(found.overlaps.iter().map(|o| {
        format!(
            "overlap s ∈ [{}, {}] with t ∈ [{}, {}]",
            d.param(o.s[0]),
            d.param(o.s[1]),
            d.param(o.t[0]),
            d.param(o.t[1])
        )
    }));
    list(&parts)
}

fn curve_text(out: &mut String, c: &CurveAnalysisReport) {
    let planar = c.dimension == 2;
    let d = Digits::of(c);
    let name = c
        .name
        .as_ref()
        .map(|n| format!(" {n:?}"))
        .unwrap_or_default();
    let _ = writeln!(
        out,
        "curves[{}]{name} ({}, {}D)",
        c.index, c.family, c.dimension
    );
    let _ = writeln!(
        out,
        "  length          {} (error ≤ {:.1e})",
        shortest_within(c.length, c.length_error),
        c.length_error
    );
    let _ = writeln!(
        out,
        "  bounding box    {} – {}",
        d.point(c.bounding_box.min, planar),
        d.point(c.bounding_box.max, planar)
    );
    let extrema: Vec<String> = c
        .extrema
        .iter()
        .map(|e| {
            format!(
                "{} at t = {} {}",
                e.axis,
                d.param(e.t),
                d.point(e.point, planar)
            )
        })
        .collect();
    let _ = writeln!(out, "  extrema         {}", list(&extrema));
    if let Some(area) = c.signed_area {
        let _ = writeln!(
            out,
            "  closed, signed area {}",
            shortest_within(area, 1e-12 * d.size * d.size)
        );
    }
    let at =
        |items: &Option<Vec<splinescope_core::analysis::report::PointReport>>| -> Option<String> {
            items.as_ref().map(|v| {
                list(
                    &v.iter()
                        .map(|p| format!("t = {} {}", d.param(p.t), d.point(p.point, planar)))
                        .collect::<Vec<_>>(),
                )
            })
        };
    if let Some(s) = at(&c.inflections) {
        let _ = writeln!(out, "  inflections     {s}");
    }
    if let Some(s) = at(&c.cusps) {
        let _ = writeln!(out, "  cusps           {s}");
    }
    if let Some(ex) = &c.curvature_extrema {
        let items: Vec<String> = ex
            .iter()
            .map(|e| {
                format!(
                    "{} |κ| = {} turning {} at t = {} {}",
                    e.kind,
                    shortest_within(e.abs_curvature, 1e-12 * e.abs_curvature),
                    e.side,
                    d.param(e.t),
                    d.point(e.point, planar)
                )
            })
            .collect();
        let _ = writeln!(out, "  curvature       {}", list(&items));
    }
    if let Some(s) = &c.self_intersections {
        let _ = writeln!(out, "  self            {}", hits(s, d));
    }
    if let Some(n) = &c.nearest {
        let _ = writeln!(
            out,
            "  nearest to {}  t = {} {}, distance {} (error ≤ {:.1e})",
            d.point(n.to, planar && n.to[2] == 0.0),
            d.param(n.t),
            d.point(n.point, planar),
            shortest_within(n.distance, n.error.max(1e-12 * d.size)),
            n.error
        );
    }
    if let Some(why) = &c.joints_refused {
        let _ = writeln!(out, "  joints          not measured: {why}");
    }
    let joints = c.joints.as_deref().unwrap_or_default();
    if !joints.is_empty() {
        let count = |class: &str| joints.iter().filter(|j| j.class == class).count();
        let mut summary: Vec<String> = ["G2", "G1", "G0", "gap"]
            .iter()
            .filter(|k| count(k) > 0)
            .map(|k| format!("{} {k}", count(k)))
            .collect();
        if summary.len() > 1 {
            summary.insert(0, format!("{} in all", joints.len()));
        }
        // The joints that are not G2, each with what breaks it.
        let items: Vec<String> = joints
            .iter()
            .filter(|j| j.class != "G2")
            .map(|j| {
                let what = match j.class {
                    "gap" => format!("gap {}", shortest_within(j.gap, 1e-12 * d.size)),
                    "G0" => format!("kink {}°", shortest_within(j.angle_deg, 1e-9)),
                    _ => match j.curvature_jump {
                        Some(k) => format!("curvature jump {} %", shortest_within(100.0 * k, 1e-6)),
                        None => "unbounded curvature".to_owned(),
                    },
                };
                format!(
                    "{} {what}{} at t = {} {}",
                    j.class,
                    if j.seam { " (seam)" } else { "" },
                    d.param(j.t),
                    d.point(j.point, planar)
                )
            })
            .collect();
        let _ = writeln!(
            out,
            "  joints          {}{}",
            summary.join(", "),
            if items.is_empty() {
                String::new()
            } else {
                format!(": {}", list(&items))
            }
        );
    }
}

/// The report as text for people.
fn text(out: &AnalyzeOutput) -> String {
    let mut s = String::new();
    if let Some(u) = &out.unit {
        let _ = writeln!(s, "lengths, coordinates and areas in {u}");
    }
    for c in &out.curves {
        curve_text(&mut s, c);
    }
    let digits = |i: usize| {
        out.curves.iter().find(|c| c.index == i).map_or(
            Digits {
                size: 1.0,
                domain: 1.0,
            },
            Digits::of,
        )
    };
    if let Some(pairs) = &out.intersections {
        let _ = writeln!(s, "intersections ({} pair(s))", pairs.len());
        for p in pairs {
            let d = Digits::both(digits(p.curves[0]), digits(p.curves[1]));
            let _ = writeln!(
                s,
                "  curves[{}] × curves[{}]: {}",
                p.curves[0],
                p.curves[1],
                hits(&p.found, d)
            );
        }
    }
    if let Some(groups) = out.copies.as_ref().filter(|g| !g.is_empty()) {
        let _ = writeln!(
            s,
            "copies ({} group(s) of curves that coincide entirely)",
            groups.len()
        );
        for g in groups {
            let names: Vec<String> = g.curves.iter().map(|i| format!("curves[{i}]")).collect();
            let _ = writeln!(
                s,
                "  {} over t ∈ [{}, {}]",
                names.join(", "),
                Num(g.t[0]),
                Num(g.t[1])
            );
        }
    }
    s.trim_end().to_owned()
}
