//! The arc length of a planar polynomial segment by Gauss–Legendre rules whose error is
//! bounded before any value is computed, from where the speed stops being analytic.
//!
//! With `p(u) = x′(u) + i y′(u)` (a complex polynomial with roots `r_j` and leading
//! coefficient `ℓ`), the speed on the real line is `|C′(u)| = |p(u)| = |ℓ| Π_j |u − r_j|`:
//! the square root of `p(u) p̄(u)`, analytic everywhere but at the `r_j` and their
//! conjugates. On an interval `[c − h, c + h]` it is therefore analytic inside the
//! Bernstein ellipse `E_ρ` (foci at the ends, `ρ` the sum of its semi-axes over `h`) that
//! passes through the nearest root, and there `|f| ≤ M = |ℓ| Π_j (|c − r_j| + h (ρ + ρ⁻¹)/2)`.
//! The `n`-point Gauss–Legendre rule's error is then at most
//! `16 h M ρ² / (3 (ρ² − 1) ρ^{2n})`: on `[−1, 1]` the Chebyshev coefficients obey
//! `|a_k| ≤ 2 M ρ^{−k}` (Trefethen, *Approximation Theory and Approximation Practice*,
//! Theorem 8.1); the rule is exact for `k < 2n`, and for odd `k` both the integral and the
//! rule vanish; for even `k ≥ 2n`, `|∫T_k − Σ w_i T_k(x_i)| ≤ 2/(k² − 1) + 2` (the weights
//! sum to 2, `|T_k| ≤ 1`). Summing, `4 M (1 + 1/(4n² − 1)) ρ^{−2n} / (1 − ρ^{−2})`, at most
//! the bound above. (The form `64 M / (15 (ρ² − 1) ρ^{2n})` is not a bound: the one-point
//! rule on `z²` errs by `2/3` where it gives `0.56` at `ρ = 2`.)
//! Each interval gets the fewest nodes whose bound meets its share
//! of the tolerance, and an interval that would need more than [`MAX_NODES`] is cut — at a
//! root's real part where it lies inside, and otherwise, toward a root beyond an end, at
//! four times the root's distance from that end (so the pieces grow geometrically away from
//! a near-cusp).
//!
//! A root within `δ` of the real axis (a near-cusp), with `δ` so small that replacing
//! `√((u − x)² + δ²)` by `|u − x|` changes the integral by at most
//! `G δ² (5/2 + ln⁺(2 (b − a) / δ) + S)` (`G` the other factors' maximum on the interval,
//! `S ≈ 9.6` the most any rule's nodes pick up from a difference `δ² / (2v)` at a distance
//! `v` from an end) and that is below a quarter of the share, is treated as an exact cusp:
//! the interval is cut at `x`, on each side `|u − x|` is a polynomial, and that bound is
//! added to the error. So even a cusp
//! `10⁻¹⁵` off the axis costs a handful of intervals, not fifty halvings.

use std::sync::OnceLock;

use nalgebra::Complex;

use super::quadrature::Quadrature;

/// The most nodes one interval's rule may have before the interval is cut.
pub const MAX_NODES: usize = 96;

/// Bits of `MAX_NODES − 1`: the steps of the binary lifting that picks a rule's size.
const NODE_BITS: usize = 7;

/// The most intervals one length evaluates.
const MAX_INTERVALS: usize = 1 << 12;

/// Complex numbers (num-complex's, through nalgebra), for the roots of the velocity.
type C64 = Complex<f64>;

const ZERO: C64 = C64::new(0.0, 0.0);
const ONE: C64 = C64::new(1.0, 0.0);

/// `Σ c_j z^j` and its derivative.
fn eval_with_derivative(c: &[C64], z: C64) -> (C64, C64) {
    let mut p = ZERO;
    let mut dp = ZERO;
    for &cj in c.iter().rev() {
        dp = dp * z + p;
        p = p * z + cj;
    }
    (p, dp)
}

/// The speed of a planar polynomial segment: its hodograph (power basis, ascending) and
/// its factors `|ℓ| Π_j |u − r_j|`, each root as `(Re r_j, |Im r_j|)` (a root and its
/// conjugate act alike).
#[derive(Debug, Clone, PartialEq)]
pub struct PlanarSpeed {
    x: [f64; MAX_ROOTS + 1],
    y: [f64; MAX_ROOTS + 1],
    /// The hodograph's degree (`x`, `y` beyond it are 0).
    degree: usize,
    lead: f64,
    roots: [(f64, f64); MAX_ROOTS],
    count: usize,
}

