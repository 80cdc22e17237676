//! The modified Bézier curve of paper 002 (Bożek & Sroda, "Modyfikacja wielomianowych
//! krzywych Béziera"): a Bézier curve plus a C¹ bump times a vector. The formulas and the
//! decisions taken (the factored bump): `docs/math.md` §1.

use glam::DVec3;

use super::Aabb;
use super::family::{Family, lowered_box};
use super::{Bezier, BezierSegment, GeomError, Lower, ParamCurve};

/// The bump `S` of paper 002 for `t* ∈ (0, 1)`:
///
/// `S(t) = (2 t t* − t²) / t*²` on `[0, t*]`,
/// `S(t) = (2 t t* − t² − 2t* + 1) / (t* − 1)²` on `[t*, 1]`.
///
/// `S` is C¹ with `S(0) = S(1) = 0`, `S(t*) = 1`, `S′(t*) = 0`. Evaluated in the factored
/// form `1 − (1 − t/t*)²` and `1 − ((t − t*)/(1 − t*))²`, which rounds less than the
/// expanded one (1 ulp from 8/9 at `t* = 0.7, t = 0.8`, where the expanded form is 17 ulp
/// off) and cannot divide by an underflowed `t*²`.
#[must_use]
pub fn bump(t: f64, t_star: f64) -> f64 {
    let r = if t <= t_star {
        1.0 - t / t_star
    } else {
        (t - t_star) / (1.0 - t_star)
    };
    1.0 - r * r
}

/// `S′(t)`: `(2/t*)(1 − t/t*)` on `[0, t*]`, `−(2/(1 − t*))·(t − t*)/(1 − t*)` on `[t*, 1]`
/// (the factored forms of `(2t* − 2t)/t*²` and `(2t* − 2t)/(t* − 1)²`).
#[must_use]
pub fn bump_deriv(t: f64, t_star: f64) -> f64 {
    if t <= t_star {
        2.0 / t_star * (1.0 - t / t_star)
    } else {
        -2.0 / (1.0 - t_star) * ((t - t_star) / (1.0 - t_star))
    }
}

/// `S″(t)`: `−2/t*²` on `[0, t*)`, `−2/(t* − 1)²` on `(t*, 1]` (the right value at `t*`).
#[must_use]
pub fn bump_second_deriv(t: f64, t_star: f64) -> f64 {
    if t < t_star {
        -2.0 / (t_star * t_star)
    } else {
        -2.0 / ((t_star - 1.0) * (t_star - 1.0))
    }
}

/// Checks `t* ∈ (0, 1)`.
pub(crate) fn check_t_star(t_star: f64) -> Result<(), GeomError> {
    if !(t_star > 0.0 && t_star < 1.0) {
        return Err(GeomError::TStarOutside { value: t_star });
    }
    // The bump's derivatives must be numbers too: S″ = −2/t*² on the left piece.
    for (what, value) in [
        (
            "the bump's second derivative −2/t*²",
            bump_second_deriv(0.0, t_star),
        ),
        (
            "the bump's second derivative −2/(1 − t*)²",
            bump_second_deriv(1.0, t_star),
        ),
    ] {
        if !value.is_finite() {
            return Err(GeomError::DerivedNotFinite {
                field: "t_star",
                what: what.into(),
                value,
            });
        }
    }
    Ok(())
}

/// Checks every coordinate of `v` is finite.
pub(crate) fn check_vector(v: DVec3) -> Result<(), GeomError> {
    match v.to_array().into_iter().find(|c| !c.is_finite()) {
        Some(value) => Err(GeomError::NonFiniteVector { value }),
        None => Ok(()),
    }
}

/// The modified Bézier curve of paper 002, §4:
///
/// `R(t) = Q(t) + S(t) v`, `t ∈ [0, 1]`,
///
/// with `Q` a Bézier curve of degree `n`, `S` the C¹ [`bump`] peaking at `t* ∈ (0, 1)` and
/// `v` a vector. `R(0) = P_0`, `R(1) = P_n`, `R′(0) = n(P_1 − P_0) + (2/t*) v`,
/// `R′(1) = n(P_n − P_{n−1}) + (2/(t* − 1)) v`.
///
/// `R` is exactly two Bézier pieces: `Q` split at `t*`, plus `v` times the bump, whose
/// quadratic Bernstein coefficients are `(0, 1, 1)` on `[0, t*]` and `(1, 1, 0)` on
/// `[t*, 1]`, both elevated to degree `max(n, 2)`.
#[derive(Debug, Clone, PartialEq)]
pub struct ModifiedBezier {
    pub(crate) base: Bezier,
    pub(crate) t_star: f64,
    pub(crate) v: DVec3,
}

