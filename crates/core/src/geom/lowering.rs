//! Lowering: every curve family becomes a list of Bézier segments — polynomial, or
//! rational with one weight per control point — each with the parameter range it covers
//! in the curve's own parameter. This list is the single representation the GPU
//! tessellates.

use glam::DVec3;

use super::{Bezier, ParamCurve};

/// One Bézier piece of a lowered curve.
///
/// Curve parameter `t ∈ [t0, t1]` maps to the segment's own `u = (t − t0) / (t1 − t0)`;
/// the curve there equals `bezier.eval(u)` for a polynomial piece (`weights` is `None`)
/// and `Σ w_i P_i B_i(u) / Σ w_i B_i(u)` for a rational one ([`BezierSegment::eval`]).
#[derive(Debug, Clone, PartialEq)]
pub struct BezierSegment {
    /// The piece's control points `P_i`, parametrised over `[0, 1]`.
    pub bezier: Bezier,
    /// The weights `w_i > 0` of a rational piece (one per control point); `None` for a
    /// polynomial piece.
    pub weights: Option<Vec<f64>>,
    /// The curve parameter where the piece starts.
    pub t0: f64,
    /// The curve parameter where the piece ends (`t1 > t0`).
    pub t1: f64,
}

impl BezierSegment {
    /// A polynomial piece.
    #[must_use]
    pub fn polynomial(bezier: Bezier, t0: f64, t1: f64) -> BezierSegment {
        BezierSegment {
            bezier,
            weights: None,
            t0,
            t1,
        }
    }

    /// The segment's own parameter `u` for curve parameter `t`.
    #[must_use]
    pub fn local_u(&self, t: f64) -> f64 {
        (t - self.t0) / (self.t1 - self.t0)
    }

    /// The control points.
    #[must_use]
    pub fn points(&self) -> &[DVec3] {
        self.bezier.points()
    }

    /// The degree.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.bezier.degree()
    }

    /// Whether the piece is rational (has weights).
    #[must_use]
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }

    /// The piece's homogeneous parts as polynomial Bézier curves: `A` (the points times
    /// their weights) and `W` (the weights as `(w_i, 0, 0)`); for a polynomial piece `A`
    /// is the piece and `W` the constant 1.
    #[must_use]
    pub fn homogeneous(&self) -> (Bezier, Bezier) {
        let w = |i: usize| self.weights.as_ref().map_or(1.0, |w| w[i]);
        let points = self.points().iter().enumerate();
        (
            Bezier::new(points.clone().map(|(i, p)| *p * w(i)).collect()),
            Bezier::new(points.map(|(i, _)| DVec3::new(w(i), 0.0, 0.0)).collect()),
        )
    }

    /// The point at the segment's own parameter `u`: de Casteljau on the control points,
    /// or on the homogeneous parts (then divided) for a rational piece.
    #[must_use]
    pub fn eval(&self, u: f64) -> DVec3 {
        if self.weights.is_none() {
            return self.bezier.eval(u);
        }
        let (a, w) = self.homogeneous();
        a.eval(u) / w.eval(u).x
    }
}

/// A curve that can be written exactly as consecutive Bézier segments.
pub trait Lower: ParamCurve {
    /// The exact Bézier segments, in parameter order, covering the whole domain.
    fn lower(&self) -> Vec<BezierSegment>;
}

/// Finds the segment holding curve parameter `t` and the local parameter there.
///
/// Segments are searched by their start parameter; a `t` on a joint belongs to the later
/// segment, except the domain's end, which belongs to the last one. Parameters outside the
/// domain extrapolate the first or last segment. Returns `None` for an empty list.
#[must_use]
pub fn locate(segments: &[BezierSegment], t: f64) -> Option<(usize, f64)> {
    if segments.is_empty() {
        return None;
    }
    // Index of the last segment whose t0 ≤ t (0 when t is before the first).
    let index = segments
        .partition_point(|s| s.t0 <= t)
        .saturating_sub(1)
        .min(segments.len() - 1);
    Some((index, segments[index].local_u(t)))
}

/// The highest degree among `segments` (0 for none): what a lowered curve needs of a
/// kernel.
#[must_use]
pub fn max_degree(segments: &[BezierSegment]) -> usize {
    segments
        .iter()
        .map(|s| s.bezier.degree())
        .max()
        .unwrap_or(0)
}

impl Lower for Bezier {
    fn lower(&self) -> Vec<BezierSegment> {
        vec![BezierSegment::polynomial(self.clone(), 0.0, 1.0)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seg(t0: f64, t1: f64) -> BezierSegment {
        BezierSegment::polynomial(Bezier::new(vec![DVec3::ZERO, DVec3::X]), t0, t1)
    }

    #[test]
    fn locate_picks_the_later_segment_on_joints_and_the_last_at_the_end() {
        let segs = vec![seg(0.0, 1.0), seg(1.0, 3.0), seg(3.0, 4.0)];
        assert_eq!(locate(&segs, 0.0), Some((0, 0.0)));
        assert_eq!(locate(&segs, 0.5), Some((0, 0.5)));
        assert_eq!(locate(&segs, 1.0), Some((1, 0.0)));
        assert_eq!(locate(&segs, 2.0), Some((1, 0.5)));
        assert_eq!(locate(&segs, 4.0), Some((2, 1.0)));
        assert_eq!(locate(&segs, -1.0), Some((0, -1.0)));
        assert_eq!(locate(&[], 0.0), None);
    }
}
