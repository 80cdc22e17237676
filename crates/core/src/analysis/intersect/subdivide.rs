//! Two segments subdivided down to candidate intersections: the sub-segments' homogeneous
//! control points (de Casteljau halves and restrictions, so the convex hull holds for
//! rational segments too), their boxes, tangent cones and flatness, Bézier clipping by the
//! other's fat line, and the chord crossings that start the refinement.

use glam::DVec2;

use crate::analysis::piece::Piece;
use crate::analysis::poly;

/// Homogeneous control points, on the stack up to degree 7 (large on purpose: the
/// subdivision makes thousands of them and must not allocate each).
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)]
pub(super) enum Points {
    Stack([[f64; 3]; 8], usize),
    Heap(Vec<[f64; 3]>),
}

impl Points {
    pub(super) fn with_len(n: usize) -> Points {
        if n <= 8 {
            Points::Stack([[0.0; 3]; 8], n)
        } else {
            Points::Heap(vec![[0.0; 3]; n])
        }
    }

    pub(super) fn as_slice(&self) -> &[[f64; 3]] {
        match self {
            Points::Stack(a, n) => &a[..*n],
            Points::Heap(v) => v,
        }
    }

    pub(super) fn as_mut_slice(&mut self) -> &mut [[f64; 3]] {
        match self {
            Points::Stack(a, n) => &mut a[..*n],
            Points::Heap(v) => v,
        }
    }
}

/// A sub-segment: homogeneous control points `(w x, w y, w)` and its range of the
/// segment's own parameter.
#[derive(Debug, Clone)]
pub(super) struct Sub {
    pub(super) h: Points,
    u0: f64,
    u1: f64,
    /// Whether the weights differ from 1 (else the points are Cartesian already).
    pub(super) rational: bool,
}

impl Sub {
    pub(super) fn of(p: &Piece, u0: f64, u1: f64) -> Sub {
        let n = p.a[0].len();
        let mut h = Points::with_len(n);
        let slots = h.as_mut_slice();
        if u0 > 0.0 || u1 < 1.0 {
            // Each coordinate restricted into one scratch row (a polynomial's weights as
            // ones, restricted too), then laid into the points.
            poly::in_two_buffers(n, |row, ones| {
                ones.fill(1.0);
                let w = p.w.as_deref().unwrap_or(ones);
                for (k, c) in [p.a[0].as_slice(), p.a[1].as_slice(), w]
                    .into_iter()
                    .enumerate()
                {
                    poly::restrict_into(c, u0, u1, row);
                    for (slot, v) in slots.iter_mut().zip(row.iter()) {
                        slot[k] = *v;
                    }
                }
            });
        } else {
            for (i, slot) in slots.iter_mut().enumerate() {
                let w = p.w.as_ref().map_or(1.0, |w| w[i]);
                *slot = [p.a[0][i], p.a[1][i], w];
            }
        }
        Sub {
            h,
            u0,
            u1,
            rational: p.w.is_some(),
        }
    }

    pub(super) fn len(&self) -> usize {
        self.h.as_slice().len()
    }

    pub(super) fn point(&self, i: usize) -> DVec2 {
        let v = self.h.as_slice()[i];
        if self.rational {
            DVec2::new(v[0] / v[2], v[1] / v[2])
        } else {
            DVec2::new(v[0], v[1])
        }
    }

    pub(super) fn bounds(&self) -> (DVec2, DVec2) {
        let mut lo = DVec2::INFINITY;
        let mut hi = DVec2::NEG_INFINITY;
        for i in 0..self.len() {
            let p = self.point(i);
            lo = lo.min(p);
            hi = hi.max(p);
        }
        (lo, hi)
    }

    /// The directions of the control polygon's legs as an interval `[θ₀, θ₁]` of
    /// [`pseudo_angle`]s (narrower than a quarter turn), or `None` when they spread wider.
    /// The curve's tangent — for positive weights a rational one's too — is a positive
    /// combination of the legs, so it stays inside.
    pub(super) fn cone(&self) -> Option<(f64, f64)> {
        let n = self.len() - 1;
        let mut first: Option<f64> = None;
        let (mut lo, mut hi) = (0.0_f64, 0.0_f64);
        for i in 0..n {
            let e = self.point(i + 1) - self.point(i);
            if e.x == 0.0 && e.y == 0.0 {
                continue;
            }
            let angle = pseudo_angle(e);
            match first {
                None => first = Some(angle),
                Some(f) => {
                    // Relative to the first leg, within half a turn either way.
                    let mut d = angle - f;
                    if d > HALF_TURN {
                        d -= 2.0 * HALF_TURN;
                    } else if d <= -HALF_TURN {
                        d += 2.0 * HALF_TURN;
                    }
                    lo = lo.min(d);
                    hi = hi.max(d);
                    if hi - lo >= QUARTER_TURN {
                        return None;
                    }
                }
            }
        }
        first.map(|f| (f + lo, f + hi))
    }

