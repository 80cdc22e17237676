//! Polynomials in Bernstein form over `[0, 1]`: `p(t) = Σ_{i=0}^{n} c_i B_{i,n}(t)`, as
//! slices of coefficients. Products, derivatives, elevation, subdivision and evaluation
//! with a running error bound — what the root finder ([`roots`]) and the analyses
//! built on it (extrema, inflections, curvature, areas, intersections with lines) need.
//!
//! Every operation forms convex combinations or products of binomial ratios that are at
//! most 1, so coefficients never grow by more than the degree (docs/math.md §7).

pub mod roots;

use crate::geom::bernstein;

/// `ln k!` for `k = 0..=n`.
fn ln_factorials(n: usize) -> Vec<f64> {
    let mut out = Vec::with_capacity(n + 1);
    let mut acc = 0.0_f64;
    out.push(0.0);
    for k in 1..=n {
        acc += (k as f64).ln();
        out.push(acc);
    }
    out
}

/// The weights `C(m, i) C(n, j) / C(m + n, i + j)` of the Bernstein product, for every
/// `i ≤ m`, `j ≤ n`: exact binomials while they fit `f64` comfortably (`m + n ≤ 1000`),
/// logarithms of factorials beyond (relative error about `1e−13` there).
struct ProductWeights {
    m: usize,
    n: usize,
    exact: Option<(Vec<f64>, Vec<f64>, Vec<f64>)>,
    ln: Vec<f64>,
}

impl ProductWeights {
    fn new(m: usize, n: usize) -> ProductWeights {
        if m + n <= 1000 {
            let row = |d: usize| {
                (0..=d)
                    .map(|k| bernstein::binomial(d, k))
                    .collect::<Vec<_>>()
            };
            ProductWeights {
                m,
                n,
                exact: Some((row(m), row(n), row(m + n))),
                ln: Vec::new(),
            }
        } else {
            ProductWeights {
                m,
                n,
                exact: None,
                ln: ln_factorials(m + n),
            }
        }
    }

    fn get(&self, i: usize, j: usize) -> f64 {
        match &self.exact {
            Some((a, b, c)) => a[i] * b[j] / c[i + j],
            None => {
                let (m, n, f) = (self.m, self.n, &self.ln);
                let k = i + j;
                let ln = (f[m] - f[i] - f[m - i]) + (f[n] - f[j] - f[n - j])
                    - (f[m + n] - f[k] - f[m + n - k]);
                ln.exp()
            }
        }
    }
}

/// The coefficients of `a · b` (degrees `m`, `n`) at degree `m + n`:
/// `c_k = Σ_{i+j=k} C(m,i) C(n,j) / C(m+n,k) · a_i b_j`.
#[must_use]
pub fn product(a: &[f64], b: &[f64]) -> Vec<f64> {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let (m, n) = (a.len() - 1, b.len() - 1);
    let w = ProductWeights::new(m, n);
    let mut out = vec![0.0; m + n + 1];
    for (i, &ai) in a.iter().enumerate() {
        if ai == 0.0 {
            continue;
        }
        for (j, &bj) in b.iter().enumerate() {
            out[i + j] += w.get(i, j) * ai * bj;
        }
    }
    out
}

/// `a − b` at the higher of their degrees (the lower one elevated).
#[must_use]
pub fn difference(a: &[f64], b: &[f64]) -> Vec<f64> {
    let d = a.len().max(b.len()).saturating_sub(1);
    let (a, b) = (elevate_to(a, d), elevate_to(b, d));
    a.iter().zip(&b).map(|(x, y)| x - y).collect()
}

/// `a + b` at the higher of their degrees.
#[must_use]
pub fn sum(a: &[f64], b: &[f64]) -> Vec<f64> {
    let d = a.len().max(b.len()).saturating_sub(1);
    let (a, b) = (elevate_to(a, d), elevate_to(b, d));
    a.iter().zip(&b).map(|(x, y)| x + y).collect()
}

/// `k · a`.
#[must_use]
pub fn scaled(a: &[f64], k: f64) -> Vec<f64> {
    a.iter().map(|x| x * k).collect()
}

