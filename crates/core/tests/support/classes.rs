//! Generators of the hard intersection classes, built in exact rational arithmetic on
//! homogeneous Bernstein coefficients `(w x, w y, w)`, with the constructed answer carried
//! along exactly. A case is kept only when every control point and weight is an `f64`
//! exactly (dyadic), so that the curve the float code reads is the constructed one and a
//! constructed contact stays a contact.
//!
//! The constructions:
//! - a contact of order `k` at parameter `s₀`: `A_h = B_h + (s − s₀)^{k+1} E(s)` with `E`
//!   moving `x`, `y` only (so `A` has `B`'s weights; powers of two keep `A`'s points
//!   dyadic), then each curve reparametrised on its own (restricted to a dyadic interval
//!   for polynomial curves, `wᵢ → wᵢ ρⁱ` for rational ones, reversed);
//! - an end on an interior point: `B(t₀)` made dyadic (a polynomial at dyadic `t₀`, or a
//!   rational curve whose points are multiples of the odd part of `W(t₀)`), then `A`
//!   starting or ending there in any direction, or near `B`'s tangent;
//! - joins: a shared end point, the neighbouring control points on one line for G1;
//! - coincident pieces: restrictions (and reversals, reparametrisations) of one parent,
//!   whose self-crossing is placed at dyadic parameters `σ₁ ≠ σ₂` by solving the linear
//!   condition `Σ wᵢ Pᵢ (Bᵢ(σ₁) W(σ₂) − Bᵢ(σ₂) W(σ₁)) = 0` for one point exactly;
//! - near-parallel near-straight pairs: a cubic close to a long line far from the origin
//!   (as a mesh edge is), and `A_h = B_h + (s − s₀) E` with `E` tiny.

#![allow(dead_code)]

use num_bigint::BigInt;
use num_traits::{One, Signed, ToPrimitive, Zero};
use splinescope_core::rng::Rng;

use super::exact::{Curve, Kind, Q, binomial, q};

/// Homogeneous Bernstein coefficients, exactly.
#[derive(Clone, Debug)]
pub struct H(pub Vec<[Q; 3]>);

fn dy(num: i64, bits: u32) -> Q {
    Q::new(BigInt::from(num), BigInt::one() << bits)
}

fn lerp3(a: &[Q; 3], b: &[Q; 3], t: &Q) -> [Q; 3] {
    let s = Q::one() - t;
    [
        &s * &a[0] + t * &b[0],
        &s * &a[1] + t * &b[1],
        &s * &a[2] + t * &b[2],
    ]
}

impl H {
    pub fn degree(&self) -> usize {
        self.0.len() - 1
    }

    /// From Cartesian points and weights.
    pub fn from_points(points: &[(Q, Q)], weights: &[Q]) -> H {
        H(points
            .iter()
            .zip(weights)
            .map(|((x, y), w)| [x * w, y * w, w.clone()])
            .collect())
    }

    pub fn eval(&self, t: &Q) -> [Q; 3] {
        let mut p = self.0.clone();
        let n = p.len();
        for k in 1..n {
            for i in 0..(n - k) {
                p[i] = lerp3(&p[i], &p[i + 1], t);
            }
        }
        p[0].clone()
    }

    pub fn point(&self, t: &Q) -> (Q, Q) {
        let h = self.eval(t);
        (&h[0] / &h[2], &h[1] / &h[2])
    }

    /// The right part at `t` (on `[t, 1]`).
    fn right(&self, t: &Q) -> H {
        let mut p = self.0.clone();
        let n = p.len();
        for k in 1..n {
            for i in 0..(n - k) {
                p[i] = lerp3(&p[i], &p[i + 1], t);
            }
        }
        // p[i] now holds the point of level n−1−i at index i: the right part's points.
        H(p)
    }

    /// Whether the curve has degree ≥ 2 and all its control points on one line: it then
    /// runs along the line (and may run back over itself), which no class is about.
    pub fn folds(&self) -> bool {
        if self.degree() < 2 {
            return false;
        }
        let pt = |i: usize| (&self.0[i][0] / &self.0[i][2], &self.0[i][1] / &self.0[i][2]);
        let (x0, y0) = pt(0);
        let far = (1..=self.degree()).find(|&i| pt(i) != (x0.clone(), y0.clone()));
        let Some(j) = far else {
            return true;
        };
        let (xj, yj) = pt(j);
        (1..=self.degree()).all(|i| {
            let (x, y) = pt(i);
            ((&xj - &x0) * (&y - &y0) - (&yj - &y0) * (&x - &x0)).is_zero()
        })
    }

    /// Whether the curve ends where it starts (its two ends are one point, which the
    /// float code reports once).
    pub fn closed(&self) -> bool {
        let n = self.degree();
        let pt = |i: usize| (&self.0[i][0] / &self.0[i][2], &self.0[i][1] / &self.0[i][2]);
        pt(0) == pt(n)
    }

    pub fn reversed(&self) -> H {
        H(self.0.iter().rev().cloned().collect())
    }

    /// The curve on `[a, b]`, reparametrised to `[0, 1]` (`b < a` reverses it).
    pub fn restricted(&self, a: &Q, b: &Q) -> H {
        if a > b {
            return self.restricted(b, a).reversed();
        }
        let r = if a.is_zero() {
            self.clone()
        } else {
            self.right(a)
        };
        if *b == Q::one() {
            return r;
        }
        let t = (b - a) / (Q::one() - a);
        // The left part at t is the right part of the reversed curve at 1 − t, reversed.
        r.reversed().right(&(Q::one() - t)).reversed()
    }

