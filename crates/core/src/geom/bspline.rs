//! Non-uniform B-spline curves of any order (paper 001, §2), and exact degree elevation.
//! Formulas (extraction by blossoms, elevation coefficients by dual functionals):
//! `docs/math.md` §3. A B-spline's [`Family`] side — its report is the
//! structure of the standard NUBMP curve on its knots — is in [`super::nubmp`], which
//! builds on this file (never the other way round).

use glam::DVec3;

use super::bezier::check_finite;
use super::exact::Scalar;

use super::family::{AtTau, Family};
use super::{Bezier, BezierSegment, GeomError, KnotVector, Lower, ParamCurve};

/// A non-uniform B-spline curve of order `k` (degree `k − 1`):
///
/// `P(t) = Σ_{i=0..n−1} N_{i,k}(t) P_i`, `t ∈ [t_{k−1}, t_n]`,
///
/// with `N_{i,k}` the B-splines of the knot vector `T` (Cox–de Boor). Evaluated by de Boor's
/// algorithm; lowered to Bézier segments by knot insertion (Bézier extraction). Paper 001
/// (Cao et al., "Non-uniform B-spline curves with multiple shape parameters", 2011), §2.
#[derive(Debug, Clone, PartialEq)]
pub struct BSpline {
    pub(crate) knots: KnotVector,
    pub(crate) points: Vec<DVec3>,
}

/// De Boor's algorithm on raw data: the point of the order-`order` spline over `knots`
/// with `points` at `t` in span `mu` (`t_mu ≤ t ≤ t_{mu+1}`).
fn de_boor(knots: &[f64], points: &[DVec3], order: usize, mu: usize, t: f64) -> DVec3 {
    let p = order - 1;
    let mut d: Vec<DVec3> = points[mu - p..=mu].to_vec();
    for r in 1..=p {
        for jj in (r..=p).rev() {
            let i = mu - p + jj;
            let denom = knots[i + p + 1 - r] - knots[i];
            let alpha = if denom == 0.0 {
                0.0
            } else {
                (t - knots[i]) / denom
            };
            d[jj] = (1.0 - alpha) * d[jj - 1] + alpha * d[jj];
        }
    }
    d[p]
}

/// The hodograph of an order-`order` spline: order `order − 1` over `knots[1..len−1]`
/// with points `(k−1)(P_{i+1} − P_i)/(t_{i+k} − t_{i+1})`.
fn hodograph(knots: &[f64], points: &[DVec3], order: usize) -> (Vec<f64>, Vec<DVec3>) {
    let p = (order - 1) as f64;
    let d = points
        .windows(2)
        .enumerate()
        .map(|(i, w)| {
            let denom = knots[i + order] - knots[i + 1];
            if denom == 0.0 {
                DVec3::ZERO
            } else {
                p * (w[1] - w[0]) / denom
            }
        })
        .collect();
    (knots[1..knots.len() - 1].to_vec(), d)
}

impl BSpline {
    /// A B-spline from control points, knots and order.
    ///
    /// # Errors
    /// [`GeomError`] for invalid knots (see [`KnotVector::try_new`]) or non-finite points.
    pub fn try_new(
        points: Vec<DVec3>,
        knots: Vec<f64>,
        order: usize,
    ) -> Result<BSpline, GeomError> {
        check_finite(&points)?;
        let knots = KnotVector::try_new(knots, order, points.len())?;
        Ok(BSpline { knots, points })
    }

    /// A B-spline from a validated knot vector.
    ///
    /// # Errors
    /// [`GeomError::TooFewPoints`] when the point count does not match the knots, or
    /// non-finite points.
    pub fn from_parts(points: Vec<DVec3>, knots: KnotVector) -> Result<BSpline, GeomError> {
        check_finite(&points)?;
        if points.len() != knots.n_points() {
            return Err(GeomError::KnotCount {
                expected: points.len() + knots.order(),
                found: knots.knots().len(),
                points: points.len(),
                order: knots.order(),
            });
        }
        Ok(BSpline { knots, points })
    }

    /// The knot vector.
    #[must_use]
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// The control points.
    #[must_use]
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// The order `k`.
    #[must_use]
    pub fn order(&self) -> usize {
        self.knots.order()
    }

