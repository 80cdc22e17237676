//! Text and guides around the curves: each curve's label at its end (name and live shape
//! parameters, as the viewer labels it), a legend, axes with ticks and tick labels in
//! scene units, a grid at the ticks. Axes and grid need the 2D (affine) view.

use glam::DVec2;
use splinescope_encoding::StrokeShape;

use splinescope_core::geom::ParamCurve;
use splinescope_encoding::Color;
use splinescope_encoding::draw::{MarkerKind, Stroke, marker_style};
use splinescope_scene::format::Scene;
use splinescope_scene::format::labels::{ANCHORS, Ink, LabelRequest, corner, hidden_note, place};

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
        shape: StrokeShape::default(),
        closed: false,
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

/// Adds to the ink the labels and the legend keep clear of everything `items` draws —
/// curves, control polygons and points, combs, markers, axes — its paths flattened (Bézier
/// pieces at 16 points) and its discs as their boxes.
pub fn add_ink(ink: &mut Ink, items: &[Item]) {
    for item in items {
        match item {
            Item::Path { runs, .. } => {
                for run in runs {
                    let mut points = vec![run.start];
                    let mut at = run.start;
                    for piece in &run.pieces {
                        match piece.seg {
                            Seg::Line(b) => points.push(b),
                            Seg::Quad(c, b) => {
                                points.extend((1..=16).map(|k| {
                                    let t = f64::from(k) / 16.0;
                                    let u = 1.0 - t;
                                    u * u * at + 2.0 * u * t * c + t * t * b
                                }));
                            }
                            Seg::Cubic(c1, c2, b) => {
                                points.extend((1..=16).map(|k| {
                                    let t = f64::from(k) / 16.0;
                                    let u = 1.0 - t;
                                    u * u * u * at
                                        + 3.0 * u * u * t * c1
                                        + 3.0 * u * t * t * c2
                                        + t * t * t * b
                                }));
                            }
                        }
                        at = piece.seg.end();
                    }
                    ink.add_polyline(&points);
                }
            }
            Item::Disc { center, radius, .. } => {
                let r = DVec2::splat(*radius);
                let (a, b) = (*center - r, *center + r);
                ink.add_polyline(&[a, DVec2::new(b.x, a.y), b, DVec2::new(a.x, b.y), a]);
            }
            Item::Text { .. } | Item::Rect { .. } => {}
        }
    }
}

/// The box a text item covers (its advance widths, an ascent of one size and a descent
/// of a quarter), `None` for another item.
#[must_use]
pub fn text_box(item: &Item) -> Option<(DVec2, DVec2)> {
    let Item::Text {
        at,
        size,
        text,
        anchor,
        ..
    } = item
    else {
        return None;
    };
    let w = width(text, *size);
    let left = match anchor {
        Anchor::Start => at.x,
        Anchor::Middle => at.x - 0.5 * w,
        Anchor::End => at.x - w,
    };
    Some((
        DVec2::new(left, at.y - size),
        DVec2::new(left + w, at.y + 0.25 * size),
    ))
}

/// The padding around a label's text inside its box.
const LABEL_PAD: f64 = 2.0;

/// The labels ([`splinescope_scene::format::labels`]): each curve's label placed by the
/// search over positions along its curve, clear of the other labels and of `blocked`
/// (the legend), off the curves where a free spot exists, inside the page, with a leader
/// line where it stands off; the number hidden for want of room.
pub fn labels(
    scene: &Scene,
    proj: &Projection,
    size: DVec2,
    ink: &Ink,
    blocked: &[(DVec2, DVec2)],
    out: &mut Vec<Item>,
) -> usize {
    let texts: Vec<String> = scene.curves.iter().map(|sc| sc.label()).collect();
    let requests: Vec<LabelRequest> = scene
        .curves
        .iter()
        .zip(&texts)
        .map(|(sc, text)| {
            let (a, b) = sc.curve.domain();
            LabelRequest {
                anchors: ANCHORS
                    .iter()
                    .map(|f| {
                        proj.point(sc.curve.eval(a + f * (b - a)))
                            .unwrap_or(DVec2::NAN)
                    })
                    .collect(),
                size: DVec2::new(
                    width(text, LABEL_SIZE) + 2.0 * LABEL_PAD,
                    1.25 * LABEL_SIZE + 2.0 * LABEL_PAD,
                ),
            }
        })
        .collect();
    let placed = place(&requests, ink, size, blocked, &[]);
    let mut hidden = 0;
    for ((sc, text), p) in scene.curves.iter().zip(texts).zip(placed) {
        let Some(p) = p else {
            hidden += 1;
            continue;
        };
        let color = darker(sc.style.color);
        if let Some((a, b)) = p.leader {
            let [r, g, bl, _] = color.0;
            out.push(line(a, b, Stroke::solid(Color([r, g, bl, 0.6]), 0.75)));
        }
        out.push(Item::Text {
            at: DVec2::new(p.min.x + LABEL_PAD, p.min.y + LABEL_PAD + LABEL_SIZE),
            size: LABEL_SIZE,
            text,
            color,
            anchor: Anchor::Start,
        });
    }
    hidden
}

/// Text in a curve's colour, darkened so that light colours stay readable on white.
fn darker(c: Color) -> Color {
    let [r, g, b, _] = c.0;
    Color([r * 0.8, g * 0.8, b * 0.8, 1.0])
}

/// A legend laid out: its rows, its box and where it goes.
pub struct Legend {
    rows: Vec<(Mark, String)>,
    text_w: f64,
    min: DVec2,
    /// Whether the box grows from the top (else from the bottom: a bottom corner).
    top: bool,
    /// Room for the row saying how many labels are hidden.
    reserve: bool,
}

