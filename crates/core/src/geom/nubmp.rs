//! Non-uniform B-splines with multiple shape parameters (NUBMP) — paper 001 (Cao, Wang,
//! Li, Chen, "Non-uniform B-spline curves with multiple shape parameters", J. Zhejiang
//! Univ.-Sci. C 12(10), 2011). Formulas and decisions (unclamped groups, the Fig. 1b
//! range, locality): `docs/math.md` §3.

use glam::DVec3;

use super::bezier::check_finite;
use super::bspline::{Elevation, elevation_coefficients};
use super::exact::Rational;

use super::family::{AtTau, Family, GroupAtTau, xyz};
use super::{BSpline, BezierSegment, GeomError, KnotVector, Lower, ParamCurve};

/// How far a group's sum may be from 1 and still be accepted.
pub const GROUP_SUM_TOLERANCE: f64 = 1e-9;

/// One group `A_j`: the shape parameters `a^i_j` of the members `i` whose B-spline
/// `N_{i,k}` uses the dual B-spline `N*_{j,k+1}`.
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// The members `i` (control point indices), increasing.
    pub members: Vec<usize>,
    /// The standard values `c^i_j` (the ordinary B-spline), by member.
    pub standard: Vec<f64>,
    /// The current values `a^i_j`, by member.
    pub values: Vec<f64>,
    /// Whether `N*_j` is non-zero somewhere inside the domain. Always true for clamped
    /// knots; with unclamped knots the groups wholly outside the domain keep their standard
    /// values and cannot be set (they do not change the curve).
    pub effective: bool,
}

impl Group {
    /// The position of member `i` in [`Group::members`].
    #[must_use]
    pub fn position(&self, i: usize) -> Option<usize> {
        self.members.iter().position(|&m| m == i)
    }

    /// `a^i_j` for member `i`.
    #[must_use]
    pub fn value(&self, i: usize) -> Option<f64> {
        self.position(i).map(|p| self.values[p])
    }
}

/// A NUBMP curve of order `k` (paper 001, Definitions 1–2):
///
/// `P(t) = Σ_{i=0..n−1} Ñ_{i,k}(t) P_i`, `Ñ_{i,k} = Σ_j a^i_j N*_{j,k+1}`,
///
/// where `N*_{j,k+1}` are the order-`k+1` B-splines on the refined knots `T*` (each distinct
/// knot once more) and the shape parameters satisfy `a^i_j ≥ 0` and, for each group
/// `A_j = {a^i_j : i}`, `Σ_i a^i_j = 1`. With `a = c`, the exact degree-elevation
/// coefficients, the curve is the ordinary B-spline (the *standard curve*).
///
/// Equivalently (the dual form, Eq. 9) it is the order-`k+1` B-spline on `T*` with dual
/// control points `P*_j = Σ_i a^i_j P_i`: that is how it is evaluated, and lowered (Bézier
/// extraction of the dual B-spline).
#[derive(Debug, Clone, PartialEq)]
pub struct Nubmp {
    pub(crate) points: Vec<DVec3>,
    pub(crate) knots: KnotVector,
    pub(crate) refined: KnotVector,
    pub(crate) groups: Vec<Group>,
    pub(crate) dual: BSpline,
}

/// The result of a permissible-range query.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PermissibleRange {
    /// The smallest permissible value of the parameter.
    pub min: f64,
    /// The largest.
    pub max: f64,
}

impl Nubmp {
    /// The standard NUBMP curve (all `a = c`) on `points`, `knots` and `order`.
    ///
    /// # Errors
    /// [`GeomError`] for invalid knots or points.
    pub fn try_new(points: Vec<DVec3>, knots: Vec<f64>, order: usize) -> Result<Nubmp, GeomError> {
        check_finite(&points)?;
        let knots = KnotVector::try_new(knots, order, points.len())?;
        Nubmp::standard(points, knots)
    }

