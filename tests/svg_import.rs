//! SVG files read as path curves and drawn on the GPU look as an independent renderer
//! (resvg) draws the same file: every ink pixel of each picture lies within 2 pixels of ink
//! in the other (99.5 % of them, the rest being anti-aliasing fringes). And the command
//! line reads SVG wherever it reads a scene, `import` writes the scene, and a hostile file
//! is an error naming the file and the line.

mod common;

use glam::DVec2;
use splinescope_image::RgbaImage;
use splinescope_scene::format::{Scene, ViewSpec};

/// A file with every kind of element the reader takes: arcs (rotated, large, swept,
/// relative), rounded rectangles, circles and ellipses under transforms, `<use>`, every
/// path command. Uniform strokes (width 1 user unit), no fill, so that both pictures are
/// outlines of one width.
const FILE: &str = r##"<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink" viewBox="0 0 240 160">
  <style>path, rect, circle, ellipse, polyline, polygon, line { fill: none; stroke: black; stroke-width: 1 }</style>
  <defs><path id="wave" d="M 0 0 q 10 -15 20 0 t 20 0 t 20 0"/></defs>
  <rect x="8" y="8" width="224" height="144" rx="14" ry="9"/>
  <circle cx="50" cy="50" r="28"/>
  <ellipse cx="120" cy="45" rx="30" ry="12" transform="rotate(25 120 45)"/>
  <path d="M 170 30 A 30 18 20 1 1 210 70 a 12 12 0 0 0 -10 20 Z"/>
  <path d="M 20 120 C 30 90 60 90 70 120 S 110 150 120 120 H 140 v -20 L 150 130 z"/>
  <g transform="translate(160 110) scale(1.2 0.8)"><use xlink:href="#wave"/><use href="#wave" y="20"/></g>
  <polygon points="90,140 100,125 110,140"/>
  <line x1="20" y1="145" x2="70" y2="140"/>
</svg>"##;

/// The picture's scale: pixels per user unit.
const K: f64 = 4.0;

fn rasterise(text: &str, w: u32, h: u32) -> RgbaImage {
    let tree = resvg::usvg::Tree::from_str(text, &resvg::usvg::Options::default())
        .expect("the SVG parses");
    let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h).expect("pixmap");
    pixmap.fill(resvg::tiny_skia::Color::WHITE);
    let scale = w as f32 / tree.size().width();
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    RgbaImage {
        width: w,
        height: h,
        data: pixmap.data().to_vec(),
    }
}

/// Pixels darker than mid-grey.
fn ink(img: &RgbaImage) -> Vec<bool> {
    img.data
        .chunks_exact(4)
        .map(|p| {
            let l = 0.3 * f64::from(p[0]) + 0.59 * f64::from(p[1]) + 0.11 * f64::from(p[2]);
            // Premultiplied or straight, an opaque background: alpha decides too.
            p[3] > 128 && l < 128.0
        })
        .collect()
}

/// The share of `a`'s ink within `r` pixels of `b`'s.
fn covered(a: &[bool], b: &[bool], w: usize, h: usize, r: i64) -> f64 {
    let (mut inside, mut total) = (0usize, 0usize);
    for y in 0..h as i64 {
        for x in 0..w as i64 {
            if !a[(y as usize) * w + x as usize] {
                continue;
            }
            total += 1;
            let near = (-r..=r).any(|dy| {
                (-r..=r).any(|dx| {
                    let (xx, yy) = (x + dx, y + dy);
                    xx >= 0
                        && yy >= 0
                        && xx < w as i64
                        && yy < h as i64
                        && b[(yy as usize) * w + xx as usize]
                })
            });
            inside += usize::from(near);
        }
    }
    inside as f64 / total.max(1) as f64
}

