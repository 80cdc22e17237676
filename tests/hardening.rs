//! Every input path fails cleanly or works correctly on the extreme inputs found by
//! mutation: no panic, no non-finite number printed with exit 0, a failing command writes
//! nothing, and special output paths are handled by the documented policy.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{bin, run, text};

fn dir(name: &str) -> PathBuf {
    let d = common::out_dir("hardening").join(name);
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(dir: &Path, name: &str, body: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, body).unwrap();
    p.to_string_lossy().into_owned()
}

/// Fails (exit 1, not a panic's 101) with every `says` in the message.
fn fails_saying(args: &[&str], says: &[&str]) {
    let out = run(args);
    let all = text(&out);
    assert_eq!(out.status.code(), Some(1), "{args:?}: {all}");
    for s in says {
        assert!(all.contains(s), "{args:?} should say {s:?}: {all}");
    }
    assert!(!all.contains("panicked"), "{all}");
}

/// Runs with one environment variable set and checks the output says `says`.
fn assert_says_with_env(args: &[&str], (var, value): (&str, &str), says: &str) {
    let out = bin().args(args).env(var, value).output().expect("run");
    assert!(
        text(&out).contains(says),
        "{var}={value} {args:?}: {}",
        text(&out)
    );
}

fn demo() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/solve_demo.json")
        .to_string_lossy()
        .into_owned()
}

