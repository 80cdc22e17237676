//! Arc length and its inverse: per segment, the planar polynomial path with its proven
//! bound ([`crate::analysis::gauss`]), adaptive Gauss–Kronrod with cuts at the speed's
//! minima for the others, and the logistic parameter for rational segments whose weights
//! are far apart.

use super::{AnalysisError, CurveAnalysis, Length, check_accuracy, check_in};
use crate::analysis::piece::{Piece, planar_polynomial_speed};
use crate::analysis::quadrature::{Quadrature, integrate};
use crate::geom::Bezier;

/// Above this ratio of a rational piece's largest weight to its smallest, its length is
/// integrated in the logistic parameter ([`CurveAnalysis::length`]).
const WEIGHT_SPREAD: f64 = 64.0;

/// The relative rounding of an arc length's integrand, per unit of control polygon length:
/// the tolerance no quadrature goes below.
const ROUNDING: f64 = 64.0 * f64::EPSILON;

/// The logistic parameter's range for a parameter `u` in `(0, 1)`: `e^{−746}` is below the
/// smallest positive double.
const LOGISTIC_END: f64 = 746.0;

/// How far past a segment's outermost weight transition its length is integrated in the
/// logistic parameter: the rest is within `e^{−40}` of its control polygon.
const TAIL: f64 = 40.0;

/// `σ = ln(u / (1 − u))`, kept within `±LOGISTIC_END`.
fn logit(u: f64) -> f64 {
    if u <= 0.0 {
        -LOGISTIC_END
    } else if u >= 1.0 {
        LOGISTIC_END
    } else {
        (u / (1.0 - u)).ln().clamp(-LOGISTIC_END, LOGISTIC_END)
    }
}

/// `u = 1 / (1 + e^{−σ})`, the inverse of [`logit`].
fn logistic_u(sigma: f64) -> f64 {
    1.0 / (1.0 + (-sigma).exp())
}

impl CurveAnalysis {
    /// The arc length of piece `k` between its own parameters `u0 ≤ u1`. The range is cut
    /// at the speed's local minima, and around a sharp one (a near-cusp, where `|C′|` dips
    /// to `m` and is analytic only within `δ` of the minimum) into intervals growing
    /// geometrically from `δ`: a Gauss rule whose nodes all miss a dip narrower than its
    /// interval would agree with its Kronrod extension on a wrong value.
    fn piece_length(&self, k: usize, u0: f64, u1: f64, tolerance: f64) -> Quadrature {
        let p = &self.pieces[k];
        // Below the rounding of the speed (a few ε times the control polygon's length) no
        // halving helps: aim no lower.
        let tolerance = tolerance.max(ROUNDING * p.polygon_length());
        if let Some(speed) = p.planar_speed() {
            return speed.length(u0, u1, tolerance);
        }
        if p.weight_spread() > WEIGHT_SPREAD {
            return self.logistic_length(k, u0, u1, tolerance);
        }
        let mut cuts: Vec<f64> = Vec::new();
        for &(m, delta) in &self.speed_minima[k] {
            cuts.push(m);
            // A wide dip is smooth enough for the adaptive rule alone.
            let mut step = delta.max(1e-15);
            while step < 0.05 {
                cuts.push(m - step);
                cuts.push(m + step);
                step *= 4.0;
            }
        }
        cuts.retain(|c| *c > u0 && *c < u1);
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let parts = cuts.len() + 1;
        let mut total = Quadrature::default();
        let mut lo = u0;
        for hi in cuts.into_iter().chain(std::iter::once(u1)) {
            let q = integrate(|u| p.speed(u), lo, hi, tolerance / parts as f64);
            total.value += q.value;
            total.error += q.error;
            total.evaluations += q.evaluations;
            lo = hi;
        }
        total
    }

