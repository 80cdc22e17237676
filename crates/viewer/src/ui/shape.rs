//! The panel's "shape" section — the curvature comb (on/off, the selected curve alone, its
//! scale typed, dragged or chosen for the view), the markers with their legend, and the
//! selected curve's readouts — and what the canvas adds: the selected curve's tight box
//! and the curvature at the extremum marker under the pointer.

use glam::DVec3;

use super::actions::{SELECTION, accepted};
use super::{Actions, PanelInfo};
use crate::edit::Editor;
use crate::interaction::Interaction;
use crate::shape::{Readouts, ShapeView};
use splinescope_encoding::draw::{MarkerKind, marker_style};
use splinescope_scene::format::shape::CombCap;

/// The colour a legend's markers are shown in (each marker takes its curve's).
const LEGEND_CURVE: egui::Color32 = egui::Color32::from_rgb(31, 119, 180);

fn color32(c: splinescope_encoding::Color) -> egui::Color32 {
    let [r, g, b, a] = c.0.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
    egui::Color32::from_rgba_unmultiplied(r, g, b, a)
}

/// A marker of `kind` as the renderer draws it (ring, then core), at `at`.
fn paint_marker(painter: &egui::Painter, at: egui::Pos2, kind: MarkerKind, scale: f32) {
    let [r, g, b, _] = LEGEND_CURVE.to_array();
    let curve = splinescope_encoding::Color([
        f32::from(r) / 255.0,
        f32::from(g) / 255.0,
        f32::from(b) / 255.0,
        1.0,
    ]);
    let (ring, core) = marker_style(kind, curve);
    painter.circle_filled(at, 0.5 * ring.width_px * scale, color32(ring.color));
    painter.circle_filled(at, 0.5 * core.width_px * scale, color32(core.color));
}

/// The "shape" section of the panel.
pub(crate) fn shape_section(
    ui: &mut egui::Ui,
    info: &PanelInfo<'_>,
    shape: &mut ShapeView,
    editor: &mut Editor,
    actions: &mut Actions,
) {
    egui::CollapsingHeader::new("shape")
        .default_open(true)
        .show(ui, |ui| {
            comb_rows(ui, shape, editor, actions);
            let s = &mut *shape;
            ui.checkbox(&mut s.inflections, "inflections and cusps");
            ui.checkbox(&mut s.curvature_extrema, "curvature extrema");
            ui.checkbox(&mut s.intersections, "intersections");
            ui.checkbox(&mut s.joints, "joints (kinks, curvature jumps)")
                .on_hover_text("where segments meet: a kink (G0) or a curvature jump (G1)");
            ui.checkbox(&mut s.bbox, "selected curve's box");
            offset_rows(ui, info, s, editor);
            let kinds = s.marker_options().marker_kinds();
            for kind in kinds {
                let count = info.markers.iter().filter(|m| m.kind == kind).count();
                ui.horizontal(|ui| {
                    let (rect, _) =
                        ui.allocate_exact_size(egui::vec2(14.0, 14.0), egui::Sense::hover());
                    paint_marker(ui.painter(), rect.center(), kind, 1.0);
                    ui.small(format!("{} ({count})", kind.label()));
                });
            }
            readouts(ui, info, shape, editor);
        });
}

