//! Knot removal (Tiller's algorithm, *The NURBS Book* §5.4) for B-spline and NURBS curves
//! (and a standard NUBMP curve, through its B-spline),
//! within a tolerance, with the distance the curve moves **proven**, not estimated.
//!
//! Removing a knot once solves for the `p − s` new control points around it (`p` the
//! degree, `s` the knot's multiplicity) from both sides: from the left,
//! `Q_i = (P_i − (1 − α_i) Q_{i−1}) / α_i`, from the right,
//! `Q_{j−1} = (P_j − α_j Q_j) / (1 − α_j)`, `α_i = (u − u_i) / (u_{i+p+1} − u_i)`; the first
//! half is taken from the left and the rest from the right (a NURBS curve's in homogeneous
//! coordinates `(w P, w)`). The knot is exactly removable when both sides agree; otherwise
//! the curve moves.
//!
//! **The bound.** The knot is inserted back (`times` times, by the family's own knot
//! insertion, which does not move a curve) into the result: it then has the original's knot vector, so the two
//! differ by `Σ N_i (A_i − A′_i)` with the same basis `N_i ≥ 0`, `Σ N_i = 1`. For a
//! B-spline, `|C(t) − C′(t)| ≤ max_i |P_i − P′_i|`. For a NURBS curve with `C = A / W`,
//! `C − C′ = ((A − A′) − C′ (W − W′)) / W`, so `|C − C′| ≤ (max_i |ΔA_i| + max_j |P′_j| ·
//! max_i |ΔW_i|) / min_i W_i` (coordinates taken about the control points' centre, which
//! makes `|P′_j|` the curve's own size). The knot is removed when that bound is within the
//! tolerance; otherwise the refusal names it.

use glam::{DVec3, DVec4};

use crate::geom::{BSpline, Curve, GeomError, Nubmp, Nurbs};

use super::OpError;

/// A curve with a knot removed, and the proven bound on how far it moved.
#[derive(Debug, Clone, PartialEq)]
pub struct Removed {
    /// The curve.
    pub curve: Curve,
    /// A bound on `max_t |C(t) − C′(t)|` (at most the tolerance).
    pub error: f64,
}

/// A B-spline's or NURBS curve's knots, order and homogeneous control points `(w P, w)`
/// (`w = 1` for a B-spline), and whether it is rational; `None` for another family.
fn homogeneous(curve: &Curve) -> Option<(Vec<f64>, usize, Vec<DVec4>, bool)> {
    match curve {
        Curve::BSpline(b) => Some((
            b.knots().knots().to_vec(),
            b.order(),
            b.points().iter().map(|p| p.extend(1.0)).collect(),
            false,
        )),
        Curve::Nurbs(n) => Some((
            n.knots().knots().to_vec(),
            n.order(),
            n.points()
                .iter()
                .zip(n.weights())
                .map(|(p, &w)| (*p * w).extend(w))
                .collect(),
            true,
        )),
        _ => None,
    }
}

/// One removal of the knot at index `r` (its last occurrence), multiplicity `s`.
fn remove_once(
    knots: &[f64],
    points: &[DVec4],
    p: usize,
    r: usize,
    s: usize,
) -> (Vec<f64>, Vec<DVec4>) {
    let u = knots[r];
    let first = r - p;
    let last = r - s;
    let alpha = |i: usize| (u - knots[i]) / (knots[i + p + 1] - knots[i]);
    // From the left: Q_{first−1} = P_{first−1}, then Q_i for i = first … last − 1.
    let mut left = vec![points[first - 1]];
    for (i, &point) in points.iter().enumerate().take(last).skip(first) {
        let a = alpha(i);
        let prev = left[left.len() - 1];
        left.push((point - (1.0 - a) * prev) / a);
    }
    // From the right: Q_last = P_{last+1}, then Q_{j−1} for j = last … first + 1.
    let mut right = vec![DVec4::ZERO; last - first + 1];
    right[last - first] = points[last + 1];
    for j in (first + 1..=last).rev() {
        let a = alpha(j);
        right[j - 1 - first] = (points[j] - a * right[j - first]) / (1.0 - a);
    }
    let count = last - first;
    let half = count.div_ceil(2);
    let mut out: Vec<DVec4> = points[..first].to_vec();
    for k in 0..count {
        out.push(if k < half { left[k + 1] } else { right[k] });
    }
    out.extend_from_slice(&points[last + 1..]);
    let mut k = knots.to_vec();
    k.remove(r);
    (k, out)
}