impl PlanarSpeed {
    /// The speed whose hodograph has these power-basis coefficients (ascending); `None`
    /// for a degree above 6 or where the roots cannot be found to full precision
    /// (coefficients whose products overflow, or a root iteration that does not settle).
    #[must_use]
    #[inline]
    pub fn new(x: &[f64], y: &[f64]) -> Option<PlanarSpeed> {
        let mut len = x.len().min(y.len());
        while len > 0 && x[len - 1] == 0.0 && y[len - 1] == 0.0 {
            len -= 1;
        }
        if len > MAX_ROOTS + 1 {
            return None;
        }
        let mut c = [ZERO; MAX_ROOTS + 1];
        for (k, v) in c.iter_mut().enumerate().take(len) {
            *v = C64::new(x[k], y[k]);
        }
        let c = &c[..len];
        if c.iter().any(|v| !v.is_finite()) {
            return None;
        }
        // Lines and quadratics (the hodographs of quadratics and cubics) without allocating.
        let mut few = [ZERO; 2];
        let many;
        let found: &[C64] = match c.len() {
            0 | 1 => &[],
            2 => {
                few[0] = -quotient(c[0], c[1]);
                &few[..1]
            }
            3 => {
                few = quadratic_roots(c[0], c[1], c[2]);
                &few
            }
            _ => {
                many = aberth(c)?;
                &many
            }
        };
        let lead = c.last().map_or(0.0, |v| modulus(*v));
        if !lead.is_finite() || found.iter().any(|r| !r.is_finite()) {
            return None;
        }
        let mut out = PlanarSpeed {
            x: [0.0; MAX_ROOTS + 1],
            y: [0.0; MAX_ROOTS + 1],
            degree: c.len().saturating_sub(1),
            lead,
            roots: [(0.0, 0.0); MAX_ROOTS],
            count: found.len(),
        };
        for (k, v) in c.iter().enumerate() {
            out.x[k] = v.re;
            out.y[k] = v.im;
        }
        for (slot, r) in out.roots.iter_mut().zip(found) {
            *slot = (r.re, r.im.abs());
        }
        Some(out)
    }

    /// The roots, as `(Re r_j, |Im r_j|)`.
    fn roots(&self) -> &[(f64, f64)] {
        &self.roots[..self.count]
    }

    /// `|C′(u)|`.
    #[must_use]
    pub fn speed(&self, u: f64) -> f64 {
        match self.degree {
            0 => self.speed_of::<0>(u),
            1 => self.speed_of::<1>(u),
            2 => self.speed_of::<2>(u),
            3 => self.speed_of::<3>(u),
            4 => self.speed_of::<4>(u),
            5 => self.speed_of::<5>(u),
            _ => self.speed_of::<6>(u),
        }
    }

    #[inline(always)]
    fn speed_of<const D: usize>(&self, u: f64) -> f64 {
        let (mut dx, mut dy) = (self.x[D], self.y[D]);
        for k in (0..D).rev() {
            dx = dx * u + self.x[k];
            dy = dy * u + self.y[k];
        }
        let s = (dx * dx + dy * dy).sqrt();
        if s.is_finite() { s } else { dx.hypot(dy) }
    }

    /// `∫_{c−h}^{c+h} |C′|` by the `n`-point rule.
    fn apply(&self, n: usize, c: f64, h: f64) -> f64 {
        match self.degree {
            0 => self.apply_of::<0>(n, c, h),
            1 => self.apply_of::<1>(n, c, h),
            2 => self.apply_of::<2>(n, c, h),
            3 => self.apply_of::<3>(n, c, h),
            4 => self.apply_of::<4>(n, c, h),
            5 => self.apply_of::<5>(n, c, h),
            _ => self.apply_of::<6>(n, c, h),
        }
    }

