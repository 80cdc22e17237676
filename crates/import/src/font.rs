//! Fonts in (`.ttf`, `.otf`, `.ttc`, `.otc`): every contour of a glyph one closed path
//! curve in font units, y up, in the font's contour order, named `<glyph> contour <k>`.
//! TrueType outlines stay quadratic (an implied on-curve point is the exact midpoint of its
//! two off-curve neighbours), CFF and CFF2 outlines cubic; a closing line only where the
//! last point differs from the first; composite glyphs with their components' transforms;
//! variable fonts at a location. TrueType outlines are read by `skrifa` (Google's font
//! reader), unhinted and unscaled (their coordinates are integers, or at a variable font's
//! location within `f32` of it); CFF and CFF2 charstrings are evaluated by `read-fonts`
//! (under `skrifa`) into a sink that takes their 16.16 fixed-point values, so that every
//! coordinate arrives exactly (skrifa's pen would round it to `f32`) and no segment is
//! dropped (its pen leaves out lines of length zero that the font draws).
//!
//! What to open: every glyph on a grid in glyph order, some glyphs (names or ids), or a
//! text laid out by the font's advances (no shaping, no kerning). One glyph sits at its
//! own origin.

use std::sync::atomic::{AtomicU64, Ordering};

use glam::{DVec2, DVec3};
use rayon::prelude::*;
use skrifa::prelude::{LocationRef, Size};
use skrifa::raw::TableProvider;
use skrifa::raw::ps::cff::CffFontRef;
use skrifa::raw::ps::cs::CommandSink;
use skrifa::raw::types::{Fixed, Tag};
use skrifa::{FontRef, GlyphId, MetadataProvider, outline::DrawSettings, outline::OutlinePen};
use splinescope_core::geom::{Curve, Path, PathSegment, SegmentPoints};
use splinescope_encoding::Color;
use splinescope_io::limits;
use splinescope_scene::format::{SceneCurve, Style};

use crate::{ImportError, Imported};

mod cff2;
mod variable;

/// What to read of a font.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FontOptions {
    /// The font's index in a collection (`.ttc`, `.otc`); 0 for a single font.
    pub index: u32,
    /// These glyphs only, by name or id (`"A"`, `"uni00E9"`, `"gid36"` or `"36"`).
    pub glyphs: Option<Vec<String>>,
    /// This text, laid out by the font's advances (no shaping or kerning).
    pub text: Option<String>,
    /// A location in a variable font's design space: `(axis tag, value)`.
    pub variations: Vec<(String, f64)>,
}

/// The outline of one glyph as the pen receives it: closed contours of path segments.
#[derive(Default)]
struct Contours {
    done: Vec<(Vec<PathSegment>, bool)>,
    current: Vec<PathSegment>,
    start: DVec3,
    at: DVec3,
    offset: DVec3,
    /// No closing lines: a closed contour's last point is left where the font puts it
    /// (the CFF2 reader adds them once the points are summed).
    no_closing_lines: bool,
}

impl Contours {
    fn p(&self, x: f32, y: f32) -> DVec3 {
        DVec3::new(f64::from(x), f64::from(y), 0.0) + self.offset
    }

    /// A segment from the pen's current point through `rest` (no heap: a segment's
    /// points are held inline).
    fn push(&mut self, rest: &[DVec3]) {
        let mut points = SegmentPoints::new();
        points.push(self.at);
        points.extend_from_slice(rest);
        self.at = rest[rest.len() - 1];
        self.current.push(PathSegment::polynomial(points));
    }

    /// Ready for the next glyph, placed at `offset`.
    fn reset(&mut self, offset: DVec3) {
        self.done.clear();
        self.current.clear();
        self.offset = offset;
        self.start = offset;
        self.at = offset;
    }

    fn finish(&mut self, closed: bool) {
        if self.current.is_empty() {
            return;
        }
        if closed && !self.no_closing_lines && self.at != self.start {
            let (a, b) = (self.at, self.start);
            self.current
                .push(PathSegment::polynomial(SegmentPoints::from_slice(&[a, b])));
        }
        // The scratch vector keeps its capacity; the contour gets one of its own size.
        let segs: Vec<PathSegment> = self.current.drain(..).collect();
        self.done.push((segs, closed));
    }
}

