//! The viewer's file actions as the model sees them: open, save as, export of the view,
//! the recovery offer, the confirmations they may need (unsaved changes, replacing a
//! file) and the answers to them.

use std::path::{Path, PathBuf};

use super::{Answer, ExportError, Interaction, Pending, Prompt, Response};
use crate::edit::Editor;
use crate::file_dialog::{self, DialogMode, FileDialog};
use splinescope_encoding::camera::Camera;
use splinescope_scene::format::Scene;

impl Interaction {
    /// Offers the recovery file of an earlier session, if the editor's file has one
    /// (an unreadable one is reported and left in place).
    pub fn offer_recovery(&mut self) {
        match self.editor.find_recovery() {
            Some((path, Ok(scene))) => {
                self.prompt = Some(Prompt::Recovery {
                    path,
                    scene: Box::new(scene),
                });
            }
            Some((path, Err(e))) => {
                self.editor.message = Some(format!(
                    "{}: unsaved edits could not be read ({e}); the file is left in place",
                    path.display()
                ));
            }
            None => {}
        }
    }

    /// The window is asked to close: closes at once when nothing is unsaved (or editing
    /// is off), otherwise asks (save / discard / cancel).
    pub fn request_close(&mut self) -> Response {
        self.request(Pending::Close)
    }

    /// Closes or replaces the scene: at once when nothing is unsaved (or editing is off),
    /// otherwise after asking (save / discard / cancel).
    pub fn request(&mut self, action: Pending) -> Response {
        self.cancel_gesture();
        if action != Pending::Close && self.refuse_files() {
            return Response::default();
        }
        if !self.editable || !self.editor.is_dirty() {
            return self.carry_out(action, false);
        }
        self.prompt = Some(Prompt::Unsaved { then: action });
        Response::default()
    }

    /// Does what was asked, without asking. With `discard`, the unsaved edits' recovery
    /// file is removed once the scene is really closed or replaced (a file that fails to
    /// load keeps both the edits and their recovery file, and says why in a prompt).
    fn carry_out(&mut self, action: Pending, discard: bool) -> Response {
        let mut imported_note: Option<Vec<String>> = None;
        let replacement = match &action {
            Pending::Close => None,
            Pending::Open(path) if !splinescope_import::is_scene_file(path) => {
                match splinescope_import::load(path) {
                    Ok(imported) => {
                        // Saved beside it as a scene, never over it (nor over a scene there).
                        let beside = path.with_extension("json");
                        let save_to = (!beside.exists()).then_some(beside);
                        let editor = Editor::new(imported.scene, save_to);
                        imported_note = Some(imported.warnings);
                        Some(editor)
                    }
                    Err(e) => {
                        self.prompt = Some(Prompt::Failed {
                            message: format!("{e}. The scene shown is unchanged."),
                        });
                        return Response::default();
                    }
                }
            }
            Pending::Open(path) => match Scene::read(path) {
                Ok((scene, text)) => Some(Editor::of_file(scene, path.clone(), text)),
                Err(e) => {
                    self.prompt = Some(Prompt::Failed {
                        message: format!(
                            "{} was not opened: {e}. The scene shown is unchanged.",
                            path.display()
                        ),
                    });
                    return Response::default();
                }
            },
            Pending::New => Some(Editor::new(Scene::of_curves([]), None)),
        };
        if discard {
            self.editor.discard_recovery();
        }
        let Some(editor) = replacement else {
            self.exit_requested = true;
            return Response { exit: true };
        };
        self.replace_editor(editor);
        match action {
            Pending::Open(path) => {
                self.editor.message = Some(match imported_note {
                    Some(left_out) => {
                        let saves = self.editor.path().map_or_else(
                            || "Save asks where (a scene of that name is there)".to_owned(),
                            |p| format!("Save writes {}", p.display()),
                        );
                        let mut m = format!(
                            "opened {} as {} path curve(s); {saves}",
                            path.display(),
                            self.editor.scene().curves.len()
                        );
                        for w in left_out {
                            m.push_str("; ");
                            m.push_str(&w);
                        }
                        m
                    }
                    None => format!("opened {}", path.display()),
                });
                self.remember(&path);
                self.offer_recovery();
            }
            _ => {
                self.editor.message = Some(
                    "new scene: right-click the canvas or use add curve… to add curves".into(),
                );
            }
        }
        Response::default()
    }

