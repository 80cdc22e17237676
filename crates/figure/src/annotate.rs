//! Text and guides around the curves: each curve's label at its end (name and live shape
//! parameters, as the viewer labels it), a legend, axes with ticks and tick labels in
//! scene units, a grid at the ticks. Axes and grid need the 2D (affine) view.

use glam::DVec2;

use splinescope_core::geom::ParamCurve;

use splinescope_scene::format::draw::{MarkerKind, Stroke, marker_style};
use splinescope_scene::format::{Color, Scene};

use super::fit::{Piece, Projection, Seg};
use super::text::width;
use super::{Anchor, Item, SubPath};

/// Label text size in points.
const LABEL_SIZE: f64 = 12.0;
/// Legend text size.
const LEGEND_SIZE: f64 = 11.0;
/// Tick label size.
const TICK_SIZE: f64 = 10.0;
/// The most curves a legend lists by name.
const LEGEND_ROWS: usize = 24;

const INK: Color = Color([0.2, 0.2, 0.2, 1.0]);

/// The curve colour a legend's marker rows are shown in.
const LEGEND_CURVE: Color = Color([0.12, 0.47, 0.71, 1.0]);

/// What a legend row shows left of its text.
enum Mark {
    /// A curve's stroke.
    Line(Color, f32),
    /// A marker kind.
    Marker(MarkerKind),
    /// Nothing.
    None,
}
const GRID: Color = Color([0.85, 0.85, 0.85, 1.0]);

fn line(a: DVec2, b: DVec2, stroke: Stroke) -> Item {
    Item::Path {
        runs: vec![SubPath {
            start: a,
            pieces: vec![Piece {
                seg: Seg::Line(b),
                exact: true,
            }],
        }],
        stroke,
        curve: None,
    }
}

/// The labels: each curve's label beside its end point (inside the figure), moved a line
/// down or up, then further, when it would cover a label placed before it.
pub fn labels(scene: &Scene, proj: &Projection, size: DVec2, out: &mut Vec<Item>) {
    let mut placed: Vec<(DVec2, DVec2)> = Vec::new();
    let overlaps = |lo: DVec2, hi: DVec2, placed: &[(DVec2, DVec2)]| {
        placed
            .iter()
            .any(|(a, b)| lo.x < b.x && a.x < hi.x && lo.y < b.y && a.y < hi.y)
    };
    for sc in &scene.curves {
        let (_, b) = sc.curve.domain();
        let Some(end) = proj.point(sc.curve.eval(b)) else {
            continue;
        };
        let text = sc.label();
        let w = width(&text, LABEL_SIZE);
        let (x, anchor, left) = if end.x + 6.0 + w > size.x - 2.0 {
            (end.x - 6.0, Anchor::End, end.x - 6.0 - w)
        } else {
            (end.x + 6.0, Anchor::Start, end.x + 6.0)
        };
        let line_h = LABEL_SIZE * 1.25;
        let base = end.y - 6.0;
        // Baselines from the first line's to the bottom margin's; a figure lower than one
        // line keeps its labels on the first line (cut at the bottom edge).
        let (top, bottom) = (LABEL_SIZE + 2.0, size.y - 4.0);
        let inside = |y: f64| y.max(top).min(bottom.max(top));
        let mut y = inside(base);
        for k in 1..=40 {
            let (lo, hi) = (
                DVec2::new(left, y - LABEL_SIZE),
                DVec2::new(left + w, y + 0.25 * LABEL_SIZE),
            );
            if !overlaps(lo, hi, &placed) {
                break;
            }
            // Alternate below and above, one line further each time.
            let step = f64::from((k + 1) / 2) * line_h;
            let candidate = if k % 2 == 1 { base + step } else { base - step };
            y = inside(candidate);
        }
        placed.push((
            DVec2::new(left, y - LABEL_SIZE),
            DVec2::new(left + w, y + 0.25 * LABEL_SIZE),
        ));
        out.push(Item::Text {
            at: DVec2::new(x, y),
            size: LABEL_SIZE,
            text,
            color: darker(sc.style.color),
            anchor,
        });
    }
}