/// The selected curve's offset: on/off, its distance (typed or dragged), what it came to.
fn offset_rows(
    ui: &mut egui::Ui,
    info: &PanelInfo<'_>,
    shape: &mut ShapeView,
    editor: &mut Editor,
) {
    let mut on = shape.offset;
    if ui
        .checkbox(&mut on, "selected curve's offset")
        .on_hover_text("the parallel curve at a distance (> 0: left of the direction of travel), within a quarter pixel, with its cusps; recomputed as you edit")
        .changed()
    {
        shape.offset = on;
        if on && shape.offset_distance == 0.0 {
            // A first distance: a twentieth of the selected curve's box.
            let size = editor
                .selected
                .and_then(|i| editor.scene().curves.get(i))
                .map(|c| {
                    let b = splinescope_core::analysis::CurveAnalysis::new(&c.curve).bounding_box();
                    (b.max - b.min).length()
                })
                .filter(|s| s.is_finite() && *s > 0.0)
                .unwrap_or(1.0);
            shape.offset_distance = 0.05 * size;
        }
    }
    if !shape.offset {
        return;
    }
    ui.horizontal(|ui| {
        let mut d = shape.offset_distance;
        let response = ui
            .add(
                egui::DragValue::new(&mut d)
                    .speed(0.01 * shape.offset_distance.abs().max(1e-6))
                    .max_decimals(6)
                    .update_while_editing(false),
            )
            .on_hover_text("the signed distance in world units: drag, or type");
        if accepted(ui.ctx(), &response) && d != shape.offset_distance {
            if d.is_finite() {
                shape.offset_distance = d;
            } else {
                editor.message = Some(format!("offset distance {d}: must be a finite number"));
            }
        }
        ui.small("distance");
    });
    match (&editor.selected, &info.offset_status) {
        (None, _) => {
            ui.small("select a curve to see its offset");
        }
        (Some(_), Some(status)) => {
            ui.small(status);
        }
        (Some(_), None) => {
            ui.small("computing…");
        }
    }
}

/// The comb's switches and scale.
fn comb_rows(ui: &mut egui::Ui, shape: &mut ShapeView, editor: &mut Editor, actions: &mut Actions) {
    let mut comb = shape.comb;
    if ui
        .checkbox(&mut comb, "curvature comb (K)")
        .on_hover_text("hairs along the normal, as long as the curvature; their tips joined")
        .changed()
    {
        actions.toggle_comb = true;
    }
    if !shape.comb {
        return;
    }
    ui.checkbox(&mut shape.comb_selected_only, "selected curve only");
    ui.horizontal(|ui| {
        let mut scale = shape.comb_scale;
        // Typed values are given once complete and never clamped: a scale that is not a
        // positive number is refused whole, with a message.
        let response = ui
            .add(
                egui::Slider::new(&mut scale, 1e-6..=1e6)
                    .logarithmic(true)
                    .clamping(egui::SliderClamping::Never)
                    .update_while_editing(false)
                    .max_decimals(6),
            )
            .on_hover_text("world length of a hair per unit of curvature: drag, or double-click the number to type");
        if accepted(ui.ctx(), &response)
            && scale != shape.comb_scale
            && let Err(e) = shape.set_comb_scale(scale)
        {
            editor.message = Some(e);
        }
        for (label, factor) in [("÷2", 0.5), ("×2", 2.0)] {
            if ui.small_button(label).clicked() {
                let _ = shape.set_comb_scale(shape.comb_scale * factor);
            }
        }
        if ui
            .small_button("auto")
            .on_hover_text("the sharpest tenth of the hairs reach 4 % of the view")
            .clicked()
        {
            actions.fit_comb = true;
        }
    });
    ui.horizontal(|ui| {
        let mut capped = shape.comb_cap.get().is_finite();
        if ui
            .checkbox(&mut capped, "cap")
            .on_hover_text("cut hairs longer than this fraction of the view's height: a cut hair is drawn in the envelope's stroke and the envelope breaks there")
            .changed()
        {
            shape.comb_cap = if capped {
                CombCap::default()
            } else {
                CombCap::NONE
            };
        }
        if capped {
            let mut cap = shape.comb_cap.get();
            let response = ui
                .add(
                    egui::DragValue::new(&mut cap)
                        .speed(0.005)
                        .max_decimals(4)
                        .update_while_editing(false),
                )
                .on_hover_text("the longest hair, a fraction of the view's height: drag, or type");
            if accepted(ui.ctx(), &response)
                && cap != shape.comb_cap.get()
                && let Err(e) = shape.set_comb_cap(cap)
            {
                editor.message = Some(e);
            }
        }
    });
    ui.small(if shape.comb_auto {
        "scale: chosen for the view"
    } else {
        "scale: as set"
    });
}

