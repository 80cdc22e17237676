//! Least-squares shape modification of Bézier curves (paper 000: "Optimal shape
//! modification of Bézier curves by geometric constraints"): move control points by the
//! least `Σ‖ε_i‖²` so that the curve passes through target points, with the end points
//! fixed and optionally the end tangents kept.
//! Formulas and decisions (the default window of Eq. 8, the cubic allowed region):
//! `docs/math.md` §2.

use glam::{DVec2, DVec3};
use nalgebra::DMatrix;

use super::SolveError;
use super::linalg::min_norm_solve;
use super::project::nearest;
use crate::geom::bernstein::bernstein_all;
use crate::geom::cubic_region::REGION_TOLERANCE;
pub use crate::geom::cubic_region::{CubicRegion, PolygonType};
use crate::geom::{Aabb, Bezier, Lower, ParamCurve};

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

/// Classifies a cubic's control polygon and returns its reachable region
/// ([`CubicRegion::from_cubic`] with the solver's errors).
///
/// # Errors
/// [`SolveError::NotCubic`] unless the degree is 3; [`SolveError::NoTangent`] for
/// coincident end points.
pub fn cubic_region(curve: &Bezier) -> Result<CubicRegion, SolveError> {
    if curve.degree() != 3 {
        return Err(SolveError::NotCubic {
            degree: curve.degree(),
        });
    }
    let directions = end_directions(curve)?;
    Ok(CubicRegion::from_cubic(curve.points(), directions))
}

/// An orthonormal basis `(u, v)` of the plane through `P_0` holding `d`, `e_1`, `e_2`, when
/// they are coplanar.
fn plane_basis(d: DVec3, e1: DVec3, e2: DVec3) -> Option<(DVec3, DVec3)> {
    let normal = [d.cross(e1), d.cross(e2), e1.cross(e2)]
        .into_iter()
        .max_by(|a, b| a.length().total_cmp(&b.length()))
        .and_then(|v| v.try_normalize())?;
    let coplanar = [d.normalize_or_zero(), e1, e2]
        .iter()
        .all(|v| v.dot(normal).abs() <= 1e-9);
    if !coplanar {
        return None;
    }
    let u = e1;
    let v = normal.cross(u).normalize();
    Some((u, v))
}

impl CubicRegion {
    fn scale(&self) -> f64 {
        (self.p3 - self.p0).length().max(1e-300)
    }

    /// Whether `target` is reachable (slides unlimited, `s, r ≥ 0`). Points within
    /// `1e-9 · |P_3 − P_0|` of the boundary count as inside.
    #[must_use]
    pub fn contains(&self, target: DVec3) -> bool {
        let d = self.p3 - self.p0;
        let w = target - self.p0;
        let tol = REGION_TOLERANCE;
        let inside = |lambda: f64, a: f64, b: f64| {
            lambda > -tol
                && lambda < 1.0 + tol
                && a >= -tol * self.scale()
                && b >= -tol * self.scale()
        };
        // Coplanar: 2D coordinates in the plane; otherwise a 3×3 solve.
        let Some((u, v)) = plane_basis(d, self.e1, self.e2) else {
            let m = glam::DMat3::from_cols(d, self.e1, self.e2);
            if m.determinant().abs() <= 1e-12 {
                return false;
            }
            let x = m.inverse() * w;
            return inside(x.x, x.y, x.z);
        };
        let to2 = |x: DVec3| DVec2::new(x.dot(u), x.dot(v));
        // Off the plane: unreachable.
        if (w - u * w.dot(u) - v * w.dot(v)).length() > tol * self.scale().max(w.length()) {
            return false;
        }
        let (d2, e1, e2, w2) = (to2(d), to2(self.e1), to2(self.e2), to2(w));
        let det = e1.perp_dot(e2);
        if det.abs() > 1e-12 {
            // (a, b) = [e1 e2]⁻¹ (w − λ d), affine in λ: find λ ∈ (0, 1) with a, b ≥ 0.
            let solve = |q: DVec2| DVec2::new(q.perp_dot(e2) / det, e1.perp_dot(q) / det);
            let at0 = solve(w2);
            let slope = -solve(d2);
            let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
            for (c0, c1) in [(at0.x, slope.x), (at0.y, slope.y)] {
                // c0 + c1 λ ≥ −tol
                let floor = -tol * self.scale();
                if c1.abs() < 1e-15 {
                    if c0 < floor {
                        return false;
                    }
                } else if c1 > 0.0 {
                    lo = lo.max((floor - c0) / c1);
                } else {
                    hi = hi.min((floor - c0) / c1);
                }
            }
            return lo <= hi + tol;
        }
        // Parallel legs: the cone is a ray (same direction) or a line (opposite).
        let n = DVec2::new(-e1.y, e1.x);
        let nd = n.dot(d2);
        if nd.abs() <= 1e-15 {
            // P0P3 parallel to the legs: only the line itself.
            return n.dot(w2).abs() <= tol * self.scale();
        }
        let lambda = n.dot(w2) / nd;
        if !(lambda > -tol && lambda < 1.0 + tol) {
            return false;
        }
        let along = e1.dot(w2 - lambda * d2);
        e1.dot(e2) < 0.0 || along >= -tol * self.scale()
    }

