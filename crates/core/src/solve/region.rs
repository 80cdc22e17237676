//! Paper 000's region of a Bézier cubic: how its control polygon is shaped (parallel,
//! converging or diverging end legs) and the part of the plane a shape modification that
//! keeps its end tangents can reach, as boundary polylines.

use glam::{DVec2, DVec3};

use super::SolveError;
use super::shape::end_directions;
use crate::geom::cubic_region::REGION_TOLERANCE;
use crate::geom::cubic_region::{CubicRegion, PolygonType};
use crate::geom::{Aabb, Bezier};

/// Classifies a cubic's control polygon and returns its reachable region
/// ([`CubicRegion::from_cubic`] with the solver's errors).
///
/// # Errors
/// [`SolveError::NotCubic`] unless the degree is 3; [`SolveError::NoTangent`] for
/// coincident end points.
pub fn cubic_region(curve: &Bezier) -> Result<CubicRegion, SolveError> {
    if curve.degree() != 3 {
        return Err(SolveError::NotCubic {
            degree: curve.degree(),
        });
    }
    let directions = end_directions(curve)?;
    Ok(CubicRegion::from_cubic(curve.points(), directions))
}

/// An orthonormal basis `(u, v)` of the plane through `P_0` holding `d`, `e_1`, `e_2`, when
/// they are coplanar.
fn plane_basis(d: DVec3, e1: DVec3, e2: DVec3) -> Option<(DVec3, DVec3)> {
    let normal = [d.cross(e1), d.cross(e2), e1.cross(e2)]
        .into_iter()
        .max_by(|a, b| a.length().total_cmp(&b.length()))
        .and_then(|v| v.try_normalize())?;
    let coplanar = [d.normalize_or_zero(), e1, e2]
        .iter()
        .all(|v| v.dot(normal).abs() <= 1e-9);
    if !coplanar {
        return None;
    }
    let u = e1;
    let v = normal.cross(u).normalize();
    Some((u, v))
}

impl CubicRegion {
    fn scale(&self) -> f64 {
        (self.p3 - self.p0).length().max(1e-300)
    }

    /// Whether `target` is reachable (slides unlimited, `s, r ≥ 0`). Points within
    /// `1e-9 · |P_3 − P_0|` of the boundary count as inside.
    #[must_use]
    pub fn contains(&self, target: DVec3) -> bool {
        let d = self.p3 - self.p0;
        let w = target - self.p0;
        let tol = REGION_TOLERANCE;
        let inside = |lambda: f64, a: f64, b: f64| {
            lambda > -tol
                && lambda < 1.0 + tol
                && a >= -tol * self.scale()
                && b >= -tol * self.scale()
        };
        // Coplanar: 2D coordinates in the plane; otherwise a 3×3 solve.
        let Some((u, v)) = plane_basis(d, self.e1, self.e2) else {
            let m = glam::DMat3::from_cols(d, self.e1, self.e2);
            if m.determinant().abs() <= 1e-12 {
                return false;
            }
            let x = m.inverse() * w;
            return inside(x.x, x.y, x.z);
        };
        let to2 = |x: DVec3| DVec2::new(x.dot(u), x.dot(v));
        // Off the plane: unreachable.
        if (w - u * w.dot(u) - v * w.dot(v)).length() > tol * self.scale().max(w.length()) {
            return false;
        }
        let (d2, e1, e2, w2) = (to2(d), to2(self.e1), to2(self.e2), to2(w));
        let det = e1.perp_dot(e2);
        if det.abs() > 1e-12 {
            // (a, b) = [e1 e2]⁻¹ (w − λ d), affine in λ: find λ ∈ (0, 1) with a, b ≥ 0.
            let solve = |q: DVec2| DVec2::new(q.perp_dot(e2) / det, e1.perp_dot(q) / det);
            let at0 = solve(w2);
            let slope = -solve(d2);
            let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
            for (c0, c1) in [(at0.x, slope.x), (at0.y, slope.y)] {
                // c0 + c1 λ ≥ −tol
                let floor = -tol * self.scale();
                if c1.abs() < 1e-15 {
                    if c0 < floor {
                        return false;
                    }
                } else if c1 > 0.0 {
                    lo = lo.max((floor - c0) / c1);
                } else {
                    hi = hi.min((floor - c0) / c1);
                }
            }
            return lo <= hi + tol;
        }
        // Parallel legs: the cone is a ray (same direction) or a line (opposite).
        let n = DVec2::new(-e1.y, e1.x);
        let nd = n.dot(d2);
        if nd.abs() <= 1e-15 {
            // P0P3 parallel to the legs: only the line itself.
            return n.dot(w2).abs() <= tol * self.scale();
        }
        let lambda = n.dot(w2) / nd;
        if !(lambda > -tol && lambda < 1.0 + tol) {
            return false;
        }
        let along = e1.dot(w2 - lambda * d2);
        e1.dot(e2) < 0.0 || along >= -tol * self.scale()
    }

