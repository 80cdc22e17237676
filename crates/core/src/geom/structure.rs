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

use super::{GeomError, KnotVector};

/// The leg `(i, i + 1)` of `polygon` nearest to `at`, and where along it (`0..=1`) the
/// nearest point lies.
pub(crate) fn nearest_leg(polygon: &[DVec3], at: DVec3) -> (usize, f64) {
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

/// `points` with `at` inserted after the nearest leg's first point: the new points, the
/// leg and where along it `at` projects (`0..=1`). The family's constructor checks the
/// points (a non-finite `at` is refused there).
pub(crate) fn insert_on_polygon(points: &[DVec3], at: DVec3) -> (Vec<DVec3>, usize, f64) {
    let (leg, s) = nearest_leg(points, at);
    let mut out = points.to_vec();
    out.insert(leg + 1, at);
    (out, leg, s)
}

/// `points` without point `index`, when at least `min` remain.
///
/// # Errors
/// [`GeomError::NoSuchPoint`], or [`GeomError::StructureRefused`] naming `family` when
/// fewer than `min` would remain.
pub(crate) fn without(
    points: &[DVec3],
    index: usize,
    min: usize,
    family: &'static str,
) -> Result<Vec<DVec3>, GeomError> {
    let count = points.len();
    if index >= count {
        return Err(GeomError::NoSuchPoint { index, count });
    }
    if count <= min {
        return Err(GeomError::refused(
            family,
            format!("a curve of this kind keeps at least {min} points"),
        ));
    }
    let mut out = points.to_vec();
    out.remove(index);
    Ok(out)
}

/// Point `index` removed with the interior knot nearest its Greville abscissa.
pub(crate) fn spline_without(
    points: &[DVec3],
    knots: &KnotVector,
    index: usize,
    family: &'static str,
) -> Result<(Vec<DVec3>, Vec<f64>), GeomError> {
    let k = knots.order();
    let n = points.len();
    if index >= n {
        return Err(GeomError::NoSuchPoint { index, count: n });
    }
    if n <= k {
        return Err(GeomError::refused(
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
