//! DXF and STEP from the command line: `check` and `analyze` say the file's length unit,
//! `export -o FILE.dxf` writes a file every command reads back with the same curves, and
//! `--ascii` is refused for anything but DXF.

mod common;

fn seed(name: &str) -> String {
    format!("{}/tests/import_seeds/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn check_and_analyze_say_a_step_files_unit() {
    let out = common::run(&["check", &seed("parts.step")]);
    assert!(out.status.success(), "{}", common::text(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("21 curve(s)") && stdout.contains("lengths in millimetre"),
        "{stdout}"
    );
    let out = common::run(&["analyze", &seed("parts.step"), "--json", "--curve", "0"]);
    assert!(out.status.success(), "{}", common::text(&out));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(v["unit"], "millimetre");
    // The box's first edge, 30 mm.
    let length = v["curves"][0]["length"].as_f64().expect("a length");
    assert!((length - 30.0).abs() <= 1e-12, "{length}");
}

#[test]
fn export_writes_dxf_that_reads_back_and_ascii_is_for_dxf_only() {
    let dir = common::out_dir("import_cli");
    let dxf = dir.join("gallery.dxf");
    let out = common::run(&["export", "-o", dxf.to_str().expect("utf-8")]);
    assert!(out.status.success(), "{}", common::text(&out));
    assert!(
        std::fs::read(&dxf)
            .expect("written")
            .starts_with(b"AutoCAD Binary DXF")
    );
    let back = splinescope_import::load(&dxf).expect("reads back").scene;
    let gallery = splinescope_scene::format::gallery::gallery();
    assert_eq!(back.curves.len(), gallery.curves.len());
    let out = common::run(&["check", dxf.to_str().expect("utf-8")]);
    assert!(out.status.success(), "{}", common::text(&out));
    let svg = dir.join("x.svg");
    let out = common::run(&["export", "--ascii", "-o", svg.to_str().expect("utf-8")]);
    assert_eq!(out.status.code(), Some(1), "{}", common::text(&out));
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("--ascii is for DXF output"),
        "{}",
        common::text(&out)
    );
    assert!(!svg.exists());
}