    /// Whether files cannot be opened (editing is off while solving); says so.
    fn refuse_files(&mut self) -> bool {
        if !self.editable {
            self.editor.message = Some("files cannot be opened while solving".into());
        }
        !self.editable
    }

    /// Puts `path` first among the recent files (a list that cannot be kept says so).
    pub(super) fn remember(&mut self, path: &Path) {
        if let Err(e) = self.recent.add(path) {
            self.editor.message = Some(e.to_string());
        }
    }

    /// Shows `editor`'s scene instead of the current one: camera, selection, hover and
    /// menus start afresh; the window redraws everything.
    fn replace_editor(&mut self, mut editor: Editor) {
        if let Some(dir) = self.editor.path().and_then(Path::parent) {
            self.last_dir = Some(dir.to_path_buf());
        }
        editor.mark_replaced();
        self.editor = editor;
        self.hovered = None;
        self.context_menu = None;
        self.dialog = None;
        self.camera = self.editor.scene().camera(self.viewport);
        self.auto_fit = self.editor.scene().view == splinescope_scene::format::ViewSpec::Auto;
        if self.auto_fit {
            self.fit();
        }
    }

    /// Opens the scene file at `path` (a dropped file, a recent one), asking first when
    /// the scene has unsaved changes.
    pub fn open_path(&mut self, path: &Path) -> Response {
        self.request(Pending::Open(path.to_path_buf()))
    }

    /// The directory the file dialogs start in: the edited file's, else the one of the
    /// file edited before (a new scene), else the current one.
    fn dialog_dir(&self) -> PathBuf {
        self.editor
            .path()
            .and_then(Path::parent)
            .or(self.last_dir.as_deref())
            .filter(|d| !d.as_os_str().is_empty())
            .map_or_else(
                || std::env::current_dir().unwrap_or_else(|_| PathBuf::from(".")),
                Path::to_path_buf,
            )
    }

    /// Shows the open dialog (Ctrl+O).
    pub fn open_dialog(&mut self) {
        if self.refuse_files() {
            return;
        }
        self.cancel_gesture();
        self.dialog = Some(FileDialog::new(DialogMode::Open, &self.dialog_dir(), ""));
    }

    /// Shows the save-as dialog (Ctrl+Shift+S), proposing the file's name.
    pub fn save_as_dialog(&mut self) {
        self.cancel_gesture();
        let name = self.editor.path().and_then(Path::file_name).map_or_else(
            || file_dialog::DEFAULT_SAVE_NAME.into(),
            |n| n.to_string_lossy().into_owned(),
        );
        self.dialog = Some(FileDialog::new(
            DialogMode::SaveAs,
            &self.dialog_dir(),
            &name,
        ));
    }

    /// Shows the export dialog (file → export view…), proposing the scene's name as SVG.
    pub fn export_dialog(&mut self) {
        self.cancel_gesture();
        let stem = self
            .editor
            .path()
            .and_then(Path::file_stem)
            .map_or_else(|| "figure".into(), |n| n.to_string_lossy().into_owned());
        self.dialog = Some(FileDialog::new(
            DialogMode::Export,
            &self.dialog_dir(),
            &format!("{stem}.svg"),
        ));
    }

    /// The part of the window the canvas shows (right of the panel) as a figure's size
    /// and camera: in 2D the panel's strip is left out (the camera's centre moves to the
    /// strip that remains, so everything stays where it is on screen); a 3D view is
    /// exported whole (its projection is centred on the window).
    #[must_use]
    pub fn export_frame(&self) -> (u32, u32, Camera) {
        let panel = if self.toggles.show_panel {
            self.panel_width_px.min(self.viewport.x - 1.0).max(0.0)
        } else {
            0.0
        };
        let height = self.viewport.y.round().max(1.0) as u32;
        match self.camera {
            Camera::Ortho2d(mut c) if panel > 0.0 => {
                c.center.x += 0.5 * panel / c.pixels_per_unit;
                let width = (self.viewport.x - panel).round().max(1.0) as u32;
                (width, height, Camera::Ortho2d(c))
            }
            camera => (self.viewport.x.round().max(1.0) as u32, height, camera),
        }
    }

