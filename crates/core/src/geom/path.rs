//! The path: Bézier segments of any degree, each polynomial or rational, joined end to
//! end, open or closed — what an SVG subpath, a glyph contour, a DXF polyline and a STEP
//! composite curve are.
//!
//! Segment `k` (of `K`) covers the parameters `[k, k + 1]`:
//!
//! `C(t) = S_k(t − k)`, `S_k(u) = Σ_i w_{k,i} P_{k,i} B_{i,n_k}(u) / Σ_i w_{k,i} B_{i,n_k}(u)`,
//!
//! with `w_{k,i} = 1` for a polynomial segment; the domain is `[0, K]`. Consecutive
//! segments share their end point (`P_{k,n_k} = P_{k+1,0}`); a closed path's last
//! segment ends where the first starts. A gap beyond rounding is refused, naming the
//! joint. The segments are kept exactly as given ([`Path::segments`]: a quadratic stays a
//! quadratic with its three points, its weights as given), and the path lowers to them
//! one for one.
//!
//! Its control points ([`Family::control_points`]) list each shared end point once —
//! segment 0's points, then each further segment's without its first (and a closed path
//! without its last) — so moving a joint moves both segments that meet there.

use glam::DVec3;

use super::bezier::{de_casteljau, deriv_at, second_deriv_at};
use super::family::Family;
use super::rational::normalised_weights;
use super::{Bezier, BezierSegment, GeomError, Lower, ParamCurve, RationalBezier};

/// A segment's control points: up to a cubic's four held inline (a font or a drawing
/// has hundreds of thousands of segments; one allocation each would cost most of reading
/// it), more on the heap.
pub type SegmentPoints = smallvec::SmallVec<[DVec3; 4]>;

/// One segment of a path: its control points `P_0 … P_n` (degree `n ≥ 1`) and, for a
/// rational segment, one weight per point.
#[derive(Debug, Clone, PartialEq)]
pub struct PathSegment {
    /// The control points.
    pub points: SegmentPoints,
    /// The weights (each a finite number greater than 0) of a rational segment; `None`
    /// for a polynomial one.
    pub weights: Option<Vec<f64>>,
}

impl PathSegment {
    /// A polynomial segment.
    #[must_use]
    pub fn polynomial(points: impl Into<SegmentPoints>) -> PathSegment {
        PathSegment {
            points: points.into(),
            weights: None,
        }
    }

    /// A rational segment.
    #[must_use]
    pub fn rational(points: impl Into<SegmentPoints>, weights: Vec<f64>) -> PathSegment {
        PathSegment {
            points: points.into(),
            weights: Some(weights),
        }
    }

    /// The degree (`points − 1`).
    #[must_use]
    pub fn degree(&self) -> usize {
        self.points.len().saturating_sub(1)
    }

    /// The piece of the segment on `[u0, u1]` (within `[0, 1]`), reparametrised to
    /// `[0, 1]`: de Casteljau's subdivision of its points (of a rational one, of its
    /// homogeneous points `(w P, w)`, the weights then those of the piece). `u0 > u1`
    /// gives the piece reversed.
    #[must_use]
    pub fn restricted(&self, u0: f64, u1: f64) -> PathSegment {
        match &self.weights {
            None => PathSegment::polynomial(
                Bezier::new(self.points.to_vec())
                    .subsegment(u0, u1)
                    .points()
                    .to_vec(),
            ),
            Some(w) => {
                let hp: Vec<DVec3> = self.points.iter().zip(w).map(|(p, w)| *p * *w).collect();
                let hw: Vec<DVec3> = w.iter().map(|w| DVec3::new(*w, 0.0, 0.0)).collect();
                let hp = Bezier::new(hp).subsegment(u0, u1);
                let hw = Bezier::new(hw).subsegment(u0, u1);
                let weights: Vec<f64> = hw.points().iter().map(|v| v.x).collect();
                let points: Vec<DVec3> = hp
                    .points()
                    .iter()
                    .zip(&weights)
                    .map(|(p, w)| *p / *w)
                    .collect();
                PathSegment::rational(points, weights)
            }
        }
    }
}

