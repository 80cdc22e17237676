//! Many single-target solves at once (paper 000, Eq. 8) on all cores, allocation-free in
//! the steady state: the viewer's stress mode re-solves thousands of curves every frame.

use glam::DVec3;
use rayon::prelude::*;

use super::SolveError;
use super::shape::DEFAULT_WINDOW;
use crate::geom::bernstein::bernstein_all_into;
use crate::geom::bezier::{STACK_POINTS, de_casteljau};

/// The largest degree [`BatchSingleTarget`] handles (its scratch lives on the stack).
pub const MAX_BATCH_DEGREE: usize = STACK_POINTS - 1;

/// The outcome of one curve of a batch.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BatchResult {
    /// `t_s` used.
    pub t_s: f64,
    /// `|P̃(t_s) − T|`.
    pub residual: f64,
    /// `false` when `t_s` was at an end (the curve is copied unchanged).
    pub solved: bool,
}

/// Single-target solves for many curves of one degree, stored flat (`degree + 1` points
/// per curve).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BatchSingleTarget {
    degree: usize,
    window: usize,
}

/// `P(t)`, `P′(t)`, `P″(t)` from one de Casteljau pass: the derivatives are differences of
/// the last levels' points (`P′ = n (b₁ⁿ⁻¹ − b₀ⁿ⁻¹)`, `P″ = n(n−1)(b₂ⁿ⁻² − 2b₁ⁿ⁻² + b₀ⁿ⁻²)`).
fn eval_derivs(points: &[DVec3], t: f64) -> (DVec3, DVec3, DVec3) {
    let n = points.len() - 1;
    let mut buf = [DVec3::ZERO; MAX_BATCH_DEGREE + 1];
    buf[..=n].copy_from_slice(points);
    let s = 1.0 - t;
    let nf = n as f64;
    let mut second = DVec3::ZERO;
    let mut first = DVec3::ZERO;
    for r in 1..=n {
        if r + 2 == n + 1 && n >= 2 {
            // Level n − 2: three points left.
            second = nf * (nf - 1.0) * (buf[2] - 2.0 * buf[1] + buf[0]);
        }
        if r == n {
            first = nf * (buf[1] - buf[0]);
        }
        for i in 0..=(n - r) {
            buf[i] = s * buf[i] + t * buf[i + 1];
        }
    }
    (buf[0], first, second)
}

/// Safeguarded Newton on `(P − T)·P′ = 0` inside `[lo, hi]` from `t` (a Newton step when
/// it stays in the bracket and gets closer, else bisection). Stops when a step moves the
/// point by less than `tol`.
fn refine(
    points: &[DVec3],
    target: DVec3,
    mut lo: f64,
    mut hi: f64,
    mut t: f64,
    tol: f64,
) -> (f64, f64) {
    let (mut p, mut d1, mut d2) = eval_derivs(points, t);
    let mut dist = (p - target).length_squared();
    for _ in 0..50 {
        let w = p - target;
        let g = w.dot(d1);
        if g < 0.0 {
            lo = lo.max(t);
        } else {
            hi = hi.min(t);
        }
        let gp = d1.length_squared() + w.dot(d2);
        let newton = if gp > 0.0 { t - g / gp } else { f64::NAN };
        let mut next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        let (mut np, mut nd1, mut nd2) = eval_derivs(points, next);
        let mut nd = (np - target).length_squared();
        if nd > dist && next == newton {
            // The Newton step went uphill: bisect instead.
            next = 0.5 * (lo + hi);
            (np, nd1, nd2) = eval_derivs(points, next);
            nd = (np - target).length_squared();
        }
        let moved = (next - t).abs() * d1.length();
        (t, p, d1, d2) = (next, np, nd1, nd2);
        dist = dist.min(nd);
        if moved <= tol || hi - lo <= 1e-15 {
            break;
        }
    }
    (t, (p - target).length_squared())
}

