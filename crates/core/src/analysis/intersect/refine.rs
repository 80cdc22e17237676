//! Candidates refined to intersections: Newton's method on `C₁(u) − C₂(v) = 0`, damped
//! (Levenberg–Marquardt) where the Jacobian is singular; the tangency conditions for a
//! touching pair; which side a crossing passes to; the closest point on a piece.

use glam::DVec2;

use super::subdivide::to_unit;
use crate::analysis::piece::Piece;

/// Newton's method on `C₁(u) − C₂(v) = 0` from a candidate, `u`, `v` kept in `[0, 1]`:
/// the 2×2 system solved directly (its conditioning is the crossing's, where the normal
/// equations would square it), a step halved until the residual falls — which keeps it
/// converging, linearly, at a tangency of any order; where no halving helps (a candidate
/// far off), damped steps (Levenberg–Marquardt) take over. It stops early where
/// `stop(u, v)` holds (inside a point already found, to which it is converging —
/// linearly, at a contact of high order). Returns the parameters and the residual.
pub(super) fn refine_until(
    a: &Piece,
    b: &Piece,
    u: f64,
    v: f64,
    stop: impl Fn(f64, f64) -> bool,
) -> (f64, f64, f64) {
    let mut state = Lm::at(a, b, u, v);
    let mut lambda = 0.0_f64;
    for _ in 0..200 {
        if state.norm == 0.0 || stop(state.u, state.v) {
            break;
        }
        // At the rounding floor of the residual no step can reduce it: the point is
        // found (the damped steps would only spend evaluations on noise).
        let floor = state.norm <= ROUNDING_FLOOR * f64::EPSILON * state.size;
        let next = match state.newton(a, b, floor) {
            Some(next) => next,
            None if floor => break,
            None => match state.step(a, b, &mut lambda) {
                Some(next) => next,
                None => break,
            },
        };
        let tiny =
            (next.u - state.u).abs() <= f64::EPSILON && (next.v - state.v).abs() <= f64::EPSILON;
        state = next;
        if tiny {
            break;
        }
    }
    (state.u, state.v, state.norm)
}

/// One point of the damped Newton iteration: the parameters, the residual
/// `C₁(u) − C₂(v)`, its length and the Jacobian's columns.
/// A residual within this many `ε` of the points' size is rounding: an evaluation of
/// degree `n` errs by up to `γ_{2n}` times the size (about `2n ε`), each of the two.
const ROUNDING_FLOOR: f64 = 8.0;

#[derive(Debug, Clone, Copy)]
pub(super) struct Lm {
    u: f64,
    v: f64,
    r: DVec2,
    norm: f64,
    /// The larger of the two points' distances from the origin (the residual's rounding
    /// is relative to it).
    size: f64,
    ja: DVec2,
    jb: DVec2,
}

impl Lm {
    pub(super) fn at(a: &Piece, b: &Piece, u: f64, v: f64) -> Lm {
        let ((p, dp), (q, dq)) = (a.point_and_deriv(u), b.point_and_deriv(v));
        let r = (p - q).truncate();
        Lm {
            u,
            v,
            r,
            norm: r.length(),
            size: p.truncate().length().max(q.truncate().length()),
            ja: dp.truncate(),
            jb: -dq.truncate(),
        }
    }

    /// Newton's step `J Δ = −r` by Cramer's rule, halved up to eight times until the
    /// residual falls (not halved at the rounding floor, `floor`: there the full step
    /// either helps or nothing does); `None` when it never does or `J` is singular.
    fn newton(&self, a: &Piece, b: &Piece, floor: bool) -> Option<Lm> {
        let det = self.ja.perp_dot(self.jb);
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let mut du = -self.r.perp_dot(self.jb) / det;
        let mut dv = -self.ja.perp_dot(self.r) / det;
        for _ in 0..8 {
            if !(du.is_finite() && dv.is_finite()) {
                return None;
            }
            let next = Lm::at(a, b, to_unit(self.u + du), to_unit(self.v + dv));
            if next.norm < self.norm {
                return Some(next);
            }
            if floor {
                return None;
            }
            du *= 0.5;
            dv *= 0.5;
        }
        None
    }

