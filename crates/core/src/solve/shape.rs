//! Least-squares shape modification of Bézier curves (paper 000: "Optimal shape
//! modification of Bézier curves by geometric constraints"): move control points by the
//! least `Σ‖ε_i‖²` so that the curve passes through target points, with the end points
//! fixed and optionally the end tangents kept.
//! Formulas and decisions (the default window of Eq. 8, the cubic allowed region):
//! `docs/math.md` §2.

use glam::DVec3;
use nalgebra::DMatrix;

use super::SolveError;
use super::linalg::min_norm_solve;
use super::project::nearest;
use crate::geom::bernstein::bernstein_all;
use crate::geom::cubic_region;
use crate::geom::{Bezier, Lower, ParamCurve};

/// How [`single_target`] chooses its start point and moved control points.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SingleTargetOptions {
    /// `t_s`, the parameter of the start point `S = P(t_s)`; `None` projects the target
    /// onto the curve.
    pub t_s: Option<f64>,
    /// `(l, m)`: move `P_l..P_{l+m−1}` (`1 ≤ l`, `l + m − 1 ≤ n − 1`). `None`: `m =
    /// min(3, n − 1)` consecutive interior points, the window with the largest
    /// `Σ B_{i,n}(t_s)²` (the one needing the least movement).
    pub window: Option<(usize, usize)>,
    /// Projection accuracy (absolute distance); `None`: relative `1e-12`.
    pub accuracy: Option<f64>,
}

/// The default number of moved points of [`single_target`].
pub const DEFAULT_WINDOW: usize = 3;

/// The result of [`single_target`].
#[derive(Debug, Clone, PartialEq)]
pub struct SingleTargetSolution {
    /// The modified curve.
    pub curve: Bezier,
    /// `t_s`.
    pub t_s: f64,
    /// `S = P(t_s)` on the original curve.
    pub start: DVec3,
    /// `l`: the first moved control point.
    pub first: usize,
    /// `ε_l..ε_{l+m−1}`.
    pub deltas: Vec<DVec3>,
    /// `|P̃(t_s) − T|` (0 up to rounding).
    pub residual: f64,
}

fn check_target(index: usize, t: DVec3) -> Result<(), SolveError> {
    match t.to_array().into_iter().find(|c| !c.is_finite()) {
        Some(value) => Err(SolveError::NonFiniteTarget { index, value }),
        None => Ok(()),
    }
}

/// `t_s`: given (checked to be strictly inside `(0, 1)`), or found by projecting the
/// target (an error when it projects onto a fixed end).
pub(crate) fn start_parameter<C: Lower + ParamCurve + ?Sized>(
    curve: &C,
    target: DVec3,
    index: usize,
    given: Option<f64>,
    accuracy: Option<f64>,
) -> Result<f64, SolveError> {
    let (start, end) = curve.domain();
    match given {
        Some(t) if !(start..=end).contains(&t) || !t.is_finite() => {
            Err(SolveError::ParameterOutsideDomain {
                value: t,
                start,
                end,
            })
        }
        Some(t) if t == start || t == end => Err(SolveError::ParameterAtEnd { index, value: t }),
        Some(t) => Ok(t),
        None => {
            let n = nearest(curve, target, accuracy);
            if n.t <= start || n.t >= end {
                Err(SolveError::TargetAtEnd { index, t: n.t })
            } else {
                Ok(n.t)
            }
        }
    }
}

