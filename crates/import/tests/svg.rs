//! SVG in, against closed forms and hand-computed control points: exact arcs and shapes,
//! every path command, transforms and `<use>`, colours from attributes, style sheets and
//! gradients, and hostile files refused with the file and the line.

use std::f64::consts::PI;

use glam::DVec3;
use splinescope_core::analysis::CurveAnalysis;
use splinescope_core::geom::{Curve, ParamCurve, Path};
use splinescope_import::{ImportError, Imported, svg};

fn read(body: &str) -> Imported {
    read_result(body).unwrap_or_else(|e| panic!("{e}"))
}

fn read_result(body: &str) -> Result<Imported, ImportError> {
    let text = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" viewBox="0 0 100 100">{body}</svg>"#
    );
    svg::read(&text, "test.svg")
}

fn path(i: &Imported, k: usize) -> &Path {
    match &i.scene.curves[k].curve {
        Curve::Path(p) => p,
        other => panic!("curve {k} is a {}", other.family()),
    }
}

/// The scene's point for the SVG user-space point `(x, y)` of a file whose viewBox is
/// `0 0 100 100`: y flipped about its bottom.
fn flip(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, 100.0 - y, 0.0)
}

#[test]
fn a_circle_is_four_exact_quarter_arcs_with_the_circles_length() {
    let i = read(r#"<circle cx="50" cy="40" r="10" stroke="red" fill="none"/>"#);
    let p = path(&i, 0);
    assert!(p.is_closed());
    assert_eq!(p.segments().len(), 4);
    for s in p.segments() {
        assert_eq!(s.degree(), 2);
        assert_eq!(
            s.weights.as_deref(),
            Some(&[1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0][..])
        );
    }
    let length = CurveAnalysis::new(p)
        .length(0.0, 4.0, 1e-13)
        .expect("length");
    assert!(
        (length.value - 20.0 * PI).abs() <= 1e-12,
        "{}",
        length.value
    );
    for k in 0..=200 {
        let q = p.eval(4.0 * f64::from(k) / 200.0);
        let d = (q - flip(50.0, 40.0)).length();
        assert!((d - 10.0).abs() <= 1e-13, "{q}");
    }
    assert_eq!(i.scene.curves[0].style.color.to_rgba8(), [255, 0, 0, 255]);
}

#[test]
fn ellipses_rounded_rectangles_and_arcs_lie_on_their_ellipses() {
    let i = read(concat!(
        r#"<ellipse cx="30" cy="30" rx="20" ry="10" stroke="black"/>"#,
        r#"<rect x="10" y="60" width="40" height="20" rx="5" ry="8" stroke="black"/>"#,
        // A rotated elliptical arc, large and swept, then a relative one.
        r#"<path d="M 60 50 A 20 10 30 1 1 90 60 a 5 5 0 0 0 0 10" stroke="black"/>"#,
    ));
    // The ellipse: (x − 30)²/20² + (y − 30)²/10² = 1 in SVG units.
    let e = path(&i, 0);
    for k in 0..=400 {
        let q = e.eval(4.0 * f64::from(k) / 400.0);
        let (x, y) = (q.x, 100.0 - q.y);
        let f = ((x - 30.0) / 20.0).powi(2) + ((y - 30.0) / 10.0).powi(2);
        assert!((f - 1.0).abs() < 1e-13, "{q}: {f}");
    }
    // The rounded rectangle: four lines and four corner quarter ellipses (5 × 8).
    let r = path(&i, 1);
    assert_eq!(r.segments().len(), 8);
    let corner = &r.segments()[1];
    assert_eq!(corner.points[1], flip(50.0, 60.0));
    for k in 0..=50 {
        let q = r.eval(1.0 + f64::from(k) / 50.0);
        let (x, y) = (q.x, 100.0 - q.y);
        // The corner's ellipse is centred on (45, 68).
        let f = ((x - 45.0) / 5.0).powi(2) + ((y - 68.0) / 8.0).powi(2);
        assert!((f - 1.0).abs() < 1e-13, "{q}: {f}");
    }
    // The arcs: each piece at most a quarter turn, the path joined end to end, ending at
    // (90, 70).
    let a = path(&i, 2);
    assert!(a.segments().len() >= 3);
    assert_eq!(a.segments()[0].points[0], flip(60.0, 50.0));
    let end = a.eval(a.domain().1);
    assert!((end - flip(90.0, 70.0)).length() < 1e-12, "{end}");
    for s in a.segments() {
        let w = s.weights.as_ref().expect("arc pieces are rational")[1];
        assert!(
            w >= std::f64::consts::FRAC_1_SQRT_2 - 1e-15,
            "more than 90°: w = {w}"
        );
    }
}

#[test]
fn every_path_command_gives_its_control_points() {
    let i = read(
        r#"<path stroke="black" d="M10 10 l 10 0 H 30 v 10 V 10 C 30 0 40 0 40 10 s 10 10 10 0 Q 55 0 60 10 t 10 0 z m 5 5 h 1"/>"#,
    );
    assert_eq!(i.scene.curves.len(), 2, "two subpaths");
    let p = path(&i, 0);
    assert!(p.is_closed());
    let pts: Vec<Vec<DVec3>> = p.segments().iter().map(|s| s.points.to_vec()).collect();
    let f = |x: f64, y: f64| flip(x, y);
    assert_eq!(
        pts,
        vec![
            vec![f(10.0, 10.0), f(20.0, 10.0)],
            vec![f(20.0, 10.0), f(30.0, 10.0)],
            vec![f(30.0, 10.0), f(30.0, 20.0)],
            vec![f(30.0, 20.0), f(30.0, 10.0)],
            vec![f(30.0, 10.0), f(30.0, 0.0), f(40.0, 0.0), f(40.0, 10.0)],
            // S reflects (40, 0) about (40, 10).
            vec![f(40.0, 10.0), f(40.0, 20.0), f(50.0, 20.0), f(50.0, 10.0)],
            vec![f(50.0, 10.0), f(55.0, 0.0), f(60.0, 10.0)],
            // T reflects (55, 0) about (60, 10).
            vec![f(60.0, 10.0), f(65.0, 20.0), f(70.0, 10.0)],
            // Z closes with a line.
            vec![f(70.0, 10.0), f(10.0, 10.0)],
        ]
    );
    // After Z, m is relative to the subpath's start.
    let q = path(&i, 1);
    assert_eq!(
        q.segments()[0].points.to_vec(),
        vec![f(15.0, 15.0), f(16.0, 15.0)]
    );
    assert!(!q.is_closed());
}

#[test]
fn transforms_groups_and_use_place_the_geometry() {
    let i = read(concat!(
        r#"<defs><path id="seg" d="M 0 0 L 10 0"/></defs>"#,
        r##"<g transform="translate(20 30) scale(2)"><use xlink:href="#seg" x="1" y="2" stroke="blue"/>"##,
        r#"<line x1="0" y1="0" x2="0" y2="5" transform="rotate(90)" stroke="blue"/></g>"#,
        r##"<use href="#seg" transform="matrix(1 0 0 1 5 5)" stroke="blue"/>"##,
    ));
    assert_eq!(i.scene.curves.len(), 3);
    // translate(20, 30) · scale(2) · translate(1, 2): (0, 0) → (22, 34), (10, 0) → (42, 34).
    assert_eq!(
        path(&i, 0).segments()[0].points.to_vec(),
        vec![flip(22.0, 34.0), flip(42.0, 34.0)]
    );
    // rotate(90) takes (0, 5) to (−5, 0); then scale and translate: (10, 30).
    let l = &path(&i, 1).segments()[0].points;
    assert!((l[1] - flip(10.0, 30.0)).length() < 1e-12, "{l:?}");
    assert_eq!(
        path(&i, 2).segments()[0].points.to_vec(),
        vec![flip(5.0, 5.0), flip(15.0, 5.0)]
    );
}

#[test]
fn colours_come_from_attributes_style_sheets_and_gradients() {
    let i = read(concat!(
        r#"<style>.a { stroke: #00ff00 } #b { stroke: rgb(0, 0, 255) }</style>"#,
        r##"<linearGradient id="g"><stop offset="0" stop-color="#123456"/><stop offset="1" stop-color="white"/></linearGradient>"##,
        r#"<path d="M0 0 L1 1" stroke="red" class="a"/>"#,
        r#"<path d="M0 0 L1 1" id="b" class="a" style="stroke: #ff00ff; stroke-opacity: 0.5"/>"#,
        r#"<path d="M0 0 L1 1 L 1 0 z" fill="url(#g)"/>"#,
        r##"<g stroke="#ffff00" opacity="0.5"><path d="M0 0 L1 1" fill="none"/></g>"##,
        r#"<path d="M0 0 L1 1" fill="none"/>"#,
        r#"<path d="M0 0 L1 1"/>"#,
    ));
    let colors: Vec<[u8; 4]> = i
        .scene
        .curves
        .iter()
        .map(|c| c.style.color.to_rgba8())
        .collect();
    assert_eq!(
        colors,
        vec![
            // A class rule beats the presentation attribute.
            [0, 255, 0, 255],
            // The style attribute beats the id rule, with its opacity.
            [255, 0, 255, 128],
            // A gradient fill: its first stop.
            [0x12, 0x34, 0x56, 255],
            // Inherited stroke, the group's opacity.
            [255, 255, 0, 128],
            // (fill none, no stroke: not drawn.) The default fill: black.
            [0, 0, 0, 255],
        ]
    );
}

#[test]
fn what_is_not_a_curve_is_left_out_with_one_warning() {
    let i = read(concat!(
        r#"<text x="0" y="0">hi</text><text>there</text><image href="x.png"/>"#,
        r#"<path d="M0 0 L1 1" stroke="black" filter="url(#f)"/>"#,
    ));
    assert_eq!(i.scene.curves.len(), 1);
    assert_eq!(i.warnings.len(), 1, "{:?}", i.warnings);
    let w = &i.warnings[0];
    assert!(
        w.contains("2 <text>") && w.contains("1 <image>") && w.contains("filter"),
        "{w}"
    );
}

#[test]
fn hostile_files_are_refused_with_the_file_and_the_line() {
    let refused = |text: &str, words: &[&str]| {
        let e = svg::read(text, "bad.svg").expect_err(text);
        let m = e.to_string();
        assert!(m.starts_with("bad.svg:"), "{m}");
        for w in words {
            assert!(m.contains(w), "{m} should say {w}");
        }
    };
    refused("<svg><path", &["bad.svg:1:"]);
    refused("<html/>", &["not an SVG file"]);
    refused(
        r#"<!DOCTYPE svg [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;">]><svg>&b;</svg>"#,
        &["bad.svg:1:"],
    );
    refused(
        "<svg>\n<path d=\"M 0 0 L 1\"/></svg>",
        &["bad.svg:2:", "<path>", "path data"],
    );
    refused("<svg><circle r=\"-1\"/></svg>", &["r = -1", "negative"]);
    refused(
        "<svg><path d=\"M 0 0 L 1e999 0\"/></svg>",
        &["path data", "invalid number"],
    );
    refused(
        r##"<svg xmlns:xlink="http://www.w3.org/1999/xlink"><g id="a"><use xlink:href="#a"/></g></svg>"##,
        &["cycle"],
    );
    refused(
        r##"<svg><use href="#nothing"/></svg>"##,
        &["no element has id"],
    );
    refused(
        r#"<svg><rect width="1" height="1" transform="scale(1e999)"/></svg>"#,
        &["transform"],
    );
    // A thousand nested groups: past the nesting limit, refused at once.
    let deep = format!("<svg>{}{}</svg>", "<g>".repeat(1000), "</g>".repeat(1000));
    refused(&deep, &["nesting", "SPLINESCOPE_MAX_IMPORT_DEPTH"]);
    // References that expand a small file into 10^10 elements: the element limit.
    let mut bomb = String::from(r#"<svg><path id="l0" d="M0 0 L1 1" stroke="black"/>"#);
    for k in 1..=10 {
        bomb += &format!(
            r##"<g id="l{k}">{}</g>"##,
            format!(r##"<use href="#l{}"/>"##, k - 1).repeat(10)
        );
    }
    bomb += "</svg>";
    refused(&bomb, &["SPLINESCOPE_MAX_IMPORT_ELEMENTS"]);
}

/// A curve's arc length (every family; tight accuracy).
fn length(c: &Curve) -> f64 {
    let a = CurveAnalysis::new(c);
    let (t0, t1) = c.domain();
    a.length(t0, t1, 1e-12).expect("a length").value
}

#[test]
fn caps_joins_and_miter_limits_are_the_strokes_with_svgs_defaults() {
    use splinescope_core::ops::{Cap, Join};
    let i = read(
        r#"<g fill="none" stroke="black">
        <line x1="0" y1="0" x2="10" y2="0"/>
        <g stroke-linecap="square" stroke-linejoin="bevel" stroke-miterlimit="2.5">
          <polyline points="0,0 5,5 10,0"/>
          <polyline points="0,0 5,5 10,0" stroke-linejoin="arcs" stroke-miterlimit="5000"/>
        </g>
        <line x1="0" y1="0" x2="10" y2="0" style="stroke-linecap: round; stroke-linejoin: round"/>
        <rect x="0" y="0" width="5" height="5" fill="red" stroke="none"/>
        </g>"#,
    );
    let shapes: Vec<_> = i.scene.curves.iter().map(|c| c.style.stroke).collect();
    // SVG's initial values: butt, miter, 4.
    assert_eq!(
        (shapes[0].cap, shapes[0].join, shapes[0].miter_limit),
        (Cap::Butt, Join::Miter, 4.0)
    );
    assert_eq!(
        (shapes[1].cap, shapes[1].join, shapes[1].miter_limit),
        (Cap::Square, Join::Bevel, 2.5)
    );
    // `arcs` is not read (the inherited bevel stays); a limit past 1000 is drawn at 1000.
    assert_eq!(
        (shapes[2].join, shapes[2].miter_limit),
        (Join::Bevel, 1000.0)
    );
    assert_eq!((shapes[3].cap, shapes[3].join), (Cap::Round, Join::Round));
    // A fill alone is an outline: round, as every scene curve by default.
    assert_eq!((shapes[4].cap, shapes[4].join), (Cap::Round, Join::Round));
}

#[test]
fn a_dashed_stroke_is_its_dashes_cut_exactly_where_the_pattern_says() {
    // A circle of circumference 20π ≈ 62.83 with dashes of 5 and gaps of 3 from offset 0:
    // dashes start every 8 units; the last dash (at 56, on till 61) is whole, the pattern
    // is in its gap at the end, so nothing joins across the start.
    let i = read(
        r#"<circle cx="50" cy="50" r="10" fill="none" stroke="black" stroke-dasharray="5 3"/>"#,
    );
    let n = i.scene.curves.len();
    assert_eq!(
        n,
        8,
        "{:?}",
        i.scene.curves.iter().map(|c| &c.name).collect::<Vec<_>>()
    );
    for (k, c) in i.scene.curves.iter().enumerate() {
        assert_eq!(
            c.name.as_deref(),
            Some(format!("circle (line 1), dash {k}").as_str())
        );
        let l = length(&c.curve);
        assert!((l - 5.0).abs() <= 1e-9, "dash {k}: {l}");
        // Each dash lies on the circle.
        let Curve::Path(p) = &c.curve else {
            panic!("a path")
        };
        assert!(!p.is_closed());
        for t in [0.0, 0.3, 0.77] {
            let q = c.curve.eval(t * p.segments().len() as f64);
            assert!(
                ((q - flip(50.0, 50.0)).length() - 10.0).abs() <= 1e-12,
                "{q}"
            );
        }
    }
    // Offset 2: the path starts 2 into a dash (on till 3), dashes start at 6 + 8k, and the
    // one at 62 is on at the end: it and the first are one dash across the start,
    // 20π − 62 + 3 long; 7 more between.
    let i = read(
        r#"<circle cx="50" cy="50" r="10" fill="none" stroke="black" stroke-dasharray="5 3" stroke-dashoffset="2"/>"#,
    );
    let lengths: Vec<f64> = i.scene.curves.iter().map(|c| length(&c.curve)).collect();
    assert_eq!(lengths.len(), 8, "{lengths:?}");
    assert!(
        (lengths[7] - (20.0 * PI - 59.0)).abs() <= 1e-9,
        "{lengths:?}"
    );
    assert!(
        lengths[..7].iter().all(|l| (l - 5.0).abs() <= 1e-9),
        "{lengths:?}"
    );
    // Dashes are measured in the element's user units, before its transform: scaled by 2,
    // each dash of a line is 8 long in the scene.
    let i = read(
        r#"<line x1="0" y1="0" x2="20" y2="0" transform="scale(2)" stroke="black" stroke-dasharray="4 1"/>"#,
    );
    let lengths: Vec<f64> = i.scene.curves.iter().map(|c| length(&c.curve)).collect();
    assert_eq!(lengths.len(), 4);
    assert!(
        lengths.iter().all(|l| (l - 8.0).abs() <= 1e-12),
        "{lengths:?}"
    );
    // A pattern in em is not read: the stroke is solid, and the warning says so.
    let i = read(r#"<line x1="0" y1="0" x2="20" y2="0" stroke="black" stroke-dasharray="1em"/>"#);
    assert_eq!(i.scene.curves.len(), 1);
    assert!(
        i.warnings
            .iter()
            .any(|w| w.contains("stroke-dasharray in em")),
        "{:?}",
        i.warnings
    );
    // A pattern that would make more dashes than the curve limit is refused naming the
    // element.
    let e = read_result(
        r#"<line x1="0" y1="0" x2="1e9" y2="0" stroke="black" stroke-dasharray="0.001"/>"#,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("test.svg:1") && e.contains("dashes"), "{e}");
}
