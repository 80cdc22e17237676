//! Figures are untrusted input too: tiny sizes, extreme weights and views, names with
//! characters no text format carries, tolerances the fit cannot keep and negative option
//! values each give a well-formed figure or a typed error naming the value — never a
//! panic, a hang, a `NaN` written, or a file written after a failure.

use std::path::{Path, PathBuf};
use std::process::Command;

use glam::{DVec2, DVec3};
use splinescope_core::geom::{Curve, Lower, ParamCurve, RationalBezier};
use splinescope_encoding::camera::{Camera, Camera2d};
use splinescope_figure::{FigureError, FigureOptions, Item, build, pdf, svg};
use splinescope_scene::format::{Scene, SceneCurve, Style, ViewSpec, gallery};

mod common;

/// A scene of one curve, seen whole.
fn scene_of(curve: Curve) -> Scene {
    let mut s = gallery::gallery();
    s.curves = vec![SceneCurve {
        name: None,
        curve,
        style: Style::default_for(0),
    }];
    s.annotations.clear();
    s.view = ViewSpec::Auto;
    s
}

fn tempdir(name: &str) -> PathBuf {
    let dir = common::out_dir("figure-input").join(format!("{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn write_scene(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).expect("write scene");
    p
}

/// Every number of an SVG document's path data, coordinates and sizes, after checking
/// that the document is well-formed XML.
fn svg_numbers(text: &str) -> Vec<f64> {
    let doc = roxmltree::Document::parse(text)
        .unwrap_or_else(|e| panic!("the SVG is not well-formed XML: {e}\n{text}"));
    let mut out = Vec::new();
    for node in doc.descendants().filter(roxmltree::Node::is_element) {
        for attr in node.attributes() {
            if matches!(
                attr.name(),
                "d" | "x" | "y" | "cx" | "cy" | "r" | "width" | "height" | "stroke-width"
            ) {
                for word in attr
                    .value()
                    .split(|c: char| c.is_ascii_alphabetic() && c != 'e' || c == ' ')
                    .filter(|w| !w.is_empty())
                {
                    let v: f64 = word.parse().unwrap_or_else(|_| {
                        panic!("{:?} is not a number in {}", word, attr.value())
                    });
                    out.push(v);
                }
            }
        }
    }
    out
}

/// Runs `pdftoppm` on a PDF file: it must read every operator (exit 0, nothing on stderr).
fn pdf_reads(path: &Path) {
    let out = Command::new("pdftoppm")
        .args(["-r", "10", "-png"])
        .arg(path)
        .arg(path.with_extension("page"))
        .output()
        .expect("pdftoppm (Debian: apt-get install poppler-utils; scripts/test installs it)");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success() && stderr.trim().is_empty(),
        "pdftoppm could not read {}: {stderr}",
        path.display()
    );
}

/// Labels and a legend fit any figure size: on a figure too small for them the labels are
/// hidden (counted) instead of drawn past the page or panicking in the placement (10×10,
/// 50×10, 100×16, 1×1), for the library, `export` (SVG, PDF) and `render`.
#[test]
fn labels_on_tiny_figures() {
    let scene = gallery::gallery();
    for (w, h) in [(10, 10), (50, 10), (100, 16), (1, 1), (3, 17), (17, 3)] {
        let mut opts = FigureOptions::new(w, h);
        opts.labels = true;
        opts.legend = true;
        let fig = build(&scene, &opts).unwrap_or_else(|e| panic!("{w}×{h}: {e}"));
        // Labels with no room are hidden (and counted), never drawn past the page.
        let labels: Vec<&Item> = fig
            .items
            .iter()
            .filter(|i| matches!(i, Item::Text { size, .. } if *size == 12.0))
            .collect();
        for l in &labels {
            if let Item::Text { at, text, .. } = l {
                assert!(
                    at.x >= 0.0 && at.y >= 0.0 && at.x <= f64::from(w) && at.y <= f64::from(h),
                    "{w}×{h}: {text:?} at {at}"
                );
            }
        }
        assert!(
            fig.items.iter().any(|i| matches!(i, Item::Text { .. })),
            "{w}×{h}: no text at all (the legend's rows)"
        );
        svg_numbers(&svg::write(&fig));
    }
    let dir = tempdir("tiny");
    for (w, h) in ["10", "50", "100"].iter().zip(["10", "10", "16"]) {
        for ext in ["svg", "pdf"] {
            let out = dir.join(format!("labels-{w}x{h}.{ext}"));
            let run = common::run(&[
                "export",
                "-o",
                out.to_str().unwrap_or_default(),
                "--width",
                w,
                "--height",
                h,
                "--labels",
                "--legend",
            ]);
            assert_eq!(run.status.code(), Some(0), "{}", common::text(&run));
            if ext == "pdf" {
                pdf_reads(&out);
            }
        }
    }
    common::on_each_gpu("labels_on_tiny_figures", |gpu| {
        let out = dir.join(format!("labels-{}.png", gpu.name));
        let run = common::run(&[
            "render",
            "-o",
            out.to_str().unwrap_or_default(),
            "--width",
            "50",
            "--height",
            "10",
            "--labels",
            "--gpu-backend",
            &gpu.name,
        ]);
        assert_eq!(run.status.code(), Some(0), "{}", common::text(&run));
        assert!(out.exists());
    });
}

fn rational(points: &[[f64; 2]], weights: &[f64]) -> RationalBezier {
    RationalBezier::try_new(
        points.iter().map(|p| DVec3::new(p[0], p[1], 0.0)).collect(),
        weights.to_vec(),
    )
    .expect("valid rational curve")
}

/// A rational curve is the same curve when every weight is scaled alike: weights of
/// 1e300 or 1e-300 evaluate, differentiate and lower as weights near 1 do (the curve
/// scales them by a power of two, exactly), and its figure holds the same path, finite.
#[test]
fn extreme_weights_are_the_same_curve() {
    let pts = [[0.0, 0.0], [1.0, 2.0], [3.0, 0.5], [4.0, 3.0]];
    let base = [1.0, 0.5, 2.0, 1.0];
    let reference = rational(&pts, &base);
    for scale in [1e300, 1e-300, 2f64.powi(1000), 5e-324 * 2f64.powi(60)] {
        let scaled: Vec<f64> = base.iter().map(|w| w * scale).collect();
        let c = rational(&pts, &scaled);
        for k in 0..=20 {
            let t = f64::from(k) / 20.0;
            for (what, a, b) in [
                ("C", c.eval(t), reference.eval(t)),
                ("C'", c.eval_deriv(t), reference.eval_deriv(t)),
                (
                    "C''",
                    c.eval_second_deriv(t),
                    reference.eval_second_deriv(t),
                ),
            ] {
                assert!(
                    a.is_finite() && (a - b).length() <= 1e-12 * (1.0 + b.length()),
                    "weights × {scale:e}: {what}({t}) = {a} against {b}"
                );
            }
        }
        for seg in c.lower() {
            let w = seg.weights.expect("unequal weights stay rational");
            assert!(
                w.iter().all(|w| (0.01..100.0).contains(w)),
                "weights × {scale:e}: lowered weights {w:?}"
            );
        }
        // The figures: the same path data as the unscaled curve's (up to the rounding of
        // the fitted pieces' decimals, within the figure's tolerance), every number finite.
        let scene = |c: &RationalBezier| scene_of(Curve::RationalBezier(c.clone()));
        let opts = FigureOptions::new(400, 300);
        let a = svg_numbers(&svg::write(&build(&scene(&c), &opts).expect("figure")));
        let b = svg_numbers(&svg::write(
            &build(&scene(&reference), &opts).expect("figure"),
        ));
        assert_eq!(a.len(), b.len(), "weights × {scale:e}");
        for (x, y) in a.iter().zip(&b) {
            assert!(
                x.is_finite() && (x - y).abs() <= opts.tolerance,
                "{x} vs {y}"
            );
        }
        let pdf_bytes = pdf::write(&build(&scene(&c), &opts).expect("figure"));
        assert!(!String::from_utf8_lossy(&pdf_bytes).contains("NaN"));
    }
    // The command line: an exported PDF of weights 1e300 reads in pdftoppm.
    let dir = tempdir("weights");
    let scene = write_scene(
        &dir,
        "w.json",
        r#"{"version": 1, "curves": [{"type": "rational_bezier", "points": [[0, 0], [1, 2], [3, 0]], "weights": [1e300, 1e300, 2e300]}]}"#,
    );
    for ext in ["svg", "pdf"] {
        let out = dir.join(format!("w.{ext}"));
        let run = common::run(&[
            "export",
            scene.to_str().unwrap_or_default(),
            "-o",
            out.to_str().unwrap_or_default(),
        ]);
        assert_eq!(run.status.code(), Some(0), "{}", common::text(&run));
        let bytes = std::fs::read(&out).expect("written");
        assert!(!String::from_utf8_lossy(&bytes).contains("NaN"));
        if ext == "pdf" {
            pdf_reads(&out);
        } else {
            assert!(
                svg_numbers(&String::from_utf8_lossy(&bytes))
                    .iter()
                    .all(|v| v.is_finite())
            );
        }
    }
}

/// A view `f64` cannot apply is refused naming it, and nothing is written: a centre at
/// 1e308, a height of 5e-324, a scene of subnormal size under the automatic view.
#[test]
fn views_that_overflow_are_refused() {
    let scene = gallery::gallery();
    let mut opts = FigureOptions::new(640, 400);
    for (center, ppu) in [
        (DVec2::splat(1e308), 100.0),
        (DVec2::ZERO, f64::INFINITY),
        (DVec2::ZERO, 5e-324),
        (DVec2::new(-1e308, 0.0), 1e10),
    ] {
        opts.camera = Some(Camera::Ortho2d(Camera2d {
            center,
            pixels_per_unit: ppu,
        }));
        match build(&scene, &opts) {
            Err(FigureError::View { view, .. }) => {
                assert!(view.contains("centre"), "{view}");
            }
            other => panic!("centre {center}, scale {ppu}: {other:?}"),
        }
    }
    let dir = tempdir("views");
    let tiny = write_scene(
        &dir,
        "tiny.json",
        r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1e-320, 2e-320], [3e-320, 0]]}]}"#,
    );
    let gallery_out = dir.join("v.svg");
    for (scene, view) in [
        (
            None,
            Some(r#"{"kind": "2d", "center": [1e308, 1e308], "height": 4}"#),
        ),
        (
            None,
            Some(r#"{"kind": "2d", "center": [0, 0], "height": 5e-324}"#),
        ),
        (Some(&tiny), None),
    ] {
        for ext in ["svg", "pdf"] {
            let out = gallery_out.with_extension(ext);
            let mut args: Vec<String> = Vec::new();
            args.push("export".into());
            if let Some(s) = scene {
                args.push(s.to_string_lossy().into_owned());
            }
            args.extend(["-o".into(), out.to_string_lossy().into_owned()]);
            if let Some(v) = view {
                args.extend(["--view".into(), v.into()]);
            }
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            let run = common::run(&args);
            let stderr = String::from_utf8_lossy(&run.stderr);
            assert_eq!(
                run.status.code(),
                Some(1),
                "{args:?}: {}",
                common::text(&run)
            );
            assert!(
                stderr.contains("the view") && stderr.contains("f64"),
                "{args:?}: {stderr}"
            );
            assert!(!out.exists(), "{args:?} wrote {}", out.display());
        }
    }
}

/// Names and labels hold text to display: a control character or a noncharacter is
/// refused when the scene is read, naming the field; text made elsewhere is escaped so
/// that the SVG stays well-formed.
#[test]
fn names_with_control_characters() {
    for (bad, code) in [
        ("\\u0001", "U+0001"),
        ("\\u001f", "U+001F"),
        ("\\u0000", "U+0000"),
        ("\\ufffe", "U+FFFE"),
        ("\\n", "U+000A"),
    ] {
        for (text, path) in [
            (
                format!(
                    r#"{{"version": 1, "curves": [{{"name": "a{bad}b", "type": "bezier", "points": [[0, 0], [1, 1]]}}]}}"#
                ),
                "curves[0].name",
            ),
            (
                format!(
                    r#"{{"version": 1, "name": "{bad}", "curves": [{{"type": "bezier", "points": [[0, 0], [1, 1]]}}]}}"#
                ),
                "name",
            ),
            (
                format!(
                    r#"{{"version": 1, "curves": [], "annotations": [{{"points": [[0, 0]], "label": "x{bad}"}}]}}"#
                ),
                "annotations[0].label",
            ),
        ] {
            let e = splinescope_scene::format::from_json_str(&text).expect_err(&text);
            let message = e.to_string();
            assert_eq!(e.path, path, "{message}");
            assert!(message.contains(code), "{message}");
        }
    }
    // A name set in code (not read from a file) with such characters: escaped.
    let mut scene = gallery::gallery();
    scene.curves[0].name = Some("a\u{1}<b>\u{fffe}&\u{0}".into());
    let mut opts = FigureOptions::new(400, 300);
    opts.labels = true;
    opts.legend = true;
    let text = svg::write(&build(&scene, &opts).expect("figure"));
    let doc = roxmltree::Document::parse(&text).expect("well-formed");
    let labels: Vec<&str> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text())
        .collect();
    assert!(
        labels
            .iter()
            .any(|t| t.starts_with("a\u{fffd}<b>\u{fffd}&\u{fffd}")),
        "{labels:?}"
    );
}