    fn apply_of<const D: usize>(&self, n: usize, c: f64, h: f64) -> f64 {
        let r = rule(n);
        // The hodograph in the interval's own variable `x` (`u = c + h x`): shifted to `c`,
        // scaled by `h^k`; then `p(±x) = E(x²) ± x O(x²)` from its even and odd parts, so a
        // pair of nodes costs one evaluation of each part.
        let (mut x, mut y) = ([0.0; 7], [0.0; 7]);
        x[..=D].copy_from_slice(&self.x[..=D]);
        y[..=D].copy_from_slice(&self.y[..=D]);
        for i in 0..D {
            for k in (i..D).rev() {
                x[k] += c * x[k + 1];
                y[k] += c * y[k + 1];
            }
        }
        let mut scale = h;
        for k in 1..=D {
            x[k] *= scale;
            y[k] *= scale;
            scale *= h;
        }
        let mut sum = 0.0;
        let mut k0 = 0;
        if n % 2 == 1 {
            sum = r.weights[0] * norm(x[0], y[0]);
            k0 = 1;
        }
        // Two square roots at once, the squares' overflow checked once on the total.
        let mut pairs = 0.0;
        for (&t, &w) in r.nodes[k0..].iter().zip(&r.weights[k0..]) {
            let t2 = t * t;
            let (mut ex, mut ey) = (x[D - D % 2], y[D - D % 2]);
            let mut k = D - D % 2;
            while k >= 2 {
                k -= 2;
                ex = ex * t2 + x[k];
                ey = ey * t2 + y[k];
            }
            let (mut ox, mut oy) = (0.0, 0.0);
            if D >= 1 {
                let top = D - 1 + D % 2;
                ox = x[top];
                oy = y[top];
                let mut k = top;
                while k >= 3 {
                    k -= 2;
                    ox = ox * t2 + x[k];
                    oy = oy * t2 + y[k];
                }
                ox *= t;
                oy *= t;
            }
            let (xm, xp, ym, yp) = (ex - ox, ex + ox, ey - oy, ey + oy);
            let s = sqrt2([xm * xm + ym * ym, xp * xp + yp * yp]);
            pairs += w * (s[0] + s[1]);
        }
        if !pairs.is_finite() {
            pairs = 0.0;
            for (&t, &w) in r.nodes[k0..].iter().zip(&r.weights[k0..]) {
                pairs += w * (self.speed_of::<D>(c - h * t) + self.speed_of::<D>(c + h * t));
            }
        }
        (sum + pairs) * h
    }

    /// `∫_{u0}^{u1} |C′|` within `tolerance`: the error returned is the sum of the
    /// intervals' bounds and of the rules' rounding, `(n + 8) ε` of each value.
    #[must_use]
    pub fn length(&self, u0: f64, u1: f64, tolerance: f64) -> Quadrature {
        let mut out = Quadrature::default();
        if u1 <= u0 || self.lead == 0.0 {
            return out;
        }
        let mut stack = Stack::default();
        let mut next = Some((u0, u1));
        let mut intervals = 0;
        // The intervals are done left to right; each gets its width's share of what the
        // ones before it left of the tolerance.
        let mut used = 0.0;
        while let Some((a, b)) = next.take().or_else(|| stack.pop()) {
            intervals += 1;
            let share = (tolerance - used).max(0.0) * (b - a) / (u1 - a);
            let (n, bound) = match self.plan(a, b, share) {
                Plan::Cut(m) if m > a && m < b && intervals + stack.len() < MAX_INTERVALS => {
                    stack.push((m, b));
                    next = Some((a, m));
                    continue;
                }
                Plan::Rule { n, bound } => (n, bound),
                // No room left to cut: the largest rule, and an unknown error.
                Plan::Cut(_) => (MAX_NODES, f64::INFINITY),
            };
            let v = self.apply(n, 0.5 * (a + b), 0.5 * (b - a));
            let error = bound + (n as f64 + 8.0) * f64::EPSILON * v.abs();
            used += error;
            out.value += v;
            out.error += error;
            out.evaluations += n;
        }
        if !out.value.is_finite() {
            out.error = f64::INFINITY;
        }
        out
    }
}

/// The roots of `a + b z + c z²` (`c ≠ 0`), without cancellation (divisions by `quotient`,
/// which does not overflow).
#[inline]
fn quadratic_roots(a: C64, b: C64, c: C64) -> [C64; 2] {
    let mut s = complex_sqrt(b * b - a * c * 4.0);
    // The sign that adds to `b` rather than cancelling it.
    if b.re * s.re + b.im * s.im < 0.0 {
        s = -s;
    }
    let q = (b + s) * -0.5;
    if q == ZERO {
        return [ZERO, ZERO];
    }
    [quotient(q, c), quotient(a, q)]
}

/// `|z|`: `√(x² + y²)` where the sum of squares is a normal number, `hypot` (which scales)
/// only where it overflows or underflows.
#[inline]
fn modulus(z: C64) -> f64 {
    let s = z.re * z.re + z.im * z.im;
    if s.is_normal() { s.sqrt() } else { z.norm() }
}

