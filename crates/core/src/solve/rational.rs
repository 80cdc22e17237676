//! Paper 000's least-squares shape modification for rational curves (rational Bézier and
//! NURBS), the weights held fixed. With fixed weights the curve `C(t) = Σ R_i(t) P_i`,
//! `R_i(t) = w_i N_i(t) / Σ_j w_j N_j(t)` (`N_i` the Bernstein or B-spline basis), is
//! linear in the control points, so the constraints `C̃(t_l) = T_l` stay linear in the
//! moves `ε_i` and the minimal change is the minimum-norm solution of
//! `Σ_i R_i(t_l) ε_i = T_l − C(t_l)` — the polynomial solvers' systems
//! ([`super::shape`]) with the rational basis in place of the Bernstein one. The end
//! points stay fixed; the weights do not change.

use glam::DVec3;

use super::SolveError;
use crate::geom::bernstein::bernstein_all;
use crate::geom::{GeomError, Lower, Nurbs, ParamCurve, RationalBezier};

/// A rational curve the solvers modify: its control points, its rational basis, and the
/// same curve on new points (same weights, same knots).
pub trait RationalCurve: ParamCurve + Lower + Clone {
    /// The control points.
    fn points(&self) -> &[DVec3];
    /// Every rational basis function `R_i(t)` (one per control point).
    fn basis(&self, t: f64) -> Vec<f64>;
    /// The same weights (and knots) on new points.
    ///
    /// # Errors
    /// The family's error for points it refuses.
    fn with_points(&self, points: Vec<DVec3>) -> Result<Self, GeomError>;
}

/// The rational basis `R_i(t)` of `weights` (degree `weights.len() − 1`).
#[must_use]
pub fn rational_basis(weights: &[f64], t: f64) -> Vec<f64> {
    normalised(
        bernstein_all(weights.len() - 1, t)
            .iter()
            .zip(weights)
            .map(|(b, w)| b * w)
            .collect(),
    )
}

fn normalised(weighted: Vec<f64>) -> Vec<f64> {
    let sum: f64 = weighted.iter().sum();
    weighted.iter().map(|v| v / sum).collect()
}

impl RationalCurve for RationalBezier {
    fn points(&self) -> &[DVec3] {
        RationalBezier::points(self)
    }
    fn basis(&self, t: f64) -> Vec<f64> {
        rational_basis(self.weights(), t)
    }
    fn with_points(&self, points: Vec<DVec3>) -> Result<RationalBezier, GeomError> {
        RationalBezier::try_new(points, self.weights().to_vec())
    }
}

impl RationalCurve for Nurbs {
    fn points(&self) -> &[DVec3] {
        Nurbs::points(self)
    }
    fn basis(&self, t: f64) -> Vec<f64> {
        let (mu, n) = self.knots().basis(t);
        let k = self.order();
        let mut weighted = vec![0.0; self.points().len()];
        for (j, v) in n.iter().enumerate() {
            let i = mu + 1 + j - k;
            weighted[i] = v * self.weights()[i];
        }
        normalised(weighted)
    }
    fn with_points(&self, points: Vec<DVec3>) -> Result<Nurbs, GeomError> {
        Nurbs::from_knot_vector(points, self.weights().to_vec(), self.knots().clone())
    }
}

/// The result of the rational solvers.
#[derive(Debug, Clone, PartialEq)]
pub struct RationalSolution<C> {
    /// The modified curve (same weights).
    pub curve: C,
    /// The parameter of each target.
    pub params: Vec<f64>,
    /// The moved control points' indices, in order.
    pub moved: Vec<usize>,
    /// Their moves `ε_i`.
    pub deltas: Vec<DVec3>,
    /// `|C̃(t_l) − T_l|` per target (0 up to rounding unless solved in least squares).
    pub residuals: Vec<f64>,
    /// The rank of the system.
    pub rank: usize,
    /// Whether the system had fewer free parameters than conditions (least squares).
    pub least_squares: bool,
}

