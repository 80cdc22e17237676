//! What the panel, canvas and dialogs ask the model to do ([`Actions`]), applied after drawing; shared constants and input helpers.

use glam::DVec3;

use crate::digest::SceneDigest;
use splinescope_encoding::camera::Camera;

use crate::interaction::{Answer, Template};

/// The panel's default width in points.
pub(crate) const PANEL_WIDTH_POINTS: f64 = 260.0;

/// What the panel shows.
pub(crate) struct PanelInfo<'a> {
    pub digest: &'a SceneDigest,
    pub adapter: &'a str,
    pub fps: f64,
    pub samples_per_frame: u64,
    /// Whether the sample buffers capped a recent frame.
    pub capped: bool,
    /// GPU milliseconds of a recent frame per stage (count, scan, tessellate, draw).
    pub stage_ms: Option<crate::timing::StageMs>,
    /// Why control polygons and points cannot be shown, when they cannot.
    pub overlays_locked: Option<&'static str>,
    pub camera: &'a Camera,
    /// Stress solving: curves re-solved per frame and the last batch's milliseconds.
    pub solving: Option<(usize, f64)>,
    /// The latest shape markers.
    pub markers: &'a [splinescope_scene::format::shape::Marker],
    /// What the selected curve's offset came to: its segments and bound, or why not.
    pub offset_status: Option<String>,
}

/// What the user asked for this frame.
#[derive(Debug, Default)]
pub(crate) struct Actions {
    pub fit: bool,
    pub save: bool,
    /// The answer to the open prompt.
    pub answer: Option<Answer>,
    /// A curve to add at the view's centre.
    pub add: Option<Template>,
    /// A curve to add at the context menu's position.
    pub add_at_menu: Option<Template>,
    /// The context menu's (or a panel button's) other entries.
    pub menu: Option<MenuItem>,
    /// The file menu's entries and the file dialog's buttons.
    pub file: Option<FileAction>,
    /// Turn the curvature combs on or off (`K`'s checkbox).
    pub toggle_comb: bool,
    /// Choose the comb's scale for the view.
    pub fit_comb: bool,
}

/// What the file menu or the file dialog asked for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum FileAction {
    New,
    Open,
    SaveAs,
    Export,
    OpenRecent(std::path::PathBuf),
    ConfirmDialog,
    CancelDialog,
}

/// An entry of the canvas's context menu (some also panel buttons).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum MenuItem {
    InsertPoint,
    DeleteSelection,
    Duplicate,
}

/// Whether a number widget's change stands: a drag always, a typed value unless Esc was
/// pressed this frame or the one before. egui gives a number field's typed text to the
/// value one frame after the field loses the keyboard, and Esc makes it lose the
/// keyboard: a typed change that arrives then is the text Esc was meant to cancel.
/// [`note_escape`] records the frame.
pub(crate) fn accepted(ctx: &egui::Context, response: &egui::Response) -> bool {
    if !response.changed() {
        return false;
    }
    let frame = ctx.cumulative_pass_nr();
    let escaped = ctx
        .data(|d| d.get_temp::<u64>(escape_id()))
        .is_some_and(|at| frame <= at + 1);
    response.dragged() || !escaped
}

/// Records the frame in which Esc was pressed (called once per frame, before any field).
pub(crate) fn note_escape(ctx: &egui::Context) {
    if ctx.input(|i| i.key_pressed(egui::Key::Escape)) {
        let frame = ctx.cumulative_pass_nr();
        ctx.data_mut(|d| d.insert_temp(escape_id(), frame));
    }
}

pub(crate) fn escape_id() -> egui::Id {
    egui::Id::unique("splinescope-escape-frame")
}

/// The colour of the selection and hover highlights: a magenta no palette colour is
/// near, so a selected curve is never mistaken for an orange one.
pub(crate) const SELECTION: egui::Color32 = egui::Color32::from_rgb(230, 0, 200);

/// The colour of warnings (a group outside its variation-diminishing range).
pub(crate) const WARNING: egui::Color32 = egui::Color32::from_rgb(200, 40, 40);

/// A point as the status line shows it (no z in planar scenes).
pub(crate) fn coords(p: DVec3, planar: bool) -> String {
    if planar {
        format!("({:.4}, {:.4})", p.x, p.y)
    } else {
        format!("({:.4}, {:.4}, {:.4})", p.x, p.y, p.z)
    }
}
