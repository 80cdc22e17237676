//! Fitting curves to points: a Bézier curve or a B-spline by weighted least squares at
//! given, chord-length or centripetal parameters; a B-spline with the fewest knots this
//! search finds whose sum of squared residuals is within a smoothing budget (scipy's
//! `make_splprep` meaning of `s`), or through every point (`s = 0`).
//!
//! The least-squares problem `min Σ w_i² |C(t_i) − p_i|²` over the control points is
//! linear; its normal equations `(Bᵀ W² B) P = Bᵀ W² p` are banded for a B-spline
//! (bandwidth `p + 1`: each row of `B` has at most `p + 1` nonzero basis values) and are
//! solved by a banded Cholesky factorisation, in `O(N p² + n p²)` for `N` points and `n`
//! control points. With a smoothing budget the interior knots are added where the
//! residuals are largest — the span whose squared residuals sum highest is cut at its
//! middle data parameter, as many spans at once as the budget is far from met — until
//! the budget holds or the knots reach the points (interpolation).

use glam::DVec3;

use crate::geom::bezier::{de_casteljau, deriv_at, second_deriv_at};
use crate::geom::{BSpline, Bezier, KnotVector};

use super::OpError;

/// How the points are given parameters.
#[derive(Debug, Clone, PartialEq)]
pub enum Params {
    /// Proportional to the distances between consecutive points, from 0 to 1.
    Chord,
    /// Proportional to the square roots of those distances (Lee's centripetal
    /// parametrisation: fewer loops and cusps on sharp turns).
    Centripetal,
    /// Given, one per point, non-decreasing.
    Given(Vec<f64>),
}

/// A fitted curve: the curve, each point's parameter and residual `|C(t_i) − p_i|`.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit<C> {
    /// The curve.
    pub curve: C,
    /// The points' parameters.
    pub params: Vec<f64>,
    /// The residuals, one per point.
    pub residuals: Vec<f64>,
}

impl<C> Fit<C> {
    /// The weighted sum of squared residuals `Σ w_i² r_i²` (`weights` as given to the
    /// fit; `None` for 1 each).
    #[must_use]
    pub fn sum_of_squares(&self, weights: Option<&[f64]>) -> f64 {
        self.residuals
            .iter()
            .enumerate()
            .map(|(i, r)| weights.map_or(1.0, |w| w[i] * w[i]) * r * r)
            .sum()
    }
}

fn fit_error(message: String) -> OpError {
    OpError::Fit(message)
}

/// Checks points and weights, and the parameters for them.
fn prepare(
    points: &[DVec3],
    params: &Params,
    weights: Option<&[f64]>,
    min: usize,
) -> Result<Vec<f64>, OpError> {
    if points.len() < min {
        return Err(fit_error(format!(
            "{} point(s): this fit needs at least {min}",
            points.len()
        )));
    }
    if let Some(i) = points.iter().position(|p| !p.is_finite()) {
        return Err(fit_error(format!(
            "points[{i}] = {}: not a finite point",
            points[i]
        )));
    }
    if let Some(w) = weights {
        if w.len() != points.len() {
            return Err(fit_error(format!(
                "weights: {} for {} points (one weight per point)",
                w.len(),
                points.len()
            )));
        }
        if let Some(i) = w.iter().position(|x| !(x.is_finite() && *x > 0.0)) {
            return Err(fit_error(format!(
                "weights[{i}] = {}: a weight must be a finite number greater than 0",
                w[i]
            )));
        }
    }
    let t = match params {
        Params::Given(t) => {
            if t.len() != points.len() {
                return Err(fit_error(format!(
                    "params: {} for {} points (one parameter per point)",
                    t.len(),
                    points.len()
                )));
            }
            if let Some(i) = (0..t.len()).find(|&i| !t[i].is_finite() || (i > 0 && t[i] < t[i - 1]))
            {
                return Err(fit_error(format!(
                    "params[{i}] = {}: parameters must be finite and non-decreasing",
                    t[i]
                )));
            }
            let (a, b) = (t[0], t[t.len() - 1]);
            if b <= a || b.is_nan() {
                return Err(fit_error(
                    "params: all equal (the points need a range of parameters)".into(),
                ));
            }
            t.iter().map(|x| (x - a) / (b - a)).collect()
        }
        Params::Chord | Params::Centripetal => {
            let power = if *params == Params::Chord { 1.0 } else { 0.5 };
            let mut t = Vec::with_capacity(points.len());
            let mut s = 0.0;
            t.push(0.0);
            for w in points.windows(2) {
                s += (w[1] - w[0]).length().powf(power);
                t.push(s);
            }
            if s <= 0.0 || s.is_nan() {
                return Err(fit_error(
                    "points: all the same (no distance to parametrise by)".into(),
                ));
            }
            t.iter().map(|x| x / s).collect()
        }
    };
    Ok(t)
}

