//! Rational curves: the rational Bézier curve and the NURBS curve, computed in
//! homogeneous coordinates. A rational curve of control points `P_i` and weights
//! `w_i > 0` is the projection `C(t) = A(t) / W(t)` of the polynomial curve
//! `(A, W) = Σ basis_i(t) (w_i P_i, w_i)` in 4D, so every operation that is linear in the
//! control points — knot insertion, degree elevation, Bézier extraction, subdivision — is
//! done on `A` and `W` with the polynomial families' own code, and the weights follow.
//!
//! Derivatives by the quotient rule: `C′ = (A′ − W′ C) / W`,
//! `C″ = (A″ − 2 W′ C′ − W″ C) / W`.
//!
//! Conics are exact: the quarter circle is the quadratic rational Bézier curve
//! `(1, 0), (1, 1), (0, 1)` with weights `1, √2/2, 1`; the whole circle the nine-point
//! quadratic NURBS curve on the knots `0,0,0,¼,¼,½,½,¾,¾,1,1,1`. With every weight 1 each
//! curve is its polynomial family exactly (evaluated by it).
//!
//! Not yet a [`super::Family`]: drawing needs the GPU's homogeneous layout (the lowering
//! to polynomial segments the renderer takes has no weights).

use glam::DVec3;

use super::{BSpline, Bezier, GeomError, KnotVector, ParamCurve};

/// Checks weights: as many as points, each finite and greater than 0.
fn check_weights(points: &[DVec3], weights: &[f64]) -> Result<(), GeomError> {
    if weights.len() != points.len() {
        return Err(GeomError::WeightCount {
            weights: weights.len(),
            points: points.len(),
        });
    }
    match weights
        .iter()
        .enumerate()
        .find(|(_, w)| !w.is_finite() || **w <= 0.0)
    {
        Some((index, &value)) => Err(GeomError::BadWeight { index, value }),
        None => Ok(()),
    }
}

/// The weighted points `w_i P_i` and the weights as points `(w_i, 0, 0)`.
fn homogeneous(points: &[DVec3], weights: &[f64]) -> (Vec<DVec3>, Vec<DVec3>) {
    (
        points.iter().zip(weights).map(|(p, w)| *p * *w).collect(),
        weights.iter().map(|w| DVec3::new(*w, 0.0, 0.0)).collect(),
    )
}

/// Points and weights back from the weighted points and the weights.
fn project(weighted: &[DVec3], weights: &[DVec3]) -> (Vec<DVec3>, Vec<f64>) {
    weighted
        .iter()
        .zip(weights)
        .map(|(a, w)| (*a / w.x, w.x))
        .unzip()
}

/// `C`, `C′`, `C″` from `A`, `W` and their derivatives (the quotient rule).
fn quotient(a: [DVec3; 3], w: [f64; 3]) -> [DVec3; 3] {
    let c = a[0] / w[0];
    let d1 = (a[1] - w[1] * c) / w[0];
    let d2 = (a[2] - 2.0 * w[1] * d1 - w[2] * c) / w[0];
    [c, d1, d2]
}

/// A rational Bézier curve of degree `n`:
/// `C(t) = Σ w_i P_i B_{i,n}(t) / Σ w_i B_{i,n}(t)`, `t ∈ [0, 1]`, weights `w_i > 0`.
#[derive(Debug, Clone, PartialEq)]
pub struct RationalBezier {
    points: Vec<DVec3>,
    weights: Vec<f64>,
    /// `A`: the weighted points as a Bézier curve.
    a: Bezier,
    /// `W`: the weights as the x coordinate of a Bézier curve.
    w: Bezier,
}

impl RationalBezier {
    /// A rational Bézier curve.
    ///
    /// # Errors
    /// Fewer than 2 points, a non-finite point, a weight count that differs, a weight
    /// that is not a finite number greater than 0.
    pub fn try_new(points: Vec<DVec3>, weights: Vec<f64>) -> Result<RationalBezier, GeomError> {
        Bezier::try_new(points.clone())?;
        check_weights(&points, &weights)?;
        let (a, w) = homogeneous(&points, &weights);
        Ok(RationalBezier {
            a: Bezier::try_new(a)?,
            w: Bezier::try_new(w)?,
            points,
            weights,
        })
    }

    /// The control points.
    #[must_use]
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// The weights.
    #[must_use]
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The degree `n`.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }

    fn polynomial(&self) -> Option<Bezier> {
        self.weights
            .iter()
            .all(|w| *w == 1.0)
            .then(|| Bezier::new(self.points.clone()))
    }

    fn all(&self, t: f64) -> [DVec3; 3] {
        let a = [
            self.a.eval(t),
            self.a.eval_deriv(t),
            self.a.eval_second_deriv(t),
        ];
        let w = [
            self.w.eval(t),
            self.w.eval_deriv(t),
            self.w.eval_second_deriv(t),
        ];
        quotient(a, w.map(|v| v.x))
    }

    fn from_parts(a: &Bezier, w: &Bezier) -> RationalBezier {
        let (points, weights) = project(a.points(), w.points());
        RationalBezier {
            a: a.clone(),
            w: w.clone(),
            points,
            weights,
        }
    }

    /// The same curve one degree higher (weights included).
    #[must_use]
    pub fn elevate(&self) -> RationalBezier {
        RationalBezier::from_parts(&self.a.elevate(), &self.w.elevate())
    }

    /// The part on `[t0, t1]`, reparameterised to `[0, 1]`.
    #[must_use]
    pub fn subsegment(&self, t0: f64, t1: f64) -> RationalBezier {
        RationalBezier::from_parts(&self.a.subsegment(t0, t1), &self.w.subsegment(t0, t1))
    }
}

