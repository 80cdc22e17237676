//! The questions asked of one curve, answered on its lowered segments ([`Piece`]) and put
//! back in the curve's own parameter.

use glam::DVec3;
use thiserror::Error;

use super::piece::Piece;
use super::poly;
use super::quadrature::{Quadrature, integrate};
use super::roots::{bernstein_roots, bernstein_roots_with_noise};
use crate::geom::{Aabb, Lower};
use crate::num::Num;

/// Why a question cannot be answered.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum AnalysisError {
    /// The accuracy is not a finite number greater than 0.
    #[error("accuracy {}: must be a finite number greater than 0", Num(*.0))]
    Accuracy(f64),
    /// A parameter outside the curve's domain (or not a number).
    #[error("{what} = {}: outside the domain [{}, {}] of the curve", Num(*value), Num(*start), Num(*end))]
    OutsideDomain {
        /// Which argument.
        what: &'static str,
        /// Its value.
        value: f64,
        /// The domain's start.
        start: f64,
        /// The domain's end.
        end: f64,
    },
    /// A question for planar curves asked of a curve with `z ≠ 0`.
    #[error(
        "{what} are defined for planar (2D) curves; this curve leaves the plane z = 0 (a 3D curve has no sign of curvature to change)"
    )]
    NotPlanar {
        /// The question.
        what: &'static str,
    },
    /// An arc length beyond the curve's.
    #[error("arc length {}: outside [0, {}], the curve's length", Num(*s), Num(*length))]
    BeyondLength {
        /// The length asked for.
        s: f64,
        /// The curve's length.
        length: f64,
    },
    /// An arc length the quadrature could not resolve: the speed is not finite somewhere
    /// in the range (weights whose ratio overflows), or the error bound stayed above the
    /// accuracy and the rounding of the value within the work budget.
    #[error(
        "arc length from t = {} to {}: not resolved to the accuracy {} (the estimate {} has an error bound {}; the speed overflows or varies faster than the quadrature can follow)",
        Num(*t0), Num(*t1), Num(*accuracy), Num(*value), Num(*error)
    )]
    Unresolved {
        /// The range's start.
        t0: f64,
        /// The range's end.
        t1: f64,
        /// The accuracy asked for.
        accuracy: f64,
        /// The estimate.
        value: f64,
        /// Its error bound.
        error: f64,
    },
    /// A value beyond the largest double: the curve's coordinates are too large for it.
    #[error(
        "the {what} overflows: the curve's control points span {}, too large for it to be a finite double",
        Num(*size)
    )]
    Overflow {
        /// The quantity.
        what: &'static str,
        /// The diagonal of the control points' box.
        size: f64,
    },
    /// A line given by two equal points.
    #[error("the line's two points are equal ({point}): they give no direction")]
    DegenerateLine {
        /// The point.
        point: DVec3,
    },
}

/// An arc length and the bound on its error kept by the quadrature.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Length {
    /// The length (negative when `t1 < t0`).
    pub value: f64,
    /// A bound on its error (the requested accuracy unless rounding forbade it).
    pub error: f64,
}

/// A parameter where one coordinate's derivative vanishes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremum {
    /// The curve parameter.
    pub t: f64,
    /// The coordinate: 0 (x), 1 (y) or 2 (z).
    pub axis: usize,
    /// The point there.
    pub point: DVec3,
}

/// Whether a curvature extremum is a local maximum or minimum of the signed curvature.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExtremumKind {
    /// A local maximum of `κ`.
    Maximum,
    /// A local minimum of `κ`.
    Minimum,
}

/// A local extremum of the signed curvature (a "vertex").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvatureExtremum {
    /// The curve parameter.
    pub t: f64,
    /// The signed curvature there (2D: positive turning left).
    pub curvature: f64,
    /// Maximum or minimum of the signed curvature.
    pub kind: ExtremumKind,
    /// The point there.
    pub point: DVec3,
}

/// How a curve meets a line or another curve at a point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HitKind {
    /// The curves cross (transversally, or with an odd order of contact).
    Crossing,
    /// The curves touch: tangent there (a double root, or parallel tangents).
    Tangent,
}