/// `a / b`: `a b̄ / |b|²` where `|b|²` is a normal number and the result finite, `fdiv`
/// (which scales) otherwise.
#[inline]
fn quotient(a: C64, b: C64) -> C64 {
    let s = b.re * b.re + b.im * b.im;
    if s.is_normal() {
        let q = C64::new(
            (a.re * b.re + a.im * b.im) / s,
            (a.im * b.re - a.re * b.im) / s,
        );
        if q.is_finite() {
            return q;
        }
    }
    a.fdiv(b)
}

/// The principal square root of `z` in algebraic form (`num-complex`'s goes through
/// `atan2` and `sin`/`cos`): `t = √((|Re z| + |z|) / 2)`, then the other part is
/// `Im z / 2t` — no cancellation, both halves scaled by ½ first so that nothing overflows.
#[inline]
fn complex_sqrt(z: C64) -> C64 {
    if z.im == 0.0 {
        return if z.re >= 0.0 {
            C64::new(z.re.sqrt(), z.im)
        } else {
            C64::new(0.0, (-z.re).sqrt())
        };
    }
    let t = (0.5 * z.re.abs() + 0.5 * modulus(z)).sqrt();
    if z.re >= 0.0 {
        C64::new(t, z.im / (2.0 * t))
    } else {
        C64::new(z.im.abs() / (2.0 * t), t.copysign(z.im))
    }
}

/// All roots of `Σ c_j z^j` (degree ≥ 3, `c_last ≠ 0`) by the Aberth–Ehrlich iteration,
/// polished by Newton steps on the polynomial itself.
fn aberth(c: &[C64]) -> Option<Vec<C64>> {
    let n = c.len() - 1;
    let lead = c[n];
    // Cauchy's bound on the roots' moduli sets the starting circle.
    let radius = c[..n]
        .iter()
        .map(|v| v.fdiv(lead).norm())
        .fold(0.0_f64, f64::max)
        .max(f64::MIN_POSITIVE);
    let radius = (1.0 + radius).min(1e150);
    let mut z: Vec<C64> = (0..n)
        .map(|k| {
            let angle = std::f64::consts::TAU * (k as f64 + 0.25) / n as f64 + 0.4;
            C64::from_polar(0.5 * radius, angle)
        })
        .collect();
    let mut settled = false;
    for _ in 0..200 {
        let mut largest = 0.0_f64;
        for i in 0..n {
            let (p, dp) = eval_with_derivative(c, z[i]);
            if p == ZERO {
                continue;
            }
            let ratio = p.fdiv(dp);
            let mut sum = ZERO;
            for (j, zj) in z.iter().enumerate() {
                if j != i {
                    sum += ONE.fdiv(z[i] - zj);
                }
            }
            let step = ratio.fdiv(ONE - ratio * sum);
            if !step.is_finite() {
                return None;
            }
            z[i] -= step;
            largest = largest.max(step.norm() / z[i].norm().max(1.0));
        }
        if largest <= 4.0 * f64::EPSILON {
            settled = true;
            break;
        }
    }
    if !settled {
        return None;
    }
    for zi in &mut z {
        for _ in 0..2 {
            let (p, dp) = eval_with_derivative(c, *zi);
            let step = p.fdiv(dp);
            if step.is_finite() {
                *zi -= step;
            }
        }
    }
    Some(z)
}

/// One Gauss–Legendre rule on `[−1, 1]`: the nonnegative nodes (ascending from the
/// middle) and their weights.
#[derive(Debug)]
struct Rule {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

/// The `n`-point rule: the roots of `P_n` by Newton's method from Tricomi's estimate, the
/// weights `2 / ((1 − x²) P_n′(x)²)`.
fn legendre_rule(n: usize) -> Rule {
    let mut nodes = Vec::new();
    let mut weights = Vec::new();
    let nf = n as f64;
    for i in 0..n.div_ceil(2) {
        // The i-th largest root.
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (nf + 0.5)).cos();
        // P_n(x) and P_n′(x) by the three-term recurrence.
        let legendre = |x: f64| {
            let (mut p0, mut p1) = (1.0_f64, x);
            for k in 2..=n {
                let kf = k as f64;
                let p2 = ((2.0 * kf - 1.0) * x * p1 - (kf - 1.0) * p0) / kf;
                p0 = p1;
                p1 = p2;
            }
            let (pn, pn1) = if n == 1 { (x, 1.0) } else { (p1, p0) };
            (pn, nf * (x * pn - pn1) / (x * x - 1.0))
        };
        for _ in 0..100 {
            let (pn, dp) = legendre(x);
            let dx = pn / dp;
            x -= dx;
            if dx.abs() <= 1e-17 {
                break;
            }
        }
        let dp = legendre(x).1;
        nodes.push(x);
        weights.push(2.0 / ((1.0 - x * x) * dp * dp));
    }
    nodes.reverse();
    weights.reverse();
    if n % 2 == 1 {
        // The middle node is exactly 0.
        nodes[0] = 0.0;
    }
    Rule { nodes, weights }
}

