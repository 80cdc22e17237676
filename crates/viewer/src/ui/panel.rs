//! The side panel: the scene's curves, the selected curve's editing section and its controls.

use glam::DVec3;

use crate::digest::{LISTED_CURVES, label};
use splinescope_encoding::camera::Camera;
use splinescope_present::{Control, ControlKind, ControlValue, Present};

use crate::edit::Editor;
use crate::interaction::{Interaction, Template};

use super::actions::*;
/// Draws the panel; returns its width in points (0 when hidden).
pub(crate) fn panel(
    ui: &mut egui::Ui,
    info: &PanelInfo<'_>,
    model: &mut Interaction,
    actions: &mut Actions,
) -> f32 {
    let editable = model.editable;
    let Interaction {
        tolerance_px,
        toggles,
        editor,
        recent,
        shape,
        ..
    } = model;
    if !toggles.show_panel {
        return 0.0;
    }
    let response = egui::Panel::left("splinescope-panel")
        .default_size(PANEL_WIDTH_POINTS as f32)
        .max_size(PANEL_WIDTH_POINTS as f32 * 1.6)
        .resizable(true)
        .show(ui, |ui| {
            header(ui, info, editor.scene());
            ui.separator();
            let mut tolerance = *tolerance_px;
            let response = ui
                .add(
                    egui::Slider::new(&mut tolerance, 0.05..=8.0)
                        .logarithmic(true)
                        .update_while_editing(false)
                        .text("tolerance (px)"),
                )
                .on_hover_text("the largest distance between a drawn polyline and its curve");
            if accepted(ui.ctx(), &response) {
                *tolerance_px = tolerance;
            }
            match info.overlays_locked {
                None => {
                    ui.checkbox(&mut toggles.show_polygons, "control polygons (P)");
                    ui.checkbox(&mut toggles.show_points, "control points (C)");
                }
                Some(reason) => {
                    ui.add_enabled(
                        false,
                        egui::Checkbox::new(&mut toggles.show_polygons, "control polygons (P)"),
                    )
                    .on_disabled_hover_text(reason);
                    ui.add_enabled(
                        false,
                        egui::Checkbox::new(&mut toggles.show_points, "control points (C)"),
                    )
                    .on_disabled_hover_text(reason);
                    ui.small(reason);
                }
            }
            if ui.button("fit (F)").clicked() {
                actions.fit = true;
            }
            super::shape::shape_section(ui, info, shape, editor, actions);
            ui.small(match info.camera {
                Camera::Ortho2d(_) => "2D · drag: pan · wheel: zoom",
                Camera::Orbit3d(_) => "3D · left drag: orbit · right drag: pan · wheel: zoom",
            });
            ui.small("F1 or ? lists every shortcut · H hides this panel");
            ui.separator();
            if editable {
                file_row(ui, editor, &recent.paths, actions);
                edit_section(ui, editor, actions, info.digest.facts.planar);
                ui.separator();
            }
            let total = editor.scene().curves.len();
            if total > LISTED_CURVES {
                // Thousands of rows say nothing: what the scene is made of, and the
                // selected curve.
                ui.label(format!("{total} curves: {}", info.digest.facts.families));
                ui.small("] / [ select the next / previous curve; click one on the canvas");
            }
            let chosen = editor.selected;
            egui::ScrollArea::vertical().show(ui, |ui| {
                let rows = info
                    .digest
                    .summaries
                    .iter()
                    .enumerate()
                    .filter(|(i, _)| total <= LISTED_CURVES || chosen == Some(*i));
                for (i, c) in rows {
                    let selected = editor.selected == Some(i);
                    let row = ui
                        .horizontal(|ui| {
                            let (rect, _) = ui
                                .allocate_exact_size(egui::vec2(10.0, 10.0), egui::Sense::hover());
                            ui.painter().rect_filled(rect, 2.0, c.color);
                            ui.add(egui::Button::selectable(selected, &c.label).truncate())
                        })
                        .inner
                        .on_hover_text(format!("{}\n{}", c.label, c.details));
                    if row.clicked() && editable {
                        editor.finish();
                        editor.selected = Some(i);
                    }
                }
            });
        });
    response.response.rect.width()
}