/// The adaptive fit has a budget: a tolerance finer than f64 keeps is refused as such, a
/// figure needing more pieces than the budget fails naming the budget and its variable,
/// and a deep zoom spends pieces only where the curve can be seen.
#[test]
fn the_fit_has_a_budget() {
    let dir = tempdir("budget");
    let quintic = write_scene(
        &dir,
        "quintic.json",
        r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1, 2], [3, 0], [4, 3], [5, -1]]}]}"#,
    );
    let q = quintic.to_str().unwrap_or_default();
    let out = dir.join("q.svg");
    let o = out.to_str().unwrap_or_default();
    let run = common::run(&["export", q, "-o", o, "--tolerance", "1e-14"]);
    assert_eq!(run.status.code(), Some(2), "{}", common::text(&run));
    assert!(String::from_utf8_lossy(&run.stderr).contains("tolerance 1e-14: must be"));
    assert!(!out.exists());
    // The finest tolerance: written, within a sensible size.
    let run = common::run(&["export", q, "-o", o, "--tolerance", "1e-6"]);
    assert_eq!(run.status.code(), Some(0), "{}", common::text(&run));
    assert!(std::fs::metadata(&out).expect("written").len() < 1 << 20);
    // Over the budget: refused, nothing written.
    std::fs::remove_file(&out).expect("remove");
    let run = common::bin()
        .args(["export", "-o", o, "--tolerance", "1e-6"])
        .env("SPLINESCOPE_MAX_FIGURE_PIECES", "50")
        .output()
        .expect("run");
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{}", common::text(&run));
    assert!(
        stderr.contains("more than 50 path pieces")
            && stderr.contains("SPLINESCOPE_MAX_FIGURE_PIECES"),
        "{stderr}"
    );
    assert!(!out.exists());
    // A deep zoom onto the curve: only the visible pieces are fitted.
    let curve = Curve::Bezier(splinescope_core::geom::Bezier::new(vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 2.0, 0.0),
        DVec3::new(3.0, 0.0, 0.0),
        DVec3::new(4.0, 3.0, 0.0),
        DVec3::new(5.0, -1.0, 0.0),
    ]));
    let on = curve.eval(0.37);
    for height in [1e-4, 1e-10, 1e-12] {
        let view = format!(
            r#"{{"kind": "2d", "center": [{}, {}], "height": {height}}}"#,
            on.x, on.y
        );
        let run = common::run(&["export", q, "-o", o, "--view", &view]);
        assert_eq!(run.status.code(), Some(0), "{view}: {}", common::text(&run));
        let text = std::fs::read_to_string(&out).expect("written");
        assert!(text.len() < 64 << 10, "{view}: {} bytes", text.len());
        // The visible part passes through the page's centre.
        let numbers = svg_numbers(&text);
        assert!(numbers.iter().all(|v| v.is_finite()));
    }
    // Past what f64 keeps, the fit says so instead of halving forever.
    let mut opts = FigureOptions::new(640, 400);
    opts.camera = Some(Camera::Ortho2d(Camera2d {
        center: on.truncate(),
        pixels_per_unit: 4e18,
    }));
    let steep = scene_of(curve);
    match build(&steep, &opts) {
        Ok(fig) => assert!(fig.check_finite().is_ok()),
        Err(FigureError::Precision { curve, .. }) => assert_eq!(curve, 0),
        Err(e) => panic!("{e}"),
    }
}

