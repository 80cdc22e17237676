//! Constrained shape modification of NUBMP curves (paper 001, §5.2): move `P(τ)` to a
//! target `q` by changing one group of shape parameters.
//! `docs/math.md` §3 (constrained modification).

use glam::DVec3;

use super::roots;
use nalgebra::DMatrix;

use super::SolveError;
use super::linalg::min_norm_solve;
use crate::geom::{Nubmp, ParamCurve};

/// The result of [`constrained`].
#[derive(Debug, Clone, PartialEq)]
pub struct ConstrainedSolution {
    /// The modified curve.
    pub curve: Nubmp,
    /// The group changed.
    pub group: usize,
    /// `τ`.
    pub tau: f64,
    /// The group's new parameters, in member order (on the simplex).
    pub values: Vec<f64>,
    /// The region `P(τ)` could reach (its vertices, before the change).
    pub region: Vec<DVec3>,
    /// `|P̃(τ) − q|` (0 up to rounding).
    pub residual: f64,
}

fn list(points: &[DVec3]) -> String {
    points
        .iter()
        .map(|p| format!("({}, {}, {})", p.x, p.y, p.z))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The weights `a` on the simplex with `Σ a_i P_i = target` closest to `current` (least
/// `‖a − current‖`), or `Err(distance)` from `target` to the convex hull of `points`.
///
/// Every support subset is tried (groups are small): on a subset `S` the equality-
/// constrained least-change problem is solved by SVD; feasible solutions (consistent and
/// `a ≥ 0`) compete on their change, infeasible ones give candidate distances.
fn simplex_weights(points: &[DVec3], current: &[f64], target: DVec3) -> Result<Vec<f64>, f64> {
    let k = points.len();
    let scale = points
        .iter()
        .map(|p| p.length())
        .fold(target.length(), f64::max)
        .max(1e-300);
    let tol = 1e-9 * scale;
    let mut best: Option<(f64, Vec<f64>)> = None;
    let mut distance = f64::INFINITY;
    for mask in 1u32..(1 << k.min(16)) {
        let idx: Vec<usize> = (0..k).filter(|&i| mask & (1 << i) != 0).collect();
        // Rows: x, y, z of Σ a_i P_i = target, and Σ a_i = 1.
        let mut a = DMatrix::zeros(4, idx.len());
        for (c, &i) in idx.iter().enumerate() {
            for r in 0..3 {
                a[(r, c)] = points[i][r];
            }
            a[(3, c)] = 1.0;
        }
        let cur = DMatrix::from_iterator(idx.len(), 1, idx.iter().map(|&i| current[i]));
        let mut rhs = DMatrix::zeros(4, 1);
        for r in 0..3 {
            rhs[(r, 0)] = target[r];
        }
        rhs[(3, 0)] = 1.0;
        let delta = min_norm_solve(&a, &(&rhs - &a * &cur));
        let sol = &cur + &delta.x;
        if sol.iter().any(|&v| v < -1e-12) {
            continue;
        }
        // The sum row is weighted like a coordinate: a residual in it is not a distance,
        // so measure the distance with the weights normalised onto the simplex.
        let sum: f64 = sol.iter().sum();
        if sum <= 0.0 {
            continue;
        }
        let reached: DVec3 = idx
            .iter()
            .zip(sol.iter())
            .map(|(&i, &w)| w / sum * points[i])
            .sum();
        let miss = (reached - target).length();
        distance = distance.min(miss);
        if delta.residual <= tol && miss <= tol {
            let mut full = vec![0.0; k];
            for (&i, &w) in idx.iter().zip(sol.iter()) {
                full[i] = w.max(0.0);
            }
            let s: f64 = full.iter().sum();
            for w in &mut full {
                *w /= s;
            }
            let change: f64 = full
                .iter()
                .zip(current)
                .map(|(a, b)| (a - b) * (a - b))
                .sum();
            if best.as_ref().is_none_or(|(c, _)| change < *c) {
                best = Some((change, full));
            }
        }
    }
    match best {
        Some((_, w)) => Ok(w),
        None => Err(distance),
    }
}

/// Checks `τ` against the curve's domain.
fn check_tau(curve: &Nubmp, tau: f64) -> Result<(), SolveError> {
    let (a, b) = curve.domain();
    if !(tau.is_finite() && (a..=b).contains(&tau)) {
        return Err(SolveError::ParameterOutsideDomain {
            value: tau,
            start: a,
            end: b,
        });
    }
    Ok(())
}

fn check_group(curve: &Nubmp, group: usize) -> Result<(), SolveError> {
    if group >= curve.groups().len() {
        return Err(crate::geom::GeomError::NoSuchGroup {
            group,
            groups: curve.groups().len(),
        }
        .into());
    }
    if !curve.groups()[group].effective {
        return Err(crate::geom::GeomError::GroupOutsideDomain { group }.into());
    }
    Ok(())
}

/// Paper 001, §5.2 (steps 1–3): moves `P(τ)` to `q` by changing the parameters of group
/// `j` only. With `w = N*_j(τ) > 0` the new dual point must be
/// `P*_j + (q − P(τ))/w`, a convex combination of the group's control points: a point of
/// the segment (two members) or triangle (three) `P(τ)` can reach. The parameters closest
/// to the current ones are chosen (unique for up to three affinely independent members).
/// With `respect_vd` (order 4) the result must also keep every Theorem 1 condition.
///
/// # Errors
/// [`SolveError`] for a non-finite `q`, `τ` outside the domain, an unknown or inactive
/// group, `q` outside the reachable region (with its distance and the region), or a VD
/// condition broken.
pub fn constrained(
    curve: &Nubmp,
    tau: f64,
    group: usize,
    q: DVec3,
    respect_vd: bool,
) -> Result<ConstrainedSolution, SolveError> {
    if let Some(value) = q.to_array().into_iter().find(|c| !c.is_finite()) {
        return Err(SolveError::NonFiniteTarget { index: 0, value });
    }
    check_tau(curve, tau)?;
    check_group(curve, group)?;
    let w = curve.dual_basis_value(group, tau);
    if w <= 0.0 {
        return Err(SolveError::GroupInactive {
            group,
            tau,
            active: curve
                .groups_at(tau)
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", "),
        });
    }
    let region = curve.reachable_region(tau, group)?;
    let g = &curve.groups()[group];
    let members: Vec<DVec3> = g.members.iter().map(|&i| curve.points()[i]).collect();
    let desired = curve.dual_points()[group] + (q - curve.eval(tau)) / w;
    let values =
        simplex_weights(&members, &g.values, desired).map_err(|d| SolveError::OutsideRegion {
            group,
            distance: d * w,
            vertices: list(&region),
        })?;
    let mut out = curve.clone();
    out.set_group(group, &values)?;
    if respect_vd && out.order() == 4 {
        for h in group.saturating_sub(1)..=(group + 1).min(out.groups().len() - 1) {
            if let Some(v) = out.vd_value(h)
                && v > 1.0 + 1e-12
            {
                return Err(SolveError::BreaksVd { group: h, value: v });
            }
        }
    }
    let residual = (out.eval(tau) - q).length();
    Ok(ConstrainedSolution {
        curve: out,
        group,
        tau,
        values,
        region,
        residual,
    })
}

/// The result of [`find_tau`].
#[derive(Debug, Clone, PartialEq)]
pub struct TauSolution {
    /// The parameter intervals on which group `j` can move `P(τ)` to `q` (single points for
    /// a group of two in the plane, whose paths are segments).
    pub intervals: Vec<(f64, f64)>,
    /// A suggested `τ`: the middle of the longest interval.
    pub best: f64,
}

/// Paper 001, §5.2 (the alternative scenario): given group `j` and a point `q`, the `τ` for
/// which `q` lies in the region `P(τ)` can reach by changing that group. The distance from
/// `q` to the region is scanned over the group's support and its zeros refined (golden
/// section on minima, bisection on interval ends).
///
/// # Errors
/// [`SolveError`] for a non-finite `q`, an unknown or inactive group, or no such `τ`.
pub fn find_tau(curve: &Nubmp, group: usize, q: DVec3) -> Result<TauSolution, SolveError> {
    if let Some(value) = q.to_array().into_iter().find(|c| !c.is_finite()) {
        return Err(SolveError::NonFiniteTarget { index: 0, value });
    }
    check_group(curve, group)?;
    let g = &curve.groups()[group];
    let members: Vec<DVec3> = g.members.iter().map(|&i| curve.points()[i]).collect();
    let rt = curve.refined_knots().knots();
    let k1 = curve.refined_knots().order();
    let (a, b) = curve.domain();
    let (lo, hi) = (rt[group].max(a), rt[group + k1].min(b));
    let scale = members
        .iter()
        .map(|p| p.length())
        .fold(q.length(), f64::max)
        .max(1.0);
    let tol = 1e-9 * scale;
    let distance = |tau: f64| -> f64 {
        let w = curve.dual_basis_value(group, tau);
        if w <= 0.0 {
            return f64::INFINITY;
        }
        let desired = curve.dual_points()[group] + (q - curve.eval(tau)) / w;
        match simplex_weights(&members, &g.values, desired) {
            Ok(_) => 0.0,
            Err(d) => d * w,
        }
    };
    let samples = 2000;
    let planar = q.z == 0.0 && curve.points().iter().all(|p| p.z == 0.0);
    if members.len() == 2 && planar {
        // Paths are segments of one direction e = P_i0 − P_i1: q is on P(τ)'s path exactly
        // where the signed distance (q − P(τ)) × e changes sign. Bisect each change to full
        // precision and keep the roots where q is within the segment.
        let e = members[0] - members[1];
        let side = |tau: f64| {
            let w = q - curve.eval(tau);
            w.x * e.y - w.y * e.x
        };
        let mut intervals = Vec::new();
        let mut prev = (lo, side(lo));
        for s in 1..=samples {
            let t = lo + (hi - lo) * f64::from(s) / f64::from(samples);
            let v = side(t);
            if prev.1 == 0.0 || prev.1.signum() != v.signum() {
                let root = roots::bisect_sign_change(side, prev.0, t, prev.1);
                if distance(root) <= tol
                    && intervals
                        .last()
                        .is_none_or(|&(_, r): &(f64, f64)| (root - r).abs() > 1e-12)
                {
                    intervals.push((root, root));
                }
            }
            prev = (t, v);
        }
        let best = intervals
            .first()
            .map(|i| i.0)
            .ok_or(SolveError::NoTau { group })?;
        return Ok(TauSolution { intervals, best });
    }
    let taus: Vec<f64> = (0..=samples)
        .map(|s| lo + (hi - lo) * f64::from(s) / f64::from(samples))
        .collect();
    let ds: Vec<f64> = taus.iter().map(|&t| distance(t)).collect();
    let mut intervals: Vec<(f64, f64)> = Vec::new();
    let mut s = 0;
    while s < taus.len() {
        if ds[s] <= tol {
            let start = s;
            while s + 1 < taus.len() && ds[s + 1] <= tol {
                s += 1;
            }
            let refine = |inside: f64, outside: f64| {
                roots::bisect_boundary(|m| distance(m) <= tol, inside, outside, 60)
            };
            let left = if start > 0 {
                refine(taus[start], taus[start - 1])
            } else {
                taus[start]
            };
            let right = if s + 1 < taus.len() {
                refine(taus[s], taus[s + 1])
            } else {
                taus[s]
            };
            intervals.push((left, right));
        } else if s > 0 && s + 1 < taus.len() && ds[s] < ds[s - 1] && ds[s] <= ds[s + 1] {
            // A local minimum above the tolerance: a touching point between samples?
            let t = roots::golden_minimum(distance, taus[s - 1], taus[s + 1], 100);
            if distance(t) <= 1e-7 * scale {
                intervals.push((t, t));
            }
        }
        s += 1;
    }
    let best = intervals
        .iter()
        .max_by(|x, y| (x.1 - x.0).total_cmp(&(y.1 - y.0)))
        .map(|&(x, y)| 0.5 * (x + y))
        .ok_or(SolveError::NoTau { group })?;
    Ok(TauSolution { intervals, best })
}