    /// The next point: `(JᵀJ + λ diag) Δ = −Jᵀ r` (λ = 0: Newton's step), λ raised until
    /// the residual falls (`None` when it never does), then lowered for the next step.
    pub(super) fn step(&self, a: &Piece, b: &Piece, lambda: &mut f64) -> Option<Lm> {
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

/// Newton's method on the tangency conditions — `(C₁(u) − C₂(v)) · C₂′(v) = 0` (the foot
/// of the perpendicular) and `C₁′(u) × C₂′(v) = 0` (parallel tangents) — which is regular
/// at a simple tangency where `C₁ = C₂` is not: from a point where the curves touch, it
/// finds the touching point to full precision; at a contact of higher order it converges
/// linearly, and a step that does not reduce the conditions is halved. `None` when it
/// does not converge inside the segments to a point whose tangents are parallel to within
/// `10⁻⁷` (about `√ε`: a contact of high order stops there).
pub(super) fn refine_tangent(a: &Piece, b: &Piece, mut u: f64, mut v: f64) -> Option<(f64, f64)> {
    // The conditions, scaled to a length and a sine, and their Jacobian.
    let eval = |u: f64, v: f64| {
        let ((p, d1), (q, e1)) = (a.point_and_deriv(u), b.point_and_deriv(v));
        let (p, d1, q, e1) = (p.truncate(), d1.truncate(), q.truncate(), e1.truncate());
        let r = p - q;
        let (f1, f2) = (r.dot(e1), d1.perp_dot(e1));
        let norm = f1.abs() / e1.length() + f2.abs() / (d1.length() * e1.length());
        (r, d1, e1, f1, f2, norm)
    };
    let (mut r, mut d1, mut e1, mut f1, mut f2, mut norm) = eval(u, v);
    let parallel = |d1: DVec2, e1: DVec2| d1.perp_dot(e1).abs() <= 1e-7 * d1.length() * e1.length();
    for _ in 0..80 {
        if norm == 0.0 {
            return Some((u, v));
        }
        let (d2, e2) = (a.second_deriv(u).truncate(), b.second_deriv(v).truncate());
        let j11 = d1.dot(e1);
        let j12 = -e1.length_squared() + r.dot(e2);
        let j21 = d2.perp_dot(e1);
        let j22 = d1.perp_dot(e2);
        let det = j11 * j22 - j12 * j21;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let mut du = -(j22 * f1 - j12 * f2) / det;
        let mut dv = -(j11 * f2 - j21 * f1) / det;
        if !(du.is_finite() && dv.is_finite()) {
            return None;
        }
        // Halve the step until the conditions fall (a few times at most near a root).
        let mut accepted = None;
        for _ in 0..30 {
            let (nu, nv) = (to_unit(u + du), to_unit(v + dv));
            let next = eval(nu, nv);
            if next.5 < norm || (nu == u && nv == v) {
                accepted = Some((nu, nv, next));
                break;
            }
            du *= 0.5;
            dv *= 0.5;
        }
        let Some((nu, nv, next)) = accepted else {
            // No step reduces them: as converged as f64 allows, if the tangents agree.
            return parallel(d1, e1).then_some((u, v));
        };
        let done = (nu - u).abs() <= 2.0 * f64::EPSILON && (nv - v).abs() <= 2.0 * f64::EPSILON;
        (u, v) = (nu, nv);
        (r, d1, e1, f1, f2, norm) = next;
        if done {
            return parallel(d1, e1).then_some((u, v));
        }
    }
    None
}

/// The foot of the perpendicular from `q` on `p` near `v` (Newton's method on
/// `(C(v) − q) · C′(v)`, kept in `range`): for points walking along a curve that stays
/// close to `p`, and to polish a root of the product polynomial (whose coefficients lose
/// digits when the weights lie far apart).
pub(super) fn foot(p: &Piece, range: (f64, f64), q: DVec2, v: f64) -> f64 {
    foot_converged(p, range, q, v).0
}

/// [`foot`], and whether it converged (to a local minimum of the distance, as far as
/// `f64` can tell): each step — Newton's where the squared distance is convex, else
/// Gauss–Newton's — halved until the distance does not grow.
pub(super) fn foot_converged(p: &Piece, range: (f64, f64), q: DVec2, mut v: f64) -> (f64, bool) {
    let dist = |v: f64| (p.point(v).truncate() - q).length_squared();
    let mut here = dist(v);
    for _ in 0..60 {
        let (c, d) = p.point_and_deriv(v);
        let (c, d) = (c.truncate(), d.truncate());
        let dd = p.second_deriv(v).truncate();
        let g = (c - q).dot(d);
        let speed2 = d.length_squared();
        let full = speed2 + (c - q).dot(dd);
        // Newton's step where the squared distance is clearly convex, else Gauss–Newton's;
        // never longer than the range.
        let dg = if full > 0.1 * speed2 && full.is_finite() {
            full
        } else {
            speed2
        };
        if dg.is_nan() || dg <= 0.0 || !dg.is_finite() || g == 0.0 {
            return (v, g == 0.0 || here == 0.0);
        }
        let width = range.1 - range.0;
        let mut step = (-g / dg).max(-width).min(width);
        let mut moved = None;
        for _ in 0..40 {
            let next = (v + step).max(range.0).min(range.1);
            let there = dist(next);
            if there <= here {
                moved = Some((next, there));
                break;
            }
            step *= 0.5;
        }
        let Some((next, there)) = moved else {
            // No step helps: a minimum to rounding if the slope is at its rounding level.
            let level = 8.0 * f64::EPSILON * d.length() * (c.length() + q.length());
            return (v, g.abs() <= level);
        };
        let tiny = (next - v).abs() <= 2.0 * f64::EPSILON * v.abs().max(f64::MIN_POSITIVE);
        (v, here) = (next, there);
        if tiny || here == 0.0 {
            return (v, true);
        }
    }
    (v, false)
}