impl ModifiedBezier {
    /// `R = Q + S v`.
    ///
    /// # Errors
    /// [`GeomError::TStarOutside`] unless `0 < t* < 1`; [`GeomError::NonFiniteVector`].
    pub fn try_new(base: Bezier, t_star: f64, v: DVec3) -> Result<ModifiedBezier, GeomError> {
        check_t_star(t_star)?;
        check_vector(v)?;
        Ok(ModifiedBezier { base, t_star, v })
    }

    /// The Bézier curve `Q`.
    #[must_use]
    pub fn base(&self) -> &Bezier {
        &self.base
    }

    /// `t*`.
    #[must_use]
    pub fn t_star(&self) -> f64 {
        self.t_star
    }

    /// `v`.
    #[must_use]
    pub fn v(&self) -> DVec3 {
        self.v
    }

    /// The two exact Bézier pieces, on `[0, t*]` and `[t*, 1]`, of degree `max(n, 2)`.
    #[must_use]
    pub fn pieces(&self) -> [Bezier; 2] {
        let m = self.base.degree().max(2);
        let (left, right) = self.base.split(self.t_star);
        let add_bump = |piece: Bezier, coeffs: [f64; 3]| {
            let bump =
                Bezier::new(coeffs.iter().map(|&c| DVec3::splat(c)).collect()).elevated_to(m);
            let pts = piece
                .elevated_to(m)
                .points()
                .iter()
                .zip(bump.points())
                .map(|(&p, b)| p + b.x * self.v)
                .collect();
            Bezier::new(pts)
        };
        [
            add_bump(left, [0.0, 1.0, 1.0]),
            add_bump(right, [1.0, 1.0, 0.0]),
        ]
    }
}

impl ParamCurve for ModifiedBezier {
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn eval(&self, t: f64) -> DVec3 {
        self.base.eval(t) + bump(t, self.t_star) * self.v
    }
    fn eval_deriv(&self, t: f64) -> DVec3 {
        self.base.eval_deriv(t) + bump_deriv(t, self.t_star) * self.v
    }
    fn eval_second_deriv(&self, t: f64) -> DVec3 {
        self.base.eval_second_deriv(t) + bump_second_deriv(t, self.t_star) * self.v
    }
}

impl Lower for ModifiedBezier {
    fn lower(&self) -> Vec<BezierSegment> {
        let [left, right] = self.pieces();
        vec![
            BezierSegment::polynomial(left, 0.0, self.t_star),
            BezierSegment::polynomial(right, self.t_star, 1.0),
        ]
    }
}

// The family: what the editor, the reports and the drawing need of every curve family.

impl Family for ModifiedBezier {
    const NAME: &'static str = "modified_bezier";

    fn with_point_on_polygon(&self, at: DVec3) -> Result<(ModifiedBezier, usize), GeomError> {
        let (points, leg, _) = crate::geom::structure::insert_on_polygon(self.base().points(), at);
        let base = Bezier::try_new(points)?;
        Ok((
            ModifiedBezier::try_new(base, self.t_star(), self.v())?,
            leg + 1,
        ))
    }

    fn with_point_removed(&self, index: usize) -> Result<ModifiedBezier, GeomError> {
        let points = crate::geom::structure::without(self.base().points(), index, 2, Self::NAME)?;
        ModifiedBezier::try_new(Bezier::try_new(points)?, self.t_star(), self.v())
    }

    /// The base `Q` of `degree` from `point`, `t* = 1/2`, and `v` a quarter of the
    /// difference of two more points.
    fn generated(
        degree: usize,
        point: &mut dyn FnMut() -> DVec3,
    ) -> Result<ModifiedBezier, GeomError> {
        let base = Bezier::generated(degree, point)?;
        let v = 0.25 * (point() - point());
        ModifiedBezier::try_new(base, 0.5, v)
    }

    fn control_points(&self) -> &[DVec3] {
        self.base.points()
    }

    fn with_control_points(&self, points: Vec<DVec3>) -> Result<ModifiedBezier, GeomError> {
        ModifiedBezier::try_new(Bezier::try_new(points)?, self.t_star, self.v)
    }

    /// The modified curve leaves its base's hull: it is bounded by its two pieces.
    fn control_box(&self) -> Aabb {
        lowered_box(self)
    }

