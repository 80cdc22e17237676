//! The viewer's editing model, free of GPU and window types: picking, dragging control
//! points, pulling a Bézier curve through the pointer (paper 000's single-target solve),
//! setting a curve from the panel, structural edits (curves added, duplicated, deleted;
//! points inserted, removed, typed), undo/redo that keeps every edit and atomic saving;
//! the recovery file that holds unsaved edits until they are saved or discarded is kept
//! by `edit/recovery.rs`.

use std::path::{Path, PathBuf};

use glam::{DVec2, DVec3};

use crate::camera::Camera;
use crate::geom::{Control, ControlValue, Curve, ParamCurve};
use crate::scene::{Scene, SceneCurve};
use crate::solve::nearest;
use crate::solve::rational;
use crate::solve::shape::{SingleTargetOptions, single_target};

mod recovery;
pub use recovery::recovery_path;

/// Why an edit, a pull or a save was refused; the scene is unchanged.
#[derive(Debug, thiserror::Error)]
pub enum EditError {
    /// No curve has this index.
    #[error("curves[{index}] does not exist")]
    NoSuchCurve {
        /// The index asked for.
        index: usize,
    },
    /// The curve refused the change (its message names the field).
    #[error("curves[{index}]: {reason}")]
    Curve {
        /// The curve.
        index: usize,
        /// What the family said.
        reason: crate::geom::GeomError,
    },
    /// A typed control point the curve refused.
    #[error("curves[{index}].points[{point}]: {reason}")]
    Point {
        /// The curve.
        index: usize,
        /// The point.
        point: usize,
        /// What the family said.
        reason: crate::geom::GeomError,
    },
    /// Pulling through a point modifies Bézier and rational curves only.
    #[error(
        "pulling a curve through a point modifies Bézier, rational Bézier and NURBS curves; curves[{index}] is {family} (drag its control points)"
    )]
    NotBezier {
        /// The curve.
        index: usize,
        /// Its family.
        family: &'static str,
    },
    /// The pull's solve refused the target (its message says why).
    #[error(transparent)]
    Pull(#[from] crate::solve::SolveError),
    /// The grab was at an end point (fixed by the solve) or the curve is a line.
    #[error("grab the curve away from its fixed end points (and degree ≥ 2)")]
    PullAtEnd,
    /// A deletion with nothing selected.
    #[error("select a curve or a control point to delete")]
    NothingSelected,
    /// The scene has no file yet.
    #[error("no file to save to")]
    NoFile,
    /// Writing the file failed (the previous file is intact).
    #[error("{}: cannot save: {reason}", path.display())]
    Save {
        /// The file.
        path: PathBuf,
        /// The cause.
        reason: std::io::Error,
    },
}

/// What the pointer is over.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Hit {
    /// A control point (as listed by `Curve::control_points`).
    Point {
        /// The curve.
        curve: usize,
        /// The point's index.
        index: usize,
        /// Its position.
        at: DVec3,
    },
    /// A point on a curve.
    Curve {
        /// The curve.
        curve: usize,
        /// The curve parameter there.
        t: f64,
        /// The point.
        at: DVec3,
    },
}

/// One committed change.
#[derive(Debug, Clone)]
enum Change {
    /// One curve replaced.
    Curve {
        curve: usize,
        before: Box<SceneCurve>,
        after: Box<SceneCurve>,
    },
    /// The list of curves replaced (a curve added, duplicated or deleted; a recovered
    /// scene restored).
    List {
        before: Vec<SceneCurve>,
        after: Vec<SceneCurve>,
    },
}

/// One committed, undoable edit.
#[derive(Debug, Clone)]
struct Edit {
    id: u64,
    change: Change,
}

/// What changed since the window layer last looked ([`Editor::take_changed`]).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Changes {
    /// Curves changed in place (each once, ascending).
    pub curves: Vec<usize>,
    /// The list of curves changed (added, removed, reordered): everything is new.
    pub list: bool,
}

impl Changes {
    /// Whether nothing changed.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.curves.is_empty() && !self.list
    }
}

/// What the open (uncommitted) edit is doing.
#[derive(Debug, Clone)]
enum Gesture {
    /// Dragging control point `index`.
    Point { index: usize },
    /// Pulling the curve's point at `t_s` through the pointer (from the original curve).
    Pull { t_s: f64, original: Box<Curve> },
    /// A panel control, identified by `key`.
    Control { key: String },
}

