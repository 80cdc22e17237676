//! Dialogs and windows: the shortcuts' help, prompts and the file dialog.

use crate::file_dialog::{DialogMode, FileDialog};
use crate::interaction::{Answer, Interaction, Pending, Prompt};

use super::actions::*;
/// Every shortcut, as the help window lists them.
pub(crate) const SHORTCUTS: &[(&str, &str)] = &[
    ("left drag on a point", "move the control point"),
    (
        "left drag on a Bézier curve",
        "pull the curve through the pointer (paper 000)",
    ),
    ("left click on a curve", "select it"),
    ("] / [", "select the next / previous curve"),
    ("left drag elsewhere", "pan (2D) / orbit (3D)"),
    ("right or middle drag", "pan"),
    (
        "right click",
        "menu: add a curve here, insert or delete a point, duplicate",
    ),
    ("wheel", "zoom at the pointer"),
    ("F", "fit the scene"),
    ("P / C", "control polygons / control points"),
    ("H", "hide or show the panel"),
    ("L", "hide or show the curves' labels on the canvas"),
    (
        "K",
        "curvature combs on or off (the panel's shape section sets their scale)",
    ),
    ("I", "insert a point into the selected curve at the pointer"),
    (
        "Delete, Backspace",
        "delete the selected point, else the selected curve",
    ),
    ("Ctrl+D", "duplicate the selected curve"),
    ("Ctrl+Z", "undo"),
    ("Ctrl+Shift+Z, Ctrl+Y", "redo"),
    ("Ctrl+S", "save (a new scene asks where)"),
    ("Ctrl+Shift+S", "save as"),
    ("Ctrl+O", "open a scene (or drop a file on the window)"),
    ("Ctrl+N", "new, empty scene"),
    (
        "Esc",
        "cancel the drag, the menu, the dialog, this help or the selection (never quits)",
    ),
    (
        "Ctrl+Q, closing the window",
        "quit (asks when there are unsaved changes)",
    ),
    ("F1, ?", "this list"),
];

/// The list of shortcuts ([`SHORTCUTS`]) in a window.
pub(crate) fn help_window(ctx: &egui::Context) {
    egui::Window::new("shortcuts (F1, ?)")
        .collapsible(false)
        .resizable(false)
        .anchor(egui::Align2::CENTER_CENTER, egui::vec2(0.0, 0.0))
        .show(ctx, |ui| {
            egui::Grid::new("shortcuts").striped(true).show(ui, |ui| {
                for (keys, what) in SHORTCUTS {
                    ui.strong(*keys);
                    ui.label(*what);
                    ui.end_row();
                }
            });
            ui.small("Esc closes this list.");
        });
}

/// The open question, as a modal window.
pub(crate) fn prompt_modal(
    ctx: &egui::Context,
    model: &Interaction,
    prompt: &Prompt,
    actions: &mut Actions,
) {
    let file = model
        .editor
        .path()
        .map_or_else(|| "The scene".to_owned(), |p| p.display().to_string());
    let (title, text, accept, discard) = match prompt {
        Prompt::Unsaved { then } => {
            let (before, accept, discard) = match then {
                Pending::Close => (
                    "closing".to_owned(),
                    "save and close",
                    "close without saving",
                ),
                Pending::Open(path) => (
                    format!("opening {}", path.display()),
                    "save, then open",
                    "open without saving",
                ),
                Pending::New => (
                    "starting a new scene".to_owned(),
                    "save, then start anew",
                    "start anew without saving",
                ),
            };
            (
                "unsaved changes",
                format!("{file} has unsaved changes. Save them before {before}?"),
                Some(accept),
                Some(discard),
            )
        }
        Prompt::Recovery { path, .. } => (
            "unsaved edits found",
            format!(
                "{} holds edits that were never saved (the viewer closed or was killed). Restore them?",
                path.display()
            ),
            Some("restore"),
            Some("delete them"),
        ),
        Prompt::Failed { message } => ("could not open the file", message.clone(), None, None),
    };
    egui::Modal::new(egui::Id::unique("splinescope-prompt")).show(ctx, |ui| {
        ui.set_max_width(480.0);
        ui.heading(title);
        ui.label(text);
        ui.horizontal(|ui| {
            if let Some(accept) = accept
                && ui.button(accept).clicked()
            {
                actions.answer = Some(Answer::Accept);
            }
            if let Some(discard) = discard
                && ui.button(discard).clicked()
            {
                actions.answer = Some(Answer::Discard);
            }
            let cancel = if accept.is_some() { "cancel" } else { "OK" };
            if ui.button(cancel).on_hover_text("Esc").clicked() {
                actions.answer = Some(Answer::Cancel);
            }
        });
    });
}