/// Checks a segment: at least two points, every coordinate finite, and for a rational
/// one its weights; the rational curve it evaluates by (a polynomial segment evaluates
/// from its own points, with no copy).
fn checked(s: &PathSegment) -> Result<Option<RationalBezier>, GeomError> {
    if s.points.len() < 2 {
        return Err(GeomError::TooFewPoints {
            min: 2,
            found: s.points.len(),
        });
    }
    for (index, p) in s.points.iter().enumerate() {
        if let Some(&value) = p.to_array().iter().find(|v| !v.is_finite()) {
            return Err(GeomError::NonFinitePoint { index, value });
        }
    }
    s.weights
        .as_ref()
        .map(|w| RationalBezier::try_new(s.points.to_vec(), w.clone()))
        .transpose()
}

/// A path: Bézier segments joined end to end (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Path {
    segments: Vec<PathSegment>,
    /// Per segment, the rational curve a rational one evaluates by; empty when no
    /// segment is rational (a font's thousands of contours allocate nothing for it).
    rational: Vec<Option<RationalBezier>>,
    points: Vec<DVec3>,
    closed: bool,
}

/// Two end points closer than this, relative to the larger coordinate of the two
/// segments, are one point: an importer's transforms round each end on its own.
const JOIN_ROUNDING: f64 = 256.0 * f64::EPSILON;

/// The largest absolute coordinate of a segment's points.
fn size_of(s: &PathSegment) -> f64 {
    s.points
        .iter()
        .map(|p| p.abs().max_element())
        .fold(0.0, f64::max)
}

/// The gap between one segment's end `p` and the next's start `q`, when it is beyond
/// rounding relative to `size`, the larger coordinate of the two segments.
fn gap(p: DVec3, q: DVec3, size: f64) -> Option<f64> {
    let d = (p - q).length();
    (d > JOIN_ROUNDING * size).then_some(d)
}

impl Path {
    /// A path of `segments` (at least one), open or `closed`.
    ///
    /// # Errors
    /// [`GeomError::NoSegments`]; [`GeomError::InSegment`] for a segment with fewer than
    /// two points, a non-finite coordinate or bad weights; [`GeomError::PathGap`] where
    /// consecutive segments (or a closed path's last and first) do not share their end
    /// point.
    pub fn try_new(segments: Vec<PathSegment>, closed: bool) -> Result<Path, GeomError> {
        if segments.is_empty() {
            return Err(GeomError::NoSegments);
        }
        // One pass: each segment checked, its joint with the one before measured (each
        // segment's size computed once), its points appended.
        let mut rational: Vec<Option<RationalBezier>> = Vec::new();
        let mut points: Vec<DVec3> =
            Vec::with_capacity(segments.iter().map(|s| s.points.len()).sum::<usize>() + 1);
        let mut sizes = (0.0, 0.0);
        for (segment, s) in segments.iter().enumerate() {
            let r = checked(s).map_err(|e| GeomError::InSegment {
                segment,
                error: Box::new(e),
            })?;
            if let Some(r) = r {
                rational.resize_with(segment, || None);
                rational.push(Some(r));
            }
            let size = size_of(s);
            if segment == 0 {
                sizes = (size, size);
                points.extend_from_slice(&s.points);
                continue;
            }
            let joint = segment - 1;
            if let Some(gap) = gap(points[points.len() - 1], s.points[0], sizes.1.max(size)) {
                return Err(GeomError::PathGap {
                    joint,
                    next: segment,
                    gap,
                });
            }
            sizes.1 = size;
            points.extend_from_slice(&s.points[1..]);
        }
        if !rational.is_empty() {
            rational.resize_with(segments.len(), || None);
        }
        let k = segments.len();
        if closed {
            // The last segment's end against the first's start.
            if let Some(gap) = gap(points[points.len() - 1], points[0], sizes.0.max(sizes.1)) {
                return Err(GeomError::PathGap {
                    joint: k - 1,
                    next: 0,
                    gap,
                });
            }
            points.pop();
        }
        Ok(Path {
            segments,
            rational,
            points,
            closed,
        })
    }

