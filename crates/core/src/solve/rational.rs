//! Paper 000's least-squares shape modification for rational Bézier curves, the weights
//! held fixed. With fixed weights the curve `C(t) = Σ R_i(t) P_i`,
//! `R_i(t) = w_i B_{i,n}(t) / Σ_j w_j B_{j,n}(t)`, is linear in the control points, so
//! the constraints `C̃(t_l) = T_l` stay linear in the moves `ε_i` and the minimal change
//! is the minimum-norm solution of `Σ_i R_i(t_l) ε_i = T_l − C(t_l)` — the polynomial
//! solver's system ([`super::shape`]) with the rational basis in place of the Bernstein
//! one. The end points stay fixed; the weights do not change.

use glam::DVec3;
use nalgebra::DMatrix;

use super::SolveError;
use super::linalg::min_norm_solve;
use crate::geom::bernstein::bernstein_all;
use crate::geom::{ParamCurve, RationalBezier};

/// The rational basis `R_i(t)` of `weights` (degree `weights.len() − 1`).
#[must_use]
pub fn rational_basis(weights: &[f64], t: f64) -> Vec<f64> {
    let b = bernstein_all(weights.len() - 1, t);
    let weighted: Vec<f64> = b.iter().zip(weights).map(|(b, w)| b * w).collect();
    let sum: f64 = weighted.iter().sum();
    weighted.iter().map(|v| v / sum).collect()
}

/// The result of [`multi_target`] (and [`single_target`]).
#[derive(Debug, Clone, PartialEq)]
pub struct RationalSolution {
    /// The modified curve (same weights).
    pub curve: RationalBezier,
    /// The moved control points' indices, in order.
    pub moved: Vec<usize>,
    /// Their moves `ε_i`.
    pub deltas: Vec<DVec3>,
    /// `|C̃(t_l) − T_l|` per target (0 up to rounding unless solved in least squares).
    pub residuals: Vec<f64>,
    /// Whether the system had fewer free parameters than conditions (least squares).
    pub least_squares: bool,
}

fn check(curve: &RationalBezier, targets: &[DVec3], params: &[f64]) -> Result<(), SolveError> {
    if targets.is_empty() {
        return Err(SolveError::NoTargets);
    }
    if params.len() != targets.len() {
        return Err(SolveError::ParamCount {
            targets: targets.len(),
            params: params.len(),
        });
    }
    let n = curve.degree();
    if n < 2 {
        return Err(SolveError::DegreeTooLow {
            method: "rational multi_target",
            degree: n,
            min: 2,
        });
    }
    for (index, (target, &t)) in targets.iter().zip(params).enumerate() {
        if let Some(value) = target.to_array().into_iter().find(|c| !c.is_finite()) {
            return Err(SolveError::NonFiniteTarget { index, value });
        }
        if !(0.0..=1.0).contains(&t) {
            return Err(SolveError::ParameterOutsideDomain {
                value: t,
                start: 0.0,
                end: 1.0,
            });
        }
        if t == 0.0 || t == 1.0 {
            return Err(SolveError::ParameterAtEnd { index, value: t });
        }
    }
    Ok(())
}

/// Moves the interior control points `P_1..P_{n−1}` by the least `Σ‖ε_i‖²` so that the
/// curve passes through `targets[l]` at `params[l]`, the weights fixed.
///
/// # Errors
/// [`SolveError`] for no targets, a count mismatch, degree < 2, a non-finite target, a
/// parameter outside `[0, 1]` or at a (fixed) end.
pub fn multi_target(
    curve: &RationalBezier,
    targets: &[DVec3],
    params: &[f64],
) -> Result<RationalSolution, SolveError> {
    check(curve, targets, params)?;
    let n = curve.degree();
    solve(curve, targets, params, (1..n).collect())
}

/// One target at `t`, moving `count` consecutive interior points from `first` (the
/// window of largest `Σ R_i(t)²` of `min(3, n − 1)` points when `None`), the weights
/// fixed: `ε_i = R_i(t) (T − C(t)) / Σ_{j∈window} R_j(t)²`.
///
/// # Errors
/// As [`multi_target`], and [`SolveError::WindowOutOfRange`] for a window that is not
/// interior.
pub fn single_target(
    curve: &RationalBezier,
    target: DVec3,
    t: f64,
    window: Option<(usize, usize)>,
) -> Result<RationalSolution, SolveError> {
    check(curve, &[target], &[t])?;
    let n = curve.degree();
    let r = rational_basis(curve.weights(), t);
    let (first, count) = match window {
        Some((l, m)) if l >= 1 && m >= 1 && l + m - 1 < n => (l, m),
        Some((l, m)) => {
            return Err(SolveError::WindowOutOfRange {
                first: l,
                count: m,
                max: n - 1,
            });
        }
        None => {
            let m = 3.min(n - 1);
            let weight = |l: usize| r[l..l + m].iter().map(|v| v * v).sum::<f64>();
            let l = (1..=n - m)
                .max_by(|&x, &y| weight(x).total_cmp(&weight(y)))
                .unwrap_or(1);
            (l, m)
        }
    };
    solve(curve, &[target], &[t], (first..first + count).collect())
}

fn solve(
    curve: &RationalBezier,
    targets: &[DVec3],
    params: &[f64],
    moved: Vec<usize>,
) -> Result<RationalSolution, SolveError> {
    let mut a = DMatrix::zeros(targets.len(), moved.len());
    let mut d = DMatrix::zeros(targets.len(), 3);
    for (l, (&t, &target)) in params.iter().zip(targets).enumerate() {
        let r = rational_basis(curve.weights(), t);
        for (k, &i) in moved.iter().enumerate() {
            a[(l, k)] = r[i];
        }
        let diff = target - curve.eval(t);
        for c in 0..3 {
            d[(l, c)] = diff[c];
        }
    }
    let sol = min_norm_solve(&a, &d);
    let deltas: Vec<DVec3> = (0..moved.len())
        .map(|k| DVec3::new(sol.x[(k, 0)], sol.x[(k, 1)], sol.x[(k, 2)]))
        .collect();
    let mut points = curve.points().to_vec();
    for (&i, delta) in moved.iter().zip(&deltas) {
        points[i] += *delta;
    }
    let modified = RationalBezier::try_new(points, curve.weights().to_vec())?;
    let residuals = params
        .iter()
        .zip(targets)
        .map(|(&t, &target)| (modified.eval(t) - target).length())
        .collect();
    Ok(RationalSolution {
        curve: modified,
        moved,
        deltas,
        residuals,
        least_squares: sol.rank < targets.len(),
    })
}
