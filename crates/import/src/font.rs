//! Fonts in (`.ttf`, `.otf`, `.ttc`, `.otc`): every contour of a glyph one closed path
//! curve in font units, y up, in the font's contour order, named `<glyph> contour <k>`.
//! TrueType outlines stay quadratic (an implied on-curve point is the exact midpoint of its
//! two off-curve neighbours), CFF and CFF2 outlines cubic; a closing line only where the
//! last point differs from the first; composite glyphs with their components' transforms;
//! variable fonts at a location. Outlines are read by `skrifa` (Google's font reader),
//! unhinted and unscaled.
//!
//! What to open: every glyph on a grid in glyph order, some glyphs (names or ids), or a
//! text laid out by the font's advances (no shaping, no kerning). One glyph sits at its
//! own origin.

use glam::DVec3;
use skrifa::prelude::{LocationRef, Size};
use skrifa::raw::TableProvider;
use skrifa::{FontRef, GlyphId, MetadataProvider, outline::DrawSettings, outline::OutlinePen};
use splinescope_core::geom::{Curve, Path, PathSegment};
use splinescope_scene::format::{Color, Scene, SceneCurve, Style};
use splinescope_scene::limits;

use crate::{ImportError, Imported};

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
    pub variations: Vec<(String, f32)>,
}

/// The outline of one glyph as the pen receives it: closed contours of path segments.
#[derive(Default)]
struct Contours {
    done: Vec<(Vec<PathSegment>, bool)>,
    current: Vec<PathSegment>,
    start: DVec3,
    at: DVec3,
    offset: DVec3,
}

impl Contours {
    fn p(&self, x: f32, y: f32) -> DVec3 {
        DVec3::new(f64::from(x), f64::from(y), 0.0) + self.offset
    }

    fn push(&mut self, points: Vec<DVec3>) {
        self.at = points[points.len() - 1];
        self.current.push(PathSegment::polynomial(points));
    }

    fn finish(&mut self, closed: bool) {
        if self.current.is_empty() {
            return;
        }
        if closed && self.at != self.start {
            let (a, b) = (self.at, self.start);
            self.current.push(PathSegment::polynomial(vec![a, b]));
        }
        let segs = std::mem::take(&mut self.current);
        self.done.push((segs, closed));
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
        self.push(vec![self.at, p]);
    }

    fn quad_to(&mut self, cx0: f32, cy0: f32, x: f32, y: f32) {
        let (c, p) = (self.p(cx0, cy0), self.p(x, y));
        self.push(vec![self.at, c, p]);
    }

    fn curve_to(&mut self, cx0: f32, cy0: f32, cx1: f32, cy1: f32, x: f32, y: f32) {
        let (c0, c1, p) = (self.p(cx0, cy0), self.p(cx1, cy1), self.p(x, y));
        self.push(vec![self.at, c0, c1, p]);
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
        if !(value.is_finite() && *value >= axis.min_value() && *value <= axis.max_value()) {
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
    let location = axes.location(opts.variations.iter().map(|(t, v)| (t.as_str(), *v)));
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
    let outlines = font.outline_glyphs();
    let max_curves = limits::CURVES
        .value()
        .map_err(|source| ImportError::Limit {
            file: file.to_owned(),
            source,
        })?;
    let mut curves = Vec::new();
    let style = {
        let mut s = Style::default_for(0);
        s.color = Color::from_rgba8([34, 34, 34, 255]);
        s.width = 1.5;
        s.show_polygon = false;
        s.show_points = false;
        s
    };
    for (gid, offset) in placed {
        let Some(glyph) = outlines.get(gid) else {
            continue;
        };
        let mut pen = Contours {
            offset,
            ..Contours::default()
        };
        let settings = DrawSettings::unhinted(Size::unscaled(), LocationRef::from(&location));
        glyph.draw(settings, &mut pen).map_err(|e| {
            font_error(
                file,
                format!("glyph {}: cannot be drawn: {e}", glyph_name(gid)),
            )
        })?;
        pen.finish(false);
        let name = glyph_name(gid);
        for (k, (segs, closed)) in pen.done.into_iter().enumerate() {
            if curves.len() as u64 >= max_curves {
                return Err(font_error(
                    file,
                    limits::CURVES
                        .check(curves.len() as u64 + 1)
                        .err()
                        .map_or_else(String::new, |e| e.to_string()),
                ));
            }
            let path = Path::try_new(segs, closed)
                .map_err(|e| font_error(file, format!("glyph {name} contour {k}: {e}")))?;
            curves.push(SceneCurve {
                name: Some(format!("{name} contour {k}")),
                curve: Curve::Path(path),
                style: style.clone(),
            });
        }
    }
    let mut scene = Scene::of_curves(std::iter::empty());
    scene.name = std::path::Path::new(file)
        .file_name()
        .map(|n| n.to_string_lossy().into_owned());
    scene.curves = curves;
    Ok(Imported { scene, warnings })
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