/// The selected curve's length, box, area, and counts.
fn readouts(ui: &mut egui::Ui, info: &PanelInfo<'_>, shape: &ShapeView, editor: &Editor) {
    let Some(index) = editor.selected else {
        ui.small("select a curve for its length, box and counts");
        return;
    };
    let intersections = shape.intersections.then_some(info.markers);
    let Some(r) = Readouts::of(editor.scene(), index, intersections) else {
        return;
    };
    let n = |x: f64| splinescope_core::num::fixed(x, 6);
    egui::Grid::new("shape-readouts").show(ui, |ui| {
        ui.label("length");
        ui.label(r.length.map_or("—".to_owned(), n));
        ui.end_row();
        ui.label("box");
        ui.label(format!(
            "[{}, {}] × [{}, {}]",
            n(r.bbox.min.x),
            n(r.bbox.max.x),
            n(r.bbox.min.y),
            n(r.bbox.max.y)
        ));
        ui.end_row();
        if let Some(area) = r.area {
            ui.label("signed area");
            ui.label(n(area));
            ui.end_row();
        }
        if let Some(k) = r.inflections {
            ui.label("inflections");
            ui.label(k.to_string());
            ui.end_row();
        }
        if let Some(k) = r.intersections {
            ui.label("intersections");
            ui.label(k.to_string());
            ui.end_row();
        }
    });
}

/// In 2D, with a curve selected and the pointer on the canvas (not dragging): the nearest
/// point of the selected curve to the pointer, a line to it and the distance.
fn nearest_to_pointer(
    painter: &egui::Painter,
    model: &Interaction,
    pixel: &dyn Fn(DVec3) -> Option<egui::Pos2>,
    pointer: egui::Pos2,
) {
    if model.is_editing()
        || model.pointer_over_ui()
        || !matches!(
            model.camera,
            splinescope_encoding::camera::Camera::Ortho2d(_)
        )
    {
        return;
    }
    let Some(index) = model.editor.selected else {
        return;
    };
    let Some(sc) = model.scene().curves.get(index) else {
        return;
    };
    let at = model.cursor_world();
    let Ok(near) = splinescope_core::analysis::CurveAnalysis::new(&sc.curve).nearest(at) else {
        return;
    };
    let foot = splinescope_core::geom::ParamCurve::eval(&sc.curve, near.t);
    let Some(f) = pixel(foot) else {
        return;
    };
    painter.line_segment(
        [pointer, f],
        egui::Stroke::new(1.0, SELECTION.gamma_multiply(0.7)),
    );
    painter.circle_stroke(f, 4.0, egui::Stroke::new(1.5, SELECTION));
    painter.text(
        f + egui::vec2(8.0, -8.0),
        egui::Align2::LEFT_BOTTOM,
        format!(
            "{} at t = {}",
            splinescope_core::num::fixed(near.distance, 6),
            splinescope_core::num::fixed(near.t, 4)
        ),
        egui::FontId::monospace(11.0),
        SELECTION,
    );
}