/// The parameter of the point of `points` nearest `target`: `8(n + 1) + 1` samples, then
/// the local minima among them refined by [`refine`] within their neighbours, best sample
/// first. A minimum is skipped when even the fastest the curve can move between samples
/// (`n · max|P_{i+1} − P_i|`) cannot bring it below the best found: sound pruning, so the
/// result is the best of all the sampled basins. Bounded work and no allocation, for
/// batches; [`super::nearest`] is the global subdivision search.
#[must_use]
pub fn sampled_nearest(points: &[DVec3], target: DVec3) -> f64 {
    let n = points.len() - 1;
    let samples = 8 * (n + 1);
    let h = 1.0 / samples as f64;
    let mut d = [0.0_f64; 8 * (MAX_BATCH_DEGREE + 1) + 1];
    for (k, slot) in d.iter_mut().enumerate().take(samples + 1) {
        *slot = (de_casteljau(points, k as f64 * h) - target).length();
    }
    let best_k = (0..=samples)
        .min_by(|&a, &b| d[a].total_cmp(&d[b]))
        .unwrap_or(0);
    let speed = n as f64
        * points
            .windows(2)
            .map(|w| (w[1] - w[0]).length())
            .fold(0.0, f64::max);
    let scale = points
        .iter()
        .map(|p| p.length())
        .fold(target.length(), f64::max)
        .max(1e-300);
    let tol = 1e-13 * scale;
    let is_min = |k: usize| (k == 0 || d[k] <= d[k - 1]) && (k == samples || d[k] <= d[k + 1]);
    let bracket = |k: usize| ((k as f64 - 1.0).max(0.0) * h, ((k + 1) as f64 * h).min(1.0));
    let (lo, hi) = bracket(best_k);
    let (mut best_t, best_sq) = refine(points, target, lo, hi, best_k as f64 * h, tol);
    let mut best = best_sq.sqrt();
    for (k, &dk) in d.iter().enumerate().take(samples + 1) {
        if k == best_k || !is_min(k) || dk - speed * h > best {
            continue;
        }
        let (lo, hi) = bracket(k);
        let (t, sq) = refine(points, target, lo, hi, k as f64 * h, tol);
        if sq.sqrt() < best {
            (best_t, best) = (t, sq.sqrt());
        }
    }
    best_t
}

impl BatchSingleTarget {
    /// A batch solver for curves of `degree` moving the default window (paper 000 with
    /// `m = min(3, n − 1)` points, the window of largest `Σ B²`).
    ///
    /// # Errors
    /// [`SolveError::DegreeTooLow`] below 2; degrees over [`MAX_BATCH_DEGREE`] are refused
    /// the same way (reported as the bound).
    pub fn new(degree: usize) -> Result<BatchSingleTarget, SolveError> {
        if !(2..=MAX_BATCH_DEGREE).contains(&degree) {
            return Err(SolveError::DegreeTooLow {
                method: "batch single_target (degree 2..=63)",
                degree,
                min: 2,
            });
        }
        Ok(BatchSingleTarget {
            degree,
            window: DEFAULT_WINDOW.min(degree - 1),
        })
    }

    /// Solves every curve: `points` holds `degree + 1` control points per curve, `targets`
    /// one target per curve, `t_s` the start parameter per curve (`None`: projected by
    /// [`sampled_nearest`]). The modified control points are written to `out` (same layout)
    /// and one [`BatchResult`] per curve to `results`. Runs on all cores; allocates nothing.
    ///
    /// # Panics
    /// When the slices' lengths do not match (a bug in the caller).
    pub fn solve(
        &self,
        points: &[DVec3],
        targets: &[DVec3],
        t_s: Option<&[f64]>,
        out: &mut [DVec3],
        results: &mut [BatchResult],
    ) {
        let stride = self.degree + 1;
        let curves = targets.len();
        assert_eq!(
            points.len(),
            curves * stride,
            "points: degree + 1 per curve"
        );
        assert_eq!(out.len(), points.len(), "out matches points");
        assert_eq!(results.len(), curves, "one result per curve");
        if let Some(t) = t_s {
            assert_eq!(t.len(), curves, "one t_s per curve");
        }
        out.par_chunks_mut(stride)
            .zip(results.par_iter_mut())
            .enumerate()
            .with_min_len(256)
            .for_each(|(c, (dst, result))| {
                let src = &points[c * stride..(c + 1) * stride];
                let target = targets[c];
                let t = t_s.map_or_else(|| sampled_nearest(src, target), |ts| ts[c]);
                *result = self.solve_one(src, target, t, dst);
            });
    }

    fn solve_one(&self, src: &[DVec3], target: DVec3, t: f64, dst: &mut [DVec3]) -> BatchResult {
        dst.copy_from_slice(src);
        let n = self.degree;
        if !(t > 0.0 && t < 1.0) {
            return BatchResult {
                t_s: t,
                residual: (de_casteljau(src, t.clamp(0.0, 1.0)) - target).length(),
                solved: false,
            };
        }
        let mut b = [0.0; MAX_BATCH_DEGREE + 1];
        bernstein_all_into(t, &mut b[..=n]);
        let m = self.window;
        let mut first = 1;
        let mut best = -1.0;
        for l in 1..=n - m {
            let w: f64 = b[l..l + m].iter().map(|v| v * v).sum();
            if w > best {
                best = w;
                first = l;
            }
        }
        let diff = target - de_casteljau(src, t);
        for i in first..first + m {
            dst[i] += b[i] / best * diff;
        }
        BatchResult {
            t_s: t,
            residual: (de_casteljau(dst, t) - target).length(),
            solved: true,
        }
    }
}