    /// The standard curve from validated parts.
    ///
    /// # Errors
    /// [`GeomError::DerivedNotFinite`] when an elevation coefficient or a dual control
    /// point overflows `f64` (distinct knots so close that their difference is subnormal,
    /// say).
    ///
    /// # Panics
    /// If `points.len()` differs from the knot vector's point count (a bug in the caller).
    pub fn standard(points: Vec<DVec3>, knots: KnotVector) -> Result<Nubmp, GeomError> {
        assert_eq!(
            points.len(),
            knots.n_points(),
            "points must match the knots"
        );
        let k = knots.order();
        let e: Elevation<f64> = elevation_coefficients(knots.knots(), k);
        for (i, row) in e.rows.iter().enumerate() {
            for (jj, &c) in row.values.iter().enumerate() {
                if !c.is_finite() {
                    return Err(GeomError::DerivedNotFinite {
                        field: "knots",
                        what: format!("degree-elevation coefficient c^{i}_{}", row.first + jj),
                        value: c,
                    });
                }
            }
        }
        if let Some(&t) = e.refined.iter().find(|t| !t.is_finite()) {
            return Err(GeomError::DerivedNotFinite {
                field: "knots",
                what: "a refined knot".into(),
                value: t,
            });
        }
        let n_star = e.refined.len() - (k + 1);
        let refined = KnotVector::try_new(e.refined.clone(), k + 1, n_star)
            .unwrap_or_else(|err| unreachable!("refined knots are valid: {err}"));
        let (a, b) = knots.domain();
        let rt = refined.knots();
        let mut groups: Vec<Group> = (0..n_star)
            .map(|j| Group {
                members: Vec::new(),
                standard: Vec::new(),
                values: Vec::new(),
                effective: rt[j] < b && rt[j + k + 1] > a,
            })
            .collect();
        for (i, row) in e.rows.iter().enumerate() {
            for (jj, &c) in row.values.iter().enumerate() {
                let g = &mut groups[row.first + jj];
                g.members.push(i);
                g.standard.push(c);
                g.values.push(c);
            }
        }
        let dual = dual_spline(&points, &groups, &refined)?;
        Ok(Nubmp {
            points,
            knots,
            refined,
            groups,
            dual,
        })
    }

    /// The control points `P_i`.
    #[must_use]
    pub fn points(&self) -> &[DVec3] {
        &self.points
    }

    /// The knot vector `T` (order `k`).
    #[must_use]
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// The refined knot vector `T*` (order `k + 1`).
    #[must_use]
    pub fn refined_knots(&self) -> &KnotVector {
        &self.refined
    }

    /// The order `k`.
    #[must_use]
    pub fn order(&self) -> usize {
        self.knots.order()
    }

    /// The groups `A_j`, `j = 0..n*`.
    #[must_use]
    pub fn groups(&self) -> &[Group] {
        &self.groups
    }

    /// The number of free shape parameters `Σ_j (#A_j − 1)` over the effective groups
    /// (paper 001, Eq. 8).
    #[must_use]
    pub fn free_parameter_count(&self) -> usize {
        self.groups
            .iter()
            .filter(|g| g.effective)
            .map(|g| g.members.len() - 1)
            .sum()
    }

    /// The dual control points `P*_j = Σ_i a^i_j P_i`.
    #[must_use]
    pub fn dual_points(&self) -> &[DVec3] {
        self.dual.points()
    }

    /// The dual curve: the order-`k+1` B-spline on `T*` with the dual control points.
    #[must_use]
    pub fn dual_spline(&self) -> &BSpline {
        &self.dual
    }

    /// Whether every parameter has its standard value.
    #[must_use]
    pub fn is_standard(&self) -> bool {
        self.groups.iter().all(|g| g.values == g.standard)
    }

    /// Group `A_j`.
    ///
    /// # Errors
    /// [`GeomError::NoSuchGroup`] for a `j` the curve does not have.
    pub fn group(&self, j: usize) -> Result<&Group, GeomError> {
        self.groups.get(j).ok_or(GeomError::NoSuchGroup {
            group: j,
            groups: self.groups.len(),
        })
    }

