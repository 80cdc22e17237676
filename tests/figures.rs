//! Figures (`splinescope export`, splinescope-figure): the SVG rasterised with resvg and
//! the PDF rasterised with pdftoppm look like `render`'s PNG of the same scene and camera
//! (FLIP tolerance below) on every backend; the written path data, read back, lies within
//! the tolerance of the exact curve at dense parameters, exact commands carry the very
//! control points; bad arguments are refused with nothing written.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use glam::{DVec2, DVec3};

use splinescope_core::geom::{Lower, ParamCurve};
use splinescope_figure::fit::Projection;
use splinescope_figure::{FigureOptions, build, pdf, svg};
use splinescope_image::RgbaImage;
use splinescope_image::compare::{Tolerance, compare_images};
use splinescope_scene::format::{Scene, gallery};

/// Rasterisers differ from the GPU in edge coverage (and PDF viewers in stroke
/// adjustment: poppler widens thin strokes, where the GPU's layer covers each edge pixel
/// once — FLIP 0.0205 on the gallery's PDF); a missing, moved or restyled curve changes
/// far more than this.
const FIGURE_TOLERANCE: &str = "channel=24,pixels=3%,flip=0.025";

fn scenes() -> Vec<(String, Scene)> {
    let mut out = vec![("gallery".to_owned(), gallery::gallery())];
    let mut paths: Vec<PathBuf> =
        std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes"))
            .expect("scenes/")
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|e| e == "json"))
            .collect();
    paths.sort();
    for p in paths {
        let name = p
            .file_stem()
            .unwrap_or_default()
            .to_string_lossy()
            .into_owned();
        out.push((name, Scene::load(&p).expect("a shipped scene loads")));
    }
    out
}

