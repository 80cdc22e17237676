//! `splinescope analyze` end to end: the numbers it prints are the closed forms (a NURBS
//! circle's length and area, a parabola's vertex), the text and JSON forms agree, and bad
//! arguments are refused naming the value.

use std::f64::consts::PI;

use serde_json::Value;

mod common;

fn scene(name: &str, text: &str) -> String {
    let p = common::out_dir("analyze-cli").join(name);
    std::fs::write(&p, text).expect("write scene");
    p.to_string_lossy().into_owned()
}

const CIRCLE: &str = r#"{"version": 1, "curves": [
  {"type": "nurbs", "name": "circle", "order": 3,
   "knots": [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1],
   "points": [[2, 0], [2, 2], [0, 2], [-2, 2], [-2, 0], [-2, -2], [0, -2], [2, -2], [2, 0]],
   "weights": [1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1]},
  {"type": "bezier", "name": "parabola", "points": [[-1, 1], [0, -1], [1, 1]]},
  {"type": "bezier", "name": "line", "points": [[-3, 0.5], [3, 0.5]]}
]}"#;

#[test]
fn analyze_reports_the_closed_forms() {
    let path = scene("circle.json", CIRCLE);
    let out = common::run(&[
        "analyze",
        &path,
        "--json",
        "--intersections",
        "--accuracy",
        "1e-12",
    ]);
    assert!(out.status.success(), "{}", common::text(&out));
    let v: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let c = &v["curves"][0];
    assert!(
        (c["length"].as_f64().unwrap() - 4.0 * PI).abs() <= 1e-13,
        "{c}"
    );
    assert!(c["length_error"].as_f64().unwrap() <= 1e-12, "{c}");
    assert_eq!(c["closed"], true);
    assert!((c["signed_area"].as_f64().unwrap() - 4.0 * PI).abs() <= 1e-12);
    let min: Vec<f64> = c["bounding_box"]["min"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(min, vec![-2.0, -2.0, 0.0]);
    assert_eq!(
        c["curvature_extrema"].as_array().unwrap().len(),
        0,
        "a circle has none"
    );
    let p = &v["curves"][1];
    assert!(p.get("signed_area").is_none(), "open: no area");
    let vertex = &p["curvature_extrema"][0];
    assert_eq!(vertex["kind"], "maximum");
    assert!((vertex["t"].as_f64().unwrap() - 0.5).abs() < 1e-12);
    assert!((vertex["curvature"].as_f64().unwrap() - 2.0).abs() < 1e-9);
    // The extremum is of |κ|, with the signed κ and the side alongside.
    assert!((vertex["abs_curvature"].as_f64().unwrap() - 2.0).abs() < 1e-9);
    assert_eq!(vertex["side"], "left");
    // The line y = ½ meets the circle twice and the parabola y = x² twice.
    let pairs = v["intersections"].as_array().unwrap();
    let find = |i: u64, j: u64| {
        pairs
            .iter()
            .find(|p| p["curves"][0].as_u64() == Some(i) && p["curves"][1].as_u64() == Some(j))
            .unwrap_or_else(|| panic!("pair {i} {j}: {v}"))
    };
    let circle_line = find(0, 2)["points"].as_array().unwrap().clone();
    assert_eq!(circle_line.len(), 2);
    for h in &circle_line {
        let x = h["point"][0].as_f64().unwrap();
        assert!((x.abs() - (4.0f64 - 0.25).sqrt()).abs() < 1e-14, "{h}");
        assert_eq!(h["kind"], "crossing");
    }
    let parabola_line = find(1, 2)["points"].as_array().unwrap().clone();
    assert_eq!(parabola_line.len(), 2);
    // The text form says the same.
    let out = common::run(&["analyze", &path, "--curve", "0", "--accuracy", "1e-12"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", common::text(&out));
    assert!(text.contains("curves[0] \"circle\" (nurbs, 2D)"), "{text}");
    // The text shows each value to what is known of it: the length within its stated
    // error of the JSON's every digit, the box's corners without rounding noise.
    let shown: f64 = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("length"))
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("a length line: {text}"));
    let (full, error) = (
        c["length"].as_f64().unwrap(),
        c["length_error"].as_f64().unwrap(),
    );
    assert!((shown - full).abs() <= error, "{shown} vs {full} ± {error}");
    assert!(text.contains("bounding box    (-2, -2) – (2, 2)"), "{text}");
    assert!(text.contains("closed, signed area 12.566370614"), "{text}");
    // Extrema with their points.
    assert!(text.contains("x at t = 0.5 (-2, 0)"), "{text}");
    // Below the rounding of the value (about 50 ε · 4π), the error it reports says so
    // instead of claiming the accuracy asked for.
    let out = common::run(&[
        "analyze",
        &path,
        "--curve",
        "0",
        "--json",
        "--accuracy",
        "1e-15",
    ]);
    assert!(out.status.success(), "{}", common::text(&out));
    let v: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let c = &v["curves"][0];
    assert!(
        (c["length"].as_f64().unwrap() - 4.0 * PI).abs() <= 1e-13,
        "{c}"
    );
    let error = c["length_error"].as_f64().unwrap();
    assert!(
        error > 1e-15 && error >= (4.0 * PI - c["length"].as_f64().unwrap()).abs(),
        "{c}"
    );
}

#[test]
fn analyze_refuses_bad_arguments() {
    let path = scene("circle2.json", CIRCLE);
    for (args, code, says) in [
        (
            vec!["--accuracy", "0"],
            2,
            "accuracy 0: must be a finite number greater than 0",
        ),
        (vec!["--accuracy", "-1"], 2, "accuracy -1: must be"),
        (vec!["--accuracy", "nan"], 2, "accuracy NaN: must be"),
        (
            vec!["--curve", "7"],
            1,
            "--curve 7: the scene has 3 curve(s)",
        ),
    ] {
        let mut all = vec!["analyze", path.as_str()];
        all.extend(args);
        let out = common::run(&all);
        assert_eq!(
            out.status.code(),
            Some(code),
            "{all:?}: {}",
            common::text(&out)
        );
        assert!(
            common::text(&out).contains(says),
            "{all:?}: {}",
            common::text(&out)
        );
    }
    let spatial = scene(
        "space.json",
        r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0, 0], [1, 1, 1], [2, 0, 2]]}]}"#,
    );
    let out = common::run(&["analyze", &spatial, "--intersections"]);
    assert_eq!(out.status.code(), Some(1), "{}", common::text(&out));
    assert!(common::text(&out).contains("curves[0] is not planar"));
    // Without --intersections a 3D curve is answered, without the planar questions.
    let out = common::run(&["analyze", &spatial, "--json"]);
    let v: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(v["curves"][0]["dimension"], 3);
    assert!(v["curves"][0].get("inflections").is_none());
}