/// The scene's name and what the frame costs: curves, samples, fps, the adapter, GPU
/// stage times and the re-solve rate while solving.
fn header(ui: &mut egui::Ui, info: &PanelInfo<'_>, scene: &splinescope_scene::format::Scene) {
    ui.heading(scene.name.as_deref().unwrap_or("splinescope"));
    ui.label(format!(
        "{} curve(s){} · {} samples/frame · {:.1} fps",
        scene.curves.len(),
        scene
            .unit
            .as_deref()
            .map(|u| format!(" in {u}"))
            .unwrap_or_default(),
        info.samples_per_frame,
        info.fps
    ));
    if info.capped {
        ui.colored_label(
            WARNING,
            "sample buffer full: curves drawn coarser than the tolerance",
        );
    }
    ui.small(info.adapter);
    if let Some([count, scan, tessellate, draw, comb, raster]) = info.stage_ms {
        // The comb's stage is an empty pass while no comb is drawn.
        let comb = if comb >= 0.005 {
            format!(" · comb {comb:.2}")
        } else {
            String::new()
        };
        ui.small(format!(
            "GPU ms: count {count:.2} · scan {scan:.2} · tessellate {tessellate:.2}{comb} · raster {raster:.2} · draw {draw:.2}"
        ));
    }
    if let Some((curves, ms)) = info.solving {
        ui.label(format!(
            "re-solving {curves} curves per frame: {ms:.2} ms ({:.1} M solves/s)",
            curves as f64 / (ms.max(1e-6) * 1e3)
        ));
    }
}

/// The selected control point's coordinates (typed) and its delete button, or how to
/// select or insert one.
fn point_row(
    ui: &mut egui::Ui,
    editor: &mut Editor,
    index: usize,
    sc: &splinescope_scene::format::SceneCurve,
    planar: bool,
) {
    if let Some(point) = editor.selected_point
        && let Some(&p) = sc.curve.control_points().get(point)
    {
        let field = format!("point {point}");
        ui.horizontal(|ui| {
            ui.label(&field);
            let mut v = p;
            if vector_row(ui, "", &mut v, planar)
                && let Err(e) = editor.set_point(index, point, v)
            {
                editor.refuse(index, &field, e.to_string());
            }
        });
        refusal_note(ui, editor, index, &field);
        if ui
            .button("delete point")
            .on_hover_text(if sc.curve.inserts_by_knot() {
                "Delete: remove this point with the knot nearest it"
            } else {
                "Delete: remove this point"
            })
            .clicked()
        {
            if let Err(e) = editor.delete_point(index, point) {
                editor.message = Some(e.to_string());
            }
            editor.selected_point = None;
        }
    } else {
        ui.small(if sc.curve.inserts_by_knot() {
            "I inserts a knot at the curve point nearest the pointer (the shape stays); click a point to type its coordinates."
        } else {
            "I inserts a point on the control polygon at the pointer; click a point to type its coordinates."
        });
    }
}

/// The file menu (new, open, recent, save, save as) and the file's name with `*` when
/// it has unsaved changes.
pub(crate) fn file_row(
    ui: &mut egui::Ui,
    editor: &Editor,
    recent: &[std::path::PathBuf],
    actions: &mut Actions,
) {
    ui.horizontal(|ui| {
        ui.menu_button("file", |ui| {
            let item = |ui: &mut egui::Ui, label: &str, keys: &str| {
                ui.add(egui::Button::new(label).shortcut_text(keys))
                    .clicked()
            };
            if item(ui, "new", "Ctrl+N") {
                actions.file = Some(FileAction::New);
            }
            if item(ui, "open…", "Ctrl+O") {
                actions.file = Some(FileAction::Open);
            }
            ui.menu_button("open recent", |ui| {
                if recent.is_empty() {
                    ui.small("no recent files");
                }
                for path in recent {
                    if ui.button(path.display().to_string()).clicked() {
                        actions.file = Some(FileAction::OpenRecent(path.clone()));
                    }
                }
            });
            if item(ui, "save", "Ctrl+S") {
                actions.save = true;
            }
            if item(ui, "save as…", "Ctrl+Shift+S") {
                actions.file = Some(FileAction::SaveAs);
            }
            if ui
                .button("export view…")
                .on_hover_text("what is on screen as an SVG or PDF figure: exact curves, labels")
                .clicked()
            {
                actions.file = Some(FileAction::Export);
            }
        })
        .response
        .on_hover_text(
            "new, open (also: drop a scene file on the window), recent, save, save as, export view",
        );
        let name = editor
            .path()
            .map_or_else(|| "untitled".to_owned(), |p| p.display().to_string());
        let star = if editor.is_dirty() { "*" } else { "" };
        ui.label(format!("{name}{star}"))
            .on_hover_text("the scene's file (* = unsaved changes)");
    });
}