    /// `wᵢ → wᵢ ρⁱ`: the same curve, its old parameter `τ` now at `τ / (τ + ρ (1 − τ))`.
    pub fn mobius(&self, rho: &Q) -> H {
        let mut f = Q::one();
        H(self
            .0
            .iter()
            .map(|h| {
                let out = [&h[0] * &f, &h[1] * &f, &h[2] * &f];
                f *= rho;
                out
            })
            .collect())
    }

    pub fn elevated(&self) -> H {
        let n = self.degree();
        let m = q(n as i64 + 1);
        let mut out = vec![self.0[0].clone()];
        for i in 1..=n {
            let a = q(i as i64) / &m;
            out.push(lerp3(&self.0[i], &self.0[i - 1], &a));
        }
        out.push(self.0[n].clone());
        H(out)
    }

    /// `h + (s − s₀)^k E(s)`, `E` of degree `n − k` given by Bernstein `(x, y)` coefficients.
    pub fn plus_contact(&self, s0: &Q, k: usize, e: &[(Q, Q)]) -> H {
        let n = self.degree();
        assert_eq!(e.len(), n - k + 1);
        let lin = [(-s0.clone(), -s0.clone()), (Q::one() - s0, Q::one() - s0)];
        let mut term: Vec<(Q, Q)> = e.to_vec();
        for _ in 0..k {
            term = bernstein_product(&term, &lin);
        }
        H(self
            .0
            .iter()
            .zip(&term)
            .map(|(h, t)| [&h[0] + &t.0, &h[1] + &t.1, h[2].clone()])
            .collect())
    }

    /// The tangent's direction at `t` (not normalised): `A′ W − A W′`.
    pub fn tangent(&self, t: &Q) -> (Q, Q) {
        let n = self.degree();
        let mut p = self.0.clone();
        for k in 1..n {
            for i in 0..(n + 1 - k) {
                p[i] = lerp3(&p[i], &p[i + 1], t);
            }
        }
        let (l, r) = (&p[0], &p[1]);
        let a = lerp3(l, r, t);
        let d: Vec<Q> = (0..3).map(|k| (&r[k] - &l[k]) * q(n as i64)).collect();
        (&d[0] * &a[2] - &a[0] * &d[2], &d[1] * &a[2] - &a[1] * &d[2])
    }

    pub fn exact(&self) -> Curve {
        let h: Vec<(Q, Q, Q)> = self
            .0
            .iter()
            .map(|h| (h[0].clone(), h[1].clone(), h[2].clone()))
            .collect();
        Curve::from_homogeneous(&h)
    }

    /// The control points and weights as `f64`, when every one is exactly an `f64`
    /// (weights scaled alike by a power of two so that the largest is about 1; `None` for
    /// the weights of a polynomial curve).
    pub fn to_float(&self) -> Option<Seg> {
        let wmax = self.0.iter().map(|h| h[2].clone()).max()?;
        // A power of two near the largest weight.
        let e = (wmax.to_f64()?).log2().floor() as i32;
        let scale = if e >= 0 {
            Q::from_integer(BigInt::one() << e as u32)
        } else {
            Q::new(BigInt::one(), BigInt::one() << (-e) as u32)
        };
        let mut points = Vec::new();
        let mut weights = Vec::new();
        for h in &self.0 {
            let x = &h[0] / &h[2];
            let y = &h[1] / &h[2];
            let w = &h[2] / &scale;
            points.push((exact_f64(&x)?, exact_f64(&y)?));
            weights.push(exact_f64(&w)?);
        }
        let polynomial = weights.iter().all(|w| *w == weights[0]);
        Some(Seg {
            points,
            weights: (!polynomial).then_some(weights),
        })
    }
}

/// `x` as an `f64` when it is one exactly.
pub fn exact_f64(x: &Q) -> Option<f64> {
    let f = x.to_f64()?;
    (f.is_finite() && Q::from_float(f)? == *x).then_some(f)
}

/// The product of two Bernstein polynomials (pairs of coordinates alike).
fn bernstein_product(a: &[(Q, Q)], b: &[(Q, Q)]) -> Vec<(Q, Q)> {
    let (m, n) = (a.len() - 1, b.len() - 1);
    let mut out = vec![(Q::zero(), Q::zero()); m + n + 1];
    for (i, ai) in a.iter().enumerate() {
        for (j, bj) in b.iter().enumerate() {
            let c = Q::new(binomial(m, i) * binomial(n, j), binomial(m + n, i + j));
            out[i + j].0 += &c * &ai.0 * &bj.0;
            out[i + j].1 += &c * &ai.1 * &bj.1;
        }
    }
    out
}

/// A curve as the float code reads it.
#[derive(Clone, Debug)]
pub struct Seg {
    pub points: Vec<(f64, f64)>,
    pub weights: Option<Vec<f64>>,
}