/// Strokes of several widths under transforms (uniform scales: a non-uniform one makes an
/// SVG stroke's width depend on its direction, which one width per curve cannot draw),
/// with round caps and joins (what the renderer draws).
const WIDE: &str = r##"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 240 160">
  <style>* { fill: none; stroke: black; stroke-linecap: round; stroke-linejoin: round }</style>
  <circle cx="50" cy="50" r="28" stroke-width="6"/>
  <g transform="scale(2)" stroke-width="3"><ellipse cx="60" cy="25" rx="12" ry="6"/></g>
  <g transform="translate(150 100) rotate(20) scale(1.5)"><path d="M 0 0 C 10 -30 40 -30 50 0" stroke-width="4"/></g>
  <polyline points="20,140 60,110 100,140" stroke-width="5"/>
  <line x1="120" y1="150" x2="220" y2="150" stroke-width="0.5"/>
</svg>"##;

#[test]
fn an_svg_file_is_drawn_as_resvg_draws_it() {
    drawn_as_resvg_draws(FILE, "all", Some(9));
}

/// Caps, joins, miter limits and dashes on wide strokes (a round cap or join where SVG
/// has a butt, square, miter or bevel one is off by half a width: 12 to 16 px here).
const SHAPED: &str = r##"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 240 160">
  <style>* { fill: none; stroke: black }</style>
  <polyline points="20,45 60,15 100,45" stroke-width="8" stroke-linecap="butt" stroke-linejoin="miter"/>
  <polyline points="130,45 170,15 210,45" stroke-width="8" stroke-linecap="square" stroke-linejoin="bevel"/>
  <polyline points="20,95 40,60 60,95" stroke-width="6" stroke-miterlimit="1.5"/>
  <rect x="85" y="62" width="50" height="30" stroke-width="7"/>
  <circle cx="190" cy="80" r="22" stroke-width="5" stroke-dasharray="10 6" stroke-dashoffset="3"/>
  <path d="M 20 130 C 60 100 100 160 140 130" stroke-width="4" stroke-dasharray="12 4 2" stroke-linecap="round"/>
  <g transform="translate(150 0) scale(1.5)"><line x1="10" y1="95" x2="55" y2="85" stroke-width="4" stroke-dasharray="6" stroke-linecap="square"/></g>
</svg>"##;

#[test]
fn caps_joins_and_dashes_are_drawn_as_resvg_draws_them() {
    drawn_as_resvg_draws(SHAPED, "shaped", None);
}

#[test]
fn strokes_keep_their_width_in_user_units_scaled_by_the_transform() {
    let imported = splinescope_import::svg::read(WIDE, "wide.svg").expect("reads");
    let widths: Vec<f32> = imported
        .scene
        .curves
        .iter()
        .map(|c| c.style.width)
        .collect();
    // 6; 3 × 2; 4 × 1.5; 5; 0.5 — in user units, the scene's.
    assert_eq!(widths.len(), 5);
    for (w, want) in widths.iter().zip([6.0, 6.0, 6.0, 5.0, 0.5]) {
        assert!((w - want).abs() <= 1e-5, "{widths:?}");
    }
    drawn_as_resvg_draws(WIDE, "wide", Some(5));
}