    /// Whether `target` is reachable with the slides of a type-2 polygon limited to
    /// `[P_0, X]` and `[P_3, X]`: inside the area between the segment `P_0P_3` and the cubic
    /// `(P_0, X, X, P_3)`. `None` unless the polygon is of type 2.
    #[must_use]
    pub fn contains_limited(&self, target: DVec3) -> Option<bool> {
        let PolygonType::Converging { apex } = self.kind else {
            return None;
        };
        let boundary = self.limited_boundary(apex, 1e-9 * self.scale());
        let (u, v) = plane_basis(self.p3 - self.p0, self.e1, self.e2)?;
        let to2 = |x: DVec3| DVec2::new((x - self.p0).dot(u), (x - self.p0).dot(v));
        let w = target - self.p0;
        if (w - u * w.dot(u) - v * w.dot(v)).length()
            > REGION_TOLERANCE * self.scale().max(w.length())
        {
            return Some(false);
        }
        let q = to2(target);
        let poly: Vec<DVec2> = boundary.iter().map(|&p| to2(p)).collect();
        // Even-odd rule.
        let mut inside = false;
        for k in 0..poly.len() {
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            if (a.y > q.y) != (b.y > q.y) {
                let x = a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x);
                if q.x < x {
                    inside = !inside;
                }
            }
        }
        Some(inside)
    }

    /// The closed boundary of the limited type-2 region: the cubic `(P_0, X, X, P_3)`
    /// flattened to `tolerance`, closed by the segment `P_3P_0`.
    fn limited_boundary(&self, apex: DVec3, tolerance: f64) -> Vec<DVec3> {
        let c = Bezier::new(vec![self.p0, apex, apex, self.p3]);
        let mut out = vec![self.p0];
        flatten(&c, 0.0, 1.0, tolerance, 0, &mut out);
        out
    }

    /// Polylines outlining the region for drawing. Unlimited: the region clipped at
    /// `reach` from the end points (a strip, half-strip or sector). With `limited` and a
    /// type-2 polygon: the segment and the cubic `(P_0, X, X, P_3)`.
    #[must_use]
    pub fn boundary(&self, limited: bool, reach: f64) -> Vec<Vec<DVec3>> {
        if let (true, PolygonType::Converging { apex }) = (limited, self.kind) {
            let mut b = self.limited_boundary(apex, 1e-4 * self.scale());
            b.push(self.p0);
            return vec![b];
        }
        let far = [
            self.p0 + reach * self.e1,
            self.p0 + reach * self.e2,
            self.p3 + reach * self.e1,
            self.p3 + reach * self.e2,
        ];
        let Some((u, v)) = plane_basis(self.p3 - self.p0, self.e1, self.e2) else {
            // 3D: the segment and the four rays.
            let mut lines = vec![vec![self.p0, self.p3]];
            lines.push(vec![self.p0, far[0]]);
            lines.push(vec![self.p0, far[1]]);
            lines.push(vec![self.p3, far[2]]);
            lines.push(vec![self.p3, far[3]]);
            return lines;
        };
        let mut pts: Vec<DVec3> = vec![self.p0, self.p3];
        pts.extend(far);
        let hull = convex_hull(&pts, u, v, self.p0);
        let mut closed = hull.clone();
        if let Some(&first) = hull.first() {
            closed.push(first);
        }
        vec![closed]
    }

    /// A box around the region's drawn boundary.
    #[must_use]
    pub fn bounds(&self, reach: f64) -> Aabb {
        self.boundary(false, reach)
            .iter()
            .fold(Aabb::EMPTY, |b, l| b.union(Aabb::from_points(l)))
    }
}

