//! Knot vectors of non-uniform B-splines (paper 001, §2).

use super::GeomError;
use super::exact::{Rational, Scalar, rational_from_f64};

/// A validated knot vector `T = (t_0 ≤ t_1 ≤ … ≤ t_{n+k−1})` of a B-spline of order `k`
/// (degree `k − 1`) with `n` control points.
///
/// Accepted: `k ≥ 2`, `n ≥ k`, exactly `n + k` finite non-decreasing knots, a non-empty
/// domain `[t_{k−1}, t_n]`, any knot multiplicity up to `k` at or outside the domain's
/// ends, and up to `k − 1` strictly inside it (so the curve is continuous). Clamped and
/// unclamped vectors are both valid.
///
/// A knot vector may also carry its knots' exact rational values (the decimals a scene file
/// wrote), used for exact derived data; equality ignores them.
#[derive(Debug, Clone)]
pub struct KnotVector {
    knots: Vec<f64>,
    order: usize,
    exact: Option<Vec<Rational>>,
}

impl PartialEq for KnotVector {
    fn eq(&self, other: &KnotVector) -> bool {
        self.knots == other.knots && self.order == other.order
    }
}

/// Order ≥ 2 and at least as many control points as the order.
fn check_order(order: usize, n_points: usize) -> Result<(), GeomError> {
    if order < 2 {
        return Err(GeomError::OrderTooLow { order });
    }
    if n_points < order {
        return Err(GeomError::TooFewPoints {
            min: order,
            found: n_points,
        });
    }
    Ok(())
}

impl KnotVector {
    /// Validates `knots` for order `order` and `n_points` control points.
    ///
    /// # Errors
    /// [`GeomError`] naming the offending knot or count.
    pub fn try_new(
        knots: Vec<f64>,
        order: usize,
        n_points: usize,
    ) -> Result<KnotVector, GeomError> {
        check_order(order, n_points)?;
        if knots.len() != n_points + order {
            return Err(GeomError::KnotCount {
                expected: n_points + order,
                found: knots.len(),
                points: n_points,
                order,
            });
        }
        for (index, &value) in knots.iter().enumerate() {
            if !value.is_finite() {
                return Err(GeomError::NonFiniteKnot { index, value });
            }
            if index > 0 && value < knots[index - 1] {
                return Err(GeomError::KnotsDecreasing {
                    index,
                    value,
                    previous: knots[index - 1],
                });
            }
        }
        let (a, b) = (knots[order - 1], knots[n_points]);
        if a >= b {
            return Err(GeomError::EmptyDomain { start: a, end: b });
        }
        let mut index = 0;
        while index < knots.len() {
            let value = knots[index];
            let count = knots[index..].iter().take_while(|&&t| t == value).count();
            let interior = value > a && value < b;
            let max = if interior { order - 1 } else { order };
            if count > max {
                return Err(GeomError::KnotMultiplicity {
                    index: index + max,
                    value,
                    multiplicity: count,
                    max,
                    interior,
                });
            }
            index += count;
        }
        Ok(KnotVector {
            knots,
            order,
            exact: None,
        })
    }

    /// Records the knots' exact values; ignored unless each rounds to its `f64` knot.
    #[must_use]
    pub fn with_exact(mut self, exact: Vec<Rational>) -> KnotVector {
        let matches = exact.len() == self.knots.len()
            && exact.iter().zip(&self.knots).all(|(r, &t)| r.to_f64() == t);
        self.exact = matches.then_some(exact);
        self
    }

    /// Whether exact values were recorded.
    #[must_use]
    pub fn has_exact(&self) -> bool {
        self.exact.is_some()
    }

    /// The knots as exact rationals: the recorded ones, else the `f64` values' exact
    /// binary values.
    #[must_use]
    pub fn exact_knots(&self) -> Vec<Rational> {
        self.exact.clone().unwrap_or_else(|| {
            self.knots
                .iter()
                .map(|&t| rational_from_f64(t).unwrap_or_else(|| unreachable!("knots are finite")))
                .collect()
        })
    }

    /// `n` uniform interior spans, clamped: `k` copies of 0, the interior knots
    /// `1/(n−k+1), …`, `k` copies of 1.
    ///
    /// # Errors
    /// As [`KnotVector::try_new`] (order < 2 or fewer points than the order).
    pub fn clamped_uniform(order: usize, n_points: usize) -> Result<KnotVector, GeomError> {
        check_order(order, n_points)?;
        let spans = n_points - order + 1;
        let mut knots = vec![0.0; order];
        knots.extend((1..spans).map(|i| i as f64 / spans as f64));
        knots.extend(std::iter::repeat_n(1.0, order));
        // Their exact values are i / spans (derived data in rationals stays small).
        let exact: Vec<Rational> = knots
            .iter()
            .enumerate()
            .map(|(idx, _)| {
                let i = idx.saturating_sub(order - 1).min(spans);
                Rational::new(i.into(), spans.into())
            })
            .collect();
        Ok(KnotVector::try_new(knots, order, n_points)?.with_exact(exact))
    }