    /// The arc length of a rational piece whose weights are far apart, in the logistic
    /// parameter `σ` (`u = 1/(1 + e^{−σ})`): there the curve changes on a scale of 1 around
    /// each `σ` where two weight terms trade dominance, however far apart the weights —
    /// in `u` such a change can be `10⁻³⁰⁰` wide, where no quadrature node would land.
    /// The range is cut at those `σ` and at the speed's minima, with cuts growing
    /// geometrically (1, 4, 16, …) around each, so every feature sits at the end of short
    /// intervals.
    fn logistic_length(&self, k: usize, u0: f64, u1: f64, tolerance: f64) -> Quadrature {
        // An end of the segment is σ = ∓∞: stop `TAIL` past the farthest transition, where
        // every weight term but the end's is below `e^{−TAIL}` of it, and count the rest of
        // the way (within that fraction of the control polygon, each of `n` terms) in the
        // error.
        let p = &self.pieces[k];
        let transitions = p.weight_transitions();
        let lowest = transitions.iter().copied().fold(0.0_f64, f64::min);
        let highest = transitions.iter().copied().fold(0.0_f64, f64::max);
        let tail = (-TAIL).exp() * p.degree().max(1) as f64 * p.polygon_length();
        let (s0, mut extra) = if u0 <= 0.0 {
            (lowest - TAIL, tail)
        } else {
            (logit(u0), 0.0)
        };
        let s1 = if u1 >= 1.0 {
            extra += tail;
            highest + TAIL
        } else {
            logit(u1)
        };
        let mut q = self.logistic_range_length(k, s0, s1, tolerance);
        q.error += extra;
        q
    }

    /// [`CurveAnalysis::logistic_length`] between two logistic parameters.
    fn logistic_range_length(&self, k: usize, s0: f64, s1: f64, tolerance: f64) -> Quadrature {
        let p = &self.pieces[k];
        let mut centres = p.weight_transitions();
        centres.extend(self.speed_minima[k].iter().map(|&(m, _)| logit(m)));
        let mut cuts = Vec::new();
        for c in centres {
            cuts.push(c);
            let mut step = 1.0;
            while step < (s1 - s0).abs() {
                cuts.push(c - step);
                cuts.push(c + step);
                step *= 4.0;
            }
        }
        cuts.retain(|c| *c > s0 && *c < s1);
        cuts.sort_by(f64::total_cmp);
        cuts.dedup_by(|a, b| (*a - *b).abs() < 0.25);
        let parts = cuts.len() + 1;
        let mut total = Quadrature::default();
        let mut lo = s0;
        for hi in cuts.into_iter().chain(std::iter::once(s1)) {
            let q = integrate(|s| p.speed_logistic(s), lo, hi, tolerance / parts as f64);
            total.value += q.value;
            total.error += q.error;
            total.evaluations += q.evaluations;
            lo = hi;
        }
        total
    }

    /// The arc length from `t0` to `t1` (negative when `t1 < t0`), within `accuracy`
    /// (absolute): per segment an adaptive Gauss–Kronrod quadrature of `|C′|` whose error
    /// bound is kept ([`Length::error`]; rounding can make it larger than asked for, up to
    /// `100 ε` times the length or `128 ε` times the control polygon's length, on a curve
    /// near `1/ε` times the accuracy in size). Rational segments whose weights are more
    /// than 64 apart are integrated in the logistic parameter `ln(u / (1 − u))`, cut where
    /// their weight terms trade dominance, so that changes `10⁻³⁰⁰` wide in `u` are found.
    ///
    /// # Errors
    /// [`AnalysisError`] for an accuracy that is not a positive number or a parameter
    /// outside the domain; [`AnalysisError::Unresolved`] where the speed overflows or the
    /// bound stays above both the accuracy and the rounding within the work budget.
    pub fn length(&self, t0: f64, t1: f64, accuracy: f64) -> Result<Length, AnalysisError> {
        check_accuracy(accuracy)?;
        self.check_t("t0", t0)?;
        self.check_t("t1", t1)?;
        // Coordinates near the ends of the double range: measured at a scale of 1 (by a
        // power of two, exactly), then scaled back.
        if let Some((e, scaled)) = self.rescaled() {
            let back = |x: f64| crate::num::scale_by_power_of_two(x, -e);
            let accuracy_there = crate::num::scale_by_power_of_two(accuracy, e);
            if !(accuracy_there.is_finite() && accuracy_there > 0.0) {
                return Err(AnalysisError::Accuracy(accuracy));
            }
            return scaled
                .length(t0, t1, accuracy_there)
                .map(|l| Length {
                    value: back(l.value),
                    error: back(l.error),
                })
                .map_err(|err| match err {
                    AnalysisError::Unresolved { value, error, .. } => AnalysisError::Unresolved {
                        t0,
                        t1,
                        accuracy,
                        value: back(value),
                        error: back(error),
                    },
                    other => other,
                });
        }
        let (lo, hi, sign) = if t0 <= t1 {
            (t0, t1, 1.0)
        } else {
            (t1, t0, -1.0)
        };
        let share = accuracy / self.pieces.len().max(1) as f64;
        let mut total = Quadrature::default();
        for (k, p) in self.pieces.iter().enumerate() {
            if p.t1 <= lo || p.t0 >= hi {
                continue;
            }
            let u0 = if lo > p.t0 { p.u_of(lo) } else { 0.0 };
            let u1 = if hi < p.t1 { p.u_of(hi) } else { 1.0 };
            let q = self.piece_length(k, u0, u1, share);
            total.value += q.value;
            total.error += q.error;
        }
        let polygon: f64 = self.pieces.iter().map(Piece::polygon_length).sum();
        finish_length(total, polygon, (t0, t1, sign), accuracy)
    }

