//! Every root in `[0, 1]` of a polynomial in Bernstein form — the engine under extrema,
//! inflections, curvature extrema and line intersections, for any degree.
//!
//! **Isolation** by the variation-diminishing property: on an interval whose Bernstein
//! coefficients all exceed the noise `η` in absolute value with one sign, there is no
//! root; with definite end values of opposite signs and one sign change among coefficients
//! that are all outside the noise band, exactly one. Otherwise the interval is split (at a
//! point where `|p|` is above its evaluation error, so that every interval end has a
//! certain sign) and each half examined.
//!
//! **Polish**: a simple root is refined by Newton's method kept inside its bracket
//! (bisection when a step leaves it) on the original coefficients, until the bracket is two
//! floating-point numbers wide or `|p(t)|` is within its evaluation error — from the
//! quadratic formula's root for a quadratic (often within that error already), else from
//! regula falsi on the bracket's ends.
//!
//! **Clusters and multiple roots**: an interval on which `p` is zero to within `η` (its
//! coefficients all in the noise band) holds roots `p` cannot separate in `f64` — a double
//! root, or roots closer than the precision allows. Its multiplicity `m` is the order of
//! the first derivative that is definitely nonzero there; the root reported is the root of
//! `p^{(m−1)}` (simple, so found to full precision), once, with `m`. So a polynomial that
//! touches zero is never lost (a double root has no sign change).
//!
//! **Error bound**: each root carries `error`, a bound on the distance to a root of the
//! exact polynomial: for a simple root the bracket, or `2 (|p̃(t)| + ε_p) / |p′(t)|` with
//! `ε_p` the running error bound of de Casteljau at `t` once `|p̃(t)| ≤ ε_p`; for a
//! cluster, the half-width of its interval.
//! Roots exactly at 0 or 1 (a zero end coefficient) are exact, with their multiplicity.

use crate::poly;

/// One root.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Root {
    /// Where, in `[0, 1]`.
    pub t: f64,
    /// How many roots of `p` (counted with multiplicity) it stands for: 1 for a simple
    /// root, 2 for a double root or a cluster of two, …
    pub multiplicity: usize,
    /// A bound on the distance from `t` to the exact root(s).
    pub error: f64,
}

/// The roots of a polynomial.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Roots {
    /// The roots in `[0, 1]`, in increasing order.
    pub roots: Vec<Root>,
    /// Whether the polynomial is identically zero (every coefficient 0): then every `t` is
    /// a root and `roots` is empty.
    pub identically_zero: bool,
}

/// How deep the isolation may split: intervals narrower than `2⁻⁵⁰` are not split.
const MAX_DEPTH: u32 = 200;
const MIN_WIDTH: f64 = 1.0 / (1u64 << 50) as f64;

/// The roots in `[0, 1]` of `p(t) = Σ c_i B_{i,n}(t)`, its coefficients taken as exact.
#[must_use]
pub fn bernstein_roots(c: &[f64]) -> Roots {
    bernstein_roots_with_noise(c, 0.0)
}

/// The roots in `[0, 1]` of `p(t) = Σ c_i B_{i,n}(t)` whose coefficients carry an absolute
/// error up to `noise` (a polynomial computed from others: a difference of products):
/// the noise band is at least `noise`, and a polynomial whose coefficients are all within
/// it is identically zero as far as `f64` can tell (a circle's curvature slope, a line's
/// `C′ × C″`).
#[must_use]
pub fn bernstein_roots_with_noise(c: &[f64], noise: f64) -> Roots {
    let scale = c.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if c.is_empty() || scale <= noise {
        return Roots {
            roots: Vec::new(),
            identically_zero: true,
        };
    }
    if !scale.is_finite() {
        return Roots::default();
    }
    let mut out = Vec::new();
    // Exact zeros at the ends: roots at 0 and 1, divided out.
    let n = c.len() - 1;
    let lead = c.iter().take_while(|v| **v == 0.0).count();
    let trail = c.iter().rev().take_while(|v| **v == 0.0).count();
    if lead > 0 {
        out.push(Root {
            t: 0.0,
            multiplicity: lead,
            error: 0.0,
        });
    }
    if trail > 0 {
        out.push(Root {
            t: 1.0,
            multiplicity: trail,
            error: 0.0,
        });
    }
    let deflated;
    let inner: &[f64] = if lead == 0 && trail == 0 {
        c
    } else {
        deflated = deflate(c, lead, trail);
        &deflated
    };
    if inner.len() >= 2 {
        let mut finder = Finder::new(inner);
        finder.eta = finder.eta.max(noise);
        finder.isolate(inner, 0.0, 1.0, 0, &mut out);
    }
    let _ = n;
    out.sort_by(|a, b| a.t.total_cmp(&b.t));
    Roots {
        roots: merge(out),
        identically_zero: false,
    }
}