    /// The knots.
    #[must_use]
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The order `k`.
    #[must_use]
    pub fn order(&self) -> usize {
        self.order
    }

    /// The degree `k − 1`.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.order - 1
    }

    /// The number of control points `n` (= knots − order).
    #[must_use]
    pub fn n_points(&self) -> usize {
        self.knots.len() - self.order
    }

    /// The parameter domain `[t_{k−1}, t_n]`.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.order - 1], self.knots[self.n_points()])
    }

    /// Whether the first `k` and the last `k` knots are equal (the curve starts at the first
    /// control point and ends at the last).
    #[must_use]
    pub fn is_clamped(&self) -> bool {
        let k = self.order;
        let n = self.knots.len();
        self.knots[..k].iter().all(|&t| t == self.knots[0])
            && self.knots[n - k..].iter().all(|&t| t == self.knots[n - 1])
    }

    /// The span `μ ∈ [k−1, n−1]` with `t_μ ≤ t < t_{μ+1}` and `t_μ < t_{μ+1}`. Parameters at
    /// or past the domain's end get the last non-empty span, before its start the first:
    /// robust at repeated knots.
    #[must_use]
    pub fn span(&self, t: f64) -> usize {
        let k = self.order;
        let n = self.n_points();
        // Last index μ in [k−1, n−1] with t_μ ≤ t (binary search over the domain's knots).
        let slice = &self.knots[k - 1..n];
        let mut mu = (k - 1) + slice.partition_point(|&x| x <= t).saturating_sub(1);
        // At the domain's end (or past it) step back to a non-empty span.
        while mu > k - 1 && self.knots[mu] == self.knots[mu + 1] {
            mu -= 1;
        }
        mu
    }

    /// The distinct knot values with their multiplicities, in order.
    #[must_use]
    pub fn distinct(&self) -> Vec<(f64, usize)> {
        let mut out: Vec<(f64, usize)> = Vec::new();
        for &t in &self.knots {
            match out.last_mut() {
                Some((v, m)) if *v == t => *m += 1,
                _ => out.push((t, 1)),
            }
        }
        out
    }

    /// How many knots equal `t`.
    #[must_use]
    pub fn multiplicity(&self, t: f64) -> usize {
        self.knots.iter().filter(|&&x| x == t).count()
    }

    /// The distinct values strictly inside the domain, and the domain's ends: the
    /// boundaries of the curve's polynomial pieces.
    #[must_use]
    pub fn breakpoints(&self) -> Vec<f64> {
        let (a, b) = self.domain();
        let mut out = vec![a];
        out.extend(
            self.distinct()
                .into_iter()
                .map(|(v, _)| v)
                .filter(|&v| v > a && v < b),
        );
        out.push(b);
        out
    }

    /// All `k` non-zero B-splines `N_{μ−k+1..=μ, k}(t)` at `t` (Cox–de Boor, the stable
    /// triangular form), with the span `μ`.
    #[must_use]
    pub fn basis(&self, t: f64) -> (usize, Vec<f64>) {
        let p = self.degree();
        let mut n = vec![0.0; p + 1];
        let mut left = vec![0.0; p + 1];
        let mut right = vec![0.0; p + 1];
        let mu = self.basis_into(t, &mut n, &mut left, &mut right);
        (mu, n)
    }

    /// [`KnotVector::basis`] into `n` (its `p + 1` values), with `left` and `right` as
    /// scratch (each at least `p + 1` long): no allocation, for loops over many
    /// parameters. Returns the span.
    ///
    /// # Panics
    /// If a slice is shorter than `p + 1`.
    pub fn basis_into(&self, t: f64, n: &mut [f64], left: &mut [f64], right: &mut [f64]) -> usize {
        let mu = self.span(t);
        let p = self.degree();
        let tk = &self.knots;
        n[..=p].fill(0.0);
        n[0] = 1.0;
        for j in 1..=p {
            left[j] = t - tk[mu + 1 - j];
            right[j] = tk[mu + j] - t;
            let mut saved = 0.0;
            for r in 0..j {
                let denom = right[r + 1] + left[j - r];
                let temp = if denom == 0.0 { 0.0 } else { n[r] / denom };
                n[r] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            n[j] = saved;
        }
        mu
    }

    /// The knot vector with `t` inserted once more.
    ///
    /// # Errors
    /// [`GeomError::KnotMultiplicity`] when `t` would exceed the allowed multiplicity, and
    /// [`GeomError::KnotOutsideDomain`] for `t` outside the domain.
    pub fn with_inserted(&self, t: f64) -> Result<KnotVector, GeomError> {
        let (a, b) = self.domain();
        if !(a..=b).contains(&t) {
            return Err(GeomError::KnotOutsideDomain {
                value: t,
                start: a,
                end: b,
            });
        }
        let at = self.knots.partition_point(|&x| x <= t);
        let mut knots = self.knots.clone();
        knots.insert(at, t);
        KnotVector::try_new(knots, self.order, self.n_points() + 1)
    }
}