/// The derivative `p′`, degree `n − 1`: `n (c_{i+1} − c_i)` (a constant's is `[0]`).
#[must_use]
pub fn derivative(c: &[f64]) -> Vec<f64> {
    if c.len() <= 1 {
        return vec![0.0];
    }
    let n = (c.len() - 1) as f64;
    c.windows(2).map(|w| n * (w[1] - w[0])).collect()
}

/// The same polynomial at degree `to ≥ n`: `c'_i = (i/(d+1)) c_{i−1} + (1 − i/(d+1)) c_i`,
/// one degree at a time.
#[must_use]
pub fn elevate_to(c: &[f64], to: usize) -> Vec<f64> {
    let mut c = c.to_vec();
    if c.is_empty() {
        return vec![0.0; to + 1];
    }
    while c.len() - 1 < to {
        let n = c.len() - 1;
        let mut next = Vec::with_capacity(n + 2);
        next.push(c[0]);
        for i in 1..=n {
            let r = i as f64 / (n + 1) as f64;
            next.push(r * c[i - 1] + (1.0 - r) * c[i]);
        }
        next.push(c[n]);
        c = next;
    }
    c
}

/// `∫₀¹ p(t) dt = Σ c_i / (n + 1)`.
#[must_use]
pub fn integral(c: &[f64]) -> f64 {
    if c.is_empty() {
        return 0.0;
    }
    c.iter().sum::<f64>() / c.len() as f64
}

/// `p(t)` by de Casteljau, and a bound on its rounding error: `γ_{2n} Σ |c_i| B_i(t)`
/// (`γ_k = kε/(1 − kε)`, the running error of the convex combinations).
#[must_use]
pub fn eval_with_bound(c: &[f64], t: f64) -> (f64, f64) {
    let len = c.len();
    if len == 0 {
        return (0.0, 0.0);
    }
    let n = len - 1;
    let gamma = {
        let k = (2 * n + 2) as f64 * f64::EPSILON * 0.5;
        k / (1.0 - k)
    };
    let s = 1.0 - t;
    let run = |v: &mut [f64], a: &mut [f64]| {
        for r in 1..=n {
            for i in 0..=(n - r) {
                v[i] = s * v[i] + t * v[i + 1];
                a[i] = s * a[i] + t * a[i + 1];
            }
        }
        (v[0], gamma * a[0] + f64::MIN_POSITIVE)
    };
    // Degrees 1–3 written out (the same operations in the same order as `run`); the others
    // in `in_buffer`'s scratch copies.
    let bound = |a: f64| gamma * a + f64::MIN_POSITIVE;
    match *c {
        [c0, c1] => return (s * c0 + t * c1, bound(s * c0.abs() + t * c1.abs())),
        [c0, c1, c2] => {
            let (p0, p1) = (s * c0 + t * c1, s * c1 + t * c2);
            let (a0, a1) = (s * c0.abs() + t * c1.abs(), s * c1.abs() + t * c2.abs());
            return (s * p0 + t * p1, bound(s * a0 + t * a1));
        }
        [c0, c1, c2, c3] => {
            let (p0, p1, p2) = (s * c0 + t * c1, s * c1 + t * c2, s * c2 + t * c3);
            let (p0, p1) = (s * p0 + t * p1, s * p1 + t * p2);
            let (a0, a1, a2) = (
                s * c0.abs() + t * c1.abs(),
                s * c1.abs() + t * c2.abs(),
                s * c2.abs() + t * c3.abs(),
            );
            let (a0, a1) = (s * a0 + t * a1, s * a1 + t * a2);
            return (s * p0 + t * p1, bound(s * a0 + t * a1));
        }
        _ => {}
    }
    in_buffer(c, |v| {
        in_buffer(c, |a| {
            for x in a.iter_mut() {
                *x = x.abs();
            }
            run(v, a)
        })
    })
}

/// Coefficients evaluated on the stack (more go to the heap).
const STACK: usize = 32;

