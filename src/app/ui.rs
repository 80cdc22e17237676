//! The viewer's side panel (egui).

use std::collections::VecDeque;
use std::time::Instant;

use glam::DVec3;

use crate::camera::Camera;
use crate::geom::{Control, ControlKind, ControlValue, Lower, ParamCurve};
use crate::scene::{Scene, SceneCurve};

use super::edit::Editor;
use super::interaction::Toggles;

/// The panel's default width in points.
pub(crate) const PANEL_WIDTH_POINTS: f64 = 260.0;
/// The panel lists at most this many curves (stress scenes have millions).
const LISTED_CURVES: usize = 200;

/// One listed curve's label and hover text, computed once per scene (not per frame).
pub(crate) struct CurveSummary {
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
/// others keep theirs).
pub(crate) fn refresh(summaries: &mut [CurveSummary], scene: &Scene, changed: &[usize]) {
    for &i in changed {
        if let Some(slot) = summaries.get_mut(i) {
            *slot = summarize_curve(i, &scene.curves[i]);
        }
    }
}

fn summarize_curve(i: usize, c: &SceneCurve) -> CurveSummary {
    let segments = c.curve.lower();
    let degree = segments
        .iter()
        .map(|s| s.bezier.degree())
        .max()
        .unwrap_or(0);
    let (a, b) = c.curve.domain();
    let [r, g, bl, _] = c.style.color.0.map(|v| (v * 255.0).round() as u8);
    CurveSummary {
        label: format!("{i}: {}", c.name.as_deref().unwrap_or(c.curve.family())),
        details: format!(
            "{} · domain [{a}, {b}] · {} segment(s), degree ≤ {degree}",
            c.curve.family(),
            segments.len()
        ),
        color: egui::Color32::from_rgb(r, g, bl),
    }
}

/// What the panel shows.
pub(crate) struct PanelInfo<'a> {
    pub summaries: &'a [CurveSummary],
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
    tolerance_px: &mut f64,
    toggles: &mut Toggles,
    editor: &mut Editor,
    editable: bool,
    actions: &mut Actions,
) -> f32 {
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
                    egui::Color32::from_rgb(200, 40, 40),
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
            ui.add(
                egui::Slider::new(tolerance_px, 0.05..=8.0)
                    .logarithmic(true)
                    .text("tolerance (px)"),
            )
            .on_hover_text("the largest distance between a drawn polyline and its curve");
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
            ui.small("H hides this panel · Esc quits");
            ui.separator();
            if editable {
                edit_section(ui, editor, actions);
                ui.separator();
            }
            egui::ScrollArea::vertical().show(ui, |ui| {
                for (i, c) in info.summaries.iter().enumerate() {
                    let selected = editor.selected == Some(i);
                    let row = ui
                        .horizontal(|ui| {
                            let (rect, _) = ui
                                .allocate_exact_size(egui::vec2(10.0, 10.0), egui::Sense::hover());
                            ui.painter().rect_filled(rect, 2.0, c.color);
                            ui.add(egui::Button::selectable(selected, &c.label).truncate())
                        })
                        .inner
                        .on_hover_text(&c.details);
                    if row.clicked() && editable {
                        editor.finish();
                        editor.selected = Some(i);
                    }
                }
                let total = editor.scene().curves.len();
                if total > LISTED_CURVES {
                    ui.small(format!("… and {} more", total - LISTED_CURVES));
                }
            });
        });
    response.response.rect.width()
}

