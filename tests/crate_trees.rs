//! What each crate pulls in, read from `cargo tree` (the lock file, no build): core without
//! its `serde` feature has no serde; the I/O policy crate only thiserror; comparing images
//! needs no GPU; the GPU layer is handed an encoding and compiles without the JSON format. A dependency added to the wrong crate fails here, naming it.

use std::process::Command;

/// The normal (non-dev, non-build) dependencies of `package` with `args`, one crate name
/// per line, as `cargo tree` resolves them offline from the lock file.
fn tree(package: &str, args: &[&str]) -> Vec<String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args([
            "tree",
            "--offline",
            "--locked",
            "-e",
            "normal",
            "--prefix",
            "none",
        ])
        .args(["--format", "{p}", "-p", package])
        .args(args)
        .output()
        .expect("run cargo tree");
    assert!(
        out.status.success(),
        "cargo tree -p {package} {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .filter_map(|l| l.split_whitespace().next().map(str::to_owned))
        .collect()
}

fn assert_none(package: &str, args: &[&str], forbidden: &[&str]) {
    let names = tree(package, args);
    assert!(
        names.len() > 1 || package == "splinescope-io",
        "{package}: {names:?}"
    );
    for f in forbidden {
        assert!(
            !names
                .iter()
                .any(|n| n == f || n.starts_with(&format!("{f}-"))),
            "{package} {args:?} depends on {f}: {names:?}"
        );
    }
}

#[test]
fn core_without_its_serde_feature_has_no_serde() {
    assert_none(
        "splinescope-core",
        &["--no-default-features"],
        &["serde", "schemars", "serde_json", "wgpu", "png"],
    );
    // With it (the default), serde is there: the check above can see it.
    assert!(tree("splinescope-core", &[]).iter().any(|n| n == "serde"));
}

#[test]
fn image_comparison_needs_no_gpu() {
    assert_none(
        "splinescope-image",
        &[],
        &[
            "wgpu",
            "naga",
            "serde_json",
            "splinescope-scene",
            "splinescope-gpu",
        ],
    );
    assert!(
        tree("splinescope-image", &[])
            .iter()
            .any(|n| n == "nv-flip")
    );
}

#[test]
fn the_gpu_layer_is_handed_an_encoding_not_the_scene_format() {
    assert_none(
        "splinescope-gpu",
        &[],
        &["serde_json", "schemars", "splinescope-scene"],
    );
    assert_none(
        "splinescope-encoding",
        &[],
        &["serde", "serde_json", "wgpu", "splinescope-scene"],
    );
    assert!(
        tree("splinescope-gpu", &[])
            .iter()
            .any(|n| n == "splinescope-encoding")
    );
}

#[test]
fn words_for_a_person_sit_above_the_math() {
    // The presentation layer uses core; core, the encoding and the GPU layer never reach
    // it (a curve's labels, controls and reports are not math, nor what the GPU draws).
    assert!(
        tree("splinescope-present", &[])
            .iter()
            .any(|n| n == "splinescope-core")
    );
    for below in [
        "splinescope-core",
        "splinescope-encoding",
        "splinescope-gpu",
    ] {
        assert_none(below, &[], &["splinescope-present"]);
    }
    assert_none(
        "splinescope-present",
        &[],
        &["wgpu", "splinescope-scene", "png", "winit"],
    );
}

#[test]
fn the_io_policy_uses_only_thiserror() {
    let names = tree("splinescope-io", &[]);
    let others: Vec<&String> = names
        .iter()
        .filter(|n| {
            ![
                "splinescope-io",
                "thiserror",
                "thiserror-impl",
                "proc-macro2",
                "quote",
                "syn",
                "unicode-ident",
            ]
            .contains(&n.as_str())
        })
        .collect();
    assert!(others.is_empty(), "splinescope-io depends on {others:?}");
}

#[test]
fn the_python_module_has_the_viewers_model_but_no_window() {
    // The notebook widget drives the viewer's window-free model; the window (winit, egui)
    // is the viewer's `window` feature, which the Python module leaves off.
    assert!(
        tree("splinescope-python", &[])
            .iter()
            .any(|n| n == "splinescope-viewer")
    );
    assert_none(
        "splinescope-python",
        &[],
        &["winit", "egui", "egui-winit", "egui-wgpu", "clap"],
    );
    // The viewer alone, without its default feature, has no window either.
    assert_none(
        "splinescope-viewer",
        &["--no-default-features"],
        &["winit", "egui"],
    );
}