/// `run` on two zeroed scratch rows of `len` numbers: on the stack up to degree 7, on the
/// heap beyond.
pub(crate) fn in_two_buffers<R>(len: usize, run: impl FnOnce(&mut [f64], &mut [f64]) -> R) -> R {
    if len <= 8 {
        let (mut a, mut b) = ([0.0; 8], [0.0; 8]);
        run(&mut a[..len], &mut b[..len])
    } else {
        run(&mut vec![0.0; len], &mut vec![0.0; len])
    }
}

/// `run` on a scratch copy of `c`: for degrees up to 7 a buffer of that size (clearing 32
/// slots per call was a tenth of a degree-7 intersection's time), up to [`STACK`] on the
/// stack, beyond it on the heap.
fn in_buffer<R>(c: &[f64], run: impl FnOnce(&mut [f64]) -> R) -> R {
    let len = c.len();
    if len <= 8 {
        let mut v = [0.0; 8];
        v[..len].copy_from_slice(c);
        run(&mut v[..len])
    } else if len <= STACK {
        let mut v = [0.0; STACK];
        v[..len].copy_from_slice(c);
        run(&mut v[..len])
    } else {
        run(&mut c.to_vec())
    }
}

/// `p″(t)`: `n (n − 1) Σ Δ²c_i B_{i,n−2}(t)`, the second differences on the stack up to
/// degree 33.
#[must_use]
pub fn eval_second_derivative(c: &[f64], t: f64) -> f64 {
    let len = c.len();
    if len < 3 {
        return 0.0;
    }
    let n = (len - 1) as f64;
    let run = |d: &mut [f64]| {
        for (i, slot) in d.iter_mut().enumerate() {
            *slot = c[i + 2] - 2.0 * c[i + 1] + c[i];
        }
        n * (n - 1.0) * eval(d, t)
    };
    if len - 2 <= STACK {
        let mut d = [0.0; STACK];
        run(&mut d[..len - 2])
    } else {
        run(&mut vec![0.0; len - 2])
    }
}

/// `p(t)` by de Casteljau (written out for degrees up to 3).
#[must_use]
pub fn eval(c: &[f64], t: f64) -> f64 {
    eval_split(c, t, 1.0 - t)
}

/// `p(t)` by de Casteljau with `s = 1 − t` given (for `t` within an ulp of 1, where
/// `1 − t` computed in floating point would be 0 or lose its digits).
#[must_use]
pub fn eval_split(c: &[f64], t: f64, s: f64) -> f64 {
    match *c {
        [] => 0.0,
        [a] => a,
        [a, b] => s * a + t * b,
        [a, b, d] => {
            let (p, q) = (s * a + t * b, s * b + t * d);
            s * p + t * q
        }
        [a, b, d, e] => {
            let (p, q, r) = (s * a + t * b, s * b + t * d, s * d + t * e);
            let (p, q) = (s * p + t * q, s * q + t * r);
            s * p + t * q
        }
        _ => {
            let n = c.len() - 1;
            let run = |v: &mut [f64]| {
                for r in 1..=n {
                    for i in 0..=(n - r) {
                        v[i] = s * v[i] + t * v[i + 1];
                    }
                }
                v[0]
            };
            in_buffer(c, run)
        }
    }
}

/// `p(t)` and `p′(t)` from one de Casteljau triangle: its last two values `a`, `b` give
/// `p = (1 − t) a + t b` and `p′ = n (b − a)`.
#[must_use]
pub fn eval_with_derivative(c: &[f64], t: f64) -> (f64, f64) {
    let len = c.len();
    let s = 1.0 - t;
    match *c {
        [] => return (0.0, 0.0),
        [a] => return (a, 0.0),
        [a, b] => return (s * a + t * b, b - a),
        [a, b, d] => {
            let (p, q) = (s * a + t * b, s * b + t * d);
            return (s * p + t * q, 2.0 * (q - p));
        }
        [a, b, d, e] => {
            let (p, q, r) = (s * a + t * b, s * b + t * d, s * d + t * e);
            let (p, q) = (s * p + t * q, s * q + t * r);
            return (s * p + t * q, 3.0 * (q - p));
        }
        _ => {}
    }
    let n = len - 1;
    let run = |v: &mut [f64]| {
        for r in 1..n {
            for i in 0..=(n - r) {
                v[i] = s * v[i] + t * v[i + 1];
            }
        }
        let (a, b) = (v[0], v[1]);
        (s * a + t * b, n as f64 * (b - a))
    };
    in_buffer(c, run)
}

