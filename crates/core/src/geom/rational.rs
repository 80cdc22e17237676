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
//! Both are families ([`Family`]): they lower to rational Bézier segments
//! ([`BezierSegment::weights`]), which the GPU evaluates in homogeneous coordinates and
//! divides; with every weight 1 they lower to the polynomial segments themselves.

use glam::DVec3;
#[cfg(feature = "serde")]
use schemars::JsonSchema;
#[cfg(feature = "serde")]
use serde::Serialize;

use super::family::Family;
use super::{BSpline, Bezier, BezierSegment, GeomError, KnotVector, Lower, ParamCurve};

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

/// The binary exponent `e` midway between those of the largest and the smallest weight:
/// the homogeneous parts hold the weights scaled by `2^−e`, exactly, so that they lie
/// around 1 (`w_i P_i` and the products of the quotient rule stay inside `f64` for weights
/// as large as `1e300` or as small as `1e−300`; a rational curve does not change when every
/// weight is scaled alike), and the largest and the smallest are as far from overflow as
/// from underflow.
///
/// Weights between `2^−100` and `2^100` — every weight a person types — are kept as they
/// are (`e = 0`).
fn weight_exponent(weights: &[f64]) -> i32 {
    let max = weights.iter().copied().fold(0.0, f64::max);
    let min = weights.iter().copied().fold(f64::INFINITY, f64::min);
    if !(min > 0.0 && max.is_finite()) {
        return 0;
    }
    let (_, hi) = crate::num::split_exponent(max);
    let (_, lo) = crate::num::split_exponent(min);
    if lo >= -100 && hi < 100 {
        0
    } else {
        (hi + lo).div_euclid(2)
    }
}

/// The weighted points `w_i P_i` and the weights as points `(w_i, 0, 0)`, the weights
/// scaled by `2^−e` for the exponent `e` returned ([`weight_exponent`]).
fn homogeneous(points: &[DVec3], weights: &[f64]) -> (Vec<DVec3>, Vec<DVec3>, i32) {
    let e = weight_exponent(weights);
    let scaled: Vec<f64> = weights
        .iter()
        .map(|w| crate::num::scale_by_power_of_two(*w, -e))
        .collect();
    (
        points.iter().zip(&scaled).map(|(p, w)| *p * *w).collect(),
        scaled.iter().map(|w| DVec3::new(*w, 0.0, 0.0)).collect(),
        e,
    )
}

/// Points and weights back from the weighted points and the weights scaled by `2^−e`.
fn project(weighted: &[DVec3], weights: &[DVec3], e: i32) -> (Vec<DVec3>, Vec<f64>) {
    weighted
        .iter()
        .zip(weights)
        .map(|(a, w)| (*a / w.x, crate::num::scale_by_power_of_two(w.x, e)))
        .unzip()
}

/// `weights` scaled alike by a power of two (exactly) so that they lie around 1
/// (`weight_exponent`): what a lowered rational segment carries.
#[must_use]
pub fn normalised_weights(weights: &[f64]) -> Vec<f64> {
    let e = weight_exponent(weights);
    weights
        .iter()
        .map(|w| crate::num::scale_by_power_of_two(*w, -e))
        .collect()
}

/// A rational curve as its homogeneous parts: `A` (the weighted points) and `W` (the
/// weights, as the x coordinate) over the same basis. With every weight 1, `A` is the
/// polynomial curve itself (`1·P` is exact) and is evaluated directly.
#[derive(Debug, Clone, PartialEq)]
struct Homogeneous<C> {
    a: C,
    w: C,
    unit: bool,
    /// The weights' binary exponent: `w` holds the weights times `2^−exp`.
    exp: i32,
}

