//! The closest point of a curve to a point: global and robust for any degree and, through
//! lowering, for every family.
//! `docs/math.md` §2.5.

use glam::DVec3;

use crate::geom::{Aabb, Bezier, Lower, ParamCurve, RationalBezier};

/// A piece [`nearest_on_bezier`] searches: a curve on `[0, 1]` inside the box of its
/// control points (a polynomial Bézier curve, or a rational one with positive weights),
/// split in two by de Casteljau.
pub trait Piece: ParamCurve + Clone {
    /// The control points (the curve lies in their convex hull).
    fn control_points(&self) -> &[DVec3];
    /// The halves at `u`, each reparameterised to `[0, 1]`.
    fn halves(&self, u: f64) -> (Self, Self);
}

impl Piece for Bezier {
    fn control_points(&self) -> &[DVec3] {
        self.points()
    }
    fn halves(&self, u: f64) -> (Bezier, Bezier) {
        self.split(u)
    }
}

impl Piece for RationalBezier {
    fn control_points(&self) -> &[DVec3] {
        self.points()
    }
    fn halves(&self, u: f64) -> (RationalBezier, RationalBezier) {
        (self.subsegment(0.0, u), self.subsegment(u, 1.0))
    }
}

/// The default accuracy of [`nearest`], relative to the curve's size: the returned distance
/// is within `DEFAULT_RELATIVE_ACCURACY · size` of the true one.
pub const DEFAULT_RELATIVE_ACCURACY: f64 = 1e-12;

/// The closest point found by [`nearest`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Nearest {
    /// Its parameter, in the curve's own domain.
    pub t: f64,
    /// The point `P(t)`.
    pub point: DVec3,
    /// `|P(t) − p|`.
    pub distance: f64,
}

/// Safeguarded Newton on `g(u) = |B(u) − p|²` inside `[lo, hi]`, from `u`: a Newton step
/// on `g′ = 0` when it stays in the bracket and decreases `g`, else a bisection of the
/// bracket on the sign of `g′`. Stops when a step moves the point by less than `accuracy`.
fn refine<B: Piece>(b: &B, p: DVec3, mut lo: f64, mut hi: f64, mut u: f64, accuracy: f64) -> f64 {
    let g = |u: f64| (b.eval(u) - p).length_squared();
    for _ in 0..100 {
        let d = b.eval(u) - p;
        let d1 = b.eval_deriv(u);
        let d2 = b.eval_second_deriv(u);
        let gp = d.dot(d1);
        let gpp = d1.length_squared() + d.dot(d2);
        // Keep the bracket around the minimum: g′ < 0 means it lies to the right.
        if gp < 0.0 {
            lo = lo.max(u);
        } else {
            hi = hi.min(u);
        }
        let newton = if gpp > 0.0 { u - gp / gpp } else { f64::NAN };
        let next = if newton.is_finite() && newton > lo && newton < hi && g(newton) <= g(u) {
            newton
        } else {
            0.5 * (lo + hi)
        };
        let moved = (next - u).abs() * d1.length().max(accuracy);
        u = next;
        if moved <= accuracy || hi - lo <= f64::EPSILON * 4.0 {
            break;
        }
    }
    u
}