/// The rules for `n = 0..=MAX_NODES` (0 standing for 1), and the largest over them of
/// `S_n = Σ_i w_i / (2 (1 − |ξ_i|))`: the most a rule's nodes can pick up from a
/// difference `≤ δ² / (2 v)` at distance `v` beyond an end of the interval, in units of `δ²`.
fn rules() -> &'static (Vec<Rule>, f64) {
    static RULES: OnceLock<(Vec<Rule>, f64)> = OnceLock::new();
    RULES.get_or_init(|| {
        let rules: Vec<Rule> = (0..=MAX_NODES).map(|n| legendre_rule(n.max(1))).collect();
        let end_sum = rules
            .iter()
            .map(|r| {
                r.nodes
                    .iter()
                    .zip(&r.weights)
                    .map(|(&x, &w)| {
                        let pair = if x == 0.0 { 1.0 } else { 2.0 };
                        pair * w / (2.0 * (1.0 - x))
                    })
                    .sum::<f64>()
            })
            .fold(0.0, f64::max);
        (rules, end_sum)
    })
}

fn rule(n: usize) -> &'static Rule {
    &rules().0[n]
}

/// Two square roots, written lane by lane so the compiler can pack them.
#[inline(always)]
fn sqrt2(v: [f64; 2]) -> [f64; 2] {
    [v[0].sqrt(), v[1].sqrt()]
}

/// The intervals still to do: a few in place, more on the heap.
#[derive(Default)]
struct Stack {
    near: [(f64, f64); 16],
    len: usize,
    far: Vec<(f64, f64)>,
}

impl Stack {
    fn push(&mut self, v: (f64, f64)) {
        if self.len < self.near.len() {
            self.near[self.len] = v;
            self.len += 1;
        } else {
            self.far.push(v);
        }
    }
    fn pop(&mut self) -> Option<(f64, f64)> {
        if let Some(v) = self.far.pop() {
            Some(v)
        } else if self.len > 0 {
            self.len -= 1;
            Some(self.near[self.len])
        } else {
            None
        }
    }
    fn len(&self) -> usize {
        self.len + self.far.len()
    }
}

/// What to do with one interval.
enum Plan {
    /// Apply the `n`-point rule; its error is at most `bound`.
    Rule { n: usize, bound: f64 },
    /// Cut at this parameter.
    Cut(f64),
}

/// `√(x² + y²)`, by `hypot` only where the squares overflow.
fn norm(x: f64, y: f64) -> f64 {
    let n = (x * x + y * y).sqrt();
    if n.is_finite() { n } else { x.hypot(y) }
}