impl ParamCurve for RationalBezier {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, t: f64) -> DVec3 {
        match self.polynomial() {
            Some(b) => b.eval(t),
            None => self.all(t)[0],
        }
    }
    fn eval_deriv(&self, t: f64) -> DVec3 {
        match self.polynomial() {
            Some(b) => b.eval_deriv(t),
            None => self.all(t)[1],
        }
    }
    fn eval_second_deriv(&self, t: f64) -> DVec3 {
        match self.polynomial() {
            Some(b) => b.eval_second_deriv(t),
            None => self.all(t)[2],
        }
    }
}

/// A NURBS curve of order `k`: `C(t) = Σ w_i P_i N_{i,k}(t) / Σ w_i N_{i,k}(t)` on the
/// B-spline's domain `[t_{k−1}, t_n]`, weights `w_i > 0`.
#[derive(Debug, Clone, PartialEq)]
pub struct Nurbs {
    points: Vec<DVec3>,
    weights: Vec<f64>,
    /// `A`: the weighted points as a B-spline.
    a: BSpline,
    /// `W`: the weights as the x coordinate of a B-spline on the same knots.
    w: BSpline,
}

impl Nurbs {
    /// A NURBS curve.
    ///
    /// # Errors
    /// The B-spline's errors (knot count, order, multiplicities, non-finite points), a
    /// weight count that differs, a weight that is not a finite number greater than 0.
    pub fn try_new(
        points: Vec<DVec3>,
        weights: Vec<f64>,
        knots: Vec<f64>,
        order: usize,
    ) -> Result<Nurbs, GeomError> {
        let spline = BSpline::try_new(points.clone(), knots, order)?;
        check_weights(&points, &weights)?;
        let (a, w) = homogeneous(&points, &weights);
        Ok(Nurbs {
            a: BSpline::from_parts(a, spline.knots().clone())?,
            w: BSpline::from_parts(w, spline.knots().clone())?,
            points,
            weights,
        })
    }

    fn from_parts(a: BSpline, w: BSpline) -> Nurbs {
        let (points, weights) = project(a.points(), w.points());
        Nurbs {
            a,
            w,
            points,
            weights,
        }
    }

    /// The control points.
    #[must_use]
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// The weights.
    #[must_use]
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The knot vector.
    #[must_use]
    pub fn knots(&self) -> &KnotVector {
        self.a.knots()
    }

    /// The order `k` (degree + 1).
    #[must_use]
    pub fn order(&self) -> usize {
        self.a.order()
    }

    fn polynomial(&self) -> Option<&BSpline> {
        self.weights.iter().all(|w| *w == 1.0).then_some(&self.a)
    }

    fn all(&self, t: f64) -> [DVec3; 3] {
        let a = [
            self.a.eval(t),
            self.a.eval_deriv(t),
            self.a.eval_second_deriv(t),
        ];
        let w = [
            self.w.eval(t),
            self.w.eval_deriv(t),
            self.w.eval_second_deriv(t),
        ];
        quotient(a, w.map(|v| v.x))
    }

    /// The same curve with the knot `t` inserted (Boehm, in homogeneous coordinates).
    ///
    /// # Errors
    /// The knot vector's error for a `t` outside the domain or repeated too often.
    pub fn insert_knot(&self, t: f64) -> Result<Nurbs, GeomError> {
        Ok(Nurbs::from_parts(
            self.a.insert_knot(t)?,
            self.w.insert_knot(t)?,
        ))
    }

    /// The same curve one degree higher (weights included).
    #[must_use]
    pub fn elevate(&self) -> Nurbs {
        Nurbs::from_parts(self.a.elevate(), self.w.elevate())
    }

    /// The rational Bézier segments of the curve with their parameter ranges (Bézier
    /// extraction in homogeneous coordinates).
    #[must_use]
    pub fn bezier_segments(&self) -> Vec<(f64, f64, RationalBezier)> {
        self.a
            .bezier_segments()
            .iter()
            .zip(self.w.bezier_segments())
            .map(|(a, w)| (a.t0, a.t1, RationalBezier::from_parts(&a.bezier, &w.bezier)))
            .collect()
    }
}

impl ParamCurve for Nurbs {
    fn domain(&self) -> (f64, f64) {
        self.a.domain()
    }
    fn eval(&self, t: f64) -> DVec3 {
        match self.polynomial() {
            Some(b) => b.eval(t),
            None => self.all(t)[0],
        }
    }
    fn eval_deriv(&self, t: f64) -> DVec3 {
        match self.polynomial() {
            Some(b) => b.eval_deriv(t),
            None => self.all(t)[1],
        }
    }
    fn eval_second_deriv(&self, t: f64) -> DVec3 {
        match self.polynomial() {
            Some(b) => b.eval_second_deriv(t),
            None => self.all(t)[2],
        }
    }
}