/// The least-squares Bézier curve of `degree` through `points` at their parameters.
///
/// # Errors
/// [`OpError::Fit`] naming the offending input: fewer points than `degree + 1`, a point
/// or weight that is not finite (or a weight not above 0), parameters that are not
/// non-decreasing or all equal, a degree of 0 or above 64.
pub fn fit_bezier(
    points: &[DVec3],
    degree: usize,
    params: &Params,
    weights: Option<&[f64]>,
) -> Result<Fit<Bezier>, OpError> {
    // A Bézier curve is the B-spline with no interior knots.
    let fit = fit_bspline(points, degree, Some(&[]), None, params, weights)?;
    Ok(Fit {
        curve: Bezier::new(fit.curve.points().to_vec()),
        params: fit.params,
        residuals: fit.residuals,
    })
}

/// A B-spline of `degree` fitted to `points`: with `knots` (interior, inside `(0, 1)` of
/// the normalised parameters, non-decreasing) a plain least-squares fit; else with
/// `smoothing = s` the fewest knots found whose weighted sum of squared residuals is at
/// most `s` (`s = 0`: through every point).
///
/// # Errors
/// [`OpError::Fit`] naming the offending input (as [`fit_bezier`]; knots outside `(0, 1)`
/// or decreasing; a negative or non-finite smoothing; both or neither of `knots` and
/// `smoothing`; knots the data cannot pin down — a span with no parameter in it).
pub fn fit_bspline(
    points: &[DVec3],
    degree: usize,
    knots: Option<&[f64]>,
    smoothing: Option<f64>,
    params: &Params,
    weights: Option<&[f64]>,
) -> Result<Fit<BSpline>, OpError> {
    if degree == 0 || degree > 64 {
        return Err(fit_error(format!("degree {degree}: from 1 to 64")));
    }
    let t = prepare(points, params, weights, degree + 1)?;
    let clamped = |interior: &[f64]| -> Vec<f64> {
        std::iter::repeat_n(0.0, degree + 1)
            .chain(interior.iter().copied())
            .chain(std::iter::repeat_n(1.0, degree + 1))
            .collect()
    };
    // The residuals from the fitted points the least squares computed (the same basis).
    let finish = |full: Vec<f64>,
                  (ctrl, fitted): (Vec<DVec3>, Vec<DVec3>)|
     -> Result<Fit<BSpline>, OpError> {
        let curve = BSpline::try_new(ctrl, full, degree + 1).map_err(OpError::Geom)?;
        let residuals = points
            .iter()
            .zip(&fitted)
            .map(|(p, q)| (*q - *p).length())
            .collect();
        Ok(Fit {
            curve,
            params: t.clone(),
            residuals,
        })
    };
    match (knots, smoothing) {
        (Some(k), None) => {
            if let Some(i) = (0..k.len()).find(|&i| !(k[i] > 0.0 && k[i] < 1.0) || (i > 0 && k[i] < k[i - 1])) {
                return Err(fit_error(format!(
                    "knots[{i}] = {}: interior knots lie inside (0, 1) of the parameters, non-decreasing",
                    k[i]
                )));
            }
            let full = clamped(k);
            let ctrl = least_squares(points, &t, weights, &full, degree)?;
            finish(full, ctrl)
        }
        (None, Some(s)) => {
            if !(s.is_finite() && s >= 0.0) {
                return Err(fit_error(format!("smoothing {s}: a finite number at least 0")));
            }
            let w2 = |i: usize| weights.map_or(1.0, |w| w[i] * w[i]);
            let most = points.len() - degree - 1;
            // Through every point: de Boor's averaged knots (each interior knot the mean
            // of `p` consecutive parameters), one control point per point.
            let interpolating = || -> Result<Fit<BSpline>, OpError> {
                let interior: Vec<f64> = (1..=most)
                    .map(|j| t[j..j + degree].iter().sum::<f64>() / degree as f64)
                    .collect();
                let full = clamped(&interior);
                let ctrl = least_squares(points, &t, weights, &full, degree)?;
                finish(full, ctrl)
            };
            if s == 0.0 {
                return interpolating();
            }
            let mut interior: Vec<f64> = Vec::new();
            loop {
                let full = clamped(&interior);
                let solved = least_squares(points, &t, weights, &full, degree)?;
                // Squared residuals by knot span.
                let mut spans: Vec<(f64, Vec<usize>)> = vec![(0.0, Vec::new()); interior.len() + 1];
                let mut total = 0.0;
                for (i, (p, &u)) in points.iter().zip(&t).enumerate() {
                    let r2 = w2(i) * (solved.1[i] - *p).length_squared();
                    total += r2;
                    let k = interior.partition_point(|&x| x <= u).min(interior.len());
                    spans[k].0 += r2;
                    spans[k].1.push(i);
                }
                if total <= s {
                    return finish(full, solved);
                }
                if interior.len() >= most {
                    return interpolating();
                }
                // Cut the worst spans at their middle data parameter: one at first, more
                // as the budget stays far off (at most doubling the knots per round).
                let mut order: Vec<usize> = (0..spans.len()).collect();
                order.sort_by(|&a, &b| spans[b].0.total_cmp(&spans[a].0));
                // As many as the budget is far off: log₂(RSS / s) spans while far, and
                // near it a share of the knots there are (a residual dominated by noise
                // approaches the budget slowly, one knot at a time would take as many
                // rounds as knots).
                let far = (total / s.max(f64::MIN_POSITIVE)).log2();
                let want = (far.ceil().max(1.0) as usize)
                    .max((interior.len() as f64 * far.min(1.0) * 0.25).ceil() as usize)
                    .min(interior.len() + 1)
                    .min(most - interior.len());
                let mut added = 0;
                for &k in &order {
                    if added >= want {
                        break;
                    }
                    let idx = &spans[k].1;
                    if idx.len() < 2 {
                        continue;
                    }
                    let u = t[idx[idx.len() / 2]];
                    let lo = if k == 0 { 0.0 } else { interior[k - 1] };
                    let hi = if k == interior.len() { 1.0 } else { interior[k] };
                    if u > lo && u < hi && u > 0.0 && u < 1.0 {
                        interior.push(u);
                        added += 1;
                    }
                }
                if added == 0 {
                    // No span left to cut: the points themselves, which meet any budget.
                    return interpolating();
                }
                interior.sort_by(f64::total_cmp);
            }
        }
        _ => Err(fit_error(
            "give either knots (a least-squares fit on them) or smoothing (the knots found), not both or neither".into(),
        )),
    }
}

