//! `splinescope import`: a file of another format (SVG) written as a splinescope scene.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use crate::say;

/// The arguments of `splinescope import`.
#[derive(Debug, clap::Args)]
pub struct ImportArgs {
    /// The file to read: SVG (`.svg`), or a scene (`.json`).
    pub file: PathBuf,
    /// Where to write the scene (JSON); the file is replaced atomically.
    #[arg(short, long, value_name = "SCENE.json")]
    pub output: PathBuf,
}

/// Runs `splinescope import`.
///
/// # Errors
/// The file does not read (naming it and where), the output is the input, or it cannot
/// be written.
pub fn run(a: &ImportArgs) -> Result<()> {
    import(&a.file, &a.output)
}

fn import(file: &Path, output: &Path) -> Result<()> {
    if splinescope::files::resolved(file) == splinescope::files::resolved(output) {
        bail!(
            "{}: the output is the file being read; write the scene to another file (e.g. {})",
            output.display(),
            file.with_extension("json").display()
        );
    }
    let imported = splinescope::import::load(file)?;
    for w in &imported.warnings {
        eprintln!("warning: {w}");
    }
    let scene = imported.scene;
    let text = splinescope::scene::to_json_string(&scene);
    splinescope::files::write_atomic(output, text.as_bytes())
        .with_context(|| format!("{}: cannot write the scene", output.display()))?;
    say!(
        "{}: {} curve(s) written to {}",
        file.display(),
        scene.curves.len(),
        output.display()
    );
    Ok(())
}