    /// Whether `target` is reachable with the slides of a type-2 polygon limited to
    /// `[P_0, X]` and `[P_3, X]`: inside the area between the segment `P_0P_3` and the cubic
    /// `(P_0, X, X, P_3)`. `None` unless the polygon is of type 2.
    #[must_use]
    pub fn contains_limited(&self, target: DVec3) -> Option<bool> {
        let PolygonType::Converging { apex } = self.kind else {
            return None;
        };
        let boundary = self.limited_boundary(apex, 1e-9 * self.scale());
        let (u, v) = plane_basis(self.p3 - self.p0, self.e1, self.e2)?;
        let to2 = |x: DVec3| DVec2::new((x - self.p0).dot(u), (x - self.p0).dot(v));
        let w = target - self.p0;
        if (w - u * w.dot(u) - v * w.dot(v)).length()
            > REGION_TOLERANCE * self.scale().max(w.length())
        {
            return Some(false);
        }
        let q = to2(target);
        let poly: Vec<DVec2> = boundary.iter().map(|&p| to2(p)).collect();
        // Even-odd rule.
        let mut inside = false;
        for k in 0..poly.len() {
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            if (a.y > q.y) != (b.y > q.y) {
                let x = a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if q.x < x {
                    inside = !inside;
                }
            }
        }
        Some(inside)
    }

    /// The closed boundary of the limited type-2 region: the cubic `(P_0, X, X, P_3)`
    /// flattened to `tolerance`, closed by the segment `P_3P_0`.
    fn limited_boundary(&self, apex: DVec3, tolerance: f64) -> Vec<DVec3> {
        let c = Bezier::new(vec![self.p0, apex, apex, self.p3]);
        let mut out = vec![self.p0];
        flatten(&c, 0.0, 1.0, tolerance, 0, &mut out);
        out
    }

    /// Polylines outlining the region for drawing. Unlimited: the region clipped at
    /// `reach` from the end points (a strip, half-strip or sector). With `limited` and a
    /// type-2 polygon: the segment and the cubic `(P_0, X, X, P_3)`.
    #[must_use]
    pub fn boundary(&self, limited: bool, reach: f64) -> Vec<Vec<DVec3>> {
        if let (true, PolygonType::Converging { apex }) = (limited, self.kind) {
            let mut b = self.limited_boundary(apex, 1e-4 * self.scale());
            b.push(self.p0);
            return vec![b];
        }
        let far = [
            self.p0 + reach * self.e1,
            self.p0 + reach * self.e2,
            self.p3 + reach * self.e1,
            self.p3 + reach * self.e2,
        ];
        let Some((u, v)) = plane_basis(self.p3 - self.p0, self.e1, self.e2) else {
            // 3D: the segment and the four rays.
            let mut lines = vec![vec![self.p0, self.p3]];
            lines.push(vec![self.p0, far[0]]);
            lines.push(vec![self.p0, far[1]]);
            lines.push(vec![self.p3, far[2]]);
            lines.push(vec![self.p3, far[3]]);
            return lines;
        };
        let mut pts: Vec<DVec3> = vec![self.p0, self.p3];
        pts.extend(far);
        let hull = convex_hull(&pts, u, v, self.p0);
        let mut closed = hull.clone();
        if let Some(&first) = hull.first() {
            closed.push(first);
        }
        vec![closed]
    }