/// Paper 000, §2.1, Eq. 8: moves `P_l..P_{l+m−1}` (ends fixed) so that the curve passes
/// through `T` at `t_s`, minimising `Σ‖ε_i‖²`:
///
/// `ε_i = B_{i,n}(t_s) / (Σ_{j=l}^{l+m−1} B_{j,n}(t_s)²) · (T − S)`,
///
/// the minimum-norm solution of `Σ ε_i B_{i,n}(t_s) = T − S`.
///
/// # Errors
/// [`SolveError`] for a non-finite target, degree < 2, `t_s` at an end or outside `[0, 1]`,
/// a window outside `1..=n−1`, or a target that projects onto a fixed end.
pub fn single_target(
    curve: &Bezier,
    target: DVec3,
    opts: &SingleTargetOptions,
) -> Result<SingleTargetSolution, SolveError> {
    check_target(0, target)?;
    let n = curve.degree();
    if n < 2 {
        return Err(SolveError::DegreeTooLow {
            method: "single_target",
            degree: n,
            min: 2,
        });
    }
    let t_s = start_parameter(curve, target, 0, opts.t_s, opts.accuracy)?;
    let b = bernstein_all(n, t_s);
    let (first, count) = window(&b, opts.window)?;
    check_influence(&b, &(first..first + count).collect::<Vec<_>>(), 0, t_s)?;
    let denom: f64 = b[first..first + count].iter().map(|v| v * v).sum();
    if denom <= 0.0 {
        return Err(SolveError::ParameterAtEnd {
            index: 0,
            value: t_s,
        });
    }
    let start = curve.eval(t_s);
    let diff = target - start;
    let deltas: Vec<DVec3> = (first..first + count)
        .map(|i| b[i] / denom * diff)
        .collect();
    let mut pts = curve.points().to_vec();
    for (k, d) in deltas.iter().enumerate() {
        pts[first + k] += *d;
    }
    check_moves_finite(&pts, &[t_s])?;
    let modified = Bezier::new(pts);
    let residual = (modified.eval(t_s) - target).length();
    check_met(curve.points(), &[(b, diff)], &[target], &[t_s], &[residual])?;
    Ok(SingleTargetSolution {
        curve: modified,
        t_s,
        start,
        first,
        deltas,
        residual,
    })
}

/// The result of [`tangent_kept`].
#[derive(Debug, Clone, PartialEq)]
pub struct TangentKeptSolution {
    /// The modified curve.
    pub curve: Bezier,
    /// `t_s`.
    pub t_s: f64,
    /// `μ_1, μ_2`: `P′_1 = P_1 + μ_1 e_1`, `P′_{n−1} = P_{n−1} + μ_2 e_2`.
    pub mu: [f64; 2],
    /// The unit directions `e_1 = unit(P_1 − P_0)`, `e_2 = unit(P_{n−1} − P_n)`.
    pub directions: [DVec3; 2],
    /// `ε_2..ε_{n−2}`.
    pub deltas: Vec<DVec3>,
    /// `|P̃(t_s) − T|`: 0 up to rounding, unless the system is over-determined (a cubic in
    /// 3D with a target off its plane) and solved in least squares.
    pub residual: f64,
    /// Whether the system was solved in least squares (fewer free parameters than
    /// conditions, or rank-deficient).
    pub least_squares: bool,
}

/// The unit end-tangent directions `e_1 = unit(P_1 − P_0)`, `e_2 = unit(P_{n−1} − P_n)`.
///
/// # Errors
/// [`SolveError::NoTangent`] when an end point coincides with its neighbour.
pub fn end_directions(curve: &Bezier) -> Result<[DVec3; 2], SolveError> {
    polygon_end_directions(curve.points())
}

/// [`end_directions`] of any control polygon `P_0 … P_n` (`n ≥ 1`).
///
/// # Errors
/// [`SolveError::NoTangent`] when an end point coincides with its neighbour.
pub(crate) fn polygon_end_directions(p: &[DVec3]) -> Result<[DVec3; 2], SolveError> {
    let n = p.len() - 1;
    let e1 = (p[1] - p[0]).try_normalize().ok_or(SolveError::NoTangent {
        end: "start (P_0 = P_1)",
    })?;
    let e2 = (p[n - 1] - p[n])
        .try_normalize()
        .ok_or(SolveError::NoTangent {
            end: "end (P_n = P_(n-1))",
        })?;
    Ok([e1, e2])
}

