//! Offscreen images: golden references with a stated tolerance, and checks against
//! analytic truth that need no reference at all.
//!
//! Golden tolerance (`splinescope regress`'s default): a pixel counts as different when any
//! channel differs by more than 24/255; at most 0.1 % of the pixels may differ. The references were made on lavapipe
//! (Mesa 22.3, Vulkan); rasterisers differ slightly in coverage at edges, which the
//! tolerance absorbs, while a missing, moved or recoloured curve changes far more pixels.
//! On failure the actual image and a diff (differing pixels in red) are written to
//! `target/test-output/images/`. `SPLINESCOPE_BLESS=1` writes new references instead.

mod common;

use std::path::PathBuf;

use common::render_scene;
use glam::{DVec2, DVec3};
use splinescope_core::geom::{Bezier, Curve};
use splinescope_encoding::Color;
use splinescope_encoding::camera::Camera;
use splinescope_image::RgbaImage;
use splinescope_image::compare::{ComparisonImages, Tolerance, compare_images};
use splinescope_scene::format::{Scene, SceneCurve, Style, ViewSpec, gallery};

/// The golden references are compared with the same code as `splinescope regress`, at
/// its default tolerance.
fn golden(name: &str, backend: &str, image: &RgbaImage) {
    let reference = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(format!("{name}.png"));
    if std::env::var("SPLINESCOPE_BLESS").is_ok_and(|v| v == "1") {
        image.write_png(&reference).expect("write reference");
        eprintln!("blessed {}", reference.display());
        return;
    }
    let want = RgbaImage::read_png(&reference)
        .unwrap_or_else(|e| panic!("{e}; run with SPLINESCOPE_BLESS=1 to create the reference"));
    let out = common::out_dir("images");
    let tolerance = Tolerance::default();
    let fail = |why: String, pictures: Option<&ComparisonImages>| {
        let actual = out.join(format!("{name}.{backend}.actual.png"));
        image.write_png(&actual).expect("write actual");
        if let Some(p) = pictures {
            p.diff
                .write_png(&out.join(format!("{name}.{backend}.diff.png")))
                .expect("write diff");
            p.flip
                .write_png(&out.join(format!("{name}.{backend}.flip.png")))
                .expect("write flip");
        }
        panic!(
            "{name} on {backend}: {why}; actual and diff images in {} (SPLINESCOPE_BLESS=1 accepts the new image)",
            out.display()
        );
    };
    match compare_images(image, &want, &tolerance) {
        Err(mismatch) => fail(mismatch.to_string(), None),
        Ok((c, pictures)) => {
            eprintln!(
                "{name} on {backend}: {} px differ ({:.3} %), FLIP mean {:.4}",
                c.differing_pixels,
                c.differing_fraction * 100.0,
                c.flip_mean
            );
            if !c.matches {
                fail(
                    format!(
                        "{} pixels ({:.3} %) differ by more than {}/255 (largest difference {}; FLIP mean {:.4})",
                        c.differing_pixels,
                        c.differing_fraction * 100.0,
                        tolerance.channel,
                        c.max_channel_diff,
                        c.flip_mean
                    ),
                    Some(&pictures),
                );
            }
        }
    }
}

#[test]
fn gallery_matches_its_golden_image() {
    common::on_each_gpu("gallery_matches_its_golden_image", |backend| {
        let ctx = &backend.ctx;
        let image = render_scene(ctx, &backend.pipelines, &gallery::gallery(), None, 480, 320)
            .expect("render");
        golden("gallery", &backend.name, &image);
    });
}

/// Renders `scenes/{name}.json` at 320×240 and compares it with its golden image.
fn scene_golden(name: &str) {
    common::on_each_gpu(&format!("{name} golden image"), |backend| {
        let ctx = &backend.ctx;
        let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.json"));
        let scene = Scene::load(&path).expect("scene");
        let image = render_scene(ctx, &backend.pipelines, &scene, None, 320, 240).expect("render");
        golden(name, &backend.name, &image);
    });
}

#[test]
fn three_d_bezier_scene_matches_its_golden_image() {
    scene_golden("bezier3d");
}

#[test]
fn modified_bezier_scene_matches_its_golden_image() {
    scene_golden("paper002_fig1");
}

#[test]
fn interpolation_scene_matches_its_golden_image() {
    scene_golden("paper002_examples");
}

#[test]
fn bspline_scene_matches_its_golden_image() {
    scene_golden("bsplines");
}

