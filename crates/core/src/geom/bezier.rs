//! Bézier curves of any degree (all three papers, docs/math.md §0).

use glam::DVec3;

use super::aabb::Aabb;
use super::{GeomError, ParamCurve};

// Bézier's `Family` side sits in a file of its own: `family.rs` imports the lowering,
// which imports this file for `BezierSegment`.
mod family;

/// Curves of up to this many control points evaluate on the stack (no allocation); more
/// allocate once per call.
pub(crate) const STACK_POINTS: usize = 64;

/// A Bézier curve of degree `n` in 3D (planar curves have `z = 0`):
///
/// `P(t) = Σ_{i=0..n} P_i B_{i,n}(t)`, `t ∈ [0, 1]`, `B_{i,n}(t) = C(n,i) tⁱ (1−t)ⁿ⁻ⁱ`.
///
/// Evaluated by de Casteljau: `P_i⁰ = P_i`, `P_iʲ = (1−t) P_{i−1}ʲ⁻¹ + t P_iʲ⁻¹`,
/// `P(t) = P_nⁿ` (paper 002, §3; used by papers 000 and 001 as well). Any degree `n ≥ 0` is
/// valid here; the GPU has a maximum (see `gpu::layout::MAX_GPU_DEGREE`).
#[derive(Debug, Clone, PartialEq)]
pub struct Bezier {
    points: Vec<DVec3>,
}

/// De Casteljau on `p` itself (overwritten), at `t`: `P_nⁿ`. `p` must not be empty.
pub(crate) fn de_casteljau_in_place(p: &mut [DVec3], t: f64) -> DVec3 {
    let s = 1.0 - t;
    let n = p.len() - 1;
    for r in 1..=n {
        for i in 0..=(n - r) {
            p[i] = s * p[i] + t * p[i + 1];
        }
    }
    p[0]
}

/// The first derivative at `t` of the Bézier curve with control points `points`:
/// `P′(t) = n Σ (P_{i+1} − P_i) B_{i,n−1}(t)` (on the stack up to the usual degrees).
pub(crate) fn deriv_at(points: &[DVec3], t: f64) -> DVec3 {
    let n = points.len().saturating_sub(1);
    if n == 0 {
        return DVec3::ZERO;
    }
    let nf = n as f64;
    if n < STACK_POINTS {
        let mut buf = [DVec3::ZERO; STACK_POINTS];
        for (slot, w) in buf.iter_mut().zip(points.windows(2)) {
            *slot = nf * (w[1] - w[0]);
        }
        de_casteljau(&buf[..n], t)
    } else {
        let d: Vec<DVec3> = points.windows(2).map(|w| nf * (w[1] - w[0])).collect();
        de_casteljau(&d, t)
    }
}

/// The second derivative at `t`:
/// `P″(t) = n(n−1) Σ (P_{i+2} − 2P_{i+1} + P_i) B_{i,n−2}(t)`.
pub(crate) fn second_deriv_at(points: &[DVec3], t: f64) -> DVec3 {
    let n = points.len().saturating_sub(1);
    if n < 2 {
        return DVec3::ZERO;
    }
    let c = (n * (n - 1)) as f64;
    if n - 1 < STACK_POINTS {
        let mut buf = [DVec3::ZERO; STACK_POINTS];
        for (slot, w) in buf.iter_mut().zip(points.windows(3)) {
            *slot = c * (w[2] - 2.0 * w[1] + w[0]);
        }
        de_casteljau(&buf[..n - 1], t)
    } else {
        let second: Vec<DVec3> = points
            .windows(3)
            .map(|w| c * (w[2] - 2.0 * w[1] + w[0]))
            .collect();
        de_casteljau(&second, t)
    }
}

/// Runs de Casteljau on a scratch copy of `points` at `t` and returns `P_nⁿ` (on the stack
/// for up to [`STACK_POINTS`] points).
pub(crate) fn de_casteljau(points: &[DVec3], t: f64) -> DVec3 {
    let run = de_casteljau_in_place;
    if points.is_empty() {
        return DVec3::ZERO;
    }
    if points.len() <= STACK_POINTS {
        let mut buf = [DVec3::ZERO; STACK_POINTS];
        buf[..points.len()].copy_from_slice(points);
        run(&mut buf[..points.len()], t)
    } else {
        run(&mut points.to_vec(), t)
    }
}