impl<C: ParamCurve> Homogeneous<C> {
    fn new(a: C, w: C, weights: &[f64], exp: i32) -> Homogeneous<C> {
        Homogeneous {
            a,
            w,
            unit: weights.iter().all(|w| *w == 1.0),
            exp,
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
    pub(crate) points: Vec<DVec3>,
    pub(crate) weights: Vec<f64>,
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
        let (a, w, e) = homogeneous(&points, &weights);
        Ok(RationalBezier {
            parts: Homogeneous::new(Bezier::try_new(a)?, Bezier::try_new(w)?, &weights, e),
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

    fn from_parts(a: &Bezier, w: &Bezier, e: i32) -> RationalBezier {
        let (points, weights) = project(a.points(), w.points(), e);
        RationalBezier {
            parts: Homogeneous::new(a.clone(), w.clone(), &weights, e),
            points,
            weights,
        }
    }

    /// The same curve one degree higher (weights included).
    #[must_use]
    pub fn elevate(&self) -> RationalBezier {
        RationalBezier::from_parts(
            &self.parts.a.elevate(),
            &self.parts.w.elevate(),
            self.parts.exp,
        )
    }

    /// The part on `[t0, t1]`, reparameterised to `[0, 1]`.
    #[must_use]
    pub fn subsegment(&self, t0: f64, t1: f64) -> RationalBezier {
        RationalBezier::from_parts(
            &self.parts.a.subsegment(t0, t1),
            &self.parts.w.subsegment(t0, t1),
            self.parts.exp,
        )
    }
}

param_curve_by_parts!(RationalBezier);

/// A NURBS curve of order `k`: `C(t) = Σ w_i P_i N_{i,k}(t) / Σ w_i N_{i,k}(t)` on the
/// B-spline's domain `[t_{k−1}, t_n]`, weights `w_i > 0`.
#[derive(Debug, Clone, PartialEq)]
pub struct Nurbs {
    pub(crate) points: Vec<DVec3>,
    pub(crate) weights: Vec<f64>,
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
        let (a, w, e) = homogeneous(&points, &weights);
        Ok(Nurbs {
            parts: Homogeneous::new(
                BSpline::from_parts(a, spline.knots().clone())?,
                BSpline::from_parts(w, spline.knots().clone())?,
                &weights,
                e,
            ),
            points,
            weights,
        })
    }

    /// A NURBS curve on a validated knot vector (its exact decimal values kept).
    ///
    /// # Errors
    /// As [`Nurbs::try_new`].
    pub fn from_knot_vector(
        points: Vec<DVec3>,
        weights: Vec<f64>,
        knots: KnotVector,
    ) -> Result<Nurbs, GeomError> {
        BSpline::from_parts(points.clone(), knots.clone())?;
        check_weights(&points, &weights)?;
        let (a, w, e) = homogeneous(&points, &weights);
        Ok(Nurbs {
            parts: Homogeneous::new(
                BSpline::from_parts(a, knots.clone())?,
                BSpline::from_parts(w, knots)?,
                &weights,
                e,
            ),
            points,
            weights,
        })
    }

    fn from_parts(a: BSpline, w: BSpline, e: i32) -> Nurbs {
        let (points, weights) = project(a.points(), w.points(), e);
        Nurbs {
            parts: Homogeneous::new(a, w, &weights, e),
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
            self.parts.exp,
        ))
    }

    /// The same curve one degree higher (weights included).
    #[must_use]
    pub fn elevate(&self) -> Nurbs {
        Nurbs::from_parts(
            self.parts.a.elevate(),
            self.parts.w.elevate(),
            self.parts.exp,
        )
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
            .map(|(a, w)| {
                (
                    a.t0,
                    a.t1,
                    RationalBezier::from_parts(&a.bezier, &w.bezier, self.parts.exp),
                )
            })
            .collect()
    }
}

param_curve_by_parts!(Nurbs);

// (Here rather than in `lowering.rs`, which the rational curves depend on.)
impl BezierSegment {
    /// The piece as a rational Bézier curve, `None` for a polynomial piece (or weights
    /// the rational curve refuses, which lowering never makes).
    #[must_use]
    pub fn rational(&self) -> Option<RationalBezier> {
        let w = self.weights.as_ref()?;
        RationalBezier::try_new(self.bezier.points().to_vec(), w.clone()).ok()
    }
}

/// The segment of a rational piece: polynomial (no weights) when its weights are all
/// equal (the rational curve is then its polynomial curve exactly), so a rational curve
/// with unit weights draws exactly as its polynomial family; otherwise the weights scaled
/// alike by a power of two so that they lie around 1 ([`normalised_weights`]).
pub(crate) fn segment(points: &[DVec3], weights: &[f64], t0: f64, t1: f64) -> BezierSegment {
    let equal = weights.iter().all(|w| *w == weights[0]);
    BezierSegment {
        bezier: Bezier::new(points.to_vec()),
        weights: (!equal).then(|| normalised_weights(weights)),
        t0,
        t1,
    }
}

impl Lower for RationalBezier {
    fn lower(&self) -> Vec<BezierSegment> {
        vec![segment(&self.points, &self.weights, 0.0, 1.0)]
    }
}

impl Lower for Nurbs {
    fn lower(&self) -> Vec<BezierSegment> {
        self.bezier_segments()
            .into_iter()
            .map(|(t0, t1, r)| segment(&r.points, &r.weights, t0, t1))
            .collect()
    }
}

/// A conic's type from a quadratic rational Bézier curve's weights: the shape factor
/// `k = w₀w₂ / w₁²` is above 1 for an ellipse, 1 for a parabola, below 1 for a hyperbola.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(Serialize, JsonSchema))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum Conic {
    /// `w₁² < w₀w₂`.
    Ellipse,
    /// `w₁² = w₀w₂`.
    Parabola,
    /// `w₁² > w₀w₂`.
    Hyperbola,
}

/// `√2 / 2`, the weight of a quarter circle's middle point.
const HALF_SQRT2: f64 = std::f64::consts::FRAC_1_SQRT_2;

impl RationalBezier {
    /// The quarter ellipse arc centred on `center` with semi-axes `a` (along x) and `b`
    /// (along y), from `(a, 0)` to `(0, b)`: the quadratic with weights `1, √2/2, 1`.
    #[must_use]
    pub fn quarter_ellipse(center: DVec3, a: f64, b: f64) -> RationalBezier {
        let points = vec![
            center + DVec3::new(a, 0.0, 0.0),
            center + DVec3::new(a, b, 0.0),
            center + DVec3::new(0.0, b, 0.0),
        ];
        RationalBezier::try_new(points, vec![1.0, HALF_SQRT2, 1.0])
            .unwrap_or_else(|e| unreachable!("a quarter ellipse's weights are valid: {e}"))
    }
}

impl Nurbs {
    /// The circle of radius `r` about `center` in the plane `z = center.z`: the nine-point
    /// quadratic NURBS curve on the knots `0,0,0,¼,¼,½,½,¾,¾,1,1,1`, corner weights `√2/2`.
    ///
    /// # Errors
    /// A non-finite centre or radius.
    pub fn circle(center: DVec3, r: f64) -> Result<Nurbs, GeomError> {
        let corners = [
            (1.0, 0.0),
            (1.0, 1.0),
            (0.0, 1.0),
            (-1.0, 1.0),
            (-1.0, 0.0),
            (-1.0, -1.0),
            (0.0, -1.0),
            (1.0, -1.0),
            (1.0, 0.0),
        ];
        let points = corners
            .iter()
            .map(|&(x, y)| center + DVec3::new(x * r, y * r, 0.0))
            .collect();
        let weights = (0..9)
            .map(|i| if i % 2 == 1 { HALF_SQRT2 } else { 1.0 })
            .collect();
        let knots = vec![
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
        ];
        Nurbs::try_new(points, weights, knots, 3)
    }
}

// The family: what the editor, the reports and the drawing need of every curve family.

/// The weight of a point inserted on leg `leg` at fraction `s`: the legs' weights
/// interpolated.
fn weight_on_leg(weights: &[f64], leg: usize, s: f64) -> f64 {
    let (a, b) = (weights[leg], weights[(leg + 1).min(weights.len() - 1)]);
    a + (b - a) * s
}

/// Weights for generated curves: a fixed cycle in `[0.5, 2]`, so that every generated
/// rational curve exercises the division.
fn generated_weights(n: usize) -> Vec<f64> {
    const CYCLE: [f64; 4] = [1.0, 2.0, 0.5, 1.5];
    (0..n).map(|i| CYCLE[i % CYCLE.len()]).collect()
}

impl Family for RationalBezier {
    const NAME: &'static str = "rational_bezier";

