//! One lowered Bézier segment as the analyses see it: per coordinate, the Bernstein
//! coefficients of the homogeneous numerator `A_k(u) = Σ w_i P_{i,k} B_i(u)` and, for a
//! rational segment, of the weight `W(u) = Σ w_i B_i(u)`; the curve there is `A / W`
//! (`W ≡ 1` for a polynomial segment). The polynomials every analysis needs are built
//! from these by [`crate::poly`]: the quotient rule's numerators, `C′ × C″`, `|C′|²`.

use glam::{DVec2, DVec3};

use super::gauss::PlanarSpeed;
use crate::geom::BezierSegment;
use crate::poly;

/// A segment in homogeneous Bernstein form, with the curve parameters it covers.
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    /// The curve parameter at `u = 0`.
    pub t0: f64,
    /// The curve parameter at `u = 1`.
    pub t1: f64,
    /// Every coefficient in one allocation (a piece is read far more than it is made, and
    /// copied whole where many are read in turn): `A_x`, `A_y`, `A_z` (`n` each), `A′` per
    /// coordinate (`m` each), then for a rational segment `W` (`n`) and `W′` (`m`).
    coef: Box<[f64]>,
    /// The number of control points.
    n: usize,
    /// The number of coefficients of a derivative.
    m: usize,
    /// Whether the segment is rational (has `W`).
    rational: bool,
    /// The box of the control points in `x`, `y` (the segment lies in it).
    bounds: (DVec2, DVec2),
    /// Whether `z ≡ 0`.
    planar: bool,
    /// For a polynomial segment of degree ≤ 7: `A′` per coordinate in the power basis
    /// (ascending), for the arc length's many evaluations of `|C′|` by Horner's rule.
    power: Option<Box<[Power; 3]>>,
    /// The length of the control polygon (at least the segment's).
    polygon: f64,
    /// For a planar polynomial segment of degree ≤ 7: its speed as `|ℓ| Π |u − r_j|`,
    /// which bounds the Gauss rules' error in advance ([`super::gauss`]).
    planar_speed: Option<Box<PlanarSpeed>>,
}

/// The most coefficients a hodograph kept in the power basis has (segments of degree ≤ 7).
const POWER_MAX: usize = 7;

/// A hodograph coordinate in the power basis (ascending), inline.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Power {
    c: [f64; POWER_MAX],
    len: usize,
}

impl Power {
    fn as_slice(&self) -> &[f64] {
        &self.c[..self.len]
    }
}

/// The power-basis coefficients (ascending) of `Σ c_i B_{i,m}` (`c.len() ≤ POWER_MAX`):
/// `a_k = C(m, k) Δᵏ c_0`.
#[inline(always)]
fn power_basis(c: &[f64]) -> Power {
    let len = c.len().min(POWER_MAX);
    let mut diff = [0.0; POWER_MAX];
    diff[..len].copy_from_slice(&c[..len]);
    let mut out = Power {
        c: [0.0; POWER_MAX],
        len,
    };
    let row = &BINOMIALS[len.saturating_sub(1)];
    // `while` loops, which unroll where `len` is a constant ([`planar_speed_of`]).
    let mut k = 0;
    while k < len {
        out.c[k] = row[k] * diff[0];
        let mut i = 0;
        while i + 1 + k < len {
            diff[i] = diff[i + 1] - diff[i];
            i += 1;
        }
        k += 1;
    }
    out
}

/// `C(m, k)` for `m < POWER_MAX`, exact.
const BINOMIALS: [[f64; POWER_MAX]; POWER_MAX] = {
    let mut rows = [[0.0; POWER_MAX]; POWER_MAX];
    let mut m = 0;
    while m < POWER_MAX {
        rows[m][0] = 1.0;
        let mut k = 1;
        while k <= m {
            rows[m][k] = rows[m - 1][k - 1] + if k < m { rows[m - 1][k] } else { 0.0 };
            k += 1;
        }
        m += 1;
    }
    rows
};

/// The speed [`Piece::new`] keeps for a planar polynomial segment with control points
/// `pts` (degree ≤ 7), with its control polygon's length — computed the same way, to the
/// bit, but without the piece's other arrays; `None` where the piece would have none.
#[must_use]
#[inline]
pub fn planar_polynomial_speed(pts: &[DVec3]) -> Option<(PlanarSpeed, f64)> {
    if pts.iter().any(|p| p.z != 0.0) {
        return None;
    }
    // The number of points a constant, so that the loops below unroll.
    match pts.len() {
        1 => planar_speed_of::<1>(pts),
        2 => planar_speed_of::<2>(pts),
        3 => planar_speed_of::<3>(pts),
        4 => planar_speed_of::<4>(pts),
        5 => planar_speed_of::<5>(pts),
        6 => planar_speed_of::<6>(pts),
        7 => planar_speed_of::<7>(pts),
        8 => planar_speed_of::<8>(pts),
        _ => None,
    }
}

