//! Bernstein polynomials `B_{i,n}(t) = C(n,i) tⁱ (1−t)ⁿ⁻ⁱ` (all three papers).

/// The binomial coefficient `C(n, k)` as `f64` (exact while it is below 2⁵³).
#[must_use]
pub fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    let mut c = 1.0_f64;
    for j in 0..k {
        // c stays an integer: c·(n−j)/(j+1) = C(n, j+1).
        c = c * (n - j) as f64 / (j + 1) as f64;
    }
    c.round()
}

/// The single Bernstein polynomial `B_{i,n}(t)`, by its closed form.
///
/// Zero when `i > n`. Prefer [`bernstein_all`] when several values at one `t` are needed.
#[must_use]
pub fn bernstein(i: usize, n: usize, t: f64) -> f64 {
    if i > n {
        return 0.0;
    }
    binomial(n, i) * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32)
}

/// All `n + 1` Bernstein polynomials of degree `n` at `t`, written into `out`
/// (`out.len()` must be `n + 1`).
///
/// Uses the triangular recurrence `B_{i,j} = (1−t) B_{i,j−1} + t B_{i−1,j−1}` (paper 002,
/// Eq. 1), which only forms convex combinations and so is stable for every `n`.
///
/// # Panics
/// If `out` is empty (a bug in the caller: degree `n` needs `n + 1` slots).
pub fn bernstein_all_into(t: f64, out: &mut [f64]) {
    assert!(!out.is_empty(), "bernstein_all_into needs n + 1 ≥ 1 slots");
    let n = out.len() - 1;
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

/// All `n + 1` Bernstein polynomials of degree `n` at `t` (see [`bernstein_all_into`]).
#[must_use]
pub fn bernstein_all(n: usize, t: f64) -> Vec<f64> {
    let mut out = vec![0.0; n + 1];
    bernstein_all_into(t, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binomials_match_pascal_triangle() {
        let mut row = vec![1.0_f64];
        for n in 1..=50usize {
            let mut next = vec![1.0; n + 1];
            for k in 1..n {
                next[k] = row[k - 1] + row[k];
            }
            row = next;
            for (k, &want) in row.iter().enumerate() {
                assert_eq!(binomial(n, k), want, "C({n},{k})");
            }
        }
        assert_eq!(binomial(3, 4), 0.0);
    }

    #[test]
    fn recurrence_matches_closed_form_and_sums_to_one() {
        for n in 0..=40 {
            for k in 0..=20 {
                let t = k as f64 / 20.0;
                let all = bernstein_all(n, t);
                let sum: f64 = all.iter().sum();
                assert!((sum - 1.0).abs() < 1e-13, "n={n} t={t} sum={sum}");
                for (i, &b) in all.iter().enumerate() {
                    let closed = bernstein(i, n, t);
                    assert!(
                        (b - closed).abs() <= 1e-13 * closed.abs().max(1e-3),
                        "n={n} i={i}"
                    );
                    assert!(b >= 0.0);
                }
            }
        }
    }
}
