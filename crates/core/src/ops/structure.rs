//! The small operations every curve library has, exact: a curve as a path of its exact
//! Bézier segments, split at a parameter, reversed, and curves joined end to end.
//!
//! A Bézier or rational Bézier curve splits into two of its own family (de Casteljau, in
//! homogeneous coordinates for a rational one); a path into two paths
//! ([`Path::between`]); every other family into two paths of its exact segments (its
//! lowering). Reversing keeps the family where it has one (a B-spline's and a NURBS
//! curve's knots mirrored about the domain's middle), else gives the reversed path.

use crate::geom::{
    BSpline, BezierSegment, Curve, GeomError, Lower, Nurbs, ParamCurve, Path, PathSegment,
    RationalBezier,
};

use super::OpError;

/// A lowered segment as a path segment: its points and, for a rational one, weights.
fn path_segment(s: &BezierSegment) -> PathSegment {
    match &s.weights {
        Some(w) => PathSegment::rational(s.bezier.points().to_vec(), w.clone()),
        None => PathSegment::polynomial(s.bezier.points().to_vec()),
    }
}

/// `curve` as a path of its exact Bézier segments (its lowering), closed for a closed
/// path. Its parameter changes (segment `k` covers `[k, k + 1]`); its points do not.
///
/// # Errors
/// [`OpError::Geom`] when the lowering's segments do not join (not a curve the families
/// make).
pub fn as_path(curve: &Curve) -> Result<Path, OpError> {
    if let Curve::Path(p) = curve {
        return Ok(p.clone());
    }
    let segments: Vec<PathSegment> = curve.lower().iter().map(path_segment).collect();
    Path::try_new(segments, false).map_err(OpError::Geom)
}

/// `curve` split at `t` (inside its domain) into the curves before and after it.
///
/// # Errors
/// [`OpError::Geom`] ([`GeomError::ParameterOutsideDomain`]) for a `t` at or outside the
/// domain's ends.
pub fn split(curve: &Curve, t: f64) -> Result<(Curve, Curve), OpError> {
    let (a, b) = curve.domain();
    if !(t > a && t < b) {
        return Err(OpError::Geom(GeomError::ParameterOutsideDomain {
            value: t,
            start: a,
            end: b,
        }));
    }
    Ok(match curve {
        Curve::Bezier(c) => {
            let (l, r) = c.split((t - a) / (b - a));
            (Curve::Bezier(l), Curve::Bezier(r))
        }
        Curve::RationalBezier(c) => {
            let u = (t - a) / (b - a);
            (
                Curve::RationalBezier(c.subsegment(0.0, u)),
                Curve::RationalBezier(c.subsegment(u, 1.0)),
            )
        }
        _ => {
            // The path's parameter at `t`: the lowered segment holding it, and where.
            let lowered = curve.lower();
            let k = lowered
                .iter()
                .position(|s| t < s.t1)
                .unwrap_or(lowered.len() - 1);
            let s = &lowered[k];
            let at = k as f64 + (t - s.t0) / (s.t1 - s.t0);
            let path = as_path(curve)?;
            let end = path.segments().len() as f64;
            (
                Curve::Path(path.between(0.0, at).map_err(OpError::Geom)?),
                Curve::Path(path.between(at, end).map_err(OpError::Geom)?),
            )
        }
    })
}

/// `curve` traced the other way: the same points, `C_reversed(a + b − t) = C(t)` for a
/// Bézier, rational Bézier, B-spline or NURBS curve (which keep their family); every
/// other family as the reversed path of its exact segments.
///
/// # Errors
/// [`OpError::Geom`] when the result is not a valid curve (not for curves the families
/// make).
pub fn reverse(curve: &Curve) -> Result<Curve, OpError> {
    let geom = OpError::Geom;
    Ok(match curve {
        Curve::Bezier(c) => Curve::Bezier(c.reversed()),
        Curve::RationalBezier(c) => {
            let mut p = c.points().to_vec();
            let mut w = c.weights().to_vec();
            p.reverse();
            w.reverse();
            Curve::RationalBezier(RationalBezier::try_new(p, w).map_err(geom)?)
        }
        Curve::BSpline(c) => {
            let (knots, points) = mirrored(c.knots().knots(), c.points());
            Curve::BSpline(BSpline::try_new(points, knots, c.order()).map_err(geom)?)
        }
        Curve::Nurbs(c) => {
            let (knots, points) = mirrored(c.knots().knots(), c.points());
            let mut w = c.weights().to_vec();
            w.reverse();
            Curve::Nurbs(Nurbs::try_new(points, w, knots, c.order()).map_err(geom)?)
        }
        _ => {
            let path = as_path(curve)?;
            let mut segments: Vec<PathSegment> = path
                .segments()
                .iter()
                .map(|s| {
                    let mut r = s.clone();
                    r.points.reverse();
                    if let Some(w) = &mut r.weights {
                        w.reverse();
                    }
                    r
                })
                .collect();
            segments.reverse();
            Curve::Path(Path::try_new(segments, path.is_closed()).map_err(geom)?)
        }
    })
}

/// Knots mirrored about the domain's middle (`k ↦ a + b − k`, in reverse order) and the
/// points reversed.
fn mirrored(knots: &[f64], points: &[glam::DVec3]) -> (Vec<f64>, Vec<glam::DVec3>) {
    let (first, last) = (knots[0], knots[knots.len() - 1]);
    let k: Vec<f64> = knots.iter().rev().map(|&x| first + last - x).collect();
    let mut p = points.to_vec();
    p.reverse();
    (k, p)
}

/// `curves` joined end to end into one path of their exact segments, in order (each must
/// start where the one before ends, to the rounding of its coordinates); `closed` when the
/// last ends where the first starts and a closed path is asked for.
///
/// # Errors
/// [`OpError::NothingToJoin`] for no curves; [`OpError::Geom`]
/// ([`GeomError::PathGap`]) naming the joint where a curve does not start where the one
/// before ends.
pub fn join(curves: &[Curve], closed: bool) -> Result<Path, OpError> {
    if curves.is_empty() {
        return Err(OpError::NothingToJoin);
    }
    let mut segments = Vec::new();
    for c in curves {
        let path = as_path(c)?;
        segments.extend(path.segments().iter().cloned());
    }
    Path::try_new(segments, closed).map_err(OpError::Geom)
}
