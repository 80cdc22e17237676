//! The command line end to end: eval on both backends, render, check, the default job and
//! bad arguments.

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

use serde_json::Value;
use splinescope_core::geom::{Aabb, ParamCurve};
use splinescope_image::RgbaImage;
use splinescope_scene::format::Scene;

use common::{bin, run};

fn scene_path(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

fn stdout_json(out: &Output) -> Value {
    assert!(
        out.status.success(),
        "exit {:?}: {}",
        out.status.code(),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("stdout is JSON")
}

fn samples(v: &Value, curve: usize) -> Vec<[f64; 3]> {
    vectors(v, curve, "samples")
}

#[test]
fn eval_cpu_prints_exact_samples_over_the_domain() {
    let out = run(&["eval", &scene_path("gallery.json"), "--samples", "5"]);
    let v = stdout_json(&out);
    let scene = Scene::load(Path::new(&scene_path("gallery.json"))).unwrap();
    let curves = v["curves"].as_array().unwrap();
    assert_eq!(curves.len(), scene.curves.len());
    for (i, c) in scene.curves.iter().enumerate() {
        assert_eq!(curves[i]["index"], i);
        let s = samples(&v, i);
        assert_eq!(s.len(), 5);
        // Uniform over the curve's own domain, ends included: the batch evaluator over the
        // exact lowering agrees with the family's own evaluation to rounding.
        let (a, b) = c.curve.domain();
        let scale = c
            .curve
            .control_points()
            .iter()
            .map(|p| p.length())
            .fold(1.0, f64::max);
        for (k, t) in [(0, a), (2, a + 0.5 * (b - a)), (4, b)] {
            let want = c.curve.eval(t);
            let got = glam::DVec3::from_array(s[k]);
            assert!(
                (got - want).length() <= 1e-12 * scale,
                "curves[{i}] at t = {t}: {got} vs {want}"
            );
        }
        // Bézier curves interpolate their end control points exactly.
        if c.curve.family() == "bezier" {
            let pts = c.curve.control_points();
            assert_eq!(s[0], pts[0].to_array());
            assert_eq!(s[4], pts[pts.len() - 1].to_array());
        }
    }
}

/// Every scene in `scenes/`, on every backend present: `eval --backend gpu` agrees with
/// the CPU within the bound of tests/gpu_tessellation.rs, taken over the curve's lowered
/// segments.
#[test]
fn eval_gpu_agrees_with_cpu_on_every_scene_and_backend() {
    use splinescope_core::geom::Lower;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("scenes")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    paths.sort();
    assert!(paths.len() >= 6, "{paths:?}");
    common::on_each_gpu(
        "eval_gpu_agrees_with_cpu_on_every_scene_and_backend",
        |backend| {
            for path in &paths {
                let path = path.to_string_lossy();
                let cpu = stdout_json(&run(&["eval", &path, "--samples", "257"]));
                let gpu = stdout_json(&run(&[
                    "eval",
                    &path,
                    "--samples",
                    "257",
                    "--backend",
                    "gpu",
                    "--gpu-backend",
                    &backend.name,
                ]));
                let scene = Scene::load(Path::new(path.as_ref())).unwrap();
                for (i, c) in scene.curves.iter().enumerate() {
                    let segments = c.curve.lower();
                    let pts: Vec<_> = segments
                        .iter()
                        .flat_map(|s| s.bezier.points().to_vec())
                        .collect();
                    let extent = Aabb::from_points(&pts).diagonal();
                    let radius = pts.iter().map(|p| p.length()).fold(0.0, f64::max);
                    let degree = segments
                        .iter()
                        .map(|s| s.bezier.degree())
                        .max()
                        .unwrap_or(0);
                    let bound = 1e-6 * extent.max(radius) * (degree.max(12) as f64 / 12.0);
                    let (a, b) = (samples(&cpu, i), samples(&gpu, i));
                    assert_eq!(a.len(), b.len());
                    for (a, b) in a.iter().zip(b) {
                        let d =
                            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2))
                                .sqrt();
                        assert!(
                            d <= bound,
                            "{}: {path} curve {i}: |cpu − gpu| = {d:e} > {bound:e}",
                            backend.name
                        );
                    }
                }
            }
        },
    );
}

