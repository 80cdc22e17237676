//! `splinescope solve` end to end: the bad-request corpus (`tests/bad_requests/`), and
//! requests whose written scene reloads and passes through its targets.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use glam::DVec3;
use serde_json::Value;
use splinescope_core::geom::ParamCurve;
use splinescope_scene::format::{AnnotationShape, Scene};

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_requests")
}

fn solve(scene: &Path, request: &Path, out: Option<&Path>) -> (Option<i32>, String, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_splinescope"));
    cmd.arg("solve").arg(scene).arg(request);
    if let Some(o) = out {
        cmd.arg("-o").arg(o);
    }
    let o = cmd.output().expect("run");
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// (file, path in the request, fragment of the message).
const EXPECTED: &[(&str, &str, &str)] = &[
    (
        "unknown-curve",
        "curve",
        "curve 9 does not exist (the scene has 5 curve(s))",
    ),
    ("unknown-method", "method", "unknown method \"teleport\""),
    ("missing-method", "method", "missing"),
    ("target-nan", "target[0]", "not a finite number (NaN)"),
    ("target-missing", "target", "missing"),
    (
        "window-out-of-range",
        "first",
        "l = 2, m = 2: they must lie between 1 and 2",
    ),
    ("window-first-zero", "first", "l = 0, m = 1"),
    ("window-count-missing", "count", "missing"),
    ("t-at-end", "t", "t = 1 is an end of the curve"),
    (
        "t-outside",
        "t",
        "parameter 1.5 is outside the domain [0, 1]",
    ),
    (
        "target-projects-on-end",
        "target",
        "projects onto the fixed end point (t = 0)",
    ),
    (
        "tangent-no-direction",
        "curve",
        "no tangent direction at the start (P_0 = P_1)",
    ),
    (
        "tangent-degree-too-low",
        "curve",
        "tangent_kept needs degree ≥ 3, the curve has degree 2",
    ),
    (
        "wrong-family",
        "curve",
        "single_target modifies Bézier curves (paper 000) and rational Bézier and NURBS curves (weights fixed); curves[3] is nubmp",
    ),
    (
        "nubmp-method-on-bezier",
        "curve",
        "nubmp_constrained modifies NUBMP curves",
    ),
    ("field-not-used", "tau", "not used by single_target"),
    (
        "single-with-targets",
        "targets",
        "not used by single_target",
    ),
    (
        "multi-target-at-end",
        "targets[1]",
        "target 1 projects onto the fixed end point",
    ),
    ("multi-params-count", "params", "1 parameters for 2 targets"),
    (
        "multi-no-targets",
        "targets",
        "needs at least 1 point, found 0",
    ),
    (
        "cubic-region-on-quadratic",
        "curve",
        "defined for cubics; the curve has degree 2",
    ),
    (
        "q-outside-region",
        "target",
        "q is outside the region P(τ) can reach by changing group 5",
    ),
    (
        "tau-outside-domain",
        "tau",
        "parameter 1.5 is outside the domain [0, 1]",
    ),
    (
        "group-inactive",
        "group",
        "group 9 does not move P(τ) at τ = 0.1",
    ),
    ("group-missing", "group", "missing"),
    (
        "group-does-not-exist",
        "group",
        "group 40 does not exist (groups 0..11)",
    ),
    (
        "find-tau-unreachable",
        "group",
        "no τ in the group's support lets group 4 move the curve through q",
    ),
    (
        "second-request-bad",
        "[1].target[1]",
        "expected a number, found the string \"x\"",
    ),
    (
        "request-not-object",
        "[0]",
        "expected an object, found the number 5",
    ),
];

#[test]
fn every_bad_request_is_a_typed_error_naming_its_field() {
    let mut listed: Vec<&str> = EXPECTED.iter().map(|e| e.0).collect();
    listed.sort_unstable();
    let mut files: Vec<String> = std::fs::read_dir(corpus())
        .expect("corpus")
        .map(|e| {
            e.expect("entry")
                .path()
                .file_stem()
                .expect("stem")
                .to_string_lossy()
                .into_owned()
        })
        .filter(|n| n != "scene")
        .collect();
    files.sort();
    assert_eq!(files, listed);
    let scene = corpus().join("scene.json");
    let out = common::out_dir("solve").join("never.json");
    for (file, path, fragment) in EXPECTED {
        let _ = std::fs::remove_file(&out);
        let (code, _, err) = solve(&scene, &corpus().join(format!("{file}.json")), Some(&out));
        assert_eq!(code, Some(1), "{file}: {err}");
        assert!(
            err.contains(&format!("{file}.json: {path}: ")),
            "{file}: {err}"
        );
        assert!(err.contains(fragment), "{file}: {err}");
        assert!(!err.contains("panicked"), "{file}: {err}");
        assert!(
            !out.exists(),
            "{file}: a failed request must not write the scene"
        );
    }
}

fn scenes() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

#[test]
fn the_documented_requests_pass_through_their_targets() {
    let out = common::out_dir("solve").join("solved.json");
    let (code, stdout, err) = solve(
        &scenes().join("solve_demo.json"),
        &scenes().join("requests/all_methods.json"),
        Some(&out),
    );
    assert_eq!(code, Some(0), "{err}");
    let report: Value = serde_json::from_str(&stdout).expect("JSON report");
    let reports = report["reports"].as_array().expect("reports");
    assert_eq!(reports.len(), 5);
    let solved = Scene::load(&out).expect("the written scene reloads");
    let point = |v: &Value| {
        let a = v.as_array().unwrap();
        DVec3::new(
            a[0].as_f64().unwrap(),
            a[1].as_f64().unwrap(),
            a[2].as_f64().unwrap(),
        )
    };
    // cubic_region: the limited type-2 region; the target is in the cone but past the apex
    // cubic.
    assert_eq!(reports[0]["type"], 2);
    assert_eq!(reports[0]["reachable"], true);
    assert_eq!(reports[0]["reachable_limited"], false);
    // tangent_kept passes through its target at t.
    let t = reports[1]["t"].as_f64().unwrap();
    assert!((solved.curves[0].curve.eval(t) - point(&reports[1]["target"])).length() < 1e-9);
    // multi_target meets all three.
    for (k, t) in reports[2]["params"].as_array().unwrap().iter().enumerate() {
        let want = point(&reports[2]["targets"][k]);
        assert!((solved.curves[1].curve.eval(t.as_f64().unwrap()) - want).length() < 1e-9);
    }
    // nubmp_constrained lands P(τ) on q, parameters on the simplex.
    let tau = reports[3]["tau"].as_f64().unwrap();
    assert!((solved.curves[2].curve.eval(tau) - point(&reports[3]["target"])).length() < 1e-9);
    let values: Vec<f64> = reports[3]["values"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!((values.iter().sum::<f64>() - 1.0).abs() < 1e-12 && values.iter().all(|&v| v >= 0.0));
    // project: the reported point is on the curve at t, nearer than the curve's ends.
    let t = reports[4]["t"].as_f64().unwrap();
    let q = point(&reports[4]["target"]);
    let p = point(&reports[4]["point"]);
    assert!((solved.curves[2].curve.eval(t) - p).length() < 1e-12);
    assert!((p - q).length() <= (solved.curves[2].curve.eval(0.0) - q).length());
    // The written scene marks the targets and outlines the region.
    assert!(
        solved
            .annotations
            .iter()
            .any(|a| matches!(a.shape, AnnotationShape::Polyline(_)))
    );
    let marks: usize = solved
        .annotations
        .iter()
        .map(|a| match &a.shape {
            AnnotationShape::Points(p) => p.len(),
            AnnotationShape::Polyline(_) => 0,
        })
        .sum();
    assert_eq!(marks, 1 + 1 + 3 + 1 + 1);
}

/// Paper 000's three methods on the gallery's rational curves (weights held fixed): the
/// written scene reloads, each solved curve passes through its targets at the reported
/// parameters, and its weights are unchanged.
#[test]
fn solve_modifies_rational_curves_keeping_their_weights() {
    let gallery = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/gallery.json");
    let before = Scene::load(&gallery).expect("gallery");
    let dir = common::out_dir("solve_cli_rational");
    let request = dir.join("rational.json");
    // 19: the NURBS circle; 23: the NURBS ellipse; 24: the cubic NURBS curve.
    std::fs::write(
        &request,
        r#"[
  {"curve": 19, "method": "single_target", "target": [8.5, -24.5]},
  {"curve": 23, "method": "tangent_kept", "target": [27.0, -22.5], "t": 0.3},
  {"curve": 24, "method": "multi_target", "targets": [[38, -24], [43.5, -25]], "params": [0.3, 0.75]}
]"#,
    )
    .expect("write request");
    let out = dir.join("solved.json");
    let (code, stdout, stderr) = solve(&gallery, &request, Some(&out));
    assert_eq!(code, Some(0), "{stderr}");
    let reports: Value = serde_json::from_str(&stdout).expect("report JSON");
    let after = Scene::load(&out).expect("solved scene reloads");
    let weights = |s: &Scene, i: usize| -> Vec<f64> {
        match &s.curves[i].curve {
            splinescope_core::geom::Curve::Nurbs(n) => n.weights().to_vec(),
            splinescope_core::geom::Curve::RationalBezier(r) => r.weights().to_vec(),
            other => panic!("curves[{i}] is {}", other.family()),
        }
    };
    let checks: [(usize, Vec<DVec3>, Vec<f64>); 3] = [
        (
            19,
            vec![DVec3::new(8.5, -24.5, 0.0)],
            vec![reports["reports"][0]["t"].as_f64().expect("t")],
        ),
        (23, vec![DVec3::new(27.0, -22.5, 0.0)], vec![0.3]),
        (
            24,
            vec![DVec3::new(38.0, -24.0, 0.0), DVec3::new(43.5, -25.0, 0.0)],
            vec![0.3, 0.75],
        ),
    ];
    for (i, targets, ts) in checks {
        assert_eq!(
            weights(&after, i),
            weights(&before, i),
            "curves[{i}] weights"
        );
        assert_ne!(
            after.curves[i].curve, before.curves[i].curve,
            "curves[{i}] moved"
        );
        for (target, t) in targets.iter().zip(&ts) {
            let p = after.curves[i].curve.eval(*t);
            assert!(
                (p - *target).length() < 1e-9,
                "curves[{i}] at {t}: {p} vs {target}"
            );
        }
    }
}
