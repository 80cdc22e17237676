//! Batch evaluation: many parameters of one curve, and many curves at once, for every
//! family through its exact Bézier segments. Nothing allocates once a [`CurveSampler`]
//! exists; cubics and lower degrees are written out; degrees 4 to 31 run Bernstein–Horner
//! (O(n) per point) where the CPU fuses multiply-adds, de Casteljau in a stack buffer
//! otherwise; [`sample_many`] spreads curves over every core (rayon).
//!
//! Accuracy: each point is the evaluation of the segment that holds `t`, at the local
//! parameter `u = (t − t0)/(t1 − t0)`, within `γ_{2n} Σ|P_i| B_i(u) ≈ 2 n ε Σ|P_i| B_i(u)`
//! (`ε = 2⁻⁵³`, `n` the segment's degree) of the exact value of the lowered segment
//! (`docs/math.md` §4) — tested against exact rational evaluation at degrees 1–40
//! (`crates/scene/tests/batch_eval.rs`).

use glam::DVec3;
use rayon::prelude::*;

use super::{BezierSegment, Curve, Lower};

/// Control points evaluated on the stack by the general path; longer curves use the
/// allocating [`super::bezier`] evaluation.
const STACK: usize = 32;

/// `P(u)` for the Bézier curve `points` at every `us[k]`, into `out[k]`: written-out
/// forms for degrees 1 to 3 (the cubic in Bernstein form); degrees 4 to 31 by
/// Bernstein–Horner where the CPU fuses multiply-adds and `u ∈ [0, 1]`, else by
/// de Casteljau; higher degrees by de Casteljau.
///
/// # Panics
/// If `us` and `out` differ in length.
pub fn bezier_into(points: &[DVec3], us: &[f64], out: &mut [DVec3]) {
    assert_eq!(us.len(), out.len(), "one output per parameter");
    match *points {
        [] => out.fill(DVec3::ZERO),
        [p0] => out.fill(p0),
        [p0, p1] => {
            for (o, &u) in out.iter_mut().zip(us) {
                let s = 1.0 - u;
                *o = s * p0 + u * p1;
            }
        }
        [p0, p1, p2] => {
            for (o, &u) in out.iter_mut().zip(us) {
                let s = 1.0 - u;
                let (q0, q1) = (s * p0 + u * p1, s * p1 + u * p2);
                *o = s * q0 + u * q1;
            }
        }
        [p0, p1, p2, p3] => {
            let planar = points.iter().all(|p| p.z.to_bits() == 0);
            for (o, &u) in out.iter_mut().zip(us) {
                *o = cubic([p0, p1, p2, p3], u, planar);
            }
        }
        _ if points.len() <= STACK => {
            // Four parameters at a time, one lane each, z skipped for a planar segment (its
            // z is then exactly 0 for every parameter): Bernstein–Horner where the CPU
            // fuses multiply-adds, de Casteljau otherwise.
            let planar = points.iter().all(|p| p.z.to_bits() == 0);
            general_lanes(points, &BINOMIALS[points.len() - 1], us, planar, out);
        }
        _ => {
            for (o, &u) in out.iter_mut().zip(us) {
                *o = super::bezier::de_casteljau(points, u);
            }
        }
    }
}

/// Parameters evaluated together by [`de_casteljau_lanes`].
const LANES: usize = 4;

/// De Casteljau at `LANES` parameters at once, coordinates in separate lane arrays (so
/// the inner loop vectorises): `out[l] = P(u[l])`, each lane computing
/// `P_i ← (1 − u) P_i + u P_{i+1}` exactly as [`super::bezier::de_casteljau_in_place`]
/// does. `planar` skips `z` (all control points have `z = +0`, so every level's `z` is
/// `+0`). At most [`STACK`] points.
fn de_casteljau_lanes(points: &[DVec3], u: &[f64; LANES], planar: bool, out: &mut [DVec3]) {
    let n = points.len();
    let mut x = [[0.0_f64; LANES]; STACK];
    let mut y = [[0.0_f64; LANES]; STACK];
    let mut z = [[0.0_f64; LANES]; STACK];
    for (j, p) in points.iter().enumerate() {
        x[j] = [p.x; LANES];
        y[j] = [p.y; LANES];
        z[j] = [p.z; LANES];
    }
    let s = u.map(|u| 1.0 - u);
    let level = |c: &mut [[f64; LANES]; STACK], len: usize| {
        for i in 0..len {
            let next = c[i + 1];
            for l in 0..LANES {
                c[i][l] = s[l] * c[i][l] + u[l] * next[l];
            }
        }
    };
    for r in 1..n {
        level(&mut x, n - r);
        level(&mut y, n - r);
        if !planar {
            level(&mut z, n - r);
        }
    }
    for (l, o) in out.iter_mut().enumerate() {
        *o = DVec3::new(x[0][l], y[0][l], if planar { 0.0 } else { z[0][l] });
    }
}