/// Two polynomials of one degree `n = cx.len() − 1 ≤ 7` (a planar curve's `x` and `y`)
/// side by side, and `levels` levels of their de Casteljau triangle at `t` (`s = 1 − t`):
/// the same operations on each as [`eval`]'s triangle, with the two coordinates' chains of
/// dependences interleaved.
#[inline]
fn triangle2(cx: &[f64], cy: &[f64], t: f64, s: f64, levels: usize) -> [[f64; 2]; 8] {
    let n = cx.len() - 1;
    let mut v = [[0.0_f64; 2]; 8];
    for ((vi, &x), &y) in v.iter_mut().zip(cx).zip(cy) {
        *vi = [x, y];
    }
    for r in 1..=levels {
        for i in 0..=(n - r).min(6) {
            let next = v[i + 1];
            for (d, nd) in v[i].iter_mut().zip(next) {
                *d = s * *d + t * nd;
            }
        }
    }
    v
}

/// [`eval`] of two polynomials of one degree (a planar curve's `x` and `y`) in one
/// triangle (`triangle2` for degrees 4 to 7): the same operations on each, so the same
/// values.
#[must_use]
#[inline]
pub fn eval2(cx: &[f64], cy: &[f64], t: f64) -> (f64, f64) {
    let len = cx.len();
    if len != cy.len() || !(5..=8).contains(&len) {
        return (eval(cx, t), eval(cy, t));
    }
    let v = triangle2(cx, cy, t, 1.0 - t, len - 1);
    (v[0][0], v[0][1])
}

/// [`eval_with_derivative`] of two polynomials of one degree (a planar curve's `x` and
/// `y`) in one triangle (written out for cubics, `triangle2` for degrees 4 to 7): the
/// same operations on each, so the same values.
#[must_use]
#[inline]
pub fn eval_with_derivative2(cx: &[f64], cy: &[f64], t: f64) -> ((f64, f64), (f64, f64)) {
    let len = cx.len();
    let s = 1.0 - t;
    if let ([a0, a1, a2, a3], [b0, b1, b2, b3]) = (cx, cy) {
        let (p, q, r) = (s * a0 + t * a1, s * a1 + t * a2, s * a2 + t * a3);
        let (e, f, g) = (s * b0 + t * b1, s * b1 + t * b2, s * b2 + t * b3);
        let (p, q) = (s * p + t * q, s * q + t * r);
        let (e, f) = (s * e + t * f, s * f + t * g);
        return (
            (s * p + t * q, 3.0 * (q - p)),
            (s * e + t * f, 3.0 * (f - e)),
        );
    }
    if len != cy.len() || !(5..=8).contains(&len) {
        return (eval_with_derivative(cx, t), eval_with_derivative(cy, t));
    }
    let n = len - 1;
    // All but the last level; its two points give the value and the derivative.
    let v = triangle2(cx, cy, t, s, n - 1);
    let nf = n as f64;
    let [a, b] = [v[0], v[1]];
    (
        (s * a[0] + t * b[0], nf * (b[0] - a[0])),
        (s * a[1] + t * b[1], nf * (b[1] - a[1])),
    )
}

/// The coefficients of `p` on `[0, t]` and on `[t, 1]`, each reparametrised to `[0, 1]`.
#[must_use]
pub fn split(c: &[f64], t: f64) -> (Vec<f64>, Vec<f64>) {
    let (mut left, mut right) = (vec![0.0; c.len()], vec![0.0; c.len()]);
    split_into(c, t, &mut left, &mut right);
    (left, right)
}

