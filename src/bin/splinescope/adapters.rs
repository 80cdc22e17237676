//! `splinescope adapters`: every GPU adapter found, its limits and self-test, and which one each command uses.

use std::io::Write;

use anyhow::{Result, bail};

use splinescope_gpu::ContextOptions;

use crate::{GpuArgs, say};

/// The arguments of `splinescope adapters`.
#[derive(Debug, clap::Args)]
pub struct AdaptersArgs {
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub gpu: GpuArgs,
}

/// Runs `splinescope adapters`.
///
/// # Errors
/// No adapter, or none that passes the kernel self-test.
pub fn run(a: &AdaptersArgs) -> Result<()> {
    adapters(a.json, &a.gpu)
}

/// What `adapters --json` prints.
#[derive(serde::Serialize)]
struct AdaptersOutput<'a, A: serde::Serialize> {
    backends: String,
    adapter_name_filter: Option<String>,
    adapters: &'a [A],
}

fn adapters(json: bool, gpu: &GpuArgs) -> Result<()> {
    let opts = ContextOptions::from_env(gpu.gpu_backend);
    let found = splinescope_gpu::context::survey(&opts);
    let chosen = found.iter().find(|a| a.chosen);
    if json {
        say!(
            "{}",
            serde_json::to_string_pretty(&AdaptersOutput {
                backends: splinescope_gpu::context::backend_names(opts.backend.backends()),
                adapter_name_filter: opts.adapter_name.clone(),
                adapters: &found,
            })?
        );
    } else {
        say!(
            "adapters for backends {}{} (most preferred first; * = chosen):",
            splinescope_gpu::context::backend_names(opts.backend.backends()),
            opts.adapter_name
                .as_ref()
                .map(|n| format!(", name containing {n:?}"))
                .unwrap_or_default()
        );
        for a in &found {
            let mib = |b: u64| b as f64 / (1024.0 * 1024.0);
            say!(
                "{} {} ({}, {}){}",
                if a.chosen { "*" } else { " " },
                a.name,
                a.backend,
                a.device_type,
                if a.driver.is_empty() {
                    String::new()
                } else {
                    format!(", driver {}", a.driver)
                }
            );
            say!(
                "    max storage binding {:.0} MiB, max buffer {:.0} MiB, {} workgroups per dimension, timestamps {}",
                mib(a.max_storage_binding_bytes),
                mib(a.max_buffer_bytes),
                a.max_workgroups_per_dimension,
                if a.timestamps { "yes" } else { "no" }
            );
            say!("    kernel self-test: {}", a.self_test);
        }
        match chosen {
            Some(a) => say!(
                "render, eval --backend gpu, bench and the headless gallery use: {} ({})\nview uses the first adapter in this list that passes and can present to its window",
                a.name,
                a.backend
            ),
            None => say!("no usable adapter"),
        }
    }
    if found.is_empty() {
        bail!(
            "no GPU adapter found; {}",
            splinescope_gpu::context::INSTALL_HINT
        );
    }
    if chosen.is_none() {
        bail!("no adapter passed the kernel self-test (see above)");
    }
    Ok(())
}