/// `C(n, k)` for `n < STACK`, `k ≤ n` (Pascal's triangle, built at compile time): exact,
/// every one an integer below 2⁵³.
const BINOMIALS: [[f64; STACK]; STACK] = {
    let mut ints = [[0_u64; STACK]; STACK];
    let mut out = [[0.0_f64; STACK]; STACK];
    let mut n = 0;
    while n < STACK {
        ints[n][0] = 1;
        let mut k = 1;
        while k <= n {
            ints[n][k] = ints[n - 1][k - 1] + ints[n - 1][k];
            k += 1;
        }
        let mut k = 0;
        while k <= n {
            out[n][k] = ints[n][k] as f64;
            k += 1;
        }
        n += 1;
    }
    out
};

/// The most parameters of one segment evaluated by one call of [`bezier_into`] (the
/// scratch of [`CurveSampler::eval_into`]).
const RUN: usize = 256;

/// The most parameters the rational path evaluates at once (its scratch).
const RATIONAL_RUN: usize = 64;

/// Parameters evaluated together by [`bernstein_horner_block`].
const BLOCK: usize = 16;

/// The general path of [`bezier_into`] (`points.len() ≤ STACK`): where the CPU fuses
/// multiply-adds (compiled also for AVX2 + FMA and chosen at run time), blocks of
/// parameters all in `[0, 1]` go to [`bernstein_horner_block`] — O(n) per point, within
/// `γ_{2n} Σ|P_i| B_i(u)` (`docs/math.md` §4); the others to [`de_casteljau_lanes`]
/// (O(n²), within the same bound where `1 − u` is exact), four at a time, and one by one
/// at the end.
#[multiversion::multiversion(targets("x86_64+avx2+fma"))]
fn general_lanes(
    points: &[DVec3],
    binomials: &[f64; STACK],
    us: &[f64],
    planar: bool,
    out: &mut [DVec3],
) {
    let fused = multiversion::target::selected_target!().supports_feature_str("fma");
    for (ub, ob) in us.chunks(BLOCK).zip(out.chunks_mut(BLOCK)) {
        if fused && ub.iter().all(|u| (0.0..=1.0).contains(u)) {
            bernstein_horner_block(points, binomials, ub, planar, ob);
            // Its partial sums weigh the points by `C(n, k) u^k`, which can pass 1:
            // coordinates near the top of the double range overflow there while de
            // Casteljau's convex combinations do not. Such a block is evaluated again.
            if ob.iter().all(|p| p.is_finite()) || !points.iter().all(|p| p.is_finite()) {
                continue;
            }
        }
        let mut groups = ub.chunks_exact(LANES).zip(ob.chunks_exact_mut(LANES));
        for (u, o) in &mut groups {
            let u: &[f64; LANES] = u.try_into().unwrap_or(&[0.0; LANES]);
            de_casteljau_lanes(points, u, planar, o);
        }
        let done = ub.len() - ub.len() % LANES;
        let n = points.len();
        let mut buf = [DVec3::ZERO; STACK];
        for (o, &u) in ob[done..].iter_mut().zip(&ub[done..]) {
            buf[..n].copy_from_slice(points);
            *o = super::bezier::de_casteljau_in_place(&mut buf[..n], u);
        }
    }
}