#[derive(Debug, Clone)]
struct Open {
    curve: usize,
    before: SceneCurve,
    gesture: Gesture,
}

/// The scene being edited, with its history.
#[derive(Debug, Clone)]
pub struct Editor {
    scene: Scene,
    history: Vec<Edit>,
    undone: Vec<Edit>,
    open: Option<Open>,
    next_id: u64,
    saved: Option<u64>,
    changed: Vec<usize>,
    list_changed: bool,
    path: Option<PathBuf>,
    /// The text of the file the scene came from (or was last saved as): saving keeps
    /// its form ([`crate::scene::to_json_string_keeping`]).
    source: Option<String>,
    /// The selected curve, if any.
    pub selected: Option<usize>,
    /// The selected control point of the selected curve, if any.
    pub selected_point: Option<usize>,
    /// The last message for the user (an error, or where a save went).
    pub message: Option<String>,
    /// The last value refused (typed or dragged), shown in the warning colour next to the
    /// field it was given in; cleared by the next accepted edit.
    pub refusal: Option<Refusal>,
}

/// A value the editor refused: where it was given and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Refusal {
    /// The curve.
    pub curve: usize,
    /// The field it was given in: a control's label (`t*`, `w1`), `point N` for a control
    /// point's coordinates, empty for a drag on the canvas.
    pub field: String,
    /// Why (the message also shown at the top of the panel).
    pub text: String,
}

impl Editor {
    /// An editor of `scene`, saving to `path` (`None`: the scene has no file yet).
    #[must_use]
    pub fn new(scene: Scene, path: Option<PathBuf>) -> Editor {
        Editor {
            source: None,
            scene,
            history: Vec::new(),
            undone: Vec::new(),
            open: None,
            next_id: 1,
            saved: None,
            changed: Vec::new(),
            list_changed: false,
            path,
            selected: None,
            selected_point: None,
            message: None,
            refusal: None,
        }
    }

    /// An editor of the scene read from `path` as `text` ([`Scene::read`]): saving keeps
    /// that text's form ([`crate::scene::to_json_string_keeping`]).
    #[must_use]
    pub fn of_file(scene: Scene, path: PathBuf, text: String) -> Editor {
        Editor {
            source: Some(text),
            ..Editor::new(scene, Some(path))
        }
    }

    /// Marks every curve as new for [`Editor::take_changed`]: this editor replaces
    /// another (a file opened, a new scene), so everything shown must be rebuilt.
    pub fn mark_replaced(&mut self) {
        self.list_changed = true;
    }

    /// The scene as edited so far.
    #[must_use]
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// What changed since the last call.
    pub fn take_changed(&mut self) -> Changes {
        let mut c = std::mem::take(&mut self.changed);
        c.sort_unstable();
        c.dedup();
        Changes {
            curves: c,
            list: std::mem::take(&mut self.list_changed),
        }
    }

    fn set_list(&mut self, curves: Vec<SceneCurve>) {
        self.scene.curves = curves;
        self.list_changed = true;
        self.selected_point = None;
        if self.selected.is_some_and(|s| s >= self.scene.curves.len()) {
            self.selected = None;
        }
    }

    /// Records a committed change, drops the redo branch and keeps the recovery file.
    fn commit(&mut self, change: Change) {
        self.history.push(Edit {
            id: self.next_id,
            change,
        });
        self.next_id += 1;
        self.undone.clear();
        self.sync_recovery();
    }

    fn set(&mut self, curve: usize, value: SceneCurve) {
        self.scene.curves[curve] = value;
        self.changed.push(curve);
    }

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

    /// Replaces `curve` from a panel control identified by `key`: consecutive changes with
    /// the same key (a slider being dragged) form one edit.
    pub fn set_curve(&mut self, curve: usize, value: Curve, key: &str) {
        let continuing = matches!(&self.open, Some(Open { curve: c, gesture: Gesture::Control { key: k }, .. }) if *c == curve && k == key);
        if !continuing {
            self.finish();
            self.open = Some(Open {
                curve,
                before: self.scene.curves[curve].clone(),
                gesture: Gesture::Control {
                    key: key.to_owned(),
                },
            });
        }
        let mut sc = self.scene.curves[curve].clone();
        sc.curve = value;
        self.set(curve, sc);
        self.message = None;
        self.refusal = None;
    }

    /// Records a refused value of curve `curve` given in `field`: the message, and the
    /// refusal shown next to the field.
    pub fn refuse(&mut self, curve: usize, field: &str, text: String) {
        self.message = Some(text.clone());
        self.refusal = Some(Refusal {
            curve,
            field: field.to_owned(),
            text,
        });
    }

