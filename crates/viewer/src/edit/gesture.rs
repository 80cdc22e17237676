//! Gestures on the canvas: picking what is under the pointer, dragging a control point,
//! and paper 000's pull (the curve's point at a parameter dragged, its control points
//! moved least) — each one undoable step when it ends.

use glam::{DVec2, DVec3};

use super::{EditError, Editor, Gesture, Hit, Open};
use splinescope_core::geom::{Curve, ParamCurve};
use splinescope_core::solve::nearest;
use splinescope_core::solve::rational;
use splinescope_core::solve::shape::{SingleTargetOptions, single_target};
use splinescope_encoding::camera::Camera;

impl Editor {
    /// The nearest control point within `radius_px` of `pixel` (only where `points_shown`),
    /// else the nearest curve within `radius_px` (2D views only). At equal distance the
    /// curve drawn on top (the later one) wins.
    #[must_use]
    pub fn pick(
        &self,
        camera: &Camera,
        viewport: DVec2,
        pixel: DVec2,
        radius_px: f64,
        points_shown: bool,
    ) -> Option<Hit> {
        let mut best: Option<(f64, Hit)> = None;
        if points_shown {
            // Later curves are drawn on top: search them first, so that a shared point goes
            // to the curve the user sees.
            for (c, sc) in self.scene.curves.iter().enumerate().rev() {
                if !sc.style.show_points {
                    continue;
                }
                for (i, &p) in sc.curve.control_points().iter().enumerate() {
                    let Some(px) = camera.pixel_from_world(p, viewport) else {
                        continue;
                    };
                    let d = (px - pixel).length();
                    if d <= radius_px && best.is_none_or(|(b, _)| d < b) {
                        best = Some((
                            d,
                            Hit::Point {
                                curve: c,
                                index: i,
                                at: p,
                            },
                        ));
                    }
                }
            }
        }
        if best.is_some() {
            return best.map(|b| b.1);
        }
        let Camera::Ortho2d(c2) = camera else {
            return None;
        };
        let world = camera.world_from_pixel(pixel, viewport);
        let radius = radius_px / c2.pixels_per_unit;
        for (c, sc) in self.scene.curves.iter().enumerate().rev() {
            if sc.curve.control_box().distance_to(world) > radius {
                continue;
            }
            let n = nearest(&sc.curve, world, None);
            if n.distance <= radius && best.is_none_or(|(d, _)| n.distance < d) {
                best = Some((
                    n.distance,
                    Hit::Curve {
                        curve: c,
                        t: n.t,
                        at: n.point,
                    },
                ));
            }
        }
        best.map(|b| b.1)
    }

    /// Starts dragging control point `index` of `curve`.
    pub fn begin_point_drag(&mut self, curve: usize, index: usize) {
        self.finish();
        self.selected = Some(curve);
        self.selected_point = Some(index);
        self.open = Some(Open {
            curve,
            before: self.scene.curves[curve].clone(),
            gesture: Gesture::Point { index },
            list_before: None,
        });
    }

    /// Whether curve `curve` can be pulled through the pointer (a Bézier, rational Bézier
    /// or NURBS curve of at least 3 control points); other curves are edited by their
    /// points.
    #[must_use]
    pub fn can_pull(&self, curve: usize) -> bool {
        self.scene
            .curves
            .get(curve)
            .is_some_and(|c| pullable(&c.curve) && c.curve.control_points().len() >= 3)
    }

    /// Starts pulling a Bézier curve's point at `t` through the pointer: while dragging, the
    /// curve is the least-squares modification of the original (paper 000, Eq. 8) passing
    /// through the pointer at `t`.
    ///
    /// # Errors
    /// A message when the curve is not a Bézier curve of degree ≥ 2 or `t` is an end.
    pub fn begin_pull(&mut self, curve: usize, t: f64) -> Result<(), EditError> {
        self.finish();
        self.selected = Some(curve);
        self.selected_point = None;
        let b = &self.scene.curves[curve].curve;
        if !pullable(b) {
            return Err(EditError::NotBezier {
                index: curve,
                family: b.family(),
            });
        }
        let (start, end) = b.domain();
        if !self.can_pull(curve) || t <= start || t >= end {
            return Err(EditError::PullAtEnd);
        }
        self.open = Some(Open {
            curve,
            before: self.scene.curves[curve].clone(),
            gesture: Gesture::Pull {
                t_s: t,
                original: Box::new(b.clone()),
            },
            list_before: None,
        });
        Ok(())
    }

    /// Moves the open drag to `world`. Invalid results leave the curve as it was and set
    /// [`Editor::message`].
    pub fn drag_to(&mut self, world: DVec3) {
        let Some(open) = self.open.clone() else {
            return;
        };
        let mut sc = self.scene.curves[open.curve].clone();
        let result = match &open.gesture {
            Gesture::Point { index } => sc
                .curve
                .with_control_point(*index, world)
                .map_err(|e| e.to_string()),
            Gesture::Pull { t_s, original } => {
                pull(open.curve, original, *t_s, world).map_err(|e| e.to_string())
            }
            Gesture::Control { .. } => return,
        };
        match result {
            Ok(curve) => {
                sc.curve = curve;
                self.set(open.curve, sc);
                self.message = None;
                self.refusal = None;
            }
            Err(e) => self.refuse(open.curve, "", e),
        }
    }
}
/// Whether paper 000's pull applies to the family (its weights fixed for rational curves).
fn pullable(curve: &Curve) -> bool {
    matches!(
        curve,
        Curve::Bezier(_) | Curve::RationalBezier(_) | Curve::Nurbs(_)
    )
}

/// The curve `original` (curve `index`) pulled so that its point at `t_s` passes through `world`: paper
/// 000's single-target modification (the weights fixed for rational curves).
fn pull(index: usize, original: &Curve, t_s: f64, world: DVec3) -> Result<Curve, EditError> {
    let result = match original {
        Curve::Bezier(b) => single_target(
            b,
            world,
            &SingleTargetOptions {
                t_s: Some(t_s),
                ..SingleTargetOptions::default()
            },
        )
        .map(|s| Curve::Bezier(s.curve)),
        Curve::RationalBezier(c) => rational::single_target(c, world, Some(t_s), None, None)
            .map(|s| Curve::RationalBezier(s.curve)),
        Curve::Nurbs(c) => {
            rational::single_target(c, world, Some(t_s), None, None).map(|s| Curve::Nurbs(s.curve))
        }
        other => {
            return Err(EditError::NotBezier {
                index,
                family: other.family(),
            });
        }
    };
    Ok(result?)
}
