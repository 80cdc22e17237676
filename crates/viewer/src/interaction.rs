//! The viewer's interaction model, free of any window: pointer, wheel and key input go in,
//! the camera, the edited scene and the panel's switches change. The window layer only
//! translates winit events into [`Input`]; tests drive this model directly.

use std::path::PathBuf;

use glam::{DVec2, DVec3};
use splinescope_present::Present;

mod file_actions;

use super::edit::{Editor, Hit};
use super::file_dialog::{FileDialog, RecentFiles};
use splinescope_encoding::camera::Camera;
use splinescope_scene::format::{Scene, SceneCurve, Style};

/// Why the view could not be exported from the viewer's file dialog.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The figure could not be built (its message names the value).
    #[error(transparent)]
    Figure(#[from] splinescope_figure::FigureError),
    /// The file could not be written.
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// Where.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
}

/// What the side panel can change.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Toggles {
    /// Draw control polygons (and the families' explaining polylines).
    pub show_polygons: bool,
    /// Draw control points.
    pub show_points: bool,
    /// Show the side panel.
    pub show_panel: bool,
    /// Label each curve on the canvas with its name (`L`).
    pub show_labels: bool,
}

impl Default for Toggles {
    fn default() -> Toggles {
        Toggles {
            show_polygons: true,
            show_points: true,
            show_panel: true,
            show_labels: true,
        }
    }
}

/// A pointer button.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Button {
    /// Edit, or orbit (3D) / pan (2D).
    Primary,
    /// Pan.
    Secondary,
    /// Pan.
    Middle,
}

/// A key the viewer reacts to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Key {
    /// A character key (case-insensitive).
    Char(char),
    /// Escape: cancels a drag, a prompt, the help or the selection (it never quits).
    Escape,
    /// Delete or Backspace: deletes the selected point, else the selected curve.
    Delete,
    /// F1: the list of shortcuts (also `?`).
    Help,
}

/// What replaces or ends the edited scene, and so asks first when it has unsaved
/// changes ([`Interaction::request`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Pending {
    /// Close the window.
    Close,
    /// Open this scene file in place of the edited one.
    Open(PathBuf),
    /// Start a new, empty scene.
    New,
}

/// A question the viewer is asking; nothing else is edited until it is answered.
#[derive(Debug, Clone, PartialEq)]
pub enum Prompt {
    /// The scene has unsaved changes and is about to be closed or replaced: save,
    /// discard or cancel?
    Unsaved {
        /// What happens once the changes are saved or discarded.
        then: Pending,
    },
    /// Something the user asked for failed (a file that does not load); the edited scene
    /// is as it was. Any answer closes it.
    Failed {
        /// What failed and why.
        message: String,
    },
    /// A recovery file holds unsaved edits of this file from an earlier session.
    Recovery {
        /// The recovery file.
        path: PathBuf,
        /// What it holds.
        scene: Box<Scene>,
    },
}

/// An answer to a [`Prompt`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Answer {
    /// Unsaved: save, then go on (a scene without a file asks where first). Recovery:
    /// restore the edits.
    Accept,
    /// Unsaved: go on without saving (the recovery file is removed). Recovery: delete
    /// the recovery file.
    Discard,
    /// Keep going as before (Unsaved: nothing is closed or replaced; Recovery: keep the
    /// file for later and open the scene as saved).
    Cancel,
}

/// A starting curve a new curve can be added from ([`Interaction::add_curve`]): one of
/// the families' templates ([`splinescope_core::geom::Curve::templates`]), by position, with its
/// menu label.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Template {
    index: usize,
    label: &'static str,
}

/// Every template's label, in menu order (made once: the menus ask every frame).
fn template_labels() -> &'static [&'static str] {
    static LABELS: std::sync::OnceLock<Vec<&'static str>> = std::sync::OnceLock::new();
    LABELS.get_or_init(|| {
        splinescope_core::geom::Curve::templates(DVec3::ZERO, 1.0)
            .into_iter()
            .map(|(label, _)| label)
            .collect()
    })
}

impl Template {
    /// Every template, in menu order (the family table's).
    #[must_use]
    pub fn all() -> Vec<Template> {
        template_labels()
            .iter()
            .enumerate()
            .map(|(index, &label)| Template { index, label })
            .collect()
    }

