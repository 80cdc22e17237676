//! The viewer's editing model, free of GPU and window types: picking, dragging control
//! points, pulling a Bézier curve through the pointer (paper 000's single-target solve),
//! setting a curve from the panel, structural edits (curves added, duplicated, deleted;
//! points inserted, removed, typed), undo/redo that keeps every edit and atomic saving;
//! the recovery file that holds unsaved edits until they are saved or discarded is kept
//! by `edit/recovery.rs`.

use std::path::{Path, PathBuf};

use glam::DVec3;

use splinescope_core::geom::Curve;
use splinescope_present::{Control, ControlValue, Present};
use splinescope_scene::format::{Scene, SceneCurve};

mod gesture;
mod recovery;
mod structure;
pub use recovery::{legacy_recovery_path, recovery_dir, recovery_path};

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
        reason: splinescope_core::geom::GeomError,
    },
    /// A typed control point the curve refused.
    #[error("curves[{index}].points[{point}]: {reason}")]
    Point {
        /// The curve.
        index: usize,
        /// The point.
        point: usize,
        /// What the family said.
        reason: splinescope_core::geom::GeomError,
    },
    /// An edit that would leave a curve the renderer cannot draw (its degree over the
    /// GPU's maximum): refused where it is made, the curve kept as it was.
    #[error(
        "curves[{index}]: {what} would raise its degree to {degree}, over the GPU maximum of {max} — the curve is kept as it was"
    )]
    Undrawable {
        /// The curve.
        index: usize,
        /// The edit.
        what: &'static str,
        /// The degree it would have.
        degree: usize,
        /// The GPU's maximum.
        max: usize,
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
    Pull(#[from] splinescope_core::solve::SolveError),
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
    /// The whole list before the gesture began, once curves were replaced from outside
    /// during it ([`Editor::replace_curves`]): the gesture then commits as one list edit.
    list_before: Option<Vec<SceneCurve>>,
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
    /// its form ([`splinescope_scene::format::to_json_string_keeping`]).
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
    /// A failure the user must not miss — a save that failed (and whether the recovery
    /// file holds the edits), an edit the renderer could not take — shown in the warning
    /// colour at the top of the panel until a save succeeds or it is dismissed.
    pub warning: Option<String>,
    /// Whether the last write of the recovery file failed.
    recovery_failed: bool,
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
            warning: None,
            recovery_failed: false,
        }
    }

    /// An editor of the scene read from `path` as `text` ([`Scene::read`]): saving keeps
    /// that text's form ([`splinescope_scene::format::to_json_string_keeping`]).
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
                list_before: None,
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

    /// Applies one of a family's panel controls ([`splinescope_present::Present::controls`]) to
    /// curve `index`. A refused value (or one whose derived data overflows) leaves the
    /// curve as it was and sets [`Editor::message`]; a discrete control (button, toggle,
    /// choice) is one edit on its own, a stream of slider changes is one edit together.
    pub fn apply_control(&mut self, index: usize, control: &Control, value: ControlValue) {
        let result = self.scene.curves[index]
            .curve
            .apply_control(control.id, value)
            .and_then(|c| Ok(c.check_derived().map(|()| c)?));
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
        if let Some(before) = open.list_before {
            if before != self.scene.curves {
                self.commit(Change::List {
                    before,
                    after: self.scene.curves.clone(),
                });
            }
            return;
        }
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
        if let Some(before) = open.list_before {
            self.set_list(before);
            self.message = Some("edit cancelled".into());
            return true;
        }
        if self.scene.curves[open.curve] != open.before {
            self.set(open.curve, open.before);
        }
        self.message = Some("edit cancelled".into());
        true
    }

    /// Replaces the curves with `curves` (a scene assigned from outside the editor, such
    /// as a solver run on each drag): one undoable edit. During a drag of a control point
    /// that `curves` still has, the drag goes on over the new curves and the whole
    /// gesture, the replacement included, commits as one edit when it finishes; any other
    /// open edit is committed first. The selection is kept where it still names a curve
    /// and a point.
    pub fn replace_curves(&mut self, curves: Vec<SceneCurve>) {
        let keeps_drag = self.open.as_ref().is_some_and(|open| match open.gesture {
            Gesture::Point { index } => curves
                .get(open.curve)
                .is_some_and(|c| index < c.curve.control_points().len()),
            _ => false,
        });
        if !keeps_drag {
            self.finish();
        }
        let (selected, selected_point) = (self.selected, self.selected_point);
        let before = self.scene.curves.clone();
        if before == curves {
            return;
        }
        match self.open.as_mut() {
            Some(open) => {
                if open.list_before.is_none() {
                    let mut list = before;
                    list[open.curve] = open.before.clone();
                    open.list_before = Some(list);
                }
                self.set_list(curves);
            }
            None => {
                self.set_list(curves.clone());
                self.commit(Change::List {
                    before,
                    after: curves,
                });
            }
        }
        self.selected = selected.filter(|&i| i < self.scene.curves.len());
        self.selected_point = selected_point.filter(|&p| {
            self.selected
                .is_some_and(|i| p < self.scene.curves[i].curve.control_points().len())
        });
    }

    /// Replaces the scene with `scene`: its curves as [`Editor::replace_curves`] does,
    /// its other fields (name, view, background, annotations) as they are, outside the
    /// history.
    pub fn replace_scene(&mut self, mut scene: Scene) {
        let curves = std::mem::replace(&mut scene.curves, std::mem::take(&mut self.scene.curves));
        self.scene = scene;
        self.replace_curves(curves);
        self.list_changed = true;
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
            Some(source) => splinescope_scene::format::to_json_string_keeping(&self.scene, source),
            None => splinescope_scene::format::to_json_string(&self.scene),
        };
        if let Err(reason) = splinescope_io::files::write_atomic(&path, text.as_bytes()) {
            // Said where it cannot be missed, with where the edits are kept.
            let kept = match self.path.as_deref() {
                None => " — the edits are kept in this window only (the scene has no file yet)"
                    .to_owned(),
                Some(_) if self.recovery_failed => {
                    " — the edits are kept in this window only: the recovery file could not be written either".to_owned()
                }
                Some(own) if self.committed_dirty() => format!(
                    " — the edits are kept in this window and in {}",
                    recovery::recovery_path(own).display()
                ),
                Some(_) => " — the edits are kept in this window".to_owned(),
            };
            let e = EditError::Save {
                path: path.clone(),
                reason,
            };
            self.warning = Some(format!("{e}{kept}"));
            return Err(e);
        }
        self.warning = None;
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
}

#[cfg(test)]
mod tests;