/// Text in a curve's colour, darkened so that light colours stay readable on white.
fn darker(c: Color) -> Color {
    let [r, g, b, _] = c.0;
    Color([r * 0.8, g * 0.8, b * 0.8, 1.0])
}

/// The legend: a box in the top right corner with a stroke sample and the label of each
/// curve (the first [`LEGEND_ROWS`], then how many more).
pub fn legend(scene: &Scene, size: DVec2, markers: &[MarkerKind], out: &mut Vec<Item>) {
    let mut rows: Vec<(Mark, String)> = scene
        .curves
        .iter()
        .take(LEGEND_ROWS)
        .map(|sc| (Mark::Line(sc.style.color, sc.style.width), sc.label()))
        .collect();
    if scene.curves.len() > LEGEND_ROWS {
        rows.push((
            Mark::None,
            format!("… and {} more", scene.curves.len() - LEGEND_ROWS),
        ));
    }
    // Each marker kind shown, in a neutral curve colour (each marker takes its curve's).
    rows.extend(
        markers
            .iter()
            .map(|&k| (Mark::Marker(k), k.label().to_owned())),
    );
    if rows.is_empty() {
        return;
    }
    let line_h = LEGEND_SIZE * 1.5;
    let sample = 24.0;
    let text_w = rows
        .iter()
        .map(|(_, t)| width(t, LEGEND_SIZE))
        .fold(0.0, f64::max);
    let box_w = 8.0 + sample + 6.0 + text_w + 8.0;
    let box_h = 6.0 + line_h * rows.len() as f64 + 4.0;
    let min = DVec2::new((size.x - 8.0 - box_w).max(0.0), 8.0);
    out.push(Item::Rect {
        min,
        max: min + DVec2::new(box_w, box_h),
        fill: Color([1.0, 1.0, 1.0, 0.9]),
        stroke: Some(Stroke::solid(Color([0.6, 0.6, 0.6, 1.0]), 0.75)),
    });
    for (i, (mark, text)) in rows.into_iter().enumerate() {
        let mid = min.y + 6.0 + line_h * (i as f64 + 0.5);
        match mark {
            Mark::Line(color, w) => out.push(line(
                DVec2::new(min.x + 8.0, mid),
                DVec2::new(min.x + 8.0 + sample, mid),
                Stroke::solid(color, w),
            )),
            Mark::Marker(kind) => {
                let (ring, core) = marker_style(kind, LEGEND_CURVE);
                for s in [ring, core] {
                    out.push(Item::Disc {
                        center: DVec2::new(min.x + 8.0 + 0.5 * sample, mid),
                        radius: 0.5 * f64::from(s.width_px),
                        color: s.color,
                    });
                }
            }
            Mark::None => {}
        }
        out.push(Item::Text {
            at: DVec2::new(min.x + 8.0 + sample + 6.0, mid + 0.35 * LEGEND_SIZE),
            size: LEGEND_SIZE,
            text,
            color: INK,
            anchor: Anchor::Start,
        });
    }
}

/// Tick positions: multiples of 1, 2 or 5 × 10ᵏ giving at most 9 ticks over `[lo, hi]`,
/// and the decimals their labels need.
#[must_use]
pub fn ticks(lo: f64, hi: f64) -> (Vec<f64>, usize) {
    let span = hi - lo;
    if !(span.is_finite() && span > 0.0) {
        return (Vec::new(), 0);
    }
    let e = (span / 6.0).log10().floor() as i32;
    let pow = |e: i32| 10f64.powi(e.abs());
    // Tick k is k·m·10^e, computed as one rounding of an integer scaled by a power of ten
    // (so 3 × 0.05 reads 0.15).
    let value = |k: i64, m: i64, e: i32| {
        if e < 0 {
            (k * m) as f64 / pow(e)
        } else {
            (k * m) as f64 * pow(e)
        }
    };
    let (m, e) = [(1, e), (2, e), (5, e), (1, e + 1)]
        .into_iter()
        .find(|&(m, e)| span / value(1, m, e) <= 8.0)
        .unwrap_or((1, e + 1));
    let step = value(1, m, e);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    ((first..=last).map(|k| value(k, m, e)).collect(), decimals)
}

