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
            let axis = |c: &[f64]| poly::restrict(c, u0, u1);
            let ones;
            let w = match &p.w {
                Some(w) => w.as_slice(),
                None => {
                    ones = vec![1.0; n];
                    ones.as_slice()
                }
            };
            let (x, y, w) = (axis(&p.a[0]), axis(&p.a[1]), axis(w));
            for (i, slot) in slots.iter_mut().enumerate() {
                *slot = [x[i], y[i], w[i]];
            }
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

    /// The directions of the control polygon's legs as an angular interval `[θ₀, θ₁]`
    /// (narrower than π/2), or `None` when they spread wider. The curve's tangent — for
    /// positive weights a rational one's too — is a positive combination of the legs, so
    /// it stays inside.
    pub(super) fn cone(&self) -> Option<(f64, f64)> {
        use std::f64::consts::{FRAC_PI_2, PI};
        let n = self.len() - 1;
        let mut first: Option<f64> = None;
        let (mut lo, mut hi) = (0.0_f64, 0.0_f64);
        for i in 0..n {
            let e = self.point(i + 1) - self.point(i);
            if e.x == 0.0 && e.y == 0.0 {
                continue;
            }
            let angle = e.y.atan2(e.x);
            match first {
                None => first = Some(angle),
                Some(f) => {
                    // Relative to the first leg, in (−π, π].
                    let mut d = angle - f;
                    if d > PI {
                        d -= 2.0 * PI;
                    } else if d <= -PI {
                        d += 2.0 * PI;
                    }
                    lo = lo.min(d);
                    hi = hi.max(d);
                    if hi - lo >= FRAC_PI_2 {
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

/// Whether two angular intervals of line directions (`[θ₀, θ₁]` modulo π, each narrower
/// than π/2) have no direction in common.
pub(super) fn cones_disjoint((a0, a1): (f64, f64), (b0, b1): (f64, f64)) -> bool {
    use std::f64::consts::PI;
    let shift = ((a0 - b0) / PI).floor() * PI;
    [shift - PI, shift, shift + PI, shift + 2.0 * PI]
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