    /// The point at `t` (de Boor). Outside the domain the end pieces are extrapolated.
    #[must_use]
    pub fn eval(&self, t: f64) -> DVec3 {
        let mu = self.knots.span(t);
        de_boor(self.knots.knots(), &self.points, self.order(), mu, t)
    }

    /// The `m`-th derivative at `t` (`m = 0` is the point).
    #[must_use]
    pub fn eval_nth_deriv(&self, t: f64, m: usize) -> DVec3 {
        let k = self.order();
        if m >= k {
            return DVec3::ZERO;
        }
        let mu = self.knots.span(t);
        let mut knots = self.knots.knots().to_vec();
        let mut points = self.points.clone();
        for level in 0..m {
            (knots, points) = hodograph(&knots, &points, k - level);
        }
        // Each hodograph drops the first knot: the span index shifts by one per level.
        de_boor(&knots, &points, k - m, mu - m, t)
    }

    /// Inserts the knot `t` once (Boehm): the curve does not change.
    ///
    /// # Errors
    /// [`GeomError`] when `t` is outside the domain or would repeat too often.
    pub fn insert_knot(&self, t: f64) -> Result<BSpline, GeomError> {
        let knots = self.knots.with_inserted(t)?;
        let mu = self.knots.span(t);
        let p = self.knots.degree();
        let tk = self.knots.knots();
        let mut q = Vec::with_capacity(self.points.len() + 1);
        for i in 0..=self.points.len() {
            let alpha = if i + p <= mu {
                1.0
            } else if i > mu {
                0.0
            } else {
                (t - tk[i]) / (tk[i + p] - tk[i])
            };
            let right = self.points.get(i).copied().unwrap_or(DVec3::ZERO);
            let left = if i > 0 {
                self.points[i - 1]
            } else {
                DVec3::ZERO
            };
            q.push(alpha * right + (1.0 - alpha) * left);
        }
        Ok(BSpline { knots, points: q })
    }

    /// The exact Bézier pieces of the curve over its domain, one per non-empty knot span
    /// (Bézier extraction). Each piece is computed on its own span: its control points are
    /// the blossom values `f(t_μ^{p−j}, t_{μ+1}^j)`, `j = 0..=p`, of the span's `p + 1`
    /// control points — the result of raising every breakpoint to multiplicity `k − 1`,
    /// in `O(p³)` per span, so the whole extraction is linear in the number of points.
    #[must_use]
    pub fn bezier_segments(&self) -> Vec<BezierSegment> {
        let p = self.knots.degree();
        let tk = self.knots.knots();
        let (a, b) = self.knots.domain();
        let mut args = vec![0.0; p];
        let mut w = vec![DVec3::ZERO; p + 1];
        (p..self.points.len())
            .filter(|&mu| tk[mu] < tk[mu + 1] && tk[mu] >= a && tk[mu + 1] <= b)
            .map(|mu| {
                let bezier = (0..=p)
                    .map(|j| {
                        for (r, x) in args.iter_mut().enumerate() {
                            *x = if r < p - j { tk[mu] } else { tk[mu + 1] };
                        }
                        blossom_points(tk, &self.points, p, mu, &args, &mut w)
                    })
                    .collect();
                BezierSegment::polynomial(Bezier::new(bezier), tk[mu], tk[mu + 1])
            })
            .collect()
    }

    /// The same curve as a B-spline of order `k + 1` on the refined knots `T*` (every
    /// distinct knot's multiplicity raised by one): `Q_j = Σ_i c^i_j P_i` with the exact
    /// elevation coefficients of [`elevation_coefficients`].
    #[must_use]
    pub fn elevate(&self) -> BSpline {
        let e = elevation_coefficients(self.knots.knots(), self.order());
        let mut q = vec![DVec3::ZERO; e.refined.len() - self.order() - 1];
        for (i, row) in e.rows.iter().enumerate() {
            for (jj, c) in row.values.iter().enumerate() {
                q[row.first + jj] += *c * self.points[i];
            }
        }
        let knots = KnotVector::try_new(e.refined, self.order() + 1, q.len())
            .unwrap_or_else(|err| unreachable!("refined knots are valid: {err}"));
        BSpline { knots, points: q }
    }
}