#[test]
fn nubmp_scene_matches_its_golden_image() {
    scene_golden("paper001_fig1");
}

/// A scene of one curve, no overlays, black on white, seen by a 2D view.
fn single(curve: Bezier, width: f32, samples: u32) -> Scene {
    Scene {
        name: None,
        unit: None,
        background: Color::WHITE,
        samples_per_segment: Some(samples),
        view: ViewSpec::TwoD {
            center: glam::DVec2::new(0.0, 0.0),
            height: 10.0,
        },
        curves: vec![SceneCurve {
            name: None,
            curve: Curve::Bezier(curve),
            style: Style {
                color: Color([0.0, 0.0, 0.0, 1.0]),
                width,
                width_in_scene: false,
                show_polygon: false,
                show_points: false,
                samples: None,
                stroke: Default::default(),
            },
        }],
        annotations: Vec::new(),
    }
}

/// Distance in pixels from `c` to the segment `a`–`b`.
fn segment_distance(c: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = ((c - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
    (a + t * ab - c).length()
}

#[test]
fn a_straight_line_has_exactly_the_analytic_coverage() {
    common::on_each_gpu(
        "a_straight_line_has_exactly_the_analytic_coverage",
        |backend| {
            let ctx = &backend.ctx;
            // A line of width 3 px at an odd angle; with 2 samples it is one capsule, whose
            // coverage at a pixel centre at distance d is clamp(w/2 + 0.5 − d, 0, 1).
            let (w, h) = (200u32, 160u32);
            let line = Bezier::new(vec![DVec3::new(-5.1, -3.3, 0.0), DVec3::new(4.3, 2.9, 0.0)]);
            let scene = single(line.clone(), 3.0, 2);
            let viewport = DVec2::new(f64::from(w), f64::from(h));
            let camera: Camera = scene.camera(viewport);
            let image =
                render_scene(ctx, &backend.pipelines, &scene, Some(camera), w, h).expect("render");
            let a = camera.pixel_from_world(line.points()[0], viewport).unwrap();
            let b = camera.pixel_from_world(line.points()[1], viewport).unwrap();
            let mut worst = 0.0_f64;
            let mut inked = 0;
            for y in 0..h {
                for x in 0..w {
                    let centre = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
                    let coverage = (1.5 + 0.5 - segment_distance(centre, a, b)).clamp(0.0, 1.0);
                    let want = 255.0 * (1.0 - coverage);
                    let got = f64::from(image.pixel(x, y)[0]);
                    worst = worst.max((got - want).abs());
                    if coverage > 0.0 {
                        inked += 1;
                    }
                }
            }
            // f32 geometry in the shader and 8-bit rounding: within 3/255 of the model.
            assert!(
                worst <= 3.0,
                "largest deviation from the analytic coverage: {worst}/255"
            );
            assert!(inked > 300, "the line must cover pixels ({inked})");
        },
    );
}

#[test]
fn curve_pixels_hug_the_exact_curve() {
    common::on_each_gpu("curve_pixels_hug_the_exact_curve", |backend| {
        let ctx = &backend.ctx;
        let (w, h) = (240u32, 180u32);
        let cubic = Bezier::new(vec![
            DVec3::new(-6.0, -3.0, 0.0),
            DVec3::new(-3.0, 5.5, 0.0),
            DVec3::new(3.5, -5.0, 0.0),
            DVec3::new(6.0, 3.0, 0.0),
        ]);
        let width = 4.0;
        let scene = single(cubic.clone(), width as f32, 512);
        let viewport = DVec2::new(f64::from(w), f64::from(h));
        let camera = scene.camera(viewport);
        let image =
            render_scene(ctx, &backend.pipelines, &scene, Some(camera), w, h).expect("render");
        // The exact curve, densely, in pixels.
        let dense: Vec<DVec2> = (0..=20_000)
            .map(|k| {
                camera
                    .pixel_from_world(cubic.eval(f64::from(k) / 20_000.0), viewport)
                    .unwrap()
            })
            .collect();
        let (mut inside, mut outside) = (0, 0);
        for y in 0..h {
            for x in 0..w {
                let c = DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5);
                let d = dense
                    .windows(2)
                    .map(|p| segment_distance(c, p[0], p[1]))
                    .fold(f64::INFINITY, f64::min);
                let v = image.pixel(x, y)[0];
                // Well inside the stroke: fully inked; well outside: untouched background.
                if d <= width / 2.0 - 1.0 {
                    assert!(
                        v <= 4,
                        "pixel ({x},{y}) at {d:.2} px from the curve is {v}, want ink"
                    );
                    inside += 1;
                } else if d >= width / 2.0 + 1.0 {
                    assert_eq!(
                        v, 255,
                        "pixel ({x},{y}) at {d:.2} px from the curve is inked"
                    );
                    outside += 1;
                }
            }
        }
        assert!(
            inside > 200 && outside > 10_000,
            "{inside} inside, {outside} outside"
        );
    });
}

#[test]
fn an_edit_written_in_place_renders_like_a_fresh_upload() {
    use splinescope_core::geom::Lower;
    use splinescope_gpu::adaptive::DEFAULT_TOLERANCE_PX;
    use splinescope_gpu::capture::{OFFSCREEN_FORMAT, render_uploaded};
    use splinescope_gpu::chunks::ChunkLimits;
    use splinescope_gpu::pack::{prepare, repack_points};
    use splinescope_gpu::renderer::Renderer;
    use splinescope_scene::format::encoding::encode;
    common::on_each_gpu(
        "an_edit_written_in_place_renders_like_a_fresh_upload",
        |backend| {
            let ctx = &backend.ctx;
            let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes/paper001_fig1.json");
            let scene = Scene::load(&path).expect("scene");
            let limits = ChunkLimits::for_binding_size(ctx.max_binding_bytes());
            let renderer = Renderer::new(&ctx.device, &backend.pipelines, OFFSCREEN_FORMAT);
            let prepared = prepare(&encode(&scene), limits).expect("pack");
            let mut gpu = renderer.upload(ctx, &prepared);
            let viewport = DVec2::new(320.0, 240.0);
            let camera = scene.camera(viewport);
            let before = render_uploaded(
                ctx,
                &renderer,
                &mut gpu,
                &camera,
                (320, 240),
                DEFAULT_TOLERANCE_PX,
            )
            .expect("render");
            // Edit the standard curve: a shape parameter and a move of a control point.
            let edit = |dy: f64| {
                let mut edited = scene.clone();
                let Curve::Nubmp(n) = &scene.curves[0].curve else {
                    panic!("a NUBMP curve")
                };
                let mut n = n.clone();
                let g = &n.groups()[5];
                let values: Vec<f64> = g
                    .values
                    .iter()
                    .zip([0.01, -0.005, -0.005])
                    .map(|(v, d)| v + d)
                    .collect();
                n.set_group(5, &values).expect("valid");
                let moved = edited.curves[0].curve.control_points()[3] + DVec3::new(0.0, dy, 0.0);
                edited.curves[0].curve = Curve::Nubmp(n)
                    .with_control_point(3, moved)
                    .expect("finite");
                edited
            };
            let repack = |edited: &Scene| {
                repack_points(
                    &prepared.placements[0],
                    &prepared.sample_counts[0],
                    &edited.curves[0].curve.lower(),
                    edited.samples_for(0),
                )
            };
            // Sample counts are chosen on the GPU every frame: even a large move, which changes
            // the curvature a lot, keeps the structure (segments and degrees) and is written
            // in place.
            let edited = edit(2.0);
            let writes = repack(&edited).expect("same structure");
            for (chunk, first, verts) in writes {
                gpu.write_points(&ctx.queue, chunk, first, &verts);
            }
            // The overlays (control polygon, dual polygon, points) are written in place
            // too, as the viewer does during a drag.
            let edit = splinescope_gpu::overlays::OverlayEdit {
                switches: splinescope_encoding::draw::Switches::ALL,
                curve_count: edited.curves.len(),
                curves: vec![(
                    0,
                    splinescope_scene::format::draw::curve_overlays(
                        &edited.curves[0],
                        splinescope_encoding::draw::Switches::ALL,
                    ),
                )],
                axes: splinescope_scene::format::draw::axis_lines(&edited),
            };
            let (lines, points) = prepared
                .overlay_map
                .rewrite(&edit)
                .expect("the overlays keep their shape");
            gpu.write_overlays(&ctx.queue, &lines, &points);
            let in_place = render_uploaded(
                ctx,
                &renderer,
                &mut gpu,
                &camera,
                (320, 240),
                DEFAULT_TOLERANCE_PX,
            )
            .expect("render");
            let fresh = render_scene(ctx, &backend.pipelines, &edited, Some(camera), 320, 240)
                .expect("render");
            assert_eq!(
                in_place, fresh,
                "in-place update and fresh upload must draw the same pixels"
            );
            assert_ne!(in_place, before, "the edit must change the picture");
        },
    );
}