/// The result of [`tangent_kept`]: as [`RationalSolution`], with the slides along the end
/// tangents.
#[derive(Debug, Clone, PartialEq)]
pub struct TangentKeptSolution<C> {
    /// The solution (`moved` and `deltas` for the free inner points `P_2..P_{n−2}`).
    pub solution: RationalSolution<C>,
    /// `μ_1`, `μ_2`: how far `P_1` and `P_{n−1}` slid along `e_1`, `e_2`.
    pub mu: [f64; 2],
    /// The unit end-tangent directions `e_1 = unit(P_1 − P_0)`, `e_2 = unit(P_{n−1} − P_n)`.
    pub directions: [DVec3; 2],
}

/// The parameter of target `index`: given (strictly inside the domain), or found by
/// projecting the target onto the curve (an error when it projects onto a fixed end).
fn parameter<C: RationalCurve>(
    curve: &C,
    index: usize,
    target: DVec3,
    given: Option<f64>,
    accuracy: Option<f64>,
) -> Result<f64, SolveError> {
    if let Some(value) = target.to_array().into_iter().find(|c| !c.is_finite()) {
        return Err(SolveError::NonFiniteTarget { index, value });
    }
    super::shape::start_parameter(curve, target, index, given, accuracy)
}

/// The targets' parameters, checked.
fn parameters<C: RationalCurve>(
    curve: &C,
    targets: &[DVec3],
    params: Option<&[f64]>,
    accuracy: Option<f64>,
) -> Result<Vec<f64>, SolveError> {
    if targets.is_empty() {
        return Err(SolveError::NoTargets);
    }
    if let Some(p) = params
        && p.len() != targets.len()
    {
        return Err(SolveError::ParamCount {
            targets: targets.len(),
            params: p.len(),
        });
    }
    targets
        .iter()
        .enumerate()
        .map(|(l, &target)| parameter(curve, l, target, params.map(|p| p[l]), accuracy))
        .collect()
}

fn degree_at_least<C: RationalCurve>(
    curve: &C,
    method: &'static str,
    min: usize,
) -> Result<usize, SolveError> {
    let last = curve.points().len() - 1;
    if last < min {
        return Err(SolveError::DegreeTooLow {
            method,
            degree: last,
            min,
        });
    }
    Ok(last)
}

/// Paper 000 §3 with the weights fixed: moves every interior point `P_1..P_{n−1}` by the
/// least `Σ‖ε_i‖²` so that the curve passes through `targets[l]` at `params[l]` (given, or
/// found by projecting each target onto the curve).
///
/// # Errors
/// [`SolveError`] for no targets, a count mismatch, fewer than 3 points, a non-finite
/// target, a parameter outside the domain or at a (fixed) end.
pub fn multi_target<C: RationalCurve>(
    curve: &C,
    targets: &[DVec3],
    params: Option<&[f64]>,
    accuracy: Option<f64>,
) -> Result<RationalSolution<C>, SolveError> {
    let last = degree_at_least(curve, "multi_target", 2)?;
    let params = parameters(curve, targets, params, accuracy)?;
    solve(curve, targets, params, (1..last).collect())
}

/// Paper 000 §2.1 with the weights fixed: one target at `t` (given, or the target's
/// projection), moving `count` consecutive interior points from `first` (the window of
/// largest `Σ R_i(t)²` of `min(3, n − 1)` points when `None`):
/// `ε_i = R_i(t) (T − C(t)) / Σ_{j∈window} R_j(t)²`.
///
/// # Errors
/// As [`multi_target`], and [`SolveError::WindowOutOfRange`] for a window that is not
/// interior.
pub fn single_target<C: RationalCurve>(
    curve: &C,
    target: DVec3,
    t: Option<f64>,
    window: Option<(usize, usize)>,
    accuracy: Option<f64>,
) -> Result<RationalSolution<C>, SolveError> {
    degree_at_least(curve, "single_target", 2)?;
    let t = parameter(curve, 0, target, t, accuracy)?;
    let basis = curve.basis(t);
    let (first, count) = super::shape::window(&basis, window)?;
    let moved: Vec<usize> = (first..first + count).collect();
    super::shape::check_influence(&basis, &moved, 0, t)?;
    solve(curve, &[target], vec![t], moved)
}