    /// The first template of family `name` (a name of `Curve::FAMILY_NAMES`).
    #[must_use]
    pub fn of_family(name: &str) -> Option<Template> {
        splinescope_core::geom::Curve::templates(DVec3::ZERO, 1.0)
            .iter()
            .position(|(_, c)| c.family() == name)
            .and_then(|index| Template::all().get(index).copied())
    }

    /// The label shown in menus.
    #[must_use]
    pub fn label(self) -> &'static str {
        self.label
    }

    /// The template's curve centred on `center`, about `size` wide, in the plane z =
    /// `center.z`.
    #[must_use]
    pub fn curve(self, center: DVec3, size: f64) -> splinescope_core::geom::Curve {
        let mut all = splinescope_core::geom::Curve::templates(center, size);
        all.swap_remove(self.index).1
    }
}

/// One input event, in physical pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Input {
    /// The pointer moved to this position.
    PointerMoved(DVec2),
    /// A button went down (not over the panel).
    Pressed(Button),
    /// A button went up (anywhere).
    Released,
    /// The wheel turned this many lines (positive: zoom in), not over the panel.
    Wheel(f64),
    /// A key was pressed (not taken by the panel).
    Key {
        /// Which.
        key: Key,
        /// Control or Command held.
        ctrl: bool,
        /// Shift held.
        shift: bool,
    },
}

/// What the window layer must do after an input.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Response {
    /// Close the window.
    pub exit: bool,
}

/// The interaction state of one viewer.
pub struct Interaction {
    /// The edited scene, its history and file.
    pub editor: Editor,
    /// The camera.
    pub camera: Camera,
    /// The panel's switches.
    pub toggles: Toggles,
    /// The curvature comb and the shape markers (the panel's "shape" section).
    pub shape: crate::shape::ShapeView,
    /// The selected curve's offset, computed off the frame thread.
    pub offset: crate::shape::OffsetWorker,
    /// The window size in physical pixels.
    pub viewport: DVec2,
    /// Physical pixels per logical pixel (pick radius scales with it).
    pub scale_factor: f64,
    /// The panel's width in physical pixels (fitting leaves it free; presses and the
    /// wheel over it are the panel's, not the canvas's).
    pub panel_width_px: f64,
    /// The rectangles (min, max, physical pixels) of the panel's floating parts this frame
    /// — open menus, popups, windows, dialogs: presses and the wheel over them are theirs.
    pub ui_rects: Vec<(DVec2, DVec2)>,
    /// Keep fitting the scene until the user moves the camera; `F` turns it back on.
    pub auto_fit: bool,
    /// Whether the scene may be edited (not in stress-solve mode).
    pub editable: bool,
    /// The tessellation tolerance in pixels (`--tolerance-px`, the panel's slider).
    pub tolerance_px: f64,
    /// Why control polygons and points cannot be shown, when they cannot (`P` and `C` then
    /// show this reason instead).
    pub overlays_locked: Option<&'static str>,
    /// The question being asked, if any.
    pub prompt: Option<Prompt>,
    /// Whether the list of shortcuts is shown (F1, `?`).
    pub show_help: bool,
    /// What the pointer is over (control point or curve), for highlighting.
    pub hovered: Option<Hit>,
    /// Where a context menu was asked for (secondary click without a drag), in pixels.
    pub context_menu: Option<DVec2>,
    /// The window should close (a prompt was answered that way).
    pub exit_requested: bool,
    /// The open file dialog, if any (open, save as).
    pub dialog: Option<FileDialog>,
    /// The recently opened and saved files.
    pub recent: RecentFiles,
    /// What to do once the save-as dialog has saved (a close or a replacement that
    /// asked to save a scene without a file first).
    after_save: Option<Pending>,
    /// The directory of the file edited before this scene replaced it.
    last_dir: Option<PathBuf>,
    cursor: DVec2,
    dragging: Option<Button>,
    /// Where the secondary button went down (a click opens the context menu, a drag pans).
    secondary_from: Option<DVec2>,
    /// The point being edited by the primary drag (its depth anchors 3D drags).
    editing: Option<DVec3>,
}

