//! `splinescope analyze`: the questions a curve answers — length, tight box, extrema,
//! inflections, cusps, curvature extrema, signed area — and, with `--intersections`,
//! every intersecting pair and each curve's self-intersections; text or JSON.

use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result};

use splinescope::analysis::CurveAnalysis;
use splinescope::analysis::report::{
    AnalyzeOutput, CurveAnalysisReport, IntersectionsReport, curve_analysis_report, pair_reports,
};
use splinescope::num::Num;
use splinescope::scene::Scene;

use crate::{say, select_curves};

/// The arguments of `splinescope analyze`.
#[derive(Debug, clap::Args)]
pub struct AnalyzeArgs {
    /// Scene file (JSON).
    pub scene: PathBuf,
    /// Only this curve (index in the scene).
    #[arg(long, allow_hyphen_values = true)]
    pub curve: Option<usize>,
    /// Also every intersecting pair of curves and each curve's self-intersections
    /// (planar curves).
    #[arg(long)]
    pub intersections: bool,
    /// Absolute accuracy of arc lengths, in scene units.
    #[arg(long, default_value_t = splinescope::analysis::DEFAULT_ACCURACY, value_parser = parse_accuracy, allow_hyphen_values = true)]
    pub accuracy: f64,
    /// Print JSON (docs/schemas/analyze.schema.json) instead of text.
    #[arg(long)]
    pub json: bool,
}

/// An accuracy: a finite number greater than 0.
fn parse_accuracy(s: &str) -> Result<f64, String> {
    let v: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("{s:?} is not a number"))?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(format!(
            "accuracy {}: must be a finite number greater than 0",
            Num(v)
        ))
    }
}

/// Runs `splinescope analyze`.
///
/// # Errors
/// A scene that does not load, a curve index out of range, or intersections asked of 3D
/// curves.
pub fn run(a: &AnalyzeArgs) -> Result<()> {
    let scene = Scene::load(&a.scene).with_context(|| format!("{}", a.scene.display()))?;
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
        curves.push(
            curve_analysis_report(
                i,
                sc.curve.family(),
                sc.name.as_deref(),
                c,
                a.accuracy,
                a.intersections,
            )
            .with_context(|| format!("curves[{i}]"))?,
        );
    }
    let (intersections, copies) = if a.intersections {
        let (pairs, copies) = pair_reports(&indices, &analyses)?;
        (Some(pairs), Some(copies))
    } else {
        (None, None)
    };
    let out = AnalyzeOutput {
        accuracy: a.accuracy,
        curves,
        intersections,
        copies,
    };
    if a.json {
        let value = serde_json::to_value(&out)?;
        say!("{}", splinescope::scene::pretty_json(&value));
    } else {
        say!("{}", text(&out));
    }
    Ok(())
}

fn point(p: [f64; 3], planar: bool) -> String {
    if planar {
        format!("({}, {})", Num(p[0]), Num(p[1]))
    } else {
        format!("({}, {}, {})", Num(p[0]), Num(p[1]), Num(p[2]))
    }
}

fn list(items: &[String]) -> String {
    if items.is_empty() {
        "none".to_owned()
    } else {
        items.join("; ")
    }
}

fn hits(found: &IntersectionsReport) -> String {
    let mut parts: Vec<String> = found
        .points
        .iter()
        .map(|h| {
            format!(
                "{} at (s, t) = ({}, {}) {}",
                h.kind,
                Num(h.s),
                Num(h.t),
                point(h.point, true)
            )
        })
        .collect();
    parts.extend(found.overlaps.iter().map(|o| {
        format!(
            "overlap s ∈ [{}, {}] with t ∈ [{}, {}]",
            Num(o.s[0]),
            Num(o.s[1]),
            Num(o.t[0]),
            Num(o.t[1])
        )
    }));
    list(&parts)
}

fn curve_text(out: &mut String, c: &CurveAnalysisReport) {
    let planar = c.dimension == 2;
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
        Num(c.length),
        c.length_error
    );
    let _ = writeln!(
        out,
        "  bounding box    {} – {}",
        point(c.bounding_box.min, planar),
        point(c.bounding_box.max, planar)
    );
    let extrema: Vec<String> = c
        .extrema
        .iter()
        .map(|e| format!("{} at t = {}", e.axis, Num(e.t)))
        .collect();
    let _ = writeln!(out, "  extrema         {}", list(&extrema));
    if let Some(area) = c.signed_area {
        let _ = writeln!(out, "  closed, signed area {}", Num(area));
    }
    let at = |items: &Option<Vec<splinescope::analysis::report::PointReport>>| -> Option<String> {
        items.as_ref().map(|v| {
            list(
                &v.iter()
                    .map(|p| format!("t = {} {}", Num(p.t), point(p.point, planar)))
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
                    "{} |κ| = {} turning {} at t = {}",
                    e.kind,
                    Num(e.abs_curvature),
                    e.side,
                    Num(e.t)
                )
            })
            .collect();
        let _ = writeln!(out, "  curvature       {}", list(&items));
    }
    if let Some(s) = &c.self_intersections {
        let _ = writeln!(out, "  self            {}", hits(s));
    }
}

/// The report as text for people.
fn text(out: &AnalyzeOutput) -> String {
    let mut s = String::new();
    for c in &out.curves {
        curve_text(&mut s, c);
    }
    if let Some(pairs) = &out.intersections {
        let _ = writeln!(s, "intersections ({} pair(s))", pairs.len());
        for p in pairs {
            let _ = writeln!(
                s,
                "  curves[{}] × curves[{}]: {}",
                p.curves[0],
                p.curves[1],
                hits(&p.found)
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