/// Paper 000, §2.2: keeps `P_0`, `P_n` and the end tangents (`P_1` slides on the line
/// `P_0P_1`, `P_{n−1}` on `P_nP_{n−1}`), moves `P_2..P_{n−2}` freely, and passes through `T`
/// at `t_s`, minimising `Σ_{i=2}^{n−2}‖ε_i‖² + μ_1² + μ_2²` — the minimum-norm solution of
///
/// `μ_1 B_{1,n}(t_s) e_1 + μ_2 B_{n−1,n}(t_s) e_2 + Σ_{i=2}^{n−2} ε_i B_{i,n}(t_s) = T − S`.
///
/// For a cubic only `μ_1, μ_2` are free: square in the plane, over-determined in 3D (solved
/// in least squares, with the residual reported).
///
/// # Errors
/// [`SolveError`] for degree < 3, a missing tangent direction, a non-finite target, `t_s`
/// at an end or outside `[0, 1]`.
pub fn tangent_kept(
    curve: &Bezier,
    target: DVec3,
    t_s: Option<f64>,
    accuracy: Option<f64>,
) -> Result<TangentKeptSolution, SolveError> {
    check_target(0, target)?;
    let n = curve.degree();
    if n < 3 {
        return Err(SolveError::DegreeTooLow {
            method: "tangent_kept",
            degree: n,
            min: 3,
        });
    }
    let [e1, e2] = end_directions(curve)?;
    let t_s = start_parameter(curve, target, 0, t_s, accuracy)?;
    let b = bernstein_all(n, t_s);
    check_influence(&b, &(1..n).collect::<Vec<_>>(), 0, t_s)?;
    let start = curve.eval(t_s);
    let moves = tangent_moves(curve.points(), &b, [e1, e2], target, target - start);
    check_moves_finite(&moves.points, &[t_s])?;
    let modified = Bezier::new(moves.points);
    let residual = (modified.eval(t_s) - target).length();
    if !moves.over_determined {
        check_met(
            curve.points(),
            &[(b, target - start)],
            &[target],
            &[t_s],
            &[residual],
        )?;
    }
    Ok(TangentKeptSolution {
        curve: modified,
        t_s,
        mu: moves.mu,
        directions: [e1, e2],
        deltas: moves.deltas,
        residual,
        least_squares: moves.least_squares,
    })
}

/// `P_a..P_b` for a sorted, consecutive list of indices (or the list).
fn points_text(indices: &[usize]) -> String {
    match indices {
        [] => "none".to_owned(),
        [i] => format!("P_{i}"),
        [first, .., last] if last - first + 1 == indices.len() => format!("P_{first}..P_{last}"),
        _ => indices
            .iter()
            .map(|i| format!("P_{i}"))
            .collect::<Vec<_>>()
            .join(", "),
    }
}

/// Refuses a target at `t` (its basis values `basis`) that none of the points `moved` can
/// move: their basis functions are all 0 there (a parameter so close to an end that they
/// underflow, or a window the parameter's knot span does not reach).
pub(crate) fn check_influence(
    basis: &[f64],
    moved: &[usize],
    index: usize,
    t: f64,
) -> Result<(), SolveError> {
    if moved
        .iter()
        .any(|&i| basis.get(i).is_some_and(|b| *b != 0.0))
    {
        return Ok(());
    }
    let n = basis.len().saturating_sub(1);
    let active: Vec<usize> = (1..n).filter(|&i| basis[i] != 0.0).collect();
    let influence = if active.is_empty() {
        "no interior control point does (the parameter is too close to a fixed end); choose a parameter further inside".to_owned()
    } else {
        format!("the interior points that do: {}", points_text(&active))
    };
    Err(SolveError::NoInfluence {
        index,
        value: t,
        moved: points_text(moved),
        influence,
    })
}

/// Whether a several-target system is over-determined by its structure — more targets
/// than moved points, or two targets sharing a parameter — so that least squares is the
/// method. Any other rank deficiency is rounding (basis values that underflow) and the
/// targets must then be met, or the solve is refused.
pub(crate) fn over_determined(targets: usize, moved: usize, params: &[f64]) -> bool {
    let mut sorted = params.to_vec();
    sorted.sort_by(f64::total_cmp);
    targets > moved || sorted.windows(2).any(|w| w[0] == w[1])
}