/// Undo/redo/save, adding curves, the selected curve with its points and its family's
/// controls.
pub(crate) fn edit_section(
    ui: &mut egui::Ui,
    editor: &mut Editor,
    actions: &mut Actions,
    planar: bool,
) {
    let (undo, redo) = editor.history_len();
    ui.horizontal(|ui| {
        if ui
            .add_enabled(undo > 0, egui::Button::new(format!("undo ({undo})")))
            .on_hover_text("Ctrl+Z: undo the last edit")
            .clicked()
        {
            editor.undo();
        }
        if ui
            .add_enabled(redo > 0, egui::Button::new(format!("redo ({redo})")))
            .on_hover_text("Ctrl+Shift+Z or Ctrl+Y: redo")
            .clicked()
        {
            editor.redo();
        }
        ui.menu_button("add curve…", |ui| {
            for t in Template::all() {
                if ui.button(t.label()).clicked() {
                    actions.add = Some(t);
                    ui.close();
                }
            }
        })
        .response
        .on_hover_text(
            "add a curve of any family at the centre of the view (right-click the canvas: at the pointer)",
        );
    });
    // A failure that must not be missed (a save that failed, an edit undone), in the
    // warning colour until dismissed or a save succeeds.
    if let Some(w) = editor.warning.clone() {
        ui.horizontal_wrapped(|ui| {
            ui.colored_label(WARNING, format!("⚠ {w}"));
            if ui.small_button("dismiss").clicked() {
                editor.warning = None;
            }
        });
    }
    // The message keeps its line even when empty, so the layout does not jump; a refusal
    // is shown in the warning colour (and again next to its field below).
    match (&editor.message, &editor.refusal) {
        (Some(m), Some(r)) if *m == r.text => {
            ui.colored_label(WARNING, m);
        }
        (m, _) => {
            ui.small(m.clone().unwrap_or_default());
        }
    }
    let Some(index) = editor.selected else {
        ui.small(
            "Click a curve to select it; drag a control point to move it, or a Bézier, rational Bézier or NURBS curve to pull it through the pointer.",
        );
        return;
    };
    let Some(sc) = editor.scene().curves.get(index).cloned() else {
        return;
    };
    ui.label(format!("{index}: {} ({})", label(&sc), sc.curve.family()));
    ui.small(sc.curve.summary());
    ui.horizontal(|ui| {
        if ui
            .button("duplicate")
            .on_hover_text("Ctrl+D: a copy of this curve, moved a little")
            .clicked()
        {
            actions.menu = Some(MenuItem::Duplicate);
        }
        if ui
            .button("delete curve")
            .on_hover_text("Delete (with no point selected): remove this curve")
            .clicked()
            && let Err(e) = editor.delete_curve(index)
        {
            editor.message = Some(e.to_string());
        }
    });
    point_row(ui, editor, index, &sc, planar);
    egui::ScrollArea::vertical()
        .id_salt("controls")
        .max_height(240.0)
        .show(ui, |ui| {
            for control in sc.curve.controls() {
                if let Some((value, typed)) = control_widget(ui, &control, planar) {
                    editor.apply_control(index, &control, value);
                    if typed {
                        // A typed value is an edit of its own (a slider drag ends on release).
                        editor.finish();
                    }
                }
                refusal_note(ui, editor, index, &control.label);
            }
        });
}

/// The refusal of a value given in `field` of curve `index`, in the warning colour,
/// right under the field (nothing when the last refusal was elsewhere).
pub(crate) fn refusal_note(ui: &mut egui::Ui, editor: &Editor, index: usize, field: &str) {
    if let Some(r) = &editor.refusal
        && r.curve == index
        && r.field == field
    {
        ui.colored_label(WARNING, format!("refused: {}", r.text));
    }
}