/// `p / (t^lead (1 − t)^trail)` for exact zero coefficients at the ends:
/// `q_j = c_{j+lead} C(n, j+lead) / C(n − lead − trail, j)`.
fn deflate(c: &[f64], lead: usize, trail: usize) -> Vec<f64> {
    if lead == 0 && trail == 0 {
        return c.to_vec();
    }
    let n = c.len() - 1;
    if lead + trail > n {
        return Vec::new();
    }
    let m = n - lead - trail;
    // The ratio of binomials, by logarithms of factorials when they are large.
    let ratio = |j: usize| -> f64 {
        let mut r = 1.0_f64;
        // C(n, j+lead) / C(m, j) = [n! / ((j+lead)! (n−j−lead)!)] · [j! (m−j)! / m!]
        // computed as a product of `lead + trail` factors.
        // n!/m! / ((j+1)…(j+lead)) / ((m−j+1)…(n−j−lead))
        for k in 0..(lead + trail) {
            r *= (n - k) as f64;
        }
        for k in 1..=lead {
            r /= (j + k) as f64;
        }
        for k in 1..=trail {
            r /= (m - j + k) as f64;
        }
        r
    };
    (0..=m).map(|j| c[j + lead] * ratio(j)).collect()
}

/// Roots from neighbouring intervals that are the same root (their error intervals meet):
/// kept once, the larger multiplicity kept.
fn merge(sorted: Vec<Root>) -> Vec<Root> {
    let mut out: Vec<Root> = Vec::with_capacity(sorted.len());
    for r in sorted {
        match out.last_mut() {
            Some(last) if r.t - last.t <= r.error + last.error && last.multiplicity > 1 => {
                if r.multiplicity > last.multiplicity {
                    *last = r;
                }
            }
            _ => out.push(r),
        }
    }
    out
}

/// For a polynomial of degree 2 (`c` its three Bernstein coefficients), its real root
/// inside `(a, b)` ([`poly::quadratic_roots`]); `None` for other degrees or where none lies
/// inside. Only a starting point: the polish checks it.
fn quadratic_root_in(c: &[f64], a: f64, b: f64) -> Option<f64> {
    let &[c0, c1, c2] = c else {
        return None;
    };
    let (roots, count, _) = poly::quadratic_roots(c0, c1, c2);
    roots[..count].iter().copied().find(|t| *t > a && *t < b)
}

/// The isolation and polish of one polynomial.
struct Finder<'a> {
    c: &'a [f64],
    /// `p′`, for Newton steps.
    d: Vec<f64>,
    /// The noise: coefficients of the restricted polynomial within `η` of zero are not
    /// known to have a sign.
    eta: f64,
}

