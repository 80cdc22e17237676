//! The nearest point of a curve to a given point: the global minimum of the distance
//! over the whole curve, never a local one.
//!
//! On each lowered segment the distance to `p` is stationary exactly where
//! `(C(u) − p) · C′(u) = 0`; times a positive factor (`W³` for a rational segment) that is
//! a polynomial in Bernstein form ([`Piece::nearest_numerator`]), and **every** root of it
//! in `[0, 1]` is isolated by [`bernstein_roots_with_noise`] (subdivision by the
//! variation-diminishing property: an interval is dropped only when its coefficients show
//! it has no root). The global minimum is at one of those roots or at a segment's end, so
//! the least distance over all of them is the least distance on the curve, up to how
//! well each root is known. Segments whose control box is farther than the best distance
//! found cannot hold a nearer point (a segment lies in the hull of its control points) and
//! are passed over.
//!
//! **The bound** ([`Nearest::error`]): each root `t̃` carries a bound `e` on its distance
//! to an exact root `t*`; the distance at `t̃` exceeds the distance at `t*` by at most
//! `e · max|C′|`, and `max|C′|` is at most [`Piece::speed_bound`]. So the distance
//! returned is at least the true least distance (it is the distance of a point on the
//! curve, up to the rounding of evaluating it) and at most that plus `error` (which also
//! covers the rounding of evaluating `C(t)` and of telling two distances apart).

use glam::{DVec2, DVec3};

use super::{AnalysisError, CurveAnalysis};
use crate::poly::roots::bernstein_roots_with_noise;

/// The nearest point of a curve to a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nearest {
    /// Where: the curve's parameter (the smallest among points equally near, as far as
    /// the rounding tells them apart).
    pub t: f64,
    /// How far: the distance from the point to `C(t)`.
    pub distance: f64,
    /// A bound on `distance` less the true least distance (it is never less than it, but
    /// for the rounding of evaluating `C(t)`, which this includes).
    pub error: f64,
}

/// The distance from `p` to the box `(lo, hi)`: 0 inside it.
fn box_distance(p: DVec2, (lo, hi): (DVec2, DVec2)) -> f64 {
    (lo - p).max(p - hi).max(DVec2::ZERO).length()
}

impl CurveAnalysis {
    /// The point of the curve nearest to `p` (see the module docs): its parameter, its
    /// distance and the bound on how far that distance may exceed the least one. A 2D
    /// curve and a point off its plane: the distance counts the point's `z`.
    ///
    /// The middle of this arch is nearest to `(2, 0)`, at distance 1.5:
    ///
    /// ```
    /// use glam::DVec3;
    /// use splinescope_core::analysis::CurveAnalysis;
    /// use splinescope_core::geom::Bezier;
    ///
    /// let arch = Bezier::new(vec![
    ///     DVec3::ZERO,
    ///     DVec3::new(1.0, 2.0, 0.0),
    ///     DVec3::new(3.0, 2.0, 0.0),
    ///     DVec3::new(4.0, 0.0, 0.0),
    /// ]);
    /// let analysis = CurveAnalysis::new(&arch);
    /// let near = analysis.nearest(DVec3::new(2.0, 0.0, 0.0)).unwrap();
    /// assert!((near.t - 0.5).abs() < 1e-12 && (near.distance - 1.5).abs() < 1e-12);
    /// assert!(near.error <= 1e-12);
    /// ```
    ///
    /// # Errors
    /// [`AnalysisError::NotFinitePoint`] for a point with a coordinate that is not
    /// finite.
    pub fn nearest(&self, p: DVec3) -> Result<Nearest, AnalysisError> {
        if !p.is_finite() {
            return Err(AnalysisError::NotFinitePoint { point: p });
        }
        let dims = if self.is_planar() { 2 } else { 3 };
        let pieces = self.pieces();
        // Nearest boxes first: once a box is farther than the best distance, every later
        // one is too.
        let mut order: Vec<(f64, usize)> = pieces
            .iter()
            .enumerate()
            .map(|(i, piece)| (box_distance(p.truncate(), piece.bounds()), i))
            .collect();
        order.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut best: Option<Nearest> = None;
        let mut error: f64 = 0.0;
        for (low, i) in order {
            if best.is_some_and(|b| low > b.distance) {
                break;
            }
            let piece = &pieces[i];
            let (c, noise) = piece.nearest_numerator(p, dims);
            let roots = bernstein_roots_with_noise(&c, noise);
            let speed = piece.speed_bound();
            let mut consider = |u: f64, e: f64| {
                let q = piece.point(u);
                let d = (q - p).length();
                let t = piece.t_of(u);
                // Equally near, as far as the rounding of two distances tells: the smaller
                // parameter.
                let better = match best {
                    None => true,
                    Some(b) => {
                        let tie = 64.0 * f64::EPSILON * (p.length() + q.length() + d);
                        if (d - b.distance).abs() <= tie {
                            t < b.t
                        } else {
                            d < b.distance
                        }
                    }
                };
                if better {
                    best = Some(Nearest {
                        t,
                        distance: d,
                        error: 0.0,
                    });
                }
                let tie = 64.0 * f64::EPSILON * (p.length() + q.length() + d);
                error = error.max(e * speed + piece.point_error(u) + tie);
            };
            consider(0.0, 0.0);
            consider(1.0, 0.0);
            for r in &roots.roots {
                consider(r.t, r.error);
            }
        }
        let mut best = best.unwrap_or_else(|| unreachable!("a curve has at least one segment"));
        best.error = error;
        Ok(best)
    }

    /// [`CurveAnalysis::nearest`] for each of `points`, over every core.
    #[must_use]
    pub fn nearest_many(&self, points: &[DVec3]) -> Vec<Result<Nearest, AnalysisError>> {
        use rayon::prelude::*;
        points.par_iter().map(|&p| self.nearest(p)).collect()
    }
}