/// Reads `file` (`curves` curves, when given) and compares its picture with resvg's.
fn drawn_as_resvg_draws(file: &str, name: &str, curves: Option<usize>) {
    let imported = splinescope_import::svg::read(file, &format!("{name}.svg")).expect("reads");
    if let Some(curves) = curves {
        assert_eq!(
            imported.scene.curves.len(),
            curves,
            "{:?}",
            imported.warnings
        );
    }
    assert!(imported.warnings.is_empty(), "{:?}", imported.warnings);
    let (w, h) = ((240.0 * K) as u32, (160.0 * K) as u32);
    let mut scene: Scene = imported.scene;
    // The viewBox exactly: its centre, flipped, and its height.
    scene.view = ViewSpec::TwoD {
        center: DVec2::new(120.0, 80.0),
        height: 160.0,
    };
    // Strokes keep their width in user units (1 unit = K px here, as resvg draws
    // them); nothing here is filled only.
    for c in &scene.curves {
        assert!(c.style.width_in_scene, "{:?}", c.name);
    }
    let reference = rasterise(file, w, h);
    let theirs = ink(&reference);
    common::on_each_gpu("svg import against resvg", |backend| {
        let ours_img = splinescope_render::render(
            &backend.ctx,
            &backend.pipelines,
            &scene,
            &splinescope_render::RenderRequest::new(w, h),
        )
        .expect("renders");
        let ours = ink(&ours_img);
        let (w, h) = (w as usize, h as usize);
        let (a, b) = (
            covered(&ours, &theirs, w, h, 2),
            covered(&theirs, &ours, w, h, 2),
        );
        if a < 0.995 || b < 0.995 {
            let dir = common::out_dir(&format!("svg_import/{name}"));
            ours_img.write_png(&dir.join("actual.png")).ok();
            reference.write_png(&dir.join("resvg.png")).ok();
            let mut diff = ours_img.clone();
            for (i, p) in diff.data.chunks_exact_mut(4).enumerate() {
                p.copy_from_slice(&match (ours[i], theirs[i]) {
                    (true, false) => [255, 0, 0, 255],
                    (false, true) => [0, 0, 255, 255],
                    (true, true) => [0, 0, 0, 255],
                    (false, false) => [255, 255, 255, 255],
                });
            }
            diff.write_png(&dir.join("diff.png")).ok();
            panic!(
                "on {}: {:.4} of our ink near resvg's, {:.4} of resvg's near ours (want 0.995; images in {})",
                backend.name,
                a,
                b,
                dir.display()
            );
        }
    });
}

#[test]
fn the_command_line_reads_svg_where_it_reads_a_scene_and_import_writes_one() {
    let dir = common::out_dir("svg_import_cli");
    let svg = dir.join("all.svg");
    std::fs::write(&svg, FILE.replace("</svg>", "<text>left out</text></svg>")).expect("write");
    let out = common::run(&["check", svg.to_str().expect("utf-8")]);
    assert!(out.status.success(), "{}", common::text(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("9 curve(s)"), "{stdout}");
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("left out (not curves): 1 <text>"),
        "{}",
        common::text(&out)
    );
    let json = dir.join("all.json");
    let out = common::run(&[
        "import",
        svg.to_str().expect("utf-8"),
        "-o",
        json.to_str().expect("utf-8"),
    ]);
    assert!(out.status.success(), "{}", common::text(&out));
    let scene = Scene::load(&json).expect("the written scene reads");
    let direct = splinescope_import::load(&svg).expect("reads").scene;
    assert_eq!(scene.curves.len(), direct.curves.len());
    for (a, b) in scene.curves.iter().zip(&direct.curves) {
        assert_eq!(a.curve, b.curve, "written exactly");
        assert_eq!(a.name, b.name);
    }
    // The input is never the output.
    let out = common::run(&[
        "import",
        svg.to_str().expect("utf-8"),
        "-o",
        svg.to_str().expect("utf-8"),
    ]);
    assert!(!out.status.success());
    assert!(
        std::fs::read_to_string(&svg)
            .expect("kept")
            .contains("<svg")
    );
    // A hostile file: the file and the line.
    let bad = dir.join("bad.svg");
    std::fs::write(&bad, "<svg>\n<g>\n<path d=\"M 0 0 L\"/></g></svg>").expect("write");
    let out = common::run(&["analyze", bad.to_str().expect("utf-8")]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.svg:3: <path>: path data"), "{err}");
    // An extension no reader takes.
    let odd = dir.join("x.dwg");
    std::fs::write(&odd, "x").expect("write");
    let out = common::run(&[
        "import",
        odd.to_str().expect("utf-8"),
        "-o",
        json.to_str().expect("utf-8"),
    ]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains(".dwg is not a format"));
}
