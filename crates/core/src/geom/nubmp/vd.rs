//! Paper 001 §4's variation-diminishing conditions for order 4 (Theorem 1): a group's
//! value, each parameter's permissible range with an absorbing member, and the bands a
//! slider shows.

use super::{Nubmp, PermissibleRange};
use crate::geom::GeomError;

impl Nubmp {
    /// For order 4 and a group of three members `(m, m+1, m+2)`, the left side of paper
    /// 001's Theorem 1: `a^m_j / a^m_{j−1} + a^{m+2}_j / a^{m+2}_{j+1}` (the VD property is
    /// guaranteed when every such value is ≤ 1). `None` for other groups or orders.
    #[must_use]
    pub fn vd_value(&self, j: usize) -> Option<f64> {
        let [a, b, c, d] = self.vd_terms(j, &|g, i| self.groups[g].value(i))?;
        Some(ratio(a, b) + ratio(c, d))
    }

    /// The four parameters of group `j`'s Theorem 1 condition `A/B + C/D ≤ 1`:
    /// `[a^m_j, a^m_{j−1}, a^{m+2}_j, a^{m+2}_{j+1}]`, read through `value`.
    fn vd_terms(&self, j: usize, value: &dyn Fn(usize, usize) -> Option<f64>) -> Option<[f64; 4]> {
        if self.order() != 4 {
            return None;
        }
        let g = self.groups.get(j)?;
        if g.members.len() != 3 || j == 0 || j + 1 >= self.groups.len() {
            return None;
        }
        let m = g.members[0];
        Some([
            value(j, m)?,
            value(j - 1, m)?,
            value(j, m + 2)?,
            value(j + 1, m + 2)?,
        ])
    }

    /// For order 4, the interval of values of `a^i_j` (with member `absorber` of the same
    /// group taking the difference, every other parameter fixed) on which every affected
    /// Theorem 1 condition holds and both parameters stay ≥ 0: the connected interval
    /// containing the current value. `None` when the order is not 4 or the current value
    /// itself violates a condition.
    ///
    /// Each condition `A/B + C/D ≤ 1` has `A, B, C, D` affine in the parameter `s`; with
    /// `B, D > 0` it is the quadratic inequality `A D + C B − B D ≤ 0`, so the interval's
    /// ends are roots of such quadratics (or zeros of a denominator, or 0 and the pair's
    /// sum): they are computed in closed form and the pieces between them tested.
    ///
    /// # Errors
    /// [`GeomError`] when a member is not in the group or the two are the same.
    pub fn permissible_range(
        &self,
        j: usize,
        i: usize,
        absorber: usize,
    ) -> Result<Option<PermissibleRange>, GeomError> {
        let current = self.groups.get(j).and_then(|g| g.value(i)).unwrap_or(0.0);
        let Some(scan) = self.vd_scan(j, i, absorber, Some(current))? else {
            return Ok(None);
        };
        let at = scan.cuts.iter().position(|&c| c == current).unwrap_or(0);
        if !scan.point_ok[at] {
            return Ok(None);
        }
        let mut lo = at;
        while lo > 0 && scan.gap_ok[lo - 1] && scan.point_ok[lo - 1] {
            lo -= 1;
        }
        let mut hi = at;
        while hi + 1 < scan.cuts.len() && scan.gap_ok[hi] && scan.point_ok[hi + 1] {
            hi += 1;
        }
        Ok(Some(PermissibleRange {
            min: scan.cuts[lo],
            max: scan.cuts[hi],
        }))
    }

    /// Every interval of values of `a^i_j` (with `a^absorber_j` absorbing the change, as
    /// in [`Nubmp::permissible_range`]) that keeps the conditions of 001's Theorem 1,
    /// whatever the parameter's current value: the bands a slider shows. Empty for
    /// orders other than 4.
    ///
    /// # Errors
    /// [`GeomError`] when a member is not in the group or the two are the same.
    pub fn vd_bands(
        &self,
        j: usize,
        i: usize,
        absorber: usize,
    ) -> Result<Vec<PermissibleRange>, GeomError> {
        let Some(scan) = self.vd_scan(j, i, absorber, None)? else {
            return Ok(Vec::new());
        };
        let mut out: Vec<PermissibleRange> = Vec::new();
        let mut run: Option<usize> = None;
        for k in 0..scan.cuts.len() {
            if !scan.point_ok[k] {
                run = None;
                continue;
            }
            let start = *run.get_or_insert(k);
            let continues = k + 1 < scan.cuts.len() && scan.gap_ok[k] && scan.point_ok[k + 1];
            if !continues {
                out.push(PermissibleRange {
                    min: scan.cuts[start],
                    max: scan.cuts[k],
                });
                run = None;
            }
        }
        Ok(out)
    }