/// The classes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    /// An end of one curve on the other's interior, at any angle.
    EndOnInterior,
    /// End to end, with a corner.
    JoinG0,
    /// End to end with a common tangent, curving to the same side (a C) or leaving in the
    /// same direction.
    JoinG1,
    /// End to end with a common tangent, curving away to opposite sides (an S).
    JoinS,
    /// A touching tangency in both interiors, from either side.
    Tangency,
    /// A contact of the second order (common tangent and curvature) in the interiors.
    SecondOrder,
    /// Pieces of one curve, traversed the same way.
    CoincidentSame,
    /// Pieces of one curve, traversed opposite ways.
    CoincidentOpposite,
    /// Pieces of one self-crossing curve, overlapping, with the self-crossing's branches
    /// in the two pieces outside the overlap.
    CoincidentSelfCrossing,
    /// Nearly straight, nearly parallel crossing curves far from the origin.
    NearParallel,
}

impl Class {
    pub const ALL: [Class; 10] = [
        Class::EndOnInterior,
        Class::JoinG0,
        Class::JoinG1,
        Class::JoinS,
        Class::Tangency,
        Class::SecondOrder,
        Class::CoincidentSame,
        Class::CoincidentOpposite,
        Class::CoincidentSelfCrossing,
        Class::NearParallel,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Class::EndOnInterior => "end on interior",
            Class::JoinG0 => "G0 join",
            Class::JoinG1 => "G1 join",
            Class::JoinS => "S join",
            Class::Tangency => "interior tangency",
            Class::SecondOrder => "second-order contact",
            Class::CoincidentSame => "coincident, same direction",
            Class::CoincidentOpposite => "coincident, opposite directions",
            Class::CoincidentSelfCrossing => "coincident on a self-crossing parent",
            Class::NearParallel => "near-parallel near-straight",
        }
    }
}

/// A generated pair and what its construction guarantees.
#[derive(Clone, Debug)]
pub struct Case {
    pub class: Class,
    pub a: H,
    pub b: H,
    /// Points the pair must have: `(s, t, kind)`, exact.
    pub points: Vec<(Q, Q, Kind)>,
    /// Stretches the pair must have: `((s0, s1), (t0, t1))`, `t0` meeting `s0`.
    pub overlaps: Vec<((Q, Q), (Q, Q))>,
    /// Whether the crossing is a near-parallel one (its accuracy is measured).
    pub measure_accuracy: bool,
}

impl Case {
    pub fn degrees(&self) -> (usize, usize) {
        (self.a.degree(), self.b.degree())
    }

    pub fn rational(&self) -> bool {
        self.a.to_float().is_some_and(|s| s.weights.is_some())
            || self.b.to_float().is_some_and(|s| s.weights.is_some())
    }

    /// The pair with the roles of the curves exchanged.
    pub fn swapped(self) -> Case {
        Case {
            class: self.class,
            a: self.b,
            b: self.a,
            points: self.points.into_iter().map(|(s, t, k)| (t, s, k)).collect(),
            overlaps: self
                .overlaps
                .into_iter()
                .map(|(s, t)| {
                    // Orient by the new first curve's parameter.
                    if t.0 <= t.1 {
                        (t, s)
                    } else {
                        ((t.1, t.0), (s.1, s.0))
                    }
                })
                .collect(),
            measure_accuracy: self.measure_accuracy,
        }
    }
}

/// A generator of cases, seeded.
pub struct Gen {
    pub rng: Rng,
    /// The highest degree generated (7 unless lowered).
    pub max_degree: usize,
}

/// How a parameter moves when its curve is reparametrised.
#[derive(Clone, Debug)]
enum Reparam {
    Restrict(Q, Q),
    Mobius(Q),
}

fn apply(r: &Reparam, h: &H) -> H {
    match r {
        Reparam::Restrict(a, b) => h.restricted(a, b),
        Reparam::Mobius(rho) => h.mobius(rho),
    }
}

fn map_param(r: &Reparam, t: &Q) -> Q {
    match r {
        Reparam::Restrict(a, b) => (t - a) / (b - a),
        Reparam::Mobius(rho) => t / (t + rho * (Q::one() - t)),
    }
}

impl Gen {
    pub fn new(seed: u64) -> Gen {
        Gen {
            rng: Rng::new(seed),
            max_degree: 7,
        }
    }

    fn int(&mut self, lo: i64, hi: i64) -> i64 {
        lo + self.rng.int(0, (hi - lo) as usize) as i64
    }

    fn coin(&mut self) -> bool {
        self.rng.unit() < 0.5
    }

    /// A dyadic in `[−r, r]` with up to `bits` fraction bits.
    fn coord(&mut self, r: i64, bits: u32) -> Q {
        let b = self.rng.int(0, bits as usize) as u32;
        dy(self.int(-r << b, r << b), b)
    }

    /// A dyadic in the open `(lo, hi)` ⊂ (0, 1) with `bits` fraction bits.
    fn param(&mut self, lo: f64, hi: f64, bits: u32) -> Q {
        let n = 1i64 << bits;
        let (a, b) = (
            ((lo * n as f64).ceil() as i64).max(1),
            ((hi * n as f64).floor() as i64).min(n - 1),
        );
        dy(self.int(a, b.max(a)), bits)
    }

    /// Weights for a degree-`n` curve: all 1, or powers of two (so that dividing by them
    /// keeps points dyadic).
    fn weights(&mut self, n: usize, rational: bool) -> Vec<Q> {
        (0..=n)
            .map(|_| {
                if rational {
                    let e = self.int(-3, 3);
                    if e >= 0 {
                        q(1 << e)
                    } else {
                        dy(1, (-e) as u32)
                    }
                } else {
                    Q::one()
                }
            })
            .collect()
    }