/// The control points minimising `Σ w_i² |C(t_i) − p_i|²` on the clamped knot vector
/// `knots` of `degree`, by the banded normal equations, and the fitted points `C(t_i)`
/// (from the same basis values).
fn least_squares(
    points: &[DVec3],
    t: &[f64],
    weights: Option<&[f64]>,
    knots: &[f64],
    degree: usize,
) -> Result<(Vec<DVec3>, Vec<DVec3>), OpError> {
    let p = degree;
    let n = knots.len() - p - 1;
    let kv = KnotVector::try_new(knots.to_vec(), p + 1, n).map_err(OpError::Geom)?;
    let band = p + 1;
    // Lower band of the symmetric matrix: a[i][j] for j in 0..band is entry (i, i − j).
    let mut a = vec![vec![0.0; band]; n];
    let mut rhs = vec![DVec3::ZERO; n];
    // Each point's span and basis values, kept for the fitted points.
    let mut spans = Vec::with_capacity(points.len());
    let mut values = vec![0.0; points.len() * band];
    let (mut left, mut right) = (vec![0.0; band], vec![0.0; band]);
    for (k, (pt, &u)) in points.iter().zip(t).enumerate() {
        let basis = &mut values[k * band..(k + 1) * band];
        let span = kv.basis_into(u, basis, &mut left, &mut right);
        spans.push(span);
        let basis = &values[k * band..(k + 1) * band];
        let w2 = weights.map_or(1.0, |w| w[k] * w[k]);
        for r in 0..=p {
            let i = span - p + r;
            rhs[i] += *pt * (w2 * basis[r]);
            for c in 0..=r {
                let j = span - p + c;
                a[i][i - j] += w2 * basis[r] * basis[c];
            }
        }
    }
    // Banded Cholesky: A = L Lᵀ, L stored in the same band.
    for i in 0..n {
        for j in i.saturating_sub(p)..=i {
            let mut sum = a[i][i - j];
            for k in i.saturating_sub(p).max(j.saturating_sub(p))..j {
                sum -= a[i][i - k] * a[j][j - k];
            }
            if i == j {
                if sum <= 1e-300 || sum.is_nan() {
                    return Err(fit_error(format!(
                        "the data cannot pin down control point {i}: no point's parameter lies where it acts (put fewer knots, or knots where the points are)"
                    )));
                }
                a[i][0] = sum.sqrt();
            } else {
                a[i][i - j] = sum / a[j][0];
            }
        }
    }
    // Solve L y = rhs, then Lᵀ x = y.
    let mut y = rhs;
    for i in 0..n {
        let mut v = y[i];
        for k in i.saturating_sub(p)..i {
            v -= y[k] * a[i][i - k];
        }
        y[i] = v / a[i][0];
    }
    for i in (0..n).rev() {
        let mut v = y[i];
        for k in i + 1..(i + p + 1).min(n) {
            v -= y[k] * a[k][k - i];
        }
        y[i] = v / a[i][0];
    }
    if let Some(i) = y.iter().position(|v| !v.is_finite()) {
        return Err(fit_error(format!(
            "control point {i} is not finite: the fit is singular"
        )));
    }
    let fitted = spans
        .iter()
        .enumerate()
        .map(|(k, &span)| {
            (0..=p).fold(DVec3::ZERO, |acc, r| {
                acc + y[span - p + r] * values[k * band + r]
            })
        })
        .collect();
    Ok((y, fitted))
}

