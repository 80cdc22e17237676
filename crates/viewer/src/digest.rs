//! What the GPU sync and the panel read of a scene: per-curve summaries, the scene's facts (the axis triad's planarity, counts) and their digest, the frame-rate counter — no UI types.
use std::collections::VecDeque;
use std::time::Instant;

use splinescope_core::geom::{BezierSegment, Lower, ParamCurve};
use splinescope_scene::format::{Scene, SceneCurve};

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

pub(crate) fn summarize_curve(i: usize, c: &SceneCurve) -> CurveSummary {
    summarize_lowered(i, c, &c.curve.lower())
}

pub(crate) fn summarize_lowered(
    i: usize,
    c: &SceneCurve,
    segments: &[BezierSegment],
) -> CurveSummary {
    let degree = splinescope_core::geom::max_degree(segments);
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
pub(crate) fn family_counts(scene: &Scene) -> String {
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
pub(crate) fn label(c: &SceneCurve) -> String {
    c.label()
}

/// What the panel and the canvas overlay need to know of the scene, derived when it
/// changes (not every frame: both walk every curve).
pub(crate) struct SceneFacts {
    /// Every point has z = 0 (no z fields, 2D coordinates).
    pub planar: bool,
    /// The 3D axis triad to label (empty in planar scenes).
    pub axes: Vec<splinescope_encoding::draw::Axis>,
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
                splinescope_scene::format::draw::axis_triad(scene).to_vec()
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

/// The panel lists at most this many curves (stress scenes have millions).
pub(crate) const LISTED_CURVES: usize = 200;

#[cfg(test)]
mod tests {
    use super::{refresh, summarize};
    use glam::DVec3;
    use splinescope_core::geom::{Bezier, Curve, Lower};

    #[test]
    fn refresh_matches_a_full_summary_after_an_edit() {
        let mut scene = splinescope_scene::format::gallery::gallery();
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
        let mut given = summarize(&splinescope_scene::format::gallery::gallery());
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
        use splinescope_core::geom::Nubmp;
        use splinescope_present::{ControlValue, Present};
        let scene = splinescope_scene::format::gallery::gallery();
        let i = scene
            .curves
            .iter()
            .position(|c| matches!(c.curve, Curve::ModifiedBezier(_)))
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
