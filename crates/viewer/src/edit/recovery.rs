//! The recovery file: unsaved edits kept next to the scene file (`scene.json` →
//! `scene.json.recovery`) until they are saved or discarded, found and restored when the
//! file is opened again. Apart from the editing model so that undo and file I/O each have
//! their own file.

use std::path::{Path, PathBuf};

use super::Editor;
use crate::scene::Scene;

/// The recovery file kept next to a scene file while it has unsaved edits:
/// `scene.json` → `scene.json.recovery`.
#[must_use]
pub fn recovery_path(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".recovery");
    path.with_file_name(name)
}

impl Editor {
    /// Keeps the recovery file in step with the committed edits: written (atomically)
    /// while they differ from the saved file, removed once they do not.
    pub(super) fn sync_recovery(&mut self) {
        let Some(path) = self.path.as_deref() else {
            return;
        };
        let recovery = recovery_path(path);
        if self.committed_dirty() {
            match self.scene.save(&recovery) {
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
    pub fn find_recovery(&self) -> Option<(PathBuf, Result<Scene, crate::scene::SceneError>)> {
        let recovery = recovery_path(self.path.as_deref()?);
        if !recovery.exists() {
            return None;
        }
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
            let recovery = recovery_path(path);
            self.remove_recovery(&recovery);
        }
    }
}