    /// This piece cut to the part that can lie in the fat line of `other`: the strip
    /// parallel to `other`'s chord between the extreme signed distances of `other`'s control
    /// points (so it holds `other`). For a rational piece the distances are weighed:
    /// `Σ w_i (d_i − d_min) B_i ≥ 0` and `Σ w_i (d_max − d_i) B_i ≥ 0`, with `W > 0`.
    /// `None` when no part can.
    pub(super) fn clipped_by(&self, other: &Sub) -> Option<Sub> {
        let m = other.len() - 1;
        let origin = other.point(0);
        let mut dir = other.point(m) - origin;
        if dir.length_squared() == 0.0 {
            // A closed chord: the direction to the farthest control point.
            dir = (1..m)
                .map(|i| other.point(i) - origin)
                .max_by(|p, q| p.length_squared().total_cmp(&q.length_squared()))?;
            if dir.length_squared() == 0.0 {
                return None;
            }
        }
        let normal = dir.perp().normalize();
        let (mut dmin, mut dmax) = (0.0_f64, 0.0_f64);
        for i in 0..=m {
            let d = (other.point(i) - origin).dot(normal);
            dmin = dmin.min(d);
            dmax = dmax.max(d);
        }
        let slack = 1e-12 * (dmax - dmin).max(dir.length());
        let (dmin, dmax) = (dmin - slack, dmax + slack);
        let h = self.h.as_slice();
        let mut below = [0.0; 16];
        let mut above = [0.0; 16];
        let n = h.len();
        if n > 16 {
            return Some(self.clone());
        }
        for (i, v) in h.iter().enumerate() {
            let w = v[2];
            let d = (DVec2::new(v[0], v[1]) - origin * w).dot(normal);
            below[i] = d - dmin * w;
            above[i] = dmax * w - d;
        }
        let (l1, h1) = nonnegative_range(&below[..n])?;
        let (l2, h2) = nonnegative_range(&above[..n])?;
        let (lo, hi) = (l1.max(l2), h1.min(h2));
        if lo > hi {
            return None;
        }
        Some(self.restricted(lo, hi))
    }

    /// The piece on its own parameter range `[lo, hi] ⊆ [0, 1]`.
    pub(super) fn restricted(&self, lo: f64, hi: f64) -> Sub {
        if lo <= 0.0 && hi >= 1.0 {
            return self.clone();
        }
        let mut h = self.h.clone();
        let pts = h.as_mut_slice();
        let n = pts.len() - 1;
        // Right part at `lo`, then the left part of that at the rescaled `hi`.
        // (A polynomial piece's weights stay 1: only `x` and `y` are interpolated.)
        let rational = self.rational;
        let split_right = |pts: &mut [[f64; 3]], t: f64| {
            let s = 1.0 - t;
            for k in 1..=n {
                for i in 0..=(n - k) {
                    let (p, q) = (pts[i], pts[i + 1]);
                    pts[i][0] = s * p[0] + t * q[0];
                    pts[i][1] = s * p[1] + t * q[1];
                    if rational {
                        pts[i][2] = s * p[2] + t * q[2];
                    }
                }
            }
        };
        // After the triangle, `pts[j]` holds the point of level n − j at index j: the right
        // part's control points.
        if lo > 0.0 {
            split_right(pts, lo);
        }
        if hi < 1.0 {
            let t = if lo > 0.0 { (hi - lo) / (1.0 - lo) } else { hi };
            // The left part at `t`: the same triangle on the reversed points.
            pts.reverse();
            split_right(pts, 1.0 - t);
            pts.reverse();
        }
        let span = self.u1 - self.u0;
        Sub {
            h,
            u0: self.u0 + lo * span,
            u1: self.u0 + hi * span,
            rational: self.rational,
        }
    }

    /// The chord from the first control point to the last.
    pub(super) fn chord(&self) -> DVec2 {
        self.point(self.len() - 1) - self.point(0)
    }