#[test]
fn subnormal_knots_are_refused_with_the_field_named_not_a_panic() {
    let d = dir("subnormal");
    let knots = r#""knots": [0, 0, 0, 5e-324, 1, 1, 1], "order": 3"#;
    let pts = r#""points": [[0, 0], [1, 2], [2, 0], [3, 1]]"#;
    let nub = write(
        &d,
        "nub.json",
        &format!(r#"{{"version": 1, "curves": [{{"type": "nubmp", {pts}, {knots}}}]}}"#),
    );
    let bs = write(
        &d,
        "bs.json",
        &format!(r#"{{"version": 1, "curves": [{{"type": "bspline", {pts}, {knots}}}]}}"#),
    );
    let png = d.join("x.png").to_string_lossy().into_owned();
    for args in [
        vec!["check", &nub],
        vec!["eval", &nub, "--samples", "3"],
        vec!["inspect", &nub],
        vec!["render", &nub, "-o", &png],
    ] {
        fails_saying(
            &args,
            &[
                "curves[0].knots",
                "degree-elevation coefficient",
                "not a finite number",
            ],
        );
    }
    assert!(!Path::new(&png).exists());
    // The B-spline itself is fine (de Boor and extraction stay finite); its standard
    // NUBMP structure, which inspect reports, is not.
    assert!(run(&["eval", &bs, "--samples", "3"]).status.success());
    fails_saying(
        &["inspect", &bs],
        &["curves[0]", "degree-elevation coefficient"],
    );
    fails_saying(
        &["inspect", &bs, "--tau", "0.5"],
        &["curves[0]", "not a finite number"],
    );
}

#[test]
fn derived_values_that_overflow_fail_the_command_naming_the_input() {
    let d = dir("derived");
    let interp = write(
        &d,
        "interp.json",
        r#"{"version": 1, "curves": [{"type": "interpolation", "points": [[0, 0], [1, 2], [2, 0]], "params": [0, 5e-324, 1]}]}"#,
    );
    for args in [
        vec!["eval", &interp, "--samples", "3"],
        vec!["check", &interp],
        vec!["inspect", &interp],
    ] {
        fails_saying(
            &args,
            &["curves[0]", "lowered Bézier segment", "not a finite number"],
        );
    }
    // A modified curve whose bump overflows: Q(t) + S(t) v with v near the f64 maximum
    // added to a control point near it.
    let modified = write(
        &d,
        "modified.json",
        r#"{"version": 1, "curves": [{"type": "modified_bezier", "points": [[0, 0], [1.7e308, 0], [2, 0]], "t_star": 0.5, "v": [1.7e308, 0]}]}"#,
    );
    fails_saying(&["eval", &modified, "--samples", "5"], &["curves[0]"]);
}

#[test]
fn solves_that_overflow_are_refused_and_write_nothing() {
    let d = dir("solve");
    let out = d.join("out.json");
    let report = d.join("report.json");
    for (name, request, says) in [
        (
            // The solver itself refuses moves that leave f64, naming the parameter.
            "tangent",
            r#"{"curve": 0, "method": "tangent_kept", "target": [2, 2.2], "t": 5e-324}"#,
            ["t: target 0", "at t = 5e-324 needs moves beyond f64"],
        ),
        (
            "project_plus",
            r#"{"curve": 0, "method": "project", "target": [1e308, -1e308]}"#,
            ["request: the solve produced", "report.distance"],
        ),
        (
            "project_minus",
            r#"{"curve": 0, "method": "project", "target": [-1e308, 1e308]}"#,
            ["request: the solve produced", "report.distance"],
        ),
    ] {
        let req = write(&d, &format!("{name}.json"), request);
        fails_saying(
            &[
                "solve",
                &demo(),
                &req,
                "-o",
                &out.to_string_lossy(),
                "--report",
                &report.to_string_lossy(),
            ],
            &says,
        );
        assert!(!out.exists() && !report.exists(), "{name}: nothing written");
    }
}

#[test]
fn a_failing_solve_writes_neither_output() {
    let d = dir("all_or_none");
    let existing = d.join("existing.json");
    std::fs::write(&existing, "old").unwrap();
    let req = write(
        &d,
        "req.json",
        r#"{"curve": 0, "method": "single_target", "target": [2, 2.5]}"#,
    );
    let missing = d.join("missing_dir/r.json");
    fails_saying(
        &[
            "solve",
            &demo(),
            &req,
            "-o",
            &existing.to_string_lossy(),
            "--report",
            &missing.to_string_lossy(),
        ],
        &["nothing was written", "missing_dir/r.json"],
    );
    assert_eq!(std::fs::read_to_string(&existing).unwrap(), "old");
    let leftovers: Vec<_> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    // Both paths fine: both written.
    let report = d.join("r.json");
    let ok = run(&[
        "solve",
        &demo(),
        &req,
        "-o",
        &existing.to_string_lossy(),
        "--report",
        &report.to_string_lossy(),
    ]);
    assert!(ok.status.success(), "{}", text(&ok));
    assert_ne!(std::fs::read_to_string(&existing).unwrap(), "old");
    assert!(report.is_file());
}

#[cfg(unix)]
#[test]
fn special_output_paths_follow_the_documented_policy() {
    use std::os::unix::fs::{FileTypeExt, PermissionsExt};
    let d = dir("special");
    let req = write(
        &d,
        "req.json",
        r#"{"curve": 0, "method": "single_target", "target": [2, 2.5]}"#,
    );
    // A read-only file is refused, not replaced.
    let ro = d.join("ro.json");
    std::fs::write(&ro, "keep").unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o444)).unwrap();
    fails_saying(
        &["solve", &demo(), &req, "-o", &ro.to_string_lossy()],
        &["is read-only; not replaced"],
    );
    assert_eq!(std::fs::read_to_string(&ro).unwrap(), "keep");
    // A symbolic link is followed: its target is replaced, the link stays.
    let real = d.join("real.json");
    std::fs::write(&real, "old").unwrap();
    let link = d.join("link.json");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    let out = run(&["solve", &demo(), &req, "-o", &link.to_string_lossy()]);
    assert!(out.status.success(), "{}", text(&out));
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(
        std::fs::read_to_string(&real)
            .unwrap()
            .contains("\"curves\"")
    );
    // A FIFO is written through and stays a FIFO.
    let fifo = d.join("fifo");
    let made = Command::new("mkfifo").arg(&fifo).status().expect("mkfifo");
    assert!(made.success());
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read_to_string(fifo).unwrap())
    };
    let out = run(&["solve", &demo(), &req, "--report", &fifo.to_string_lossy()]);
    assert!(out.status.success(), "{}", text(&out));
    let got = reader.join().unwrap();
    assert!(got.contains("\"reports\""), "{got}");
    assert!(
        std::fs::symlink_metadata(&fifo)
            .unwrap()
            .file_type()
            .is_fifo()
    );
    // A directory is refused.
    fails_saying(
        &["solve", &demo(), &req, "--report", &d.to_string_lossy()],
        &["is a directory"],
    );
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o644)).unwrap();
}