    /// The segments, exactly as given (or as the last edit of the control points left
    /// them).
    #[must_use]
    pub fn segments(&self) -> &[PathSegment] {
        &self.segments
    }

    /// Whether the last segment ends where the first starts.
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// The open path from parameter `t0` to `t1` (`0 ≤ t0 < t1 ≤` the segment count):
    /// the segments between, the first and last cut exactly ([`PathSegment::restricted`]),
    /// so that it traces the same points with the same parametrisation shifted by `t0`
    /// within each segment.
    ///
    /// # Errors
    /// [`GeomError::ParameterOutsideDomain`] for `t0` or `t1` outside the domain or
    /// `t0 ≥ t1`.
    pub fn between(&self, t0: f64, t1: f64) -> Result<Path, GeomError> {
        let end = self.segments.len() as f64;
        for t in [t0, t1] {
            if !(0.0..=end).contains(&t) || t0 >= t1 {
                return Err(GeomError::ParameterOutsideDomain {
                    value: t,
                    start: 0.0,
                    end,
                });
            }
        }
        let (k0, u0) = self.locate(t0);
        // `t1` on a joint ends the segment before it.
        let (k1, u1) = if t1.fract() == 0.0 && t1 > 0.0 {
            (t1 as usize - 1, 1.0)
        } else {
            self.locate(t1)
        };
        let pieces: Vec<PathSegment> = (k0..=k1)
            .map(|k| {
                let a = if k == k0 { u0 } else { 0.0 };
                let b = if k == k1 { u1 } else { 1.0 };
                if a == 0.0 && b == 1.0 {
                    self.segments[k].clone()
                } else {
                    self.segments[k].restricted(a, b)
                }
            })
            .collect();
        Path::try_new(pieces, false)
    }

    /// The index, in [`Family::control_points`], of segment `k`'s first point.
    fn start_of(&self, k: usize) -> usize {
        self.segments[..k].iter().map(PathSegment::degree).sum()
    }

    /// The index in [`Family::control_points`] of point `i` of segment `k`.
    fn flat_index(&self, k: usize, i: usize) -> usize {
        let at = self.start_of(k) + i;
        if self.closed && at == self.points.len() {
            0
        } else {
            at
        }
    }

    /// The segment holding `t` and the local parameter there: `t` on a joint belongs to
    /// the later segment, the domain's end to the last; outside the domain the first or
    /// last segment extrapolates.
    fn locate(&self, t: f64) -> (usize, f64) {
        let last = self.segments.len() - 1;
        let k = if t.is_nan() || t < 0.0 {
            0
        } else {
            // `as` saturates: t beyond usize is the last segment.
            (t.floor() as usize).min(last)
        };
        (k, t - k as f64)
    }
}

impl ParamCurve for Path {
    fn domain(&self) -> (f64, f64) {
        (0.0, self.segments.len() as f64)
    }

    fn eval(&self, t: f64) -> DVec3 {
        let (k, u) = self.locate(t);
        match self.rational.get(k).and_then(Option::as_ref) {
            Some(r) => r.eval(u),
            None => de_casteljau(&self.segments[k].points, u),
        }
    }

    fn eval_deriv(&self, t: f64) -> DVec3 {
        let (k, u) = self.locate(t);
        match self.rational.get(k).and_then(Option::as_ref) {
            Some(r) => r.eval_deriv(u),
            None => deriv_at(&self.segments[k].points, u),
        }
    }

    fn eval_second_deriv(&self, t: f64) -> DVec3 {
        let (k, u) = self.locate(t);
        match self.rational.get(k).and_then(Option::as_ref) {
            Some(r) => r.eval_second_deriv(u),
            None => second_deriv_at(&self.segments[k].points, u),
        }
    }
}

impl Lower for Path {
    /// One Bézier segment per path segment, as given, segment `k` on `[k, k + 1]`.
    fn lower(&self) -> Vec<BezierSegment> {
        self.segments
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let (t0, t1) = (k as f64, (k + 1) as f64);
                // The weights as given (scaled by a power of two only when they lie
                // beyond 2^±100), also when they are all equal.
                BezierSegment {
                    bezier: Bezier::new(s.points.to_vec()),
                    weights: s.weights.as_deref().map(normalised_weights),
                    t0,
                    t1,
                }
            })
            .collect()
    }
}