#[test]
fn eval_params_evaluate_at_the_given_parameters_on_both_backends() {
    let path = scene_path("bezier3d.json");
    let v = stdout_json(&run(&[
        "eval", &path, "--params", "0.25,0.5", "--curve", "1",
    ]));
    let scene = Scene::load(Path::new(&path)).unwrap();
    assert_eq!(v["curves"].as_array().unwrap().len(), 1);
    assert_eq!(v["curves"][0]["index"], 1);
    let s = samples(&v, 0);
    assert_eq!(s[0], scene.curves[1].curve.eval(0.25).to_array());
    assert_eq!(s[1], scene.curves[1].curve.eval(0.5).to_array());
    common::on_each_gpu("eval_params (gpu half)", |backend| {
        let g = stdout_json(&run(&[
            "eval",
            &path,
            "--params",
            "0.25,0.5",
            "--curve",
            "1",
            "--backend",
            "gpu",
            "--gpu-backend",
            &backend.name,
        ]));
        for (a, b) in s.iter().zip(samples(&g, 0)) {
            for k in 0..3 {
                assert!(
                    (a[k] - b[k]).abs() < 1e-5,
                    "{}: {a:?} vs {b:?}",
                    backend.name
                );
            }
        }
    });
}

fn stderr_of(args: &[&str]) -> (Option<i32>, String) {
    let out = run(args);
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn bad_eval_arguments_name_the_offending_value() {
    let path = scene_path("gallery.json");
    let cases: &[(&[&str], &str)] = &[
        (
            &["eval", &path, "--params", "0.5,1.5"],
            "--params[1] = 1.5 is outside the domain [0, 1] of curves[0]",
        ),
        (
            &["eval", &path, "--params", "0.5,abc"],
            "--params[1]: \"abc\" is not a number",
        ),
        (
            &["eval", &path, "--params", "nan"],
            "--params[0]: NaN is not a finite number",
        ),
        (&["eval", &path], "give --samples N or --params"),
        (
            &["eval", &path, "--samples", "3", "--curve", "99"],
            "--curve 99: the scene has 25 curve(s) (indices 0 to 24)",
        ),
        (
            &["eval", "/nonexistent/scene.json", "--samples", "3"],
            "/nonexistent/scene.json: cannot read the file",
        ),
    ];
    for (args, want) in cases {
        let (code, err) = stderr_of(args);
        assert_eq!(code, Some(1), "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err:?} lacks {want:?}");
    }
    // Argument syntax errors are clap's (exit 2), naming the argument.
    for (args, want) in [
        (vec!["eval", path.as_str(), "--samples", "1"], "--samples"),
        (vec!["render", "-o", "x.png", "--width", "0"], "--width"),
        (
            vec!["eval", path.as_str(), "--samples", "3", "--backend", "tpu"],
            "--backend",
        ),
        (
            vec!["render", "-o", "x.png", "--gpu-backend", "glide"],
            "unknown GPU backend \"glide\"",
        ),
    ] {
        let (code, err) = stderr_of(&args);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
}

fn out_dir() -> PathBuf {
    common::out_dir("cli")
}

fn write_degree_40_scene() -> PathBuf {
    let pts: Vec<String> = (0..=40)
        .map(|i| format!("[{}, {}]", i, if i % 2 == 0 { 0 } else { 1 }))
        .collect();
    let path = out_dir().join("degree40.json");
    std::fs::write(
        &path,
        format!(
            "{{\"version\": 1, \"curves\": [{{\"type\": \"bezier\", \"points\": [{}]}}]}}",
            pts.join(", ")
        ),
    )
    .unwrap();
    path
}

/// Coordinates near 1e308 are fine for the f64 CPU path but overflow f32: `check`, `eval
/// --backend gpu` and `render` refuse them alike, naming the curve and the point (an
/// annotation's too).
#[test]
fn coordinates_beyond_f32_are_refused_by_check_and_the_gpu_path_alike() {
    let path = out_dir().join("huge.json");
    std::fs::write(
        &path,
        r#"{"version": 1, "curves": [
            {"type": "bezier", "points": [[0, 0], [1, 1]]},
            {"type": "bezier", "points": [[0, 0], [1e308, 1], [2, 0]]}
        ]}"#,
    )
    .unwrap();
    let s = path.to_string_lossy();
    let want = "curves[1]: Bézier segment 0, control point 1 has coordinate 1e308, beyond the GPU's f32 range of ±1e38";
    let (code, err) = stderr_of(&["check", &s]);
    assert_eq!(code, Some(1));
    assert!(err.contains(want), "{err}");
    common::on_each_gpu("huge coordinates (gpu half)", |backend| {
        let out_png = out_dir().join(format!("huge.{}.png", backend.name));
        let _ = std::fs::remove_file(&out_png);
        for args in [
            vec![
                "render",
                &s,
                "-o",
                &out_png.to_string_lossy(),
                "--gpu-backend",
                &backend.name,
            ],
            vec![
                "eval",
                &s,
                "--samples",
                "3",
                "--backend",
                "gpu",
                "--gpu-backend",
                &backend.name,
            ],
        ] {
            let (code, err) = stderr_of(&args);
            assert_eq!(code, Some(1), "{}: {args:?}", backend.name);
            assert!(err.contains(want), "{}: {err}", backend.name);
        }
        assert!(!out_png.exists(), "a refused render writes nothing");
    });
    let annotated = out_dir().join("huge_annotation.json");
    std::fs::write(
        &annotated,
        r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1, 1]]}],
            "annotations": [{"points": [[0, 0], [3e38, 0]]}]}"#,
    )
    .unwrap();
    let (code, err) = stderr_of(&["check", &annotated.to_string_lossy()]);
    assert_eq!(code, Some(1), "{err}");
    assert!(
        err.contains("annotations[0].points[1] has coordinate 3e38"),
        "{err}"
    );
}