    fn points(&mut self, n: usize, r: i64, bits: u32) -> Vec<(Q, Q)> {
        (0..=n)
            .map(|_| (self.coord(r, bits), self.coord(r, bits)))
            .collect()
    }

    /// A random curve of degree `n`.
    fn curve(&mut self, n: usize, rational: bool) -> H {
        let w = self.weights(n, rational);
        let p = self.points(n, 8, 3);
        H::from_points(&p, &w)
    }

    fn degree(&mut self, lo: usize, hi: usize) -> usize {
        let hi = hi.min(self.max_degree).max(lo);
        lo + self.rng.int(0, hi - lo)
    }

    /// A reparametrisation keeping the curve exactly representable: a restriction to a
    /// dyadic interval around `keep` for a polynomial curve, `ρ = 2^k` for a rational one.
    fn reparam(&mut self, rational: bool, keep: &[Q]) -> Option<Reparam> {
        if self.coin() {
            return None;
        }
        if rational {
            let e = self.int(-3, 3);
            let rho = if e >= 0 {
                q(1 << e)
            } else {
                dy(1, (-e) as u32)
            };
            return Some(Reparam::Mobius(rho));
        }
        let lo = keep.iter().cloned().min().unwrap_or_else(|| dy(1, 1));
        let hi = keep.iter().cloned().max().unwrap_or_else(|| dy(1, 1));
        let a = if lo.is_positive() && self.coin() {
            let f = lo.to_f64()?;
            self.param(0.0, f, 3).min(lo.clone())
        } else {
            Q::zero()
        };
        let b = if hi < Q::one() && self.coin() {
            let f = hi.to_f64()?;
            self.param(f, 1.0, 3).max(hi.clone())
        } else {
            Q::one()
        };
        if a >= lo && !lo.is_zero() || b <= hi && hi != Q::one() {
            return None;
        }
        Some(Reparam::Restrict(a, b))
    }

    /// One case of `class`, polynomial or rational, degrees in the class's range.
    pub fn case(&mut self, class: Class) -> Case {
        for _ in 0..10_000 {
            let c = match class {
                Class::EndOnInterior => self.end_on_interior(),
                Class::JoinG0 | Class::JoinG1 | Class::JoinS => self.join(class),
                Class::Tangency => self.contact(1),
                Class::SecondOrder => self.contact(2),
                Class::CoincidentSame | Class::CoincidentOpposite => self.coincident(class),
                Class::CoincidentSelfCrossing => self.self_crossing(),
                Class::NearParallel => self.near_parallel(),
            };
            if let Some(c) = c
                && c.a.to_float().is_some()
                && c.b.to_float().is_some()
                && !c.a.folds()
                && !c.b.folds()
                && !c.a.closed()
                && !c.b.closed()
                && (!c.overlaps.is_empty() || !collinear_lines(&c.a, &c.b))
            {
                return if self.coin() { c.swapped() } else { c };
            }
        }
        panic!("no representable case of {class:?} in 10,000 tries");
    }

    fn end_on_interior(&mut self) -> Option<Case> {
        let (m, n) = (self.degree(1, 7), self.degree(1, 7));
        let rational = self.coin();
        let t0 = self.param(0.05, 0.95, 4);
        // B with B(t0) dyadic: for a rational B, its points multiples of W(t0)'s odd part.
        let wb = self.weights(m, rational);
        let mut b = H::from_points(&self.points(m, 8, 3), &wb);
        let w_at = b.eval(&t0)[2].clone();
        let odd = odd_part(&w_at);
        if odd > q(255) {
            return None;
        }
        if !odd.is_one() {
            let pts: Vec<(Q, Q)> = self
                .points(m, 8, 3)
                .into_iter()
                .map(|(x, y)| (x * &odd, y * &odd))
                .collect();
            b = H::from_points(&pts, &wb);
        }
        let x = b.point(&t0);
        let mut a = {
            let r = self.coin();
            self.curve(n, r)
        };
        // The end at X; its neighbour anywhere, or near B's tangent.
        let at_start = self.coin();
        let (end, next) = if at_start { (0, 1) } else { (n, n - 1) };
        let w = a.0[end][2].clone();
        a.0[end] = [&x.0 * &w, &x.1 * &w, w];
        if self.rng.unit() < 0.3 {
            let d = b.tangent(&t0);
            let len = (d.0.to_f64()?.abs() + d.1.to_f64()?.abs()).max(1e-300);
            let k = self.int(1, 20) as u32;
            let sign = if self.coin() { 1.0 } else { -1.0 };
            let (dx, dy_) = (d.0.to_f64()? / len * sign, d.1.to_f64()? / len * sign);
            let tilt = 2f64.powi(-(k as i32));
            let (ux, uy) = (dx - tilt * dy_, dy_ + tilt * dx);
            let nx = Q::from_float(x.0.to_f64()? + ux * 4.0)?;
            let ny = Q::from_float(x.1.to_f64()? + uy * 4.0)?;
            let w = a.0[next][2].clone();
            a.0[next] = [&nx * &w, &ny * &w, w];
        }
        let s = if at_start { Q::zero() } else { Q::one() };
        let kind = kind_of(&a, &s, &b, &t0);
        if kind == Kind::Crossing && !resolvable(&a, &s, &b, &t0) {
            return None;
        }
        Some(Case {
            class: Class::EndOnInterior,
            a,
            b,
            points: vec![(s, t0, kind)],
            overlaps: Vec::new(),
            measure_accuracy: false,
        })
    }