/// Refuses moves that leave `f64` (`new_points` not all finite), naming the first target.
pub(crate) fn check_moves_finite(new_points: &[DVec3], params: &[f64]) -> Result<(), SolveError> {
    if new_points.iter().all(|p| p.is_finite()) {
        Ok(())
    } else {
        Err(SolveError::MovesOverflow {
            index: 0,
            value: params.first().copied().unwrap_or(f64::NAN),
        })
    }
}

/// Refuses a solution that misses a target it should meet: `residuals[l]` above `1e−9` of
/// `|T_l| + Σ_i |basis_i(t_l)| ‖P_i‖` — the target's size and the size of the terms the
/// unmodified curve sums at `t_l`. A solution whose moves are so large that rounding
/// them spoils the target (another target at 1e15, say) is refused rather than returned
/// with a residual. Least-squares solutions (more conditions than the rank) report their
/// residuals instead.
pub(crate) fn check_met(
    points: &[DVec3],
    conditions: &[(Vec<f64>, DVec3)],
    targets: &[DVec3],
    params: &[f64],
    residuals: &[f64],
) -> Result<(), SolveError> {
    for (l, ((basis, _), target)) in conditions.iter().zip(targets).enumerate() {
        let terms: f64 = basis
            .iter()
            .zip(points)
            .map(|(b, p)| b.abs() * p.abs().max_element())
            .sum();
        let scale = target.abs().max_element() + terms;
        let residual = residuals[l];
        // NaN fails too.
        if residual.is_nan() || residual > 1e-9 * scale + f64::MIN_POSITIVE {
            return Err(SolveError::Missed {
                index: l,
                value: params[l],
                residual,
            });
        }
    }
    Ok(())
}

/// The points Eq. 8 moves, `(first, count)`, for the basis values `basis` (`n + 1` of
/// them) at `t_s`: `given` when it is interior, else the `min(DEFAULT_WINDOW, n − 1)`
/// consecutive interior points of largest `Σ basis_i²` (the one needing the least
/// movement).
///
/// # Errors
/// [`SolveError::WindowOutOfRange`] for a given window that is not interior.
pub(crate) fn window(
    basis: &[f64],
    given: Option<(usize, usize)>,
) -> Result<(usize, usize), SolveError> {
    let n = basis.len() - 1;
    match given {
        Some((l, m)) if l < 1 || m < 1 || l + m - 1 > n - 1 => Err(SolveError::WindowOutOfRange {
            first: l,
            count: m,
            max: n - 1,
        }),
        Some(w) => Ok(w),
        None => {
            let m = DEFAULT_WINDOW.min(n - 1);
            // Σ basis² underflows to 0 for basis values below 1e-162 (a parameter next to
            // an end): then the window of largest Σ |basis| is the one that moves the curve.
            let squares = |l: usize| basis[l..l + m].iter().map(|v| v * v).sum::<f64>();
            let sums = |l: usize| basis[l..l + m].iter().map(|v| v.abs()).sum::<f64>();
            let any_square = (1..=n - m).any(|l| squares(l) > 0.0);
            let weight = |l: usize| if any_square { squares(l) } else { sums(l) };
            let l = (1..=n - m)
                .max_by(|&x, &y| weight(x).total_cmp(&weight(y)))
                .unwrap_or(1);
            Ok((l, m))
        }
    }
}

/// The moves of §2.2 for any basis with fixed values `basis[i]` at the target's parameter
/// (Bernstein, or a rational basis with fixed weights).
pub(crate) struct TangentMoves {
    /// The moved control points.
    pub points: Vec<DVec3>,
    /// `μ_1`, `μ_2`.
    pub mu: [f64; 2],
    /// `ε_2..ε_{n−2}`.
    pub deltas: Vec<DVec3>,
    /// The system's rank.
    pub rank: usize,
    /// Whether it was solved in least squares (rank below the equations).
    pub least_squares: bool,
    /// Whether it has fewer unknowns than equations (a 3D cubic: only `μ_1, μ_2` for
    /// three coordinates), so that least squares is the method and not a failure.
    pub over_determined: bool,
}

