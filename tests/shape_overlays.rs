//! Curvature combs and shape markers as pictures show them — figures (`export`, the
//! figure library) and renders (`render --comb`, on the GPU) — read back against exact
//! values: a circle's hairs all end `s / r` beyond it on its radii; an S curve's inflection
//! marker sits at its centre of symmetry and its crossings with a line where the line's
//! equation says; a render with a comb is coloured where the hairs are and nowhere a
//! render without one is not; the gallery's comb in the GPU's PNG and in the rasterised
//! SVG covers the same pixels (≥ 80 % intersection over union) and no hair reaches past
//! its cap; bad `--comb` and `--comb-cap` values are refused with their value named.

mod common;

use glam::{DVec2, DVec3};
use splinescope_core::geom::{Bezier, Curve, Nurbs};
use splinescope_figure::{FigureOptions, Item, build};
use splinescope_image::RgbaImage;
use splinescope_scene::format::Scene;
use splinescope_scene::format::shape::{CombCap, CombScale, ShapeOptions};

fn p(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, 0.0)
}

fn bare(curves: Vec<Curve>) -> Scene {
    let mut scene = Scene::of_curves(curves);
    for c in &mut scene.curves {
        c.style.show_polygon = false;
        c.style.show_points = false;
    }
    scene
}

#[test]
fn a_circles_figure_comb_ends_scale_over_radius_beyond_it() {
    let (r, s) = (2.0, 0.2);
    let center = p(1.0, -0.5);
    let scene = bare(vec![Curve::Nurbs(
        Nurbs::circle(center, r).expect("circle"),
    )]);
    let mut opts = FigureOptions::new(600, 600);
    opts.shape.comb = Some(CombScale::Fixed(s));
    let fig = build(&scene, &opts).expect("figure");
    let c = fig.projection.point(center).expect("in front");
    // The output's scale: world unit → points, from two projected points.
    let unit = (fig.projection.point(center + DVec3::X).expect("x") - c).length();
    let mut hairs = 0;
    let mut envelope = 0;
    for item in &fig.items {
        let Item::Path {
            runs,
            curve: None,
            stroke,
            ..
        } = item
        else {
            continue;
        };
        for run in runs {
            let ends: Vec<DVec2> = std::iter::once(run.start)
                .chain(run.pieces.iter().map(|pc| pc.seg.end()))
                .collect();
            for e in &ends {
                // Every point of a comb path — a hair's foot, a tip — is on the circle
                // (radius r) or on the tips' circle (radius r + s / r).
                let d = (*e - c).length() / unit;
                let on_curve = (d - r).abs() < 1e-6;
                let on_tips = (d - (r + s / r)).abs() < 1e-6;
                assert!(
                    on_curve || on_tips,
                    "comb point at radius {d} (stroke {stroke:?})"
                );
            }
            if ends.len() == 2 {
                // A hair: its foot and tip on one radius.
                let (a, b) = ((ends[0] - c).normalize(), (ends[1] - c).normalize());
                assert!(a.dot(b) > 1.0 - 1e-9, "a hair off its radius: {ends:?}");
                hairs += 1;
            } else {
                envelope += ends.len();
            }
        }
    }
    assert!(hairs >= 4 * 20, "{hairs} hairs");
    assert!(envelope >= hairs, "{envelope} envelope vertices");
    // The SVG carries them.
    let text = splinescope_figure::svg::write(&fig);
    assert!(text.matches("<path").count() >= 3, "{text:.400}");
}

#[test]
fn markers_sit_where_the_exact_answers_are() {
    // An S antisymmetric about (1, 0): one inflection there; the x axis meets it at
    // t = 0, 1/2, 1 (y = 6 t (1 − t)(1 − 2t)).
    let s = Curve::Bezier(Bezier::new(vec![
        p(0.0, 0.0),
        p(1.0, 2.0),
        p(1.0, -2.0),
        p(2.0, 0.0),
    ]));
    let line = Curve::Bezier(Bezier::new(vec![p(-1.0, 0.0), p(3.0, 0.0)]));
    let scene = bare(vec![s, line]);
    let mut opts = FigureOptions::new(400, 300);
    opts.shape = ShapeOptions {
        comb: None,
        comb_cap: CombCap::default(),
        inflections: true,
        curvature_extrema: false,
        intersections: true,
        joints: false,
    };
    let fig = build(&scene, &opts).expect("figure");
    let discs: Vec<DVec2> = fig
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Disc { center, .. } => Some(*center),
            _ => None,
        })
        .collect();
    let at = |q: DVec3| fig.projection.point(q).expect("in front");
    for want in [p(0.0, 0.0), p(1.0, 0.0), p(2.0, 0.0)] {
        let w = at(want);
        assert!(
            discs.iter().any(|d| (*d - w).length() < 1e-6),
            "no marker at {want} ({w}); discs {discs:?}"
        );
    }
    // Nothing anywhere else: every disc is at one of those points.
    for d in &discs {
        assert!(
            [p(0.0, 0.0), p(1.0, 0.0), p(2.0, 0.0)]
                .iter()
                .any(|q| (at(*q) - *d).length() < 1e-6),
            "stray marker at {d}"
        );
    }
}

