//! Reading the scene a command works on: a splinescope scene (`.json`), or a file of
//! another format (`.svg`) read as a scene of path curves, what it left out said on stderr.

use std::path::Path;

use anyhow::{Context, Result};
use splinescope::scene::Scene;

/// The scene in `path`: a scene file as it is, an SVG file imported
/// ([`splinescope::import::load`]), each warning of the import printed on stderr.
///
/// # Errors
/// The file does not read: the message names the file and the value or the place.
pub fn scene(path: &Path) -> Result<Scene> {
    if splinescope::import::is_scene_file(path) {
        return Scene::load(path).with_context(|| format!("{}", path.display()));
    }
    let imported = splinescope::import::load(path)?;
    for w in &imported.warnings {
        eprintln!("warning: {w}");
    }
    Ok(imported.scene)
}
