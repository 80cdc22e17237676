//! The viewer's side panel (egui).

use std::collections::VecDeque;
use std::time::Instant;

use glam::DVec3;

use crate::camera::Camera;
use crate::geom::{BezierSegment, Control, ControlKind, ControlValue, Lower, ParamCurve};
use crate::scene::{Scene, SceneCurve};

use super::edit::{Editor, Hit};
use super::files::{DialogMode, FileDialog};
use super::interaction::{Answer, Input, Interaction, Pending, Prompt, Template};

/// The panel's default width in points.
pub(crate) const PANEL_WIDTH_POINTS: f64 = 260.0;
/// The panel lists at most this many curves (stress scenes have millions).
const LISTED_CURVES: usize = 200;

/// One listed curve's label and hover text, computed once per scene (not per frame).
pub(crate) struct CurveSummary {
    /// The curve's name with its live parameters (the canvas label).
    pub name: String,
    /// `index: name` (the list row).
    pub label: String,
    pub details: String,
    pub color: egui::Color32,
}

/// Summaries of the first curves of `scene` (the panel lists at most that many).
pub(crate) fn summarize(scene: &Scene) -> Vec<CurveSummary> {
    scene
        .curves
        .iter()
        .take(LISTED_CURVES)
        .enumerate()
        .map(|(i, c)| summarize_curve(i, c))
        .collect()
}

/// Refreshes the summaries of the `changed` curves (edits change curves in place; the
/// others keep theirs), with the lowerings in `lowered` where the caller has them.
pub(crate) fn refresh(
    summaries: &mut [CurveSummary],
    scene: &Scene,
    changed: &[usize],
    lowered: &[(usize, Vec<BezierSegment>)],
) {
    for &i in changed {
        if let Some(slot) = summaries.get_mut(i) {
            *slot = match lowered.iter().find(|(c, _)| *c == i) {
                Some((_, segments)) => summarize_lowered(i, &scene.curves[i], segments),
                None => summarize_curve(i, &scene.curves[i]),
            };
        }
    }
}

fn summarize_curve(i: usize, c: &SceneCurve) -> CurveSummary {
    summarize_lowered(i, c, &c.curve.lower())
}

fn summarize_lowered(i: usize, c: &SceneCurve, segments: &[BezierSegment]) -> CurveSummary {
    let degree = crate::geom::max_degree(segments);
    let (a, b) = c.curve.domain();
    let [r, g, bl, _] = c.style.color.0.map(|v| (v * 255.0).round() as u8);
    let name = label(c);
    CurveSummary {
        label: format!("{i}: {name}"),
        name,
        details: format!(
            "{} · domain [{a}, {b}] · {} segment(s), degree ≤ {degree}",
            c.curve.family(),
            segments.len()
        ),
        color: egui::Color32::from_rgb(r, g, bl),
    }
}