/// The real roots of the quadratic whose Bernstein coefficients are `c0, c1, c2` (power
/// form `α u² + β u + γ`: `α = c0 − 2c1 + c2`, `β = 2 (c1 − c0)`, `γ = c0`), by the quadratic
/// formula without cancellation (`q = −(β + sgn β √D)/2`, roots `q/α` and `γ/q`), unsorted
/// and unfiltered; the one root `−γ/β` when `α = 0`. With them, the vertex `−β/(2α)` where
/// the discriminant is within its rounding of 0 (`|D| ≤ 16 ε (β² + 4|αγ|)`): two roots
/// that rounding may merge, or lose, lie within rounding of it.
#[must_use]
pub fn quadratic_roots(c0: f64, c1: f64, c2: f64) -> ([f64; 2], usize, Option<f64>) {
    let (a, b, c) = (c0 - 2.0 * c1 + c2, 2.0 * (c1 - c0), c0);
    if a == 0.0 {
        return if b == 0.0 {
            ([0.0; 2], 0, None)
        } else {
            ([-c / b, 0.0], 1, None)
        };
    }
    let disc = b * b - 4.0 * a * c;
    let vertex =
        (disc.abs() <= 16.0 * f64::EPSILON * (b * b + 4.0 * (a * c).abs())).then(|| -0.5 * b / a);
    // A negative or NaN discriminant: no real root.
    if disc.is_nan() || disc < 0.0 {
        return ([0.0; 2], 0, vertex);
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    if q == 0.0 {
        return ([q / a, 0.0], 1, vertex);
    }
    ([q / a, c / q], 2, vertex)
}

/// [`split`] into `left` and `right` (each as long as `c`), without allocating: the same
/// arithmetic, so the same coefficients to the bit.
pub fn split_into(c: &[f64], t: f64, left: &mut [f64], right: &mut [f64]) {
    let len = c.len();
    if len == 0 {
        return;
    }
    let n = len - 1;
    let s = 1.0 - t;
    // `right` is the working row: level `r` lives in `right[..=n − r]`, and the last entry
    // of each level is `right[n − r]`, the one the right half keeps.
    right.copy_from_slice(c);
    left[0] = right[0];
    for (r, slot) in left.iter_mut().enumerate().skip(1) {
        for i in 0..=(n - r) {
            right[i] = s * right[i] + t * right[i + 1];
        }
        *slot = right[0];
    }
}

/// [`restrict`] into `out` (as long as `c`): scratch rows on the stack up to degree 7.
pub fn restrict_into(c: &[f64], a: f64, b: f64, out: &mut [f64]) {
    in_two_buffers(c.len(), |scratch, right| {
        if a > 0.0 {
            split_into(c, a, scratch, right);
        } else {
            right.copy_from_slice(c);
        }
        if b >= 1.0 {
            out.copy_from_slice(right);
            return;
        }
        let u = (b - a) / (1.0 - a);
        split_into(right, u.clamp(0.0, 1.0), out, scratch);
    });
}

/// The coefficients of `p` on `[a, b] ⊆ [0, 1]`, reparametrised to `[0, 1]`.
#[must_use]
pub fn restrict(c: &[f64], a: f64, b: f64) -> Vec<f64> {
    let mut out = vec![0.0; c.len()];
    restrict_into(c, a, b, &mut out);
    out
}

/// Deprecated: `splinescope_core::geom::bernstein::binomial`.
#[deprecated(note = "use splinescope_core::geom::bernstein::binomial")]
#[must_use]
pub fn binomial(n: usize, k: usize) -> f64 {
    bernstein::binomial(n, k)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn power_eval(c: &[f64], t: f64) -> f64 {
        let n = c.len() - 1;
        c.iter()
            .enumerate()
            .map(|(i, ci)| {
                bernstein::binomial(n, i) * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32) * ci
            })
            .sum()
    }

    #[test]
    fn arithmetic_keeps_the_polynomials() {
        let a = [1.0, -2.0, 0.5, 3.0];
        let b = [0.25, 4.0, -1.0];
        let p = product(&a, &b);
        let d = derivative(&a);
        let e = elevate_to(&b, 7);
        let (l, r) = split(&a, 0.3);
        let sub = restrict(&a, 0.2, 0.7);
        for k in 0..=20 {
            let t = f64::from(k) / 20.0;
            assert!((power_eval(&p, t) - power_eval(&a, t) * power_eval(&b, t)).abs() < 1e-13);
            assert!((power_eval(&e, t) - power_eval(&b, t)).abs() < 1e-13);
            let h = 1e-6;
            let fd = (power_eval(&a, (t + h).min(1.0)) - power_eval(&a, (t - h).max(0.0)))
                / ((t + h).min(1.0) - (t - h).max(0.0));
            assert!((power_eval(&d, t) - fd).abs() < 1e-4, "{t}");
            assert!((power_eval(&l, t) - power_eval(&a, 0.3 * t)).abs() < 1e-13);
            assert!((power_eval(&r, t) - power_eval(&a, 0.3 + 0.7 * t)).abs() < 1e-13);
            assert!((power_eval(&sub, t) - power_eval(&a, 0.2 + 0.5 * t)).abs() < 1e-13);
            let (v, bound) = eval_with_bound(&a, t);
            assert!((v - power_eval(&a, t)).abs() <= bound + 1e-15);
        }
        // ∫₀¹ (1 − 2t + 0.5·… ) against Simpson on the power form.
        let exact: f64 = (0..=2000)
            .map(|k| {
                let t = f64::from(k) / 2000.0;
                let w = if k == 0 || k == 2000 {
                    1.0
                } else if k % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                w * power_eval(&a, t)
            })
            .sum::<f64>()
            / 6000.0;
        assert!((integral(&a) - exact).abs() < 1e-12);
    }

    #[test]
    fn low_degrees_written_out_evaluate_as_the_loop() {
        // The loop of `eval_with_bound`, restated: degrees 1–3 must give the same bits.
        fn looped(c: &[f64], t: f64) -> (f64, f64) {
            let n = c.len() - 1;
            let k = (2 * n + 2) as f64 * f64::EPSILON * 0.5;
            let gamma = k / (1.0 - k);
            let s = 1.0 - t;
            let (mut v, mut a) = (c.to_vec(), c.iter().map(|x| x.abs()).collect::<Vec<_>>());
            for r in 1..=n {
                for i in 0..=(n - r) {
                    v[i] = s * v[i] + t * v[i + 1];
                    a[i] = s * a[i] + t * a[i + 1];
                }
            }
            (v[0], gamma * a[0] + f64::MIN_POSITIVE)
        }
        for c in [
            vec![0.3, -1.7],
            vec![1e-300, -3.0, 2.5],
            vec![1.0, -2.0, 0.5, 3.0],
            vec![-1e10, 1.0, 1e-10, 7.0],
        ] {
            for k in 0..=64 {
                let t = f64::from(k) / 64.0 + if k % 2 == 1 { 1e-3 } else { 0.0 };
                let (v, b) = eval_with_bound(&c, t);
                let (w, d) = looped(&c, t);
                assert_eq!(
                    (v.to_bits(), b.to_bits()),
                    (w.to_bits(), d.to_bits()),
                    "{c:?} at {t}"
                );
            }
        }
    }

    #[test]
    fn quadratic_roots_in_closed_form() {
        // Bernstein coefficients of a power-form quadratic a t² + b t + c.
        let bern = |a: f64, b: f64, c: f64| (c, c + 0.5 * b, a + b + c);
        let sorted = |(r, n, v): ([f64; 2], usize, Option<f64>)| {
            let mut r = r[..n].to_vec();
            r.sort_by(f64::total_cmp);
            (r, v)
        };
        // (t − ¼)(t − ¾): exact roots, no vertex.
        let (c0, c1, c2) = bern(1.0, -1.0, 0.1875);
        assert_eq!(
            sorted(quadratic_roots(c0, c1, c2)),
            (vec![0.25, 0.75], None)
        );
        // A root at 0 (γ = 0) and one at 0.5: t² − t/2.
        let (c0, c1, c2) = bern(1.0, -0.5, 0.0);
        assert_eq!(sorted(quadratic_roots(c0, c1, c2)), (vec![0.0, 0.5], None));
        // Linear (α = 0): 2t − 1.
        let (c0, c1, c2) = bern(0.0, 2.0, -1.0);
        assert_eq!(sorted(quadratic_roots(c0, c1, c2)), (vec![0.5], None));
        // A double root at ⅜: the roots and the vertex there.
        let (c0, c1, c2) = bern(1.0, -0.75, 0.140_625);
        let (r, v) = sorted(quadratic_roots(c0, c1, c2));
        assert_eq!(v, Some(0.375));
        assert!(r.iter().all(|x| (x - 0.375).abs() < 1e-15), "{r:?}");
        // No real root, far from a double one: nothing. A constant: nothing.
        assert_eq!(sorted(quadratic_roots(1.0, 0.0, 1.0)), (vec![], None));
        assert_eq!(sorted(quadratic_roots(2.0, 2.0, 2.0)), (vec![], None));
    }

    /// The de Casteljau split as first written (allocating, the left half pushed and the
    /// right half filled from the end): `split` and `split_into` must give its bits.
    fn split_as_written(c: &[f64], t: f64) -> (Vec<f64>, Vec<f64>) {
        if c.is_empty() {
            return (Vec::new(), Vec::new());
        }
        let n = c.len() - 1;
        let mut work = c.to_vec();
        let mut left = vec![work[0]];
        let mut right = vec![0.0; n + 1];
        right[n] = work[n];
        let s = 1.0 - t;
        for r in 1..=n {
            for i in 0..=(n - r) {
                work[i] = s * work[i] + t * work[i + 1];
            }
            left.push(work[0]);
            right[n - r] = work[n - r];
        }
        (left, right)
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    #[test]
    fn restricting_in_place_gives_the_same_coefficients() {
        // `restrict` as first written: the right half at `a`, then its left half.
        let restrict_as_written = |c: &[f64], a: f64, b: f64| {
            let right = if a > 0.0 {
                split_as_written(c, a).1
            } else {
                c.to_vec()
            };
            if b >= 1.0 {
                return right;
            }
            split_as_written(&right, ((b - a) / (1.0 - a)).clamp(0.0, 1.0)).0
        };
        for len in 1..=12 {
            let c: Vec<f64> = (0..len).map(|i| (i as f64 * 0.37).sin() * 3.0).collect();
            for (a, b) in [
                (0.0, 1.0),
                (0.0, 0.3),
                (0.2, 1.0),
                (0.25, 0.75),
                (0.6, 0.61),
            ] {
                let want = bits(&restrict_as_written(&c, a, b));
                let mut out = vec![f64::NAN; len];
                restrict_into(&c, a, b, &mut out);
                assert_eq!(bits(&out), want, "{c:?} on [{a}, {b}]");
                assert_eq!(bits(&restrict(&c, a, b)), want, "{c:?} on [{a}, {b}]");
            }
        }
    }

    #[test]
    fn splitting_in_place_gives_the_same_halves() {
        let mut rng = crate::rng::Rng::new(3);
        for len in 0..=12 {
            for _ in 0..50 {
                let c: Vec<f64> = (0..len).map(|_| rng.range(-2.0, 2.0)).collect();
                let t = rng.unit();
                let (l, r) = split_as_written(&c, t);
                let (mut l2, mut r2) = (vec![f64::NAN; len], vec![f64::NAN; len]);
                split_into(&c, t, &mut l2, &mut r2);
                assert_eq!((bits(&l), bits(&r)), (bits(&l2), bits(&r2)), "{c:?} at {t}");
                let (l3, r3) = split(&c, t);
                assert_eq!((bits(&l), bits(&r)), (bits(&l3), bits(&r3)), "{c:?} at {t}");
            }
        }
    }

    #[test]
    fn products_of_high_degree_use_logarithms_and_agree() {
        // (1 − t)^600 · t^500 ·… against the exact weight: a product of two Bernstein
        // basis functions is a single scaled basis function.
        let (m, n) = (600, 500);
        let mut a = vec![0.0; m + 1];
        let mut b = vec![0.0; n + 1];
        a[200] = 1.0;
        b[300] = 1.0;
        let p = product(&a, &b);
        let want = (ln_factorials(m + n), 500);
        let f = &want.0;
        let ln = (f[m] - f[200] - f[m - 200]) + (f[n] - f[300] - f[n - 300])
            - (f[m + n] - f[500] - f[m + n - 500]);
        assert!((p[want.1] - ln.exp()).abs() <= 1e-12 * ln.exp());
        assert_eq!(p.iter().filter(|v| **v != 0.0).count(), 1);
    }
}