/// Paper 000 §2.2 with the weights fixed: keeps `P_0`, `P_n` and the end tangents (`P_1`
/// slides on the line `P_0P_1`, `P_{n−1}` on `P_nP_{n−1}`), moves `P_2..P_{n−2}` freely and
/// passes through `T` at `t` — the minimum-norm solution of
/// `μ_1 R_1(t) e_1 + μ_2 R_{n−1}(t) e_2 + Σ_{i=2}^{n−2} ε_i R_i(t) = T − C(t)`.
/// With four points only `μ_1, μ_2` are free (least squares off the plane they span).
///
/// # Errors
/// As [`single_target`]; fewer than 4 points; [`SolveError::NoTangent`] when an end point
/// coincides with its neighbour.
pub fn tangent_kept<C: RationalCurve>(
    curve: &C,
    target: DVec3,
    t: Option<f64>,
    accuracy: Option<f64>,
) -> Result<TangentKeptSolution<C>, SolveError> {
    let n = degree_at_least(curve, "tangent_kept", 3)?;
    let directions = super::shape::polygon_end_directions(curve.points())?;
    let t = parameter(curve, 0, target, t, accuracy)?;
    let basis = curve.basis(t);
    super::shape::check_influence(&basis, &(1..n).collect::<Vec<_>>(), 0, t)?;
    let diff = target - curve.eval(t);
    let moves = super::shape::tangent_moves(curve.points(), &basis, directions, target, diff);
    super::shape::check_moves_finite(&moves.points, &[t])?;
    let modified = curve.with_points(moves.points)?;
    let residual = (modified.eval(t) - target).length();
    if !moves.over_determined {
        super::shape::check_met(
            curve.points(),
            &[(basis, diff)],
            &[target],
            &[t],
            &[residual],
        )?;
    }
    Ok(TangentKeptSolution {
        solution: RationalSolution {
            curve: modified,
            params: vec![t],
            moved: (2..n - 1).collect(),
            deltas: moves.deltas,
            residuals: vec![residual],
            rank: moves.rank,
            least_squares: moves.least_squares,
        },
        mu: moves.mu,
        directions,
    })
}

fn solve<C: RationalCurve>(
    curve: &C,
    targets: &[DVec3],
    params: Vec<f64>,
    moved: Vec<usize>,
) -> Result<RationalSolution<C>, SolveError> {
    let conditions: Vec<(Vec<f64>, DVec3)> = params
        .iter()
        .zip(targets)
        .map(|(&t, &target)| (curve.basis(t), target - curve.eval(t)))
        .collect();
    for (l, (basis, _)) in conditions.iter().enumerate() {
        super::shape::check_influence(basis, &moved, l, params[l])?;
    }
    let moves = super::shape::point_moves(curve.points(), &moved, &conditions);
    super::shape::check_moves_finite(&moves.points, &params)?;
    let modified = curve.with_points(moves.points)?;
    let residuals: Vec<f64> = params
        .iter()
        .zip(targets)
        .map(|(&t, &target)| (modified.eval(t) - target).length())
        .collect();
    let least_squares = moves.rank < targets.len();
    if !super::shape::over_determined(targets.len(), moved.len(), &params) {
        super::shape::check_met(curve.points(), &conditions, targets, &params, &residuals)?;
    }
    Ok(RationalSolution {
        curve: modified,
        params,
        moved,
        deltas: moves.deltas,
        residuals,
        rank: moves.rank,
        least_squares,
    })
}