impl Bezier {
    /// A Bézier curve with the given control points (degree = `points.len() − 1`).
    ///
    /// # Errors
    /// [`GeomError::TooFewPoints`] for an empty list, [`GeomError::NonFinitePoint`] for a
    /// NaN or infinite coordinate.
    pub fn try_new(points: Vec<DVec3>) -> Result<Bezier, GeomError> {
        if points.is_empty() {
            return Err(GeomError::TooFewPoints { min: 1, found: 0 });
        }
        check_finite(&points)?;
        Ok(Bezier { points })
    }

    /// A Bézier curve from points known to be valid (non-empty, finite).
    ///
    /// # Panics
    /// If `points` is empty: that is a bug in the caller. Use [`Bezier::try_new`] for data.
    #[must_use]
    pub fn new(points: Vec<DVec3>) -> Bezier {
        assert!(
            !points.is_empty(),
            "a Bézier curve needs at least one point"
        );
        Bezier { points }
    }

    /// The degree `n` (number of control points − 1).
    #[must_use]
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }

    /// The control points `P_0..P_n`.
    #[must_use]
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// The point `P(t)` by de Casteljau (also valid for `t` outside `[0, 1]`, where it
    /// extrapolates the polynomial).
    #[must_use]
    pub fn eval(&self, t: f64) -> DVec3 {
        de_casteljau(&self.points, t)
    }

    /// The hodograph `P′` as a Bézier curve of degree `n − 1` with control points
    /// `n (P_{i+1} − P_i)`; for `n = 0` the zero curve of degree 0.
    #[must_use]
    pub fn deriv(&self) -> Bezier {
        let n = self.degree();
        if n == 0 {
            return Bezier::new(vec![DVec3::ZERO]);
        }
        let nf = n as f64;
        Bezier::new(self.points.windows(2).map(|w| nf * (w[1] - w[0])).collect())
    }

    /// `P′(t) = n Σ (P_{i+1} − P_i) B_{i,n−1}(t)`.
    #[must_use]
    pub fn eval_deriv(&self, t: f64) -> DVec3 {
        deriv_at(&self.points, t)
    }

    /// `P″(t) = n(n−1) Σ (P_{i+2} − 2P_{i+1} + P_i) B_{i,n−2}(t)`.
    #[must_use]
    pub fn eval_second_deriv(&self, t: f64) -> DVec3 {
        second_deriv_at(&self.points, t)
    }

    /// Splits at `t` into the curves on `[0, t]` and `[t, 1]`, each reparametrised to
    /// `[0, 1]`, from the de Casteljau triangle: the left polygon is the first point of
    /// each column, the right polygon the last point of each column, reversed.
    #[must_use]
    pub fn split(&self, t: f64) -> (Bezier, Bezier) {
        let n = self.degree();
        let s = 1.0 - t;
        let mut work = self.points.clone();
        let mut left = Vec::with_capacity(n + 1);
        let mut right = vec![DVec3::ZERO; n + 1];
        left.push(work[0]);
        right[n] = work[n];
        for r in 1..=n {
            for i in 0..=(n - r) {
                work[i] = s * work[i] + t * work[i + 1];
            }
            left.push(work[0]);
            right[n - r] = work[n - r];
        }
        (Bezier::new(left), Bezier::new(right))
    }

    /// The piece of the curve on `[t0, t1]` reparametrised to `[0, 1]`
    /// (`Q(u) = P(t0 + u (t1 − t0))`). `t0 > t1` gives the reversed piece.
    #[must_use]
    pub fn subsegment(&self, t0: f64, t1: f64) -> Bezier {
        if t0 == 0.0 && t1 == 1.0 {
            return self.clone();
        }
        if t0 > t1 {
            // Interpolate on [t1, t0] (stable), then reverse.
            return self.subsegment(t1, t0).reversed();
        }
        if t1 != 0.0 {
            // The left piece L(u) = P(u t1); its right part from u = t0/t1 ∈ [0, 1] is
            // L(t0/t1 + v (1 − t0/t1)) = P(t0 + v (t1 − t0)).
            let (left, _) = self.split(t1);
            left.split(t0 / t1).1
        } else if t0 == 0.0 {
            // t0 = t1 = 0: the piece is the point P(0).
            Bezier::new(vec![self.points[0]; self.points.len()])
        } else {
            // t0 < t1 = 0 (extrapolation): R(v) = P(t0 + v (1 − t0)) is the right piece at
            // t0, and the wanted piece is R on [0, −t0 / (1 − t0)].
            let (_, right) = self.split(t0);
            right.split(-t0 / (1.0 - t0)).0
        }
    }

    /// The same curve traversed backwards (`Q(t) = P(1 − t)`).
    #[must_use]
    pub fn reversed(&self) -> Bezier {
        let mut points = self.points.clone();
        points.reverse();
        Bezier::new(points)
    }

    /// The unit end-tangent directions `e_1 = unit(P_1 − P_0)`, `e_2 = unit(P_{n−1} − P_n)`,
    /// or `None` when an end point coincides with its neighbour (or the degree is 0).
    #[must_use]
    pub fn end_directions(&self) -> Option<[DVec3; 2]> {
        let p = &self.points;
        let n = p.len() - 1;
        if n == 0 {
            return None;
        }
        Some([
            (p[1] - p[0]).try_normalize()?,
            (p[n - 1] - p[n]).try_normalize()?,
        ])
    }

    /// Degree elevation by one: `Q_i = (i/(n+1)) P_{i−1} + (1 − i/(n+1)) P_i`,
    /// `i = 0..n+1`. The curve does not change.
    #[must_use]
    pub fn elevate(&self) -> Bezier {
        let n = self.degree();
        let m = (n + 1) as f64;
        let mut q = Vec::with_capacity(n + 2);
        q.push(self.points[0]);
        for i in 1..=n {
            let a = i as f64 / m;
            q.push(a * self.points[i - 1] + (1.0 - a) * self.points[i]);
        }
        q.push(self.points[n]);
        Bezier::new(q)
    }

    /// The curve elevated to `degree` (unchanged when `degree ≤ self.degree()`).
    #[must_use]
    pub fn elevated_to(&self, degree: usize) -> Bezier {
        let mut b = self.clone();
        while b.degree() < degree {
            b = b.elevate();
        }
        b
    }

    /// How far the control polygon strays from the chord `P_0P_n`: the largest distance of
    /// a control point from the line through the end points (from `P_0` when the ends
    /// coincide). The curve lies within this distance of the line (convex hull property),
    /// so 0 means the curve is straight.
    #[must_use]
    pub fn flatness(&self) -> f64 {
        polygon_flatness(&self.points)
    }

    /// The box of the control points: it holds the curve (convex hull property).
    #[must_use]
    pub fn control_box(&self) -> Aabb {
        Aabb::from_points(&self.points)
    }

    /// The tight bounding box of the curve on `[0, 1]`: the end points and the points where
    /// a coordinate's derivative vanishes, found by the analysis' Bernstein root finder
    /// ([`crate::poly::roots::bernstein_roots`], polished to full precision).
    #[must_use]
    pub fn bounding_box(&self) -> Aabb {
        let n = self.degree();
        let mut bbox = Aabb::from_points(&[self.points[0], self.points[n]]);
        if n < 2 {
            return bbox;
        }
        let hodograph = self.deriv();
        for axis in 0..3 {
            let coeffs: Vec<f64> = hodograph.points.iter().map(|p| p[axis]).collect();
            for root in crate::poly::roots::bernstein_roots(&coeffs).roots {
                bbox = bbox.including(self.eval(root.t));
            }
        }
        bbox
    }
}