fn render(scene: &std::path::Path, out: &std::path::Path, extra: &[&str]) -> RgbaImage {
    let mut args = vec![
        "render",
        scene.to_str().expect("utf-8"),
        "-o",
        out.to_str().expect("utf-8"),
        "--width",
        "400",
        "--height",
        "400",
    ];
    args.extend_from_slice(extra);
    let run = common::run(&args);
    assert!(run.status.success(), "{}", common::text(&run));
    RgbaImage::read_png(out).expect("png")
}

#[test]
fn render_draws_the_comb_on_the_gpu_where_the_hairs_are() {
    let gpus = common::gpus("render_draws_the_comb_on_the_gpu_where_the_hairs_are");
    if gpus.is_empty() {
        return;
    }
    let dir = common::out_dir("shape_overlays");
    let scene_path = dir.join("circle.json");
    let (r, s) = (2.0, 0.4);
    let scene = bare(vec![Curve::Nurbs(
        Nurbs::circle(DVec3::ZERO, r).expect("circle"),
    )]);
    splinescope_io::files::write_atomic(
        &scene_path,
        splinescope_scene::format::to_json_string(&scene).as_bytes(),
    )
    .expect("scene");
    for backend in gpus {
        let plain = render(
            &scene_path,
            &dir.join("plain.png"),
            &["--gpu-backend", &backend.name],
        );
        let combed = render(
            &scene_path,
            &dir.join(format!("comb-{}.png", backend.name)),
            &["--gpu-backend", &backend.name, "--comb", "0.4"],
        );
        // Pixels halfway along the hairs (radius r + s / (2 r)) in 16 directions: the
        // comb colours some there; without it they are all background.
        let camera = scene.camera(DVec2::new(400.0, 400.0));
        let bg = plain.pixel(0, 0);
        let (mut inked, mut plain_inked) = (0, 0);
        for k in 0..64 {
            let a = std::f64::consts::TAU * f64::from(k) / 64.0;
            let q = (r + 0.5 * s / r) * DVec3::new(a.cos(), a.sin(), 0.0);
            let px = camera
                .pixel_from_world(q, DVec2::new(400.0, 400.0))
                .expect("on screen");
            let (x, y) = (px.x.round() as u32, px.y.round() as u32);
            let differs = |img: &RgbaImage| {
                (x.saturating_sub(1)..=x + 1)
                    .any(|xx| (y.saturating_sub(1)..=y + 1).any(|yy| img.pixel(xx, yy) != bg))
            };
            inked += usize::from(differs(&combed));
            plain_inked += usize::from(differs(&plain));
        }
        assert_eq!(
            plain_inked, 0,
            "{}: nothing drawn there without a comb",
            backend.name
        );
        assert!(
            inked >= 16,
            "{}: the comb's hairs reach {inked} of 64 probes",
            backend.name
        );
    }
}

#[test]
fn bad_comb_scales_are_refused_naming_the_value() {
    for bad in ["0", "-2", "nan", "inf", "wide"] {
        let run = common::run(&["render", "-o", "/dev/null/never.png", "--comb", bad]);
        assert!(!run.status.success(), "--comb {bad} accepted");
        let text = common::text(&run);
        assert!(
            text.contains(bad) || text.contains("NaN") || text.contains("inf"),
            "{text}"
        );
        assert!(text.contains("--comb"), "{text}");
    }
    for bad in ["0", "-0.1", "nan", "inf", "tall"] {
        for command in ["render", "export"] {
            let run = common::run(&[
                command,
                "-o",
                "/dev/null/never.png",
                "--comb",
                "--comb-cap",
                bad,
            ]);
            assert!(!run.status.success(), "{command} --comb-cap {bad} accepted");
            let text = common::text(&run);
            assert!(
                text.contains(bad) || text.contains("NaN") || text.contains("inf"),
                "{text}"
            );
            assert!(text.contains("--comb-cap"), "{text}");
        }
    }
}