impl Family for Path {
    const NAME: &'static str = "path";

    fn control_points(&self) -> &[DVec3] {
        &self.points
    }

    /// Each segment's points taken from `points` (a shared end point for both segments
    /// that meet there); the weights kept.
    fn with_control_points(&self, points: Vec<DVec3>) -> Result<Path, GeomError> {
        if points.len() != self.points.len() {
            return Err(GeomError::TooFewPoints {
                min: self.points.len(),
                found: points.len(),
            });
        }
        let segments = self
            .segments
            .iter()
            .enumerate()
            .map(|(k, s)| PathSegment {
                points: (0..s.points.len())
                    .map(|i| points[self.flat_index(k, i)])
                    .collect(),
                weights: s.weights.clone(),
            })
            .collect();
        Path::try_new(segments, self.closed)
    }

    /// On the control polygon's leg nearest to `at`, inside the segment that leg belongs
    /// to (its degree rises by one; a rational segment's new weight interpolates its
    /// neighbours').
    fn with_point_on_polygon(&self, at: DVec3) -> Result<(Path, usize), GeomError> {
        // The nearest leg of each segment's polygon, then the nearest of those.
        let mut best = (0, 0, 0.0, f64::INFINITY);
        for (k, s) in self.segments.iter().enumerate() {
            let (i, f) = crate::geom::structure::nearest_leg(&s.points, at);
            let (a, b) = (s.points[i], s.points[i + 1]);
            let dist = (a + f * (b - a) - at).length_squared();
            if dist < best.3 {
                best = (k, i, f, dist);
            }
        }
        let (k, i, f, _) = best;
        let mut segments = self.segments.clone();
        let s = &mut segments[k];
        s.points.insert(i + 1, at);
        if let Some(w) = &mut s.weights {
            let nw = w[i] + (w[i + 1] - w[i]) * f;
            w.insert(i + 1, nw);
        }
        let index = self.start_of(k) + i + 1;
        Ok((Path::try_new(segments, self.closed)?, index))
    }

    /// An inner point of a segment of degree 2 or more (the segment's degree falls by
    /// one); a point where two segments meet is refused.
    fn with_point_removed(&self, index: usize) -> Result<Path, GeomError> {
        let count = self.points.len();
        if index >= count {
            return Err(GeomError::NoSuchPoint { index, count });
        }
        let mut start = 0;
        for (k, s) in self.segments.iter().enumerate() {
            let n = s.degree();
            if index > start && index < start + n {
                if n < 2 {
                    break;
                }
                let mut segments = self.segments.clone();
                let i = index - start;
                segments[k].points.remove(i);
                if let Some(w) = &mut segments[k].weights {
                    w.remove(i);
                }
                return Path::try_new(segments, self.closed);
            }
            start += n;
        }
        Err(GeomError::refused(
            Self::NAME,
            format!(
                "point {index} is where segments meet (or a line's end): remove an inner point of a segment"
            ),
        ))
    }