    fn join(&mut self, class: Class) -> Option<Case> {
        let lo = if class == Class::JoinG0 { 1 } else { 2 };
        let (m, n) = (self.degree(lo, 7), self.degree(lo, 7));
        let mut a = {
            let r = self.coin();
            self.curve(n, r)
        };
        let mut b = {
            let r = self.coin();
            self.curve(m, r)
        };
        // Which ends meet: A's end `ea` (0 or n), B's `eb`.
        let (a_end, b_end) = (self.coin(), self.coin());
        let (ea, na) = if a_end { (n, n - 1) } else { (0, 1) };
        let (eb, nb) = if b_end { (m, m - 1) } else { (0, 1) };
        let (jx, jy) = (&b.0[eb][0] / &b.0[eb][2], &b.0[eb][1] / &b.0[eb][2]);
        set_point(&mut a, ea, &jx, &jy);
        if class != Class::JoinG0 {
            // A's neighbouring point on the line through the joint along B's end leg.
            let (bx, by) = (&b.0[nb][0] / &b.0[nb][2], &b.0[nb][1] / &b.0[nb][2]);
            let (dx, dy_) = (&bx - &jx, &by - &jy);
            if dx.is_zero() && dy_.is_zero() {
                return None;
            }
            // Opposite to B's leg (a smooth continuation) or along it (leaving together).
            let lam = dy(self.int(1, 16), 2) * if self.coin() { q(-1) } else { q(1) };
            let (ax, ay) = (&jx + &dx * &lam, &jy + &dy_ * &lam);
            set_point(&mut a, na, &ax, &ay);
            // The sides: the next points of each relative to the common line.
            let side = |h: &H, i: usize| -> Option<i32> {
                let (px, py) = (&h.0[i][0] / &h.0[i][2], &h.0[i][1] / &h.0[i][2]);
                let c = &dx * (&py - &jy) - &dy_ * (&px - &jx);
                Some(if c.is_positive() {
                    1
                } else if c.is_negative() {
                    -1
                } else {
                    0
                })
            };
            // A's and B's second points from the joint, when they exist.
            let a2 = if a_end { n.checked_sub(2)? } else { 2 };
            let b2 = if b_end { m.checked_sub(2)? } else { 2 };
            if a2 > n || b2 > m {
                return None;
            }
            let (sa, sb) = (side(&a, a2)?, side(&b, b2)?);
            if sa == 0 || sb == 0 {
                return None;
            }
            // The S: the curves, leaving the joint in opposite directions (a smooth
            // continuation), bend to opposite sides; or, leaving together, to the same
            // side... the shape class by the union's look: an S has an inflection there.
            let continuation = lam.is_negative();
            let s_shape = if continuation { sa == sb } else { sa != sb };
            if (class == Class::JoinS) != s_shape {
                // Flip A's second point across the line to get the other shape.
                let (px, py) = (&a.0[a2][0] / &a.0[a2][2], &a.0[a2][1] / &a.0[a2][2]);
                // Reflect across the common line through the joint.
                let len2 = &dx * &dx + &dy_ * &dy_;
                let (rx, ry) = (&px - &jx, &py - &jy);
                let along = (&rx * &dx + &ry * &dy_) / &len2;
                let (fx, fy) = (
                    &dx * &along * q(2) - &rx + &jx,
                    &dy_ * &along * q(2) - &ry + &jy,
                );
                set_point(&mut a, a2, &fx, &fy);
            }
        }
        let s = if a_end { Q::one() } else { Q::zero() };
        let t = if b_end { Q::one() } else { Q::zero() };
        let kind = kind_of(&a, &s, &b, &t);
        if (class == Class::JoinG0) != (kind == Kind::Crossing)
            || (kind == Kind::Crossing && !resolvable(&a, &s, &b, &t))
        {
            return None;
        }
        let _ = &mut b;
        Some(Case {
            class,
            a,
            b,
            points: vec![(s, t, kind)],
            overlaps: Vec::new(),
            measure_accuracy: false,
        })
    }