/// `P(u) = Σ C(n, k) u^k (1 − u)^{n−k} P_k` at up to [`BLOCK`] parameters in `[0, 1]` by
/// Horner's rule in `1 − u` with the powers of `u` built along the way:
/// `q ← fma(C(n, k) u^k, P_k, fma(−q, u, q))` for `k = 1..=n` from `q = P_0`.
/// `fma(−q, u, q)` is `q (1 − u)` rounded once — `1 − u` is never rounded — so term `k`
/// passes `k` roundings in its weight, one in the step that adds it and two in each of
/// the `n − k` steps after: at most `2n`, and `|P̂ − P| ≤ γ_{2n} Σ|P_i| B_i(u)`
/// (`γ_m = m 2⁻⁵³ / (1 − m 2⁻⁵³)`), de Casteljau's bound where `1 − u` is exact, for
/// `n` steps of `2 + 2·dims` operations instead of `n(n + 1)/2` interpolations. The ends
/// are exact: at `u = 0` every weight is 0, at `u = 1` every step but the last multiplies
/// by 0 and the last adds `1 · P_n`. `planar` skips `z` (then exactly 0). Called only
/// where `mul_add` is one instruction; each step is a simple loop over the block, which
/// the compiler vectorises.
#[inline(always)]
fn bernstein_horner_block(
    points: &[DVec3],
    binomials: &[f64; STACK],
    us: &[f64],
    planar: bool,
    out: &mut [DVec3],
) {
    let m = us.len().min(BLOCK);
    let mut u = [0.0_f64; BLOCK];
    u[..m].copy_from_slice(&us[..m]);
    let first = points[0];
    let (mut qx, mut qy, mut qz) = ([first.x; BLOCK], [first.y; BLOCK], [first.z; BLOCK]);
    let mut power = [1.0_f64; BLOCK];
    for (p, &c) in points.iter().zip(binomials).skip(1) {
        for l in 0..BLOCK {
            power[l] *= u[l];
            let w = c * power[l];
            qx[l] = w.mul_add(p.x, (-qx[l]).mul_add(u[l], qx[l]));
            qy[l] = w.mul_add(p.y, (-qy[l]).mul_add(u[l], qy[l]));
        }
        if !planar {
            for l in 0..BLOCK {
                let w = c * power[l];
                qz[l] = w.mul_add(p.z, (-qz[l]).mul_add(u[l], qz[l]));
            }
        }
    }
    for (l, o) in out.iter_mut().enumerate().take(m) {
        *o = DVec3::new(qx[l], qy[l], if planar { 0.0 } else { qz[l] });
    }
}

/// The cubic Bernstein weights at `u`: `(s³, 3s²u, 3su², u³)`, `s = 1 − u`.
#[inline]
fn cubic_weights(u: f64) -> [f64; 4] {
    let s = 1.0 - u;
    let (s2, u2) = (s * s, u * u);
    [s2 * s, 3.0 * s2 * u, 3.0 * s * u2, u2 * u]
}

/// A cubic in Bernstein form, `s³P₀ + 3s²uP₁ + 3su²P₂ + u³P₃` (`s = 1 − u`): fewer
/// operations than de Casteljau's six interpolations, within the same bound. `planar`
/// skips `z` (all control points have `z = +0`, so the sum's `z` is exactly 0 anyway).
#[inline]
fn cubic(p: [DVec3; 4], u: f64, planar: bool) -> DVec3 {
    let [a, b, c, d] = cubic_weights(u);
    let sum = |k: usize| a * p[0][k] + b * p[1][k] + c * p[2][k] + d * p[3][k];
    DVec3::new(sum(0), sum(1), if planar { 0.0 } else { sum(2) })
}

