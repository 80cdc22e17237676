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
    let solve = |rhs: &DMatrix<f64>| {
        svd.solve(rhs, tol)
            .unwrap_or_else(|e| unreachable!("both U and V were computed: {e}"))
    };
    let mut x = solve(b);
    let mut residual = (a * &x - b).norm();
    // nalgebra's SVD can factor A to only ~1e-7 when singular values nearly coincide
    // (dimforge/nalgebra#1172), which leaves that much residual in a system solvable
    // exactly. Iterative refinement with the same pseudo-inverse recovers it: each step
    // solves for the correction of the current residual and is kept only if it helps.
    for _ in 0..4 {
        let step = solve(&(b - a * &x));
        let candidate = &x + &step;
        let r = (a * &candidate - b).norm();
        if r >= residual {
            break;
        }
        x = candidate;
        residual = r;
    }
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
    fn nearly_repeated_singular_values_still_give_an_exact_minimum_norm_solution() {
        // A tangent-kept system (paper 000, degree 5, 3D, t* ≈ 0.0588) whose two smaller
        // singular values agree to 6 digits: the bare SVD solve left a residual of 7e-7.
        let t = 0.058_783_202_057_699_33_f64;
        let bern: Vec<f64> = (0..=5)
            .map(|i| {
                let c = [1.0, 5.0, 10.0, 10.0, 5.0, 1.0][i];
                c * t.powi(i as i32) * (1.0 - t).powi(5 - i as i32)
            })
            .collect();
        // The degree-5 curve's first two and last two control points, and T − P(t*).
        let p0 = [-4.955521347757966, -4.930018274197926, -3.512741544788752];
        let p1 = [1.9766602889632683, -2.8986229658565996, 0.6615664767709077];
        let p4 = [-4.789153453024851, -1.3835686988330744, -2.412235826847592];
        let p5 = [2.717983537810386, -3.7504351533147084, 0.20754243364979708];
        let unit = |from: [f64; 3], to: [f64; 3]| {
            let d = [to[0] - from[0], to[1] - from[1], to[2] - from[2]];
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            d.map(|c| c / len)
        };
        let (e1, e2) = (unit(p0, p1), unit(p5, p4));
        let mut a = DMatrix::zeros(3, 8);
        for row in 0..3 {
            a[(row, 0)] = bern[1] * e1[row];
            a[(row, 1)] = bern[4] * e2[row];
            a[(row, 2 + row)] = bern[2];
            a[(row, 5 + row)] = bern[3];
        }
        let b = DMatrix::from_row_slice(3, 1, &[5.1, 4.9, 8.2]);
        let s = min_norm_solve(&a, &b);
        assert_eq!(s.rank, 3);
        assert!(s.residual < 1e-12, "residual {}", s.residual);
        // Independent truth for full row rank: x = Aᵀ (A Aᵀ)⁻¹ b (A Aᵀ is well
        // conditioned here, so the normal equations are accurate).
        let y = (&a * a.transpose()).lu().solve(&b).unwrap();
        let x = a.transpose() * y;
        assert!(
            (&s.x - &x).norm() <= 1e-12 * x.norm(),
            "{}",
            (&s.x - &x).norm()
        );
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
