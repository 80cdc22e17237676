//! Candidates refined to intersections: Newton's method on `C₁(u) − C₂(v) = 0`, damped
//! (Levenberg–Marquardt) where the Jacobian is singular; the tangency conditions for a
//! touching pair; which side a crossing passes to; the closest point on a piece.

use glam::DVec2;

use super::subdivide::to_unit;
use crate::analysis::piece::Piece;
use crate::analysis::{bernstein_roots, poly};

/// Newton's method on `C₁(u) − C₂(v) = 0` from a candidate, `u`, `v` kept in `[0, 1]`;
/// where a step does not reduce the residual (a singular Jacobian at a tangency, a
/// candidate far off), damped steps (Levenberg–Marquardt) take over. Returns the
/// parameters and the residual.
pub(super) fn refine(a: &Piece, b: &Piece, u: f64, v: f64) -> (f64, f64, f64) {
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
pub(super) struct Lm {
    u: f64,
    v: f64,
    r: DVec2,
    norm: f64,
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
            ja: dp.truncate(),
            jb: -dq.truncate(),
        }
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

/// Whether `a` passes from one side of `b`'s tangent line at `b(v)` to the other around
/// `a(u)` (a crossing at a small angle, or an odd order of contact) rather than staying on
/// one side (touching): the signed distances a step `δ` before and after, where they are
/// far above rounding.
pub(super) fn crosses(a: &Piece, b: &Piece, u: f64, v: f64, (a0, a1): (f64, f64)) -> bool {
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
pub(super) fn refine_tangent(a: &Piece, b: &Piece, mut u: f64, mut v: f64) -> Option<(f64, f64)> {
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
pub(super) fn closest(p: &Piece, (u0, u1): (f64, f64), q: DVec2) -> (f64, f64) {
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