#[test]
fn a_degree_over_the_gpu_maximum_is_an_error_on_the_gpu_and_fine_on_the_cpu() {
    let scene = write_degree_40_scene();
    let s = scene.to_string_lossy();
    let want = "curves[0]: Bézier segment 0 has degree 40, over the GPU maximum of 31";
    let (code, err) = stderr_of(&["check", &s]);
    assert_eq!(code, Some(1));
    assert!(err.contains(want), "{err}");
    let v = stdout_json(&run(&["eval", &s, "--samples", "3"]));
    assert_eq!(samples(&v, 0)[2], [40.0, 0.0, 0.0]);
    if !common::gpus("degree over max (gpu half)").is_empty() {
        let out_png = out_dir().join("degree40.png");
        let (code, err) = stderr_of(&["render", &s, "-o", &out_png.to_string_lossy()]);
        assert_eq!(code, Some(1));
        assert!(err.contains(want), "{err}");
        let (code, err) = stderr_of(&["eval", &s, "--samples", "3", "--backend", "gpu"]);
        assert_eq!(code, Some(1));
        assert!(err.contains(want), "{err}");
    }
}

#[test]
fn render_writes_a_png_of_the_requested_size() {
    common::on_each_gpu("render_writes_a_png_of_the_requested_size", |backend| {
        let png = out_dir().join(format!("render.{}.png", backend.name));
        let _ = std::fs::remove_file(&png);
        let out = run(&[
            "render",
            &scene_path("gallery.json"),
            "-o",
            &png.to_string_lossy(),
            "--width",
            "321",
            "--height",
            "123",
            "--gpu-backend",
            &backend.name,
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let img = RgbaImage::read_png(&png).expect("png");
        assert_eq!((img.width, img.height), (321, 123));
        // Something other than the white background was drawn.
        assert!(img.data.chunks_exact(4).any(|p| p[0] < 128));
    });
}

#[test]
fn no_arguments_and_no_display_render_the_gallery_and_say_where() {
    common::on_each_gpu(
        "no_arguments_and_no_display_render_the_gallery_and_say_where",
        |backend| {
            let dir = out_dir().join(format!("headless-{}", backend.name));
            std::fs::create_dir_all(&dir).unwrap();
            let png = dir.join("splinescope-gallery.png");
            let _ = std::fs::remove_file(&png);
            let out = bin()
                .current_dir(&dir)
                .env("WGPU_BACKEND", &backend.name)
                .env_remove("DISPLAY")
                .env_remove("WAYLAND_DISPLAY")
                .output()
                .expect("run");
            let stdout = String::from_utf8_lossy(&out.stdout);
            assert!(
                out.status.success(),
                "{}",
                String::from_utf8_lossy(&out.stderr)
            );
            assert!(stdout.contains("no display found"), "{stdout}");
            assert!(
                stdout.contains(&backend.ctx.describe()),
                "{}: the message names the adapter used: {stdout}",
                backend.name
            );
            assert!(
                stdout.contains(&png.to_string_lossy().into_owned()),
                "{stdout}"
            );
            let img = RgbaImage::read_png(&png).expect("png");
            assert_eq!((img.width, img.height), (1600, 1000));
        },
    );
}

#[test]
fn view_without_a_display_is_a_clear_error() {
    let out = bin()
        .args(["view", "--frames", "1"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("run");
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no display found"));
}

#[test]
fn check_summarises_a_valid_scene() {
    let out = run(&["check", &scene_path("gallery.json")]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    let n = Scene::load(Path::new(&scene_path("gallery.json")))
        .unwrap()
        .curves
        .len();
    assert!(
        text.contains(&format!("valid scene, {n} curve(s)")),
        "{text}"
    );
    assert!(text.contains("every curve fits the GPU kernel"), "{text}");
}

#[test]
fn eval_samples_cover_each_familys_own_domain() {
    // Interpolation over [t_0, t_k] = [0, 3]: 4 samples land on the interpolated points.
    let v = stdout_json(&run(&[
        "eval",
        &scene_path("paper002_examples.json"),
        "--samples",
        "4",
    ]));
    for curve in 0..3 {
        let s = samples(&v, curve);
        let want = [
            [0.0, 0.0, 0.0],
            [0.0, 6.0, 0.0],
            [6.0, 6.0, 0.0],
            [6.0, 0.0, 0.0],
        ];
        for (got, want) in s.iter().zip(want) {
            for k in 0..3 {
                assert!(
                    (got[k] - want[k]).abs() < 1e-12,
                    "curve {curve}: {got:?} vs {want:?}"
                );
            }
        }
    }
    // A clamped B-spline / NUBMP starts and ends at its end control points; --params is
    // in the curve's own parameter (here the domain is [0, 1]).
    let v = stdout_json(&run(&[
        "eval",
        &scene_path("paper001_fig1.json"),
        "--params",
        "0,1",
    ]));
    let scene = Scene::load(Path::new(&scene_path("paper001_fig1.json"))).unwrap();
    for (i, c) in scene.curves.iter().enumerate() {
        let pts = c.curve.control_points();
        let s = samples(&v, i);
        assert_eq!(s[0], pts[0].to_array());
        let last = pts[pts.len() - 1].to_array();
        for k in 0..3 {
            assert!((s[1][k] - last[k]).abs() < 1e-12);
        }
    }
    // The unclamped B-spline's domain is [t_(k-1), t_n] = [2, 7].
    let (code, err) = stderr_of(&[
        "eval",
        &scene_path("bsplines.json"),
        "--curve",
        "1",
        "--params",
        "1",
    ]);
    assert_eq!(code, Some(1));
    assert!(
        err.contains("--params[0] = 1 is outside the domain [2, 7] of curves[1]"),
        "{err}"
    );
}

#[test]
fn inspect_reports_the_papers_derived_data() {
    let v = stdout_json(&run(&[
        "inspect",
        &scene_path("paper001_fig1.json"),
        "--curve",
        "0",
    ]));
    let c = &v["curves"][0];
    assert_eq!(c["family"], "nubmp");
    assert_eq!(c["free_parameters"], 12);
    assert_eq!(c["exact_from"], "decimal knots");
    assert_eq!(c["refined_knots"].as_array().unwrap().len(), 16);
    // Exact coefficients of N_1 (checked against exact Cox–de Boor in tests/families.rs).
    assert_eq!(
        c["coefficients"][1]["exact"],
        serde_json::json!(["3/4", "7/10", "1/10"])
    );
    let g4 = &c["groups"][4];
    assert_eq!(g4["members"], serde_json::json!([2, 3]));
    let r = &g4["permissible_ranges"][0];
    assert_eq!(
        (r["member"].as_u64(), r["absorber"].as_u64()),
        (Some(2), Some(3))
    );
    assert!((r["min"].as_f64().unwrap() - 0.125427).abs() < 1e-6);
    assert!((r["max"].as_f64().unwrap() - 0.901685).abs() < 1e-6);
    assert_eq!(c["segments"].as_array().unwrap().len(), 4);
    assert_eq!(c["segments"][0]["degree"], 4);
    // Interpolation: tangents and inner points of paper 002's Example 1.
    let v = stdout_json(&run(&[
        "inspect",
        &scene_path("paper002_examples.json"),
        "--curve",
        "0",
    ]));
    let inner: Vec<Vec<f64>> =
        serde_json::from_value(v["curves"][0]["inner_points"][0].clone()).unwrap();
    assert_eq!(inner, vec![vec![-1.0, 3.0, 0.0], vec![-1.0, 5.0, 0.0]]);
}

#[test]
fn a_degree_over_the_maximum_after_lowering_is_caught() {
    // Order 33 lowers to degree-32 Bézier segments; NUBMP of order 32 too (its dual spline
    // has order 33).
    let path = out_dir().join("order33.json");
    let pts: Vec<String> = (0..33).map(|i| format!("[{i}, {}]", i % 3)).collect();
    std::fs::write(
        &path,
        format!(
            "{{\"version\": 1, \"curves\": [{{\"type\": \"bspline\", \"points\": [{p}], \"knots\": \"clamped_uniform\", \"order\": 33}}, {{\"type\": \"nubmp\", \"points\": [{p}], \"knots\": \"clamped_uniform\", \"order\": 32}}]}}",
            p = pts.join(", ")
        ),
    )
    .unwrap();
    let (code, err) = stderr_of(&["check", &path.to_string_lossy()]);
    assert_eq!(code, Some(1));
    assert!(
        err.contains("curves[0]: Bézier segment 0 has degree 32, over the GPU maximum of 31"),
        "{err}"
    );
    assert!(
        err.contains("curves[1]: Bézier segment 0 has degree 32"),
        "{err}"
    );
    // The CPU evaluates it.
    let v = stdout_json(&run(&["eval", &path.to_string_lossy(), "--samples", "2"]));
    assert_eq!(samples(&v, 0)[1], [32.0, 2.0, 0.0]);
}

#[test]
fn inspect_at_tau_reports_the_groups_and_their_regions() {
    let path = scene_path("paper001_fig1.json");
    let v = stdout_json(&run(&["inspect", &path, "--curve", "3", "--tau", "0.4"]));
    let c = &v["curves"][0];
    let at = &c["at_tau"];
    let p: Vec<f64> = at["point"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let groups = at["groups"].as_array().unwrap();
    // Order 4: the dual B-splines of order 5 acting at an interior τ: at most 5.
    assert!(!groups.is_empty() && groups.len() <= 5);
    let weight_sum: f64 = groups.iter().map(|g| g["weight"].as_f64().unwrap()).sum();
    assert!(
        (weight_sum - 1.0).abs() < 1e-12,
        "the dual B-splines sum to 1 at τ"
    );
    for g in groups {
        let j = g["group"].as_u64().unwrap() as usize;
        let values: Vec<f64> = c["groups"][j]["values"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let region = g["region"].as_array().unwrap();
        assert_eq!(region.len(), values.len());
        // Σ a_i (P(τ) + w (P_i − P*_j)) = P(τ): the current parameters locate P(τ).
        for k in 0..3 {
            let s: f64 = region
                .iter()
                .zip(&values)
                .map(|(r, a)| a * r[k].as_f64().unwrap())
                .sum();
            assert!((s - p[k]).abs() < 1e-12, "group {j}");
        }
    }
    let (code, err) = stderr_of(&["inspect", &path, "--tau", "1.4"]);
    assert_eq!(code, Some(1));
    assert!(
        err.contains("--tau 1.4 is outside the domain [0, 1] of curves[0]"),
        "{err}"
    );
}

/// `adapters` lists, for each backend present, its adapters with their limits and
/// self-test, and marks exactly the one offscreen commands use.
#[test]
fn adapters_lists_each_backend_and_marks_the_chosen_one() {
    common::on_each_gpu("adapters", |backend| {
        let v = stdout_json(&run(&[
            "adapters",
            "--json",
            "--gpu-backend",
            &backend.name,
        ]));
        assert_eq!(v["backends"], backend.name.as_str());
        let list = v["adapters"].as_array().expect("adapters");
        assert!(!list.is_empty(), "{}: {v}", backend.name);
        let info = backend.ctx.adapter.get_info();
        for a in list {
            assert_eq!(a["backend"], format!("{:?}", info.backend), "{a}");
            assert!(a["max_storage_binding_bytes"].as_u64().unwrap() > 0, "{a}");
            assert!(
                a["max_workgroups_per_dimension"].as_u64().unwrap() > 0,
                "{a}"
            );
            assert!(a["timestamps"].is_boolean(), "{a}");
        }
        let chosen: Vec<&Value> = list.iter().filter(|a| a["chosen"] == true).collect();
        assert_eq!(chosen.len(), 1, "{}: {v}", backend.name);
        assert_eq!(chosen[0]["name"], info.name.as_str());
        assert_eq!(chosen[0]["self_test"], "passed");
        let text = run(&["adapters", "--gpu-backend", &backend.name]);
        let text = String::from_utf8_lossy(&text.stdout);
        assert!(text.contains("kernel self-test: passed"), "{text}");
        assert!(
            text.contains(&format!("* {}", info.name)),
            "the chosen adapter is starred: {text}"
        );
    });
}

fn vectors(v: &Value, curve: usize, key: &str) -> Vec<[f64; 3]> {
    v["curves"][curve][key]
        .as_array()
        .unwrap_or_else(|| panic!("{key} missing"))
        .iter()
        .map(|p| {
            let a = p.as_array().expect("vector");
            [0, 1, 2].map(|i| a[i].as_f64().expect("number"))
        })
        .collect()
}

/// `eval --derivatives 2`: P′ and P″ against central differences of the exact curve (at
/// the middle of every lowered segment, away from joints where P″ may jump), the curvature
/// against a closed form, and the GPU (hodographs through the same kernel) against the CPU
/// within the documented bound applied to the hodographs' control points.
#[test]
fn eval_derivatives_match_finite_differences_closed_forms_and_the_gpu() {
    use splinescope_core::geom::Lower;
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    for name in [
        "gallery.json",
        "bezier3d.json",
        "paper001_fig1.json",
        "bsplines.json",
    ] {
        let path = dir.join(name);
        let scene = Scene::load(&path).unwrap();
        for (i, c) in scene.curves.iter().enumerate() {
            let segs = c.curve.lower();
            let ts: Vec<f64> = segs.iter().map(|s| 0.5 * (s.t0 + s.t1)).collect();
            let list = ts
                .iter()
                .map(|t| format!("{t:e}"))
                .collect::<Vec<_>>()
                .join(",");
            let p = path.to_string_lossy();
            let idx = i.to_string();
            let args = [
                "eval",
                &p,
                "--curve",
                &idx,
                "--params",
                &list,
                "--derivatives",
                "2",
            ];
            let cpu = stdout_json(&run(&args));
            let (d1, d2) = (vectors(&cpu, 0, "d1"), vectors(&cpu, 0, "d2"));
            for (k, (&t, s)) in ts.iter().zip(&segs).enumerate() {
                let h = 1e-5 * (s.t1 - s.t0);
                let fd1 = (c.curve.eval(t + h) - c.curve.eval(t - h)) / (2.0 * h);
                let fd2 = (c.curve.eval_deriv(t + h) - c.curve.eval_deriv(t - h)) / (2.0 * h);
                let scale1 = fd1.length().max(1.0);
                let scale2 = fd2.length().max(1.0);
                let e1 = (glam::DVec3::from(d1[k]) - fd1).length();
                let e2 = (glam::DVec3::from(d2[k]) - fd2).length();
                assert!(
                    e1 <= 1e-6 * scale1,
                    "{name} curves[{i}] t={t}: P′ off by {e1:e}"
                );
                assert!(
                    e2 <= 1e-5 * scale2,
                    "{name} curves[{i}] t={t}: P″ off by {e2:e}"
                );
            }
            common::on_each_gpu("eval --derivatives (gpu half)", |backend| {
                let mut gargs = args.to_vec();
                gargs.extend(["--backend", "gpu", "--gpu-backend", &backend.name]);
                let gpu = stdout_json(&run(&gargs));
                for (key, order) in [("d1", 1u32), ("d2", 2)] {
                    let (want, got) = (vectors(&cpu, 0, key), vectors(&gpu, 0, key));
                    for (k, s) in segs.iter().enumerate() {
                        let h = splinescope_gpu::eval::hodographs(std::slice::from_ref(s), order);
                        let pts = h[0].bezier.points();
                        let extent = Aabb::from_points(pts).diagonal();
                        let radius = pts.iter().map(|p| p.length()).fold(0.0, f64::max);
                        let n = s.bezier.degree();
                        let bound = 1e-6 * extent.max(radius) * (n.max(12) as f64 / 12.0)
                            / (s.t1 - s.t0).powi(order as i32);
                        let e = (glam::DVec3::from(want[k]) - glam::DVec3::from(got[k])).length();
                        assert!(
                            e <= bound,
                            "{}: {name} curves[{i}] {key} at segment {k}: {e:e} > {bound:e}",
                            backend.name
                        );
                    }
                }
            });
        }
    }
    // Curvature of the parabola P(t) = (2t, 4t(1 − t)): κ = 16 / (4 + (4 − 8t)²)^{3/2}.
    let d = out_dir();
    let parabola = d.join("parabola.json");
    std::fs::write(
        &parabola,
        r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1, 2], [2, 0]]}]}"#,
    )
    .unwrap();
    let v = stdout_json(&run(&[
        "eval",
        &parabola.to_string_lossy(),
        "--params",
        "0,0.25,0.5",
        "--derivatives",
        "2",
    ]));
    let kappa: Vec<f64> = v["curves"][0]["curvature"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k.as_f64().unwrap())
        .collect();
    for (k, t) in kappa.iter().zip([0.0_f64, 0.25, 0.5]) {
        let want = 16.0 / (4.0 + (4.0 - 8.0 * t).powi(2)).powf(1.5);
        assert!((k - want).abs() <= 1e-14 * want, "t={t}: {k} vs {want}");
    }
    // A point where P′ = 0 has no curvature: null, not a number.
    let cusp = d.join("cusp.json");
    std::fs::write(
        &cusp,
        r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [0, 0], [1, 1]]}]}"#,
    )
    .unwrap();
    let v = stdout_json(&run(&[
        "eval",
        &cusp.to_string_lossy(),
        "--params",
        "0",
        "--derivatives",
        "2",
    ]));
    assert!(v["curves"][0]["curvature"][0].is_null(), "{v}");
    let (code, err) = stderr_of(&[
        "eval",
        &cusp.to_string_lossy(),
        "--params",
        "0",
        "--derivatives",
        "3",
    ]);
    assert_eq!(code, Some(2), "{err}");
}

