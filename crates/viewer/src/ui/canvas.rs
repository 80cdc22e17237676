//! The canvas: curve labels, the pointer's gestures and the context menu.

use glam::DVec3;

use crate::camera::Camera;
use crate::digest::{CurveSummary, LISTED_CURVES, SceneDigest};
use crate::geom::ParamCurve;
use crate::scene::{Scene, SceneCurve};

use crate::edit::Hit;
use crate::interaction::{Interaction, Template};

use super::actions::*;
use super::dialogs::{help_window, prompt_modal};
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
    let name_of = |curve: usize| {
        scene
            .curves
            .get(curve)
            .map(SceneCurve::label)
            .unwrap_or_default()
    };
    match model.hovered {
        Some(Hit::Point { curve, index, at }) if !model.is_editing() => {
            ring(at, 9.0, accent.gamma_multiply(0.8), false);
            ctx.set_cursor_icon(egui::CursorIcon::Grab);
            let name = name_of(curve);
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
            let name = name_of(curve);
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
        painter.text(
            ctx.content_rect().right_bottom() - egui::vec2(8.0, 6.0),
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
    axis_labels(&painter, facts, &pixel);
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

/// Labels just past the ends of the 3D axis triad.
fn axis_labels(
    painter: &egui::Painter,
    facts: &crate::digest::SceneFacts,
    pixel: &impl Fn(DVec3) -> Option<egui::Pos2>,
) {
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
}

/// Each curve's name (and live parameters) beside its middle point, in its colour on a
/// translucent plate of the scene's background, moved to another side of the point when it
/// would cover a label already placed or leave the window (and left out when no side
/// will do).
pub(crate) fn curve_labels(
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
pub(crate) fn context_menu(
    ctx: &egui::Context,
    model: &Interaction,
    at: egui::Pos2,
    actions: &mut Actions,
) {
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