    /// Two segments of `degree`, the second starting where the first ends.
    fn generated(degree: usize, point: &mut dyn FnMut() -> DVec3) -> Result<Path, GeomError> {
        let degree = degree.max(1);
        let first: Vec<DVec3> = (0..=degree).map(|_| point()).collect();
        let mut second = vec![first[degree]];
        second.extend((0..degree).map(|_| point()));
        Path::try_new(
            vec![
                PathSegment::polynomial(first),
                PathSegment::polynomial(second),
            ],
            false,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64) -> DVec3 {
        DVec3::new(x, y, 0.0)
    }

    /// A line, a quadratic and a quarter circle (rational), closed.
    fn sample() -> Path {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        Path::try_new(
            vec![
                PathSegment::polynomial(vec![v(0.0, 0.0), v(1.0, 0.0)]),
                PathSegment::rational(
                    vec![v(1.0, 0.0), v(2.0, 0.0), v(2.0, 1.0)],
                    vec![1.0, h, 1.0],
                ),
                PathSegment::polynomial(vec![v(2.0, 1.0), v(1.0, 2.0), v(0.0, 0.0)]),
            ],
            true,
        )
        .expect("a closed path")
    }

    #[test]
    fn segment_k_covers_k_to_k_plus_one_and_the_shared_points_are_listed_once() {
        let p = sample();
        assert_eq!(p.domain(), (0.0, 3.0));
        assert_eq!(p.control_points().len(), 5);
        assert_eq!(p.eval(0.5), v(0.5, 0.0));
        // The quarter circle about (1, 1): its middle at 45°.
        let m = p.eval(1.5);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((m - v(1.0 + h, 1.0 - h)).length() < 1e-15, "{m}");
        // The quadratic at its middle: (P0 + 2 P1 + P2) / 4.
        assert_eq!(p.eval(2.5), v((2.0 + 2.0) / 4.0, (1.0 + 4.0) / 4.0));
        assert_eq!(p.eval(3.0), v(0.0, 0.0));
        assert_eq!(p.lower().len(), 3);
        assert_eq!(p.lower()[1].degree(), 2);
    }

    #[test]
    fn moving_a_shared_point_moves_both_segments() {
        let p = sample();
        let mut pts = p.control_points().to_vec();
        pts[1] = v(1.0, -1.0);
        let q = p.with_control_points(pts.clone()).expect("moved");
        assert_eq!(q.segments()[0].points[1], v(1.0, -1.0));
        assert_eq!(q.segments()[1].points[0], v(1.0, -1.0));
        // The closing point is point 0.
        pts[0] = v(0.0, -0.5);
        let q = p.with_control_points(pts).expect("moved");
        assert_eq!(q.segments()[2].points[2], v(0.0, -0.5));
        assert_eq!(q.segments()[0].points[0], v(0.0, -0.5));
    }

    #[test]
    fn a_gap_is_refused_naming_the_joint() {
        let e = Path::try_new(
            vec![
                PathSegment::polynomial(vec![v(0.0, 0.0), v(1.0, 0.0)]),
                PathSegment::polynomial(vec![v(1.0, 1e-9), v(2.0, 0.0)]),
            ],
            false,
        )
        .expect_err("a gap");
        assert!(
            matches!(e, GeomError::PathGap { joint: 0, next: 1, gap } if (gap - 1e-9).abs() < 1e-20),
            "{e}"
        );
        // Closing a path whose ends differ.
        let e = Path::try_new(
            vec![PathSegment::polynomial(vec![v(0.0, 0.0), v(1.0, 0.0)])],
            true,
        )
        .expect_err("not closed");
        assert!(
            matches!(
                e,
                GeomError::PathGap {
                    joint: 0,
                    next: 0,
                    ..
                }
            ),
            "{e}"
        );
        // A segment's own error names the segment.
        let e = Path::try_new(
            vec![
                PathSegment::polynomial(vec![v(0.0, 0.0), v(1.0, 0.0)]),
                PathSegment::rational(vec![v(1.0, 0.0), v(2.0, 0.0)], vec![1.0, -1.0]),
            ],
            false,
        )
        .expect_err("a bad weight");
        assert_eq!(e.field(), "segments[1].weights[1]", "{e}");
        assert!(Path::try_new(vec![], false).is_err());
    }

    #[test]
    fn structure_edits_stay_inside_a_segment() {
        let p = sample();
        // Point 4 is the last quadratic's middle point: removing it leaves a line.
        let q = p.with_point_removed(4).expect("an inner point");
        assert_eq!(q.segments()[2].degree(), 1);
        assert!(p.with_point_removed(1).is_err(), "a joint");
        let (q, i) = p.with_point_on_polygon(v(0.5, -0.1)).expect("inserted");
        assert_eq!(i, 1);
        assert_eq!(q.segments()[0].degree(), 2);
        assert_eq!(q.control_points()[1], v(0.5, -0.1));
    }
}