/// Undo/redo/save, the selected curve and its family's controls.
fn edit_section(ui: &mut egui::Ui, editor: &mut Editor, actions: &mut Actions) {
    let (undo, redo) = editor.history_len();
    ui.horizontal(|ui| {
        if ui
            .add_enabled(undo > 0, egui::Button::new(format!("undo ({undo})")))
            .on_hover_text("Ctrl+Z")
            .clicked()
        {
            editor.undo();
        }
        if ui
            .add_enabled(redo > 0, egui::Button::new(format!("redo ({redo})")))
            .on_hover_text("Ctrl+Shift+Z")
            .clicked()
        {
            editor.redo();
        }
        let label = if editor.is_dirty() { "save*" } else { "save" };
        let target = editor
            .path()
            .map_or_else(String::new, |p| p.display().to_string());
        if ui
            .button(label)
            .on_hover_text(format!("Ctrl+S: write {target} (* = unsaved changes)"))
            .clicked()
        {
            actions.save = true;
        }
    });
    if let Some(m) = &editor.message {
        ui.small(m.clone());
    }
    let Some(index) = editor.selected else {
        ui.small(
            "Drag a control point to move it, or a Bézier curve to pull it through the pointer.",
        );
        return;
    };
    let sc = editor.scene().curves[index].clone();
    ui.label(format!(
        "{index}: {} ({})",
        sc.name.as_deref().unwrap_or("unnamed"),
        sc.curve.family()
    ));
    ui.small(sc.curve.summary());
    egui::ScrollArea::vertical()
        .id_salt("controls")
        .max_height(240.0)
        .show(ui, |ui| {
            for control in sc.curve.controls() {
                if let Some(value) = control_widget(ui, &control) {
                    editor.apply_control(index, &control, value);
                }
            }
        });
}

/// Draws one of a family's controls; the value the user gave, if any.
fn control_widget(ui: &mut egui::Ui, control: &Control) -> Option<ControlValue> {
    let hint = control.hint.as_deref().unwrap_or_default();
    match &control.kind {
        ControlKind::Note { warning } => {
            let color = if *warning {
                egui::Color32::from_rgb(200, 40, 40)
            } else {
                ui.visuals().text_color()
            };
            ui.colored_label(color, &control.label);
            None
        }
        ControlKind::Number { value, range } => {
            let mut v = *value;
            // Typed values are not clamped: the family refuses invalid ones, with a message.
            let slider = egui::Slider::new(&mut v, range.0..=range.1)
                .clamping(egui::SliderClamping::Never)
                .text(&control.label);
            if !hint.is_empty() {
                ui.small(hint);
            }
            ui.add(slider).changed().then_some(ControlValue::Number(v))
        }
        ControlKind::Vector { value } => {
            let mut v = *value;
            vector_row(ui, &control.label, &mut v).then_some(ControlValue::Vector(v))
        }
        ControlKind::Toggle { value } => {
            let mut on = *value;
            ui.checkbox(&mut on, &control.label)
                .on_hover_text(hint)
                .changed()
                .then_some(ControlValue::Toggle(on))
        }
        ControlKind::Choice { options, selected } => {
            let mut choice = *selected;
            ui.horizontal(|ui| {
                ui.label(&control.label);
                for (i, option) in options.iter().enumerate() {
                    ui.radio_value(&mut choice, i, *option);
                }
            });
            (choice != *selected).then_some(ControlValue::Choice(choice))
        }
        ControlKind::Action => ui
            .button(&control.label)
            .on_hover_text(hint)
            .clicked()
            .then_some(ControlValue::Press),
    }
}

/// A row of drag values for a vector; whether it changed.
fn vector_row(ui: &mut egui::Ui, label: &str, v: &mut DVec3) -> bool {
    ui.horizontal(|ui| {
        ui.label(label);
        let mut changed = ui
            .add(egui::DragValue::new(&mut v.x).speed(0.01).prefix("x "))
            .changed();
        changed |= ui
            .add(egui::DragValue::new(&mut v.y).speed(0.01).prefix("y "))
            .changed();
        changed |= ui
            .add(egui::DragValue::new(&mut v.z).speed(0.01).prefix("z "))
            .changed();
        changed
    })
    .inner
}

#[cfg(test)]
mod tests {
    use super::{refresh, summarize};
    use crate::geom::{Bezier, Curve};
    use glam::DVec3;

    #[test]
    fn refresh_matches_a_full_summary_after_an_edit() {
        let mut scene = crate::scene::gallery::gallery();
        let mut summaries = summarize(&scene);
        // Replace curve 1 by a line: its family, segment count and degree all change.
        scene.curves[1].curve = Curve::Bezier(Bezier::new(vec![DVec3::ZERO, DVec3::X]));
        scene.curves[1].name = None;
        let before_0 = summaries[0].details.clone();
        refresh(&mut summaries, &scene, &[1]);
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
    }
}
