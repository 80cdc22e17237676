//! The recovery file: unsaved edits kept in the user's state directory
//! (`$XDG_STATE_HOME/splinescope/recovery/`, named by the scene's file name and a hash of
//! its absolute path) until they are saved or discarded, found and restored when the file
//! is opened again — also from `scene.json.recovery` beside the scene, where earlier
//! versions kept it. Apart from the editing model so that undo and file I/O each have
//! their own file.

use std::path::{Path, PathBuf};

use super::Editor;
use splinescope_scene::format::Scene;

/// Where recovery files are kept: `$SPLINESCOPE_STATE_DIR/recovery`, else
/// `$XDG_STATE_HOME/splinescope/recovery`, else `$HOME/.local/state/splinescope/recovery`;
/// `None` when none of them is set.
#[must_use]
pub fn recovery_dir() -> Option<PathBuf> {
    let state = crate::file_dialog::user_dir(
        "SPLINESCOPE_STATE_DIR",
        "XDG_STATE_HOME",
        &[".local", "state"],
    )?;
    Some(state.join("recovery"))
}

/// The recovery file of the scene file `path`: in [`recovery_dir`], named by the file's
/// name and a hash of its absolute path (`gallery.json` →
/// `gallery.json-1f2e3d4c5b6a7988.json`), so that scenes of one name in different
/// folders keep apart and nothing is written beside the scene; beside it
/// ([`legacy_recovery_path`]) only when no state directory can be named.
#[must_use]
pub fn recovery_path(path: &Path) -> PathBuf {
    let Some(dir) = recovery_dir() else {
        return legacy_recovery_path(path);
    };
    let absolute = std::fs::canonicalize(path)
        .or_else(|_| std::path::absolute(path))
        .unwrap_or_else(|_| path.to_path_buf());
    let name = path.file_name().unwrap_or_default().to_string_lossy();
    dir.join(format!(
        "{name}-{:016x}.json",
        fnv1a(absolute.as_os_str().as_encoded_bytes())
    ))
}

/// Where earlier versions kept the recovery file, beside the scene: `scene.json` →
/// `scene.json.recovery` (still offered when found there).
#[must_use]
pub fn legacy_recovery_path(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".recovery");
    path.with_file_name(name)
}

/// FNV-1a, 64 bits: a hash that is the same in every build and on every machine (the
/// standard library's is not promised to be).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

impl Editor {
    /// Keeps the recovery file in step with the committed edits: written (atomically)
    /// while they differ from the saved file, removed once they do not.
    pub(super) fn sync_recovery(&mut self) {
        let Some(path) = self.path.as_deref() else {
            return;
        };
        let (recovery, legacy) = (recovery_path(path), legacy_recovery_path(path));
        if self.committed_dirty() {
            let made = recovery
                .parent()
                .map_or(Ok(()), std::fs::create_dir_all)
                .map_err(|e| e.to_string());
            match made.and_then(|()| self.scene.save(&recovery).map_err(|e| e.to_string())) {
                Err(e) => {
                    let text = format!(
                        "the unsaved edits are not kept on disk: the recovery file {} cannot be written ({e})",
                        recovery.display()
                    );
                    self.message = Some(text.clone());
                    self.warning = Some(text);
                    self.recovery_failed = true;
                }
                Ok(()) => {
                    // A warning about the recovery file is over once it is written.
                    if std::mem::take(&mut self.recovery_failed) {
                        self.warning = None;
                    }
                }
            }
        } else {
            self.remove_recovery(&recovery);
            self.remove_recovery(&legacy);
        }
    }

    /// Removes the recovery file `recovery` if it exists (a failure is the message).
    pub(super) fn remove_recovery(&mut self, recovery: &Path) {
        if recovery.exists()
            && let Err(e) = std::fs::remove_file(recovery)
        {
            self.message = Some(format!("{}: cannot remove: {e}", recovery.display()));
        }
    }

    /// The recovery file left by an earlier session of this file (unsaved edits), if
    /// any: its path and the scene it holds, or why it cannot be read.
    #[must_use]
    pub fn find_recovery(
        &self,
    ) -> Option<(
        PathBuf,
        Result<Scene, splinescope_scene::format::SceneError>,
    )> {
        let path = self.path.as_deref()?;
        let recovery = [recovery_path(path), legacy_recovery_path(path)]
            .into_iter()
            .find(|r| r.exists())?;
        let scene = Scene::load(&recovery);
        Some((recovery, scene))
    }

    /// Restores the curves of a recovered scene as one undoable edit (the scene is then
    /// unsaved, and the recovery file kept until it is saved).
    pub fn restore(&mut self, recovered: &Scene) {
        self.finish();
        if recovered.curves == self.scene.curves {
            return;
        }
        self.edit_list(recovered.curves.clone(), None);
        self.message = Some("unsaved edits restored".into());
    }

    /// Removes the recovery file (the user discarded the unsaved edits).
    pub fn discard_recovery(&mut self) {
        if let Some(path) = self.path.as_deref() {
            let (recovery, legacy) = (recovery_path(path), legacy_recovery_path(path));
            self.remove_recovery(&recovery);
            self.remove_recovery(&legacy);
        }
    }
}
