//! The viewer's side panel (egui).

use std::collections::VecDeque;
use std::time::Instant;

use glam::DVec3;

use crate::camera::Camera;
use crate::geom::{
    CubicInterpolation, Curve, Lower, Modification, ModifiedBezier, Nubmp, ParamCurve, Reading,
};
use crate::scene::{Scene, SceneCurve};

use super::Toggles;
use super::edit::Editor;

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
                "{} curve(s) · {} samples/frame · {:.0} fps",
                scene.curves.len(),
                info.samples_per_frame,
                info.fps
            ));
            ui.small(info.adapter);
            if let Some((curves, ms)) = info.solving {
                ui.label(format!(
                    "re-solving {curves} curves per frame: {ms:.2} ms ({:.1} M solves/s)",
                    curves as f64 / (ms.max(1e-6) * 1e3)
                ));
            }
            ui.separator();
            ui.checkbox(&mut toggles.show_polygons, "control polygons (P)");
            ui.checkbox(&mut toggles.show_points, "control points (C)");
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
    match &sc.curve {
        Curve::Bezier(b) => {
            ui.small(format!("degree {}", b.degree()));
            if ui
                .button("elevate degree")
                .on_hover_text("the same curve with one more control point")
                .clicked()
            {
                editor.set_curve(index, Curve::Bezier(b.elevate()), "elevate");
                editor.finish();
            }
        }
        Curve::Modified(m) => {
            let mut t_star = m.t_star();
            let slider = egui::Slider::new(&mut t_star, 0.01..=0.99)
                .clamping(egui::SliderClamping::Never)
                .text("t*");
            if ui.add(slider).changed() {
                apply(
                    editor,
                    index,
                    "t*",
                    ModifiedBezier::try_new(m.base().clone(), t_star, m.v()).map(Curve::Modified),
                );
            }
            let mut v = m.v();
            if vector_row(ui, "v", &mut v) {
                apply(
                    editor,
                    index,
                    "v",
                    ModifiedBezier::try_new(m.base().clone(), m.t_star(), v).map(Curve::Modified),
                );
            }
        }
        Curve::Interpolation(c) => {
            let rebuild = |m: Option<Modification>| {
                CubicInterpolation::try_new(c.points().to_vec(), Some(c.params().to_vec()), m)
                    .map(Curve::Interpolation)
            };
            let mut modified = c.modification().is_some();
            if ui.checkbox(&mut modified, "modified (paper 002)").changed() {
                let m = modified.then_some(Modification {
                    t_star: 0.5,
                    v: DVec3::ZERO,
                    reading: Reading::Paper,
                });
                apply(editor, index, "modified", rebuild(m));
                editor.finish();
            }
            if let Some(m) = c.modification() {
                let mut next = m;
                let slider = egui::Slider::new(&mut next.t_star, 0.01..=0.99)
                    .clamping(egui::SliderClamping::Never)
                    .text("t*");
                let mut changed = ui.add(slider).changed();
                changed |= vector_row(ui, "v", &mut next.v);
                ui.horizontal(|ui| {
                    changed |= ui
                        .radio_value(&mut next.reading, Reading::Paper, "paper")
                        .changed();
                    changed |= ui
                        .radio_value(&mut next.reading, Reading::BumpAdded, "bump added")
                        .changed();
                });
                if changed {
                    apply(editor, index, "modification", rebuild(Some(next)));
                }
            }
        }
        Curve::BSpline(b) => {
            ui.small(format!(
                "order {}, knots {:?}",
                b.order(),
                b.knots().knots()
            ));
        }
        Curve::Nubmp(n) => nubmp_controls(ui, editor, index, n),
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

/// Applies a panel edit, or shows why it is refused (nothing changes then).
fn apply<E: std::fmt::Display>(
    editor: &mut Editor,
    index: usize,
    key: &str,
    result: Result<Curve, E>,
) {
    match result {
        Ok(curve) => editor.set_curve(index, curve, key),
        Err(e) => editor.message = Some(format!("curves[{index}]: {e}")),
    }
}

/// Sliders for the shape parameters of every group (the last member absorbs), with the
/// Theorem 1 value and permissible ranges for order 4.
fn nubmp_controls(ui: &mut egui::Ui, editor: &mut Editor, index: usize, n: &Nubmp) {
    ui.small(format!(
        "order {}, {} groups, {} free parameters",
        n.order(),
        n.groups().len(),
        n.free_parameter_count()
    ));
    if !n.is_standard() && ui.button("reset to the standard curve").clicked() {
        // The curve's own knots gave a finite standard structure when it was built.
        if let Ok(standard) = Nubmp::standard(n.points().to_vec(), n.knots().clone()) {
            editor.set_curve(index, Curve::Nubmp(standard), "reset");
            editor.finish();
        }
    }
    egui::ScrollArea::vertical()
        .id_salt("groups")
        .max_height(220.0)
        .show(ui, |ui| {
            for (j, g) in n.groups().iter().enumerate() {
                if !g.effective || g.members.len() < 2 {
                    continue;
                }
                let vd = n.vd_value(j);
                let title = match vd {
                    Some(v) => format!("A_{j}: Theorem 1 value {v:.3}"),
                    None => format!("A_{j}"),
                };
                let color = if vd.is_some_and(|v| v > 1.0) {
                    egui::Color32::from_rgb(200, 40, 40)
                } else {
                    ui.visuals().text_color()
                };
                ui.colored_label(color, title);
                let last = g.members[g.members.len() - 1];
                for &i in &g.members[..g.members.len() - 1] {
                    let (Some(mut a), Some(b)) = (g.value(i), g.value(last)) else {
                        continue;
                    };
                    let pair = a + b;
                    // Typed values are not clamped: the model refuses invalid ones, with a message.
                    let slider = egui::Slider::new(&mut a, 0.0..=pair)
                        .clamping(egui::SliderClamping::Never)
                        .text(format!("a^{i}_{j}"));
                    if let Ok(Some(r)) = n.permissible_range(j, i, last) {
                        ui.small(format!(
                            "VD range [{:.4}, {:.4}] (a^{last}_{j} absorbs)",
                            r.min, r.max
                        ));
                    }
                    if ui.add(slider).changed() {
                        let mut next = n.clone();
                        let result = next
                            .set_parameter(j, i, a, last)
                            .map(|()| Curve::Nubmp(next));
                        apply(editor, index, &format!("a^{i}_{j}"), result);
                    }
                }
            }
        });
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
