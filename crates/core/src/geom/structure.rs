//! Structural edits of a curve: inserting and removing control points.
//!
//! - Bézier curves (plain, the base `Q` of a modified one, and the interpolated points of
//!   cubic interpolation): a point is inserted on the control polygon's leg nearest to it
//!   and removed outright. The curve changes shape (so does its degree, or for
//!   interpolation the number of pieces): the user asked for a new point there.
//! - B-splines and standard NUBMP curves (paper 001): a point is inserted by inserting a
//!   knot (Boehm's algorithm), which keeps the curve; removing point `i` removes it with
//!   the interior knot nearest its Greville abscissa, so the knot count stays `n + k`.
//!   NUBMP curves whose shape parameters differ from the standard values are refused:
//!   the groups of the new knot vector would no longer correspond to the old ones.

use glam::DVec3;

use super::{BSpline, Bezier, CubicInterpolation, Curve, GeomError, KnotVector, ModifiedBezier};
use super::{Family, Nubmp};

fn refused(family: &'static str, reason: impl Into<String>) -> GeomError {
    GeomError::StructureRefused {
        family,
        reason: reason.into(),
    }
}

/// The leg `(i, i + 1)` of `polygon` nearest to `at`, and where along it (`0..=1`) the
/// nearest point lies.
fn nearest_leg(polygon: &[DVec3], at: DVec3) -> (usize, f64) {
    let mut best = (0, 0.5, f64::INFINITY);
    for (i, w) in polygon.windows(2).enumerate() {
        let d = w[1] - w[0];
        let len2 = d.length_squared();
        let s = if len2 > 0.0 {
            ((at - w[0]).dot(d) / len2).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let dist = (w[0] + s * d - at).length_squared();
        if dist < best.2 {
            best = (i, s, dist);
        }
    }
    (best.0, best.1)
}

impl Curve {
    /// Whether points are inserted by knot insertion at a curve parameter
    /// ([`Curve::with_knot_inserted`]) rather than on the control polygon
    /// ([`Curve::with_point_on_polygon`]).
    #[must_use]
    pub fn inserts_by_knot(&self) -> bool {
        matches!(self, Curve::BSpline(_) | Curve::Nubmp(_))
    }

    /// The curve with a new control point `at`, placed on the control polygon's leg
    /// nearest to it (Bézier, modified Bézier, interpolation); returns the curve and the
    /// new point's index. For interpolation the new point's parameter lies between its
    /// neighbours' in proportion to where `at` projects on the leg.
    ///
    /// # Errors
    /// [`GeomError::StructureRefused`] for B-splines and NUBMP curves (use
    /// [`Curve::with_knot_inserted`]), [`GeomError::NonFinitePoint`] for a non-finite
    /// `at`, or the family's own error.
    pub fn with_point_on_polygon(&self, at: DVec3) -> Result<(Curve, usize), GeomError> {
        super::bezier::check_finite(&[at])?;
        let insert = |pts: &[DVec3]| {
            let (leg, s) = nearest_leg(pts, at);
            let mut out = pts.to_vec();
            out.insert(leg + 1, at);
            (out, leg, s)
        };
        match self {
            Curve::Bezier(b) => {
                let (pts, leg, _) = insert(b.points());
                Ok((Curve::Bezier(Bezier::try_new(pts)?), leg + 1))
            }
            Curve::Modified(m) => {
                let (pts, leg, _) = insert(m.base().points());
                let base = Bezier::try_new(pts)?;
                Ok((
                    Curve::Modified(ModifiedBezier::try_new(base, m.t_star(), m.v())?),
                    leg + 1,
                ))
            }
            Curve::Interpolation(c) => {
                let (pts, leg, s) = insert(c.points());
                let mut params = c.params().to_vec();
                let t = params[leg] + s.clamp(0.05, 0.95) * (params[leg + 1] - params[leg]);
                params.insert(leg + 1, t);
                Ok((
                    Curve::Interpolation(CubicInterpolation::try_new(
                        pts,
                        Some(params),
                        c.modification(),
                    )?),
                    leg + 1,
                ))
            }
            Curve::BSpline(_) | Curve::Nubmp(_) => Err(refused(
                self.family(),
                "points are inserted by knot insertion at a curve parameter",
            )),
        }
    }

    /// The curve with the knot `t` inserted (B-splines and standard NUBMP curves): one
    /// more control point and the same curve (Boehm).
    ///
    /// # Errors
    /// [`GeomError::StructureRefused`] for the Bézier families and for NUBMP curves whose
    /// shape parameters are not standard; the knot vector's error when `t` lies outside
    /// the domain or would repeat more than `k − 1` times.
    pub fn with_knot_inserted(&self, t: f64) -> Result<Curve, GeomError> {
        match self {
            Curve::BSpline(b) => Ok(Curve::BSpline(b.insert_knot(t)?)),
            Curve::Nubmp(n) => {
                if !n.is_standard() {
                    return Err(refused(
                        <Nubmp as Family>::NAME,
                        "reset the shape parameters to the standard curve before inserting a knot (the groups of the new knot vector differ)",
                    ));
                }
                let b = BSpline::from_parts(n.points().to_vec(), n.knots().clone())?;
                let b = b.insert_knot(t)?;
                Ok(Curve::Nubmp(Nubmp::standard(
                    b.points().to_vec(),
                    b.knots().clone(),
                )?))
            }
            _ => Err(refused(
                self.family(),
                "points are inserted on the control polygon",
            )),
        }
    }

    /// The curve without control point `index`. Bézier families lose the point (a Bézier
    /// curve keeps at least 2, interpolation at least 2); B-splines and NUBMP curves lose
    /// it with the interior knot nearest its Greville abscissa and keep at least `k`
    /// points; NUBMP curves are rebuilt with standard shape parameters only when they had
    /// them (otherwise refused).
    ///
    /// # Errors
    /// [`GeomError::NoSuchPoint`], [`GeomError::StructureRefused`] or the family's own
    /// error.
    pub fn with_point_removed(&self, index: usize) -> Result<Curve, GeomError> {
        let count = self.control_points().len();
        if index >= count {
            return Err(GeomError::NoSuchPoint { index, count });
        }
        let without = |pts: &[DVec3]| {
            let mut out = pts.to_vec();
            out.remove(index);
            out
        };
        let too_few = |min: usize| {
            refused(
                self.family(),
                format!("a curve of this kind keeps at least {min} points"),
            )
        };
        match self {
            Curve::Bezier(b) => {
                if count <= 2 {
                    return Err(too_few(2));
                }
                Ok(Curve::Bezier(Bezier::try_new(without(b.points()))?))
            }
            Curve::Modified(m) => {
                if count <= 2 {
                    return Err(too_few(2));
                }
                let base = Bezier::try_new(without(m.base().points()))?;
                Ok(Curve::Modified(ModifiedBezier::try_new(
                    base,
                    m.t_star(),
                    m.v(),
                )?))
            }
            Curve::Interpolation(c) => {
                if count <= 2 {
                    return Err(too_few(2));
                }
                let mut params = c.params().to_vec();
                params.remove(index);
                Ok(Curve::Interpolation(CubicInterpolation::try_new(
                    without(c.points()),
                    Some(params),
                    c.modification(),
                )?))
            }
            Curve::BSpline(b) => {
                let (pts, knots) = spline_without(b.points(), b.knots(), index, self.family())?;
                Ok(Curve::BSpline(BSpline::try_new(pts, knots, b.order())?))
            }
            Curve::Nubmp(n) => {
                if !n.is_standard() {
                    return Err(refused(
                        <Nubmp as Family>::NAME,
                        "reset the shape parameters to the standard curve before removing a point (the groups of the new knot vector differ)",
                    ));
                }
                let (pts, knots) = spline_without(n.points(), n.knots(), index, self.family())?;
                Ok(Curve::Nubmp(Nubmp::try_new(pts, knots, n.order())?))
            }
        }
    }
}

/// Point `index` removed with the interior knot nearest its Greville abscissa.
fn spline_without(
    points: &[DVec3],
    knots: &KnotVector,
    index: usize,
    family: &'static str,
) -> Result<(Vec<DVec3>, Vec<f64>), GeomError> {
    let k = knots.order();
    let n = points.len();
    if n <= k {
        return Err(refused(
            family,
            format!("an order-{k} spline keeps at least {k} points"),
        ));
    }
    let t = knots.knots();
    // Greville abscissa of point i: the mean of t_{i+1} .. t_{i+k−1}.
    let greville = t[index + 1..index + k].iter().sum::<f64>() / (k - 1) as f64;
    // Interior knots are t_k .. t_{n−1}.
    let drop = (k..n)
        .min_by(|&a, &b| (t[a] - greville).abs().total_cmp(&(t[b] - greville).abs()))
        .unwrap_or(k);
    let mut pts = points.to_vec();
    pts.remove(index);
    let mut kn = t.to_vec();
    kn.remove(drop);
    Ok((pts, kn))
}