/// A rational quadratic or cubic at every `us[k]` into `out[k]`, the numerator `A` and the
/// weight `W` summed in one pass with the same Bernstein weights (the written-out forms of
/// the polynomial path: `s²`, `2su`, `u²` and the cubic's), then divided — what two
/// polynomial passes and a division cost, in about one. `false` (nothing written) for
/// other degrees. (Planar ones take [`planar_rational`].)
fn fused_rational(a: &[DVec3], w: &[DVec3], us: &[f64], out: &mut [DVec3]) -> bool {
    match (a, w) {
        ([a0, a1, a2], [w0, w1, w2]) => {
            let h = [*a0, *a1, *a2].map(|p| p.to_array());
            let ws = [w0.x, w1.x, w2.x];
            for (o, &u) in out.iter_mut().zip(us) {
                let s = 1.0 - u;
                let b = [s * s, 2.0 * s * u, u * u];
                let den = b[0] * ws[0] + b[1] * ws[1] + b[2] * ws[2];
                let coord = |d: usize| b[0] * h[0][d] + b[1] * h[1][d] + b[2] * h[2][d];
                *o = DVec3::new(coord(0), coord(1), coord(2)) / den;
            }
            true
        }
        ([a0, a1, a2, a3], [w0, w1, w2, w3]) => {
            let h = [*a0, *a1, *a2, *a3].map(|p| p.to_array());
            let ws = [w0.x, w1.x, w2.x, w3.x];
            for (o, &u) in out.iter_mut().zip(us) {
                let b = cubic_weights(u);
                let den = b[0] * ws[0] + b[1] * ws[1] + b[2] * ws[2] + b[3] * ws[3];
                let coord =
                    |d: usize| b[0] * h[0][d] + b[1] * h[1][d] + b[2] * h[2][d] + b[3] * h[3][d];
                *o = DVec3::new(coord(0), coord(1), coord(2)) / den;
            }
            true
        }
        _ => false,
    }
}

/// A planar rational quadratic or cubic (the sums of [`fused_rational`]), a block of
/// parameters at a time with each step one loop over the block (Bernstein weights, the
/// sums of `x`, `y` and the weight, the two divisions, the stores): the loops vectorise
/// across parameters (compiled also for AVX2, chosen at run time). The operations on each
/// parameter are the ones of the scalar forms — no fused multiply-adds — so every CPU gets
/// the same bits.
#[multiversion::multiversion(targets("x86_64+avx2"))]
fn planar_rational(xy: [[f64; 4]; 2], ws: [f64; 4], cubic: bool, us: &[f64], out: &mut [DVec3]) {
    const B: usize = 16;
    for (ub, ob) in us.chunks(B).zip(out.chunks_mut(B)) {
        let mut u = [0.0_f64; B];
        u[..ub.len()].copy_from_slice(ub);
        let mut b = [[0.0_f64; B]; 4];
        for l in 0..B {
            let s = 1.0 - u[l];
            if cubic {
                let (s2, u2) = (s * s, u[l] * u[l]);
                b[0][l] = s2 * s;
                b[1][l] = 3.0 * s2 * u[l];
                b[2][l] = 3.0 * s * u2;
                b[3][l] = u2 * u[l];
            } else {
                b[0][l] = s * s;
                b[1][l] = 2.0 * s * u[l];
                b[2][l] = u[l] * u[l];
            }
        }
        let sum = |c: &[f64; 4], l: usize| {
            let v = b[0][l] * c[0] + b[1][l] * c[1] + b[2][l] * c[2];
            if cubic { v + b[3][l] * c[3] } else { v }
        };
        let (mut x, mut y) = ([0.0_f64; B], [0.0_f64; B]);
        for l in 0..B {
            let den = sum(&ws, l);
            x[l] = sum(&xy[0], l) / den;
            y[l] = sum(&xy[1], l) / den;
        }
        for (l, o) in ob.iter_mut().enumerate() {
            *o = DVec3::new(x[l], y[l], 0.0);
        }
    }
}

/// A rational segment's homogeneous parts as polynomial Bézier control points: `A` (the
/// weighted points) and `W` (the weights as `(w, 0, 0)`), each with its first and second
/// hodographs (in the segment's own parameter).
#[derive(Debug, Clone, PartialEq)]
struct Homogeneous {
    a: [Vec<DVec3>; 3],
    w: [Vec<DVec3>; 3],
    /// A planar quadratic or cubic's weighted `x`, `y` and weights inline, so that
    /// evaluating it reads no memory beyond the sampler's own arrays.
    planar: Option<PlanarRational>,
}

/// A planar rational quadratic or cubic: per control point its weighted `x` and `y` and
/// its weight (the fourth entries 0 for a quadratic).
#[derive(Debug, Clone, Copy, PartialEq)]
struct PlanarRational {
    xy: [[f64; 4]; 2],
    ws: [f64; 4],
    cubic: bool,
}