/// `curve` (a B-spline or NURBS curve) with the knot `u` removed `times` times, when the
/// curve moves by at most `tolerance` (the proven bound above); else a refusal naming the
/// bound it would reach.
///
/// # Errors
/// [`OpError::Tolerance`] for a tolerance that is negative or not finite (0 removes only a
/// knot whose removal does not move the curve, up to rounding);
/// [`OpError::NotAKnot`] when `u` is not an interior knot of the curve or is there fewer
/// than `times` times; [`OpError::Unsupported`] for another family; [`OpError::Geom`]
/// for a NUBMP curve whose shape parameters are set (it is refused until they are reset);
/// [`OpError::WouldMove`] naming the bound when it exceeds the tolerance;
/// [`OpError::Geom`] when the result is not a valid curve.
pub fn remove_knot(
    curve: &Curve,
    u: f64,
    times: usize,
    tolerance: f64,
) -> Result<Removed, OpError> {
    if !(tolerance.is_finite() && tolerance >= 0.0) {
        return Err(OpError::Tolerance(tolerance));
    }
    // A standard NUBMP curve is its B-spline (paper 001): the knot is removed there and
    // the result is the standard curve of the new spline; with shape parameters set the
    // groups of the new knot vector would not correspond to the old ones.
    if let Curve::Nubmp(n) = curve {
        if !n.is_standard() {
            return Err(OpError::Geom(GeomError::refused(
                "nubmp",
                "reset the shape parameters to the standard curve before removing a knot (the groups of the new knot vector differ)",
            )));
        }
        let spline =
            BSpline::from_parts(n.points().to_vec(), n.knots().clone()).map_err(OpError::Geom)?;
        let r = remove_knot(&Curve::BSpline(spline), u, times, tolerance)?;
        let Curve::BSpline(b) = r.curve else {
            unreachable!("a B-spline's knot removal gives a B-spline")
        };
        let back =
            Nubmp::standard(b.points().to_vec(), b.knots().clone()).map_err(OpError::Geom)?;
        return Ok(Removed {
            curve: Curve::Nubmp(back),
            error: r.error,
        });
    }
    let Some((knots, order, points, rational)) = homogeneous(curve) else {
        return Err(OpError::Unsupported {
            operation: "remove_knot",
            family: curve.family(),
            families: "B-spline and NURBS curves (a NUBMP curve through its B-spline)",
        });
    };
    let p = order - 1;
    let (a, b) = (knots[p], knots[knots.len() - 1 - p]);
    let s = knots.iter().filter(|&&k| k == u).count();
    if !(u > a && u < b) || s < times || times == 0 {
        return Err(OpError::NotAKnot {
            u,
            times,
            present: if u > a && u < b { s } else { 0 },
        });
    }
    // Coordinates about the control points' centre (the bound's |P′| is then the curve's
    // size, not its distance from the origin); moved back at the end.
    let centre = {
        let (lo, hi) = points.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), h| {
                let q = h.truncate() / h.w;
                (lo.min(q), hi.max(q))
            },
        );
        0.5 * (lo + hi)
    };
    let shifted: Vec<DVec4> = points
        .iter()
        .map(|h| (h.truncate() - centre * h.w).extend(h.w))
        .collect();
    let (mut k, mut q) = (knots.clone(), shifted.clone());
    for m in 0..times {
        let r = k
            .iter()
            .rposition(|&x| x == u)
            .unwrap_or_else(|| unreachable!("present"));
        (k, q) = remove_once(&k, &q, p, r, s - m);
    }
    let geom = OpError::Geom;
    let removed = if rational {
        if let Some(i) = q.iter().position(|h| h.w <= 0.0 || h.w.is_nan()) {
            return Err(OpError::Geom(GeomError::BadWeight {
                index: i,
                value: q[i].w,
            }));
        }
        let pts: Vec<DVec3> = q.iter().map(|h| h.truncate() / h.w + centre).collect();
        let w: Vec<f64> = q.iter().map(|h| h.w).collect();
        Curve::Nurbs(Nurbs::try_new(pts, w, k, order).map_err(geom)?)
    } else {
        let pts: Vec<DVec3> = q.iter().map(|h| h.truncate() + centre).collect();
        Curve::BSpline(BSpline::try_new(pts, k, order).map_err(geom)?)
    };
    // Back in (the families' own knot insertion): the original's knot vector, the
    // difference on one basis, taken about the centre (`ΔA − c ΔW`).
    let mut back = removed.clone();
    for _ in 0..times {
        back = match &back {
            Curve::BSpline(b) => Curve::BSpline(b.insert_knot(u).map_err(geom)?),
            Curve::Nurbs(n) => Curve::Nurbs(n.insert_knot(u).map_err(geom)?),
            _ => unreachable!("a B-spline or NURBS curve"),
        };
    }
    let (_, _, again, _) = homogeneous(&back).unwrap_or_else(|| unreachable!("the same family"));
    let da = again
        .iter()
        .zip(&points)
        .map(|(x, y)| ((x.truncate() - y.truncate()) - centre * (x.w - y.w)).length())
        .fold(0.0, f64::max);
    let error = if rational {
        let dw = again
            .iter()
            .zip(&points)
            .map(|(x, y)| (x.w - y.w).abs())
            .fold(0.0, f64::max);
        let size = q
            .iter()
            .map(|h| (h.truncate() / h.w).length())
            .fold(0.0, f64::max);
        let w_min = points.iter().map(|h| h.w).fold(f64::INFINITY, f64::min);
        (da + size * dw) / w_min
    } else {
        da
    };
    // The rounding of the solve and the check themselves (the solve divides by the α's,
    // which can be small): a removal within this of exact counts as exact.
    let size = shifted
        .iter()
        .map(|h| h.truncate().length())
        .fold(0.0, f64::max);
    let (w_lo, w_hi) = shifted
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), h| {
            (lo.min(h.w), hi.max(h.w))
        });
    let euclid = shifted
        .iter()
        .map(|h| (h.truncate() / h.w).length())
        .fold(0.0, f64::max);
    let scale = (size + euclid * w_hi) / w_lo;
    let rounding = 4096.0 * f64::EPSILON * scale;
    let error = error + 64.0 * f64::EPSILON * scale;
    if error > tolerance.max(rounding) {
        return Err(OpError::WouldMove {
            u,
            times,
            bound: error,
            tolerance,
        });
    }
    Ok(Removed {
        curve: removed,
        error,
    })
}
