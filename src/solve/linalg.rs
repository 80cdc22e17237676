//! Small dense linear algebra: minimum-norm least squares by SVD (never normal equations).

use nalgebra::DMatrix;

/// The minimum-norm least-squares solution of `A X = B`.
#[derive(Debug, Clone, PartialEq)]
pub struct LeastSquares {
    /// `X` (`A.ncols() × B.ncols()`): among the minimisers of `‖A X − B‖`, the one of least
    /// Frobenius norm.
    pub x: DMatrix<f64>,
    /// The numerical rank of `A` (singular values above `max(m, n) · ε · σ_max`).
    pub rank: usize,
    /// `‖A X − B‖` (Frobenius).
    pub residual: f64,
}

/// Solves `A X = B` in the least-squares sense with the pseudo-inverse of `A`'s SVD.
/// Exact (residual 0 up to rounding) when `B` is in `A`'s range, e.g. an under-determined
/// system of full row rank.
///
/// # Panics
/// If `A` and `B` have different row counts (a bug in the caller).
#[must_use]
pub fn min_norm_solve(a: &DMatrix<f64>, b: &DMatrix<f64>) -> LeastSquares {
    assert_eq!(a.nrows(), b.nrows(), "A and B need the same number of rows");
    if a.nrows() == 0 || a.ncols() == 0 {
        return LeastSquares {
            x: DMatrix::zeros(a.ncols(), b.ncols()),
            rank: 0,
            residual: b.norm(),
        };
    }
    let svd = a.clone().svd(true, true);
    let sigma_max = svd.singular_values.max();
    let tol = (a.nrows().max(a.ncols()) as f64) * f64::EPSILON * sigma_max;
    let rank = svd.rank(tol);
    let x = svd
        .solve(b, tol)
        .unwrap_or_else(|e| unreachable!("both U and V were computed: {e}"));
    let residual = (a * &x - b).norm();
    LeastSquares { x, rank, residual }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn under_determined_systems_get_the_minimum_norm_solution() {
        // x + y = 2: the minimum-norm solution is (1, 1).
        let a = DMatrix::from_row_slice(1, 2, &[1.0, 1.0]);
        let b = DMatrix::from_row_slice(1, 1, &[2.0]);
        let s = min_norm_solve(&a, &b);
        assert!((s.x[(0, 0)] - 1.0).abs() < 1e-14 && (s.x[(1, 0)] - 1.0).abs() < 1e-14);
        assert_eq!(s.rank, 1);
        assert!(s.residual < 1e-14);
    }

    #[test]
    fn inconsistent_systems_are_solved_in_least_squares_with_a_residual() {
        // x = 0 and x = 2: least squares gives 1, residual sqrt(2).
        let a = DMatrix::from_row_slice(2, 1, &[1.0, 1.0]);
        let b = DMatrix::from_row_slice(2, 1, &[0.0, 2.0]);
        let s = min_norm_solve(&a, &b);
        assert!((s.x[(0, 0)] - 1.0).abs() < 1e-14);
        assert!((s.residual - 2f64.sqrt()).abs() < 1e-14);
    }

    #[test]
    fn rank_deficient_columns_share_the_load() {
        // Two identical columns: x1 + x2 = 4 → (2, 2).
        let a = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 2.0, 2.0]);
        let b = DMatrix::from_row_slice(2, 1, &[4.0, 8.0]);
        let s = min_norm_solve(&a, &b);
        assert_eq!(s.rank, 1);
        assert!((s.x[(0, 0)] - 2.0).abs() < 1e-13 && (s.x[(1, 0)] - 2.0).abs() < 1e-13);
    }
}