/// `inspect`'s power-basis coefficients of a Bézier curve: the exact rationals of the
/// decimals written in the file, against an independent expansion of the Bernstein sum in
/// integers (coordinates in tenths), and the f64 values against the curve.
#[test]
fn inspect_reports_exact_power_basis_coefficients_of_the_decimal_input() {
    let tenths: [[i64; 2]; 4] = [[1, 0], [2, 7], [13, -4], [20, 10]];
    let d = out_dir();
    let path = d.join("power.json");
    let pts: Vec<String> = tenths
        .iter()
        .map(|p| format!("[{}, {}]", p[0] as f64 / 10.0, p[1] as f64 / 10.0))
        .collect();
    std::fs::write(
        &path,
        format!(
            r#"{{"version": 1, "curves": [{{"type": "bezier", "points": [{}]}}]}}"#,
            pts.join(", ")
        ),
    )
    .unwrap();
    // Σ_i P_i C(3,i) t^i (1 − t)^{3−i}, multiplied out as integer polynomials.
    let n = 3usize;
    let binom = |n: usize, k: usize| -> i64 {
        (0..k).fold(1i64, |b, j| b * (n - j) as i64 / (j as i64 + 1))
    };
    let mut want = vec![[0i64; 2]; n + 1];
    for (i, p) in tenths.iter().enumerate() {
        // (1 − t)^{n−i} = Σ_j C(n−i, j) (−t)^j
        for j in 0..=n - i {
            let c = binom(n, i) * binom(n - i, j) * if j % 2 == 0 { 1 } else { -1 };
            for axis in 0..2 {
                want[i + j][axis] += c * p[axis];
            }
        }
    }
    let reduce = |num: i64| -> String {
        let g = (1..=10)
            .rev()
            .find(|g| num % g == 0 && 10 % g == 0)
            .unwrap_or(1);
        let (a, b) = (num / g, 10 / g);
        if b == 1 {
            a.to_string()
        } else {
            format!("{a}/{b}")
        }
    };
    let v = stdout_json(&run(&["inspect", &path.to_string_lossy()]));
    let pb = &v["curves"][0]["power_basis"];
    for k in 0..=n {
        for axis in 0..2 {
            assert_eq!(
                pb["exact"][k][axis].as_str().unwrap(),
                reduce(want[k][axis]),
                "a_{k}[{axis}]"
            );
        }
        assert_eq!(pb["exact"][k][2], "0");
    }
    let scene = Scene::load(&path).unwrap();
    for t in [0.0, 0.3, 0.77, 1.0] {
        let p = scene.curves[0].curve.eval(t);
        let mut q = [0.0; 2];
        for k in (0..=n).rev() {
            for axis in 0..2 {
                q[axis] = q[axis] * t + pb["values"][k][axis].as_f64().unwrap();
            }
        }
        assert!(
            (q[0] - p.x).abs() < 1e-12 && (q[1] - p.y).abs() < 1e-12,
            "t={t}"
        );
    }
}

