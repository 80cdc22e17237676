//! The figures' font — Ubuntu Light (Ubuntu Font Licence, embedding allowed), the face the
//! viewer's panel uses — its metrics for laying text out, and its embedding in PDF files
//! as a subset (only the glyphs the figure uses, as a CID-keyed TrueType font with a
//! `ToUnicode` map, so text stays searchable and copyable).

use std::collections::BTreeMap;
use std::sync::OnceLock;

use pdf_writer::types::{CidFontType, FontFlags, SystemInfo, UnicodeCmap};
use pdf_writer::{Name, Pdf, Rect, Ref, Str};

/// The font's bytes.
pub const FONT: &[u8] = epaint_default_fonts::UBUNTU_LIGHT;

/// The family name written in SVG files (with a generic fallback).
pub const SVG_FAMILY: &str = "Ubuntu, 'Ubuntu Light', sans-serif";

/// The font, parsed once.
struct Face {
    face: ttf_parser::Face<'static>,
    units: f64,
}

fn face() -> Option<&'static Face> {
    static FACE: OnceLock<Option<Face>> = OnceLock::new();
    FACE.get_or_init(|| {
        let face = ttf_parser::Face::parse(FONT, 0).ok()?;
        let units = f64::from(face.units_per_em());
        Some(Face { face, units })
    })
    .as_ref()
}

/// The glyph of `c` (0, `.notdef`, when the font lacks it).
#[must_use]
pub fn glyph(c: char) -> u16 {
    face()
        .and_then(|f| f.face.glyph_index(c))
        .map_or(0, |g| g.0)
}

/// The advance of glyph `g` in ems.
#[must_use]
pub fn advance(g: u16) -> f64 {
    face().map_or(0.5, |f| {
        f.face
            .glyph_hor_advance(ttf_parser::GlyphId(g))
            .map_or(0.5, |a| f64::from(a) / f.units)
    })
}

/// The width of `text` at `size` points.
#[must_use]
pub fn width(text: &str, size: f64) -> f64 {
    text.chars().map(|c| advance(glyph(c))).sum::<f64>() * size
}

/// The ascent (above the baseline) in ems.
#[must_use]
pub fn ascent() -> f64 {
    face().map_or(0.8, |f| f64::from(f.face.ascender()) / f.units)
}

/// The glyphs a PDF's text uses, gathered before the page is written (the subset
/// renumbers them).
#[derive(Debug, Default)]
pub struct Used {
    glyphs: BTreeMap<u16, char>,
}

impl Used {
    /// Records the glyphs of `text`.
    pub fn collect(&mut self, text: &str) {
        for c in text.chars() {
            self.glyphs.entry(glyph(c)).or_insert(c);
        }
    }

    /// The subset of these glyphs.
    #[must_use]
    pub fn subset(self) -> Subset {
        let ids: Vec<u16> = self.glyphs.keys().copied().collect();
        Subset {
            remapper: subsetter::GlyphRemapper::new_from_glyphs_sorted(&ids),
            glyphs: self.glyphs,
        }
    }
}

/// The font subset of a PDF: the glyphs used, renumbered from 1 (0 is `.notdef`).
#[derive(Debug)]
pub struct Subset {
    remapper: subsetter::GlyphRemapper,
    glyphs: BTreeMap<u16, char>,
}

impl Subset {
    /// `text` as the hex string of its glyphs' ids in the subset (two bytes each).
    #[must_use]
    pub fn encode(&self, text: &str) -> String {
        text.chars()
            .map(|c| format!("{:04X}", self.remapper.get(glyph(c)).unwrap_or(0)))
            .collect()
    }

    /// Whether no text uses the font.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.glyphs.is_empty()
    }

    /// Writes the font objects (`Type0` → `CIDFontType2` → descriptor → the subset as
    /// `FontFile2`, and the `ToUnicode` map) from `first` on; returns the `Type0` font's
    /// reference and the next free one. CIDs are the subset's glyph ids
    /// (`CIDToGIDMap /Identity`).
    pub fn write(&self, pdf: &mut Pdf, first: i32) -> (Ref, i32) {
        let (type0, cid, descriptor, file, cmap) = (
            Ref::new(first),
            Ref::new(first + 1),
            Ref::new(first + 2),
            Ref::new(first + 3),
            Ref::new(first + 4),
        );
        let base = Name(b"SPLSCP+Ubuntu-Light");
        pdf.type0_font(type0)
            .base_font(base)
            .encoding_predefined(Name(b"Identity-H"))
            .descendant_font(cid)
            .to_unicode(cmap);
        let info = SystemInfo {
            registry: Str(b"Adobe"),
            ordering: Str(b"Identity"),
            supplement: 0,
        };
        {
            let mut font = pdf.cid_font(cid);
            font.subtype(CidFontType::Type2)
                .base_font(base)
                .system_info(info)
                .font_descriptor(descriptor)
                .default_width(500.0)
                .cid_to_gid_map_predefined(Name(b"Identity"));
            let mut widths = font.widths();
            for &g in self.glyphs.keys() {
                let new = self.remapper.get(g).unwrap_or(0);
                widths.consecutive(new, [(advance(g) * 1000.0) as f32]);
            }
        }
        let (bbox, ascent, descent, cap) = face().map_or(
            (Rect::new(0.0, -200.0, 1000.0, 900.0), 800.0, -200.0, 700.0),
            |f| {
                let scale = 1000.0 / f.units;
                let b = f.face.global_bounding_box();
                let s = |v: i16| (f64::from(v) * scale) as f32;
                (
                    Rect::new(s(b.x_min), s(b.y_min), s(b.x_max), s(b.y_max)),
                    s(f.face.ascender()),
                    s(f.face.descender()),
                    f.face.capital_height().map_or(700.0, s),
                )
            },
        );
        pdf.font_descriptor(descriptor)
            .name(base)
            .flags(FontFlags::NON_SYMBOLIC)
            .bbox(bbox)
            .italic_angle(0.0)
            .ascent(ascent)
            .descent(descent)
            .cap_height(cap)
            .stem_v(80.0)
            .font_file2(file);
        let data = subsetter::subset(FONT, 0, &self.remapper).unwrap_or_else(|_| FONT.to_vec());
        pdf.stream(file, &data);
        let mut unicode = UnicodeCmap::new(Name(b"Custom"), info);
        for (&g, &c) in &self.glyphs {
            unicode.pair(self.remapper.get(g).unwrap_or(0), c);
        }
        pdf.cmap(cmap, &unicode.finish());
        (type0, first + 5)
    }
}
