//! The viewer's interaction model, free of any window: pointer, wheel and key input go in,
//! the camera, the edited scene and the panel's switches change. The window layer only
//! translates winit events into [`Input`]; tests drive this model directly.

use glam::{DVec2, DVec3};

use super::edit::{Editor, Hit};
use crate::camera::Camera;
use crate::scene::Scene;

/// What the side panel can change.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Toggles {
    /// Draw control polygons (and the families' explaining polylines).
    pub show_polygons: bool,
    /// Draw control points.
    pub show_points: bool,
    /// Show the side panel.
    pub show_panel: bool,
}

impl Default for Toggles {
    fn default() -> Toggles {
        Toggles {
            show_polygons: true,
            show_points: true,
            show_panel: true,
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
    /// Escape.
    Escape,
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
    /// The window size in physical pixels.
    pub viewport: DVec2,
    /// Physical pixels per logical pixel (pick radius scales with it).
    pub scale_factor: f64,
    /// The panel's width in physical pixels (fitting leaves it free).
    pub panel_width_px: f64,
    /// Keep fitting the scene until the user moves the camera; `F` turns it back on.
    pub auto_fit: bool,
    /// Whether the scene may be edited (not in stress-solve mode).
    pub editable: bool,
    /// The tessellation tolerance in pixels (`--tolerance-px`, the panel's slider).
    pub tolerance_px: f64,
    /// Why control polygons and points cannot be shown, when they cannot (`P` and `C` then
    /// show this reason instead).
    pub overlays_locked: Option<&'static str>,
    cursor: DVec2,
    dragging: Option<Button>,
    /// The point being edited by the primary drag (its depth anchors 3D drags).
    editing: Option<DVec3>,
}

impl Interaction {
    /// The model for `scene` shown in a `viewport`-sized window, saving to `editor`'s
    /// path. With an `"auto"` view the scene is fitted.
    #[must_use]
    pub fn new(editor: Editor, viewport: DVec2, scale_factor: f64, panel_width_px: f64) -> Self {
        let camera = editor.scene().camera(viewport);
        let auto_fit = editor.scene().view == crate::scene::ViewSpec::Auto;
        let mut model = Interaction {
            editor,
            camera,
            toggles: Toggles::default(),
            viewport,
            scale_factor,
            panel_width_px,
            auto_fit,
            editable: true,
            tolerance_px: crate::gpu::adaptive::DEFAULT_TOLERANCE_PX,
            overlays_locked: None,
            cursor: DVec2::ZERO,
            dragging: None,
            editing: None,
        };
        if model.auto_fit {
            model.fit();
        }
        model
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

    /// Applies one input.
    pub fn handle(&mut self, input: Input) -> Response {
        match input {
            Input::PointerMoved(p) => self.pointer_moved(p),
            Input::Pressed(button) => {
                if !(button == Button::Primary && self.begin_edit()) {
                    self.dragging = Some(button);
                }
            }
            Input::Released => {
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
            Key::Escape => return Response { exit: true },
            Key::Char(c) => c.to_ascii_lowercase(),
        };
        match c {
            'z' if ctrl && !shift => {
                self.editor.undo();
            }
            'z' | 'y' if ctrl => {
                self.editor.redo();
            }
            's' if ctrl => self.save(),
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
            _ => {}
        }
        Response::default()
    }

    /// Saves to the editor's file; a failure is shown as the editor's message.
    pub fn save(&mut self) {
        if let Err(message) = self.editor.save(None) {
            self.editor.message = Some(message);
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

    /// Starts an edit under the pointer (a control point, or a Bézier curve to pull);
    /// `false` when there is nothing to edit there.
    fn begin_edit(&mut self) -> bool {
        if !self.editable {
            return false;
        }
        let radius = 9.0 * self.scale_factor;
        let hit = self.editor.pick(
            &self.camera,
            self.viewport,
            self.cursor,
            radius,
            self.toggles.show_points,
        );
        let at = match hit {
            Some(Hit::Point { curve, index, at }) => {
                self.editor.begin_point_drag(curve, index);
                at
            }
            Some(Hit::Curve { curve, t, at }) => match self.editor.begin_pull(curve, t) {
                Ok(()) => at,
                Err(message) => {
                    self.editor.message = Some(message);
                    return false;
                }
            },
            None => return false,
        };
        self.editing = Some(at);
        // The view stays put while the scene is edited.
        self.auto_fit = false;
        true
    }
}