/// Checks every coordinate of `points` is finite.
pub(crate) fn check_finite(points: &[DVec3]) -> Result<(), GeomError> {
    for (index, p) in points.iter().enumerate() {
        for value in p.to_array() {
            if !value.is_finite() {
                return Err(GeomError::NonFinitePoint { index, value });
            }
        }
    }
    Ok(())
}

impl ParamCurve for Bezier {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, t: f64) -> DVec3 {
        Bezier::eval(self, t)
    }
    fn eval_deriv(&self, t: f64) -> DVec3 {
        Bezier::eval_deriv(self, t)
    }
    fn eval_second_deriv(&self, t: f64) -> DVec3 {
        Bezier::eval_second_deriv(self, t)
    }
}

/// How far the points `P_0 … P_n` stray from the chord `P_0P_n`: the largest distance of
/// a point from the line through the end points (from `P_0` when the ends coincide).
pub(crate) fn polygon_flatness(points: &[DVec3]) -> f64 {
    let a = points[0];
    let chord = points[points.len() - 1] - a;
    let len2 = chord.length_squared();
    points
        .iter()
        .map(|&q| {
            let w = q - a;
            if len2 > 0.0 {
                (w - chord * (w.dot(chord) / len2)).length()
            } else {
                w.length()
            }
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::bernstein::bernstein;

    fn cubic() -> Bezier {
        Bezier::new(vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(3.0, 2.0, 1.0),
            DVec3::new(4.0, 0.0, -1.0),
        ])
    }

    #[test]
    fn flatness_is_the_polygon_distance_from_the_chord() {
        // Chord along x; the inner points stand 2 and 3 off it.
        let b = Bezier::new(vec![
            DVec3::ZERO,
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(3.0, 0.0, 3.0),
            DVec3::new(4.0, 0.0, 0.0),
        ]);
        assert_eq!(b.flatness(), 3.0);
        let line = Bezier::new(vec![DVec3::ZERO, DVec3::X, DVec3::X * 5.0]);
        assert_eq!(line.flatness(), 0.0);
        // Closed curve: measured from the shared end point.
        let closed = Bezier::new(vec![DVec3::ZERO, DVec3::new(3.0, 4.0, 0.0), DVec3::ZERO]);
        assert_eq!(closed.flatness(), 5.0);
    }

    #[test]
    fn box_distance_is_zero_inside_and_euclidean_outside() {
        let b = Aabb::from_points(&[DVec3::ZERO, DVec3::new(1.0, 1.0, 1.0)]);
        assert_eq!(b.distance_to(DVec3::splat(0.5)), 0.0);
        assert_eq!(b.distance_to(DVec3::new(1.0, 0.5, 0.0)), 0.0);
        assert_eq!(b.distance_to(DVec3::new(4.0, 5.0, 0.5)), 5.0);
        assert_eq!(b.distance_to(DVec3::new(-2.0, 0.5, 0.5)), 2.0);
    }

    #[test]
    fn de_casteljau_matches_bernstein_sum() {
        let b = cubic();
        for k in 0..=16 {
            let t = k as f64 / 16.0;
            let want: DVec3 = b
                .points()
                .iter()
                .enumerate()
                .map(|(i, &p)| p * bernstein(i, 3, t))
                .sum();
            assert!((b.eval(t) - want).length() < 1e-14);
        }
    }

    #[test]
    fn end_points_are_interpolated_exactly() {
        let b = cubic();
        assert_eq!(b.eval(0.0), b.points()[0]);
        assert_eq!(b.eval(1.0), b.points()[3]);
    }

    #[test]
    fn end_derivatives_are_n_times_the_end_legs() {
        // Paper 002: Q'(0) = n (P1 − P0), Q'(1) = n (Pn − P_{n−1}).
        let b = cubic();
        let p = b.points();
        assert_eq!(b.eval_deriv(0.0), 3.0 * (p[1] - p[0]));
        assert_eq!(b.eval_deriv(1.0), 3.0 * (p[3] - p[2]));
        assert_eq!(b.eval_second_deriv(0.0), 6.0 * (p[2] - 2.0 * p[1] + p[0]));
    }

    #[test]
    fn bounding_box_of_a_parabola_is_exact() {
        // P(t) = (2t, 4t(1−t)): y peaks at t = 1/2 with value 1.
        let b = Bezier::new(vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
        ]);
        let bb = b.bounding_box();
        assert!((bb.max.y - 1.0).abs() < 1e-12);
        assert_eq!(bb.min.y, 0.0);
        assert_eq!((bb.min.x, bb.max.x), (0.0, 2.0));
        assert!(b.control_box().max.y == 2.0);
    }

    #[test]
    fn empty_and_non_finite_points_are_errors() {
        assert_eq!(
            Bezier::try_new(vec![]),
            Err(GeomError::TooFewPoints { min: 1, found: 0 })
        );
        let err = Bezier::try_new(vec![DVec3::ZERO, DVec3::new(0.0, f64::NAN, 0.0)]).unwrap_err();
        assert_eq!(err.field(), "points[1]");
    }
}