/// How many curves of each family `scene` holds, with their control point counts:
/// `bezier × 10000 (4 points each)`.
fn family_counts(scene: &Scene) -> String {
    let mut counts: Vec<(&'static str, usize, usize, usize)> = Vec::new();
    for c in &scene.curves {
        let points = c.curve.control_points().len();
        match counts.iter_mut().find(|(f, ..)| *f == c.curve.family()) {
            Some((_, n, lo, hi)) => {
                *n += 1;
                *lo = (*lo).min(points);
                *hi = (*hi).max(points);
            }
            None => counts.push((c.curve.family(), 1, points, points)),
        }
    }
    counts
        .iter()
        .map(|(f, n, lo, hi)| {
            if lo == hi {
                format!("{f} × {n} ({lo} points each)")
            } else {
                format!("{f} × {n} ({lo} to {hi} points)")
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// A curve's name (or family) with its shape parameters as they are now, so that the
/// label never goes stale when they are edited.
fn label(c: &SceneCurve) -> String {
    c.label()
}

/// What the panel and the canvas overlay need to know of the scene, derived when it
/// changes (not every frame: both walk every curve).
pub(crate) struct SceneFacts {
    /// Every point has z = 0 (no z fields, 2D coordinates).
    pub planar: bool,
    /// The 3D axis triad to label (empty in planar scenes).
    pub axes: Vec<crate::scene::draw::Axis>,
    /// What the scene is made of, when it has more curves than the panel lists
    /// ([`family_counts`]); empty otherwise.
    pub families: String,
}

impl SceneFacts {
    pub fn of(scene: &Scene) -> SceneFacts {
        let planar = scene.is_planar();
        SceneFacts {
            families: if scene.curves.len() > LISTED_CURVES {
                family_counts(scene)
            } else {
                String::new()
            },
            planar,
            axes: if planar {
                Vec::new()
            } else {
                crate::scene::draw::axis_triad(scene).to_vec()
            },
        }
    }
}

/// What the panel and the canvas overlay show of the scene (its listed curves and its
/// facts), brought up to date only when the scene changes.
pub(crate) struct SceneDigest {
    pub summaries: Vec<CurveSummary>,
    pub facts: SceneFacts,
}

impl SceneDigest {
    pub fn of(scene: &Scene) -> SceneDigest {
        SceneDigest {
            summaries: summarize(scene),
            facts: SceneFacts::of(scene),
        }
    }

    /// Follows the editor's `changes` of `scene` (a changed list is summarised anew,
    /// curves changed in place are refreshed, from `lowered` where it holds their
    /// lowering; nothing is done when nothing changed).
    pub fn update(
        &mut self,
        scene: &Scene,
        changes: &super::edit::Changes,
        lowered: &[(usize, Vec<BezierSegment>)],
    ) {
        if changes.is_empty() {
            return;
        }
        self.facts = SceneFacts::of(scene);
        if changes.list {
            self.summaries = summarize(scene);
        } else {
            refresh(&mut self.summaries, scene, &changes.curves, lowered);
        }
    }
}

/// What the panel shows.
pub(crate) struct PanelInfo<'a> {
    pub digest: &'a SceneDigest,
    pub adapter: &'a str,
    pub fps: f64,
    pub samples_per_frame: u64,
    /// Whether the sample buffers capped a recent frame.
    pub capped: bool,
    /// GPU milliseconds of a recent frame per stage (count, scan, tessellate, draw).
    pub stage_ms: Option<[f64; 4]>,
    /// Why control polygons and points cannot be shown, when they cannot.
    pub overlays_locked: Option<&'static str>,
    pub camera: &'a Camera,
    /// Stress solving: curves re-solved per frame and the last batch's milliseconds.
    pub solving: Option<(usize, f64)>,
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

/// Frames per second over the last second.
pub(crate) struct FpsCounter {
    stamps: VecDeque<Instant>,
}

impl FpsCounter {
    pub fn new(now: Instant) -> FpsCounter {
        FpsCounter {
            stamps: VecDeque::from([now]),
        }
    }

    pub fn tick(&mut self, now: Instant) {
        self.stamps.push_back(now);
        while self.stamps.len() > 2 && now.duration_since(self.stamps[0]).as_secs_f64() > 1.0 {
            self.stamps.pop_front();
        }
    }

    pub fn fps(&self) -> f64 {
        let (Some(first), Some(last)) = (self.stamps.front(), self.stamps.back()) else {
            return 0.0;
        };
        let span = last.duration_since(*first).as_secs_f64();
        if span > 0.0 {
            (self.stamps.len() - 1) as f64 / span
        } else {
            0.0
        }
    }
}

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
            let scene = editor.scene();
            ui.heading(scene.name.as_deref().unwrap_or("splinescope"));
            ui.label(format!(
                "{} curve(s) · {} samples/frame · {:.1} fps",
                scene.curves.len(),
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
            if let Some([count, scan, tessellate, draw]) = info.stage_ms {
                ui.small(format!(
                    "GPU ms: count {count:.2} · scan {scan:.2} · tessellate {tessellate:.2} · draw {draw:.2}"
                ));
            }
            if let Some((curves, ms)) = info.solving {
                ui.label(format!(
                    "re-solving {curves} curves per frame: {ms:.2} ms ({:.1} M solves/s)",
                    curves as f64 / (ms.max(1e-6) * 1e3)
                ));
            }
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

/// The file menu (new, open, recent, save, save as) and the file's name with `*` when
/// it has unsaved changes.
fn file_row(
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

/// Carries out what the panel, the context menu, the prompt and the file dialog asked
/// for this frame.
pub(crate) fn apply(model: &mut Interaction, actions: Actions) {
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
    if model.prompt.is_none()
        && let Some(dialog) = model.dialog.as_mut()
    {
        file_dialog(ui.ctx(), dialog, actions);
    }
    width
}

/// Undo/redo/save, adding curves, the selected curve with its points and its family's
/// controls.
fn edit_section(ui: &mut egui::Ui, editor: &mut Editor, actions: &mut Actions, planar: bool) {
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
fn refusal_note(ui: &mut egui::Ui, editor: &Editor, index: usize, field: &str) {
    if let Some(r) = &editor.refusal
        && r.curve == index
        && r.field == field
    {
        ui.colored_label(WARNING, format!("refused: {}", r.text));
    }
}

/// Draws one of a family's controls; the value the user gave, if any, and whether it
/// was typed or clicked (complete) rather than dragged (continuing).
fn control_widget(
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

/// Whether a number widget's change stands: a drag always, a typed value unless Esc was
/// pressed this frame or the one before. egui gives a number field's typed text to the
/// value one frame after the field loses the keyboard, and Esc makes it lose the
/// keyboard: a typed change that arrives then is the text Esc was meant to cancel.
/// [`note_escape`] records the frame.
fn accepted(ctx: &egui::Context, response: &egui::Response) -> bool {
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

fn escape_id() -> egui::Id {
    egui::Id::unique("splinescope-escape-frame")
}

/// The colour of the selection and hover highlights: a magenta no palette colour is
/// near, so a selected curve is never mistaken for an orange one.
pub(crate) const SELECTION: egui::Color32 = egui::Color32::from_rgb(230, 0, 200);

/// The colour of warnings (a group outside its variation-diminishing range).
const WARNING: egui::Color32 = egui::Color32::from_rgb(200, 40, 40);

/// Marks `band` (a part of the slider's `range`) as a green strip under the slider's
/// rail, where the handle's centre would stand at the band's ends.
fn paint_band(ui: &egui::Ui, response: &egui::Response, range: (f64, f64), band: (f64, f64)) {
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
fn vector_row(ui: &mut egui::Ui, label: &str, v: &mut DVec3, planar: bool) -> bool {
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

/// Everything drawn over the canvas: the highlight of the selected, hovered and dragged
/// curve and point, the pointer's coordinates, labels of the 3D axes, the context menu,
/// the help window and the open prompt.
pub(crate) fn canvas(
    ui: &mut egui::Ui,
    model: &Interaction,
    digest: &SceneDigest,
    actions: &mut Actions,
) {
    let facts = &digest.facts;
    let ctx = ui.ctx().clone();
    let ppp = f64::from(ctx.pixels_per_point());
    let to_pos = |p: glam::DVec2| egui::pos2((p.x / ppp) as f32, (p.y / ppp) as f32);
    let pixel = |w: DVec3| model.camera.pixel_from_world(w, model.viewport).map(to_pos);
    let painter = ctx.layer_painter(egui::LayerId::background());
    let scene = model.scene();
    let accent = SELECTION;
    let curve_line = |index: usize, stroke: egui::Stroke| {
        let Some(sc) = scene.curves.get(index) else {
            return;
        };
        let (a, b) = sc.curve.domain();
        let points: Vec<egui::Pos2> = (0..=256)
            .filter_map(|j| pixel(sc.curve.eval(a + (b - a) * f64::from(j) / 256.0)))
            .collect();
        painter.add(egui::Shape::line(points, stroke));
    };
    let ring = |at: DVec3, radius: f32, color: egui::Color32, fill: bool| {
        if let Some(p) = pixel(at) {
            if fill {
                painter.circle_filled(p, radius, color);
            } else {
                painter.circle_stroke(p, radius, egui::Stroke::new(2.0, color));
            }
        }
    };
    if let Some(index) = model.editor.selected {
        curve_line(index, egui::Stroke::new(7.0, accent.gamma_multiply(0.35)));
        if let Some(point) = model.editor.selected_point
            && let Some(&p) = scene
                .curves
                .get(index)
                .and_then(|c| c.curve.control_points().get(point))
        {
            // Filled while it is being dragged.
            ring(p, 8.0, accent, model.is_editing());
        }
    }
    let mut status = String::new();
    match model.hovered {
        Some(Hit::Point { curve, index, at }) if !model.is_editing() => {
            ring(at, 9.0, accent.gamma_multiply(0.8), false);
            ctx.set_cursor_icon(egui::CursorIcon::Grab);
            let name = scene
                .curves
                .get(curve)
                .map(SceneCurve::label)
                .unwrap_or_default();
            status = format!(
                "curves[{curve}] {name:?} point {index} = {}",
                coords(at, facts.planar)
            );
        }
        Some(Hit::Curve { curve, t, at }) if !model.is_editing() => {
            if model.editor.selected != Some(curve) {
                curve_line(curve, egui::Stroke::new(5.0, accent.gamma_multiply(0.2)));
            }
            if model.editor.can_pull(curve) {
                ctx.set_cursor_icon(egui::CursorIcon::Grab);
            } else {
                ctx.set_cursor_icon(egui::CursorIcon::PointingHand);
            }
            let name = scene
                .curves
                .get(curve)
                .map(SceneCurve::label)
                .unwrap_or_default();
            status = format!(
                "curves[{curve}] {name:?} at t = {t:.4}: {}",
                coords(at, facts.planar)
            );
        }
        _ => {}
    }
    if model.is_editing() {
        ctx.set_cursor_icon(egui::CursorIcon::Grabbing);
    }
    // Over the panel or a menu the pointer is not on the canvas: no readout.
    if status.is_empty() && !model.pointer_over_ui() {
        status = match model.camera {
            Camera::Ortho2d(_) => format!("pointer {}", coords(model.cursor_world(), true)),
            Camera::Orbit3d(_) => String::new(),
        };
    }
    if !status.is_empty() {
        let rect = ctx.content_rect();
        painter.text(
            rect.right_bottom() - egui::vec2(8.0, 6.0),
            egui::Align2::RIGHT_BOTTOM,
            status,
            egui::FontId::monospace(12.0),
            ui.visuals().text_color(),
        );
    }
    if model.toggles.show_labels && scene.curves.len() <= LISTED_CURVES {
        let [r, g, b, _] = scene.background.0.map(|v| (v * 255.0).round() as u8);
        curve_labels(
            &painter,
            scene,
            &digest.summaries,
            &pixel,
            egui::Color32::from_rgb(r, g, b),
        );
    }
    // Labels just past the ends of the 3D axis triad.
    for axis in &facts.axes {
        let [r, g, b, _] = axis.color.0.map(|v| (v * 255.0).round() as u8);
        let color = egui::Color32::from_rgb(r, g, b);
        if let Some(p) = pixel(axis.from + (axis.to - axis.from) * 1.08) {
            painter.text(
                p,
                egui::Align2::CENTER_CENTER,
                axis.name,
                egui::FontId::proportional(14.0),
                color,
            );
        }
    }
    if let Some(at) = model.context_menu {
        context_menu(&ctx, model, to_pos(at), actions);
    }
    if model.show_help {
        help_window(&ctx);
    }
    if let Some(prompt) = &model.prompt {
        prompt_modal(&ctx, model, prompt, actions);
    }
}

/// Each curve's name (and live parameters) beside its middle point, in its colour on a
/// translucent plate of the scene's background, moved to another side of the point when it
/// would cover a label already placed or leave the window (and left out when no side
/// will do).
fn curve_labels(
    painter: &egui::Painter,
    scene: &Scene,
    summaries: &[CurveSummary],
    pixel: &dyn Fn(DVec3) -> Option<egui::Pos2>,
    plate: egui::Color32,
) {
    let mut placed: Vec<egui::Rect> = Vec::new();
    for (sc, summary) in scene.curves.iter().zip(summaries) {
        let (a, b) = sc.curve.domain();
        let Some(at) = pixel(sc.curve.eval(0.5 * (a + b))) else {
            continue;
        };
        let [r, g, bl, _] = sc.style.color.0.map(|v| (v * 255.0).round() as u8);
        let galley = painter.layout_no_wrap(
            summary.name.clone(),
            egui::FontId::proportional(12.0),
            egui::Color32::from_rgb(r, g, bl),
        );
        let size = galley.size();
        let sides = [
            egui::vec2(8.0, -8.0 - size.y),
            egui::vec2(8.0, 8.0),
            egui::vec2(-8.0 - size.x, -8.0 - size.y),
            egui::vec2(-8.0 - size.x, 8.0),
        ];
        let screen = painter.clip_rect();
        let Some(rect) = sides
            .iter()
            .map(|d| egui::Rect::from_min_size(at + *d, size).expand(2.0))
            .find(|r| screen.contains_rect(*r) && placed.iter().all(|p| !p.intersects(*r)))
        else {
            continue;
        };
        painter.rect_filled(rect, 3.0, plate.gamma_multiply(0.75));
        painter.galley(
            rect.min + egui::vec2(2.0, 2.0),
            galley,
            egui::Color32::WHITE,
        );
        placed.push(rect);
    }
}

/// The right-click menu at `at` (points): add a curve there, insert or delete a point,
/// duplicate.
fn context_menu(ctx: &egui::Context, model: &Interaction, at: egui::Pos2, actions: &mut Actions) {
    egui::Area::new(egui::Id::unique("splinescope-context-menu"))
        .fixed_pos(at)
        .order(egui::Order::Foreground)
        .show(ctx, |ui| {
            egui::Frame::menu(ui.style()).show(ui, |ui| {
                ui.menu_button("add curve here", |ui| {
                    for t in Template::all() {
                        if ui.button(t.label()).clicked() {
                            actions.add_at_menu = Some(t);
                        }
                    }
                });
                let selected = model.editor.selected.is_some();
                if ui
                    .add_enabled(selected, egui::Button::new("insert point here (I)"))
                    .clicked()
                {
                    actions.menu = Some(MenuItem::InsertPoint);
                }
                let what = if model.editor.selected_point.is_some() {
                    "delete point (Delete)"
                } else {
                    "delete curve (Delete)"
                };
                if ui.add_enabled(selected, egui::Button::new(what)).clicked() {
                    actions.menu = Some(MenuItem::DeleteSelection);
                }
                if ui
                    .add_enabled(selected, egui::Button::new("duplicate curve (Ctrl+D)"))
                    .clicked()
                {
                    actions.menu = Some(MenuItem::Duplicate);
                }
            });
        });
}

/// The list of shortcuts ([`SHORTCUTS`]) in a window.
fn help_window(ctx: &egui::Context) {
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
fn prompt_modal(ctx: &egui::Context, model: &Interaction, prompt: &Prompt, actions: &mut Actions) {
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
                    ui.small("no scene files (.json) or directories here");
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

/// A point as the status line shows it (no z in planar scenes).
fn coords(p: DVec3, planar: bool) -> String {
    if planar {
        format!("({:.4}, {:.4})", p.x, p.y)
    } else {
        format!("({:.4}, {:.4}, {:.4})", p.x, p.y, p.z)
    }
}

#[cfg(test)]
mod tests {
    use super::{refresh, summarize};
    use crate::geom::{Bezier, Curve, Lower};
    use glam::DVec3;

    #[test]
    fn refresh_matches_a_full_summary_after_an_edit() {
        let mut scene = crate::scene::gallery::gallery();
        let mut summaries = summarize(&scene);
        // Replace curve 1 by a line: its family, segment count and degree all change.
        scene.curves[1].curve = Curve::Bezier(Bezier::new(vec![DVec3::ZERO, DVec3::X]));
        scene.curves[1].name = None;
        let before_0 = summaries[0].details.clone();
        refresh(&mut summaries, &scene, &[1], &[]);
        let full = summarize(&scene);
        assert_eq!(summaries.len(), full.len());
        for (got, want) in summaries.iter().zip(&full) {
            assert_eq!(got.label, want.label);
            assert_eq!(got.details, want.details);
            assert_eq!(got.color, want.color);
        }
        assert_eq!(summaries[0].details, before_0);
        assert!(
            summaries[1].details.contains("1 segment(s), degree ≤ 1"),
            "{}",
            summaries[1].details
        );
        // Given the curve's lowering (as a drag has it), the summary is the same.
        let mut given = summarize(&crate::scene::gallery::gallery());
        refresh(
            &mut given,
            &scene,
            &[1],
            &[(1, scene.curves[1].curve.lower())],
        );
        assert_eq!(given[1].details, full[1].details);
        assert_eq!(given[1].label, full[1].label);
    }

    #[test]
    fn labels_show_the_parameters_as_they_are_now() {
        use crate::edit::Editor;
        use crate::geom::{ControlValue, Nubmp};
        let scene = crate::scene::gallery::gallery();
        let i = scene
            .curves
            .iter()
            .position(|c| matches!(c.curve, Curve::Modified(_)))
            .unwrap();
        let mut e = Editor::new(scene, None);
        let label = |e: &Editor| summarize(e.scene())[i].label.clone();
        assert!(label(&e).contains("t* = 0.3,"), "{}", label(&e));
        let control = e.scene().curves[i]
            .curve
            .controls()
            .into_iter()
            .find(|c| c.label == "t*")
            .unwrap();
        e.apply_control(i, &control, ControlValue::Number(0.45));
        e.finish();
        let now = label(&e);
        assert!(now.contains("t* = 0.45,") && !now.contains("0.3"), "{now}");
        // A NUBMP label lists the parameters that differ from the standard curve's.
        let pts: Vec<DVec3> = (0..7).map(|k| DVec3::new(f64::from(k), 0.0, 0.0)).collect();
        let knots = vec![0., 0., 0., 0., 0.3, 0.5, 0.89, 1., 1., 1., 1.];
        let mut n = Nubmp::try_new(pts, knots, 4).unwrap();
        assert_eq!(Curve::Nubmp(n.clone()).parameter_text(), None);
        let g = n.groups()[4].clone();
        n.set_parameter(4, g.members[0], 0.2, *g.members.last().unwrap())
            .unwrap();
        let text = Curve::Nubmp(n).parameter_text().unwrap();
        assert!(
            text.contains(&format!("a^{}_4 = 0.2", g.members[0])),
            "{text}"
        );
    }
}