impl PlanarRational {
    fn of(a: &[DVec3], w: &[DVec3]) -> Option<PlanarRational> {
        let planar = a.iter().all(|p| p.z.to_bits() == 0);
        if !planar || !matches!(a.len(), 3 | 4) || a.len() != w.len() {
            return None;
        }
        let mut out = PlanarRational {
            xy: [[0.0; 4]; 2],
            ws: [0.0; 4],
            cubic: a.len() == 4,
        };
        for (i, (p, q)) in a.iter().zip(w).enumerate() {
            out.xy[0][i] = p.x;
            out.xy[1][i] = p.y;
            out.ws[i] = q.x;
        }
        Some(out)
    }
}

impl Homogeneous {
    fn of(seg: &BezierSegment) -> Option<Homogeneous> {
        seg.weights.as_ref()?;
        let hodographs = |b0: super::Bezier| {
            let b1 = b0.deriv();
            let b2 = b1.deriv();
            [b0, b1, b2].map(|b| b.points().to_vec())
        };
        let (a, w) = seg.homogeneous();
        let (a, w) = (hodographs(a), hodographs(w));
        let planar = PlanarRational::of(&a[0], &w[0]);
        Some(Homogeneous { a, w, planar })
    }
}

/// A curve lowered once, ready to be evaluated at many parameters without allocating.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveSampler {
    segments: Vec<BezierSegment>,
    /// A curve of one cubic segment keeps its control points inline too, so that
    /// sampling many such curves reads one contiguous array.
    single_cubic: Option<[DVec3; 4]>,
    /// Per segment, the rational piece's homogeneous parts (`None` for a polynomial one),
    /// evaluated like polynomial pieces and combined by the quotient rule.
    rational: Vec<Option<Homogeneous>>,
    /// The derivative this sampler evaluates on rational pieces (0, 1 or 2; polynomial
    /// pieces hold their hodographs instead).
    order: u32,
}

impl CurveSampler {
    /// Lowers `curve` (the only allocation).
    #[must_use]
    pub fn new(curve: &Curve) -> CurveSampler {
        let segments = curve.lower();
        let single_cubic = match segments.as_slice() {
            [seg] if !seg.is_rational() => match *seg.bezier.points() {
                [a, b, c, d] => Some([a, b, c, d]),
                _ => None,
            },
            _ => None,
        };
        let rational = segments.iter().map(Homogeneous::of).collect();
        CurveSampler {
            segments,
            single_cubic,
            rational,
            order: 0,
        }
    }

    /// The sampler of the `order`-th derivative with respect to the curve's parameter:
    /// each segment's hodograph taken `order` times, its points divided by
    /// `(t1 − t0)^order` (the chain rule from the segment's local parameter), on the same
    /// parameter ranges. Evaluating it costs what evaluating the curve costs, whatever
    /// the family. A rational piece has no polynomial hodograph: it keeps its curve and
    /// evaluates the derivative by the quotient rule (`order` 1 or 2; higher orders
    /// give the second derivative's `order` too — only 1 and 2 are asked for).
    ///
    /// # Panics
    /// If `order` is above 2 and the curve has a rational piece.
    #[must_use]
    pub fn derivative(&self, order: u32) -> CurveSampler {
        assert!(
            order <= 2 || self.rational.iter().all(Option::is_none),
            "rational pieces give derivatives up to the second"
        );
        let segments = self
            .segments
            .iter()
            .map(|s| {
                if s.is_rational() {
                    return s.clone();
                }
                let mut b = s.bezier.clone();
                for _ in 0..order {
                    b = b.deriv();
                }
                let scale = (s.t1 - s.t0).powi(order as i32);
                BezierSegment::polynomial(
                    super::Bezier::new(b.points().iter().map(|p| *p / scale).collect()),
                    s.t0,
                    s.t1,
                )
            })
            .collect();
        CurveSampler {
            segments,
            single_cubic: None,
            rational: self.rational.clone(),
            order: self.order + order,
        }
    }

