//! SVG output: one `<path>` per curve (its runs joined, `M` starting each), overlay
//! polylines as paths, points as circles, styled as the renderer draws them (round caps
//! and joins, dashes of half the period on). Exact commands carry their control points
//! as the shortest decimals that read back as the same `f64`; approximated pieces are
//! rounded to the coarsest decimal step that keeps them within the tolerance.

use std::fmt::Write as _;

use splinescope_core::num::trim_zeros as trim;

use super::fit::{Piece, Seg};
use super::{Anchor, Figure, Item, SubPath, hex};
use splinescope_core::ops::{Cap, Join};
use splinescope_encoding::StrokeShape;

/// The decimal step approximated pieces are rounded to: the largest power of ten at most
/// a quarter of the tolerance (a point moves at most `step/√2` by it).
#[must_use]
pub fn step(tolerance: f64) -> f64 {
    10f64.powf((tolerance / 4.0).log10().floor())
}

/// `x` in its shortest form: the round-trip decimal (`exact`), or rounded to `step`. A
/// number so large that rounding to `step` changes nothing (`|x / step| ≥ 2⁵²`, where
/// every `f64` is a whole number of steps) is written exactly; exact numbers take the
/// shorter of the plain and the exponent form (`1e300`, not 301 digits), both of which
/// SVG reads.
#[must_use]
pub fn number(x: f64, exact: bool, step: f64) -> String {
    let scaled = x / step;
    if exact || !scaled.is_finite() || scaled.abs() >= 4_503_599_627_370_496.0 {
        return trim(splinescope_core::num::Num(x).to_string());
    }
    let decimals = (-step.log10()).round().max(0.0) as usize;
    trim(format!("{:.*}", decimals, scaled.round() * step))
}

/// A path's `stroke-linecap`, `stroke-linejoin` and (for a miter join other than 4)
/// `stroke-miterlimit` attributes.
fn stroke_shape(shape: &StrokeShape) -> String {
    let cap = match shape.cap {
        Cap::Round => "round",
        Cap::Butt => "butt",
        Cap::Square => "square",
    };
    let join = match shape.join {
        Join::Round => "round",
        Join::Miter => "miter",
        Join::Bevel => "bevel",
    };
    let limit = if shape.join == Join::Miter && shape.miter_limit != 4.0 {
        format!(r#" stroke-miterlimit="{}""#, shape.miter_limit)
    } else {
        String::new()
    };
    format!(r#" stroke-linecap="{cap}" stroke-linejoin="{join}"{limit}"#)
}

/// The path data of `runs`.
#[must_use]
pub fn path_data(runs: &[SubPath], step: f64) -> String {
    let mut d = String::new();
    let pt = |d: &mut String, p: glam::DVec2, exact: bool| {
        let _ = write!(
            d,
            "{} {}",
            number(p.x, exact, step),
            number(p.y, exact, step)
        );
    };
    for run in runs {
        let first_exact = run.pieces.first().is_none_or(|p| p.exact);
        d.push('M');
        pt(&mut d, run.start, first_exact);
        for &Piece { seg, exact } in &run.pieces {
            match seg {
                Seg::Line(p) => {
                    d.push('L');
                    pt(&mut d, p, exact);
                }
                Seg::Quad(a, p) => {
                    d.push('Q');
                    pt(&mut d, a, exact);
                    d.push(' ');
                    pt(&mut d, p, exact);
                }
                Seg::Cubic(a, b, p) => {
                    d.push('C');
                    pt(&mut d, a, exact);
                    d.push(' ');
                    pt(&mut d, b, exact);
                    d.push(' ');
                    pt(&mut d, p, exact);
                }
            }
        }
    }
    d
}

/// The figure as an SVG document.
#[must_use]
pub fn write(fig: &Figure) -> String {
    let step = step(fig.tolerance);
    let mut s = String::new();
    let (w, h) = (
        number(fig.width, true, step),
        number(fig.height, true, step),
    );
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}">"#
    );
    let (bg, bg_a) = hex(fig.background);
    let _ = writeln!(
        s,
        r#"<rect width="{w}" height="{h}" fill="{bg}"{}/>"#,
        opacity("fill-opacity", bg_a)
    );
    for item in &fig.items {
        match item {
            Item::Path {
                runs,
                stroke,
                shape,
                closed,
                curve,
            } => {
                if runs.is_empty() {
                    continue;
                }
                let (c, a) = hex(stroke.color);
                let dash = if stroke.dash_px > 0.0 {
                    let half = number(f64::from(stroke.dash_px) / 2.0, true, step);
                    format!(r#" stroke-dasharray="{half} {half}""#)
                } else {
                    String::new()
                };
                let id = curve
                    .map(|i| format!(r#" id="curve-{i}""#))
                    .unwrap_or_default();
                let _ = writeln!(
                    s,
                    r#"<path{id} d="{}{}" fill="none" stroke="{c}"{} stroke-width="{}"{}{dash}/>"#,
                    path_data(runs, step),
                    if *closed { "Z" } else { "" },
                    opacity("stroke-opacity", a),
                    number(f64::from(stroke.width_px), true, step),
                    stroke_shape(shape),
                );
            }
            Item::Text {
                at,
                size,
                text,
                color,
                anchor,
            } => {
                let (c, a) = hex(*color);
                let anchor = match anchor {
                    Anchor::Start => "",
                    Anchor::Middle => r#" text-anchor="middle""#,
                    Anchor::End => r#" text-anchor="end""#,
                };
                let _ = writeln!(
                    s,
                    r#"<text x="{}" y="{}" font-family="{}" font-weight="300" font-size="{}" fill="{c}"{}{anchor}>{}</text>"#,
                    number(at.x, true, step),
                    number(at.y, true, step),
                    super::text::SVG_FAMILY,
                    number(*size, true, step),
                    opacity("fill-opacity", a),
                    escape(text),
                );
            }
            Item::Rect {
                min,
                max,
                fill,
                stroke,
            } => {
                let (c, a) = hex(*fill);
                let outline = stroke.map_or_else(String::new, |st| {
                    let (sc, sa) = hex(st.color);
                    format!(
                        r#" stroke="{sc}"{} stroke-width="{}""#,
                        opacity("stroke-opacity", sa),
                        number(f64::from(st.width_px), true, step)
                    )
                });
                let _ = writeln!(
                    s,
                    r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{c}"{}{outline}/>"#,
                    number(min.x, true, step),
                    number(min.y, true, step),
                    number(max.x - min.x, true, step),
                    number(max.y - min.y, true, step),
                    opacity("fill-opacity", a),
                );
            }
            Item::Disc {
                center,
                radius,
                color,
            } => {
                let (c, a) = hex(*color);
                let _ = writeln!(
                    s,
                    r#"<circle cx="{}" cy="{}" r="{}" fill="{c}"{}/>"#,
                    number(center.x, true, step),
                    number(center.y, true, step),
                    number(*radius, true, step),
                    opacity("fill-opacity", a),
                );
            }
        }
    }
    s.push_str("</svg>\n");
    s
}

fn opacity(attr: &str, a: f64) -> String {
    if a >= 1.0 {
        String::new()
    } else {
        format!(r#" {attr}="{}""#, trim(format!("{a:.3}")))
    }
}

/// `text` with XML's special characters escaped, and any character XML 1.0 cannot carry
/// (scene files refuse them in names; text made elsewhere could hold one) written as
/// U+FFFD, so that the document is always well-formed.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c if splinescope_scene::text::displayable(c) => out.push(c),
            _ => out.push('\u{fffd}'),
        }
    }
    out
}
