//! PDF output: one page of the figure's size in points, drawn as the SVG is (paths with
//! round caps and joins, dashes, discs as four cubic arcs; opacity through graphics
//! states). The content stream is written here with plain decimals (PDF has no exponent
//! notation): exact commands with up to six decimals more than the rounding step of
//! approximated pieces, which keep the tolerance. A quadratic is raised to its cubic
//! exactly (`c₁ = p₀ + ⅔(q − p₀)`, `c₂ = p₂ + ⅔(q − p₂)`).

use std::collections::BTreeMap;
use std::fmt::Write as _;

use glam::DVec2;
use pdf_writer::{Name, Pdf, Rect, Ref};
// `x` as a PDF number with at most `decimals` decimals, trailing zeros removed.
use splinescope_core::num::fixed as num;

use super::fit::{Piece, Seg};
use super::svg::step;
use super::{Anchor, Figure, Item, SubPath};
use splinescope_core::ops::{Cap, Join};

/// The magic of the four-arc circle: a cubic arc of a quarter circle has its control
/// points at this fraction of the radius along the tangents.
const KAPPA: f64 = 0.552_284_749_830_793_4;

/// The figure as a PDF file.
#[must_use]
pub fn write(fig: &Figure) -> Vec<u8> {
    let step = step(fig.tolerance);
    let approx = (-step.log10()).round().max(0.0) as usize;
    let mut used = super::text::Used::default();
    for item in &fig.items {
        if let Item::Text { text, .. } = item {
            used.collect(text);
        }
    }
    let mut content = Content {
        text: String::new(),
        alphas: BTreeMap::new(),
        approx,
        exact: approx + 6,
        font: used.subset(),
    };
    content.background(fig);
    for item in &fig.items {
        content.item(item);
    }
    document(fig, &content)
}

/// The page's content stream as it is written, with the opacities it needs and the font.
struct Content {
    /// The stream.
    text: String,
    /// Each opacity used below 1 (in thousandths) and its graphics state's name.
    alphas: BTreeMap<u16, String>,
    /// Decimals of approximated pieces (the rounding step's).
    approx: usize,
    /// Decimals of exact commands.
    exact: usize,
    /// The subset of the font the text uses.
    font: super::text::Subset,
}

impl Content {
    fn num(&self, x: f64) -> String {
        num(x, self.exact)
    }

    fn rgb(c: splinescope_encoding::Color) -> [String; 4] {
        c.0.map(|v| num(f64::from(v).clamp(0.0, 1.0), 4))
    }

    /// `q`, then the graphics state of opacity `a` where it is below 1.
    fn begin(&mut self, a: f32) {
        self.text.push_str("q\n");
        let a = f64::from(a);
        if a < 1.0 {
            let key = (a * 1000.0).round() as u16;
            let n = self.alphas.len();
            let name = self
                .alphas
                .entry(key)
                .or_insert_with(|| format!("G{n}"))
                .clone();
            let _ = writeln!(self.text, "/{name} gs");
        }
    }

    /// The y-down transform and the background.
    fn background(&mut self, fig: &Figure) {
        // y down, as the figure's coordinates.
        let _ = writeln!(self.text, "1 0 0 -1 0 {} cm", self.num(fig.height));
        let [r, g, b, _] = Self::rgb(fig.background);
        let (w, h) = (self.num(fig.width), self.num(fig.height));
        let _ = writeln!(self.text, "{r} {g} {b} rg 0 0 {w} {h} re f");
        self.text.push_str("1 J 1 j\n");
    }

    fn item(&mut self, item: &Item) {
        match item {
            Item::Path {
                runs,
                stroke,
                shape,
                closed,
                ..
            } => {
                if runs.is_empty() {
                    return;
                }
                self.begin(stroke.color.0[3]);
                let [r, g, b, _] = Self::rgb(stroke.color);
                let width = self.num(f64::from(stroke.width_px));
                let _ = writeln!(self.text, "{r} {g} {b} RG {width} w");
                if !shape.is_round() {
                    // The page's default is round (set with the background); this path's
                    // own, inside its q … Q.
                    let cap = match shape.cap {
                        Cap::Butt => 0,
                        Cap::Round => 1,
                        Cap::Square => 2,
                    };
                    let join = match shape.join {
                        Join::Miter => 0,
                        Join::Round => 1,
                        Join::Bevel => 2,
                    };
                    let limit = self.num(shape.miter_limit);
                    let _ = writeln!(self.text, "{cap} J {join} j {limit} M");
                }
                if stroke.dash_px > 0.0 {
                    let half = self.num(f64::from(stroke.dash_px) / 2.0);
                    let _ = writeln!(self.text, "[{half} {half}] 0 d");
                }
                path(&mut self.text, runs, self.approx, self.exact);
                self.text
                    .push_str(if *closed { "h S\nQ\n" } else { "S\nQ\n" });
            }
            Item::Text {
                at,
                size,
                text,
                color,
                anchor,
            } => {
                self.begin(color.0[3]);
                let [r, g, b, _] = Self::rgb(*color);
                let w = super::text::width(text, *size);
                let x = match anchor {
                    Anchor::Start => at.x,
                    Anchor::Middle => at.x - 0.5 * w,
                    Anchor::End => at.x - w,
                };
                // The text matrix flips y back (the page's y points down here).
                let (size, x, y) = (self.num(*size), self.num(x), self.num(at.y));
                let glyphs = self.font.encode(text);
                let _ = writeln!(
                    self.text,
                    "{r} {g} {b} rg BT /F0 {size} Tf 1 0 0 -1 {x} {y} Tm <{glyphs}> Tj ET\nQ"
                );
            }
            Item::Rect {
                min,
                max,
                fill,
                stroke,
            } => {
                self.begin(fill.0[3]);
                let [r, g, b, _] = Self::rgb(*fill);
                let rect = format!(
                    "{} {} {} {} re",
                    self.num(min.x),
                    self.num(min.y),
                    self.num(max.x - min.x),
                    self.num(max.y - min.y)
                );
                let _ = writeln!(self.text, "{r} {g} {b} rg {rect} f");
                if let Some(st) = stroke {
                    let [r, g, b, _] = Self::rgb(st.color);
                    let width = self.num(f64::from(st.width_px));
                    let _ = writeln!(self.text, "{r} {g} {b} RG {width} w {rect} S");
                }
                self.text.push_str("Q\n");
            }
            Item::Disc {
                center,
                radius,
                color,
            } => {
                self.begin(color.0[3]);
                let [r, g, b, _] = Self::rgb(*color);
                let _ = writeln!(self.text, "{r} {g} {b} rg");
                disc(&mut self.text, *center, *radius, self.exact);
                self.text.push_str("f\nQ\n");
            }
        }
    }
}