/// Draws one of a family's controls; the value the user gave, if any, and whether it
/// was typed or clicked (complete) rather than dragged (continuing).
pub(crate) fn control_widget(
    ui: &mut egui::Ui,
    control: &Control,
    planar: bool,
) -> Option<(ControlValue, bool)> {
    let hint = control.hint.as_deref().unwrap_or_default();
    match &control.kind {
        ControlKind::Note { warning } => {
            let color = if *warning {
                WARNING
            } else {
                ui.visuals().text_color()
            };
            ui.colored_label(color, &control.label);
            None
        }
        ControlKind::Number {
            value,
            range,
            bands,
        } => {
            let mut v = *value;
            // Typed values are not clamped and only given once complete (Enter or focus
            // lost): the family accepts or refuses them whole, with a message.
            let slider = egui::Slider::new(&mut v, range.0..=range.1)
                .clamping(egui::SliderClamping::Never)
                .update_while_editing(false)
                .text(&control.label);
            if !hint.is_empty() {
                let outside = !bands.is_empty()
                    && !bands.iter().any(|&(lo, hi)| lo <= *value && *value <= hi);
                if outside {
                    ui.colored_label(WARNING, egui::RichText::new(hint).small());
                } else {
                    ui.small(hint);
                }
            }
            let response = ui.add(slider).on_hover_text(if hint.is_empty() {
                "drag, or double-click the number to type a value"
            } else {
                hint
            });
            for band in bands {
                paint_band(ui, &response, *range, *band);
            }
            accepted(ui.ctx(), &response).then_some((ControlValue::Number(v), !response.dragged()))
        }
        ControlKind::Vector { value } => {
            let mut v = *value;
            vector_row(ui, &control.label, &mut v, planar)
                .then_some((ControlValue::Vector(v), true))
        }
        ControlKind::Toggle { value } => {
            let mut on = *value;
            ui.checkbox(&mut on, &control.label)
                .on_hover_text(hint)
                .changed()
                .then_some((ControlValue::Toggle(on), true))
        }
        ControlKind::Choice { options, selected } => {
            let mut choice = *selected;
            ui.horizontal(|ui| {
                ui.label(&control.label);
                for (i, option) in options.iter().enumerate() {
                    ui.radio_value(&mut choice, i, *option);
                }
            });
            (choice != *selected).then_some((ControlValue::Choice(choice), true))
        }
        ControlKind::Action => ui
            .button(&control.label)
            .on_hover_text(hint)
            .clicked()
            .then_some((ControlValue::Press, true)),
    }
}

/// Marks `band` (a part of the slider's `range`) as a green strip under the slider's
/// rail, where the handle's centre would stand at the band's ends.
pub(crate) fn paint_band(
    ui: &egui::Ui,
    response: &egui::Response,
    range: (f64, f64),
    band: (f64, f64),
) {
    let (lo, hi) = range;
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        return;
    }
    // The slider's own rect starts the response (the value field and the label follow);
    // its handle's centre runs over the rect's width less a handle radius at each end.
    let height = ui.spacing().interact_size.y;
    let width = ui.spacing().slider_width;
    let left = response.rect.left();
    let radius = height / 2.5;
    let x = |v: f64| {
        let f = ((v - lo) / (hi - lo)).clamp(0.0, 1.0) as f32;
        left + radius + f * (width - 2.0 * radius)
    };
    let bottom = response.rect.top() + height;
    let strip = egui::Rect::from_min_max(
        egui::pos2(x(band.0), bottom - 3.0),
        egui::pos2(x(band.1).max(x(band.0) + 1.0), bottom - 1.0),
    );
    ui.painter()
        .rect_filled(strip, 1.0, egui::Color32::from_rgb(40, 170, 70));
}

/// A row of drag values for a vector (no z field in a planar scene); whether it
/// changed. Typed values are given once complete.
pub(crate) fn vector_row(ui: &mut egui::Ui, label: &str, v: &mut DVec3, planar: bool) -> bool {
    ui.horizontal(|ui| {
        if !label.is_empty() {
            ui.label(label);
        }
        let field = |ui: &mut egui::Ui, x: &mut f64, prefix: &str| {
            let before = *x;
            let response = ui
                .add(
                    egui::DragValue::new(x)
                        .speed(0.01)
                        .update_while_editing(false)
                        .prefix(prefix),
                )
                .on_hover_text("drag, or click to type");
            if !accepted(ui.ctx(), &response) {
                // Unchanged, or typed text Esc dropped: the field shows the value again.
                *x = before;
                return false;
            }
            true
        };
        let mut changed = field(ui, &mut v.x, "x ");
        changed |= field(ui, &mut v.y, "y ");
        if !planar {
            changed |= field(ui, &mut v.z, "z ");
        }
        changed
    })
    .inner
}