/// The most segments [`fit_path`] makes (a guard against a tolerance far below the data's
/// rounding).
pub const MAX_PATH_SEGMENTS: usize = 1 << 16;

/// A path of cubic segments through `points` (a polyline from a pen or a scan, free of
/// noise) within `tolerance` of every point, its corners kept: where the polyline turns by
/// more than `corner_angle` degrees the path has a corner (a joint without a common
/// tangent); elsewhere segments meet with one tangent (G1). Each stretch between corners
/// is fitted by Schneider's algorithm: a cubic with the stretch's end points and end
/// tangent directions, its two tangent lengths by least squares, the points' parameters
/// refined by Newton's method, and the stretch cut at its worst point (the tangent there
/// the chord of its neighbours) until every point is within the tolerance of its point on
/// the curve — so within it of the curve. A polyline whose last point is its first gives a
/// closed path.
///
/// # Errors
/// [`OpError::Fit`] for fewer than 2 points, a point that is not finite, a tolerance that
/// is not a finite number greater than 0, a corner angle outside `[0, 180]`, or more than
/// [`MAX_PATH_SEGMENTS`] segments.
pub fn fit_path(
    points: &[DVec3],
    tolerance: f64,
    corner_angle: f64,
) -> Result<Fit<crate::geom::Path>, OpError> {
    use crate::geom::{Path, PathSegment};
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(fit_error(format!(
            "tolerance {tolerance}: a finite number greater than 0"
        )));
    }
    if !(0.0..=180.0).contains(&corner_angle) {
        return Err(fit_error(format!(
            "corner_angle {corner_angle}: degrees from 0 to 180"
        )));
    }
    // Consecutive repeats add nothing: dropped (their residuals are their twins').
    let mut pts: Vec<DVec3> = Vec::with_capacity(points.len());
    let mut owner: Vec<usize> = Vec::with_capacity(points.len());
    prepare(points, &Params::Chord, None, 2)?;
    for p in points {
        if pts.last() != Some(p) {
            pts.push(*p);
        }
        owner.push(pts.len() - 1);
    }
    if pts.len() < 2 {
        return Err(fit_error("points: all the same (nothing to fit)".into()));
    }
    let closed = pts.len() > 2 && pts[0] == pts[pts.len() - 1];
    let n = pts.len();
    let cos_corner = corner_angle.to_radians().cos();
    let dir = |a: DVec3, b: DVec3| (b - a).normalize_or_zero();
    // Corners: interior points (and a closed polyline's start) where it turns too far.
    let turns = |i: usize, prev: usize, next: usize| {
        dir(pts[prev], pts[i]).dot(dir(pts[i], pts[next])) < cos_corner
    };
    let mut corners: Vec<usize> = vec![0];
    for i in 1..n - 1 {
        if turns(i, i - 1, i + 1) {
            corners.push(i);
        }
    }
    corners.push(n - 1);
    let seam_smooth = closed && !turns(0, n - 2, 1);
    let mut segments: Vec<[DVec3; 4]> = Vec::new();
    let mut params: Vec<f64> = vec![0.0; n];
    for w in corners.windows(2) {
        let (a, b) = (w[0], w[1]);
        let t0 = if a == 0 && seam_smooth {
            dir(pts[n - 2], pts[1])
        } else {
            dir(pts[a], pts[a + 1])
        };
        let t1 = if b == n - 1 && seam_smooth {
            dir(pts[1], pts[n - 2])
        } else {
            dir(pts[b], pts[b - 1])
        };
        schneider(&pts, a, b, t0, t1, tolerance, &mut segments, &mut params, 0)?;
    }
    if segments.len() > MAX_PATH_SEGMENTS {
        return Err(fit_error(format!(
            "more than {MAX_PATH_SEGMENTS} segments within tolerance {tolerance}: ask for a larger tolerance"
        )));
    }
    let path_segments: Vec<PathSegment> = segments
        .iter()
        .map(|s| PathSegment::polynomial(s.to_vec()))
        .collect();
    let path = Path::try_new(path_segments, closed).map_err(OpError::Geom)?;
    let curve_points: Vec<DVec3> = (0..n).map(|i| eval_path_at(&segments, params[i])).collect();
    let residuals = owner
        .iter()
        .map(|&k| (curve_points[k] - pts[k]).length())
        .collect();
    let params = owner.iter().map(|&k| params[k]).collect();
    Ok(Fit {
        curve: path,
        params,
        residuals,
    })
}