    /// Applies one of a family's panel controls ([`crate::geom::Family::controls`]) to
    /// curve `index`. A refused value (or one whose derived data overflows) leaves the
    /// curve as it was and sets [`Editor::message`]; a discrete control (button, toggle,
    /// choice) is one edit on its own, a stream of slider changes is one edit together.
    pub fn apply_control(&mut self, index: usize, control: &Control, value: ControlValue) {
        let result = self.scene.curves[index]
            .curve
            .apply_control(control.id, value)
            .and_then(|c| c.check_derived().map(|()| c));
        match result {
            Ok(curve) => {
                self.set_curve(index, curve, &control.id.to_string());
                if control.kind.is_discrete() {
                    self.finish();
                }
            }
            Err(e) => self.refuse(
                index,
                &control.label,
                format!("curves[{index}]: {}: {e}", control.label),
            ),
        }
    }

    /// Commits the open edit, if it changed anything (pointer released, another control
    /// used, a typed value entered).
    pub fn finish(&mut self) {
        let Some(open) = self.open.take() else {
            return;
        };
        let after = self.scene.curves[open.curve].clone();
        if after != open.before {
            self.commit(Change::Curve {
                curve: open.curve,
                before: Box::new(open.before),
                after: Box::new(after),
            });
        }
    }

    /// Cancels the open edit (Esc): the curve goes back to how it was before the drag or
    /// slider started, and nothing enters the history. Whether there was one.
    pub fn cancel(&mut self) -> bool {
        let Some(open) = self.open.take() else {
            return false;
        };
        if self.scene.curves[open.curve] != open.before {
            self.set(open.curve, open.before);
        }
        self.message = Some("edit cancelled".into());
        true
    }

    /// Whether an edit is open (a drag or a slider not yet committed).
    #[must_use]
    pub fn is_open(&self) -> bool {
        self.open.is_some()
    }

    fn apply(&mut self, change: &Change, forward: bool) {
        match change {
            Change::Curve {
                curve,
                before,
                after,
            } => {
                let value = if forward { after } else { before };
                self.set(*curve, (**value).clone());
                self.selected = Some(*curve);
                self.selected_point = None;
            }
            Change::List { before, after } => {
                let value = if forward { after } else { before };
                self.set_list(value.clone());
            }
        }
    }

    /// Undoes the last edit; whether there was one.
    pub fn undo(&mut self) -> bool {
        self.finish();
        let Some(edit) = self.history.pop() else {
            return false;
        };
        self.apply(&edit.change, false);
        self.undone.push(edit);
        self.sync_recovery();
        true
    }

    /// Redoes the last undone edit; whether there was one.
    pub fn redo(&mut self) -> bool {
        self.finish();
        let Some(edit) = self.undone.pop() else {
            return false;
        };
        self.apply(&edit.change, true);
        self.history.push(edit);
        self.sync_recovery();
        true
    }

    /// How many edits can be undone and redone.
    #[must_use]
    pub fn history_len(&self) -> (usize, usize) {
        (self.history.len(), self.undone.len())
    }

    /// Whether the scene differs from the last save (or the file it came from).
    #[must_use]
    pub fn is_dirty(&self) -> bool {
        self.open.is_some() || self.committed_dirty()
    }

    fn committed_dirty(&self) -> bool {
        self.history.last().map(|e| e.id) != self.saved
    }