impl Interaction {
    /// The model for `scene` shown in a `viewport`-sized window, saving to `editor`'s
    /// path. With an `"auto"` view the scene is fitted.
    #[must_use]
    pub fn new(editor: Editor, viewport: DVec2, scale_factor: f64, panel_width_px: f64) -> Self {
        let camera = editor.scene().camera(viewport);
        let auto_fit = editor.scene().view == splinescope_scene::format::ViewSpec::Auto;
        let mut model = Interaction {
            editor,
            camera,
            toggles: Toggles::default(),
            shape: crate::shape::ShapeView::default(),
            offset: crate::shape::OffsetWorker::default(),
            viewport,
            scale_factor,
            panel_width_px,
            ui_rects: Vec::new(),
            auto_fit,
            editable: true,
            tolerance_px: splinescope_gpu::adaptive::DEFAULT_TOLERANCE_PX,
            overlays_locked: None,
            prompt: None,
            show_help: false,
            hovered: None,
            context_menu: None,
            exit_requested: false,
            dialog: None,
            recent: RecentFiles::default(),
            after_save: None,
            last_dir: None,
            cursor: DVec2::ZERO,
            dragging: None,
            secondary_from: None,
            editing: None,
        };
        if model.auto_fit {
            model.fit();
        }
        model
    }

    /// The pointer's position in pixels.
    #[must_use]
    pub fn cursor(&self) -> DVec2 {
        self.cursor
    }

    /// The pointer's position in the scene (2D views; in 3D on the plane through the
    /// orbit target facing the camera).
    #[must_use]
    pub fn cursor_world(&self) -> DVec3 {
        self.camera.world_from_pixel(self.cursor, self.viewport)
    }

    /// The world size of `px` physical pixels around the view's centre (for templates
    /// and duplicate offsets).
    #[must_use]
    pub fn world_per_pixel(&self, px: f64) -> f64 {
        match &self.camera {
            Camera::Ortho2d(c) => px / c.pixels_per_unit,
            Camera::Orbit3d(c) => px * c.distance / self.viewport.y.max(1.0),
        }
    }

    /// Adds a curve of `template`'s family centred at `center` (the pointer, or the view's
    /// centre), about 200 pixels wide; one undoable edit.
    pub fn add_curve(&mut self, template: Template, center: DVec3) -> usize {
        let index = self.editor.scene().curves.len();
        let curve = SceneCurve {
            name: None,
            curve: template.curve(center, self.world_per_pixel(200.0)),
            style: Style::default_for(index),
        };
        self.auto_fit = false;
        self.editor.add_curve(curve)
    }

    /// Duplicates the selected curve, 20 pixels right and down; one undoable edit.
    pub fn duplicate_selected(&mut self) {
        let Some(index) = self.editor.selected else {
            self.editor.message = Some("select a curve to duplicate".into());
            return;
        };
        let d = self.world_per_pixel(20.0);
        if let Err(e) = self.editor.duplicate(index, DVec3::new(d, -d, 0.0)) {
            self.editor.message = Some(e.to_string());
        }
    }

    /// Inserts a control point into the selected curve at the pointer (on its polygon,
    /// or by knot insertion at the nearest curve parameter).
    pub fn insert_point_at_cursor(&mut self) {
        let Some(index) = self.editor.selected else {
            self.editor.message = Some("select a curve to insert a point into".into());
            return;
        };
        let at = self.cursor_world();
        match self.editor.insert_point(index, at) {
            Ok(point) => self.editor.selected_point = Some(point),
            Err(e) => {
                // Shown as a refused value is: in the warning colour.
                let text = e.to_string();
                self.editor.refusal = Some(crate::edit::Refusal {
                    curve: index,
                    field: String::new(),
                    text: text.clone(),
                });
                self.editor.message = Some(text);
            }
        }
    }

    /// Deletes the selected control point, else the selected curve.
    pub fn delete_selection(&mut self) {
        let result = match (self.editor.selected, self.editor.selected_point) {
            (Some(c), Some(p)) => self.editor.delete_point(c, p),
            (Some(c), None) => self.editor.delete_curve(c),
            (None, _) => Err(crate::edit::EditError::NothingSelected),
        };
        self.editor.selected_point = None;
        if let Err(e) = result {
            self.editor.message = Some(e.to_string());
        }
    }

    /// Cancels a drag in progress (the edit is undone, not recorded); whether there was
    /// one.
    fn cancel_gesture(&mut self) -> bool {
        self.dragging = None;
        self.secondary_from = None;
        if self.editing.take().is_some() {
            self.editor.cancel();
            return true;
        }
        self.editor.cancel()
    }

    /// The scene being shown.
    #[must_use]
    pub fn scene(&self) -> &Scene {
        self.editor.scene()
    }