    /// A rational piece's points (or derivatives, by the sampler's order) at the local
    /// parameters `us` into `out`: its parts `A`, `W` (and their hodographs) by the
    /// polynomial path, then `C = A/W`, `C′ = (A′ − W′C)/W`, `C″ = (A″ − 2W′C′ − W″C)/W`,
    /// divided by `(t1 − t0)ᵏ` for the curve's parameter.
    fn rational_into(
        &self,
        parts: &Homogeneous,
        seg: &BezierSegment,
        us: &[f64],
        out: &mut [DVec3],
    ) {
        let n = us.len();
        if let (0, Some(p)) = (self.order, &parts.planar) {
            planar_rational(p.xy, p.ws, p.cubic, us, out);
            return;
        }
        if self.order == 0 && fused_rational(&parts.a[0], &parts.w[0], us, out) {
            return;
        }
        if self.order == 0 {
            // A into `out`, W beside it, then the division: one scratch run.
            let mut w = [DVec3::ZERO; RATIONAL_RUN];
            bezier_into(&parts.a[0], us, out);
            bezier_into(&parts.w[0], us, &mut w[..n]);
            for (o, w) in out.iter_mut().zip(&w) {
                *o /= w.x;
            }
            return;
        }
        let mut a = [[DVec3::ZERO; RATIONAL_RUN]; 3];
        let mut w = [[DVec3::ZERO; RATIONAL_RUN]; 3];
        let order = (self.order as usize).min(2);
        for k in 0..=order {
            bezier_into(&parts.a[k], us, &mut a[k][..n]);
            bezier_into(&parts.w[k], us, &mut w[k][..n]);
        }
        let h = seg.t1 - seg.t0;
        for (j, o) in out.iter_mut().enumerate() {
            let w0 = w[0][j].x;
            let c = a[0][j] / w0;
            *o = match order {
                0 => c,
                1 => (a[1][j] - w[1][j].x * c) / w0 / h,
                _ => {
                    let d1 = (a[1][j] - w[1][j].x * c) / w0;
                    (a[2][j] - 2.0 * w[1][j].x * d1 - w[2][j].x * c) / w0 / (h * h)
                }
            };
        }
    }

    /// The parameter domain `[t0 of the first segment, t1 of the last]`.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        match (self.segments.first(), self.segments.last()) {
            (Some(a), Some(b)) => (a.t0, b.t1),
            _ => (0.0, 0.0),
        }
    }

    /// The parameters `[lo, hi)` that [`super::locate`] gives segment `j`: from its `t0`
    /// (from −∞ for the first) to the next one's (to +∞ for the last).
    fn run_range(&self, j: usize) -> (f64, f64) {
        let lo = match j {
            0 => f64::NEG_INFINITY,
            _ => self.segments.get(j).map_or(f64::INFINITY, |s| s.t0),
        };
        let hi = self.segments.get(j + 1).map_or(f64::INFINITY, |s| s.t0);
        (lo, hi)
    }

    /// `P(t)` at every `ts[k]` into `out[k]`, each in the segment holding it (parameters
    /// outside the domain extrapolate the first or last segment). Runs of parameters in
    /// one segment are evaluated together.
    ///
    /// # Panics
    /// If `ts` and `out` differ in length.
    pub fn eval_into(&self, ts: &[f64], out: &mut [DVec3]) {
        assert_eq!(ts.len(), out.len(), "one output per parameter");
        let mut k = 0;
        // A buffer of local parameters, so that a run is one call of bezier_into.
        let mut us = [0.0_f64; RUN];
        // The segment of the previous run: sorted parameters are usually in it or the next.
        let mut last: Option<usize> = None;
        while k < ts.len() {
            let t = ts[k];
            let following = last.and_then(|i| {
                [i, i + 1].into_iter().find(|&j| {
                    let (lo, hi) = self.run_range(j);
                    j < self.segments.len() && t >= lo && t < hi
                })
            });
            let index = match following {
                Some(j) => j,
                None => match super::locate(&self.segments, t) {
                    Some((index, _)) => index,
                    None => {
                        out[k..].fill(DVec3::ZERO);
                        return;
                    }
                },
            };
            last = Some(index);
            let seg = &self.segments[index];
            let (lo, hi) = self.run_range(index);
            let in_segment = |t: f64| t >= lo && t < hi;
            // The located parameter always belongs to its run (even a NaN one). The run's
            // end first (comparisons only), then its local parameters in one loop that
            // vectorises.
            let limit = (ts.len() - k).min(us.len());
            let mut len = 1;
            while len < limit && in_segment(ts[k + len]) {
                len += 1;
            }
            let end = k + len;
            let (t0, span) = (seg.t0, seg.t1 - seg.t0);
            for (u, &t) in us[..len].iter_mut().zip(&ts[k..end]) {
                // `seg.local_u(t)`, the same operations.
                *u = (t - t0) / span;
            }
            match &self.rational[index] {
                None => bezier_into(seg.bezier.points(), &us[..end - k], &mut out[k..end]),
                Some(parts) => {
                    // The rational path's scratch holds RATIONAL_RUN parameters.
                    for (u, o) in us[..end - k]
                        .chunks(RATIONAL_RUN)
                        .zip(out[k..end].chunks_mut(RATIONAL_RUN))
                    {
                        self.rational_into(parts, seg, u, o);
                    }
                }
            }
            k = end;
        }
    }

    /// `weights.count()` uniform parameters over the domain (ends included) into `out`,
    /// as [`CurveSampler::sample_uniform_into`] but with the weights computed once for
    /// many curves: a curve of one cubic segment is then one fused four-lane sum per
    /// sample (the same Bernstein sum, within the same bound); any other curve takes the
    /// general path.
    ///
    /// # Panics
    /// If `out.len() != weights.count()`.
    pub fn sample_uniform_with(&self, weights: &UniformCubicWeights, out: &mut [DVec3]) {
        assert_eq!(out.len(), weights.count(), "one output per sample");
        match self.single_cubic {
            Some(p) => cubic_weighted(p, weights, out),
            None => self.sample_uniform_into(out.len(), out),
        }
    }

    /// `count` uniform parameters over the domain (ends included) into `out`.
    ///
    /// # Panics
    /// If `out.len() != count`.
    pub fn sample_uniform_into(&self, count: usize, out: &mut [DVec3]) {
        assert_eq!(out.len(), count, "one output per sample");
        let (a, b) = self.domain();
        let mut ts = [0.0_f64; 64];
        let mut start = 0;
        while start < count {
            let len = (count - start).min(ts.len());
            for (j, t) in ts[..len].iter_mut().enumerate() {
                *t = uniform(a, b, start + j, count);
            }
            self.eval_into(&ts[..len], &mut out[start..start + len]);
            start += len;
        }
    }
}

