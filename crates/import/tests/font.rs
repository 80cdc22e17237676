//! Fonts in: contours as closed paths with the font's own coordinates, glyphs chosen by
//! name or id, text by the advances, and bad files or requests refused naming the file
//! and what. (Every glyph against fontTools: `crates/python/tests/test_fonts.py`.)

use splinescope_core::geom::Curve;
use splinescope_import::font::{FontOptions, read};

const DEJAVU: &str = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

fn dejavu() -> Vec<u8> {
    std::fs::read(DEJAVU).unwrap_or_else(|e| {
        panic!(
            "{DEJAVU}: {e}; the font tests need Debian's fonts-dejavu-core (sudo apt-get install fonts-dejavu-core; scripts/test installs it)"
        )
    })
}

fn glyphs(names: &[&str]) -> FontOptions {
    FontOptions {
        glyphs: Some(names.iter().map(|s| (*s).to_owned()).collect()),
        ..FontOptions::default()
    }
}

#[test]
fn a_glyph_is_its_closed_contours_in_font_units_quadratics_kept() {
    let font = dejavu();
    let i = read(&font, "DejaVuSans.ttf", &glyphs(&["o"])).expect("reads");
    // The letter o: an outer and an inner contour, closed, every segment a line or a
    // quadratic with integer or half-integer (implied midpoint) coordinates.
    assert_eq!(i.scene.curves.len(), 2);
    for (k, c) in i.scene.curves.iter().enumerate() {
        assert_eq!(c.name.as_deref(), Some(format!("o contour {k}").as_str()));
        let Curve::Path(p) = &c.curve else {
            panic!("a path")
        };
        assert!(p.is_closed());
        for s in p.segments() {
            assert!(s.degree() <= 2 && s.weights.is_none());
            for q in &s.points {
                assert_eq!((2.0 * q.x).fract(), 0.0, "{q}");
                assert_eq!((2.0 * q.y).fract(), 0.0, "{q}");
            }
        }
    }
    // The same glyph by id: gid of "o" in DejaVu Sans is 82.
    let by_id = read(&font, "f", &glyphs(&["gid82"])).expect("reads");
    assert_eq!(
        by_id.scene.curves[0].curve.control_points(),
        i.scene.curves[0].curve.control_points()
    );
}

#[test]
fn bad_files_and_requests_are_refused_naming_the_file_and_what() {
    let font = dejavu();
    let refused = |bytes: &[u8], opts: &FontOptions, words: &[&str]| {
        let e = read(bytes, "bad.ttf", opts).expect_err("refused");
        let m = e.to_string();
        assert!(m.starts_with("bad.ttf: "), "{m}");
        for w in words {
            assert!(m.contains(w), "{m} should say {w}");
        }
    };
    refused(
        b"not a font at all",
        &FontOptions::default(),
        &["not a font"],
    );
    refused(&font[..100], &FontOptions::default(), &["not a font"]);
    refused(
        &font,
        &FontOptions {
            index: 2,
            ..FontOptions::default()
        },
        &["index 2"],
    );
    refused(
        &font,
        &glyphs(&["no-such-glyph"]),
        &["no-such-glyph", "no glyph of that name"],
    );
    refused(&font, &glyphs(&["gid99999"]), &["gid99999", "ids 0 to"]);
    refused(
        &font,
        &FontOptions {
            text: Some("a\u{10FFFD}".into()),
            ..FontOptions::default()
        },
        &["U+10FFFD"],
    );
    refused(
        &font,
        &FontOptions {
            variations: vec![("wght".into(), 700.0)],
            ..FontOptions::default()
        },
        &["wght", "not a variable font"],
    );
    // Bytes flipped anywhere: a typed error or an outline, never a panic.
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    for _ in 0..200 {
        let mut b = font.clone();
        for _ in 0..16 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let at = (state % b.len() as u64) as usize;
            b[at] ^= (state >> 32) as u8;
        }
        let opts = FontOptions {
            text: Some("Ag&".into()),
            ..FontOptions::default()
        };
        if let Ok(i) = read(&b, "flipped.ttf", &opts) {
            for c in &i.scene.curves {
                assert!(c.curve.control_points().iter().all(|p| p.is_finite()));
            }
        }
    }
}