/// The open or save-as dialog (drawn in egui: no desktop portal needed). Clicking a
/// directory enters it, clicking a file takes its name, double-clicking a file or
/// pressing Enter in the name field confirms, Esc cancels.
pub(crate) fn file_dialog(ctx: &egui::Context, dialog: &mut FileDialog, actions: &mut Actions) {
    let (title, verb) = match dialog.mode {
        DialogMode::Open => ("open a scene", "open"),
        DialogMode::SaveAs => ("save the scene as", "save"),
        DialogMode::Export => ("export the view as a figure (.svg or .pdf)", "export"),
    };
    egui::Modal::new(egui::Id::unique("splinescope-file-dialog")).show(ctx, |ui| {
        ui.set_width(460.0);
        ui.heading(title);
        ui.horizontal(|ui| {
            if ui
                .button("up")
                .on_hover_text("the parent directory")
                .clicked()
            {
                dialog.up();
            }
            ui.label(dialog.dir.display().to_string());
        });
        let mut picked = None;
        egui::ScrollArea::vertical()
            .id_salt("files")
            .max_height(260.0)
            .auto_shrink([false, true])
            .show(ui, |ui| {
                if dialog.entries.is_empty() {
                    ui.small("no scene (.json) or SVG (.svg) files, or directories, here");
                }
                for (i, entry) in dialog.entries.iter().enumerate() {
                    let label = if entry.is_dir {
                        format!("{}/", entry.name)
                    } else {
                        entry.name.clone()
                    };
                    let chosen = !entry.is_dir && entry.name == dialog.name;
                    let row = ui.add(egui::Button::selectable(chosen, label));
                    if row.clicked() {
                        picked = Some((i, false));
                    }
                    if row.double_clicked() && !entry.is_dir {
                        picked = Some((i, true));
                    }
                }
            });
        if let Some((i, confirm)) = picked {
            dialog.pick(i);
            if confirm {
                actions.file = Some(FileAction::ConfirmDialog);
            }
        }
        ui.horizontal(|ui| {
            ui.label("file");
            let mut output = egui::TextEdit::singleline(&mut dialog.name)
                .desired_width(320.0)
                .hint_text("name.json, or a path")
                .show(ui);
            if std::mem::take(&mut dialog.focus_name) {
                // The proposed name's stem is selected, so typing replaces it and keeps
                // the extension.
                let stem = dialog
                    .name
                    .rfind('.')
                    .filter(|&i| i > 0)
                    .unwrap_or(dialog.name.len());
                let stem = dialog.name[..stem].chars().count();
                output
                    .state
                    .cursor
                    .set_char_range(Some(egui::text_selection::CCursorRange::two(
                        egui::text::CCursor::new(0),
                        egui::text::CCursor::new(stem),
                    )));
                output.state.store(ui.ctx(), output.response.id);
                output.response.request_focus();
            }
            let field = output.response.response;
            if field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)) {
                actions.file = Some(FileAction::ConfirmDialog);
            }
        });
        ui.add_space(2.0);
        ui.colored_label(WARNING, dialog.error.clone().unwrap_or_default());
        ui.horizontal(|ui| {
            if ui.button(verb).on_hover_text("Enter").clicked() {
                actions.file = Some(FileAction::ConfirmDialog);
            }
            if ui.button("cancel").on_hover_text("Esc").clicked()
                || ui.input(|i| i.key_pressed(egui::Key::Escape))
            {
                actions.file = Some(FileAction::CancelDialog);
            }
        });
    });
}