/// Joints in the report: a cubic B-spline whose triple knot at 1 joins tangents built 90°
/// apart (from (2, 1) to (3, 1), then towards (3, 2)) and whose double knot at 2 keeps the
/// tangent but not the curvature; the circle's seam is G2.
#[test]
fn analyze_reports_the_joints() {
    let path = scene(
        "joints.json",
        r#"{"version": 1, "curves": [
  {"type": "bspline", "name": "kinked", "order": 4,
   "knots": [0, 0, 0, 0, 1, 1, 1, 2, 2, 3, 3, 3, 3],
   "points": [[0, 0], [1, 1.5], [2, 1], [3, 1], [3, 2], [3.5, 4], [5, 3], [6, 5], [7, 4]]},
  {"type": "nurbs", "name": "circle", "order": 3,
   "knots": [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1],
   "points": [[2, 0], [2, 2], [0, 2], [-2, 2], [-2, 0], [-2, -2], [0, -2], [2, -2], [2, 0]],
   "weights": [1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1, 0.7071067811865476, 1]}
]}"#,
    );
    let out = common::run(&["analyze", &path, "--json"]);
    assert!(out.status.success(), "{}", common::text(&out));
    let v: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let joints = v["curves"][0]["joints"].as_array().expect("joints");
    let at = |t: f64| {
        joints
            .iter()
            .find(|j| j["t"].as_f64() == Some(t))
            .unwrap_or_else(|| panic!("no joint at {t}: {joints:?}"))
    };
    let kink = at(1.0);
    assert_eq!(kink["class"], "G0", "{kink}");
    assert!(
        (kink["angle_deg"].as_f64().unwrap() - 90.0).abs() <= 1e-9,
        "{kink}"
    );
    let jump = at(2.0);
    assert_eq!(jump["class"], "G1", "{jump}");
    assert!(jump["curvature_jump"].as_f64().unwrap() > 1e-3, "{jump}");
    let circle = v["curves"][1]["joints"].as_array().expect("joints");
    assert!(circle.iter().all(|j| j["class"] == "G2"), "{circle:?}");
    assert_eq!(circle.iter().filter(|j| j["seam"] == true).count(), 1);
    // The text names the kink and the jump.
    let out = common::run(&["analyze", &path]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("G0 kink 90° at t = 1"), "{text}");
    assert!(text.contains("G1 curvature jump"), "{text}");
}

#[test]
fn analyze_finds_each_curves_nearest_point() {
    let path = scene("nearest.json", CIRCLE);
    // (3, 4) is 5 from the circle's centre: 3 from the circle, at (6/5, 8/5); the line
    // y = 0.5 from x = −3 to 3 is nearest at its end (3, 0.5), 3.5 away.
    let out = common::run(&["analyze", &path, "--json", "--nearest", "3,4"]);
    assert!(out.status.success(), "{}", common::text(&out));
    let v: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let n = &v["curves"][0]["nearest"];
    assert!(
        (n["distance"].as_f64().unwrap() - 3.0).abs() <= 1e-13,
        "{n}"
    );
    let point: Vec<f64> = n["point"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!(
        (point[0] - 1.2).abs() <= 1e-13 && (point[1] - 1.6).abs() <= 1e-13,
        "{n}"
    );
    let line = &v["curves"][2]["nearest"];
    assert!(
        (line["distance"].as_f64().unwrap() - 3.5).abs() <= 1e-14,
        "{line}"
    );
    // The line ends at x = 3: its nearest point is its end, t = 1.
    assert_eq!(line["t"].as_f64(), Some(1.0));
    // In 3D: the distance counts z.
    let out = common::run(&[
        "analyze",
        &path,
        "--json",
        "--curve",
        "2",
        "--nearest",
        "0,0.5,-2",
    ]);
    let v: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert!((v["curves"][0]["nearest"]["distance"].as_f64().unwrap() - 2.0).abs() <= 1e-15);
    // The text says it too.
    let out = common::run(&["analyze", &path, "--curve", "0", "--nearest", "3,4"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("nearest to (3, 4)") && text.contains("distance 3"),
        "{text}"
    );
    // Bad points are refused naming them.
    for (bad, says) in [
        ("3", "a point is X,Y or X,Y,Z"),
        ("3,y", "\"y\" is not a number"),
        ("3,NaN", "not a finite number"),
        ("1,2,3,4", "a point is X,Y or X,Y,Z"),
    ] {
        let out = common::run(&["analyze", &path, "--nearest", bad]);
        assert_eq!(out.status.code(), Some(2), "{}", common::text(&out));
        assert!(
            String::from_utf8_lossy(&out.stderr).contains(says),
            "{}",
            common::text(&out)
        );
    }
}
