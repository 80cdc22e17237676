//! Reading the scene a command works on: a splinescope scene (`.json`), or a file of
//! another format (SVG, DXF, STEP, a font) read as a scene, what it left out said on
//! stderr, with the font options the command line gave (`--glyphs`, `--text`,
//! `--variations`, `--font-index`: global flags).

use std::path::Path;

use std::sync::OnceLock;

use anyhow::{Context, Result};
use splinescope_scene::format::Scene;

static OPTIONS: OnceLock<splinescope_import::Options> = OnceLock::new();

/// Sets the import options of this run (once, from the command line).
pub fn set_options(options: splinescope_import::Options) {
    let _ = OPTIONS.set(options);
}

/// The import options of this run (the defaults when none were set).
pub fn options() -> splinescope_import::Options {
    OPTIONS.get().cloned().unwrap_or_default()
}

/// The scene in `path`: a scene file as it is, an SVG file imported
/// ([`splinescope_import::load`]), each warning of the import printed on stderr.
///
/// # Errors
/// The file does not read: the message names the file and the value or the place.
pub fn scene(path: &Path) -> Result<Scene> {
    if splinescope_import::is_scene_file(path) {
        return Scene::load(path).with_context(|| format!("{}", path.display()));
    }
    let imported = splinescope_import::load_with(path, &options())?;
    for w in &imported.warnings {
        eprintln!("warning: {w}");
    }
    Ok(imported.scene)
}