    /// A contact of order `k` (1: tangency, 2: common curvature) in both interiors.
    fn contact(&mut self, order: usize) -> Option<Case> {
        let rational = self.coin();
        let n = self.degree(order + 1, 7);
        let b0 = if rational {
            self.curve(n, true)
        } else {
            // Polynomial points multiples of 315 may be elevated exactly: B of lower degree.
            let m = self.degree(1.max(order), n);
            let mut b = self.curve(m, false);
            for h in &mut b.0 {
                h[0] *= q(315);
                h[1] *= q(315);
            }
            b
        };
        let mut b = b0.clone();
        while b.degree() < n {
            b = b.elevated();
        }
        let s0 = self.param(0.1, 0.9, 3);
        let scale = if rational { 8 } else { 8 * 315 };
        let e: Vec<(Q, Q)> = (0..=(n - order - 1))
            .map(|_| (self.coord(scale, 2), self.coord(scale, 2)))
            .collect();
        // E = 0 would make A the very curve B (a coincidence, not a contact).
        if e.iter().all(|(x, y)| x.is_zero() && y.is_zero()) {
            return None;
        }
        let a = b.plus_contact(&s0, order + 1, &e);
        // A line tangent to a curve: A of degree 1 through the point along the tangent.
        let (mut a, mut sa) = (a, s0.clone());
        if order == 1 && b0.degree() >= 2 && self.rng.unit() < 0.2 {
            let x = b0.point(&s0);
            let d = b0.tangent(&s0);
            let (l1, l2) = (dy(self.int(1, 16), 2), dy(self.int(1, 16), 2));
            // Points X − l1 d and X + l2 d, d scaled to integers.
            let den = lcm(d.0.denom(), d.1.denom());
            let (dx, dy_) = (
                &d.0 * Q::from_integer(den.clone()),
                &d.1 * Q::from_integer(den),
            );
            let g = gcd_int(dx.numer(), dy_.numer());
            if g.is_zero() {
                return None;
            }
            let (dx, dy_) = (dx / Q::from_integer(g.clone()), dy_ / Q::from_integer(g));
            a = H::from_points(
                &[
                    (&x.0 - &dx * &l1, &x.1 - &dy_ * &l1),
                    (&x.0 + &dx * &l2, &x.1 + &dy_ * &l2),
                ],
                &[Q::one(), Q::one()],
            );
            sa = &l1 / (&l1 + &l2);
        }
        let mut b = b0;
        let mut tb = s0;
        if let Some(r) = self.reparam(rational, &[sa.clone()]) {
            a = apply(&r, &a);
            sa = map_param(&r, &sa);
        }
        if let Some(r) = self.reparam(rational, &[tb.clone()]) {
            b = apply(&r, &b);
            tb = map_param(&r, &tb);
        }
        if self.coin() {
            a = a.reversed();
            sa = Q::one() - sa;
        }
        if (sa.is_zero() || sa == Q::one()) || (tb.is_zero() || tb == Q::one()) {
            return None;
        }
        // The contact is of order `order` exactly when the next term moves off the tangent
        // (else it is higher: keep it, its kind is the same).
        if kind_of(&a, &sa, &b, &tb) != Kind::Tangent {
            return None;
        }
        Some(Case {
            class: if order == 1 {
                Class::Tangency
            } else {
                Class::SecondOrder
            },
            a,
            b,
            points: vec![(sa, tb, Kind::Tangent)],
            overlaps: Vec::new(),
            measure_accuracy: false,
        })
    }

    /// Two pieces of one parent `p` on `[a0, a1]` and `[b0, b1]` (`b` reversed when
    /// `opposite`), as a case with its stretch, if they overlap.
    fn pieces(
        &mut self,
        class: Class,
        p: &H,
        (a0, a1): (Q, Q),
        (b0, b1): (Q, Q),
        opposite: bool,
    ) -> Option<Case> {
        let lo = (&a0).max(&b0).clone();
        let hi = (&a1).min(&b1).clone();
        if lo >= hi {
            return None;
        }
        let a = p.restricted(&a0, &a1);
        let (b, tb) = if opposite {
            (
                p.restricted(&b1, &b0),
                ((&b1 - &lo) / (&b1 - &b0), (&b1 - &hi) / (&b1 - &b0)),
            )
        } else {
            (
                p.restricted(&b0, &b1),
                ((&lo - &b0) / (&b1 - &b0), (&hi - &b0) / (&b1 - &b0)),
            )
        };
        let sa = ((&lo - &a0) / (&a1 - &a0), (&hi - &a0) / (&a1 - &a0));
        Some(Case {
            class,
            a,
            b,
            points: Vec::new(),
            overlaps: vec![(sa, tb)],
            measure_accuracy: false,
        })
    }

    fn coincident(&mut self, class: Class) -> Option<Case> {
        let opposite = class == Class::CoincidentOpposite;
        let rational = self.rng.unit() < 0.3;
        let n = self.degree(1, 7);
        let p = self.curve(n, rational);
        if rational {
            // Whole coincidence with two speeds: ρ reparametrisations (restrictions of a
            // rational curve are seldom exactly representable).
            let (ra, rb) = (self.int(-3, 3), self.int(-3, 3));
            let pw = |e: i64| {
                if e >= 0 {
                    q(1 << e)
                } else {
                    dy(1, (-e) as u32)
                }
            };
            let a = p.mobius(&pw(ra));
            let mut b = p.mobius(&pw(rb));
            let mut t = (Q::zero(), Q::one());
            if opposite {
                b = b.reversed();
                t = (Q::one(), Q::zero());
            }
            return Some(Case {
                class,
                a,
                b,
                points: Vec::new(),
                overlaps: vec![((Q::zero(), Q::one()), t)],
                measure_accuracy: false,
            });
        }
        let mut cuts: Vec<Q> = (0..4).map(|_| self.param(0.0, 1.0, 3)).collect();
        cuts.push(Q::zero());
        cuts.push(Q::one());
        let pick = |g: &mut Gen| cuts[g.rng.int(0, cuts.len() - 1)].clone();
        let (x0, x1, y0, y1) = (pick(self), pick(self), pick(self), pick(self));
        let ((a0, a1), (b0, b1)) = (
            (x0.clone().min(x1.clone()), x0.max(x1)),
            (y0.clone().min(y1.clone()), y0.max(y1)),
        );
        if a0 == a1 || b0 == b1 {
            return None;
        }
        self.pieces(class, &p, (a0, a1), (b0, b1), opposite)
    }