/// The cubic Bernstein weights `(s³, 3s²u, 3su², u³)` of `count` uniform parameters
/// `u_j = j / (count − 1)` on `[0, 1]`, computed once and shared by every curve sampled
/// at those parameters ([`CurveSampler::sample_uniform_with`]).
#[derive(Debug, Clone, PartialEq)]
pub struct UniformCubicWeights {
    /// Weight `i` of every parameter, one array per `i`.
    w: [Vec<f64>; 4],
}

impl UniformCubicWeights {
    /// The weights of `count` uniform parameters (ends exact).
    #[must_use]
    pub fn new(count: usize) -> UniformCubicWeights {
        let mut w: [Vec<f64>; 4] = Default::default();
        for j in 0..count {
            for (v, x) in w.iter_mut().zip(cubic_weights(uniform(0.0, 1.0, j, count))) {
                v.push(x);
            }
        }
        UniformCubicWeights { w }
    }

    /// How many parameters.
    #[must_use]
    pub fn count(&self) -> usize {
        self.w[0].len()
    }
}

/// `out[j] = Σ w_i[j] P_i`: a single cubic at precomputed weights. Each point is computed
/// as one four-lane sum (x, y, z and a zero lane) of the control points scaled by the
/// sample's weights as fused multiply-adds, which vectorises across coordinates. The
/// function is compiled also for AVX2 + FMA and chosen at run time (`multiversion`); a CPU
/// without FMA gets the same fused operations from software (slower, same results). The
/// fused sum rounds less than the plain one, within the same bound.
#[multiversion::multiversion(targets("x86_64+avx2+fma"))]
fn cubic_weighted(p: [DVec3; 4], weights: &UniformCubicWeights, out: &mut [DVec3]) {
    let lanes = p.map(|q| [q.x, q.y, q.z, 0.0]);
    let [w0, w1, w2, w3] = &weights.w;
    let n = out.len();
    let (w0, w1, w2, w3) = (&w0[..n], &w1[..n], &w2[..n], &w3[..n]);
    for (k, o) in out.iter_mut().enumerate() {
        let (a, b, c, d) = (w0[k], w1[k], w2[k], w3[k]);
        let mut acc = [0.0_f64; 4];
        for (lane, v) in acc.iter_mut().enumerate() {
            *v = a.mul_add(
                lanes[0][lane],
                b.mul_add(
                    lanes[1][lane],
                    c.mul_add(lanes[2][lane], d * lanes[3][lane]),
                ),
            );
        }
        *o = DVec3::new(acc[0], acc[1], acc[2]);
    }
}