/// Knots written for people (panels, summaries): each to six decimals at most, trailing
/// zeros dropped (`[0, 0, 0.333333, 1, 1]`); the exact values stay in the curve, the scene
/// file and `inspect`.
#[must_use]
pub fn knots_text(knots: &[f64]) -> String {
    let items: Vec<String> = knots.iter().map(|&k| crate::num::fixed(k, 6)).collect();
    format!("[{}]", items.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn knots_are_written_to_six_decimals_without_trailing_zeros() {
        assert_eq!(
            knots_text(&[0.0, 1.0 / 3.0, 0.5, 2.0, 12.25, -0.0, 1e-9]),
            "[0, 0.333333, 0.5, 2, 12.25, 0, 0]"
        );
    }

    #[test]
    fn validation_names_the_problem() {
        assert_eq!(
            KnotVector::try_new(vec![0.0, 0.0, 1.0, 1.0], 1, 3),
            Err(GeomError::OrderTooLow { order: 1 })
        );
        assert!(matches!(
            KnotVector::try_new(vec![0.0, 0.0, 1.0], 2, 2),
            Err(GeomError::KnotCount {
                expected: 4,
                found: 3,
                ..
            })
        ));
        assert_eq!(
            KnotVector::try_new(vec![0.0, 0.0, 0.5, 0.4, 1.0, 1.0], 2, 4)
                .unwrap_err()
                .field(),
            "knots[3]"
        );
        // Interior multiplicity k would break continuity.
        let e = KnotVector::try_new(vec![0., 0., 0., 0.5, 0.5, 0.5, 1., 1., 1.], 3, 6).unwrap_err();
        assert!(matches!(
            e,
            GeomError::KnotMultiplicity {
                multiplicity: 3,
                max: 2,
                interior: true,
                ..
            }
        ));
        assert!(KnotVector::try_new(vec![0., 0., 0., 0.5, 0.5, 1., 1., 1.], 3, 5).is_ok());
        assert!(matches!(
            KnotVector::try_new(vec![0., 0., 0., 0., 1., 1., 1.], 3, 4),
            Err(GeomError::KnotMultiplicity {
                multiplicity: 4,
                max: 3,
                interior: false,
                ..
            })
        ));
        assert!(matches!(
            KnotVector::try_new(vec![0., 1., 1., 1.], 2, 2),
            Err(GeomError::KnotMultiplicity { .. }) | Err(GeomError::EmptyDomain { .. })
        ));
    }

    #[test]
    fn span_is_robust_at_repeated_knots_and_the_domain_end() {
        let kv =
            KnotVector::try_new(vec![0., 0., 0., 0., 0.3, 0.5, 0.5, 1., 1., 1., 1.], 4, 7).unwrap();
        assert_eq!(kv.span(0.0), 3);
        assert_eq!(kv.span(0.29), 3);
        assert_eq!(kv.span(0.3), 4);
        assert_eq!(kv.span(0.5), 6);
        assert_eq!(kv.span(0.99), 6);
        assert_eq!(kv.span(1.0), 6);
        assert_eq!(kv.span(1.5), 6);
        assert_eq!(kv.span(-1.0), 3);
    }

    #[test]
    fn basis_is_a_partition_of_unity_and_matches_a_closed_form() {
        // Uniform quadratic B-spline on 0,1,2,3: N_0(t) = t²/2 on [0,1].
        let kv = KnotVector::try_new(vec![0., 1., 2., 3., 4., 5.], 3, 3).unwrap();
        let (mu, n) = kv.basis(2.25);
        assert_eq!(mu, 2);
        // On [2,3]: N_0 = (3−t)²/2, N_1 = … , N_2 = (t−2)²/2.
        assert!((n[0] - 0.75f64.powi(2) / 2.0).abs() < 1e-15);
        assert!((n[2] - 0.25f64.powi(2) / 2.0).abs() < 1e-15);
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
    }
}