    /// A polynomial parent of degree ≥ 3 (or a rational one of degree ≥ 3) crossing itself
    /// at dyadic `σ₁ < σ₂`; pieces overlapping between them, each holding one of the
    /// crossing's branches outside the overlap.
    fn self_crossing(&mut self) -> Option<Case> {
        let n = self.degree(3, 7);
        let rational = self.rng.unit() < 0.3;
        let w = self.weights(n, rational);
        let s1 = self.param(0.05, 0.45, 3);
        let s2 = self.param(0.55, 0.95, 3);
        let wh = H::from_points(&vec![(Q::zero(), Q::zero()); n + 1], &w);
        let (w1, w2) = (wh.eval(&s1)[2].clone(), wh.eval(&s2)[2].clone());
        let basis = |i: usize, t: &Q| -> Q {
            Q::from_integer(binomial(n, i))
                * num_traits::pow(t.clone(), i)
                * num_traits::pow(Q::one() - t, n - i)
        };
        let c: Vec<Q> = (0..=n)
            .map(|i| &w[i] * (basis(i, &s1) * &w2 - basis(i, &s2) * &w1))
            .collect();
        let j = (0..=n).rev().find(|&i| !c[i].is_zero())?;
        let odd = odd_part(&c[j]);
        let mut pts = self.points(n, 8, 2);
        for (i, p) in pts.iter_mut().enumerate() {
            if i != j {
                p.0 *= &odd;
                p.1 *= &odd;
            }
        }
        let (mut sx, mut sy) = (Q::zero(), Q::zero());
        for i in 0..=n {
            if i != j {
                sx += &c[i] * &pts[i].0;
                sy += &c[i] * &pts[i].1;
            }
        }
        pts[j] = (-sx / &c[j], -sy / &c[j]);
        let p = H::from_points(&pts, &w);
        // A genuine crossing, not a cusp or a fold: the tangents there differ.
        let (d1, d2) = (p.tangent(&s1), p.tangent(&s2));
        if (&d1.0 * &d2.1 - &d1.1 * &d2.0).is_zero() {
            return None;
        }
        let opposite = self.coin();
        if rational {
            let pw = |e: i64| {
                if e >= 0 {
                    q(1 << e)
                } else {
                    dy(1, (-e) as u32)
                }
            };
            let (ra, rb) = (self.int(-3, 3), self.int(-3, 3));
            let a = p.mobius(&pw(ra));
            let mut b = p.mobius(&pw(rb));
            let mut t = (Q::zero(), Q::one());
            if opposite {
                b = b.reversed();
                t = (Q::one(), Q::zero());
            }
            return Some(Case {
                class: Class::CoincidentSelfCrossing,
                a,
                b,
                points: Vec::new(),
                overlaps: vec![((Q::zero(), Q::one()), t)],
                measure_accuracy: false,
            });
        }
        // A holds σ₁ outside the overlap, B holds σ₂ outside it: A = [a0, m1], B = [m0, b1]
        // with a0 < σ₁ < m0 < m1 < σ₂ < b1.
        let m0 = self.param(s1.to_f64()? + 0.01, s2.to_f64()? - 0.02, 4);
        let m1 = self.param(m0.to_f64()? + 0.01, s2.to_f64()? - 0.01, 4);
        if !(s1 < m0 && m0 < m1 && m1 < s2) {
            return None;
        }
        let a0 = if self.coin() {
            Q::zero()
        } else {
            self.param(0.0, s1.to_f64()? - 0.01, 4)
        };
        let b1 = if self.coin() {
            Q::one()
        } else {
            self.param(s2.to_f64()? + 0.01, 1.0, 4)
        };
        if a0 >= s1 || b1 <= s2 {
            return None;
        }
        let mut case = self.pieces(
            Class::CoincidentSelfCrossing,
            &p,
            (a0.clone(), m1.clone()),
            (m0.clone(), b1.clone()),
            opposite,
        )?;
        let sa = (&s1 - &a0) / (&m1 - &a0);
        let tb = if opposite {
            (&b1 - &s2) / (&b1 - &m0)
        } else {
            (&s2 - &m0) / (&b1 - &m0)
        };
        if !resolvable(&case.a, &sa, &case.b, &tb) {
            return None;
        }
        case.points.push((sa, tb, Kind::Crossing));
        Some(case)
    }