    fn control_points(&self) -> &[DVec3] {
        &self.points
    }

    fn with_control_points(&self, points: Vec<DVec3>) -> Result<RationalBezier, GeomError> {
        RationalBezier::try_new(points, self.weights.clone())
    }

    fn with_point_on_polygon(&self, at: DVec3) -> Result<(RationalBezier, usize), GeomError> {
        let (points, leg, s) = crate::geom::structure::insert_on_polygon(&self.points, at);
        let mut weights = self.weights.clone();
        weights.insert(leg + 1, weight_on_leg(&self.weights, leg, s));
        Ok((RationalBezier::try_new(points, weights)?, leg + 1))
    }

    fn with_point_removed(&self, index: usize) -> Result<RationalBezier, GeomError> {
        let points = crate::geom::structure::without(&self.points, index, 2, Self::NAME)?;
        let mut weights = self.weights.clone();
        weights.remove(index);
        RationalBezier::try_new(points, weights)
    }

    /// Degree `degree`, its weights cycling through `1, 2, 0.5, 1.5`.
    fn generated(
        degree: usize,
        point: &mut dyn FnMut() -> DVec3,
    ) -> Result<RationalBezier, GeomError> {
        let points: Vec<DVec3> = (0..=degree).map(|_| point()).collect();
        let weights = generated_weights(points.len());
        RationalBezier::try_new(points, weights)
    }
}

impl Family for Nurbs {
    const NAME: &'static str = "nurbs";

    fn control_points(&self) -> &[DVec3] {
        &self.points
    }

    fn with_control_points(&self, points: Vec<DVec3>) -> Result<Nurbs, GeomError> {
        Nurbs::from_knot_vector(points, self.weights.clone(), self.knots().clone())
    }

    fn derived_field(&self) -> &'static str {
        "knots"
    }

    fn inserts_by_knot(&self) -> bool {
        true
    }

    fn with_knot_inserted(&self, t: f64) -> Result<Nurbs, GeomError> {
        self.insert_knot(t)
    }

    fn with_point_removed(&self, index: usize) -> Result<Nurbs, GeomError> {
        let (points, knots) =
            crate::geom::structure::spline_without(&self.points, self.knots(), index, Self::NAME)?;
        let mut weights = self.weights.clone();
        weights.remove(index);
        Nurbs::try_new(points, weights, knots, self.order())
    }

    /// The clamped uniform NURBS curve of order `degree + 1` on `degree + 4` points (four
    /// rational Bézier segments), its weights cycling through `1, 2, 0.5, 1.5`.
    fn generated(degree: usize, point: &mut dyn FnMut() -> DVec3) -> Result<Nurbs, GeomError> {
        let points: Vec<DVec3> = (0..degree + 4).map(|_| point()).collect();
        let knots = KnotVector::clamped_uniform(degree + 1, points.len())?;
        let weights = generated_weights(points.len());
        Nurbs::from_knot_vector(points, weights, knots)
    }
}
