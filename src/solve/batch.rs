//! Many single-target solves at once (paper 000, Eq. 8) on all cores, allocation-free in
//! the steady state: the viewer's stress mode re-solves thousands of curves every frame.

use glam::DVec3;
use rayon::prelude::*;

use super::SolveError;
use super::shape::DEFAULT_WINDOW;

/// The largest degree [`BatchSingleTarget`] handles (its scratch lives on the stack).
pub const MAX_BATCH_DEGREE: usize = 63;

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

/// The Bernstein values of degree `n` at `t` into `out[..=n]` (triangular recurrence).
fn bernstein(n: usize, t: f64, out: &mut [f64; MAX_BATCH_DEGREE + 1]) {
    let s = 1.0 - t;
    out[0] = 1.0;
    for j in 1..=n {
        let mut saved = 0.0;
        for slot in out.iter_mut().take(j) {
            let tmp = *slot;
            *slot = saved + s * tmp;
            saved = t * tmp;
        }
        out[j] = saved;
    }
}

fn eval(points: &[DVec3], t: f64) -> DVec3 {
    let mut buf = [DVec3::ZERO; MAX_BATCH_DEGREE + 1];
    let n = points.len() - 1;
    buf[..=n].copy_from_slice(points);
    let s = 1.0 - t;
    for r in 1..=n {
        for i in 0..=(n - r) {
            buf[i] = s * buf[i] + t * buf[i + 1];
        }
    }
    buf[0]
}

/// `P(t)`, `P′(t)`, `P″(t)` without allocating.
fn eval_derivs(points: &[DVec3], t: f64) -> (DVec3, DVec3, DVec3) {
    let n = points.len() - 1;
    let mut d1 = [DVec3::ZERO; MAX_BATCH_DEGREE + 1];
    let mut d2 = [DVec3::ZERO; MAX_BATCH_DEGREE + 1];
    for i in 0..n {
        d1[i] = n as f64 * (points[i + 1] - points[i]);
    }
    for i in 0..n.saturating_sub(1) {
        d2[i] = (n - 1) as f64 * (d1[i + 1] - d1[i]);
    }
    let p1 = if n >= 1 {
        eval(&d1[..n], t)
    } else {
        DVec3::ZERO
    };
    let p2 = if n >= 2 {
        eval(&d2[..n - 1], t)
    } else {
        DVec3::ZERO
    };
    (eval(points, t), p1, p2)
}

/// Safeguarded Newton on `(P − T)·P′ = 0` inside `[lo, hi]` from `t` (a Newton step when
/// it stays in the bracket and gets closer, else bisection).
fn refine(points: &[DVec3], target: DVec3, mut lo: f64, mut hi: f64, mut t: f64) -> f64 {
    let dist = |t: f64| (eval(points, t) - target).length_squared();
    for _ in 0..60 {
        let (p, d1, d2) = eval_derivs(points, t);
        let w = p - target;
        let g = w.dot(d1);
        if g < 0.0 {
            lo = lo.max(t);
        } else {
            hi = hi.min(t);
        }
        let gp = d1.length_squared() + w.dot(d2);
        let newton = if gp > 0.0 { t - g / gp } else { f64::NAN };
        let next = if newton > lo && newton < hi && dist(newton) <= dist(t) {
            newton
        } else {
            0.5 * (lo + hi)
        };
        let done = (next - t).abs() <= 1e-15 || hi - lo <= 1e-15;
        t = next;
        if done {
            break;
        }
    }
    t
}

/// The parameter of the point of `points` nearest `target`: `8(n + 1) + 1` samples, and
/// every local minimum among them refined by [`refine`] within its neighbours; the best
/// wins. Bounded work and no allocation, for batches; [`super::nearest`] is the global
/// subdivision search.
#[must_use]
pub fn sampled_nearest(points: &[DVec3], target: DVec3) -> f64 {
    let n = points.len() - 1;
    let samples = 8 * (n + 1);
    let dist = |t: f64| (eval(points, t) - target).length_squared();
    let at = |k: usize| k as f64 / samples as f64;
    let mut best = (0.0, dist(0.0));
    let end = dist(1.0);
    if end < best.1 {
        best = (1.0, end);
    }
    let (mut prev, mut cur) = (f64::INFINITY, dist(0.0));
    for k in 0..=samples {
        let next = if k < samples {
            dist(at(k + 1))
        } else {
            f64::INFINITY
        };
        if cur <= prev && cur <= next {
            let lo = at(k.saturating_sub(1));
            let hi = at((k + 1).min(samples));
            let t = refine(points, target, lo, hi, at(k));
            let d = dist(t);
            if d < best.1 {
                best = (t, d);
            }
        }
        prev = cur;
        cur = next;
    }
    best.0
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
                residual: (eval(src, t.clamp(0.0, 1.0)) - target).length(),
                solved: false,
            };
        }
        let mut b = [0.0; MAX_BATCH_DEGREE + 1];
        bernstein(n, t, &mut b);
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
        let diff = target - eval(src, t);
        for i in first..first + m {
            dst[i] += b[i] / best * diff;
        }
        BatchResult {
            t_s: t,
            residual: (eval(dst, t) - target).length(),
            solved: true,
        }
    }
}