    fn member_position(&self, j: usize, i: usize) -> Result<usize, GeomError> {
        let g = self.group(j)?;
        g.position(i).ok_or_else(|| GeomError::NotInGroup {
            group: j,
            member: i,
            members: g
                .members
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", "),
        })
    }

    /// The same curve with new control points (shape parameters kept).
    ///
    /// # Errors
    /// [`GeomError::TooFewPoints`] / [`GeomError::KnotCount`] when the count changes, or a
    /// non-finite point.
    pub fn with_points(&self, points: Vec<DVec3>) -> Result<Nubmp, GeomError> {
        check_finite(&points)?;
        if points.len() != self.points.len() {
            return Err(GeomError::KnotCount {
                expected: points.len() + self.order(),
                found: self.knots.knots().len(),
                points: points.len(),
                order: self.order(),
            });
        }
        let mut out = self.clone();
        out.points = points;
        out.update_dual()?;
        Ok(out)
    }

    /// Sets all parameters of group `j` (in member order).
    ///
    /// # Errors
    /// [`GeomError`] when the group does not exist or lies outside the domain, the count is
    /// wrong, a value is negative or not finite, or the sum is not 1 within
    /// [`GROUP_SUM_TOLERANCE`]. Nothing changes on error.
    pub fn set_group(&mut self, j: usize, values: &[f64]) -> Result<(), GeomError> {
        let g = self.group(j)?;
        if values.len() != g.members.len() {
            return Err(GeomError::GroupSize {
                group: j,
                expected: g.members.len(),
                found: values.len(),
            });
        }
        for (&member, &value) in g.members.iter().zip(values) {
            if !(value.is_finite() && value >= 0.0) {
                return Err(GeomError::NegativeParameter {
                    group: j,
                    member,
                    value,
                });
            }
        }
        let sum: f64 = values.iter().sum();
        if (sum - 1.0).abs() > GROUP_SUM_TOLERANCE {
            return Err(GeomError::GroupSum {
                group: j,
                sum,
                tolerance: GROUP_SUM_TOLERANCE,
            });
        }
        if !g.effective && values != g.standard.as_slice() {
            return Err(GeomError::GroupOutsideDomain { group: j });
        }
        let before = std::mem::replace(&mut self.groups[j].values, values.to_vec());
        if let Err(e) = self.update_dual() {
            // Refused: the curve stays as it was.
            self.groups[j].values = before;
            return Err(e);
        }
        Ok(())
    }

    /// Sets `a^i_j = value`, member `absorber` of the same group taking the difference so
    /// the group still sums to 1 (paper 001, Eq. 10–11).
    ///
    /// # Errors
    /// [`GeomError`] when a member is not in the group, the two are the same, or a
    /// resulting value would be negative. Nothing changes on error.
    pub fn set_parameter(
        &mut self,
        j: usize,
        i: usize,
        value: f64,
        absorber: usize,
    ) -> Result<(), GeomError> {
        let pi = self.member_position(j, i)?;
        let pa = self.member_position(j, absorber)?;
        if pi == pa {
            return Err(GeomError::SameAbsorber { member: i });
        }
        let mut values = self.groups[j].values.clone();
        let pair = values[pi] + values[pa];
        if !(value.is_finite() && value >= 0.0) {
            return Err(GeomError::NegativeParameter {
                group: j,
                member: i,
                value,
            });
        }
        if value > pair {
            return Err(GeomError::AbsorberNegative {
                group: j,
                member: i,
                absorber,
                value,
                pair,
            });
        }
        values[pi] = value;
        values[pa] = pair - value;
        self.set_group(j, &values)
    }

    fn update_dual(&mut self) -> Result<(), GeomError> {
        self.dual = dual_spline(&self.points, &self.groups, &self.refined)?;
        Ok(())
    }

    /// The NUBMP basis functions `Ñ_{i,k}(t) = Σ_j a^i_j N*_{j,k+1}(t)` that are non-zero at
    /// `t`, as `(i, value)`.
    #[must_use]
    pub fn basis(&self, t: f64) -> Vec<(usize, f64)> {
        let (mu, n_star) = self.refined.basis(t);
        let k1 = self.refined.order();
        let mut out: Vec<(usize, f64)> = Vec::new();
        for (r, &nj) in n_star.iter().enumerate() {
            let j = mu + 1 - k1 + r;
            let g = &self.groups[j];
            for (&i, &a) in g.members.iter().zip(&g.values) {
                match out.iter_mut().find(|(m, _)| *m == i) {
                    Some(slot) => slot.1 += a * nj,
                    None => out.push((i, a * nj)),
                }
            }
        }
        out.sort_by_key(|&(i, _)| i);
        out
    }

    /// `P(t) = Σ_i Ñ_{i,k}(t) P_i` through the original basis (the dual form,
    /// [`ParamCurve::eval`], is the same curve).
    #[must_use]
    pub fn eval_by_basis(&self, t: f64) -> DVec3 {
        self.basis(t)
            .into_iter()
            .map(|(i, w)| w * self.points[i])
            .sum()
    }

    /// `N*_{j,k+1}(t)`.
    #[must_use]
    pub fn dual_basis_value(&self, j: usize, t: f64) -> f64 {
        let (mu, n_star) = self.refined.basis(t);
        let k1 = self.refined.order();
        if j + k1 > mu && j <= mu {
            n_star[j + k1 - 1 - mu]
        } else {
            0.0
        }
    }

    /// The knot spans of `T` (as parameter intervals inside the domain) on which group `j`'s
    /// parameters change the curve: the support of `N*_j` (paper 001, §4: at most
    /// `⌊k/2⌋ + 1` spans).
    #[must_use]
    pub fn affected_spans(&self, j: usize) -> Vec<(f64, f64)> {
        let rt = self.refined.knots();
        let k1 = self.refined.order();
        let (a, b) = self.knots.domain();
        let (lo, hi) = (rt[j].max(a), rt[j + k1].min(b));
        // The distinct knots in [lo, hi] (all breakpoints, as lo ≥ a and hi ≤ b), found by
        // binary search: linear in the group's support, not in the curve's size.
        let t = self.knots.knots();
        let mut bps = t[t.partition_point(|&x| x < lo)..t.partition_point(|&x| x <= hi)].to_vec();
        bps.dedup();
        bps.windows(2).map(|w| (w[0], w[1])).collect()
    }

    /// The groups whose dual B-spline is non-zero at `τ` (those that can move `P(τ)`).
    #[must_use]
    pub fn groups_at(&self, tau: f64) -> Vec<usize> {
        (0..self.groups.len())
            .filter(|&j| self.groups[j].effective && self.dual_basis_value(j, tau) > 0.0)
            .collect()
    }

    /// The vertices of the region `P(τ)` reaches when group `j`'s parameters vary over the
    /// simplex (others fixed): `P(τ) + N*_j(τ)(P_i − P*_j)` for each member `i` — a point,
    /// a segment (two members), a triangle (three), … (paper 001, §4, Eq. 14).
    ///
    /// # Errors
    /// [`GeomError::NoSuchGroup`].
    pub fn reachable_region(&self, tau: f64, j: usize) -> Result<Vec<DVec3>, GeomError> {
        let g = self.group(j)?;
        let p = self.eval(tau);
        let w = self.dual_basis_value(j, tau);
        let dual = self.dual.points()[j];
        Ok(g.members
            .iter()
            .map(|&i| p + w * (self.points[i] - dual))
            .collect())
    }

    /// The exact elevation coefficients `c^i_j` as rationals, from the knots' exact values
    /// ([`KnotVector::exact_knots`]). Rows as in [`elevation_coefficients`].
    #[must_use]
    pub fn exact_coefficients(&self) -> Elevation<Rational> {
        elevation_coefficients(&self.knots.exact_knots(), self.order())
    }
}