/// A negative number is read as the option's value and refused with the option's own
/// message, not as an unknown argument.
#[test]
fn negative_values_are_values() {
    let dir = tempdir("negative");
    let out = dir.join("n.svg");
    let o = out.to_str().unwrap_or_default();
    for (args, want) in [
        (
            vec!["export", "-o", o, "--tolerance", "-1"],
            "tolerance -1: must be",
        ),
        (
            vec!["export", "-o", o, "--tolerance", "-inf"],
            "tolerance -inf: must be",
        ),
        (
            vec!["export", "-o", o, "--width", "-5"],
            "invalid value '-5' for '--width",
        ),
        (
            vec!["render", "-o", o, "--height", "-1"],
            "invalid value '-1' for '--height",
        ),
        (
            vec!["render", "-o", o, "--tolerance-px", "-0.5"],
            "invalid value '-0.5' for '--tolerance-px",
        ),
        (
            vec![
                "eval",
                "scenes/gallery.json",
                "--curve",
                "-1",
                "--samples",
                "3",
            ],
            "invalid value '-1' for '--curve",
        ),
        (
            vec!["bench", "--curves", "-10"],
            "invalid value '-10' for '--curves",
        ),
    ] {
        let run = common::run(&args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(
            run.status.code(),
            Some(2),
            "{args:?}: {}",
            common::text(&run)
        );
        assert!(stderr.contains(want), "{args:?}: {stderr}");
        assert!(
            !stderr.contains("unexpected argument"),
            "{args:?}: {stderr}"
        );
        assert!(!out.exists());
    }
}

/// A width in scene units is written in output points: the width times the points one
/// unit spans in the figure's view (a 2D view of height 10 on a figure 800 high: 80).
#[test]
fn a_width_in_scene_units_scales_with_the_view() {
    use splinescope_core::geom::Bezier;
    let mut scene = scene_of(Curve::Bezier(Bezier::new(vec![
        DVec3::new(-2.0, 0.0, 0.0),
        DVec3::new(0.0, 2.0, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
    ])));
    scene.view = ViewSpec::TwoD {
        center: DVec2::ZERO,
        height: 10.0,
    };
    scene.curves[0].style.width = 0.25;
    scene.curves[0].style.width_in_scene = true;
    let fig = build(&scene, &FigureOptions::new(1200, 800)).expect("builds");
    let widths: Vec<f32> = fig
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Path {
                stroke,
                curve: Some(0),
                ..
            } => Some(stroke.width_px),
            _ => None,
        })
        .collect();
    assert_eq!(widths.len(), 1, "{widths:?}");
    assert!((widths[0] - 20.0).abs() <= 1e-4, "{widths:?}");
    // In pixels, as it is.
    scene.curves[0].style.width_in_scene = false;
    let fig = build(&scene, &FigureOptions::new(1200, 800)).expect("builds");
    assert!(fig.items.iter().any(|i| matches!(i, Item::Path { stroke, curve: Some(0), .. } if (stroke.width_px - 0.25).abs() < 1e-6)));
}