/// Parameter `j` of `count` uniform ones over `[a, b]`, ends exact.
#[must_use]
pub fn uniform(a: f64, b: f64, j: usize, count: usize) -> f64 {
    if count < 2 || j == 0 {
        a
    } else if j + 1 == count {
        b
    } else {
        a + (b - a) * j as f64 / (count - 1) as f64
    }
}

/// `count` uniform samples of every curve, curve `c` into `out[c · count ..][..count]`,
/// spread over every core (the cubic weights computed once for all).
///
/// # Panics
/// If `out.len() != curves.len() · count`.
pub fn sample_many(curves: &[CurveSampler], count: usize, out: &mut [DVec3]) {
    assert_eq!(out.len(), curves.len() * count, "count samples per curve");
    if count == 0 {
        return;
    }
    let weights = UniformCubicWeights::new(count);
    out.par_chunks_mut(count)
        .zip(curves.par_iter())
        .for_each(|(o, c)| c.sample_uniform_with(&weights, o));
}

/// `count` uniform samples of every curve, handed to `consume(curve index, samples)`
/// curve by curve, spread over every core: each worker thread fills one reused buffer,
/// so nothing is allocated per curve and the samples need not all fit in memory at once
/// (what a consumer computing bounds, lengths or nearest points needs). The cubic weights
/// are computed once for all.
pub fn for_each_sampled<F>(curves: &[CurveSampler], count: usize, consume: F)
where
    F: Fn(usize, &[DVec3]) + Sync,
{
    let weights = UniformCubicWeights::new(count);
    curves.par_iter().enumerate().for_each_init(
        || vec![DVec3::ZERO; count],
        |buf, (i, c)| {
            c.sample_uniform_with(&weights, buf);
            consume(i, buf);
        },
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lane-parallel path computes the very bits of one de Casteljau run per
    /// parameter (so its accuracy bound is de Casteljau's), planar or not, for parameters
    /// inside and outside `[0, 1]` and run lengths that leave a remainder.
    #[test]
    fn lanes_equal_de_casteljau_bit_for_bit() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for degree in 4..STACK {
            for planar in [true, false] {
                let points: Vec<DVec3> = (0..=degree)
                    .map(|_| DVec3::new(next(), next(), if planar { 0.0 } else { next() }))
                    .collect();
                let us: Vec<f64> = (0..(degree % 7 + 9)).map(|_| 1.5 * next() + 0.5).collect();
                let mut out = vec![DVec3::ZERO; us.len()];
                bezier_into(&points, &us, &mut out);
                for (o, &u) in out.iter().zip(&us) {
                    let want = super::super::bezier::de_casteljau(&points, u);
                    assert_eq!(
                        o.to_array().map(f64::to_bits),
                        want.to_array().map(f64::to_bits),
                        "degree {degree}, planar {planar}, u = {u}"
                    );
                }
            }
        }
    }

    /// Control points near the top of the double range: every point of the curve is a
    /// convex combination of them, so finite, though Bernstein–Horner's partial sums
    /// (weights `C(n, k) u^k` above 1) overflow — the batch gives de Casteljau's values
    /// (the case a solve produced: paper 000's moves of 1.5e308 on a degree-7 curve).
    #[test]
    fn control_points_near_the_largest_double_evaluate_finite() {
        let big = 1.4e308;
        for degree in [4usize, 5, 7, 12, 20] {
            let points: Vec<DVec3> = (0..=degree)
                .map(|i| DVec3::new(if i % 2 == 0 { big } else { -0.5 * big }, big, 0.0))
                .collect();
            let us: Vec<f64> = (0..=64).map(|k| f64::from(k) / 64.0).collect();
            let mut out = vec![DVec3::ZERO; us.len()];
            bezier_into(&points, &us, &mut out);
            for (o, &u) in out.iter().zip(&us) {
                let want = super::super::bezier::de_casteljau(&points, u);
                assert!(want.is_finite(), "de Casteljau at {u}");
                assert_eq!(*o, want, "degree {degree}, u = {u}");
            }
        }
    }
}