fn dual_spline(
    points: &[DVec3],
    groups: &[Group],
    refined: &KnotVector,
) -> Result<BSpline, GeomError> {
    let dual: Vec<DVec3> = groups
        .iter()
        .map(|g| {
            g.members
                .iter()
                .zip(&g.values)
                .map(|(&i, &a)| a * points[i])
                .sum()
        })
        .collect();
    BSpline::from_parts(dual, refined.clone()).map_err(|e| match e {
        GeomError::NonFinitePoint { index, value } => GeomError::DerivedNotFinite {
            field: "points",
            what: format!("dual control point P*_{index}"),
            value,
        },
        other => other,
    })
}

impl ParamCurve for Nubmp {
    fn domain(&self) -> (f64, f64) {
        self.knots.domain()
    }
    fn eval(&self, t: f64) -> DVec3 {
        self.dual.eval(t)
    }
    fn eval_deriv(&self, t: f64) -> DVec3 {
        self.dual.eval_deriv(t)
    }
    fn eval_second_deriv(&self, t: f64) -> DVec3 {
        self.dual.eval_second_deriv(t)
    }
}

impl Lower for Nubmp {
    fn lower(&self) -> Vec<BezierSegment> {
        self.dual.bezier_segments()
    }
}

impl BSpline {
    /// The standard NUBMP curve on this spline's points and knots (the same curve).
    ///
    /// # Errors
    /// [`GeomError::DerivedNotFinite`] when its structure overflows `f64`.
    pub fn standard_nubmp(&self) -> Result<Nubmp, GeomError> {
        Nubmp::standard(self.points().to_vec(), self.knots().clone())
    }
}