/// The PDF document around the content stream: catalog, one page of the figure's size,
/// the font subset and one graphics state per opacity.
fn document(fig: &Figure, content: &Content) -> Vec<u8> {
    let mut pdf = Pdf::new();
    let (catalog, pages, page, stream) = (Ref::new(1), Ref::new(2), Ref::new(3), Ref::new(4));
    pdf.catalog(catalog).pages(pages);
    pdf.pages(pages).kids([page]).count(1);
    let mut next = 5;
    let font_ref = if content.font.is_empty() {
        None
    } else {
        let (r, n) = content.font.write(&mut pdf, next);
        next = n;
        Some(r)
    };
    let states: Vec<(String, Ref, f32)> = content
        .alphas
        .iter()
        .map(|(key, name)| {
            let id = Ref::new(next);
            next += 1;
            (name.clone(), id, f32::from(*key) / 1000.0)
        })
        .collect();
    {
        let mut p = pdf.page(page);
        p.media_box(Rect::new(0.0, 0.0, fig.width as f32, fig.height as f32));
        p.parent(pages);
        p.contents(stream);
        let mut res = p.resources();
        if let Some(f) = font_ref {
            res.fonts().pair(Name(b"F0"), f);
        }
        let mut dict = res.ext_g_states();
        for (name, id, _) in &states {
            dict.pair(Name(name.as_bytes()), *id);
        }
    }
    for (_, id, a) in &states {
        pdf.ext_graphics(*id)
            .stroking_alpha(*a)
            .non_stroking_alpha(*a);
    }
    pdf.stream(stream, content.text.as_bytes());
    pdf.finish()
}

fn path(out: &mut String, runs: &[SubPath], approx: usize, exact: usize) {
    let p = |q: DVec2, exact_piece: bool| {
        let d = if exact_piece { exact } else { approx };
        format!("{} {}", num(q.x, d), num(q.y, d))
    };
    for run in runs {
        let first_exact = run.pieces.first().is_none_or(|p| p.exact);
        let _ = writeln!(out, "{} m", p(run.start, first_exact));
        let mut current = run.start;
        for &Piece { seg, exact: e } in &run.pieces {
            match seg {
                Seg::Line(q) => {
                    let _ = writeln!(out, "{} l", p(q, e));
                }
                Seg::Quad(c, q) => {
                    let c1 = current + (c - current) * (2.0 / 3.0);
                    let c2 = q + (c - q) * (2.0 / 3.0);
                    let _ = writeln!(out, "{} {} {} c", p(c1, e), p(c2, e), p(q, e));
                }
                Seg::Cubic(a, b, q) => {
                    let _ = writeln!(out, "{} {} {} c", p(a, e), p(b, e), p(q, e));
                }
            }
            current = seg.end();
        }
    }
}

fn disc(out: &mut String, c: DVec2, r: f64, d: usize) {
    let k = KAPPA * r;
    let pt = |x: f64, y: f64| format!("{} {}", num(x, d), num(y, d));
    let _ = writeln!(out, "{} m", pt(c.x + r, c.y));
    for (a, b, e) in [
        ((r, k), (k, r), (0.0, r)),
        ((-k, r), (-r, k), (-r, 0.0)),
        ((-r, -k), (-k, -r), (0.0, -r)),
        ((k, -r), (r, -k), (r, 0.0)),
    ] {
        let _ = writeln!(
            out,
            "{} {} {} c",
            pt(c.x + a.0, c.y + a.1),
            pt(c.x + b.0, c.y + b.1),
            pt(c.x + e.0, c.y + e.1)
        );
    }
}