/// [`planar_polynomial_speed`] of `P = pts.len()` points (`1 ≤ P ≤ POWER_MAX + 1`).
#[inline(always)]
fn planar_speed_of<const P: usize>(pts: &[DVec3]) -> Option<(PlanarSpeed, f64)> {
    // `poly::derivative` of each coordinate, in place.
    let n = P - 1;
    let mut dx = [0.0; POWER_MAX];
    let mut dy = [0.0; POWER_MAX];
    let len = n.max(1);
    let scale = n as f64;
    for i in 0..n {
        dx[i] = scale * (pts[i + 1].x - pts[i].x);
        dy[i] = scale * (pts[i + 1].y - pts[i].y);
    }
    let (x, y) = (power_basis(&dx[..len]), power_basis(&dy[..len]));
    let speed = PlanarSpeed::new(x.as_slice(), y.as_slice())?;
    Some((speed, polygon_length(&pts[..P])))
}

/// The length of the control polygon through `pts`.
fn polygon_length(pts: &[DVec3]) -> f64 {
    pts.windows(2).map(|w| (w[1] - w[0]).length()).sum()
}

fn horner(a: &[f64], u: f64) -> f64 {
    a.iter().rev().fold(0.0, |acc, c| acc * u + c)
}

impl Piece {
    /// The segment's piece.
    #[must_use]
    pub fn new(seg: &BezierSegment) -> Piece {
        let weight = |i: usize| seg.weights.as_ref().map_or(1.0, |w| w[i]);
        let pts = seg.points();
        let axis = |k: usize| -> Vec<f64> {
            pts.iter()
                .enumerate()
                .map(|(i, p)| p[k] * weight(i))
                .collect()
        };
        let a = [axis(0), axis(1), axis(2)];
        let da = [
            poly::derivative(&a[0]),
            poly::derivative(&a[1]),
            poly::derivative(&a[2]),
        ];
        let w = seg.weights.clone();
        let dw = w.as_deref().map(poly::derivative);
        let bounds = pts
            .iter()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.truncate()), hi.max(p.truncate()))
            });
        let planar = a[2].iter().all(|v| *v == 0.0);
        let power = (w.is_none() && pts.len() <= POWER_MAX + 1).then(|| {
            [
                power_basis(&da[0]),
                power_basis(&da[1]),
                power_basis(&da[2]),
            ]
        });
        let polygon = polygon_length(pts);
        let planar_speed = match &power {
            Some([x, y, _]) if planar => PlanarSpeed::new(x.as_slice(), y.as_slice()).map(Box::new),
            _ => None,
        };
        let power = power.map(Box::new);
        let (n, m) = (a[0].len(), da[0].len());
        let mut coef: Vec<f64> = Vec::with_capacity(3 * n + 3 * m + 2 * (n + m));
        for c in a.iter().chain(&da) {
            coef.extend_from_slice(c);
        }
        if let (Some(w), Some(dw)) = (&w, &dw) {
            coef.extend_from_slice(w);
            coef.extend_from_slice(dw);
        }
        Piece {
            planar_speed,
            polygon,
            t0: seg.t0,
            t1: seg.t1,
            coef: coef.into_boxed_slice(),
            n,
            m,
            rational: w.is_some(),
            bounds,
            planar,
            power,
        }
    }

    /// The largest absolute coordinate of a control point.
    #[must_use]
    pub fn magnitude(&self) -> f64 {
        let (lo, hi) = self.bounds;
        lo.abs().max(hi.abs()).max_element()
    }

    /// The piece without what only its arc length uses (the power-basis speed): a light
    /// copy, for many pieces laid out anew in the order they will be read.
    #[must_use]
    pub fn geometry(&self) -> Piece {
        Piece {
            t0: self.t0,
            t1: self.t1,
            coef: self.coef.clone(),
            n: self.n,
            m: self.m,
            rational: self.rational,
            bounds: self.bounds,
            planar: self.planar,
            power: None,
            polygon: self.polygon,
            planar_speed: None,
        }
    }

    /// `A_k`'s Bernstein coefficients (`k` = 0, 1, 2 for `x`, `y`, `z`).
    #[must_use]
    #[inline]
    pub fn a(&self, k: usize) -> &[f64] {
        &self.coef[k * self.n..(k + 1) * self.n]
    }

    /// `W`'s Bernstein coefficients, `None` for a polynomial segment.
    #[must_use]
    #[inline]
    pub fn w(&self) -> Option<&[f64]> {
        let start = 3 * (self.n + self.m);
        self.rational.then(|| &self.coef[start..start + self.n])
    }

    /// `A_k′`.
    #[inline]
    fn da(&self, k: usize) -> &[f64] {
        let start = 3 * self.n + k * self.m;
        &self.coef[start..start + self.m]
    }

    /// `W′`.
    #[inline]
    fn dw(&self) -> Option<&[f64]> {
        let start = 3 * (self.n + self.m) + self.n;
        self.rational.then(|| &self.coef[start..start + self.m])
    }

    /// `A` per coordinate.
    fn aa(&self) -> [&[f64]; 3] {
        [self.a(0), self.a(1), self.a(2)]
    }

    /// `A′` per coordinate.
    fn daa(&self) -> [&[f64]; 3] {
        [self.da(0), self.da(1), self.da(2)]
    }

    /// `|dC/du|`: Horner's rule on the power-basis hodograph for a polynomial segment of
    /// degree ≤ 7, [`Piece::deriv`] otherwise.
    #[must_use]
    pub fn speed(&self, u: f64) -> f64 {
        match self.power.as_deref() {
            Some([x, y, z]) => {
                let (dx, dy) = (horner(x.as_slice(), u), horner(y.as_slice(), u));
                let dz = if self.planar {
                    0.0
                } else {
                    horner(z.as_slice(), u)
                };
                let s = (dx * dx + dy * dy + dz * dz).sqrt();
                if s.is_finite() {
                    s
                } else {
                    dx.hypot(dy).hypot(dz)
                }
            }
            None => self.deriv(u).length(),
        }
    }

    /// `|dC/dσ|` in the logistic parameter `σ` (`u = 1 / (1 + e^{−σ})`), in which a
    /// rational segment with weights far apart changes on a scale of 1 wherever its
    /// weights' terms trade dominance. Evaluated without `u`: the curve is the blend
    /// `C = Σ ωᵢ Pᵢ` with `ωᵢ ∝ e^{ln wᵢ + ln C(n, i) + iσ}` (computed from the largest
    /// exponent down, so any `σ` is representable — a transition at `1 − u ≈ 10⁻⁶⁰⁰`
    /// sits at `σ ≈ 1380`), and `dC/dσ = Σ ωᵢ (i − ī)(Pᵢ − P_k)` (`ī` the mean index,
    /// `P_k` the heaviest point). For a polynomial segment the weights are 1.
    #[must_use]
    pub fn speed_logistic(&self, sigma: f64) -> f64 {
        let n = self.n - 1;
        let mut exps = [0.0_f64; 64];
        let mut buf;
        let exps: &mut [f64] = if self.n <= 64 {
            &mut exps[..self.n]
        } else {
            buf = vec![0.0; self.n];
            &mut buf
        };
        let ln_w = |i: usize| self.w().map_or(0.0, |w| w[i].ln());
        let mut top = f64::NEG_INFINITY;
        let mut heavy = 0;
        for (i, e) in exps.iter_mut().enumerate() {
            *e = ln_w(i) + crate::geom::bernstein::binomial(n, i).ln() + i as f64 * sigma;
            if *e > top {
                top = *e;
                heavy = i;
            }
        }
        let point = |i: usize| {
            let w = self.w().map_or(1.0, |w| w[i]);
            DVec3::new(self.a(0)[i], self.a(1)[i], self.a(2)[i]) / w
        };
        let mut total = 0.0;
        let mut mean = 0.0;
        for (i, e) in exps.iter_mut().enumerate() {
            *e = (*e - top).exp();
            total += *e;
            mean += *e * i as f64;
        }
        mean /= total;
        let pk = point(heavy);
        let mut d = DVec3::ZERO;
        for (i, e) in exps.iter().enumerate() {
            if *e > 0.0 && i != heavy {
                d += (*e / total) * (i as f64 - mean) * (point(i) - pk);
            }
        }
        let m = d.abs().max_element();
        if m > 0.0 && m.is_finite() {
            m * (d / m).length()
        } else {
            m
        }
    }

    /// Whether the weights lie so far apart (more than `2⁴⁰`) that the segment's
    /// polynomials in `u` lose its features to rounding: then its roots are found in the
    /// logistic parameter ([`Piece::logistic_roots`]).
    #[must_use]
    pub fn weights_far_apart(&self) -> bool {
        self.weight_spread() > 2f64.powi(40)
    }

    /// The blend `ωᵢ(σ)` (`Σ ωᵢ = 1`, `C = Σ ωᵢ Pᵢ`) at the logistic parameter `σ`, from
    /// the largest exponent `ln wᵢ + ln C(n, i) + iσ` down; and the mean index `Σ i ωᵢ`.
    fn blend(&self, sigma: f64, out: &mut [f64]) -> f64 {
        let n = self.n - 1;
        let mut top = f64::NEG_INFINITY;
        for (i, e) in out.iter_mut().enumerate() {
            let ln_w = self.w().map_or(0.0, |w| w[i].ln());
            *e = ln_w + crate::geom::bernstein::binomial(n, i).ln() + i as f64 * sigma;
            top = top.max(*e);
        }
        let mut total = 0.0;
        for e in out.iter_mut() {
            *e = (*e - top).exp();
            total += *e;
        }
        let mut mean = 0.0;
        for (i, e) in out.iter_mut().enumerate() {
            *e /= total;
            mean += *e * i as f64;
        }
        mean
    }

    /// The control point `Pᵢ`.
    fn control_point(&self, i: usize) -> DVec3 {
        let w = self.w().map_or(1.0, |w| w[i]);
        DVec3::new(self.a(0)[i], self.a(1)[i], self.a(2)[i]) / w
    }

    /// `C` at the logistic parameter `σ` (any `σ`, also where `u` is not a double).
    #[must_use]
    pub fn point_logistic(&self, sigma: f64) -> DVec3 {
        let mut om = vec![0.0; self.n];
        self.blend(sigma, &mut om);
        om.iter()
            .enumerate()
            .map(|(i, w)| *w * self.control_point(i))
            .sum()
    }

    /// The logistic range that holds a segment's every feature: its outermost weight
    /// transitions, `±40` beyond.
    #[must_use]
    pub fn logistic_span(&self) -> (f64, f64) {
        let t = self.weight_transitions();
        let lo = t.iter().copied().fold(0.0_f64, f64::min);
        let hi = t.iter().copied().fold(0.0_f64, f64::max);
        (lo - 40.0, hi + 40.0)
    }

    /// Where `F(σ) = Σ ωᵢ(σ) fᵢ` is largest and smallest across [`Piece::logistic_span`]
    /// (sampled every `1/16`, then golden-section search around the best sample): the
    /// extremes of a coordinate where it levels off within rounding (a stretch parked at
    /// one control point), which no sign change of `F′` shows. `(σ_min, σ_max)`.
    #[must_use]
    pub fn logistic_extremes(&self, f: &[f64]) -> (f64, f64) {
        let mut om = vec![0.0; self.n];
        let mut value = |sigma: f64| -> f64 {
            self.blend(sigma, &mut om);
            om.iter().zip(f).map(|(w, x)| w * x).sum()
        };
        let (lo, hi) = self.logistic_span();
        let steps = ((hi - lo) * 16.0).ceil().max(1.0) as usize;
        let h = (hi - lo) / steps as f64;
        let (mut best_lo, mut best_hi) = ((lo, f64::INFINITY), (lo, f64::NEG_INFINITY));
        for k in 0..=steps {
            let x = lo + h * k as f64;
            let v = value(x);
            if v < best_lo.1 {
                best_lo = (x, v);
            }
            if v > best_hi.1 {
                best_hi = (x, v);
            }
        }
        let mut golden = |centre: f64, sign: f64| -> f64 {
            let (mut a, mut b) = (centre - h, centre + h);
            let r = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..60 {
                let (c, d) = (b - r * (b - a), a + r * (b - a));
                if sign * value(c) > sign * value(d) {
                    b = d;
                } else {
                    a = c;
                }
            }
            0.5 * (a + b)
        };
        (golden(best_lo.0, -1.0), golden(best_hi.0, 1.0))
    }

    /// The roots in the logistic parameter of `F(σ) = Σ ωᵢ(σ) fᵢ` (or, with `slope`, of
    /// `F′(σ) = Σ ωᵢ (i − ī)(fᵢ − f_k)`), `fᵢ` given per control point: `F` sampled every
    /// `1/16` across [`Piece::logistic_span`] (it changes on a scale of 1 there, however
    /// far apart the weights), each sign change closed by the Illinois method, and each
    /// local minimum of `|F|` within its rounding a touching root (`true`).
    #[must_use]
    pub fn logistic_roots(&self, f: &[f64], slope: bool) -> Vec<(f64, bool)> {
        let mut om = vec![0.0; self.n];
        let scale = f.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let noise = 64.0 * f64::EPSILON * scale;
        let mut value = |sigma: f64| -> f64 {
            let mean = self.blend(sigma, &mut om);
            if slope {
                let k = om
                    .iter()
                    .enumerate()
                    .fold((0, 0.0), |b, (i, &w)| if w > b.1 { (i, w) } else { b })
                    .0;
                om.iter()
                    .enumerate()
                    .map(|(i, w)| w * (i as f64 - mean) * (f[i] - f[k]))
                    .sum()
            } else {
                om.iter().zip(f).map(|(w, x)| w * x).sum()
            }
        };
        let (lo, hi) = self.logistic_span();
        let steps = ((hi - lo) * 16.0).ceil().max(1.0) as usize;
        let at = |k: usize| lo + (hi - lo) * k as f64 / steps as f64;
        let mut out = Vec::new();
        let mut prev: Option<(f64, f64)> = None;
        let mut before: Option<f64> = None;
        for k in 0..=steps {
            let x = at(k);
            let v = value(x);
            if let Some((px, pv)) = prev {
                // A sign change between values both within rounding of 0 is rounding (the
                // tails, where every term but one has died away).
                let above = pv.abs() > noise || v.abs() > noise;
                if v == 0.0 && pv.abs() > noise {
                    out.push((x, false));
                } else if above && pv != 0.0 && v != 0.0 && (pv < 0.0) != (v < 0.0) {
                    // Illinois on [px, x].
                    let (mut a, mut fa, mut b, mut fb) = (px, pv, x, v);
                    let mut side = 0;
                    for _ in 0..100 {
                        let m = (a - fa * (b - a) / (fb - fa)).max(a.min(b)).min(a.max(b));
                        let fm = value(m);
                        if fm == 0.0 || (b - a).abs() <= 4.0 * f64::EPSILON * m.abs().max(1.0) {
                            a = m;
                            b = m;
                            break;
                        }
                        if (fm < 0.0) == (fa < 0.0) {
                            a = m;
                            fa = fm;
                            if side == -1 {
                                fb *= 0.5;
                            }
                            side = -1;
                        } else {
                            b = m;
                            fb = fm;
                            if side == 1 {
                                fa *= 0.5;
                            }
                            side = 1;
                        }
                    }
                    out.push((0.5 * (a + b), false));
                } else if let Some(bv) = before
                    && !slope
                    && pv.abs() <= noise
                    && pv.abs() < bv.abs()
                    && pv.abs() < v.abs()
                    && (bv < 0.0) == (v < 0.0)
                {
                    out.push((px, true));
                }
                before = Some(pv);
            }
            prev = Some((x, v));
        }
        out
    }

    /// The length of the control polygon: at least the segment's arc length (corner
    /// cutting shortens a polygon), and the scale of the rounding in its speed.
    #[must_use]
    pub fn polygon_length(&self) -> f64 {
        self.polygon
    }

    /// For a rational segment, the ratio of its largest weight to its smallest (1 for a
    /// polynomial one).
    #[must_use]
    pub fn weight_spread(&self) -> f64 {
        self.w().map_or(1.0, |w| {
            let (lo, hi) = w.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), &x| {
                (lo.min(x), hi.max(x))
            });
            hi / lo
        })
    }

    /// The logistic parameters `σ` (see [`Piece::speed_logistic`]) where two terms
    /// `w_i B_i` and `w_j B_j` of the weight are equal — where a segment with weights far
    /// apart moves from one control point's pull to another's.
    #[must_use]
    pub fn weight_transitions(&self) -> Vec<f64> {
        let Some(w) = self.w() else {
            return Vec::new();
        };
        let n = w.len() - 1;
        let ln: Vec<f64> = w
            .iter()
            .enumerate()
            .map(|(i, &x)| x.ln() + crate::geom::bernstein::binomial(n, i).ln())
            .collect();
        let mut out = Vec::new();
        for i in 0..=n {
            for j in i + 1..=n {
                // w_i C(n,i) (1−u)^{n−i} u^i = w_j C(n,j) (1−u)^{n−j} u^j ⇔ σ (j−i) = ln_i − ln_j.
                let sigma = (ln[i] - ln[j]) / (j - i) as f64;
                if sigma.is_finite() {
                    out.push(sigma);
                }
            }
        }
        out
    }

    /// The factors of the speed of a planar polynomial segment of degree ≤ 7 (`None`
    /// for the others).
    #[must_use]
    pub fn planar_speed(&self) -> Option<&PlanarSpeed> {
        self.planar_speed.as_deref()
    }

    /// The box of the control points in `x` and `y` (the segment lies in it).
    #[must_use]
    pub fn bounds(&self) -> (DVec2, DVec2) {
        self.bounds
    }

    /// The degree.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.a(0).len().saturating_sub(1)
    }

    /// The curve parameter of the segment's own `u`.
    #[must_use]
    pub fn t_of(&self, u: f64) -> f64 {
        if u >= 1.0 {
            self.t1
        } else {
            self.t0 + u * (self.t1 - self.t0)
        }
    }

    /// The segment's own `u` of the curve parameter `t`.
    #[must_use]
    pub fn u_of(&self, t: f64) -> f64 {
        ((t - self.t0) / (self.t1 - self.t0)).clamp(0.0, 1.0)
    }

    /// Whether every control point has `z = 0`.
    #[must_use]
    pub fn is_planar(&self) -> bool {
        self.planar
    }

    fn eval3(&self, c: [&[f64]; 3], u: f64) -> DVec3 {
        if self.planar {
            let (x, y) = poly::eval2(c[0], c[1], u);
            return DVec3::new(x, y, 0.0);
        }
        DVec3::new(
            poly::eval(c[0], u),
            poly::eval(c[1], u),
            poly::eval(c[2], u),
        )
    }

    fn weight(&self, u: f64) -> f64 {
        self.w().map_or(1.0, |w| poly::eval(w, u))
    }

    /// `C(u)`.
    #[must_use]
    pub fn point(&self, u: f64) -> DVec3 {
        let p = self.eval3(self.aa(), u);
        match self.w() {
            Some(_) => p / self.weight(u),
            None => p,
        }
    }

    /// A bound on the rounding error of [`Piece::point`] at `u` in `x`, `y` (the sum of
    /// the two): de Casteljau's running bounds on the numerators, and for a rational
    /// piece the weight's, carried through the division.
    #[must_use]
    pub fn point_error(&self, u: f64) -> f64 {
        let (x, ex) = poly::eval_with_bound(self.a(0), u);
        let (y, ey) = poly::eval_with_bound(self.a(1), u);
        match self.w() {
            None => ex + ey,
            Some(w) => {
                let (wv, ew) = poly::eval_with_bound(w, u);
                let c = x.abs().max(y.abs()) / wv;
                (ex + ey + 2.0 * c * ew) / wv + 2.0 * f64::EPSILON * c
            }
        }
    }

    /// For a polynomial piece of degree ≤ 3, the parameters in `(0, 1)` where some
    /// coordinate's derivative (a quadratic) may vanish: its real roots, and its vertex
    /// where the discriminant is within rounding of 0 ([`poly::quadratic_roots`]).
    /// Every root of a derivative is among them up to rounding, which moves the value at
    /// an extremum only to second order; an extra one is still a point of the curve.
    /// `None` for rational pieces and higher degrees. At most 9 parameters.
    #[must_use]
    pub fn box_candidates(&self) -> Option<([f64; 9], usize)> {
        if self.rational || self.m > 3 {
            return None;
        }
        let mut out = [0.0; 9];
        let mut count = 0;
        let mut push = |u: f64| {
            if u > 0.0 && u < 1.0 {
                out[count] = u;
                count += 1;
            }
        };
        let axes = if self.planar { 2 } else { 3 };
        for d in &self.daa()[..axes] {
            match **d {
                [d0, d1] if d0 != d1 => push(d0 / (d0 - d1)),
                [d0, d1, d2] => {
                    let (roots, n, vertex) = poly::quadratic_roots(d0, d1, d2);
                    roots[..n].iter().chain(&vertex).for_each(|&u| push(u));
                }
                _ => {}
            }
        }
        Some((out, count))
    }

    /// `C(u)` and `dC/du` from one de Casteljau triangle per coordinate (and for `W`).
    #[must_use]
    pub fn point_and_deriv(&self, u: f64) -> (DVec3, DVec3) {
        let ((x, dx), (y, dy)) = poly::eval_with_derivative2(self.a(0), self.a(1), u);
        let (z, dz) = if self.planar {
            (0.0, 0.0)
        } else {
            poly::eval_with_derivative(self.a(2), u)
        };
        let (a, da) = (DVec3::new(x, y, z), DVec3::new(dx, dy, dz));
        match self.w() {
            Some(w) => {
                let (w0, w1) = poly::eval_with_derivative(w, u);
                let c = a / w0;
                (c, (da - w1 * c) / w0)
            }
            None => (a, da),
        }
    }

    /// `dC/du` (the quotient rule for a rational segment, `(A′W − AW′) / W²`, evaluated as
    /// `(A′ − C W′) / W` so that `W²` cannot overflow where `W` itself does not).
    #[must_use]
    pub fn deriv(&self, u: f64) -> DVec3 {
        let da = self.eval3(self.daa(), u);
        match (self.w(), self.dw()) {
            (Some(w), Some(dw)) => {
                let (w0, w1) = (poly::eval(w, u), poly::eval(dw, u));
                let c = self.eval3(self.aa(), u) / w0;
                (da - c * w1) / w0
            }
            _ => da,
        }
    }

    /// `d²C/du²`.
    #[must_use]
    pub fn second_deriv(&self, u: f64) -> DVec3 {
        let dd = poly::eval_second_derivative;
        let z = if self.planar { 0.0 } else { dd(self.a(2), u) };
        let dda = DVec3::new(dd(self.a(0), u), dd(self.a(1), u), z);
        match self.w() {
            Some(w) => {
                let (w0, w1) = poly::eval_with_derivative(w, u);
                let w2 = dd(w, u);
                let (c, d1) = self.point_and_deriv(u);
                (dda - 2.0 * w1 * d1 - w2 * c) / w0
            }
            None => dda,
        }
    }

    /// The local minima of `|C′|` inside `(0, 1)` — where `d|N|²/du` (`N` the velocity's
    /// numerator) changes sign from negative to positive — each with `δ`, the distance
    /// from the real axis of the complex roots of `|N|²` near it (`|N|² ≈ m² + ½Q″(u − u₀)²`
    /// gives `δ = m √(2/Q″)`): the speed is analytic only that close to the minimum, so a
    /// quadrature must use intervals no longer than about `δ` there. For a rational
    /// segment the minima of `|N|` stand in for those of `|C′| = |N| / W²`.
    #[must_use]
    pub fn speed_minima(&self) -> Vec<(f64, f64)> {
        let g = self.speed_squared_numerator(if self.planar { 2 } else { 3 });
        let slope = poly::derivative(&g);
        let curve = poly::derivative(&slope);
        crate::poly::roots::bernstein_roots(&slope)
            .roots
            .iter()
            .filter(|r| r.t > 0.0 && r.t < 1.0 && r.multiplicity % 2 == 1)
            .filter(|r| {
                let h = 1e-6;
                poly::eval(&slope, (r.t - h).max(0.0)) < 0.0
                    && poly::eval(&slope, (r.t + h).min(1.0)) > 0.0
            })
            .map(|r| {
                let (q, q2) = (poly::eval(&g, r.t).max(0.0), poly::eval(&curve, r.t));
                let delta = if q2 > 0.0 { (2.0 * q / q2).sqrt() } else { 1.0 };
                (r.t, delta)
            })
            .collect()
    }

    /// The numerator of `dC_k/du` in Bernstein form: `A_k′` (polynomial) or
    /// `A_k′ W − A_k W′` (rational; `W² > 0` does not change its roots or sign).
    #[must_use]
    pub fn deriv_numerator(&self, k: usize) -> Vec<f64> {
        match (self.w(), self.dw()) {
            (Some(w), Some(dw)) => {
                poly::difference(&poly::product(self.da(k), w), &poly::product(self.a(k), dw))
            }
            _ => self.da(k).to_vec(),
        }
    }

    /// `C′ × C″` (2D) up to a positive factor: `x′y″ − y′x″` for a polynomial segment,
    /// `det(H, H′, H″)` with `H = (A_x, A_y, W)` for a rational one (`C′ × C″ =
    /// det(H, H′, H″) / W³`, `W > 0`). Its sign is the sign of the curvature. With it, the
    /// rounding its coefficients may carry (the cancellation of its terms).
    #[must_use]
    pub fn cross_numerator(&self) -> (Vec<f64>, f64) {
        let (x1, y1) = (self.da(0), self.da(1));
        let (x2, y2) = (poly::derivative(x1), poly::derivative(y1));
        match (self.w(), self.dw()) {
            (Some(w), Some(w1)) => {
                let w2 = poly::derivative(w1);
                let (x, y) = (self.a(0), self.a(1));
                // x (y′w″ − w′y″) − y (x′w″ − w′x″) + w (x′y″ − y′x″)
                let t1 = poly::product(
                    x,
                    &poly::difference(&poly::product(y1, &w2), &poly::product(w1, &y2)),
                );
                let t2 = poly::product(
                    y,
                    &poly::difference(&poly::product(x1, &w2), &poly::product(w1, &x2)),
                );
                let t3 = poly::product(
                    w,
                    &poly::difference(&poly::product(x1, &y2), &poly::product(y1, &x2)),
                );
                let size = [
                    (x, y1, &w2),
                    (x, w1, &y2),
                    (y, x1, &w2),
                    (y, w1, &x2),
                    (w, x1, &y2),
                    (w, y1, &x2),
                ]
                .iter()
                .map(|(a, b, c)| max_abs(a) * max_abs(b) * max_abs(c))
                .sum::<f64>();
                let c = poly::sum(&poly::difference(&t1, &t2), &t3);
                let noise = rounding(c.len(), size);
                (c, noise)
            }
            _ => {
                let (p, q) = (poly::product(x1, &y2), poly::product(y1, &x2));
                let size = max_abs(x1) * max_abs(&y2) + max_abs(y1) * max_abs(&x2);
                let c = poly::difference(&p, &q);
                let noise = rounding(c.len(), size);
                (c, noise)
            }
        }
    }

    /// `|N|²` for the velocity numerator `N` (`A′` or `A′W − AW′`), in 2D (`x`, `y`) or 3D:
    /// zero exactly where `C′ = 0` (cusps and stationary points).
    #[must_use]
    pub fn speed_squared_numerator(&self, dims: usize) -> Vec<f64> {
        (0..dims)
            .map(|k| {
                let n = self.deriv_numerator(k);
                poly::product(&n, &n)
            })
            .reduce(|a, b| poly::sum(&a, &b))
            .unwrap_or_default()
    }

    /// The numerator of `dκ/du` (2D), whose roots are the curvature's stationary points:
    /// with `κ = F / G^{3/2}`, `F = det(H, H′, H″) W³` (`C′ × C″` for a polynomial
    /// segment) and `G = |N|²`, it is `2F′G − 3FG′`; with the rounding its coefficients
    /// may carry (on a circular arc the two terms cancel exactly in exact arithmetic).
    #[must_use]
    pub fn curvature_slope_numerator(&self) -> (Vec<f64>, f64) {
        let (cross, cross_noise) = self.cross_numerator();
        let (f, f_noise) = match self.w() {
            Some(w) => {
                let w3 = poly::product(w, &poly::product(w, w));
                let m = max_abs(&w3);
                (poly::product(&cross, &w3), cross_noise * m)
            }
            None => (cross, cross_noise),
        };
        let g = self.speed_squared_numerator(2);
        let (df, dg) = (poly::derivative(&f), poly::derivative(&g));
        let t1 = poly::scaled(&poly::product(&df, &g), 2.0);
        let t2 = poly::scaled(&poly::product(&f, &dg), 3.0);
        let c = poly::difference(&t1, &t2);
        let deg = f.len() as f64;
        let size = 2.0 * max_abs(&df) * max_abs(&g) + 3.0 * max_abs(&f) * max_abs(&dg);
        let propagated = f_noise * (2.0 * deg * max_abs(&g) + 3.0 * max_abs(&dg));
        let noise = rounding(c.len(), size) + propagated;
        (c, noise)
    }

    /// The integrand of the signed area (2D), `x y′ − y x′`: for a polynomial segment its
    /// Bernstein coefficients (then `∫₀¹ = Σ c_i / (m + 1)` is exact but for rounding).
    #[must_use]
    pub fn area_integrand(&self) -> Option<Vec<f64>> {
        if self.rational {
            return None;
        }
        Some(poly::difference(
            &poly::product(self.a(0), self.da(1)),
            &poly::product(self.a(1), self.da(0)),
        ))
    }
}

