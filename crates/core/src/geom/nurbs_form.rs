//! Every curve as one NURBS: degree, knots, control points and (for a rational curve)
//! weights — what exchange formats (DXF `SPLINE`, STEP `B_SPLINE_CURVE_WITH_KNOTS`) store.
//!
//! B-splines, NURBS and Bézier curves (plain and rational) are written as they are: their
//! own points, weights and knots, nothing recomputed. Every other family (the modified
//! Bézier curve, cubic interpolation, NUBMP, paths) goes through its exact lowering
//! ([`Lower`]): the Bézier pieces are raised to the highest degree among them, made
//! rational when any one is (weights 1; a rational piece's weights scaled so that it
//! meets the piece before it with the same weight — scaling every weight of a rational
//! Bézier curve does not move it), and joined with knots of multiplicity `p` at the
//! pieces' parameters, so the NURBS covers the same parameter range as the curve and
//! passes through the same points (to rounding in the elevation).

use glam::DVec3;

use super::{Bezier, BezierSegment, Curve, Lower, Nurbs, RationalBezier};

/// A curve written as a NURBS (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsForm {
    /// The degree `p`.
    pub degree: usize,
    /// The knots: `points.len() + p + 1` of them, non-decreasing.
    pub knots: Vec<f64>,
    /// The control points.
    pub points: Vec<DVec3>,
    /// One weight per point for a rational curve; `None` for a polynomial one.
    pub weights: Option<Vec<f64>>,
}

impl NurbsForm {
    /// The form of `curve`.
    #[must_use]
    pub fn of(curve: &Curve) -> NurbsForm {
        match curve {
            Curve::Bezier(b) => clamped(b.points().to_vec(), None),
            Curve::RationalBezier(r) => clamped(r.points().to_vec(), Some(r.weights().to_vec())),
            Curve::BSpline(b) => NurbsForm {
                degree: b.order() - 1,
                knots: b.knots().knots().to_vec(),
                points: b.points().to_vec(),
                weights: None,
            },
            Curve::Nurbs(n) => NurbsForm {
                degree: n.order() - 1,
                knots: n.knots().knots().to_vec(),
                points: n.points().to_vec(),
                weights: Some(n.weights().to_vec()),
            },
            other => from_segments(&other.lower()),
        }
    }

    /// The form as a [`Nurbs`] curve (weights 1 for a polynomial form).
    ///
    /// # Errors
    /// [`super::GeomError`] when the form is not a valid NURBS (it always is for a form
    /// made by [`NurbsForm::of`]; a form read from a file may not be).
    pub fn to_nurbs(&self) -> Result<Nurbs, super::GeomError> {
        Nurbs::try_new(
            self.points.clone(),
            self.weights
                .clone()
                .unwrap_or_else(|| vec![1.0; self.points.len()]),
            self.knots.clone(),
            self.degree + 1,
        )
    }
}

/// A Bézier curve's form: knots `0` and `1`, each `p + 1` times.
fn clamped(points: Vec<DVec3>, weights: Option<Vec<f64>>) -> NurbsForm {
    let p = points.len() - 1;
    let mut knots = vec![0.0; p + 1];
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    NurbsForm {
        degree: p,
        knots,
        points,
        weights,
    }
}

/// Lowered pieces joined into one NURBS (see the [module docs](self)).
fn from_segments(segments: &[BezierSegment]) -> NurbsForm {
    let p = super::max_degree(segments);
    let rational = segments.iter().any(BezierSegment::is_rational);
    let mut knots = Vec::new();
    let mut points: Vec<DVec3> = Vec::new();
    let mut weights: Vec<f64> = Vec::new();
    for (k, s) in segments.iter().enumerate() {
        let (pts, ws) = raised(s, p, rational);
        let skip = usize::from(k > 0);
        let scale = match (weights.last(), ws.first()) {
            (Some(&before), Some(&first)) if k > 0 => before / first,
            _ => 1.0,
        };
        if k == 0 {
            knots.extend(std::iter::repeat_n(s.t0, p + 1));
        }
        knots.extend(std::iter::repeat_n(s.t1, p));
        points.extend_from_slice(&pts[skip..]);
        if rational {
            weights.extend(ws[skip..].iter().map(|w| w * scale));
        }
    }
    if let Some(&last) = knots.last() {
        knots.push(last);
    }
    NurbsForm {
        degree: p,
        knots,
        points,
        weights: rational.then_some(weights),
    }
}

/// A piece's points (and weights, when the whole is rational) raised to degree `p`.
fn raised(s: &BezierSegment, p: usize, rational: bool) -> (Vec<DVec3>, Vec<f64>) {
    match &s.weights {
        Some(w) => {
            // Weights are positive and points finite in a lowered piece.
            let mut r = RationalBezier::try_new(s.points().to_vec(), w.clone())
                .unwrap_or_else(|_| unreachable!("a lowered rational piece is valid"));
            while r.degree() < p {
                r = r.elevate();
            }
            (r.points().to_vec(), r.weights().to_vec())
        }
        None => {
            let b: Bezier = s.bezier.elevated_to(p);
            let n = b.points().len();
            (
                b.points().to_vec(),
                if rational { vec![1.0; n] } else { Vec::new() },
            )
        }
    }
}