/// A curve meeting a line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineHit {
    /// The curve parameter.
    pub t: f64,
    /// The line's parameter: the point is `p + λ (q − p)`.
    pub lambda: f64,
    /// The point.
    pub point: DVec3,
    /// Crossing or tangent.
    pub kind: HitKind,
    /// A bound on the error of `t`.
    pub error: f64,
}

/// Where a curve meets a line.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LineIntersections {
    /// The points, by the curve's parameter.
    pub hits: Vec<LineHit>,
    /// The curve's parameter ranges lying on the line.
    pub overlaps: Vec<(f64, f64)>,
}

/// One curve, lowered, ready to be asked.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveAnalysis {
    pieces: Vec<Piece>,
    domain: (f64, f64),
    planar: bool,
    /// Per piece, the local minima of its speed inside `(0, 1)` with the width `δ` of
    /// the dip (where the arc length's integrand is cut).
    speed_minima: Vec<Vec<(f64, f64)>>,
}

/// Above this ratio of a rational piece's largest weight to its smallest, its length is
/// integrated in the logistic parameter ([`CurveAnalysis::length`]).
const WEIGHT_SPREAD: f64 = 64.0;

/// The relative rounding of an arc length's integrand, per unit of control polygon length:
/// the tolerance no quadrature goes below.
const ROUNDING: f64 = 64.0 * f64::EPSILON;

/// The logistic parameter's range: `e^{−746}` is below the smallest positive double.
const LOGISTIC_END: f64 = 746.0;

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

/// The default accuracy of lengths: absolute, in the curve's units.
pub const DEFAULT_ACCURACY: f64 = 1e-12;

fn check_accuracy(accuracy: f64) -> Result<f64, AnalysisError> {
    if accuracy.is_finite() && accuracy > 0.0 {
        Ok(accuracy)
    } else {
        Err(AnalysisError::Accuracy(accuracy))
    }
}

impl CurveAnalysis {
    /// The analysis of `curve` (its exact Bézier segments).
    #[must_use]
    pub fn new(curve: &impl Lower) -> CurveAnalysis {
        let pieces: Vec<Piece> = curve.lower().iter().map(Piece::new).collect();
        let planar = pieces.iter().all(Piece::is_planar);
        // Pieces with an a-priori bound (planar polynomial ones) need no cuts.
        let speed_minima = pieces
            .iter()
            .map(|p| {
                if p.planar_speed().is_some() {
                    Vec::new()
                } else {
                    p.speed_minima()
                }
            })
            .collect();
        CurveAnalysis {
            pieces,
            domain: curve.domain(),
            planar,
            speed_minima,
        }
    }

    /// The segments.
    #[must_use]
    pub fn pieces(&self) -> &[Piece] {
        &self.pieces
    }

    /// The parameter domain.
    #[must_use]
    pub fn domain(&self) -> (f64, f64) {
        self.domain
    }

    /// Whether every point has `z = 0`.
    #[must_use]
    pub fn is_planar(&self) -> bool {
        self.planar
    }

    /// Refuses a parameter outside the domain (or NaN), naming it.
    ///
    /// # Errors
    /// [`AnalysisError::OutsideDomain`].
    pub fn check_t(&self, what: &'static str, t: f64) -> Result<f64, AnalysisError> {
        let (a, b) = self.domain;
        if t >= a && t <= b {
            Ok(t)
        } else {
            Err(AnalysisError::OutsideDomain {
                what,
                value: t,
                start: a,
                end: b,
            })
        }
    }

    fn require_planar(&self, what: &'static str) -> Result<(), AnalysisError> {
        if self.planar {
            Ok(())
        } else {
            Err(AnalysisError::NotPlanar { what })
        }
    }

    /// The piece holding `t` and the local parameter (a joint belongs to the later piece,
    /// the domain's end to the last).
    fn locate(&self, t: f64) -> (usize, f64) {
        let k = self
            .pieces
            .partition_point(|p| p.t0 <= t)
            .saturating_sub(1)
            .min(self.pieces.len().saturating_sub(1));
        (k, self.pieces[k].u_of(t))
    }