#[test]
fn the_legend_lists_the_markers_shown() {
    let scene = bare(vec![Curve::Bezier(Bezier::new(vec![
        p(0.0, 0.0),
        p(1.0, 2.0),
        p(1.0, -2.0),
        p(2.0, 0.0),
    ]))]);
    let mut opts = FigureOptions::new(400, 300);
    opts.legend = true;
    opts.shape.inflections = true;
    let texts = |fig: &splinescope_figure::Figure| -> Vec<String> {
        fig.items
            .iter()
            .filter_map(|i| match i {
                Item::Text { text, .. } => Some(text.clone()),
                _ => None,
            })
            .collect()
    };
    let fig = build(&scene, &opts).expect("figure");
    let rows = texts(&fig);
    assert!(rows.iter().any(|t| t.starts_with("inflection")), "{rows:?}");
    assert!(rows.iter().any(|t| t.starts_with("cusp")), "{rows:?}");
    assert!(
        !rows.iter().any(|t| t.starts_with("intersection")),
        "{rows:?}"
    );
    opts.shape.inflections = false;
    let rows = texts(&build(&scene, &opts).expect("figure"));
    assert!(
        !rows.iter().any(|t| t.starts_with("inflection")),
        "{rows:?}"
    );
}

/// The pixels where `with` differs from `without` (what an overlay adds to a picture).
fn added(with: &RgbaImage, without: &RgbaImage) -> Vec<bool> {
    let (w, h) = (with.width, with.height);
    let mut out = vec![false; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            let (a, b) = (with.pixel(x, y), without.pixel(x, y));
            let d = a
                .iter()
                .zip(b.iter())
                .map(|(p, q)| i32::from(*p).abs_diff(i32::from(*q)))
                .max()
                .unwrap_or(0);
            out[(y * w + x) as usize] = d > 24;
        }
    }
    out
}

/// `mask` grown by one pixel each way (rasterisers place a one-pixel line's coverage a
/// pixel apart where it falls between two).
fn dilated(mask: &[bool], w: u32, h: u32) -> Vec<bool> {
    let mut out = vec![false; mask.len()];
    for y in 0..h as i64 {
        for x in 0..w as i64 {
            if mask[(y * i64::from(w) + x) as usize] {
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        let (xx, yy) = (x + dx, y + dy);
                        if xx >= 0 && yy >= 0 && xx < i64::from(w) && yy < i64::from(h) {
                            out[(yy * i64::from(w) + xx) as usize] = true;
                        }
                    }
                }
            }
        }
    }
    out
}

/// The gallery with its automatic comb, as `render --comb` draws it on the GPU and as
/// `export --comb` writes it to SVG: the comb's own pixels (what it adds to the plain
/// picture) in the two overlap by at least 80 % (intersection over union, each mask grown
/// by a pixel for the rasterisers' different coverage) — the same hairs at the same
/// parameters, the same caps and breaks. And no comb pixel of the PNG lies farther from
/// the plain picture's ink than the cap (a hair never crosses the view).
#[test]
fn the_galleries_comb_is_the_same_in_the_png_and_the_svg_and_stays_within_its_cap() {
    let (w, h) = (1200_u32, 800_u32);
    let scene = splinescope_scene::format::gallery::gallery();
    let combed = ShapeOptions {
        comb: Some(CombScale::Auto),
        ..ShapeOptions::default()
    };
    let figure = |shape: ShapeOptions| {
        let mut opts = FigureOptions::new(w, h);
        opts.shape = shape;
        common::rasterise_svg(
            &splinescope_figure::svg::write(&build(&scene, &opts).expect("figure")),
            w,
            h,
        )
    };
    let (svg_plain, svg_comb) = (figure(ShapeOptions::default()), figure(combed));
    let svg_mask = dilated(&added(&svg_comb, &svg_plain), w, h);
    let cap_px = CombCap::default().get() * f64::from(h);
    common::on_each_gpu("the gallery's comb in the PNG and the SVG", |backend| {
        let render = |shape: &ShapeOptions| {
            splinescope_render::render(
                &backend.ctx,
                &backend.pipelines,
                &scene,
                &splinescope_render::RenderRequest::new(w, h).with_shape(*shape),
            )
            .expect("render")
        };
        let (png_plain, png_comb) = (render(&ShapeOptions::default()), render(&combed));
        let raw = added(&png_comb, &png_plain);
        let png_mask = dilated(&raw, w, h);
        let both = png_mask
            .iter()
            .zip(&svg_mask)
            .filter(|(a, b)| **a && **b)
            .count();
        let either = png_mask
            .iter()
            .zip(&svg_mask)
            .filter(|(a, b)| **a || **b)
            .count();
        let iou = both as f64 / either.max(1) as f64;
        println!(
            "{}: comb pixels IoU {iou:.3} ({either} in either)",
            backend.name
        );
        let dir = common::out_dir("shape_overlays");
        let save = |what: &str| {
            png_comb
                .write_png(&dir.join(format!("gallery-comb.{}.png", backend.name)))
                .ok();
            svg_comb
                .write_png(&dir.join(format!("gallery-comb.{}.svg.png", backend.name)))
                .ok();
            format!("{what} (images in {})", dir.display())
        };
        assert!(
            either > 20_000,
            "{}",
            save(&format!(
                "{}: the comb adds only {either} pixels",
                backend.name
            ))
        );
        assert!(
            iou >= 0.8,
            "{}",
            save(&format!(
                "{}: the comb's pixels in the PNG and the SVG overlap {iou:.3} (IoU)",
                backend.name
            ))
        );
        // Every comb pixel within the cap (plus the line's pixel) of the plain ink.
        let ink: Vec<DVec2> = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| png_plain.pixel(x, y) != png_plain.pixel(0, 0))
            .map(|(x, y)| DVec2::new(f64::from(x), f64::from(y)))
            .collect();
        let reach = cap_px + 2.0;
        let mut grid: std::collections::HashMap<(i64, i64), Vec<DVec2>> = Default::default();
        for q in &ink {
            grid.entry(((q.x / reach) as i64, (q.y / reach) as i64))
                .or_default()
                .push(*q);
        }
        let mut far = 0;
        for y in 0..h {
            for x in 0..w {
                if !raw[(y * w + x) as usize] {
                    continue;
                }
                let q = DVec2::new(f64::from(x), f64::from(y));
                let (cx, cy) = ((q.x / reach) as i64, (q.y / reach) as i64);
                let near = (cx - 1..=cx + 1).any(|gx| {
                    (cy - 1..=cy + 1).any(|gy| {
                        grid.get(&(gx, gy))
                            .is_some_and(|v| v.iter().any(|p| (*p - q).length() <= reach))
                    })
                });
                far += usize::from(!near);
            }
        }
        assert_eq!(
            far,
            0,
            "{}",
            save(&format!(
                "{}: {far} comb pixels lie beyond the cap ({cap_px} px) from the curves",
                backend.name
            ))
        );
    });
}

