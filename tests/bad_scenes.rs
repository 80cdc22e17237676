//! The bad-input corpus (`tests/bad_scenes/*.json`): each malformed scene gives its typed
//! error naming the offending path, in the library and through the CLI, never a panic.

use std::path::{Path, PathBuf};
use std::process::Command;

use splinescope_scene::format::{Scene, SceneErrorKind};

/// (file, path the error must name — empty for the document as a whole, which the message
/// then names no path for — fragment its message must contain).
const EXPECTED: &[(&str, &str, &str)] = &[
    (
        "not-json",
        "",
        "invalid JSON at line 2, column 0: EOF while parsing a list",
    ),
    ("empty-file", "", "invalid JSON"),
    (
        "root-is-array",
        "",
        "expected an object, found an array of 2 items",
    ),
    ("missing-version", "version", "missing"),
    (
        "wrong-version",
        "version",
        "unsupported version the number 2",
    ),
    ("missing-curves", "curves", "missing"),
    (
        "curves-not-array",
        "curves",
        "expected an array, found an object",
    ),
    (
        "unknown-root-field",
        "colour",
        "unknown field (expected one of: version, name",
    ),
    (
        "curve-not-object",
        "curves[0]",
        "expected a curve object, found the number 5",
    ),
    ("curve-missing-type", "curves[0].type", "missing"),
    (
        "unknown-curve-type",
        "curves[0].type",
        "unknown curve type \"hermite\"",
    ),
    (
        "too-few-points",
        "curves[1].points",
        "needs at least 2 points, found 1",
    ),
    (
        "points-not-array",
        "curves[0].points",
        "expected an array, found the number 5",
    ),
    (
        "point-wrong-arity",
        "curves[0].points[1]",
        "a point has 2 or 3 coordinates, found 4",
    ),
    (
        "coordinate-is-string",
        "curves[0].points[0][0]",
        "expected a number, found the string \"1\"",
    ),
    (
        "nan-literal",
        "curves[1].points[2][1]",
        "not a finite number (NaN)",
    ),
    (
        "infinity-literal",
        "curves[0].points[1][0]",
        "not a finite number (-Infinity)",
    ),
    (
        "number-overflows",
        "curves[0].points[0][1]",
        "not a finite number (1e+400)",
    ),
    (
        "bad-hex-colour",
        "curves[0].style.color",
        "\"#12345\" is not a colour",
    ),
    (
        "colour-channel-out-of-range",
        "curves[0].style.color[0]",
        "colour channel 1.2 is outside [0, 1]",
    ),
    (
        "negative-width",
        "curves[0].style.width",
        "must be greater than 0, found -2",
    ),
    (
        "unknown-style-field",
        "curves[0].style.dashed",
        "unknown field",
    ),
    ("samples-too-few", "samples", "1 is not between 2 and 4096"),
    (
        "samples-not-integer",
        "samples",
        "expected an integer between 2 and 4096, found the number 64.5",
    ),
    ("view-unknown-kind", "view.kind", "unknown view kind \"4d\""),
    (
        "view-zero-height",
        "view.height",
        "must be greater than 0, found 0",
    ),
    (
        "unknown-curve-field",
        "curves[0].weights",
        "unknown field (expected one of: type, name, style, points)",
    ),
    (
        "modified-t-star-zero",
        "curves[0].t_star",
        "t* = 0 is not inside the open interval (0, 1)",
    ),
    (
        "modified-t-star-one",
        "curves[0].t_star",
        "t* = 1 is not inside the open interval (0, 1)",
    ),
    (
        "modified-t-star-negative",
        "curves[0].t_star",
        "t* = -0.5 is not inside",
    ),
    ("modified-missing-v", "curves[0].v", "missing"),
    (
        "modified-v-nan",
        "curves[0].v[0]",
        "not a finite number (NaN)",
    ),
    (
        "interp-one-point",
        "curves[0].points",
        "needs at least 2 points, found 1",
    ),
    (
        "interp-params-repeated",
        "curves[0].params[2]",
        "parameters must increase strictly: 1 follows 1",
    ),
    (
        "interp-params-decreasing",
        "curves[0].params[2]",
        "parameters must increase strictly: 1 follows 2",
    ),
    (
        "interp-params-count",
        "curves[0].params",
        "3 parameters for 4 points",
    ),
    (
        "interp-params-infinite",
        "curves[0].params[3]",
        "not a finite number (Infinity)",
    ),
    (
        "interp-unknown-reading",
        "curves[0].modification.reading",
        "unknown reading \"sideways\"",
    ),
    (
        "interp-t-star-outside",
        "curves[0].modification.t_star",
        "t* = 1.5 is not inside the open interval (0, 1)",
    ),
    (
        "bspline-knots-decreasing",
        "curves[0].knots[5]",
        "knots must not decrease: 0.4 follows 0.5",
    ),
    (
        "bspline-interior-multiplicity",
        "curves[0].knots[5]",
        "knot 0.5 has multiplicity 3; at most 2 allowed inside the domain",
    ),
    (
        "bspline-end-multiplicity",
        "curves[0].knots[4]",
        "knot 0 has multiplicity 5; at most 4 allowed at the domain's ends",
    ),
    (
        "bspline-knot-count",
        "curves[0].knots",
        "9 knots for 7 control points of order 4: expected n + k = 11",
    ),
    ("bspline-order-one", "curves[0].order", "order 1 is below 2"),
    ("bspline-missing-order", "curves[0].order", "missing"),
    (
        "bspline-knot-nan",
        "curves[0].knots[4]",
        "not a finite number (NaN)",
    ),
    (
        "bspline-unknown-knot-kind",
        "curves[0].knots",
        "unknown knot vector \"uniformish\"",
    ),
    (
        "bspline-too-few-points",
        "curves[0].points",
        "needs at least 4 points, found 3",
    ),
    (
        "bspline-empty-domain",
        "curves[0].knots",
        "the domain [t_(k-1), t_n] = [1, 1] is empty",
    ),
    (
        "nubmp-negative-parameter",
        "curves[0].shape[0].values[0]",
        "shape parameter a^0_1 = -0.2 must be finite and ≥ 0",
    ),
    (
        "nubmp-group-sum",
        "curves[0].shape[0].values",
        "group 1 sums to 1.1, not 1 (tolerance 1e-9)",
    ),
    (
        "nubmp-not-in-group",
        "curves[0].shape[0].member",
        "control point 5 is not in group 1 (members: 0, 1)",
    ),
    (
        "nubmp-no-such-group",
        "curves[0].shape[0].group",
        "group 99 does not exist (groups 0..11)",
    ),
    (
        "nubmp-value-too-large",
        "curves[0].shape[0].value",
        "the absorbing a^1_1 would become negative",
    ),
    (
        "nubmp-same-absorber",
        "curves[0].shape[0].absorber",
        "the absorbing member must differ from the changed one",
    ),
    (
        "nubmp-values-count",
        "curves[0].shape[0].values",
        "group 1 has 2 parameters, found 3 values",
    ),
    (
        "nubmp-mixed-forms",
        "curves[0].shape[0].member",
        "give either \"values\"",
    ),
    (
        "nubmp-absorber-missing",
        "curves[0].shape[0].absorber",
        "missing",
    ),
    (
        "annotation-two-shapes",
        "annotations[0].points",
        "either a \"polyline\" or \"points\", not both",
    ),
    (
        "annotation-no-shape",
        "annotations[0]",
        "an annotation needs \"polyline\" or \"points\"",
    ),
    (
        "rational-zero-weight",
        "curves[0].weights[1]",
        "weight 0 of point 1: a weight must be a finite number greater than 0",
    ),
    (
        "rational-negative-weight",
        "curves[0].weights[1]",
        "weight -0.5 of point 1",
    ),
    (
        "rational-weight-count",
        "curves[0].weights",
        "2 weights for 3 control points",
    ),
    ("rational-missing-weights", "curves[0].weights", "missing"),
    (
        "rational-weight-string",
        "curves[0].weights[1]",
        "expected a number, found the string \"heavy\"",
    ),
    (
        "nurbs-weight-overflow",
        "curves[0].weights[3]",
        "not a finite number",
    ),
    (
        "nurbs-knots-decreasing",
        "curves[0].knots[4]",
        "knots must not decrease: 0.4 follows 0.5",
    ),
    (
        "nurbs-weight-count",
        "curves[0].weights",
        "3 weights for 4 control points",
    ),
];

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/bad_scenes")
}