impl Piece {
    /// `(C − p) · dC/du` up to a positive factor, in Bernstein form, over the first `dims`
    /// coordinates: `Σ (A_k − p_k) A_k′` for a polynomial segment, `Σ (A_k − p_k W)(A_k′ W
    /// − A_k W′)` for a rational one (the true value times `W³ > 0`). Its roots are where
    /// the distance to `p` is stationary. With the rounding its coefficients may carry.
    #[must_use]
    pub fn nearest_numerator(&self, p: DVec3, dims: usize) -> (Vec<f64>, f64) {
        let mut total: Vec<f64> = Vec::new();
        let mut size = 0.0;
        for k in 0..dims {
            let (diff, deriv, span) = match self.w() {
                Some(w) => {
                    let d: Vec<f64> = self.a(k).iter().zip(w).map(|(a, w)| a - p[k] * w).collect();
                    let span = max_abs(self.a(k)) + p[k].abs() * max_abs(w);
                    (d, self.deriv_numerator(k), span)
                }
                None => {
                    let d: Vec<f64> = self.a(k).iter().map(|a| a - p[k]).collect();
                    let span = max_abs(self.a(k)) + p[k].abs();
                    (d, self.da(k).to_vec(), span)
                }
            };
            size += span * max_abs(&deriv);
            let term = poly::product(&diff, &deriv);
            total = if total.is_empty() {
                term
            } else {
                poly::sum(&total, &term)
            };
        }
        let noise = rounding(total.len(), size);
        (total, noise)
    }