impl Contours {
    fn fixed(&self, x: Fixed, y: Fixed) -> DVec3 {
        // 16.16 values: `to_bits / 65536` is exact in `f64`.
        DVec3::new(
            f64::from(x.to_bits()) / 65536.0,
            f64::from(y.to_bits()) / 65536.0,
            0.0,
        ) + self.offset
    }
}

/// A TrueType glyph's contours (points and on-curve flags, `f64`) drawn into `pen` as
/// TrueType means them: quadratic splines, an implied on-curve point the exact midpoint of
/// two off-curve neighbours, each contour closed (a closing line where its last point is
/// not its first).
fn draw_truetype(pen: &mut Contours, contours: &[variable::Contour]) {
    for (pts, on) in contours {
        let n = pts.len();
        if n == 0 {
            continue;
        }
        let offset = pen.offset;
        let p3 = |p: DVec2| p.extend(0.0) + offset;
        // Start at the first on-curve point, or (none) the midpoint of the last and the
        // first; then walk the rest of the contour once round.
        let (start, first, count) = match on.iter().position(|&o| o) {
            Some(s) => (pts[s], s + 1, n - 1),
            None => (0.5 * (pts[n - 1] + pts[0]), 0, n),
        };
        pen.finish(false);
        pen.start = p3(start);
        pen.at = pen.start;
        let mut pending: Option<DVec2> = None;
        for i in (first..first + count).map(|k| k % n) {
            let q = pts[i];
            match (on[i], pending) {
                (true, Some(c)) => {
                    pen.push(&[p3(c), p3(q)]);
                    pending = None;
                }
                (true, None) => pen.push(&[p3(q)]),
                (false, Some(c)) => {
                    let m = 0.5 * (c + q);
                    pen.push(&[p3(c), p3(m)]);
                    pending = Some(q);
                }
                (false, None) => pending = Some(q),
            }
        }
        if let Some(c) = pending {
            let start = pen.start;
            pen.push(&[p3(c), start]);
        }
        pen.finish(true);
    }
}

/// The CFF charstring evaluator's commands, exactly (a pen would take them as `f32`).
struct Exact<'a>(&'a mut Contours);

impl CommandSink for Exact<'_> {
    fn move_to(&mut self, x: Fixed, y: Fixed) {
        let c = &mut *self.0;
        c.finish(false);
        c.start = c.fixed(x, y);
        c.at = c.start;
    }

    fn line_to(&mut self, x: Fixed, y: Fixed) {
        let p = self.0.fixed(x, y);
        self.0.push(&[p]);
    }

    fn curve_to(&mut self, cx0: Fixed, cy0: Fixed, cx1: Fixed, cy1: Fixed, x: Fixed, y: Fixed) {
        let c = &mut *self.0;
        let (c0, c1, p) = (c.fixed(cx0, cy0), c.fixed(cx1, cy1), c.fixed(x, y));
        c.push(&[c0, c1, p]);
    }

    fn close(&mut self) {
        self.0.finish(true);
    }
}

impl OutlinePen for Contours {
    fn move_to(&mut self, x: f32, y: f32) {
        self.finish(false);
        self.start = self.p(x, y);
        self.at = self.start;
    }

    fn line_to(&mut self, x: f32, y: f32) {
        let p = self.p(x, y);
        self.push(&[p]);
    }

    fn quad_to(&mut self, cx0: f32, cy0: f32, x: f32, y: f32) {
        let (c, p) = (self.p(cx0, cy0), self.p(x, y));
        self.push(&[c, p]);
    }

    fn curve_to(&mut self, cx0: f32, cy0: f32, cx1: f32, cy1: f32, x: f32, y: f32) {
        let (c0, c1, p) = (self.p(cx0, cy0), self.p(cx1, cy1), self.p(x, y));
        self.push(&[c0, c1, p]);
    }

    fn close(&mut self) {
        self.finish(true);
    }
}

fn font_error(file: &str, message: String) -> ImportError {
    ImportError::Font {
        file: file.to_owned(),
        message,
    }
}