    /// Whether a primary-button edit (point drag or curve pull) is in progress.
    #[must_use]
    pub fn is_editing(&self) -> bool {
        self.editing.is_some()
    }

    /// Applies one input. While a prompt is open only Esc (cancel) and the camera act.
    pub fn handle(&mut self, input: Input) -> Response {
        let response = self.handle_input(input);
        // What lies under the pointer may have changed (a drag ended, an undo moved a
        // point, the view moved): the highlight follows.
        if self.dragging.is_none() && self.editing.is_none() {
            self.hovered = self.pick();
        }
        response
    }

    fn handle_input(&mut self, input: Input) -> Response {
        // A prompt or a file dialog is modal: Esc answers "cancel", other clicks and keys
        // on the canvas do nothing (the camera still follows the pointer).
        if self.prompt.is_some() || self.dialog.is_some() {
            if let Input::Key {
                key: Key::Escape, ..
            } = input
            {
                if self.prompt.is_some() {
                    return self.answer(Answer::Cancel);
                }
                self.cancel_dialog();
                return Response::default();
            }
            if matches!(input, Input::Pressed(_) | Input::Key { .. }) {
                return Response::default();
            }
        }
        match input {
            Input::PointerMoved(p) => self.pointer_moved(p),
            // The panel's: a slider, a checkbox, a list row, a menu (the window layer also
            // drops what egui says it took, but egui's knowledge is a frame old).
            Input::Pressed(_) | Input::Wheel(_) if self.pointer_over_ui() => {}
            Input::Pressed(button) => {
                self.context_menu = None;
                if button == Button::Secondary {
                    self.secondary_from = Some(self.cursor);
                }
                if !(button == Button::Primary && self.begin_edit()) {
                    self.dragging = Some(button);
                }
            }
            Input::Released => {
                // A secondary click that did not move opens the context menu.
                if let Some(from) = self.secondary_from.take()
                    && (self.cursor - from).length() <= 3.0 * self.scale_factor
                    && self.editable
                {
                    self.context_menu = Some(self.cursor);
                }
                self.dragging = None;
                if self.editing.take().is_some() {
                    self.editor.finish();
                }
            }
            Input::Wheel(lines) => {
                self.camera
                    .zoom_at(1.15_f64.powf(lines), self.cursor, self.viewport);
                self.auto_fit = false;
            }
            Input::Key { key, ctrl, shift } => return self.key(key, ctrl, shift),
        }
        Response::default()
    }

    fn pointer_moved(&mut self, p: DVec2) {
        let delta = p - self.cursor;
        self.cursor = p;
        if let Some(anchor) = self.editing {
            let world = self.camera.drag_point(p, self.viewport, anchor);
            self.editor.drag_to(world);
            return;
        }
        match self.dragging {
            Some(Button::Primary) if self.camera.is_3d() => self.camera.orbit(delta),
            Some(_) => self.camera.pan(delta, self.viewport),
            None => return,
        }
        self.auto_fit = false;
    }

    fn key(&mut self, key: Key, ctrl: bool, shift: bool) -> Response {
        let c = match key {
            Key::Escape => {
                // Esc backs out of one thing at a time (menu, drag, help, selection); it
                // never quits.
                let backed_out = self.context_menu.take().is_some() || self.cancel_gesture();
                if !backed_out && self.show_help {
                    self.show_help = false;
                } else if !backed_out {
                    self.editor.selected_point = None;
                    self.editor.selected = None;
                }
                return Response::default();
            }
            Key::Help => {
                self.show_help ^= true;
                return Response::default();
            }
            Key::Delete => {
                if self.editable {
                    self.delete_selection();
                }
                return Response::default();
            }
            Key::Char(c) => c.to_ascii_lowercase(),
        };
        match c {
            '?' => self.show_help ^= true,
            ']' => self.select_next(1),
            '[' => self.select_next(-1),
            'q' if ctrl => return self.request_close(),
            'd' if ctrl && self.editable => self.duplicate_selected(),
            'i' if self.editable => self.insert_point_at_cursor(),
            'z' if ctrl && !shift => {
                self.editor.undo();
            }
            'z' | 'y' if ctrl => {
                self.editor.redo();
            }
            's' if ctrl && shift => self.save_as_dialog(),
            's' if ctrl => self.save(),
            'o' if ctrl => self.open_dialog(),
            'n' if ctrl => return self.request(Pending::New),
            'f' => {
                self.auto_fit = true;
                self.fit();
            }
            'p' | 'c' if self.overlays_locked.is_some() => {
                self.editor.message = self.overlays_locked.map(str::to_owned);
            }
            'p' => self.toggles.show_polygons ^= true,
            'c' => self.toggles.show_points ^= true,
            'h' => self.toggles.show_panel ^= true,
            'k' => self.toggle_comb(),
            'l' => self.toggles.show_labels ^= true,
            _ => {}
        }
        Response::default()
    }