impl<'a> Finder<'a> {
    fn new(c: &'a [f64]) -> Finder<'a> {
        let n = c.len() - 1;
        let scale = c.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        Finder {
            c,
            d: poly::derivative(c),
            eta: 8.0 * (n + 1) as f64 * f64::EPSILON * scale,
        }
    }

    fn isolate(&self, lc: &[f64], a: f64, b: f64, depth: u32, out: &mut Vec<Root>) {
        let eta = self.eta;
        if lc.iter().all(|v| *v > eta) || lc.iter().all(|v| *v < -eta) {
            return;
        }
        let n = lc.len() - 1;
        let (first, last) = (lc[0], lc[n]);
        let flat = lc.iter().all(|v| v.abs() <= eta);
        if !flat {
            let clear = lc[1..n].iter().all(|v| v.abs() > eta);
            let changes = lc
                .windows(2)
                .filter(|w| (w[0] < 0.0) != (w[1] < 0.0))
                .count();
            if clear && changes == 1 && first != 0.0 && last != 0.0 && (first < 0.0) != (last < 0.0)
            {
                out.push(self.polish(a, b, first < 0.0));
                return;
            }
        }
        if flat || b - a <= MIN_WIDTH || depth >= MAX_DEPTH {
            if let Some(r) = self.cluster(a, b, flat, first, last) {
                out.push(r);
            }
            return;
        }
        // Split where |p| is above its evaluation error, so that both halves have ends of
        // certain sign; a cluster spread over the whole interval has no such point.
        let Some(u) = self.split_point(a, b) else {
            if let Some(r) = self.cluster(a, b, true, first, last) {
                out.push(r);
            }
            return;
        };
        let m = a + u * (b - a);
        poly::in_two_buffers(lc.len(), |left, right| {
            poly::split_into(lc, u, left, right);
            self.isolate(left, a, m, depth + 1, out);
            self.isolate(right, m, b, depth + 1, out);
        });
    }

    /// A split fraction of `[a, b]` at which `|p|` exceeds the noise `η` (and so its
    /// evaluation error): both halves then start and end with a value of certain sign, and
    /// a region where `p` is within its noise of zero is never cut into pieces whose
    /// rounding would look like separate roots.
    fn split_point(&self, a: f64, b: f64) -> Option<f64> {
        for u in [
            0.5,
            0.5 + 1.0 / 7.0,
            0.5 - 1.0 / 11.0,
            0.5 + 3.0 / 13.0,
            0.25,
            0.75,
            0.125,
            0.875,
        ] {
            let t = a + u * (b - a);
            if t <= a || t >= b {
                continue;
            }
            let (v, bound) = poly::eval_with_bound(self.c, t);
            if v.abs() > bound.max(self.eta) {
                return Some(u);
            }
        }
        None
    }

    /// The one root in `[a, b]`, where `p(a) < 0` when `negative_at_a` and `p(b)` has the
    /// other sign: Newton's method kept inside the bracket.
    fn polish(&self, mut a: f64, mut b: f64, negative_at_a: bool) -> Root {
        // A quadratic's root in closed form as the start (usually within the evaluation's
        // rounding already), else regula falsi from the end values.
        let mut t = match quadratic_root_in(self.c, a, b) {
            Some(t) => t,
            None => {
                let (fa, _) = poly::eval_with_bound(self.c, a);
                let (fb, _) = poly::eval_with_bound(self.c, b);
                if fa != fb {
                    a - fa * (b - a) / (fb - fa)
                } else {
                    0.5 * (a + b)
                }
            }
        };
        if !(t > a && t < b) {
            t = 0.5 * (a + b);
        }
        let mut error = b - a;
        for _ in 0..200 {
            let (v, bound) = poly::eval_with_bound(self.c, t);
            let slope = poly::eval(&self.d, t);
            if v.abs() <= bound {
                // |p(t)| is within its rounding: the exact root lies within
                // (|p̃(t)| + bound) / |p′| of t (and inside the bracket).
                error = (2.0 * (v.abs() + bound) / slope.abs())
                    .min(b - a)
                    .max(ulp(t));
                break;
            }
            if (v < 0.0) == negative_at_a {
                a = t;
            } else {
                b = t;
            }
            let mid = 0.5 * (a + b);
            if mid <= a || mid >= b {
                error = (b - a).max(ulp(t));
                break;
            }
            let newton = t - v / slope;
            t = if newton > a && newton < b && slope != 0.0 {
                newton
            } else {
                mid
            };
            error = b - a;
        }
        Root {
            t,
            multiplicity: 1,
            error,
        }
    }

    /// The roots in `[a, b]` that `p` cannot separate: their multiplicity is the order of
    /// the first derivative definitely nonzero on the interval; reported at the root of
    /// the derivative one order lower. `None` when `p` does not come within its noise of
    /// zero there.
    fn cluster(&self, a: f64, b: f64, flat: bool, first: f64, last: f64) -> Option<Root> {
        if !flat {
            // Not flat but too narrow to split: a sign change is one root, else none.
            if first != 0.0 && last != 0.0 && (first < 0.0) != (last < 0.0) {
                return Some(self.polish(a, b, first < 0.0));
            }
            return None;
        }
        let mut derivative = self.c.to_vec();
        for m in 1..self.c.len() {
            let lower = derivative;
            derivative = poly::derivative(&lower);
            let scale = derivative.iter().fold(0.0_f64, |x, v| x.max(v.abs()));
            let n = derivative.len() as f64;
            let eta = 8.0 * (n + 1.0) * f64::EPSILON * scale;
            let local = poly::restrict(&derivative, a, b);
            let definite = local.iter().all(|v| *v > eta) || local.iter().all(|v| *v < -eta);
            if definite {
                // p^{(m−1)} is monotone here: its root (if it changes sign) is the place.
                let (fa, _) = poly::eval_with_bound(&lower, a);
                let (fb, _) = poly::eval_with_bound(&lower, b);
                let t = if fa != 0.0 && fb != 0.0 && (fa < 0.0) != (fb < 0.0) {
                    Finder {
                        c: &lower,
                        d: derivative.clone(),
                        eta,
                    }
                    .polish(a, b, fa < 0.0)
                    .t
                } else if fa.abs() < fb.abs() {
                    a
                } else {
                    b
                };
                return Some(Root {
                    t,
                    multiplicity: m,
                    error: (0.5 * (b - a)).max(ulp(t)),
                });
            }
        }
        Some(Root {
            t: 0.5 * (a + b),
            multiplicity: self.c.len() - 1,
            error: 0.5 * (b - a),
        })
    }
}

/// The spacing of `f64` at `t` (for `t` in `[0, 1]`).
fn ulp(t: f64) -> f64 {
    let t = t.abs().max(f64::MIN_POSITIVE);
    f64::from_bits(t.to_bits() + 1) - t
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Bernstein coefficients of `Π (t − r_i)`, by multiplying linear factors.
    fn with_roots(roots: &[f64]) -> Vec<f64> {
        roots
            .iter()
            .fold(vec![1.0], |acc, r| poly::product(&acc, &[-r, 1.0 - r]))
    }

    fn ts(r: &Roots) -> Vec<(f64, usize)> {
        r.roots.iter().map(|x| (x.t, x.multiplicity)).collect()
    }

    #[test]
    fn simple_roots_to_full_precision() {
        let want = [0.1, 0.25, 0.5, 0.73, 0.9];
        let r = bernstein_roots(&with_roots(&want));
        assert_eq!(r.roots.len(), 5, "{:?}", ts(&r));
        for (root, w) in r.roots.iter().zip(want) {
            assert!((root.t - w).abs() <= 4e-16, "{} vs {w}", root.t);
            assert_eq!(root.multiplicity, 1);
            assert!((root.t - w).abs() <= root.error.max(4e-16));
        }
    }

    #[test]
    fn roots_at_the_ends_and_outside() {
        let r = bernstein_roots(&with_roots(&[0.0, 0.0, 0.4, 1.0, 1.7, -0.3]));
        assert_eq!(ts(&r)[0], (0.0, 2));
        assert_eq!(r.roots.len(), 3, "{:?}", ts(&r));
        assert!((r.roots[1].t - 0.4).abs() < 1e-15);
        assert_eq!(ts(&r)[2], (1.0, 1));
        assert!(bernstein_roots(&[0.0, 0.0]).identically_zero);
        assert!(bernstein_roots(&[1.0, 2.0, 0.5]).roots.is_empty());
    }

    #[test]
    fn double_and_triple_roots_once_with_multiplicity() {
        let r = bernstein_roots(&with_roots(&[0.3, 0.3, 0.8]));
        assert_eq!(r.roots.len(), 2, "{:?}", ts(&r));
        assert_eq!(r.roots[0].multiplicity, 2);
        assert!((r.roots[0].t - 0.3).abs() < 1e-12, "{}", r.roots[0].t);
        let r = bernstein_roots(&with_roots(&[0.6, 0.6, 0.6]));
        assert_eq!(r.roots.len(), 1, "{:?}", ts(&r));
        assert_eq!(r.roots[0].multiplicity, 3);
        assert!((r.roots[0].t - 0.6).abs() < 1e-10, "{}", r.roots[0].t);
        // A touching polynomial: (t − 0.5)² ≥ 0 has no sign change but a root.
        let r = bernstein_roots(&with_roots(&[0.5, 0.5]));
        assert_eq!(ts(&r), vec![(0.5, 2)]);
    }

    #[test]
    fn clusters_are_reported_once() {
        // Roots 1e-9 apart are beyond f64's resolution of this polynomial: one cluster.
        let r = bernstein_roots(&with_roots(&[0.4, 0.4 + 1e-9, 0.4 + 2e-9, 0.9]));
        let total: usize = r.roots.iter().map(|x| x.multiplicity).sum();
        assert_eq!(total, 4, "{:?}", ts(&r));
        assert!((r.roots[0].t - 0.4).abs() < 1e-6);
        // Six roots 1e-4 apart: between them |p| is about 1e-24, far below the noise of
        // coefficients of size 1 (1e-14): one cluster of six, at their mean.
        let want: Vec<f64> = (0..6).map(|i| 0.5 + 1e-4 * f64::from(i)).collect();
        let r = bernstein_roots(&with_roots(&want));
        assert_eq!(ts(&r).len(), 1, "{:?}", ts(&r));
        assert_eq!(r.roots[0].multiplicity, 6);
        assert!((r.roots[0].t - 0.50025).abs() < 1e-9);
        // Three roots 1e-3 apart (|p| about 1e-9 between them) are resolved.
        let want = [0.5, 0.501, 0.502];
        let r = bernstein_roots(&with_roots(&want));
        assert_eq!(r.roots.len(), 3, "{:?}", ts(&r));
        for (x, w) in r.roots.iter().zip(&want) {
            assert!((x.t - w).abs() < 1e-12, "{} vs {w}", x.t);
        }
    }

    #[test]
    fn wilkinson_like_twenty_roots() {
        let want: Vec<f64> = (1..=20).map(|i| f64::from(i) / 21.0).collect();
        let r = bernstein_roots(&with_roots(&want));
        assert_eq!(r.roots.len(), 20, "{:?}", ts(&r));
        for (x, w) in r.roots.iter().zip(&want) {
            assert!(
                (x.t - w).abs() <= x.error.max(1e-10),
                "{} vs {w} ± {}",
                x.t,
                x.error
            );
        }
    }
}