    /// The largest distance of a control point from the chord.
    pub(super) fn flatness(&self) -> f64 {
        let n = self.len() - 1;
        let (a, b) = (self.point(0), self.point(n));
        let d = b - a;
        let len = d.length();
        (1..n)
            .map(|i| {
                let p = self.point(i) - a;
                if len > 0.0 {
                    (p.perp_dot(d) / len).abs()
                } else {
                    p.length()
                }
            })
            .fold(0.0, f64::max)
    }

    pub(super) fn halves(&self) -> (Sub, Sub) {
        let n = self.len() - 1;
        let mut left = Points::with_len(n + 1);
        let mut right = Points::with_len(n + 1);
        {
            // The right half's points are the triangle's last column: work in `right`.
            let (l, r) = (left.as_mut_slice(), right.as_mut_slice());
            r.copy_from_slice(self.h.as_slice());
            l[0] = r[0];
            for (k, slot) in l.iter_mut().enumerate().skip(1) {
                for i in 0..=(n - k) {
                    let (p, q) = (r[i], r[i + 1]);
                    r[i] = [
                        0.5 * (p[0] + q[0]),
                        0.5 * (p[1] + q[1]),
                        0.5 * (p[2] + q[2]),
                    ];
                }
                *slot = r[0];
            }
        }
        let mid = 0.5 * (self.u0 + self.u1);
        (
            Sub {
                h: left,
                u0: self.u0,
                u1: mid,
                rational: self.rational,
            },
            Sub {
                h: right,
                u0: mid,
                u1: self.u1,
                rational: self.rational,
            },
        )
    }
}

/// Whether `q` lies farther than `tol` from the piece on `[u0, u1]`, shown by boxes: the
/// sub-pieces' control boxes (which hold them, rational ones too) halved until every box
/// near `q` is gone. `false` when a box within `tol` of `q` is no larger than `tol` or
/// after 64 halvings — then only the closest point can tell.
pub(super) fn surely_off(p: &Piece, (u0, u1): (f64, f64), q: DVec2, tol: f64) -> bool {
    let mut stack = vec![Sub::of(p, u0, u1)];
    let mut halvings = 0;
    while let Some(s) = stack.pop() {
        let (lo, hi) = s.bounds();
        let gap = (lo - q).max(q - hi).max(DVec2::ZERO).length();
        if gap > tol {
            continue;
        }
        if halvings == 64 || (hi - lo).max_element() <= tol {
            return false;
        }
        halvings += 1;
        let (l, r) = s.halves();
        stack.push(l);
        stack.push(r);
    }
    true
}

/// `x` held to `[0, 1]`; a NaN becomes ½ (never left to the optimiser's choice of
/// `min`/`max`, which treat NaN differently).
#[allow(clippy::manual_clamp)]
pub(super) fn to_unit(x: f64) -> f64 {
    if x.is_nan() {
        0.5
    } else if x < 0.0 {
        0.0
    } else if x > 1.0 {
        1.0
    } else {
        x
    }
}

pub(super) fn boxes_meet(a: (DVec2, DVec2), b: (DVec2, DVec2), margin: f64) -> bool {
    a.0.x <= b.1.x + margin
        && b.0.x <= a.1.x + margin
        && a.0.y <= b.1.y + margin
        && b.0.y <= a.1.y + margin
}

/// Candidate `(u, v)` pairs of two segments from subdivision: the crossing of the chords
/// of two sub-segments flat to `flat`, or of two that meet at most once (flat to 5 % of
/// their chords, their tangent cones disjoint).
pub(super) struct Subdivider {
    pub(super) flat: f64,
    pub(super) margin: f64,
    /// `(u, v)` to start from, and — for a pair that meets at most once — the sub-ranges
    /// `(u0, u1, v0, v1)` that hold its one point.
    pub(super) candidates: Vec<Candidate>,
}

/// A start `(u, v)` for Newton's method, and for a pair meeting at most once the
/// sub-ranges `[u0, u1, v0, v1]` holding its point.
pub(super) type Candidate = ((f64, f64), Option<[f64; 4]>);

