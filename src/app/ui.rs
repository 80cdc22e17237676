//! The viewer's side panel (egui).

use std::collections::VecDeque;
use std::time::Instant;

use crate::camera::Camera;
use crate::geom::{Lower, ParamCurve};
use crate::scene::Scene;

use super::Toggles;

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
        .map(|(i, c)| {
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
        })
        .collect()
}

/// What the panel shows.
pub(crate) struct PanelInfo<'a> {
    pub scene: &'a Scene,
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
            ui.heading(info.scene.name.as_deref().unwrap_or("splinescope"));
            ui.label(format!(
                "{} curve(s) · {} samples/frame · {:.0} fps",
                info.scene.curves.len(),
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
            egui::ScrollArea::vertical().show(ui, |ui| {
                for c in info.summaries {
                    ui.horizontal(|ui| {
                        let (rect, _) =
                            ui.allocate_exact_size(egui::vec2(10.0, 10.0), egui::Sense::hover());
                        ui.painter().rect_filled(rect, 2.0, c.color);
                        ui.add(egui::Label::new(&c.label).truncate());
                    })
                    .response
                    .on_hover_text(&c.details);
                }
                if info.scene.curves.len() > LISTED_CURVES {
                    ui.small(format!(
                        "… and {} more",
                        info.scene.curves.len() - LISTED_CURVES
                    ));
                }
            });
        });
    response.response.rect.width()
}