    fn near_parallel(&mut self) -> Option<Case> {
        let rational = self.rng.unit() < 0.25;
        let n = self.degree(1, 7);
        // A long line far from the origin (a mesh edge), its interior points bent a little.
        let (ox, oy) = (q(self.int(-1000, 1000)), q(self.int(-1000, 1000)));
        let (dx, dy_) = (self.coord(64, 4), self.coord(64, 4));
        if dx.is_zero() && dy_.is_zero() {
            return None;
        }
        let bend = self.int(6, 30) as u32;
        let mut pts = Vec::new();
        for i in 0..=n {
            let f = q(i as i64) / q(n as i64);
            let jx = dy(self.int(-64, 64), 6 + bend);
            let jy = dy(self.int(-64, 64), 6 + bend);
            pts.push((&ox + &dx * &f + jx, &oy + &dy_ * &f + jy));
        }
        let w = self.weights(n, rational);
        let b = H::from_points(&pts, &w);
        let s0 = self.param(0.05, 0.95, 4);
        // E tiny: the angle between them about |E| / |d|.
        let tilt = self.int(4, 26) as u32;
        let e: Vec<(Q, Q)> = (0..n)
            .map(|_| {
                (
                    dy(self.int(-64, 64), 6 + tilt),
                    dy(self.int(-64, 64), 6 + tilt),
                )
            })
            .collect();
        if n == 0 {
            return None;
        }
        let mut a = b.plus_contact(&s0, 1, &e);
        let (mut sa, mut b, mut tb) = (s0.clone(), b, s0);
        if let Some(r) = self.reparam(rational, &[sa.clone()]) {
            a = apply(&r, &a);
            sa = map_param(&r, &sa);
        }
        if let Some(r) = self.reparam(rational, &[tb.clone()]) {
            b = apply(&r, &b);
            tb = map_param(&r, &tb);
        }
        if kind_of(&a, &sa, &b, &tb) != Kind::Crossing || !resolvable(&a, &sa, &b, &tb) {
            return None;
        }
        Some(Case {
            class: Class::NearParallel,
            a,
            b,
            points: vec![(sa, tb, Kind::Crossing)],
            overlaps: Vec::new(),
            measure_accuracy: true,
        })
    }
}

/// Whether a crossing at `(s, t)` can be told from a tangency in `f64`: its angle `θ`
/// satisfies `θ² > 64 δ |Δκ|` (the resolution `δ` as the float code takes it, `Δκ` the
/// curvatures' difference) — below that, the curves come within `δ` of a tangency nearby
/// and no floating-point method can tell the two apart — and `θ` times the pair's size
/// exceeds `1000 δ` (else the curves stay within `δ` of each other all along, and are as
/// good as coincident).
pub fn resolvable(a: &H, s: &Q, b: &H, t: &Q) -> bool {
    let (Some(fa), Some(fb)) = (a.to_float(), b.to_float()) else {
        return false;
    };
    let pts = fa.points.iter().chain(&fb.points);
    let (mut lo, mut hi) = (
        (f64::INFINITY, f64::INFINITY),
        (f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for &(x, y) in pts {
        lo = (lo.0.min(x), lo.1.min(y));
        hi = (hi.0.max(x), hi.1.max(y));
    }
    let size = (hi.0 - lo.0).hypot(hi.1 - lo.1);
    let magnitude = lo.0.abs().max(lo.1.abs()).max(hi.0.abs()).max(hi.1.abs());
    let tol = 64.0 * f64::EPSILON * size.max(magnitude);
    let (da, dda) = a.exact().derivatives(s);
    let (db, ddb) = b.exact().derivatives(t);
    let cross = |p: (f64, f64), q: (f64, f64)| p.0 * q.1 - p.1 * q.0;
    let len = |p: (f64, f64)| p.0.hypot(p.1);
    let sin = cross(da, db).abs() / (len(da) * len(db));
    let ka = cross(da, dda) / len(da).powi(3);
    let kb = cross(db, ddb) / len(db).powi(3);
    let dk = if da.0 * db.0 + da.1 * db.1 >= 0.0 {
        ka - kb
    } else {
        ka + kb
    };
    sin * sin > 64.0 * tol * dk.abs() && sin * size > 1e3 * tol
}

fn set_point(h: &mut H, i: usize, x: &Q, y: &Q) {
    let w = h.0[i][2].clone();
    h.0[i] = [x * &w, y * &w, w];
}

/// Crossing or tangent by the exact cross product of the tangents at the point.
pub fn kind_of(a: &H, s: &Q, b: &H, t: &Q) -> Kind {
    let (da, db) = (a.tangent(s), b.tangent(t));
    if (&da.0 * &db.1 - &da.1 * &db.0).is_zero() {
        Kind::Tangent
    } else {
        Kind::Crossing
    }
}

/// The odd part of a rational's numerator (its factor that is not a power of two; the
/// denominators here are powers of two).
fn odd_part(x: &Q) -> Q {
    let mut n = x.numer().abs();
    let two = BigInt::from(2);
    while !n.is_zero() && (&n % &two).is_zero() {
        n /= &two;
    }
    let mut d = x.denom().clone();
    while (&d % &two).is_zero() {
        d /= &two;
    }
    Q::from_integer(n * d)
}

fn gcd_int(a: &BigInt, b: &BigInt) -> BigInt {
    let (mut a, mut b) = (a.abs(), b.abs());
    while !b.is_zero() {
        let r = &a % &b;
        a = b;
        b = r;
    }
    a
}

fn lcm(a: &BigInt, b: &BigInt) -> BigInt {
    let g = gcd_int(a, b);
    if g.is_zero() {
        return BigInt::one();
    }
    a * b / g
}

/// Two segments of one line (degree 1, all four points on it, exactly): they coincide
/// where they overlap, so no class of isolated points can be built from them.
fn collinear_lines(a: &H, b: &H) -> bool {
    if a.degree() != 1 || b.degree() != 1 {
        return false;
    }
    let (p, q) = (b.point(&Q::zero()), b.point(&Q::one()));
    let cross = |r: &(Q, Q)| (&q.0 - &p.0) * (&r.1 - &p.1) - (&q.1 - &p.1) * (&r.0 - &p.0);
    cross(&a.point(&Q::zero())).is_zero() && cross(&a.point(&Q::one())).is_zero()
}