#[test]
fn duplicate_keys_markers_and_extreme_numbers_in_messages() {
    let d = dir("small");
    // A duplicated key is refused at its path, whichever copy holds the bad value.
    for (name, body, command, says) in [
        (
            "dup.json",
            r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, NaN], [1, 1]], "points": [[0, 0], [1, 1]]}]}"#,
            "check",
            "curves[0].points: the key \"points\" appears more than once",
        ),
        (
            "dup_root.json",
            r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1, 1]]}], "version": 1}"#,
            "check",
            "version: the key \"version\"",
        ),
        (
            "dup_req.json",
            r#"{"curve": 0, "method": "project", "target": [1, 1], "target": [2, 2]}"#,
            "solve",
            "target: the key \"target\" appears more than once",
        ),
        (
            "nan.json",
            r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1, -Infinity]]}]}"#,
            "check",
            "curves[0].points[1][1]: not a finite number (-Infinity)",
        ),
        (
            // Subnormals are printed in their shortest round-trip form, not 300 digits.
            "sub.json",
            r#"{"version": 1, "curves": [{"type": "interpolation", "points": [[0, 0], [1, 2], [2, 0]], "params": [0, 5e-324, 0]}]}"#,
            "check",
            "0 follows 5e-324",
        ),
    ] {
        let file = write(&d, name, body);
        let demo = demo();
        let args: Vec<&str> = if command == "solve" {
            vec!["solve", &demo, &file]
        } else {
            vec![command, &file]
        };
        fails_saying(&args, &[says]);
    }
    // A user string that looks like the old internal marker is just a string: refused
    // for its control character (names are text to display), never read as a NaN.
    let marker = write(
        &d,
        "marker.json",
        r#"{"version": 1, "curves": [{"type": "bezier", "name": "\u0001NaN", "points": [[0, 0], [1, 1]]}]}"#,
    );
    let out = run(&["check", &marker]);
    let all = text(&out);
    assert_eq!(out.status.code(), Some(1), "{all}");
    assert!(
        all.contains("curves[0].name: the character U+0001") && !all.contains("finite"),
        "{all}"
    );
    let bez = write(
        &d,
        "bez.json",
        r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1, 1]]}]}"#,
    );
    let out = run(&["eval", &bez, "--params", "2.5e-320,-5e-324"]);
    let all = text(&out);
    assert!(all.contains("--params[1] = -5e-324 is outside"), "{all}");
    assert!(all.len() < 400, "no 300-digit numbers: {all}");
}