/// The minimum-norm solution of
/// `μ_1 N_1 e_1 + μ_2 N_{n−1} e_2 + Σ_{i=2}^{n−2} ε_i N_i = diff` for the control polygon
/// `points` (`n ≥ 3`) and the basis values `basis`: two equations (x, y) for a planar
/// polygon and target, three otherwise.
pub(crate) fn tangent_moves(
    points: &[DVec3],
    basis: &[f64],
    [e1, e2]: [DVec3; 2],
    target: DVec3,
    diff: DVec3,
) -> TangentMoves {
    let n = points.len() - 1;
    let planar = points.iter().all(|p| p.z == 0.0) && target.z == 0.0;
    let d = if planar { 2 } else { 3 };
    let free = n - 3; // ε_2..ε_{n−2}
    let mut a = DMatrix::zeros(d, 2 + d * free);
    for row in 0..d {
        a[(row, 0)] = basis[1] * e1[row];
        a[(row, 1)] = basis[n - 1] * e2[row];
        for k in 0..free {
            a[(row, 2 + d * k + row)] = basis[2 + k];
        }
    }
    let rhs = DMatrix::from_iterator(d, 1, (0..d).map(|row| diff[row]));
    let sol = min_norm_solve(&a, &rhs);
    let mu = [sol.x[(0, 0)], sol.x[(1, 0)]];
    let deltas: Vec<DVec3> = (0..free)
        .map(|k| {
            let mut v = DVec3::ZERO;
            for row in 0..d {
                v[row] = sol.x[(2 + d * k + row, 0)];
            }
            v
        })
        .collect();
    let mut moved = points.to_vec();
    moved[1] += mu[0] * e1;
    moved[n - 1] += mu[1] * e2;
    for (k, dv) in deltas.iter().enumerate() {
        moved[2 + k] += *dv;
    }
    TangentMoves {
        points: moved,
        mu,
        deltas,
        rank: sol.rank,
        least_squares: sol.rank < d,
        over_determined: 2 + d * free < d,
    }
}

/// The result of [`multi_target`].
#[derive(Debug, Clone, PartialEq)]
pub struct MultiTargetSolution {
    /// The modified curve.
    pub curve: Bezier,
    /// The parameter of each target.
    pub params: Vec<f64>,
    /// `ε_1..ε_{n−1}`.
    pub deltas: Vec<DVec3>,
    /// `|P̃(t_l) − T_l|` per target.
    pub residuals: Vec<f64>,
    /// The rank of the system matrix `B_{i,n}(t_l)`.
    pub rank: usize,
    /// Whether the targets could not all be met exactly (more conditions than the rank).
    pub least_squares: bool,
}

