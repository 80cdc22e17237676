//! The viewer's egui layer, one file per job: the side panel (`panel.rs`), the canvas and
//! its context menu (`canvas.rs`), the help window, prompts and file dialog
//! (`dialogs.rs`), and what they ask of the model (`actions.rs`); here the frame's drawing
//! and the actions' application. What the GPU sync needs of the scene is in `digest.rs`.

mod actions;
mod canvas;
mod dialogs;
mod panel;
mod shape;

pub(crate) use actions::{
    Actions, FileAction, MenuItem, PANEL_WIDTH_POINTS, PanelInfo, note_escape,
};

use crate::interaction::{Input, Interaction, Pending};
use canvas::canvas;
use dialogs::file_dialog;
use panel::panel;

/// Carries out what the panel, the context menu, the prompt and the file dialog asked
/// for this frame.
pub(crate) fn apply(model: &mut Interaction, actions: Actions) {
    if actions.toggle_comb {
        model.toggle_comb();
    }
    if actions.fit_comb {
        model.fit_comb();
    }
    if actions.fit {
        model.auto_fit = true;
    }
    if actions.save {
        model.save();
    }
    if let Some(answer) = actions.answer {
        model.answer(answer);
    }
    match actions.file {
        Some(FileAction::New) => {
            model.request(Pending::New);
        }
        Some(FileAction::Open) => model.open_dialog(),
        Some(FileAction::SaveAs) => model.save_as_dialog(),
        Some(FileAction::Export) => model.export_dialog(),
        Some(FileAction::OpenRecent(path)) => {
            model.open_path(&path);
        }
        Some(FileAction::ConfirmDialog) => {
            model.confirm_dialog();
        }
        Some(FileAction::CancelDialog) => model.cancel_dialog(),
        None => {}
    }
    if let Some(t) = actions.add {
        let center = model.camera.world_from_pixel(
            glam::DVec2::new(
                0.5 * (model.viewport.x + model.panel_width_px),
                0.5 * model.viewport.y,
            ),
            model.viewport,
        );
        model.add_curve(t, center);
    }
    let menu_at = model.context_menu;
    if let (Some(t), Some(at)) = (actions.add_at_menu, menu_at) {
        let center = model.camera.world_from_pixel(at, model.viewport);
        model.add_curve(t, center);
        model.context_menu = None;
    }
    if let Some(item) = actions.menu {
        match item {
            MenuItem::InsertPoint => {
                // At the point where the menu was opened.
                if let Some(at) = menu_at {
                    model.handle(Input::PointerMoved(at));
                }
                model.insert_point_at_cursor();
            }
            MenuItem::DeleteSelection => model.delete_selection(),
            MenuItem::Duplicate => model.duplicate_selected(),
        }
        model.context_menu = None;
    }
}

/// The whole overlay of one frame: the side panel, the canvas's feedback, menus and
/// prompt, and the file dialog. Returns the panel's width in points.
pub(crate) fn draw(
    ui: &mut egui::Ui,
    info: &PanelInfo<'_>,
    model: &mut Interaction,
    actions: &mut Actions,
) -> f32 {
    note_escape(ui.ctx());
    let width = panel(ui, info, model, actions);
    canvas(ui, model, info.digest, actions);
    shape::canvas_shape(ui, info, model);
    if model.prompt.is_none()
        && let Some(dialog) = model.dialog.as_mut()
    {
        file_dialog(ui.ctx(), dialog, actions);
    }
    width
}