const LEGEND_LINE: f64 = LEGEND_SIZE * 1.5;
const LEGEND_SAMPLE: f64 = 24.0;

impl Legend {
    fn box_size(&self, rows: usize) -> DVec2 {
        DVec2::new(
            8.0 + LEGEND_SAMPLE + 6.0 + self.text_w + 8.0,
            6.0 + LEGEND_LINE * rows as f64 + 4.0,
        )
    }

    /// The box the labels keep clear of (with the reserved row).
    #[must_use]
    pub fn area(&self) -> (DVec2, DVec2) {
        let size = self.box_size(self.rows.len() + usize::from(self.reserve));
        (self.min, self.min + size)
    }
}

/// `text` shortened with an ellipsis to at most `max` points wide at `size`.
fn shortened(text: &str, size: f64, max: f64) -> String {
    if width(text, size) <= max {
        return text.to_owned();
    }
    let mut chars: Vec<char> = text.chars().collect();
    while !chars.is_empty() {
        chars.pop();
        let t: String = chars.iter().collect::<String>().trim_end().to_owned() + "…";
        if width(&t, size) <= max {
            return t;
        }
    }
    "…".to_owned()
}

/// The legend's layout: a stroke sample and the label of each curve, then the marker
/// kinds shown; as many rows as the page's height holds (then how many more), each text
/// shortened with an ellipsis to fit the page's width; in the corner whose box covers
/// the fewest curve pixels. `reserve`: room for a row saying how many labels are hidden.
#[must_use]
pub fn legend_layout(
    scene: &Scene,
    size: DVec2,
    markers: &[MarkerKind],
    ink: &Ink,
    reserve: bool,
) -> Option<Legend> {
    let fixed = 8.0 + LEGEND_SAMPLE + 6.0 + 8.0;
    let max_text = (size.x - 16.0 - fixed).max(LEGEND_SIZE);
    let room = (((size.y - 16.0 - 10.0) / LEGEND_LINE).floor().max(1.0) as usize)
        .saturating_sub(markers.len() + usize::from(reserve))
        .max(1);
    let curve_rows = scene.curves.len().min(LEGEND_ROWS).min(room);
    let more = scene.curves.len() - curve_rows;
    let mut rows: Vec<(Mark, String)> = scene
        .curves
        .iter()
        .take(if more > 0 {
            curve_rows.saturating_sub(1)
        } else {
            curve_rows
        })
        .map(|sc| {
            // A width in scene units has no one size in pixels: the legend shows the default.
            let w = if sc.style.width_in_scene {
                2.5
            } else {
                sc.style.width
            };
            (Mark::Line(sc.style.color, w), sc.label())
        })
        .collect();
    if more > 0 {
        let n = scene.curves.len() - rows.len();
        rows.push((Mark::None, format!("… and {n} more")));
    }
    rows.extend(
        markers
            .iter()
            .map(|&k| (Mark::Marker(k), k.label().to_owned())),
    );
    if rows.is_empty() {
        return None;
    }
    for (_, t) in &mut rows {
        *t = shortened(t, LEGEND_SIZE, max_text);
    }
    let hidden_row = if reserve {
        width("999 labels hidden", LEGEND_SIZE).min(max_text)
    } else {
        0.0
    };
    let text_w = rows
        .iter()
        .map(|(_, t)| width(t, LEGEND_SIZE))
        .fold(hidden_row, f64::max);
    let mut legend = Legend {
        rows,
        text_w,
        min: DVec2::ZERO,
        top: true,
        reserve,
    };
    let full = legend.box_size(legend.rows.len() + usize::from(reserve));
    legend.min = corner(ink, size, full);
    legend.top = legend.min.y + 0.5 * full.y <= 0.5 * size.y;
    Some(legend)
}

/// Draws a legend laid out by [`legend_layout`], with a row saying how many labels are
/// `hidden` when any are.
pub fn legend(layout: Legend, hidden: usize, out: &mut Vec<Item>) {
    let (area_min, area_max) = layout.area();
    let mut rows = layout.rows;
    if let Some(text) = hidden_note(hidden) {
        rows.push((Mark::None, text));
    }
    let box_w = area_max.x - area_min.x;
    let box_h = 6.0 + LEGEND_LINE * rows.len() as f64 + 4.0;
    // Inside the area the labels kept clear of: grown from its top, or from its bottom in
    // a bottom corner.
    let min = DVec2::new(
        area_min.x,
        if layout.top {
            area_min.y
        } else {
            area_max.y - box_h
        },
    );
    out.push(Item::Rect {
        min,
        max: min + DVec2::new(box_w, box_h),
        fill: Color([1.0, 1.0, 1.0, 0.9]),
        stroke: Some(Stroke::solid(Color([0.6, 0.6, 0.6, 1.0]), 0.75)),
    });
    for (i, (mark, text)) in rows.into_iter().enumerate() {
        let mid = min.y + 6.0 + LEGEND_LINE * (i as f64 + 0.5);
        match mark {
            Mark::Line(color, w) => out.push(line(
                DVec2::new(min.x + 8.0, mid),
                DVec2::new(min.x + 8.0 + LEGEND_SAMPLE, mid),
                Stroke::solid(color, w),
            )),
            Mark::Marker(kind) => {
                let (ring, core) = marker_style(kind, LEGEND_CURVE);
                for s in [ring, core] {
                    out.push(Item::Disc {
                        center: DVec2::new(min.x + 8.0 + 0.5 * LEGEND_SAMPLE, mid),
                        radius: 0.5 * f64::from(s.width_px),
                        color: s.color,
                    });
                }
            }
            Mark::None => {}
        }
        out.push(Item::Text {
            at: DVec2::new(min.x + 8.0 + LEGEND_SAMPLE + 6.0, mid + 0.35 * LEGEND_SIZE),
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