impl PlanarSpeed {
    fn plan(&self, a: f64, b: f64, share: f64) -> Plan {
        let roots = self;
        let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
        let inv_h = 1.0 / h;
        let count = roots.count;
        let mut dist = [0.0_f64; MAX_ROOTS];
        let mut top = roots.lead;
        for (dj, &(x, d)) in dist.iter_mut().zip(roots.roots()) {
            *dj = norm(c - x, d);
            top *= *dj + h;
        }
        let mut cusp_error = 0.0;
        let mut cusps = 0;
        // `δ` of the roots taken as cusps: `|z − x| ≤ |z − r| + δ` in the bound below.
        let mut cusp_widths = [0.0_f64; MAX_ROOTS];
        // The nearest root in the Bernstein-ellipse sense: the smallest `α`, the mean of its
        // distances to the ends in units of `h` (`ρ = α + √(α² − 1)` grows with `α`).
        let mut alpha_min = f64::INFINITY;
        let mut critical = None;
        let per_cusp = 0.25 * share / count.max(1) as f64;
        let end_sum = 2.5 + rules().1;
        for (j, &(x, delta)) in roots.roots().iter().enumerate() {
            // Replacing √((u − x)² + δ²) by |u − x| (x at an end or beyond) changes the
            // integral by at most `G δ² (3/2 + ln(2 (b − a) / δ + 1))` and the rule's sum
            // by at most `G δ² S_n`; `ln(y + 1) ≤ ln⁺ y + 1`. (`G = top / (dist + h)`, the
            // comparison made before dividing.)
            let scaled = top * delta * delta * end_sum;
            if delta == 0.0 || scaled <= per_cusp * (dist[j] + h) {
                let others = top / (dist[j] + h);
                let base = others * delta * delta * end_sum;
                let replaced = if delta == 0.0 {
                    0.0
                } else {
                    base + others * delta * delta * (2.0 * (b - a) / delta).ln().max(0.0)
                };
                if replaced <= per_cusp {
                    if x > a && x < b {
                        return Plan::Cut(x);
                    }
                    cusp_error += replaced;
                    cusps += 1;
                    cusp_widths[j] = delta;
                    continue;
                }
            }
            // `α ≥ |w|` (the mean of the distances to `±1` is at least the distance to 0):
            // a root that far is not nearer than the nearest so far.
            if dist[j] * inv_h > alpha_min * (1.0 + 1e-12) {
                continue;
            }
            let (wr, wi) = ((x - c) * inv_h, delta * inv_h);
            let alpha = 0.5 * (norm(wr - 1.0, wi) + norm(wr + 1.0, wi));
            if alpha < alpha_min {
                alpha_min = alpha;
                critical = Some((x, delta));
            }
        }
        let Some((x, delta)) = critical else {
            // A polynomial of degree `cusps` (and `cusps = 0`: a constant).
            return Plan::Rule {
                n: (cusps + 2) / 2,
                bound: cusp_error,
            };
        };
        // `ρ = α + √(α² − 1)`, `(ρ + ρ⁻¹)/2 = α` (the ellipse's semi-major axis over `h`),
        // `ρ² − 1 = 2ρ√(α² − 1)`.
        let root = ((alpha_min - 1.0) * (alpha_min + 1.0)).max(0.0).sqrt();
        let rho = alpha_min + root;
        let inv_rho = 1.0 / rho;
        let mut m = roots.lead;
        for (dj, d) in dist.iter().zip(&cusp_widths).take(count) {
            m *= dj + h * alpha_min + d;
        }
        // The bound is `k ρ^{−2n}` with `k = 16 h M ρ² / (3 (ρ² − 1))`; the comparisons below
        // are made on `3 (ρ² − 1)` times both sides, so no division waits on `M`.
        let denominator = 3.0 * 2.0 * rho * root;
        let k = 16.0 * h * m * rho * rho;
        // The fewest nodes whose bound meets the share left by the cusps and by the rule's
        // rounding (`(n + 8) ε` of a value at most `2 h top`) — or a tenth of the share,
        // where rounding takes more (the caller's floor then applies).
        let rounding = (MAX_NODES as f64 + 8.0) * f64::EPSILON * 2.0 * h * top;
        let target = (share - cusp_error - rounding).max(0.1 * share) * denominator;
        // Binary lifting on `m = n − 1`: the largest `m` with `k q^m` above the target.
        let q = inv_rho * inv_rho;
        let mut powers = [q; NODE_BITS];
        for i in 1..NODE_BITS {
            powers[i] = powers[i - 1] * powers[i - 1];
        }
        let (mut m, mut above) = (0, k);
        for i in (0..NODE_BITS).rev() {
            let next = above * powers[i];
            let take = next > target && m + (1 << i) < MAX_NODES;
            above = if take { next } else { above };
            m += usize::from(take) << i;
        }
        if above * q <= target {
            return Plan::Rule {
                n: m + 1,
                bound: above * q / denominator + cusp_error,
            };
        }
        if x > a && x < b {
            return Plan::Cut(x);
        }
        let (end, dir) = if x <= a { (a, 1.0) } else { (b, -1.0) };
        let step = GRADING * norm(x - end, delta);
        if step >= h {
            Plan::Cut(c)
        } else {
            Plan::Cut(end + dir * step)
        }
    }
}

/// How far from an end, in multiples of a root's distance beyond it, an interval is cut.
const GRADING: f64 = 4.0;