/// Reads the font in `data` (from `file`, for messages) as a scene of path curves.
///
/// # Errors
/// [`ImportError::Font`]: not a font (or no font at the index), a glyph or a character
/// the font does not have, an axis it does not have or a value outside its range, an
/// outline that cannot be drawn; [`ImportError::Limit`] past the curve limit.
pub fn read(data: &[u8], file: &str, opts: &FontOptions) -> Result<Imported, ImportError> {
    let font = FontRef::from_index(data, opts.index).map_err(|e| {
        font_error(
            file,
            format!("not a font, or no font at index {}: {e}", opts.index),
        )
    })?;
    let upem = font
        .head()
        .map(|h| f64::from(h.units_per_em()))
        .map_err(|e| {
            font_error(
                file,
                format!("not a font, or a truncated one: no head table ({e})"),
            )
        })?;
    // The location: every axis named must be the font's, every value inside its range
    // (skrifa would clamp it silently).
    let axes = font.axes();
    for (tag, value) in &opts.variations {
        let Some(axis) = axes.iter().find(|a| a.tag().to_string() == *tag) else {
            let known: Vec<String> = axes.iter().map(|a| a.tag().to_string()).collect();
            return Err(font_error(
                file,
                format!(
                    "--variations {tag}={value}: the font has no axis {tag:?} (its axes: {})",
                    if known.is_empty() {
                        "none, it is not a variable font".to_owned()
                    } else {
                        known.join(", ")
                    }
                ),
            ));
        };
        if !(value.is_finite()
            && *value >= f64::from(axis.min_value())
            && *value <= f64::from(axis.max_value()))
        {
            return Err(font_error(
                file,
                format!(
                    "--variations {tag}={value}: outside the axis's range [{}, {}]",
                    axis.min_value(),
                    axis.max_value()
                ),
            ));
        }
    }
    // skrifa's location is in f32 (its readers compute in f32 and 16.16); the f64
    // reader of variable TrueType outlines takes the values as given.
    let location = axes.location(opts.variations.iter().map(|(t, v)| (t.as_str(), *v as f32)));
    let count = font.maxp().map(|m| u32::from(m.num_glyphs())).unwrap_or(0);
    let names = glyph_names(&font, count);
    let glyph_name = |gid: GlyphId| {
        names
            .get(gid.to_u32() as usize)
            .cloned()
            .unwrap_or_else(|| format!("gid{}", gid.to_u32()))
    };
    // The glyphs and where each sits.
    let mut warnings = Vec::new();
    let placed: Vec<(GlyphId, DVec3)> = if let Some(text) = &opts.text {
        let charmap = font.charmap();
        let metrics = font.glyph_metrics(Size::unscaled(), LocationRef::from(&location));
        let mut x = 0.0;
        let mut out = Vec::new();
        for ch in text.chars() {
            let gid = charmap.map(ch).ok_or_else(|| {
                font_error(
                    file,
                    format!(
                        "--text: the font has no glyph for {ch:?} (U+{:04X})",
                        u32::from(ch)
                    ),
                )
            })?;
            out.push((gid, DVec3::new(x, 0.0, 0.0)));
            x += f64::from(metrics.advance_width(gid).unwrap_or(0.0));
        }
        warnings.push(format!(
            "{file}: --text laid out by the glyphs' advances: no shaping and no kerning"
        ));
        out
    } else {
        let gids: Vec<GlyphId> = match &opts.glyphs {
            Some(wanted) => wanted
                .iter()
                .map(|w| find_glyph(w, count, glyph_name))
                .collect::<Result<_, String>>()
                .map_err(|m| font_error(file, m))?,
            None => (0..count).map(GlyphId::new).collect(),
        };
        if gids.len() == 1 {
            vec![(gids[0], DVec3::ZERO)]
        } else {
            let columns = (gids.len() as f64).sqrt().ceil().max(1.0) as usize;
            let cell = 1.25 * upem;
            gids.iter()
                .enumerate()
                .map(|(i, &g)| {
                    let (c, r) = (i % columns, i / columns);
                    (g, DVec3::new(c as f64 * cell, -(r as f64) * cell, 0.0))
                })
                .collect()
        }
    };
    // A CFF or CFF2 font (no glyf table) with the default font matrix: its charstrings
    // evaluated exactly (a font matrix other than the default scales coordinates: such a
    // font is drawn through skrifa's pen).
    let cff_data = if font.table_data(Tag::new(b"glyf")).is_some() {
        None
    } else {
        font.table_data(Tag::new(b"CFF "))
            .or_else(|| font.table_data(Tag::new(b"CFF2")))
    };
    let cff = cff_data
        .as_ref()
        .and_then(|d| CffFontRef::new(d.as_bytes(), 0, Some(upem as i32)).ok())
        .filter(|c| c.matrix().is_none());
    // A variable TrueType font away from its default location: its deltas applied in
    // f64 (skrifa's FreeType-compatible scaler rounds the outline to whole units).
    let variable = if opts.variations.is_empty() || cff.is_some() {
        None
    } else {
        variable::Variable::new(&font, &opts.variations)
    };
    // A CFF2 font away from its default location: its blends summed in f64.
    let cff2 = match cff.as_ref().filter(|c| c.version() == 2) {
        Some(c) if !opts.variations.is_empty() => cff2::Cff2Blend::new(&font, c, &opts.variations)
            .unwrap_or_else(|n| {
                warnings.push(format!(
                    "{file}: {n} variation regions count at this location (more than {}): \
                     its blends are evaluated in 16.16 fixed point, within about 10⁻³ units",
                    cff2::MAX_REGIONS
                ));
                None
            }),
        _ => None,
    };
    let max_curves = limits::CURVES
        .value()
        .map_err(|source| ImportError::Limit {
            file: file.to_owned(),
            source,
        })?;
    let style = {
        let mut s = Style::default_for(0);
        s.color = Color::from_rgba8([34, 34, 34, 255]);
        s.width = 1.5;
        s.show_polygon = false;
        s.show_points = false;
        s
    };
    let reader = GlyphReader {
        file,
        outlines: &font.outline_glyphs(),
        cff: cff.as_ref(),
        variable: variable.as_ref(),
        cff2: cff2.as_ref(),
        location: &location,
        style: &style,
        names: &glyph_name,
        max_curves,
        made: AtomicU64::new(0),
    };
    // The glyphs in chunks over every core (each chunk with its own pen, whose scratch
    // vectors keep their capacity), then in order: the first error in glyph order is
    // the one reported.
    let chunks: Vec<Result<Vec<SceneCurve>, ImportError>> = placed
        .par_chunks(64)
        .map(|chunk| reader.read(chunk))
        .collect();
    let mut curves =
        Vec::with_capacity(chunks.iter().map(|c| c.as_ref().map_or(0, Vec::len)).sum());
    for chunk in chunks {
        curves.extend(chunk?);
    }
    let mut imported = Imported::of_file(
        file,
        curves,
        &std::collections::BTreeMap::<String, u64>::new(),
    );
    imported.warnings = warnings;
    Ok(imported)
}