fn tick_text(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    if s.trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        "0".into()
    } else {
        s.replace('-', "−")
    }
}

/// Axes along the bottom and left edges with ticks and labels in scene units, and a grid
/// at the ticks when `grid` (drawn first, behind everything). Affine views only.
pub fn axes(proj: &Projection, size: DVec2, axes: bool, grid: bool) -> (Vec<Item>, Vec<Item>) {
    let (mut back, mut front) = (Vec::new(), Vec::new());
    let [rx, ry, _] = proj.rows;
    // World coordinate at an output position (the 2D view has no rotation or shear).
    let world_x = |px: f64| (px - rx[3]) / rx[0];
    let world_y = |py: f64| (py - ry[3]) / ry[1];
    let out_x = |x: f64| rx[0] * x + rx[3];
    let out_y = |y: f64| ry[1] * y + ry[3];
    let (xs, xd) = ticks(
        world_x(0.0).min(world_x(size.x)),
        world_x(0.0).max(world_x(size.x)),
    );
    let (ys, yd) = ticks(
        world_y(0.0).min(world_y(size.y)),
        world_y(0.0).max(world_y(size.y)),
    );
    let ink = Stroke::solid(INK, 0.75);
    if grid {
        let g = Stroke::solid(GRID, 0.5);
        for &x in &xs {
            back.push(line(
                DVec2::new(out_x(x), 0.0),
                DVec2::new(out_x(x), size.y),
                g,
            ));
        }
        for &y in &ys {
            back.push(line(
                DVec2::new(0.0, out_y(y)),
                DVec2::new(size.x, out_y(y)),
                g,
            ));
        }
    }
    if axes {
        let y_labels: Vec<String> = ys.iter().map(|&y| tick_text(y, yd)).collect();
        let left = 6.0
            + y_labels
                .iter()
                .map(|t| width(t, TICK_SIZE))
                .fold(0.0, f64::max)
            + 4.0;
        let bottom = size.y - TICK_SIZE - 8.0;
        front.push(line(DVec2::new(left, 0.0), DVec2::new(left, bottom), ink));
        front.push(line(
            DVec2::new(left, bottom),
            DVec2::new(size.x, bottom),
            ink,
        ));
        for &x in &xs {
            let px = out_x(x);
            if px < left {
                continue;
            }
            front.push(line(
                DVec2::new(px, bottom),
                DVec2::new(px, bottom - 5.0),
                ink,
            ));
            front.push(Item::Text {
                at: DVec2::new(px, size.y - 4.0),
                size: TICK_SIZE,
                text: tick_text(x, xd),
                color: INK,
                anchor: Anchor::Middle,
            });
        }
        for (&y, text) in ys.iter().zip(y_labels) {
            let py = out_y(y);
            if py > bottom {
                continue;
            }
            front.push(line(DVec2::new(left, py), DVec2::new(left + 5.0, py), ink));
            front.push(Item::Text {
                at: DVec2::new(left - 4.0, py + 0.35 * TICK_SIZE),
                size: TICK_SIZE,
                text,
                color: INK,
                anchor: Anchor::End,
            });
        }
    }
    (back, front)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside() {
        let (t, d) = ticks(-0.37, 4.2);
        assert_eq!(t, vec![0.0, 1.0, 2.0, 3.0, 4.0]);
        assert_eq!(d, 0);
        let (t, d) = ticks(0.02, 0.31);
        assert_eq!(t, vec![0.05, 0.1, 0.15, 0.2, 0.25, 0.3]);
        assert_eq!(d, 2);
        let (t, d) = ticks(0.0, 1000.0);
        assert_eq!(t.len(), 6);
        assert_eq!((t[1], d), (200.0, 0));
        assert_eq!(tick_text(-2.5, 1), "−2.5");
        assert_eq!(tick_text(-0.0, 1), "0");
    }
}