impl Subdivider {
    pub(super) fn run(&mut self, a: &Sub, b: &Sub, depth: u32) {
        let (ba, bb) = (a.bounds(), b.bounds());
        if !boxes_meet(ba, bb, self.margin) {
            return;
        }
        // Too many candidates means coincident stretches the overlap test did not catch:
        // stop rather than multiply them.
        if self.candidates.len() > 4096 {
            return;
        }
        let (fa, fb) = (a.flatness(), b.flatness());
        if (fa <= self.flat && fb <= self.flat) || depth >= 64 {
            self.candidates.push((chord_crossing(a, b), None));
            return;
        }
        // Two pieces each within 5 % of its chord's length of the chord, whose tangent
        // cones (as lines, directions modulo π) are disjoint, meet at most once; Newton's
        // method from the chords' crossing finds that point.
        let (ca, cb) = (a.chord(), b.chord());
        if fa <= 0.05 * ca.length()
            && fb <= 0.05 * cb.length()
            && let (Some(ka), Some(kb)) = (a.cone(), b.cone())
            && cones_disjoint(ka, kb)
        {
            self.candidates
                .push((chord_crossing(a, b), Some([a.u0, a.u1, b.u0, b.u1])));
            return;
        }
        // Fat-line clipping (Sederberg–Nishita): the part of `b` inside the strip around
        // `a`'s chord that holds `a`, then the part of `a` inside the strip around the
        // clipped `b`'s chord. Each clip keeps every point the two have in common.
        if fa > 0.0 && fb > 0.0 {
            let Some(b2) = b.clipped_by(a) else {
                return;
            };
            let Some(a2) = a.clipped_by(&b2) else {
                return;
            };
            let shrink = ((a2.u1 - a2.u0) * (b2.u1 - b2.u0)) / ((a.u1 - a.u0) * (b.u1 - b.u0));
            if shrink <= 0.5 {
                self.run(&a2, &b2, depth + 1);
                return;
            }
            self.split(&a2, &b2, depth);
            return;
        }
        self.split(a, b, depth);
    }

    /// Halves the larger of two pieces that clipping did not shrink enough (several points
    /// in common, or a tangency) and examines both halves.
    pub(super) fn split(&mut self, a: &Sub, b: &Sub, depth: u32) {
        let (ba, bb) = (a.bounds(), b.bounds());
        let (fa, fb) = (a.flatness(), b.flatness());
        let size_a = (ba.1 - ba.0).length();
        let size_b = (bb.1 - bb.0).length();
        if (fa > self.flat && size_a >= size_b) || fb <= self.flat {
            let (l, r) = a.halves();
            self.run(&l, b, depth + 1);
            self.run(&r, b, depth + 1);
        } else {
            let (l, r) = b.halves();
            self.run(a, &l, depth + 1);
            self.run(a, &r, depth + 1);
        }
    }
}

/// The parameter interval `[lo, hi] ⊆ [0, 1]` where a polynomial with Bernstein
/// coefficients `y` can be ≥ 0: where the convex hull of the points `(i/n, y_i)` reaches
/// `y ≥ 0`. `None` when it cannot anywhere.
pub(super) fn nonnegative_range(y: &[f64]) -> Option<(f64, f64)> {
    let n = (y.len() - 1) as f64;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (i, &yi) in y.iter().enumerate() {
        let xi = i as f64 / n;
        if yi >= 0.0 {
            lo = lo.min(xi);
            hi = hi.max(xi);
        }
        for (j, &yj) in y.iter().enumerate().skip(i + 1) {
            if (yi < 0.0) != (yj < 0.0) {
                let xj = j as f64 / n;
                let x = xi + (xj - xi) * yi / (yi - yj);
                lo = lo.min(x);
                hi = hi.max(x);
            }
        }
    }
    (lo <= hi).then_some((lo.max(0.0), hi.min(1.0)))
}

/// A quarter turn in [`pseudo_angle`]'s units.
const QUARTER_TURN: f64 = 1.0;

/// Half a turn in [`pseudo_angle`]'s units.
const HALF_TURN: f64 = 2.0;

/// The direction of `e ≠ 0` as a number in `[0, 4)` that grows with its angle from the
/// `+x` axis and grows by exactly 1 for each quarter turn (the "diamond angle": in each
/// quadrant the share of the second coordinate in the sum of the two): every comparison of
/// angles, and every shift by quarter and half turns, holds for it as for the angle,
/// without a trigonometric function.
fn pseudo_angle(e: DVec2) -> f64 {
    let (x, y) = (e.x, e.y);
    if y >= 0.0 {
        if x >= 0.0 {
            y / (x + y)
        } else {
            1.0 - x / (y - x)
        }
    } else if x < 0.0 {
        2.0 - y / (-x - y)
    } else {
        3.0 + x / (x - y)
    }
}

/// Whether two intervals of line directions (`[θ₀, θ₁]` in [`pseudo_angle`]'s units,
/// modulo half a turn, each narrower than a quarter turn) have no direction in common.
pub(super) fn cones_disjoint((a0, a1): (f64, f64), (b0, b1): (f64, f64)) -> bool {
    let shift = ((a0 - b0) / HALF_TURN).floor() * HALF_TURN;
    [
        shift - HALF_TURN,
        shift,
        shift + HALF_TURN,
        shift + 2.0 * HALF_TURN,
    ]
    .iter()
    .all(|k| b1 + k < a0 || b0 + k > a1)
}

