//! Degree reduction of a Bézier curve: the lowest degree within a tolerance, its ends
//! kept, with the distance proven.
//!
//! For each degree `m = 1, 2, …, n − 1` in turn, the Bézier curve `Q` of degree `m` with
//! `Q₀ = P₀`, `Q_m = P_n` that is nearest to `P` in the least-squares sense over the whole
//! parameter range, `min ∫₀¹ |P(t) − Q(t)|² dt`, is found exactly from the Bernstein
//! basis's inner products (`∫ B_i^m B_k^n = C(m,i) C(n,k) / ((m + n + 1) C(m+n, i+k))`):
//! the normal equations of its `m − 1` inner points, solved by Gaussian elimination with
//! partial pivoting. Its distance from `P` at every `t` is at most the bound on the
//! difference `P − Q` (`Q` raised to degree `n`) of `approx` (the Bernstein hull, halved
//! until it settles): that bounds the Hausdorff distance. The first degree whose bound is
//! within the tolerance is returned; if none is, the refusal names the least bound
//! reached (at degree `n − 1`).

use glam::DVec3;

use crate::geom::Bezier;
use crate::poly;

use super::OpError;
use super::approx::{bound_within, hull_bound};

/// A Bézier curve of lower degree, with the proven bound on its distance from the
/// original.
#[derive(Debug, Clone, PartialEq)]
pub struct Reduced {
    /// The curve.
    pub curve: Bezier,
    /// A bound on the Hausdorff distance from the original (at most the tolerance).
    pub error: f64,
}

fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// `∫₀¹ B_i^m(t) B_k^n(t) dt`.
fn inner(m: usize, i: usize, n: usize, k: usize) -> f64 {
    binomial(m, i) * binomial(n, k) / ((m + n + 1) as f64 * binomial(m + n, i + k))
}

/// The least-squares Bézier curve of degree `m` (ends kept) nearest to `p`.
fn least_squares(p: &[DVec3], m: usize) -> Vec<DVec3> {
    let n = p.len() - 1;
    let (q0, qm) = (p[0], p[n]);
    if m == 1 {
        return vec![q0, qm];
    }
    let k = m - 1;
    let mut a = vec![vec![0.0; k]; k];
    let mut rhs = vec![DVec3::ZERO; k];
    for (r, row) in a.iter_mut().enumerate() {
        let i = r + 1;
        for (c, entry) in row.iter_mut().enumerate() {
            *entry = inner(m, i, m, c + 1);
        }
        let mut b = DVec3::ZERO;
        for (j, pj) in p.iter().enumerate() {
            b += *pj * inner(m, i, n, j);
        }
        rhs[r] = b - q0 * inner(m, i, m, 0) - qm * inner(m, i, m, m);
    }
    // Gaussian elimination with partial pivoting (the Gram matrix is symmetric positive
    // definite; pivoting guards its rounding at high degrees).
    for col in 0..k {
        let piv = (col..k)
            .max_by(|&x, &y| a[x][col].abs().total_cmp(&a[y][col].abs()))
            .unwrap_or(col);
        a.swap(col, piv);
        rhs.swap(col, piv);
        let pivot_row = a[col].clone();
        for r in col + 1..k {
            let f = a[r][col] / pivot_row[col];
            for (entry, &p) in a[r].iter_mut().zip(&pivot_row).skip(col) {
                *entry -= f * p;
            }
            rhs[r] = rhs[r] - rhs[col] * f;
        }
    }
    let mut x = vec![DVec3::ZERO; k];
    for r in (0..k).rev() {
        let mut v = rhs[r];
        for c in r + 1..k {
            v -= x[c] * a[r][c];
        }
        x[r] = v / a[r][r];
    }
    let mut out = vec![q0];
    out.extend(x);
    out.push(qm);
    out
}

/// `P − Q` (Q raised to `P`'s degree), per coordinate.
fn difference(p: &[DVec3], q: &[DVec3]) -> [Vec<f64>; 3] {
    let n = p.len() - 1;
    [0, 1, 2].map(|c| {
        let pc: Vec<f64> = p.iter().map(|v| v[c]).collect();
        let qc: Vec<f64> = q.iter().map(|v| v[c]).collect();
        poly::difference(&pc, &poly::elevate_to(&qc, n))
    })
}

/// `curve` at the lowest degree within `tolerance` (Hausdorff, proven), its ends kept.
///
/// # Errors
/// [`OpError::Tolerance`] for a tolerance that is not a finite number greater than 0;
/// [`OpError::NoLowerDegree`] when even degree `n − 1` is farther than the tolerance (it
/// names the least bound reached), or the curve is a line already.
pub fn reduce_degree(curve: &Bezier, tolerance: f64) -> Result<Reduced, OpError> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(OpError::Tolerance(tolerance));
    }
    let p = curve.points();
    let n = p.len() - 1;
    if n <= 1 {
        return Err(OpError::NoLowerDegree {
            degree: n,
            best: None,
            tolerance,
        });
    }
    let mut best = f64::INFINITY;
    for m in 1..n {
        let q = least_squares(p, m);
        if q.iter().any(|v| !v.is_finite()) {
            continue;
        }
        let d = difference(p, &q);
        if let Some(e) = bound_within(&d, None, tolerance) {
            return Ok(Reduced {
                curve: Bezier::new(q),
                error: e,
            });
        }
        if m == n - 1 {
            best = hull_bound(&d, 6);
        }
    }
    Err(OpError::NoLowerDegree {
        degree: n,
        best: Some(best),
        tolerance,
    })
}