#[test]
fn every_file_of_the_corpus_is_listed() {
    let mut files: Vec<String> = std::fs::read_dir(corpus())
        .expect("corpus dir")
        .map(|e| {
            e.expect("entry")
                .path()
                .file_stem()
                .expect("stem")
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    files.sort();
    let mut listed: Vec<String> = EXPECTED.iter().map(|e| e.0.to_owned()).collect();
    listed.sort();
    assert_eq!(files, listed);
    assert!(EXPECTED.len() >= 15 + 20);
}

#[test]
fn each_bad_scene_gives_its_typed_error() {
    for (file, path, fragment) in EXPECTED {
        let err = Scene::load(&corpus().join(format!("{file}.json")))
            .expect_err(&format!("{file} must be rejected"));
        assert_eq!(err.path, *path, "{file}: {err}");
        let text = err.to_string();
        assert!(
            text.contains(fragment),
            "{file}: {text:?} lacks {fragment:?}"
        );
        assert!(
            !matches!(err.kind, SceneErrorKind::Io(_)),
            "{file}: must be a content error, got {err}"
        );
    }
}

#[test]
fn the_cli_reports_each_bad_scene_and_exits_1_without_panicking() {
    for (file, path, fragment) in EXPECTED {
        let scene = corpus().join(format!("{file}.json"));
        let out = Command::new(env!("CARGO_BIN_EXE_splinescope"))
            .arg("check")
            .arg(&scene)
            .output()
            .expect("run splinescope");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{file}: {stderr}");
        assert!(stderr.contains(&format!("{path}: ")), "{file}: {stderr}");
        assert!(!stderr.contains("(root)"), "{file}: {stderr}");
        assert!(stderr.contains(fragment), "{file}: {stderr}");
        assert!(!stderr.contains("panicked"), "{file}: {stderr}");
    }
}
