//! Shared helpers of the integration tests.
#![allow(dead_code, missing_docs)]

use std::sync::OnceLock;

use splinescope::gpu::{BackendChoice, ContextOptions, GpuContext, GpuError};

/// The environment variable that lets GPU tests skip (and say so) when no adapter exists.
pub const SKIP_VAR: &str = "SPLINESCOPE_SKIP_GPU_TESTS";

/// The environment variable that lists the backends GPU tests run on
/// (`vulkan,gl`); by default every backend that has an adapter.
pub const BACKENDS_VAR: &str = "SPLINESCOPE_TEST_BACKENDS";

/// One backend's device, shared by the tests of a test binary.
pub struct Backend {
    /// `vulkan`, `gl`, `metal` or `dx12`: what `--gpu-backend` takes.
    pub name: String,
    /// Its context.
    pub ctx: GpuContext,
}

const ALL: [BackendChoice; 4] = [
    BackendChoice::Vulkan,
    BackendChoice::Gl,
    BackendChoice::Metal,
    BackendChoice::Dx12,
];

fn open_all() -> Result<Vec<Backend>, String> {
    let listed = std::env::var(BACKENDS_VAR)
        .ok()
        .filter(|v| !v.trim().is_empty());
    let (choices, explicit) = match &listed {
        Some(list) => (
            list.split(',')
                .map(|s| {
                    s.trim()
                        .parse::<BackendChoice>()
                        .map_err(|e| format!("{BACKENDS_VAR}: {e}"))
                })
                .collect::<Result<Vec<_>, _>>()?,
            true,
        ),
        None => (ALL.to_vec(), false),
    };
    let mut found = Vec::new();
    let mut missing = Vec::new();
    for choice in choices {
        match GpuContext::new(&ContextOptions::from_env(choice)) {
            Ok(ctx) => found.push(Backend {
                name: choice.to_string(),
                ctx,
            }),
            // Without a list, a backend with no adapter at all is simply not present; one
            // whose adapter was refused (a kernel computing wrong samples) is a failure.
            Err(GpuError::NoAdapter { .. }) if !explicit => {}
            Err(e) => missing.push(format!("{choice}: {e}")),
        }
    }
    if !missing.is_empty() {
        return Err(format!(
            "GPU backend(s) without a usable adapter: {}",
            missing.join("; ")
        ));
    }
    if found.is_empty() {
        return Err("no GPU adapter on any backend".into());
    }
    Ok(found)
}

/// Every backend the GPU tests run on, each with its context. Without an adapter this
/// fails the test with installation instructions, unless `SPLINESCOPE_SKIP_GPU_TESTS=1`
/// asks to skip: then it prints that the test was skipped and returns an empty list.
pub fn gpus(test: &str) -> Vec<&'static Backend> {
    static BACKENDS: OnceLock<Result<Vec<Backend>, String>> = OnceLock::new();
    match BACKENDS.get_or_init(open_all) {
        Ok(all) => all.iter().collect(),
        Err(e) if std::env::var(SKIP_VAR).is_ok_and(|v| v == "1") => {
            eprintln!("SKIPPED {test}: {e}; {SKIP_VAR}=1 asked to skip");
            Vec::new()
        }
        Err(e) => panic!(
            "{test} needs a GPU adapter: {e}\n\
             Install the software ones (Debian/Ubuntu: sudo apt-get install mesa-vulkan-drivers \
             libvulkan1 libegl1 libgl1-mesa-dri), choose backends with {BACKENDS_VAR}=vulkan,gl, \
             or set {SKIP_VAR}=1 to skip GPU tests explicitly."
        ),
    }
}

/// Runs `body` once per backend, saying which backend each run is on (the test's output
/// names the backend of a failure).
pub fn on_each_gpu(test: &str, mut body: impl FnMut(&'static Backend)) {
    for backend in gpus(test) {
        eprintln!(
            "{test}: on backend {} ({})",
            backend.name,
            backend.ctx.describe()
        );
        body(backend);
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

/// The splinescope binary under test.
pub fn bin() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_splinescope"))
}

/// Runs the binary with `args`.
pub fn run(args: &[&str]) -> std::process::Output {
    bin().args(args).output().expect("run splinescope")
}

/// Exit code, stdout and stderr of a run, for assertion messages.
pub fn text(out: &std::process::Output) -> String {
    format!(
        "exit {:?}\nstdout:\n{}\nstderr:\n{}",
        out.status.code(),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}
