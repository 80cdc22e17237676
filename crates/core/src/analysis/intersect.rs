//! Intersections of planar curves: two curves, a curve with itself, and every pair among
//! many — on their lowered segments, polynomial or rational.
//!
//! **Two segments.** First, coincidence: a segment's end point on the other segment (its
//! closest point by the root finder, within `1e−9` of their size), two such points, and
//! seven points between them on the other curve, make an *overlap* — reported as a pair
//! of parameter intervals, not a cloud of points. Then subdivision: while the control
//! boxes of two sub-segments overlap, the larger is halved (de Casteljau on the
//! homogeneous points, so the convex hull holds for rational segments too), until both
//! are flat to `1e−6` of their size; their chords' crossing starts Newton's method on
//! `C₁(s) − C₂(t) = 0` (damped, Levenberg–Marquardt, where the Jacobian is singular),
//! which converges to full precision for a transversal crossing and to about `√ε` in the
//! parameters at a tangency. A point is kept when `|C₁(s) − C₂(t)| ≤ 64 ε` times the size;
//! it is a *tangent* point where the tangents are parallel within `1e−6` rad (then the
//! neighbouring candidates, which converge to the same point more slowly, are merged
//! into it), a *crossing* otherwise.
//!
//! **A curve with itself.** Its segments are cut where `x′` or `y′` vanishes: the pieces
//! are monotone in both coordinates and cannot cross themselves; every pair of pieces is
//! intersected, leaving out the joint two neighbours share (and, for a closed curve, the
//! start meeting the end).
//!
//! **Many curves.** A sweep over the segments' boxes sorted by `x` pairs the boxes that
//! overlap; the pairs are intersected on every core (rayon).

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::curve::{AnalysisError, CurveAnalysis, HitKind};
use super::piece::Piece;
use super::{bernstein_roots, poly};

/// One point where two curves meet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// The first curve's parameter.
    pub s: f64,
    /// The second curve's parameter.
    pub t: f64,
    /// The point (the first curve's, at `s`).
    pub point: DVec3,
    /// Crossing or tangent.
    pub kind: HitKind,
    /// A bound on the error of `s` and `t`: a few ulps for a crossing, about `√ε` of the
    /// parameter range at a tangency.
    pub error: f64,
}

/// A stretch where two curves coincide.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Overlap {
    /// The first curve's parameter interval.
    pub s: (f64, f64),
    /// The second curve's parameter interval (in the order matching `s`: `t.0` meets
    /// `s.0`).
    pub t: (f64, f64),
}

/// Everything two curves (or a curve and itself) have in common.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Intersections {
    /// The points, by `s`.
    pub hits: Vec<Hit>,
    /// The coincident stretches, by `s`.
    pub overlaps: Vec<Overlap>,
}

/// The intersections of one pair among many curves.
#[derive(Debug, Clone, PartialEq)]
pub struct PairIntersections {
    /// The first curve's index.
    pub i: usize,
    /// The second curve's index (`i < j`).
    pub j: usize,
    /// What they have in common.
    pub found: Intersections,
}

/// Homogeneous control points, on the stack up to degree 7 (large on purpose: the
/// subdivision makes thousands of them and must not allocate each).
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)]
enum Points {
    Stack([[f64; 3]; 8], usize),
    Heap(Vec<[f64; 3]>),
}

impl Points {
    fn with_len(n: usize) -> Points {
        if n <= 8 {
            Points::Stack([[0.0; 3]; 8], n)
        } else {
            Points::Heap(vec![[0.0; 3]; n])
        }
    }

    fn as_slice(&self) -> &[[f64; 3]] {
        match self {
            Points::Stack(a, n) => &a[..*n],
            Points::Heap(v) => v,
        }
    }

    fn as_mut_slice(&mut self) -> &mut [[f64; 3]] {
        match self {
            Points::Stack(a, n) => &mut a[..*n],
            Points::Heap(v) => v,
        }
    }
}

/// A sub-segment: homogeneous control points `(w x, w y, w)` and its range of the
/// segment's own parameter.
#[derive(Debug, Clone)]
struct Sub {
    h: Points,
    u0: f64,
    u1: f64,
    /// Whether the weights differ from 1 (else the points are Cartesian already).
    rational: bool,
}