/// Each documented limit is checked before allocating, names the value, the limit and the
/// variable that raises it; raising the variable lets the input through.
#[test]
fn limits_are_named_with_the_variable_that_raises_them() {
    let d = dir("limits");
    let pts = |n: usize| {
        (0..n)
            .map(|i| format!("[{i}, {}]", i % 3))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let degree = write(
        &d,
        "degree.json",
        &format!(
            r#"{{"version": 1, "curves": [{{"type": "bezier", "points": [{}]}}]}}"#,
            pts(1002)
        ),
    );
    fails_saying(
        &["eval", &degree, "--params", "0.5"],
        &[
            "curves[0].points: 1001 is over the limit of 1000 for the degree of a Bézier curve",
            "SPLINESCOPE_MAX_DEGREE=N",
        ],
    );
    let raised = bin()
        .args(["eval", &degree, "--params", "0.5"])
        .env("SPLINESCOPE_MAX_DEGREE", "2000")
        .output()
        .unwrap();
    assert!(raised.status.success(), "{}", text(&raised));
    let order = write(
        &d,
        "order.json",
        &format!(
            r#"{{"version": 1, "curves": [{{"type": "bspline", "points": [{}], "knots": "clamped_uniform", "order": 65}}]}}"#,
            pts(70)
        ),
    );
    fails_saying(
        &["check", &order],
        &[
            "curves[0].order: 65 is over the limit of 64",
            "SPLINESCOPE_MAX_ORDER",
        ],
    );
    assert_says_with_env(
        &["check", &order],
        ("SPLINESCOPE_MAX_POINTS", "50"),
        "curves[0].points: 70 is over the limit of 50 points per curve",
    );
    assert_says_with_env(
        &["check", &degree],
        ("SPLINESCOPE_MAX_CURVES", "0"),
        "curves: 1 is over the limit of 0 curves per scene",
    );
    assert_says_with_env(
        &["check", &degree],
        ("SPLINESCOPE_MAX_FILE_BYTES", "100"),
        "is over the limit of 100 bytes per scene or request file",
    );
    let gallery = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/gallery.json")
        .to_string_lossy()
        .into_owned();
    fails_saying(
        &["eval", &gallery, "--samples", "10000000"],
        &[
            "250000000 is over the limit of 134217728 samples per command",
            "SPLINESCOPE_MAX_SAMPLES",
        ],
    );
    fails_saying(
        &["bench", "--curves", "10000000", "--samples", "64"],
        &["640000000 is over the limit of 134217728 samples per command"],
    );
    if common::gpus("limits (render half)").is_empty() {
        return;
    }
    let render = bin()
        .args(["render", &gallery, "-o", &d.join("x.png").to_string_lossy()])
        .env("SPLINESCOPE_MAX_SAMPLES", "100")
        .output()
        .unwrap();
    assert_eq!(render.status.code(), Some(1), "{}", text(&render));
    assert!(
        text(&render).contains("is over the limit of 100 samples per command"),
        "{}",
        text(&render)
    );
    assert!(!d.join("x.png").exists());
}

/// Exits 2 (an argument refused by the parser) with every `says` in the message.
fn refused_saying(args: &[&str], says: &[&str]) {
    let out = run(args);
    let all = text(&out);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {all}");
    for s in says {
        assert!(all.contains(s), "{args:?} should say {s:?}: {all}");
    }
}

#[test]
fn option_values_are_parsed_strictly_and_named() {
    let d = dir("options");
    let scenes = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let scenes = scenes.to_string_lossy();
    let refs = d.join("refs").to_string_lossy().into_owned();
    for (bad, says) in [
        ("", "is empty"),
        (" ", "is empty"),
        ("channel=4,", "empty item"),
        ("channel=4,,flip=0.1", "empty item"),
        ("channel=4,channel=5", "gives channel twice"),
        ("pixels=1%%", "pixels=1%%"),
        ("flip=", "flip="),
    ] {
        refused_saying(
            &["regress", &scenes, &refs, "--tolerance", bad],
            &["--tolerance", says],
        );
        refused_saying(&["diff", "a.png", "b.png", "--tolerance", bad], &[says]);
    }
    assert!(!d.join("refs").exists(), "nothing was created");
    for bad in ["", "10%%", "%", "ten", "nan%", "-1"] {
        refused_saying(&["bench", &format!("--threshold={bad}")], &["--threshold"]);
    }
    // A --compare file whose rates are not numbers names the row, the field and the value.
    let rows = |rate: &str| {
        format!(
            r#"[{{"family": "bezier", "curves": 10, "degree": 3, "samples_per_curve": 8, "cpu_f64_one_thread_samples_per_s": 5.0}},
               {{"family": "bezier", "curves": 20, "degree": 3, "samples_per_curve": 8, "cpu_f64_one_thread_samples_per_s": {rate}}}]"#
        )
    };
    for (name, rate, says) in [
        (
            "string",
            r#""1.5e8""#,
            r#"row 1: `cpu_f64_one_thread_samples_per_s` is "1.5e8""#,
        ),
        (
            "negative",
            "-3",
            "row 1: `cpu_f64_one_thread_samples_per_s` is -3",
        ),
        (
            "object",
            r#"{"v": 1}"#,
            "row 1: `cpu_f64_one_thread_samples_per_s` is {",
        ),
    ] {
        let file = write(&d, &format!("{name}.json"), &rows(rate));
        fails_saying(&["bench", "--compare", &file], &["--compare", says]);
    }
    let family = write(
        &d,
        "family.json",
        r#"{"family": 3, "curves": 10, "degree": 3, "samples_per_curve": 8}"#,
    );
    fails_saying(&["bench", "--compare", &family], &["`family` is 3"]);
}