/// What every chunk of glyphs is read with.
struct GlyphReader<'a, 'f, N> {
    file: &'a str,
    outlines: &'a skrifa::outline::OutlineGlyphCollection<'f>,
    cff: Option<&'a CffFontRef<'f>>,
    variable: Option<&'a variable::Variable<'f>>,
    cff2: Option<&'a cff2::Cff2Blend>,
    location: &'a skrifa::instance::Location,
    style: &'a Style,
    names: &'a N,
    max_curves: u64,
    /// The curves made so far, by every chunk: past the limit, every chunk stops.
    made: AtomicU64,
}

impl<N: Fn(GlyphId) -> String + Sync> GlyphReader<'_, '_, N> {
    /// The curves of the glyphs of `chunk`, each at its place, in order.
    fn read(&self, chunk: &[(GlyphId, DVec3)]) -> Result<Vec<SceneCurve>, ImportError> {
        let file = self.file;
        let coords = self.location.coords();
        let mut curves = Vec::with_capacity(2 * chunk.len());
        // One pen for the chunk: its scratch vectors keep their capacity.
        let mut pen = Contours::default();
        for &(gid, offset) in chunk {
            let Some(glyph) = self.outlines.get(gid) else {
                continue;
            };
            pen.reset(offset);
            // The drawing, by the first reader that takes the glyph: a variable TrueType
            // outline in f64, a CFF2 outline at a location in f64, a CFF charstring
            // exactly, else skrifa's pen.
            let mut drawn_in_f64 = self
                .variable
                .and_then(|v| v.contours(gid).ok())
                .map(|contours| draw_truetype(&mut pen, &contours))
                .is_some();
            if let (false, Some(blend), Some(cff)) = (drawn_in_f64, self.cff2, self.cff) {
                pen.done = blend.contours(cff, gid, offset).map_err(|m| {
                    font_error(
                        file,
                        format!("glyph {}: cannot be drawn: {m}", (self.names)(gid)),
                    )
                })?;
                drawn_in_f64 = true;
            }
            let exact = if drawn_in_f64 {
                Some(Ok(()))
            } else {
                self.cff.map(|c| {
                    let index = c.subfont_index(gid).unwrap_or(0);
                    let subfont = c.subfont(index, coords)?;
                    if subfont.matrix().is_some() {
                        return Err(skrifa::raw::ps::error::Error::InvalidFontFormat);
                    }
                    c.evaluate_charstring(&subfont, gid, coords, &mut Exact(&mut pen))
                        .map(|_| ())
                })
            };
            match exact {
                Some(Ok(())) => {}
                Some(Err(e)) if !matches!(e, skrifa::raw::ps::error::Error::InvalidFontFormat) => {
                    return Err(font_error(
                        file,
                        format!("glyph {}: cannot be drawn: {e}", (self.names)(gid)),
                    ));
                }
                _ => {
                    pen.reset(offset);
                    let settings =
                        DrawSettings::unhinted(Size::unscaled(), LocationRef::from(self.location));
                    glyph.draw(settings, &mut pen).map_err(|e| {
                        font_error(
                            file,
                            format!("glyph {}: cannot be drawn: {e}", (self.names)(gid)),
                        )
                    })?;
                }
            }
            pen.finish(false);
            let made = self
                .made
                .fetch_add(pen.done.len() as u64, Ordering::Relaxed)
                + pen.done.len() as u64;
            if made > self.max_curves {
                return Err(font_error(
                    file,
                    limits::CURVES
                        .check(self.max_curves + 1)
                        .err()
                        .map_or_else(String::new, |e| e.to_string()),
                ));
            }
            let name = (self.names)(gid);
            for (k, (segs, closed)) in pen.done.drain(..).enumerate() {
                let path = Path::try_new(segs, closed)
                    .map_err(|e| font_error(file, format!("glyph {name} contour {k}: {e}")))?;
                curves.push(SceneCurve {
                    name: Some(format!("{name} contour {k}")),
                    curve: Curve::Path(path),
                    style: self.style.clone(),
                });
            }
        }
        Ok(curves)
    }
}