/// Where the chords of two flat sub-segments cross, as segment parameters (clamped to the
/// sub-segments; the midpoints for parallel chords).
pub(super) fn chord_crossing(a: &Sub, b: &Sub) -> (f64, f64) {
    let (p0, p1) = (a.point(0), a.point(a.len() - 1));
    let (q0, q1) = (b.point(0), b.point(b.len() - 1));
    let (d, e) = (p1 - p0, q1 - q0);
    let det = d.perp_dot(e);
    let (alpha, beta) = if det.abs() > 1e-300 {
        let r = q0 - p0;
        (to_unit(r.perp_dot(e) / det), to_unit(r.perp_dot(d) / det))
    } else {
        (0.5, 0.5)
    };
    (a.u0 + alpha * (a.u1 - a.u0), b.u0 + beta * (b.u1 - b.u0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Bezier, BezierSegment};
    use crate::rng::Rng;
    use glam::DVec3;

    fn random_piece(rng: &mut Rng, degree: usize, rational: bool) -> Piece {
        let points = (0..=degree)
            .map(|_| DVec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), 0.0))
            .collect();
        let weights = rational.then(|| (0..=degree).map(|_| rng.range(0.1, 10.0)).collect());
        Piece::new(&BezierSegment {
            bezier: Bezier::new(points),
            weights,
            t0: 0.0,
            t1: 1.0,
        })
    }

    #[test]
    fn a_point_near_the_curve_is_never_surely_off_and_a_far_one_is() {
        let mut rng = Rng::new(5);
        for case in 0..400 {
            let p = random_piece(&mut rng, 1 + case % 7, case % 2 == 1);
            let tol = 10f64.powf(rng.range(-12.0, -2.0));
            let (u0, u1) = if case % 3 == 0 {
                (rng.range(0.0, 0.5), rng.range(0.5, 1.0))
            } else {
                (0.0, 1.0)
            };
            // On the curve, then moved by less than the tolerance in any direction.
            let u = rng.range(u0, u1);
            let angle = rng.range(0.0, std::f64::consts::TAU);
            let near = p.point(u).truncate()
                + 0.9 * tol * rng.unit() * DVec2::new(angle.cos(), angle.sin());
            assert!(
                !surely_off(&p, (u0, u1), near, tol),
                "case {case}: a point within {tol} of the curve at u = {u} called off"
            );
            // Far outside the unit square the points lie in.
            let far = DVec2::new(5.0 * angle.cos(), 5.0 * angle.sin());
            assert!(surely_off(&p, (u0, u1), far, tol), "case {case}: {far}");
        }
    }

    #[test]
    fn pseudo_angles_order_directions_as_angles_and_turn_by_one_a_quarter() {
        let mut rng = Rng::new(6);
        let turn = |e: DVec2| {
            let a = e.y.atan2(e.x);
            if a < 0.0 {
                a + std::f64::consts::TAU
            } else {
                a
            }
        };
        for _ in 0..2000 {
            let e = DVec2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
            let f = DVec2::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
            let (pe, pf) = (pseudo_angle(e), pseudo_angle(f));
            assert!((0.0..4.0).contains(&pe), "{e}: {pe}");
            // Order as the angles in [0, 2π), unless the two are within rounding.
            if (turn(e) - turn(f)).abs() > 1e-12 {
                assert_eq!(pe < pf, turn(e) < turn(f), "{e} {f}: {pe} {pf}");
            }
            // A quarter turn adds exactly one (modulo four).
            let quarter = pseudo_angle(e.perp());
            let want = (pe + QUARTER_TURN) % 4.0;
            assert!(
                (quarter - want).abs() <= 4.0 * f64::EPSILON
                    || (quarter - want).abs() >= 4.0 - 1e-15,
                "{e}: {pe} then {quarter}"
            );
        }
        // The axes and diagonals exactly.
        for (e, want) in [
            (DVec2::X, 0.0),
            (DVec2::new(1.0, 1.0), 0.5),
            (DVec2::Y, 1.0),
            (DVec2::new(-1.0, 1.0), 1.5),
            (-DVec2::X, 2.0),
            (DVec2::new(-1.0, -1.0), 2.5),
            (-DVec2::Y, 3.0),
            (DVec2::new(1.0, -1.0), 3.5),
        ] {
            assert_eq!(pseudo_angle(e), want, "{e}");
        }
    }
}