#[cfg(unix)]
#[test]
fn schema_write_is_all_or_none() {
    use std::os::unix::fs::PermissionsExt;
    let names = [
        "scene", "request", "report", "inspect", "analyze", "eval", "check",
    ];
    let listing = |d: &Path| {
        let mut n: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        n.sort();
        n
    };
    // Each kind of bad target, alone: the run fails naming it and writes no other file.
    for bad in ["read-only", "directory", "dangling-link"] {
        let d = dir(&format!("schema-{bad}"));
        let target = d.join("report.schema.json");
        match bad {
            "read-only" => {
                std::fs::write(&target, "keep").unwrap();
                std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o444)).unwrap();
            }
            "directory" => std::fs::create_dir(&target).unwrap(),
            _ => std::os::unix::fs::symlink(d.join("nowhere"), &target).unwrap(),
        }
        let before = listing(&d);
        fails_saying(
            &["schema", "--write", &d.to_string_lossy()],
            &["nothing was written", "report.schema.json"],
        );
        assert_eq!(listing(&d), before, "{bad}: no file added or left behind");
        if bad == "read-only" {
            assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
            std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o644)).unwrap();
        }
    }
    // A good directory (made for the purpose): every schema written.
    let d = dir("schema-good").join("new");
    let out = run(&["schema", "--write", &d.to_string_lossy()]);
    assert!(out.status.success(), "{}", text(&out));
    let want: Vec<String> = {
        let mut w: Vec<String> = names.iter().map(|n| format!("{n}.schema.json")).collect();
        w.sort();
        w
    };
    for w in &want {
        assert!(listing(&d).contains(w), "{w} written: {:?}", listing(&d));
    }
}

#[test]
fn schema_without_a_name_lists_every_schema() {
    // The synopsis shows NAME as optional: without it, the list (exit 0), each named once
    // with what it describes; a name not in it is still an error naming the choices.
    let out = run(&["schema"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    for (name, _) in splinescope::schemas::all() {
        let line = text
            .lines()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("{name} listed: {text}"));
        assert!(line.len() > name.len() + 10, "{name} described: {line:?}");
    }
    let out = run(&["schema", "scenery"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("\"scenery\""));
}

/// The numbers of a JSON document that are `null` inside an array (where a number was
/// due), with their paths.
fn nulls_in_arrays(v: &serde_json::Value, at: &str, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                if x.is_null() {
                    out.push(format!("{at}[{i}]"));
                }
                nulls_in_arrays(x, &format!("{at}[{i}]"), out);
            }
        }
        serde_json::Value::Object(m) => {
            for (k, x) in m {
                nulls_in_arrays(x, &format!("{at}.{k}"), out);
            }
        }
        _ => {}
    }
}

#[test]
fn inspect_falls_back_to_exact_coefficients_beyond_f64() {
    let d = dir("inspect-huge");
    let scene = write(
        &d,
        "huge.json",
        r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1e308, 0], [0, 1], [-1e308, 0]]}]}"#,
    );
    let out = run(&["inspect", &scene]);
    assert!(out.status.success(), "{}", text(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let mut nulls = Vec::new();
    nulls_in_arrays(&v, "", &mut nulls);
    assert!(nulls.is_empty(), "null where numbers were due: {nulls:?}");
    let pb = &v["curves"][0]["power_basis"];
    assert!(pb.get("values").is_none(), "{pb}");
    assert!(
        pb["values_unavailable"]
            .as_str()
            .unwrap()
            .contains("a_1.x is beyond the range of f64"),
        "{pb}"
    );
    // a_1 = 3 (P1 − P0) = 3e308 and a_2 = 3 (P0 − 2 P1 + P2) = −6e308, exactly.
    let big = |lead: &str| format!("{lead}{}", "0".repeat(308));
    assert_eq!(pb["exact"][1][0].as_str().unwrap(), big("3"));
    assert_eq!(pb["exact"][2][0].as_str().unwrap(), big("-6"));
    assert_eq!(pb["exact"][2][1].as_str().unwrap(), "3");
}

/// A quadratic 10⁻¹¹¹ across: `P′(0) = (2, 0)·10⁻¹¹¹` and `κ(0) = 5·10¹¹⁰` (the unit
/// curve's 1/2, divided by the scale); `|P′|³` underflows `f64`.
fn tiny_quadratic(d: &Path) -> String {
    write(
        d,
        "tiny.json",
        r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1e-111, 0], [1e-111, 1e-111]]}]}"#,
    )
}