/// Every glyph's name, in one pass: a version-2 `post` table's strings read once (asking
/// for each name on its own walks the strings from the start: quadratic in the glyphs),
/// else the font's own names (CFF's charset, or synthesized ones).
fn glyph_names(font: &FontRef<'_>, count: u32) -> Vec<String> {
    use skrifa::raw::tables::post::DEFAULT_GLYPH_NAMES;
    if let Ok(post) = font.post()
        && let (Some(index), Some(strings)) = (post.glyph_name_index(), post.string_data())
    {
        let strings: Vec<String> = strings
            .iter()
            .map(|s| s.map(|s| s.to_string()).unwrap_or_default())
            .collect();
        return (0..count as usize)
            .map(|g| {
                let i = index.get(g).map_or(usize::MAX, |i| usize::from(i.get()));
                if i < DEFAULT_GLYPH_NAMES.len() {
                    DEFAULT_GLYPH_NAMES[i].to_owned()
                } else {
                    strings
                        .get(i - DEFAULT_GLYPH_NAMES.len())
                        .filter(|s| !s.is_empty())
                        .cloned()
                        .unwrap_or_else(|| format!("gid{g}"))
                }
            })
            .collect();
    }
    let names = font.glyph_names();
    (0..count)
        .map(|g| {
            names
                .get(GlyphId::new(g))
                .map_or_else(|| format!("gid{g}"), |n| n.as_str().to_owned())
        })
        .collect()
}

/// The glyph `wanted` names: a glyph name, `gidN` or a bare number below `count`.
fn find_glyph(
    wanted: &str,
    count: u32,
    name: impl Fn(GlyphId) -> String,
) -> Result<GlyphId, String> {
    let id = wanted
        .strip_prefix("gid")
        .unwrap_or(wanted)
        .parse::<u32>()
        .ok();
    if let Some(id) = id {
        if id < count {
            return Ok(GlyphId::new(id));
        }
        return Err(format!(
            "--glyphs {wanted}: the font has {count} glyphs (ids 0 to {})",
            count.saturating_sub(1)
        ));
    }
    (0..count)
        .map(GlyphId::new)
        .find(|&g| name(g) == wanted)
        .ok_or_else(|| format!("--glyphs {wanted}: the font has no glyph of that name"))
}
