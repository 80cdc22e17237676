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

#[test]
fn a_whole_font_read_over_every_core_keeps_glyph_order_and_each_glyph_alone() {
    // The glyphs are read in chunks on every core: the scene must still be the font's
    // glyph order, and each glyph's contours what it gives when read alone.
    let font = dejavu();
    let all = read(&font, "DejaVuSans.ttf", &FontOptions::default()).expect("reads");
    let names: Vec<&str> = all
        .scene
        .curves
        .iter()
        .map(|c| c.name.as_deref().expect("named"))
        .collect();
    let glyph_of = |n: &str| {
        n.rsplit_once(" contour ")
            .expect("a contour name")
            .0
            .to_owned()
    };
    // Contour numbers restart at 0 for each glyph and count up within it.
    for w in names.windows(2) {
        let (a, b) = (w[0], w[1]);
        let k = |n: &str| -> usize { n.rsplit_once(" contour ").unwrap().1.parse().unwrap() };
        if glyph_of(a) == glyph_of(b) {
            assert_eq!(k(b), k(a) + 1, "{a} then {b}");
        } else {
            assert_eq!(k(b), 0, "{a} then {b}");
        }
    }
    // Three glyphs read alone: the whole font holds the same contours, under the same
    // names, moved to the glyph's cell.
    for (gid, name) in [(36, "A"), (82, "o"), (1000, "")] {
        let wanted = if name.is_empty() {
            format!("gid{gid}")
        } else {
            name.to_owned()
        };
        let alone = read(&font, "f", &glyphs(&[&wanted])).expect("reads");
        let first = alone.scene.curves[0]
            .name
            .as_deref()
            .expect("named")
            .to_owned();
        let at = names
            .iter()
            .position(|n| *n == first)
            .expect("in the whole font");
        for (k, c) in alone.scene.curves.iter().enumerate() {
            let whole = &all.scene.curves[at + k];
            assert_eq!(whole.name, c.name);
            // The same outline, moved to its cell: the same differences between points.
            let (p, q) = (c.curve.control_points(), whole.curve.control_points());
            assert_eq!(p.len(), q.len());
            let shift = q[0] - p[0];
            for (a, b) in p.iter().zip(q) {
                assert_eq!(*b - shift, *a, "{first}");
            }
        }
    }
}

#[test]
fn a_font_past_the_curve_limit_is_refused_naming_the_limit() {
    // Run in a child process: the limit is read from the environment.
    if std::env::var_os("SPLINESCOPE_FONT_LIMIT_CHILD").is_none() {
        let out = std::process::Command::new(std::env::current_exe().expect("the test binary"))
            .args([
                "a_font_past_the_curve_limit_is_refused_naming_the_limit",
                "--exact",
                "--nocapture",
            ])
            .env("SPLINESCOPE_FONT_LIMIT_CHILD", "1")
            .env("SPLINESCOPE_MAX_CURVES", "1000")
            .output()
            .expect("runs");
        assert!(
            out.status.success(),
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        );
        return;
    }
    let font = dejavu();
    let e = read(&font, "DejaVuSans.ttf", &FontOptions::default()).expect_err("over the limit");
    let m = e.to_string();
    assert!(
        m.starts_with("DejaVuSans.ttf: ") && m.contains("1001 is over the limit of 1000 curves"),
        "{m}"
    );
    // Under the limit, a few glyphs read.
    assert!(read(&font, "f", &glyphs(&["A", "o"])).is_ok());
}