/// The knots `T*`: every distinct knot of `knots` repeated once more (paper 001, Eq. 2).
#[must_use]
pub fn refine_knots<S: Scalar>(knots: &[S]) -> Vec<S> {
    let mut out = Vec::with_capacity(knots.len() * 2);
    for (i, t) in knots.iter().enumerate() {
        out.push(t.clone());
        if knots.get(i + 1) != Some(t) {
            out.push(t.clone());
        }
    }
    out
}

/// Paper 001's knot map `τ(i)`: the index in `T*` of the knot converted from `t_i` (with
/// `t_i` the `s`-th distinct knot, 0-based, `τ(i) = i + s`). Named apart from the curve
/// parameter `τ` of the constrained modification.
#[must_use]
pub fn refined_index<S: Scalar>(knots: &[S], i: usize) -> usize {
    let s = (1..=i).filter(|&l| knots[l] != knots[l - 1]).count();
    i + s
}

/// [`refined_index`] for every `i` in `0..count`, in one pass.
fn refined_indices<S: Scalar>(knots: &[S], count: usize) -> Vec<usize> {
    let mut s = 0;
    (0..count)
        .map(|i| {
            if i > 0 && knots[i] != knots[i - 1] {
                s += 1;
            }
            i + s
        })
        .collect()
}

/// One row of the elevation coefficients: `c^i_j` for `j = first .. first + values.len()`.
#[derive(Debug, Clone, PartialEq)]
pub struct CoefficientRow<S> {
    /// The first `j` (`τ(i)`).
    pub first: usize,
    /// `c^i_j` for `j = first ..= τ(i+k) − k`.
    pub values: Vec<S>,
}

/// The degree-elevation coefficients of a knot vector (paper 001, Eq. 3).
#[derive(Debug, Clone, PartialEq)]
pub struct Elevation<S> {
    /// The refined knots `T*`.
    pub refined: Vec<S>,
    /// Row `i`: the `c^i_j` with `N_{i,k} = Σ_j c^i_j N*_{j,k+1}`.
    pub rows: Vec<CoefficientRow<S>>,
}

/// The blossom (polar form) of the degree-`p` polynomial piece on span `mu` of the spline
/// with `knots` and scalar coefficients `d`, at the `p` arguments `xs` (de Boor's algorithm
/// with argument `xs[r−1]` at level `r`).
/// The blossom of the degree-`p` spline with control points `points` on span `μ`, at
/// `xs` (de Boor's recurrence with one argument per level); `w` is scratch of `p + 1`.
fn blossom_points(
    knots: &[f64],
    points: &[DVec3],
    p: usize,
    mu: usize,
    xs: &[f64],
    w: &mut [DVec3],
) -> DVec3 {
    w.copy_from_slice(&points[mu - p..=mu]);
    for r in 1..=p {
        for jj in (r..=p).rev() {
            let i = mu - p + jj;
            let alpha = (xs[r - 1] - knots[i]) / (knots[i + p + 1 - r] - knots[i]);
            w[jj] = (1.0 - alpha) * w[jj - 1] + alpha * w[jj];
        }
    }
    w[p]
}

fn blossom<S: Scalar>(knots: &[S], d: &[S], p: usize, mu: usize, xs: &[S]) -> S {
    let mut w: Vec<S> = d[mu - p..=mu].to_vec();
    for r in 1..=p {
        for jj in (r..=p).rev() {
            let i = mu - p + jj;
            let alpha = (xs[r - 1].clone() - knots[i].clone())
                / (knots[i + p + 1 - r].clone() - knots[i].clone());
            w[jj] = (S::one() - alpha.clone()) * w[jj - 1].clone() + alpha * w[jj].clone();
        }
    }
    w[p].clone()
}