    /// A box around the region's drawn boundary.
    #[must_use]
    pub fn bounds(&self, reach: f64) -> Aabb {
        self.boundary(false, reach)
            .iter()
            .fold(Aabb::EMPTY, |b, l| b.union(Aabb::from_points(l)))
    }
}

/// Appends the flattened points of `c` on `(t0, t1]` to `out`.
fn flatten(c: &Bezier, t0: f64, t1: f64, tol: f64, depth: u32, out: &mut Vec<DVec3>) {
    let piece = c.subsegment(t0, t1);
    if piece.flatness() <= tol || depth >= 24 {
        out.push(piece.points()[3]);
    } else {
        let mid = 0.5 * (t0 + t1);
        flatten(c, t0, mid, tol, depth + 1, out);
        flatten(c, mid, t1, tol, depth + 1, out);
    }
}

/// The convex hull (counter-clockwise) of points lying in the plane through `origin`
/// spanned by the orthonormal `u`, `v`.
fn convex_hull(points: &[DVec3], u: DVec3, v: DVec3, origin: DVec3) -> Vec<DVec3> {
    let mut pts: Vec<(DVec2, DVec3)> = points
        .iter()
        .map(|&p| (DVec2::new((p - origin).dot(u), (p - origin).dot(v)), p))
        .collect();
    pts.sort_by(|a, b| a.0.x.total_cmp(&b.0.x).then(a.0.y.total_cmp(&b.0.y)));
    pts.dedup_by(|a, b| (a.0 - b.0).length() < 1e-12);
    if pts.len() < 3 {
        return pts.into_iter().map(|p| p.1).collect();
    }
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut lower: Vec<(DVec2, DVec3)> = Vec::new();
    for &p in &pts {
        while lower.len() >= 2
            && cross(lower[lower.len() - 2].0, lower[lower.len() - 1].0, p.0) <= 0.0
        {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<(DVec2, DVec3)> = Vec::new();
    for &p in pts.iter().rev() {
        while upper.len() >= 2
            && cross(upper[upper.len() - 2].0, upper[upper.len() - 1].0, p.0) <= 0.0
        {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.into_iter().chain(upper).map(|p| p.1).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solve::shape::tangent_kept;

    fn p2(x: f64, y: f64) -> DVec3 {
        DVec3::new(x, y, 0.0)
    }

    #[test]
    fn polygon_types_are_classified() {
        let parallel = Bezier::new(vec![p2(0., 0.), p2(0., 1.), p2(3., 1.), p2(3., 0.)]);
        assert_eq!(cubic_region(&parallel).unwrap().kind, PolygonType::Parallel);
        let converging = Bezier::new(vec![p2(0., 0.), p2(1., 1.), p2(3., 1.), p2(4., 0.)]);
        match cubic_region(&converging).unwrap().kind {
            PolygonType::Converging { apex } => assert!((apex - p2(2., 2.)).length() < 1e-12),
            other => panic!("{other:?}"),
        }
        let diverging = Bezier::new(vec![p2(0., 0.), p2(-1., 1.), p2(5., 1.), p2(4., 0.)]);
        assert_eq!(
            cubic_region(&diverging).unwrap().kind,
            PolygonType::Diverging
        );
    }

    #[test]
    fn coincident_end_points_have_no_tangent() {
        let b = Bezier::new(vec![p2(0., 0.), p2(0., 0.), p2(3., 1.), p2(3., 0.)]);
        assert!(matches!(
            tangent_kept(&b, p2(1., 1.), Some(0.5), None),
            Err(SolveError::NoTangent { .. })
        ));
    }
}