    /// Where [`Editor::save`] writes without an explicit path.
    #[must_use]
    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }

    /// The window title: the file's name (or the scene's), `*` when there are unsaved
    /// changes.
    #[must_use]
    pub fn title(&self) -> String {
        let name = self
            .path
            .as_deref()
            .and_then(Path::file_name)
            .map(|n| n.to_string_lossy().into_owned())
            .or_else(|| self.scene.name.clone())
            .unwrap_or_else(|| "untitled".into());
        let star = if self.is_dirty() { "*" } else { "" };
        format!("{name}{star} — splinescope")
    }

    /// Writes the scene atomically to `path` (or the editor's own path) and remembers it.
    /// The recovery file is removed.
    ///
    /// # Errors
    /// A message naming the file when there is no path or writing fails (the previous
    /// file is left intact).
    pub fn save(&mut self, path: Option<&Path>) -> Result<PathBuf, EditError> {
        self.finish();
        let path = path
            .map(Path::to_path_buf)
            .or_else(|| self.path.clone())
            .ok_or(EditError::NoFile)?;
        // Unchanged curves, styles and shorthands are written as the file had them.
        let text = match &self.source {
            Some(source) => crate::scene::to_json_string_keeping(&self.scene, source),
            None => crate::scene::to_json_string(&self.scene),
        };
        crate::file_output::write_atomic(&path, text.as_bytes()).map_err(|reason| {
            EditError::Save {
                path: path.clone(),
                reason,
            }
        })?;
        self.source = Some(text);
        if self.path.as_deref() != Some(path.as_path()) {
            self.discard_recovery();
        }
        self.saved = self.history.last().map(|e| e.id);
        self.path = Some(path.clone());
        self.sync_recovery();
        self.message = Some(format!("saved {}", path.display()));
        Ok(path)
    }

    /// Curve `index`, or a message saying it does not exist.
    fn curve_at(&self, index: usize) -> Result<&SceneCurve, EditError> {
        self.scene
            .curves
            .get(index)
            .ok_or(EditError::NoSuchCurve { index })
    }

    /// Replaces the list of curves as one undoable edit, selecting `select`.
    fn edit_list(&mut self, after: Vec<SceneCurve>, select: Option<usize>) {
        self.finish();
        let before = self.scene.curves.clone();
        self.set_list(after.clone());
        self.commit(Change::List { before, after });
        self.selected = select;
    }

    /// Adds `curve` at the end (drawn on top) and selects it; its index.
    pub fn add_curve(&mut self, curve: SceneCurve) -> usize {
        let mut after = self.scene.curves.clone();
        after.push(curve);
        let index = after.len() - 1;
        self.edit_list(after, Some(index));
        self.message = Some(format!("added curves[{index}]"));
        index
    }

    /// Adds a copy of curve `index`, moved by `offset`, on top, and selects it.
    ///
    /// # Errors
    /// A message when there is no such curve or the moved copy is invalid.
    pub fn duplicate(&mut self, index: usize, offset: DVec3) -> Result<usize, EditError> {
        let mut copy = self.curve_at(index)?.clone();
        let moved: Vec<DVec3> = copy
            .curve
            .control_points()
            .iter()
            .map(|&p| p + offset)
            .collect();
        copy.curve = copy
            .curve
            .with_control_points(moved)
            .map_err(|reason| EditError::Curve { index, reason })?;
        copy.name = copy.name.map(|n| format!("{n} (copy)"));
        Ok(self.add_curve(copy))
    }

    /// Deletes curve `index`.
    ///
    /// # Errors
    /// A message when there is no such curve.
    pub fn delete_curve(&mut self, index: usize) -> Result<(), EditError> {
        self.curve_at(index)?;
        let mut after = self.scene.curves.clone();
        after.remove(index);
        self.edit_list(after, None);
        self.message = Some(format!("deleted curves[{index}] (Ctrl+Z brings it back)"));
        Ok(())
    }

    /// Replaces curve `index` by `curve` as one edit of its own.
    fn edit_curve(&mut self, index: usize, curve: Curve) {
        self.finish();
        let before = self.scene.curves[index].clone();
        let mut after = before.clone();
        after.curve = curve;
        self.set(index, after.clone());
        self.commit(Change::Curve {
            curve: index,
            before: Box::new(before),
            after: Box::new(after),
        });
        self.selected = Some(index);
    }

    /// Inserts a control point into curve `index` near `at`: on the control polygon
    /// (Bézier families) or by inserting the knot at the curve parameter nearest to `at`
    /// (B-splines, NUBMP; the curve keeps its shape). Returns the new point's index.
    ///
    /// # Errors
    /// A message naming the curve and the reason.
    pub fn insert_point(&mut self, index: usize, at: DVec3) -> Result<usize, EditError> {
        let sc = self.curve_at(index)?;
        let fail = |reason| EditError::Curve { index, reason };
        let (curve, point) = if sc.curve.inserts_by_knot() {
            let t = nearest(&sc.curve, at, None).t;
            let curve = sc.curve.with_knot_inserted(t).map_err(fail)?;
            // The new point is the one the old list lacks.
            let old = sc.curve.control_points();
            let point = curve
                .control_points()
                .iter()
                .zip(old)
                .position(|(a, b)| a != b)
                .unwrap_or(old.len());
            (curve, point)
        } else {
            sc.curve.with_point_on_polygon(at).map_err(fail)?
        };
        self.edit_curve(index, curve);
        self.message = Some(format!("inserted point {point} into curves[{index}]"));
        Ok(point)
    }

    /// Removes control point `point` of curve `index` (B-splines and NUBMP curves lose a
    /// knot with it).
    ///
    /// # Errors
    /// A message naming the curve and the reason.
    pub fn delete_point(&mut self, index: usize, point: usize) -> Result<(), EditError> {
        let sc = self.curve_at(index)?;
        let curve = sc
            .curve
            .with_point_removed(point)
            .map_err(|reason| EditError::Curve { index, reason })?;
        self.edit_curve(index, curve);
        self.message = Some(format!("deleted point {point} of curves[{index}]"));
        Ok(())
    }

    /// Moves control point `point` of curve `index` to the typed position `p`, as one
    /// edit.
    ///
    /// # Errors
    /// A message naming the curve, the point and the reason; the curve is unchanged.
    pub fn set_point(&mut self, index: usize, point: usize, p: DVec3) -> Result<(), EditError> {
        let sc = self.curve_at(index)?;
        let curve = sc
            .curve
            .with_control_point(point, p)
            .map_err(|reason| EditError::Point {
                index,
                point,
                reason,
            })?;
        if curve != sc.curve {
            self.edit_curve(index, curve);
        }
        self.message = None;
        self.refusal = None;
        Ok(())
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Camera2d;
    use crate::geom::{Bezier, Nubmp};
    use crate::scene::{Color, Style, ViewSpec};

    fn scene() -> Scene {
        let cubic = Bezier::new(vec![
            DVec3::ZERO,
            DVec3::new(1., 2., 0.),
            DVec3::new(3., 2., 0.),
            DVec3::new(4., 0., 0.),
        ]);
        let pts: Vec<DVec3> = (0..7)
            .map(|i| DVec3::new(f64::from(i), f64::from(i % 2), 0.0))
            .collect();
        let nub =
            Nubmp::try_new(pts, vec![0., 0., 0., 0., 0.3, 0.5, 0.89, 1., 1., 1., 1.], 4).unwrap();
        Scene {
            name: None,
            background: Color::WHITE,
            samples_per_segment: Some(64),
            view: ViewSpec::Auto,
            curves: vec![
                SceneCurve {
                    name: None,
                    curve: Curve::Bezier(cubic),
                    style: Style::default_for(0),
                },
                SceneCurve {
                    name: None,
                    curve: Curve::Nubmp(nub),
                    style: Style::default_for(1),
                },
            ],
            annotations: Vec::new(),
        }
    }

    const VIEW: DVec2 = DVec2::new(800.0, 600.0);

    fn camera() -> Camera {
        Camera::Ortho2d(Camera2d {
            center: DVec2::new(2.0, 1.0),
            pixels_per_unit: 50.0,
        })
    }

    #[test]
    fn picking_prefers_control_points_then_curves() {
        let e = Editor::new(scene(), None);
        let cam = camera();
        let px = cam.pixel_from_world(DVec3::new(1., 2., 0.), VIEW).unwrap();
        assert_eq!(
            e.pick(&cam, VIEW, px + DVec2::new(3.0, 0.0), 8.0, true),
            Some(Hit::Point {
                curve: 0,
                index: 1,
                at: DVec3::new(1., 2., 0.)
            })
        );
        // A point on the cubic far from its control points.
        let on = Bezier::new(scene().curves[0].curve.control_points().to_vec()).eval(0.5);
        let px = cam.pixel_from_world(on, VIEW).unwrap();
        match e.pick(&cam, VIEW, px, 8.0, true) {
            Some(Hit::Curve { curve: 0, t, .. }) => assert!((t - 0.5).abs() < 1e-6),
            other => panic!("{other:?}"),
        }
        assert_eq!(e.pick(&cam, VIEW, DVec2::new(5.0, 5.0), 8.0, true), None);
    }

    #[test]
    fn every_edit_is_undoable_and_redoable() {
        let original = scene();
        let mut e = Editor::new(original.clone(), None);
        e.begin_point_drag(0, 1);
        e.drag_to(DVec3::new(1.5, 3.0, 0.0));
        e.drag_to(DVec3::new(2.0, 3.5, 0.0));
        e.finish();
        let after_drag = e.scene().clone();
        assert_eq!(
            after_drag.curves[0].curve.control_points()[1],
            DVec3::new(2.0, 3.5, 0.0)
        );
        // A NUBMP point keeps its shape parameters.
        let mut nub = match &e.scene().curves[1].curve {
            Curve::Nubmp(n) => n.clone(),
            _ => unreachable!(),
        };
        nub.set_group(4, &[0.3, 0.7]).unwrap();
        e.set_curve(1, Curve::Nubmp(nub.clone()), "group 4");
        nub.set_group(4, &[0.35, 0.65]).unwrap();
        e.set_curve(1, Curve::Nubmp(nub), "group 4");
        e.begin_point_drag(1, 3);
        e.drag_to(DVec3::new(3.0, 2.0, 0.0));
        e.finish();
        match &e.scene().curves[1].curve {
            Curve::Nubmp(n) => assert_eq!(n.groups()[4].values, vec![0.35, 0.65]),
            _ => unreachable!(),
        }
        // Three edits: the drag, the slider (one edit), the NUBMP drag.
        assert_eq!(e.history_len(), (3, 0));
        assert!(e.undo());
        assert!(e.undo());
        assert_eq!(e.scene(), &after_drag);
        assert!(e.undo());
        assert_eq!(e.scene(), &original);
        assert!(!e.undo());
        assert!(e.redo());
        assert_eq!(e.scene(), &after_drag);
        assert_eq!(e.history_len(), (1, 2));
        // A new edit drops the redo branch.
        e.begin_point_drag(0, 2);
        e.drag_to(DVec3::new(3.0, 1.0, 0.0));
        e.finish();
        assert_eq!(e.history_len(), (2, 0));
    }

    #[test]
    fn pulling_a_curve_passes_it_through_the_pointer() {
        let mut e = Editor::new(scene(), None);
        e.begin_pull(0, 0.4).unwrap();
        let target = DVec3::new(1.5, 2.5, 0.0);
        e.drag_to(DVec3::new(1.4, 2.2, 0.0));
        e.drag_to(target);
        e.finish();
        assert!((e.scene().curves[0].curve.eval(0.4) - target).length() < 1e-12);
        assert!(
            e.begin_pull(1, 0.4).is_err(),
            "NUBMP curves are edited by their points"
        );
        assert!(e.begin_pull(0, 0.0).is_err(), "the ends are fixed");
    }

    #[test]
    fn pulling_a_rational_curve_keeps_its_weights_and_undoes() {
        let mut sc = scene();
        let circle = crate::geom::Nurbs::circle(DVec3::ZERO, 2.0).unwrap();
        sc.curves[1].curve = Curve::Nurbs(circle.clone());
        let mut e = Editor::new(sc, None);
        assert!(e.can_pull(1));
        e.begin_pull(1, 0.3).unwrap();
        let target = DVec3::new(-0.5, 2.8, 0.0);
        e.drag_to(DVec3::new(-0.4, 2.4, 0.0));
        e.drag_to(target);
        e.finish();
        let Curve::Nurbs(pulled) = &e.scene().curves[1].curve else {
            panic!("still a NURBS curve");
        };
        assert!((pulled.eval(0.3) - target).length() < 1e-12);
        assert_eq!(pulled.weights(), circle.weights());
        assert!(e.undo());
        assert_eq!(e.scene().curves[1].curve, Curve::Nurbs(circle));
    }

    #[test]
    fn saving_is_atomic_and_tracks_unsaved_changes() {
        let dir = std::env::temp_dir().join(format!("splinescope-edit-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("scene.json");
        let mut e = Editor::new(scene(), Some(path.clone()));
        assert!(!e.is_dirty());
        e.begin_point_drag(0, 1);
        e.drag_to(DVec3::new(1.0, 3.0, 0.0));
        assert!(e.is_dirty());
        assert_eq!(e.save(None).unwrap(), path);
        assert!(!e.is_dirty());
        let back = Scene::load(&path).unwrap();
        assert_eq!(back.curves[0].curve, e.scene().curves[0].curve);
        e.undo();
        assert!(e.is_dirty());
        e.redo();
        assert!(!e.is_dirty());
        // No leftover temporary files.
        let entries: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert_eq!(entries.len(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
        let mut unsaved = Editor::new(scene(), None);
        assert!(unsaved.save(None).is_err());
    }

    #[test]
    fn invalid_drags_leave_the_curve_and_say_why() {
        let mut e = Editor::new(scene(), None);
        e.begin_point_drag(0, 1);
        e.drag_to(DVec3::new(f64::NAN, 0.0, 0.0));
        assert!(e.message.is_some());
        assert_eq!(e.scene(), &scene());
    }
}