/// `inspect` classifies a cubic's control polygon as paper 000 §2.3 does, with the finer
/// subtype and where the legs' lines meet (worked out by hand below), and reports an
/// interpolation's chord slopes and parabola weights (paper 002's Example 1).
#[test]
fn inspect_reports_cubic_subtypes_and_interpolation_weights() {
    let d = out_dir();
    /// Name, control points, type, subtype, where the legs' lines meet.
    type Case = (
        &'static str,
        [[f64; 2]; 4],
        u64,
        &'static str,
        Option<[f64; 2]>,
    );
    let cases: [Case; 5] = [
        (
            "parallel",
            [[0.0, 0.0], [0.0, 1.0], [4.0, 1.0], [4.0, 0.0]],
            1,
            "parallel",
            None,
        ),
        (
            "anti",
            [[0.0, 0.0], [0.0, 1.0], [4.0, -1.0], [4.0, 0.0]],
            1,
            "antiparallel",
            None,
        ),
        (
            "conv",
            [[0.0, 0.0], [1.0, 1.0], [3.0, 1.0], [4.0, 0.0]],
            2,
            "converging",
            Some([2.0, 2.0]),
        ),
        (
            "div",
            [[0.0, 0.0], [-1.0, 1.0], [5.0, 1.0], [4.0, 0.0]],
            3,
            "diverging",
            Some([2.0, -2.0]),
        ),
        (
            "mixed",
            [[0.0, 0.0], [1.0, 1.0], [5.0, -1.0], [4.0, 0.0]],
            3,
            "mixed",
            Some([2.0, 2.0]),
        ),
    ];
    for (name, pts, ty, subtype, meet) in cases {
        let path = d.join(format!("region_{name}.json"));
        let list: Vec<String> = pts
            .iter()
            .map(|p| format!("[{}, {}]", p[0], p[1]))
            .collect();
        std::fs::write(
            &path,
            format!(
                r#"{{"version": 1, "curves": [{{"type": "bezier", "points": [{}]}}]}}"#,
                list.join(", ")
            ),
        )
        .unwrap();
        let v = stdout_json(&run(&["inspect", &path.to_string_lossy()]));
        let r = &v["curves"][0]["cubic_region"];
        assert_eq!(r["type"], ty, "{name}: {r}");
        assert_eq!(r["subtype"], subtype, "{name}: {r}");
        match meet {
            None => assert!(r.get("lines_meet_at").is_none(), "{name}: {r}"),
            Some(m) => {
                let x = &r["lines_meet_at"];
                for k in 0..2 {
                    assert!((x[k].as_f64().unwrap() - m[k]).abs() < 1e-12, "{name}: {r}");
                }
            }
        }
    }
    // Example 1: chords (0,6), (6,0), (0,−6) over unit steps; weights 1/2, 1/2.
    let ex = d.join("example1.json");
    std::fs::write(
        &ex,
        r#"{"version": 1, "curves": [{"type": "interpolation", "points": [[0, 0], [0, 6], [6, 6], [6, 0]], "params": [0, 1, 2, 3]}]}"#,
    )
    .unwrap();
    let v = stdout_json(&run(&["inspect", &ex.to_string_lossy()]));
    let c = &v["curves"][0];
    let chords = vectors(&v, 0, "chord_slopes");
    assert_eq!(
        chords,
        vec![[0.0, 6.0, 0.0], [6.0, 0.0, 0.0], [0.0, -6.0, 0.0]]
    );
    assert_eq!(c["parabola_weights"], serde_json::json!([0.5, 0.5]));
}

/// Whole numbers out of their range are refused with the range in words, never in Rust's
/// range syntax.
#[test]
fn out_of_range_numbers_are_refused_in_words() {
    let cases: [(&[&str], &str); 4] = [
        (
            &["render", "-o", "/dev/null/never.png", "--width", "0"],
            "0 is not a whole number between 1 and 16384",
        ),
        (
            &["view", "--stress", "5", "--degree", "40"],
            "40 is not a whole number between 1 and 31",
        ),
        (
            &["eval", "--samples", "1"],
            "1 is not a whole number between 2 and 10000000",
        ),
        (
            &["export", "-o", "/dev/null/never.svg", "--height", "wide"],
            "wide is not a whole number between 1 and 16384",
        ),
    ];
    for (args, want) in cases {
        let (code, err) = stderr_of(args);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
        assert!(!err.contains("..="), "{args:?}: {err}");
    }
}
