//! Shared helpers of the integration tests.
#![allow(dead_code, missing_docs)]

use std::sync::OnceLock;

use splinescope::gpu::{BackendChoice, ContextOptions, GpuContext};

/// The environment variable that lets GPU tests skip (and say so) when no adapter exists.
pub const SKIP_VAR: &str = "SPLINESCOPE_SKIP_GPU_TESTS";

/// The shared GPU context. Without an adapter this fails the test with installation
/// instructions, unless `SPLINESCOPE_SKIP_GPU_TESTS=1` asks to skip: then it prints that
/// the test was skipped and returns `None`.
pub fn gpu(test: &str) -> Option<&'static GpuContext> {
    static CTX: OnceLock<Result<GpuContext, String>> = OnceLock::new();
    let ctx = CTX.get_or_init(|| {
        GpuContext::new(&ContextOptions::from_env(BackendChoice::Auto)).map_err(|e| e.to_string())
    });
    match ctx {
        Ok(c) => Some(c),
        Err(e) if std::env::var(SKIP_VAR).is_ok_and(|v| v == "1") => {
            eprintln!("SKIPPED {test}: no GPU adapter ({e}); {SKIP_VAR}=1 asked to skip");
            None
        }
        Err(e) => panic!(
            "{test} needs a GPU adapter and none was found: {e}\n\
             Install the software one (Debian/Ubuntu: sudo apt-get install mesa-vulkan-drivers libvulkan1), \
             or set {SKIP_VAR}=1 to skip GPU tests explicitly."
        ),
    }
}

/// Where tests write their output files (under `target/`).
pub fn out_dir(sub: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("target")
        .join("test-output")
        .join(sub);
    std::fs::create_dir_all(&dir).expect("create test output dir");
    dir
}