/// Paper 000, §3: moves every interior point (`P_1..P_{n−1}`) so that the curve passes
/// through the targets `T_l` at their parameters `t_l` (given, or found by projecting each
/// target onto the current curve), minimising `Σ‖ε_i‖²`: the minimum-norm solution of
/// `Σ_i ε_i B_{i,n}(t_l) = T_l − P(t_l)`, by SVD. With more targets than the rank allows
/// (more than `n − 1`, or two sharing a parameter) it is solved in least squares and the
/// residuals say how far each target stays.
///
/// # Errors
/// [`SolveError`] for no targets, a non-finite target, degree < 2, parameters outside
/// `[0, 1]` or of the wrong count, or a target whose parameter is a (fixed) end.
pub fn multi_target(
    curve: &Bezier,
    targets: &[DVec3],
    params: Option<&[f64]>,
    accuracy: Option<f64>,
) -> Result<MultiTargetSolution, SolveError> {
    if targets.is_empty() {
        return Err(SolveError::NoTargets);
    }
    for (i, t) in targets.iter().enumerate() {
        check_target(i, *t)?;
    }
    let n = curve.degree();
    if n < 2 {
        return Err(SolveError::DegreeTooLow {
            method: "multi_target",
            degree: n,
            min: 2,
        });
    }
    if let Some(p) = params
        && p.len() != targets.len()
    {
        return Err(SolveError::ParamCount {
            targets: targets.len(),
            params: p.len(),
        });
    }
    let params: Vec<f64> = targets
        .iter()
        .enumerate()
        .map(|(i, &t)| start_parameter(curve, t, i, params.map(|p| p[i]), accuracy))
        .collect::<Result<_, _>>()?;
    let conditions: Vec<(Vec<f64>, DVec3)> = params
        .iter()
        .zip(targets)
        .map(|(&t, &target)| (bernstein_all(n, t), target - curve.eval(t)))
        .collect();
    let moved: Vec<usize> = (1..n).collect();
    for (l, (basis, _)) in conditions.iter().enumerate() {
        check_influence(basis, &moved, l, params[l])?;
    }
    let moves = point_moves(curve.points(), &moved, &conditions);
    check_moves_finite(&moves.points, &params)?;
    let modified = Bezier::new(moves.points);
    let residuals: Vec<f64> = params
        .iter()
        .zip(targets)
        .map(|(&t, &target)| (modified.eval(t) - target).length())
        .collect();
    let least_squares = moves.rank < targets.len();
    if !over_determined(targets.len(), moved.len(), &params) {
        check_met(curve.points(), &conditions, targets, &params, &residuals)?;
    }
    Ok(MultiTargetSolution {
        curve: modified,
        params,
        deltas: moves.deltas,
        residuals,
        rank: moves.rank,
        least_squares,
    })
}

/// Moves of the control points `moved` of `points`.
pub(crate) struct PointMoves {
    /// The moved control points.
    pub points: Vec<DVec3>,
    /// `ε_i` for each index of `moved`, in order.
    pub deltas: Vec<DVec3>,
    /// The system's rank.
    pub rank: usize,
}

/// The least `Σ‖ε_i‖²` over the points `moved` such that `Σ_i basis_l[i] ε_i = diff_l`
/// for every condition `(basis_l, diff_l)` (in least squares when they cannot all
/// hold): §3's system, for any basis with fixed values at the conditions' parameters.
pub(crate) fn point_moves(
    points: &[DVec3],
    moved: &[usize],
    conditions: &[(Vec<f64>, DVec3)],
) -> PointMoves {
    let mut m = DMatrix::zeros(conditions.len(), moved.len());
    let mut r = DMatrix::zeros(conditions.len(), 3);
    for (l, (basis, diff)) in conditions.iter().enumerate() {
        for (k, &i) in moved.iter().enumerate() {
            m[(l, k)] = basis[i];
        }
        for c in 0..3 {
            r[(l, c)] = diff[c];
        }
    }
    let sol = min_norm_solve(&m, &r);
    let deltas: Vec<DVec3> = (0..moved.len())
        .map(|k| DVec3::new(sol.x[(k, 0)], sol.x[(k, 1)], sol.x[(k, 2)]))
        .collect();
    let mut out = points.to_vec();
    for (&i, d) in moved.iter().zip(&deltas) {
        out[i] += *d;
    }
    PointMoves {
        points: out,
        deltas,
        rank: sol.rank,
    }
}

/// Deprecated: `splinescope_core::geom::cubic_region::CubicRegion`.
#[deprecated(note = "use splinescope_core::geom::cubic_region::CubicRegion")]
pub type CubicRegion = cubic_region::CubicRegion;

/// Deprecated: `splinescope_core::geom::cubic_region::PolygonType`.
#[deprecated(note = "use splinescope_core::geom::cubic_region::PolygonType")]
pub type PolygonType = cubic_region::PolygonType;
