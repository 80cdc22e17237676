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
#[derive(Debug, Clone, PartialEq)]
pub struct BatchSingleTarget {
    degree: usize,
    window: usize,
    projector: Projector,
}

/// `P(t)`, `P′(t)`, `P″(t)` from one de Casteljau pass in `buf` (at least `n + 1`
/// points): the derivatives are differences of the last levels' points
/// (`P′ = n (b₁ⁿ⁻¹ − b₀ⁿ⁻¹)`, `P″ = n(n−1)(b₂ⁿ⁻² − 2b₁ⁿ⁻² + b₀ⁿ⁻²)`). Cubics take the
/// same levels written out.
fn eval_derivs(points: &[DVec3], t: f64, buf: &mut [DVec3]) -> (DVec3, DVec3, DVec3) {
    let s = 1.0 - t;
    if let [p0, p1, p2, p3] = *points {
        let (a, b, c) = (s * p0 + t * p1, s * p1 + t * p2, s * p2 + t * p3);
        let (d, e) = (s * a + t * b, s * b + t * c);
        return (s * d + t * e, 3.0 * (e - d), 6.0 * (c - 2.0 * b + a));
    }
    let n = points.len() - 1;
    let buf = &mut buf[..=n];
    buf.copy_from_slice(points);
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
/// it stays in the bracket and gets closer than rounding noise allows, else bisection), in
/// `buf`'s scratch. Stops when a step moves the point by less than `1e-13 · scale`, or at
/// an end of the curve where the distance grows inwards.
fn refine(
    points: &[DVec3],
    target: DVec3,
    (mut lo, mut hi): (f64, f64),
    mut t: f64,
    scale: f64,
    buf: &mut [DVec3],
) -> (f64, f64) {
    let tol = 1e-13 * scale;
    let (mut p, mut d1, mut d2) = eval_derivs(points, t, buf);
    let mut dist = (p - target).length_squared();
    for _ in 0..50 {
        let w = p - target;
        let g = w.dot(d1);
        if (t <= 0.0 && g >= 0.0) || (t >= 1.0 && g <= 0.0) {
            // An end of the curve where the distance grows inwards: a minimum there.
            break;
        }
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
        let (mut np, mut nd1, mut nd2) = eval_derivs(points, next, buf);
        let mut nd = (np - target).length_squared();
        if next == newton && (next - t).abs() * d1.length() <= tol {
            // Converged: a step this small only moves the distance by rounding noise,
            // which must not be read as going uphill.
            (t, p) = (next, np);
            break;
        }
        // Rounding noise in a squared distance near a minimum is about ε · |P| · d; a
        // rise within a few times that is no evidence of going uphill.
        let noise = 8.0 * f64::EPSILON * (dist + scale * dist.sqrt());
        if nd > dist + noise && next == newton {
            // The Newton step went uphill: bisect instead.
            next = 0.5 * (lo + hi);
            (np, nd1, nd2) = eval_derivs(points, next, buf);
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
/// the local minima among them refined by `refine` within their neighbours, best sample
/// first. A minimum is skipped when even the fastest the curve can move between samples
/// (`n · max|P_{i+1} − P_i|`) cannot bring it below the best found: sound pruning, so the
/// result is the best of all the sampled basins. [`Projector`] is the same search with its
/// sampling weights computed once, for batches; [`super::nearest`] is the global
/// subdivision search.
#[must_use]
pub fn sampled_nearest(points: &[DVec3], target: DVec3) -> f64 {
    let projector = Projector::new(points.len().saturating_sub(1));
    projector.nearest(points, target, &mut ProjectScratch::default())
}

/// The sampled nearest-point search of [`sampled_nearest`] for curves of one degree: the
/// Bernstein weights of its `8(n + 1) + 1` uniform samples are computed once, so sampling a
/// curve is `n + 1` multiply-adds per coordinate and sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Projector {
    degree: usize,
    /// `weights[k (n + 1) + i] = B_i^n(k / S)`, `S = 8 (n + 1)`.
    weights: Vec<f64>,
}

/// The squared distances from `target` of the samples whose Bernstein weights `weights`
/// holds, `M` per sample, for a curve of `M` control points (the sums unrolled).
fn sample_fixed<const M: usize>(
    weights: &[f64],
    points: &[DVec3],
    target: DVec3,
    out: &mut Vec<f64>,
) {
    let Ok(p) = <&[DVec3; M]>::try_from(points) else {
        return;
    };
    out.extend(weights.chunks_exact(M).map(|w| {
        let mut acc = DVec3::ZERO;
        for i in 0..M {
            acc += w[i] * p[i];
        }
        (acc - target).length_squared()
    }));
}

thread_local! {
    /// The projection's buffers of each worker thread: allocated on a thread's first
    /// projection, reused by every later batch.
    static SCRATCH: std::cell::RefCell<ProjectScratch> =
        std::cell::RefCell::new(ProjectScratch::default());
}

/// Reusable buffers of [`Projector::nearest`] (one per thread in a batch).
#[derive(Debug, Clone, Default)]
pub struct ProjectScratch {
    distances: Vec<f64>,
    levels: Vec<DVec3>,
}

impl Projector {
    /// The search for curves of `degree`.
    #[must_use]
    pub fn new(degree: usize) -> Projector {
        let samples = 8 * (degree + 1);
        let mut weights = vec![0.0; (samples + 1) * (degree + 1)];
        for (k, row) in weights.chunks_exact_mut(degree + 1).enumerate() {
            bernstein_all_into(k as f64 / samples as f64, row);
        }
        Projector { degree, weights }
    }

    /// The parameter of the point of `points` (`degree + 1` of them) nearest `target`.
    ///
    /// # Panics
    /// If `points` does not hold `degree + 1` points.
    #[must_use]
    pub fn nearest(&self, points: &[DVec3], target: DVec3, scratch: &mut ProjectScratch) -> f64 {
        let n = self.degree;
        assert_eq!(points.len(), n + 1, "degree + 1 control points");
        let samples = 8 * (n + 1);
        let h = 1.0 / samples as f64;
        let d = &mut scratch.distances;
        d.clear();
        // Squared distances: the square root only for the candidates.
        match points.len() {
            3 => sample_fixed::<3>(&self.weights, points, target, d),
            4 => sample_fixed::<4>(&self.weights, points, target, d),
            5 => sample_fixed::<5>(&self.weights, points, target, d),
            6 => sample_fixed::<6>(&self.weights, points, target, d),
            7 => sample_fixed::<7>(&self.weights, points, target, d),
            8 => sample_fixed::<8>(&self.weights, points, target, d),
            _ => d.extend(self.weights.chunks_exact(n + 1).map(|w| {
                let p = w
                    .iter()
                    .zip(points)
                    .fold(DVec3::ZERO, |acc, (&b, &q)| acc + b * q);
                (p - target).length_squared()
            })),
        }
        scratch.levels.resize(n + 1, DVec3::ZERO);
        let buf = &mut scratch.levels;
        let best_k = (0..=samples)
            .min_by(|&a, &b| d[a].total_cmp(&d[b]))
            .unwrap_or(0);
        // The magnitude of the coordinates (within √3 of the largest length): it only
        // scales the stopping tolerance and the noise allowance.
        let scale = points
            .iter()
            .map(|p| p.abs().max_element())
            .fold(target.abs().max_element(), f64::max)
            .max(1e-300);
        let is_min = |k: usize| (k == 0 || d[k] <= d[k - 1]) && (k == samples || d[k] <= d[k + 1]);
        let bracket = |k: usize| ((k as f64 - 1.0).max(0.0) * h, ((k + 1) as f64 * h).min(1.0));
        // Newton starts at the vertex of the parabola through the three samples around k
        // (closer than the sample, so fewer steps).
        let start = |k: usize| {
            if k == 0 || k == samples {
                return k as f64 * h;
            }
            let curvature = d[k - 1] - 2.0 * d[k] + d[k + 1];
            let offset = if curvature > 0.0 {
                (0.5 * (d[k - 1] - d[k + 1]) / curvature).clamp(-1.0, 1.0)
            } else {
                0.0
            };
            (k as f64 + offset) * h
        };
        let (mut best_t, best_sq) =
            refine(points, target, bracket(best_k), start(best_k), scale, buf);
        let mut best = best_sq.sqrt();
        // Computed only when another sampled minimum needs the pruning test.
        let mut speed = None;
        for (k, &dk) in d.iter().enumerate() {
            if k == best_k || !is_min(k) {
                continue;
            }
            let v = *speed.get_or_insert_with(|| {
                n as f64
                    * points
                        .windows(2)
                        .map(|w| (w[1] - w[0]).length())
                        .fold(0.0, f64::max)
            });
            if dk.sqrt() - v * h > best {
                continue;
            }
            let (t, sq) = refine(points, target, bracket(k), start(k), scale, buf);
            if sq.sqrt() < best {
                (best_t, best) = (t, sq.sqrt());
            }
        }
        best_t
    }
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
                method: "batch single_target (degree 2 to 63)",
                degree,
                min: 2,
            });
        }
        Ok(BatchSingleTarget {
            degree,
            window: DEFAULT_WINDOW.min(degree - 1),
            projector: Projector::new(degree),
        })
    }

    /// Solves every curve: `points` holds `degree + 1` control points per curve, `targets`
    /// one target per curve, `t_s` the start parameter per curve (`None`: projected by
    /// the batch's [`Projector`]). The modified control points are written to `out` (same
    /// layout) and one [`BatchResult`] per curve to `results`. Runs on all cores; allocates
    /// nothing once each worker thread has projected once.
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
        // Runs of curves per task, each with its thread's scratch borrowed once.
        const RUN: usize = 256;
        out.par_chunks_mut(stride * RUN)
            .zip(results.par_chunks_mut(RUN))
            .enumerate()
            .for_each(|(run, (dsts, results))| {
                SCRATCH.with_borrow_mut(|scratch| {
                    for (k, (dst, result)) in
                        dsts.chunks_mut(stride).zip(results.iter_mut()).enumerate()
                    {
                        let c = run * RUN + k;
                        let src = &points[c * stride..(c + 1) * stride];
                        let target = targets[c];
                        let t = t_s.map_or_else(
                            || self.projector.nearest(src, target, scratch),
                            |ts| ts[c],
                        );
                        *result = self.solve_one(src, target, t, dst);
                    }
                });
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
        let b = &mut b[..=n];
        bernstein_all_into(t, b);
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
        let at = |q: &[DVec3]| {
            b.iter()
                .zip(q)
                .fold(DVec3::ZERO, |acc, (&w, &p)| acc + w * p)
        };
        let diff = target - at(src);
        for i in first..first + m {
            dst[i] += b[i] / best * diff;
        }
        BatchResult {
            t_s: t,
            residual: (at(dst) - target).length(),
            solved: true,
        }
    }
}