    /// The parameter `t` at which the arc length from the domain's start is `s`, within
    /// `accuracy` of `s` — or of the length's rounding (`100 ε` times the length, `128 ε`
    /// times the control polygon's), where that is larger (Newton's method on the length, kept inside a bracket).
    ///
    /// # Errors
    /// [`AnalysisError`] for an accuracy that is not a positive number, or `s` outside
    /// `[0, length]`.
    pub fn parameter_at_length(&self, s: f64, accuracy: f64) -> Result<f64, AnalysisError> {
        check_accuracy(accuracy)?;
        if let Some((e, scaled)) = self.rescaled() {
            let there = |x: f64| crate::num::scale_by_power_of_two(x, e);
            let (s_there, accuracy_there) = (there(s), there(accuracy));
            if !(accuracy_there.is_finite() && accuracy_there > 0.0) {
                return Err(AnalysisError::Accuracy(accuracy));
            }
            return scaled
                .parameter_at_length(s_there, accuracy_there)
                .map_err(|err| match err {
                    AnalysisError::BeyondLength { length, .. } => AnalysisError::BeyondLength {
                        s,
                        length: crate::num::scale_by_power_of_two(length, -e),
                    },
                    other => other,
                });
        }
        let n = self.pieces.len().max(1) as f64;
        let pieces: Vec<Quadrature> = (0..self.pieces.len())
            .map(|k| self.piece_length(k, 0.0, 1.0, 0.25 * accuracy / n))
            .collect();
        let lengths: Vec<f64> = pieces.iter().map(|q| q.value).collect();
        let total: f64 = lengths.iter().sum();
        let error: f64 = pieces.iter().map(|q| q.error).sum();
        if !(total.is_finite() && error.is_finite()) {
            let (t0, t1) = self.domain;
            return Err(AnalysisError::Unresolved {
                t0,
                t1,
                accuracy,
                value: total,
                error,
            });
        }
        // Below the rounding of the length (about 50 ε per unit) no parameter can do
        // better: aim at what the quadrature can resolve.
        let polygon: f64 = self.pieces.iter().map(Piece::polygon_length).sum();
        let accuracy = accuracy
            .max(100.0 * f64::EPSILON * total)
            .max(2.0 * ROUNDING * polygon);
        if !(s >= 0.0 && s <= total + accuracy) {
            return Err(AnalysisError::BeyondLength { s, length: total });
        }
        let (a, b) = self.domain;
        if s == 0.0 {
            return Ok(a);
        }
        let mut before = 0.0;
        for (k, &len) in lengths.iter().enumerate() {
            if before + len < s && k + 1 < lengths.len() {
                before += len;
                continue;
            }
            let p = &self.pieces[k];
            let target = (s - before).min(len);
            if target >= len {
                return Ok(p.t1.min(b));
            }
            // Newton's method kept inside a bracket, in `u` — or in the logistic parameter
            // for a piece whose length is integrated in it, where its features are wide.
            let logistic = p.weight_spread() > WEIGHT_SPREAD;
            let (mut lo, mut hi) = if logistic {
                (-LOGISTIC_END, LOGISTIC_END)
            } else {
                (0.0_f64, 1.0_f64)
            };
            let length_to = |x: f64| {
                if logistic {
                    self.logistic_range_length(k, -LOGISTIC_END, x, 0.25 * accuracy)
                } else {
                    self.piece_length(k, 0.0, x, 0.25 * accuracy)
                }
                .value
            };
            let speed_at = |x: f64| {
                if logistic {
                    p.speed_logistic(x)
                } else {
                    p.deriv(x).length()
                }
            };
            let mut x = if logistic {
                0.0
            } else if len > 0.0 {
                target / len
            } else {
                0.0
            };
            for _ in 0..200 {
                let f = length_to(x) - target;
                if f.abs() <= 0.5 * accuracy {
                    break;
                }
                if f < 0.0 {
                    lo = x;
                } else {
                    hi = x;
                }
                let speed = speed_at(x);
                let newton = x - f / speed;
                let mid = 0.5 * (lo + hi);
                x = if speed > 0.0 && newton > lo && newton < hi {
                    newton
                } else {
                    mid
                };
                if hi - lo <= f64::EPSILON * hi.abs().max(lo.abs()).max(1.0) {
                    break;
                }
            }
            let u = if logistic { logistic_u(x) } else { x };
            return Ok(p.t_of(u));
        }
        Ok(b)
    }
}