    /// The points where a Theorem 1 condition involving `a^i_j` can change truth (plus
    /// `extra`), sorted in `[0, a^i_j + a^absorber_j]`, and whether the conditions hold at
    /// each point and in each gap between neighbours. `None` for orders other than 4.
    fn vd_scan(
        &self,
        j: usize,
        i: usize,
        absorber: usize,
        extra: Option<f64>,
    ) -> Result<Option<VdScan>, GeomError> {
        let pi = self.member_position(j, i)?;
        let pa = self.member_position(j, absorber)?;
        if pi == pa {
            return Err(GeomError::SameAbsorber { member: i });
        }
        if self.order() != 4 {
            return Ok(None);
        }
        let g = &self.groups[j];
        let pair = g.values[pi] + g.values[pa];
        let value_at = |s: f64| {
            move |grp: usize, mem: usize| -> Option<f64> {
                if grp == j && mem == i {
                    Some(s)
                } else if grp == j && mem == absorber {
                    Some(pair - s)
                } else {
                    self.groups[grp].value(mem)
                }
            }
        };
        let terms_at = |h: usize, s: f64| self.vd_terms(h, &value_at(s));
        // The conditions whose terms change with s: condition h reads groups h − 1, h and
        // h + 1 only, so only conditions j − 1 ..= j + 1 can.
        let near = j.saturating_sub(1)..=(j + 1).min(self.groups.len() - 1);
        let involved: Vec<usize> = near
            .filter(|&h| match (terms_at(h, 0.0), terms_at(h, pair)) {
                (Some(x), Some(y)) => x != y,
                _ => false,
            })
            .collect();
        let holds = |s: f64| {
            involved.iter().all(|&h| {
                terms_at(h, s).is_some_and(|[a, b, c, d]| ratio(a, b) + ratio(c, d) <= 1.0 + 1e-12)
            })
        };
        let mut cuts = vec![0.0, pair];
        for &h in &involved {
            let q = |s: f64| {
                let [a, b, c, d] = terms_at(h, s).unwrap_or([0.0; 4]);
                a * d + c * b - b * d
            };
            // Exact quadratic through three samples.
            let (q0, qm, q1) = (q(0.0), q(0.5 * pair), q(pair));
            let qa = 2.0 * (q1 - 2.0 * qm + q0) / (pair * pair);
            let qb = (q1 - q0) / pair - qa * pair;
            cuts.extend(quadratic_roots(qa, qb, q0));
            // Zeros of the denominators B and D (affine in s).
            for idx in [1, 3] {
                let (b0, b1) = (
                    terms_at(h, 0.0).map_or(0.0, |t| t[idx]),
                    terms_at(h, pair).map_or(0.0, |t| t[idx]),
                );
                if b1 != b0 {
                    cuts.push(-b0 * pair / (b1 - b0));
                }
            }
        }
        cuts.retain(|&c| (0.0..=pair).contains(&c));
        cuts.extend(extra);
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let point_ok = cuts.iter().map(|&c| holds(c)).collect();
        let gap_ok = cuts
            .windows(2)
            .map(|w| holds(0.5 * (w[0] + w[1])))
            .collect();
        Ok(Some(VdScan {
            cuts,
            point_ok,
            gap_ok,
        }))
    }
}

/// The pieces of one parameter's range between the points where a Theorem 1 condition
/// can change truth ([`Nubmp::vd_scan`]).
struct VdScan {
    cuts: Vec<f64>,
    point_ok: Vec<bool>,
    gap_ok: Vec<bool>,
}

/// `num / den` with `0/0 = 0` and `x/0 = ∞` (a zero parameter over a zero parameter adds
/// nothing to a Theorem 1 sum; a positive one over zero violates it).
fn ratio(num: f64, den: f64) -> f64 {
    if num == 0.0 {
        0.0
    } else if den == 0.0 {
        f64::INFINITY
    } else {
        num / den
    }
}

/// The real roots of `a s² + b s + c` (the linear or constant case when `a` vanishes),
/// by the cancellation-free formula.
fn quadratic_roots(a: f64, b: f64, c: f64) -> Vec<f64> {
    let scale = a.abs().max(b.abs()).max(c.abs());
    if scale == 0.0 {
        return Vec::new();
    }
    if a.abs() <= 1e-14 * scale {
        return if b == 0.0 { Vec::new() } else { vec![-c / b] };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return Vec::new();
    }
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q == 0.0 {
        return vec![0.0];
    }
    vec![q / a, c / q]
}