// The family: what the editor, the reports and the drawing need of every curve family.

impl Family for Nubmp {
    const NAME: &'static str = "nubmp";

    fn inserts_by_knot(&self) -> bool {
        true
    }

    /// Standard curves only: the groups of the new knot vector differ from the old ones.
    fn with_knot_inserted(&self, t: f64) -> Result<Nubmp, GeomError> {
        if !self.is_standard() {
            return Err(GeomError::refused(
                Self::NAME,
                "reset the shape parameters to the standard curve before inserting a knot (the groups of the new knot vector differ)",
            ));
        }
        let b = BSpline::from_parts(self.points().to_vec(), self.knots().clone())?;
        let b = b.insert_knot(t)?;
        Nubmp::standard(b.points().to_vec(), b.knots().clone())
    }

    fn with_point_removed(&self, index: usize) -> Result<Nubmp, GeomError> {
        if !self.is_standard() {
            return Err(GeomError::refused(
                Self::NAME,
                "reset the shape parameters to the standard curve before removing a point (the groups of the new knot vector differ)",
            ));
        }
        let (points, knots) =
            crate::geom::structure::spline_without(self.points(), self.knots(), index, Self::NAME)?;
        Nubmp::try_new(points, knots, self.order())
    }

    /// The standard NUBMP curve of [`BSpline::generated`]'s spline (four segments, which
    /// lower one degree higher).
    fn generated(degree: usize, point: &mut dyn FnMut() -> DVec3) -> Result<Nubmp, GeomError> {
        let b = BSpline::generated(degree, point)?;
        Nubmp::standard(b.points().to_vec(), b.knots().clone())
    }

    fn control_points(&self) -> &[DVec3] {
        &self.points
    }

    fn with_control_points(&self, points: Vec<DVec3>) -> Result<Nubmp, GeomError> {
        self.with_points(points)
    }

    fn derived_field(&self) -> &'static str {
        "knots"
    }

    fn at_tau(&self, tau: f64) -> Result<Option<AtTau>, GeomError> {
        nubmp_at_tau(self, tau).map(Some)
    }
}

/// [`Family::at_tau`] for NUBMP curves (and B-splines, as standard NUBMP curves).
pub(crate) fn nubmp_at_tau(n: &Nubmp, tau: f64) -> Result<AtTau, GeomError> {
    let (start, end) = n.domain();
    if !(tau >= start && tau <= end) {
        return Err(GeomError::ParameterOutsideDomain {
            value: tau,
            start,
            end,
        });
    }
    let groups = n
        .groups_at(tau)
        .into_iter()
        .map(|j| GroupAtTau {
            group: j,
            members: n.groups[j].members.clone(),
            weight: n.dual_basis_value(j, tau),
            region: xyz(&n.reachable_region(tau, j).unwrap_or_default()),
        })
        .collect();
    Ok(AtTau {
        tau,
        point: n.eval(tau).to_array(),
        groups,
    })
}

#[cfg(test)]
mod tests;
mod vd;