/// The canvas's shape feedback: the selected curve's tight box, and the signed curvature
/// of the curvature-extremum marker under the pointer.
pub(crate) fn canvas_shape(ui: &mut egui::Ui, info: &PanelInfo<'_>, model: &Interaction) {
    let ctx = ui.ctx().clone();
    let ppp = f64::from(ctx.pixels_per_point());
    let pixel = |w: DVec3| {
        model
            .camera
            .pixel_from_world(w, model.viewport)
            .map(|p| egui::pos2((p.x / ppp) as f32, (p.y / ppp) as f32))
    };
    let painter = ctx.layer_painter(egui::LayerId::background());
    if model.shape.bbox
        && let Some(index) = model.editor.selected
        && let Some(sc) = model.scene().curves.get(index)
    {
        let b = splinescope_core::analysis::CurveAnalysis::new(&sc.curve).bounding_box();
        let corners = [
            DVec3::new(b.min.x, b.min.y, b.min.z),
            DVec3::new(b.max.x, b.min.y, b.min.z),
            DVec3::new(b.max.x, b.max.y, b.min.z),
            DVec3::new(b.min.x, b.max.y, b.min.z),
            DVec3::new(b.min.x, b.min.y, b.min.z),
        ];
        let points: Vec<egui::Pos2> = corners.iter().filter_map(|&c| pixel(c)).collect();
        painter.add(egui::Shape::dashed_line(
            &points,
            egui::Stroke::new(1.0, SELECTION),
            6.0,
            4.0,
        ));
    }
    // The selected curve's offset, dashed in the selection's colour.
    if model.shape.offset
        && let Some(Ok(o)) = model.offset.current()
    {
        for path in &o.paths {
            let curve = splinescope_core::geom::Curve::Path(path.clone());
            let (a, b) = splinescope_core::geom::ParamCurve::domain(&curve);
            let n = 32 * path.segments().len().max(1);
            let points: Vec<egui::Pos2> = (0..=n)
                .filter_map(|j| {
                    pixel(splinescope_core::geom::ParamCurve::eval(
                        &curve,
                        a + (b - a) * j as f64 / n as f64,
                    ))
                })
                .collect();
            painter.add(egui::Shape::dashed_line(
                &points,
                egui::Stroke::new(1.5, SELECTION),
                8.0,
                4.0,
            ));
        }
    }
    let Some(pointer) = ctx.pointer_hover_pos() else {
        return;
    };
    nearest_to_pointer(&painter, model, &pixel, pointer);
    let near = info
        .markers
        .iter()
        .filter(|m| m.curvature.is_some() || m.joint.is_some())
        .filter_map(|m| pixel(m.point).map(|p| (p.distance(pointer), m)))
        .filter(|(d, _)| *d <= 8.0)
        .min_by(|a, b| a.0.total_cmp(&b.0));
    if let Some((_, m)) = near
        && let Some((angle, jump)) = m.joint
    {
        let what = if m.kind == MarkerKind::Kink {
            format!(
                "the tangents {}° apart",
                splinescope_core::num::fixed(angle.to_degrees(), 3)
            )
        } else if jump.is_finite() {
            format!(
                "the curvature jumps by {} %",
                splinescope_core::num::fixed(100.0 * jump, 2)
            )
        } else {
            "the curvature is unbounded there".to_owned()
        };
        let text = format!(
            "{} of curve {} at t = {}: {what}",
            m.kind.label(),
            m.curve,
            splinescope_core::num::fixed(m.t, 6)
        );
        marker_tip(&ctx, text);
    } else if let Some((_, m)) = near {
        // The extremum is of |κ| (a bend's sharpest point is a maximum either way); the
        // signed value says which way it turns.
        let k = m.curvature.unwrap_or_default();
        let text = format!(
            "{} of curve {}: |κ| = {}, turning {} (κ = {}) at t = {}",
            m.kind.label(),
            m.curve,
            splinescope_core::num::fixed(k.abs(), 6),
            if k < 0.0 { "right" } else { "left" },
            splinescope_core::num::fixed(k, 6),
            splinescope_core::num::fixed(m.t, 6)
        );
        marker_tip(&ctx, text);
    }
}

/// The tooltip at the pointer saying what the marker under it measures.
fn marker_tip(ctx: &egui::Context, text: String) {
    egui::Tooltip::always_open(
        ctx.clone(),
        egui::LayerId::background(),
        egui::Id::unique("splinescope-marker-hover"),
        egui::PopupAnchor::Pointer,
    )
    .show(|ui| ui.label(text));
}
