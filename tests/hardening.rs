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
            "tangent",
            r#"{"curve": 0, "method": "tangent_kept", "target": [2, 2.2], "t": 5e-324}"#,
            "report.mu",
        ),
        (
            "project_plus",
            r#"{"curve": 0, "method": "project", "target": [1e308, -1e308]}"#,
            "report.distance",
        ),
        (
            "project_minus",
            r#"{"curve": 0, "method": "project", "target": [-1e308, 1e308]}"#,
            "report.distance",
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
            &["request", says, "not a finite number"],
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
    // A user string that looks like the old internal marker is just a string.
    let marker = write(
        &d,
        "marker.json",
        r#"{"version": 1, "curves": [{"type": "bezier", "name": "\u0001NaN", "points": [[0, 0], [1, 1]]}]}"#,
    );
    let out = run(&["check", &marker]);
    assert!(out.status.success(), "{}", text(&out));
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
            "190000000 is over the limit of 134217728 samples per command",
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