/// The closest point of a Bézier curve to `p` on `[0, 1]`: `(u, distance)`.
///
/// Global: the curve is subdivided while a piece's control box (which holds the piece) may
/// hold a point closer than the best found; pieces that are small or nearly straight are
/// finished with safeguarded Newton from their chord's projection. `accuracy` is an
/// absolute distance.
#[must_use]
pub fn nearest_on_bezier<B: Piece>(b: &B, p: DVec3, accuracy: f64) -> (f64, f64) {
    let mut best = (0.0, (b.eval(0.0) - p).length());
    let end = (b.eval(1.0) - p).length();
    if end < best.1 {
        best = (1.0, end);
    }
    if b.control_points().len() < 2 {
        return best;
    }
    let mut stack: Vec<(B, f64, f64, u32)> = vec![(b.clone(), 0.0, 1.0, 0)];
    while let Some((piece, u0, u1, depth)) = stack.pop() {
        let bbox = Aabb::from_points(piece.control_points());
        if bbox.distance_to(p) >= best.1 {
            continue;
        }
        let pts = piece.control_points();
        let (a, z) = (pts[0], pts[pts.len() - 1]);
        let chord = z - a;
        let size = bbox.diagonal();
        if crate::geom::bezier::polygon_flatness(pts) <= 0.01 * size.max(accuracy) || depth >= 40 {
            let s = if chord.length_squared() > 0.0 {
                ((p - a).dot(chord) / chord.length_squared()).clamp(0.0, 1.0)
            } else {
                0.5
            };
            let u = refine(b, p, u0, u1, u0 + s * (u1 - u0), accuracy);
            let d = (b.eval(u) - p).length();
            if d < best.1 {
                best = (u, d);
            }
            continue;
        }
        let (left, right) = piece.halves(0.5);
        let mid = 0.5 * (u0 + u1);
        // Visit the nearer half first (pushed last) so the bound tightens sooner.
        let (dl, dr) = (
            Aabb::from_points(left.control_points()).distance_to(p),
            Aabb::from_points(right.control_points()).distance_to(p),
        );
        if dl <= dr {
            stack.push((right, mid, u1, depth + 1));
            stack.push((left, u0, mid, depth + 1));
        } else {
            stack.push((left, u0, mid, depth + 1));
            stack.push((right, mid, u1, depth + 1));
        }
    }
    best
}

/// The closest point of any curve to `p`, through its Bézier segments. `accuracy` is an
/// absolute distance; `None` takes [`DEFAULT_RELATIVE_ACCURACY`] times the curve's size.
#[must_use]
pub fn nearest<C: Lower + ParamCurve + ?Sized>(
    curve: &C,
    p: DVec3,
    accuracy: Option<f64>,
) -> Nearest {
    let segments = curve.lower();
    let size = segments
        .iter()
        .fold(Aabb::EMPTY, |b, s| b.union(s.bezier.control_box()))
        .diagonal()
        .max(p.length())
        .max(1e-300);
    let accuracy = accuracy.unwrap_or(DEFAULT_RELATIVE_ACCURACY * size);
    let mut best: Option<Nearest> = None;
    for s in &segments {
        let (u, d) = match s.rational() {
            Some(r) => nearest_on_bezier(&r, p, accuracy),
            None => nearest_on_bezier(&s.bezier, p, accuracy),
        };
        if best.is_none_or(|b| d < b.distance) {
            let t = if u >= 1.0 {
                s.t1
            } else {
                s.t0 + u * (s.t1 - s.t0)
            };
            best = Some(Nearest {
                t,
                point: s.eval(u),
                distance: d,
            });
        }
    }
    let best = best.unwrap_or_else(|| {
        let (a, _) = curve.domain();
        let q = curve.eval(a);
        Nearest {
            t: a,
            point: q,
            distance: (q - p).length(),
        }
    });
    // Report the curve's own exact point at that parameter.
    let point = curve.eval(best.t);
    Nearest {
        t: best.t,
        point,
        distance: (point - p).length(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_point_on_a_circle_like_curve_is_found_globally() {
        // A parabola y = x² (Bézier on x ∈ [−1, 1]); from (0, 2) the nearest points are at
        // x = ±sqrt(3/2) outside, so inside [−1, 1] they are the ends... use (0.3, 2):
        // minimise (x−0.3)² + (x²−2)²: derivative 2(x−0.3) + 4x(x²−2) = 0.
        let b = Bezier::new(vec![
            DVec3::new(-1.0, 1.0, 0.0),
            DVec3::new(0.0, -1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
        ]);
        let p = DVec3::new(0.3, 0.2, 0.0);
        let n = nearest(&b, p, None);
        // Brute force over a fine grid, then compare.
        let mut brute = (0.0, f64::INFINITY);
        for k in 0..=200_000 {
            let u = f64::from(k) / 200_000.0;
            let d = (b.eval(u) - p).length();
            if d < brute.1 {
                brute = (u, d);
            }
        }
        assert!(n.distance <= brute.1 + 1e-12);
        assert!((n.t - brute.0).abs() < 1e-4);
    }
}