    /// The point at `t`.
    #[must_use]
    pub fn point(&self, t: f64) -> DVec3 {
        if self.pieces.is_empty() {
            return DVec3::ZERO;
        }
        let (k, u) = self.locate(t);
        self.pieces[k].point(u)
    }

    /// The first derivative with respect to the curve parameter at `t`.
    #[must_use]
    pub fn deriv(&self, t: f64) -> DVec3 {
        if self.pieces.is_empty() {
            return DVec3::ZERO;
        }
        let (k, u) = self.locate(t);
        let p = &self.pieces[k];
        p.deriv(u) / (p.t1 - p.t0)
    }

    /// The second derivative with respect to the curve parameter at `t`.
    #[must_use]
    pub fn second_deriv(&self, t: f64) -> DVec3 {
        if self.pieces.is_empty() {
            return DVec3::ZERO;
        }
        let (k, u) = self.locate(t);
        let p = &self.pieces[k];
        let h = p.t1 - p.t0;
        p.second_deriv(u) / (h * h)
    }

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
        self.logistic_range_length(k, logit(u0), logit(u1), tolerance)
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
            while step < 2.0 * LOGISTIC_END {
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
        // Rounding alone can leave an error of about 50 ε per unit of length (the
        // quadrature's floor), or ROUNDING per unit of the control polygon's length (the
        // speed's rounding); more than twice that, or none at all, is a failure.
        let polygon: f64 = self.pieces.iter().map(Piece::polygon_length).sum();
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

    /// The parameter `t` at which the arc length from the domain's start is `s`, within
    /// `accuracy` of `s` — or of the length's rounding (`100 ε` times the length, `128 ε`
    /// times the control polygon's), where that is larger (Newton's method on the length, kept inside a bracket).
    ///
    /// # Errors
    /// [`AnalysisError`] for an accuracy that is not a positive number, or `s` outside
    /// `[0, length]`.
    pub fn parameter_at_length(&self, s: f64, accuracy: f64) -> Result<f64, AnalysisError> {
        check_accuracy(accuracy)?;
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

    /// The parameters strictly inside the domain where one coordinate's derivative
    /// vanishes (for a rational segment, the numerator of the quotient rule), by axis
    /// then parameter; 2 axes for a planar curve, 3 otherwise.
    #[must_use]
    pub fn extrema(&self) -> Vec<Extremum> {
        let dims = if self.planar { 2 } else { 3 };
        let (a, b) = self.domain;
        let mut out: Vec<Extremum> = Vec::new();
        for axis in 0..dims {
            let mut ts: Vec<f64> = Vec::new();
            for p in &self.pieces {
                let roots = bernstein_roots(&p.deriv_numerator(axis));
                for r in roots.roots {
                    let t = p.t_of(r.t);
                    if t > a && t < b {
                        ts.push(t);
                    }
                }
            }
            ts.sort_by(f64::total_cmp);
            ts.dedup_by(|x, y| (*x - *y).abs() <= 4.0 * f64::EPSILON * x.abs().max(1.0));
            out.extend(ts.into_iter().map(|t| Extremum {
                t,
                axis,
                point: self.point(t),
            }));
        }
        out
    }

    /// The tight axis-aligned box of the curve: its end points, the segments' joints and
    /// the points where a coordinate's derivative vanishes (not the control points' box).
    #[must_use]
    pub fn bounding_box(&self) -> Aabb {
        let mut bbox = Aabb::EMPTY;
        for p in &self.pieces {
            bbox = bbox.including(p.point(0.0)).including(p.point(1.0));
        }
        for e in self.extrema() {
            bbox = bbox.including(e.point);
        }
        bbox
    }

    /// Whether the curve ends where it starts (within `1e−12` of its size).
    #[must_use]
    pub fn is_closed(&self) -> bool {
        let (a, b) = self.domain;
        let (p, q) = (self.point(a), self.point(b));
        let size = self.control_box().diagonal().max(f64::MIN_POSITIVE);
        (p - q).length() <= 1e-12 * size
    }

    /// The box of every segment's control points (holds the curve).
    #[must_use]
    pub fn control_box(&self) -> Aabb {
        let mut bbox = Aabb::EMPTY;
        for p in &self.pieces {
            for i in 0..p.a[0].len() {
                let w = p.w.as_ref().map_or(1.0, |w| w[i]);
                bbox = bbox.including(DVec3::new(p.a[0][i], p.a[1][i], p.a[2][i]) / w);
            }
        }
        bbox
    }

    /// The signed area enclosed by the curve and, if it is open, the straight chord from
    /// its end back to its start: `½ ∮ (x dy − y dx)`, positive counter-clockwise. Exact
    /// but for rounding on polynomial segments (Green's theorem on the Bernstein form:
    /// `∫₀¹ (x y′ − y x′) du` is the mean of the product's coefficients); rational segments
    /// by quadrature to `1e−15` of the curve's size squared.
    ///
    /// # Errors
    /// [`AnalysisError::NotPlanar`] for a 3D curve; [`AnalysisError::Overflow`] where the
    /// area is beyond the largest double (coordinates near `10¹⁵⁴` and above).
    pub fn signed_area(&self) -> Result<f64, AnalysisError> {
        self.require_planar("signed areas")?;
        let size = self.control_box().diagonal();
        let mut twice = 0.0;
        for p in &self.pieces {
            match p.area_integrand() {
                Some(c) => twice += poly::integral(&c),
                None => {
                    let q = integrate(
                        |u| {
                            let c = p.point(u);
                            let d = p.deriv(u);
                            c.x * d.y - c.y * d.x
                        },
                        0.0,
                        1.0,
                        1e-15 * size * size,
                    );
                    twice += q.value;
                }
            }
        }
        let (a, b) = self.domain;
        let (start, end) = (self.point(a), self.point(b));
        twice += end.x * start.y - end.y * start.x;
        let area = 0.5 * twice;
        if area.is_finite() {
            Ok(area)
        } else {
            Err(AnalysisError::Overflow {
                what: "signed area",
                size,
            })
        }
    }

    /// The parameters where the velocity vanishes (`C′ = 0`): cusps and stationary points,
    /// strictly inside the domain.
    ///
    /// # Errors
    /// [`AnalysisError::NotPlanar`] for a 3D curve.
    pub fn cusps(&self) -> Result<Vec<f64>, AnalysisError> {
        self.require_planar("cusps")?;
        Ok(self.cusp_parameters())
    }

    fn cusp_parameters(&self) -> Vec<f64> {
        let (a, b) = self.domain;
        let mut out: Vec<f64> = Vec::new();
        for p in &self.pieces {
            let roots = bernstein_roots(&p.speed_squared_numerator(2));
            for r in roots.roots {
                let t = p.t_of(r.t);
                if t > a && t < b {
                    out.push(t);
                }
            }
        }
        out.sort_by(f64::total_cmp);
        out.dedup_by(|x, y| (*x - *y).abs() <= 1e-12 * (b - a));
        out
    }

    /// The inflections: parameters where `C′ × C″` changes sign (an odd-order root inside a
    /// segment, or a sign that differs across a joint), cusps excluded.
    ///
    /// # Errors
    /// [`AnalysisError::NotPlanar`] for a 3D curve.
    pub fn inflections(&self) -> Result<Vec<f64>, AnalysisError> {
        self.require_planar("inflections")?;
        let (a, b) = self.domain;
        let cusps = self.cusp_parameters();
        let near_cusp = |t: f64| cusps.iter().any(|c| (c - t).abs() <= 1e-9 * (b - a));
        let mut out: Vec<f64> = Vec::new();
        // The sign just inside each end of each segment's cross product.
        let mut ends: Vec<(f64, f64)> = Vec::with_capacity(self.pieces.len());
        for p in &self.pieces {
            let (c, noise) = p.cross_numerator();
            // Coefficients within the rounding have no sign (a straight stretch).
            let c: Vec<f64> = c
                .into_iter()
                .map(|v| if v.abs() <= noise { 0.0 } else { v })
                .collect();
            let sign = |v: Option<&f64>| v.map_or(0.0, |v| v.signum());
            ends.push((
                sign(c.iter().find(|v| **v != 0.0)),
                sign(c.iter().rev().find(|v| **v != 0.0)),
            ));
            for r in bernstein_roots_with_noise(&c, noise).roots {
                if r.multiplicity % 2 == 1 && r.t > 0.0 && r.t < 1.0 {
                    let t = p.t_of(r.t);
                    if t > a && t < b && !near_cusp(t) {
                        out.push(t);
                    }
                }
            }
        }
        for k in 1..self.pieces.len() {
            let (left, right) = (ends[k - 1].1, ends[k].0);
            let t = self.pieces[k].t0;
            if left != 0.0 && right != 0.0 && left != right && t > a && t < b && !near_cusp(t) {
                out.push(t);
            }
        }
        out.sort_by(f64::total_cmp);
        out.dedup_by(|x, y| (*x - *y).abs() <= 1e-12 * (b - a));
        Ok(out)
    }

    /// The signed curvature at `t` (2D): `(C′ × C″) / |C′|³`; `None` where `C′ = 0`.
    #[must_use]
    pub fn signed_curvature(&self, t: f64) -> Option<f64> {
        let (d1, d2) = (self.deriv(t), self.second_deriv(t));
        let k = crate::geom::curvature(d1, d2)?;
        Some(if d1.x * d2.y - d1.y * d2.x < 0.0 {
            -k
        } else {
            k
        })
    }

    /// The local extrema of the signed curvature inside each segment (the stationary
    /// points of `κ`, where `2F′G − 3FG′ = 0` with `κ = F/G^{3/2}`), cusps excluded, with
    /// `κ` and whether it is a maximum or a minimum there. A segment of constant
    /// curvature (a circular arc, a line) has none.
    ///
    /// # Errors
    /// [`AnalysisError::NotPlanar`] for a 3D curve.
    pub fn curvature_extrema(&self) -> Result<Vec<CurvatureExtremum>, AnalysisError> {
        self.require_planar("curvature extrema")?;
        let (a, b) = self.domain;
        let cusps = self.cusp_parameters();
        let mut out = Vec::new();
        // The slope's sign just inside each end of each segment (0: none there).
        let mut ends: Vec<(f64, f64)> = Vec::with_capacity(self.pieces.len());
        for p in &self.pieces {
            let (slope, noise) = p.curvature_slope_numerator();
            // Coefficients within the rounding are no sign at all (a circular arc).
            let slope: Vec<f64> = slope
                .into_iter()
                .map(|v| if v.abs() <= noise { 0.0 } else { v })
                .collect();
            let sign = |v: Option<&f64>| v.map_or(0.0, |v| v.signum());
            ends.push((
                sign(slope.iter().find(|v| **v != 0.0)),
                sign(slope.iter().rev().find(|v| **v != 0.0)),
            ));
            let roots = bernstein_roots_with_noise(&slope, noise);
            if roots.identically_zero {
                continue;
            }
            let rs: Vec<f64> = roots
                .roots
                .iter()
                .filter(|r| r.multiplicity % 2 == 1 && r.t > 0.0 && r.t < 1.0)
                .map(|r| r.t)
                .collect();
            for (i, &u) in rs.iter().enumerate() {
                let t = p.t_of(u);
                if !(t > a && t < b) || cusps.iter().any(|c| (c - t).abs() <= 1e-9 * (b - a)) {
                    continue;
                }
                // Which way κ goes: the sign of the slope numerator (G > 0) on each side,
                // a step short of the neighbouring roots.
                let left_room = if i == 0 { u } else { u - rs[i - 1] };
                let right_room = if i + 1 == rs.len() {
                    1.0 - u
                } else {
                    rs[i + 1] - u
                };
                let h = (0.25 * left_room.min(right_room)).min(1e-3);
                let before = poly::eval(&slope, u - h);
                let after = poly::eval(&slope, u + h);
                let kind = match (before > 0.0, after > 0.0) {
                    (true, false) => ExtremumKind::Maximum,
                    (false, true) => ExtremumKind::Minimum,
                    _ => continue,
                };
                let Some(curvature) = self.signed_curvature(t) else {
                    continue;
                };
                out.push(CurvatureExtremum {
                    t,
                    curvature,
                    kind,
                    point: self.point(t),
                });
            }
        }
        // A joint where the slope changes sign and κ is continuous (a joint where κ
        // jumps, as at the knots of a C¹ spline, is not a stationary point).
        for k in 1..self.pieces.len() {
            let t = self.pieces[k].t0;
            let (left, right) = (ends[k - 1].1, ends[k].0);
            let kind = match (left, right) {
                (l, r) if l > 0.0 && r < 0.0 => ExtremumKind::Maximum,
                (l, r) if l < 0.0 && r > 0.0 => ExtremumKind::Minimum,
                _ => continue,
            };
            if !(t > a && t < b) || cusps.iter().any(|c| (c - t).abs() <= 1e-9 * (b - a)) {
                continue;
            }
            let (prev, next) = (&self.pieces[k - 1], &self.pieces[k]);
            let side = |p: &Piece, u: f64| {
                let h = p.t1 - p.t0;
                let (d1, d2) = (p.deriv(u) / h, p.second_deriv(u) / (h * h));
                crate::geom::curvature(d1, d2).map(|k| {
                    if d1.x * d2.y - d1.y * d2.x < 0.0 {
                        -k
                    } else {
                        k
                    }
                })
            };
            let (Some(kl), Some(kr)) = (side(prev, 1.0), side(next, 0.0)) else {
                continue;
            };
            if (kl - kr).abs() > 1e-9 * kl.abs().max(kr.abs()) {
                continue;
            }
            out.push(CurvatureExtremum {
                t,
                curvature: kr,
                kind,
                point: self.point(t),
            });
        }
        out.sort_by(|x, y| x.t.total_cmp(&y.t));
        Ok(out)
    }

    /// Where the curve meets the line through `p` and `q` (2D): each segment's signed
    /// distance `(A − pW) × (q − p)` in Bernstein form, its roots; a double root is a
    /// tangency. Segments lying on the line are reported as overlaps (their parameter
    /// ranges, joined).
    ///
    /// # Errors
    /// [`AnalysisError`] for a 3D curve or `p = q`.
    pub fn intersect_line(&self, p: DVec3, q: DVec3) -> Result<LineIntersections, AnalysisError> {
        self.require_planar("intersections")?;
        let d = q - p;
        if d.x == 0.0 && d.y == 0.0 {
            return Err(AnalysisError::DegenerateLine { point: p });
        }
        let mut hits: Vec<LineHit> = Vec::new();
        let mut overlaps: Vec<(f64, f64)> = Vec::new();
        for piece in &self.pieces {
            let n = piece.a[0].len();
            let c: Vec<f64> = (0..n)
                .map(|i| {
                    let w = piece.w.as_ref().map_or(1.0, |w| w[i]);
                    let x = piece.a[0][i] - p.x * w;
                    let y = piece.a[1][i] - p.y * w;
                    x * d.y - y * d.x
                })
                .collect();
            let roots = bernstein_roots(&c);
            if roots.identically_zero {
                match overlaps.last_mut() {
                    Some(last) if last.1 == piece.t0 => last.1 = piece.t1,
                    _ => overlaps.push((piece.t0, piece.t1)),
                }
                continue;
            }
            for r in roots.roots {
                let t = piece.t_of(r.t);
                let point = piece.point(r.t);
                hits.push(LineHit {
                    t,
                    lambda: (point - p).dot(d) / d.length_squared(),
                    point,
                    kind: if r.multiplicity % 2 == 0 {
                        HitKind::Tangent
                    } else {
                        HitKind::Crossing
                    },
                    error: r.error * (piece.t1 - piece.t0),
                });
            }
        }
        hits.sort_by(|x, y| x.t.total_cmp(&y.t));
        // A hit at a joint is found by both segments.
        hits.dedup_by(|x, y| (x.t - y.t).abs() <= x.error + y.error + 4.0 * f64::EPSILON);
        hits.retain(|h| !overlaps.iter().any(|(s, e)| h.t >= *s && h.t <= *e));
        Ok(LineIntersections { hits, overlaps })
    }
}