/// A cubic at `u` (de Casteljau).
fn cubic_at(c: &[DVec3; 4], u: f64) -> DVec3 {
    de_casteljau(c, u)
}

/// The path of cubics at parameter `t` (segment `⌊t⌋`).
fn eval_path_at(segments: &[[DVec3; 4]], t: f64) -> DVec3 {
    let k = (t.floor() as usize).min(segments.len() - 1);
    cubic_at(&segments[k], t - k as f64)
}

/// Schneider's fit of `pts[a..=b]` with end tangent directions `t0` (out of `a`) and `t1`
/// (out of `b`, pointing back), appending cubics and setting each point's path parameter.
#[allow(clippy::too_many_arguments)]
fn schneider(
    pts: &[DVec3],
    a: usize,
    b: usize,
    t0: DVec3,
    t1: DVec3,
    tolerance: f64,
    out: &mut Vec<[DVec3; 4]>,
    params: &mut [f64],
    depth: usize,
) -> Result<(), OpError> {
    if out.len() > MAX_PATH_SEGMENTS || depth > 200 {
        return Err(fit_error(format!(
            "more than {MAX_PATH_SEGMENTS} segments within tolerance {tolerance}: ask for a larger tolerance"
        )));
    }
    let (p0, p3) = (pts[a], pts[b]);
    let chord = (p3 - p0).length();
    if b == a + 1 {
        let c = [p0, p0 + t0 * chord / 3.0, p3 + t1 * chord / 3.0, p3];
        params[a] = out.len() as f64;
        out.push(c);
        params[b] = out.len() as f64;
        return Ok(());
    }
    // Chord-length parameters.
    let mut u: Vec<f64> = Vec::with_capacity(b - a + 1);
    let mut s = 0.0;
    u.push(0.0);
    for i in a + 1..=b {
        s += (pts[i] - pts[i - 1]).length();
        u.push(s);
    }
    for x in &mut u {
        *x /= s;
    }
    let mut best: Option<([DVec3; 4], f64, usize)> = None;
    for _ in 0..5 {
        let c = tangent_fit(pts, a, b, &u, t0, t1);
        let (worst, at) = (a..=b)
            .map(|i| ((cubic_at(&c, u[i - a]) - pts[i]).length(), i))
            .fold((0.0, a), |m, x| if x.0 > m.0 { x } else { m });
        if best.as_ref().is_none_or(|bst| worst < bst.1) {
            best = Some((c, worst, at));
        }
        if worst <= tolerance || worst > 4.0 * tolerance {
            break;
        }
        // Newton's step for each parameter toward its point's foot on the curve.
        for i in a + 1..b {
            let v = u[i - a];
            let (q, d1, d2) = (cubic_at(&c, v), deriv_at(&c, v), second_deriv_at(&c, v));
            let f = (q - pts[i]).dot(d1);
            let g = d1.dot(d1) + (q - pts[i]).dot(d2);
            if g.abs() > 1e-300 {
                u[i - a] = (v - f / g).clamp(0.0, 1.0);
            }
        }
    }
    let (c, worst, at) = best.unwrap_or_else(|| unreachable!("at least one fit"));
    if worst <= tolerance {
        let base = out.len() as f64;
        for i in a..b {
            params[i] = base + u[i - a];
        }
        out.push(c);
        params[b] = out.len() as f64;
        return Ok(());
    }
    // Cut at the worst point, the tangent there the chord of its neighbours.
    let split = at.clamp(a + 1, b - 1);
    let centre = (pts[split - 1] - pts[split + 1]).normalize_or_zero();
    schneider(pts, a, split, t0, centre, tolerance, out, params, depth + 1)?;
    schneider(
        pts,
        split,
        b,
        -centre,
        t1,
        tolerance,
        out,
        params,
        depth + 1,
    )
}