/// The exact degree-elevation coefficients `c^i_j ≥ 0` of the order-`order` B-splines on
/// `knots`: `N_{i,k} = Σ_j c^i_j N*_{j,k+1}` over the refined knots `T*`, non-zero only for
/// `j = τ(i) ..= τ(i+k) − k` (paper 001, Eq. 3).
///
/// Computed by dual functionals: `c^i_j` is the blossom of `N_{i,k}` (the spline with
/// coefficients `e_i`) elevated to degree `k` — the mean of the degree-`(k−1)` blossoms
/// leaving out one argument — at the knots `t*_{j+1}, …, t*_{j+k}`, on any non-empty
/// interval of `N*_j`'s support. The knot vector is padded with `k − 1` distinct knots at
/// each end so that the pieces outside an unclamped domain have their blossoms too. Exact
/// for [`super::exact::Rational`]; in `f64` every step is a ratio of knot differences.
///
/// # Panics
/// If `knots` has fewer than `order + 1` entries or is not non-decreasing (callers pass a
/// validated [`KnotVector`]'s knots).
#[must_use]
pub fn elevation_coefficients<S: Scalar>(knots: &[S], order: usize) -> Elevation<S> {
    let k = order;
    let p = k - 1;
    let n = knots.len() - k;
    let refined = refine_knots(knots);
    // Pad: p knots before and after, distinct and away from the real ones.
    let first = knots[0].clone();
    let last = knots[knots.len() - 1].clone();
    let span = if last > first {
        last.clone() - first.clone()
    } else {
        S::one()
    };
    let mut padded: Vec<S> = (0..p)
        .map(|i| first.clone() - span.clone() * S::from_usize(p - i))
        .collect();
    padded.extend(knots.iter().cloned());
    padded.extend((1..=p).map(|i| last.clone() + span.clone() * S::from_usize(i)));
    let taus = refined_indices(knots, n + k);
    let kk = S::from_usize(k);
    // e_i in the padded numbering, one entry set at a time.
    let mut d = vec![S::zero(); n + 2 * p];
    let rows = (0..n)
        .map(|i| {
            d[i + p] = S::one();
            let j_first = taus[i];
            let j_last = taus[i + k] - k;
            let values = (j_first..=j_last)
                .map(|j| {
                    let args = &refined[j + 1..=j + k];
                    // A non-empty interval of T* in N*_j's support, and its span in the
                    // padded original knots.
                    let l = (j..=j + k)
                        .find(|&l| refined[l] < refined[l + 1])
                        .unwrap_or_else(|| unreachable!("N*_{j} has a non-empty support"));
                    // The last non-empty span of the padded knots starting at or before
                    // refined[l] (binary search, then back over repeated knots).
                    let mut mu = padded
                        .partition_point(|x| *x <= refined[l])
                        .saturating_sub(1)
                        .min(padded.len() - 2);
                    while mu > 0 && padded[mu] >= padded[mu + 1] {
                        mu -= 1;
                    }
                    let mut sum = S::zero();
                    for skip in 0..k {
                        let xs: Vec<S> = args
                            .iter()
                            .enumerate()
                            .filter(|(r, _)| *r != skip)
                            .map(|(_, x)| x.clone())
                            .collect();
                        sum = sum + blossom(&padded, &d, p, mu, &xs);
                    }
                    sum / kk.clone()
                })
                .collect();
            d[i + p] = S::zero();
            CoefficientRow {
                first: j_first,
                values,
            }
        })
        .collect();
    Elevation { refined, rows }
}

impl ParamCurve for BSpline {
    fn domain(&self) -> (f64, f64) {
        self.knots.domain()
    }
    fn eval(&self, t: f64) -> DVec3 {
        BSpline::eval(self, t)
    }
    fn eval_deriv(&self, t: f64) -> DVec3 {
        self.eval_nth_deriv(t, 1)
    }
    fn eval_second_deriv(&self, t: f64) -> DVec3 {
        self.eval_nth_deriv(t, 2)
    }
}

impl Lower for BSpline {
    fn lower(&self) -> Vec<BezierSegment> {
        self.bezier_segments()
    }
}

// The family: what the editor, the reports and the drawing need of every curve family.

// The B-spline as a family: it is the standard NUBMP curve on its knots (paper 001, §3),
// so its report and its `at_tau` are that curve's.

impl Family for BSpline {
    const NAME: &'static str = "bspline";

    fn inserts_by_knot(&self) -> bool {
        true
    }