    /// A bound on the speed `|dC/du|` over the segment: `n max |P_{i+1} − P_i|` for a
    /// polynomial one; for a rational one that times `(w_max / w_min)²` (Floater's bound
    /// on the derivative of a rational Bézier curve).
    #[must_use]
    pub fn speed_bound(&self) -> f64 {
        let degree = self.degree() as f64;
        let point = |i: usize| {
            let v = DVec3::new(self.a(0)[i], self.a(1)[i], self.a(2)[i]);
            match self.w() {
                Some(w) => v / w[i],
                None => v,
            }
        };
        let legs = (1..self.n)
            .map(|i| (point(i) - point(i - 1)).length())
            .fold(0.0, f64::max);
        let ratio = self.w().map_or(1.0, |w| {
            let (lo, hi) = w.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), &x| {
                (lo.min(x), hi.max(x))
            });
            (hi / lo).powi(2)
        });
        degree * legs * ratio
    }
}

/// The largest coefficient in absolute value.
fn max_abs(c: &[f64]) -> f64 {
    c.iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// The rounding a polynomial of `len` coefficients computed from products of size `size`
/// may carry: generously `16 len ε size` (each product coefficient sums at most `len`
/// rounded terms, each elevation and difference adds one rounding).
fn rounding(len: usize, size: f64) -> f64 {
    16.0 * len as f64 * f64::EPSILON * size
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Bezier, RationalBezier};

    /// The table is Pascal's triangle: `C(m, k) = m! / (k! (m − k)!)`, in integers.
    #[test]
    fn binomials_are_pascals_triangle() {
        let factorial = |n: usize| (1..=n as u64).product::<u64>();
        for (m, row) in BINOMIALS.iter().enumerate() {
            for (k, &c) in row.iter().enumerate() {
                let want = if k <= m {
                    factorial(m) / (factorial(k) * factorial(m - k))
                } else {
                    0
                };
                assert_eq!(c, want as f64, "C({m}, {k})");
            }
        }
    }

    #[test]
    fn derivatives_agree_with_the_curves() {
        let pts = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 3.0, 1.0),
            DVec3::new(3.0, -1.0, 2.0),
            DVec3::new(4.0, 2.0, 0.5),
        ];
        let b = Bezier::new(pts.clone());
        let r = RationalBezier::try_new(pts, vec![1.0, 0.5, 2.0, 1.5]).expect("curve");
        let pb = Piece::new(&BezierSegment::polynomial(b.clone(), 0.0, 1.0));
        let pr = Piece::new(&BezierSegment {
            bezier: b.clone(),
            weights: Some(vec![1.0, 0.5, 2.0, 1.5]),
            t0: 0.0,
            t1: 1.0,
        });
        use crate::geom::ParamCurve;
        for k in 0..=10 {
            let u = f64::from(k) / 10.0;
            assert!((pb.point(u) - b.eval(u)).length() < 1e-14);
            assert!((pb.deriv(u) - b.eval_deriv(u)).length() < 1e-13);
            assert!((pb.second_deriv(u) - b.eval_second_deriv(u)).length() < 1e-12);
            assert!((pr.point(u) - r.eval(u)).length() < 1e-14);
            assert!((pr.deriv(u) - r.eval_deriv(u)).length() < 1e-12);
            assert!((pr.second_deriv(u) - r.eval_second_deriv(u)).length() < 1e-11);
            // The cross numerator's sign is the sign of C′ × C″ (W > 0).
            let cross = poly::eval(&pr.cross_numerator().0, u);
            let d1 = r.eval_deriv(u);
            let d2 = r.eval_second_deriv(u);
            let want = d1.x * d2.y - d1.y * d2.x;
            let w = poly::eval(pr.w().unwrap_or(&[1.0]), u);
            assert!((cross / w.powi(3) - want).abs() < 1e-10 * (1.0 + want.abs()));
        }
    }
}