/// The most roots a speed has (degree 7: a hodograph of degree 6).
const MAX_ROOTS: usize = 6;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_integrate_polynomials_exactly() {
        for n in 1..=MAX_NODES {
            let r = rule(n);
            // Σ w = 2 and ∫ x^{2k} = 2 / (2k + 1) for 2k ≤ 2n − 1.
            for k in 0..n {
                let exact = 2.0 / (2 * k + 1) as f64;
                let got: f64 = r
                    .nodes
                    .iter()
                    .zip(&r.weights)
                    .map(|(&x, &w)| w * x.powi(2 * k as i32) * if x == 0.0 { 1.0 } else { 2.0 })
                    .sum();
                // A node's rounding moves `x^{2k}` by `2k ε` of itself: the monomial's
                // condition, on top of the sum's.
                let allowed = 3e-14 + 4.0 * (2 * k) as f64 * f64::EPSILON;
                assert!(
                    (got - exact).abs() <= allowed * exact,
                    "n = {n}, x^{}: {got} vs {exact}",
                    2 * k
                );
            }
        }
        assert!((rule(2).nodes[0] - 1.0 / 3f64.sqrt()).abs() <= 2.0 * f64::EPSILON);
    }

    #[test]
    fn roots_of_the_velocity() {
        // x′ = (u − 0.25)(u − 0.75), y′ = 0: real roots at 0.25 and 0.75, ℓ = 1.
        let s = PlanarSpeed::new(&[0.1875, -1.0, 1.0], &[0.0, 0.0, 0.0]).unwrap();
        let mut r = s.roots().to_vec();
        r.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert!((r[0].0 - 0.25).abs() < 1e-15 && (r[1].0 - 0.75).abs() < 1e-15);
        assert!(r.iter().all(|&(_, d)| d < 1e-15) && s.lead == 1.0);
        // Degree 5: roots 0.1, 0.2 ± 0.3i, 0.9 + 0.01i, −2 (product of the factors,
        // expanded exactly in rationals is not needed: the speed agrees).
        let p: [(f64, f64); 5] = [
            (0.1, 0.0),
            (0.2, 0.3),
            (0.2, -0.3),
            (0.9, 0.01),
            (-2.0, 0.0),
        ];
        let mut c = vec![ONE];
        for &(re, im) in &p {
            let mut next = vec![ZERO; c.len() + 1];
            for (i, ci) in c.iter().enumerate() {
                next[i + 1] += ci;
                next[i] -= ci * C64::new(re, im);
            }
            c = next;
        }
        let x: Vec<f64> = c.iter().map(|v| v.re).collect();
        let y: Vec<f64> = c.iter().map(|v| v.im).collect();
        let s = PlanarSpeed::new(&x, &y).unwrap();
        for &(re, im) in &p {
            assert!(
                s.roots()
                    .iter()
                    .any(|&(a, d)| (a - re).abs() < 1e-12 && (d - im.abs()).abs() < 1e-12),
                "{re} + {im}i not in {:?}",
                s.roots()
            );
        }
    }

    #[test]
    fn complex_square_roots() {
        // Squares of known roots, exact in binary: the root comes back exactly (principal
        // branch: real part ≥ 0), on the axes and in every quadrant; and huge or tiny
        // values neither overflow nor lose the small part.
        for (re, im) in [
            (3.0, 4.0),
            (0.5, -0.25),
            (0.0, 2.0),
            (2.0, -3.0),
            (1.5, 0.0),
            (0.75, 1e-8),
        ] {
            let r = C64::new(re, im);
            let got = complex_sqrt(r * r);
            assert!(
                (got - r).norm() <= 4.0 * f64::EPSILON * r.norm(),
                "{r}: {got}"
            );
        }
        assert_eq!(complex_sqrt(C64::new(-9.0, 0.0)), C64::new(0.0, 3.0));
        let big = complex_sqrt(C64::new(-1e308, 1e308));
        let want = C64::new(1e308, 1e308).norm().sqrt();
        assert!(
            big.is_finite() && (big.norm() - want).abs() <= 1e-15 * want,
            "{big}"
        );
        let small = complex_sqrt(C64::new(1e-300, 3e-310));
        assert!(
            (small.im - 1.5e-310 / 1e-150).abs() <= 1e-10 * 1.5e-160,
            "{small}"
        );
    }

    #[test]
    fn quotients_and_moduli_across_the_range() {
        // Exact cases: (3 + 4i) / (1 + 2i) = 2.2 − 0.4i rounds like the closed form;
        // |3 + 4i| = 5 exactly. Then values whose squares overflow or underflow take the
        // scaled path and stay right.
        let q = quotient(C64::new(3.0, 4.0), C64::new(1.0, 2.0));
        assert!(
            (q - C64::new(2.2, -0.4)).norm() <= 2.0 * f64::EPSILON * 2.3,
            "{q}"
        );
        assert_eq!(modulus(C64::new(3.0, 4.0)), 5.0);
        for scale in [1e200, 1e-200, 1e300, 1e-300] {
            let a = C64::new(3.0 * scale, 4.0 * scale);
            assert!((modulus(a) / scale - 5.0).abs() <= 1e-15 * 5.0, "{scale}");
            let q = quotient(a, C64::new(1.0 * scale, 2.0 * scale));
            assert!(
                (q - C64::new(2.2, -0.4)).norm() <= 1e-15 * 2.3,
                "{scale}: {q}"
            );
            let q = quotient(C64::new(3.0, 4.0), C64::new(scale, 0.0));
            assert!(
                ((q * scale) - C64::new(3.0, 4.0)).norm() <= 1e-14 * 5.0,
                "{scale}: {q}"
            );
        }
    }

    fn simpson(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
        let n = 20_000;
        let h = (b - a) / n as f64;
        let mut sum = f(a) + f(b);
        for i in 1..n {
            sum += f(a + h * i as f64) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        sum * h / 3.0
    }

    #[test]
    fn a_linear_velocity_against_its_closed_form() {
        // x′ + i y′ = 3 (u − (0.4 + δ i)): ∫₀¹ 3 √((u − 0.4)² + δ²) in closed form.
        for delta in [0.3, 1e-2, 1e-5, 1e-10, 0.0] {
            let s = PlanarSpeed::new(&[-1.2, 3.0], &[-3.0 * delta, 0.0]).unwrap();
            let g = |u: f64| {
                let v = u - 0.4;
                let tail = if delta > 0.0 {
                    delta * delta * (v / delta).asinh()
                } else {
                    0.0
                };
                1.5 * (v * v.hypot(delta) + tail)
            };
            let exact = g(1.0) - g(0.0);
            for tol in [1e-1, 1e-2, 1e-3, 1e-6, 1e-9, 1e-12, 1e-14] {
                let q = s.length(0.0, 1.0, tol);
                // Below the rounding of the sum (`(n + 8) ε` of the value) no rule can go.
                let floor = (MAX_NODES as f64 + 8.0) * f64::EPSILON * exact;
                assert!(q.error <= tol.max(floor), "δ {delta} tol {tol}: {q:?}");
                assert!(
                    (q.value - exact).abs() <= q.error,
                    "δ {delta} tol {tol}: {} vs {exact} ({q:?})",
                    q.value
                );
            }
        }
    }

    #[test]
    fn bounds_hold_against_a_reference() {
        // |u − x| · √((u − 0.5)² + δ²) style speeds: x′ + i y′ = (u − r₁)(u − r₂).
        for (r1, r2) in [
            ((0.5, 1e-3), (-0.4, 0.7)),
            ((0.5, 1e-14), (2.0, 0.1)),
            ((1.2, 0.05), (0.3, 0.0)),
            ((0.0, 1e-9), (1.0, 1e-6)),
        ] {
            let r1 = C64::new(r1.0, r1.1);
            let r2 = C64::new(r2.0, r2.1);
            let c = [r1 * r2, -(r1 + r2), ONE];
            let x: Vec<f64> = c.iter().map(|v| v.re).collect();
            let y: Vec<f64> = c.iter().map(|v| v.im).collect();
            let s = PlanarSpeed::new(&x, &y).unwrap();
            let f = |u: f64| (C64::new(u, 0.0) - r1).norm() * (C64::new(u, 0.0) - r2).norm();
            // Reference: composite Simpson's rule on 20,000 panels per piece, cut at the
            // roots' real parts and at distances δ, 10δ, 100δ, … from them (so each piece
            // is smooth at its resolution).
            let mut cuts = vec![0.0, 1.0];
            for r in [r1, r2] {
                let mut step = r.im.abs();
                cuts.push(r.re);
                while step > 0.0 && step < 1.0 {
                    cuts.extend([r.re - step, r.re + step]);
                    step *= 10.0;
                }
            }
            cuts.retain(|c| (0.0..=1.0).contains(c));
            cuts.sort_by(f64::total_cmp);
            let reference: f64 = cuts.windows(2).map(|w| simpson(&f, w[0], w[1])).sum();
            for tol in [1e-1, 1e-2, 1e-3, 1e-6, 1e-9, 1e-12] {
                let q = s.length(0.0, 1.0, tol);
                assert!(q.error <= tol, "{r1:?} {r2:?} tol {tol}: {q:?}");
                assert!(
                    (q.value - reference).abs() <= q.error + 1e-13,
                    "{r1:?} {r2:?} tol {tol}: {} vs {reference} ({q:?})",
                    q.value
                );
            }
        }
    }
}