    fn with_knot_inserted(&self, t: f64) -> Result<BSpline, GeomError> {
        self.insert_knot(t)
    }

    fn with_point_removed(&self, index: usize) -> Result<BSpline, GeomError> {
        let (points, knots) =
            crate::geom::structure::spline_without(self.points(), self.knots(), index, Self::NAME)?;
        BSpline::try_new(points, knots, self.order())
    }

    /// The clamped uniform B-spline of order `degree + 1` on `degree + 4` points: four
    /// Bézier segments of `degree`.
    fn generated(degree: usize, point: &mut dyn FnMut() -> DVec3) -> Result<BSpline, GeomError> {
        let points: Vec<DVec3> = (0..degree + 4).map(|_| point()).collect();
        let knots = KnotVector::clamped_uniform(degree + 1, points.len())?;
        BSpline::from_parts(points, knots)
    }

    fn control_points(&self) -> &[DVec3] {
        self.points()
    }

    fn with_control_points(&self, points: Vec<DVec3>) -> Result<BSpline, GeomError> {
        BSpline::from_parts(points, self.knots().clone())
    }

    fn derived_field(&self) -> &'static str {
        "knots"
    }

    fn at_tau(&self, tau: f64) -> Result<Option<AtTau>, GeomError> {
        Family::at_tau(&self.standard_nubmp()?, tau)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paper_knots() -> Vec<f64> {
        vec![0., 0., 0., 0., 0.3, 0.5, 0.89, 1., 1., 1., 1.]
    }

    fn paper_curve() -> BSpline {
        let pts = [
            (0., 0.),
            (1., 2.),
            (2., 2.5),
            (3., 0.5),
            (4., 2.),
            (5., 2.5),
            (6., 0.),
        ]
        .map(|(x, y)| DVec3::new(x, y, 0.0));
        BSpline::try_new(pts.to_vec(), paper_knots(), 4).unwrap()
    }

    #[test]
    fn clamped_bspline_with_one_span_is_the_bezier_curve() {
        let pts = vec![
            DVec3::ZERO,
            DVec3::new(1., 2., 0.),
            DVec3::new(3., 2., 1.),
            DVec3::X * 4.0,
        ];
        let b = BSpline::try_new(pts.clone(), vec![0., 0., 0., 0., 1., 1., 1., 1.], 4).unwrap();
        let z = Bezier::new(pts);
        for k in 0..=10 {
            let t = f64::from(k) / 10.0;
            assert!((b.eval(t) - z.eval(t)).length() < 1e-15);
            assert!((b.eval_deriv(t) - z.eval_deriv(t)).length() < 1e-13);
            assert!((b.eval_second_deriv(t) - z.eval_second_deriv(t)).length() < 1e-12);
        }
    }

    #[test]
    fn refined_knots_and_tau_follow_the_paper() {
        let t = paper_knots();
        let r = refine_knots(&t);
        assert_eq!(
            r,
            vec![
                0., 0., 0., 0., 0., 0.3, 0.3, 0.5, 0.5, 0.89, 0.89, 1., 1., 1., 1., 1.
            ]
        );
        // n* = n + m − 1 = 7 + 5 − 1 = 11 B-splines of order 5 need 16 knots.
        assert_eq!(r.len(), 11 + 5);
        assert_eq!(refined_index(&t, 0), 0);
        assert_eq!(refined_index(&t, 4), 5); // t_4 = 0.3 is distinct knot 1
        assert_eq!(refined_index(&t, 10), 14);
    }

    #[test]
    fn elevation_and_extraction_keep_the_curve() {
        let b = paper_curve();
        let e = b.elevate();
        assert_eq!(e.order(), 5);
        let segs = b.bezier_segments();
        assert_eq!(segs.len(), 4);
        for k in 0..=1000 {
            let t = f64::from(k) / 1000.0;
            assert!((e.eval(t) - b.eval(t)).length() < 1e-13, "t={t}");
            let (s, u) = crate::geom::locate(&segs, t).unwrap();
            assert!(
                (segs[s].bezier.eval(u) - b.eval(t)).length() < 1e-13,
                "t={t}"
            );
        }
    }
}