    fn is_planar(&self) -> bool {
        self.base.points().iter().all(|p| p.z == 0.0) && self.v.z == 0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The factored bump against exact rational arithmetic on the same `f64` inputs.
    #[test]
    fn bump_is_within_a_few_ulp_of_the_exact_value() {
        use crate::geom::exact::{Scalar, rational_from_f64};
        let exact = |t: f64, ts: f64| {
            let (t, ts) = (
                rational_from_f64(t).unwrap(),
                rational_from_f64(ts).unwrap(),
            );
            let one = crate::geom::exact::Rational::one();
            let r = if t <= ts {
                one.clone() - t / ts
            } else {
                (t - ts.clone()) / (one.clone() - ts)
            };
            (one - r.clone() * r).to_f64()
        };
        assert!((bump(0.8, 0.7) - 8.0 / 9.0).abs() <= f64::EPSILON);
        let mut worst = 0.0_f64;
        for i in 1..40 {
            let ts = f64::from(i) / 40.0;
            for j in 0..=100 {
                let t = f64::from(j) / 100.0;
                let want = exact(t, ts);
                let err = (bump(t, ts) - want).abs();
                worst = worst.max(err);
                assert!(err <= 4.0 * f64::EPSILON, "t* = {ts}, t = {t}: {err:e}");
            }
        }
        assert!(worst > 0.0, "the comparison is not vacuous");
        // A t* so small that t*² underflows: S is still a number, and the curve is
        // refused only because S″ = −2/t*² is not.
        assert_eq!(bump(0.0, 5e-324), 0.0);
        assert!(check_t_star(5e-324).is_err());
        assert!(check_t_star(1e-100).is_ok());
    }

    #[test]
    fn bump_meets_its_c1_conditions() {
        for &ts in &[0.1, 0.25, 0.5, 0.7, 0.93] {
            assert_eq!(bump(0.0, ts), 0.0);
            assert!(bump(1.0, ts).abs() < 1e-15);
            assert!((bump(ts, ts) - 1.0).abs() < 1e-15);
            assert!((bump_deriv(0.0, ts) - 2.0 / ts).abs() < 1e-12);
            assert_eq!(bump_deriv(ts, ts), 0.0);
            assert!((bump_deriv(1.0, ts) - 2.0 / (ts - 1.0)).abs() < 1e-12);
            // Both formulas agree at t* (value and slope): C¹ across the joint.
            let right_value =
                (2.0 * ts * ts - ts * ts - 2.0 * ts + 1.0) / ((ts - 1.0) * (ts - 1.0));
            assert!((right_value - 1.0).abs() < 1e-14);
            // The derivative matches central differences on both sides.
            for &t in &[0.3 * ts, ts + 0.4 * (1.0 - ts)] {
                let h = 1e-6;
                let fd = (bump(t + h, ts) - bump(t - h, ts)) / (2.0 * h);
                assert!((fd - bump_deriv(t, ts)).abs() < 1e-7);
            }
        }
    }

    #[test]
    fn modified_curve_end_conditions_match_the_paper() {
        // Paper 002, Fig. 1 control points.
        let pts = [
            (-1., 1.),
            (-2., 1.),
            (3., 3.),
            (5., 2.),
            (7., 0.),
            (4., -1.),
        ]
        .map(|(x, y)| DVec3::new(x, y, 0.0));
        let q = Bezier::new(pts.to_vec());
        let v = DVec3::new(1.0, 2.0, 0.0);
        let r = ModifiedBezier::try_new(q.clone(), 0.4, v).unwrap();
        assert_eq!(r.eval(0.0), pts[0]);
        assert!((r.eval(1.0) - pts[5]).length() < 1e-14);
        let n = 5.0;
        assert!((r.eval_deriv(0.0) - (n * (pts[1] - pts[0]) + (2.0 / 0.4) * v)).length() < 1e-12);
        assert!(
            (r.eval_deriv(1.0) - (n * (pts[5] - pts[4]) + (2.0 / (0.4 - 1.0)) * v)).length()
                < 1e-12
        );
        assert!((r.eval(0.4) - (q.eval(0.4) + v)).length() < 1e-14);
    }

    #[test]
    fn t_star_outside_the_open_interval_is_an_error() {
        let q = Bezier::new(vec![DVec3::ZERO, DVec3::X]);
        for bad in [0.0, 1.0, -0.2, 1.5, f64::NAN] {
            assert!(matches!(
                ModifiedBezier::try_new(q.clone(), bad, DVec3::Y),
                Err(GeomError::TStarOutside { .. })
            ));
        }
    }
}