impl Sub {
    fn of(p: &Piece, u0: f64, u1: f64) -> Sub {
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

    fn len(&self) -> usize {
        self.h.as_slice().len()
    }

    fn point(&self, i: usize) -> DVec2 {
        let v = self.h.as_slice()[i];
        if self.rational {
            DVec2::new(v[0] / v[2], v[1] / v[2])
        } else {
            DVec2::new(v[0], v[1])
        }
    }

    fn bounds(&self) -> (DVec2, DVec2) {
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
    fn cone(&self) -> Option<(f64, f64)> {
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
    fn clipped_by(&self, other: &Sub) -> Option<Sub> {
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
    fn restricted(&self, lo: f64, hi: f64) -> Sub {
        if lo <= 0.0 && hi >= 1.0 {
            return self.clone();
        }
        let mut h = self.h.clone();
        let pts = h.as_mut_slice();
        let n = pts.len() - 1;
        // Right part at `lo`, then the left part of that at the rescaled `hi`.
        let split_right = |pts: &mut [[f64; 3]], t: f64| {
            let s = 1.0 - t;
            for k in 1..=n {
                for i in 0..=(n - k) {
                    let (p, q) = (pts[i], pts[i + 1]);
                    pts[i] = [
                        s * p[0] + t * q[0],
                        s * p[1] + t * q[1],
                        s * p[2] + t * q[2],
                    ];
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
    fn chord(&self) -> DVec2 {
        self.point(self.len() - 1) - self.point(0)
    }

    /// The largest distance of a control point from the chord.
    fn flatness(&self) -> f64 {
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

    fn halves(&self) -> (Sub, Sub) {
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
fn to_unit(x: f64) -> f64 {
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

fn boxes_meet(a: (DVec2, DVec2), b: (DVec2, DVec2), margin: f64) -> bool {
    a.0.x <= b.1.x + margin
        && b.0.x <= a.1.x + margin
        && a.0.y <= b.1.y + margin
        && b.0.y <= a.1.y + margin
}

/// Candidate `(u, v)` pairs of two segments from subdivision: the crossing of the chords
/// of two sub-segments flat to `flat`, or of two that meet at most once (flat to 5 % of
/// their chords, their tangent cones disjoint).
struct Subdivider {
    flat: f64,
    margin: f64,
    /// `(u, v)` to start from, and — for a pair that meets at most once — the sub-ranges
    /// `(u0, u1, v0, v1)` that hold its one point.
    candidates: Vec<Candidate>,
}

/// A start `(u, v)` for Newton's method, and for a pair meeting at most once the
/// sub-ranges `[u0, u1, v0, v1]` holding its point.
type Candidate = ((f64, f64), Option<[f64; 4]>);

impl Subdivider {
    fn run(&mut self, a: &Sub, b: &Sub, depth: u32) {
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
    fn split(&mut self, a: &Sub, b: &Sub, depth: u32) {
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
fn nonnegative_range(y: &[f64]) -> Option<(f64, f64)> {
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
fn cones_disjoint((a0, a1): (f64, f64), (b0, b1): (f64, f64)) -> bool {
    use std::f64::consts::PI;
    let shift = ((a0 - b0) / PI).floor() * PI;
    [shift - PI, shift, shift + PI, shift + 2.0 * PI]
        .iter()
        .all(|k| b1 + k < a0 || b0 + k > a1)
}

/// Where the chords of two flat sub-segments cross, as segment parameters (clamped to the
/// sub-segments; the midpoints for parallel chords).
fn chord_crossing(a: &Sub, b: &Sub) -> (f64, f64) {
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

/// Newton's method on `C₁(u) − C₂(v) = 0` from a candidate, `u`, `v` kept in `[0, 1]`;
/// where a step does not reduce the residual (a singular Jacobian at a tangency, a
/// candidate far off), damped steps (Levenberg–Marquardt) take over. Returns the
/// parameters and the residual.
fn refine(a: &Piece, b: &Piece, u: f64, v: f64) -> (f64, f64, f64) {
    let mut state = Lm::at(a, b, u, v);
    let mut lambda = 0.0_f64;
    for _ in 0..100 {
        if state.norm == 0.0 {
            break;
        }
        match state.step(a, b, &mut lambda) {
            Some(next) => {
                let tiny = (next.u - state.u).abs() <= f64::EPSILON
                    && (next.v - state.v).abs() <= f64::EPSILON;
                state = next;
                if tiny {
                    break;
                }
            }
            None => break,
        }
    }
    (state.u, state.v, state.norm)
}

/// One point of the damped Newton iteration: the parameters, the residual
/// `C₁(u) − C₂(v)`, its length and the Jacobian's columns.
#[derive(Debug, Clone, Copy)]
struct Lm {
    u: f64,
    v: f64,
    r: DVec2,
    norm: f64,
    ja: DVec2,
    jb: DVec2,
}

impl Lm {
    fn at(a: &Piece, b: &Piece, u: f64, v: f64) -> Lm {
        let ((p, dp), (q, dq)) = (a.point_and_deriv(u), b.point_and_deriv(v));
        let r = (p - q).truncate();
        Lm {
            u,
            v,
            r,
            norm: r.length(),
            ja: dp.truncate(),
            jb: -dq.truncate(),
        }
    }

    /// The next point: `(JᵀJ + λ diag) Δ = −Jᵀ r` (λ = 0: Newton's step), λ raised until
    /// the residual falls (`None` when it never does), then lowered for the next step.
    fn step(&self, a: &Piece, b: &Piece, lambda: &mut f64) -> Option<Lm> {
        let (m11, m12, m22) = (
            self.ja.dot(self.ja),
            self.ja.dot(self.jb),
            self.jb.dot(self.jb),
        );
        let (g1, g2) = (self.ja.dot(self.r), self.jb.dot(self.r));
        for _ in 0..30 {
            let (d11, d22) = (m11 * (1.0 + *lambda), m22 * (1.0 + *lambda));
            let det = d11 * d22 - m12 * m12;
            if det != 0.0 && det.is_finite() {
                let du = -(d22 * g1 - m12 * g2) / det;
                let dv = -(d11 * g2 - m12 * g1) / det;
                let (nu, nv) = (self.u + du, self.v + dv);
                if !(nu.is_finite() && nv.is_finite()) {
                    *lambda = if *lambda == 0.0 { 1e-6 } else { *lambda * 10.0 };
                    continue;
                }
                let next = Lm::at(a, b, to_unit(nu), to_unit(nv));
                if next.norm < self.norm {
                    *lambda *= 0.1;
                    return Some(next);
                }
            }
            *lambda = if *lambda == 0.0 { 1e-6 } else { *lambda * 10.0 };
        }
        None
    }
}

/// Whether `a` passes from one side of `b`'s tangent line at `b(v)` to the other around
/// `a(u)` (a crossing at a small angle, or an odd order of contact) rather than staying on
/// one side (touching): the signed distances a step `δ` before and after, where they are
/// far above rounding.
fn crosses(a: &Piece, b: &Piece, u: f64, v: f64, (a0, a1): (f64, f64)) -> bool {
    let (q, dq) = b.point_and_deriv(v);
    let (q, dq) = (q.truncate(), dq.truncate());
    let side = |w: f64| (a.point(w).truncate() - q).perp_dot(dq);
    let delta = 1e-4 * (a1 - a0);
    let (before, after) = (side((u - delta).max(a0)), side((u + delta).min(a1)));
    let noise = 1e-12 * (q.length() + 1.0) * dq.length();
    before.abs() > noise && after.abs() > noise && (before < 0.0) != (after < 0.0)
}

/// Newton's method on the tangency conditions — `(C₁(u) − C₂(v)) · C₂′(v) = 0` (the foot
/// of the perpendicular) and `C₁′(u) × C₂′(v) = 0` (parallel tangents) — which is regular
/// at a simple tangency where `C₁ = C₂` is not: from a point where the curves touch, it
/// finds the touching point to full precision. `None` when it does not converge inside
/// the ranges.
fn refine_tangent(a: &Piece, b: &Piece, mut u: f64, mut v: f64) -> Option<(f64, f64)> {
    for _ in 0..40 {
        let (p, q) = (a.point(u).truncate(), b.point(v).truncate());
        let (d1, e1) = (a.deriv(u).truncate(), b.deriv(v).truncate());
        let (d2, e2) = (a.second_deriv(u).truncate(), b.second_deriv(v).truncate());
        let r = p - q;
        let f1 = r.dot(e1);
        let f2 = d1.perp_dot(e1);
        let j11 = d1.dot(e1);
        let j12 = -e1.length_squared() + r.dot(e2);
        let j21 = d2.perp_dot(e1);
        let j22 = d1.perp_dot(e2);
        let det = j11 * j22 - j12 * j21;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let du = -(j22 * f1 - j12 * f2) / det;
        let dv = -(j11 * f2 - j21 * f1) / det;
        let (nu, nv) = (u + du, v + dv);
        if !(nu.is_finite() && nv.is_finite()) {
            return None;
        }
        let (nu, nv) = (to_unit(nu), to_unit(nv));
        let done = (nu - u).abs() <= 2.0 * f64::EPSILON && (nv - v).abs() <= 2.0 * f64::EPSILON;
        u = nu;
        v = nv;
        if done {
            return Some((u, v));
        }
    }
    None
}

/// The closest point of piece `p` on its range `[u0, u1]` to `q` (2D): its parameter and
/// distance, from the roots of `(C(u) − q) · C′(u)` (numerator) and the range's ends.
fn closest(p: &Piece, (u0, u1): (f64, f64), q: DVec2) -> (f64, f64) {
    let w = p.w.as_deref();
    // (A − qW) per axis, and the velocity numerator per axis.
    let shifted = |k: usize, qk: f64| -> Vec<f64> {
        match w {
            Some(w) => p.a[k].iter().zip(w).map(|(a, w)| a - qk * w).collect(),
            None => p.a[k].iter().map(|a| a - qk).collect(),
        }
    };
    let dot = poly::sum(
        &poly::product(&shifted(0, q.x), &p.deriv_numerator(0)),
        &poly::product(&shifted(1, q.y), &p.deriv_numerator(1)),
    );
    let mut best = (0.0, f64::INFINITY);
    let mut consider = |u: f64| {
        let d = (p.point(u).truncate() - q).length();
        if d < best.1 {
            best = (u, d);
        }
    };
    consider(u0);
    consider(u1);
    for r in bernstein_roots(&dot).roots {
        if r.t >= u0 && r.t <= u1 {
            consider(r.t);
        }
    }
    best
}

/// Coincident stretches of two segments on their ranges: each end of one range whose
/// point lies on the other, confirmed by seven points between two of them. In segment
/// parameters.
fn segment_overlaps(
    a: &Piece,
    ra: (f64, f64),
    b: &Piece,
    rb: (f64, f64),
    tol: f64,
) -> Vec<SpanPair> {
    let on_b = |u: f64| -> Option<(f64, f64)> {
        let q = a.point(u).truncate();
        let (v, d) = closest(b, rb, q);
        (d <= tol).then_some((u, v))
    };
    let on_a = |v: f64| -> Option<(f64, f64)> {
        let q = b.point(v).truncate();
        let (u, d) = closest(a, ra, q);
        (d <= tol).then_some((u, v))
    };
    let mut ends: Vec<(f64, f64)> = [on_b(ra.0), on_b(ra.1), on_a(rb.0), on_a(rb.1)]
        .into_iter()
        .flatten()
        .collect();
    ends.sort_by(|x, y| x.0.total_cmp(&y.0));
    ends.dedup_by(|x, y| (x.0 - y.0).abs() <= 1e-9 && (x.1 - y.1).abs() <= 1e-9);
    if ends.len() < 2 {
        return Vec::new();
    }
    let (first, last) = (ends[0], ends[ends.len() - 1]);
    if (last.0 - first.0).abs() <= 1e-9 || (last.1 - first.1).abs() <= 1e-9 {
        return Vec::new();
    }
    let coincide = (1..=7).all(|k| {
        let u = first.0 + (last.0 - first.0) * f64::from(k) / 8.0;
        closest(b, rb, a.point(u).truncate()).1 <= tol
    });
    if coincide {
        vec![((first.0, last.0), (first.1, last.1))]
    } else {
        Vec::new()
    }
}

/// The size two pieces are measured by: the diagonal of their control boxes' union.
fn size_of(a: &Piece, b: &Piece) -> f64 {
    let (ba, bb) = (a.bounds(), b.bounds());
    let lo = ba.0.min(bb.0);
    let hi = ba.1.max(bb.1);
    (hi - lo).length().max(f64::MIN_POSITIVE)
}

/// The points and overlaps of two segments, in segment parameters (`u` of `a`, `v` of
/// `b`), on the sub-ranges given.
fn piece_pair(a: &Piece, (a0, a1): (f64, f64), b: &Piece, (b0, b1): (f64, f64)) -> PieceHits {
    let size = size_of(a, b);
    let first = points_of(a, (a0, a1), b, (b0, b1), &[], size);
    // Coincident stretches show as tangent points or as many candidates; only then is the
    // (costlier) coincidence test run, and the points found again outside what coincides.
    if first.iter().all(|h| h.2 == HitKind::Crossing) && first.len() <= 8 {
        return PieceHits {
            hits: first,
            overlaps: Vec::new(),
        };
    }
    let overlaps = segment_overlaps(a, (a0, a1), b, (b0, b1), 1e-9 * size);
    if overlaps.is_empty() {
        return PieceHits {
            hits: first,
            overlaps,
        };
    }
    PieceHits {
        hits: points_of(a, (a0, a1), b, (b0, b1), &overlaps, size),
        overlaps,
    }
}

/// The points where two segments meet on their ranges, outside the given overlaps of `a`
/// (segment parameters).
fn points_of(
    a: &Piece,
    (a0, a1): (f64, f64),
    b: &Piece,
    (b0, b1): (f64, f64),
    overlaps: &[SpanPair],
    size: f64,
) -> Vec<(f64, f64, HitKind)> {
    let tol = 64.0 * f64::EPSILON * size;
    let inside_overlap = |u: f64| {
        overlaps
            .iter()
            .any(|((u0, u1), _)| u >= u0.min(*u1) - 1e-9 && u <= u0.max(*u1) + 1e-9)
    };
    // The parts of `a` outside the overlaps are what the subdivision examines.
    let mut ranges = vec![(a0, a1)];
    for ((u0, u1), _) in overlaps {
        let (lo, hi) = (u0.min(*u1), u0.max(*u1));
        ranges = ranges
            .into_iter()
            .flat_map(|(r0, r1)| {
                let mut parts = Vec::new();
                if lo > r0 {
                    parts.push((r0, lo.min(r1)));
                }
                if hi < r1 {
                    parts.push((hi.max(r0), r1));
                }
                parts
            })
            .filter(|(r0, r1)| r1 > r0)
            .collect();
    }
    let mut sub = Subdivider {
        flat: 1e-6 * size,
        margin: tol,
        candidates: Vec::new(),
    };
    let sb = Sub::of(b, b0, b1);
    for (r0, r1) in ranges {
        sub.run(&Sub::of(a, r0, r1), &sb, 0);
    }
    let mut found: Vec<(f64, f64, HitKind)> = Vec::new();
    // Converged points, to skip candidates of pairs that meet at most once and already
    // hold one (neighbouring leaves share the point on their common edge).
    let mut seen: Vec<(f64, f64)> = Vec::new();
    for &((u, v), single) in &sub.candidates {
        if let Some([u0, u1, v0, v1]) = single
            && seen
                .iter()
                .any(|&(su, sv)| su >= u0 && su <= u1 && sv >= v0 && sv <= v1)
        {
            continue;
        }
        let (u, v, residual) = refine(a, b, u, v);
        if residual <= tol {
            seen.push((u, v));
        }
        if residual > tol || u < a0 || u > a1 || v < b0 || v > b1 || inside_overlap(u) {
            continue;
        }
        let (da, db) = (a.deriv(u).truncate(), b.deriv(v).truncate());
        let sin = da.perp_dot(db).abs() / (da.length() * db.length());
        if (sin.is_finite() && sin > 1e-6) || crosses(a, b, u, v, (a0, a1)) {
            found.push((u, v, HitKind::Crossing));
            continue;
        }
        // A tangency: the touching point itself, where the tangency conditions converge
        // and the curves still meet there.
        let (u, v) = match refine_tangent(a, b, u, v) {
            Some((tu, tv))
                if tu >= a0
                    && tu <= a1
                    && tv >= b0
                    && tv <= b1
                    && (a.point(tu) - b.point(tv)).length() <= tol =>
            {
                (tu, tv)
            }
            _ => (u, v),
        };
        found.push((u, v, HitKind::Tangent));
    }
    found.sort_by(|x, y| x.0.total_cmp(&y.0));
    // One point from candidates that converged to the same place: within a few ulps for
    // crossings, within √ε for tangencies (Newton converges slowly there).
    let mut merged: Vec<(f64, f64, HitKind)> = Vec::new();
    for h in found {
        let same = merged.iter_mut().rev().find(|m| {
            let radius = if m.2 == HitKind::Tangent || h.2 == HitKind::Tangent {
                1e-7
            } else {
                1e-12
            };
            (m.0 - h.0).abs() <= radius && (m.1 - h.1).abs() <= radius
        });
        match same {
            Some(m) => {
                if h.2 == HitKind::Tangent {
                    m.2 = HitKind::Tangent;
                }
            }
            None => merged.push(h),
        }
    }
    merged
}

/// A coincident stretch in two segments' own parameters: `((u0, u1), (v0, v1))`.
type SpanPair = ((f64, f64), (f64, f64));

/// Hits and overlaps of two segments in their own parameters.
#[derive(Debug, Default)]
struct PieceHits {
    hits: Vec<(f64, f64, HitKind)>,
    overlaps: Vec<SpanPair>,
}

/// `u` of a piece as the curve parameter.
fn to_t(p: &Piece, u: f64) -> f64 {
    p.t_of(u)
}

fn hit(a: &Piece, b: &Piece, (u, v, kind): (f64, f64, HitKind)) -> Hit {
    let error = match kind {
        HitKind::Crossing => 8.0 * f64::EPSILON,
        HitKind::Tangent => 1e-7,
    };
    Hit {
        s: to_t(a, u),
        t: to_t(b, v),
        point: a.point(u),
        kind,
        error: error * (a.t1 - a.t0).abs().max(b.t1 - b.t0),
    }
}

/// Sorts hits and overlaps, and merges the copies two neighbouring segments report of a
/// point on their joint, and overlaps that continue across joints.
fn tidy(mut found: Intersections) -> Intersections {
    found
        .hits
        .sort_by(|x, y| x.s.total_cmp(&y.s).then(x.t.total_cmp(&y.t)));
    found.hits.dedup_by(|x, y| {
        (x.s - y.s).abs() <= x.error + y.error && (x.t - y.t).abs() <= x.error + y.error
    });
    found.overlaps.sort_by(|x, y| x.s.0.total_cmp(&y.s.0));
    let mut overlaps: Vec<Overlap> = Vec::new();
    for o in found.overlaps {
        match overlaps.last_mut() {
            Some(last) if (last.s.1 - o.s.0).abs() <= 1e-12 => {
                last.s.1 = o.s.1;
                last.t.1 = o.t.1;
            }
            _ => overlaps.push(o),
        }
    }
    let within = |h: &Hit| {
        overlaps.iter().any(|o| {
            let (lo, hi) = (o.s.0.min(o.s.1), o.s.0.max(o.s.1));
            h.s >= lo - h.error && h.s <= hi + h.error
        })
    };
    found.hits.retain(|h| !within(h));
    found.overlaps = overlaps;
    found
}

impl CurveAnalysis {
    /// The distance from `q` to the curve (2D), by each segment's closest point (segments
    /// whose boxes are farther than the best so far skipped).
    fn distance_to(&self, q: DVec2) -> f64 {
        let mut best = f64::INFINITY;
        for p in self.pieces() {
            let (lo, hi) = piece_box(p);
            let outside = (lo - q).max(q - hi).max(DVec2::ZERO).length();
            if outside < best {
                best = best.min(closest(p, (0.0, 1.0), q).1);
            }
        }
        best
    }

    /// The curve's size: the diagonal of its control box.
    fn size(&self) -> f64 {
        self.control_box().diagonal().max(f64::MIN_POSITIVE)
    }
}

/// Whether `a` stays on `b` (within `tol`) at three points strictly between `s0` and `s1`.
fn coincide_between(a: &CurveAnalysis, b: &CurveAnalysis, s0: f64, s1: f64, tol: f64) -> bool {
    [0.25, 0.5, 0.75].iter().all(|f| {
        let s = s0 + f * (s1 - s0);
        b.distance_to(a.point(s).truncate()) <= tol
    })
}

/// The last cleaning of what two curves have in common, with both curves at hand: a
/// closed curve's start and end are one point; tangent points that the curves join by a
/// stretch along which they stay within `1e−9` of their size (a contact of high order,
/// where Newton's method stops anywhere in a tiny coincident stretch) are one point; and
/// a point joined that way to an overlap's end belongs to the overlap.
fn settle(mut found: Intersections, a: &CurveAnalysis, b: &CurveAnalysis) -> Intersections {
    let close = |c: &CurveAnalysis| c.is_closed().then(|| c.domain());
    if let Some((start, end)) = close(a) {
        let starts: Vec<f64> = found
            .hits
            .iter()
            .filter(|h| h.s == start)
            .map(|h| h.t)
            .collect();
        found
            .hits
            .retain(|h| !(h.s == end && starts.iter().any(|t| (t - h.t).abs() <= 2.0 * h.error)));
    }
    if let Some((start, end)) = close(b) {
        let starts: Vec<f64> = found
            .hits
            .iter()
            .filter(|h| h.t == start)
            .map(|h| h.s)
            .collect();
        found
            .hits
            .retain(|h| !(h.t == end && starts.iter().any(|s| (s - h.s).abs() <= 2.0 * h.error)));
    }
    let tol = 1e-9 * a.size().max(b.size());
    let (da, _) = a.domain();
    let reach = 1e-3 * (a.domain().1 - da).abs();
    // Points joined to an overlap's end by a coincident stretch.
    let overlaps = found.overlaps.clone();
    found.hits.retain(|h| {
        !overlaps.iter().any(|o| {
            [o.s.0, o.s.1].iter().any(|&end| {
                let gap = (h.s - end).abs();
                gap <= reach && (gap == 0.0 || coincide_between(a, b, h.s, end, tol))
            })
        })
    });
    // Tangent points joined by a coincident stretch: one point (the first).
    let mut hits: Vec<Hit> = Vec::with_capacity(found.hits.len());
    for h in std::mem::take(&mut found.hits) {
        if let Some(last) = hits.last()
            && last.kind == HitKind::Tangent
            && h.kind == HitKind::Tangent
            && (h.s - last.s).abs() <= reach
            && coincide_between(a, b, last.s, h.s, tol)
        {
            continue;
        }
        hits.push(h);
    }
    found.hits = hits;
    found
}

/// The control box of a piece, in 2D.
fn piece_box(p: &Piece) -> (DVec2, DVec2) {
    p.bounds()
}

impl CurveAnalysis {
    /// Where this curve and `other` meet (2D): points with both parameters and their kind,
    /// and coincident stretches as parameter intervals.
    ///
    /// # Errors
    /// [`AnalysisError::NotPlanar`] when either curve is 3D.
    pub fn intersect(&self, other: &CurveAnalysis) -> Result<Intersections, AnalysisError> {
        if !self.is_planar() || !other.is_planar() {
            return Err(AnalysisError::NotPlanar {
                what: "intersections",
            });
        }
        let mut found = Intersections::default();
        let boxes_b: Vec<(DVec2, DVec2)> = other.pieces().iter().map(piece_box).collect();
        for a in self.pieces() {
            let ba = piece_box(a);
            for (b, bb) in other.pieces().iter().zip(&boxes_b) {
                let margin = 1e-9 * size_of(a, b);
                if !boxes_meet(ba, *bb, margin) {
                    continue;
                }
                let ph = piece_pair(a, (0.0, 1.0), b, (0.0, 1.0));
                found.hits.extend(ph.hits.into_iter().map(|h| hit(a, b, h)));
                found
                    .overlaps
                    .extend(ph.overlaps.into_iter().map(|((u0, u1), (v0, v1))| Overlap {
                        s: (to_t(a, u0), to_t(a, u1)),
                        t: (to_t(b, v0), to_t(b, v1)),
                    }));
            }
        }
        Ok(settle(tidy(found), self, other))
    }

    /// Where the curve crosses or touches itself (2D), `s < t`: its segments cut into
    /// pieces monotone in `x` and `y`, every pair of pieces intersected, the joints that
    /// neighbouring pieces share (and a closed curve's start meeting its end) left out.
    ///
    /// # Errors
    /// [`AnalysisError::NotPlanar`] for a 3D curve.
    pub fn self_intersections(&self) -> Result<Intersections, AnalysisError> {
        if !self.is_planar() {
            return Err(AnalysisError::NotPlanar {
                what: "self-intersections",
            });
        }
        // Monotone pieces: (segment index, u0, u1).
        let mut parts: Vec<(usize, f64, f64)> = Vec::new();
        for (k, p) in self.pieces().iter().enumerate() {
            let mut cuts: Vec<f64> = (0..2)
                .flat_map(|axis| {
                    bernstein_roots(&p.deriv_numerator(axis))
                        .roots
                        .into_iter()
                        .map(|r| r.t)
                        // An extremum at a joint needs no cut (it would leave a sliver).
                        .filter(|u| *u > 1e-9 && *u < 1.0 - 1e-9)
                })
                .collect();
            cuts.sort_by(f64::total_cmp);
            cuts.dedup_by(|x, y| (*x - *y).abs() <= 1e-12);
            let mut prev = 0.0;
            for c in cuts.into_iter().chain(std::iter::once(1.0)) {
                if c > prev {
                    parts.push((k, prev, c));
                }
                prev = c;
            }
        }
        let (a, b) = self.domain();
        let closed = self.is_closed();
        let pieces = self.pieces();
        let boxes: Vec<(DVec2, DVec2)> = parts
            .iter()
            .map(|&(k, u0, u1)| Sub::of(&pieces[k], u0, u1).bounds())
            .collect();
        let mut found = Intersections::default();
        for i in 0..parts.len() {
            for j in (i + 1)..parts.len() {
                let (pi, pj) = (parts[i], parts[j]);
                let (ka, kb) = (pi.0, pj.0);
                let size = size_of(&pieces[ka], &pieces[kb]);
                if !boxes_meet(boxes[i], boxes[j], 1e-9 * size) {
                    continue;
                }
                let ph = piece_pair(&pieces[ka], (pi.1, pi.2), &pieces[kb], (pj.1, pj.2));
                let ta = |u: f64| to_t(&pieces[ka], u);
                let tb = |v: f64| to_t(&pieces[kb], v);
                let shared = |s: f64, t: f64| {
                    let eps = 1e-9 * (b - a);
                    // One parameter is one point of the curve, not a crossing with itself.
                    if (t - s).abs() <= eps {
                        return true;
                    }
                    // Neighbouring pieces meet at their joint; a closed curve at its ends.
                    (j == i + 1 && (s - ta(pi.2)).abs() <= eps && (t - tb(pj.1)).abs() <= eps)
                        || (closed && (s - a).abs() <= eps && (t - b).abs() <= eps)
                };
                for h in ph.hits {
                    let hh = hit(&pieces[ka], &pieces[kb], h);
                    if !shared(hh.s, hh.t) {
                        found.hits.push(hh);
                    }
                }
                for ((u0, u1), (v0, v1)) in ph.overlaps {
                    found.overlaps.push(Overlap {
                        s: (ta(u0), ta(u1)),
                        t: (tb(v0), tb(v1)),
                    });
                }
            }
        }
        Ok(settle(tidy(found), self, self))
    }
}

/// Every intersecting pair among `curves` (2D; 3D curves are refused): a sweep over the
/// segments' boxes finds the pairs of segments whose boxes overlap, and the pairs are
/// intersected on every core. Pairs in `(i, j)` order with `i < j`; self-intersections
/// are not included.
///
/// # Errors
/// [`AnalysisError::NotPlanar`] naming the first 3D curve.
pub fn all_intersections(
    curves: &[CurveAnalysis],
) -> Result<Vec<PairIntersections>, AnalysisError> {
    if curves.iter().any(|c| !c.is_planar()) {
        return Err(AnalysisError::NotPlanar {
            what: "intersections",
        });
    }
    // (min x, max x, min y, max y, curve, piece)
    let mut items: Vec<(DVec2, DVec2, usize, usize)> = Vec::new();
    for (ci, c) in curves.iter().enumerate() {
        for (pi, p) in c.pieces().iter().enumerate() {
            let (lo, hi) = piece_box(p);
            items.push((lo, hi, ci, pi));
        }
    }
    items.sort_by(|x, y| x.0.x.total_cmp(&y.0.x));
    let mut pairs: Vec<(usize, usize, usize, usize)> = Vec::new();
    for (k, a) in items.iter().enumerate() {
        for b in &items[k + 1..] {
            if b.0.x > a.1.x {
                break;
            }
            if a.2 != b.2 && b.0.y <= a.1.y && a.0.y <= b.1.y {
                let (first, second) = if a.2 < b.2 { (a, b) } else { (b, a) };
                pairs.push((first.2, first.3, second.2, second.3));
            }
        }
    }
    // Grouped by pair of curves, then by their segments.
    pairs.sort_unstable_by_key(|&(ci, pi, cj, pj)| (ci, cj, pi, pj));
    let results: Vec<(usize, usize, PieceHits, usize, usize)> = pairs
        .par_iter()
        .map(|&(ci, pi, cj, pj)| {
            let (a, b) = (&curves[ci].pieces()[pi], &curves[cj].pieces()[pj]);
            (ci, cj, piece_pair(a, (0.0, 1.0), b, (0.0, 1.0)), pi, pj)
        })
        .collect();
    let mut out: Vec<PairIntersections> = Vec::new();
    for (ci, cj, ph, pi, pj) in results {
        if ph.hits.is_empty() && ph.overlaps.is_empty() {
            continue;
        }
        let (a, b) = (&curves[ci].pieces()[pi], &curves[cj].pieces()[pj]);
        let entry = match out.last_mut() {
            Some(e) if e.i == ci && e.j == cj => e,
            _ => {
                out.push(PairIntersections {
                    i: ci,
                    j: cj,
                    found: Intersections::default(),
                });
                out.last_mut()
                    .unwrap_or_else(|| unreachable!("just pushed"))
            }
        };
        entry
            .found
            .hits
            .extend(ph.hits.into_iter().map(|h| hit(a, b, h)));
        entry
            .found
            .overlaps
            .extend(ph.overlaps.into_iter().map(|((u0, u1), (v0, v1))| Overlap {
                s: (to_t(a, u0), to_t(a, u1)),
                t: (to_t(b, v0), to_t(b, v1)),
            }));
    }
    Ok(out
        .into_iter()
        .map(|mut p| {
            p.found = settle(tidy(p.found), &curves[p.i], &curves[p.j]);
            p
        })
        .collect())
}