/// Appends the flattened points of `c` on `(t0, t1]` to `out`.
fn flatten(c: &Bezier, t0: f64, t1: f64, tol: f64, depth: u32, out: &mut Vec<DVec3>) {
    let piece = c.subsegment(t0, t1);
    if piece.flatness() <= tol || depth >= 24 {
        out.push(piece.points()[3]);
    } else {
        let mid = 0.5 * (t0 + t1);
        flatten(c, t0, mid, tol, depth + 1, out);
        flatten(c, mid, t1, tol, depth + 1, out);
    }
}

/// The convex hull (counter-clockwise) of points lying in the plane through `origin`
/// spanned by the orthonormal `u`, `v`.
fn convex_hull(points: &[DVec3], u: DVec3, v: DVec3, origin: DVec3) -> Vec<DVec3> {
    let mut pts: Vec<(DVec2, DVec3)> = points
        .iter()
        .map(|&p| (DVec2::new((p - origin).dot(u), (p - origin).dot(v)), p))
        .collect();
    pts.sort_by(|a, b| a.0.x.total_cmp(&b.0.x).then(a.0.y.total_cmp(&b.0.y)));
    pts.dedup_by(|a, b| (a.0 - b.0).length() < 1e-12);
    if pts.len() < 3 {
        return pts.into_iter().map(|p| p.1).collect();
    }
    let cross = |o: DVec2, a: DVec2, b: DVec2| (a - o).perp_dot(b - o);
    let mut lower: Vec<(DVec2, DVec3)> = Vec::new();
    for &p in &pts {
        while lower.len() >= 2
            && cross(lower[lower.len() - 2].0, lower[lower.len() - 1].0, p.0) <= 0.0
        {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<(DVec2, DVec3)> = Vec::new();
    for &p in pts.iter().rev() {
        while upper.len() >= 2
            && cross(upper[upper.len() - 2].0, upper[upper.len() - 1].0, p.0) <= 0.0
        {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.into_iter().chain(upper).map(|p| p.1).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p2(x: f64, y: f64) -> DVec3 {
        DVec3::new(x, y, 0.0)
    }

    #[test]
    fn polygon_types_are_classified() {
        let parallel = Bezier::new(vec![p2(0., 0.), p2(0., 1.), p2(3., 1.), p2(3., 0.)]);
        assert_eq!(cubic_region(&parallel).unwrap().kind, PolygonType::Parallel);
        let converging = Bezier::new(vec![p2(0., 0.), p2(1., 1.), p2(3., 1.), p2(4., 0.)]);
        match cubic_region(&converging).unwrap().kind {
            PolygonType::Converging { apex } => assert!((apex - p2(2., 2.)).length() < 1e-12),
            other => panic!("{other:?}"),
        }
        let diverging = Bezier::new(vec![p2(0., 0.), p2(-1., 1.), p2(5., 1.), p2(4., 0.)]);
        assert_eq!(
            cubic_region(&diverging).unwrap().kind,
            PolygonType::Diverging
        );
    }

    #[test]
    fn coincident_end_points_have_no_tangent() {
        let b = Bezier::new(vec![p2(0., 0.), p2(0., 0.), p2(3., 1.), p2(3., 0.)]);
        assert!(matches!(
            tangent_kept(&b, p2(1., 1.), Some(0.5), None),
            Err(SolveError::NoTangent { .. })
        ));
    }
}