/// The length `total` (of curves whose control polygons are `polygon` long) as
/// [`CurveAnalysis::length`] returns it: signed, or [`AnalysisError::Unresolved`] where it
/// is not finite or its bound is above both the accuracy and the rounding's floor.
fn finish_length(
    total: Quadrature,
    polygon: f64,
    (t0, t1, sign): (f64, f64, f64),
    accuracy: f64,
) -> Result<Length, AnalysisError> {
    // Rounding alone can leave an error of about 50 ε per unit of length (the
    // quadrature's floor), or ROUNDING per unit of the control polygon's length (the
    // speed's rounding); more than twice that, or none at all, is a failure.
    let floor = (100.0 * f64::EPSILON * total.value.abs()).max(2.0 * ROUNDING * polygon);
    if !(total.value.is_finite() && total.error <= accuracy.max(floor)) {
        return Err(AnalysisError::Unresolved {
            t0,
            t1,
            accuracy,
            value: total.value,
            error: total.error,
        });
    }
    Ok(Length {
        value: sign * total.value,
        error: total.error,
    })
}

/// The arc length of a Bézier curve from `t0` to `t1` (negative when `t1 < t0`), within
/// `accuracy`: the value and bound `CurveAnalysis::new(curve).length(t0, t1, accuracy)`
/// gives, to the bit, without building the analysis — for a planar curve of degree ≤ 7
/// only the hodograph (in the power basis) and its roots, on the stack, then the same
/// Gauss–Legendre plan ([`crate::analysis::gauss`]); any other curve through the
/// analysis. For a length asked once (a curve's analysis, kept, answers later questions
/// faster).
///
/// # Errors
/// As [`CurveAnalysis::length`]: an accuracy that is not a positive number, a parameter
/// outside `[0, 1]`, or [`AnalysisError::Unresolved`].
pub fn bezier_length(
    curve: &Bezier,
    t0: f64,
    t1: f64,
    accuracy: f64,
) -> Result<Length, AnalysisError> {
    let Some((speed, polygon)) = planar_polynomial_speed(curve.points()) else {
        return CurveAnalysis::new(curve).length(t0, t1, accuracy);
    };
    check_accuracy(accuracy)?;
    let domain = (0.0, 1.0);
    check_in(domain, "t0", t0)?;
    check_in(domain, "t1", t1)?;
    let (lo, hi, sign) = if t0 <= t1 {
        (t0, t1, 1.0)
    } else {
        (t1, t0, -1.0)
    };
    // One piece over the whole domain: `u = t` ([`CurveAnalysis::length`]'s loop and
    // `piece_length`, for that piece).
    let mut total = Quadrature::default();
    if hi > 0.0 && lo < 1.0 {
        let tolerance = accuracy.max(ROUNDING * polygon);
        let u0 = if lo > 0.0 { lo } else { 0.0 };
        let u1 = if hi < 1.0 { hi } else { 1.0 };
        let q = speed.length(u0, u1, tolerance);
        total.value += q.value;
        total.error += q.error;
    }
    finish_length(total, polygon, (t0, t1, sign), accuracy)
}