    /// Turns the curvature combs on or off (`K`); turned on with an automatic scale, the
    /// scale is chosen for the current view.
    pub fn toggle_comb(&mut self) {
        self.shape.comb ^= true;
        if self.shape.comb && self.shape.comb_auto {
            self.fit_comb();
        }
    }

    /// Chooses the comb's scale for the current view (the panel's "auto").
    pub fn fit_comb(&mut self) {
        let height = self.camera.view_height(self.viewport);
        let scene = self.editor.scene();
        self.shape.fit_comb(scene, height);
    }

    /// Selects the curve `step` places after the selected one (before it when negative),
    /// wrapping around; the first (or last) when none is selected.
    pub fn select_next(&mut self, step: isize) {
        let n = self.scene().curves.len();
        if n == 0 || !self.editable {
            return;
        }
        self.cancel_gesture();
        let next = match self.editor.selected {
            Some(i) => (i as isize + step).rem_euclid(n as isize) as usize,
            None if step < 0 => n - 1,
            None => 0,
        };
        self.editor.selected = Some(next);
        self.editor.selected_point = None;
    }

    /// Saves to the editor's file (a scene without one asks where, in the save-as
    /// dialog); a failure is shown as the editor's message.
    pub fn save(&mut self) {
        if self.editor.path().is_none() {
            self.save_as_dialog();
            return;
        }
        match self.editor.save(None) {
            Ok(path) => self.remember(&path),
            Err(message) => self.editor.message = Some(message.to_string()),
        }
    }

    /// Fits the scene into the part of the window the panel leaves free.
    pub fn fit(&mut self) {
        let panel = if self.toggles.show_panel {
            self.panel_width_px.min(self.viewport.x * 0.5)
        } else {
            0.0
        };
        let free = DVec2::new((self.viewport.x - panel).max(1.0), self.viewport.y);
        let scene = self.editor.scene();
        self.camera = Camera::fit(scene.bounds(), free, !scene.is_planar());
        // Keep the scale fitted to the free area, centred in it.
        if let Camera::Ortho2d(c) = &mut self.camera {
            c.center.x -= 0.5 * panel / c.pixels_per_unit;
        }
    }

    /// Whether the pointer is over the panel or one of its floating parts: input there is
    /// the panel's, and nothing on the canvas is picked or read out.
    #[must_use]
    pub fn pointer_over_ui(&self) -> bool {
        let p = self.cursor;
        p.x < self.panel_width_px
            || self
                .ui_rects
                .iter()
                .any(|(lo, hi)| p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y)
    }

    /// What is under the pointer (nothing when editing is off or the pointer is over the
    /// panel).
    fn pick(&self) -> Option<Hit> {
        if !self.editable || self.pointer_over_ui() {
            return None;
        }
        self.editor.pick(
            &self.camera,
            self.viewport,
            self.cursor,
            9.0 * self.scale_factor,
            self.toggles.show_points,
        )
    }

    /// Starts an edit under the pointer (a control point, or a Bézier curve to pull);
    /// `false` when there is nothing to edit there. A curve that cannot be pulled is
    /// selected (and the drag pans).
    fn begin_edit(&mut self) -> bool {
        let at = match self.pick() {
            Some(Hit::Point { curve, index, at }) => {
                self.editor.begin_point_drag(curve, index);
                at
            }
            Some(Hit::Curve { curve, t, at }) => {
                if !self.editor.can_pull(curve) {
                    self.editor.finish();
                    self.editor.selected = Some(curve);
                    self.editor.selected_point = None;
                    return false;
                }
                match self.editor.begin_pull(curve, t) {
                    Ok(()) => at,
                    Err(message) => {
                        self.editor.message = Some(message.to_string());
                        return false;
                    }
                }
            }
            None => return false,
        };
        self.editing = Some(at);
        // The view stays put while the scene is edited.
        self.auto_fit = false;
        true
    }
}
