//! Structure edits: adding, duplicating and deleting curves, inserting, deleting and
//! moving control points — each one undoable step.

use glam::DVec3;

use super::{Change, EditError, Editor};
use splinescope_core::geom::Curve;
use splinescope_core::solve::nearest;
use splinescope_scene::format::SceneCurve;

impl Editor {
    /// Curve `index`, or a message saying it does not exist.
    fn curve_at(&self, index: usize) -> Result<&SceneCurve, EditError> {
        self.scene
            .curves
            .get(index)
            .ok_or(EditError::NoSuchCurve { index })
    }

    /// Replaces the list of curves as one undoable edit, selecting `select`.
    pub(super) fn edit_list(&mut self, after: Vec<SceneCurve>, select: Option<usize>) {
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
        // A Bézier curve gains a degree with each point: past the GPU's maximum the
        // renderer could not draw it, so the edit is refused here.
        let degree =
            splinescope_core::geom::max_degree(&splinescope_core::geom::Lower::lower(&curve));
        if degree > splinescope_gpu::layout::MAX_GPU_DEGREE {
            return Err(EditError::Undrawable {
                index,
                what: "inserting a point",
                degree,
                max: splinescope_gpu::layout::MAX_GPU_DEGREE,
            });
        }
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
