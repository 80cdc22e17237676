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

/// A rational curve as its homogeneous parts: `A` (the weighted points) and `W` (the
/// weights, as the x coordinate) over the same basis. With every weight 1, `A` is the
/// polynomial curve itself (`1·P` is exact) and is evaluated directly.
#[derive(Debug, Clone, PartialEq)]
struct Homogeneous<C> {
    a: C,
    w: C,
    unit: bool,
}

impl<C: ParamCurve> Homogeneous<C> {
    fn new(a: C, w: C, weights: &[f64]) -> Homogeneous<C> {
        Homogeneous {
            a,
            w,
            unit: weights.iter().all(|w| *w == 1.0),
        }
    }

    /// `C`, `C′`, `C″` up to derivative `k` by the quotient rule.
    fn derivative(&self, t: f64, k: usize) -> DVec3 {
        if self.unit {
            return match k {
                0 => self.a.eval(t),
                1 => self.a.eval_deriv(t),
                _ => self.a.eval_second_deriv(t),
            };
        }
        // Only the derivatives asked for.
        let w0 = self.w.eval(t).x;
        let c = self.a.eval(t) / w0;
        if k == 0 {
            return c;
        }
        let w1 = self.w.eval_deriv(t).x;
        let d1 = (self.a.eval_deriv(t) - w1 * c) / w0;
        if k == 1 {
            return d1;
        }
        (self.a.eval_second_deriv(t) - 2.0 * w1 * d1 - self.w.eval_second_deriv(t).x * c) / w0
    }
}

impl<C: ParamCurve> ParamCurve for Homogeneous<C> {
    fn domain(&self) -> (f64, f64) {
        self.a.domain()
    }
    fn eval(&self, t: f64) -> DVec3 {
        self.derivative(t, 0)
    }
    fn eval_deriv(&self, t: f64) -> DVec3 {
        self.derivative(t, 1)
    }
    fn eval_second_deriv(&self, t: f64) -> DVec3 {
        self.derivative(t, 2)
    }
}

/// The rational curves' [`ParamCurve`]: their homogeneous parts'.
macro_rules! param_curve_by_parts {
    ($t:ty) => {
        impl ParamCurve for $t {
            fn domain(&self) -> (f64, f64) {
                self.parts.domain()
            }
            fn eval(&self, t: f64) -> DVec3 {
                self.parts.eval(t)
            }
            fn eval_deriv(&self, t: f64) -> DVec3 {
                self.parts.eval_deriv(t)
            }
            fn eval_second_deriv(&self, t: f64) -> DVec3 {
                self.parts.eval_second_deriv(t)
            }
        }
    };
}

/// A rational Bézier curve of degree `n`:
/// `C(t) = Σ w_i P_i B_{i,n}(t) / Σ w_i B_{i,n}(t)`, `t ∈ [0, 1]`, weights `w_i > 0`.
#[derive(Debug, Clone, PartialEq)]
pub struct RationalBezier {
    points: Vec<DVec3>,
    weights: Vec<f64>,
    /// `A` and `W` as Bézier curves.
    parts: Homogeneous<Bezier>,
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
            parts: Homogeneous::new(Bezier::try_new(a)?, Bezier::try_new(w)?, &weights),
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

    fn from_parts(a: &Bezier, w: &Bezier) -> RationalBezier {
        let (points, weights) = project(a.points(), w.points());
        RationalBezier {
            parts: Homogeneous::new(a.clone(), w.clone(), &weights),
            points,
            weights,
        }
    }

    /// The same curve one degree higher (weights included).
    #[must_use]
    pub fn elevate(&self) -> RationalBezier {
        RationalBezier::from_parts(&self.parts.a.elevate(), &self.parts.w.elevate())
    }

    /// The part on `[t0, t1]`, reparameterised to `[0, 1]`.
    #[must_use]
    pub fn subsegment(&self, t0: f64, t1: f64) -> RationalBezier {
        RationalBezier::from_parts(
            &self.parts.a.subsegment(t0, t1),
            &self.parts.w.subsegment(t0, t1),
        )
    }
}

param_curve_by_parts!(RationalBezier);

/// A NURBS curve of order `k`: `C(t) = Σ w_i P_i N_{i,k}(t) / Σ w_i N_{i,k}(t)` on the
/// B-spline's domain `[t_{k−1}, t_n]`, weights `w_i > 0`.
#[derive(Debug, Clone, PartialEq)]
pub struct Nurbs {
    points: Vec<DVec3>,
    weights: Vec<f64>,
    /// `A` and `W` as B-splines on the same knots.
    parts: Homogeneous<BSpline>,
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
            parts: Homogeneous::new(
                BSpline::from_parts(a, spline.knots().clone())?,
                BSpline::from_parts(w, spline.knots().clone())?,
                &weights,
            ),
            points,
            weights,
        })
    }

    fn from_parts(a: BSpline, w: BSpline) -> Nurbs {
        let (points, weights) = project(a.points(), w.points());
        Nurbs {
            parts: Homogeneous::new(a, w, &weights),
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
        self.parts.a.knots()
    }

    /// The order `k` (degree + 1).
    #[must_use]
    pub fn order(&self) -> usize {
        self.parts.a.order()
    }

    /// The same curve with the knot `t` inserted (Boehm, in homogeneous coordinates).
    ///
    /// # Errors
    /// The knot vector's error for a `t` outside the domain or repeated too often.
    pub fn insert_knot(&self, t: f64) -> Result<Nurbs, GeomError> {
        Ok(Nurbs::from_parts(
            self.parts.a.insert_knot(t)?,
            self.parts.w.insert_knot(t)?,
        ))
    }

    /// The same curve one degree higher (weights included).
    #[must_use]
    pub fn elevate(&self) -> Nurbs {
        Nurbs::from_parts(self.parts.a.elevate(), self.parts.w.elevate())
    }

    /// The rational Bézier segments of the curve with their parameter ranges (Bézier
    /// extraction in homogeneous coordinates).
    #[must_use]
    pub fn bezier_segments(&self) -> Vec<(f64, f64, RationalBezier)> {
        self.parts
            .a
            .bezier_segments()
            .iter()
            .zip(self.parts.w.bezier_segments())
            .map(|(a, w)| (a.t0, a.t1, RationalBezier::from_parts(&a.bezier, &w.bezier)))
            .collect()
    }
}

param_curve_by_parts!(Nurbs);