/// Joint markers where the analysis finds the joints that are not G2: on a cubic B-spline
/// with a triple knot (a kink at (3, 1)) and a double knot (a curvature jump), a figure with
/// `joints` on has a kink marker at the kink's exact point, a curvature-jump marker at the
/// double knot's point and no other marker; the legend names both kinds.
#[test]
fn joint_markers_sit_at_the_kink_and_the_curvature_jump() {
    let s = splinescope_core::geom::BSpline::try_new(
        vec![
            p(0.0, 0.0),
            p(1.0, 1.5),
            p(2.0, 1.0),
            p(3.0, 1.0),
            p(3.0, 2.0),
            p(3.5, 4.0),
            p(5.0, 3.0),
            p(6.0, 5.0),
            p(7.0, 4.0),
        ],
        vec![0., 0., 0., 0., 1., 1., 1., 2., 2., 3., 3., 3., 3.],
        4,
    )
    .expect("spline");
    let jump_at = s.eval(2.0);
    let scene = bare(vec![Curve::BSpline(s)]);
    let mut opts = FigureOptions::new(400, 300);
    opts.legend = true;
    opts.shape = ShapeOptions {
        joints: true,
        ..ShapeOptions::default()
    };
    let fig = build(&scene, &opts).expect("figure");
    let discs: Vec<DVec2> = fig
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Disc { center, .. } => Some(*center),
            _ => None,
        })
        .collect();
    let at = |q: DVec3| fig.projection.point(q).expect("in front");
    for want in [p(3.0, 1.0), jump_at] {
        assert!(
            discs.iter().any(|d| (*d - at(want)).length() < 1e-6),
            "no marker at {want}: {discs:?}"
        );
    }
    let legend_discs = 2 * 2; // the legend's two kinds, ring and core each
    let curve_markers = discs
        .iter()
        .filter(|d| {
            [p(3.0, 1.0), jump_at]
                .iter()
                .any(|q| (at(*q) - **d).length() < 1e-6)
        })
        .count();
    // Two markers; each a ring and a core, each drawn as a rim and its fill.
    assert_eq!(curve_markers, 8, "{discs:?}");
    assert_eq!(discs.len(), curve_markers + legend_discs, "{discs:?}");
    let texts: Vec<&str> = fig
        .items
        .iter()
        .filter_map(|i| match i {
            Item::Text { text, .. } => Some(text.as_str()),
            _ => None,
        })
        .collect();
    assert!(
        texts.contains(&"kink (G0 joint)") && texts.contains(&"curvature jump (G1 joint)"),
        "{texts:?}"
    );
}
