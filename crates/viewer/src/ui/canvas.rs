//! The canvas: curve labels, the pointer's gestures and the context menu.

use glam::{DVec2, DVec3};

use crate::digest::{CurveSummary, LISTED_CURVES, SceneDigest};
use splinescope_core::geom::ParamCurve;
use splinescope_encoding::camera::Camera;
use splinescope_scene::format::{Scene, SceneCurve};

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
        // Right of the panel: the canvas the curves are seen in.
        let mut area = ctx.content_rect();
        area.min.x += (model.panel_width_px / ppp) as f32;
        curve_labels(
            &painter.with_clip_rect(area),
            (scene, model.toggles),
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

/// Each curve's name (and live parameters) in its colour on a translucent plate of the
/// scene's background, placed by the search figures use
/// ([`splinescope_scene::format::labels`]): along its curve, clear of every other label, off the
/// curves where a free spot exists, inside the canvas, with a leader line where it stands
/// off; kept where it was last frame while that place stays good (no jumping during a
/// drag); hidden, and counted in the canvas's corner, where no place is free.
pub(crate) fn curve_labels(
    painter: &egui::Painter,
    (scene, toggles): (&Scene, crate::interaction::Toggles),
    summaries: &[CurveSummary],
    pixel: &dyn Fn(DVec3) -> Option<egui::Pos2>,
    plate: egui::Color32,
) {
    use splinescope_core::geom::Lower;
    use splinescope_scene::format::labels::{ANCHORS, Choice, Ink, LabelRequest, place};
    let screen = painter.clip_rect();
    let origin = screen.min;
    let local = |p: egui::Pos2| DVec2::new(f64::from(p.x - origin.x), f64::from(p.y - origin.y));
    let size = DVec2::new(f64::from(screen.width()), f64::from(screen.height()));
    let mut ink = Ink::new(size);
    for sc in &scene.curves {
        let (a, b) = sc.curve.domain();
        let n = 64 * sc.curve.lower().len().clamp(1, 64);
        let points: Vec<DVec2> = (0..=n)
            .filter_map(|k| pixel(sc.curve.eval(a + (b - a) * k as f64 / n as f64)))
            .map(local)
            .collect();
        ink.add_polyline(&points);
        // The control polygon and points as shown.
        let polygon: Vec<DVec2> = sc
            .curve
            .control_points()
            .iter()
            .filter_map(|p| pixel(*p))
            .map(local)
            .collect();
        if toggles.show_polygons && sc.style.show_polygon {
            ink.add_polyline(&polygon);
        } else if toggles.show_points && sc.style.show_points {
            for p in polygon {
                ink.add_polyline(&[p]);
            }
        }
    }
    let galleys: Vec<_> = scene
        .curves
        .iter()
        .zip(summaries)
        .map(|(sc, summary)| {
            let [r, g, bl, _] = sc.style.color.0.map(|v| (v * 255.0).round() as u8);
            painter.layout_no_wrap(
                summary.name.clone(),
                egui::FontId::proportional(12.0),
                egui::Color32::from_rgb(r, g, bl),
            )
        })
        .collect();
    let requests: Vec<LabelRequest> = scene
        .curves
        .iter()
        .zip(&galleys)
        .map(|(sc, galley)| {
            let (a, b) = sc.curve.domain();
            let size = galley.size() + egui::vec2(4.0, 4.0);
            LabelRequest {
                anchors: ANCHORS
                    .iter()
                    .map(|f| pixel(sc.curve.eval(a + f * (b - a))).map_or(DVec2::NAN, local))
                    .collect(),
                size: DVec2::new(f64::from(size.x), f64::from(size.y)),
            }
        })
        .collect();
    let id = egui::Id::unique("splinescope-label-places");
    let keep: Vec<Option<Choice>> = painter
        .ctx()
        .data(|d| d.get_temp::<Vec<Option<Choice>>>(id))
        .filter(|k| k.len() == requests.len())
        .unwrap_or_default();
    let placed = place(&requests, &ink, size, &[], &keep);
    painter.ctx().data_mut(|d| {
        d.insert_temp(
            id,
            placed
                .iter()
                .map(|p| p.map(|p| p.choice))
                .collect::<Vec<Option<Choice>>>(),
        );
    });
    let to_pos = |p: DVec2| origin + egui::vec2(p.x as f32, p.y as f32);
    let mut hidden = 0;
    for (galley, p) in galleys.into_iter().zip(placed) {
        let Some(p) = p else {
            hidden += 1;
            continue;
        };
        if let Some((a, b)) = p.leader {
            painter.line_segment(
                [to_pos(a), to_pos(b)],
                egui::Stroke::new(1.0, galley_color(&galley).gamma_multiply(0.6)),
            );
        }
        let rect = egui::Rect::from_min_max(to_pos(p.min), to_pos(p.max));
        painter.rect_filled(rect, 3.0, plate.gamma_multiply(0.75));
        painter.galley(
            rect.min + egui::vec2(2.0, 2.0),
            galley,
            egui::Color32::WHITE,
        );
    }
    if let Some(text) = splinescope_scene::format::labels::hidden_note(hidden) {
        painter.text(
            screen.left_bottom() + egui::vec2(8.0, -6.0),
            egui::Align2::LEFT_BOTTOM,
            text,
            egui::FontId::proportional(12.0),
            egui::Color32::GRAY,
        );
    }
}

/// The colour a galley's text was laid out in.
fn galley_color(galley: &egui::Galley) -> egui::Color32 {
    galley
        .job
        .sections
        .first()
        .map_or(egui::Color32::GRAY, |s| s.format.color)
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