fn eval_values(out: &std::process::Output, key: &str) -> Vec<serde_json::Value> {
    assert!(out.status.success(), "{}", text(out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    v["curves"][0][key].as_array().unwrap().clone()
}

#[test]
fn curvature_is_null_only_where_the_tangent_vanishes() {
    let d = dir("curvature");
    let tiny = tiny_quadratic(&d);
    let out = run(&["eval", &tiny, "--params", "0,0.5,1", "--derivatives", "2"]);
    let ks = eval_values(&out, "curvature");
    // κ(t) of the unit quadratic (0,0), (1,0), (1,1): P′ = 2((1−t), t), P″ = 2(−1, 1),
    // κ = |P′ × P″| / |P′|³ = 8 / (8 ((1−t)² + t²)^{3/2}); times 10¹¹¹.
    for (t, k) in [0.0_f64, 0.5, 1.0].iter().zip(&ks) {
        let unit = 1.0 / ((1.0 - t).powi(2) + t * t).powf(1.5);
        let want = unit * 0.5 * 1e111;
        let got = k.as_f64().unwrap_or_else(|| panic!("t = {t}: κ is {k}"));
        assert!(
            (got / want - 1.0).abs() < 1e-12,
            "t = {t}: {got:e} vs {want:e}"
        );
    }
    // A point where P′ really is zero: a quadratic whose middle point doubles back.
    let cusp = write(
        &d,
        "cusp.json",
        r#"{"version": 1, "curves": [{"type": "bezier", "points": [[0, 0], [1, 0], [0, 0]]}]}"#,
    );
    let out = run(&["eval", &cusp, "--params", "0.25,0.5", "--derivatives", "2"]);
    let ks = eval_values(&out, "curvature");
    assert_eq!(ks[0].as_f64(), Some(0.0), "a straight piece: κ = 0");
    assert!(ks[1].is_null(), "P′(1/2) = 0: κ is null, got {}", ks[1]);
}

#[test]
fn gpu_eval_of_coordinates_below_f32_is_rescaled_not_flushed() {
    let d = dir("gpu-tiny");
    let tiny = tiny_quadratic(&d);
    common::on_each_gpu("gpu eval of tiny coordinates", |backend| {
        let out = run(&[
            "eval",
            &tiny,
            "--params",
            "0,0.5,1",
            "--derivatives",
            "2",
            "--backend",
            "gpu",
            "--gpu-backend",
            &backend.name,
        ]);
        let samples = eval_values(&out, "samples");
        let d1 = eval_values(&out, "d1");
        let ks = eval_values(&out, "curvature");
        // P(1/2) = (0.75, 0.25)·10⁻¹¹¹, P′(0) = (2, 0)·10⁻¹¹¹, P′(1) = (0, 2)·10⁻¹¹¹:
        // within the documented f32 bound, 1e-6 of the curve's size.
        let near = |got: &serde_json::Value, want: [f64; 2]| {
            for (g, w) in got.as_array().unwrap().iter().zip(want) {
                let g = g.as_f64().unwrap();
                assert!((g - w).abs() <= 2e-6 * 1e-111, "{g:e} vs {w:e}");
            }
        };
        near(&samples[1], [0.75e-111, 0.25e-111]);
        near(&d1[0], [2e-111, 0.0]);
        near(&d1[2], [0.0, 2e-111]);
        let k0 = ks[0].as_f64().unwrap();
        assert!((k0 / 5e110 - 1.0).abs() < 1e-5, "κ(0) = {k0:e}");
        // Printed at f32 precision: at most 9 significant digits.
        let printed = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(printed.contains("e-111"), "{printed}");
    });
}

#[test]
fn a_solve_writes_only_scenes_that_check_passes() {
    let d = dir("solve-check");
    let out = d.join("out.json");
    for (name, request) in [
        (
            "project",
            r#"{"curve": 0, "method": "project", "target": [1e300, 0]}"#,
        ),
        (
            "single",
            r#"{"curve": 0, "method": "single_target", "target": [2, 1e308]}"#,
        ),
        (
            "single-huge",
            r#"{"curve": 0, "method": "single_target", "target": [1e39, 0], "t": 0.5}"#,
        ),
        (
            "project-huge",
            r#"{"curve": 0, "method": "project", "target": [1e39, 0]}"#,
        ),
        (
            "single-fine",
            r#"{"curve": 0, "method": "single_target", "target": [2, 2.5]}"#,
        ),
    ] {
        let _ = std::fs::remove_file(&out);
        let req = write(&d, &format!("{name}.json"), request);
        let solved = run(&["solve", &demo(), &req, "-o", &out.to_string_lossy()]);
        match solved.status.code() {
            Some(0) => {
                let check = run(&["check", &out.to_string_lossy()]);
                assert!(
                    check.status.success(),
                    "{name}: the solve wrote a scene that check refuses: {}",
                    text(&check)
                );
            }
            Some(1) => {
                assert!(!out.exists(), "{name}: a failed solve wrote its scene");
                assert!(!text(&solved).contains("panicked"), "{}", text(&solved));
            }
            other => panic!("{name}: exit {other:?}: {}", text(&solved)),
        }
        if name == "single-fine" {
            assert!(
                out.exists(),
                "an ordinary solve still writes: {}",
                text(&solved)
            );
        }
        if name.ends_with("-huge") {
            assert!(
                text(&solved).contains("would not pass `check`"),
                "{}",
                text(&solved)
            );
        }
    }
}

/// The findings of the analysis fuzzer at the command line: a `--compare` file with a key
/// given twice is refused as every other file is; a command whose stderr is closed or full
/// exits with its own code, not a panic's; copies of one curve are one group in
/// `analyze --intersections`, found at once however many there are.
#[test]
fn compare_files_stderr_and_copies() {
    let d = dir("findings");
    let dup = write(
        &d,
        "dup.json",
        r#"[{"family":"bezier","family":"nurbs","curves":1,"degree":3,"samples_per_curve":8}]"#,
    );
    fails_saying(
        &["bench", "--compare", &dup, "--curves", "2"],
        &["family", "more than once"],
    );
    // stderr closed (2>&-) and full (/dev/full): the exit code of the failure, 1.
    let exe = env!("CARGO_BIN_EXE_splinescope");
    for redirect in ["2>&-", "2>/dev/full"] {
        let status = Command::new("sh")
            .arg("-c")
            .arg(format!(
                "'{exe}' analyze /nonexistent/scene.json {redirect}"
            ))
            .status()
            .expect("sh runs");
        assert_eq!(status.code(), Some(1), "stderr {redirect}: {status:?}");
    }
    // 300 copies of a cubic and a line crossing them: one group, 300 pairs.
    let cubic = r#"{"type": "bezier", "points": [[0, 0], [1, 2], [3, -1], [4, 1]]}"#;
    let line = r#"{"type": "bezier", "points": [[-1, 0.5], [5, 0.5]]}"#;
    let mut curves = vec![cubic; 300];
    curves.push(line);
    let scene = write(
        &d,
        "copies.json",
        &format!(r#"{{"version": 1, "curves": [{}]}}"#, curves.join(", ")),
    );
    let out = run(&["analyze", &scene, "--intersections", "--json"]);
    assert!(out.status.success(), "{}", text(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let groups = v["copies"].as_array().expect("copies");
    assert_eq!(groups.len(), 1, "{groups:?}");
    assert_eq!(groups[0]["curves"].as_array().expect("curves").len(), 300);
    let pairs = v["intersections"].as_array().expect("pairs");
    assert_eq!(pairs.len(), 300);
    assert!(
        pairs.iter().all(|p| p["curves"][1] == 300),
        "{:?}",
        pairs[0]
    );
    let out = run(&["analyze", &scene, "--intersections"]);
    assert!(
        text(&out).contains("300 group") || text(&out).contains("copies (1 group"),
        "{}",
        text(&out)
    );
}