/// The two handle lengths `(l₀, l₁)` of the cubic from `pts[0]` to the last point with
/// inner points `P₀ + l₀ t₀` and `P₃ + l₁ t₁` that minimise `Σ w_j² |B(u_j) − p_j|²` (a
/// 2 × 2 system; `w` all 1 when `None`), or `None` when the system is singular.
pub(super) fn handle_lengths(
    pts: &[DVec3],
    u: &[f64],
    w: Option<&[f64]>,
    t0: DVec3,
    t1: DVec3,
) -> Option<(f64, f64)> {
    let (p0, p3) = (pts[0], pts[pts.len() - 1]);
    let (mut c00, mut c01, mut c11, mut x0, mut x1) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (j, (p, &v)) in pts.iter().zip(u).enumerate() {
        let s = 1.0 - v;
        let (b0, b1, b2, b3) = (s * s * s, 3.0 * s * s * v, 3.0 * s * v * v, v * v * v);
        let w2 = w.map_or(1.0, |w| w[j] * w[j]);
        let (a1, a2) = (t0 * b1, t1 * b2);
        c00 += w2 * a1.dot(a1);
        c01 += w2 * a1.dot(a2);
        c11 += w2 * a2.dot(a2);
        let rest = *p - (p0 * (b0 + b1) + p3 * (b2 + b3));
        x0 += w2 * a1.dot(rest);
        x1 += w2 * a2.dot(rest);
    }
    let det = c00 * c11 - c01 * c01;
    let solved = ((x0 * c11 - x1 * c01) / det, (c00 * x1 - c01 * x0) / det);
    (det.abs() > 1e-12 * (c00 * c11).max(f64::MIN_POSITIVE)
        && solved.0.is_finite()
        && solved.1.is_finite())
    .then_some(solved)
}

/// The cubic with ends `pts[a]`, `pts[b]` and inner points along `t0`, `t1` whose two
/// lengths minimise the squared distances at `u` ([`handle_lengths`]; a singular system,
/// or a negative or vanishing length, which would loop or cusp, falls back to a third of
/// the chord).
fn tangent_fit(pts: &[DVec3], a: usize, b: usize, u: &[f64], t0: DVec3, t1: DVec3) -> [DVec3; 4] {
    let (p0, p3) = (pts[a], pts[b]);
    let chord = (p3 - p0).length();
    let (l0, l1) = handle_lengths(&pts[a..=b], u, None, t0, t1)
        .filter(|&(l0, l1)| l0 > 1e-6 * chord && l1 > 1e-6 * chord)
        .unwrap_or((chord / 3.0, chord / 3.0));
    [p0, p0 + t0 * l0, p3 + t1 * l1, p3]
}