fn rasterise_pdf(bytes: &[u8], dir: &Path) -> RgbaImage {
    let pdf_path = dir.join("figure.pdf");
    std::fs::write(&pdf_path, bytes).expect("write the PDF");
    let out = Command::new("pdftoppm")
        .args(["-png", "-r", "72", "-singlefile"])
        .arg(&pdf_path)
        .arg(dir.join("figure"))
        .output()
        .unwrap_or_else(|e| {
            panic!(
                "pdftoppm is needed to check PDF figures ({e}): sudo apt-get install poppler-utils"
            )
        });
    assert!(
        out.status.success(),
        "pdftoppm: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    RgbaImage::read_png(&dir.join("figure.png")).expect("pdftoppm's PNG")
}

/// Text rasterisers differ in hinting and gamma on every glyph edge; a label set in the
/// wrong place or size moves whole glyphs, far beyond this.
const TEXT_TOLERANCE: &str = "channel=24,pixels=10%,flip=0.05";

fn check_like(name: &str, what: &str, actual: &RgbaImage, reference: &RgbaImage) {
    check_within(name, what, actual, reference, FIGURE_TOLERANCE);
}

fn check_within(
    name: &str,
    what: &str,
    actual: &RgbaImage,
    reference: &RgbaImage,
    tolerance: &str,
) {
    let tol: Tolerance = tolerance.parse().expect("tolerance");
    let (c, images) = compare_images(actual, reference, &tol).expect("same size");
    if !c.matches {
        let dir = common::out_dir("figures");
        actual
            .write_png(&dir.join(format!("{name}.{what}.actual.png")))
            .ok();
        reference
            .write_png(&dir.join(format!("{name}.{what}.render.png")))
            .ok();
        images
            .diff
            .write_png(&dir.join(format!("{name}.{what}.diff.png")))
            .ok();
        panic!(
            "{name}: the {what} figure differs from its reference beyond {tolerance}: {c:?} (images in {})",
            dir.display()
        );
    }
}

#[test]
fn svg_and_pdf_figures_look_like_the_rendered_png() {
    let (w, h) = (480, 320);
    common::on_each_gpu("figures look like render", |backend| {
        let dir = tempdir();
        for (name, scene) in scenes() {
            let png = splinescope_render::render(
                &backend.ctx,
                &backend.pipelines,
                &scene,
                &splinescope_render::RenderRequest::new(w, h),
            )
            .expect("render");
            let fig = build(&scene, &FigureOptions::new(w, h)).expect("figure");
            let name = format!("{name}.{}", backend.name);
            check_like(
                &name,
                "svg",
                &common::rasterise_svg(&svg::write(&fig), w, h),
                &png,
            );
            check_like(&name, "pdf", &rasterise_pdf(&pdf::write(&fig), &dir), &png);
        }
    });
}

/// The numbers of one path's data, by command.
fn parse_path(d: &str) -> Vec<(char, Vec<f64>)> {
    let mut out: Vec<(char, Vec<f64>)> = Vec::new();
    let mut number = String::new();
    let flush = |number: &mut String, out: &mut Vec<(char, Vec<f64>)>| {
        if !number.is_empty() {
            let v: f64 = number.parse().expect("a number");
            out.last_mut().expect("a command first").1.push(v);
            number.clear();
        }
    };
    for ch in d.chars() {
        if "MLQC".contains(ch) {
            flush(&mut number, &mut out);
            out.push((ch, Vec::new()));
        } else if ch == 'Z' {
            // A closed curve's close: its run already ends where it starts.
            flush(&mut number, &mut out);
        } else if ch == ' ' {
            flush(&mut number, &mut out);
        } else {
            number.push(ch);
        }
    }
    flush(&mut number, &mut out);
    out
}

/// Each curve's path data, by curve index.
fn curve_paths(text: &str) -> Vec<(usize, String)> {
    text.lines()
        .filter_map(|l| {
            let rest = l.split_once("<path id=\"curve-")?.1;
            let (index, rest) = rest.split_once('"')?;
            let d = rest.split_once("d=\"")?.1.split_once('"')?.0;
            Some((index.parse().ok()?, d.to_owned()))
        })
        .collect()
}

/// Points along a path's commands (each command sampled at `k` parameters).
fn path_points(cmds: &[(char, Vec<f64>)], k: usize) -> Vec<DVec2> {
    let mut out = Vec::new();
    let mut cur = DVec2::ZERO;
    for (c, v) in cmds {
        let p: Vec<DVec2> = v.chunks(2).map(|c| DVec2::new(c[0], c[1])).collect();
        let ctrl: Vec<DVec2> = std::iter::once(cur).chain(p.iter().copied()).collect();
        if *c == 'M' {
            cur = p[0];
            out.push(cur);
            continue;
        }
        for j in 1..=k {
            let u = j as f64 / k as f64;
            let mut b = ctrl.clone();
            for r in 1..b.len() {
                for i in 0..b.len() - r {
                    b[i] = b[i] * (1.0 - u) + b[i + 1] * u;
                }
            }
            out.push(b[0]);
        }
        cur = *p.last().expect("an end point");
    }
    out
}

/// The largest distance from a point of `points` (in order along a curve) to the
/// polyline `line` (the same curve, in order): each point is matched within a window that
/// follows the previous match, so the sweep is linear.
fn sweep_distance(points: &[DVec2], line: &[DVec2]) -> f64 {
    const WINDOW: usize = 4000;
    let mut at = 0usize;
    let mut worst = 0.0_f64;
    for p in points {
        let lo = at.saturating_sub(WINDOW);
        let hi = (at + WINDOW).min(line.len().saturating_sub(1));
        let (mut best, mut best_i) = (f64::INFINITY, at);
        for i in lo..hi.max(lo + 1).min(line.len().saturating_sub(1)) {
            let d = distance_to_polyline(*p, &line[i..i + 2]);
            if d < best {
                best = d;
                best_i = i;
            }
        }
        at = best_i;
        worst = worst.max(best);
    }
    worst
}

fn distance_to_polyline(p: DVec2, line: &[DVec2]) -> f64 {
    line.windows(2)
        .map(|w| {
            let d = w[1] - w[0];
            let t = if d.length_squared() > 0.0 {
                ((p - w[0]).dot(d) / d.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (w[0] + t * d - p).length()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Every written piece lies within the tolerance of the exact curve (dense parameters of
/// the exact curve, projected), and the exact curve within the tolerance of the pieces;
/// in 2D views every segment of degree ≤ 3 is written with its projected control points,
/// bit for bit.
#[test]
fn written_paths_keep_the_tolerance_and_exact_control_points() {
    let (w, h) = (640.0, 400.0);
    for tolerance in [0.01, 0.5] {
        for (name, scene) in scenes() {
            let mut opts = FigureOptions::new(w as u32, h as u32);
            opts.tolerance = tolerance;
            let fig = build(&scene, &opts).expect("figure");
            let proj: Projection = fig.projection;
            let text = svg::write(&fig);
            for (index, d) in curve_paths(&text) {
                let curve = &scene.curves[index].curve;
                let cmds = parse_path(&d);
                // The exact curve, densely: its own evaluation, projected.
                let (a, b) = curve.domain();
                let exact: Vec<DVec2> = (0..=40_000)
                    .filter_map(|j| proj.point(curve.eval(a + (b - a) * f64::from(j) / 40_000.0)))
                    .collect();
                let written = path_points(&cmds, 64);
                // The dense polylines are within ~1e-4 pt of their curves here.
                let slack = 2e-3;
                let worst = sweep_distance(&written, &exact);
                assert!(
                    worst <= tolerance + slack,
                    "{name} curve {index}, T = {tolerance}: a written point is {worst} pt from the curve"
                );
                let dense = path_points(&cmds, 2048);
                let back = sweep_distance(
                    &exact.iter().step_by(7).copied().collect::<Vec<_>>(),
                    &dense,
                );
                assert!(
                    back <= tolerance + slack,
                    "{name} curve {index}, T = {tolerance}: the curve is {back} pt from the path"
                );
                if proj.affine {
                    let segs = curve.lower();
                    // Polynomial pieces of degree ≤ 3 are written exactly (rational
                    // ones are fitted, checked against the tolerance above).
                    if segs
                        .iter()
                        .all(|s| s.bezier.degree() <= 3 && !s.is_rational())
                    {
                        let mut want: Vec<f64> = Vec::new();
                        for (k, s) in segs.iter().enumerate() {
                            let pts: Vec<DVec2> = s
                                .bezier
                                .points()
                                .iter()
                                .filter_map(|&p| proj.point(p))
                                .collect();
                            let skip = usize::from(k > 0 && Some(pts[0]) == want_end(&want));
                            for p in &pts[skip..] {
                                want.extend([p.x, p.y]);
                            }
                        }
                        let got: Vec<f64> =
                            cmds.iter().flat_map(|(_, v)| v.iter().copied()).collect();
                        assert_eq!(
                            got.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                            want.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                            "{name} curve {index}: exact control points"
                        );
                    }
                }
            }
        }
    }
}

fn want_end(v: &[f64]) -> Option<DVec2> {
    (v.len() >= 2).then(|| DVec2::new(v[v.len() - 2], v[v.len() - 1]))
}

/// A high-degree segment takes more pieces for a smaller tolerance, and a 3D view's
/// perspective bends even straight lines' parameterisation but keeps lines straight.
#[test]
fn pieces_follow_the_tolerance() {
    let bez = splinescope_core::geom::Bezier::new(
        (0..=12)
            .map(|i| DVec3::new(f64::from(i), if i % 2 == 0 { 0.0 } else { 4.0 }, 0.0))
            .collect(),
    );
    let proj = Projection {
        rows: [
            [30.0, 0.0, 0.0, 10.0],
            [0.0, -30.0, 0.0, 200.0],
            [0.0, 0.0, 0.0, 1.0],
        ],
        affine: true,
    };
    let count = |t: f64| {
        let mut budget = splinescope_figure::fit::Budget::new(1 << 20);
        splinescope_figure::fit::segment_pieces(&bez, None, &proj, t, None, &mut budget)
            .expect("within the budget")
            .expect("in front")
            .len()
    };
    let (coarse, fine) = (count(1.0), count(0.001));
    assert!(coarse >= 1 && fine > coarse, "{coarse} vs {fine}");
    // Halving pieces: 4⁴ = 256 times finer needs 2⁴/2 … more pieces than ~ (256)^(1/4).
    assert!(fine <= coarse * 64, "{coarse} vs {fine}");
}

fn tempdir() -> PathBuf {
    static NEXT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = common::out_dir("figures-tmp").join(format!("{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

#[test]
fn export_refuses_bad_arguments_and_writes_nothing() {
    let bin = env!("CARGO_BIN_EXE_splinescope");
    let dir = tempdir();
    let run = |args: &[&str]| Command::new(bin).args(args).output().expect("run");
    let txt = dir.join("figure.txt");
    let out = run(&["export", "-o", txt.to_str().unwrap_or_default()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&out.stderr)
            .contains("unknown output format .txt (expected .svg, .pdf, .png or .dxf)")
    );
    assert!(!txt.exists());
    for t in ["0", "-1", "nan", "inf"] {
        let svg_path = dir.join("t.svg");
        let arg = format!("--tolerance={t}");
        let out = run(&["export", "-o", svg_path.to_str().unwrap_or_default(), &arg]);
        assert_eq!(out.status.code(), Some(2), "{t}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains("--tolerance"),
            "{t}"
        );
        assert!(!svg_path.exists());
    }
    let missing = dir.join("no").join("such").join("dir").join("f.svg");
    let out = run(&["export", "-o", missing.to_str().unwrap_or_default()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot write"));
    // An existing file stays as it was when the export fails.
    let kept = dir.join("kept.svg");
    std::fs::write(&kept, "old").expect("write");
    let out = run(&[
        "export",
        "no-such-scene.json",
        "-o",
        kept.to_str().unwrap_or_default(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(std::fs::read_to_string(&kept).expect("read"), "old");
    // A good export writes an SVG and a PDF.
    for ext in ["svg", "pdf"] {
        let f = dir.join(format!("ok.{ext}"));
        let out = run(&["export", "-o", f.to_str().unwrap_or_default()]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let bytes = std::fs::read(&f).expect("written");
        assert!(bytes.starts_with(if ext == "svg" { b"<svg" } else { b"%PDF" }));
    }
}

fn rasterise_svg_with_font(text: &str, w: u32, h: u32) -> RgbaImage {
    let mut opts = resvg::usvg::Options::default();
    opts.fontdb_mut()
        .load_font_data(splinescope_figure::text::FONT.to_vec());
    let tree = resvg::usvg::Tree::from_str(text, &opts).expect("the SVG parses");
    let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h).expect("pixmap");
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    RgbaImage {
        width: w,
        height: h,
        data: pixmap.data().to_vec(),
    }
}

/// Labels, legend, axes and grid: SVG keeps them as text (every label written), the PDF
/// embeds a subset of the font and its text extracts as written, and the two writers put
/// the text in the same places (their rasters agree within the figure tolerance).
#[test]
fn text_is_text_in_svg_and_embedded_in_pdf_and_both_agree() {
    let dir = tempdir();
    let (w, h) = (900, 600);
    for (name, scene) in scenes() {
        let mut opts = FigureOptions::new(w, h);
        opts.labels = true;
        opts.legend = true;
        let planar = matches!(
            scene.camera(DVec2::new(f64::from(w), f64::from(h))),
            splinescope_encoding::camera::Camera::Ortho2d(_)
        );
        opts.axes = planar;
        opts.grid = planar;
        let fig = build(&scene, &opts).expect("figure");
        let text = svg::write(&fig);
        // Every label is text in the SVG, or counted among the hidden ones.
        let hidden: usize = text
            .split("</text>")
            .find_map(|t| {
                let t = t.rsplit('>').next()?;
                t.strip_suffix(" labels hidden")
                    .or_else(|| t.strip_suffix(" label hidden"))
                    .and_then(|n| n.parse().ok())
            })
            .unwrap_or(0);
        let shown = scene
            .curves
            .iter()
            .filter(|sc| {
                let label = sc.label().replace('&', "&amp;").replace('<', "&lt;");
                text.contains(&format!(">{label}</text>"))
            })
            .count();
        assert!(
            shown + hidden >= scene.curves.len() && shown > 0,
            "{name}: {shown} labels as SVG text, {hidden} hidden, of {}",
            scene.curves.len()
        );
        let bytes = pdf::write(&fig);
        let pdf_path = dir.join("text.pdf");
        std::fs::write(&pdf_path, &bytes).expect("write");
        let fonts = Command::new("pdffonts")
            .arg(&pdf_path)
            .output()
            .expect("pdffonts (poppler-utils)");
        let fonts = String::from_utf8_lossy(&fonts.stdout);
        assert!(
            fonts.contains("SPLSCP+Ubuntu-Light")
                && fonts.contains("CID TrueType")
                && fonts.contains(" yes yes yes "),
            "{name}: the font is embedded as a subset with a ToUnicode map: {fonts}"
        );
        let out = Command::new("pdftotext")
            .args(["-raw"])
            .arg(&pdf_path)
            .arg("-")
            .output()
            .expect("pdftotext (poppler-utils)");
        let extracted = String::from_utf8_lossy(&out.stdout).replace(char::is_whitespace, "");
        for sc in scene.curves.iter().take(10) {
            let label = sc.label().replace(char::is_whitespace, "");
            assert!(
                extracted.contains(&label),
                "{name}: PDF text {label:?} in {extracted:?}"
            );
        }
        let a = rasterise_svg_with_font(&text, w, h);
        let b = rasterise_pdf(&bytes, &dir);
        check_within(
            &format!("{name}.text"),
            "svg-vs-pdf",
            &a,
            &b,
            TEXT_TOLERANCE,
        );
    }
    // Axes in a 3D view are refused, naming why.
    let scene = Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/bezier3d.json"))
        .expect("scene");
    let mut opts = FigureOptions::new(w, h);
    opts.axes = true;
    let e = build(&scene, &opts).expect_err("3D axes");
    assert!(e.to_string().contains("2D views only"), "{e}");
}

/// `render --labels` writes each label into the PNG: pixels change where the labels go
/// and nowhere near the curves' other ends.
#[test]
fn rendered_png_carries_the_labels() {
    let scene = gallery::gallery();
    let (w, h) = (900, 600);
    common::on_each_gpu("rendered labels", |backend| {
        let plain = splinescope_render::render(
            &backend.ctx,
            &backend.pipelines,
            &scene,
            &splinescope_render::RenderRequest::new(w, h),
        )
        .expect("render");
        let labelled = splinescope_render::render(
            &backend.ctx,
            &backend.pipelines,
            &scene,
            &splinescope_render::RenderRequest::new(w, h).with_text(
                splinescope_figure::TextOptions {
                    labels: true,
                    ..Default::default()
                },
            ),
        )
        .expect("labels");
        let mut opts = FigureOptions::new(w, h);
        opts.labels = true;
        let fig = build(&scene, &opts).expect("figure");
        let mut texts = 0;
        for item in &fig.items[fig.front..] {
            if let splinescope_figure::Item::Text {
                at,
                size,
                text,
                anchor,
                ..
            } = item
            {
                texts += 1;
                let tw = splinescope_figure::text::width(text, *size);
                let x0 = match anchor {
                    splinescope_figure::Anchor::Start => at.x,
                    splinescope_figure::Anchor::Middle => at.x - tw / 2.0,
                    splinescope_figure::Anchor::End => at.x - tw,
                };
                let changed = (0..(tw as u32))
                    .flat_map(|dx| (0..(*size as u32)).map(move |dy| (dx, dy)))
                    .filter(|(dx, dy)| {
                        let (x, y) = (x0 as u32 + dx, (at.y - size) as u32 + dy);
                        x < w && y < h && labelled.pixel(x, y) != plain.pixel(x, y)
                    })
                    .count();
                assert!(
                    changed > 20,
                    "{}: label {text:?} drew {changed} pixels",
                    backend.name
                );
            }
        }
        assert_eq!(texts, scene.curves.len());
    });
}

/// `--view` gives the camera (the scene format's view object, checked as in a scene
/// file); the figure is the one of that view.
#[test]
fn export_takes_a_given_view() {
    let bin = env!("CARGO_BIN_EXE_splinescope");
    let dir = tempdir();
    let scene_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper002_examples.json");
    let out = dir.join("view.svg");
    let view = r#"{"kind": "2d", "center": [3, 3], "height": 4}"#;
    let run = Command::new(bin)
        .args(["export", scene_path.to_str().unwrap_or_default(), "-o"])
        .arg(&out)
        .args(["--width", "600", "--height", "400", "--view", view])
        .output()
        .expect("run");
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let mut scene = Scene::load(&scene_path).expect("scene");
    scene.view = splinescope_scene::format::ViewSpec::TwoD {
        center: DVec2::new(3.0, 3.0),
        height: 4.0,
    };
    let want = svg::write(&build(&scene, &FigureOptions::new(600, 400)).expect("figure"));
    assert_eq!(std::fs::read_to_string(&out).expect("written"), want);
    for (bad, says) in [
        (
            r#"{"kind": "2d", "center": [3, 3], "height": -4}"#,
            "height: must be greater than 0",
        ),
        (r#"{"kind": "4d"}"#, "unknown view kind"),
        ("x", "is not JSON"),
    ] {
        let o = dir.join("bad.svg");
        let run = Command::new(bin)
            .args(["export", "-o"])
            .arg(&o)
            .args(["--view", bad])
            .output()
            .expect("run");
        assert_eq!(run.status.code(), Some(1), "{bad}");
        assert!(
            String::from_utf8_lossy(&run.stderr).contains(says),
            "{bad}: {}",
            String::from_utf8_lossy(&run.stderr)
        );
        assert!(!o.exists());
    }
}

/// The PDF's own path data, read back from its content stream: each curve's commands
/// (between its stroke colour and `S`) lie within the tolerance of the exact curve too —
/// the decimals PDF allows included.
#[test]
fn pdf_path_data_keeps_the_tolerance() {
    let (w, h) = (640.0, 400.0);
    for (name, scene) in scenes() {
        let mut opts = FigureOptions::new(w as u32, h as u32);
        opts.switches = splinescope_encoding::draw::Switches {
            polygons: false,
            points: false,
        };
        let fig = build(&scene, &opts).expect("figure");
        let bytes = pdf::write(&fig);
        let text = String::from_utf8_lossy(&bytes);
        // Every stroked path, in order.
        let mut paths: Vec<Vec<(char, Vec<f64>)>> = Vec::new();
        let mut current: Vec<(char, Vec<f64>)> = Vec::new();
        let mut numbers: Vec<f64> = Vec::new();
        for token in text.split_whitespace() {
            match token {
                "m" | "l" | "c" => {
                    let cmd = match token {
                        "m" => 'M',
                        "l" => 'L',
                        _ => 'C',
                    };
                    current.push((cmd, std::mem::take(&mut numbers)));
                }
                "S" => {
                    paths.push(std::mem::take(&mut current));
                    numbers.clear();
                }
                _ => match token.parse::<f64>() {
                    Ok(v) => numbers.push(v),
                    Err(_) => numbers.clear(),
                },
            }
        }
        let drawn: Vec<usize> = fig
            .items
            .iter()
            .filter_map(|i| match i {
                splinescope_figure::Item::Path {
                    runs,
                    curve: Some(c),
                    ..
                } if !runs.is_empty() => Some(*c),
                _ => None,
            })
            .collect();
        // Overlay polylines (the 3D axis triad) come first, the curves last.
        assert!(
            paths.len() >= drawn.len(),
            "{name}: one stroked path per curve"
        );
        let curves = &paths[paths.len() - drawn.len()..];
        for (cmds, index) in curves.iter().zip(drawn) {
            let curve = &scene.curves[index].curve;
            let (a, b) = curve.domain();
            let exact: Vec<DVec2> = (0..=40_000)
                .filter_map(|j| {
                    fig.projection
                        .point(curve.eval(a + (b - a) * f64::from(j) / 40_000.0))
                })
                .collect();
            let worst = sweep_distance(&path_points(cmds, 64), &exact);
            assert!(
                worst <= fig.tolerance + 2e-3,
                "{name} curve {index}: {worst} pt from the curve"
            );
        }
    }
}

/// Word boxes `(xMin, yMin, xMax, yMax, word)` as `pdftotext -bbox` reads them from a PDF.
fn pdf_words(bytes: &[u8], dir: &Path) -> Vec<(f64, f64, f64, f64, String)> {
    let pdf = dir.join("words.pdf");
    std::fs::write(&pdf, bytes).expect("write the PDF");
    let out = Command::new("pdftotext")
        .args(["-bbox"])
        .arg(&pdf)
        .arg("-")
        .output()
        .unwrap_or_else(|e| {
            panic!(
                "pdftotext is needed to read a PDF's text ({e}): sudo apt-get install poppler-utils"
            )
        });
    assert!(
        out.status.success(),
        "pdftotext: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let number = |tag: &str, key: &str| -> f64 {
        let at = tag.find(&format!("{key}=\"")).expect("attribute") + key.len() + 2;
        tag[at..at + tag[at..].find('"').expect("quote")]
            .parse()
            .expect("a number")
    };
    text.lines()
        .filter_map(|l| {
            let l = l.trim();
            let body = l.strip_prefix("<word ")?;
            let (tag, rest) = body.split_once('>')?;
            let word = rest.strip_suffix("</word>")?.to_owned();
            Some((
                number(tag, "xMin"),
                number(tag, "yMin"),
                number(tag, "xMax"),
                number(tag, "yMax"),
                word,
            ))
        })
        .collect()
}

/// Text boxes of an SVG's `<text>` elements from the font's metrics (advance widths, an
/// ascent of one size and a descent of a quarter): `(min, max, text, size)`.
fn svg_text_boxes(svg: &str) -> Vec<(DVec2, DVec2, String, f64)> {
    let attr = |tag: &str, key: &str| -> Option<String> {
        let at = tag.find(&format!(" {key}=\""))? + key.len() + 3;
        Some(tag[at..at + tag[at..].find('"')?].to_owned())
    };
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(start) = rest.find("<text ") {
        let after = &rest[start..];
        let (tag, tail) = after.split_once('>').expect("a closed tag");
        let (content, tail) = tail.split_once("</text>").expect("a closed text");
        let x: f64 = attr(tag, "x").expect("x").parse().expect("x");
        let y: f64 = attr(tag, "y").expect("y").parse().expect("y");
        let size: f64 = attr(tag, "font-size").expect("size").parse().expect("size");
        let content = content
            .replace("&amp;", "&")
            .replace("&lt;", "<")
            .replace("&gt;", ">");
        let w = splinescope_figure::text::width(&content, size);
        let left = match attr(tag, "text-anchor").as_deref() {
            Some("end") => x - w,
            Some("middle") => x - 0.5 * w,
            _ => x,
        };
        out.push((
            DVec2::new(left, y - size),
            DVec2::new(left + w, y + 0.25 * size),
            content,
            size,
        ));
        rest = tail;
    }
    out
}

/// The gallery and crowded generated scenes with every label and the legend, at several
/// page sizes: read back from the written files — the PDF's words by `pdftotext -bbox`,
/// the SVG's texts by the font's metrics — no text box overlaps another (beyond half a
/// point of rounding), none leaves the page, and every curve's label is either on the
/// page or counted in the legend's "N labels hidden".
#[test]
fn labels_never_overlap_on_the_written_page() {
    use splinescope_scene::format::generate::{StressOptions, random_bezier_scene};
    let dir = tempdir();
    let mut cases = vec![
        ("gallery", gallery::gallery(), 1200, 800),
        ("gallery small", gallery::gallery(), 640, 400),
        (
            "gallery with axes, combs and markers",
            gallery::gallery(),
            1000,
            700,
        ),
    ];
    for (curves, seed) in [(30, 1), (80, 2)] {
        let mut scene = random_bezier_scene(StressOptions {
            curves,
            degree: 3,
            seed,
            ..Default::default()
        });
        for (i, c) in scene.curves.iter_mut().enumerate() {
            c.name = Some(format!("curve {i} of the crowd"));
        }
        cases.push(("crowd", scene, 600, 400));
    }
    let apart = |a: (f64, f64, f64, f64), b: (f64, f64, f64, f64)| {
        let e = 0.5;
        a.2 - e <= b.0 || b.2 - e <= a.0 || a.3 - e <= b.1 || b.3 - e <= a.1
    };
    for (name, scene, w, h) in cases {
        let mut opts = FigureOptions::new(w, h);
        opts.labels = true;
        opts.legend = true;
        if name.contains("axes") {
            opts.axes = true;
            opts.grid = true;
            opts.shape.comb = Some(splinescope_scene::format::shape::CombScale::Auto);
            opts.shape.inflections = true;
            opts.shape.curvature_extrema = true;
            opts.shape.intersections = true;
        }
        let fig = build(&scene, &opts).expect("figure");
        let what = format!("{name} ({} curves, {w}×{h})", scene.curves.len());
        // SVG: the font's metrics.
        let boxes = svg_text_boxes(&svg::write(&fig));
        assert!(!boxes.is_empty(), "{what}: no text");
        for (i, a) in boxes.iter().enumerate() {
            assert!(
                a.0.x >= -0.5
                    && a.0.y >= -0.5
                    && a.1.x <= f64::from(w) + 0.5
                    && a.1.y <= f64::from(h) + 0.5,
                "{what}: {:?} leaves the page",
                a.2
            );
            for b in &boxes[i + 1..] {
                assert!(
                    apart((a.0.x, a.0.y, a.1.x, a.1.y), (b.0.x, b.0.y, b.1.x, b.1.y)),
                    "{what}: SVG texts {:?} and {:?} overlap",
                    a.2,
                    b.2
                );
            }
        }
        // Every label drawn (the canvas's labels are set at 12 points, the legend's rows
        // at 11) or counted as hidden in the legend.
        let hidden: usize = boxes
            .iter()
            .find_map(|b| {
                b.2.strip_suffix(" labels hidden")
                    .or_else(|| b.2.strip_suffix(" label hidden"))
                    .map(|n| n.parse().expect("a count"))
            })
            .unwrap_or(0);
        let labels: Vec<&String> = boxes.iter().filter(|b| b.3 == 12.0).map(|b| &b.2).collect();
        assert_eq!(
            labels.len() + hidden,
            scene.curves.len(),
            "{what}: {} labels drawn, {hidden} hidden",
            labels.len()
        );
        for l in &labels {
            assert!(
                scene.curves.iter().any(|c| c.label() == **l),
                "{what}: {l:?} is no curve's label"
            );
        }
        // PDF: pdftotext's word boxes.
        let words = pdf_words(&pdf::write(&fig), &dir);
        assert!(!words.is_empty(), "{what}: no words in the PDF");
        for (i, a) in words.iter().enumerate() {
            for b in &words[i + 1..] {
                assert!(
                    apart((a.0, a.1, a.2, a.3), (b.0, b.1, b.2, b.3)),
                    "{what}: PDF words {:?} and {:?} overlap",
                    a.4,
                    b.4
                );
            }
        }
        println!(
            "{what}: {} texts, {hidden} labels hidden, no overlap",
            boxes.len()
        );
    }
}

/// The labels of a rendered PNG, measured from its pixels: a crowded scene whose curves
/// each have their own colour (so each label's text has its own), drawn by `render`'s
/// path (the GPU's picture, then the text); the pixels the labels change, attributed to
/// the label whose colour they are nearest (within a margin that leaves out leader lines
/// and anti-aliased edges), give each label's box — and no two boxes overlap.
#[test]
fn rendered_labels_never_overlap_in_the_png() {
    use splinescope_scene::format::generate::{StressOptions, random_bezier_scene};
    let mut crowd = random_bezier_scene(StressOptions {
        curves: 18,
        degree: 3,
        seed: 5,
        ..Default::default()
    });
    for (i, c) in crowd.curves.iter_mut().enumerate() {
        c.name = Some(format!("curve number {i}"));
        c.style.show_polygon = false;
        c.style.show_points = false;
    }
    png_labels_apart("crowd", crowd, (640, 420));
    png_labels_apart("gallery", gallery::gallery(), (1200, 800));
}

/// [`rendered_labels_never_overlap_in_the_png`] on one scene, its curves recoloured with
/// hues spread evenly round the circle.
fn png_labels_apart(what: &str, mut scene: Scene, (w, h): (u32, u32)) {
    let step = 360.0 / scene.curves.len().max(1) as f32;
    for (i, c) in scene.curves.iter_mut().enumerate() {
        let hue = i as f32 * step;
        let f = |n: f32| {
            let k = (n + hue / 60.0) % 6.0;
            0.9 - 0.9 * k.min(4.0 - k).clamp(0.0, 1.0)
        };
        c.style.color = splinescope_encoding::Color([f(5.0), f(3.0), f(1.0), 1.0]);
    }
    // The hue of each label's text (the curve's colour, darkened: the same hue).
    let hue_of = |[r, g, b]: [f32; 3]| -> (f32, f32) {
        let (max, min) = (r.max(g).max(b), r.min(g).min(b));
        let s = if max > 0.0 { (max - min) / max } else { 0.0 };
        if max == min {
            return (0.0, s);
        }
        let h = if max == r {
            60.0 * ((g - b) / (max - min)).rem_euclid(6.0)
        } else if max == g {
            60.0 * ((b - r) / (max - min) + 2.0)
        } else {
            60.0 * ((r - g) / (max - min) + 4.0)
        };
        (h, s)
    };
    let hues: Vec<f32> = scene
        .curves
        .iter()
        .map(|c| {
            let [r, g, b, _] = c.style.color.0;
            hue_of([r, g, b]).0
        })
        .collect();
    common::on_each_gpu(
        &format!("rendered labels never overlap ({what})"),
        |backend| {
            let plain = splinescope_render::render(
                &backend.ctx,
                &backend.pipelines,
                &scene,
                &splinescope_render::RenderRequest::new(w, h),
            )
            .expect("render");
            let labelled = splinescope_render::render(
                &backend.ctx,
                &backend.pipelines,
                &scene,
                &splinescope_render::RenderRequest::new(w, h).with_text(
                    splinescope_figure::TextOptions {
                        labels: true,
                        ..Default::default()
                    },
                ),
            )
            .expect("labels");
            // SPLINESCOPE_DUMP=DIR keeps the labelled picture there, to look at.
            if let Some(dir) = std::env::var_os("SPLINESCOPE_DUMP") {
                labelled
                    .write_png(&std::path::Path::new(&dir).join(format!("{what}.png")))
                    .ok();
            }
            // Per label: the box of the changed pixels nearest its colour — text over the
            // background only (over a curve its colour mixes with the curve's, and the hue
            // with it).
            let background = plain.pixel(0, 0);
            let mut pixels: Vec<Vec<(u32, u32)>> = vec![Vec::new(); hues.len()];
            for y in 0..h {
                for x in 0..w {
                    let p = labelled.pixel(x, y);
                    if p == plain.pixel(x, y) || plain.pixel(x, y) != background {
                        continue;
                    }
                    // Text over white keeps its hue; a glyph's well-covered pixels keep most of
                    // its saturation, where a leader line (60 % opacity, thin) keeps at most
                    // about half of it.
                    let (h, sat) = hue_of([p[0], p[1], p[2]].map(|v| f32::from(v) / 255.0));
                    if sat < 0.6 {
                        continue;
                    }
                    let (k, d) = hues
                        .iter()
                        .enumerate()
                        .map(|(k, c)| {
                            let d = (h - c).abs();
                            (k, d.min(360.0 - d))
                        })
                        .fold((0, f32::MAX), |a, b| if b.1 < a.1 { b } else { a });
                    if d > (step / 3.0).min(6.0) {
                        continue;
                    }
                    pixels[k].push((x, y));
                }
            }
            // A label's box: that of the largest cluster of its pixels (glyphs 3 pixels
            // apart or less joined) — a stray pixel of a neighbouring hue elsewhere is not
            // the label.
            let found: Vec<(usize, (u32, u32, u32, u32))> = pixels
                .iter()
                .enumerate()
                .filter_map(|(k, p)| largest_cluster(p).map(|b| (k, b)))
                .collect();
            assert!(
                found.len() >= 10,
                "{what}, {}: only {} labels measured",
                backend.name,
                found.len()
            );
            for (i, (ka, a)) in found.iter().enumerate() {
                // One line of 12-pixel text: no taller than a line and a half.
                assert!(
                    a.3 - a.1 <= 18,
                    "{what}, {}: label {ka} is {} px tall",
                    backend.name,
                    a.3 - a.1
                );
                for (kb, b) in &found[i + 1..] {
                    let apart = a.2 < b.0 || b.2 < a.0 || a.3 < b.1 || b.3 < a.1;
                    assert!(
                        apart,
                        "{what}, {}: labels {ka} {a:?} and {kb} {b:?} overlap in the PNG",
                        backend.name
                    );
                }
            }
            println!(
                "{what}, {}: {} labels measured in the PNG, none overlapping",
                backend.name,
                found.len()
            );
        },
    );
}

/// The bounding box `(x0, y0, x1, y1)` of the largest cluster of `pixels`, two pixels
/// being in one cluster when a chain of pixels at most 3 apart (each way) joins them.
fn largest_cluster(pixels: &[(u32, u32)]) -> Option<(u32, u32, u32, u32)> {
    let set: std::collections::HashSet<(u32, u32)> = pixels.iter().copied().collect();
    let mut seen = std::collections::HashSet::new();
    let mut best: Option<(usize, (u32, u32, u32, u32))> = None;
    for &start in pixels {
        if !seen.insert(start) {
            continue;
        }
        let (mut count, mut b) = (0, (start.0, start.1, start.0, start.1));
        let mut stack = vec![start];
        while let Some((x, y)) = stack.pop() {
            count += 1;
            b = (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y));
            for dy in -3_i64..=3 {
                for dx in -3_i64..=3 {
                    let (nx, ny) = (i64::from(x) + dx, i64::from(y) + dy);
                    if nx < 0 || ny < 0 {
                        continue;
                    }
                    let n = (nx as u32, ny as u32);
                    if set.contains(&n) && seen.insert(n) {
                        stack.push(n);
                    }
                }
            }
        }
        if best.is_none_or(|(c, _)| count > c) {
            best = Some((count, b));
        }
    }
    best.map(|(_, b)| b)
}

#[test]
fn figures_keep_each_curves_caps_joins_and_closed_seams() {
    let scene = Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/strokes.json"))
        .expect("scenes/strokes.json");
    let fig = build(&scene, &FigureOptions::new(480, 320)).expect("figure");
    let text = svg::write(&fig);
    let attrs: Vec<&str> = text
        .lines()
        .filter(|l| l.contains("<path id=\"curve-"))
        .collect();
    assert_eq!(attrs.len(), 6);
    for (line, want) in attrs.iter().zip([
        r#"stroke-linecap="butt" stroke-linejoin="miter""#,
        r#"stroke-linecap="square" stroke-linejoin="bevel""#,
        r#"stroke-linecap="round" stroke-linejoin="round""#,
        r#"stroke-linecap="butt" stroke-linejoin="miter""#,
        r#"stroke-linecap="butt" stroke-linejoin="bevel""#,
        r#"stroke-linecap="square" stroke-linejoin="miter""#,
    ]) {
        assert!(line.contains(want), "{line}");
    }
    // The closed rectangle and triangle are written closed (their seams are joins).
    let closed: Vec<bool> = attrs.iter().map(|l| l.contains("Z\"")).collect();
    assert_eq!(closed, [false, false, false, true, true, false]);
    // The PDF sets each shaped path's cap, join and miter limit, and closes the closed.
    let pdf = pdf::write(&fig);
    let content = String::from_utf8_lossy(&pdf);
    for op in ["0 J 0 j 4 M", "2 J 2 j 2 M", "0 J 2 j 4 M", "h S"] {
        assert!(content.contains(op), "the PDF lacks {op:?}");
    }
}