    /// Writes what is on screen — the canvas right of the panel, with the same camera,
    /// overlay toggles, comb and markers, curves labelled as on the canvas — as an SVG or
    /// PDF figure at
    /// `path` (atomically).
    ///
    /// # Errors
    /// [`ExportError`]: the figure's or the write's.
    pub fn export_view(&self, path: &Path) -> Result<(), ExportError> {
        let (width, height, camera) = self.export_frame();
        let mut opts = splinescope_figure::FigureOptions::new(width, height);
        opts.camera = Some(camera);
        opts.switches = splinescope_encoding::draw::Switches {
            polygons: self.toggles.show_polygons,
            points: self.toggles.show_points,
        };
        opts.labels = true;
        // The shape overlays as shown: the comb at the panel's scale, the markers.
        opts.shape = self.shape.marker_options();
        if self.shape.comb && (!self.shape.comb_selected_only || self.editor.selected.is_some()) {
            opts.shape.comb = Some(splinescope_scene::format::shape::CombScale::Fixed(
                self.shape.comb_scale,
            ));
            opts.comb_only = self
                .editor
                .selected
                .filter(|_| self.shape.comb_selected_only);
        }
        let fig = splinescope_figure::build(self.scene(), &opts)?;
        let pdf = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("pdf"));
        let bytes = if pdf {
            splinescope_figure::pdf::write(&fig)
        } else {
            splinescope_figure::svg::write(&fig).into_bytes()
        };
        splinescope_io::files::write_atomic(path, &bytes).map_err(|source| ExportError::Write {
            path: path.to_owned(),
            source,
        })
    }

    /// Closes the file dialog without choosing (what was waiting for a save is dropped).
    pub fn cancel_dialog(&mut self) {
        self.dialog = None;
        self.after_save = None;
    }

    /// Confirms the file dialog's choice: opens the file (asking first when there are
    /// unsaved changes) or saves to it, then does what waited for the save. A choice
    /// that cannot be used keeps the dialog open with the reason.
    pub fn confirm_dialog(&mut self) -> Response {
        let Some(dialog) = self.dialog.as_mut() else {
            return Response::default();
        };
        let Some(path) = dialog.confirm() else {
            return Response::default();
        };
        match dialog.mode {
            DialogMode::Open => {
                self.dialog = None;
                self.open_path(&path)
            }
            DialogMode::Export => {
                match self.export_view(&path) {
                    Ok(()) => {
                        self.dialog = None;
                        self.editor.message =
                            Some(format!("exported the view to {}", path.display()));
                    }
                    Err(e) => {
                        if let Some(d) = self.dialog.as_mut() {
                            d.error = Some(e.to_string());
                        }
                    }
                }
                Response::default()
            }
            DialogMode::SaveAs => match self.editor.save(Some(&path)) {
                Ok(saved) => {
                    self.dialog = None;
                    self.remember(&saved);
                    match self.after_save.take() {
                        Some(then) => self.carry_out(then, false),
                        None => Response::default(),
                    }
                }
                Err(e) => {
                    dialog.error = Some(e.to_string());
                    Response::default()
                }
            },
        }
    }

    /// Answers the open prompt.
    pub fn answer(&mut self, answer: Answer) -> Response {
        let Some(prompt) = self.prompt.take() else {
            return Response::default();
        };
        match (prompt, answer) {
            (Prompt::Unsaved { then }, Answer::Accept) => {
                let asks_where = self.editor.path().is_none();
                self.save();
                if asks_where {
                    // The save-as dialog saves, then goes on.
                    self.after_save = Some(then);
                    return Response::default();
                }
                if self.editor.is_dirty() {
                    // The save failed (its message says why): nothing is closed.
                    return Response::default();
                }
                return self.carry_out(then, false);
            }
            (Prompt::Unsaved { then }, Answer::Discard) => return self.carry_out(then, true),
            (Prompt::Recovery { scene, .. }, Answer::Accept) => self.editor.restore(&scene),
            (Prompt::Recovery { path, .. }, Answer::Discard) => {
                self.editor.discard_recovery();
                self.editor.message = Some(format!("deleted {}", path.display()));
            }
            (Prompt::Recovery { path, .. }, Answer::Cancel) => {
                self.editor.message = Some(format!(
                    "unsaved edits kept in {} (offered again next time)",
                    path.display()
                ));
            }
            (Prompt::Unsaved { .. } | Prompt::Failed { .. }, _) => {}
        }
        Response {
            exit: self.exit_requested,
        }
    }
}
